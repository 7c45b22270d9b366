//! Settings of `railcontact serve`, in layers: compiled defaults, then a
//! TOML file (`--config FILE.toml`), then environment variables
//! `RAILCONTACT_<KEY>` (e.g. `RAILCONTACT_LISTEN=0.0.0.0:50051`), then
//! command-line flags. Every key of [`ServeConfig`] can be set in each
//! layer; the server runs with no file and no variables at all.
//!
//! All settings are parsed and every error reported before a port is
//! bound. The environment is read through a function so that tests pass a
//! map instead of changing the process environment.

use std::net::SocketAddr;
use std::path::{Path, PathBuf};

use clap::builder::{OsStringValueParser, TypedValueParser};
use serde::Deserialize;

/// Prefix of the environment variables.
pub const ENV_PREFIX: &str = "RAILCONTACT_";

/// Variables with the [`ENV_PREFIX`] that are not settings but are read by
/// other parts of railcontact: the clients' token, the tests' switches.
pub const OTHER_ENV_VARS: &[&str] = &[
    "RAILCONTACT_TOKEN",
    "RAILCONTACT_SKIP_CLIENT_TESTS",
    "RAILCONTACT_SKIP_PROXY_TEST",
    "RAILCONTACT_BIN",
    "RAILCONTACT_PYTHON",
];

/// A warning for each of `names` (the process's variable names) that has
/// the [`ENV_PREFIX`] but is neither a setting nor one of
/// [`OTHER_ENV_VARS`]: most likely a misspelt setting, which would
/// otherwise be ignored without a word. Names the nearest setting when one
/// is close (at most 3 edits).
pub fn unknown_env_vars(names: impl IntoIterator<Item = String>) -> Vec<String> {
    let settings: Vec<String> = serde_aux::serde_introspection::serde_introspect::<ServeConfig>()
        .iter()
        .map(|k| format!("{ENV_PREFIX}{}", k.to_ascii_uppercase()))
        .collect();
    let mut out: Vec<String> = names
        .into_iter()
        .filter(|n| n.starts_with(ENV_PREFIX))
        .filter(|n| !settings.contains(n) && !OTHER_ENV_VARS.contains(&n.as_str()))
        .map(|n| {
            let nearest = settings
                .iter()
                .map(|s| (edit_distance(&n, s), s))
                .min()
                .filter(|(d, _)| *d <= 3);
            match nearest {
                Some((_, s)) => format!("{n} is not a setting (did you mean {s}?); ignored"),
                None => format!(
                    "{n} is not a setting; ignored (`railcontact serve --help` lists the settings \
                     and their variables)"
                ),
            }
        })
        .collect();
    out.sort();
    out
}

/// Levenshtein distance of two ASCII names.
fn edit_distance(a: &str, b: &str) -> usize {
    let (a, b) = (a.as_bytes(), b.as_bytes());
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.iter().enumerate() {
        let mut prev = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let here = row[j + 1];
            row[j + 1] = (prev + usize::from(ca != cb)).min(row[j] + 1).min(here + 1);
            prev = here;
        }
    }
    row[b.len()]
}

/// `table` (the file's keys) with every key of [`ServeConfig`] that the
/// environment sets (`RAILCONTACT_<KEY>`) put over it. A variable's text
/// is read as a TOML value (`5`, `2.5`, `true`) or else as a string
/// (`127.0.0.1:9464`, `/var/lib/railcontact`); one that does not fit its
/// key is left out and reported in `errors`, naming the variable.
fn env_layer(
    mut table: toml::Table,
    env: &dyn Fn(&str) -> Option<String>,
    errors: &mut Vec<String>,
) -> toml::Table {
    for &key in serde_aux::serde_introspection::serde_introspect::<ServeConfig>() {
        let name = format!("{ENV_PREFIX}{}", key.to_ascii_uppercase());
        let Some(text) = env(&name) else { continue };
        let value = format!("v = {}", text.trim())
            .parse::<toml::Table>()
            .ok()
            .and_then(|mut t| t.remove("v"))
            .unwrap_or_else(|| toml::Value::String(text.trim().to_string()));
        let alone = toml::Table::from_iter([(key.to_string(), value.clone())]);
        match ServeConfig::deserialize(alone) {
            Ok(_) => {
                table.insert(key.to_string(), value);
            }
            Err(e) => errors.push(format!("{name}={text:?}: {}", e.to_string().trim_end())),
        }
    }
    table
}

/// Longest duration any setting in seconds may take (one week): beyond it
/// `Duration` arithmetic is no longer meaningful for a server.
const MAX_SECONDS: f64 = 7.0 * 86400.0;

