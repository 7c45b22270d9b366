//! Prescribed tangential forces: in steady rolling the creepage that gives
//! a prescribed total force Fx and/or Fy (on body 1, signs as in
//! [`crate::core::problem`]), the other creepages given
//! ([`solve_prescribed_force`]); in a transient step the shift that gives a
//! prescribed Fx or Fy, the step's other shift and rotation given
//! ([`solve_prescribed_force_step`]).
//!
//! # Method
//!
//! An outer iteration on the creepage(s) around the exact solve, each inner
//! solve warm-started from the previous iterate's tractions (the same
//! [`ContactSolver`]).
//!
//! * One force prescribed: F(creepage) decreases monotonically and saturates
//!   near mu Fn, so a root is found by the secant method safeguarded by a
//!   bracket ([`crate::core::root`]). The first
//!   step uses Kalker's linear slope -G c² C with c² the contact area over
//!   pi and C = 4 (about C11 = C22 of a round patch).
//! * Both forces prescribed: Newton on (xi, eta) with a forward-difference
//!   Jacobian (two extra solves per iteration, from clones of the solver)
//!   and a backtracking line search on |F - F*|.
//!
//! The iteration stops when |F - F*| <= tol mu Fn (each component), mu the
//! kinetic friction coefficient, or when the bracket of the one creepage is
//! narrower than 1e-14 of it. The inner solve's forces are only as exact as
//! its own tolerance ([`crate::core::tangential::TangentialSettings::tolerance`],
//! relative to max mu p_n), so tol = max(`tolerance`, 10 x the inner
//! tolerance): 1e-6 with the default inner tolerance 1e-7, 1e-9 with an
//! inner tolerance of 1e-10 or less.
//!
//! A transient step's force decreases with its shift in the same way (a
//! convex problem from the same previous state), so one prescribed force
//! takes the same safeguarded secant on the shift, and both forces the same
//! Newton iteration on the two shifts, each solve from the state before the
//! step (restored: [`ContactSolver::save_state`]); the first step uses
//! Mindlin's tangential stiffness 8 G a/(2 - nu), a the radius of a circle
//! of the contact area.
//!
//! A force of magnitude mu Fn or more (mu kinetic: the bound at full
//! slip) has no finite creepage and is refused naming its key; a smaller
//! force that the given other creepage and spin leave out of reach is
//! refused when the creepage would leave its input range (|creepage| <= 1).

use std::time::Instant;

use crate::core::error::Range;
use crate::core::error::{show, ContactError};
use crate::core::problem::{ContactProblem, Creepages, Kinematics, ShiftStep, CREEPAGE_RANGE};
use crate::core::root::{decreasing_root, RootEnd, RootError, RootSettings};
use crate::core::solution::{ContactSolution, SolveStatus};
use crate::core::solve::{ContactSolver, SolverState};

/// Key of the prescribed longitudinal force in a case (`[rolling]`).
pub const FORCE_X_KEY: &str = "rolling.force_x_n";
/// Key of the prescribed lateral force in a case (`[rolling]`).
pub const FORCE_Y_KEY: &str = "rolling.force_y_n";
/// Key of a transient step's prescribed longitudinal force.
pub const STEP_FORCE_X_KEY: &str = "step.force_x_n";
/// Key of a transient step's prescribed lateral force.
pub const STEP_FORCE_Y_KEY: &str = "step.force_y_n";

/// The shifts a prescribed-force step may try \[m\]: beyond them the force
/// is out of reach.
const SHIFT_RANGE: Range = Range::symmetric(1.0, "");

/// The prescribed forces \[N\] (on body 1); `None`: that direction's
/// creepage is given.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PrescribedForce {
    /// Prescribed Fx \[N\] instead of `creepage_long`.
    pub force_x_n: Option<f64>,
    /// Prescribed Fy \[N\] instead of `creepage_lat`.
    pub force_y_n: Option<f64>,
}

impl PrescribedForce {
    /// Whether any force is prescribed.
    pub fn any(&self) -> bool {
        self.force_x_n.is_some() || self.force_y_n.is_some()
    }
}

/// Outer iteration settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ForceControlSettings {
    /// Force tolerance relative to mu Fn [-] (default 1e-9; at least 10
    /// times the inner tangential tolerance, see the module docs).
    pub tolerance: f64,
    /// Outer iteration limit (default 60).
    pub max_iterations: usize,
}

impl Default for ForceControlSettings {
    fn default() -> Self {
        Self {
            tolerance: 1e-9,
            max_iterations: 60,
        }
    }
}

/// The solution at the creepages found.
#[derive(Debug, Clone)]
pub struct ForceSolution {
    /// The exact solution at `creepages`.
    pub solution: ContactSolution,
    /// The creepages found (the given ones in the other direction).
    pub creepages: Creepages,
    /// Outer iterations (secant or Newton steps).
    pub outer_iterations: usize,
    /// Exact solves, all included (finite-difference ones too).
    pub solves: usize,
    /// Whether the force tolerance was met within the iteration limit.
    pub converged: bool,
}

/// `work` (a copy of the problem, made once per prescribed-force solve)
/// with creepages `c`.
fn with(work: &mut ContactProblem, c: Creepages) -> &ContactProblem {
    work.kinematics = Kinematics::SteadyRolling(c);
    work
}

fn one(solver: &mut ContactSolver, p: &ContactProblem) -> Result<ContactSolution, ContactError> {
    solver
        .solve(p)?
        .pop()
        .ok_or_else(|| ContactError::invalid("rolling", "the solver returned no solution"))
}

/// The error of a force out of reach: the `unknown` (creepage or shift)
/// would leave [-1, 1], its last value `c`; `given` names what is fixed.
fn out_of_reach(key: &str, force: f64, [given, unknown]: [&str; 2], c: f64) -> ContactError {
    ContactError::invalid(
        key,
        format!(
            "{} N is out of reach with the given {given}: the {unknown} would leave [-1, 1] \
             (last {})",
            show(force),
            show(c)
        ),
    )
}

/// What [`out_of_reach`] says of a steady solve.
const STEADY_REACH: [&str; 2] = ["other creepage and spin", "creepage"];

