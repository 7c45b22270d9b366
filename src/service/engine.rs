//! One contact patch as the service runs it: a validated case and, for the
//! exact model, the problem and the [`ContactSolver`] that keeps warm
//! starts and the transient history between calls.
//!
//! The exact model runs on the core directly (the solver must outlive one
//! request: creep curves and sessions warm-start from it). The other
//! models run through the same functions as `railcontact solve`, so the
//! service and the command line give the same numbers; they keep no state
//! between calls.
//!
//! An engine is plain synchronous code: the server moves it onto a solve
//! thread and back.

use crate::conformal::frictional::FrictionalWorkspace;
use crate::core::cache::KernelCache;
use crate::core::force::{
    continued_start, solve_prescribed_force_step, ForceControlSettings, PrescribedForce,
};
use crate::core::memory::HeapBytes;
use crate::core::normal::NormalLoad;
use crate::core::problem::{ContactProblem, Creepages, Kinematics, ShiftStep};
use crate::core::sensitivity::{
    central_differences, exact_jacobian, forces_of, ForceJacobian, JacobianPoint, JacobianSteps,
};
use crate::core::solution::{ContactSolution, Totals};
use crate::core::solve::{ContactSolver, SolverState};
use crate::problem::case::{Case, Model, TransientStep};
use crate::problem::reference_models as reference;
use crate::problem::report::StepForceReport;
use crate::problem::{solve_exact, ModelRun, SolutionExtras};
use crate::service::convert::{self, ValidCase};
use crate::service::pb;
use crate::service::status::ServiceError;

/// Whether the Jacobian of the forces can be computed for `case`: steady
/// rolling with the exact or fastsim model; INVALID_ARGUMENT
/// `include_sensitivities` otherwise.
pub fn check_sensitivities(case: &Case) -> Result<(), ServiceError> {
    let steady = matches!(case.kinematics, Kinematics::SteadyRolling(_));
    if steady && matches!(case.model, Model::Exact | Model::Fastsim) {
        return Ok(());
    }
    Err(ServiceError::invalid(
        "include_sensitivities",
        format!(
            "the Jacobian of the forces is computed for steady rolling with the exact or \
             fastsim model; this case is {} with model {}",
            if steady {
                "steady rolling"
            } else {
                "not steady rolling"
            },
            case.model.name()
        ),
    ))
}

/// The exact model's persistent state.
struct Exact {
    problem: ContactProblem,
    solver: ContactSolver,
    /// The last transient step solved by `solve_next_step`, as solved (the
    /// next prescribed force's secant continues from it).
    last_step: Option<ShiftStep>,
    /// How far the quadratic undeformed distance has travelled in +x over
    /// the grid in the steps of `solve_next_step` \[m\].
    gap_offset_m: f64,
    /// Whether the case adds a gap per element (`extra_gap_m`): the gap
    /// then does not travel.
    extra_gap: bool,
}

/// A contact patch ready to solve.
pub struct PatchEngine {
    case: Case,
    exact: Option<Exact>,
    /// Compute the Jacobian of the forces with every solve.
    sensitivities: bool,
    /// Buffers of the conformal models' solves, kept between steps.
    conformal: FrictionalWorkspace,
}

impl PatchEngine {
    /// An engine for a validated case; the exact model fetches its kernels
    /// from `cache` (built on a miss).
    pub fn new(valid: ValidCase, cache: &KernelCache) -> Result<Self, ServiceError> {
        let ValidCase { case, extra_gap_m } = valid;
        if !case.step_gap_offsets_m.is_empty() && !extra_gap_m.is_empty() {
            return Err(ServiceError::invalid(
                "geometry.extra_gap_m",
                "a gap given per element does not travel: not with transient steps' \
                 `gap_travel_x_m`",
            ));
        }
        let exact = if case.model == Model::Exact {
            let mut problem = case.problem()?;
            for (h, e) in problem.gap_m.iter_mut().zip(&extra_gap_m) {
                *h += e;
            }
            let mut solver = ContactSolver::new(&problem, cache);
            // Large steady-rolling cases start from their solution on the
            // grid of twice the element size (the first solve's start).
            solver.start_nested(&problem, cache)?;
            Some(Exact {
                problem,
                solver,
                last_step: None,
                gap_offset_m: 0.0,
                extra_gap: !extra_gap_m.is_empty(),
            })
        } else {
            None
        };
        Ok(Self {
            case,
            exact,
            sensitivities: false,
            conformal: FrictionalWorkspace::default(),
        })
    }

    /// The validated case.
    pub fn case(&self) -> &Case {
        &self.case
    }

