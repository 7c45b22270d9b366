//! Transient rolling against Vollebregt's CONTACT: the onset of rolling
//! "from Cattaneo to Carter" (Kalker 1990, §5.2.2.5, fig. 5.25), the
//! `catt_to_cart` example of CONTACT (github.com/eve70a/CONTACT,
//! `examples/catt_to_cart.inp` and `examples/catt_to_cart.ref_out`, commit
//! 424e4e6, revision 2356, 2023-05-10). Case 1 is a Cattaneo shift from
//! rest, cases 2-57 roll one element (dq = dx = 0.25 mm) per step in moving
//! coordinates from the tractions of case 1. Cases 58-114 repeat them in
//! world-fixed coordinates: shift steps on a longer grid in which the
//! undeformed distance moves one element a step with the bodies.
//!
//! CONTACT prescribes Fx/(mu Fn) = -0.657 in every case and reports the
//! shift (case 1) or creepage (cases 2-57) that gives it, printed to four
//! digits. We prescribe those printed shifts and creepages for cases 1-57
//! (and 58-75) and compare our Fx/(mu Fn) with -0.657 (within 1 %), and
//! our contact, adhesion and slip element counts with CONTACT's (exact but
//! for one step with ties, see `check_counts`).
//!
//! CONTACT's test bank case 17 rolls the same bodies two elements in one
//! step: the leading-edge correction of steps of several elements
//! (`railcontact_solver::core::leading_edge`).

use railcontact_solver::core::cache::KernelCache;
use railcontact_solver::core::force::{solve_prescribed_force_step, PrescribedForce};
use railcontact_solver::core::grid::Grid;
use railcontact_solver::core::material::{CombinedMaterial, Material};
use railcontact_solver::core::normal::NormalLoad;
use railcontact_solver::core::problem::{
    ContactProblem, Creepages, Friction, Kinematics, ShiftStep, SolverSettings,
};
use railcontact_solver::core::solution::{ContactSolution, ElementState, SolveStatus};
use railcontact_solver::core::solve::ContactSolver;

/// CONTACT's units: mm and N/mm² (GG = 1 N/mm² = 1e6 Pa).
const MM: f64 = 1e-3;

/// Fx/(mu Fn) prescribed in every case of `catt_to_cart.inp` (FX = -0.657).
const FX_OVER_MU_FN: f64 = -0.657;

/// `catt_to_cart.ref_out`, case 1: "SHIFT X 1.774E-02" \[mm\].
const CASE_1_SHIFT_MM: f64 = 1.774e-2;

/// `catt_to_cart.ref_out`, cases 2 to 57: "CREEP X" of each case [-].
const CREEPAGE: [f64; 56] = [
    1.824e-3, 1.882e-3, 1.955e-3, 2.050e-3, 2.140e-3, 2.221e-3, 2.334e-3, 2.428e-3, 2.551e-3,
    2.676e-3, 2.801e-3, 2.968e-3, 3.184e-3, 3.403e-3, 3.402e-3, 3.334e-3, 3.241e-3, 3.192e-3,
    3.123e-3, 3.112e-3, 3.088e-3, 3.072e-3, 3.064e-3, 3.062e-3, 3.064e-3, 3.070e-3, 3.077e-3,
    3.085e-3, 3.093e-3, 3.101e-3, 3.107e-3, 3.111e-3, 3.111e-3, 3.110e-3, 3.107e-3, 3.105e-3,
    3.103e-3, 3.101e-3, 3.100e-3, 3.099e-3, 3.099e-3, 3.099e-3, 3.099e-3, 3.099e-3, 3.100e-3,
    3.100e-3, 3.100e-3, 3.101e-3, 3.101e-3, 3.101e-3, 3.101e-3, 3.101e-3, 3.101e-3, 3.101e-3,
    3.101e-3, 3.101e-3,
];

