//! A co-simulation session on a wheelset: the state machine behind
//! `WheelRailSession`, free of any transport.
//!
//! The session holds its prepared pair (kept alive even if the pair is
//! deleted meanwhile), the settings of its opening message, a search
//! scratch and the warm start of the previous step ([`WarmStart`]: roll
//! angle and each wheel's normal force per vertical load). It shares no
//! mutable state with other sessions, so its outputs depend only on its own
//! sequence of requests. A marked step keeps a copy of the warm start after
//! it; a rollback restores it, so repeating the steps after the mark
//! reproduces their outputs bit for bit.

use std::sync::Arc;

use crate::core::cache::KernelCache;
use crate::service::pairs::{PairEntry, PreparedPair};
use crate::service::pb;
use crate::service::session::Marks;
use crate::service::status::ServiceError;
use crate::service::wheelrail;
use crate::wheelrail::{
    solve_wheelset_warm, SearchScratch, WarmStart, WheelRailInput, WheelRailModel,
};

/// A validated step, ready to solve.
#[derive(Debug, Clone)]
pub struct WheelRailStep {
    index: u64,
    time_s: f64,
    input: WheelRailInput,
    mark: bool,
}

/// One open wheel/rail session.
pub struct WheelRailSession {
    entry: Arc<PairEntry>,
    prepared: Arc<PreparedPair>,
    open: pb::WheelRailSessionOpen,
    model: WheelRailModel,
    scratch: SearchScratch,
    warm: WarmStart,
    marks: Marks<WarmStart>,
}

impl WheelRailSession {
    /// Opens a session on a prepared pair; the opening message's settings
    /// are checked here (field paths relative to `open`).
    pub fn open(
        entry: Arc<PairEntry>,
        prepared: Arc<PreparedPair>,
        open: pb::WheelRailSessionOpen,
    ) -> Result<Self, ServiceError> {
        // Checks model, sides, friction and element size once, with a
        // placeholder motion.
        let probe = query(&open, &placeholder_step());
        let input = wheelrail::input(&probe, &entry.spec.settings)?;
        Ok(Self {
            model: input.settings.model,
            entry,
            prepared,
            open,
            scratch: SearchScratch::default(),
            warm: WarmStart::default(),
            marks: Marks::new(),
        })
    }

    /// The pair's id.
    pub fn pair_id(&self) -> &str {
        &self.entry.spec.id
    }

    /// The model that runs.
    pub fn model(&self) -> WheelRailModel {
        self.model
    }

    /// The index the next step must have.
    pub fn next_step(&self) -> u64 {
        self.marks.next_step()
    }

    /// Checks a step's order and inputs without solving; field paths are
    /// relative to the request (`step.`).
    pub fn check_step(&self, s: &pb::WheelRailSessionStep) -> Result<WheelRailStep, ServiceError> {
        self.marks.check_order(s.step_index)?;
        if !s.time_s.is_finite() {
            return Err(ServiceError::invalid(
                "step.time_s",
                format!("must be finite, got {}", s.time_s),
            ));
        }
        let input = wheelrail::input(&query(&self.open, s), &self.entry.spec.settings)
            .map_err(|e| e.within("step"))?;
        Ok(WheelRailStep {
            index: s.step_index,
            time_s: s.time_s,
            input,
            mark: s.mark,
        })
    }

    /// Solves a checked step (CPU-bound: run it on the solve pool). A
    /// failed step changes nothing.
    pub fn step(
        &mut self,
        step: WheelRailStep,
    ) -> Result<pb::WheelRailSessionStepResult, ServiceError> {
        let mut warm = self.warm;
        let solution = solve_wheelset_warm(
            &self.prepared.pair,
            &step.input,
            KernelCache::global(),
            &mut self.scratch,
            &mut warm,
        )
        .map_err(|e| {
            ServiceError::from(e)
                .within("step")
                .rekey("step.grid.element_size_m", "open.element_size_m")
        })?;
        let result = wheelrail::result(
            self.pair_id(),
            self.model,
            &solution,
            self.open.include_fields,
        )
        .map_err(|e| e.within("step"))?;
        self.warm = warm;
        self.marks.done(step.index, step.mark, || warm);
        Ok(pb::WheelRailSessionStepResult {
            step_index: step.index,
            time_s: step.time_s,
            result: Some(result),
            marked: step.mark,
        })
    }

    /// Goes back to the state after marked step `to`.
    pub fn rollback(&mut self, to: u64) -> Result<pb::SessionRolledBack, ServiceError> {
        let (warm, out) = self.marks.rollback(to)?;
        self.warm = warm;
        Ok(out)
    }
}

/// A step with the least motion the checks accept, to check an opening
/// message's own settings.
fn placeholder_step() -> pb::WheelRailSessionStep {
    pb::WheelRailSessionStep {
        velocity: Some(pb::WheelsetVelocity {
            forward_m_per_s: 1.0,
            ..Default::default()
        }),
        load: Some(pb::WheelLoad {
            load: Some(pb::wheel_load::Load::ApproachM(1e-5)),
        }),
        ..Default::default()
    }
}

/// The one-shot query of a step in a session opened with `open`.
fn query(
    open: &pb::WheelRailSessionOpen,
    s: &pb::WheelRailSessionStep,
) -> pb::SolveWheelRailRequest {
    pb::SolveWheelRailRequest {
        pair_id: open.pair_id.clone(),
        model: open.model,
        sides: open.sides,
        position: s.position,
        velocity: s.velocity,
        load: s.load,
        friction: open.friction,
        element_size_m: open.element_size_m,
        include_fields: open.include_fields,
    }
}
