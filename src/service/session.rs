//! A co-simulation session on one contact patch: the state machine behind
//! `PatchSession`, free of any transport.
//!
//! The session owns its [`PatchEngine`] (and so its exact solver: warm
//! starts and the transient history) and nothing else; it shares no
//! mutable state with other sessions, which is why a session's outputs do
//! not depend on what other sessions run meanwhile. Steps must come in
//! order. A marked step stores a clone of the engine after that step;
//! rolling back restores the clone, so repeating the steps after it
//! reproduces their outputs bit for bit.

use std::collections::BTreeMap;

use crate::core::normal::NormalLoad;
use crate::core::problem::{Creepages, Kinematics, ShiftStep};
use crate::problem::case::{check_shift_step, ranges, Model};
use crate::service::convert;
use crate::service::engine::PatchEngine;
use crate::service::pb;
use crate::service::status::ServiceError;

/// Marks kept per session; marking more drops the oldest.
pub const MAX_MARKS: usize = 16;

/// What the steps of a session prescribe, fixed by the opening case.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SessionKind {
    /// Frictionless normal contact: steps give loads.
    Frictionless,
    /// Steady rolling: steps give creepages (and loads).
    SteadyRolling,
    /// Transient shifts (exact model): steps give shifts (and loads).
    Transient,
}

/// A validated step, ready to solve.
#[derive(Debug, Clone, Copy)]
pub struct StepInput {
    index: u64,
    time_s: f64,
    load: NormalLoad,
    motion: Motion,
    mark: bool,
}

#[derive(Debug, Clone, Copy)]
enum Motion {
    Static,
    Rolling(Creepages),
    Shift(ShiftStep),
}

/// The step order and the marked states of a session (of any kind): the
/// index the next step must have, and a state per marked step.
#[derive(Debug)]
pub struct Marks<T> {
    next_step: u64,
    marks: BTreeMap<u64, T>,
}

impl<T: Clone> Marks<T> {
    /// No step yet, nothing marked.
    pub fn new() -> Self {
        Self {
            next_step: 0,
            marks: BTreeMap::new(),
        }
    }

    /// The index the next step must have.
    pub fn next_step(&self) -> u64 {
        self.next_step
    }

    /// FAILED_PRECONDITION unless `index` is the next step's.
    pub fn check_order(&self, index: u64) -> Result<(), ServiceError> {
        if index == self.next_step {
            return Ok(());
        }
        Err(ServiceError::precondition(
            "step.step_index",
            format!(
                "step_index {index} is out of order: this session expects step {} next \
             (steps are consecutive from 0; to repeat earlier steps, roll back to a marked step{})",
                self.next_step,
                self.list()
            ),
        ))
    }

    /// Step `index` succeeded; `state` (the state after it) is kept when
    /// the step is marked (dropping the oldest mark beyond [`MAX_MARKS`]).
    pub fn done(&mut self, index: u64, mark: bool, state: impl FnOnce() -> T) {
        self.next_step = index + 1;
        if mark {
            if self.marks.len() >= MAX_MARKS {
                self.marks.pop_first();
            }
            self.marks.insert(index, state());
        }
    }

    /// Goes back to marked step `to`: its state; later marks are dropped,
    /// the mark itself stays.
    pub fn rollback(&mut self, to: u64) -> Result<(T, pb::SessionRolledBack), ServiceError> {
        let state = self.marks.get(&to).cloned().ok_or_else(|| {
            ServiceError::precondition(
                "rollback.to_step_index",
                format!(
                    "step {to} is not marked in this session{}; mark a step with `mark = true`",
                    self.list()
                ),
            )
        })?;
        self.marks.split_off(&(to + 1));
        self.next_step = to + 1;
        Ok((
            state,
            pb::SessionRolledBack {
                to_step_index: to,
                next_step_index: self.next_step,
            },
        ))
    }

    /// " (marked: 3, 7)" or " (none is marked)", for messages.
    pub fn list(&self) -> String {
        if self.marks.is_empty() {
            " (none is marked)".to_string()
        } else {
            let k: Vec<String> = self.marks.keys().map(|k| k.to_string()).collect();
            format!(" (marked: {})", k.join(", "))
        }
    }
}

impl<T: Clone> Default for Marks<T> {
    fn default() -> Self {
        Self::new()
    }
}

/// One open session.
pub struct Session {
    engine: PatchEngine,
    kind: SessionKind,
    fields: bool,
    default_load: NormalLoad,
    marks: Marks<PatchEngine>,
}

impl Session {
    /// Opens a session on a validated case (field paths relative to `open`).
    pub fn open(engine: PatchEngine, fields: bool) -> Result<Self, ServiceError> {
        let case = engine.case();
        convert::check_fields(case, fields)?;
        let kind = match case.kinematics {
            Kinematics::Frictionless => SessionKind::Frictionless,
            Kinematics::SteadyRolling(_) => SessionKind::SteadyRolling,
            Kinematics::Transient(_) if case.model == Model::Exact => SessionKind::Transient,
            Kinematics::Transient(_) => {
                return Err(ServiceError::invalid(
                    "case.transient",
                    format!(
                        "transient sessions run the exact model only, not {}",
                        case.model.name()
                    ),
                ))
            }
        };
        Ok(Self {
            default_load: case.load,
            engine,
            kind,
            fields,
            marks: Marks::new(),
        })
    }