/// `catt_to_cart.ref_out`, cases 1 to 57: adhesion elements of "Tang: final
/// element division: A, S="; every case has 621 elements in contact
/// ("Norm: final element division: C, E= 621 468") and 621 - A in slip.
const ADHESION: [usize; 57] = [
    305, 422, 420, 416, 406, 405, 395, 390, 382, 375, 365, 352, 346, 323, 319, 330, 328, 341, 341,
    343, 348, 348, 350, 350, 350, 348, 348, 348, 346, 346, 346, 346, 346, 346, 346, 346, 346, 346,
    346, 346, 346, 346, 346, 346, 346, 346, 346, 346, 346, 346, 346, 346, 346, 346, 346, 346, 346,
];

/// CONTACT's contact elements in every case.
const CONTACT_ELEMENTS: usize = 621;

/// `catt_to_cart.inp`, case 1: 33 x 33 elements of 0.25 mm from (-4.125,
/// -4.125) mm, h = 0.002963 (x² + y²) /mm, G = 1 N/mm², nu = 0.28 both,
/// Fn = 0.4705 N, mu = 0.4013 (static and kinetic), tolerance 1e-7.
fn problem() -> ContactProblem {
    let grid = Grid::new(33, 33, 0.25 * MM, 0.25 * MM, -4.125 * MM, -4.125 * MM).unwrap();
    let curvature = 0.002963 / MM;
    ContactProblem {
        material: CombinedMaterial::identical(Material {
            shear_modulus_pa: 1e6,
            poisson_ratio: 0.28,
        })
        .unwrap(),
        friction: Friction::coulomb(0.4013),
        gap_m: ContactProblem::quadratic_gap(&grid, curvature, curvature),
        grid,
        load: NormalLoad::NormalForce(0.4705),
        kinematics: Kinematics::Transient(Vec::new()),
        settings: SolverSettings::default(),
        rolling_direction_rad: 0.0,
        extra_rigid_slip: None,
        numerical_influence: None,
    }
}

fn counts(s: &ContactSolution) -> [usize; 3] {
    let n = |st: ElementState| s.fields.state.iter().filter(|&&e| e == st).count();
    let contact = s.fields.pressure_pa.iter().filter(|&&p| p > 0.0).count();
    [contact, n(ElementState::Adhesion), n(ElementState::Slip)]
}

/// Checks our contact, adhesion and slip elements of `case` against
/// CONTACT's 621 and `want` adhesion elements; returns whether the counts
/// are equal. Tied elements are in slip with a slip distance below 1e-3 of
/// the median of the case: on the border between adhesion and slip, which
/// either side may count. CONTACT's count must lie between ours and ours
/// plus the ties. Ties (1 to 4 elements) occur in cases 8, 11, 12 and 13
/// and their world-fixed twins 65, 68, 69 and 70; CONTACT counts them as
/// slip, as we do, except in case 12 (four elements, two pairs symmetric
/// in y slipping 5e-11 m and 2.3e-10 m in the step, 4e-5 and 2e-4 of the
/// median: all four adhesion in CONTACT) and case 69 (two of them).
fn check_counts(case: usize, s: &ContactSolution, want: usize) -> bool {
    let [contact, adhesion, slip] = counts(s);
    assert_eq!(contact, CONTACT_ELEMENTS, "case {case}: contact elements");
    let mut slips: Vec<f64> = (0..s.fields.state.len())
        .filter(|&i| s.fields.state[i] == ElementState::Slip)
        .map(|i| s.fields.slip_x[i].hypot(s.fields.slip_y[i]))
        .collect();
    slips.sort_by(f64::total_cmp);
    let median = slips[slips.len() / 2];
    let tied = slips.iter().filter(|&&m| m < 1e-3 * median).count();
    assert!(
        (adhesion..=adhesion + tied).contains(&want) && adhesion + slip == CONTACT_ELEMENTS,
        "case {case}: adhesion / slip {adhesion} / {slip} ({tied} tied) against CONTACT's \
         {want} / {}",
        CONTACT_ELEMENTS - want
    );
    adhesion == want
}

