//! The interfacial (third-body) layer (`core::layer`, CONTACT's material
//! model M = 4, issue 42) against CONTACT's printed results.
//!
//! CONTACT: the open-source program (github.com/eve70a/CONTACT, commit
//! d431cdb, revision 2707, 2025-07-23). Its reference outputs are the
//! shipped `*.ref_out` files (written by the official build); the
//! contact-kit build (`/work/shared/contact-kit`) reproduces
//! `examples/plastic_3bl.ref_out` line by line (its README). Every number
//! is compared within half a unit of the last digit CONTACT prints (the
//! tolerance comes from the printed string itself, [`printed`]).
//!
//! * `examples/plastic_3bl` (user guide §5.12, "Shear stiffness of one
//!   element with an interfacial layer"): transient shift steps of one
//!   element of 1 x 1 mm under FN = 900 N, mu = 0.7, G = 82000 N/mm² and
//!   nu = 0.28 for both bodies; case 1 without a layer, then four series
//!   (a new sequence each, P = 2) of an elastic-perfectly plastic
//!   magnetite layer (cases 2-14), hardening clay with unloading and
//!   reloading (15-31), softening sand (32-44) and slightly hardening
//!   MoS2 (45-57). The plastic deformation is the history between the
//!   steps.
//! * `testbank/examples_plast/carter_plast` (steady rolling, 2D Carter
//!   with plasticity at the surface, h = 0).

use railcontact_solver::core::cache::KernelCache;
use railcontact_solver::core::grid::Grid;
use railcontact_solver::core::layer::InterfacialLayer;
use railcontact_solver::core::material::{CombinedMaterial, Material};
use railcontact_solver::core::normal::NormalLoad;
use railcontact_solver::core::problem::{
    ContactProblem, Friction, Kinematics, ShiftStep, SolverSettings,
};
use railcontact_solver::core::solution::{ContactSolution, ElementState, SolveStatus};
use railcontact_solver::core::solve::ContactSolver;

use crate::printed;

/// CONTACT's units: mm, N/mm² (= 1e6 Pa), N/mm³ (= 1e9 Pa/m).
const MM: f64 = 1e-3;
const N_PER_MM2: f64 = 1e6;
const N_PER_MM3: f64 = 1e9;

/// Checks `ours` (in CONTACT's unit) against CONTACT's printed `want`.
fn check(what: &str, ours: f64, want: &str) {
    check_near(what, ours, want, 0.0);
}

/// [`check`] with a stated model difference `rel` relative to CONTACT's
/// value on top of its printed digits.
fn check_near(what: &str, ours: f64, want: &str, rel: f64) {
    let (value, half) = printed(want);
    assert!(
        (ours - value).abs() <= half * (1.0 + 1e-9) + rel * value.abs(),
        "{what}: {ours} against CONTACT's {want}"
    );
}

/// `plastic_3bl.inp`: one element of 1 x 1 mm (MX = MY = 1, the Hertzian
/// semi-axes 0.5 mm, IPOTCN = -3), FN = 900 N, FSTAT = FKIN = 0.7, POISS
/// 0.28, GG 82000 N/mm², EPS 1e-6. Our grids have at least 4 x 4
/// elements: the element is the centre of 5 x 5 under CONTACT's Hertzian
/// undeformed distance, whose other elements stay out of contact (0.02371
/// mm at the nearest centres against the approach of 8.868e-3 mm), so the
/// only loaded element sees its own influence coefficients, as CONTACT's.
fn one_element(layer: Option<InterfacialLayer>, steps: Vec<ShiftStep>) -> ContactProblem {
    let grid = Grid::centered(5, 5, 5.0 * MM, 5.0 * MM).unwrap();
    ContactProblem {
        material: CombinedMaterial::identical(Material {
            shear_modulus_pa: 82000.0 * N_PER_MM2,
            poisson_ratio: 0.28,
        })
        .unwrap(),
        friction: Friction::coulomb(0.7),
        // The Hertzian curvature A = B = 0.02371 /mm ("THE CURVATURES
        // A1,B1"): zero at the centre.
        gap_m: ContactProblem::quadratic_gap(&grid, 0.02371 / MM, 0.02371 / MM),
        grid,
        load: NormalLoad::NormalForce(900.0),
        kinematics: Kinematics::Transient(steps),
        settings: SolverSettings {
            interfacial_layer: layer,
            ..SolverSettings::default()
        },
        rolling_direction_rad: 0.0,
        extra_rigid_slip: None,
        numerical_influence: None,
    }
}