/// Solves `problem` (steady rolling; the creepages of the prescribed
/// directions are the start) for the creepages giving `target`.
pub fn solve_prescribed_force(
    solver: &mut ContactSolver,
    problem: &ContactProblem,
    target: PrescribedForce,
    settings: ForceControlSettings,
) -> Result<ForceSolution, ContactError> {
    let t0 = Instant::now();
    let mut f = creepages_for_force(solver, problem, target, settings)?;
    // The solve time is the whole iteration's.
    f.solution.info.solve_time_s = t0.elapsed().as_secs_f64();
    Ok(f)
}

/// [`solve_prescribed_force`] but for the solve time.
fn creepages_for_force(
    solver: &mut ContactSolver,
    problem: &ContactProblem,
    target: PrescribedForce,
    settings: ForceControlSettings,
) -> Result<ForceSolution, ContactError> {
    let Kinematics::SteadyRolling(c0) = problem.kinematics else {
        return Err(ContactError::invalid(
            FORCE_X_KEY,
            "a prescribed force needs steady rolling (`[rolling]`)",
        ));
    };
    for (key, f) in [
        (FORCE_X_KEY, target.force_x_n),
        (FORCE_Y_KEY, target.force_y_n),
    ] {
        if let Some(f) = f {
            crate::core::error::require_finite(key, f)?;
        }
    }
    let first = one(solver, problem)?;
    let limit = saturation(problem, &first, target, [FORCE_X_KEY, FORCE_Y_KEY])?;
    let tol = settings
        .tolerance
        .max(10.0 * problem.settings.tangential.tolerance)
        * limit;
    let g = problem.material.shear_modulus_pa;
    let c2 = first.totals.contact_area_m2 / std::f64::consts::PI;
    // Kalker's linear slope dF/dcreepage (module docs).
    let slope0 = -g * c2 * 4.0;
    match (target.force_x_n, target.force_y_n) {
        (Some(fx), None) => one_direction(solver, problem, c0, 0, fx, first, slope0, tol, settings),
        (None, Some(fy)) => one_direction(solver, problem, c0, 1, fy, first, slope0, tol, settings),
        (Some(fx), Some(fy)) => {
            // Finite-difference step: 1e-3 of the creepage where the
            // linear theory saturates (as in `core::sensitivity`).
            let h = (1e-3 * limit / slope0.abs()).max(1e-12);
            both(
                solver,
                problem,
                c0,
                [fx, fy],
                first,
                [slope0, h],
                tol,
                settings,
            )
        }
        (None, None) => Ok(ForceSolution {
            solution: first,
            creepages: c0,
            outer_iterations: 0,
            solves: 1,
            converged: true,
        }),
    }
}

/// A transient step solved for a prescribed force.
#[derive(Debug, Clone)]
pub struct StepForceSolution {
    /// The step's solution at `step`.
    pub solution: ContactSolution,
    /// The step with the shift found (the other components as given).
    pub step: ShiftStep,
    /// Outer (secant) iterations.
    pub outer_iterations: usize,
    /// Solves of the step, all included.
    pub solves: usize,
    /// Whether the force tolerance was met within the iteration limit.
    pub converged: bool,
}

/// Solves the transient `step` of `problem` (transient kinematics), going on
/// from `solver`'s state as [`ContactSolver::solve_next_step`] does, for the
/// shift that gives `target`: Fx (the shift in x found), Fy (in y) or
/// both; the step's shifts in those directions are the start, its other
/// shift, rotation, rolling distance and load are kept. The solver ends in
/// the state after the step at the shift found (its state before the step
/// when an error is returned: `problem`'s grid; a force at or beyond
/// saturation refused naming `step.force_x_n` / `step.force_y_n`).
pub fn solve_prescribed_force_step(
    solver: &mut ContactSolver,
    problem: &ContactProblem,
    step: &ShiftStep,
    target: PrescribedForce,
    settings: ForceControlSettings,
) -> Result<StepForceSolution, ContactError> {
    let t0 = Instant::now();
    let mut f = shifts_for_force(solver, problem, step, target, settings)?;
    // The solve time is the whole step's, all its solves.
    f.solution.info.solve_time_s = t0.elapsed().as_secs_f64();
    Ok(f)
}

/// [`solve_prescribed_force_step`] but for the solve time.
fn shifts_for_force(
    solver: &mut ContactSolver,
    problem: &ContactProblem,
    step: &ShiftStep,
    target: PrescribedForce,
    settings: ForceControlSettings,
) -> Result<StepForceSolution, ContactError> {
    let (k, f) = match (target.force_x_n, target.force_y_n) {
        (Some(x), None) => (0, x),
        (None, Some(y)) => (1, y),
        (None, None) => {
            let solution = solver.solve_next_step(problem, step)?;
            return Ok(StepForceSolution {
                converged: solution.info.status == SolveStatus::Converged,
                solution,
                step: *step,
                outer_iterations: 0,
                solves: 1,
            });
        }
        (Some(fx), Some(fy)) => {
            return step_both(solver, problem, step, [fx, fy], settings);
        }
    };
    let key = if k == 0 {
        STEP_FORCE_X_KEY
    } else {
        STEP_FORCE_Y_KEY
    };
    crate::core::error::require_finite(key, f)?;
    let shift = |s: &ShiftStep| if k == 0 { s.shift_x_m } else { s.shift_y_m };
    let with_shift = |x: f64| {
        let mut s = *step;
        if k == 0 {
            s.shift_x_m = x;
        } else {
            s.shift_y_m = x;
        }
        s
    };
    let mut before = SolverState::default();
    solver.save_state(&mut before);
    let first = solver.solve_next_step(problem, step)?;
    let limit = match saturation(
        problem,
        &first,
        target,
        [STEP_FORCE_X_KEY, STEP_FORCE_Y_KEY],
    ) {
        Ok(l) => l,
        Err(e) => {
            solver.restore_state(&before)?;
            return Err(e);
        }
    };
    let tol = settings
        .tolerance
        .max(10.0 * problem.settings.tangential.tolerance)
        * limit;
    let slope0 = mindlin_slope(problem, &first);
    let mut last = shift(step);
    let root = decreasing_root(
        shift(step),
        force(&first, k) - f,
        first,
        RootSettings {
            tolerance: tol,
            max_iterations: settings.max_iterations,
            slope: slope0,
        },
        SHIFT_RANGE,
        |x| {
            solver.restore_state(&before)?;
            last = x;
            let sol = solver.solve_next_step(problem, &with_shift(x))?;
            Ok((force(&sol, k) - f, sol))
        },
    );
    let root = match root {
        Ok(r) => r,
        Err(e) => {
            solver.restore_state(&before)?;
            return Err(match e {
                RootError::Eval(e) => e,
                RootError::OutOfRange { next } => out_of_reach(key, f, STEP_REACH, next),
            });
        }
    };
    let found = with_shift(root.x);
    let mut solves = root.evaluations;
    if last != root.x {
        // The solver holds the last evaluation's state: solve the root's
        // step again from the state before (the same bits as its first
        // solve of it).
        solver.restore_state(&before)?;
        solver.solve_next_step(problem, &found)?;
        solves += 1;
    }
    Ok(StepForceSolution {
        converged: root.end != RootEnd::IterationLimit
            && root.state.info.status == SolveStatus::Converged,
        solution: root.state,
        step: found,
        outer_iterations: root.iterations,
        solves,
    })
}