#[test]
fn onset_of_rolling_matches_contact_catt_to_cart() {
    let p = problem();
    let load = p.load;
    let dq = p.grid.dx_m;
    let mut steps = vec![ShiftStep {
        load,
        shift_x_m: CASE_1_SHIFT_MM * MM,
        shift_y_m: 0.0,
        rotation_rad: 0.0,
        rolling_m: 0.0,
    }];
    for &xi in &CREEPAGE {
        let c = Creepages {
            creepage_long: xi,
            ..Creepages::default()
        };
        steps.push(ShiftStep::rolling(load, dq, &c));
    }
    let p = ContactProblem {
        kinematics: Kinematics::Transient(steps),
        ..p
    };
    let sols = ContactSolver::new(&p, &KernelCache::default())
        .solve(&p)
        .unwrap();
    let mu = p.friction.kinetic_coefficient;
    let mut worst: f64 = 0.0;
    for (k, s) in sols.iter().enumerate() {
        assert_eq!(s.info.status, SolveStatus::Converged, "case {}", k + 1);
        let f = s.totals.fx_n / (mu * s.totals.normal_force_n);
        let err = (f / FX_OVER_MU_FN - 1.0).abs();
        worst = worst.max(err);
        assert!(
            err < 0.01,
            "case {}: Fx/(mu Fn) {f:.4} against CONTACT's {FX_OVER_MU_FN}",
            k + 1
        );
    }
    eprintln!(
        "worst Fx/(mu Fn) difference over cases 1-57: {:.3} %",
        100.0 * worst
    );
    let differ: Vec<usize> = (0..sols.len())
        .filter(|&k| !check_counts(k + 1, &sols[k], ADHESION[k]))
        .map(|k| k + 1)
        .collect();
    assert_eq!(differ, [12], "cases whose counts differ (by ties)");
}

/// `catt_to_cart.ref_out`, cases 59 to 75: "SHIFT X" of each world-fixed
/// step \[mm\] (case 58 is case 1 on the longer grid).
const WORLD_SHIFT_MM: [f64; 17] = [
    4.548e-4, 4.705e-4, 4.886e-4, 5.125e-4, 5.349e-4, 5.552e-4, 5.835e-4, 6.069e-4, 6.377e-4,
    6.690e-4, 7.003e-4, 7.419e-4, 7.960e-4, 8.508e-4, 8.505e-4, 8.334e-4, 8.103e-4,
];

/// `catt_to_cart.ref_out`, cases 58 to 75: adhesion elements of "Tang:
/// final element division: A, S=", of 621 in contact.
const WORLD_ADHESION: [usize; 18] = [
    305, 422, 420, 416, 406, 405, 395, 390, 382, 375, 365, 350, 346, 323, 319, 330, 328, 341,
];

#[test]
fn world_fixed_steps_with_moving_geometry_match_contact_catt_to_cart() {
    // `catt_to_cart.inp`, cases 58-75: 90 x 33 elements from (-4.125,
    // -4.125) mm; case 58 at Fn = 0.4705 N, then the approach 0.07258 mm
    // and h = 0.002963 ((x - k dq)² + y²) /mm after k steps of dq = 0.25 mm
    // (its B(4), B(6)). The solver takes each step's own undeformed
    // distance; the tractions stay where they are on the grid.
    let base = problem();
    let grid = Grid::new(90, 33, 0.25 * MM, 0.25 * MM, -4.125 * MM, -4.125 * MM).unwrap();
    let curvature = 0.002963 / MM;
    let dq = grid.dx_m;
    let moved = |k: usize| {
        let mut h = ContactProblem::quadratic_gap(&grid, curvature, curvature);
        for iy in 0..grid.ny {
            for ix in 0..grid.nx {
                let x = grid.x_m(ix);
                let shifted = x - k as f64 * dq;
                h[grid.index(ix, iy)] += curvature * (shifted * shifted - x * x);
            }
        }
        h
    };
    let step = |load: NormalLoad, shift_mm: f64| ShiftStep {
        load,
        shift_x_m: shift_mm * MM,
        shift_y_m: 0.0,
        rotation_rad: 0.0,
        rolling_m: 0.0,
    };
    let mut p = ContactProblem {
        grid,
        gap_m: moved(0),
        kinematics: Kinematics::Transient(vec![step(base.load, CASE_1_SHIFT_MM)]),
        ..base
    };
    let mut solver = ContactSolver::new(&p, &KernelCache::default());
    let mut sols = vec![solver
        .solve_next_step(&p, &step(p.load, CASE_1_SHIFT_MM))
        .unwrap()];
    for (k, &shift_mm) in WORLD_SHIFT_MM.iter().enumerate() {
        p.gap_m = moved(k + 1);
        let load = NormalLoad::Approach(0.07258 * MM);
        sols.push(solver.solve_next_step(&p, &step(load, shift_mm)).unwrap());
    }
    let mu = p.friction.kinetic_coefficient;
    let mut worst: f64 = 0.0;
    let mut differ = Vec::new();
    for (k, s) in sols.iter().enumerate() {
        let case = 58 + k;
        assert_eq!(s.info.status, SolveStatus::Converged, "case {case}");
        // Fn: "FN 0.4705" in every case.
        let fn_err = (s.totals.normal_force_n / 0.4705 - 1.0).abs();
        let f = s.totals.fx_n / (mu * s.totals.normal_force_n);
        let err = (f / FX_OVER_MU_FN - 1.0).abs();
        worst = worst.max(err).max(fn_err);
        assert!(
            err < 0.01 && fn_err < 0.01,
            "case {case}: Fx/(mu Fn) {f:.4}, Fn {}",
            s.totals.normal_force_n
        );
        if !check_counts(case, s, WORLD_ADHESION[k]) {
            differ.push(case);
        }
    }
    eprintln!(
        "worst Fn, Fx/(mu Fn) difference over cases 58-75: {:.3} %",
        100.0 * worst
    );
    assert_eq!(differ, [69], "cases whose counts differ (by ties)");
}

