//! The massless rail (F = 3, `cntc_settrackdimensions` with Z = 32, 33)
//! called as a C caller calls it, against CONTACT's library on the
//! Manchester benchmark (python_mbench.py's set-up, CONTACT's planar
//! approach D = 2): the left wheel in tread contact and the right wheel in
//! flange contact, the vertical force prescribed (N = 1) and the wheelset's
//! height (N = 0, the height CONTACT's library found with N = 1, which
//! gives the same balance). Reference values: CONTACT's library
//! (/tmp/cntc-ref/bin/contact_addon_linux64.so, CONTACT revision 2707) in
//! `crates/cntc/bench/massless_rail.py`, cases `mb-*`. Each test uses its
//! own result element.
//!
//! CONTACT's test bank cases 36 and 37 (testbank.inp, the massless rail on
//! the worn wheel of its case 33) keep case 35's conformal approach
//! (D = 4), which module 1 refuses; the same script reproduces their
//! testbank.ref_out values with CONTACT's library and D = 4 (see
//! docs/cntc.md, "Massless rail").

mod common;

use common::{close, mbench_wheel, read_inp, InpDir, MBENCH_RIGHT_INP};
use contact_addon::ffi::*;
use contact_addon::flags::{self, err};

/// python_mbench.py's set-up of wheel `iwhe` with F = 3 and the N digit
/// `norm`.
unsafe fn mbench(ire: i32, iwhe: i32, norm: i32) {
    mbench_wheel(ire, iwhe, norm, 3);
}

/// The massless rail `rail` (KYRAIL, FYRAIL, KZRAIL, FZRAIL, DYSTEP0), the
/// position `pos` at 2 m/s with pitch rate `vpitch`: ierror.
unsafe fn solve(ire: i32, rail: [f64; 5], pos: [f64; 6], vpitch: f64) -> i32 {
    cntc_settrackdimensions(&ire, &32, &5, rail.as_ptr());
    cntc_setwheelsetposition(&ire, &2, &6, pos.as_ptr());
    let vel = [2000.0, 0.0, 0.0, 0.0, 0.0, vpitch];
    cntc_setwheelsetvelocity(&ire, &2, &6, vel.as_ptr());
    let mut ierror = -1;
    cntc_calculate1(&ire, &mut ierror);
    ierror
}

/// What CONTACT's library reports for a case: DY_DEFL, DZ_DEFL \[mm\],
/// FX, FY, FZ on the rail (track) \[N\], Z_WS, YCP_TR, ZCP_TR, YCP_R,
/// ZCP_R \[mm\], DELTCP_TR \[rad\].
struct Reference {
    defl: [f64; 2],
    force: [f64; 3],
    z_ws: f64,
    location: [f64; 4],
    angle: f64,
}

/// Checks element `ire` (one patch) against `r`: the deflections and the
/// total forces within 1 % (of the lateral force for FX, FY: the
/// deflection follows FY), the wheelset's height within 1 % of its
/// deflection, the contact location within 0.1 mm and 1 mrad.
unsafe fn check(ire: i32, r: &Reference) {
    let mut npatch = 0;
    cntc_getnumcontactpatches(&ire, &mut npatch);
    assert_eq!(npatch, 1);
    let mut loc = [0.0; 38];
    cntc_getcontactlocation(&ire, &1, &38, loc.as_mut_ptr());
    close("DY_DEFL", loc[17], r.defl[0], 0.01 * r.defl[0].abs());
    close("DZ_DEFL", loc[18], r.defl[1], 0.01 * r.defl[1].abs());
    let mut g = [0.0; 24];
    cntc_getglobalforces(&ire, &-1, &24, g.as_mut_ptr());
    let fy = r.force[1].abs();
    close("FX_TR", g[0], r.force[0], 0.01 * fy);
    close("FY_TR", g[1], r.force[1], 0.01 * fy);
    close("FZ_TR", g[2], r.force[2], 0.01 * r.force[2]);
    let mut ws = [0.0; 6];
    cntc_getwheelsetposition(&ire, &6, ws.as_mut_ptr());
    close("Z_WS", ws[2], r.z_ws, 0.01 * r.defl[1].abs());
    close("YCP_TR", loc[1], r.location[0], 0.1);
    close("ZCP_TR", loc[2], r.location[1], 0.1);
    close("YCP_R", loc[5], r.location[2], 0.1);
    close("ZCP_R", loc[6], r.location[3], 0.1);
    close("DELTCP_TR", loc[3], r.angle, 1e-3);
}

