//! The exported functions called as a C caller calls them (through
//! `contact_addon::ffi`, the same code the shared library exports): error
//! codes for bad arguments instead of crashes, CONTACT's error
//! conventions, and result elements used from several threads at once.
//! Each test uses its own result elements (the library is one per
//! process, and the tests run side by side).

use std::ptr::{null, null_mut};

use contact_addon::ffi::*;
use contact_addon::flags::{self, err};

/// Configures (ire, 1) as CONTACT's tractcurv curve 1 (module 3, steady
/// rolling of an ellipse a/b = 0.5 at 106.7 kN, mu 0.33).
fn tractcurv(ire: i32) {
    let icp = 1;
    unsafe {
        let (codes, values) = (
            [
                flags::IF_UNITS,
                flags::IC_TANG,
                flags::IC_NORM,
                flags::IC_PVTIME,
            ],
            [flags::UN_CNTC, 3, 1, 2],
        );
        cntc_setflags(&ire, &icp, &4, codes.as_ptr(), values.as_ptr());
        let mat = [0.28, 0.28, 82000.0, 82000.0];
        cntc_setmaterialparameters(&ire, &icp, &0, &4, mat.as_ptr());
        let mu = [0.33, 0.33];
        cntc_setfrictionmethod(&ire, &icp, &0, &2, mu.as_ptr());
        let hz = [48.0, 44.0, 0.0008, 0.5, 1.1];
        cntc_sethertzcontact(&ire, &icp, &-2, &5, hz.as_ptr());
        cntc_setreferencevelocity(&ire, &icp, &10000.0);
        cntc_setnormalforce(&ire, &icp, &106700.0);
    }
}

/// Solves (ire, 1) at creepage `cksi`: (ierror, FX).
fn fx_at(ire: i32, cksi: f64) -> (i32, f64) {
    let icp = 1;
    let (mut ierror, mut f) = (12345, [0.0; 4]);
    unsafe {
        cntc_setcreepages(&ire, &icp, &cksi, &0.0, &0.0);
        cntc_calculate(&ire, &icp, &mut ierror);
        let [fn_, fx, fy, mz] = &mut f;
        cntc_getcontactforces(&ire, &icp, fn_, fx, fy, mz);
    }
    (ierror, f[1])
}

#[test]
fn null_pointers_and_negative_lengths_are_error_codes() {
    let (ire, icp) = (101, 1);
    tractcurv(ire);
    let mut ierror = 0;
    unsafe {
        // A null ire, icp or creepage: an error code, no crash.
        cntc_calculate(null(), &icp, &mut ierror);
        assert_eq!(ierror, err::ARGUMENT);
        cntc_calculate(&ire, null(), &mut ierror);
        assert_eq!(ierror, err::ARGUMENT);
        // A null ierror: nothing to write it to, no crash.
        cntc_calculate(&ire, &icp, null_mut());
        cntc_setcreepages(&ire, &icp, null(), &0.0, &0.0);
        // A negative array length, and null arrays with a positive one,
        // leave the configuration as it was.
        cntc_setflags(&ire, &icp, &-1, null(), null());
        cntc_setflags(&ire, &icp, &2, null(), null());
        let (code, mut value) = ([flags::IC_TANG], [0]);
        cntc_getflags(&ire, &icp, &1, code.as_ptr(), value.as_mut_ptr());
        assert_eq!(value[0], 3);
        let hz = [48.0, 44.0];
        cntc_sethertzcontact(&ire, &icp, &-2, &-5, hz.as_ptr());
        // Null outputs of a getter: untouched, no crash.
        cntc_getcontactforces(&ire, &icp, null_mut(), null_mut(), null_mut(), null_mut());
        let mut tiny = [7.0_f64; 1];
        cntc_getpotcontact(&ire, &icp, &1, tiny.as_mut_ptr());
        // Strings: a null name with a length, a negative length.
        cntc_readinpfile(&ire, &1988, null(), &5, &mut ierror);
        assert_eq!(ierror, err::ARGUMENT);
    }
    // The problem is intact: CONTACT's force (tractcurv curve 1, cksi 0.0004:
    // -9111.544 N, see tests/examples.rs).
    let (ierror, fx) = fx_at(ire, 0.0004);
    assert_eq!(ierror, 0);
    assert!((fx / -9111.544156 - 1.0).abs() < 1e-6, "{fx}");
}

