//! The interfacial (third-body) layer, M = 4 of `cntc_setmaterialparameters`
//! (`[nu1, nu2, g1, g2, g3, laythk, tau_c0, k_tau]`), through the C calls
//! against CONTACT's own library.
//!
//! CONTACT's numbers come from its shared library (`contact_addon_linux64.so`
//! of CONTACT revision 2707, 2025-07-23, built with gfortran 12 `-O2`),
//! driven from Python (`examples/python_intfc`, numpy) through the same
//! `cntc_*` calls as below on result elements of their own, reading back
//! `cntc_getcontactforces`, `cntc_getelementdivision`,
//! `cntc_getcontactpatchareas`, `cntc_getfielddata` (TAUCRT, UPLSX, UPLSY,
//! PX) and `cntc_getparameters`; the doubles as the library returned them.
//!
//! Each test uses its own result elements (the library is one per process).

use contact_addon::ffi::*;
use contact_addon::flags::{self, field};

fn rel(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

fn count(v: &[i32], code: i32) -> usize {
    v.iter().filter(|&&d| d == code).count()
}

/// Sets module 3 flags of (ire, 1): CONTACT's units, N = 1 (the normal
/// force), T = `tang`, P = `pvtime`.
fn flags3(ire: i32, tang: i32, pvtime: i32) {
    let codes = [
        flags::IF_UNITS,
        flags::IC_NORM,
        flags::IC_TANG,
        flags::IC_PVTIME,
    ];
    let values = [flags::UN_CNTC, 1, tang, pvtime];
    unsafe { cntc_setflags(&ire, &1, &4, codes.as_ptr(), values.as_ptr()) };
}

/// Sets the creepages (or a shift), solves: ierror and FN, FX, FY, MZ.
fn solve(ire: i32, cksi: f64) -> (i32, [f64; 4]) {
    let (mut ierror, mut f) = (12345, [0.0; 4]);
    unsafe {
        cntc_setcreepages(&ire, &1, &cksi, &0.0, &0.0);
        cntc_calculate(&ire, &1, &mut ierror);
        let [fn_, fx, fy, mz] = &mut f;
        cntc_getcontactforces(&ire, &1, fn_, fx, fy, mz);
    }
    (ierror, f)
}

fn division(ire: i32, n: usize) -> Vec<i32> {
    let mut d = vec![-1; n];
    unsafe { cntc_getelementdivision(&ire, &1, &(n as i32), d.as_mut_ptr()) };
    d
}

fn field(ire: i32, n: usize, ifld: i32) -> Vec<f64> {
    let mut v = vec![f64::NAN; n];
    unsafe { cntc_getfielddata(&ire, &1, &ifld, &(n as i32), v.as_mut_ptr()) };
    v
}

/// Configures (ire, 1) as `examples/python_tractcurv.py` (steady rolling,
/// Hertzian option -2: A1 = 0.0008 /mm, a/b = 0.5, 48 x 44 elements over
/// 1.1 times the ellipse, FN = 106.7 kN, V = 10 m/s, G = 82000 N/mm², nu =
/// 0.28, B = 0, G = 0 with MAXOUT 1 and EPS 1e-6) with the material
/// parameters `mat` (M = 4 when 8, else M = 0) and its curve 2's
/// exponential falling friction (L = 4: 0.14 + 0.19 exp(-ln2 s / 1250
/// mm/s)) without its memory (MEMDST = MEM_S0 = 0, see below).
fn tractcurv_falling(ire: i32, mat: &[f64]) {
    flags3(ire, 3, 2);
    unsafe {
        let m = if mat.len() == 8 { 4 } else { 0 };
        cntc_setmaterialparameters(&ire, &1, &m, &(mat.len() as i32), mat.as_ptr());
        let hz = [48.0, 44.0, 0.0008, 0.5, 1.1];
        cntc_sethertzcontact(&ire, &1, &-2, &5, hz.as_ptr());
        cntc_setreferencevelocity(&ire, &1, &10000.0);
        cntc_setnormalforce(&ire, &1, &106700.0);
        let (ip, rp) = ([80, 200, 5, 1], [1e-6]);
        cntc_setsolverflags(&ire, &1, &0, &4, ip.as_ptr(), &1, rp.as_ptr());
        let law = [0.14, 0.19, 1250.0, 0.0, 0.0, 0.0, 0.0];
        cntc_setfrictionmethod(&ire, &1, &4, &7, law.as_ptr());
        cntc_setflags(&ire, &1, &1, &flags::IC_BOUND, &0);
    }
}

/// Runs the creepages of `cases` (CKSI, CONTACT's FX [N], its adhesion
/// and slip elements) on (ire, 1): FX within `tol` (relative), the
/// element counts exact, no plasticity. Returns the largest difference.
fn falling_curve(ire: i32, cases: &[(f64, f64, [usize; 2])], tol: f64) -> f64 {
    let mut worst: f64 = 0.0;
    for &(cksi, fx, [adh, slip]) in cases {
        let (ierror, f) = solve(ire, cksi);
        assert_eq!(ierror, 0, "cksi {cksi}");
        let d = division(ire, 48 * 44);
        eprintln!(
            "element {ire}, cksi {cksi}: FX {} N against CONTACT's {fx} ({:.1e}), adhesion/slip \
             {:?} against {:?}",
            f[1],
            rel(f[1], fx),
            (count(&d, 1), count(&d, 2)),
            (adh, slip)
        );
        worst = worst.max(rel(f[1], fx));
        assert!(rel(f[1], fx) < tol, "cksi {cksi}: FX {} vs {fx}", f[1]);
        assert_eq!((count(&d, 1), count(&d, 2), count(&d, 3)), (adh, slip, 0));
    }
    worst
}

/// Falling friction's difference from CONTACT at full sliding, before
/// any layer: 8.4e-6 on M = 0 (CKSI 0.25 below); with the layer the
/// largest is 1.4e-5, at the same creepage (the falling law's iteration
/// at large slip velocities, not the layer: at CKSI <= 0.014 within
/// 3.7e-6 with the layer and 1.7e-6 without).
const FALLING_TOL: f64 = 3e-5;

/// An elastic layer (GG3 = 8200 N/mm², LAYTHK = 1.25 mm, TAU_C0 = K_TAU =
/// 0: python_tractcurv's curve 2) under falling friction, against
/// CONTACT's library on the same calls, and the same without the layer (M
/// = 0) beside it: the layer softens the curve (FX at CKSI 0.003 -17323
/// against -34648 N) and the two agree with CONTACT alike.
///
/// Curve 2 itself has the law's memory (MEMDST 0.003 mm, MEM_S0 1 mm/s):
/// there FX differs from CONTACT's by up to 8.5e-4 (CKSI 0.014: -33162.9
/// against -33191.1 N), and by 3.4e-4 without the layer as well (M = 0,
/// CKSI 0.008: -34358.7 against -34370.2 N): a difference of the
/// falling law with memory in steady rolling, not of the layer.
#[test]
fn an_elastic_layer_with_falling_friction_matches_contact() {
    let layer = [0.28, 0.28, 82000.0, 82000.0, 8200.0, 1.25, 0.0, 0.0];
    tractcurv_falling(401, &layer);
    let worst = falling_curve(
        401,
        &[
            (0.00001, -65.81035900149209, [1382, 2]),
            (0.003, -17323.465314563244, [1124, 260]),
            (0.008, -30401.454235036286, [534, 850]),
            (0.014, -33127.67073336513, [186, 1198]),
            (0.05, -30336.3533873554, [0, 1384]),
            (0.25, -20014.42345008275, [0, 1384]),
        ],
        FALLING_TOL,
    );
    eprintln!("M = 4: largest FX difference {worst:.1e}");
    tractcurv_falling(403, &layer[..4]);
    let worst = falling_curve(
        403,
        &[
            (0.00001, -247.00134301284572, [1382, 2]),
            (0.003, -34648.15876796068, [68, 1316]),
            (0.008, -34333.403561548505, [0, 1384]),
            (0.014, -33702.62973558743, [0, 1384]),
            (0.05, -30307.821840509474, [0, 1384]),
            (0.25, -20007.681109316884, [0, 1384]),
        ],
        FALLING_TOL,
    );
    eprintln!("M = 0: largest FX difference {worst:.1e}");
    // The layer's parameters read back as CONTACT's (cntc_getparameters
    // 2: FLX(1:3) = LAYTHK / GG3 [mm³/N], GG3, LAYTHK, TAU_C0, K_TAU as
    // values 8-10 and 15-18; 1: TAU_C0 as value 6).
    let mut v = [f64::NAN; 18];
    unsafe { cntc_getparameters(&401, &1, &2, &18, v.as_mut_ptr()) };
    let flx = 1.25 / 8200.0;
    for k in 7..10 {
        assert!(rel(v[k], flx) < 1e-15, "FLX: {v:?}");
    }
    assert_eq!(&v[14..18], &[8200.0, 1.25, 0.0, 0.0]);
}

/// The catt3d_plast problem (CONTACT's `testbank/examples_plast/
/// catt3d_plast.inp`): 34 x 33 elements of 0.25 mm from (-4.125, -4.125)
/// mm (IPOTCN 1), h = 0.002963 (x² + y²) /mm (IBASE 1), G = 1 N/mm², nu
/// 0.28, FN = 0.4705 N, mu = 0.4013, plasticity at the surface (LAYTHK 0,
/// which CONTACT and this library take as 1e-9 mm) with TAU_C0 = 0.005
/// N/mm² hardening by K_TAU = 0.42857 N/mm³, V = 1000 mm/s, DQ = 0.25 mm,
/// G = 0 with EPS 1e-8. One element runs: steady rolling at CKSI =
/// -0.0034 (P = 2); two shifts of 0.012 mm from zero tractions (P = 2,
/// then P = 0: the second flows); three transient rolling steps of DQ at
/// CKSI = -0.0034 (P = 0), the plastic deformation carried with the
/// material.
#[test]
fn plasticity_in_steady_rolling_shifts_and_rolling_steps_matches_contact() {
    let ire = 402;
    let n = 34 * 33;
    flags3(ire, 3, 2);
    unsafe {
        let mat = [0.28, 0.28, 1.0, 1.0, 1.0, 0.0, 0.005, 0.42857];
        cntc_setmaterialparameters(&ire, &1, &4, &8, mat.as_ptr());
        let pot = [34.0, 33.0, -4.125, -4.125, 0.25, 0.25];
        cntc_setpotcontact(&ire, &1, &1, &6, pot.as_ptr());
        let b = [0.002963, 0.0, 0.002963, 0.0, 0.0, 0.0];
        cntc_setundeformeddistc(&ire, &1, &1, &6, b.as_ptr());
        cntc_setfrictionmethod(&ire, &1, &0, &2, [0.4013, 0.4013].as_ptr());
        cntc_setreferencevelocity(&ire, &1, &1000.0);
        cntc_setrollingstepsize(&ire, &1, &0.0, &0.25);
        cntc_setnormalforce(&ire, &1, &0.4705);
        let (ip, rp) = ([999, 100, 30, 1], [1e-8]);
        cntc_setsolverflags(&ire, &1, &0, &4, ip.as_ptr(), &1, rp.as_ptr());
    }
    /// CONTACT's case: (T, P, CKSI) and FX [N]; adhesion, slip and
    /// plastic elements; the contact, adhesion and slip areas [mm²]; the
    /// sums of TAUCRT [N/mm²] and UPLSX [mm] over the grid; the largest
    /// |PX|'s element (0-based), its PX, TAUCRT [N/mm²] and UPLSX [mm];
    /// the largest |UPLSY|'s element, its UPLSY and the sum of |UPLSY|
    /// \[mm\] (UPLSY is odd in y, the problem symmetric).
    struct Case {
        tang_pvtime_cksi: (i32, i32, f64),
        fx: f64,
        counts: [usize; 3],
        areas: [f64; 3],
        sums: [f64; 2],
        at: (usize, [f64; 3]),
        uy: (usize, f64, f64),
    }
    let cases = [
        Case {
            tang_pvtime_cksi: (3, 2, -0.0034),
            fx: 0.1306153561950025,
            counts: [282, 245, 94],
            areas: [38.8125, 17.625, 15.3125],
            sums: [5.880728717616521, 0.6315720302254113],
            at: (
                553,
                [
                    0.006376793134545439,
                    0.006376793134545439,
                    0.0032125279895337034,
                ],
            ),
            uy: (340, -6.348143619259845e-05, 0.010335279121809468),
        },
        Case {
            tang_pvtime_cksi: (1, 2, 0.012),
            fx: -0.08868931890727609,
            counts: [421, 200, 0],
            areas: [38.8125, 26.3125, 12.5],
            sums: [5.609999999999999, 0.0],
            at: (937, [-0.0041853913992382545, 0.005, 0.0]),
            uy: (0, 0.0, 0.0),
        },
        Case {
            tang_pvtime_cksi: (1, 0, 0.012),
            fx: -0.15529299446985184,
            counts: [145, 348, 128],
            areas: [38.8125, 9.0625, 21.75],
            sums: [5.655423208814204, -0.10598177127376421],
            at: (
                256,
                [
                    -0.005542913140602741,
                    0.005543042222542221,
                    -0.0012670732356644804,
                ],
            ),
            uy: (837, 1.723907726258008e-05, 0.0008396055751424761),
        },
        Case {
            tang_pvtime_cksi: (2, 0, -0.0034),
            fx: -0.14546926404573476,
            counts: [374, 175, 72],
            areas: [38.8125, 23.375, 10.9375],
            sums: [5.660643358288203, -0.11816182870500418],
            at: (
                867,
                [
                    -0.00554498551028601,
                    0.0055451116694726285,
                    -0.00127190185131676,
                ],
            ),
            uy: (836, 1.723907726258008e-05, 0.0009015997966610432),
        },
        Case {
            tang_pvtime_cksi: (2, 0, -0.0034),
            fx: -0.1356929927078745,
            counts: [386, 173, 62],
            areas: [38.8125, 24.125, 10.8125],
            sums: [5.66557869407339, -0.12967729249991483],
            at: (
                865,
                [
                    -0.005555028851716016,
                    0.005555108097883937,
                    -0.0012952504051361073,
                ],
            ),
            uy: (835, 1.723907726258008e-05, 0.0009477779837442668),
        },
        Case {
            tang_pvtime_cksi: (2, 0, -0.0034),
            fx: -0.1259821690031486,
            counts: [394, 167, 60],
            areas: [38.8125, 24.625, 10.4375],
            sums: [5.670007273578649, -0.14001024857617847],
            at: (
                865,
                [
                    -0.00557277833401759,
                    0.005573006807071405,
                    -0.0013369883261353907,
                ],
            ),
            uy: (834, 1.723907726258008e-05, 0.0010110037719491722),
        },
    ];
    for (k, c) in cases.iter().enumerate() {
        let (tang, pvtime, cksi) = c.tang_pvtime_cksi;
        flags3(ire, tang, pvtime);
        let (ierror, f) = solve(ire, cksi);
        assert_eq!(ierror, 0, "case {k}");
        let d = division(ire, n);
        let (tau, ux, uy, px) = (
            field(ire, n, field::TAUCRT),
            field(ire, n, field::UPLSX),
            field(ire, n, field::UPLSY),
            field(ire, n, field::PX),
        );
        let mut areas = [0.0; 3];
        unsafe {
            let [a, b, s] = &mut areas;
            cntc_getcontactpatchareas(&ire, &1, a, b, s);
        }
        let counts = [count(&d, 1), count(&d, 2), count(&d, 3)];
        let sums = [tau.iter().sum::<f64>(), ux.iter().sum::<f64>()];
        let j = c.at.0;
        eprintln!(
            "case {k} (T {tang}, P {pvtime}, CKSI {cksi}): FX {} against {} ({:.1e}); counts \
             {counts:?} against {:?}; sums TAUCRT {} against {} ({:.1e}), UPLSX {} against {} \
             ({:.1e}); element {j}: PX {} TAUCRT {} UPLSX {} against {:?}",
            f[1],
            c.fx,
            rel(f[1], c.fx),
            c.counts,
            sums[0],
            c.sums[0],
            rel(sums[0], c.sums[0]),
            sums[1],
            c.sums[1],
            (sums[1] - c.sums[1]).abs(),
            px[j],
            tau[j],
            ux[j],
            c.at.1
        );
        assert!(rel(f[1], c.fx) < TOL, "case {k}: FX {} vs {}", f[1], c.fx);
        assert_eq!(counts, c.counts, "case {k}: adhesion, slip, plasticity");
        assert_eq!(areas, c.areas, "case {k}: contact, adhesion, slip areas");
        assert!(rel(sums[0], c.sums[0]) < TOL, "case {k}: sum TAUCRT");
        // UPLSX summed over the grid against the largest deformation
        // times the number of elements (it is 0 before any flow).
        let scale = 0.0014 * n as f64;
        assert!(
            (sums[1] - c.sums[1]).abs() < TOL * scale,
            "case {k}: sum UPLSX {} vs {}",
            sums[1],
            c.sums[1]
        );
        let (i, uy_i, uy_abs) = c.uy;
        let sum_abs: f64 = uy.iter().map(|v| v.abs()).sum();
        eprintln!(
            "case {k}: UPLSY at {i} {} against {uy_i}, sum |UPLSY| {sum_abs} against {uy_abs}",
            uy[i]
        );
        assert!(
            (uy[i] - uy_i).abs() < TOL * 0.0014,
            "case {k}: UPLSY at {i}"
        );
        assert!(
            (sum_abs - uy_abs).abs() < TOL * scale,
            "case {k}: sum |UPLSY|"
        );
        for (ours, theirs, unit) in [
            (px[j], c.at.1[0], 0.0056),
            (tau[j], c.at.1[1], 0.0056),
            (ux[j], c.at.1[2], 0.0014),
        ] {
            assert!(
                (ours - theirs).abs() < TOL * unit,
                "case {k}, element {j}: {ours} vs {theirs}"
            );
        }
    }
    // cntc_getparameters 1's TAU_C0 (value 6) and 2's FLX(1:3), K_EFF,
    // GG3, LAYTHK, TAU_C0, K_TAU as CONTACT's library returns them for
    // this problem: 0.005; 1e-9 (x3), 0, 1.0, 1e-9 (LAYTHK 0 taken as
    // 1e-9 mm), 0.005, 0.42857.
    let (mut p1, mut p2) = ([f64::NAN; 6], [f64::NAN; 18]);
    unsafe {
        cntc_getparameters(&ire, &1, &1, &6, p1.as_mut_ptr());
        cntc_getparameters(&ire, &1, &2, &18, p2.as_mut_ptr());
    }
    assert_eq!(p1[5], 0.005);
    for flx in &p2[7..10] {
        assert!(rel(*flx, 1e-9) < 1e-12, "FLX {flx}");
    }
    assert_eq!((p2[13], p2[14]), (0.0, 1.0));
    assert!(rel(p2[15], 1e-9) < 1e-12, "LAYTHK {}", p2[15]);
    assert!(rel(p2[16], 0.005) < 1e-15 && rel(p2[17], 0.42857) < 1e-15);
}

/// Our difference from CONTACT's library allowed in the plastic cases,
/// relative (to the value, or for UPLSX to the largest deformation, 1.4e-3
/// mm; for PX and TAUCRT of an element to the largest traction, 5.6e-3
/// N/mm²): both solve to EPS 1e-8; measured at most 1e-8 on FX, 4e-9 on
/// the sum of TAUCRT, 3.3e-8 on the sum of UPLSX and 2.2e-7 on one
/// element's UPLSX (case 5, element 865: 1.3369886e-3 against 1.3369883e-3
/// mm).
const TOL: f64 = 5e-7;

/// What M = 4 refuses: an elasto-plastic layer with a falling friction
/// law (-99, at calculation); an elastic layer takes the law (above), and
/// Coulomb's law makes the plastic one run. (Module 1 with a plastic
/// layer: `module1.rs`.)
#[test]
fn a_plastic_layer_refuses_a_falling_law() {
    let ire = 404;
    tractcurv_falling(
        ire,
        &[0.28, 0.28, 82000.0, 82000.0, 8200.0, 1.25, 300.0, 0.0],
    );
    let (ierror, _) = solve(ire, 0.003);
    assert_eq!(ierror, contact_addon::flags::err::OTHER);
    unsafe { cntc_setfrictionmethod(&ire, &1, &0, &2, [0.3, 0.3].as_ptr()) };
    let (ierror, f) = solve(ire, 0.003);
    assert_eq!(ierror, 0);
    assert!(f[1] < 0.0);
}

/// Prescribed forces on the catt3d_plast problem (above): F = 1 with
/// FX/(mu FN) = -0.6918 (catt3d_plast's value), in steady rolling (P =
/// 2), then a rolling step of DQ from zero tractions (P = 2) and two more
/// continuing (P = 0): the creepage each needs, the element counts and
/// the sum of UPLSX [mm] against CONTACT's library (the creepage found
/// by its iteration, to its tolerance).
#[test]
fn prescribed_forces_on_a_plastic_layer_find_contacts_creepages() {
    let ire = 406;
    let n = 34 * 33;
    flags3(ire, 3, 2);
    unsafe {
        cntc_setflags(&ire, &1, &1, &flags::IC_FORCE, &1);
        let mat = [0.28, 0.28, 1.0, 1.0, 1.0, 0.0, 0.005, 0.42857];
        cntc_setmaterialparameters(&ire, &1, &4, &8, mat.as_ptr());
        let pot = [34.0, 33.0, -4.125, -4.125, 0.25, 0.25];
        cntc_setpotcontact(&ire, &1, &1, &6, pot.as_ptr());
        let b = [0.002963, 0.0, 0.002963, 0.0, 0.0, 0.0];
        cntc_setundeformeddistc(&ire, &1, &1, &6, b.as_ptr());
        cntc_setfrictionmethod(&ire, &1, &0, &2, [0.4013, 0.4013].as_ptr());
        cntc_setreferencevelocity(&ire, &1, &1000.0);
        cntc_setrollingstepsize(&ire, &1, &0.0, &0.25);
        cntc_setnormalforce(&ire, &1, &0.4705);
        let (ip, rp) = ([999, 100, 30, 1], [1e-8]);
        cntc_setsolverflags(&ire, &1, &0, &4, ip.as_ptr(), &1, rp.as_ptr());
    }
    for (k, ((tang, pvtime), cksi, counts, sum_ux)) in [
        (
            (3, 2),
            0.00340018565023407,
            [282, 245, 94],
            -0.6316447065567488,
        ),
        (
            (2, 2),
            0.07570738663495462,
            [277, 300, 44],
            -0.01022696592954657,
        ),
        (
            (2, 0),
            0.00197929498338184,
            [369, 193, 59],
            -0.018206462823908122,
        ),
        (
            (2, 0),
            0.0020906896965123913,
            [352, 193, 76],
            -0.030712566968287898,
        ),
    ]
    .into_iter()
    .enumerate()
    {
        flags3(ire, tang, pvtime);
        let (mut ierror, mut f, mut c) = (12345, [0.0; 4], [0.0; 3]);
        unsafe {
            cntc_setflags(&ire, &1, &1, &flags::IC_FORCE, &1);
            cntc_settangentialforces(&ire, &1, &-0.6918, &0.0);
            cntc_calculate(&ire, &1, &mut ierror);
            let [fn_, fx, fy, mz] = &mut f;
            cntc_getcontactforces(&ire, &1, fn_, fx, fy, mz);
            let [a, b, cc] = &mut c;
            cntc_getcreepages(&ire, &1, a, b, cc);
        }
        let d = division(ire, n);
        let ux: f64 = field(ire, n, field::UPLSX).iter().sum();
        let ours = [count(&d, 1), count(&d, 2), count(&d, 3)];
        eprintln!(
            "case {k} (T {tang}, P {pvtime}): FX {} CKSI {} against {cksi} ({:.1e}), counts \
             {ours:?} against {counts:?}, sum UPLSX {ux} against {sum_ux}",
            f[1],
            c[0],
            rel(c[0], cksi)
        );
        assert_eq!(ierror, 0, "case {k}");
        // CONTACT: -0.13061989947 N in every case.
        assert!(rel(f[1], -0.13061989947) < FORCE_TOL, "case {k}: FX");
        assert!(rel(c[0], cksi) < FORCE_TOL, "case {k}: CKSI");
        assert_eq!(ours, counts, "case {k}");
        assert!(
            (ux - sum_ux).abs() < FORCE_TOL * 0.0014 * n as f64,
            "case {k}: sum UPLSX"
        );
    }
}

/// The prescribed force's case allowed from CONTACT's, relative: both
/// iterate on the creepage to their tolerance (EPS 1e-8); measured FX
/// within 4e-9, CKSI within 1.1e-7 (case 3: 0.00209068993 against
/// 0.00209068970), the sum of UPLSX within 2e-8 mm.
const FORCE_TOL: f64 = 5e-7;
