//! Module 1 (wheel/rail contact) called as a C caller calls it, with the
//! Manchester benchmark set up as CONTACT's `python_mbench.py` sets it up,
//! against the values CONTACT's own library returned there. Each test
//! uses its own result element (the library is one per process).

mod common;

use std::ptr::null;

use common::{close, mbench_wheel};
use contact_addon::ffi::*;
use contact_addon::flags;

/// Configures result element `ire` as `python_mbench.py` does for its
/// wheel `iwhe` ([`mbench_wheel`] with N = 1, F = 0), the wheelset not
/// flexible.
unsafe fn mbench(ire: i32, iwhe: i32) {
    mbench_wheel(ire, iwhe, 1, 0);
    let flex = [0.0; 12];
    cntc_setwheelsetflexibility(&ire, &1, &12, flex.as_ptr());
}

/// Sets the wheelset position `pos` (E = 2: s, y, z, roll, yaw, pitch)
/// and the velocity of 2 m/s with pitch rate `vpitch`, solves, and checks
/// that one patch is found without an error.
unsafe fn solve_one_patch(ire: i32, pos: [f64; 6], vpitch: f64) {
    cntc_setwheelsetposition(&ire, &2, &6, pos.as_ptr());
    let vel = [2000.0, 0.0, 0.0, 0.0, 0.0, vpitch];
    cntc_setwheelsetvelocity(&ire, &2, &6, vel.as_ptr());
    let mut ierror = -1;
    cntc_calculate1(&ire, &mut ierror);
    assert_eq!(ierror, 0);
    let mut npatch = 0;
    cntc_getnumcontactpatches(&ire, &mut npatch);
    assert_eq!(npatch, 1);
}

/// CONTACT's library, python_mbench.py case 5 of wheel 1 (the left wheel:
/// y = 2 mm, yaw 4.8 mrad, tread contact).
#[test]
fn left_wheel_of_python_mbench_through_the_c_calls() {
    let ire = 31;
    unsafe {
        mbench(ire, 1);
        solve_one_patch(ire, [0.0, 2.0, 0.0, -0.0001128, 0.0048, 0.0], -4.3459197);

        let icp = 1;
        let (mut fn_, mut fx, mut fs, mut mz) = (0.0, 0.0, 0.0, 0.0);
        cntc_getcontactforces(&ire, &icp, &mut fn_, &mut fx, &mut fs, &mut mz);
        close("FN", fn_, 10040.715121559264, 10.0);
        close("FX", fx, 546.2665948836895, 10.0);
        close("FS", fs, -2961.0836757778825, 10.0);
        let (mut cksi, mut ceta, mut cphi) = (0.0, 0.0, 0.0);
        cntc_getcreepages(&ire, &icp, &mut cksi, &mut ceta, &mut cphi);
        close("CKSI", cksi, -0.0008651007927205669, 1e-5);
        close("CETA", ceta, 0.004798401609212832, 1e-5);
        let mut pen = 0.0;
        cntc_getpenetration(&ire, &icp, &mut pen);
        close("PEN", pen, 0.020543975556290815, 2e-4);
        let mut veloc = 0.0;
        cntc_getreferencevelocity(&ire, &icp, &mut veloc);
        close("VELOC", veloc, 1999.13527324518, 0.05);

        let mut g = [0.0; 24];
        cntc_getglobalforces(&ire, &-1, &24, g.as_mut_ptr());
        close("FX_TR", g[0], 546.2665948836895, 10.0);
        close("FY_TR", g[1], -3095.7975364776526, 10.0);
        close("FZ_TR", g[2], 10000.000715020276, 1.0);
        close("MX_R_TR", g[3], 40032.761166105505, 200.0);
        close("MZ_R_TR", g[5], -13235.98784802425, 200.0);

        let mut loc = [0.0; 38];
        cntc_getcontactlocation(&ire, &icp, &38, loc.as_mut_ptr());
        close("YCP_TR", loc[1], -756.5055572557221, 0.3);
        close("YW_TR", loc[21], -747.9394672453138, 1e-3);
        close("YR_TR", loc[25], -760.5325577483475, 1e-3);
        close("ZW_WS", loc[35], 460.0, 1e-9);

        let mut ws = [0.0; 6];
        cntc_getwheelsetposition(&ire, &6, ws.as_mut_ptr());
        close("Y_WS", ws[1], 2.0, 1e-12);
        cntc_finalize(&ire);
    }
}