/// Server settings. The TOML file uses these keys at top level.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ServeConfig {
    /// Address of the gRPC server (default `127.0.0.1:50051`; port 0: any
    /// free port).
    pub listen: SocketAddr,
    /// Address of the Prometheus metrics endpoint (`GET /metrics`, plain
    /// HTTP, no token); not set: no endpoint (default). An address other
    /// than loopback needs `metrics_insecure`.
    pub metrics_listen: Option<SocketAddr>,
    /// Solve threads at once, per lane (default 0: one per core). An exact
    /// or conformal wheelset takes two when two are free, one per wheel.
    pub workers: usize,
    /// Requests admitted at once, running plus waiting (default 0: 16 per
    /// worker); more get RESOURCE_EXHAUSTED.
    pub queue_capacity: usize,
    /// Requests of one client (its token's name, or without tokens its
    /// address) admitted at once, running plus waiting (default 0: half of
    /// the queue's capacity, rounded up); more get RESOURCE_EXHAUSTED
    /// naming this setting while other clients are admitted. The workers
    /// serve the clients with solves waiting in turn, whatever this is.
    pub client_max_admitted: usize,
    /// Largest number of items of one SolvePatchBatch (default 1024).
    pub max_batch_items: usize,
    /// Largest number of points of one CreepCurve (default 1000).
    pub max_curve_points: usize,
    /// Sessions open at once (default 256); more get RESOURCE_EXHAUSTED.
    pub max_sessions: usize,
    /// Sessions of one client open at once (default 0: half of
    /// `max_sessions`, rounded up: 128); more get RESOURCE_EXHAUSTED naming
    /// this setting while other clients open theirs.
    pub client_max_sessions: usize,
    /// Memory one session may hold between its steps \[bytes\]: its live
    /// working state (the exact solver's buffers, FFT workspaces and Newton
    /// scratch, warm starts, a wheel/rail session's patch solvers; not the
    /// influence kernels, which count against `kernel_cache_max_bytes`) and
    /// its marks. Default 256 MiB: an exact steady-rolling session on the
    /// largest grid (256 x 256, `max_grid_elements`) holds 88 MB (1346
    /// bytes an element) and 4.3 MB a mark, 157 MB with all 16 marks. A
    /// step that would leave the session beyond it is refused in-band with
    /// RESOURCE_EXHAUSTED and not applied; a session whose solver does not
    /// fit at all is not opened (RESOURCE_EXHAUSTED).
    pub max_session_bytes: usize,
    /// Memory all sessions together may hold between their steps \[bytes\]
    /// (default 1 GiB: twelve exact sessions on 256 x 256 without marks);
    /// beyond it as `max_session_bytes`.
    pub max_sessions_total_bytes: usize,
    /// A session that receives no message for this long is closed: its
    /// last message is an in-band error saying so, then the stream ends
    /// with DEADLINE_EXCEEDED and its slot is free \[s\] (default 300).
    pub session_idle_timeout_s: f64,
    /// Largest grid, nx * ny elements (default 65536 = 256 x 256).
    pub max_grid_elements: usize,
    /// Largest gRPC message, either direction \[bytes\] (default 16 MiB).
    /// An answer that would be larger is RESOURCE_EXHAUSTED; a batch is
    /// refused as soon as the results it has built exceed it, without
    /// solving its other items.
    pub max_message_bytes: usize,
    /// Memory cap of the influence-kernel cache \[bytes\] (default 1 GiB);
    /// beyond it the least recently used kernel sets are dropped.
    pub kernel_cache_max_bytes: usize,
    /// On SIGTERM or Ctrl-C: how long in-flight requests and open sessions
    /// may take to finish before the server stops anyway \[s\] (default 30).
    pub shutdown_grace_s: f64,
    /// Directory of the server's store (`pairs.redb`: the registered
    /// profile pairs, which survive a restart); created if missing. Default
    /// `railcontact-data`, relative to the working directory. Empty: no
    /// store, pairs are kept in memory only.
    pub data_dir: PathBuf,
    /// What a start does with records of the store that are damaged (they
    /// cannot be decoded, or their content no longer hashes to their id):
    /// `start` (default) serves the other pairs and lists each damaged one
    /// as FAILED with the reason (logged as an error, counted in
    /// `railcontact_store_damaged_records`) until it is registered again
    /// or deleted; `fail` refuses to start, naming the records. A damaged
    /// record is never served either way.
    pub store_damaged: StoreDamaged,
    /// Largest number of registered profile pairs, the built-in one not
    /// counted (default 256); more registrations get RESOURCE_EXHAUSTED.
    pub max_profile_pairs: usize,
    /// Largest number of points of one profile of a registration (default
    /// 20000; measured profiles have a few hundred to a few thousand); more
    /// get INVALID_ARGUMENT naming the profile's field.
    pub max_profile_points: usize,
    /// Largest size of the registrations held, their encoded bytes summed
    /// \[bytes\] (default 256 MiB): in the store, or in memory on a server
    /// without one (an empty `data_dir`); a registration beyond it gets
    /// RESOURCE_EXHAUSTED. The store's file is somewhat larger (redb's
    /// pages and free space).
    pub max_store_bytes: u64,
    /// Largest memory of the prepared pairs the registry holds \[bytes\]
    /// (default 1 GiB): each registered pair's placed profiles (about 1 MB
    /// for the Manchester benchmark's, growing with the points) and, once
    /// model hertz_fastsim_table has used it, its contact table (about as
    /// much again). Beyond it the least recently used pairs are let go and
    /// prepared again on their next use (a few ms to a second); a pair
    /// alone larger than the limit gets RESOURCE_EXHAUSTED. Sessions keep
    /// their pair while they run.
    pub max_prepared_bytes: u64,
    /// Longest one solve may run on a worker \[s\] (default 120): a unary
    /// solve, one item of a batch or creep curve, one session step, a
    /// pair's preparation. A solve still running then is stopped and
    /// answered with RESOURCE_EXHAUSTED, whatever its solver settings ask
    /// for; a client's deadline can only shorten it.
    pub max_solve_time_s: f64,
    /// How long a session stream (PatchSession, WheelRailSession) may take
    /// to send its first message \[s\] (default 10); a stream still silent
    /// then is ended with DEADLINE_EXCEEDED and costs nothing more.
    pub stream_first_message_timeout_s: f64,
    /// HTTP/2 keepalive: the server pings each connection that has been
    /// quiet this long \[s\] (default 30; 0: no pings) ...
    pub http2_keepalive_interval_s: f64,
    /// ... and closes it when the ping is not answered within this time
    /// \[s\] (default 20): a client that vanished without closing its
    /// connection (power loss, a stopped process) frees its calls.
    pub http2_keepalive_timeout_s: f64,
    /// Calls open at once on one HTTP/2 connection (default 256); a client
    /// needing more opens another connection.
    pub max_streams_per_connection: u32,
    /// Calls open at once on the whole server, every connection's
    /// together (default 4096: a silent stream holds about 60 kB, so about
    /// 250 MB at most); more get RESOURCE_EXHAUSTED naming this setting. A
    /// health check is never refused.
    pub max_streams: usize,
    /// Calls of one client open at once (default 0: half of
    /// `max_streams`, rounded up); more get RESOURCE_EXHAUSTED naming this
    /// setting.
    pub client_max_streams: usize,
    /// Connections open at once (default 1024); more are closed as soon as
    /// they are accepted. Keep it below the process's limit of open files.
    pub max_connections: usize,
    /// Connections of one address open at once (default 0: half of
    /// `max_connections`, rounded up); more are closed as soon as they are
    /// accepted. By address even with tokens: a connection comes before
    /// its first token.
    pub client_max_connections: usize,
    /// A connection that has not started a call (its TLS handshake, the
    /// HTTP/2 preface and a request's headers) this long after it was
    /// accepted is closed \[s\] (default 10).
    pub connection_first_call_timeout_s: f64,
    /// A streamed response (CreepCurve) whose client reads none of its
    /// answers for this long is ended: its solve's queue slot and state
    /// are freed and its connection is closed \[s\] (default 60).
    /// Sessions have `session_idle_timeout_s` instead.
    pub stream_write_timeout_s: f64,
    /// TLS on the gRPC port: the server's certificate chain, a PEM file
    /// (leaf first). Set together with `tls_key`; not set (default): plain
    /// HTTP/2 (h2c).
    pub tls_cert: Option<PathBuf>,
    /// The private key of `tls_cert`, a PEM file (PKCS#8, PKCS#1 or SEC1).
    pub tls_key: Option<PathBuf>,
    /// Mutual TLS: a PEM file of the certificate authorities whose client
    /// certificates are accepted; every client must then present one.
    /// Needs `tls_cert`. Not set (default): clients present none.
    pub tls_client_ca: Option<PathBuf>,
    /// Bearer tokens, a TOML file of `[[token]]` entries (`name`, `role` =
    /// "solve" or "admin", and `sha256` = the token's SHA-256 in hex, or
    /// `token` = the token itself); see [`crate::service::auth`]. Set:
    /// every call but the health service's needs `authorization: Bearer
    /// TOKEN`. Not set (default): no tokens.
    pub auth_tokens_file: Option<PathBuf>,
    /// Unknown tokens one address may present before it is slowed down
    /// (default 10); then one more every `1 / auth_failure_rate_per_s`
    /// seconds. Meanwhile its calls needing a token get RESOURCE_EXHAUSTED
    /// naming this setting, their token unchecked.
    pub auth_failure_burst: u32,
    /// Unknown tokens per second an address may present once its
    /// `auth_failure_burst` is spent (default 1).
    pub auth_failure_rate_per_s: f64,
    /// Addresses of proxies in front of this server (nginx, Envoy) whose
    /// calls carry their client's address as the last entry of
    /// `x-forwarded-for` (default none): single addresses (`10.0.0.5`,
    /// `fd00::7`) or ranges in CIDR notation (`10.244.0.0/16`, a
    /// Kubernetes cluster's pod network, where the proxy's address is not
    /// fixed). A call from one of them is that client for the quotas by
    /// address and the token back-off (without it, every client behind the
    /// proxy is the proxy: one guessing tokens slows them all), and their
    /// connections count against `max_connections` only. Anyone else's
    /// `x-forwarded-for` is ignored; list only proxies that set it
    /// themselves (a range that holds clients lets them name any address).
    pub trusted_proxies: Vec<crate::service::quota::ProxyRange>,
    /// Serve gRPC reflection (default true); with `auth_tokens_file` it
    /// needs a token of any role.
    pub reflection: bool,
    /// Allow listening on an address other than loopback without both TLS
    /// and tokens (default false: such a start is refused). A warning is
    /// logged at start.
    pub insecure: bool,
    /// Allow `metrics_listen` on an address other than loopback (default
    /// false: such a start is refused). The metrics port is plain HTTP
    /// without a token whatever the gRPC port's TLS and tokens, so this is
    /// for where something else keeps the port to the scraper: a
    /// container whose port is published on loopback or a private
    /// network, a Kubernetes NetworkPolicy, a firewall. A warning is
    /// logged at start. Independent of `insecure`.
    pub metrics_insecure: bool,
    /// The log's format on stderr: `text` (default: one readable line per
    /// event) or `json` (one JSON object per line, for log shippers:
    /// `timestamp`, `level`, `fields`, `target`, `spans`).
    pub log_format: LogFormat,
}