/// Solves every step of the transient `problem` on from the solver's
/// state (after [`ContactSolver::reset`] from the unloaded state, as
/// [`ContactSolver::solve`] does; after a steady solve and
/// [`ContactSolver::continue_from_last_solution`] from that steady
/// rolling state), each step with a prescribed force in
/// `forces` (one entry per step; `PrescribedForce::default()` for a step
/// solved as given) for its shift ([`solve_prescribed_force_step`]), the
/// secant of a step starting where [`continued_start`] puts it.
/// `before_step(k, problem)` may change what a step sees of the problem
/// (its undeformed distance: bodies moving over the grid) before step `k`
/// is solved. An error names its step's key under `steps_key`
/// (`transient.steps[k]` for `steps_key = "transient.steps"`); the solver
/// then holds the state after the steps before it.
pub fn solve_steps_with_forces(
    solver: &mut ContactSolver,
    problem: &ContactProblem,
    forces: &[PrescribedForce],
    settings: ForceControlSettings,
    steps_key: &str,
    mut before_step: impl FnMut(usize, &mut ContactProblem),
) -> Result<Vec<StepForceSolution>, ContactError> {
    let Kinematics::Transient(steps) = &problem.kinematics else {
        return Err(ContactError::invalid(
            "kinematics",
            "prescribed step forces need transient steps",
        ));
    };
    if forces.len() != steps.len() {
        return Err(ContactError::invalid(
            steps_key,
            format!(
                "{} steps but {} prescribed forces",
                steps.len(),
                forces.len()
            ),
        ));
    }
    let mut work = problem.clone();
    let mut out: Vec<StepForceSolution> = Vec::with_capacity(steps.len());
    for (k, (step, &target)) in steps.iter().zip(forces).enumerate() {
        let start = match out.last() {
            Some(previous) => continued_start(&previous.step, step, target),
            None => *step,
        };
        before_step(k, &mut work);
        let solved = solve_prescribed_force_step(solver, &work, &start, target, settings)
            .map_err(|e| e.with_key_prefix("step", &format!("{steps_key}[{k}]")))?;
        out.push(solved);
    }
    Ok(out)
}

/// `step` with the shift in the direction of `target`'s force continued
/// from `previous`, the step before as solved: the same creepage when both
/// roll (shift over rolling distance), the same shift when neither does;
/// the step as given otherwise, and without a prescribed force. Where the
/// secant of [`solve_prescribed_force_step`] starts: a step rolling on at
/// a steady force needs about two solves from there.
pub fn continued_start(
    previous: &ShiftStep,
    step: &ShiftStep,
    target: PrescribedForce,
) -> ShiftStep {
    let scale = match (previous.rolling_m > 0.0, step.rolling_m > 0.0) {
        (true, true) => step.rolling_m / previous.rolling_m,
        (false, false) => 1.0,
        _ => return *step,
    };
    let mut start = *step;
    if target.force_x_n.is_some() {
        start.shift_x_m = scale * previous.shift_x_m;
    }
    if target.force_y_n.is_some() {
        start.shift_y_m = scale * previous.shift_y_m;
    }
    start
}

/// [`solve_prescribed_force_step`] with both forces prescribed: Newton on
/// the two shifts, each solve from the state before the step.
fn step_both(
    solver: &mut ContactSolver,
    problem: &ContactProblem,
    step: &ShiftStep,
    target: [f64; 2],
    settings: ForceControlSettings,
) -> Result<StepForceSolution, ContactError> {
    for (key, f) in [(STEP_FORCE_X_KEY, target[0]), (STEP_FORCE_Y_KEY, target[1])] {
        crate::core::error::require_finite(key, f)?;
    }
    let with_shifts = |x: [f64; 2]| ShiftStep {
        shift_x_m: x[0],
        shift_y_m: x[1],
        ..*step
    };
    let mut before = SolverState::default();
    solver.save_state(&mut before);
    let prescribed = PrescribedForce {
        force_x_n: Some(target[0]),
        force_y_n: Some(target[1]),
    };
    let solved = (|| {
        let first = solver.solve_next_step(problem, step)?;
        let limit = saturation(
            problem,
            &first,
            prescribed,
            [STEP_FORCE_X_KEY, STEP_FORCE_Y_KEY],
        )?;
        let tol = settings
            .tolerance
            .max(10.0 * problem.settings.tangential.tolerance)
            * limit;
        let slope0 = mindlin_slope(problem, &first);
        let h = (1e-3 * limit / slope0.abs()).max(1e-15);
        let reach = Reach {
            range: SHIFT_RANGE,
            key: STEP_FORCE_X_KEY,
            words: STEP_REACH,
        };
        newton_both(
            [step.shift_x_m, step.shift_y_m],
            first,
            target,
            [slope0, h],
            tol,
            settings,
            reach,
            |x, _| {
                solver.restore_state(&before)?;
                solver.solve_next_step(problem, &with_shifts(x))
            },
        )
    })();
    match solved {
        Ok(end) => Ok(StepForceSolution {
            solution: end.solution,
            step: with_shifts(end.x),
            outer_iterations: end.iterations,
            solves: end.solves,
            converged: end.converged,
        }),
        Err(e) => {
            solver.restore_state(&before)?;
            Err(e)
        }
    }
}

