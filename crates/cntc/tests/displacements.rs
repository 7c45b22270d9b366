//! The displacement differences UN, UX, UY (`cntc_getdisplacements`):
//! Hertz's normal contact analytically, and CONTACT's own library.
//!
//! CONTACT's numbers come from its shared library (`contact_addon_linux64.so`
//! of CONTACT revision 2707, 2025-07-23, built with gfortran 12 `-O2`),
//! driven with ctypes through the same `cntc_*` calls as below (the set-up
//! of `common::tractcurv`, with A = 2, `CNTC_ic_matfil`, so that CONTACT
//! computes US at the exterior elements too: with A < 2 it computes them
//! in the contact area only and leaves the others as they were), reading
//! back `cntc_getdisplacements`: the doubles as the library printed them
//! (Python's repr).
//!
//! Each test uses its own result elements (the library is one per process).

mod common;

use common::{calculate, close, set_flags, tractcurv};
use contact_addon::ffi::*;
use contact_addon::flags::{self, field};

/// The grid of (ire, 1): its number of elements.
fn elements(ire: i32) -> usize {
    let (mut mx, mut my) = (0, 0);
    unsafe { cntc_getnumelements(&ire, &1, &mut mx, &mut my) };
    (mx * my) as usize
}

/// UN, UX, UY of (ire, icp).
fn displacements(ire: i32, icp: i32, n: usize) -> [Vec<f64>; 3] {
    let mut u = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
    let [un, ux, uy] = &mut u;
    let len = n as i32;
    unsafe {
        cntc_getdisplacements(
            &ire,
            &icp,
            &len,
            un.as_mut_ptr(),
            ux.as_mut_ptr(),
            uy.as_mut_ptr(),
        )
    };
    u
}

/// Field `ifld` of (ire, icp) (`cntc_getfielddata`).
fn field_data(ire: i32, icp: i32, n: usize, ifld: i32) -> Vec<f64> {
    let mut v = vec![0.0; n];
    unsafe { cntc_getfielddata(&ire, &icp, &ifld, &(n as i32), v.as_mut_ptr()) };
    v
}

/// The approach PEN of (ire, icp).
fn penetration(ire: i32, icp: i32) -> f64 {
    let mut pen = 0.0;
    unsafe { cntc_getpenetration(&ire, &icp, &mut pen) };
    pen
}

/// CONTACT's displacement differences of one case: (element, UN, UX, UY)
/// at a few elements (0 a corner outside the contact area, the others
/// inside), and the largest and smallest value of each field.
struct Reference {
    elements: [(usize, [f64; 3]); 5],
    max: [f64; 3],
    min: [f64; 3],
}

/// Compares (ire, 1)'s UN, UX, UY with `r`: each within `tol` times the
/// field's largest magnitude; returns the largest difference so measured.
fn compare(what: &str, ire: i32, r: &Reference, tol: f64) -> [f64; 3] {
    let n = elements(ire);
    let u = displacements(ire, 1, n);
    let names = ["UN", "UX", "UY"];
    let mut worst = [0.0f64; 3];
    for c in 0..3 {
        let scale = r.max[c].abs().max(r.min[c].abs());
        let max = u[c].iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        let min = u[c].iter().cloned().fold(f64::INFINITY, f64::min);
        let mut pairs = vec![
            ("max".to_string(), max, r.max[c]),
            ("min".to_string(), min, r.min[c]),
        ];
        for (i, v) in &r.elements {
            pairs.push((format!("element {i}"), u[c][*i], v[c]));
        }
        for (at, ours, theirs) in pairs {
            let d = if scale > 0.0 {
                (ours - theirs).abs() / scale
            } else {
                (ours - theirs).abs()
            };
            worst[c] = worst[c].max(d);
            assert!(
                d <= tol,
                "{what}: {} {at}: ours {ours:e}, CONTACT's {theirs:e} ({d:.1e} of the largest)",
                names[c]
            );
        }
    }
    eprintln!(
        "{what}: UN, UX, UY within {:.1e}, {:.1e}, {:.1e} of CONTACT's largest",
        worst[0], worst[1], worst[2]
    );
    worst
}

