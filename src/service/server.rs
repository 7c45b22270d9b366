//! Starting, running and stopping the server: the gRPC service with health
//! checking and reflection, and the optional metrics port.
//!
//! Shutdown is graceful: on SIGTERM or Ctrl-C (or [`RunningServer::shutdown`])
//! the health service reports NOT_SERVING, the listener stops accepting,
//! in-flight calls and open sessions get `shutdown_grace_s` to finish, and
//! whatever is left is then dropped; then the metrics endpoint stops (the
//! scrapes being answered finish) and the store is closed.
//!
//! At start the store of profile pairs is opened (`data_dir`), its pairs
//! restored (prepared on first use), and the built-in pair
//! `mbench_s1002_uic60` registered and prepared; its contact table is built
//! in the background once the server listens.

use std::net::SocketAddr;
use std::sync::Arc;
use std::time::Duration;

use tokio::net::TcpListener;
use tokio::sync::oneshot;
use tokio::task::JoinHandle;
use tonic::codec::CompressionEncoding;

use crate::service::auth::{AuthBackoff, AuthLayer, Tokens};
use crate::service::config::{LogFormat, ServeConfig};
use crate::service::connections::Incoming;
use crate::service::convert::CaseLimits;
use crate::service::handlers::{ContactHandlers, RequestLimits};
use crate::service::metrics::{serve_metrics, Metrics};
use crate::service::pairs::{self, PairRegistry, RegistryLimits};
use crate::service::pb;
use crate::service::pb::contact_service_server::ContactServiceServer;
use crate::service::pool::SolvePool;
use crate::service::quota::{client_share, Quota, Resource, TrustedProxies};
use crate::service::status;
use crate::service::store::PairStore;
use crate::service::streams::StreamsLayer;
use crate::service::tls;

/// A server running on the current tokio runtime.
pub struct RunningServer {
    /// The gRPC address it listens on (the real port when 0 was asked).
    pub addr: SocketAddr,
    /// The metrics address, if any.
    pub metrics_addr: Option<SocketAddr>,
    stop: oneshot::Sender<()>,
    task: JoinHandle<Result<(), tonic::transport::Error>>,
    metrics_task: Option<(oneshot::Sender<()>, JoinHandle<std::io::Result<()>>)>,
    /// The daily check of the TLS certificates' validity.
    validity_task: Option<JoinHandle<()>>,
    health: tonic_health::server::HealthReporter,
    grace: Duration,
    pairs: Arc<PairRegistry>,
}

/// Seconds since 1970 now (0 on a clock before it).
fn unix_now() -> i64 {
    std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs() as i64)
}

/// Registers and prepares the built-in pair.
async fn register_builtin(pairs: &Arc<PairRegistry>, pool: &SolvePool) -> std::io::Result<()> {
    let t0 = std::time::Instant::now();
    let spec =
        pairs::canonicalize(&pairs::builtin_registration()).map_err(std::io::Error::other)?;
    let (entry, _) = pairs.begin(spec).map_err(std::io::Error::other)?;
    let admission = pool.admit(None).map_err(std::io::Error::other)?;
    let prepared = pairs
        .prepared(&entry, &admission, Arc::new(|_, _| {}))
        .await
        .map_err(std::io::Error::other)?;
    tracing::info!(pair = pairs::BUILTIN_PAIR, pair_id = %entry.spec.id, seconds = t0.elapsed().as_secs_f64(), "built-in profile pair ready");
    // Its contact table (about a second) is built in the background, so
    // that the server listens at once; a hertz_fastsim_table request that
    // comes first waits for the same build.
    let background = pool.internal();
    let pairs = pairs.clone();
    tokio::spawn(async move {
        if let Err(e) = pairs.table(&prepared, &background).await {
            tracing::warn!(error = %e, "contact table of the built-in pair not built");
        }
    });
    Ok(())
}