/// Prints what the library found (for the report of the agreement).
unsafe fn report(ire: i32, norm: i32) {
    let mut loc = [0.0; 38];
    cntc_getcontactlocation(&ire, &1, &38, loc.as_mut_ptr());
    let mut g = [0.0; 24];
    cntc_getglobalforces(&ire, &-1, &24, g.as_mut_ptr());
    eprintln!(
        "ire {ire} N = {norm}: DY_DEFL {:.6} DZ_DEFL {:.6} FX {:.2} FY {:.2} FZ {:.2} YCP_TR \
         {:.5} ZCP_TR {:.5} DELT {:.6} YCP_R {:.5} ZCP_R {:.5}",
        loc[17], loc[18], g[0], g[1], g[2], loc[1], loc[2], loc[3], loc[5], loc[6]
    );
}

/// massless_rail.py `mb-left-tread` (N = 1) and `mb-left-tread-n0`
/// (N = 0 at CONTACT's Z_WS): KYRAIL 5000 N/mm, KZRAIL 20000 N/mm, no
/// forces on the rail.
#[test]
fn left_wheel_tread_on_a_massless_rail() {
    let n1 = Reference {
        defl: [-0.615198, 0.5],
        force: [563.208, -3075.99, 10000.0],
        z_ws: 0.660849,
        location: [-757.57829, 0.52131, 3.56947, 0.02131],
        angle: 0.011919,
    };
    // CONTACT's iteration moves the wheelset's height given (N = 0) by
    // -0.04 um here; this library keeps it.
    let n0 = Reference {
        defl: [-0.615148, 0.499960],
        force: [563.161, -3075.74, 9999.2],
        z_ws: 0.660808,
        location: [-757.57821, 0.52127, 3.56949, 0.02131],
        angle: 0.011919,
    };
    let rail = [5000.0, 0.0, 20000.0, 0.0, 0.5];
    let pos = [0.0, 2.0, 0.660849266, -0.0001128, 0.0048, 0.0];
    for (ire, norm, reference) in [(41, 1, n1), (42, 0, n0)] {
        unsafe {
            mbench(ire, 1, norm);
            assert_eq!(solve(ire, rail, pos, -4.3459197), 0, "N = {norm}");
            check(ire, &reference);
            report(ire, norm);
            // N = 1: DZ_DEFL = (FZ + FZRAIL) / KZRAIL exactly.
            if norm == 1 {
                let mut loc = [0.0; 19];
                cntc_getcontactlocation(&ire, &1, &19, loc.as_mut_ptr());
                assert_eq!(loc[18], 0.5);
            }
            cntc_finalize(&ire);
        }
    }
}

/// massless_rail.py `mb-right-flange` and `mb-right-flange-n0`: the right
/// wheel in flange contact (contact angle -1.02 rad), KYRAIL = KZRAIL =
/// 20000 N/mm, FYRAIL = -2 kN, FZRAIL = -5 kN.
#[test]
fn right_wheel_flange_on_a_massless_rail() {
    let n1 = Reference {
        defl: [0.383038, 0.25],
        force: [-2008.44, 9660.84, 10000.0],
        z_ws: -4.665783,
        location: [719.69977, 9.03629, -41.21583, 8.78629],
        angle: -1.021861,
    };
    // CONTACT's iteration moves Z_WS by 0.33 um.
    let n0 = Reference {
        defl: [0.383162, 0.250118],
        force: [-2008.89, 9663.23, 10002.4],
        z_ws: -4.665450,
        location: [719.69985, 9.03648, -41.21587, 8.78636],
        angle: -1.021868,
    };
    let rail = [20000.0, -2000.0, 20000.0, -5000.0, 0.5];
    let pos = [0.0, 7.5, -4.665782605, -0.007642, 0.018, 0.0];
    for (ire, norm, reference) in [(43, 1, n1), (44, 0, n0)] {
        unsafe {
            mbench(ire, 2, norm);
            assert_eq!(solve(ire, rail, pos, -4.2575747), 0, "N = {norm}");
            check(ire, &reference);
            report(ire, norm);
            cntc_finalize(&ire);
        }
    }
}

