//! The problem layer: one contact patch as a user states it, solved with
//! the model the user chose, reported in SI units.
//!
//! * [`case`]: the case description (materials, friction, geometry, load,
//!   kinematics, grid, solver settings), read from TOML and validated
//!   ([`case::Case`]), and the model names ([`case::Model`]);
//! * [`report`]: what a solve gives back ([`report::Report`]);
//! * [`ModelRun`]: "solve this case with its model": the exact model on
//!   the core, the conformal models ([`conformal_models`]) and the
//!   closed-form and FASTSIM models ([`reference_models`]).
//!
//! The command line and the service both stand on this layer, so they give
//! the same numbers for the same case.

pub mod case;
pub mod conformal_models;
pub mod reference_models;
pub mod report;

use std::time::Instant;

use thiserror::Error;

use crate::conformal::frictional::FrictionalWorkspace;
use crate::core::cache::KernelCache;
use crate::core::error::ContactError;
use crate::core::force::{
    solve_prescribed_force, solve_steps_with_forces, ForceControlSettings, PrescribedForce,
};
use crate::core::grid::Grid;
use crate::core::layer::LayerFields;
use crate::core::problem::{ContactProblem, Kinematics};
use crate::core::solution::{ContactSolution, SolveStatus};
use crate::core::solve::ContactSolver;
use crate::core::subsurface::{subsurface_fields, surface_fatigue_index, BodySubsurface};
use crate::core::temperature::{flash_temperatures, SurfaceTemperatures};

use case::{Case, Model};
use conformal_models::ConformalRun;
use report::{
    Fields, FieldsReport, ForceControlReport, LayerReport, Report, StepForceReport, StepReport,
    SubsurfaceReport,
};

/// Why a case could not be solved.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum CaseError {
    /// The input is wrong: the message names the key to fix and says how.
    #[error("{0}")]
    BadInput(String),
    /// The case is valid but could not be solved.
    #[error("{0}")]
    Failure(String),
    /// The solve was stopped before it finished ([`crate::core::cancel`]).
    #[error("the solve was cancelled before it finished")]
    Cancelled,
}

impl From<ContactError> for CaseError {
    fn from(e: ContactError) -> Self {
        match e {
            ContactError::Cancelled => CaseError::Cancelled,
            // Every other core error is about the input: a key out of
            // range, a grid too small for the patch, no contact, a
            // rejected reference input. The message names the key (as
            // `invalid input `key`: ...`) wherever the error has one.
            ContactError::InvalidInput { .. } => CaseError::BadInput(e.to_string()),
            e => match e.key() {
                Some(key) => CaseError::BadInput(format!("invalid input `{key}`: {e}")),
                None => CaseError::BadInput(e.to_string()),
            },
        }
    }
}

/// One case solved with its model.
pub enum ModelRun {
    /// Kalker's exact theory on the planar half-space.
    Exact(ExactRun),
    /// The conformal models (`cect`, `cect_halfspace`).
    Conformal(ConformalRun),
    /// The closed-form and FASTSIM models: their report is the whole result.
    Reference(Box<Report<'static>>),
}

impl ModelRun {
    /// Solves `case` with `case.model`; the conformal models keep their
    /// buffers in `workspace` (reused between solves).
    pub fn solve(case: &Case, workspace: &mut FrictionalWorkspace) -> Result<Self, CaseError> {
        Ok(match case.model {
            Model::Exact => ModelRun::Exact(ExactRun::solve(case)?),
            Model::Cect | Model::CectHalfspace => {
                ModelRun::Conformal(ConformalRun::solve(workspace, case)?)
            }
            Model::HertzCorrected => ModelRun::Reference(Box::new(
                reference_models::solve_conformal_hertz(case, true)?,
            )),
            Model::Hertz if case.geometry.is_conformal() => ModelRun::Reference(Box::new(
                reference_models::solve_conformal_hertz(case, false)?,
            )),
            Model::Hertz => ModelRun::Reference(Box::new(reference_models::solve_hertz(case)?)),
            Model::Fastsim => ModelRun::Reference(Box::new(reference_models::solve_fastsim(case)?)),
        })
    }

    /// The report of the run, with the per-element fields when `fields`
    /// (exact and conformal models only).
    pub fn report(&self, case: &Case, fields: bool) -> Report<'_> {
        match self {
            ModelRun::Exact(run) => run.report(case, fields),
            ModelRun::Conformal(run) => run.report(case, fields),
            ModelRun::Reference(report) => (**report).clone(),
        }
    }
}

