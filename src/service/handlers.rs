//! The `railcontact.v1.ContactService` handlers. Each is short: validate
//! the request (on the reactor: microseconds), admit it to the solve pool,
//! run the engine there, map the result. Field paths in errors are those
//! of the request (`case.`, `items[3].case.`, `open.case.`, `step.`).

use std::pin::Pin;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant as StdInstant};

use tokio::sync::mpsc;
use tokio_stream::wrappers::{ReceiverStream, UnboundedReceiverStream};
use tokio_stream::Stream;
use tonic::{Request, Response, Status, Streaming};
use tracing::Instrument;

use crate::core::cache::KernelCache;
use crate::core::problem::{Creepages, Kinematics};
use crate::problem::case::{Case, Model};
use crate::service::connections::ConnInfo;
use crate::service::contact_library::LibraryElement;
use crate::service::convert::{self, CaseLimits};
use crate::service::engine::{check_sensitivities, PatchEngine};
use crate::service::escaped;
use crate::service::memory::{ReturnMemoryOnDrop, SessionBudget};
use crate::service::metrics::Metrics;
use crate::service::pairs::{self, PairRegistry, PairSpec, Progress};
use crate::service::pb;
use crate::service::pool::{deadline_of, Admission, Lane, SolvePool, INLINE_FASTSIM_ELEMENTS};
use crate::service::quota::{client_share, ClientId, Quota, QuotaGuard, Resource};
use crate::service::session::{Session, SessionLimits};
use crate::service::status::{self, ServiceError};
use crate::service::streams::{outbound, Unsent};
use crate::service::wheelrail;
use crate::service::wheelrail_session::WheelRailSession;
use crate::wheelrail::{
    check_plausibility, solve_wheelset, solve_wheelset_tabulated, SearchScratch, WheelRailModel,
};

/// Limits of the requests, from the server settings.
#[derive(Debug, Clone, Copy)]
pub struct RequestLimits {
    /// Grid size.
    pub case: CaseLimits,
    /// Items of a batch.
    pub max_batch_items: usize,
    /// Points of a creep curve.
    pub max_curve_points: usize,
    /// Open sessions.
    pub max_sessions: usize,
    /// Open sessions of one client (0: half of `max_sessions`).
    pub client_max_sessions: usize,
    /// Largest message \[bytes\] (a session step's response included).
    pub max_message_bytes: usize,
    /// Memory of one session, live state and marks \[bytes\].
    pub max_session_bytes: usize,
    /// Memory of all sessions together \[bytes\].
    pub max_sessions_total_bytes: usize,
    /// A session without a message for this long is closed.
    pub session_idle_timeout: Duration,
    /// A session stream must send its first message (`open`) within this.
    pub first_message_timeout: Duration,
    /// A streamed response whose client reads nothing for this long is
    /// ended (`stream_write_timeout_s`).
    pub stream_write_timeout: Duration,
}

/// The service: shared by all connections.
#[derive(Clone)]
pub struct ContactHandlers {
    pool: SolvePool,
    limits: RequestLimits,
    metrics: Arc<Metrics>,
    /// Open sessions, per client and in all.
    sessions: Arc<Quota>,
    /// The memory of the sessions (live state and marks).
    memory: SessionBudget,
    next_id: Arc<AtomicU64>,
    pairs: Arc<PairRegistry>,
}

/// Messages buffered per streaming response before the solver waits for
/// the client.
const STREAM_BUFFER: usize = 8;

/// Answers of a creep curve queued before its solve waits for the client
/// (each may hold per-element fields: megabytes).
const CURVE_BUFFER: usize = 2;

type BoxStream<T> = Pin<Box<dyn Stream<Item = Result<T, Status>> + Send>>;

impl ContactHandlers {
    /// Handlers solving on `pool` within `limits` on the profile pairs of
    /// `pairs`, counting into `metrics`.
    pub fn new(
        pool: SolvePool,
        limits: RequestLimits,
        metrics: Arc<Metrics>,
        pairs: Arc<PairRegistry>,
    ) -> Self {
        Self {
            pool,
            limits,
            sessions: Quota::new(
                Resource::Sessions,
                Some(limits.max_sessions),
                client_share(limits.client_max_sessions, limits.max_sessions),
                metrics.clone(),
            ),
            metrics,
            memory: SessionBudget::new(limits.max_session_bytes, limits.max_sessions_total_bytes),
            next_id: Arc::new(AtomicU64::new(1)),
            pairs,
        }
    }

    /// The client's `x-request-id` (escaped for the log), or a new server
    /// id.
    fn request_id<T>(&self, req: &Request<T>) -> String {
        req.metadata()
            .get("x-request-id")
            .and_then(|v| v.to_str().ok())
            .map(escaped)
            .unwrap_or_else(|| format!("r{}", self.next_id.fetch_add(1, Ordering::Relaxed)))
    }

    /// [`convert::validate_case`] of `case`, on a solve worker when it
    /// carries numerical influence coefficients: their text is parsed at
    /// about 1 ms per 100 kB, up to a few hundred milliseconds at the
    /// message limit, which would stall the runtime's threads. Other cases
    /// validate in microseconds, here.
    async fn validate_case(&self, case: pb::PatchCase) -> Result<convert::ValidCase, ServiceError> {
        let limits = self.limits.case;
        if !convert::carries_influence_content(&case) {
            return convert::validate_case(&case, limits);
        }
        self.pool
            .internal()
            .run(move || convert::validate_case(&case, limits))
            .await?
    }

    /// Validates and solves one patch on an admitted slot; errors carry
    /// field paths under `prefix`.
    async fn solve_one(
        &self,
        admission: &Admission,
        req: pb::SolvePatchRequest,
        prefix: &str,
    ) -> Result<pb::PatchResult, ServiceError> {
        let case = req
            .case
            .ok_or_else(|| ServiceError::invalid("case", "missing"))
            .map_err(|e| e.within(prefix))?;
        let valid = self
            .validate_case(case)
            .await
            .map_err(|e| e.within(&join(prefix, "case")))?;
        convert::check_fields(&valid.case, req.include_fields).map_err(|e| e.within(prefix))?;
        let jacobian = req.include_sensitivities;
        if jacobian {
            check_sensitivities(&valid.case).map_err(|e| e.within(prefix))?;
        }
        let model = valid.case.model;
        let lane = patch_lane(&valid.case, jacobian);
        let fields = req.include_fields;
        let t0 = StdInstant::now();
        let result = admission
            .run_on(lane, move || {
                let mut engine = PatchEngine::new(valid, KernelCache::global())?;
                if jacobian {
                    engine.enable_sensitivities()?;
                }
                engine.solve(fields)
            })
            .await
            .and_then(|r| r)
            .map_err(|e| e.within(&join(prefix, "case")));
        self.metrics
            .solved(model, t0.elapsed().as_secs_f64(), result.is_ok());
        result
    }
}