/// CONTACT's steady T=3.
const STEADY: Reference = Reference {
    elements: [
        (
            0,
            [
                0.02164890097493451,
                -0.0037053811082524294,
                0.0010911358235349419,
            ],
        ),
        (
            1058,
            [
                0.04561188010865625,
                -0.009265132843494847,
                0.003914346337866293,
            ],
        ),
        (
            1080,
            [
                0.07646306145017497,
                -0.010081347745730176,
                0.0034460926138046954,
            ],
        ),
        (
            510,
            [
                0.05889788950992006,
                -0.009438567003464926,
                0.0031278083569392856,
            ],
        ),
        (
            1500,
            [
                0.05758444904976651,
                -0.009543482733840052,
                0.004623606600872172,
            ],
        ),
    ],
    max: [
        0.07646306145017497,
        -0.002717597119364648,
        0.005274166434345042,
    ],
    min: [
        0.02164890097493451,
        -0.013520902545573059,
        0.0008022814735409269,
    ],
};

/// CONTACT's shift 1 (T=1,P=2).
const SHIFT_1: Reference = Reference {
    elements: [
        (
            0,
            [
                0.02164890097493451,
                -0.0009212648050163057,
                -0.0005464025479675546,
            ],
        ),
        (
            1058,
            [
                0.04561188010865625,
                -0.0019128992527677093,
                -0.0009528084378945972,
            ],
        ),
        (
            1080,
            [
                0.07646306145017497,
                -0.001999999672945828,
                -0.001000000018121831,
            ],
        ),
        (
            510,
            [
                0.05889788950992006,
                -0.001999999767463423,
                -0.0010000000634789285,
            ],
        ),
        (
            1500,
            [
                0.05758444904976651,
                -0.0019999995504374783,
                -0.0010000000734299089,
            ],
        ),
    ],
    max: [
        0.07646306145017497,
        -0.0008255084656401664,
        -0.0003454484138992222,
    ],
    min: [
        0.02164890097493451,
        -0.0020000005705876557,
        -0.0010000010203219862,
    ],
};

/// CONTACT's shift 2 (T=1,P=0).
const SHIFT_2: Reference = Reference {
    elements: [
        (
            0,
            [
                0.02164890097493451,
                -0.0025586837860857576,
                -0.0009334242050855282,
            ],
        ),
        (
            1058,
            [
                0.04561188010865625,
                -0.005377696056634922,
                -0.0013079769111935167,
            ],
        ),
        (
            1080,
            [
                0.07646306145017497,
                -0.005999993389930493,
                -0.0014999995120687458,
            ],
        ),
        (
            510,
            [
                0.05889788950992006,
                -0.005999997335862199,
                -0.00149999855479047,
            ],
        ),
        (
            1500,
            [
                0.05758444904976651,
                -0.005999997274514004,
                -0.0014999979741188985,
            ],
        ),
    ],
    max: [
        0.07646306145017497,
        -0.0024171224931144523,
        -0.0003468129365933498,
    ],
    min: [
        0.02164890097493451,
        -0.006000001363387839,
        -0.0015000118074207436,
    ],
};

/// CONTACT's rolling step 4 (T=2).
const ROLLING_4: Reference = Reference {
    elements: [
        (
            0,
            [
                0.02164890097493451,
                -0.00033423294573853605,
                0.00016687096824241583,
            ],
        ),
        (
            1058,
            [
                0.04561188010865625,
                -0.000808961955391886,
                0.00046226416765581706,
            ],
        ),
        (
            1080,
            [
                0.07646306145017497,
                -0.0008089618664263552,
                0.0004622642736318948,
            ],
        ),
        (
            510,
            [
                0.05889788950992006,
                -0.0008089617519906685,
                0.0004622639754049925,
            ],
        ),
        (
            1500,
            [
                0.05758444904976651,
                -0.000808961450892624,
                0.00046226393105583207,
            ],
        ),
    ],
    max: [
        0.07646306145017497,
        -0.0003281553052764894,
        0.00046226564654641635,
    ],
    min: [
        0.02164890097493451,
        -0.0008089624590306539,
        0.00016139393745111477,
    ],
};

/// CONTACT's FASTSIM B=3.
const FASTSIM_B3: Reference = Reference {
    elements: [
        (0, [0.0, 0.0, 0.0]),
        (1058, [0.0, -0.0003896404711414213, 0.00024945642040502205]),
        (1080, [0.0, -0.004378209466277851, 0.0016653817663701861]),
        (510, [0.0, -0.0033186106602415646, 0.0008655481434545435]),
        (1500, [0.0, -0.0043664583705807485, 0.0031767363314111298]),
    ],
    max: [0.0, 0.0, 0.003836962787474575],
    min: [0.0, -0.008238201792802487, 0.0],
};