/// The exact model's solutions of one case.
pub struct ExactRun {
    /// The potential contact grid.
    pub grid: Grid,
    /// One solution, or one per transient step (never empty).
    solutions: Vec<ContactSolution>,
    /// Wall time from the validated case to the solutions \[s\].
    elapsed_s: f64,
    /// Prescribed forces: the creepages found.
    force_control: Option<ForceControlReport>,
    /// Prescribed step forces: the shifts found, per step.
    step_forces: Vec<Option<StepForceReport>>,
    /// The steady rolling state the transient steps started from
    /// (`transient.steady_start`).
    steady_start: Option<Box<ContactSolution>>,
    /// The subsurface fields of both bodies below the (last) solution,
    /// when the case asks for them (`[subsurface]`).
    pub subsurface: Option<Box<SubsurfaceRun>>,
    /// The flash temperatures of both surfaces of the solution, when the
    /// case asks for them (`[temperature]`).
    pub temperature: Option<Box<SurfaceTemperatures>>,
    /// An elasto-plastic interfacial layer's state after the last solve
    /// (`[interfacial_layer]` with a yield limit).
    pub layer: Option<LayerFields>,
}

/// The exact model's solutions of a case, with what its prescribed forces
/// found.
pub struct ExactSolves {
    /// One solution, or one per transient step.
    pub solutions: Vec<ContactSolution>,
    /// Steady rolling with prescribed forces (`[rolling] force_x_n`, ...):
    /// the creepages found.
    pub force_control: Option<ForceControlReport>,
    /// Per transient step with a prescribed force: the shift found (empty
    /// when no step prescribes one).
    pub step_forces: Vec<Option<StepForceReport>>,
    /// The steady rolling state the transient steps started from
    /// (`transient.steady_start`).
    pub steady_start: Option<ContactSolution>,
}

/// Solves `case` with the exact model on `solver`, which was built for
/// `problem` (the case's problem, its undeformed distance as the caller
/// needs it): the creepages of prescribed forces in steady rolling, the
/// transient steps (from the unloaded state, or from the steady rolling
/// state of `transient.steady_start`, each at its own friction start,
/// solved for the shifts of prescribed step forces), or the problem as
/// given (steady and static solves warm-start from the solver's last).
pub fn solve_exact(
    case: &Case,
    solver: &mut ContactSolver,
    problem: &ContactProblem,
) -> Result<ExactSolves, CaseError> {
    let settings = ForceControlSettings::default();
    if case.prescribed_force.any() {
        let f = solve_prescribed_force(solver, problem, case.prescribed_force, settings)?;
        let report = ForceControlReport::of(&f)?;
        return Ok(ExactSolves {
            solutions: vec![f.solution],
            force_control: Some(report),
            step_forces: Vec::new(),
            steady_start: None,
        });
    }
    if case.step_forces.is_empty()
        && case.step_gap_offsets_m.is_empty()
        && case.steady_start.is_none()
        && case.step_slip_starts.is_empty()
    {
        return Ok(ExactSolves {
            solutions: solver.solve(problem)?,
            force_control: None,
            step_forces: Vec::new(),
            steady_start: None,
        });
    }
    let steady_start = match case.steady_start {
        Some(creepages) => {
            let steady = ContactProblem {
                kinematics: Kinematics::SteadyRolling(creepages),
                ..problem.clone()
            };
            solver.reset();
            let solved = solver
                .solve(&steady)
                .map_err(|e| e.with_key_prefix("rolling", "transient.steady_start"))?;
            solver.continue_from_last_solution();
            solved.into_iter().next_back()
        }
        None => {
            solver.reset();
            None
        }
    };
    let default_start = problem.friction.slip_velocity_law.map(|l| l.start);
    let steps = match &problem.kinematics {
        Kinematics::Transient(steps) => steps.len(),
        _ => 0,
    };
    let forces = if case.step_forces.is_empty() {
        vec![PrescribedForce::default(); steps]
    } else {
        case.step_forces.clone()
    };
    // Bodies travelling over the grid: a step's gap, moved where it
    // travelled (the problem's gap is the one at offset 0).
    let mut at = 0.0;
    let step = std::cell::Cell::new(0);
    let travel = |k: usize, p: &mut ContactProblem| {
        step.set(k);
        if let (Some(law), Some(start)) = (&mut p.friction.slip_velocity_law, default_start) {
            law.start = case
                .step_slip_starts
                .get(k)
                .copied()
                .flatten()
                .unwrap_or(start);
        }
        if let Some(&offset) = case.step_gap_offsets_m.get(k) {
            if offset != at {
                let grid = p.grid;
                ContactProblem::quadratic_gap_at(
                    &grid,
                    case.a_per_m,
                    case.b_per_m,
                    offset,
                    &mut p.gap_m,
                );
                at = offset;
            }
        }
    };
    let solved = solve_steps_with_forces(
        solver,
        problem,
        &forces,
        settings,
        "transient.steps",
        travel,
    )
    .map_err(|e| match e {
        // Travelled off the grid: say how far, and which key moved them.
        ContactError::GridTooSmall { key, detail } => {
            let k = step.get();
            match case.step_gap_offsets_m.get(k) {
                Some(&offset) if offset != 0.0 => ContactError::GridTooSmall {
                    key,
                    detail: format!(
                        "{detail}; at transient.steps[{k}] the bodies have travelled {} m over \
                         the grid (the steps' gap_travel_x_m summed)",
                        crate::core::error::show(offset)
                    ),
                },
                _ => ContactError::GridTooSmall { key, detail },
            }
        }
        e => e,
    })?;
    let mut solutions = Vec::with_capacity(solved.len());
    let mut step_forces = Vec::with_capacity(solved.len());
    for (k, (f, &target)) in solved.into_iter().zip(&forces).enumerate() {
        let key = format!("transient.steps[{k}]");
        step_forces.push(StepForceReport::of(&key, target, &f)?);
        solutions.push(f.solution);
    }
    Ok(ExactSolves {
        solutions,
        force_control: None,
        step_forces,
        steady_start,
    })
}

