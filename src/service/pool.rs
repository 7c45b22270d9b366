//! Where the solves run: off the async runtime, on tokio's blocking
//! threads, at most `workers` at a time, behind a bounded queue.
//!
//! Why this shape: a solve is CPU-bound for microseconds (Hertz) to
//! seconds (large exact grids). Running it on the reactor would stall
//! every other connection, so each goes to `spawn_blocking`; a semaphore
//! of `workers` permits (default: the cores) keeps them from oversubscribing
//! the CPU. Admission is a second semaphore of `queue_capacity` slots
//! (running plus waiting): a request that finds it full is refused at
//! once with RESOURCE_EXHAUSTED instead of queueing without bound. A batch
//! or a creep curve takes one slot and runs its items on the worker
//! permits. No lock is held across a solve.
//!
//! An exact or conformal wheelset (unary or a session step) solves its two
//! wheels at once on two threads when a second heavy worker is free as it
//! starts, and holds that worker's permit too ([`Admission::run_on_wide`]):
//! an idle server answers such a step in about the time of its slower
//! wheel, a busy one runs it on one thread like every other solve, and the
//! solve threads never outnumber `workers`. A session step goes wide only
//! after a step of at least
//! [`TWO_THREADS_MIN_WORK_S`](crate::service::wheelrail_session::TWO_THREADS_MIN_WORK_S)
//! of work: shorter steps gain nothing from the second thread and lose to
//! it when another process takes a core. The answer is the same bits
//! either way.
//!
//! Two lanes: the fast models (Hertz, FASTSIM, Hertz+FASTSIM wheelsets:
//! microseconds to a few milliseconds) have `workers` permits of their
//! own, so they never queue behind exact solves that hold every heavy
//! permit for tens of milliseconds (the load test measured a 3.7 ms
//! Hertz+FASTSIM wheelset step at 280 ms median behind two exact
//! wheelsets with one shared lane). The operating system shares the cores
//! between the lanes; a fast solve costs the exact ones little.
//!
//! A third lane for the smallest solves (Hertz, FASTSIM on small grids,
//! Hertz+FASTSIM wheelset steps on contact tables: tens of
//! microseconds): they run on the runtime thread that received
//! them, under a fast-lane permit. The hop to a blocking thread and back
//! cost more than such a solve: on the development machine it took the
//! loopback FASTSIM 40x40 session step from 71-79 µs to 90-113 µs at the
//! median and from 117-119 µs to 150-184 µs at p99 (load test, servers
//! alternated, 3000 steps each). A few tens of microseconds on the runtime
//! thread delay other connections less than that hop delays these.
//!
//! Deadlines: a request that waited past its deadline is not started; one
//! that is running when the deadline passes is answered with
//! DEADLINE_EXCEEDED at once. Its thread is told to stop
//! ([`crate::core::cancel`]: the solve runs under a token that is
//! cancelled when the request's future ends, by the deadline or because
//! the client went away) and gives its permit back at the solver's next
//! check, within one iteration (a Newton or CG step, an alternation, a
//! load iteration), instead of finishing a solve that nobody waits for.
//!
//! Fair to clients ([`crate::service::quota`]): each admitted request and
//! session belongs to a client (its token's name, or its address), and a
//! client holds at most `client_max_admitted` of the queue's slots (beyond
//! them RESOURCE_EXHAUSTED naming that setting, while other clients are
//! admitted). A lane's workers go to the waiting solves client by client
//! in turn ([`FairLane`]), first come first served within a client: a
//! client that has sixteen solves waiting delays another client's one
//! solve by the solves running and at most one more per worker, not by
//! its sixteen; session
//! steps queue the same way under their session's client.

use std::collections::{HashMap, VecDeque};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use tokio::sync::{oneshot, OwnedSemaphorePermit, Semaphore};
use tokio::time::Instant;

use crate::core::cancel::CancelToken;
use crate::service::metrics::Metrics;
use crate::service::quota::{client_share, ClientId, Quota, QuotaGuard, Resource};
use crate::service::status::ServiceError;

/// The solve threads of one lane, handed to the waiting solves client by
/// client in turn (round robin over the clients that have solves waiting;
/// first come, first served within a client). Cheap to share (`Arc`); a
/// short lock per acquire and release.
#[derive(Debug)]
pub struct FairLane {
    state: Mutex<LaneState>,
}

