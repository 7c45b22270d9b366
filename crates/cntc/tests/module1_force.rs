//! Module 1 with a prescribed total force (F = 1): the pitch rate VPITCH
//! is found so that the wheel's total force on the rail along the
//! wheelset's longitudinal axis (FX_WS, given by
//! `cntc_settangentialforces(ire, -1, fx, 0)`) is the one asked, against
//! CONTACT's library on the Manchester benchmark's right wheel; and the
//! inputs F = 1 needs, refused by name when missing.

mod common;

use common::{mbench_right_wheel, set_flags};
use contact_addon::ffi::*;
use contact_addon::flags::{self, err};

/// The values of `mbench_right_wheel`'s bits: the 24 global forces first,
/// the wheelset's velocity last.
fn forces_and_vpitch(bits: &[u64]) -> ([f64; 24], f64) {
    let g: Vec<f64> = bits[..24].iter().map(|b| f64::from_bits(*b)).collect();
    let vpitch = f64::from_bits(*bits.last().unwrap());
    (g.try_into().unwrap(), vpitch)
}

/// CONTACT's library (eve70a/CONTACT at d431cdb, gfortran 12.2 -O2, FFTW
/// 3.3.10) on the calls of `mbench_right_wheel` with F = 1: lateral shift
/// y [mm], FX_WS [N], and what it answered with ierror 0: VPITCH [rad/s],
/// FX_TR, FY_TR [N] (cntc_getglobalforces 1, 2; CONTACT's units). Run with
/// ctypes on `contact_addon_linux64.so`, 2026-12-06. Left out: the
/// traction cases (FX_WS = -1500 N at 0, 3 and 6.5 mm) and 0 N at 3 mm,
/// where CONTACT's secant iteration stops with ierror -29 short of the
/// force (FX_WS -1568, -1073, -1287 and -453 N); railcontact reaches them.
const CONTACT: [(f64, f64, f64, f64, f64); 8] = [
    (0.0, 0.0, -4.3384093384, 33.7543, -1799.2145),
    (0.0, 1500.0, -4.2918996172, 1526.4928, -1382.3558),
    (0.0, 2500.0, -4.2177988932, 2509.8621, -450.2137),
    (3.0, 1500.0, -4.1790448427, 1252.1204, 13859.3903),
    (3.0, 2500.0, -4.1304246844, 2241.6790, 14448.1270),
    (6.5, 0.0, -4.1866807881, -171.9103, 9626.2197),
    (6.5, 1500.0, -4.1292124826, 1322.9969, 9922.0378),
    (6.5, 2500.0, -4.0839677426, 2311.7920, 10553.4735),
];

/// The sum of the normal forces of element `ire`'s patches \[N\].
fn normal_forces(ire: i32) -> f64 {
    let mut n = 0;
    unsafe { cntc_getnumcontactpatches(&ire, &mut n) };
    (1..=n)
        .map(|icp| {
            let (mut fn_, mut fx, mut fs, mut mz) = (0.0, 0.0, 0.0, 0.0);
            unsafe { cntc_getcontactforces(&ire, &icp, &mut fn_, &mut fx, &mut fs, &mut mz) };
            fn_
        })
        .sum()
}

#[test]
fn the_pitch_rate_found_for_a_total_force_is_contacts() {
    let (fz, mu) = (10_000.0, 0.3);
    for (k, &(y, fx_ws, vpitch_ref, fx_ref, fy_ref)) in CONTACT.iter().enumerate() {
        let ire = 200 + k as i32;
        let (ierror, bits) = mbench_right_wheel(ire, y, Some(fx_ws));
        assert_eq!(ierror, 0, "y = {y} mm, FX_WS = {fx_ws} N");
        let (g, vpitch) = forces_and_vpitch(&bits);
        let case = format!("y = {y} mm, FX_WS = {fx_ws} N: {g:?}, VPITCH {vpitch}");
        // The force asked, to the tolerance of the iteration: the
        // tangential tolerance of wheel/rail patches (1e-4) of mu FN, FN
        // the sum of the patches' normal forces (13,000 N on the flange
        // at 6.5 mm, where FZ is 10,000 N).
        let fn_sum = normal_forces(ire);
        assert!((g[6] - fx_ws).abs() <= 1e-4 * mu * fn_sum, "FX_WS: {case}");
        // CONTACT's pitch rate: within 1e-4 of it (largest seen 4.3e-5, on
        // the flange at 6.5 mm).
        assert!(
            (vpitch / vpitch_ref - 1.0).abs() <= 1e-4,
            "VPITCH {vpitch} against CONTACT's {vpitch_ref}: {case}"
        );
        // Track forces within 1e-4 FZ (largest seen 0.56 N).
        assert!((g[0] - fx_ref).abs() <= 1e-4 * fz, "FX_TR: {case}");
        assert!((g[1] - fy_ref).abs() <= 1e-4 * fz, "FY_TR: {case}");
        unsafe { cntc_finalize(&ire) };
    }
}

#[test]
fn a_traction_force_contact_stops_short_of_is_reached() {
    // FX_WS = -1500 N (traction) at 3 mm: CONTACT's library ends with
    // ierror -29 at -1073 N; railcontact's iteration reaches the force.
    let (ierror, bits) = mbench_right_wheel(220, 3.0, Some(-1500.0));
    assert_eq!(ierror, 0);
    let (g, vpitch) = forces_and_vpitch(&bits);
    assert!((g[6] + 1500.0).abs() <= 0.3, "{g:?}");
    // Traction turns the wheel faster than free rolling (-4.2473 rad/s
    // at FX_WS = 0, from the same iteration).
    assert!(vpitch < -4.25, "{vpitch}");
    unsafe { cntc_finalize(&220) };
}

#[test]
fn what_a_total_force_needs_is_named() {
    // F = 1 without a vertical force (N = 0), then without FX_WS, then
    // F = 2 (MY_WS, which CONTACT does not offer either).
    let ire = 230;
    let (ierror, _) = mbench_right_wheel(ire, 3.0, Some(1500.0));
    assert_eq!(ierror, 0);
    set_flags(ire, -1, &[(flags::IC_NORM, 0)]);
    let mut ierror = 0;
    unsafe { cntc_calculate1(&ire, &mut ierror) };
    assert_eq!(ierror, err::OTHER, "F = 1 with N = 0");
    unsafe { cntc_finalize(&ire) };

    let (mut ierror, _) = mbench_right_wheel(ire, 3.0, None);
    assert_eq!(ierror, 0);
    set_flags(ire, -1, &[(flags::IC_FORCE, 1)]);
    unsafe { cntc_calculate1(&ire, &mut ierror) };
    assert_eq!(ierror, err::OTHER, "F = 1 without FX_WS");
    set_flags(ire, -1, &[(flags::IC_FORCE, 2)]);
    unsafe { cntc_calculate1(&ire, &mut ierror) };
    assert_eq!(ierror, err::NOT_SUPPORTED, "F = 2");
    // A module 3 patch number is not module 1's total force.
    set_flags(ire, -1, &[(flags::IC_FORCE, 1)]);
    unsafe { cntc_settangentialforces(&ire, &1, &1500.0, &0.0) };
    unsafe { cntc_calculate1(&ire, &mut ierror) };
    assert_eq!(ierror, err::OTHER, "FX_WS still missing");
    unsafe { cntc_finalize(&ire) };
}