impl ContactHandlers {
    /// Solves one wheelset query on an admitted slot; errors carry field
    /// paths under `prefix`.
    async fn solve_wheel_rail_one(
        &self,
        admission: &Admission,
        req: pb::SolveWheelRailRequest,
        prefix: &str,
    ) -> Result<pb::WheelRailResult, ServiceError> {
        let entry = self.pairs.lookup(&req.pair_id)?;
        let mut input = wheelrail::input(
            &req,
            &entry.spec.settings,
            self.limits.case.max_grid_elements,
        )
        .map_err(|e| e.within(prefix))?;
        let load_field = wheelrail::load_field(req.load.as_ref());
        let model = input.settings.model;
        let prepared = self
            .pairs
            .prepared(&entry, admission, Arc::new(|_, _| {}))
            .await?;
        let tabulated = wheelrail::tabulated(req.model);
        let table = match tabulated {
            true => Some(self.pairs.table(&prepared, admission).await?),
            false => None,
        };
        input.rail_slices = prepared.rail_slices();
        let t0 = StdInstant::now();
        let solved = admission
            .run_on_wide(wheelrail_lane(model), true, move |wide| {
                let mut scratch = SearchScratch::default();
                scratch.parallel_wheels = wide;
                let cache = KernelCache::global();
                // A rail varying along the track: placed at the position.
                let at = prepared.pair_at(input.position.track_s_m)?;
                let pair = at.as_deref().unwrap_or(&prepared.pair);
                match &table {
                    Some(t) => solve_wheelset_tabulated(t, &input, cache, &mut scratch),
                    None => solve_wheelset(pair, &input, cache, &mut scratch),
                }
                .map(|s| {
                    let w = check_plausibility(&input, &s);
                    (s, w)
                })
            })
            .await?
            .map_err(|e| {
                wheelrail::rollers_rekeyed(ServiceError::from(e))
                    .rekey("grid.element_size_m", "element_size_m")
                    .rename("load", load_field)
                    .within(prefix)
            });
        self.metrics.solved_as(
            wheelrail::model_name(model),
            t0.elapsed().as_secs_f64(),
            solved.is_ok(),
        );
        let (solution, warnings) = solved?;
        let warnings = wheelrail::warnings(&warnings, prefix);
        let mut result = wheelrail::result(
            &entry.spec.id,
            model,
            &solution,
            warnings,
            req.include_fields,
        )?;
        if tabulated {
            result.model = req.model;
        }
        Ok(result)
    }

    /// Runs the items of a batch concurrently on one admission (one queue
    /// slot; at most one item per worker in flight, so that other requests
    /// do not wait for the whole batch, see [`SolvePool::run_items`]):
    /// `solve(handlers, admission, item, "items[i]")`. Outcomes in request
    /// order.
    ///
    /// The answer is counted as it is built: once the results solved so
    /// far are larger than one message may be (`max_message_bytes`), the
    /// items not yet started are not solved and the batch is refused
    /// (RESOURCE_EXHAUSTED naming `include_fields` and the batch's size),
    /// so a batch holds at most about one message of results, not all of
    /// them, before it is found too large.
    async fn batch<T, R, F, Fut>(
        &self,
        client: &ClientId,
        items: Vec<T>,
        deadline: Option<tokio::time::Instant>,
        solve: F,
    ) -> Result<Vec<(u32, Result<R, ServiceError>)>, ServiceError>
    where
        T: Send + 'static,
        R: prost::Message + Send + 'static,
        F: Fn(ContactHandlers, Arc<Admission>, T, String) -> Fut + Clone + Send + 'static,
        Fut: std::future::Future<Output = Result<R, ServiceError>> + Send + 'static,
    {
        if items.len() > self.limits.max_batch_items {
            return Err(ServiceError::invalid(
                "items",
                format!(
                    "{} items, more than this server's limit of {} per batch: split the batch",
                    items.len(),
                    self.limits.max_batch_items
                ),
            ));
        }
        let admission = Arc::new(self.pool.admit_for(client, deadline)?);
        let _trim = ReturnMemoryOnDrop;
        let (n, max) = (items.len(), self.limits.max_message_bytes);
        // Bytes of the results built so far, and the items solved.
        let built = Arc::new((AtomicUsize::new(0), AtomicUsize::new(0)));
        let outcomes = self
            .pool
            .run_items(items, |i, item| {
                let (this, admission, solve) = (self.clone(), admission.clone(), solve.clone());
                let built = built.clone();
                async move {
                    if built.0.load(Ordering::Relaxed) > max {
                        return (i as u32, Err(ServiceError::Exhausted(String::new())));
                    }
                    let r = solve(this, admission, item, format!("items[{i}]")).await;
                    if let Ok(result) = &r {
                        built.0.fetch_add(result.encoded_len(), Ordering::Relaxed);
                        built.1.fetch_add(1, Ordering::Relaxed);
                    }
                    (i as u32, r)
                }
                .in_current_span()
            })
            .await?;
        let (bytes, solved) = (
            built.0.load(Ordering::Relaxed),
            built.1.load(Ordering::Relaxed),
        );
        if bytes > max {
            return Err(ServiceError::Exhausted(format!(
                "the answer would be more than {bytes} bytes (the results of {solved} of the \
                 batch's {n} items), more than this server's max_message_bytes ({max}); the \
                 other items were not solved: {BATCH_REMEDY}"
            )));
        }
        Ok(outcomes)
    }
}

/// Progress messages of a registration.
type ProgressTx = mpsc::UnboundedSender<Result<pb::RegistrationProgress, Status>>;

/// Share of a registration done at each stage [-].
fn fraction_done(stage: pb::RegistrationStage) -> f64 {
    use pb::RegistrationStage as S;
    match stage {
        S::Unspecified => 0.0,
        S::Validated => 0.01,
        S::WheelParsed => 0.02,
        S::RailParsed => 0.03,
        S::Placed => 0.05,
        S::TableBuilt => 0.95,
        S::Stored => 0.97,
        S::Ready => 1.0,
    }
}