#[derive(Debug)]
struct LaneState {
    free: usize,
    /// Each waiting client's waiters, oldest first.
    waiting: HashMap<ClientId, VecDeque<oneshot::Sender<()>>>,
    /// The clients with waiters, in the order they are served.
    turn: VecDeque<ClientId>,
}

/// A worker of a [`FairLane`], given back (to the next client in turn)
/// when dropped.
#[derive(Debug)]
pub struct LanePermit {
    lane: Arc<FairLane>,
}

impl Drop for LanePermit {
    fn drop(&mut self) {
        self.lane.release();
    }
}

/// A waiter's place: if it is dropped after the lane granted it a worker
/// but before it took it, the worker goes to the next in turn.
struct Waiting {
    lane: Arc<FairLane>,
    granted: Option<oneshot::Receiver<()>>,
}

impl Drop for Waiting {
    fn drop(&mut self) {
        if let Some(mut rx) = self.granted.take() {
            if rx.try_recv().is_ok() {
                self.lane.release();
            }
        }
    }
}

impl FairLane {
    /// A lane of `workers` threads.
    pub fn new(workers: usize) -> Arc<Self> {
        Arc::new(Self {
            state: Mutex::new(LaneState {
                free: workers,
                waiting: HashMap::new(),
                turn: VecDeque::new(),
            }),
        })
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, LaneState> {
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// A worker for `client`: at once when one is free and nobody waits,
    /// else when its turn comes.
    pub async fn acquire(self: &Arc<Self>, client: &ClientId) -> LanePermit {
        let rx = {
            let mut s = self.lock();
            if s.free > 0 && s.turn.is_empty() {
                s.free -= 1;
                return LanePermit { lane: self.clone() };
            }
            let (tx, rx) = oneshot::channel();
            let queue = s.waiting.entry(client.clone()).or_default();
            if queue.is_empty() {
                s.turn.push_back(client.clone());
                s.waiting.get_mut(client).unwrap().push_back(tx);
            } else {
                queue.push_back(tx);
            }
            rx
        };
        let mut waiting = Waiting {
            lane: self.clone(),
            granted: Some(rx),
        };
        let granted = waiting.granted.as_mut().unwrap().await;
        waiting.granted = None;
        // The sender lives in the lane until it grants: it never drops
        // unsent while this waits.
        debug_assert!(granted.is_ok());
        LanePermit { lane: self.clone() }
    }

    /// A worker at once if one is free and nobody waits (who would then
    /// go first).
    pub fn try_acquire(self: &Arc<Self>) -> Option<LanePermit> {
        let mut s = self.lock();
        (s.free > 0 && s.turn.is_empty()).then(|| {
            s.free -= 1;
            LanePermit { lane: self.clone() }
        })
    }

    /// Workers free now.
    pub fn available_permits(&self) -> usize {
        self.lock().free
    }

    /// A worker came back: to the first waiter of the client whose turn it
    /// is (that client then goes to the end of the turn if it has more
    /// waiting), or free.
    fn release(&self) {
        let mut s = self.lock();
        while let Some(client) = s.turn.pop_front() {
            let Some(queue) = s.waiting.get_mut(&client) else {
                continue;
            };
            let next = queue.pop_front();
            if queue.is_empty() {
                s.waiting.remove(&client);
            } else {
                s.turn.push_back(client);
            }
            // A waiter that gave up (its request ended) has dropped its
            // receiver: the worker goes on to the next.
            if let Some(tx) = next {
                if tx.send(()).is_ok() {
                    return;
                }
            }
        }
        s.free += 1;
    }
}

/// The solve pool (cheap to clone: shared lanes and counts).
#[derive(Clone)]
pub struct SolvePool {
    workers: Arc<FairLane>,
    fast_workers: Arc<FairLane>,
    queue: Arc<Semaphore>,
    /// Each client's admitted requests, against `client_max_admitted`.
    admitted: Arc<Quota>,
    capacity: usize,
    /// Solve permits per lane.
    worker_count: usize,
    /// Solves whose request ended while they ran (see [`SolvePool::cancelled`]).
    cancelled: Arc<AtomicU64>,
    /// Longest a solve may run on a worker (see [`SolvePool::with_max_solve_time`]).
    max_solve_time: Option<Duration>,
    /// Solves stopped at [`SolvePool::with_max_solve_time`]'s limit.
    timed_out: Arc<AtomicU64>,
}

/// Which workers a solve runs on (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Lane {
    /// Exact and conformal models, preparations, tables.
    Heavy,
    /// Hertz+FASTSIM wheelsets, and Hertz and FASTSIM patches too large
    /// for [`Lane::Inline`].
    Fast,
    /// Hertz and FASTSIM patches of at most [`INLINE_FASTSIM_ELEMENTS`]
    /// elements, without sensitivities, and wheel/rail session steps on
    /// contact tables
    /// ([`WheelRailSession::is_inline`](crate::service::wheelrail_session::WheelRailSession::is_inline)):
    /// run on the runtime thread, under a fast-lane permit.
    Inline,
}

/// Largest FASTSIM grid (nx * ny) solved on the runtime thread: 64 x 64,
/// about 50 µs on the development machine (40 x 40: 20 µs).
pub const INLINE_FASTSIM_ELEMENTS: usize = 4096;

impl Lane {
    /// The fast lane when `fast`.
    pub fn of(fast: bool) -> Self {
        if fast {
            Lane::Fast
        } else {
            Lane::Heavy
        }
    }
}

/// An admitted request: holds a queue slot, and a unit of its client's
/// share, until dropped (none for the server's own work, see
/// [`SolvePool::internal`], nor for sessions, see [`SolvePool::session`]).
pub struct Admission {
    pool: SolvePool,
    client: ClientId,
    deadline: Option<Instant>,
    _slot: Option<(QuotaGuard, OwnedSemaphorePermit)>,
}

impl SolvePool {
    /// A pool running at most `workers` solves at once, with at most
    /// `queue_capacity` requests admitted (at least `workers`), half of
    /// them (rounded up) per client.
    pub fn new(workers: usize, queue_capacity: usize) -> Self {
        Self::with_client_share(workers, queue_capacity, 0, Arc::new(Metrics::default()))
    }

