//! Prometheus metrics of the server, kept and encoded by `prometheus-client`
//! (Prometheus text format 0.0.4) and served over HTTP/1.1 (axum on hyper)
//! on their own port (`metrics_listen`): `GET /metrics`, 404 elsewhere.
//!
//! | metric | labels | what |
//! |---|---|---|
//! | `railcontact_requests_total` | `method`, `code` | finished calls by gRPC status |
//! | `railcontact_request_duration_seconds` | `method` | latency histogram of unary calls and stream set-up |
//! | `railcontact_solve_duration_seconds` | `model`, `outcome` | histogram of each solve (batch items, curve points, session steps) |
//! | `railcontact_sessions_active` | | open co-simulation sessions |
//! | `railcontact_sessions_opened_total` | | sessions opened |
//! | `railcontact_sessions_idle_closed_total` | | session streams closed because no message came (or no response was read) for `session_idle_timeout_s` |
//! | `railcontact_session_bytes` | | memory held by all open sessions, their live working state (solvers' buffers, warm starts) and marks, against `max_sessions_total_bytes` |
//! | `railcontact_session_mark_bytes` | | the part of it that marks hold |
//! | `railcontact_session_memory_refused_total` | | session opens and steps refused because the session would go beyond `max_session_bytes` or `max_sessions_total_bytes` |
//! | `railcontact_session_marks_refused_total` | | marked steps among them that would have fitted without their mark |
//! | `railcontact_solve_queue_admitted` | | requests admitted to the solve pool |
//! | `railcontact_solves_cancelled_total` | | solves told to stop because their request ended while they ran (deadline, client gone, shutdown; see `core::cancel`) |
//! | `railcontact_kernel_cache_hits_total`, `..._misses_total`, `..._evictions_total` | | influence-kernel cache look-ups and least-recently-used evictions |
//! | `railcontact_kernel_cache_entries`, `..._bytes`, `..._max_bytes` | | kernel sets held, their memory and the cap |
//! | `railcontact_library_pairs_live`, `railcontact_library_pair_hits_total`, `..._builds_total` | | placed profile pairs of the CONTACT-compatible library's elements (`ContactLibrary` sessions), shared by content: pairs held now, requests answered by a pair already placed, pairs placed |
//! | `railcontact_streams_first_message_timed_out_total` | | session streams ended because no first message came within `stream_first_message_timeout_s` |
//! | `railcontact_solves_timed_out_total` | | solves stopped at the server's limit `max_solve_time_s` |
//! | `railcontact_prepared_pairs`, `railcontact_prepared_pair_bytes` | | registered pairs the registry holds prepared (placed profiles, and their contact tables once built) and their memory, against `max_prepared_bytes` |
//! | `railcontact_prepared_pairs_released_total` | | prepared pairs let go, least recently used first, to stay within `max_prepared_bytes` (each is prepared again on its next use) |
//! | `railcontact_store_damaged_records` | | records of the profile pair store found damaged at start and still there (listed as FAILED pairs) |
//! | `railcontact_registrations_refused_total` | `limit` | registrations refused by a limit: `max_profile_pairs`, `max_store_bytes`, `max_profile_points` |
//! | `railcontact_auth_refused_total` | `reason` | calls refused by the bearer tokens (`auth_tokens_file`): `missing` (no `authorization` metadata, or not `Bearer`), `unknown` (no such token), `forbidden` (the token's role may not call the method) |
//! | `railcontact_quota_refused_total` | `quota` | calls, sessions and connections refused by a server-wide cap or a client's share, by the setting's name: `max_sessions`, `client_max_sessions`, `queue_capacity`, `client_max_admitted`, `max_streams`, `client_max_streams`, `max_connections`, `client_max_connections`, and `auth_failure_burst` (calls of a peer in back-off after failed token checks, not checked) |
//! | `railcontact_connections_open` | | connections open (TLS handshakes under way included) |
//! | `railcontact_streams_open` | | calls open (HTTP/2 streams), against `max_streams` |
//! | `railcontact_connections_timed_out_total` | | connections closed because they sent no call within `connection_first_call_timeout_s` |
//! | `railcontact_connections_failed_before_call_total` | | connections that sent bytes but ended before their first call: with TLS a failed handshake (by reason in `railcontact_tls_handshakes_failed_total`) or a client that spoke no gRPC after it, without TLS a client speaking something other than gRPC (TLS to a plaintext port) |
//! | `railcontact_tls_handshakes_failed_total` | `reason` | TLS handshakes of the gRPC port that failed, each also a (rate-limited) WARN line with the peer and rustls' reason: `not_tls` (plaintext to the TLS port), `client_alert` (the client refused the handshake with an alert, most often because it does not trust the server's certificate or finds it expired), `no_client_cert` and `client_cert_untrusted`, `client_cert_expired` (mTLS: no client certificate, one not signed by `tls_client_ca`, one expired or not valid yet), `incompatible` (no protocol version, cipher suite or ALPN `h2` in common), `timeout` (no handshake within `connection_first_call_timeout_s`, also in `railcontact_connections_timed_out_total`), `closed` (the client closed mid-handshake after sending bytes), `other` |
//! | `railcontact_streams_write_timed_out_total` | | streamed responses (CreepCurve) ended because their client read nothing for `stream_write_timeout_s` |
//!
//! Metrics that the handlers count are fields of [`Metrics`], registered in
//! [`Metrics::default`] (a counter is registered without its `_total`
//! suffix: the encoder appends it). Figures that another part of the server
//! already counts (the solve pool, the kernel cache) are read at each
//! scrape ([`Metrics::render`]). Counting is lock-free (atomics); the label
//! families take a short read lock.