/// Registers a checked pair, streaming its progress into `tx`.
async fn register(
    registry: &Arc<PairRegistry>,
    spec: PairSpec,
    admission: &Admission,
    tx: &ProgressTx,
    t0: StdInstant,
) -> Result<(), ServiceError> {
    let send = {
        let (tx, id) = (tx.clone(), spec.id.clone());
        move |stage: pb::RegistrationStage,
              message: &str,
              pair: Option<pb::ProfilePairInfo>,
              already: bool| {
            let _ = tx.send(Ok(pb::RegistrationProgress {
                stage: stage as i32,
                pair_id: id.clone(),
                fraction_done: fraction_done(stage),
                elapsed_s: t0.elapsed().as_secs_f64(),
                message: message.to_string(),
                pair,
                already_registered: already,
            }));
        }
    };
    let (entry, existed) = registry.begin(spec)?;
    send(
        pb::RegistrationStage::Validated,
        "request checked, id computed",
        None,
        false,
    );
    if !(existed && entry.is_ready()) {
        let s = send.clone();
        let progress: Arc<Progress> = Arc::new(move |stage, m: &str| s(stage, m, None, false));
        let prepared = match registry.prepared(&entry, admission, progress).await {
            Ok(p) => p,
            Err(e) => {
                if !existed {
                    registry.abandon(&entry);
                }
                return Err(e);
            }
        };
        // The contact table: only model hertz_fastsim_table needs it, so a
        // pair whose table cannot be built is still registered.
        let message = match registry.table(&prepared, admission).await {
            Ok(t) => format!(
                "contact table built: {} nodes in {:.2} s",
                t.node_count(),
                t.build_time_s()
            ),
            Err(e) => {
                tracing::warn!(pair_id = %escaped(&entry.spec.id), error = %escaped(&e.to_string()), "contact table not built");
                format!("contact table not built ({e}); model hertz_fastsim_table will fail for this pair, the others do not need it")
            }
        };
        send(pb::RegistrationStage::TableBuilt, &message, None, false);
        let (r, e) = (registry.clone(), entry.clone());
        if admission.run(move || r.persist(&e)).await?? {
            send(
                pb::RegistrationStage::Stored,
                "written to the store",
                None,
                false,
            );
        }
    }
    tracing::info!(pair_id = %escaped(&entry.spec.id), existed, "profile pair registered");
    send(
        pb::RegistrationStage::Ready,
        "ready",
        Some(entry.info()),
        existed,
    );
    Ok(())
}

/// `prefix.name`, or `name` without a prefix.
fn join(prefix: &str, name: &str) -> String {
    if prefix.is_empty() {
        name.to_string()
    } else {
        format!("{prefix}.{name}")
    }
}

/// Timing and outcome of one call, into the metrics.
fn finish<T>(
    metrics: &Metrics,
    method: &'static str,
    t0: StdInstant,
    r: Result<T, ServiceError>,
) -> Result<T, Status> {
    metrics.request(
        method,
        t0.elapsed().as_secs_f64(),
        r.as_ref().err().map(|e| e.code()),
    );
    match &r {
        // A client over its share may send thousands a second: those
        // lines are limited.
        Err(e @ ServiceError::Exhausted(_)) => {
            if let Some(left_out) = crate::service::quota::REFUSED_CALLS_LOG.allow() {
                tracing::info!(code = ?e.code(), error = %escaped(&e.to_string()), left_out, "request failed");
            }
        }
        Err(e) => {
            tracing::info!(code = ?e.code(), error = %escaped(&e.to_string()), "request failed")
        }
        Ok(_) => {}
    }
    r.map_err(Status::from)
}

/// What to do about an answer larger than `max_message_bytes`.
const ANSWER_REMEDY: &str =
    "ask without per-element fields (`include_fields`) or on a coarser grid";
/// ... about a batch's answer.
const BATCH_REMEDY: &str =
    "split the batch into smaller ones, or ask without per-element fields (`include_fields`)";

impl ContactHandlers {
    /// `answer` when it fits in one message (`max_message_bytes`), else
    /// RESOURCE_EXHAUSTED saying its size, the limit and `remedy` (tonic
    /// would refuse to send it with OUT_OF_RANGE and its own text).
    fn sized<M: prost::Message>(&self, answer: M, remedy: &str) -> Result<M, ServiceError> {
        let (len, max) = (answer.encoded_len(), self.limits.max_message_bytes);
        if len <= max {
            return Ok(answer);
        }
        Err(ServiceError::Exhausted(format!(
            "the answer would be {len} bytes, more than this server's max_message_bytes ({max}): \
             {remedy}"
        )))
    }
}

#[tonic::async_trait]
impl pb::contact_service_server::ContactService for ContactHandlers {
    async fn solve_patch(
        &self,
        req: Request<pb::SolvePatchRequest>,
    ) -> Result<Response<pb::SolvePatchResponse>, Status> {
        let t0 = StdInstant::now();
        let span = tracing::info_span!("SolvePatch", request_id = %self.request_id(&req));
        let deadline = deadline_of(req.metadata());
        let client = ClientId::of(&req);
        let r = async {
            let admission = self.pool.admit_for(&client, deadline)?;
            let result = self.solve_one(&admission, req.into_inner(), "").await?;
            self.sized(
                pb::SolvePatchResponse {
                    result: Some(result),
                },
                ANSWER_REMEDY,
            )
        }
        .instrument(span)
        .await;
        finish(&self.metrics, "SolvePatch", t0, r).map(Response::new)
    }

    async fn solve_patch_batch(
        &self,
        req: Request<pb::SolvePatchBatchRequest>,
    ) -> Result<Response<pb::SolvePatchBatchResponse>, Status> {
        let t0 = StdInstant::now();
        let span = tracing::info_span!("SolvePatchBatch", request_id = %self.request_id(&req));
        let deadline = deadline_of(req.metadata());
        let client = ClientId::of(&req);
        let r = async {
            let items = req.into_inner().items;
            let solve = |this: ContactHandlers, a: Arc<Admission>, item, prefix: String| async move {
                this.solve_one(&a, item, &prefix).await
            };
            let slots = self
                .batch(&client, items, deadline, solve)
                .await?
                .into_iter()
                .map(|(index, r)| pb::BatchItemResult {
                    index,
                    outcome: Some(match r {
                        Ok(result) => pb::batch_item_result::Outcome::Result(result),
                        Err(e) => pb::batch_item_result::Outcome::Error(e.item_error()),
                    }),
                })
                .collect();
            self.sized(pb::SolvePatchBatchResponse { items: slots }, BATCH_REMEDY)
        }
        .instrument(span)
        .await;
        finish(&self.metrics, "SolvePatchBatch", t0, r).map(Response::new)
    }