    /// [`SolvePool::new`] with at most `client_max_admitted` requests of
    /// one client admitted at once (0: half the capacity, rounded up);
    /// refusals counted into `metrics`.
    pub fn with_client_share(
        workers: usize,
        queue_capacity: usize,
        client_max_admitted: usize,
        metrics: Arc<Metrics>,
    ) -> Self {
        let workers = workers.max(1);
        let capacity = queue_capacity.max(workers);
        Self {
            workers: FairLane::new(workers),
            fast_workers: FairLane::new(workers),
            queue: Arc::new(Semaphore::new(capacity)),
            admitted: Quota::new(
                Resource::Admitted,
                None,
                client_share(client_max_admitted, capacity),
                metrics,
            ),
            capacity,
            worker_count: workers,
            cancelled: Arc::new(AtomicU64::new(0)),
            max_solve_time: None,
            timed_out: Arc::new(AtomicU64::new(0)),
        }
    }

    /// The same pool with a server-side limit on how long one solve may run
    /// on a worker (not counting the wait for one): a solve still running
    /// then is told to stop ([`crate::core::cancel`]) and answered with
    /// RESOURCE_EXHAUSTED. A client's deadline can only shorten it. The
    /// inline lane (solves of microseconds) is not timed.
    pub fn with_max_solve_time(mut self, limit: Duration) -> Self {
        self.max_solve_time = Some(limit);
        self
    }