/// F = 3 without the rail's parameters, a vertical stiffness of 0 with the
/// height prescribed, and a parameter count outside 4-5 are refused by
/// name; with F = 0 afterwards the deflections are zero again.
#[test]
fn massless_rail_inputs_are_checked() {
    let ire = 45;
    unsafe {
        mbench(ire, 1, 0);
        let pos = [0.0, 2.0, 0.660849266, -0.0001128, 0.0048, 0.0];
        cntc_setwheelsetposition(&ire, &2, &6, pos.as_ptr());
        let vel = [2000.0, 0.0, 0.0, 0.0, 0.0, -4.3459197];
        cntc_setwheelsetvelocity(&ire, &2, &6, vel.as_ptr());
        let mut ierror = 0;
        cntc_calculate1(&ire, &mut ierror);
        assert_eq!(ierror, err::OTHER, "F = 3 without Z = 32");
        assert_eq!(
            solve(ire, [5000.0, 0.0, 0.0, 0.0, 0.5], pos, -4.3459197),
            err::OTHER,
            "KZRAIL = 0 with N = 0"
        );
        let mut loc = [0.0; 19];
        assert_eq!(
            solve(ire, [5000.0, 0.0, 20000.0, 0.0, 0.5], pos, -4.3459197),
            0
        );
        cntc_getcontactlocation(&ire, &1, &19, loc.as_mut_ptr());
        assert!(loc[17] < -0.5, "DY_DEFL {}", loc[17]);
        let codes = [flags::IC_FORCE];
        cntc_setflags(&ire, &-1, &1, codes.as_ptr(), [0].as_ptr());
        cntc_calculate1(&ire, &mut ierror);
        assert_eq!(ierror, 0);
        cntc_getcontactlocation(&ire, &1, &19, loc.as_mut_ptr());
        assert_eq!([loc[17], loc[18]], [0.0, 0.0]);
        cntc_finalize(&ire);
    }
}

/// An input file with F = 3 (the benchmark's right wheel at y = 3 mm, its
/// rail deflection line after the rail deviations) reads into
/// `cntc_settrackdimensions` with Z = 32: the deflections found meet the
/// balance DY_DEFL = (FY_TR + FYRAIL) / KYRAIL to 1e-4 of FZ (the final
/// solve on the deflected rail against the iteration's) and DZ_DEFL =
/// (FZ + FZRAIL) / KZRAIL (N = 1) exactly.
#[test]
fn an_input_file_sets_the_massless_rail() {
    let ire = 46;
    let text = MBENCH_RIGHT_INP
        .replacen(" 1203100 ", " 1203130 ", 1)
        .replacen(
        "DY, DZ, ROLL, VY, VZ, VROLL\n",
        "DY, DZ, ROLL, VY, VZ, VROLL\n  8000. 500. 15000. -2000. 0.5   KYRAIL, FYRAIL, KZRAIL, \
             FZRAIL, DYSTEP0\n",
        1,
    );
    assert!(text.contains("KYRAIL") && text.contains(" 1203130 "));
    let dir = InpDir::new("massless");
    let inp = dir.write("massless.inp", &text);
    assert_eq!(read_inp(ire, flags::INP_MODUL1, &inp), 0);
    unsafe {
        let mut ierror = -1;
        cntc_calculate1(&ire, &mut ierror);
        assert_eq!(ierror, 0);
        let mut loc = [0.0; 19];
        cntc_getcontactlocation(&ire, &1, &19, loc.as_mut_ptr());
        let mut g = [0.0; 3];
        cntc_getglobalforces(&ire, &-1, &3, g.as_mut_ptr());
        close(
            "DY_DEFL",
            loc[17],
            (g[1] + 500.0) / 8000.0,
            1e-4 * 1e4 / 8000.0,
        );
        assert_eq!(loc[18], (10000.0 - 2000.0) / 15000.0);
        assert!(loc[17].abs() > 0.1, "DY_DEFL {}", loc[17]);
        cntc_finalize(&ire);
    }
}