    type RegisterProfilePairStream = BoxStream<pb::RegistrationProgress>;

    async fn register_profile_pair(
        &self,
        req: Request<pb::RegisterProfilePairRequest>,
    ) -> Result<Response<Self::RegisterProfilePairStream>, Status> {
        let t0 = StdInstant::now();
        let span = tracing::info_span!("RegisterProfilePair", request_id = %self.request_id(&req));
        let deadline = deadline_of(req.metadata());
        let client = ClientId::of(&req);
        let checked = async {
            let spec = pairs::canonicalize(&req.into_inner())?;
            let admission = self.pool.admit_for(&client, deadline)?;
            Ok((spec, admission))
        }
        .instrument(span.clone())
        .await;
        let (spec, admission) = finish(&self.metrics, "RegisterProfilePair", t0, checked)?;
        let (tx, rx) = mpsc::unbounded_channel();
        let registry = self.pairs.clone();
        tokio::spawn(
            async move {
                if let Err(e) = register(&registry, spec, &admission, &tx, t0).await {
                    tracing::info!(code = ?e.code(), error = %escaped(&e.to_string()), "registration failed");
                    let _ = tx.send(Err(Status::from(e)));
                }
            }
            .instrument(span),
        );
        Ok(Response::new(Box::pin(UnboundedReceiverStream::new(rx))))
    }

    async fn get_profile_pair(
        &self,
        req: Request<pb::GetProfilePairRequest>,
    ) -> Result<Response<pb::ProfilePairInfo>, Status> {
        let t0 = StdInstant::now();
        let r = self.pairs.lookup(&req.get_ref().pair_id).map(|e| e.info());
        finish(&self.metrics, "GetProfilePair", t0, r).map(Response::new)
    }

    async fn list_profile_pairs(
        &self,
        _req: Request<pb::ListProfilePairsRequest>,
    ) -> Result<Response<pb::ListProfilePairsResponse>, Status> {
        let t0 = StdInstant::now();
        let pairs = self.pairs.list().iter().map(|e| e.info()).collect();
        let r = Ok(pb::ListProfilePairsResponse { pairs });
        finish(&self.metrics, "ListProfilePairs", t0, r).map(Response::new)
    }

    async fn delete_profile_pair(
        &self,
        req: Request<pb::DeleteProfilePairRequest>,
    ) -> Result<Response<pb::DeleteProfilePairResponse>, Status> {
        let t0 = StdInstant::now();
        let span = tracing::info_span!("DeleteProfilePair", request_id = %self.request_id(&req));
        let deadline = deadline_of(req.metadata());
        let client = ClientId::of(&req);
        let r = async {
            let id = self.pairs.lookup(&req.get_ref().pair_id)?.spec.id.clone();
            let admission = self.pool.admit_for(&client, deadline)?;
            let (registry, key) = (self.pairs.clone(), id.clone());
            admission.run(move || registry.delete(&key)).await??;
            tracing::info!(pair_id = %escaped(&id), "profile pair deleted");
            Ok(pb::DeleteProfilePairResponse { pair_id: id })
        }
        .instrument(span)
        .await;
        finish(&self.metrics, "DeleteProfilePair", t0, r).map(Response::new)
    }

    async fn solve_wheel_rail(
        &self,
        req: Request<pb::SolveWheelRailRequest>,
    ) -> Result<Response<pb::SolveWheelRailResponse>, Status> {
        let t0 = StdInstant::now();
        let span = tracing::info_span!("SolveWheelRail", request_id = %self.request_id(&req));
        let deadline = deadline_of(req.metadata());
        let client = ClientId::of(&req);
        let r = async {
            let admission = self.pool.admit_for(&client, deadline)?;
            let result = self
                .solve_wheel_rail_one(&admission, req.into_inner(), "")
                .await?;
            self.sized(
                pb::SolveWheelRailResponse {
                    result: Some(result),
                },
                ANSWER_REMEDY,
            )
        }
        .instrument(span)
        .await;
        finish(&self.metrics, "SolveWheelRail", t0, r).map(Response::new)
    }

    async fn solve_wheel_rail_batch(
        &self,
        req: Request<pb::SolveWheelRailBatchRequest>,
    ) -> Result<Response<pb::SolveWheelRailBatchResponse>, Status> {
        let t0 = StdInstant::now();
        let span = tracing::info_span!("SolveWheelRailBatch", request_id = %self.request_id(&req));
        let deadline = deadline_of(req.metadata());
        let client = ClientId::of(&req);
        let r = async {
            let items = req.into_inner().items;
            let solve = |this: ContactHandlers, a: Arc<Admission>, item, prefix: String| async move {
                this.solve_wheel_rail_one(&a, item, &prefix).await
            };
            let items = self
                .batch(&client, items, deadline, solve)
                .await?
                .into_iter()
                .map(|(index, r)| pb::WheelRailBatchItem {
                    index,
                    outcome: Some(match r {
                        Ok(result) => pb::wheel_rail_batch_item::Outcome::Result(result),
                        Err(e) => pb::wheel_rail_batch_item::Outcome::Error(e.item_error()),
                    }),
                })
                .collect();
            self.sized(pb::SolveWheelRailBatchResponse { items }, BATCH_REMEDY)
        }
        .instrument(span)
        .await;
        finish(&self.metrics, "SolveWheelRailBatch", t0, r).map(Response::new)
    }

    type CreepCurveStream = BoxStream<pb::CreepCurvePoint>;