    /// Runs the items of one request (a batch) concurrently, `solve(i,
    /// item)`, with at most one item per worker in flight at a time; the
    /// outcomes in item order. Fair to other requests: the workers'
    /// semaphore is first come, first served, and a batch keeps at most
    /// `workers` items waiting there, so a request that arrives while a
    /// batch of 1,024 items runs waits for at most one item per worker,
    /// not for the whole batch.
    pub async fn run_items<T, R, F, Fut>(
        &self,
        items: Vec<T>,
        solve: F,
    ) -> Result<Vec<R>, ServiceError>
    where
        T: Send + 'static,
        R: Send + 'static,
        F: Fn(usize, T) -> Fut,
        Fut: std::future::Future<Output = R> + Send + 'static,
    {
        let in_flight = Arc::new(Semaphore::new(self.worker_count));
        let mut tasks = tokio::task::JoinSet::new();
        let n = items.len();
        for (i, item) in items.into_iter().enumerate() {
            let permit = in_flight
                .clone()
                .acquire_owned()
                .await
                .map_err(|_| ServiceError::Unavailable("the solve pool is closed".into()))?;
            let item = solve(i, item);
            tasks.spawn(async move {
                let out = item.await;
                drop(permit);
                (i, out)
            });
        }
        let mut slots: Vec<Option<R>> = (0..n).map(|_| None).collect();
        while let Some(done) = tasks.join_next().await {
            let (i, r) = done.map_err(|e| ServiceError::Internal(format!("batch item: {e}")))?;
            slots[i] = Some(r);
        }
        Ok(slots.into_iter().flatten().collect())
    }

    /// Solves stopped at the server's time limit so far.
    pub fn timed_out(&self) -> u64 {
        self.timed_out.load(Ordering::Relaxed)
    }

    /// Admits a request of the server's own with an optional deadline, or
    /// refuses it when the queue is full.
    pub fn admit(&self, deadline: Option<Instant>) -> Result<Admission, ServiceError> {
        self.admit_for(&ClientId::Server, deadline)
    }

    /// Admits a request of `client` with an optional deadline, or refuses
    /// it (RESOURCE_EXHAUSTED) when the client holds its share of the
    /// queue (`client_max_admitted`) or the queue is full.
    pub fn admit_for(
        &self,
        client: &ClientId,
        deadline: Option<Instant>,
    ) -> Result<Admission, ServiceError> {
        let share = self.admitted.take(client)?;
        let slot = self.queue.clone().try_acquire_owned().map_err(|_| {
            self.admitted.refused_by(Resource::Admitted.total_setting());
            ServiceError::Exhausted(format!(
                "the solve queue is full ({} requests admitted, queue_capacity); retry with \
                 backoff",
                self.capacity
            ))
        })?;
        Ok(Admission {
            pool: self.clone(),
            client: client.clone(),
            deadline,
            _slot: Some((share, slot)),
        })
    }

    /// An admission for the server's own background work (the built-in
    /// pair's contact table at start): it runs on the workers like a
    /// request, but takes no queue slot, so clients never find the queue
    /// full because of it.
    pub fn internal(&self) -> Admission {
        self.unqueued()
    }

    /// An admission for a session's work: its opening (a pair's
    /// preparation, a patch's kernels) and each of its steps. It takes no
    /// queue slot: the sessions are bounded by `max_sessions` and each has
    /// at most one solve in flight, so a server that admitted a session
    /// always has room for its steps (they wait for a worker like every
    /// solve). The queue bounds the unary requests and batches alone.
    /// Its solves wait for a worker in `client`'s turn.
    pub fn session(&self, client: &ClientId) -> Admission {
        Admission {
            client: client.clone(),
            ..self.unqueued()
        }
    }

    /// An admission without a queue slot or deadline, of the server.
    fn unqueued(&self) -> Admission {
        Admission {
            pool: self.clone(),
            client: ClientId::Server,
            deadline: None,
            _slot: None,
        }
    }

    /// Requests of `client` admitted now.
    pub fn admitted_by(&self, client: &ClientId) -> usize {
        self.admitted.held_by(client)
    }

    /// Requests admitted now (running or waiting).
    pub fn admitted(&self) -> usize {
        self.capacity - self.queue.available_permits()
    }

    /// Solves told to stop so far: their request ended (deadline passed,
    /// client gone, shutdown) while they ran on a solve thread.
    pub fn cancelled(&self) -> u64 {
        self.cancelled.load(Ordering::Relaxed)
    }
}

impl Admission {
    /// Runs `f` on a solve thread when a worker is free; errors when the
    /// deadline passes first, or when `f` panicked (a server fault).
    pub async fn run<T, F>(&self, f: F) -> Result<T, ServiceError>
    where
        T: Send + 'static,
        F: FnOnce() -> T + Send + 'static,
    {
        self.run_on(Lane::Heavy, f).await
    }