    /// The potential contact grid of the exact and conformal models.
    pub fn grid(&self) -> Option<pb::GridInfo> {
        match self.case.model {
            Model::Exact | Model::Cect | Model::CectHalfspace => {
                self.case.grid().ok().map(|g| convert::grid_info(&g))
            }
            _ => None,
        }
    }

    /// Copies what the next solves read from the solves before them into
    /// `to` (reusing its buffers): the load and creepages and the exact
    /// solver's [`SolverState`]. The other models keep nothing between
    /// solves (the conformal buffers are no state: answers do not depend
    /// on them).
    pub fn save(&self, to: &mut EngineState) {
        to.load = Some(self.case.load);
        to.creepages = match self.case.kinematics {
            Kinematics::SteadyRolling(c) => Some(c),
            _ => None,
        };
        if let Some(e) = &self.exact {
            e.solver.save_state(&mut to.solver);
            to.last_step = e.last_step;
            to.gap_offset_m = e.gap_offset_m;
        }
    }

    /// Puts back a state saved from this engine: the next solve gives the
    /// same bits as it would have given right after the save.
    pub fn restore(&mut self, from: &EngineState) -> Result<(), ServiceError> {
        if let Some(load) = from.load {
            self.set_load(load);
        }
        if let Some(c) = from.creepages {
            self.set_creepages(c);
        }
        if let Some(e) = &mut self.exact {
            e.solver.restore_state(&from.solver).map_err(|err| {
                ServiceError::Internal(format!("restoring a session state: {err}"))
            })?;
            e.last_step = from.last_step;
            if e.gap_offset_m != from.gap_offset_m {
                e.move_gap(&self.case, from.gap_offset_m);
            }
        }
        Ok(())
    }

    /// The size of [`PatchEngine::save`]'s copy \[bytes\].
    pub fn state_bytes(&self) -> usize {
        std::mem::size_of::<EngineState>()
            + self.exact.as_ref().map_or(0, |e| e.solver.state_bytes())
    }

    /// The memory the engine holds between solves \[bytes\]: the exact
    /// model's solver (its buffers, not the cache's kernels), gap and
    /// numerical influence coefficients (sent inline: up to 3.3 times the
    /// request's text), the conformal models' workspace.
    pub fn heap_bytes(&self) -> usize {
        let exact = self.exact.as_ref().map_or(0, |e| {
            e.solver.heap_bytes()
                + e.problem.gap_m.heap_bytes()
                + e.problem.extra_rigid_slip.heap_bytes()
                + e.problem
                    .numerical_influence
                    .as_deref()
                    .map_or(0, HeapBytes::heap_bytes)
        });
        exact + self.conformal.heap_bytes()
    }

    /// Frees the buffers that hold no state (the exact solver's Newton
    /// scratch, the conformal workspace): the next solve allocates them
    /// again and gives the same bits.
    pub fn release_scratch(&mut self) {
        if let Some(e) = &mut self.exact {
            e.solver.release_scratch();
        }
        self.conformal = FrictionalWorkspace::default();
    }

    /// Computes the Jacobian of the forces with every solve from now on
    /// (see [`check_sensitivities`]).
    pub fn enable_sensitivities(&mut self) -> Result<(), ServiceError> {
        check_sensitivities(&self.case)?;
        self.sensitivities = true;
        Ok(())
    }

    /// Whether every solve computes the Jacobian of the forces.
    pub fn sensitivities(&self) -> bool {
        self.sensitivities
    }

    /// Replaces the normal load of the next solves.
    pub fn set_load(&mut self, load: NormalLoad) {
        self.case.load = load;
        if let Some(e) = &mut self.exact {
            e.problem.load = load;
        }
    }

    /// Replaces the creepages of a steady-rolling case.
    pub fn set_creepages(&mut self, c: Creepages) {
        self.case.kinematics = Kinematics::SteadyRolling(c);
        if let Some(e) = &mut self.exact {
            e.problem.kinematics = Kinematics::SteadyRolling(c);
        }
    }

    /// Replaces the creepages of a steady-rolling case and the forces the
    /// next solves prescribe; the creepage of a direction with a force
    /// starts its iteration from the creepage the last solve had (found or
    /// given): a session's step continues from its last step.
    pub fn set_rolling(&mut self, c: Creepages, force: PrescribedForce) {
        let last = self.case.creepages();
        let start = Creepages {
            creepage_long: match force.force_x_n {
                Some(_) => last.creepage_long,
                None => c.creepage_long,
            },
            creepage_lat: match force.force_y_n {
                Some(_) => last.creepage_lat,
                None => c.creepage_lat,
            },
            spin_per_m: c.spin_per_m,
        };
        self.case.prescribed_force = force;
        self.set_creepages(start);
    }