use std::future::Future;
use std::sync::Arc;

use axum::extract::State;
use axum::http::header::CONTENT_TYPE;
use axum::response::IntoResponse;
use axum::routing::get;
use axum::Router;
use prometheus_client::collector::Collector;
use prometheus_client::encoding::{
    prometheus_text, DescriptorEncoder, EncodeLabelSet, EncodeMetric,
};
use prometheus_client::metrics::counter::{ConstCounter, Counter};
use prometheus_client::metrics::family::Family;
use prometheus_client::metrics::gauge::{ConstGauge, Gauge};
use prometheus_client::metrics::histogram::Histogram;
use prometheus_client::registry::Registry;
use tokio::net::TcpListener;

use crate::core::cache::KernelCache;
use crate::problem::case::Model;
use crate::service::memory::SessionBudget;
use crate::service::pool::SolvePool;
use crate::wheelrail::PairCache;

/// Upper bounds of the latency buckets [s].
const BUCKETS_S: [f64; 14] = [
    50e-6, 100e-6, 250e-6, 500e-6, 1e-3, 2.5e-3, 5e-3, 10e-3, 25e-3, 50e-3, 0.1, 0.5, 2.0, 10.0,
];

fn latency_histogram() -> Histogram {
    Histogram::new(BUCKETS_S)
}

/// A histogram per label set, all with the latency buckets.
type Histograms<L> = Family<L, Histogram, fn() -> Histogram>;

#[derive(Clone, Debug, Hash, PartialEq, Eq, EncodeLabelSet)]
struct CallLabels {
    method: &'static str,
    code: String,
}

#[derive(Clone, Debug, Hash, PartialEq, Eq, EncodeLabelSet)]
struct MethodLabels {
    method: &'static str,
}

#[derive(Clone, Debug, Hash, PartialEq, Eq, EncodeLabelSet)]
struct LimitLabels {
    limit: &'static str,
}

#[derive(Clone, Debug, Hash, PartialEq, Eq, EncodeLabelSet)]
struct QuotaLabels {
    quota: &'static str,
}