/// CONTACT's FASTSIM B=0.
const FASTSIM_B0: Reference = Reference {
    elements: [
        (0, [0.02164890097493451, 0.0, 0.0]),
        (
            1058,
            [
                0.04561188010865625,
                -0.00147012783548185,
                0.0008848638154038218,
            ],
        ),
        (
            1080,
            [
                0.07646306145017497,
                -0.004378209466277851,
                0.0016653817663701861,
            ],
        ),
        (
            510,
            [
                0.05889788950992006,
                -0.0033186106602415646,
                0.0008655481434545435,
            ],
        ),
        (
            1500,
            [
                0.05758444904976651,
                -0.0043664583705807485,
                0.0031767363314111298,
            ],
        ),
    ],
    max: [0.07646306145017497, 0.0, 0.003971929167950223],
    min: [0.02164890097493451, -0.008304227502598377, 0.0],
};

/// CONTACT's layer M=4.
const LAYER: Reference = Reference {
    elements: [
        (
            0,
            [
                0.02164890097493451,
                -0.0011588973086140983,
                0.00045369803463240967,
            ],
        ),
        (
            1058,
            [
                0.04561188010865625,
                -0.0072020304284678045,
                0.0038317964575082827,
            ],
        ),
        (
            1080,
            [
                0.07646306145017497,
                -0.006169294061188525,
                0.0025373359957491714,
            ],
        ),
        (
            510,
            [
                0.05889788950992006,
                -0.00506274617889648,
                0.0018075729464550228,
            ],
        ),
        (
            1500,
            [
                0.05758444904976651,
                -0.006164349832291983,
                0.0038352758810141,
            ],
        ),
    ],
    max: [
        0.07646306145017497,
        -0.0008223829691919589,
        0.00555458335975643,
    ],
    min: [
        0.02164890097493451,
        -0.011625284071632458,
        0.00033470128899471164,
    ],
};

/// CONTACT's frictionless T=0, SI.
const FRICTIONLESS_SI: Reference = Reference {
    elements: [
        (0, [2.164890097493451e-05, 0.0, 0.0]),
        (1058, [4.561188010865625e-05, 0.0, 0.0]),
        (1080, [7.646306145017496e-05, 0.0, 0.0]),
        (510, [5.889788950992006e-05, 0.0, 0.0]),
        (1500, [5.758444904976652e-05, 0.0, 0.0]),
    ],
    max: [7.646306145017496e-05, 0.0, 0.0],
    min: [2.164890097493451e-05, 0.0, 0.0],
};

/// CONTACT's steady T=3, SIMPACK units.
const STEADY_SIMPACK: Reference = Reference {
    elements: [
        (
            0,
            [
                2.164890097493451e-05,
                -3.7053811082524266e-06,
                1.0911358235349422e-06,
            ],
        ),
        (
            1058,
            [
                4.561188010865625e-05,
                -9.265132843494848e-06,
                3.914346337866293e-06,
            ],
        ),
        (
            1080,
            [
                7.646306145017496e-05,
                -1.0081347745730175e-05,
                3.4460926138046954e-06,
            ],
        ),
        (
            510,
            [
                5.889788950992006e-05,
                -9.438567003464923e-06,
                3.1278083569392864e-06,
            ],
        ),
        (
            1500,
            [
                5.758444904976652e-05,
                -9.543482733840052e-06,
                4.623606600872172e-06,
            ],
        ),
    ],
    max: [
        7.646306145017496e-05,
        -2.7175971193646454e-06,
        5.274166434345043e-06,
    ],
    min: [
        2.164890097493451e-05,
        -1.3520902545573054e-05,
        8.022814735409266e-07,
    ],
};

/// Our difference from CONTACT allowed, relative to the field's largest
/// magnitude: both solve to their tolerances (EPS 1e-5 here) on the same
/// grid with the same influence coefficients, and a displacement sums the
/// tractions over the whole grid, so it agrees better than the tractions
/// (within 1 % or CONTACT's printed digits). Measured: see the tests'
/// output and docs/cntc.md.
const TOL: f64 = 2e-5;