/// CONTACT's `cattaneo` example, case 2 (github.com/eve70a/CONTACT,
/// `examples/cattaneo.inp` and `examples/cattaneo.ref_out`, commit
/// 424e4e6): a polyethylene ball (G = 200 N/mm², nu = 0.42 both, h = 0.01
/// (x² + y²) /mm) on 19 x 19 elements of 0.13333 mm from (-1.26667,
/// -1.26667) mm, pressed by Fn = 9.1954 N and shifted from the unloaded
/// state by the tangential force Fx = -0.875 mu Fn (mu = 0.4). CONTACT
/// finds "SHIFT X 8.155E-03" mm with 177 contact, 45 adhesion and 132 slip
/// elements ("NCON NADH NSLIP").
#[test]
fn prescribed_force_shift_matches_contact_cattaneo_case_2() {
    let d = 0.13333 * MM;
    let grid = Grid::new(19, 19, d, d, -1.26667 * MM, -1.26667 * MM).unwrap();
    let curvature = 0.01 / MM;
    let load = NormalLoad::NormalForce(9.1954);
    let step = ShiftStep {
        load,
        shift_x_m: 0.0,
        shift_y_m: 0.0,
        rotation_rad: 0.0,
        rolling_m: 0.0,
    };
    let problem = ContactProblem {
        material: CombinedMaterial::identical(Material {
            shear_modulus_pa: 200e6,
            poisson_ratio: 0.42,
        })
        .unwrap(),
        friction: Friction::coulomb(0.4),
        gap_m: ContactProblem::quadratic_gap(&grid, curvature, curvature),
        grid,
        load,
        kinematics: Kinematics::Transient(vec![step]),
        settings: SolverSettings::default(),
        rolling_direction_rad: 0.0,
        extra_rigid_slip: None,
        numerical_influence: None,
    };
    let mut solver = ContactSolver::new(&problem, &KernelCache::default());
    let target = PrescribedForce {
        force_x_n: Some(-0.875 * 0.4 * 9.1954),
        force_y_n: None,
    };
    let r = solve_prescribed_force_step(&mut solver, &problem, &step, target, Default::default())
        .unwrap();
    assert!(r.converged);
    let shift_mm = r.step.shift_x_m / MM;
    println!(
        "cattaneo case 2: shift {shift_mm:.6e} mm (CONTACT 8.155e-3), counts {:?}, {} secant steps",
        counts(&r.solution),
        r.outer_iterations
    );
    assert!(
        (shift_mm / 8.155e-3 - 1.0).abs() <= 1e-3,
        "shift {shift_mm:e} mm against 8.155e-3"
    );
    assert_eq!(counts(&r.solution), [177, 45, 132]);
}