    /// Solves the case: one solution, or one per transient step (which
    /// then start from the unloaded state, or from the steady rolling
    /// state of `transient.steady_start`). Steady-rolling and static
    /// solves of the exact model warm-start from the previous solve.
    pub fn solve(&mut self, fields: bool) -> Result<pb::PatchResult, ServiceError> {
        let (mut result, jacobian) = match &mut self.exact {
            Some(e) => {
                let solved = solve_exact(&self.case, &mut e.solver, &e.problem)?;
                if let Some(f) = &solved.force_control {
                    // The Jacobian (if asked) is taken about the creepages
                    // found, and a session's next step starts from them.
                    let found = Kinematics::SteadyRolling(Creepages {
                        creepage_long: f.creepage_long,
                        creepage_lat: f.creepage_lat,
                        spin_per_m: f.spin_per_m,
                    });
                    e.problem.kinematics = found.clone();
                    self.case.kinematics = found;
                }
                let (solutions, force) = (solved.solutions, solved.force_control);
                let grid = e.problem.grid;
                let jacobian = match (&self.exact, solutions.last()) {
                    (Some(e), Some(base)) if self.sensitivities => {
                        Some(exact_jacobian(&e.solver, &e.problem, base)?)
                    }
                    _ => None,
                };
                let mut result = self.exact_result(&solutions, &solved.step_forces, fields);
                result.force_control = force.as_ref().map(convert::force_control);
                result.steady_start = solved.steady_start.as_ref().map(convert::step_of_solution);
                if let Some(last) = solutions.last() {
                    let extras = SolutionExtras::of(&self.case, &grid, last)?;
                    result.temperature = extras
                        .temperature
                        .as_ref()
                        .map(|t| convert::temperature_result(t, fields));
                    result.subsurface = extras.subsurface.map(|s| {
                        convert::subsurface_result(
                            &grid,
                            &s.bodies,
                            s.surface_fatigue_index,
                            fields,
                        )
                    });
                }
                (result, jacobian)
            }
            None => {
                let (mut r, totals) = self.reference_result(fields)?;
                r.notes.extend(self.case.notes.iter().cloned());
                let jacobian = match self.sensitivities {
                    true => Some(self.fastsim_jacobian(&totals)?),
                    false => None,
                };
                (r, jacobian)
            }
        };
        if let (Some(j), Some(step)) = (jacobian, result.result.as_mut()) {
            step.sensitivities = Some(convert::sensitivities(&j));
        }
        self.check_finite(&result)?;
        Ok(result)
    }

    /// Solves one more transient step of the exact model, from the state
    /// the previous step left, with the bodies' undeformed distance moved
    /// its `gap_travel_x_m` further over the grid, for the shift giving its
    /// prescribed force if it has one (errors name `step.shift.…`).
    pub fn solve_next_step(
        &mut self,
        step: &TransientStep,
        fields: bool,
    ) -> Result<pb::PatchResult, ServiceError> {
        let gap_travel_x_m = step.gap_travel_x_m;
        let e = self.exact.as_mut().ok_or_else(|| {
            ServiceError::invalid("model", "transient sessions run the exact model only")
        })?;
        if gap_travel_x_m != 0.0 {
            if e.extra_gap {
                return Err(ServiceError::invalid(
                    "step.shift.gap_travel_x_m",
                    "moves the quadratic undeformed distance: not with a gap given per element \
                     (`geometry.extra_gap_m`)",
                ));
            }
            e.move_gap(&self.case, e.gap_offset_m + gap_travel_x_m);
        }
        let start = match &e.last_step {
            Some(previous) => continued_start(previous, &step.step, step.force),
            None => step.step,
        };
        let f = solve_prescribed_force_step(
            &mut e.solver,
            &e.problem,
            &start,
            step.force,
            ForceControlSettings::default(),
        )
        .map_err(|err| err.with_key_prefix("step", "step.shift"))?;
        e.last_step = Some(f.step);
        let report = StepForceReport::of("step.shift", step.force, &f)?;
        let result = self.exact_result(std::slice::from_ref(&f.solution), &[report], fields);
        self.check_finite(&result)?;
        Ok(result)
    }

    /// Refuses a result with a non-finite figure as INVALID_ARGUMENT naming
    /// the input that drives the solve (creepages of steady rolling, the
    /// shifts of transient steps, the load of frictionless contact): inputs
    /// this far outside rolling contact overflow the arithmetic.
    fn check_finite(&self, result: &pb::PatchResult) -> Result<(), ServiceError> {
        convert::check_finite(result).map_err(|_| {
            let field = match (&self.case.kinematics, self.case.load) {
                (Kinematics::SteadyRolling(_), _) => "rolling",
                (Kinematics::Transient(_), _) => "transient",
                (Kinematics::Frictionless, NormalLoad::NormalForce(_)) => "load.normal_force_n",
                (Kinematics::Frictionless, NormalLoad::Approach(_)) => "load.approach_m",
            };
            ServiceError::invalid(
                field,
                "the solve gives non-finite forces for these inputs: they are too far outside \
                 wheel/rail contact for the arithmetic (creepages, spin and shifts of rolling \
                 contact are small: |creepage| < 1, |spin| times the patch size < 1)",
            )
        })
    }