    async fn creep_curve(
        &self,
        req: Request<pb::CreepCurveRequest>,
    ) -> Result<Response<Self::CreepCurveStream>, Status> {
        let t0 = StdInstant::now();
        let span = tracing::info_span!("CreepCurve", request_id = %self.request_id(&req));
        let deadline = deadline_of(req.metadata());
        let client = ClientId::of(&req);
        let connection = req.extensions().get::<ConnInfo>().cloned();
        let prepared = async {
            let req = req.into_inner();
            let points = sweep_points(&req, self.limits.max_curve_points)?;
            let case = req
                .case
                .ok_or_else(|| ServiceError::invalid("case", "missing"))?;
            let valid = self.validate_case(case).await.map_err(|e| e.within("case"))?;
            convert::refuse_solve_patch_only(&valid.case, "creep curves")
                .map_err(|e| e.within("case"))?;
            convert::check_fields(&valid.case, req.include_fields)?;
            if !matches!(valid.case.kinematics, Kinematics::SteadyRolling(_)) {
                return Err(ServiceError::invalid(
                    "case.rolling",
                    "missing: a creep curve is a steady-rolling sweep; set `rolling` (its creepages are replaced by the sweep's)",
                ));
            }
            if matches!(valid.case.model, Model::Hertz | Model::HertzCorrected) {
                return Err(ServiceError::invalid(
                    "case.model",
                    "the Hertz models compute no tangential forces: use exact, fastsim, cect or cect_halfspace",
                ));
            }
            let admission = self.pool.admit_for(&client, deadline)?;
            Ok((valid, points, req.include_fields, admission))
        }
        .instrument(span.clone())
        .await;
        let (valid, points, fields, admission) = finish(&self.metrics, "CreepCurve", t0, prepared)?;
        let (tx, rx) = outbound(CURVE_BUFFER);
        let tx = Arc::new(tx);
        let metrics = self.metrics.clone();
        let stalls = self.metrics.clone();
        let write_timeout = self.limits.stream_write_timeout;
        // Queues an answer; false when the curve is to stop: its client is
        // gone, or has read nothing for `stream_write_timeout_s` (then the
        // stream is ended, and its connection closed, which frees what
        // HTTP/2 buffered for it).
        let send = move |msg: Result<pb::CreepCurvePoint, Status>, index: usize| {
            let (tx, metrics, connection) = (tx.clone(), stalls.clone(), connection.clone());
            async move {
                match tx.send(msg, write_timeout).await {
                    Ok(()) => true,
                    Err(Unsent::Gone) => false,
                    Err(Unsent::Stalled) => {
                        metrics.stream_write_timed_out();
                        let message = format!(
                            "the client read none of this creep curve's answers for {} s, this \
                             server's stream_write_timeout_s: the curve was stopped at point \
                             {index} and its connection closed",
                            write_timeout.as_secs_f64()
                        );
                        if let Some(left_out) = crate::service::quota::REFUSED_CALLS_LOG.allow() {
                            tracing::info!(left_out, "{message}");
                        }
                        tx.fail(Status::deadline_exceeded(message));
                        if let Some(c) = connection {
                            c.state.abort();
                        }
                        false
                    }
                }
            }
        };
        tokio::spawn(
            async move {
                let _trim = ReturnMemoryOnDrop;
                let model = valid.case.model;
                let lane = patch_lane(&valid.case, false);
                let built = admission
                    .run_on(lane, move || PatchEngine::new(valid, KernelCache::global()))
                    .await
                    .and_then(|r| r);
                let mut engine = match built {
                    Ok(e) => e,
                    Err(e) => {
                        send(Err(Status::from(e.within("case"))), 0).await;
                        return;
                    }
                };
                for (index, c) in points.into_iter().enumerate() {
                    let t = StdInstant::now();
                    let solved = admission
                        .run_on(lane, move || {
                            engine.set_creepages(c);
                            let r = engine.solve(fields);
                            (engine, r)
                        })
                        .await;
                    let r = match solved {
                        Ok((e, r)) => {
                            engine = e;
                            r
                        }
                        Err(e) => {
                            send(Err(Status::from(e)), index).await;
                            return;
                        }
                    };
                    metrics.solved(model, t.elapsed().as_secs_f64(), r.is_ok());
                    let msg = r
                        .map(|result| pb::CreepCurvePoint {
                            index: index as u32,
                            creepages: Some(convert::wire_creepages(&c)),
                            result: Some(result),
                        })
                        .map_err(|e| Status::from(e.within("case")));
                    let failed = msg.is_err();
                    if !send(msg, index).await || failed {
                        return;
                    }
                }
            }
            .instrument(span),
        );
        Ok(Response::new(Box::pin(rx)))
    }

    type WheelRailSessionStream = BoxStream<pb::WheelRailSessionResponse>;

    async fn wheel_rail_session(
        &self,
        req: Request<Streaming<pb::WheelRailSessionRequest>>,
    ) -> Result<Response<Self::WheelRailSessionStream>, Status> {
        let session_id = format!("w{}", self.next_id.fetch_add(1, Ordering::Relaxed));
        let span = tracing::info_span!("WheelRailSession", request_id = %self.request_id(&req), session_id = %session_id);
        let client = ClientId::of(&req);
        let mut inbound = req.into_inner();
        Ok(self.serve_stream(span, move |this, tx| async move {
            this.run_wheelrail_session(&mut inbound, &tx, session_id, client)
                .await
        }))
    }

    type ContactLibraryStream = BoxStream<pb::ContactLibraryResponse>;

    async fn contact_library(
        &self,
        req: Request<Streaming<pb::ContactLibraryRequest>>,
    ) -> Result<Response<Self::ContactLibraryStream>, Status> {
        let session_id = format!("c{}", self.next_id.fetch_add(1, Ordering::Relaxed));
        let span = tracing::info_span!("ContactLibrary", request_id = %self.request_id(&req), session_id = %session_id);
        let client = ClientId::of(&req);
        let mut inbound = req.into_inner();
        Ok(self.serve_stream(span, move |this, tx| async move {
            this.run_contact_library(&mut inbound, &tx, session_id, client)
                .await
        }))
    }

    type PatchSessionStream = BoxStream<pb::SessionResponse>;

    async fn patch_session(
        &self,
        req: Request<Streaming<pb::SessionRequest>>,
    ) -> Result<Response<Self::PatchSessionStream>, Status> {
        let session_id = format!("s{}", self.next_id.fetch_add(1, Ordering::Relaxed));
        let span = tracing::info_span!("PatchSession", request_id = %self.request_id(&req), session_id = %session_id);
        let client = ClientId::of(&req);
        let mut inbound = req.into_inner();
        Ok(self.serve_stream(span, move |this, tx| async move {
            this.run_session(&mut inbound, &tx, session_id, client)
                .await
        }))
    }
}

