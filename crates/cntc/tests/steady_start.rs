//! Transient steps started from steady rolling in module 1: a case of
//! steady rolling (T = 3), then transient steps (T = 1 or 2) with P = 0,
//! which start from the steady state's tractions as CONTACT's do (its
//! testbank/examples_trans t3_t1_force, t3_t2_force on worn profiles).
//! Rolled on as before, the tractions stay the steady state's.
//!
//! The case: the Manchester benchmark's right wheel at y = 3 mm
//! ([`MBENCH_RIGHT_INP`], FZ 10 kN, 2 m/s) with the yaw reduced to 0.5
//! mrad, so that the patch adheres over 37 % of its area. Reference
//! values: CONTACT's library (contact-kit build of CONTACT revision 2707,
//! eve70a/CONTACT) called with this input and these calls through its
//! python_intfc (`cntc_readinpfile`, `cntc_calculate`; then per step
//! `cntc_setflags` T and P = 0, `cntc_setwheelsetposition`,
//! `cntc_setwheelsetvelocity`, `cntc_calculate`), printed to the digits
//! below.

mod common;

use common::{
    close, patch_totals, read_inp, set_flags, wheelrail_element, InpDir, MBENCH_RIGHT_INP,
};
use contact_addon::ffi::*;
use contact_addon::flags;

/// A step's patch: FN, FX, FS \[N\], the contact area and the area of
/// adhesion \[mm2\].
type Step = (f64, f64, f64, f64, f64);

/// The steady case, then `want.len() - 1` transient steps of the T digit
/// `tang`, each S += 0.2 mm (one element) at the same position; with T =
/// 2 the velocities of the steady case, with T = 1 the step's shift and
/// rotation (VS 0.2 mm, VPITCH the steady pitch rate over the step's 0.1
/// ms). With `fx_ws`, the steady case finds VPITCH for that FX_WS \[N\]
/// (F = 1, `cntc_settangentialforces(ire, -1, FX_WS, 0)`), and the steps
/// (F = 0) take the VPITCH it found (`cntc_getwheelsetvelocity`). Checks every step against `want`: FN within 0.1 %, FX and FS
/// within 1 % of their size (the steady state's FS lies 0.66 % from
/// CONTACT's), the areas within 2 % of the contact area; and that each
/// transient step's FX and FS stay within 1.5 % of the steady state's
/// (CONTACT's move by 0.9 % and 0.7 %; started from rest, the first
/// step's are a twentieth of them).
fn from_steady(ire: i32, tang: i32, fx_ws: Option<f64>, want: &[Step]) {
    let yaw = 0.0005;
    let inp = MBENCH_RIGHT_INP.replace(
        "  0.0  3.0  10000. -0.00018030 0.0072  0.0",
        &format!("  0.0  3.0  10000. -0.00018030 {yaw}  0.0"),
    );
    assert_ne!(inp, MBENCH_RIGHT_INP, "the yaw replaced");
    let dir = InpDir::new(&format!("steady-start-{ire}"));
    let path = dir.write("case.inp", &inp);
    let mut vpitch = -4.34515030;
    let mut steady = None;
    for (k, want) in want.iter().enumerate() {
        let ours = unsafe {
            if k == 0 {
                wheelrail_element(ire, &[]);
                assert_eq!(read_inp(ire, flags::INP_MODUL1, &path), 0);
                if let Some(fx) = fx_ws {
                    set_flags(ire, -1, &[(flags::IC_FORCE, 1)]);
                    cntc_settangentialforces(&ire, &-1, &fx, &0.0);
                }
            } else {
                let digits = [
                    (flags::IC_TANG, tang),
                    (flags::IC_PVTIME, 0),
                    (flags::IC_FORCE, 0),
                ];
                set_flags(ire, -1, &digits);
                let pos = [0.2 * k as f64, 3.0, 10000.0, -0.00018030, yaw, 0.0];
                cntc_setwheelsetposition(&ire, &1, &6, pos.as_ptr());
                let (vs, vpitch) = match tang {
                    2 => (2000.0, vpitch),
                    _ => (0.2, vpitch * 0.2 / 2000.0),
                };
                let vel = [vs, 0.0, 0.0, 0.0, 0.0, vpitch];
                cntc_setwheelsetvelocity(&ire, &1, &6, vel.as_ptr());
            }
            let mut ierror = -1;
            cntc_calculate1(&ire, &mut ierror);
            assert_eq!(ierror, 0, "T = {tang} step {k}");
            if k == 0 && fx_ws.is_some() {
                let mut vel = [0.0; 6];
                cntc_getwheelsetvelocity(&ire, &6, vel.as_mut_ptr());
                vpitch = vel[5];
            }
            let mut n = 0;
            cntc_getnumcontactpatches(&ire, &mut n);
            assert_eq!(n, 1, "T = {tang} step {k}");
            patch_totals(ire, 1)
        };
        let [fn_, fx, fs, _] = ours.forces;
        println!(
            "T = {tang} step {k}: FN {fn_} FX {fx} FS {fs} areas {:?}",
            ours.areas
        );
        let what = |field: &str| format!("T = {tang} step {k} {field}");
        close(&what("FN"), fn_, want.0, 1e-3 * want.0);
        close(&what("FX"), fx, want.1, 0.01 * want.1.abs());
        close(&what("FS"), fs, want.2, 0.01 * want.2.abs());
        close(&what("area"), ours.areas[0], want.3, 0.02 * want.3);
        close(&what("adhesion"), ours.areas[1], want.4, 0.02 * want.3);
        match steady {
            None => steady = Some((fx, fs)),
            Some((sx, ss)) => {
                close(&what("FX from steady"), fx, sx, 0.015 * sx.abs());
                close(&what("FS from steady"), fs, ss, 0.015 * ss.abs());
            }
        }
    }
}