/// The loaded element's index in the 5 x 5 grid.
const CENTRE: usize = 12;

/// A layer in CONTACT's units: GG3 \[N/mm²\], LAYTHK \[mm\], TAU_C0
/// \[N/mm²\], K_TAU \[N/mm³\].
fn layer(gg3: f64, laythk: f64, tau_c0: f64, k_tau: f64) -> InterfacialLayer {
    InterfacialLayer {
        thickness_m: laythk * MM,
        shear_modulus_pa: gg3 * N_PER_MM2,
        yield_limit_pa: tau_c0 * N_PER_MM2,
        hardening_pa_per_m: k_tau * N_PER_MM3,
    }
}

/// One case of `plastic_3bl.ref_out`: CKSI (the shift of the step [mm],
/// from the input), and as printed FX \[N\], FRIC.WORK \[N mm\] and the
/// CONTACT STATISTICS' NADH, NSLIP, NPLAST.
struct Case {
    cksi: f64,
    fx: &'static str,
    work: &'static str,
    adh_slip_plast: [usize; 3],
}

const fn case(cksi: f64, fx: &'static str, work: &'static str, adh_slip_plast: [usize; 3]) -> Case {
    Case {
        cksi,
        fx,
        work,
        adh_slip_plast,
    }
}

const ADH: [usize; 3] = [1, 0, 0];
const PLAST: [usize; 3] = [0, 0, 1];

/// Series 1, cases 2-14: magnetite, GG3 176.63, LAYTHK 0.020, TAU_C0 560,
/// K_TAU 0 (elastic-perfectly plastic).
const MAGNETITE: [Case; 13] = [
    case(-0.035, "280.0", "0.000", ADH),
    case(-0.035, "560.0", "0.000", ADH),
    case(-0.030, "560.0", "-1.680E-02", PLAST),
    case(-0.050, "560.0", "-2.800E-02", PLAST),
    case(-0.050, "560.0", "-2.800E-02", PLAST),
    case(-0.050, "560.0", "-2.800E-02", PLAST),
    case(-0.050, "560.0", "-2.800E-02", PLAST),
    case(-0.050, "560.0", "-2.800E-02", PLAST),
    case(-0.050, "560.0", "-2.800E-02", PLAST),
    case(-0.050, "560.0", "-2.800E-02", PLAST),
    case(-0.050, "560.0", "-2.800E-02", PLAST),
    case(-0.050, "560.0", "-2.800E-02", PLAST),
    case(-0.050, "560.0", "-2.800E-02", PLAST),
];

/// Series 2, cases 15-31: clay, GG3 106.25, LAYTHK 0.020, TAU_C0 200,
/// K_TAU 435 (hardening), unloaded in cases 20-22 and loaded again.
const CLAY: [Case; 17] = [
    case(-0.040, "200.0", "0.000", ADH),
    case(-0.040, "216.0", "-7.949E-03", PLAST),
    case(-0.040, "232.0", "-8.538E-03", PLAST),
    case(-0.040, "248.0", "-9.127E-03", PLAST),
    case(-0.036, "262.4", "-8.691E-03", PLAST),
    case(0.000, "262.4", "0.000", ADH),
    case(0.036, "82.43", "0.000", ADH),
    case(0.000, "82.43", "0.000", ADH),
    case(-0.046, "266.4", "-2.451E-03", PLAST),
    case(-0.044, "284.0", "-1.150E-02", PLAST),
    case(-0.050, "304.0", "-1.399E-02", PLAST),
    case(-0.050, "324.1", "-1.491E-02", PLAST),
    case(-0.050, "344.1", "-1.583E-02", PLAST),
    case(-0.050, "364.1", "-1.675E-02", PLAST),
    case(-0.050, "384.1", "-1.767E-02", PLAST),
    case(-0.050, "404.1", "-1.859E-02", PLAST),
    case(-0.050, "424.1", "-1.951E-02", PLAST),
];