#[test]
fn unknown_result_elements_and_patches_are_refused() {
    let mut ierror = 0;
    let mut fx = [-1.0_f64; 4];
    unsafe {
        // ire outside [1, 999]: CONTACT's -101.
        for ire in [0, -3, 1000] {
            cntc_calculate(&ire, &1, &mut ierror);
            assert_eq!(ierror, err::IRE, "ire {ire}");
        }
        // icp outside [1, 9] in module 3: CONTACT's -31.
        tractcurv(102);
        cntc_calculate(&102, &10, &mut ierror);
        assert_eq!(ierror, err::ICP);
        // A getter of an element never configured leaves its outputs.
        let [a, b, c, d] = &mut fx;
        cntc_getcontactforces(&103, &1, a, b, c, d);
        assert_eq!(fx, [-1.0; 4]);
        // A module 1 getter on a module 3 element.
        let mut npatch = -7;
        cntc_getnumcontactpatches(&102, &mut npatch);
        assert_eq!(npatch, -7);
        // Results before any calculation.
        let [a, b, c, d] = &mut fx;
        cntc_getcontactforces(&102, &1, a, b, c, d);
        assert_eq!(fx, [-1.0; 4]);
    }
}

#[test]
fn viscoelastic_bodies_relaxing_at_once_are_elastic_with_the_final_modulus() {
    // M = 1 (FG, TC per body) in steady rolling: TC = 0 relaxes at once,
    // the elastic bodies of G_g/(1 + FG) (CONTACT's user guide,
    // §"Viscoelastic materials"); TC = 0.1 s at VELOC = 10 m/s relaxes
    // over 1 m, a hundred times the patch's size: between the two elastic
    // moduli, near the glassy one.
    // T = 1 (a shift) is refused. The grid is given (40 x 40 elements over
    // 22 x 44 mm, h = 0.0008 x² + 0.0002814 y² per mm), the same for all.
    let (ire, icp) = (111, 1);
    tractcurv(ire);
    unsafe {
        let pot = [40.0, 40.0, -10.725, -21.45, 0.55, 1.1];
        cntc_setpotcontact(&ire, &icp, &3, &6, pot.as_ptr());
        let udist = [0.0008, 0.0, 0.0002814, 0.0, 0.0, 0.0];
        cntc_setundeformeddistc(&ire, &icp, &1, &6, udist.as_ptr());
    }
    let visco = |fg: f64, tc: f64| {
        let p = [0.28, 0.28, 82000.0, 82000.0, fg, fg, tc, tc];
        unsafe { cntc_setmaterialparameters(&ire, &icp, &1, &8, p.as_ptr()) };
    };
    let elastic = |g: f64| {
        let p = [0.28, 0.28, g, g];
        unsafe { cntc_setmaterialparameters(&ire, &icp, &0, &4, p.as_ptr()) };
    };
    let cksi = -3e-4;
    visco(1.0, 0.0);
    let (e1, at_once) = fx_at(ire, cksi);
    elastic(41000.0);
    let (e2, relaxed) = fx_at(ire, cksi);
    elastic(82000.0);
    let (e3, glassy) = fx_at(ire, cksi);
    visco(1.0, 0.1);
    let (e4, between) = fx_at(ire, cksi);
    assert_eq!([e1, e2, e3, e4], [0; 4]);
    assert!(
        (at_once / relaxed - 1.0).abs() < 1e-6,
        "{at_once} vs {relaxed}"
    );
    assert!(
        relaxed.abs() < between.abs() && between.abs() < glassy.abs(),
        "{relaxed} {between} {glassy}"
    );
    let mut ierror = 0;
    unsafe {
        cntc_setflags(&ire, &icp, &1, &flags::IC_TANG, &1);
        cntc_calculate(&ire, &icp, &mut ierror);
    }
    assert!(ierror < 0, "{ierror}");
}

#[test]
fn methods_the_library_lacks_are_named_at_calculation() {
    let (ire, icp) = (110, 1);
    tractcurv(ire);
    let mut ierror = 0;
    unsafe {
        // M = 6 (CONTACT's original FaStrip, for testing): refused until
        // replaced.
        let fastrip = [0.28, 0.28, 82000.0, 82000.0];
        cntc_setmaterialparameters(&ire, &icp, &6, &4, fastrip.as_ptr());
        cntc_calculate(&ire, &icp, &mut ierror);
        assert_eq!(ierror, err::NOT_SUPPORTED);
        let elastic = [0.28, 0.28, 82000.0, 82000.0];
        cntc_setmaterialparameters(&ire, &icp, &0, &4, elastic.as_ptr());
        cntc_calculate(&ire, &icp, &mut ierror);
        assert_eq!(ierror, 0);
        // Imperial units.
        cntc_setflags(&ire, &icp, &1, &flags::IF_UNITS, &flags::UN_IMPER);
        cntc_calculate(&ire, &icp, &mut ierror);
        assert_eq!(ierror, err::NOT_SUPPORTED);
        cntc_setflags(&ire, &icp, &1, &flags::IF_UNITS, &flags::UN_CNTC);
        // Temperature-dependent friction (L = 6).
        let p = [0.3, 20.0, -0.1, 200.0, 0.0, 0.0];
        cntc_setfrictionmethod(&ire, &icp, &6, &6, p.as_ptr());
        cntc_calculate(&ire, &icp, &mut ierror);
        assert_eq!(ierror, err::NOT_SUPPORTED);
        let mu = [0.33, 0.33];
        cntc_setfrictionmethod(&ire, &icp, &0, &2, mu.as_ptr());
        cntc_calculate(&ire, &icp, &mut ierror);
        assert_eq!(ierror, 0);
        // A friction method with the wrong number of parameters is
        // refused at once; the law stays as it was.
        cntc_setfrictionmethod(&ire, &icp, &4, &3, mu.as_ptr());
    }
    let (ierror, fx) = fx_at(ire, 0.0004);
    assert_eq!(ierror, 0);
    assert!((fx / -9111.544156 - 1.0).abs() < 1e-6, "{fx}");
}

