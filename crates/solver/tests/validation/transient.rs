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