    /// [`Admission::run`] on the given lane.
    pub async fn run_on<T, F>(&self, lane: Lane, f: F) -> Result<T, ServiceError>
    where
        T: Send + 'static,
        F: FnOnce() -> T + Send + 'static,
    {
        self.run_spread(lane, false, move |_| f()).await
    }

    /// [`Admission::run_on`] for a solve that can use a second thread (an
    /// exact or conformal wheelset's two wheels) and `wanted` one: `f` is
    /// told whether it may. It may on the heavy lane when a second worker
    /// was free as the solve got its own; the solve then holds both
    /// permits until it ends, so the threads of the solves in flight never
    /// outnumber the workers. Not wanted, on a busy server, on the other
    /// lanes and with one worker such solves run on one thread, as every
    /// other.
    pub async fn run_on_wide<T, F>(&self, lane: Lane, wanted: bool, f: F) -> Result<T, ServiceError>
    where
        T: Send + 'static,
        F: FnOnce(bool) -> T + Send + 'static,
    {
        self.run_spread(lane, wanted, f).await
    }

    async fn run_spread<T, F>(&self, lane: Lane, spread: bool, f: F) -> Result<T, ServiceError>
    where
        T: Send + 'static,
        F: FnOnce(bool) -> T + Send + 'static,
    {
        let workers = match lane {
            Lane::Heavy => self.pool.workers.clone(),
            Lane::Fast | Lane::Inline => self.pool.fast_workers.clone(),
        };
        let deadline = self.deadline;
        let client = self.client.clone();
        // Cancelled when this future ends, whichever way: the solve thread
        // stops at its next check once the deadline's timeout or a
        // client that went away has dropped the future.
        let token = CancelToken::new();
        let stop = CancelOnDrop(token.clone());
        let cancelled = self.pool.cancelled.clone();
        let (limit, timed_out) = (self.pool.max_solve_time, self.pool.timed_out.clone());
        let work = async move {
            let _stop = stop;
            let permit = workers.acquire(&client).await;
            if deadline.is_some_and(|d| Instant::now() >= d) {
                return Err(expired());
            }
            if lane == Lane::Inline {
                let _permit = permit;
                return std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                    token.scope(|| f(false))
                }))
                .map_err(|_| ServiceError::Internal("a solve failed: it panicked".into()));
            }
            // The fast lanes' solves are too short to gain from a thread.
            let second = match spread && lane == Lane::Heavy {
                true => workers.try_acquire(),
                false => None,
            };
            let wide = second.is_some();
            let solve = tokio::task::spawn_blocking(move || {
                let _permits = (permit, second);
                let out = token.scope(|| f(wide));
                if token.is_cancelled() {
                    cancelled.fetch_add(1, Ordering::Relaxed);
                }
                out
            });
            let joined = match limit {
                // Returning drops `_stop`, which tells the thread to stop.
                Some(limit) => tokio::time::timeout(limit, solve).await.map_err(|_| {
                    timed_out.fetch_add(1, Ordering::Relaxed);
                    ServiceError::Exhausted(format!(
                        "the solve ran longer than this server's limit of {} s per solve \
                         (max_solve_time_s) and was stopped: use a coarser grid, fewer \
                         steps or looser solver settings, or split the work",
                        limit.as_secs_f64()
                    ))
                })?,
                None => solve.await,
            };
            joined.map_err(|e| ServiceError::Internal(format!("a solve failed: {e}")))
        };
        match deadline {
            Some(d) => tokio::time::timeout_at(d, work)
                .await
                .map_err(|_| expired())?,
            None => work.await,
        }
    }
}

/// Cancels its token when dropped.
struct CancelOnDrop(CancelToken);

impl Drop for CancelOnDrop {
    fn drop(&mut self) {
        self.0.cancel();
    }
}

fn expired() -> ServiceError {
    ServiceError::Deadline("the deadline passed before the solve finished".into())
}

