//! FASTSIM (M = 3) through the C calls, against CONTACT's own library.
//!
//! CONTACT's numbers come from its shared library (`contact_addon_linux64.so`
//! of CONTACT revision 2707, 2025-07-23, built with gfortran 12 `-O2`):
//! * "python_tractcurv.py curve 3/4": CONTACT's example
//!   `examples/python_tractcurv.py` run against it, the forces
//!   `cntc_getcontactforces` returned (CONTACT's units: N);
//! * the other cases: the same library driven through the same `cntc_*`
//!   calls as below with ctypes, and its `cntc_gettractions`,
//!   `cntc_getelementdivision`, `cntc_getfielddata` read back.
//!
//! Each test uses its own result elements (the library is one per process).

use contact_addon::ffi::*;
use contact_addon::flags::{self, err, field};

/// Configures (ire, 1) as `python_tractcurv.py` (module 3, steady rolling,
/// Hertzian option -2: A1 = 0.0008 /mm, a/b = 0.5, 48 x 44 elements over
/// 1.1 times the ellipse, FN = 106.7 kN, V = 10 m/s, CONTACT's units) with
/// M = 3, B = 3 and the slope reduction `k0, alpha, beta`.
fn tractcurv_fastsim(ire: i32, k0_alpha_beta: [f64; 3]) {
    let icp = 1;
    unsafe {
        let codes = [
            flags::IF_UNITS,
            flags::IC_TANG,
            flags::IC_NORM,
            flags::IC_PVTIME,
        ];
        let values = [flags::UN_CNTC, 3, 1, 2];
        cntc_setflags(&ire, &icp, &4, codes.as_ptr(), values.as_ptr());
        let [k0, alpha, beta] = k0_alpha_beta;
        let mat = [0.28, 0.28, 82000.0, 82000.0, k0, alpha, beta];
        cntc_setmaterialparameters(&ire, &icp, &3, &7, mat.as_ptr());
        cntc_setflags(&ire, &icp, &1, &flags::IC_BOUND, &3);
        let hz = [48.0, 44.0, 0.0008, 0.5, 1.1];
        cntc_sethertzcontact(&ire, &icp, &-2, &5, hz.as_ptr());
        cntc_setreferencevelocity(&ire, &icp, &10000.0);
        cntc_setnormalforce(&ire, &icp, &106700.0);
    }
}

/// Sets the creepages, solves: ierror and FN, FX, FY, MZ.
fn solve(ire: i32, creep: [f64; 3]) -> (i32, [f64; 4]) {
    let icp = 1;
    let (mut ierror, mut f) = (12345, [0.0; 4]);
    unsafe {
        cntc_setcreepages(&ire, &icp, &creep[0], &creep[1], &creep[2]);
        cntc_calculate(&ire, &icp, &mut ierror);
        let [fn_, fx, fy, mz] = &mut f;
        cntc_getcontactforces(&ire, &icp, fn_, fx, fy, mz);
    }
    (ierror, f)
}

/// The per-element results of (ire, 1) on its grid of `n` elements: pn,
/// px, py, sx, sy, mu and the element division.
struct Fields {
    pn: Vec<f64>,
    px: Vec<f64>,
    sx: Vec<f64>,
    mu: Vec<f64>,
    division: Vec<i32>,
}

