//! A co-simulation session on one contact patch: the state machine behind
//! `PatchSession`, free of any transport.
//!
//! The session owns its [`PatchEngine`] (and so its exact solver: warm
//! starts and the transient history) and nothing else; it shares no
//! mutable state with other sessions, which is why a session's outputs do
//! not depend on what other sessions run meanwhile. Steps must come in
//! order.
//!
//! Steps are transactions: the engine's state ([`EngineState`]: the load,
//! the creepages, the exact solver's pressures, tractions, transient
//! history and warm-start path) is saved before a step and put back when
//! the step is refused for any reason (its inputs, the solver, a
//! non-finite result, a response too large to send, a mark beyond the
//! budget, a cancelled solve), so the next step gives the same bits as if
//! the refused one had never been sent.
//!
//! A marked step keeps a copy of that state (not the kernels or buffers);
//! rolling back puts it back, so repeating the steps after it reproduces
//! their outputs bit for bit. The session's live working state (the
//! engine's solver and buffers, the undo copy) and its marks count against
//! the memory limits per session and for the whole server
//! ([`crate::service::memory`]), settled after every step: a step that
//! would take the session beyond them is refused like any other, and the
//! session then gives back the buffers that hold no state.

use std::collections::BTreeMap;

use crate::core::force::PrescribedForce;
use crate::core::memory::HeapBytes;
use crate::core::normal::NormalLoad;
use crate::core::problem::{Creepages, Kinematics};
use crate::problem::case::{ranges, transient_step, Model, TransientStep};
use crate::service::convert;
use crate::service::engine::{EngineState, PatchEngine};
use crate::service::memory::{Beyond, SessionBudget, SessionMemory};
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
    /// Steady rolling at these creepages, or at the forces prescribed.
    Rolling(Creepages, PrescribedForce),
    /// A transient step (with how far the bodies' gap travels in it).
    Shift(TransientStep),
}

/// Field number of `step` in `SessionResponse` and `WheelRailSessionResponse`.
const STEP_FIELD: u32 = 2;

/// Refuses a step response that the server could not send: encoded in
/// its response message, more than `max_bytes` (`max_message_bytes`).
pub fn check_response_size<M: prost::Message>(
    step: &M,
    max_bytes: usize,
) -> Result<(), ServiceError> {
    let len = prost::encoding::message::encoded_len(STEP_FIELD, step);
    if len <= max_bytes {
        return Ok(());
    }
    Err(ServiceError::Exhausted(format!(
        "the step's response would be {len} bytes, more than this server's max_message_bytes \
         ({max_bytes}); the step was not applied: open the session without per-element fields \
         (`open.include_fields`) or on a coarser grid"
    )))
}

/// The step order and the marked states of a session (of any kind): the
/// index the next step must have, a state per marked step with its size
/// in bytes, and the session's memory in the server's count (its live
/// state and its marks).
#[derive(Debug)]
pub struct Marks<T> {
    next_step: u64,
    marks: BTreeMap<u64, (T, usize)>,
    memory: SessionMemory,
}

/// RESOURCE_EXHAUSTED for a session whose opening would take `live` bytes
/// beyond `beyond`.
fn open_refused(live: usize, beyond: Beyond) -> ServiceError {
    let Beyond {
        key,
        max_bytes,
        whose,
    } = beyond;
    ServiceError::Exhausted(format!(
        "opening this session takes {live} bytes of working state (its solvers' buffers), \
         beyond {whose} limit, this server's {key} ({max_bytes} bytes): open it on a coarser \
         grid, or retry when other sessions have closed"
    ))
}

impl<T> Marks<T> {
    /// No step yet, nothing marked; the session holds `live` bytes to
    /// begin with. RESOURCE_EXHAUSTED when they do not fit `budget`.
    pub fn open(budget: SessionBudget, live: usize) -> Result<Self, ServiceError> {
        Ok(Self {
            next_step: 0,
            marks: BTreeMap::new(),
            memory: SessionMemory::open(budget, live).map_err(|b| open_refused(live, b))?,
        })
    }

    /// Bytes held by this session's marks.
    pub fn bytes(&self) -> usize {
        self.memory.mark_bytes()
    }

