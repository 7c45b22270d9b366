//! Module 3 transient rolling (T = 2) with a rolling step of more than one
//! element, through the C calls, against CONTACT's test bank
//! (github.com/eve70a/CONTACT, `testbank/testbank.inp` and
//! `testbank/testbank.ref_out`, case 17): the elements that enter the
//! contact area during the step take CONTACT's leading-edge correction
//! (`railcontact_solver::core::leading_edge`).

use contact_addon::ffi::*;
use contact_addon::flags;

/// testbank.inp case 17: 41 x 41 elements of 0.2 mm from (-4.1, -4.1) mm
/// (IPOTCN 1), h = 0.002963 (x² + y²) /mm (IBASE 1), G = 1 N/mm², nu =
/// 0.28 both, FN = 0.4705 N (N = 1), mu = 0.4013, one transient rolling
/// step (T = 2) from rest (P = 2) of DQ = 0.4 mm (two elements) at V =
/// 1000 mm/s with FX/(FSTAT FN) = 0.657 prescribed (F = 1), EPS 1e-6.
/// CONTACT finds "CREEP X -4.500E-02" with "NCON NADH NSLIP" 973 466 507
/// and FX 0.1240 N; with a step of two elements without the correction
/// the creepage would be -4.434e-2 and NADH 485 (the solver's
/// `a_rolling_step_of_two_elements_from_rest_matches_contact_testbank_case_17`).
#[test]
fn a_rolling_step_of_two_elements_at_a_prescribed_force_matches_contacts_reference() {
    let (ire, icp) = (501, 1);
    let codes = [
        flags::IF_UNITS,
        flags::IC_NORM,
        flags::IC_TANG,
        flags::IC_PVTIME,
        flags::IC_FORCE,
    ];
    let values = [flags::UN_CNTC, 1, 2, 2, 1];
    let (mut ierror, mut cksi, mut ceta, mut cphi) = (12345, f64::NAN, f64::NAN, f64::NAN);
    let (mut fn_, mut fx, mut fy, mut mz) = (f64::NAN, f64::NAN, f64::NAN, f64::NAN);
    let (mut carea, mut harea, mut sarea) = (f64::NAN, f64::NAN, f64::NAN);
    unsafe {
        cntc_setflags(&ire, &icp, &5, codes.as_ptr(), values.as_ptr());
        let mat = [0.28, 0.28, 1.0, 1.0];
        cntc_setmaterialparameters(&ire, &icp, &0, &4, mat.as_ptr());
        let pot = [41.0, 41.0, -4.1, -4.1, 0.2, 0.2];
        cntc_setpotcontact(&ire, &icp, &1, &6, pot.as_ptr());
        let b = [0.002963, 0.0, 0.002963, 0.0, 0.0, 0.0];
        cntc_setundeformeddistc(&ire, &icp, &1, &6, b.as_ptr());
        cntc_setfrictionmethod(&ire, &icp, &0, &2, [0.4013, 0.4013].as_ptr());
        cntc_setreferencevelocity(&ire, &icp, &1000.0);
        cntc_setrollingstepsize(&ire, &icp, &0.0, &0.4);
        cntc_setnormalforce(&ire, &icp, &0.4705);
        let (ip, rp) = ([80, 30, 5, 1], [1e-6]);
        cntc_setsolverflags(&ire, &icp, &0, &4, ip.as_ptr(), &1, rp.as_ptr());
        cntc_settangentialforces(&ire, &icp, &0.657, &0.0);
        cntc_calculate(&ire, &icp, &mut ierror);
        cntc_getcreepages(&ire, &icp, &mut cksi, &mut ceta, &mut cphi);
        cntc_getcontactforces(&ire, &icp, &mut fn_, &mut fx, &mut fy, &mut mz);
        cntc_getcontactpatchareas(&ire, &icp, &mut carea, &mut harea, &mut sarea);
    }
    assert_eq!(ierror, 0);
    let counts = [carea, harea, sarea].map(|a| (a / (0.2 * 0.2)).round() as i64);
    println!("testbank case 17: CKSI {cksi:.6e}, FX {fx:.6} N, NCON NADH NSLIP {counts:?}");
    assert!(
        (cksi / -4.5e-2 - 1.0).abs() <= 1e-3,
        "CKSI {cksi:e} against -4.500e-2"
    );
    assert!((fx / 0.1240 - 1.0).abs() <= 5e-4, "FX {fx} against 0.1240");
    assert_eq!(counts, [973, 466, 507]);
}