/// Binds `addr`; an error names the address, the setting that chose it
/// (`setting`) and, for a port in use, what to do.
async fn bind(addr: std::net::SocketAddr, setting: &str) -> std::io::Result<TcpListener> {
    TcpListener::bind(addr).await.map_err(|e| {
        let hint = match e.kind() {
            std::io::ErrorKind::AddrInUse => format!(
                ": another process listens there (another railcontact server?); stop it, or \
                 choose another address with {setting}"
            ),
            std::io::ErrorKind::AddrNotAvailable => {
                format!(": not an address of this host; choose another with {setting}")
            }
            std::io::ErrorKind::PermissionDenied => {
                format!(": ports below 1024 need privileges; choose another with {setting}")
            }
            _ => String::new(),
        };
        std::io::Error::new(e.kind(), format!("cannot listen on {addr}: {e}{hint}"))
    })
}

/// Binds the ports and starts serving `config` on the current runtime.
/// Settings it refuses (a listen address beyond loopback without TLS and
/// tokens, a metrics address beyond loopback without `metrics_insecure`,
/// unreadable or invalid TLS or tokens files) are errors of kind
/// `InvalidInput`, before any port is bound; a port it cannot bind is an
/// error naming it (and what to do when it is in use), before the store is
/// opened.
pub async fn start(config: &ServeConfig) -> std::io::Result<RunningServer> {
    let invalid = |e: String| std::io::Error::new(std::io::ErrorKind::InvalidInput, e);
    if let Some(warning) = config.check_exposure().map_err(invalid)? {
        tracing::warn!("{warning}");
    }
    let tls = tls::server_tls(config).map_err(|e| invalid(e.to_string()))?;
    let validity = tls::Validity::of(config);
    let with_tls = tls.is_some();
    for w in validity.warnings(unix_now()) {
        tracing::warn!("{w}");
    }
    let tokens = match &config.auth_tokens_file {
        Some(path) => Some(Tokens::load(path).map_err(|e| invalid(e.to_string()))?),
        None => None,
    };
    if let Some(warning) = config.check_open_files() {
        tracing::warn!("{warning}");
    }
    let workers = config.worker_count();
    let metrics = Arc::new(Metrics::default());
    let pool = SolvePool::with_client_share(
        workers,
        config.queue_count(),
        config.client_max_admitted,
        metrics.clone(),
    )
    .with_max_solve_time(Duration::from_secs_f64(config.max_solve_time_s));
    crate::core::cache::KernelCache::global().set_max_bytes(config.kernel_cache_max_bytes);
    let limits = RequestLimits {
        case: CaseLimits {
            max_grid_elements: config.max_grid_elements,
        },
        max_batch_items: config.max_batch_items,
        max_curve_points: config.max_curve_points,
        max_sessions: config.max_sessions,
        client_max_sessions: config.client_max_sessions,
        max_message_bytes: config.max_message_bytes,
        max_session_bytes: config.max_session_bytes,
        max_sessions_total_bytes: config.max_sessions_total_bytes,
        session_idle_timeout: Duration::from_secs_f64(config.session_idle_timeout_s),
        first_message_timeout: Duration::from_secs_f64(config.stream_first_message_timeout_s),
        stream_write_timeout: Duration::from_secs_f64(config.stream_write_timeout_s),
    };
    // Ports first: a port in use is said at once, naming it, before the
    // store is opened and the built-in pair prepared.
    let listener = bind(config.listen, "--listen / RAILCONTACT_LISTEN").await?;
    let metrics_listener = match config.metrics_listen {
        Some(a) => Some(bind(a, "--metrics-listen / RAILCONTACT_METRICS_LISTEN").await?),
        None => None,
    };
    let store = match config.store_dir() {
        Some(dir) => {
            let s = PairStore::open(dir).map_err(std::io::Error::other)?;
            tracing::info!(path = %s.path().display(), "profile pair store opened");
            Some(s)
        }
        None => {
            tracing::info!("no data_dir: profile pairs are kept in memory only");
            None
        }
    };
    let pairs = Arc::new(PairRegistry::open(
        store,
        RegistryLimits::of(config),
        metrics.clone(),
    )?);
    register_builtin(&pairs, &pool).await?;
    let handlers = ContactHandlers::new(pool.clone(), limits, metrics.clone(), pairs.clone());
    let (health, health_service) = tonic_health::server::health_reporter();
    health
        .set_serving::<ContactServiceServer<ContactHandlers>>()
        .await;
    let reflection = |b: tonic_reflection::server::Builder<'static>| {
        b.register_encoded_file_descriptor_set(pb::FILE_DESCRIPTOR_SET)
            .register_encoded_file_descriptor_set(tonic_health::pb::FILE_DESCRIPTOR_SET)
    };
    let (reflection_v1, reflection_v1alpha) = if config.reflection {
        (
            Some(
                reflection(tonic_reflection::server::Builder::configure())
                    .build_v1()
                    .map_err(std::io::Error::other)?,
            ),
            Some(
                reflection(tonic_reflection::server::Builder::configure())
                    .build_v1alpha()
                    .map_err(std::io::Error::other)?,
            ),
        )
    } else {
        (None, None)
    };
    // gzip: requests may come compressed, and answers go compressed to a
    // client that says it accepts gzip (grpc-accept-encoding); others get
    // them as they are.
    let service = ContactServiceServer::new(handlers)
        .max_decoding_message_size(config.max_message_bytes)
        .max_encoding_message_size(config.max_message_bytes)
        .accept_compressed(CompressionEncoding::Gzip)
        .send_compressed(CompressionEncoding::Gzip);

    let security = format!(
        "tls: {}, client certificates: {}, tokens: {}, reflection: {}",
        if tls.is_some() { "on" } else { "off" },
        if config.tls_client_ca.is_some() {
            "required"
        } else {
            "not asked"
        },
        tokens.as_ref().map_or(0, Tokens::len),
        config.reflection
    );
    let proxies = TrustedProxies::new(&config.trusted_proxies);
    let auth = AuthLayer::new(
        tokens,
        AuthBackoff::new(config.auth_failure_burst, config.auth_failure_rate_per_s),
        proxies.clone(),
        metrics.clone(),
    );
    let streams = StreamsLayer::new(Quota::new(
        Resource::Streams,
        Some(config.max_streams),
        client_share(config.client_max_streams, config.max_streams),
        metrics.clone(),
    ));
    let connections = Quota::new(
        Resource::Connections,
        Some(config.max_connections),
        client_share(config.client_max_connections, config.max_connections),
        metrics.clone(),
    );
    let mut shares = format!(
        "per client: {} sessions, {} admitted, {} calls, {} connections; in all: {} calls, {} \
         connections",
        client_share(config.client_max_sessions, config.max_sessions),
        client_share(config.client_max_admitted, config.queue_count()),
        client_share(config.client_max_streams, config.max_streams),
        client_share(config.client_max_connections, config.max_connections),
        config.max_streams,
        config.max_connections,
    );
    if !config.trusted_proxies.is_empty() {
        let listed: Vec<String> = config
            .trusted_proxies
            .iter()
            .map(|a| a.to_string())
            .collect();
        shares.push_str(&format!("; trusted proxies: {}", listed.join(", ")));
    }
    // TLS, if on, is the listener's (service::connections): tonic serves
    // the streams its handshakes give.
    let builder = tonic::transport::Server::builder();

    let addr = listener.local_addr()?;
    let (metrics_addr, metrics_task) = match metrics_listener {
        Some(l) => {
            let bound = l.local_addr()?;
            let (stop, stopped) = oneshot::channel::<()>();
            let task = tokio::spawn(serve_metrics(l, metrics.clone(), pool, async {
                let _ = stopped.await;
            }));
            (Some(bound), Some((stop, task)))
        }
        None => (None, None),
    };
    let incoming = Incoming::new(
        listener,
        connections,
        proxies,
        Duration::from_secs_f64(config.connection_first_call_timeout_s),
        metrics,
        tls,
    );
    let (stop, stopped) = oneshot::channel::<()>();
    // The certificates' validity, again every day while the server runs.
    let validity_task = with_tls.then(|| {
        tokio::spawn(async move {
            let day = Duration::from_secs(86_400);
            let mut every_day = tokio::time::interval_at(tokio::time::Instant::now() + day, day);
            loop {
                every_day.tick().await;
                for w in validity.warnings(unix_now()) {
                    tracing::warn!("{w}");
                }
            }
        })
    });
    let task = tokio::spawn(
        builder
            // Every call passes the token check first (which says who the
            // client is), then the count of open calls.
            .layer(auth)
            .layer(streams)
            .layer(tower::util::MapResponseLayer::new(
                oversize_request_is_resource_exhausted,
            ))
            .http2_keepalive_interval(
                (config.http2_keepalive_interval_s > 0.0)
                    .then(|| Duration::from_secs_f64(config.http2_keepalive_interval_s)),
            )
            .http2_keepalive_timeout(Some(Duration::from_secs_f64(
                config.http2_keepalive_timeout_s,
            )))
            .max_concurrent_streams(config.max_streams_per_connection)
            .trace_fn(|req| {
                tracing::info_span!("grpc", path = %crate::service::escaped(req.uri().path()))
            })
            .add_service(health_service)
            .add_optional_service(reflection_v1)
            .add_optional_service(reflection_v1alpha)
            .add_service(service)
            // Counted connections with TCP_NODELAY, TLS after its handshake
            // (service::connections).
            .serve_with_incoming_shutdown(incoming, async {
                let _ = stopped.await;
            }),
    );
    let store = match config.store_dir() {
        Some(dir) => dir
            .join(crate::service::store::FILE_NAME)
            .display()
            .to_string(),
        None => "memory only".to_string(),
    };
    let metrics_at = metrics_addr.map_or_else(|| "off".to_string(), |a| a.to_string());
    tracing::info!(%addr, metrics = %metrics_at, workers, queue = config.queue_count(), %store, %security, %shares, "railcontact serving");
    Ok(RunningServer {
        addr,
        metrics_addr,
        stop,
        task,
        metrics_task,
        validity_task,
        health,
        grace: Duration::from_secs_f64(config.shutdown_grace_s),
        pairs,
    })
}