/// Mindlin's tangential stiffness dF/dshift of a circle of `first`'s
/// contact area, 8 G a/(2 - nu) (negative: the force opposes the shift).
fn mindlin_slope(problem: &ContactProblem, first: &ContactSolution) -> f64 {
    let m = &problem.material;
    let a = (first.totals.contact_area_m2 / std::f64::consts::PI).sqrt();
    -8.0 * m.shear_modulus_pa * a / (2.0 - m.poisson_ratio)
}

/// What [`out_of_reach`] says of a transient step.
const STEP_REACH: [&str; 2] = ["other shift and rotation", "shift [m]"];

/// mu Fn of `first` (mu kinetic), or the error of a `target` at or beyond it
/// (naming `keys`, x then y).
fn saturation(
    problem: &ContactProblem,
    first: &ContactSolution,
    target: PrescribedForce,
    [key_x, key_y]: [&str; 2],
) -> Result<f64, ContactError> {
    let mu = problem.friction.kinetic_coefficient;
    let limit = mu * first.totals.normal_force_n;
    let magnitude = target
        .force_x_n
        .unwrap_or(0.0)
        .hypot(target.force_y_n.unwrap_or(0.0));
    if magnitude >= limit {
        let (key, value) = match (target.force_x_n, target.force_y_n) {
            (Some(x), None) => (key_x.to_string(), show(x)),
            (None, Some(y)) => (key_y.to_string(), show(y)),
            _ => (
                format!("{key_x}, {key_y}"),
                format!(
                    "|({}, {})| = {}",
                    show(target.force_x_n.unwrap_or(0.0)),
                    show(target.force_y_n.unwrap_or(0.0)),
                    show(magnitude)
                ),
            ),
        };
        return Err(ContactError::invalid(
            key,
            format!(
                "{value} N is at or beyond saturation mu Fn = {} x {} N = {} N (mu: the kinetic \
                 coefficient): no finite creepage or shift gives it",
                show(mu),
                show(first.totals.normal_force_n),
                show(limit)
            ),
        ));
    }
    Ok(limit)
}

fn component(c: &Creepages, k: usize) -> f64 {
    if k == 0 {
        c.creepage_long
    } else {
        c.creepage_lat
    }
}

fn set(c: &mut Creepages, k: usize, v: f64) {
    if k == 0 {
        c.creepage_long = v
    } else {
        c.creepage_lat = v
    }
}

fn force(s: &ContactSolution, k: usize) -> f64 {
    if k == 0 {
        s.totals.fx_n
    } else {
        s.totals.fy_n
    }
}

#[allow(clippy::too_many_arguments)]
fn one_direction(
    solver: &mut ContactSolver,
    problem: &ContactProblem,
    c0: Creepages,
    k: usize,
    target: f64,
    first: ContactSolution,
    slope0: f64,
    tol: f64,
    settings: ForceControlSettings,
) -> Result<ForceSolution, ContactError> {
    let key = if k == 0 { FORCE_X_KEY } else { FORCE_Y_KEY };
    let mut work = problem.clone();
    let r0 = force(&first, k) - target;
    let root = decreasing_root(
        component(&c0, k),
        r0,
        first,
        RootSettings {
            tolerance: tol,
            max_iterations: settings.max_iterations,
            slope: slope0,
        },
        CREEPAGE_RANGE,
        |x| {
            let mut c = c0;
            set(&mut c, k, x);
            let sol = one(solver, with(&mut work, c))?;
            Ok((force(&sol, k) - target, sol))
        },
    )
    .map_err(|e| match e {
        RootError::Eval(e) => e,
        RootError::OutOfRange { next } => out_of_reach(key, target, STEADY_REACH, next),
    })?;
    let mut creepages = c0;
    set(&mut creepages, k, root.x);
    Ok(ForceSolution {
        converged: root.end != RootEnd::IterationLimit
            && root.state.info.status == SolveStatus::Converged,
        solution: root.state,
        creepages,
        outer_iterations: root.iterations,
        solves: root.evaluations,
    })
}

/// What the Newton iteration of two prescribed forces ([`newton_both`])
/// ends with.
struct BothEnd {
    solution: ContactSolution,
    /// The unknowns found (creepages or shifts).
    x: [f64; 2],
    iterations: usize,
    solves: usize,
    converged: bool,
}

/// The unknowns' range of [`newton_both`] and the error of leaving it.
struct Reach<'a> {
    range: Range,
    key: &'a str,
    /// What [`out_of_reach`] says.
    words: [&'a str; 2],
}