/// What a case asks of an exact solution besides its tractions, computed
/// in one place for the command line ([`ExactRun`]) and the service.
pub struct SolutionExtras {
    /// The subsurface fields (`[subsurface]`).
    pub subsurface: Option<SubsurfaceRun>,
    /// The flash temperatures of both surfaces (`[temperature]`).
    pub temperature: Option<SurfaceTemperatures>,
}

impl SolutionExtras {
    /// The extras `case` asks of `solution` on `grid`.
    pub fn of(case: &Case, grid: &Grid, solution: &ContactSolution) -> Result<Self, CaseError> {
        Ok(Self {
            subsurface: SubsurfaceRun::of(case, grid, solution)?,
            temperature: case
                .temperature
                .as_ref()
                .map(|input| flash_temperatures(grid, &solution.fields, input))
                .transpose()?,
        })
    }
}

/// The subsurface fields of both bodies below a solution.
pub struct SubsurfaceRun {
    /// Body 1, body 2.
    pub bodies: [BodySubsurface; 2],
    /// Ekberg's surface fatigue index, when the case gives
    /// `subsurface.shear_yield_stress_pa`.
    pub surface_fatigue_index: Option<f64>,
}

impl SubsurfaceRun {
    /// The fields below `solution` on `grid` for a case with
    /// `[subsurface]` (None without).
    pub fn of(
        case: &Case,
        grid: &Grid,
        solution: &ContactSolution,
    ) -> Result<Option<Self>, CaseError> {
        let Some(r) = &case.subsurface else {
            return Ok(None);
        };
        let t = &solution.totals;
        Ok(Some(SubsurfaceRun {
            bodies: subsurface_fields(grid, &case.material, &solution.fields, &r.depths_m)?,
            surface_fatigue_index: r.shear_yield_stress_pa.and_then(|k| {
                surface_fatigue_index(t.normal_force_n, t.fx_n.hypot(t.fy_n), t.contact_area_m2, k)
            }),
        }))
    }

    /// The peaks of both bodies' fields on `grid`.
    pub fn report(&self, grid: &Grid) -> SubsurfaceReport {
        let [b1, b2] = &self.bodies;
        SubsurfaceReport {
            depths_m: b1.depths_m.clone(),
            body1: b1.summary(grid),
            body2: b2.summary(grid),
            surface_fatigue_index: self.surface_fatigue_index,
        }
    }
}