/// The log's format ([`ServeConfig::log_format`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum LogFormat {
    /// One readable line per event.
    #[default]
    Text,
    /// One JSON object per line.
    Json,
}

/// What to do at start with damaged records of the store; see
/// [`ServeConfig::store_damaged`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum StoreDamaged {
    /// Start; the damaged records are FAILED pairs.
    #[default]
    Start,
    /// Refuse to start.
    Fail,
}

impl Default for ServeConfig {
    fn default() -> Self {
        Self {
            listen: SocketAddr::from(([127, 0, 0, 1], 50051)),
            metrics_listen: None,
            workers: 0,
            queue_capacity: 0,
            client_max_admitted: 0,
            max_batch_items: 1024,
            max_curve_points: 1000,
            max_sessions: 256,
            client_max_sessions: 0,
            max_session_bytes: 256 << 20,
            max_sessions_total_bytes: 1 << 30,
            session_idle_timeout_s: 300.0,
            max_grid_elements: 256 * 256,
            max_message_bytes: 16 << 20,
            kernel_cache_max_bytes: crate::core::cache::DEFAULT_MAX_BYTES,
            shutdown_grace_s: 30.0,
            data_dir: PathBuf::from("railcontact-data"),
            max_solve_time_s: 120.0,
            stream_first_message_timeout_s: 10.0,
            http2_keepalive_interval_s: 30.0,
            http2_keepalive_timeout_s: 20.0,
            max_streams_per_connection: 256,
            max_streams: 4096,
            client_max_streams: 0,
            max_connections: 1024,
            client_max_connections: 0,
            connection_first_call_timeout_s: 10.0,
            stream_write_timeout_s: 60.0,
            store_damaged: StoreDamaged::Start,
            max_profile_pairs: 256,
            max_profile_points: 20_000,
            max_store_bytes: 256 << 20,
            max_prepared_bytes: 1 << 30,
            tls_cert: None,
            tls_key: None,
            tls_client_ca: None,
            auth_tokens_file: None,
            auth_failure_burst: 10,
            auth_failure_rate_per_s: 1.0,
            trusted_proxies: Vec::new(),
            reflection: true,
            insecure: false,
            metrics_insecure: false,
            log_format: LogFormat::Text,
        }
    }
}