/// Newton on the two unknowns `x` (creepages or shifts) for the forces
/// `target` (Fx, Fy), from `x0` whose solution is `first`, with a
/// forward-difference Jacobian of step `h` (two extra solves an
/// iteration; `slope0` where it is singular) and a backtracking line
/// search on |F - F*|. `eval(x, probe)` solves at `x`; `probe` marks the
/// difference solves, which must not move the state the next solves start
/// from. The last evaluation is always the solution returned.
#[allow(clippy::too_many_arguments)]
fn newton_both(
    x0: [f64; 2],
    first: ContactSolution,
    target: [f64; 2],
    [slope0, h]: [f64; 2],
    tol: f64,
    settings: ForceControlSettings,
    reach: Reach,
    mut eval: impl FnMut([f64; 2], bool) -> Result<ContactSolution, ContactError>,
) -> Result<BothEnd, ContactError> {
    let residual = |s: &ContactSolution| [s.totals.fx_n - target[0], s.totals.fy_n - target[1]];
    let norm = |r: [f64; 2]| r[0].hypot(r[1]);
    let mut x = x0;
    let mut sol = first;
    let mut r = residual(&sol);
    let mut solves = 1;
    let mut iterations = 0;
    while r[0].abs() > tol || r[1].abs() > tol {
        if iterations == settings.max_iterations {
            return Ok(BothEnd {
                solution: sol,
                x,
                iterations,
                solves,
                converged: false,
            });
        }
        iterations += 1;
        // col[k]: d(Fx, Fy)/d(x k).
        let mut col = [[0.0; 2]; 2];
        for (k, d) in col.iter_mut().enumerate() {
            let mut xp = x;
            xp[k] += h;
            let s = eval(xp, true)?;
            solves += 1;
            *d = [
                (s.totals.fx_n - sol.totals.fx_n) / h,
                (s.totals.fy_n - sol.totals.fy_n) / h,
            ];
        }
        let jac = [[col[0][0], col[1][0]], [col[0][1], col[1][1]]];
        let det = jac[0][0] * jac[1][1] - jac[0][1] * jac[1][0];
        let step = if det.is_finite() && det != 0.0 {
            [
                -(jac[1][1] * r[0] - jac[0][1] * r[1]) / det,
                -(-jac[1][0] * r[0] + jac[0][0] * r[1]) / det,
            ]
        } else {
            [-r[0] / slope0, -r[1] / slope0]
        };
        let mut t = 1.0;
        loop {
            let xn = [x[0] + t * step[0], x[1] + t * step[1]];
            if !(reach.range.contains(xn[0]) && reach.range.contains(xn[1])) {
                if t < 1e-6 {
                    return Err(out_of_reach(
                        reach.key,
                        target[0].hypot(target[1]),
                        reach.words,
                        xn[0].hypot(xn[1]),
                    ));
                }
                t *= 0.5;
                continue;
            }
            let s = eval(xn, false)?;
            solves += 1;
            let rn = residual(&s);
            if norm(rn) < (1.0 - 1e-4 * t) * norm(r) || t < 1e-6 {
                x = xn;
                sol = s;
                r = rn;
                break;
            }
            t *= 0.5;
        }
    }
    Ok(BothEnd {
        converged: sol.info.status == SolveStatus::Converged,
        solution: sol,
        x,
        iterations,
        solves,
    })
}