#[derive(Clone, Debug, Hash, PartialEq, Eq, EncodeLabelSet)]
struct ReasonLabels {
    reason: &'static str,
}

#[derive(Clone, Debug, Hash, PartialEq, Eq, EncodeLabelSet)]
struct SolveLabels {
    model: &'static str,
    outcome: &'static str,
}

/// Registers a clone of each metric (they share their values) under its
/// name and help.
macro_rules! register {
    ($registry:ident, $($name:literal, $help:literal => $metric:expr;)*) => {
        $($registry.register($name, $help, $metric.clone());)*
    };
}

/// The server's metrics.
#[derive(Debug)]
pub struct Metrics {
    registry: Registry,
    requests: Family<CallLabels, Counter>,
    request_duration: Histograms<MethodLabels>,
    solve_duration: Histograms<SolveLabels>,
    sessions_active: Gauge,
    sessions_opened: Counter,
    store_damaged_records: Gauge,
    prepared_pairs: Gauge,
    prepared_pair_bytes: Gauge,
    prepared_pairs_released: Counter,
    registrations_refused: Family<LimitLabels, Counter>,
    auth_refused: Family<ReasonLabels, Counter>,
    sessions_idle_closed: Counter,
    first_message_timeouts: Counter,
    session_bytes: Gauge,
    session_mark_bytes: Gauge,
    session_memory_refused: Counter,
    session_marks_refused: Counter,
    quota_refused: Family<QuotaLabels, Counter>,
    connections_open: Gauge,
    streams_open: Gauge,
    connections_timed_out: Counter,
    connections_failed_before_call: Counter,
    tls_handshakes_failed: Family<ReasonLabels, Counter>,
    streams_write_timed_out: Counter,
}

impl Default for Metrics {
    fn default() -> Self {
        let m = Self {
            registry: Registry::default(),
            requests: Family::default(),
            request_duration: Family::new_with_constructor(latency_histogram),
            solve_duration: Family::new_with_constructor(latency_histogram),
            sessions_active: Gauge::default(),
            sessions_opened: Counter::default(),
            store_damaged_records: Gauge::default(),
            prepared_pairs: Gauge::default(),
            prepared_pair_bytes: Gauge::default(),
            prepared_pairs_released: Counter::default(),
            registrations_refused: Family::default(),
            auth_refused: Family::default(),
            sessions_idle_closed: Counter::default(),
            first_message_timeouts: Counter::default(),
            session_bytes: Gauge::default(),
            session_mark_bytes: Gauge::default(),
            session_memory_refused: Counter::default(),
            session_marks_refused: Counter::default(),
            quota_refused: Family::default(),
            connections_open: Gauge::default(),
            streams_open: Gauge::default(),
            connections_timed_out: Counter::default(),
            connections_failed_before_call: Counter::default(),
            tls_handshakes_failed: Family::default(),
            streams_write_timed_out: Counter::default(),
        };
        let mut r = m.registry;
        // name (a counter's without `_total`), help, metric: one line each.
        register!(r,
            "railcontact_requests", "Finished gRPC calls" => m.requests;
            "railcontact_request_duration_seconds", "Latency of calls [s]" => m.request_duration;
            "railcontact_solve_duration_seconds", "Duration of single solves [s]" => m.solve_duration;
            "railcontact_sessions_active", "Open co-simulation sessions" => m.sessions_active;
            "railcontact_sessions_opened", "Co-simulation sessions opened" => m.sessions_opened;
            "railcontact_store_damaged_records", "Damaged records of the profile pair store, listed as FAILED pairs" => m.store_damaged_records;
            "railcontact_prepared_pairs", "Registered pairs held prepared" => m.prepared_pairs;
            "railcontact_prepared_pair_bytes", "Memory of the registered pairs held prepared, against max_prepared_bytes [bytes]" => m.prepared_pair_bytes;
            "railcontact_prepared_pairs_released", "Prepared pairs let go to stay within max_prepared_bytes" => m.prepared_pairs_released;
            "railcontact_registrations_refused", "Registrations refused by a limit" => m.registrations_refused;
            "railcontact_auth_refused", "Calls refused by the bearer tokens, by reason" => m.auth_refused;
            "railcontact_sessions_idle_closed", "Sessions closed because they idled past session_idle_timeout_s" => m.sessions_idle_closed;
            "railcontact_streams_first_message_timed_out", "Session streams ended because no first message came within stream_first_message_timeout_s" => m.first_message_timeouts;
            "railcontact_session_bytes", "Memory held by all sessions, live state and marks [bytes]" => m.session_bytes;
            "railcontact_session_mark_bytes", "Memory held by the marks of all sessions [bytes]" => m.session_mark_bytes;
            "railcontact_session_memory_refused", "Session opens and steps refused by max_session_bytes or max_sessions_total_bytes" => m.session_memory_refused;
            "railcontact_session_marks_refused", "Marked steps refused by max_session_bytes or max_sessions_total_bytes that would have fitted without their mark" => m.session_marks_refused;
            "railcontact_quota_refused", "Calls, sessions and connections refused by a server-wide cap or a client's share, by the setting's name" => m.quota_refused;
            "railcontact_connections_open", "Connections open" => m.connections_open;
            "railcontact_streams_open", "Calls open (HTTP/2 streams), against max_streams" => m.streams_open;
            "railcontact_connections_timed_out", "Connections closed because they sent no call within connection_first_call_timeout_s" => m.connections_timed_out;
            "railcontact_connections_failed_before_call", "Connections that sent bytes but ended before their first call (a failed TLS handshake among them)" => m.connections_failed_before_call;
            "railcontact_tls_handshakes_failed", "TLS handshakes of the gRPC port that failed, by reason" => m.tls_handshakes_failed;
            "railcontact_streams_write_timed_out", "Streamed responses ended because their client read nothing for stream_write_timeout_s" => m.streams_write_timed_out;
        );
        Self { registry: r, ..m }
    }
}