impl RunningServer {
    /// Stops gracefully: NOT_SERVING, no new connections, in-flight work
    /// finishes within the grace period.
    pub async fn shutdown(self) {
        self.shutdown_or(std::future::pending()).await
    }

    /// [`RunningServer::shutdown`], cut short when `now` completes first
    /// (a second Ctrl-C): unfinished calls and sessions are dropped at
    /// once.
    pub async fn shutdown_or(self, now: impl std::future::Future<Output = ()>) {
        self.health
            .set_not_serving::<ContactServiceServer<ContactHandlers>>()
            .await;
        let _ = self.stop.send(());
        if let Some(t) = &self.validity_task {
            t.abort();
        }
        let mut task = self.task;
        tokio::select! {
            done = tokio::time::timeout(self.grace, &mut task) => match done {
                Ok(Ok(Ok(()))) => tracing::info!("stopped"),
                Ok(Ok(Err(e))) => tracing::warn!(error = %e, "server error while stopping"),
                Ok(Err(e)) => tracing::warn!(error = %e, "server task failed"),
                Err(_) => {
                    tracing::warn!(
                        grace_s = self.grace.as_secs_f64(),
                        "grace period over: dropping unfinished calls"
                    );
                    task.abort();
                }
            },
            _ = now => {
                tracing::warn!("stopping now: unfinished calls and sessions dropped");
                task.abort();
            }
        }
        if let Some((stop, mut task)) = self.metrics_task {
            let _ = stop.send(());
            // A scrape takes milliseconds; idle keep-alive connections
            // close at once.
            match tokio::time::timeout(Duration::from_secs(2), &mut task).await {
                Ok(Ok(Ok(()))) => {}
                Ok(Ok(Err(e))) => {
                    tracing::warn!(error = %e, "metrics endpoint error while stopping")
                }
                Ok(Err(e)) => tracing::warn!(error = %e, "metrics task failed"),
                Err(_) => task.abort(),
            }
        }
        self.pairs.close_store();
    }
}