/// CONTACT's library, python_mbench.py case 16 of wheel 2 (the right
/// wheel on the MiniProf rail: y = 7.5 mm, yaw 18 mrad, roll -7.642 mrad,
/// flange contact at a contact angle of -1.0 rad in CONTACT's frame).
#[test]
fn right_wheel_flange_on_the_miniprof_rail() {
    let ire = 33;
    unsafe {
        mbench(ire, 2);
        solve_one_patch(ire, [0.0, 7.5, 0.0, -0.007642, 0.018, 0.0], -4.2575747);
        let icp = 1;
        let (mut fn_, mut fx, mut fs, mut mz) = (0.0, 0.0, 0.0, 0.0);
        cntc_getcontactforces(&ire, &icp, &mut fn_, &mut fx, &mut fs, &mut mz);
        // Within 1 % of CONTACT's FN and of mu FN for the creep forces.
        close("FN", fn_, 13263.228133151724, 133.0);
        close("FX", fx, -2085.8570270052205, 40.0);
        close("FS", fs, -3374.633186994974, 40.0);
        let mut g = [0.0; 24];
        cntc_getglobalforces(&ire, &-1, &24, g.as_mut_ptr());
        close("FX_TR", g[0], -2085.8570270052205, 40.0);
        close("FY_TR", g[1], 9343.542301339861, 100.0);
        close("FZ_TR", g[2], 9999.979346072065, 1.0);
        let mut loc = [0.0; 38];
        cntc_getcontactlocation(&ire, &icp, &38, loc.as_mut_ptr());
        close("DELTCP_TR", loc[3], -1.0006240948464022, 0.01);
        cntc_finalize(&ire);
    }
}

/// CONTACT's blended patch: python_mbench.py case 11 of wheel 2 (the right
/// wheel on the MiniProf rail: y = 5 mm, yaw 12 mrad, roll -0.3554 mrad),
/// where the tread and the flange root touch in two regions between
/// D_COMB = 4 mm and D_SEP = 8 mm apart. CONTACT keeps them one patch
/// whose regions press on each other reduced, and leaves the elements
/// between them out of contact. Merged into one region instead, the
/// approach was 2.9 %, FX 4.6 % and MZ 14 % from CONTACT's. Reference:
/// CONTACT's library in python_mbench.py (CONTACT revision 2707, the
/// cases of wheel 2 run in order in one result element; its
/// `cntc_getpenetration`, `cntc_getcontactforces`,
/// `cntc_getmaximumpressure`, `cntc_getcontactpatchareas`,
/// `cntc_getcreepages`). Tolerances: 1 % of the approach, the maximum
/// pressure, the area and CKSI (measured 0.28 %, 0.36 %, 0.26 %, 0.14 %),
/// 0.1 % of FN for FN, FX and FS (0.01 %), 3 % of MZ (1.7 %: the pressure
/// centres differ by micrometres, as on the flange, see docs/cntc.md).
#[test]
fn the_blended_patch_at_5_mm_is_contacts() {
    let ire = 36;
    unsafe {
        mbench(ire, 2);
        solve_one_patch(ire, [0.0, 5.0, 0.0, -0.0003554, 0.012, 0.0], -4.3353637);
        let icp = 1;
        let fn_ref = 9618.76645577443;
        let (mut fn_, mut fx, mut fs, mut mz) = (0.0, 0.0, 0.0, 0.0);
        cntc_getcontactforces(&ire, &icp, &mut fn_, &mut fx, &mut fs, &mut mz);
        close("FN", fn_, fn_ref, 1e-3 * fn_ref);
        close("FX", fx, -763.2905284645734, 1e-3 * fn_ref);
        close("FS", fs, -2738.01334626845, 1e-3 * fn_ref);
        close("MZ", mz, -826.5856870996711, 0.03 * 826.6);
        let mut pen = 0.0;
        cntc_getpenetration(&ire, &icp, &mut pen);
        close("PEN", pen, 0.027189608732256534, 0.01 * 0.02719);
        let mut pmax = 0.0;
        cntc_getmaximumpressure(&ire, &icp, &mut pmax);
        close("PMAX", pmax, 1556.2589693280984, 0.01 * 1556.3);
        let (mut carea, mut harea, mut sarea) = (0.0, 0.0, 0.0);
        cntc_getcontactpatchareas(&ire, &icp, &mut carea, &mut harea, &mut sarea);
        close("CAREA", carea, 15.56, 0.01 * 15.56);
        let mut c = [0.0; 3];
        cntc_getcreepages(&ire, &icp, &mut c[0], &mut c[1], &mut c[2]);
        close("CKSI", c[0], 0.004173902446739483, 0.01 * 0.004174);
        cntc_finalize(&ire);
    }
}