impl Metrics {
    /// A finished call of `method` that took `seconds`; `error` its code
    /// when it failed.
    pub fn request(&self, method: &'static str, seconds: f64, error: Option<tonic::Code>) {
        let code = format!("{:?}", error.unwrap_or(tonic::Code::Ok));
        self.requests
            .get_or_create(&CallLabels { method, code })
            .inc();
        self.request_duration
            .get_or_create(&MethodLabels { method })
            .observe(seconds);
    }

    /// One solve of `model` that took `seconds`.
    pub fn solved(&self, model: Model, seconds: f64, ok: bool) {
        self.solved_as(model.name(), seconds, ok);
    }

    /// One solve of the model named `model` (wheel/rail models:
    /// `wheelrail_exact`, ...) that took `seconds`.
    pub fn solved_as(&self, model: &'static str, seconds: f64, ok: bool) {
        let outcome = if ok { "ok" } else { "error" };
        self.solve_duration
            .get_or_create(&SolveLabels { model, outcome })
            .observe(seconds);
    }

    /// A session was opened.
    pub fn session_opened(&self) {
        self.sessions_active.inc();
        self.sessions_opened.inc();
    }

    /// `n` damaged records of the store are listed as FAILED pairs.
    pub fn store_damaged_records(&self, n: u64) {
        self.store_damaged_records.set(n as i64);
    }

    /// The registry holds `pairs` prepared pairs of `bytes` in all, having
    /// let go of `released` more.
    pub fn prepared_pairs(&self, pairs: usize, bytes: usize, released: u64) {
        self.prepared_pairs.set(pairs as i64);
        self.prepared_pair_bytes.set(bytes as i64);
        self.prepared_pairs_released.inc_by(released);
    }

    /// A registration was refused by the limit named `limit`.
    pub fn registration_refused(&self, limit: &'static str) {
        self.registrations_refused
            .get_or_create(&LimitLabels { limit })
            .inc();
    }