    /// The Jacobian of a FASTSIM solution with `totals`: central
    /// differences of FASTSIM solves (each costs microseconds).
    fn fastsim_jacobian(&self, totals: &Totals) -> Result<ForceJacobian, ServiceError> {
        let Kinematics::SteadyRolling(creepages) = self.case.kinematics else {
            return Err(ServiceError::Internal(
                "sensitivities of a case that is not steady rolling".into(),
            ));
        };
        let steps = JacobianSteps::for_solution(
            totals,
            self.case.friction.kinetic_coefficient,
            self.case.material.shear_modulus_pa,
        );
        let point = JacobianPoint {
            approach_m: totals.approach_m,
            creepages,
        };
        let mut case = self.case.clone();
        central_differences(point, steps, |approach_m, c| {
            case.load = NormalLoad::Approach(approach_m);
            case.kinematics = Kinematics::SteadyRolling(c);
            let r = reference::solve_fastsim(&case)?;
            Ok::<_, ServiceError>(forces_of(&r.totals.totals))
        })
    }

    /// The result of a model other than exact, through the problem layer's
    /// model dispatch (as `railcontact solve`), with its totals.
    fn reference_result(
        &mut self,
        fields: bool,
    ) -> Result<(pb::PatchResult, Totals), ServiceError> {
        let case = &self.case;
        let run = ModelRun::solve(case, &mut self.conformal)?;
        let report = run.report(case, fields);
        Ok((convert::result_of_report(&report), report.totals.totals))
    }

    /// The wire result of exact-model solutions (the last is the result),
    /// with the shifts their prescribed step forces found (`step_forces`,
    /// one per solution or empty).
    fn exact_result(
        &self,
        solutions: &[ContactSolution],
        step_forces: &[Option<StepForceReport>],
        fields: bool,
    ) -> pb::PatchResult {
        let case = &self.case;
        let frictional = case.has_friction && !matches!(case.kinematics, Kinematics::Frictionless);
        let steps: Vec<pb::StepResult> = solutions
            .iter()
            .enumerate()
            .map(|(k, s)| {
                let mut step = convert::step_of_solution(s);
                step.force_control = step_forces
                    .get(k)
                    .copied()
                    .flatten()
                    .map(|f| convert::step_force_control(&f));
                step
            })
            .collect();
        let last = solutions.last();
        pb::PatchResult {
            model: pb::Model::Exact as i32,
            result: steps.last().cloned(),
            steps: if steps.len() > 1 { steps } else { Vec::new() },
            friction_coefficient: if frictional {
                case.friction.kinetic_coefficient
            } else {
                0.0
            },
            grid: self.grid(),
            notes: case.notes.clone(),
            fields: last.filter(|_| fields).map(|s| {
                let mut f = convert::planar_fields(&s.fields);
                if let Some(l) = self.exact.as_ref().and_then(|e| e.solver.layer_fields()) {
                    convert::add_layer_fields(&mut f, &l);
                }
                f
            }),
            force_control: None,
            subsurface: None,
            temperature: None,
            fastsim_max_pressure_pa: None,
            steady_start: None,
        }
    }
}

impl Exact {
    /// Puts the case's quadratic gap `offset_m` along +x on the grid.
    fn move_gap(&mut self, case: &Case, offset_m: f64) {
        let grid = self.problem.grid;
        ContactProblem::quadratic_gap_at(
            &grid,
            case.a_per_m,
            case.b_per_m,
            offset_m,
            &mut self.problem.gap_m,
        );
        self.gap_offset_m = offset_m;
    }
}

impl HeapBytes for EngineState {
    fn heap_bytes(&self) -> usize {
        self.solver.heap_bytes()
    }
}

/// What [`PatchEngine::save`] keeps: what the next solves read from the
/// solves before them. A session's refused step restores it; a mark keeps
/// one.
#[derive(Clone, Default)]
pub struct EngineState {
    load: Option<NormalLoad>,
    creepages: Option<Creepages>,
    /// The exact solver's state (empty for the other models).
    solver: SolverState,
    /// The exact model's last transient step as solved.
    last_step: Option<ShiftStep>,
    /// How far the exact model's gap has travelled \[m\].
    gap_offset_m: f64,
}