    /// The session kind.
    pub fn kind(&self) -> SessionKind {
        self.kind
    }

    /// The engine (its case and grid).
    pub fn engine(&self) -> &PatchEngine {
        &self.engine
    }

    /// The index the next step must have.
    pub fn next_step(&self) -> u64 {
        self.marks.next_step()
    }

    /// Checks a step's order and inputs without solving; field paths are
    /// relative to the request (`step.`).
    pub fn check_step(&self, s: &pb::SessionStep) -> Result<StepInput, ServiceError> {
        self.marks.check_order(s.step_index)?;
        if !self.engine.history_intact() {
            return Err(ServiceError::precondition("", format!(
                "a previous step was rejected by the solver after it had started (the patch reached \
                 the grid border), so the session's history is no longer that of step {}; roll back \
                 to a marked step{} or open a new session with a larger grid window",
                self.marks.next_step().saturating_sub(1),
                self.marks.list()
            )));
        }
        if !s.time_s.is_finite() {
            return Err(ServiceError::invalid(
                "step.time_s",
                format!("must be finite, got {}", s.time_s),
            ));
        }
        let load = match s.load {
            Some(pb::session_step::Load::NormalForceN(f)) => {
                ranges::NORMAL_FORCE.check("step.normal_force_n", f)?;
                NormalLoad::NormalForce(f)
            }
            Some(pb::session_step::Load::ApproachM(d)) => {
                ranges::APPROACH.check("step.approach_m", d)?;
                NormalLoad::Approach(d)
            }
            None => self.default_load,
        };
        let unused = |field: &str, what: &str| {
            ServiceError::invalid(
                format!("step.{field}"),
                format!("not used in a {what} session"),
            )
        };
        let motion = match self.kind {
            SessionKind::Frictionless => {
                if s.creepages.is_some() {
                    return Err(unused("creepages", "frictionless"));
                }
                if s.shift.is_some() {
                    return Err(unused("shift", "frictionless"));
                }
                Motion::Static
            }
            SessionKind::SteadyRolling => {
                if s.shift.is_some() {
                    return Err(unused("shift", "steady-rolling"));
                }
                let c = s
                    .creepages
                    .as_ref()
                    .map(convert::creepages)
                    .unwrap_or_default();
                c.check_input()
                    .map_err(|e| ServiceError::from(e).rekey("rolling.", "step.creepages."))?;
                Motion::Rolling(c)
            }
            SessionKind::Transient => {
                if s.creepages.is_some() {
                    return Err(unused("creepages", "transient"));
                }
                let sh = s
                    .shift
                    .as_ref()
                    .ok_or_else(|| ServiceError::invalid("step.shift", "missing"))?;
                if sh.normal_force_n.is_some() || sh.approach_m.is_some() {
                    return Err(ServiceError::invalid(
                        "step.shift.normal_force_n",
                        "give the step's load in step.normal_force_n or step.approach_m",
                    ));
                }
                let shift = ShiftStep {
                    load,
                    shift_x_m: sh
                        .shift_x_m
                        .ok_or_else(|| ServiceError::invalid("step.shift.shift_x_m", "missing"))?,
                    shift_y_m: sh.shift_y_m,
                    rotation_rad: sh.rotation_rad,
                };
                check_shift_step("step.shift", &shift)?;
                Motion::Shift(shift)
            }
        };
        Ok(StepInput {
            index: s.step_index,
            time_s: s.time_s,
            load,
            motion,
            mark: s.mark,
        })
    }

    /// Solves a checked step (CPU-bound: run it on the solve pool). A
    /// failed step leaves the step counter where it was.
    pub fn step(&mut self, input: StepInput) -> Result<pb::SessionStepResult, ServiceError> {
        self.engine.set_load(input.load);
        let result = match input.motion {
            Motion::Static => self.engine.solve(self.fields),
            Motion::Rolling(c) => {
                self.engine.set_creepages(c);
                self.engine.solve(self.fields)
            }
            Motion::Shift(shift) => self.engine.solve_next_step(&shift, self.fields),
        }
        .map_err(|e| e.rekey("load", "step").rekey("grid", "open.case.grid"))?;
        let engine = &self.engine;
        self.marks.done(input.index, input.mark, || engine.clone());
        Ok(pb::SessionStepResult {
            step_index: input.index,
            time_s: input.time_s,
            result: result.result,
            fields: result.fields,
            marked: input.mark,
        })
    }

    /// Goes back to the state after marked step `to`; later marks are
    /// dropped, the mark itself stays.
    pub fn rollback(&mut self, to: u64) -> Result<pb::SessionRolledBack, ServiceError> {
        let (engine, out) = self.marks.rollback(to)?;
        self.engine = engine;
        Ok(out)
    }
}