    /// A call refused by the bearer tokens, for `reason` (`missing`,
    /// `unknown`, `forbidden`).
    pub fn auth_refused(&self, reason: &'static str) {
        self.auth_refused
            .get_or_create(&ReasonLabels { reason })
            .inc();
    }

    /// A call, session or connection refused by the limit of the setting
    /// `quota` (`client_max_sessions`, `max_streams`, ...).
    pub fn quota_refused(&self, quota: &'static str) {
        self.quota_refused
            .get_or_create(&QuotaLabels { quota })
            .inc();
    }

    /// Connections open now.
    pub fn connections_open(&self, n: usize) {
        self.connections_open.set(n as i64);
    }

    /// Calls open now.
    pub fn streams_open(&self, n: usize) {
        self.streams_open.set(n as i64);
    }

    /// A connection closed for sending no call in time.
    pub fn connection_timed_out(&self) {
        self.connections_timed_out.inc();
    }

    /// A connection that sent bytes ended before its first call.
    pub fn connection_failed_before_call(&self) {
        self.connections_failed_before_call.inc();
    }

    /// A TLS handshake failed, for `reason` (a label of
    /// [`crate::service::tls::HandshakeFailure`]).
    pub fn tls_handshake_failed(&self, reason: &'static str) {
        self.tls_handshakes_failed
            .get_or_create(&ReasonLabels { reason })
            .inc();
    }

    /// A streamed response ended because its client read nothing.
    pub fn stream_write_timed_out(&self) {
        self.streams_write_timed_out.inc();
    }

    /// A session was closed because it idled.
    pub fn session_idle_closed(&self) {
        self.sessions_idle_closed.inc();
    }

    /// A session stream sent no first message in time.
    pub fn first_message_timed_out(&self) {
        self.first_message_timeouts.inc();
    }

    /// The sessions' memory now: bytes held (all, and by marks), opens,
    /// steps and marks refused so far.
    pub fn session_memory(&self, budget: &SessionBudget) {
        use std::sync::atomic::Ordering::Relaxed;
        self.session_bytes.set(budget.total_bytes() as i64);
        self.session_mark_bytes.set(budget.mark_bytes() as i64);
        self.session_memory_refused
            .inner()
            .store(budget.refused(), Relaxed);
        self.session_marks_refused
            .inner()
            .store(budget.refused_marks(), Relaxed);
    }

    /// A session ended.
    pub fn session_closed(&self) {
        use std::sync::atomic::Ordering::Relaxed;
        let _ = self
            .sessions_active
            .inner()
            .fetch_update(Relaxed, Relaxed, |n| (n > 0).then(|| n - 1));
    }