/// Gives the session's place back (the server's count and its client's)
/// when a session ends, however it ends, and updates the sessions' memory
/// figures (declared before the session, it is dropped after it and its
/// memory).
struct SessionSlot(Option<QuotaGuard>, Arc<Metrics>, SessionBudget);

impl Drop for SessionSlot {
    fn drop(&mut self) {
        drop(self.0.take());
        self.1.session_closed();
        self.1.session_memory(&self.2);
    }
}

/// The solve lane of a patch: Hertz and FASTSIM are fast, and run inline
/// on small grids without sensitivities (see [`Lane::Inline`]).
fn patch_lane(case: &Case, sensitivities: bool) -> Lane {
    match case.model {
        Model::Hertz | Model::HertzCorrected if !sensitivities => Lane::Inline,
        Model::Fastsim if !sensitivities && case.nx * case.ny <= INLINE_FASTSIM_ELEMENTS => {
            Lane::Inline
        }
        Model::Hertz | Model::HertzCorrected | Model::Fastsim => Lane::Fast,
        _ => Lane::Heavy,
    }
}

/// The solve lane of a wheel/rail model: the Hertz models and
/// kik_piotrowski are fast.
fn wheelrail_lane(model: WheelRailModel) -> Lane {
    Lane::of(model.is_fast())
}

fn open_first() -> ServiceError {
    ServiceError::invalid("open", "the first message of a session must be `open`")
}

fn already_open() -> ServiceError {
    ServiceError::precondition(
        "open",
        "the session is already open: send steps or a rollback",
    )
}

/// A refused session request, answered in-band.
fn refused(e: ServiceError) -> pb::ItemError {
    tracing::debug!(error = %escaped(&e.to_string()), "session request refused");
    e.item_error()
}

type SessionTx = mpsc::Sender<Result<pb::SessionResponse, Status>>;

fn reply(kind: pb::session_response::Kind) -> pb::SessionResponse {
    pb::SessionResponse { kind: Some(kind) }
}

impl ContactHandlers {
    /// Counts a session of `client` in, or RESOURCE_EXHAUSTED at the
    /// server's limit (`max_sessions`) or the client's share
    /// (`client_max_sessions`), naming it.
    fn session_slot(&self, client: &ClientId) -> Result<SessionSlot, ServiceError> {
        let counted = self.sessions.take(client)?;
        self.metrics.session_opened();
        Ok(SessionSlot(
            Some(counted),
            self.metrics.clone(),
            self.memory.clone(),
        ))
    }

    /// The limits of a new session.
    fn session_limits(&self) -> SessionLimits {
        SessionLimits {
            max_response_bytes: self.limits.max_message_bytes,
            memory: self.memory.clone(),
            max_grid_elements: self.limits.case.max_grid_elements,
        }
    }

    /// A session's next message; None when the client closed its stream.
    /// After `session_idle_timeout` without one, the session is closed:
    /// its last message is the in-band error `in_band(e)` (if the client
    /// reads it in time), then the stream ends with its status
    /// (DEADLINE_EXCEEDED).
    async fn receive<T, R>(
        &self,
        inbound: &mut Streaming<T>,
        tx: &mpsc::Sender<Result<R, Status>>,
        in_band: impl FnOnce(pb::ItemError) -> R,
    ) -> Result<Option<T>, Status> {
        let idle = self.limits.session_idle_timeout;
        match tokio::time::timeout(idle, inbound.message()).await {
            Ok(message) => message.map_err(status::inbound),
            Err(_) => {
                let e = self.idle_closed();
                let _ = tokio::time::timeout(idle, tx.send(Ok(in_band(e.item_error())))).await;
                Err(e.into())
            }
        }
    }

    /// A session's first message, which must come within
    /// `stream_first_message_timeout_s` of the stream's start: a stream that
    /// stays silent is ended with DEADLINE_EXCEEDED before it takes a
    /// session slot. None when the client closed its stream.
    async fn receive_first<T>(&self, inbound: &mut Streaming<T>) -> Result<Option<T>, Status> {
        let wait = self.limits.first_message_timeout;
        match tokio::time::timeout(wait, inbound.message()).await {
            Ok(message) => message.map_err(status::inbound),
            Err(_) => {
                self.metrics.first_message_timed_out();
                Err(ServiceError::Deadline(format!(
                    "no message within {} s of the stream's start, this server's \
                     stream_first_message_timeout_s: send `open` first",
                    wait.as_secs_f64()
                ))
                .into())
            }
        }
    }

    /// Sends a session's response: false when the client has gone; the
    /// idle error when it read nothing for `session_idle_timeout` (the
    /// session is then closed, see [`ContactHandlers::receive`]).
    async fn send<R>(&self, tx: &mpsc::Sender<Result<R, Status>>, r: R) -> Result<bool, Status> {
        self.metrics.session_memory(&self.memory);
        match tokio::time::timeout(self.limits.session_idle_timeout, tx.send(Ok(r))).await {
            Ok(sent) => Ok(sent.is_ok()),
            Err(_) => Err(self.idle_closed().into()),
        }
    }

    /// Counts a session closed for idling and says why.
    fn idle_closed(&self) -> ServiceError {
        self.metrics.session_idle_closed();
        let e = ServiceError::Deadline(format!(
            "the session was idle for {} s (no message from the client, or none of its \
             responses read), this server's session_idle_timeout_s: it is closed; open a new \
             session",
            self.limits.session_idle_timeout.as_secs_f64()
        ));
        tracing::info!(error = %escaped(&e.to_string()), "session closed");
        e
    }

    /// Ends a stream with `status` (given up after `session_idle_timeout`
    /// when the client reads nothing).
    /// A streamed answer whose messages `run` sends on its channel, run on
    /// its own task in `span`; an error it returns ends the stream with
    /// that status ([`ContactHandlers::end_stream`]).
    fn serve_stream<R, Run, Fut>(&self, span: tracing::Span, run: Run) -> Response<BoxStream<R>>
    where
        R: Send + 'static,
        Run: FnOnce(ContactHandlers, mpsc::Sender<Result<R, Status>>) -> Fut + Send + 'static,
        Fut: std::future::Future<Output = Result<(), Status>> + Send + 'static,
    {
        let (tx, rx) = mpsc::channel(STREAM_BUFFER);
        let this = self.clone();
        tokio::spawn(
            async move {
                let _trim = ReturnMemoryOnDrop;
                let errors = tx.clone();
                if let Err(status) = run(this.clone(), tx).await {
                    this.end_stream(&errors, status).await;
                }
            }
            .instrument(span),
        );
        Response::new(Box::pin(ReceiverStream::new(rx)))
    }