fn fields(ire: i32, n: usize) -> Fields {
    let (icp, len) = (1, n as i32);
    let (mut pn, mut px, mut py) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let (mut sx, mut sy, mut mu) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let mut division = vec![-1; n];
    unsafe {
        cntc_gettractions(
            &ire,
            &icp,
            &len,
            pn.as_mut_ptr(),
            px.as_mut_ptr(),
            py.as_mut_ptr(),
        );
        cntc_getmicroslip(&ire, &icp, &len, sx.as_mut_ptr(), sy.as_mut_ptr());
        cntc_getfielddata(&ire, &icp, &field::MU, &len, mu.as_mut_ptr());
        cntc_getelementdivision(&ire, &icp, &len, division.as_mut_ptr());
    }
    Fields {
        pn,
        px,
        sx,
        mu,
        division,
    }
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

fn count(division: &[i32], state: i32) -> usize {
    division.iter().filter(|d| **d == state).count()
}

/// CONTACT's library, python_tractcurv.py curve 3 (Kalker's FASTSIM,
/// k0 = alpha = beta = 1, parabolic bound B = 3, Coulomb mu = 0.33):
/// FX at cksi = 1e-5, 0.0016, 0.002 and 0.0048 (full sliding, mu times
/// the grid's pressure sum, not mu FN). Ours agree to 4e-8.
#[test]
fn tractcurv_curve_3() {
    let ire = 301;
    tractcurv_fastsim(ire, [1.0, 1.0, 1.0]);
    unsafe {
        cntc_setfrictionmethod(&ire, &1, &0, &2, [0.33, 0.33].as_ptr());
    }
    for (cksi, fx) in [
        (1e-5, -250.91899146741756),
        (0.0016, -26480.725658521496),
        (0.002, -29694.36379245238),
        (0.0048, -35213.807804809905),
    ] {
        let (ierror, f) = solve(ire, [cksi, 0.0, 0.0]);
        assert_eq!(ierror, 0);
        assert_eq!(f[0], 106700.0);
        assert!(rel(f[1], fx) < 1e-7, "cksi {cksi}: {} vs {fx}", f[1]);
        assert!(f[2].abs() < 1e-9 && f[3].abs() < 1e-6, "{f:?}");
    }
    // The fields at cksi = 0.0016, CONTACT's: 778 elements in adhesion,
    // 598 in slip, sum px = -145402.38310949167 N/mm^2, sum pn =
    // 585923.1968925573 N/mm^2, the largest |px| 248.56012092203946 N/mm^2
    // at element 1025 (1-based) with slip 0.0006809358283775271.
    solve(ire, [0.0016, 0.0, 0.0]);
    let f = fields(ire, 48 * 44);
    assert_eq!((count(&f.division, 1), count(&f.division, 2)), (778, 598));
    assert!(rel(f.px.iter().sum(), -145402.38310949167) < 1e-7);
    assert!(rel(f.pn.iter().sum(), 585923.1968925573) < 1e-9);
    assert!(rel(f.px[1024], -248.56012092203946) < 1e-7);
    assert!(rel(f.sx[1024], 0.0006809358283775271) < 1e-5);
    assert!(f.mu.iter().all(|m| *m == 0.33));
}

/// CONTACT's library, python_tractcurv.py curve 4 (modified FASTSIM k0 =
/// 0.54, alpha = 0.02, beta = 0.62; exponential falling friction L = 4,
/// mu = 0.1368 + 0.2232 exp(-ln2 s/990 mm/s), memory 0.003 mm, 1 mm/s,
/// which CONTACT's FASTSIM evaluates once at V sqrt(cksi^2 + ceta^2)):
/// FX at cksi = 1e-5, 0.002, 0.008, 0.022 (the peak) and 0.25. Ours
/// agree to 4e-8.
#[test]
fn tractcurv_curve_4() {
    let ire = 302;
    tractcurv_fastsim(ire, [0.54, 0.02, 0.62]);
    let law = [0.1368, 0.2232, 990.0, 0.0, 0.0, 0.003, 1.0];
    unsafe {
        cntc_setfrictionmethod(&ire, &1, &4, &7, law.as_ptr());
    }
    for (cksi, fx) in [
        (1e-5, -135.4409506408285),
        (0.002, -16855.728120572814),
        (0.008, -29446.144324073313),
        (0.022, -32463.683319265947),
        (0.25, -18735.018913849635),
    ] {
        let (ierror, f) = solve(ire, [cksi, 0.0, 0.0]);
        assert_eq!(ierror, 0);
        assert!(rel(f[1], fx) < 1e-7, "cksi {cksi}: {} vs {fx}", f[1]);
    }
    // At cksi = 0.008: 730 elements in adhesion, 646 in slip, sum px =
    // -161685.12952848375 N/mm^2, the coefficient 0.34784182511548756
    // everywhere (CONTACT's field MU).
    solve(ire, [0.008, 0.0, 0.0]);
    let f = fields(ire, 48 * 44);
    assert_eq!((count(&f.division, 1), count(&f.division, 2)), (730, 646));
    assert!(rel(f.px.iter().sum(), -161685.12952848375) < 1e-7);
    assert!(f.mu.iter().all(|m| rel(*m, 0.34784182511548756) < 1e-13));
}

/// CONTACT's library, SI units (CNTC_un_si): Hertzian option -1 (A1, B1 =
/// 0.5, 1.2 /m, 40 x 36 elements over 1.15 times the ellipse), FN = 60
/// kN, V = 20 m/s, M = 3 with k0 = 0.7, alpha = 0.3, beta = 0.8, linear
/// falling friction L = 2 (0.2 + 0.15 max(0, 1 - s/4 m/s)), the elliptic
/// bound B = 2, creepages 0.002, 0.001, 0.4 /m (blended flexibilities, an
/// a/b between the table's rows): FX, FY [N], MZ [N m], 560 elements in
/// adhesion and 296 in slip. Ours agree to 5e-8.
#[test]
fn combined_creepages_falling_friction_si() {
    let (ire, icp) = (303, 1);
    unsafe {
        let codes = [
            flags::IF_UNITS,
            flags::IC_TANG,
            flags::IC_NORM,
            flags::IC_PVTIME,
        ];
        let values = [flags::UN_SI, 3, 1, 2];
        cntc_setflags(&ire, &icp, &4, codes.as_ptr(), values.as_ptr());
        let mat = [0.28, 0.28, 82e9, 82e9, 0.7, 0.3, 0.8];
        cntc_setmaterialparameters(&ire, &icp, &3, &7, mat.as_ptr());
        cntc_setflags(&ire, &icp, &1, &flags::IC_BOUND, &2);
        let law = [0.2, 0.15, 2.0, 0.0, 0.0, 0.0, 0.0];
        cntc_setfrictionmethod(&ire, &icp, &2, &7, law.as_ptr());
        let hz = [40.0, 36.0, 0.5, 1.2, 1.15];
        cntc_sethertzcontact(&ire, &icp, &-1, &5, hz.as_ptr());
        cntc_setreferencevelocity(&ire, &icp, &20.0);
        cntc_setnormalforce(&ire, &icp, &60000.0);
    }
    let (ierror, f) = solve(ire, [0.002, 0.001, 0.4]);
    assert_eq!(ierror, 0);
    let contact = [
        60000.0,
        -10259.311279527898,
        -11990.899893883154,
        -4.531178692649356,
    ];
    for k in 0..4 {
        assert!(
            rel(f[k], contact[k]) < 1e-7,
            "{k}: {} vs {}",
            f[k],
            contact[k]
        );
    }
    let div = fields(ire, 40 * 36).division;
    assert_eq!((count(&div, 1), count(&div, 2)), (560, 296));
}

/// B = 0: the exact normal problem, then FASTSIM on its pressure.
/// CONTACT's library: examples/fastsim.inp's ellipse (option -3, AA, BB =
/// 8, 4 mm, 44 x 44 elements over 1.1 times it, FN = 82 kN, mu = 0.3,
/// CETA = -0.000625, CPHI = 0.000625 rad/mm): FY = -14799.30576547192 N,
/// MZ = -48203.41604714184 N mm; and a non-Hertzian grid (option 3, 30 x
/// 24 elements of 0.5 mm from (-7.25, -5.75) mm, the undeformed distance
/// 0.09 x^2 + 0.16 y^2 + 0.002 x per element, FN = 20 kN, creepages
/// 0.0006, 0.0003, 0.0002 rad/mm; the flexibilities of the contact's
/// equivalent ellipse): FX = -212.70289890123811 N, FY =
/// -130.55920688646583 N, MZ = 16.371387965045535 N mm. Ours agree to
/// 6e-8.
#[test]
fn normal_problem_pressure() {
    let icp = 1;
    let setup = |ire: i32| unsafe {
        let codes = [
            flags::IF_UNITS,
            flags::IC_TANG,
            flags::IC_NORM,
            flags::IC_PVTIME,
            flags::IC_BOUND,
        ];
        let values = [flags::UN_CNTC, 3, 1, 2, 0];
        let mat = [0.28, 0.28, 82000.0, 82000.0, 1.0, 1.0, 1.0];
        cntc_setmaterialparameters(&ire, &icp, &3, &7, mat.as_ptr());
        cntc_setflags(&ire, &icp, &5, codes.as_ptr(), values.as_ptr());
        cntc_setfrictionmethod(&ire, &icp, &0, &2, [0.3, 0.3].as_ptr());
        cntc_setreferencevelocity(&ire, &icp, &30000.0);
    };
    let ire = 304;
    setup(ire);
    unsafe {
        let hz = [44.0, 44.0, 8.0, 4.0, 1.1];
        cntc_sethertzcontact(&ire, &icp, &-3, &5, hz.as_ptr());
        cntc_setnormalforce(&ire, &icp, &82000.0);
    }
    let (ierror, f) = solve(ire, [0.0, -0.000625, 0.000625]);
    assert_eq!(ierror, 0);
    assert!(rel(f[2], -14799.30576547192) < 1e-7, "{}", f[2]);
    assert!(rel(f[3], -48203.41604714184) < 1e-7, "{}", f[3]);

    let ire = 305;
    setup(ire);
    let (mx, my, dx) = (30, 24, 0.5);
    let mut h = Vec::with_capacity(mx * my);
    for iy in 0..my {
        for ix in 0..mx {
            let (x, y) = (-7.25 + ix as f64 * dx, -5.75 + iy as f64 * dx);
            h.push(0.09 * x * x + 0.16 * y * y + 0.002 * x);
        }
    }
    unsafe {
        let pot = [mx as f64, my as f64, -7.25, -5.75, dx, dx];
        cntc_setpotcontact(&ire, &icp, &3, &6, pot.as_ptr());
        cntc_setundeformeddistc(&ire, &icp, &9, &(h.len() as i32), h.as_ptr());
        cntc_setnormalforce(&ire, &icp, &20000.0);
    }
    let (ierror, f) = solve(ire, [0.0006, 0.0003, 0.0002]);
    assert_eq!(ierror, 0);
    let contact = [
        20000.0,
        -212.70289890123811,
        -130.55920688646583,
        16.371387965045535,
    ];
    for k in 1..4 {
        assert!(
            rel(f[k], contact[k]) < 1e-7,
            "{k}: {} vs {}",
            f[k],
            contact[k]
        );
    }
}

/// What FASTSIM does not do here is refused with CNTC_err_notsupported:
/// transient rolling (T = 2), prescribed forces (F = 1), an extra rigid
/// slip (E = 9), the elliptic bound on a non-Hertzian grid.
#[test]
fn refusals() {
    let (ire, icp) = (306, 1);
    tractcurv_fastsim(ire, [1.0, 1.0, 1.0]);
    assert_eq!(solve(ire, [0.001, 0.0, 0.0]).0, 0);
    unsafe {
        cntc_setflags(&ire, &icp, &1, &flags::IC_TANG, &2);
        assert_eq!(solve(ire, [0.001, 0.0, 0.0]).0, err::NOT_SUPPORTED);
        cntc_setflags(&ire, &icp, &1, &flags::IC_TANG, &3);
        cntc_setflags(&ire, &icp, &1, &flags::IC_FORCE, &1);
        assert_eq!(solve(ire, [0.001, 0.0, 0.0]).0, err::NOT_SUPPORTED);
        cntc_setflags(&ire, &icp, &1, &flags::IC_FORCE, &0);
        let w = vec![1e-4; 48 * 44];
        cntc_setextrarigidslip(&ire, &icp, &(w.len() as i32), w.as_ptr(), w.as_ptr());
        assert_eq!(solve(ire, [0.001, 0.0, 0.0]).0, err::NOT_SUPPORTED);
        cntc_setextrarigidslip(&ire, &icp, &0, w.as_ptr(), w.as_ptr());
        assert_eq!(solve(ire, [0.001, 0.0, 0.0]).0, 0);
        let pot = [20.0, 20.0, -5.0, -5.0, 0.5, 0.5];
        cntc_setpotcontact(&ire, &icp, &3, &6, pot.as_ptr());
        let udist = [0.05, 0.0, 0.05, 0.0, 0.0, 0.0];
        cntc_setundeformeddistc(&ire, &icp, &1, &6, udist.as_ptr());
        assert_eq!(solve(ire, [0.001, 0.0, 0.0]).0, err::NOT_SUPPORTED);
        // B = 0 on that grid solves.
        cntc_setflags(&ire, &icp, &1, &flags::IC_BOUND, &0);
        let (ierror, f) = solve(ire, [0.001, 0.0, 0.0]);
        assert_eq!(ierror, 0);
        assert!(f[1] < 0.0 && f[1].is_finite());
    }
}