/// T = 3, then four steps of transient rolling (T = 2, one element a
/// step).
#[test]
fn transient_rolling_starts_from_the_steady_state() {
    let want = [
        (9902.04, -2040.38, -1518.49, 21.160, 7.800),
        (9902.96, -2021.87, -1508.55, 21.320, 8.000),
        (9902.99, -2022.81, -1508.28, 21.320, 8.000),
        (9903.0, -2023.69, -1508.18, 21.320, 7.960),
        (9903.0, -2024.54, -1508.18, 21.320, 7.960),
    ];
    from_steady(131, 2, None, &want);
}

/// T = 3, then four transient shifts (T = 1) of one element each.
#[test]
fn transient_shifts_start_from_the_steady_state() {
    let want = [
        (9902.04, -2040.38, -1518.49, 21.160, 7.800),
        (9903.02, -2021.99, -1507.99, 21.320, 8.000),
        (9903.09, -2023.06, -1507.2, 21.320, 8.000),
        (9903.14, -2024.06, -1506.6, 21.320, 7.960),
        (9903.19, -2025.01, -1506.13, 21.320, 7.960),
    ];
    from_steady(132, 1, None, &want);
}

/// T = 3 with FX_WS = -1000 N prescribed (F = 1, VPITCH found: CONTACT's
/// -4.3423886073 rad/s, ours -4.3423847080), then four steps of transient
/// rolling (T = 2, F = 0) at that VPITCH: they start from the steady
/// state's tractions as after F = 0. Reference: CONTACT's library as in
/// the module docs, with `cntc_setflags` F = 1 and
/// `cntc_settangentialforces(ire, -1, -1000, 0)` after the input file
/// (2026-12-07); from rest the first step's FX was -44 N.
#[test]
fn transient_rolling_starts_from_the_steady_state_of_a_prescribed_force() {
    let want = [
        (9877.47, -999.569, -1783.46, 21.160, 12.440),
        (9878.71, -989.369, -1769.84, 21.320, 12.560),
        (9878.74, -989.844, -1769.52, 21.320, 12.560),
        (9878.76, -990.256, -1769.31, 21.320, 12.560),
        (9878.77, -990.642, -1769.19, 21.320, 12.560),
    ];
    from_steady(133, 2, Some(-1000.0), &want);
}
