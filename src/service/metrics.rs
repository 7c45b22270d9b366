//! Prometheus metrics of the server, in the text exposition format, served
//! on their own port (`metrics_listen`) by a minimal HTTP responder:
//!
//! | metric | labels | what |
//! |---|---|---|
//! | `railcontact_requests_total` | `method`, `code` | finished calls by gRPC status |
//! | `railcontact_request_duration_seconds` | `method` | latency histogram of unary calls and stream set-up |
//! | `railcontact_solve_duration_seconds` | `model`, `outcome` | histogram of each solve (batch items, curve points, session steps) |
//! | `railcontact_sessions_active` | | open co-simulation sessions |
//! | `railcontact_sessions_opened_total` | | sessions opened |
//! | `railcontact_sessions_idle_closed_total` | | session streams closed because no message came (or no response was read) for `session_idle_timeout_s` |
//! | `railcontact_session_mark_bytes` | | memory held by the marks of all open sessions (`max_sessions_total_bytes`) |
//! | `railcontact_session_marks_refused_total` | | marked steps refused because the mark went beyond `max_session_bytes` or `max_sessions_total_bytes` |
//! | `railcontact_solve_queue_admitted` | | requests admitted to the solve pool |
//! | `railcontact_solves_cancelled_total` | | solves told to stop because their request ended while they ran (deadline, client gone, shutdown; see `core::cancel`) |
//! | `railcontact_kernel_cache_hits_total`, `..._misses_total`, `..._evictions_total` | | influence-kernel cache look-ups and least-recently-used evictions |
//! | `railcontact_kernel_cache_entries`, `..._bytes`, `..._max_bytes` | | kernel sets held, their memory and the cap |
//!
//! The counters sit behind one short-held mutex (never held across a solve).

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::sync::Mutex;

use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpListener;

use crate::core::cache::KernelCache;
use crate::problem::case::Model;
use crate::service::pool::SolvePool;

/// Upper bounds of the latency buckets [s].
const BUCKETS_S: [f64; 14] = [
    50e-6, 100e-6, 250e-6, 500e-6, 1e-3, 2.5e-3, 5e-3, 10e-3, 25e-3, 50e-3, 0.1, 0.5, 2.0, 10.0,
];

#[derive(Default, Clone)]
struct Histogram {
    counts: [u64; BUCKETS_S.len()],
    count: u64,
    sum_s: f64,
}

impl Histogram {
    fn observe(&mut self, v: f64) {
        for (c, b) in self.counts.iter_mut().zip(BUCKETS_S) {
            if v <= b {
                *c += 1;
            }
        }
        self.count += 1;
        self.sum_s += v;
    }

    fn render(&self, out: &mut String, name: &str, labels: &str) {
        let sep = if labels.is_empty() { "" } else { "," };
        for (c, b) in self.counts.iter().zip(BUCKETS_S) {
            let _ = writeln!(out, "{name}_bucket{{{labels}{sep}le=\"{b}\"}} {c}");
        }
        let _ = writeln!(
            out,
            "{name}_bucket{{{labels}{sep}le=\"+Inf\"}} {}",
            self.count
        );
        let _ = writeln!(out, "{name}_sum{{{labels}}} {}", self.sum_s);
        let _ = writeln!(out, "{name}_count{{{labels}}} {}", self.count);
    }
}

#[derive(Default)]
struct Counters {
    requests: BTreeMap<(&'static str, String), u64>,
    latency: BTreeMap<&'static str, Histogram>,
    solves: BTreeMap<(&'static str, &'static str), Histogram>,
    sessions_active: u64,
    sessions_opened: u64,
    sessions_idle_closed: u64,
    session_mark_bytes: u64,
    session_marks_refused: u64,
}

/// The server's metrics.
#[derive(Default)]
pub struct Metrics {
    counters: Mutex<Counters>,
}

impl Metrics {
    fn with<R>(&self, f: impl FnOnce(&mut Counters) -> R) -> R {
        f(&mut self.counters.lock().unwrap_or_else(|e| e.into_inner()))
    }

    /// A finished call of `method` that took `seconds`; `error` its code
    /// when it failed.
    pub fn request(&self, method: &'static str, seconds: f64, error: Option<tonic::Code>) {
        let code = format!("{:?}", error.unwrap_or(tonic::Code::Ok));
        self.with(|c| {
            *c.requests.entry((method, code)).or_default() += 1;
            c.latency.entry(method).or_default().observe(seconds);
        });
    }

    /// One solve of `model` that took `seconds`.
    pub fn solved(&self, model: Model, seconds: f64, ok: bool) {
        self.solved_as(model.name(), seconds, ok);
    }

    /// One solve of the model named `model` (wheel/rail models:
    /// `wheelrail_exact`, ...) that took `seconds`.
    pub fn solved_as(&self, model: &'static str, seconds: f64, ok: bool) {
        let outcome = if ok { "ok" } else { "error" };
        self.with(|c| {
            c.solves
                .entry((model, outcome))
                .or_default()
                .observe(seconds)
        });
    }

