//! FASTSIM (M = 3, and M = 2 with one given flexibility) through the C
//! calls, against CONTACT's own library.
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
    let [k0, alpha, beta] = k0_alpha_beta;
    let mat = [0.28, 0.28, 82000.0, 82000.0, k0, alpha, beta];
    tractcurv_with(ire, 3, &mat, 3);
}

/// [`tractcurv_fastsim`] with the M digit `m`, its parameters `mat` and the
/// B digit `bound`.
fn tractcurv_with(ire: i32, m: i32, mat: &[f64], bound: i32) {
    let icp = 1;
    steady_rolling(ire, flags::UN_CNTC, m, mat, bound);
    unsafe {
        let hz = [48.0, 44.0, 0.0008, 0.5, 1.1];
        cntc_sethertzcontact(&ire, &icp, &-2, &5, hz.as_ptr());
        cntc_setreferencevelocity(&ire, &icp, &10000.0);
        cntc_setnormalforce(&ire, &icp, &106700.0);
    }
}

/// Steady rolling of (ire, 1) in the unit convention `units` with a
/// prescribed normal force, P = 2, the M digit `m` with its parameters
/// `mat` and the B digit `bound`.
fn steady_rolling(ire: i32, units: i32, m: i32, mat: &[f64], bound: i32) {
    let icp = 1;
    unsafe {
        let codes = [
            flags::IF_UNITS,
            flags::IC_TANG,
            flags::IC_NORM,
            flags::IC_PVTIME,
        ];
        let values = [units, 3, 1, 2];
        cntc_setflags(&ire, &icp, &4, codes.as_ptr(), values.as_ptr());
        let n = mat.len() as i32;
        cntc_setmaterialparameters(&ire, &icp, &m, &n, mat.as_ptr());
        cntc_setflags(&ire, &icp, &1, &flags::IC_BOUND, &bound);
    }
}