/// tonic refuses a request message larger than `max_message_bytes` with
/// OUT_OF_RANGE before any handler sees it; such a refusal of a unary call
/// is a trailers-only response, its status in the headers, which this
/// rewrites to RESOURCE_EXHAUSTED ([`status::oversize_request`]). Session
/// streams map it where they read ([`status::inbound`]).
fn oversize_request_is_resource_exhausted(
    mut res: tonic::codegen::http::Response<tonic::body::Body>,
) -> tonic::codegen::http::Response<tonic::body::Body> {
    use tonic::codegen::http::HeaderValue;
    let headers = res.headers_mut();
    if headers.get("grpc-status").map(|v| v.as_bytes()) != Some(b"11") {
        return res;
    }
    let message = headers
        .get("grpc-message")
        .and_then(|v| v.to_str().ok())
        .map(|m| m.replace("%20", " "));
    if let Some(status) = message.as_deref().and_then(status::oversize_request) {
        headers.insert("grpc-status", HeaderValue::from_static("8"));
        if let Ok(v) = HeaderValue::from_str(status.message()) {
            headers.insert("grpc-message", v);
        }
    }
    res
}

/// Waits for SIGTERM or Ctrl-C.
async fn termination() {
    #[cfg(unix)]
    {
        use tokio::signal::unix::{signal, SignalKind};
        match signal(SignalKind::terminate()) {
            Ok(mut term) => {
                tokio::select! {
                    _ = term.recv() => {}
                    _ = tokio::signal::ctrl_c() => {}
                }
            }
            Err(_) => {
                let _ = tokio::signal::ctrl_c().await;
            }
        }
    }
    #[cfg(not(unix))]
    {
        let _ = tokio::signal::ctrl_c().await;
    }
}