    /// After a refused step: the session holds `live` bytes (it gave back
    /// what the step allocated).
    pub fn settle(&mut self, live: usize) {
        self.memory.settle(live);
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

    /// Step `index` succeeded and leaves the session holding `live` bytes
    /// of working state; `state` (the state after it, `bytes` in size) is
    /// kept when the step is marked, dropping the oldest mark beyond
    /// [`MAX_MARKS`]. RESOURCE_EXHAUSTED, and nothing changed, when the
    /// live state and the marks would take the session or the server
    /// beyond its limit.
    pub fn done(
        &mut self,
        index: u64,
        mark: bool,
        live: usize,
        bytes: usize,
        state: impl FnOnce() -> T,
    ) -> Result<(), ServiceError> {
        let evicted = match mark && self.marks.len() >= MAX_MARKS {
            true => self.marks.first_key_value().map_or(0, |(_, m)| m.1),
            false => 0,
        };
        let own = if mark { bytes } else { 0 };
        let marks = self.memory.mark_bytes() - evicted + own;
        if let Err(Beyond {
            key,
            max_bytes,
            whose,
        }) = self.memory.reserve(live, marks, own)
        {
            let advice = match mark {
                true => {
                    "send it again without `mark`, or roll back to an earlier mark (later \
                         marks are dropped)"
                }
                false => {
                    "roll back to an earlier mark (later marks are dropped), open the \
                          session on a coarser grid, or retry when other sessions have closed"
                }
            };
            let kept = match mark {
                true => format!(" (this step's mark {bytes} bytes of them)"),
                false => String::new(),
            };
            return Err(ServiceError::Exhausted(format!(
                "this step would leave the session holding {live} bytes of working state and \
                 {marks} bytes of marks{kept}, beyond {whose} limit, this server's {key} \
                 ({max_bytes} bytes); the step was not applied: {advice}{}",
                self.list()
            )));
        }
        if mark {
            if evicted > 0 {
                self.marks.pop_first();
            }
            self.marks.insert(index, (state(), bytes));
        }
        self.next_step = index + 1;
        Ok(())
    }

    /// Goes back to marked step `to`: its state; later marks are dropped,
    /// the mark itself stays.
    pub fn rollback(&mut self, to: u64) -> Result<(&T, pb::SessionRolledBack), ServiceError> {
        if !self.marks.contains_key(&to) {
            return Err(ServiceError::precondition(
                "rollback.to_step_index",
                format!(
                    "step {to} is not marked in this session{}; mark a step with `mark = true`",
                    self.list()
                ),
            ));
        }
        let later: usize = self.marks.split_off(&(to + 1)).values().map(|m| m.1).sum();
        self.memory.drop_marks(later);
        self.next_step = to + 1;
        Ok((
            &self.marks[&to].0,
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

/// The limits of a session, from the server's settings.
#[derive(Debug, Clone)]
pub struct SessionLimits {
    /// Largest step response \[bytes\] (`max_message_bytes`).
    pub max_response_bytes: usize,
    /// The sessions' memory (live state and marks).
    pub memory: SessionBudget,
    /// Largest patch grid of a wheel/rail session, nx * ny elements
    /// (`max_grid_elements`).
    pub max_grid_elements: usize,
}

/// One open session.
pub struct Session {
    engine: PatchEngine,
    kind: SessionKind,
    fields: bool,
    default_load: NormalLoad,
    marks: Marks<EngineState>,
    /// The engine's state before the step being solved (buffers reused
    /// from step to step).
    undo: EngineState,
    max_response_bytes: usize,
}

impl Session {
    /// Opens a session on a validated case (field paths relative to `open`).
    pub fn open(
        engine: PatchEngine,
        fields: bool,
        limits: SessionLimits,
    ) -> Result<Self, ServiceError> {
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
        // The copy a refused step is undone from, at its size from the start.
        let mut undo = EngineState::default();
        engine.save(&mut undo);
        let live = engine.heap_bytes() + undo.heap_bytes();
        Ok(Self {
            default_load: case.load,
            engine,
            kind,
            fields,
            marks: Marks::open(limits.memory, live)?,
            undo,
            max_response_bytes: limits.max_response_bytes,
        })
    }

    /// The memory the session holds between steps, its marks aside
    /// \[bytes\]: the engine's and the undo copy's.
    pub fn live_bytes(&self) -> usize {
        self.engine.heap_bytes() + self.undo.heap_bytes()
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

    /// Bytes held by the session's marks.
    pub fn mark_bytes(&self) -> usize {
        self.marks.bytes()
    }

    /// Checks a step's order and inputs without solving; field paths are
    /// relative to the request (`step.`).
    pub fn check_step(&self, s: &pb::SessionStep) -> Result<StepInput, ServiceError> {
        self.marks.check_order(s.step_index)?;
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
                let (c, force) = match &s.creepages {
                    Some(w) => self.step_creepages(w)?,
                    None => Default::default(),
                };
                c.check_input()
                    .map_err(|e| ServiceError::from(e).rekey("rolling.", "step.creepages."))?;
                Motion::Rolling(c, force)
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
                if sh.friction_start != 0 {
                    return Err(ServiceError::invalid(
                        "step.shift.friction_start",
                        "a session's steps take the falling law's start of its case \
                         (friction.start): leave it unspecified",
                    ));
                }
                let section = convert::step_section("step.shift", sh)?;
                let case = self.engine.case();
                let shift = transient_step(
                    "step.shift",
                    &section,
                    load,
                    case.rolling_step_m,
                    case.geometry.is_line(),
                    case.model,
                    case.gap_m.is_some(),
                )?;
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

    /// The creepages of a steady-rolling step and the forces it prescribes
    /// instead (exact model; a direction's creepage is then where the
    /// force's iteration starts: the last step's, see
    /// [`PatchEngine::set_rolling`]).
    fn step_creepages(
        &self,
        w: &pb::Creepages,
    ) -> Result<(Creepages, PrescribedForce), ServiceError> {
        if w.force_x_n_per_m.is_some() {
            return Err(ServiceError::invalid(
                "step.creepages.force_x_n_per_m",
                "a force per metre is for line contacts, which sessions do not solve: give \
                 `force_x_n`",
            ));
        }
        let (c, force) = convert::rolling(w)
            .split()
            .map_err(|e| ServiceError::from(e).rekey("rolling.", "step.creepages."))?;
        let model = self.engine.case().model;
        if force.any() && model != Model::Exact {
            let key = if force.force_x_n.is_some() {
                "step.creepages.force_x_n"
            } else {
                "step.creepages.force_y_n"
            };
            return Err(ServiceError::invalid(
                key,
                format!(
                    "a prescribed force is solved with the exact model only, not {}: give the \
                     creepage",
                    model.name()
                ),
            ));
        }
        Ok((c, force))
    }

    /// Solves a checked step (CPU-bound: run it on the solve pool). A
    /// refused step leaves the session as it was, bit for bit.
    pub fn step(&mut self, input: StepInput) -> Result<pb::SessionStepResult, ServiceError> {
        self.engine.save(&mut self.undo);
        let r = self.try_step(input);
        if r.is_err() {
            let restored = self.engine.restore(&self.undo);
            self.engine.release_scratch();
            self.marks.settle(self.live_bytes());
            restored?;
        }
        r
    }

    /// [`Session::step`] without the undo: the caller restores the engine
    /// when this fails.
    fn try_step(&mut self, input: StepInput) -> Result<pb::SessionStepResult, ServiceError> {
        self.engine.set_load(input.load);
        let result = match input.motion {
            Motion::Static => self.engine.solve(self.fields),
            Motion::Rolling(c, force) => {
                self.engine.set_rolling(c, force);
                self.engine.solve(self.fields)
            }
            Motion::Shift(shift) => self.engine.solve_next_step(&shift, self.fields),
        }
        .map_err(|e| {
            e.rekey("load", "step")
                .rekey("rolling", "step.creepages")
                .rekey("transient", "step.shift")
                .rekey("grid", "open.case.grid")
        })?;
        let out = pb::SessionStepResult {
            step_index: input.index,
            time_s: input.time_s,
            result: result.result,
            fields: result.fields,
            marked: input.mark,
            force_control: result.force_control,
        };
        check_response_size(&out, self.max_response_bytes)?;
        let live = self.live_bytes();
        let engine = &self.engine;
        self.marks
            .done(input.index, input.mark, live, engine.state_bytes(), || {
                let mut state = EngineState::default();
                engine.save(&mut state);
                state
            })?;
        Ok(out)
    }

    /// Goes back to the state after marked step `to`; later marks are
    /// dropped, the mark itself stays.
    pub fn rollback(&mut self, to: u64) -> Result<pb::SessionRolledBack, ServiceError> {
        let (state, out) = self.marks.rollback(to)?;
        self.engine.restore(state)?;
        Ok(out)
    }
}