/// Hertz's frictionless normal contact (module 3, T = 0, the tractcurv
/// ellipse): where the pressure is positive the deformed distance
/// h - PEN + UN is zero, so UN = PEN - h; elsewhere it is positive (no
/// interpenetration), UN > PEN - h. These are the contact conditions of
/// Kalker's variational theory (J.J. Kalker, Three-dimensional elastic
/// bodies in rolling contact, Kluwer 1990, §2.1.3, eqs. 2.5-2.6), in
/// CONTACT's sign convention (its `soutpt` computes the deformed distance
/// as hs - pen + us; user guide, section "Solution arrays"). UX, UY are
/// zero (no friction, equal materials). The same case in SI against
/// CONTACT's library.
#[test]
fn hertz_normal_displacement_is_the_approach_minus_the_gap_in_contact() {
    let ire = 701;
    tractcurv(ire, 0, 2);
    assert_eq!(calculate(ire, [0.0; 3]), 0);
    let n = elements(ire);
    let [un, ux, uy] = displacements(ire, 1, n);
    let pen = penetration(ire, 1);
    let h = field_data(ire, 1, n, field::H);
    let pn = field_data(ire, 1, n, field::PN);
    let (mut inside, mut outside, mut worst) = (0, 0, 0.0f64);
    for i in 0..n {
        let rigid = pen - h[i];
        if pn[i] > 0.0 {
            inside += 1;
            worst = worst.max((un[i] - rigid).abs() / pen);
        } else {
            outside += 1;
            assert!(
                un[i] > rigid,
                "element {i}: UN {} <= PEN - h {rigid}",
                un[i]
            );
        }
    }
    eprintln!("{inside} elements in contact: |UN - (PEN - h)| <= {worst:.1e} PEN");
    assert!(inside > 1000 && outside > 100, "{inside} in, {outside} out");
    assert!(worst < 1e-6, "UN - (PEN - h) up to {worst:e} PEN");
    assert!(ux.iter().chain(&uy).all(|u| *u == 0.0));

    let ire = 702;
    tractcurv(ire, 0, 2);
    set_flags(ire, 1, &[(flags::IF_UNITS, flags::UN_SI)]);
    unsafe { cntc_setnormalforce(&ire, &1, &106700.0) };
    assert_eq!(calculate(ire, [0.0; 3]), 0);
    compare("frictionless, SI", ire, &FRICTIONLESS_SI, TOL);
}

/// Steady rolling (T = 3) at creepages and spin, in CONTACT's units and
/// in SIMPACK's (which, as CONTACT, gives body 1's displacement
/// differences: CONTACT scales them by the length unit only).
#[test]
fn steady_rolling_matches_contact() {
    let ire = 711;
    tractcurv(ire, 3, 2);
    assert_eq!(calculate(ire, [0.0007, -0.0004, 0.00003]), 0);
    compare("steady rolling", ire, &STEADY, TOL);

    let ire = 712;
    tractcurv(ire, 3, 2);
    set_flags(ire, 1, &[(flags::IF_UNITS, flags::UN_SPCK)]);
    unsafe {
        cntc_setreferencevelocity(&ire, &1, &10.0);
        cntc_setnormalforce(&ire, &1, &106700.0);
    }
    assert_eq!(calculate(ire, [0.0007, -0.0004, 0.03]), 0);
    compare("steady rolling, SIMPACK's units", ire, &STEADY_SIMPACK, TOL);
}

/// `r` turned a half turn about n on a grid of `n` elements symmetric
/// about the origin (the tractcurv grid): element i goes to n - 1 - i,
/// UX and UY change sign (their largest and smallest values exchanged),
/// UN stays.
fn half_turn(r: &Reference, n: usize) -> Reference {
    let turn = |[un, ux, uy]: [f64; 3]| [un, -ux, -uy];
    Reference {
        elements: r.elements.map(|(i, v)| (n - 1 - i, turn(v))),
        max: [r.max[0], -r.min[1], -r.min[2]],
        min: [r.min[0], -r.max[1], -r.max[2]],
    }
}