/// Whether log lines on stderr get ANSI colours: only on a terminal, and
/// not when `NO_COLOR` is set to anything but the empty string
/// (<https://no-color.org>). journald, `docker logs` and files get plain
/// text.
pub fn log_colours(no_color: Option<&std::ffi::OsStr>, stderr_is_terminal: bool) -> bool {
    stderr_is_terminal && no_color.is_none_or(|v| v.is_empty())
}

/// `railcontact serve`: tracing from RUST_LOG (default `info`) to stderr
/// (coloured as [`log_colours`] says), a runtime, the server until SIGTERM
/// or Ctrl-C, then a graceful stop.
pub fn serve(config: &ServeConfig) -> std::io::Result<()> {
    use std::io::IsTerminal;
    let filter = tracing_subscriber::EnvFilter::try_from_default_env()
        .unwrap_or_else(|_| tracing_subscriber::EnvFilter::new("info"));
    let colours = log_colours(
        std::env::var_os("NO_COLOR").as_deref(),
        std::io::stderr().is_terminal(),
    );
    let logs = tracing_subscriber::fmt()
        .with_env_filter(filter)
        .with_writer(std::io::stderr);
    let _ = match config.log_format {
        LogFormat::Text => logs.with_ansi(colours).try_init(),
        LogFormat::Json => logs.json().with_ansi(false).try_init(),
    };
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .thread_name("railcontact-io")
        .build()?;
    runtime.block_on(async {
        let server = start(config).await?;
        // One stable line on stdout for scripts and test fixtures that
        // listen on port 0 and need the port the system gave.
        {
            use std::io::Write;
            let mut out = std::io::stdout().lock();
            let _ = writeln!(out, "railcontact listening on {}", server.addr);
            if let Some(m) = server.metrics_addr {
                let _ = writeln!(out, "railcontact metrics on {m}");
            }
            let _ = out.flush();
        }
        termination().await;
        tracing::info!(
            grace_s = config.shutdown_grace_s,
            "shutting down: new calls refused, calls and sessions under way get the grace \
             period to finish; a second Ctrl-C (or SIGTERM) stops at once"
        );
        server.shutdown_or(termination()).await;
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::log_colours;
    use std::ffi::OsStr;

    #[test]
    fn logs_are_coloured_only_on_a_terminal_without_no_color() {
        assert!(log_colours(None, true));
        assert!(log_colours(Some(OsStr::new("")), true));
        assert!(!log_colours(Some(OsStr::new("1")), true));
        assert!(!log_colours(None, false));
        assert!(!log_colours(Some(OsStr::new("1")), false));
    }
}