impl ExactRun {
    /// Solves `case` with the core (Kalker's exact theory).
    pub fn solve(case: &Case) -> Result<Self, CaseError> {
        let t0 = Instant::now();
        let problem = case.problem()?;
        let cache = KernelCache::global();
        let mut solver = ContactSolver::new(&problem, cache);
        // Large cold steady-rolling problems start from their solution on
        // the grid of twice the element size.
        solver.start_nested(&problem, cache)?;
        let solved = solve_exact(case, &mut solver, &problem)?;
        let layer = solver.layer_fields();
        let (solutions, force_control, step_forces, steady_start) = (
            solved.solutions,
            solved.force_control,
            solved.step_forces,
            solved.steady_start.map(Box::new),
        );
        let Some(last) = solutions.last() else {
            return Err(CaseError::Failure("the solver returned no solution".into()));
        };
        let extras = SolutionExtras::of(case, &problem.grid, last)?;
        Ok(ExactRun {
            grid: problem.grid,
            solutions,
            step_forces,
            steady_start,
            elapsed_s: t0.elapsed().as_secs_f64(),
            force_control,
            subsurface: extras.subsurface.map(Box::new),
            temperature: extras.temperature.map(Box::new),
            layer,
        })
    }

    /// The solutions: one, or one per transient step.
    pub fn solutions(&self) -> &[ContactSolution] {
        &self.solutions
    }

    /// The steady rolling state the transient steps started from
    /// (`transient.steady_start`).
    pub fn steady_start(&self) -> Option<&ContactSolution> {
        self.steady_start.as_deref()
    }

    /// The (last) solution.
    pub fn last(&self) -> &ContactSolution {
        &self.solutions[self.solutions.len() - 1]
    }

    /// The report: the last step's totals with counters summed over steps.
    pub fn report(&self, case: &Case, with_fields: bool) -> Report<'_> {
        let steps: Vec<StepReport> = self
            .solutions
            .iter()
            .enumerate()
            .map(|(k, s)| StepReport {
                force_control: self.step_forces.get(k).copied().flatten(),
                ..StepReport::from_solution(s)
            })
            .collect();
        let steady_start = self.steady_start.as_deref().map(StepReport::from_solution);
        let all = || steady_start.iter().chain(&steps);
        let mut totals = StepReport::from_solution(self.last());
        totals.solve_time_s = self.elapsed_s;
        totals.normal_iterations = all().map(|s| s.normal_iterations).sum();
        totals.tangential_iterations = all().map(|s| s.tangential_iterations).sum();
        totals.iterations = all().map(|s| s.iterations).sum();
        totals.status = all().fold(SolveStatus::Converged, |a, s| a.worst(s.status));
        let mut notes = Vec::new();
        if self.grid.is_line() {
            notes.push(
                "line contact (plane strain): forces per metre of the cylinders [N/m], areas per metre [m²/m], \
                 the approach relative to the surface 1 m from the load"
                    .to_string(),
            );
        }
        if totals.status != SolveStatus::Converged {
            // Name the limit each failed step stopped at (that key raises it).
            let mut keys: Vec<&str> = self
                .steady_start
                .as_deref()
                .into_iter()
                .chain(&self.solutions)
                .filter_map(|s| s.info.limit.map(|l| l.key()))
                .collect();
            keys.sort_unstable();
            keys.dedup();
            notes.push(format!(
                "a solver hit its iteration limit: the result is the last iterate (raise {})",
                keys.iter()
                    .map(|k| format!("`{k}`"))
                    .collect::<Vec<_>>()
                    .join(" and ")
            ));
        }
        let frictional = case.has_friction && !matches!(case.kinematics, Kinematics::Frictionless);
        Report {
            model: Model::Exact,
            totals,
            fastsim_max_pressure_pa: None,
            friction_coefficient: if frictional {
                case.friction.kinetic_coefficient
            } else {
                0.0
            },
            grid: Some([self.grid.nx, self.grid.ny]),
            window_m: Some([case.window_x_m, case.window_y_m]),
            wfric_lateral: None,
            notes,
            steady_start,
            steps: matches!(case.kinematics, Kinematics::Transient(_)).then_some(steps),
            fields: with_fields.then_some(Fields::Planar(FieldsReport {
                grid: &self.grid,
                fields: &self.last().fields,
            })),
            geometry: None,
            force_control: self.force_control,
            subsurface: self.subsurface.as_ref().map(|s| s.report(&self.grid)),
            temperature: self.temperature.as_ref().map(|t| t.summary),
            interfacial_layer: self
                .layer
                .as_ref()
                .map(|l| LayerReport::of(&self.grid, l, with_fields)),
        }
    }
}