/// Series 3, cases 32-44: sand, GG3 176.63, LAYTHK 0.020, TAU_C0 400,
/// K_TAU -195 (softening).
const SAND: [Case; 13] = [
    case(-0.025, "200.0", "0.000", ADH),
    case(-0.025, "400.0", "0.000", ADH),
    case(-0.050, "390.0", "-1.999E-02", PLAST),
    case(-0.050, "380.0", "-1.948E-02", PLAST),
    case(-0.050, "370.0", "-1.896E-02", PLAST),
    case(-0.050, "360.0", "-1.845E-02", PLAST),
    case(-0.050, "350.0", "-1.794E-02", PLAST),
    case(-0.050, "340.0", "-1.743E-02", PLAST),
    case(-0.050, "330.0", "-1.691E-02", PLAST),
    case(-0.050, "320.1", "-1.640E-02", PLAST),
    case(-0.050, "310.1", "-1.589E-02", PLAST),
    case(-0.050, "300.1", "-1.538E-02", PLAST),
    case(-0.050, "290.1", "-1.487E-02", PLAST),
];

/// Series 4, cases 45-57: MoS2, GG3 20.238, LAYTHK 0.020, TAU_C0 20,
/// K_TAU 20.4.
const MOS2: [Case; 13] = [
    case(-0.020, "20.00", "0.000", ADH),
    case(-0.040, "20.80", "-8.154E-04", PLAST),
    case(-0.040, "21.60", "-8.467E-04", PLAST),
    case(-0.050, "22.60", "-1.107E-03", PLAST),
    case(-0.050, "23.60", "-1.156E-03", PLAST),
    case(-0.050, "24.60", "-1.205E-03", PLAST),
    case(-0.050, "25.60", "-1.254E-03", PLAST),
    case(-0.050, "26.60", "-1.303E-03", PLAST),
    case(-0.050, "27.60", "-1.352E-03", PLAST),
    case(-0.050, "28.60", "-1.401E-03", PLAST),
    case(-0.050, "29.60", "-1.450E-03", PLAST),
    case(-0.050, "30.60", "-1.499E-03", PLAST),
    case(-0.050, "31.60", "-1.548E-03", PLAST),
];

fn shift(cksi: f64) -> ShiftStep {
    ShiftStep {
        load: NormalLoad::NormalForce(900.0),
        shift_x_m: cksi * MM,
        shift_y_m: 0.0,
        rotation_rad: 0.0,
        rolling_m: 0.0,
    }
}

/// Adhesion (not flowing), slip and plastic (flowing without slip)
/// elements, as CONTACT's NADH, NSLIP and NPLAST.
fn counts(solver: &ContactSolver, s: &ContactSolution) -> [usize; 3] {
    let plastic = solver
        .layer_fields()
        .map_or(vec![false; s.fields.state.len()], |f| f.plastic);
    let n = |st: ElementState, p: bool| {
        (0..plastic.len())
            .filter(|&i| s.fields.state[i] == st && plastic[i] == p)
            .count()
    };
    [
        n(ElementState::Adhesion, false),
        n(ElementState::Slip, false),
        n(ElementState::Adhesion, true),
    ]
}