/// Overrides from the command line (unset: keep the lower layers'): the
/// flags of `railcontact serve` (see [`super::command`]).
#[derive(Debug, Clone, Default, clap::Args)]
pub struct ServeFlags {
    /// gRPC address (default 127.0.0.1:50051).
    #[arg(long, value_name = "ADDR:PORT")]
    pub listen: Option<SocketAddr>,
    /// Prometheus metrics address (GET /metrics); default: none.
    #[arg(long, value_name = "ADDR:PORT")]
    pub metrics_listen: Option<SocketAddr>,
    /// Solve threads at once, per lane (default: one per core); an exact
    /// or conformal wheelset takes two when two are free.
    #[arg(long)]
    pub workers: Option<usize>,
    /// Directory of the store of registered profile pairs (default
    /// railcontact-data; "": memory only).
    #[arg(long, value_name = "DIR", value_parser = OsStringValueParser::new().map(PathBuf::from))]
    pub data_dir: Option<PathBuf>,
    /// TLS: the server's certificate chain, PEM (with --tls-key).
    #[arg(long, value_name = "FILE.pem")]
    pub tls_cert: Option<PathBuf>,
    /// TLS: the private key of --tls-cert, PEM.
    #[arg(long, value_name = "FILE.pem")]
    pub tls_key: Option<PathBuf>,
    /// Mutual TLS: the authorities of the client certificates, PEM; every
    /// client must then present a certificate they signed.
    #[arg(long, value_name = "FILE.pem")]
    pub tls_client_ca: Option<PathBuf>,
    /// Bearer tokens and their roles, TOML (see deploy/README.md).
    #[arg(long, value_name = "FILE.toml")]
    pub auth_tokens_file: Option<PathBuf>,
    /// Allow listening on an address other than loopback without both TLS
    /// and tokens (logs a warning).
    #[arg(long)]
    pub insecure: bool,
    /// Allow --metrics-listen on an address other than loopback (plain
    /// HTTP, no token; logs a warning).
    #[arg(long)]
    pub metrics_insecure: bool,
}