    async fn end_stream<R>(&self, tx: &mpsc::Sender<Result<R, Status>>, status: Status) {
        let _ = tokio::time::timeout(self.limits.session_idle_timeout, tx.send(Err(status))).await;
    }

    /// Runs one wheel/rail session until the client closes its stream.
    /// Refused steps are answered in-band; an `Err` ends the stream.
    async fn run_wheelrail_session(
        &self,
        inbound: &mut Streaming<pb::WheelRailSessionRequest>,
        tx: &mpsc::Sender<Result<pb::WheelRailSessionResponse, Status>>,
        session_id: String,
        client: ClientId,
    ) -> Result<(), Status> {
        use pb::wheel_rail_session_request::Kind;
        use pb::wheel_rail_session_response::Kind as Out;
        let reply = |kind| pb::WheelRailSessionResponse { kind: Some(kind) };
        let in_band = |e| reply(Out::Error(e));
        let open = match self.receive_first(inbound).await? {
            Some(pb::WheelRailSessionRequest {
                kind: Some(Kind::Open(open)),
            }) => open,
            Some(_) => return Err(open_first().into()),
            None => return Ok(()),
        };
        let _slot = self.session_slot(&client)?;
        let entry = self.pairs.lookup(&open.pair_id)?;
        let admission = self.pool.session(&client);
        let prepared = self
            .pairs
            .prepared(&entry, &admission, Arc::new(|_, _| {}))
            .await?;
        let table = match wheelrail::tabulated(open.model) {
            true => Some(self.pairs.table(&prepared, &admission).await?),
            false => None,
        };
        drop(admission);
        let mut session =
            WheelRailSession::open(entry, prepared, table, &open, self.session_limits())
                .map_err(|e| Status::from(e.within("open")))?;
        let model = session.model();
        tracing::info!(label = %escaped(&open.client_label), pair_id = session.pair_id(), model = wheelrail::model_name(model), "wheel/rail session opened");
        let opened = Out::Opened(pb::WheelRailSessionOpened {
            session_id,
            pair_id: session.pair_id().to_string(),
            model: session.wire_model() as i32,
        });
        if !self.send(tx, reply(opened)).await? {
            return Ok(());
        }
        while let Some(msg) = self.receive(inbound, tx, in_band).await? {
            let out = match msg.kind {
                Some(Kind::Step(step)) => {
                    let t0 = StdInstant::now();
                    let r = match session.check_step(&step) {
                        Ok(input) => {
                            let lane = if session.is_inline(&input) {
                                Lane::Inline
                            } else {
                                wheelrail_lane(model)
                            };
                            let wanted = session.wants_two_threads();
                            let (s, r) = self
                                .pool
                                .session(&client)
                                .run_on_wide(lane, wanted, move |wide| {
                                    let r = session.step(input, wide);
                                    (session, r)
                                })
                                .await?;
                            session = s;
                            r
                        }
                        Err(e) => Err(e),
                    };
                    self.metrics.solved_as(
                        wheelrail::model_name(model),
                        t0.elapsed().as_secs_f64(),
                        r.is_ok(),
                    );
                    r.map(Out::Step)
                }
                Some(Kind::Rollback(r)) => session.rollback(r.to_step_index).map(Out::RolledBack),
                Some(Kind::Open(_)) => Err(already_open()),
                None => Err(ServiceError::invalid("kind", "missing: step or rollback")),
            };
            let out = out.unwrap_or_else(|e| Out::Error(refused(e)));
            if !self.send(tx, reply(out)).await? {
                break;
            }
        }
        tracing::info!(
            next_step = session.next_step(),
            live_bytes = session.live_bytes(),
            mark_bytes = session.mark_bytes(),
            "wheel/rail session closed"
        );
        Ok(())
    }

    /// Runs one `ContactLibrary` session (a copy of a result element of
    /// CONTACT's library) until the client closes its stream; a request
    /// refused before its calculation is answered in-band.
    async fn run_contact_library(
        &self,
        inbound: &mut Streaming<pb::ContactLibraryRequest>,
        tx: &mpsc::Sender<Result<pb::ContactLibraryResponse, Status>>,
        session_id: String,
        client: ClientId,
    ) -> Result<(), Status> {
        use pb::contact_library_request::Kind;
        use pb::contact_library_response::Kind as Out;
        let reply = |kind| pb::ContactLibraryResponse { kind: Some(kind) };
        let in_band = |e| reply(Out::Error(e));
        let open = match self.receive_first(inbound).await? {
            Some(pb::ContactLibraryRequest {
                kind: Some(Kind::Open(open)),
            }) => open,
            Some(_) => return Err(open_first().into()),
            None => return Ok(()),
        };
        let _slot = self.session_slot(&client)?;
        let mut element = LibraryElement::open(
            open.format_version,
            open.module,
            self.limits.case.max_grid_elements,
            self.pairs.slices_limits(),
        )?;
        tracing::info!(label = %escaped(&open.client_label), ire = open.ire, module = element.module(), "contact library element opened");
        let opened = Out::Opened(pb::ContactLibraryOpened {
            session_id,
            format_version: railcontact_cntc_core::remote::FORMAT_VERSION,
        });
        if !self.send(tx, reply(opened)).await? {
            return Ok(());
        }
        let mut calculations = 0u64;
        while let Some(msg) = self.receive(inbound, tx, in_band).await? {
            let out = match msg.kind {
                Some(Kind::Calculate(c)) => {
                    let t0 = StdInstant::now();
                    let (e, r) = self
                        .pool
                        .session(&client)
                        .run_on(Lane::Heavy, move || {
                            let r = element.calculate(&c.request, KernelCache::global());
                            (element, r)
                        })
                        .await?;
                    element = e;
                    calculations += 1;
                    self.metrics.solved_as(
                        "contact_library",
                        t0.elapsed().as_secs_f64(),
                        r.is_ok(),
                    );
                    r.map(Out::Reply)
                }
                Some(Kind::Open(_)) => Err(already_open()),
                None => Err(ServiceError::invalid("kind", "missing: calculate")),
            };
            let out = out.unwrap_or_else(|e| Out::Error(refused(e)));
            if !self.send(tx, reply(out)).await? {
                break;
            }
        }
        tracing::info!(calculations, "contact library element closed");
        Ok(())
    }