    /// The exposition text (Prometheus text format 0.0.4), with the pool's
    /// and the kernel cache's figures.
    pub fn render(&self, pool: &SolvePool, cache: &KernelCache) -> String {
        let f = cache.figures();
        let pairs = PairCache::global().stats();
        let mut scrape = Registry::default();
        scrape.register_collector(Box::new(Figures(vec![
            Figure::gauge(
                "railcontact_solve_queue_admitted",
                "Requests admitted to the solve pool, running plus waiting.",
                pool.admitted() as u64,
            ),
            Figure::counter(
                "railcontact_solves_cancelled",
                "Solves told to stop because their request ended while they ran.",
                pool.cancelled(),
            ),
            Figure::counter(
                "railcontact_solves_timed_out",
                "Solves stopped at the server's limit max_solve_time_s.",
                pool.timed_out(),
            ),
            Figure::counter(
                "railcontact_kernel_cache_hits",
                "Influence-kernel cache hits.",
                f.hits,
            ),
            Figure::counter(
                "railcontact_kernel_cache_misses",
                "Influence-kernel cache misses.",
                f.misses,
            ),
            Figure::counter(
                "railcontact_kernel_cache_evictions",
                "Kernel sets evicted as least recently used.",
                f.evictions,
            ),
            Figure::gauge(
                "railcontact_kernel_cache_entries",
                "Kernel sets held.",
                f.entries as u64,
            ),
            Figure::gauge(
                "railcontact_kernel_cache_bytes",
                "Memory of the kernel sets held [bytes].",
                f.bytes as u64,
            ),
            Figure::gauge(
                "railcontact_kernel_cache_max_bytes",
                "Memory cap of the kernel cache [bytes].",
                f.max_bytes as u64,
            ),
            Figure::gauge(
                "railcontact_library_pairs_live",
                "Placed profile pairs held by ContactLibrary sessions, shared by content.",
                pairs.live as u64,
            ),
            Figure::counter(
                "railcontact_library_pair_hits",
                "ContactLibrary pair requests answered by a pair already placed.",
                pairs.hits,
            ),
            Figure::counter(
                "railcontact_library_pair_builds",
                "Profile pairs placed for ContactLibrary sessions.",
                pairs.builds,
            ),
        ])));
        let mut text = String::new();
        // Writing into a String cannot fail; an encoder error would only
        // shorten the page.
        let _ = prometheus_text::encode(&mut text, &self.registry);
        let _ = prometheus_text::encode(&mut text, &scrape);
        text
    }
}

/// One figure read at scrape time; its help ends in a full stop, as the
/// registry's (which appends one).
#[derive(Debug)]
struct Figure {
    name: &'static str,
    help: &'static str,
    counter: bool,
    value: u64,
}

impl Figure {
    /// A counter, named without its `_total` suffix.
    fn counter(name: &'static str, help: &'static str, value: u64) -> Self {
        Self {
            name,
            help,
            counter: true,
            value,
        }
    }

    fn gauge(name: &'static str, help: &'static str, value: u64) -> Self {
        Self {
            name,
            help,
            counter: false,
            value,
        }
    }
}

#[derive(Debug)]
struct Figures(Vec<Figure>);

impl Collector for Figures {
    fn encode(&self, mut encoder: DescriptorEncoder) -> Result<(), std::fmt::Error> {
        for f in &self.0 {
            if f.counter {
                let m = ConstCounter::new(f.value);
                m.encode(encoder.encode_descriptor(f.name, f.help, None, m.metric_type())?)?;
            } else {
                let m = ConstGauge::new(f.value);
                m.encode(encoder.encode_descriptor(f.name, f.help, None, m.metric_type())?)?;
            }
        }
        Ok(())
    }
}

/// What the metrics page needs.
#[derive(Clone)]
struct Page {
    metrics: Arc<Metrics>,
    pool: SolvePool,
}

async fn metrics_page(State(page): State<Page>) -> impl IntoResponse {
    (
        [(CONTENT_TYPE, prometheus_text::CONTENT_TYPE)],
        page.metrics.render(&page.pool, KernelCache::global()),
    )
}

/// Serves `GET /metrics` on `listener` (404 for any other path) until
/// `shutdown` completes; then stops accepting and lets the requests being
/// answered finish.
pub async fn serve_metrics(
    listener: TcpListener,
    metrics: Arc<Metrics>,
    pool: SolvePool,
    shutdown: impl Future<Output = ()> + Send + 'static,
) -> std::io::Result<()> {
    let app = Router::new()
        .route("/metrics", get(metrics_page))
        .with_state(Page { metrics, pool });
    axum::serve(listener, app)
        .with_graceful_shutdown(shutdown)
        .await
}

#[cfg(test)]
mod tests {
    use super::*;
    use tokio::io::{AsyncReadExt, AsyncWriteExt};