impl ServeConfig {
    /// The layered settings: defaults, `file` (if any), the variables
    /// `env` returns, `flags`. The error lists every problem found.
    pub fn load(
        file: Option<&Path>,
        env: &dyn Fn(&str) -> Option<String>,
        flags: &ServeFlags,
    ) -> Result<Self, String> {
        let file_layer = match file {
            Some(path) => {
                let text = std::fs::read_to_string(path)
                    .map_err(|e| format!("cannot read config file {}: {e}", path.display()))?;
                let in_file = |e: &dyn std::fmt::Display| {
                    format!(
                        "config file {}: {}",
                        path.display(),
                        e.to_string().trim_end()
                    )
                };
                // Checked whole first, so that its errors name its lines.
                toml::from_str::<ServeConfig>(&text).map_err(|e| in_file(&e))?;
                text.parse::<toml::Table>().map_err(|e| in_file(&e))?
            }
            None => toml::Table::new(),
        };
        let mut errors = Vec::new();
        let layers = env_layer(file_layer, env, &mut errors);
        let mut c: ServeConfig = layers
            .try_into()
            .map_err(|e: toml::de::Error| format!("settings: {}", e.to_string().trim_end()))?;
        if let Some(v) = flags.listen {
            c.listen = v;
        }
        if let Some(v) = flags.metrics_listen {
            c.metrics_listen = Some(v);
        }
        if let Some(v) = flags.workers {
            c.workers = v;
        }
        if let Some(v) = &flags.data_dir {
            c.data_dir = v.clone();
        }
        for (flag, key) in [
            (&flags.tls_cert, &mut c.tls_cert),
            (&flags.tls_key, &mut c.tls_key),
            (&flags.tls_client_ca, &mut c.tls_client_ca),
            (&flags.auth_tokens_file, &mut c.auth_tokens_file),
        ] {
            if flag.is_some() {
                key.clone_from(flag);
            }
            // An empty path (`RAILCONTACT_TLS_CERT=`) is "not set".
            if key.as_ref().is_some_and(|p| p.as_os_str().is_empty()) {
                *key = None;
            }
        }
        c.insecure |= flags.insecure;
        c.metrics_insecure |= flags.metrics_insecure;
        match (&c.tls_cert, &c.tls_key) {
            (Some(_), None) => {
                errors.push("tls_cert is set but tls_key is not: set both (TLS) or neither".into())
            }
            (None, Some(_)) => {
                errors.push("tls_key is set but tls_cert is not: set both (TLS) or neither".into())
            }
            _ => {}
        }
        if c.tls_client_ca.is_some() && c.tls_cert.is_none() {
            errors
                .push("tls_client_ca needs TLS: set tls_cert and tls_key too (mutual TLS)".into());
        }
        for (key, v, least) in [
            ("shutdown_grace_s", c.shutdown_grace_s, 0.0),
            (
                "http2_keepalive_interval_s",
                c.http2_keepalive_interval_s,
                0.0,
            ),
        ] {
            if !(v.is_finite() && v >= least && v <= MAX_SECONDS) {
                errors.push(format!(
                    "{key} must be from {least} to {MAX_SECONDS} s, got {v}"
                ));
            }
        }
        for (key, v) in [
            ("max_solve_time_s", c.max_solve_time_s),
            (
                "stream_first_message_timeout_s",
                c.stream_first_message_timeout_s,
            ),
            ("http2_keepalive_timeout_s", c.http2_keepalive_timeout_s),
            (
                "connection_first_call_timeout_s",
                c.connection_first_call_timeout_s,
            ),
            ("stream_write_timeout_s", c.stream_write_timeout_s),
        ] {
            if !(0.001..=MAX_SECONDS).contains(&v) {
                errors.push(format!(
                    "{key} must be from 0.001 to {MAX_SECONDS} s, got {v}"
                ));
            }
        }
        if c.max_streams_per_connection == 0 {
            errors.push("max_streams_per_connection must be at least 1".into());
        }
        if c.auth_failure_burst == 0 {
            errors.push("auth_failure_burst must be at least 1".into());
        }
        if !(c.auth_failure_rate_per_s.is_finite()
            && c.auth_failure_rate_per_s > 0.0
            && c.auth_failure_rate_per_s <= 1e6)
        {
            errors.push(format!(
                "auth_failure_rate_per_s must be > 0 and at most 1e6, got {}",
                c.auth_failure_rate_per_s
            ));
        }
        // Up to a year: a Duration of it never overflows.
        if !(c.session_idle_timeout_s > 0.0 && c.session_idle_timeout_s <= 3.2e7) {
            errors.push(format!(
                "session_idle_timeout_s must be > 0 and at most 3.2e7 (a year), got {}",
                c.session_idle_timeout_s
            ));
        }
        for (key, v) in [
            ("max_batch_items", c.max_batch_items),
            ("max_curve_points", c.max_curve_points),
            ("max_sessions", c.max_sessions),
            ("max_streams", c.max_streams),
            ("max_connections", c.max_connections),
            ("max_grid_elements", c.max_grid_elements),
            ("max_message_bytes", c.max_message_bytes),
            ("max_profile_pairs", c.max_profile_pairs),
            ("max_profile_points", c.max_profile_points),
            ("max_store_bytes", c.max_store_bytes as usize),
            ("max_prepared_bytes", c.max_prepared_bytes as usize),
        ] {
            if v == 0 {
                errors.push(format!("{key} must be at least 1"));
            }
        }
        if errors.is_empty() {
            Ok(c)
        } else {
            Err(errors.join("; "))
        }
    }