    /// A session was opened.
    pub fn session_opened(&self) {
        self.with(|c| {
            c.sessions_active += 1;
            c.sessions_opened += 1;
        });
    }

    /// A session ended.
    pub fn session_closed(&self) {
        self.with(|c| c.sessions_active = c.sessions_active.saturating_sub(1));
    }

    /// A session was closed because it idled.
    pub fn session_idle_closed(&self) {
        self.with(|c| c.sessions_idle_closed += 1);
    }

    /// The session marks now: `bytes` held, `refused` marks so far.
    pub fn session_marks(&self, bytes: usize, refused: u64) {
        self.with(|c| {
            c.session_mark_bytes = bytes as u64;
            c.session_marks_refused = refused;
        });
    }

    /// The exposition text, with the pool's and the kernel cache's figures.
    pub fn render(&self, pool: &SolvePool, cache: &KernelCache) -> String {
        let mut o = String::new();
        self.with(|c| {
            o.push_str("# HELP railcontact_requests_total Finished gRPC calls.\n# TYPE railcontact_requests_total counter\n");
            for ((m, code), n) in &c.requests {
                let _ = writeln!(o, "railcontact_requests_total{{method=\"{m}\",code=\"{code}\"}} {n}");
            }
            o.push_str("# HELP railcontact_request_duration_seconds Latency of calls [s].\n# TYPE railcontact_request_duration_seconds histogram\n");
            for (m, h) in &c.latency {
                h.render(&mut o, "railcontact_request_duration_seconds", &format!("method=\"{m}\""));
            }
            o.push_str("# HELP railcontact_solve_duration_seconds Duration of single solves [s].\n# TYPE railcontact_solve_duration_seconds histogram\n");
            for ((model, outcome), h) in &c.solves {
                h.render(
                    &mut o,
                    "railcontact_solve_duration_seconds",
                    &format!("model=\"{model}\",outcome=\"{outcome}\""),
                );
            }
            let _ = writeln!(o, "# TYPE railcontact_sessions_active gauge\nrailcontact_sessions_active {}", c.sessions_active);
            let _ = writeln!(o, "# TYPE railcontact_sessions_opened_total counter\nrailcontact_sessions_opened_total {}", c.sessions_opened);
            let _ = writeln!(o, "# TYPE railcontact_sessions_idle_closed_total counter\nrailcontact_sessions_idle_closed_total {}", c.sessions_idle_closed);
            let _ = writeln!(o, "# TYPE railcontact_session_mark_bytes gauge\nrailcontact_session_mark_bytes {}", c.session_mark_bytes);
            let _ = writeln!(o, "# TYPE railcontact_session_marks_refused_total counter\nrailcontact_session_marks_refused_total {}", c.session_marks_refused);
        });
        let f = cache.figures();
        let _ = writeln!(
            o,
            "# TYPE railcontact_solve_queue_admitted gauge\nrailcontact_solve_queue_admitted {}",
            pool.admitted()
        );
        let _ = writeln!(
            o,
            "# TYPE railcontact_solves_cancelled_total counter\nrailcontact_solves_cancelled_total {}",
            pool.cancelled()
        );
        for (name, kind, value) in [
            ("hits_total", "counter", f.hits),
            ("misses_total", "counter", f.misses),
            ("evictions_total", "counter", f.evictions),
            ("entries", "gauge", f.entries as u64),
            ("bytes", "gauge", f.bytes as u64),
            ("max_bytes", "gauge", f.max_bytes as u64),
        ] {
            let _ = writeln!(
                o,
                "# TYPE railcontact_kernel_cache_{name} {kind}\nrailcontact_kernel_cache_{name} {value}"
            );
        }
        o
    }
}

/// Serves `GET /metrics` on `listener` until the task is dropped.
pub async fn serve_metrics(
    listener: TcpListener,
    metrics: std::sync::Arc<Metrics>,
    pool: SolvePool,
) {
    loop {
        let Ok((mut stream, _)) = listener.accept().await else {
            continue;
        };
        let metrics = metrics.clone();
        let pool = pool.clone();
        tokio::spawn(async move {
            let mut buf = vec![0u8; 4096];
            let n = stream.read(&mut buf).await.unwrap_or(0);
            let head = String::from_utf8_lossy(&buf[..n]);
            let response = if head.starts_with("GET /metrics") {
                let body = metrics.render(&pool, KernelCache::global());
                format!(
                    "HTTP/1.1 200 OK\r\ncontent-type: text/plain; version=0.0.4\r\ncontent-length: {}\r\nconnection: close\r\n\r\n{body}",
                    body.len()
                )
            } else {
                "HTTP/1.1 404 Not Found\r\ncontent-length: 0\r\nconnection: close\r\n\r\n"
                    .to_string()
            };
            let _ = stream.write_all(response.as_bytes()).await;
        });
    }
}