/// A patch reaching the border of its grid is solved and its border
/// elements counted in a positive ierror, as CONTACT counts them: the
/// ellipse of 106.7 kN on a grid of 0.9 times its size.
#[test]
fn border_contact_is_a_positive_count() {
    let (ire, icp) = (120, 1);
    tractcurv(ire);
    let mut ierror = 0;
    unsafe {
        let hz = [24.0, 22.0, 0.0008, 0.5, 0.9];
        cntc_sethertzcontact(&ire, &icp, &-2, &5, hz.as_ptr());
        cntc_setflags(&ire, &icp, &1, &flags::IC_TANG, &0);
        cntc_calculate(&ire, &icp, &mut ierror);
    }
    assert!(ierror > 0, "{ierror}");
}

/// Result elements solved on several threads at once give the numbers of
/// one thread, bit for bit.
#[test]
fn threads_on_different_result_elements() {
    let creepages = [0.0004, 0.0012, 0.0024, 0.006];
    tractcurv(130);
    let serial: Vec<(i32, f64)> = creepages.iter().map(|c| fx_at(130, *c)).collect();
    let threads: Vec<_> = (0..4)
        .map(|t| {
            std::thread::spawn(move || {
                let ire = 131 + t;
                tractcurv(ire);
                creepages.iter().map(|c| fx_at(ire, *c)).collect::<Vec<_>>()
            })
        })
        .collect();
    for t in threads {
        let got = t.join().unwrap();
        for (g, s) in got.iter().zip(&serial) {
            assert_eq!(g.0, s.0);
            assert_eq!(g.1.to_bits(), s.1.to_bits(), "{g:?} {s:?}");
        }
    }
}

/// The fields WX and WY are what CONTACT returns: the rigid slip's
/// right-hand side, -w, with the spin's term a sixth of an element
/// downstream.
#[test]
fn rigid_slip_fields_have_contacts_sign() {
    let (ire, icp) = (140, 1);
    let n = 400;
    let (mut wx, mut wy) = (vec![0.0; n], vec![0.0; n]);
    let mut ierror = 12345;
    unsafe {
        let codes = [
            flags::IF_UNITS,
            flags::IC_TANG,
            flags::IC_NORM,
            flags::IC_PVTIME,
        ];
        let values = [flags::UN_CNTC, 3, 1, 2];
        cntc_setflags(&ire, &icp, &4, codes.as_ptr(), values.as_ptr());
        let mat = [0.28, 0.28, 82000.0, 82000.0];
        cntc_setmaterialparameters(&ire, &icp, &0, &4, mat.as_ptr());
        cntc_setfrictionmethod(&ire, &icp, &0, &2, [0.3, 0.3].as_ptr());
        let hz = [20.0, 20.0, 0.0005, 0.0011, 1.2];
        cntc_sethertzcontact(&ire, &icp, &-1, &5, hz.as_ptr());
        cntc_setnormalforce(&ire, &icp, &50000.0);
        cntc_setcreepages(&ire, &icp, &0.001, &0.0005, &0.0003);
        cntc_calculate(&ire, &icp, &mut ierror);
        cntc_getfielddata(&ire, &icp, &22, &(n as i32), wx.as_mut_ptr());
        cntc_getfielddata(&ire, &icp, &23, &(n as i32), wy.as_mut_ptr());
    }
    assert_eq!(ierror, 0);
    // CONTACT's own library (eve70a/CONTACT, built with the contact kit)
    // on the same calls: elements 1, 38, 211 and 400 (Fortran numbering).
    let contact_wx = [-0.002579906, -0.002413601, -0.000916847, 0.000579906];
    let contact_wy = [0.002121717, -0.002653553, -0.000687266, -0.00321535];
    for (k, &i) in [0, 37, 210, 399].iter().enumerate() {
        assert!((wx[i] - contact_wx[k]).abs() < 1e-9, "WX[{i}] = {}", wx[i]);
        assert!((wy[i] - contact_wy[k]).abs() < 1e-9, "WY[{i}] = {}", wy[i]);
    }
}