/// `catt_to_cart.ref_out`, cases 116 to 171: "SHIFT X" of each world-fixed
/// step whose potential contact area moves one element with the bodies
/// (its XL grows by DX = 0.25 mm a case) \[mm\]. Case 115 is case 1 again
/// (the Cattaneo shift 1.774e-2 mm).
const MOVING_WINDOW_SHIFT_MM: [f64; 56] = [
    4.548e-4, 4.705e-4, 4.886e-4, 5.125e-4, 5.349e-4, 5.552e-4, 5.835e-4, 6.069e-4, 6.377e-4,
    6.690e-4, 7.003e-4, 7.419e-4, 7.960e-4, 8.508e-4, 8.505e-4, 8.334e-4, 8.103e-4, 7.980e-4,
    7.808e-4, 7.779e-4, 7.719e-4, 7.681e-4, 7.661e-4, 7.655e-4, 7.660e-4, 7.676e-4, 7.693e-4,
    7.712e-4, 7.733e-4, 7.752e-4, 7.767e-4, 7.776e-4, 7.777e-4, 7.774e-4, 7.767e-4, 7.762e-4,
    7.757e-4, 7.753e-4, 7.750e-4, 7.748e-4, 7.747e-4, 7.747e-4, 7.747e-4, 7.748e-4, 7.749e-4,
    7.750e-4, 7.750e-4, 7.751e-4, 7.752e-4, 7.752e-4, 7.752e-4, 7.752e-4, 7.752e-4, 7.752e-4,
    7.751e-4, 7.751e-4,
];

/// `catt_to_cart.ref_out`, cases 115 to 171: adhesion elements ("Tang:
/// final element division: A, S=", of 621): those of cases 1-57 but for
/// case 126 (350, as its world-fixed twin 70; case 12 has 352).
fn moving_window_adhesion(k: usize) -> usize {
    if k == 11 {
        350
    } else {
        ADHESION[k]
    }
}

/// The catt_to_cart case file of [`prescribed_step_forces_from_a_case_match_contact_catt_to_cart`]
/// with these `[grid]` elements in x and steps.
fn catt_to_cart_case(nx: usize, steps: &[String]) -> String {
    format!(
        r#"
model = "exact"
[material]
shear_modulus_pa = 1.0e6
poisson_ratio = 0.28
[friction]
coefficient = 0.4013
[geometry]
kind = "quadratic"
a_per_m = 2.963
b_per_m = 2.963
[load]
normal_force_n = 0.4705
[grid]
nx = {nx}
ny = 33
window_x_m = {}
window_y_m = 8.25e-3
[transient]
steps = [{}]
"#,
        nx as f64 * 0.25e-3,
        steps.join(", ")
    )
}

