//! A co-simulation session on a wheelset: the state machine behind
//! `WheelRailSession`, free of any transport.
//!
//! The session holds its prepared pair (kept alive even if the pair is
//! deleted meanwhile), the settings of its opening message, a search
//! scratch and the warm start of the previous step ([`WarmStart`]: roll
//! angle, each wheel's normal force per vertical load, and a single exact
//! patch's pressures and tangential tractions of the last two steps). It shares no
//! mutable state with other sessions, so its outputs depend only on its own
//! sequence of requests. A step is a transaction: it solves from a copy of
//! the warm start, which replaces the session's only when the step is
//! answered, so a refused step (its inputs, the solver, a non-finite
//! result, a response too large to send, memory beyond the limits) leaves
//! the session as it was. A marked step keeps a copy of the warm start
//! after it; a rollback restores it, so repeating the steps after the mark
//! reproduces their outputs bit for bit. The search scratch holds buffers
//! only (with each wheel's last exact patch solver, renewed for its
//! kernels and buffers, none of its state): answers do not depend on it.
//! The scratch, the warm start and the marks count against the memory
//! limits ([`crate::service::memory`]) after every step; a refused step
//! drops the patch solvers (the next step builds them again).

use std::sync::Arc;

use crate::core::cache::KernelCache;
use crate::core::memory::HeapBytes;
use crate::service::pairs::{PairEntry, PreparedPair};
use crate::service::pb;
use crate::service::session::{check_response_size, Marks, SessionLimits};
use crate::service::status::ServiceError;
use crate::service::wheelrail::{self, QuerySettings};
use crate::wheelrail::{
    check_plausibility, solve_wheelset_tabulated_warm, solve_wheelset_warm, ContactTable,
    SearchScratch, WarmStart, WheelRailInput, WheelRailModel, WheelRailPair,
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
    /// The pair's contact table (model hertz_fastsim_table).
    table: Option<Arc<ContactTable>>,
    /// Send per-element fields with every step.
    fields: bool,
    settings: QuerySettings,
    scratch: SearchScratch,
    warm: WarmStart,
    marks: Marks<WarmStart>,
    max_response_bytes: usize,
    /// A rail varying along the track: the pair placed at the last step's
    /// position, held so that the next step there finds it built
    /// ([`PreparedPair::pair_at`]).
    placed: Option<Arc<WheelRailPair>>,
    /// The work of the last step solved (its search, geometry and solves
    /// summed over threads) \[s\]; None before the first.
    last_work_s: Option<f64>,
}

/// The work of a session's last step \[s\] from which its next step may
/// solve the two wheels on two threads ([`WheelRailSession::wants_two_threads`]).
/// Measured through the service on the 2-core machine (benches/README.md,
/// "Two threads for long steps only"): steps of about 1 ms of work (the
/// load test with `force_tolerance_of_wheel_load` 5e-3) gain nothing from
/// the second thread on an idle machine and take 2.5 times as long when
/// another process uses a core; steps of the default 0.2 mm elements
/// (about 10 ms of work) take a fifth less on two.
pub const TWO_THREADS_MIN_WORK_S: f64 = 3e-3;

/// Whether a step after one of `last_work_s` of work (None: the first)
/// should solve the two wheels on two threads.
fn two_threads_after(last_work_s: Option<f64>) -> bool {
    last_work_s.is_none_or(|w| w >= TWO_THREADS_MIN_WORK_S)
}

impl WheelRailSession {
    /// Opens a session on a prepared pair; the opening message's settings
    /// are checked here (field paths relative to `open`).
    pub fn open(
        entry: Arc<PairEntry>,
        prepared: Arc<PreparedPair>,
        table: Option<Arc<ContactTable>>,
        open: &pb::WheelRailSessionOpen,
        limits: SessionLimits,
    ) -> Result<Self, ServiceError> {
        let settings = QuerySettings::new(
            open.model,
            open.sides,
            open.friction.as_ref(),
            open.element_size_m,
            &entry.spec.settings,
        )?
        .with_polach(open.polach.as_ref())?
        .with_modified_fastsim(open.modified_fastsim.as_ref())?
        .with_conformal(open.conformal.as_ref())?
        .with_friction_table(open.friction_table.as_ref())?
        .with_temperature(open.temperature.as_ref())?
        .with_min_elements_across(open.min_elements_across)
        .with_force_tolerance(open.force_tolerance_of_wheel_load)?
        .with_max_grid_elements(limits.max_grid_elements);
        let (scratch, warm) = (SearchScratch::default(), WarmStart::default());
        let live = scratch.heap_bytes() + warm.bytes();
        Ok(Self {
            settings,
            entry,
            prepared,
            table,
            fields: open.include_fields,
            scratch,
            warm,
            marks: Marks::open(limits.memory, live)?,
            max_response_bytes: limits.max_response_bytes,
            placed: None,
            last_work_s: None,
        })
    }

    /// The memory the session holds between steps, its marks aside
    /// \[bytes\]: the search scratch (with each wheel's last exact patch
    /// solver), the warm start and, on a rail varying along the track, the
    /// pair placed at the last step's position.
    pub fn live_bytes(&self) -> usize {
        self.scratch.heap_bytes() + self.warm.bytes() + self.placed_bytes()
    }

    /// The memory of the pair placed for a rail varying along the track
    /// that the session holds \[bytes\] (shared by content with other
    /// holders, counted whole here).
    fn placed_bytes(&self) -> usize {
        self.placed.as_ref().map_or(0, |p| p.heap_bytes())
    }

    /// The pair's id.
    pub fn pair_id(&self) -> &str {
        &self.entry.spec.id
    }