    /// Whether the ports may listen where they are asked to. The gRPC
    /// port: loopback always; any other address needs both TLS
    /// (`tls_cert`, `tls_key`) and tokens (`auth_tokens_file`), or
    /// `insecure`. The metrics port, plain HTTP without a token whatever
    /// the gRPC port has: loopback always; any other address needs
    /// `metrics_insecure`. `Err` names every refusal; `Ok` holds the
    /// warning to log when an override is what allowed a port (both in
    /// one text when both did).
    pub fn check_exposure(&self) -> Result<Option<String>, String> {
        let mut warnings = Vec::new();
        let mut refusals = Vec::new();
        match self.check_grpc_exposure() {
            Ok(Some(w)) => warnings.push(w),
            Ok(None) => {}
            Err(e) => refusals.push(e),
        }
        if let Some(metrics) = self.metrics_listen.filter(|a| !a.ip().is_loopback()) {
            if self.metrics_insecure {
                warnings.push(format!(
                    "serving metrics on {metrics}, which is not loopback, in plain HTTP without a \
                     token: anyone who reaches the port reads them (metrics_insecure = true)"
                ));
            } else {
                refusals.push(format!(
                    "refusing to serve metrics on {metrics}, which is not loopback: the metrics \
                     port is plain HTTP without a token. Bind it to loopback (metrics_listen = \
                     \"127.0.0.1:9464\"), or, where a firewall, a network policy or a port \
                     published on loopback keeps it to the scraper, allow it with \
                     --metrics-insecure, metrics_insecure = true or \
                     RAILCONTACT_METRICS_INSECURE=true"
                ));
            }
        }
        if !refusals.is_empty() {
            Err(refusals.join("; "))
        } else if warnings.is_empty() {
            Ok(None)
        } else {
            Ok(Some(warnings.join("; ")))
        }
    }

    /// [`Self::check_exposure`] of the gRPC port alone.
    fn check_grpc_exposure(&self) -> Result<Option<String>, String> {
        if self.listen.ip().is_loopback() {
            return Ok(None);
        }
        let mut missing = Vec::new();
        if self.tls_cert.is_none() {
            missing.push("TLS (tls_cert and tls_key)");
        }
        if self.auth_tokens_file.is_none() {
            missing.push("bearer tokens (auth_tokens_file)");
        }
        if missing.is_empty() {
            return Ok(None);
        }
        let missing = missing.join(" and ");
        if self.insecure {
            Ok(Some(format!(
                "listening on {} without {missing}: anyone who reaches the port can use it \
                 (insecure = true)",
                self.listen
            )))
        } else {
            Err(format!(
                "refusing to listen on {}, which is not loopback, without {missing}: add them, \
                 or override with --insecure, insecure = true or RAILCONTACT_INSECURE=true \
                 (for a trusted network, or behind a proxy that authenticates)",
                self.listen
            ))
        }
    }

    /// The store's directory, if the pairs are to be persisted.
    pub fn store_dir(&self) -> Option<&Path> {
        (!self.data_dir.as_os_str().is_empty()).then_some(self.data_dir.as_path())
    }

    /// Solve threads: `workers`, or the cores when 0.
    pub fn worker_count(&self) -> usize {
        if self.workers > 0 {
            self.workers
        } else {
            std::thread::available_parallelism().map_or(1, |n| n.get())
        }
    }

    /// Admission capacity: `queue_capacity`, or 16 per worker when 0.
    pub fn queue_count(&self) -> usize {
        if self.queue_capacity > 0 {
            self.queue_capacity
        } else {
            16 * self.worker_count()
        }
    }