/// The prescribed force of every step, from a case file: CONTACT's
/// `catt_to_cart` cases 115-171 (and 1-57) as CONTACT states them, Fx =
/// -0.657 mu Fn prescribed in each step and the shift found. Step 1 is the
/// Cattaneo shift at Fn = 0.4705 N; steps 2-57 are shift steps at the
/// approach 0.07258 mm (`catt_to_cart.inp`, cases 116-171: PEN) whose
/// potential contact area moves one element with the bodies
/// (`rolling_m` = dx): the tractions stay on the bodies, one element
/// upstream on the grid, which is a rolling step given by its shift.
#[test]
fn prescribed_step_forces_from_a_case_match_contact_catt_to_cart() {
    use railcontact_solver::problem::case::Case;
    use railcontact_solver::problem::ExactRun;
    let f = FX_OVER_MU_FN * 0.4013 * 0.4705;
    let mut steps = vec![format!("{{ force_x_n = {f:e} }}")];
    for _ in 0..56 {
        steps.push(format!(
            "{{ force_x_n = {f:e}, rolling_m = 2.5e-4, approach_m = 7.258e-5 }}"
        ));
    }
    let text = catt_to_cart_case(33, &steps);
    let case = Case::from_toml(&text).unwrap();
    let run = ExactRun::solve(&case).unwrap();
    let report = run.report(&case, false);
    let steps = report.steps.as_ref().unwrap();
    assert_eq!(steps.len(), 57);
    let dq = 0.25 * MM;
    let (mut worst_shift, mut worst_creep, mut worst_fn) = (0.0f64, 0.0f64, 0.0f64);
    let (mut secant, mut solves) = (0, 0);
    let mut differ = Vec::new();
    for (k, s) in steps.iter().enumerate() {
        let fc = s
            .force_control
            .expect("a prescribed force reports its shift");
        secant += fc.force_iterations;
        solves += fc.force_solves;
        let t = &s.totals;
        // The force is met to the outer tolerance (1e-6 mu Fn).
        assert!(
            (t.fx_n - f).abs() <= 1e-5 * 0.4013 * t.normal_force_n,
            "step {}: Fx {} against {f}",
            k + 1,
            t.fx_n
        );
        // "FN 0.4705" in every case.
        let fn_err = (t.normal_force_n / 0.4705 - 1.0).abs();
        worst_fn = worst_fn.max(fn_err);
        let (want, got) = if k == 0 {
            (CASE_1_SHIFT_MM, fc.shift_x_m / MM)
        } else {
            (MOVING_WINDOW_SHIFT_MM[k - 1], fc.shift_x_m / MM)
        };
        let err = (got / want - 1.0).abs();
        if k == 1 {
            eprintln!("case 116: shift {got:.4e} mm against CONTACT's {want:.4e}");
        }
        worst_shift = worst_shift.max(err);
        assert!(
            err < 0.01 && fn_err < 0.01,
            "case {}: shift {got:.4e} mm against CONTACT's {want:.4e}, Fn {}",
            115 + k,
            t.normal_force_n
        );
        if k > 0 {
            // The creepage of the same step in moving coordinates (cases
            // 2-57).
            let xi = fc
                .creepage_long
                .expect("a rolling step reports its creepage");
            assert_eq!(fc.rolling_m, dq);
            worst_creep = worst_creep.max((xi / CREEPAGE[k - 1] - 1.0).abs());
        }
    }
    for (k, s) in run.solutions().iter().enumerate() {
        if !check_counts(115 + k, s, moving_window_adhesion(k)) {
            differ.push(115 + k);
        }
    }
    eprintln!(
        "catt_to_cart 115-171 from a case with prescribed Fx: worst shift {:.3} %, creepage \
         against cases 2-57 {:.3} %, Fn {:.3} %; {secant} secant steps, {solves} solves in 57 \
         steps; counts differ in {differ:?}",
        100.0 * worst_shift,
        100.0 * worst_creep,
        100.0 * worst_fn
    );
    assert!(worst_creep < 0.01, "creepage {worst_creep}");
    // Case 116 differs most: 4.564e-4 mm against 4.548e-4, where CONTACT's
    // moving-coordinate twin (case 2) has 1.824e-3 x 0.25 mm = 4.560e-4.
    assert!(worst_shift < 0.004, "shift {worst_shift}");
    assert_eq!(differ, [126], "cases whose counts differ (by ties)");
}