/// The patch's contact reference point, contact angle, creepages and spin
/// moment (about that point) against CONTACT's library: module 1 places
/// the point where CONTACT does, at the weighted centre of the
/// interpenetration with its mean contact angle, and takes the creepages
/// as CONTACT does. python_mbench.py case 1 of wheel 1 (the centred
/// wheelset: a nearly flat gap, whose smallest-gap point lies 1.38 mm
/// from CONTACT's reference) and case 3 of wheel 2 (y = 1 mm, yaw 2.4
/// mrad, on the MiniProf rail: 0.30 mm). The values are those CONTACT's
/// library returned in python_mbench.py (CONTACT revision 2707, its
/// `cntc_getcontactlocation`, `cntc_getcreepages`,
/// `cntc_getcontactforces`). Tolerances: 1 % on the scales the comparison
/// of the two libraries uses, 0.01 mm of a location, 0.1 mrad of an
/// angle, 1 % of a creepage (at least of 1e-4, of 1e-5 /mm for the spin)
/// and of 0.3 FN mm of the spin moment.
#[test]
fn the_reference_point_is_contacts() {
    #[allow(clippy::type_complexity)]
    let cases: [(i32, i32, [f64; 6], f64, [f64; 4], [f64; 3], [f64; 2]); 2] = [
        (
            34,
            1,
            [0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
            -4.3481181,
            // XCP_TR, YCP_TR, ZCP_TR, DELTCP_TR
            [
                0.0,
                -751.8725957636389,
                0.12518971129603756,
                0.02899119814871976,
            ],
            // CKSI, CETA, CPHI
            [-5.665316728041849e-05, 0.0, -6.302153306720445e-05],
            // FN, MZ
            [9996.844167070056, 4605.070749329929],
        ),
        (
            35,
            2,
            [0.0, 1.0, 0.0, -5.049e-05, 0.0024, 0.0],
            -4.3465752,
            [
                -1.7013335287921558,
                741.9907813579974,
                0.5753421618929782,
                -0.06959780394225558,
            ],
            [
                0.0006942547763011791,
                0.0024066580550941726,
                0.00015097164011809602,
            ],
            [9826.836124602472, -227.91440401376107],
        ),
    ];
    for (ire, iwhe, pos, vpitch, location, creepages, [fn_ref, mz_ref]) in cases {
        unsafe {
            mbench(ire, iwhe);
            solve_one_patch(ire, pos, vpitch);
            let icp = 1;
            let mut loc = [0.0; 38];
            cntc_getcontactlocation(&ire, &icp, &38, loc.as_mut_ptr());
            for (k, name) in ["XCP_TR", "YCP_TR", "ZCP_TR"].iter().enumerate() {
                close(name, loc[k], location[k], 0.01);
            }
            close("DELTCP_TR", loc[3], location[3], 1e-4);
            let mut c = [0.0; 3];
            cntc_getcreepages(&ire, &icp, &mut c[0], &mut c[1], &mut c[2]);
            for (k, (name, floor)) in [("CKSI", 1e-4), ("CETA", 1e-4), ("CPHI", 1e-5)]
                .into_iter()
                .enumerate()
            {
                close(
                    name,
                    c[k],
                    creepages[k],
                    0.01 * creepages[k].abs().max(floor),
                );
            }
            let (mut fn_, mut fx, mut fs, mut mz) = (0.0, 0.0, 0.0, 0.0);
            cntc_getcontactforces(&ire, &icp, &mut fn_, &mut fx, &mut fs, &mut mz);
            close("FN", fn_, fn_ref, 0.01 * fn_ref);
            close("MZ", mz, mz_ref, 0.01 * 0.3 * fn_ref);
            cntc_finalize(&ire);
        }
    }
}

/// A missing profile is CONTACT's profile error (-32).
#[test]
fn missing_profile_is_a_profile_error() {
    let ire = 32;
    unsafe {
        let (mut ifcver, mut ierror) = (0, 0);
        cntc_initialize(&ire, &1, &mut ifcver, &mut ierror, null(), null());
        let pot = [0.2, 0.2, 1.5, 8.0, 4.0];
        cntc_setpotcontact(&ire, &-1, &-1, &5, pot.as_ptr());
        cntc_calculate1(&ire, &mut ierror);
        assert_eq!(ierror, flags::err::PROFIL);
        cntc_finalize(&ire);
    }
}

/// CONTACT's library values of one wheel/rail case: the global forces
/// FX_TR, FY_TR, FZ_TR and the patch's FN, FX, FS, contact area [mm²],
/// adhesion area [mm²], maximum pressure [N/mm²].
struct Reference {
    ire: i32,
    iwhe: i32,
    pos: [f64; 6],
    vpitch: f64,
    global: [f64; 3],
    patch: [f64; 6],
}

/// python_mbench.py case 5 of wheel 1 (the left wheel, tread) and case 16
/// of wheel 2 (the right wheel, flange) on elements `ire` and `ire + 1`
/// with CONTACT's values `values` (global, patch).
fn tread_and_flange(ire: i32, values: &[([f64; 3], [f64; 6]); 2]) -> [Reference; 2] {
    let [(g1, p1), (g2, p2)] = *values;
    [
        Reference {
            ire,
            iwhe: 1,
            pos: [0.0, 2.0, 0.0, -0.0001128, 0.0048, 0.0],
            vpitch: -4.3459197,
            global: g1,
            patch: p1,
        },
        Reference {
            ire: ire + 1,
            iwhe: 2,
            pos: [0.0, 7.5, 0.0, -0.007642, 0.018, 0.0],
            vpitch: -4.2575747,
            global: g2,
            patch: p2,
        },
    ]
}

/// M = 3 with the slope reduction [k0, alpha_inf, beta], as
/// `cntc_setmaterialparameters`'s M digit and parameters.
fn modified_fastsim(k0: f64, alpha_inf: f64, beta: f64) -> (i32, Vec<f64>) {
    (3, vec![0.28, 0.28, 82000.0, 82000.0, k0, alpha_inf, beta])
}

/// M = 4 with an interfacial layer of shear modulus `g3` [N/mm²],
/// thickness `laythk` [mm] and yield limit `tau_c0` [N/mm²] (0: elastic),
/// without hardening.
fn layer(g3: f64, laythk: f64, tau_c0: f64) -> (i32, Vec<f64>) {
    (
        4,
        vec![0.28, 0.28, 82000.0, 82000.0, g3, laythk, tau_c0, 0.0],
    )
}

/// Solves `r` on its element, set up as `mbench` with the T digit `tang`
/// and, with `Some`, the M digit and material parameters `material`;
/// compares against CONTACT's values with the tolerances `tol`:
/// [N] of the forces (global FX_TR, FY_TR and the patch's FN, FX, FS),
/// relative of the contact area and of the maximum pressure, [mm²] of the
/// adhesion area. FZ_TR is the load, met to 1 N.
fn compare(r: &Reference, tang: i32, material: Option<(i32, Vec<f64>)>, tol: [f64; 4]) {
    compare_then(r, tang, material, tol, |_| {});
}

/// [`compare`], then `check` on the solved element's number before it is
/// finalised.
fn compare_then(
    r: &Reference,
    tang: i32,
    material: Option<(i32, Vec<f64>)>,
    tol: [f64; 4],
    check: impl FnOnce(i32),
) {
    let [force_tol, area_tol, pmax_tol, adh_tol] = tol;
    let ire = r.ire;
    // An elasto-plastic layer's plastic elements are neither adhesion nor
    // slip.
    let plastic = matches!(&material, Some((4, p)) if p[6] > 0.0);
    unsafe {
        mbench(ire, r.iwhe);
        let (codes, values) = ([flags::IC_TANG], [tang]);
        cntc_setflags(&ire, &-1, &1, codes.as_ptr(), values.as_ptr());
        if let Some((m, params)) = material {
            let n = params.len() as i32;
            cntc_setmaterialparameters(&ire, &-1, &m, &n, params.as_ptr());
        }
        solve_one_patch(ire, r.pos, r.vpitch);
        let case = format!("ire {ire}");
        let mut g = [0.0; 24];
        cntc_getglobalforces(&ire, &-1, &24, g.as_mut_ptr());
        close(&format!("{case} FX_TR"), g[0], r.global[0], force_tol);
        close(&format!("{case} FY_TR"), g[1], r.global[1], force_tol);
        close(&format!("{case} FZ_TR"), g[2], r.global[2], 1.0);
        let icp = 1;
        let (mut fn_, mut fx, mut fs, mut mz) = (0.0, 0.0, 0.0, 0.0);
        cntc_getcontactforces(&ire, &icp, &mut fn_, &mut fx, &mut fs, &mut mz);
        close(&format!("{case} FN"), fn_, r.patch[0], force_tol);
        close(&format!("{case} FX"), fx, r.patch[1], force_tol);
        close(&format!("{case} FS"), fs, r.patch[2], force_tol);
        let (mut ca, mut ha, mut sa) = (0.0, 0.0, 0.0);
        cntc_getcontactpatchareas(&ire, &icp, &mut ca, &mut ha, &mut sa);
        close(
            &format!("{case} CAREA"),
            ca,
            r.patch[3],
            area_tol * r.patch[3],
        );
        close(&format!("{case} HAREA"), ha, r.patch[4], adh_tol);
        if plastic {
            assert!(ha + sa <= ca + 1e-9, "{case}: HAREA + SAREA > CAREA");
        } else {
            close(&format!("{case} CAREA = HAREA + SAREA"), ha + sa, ca, 1e-9);
        }
        let mut pmax = 0.0;
        cntc_getmaximumpressure(&ire, &icp, &mut pmax);
        close(
            &format!("{case} PMAX"),
            pmax,
            r.patch[5],
            pmax_tol * r.patch[5],
        );
        if tang == 0 {
            // No tangential problem: no creep forces, creepages 0.
            let mut c = [1.0; 3];
            cntc_getcreepages(&ire, &icp, &mut c[0], &mut c[1], &mut c[2]);
            assert_eq!(c, [0.0; 3], "{case} creepages");
            assert_eq!([g[0], fx, fs, mz], [0.0; 4], "{case} creep forces");
        }
        check(ire);
        cntc_finalize(&ire);
    }
}

/// Checks `cntc_getparameters` task 2's FLX(1:3) (values 8-10, [mm³/N])
/// and K_EFF (value 14) of patch 1 of `ire` against CONTACT's `flx`, `k_eff`
/// within the relative tolerances `flx_tol`, `k_tol`.
fn flx_and_k_eff(ire: i32, flx: f64, k_eff: f64, flx_tol: f64, k_tol: f64) {
    let mut v = [0.0; 30];
    unsafe { cntc_getparameters(&ire, &1, &2, &30, v.as_mut_ptr()) };
    for (i, l) in v[7..10].iter().enumerate() {
        close(&format!("ire {ire} FLX({})", i + 1), *l, flx, flx_tol * flx);
    }
    close(&format!("ire {ire} K_EFF"), v[13], k_eff, k_tol * k_eff);
}

// The CONTACT values below are those CONTACT's own library returned
// (eve70a/CONTACT at d431cdb, contact_addon_linux64.so built with gfortran
// 12.2 -O2 and FFTW 3.3.10) for python_mbench.py's set-up driven through
// CONTACT's python_intfc (its mends as in crates/cntc/bench/
// contact_examples.sh; flags T and B, and cntc_setmaterialparameters with
// M = 3 and [nu, nu, G, G, k0, alpha_inf, beta] added): cases 5 of wheel 1
// and 16 of wheel 2. Over all 42 cases of the example the differences of
// CONTACT's and railcontact's areas and maximum pressures are those of the
// normal problems, as with M = 0 (docs/cntc.md): the contact areas within
// 0.9 % (two elements), the maximum pressures within 0.25 %.
//
// Per set-up (M = 3 with k0 = 1, alpha_inf = 1, beta = 0; M = 3 with k0 =
// 0.54, alpha_inf = 0.02, beta = 0.62; T = 0 with M = 0), tread then
// flange: (FX_TR, FY_TR, FZ_TR), (FN, FX, FS, CAREA, HAREA, PMAX).
#[rustfmt::skip]
const CONTACT: [[([f64; 3], [f64; 6]); 2]; 3] = [
    [([536.061539, -3094.45336, 10000.0007], [10040.6971, 536.061539, -2959.73963, 33.2, 0.76, 465.945205]),
     ([-2087.57785, 9343.91373, 9999.97567], [13263.5388, -2087.57785, -3374.42959, 8.32, 0.0, 2629.73891])],
    [([422.005142, -2458.67958, 10000.0005], [10032.1491, 422.005142, -2324.02677, 33.12, 18.4, 465.813301]),
     ([-1872.042, 9327.62437, 9999.99875], [13249.8387, -1872.042, -3383.24209, 8.32, 1.52, 2628.87625])],
    [([0.0, -134.430058, 9999.99422], [10000.8978, 0.0, 0.0, 33.04, 33.04, 465.33057]),
     ([0.0, 15594.9354, 10000.0104], [18525.7177, 0.0, 0.0, 10.84, 10.84, 2921.26766])],
];

// FLX(1:3) [mm³/N] (all three equal: fully blended) and K_EFF that
// CONTACT's library returned (cntc_getparameters task 2, icp = 1) on these
// two set-ups after the calculation, tread then flange (revision 2707,
// crates/cntc/bench/given_flexibility_cases.py, its "m1-m3" cases; beta = 1
// there instead of 0 for k0 = alpha_inf = 1, which gives k = 1 either way).
const CONTACT_FLX_K_EFF: [[(f64, f64); 2]; 2] = [
    [(2.786839530941207e-05, 1.0), (1.1999925138279914e-05, 1.0)],
    [
        (2.7834798513449764e-05, 0.2215399818609883),
        (1.19999279805663e-05, 0.05315334406334094),
    ],
];

/// M = 3 with k0 = 1, alpha_inf = 1, beta = 0 (Kalker's FASTSIM on each
/// patch, the exact pressure as its bound). Measured: forces within 0.28 N
/// (the flange's FX), the areas within 0.12 % (the tread's, one element
/// of 0.04 mm² in 33 mm²), the maximum pressures within 0.11 %, the same
/// adhesion areas. Tolerances: 2 N, the area 1 %, the pressure 0.5 %, the
/// adhesion area 0.1 mm² (two elements). FLX(1:3), the flexibilities of
/// each patch's equivalent ellipse (blended): measured within 6.0e-4 of
/// CONTACT's on the tread, whose contact elements are one fewer than
/// CONTACT's (the equivalent ellipse follows them), 3.5e-6 on the flange
/// (the same elements; its creepages, which weigh the blend, 5e-5 apart).
/// Tolerances 1e-3 and 1e-5 relative; K_EFF exactly 1.
#[test]
fn fastsim_on_tread_and_flange_matches_contacts_library() {
    let [tread, flange] = tread_and_flange(41, &CONTACT[0]);
    let kalker = || Some(modified_fastsim(1.0, 1.0, 0.0));
    let [(tread_flx, _), (flange_flx, _)] = CONTACT_FLX_K_EFF[0];
    compare_then(&tread, 3, kalker(), [2.0, 0.01, 0.005, 0.1], |ire| {
        flx_and_k_eff(ire, tread_flx, 1.0, 1e-3, 0.0)
    });
    compare_then(&flange, 3, kalker(), [2.0, 0.01, 0.005, 0.1], |ire| {
        flx_and_k_eff(ire, flange_flx, 1.0, 1e-5, 0.0)
    });
}

/// M = 3 with the slope reduction of CONTACT's tractcurv example (k0 =
/// 0.54, alpha_inf = 0.02, beta = 0.62): in partial slip the creep forces
/// depend on the flexibilities of the equivalent ellipse of the loaded
/// elements, which both grids now load alike (an element's centre on the
/// reference point). Measured: forces within 0.9 N (the flange's FY_TR),
/// the same areas, the maximum pressures within 0.11 %, the same adhesion
/// areas. Tolerances: 2 N; areas, pressures and adhesion areas as above.
/// FLX(1:3) and K_EFF: measured within 7.3e-8 and 2.1e-7 of CONTACT's on
/// the tread (CONTACT's Kalker table holds single-precision constants,
/// 3.6e-8 apart at a/b = 0.5), 3.3e-6 and 3.8e-5 on the flange (its
/// creepages 5e-5 apart). Tolerances 1e-6, 1e-6; 1e-5, 1e-4 relative.
#[test]
fn modified_fastsim_on_tread_and_flange_matches_contacts_library() {
    let [tread, flange] = tread_and_flange(43, &CONTACT[1]);
    let reduction = || Some(modified_fastsim(0.54, 0.02, 0.62));
    let [(tread_flx, tread_k), (flange_flx, flange_k)] = CONTACT_FLX_K_EFF[1];
    compare_then(&tread, 3, reduction(), [2.0, 0.01, 0.005, 0.1], |ire| {
        flx_and_k_eff(ire, tread_flx, tread_k, 1e-6, 1e-6)
    });
    compare_then(&flange, 3, reduction(), [2.0, 0.01, 0.005, 0.1], |ire| {
        flx_and_k_eff(ire, flange_flx, flange_k, 1e-5, 1e-4)
    });
}

/// T = 0 (the normal problem only, M = 0): measured FN within 0.16 N,
/// FY_TR within 0.19 N, the areas within 0.12 % (one element, which
/// CONTACT counts as adhesion too: it counts the contact area as adhesion
/// and reports zero creepages), the pressures within 0.12 %. Tolerances:
/// 1 N, the area (and the adhesion area) 1 %, the pressure 0.5 %.
#[test]
fn frictionless_tread_and_flange_match_contacts_library() {
    let [tread, flange] = tread_and_flange(45, &CONTACT[2]);
    compare(&tread, 0, None, [1.0, 0.01, 0.005, 0.01 * 33.04]);
    compare(&flange, 0, None, [1.0, 0.01, 0.005, 0.01 * 10.84]);
}

// M = 4 with an interfacial layer on the same two cases: CONTACT's own
// library (d431cdb, built and driven as above) with
// cntc_setmaterialparameters(ire, -1, 4, [0.28, 0.28, 82000, 82000, G3,
// LAYTHK, TAU_C0, 0]), per row (G3 [N/mm²], LAYTHK [mm], TAU_C0 [N/mm²]):
// elastic (500, 0.1, 0), the layer halving the tread's creep forces, and
// (1000, 0.01, 0); elasto-plastic (500, 0.1, 60), flowing on the tread and
// the flange, and (5000, 0.01, 80). Tread then flange: (FX_TR, FY_TR,
// FZ_TR), (FN, FX, FS, CAREA, HAREA, PMAX).
const LAYERS: [(f64, f64, f64); 4] = [
    (500.0, 0.1, 0.0),
    (1000.0, 0.01, 0.0),
    (500.0, 0.1, 60.0),
    (5000.0, 0.01, 80.0),
];
#[rustfmt::skip]
const CONTACT_LAYER: [[([f64; 3], [f64; 6]); 2]; 4] = [
    [([292.329078, -1717.51399, 10000.001], [10022.1854, 292.329078, -1582.93218, 33.12, 26.32, 465.65945]),
     ([-1880.83795, 9293.22286, 9999.99028], [13220.8744, -1880.83795, -3401.80506, 8.32, 1.2, 2627.0609])],
    [([549.155499, -3095.25047, 10000.0007], [10040.7078, 549.155499, -2960.53666, 33.2, 0.04, 465.94537]),
     ([-2072.04775, 9332.81914, 10000.0039], [13254.2145, -2072.04775, -3380.4423, 8.32, 0.0, 2629.15392])],
    [([248.421793, -1486.09073, 10000.0011], [10019.0744, 248.421793, -1351.5311, 33.12, 17.68, 465.611406]),
     ([-317.380065, 14652.0914, 9999.99939], [17732.0254, -317.380065, -508.96474, 10.48, 0.04, 2882.89669])],
    [([414.903163, -2406.63221, 10000.0008], [10031.4496, 414.903163, -2271.98439, 33.12, 0.0, 465.802499]),
     ([-417.957207, 14375.6874, 9999.94775], [17499.3201, -417.957207, -658.132675, 10.32, 0.0, 2871.24608])],
];

/// M = 4 (the layer's flexibility LAYTHK/G3 in the patches' tangential
/// influence coefficients, its plasticity in their tangential solvers).
/// Measured: the forces within 2.7 N (0.03 % of FZ: the elastic layer's
/// FY_TR on the flange), the adhesion area within 0.04 mm² (one element;
/// the plastic elements counted apart as CONTACT counts them), the areas
/// within 0.39 % and the maximum pressures within 0.12 % (the normal
/// problem, which the layer does not change). Tolerances: 5 N, areas,
/// pressures and adhesion areas as with M = 3.
#[test]
fn layers_on_tread_and_flange_match_contacts_library() {
    for (k, (g3, laythk, tau_c0)) in LAYERS.into_iter().enumerate() {
        let ire = 47 + 2 * k as i32;
        let [tread, flange] = tread_and_flange(ire, &CONTACT_LAYER[k]);
        let m4 = || Some(layer(g3, laythk, tau_c0));
        compare(&tread, 3, m4(), [5.0, 0.01, 0.005, 0.1]);
        compare(&flange, 3, m4(), [5.0, 0.01, 0.005, 0.1]);
    }
}

// M = 2 (FASTSIM with one given flexibility FLX [mm³/N]) on the same two
// cases: CONTACT's own library (contact_addon_linux64.so of CONTACT
// revision 2707, built with gfortran 12 -O2) driven through its
// python_intfc by crates/cntc/bench/given_flexibility_cases.py (python_mbench.py's set-up as `mbench`
// makes it, then cntc_setmaterialparameters(ire, -1, 2, [0.28, 0.28,
// 82000, 82000, FLX, K0_MF, ALFAMF, BETAMF])), per row (FLX, K0_MF, ALFAMF,
// BETAMF): (5e-5, 1, 1, 1), no slope reduction; (1.5e-4, 0.54, 0.02,
// 0.62). Tread then flange: (FX_TR, FY_TR, FZ_TR), (FN, FX, FS, CAREA,
// HAREA, PMAX).
const GIVEN: [(f64, [f64; 3]); 2] = [(5e-5, [1.0, 1.0, 1.0]), (1.5e-4, [0.54, 0.02, 0.62])];
#[rustfmt::skip]
const CONTACT_GIVEN: [[([f64; 3], [f64; 6]); 2]; 2] = [
    [([526.887174, -3039.01183, 10000.0007], [10039.9517, 526.887174, -2904.30341, 33.2, 4.64, 465.933719]),
     ([-2039.20642, 9306.57163, 9999.98304], [13232.1077, -2039.20642, -3394.59324, 8.32, 0.0, 2627.76805])],
    [([109.748188, -739.646271, 9999.99789], [10009.0368, 109.748188, -605.158189, 33.08, 32.0, 465.456404]),
     ([-489.653239, 13947.1105, 10000.0003], [17138.5712, -489.653239, -889.536475, 10.16, 9.56, 2852.75776])],
];

/// CONTACT's K_EFF of the [`GIVEN`] set-ups, tread then flange (the same
/// script's "m1-tread", "m1-flange" cases).
const CONTACT_GIVEN_K_EFF: [[f64; 2]; 2] = [[1.0, 1.0], [0.22140071259701247, 0.05921744153351214]];

/// M = 2: FASTSIM on each patch with the one flexibility FLX (no blending,
/// the spin's rigid slip unscaled), the exact pressure as its bound, the
/// slope reduction with the loaded elements' equivalent ellipse, as
/// CONTACT's library runs it in module 1. Measured: forces within 0.44 N
/// (0.004 % of FZ) on the tread and on the flange without slope reduction;
/// the reduced flange within 5.0 N (FY_TR; FS 2.6 N, 0.29 % of FS, and FN
/// 4.2 N apart): its normal problem loads one element more than
/// CONTACT's (10.20 mm² for 10.16 mm², +0.39 %), and the equivalent
/// ellipse's area enters the slope reduction's epsilon: at CONTACT's k_eff
/// 0.0592 (`cntc_getparameters`) d ln k / d ln epsilon = -0.74, so k and
/// the (mostly adhering) FS fall by 0.29 %, as measured; FN follows FS
/// through the vertical balance on the flange. The adhesion areas within
/// one element (0.04 mm²), the maximum pressures within 0.11 %.
/// Tolerances: 2 N, the reduced flange 6 N; areas, pressures and adhesion
/// areas as with M = 3. `cntc_getparameters` task 2: FLX(1:3) is FLX;
/// K_EFF 1 without slope reduction, with it CONTACT's 0.22140071259701247
/// (tread) and 0.05921744153351214 (flange) (the script above): measured
/// within 6.9e-4 (the tread's contact one element more than CONTACT's) and
/// 3.1e-3 (the flange's, as above). Tolerances 1e-3 and 4e-3 relative.
#[test]
fn given_flexibility_on_tread_and_flange_matches_contacts_library() {
    for (k, (flx, [k0, alpha, beta])) in GIVEN.into_iter().enumerate() {
        let ire = 55 + 2 * k as i32;
        let [tread, flange] = tread_and_flange(ire, &CONTACT_GIVEN[k]);
        let m2 = || {
            let p = vec![0.28, 0.28, 82000.0, 82000.0, flx, k0, alpha, beta];
            Some((2, p))
        };
        let flange_tol = if k == 0 { 2.0 } else { 6.0 };
        let [tread_k, flange_k] = CONTACT_GIVEN_K_EFF[k];
        compare_then(&tread, 3, m2(), [2.0, 0.01, 0.005, 0.1], |ire| {
            flx_and_k_eff(ire, flx, tread_k, 1e-12, 1e-3)
        });
        compare_then(&flange, 3, m2(), [flange_tol, 0.01, 0.005, 0.1], |ire| {
            flx_and_k_eff(ire, flx, flange_k, 1e-12, 4e-3)
        });
    }
}