    /// One HTTP/1.1 request on a fresh connection; the whole response.
    async fn get(addr: std::net::SocketAddr, path: &str) -> String {
        let mut s = tokio::net::TcpStream::connect(addr).await.unwrap();
        let request = format!("GET {path} HTTP/1.1\r\nhost: x\r\nconnection: close\r\n\r\n");
        s.write_all(request.as_bytes()).await.unwrap();
        let mut page = String::new();
        s.read_to_string(&mut page).await.unwrap();
        page
    }

    #[test]
    fn the_page_has_every_metric_with_its_type_and_labels() {
        let m = Metrics::default();
        m.request("SolvePatch", 3e-4, None);
        m.request("SolvePatch", 2e-3, Some(tonic::Code::ResourceExhausted));
        m.solved_as("wheelrail_exact", 7e-3, true);
        m.session_opened();
        m.session_opened();
        m.session_closed();
        let page = m.render(&SolvePool::new(1, 4), KernelCache::global());
        for line in [
            "# TYPE railcontact_requests_total counter",
            "railcontact_requests_total{method=\"SolvePatch\",code=\"Ok\"} 1",
            "railcontact_requests_total{method=\"SolvePatch\",code=\"ResourceExhausted\"} 1",
            "# TYPE railcontact_request_duration_seconds histogram",
            "railcontact_request_duration_seconds_count{method=\"SolvePatch\"} 2",
            "railcontact_request_duration_seconds_bucket{method=\"SolvePatch\",le=\"0.0005\"} 1",
            "railcontact_request_duration_seconds_bucket{method=\"SolvePatch\",le=\"0.0025\"} 2",
            "railcontact_solve_duration_seconds_count{model=\"wheelrail_exact\",outcome=\"ok\"} 1",
            "# TYPE railcontact_sessions_active gauge",
            "railcontact_sessions_active 1",
            "railcontact_sessions_opened_total 2",
            "railcontact_solve_queue_admitted 0",
            "# TYPE railcontact_solves_cancelled_total counter",
            "railcontact_solves_cancelled_total 0",
            "# TYPE railcontact_kernel_cache_hits_total counter",
            "# TYPE railcontact_kernel_cache_misses_total counter",
            "# TYPE railcontact_kernel_cache_evictions_total counter",
            "# TYPE railcontact_kernel_cache_entries gauge",
            "# TYPE railcontact_kernel_cache_bytes gauge",
            "# TYPE railcontact_kernel_cache_max_bytes gauge",
            "# HELP railcontact_kernel_cache_max_bytes Memory cap of the kernel cache [bytes].",
            "# HELP railcontact_requests_total Finished gRPC calls.",
        ] {
            assert!(page.lines().any(|l| l == line), "no {line:?} in\n{page}");
        }
    }

    #[tokio::test(flavor = "current_thread")]
    async fn metrics_are_served_over_http_until_shutdown() {
        let listener = TcpListener::bind("127.0.0.1:0").await.unwrap();
        let addr = listener.local_addr().unwrap();
        let metrics = Arc::new(Metrics::default());
        metrics.session_opened();
        let (stop, stopped) = tokio::sync::oneshot::channel::<()>();
        let task = tokio::spawn(serve_metrics(
            listener,
            metrics,
            SolvePool::new(1, 4),
            async {
                let _ = stopped.await;
            },
        ));
        let page = get(addr, "/metrics").await;
        assert!(page.starts_with("HTTP/1.1 200 OK\r\n"), "{page}");
        let head = page.to_ascii_lowercase();
        assert!(
            head.contains("content-type: text/plain; version=0.0.4; charset=utf-8\r\n"),
            "{page}"
        );
        assert!(page.contains("\nrailcontact_sessions_active 1\n"), "{page}");
        let other = get(addr, "/").await;
        assert!(other.starts_with("HTTP/1.1 404 Not Found\r\n"), "{other}");
        stop.send(()).unwrap();
        task.await.unwrap().unwrap();
        assert!(
            tokio::net::TcpStream::connect(addr).await.is_err(),
            "still listening after shutdown"
        );
    }
}