    /// A warning when `max_connections` does not fit under the process's
    /// limit of open files (Linux: `/proc/self/limits`; None elsewhere or
    /// when it fits): connections beyond the limit fail at accept, before
    /// the cap can refuse them, and the store needs descriptors too.
    pub fn check_open_files(&self) -> Option<String> {
        let limits = std::fs::read_to_string("/proc/self/limits").ok()?;
        let soft: u64 = limits
            .lines()
            .find(|l| l.starts_with("Max open files"))?
            .split_whitespace()
            .nth(3)?
            .parse()
            .ok()?;
        let needed = self.max_connections as u64 + 64;
        (needed > soft).then(|| {
            format!(
                "max_connections = {} needs about {needed} open files, more than this process's \
                 limit of {soft} (`ulimit -n`, LimitNOFILE in systemd): raise the limit or \
                 lower max_connections",
                self.max_connections
            )
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    fn env(pairs: &[(&str, &str)]) -> impl Fn(&str) -> Option<String> {
        let map: HashMap<String, String> = pairs
            .iter()
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect();
        move |k: &str| map.get(k).cloned()
    }

    #[test]
    fn misspelt_variables_are_named_with_the_nearest_setting() {
        let names = [
            "RAILCONTACT_LISTNE",
            "RAILCONTACT_LISTEN",
            "RAILCONTACT_TOKEN",
            "RAILCONTACT_SOMETHING_ELSE_ENTIRELY",
            "PATH",
        ]
        .map(String::from);
        let w = unknown_env_vars(names);
        assert_eq!(w.len(), 2, "{w:?}");
        assert!(
            w[0].contains("RAILCONTACT_LISTNE is not a setting (did you mean RAILCONTACT_LISTEN?)"),
            "{w:?}"
        );
        assert!(
            w[1].starts_with("RAILCONTACT_SOMETHING_ELSE_ENTIRELY is not a setting; ignored"),
            "{w:?}"
        );
    }

    #[test]
    fn trusted_proxies_from_the_environment_are_a_list_of_addresses_or_ranges() {
        let e = env(&[(
            "RAILCONTACT_TRUSTED_PROXIES",
            r#"["10.0.0.5", "fd00::7", "10.244.0.0/16"]"#,
        )]);
        let c = ServeConfig::load(None, &e, &ServeFlags::default()).unwrap();
        use crate::service::quota::ProxyRange;
        let want: Vec<ProxyRange> = ["10.0.0.5/32", "fd00::7/128", "10.244.0.0/16"]
            .iter()
            .map(|s| ProxyRange(s.parse().unwrap()))
            .collect();
        assert_eq!(c.trusted_proxies, want);
        let shown: Vec<String> = c.trusted_proxies.iter().map(|p| p.to_string()).collect();
        assert_eq!(shown, ["10.0.0.5", "fd00::7", "10.244.0.0/16"]);
        let ip = |s: &str| s.parse::<std::net::IpAddr>().unwrap();
        let pods = c.trusted_proxies[2];
        assert!(pods.contains(ip("10.244.3.17")) && pods.contains(ip("::ffff:10.244.0.1")));
        assert!(!pods.contains(ip("10.245.0.1")));
        let mapped: ProxyRange = "::ffff:10.244.0.0/112".parse().unwrap();
        assert!(mapped.contains(ip("10.244.9.9")) && !mapped.contains(ip("10.245.0.1")));
        // A bare address is not a list; a name is not an address, nor is
        // a range with a bad prefix.
        for bad in ["10.0.0.5", r#"["proxy.example"]"#, r#"["10.0.0.0/33"]"#] {
            let e = env(&[("RAILCONTACT_TRUSTED_PROXIES", bad)]);
            let err = ServeConfig::load(None, &e, &ServeFlags::default()).unwrap_err();
            assert!(err.contains("RAILCONTACT_TRUSTED_PROXIES"), "{err}");
        }
    }

    #[test]
    fn layers_apply_in_order_and_errors_are_collected() {
        let none = env(&[]);
        let c = ServeConfig::load(None, &none, &ServeFlags::default()).unwrap();
        assert_eq!(c, ServeConfig::default());
        assert_eq!(c.listen.to_string(), "127.0.0.1:50051");

        let dir = std::env::temp_dir().join(format!("railcontact-config-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("serve.toml");
        std::fs::write(
            &file,
            "listen = \"127.0.0.1:6000\"\nworkers = 3\nmax_sessions = 7\n",
        )
        .unwrap();
        let e = env(&[
            ("RAILCONTACT_WORKERS", "5"),
            ("RAILCONTACT_METRICS_LISTEN", "127.0.0.1:9464"),
            ("RAILCONTACT_DATA_DIR", "/var/lib/railcontact"),
            ("RAILCONTACT_STORE_DAMAGED", "fail"),
            ("RAILCONTACT_MAX_PROFILE_POINTS", "5000"),
            ("RAILCONTACT_SESSION_IDLE_TIMEOUT_S", "2.5"),
            ("RAILCONTACT_MAX_SESSION_BYTES", "1000"),
        ]);
        let flags = ServeFlags {
            listen: Some("127.0.0.1:7000".parse().unwrap()),
            ..Default::default()
        };
        let c = ServeConfig::load(Some(&file), &e, &flags).unwrap();
        assert_eq!(c.listen.port(), 7000, "flag over file");
        assert_eq!(c.workers, 5, "env over file");
        assert_eq!(c.max_sessions, 7, "file over default");
        assert_eq!(c.metrics_listen.map(|a| a.port()), Some(9464));
        assert_eq!(c.store_dir(), Some(Path::new("/var/lib/railcontact")));
        assert_eq!(c.store_damaged, StoreDamaged::Fail);
        assert_eq!(c.max_profile_points, 5000);
        assert_eq!(c.session_idle_timeout_s, 2.5);
        assert_eq!(c.max_session_bytes, 1000);

        let bad = env(&[
            ("RAILCONTACT_WORKERS", "many"),
            ("RAILCONTACT_MAX_SESSIONS", "0"),
            ("RAILCONTACT_STORE_DAMAGED", "ignore"),
            ("RAILCONTACT_SESSION_IDLE_TIMEOUT_S", "0"),
        ]);
        let err = ServeConfig::load(None, &bad, &ServeFlags::default()).unwrap_err();
        assert!(
            err.contains("RAILCONTACT_WORKERS")
                && err.contains("max_sessions")
                && err.contains("RAILCONTACT_STORE_DAMAGED")
                && err.contains("session_idle_timeout_s"),
            "{err}"
        );
        // Security keys through the environment; an empty path is "not set".
        let e = env(&[
            ("RAILCONTACT_INSECURE", "true"),
            ("RAILCONTACT_LISTEN", "0.0.0.0:50051"),
            ("RAILCONTACT_TLS_CERT", ""),
            ("RAILCONTACT_REFLECTION", "false"),
            (
                "RAILCONTACT_AUTH_TOKENS_FILE",
                "/etc/railcontact/tokens.toml",
            ),
        ]);
        let c = ServeConfig::load(None, &e, &ServeFlags::default()).unwrap();
        assert!(c.insecure && !c.reflection && c.tls_cert.is_none());
        assert_eq!(
            c.auth_tokens_file.as_deref(),
            Some(Path::new("/etc/railcontact/tokens.toml"))
        );
        assert!(c.check_exposure().unwrap().unwrap().contains("TLS"));
        let c = ServeConfig {
            insecure: false,
            ..c
        };
        let err = c.check_exposure().unwrap_err();
        assert!(
            err.contains("tls_cert") && err.contains("--insecure"),
            "{err}"
        );
        assert_eq!(ServeConfig::default().check_exposure(), Ok(None));

        // The metrics port: loopback always, any other address only with
        // its own override, whatever the gRPC port has.
        let metrics = |addr: &str, metrics_insecure: bool, insecure: bool| ServeConfig {
            metrics_listen: Some(addr.parse().unwrap()),
            metrics_insecure,
            insecure,
            ..ServeConfig::default()
        };
        assert_eq!(
            metrics("127.0.0.1:9464", false, false).check_exposure(),
            Ok(None)
        );
        assert_eq!(
            metrics("[::1]:9464", false, false).check_exposure(),
            Ok(None)
        );
        for addr in ["0.0.0.0:9464", "[::]:9464", "10.0.0.5:9464"] {
            let err = metrics(addr, false, true).check_exposure().unwrap_err();
            assert!(
                err.contains("metrics")
                    && err.contains("--metrics-insecure")
                    && err.contains("RAILCONTACT_METRICS_INSECURE=true"),
                "{err}"
            );
            let warning = metrics(addr, true, false)
                .check_exposure()
                .unwrap()
                .unwrap();
            assert!(warning.contains("metrics_insecure = true"), "{warning}");
        }
        // Both refusals at once, and both warnings.
        let both = ServeConfig {
            listen: "0.0.0.0:50051".parse().unwrap(),
            ..metrics("0.0.0.0:9464", false, false)
        };
        let err = both.check_exposure().unwrap_err();
        assert!(
            err.contains("--insecure") && err.contains("--metrics-insecure"),
            "{err}"
        );
        let warning = ServeConfig {
            insecure: true,
            metrics_insecure: true,
            ..both
        }
        .check_exposure()
        .unwrap()
        .unwrap();
        assert!(
            warning.contains("insecure = true") && warning.contains("metrics_insecure = true"),
            "{warning}"
        );
        // Set by its variable and by its flag.
        let e = env(&[
            ("RAILCONTACT_METRICS_LISTEN", "0.0.0.0:9464"),
            ("RAILCONTACT_METRICS_INSECURE", "true"),
        ]);
        let c = ServeConfig::load(None, &e, &ServeFlags::default()).unwrap();
        assert!(c.metrics_insecure && c.check_exposure().is_ok());
        let flags = ServeFlags {
            metrics_listen: Some("0.0.0.0:9464".parse().unwrap()),
            metrics_insecure: true,
            ..Default::default()
        };
        let c = ServeConfig::load(None, &none, &flags).unwrap();
        assert!(c.metrics_insecure && c.check_exposure().is_ok());

        std::fs::write(&file, "listen = \"127.0.0.1:6000\"\nworker = 3\n").unwrap();
        let err = ServeConfig::load(Some(&file), &none, &ServeFlags::default()).unwrap_err();
        assert!(err.contains("worker"), "{err}");
        std::fs::remove_dir_all(&dir).ok();
    }
}