/// CONTACT's `catt_to_cart` cases 58-114 from a case file: world-fixed
/// steps on a fixed grid of 90 x 33 elements over which the bodies travel
/// one element (0.25 mm) a step (`gap_travel_x_m`), Fx = -0.657 mu Fn
/// prescribed in each. The grid is centred on the origin, so the first
/// step puts the bodies 7.125 mm left of its centre, where CONTACT's grid
/// from x = -4.125 mm has them. Against CONTACT's printed shifts of cases
/// 58-75 (`WORLD_SHIFT_MM`) and, over all 57 steps, against the same
/// steps with the potential contact area moving instead (cases 115-171:
/// the same physics in other coordinates).
#[test]
fn bodies_travelling_over_a_fixed_grid_match_contact_catt_to_cart() {
    use railcontact_solver::problem::case::Case;
    use railcontact_solver::problem::ExactRun;
    let f = FX_OVER_MU_FN * 0.4013 * 0.4705;
    let run = |nx: usize, first: &str, step: &str| {
        let mut steps = vec![format!("{{ force_x_n = {f:e}{first} }}")];
        for _ in 0..56 {
            steps.push(format!(
                "{{ force_x_n = {f:e}, approach_m = 7.258e-5, {step} }}"
            ));
        }
        let case = Case::from_toml(&catt_to_cart_case(nx, &steps)).unwrap();
        let run = ExactRun::solve(&case).unwrap();
        let report = run.report(&case, false);
        let shifts: Vec<f64> = report
            .steps
            .as_ref()
            .unwrap()
            .iter()
            .map(|s| s.force_control.unwrap().shift_x_m)
            .collect();
        (shifts, run)
    };
    let (world, world_run) = run(
        90,
        ", gap_travel_x_m = -7.125e-3",
        "gap_travel_x_m = 2.5e-4",
    );
    let (moving, _) = run(33, "", "rolling_m = 2.5e-4");
    let mut worst: f64 = 0.0;
    for (k, s) in world.iter().enumerate() {
        if let Some(&want) = [CASE_1_SHIFT_MM].iter().chain(&WORLD_SHIFT_MM).nth(k) {
            let err = (s / MM / want - 1.0).abs();
            worst = worst.max(err);
            assert!(
                err < 0.01,
                "case {}: shift {} mm against {want}",
                58 + k,
                s / MM
            );
        }
        let same = (s / moving[k] - 1.0).abs();
        assert!(same < 1e-4, "step {}: {s:e} against {:e}", k + 1, moving[k]);
    }
    let differ: Vec<usize> = (0..18)
        .filter(|&k| !check_counts(58 + k, &world_run.solutions()[k], WORLD_ADHESION[k]))
        .map(|k| 58 + k)
        .collect();
    eprintln!(
        "catt_to_cart 58-75 from a case with the bodies travelling: worst shift {:.3} %; counts \
         differ in {differ:?}",
        100.0 * worst
    );
    assert_eq!(differ, [69], "cases whose counts differ (by ties)");
}

/// CONTACT's test bank (github.com/eve70a/CONTACT, `testbank/testbank.inp`
/// and `testbank/testbank.ref_out`, case 17): catt_to_cart's bodies
/// ([`problem`]'s material, friction, load and h = 0.002963 (x² + y²) /mm)
/// on 41 x 41 elements of 0.2 mm from (-4.1, -4.1) mm, one transient
/// rolling step from rest (P = 2) of DQ = 0.4 mm, two elements, at
/// Fx/(mu Fn) = 0.657 (F = 1). The elements of each row's last one before
/// the leading edge entered the contact area in the step: CONTACT's
/// leading-edge correction gives them half the rigid shift. CONTACT finds
/// "CREEP X -4.500E-02" with 973 contact, 466 adhesion and 507 slip
/// elements ("NCON NADH NSLIP").
#[test]
fn a_rolling_step_of_two_elements_from_rest_matches_contact_testbank_case_17() {
    let d = 0.2 * MM;
    let grid = Grid::new(41, 41, d, d, -4.1 * MM, -4.1 * MM).unwrap();
    let curvature = 0.002963 / MM;
    let base = problem();
    let step = ShiftStep::rolling(base.load, 2.0 * d, &Creepages::default());
    let problem = ContactProblem {
        gap_m: ContactProblem::quadratic_gap(&grid, curvature, curvature),
        grid,
        kinematics: Kinematics::Transient(vec![step]),
        ..base
    };
    let mut solver = ContactSolver::new(&problem, &KernelCache::default());
    let target = PrescribedForce {
        force_x_n: Some(0.657 * 0.4013 * 0.4705),
        force_y_n: None,
    };
    let r = solve_prescribed_force_step(&mut solver, &problem, &step, target, Default::default())
        .unwrap();
    assert!(r.converged);
    let creepage = r.step.shift_x_m / step.rolling_m;
    println!(
        "testbank case 17: creepage {creepage:.6e} (CONTACT -4.500e-2), counts {:?}",
        counts(&r.solution)
    );
    assert!(
        (creepage / -4.5e-2 - 1.0).abs() <= 1e-3,
        "creepage {creepage:e} against -4.500e-2"
    );
    assert_eq!(counts(&r.solution), [973, 466, 507]);
}