/// The deadline of a request from its `grpc-timeout` header: a little
/// before the client's own, so that DEADLINE_EXCEEDED reaches it in time
/// (tonic's transport would otherwise answer CANCELLED when the header's
/// time is up).
pub fn deadline_of(metadata: &tonic::metadata::MetadataMap) -> Option<Instant> {
    let v = metadata.get("grpc-timeout")?.to_str().ok()?;
    let (digits, unit) = v.split_at(v.len().checked_sub(1)?);
    let n: u64 = digits.parse().ok()?;
    let timeout = match unit {
        "H" => Duration::from_secs(n.saturating_mul(3600)),
        "M" => Duration::from_secs(n.saturating_mul(60)),
        "S" => Duration::from_secs(n),
        "m" => Duration::from_millis(n),
        "u" => Duration::from_micros(n),
        "n" => Duration::from_nanos(n),
        _ => return None,
    };
    // 10 % of the timeout, 2 ms to 100 ms (at most half of it): covers the
    // time from the transport's timer start to here and a busy runtime.
    let margin = (timeout / 10)
        .clamp(Duration::from_millis(2), Duration::from_millis(100))
        .min(timeout / 2);
    Some(Instant::now() + timeout.saturating_sub(margin))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[tokio::test]
    async fn a_full_queue_refuses_and_frees_its_slots() {
        let pool = SolvePool::new(1, 2);
        let a = pool.admit(None).unwrap();
        let _b = pool.admit(None).unwrap();
        let third = pool.admit(None);
        assert!(matches!(third, Err(ServiceError::Exhausted(_))));
        assert_eq!(a.run(|| 2 + 2).await.unwrap(), 4);
        drop(a);
        assert_eq!(pool.admitted(), 1);
        assert!(pool.admit(None).is_ok());
    }

    #[tokio::test]
    async fn a_lane_serves_the_waiting_clients_in_turn() {
        let lane = FairLane::new(1);
        let (a, b) = (
            ClientId::peer("10.0.0.1".parse().unwrap()),
            ClientId::peer("10.0.0.2".parse().unwrap()),
        );
        let held = lane.acquire(&a).await;
        assert!(lane.try_acquire().is_none());
        // Three of a's wait, then one of b's: each waiter sends its name
        // when it gets the worker, and gives the worker back at once.
        let (tx, mut order) = tokio::sync::mpsc::unbounded_channel();
        let mut tasks = tokio::task::JoinSet::new();
        let waiters = [(&a, "a1"), (&a, "a2"), (&a, "a3"), (&b, "b1")];
        for (client, name) in waiters {
            let (mine, client, tx) = (lane.clone(), client.clone(), tx.clone());
            tasks.spawn(async move {
                let _permit = mine.acquire(&client).await;
                tx.send(name).unwrap();
            });
            // Queued in this order (each task waits before the next starts).
            while lane
                .lock()
                .waiting
                .values()
                .map(VecDeque::len)
                .sum::<usize>()
                < tasks.len()
            {
                tokio::task::yield_now().await;
            }
        }
        // One that gives up while waiting passes its turn on.
        let (lane2, a2) = (lane.clone(), a.clone());
        let gone = tokio::spawn(async move { lane2.acquire(&a2).await });
        while lane.lock().waiting[&a].len() < 4 {
            tokio::task::yield_now().await;
        }
        gone.abort();
        let _ = gone.await;
        drop(held);
        while tasks.join_next().await.is_some() {}
        drop(tx);
        let mut served = Vec::new();
        while let Some(name) = order.recv().await {
            served.push(name);
        }
        // First come, first served would be a1 a2 a3 b1.
        assert_eq!(served, ["a1", "b1", "a2", "a3"]);
        assert_eq!(lane.available_permits(), 1, "the worker is back");
        let state = lane.lock();
        assert!(state.turn.is_empty() && state.waiting.is_empty());
    }

    #[tokio::test]
    async fn a_passed_deadline_is_not_started_and_a_panic_is_internal() {
        let pool = SolvePool::new(1, 4);
        let late = pool.admit(Some(Instant::now())).unwrap();
        let r = late.run(|| 1).await;
        assert!(matches!(r, Err(ServiceError::Deadline(_))), "{r:?}");
        let a = pool.admit(None).unwrap();
        let r: Result<(), _> = a.run(|| panic!("boom")).await;
        assert!(matches!(r, Err(ServiceError::Internal(_))), "{r:?}");
    }

    #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
    async fn a_fast_solve_does_not_wait_behind_a_heavy_one() {
        let pool = SolvePool::new(1, 4);
        let heavy = pool.admit(None).unwrap();
        let (release, blocked) = std::sync::mpsc::channel::<()>();
        let (started, running_now) = tokio::sync::oneshot::channel::<()>();
        // The heavy lane's only worker is taken until the fast solve is done.
        let running = tokio::spawn(async move {
            heavy
                .run(move || {
                    let _ = started.send(());
                    blocked.recv().is_ok()
                })
                .await
        });
        running_now.await.unwrap();
        let fast = pool.admit(None).unwrap();
        let r = tokio::time::timeout(Duration::from_secs(30), fast.run_on(Lane::Fast, || 7))
            .await
            .expect("the fast lane is not blocked by the heavy one");
        assert_eq!(r.unwrap(), 7);
        release.send(()).unwrap();
        assert!(running.await.unwrap().unwrap());
    }

    /// A solve that runs until its thread's token is cancelled (at most
    /// 60 s), and says whether the token stopped it.
    fn until_cancelled() -> bool {
        let t0 = std::time::Instant::now();
        while !crate::core::cancel::requested() && t0.elapsed() < Duration::from_secs(60) {
            std::thread::sleep(Duration::from_millis(1));
        }
        crate::core::cancel::requested()
    }

    #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
    async fn a_solve_nobody_waits_for_is_told_to_stop_and_frees_its_worker() {
        let pool = SolvePool::new(1, 4);
        let (tx, rx) = std::sync::mpsc::channel::<bool>();
        // The deadline passes while it runs.
        let a = pool
            .admit(Some(Instant::now() + Duration::from_millis(50)))
            .unwrap();
        let t = tx.clone();
        let r = a.run(move || t.send(until_cancelled())).await;
        assert!(matches!(r, Err(ServiceError::Deadline(_))), "{r:?}");
        // The client goes away while it runs (its request's future is
        // dropped).
        let b = pool.admit(None).unwrap();
        let (started, running) = tokio::sync::oneshot::channel::<()>();
        let task = tokio::spawn(async move {
            b.run(move || {
                let _ = started.send(());
                tx.send(until_cancelled())
            })
            .await
        });
        running.await.unwrap();
        task.abort();
        assert!(task.await.unwrap_err().is_cancelled());
        // Both threads saw their token cancelled, and the only worker is
        // free again.
        let c = pool.admit(None).unwrap();
        assert_eq!(c.run(|| 5).await.unwrap(), 5);
        assert!(rx.recv().unwrap() && rx.recv().unwrap());
        assert_eq!(pool.cancelled(), 2);
        // A solve that ends normally was never cancelled.
        assert!(!c.run(crate::core::cancel::requested).await.unwrap());
    }

    #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
    async fn a_solve_past_the_server_limit_is_stopped_and_refused() {
        let pool = SolvePool::new(1, 4).with_max_solve_time(Duration::from_millis(50));
        let a = pool.admit(None).unwrap();
        let (tx, rx) = std::sync::mpsc::channel::<bool>();
        let r = a.run(move || tx.send(until_cancelled())).await;
        match r {
            Err(ServiceError::Exhausted(m)) => assert!(m.contains("max_solve_time_s"), "{m}"),
            other => panic!("expected RESOURCE_EXHAUSTED, got {other:?}"),
        }
        // The thread was told to stop, and the only worker is free again.
        assert!(rx.recv().unwrap());
        assert_eq!(a.run(|| 6).await.unwrap(), 6);
        assert_eq!(pool.timed_out(), 1);
        assert_eq!(pool.cancelled(), 1);
    }

    #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
    async fn a_request_waits_for_one_item_of_a_batch_not_for_the_batch() {
        let pool = SolvePool::new(1, 4);
        let done = Arc::new(std::sync::Mutex::new(Vec::<String>::new()));
        let batch = {
            let (pool, done) = (pool.clone(), done.clone());
            tokio::spawn(async move {
                let admission = Arc::new(pool.admit(None).unwrap());
                pool.run_items((0..50).collect(), |i, _: u32| {
                    let (admission, done) = (admission.clone(), done.clone());
                    async move {
                        admission
                            .run(move || {
                                std::thread::sleep(Duration::from_millis(5));
                                done.lock().unwrap().push(format!("item {i}"));
                            })
                            .await
                    }
                })
                .await
            })
        };
        // Let the batch start, then ask for one small solve.
        while done.lock().unwrap().is_empty() {
            tokio::time::sleep(Duration::from_millis(1)).await;
        }
        let small = pool.admit(None).unwrap();
        let d = done.clone();
        small
            .run(move || d.lock().unwrap().push("small".into()))
            .await
            .unwrap();
        let results = batch.await.unwrap().unwrap();
        assert_eq!(results.len(), 50);
        assert!(results.iter().all(|r| r.is_ok()));
        let order = done.lock().unwrap().clone();
        let at = order.iter().position(|s| s == "small").unwrap();
        // One worker: the small solve comes after at most the item that
        // was running and the one already waiting when it arrived (and
        // the items that finished while it was being admitted).
        assert!(at <= 4, "the small solve came {at}th: {order:?}");
        // The items come back in order.
        assert_eq!(order.len(), 51);
    }

    #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
    async fn a_wide_solve_takes_a_second_worker_only_when_one_is_free() {
        let pool = SolvePool::new(2, 4);
        let a = pool.admit(None).unwrap();
        // Whether the solve went wide, and the workers left free as it ran.
        let probe = |wanted: bool| {
            let workers = pool.workers.clone();
            a.run_on_wide(Lane::Heavy, wanted, move |wide| {
                (wide, workers.available_permits())
            })
        };
        // Idle: the second worker is free, and held while the solve runs.
        assert_eq!(probe(true).await.unwrap(), (true, 0));
        assert_eq!(pool.workers.available_permits(), 2, "both permits back");
        // Not wanted: one thread, the second worker left free.
        assert_eq!(probe(false).await.unwrap(), (false, 1));
        // A plain solve on the lane leaves none to spare.
        let (release, wait) = std::sync::mpsc::channel::<()>();
        let (started, running) = tokio::sync::oneshot::channel::<()>();
        let other = pool.admit(None).unwrap();
        let busy = tokio::spawn(async move {
            other
                .run(move || {
                    let _ = started.send(());
                    wait.recv()
                })
                .await
        });
        running.await.unwrap();
        assert!(!a.run_on_wide(Lane::Heavy, true, |wide| wide).await.unwrap());
        release.send(()).unwrap();
        busy.await.unwrap().unwrap().unwrap();
        // Other lanes never spread; nor does a pool of one worker.
        assert!(!a
            .run_on_wide(Lane::Inline, true, |wide| wide)
            .await
            .unwrap());
        let one = SolvePool::new(1, 4).admit(None).unwrap();
        assert!(!one
            .run_on_wide(Lane::Heavy, true, |wide| wide)
            .await
            .unwrap());
    }

    #[tokio::test]
    async fn the_inline_lane_runs_on_the_calling_thread_and_reports_panics() {
        let pool = SolvePool::new(1, 4);
        let a = pool.admit(None).unwrap();
        let here = std::thread::current().id();
        let there = a
            .run_on(Lane::Inline, || std::thread::current().id())
            .await
            .unwrap();
        assert_eq!(here, there);
        let r: Result<(), _> = a.run_on(Lane::Inline, || panic!("boom")).await;
        assert!(matches!(r, Err(ServiceError::Internal(_))), "{r:?}");
        // The permit came back: the lane still runs.
        assert_eq!(a.run_on(Lane::Inline, || 3).await.unwrap(), 3);
        let late = pool.admit(Some(Instant::now())).unwrap();
        let r = late.run_on(Lane::Inline, || 1).await;
        assert!(matches!(r, Err(ServiceError::Deadline(_))), "{r:?}");
    }

    #[test]
    fn grpc_timeout_header_units() {
        let mut m = tonic::metadata::MetadataMap::new();
        assert!(deadline_of(&m).is_none());
        m.insert("grpc-timeout", "2S".parse().unwrap());
        let d = deadline_of(&m).unwrap() - Instant::now();
        // 2 s less the 100 ms margin (10 %, capped).
        assert!(
            d > Duration::from_millis(1800) && d <= Duration::from_millis(1900),
            "{d:?}"
        );
        m.insert("grpc-timeout", "oops".parse().unwrap());
        assert!(deadline_of(&m).is_none());
    }
}