/// Steady rolling along -x (CHI = 180°) at the creepages of
/// [`steady_rolling_matches_contact`] turned a half turn (-xi, -eta, phi):
/// the solution is that one turned, so CONTACT's values of it turned are
/// the reference (the solver turns its grid to roll along +x; the
/// displacement differences are computed on the problem's grid).
#[test]
fn rolling_along_minus_x_matches_contact_turned() {
    let ire = 713;
    tractcurv(ire, 3, 2);
    let chi = std::f64::consts::PI;
    unsafe { cntc_setrollingstepsize(&ire, &1, &chi, &0.2889148735610571) };
    assert_eq!(calculate(ire, [-0.0007, 0.0004, 0.00003]), 0);
    let n = elements(ire);
    // mx, my, xc1, yc1, dx, dy: element centres symmetric about the origin.
    let mut g = [0.0; 6];
    unsafe { cntc_getpotcontact(&ire, &1, &6, g.as_mut_ptr()) };
    let [mx, my, x1, y1, dx, dy] = g;
    let xc = x1 + 0.5 * (mx - 1.0) * dx;
    let yc = y1 + 0.5 * (my - 1.0) * dy;
    assert!(
        xc.abs() < 1e-9 * dx && yc.abs() < 1e-9 * dy,
        "grid centre {xc}, {yc}"
    );
    compare("steady rolling along -x", ire, &half_turn(&STEADY, n), TOL);
}

/// Transient shifts (T = 1) from rest and continuing (P = 0), and four
/// transient rolling steps (T = 2) of one element from rest: the
/// displacement differences of the current tractions (in adhesion UX, UY
/// are minus the rigid shift).
#[test]
fn shifts_and_rolling_steps_match_contact() {
    let ire = 721;
    tractcurv(ire, 1, 2);
    assert_eq!(calculate(ire, [0.002, 0.001, 0.0]), 0);
    compare("shift from rest", ire, &SHIFT_1, TOL);
    set_flags(ire, 1, &[(flags::IC_PVTIME, 0)]);
    assert_eq!(calculate(ire, [0.004, 0.0005, 0.0]), 0);
    compare("second shift", ire, &SHIFT_2, TOL);

    let ire = 722;
    tractcurv(ire, 2, 2);
    // CONTACT's element size on this grid [mm].
    unsafe { cntc_setrollingstepsize(&ire, &1, &0.0, &0.2889148735610571) };
    assert_eq!(calculate(ire, [0.0007, -0.0004, 0.0]), 0);
    set_flags(ire, 1, &[(flags::IC_PVTIME, 0)]);
    for _ in 0..3 {
        assert_eq!(calculate(ire, [0.0007, -0.0004, 0.0]), 0);
    }
    compare("fourth rolling step", ire, &ROLLING_4, TOL);
}

/// FASTSIM (M = 3, no slope reduction: k0 = alpha = beta = 1) with the
/// parabolic traction bound (B = 3: UN zero, as CONTACT sets it) and on
/// the exact normal problem's pressure (B = 0).
#[test]
fn fastsim_matches_contact() {
    for (ire, bound, r) in [(731, 3, &FASTSIM_B3), (732, 0, &FASTSIM_B0)] {
        tractcurv(ire, 3, 2);
        let mat = [0.28, 0.28, 82000.0, 82000.0, 1.0, 1.0, 1.0];
        unsafe { cntc_setmaterialparameters(&ire, &1, &3, &7, mat.as_ptr()) };
        set_flags(ire, 1, &[(flags::IC_BOUND, bound)]);
        assert_eq!(calculate(ire, [0.0007, -0.0004, 0.00003]), 0);
        compare(&format!("FASTSIM, B = {bound}"), ire, r, TOL);
    }
}

/// CONTACT's FASTSIM with one given flexibility (M = 2, FLX = 5e-5 mm³/N,
/// k0 = 0.54, alpha = 0.02, beta = 0.62), B = 3: its library driven by
/// crates/cntc/bench/given_flexibility_cases.py (the set-up as below, A =
/// 2).
const FASTSIM_GIVEN: Reference = Reference {
    elements: [
        (0, [0.0, 0.0, 0.0]),
        (1058, [0.0, -0.0007282144531693811, 0.0004311739330935255]),
        (1080, [0.0, -0.004389189353781483, 0.0019272636906427147]),
        (510, [0.0, -0.0031808629806504922, 0.001021184890851243]),
        (1500, [0.0, -0.004660419904200831, 0.003297905579955135]),
    ],
    max: [0.0, 0.0, 0.004405611286148431],
    min: [0.0, -0.008827029918841227, 0.0],
};