/// Runs one series of `plastic_3bl` as one transient sequence.
fn run_series(name: &str, first_case: usize, layer: InterfacialLayer, cases: &[Case]) {
    let cache = KernelCache::new(64 << 20);
    let p = one_element(Some(layer), cases.iter().map(|c| shift(c.cksi)).collect());
    let mut solver = ContactSolver::new(&p, &cache);
    // Step by step (ContactSolver::solve of `p` would give the same
    // solutions) to read the layer's state after each.
    for (k, c) in cases.iter().enumerate() {
        let what = format!("{name}, case {}", first_case + k);
        let s = solver.solve_next_step(&p, &shift(c.cksi)).unwrap();
        assert_eq!(
            s.info.status,
            SolveStatus::Converged,
            "{what}: {:?}",
            s.info
        );
        let f = solver.layer_fields().expect("a plastic layer has fields");
        let (tau_c, u_pl) = (f.yield_limit_pa[CENTRE], f.plastic_x_m[CENTRE]);
        eprintln!(
            "{what}: FX {:.4} N (CONTACT {}), work {:.4e} J (CONTACT {}), tau_c {:.4} N/mm², \
             u_pl {:.5e} mm",
            s.totals.fx_n,
            c.fx,
            -s.totals.frictional_work_j,
            c.work,
            tau_c / N_PER_MM2,
            u_pl / MM,
        );
        check(&format!("{what}: FX"), s.totals.fx_n, c.fx);
        // CONTACT's FRIC.WORK is the frictional power [W] (user guide,
        // "FRIC"), VELOC / 1000 dx dy sum p . s with s the slip per unit
        // rolled distance; of a shift step with VELOC = 1 mm/s and DT = 1 s
        // (printed): the work on the interface in the step, -(the
        // dissipation) [J].
        check(
            &format!("{what}: FRIC.WORK"),
            -s.totals.frictional_work_j,
            c.work,
        );
        assert_eq!(
            counts(&solver, &s),
            c.adh_slip_plast,
            "{what}: adhesion, slip, plastic"
        );
        // The layer's state: the flowing element's traction is its
        // yield limit (FX on 1 mm²), and every series flows in +x only
        // (unloading stays elastic), so the accumulated plastic
        // deformation is u_pl and tau_c = tau_c0 + k_tau u_pl.
        if c.adh_slip_plast == PLAST {
            check(&format!("{what}: TAUCRT"), tau_c / N_PER_MM2, c.fx);
        }
        assert!(u_pl >= 0.0, "{what}: u_pl {u_pl} m");
        let hardened = layer.yield_limit_pa + layer.hardening_pa_per_m * u_pl;
        assert!(
            (tau_c - hardened).abs() <= 1e-9 * layer.yield_limit_pa,
            "{what}: tau_c {tau_c} Pa against tau_c0 + k_tau u_pl = {hardened} Pa"
        );
    }
}

#[test]
fn one_element_without_a_layer_matches_plastic_3bl_case_1() {
    // Case 1: CKSI -0.001 mm, no layer (M = 0): FX 84.97 N, adhesion.
    let cache = KernelCache::new(64 << 20);
    let p = one_element(None, vec![shift(-0.001)]);
    let mut solver = ContactSolver::new(&p, &cache);
    let s = solver.solve_next_step(&p, &shift(-0.001)).unwrap();
    check("case 1: FX", s.totals.fx_n, "84.97");
    assert_eq!(counts(&solver, &s), ADH);
}

#[test]
fn a_perfectly_plastic_magnetite_layer_matches_plastic_3bl() {
    run_series("magnetite", 2, layer(176.63, 0.020, 560.0, 0.0), &MAGNETITE);
}

#[test]
fn a_hardening_clay_layer_unloaded_and_reloaded_matches_plastic_3bl() {
    run_series("clay", 15, layer(106.25, 0.020, 200.0, 435.0), &CLAY);
}

#[test]
fn a_softening_sand_layer_matches_plastic_3bl() {
    run_series("sand", 32, layer(176.63, 0.020, 400.0, -195.0), &SAND);
}

#[test]
fn a_mos2_layer_matches_plastic_3bl() {
    run_series("MoS2", 45, layer(20.238, 0.020, 20.0, 20.4), &MOS2);
}

/// `testbank/examples_plast/carter_plast`: Carter's 2-D problem in steady
/// rolling with plasticity at the surface (LAYTHK = 0: no layer's
/// flexibility, "the tangential plasticity feature of CONTACT without
/// using a third body layer"), the yield limit TAU_C0 = 35 N/mm² hardening
/// or softening with K_TAU = G k_rel / (1 - k_rel) for k_rel = 0.98, 0.6,
/// 0 and -0.333 (the input's comment), on three grids. FN = 35780 N over
/// DY = 200 mm (CONTACT's 2-D mode: one row of elements across the
/// length DY; forces over DY are forces per metre here, as in
/// `line_contact`), h = 0.001 x² /mm (IBASE 1, B1), CKSI = -0.0004, mu =
/// 0.5, G = 82000 N/mm², nu = 0.28, DQ = DX, EPS 1e-5.
mod carter_plast {
    use super::*;
    use railcontact_solver::core::problem::Creepages;