#[allow(clippy::too_many_arguments)]
fn both(
    solver: &mut ContactSolver,
    problem: &ContactProblem,
    c0: Creepages,
    target: [f64; 2],
    first: ContactSolution,
    slope_h: [f64; 2],
    tol: f64,
    settings: ForceControlSettings,
) -> Result<ForceSolution, ContactError> {
    let mut work = problem.clone();
    let creepages = |x: [f64; 2]| Creepages {
        creepage_long: x[0],
        creepage_lat: x[1],
        ..c0
    };
    let reach = Reach {
        range: CREEPAGE_RANGE,
        key: FORCE_X_KEY,
        words: STEADY_REACH,
    };
    let end = newton_both(
        [c0.creepage_long, c0.creepage_lat],
        first,
        target,
        slope_h,
        tol,
        settings,
        reach,
        |x, probe| {
            let p = with(&mut work, creepages(x));
            if probe {
                // From a clone: the warm start stays the iterate's.
                one(&mut solver.clone(), p)
            } else {
                one(solver, p)
            }
        },
    )?;
    Ok(ForceSolution {
        solution: end.solution,
        creepages: creepages(end.x),
        outer_iterations: end.iterations,
        solves: end.solves,
        converged: end.converged,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::cache::KernelCache;
    use crate::core::creep::kalker_creep_coefficients;
    use crate::core::grid::Grid;
    use crate::core::hertz::{hertz, HertzLoad};
    use crate::core::material::{CombinedMaterial, Material};
    use crate::core::normal::NormalLoad;
    use crate::core::problem::Friction;

    const FN: f64 = 1e4;
    const MU: f64 = 0.3;

    /// Identical bodies, G = 80 GPa, nu = 0.25 (a column of Kalker's
    /// table), A = B = 1/m, Fn = 10 kN, mu = 0.3 on an n x n grid over 2.4
    /// Hertz semi-axes; inner tangential tolerance 1e-10.
    fn problem(n: usize, c: Creepages) -> ContactProblem {
        problem_with(n, c, MU, 1.1 * FN)
    }

    /// As [`problem`] with friction coefficient `mu` and a window of 2.4
    /// semi-axes of the Hertz patch at `window_load_n`.
    fn problem_with(n: usize, c: Creepages, mu: f64, window_load_n: f64) -> ContactProblem {
        let m = CombinedMaterial::identical(Material {
            shear_modulus_pa: 8e10,
            poisson_ratio: 0.25,
        })
        .unwrap();
        let a = hertz(
            1.0,
            1.0,
            m.effective_modulus_pa(),
            HertzLoad::NormalForce {
                normal_force_n: window_load_n,
            },
        )
        .unwrap()
        .semi_axis_x_m;
        let grid = Grid::centered(n, n, 2.4 * a, 2.4 * a).unwrap();
        let mut p = ContactProblem {
            material: m,
            friction: Friction::coulomb(mu),
            gap_m: ContactProblem::quadratic_gap(&grid, 1.0, 1.0),
            grid,
            load: NormalLoad::NormalForce(FN),
            kinematics: Kinematics::SteadyRolling(c),
            settings: Default::default(),
            rolling_direction_rad: 0.0,
            extra_rigid_slip: None,
            numerical_influence: None,
        };
        p.settings.tangential.tolerance = 1e-10;
        p
    }

    fn creep(xi: f64, eta: f64, phi: f64) -> Creepages {
        Creepages {
            creepage_long: xi,
            creepage_lat: eta,
            spin_per_m: phi,
        }
    }

    fn forward(c: Creepages) -> ContactSolution {
        let p = problem(32, c);
        one(&mut ContactSolver::new(&p, KernelCache::global()), &p).unwrap()
    }

    fn prescribed(c: Creepages, t: PrescribedForce) -> Result<ForceSolution, ContactError> {
        let p = problem(32, c);
        let mut s = ContactSolver::new(&p, KernelCache::global());
        solve_prescribed_force(&mut s, &p, t, ForceControlSettings::default())
    }

    /// Creepage at which Kalker's linear theory reaches mu Fn (C = 4).
    fn xi_saturation() -> f64 {
        let s = forward(creep(0.0, 0.0, 0.0));
        MU * FN / (8e10 * s.totals.contact_area_m2 / std::f64::consts::PI * 4.0)
    }

    fn close(got: f64, want: f64, rel: f64) {
        assert!(
            (got - want).abs() <= rel * want.abs(),
            "{got} against {want}"
        );
    }

    #[test]
    fn one_prescribed_force_gives_back_the_creepage_it_came_from() {
        let sat = xi_saturation();
        // From the linear range to beyond the linear saturation creepage,
        // for each direction, the other creepage and spin given.
        for f in [0.05, 0.4, 0.9, 1.6, 2.5] {
            for k in 0..2 {
                let (xi, eta, phi) = if k == 0 {
                    (f * sat, -0.1 * sat, 0.0)
                } else {
                    (0.2 * sat, -f * sat, 0.2)
                };
                let fw = forward(creep(xi, eta, phi));
                let (start, t) = if k == 0 {
                    (
                        creep(0.0, eta, phi),
                        PrescribedForce {
                            force_x_n: Some(fw.totals.fx_n),
                            force_y_n: None,
                        },
                    )
                } else {
                    (
                        creep(xi, 0.0, phi),
                        PrescribedForce {
                            force_x_n: None,
                            force_y_n: Some(fw.totals.fy_n),
                        },
                    )
                };
                let r = prescribed(start, t).unwrap();
                eprintln!(
                    "k {k} f {f}: F/muFn {:.4}, {} outer iterations, {} solves",
                    force(&fw, k) / (MU * FN),
                    r.outer_iterations,
                    r.solves
                );
                assert!(r.converged);
                close(
                    component(&r.creepages, k),
                    if k == 0 { xi } else { eta },
                    1e-6,
                );
                assert!((force(&r.solution, k) - force(&fw, k)).abs() <= 1e-9 * MU * FN);
                // The given creepages are kept.
                assert_eq!(r.creepages.spin_per_m, phi);
                assert_eq!(
                    component(&r.creepages, 1 - k),
                    if k == 0 { eta } else { xi }
                );
            }
        }
    }

    #[test]
    fn both_prescribed_forces_give_back_both_creepages() {
        let sat = xi_saturation();
        for (xi, eta) in [
            (0.1 * sat, 0.05 * sat),
            (0.6 * sat, -0.5 * sat),
            (-1.2 * sat, 0.3 * sat),
        ] {
            let fw = forward(creep(xi, eta, 0.1));
            let t = PrescribedForce {
                force_x_n: Some(fw.totals.fx_n),
                force_y_n: Some(fw.totals.fy_n),
            };
            let r = prescribed(creep(0.0, 0.0, 0.1), t).unwrap();
            eprintln!(
                "both ({xi:e}, {eta:e}): {} outer iterations, {} solves",
                r.outer_iterations, r.solves
            );
            assert!(r.converged);
            close(r.creepages.creepage_long, xi, 1e-6);
            close(r.creepages.creepage_lat, eta, 1e-6);
        }
    }

    #[test]
    fn the_default_inner_tolerance_sets_a_reachable_force_tolerance() {
        // Inner tolerance 1e-7 (the default): forces meet 1e-6 mu Fn; a
        // demand of 1e-9 mu Fn would stall on the inner solve's accuracy.
        let sat = xi_saturation();
        let mut p = problem(32, creep(0.6 * sat, -0.5 * sat, 0.1));
        p.settings.tangential.tolerance = 1e-7;
        let fw = one(&mut ContactSolver::new(&p, KernelCache::global()), &p).unwrap();
        p.kinematics = Kinematics::SteadyRolling(creep(0.0, 0.0, 0.1));
        let t = PrescribedForce {
            force_x_n: Some(fw.totals.fx_n),
            force_y_n: Some(fw.totals.fy_n),
        };
        let mut s = ContactSolver::new(&p, KernelCache::global());
        let r = solve_prescribed_force(&mut s, &p, t, ForceControlSettings::default()).unwrap();
        assert!(
            r.converged && r.outer_iterations < 10,
            "{} iterations",
            r.outer_iterations
        );
        assert!((r.solution.totals.fx_n - fw.totals.fx_n).abs() <= 1e-6 * MU * FN);
        assert!((r.solution.totals.fy_n - fw.totals.fy_n).abs() <= 1e-6 * MU * FN);
    }

    #[test]
    fn a_small_force_follows_kalkers_linear_theory() {
        // Fx = -G a b C11 xi, C11 = 4.12 for a/b = 1, nu = 0.25: Kalker,
        // Three-dimensional elastic bodies in rolling contact, 1990, Table
        // E3 (`core::creep`). Full adhesion (mu = 100, the limit of the
        // linear theory) on the grid of tests/validation/physics.rs
        // (32 x 32 over 2.4 Hertz semi-axes), where the forward solve meets
        // C11 within 3 %: the inverse must too.
        let target = -1e-3 * 0.3 * FN;
        let p = problem_with(32, creep(0.0, 0.0, 0.0), 100.0, FN);
        let mut s = ContactSolver::new(&p, KernelCache::global());
        let force = PrescribedForce {
            force_x_n: Some(target),
            force_y_n: None,
        };
        let r = solve_prescribed_force(&mut s, &p, force, ForceControlSettings::default()).unwrap();
        let a = hertz(
            1.0,
            1.0,
            CombinedMaterial::identical(Material {
                shear_modulus_pa: 8e10,
                poisson_ratio: 0.25,
            })
            .unwrap()
            .effective_modulus_pa(),
            HertzLoad::NormalForce { normal_force_n: FN },
        )
        .unwrap()
        .semi_axis_x_m;
        let c11 = kalker_creep_coefficients(1.0, 0.25).unwrap().c11;
        assert!((c11 - 4.12).abs() < 0.005, "table C11 {c11}");
        let linear = -target / (8e10 * a * a * c11);
        eprintln!(
            "xi {:e} against linear theory {linear:e}",
            r.creepages.creepage_long
        );
        close(r.creepages.creepage_long, linear, 0.03);
        close(r.solution.totals.fx_n, target, 1e-6);
    }

    #[test]
    fn near_saturation_converges_to_a_large_finite_creepage() {
        let sat = xi_saturation();
        for sign in [1.0, -1.0] {
            let target = sign * 0.999 * MU * FN;
            let r = prescribed(
                creep(0.0, 0.0, 0.0),
                PrescribedForce {
                    force_x_n: None,
                    force_y_n: Some(target),
                },
            )
            .unwrap();
            eprintln!(
                "0.999 mu Fn: eta {:e} ({} x linear saturation), {} outer iterations",
                r.creepages.creepage_lat,
                r.creepages.creepage_lat / sat,
                r.outer_iterations
            );
            assert!(r.converged);
            assert!((r.solution.totals.fy_n - target).abs() <= 1e-9 * MU * FN);
            assert!(r.creepages.creepage_lat * sign < -sat, "{:?}", r.creepages);
        }
    }

    #[test]
    fn saturation_is_refused_naming_the_key() {
        // Beyond mu Fn = 3000 N: exactly at it, the refusal hinges on the
        // last bit of the computed Fn (9999.99... or 10000.0...).
        let cases = [
            (Some(3030.0), None, "rolling.force_x_n", "3030"),
            (None, Some(-1.5 * MU * FN), "rolling.force_y_n", "-4500"),
            (
                Some(2400.0),
                Some(1810.0),
                "rolling.force_x_n, rolling.force_y_n",
                "3006",
            ),
        ];
        for (fx, fy, key, value) in cases {
            let e = prescribed(
                creep(0.0, 0.0, 0.0),
                PrescribedForce {
                    force_x_n: fx,
                    force_y_n: fy,
                },
            )
            .unwrap_err();
            let msg = e.to_string();
            assert_eq!(e.key(), Some(key), "{msg}");
            assert!(
                msg.contains(value)
                    && (msg.contains("mu Fn = 0.3 x 9999.99")
                        || msg.contains("mu Fn = 0.3 x 10000"))
                    && (msg.contains("N = 2999.99") || msg.contains("N = 3000")),
                "{msg}"
            );
        }
    }

    /// The circle of [`problem`] on a 24 x 24 grid, loaded by one transient
    /// step, and the solver after that step.
    fn loaded() -> (ContactProblem, ContactSolver) {
        let mut p = problem(24, creep(0.0, 0.0, 0.0));
        let load = ShiftStep {
            load: p.load,
            shift_x_m: 0.0,
            shift_y_m: 0.0,
            rotation_rad: 0.0,
            rolling_m: 0.0,
        };
        p.kinematics = Kinematics::Transient(vec![load]);
        let mut s = ContactSolver::new(&p, KernelCache::global());
        s.solve(&p).unwrap();
        (p, s)
    }

    fn shift_step(p: &ContactProblem, x: f64, y: f64, rotation_rad: f64) -> ShiftStep {
        ShiftStep {
            load: p.load,
            shift_x_m: x,
            shift_y_m: y,
            rotation_rad,
            rolling_m: 0.0,
        }
    }

    #[test]
    fn a_prescribed_step_force_gives_back_the_shift_it_came_from() {
        // Mindlin's full-slip shift of this circle is 3 mu Fn (2 - nu)/(8 G
        // a), about 7.5 um (a = 3.3 mm): these shifts leave an adhesion
        // zone, the first with rotation.
        let (p, mut s) = loaded();
        let mut before = SolverState::default();
        s.save_state(&mut before);
        for (k, dx, dy, rot) in [
            (0, 2e-6, 0.0, 3e-4),
            (1, 0.5e-6, -1.5e-6, 0.0),
            (0, -4e-6, 1e-6, 0.0),
        ] {
            s.restore_state(&before).unwrap();
            let step = shift_step(&p, dx, dy, rot);
            let forward = s.solve_next_step(&p, &step).unwrap();
            let after_forward = s
                .solve_next_step(&p, &shift_step(&p, 0.0, 0.0, 0.0))
                .unwrap();
            s.restore_state(&before).unwrap();
            let (start, target, want) = if k == 0 {
                let t = PrescribedForce {
                    force_x_n: Some(forward.totals.fx_n),
                    force_y_n: None,
                };
                (shift_step(&p, 0.0, dy, rot), t, dx)
            } else {
                let t = PrescribedForce {
                    force_x_n: None,
                    force_y_n: Some(forward.totals.fy_n),
                };
                (shift_step(&p, dx, 0.0, rot), t, dy)
            };
            let r = solve_prescribed_force_step(&mut s, &p, &start, target, Default::default())
                .unwrap();
            assert!(r.converged, "{k} {dx} {dy}");
            let got = if k == 0 {
                r.step.shift_x_m
            } else {
                r.step.shift_y_m
            };
            assert!(
                (got - want).abs() <= 1e-6 * want.abs(),
                "shift {got:e} against {want:e}"
            );
            let limit = MU * r.solution.totals.normal_force_n;
            let f = [r.solution.totals.fx_n, r.solution.totals.fy_n];
            let t = [forward.totals.fx_n, forward.totals.fy_n];
            assert!((f[k] - t[k]).abs() <= 1e-9 * limit, "{f:?} against {t:?}");
            println!(
                "shift {k}: {:.3e} m in {} secant steps, {} solves",
                got, r.outer_iterations, r.solves
            );
            // The solver is left after the step found: the next step
            // from it is the forward path's next step.
            let next = s
                .solve_next_step(&p, &shift_step(&p, 0.0, 0.0, 0.0))
                .unwrap();
            for (a, b) in [
                (next.totals.fx_n, after_forward.totals.fx_n),
                (next.totals.fy_n, after_forward.totals.fy_n),
            ] {
                assert!((a - b).abs() <= 1e-6 * limit, "{a} against {b}");
            }
        }
    }

    #[test]
    fn both_step_forces_give_back_both_shifts() {
        let (p, mut s) = loaded();
        let mut before = SolverState::default();
        s.save_state(&mut before);
        let step = shift_step(&p, 2e-6, -1.5e-6, 2e-4);
        let forward = s.solve_next_step(&p, &step).unwrap();
        s.restore_state(&before).unwrap();
        let target = PrescribedForce {
            force_x_n: Some(forward.totals.fx_n),
            force_y_n: Some(forward.totals.fy_n),
        };
        let start = shift_step(&p, 0.0, 0.0, 2e-4);
        let r =
            solve_prescribed_force_step(&mut s, &p, &start, target, Default::default()).unwrap();
        assert!(r.converged);
        for (got, want) in [
            (r.step.shift_x_m, step.shift_x_m),
            (r.step.shift_y_m, step.shift_y_m),
        ] {
            assert!(
                (got - want).abs() <= 1e-5 * want.abs(),
                "shift {got:e} against {want:e}"
            );
        }
        let limit = MU * r.solution.totals.normal_force_n;
        assert!((r.solution.totals.fx_n - forward.totals.fx_n).abs() <= 1e-9 * limit);
        assert!((r.solution.totals.fy_n - forward.totals.fy_n).abs() <= 1e-9 * limit);
        println!(
            "both shifts in {} Newton steps, {} solves",
            r.outer_iterations, r.solves
        );
        // The solver is left after the step found: its state is the
        // forward step's (the same shifts to the tolerance).
        let next = s
            .solve_next_step(&p, &shift_step(&p, 0.0, 0.0, 0.0))
            .unwrap();
        s.restore_state(&before).unwrap();
        s.solve_next_step(&p, &step).unwrap();
        let again = s
            .solve_next_step(&p, &shift_step(&p, 0.0, 0.0, 0.0))
            .unwrap();
        assert!((next.totals.fx_n - again.totals.fx_n).abs() <= 1e-6 * limit);
        assert!((next.totals.fy_n - again.totals.fy_n).abs() <= 1e-6 * limit);
    }

    #[test]
    fn a_step_force_at_saturation_is_refused() {
        let (p, mut s) = loaded();
        let step = shift_step(&p, 0.0, 0.0, 0.0);
        let cases = [
            (Some(1.01 * MU * FN), None, STEP_FORCE_X_KEY),
            (None, Some(-MU * FN), STEP_FORCE_Y_KEY),
            (
                Some(0.8 * MU * FN),
                Some(0.8 * MU * FN),
                "step.force_x_n, step.force_y_n",
            ),
        ];
        let mut before = SolverState::default();
        s.save_state(&mut before);
        let reference = s.clone().solve_next_step(&p, &step).unwrap();
        for (fx, fy, key) in cases {
            let target = PrescribedForce {
                force_x_n: fx,
                force_y_n: fy,
            };
            let e = solve_prescribed_force_step(&mut s, &p, &step, target, Default::default())
                .unwrap_err();
            assert_eq!(e.key(), Some(key), "{e}");
            // The solver keeps its state before the step.
            let again = s.clone().solve_next_step(&p, &step).unwrap();
            assert_eq!(again.totals.fx_n, reference.totals.fx_n);
            assert_eq!(again.totals.fy_n, reference.totals.fy_n);
        }
    }

    #[test]
    fn a_sequence_of_steps_with_forces_follows_the_forward_path() {
        // Load, a shift, two rolling steps of one element each: the forces
        // of a forward solve, prescribed step by step (the load step as
        // given, Fx for the shift, Fx and then Fy for the rolling steps),
        // give back the shifts and rolled creepages they came from.
        let (mut p, _) = loaded();
        let dq = p.grid.dx_m;
        let steps = vec![
            shift_step(&p, 0.0, 0.0, 0.0),
            shift_step(&p, 2e-6, 0.0, 0.0),
            ShiftStep::rolling(p.load, dq, &creep(1e-3, 2e-4, 0.0)),
            ShiftStep::rolling(p.load, dq, &creep(5e-4, -3e-4, 0.0)),
        ];
        p.kinematics = Kinematics::Transient(steps.clone());
        let mut s = ContactSolver::new(&p, KernelCache::global());
        let forward = s.solve(&p).unwrap();
        let fx = |k: usize| PrescribedForce {
            force_x_n: Some(forward[k].totals.fx_n),
            force_y_n: None,
        };
        let forces = [
            PrescribedForce::default(),
            fx(1),
            fx(2),
            PrescribedForce {
                force_x_n: None,
                force_y_n: Some(forward[3].totals.fy_n),
            },
        ];
        // The steps' shifts in the prescribed directions are only starts.
        let mut start = steps.clone();
        start[1].shift_x_m = 0.0;
        start[2].shift_x_m = 0.0;
        start[3].shift_y_m = 0.0;
        let q = ContactProblem {
            kinematics: Kinematics::Transient(start),
            ..p.clone()
        };
        s.reset();
        let r = solve_steps_with_forces(
            &mut s,
            &q,
            &forces,
            Default::default(),
            "transient.steps",
            |_, _| {},
        )
        .unwrap();
        assert_eq!(r.len(), 4);
        assert_eq!(r[0].outer_iterations, 0);
        for (k, got) in r.iter().enumerate() {
            assert!(got.converged, "step {k}");
            for (a, b) in [
                (got.step.shift_x_m, steps[k].shift_x_m),
                (got.step.shift_y_m, steps[k].shift_y_m),
            ] {
                assert!(
                    (a - b).abs() <= 1e-6 * b.abs().max(1e-9),
                    "step {k}: {a:e} against {b:e}"
                );
            }
            assert_eq!(got.step.rolling_m, steps[k].rolling_m);
        }
        // A force beyond saturation names its step.
        let mut bad = forces;
        bad[2].force_x_n = Some(2.0 * MU * FN);
        s.reset();
        let e = solve_steps_with_forces(
            &mut s,
            &q,
            &bad,
            Default::default(),
            "transient.steps",
            |_, _| {},
        )
        .unwrap_err();
        assert_eq!(e.key(), Some("transient.steps[2].force_x_n"), "{e}");
        let no_change = |_: usize, _: &mut ContactProblem| {};
        let e = solve_steps_with_forces(
            &mut s,
            &q,
            &bad[..3],
            Default::default(),
            "transient.steps",
            no_change,
        )
        .unwrap_err();
        assert_eq!(e.key(), Some("transient.steps"), "{e}");
    }
}