    /// The model that runs.
    pub fn model(&self) -> WheelRailModel {
        self.settings.model()
    }

    /// The wire model of the session (as opened).
    pub fn wire_model(&self) -> pb::WheelRailModel {
        match &self.table {
            Some(_) => pb::WheelRailModel::HertzFastsimTable,
            None => wheelrail::wire_model(self.model()),
        }
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
    pub fn check_step(&self, s: &pb::WheelRailSessionStep) -> Result<WheelRailStep, ServiceError> {
        self.marks.check_order(s.step_index)?;
        if !s.time_s.is_finite() {
            return Err(ServiceError::invalid(
                "step.time_s",
                format!("must be finite, got {}", s.time_s),
            ));
        }
        let mut input = self
            .settings
            .input(s.position, s.velocity, s.load)
            .map_err(|e| e.within("step"))?;
        input.rail_slices = self.prepared.rail_slices();
        Ok(WheelRailStep {
            index: s.step_index,
            time_s: s.time_s,
            input,
            mark: s.mark,
        })
    }

    /// Whether `step` is as cheap as the patches that run on the runtime
    /// thread ([`Lane::Inline`](crate::service::pool::Lane::Inline)): a
    /// Hertz+FASTSIM step on contact tables (tens of microseconds: a
    /// look-up, a few point evaluations and about four FASTSIM solves of
    /// 40 x 40) at a position inside the table, without a prescribed total
    /// longitudinal force (which solves the wheels several times) and
    /// without per-element fields.
    pub fn is_inline(&self, step: &WheelRailStep) -> bool {
        let Some(table) = &self.table else {
            return false;
        };
        let p = &step.input.position;
        let roll = p.roll_rad.or(self.warm.roll_rad).unwrap_or(0.0);
        step.input.settings.model == WheelRailModel::HertzFastsim
            && step.input.total_longitudinal_force_n.is_none()
            && !self.fields
            && table.covers(p.lateral_m, roll)
    }

    /// Whether the next step should solve the two wheels on two threads:
    /// the first step, and after a step of at least
    /// [`TWO_THREADS_MIN_WORK_S`] of work.
    pub fn wants_two_threads(&self) -> bool {
        two_threads_after(self.last_work_s)
    }

    /// Solves a checked step (CPU-bound: run it on the solve pool), the
    /// two wheels at once on two threads when `two_threads` (the same
    /// bits either way, [`SearchScratch::parallel_wheels`]). A refused
    /// step changes nothing but the buffers of the search scratch.
    pub fn step(
        &mut self,
        step: WheelRailStep,
        two_threads: bool,
    ) -> Result<pb::WheelRailSessionStepResult, ServiceError> {
        self.scratch.parallel_wheels = two_threads;
        let r = self.try_step(step);
        if r.is_err() {
            self.scratch.release_solvers();
            self.marks.settle(self.live_bytes());
        }
        r
    }

    /// [`WheelRailSession::step`] without giving back the scratch's
    /// buffers when it fails.
    fn try_step(
        &mut self,
        step: WheelRailStep,
    ) -> Result<pb::WheelRailSessionStepResult, ServiceError> {
        let mut warm = self.warm.clone();
        let cache = KernelCache::global();
        let placed = self
            .prepared
            .pair_at(step.input.position.track_s_m)
            .map_err(|e| ServiceError::from(e).within("step"))?;
        if placed.is_some() {
            self.placed = placed;
        }
        let pair = self.placed.as_deref().unwrap_or(&self.prepared.pair);
        let solution = match &self.table {
            Some(t) => {
                solve_wheelset_tabulated_warm(t, &step.input, cache, &mut self.scratch, &mut warm)
            }
            None => solve_wheelset_warm(pair, &step.input, cache, &mut self.scratch, &mut warm),
        }
        .map_err(|e| {
            wheelrail::rollers_rekeyed(ServiceError::from(e))
                .within("step")
                .rekey("step.grid.element_size_m", "open.element_size_m")
        })?;
        self.last_work_s = Some(solution.timing.work_s());
        let warnings = wheelrail::warnings(&check_plausibility(&step.input, &solution), "step");
        let mut result = wheelrail::result(
            self.pair_id(),
            self.model(),
            &solution,
            warnings,
            self.fields,
        )
        .map_err(|e| match e {
            ServiceError::Internal(_) => ServiceError::invalid(
                "step",
                "the solve gives non-finite figures for this position, velocity and load: \
                     they are too far outside a wheelset on its track for the arithmetic",
            ),
            e => e.within("step"),
        })?;
        result.model = self.wire_model() as i32;
        let out = pb::WheelRailSessionStepResult {
            step_index: step.index,
            time_s: step.time_s,
            result: Some(result),
            marked: step.mark,
        };
        check_response_size(&out, self.max_response_bytes)?;
        let live = self.scratch.heap_bytes() + warm.bytes() + self.placed_bytes();
        self.marks
            .done(step.index, step.mark, live, warm.bytes(), || warm.clone())?;
        self.warm = warm;
        Ok(out)
    }

    /// Goes back to the state after marked step `to`.
    pub fn rollback(&mut self, to: u64) -> Result<pb::SessionRolledBack, ServiceError> {
        let (warm, out) = self.marks.rollback(to)?;
        self.warm = warm.clone();
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_threads_for_the_first_step_and_after_long_ones_only() {
        assert!(two_threads_after(None));
        assert!(two_threads_after(Some(TWO_THREADS_MIN_WORK_S)));
        assert!(two_threads_after(Some(8e-3)));
        assert!(!two_threads_after(Some(1.2e-3)));
    }
}