/// FASTSIM with one given flexibility (M = 2) and a slope reduction: UX, UY
/// are FLX/k times the tractions (k CONTACT's slope reduction factor).
/// Measured: within 6.3e-10 of the largest.
#[test]
fn fastsim_with_a_given_flexibility_matches_contact() {
    let ire = 733;
    tractcurv(ire, 3, 2);
    let mat = [0.28, 0.28, 82000.0, 82000.0, 5e-5, 0.54, 0.02, 0.62];
    unsafe { cntc_setmaterialparameters(&ire, &1, &2, &8, mat.as_ptr()) };
    set_flags(ire, 1, &[(flags::IC_BOUND, 3)]);
    assert_eq!(calculate(ire, [0.0007, -0.0004, 0.00003]), 0);
    compare("FASTSIM, M = 2", ire, &FASTSIM_GIVEN, TOL);
}

/// An elastic interfacial layer (M = 4: G3 = 8200 N/mm², 1.25 mm): its
/// shear is part of UX, UY.
#[test]
fn an_interfacial_layer_matches_contact() {
    let ire = 741;
    tractcurv(ire, 3, 2);
    let mat = [0.28, 0.28, 82000.0, 82000.0, 8200.0, 1.25, 0.0, 0.0];
    unsafe { cntc_setmaterialparameters(&ire, &1, &4, &8, mat.as_ptr()) };
    assert_eq!(calculate(ire, [0.0007, -0.0004, 0.00003]), 0);
    compare("interfacial layer", ire, &LAYER, TOL);
}

/// A wheel/rail patch (module 1, the Manchester benchmark's right wheel
/// at 7.5 mm): UN = PEN - h where the pressure is positive, UN > PEN - h
/// elsewhere, on the patch's grid.
#[test]
fn a_wheel_rail_patch_has_the_approach_minus_the_gap_in_contact() {
    let ire = 751;
    let (ierror, _) = common::mbench_right_wheel(ire, 7.5, None);
    assert_eq!(ierror, 0);
    let (mut mx, mut my) = (0, 0);
    unsafe { cntc_getnumelements(&ire, &1, &mut mx, &mut my) };
    let n = (mx * my) as usize;
    let [un, _, _] = displacements(ire, 1, n);
    let pen = penetration(ire, 1);
    let h = field_data(ire, 1, n, field::H);
    let pn = field_data(ire, 1, n, field::PN);
    let mut worst = 0.0f64;
    for i in 0..n {
        if pn[i] > 0.0 {
            worst = worst.max((un[i] - (pen - h[i])).abs() / pen);
        } else {
            assert!(un[i] > pen - h[i], "element {i}");
        }
    }
    eprintln!("module 1: |UN - (PEN - h)| <= {worst:.1e} PEN in contact");
    assert!(worst < 1e-6, "{worst:e}");
}