    /// Grid (MX, XC1 the first element's centre \[mm\], DX \[mm\]).
    const GRIDS: [(usize, f64, f64); 3] =
        [(30, -1.16, 0.08), (55, -1.08, 0.04), (105, -1.04, 0.02)];

    /// K_TAU \[N/mm³\] of the four cases of each grid.
    const K_TAU: [f64; 4] = [4018000.0, 123000.0, 0.0, -20500.0];

    /// Printed, cases 1-12 (grid by grid, K_TAU in the order above): FX
    /// \[N\], FX/FSTAT/FN, FRIC.POWER \[W\], PMAX \[N/mm²\] and the CONTACT
    /// STATISTICS' NCON, NADH, NSLIP, NPLAST.
    #[allow(clippy::type_complexity)]
    const PRINTED: [(&str, &str, &str, &str, [usize; 4]); 12] = [
        ("1.174E+04", "0.6562", "-127.6", "113.8", [26, 12, 11, 3]),
        ("1.149E+04", "0.6420", "-126.2", "113.8", [26, 11, 8, 7]),
        ("1.066E+04", "0.5959", "-119.0", "113.8", [26, 9, 4, 13]),
        ("9856.", "0.5509", "-111.1", "113.8", [26, 8, 3, 15]),
        ("1.159E+04", "0.6478", "-132.4", "113.9", [51, 25, 21, 5]),
        ("1.134E+04", "0.6340", "-130.2", "113.9", [51, 22, 15, 14]),
        ("1.055E+04", "0.5896", "-122.0", "113.9", [51, 19, 7, 25]),
        ("9762.", "0.5457", "-113.5", "113.9", [51, 17, 4, 30]),
        ("1.151E+04", "0.6436", "-134.8", "113.9", [101, 52, 41, 8]),
        ("1.127E+04", "0.6299", "-132.3", "113.9", [101, 46, 29, 26]),
        ("1.049E+04", "0.5864", "-123.6", "113.9", [101, 39, 12, 50]),
        ("9715.", "0.5430", "-114.7", "113.9", [101, 34, 5, 62]),
    ];

    /// Our difference from CONTACT allowed beyond its printed digits,
    /// relative: two causes, measured with CONTACT's program (the
    /// contact-kit build, `contact_linux64 2 carter_plast`, which prints
    /// the `.ref_out`'s numbers; its detailed output `.mat` of cases 2, 7,
    /// 9 and 12 gives six digits an element). (1) Its 2-D mode is a strip
    /// of its 3-D influence coefficients 200 mm long, ours plane strain:
    /// the pressures differ by up to 9e-4 at the patch's edges (case 2,
    /// element 3: 7.5909 against our 7.5975 N/mm²), so FX differs though
    /// the tangential solution follows the pressures element by element
    /// (case 2, element 10: PX = TAUCRT = 50.6792 N/mm² against our
    /// 50.67977; UPLSX 1.27473e-4 mm against 1.27477e-4). (2) Its iteration
    /// tolerance EPS 1e-5: FX summed from the `.mat` of case 12 (softening)
    /// is 9714.77 N, with EPS 1e-10 9713.89 N (9e-5 apart; ours 9714.11
    /// N); case 2 11486.09 and 11486.06 N (ours 11486.37 N, the 2.7e-5 of
    /// cause 1).
    const LINE_MODEL: f64 = 1e-4;

    /// DY [m]: CONTACT's forces are over it.
    const DY: f64 = 0.2;

    /// CONTACT's VELOC, 30000 mm/s \[m/s\].
    const VELOC: f64 = 30.0;