/// The SI set-up of `combined_creepages_falling_friction_si` (its doc)
/// with the M digit `m` and its parameters `mat`, on (ire, 1).
fn si_ellipse(ire: i32, m: i32, mat: &[f64]) {
    let icp = 1;
    steady_rolling(ire, flags::UN_SI, m, mat, 2);
    unsafe {
        let law = [0.2, 0.15, 2.0, 0.0, 0.0, 0.0, 0.0];
        cntc_setfrictionmethod(&ire, &icp, &2, &7, law.as_ptr());
        let hz = [40.0, 36.0, 0.5, 1.2, 1.15];
        cntc_sethertzcontact(&ire, &icp, &-1, &5, hz.as_ptr());
        cntc_setreferencevelocity(&ire, &icp, &20.0);
        cntc_setnormalforce(&ire, &icp, &60000.0);
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
    let ire = 303;
    si_ellipse(ire, 3, &[0.28, 0.28, 82e9, 82e9, 0.7, 0.3, 0.8]);
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

/// What FASTSIM (M = 3, and M = 2 and FaStrip's M = 5 alike) does not do
/// here is refused with
/// CNTC_err_notsupported: transient rolling (T = 2), prescribed forces (F
/// = 1), an extra rigid slip (E = 9), the elliptic bound on a non-Hertzian
/// grid.
#[test]
fn refusals() {
    refusals_of(306, 3, &[0.28, 0.28, 82000.0, 82000.0, 1.0, 1.0, 1.0]);
    refusals_of(307, 2, &[0.28, 0.28, 82000.0, 82000.0, 5e-5, 1.0, 1.0, 1.0]);
    refusals_of(308, 5, &[0.28, 0.28, 82000.0, 82000.0, 1.0, 1.0, 1.0]);
}

/// [`refusals`] of the M digit `m` with its parameters `mat`.
fn refusals_of(ire: i32, m: i32, mat: &[f64]) {
    let icp = 1;
    tractcurv_with(ire, m, mat, 3);
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

/// One M = 2 case: the creepages CKSI, CETA, CPHI and CONTACT's FX, FY,
/// MZ and adhesion area there.
type GivenCase = ([f64; 3], [f64; 3], f64);

/// Solves `cases` on (ire, 1) and compares with CONTACT's: FX and FY
/// within `tol` FN [N], MZ within `tol` FN [N length-unit], the adhesion
/// area within 1e-6 of the contact area `carea` (the same elements).
fn compare_given(ire: i32, fn_n: f64, carea: f64, tol: f64, cases: &[GivenCase]) {
    for (creep, contact, harea) in cases {
        let (ierror, f) = solve(ire, *creep);
        assert_eq!(ierror, 0, "{creep:?}");
        assert_eq!(f[0], fn_n);
        for k in 0..3 {
            let d = (f[k + 1] - contact[k]).abs();
            assert!(
                d <= tol * fn_n,
                "ire {ire} {creep:?} [FX, FY, MZ][{k}]: {} vs CONTACT's {}",
                f[k + 1],
                contact[k]
            );
        }
        let (mut ca, mut ha, mut sa) = (0.0, 0.0, 0.0);
        unsafe { cntc_getcontactpatchareas(&ire, &1, &mut ca, &mut ha, &mut sa) };
        assert!(
            (ca - carea).abs() <= 1e-6 * carea && (ha - harea).abs() <= 1e-6 * carea,
            "ire {ire} {creep:?}: areas {ca}, {ha} vs CONTACT's {carea}, {harea}"
        );
    }
}

/// `cntc_getparameters` task 2's FLX(1:3) (values 8-10) and K0_MF, ALFAMF,
/// BETAMF (11-13) of (ire, 1).
fn flx_and_reduction(ire: i32) -> [f64; 6] {
    let v = material_parameters(ire);
    [v[7], v[8], v[9], v[10], v[11], v[12]]
}

/// `cntc_getparameters` task 2 of (ire, 1), 30 values.
fn material_parameters(ire: i32) -> [f64; 30] {
    let mut v = [0.0; 30];
    unsafe { cntc_getparameters(&ire, &1, &2, &30, v.as_mut_ptr()) };
    v
}

/// One case of FLX(1:3) and K_EFF after a calculation: the creepages CKSI,
/// CETA, CPHI and CONTACT's FLX(1:3) (None: FLX, M = 2) and K_EFF.
type AppliedCase<'a> = ([f64; 3], Option<&'a [f64; 3]>, f64);

/// Solves each case on (ire, 1) and compares `cntc_getparameters` task
/// 2's FLX(1:3) (values 8-10) and K_EFF (value 14) with CONTACT's within
/// `tol` relative; `given` is M = 2's FLX.
fn compare_applied(ire: i32, given: f64, tol: f64, cases: &[AppliedCase]) {
    for (creep, flx, k_eff) in cases {
        assert_eq!(solve(ire, *creep).0, 0, "{creep:?}");
        let v = material_parameters(ire);
        let flx = flx.copied().unwrap_or([given; 3]);
        for i in 0..3 {
            assert!(
                rel(v[7 + i], flx[i]) <= tol,
                "ire {ire} {creep:?} FLX({}): {} vs CONTACT's {}",
                i + 1,
                v[7 + i],
                flx[i]
            );
        }
        assert!(
            rel(v[13], *k_eff) <= tol,
            "ire {ire} {creep:?} K_EFF: {} vs CONTACT's {k_eff}",
            v[13]
        );
    }
}

/// CONTACT's tractcurv set-up's contact area [mm²] (Hertzian option -2,
/// 48 x 44 elements).
const TRACTCURV_CAREA: f64 = 250.59753304515812;

// M = 2 (modified FASTSIM with one given flexibility FLX, CONTACT's units
// mm³/N): CONTACT's library (contact_addon_linux64.so, as above) driven
// through its python_intfc by crates/cntc/bench/given_flexibility_cases.py
// (tractcurv's ellipse as in this module's doc, Coulomb mu = 0.33) with
// cntc_setmaterialparameters(ire, 1, 2, [0.28, 0.28, 82000, 82000, FLX,
// K0_MF, ALFAMF, BETAMF]) per set-up below; cntc_getcontactforces' FX, FY, MZ and
// cntc_getcontactpatchareas' adhesion area per creepages CKSI, CETA, CPHI
// [rad/mm] (the contact area 250.59753304515812 mm² throughout).

/// FLX = 5e-5, no slope reduction (k0 = alpha = beta = 1), B = 3.
#[rustfmt::skip]
const GIVEN_B3: [GivenCase; 8] = [
    ([1e-05, 0.0, 0.0], [-275.461027740807, 0.0, 0.0], 249.86905184444547),
    ([0.0008, 0.0, 0.0], [-17622.247962267575, 0.0, 0.0], 190.86207458671927),
    ([0.0016, 0.0, 0.0], [-27865.342970050853, 0.0, 0.0], 133.3120597304184),
    ([0.0048, 0.0, 0.0], [-35213.807804809905, 0.0, 0.0], 0.0),
    ([0.0, 0.001, 0.0], [0.0, -20791.89491022598, 20301.076397685996], 176.2924505724659),
    ([0.0005, 0.0008, 0.0003], [-5679.816262150964, -23247.134466435276, -104056.06185615178], 86.32502228445128),
    ([0.0, 0.0, 0.0004], [0.0, -14237.359687098346, -136249.11890060114], 97.98072149585397),
    ([0.002, -0.001, -0.0006], [-12596.02022068342, 21096.77639147867, 120299.33358490102], 0.0),
];

/// FLX = 5e-5, k0 = 0.54, alpha = 0.02, beta = 0.62, B = 3.
#[rustfmt::skip]
const GIVEN_B3_REDUCED: [GivenCase; 8] = [
    ([1e-05, 0.0, 0.0], [-148.7106668234971, 0.0, 0.0], 250.59753304515812),
    ([0.0008, 0.0, 0.0], [-9382.77157140722, 0.0, 0.0], 222.18676621736404),
    ([0.0016, 0.0, 0.0], [-15367.402306383996, 0.0, 0.0], 199.96808959562765),
    ([0.0048, 0.0, 0.0], [-25939.66224580148, 0.0, 0.0], 146.7889619436028),
    ([0.0, 0.001, 0.0], [0.0, -11122.854958329266, 15544.13124030852], 215.63043541095),
    ([0.0005, 0.0008, 0.0003], [-3572.991786206801, -11818.27461676449, -59855.2286290296], 188.67663098458127),
    ([0.0, 0.0, 0.0004], [0.0, -7058.11959784141, -87412.54692566633], 181.7560595778109),
    ([0.002, -0.001, -0.0006], [-9275.330580377875, 13352.30007089904, 79589.5828481613], 159.5373829560745),
];

/// FLX = 1.2e-4, no slope reduction, B = 2.
#[rustfmt::skip]
const GIVEN_B2: [GivenCase; 8] = [
    ([1e-05, 0.0, 0.0], [-114.9511816572132, 0.0, 0.0], 250.59753304515812),
    ([0.0008, 0.0, 0.0], [-8943.558783725315, 0.0, 0.0], 240.7630368355371),
    ([0.0016, 0.0, 0.0], [-16637.516031607924, 0.0, 0.0], 215.63043541095),
    ([0.0048, 0.0, 0.0], [-31258.231944051488, 0.0, 0.0], 97.98072149585397),
    ([0.0, 0.001, 0.0], [0.0, -11018.616913053951, 18264.60297807461], 234.5709466294794),
    ([0.0005, 0.0008, 0.0003], [-4236.907524749489, -14214.825101316472, -75818.78994975265], 196.14356329188612),
    ([0.0, 0.0, 0.0004], [0.0, -8098.17385176071, -109398.53254128103], 187.9481497838686),
    ([0.002, -0.001, -0.0006], [-10863.427354361427, 17944.065760318408, 109771.5440998392], 122.02060111937206),
];

/// FLX = 1.2e-4, k0 = 0.7, alpha = 0.3, beta = 0.8, B = 2.
#[rustfmt::skip]
const GIVEN_B2_REDUCED: [GivenCase; 8] = [
    ([1e-05, 0.0, 0.0], [-80.29434353983756, 0.0, 0.0], 250.59753304515812),
    ([0.0008, 0.0, 0.0], [-5492.336080550037, 0.0, 0.0], 246.95512704159478),
    ([0.0016, 0.0, 0.0], [-9607.427155785475, 0.0, 0.0], 239.30607443411176),
    ([0.0048, 0.0, 0.0], [-19521.687521941672, 0.0, 0.0], 200.6965707963403),
    ([0.0, 0.001, 0.0], [0.0, -6624.879317558846, 11617.149986268085], 244.76968343945677),
    ([0.0005, 0.0008, 0.0003], [-2512.941336246022, -7273.672124646667, -42223.572180204166], 234.75306692965756),
    ([0.0, 0.0, 0.0004], [0.0, -4134.786154584146, -65343.850935439965], 229.1073376241344),
    ([0.002, -0.001, -0.0006], [-7414.6110406893495, 9185.504629349107, 66570.47117774143], 213.08075120845567),
];

/// M = 2 on tractcurv's ellipse: the one flexibility for all three
/// creepages (the spin's rigid slip unscaled, no blending), with and
/// without the slope reduction, the parabolic and the elliptic bound.
/// Measured: FX, FY within 2.1e-9 FN, MZ within 6.5e-9 FN mm, the same
/// adhesion elements. Tolerance 2e-8 FN (N; N mm).
#[test]
fn given_flexibility_on_tractcurv_matches_contact() {
    let mat = |flx: f64, [k0, alpha, beta]: [f64; 3]| {
        [0.28, 0.28, 82000.0, 82000.0, flx, k0, alpha, beta]
    };
    for (ire, flx, reduction, bound, cases) in [
        (311, 5e-5, [1.0; 3], 3, &GIVEN_B3),
        (312, 5e-5, [0.54, 0.02, 0.62], 3, &GIVEN_B3_REDUCED),
        (313, 1.2e-4, [1.0; 3], 2, &GIVEN_B2),
        (314, 1.2e-4, [0.7, 0.3, 0.8], 2, &GIVEN_B2_REDUCED),
    ] {
        tractcurv_with(ire, 2, &mat(flx, reduction), bound);
        unsafe { cntc_setfrictionmethod(&ire, &1, &0, &2, [0.33, 0.33].as_ptr()) };
        compare_given(ire, 106700.0, TRACTCURV_CAREA, 2e-8, cases);
        // CONTACT returns FLX in FLX(1:3) and the slope reduction (FLX
        // to rounding: converted to SI and back).
        let p = flx_and_reduction(ire);
        assert!(p[..3].iter().all(|v| rel(*v, flx) < 1e-15), "{p:?}");
        assert_eq!(p[3..], reduction);
    }
}

/// M = 2 with B = 0 (the exact normal problem's pressure as the bound) on
/// examples/fastsim.inp's ellipse (option -3, AA, BB = 8, 4 mm, 44 x 44
/// elements over 1.1 times it, FN = 82 kN), FLX = 8e-5 mm³/N, k0 = 0.54,
/// alpha = 0.02, beta = 0.62, and tractcurv's curve 4 exponential falling
/// friction at V = 10 m/s. CONTACT's library
/// (crates/cntc/bench/given_flexibility_cases.py, as above): FX, FY [N],
/// MZ [N mm], the adhesion area [mm²] (the contact area 102.08 mm²). Measured: forces within 4.6e-8 FN, MZ within 1.4e-7 FN
/// mm (the normal problem's pressure, solved to its tolerance, as with M
/// = 3). Tolerance 1e-7 FN (N) and 1e-7 FN a (N mm, a = 8 mm).
#[test]
fn given_flexibility_with_the_normal_problem_matches_contact() {
    let ire = 315;
    let mat = [0.28, 0.28, 82000.0, 82000.0, 8e-5, 0.54, 0.02, 0.62];
    tractcurv_with(ire, 2, &mat, 0);
    let law = [0.1368, 0.2232, 990.0, 0.0, 0.0, 0.003, 1.0];
    unsafe {
        cntc_setfrictionmethod(&ire, &1, &4, &7, law.as_ptr());
        let hz = [44.0, 44.0, 8.0, 4.0, 1.1];
        cntc_sethertzcontact(&ire, &1, &-3, &5, hz.as_ptr());
        cntc_setnormalforce(&ire, &1, &82000.0);
    }
    #[rustfmt::skip]
    let cases: [GivenCase; 2] = [
        ([0.0, -0.000625, 0.000625], [0.0, -2731.747188427035, -11230.183233677173], 100.16000000000003),
        ([0.003, 0.0005, -0.0002], [-9834.125994776541, 0.27716973296054714, 5540.211690006373], 93.76000000000002),
    ];
    for (creep, contact, harea) in cases {
        let (ierror, f) = solve(ire, creep);
        assert_eq!(ierror, 0);
        let tol = [1e-7 * 82000.0, 1e-7 * 82000.0, 1e-7 * 82000.0 * 8.0];
        for k in 0..3 {
            let d = (f[k + 1] - contact[k]).abs();
            assert!(d <= tol[k], "{creep:?} {k}: {} vs {}", f[k + 1], contact[k]);
        }
        let (mut ca, mut ha, mut sa) = (0.0, 0.0, 0.0);
        unsafe { cntc_getcontactpatchareas(&ire, &1, &mut ca, &mut ha, &mut sa) };
        assert!(
            (ca - 102.08).abs() < 1e-9 && (ha - harea).abs() < 1e-9,
            "{ca} {ha}"
        );
    }
}

/// M = 2 in SI units: FLX = 6e-14 m³/N (6e-5 mm³/N) converted once,
/// CONTACT's library (crates/cntc/bench/given_flexibility_cases.py) on
/// the set-up of `combined_creepages_falling_friction_si` (B = 2, linear falling
/// friction) with k0 = 0.7, alpha = 0.3, beta = 0.8: FX, FY [N], MZ [N m],
/// the adhesion area [m²] (contact area 1.2385898948982465e-4 m²).
/// Measured: forces within 1.1e-9 FN. Tolerance 2e-8 FN.
#[test]
fn given_flexibility_in_si_units_matches_contact() {
    let ire = 316;
    si_ellipse(ire, 2, &[0.28, 0.28, 82e9, 82e9, 6e-14, 0.7, 0.3, 0.8]);
    #[rustfmt::skip]
    let cases: [GivenCase; 2] = [
        ([0.002, 0.001, 0.4], [-9799.240736093514, -10682.701558210045, -1.3584234424296537], 8.971095033141505e-05),
        ([0.0003, 0.0, 0.0], [-2964.608160122917, 0.0, 0.0], 0.00012241203867802765),
    ];
    compare_given(ire, 60000.0, 1.2385898948982465e-4, 2e-8, &cases);
    let p = flx_and_reduction(ire);
    assert!(p[..3].iter().all(|v| rel(*v, 6e-14) < 1e-15), "{p:?}");
    // K_EFF, unitless, CONTACT's after each case ("si" in the script):
    // measured within 1.2e-8 relative. Tolerance 1e-7.
    compare_applied(
        ire,
        6e-14,
        1e-7,
        &[
            (cases[0].0, None, 0.39940600187440484),
            (cases[1].0, None, 0.6553469055626079),
        ],
    );
}

/// A flexibility FLX that is not finite and > 0 is refused by
/// `cntc_setmaterialparameters` naming FLX (the error the log prints);
/// the material stays as it was (M = 3 here, which then solves).
#[test]
fn a_bad_flexibility_is_refused_naming_it() {
    use contact_addon::call::Call;
    use contact_addon::library::{lock, Library};
    let (ire, icp) = (317, 1);
    tractcurv_fastsim(ire, [1.0, 1.0, 1.0]);
    unsafe { cntc_setfrictionmethod(&ire, &icp, &0, &2, [0.33, 0.33].as_ptr()) };
    for flx in [0.0, -5e-5, f64::NAN, f64::INFINITY, 1e-320] {
        let params = vec![0.28, 0.28, 82000.0, 82000.0, flx, 1.0, 1.0, 1.0];
        unsafe { cntc_setmaterialparameters(&ire, &icp, &2, &8, params.as_ptr()) };
        let entry = Library::get().element(ire, icp).unwrap();
        let e = lock(&entry)
            .apply(icp, Call::SetMaterial { mdigit: 2, params })
            .unwrap_err()
            .to_string();
        assert!(e.contains("FLX") && e.contains("M = 2"), "{flx}: {e}");
        let mut m = -1;
        unsafe { cntc_getflags(&ire, &icp, &1, &flags::IC_MATER, &mut m) };
        assert_eq!(m, 3, "{flx}");
    }
    // Kalker's FASTSIM (M = 3) as before: python_tractcurv.py curve 3.
    let (ierror, f) = solve(ire, [0.0016, 0.0, 0.0]);
    assert_eq!(ierror, 0);
    assert!(rel(f[1], -26480.725658521496) < 1e-7, "{}", f[1]);
}

// FLX(1:3) [mm³/N] and K_EFF (cntc_getparameters task 2, values 8-10 and
// 14) that CONTACT's library (as above) returned after each calculation
// on tractcurv's ellipse (Coulomb mu = 0.33), driven through its
// python_intfc by crates/cntc/bench/given_flexibility_cases.py (cases
// "m3-b3", "m3-b3-red", "m3-b2-red", "b3-red", "b2-red"), at the eight
// creepages of GIVEN_B3. FLX with M = 3: Kalker's L1, L2, L3 of the
// ellipse, blended; they do not depend on the B digit nor the slope
// reduction.
#[rustfmt::skip]
const TRACTCURV_FLX: [[f64; 3]; 8] = [
    [5.490687659613463e-05, 6.773423911242006e-05, 4.526289362023008e-05],
    [5.490687659613462e-05, 6.626259293543156e-05, 4.636931987577665e-05],
    [5.490687659613463e-05, 6.477231832582295e-05, 4.7489751526963056e-05],
    [5.490687659613463e-05, 5.8811219887388506e-05, 5.197147813170866e-05],
    [5.6769719858145394e-05, 6.775286754504017e-05, 4.8512271050584015e-05],
    [5.526853323767755e-05, 6.635712136800426e-05, 4.693181124826461e-05],
    [5.4906876595812694e-05, 6.775286754429004e-05, 4.524888822459025e-05],
    [5.469475971267245e-05, 6.337530649629447e-05, 4.816847301137198e-05],
];

/// K_EFF with k0 = 0.54, alpha = 0.02, beta = 0.62 (the same with M = 2
/// and M = 3, B = 3: the contact elements' equivalent ellipse).
const TRACTCURV_K_EFF_054: [f64; 8] = [
    0.5390355884108974,
    0.4725568160144368,
    0.42036087925535187,
    0.2928374157658582,
    0.4582990858645254,
    0.363183535356501,
    0.37249236173894273,
    0.2821548175134931,
];

/// K_EFF with k0 = 0.7, alpha = 0.3, beta = 0.8 (M = 2 and M = 3, B = 2).
const TRACTCURV_K_EFF_07: [f64; 8] = [
    0.698508204807125,
    0.6037950210663446,
    0.539167385567954,
    0.4087174184534456,
    0.585370281269482,
    0.47640781144522876,
    0.48611291082735253,
    0.3992354729972366,
];

/// `cntc_getparameters` task 2 with M = 2 and M = 3 on tractcurv's
/// ellipse: FLX(1:3) the flexibilities the modified FASTSIM used (M = 3
/// Kalker's of the ellipse, blended; M = 2 FLX) and K_EFF its slope
/// reduction factor, after each calculation; before the first, CONTACT's
/// initial values (M = 3: 1e-5, 1e-5, 0 mm³/N; M = 2: FLX) and K_EFF 0.
/// Measured against CONTACT's library: FLX within 3.6e-8 relative, K_EFF
/// within 1.7e-8. CONTACT's Kalker table (`linrol`) holds its numbers as
/// single-precision constants: at a/b = 0.5, nu = 0.28 its C11 is 3.57e-8
/// above the table's decimals (C22 3.2e-9), ours L1 3.51e-8 below and L2
/// 2.8e-9 below CONTACT's; K_EFF's epsilon takes the same C11. Tolerance
/// 1e-7 relative.
#[test]
fn flexibilities_and_k_eff_match_contact() {
    let k1 = [1.0; 8];
    let mat3 = |[k0, alpha, beta]: [f64; 3]| vec![0.28, 0.28, 82000.0, 82000.0, k0, alpha, beta];
    let mat2 = |flx: f64, [k0, alpha, beta]: [f64; 3]| {
        vec![0.28, 0.28, 82000.0, 82000.0, flx, k0, alpha, beta]
    };
    for (ire, m, mat, bound, given, k_eff) in [
        (318, 3, mat3([1.0; 3]), 3, 0.0, &k1),
        (
            319,
            3,
            mat3([0.54, 0.02, 0.62]),
            3,
            0.0,
            &TRACTCURV_K_EFF_054,
        ),
        (320, 3, mat3([0.7, 0.3, 0.8]), 2, 0.0, &TRACTCURV_K_EFF_07),
        (
            321,
            2,
            mat2(5e-5, [0.54, 0.02, 0.62]),
            3,
            5e-5,
            &TRACTCURV_K_EFF_054,
        ),
        (
            322,
            2,
            mat2(1.2e-4, [0.7, 0.3, 0.8]),
            2,
            1.2e-4,
            &TRACTCURV_K_EFF_07,
        ),
    ] {
        tractcurv_with(ire, m, &mat, bound);
        unsafe { cntc_setfrictionmethod(&ire, &1, &0, &2, [0.33, 0.33].as_ptr()) };
        let before = material_parameters(ire);
        let initial = if m == 3 {
            [1e-5, 1e-5, 0.0]
        } else {
            [given; 3]
        };
        for i in 0..3 {
            let d = (before[7 + i] - initial[i]).abs();
            assert!(d <= 1e-15 * initial[i], "ire {ire}: {before:?}");
        }
        assert_eq!(before[13], 0.0, "ire {ire}: K_EFF before a calculation");
        let cases: Vec<AppliedCase> = (0..8)
            .map(|i| {
                let flx = (m == 3).then_some(&TRACTCURV_FLX[i]);
                (GIVEN_B3[i].0, flx, k_eff[i])
            })
            .collect();
        compare_applied(ire, given, 1e-7, &cases);
    }
}

/// `examples/fastsim.inp`'s patch on (ire, 1) with M = 5 (modified
/// FaStrip): Hertzian option -3 (AA, BB = 8, 4 mm, 44 x 44 elements over
/// 1.1 times the ellipse), FN = 82 kN, G = 82000 N/mm^2, nu = 0.28,
/// VELOC 30 m/s, steady rolling with CHI `chi` (DQ 0.4 mm), the B digit
/// `bound`, the slope reduction `red`, the friction method `imeth` with
/// `law`; CONTACT's units.
fn fastsim_inp_fastrip(ire: i32, bound: i32, red: [f64; 3], chi: f64, imeth: i32, law: &[f64]) {
    let icp = 1;
    let mat = [0.28, 0.28, 82000.0, 82000.0, red[0], red[1], red[2]];
    steady_rolling(ire, flags::UN_CNTC, 5, &mat, bound);
    unsafe {
        let hz = [44.0, 44.0, 8.0, 4.0, 1.1];
        cntc_sethertzcontact(&ire, &icp, &-3, &5, hz.as_ptr());
        cntc_setreferencevelocity(&ire, &icp, &30000.0);
        cntc_setrollingstepsize(&ire, &icp, &chi, &0.4);
        cntc_setnormalforce(&ire, &icp, &82000.0);
        cntc_setfrictionmethod(&ire, &icp, &imeth, &(law.len() as i32), law.as_ptr());
    }
}

/// One M = 5 case: name, creepages, slope reduction, B digit, CHI, the
/// friction method (L = 0 or 4), CONTACT's FX, FY, MZ [N, N mm], adhesion
/// and slip element counts and K_EFF.
type FastripCase = (
    &'static str,
    [f64; 3],
    [f64; 3],
    i32,
    f64,
    i32,
    [f64; 3],
    [usize; 2],
    f64,
);

/// M = 5 (modified FaStrip) against CONTACT's library
/// (`crates/cntc/bench/fastrip_cases.py`, the same calls through CONTACT's
/// `python_intfc`; its cases of these names): longitudinal, lateral and
/// spin creepage alone and combined, from nearly linear to full sliding;
/// the slope reduction (0.54, 0.02, 0.62) and (0.7, 0.3, 0.8); the
/// parabolic bound (B = 3) and the normal problem's pressure (B = 0);
/// rolling along -x (CHI = 180 degrees: CONTACT's strip part keeps its
/// adhesion zone at +x, `case3-back` slides everywhere); exponential
/// falling friction (L = 4, python_tractcurv.py's law). The first case is
/// `fastsim.inp` case 4 (`fastsim.ref_out`: FY -1.583E+04, MZ -4.816E+04,
/// NADH 626, NSLIP 638). FX, FY, MZ/(8 mm) within 1e-7 mu FN of
/// CONTACT's (the scheme and grid are CONTACT's; measured: within 3e-8,
/// B = 0 too), the element counts equal, K_EFF within 1e-7 relative as
/// M = 3's (the same code; measured 7e-9).
#[test]
fn fastrip_against_contacts_library() {
    const PLAIN: [f64; 3] = [1.0, 1.0, 1.0];
    const RED1: [f64; 3] = [0.54, 0.02, 0.62];
    const RED2: [f64; 3] = [0.7, 0.3, 0.8];
    const PI: f64 = std::f64::consts::PI;
    #[rustfmt::skip]
    let cases: [FastripCase; 21] = [
        ("case4", [0.0, -0.000625, 0.000625], PLAIN, 2, 0.0, 0, [0.0, -15829.428007966377, -48164.809410048954], [626, 638], 1.0),
        ("xi-tiny", [1e-06, 0.0, 0.0], PLAIN, 2, 0.0, 0, [-12.823028835713535, 0.0, 0.0], [1264, 0], 1.0),
        ("xi", [0.001, 0.0, 0.0], PLAIN, 2, 0.0, 0, [-11705.693492681163, 0.0, 0.0], [868, 396], 1.0),
        ("xi-full", [0.05, 0.0, 0.0], PLAIN, 2, 0.0, 0, [-24618.611900975364, 0.0, 0.0], [0, 1264], 1.0),
        ("eta", [0.0, 0.0005, 0.0], PLAIN, 2, 0.0, 0, [0.0, -6115.537999901721, 16904.585091430974], [1064, 200], 1.0),
        ("eta-neg", [0.0, -0.002, 0.0], PLAIN, 2, 0.0, 0, [0.0, 18801.797072589634, -20937.014734274886], [568, 696], 1.0),
        ("phi", [0.0, 0.0, 0.0003], PLAIN, 2, 0.0, 0, [0.0, -12000.949945675542, -16632.104390835277], [972, 292], 1.0),
        ("phi-neg", [0.0, 0.0, -0.001], PLAIN, 2, 0.0, 0, [0.0, 15186.767113221182, 57487.77397066643], [0, 1264], 1.0),
        ("phi-large", [0.0, 0.0, 0.004], PLAIN, 2, 0.0, 0, [0.0, -6634.218360787594, -82973.9188524254], [0, 1264], 1.0),
        ("mixed", [0.0005, 0.0008, 0.0003], PLAIN, 2, 0.0, 0, [-4882.738873060012, -18955.583570236784, -6128.07901622222], [589, 675], 1.0),
        ("mixed2", [0.002, -0.001, -0.0006], PLAIN, 2, 0.0, 0, [-13042.781885049764, 17764.07643034795, 29170.180350575967], [0, 1264], 1.0),
        ("case4-red1", [0.0, -0.000625, 0.000625], RED1, 2, 0.0, 0, [0.0, -16711.962661680493, -44330.5667472003], [626, 638], 0.3326120387336499),
        ("phi-red1", [0.0, 0.0, 0.0003], RED1, 2, 0.0, 0, [0.0, -12025.74391964172, -16502.993774715604], [972, 292], 0.4018229866429141),
        ("mixed2-red1", [0.002, -0.001, -0.0006], RED1, 2, 0.0, 0, [-11563.556540950365, 20155.049658330732, 18618.683328680523], [0, 1264], 0.28893903209562893),
        ("mixed-red2", [0.0005, 0.0008, 0.0003], RED2, 2, 0.0, 0, [-4714.580405714607, -19141.494048473847, -4907.527521534329], [589, 675], 0.48267255301729495),
        ("phi-large-red2", [0.0, 0.0, 0.004], RED2, 2, 0.0, 0, [0.0, -14756.472029000819, -59251.265903548745], [0, 1264], 0.2651746997419732),
        ("case4-b3", [0.0, -0.000625, 0.000625], PLAIN, 3, 0.0, 0, [0.0, -15830.284405383525, -40206.61189089336], [626, 638], 1.0),
        ("mixed-b0", [0.0005, 0.0008, 0.0003], PLAIN, 0, 0.0, 0, [-4899.000686558353, -19075.661660375237, -6484.864478151935], [575, 701], 1.0),
        ("case3-back", [0.0, -0.000625, -0.000625], PLAIN, 2, PI, 0, [0.0, -16327.337767153876, 51138.971932769666], [0, 1264], 1.0),
        ("mixed-back", [-0.0005, 0.0008, -0.0003], PLAIN, 2, PI, 0, [3906.1700508422396, 895.4524693361723, 41332.31587610504], [918, 346], 1.0),
        ("mixed-l4", [0.0005, 0.0008, 0.0003], RED1, 2, 0.0, 4, [-5045.638321899365, -20034.871571298965, -871.8312960625844], [750, 514], 0.38826606647031214),
    ];
    let ire = 340;
    let limit = 1e-7 * 0.3 * 82000.0;
    for (name, creep, red, bound, chi, l, f_ref, [nadh, nslip], keff) in cases {
        let law: &[f64] = if l == 4 {
            &[0.1368, 0.2232, 990.0, 0.0, 0.0, 0.003, 1.0]
        } else {
            &[0.3, 0.3]
        };
        fastsim_inp_fastrip(ire, bound, red, chi, l, law);
        let (ierror, f) = solve(ire, creep);
        assert_eq!(ierror, 0, "{name}");
        assert!(rel(f[0], 82000.0) < 1e-12, "{name}: FN {}", f[0]);
        for (k, (ours, theirs)) in [f[1], f[2], f[3] / 8.0]
            .iter()
            .zip([f_ref[0], f_ref[1], f_ref[2] / 8.0])
            .enumerate()
        {
            assert!(
                (ours - theirs).abs() < limit,
                "{name} [{k}]: {ours} vs {theirs}"
            );
        }
        let fl = fields(ire, 44 * 44);
        assert_eq!(
            (count(&fl.division, 1), count(&fl.division, 2)),
            (nadh, nslip),
            "{name}"
        );
        assert!(rel(material_parameters(ire)[13], keff) < 1e-7, "{name}");
    }
    unsafe { cntc_finalize(&ire) };
}

/// M = 5's analytic limits through the C calls: full sliding gives mu
/// times the grid's pressure sum (CONTACT's pressure is not normalised:
/// `xi-full`'s FX -24618.611900975364 N is 0.3 times it, 0.08 % above
/// 0.3 FN); with one creepage the slope reduction changes nothing (module
/// docs of `core::fastrip`; CONTACT's library alike, `xi-red1`); in SI
/// units (CNTC_un_spck: forces on body 2) the same numbers turned
/// (CONTACT's `mixed-si`: FX 4714.580405714607 N). The slip is zero in
/// adhesion and the tractions within the bound.
#[test]
fn fastrip_limits_and_units() {
    let ire = 341;
    fastsim_inp_fastrip(ire, 2, [1.0, 1.0, 1.0], 0.0, 0, &[0.3, 0.3]);
    let (_, f) = solve(ire, [0.05, 0.0, 0.0]);
    let fl = fields(ire, 44 * 44);
    let sum_pn: f64 = fl.pn.iter().sum::<f64>() * 0.4 * 0.2;
    assert!(rel(f[1], -0.3 * sum_pn) < 1e-12, "{} vs {}", f[1], sum_pn);
    assert!(rel(sum_pn, 82000.0) < 1e-3 && rel(sum_pn, 82000.0) > 1e-4);
    let (_, plain) = solve(ire, [0.001, 0.0, 0.0]);
    fastsim_inp_fastrip(ire, 2, [0.54, 0.02, 0.62], 0.0, 0, &[0.3, 0.3]);
    let (_, reduced) = solve(ire, [0.001, 0.0, 0.0]);
    assert!(rel(reduced[1], plain[1]) < 1e-14);
    let fl = fields(ire, 44 * 44);
    for i in 0..44 * 44 {
        assert!(fl.px[i].abs() <= 0.3 * fl.pn[i] * (1.0 + 1e-12));
        if fl.division[i] == 1 {
            assert_eq!(fl.sx[i], 0.0);
        }
    }
    // SI, CONTACT's Simpack convention.
    let icp = 1;
    let mat = [0.28, 0.28, 82e9, 82e9, 0.7, 0.3, 0.8];
    steady_rolling(ire, flags::UN_SPCK, 5, &mat, 2);
    unsafe {
        let hz = [44.0, 44.0, 8e-3, 4e-3, 1.1];
        cntc_sethertzcontact(&ire, &icp, &-3, &5, hz.as_ptr());
        cntc_setreferencevelocity(&ire, &icp, &30.0);
        cntc_setrollingstepsize(&ire, &icp, &0.0, &0.4e-3);
        cntc_setnormalforce(&ire, &icp, &82000.0);
        cntc_setfrictionmethod(&ire, &icp, &0, &2, [0.3, 0.3].as_ptr());
    }
    let (ierror, f) = solve(ire, [0.0005, 0.0008, 0.3]);
    assert_eq!(ierror, 0);
    let limit = 1e-7 * 0.3 * 82000.0;
    assert!((f[1] - 4714.580405714607).abs() < limit, "{}", f[1]);
    assert!((f[2] - 19141.494048473847).abs() < limit, "{}", f[2]);
    assert!(
        (f[3] * 1e3 - 4907.527521534329).abs() / 8.0 < limit,
        "{}",
        f[3]
    );
    unsafe { cntc_finalize(&ire) };
}