    /// Runs one session until the client closes its stream. Refused steps
    /// are answered in-band; an `Err` ends the stream with that status.
    async fn run_session(
        &self,
        inbound: &mut Streaming<pb::SessionRequest>,
        tx: &SessionTx,
        session_id: String,
        client: ClientId,
    ) -> Result<(), Status> {
        use pb::session_request::Kind;
        use pb::session_response::Kind as Out;
        let in_band = |e| pb::SessionResponse {
            kind: Some(Out::Error(e)),
        };
        let open = match self.receive_first(inbound).await? {
            Some(pb::SessionRequest {
                kind: Some(Kind::Open(open)),
            }) => open,
            Some(_) => return Err(open_first().into()),
            None => return Ok(()),
        };
        let _slot = self.session_slot(&client)?;
        let case = open
            .case
            .ok_or_else(|| ServiceError::invalid("open.case", "missing"))?;
        let valid = self
            .validate_case(case)
            .await
            .map_err(|e| e.within("open.case"))?;
        convert::refuse_solve_patch_only(&valid.case, "sessions")
            .map_err(|e| e.within("open.case"))?;
        let jacobian = open.include_sensitivities;
        if jacobian {
            check_sensitivities(&valid.case).map_err(|e| e.within("open"))?;
        }
        let model = valid.case.model;
        let fields = open.include_fields;
        let limits = self.session_limits();
        let admission = self.pool.session(&client);
        let mut session = admission
            .run(move || {
                let mut engine =
                    PatchEngine::new(valid, KernelCache::global()).map_err(|e| e.within("case"))?;
                if jacobian {
                    engine.enable_sensitivities()?;
                }
                Session::open(engine, fields, limits)
            })
            .await
            .and_then(|r| r)
            .map_err(|e| e.within("open"))?;
        drop(admission);
        tracing::info!(label = %escaped(&open.client_label), model = model.name(), kind = ?session.kind(), "session opened");
        let opened = Out::Opened(pb::SessionOpened {
            session_id,
            model: convert::wire_model(model) as i32,
            grid: session.engine().grid(),
            notes: session.engine().case().notes.clone(),
        });
        if !self.send(tx, reply(opened)).await? {
            return Ok(());
        }
        while let Some(msg) = self.receive(inbound, tx, in_band).await? {
            let out = match msg.kind {
                Some(Kind::Step(step)) => {
                    let t0 = StdInstant::now();
                    let (s, r) = self.session_step(session, &step, &client).await?;
                    session = s;
                    self.metrics
                        .solved(model, t0.elapsed().as_secs_f64(), r.is_ok());
                    r.map(Out::Step)
                }
                Some(Kind::Rollback(r)) => session.rollback(r.to_step_index).map(Out::RolledBack),
                Some(Kind::Open(_)) => Err(already_open()),
                None => Err(ServiceError::invalid("kind", "missing: step or rollback")),
            };
            let out = out.unwrap_or_else(|e| Out::Error(refused(e)));
            if !self.send(tx, reply(out)).await? {
                break;
            }
        }
        tracing::info!(
            next_step = session.next_step(),
            live_bytes = session.live_bytes(),
            mark_bytes = session.mark_bytes(),
            "session closed"
        );
        Ok(())
    }

    /// Checks and solves one step on the pool. The session comes back with
    /// the step's outcome; an `Err` (a solve thread failed) ends the session.
    async fn session_step(
        &self,
        mut session: Session,
        step: &pb::SessionStep,
        client: &ClientId,
    ) -> Result<(Session, Result<pb::SessionStepResult, ServiceError>), Status> {
        let input = match session.check_step(step) {
            Ok(i) => i,
            Err(e) => return Ok((session, Err(e))),
        };
        let admission = self.pool.session(client);
        let engine = session.engine();
        let lane = patch_lane(engine.case(), engine.sensitivities());
        let (session, r) = admission
            .run_on(lane, move || {
                let r = session.step(input);
                (session, r)
            })
            .await?;
        Ok((session, r))
    }
}

/// The creepages of a sweep, checked; field paths relative to the request.
fn sweep_points(req: &pb::CreepCurveRequest, max: usize) -> Result<Vec<Creepages>, ServiceError> {
    use pb::creep_curve_request::Sweep;
    let check = |c: &pb::Creepages, key: String| {
        convert::no_prescribed_force(c, &key, "creep curves")?;
        let c = convert::creepages(c);
        c.check_input()
            .map_err(|e| ServiceError::from(e).rekey("rolling", &key))?;
        Ok::<_, ServiceError>(c)
    };
    let points: Vec<Creepages> = match &req.sweep {
        None => {
            return Err(ServiceError::invalid(
                "sweep",
                "missing: give `linear` or `list`",
            ))
        }
        Some(Sweep::List(l)) => {
            if l.points.is_empty() || l.points.len() > max {
                return Err(ServiceError::invalid(
                    "list.points",
                    format!("needs 1 to {max} points, got {}", l.points.len()),
                ));
            }
            l.points
                .iter()
                .enumerate()
                .map(|(k, c)| check(c, format!("list.points[{k}]")))
                .collect::<Result<_, _>>()?
        }
        Some(Sweep::Linear(l)) => {
            let n = l.points as usize;
            if !(2..=max).contains(&n) {
                return Err(ServiceError::invalid(
                    "linear.points",
                    format!("needs 2 to {max} points, got {n}"),
                ));
            }
            let zero = pb::Creepages::default();
            let a = check(l.from.as_ref().unwrap_or(&zero), "linear.from".into())?;
            let b = check(l.to.as_ref().unwrap_or(&zero), "linear.to".into())?;
            let at = |u: f64, p: f64, q: f64| p + u * (q - p);
            (0..n)
                .map(|k| {
                    let u = k as f64 / (n - 1) as f64;
                    Creepages {
                        creepage_long: at(u, a.creepage_long, b.creepage_long),
                        creepage_lat: at(u, a.creepage_lat, b.creepage_lat),
                        spin_per_m: at(u, a.spin_per_m, b.spin_per_m),
                    }
                })
                .collect()
        }
    };
    Ok(points)
}