    fn problem(grid: (usize, f64, f64), k_tau: f64) -> ContactProblem {
        let (mx, xc1, dx) = grid;
        let grid = Grid::line_from(mx, dx * MM, (xc1 - 0.5 * dx) * MM).unwrap();
        ContactProblem {
            material: CombinedMaterial::identical(Material {
                shear_modulus_pa: 82000.0 * N_PER_MM2,
                poisson_ratio: 0.28,
            })
            .unwrap(),
            friction: Friction::coulomb(0.5),
            gap_m: ContactProblem::quadratic_gap(&grid, 0.001 / MM, 0.0),
            grid,
            load: NormalLoad::NormalForce(35780.0 / DY),
            kinematics: Kinematics::SteadyRolling(Creepages {
                creepage_long: -0.0004,
                creepage_lat: 0.0,
                spin_per_m: 0.0,
            }),
            settings: SolverSettings {
                interfacial_layer: Some(layer(82000.0, 0.0, 35.0, k_tau)),
                ..SolverSettings::default()
            },
            rolling_direction_rad: 0.0,
            extra_rigid_slip: None,
            numerical_influence: None,
        }
    }

    #[test]
    fn steady_rolling_with_plasticity_at_the_surface_matches_carter_plast() {
        let cache = KernelCache::new(64 << 20);
        for (g, &grid) in GRIDS.iter().enumerate() {
            for (k, &k_tau) in K_TAU.iter().enumerate() {
                let case = 4 * g + k + 1;
                let (fx, fx_rel, power, pmax, stats) = PRINTED[case - 1];
                let p = problem(grid, k_tau);
                let mut solver = ContactSolver::new(&p, &cache);
                let s = solver.solve(&p).unwrap().pop().unwrap();
                let what = format!("carter_plast case {case} (K_TAU {k_tau})");
                let plastic = solver.layer_fields().expect("a plastic layer").plastic;
                let st = &s.fields.state;
                let n = |e: ElementState, pl: bool| {
                    (0..st.len())
                        .filter(|&i| st[i] == e && plastic[i] == pl)
                        .count()
                };
                let ncon = s.fields.pressure_pa.iter().filter(|&&p| p > 0.0).count();
                let ours = [
                    ncon,
                    n(ElementState::Adhesion, false),
                    n(ElementState::Slip, false),
                    n(ElementState::Adhesion, true),
                ];
                let t = &s.totals;
                eprintln!(
                    "{what}: FX {:.2} N (CONTACT {fx}), FX/mu/FN {:.5} ({fx_rel}), power {:.2} W \
                     ({power}), pmax {:.2} ({pmax}), counts {ours:?} ({stats:?}), {} iterations",
                    t.fx_n * DY,
                    t.fx_n / (0.5 * t.normal_force_n),
                    -t.tgamma_n * DY * VELOC,
                    t.max_pressure_pa / N_PER_MM2,
                    s.info.tangential_iterations,
                );
                assert_eq!(
                    s.info.status,
                    SolveStatus::Converged,
                    "{what}: {:?}",
                    s.info
                );
                let near = |name: &str, ours: f64, want: &str| {
                    check_near(&format!("{what}: {name}"), ours, want, LINE_MODEL)
                };
                near("FX", t.fx_n * DY, fx);
                near("FX/FSTAT/FN", t.fx_n / (0.5 * t.normal_force_n), fx_rel);
                // FRIC.POWER = VELOC dx dy sum p . s (user guide, "FRIC"):
                // -(T gamma) times the rolling speed.
                near("FRIC.POWER", -t.tgamma_n * DY * VELOC, power);
                near("PMAX", t.max_pressure_pa / N_PER_MM2, pmax);
                eprintln!(
                    "  relative to CONTACT: FX {:.1e}, FX/FSTAT/FN {:.1e}, power {:.1e}, pmax {:.1e}",
                    t.fx_n * DY / printed(fx).0 - 1.0,
                    t.fx_n / (0.5 * t.normal_force_n) / printed(fx_rel).0 - 1.0,
                    -t.tgamma_n * DY * VELOC / printed(power).0 - 1.0,
                    t.max_pressure_pa / N_PER_MM2 / printed(pmax).0 - 1.0,
                );
                assert_eq!(ours, stats, "{what}: contact, adhesion, slip, plastic");
            }
        }
    }
}