/// FASTSIM on a wheel/rail patch (module 1, M = 2 and 3): UX, UY are
/// FLX(1:2)/K_EFF times the tractions, as CONTACT's, and UN the exact
/// normal problem's (PEN - h in contact). CONTACT's library (the revision
/// above, driven with ctypes through the same calls: python_mbench.py's
/// set-up of wheel `iwhe`, no wheelset flexibility, 2 m/s; printed with
/// `%.10g` by crates/cntc/bench/given_flexibility_cases.py, "m1 disp") on its own grid of the patch (47 x 52, 83 x 11 elements; ours
/// are larger, so the extremes are compared): per case the largest UN and
/// the extremes of UX and UY [mm].
#[test]
fn fastsim_wheel_rail_patches_match_contact() {
    struct Case {
        ire: i32,
        iwhe: i32,
        mater: i32,
        params: &'static [f64],
        pos: [f64; 6],
        vpitch: f64,
        /// UN max, UX min, UX max, UY min, UY max.
        contact: [f64; 5],
    }
    let tread = [0.0, 2.0, 0.0, -0.0001128, 0.0048, 0.0];
    let flange = [0.0, 7.5, 0.0, -0.007642, 0.018, 0.0];
    let cases = [
        // python_mbench.py case 5 of wheel 1, M = 3, no slope reduction.
        Case {
            ire: 761,
            iwhe: 1,
            mater: 3,
            params: &[0.28, 0.28, 82000.0, 82000.0, 1.0, 1.0, 1.0],
            pos: tread,
            vpitch: -4.3459197,
            contact: [0.02054395024, 0.0, 0.000707217727, -0.003831495237, 0.0],
        },
        // Case 16 of wheel 2 (flange), M = 3 with tractcurv's slope
        // reduction.
        Case {
            ire: 762,
            iwhe: 2,
            mater: 3,
            params: &[0.28, 0.28, 82000.0, 82000.0, 0.54, 0.02, 0.62],
            pos: flange,
            vpitch: -4.2575747,
            contact: [0.0352201402, -0.08414146435, 0.0, -0.1578407044, 0.0],
        },
        // Case 5 of wheel 1, M = 2: FLX 1.5e-4 mm^3/N with that reduction.
        Case {
            ire: 763,
            iwhe: 1,
            mater: 2,
            params: &[0.28, 0.28, 82000.0, 82000.0, 1.5e-4, 0.54, 0.02, 0.62],
            pos: tread,
            vpitch: -4.3459197,
            contact: [0.02050089078, 0.0, 0.005332112935, -0.02876683564, 0.0],
        },
    ];
    for c in cases {
        let ire = c.ire;
        let (mut mx, mut my) = (0, 0);
        unsafe {
            common::mbench_wheel(ire, c.iwhe, 1, 0);
            cntc_setwheelsetflexibility(&ire, &1, &12, [0.0; 12].as_ptr());
            let n = c.params.len() as i32;
            cntc_setmaterialparameters(&ire, &-1, &c.mater, &n, c.params.as_ptr());
            cntc_setwheelsetposition(&ire, &2, &6, c.pos.as_ptr());
            let vel = [2000.0, 0.0, 0.0, 0.0, 0.0, c.vpitch];
            cntc_setwheelsetvelocity(&ire, &2, &6, vel.as_ptr());
            let mut ierror = -1;
            cntc_calculate1(&ire, &mut ierror);
            assert_eq!(ierror, 0, "ire {ire}");
            cntc_getnumelements(&ire, &1, &mut mx, &mut my);
        }
        let n = (mx * my) as usize;
        let [un, ux, uy] = displacements(ire, 1, n);
        let [pn, px, py] = [field::PN, field::PX, field::PY].map(|f| field_data(ire, 1, n, f));
        // FLX(1:2) [mm^3/N] and K_EFF of the patch (cntc_getparameters
        // task 2, values 8, 9 and 14).
        let mut v = [0.0; 30];
        unsafe { cntc_getparameters(&ire, &1, &2, &30, v.as_mut_ptr()) };
        let (l1, l2) = (v[7] / v[13], v[8] / v[13]);
        let (pen, h) = (penetration(ire, 1), field_data(ire, 1, n, field::H));
        for i in 0..n {
            close(&format!("ire {ire} UX({i})"), ux[i], l1 * px[i], 1e-12);
            close(&format!("ire {ire} UY({i})"), uy[i], l2 * py[i], 1e-12);
            if pn[i] > 0.0 {
                close(&format!("ire {ire} UN({i})"), un[i], pen - h[i], 1e-6 * pen);
            }
        }
        let max = |u: &[f64]| u.iter().fold(f64::MIN, |m, &x| m.max(x));
        let min = |u: &[f64]| u.iter().fold(f64::MAX, |m, &x| m.min(x));
        let ours = [max(&un), min(&ux), max(&ux), min(&uy), max(&uy)];
        eprintln!(
            "ire {ire}: UN max, UX min/max, UY min/max {ours:?}, CONTACT's {:?}",
            c.contact
        );
        // Within 0.5 % of each component's largest size: the patches'
        // tractions lie that close to CONTACT's (UX at the flange's gauge
        // side 0.31 % apart, the others within 0.11 %).
        for (k, (o, t)) in ours.iter().zip(c.contact).enumerate() {
            let size = if k == 0 {
                c.contact[0]
            } else if k < 3 {
                c.contact[1].abs().max(c.contact[2].abs())
            } else {
                c.contact[3].abs().max(c.contact[4].abs())
            };
            close(&format!("ire {ire} extreme {k}"), *o, t, 5e-3 * size);
        }
        unsafe { cntc_finalize(&ire) };
    }
}
