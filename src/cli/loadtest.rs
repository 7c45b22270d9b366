//! `railcontact loadtest`: drives a running server (or several replicas)
//! with concurrent co-simulation sessions and batch clients, measures the
//! round trip of every step, and checks every answer bit for bit against a
//! replay of the same inputs, each session alone on its stream.
//!
//! # What runs
//!
//! * `--sessions N` co-simulation sessions, each its own connection and
//!   bidi stream (WheelRailSession or PatchSession), each stepping a
//!   deterministic input sequence for at most `--steps M` steps and at most
//!   `--seconds S` (whichever ends first). Session `i` goes to target
//!   `i mod T` of the `T` targets (`--target` repeated or comma-separated):
//!   client-side load balancing, with every session pinned to one replica.
//!   Every stream carries the metadata `x-railcontact-session: <label>` so
//!   that a proxy can pin it by a header hash (see deploy/envoy.yaml).
//! * `--batch-clients B` batch clients, each its own connection, each
//!   sending up to `M` batches of `--batch-items` queries one after the
//!   other (same time limit). Even-numbered clients send
//!   SolveWheelRailBatch (Hertz+FASTSIM wheelsets), odd-numbered ones
//!   SolvePatchBatch (FASTSIM patches). Client `b` goes to target
//!   `(N + b) mod T`.
//!
//! # The mix
//!
//! `--mix KIND=WEIGHT,KIND=WEIGHT,...` shares the N sessions among kinds in
//! proportion to the weights (largest remainder; while N is at least the
//! number of kinds, every kind gets at least one session). Kinds:
//!
//! | kind | session |
//! |---|---|
//! | `wheelrail:hertz_fastsim`, `wheelrail:exact`, `wheelrail:cect`, `wheelrail:auto` | WheelRailSession on the built-in pair `mbench_s1002_uic60`, both wheels, with that model |
//! | `patch:hertz`, `patch:fastsim` | PatchSession, steady rolling, with that model |
//! | `patch:exact`, `patch:exactN` | PatchSession, exact model, default grid or N x N (e.g. `patch:exact40`) |
//!
//! The default, [`DEFAULT_MIX`] with 16 sessions, is a 4-car train of 16
//! wheelsets plus two detailed patch studies: 12 wheelsets on the fast
//! Hertz+FASTSIM path, 2 with the exact model (the leading wheelsets, where
//! flange contact matters), one exact 40 x 40 patch and one FASTSIM patch.
//!
//! # The inputs
//!
//! Time step 1 ms. Wheelsets oscillate laterally as in hunting: lateral
//! shift `4 mm sin(w t + phi)`, yaw `2 mrad cos(w t + phi)` with the
//! matching lateral speed and yaw rate, f = 2 Hz, forward 20 m/s, wheel
//! load `50 kN + 2 kN sin(3 w t)`, roll and pitch rate left to the server.
//! Patches (h = A x^2 + B y^2, A = 1.09 /m, B = 1.67 /m, steel, mu = 0.3)
//! roll with creepage ramps: `xi = 1e-3 (1 + 0.5 sin(w t + phi))`,
//! `eta = 5e-4 cos(w t + phi)`, `phi_spin = 0.1 sin(w t + phi) /m`, normal
//! force `50 kN + 2 kN sin(3 w t)`. Every session has its own phase `phi`
//! (session index times 2 pi / 16), so the sequence is fixed by the session
//! index alone.
//!
//! # The check
//!
//! After the concurrent run, every session and batch client is replayed
//! with the same inputs on one connection to the first target, for as many
//! steps as it completed: each alone on its own stream, four at a time per
//! core of the client machine. Each answer's result
//! (server timing fields cleared) is compared by the SHA-256 of its
//! protobuf encoding, which holds every double bit for bit: the server
//! promises identical outputs however sessions interleave, and replicas
//! must agree with each other. A differing step counts as a mismatch.
//!
//! # The report
//!
//! Latency is the round trip of one step (send the step, receive its
//! answer) or one batch call, in seconds; percentiles are nearest-rank on
//! the sorted samples. Throughput is completed steps and batch calls per
//! second of the concurrent run's wall time. `--json` prints one object
//! (`p50_s`, `p90_s`, `p99_s`, `max_s`, `mean_s`, `throughput_per_s`,
//! `steps`, `errors`, `mismatches`, `wall_s`, per kind in `kinds` and per
//! target in `targets`); otherwise a table. The exit code is 1 when there
//! were errors or mismatches, 2 for bad options, and 1 when a target cannot
//! be reached (checked first, by gRPC health of
//! `railcontact.v1.ContactService`, before any load). Ctrl-C stops the
//! load after the steps under way and prints the report of what was done
//! (`interrupted: true`, not replayed against the baseline; exit code 1);
//! a second Ctrl-C exits at once (130).

use std::collections::BTreeMap;
use std::io::IsTerminal;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use clap::Args;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use prost::Message;
use serde::Serialize;
use sha2::{Digest, Sha256};
use tokio::sync::mpsc;
use tokio_stream::wrappers::ReceiverStream;
use tonic::metadata::{Ascii, MetadataValue};
use tonic::service::interceptor::InterceptedService;
use tonic::transport::{Certificate, Channel, ClientTlsConfig, Endpoint, Identity};

use super::CliError;
use crate::shared::pb;
use crate::shared::pb::contact_service_client::ContactServiceClient;
use crate::shared::{error_chain, BUILTIN_PAIR};

/// The default `--mix`: see the module documentation.
pub const DEFAULT_MIX: &str =
    "wheelrail:hertz_fastsim=12,wheelrail:exact=2,patch:exact40=1,patch:fastsim=1";

/// Metadata key that names a co-simulation session (for proxies that pin a
/// session to one replica by hashing it).
pub const SESSION_HEADER: &str = "x-railcontact-session";

/// The contact service's name in the gRPC health service: NOT_SERVING
/// as soon as a server starts draining (the empty name stays SERVING).
pub const CONTACT_SERVICE: &str = "railcontact.v1.ContactService";

/// Simulated time step [s].
const DT_S: f64 = 1e-3;
/// Frequency of the lateral oscillation and the creepage ramps [Hz].
const FREQ_HZ: f64 = 2.0;

/// Options of `railcontact loadtest`.
#[derive(Debug, Clone, Args)]
pub struct LoadtestArgs {
    /// Server(s) to drive, HOST:PORT; repeat the option or separate by
    /// commas for several replicas (session i goes to target i mod T).
    #[arg(long, value_name = "HOST:PORT", required = true, value_delimiter = ',')]
    pub target: Vec<String>,
    /// Concurrent co-simulation sessions.
    #[arg(long, default_value_t = 16)]
    pub sessions: usize,
    /// Steps per session at most (and batches per batch client).
    #[arg(long, default_value_t = 200)]
    pub steps: u64,
    /// Time limit of the concurrent run, in seconds: no step starts after it.
    #[arg(long, default_value_t = 60.0)]
    pub seconds: f64,
    /// Batch clients besides the sessions (even: SolveWheelRailBatch of
    /// Hertz+FASTSIM wheelsets; odd: SolvePatchBatch of FASTSIM patches).
    #[arg(long, default_value_t = 1)]
    pub batch_clients: usize,
    /// Queries per batch call.
    #[arg(long, default_value_t = 8)]
    pub batch_items: usize,
    /// Session kinds and weights, KIND=WEIGHT,... (kinds: wheelrail:MODEL
    /// with MODEL one of hertz_fastsim, hertz_fastsim_table,
    /// hertz_fastsim_elliptic, hertz_polach, hertz_strip,
    /// hertz_fastsim_modified, kik_piotrowski, exact, cect, auto;
    /// patch:hertz, patch:fastsim, patch:exact, patch:exactN for an N x N
    /// grid).
    #[arg(long, default_value = DEFAULT_MIX)]
    pub mix: String,
    /// Wheel/rail sessions of the models exact, cect and auto: open them
    /// with this force_tolerance_of_wheel_load (each wheel's patches on
    /// the coarsest grid whose forces lie within half this fraction of the
    /// wheel load of those on the element size; 5e-3 to 0.1). Not set:
    /// every patch on the element size.
    #[arg(long, value_name = "FRACTION")]
    pub force_tolerance_of_wheel_load: Option<f64>,
    /// Print one JSON object instead of the table (no progress bar).
    #[arg(long)]
    pub json: bool,
    /// Time limit to connect to each target and get its health, in seconds.
    #[arg(long, default_value_t = 10.0)]
    pub connect_timeout: f64,
    /// TLS and token.
    #[command(flatten)]
    pub security: ConnectArgs,
}

/// How `loadtest` and `health` reach a server that asks for TLS or a
/// token.
#[derive(Debug, Clone, Default, Args)]
pub struct ConnectArgs {
    /// Connect with TLS, trusting server certificates signed by the
    /// authorities of this PEM file.
    #[arg(long, value_name = "FILE.pem")]
    pub tls_ca: Option<std::path::PathBuf>,
    /// With --tls-ca: the name the server's certificate must hold
    /// (default: the host of --target).
    #[arg(long, value_name = "NAME", requires = "tls_ca")]
    pub tls_server_name: Option<String>,
    /// Mutual TLS: this client's certificate chain, PEM (with
    /// --tls-client-key and --tls-ca).
    #[arg(long, value_name = "FILE.pem", requires_all = ["tls_client_key", "tls_ca"])]
    pub tls_client_cert: Option<std::path::PathBuf>,
    /// Mutual TLS: the private key of --tls-client-cert, PEM.
    #[arg(long, value_name = "FILE.pem", requires = "tls_client_cert")]
    pub tls_client_key: Option<std::path::PathBuf>,
    /// Bearer token, sent on every call as `authorization: Bearer TOKEN`
    /// (the variable keeps it out of the process list).
    #[arg(long, env = "RAILCONTACT_TOKEN", hide_env_values = true)]
    pub token: Option<String>,
}

/// Adds `authorization: Bearer TOKEN` to every call, when there is a
/// token.
#[derive(Clone, Default)]
pub struct Bearer(Option<MetadataValue<Ascii>>);

impl tonic::service::Interceptor for Bearer {
    fn call(&mut self, mut req: tonic::Request<()>) -> Result<tonic::Request<()>, tonic::Status> {
        if let Some(v) = &self.0 {
            req.metadata_mut().insert("authorization", v.clone());
        }
        Ok(req)
    }
}

/// A connection to a server, with its token.
pub type Connection = InterceptedService<Channel, Bearer>;

// ---------------------------------------------------------------------
// Kinds and the mix
// ---------------------------------------------------------------------

/// What one session (or batch client) runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Kind {
    /// WheelRailSession on the built-in pair with this model.
    WheelRail(pb::WheelRailModel),
    /// PatchSession in steady rolling, model and grid (None: default).
    Patch(pb::Model, Option<u32>),
    /// SolveWheelRailBatch of Hertz+FASTSIM wheelsets.
    WheelRailBatch,
    /// SolvePatchBatch of FASTSIM patches.
    PatchBatch,
}

impl Kind {
    /// Parses a session kind of `--mix`.
    pub fn parse(s: &str) -> Result<Kind, String> {
        let (family, model) = s
            .split_once(':')
            .ok_or_else(|| format!("`{s}`: expected wheelrail:MODEL or patch:MODEL"))?;
        match family {
            "wheelrail" => {
                let m = match model {
                    "hertz_fastsim" => pb::WheelRailModel::HertzFastsim,
                    "hertz_fastsim_table" => pb::WheelRailModel::HertzFastsimTable,
                    "hertz_polach" => pb::WheelRailModel::HertzPolach,
                    "hertz_fastsim_elliptic" => pb::WheelRailModel::HertzFastsimElliptic,
                    "hertz_strip" => pb::WheelRailModel::HertzStrip,
                    "hertz_fastsim_modified" => pb::WheelRailModel::HertzFastsimModified,
                    "kik_piotrowski" => pb::WheelRailModel::KikPiotrowski,
                    "exact" => pb::WheelRailModel::Exact,
                    "cect" => pb::WheelRailModel::Cect,
                    "auto" => pb::WheelRailModel::Auto,
                    _ => {
                        return Err(format!(
                            "`{s}`: wheelrail models are hertz_fastsim, hertz_fastsim_table, \
                             hertz_polach, hertz_fastsim_elliptic, hertz_strip, \
                             hertz_fastsim_modified, kik_piotrowski, exact, cect, auto"
                        ))
                    }
                };
                Ok(Kind::WheelRail(m))
            }
            "patch" => match model {
                "hertz" => Ok(Kind::Patch(pb::Model::Hertz, None)),
                "fastsim" => Ok(Kind::Patch(pb::Model::Fastsim, None)),
                "exact" => Ok(Kind::Patch(pb::Model::Exact, None)),
                _ => match model.strip_prefix("exact").map(str::parse::<u32>) {
                    Some(Ok(n)) if (4..=256).contains(&n) => Ok(Kind::Patch(pb::Model::Exact, Some(n))),
                    _ => Err(format!(
                        "`{s}`: patch models are hertz, fastsim, exact, exactN (N x N grid, 4 <= N <= 256)"
                    )),
                },
            },
            _ => Err(format!("`{s}`: kinds start with wheelrail: or patch:")),
        }
    }

    /// The kind's name in reports (the `--mix` spelling).
    pub fn name(&self) -> String {
        match self {
            Kind::WheelRail(m) => format!(
                "wheelrail:{}",
                match m {
                    pb::WheelRailModel::HertzFastsim => "hertz_fastsim",
                    pb::WheelRailModel::HertzFastsimTable => "hertz_fastsim_table",
                    pb::WheelRailModel::HertzPolach => "hertz_polach",
                    pb::WheelRailModel::HertzFastsimElliptic => "hertz_fastsim_elliptic",
                    pb::WheelRailModel::HertzStrip => "hertz_strip",
                    pb::WheelRailModel::HertzFastsimModified => "hertz_fastsim_modified",
                    pb::WheelRailModel::KikPiotrowski => "kik_piotrowski",
                    pb::WheelRailModel::Cect => "cect",
                    pb::WheelRailModel::Auto => "auto",
                    _ => "exact",
                }
            ),
            Kind::Patch(m, n) => {
                let model = match m {
                    pb::Model::Hertz => "hertz",
                    pb::Model::Fastsim => "fastsim",
                    _ => "exact",
                };
                match n {
                    Some(n) => format!("patch:{model}{n}"),
                    None => format!("patch:{model}"),
                }
            }
            Kind::WheelRailBatch => "batch:wheelrail:hertz_fastsim".into(),
            Kind::PatchBatch => "batch:patch:fastsim".into(),
        }
    }
}

/// Parses `--mix` and shares `sessions` among its kinds: one kind per
/// session, in session order (each kind's sessions together, in the order
/// of the option).
pub fn assign(mix: &str, sessions: usize) -> Result<Vec<Kind>, String> {
    let mut entries: Vec<(Kind, f64)> = Vec::new();
    for part in mix.split(',').map(str::trim).filter(|p| !p.is_empty()) {
        let (kind, weight) = match part.split_once('=') {
            Some((k, w)) => {
                let w: f64 = w
                    .trim()
                    .parse()
                    .map_err(|_| format!("`{part}`: the weight must be a number"))?;
                (k.trim(), w)
            }
            None => (part, 1.0),
        };
        if !(weight.is_finite() && weight >= 0.0) {
            return Err(format!("`{part}`: the weight must be >= 0"));
        }
        let kind = Kind::parse(kind)?;
        if entries.iter().any(|(k, _)| *k == kind) {
            return Err(format!("`{part}`: kind given twice"));
        }
        if weight > 0.0 {
            entries.push((kind, weight));
        }
    }
    let total: f64 = entries.iter().map(|(_, w)| w).sum();
    if entries.is_empty() || total <= 0.0 {
        return Err("no kind with a positive weight".into());
    }
    // Largest remainder.
    let quota: Vec<f64> = entries
        .iter()
        .map(|(_, w)| w / total * sessions as f64)
        .collect();
    let mut counts: Vec<usize> = quota.iter().map(|q| q.floor() as usize).collect();
    let mut order: Vec<usize> = (0..entries.len()).collect();
    order.sort_by(|&a, &b| {
        let (ra, rb) = (quota[a] - quota[a].floor(), quota[b] - quota[b].floor());
        rb.partial_cmp(&ra).unwrap().then(a.cmp(&b))
    });
    let mut left = sessions - counts.iter().sum::<usize>();
    for &i in order.iter().cycle() {
        if left == 0 {
            break;
        }
        counts[i] += 1;
        left -= 1;
    }
    // Every kind at least once while there are sessions enough.
    if sessions >= entries.len() {
        while let Some(empty) = counts.iter().position(|&c| c == 0) {
            let largest = (0..counts.len()).max_by_key(|&i| (counts[i], usize::MAX - i));
            let largest = largest.expect("non-empty");
            counts[largest] -= 1;
            counts[empty] += 1;
        }
    }
    Ok(entries
        .iter()
        .zip(counts)
        .flat_map(|((k, _), c)| std::iter::repeat_n(*k, c))
        .collect())
}

// ---------------------------------------------------------------------
// Deterministic inputs
// ---------------------------------------------------------------------

fn omega() -> f64 {
    2.0 * std::f64::consts::PI * FREQ_HZ
}

/// Phase of session (or batch item) `i`.
fn phase(i: usize) -> f64 {
    i as f64 * 2.0 * std::f64::consts::PI / 16.0
}

/// The wheelset's state at step `k` for phase index `i`: position,
/// velocity, load.
fn wheelset_state(
    i: usize,
    k: u64,
) -> (
    Option<pb::WheelsetPosition>,
    Option<pb::WheelsetVelocity>,
    Option<pb::WheelLoad>,
) {
    let t = k as f64 * DT_S;
    let w = omega();
    let a = w * t + phase(i);
    let (y0, psi0) = (4e-3, 2e-3);
    (
        Some(pb::WheelsetPosition {
            lateral_m: y0 * a.sin(),
            yaw_rad: psi0 * a.cos(),
            roll_rad: None,
            track_s_m: 0.0,
        }),
        Some(pb::WheelsetVelocity {
            forward_m_per_s: 20.0,
            lateral_m_per_s: y0 * w * a.cos(),
            yaw_rad_per_s: -psi0 * w * a.sin(),
            ..Default::default()
        }),
        Some(pb::WheelLoad {
            load: Some(pb::wheel_load::Load::VerticalForceN(
                50e3 + 2e3 * (3.0 * w * t).sin(),
            )),
            total_longitudinal_force_n: None,
        }),
    )
}

/// The patch creepages at step `k` for phase index `i`.
fn creepages(i: usize, k: u64) -> pb::Creepages {
    let a = omega() * k as f64 * DT_S + phase(i);
    pb::Creepages {
        creepage_long: 1e-3 * (1.0 + 0.5 * a.sin()),
        creepage_lat: 5e-4 * a.cos(),
        spin_per_m: 0.1 * a.sin(),
        ..Default::default()
    }
}

/// The patch normal force at step `k` [N].
fn patch_load(k: u64) -> f64 {
    50e3 + 2e3 * (3.0 * omega() * k as f64 * DT_S).sin()
}

/// The patch case of a session or batch item (steady rolling).
fn patch_case(model: pb::Model, grid: Option<u32>, c: pb::Creepages, load_n: f64) -> pb::PatchCase {
    pb::PatchCase {
        model: model as i32,
        material: Some(pb::MaterialSection {
            shear_modulus_pa: Some(81.0e9),
            poisson_ratio: Some(0.30),
            ..Default::default()
        }),
        friction: Some(pb::FrictionSection {
            coefficient: Some(0.3),
            ..Default::default()
        }),
        geometry: Some(pb::GeometrySection {
            kind: pb::GeometryKind::Quadratic as i32,
            a_per_m: Some(1.0 / (2.0 * 0.46)),
            b_per_m: Some(1.0 / (2.0 * 0.3)),
            ..Default::default()
        }),
        load: Some(pb::LoadSection {
            load: Some(pb::load_section::Load::NormalForceN(load_n)),
        }),
        kinematics: Some(pb::patch_case::Kinematics::Rolling(c)),
        grid: grid.map(|n| pb::GridSection {
            nx: Some(n),
            ny: Some(n),
            ..Default::default()
        }),
        ..Default::default()
    }
}

fn wheelrail_query(i: usize, k: u64, model: pb::WheelRailModel) -> pb::SolveWheelRailRequest {
    let (position, velocity, load) = wheelset_state(i, k);
    pb::SolveWheelRailRequest {
        pair_id: BUILTIN_PAIR.into(),
        model: model as i32,
        sides: pb::WheelSides::Both as i32,
        position,
        velocity,
        load,
        ..Default::default()
    }
}

// ---------------------------------------------------------------------
// Fingerprints
// ---------------------------------------------------------------------

type Digest32 = [u8; 32];

fn digest(bytes: &[u8]) -> Digest32 {
    Sha256::digest(bytes).into()
}

/// Clears the server's wall-time fields (the only figures that may
/// differ between equal solves).
fn clear_step_timing(r: &mut pb::StepResult) {
    if let Some(info) = r.info.as_mut() {
        info.solve_time_s = 0.0;
    }
}

fn clear_patch_timing(r: &mut pb::PatchResult) {
    if let Some(s) = r.result.as_mut() {
        clear_step_timing(s);
    }
    r.steps.iter_mut().for_each(clear_step_timing);
}

fn wheelrail_digest(mut r: pb::WheelRailResult) -> Digest32 {
    r.timing = None;
    digest(&r.encode_to_vec())
}

fn step_digest(mut r: pb::StepResult) -> Digest32 {
    clear_step_timing(&mut r);
    digest(&r.encode_to_vec())
}

// ---------------------------------------------------------------------
// Clients
// ---------------------------------------------------------------------

type Client = ContactServiceClient<Connection>;

/// `HOST:PORT` (or a URI) as an endpoint URI (https with TLS).
fn target_uri(target: &str, tls: bool) -> Result<String, CliError> {
    let t = target.trim();
    let uri = if t.contains("://") {
        t.to_string()
    } else if tls {
        format!("https://{t}")
    } else {
        format!("http://{t}")
    };
    let ok = uri
        .parse::<tonic::codegen::http::Uri>()
        .ok()
        .filter(|u| u.host().is_some() && u.port_u16().is_some());
    match ok {
        Some(_) => Ok(uri),
        None => Err(CliError::BadInput(format!(
            "--target `{target}`: expected HOST:PORT, e.g. 127.0.0.1:50051"
        ))),
    }
}

/// The TLS settings of `args` (None without --tls-ca).
fn client_tls(args: &ConnectArgs) -> Result<Option<ClientTlsConfig>, CliError> {
    let Some(ca) = &args.tls_ca else {
        return Ok(None);
    };
    let read = |option: &str, path: &std::path::Path| {
        std::fs::read(path).map_err(|e| {
            CliError::BadInput(format!("{option} {}: cannot read it: {e}", path.display()))
        })
    };
    let mut tls =
        ClientTlsConfig::new().ca_certificate(Certificate::from_pem(read("--tls-ca", ca)?));
    if let Some(name) = &args.tls_server_name {
        tls = tls.domain_name(name.clone());
    }
    if let (Some(cert), Some(key)) = (&args.tls_client_cert, &args.tls_client_key) {
        tls = tls.identity(Identity::from_pem(
            read("--tls-client-cert", cert)?,
            read("--tls-client-key", key)?,
        ));
    }
    Ok(Some(tls))
}

/// The token interceptor of `args`.
fn bearer(args: &ConnectArgs) -> Result<Bearer, CliError> {
    match &args.token {
        None => Ok(Bearer(None)),
        Some(t) => format!("Bearer {}", t.trim())
            .parse::<MetadataValue<Ascii>>()
            .map(|v| Bearer(Some(v)))
            .map_err(|_| {
                CliError::BadInput(
                    "--token: not a valid metadata value (printable ASCII, no line breaks)".into(),
                )
            }),
    }
}

/// Connects to `target` (HOST:PORT) within `timeout`, with the TLS and
/// token of `security`.
pub(crate) async fn connect(
    target: &str,
    timeout: Duration,
    security: &ConnectArgs,
) -> Result<Connection, CliError> {
    let tls = client_tls(security)?;
    let token = bearer(security)?;
    let with_tls = tls.is_some();
    let uri = target_uri(target, with_tls)?;
    let mut endpoint = Endpoint::from_shared(uri)
        .map_err(|e| CliError::BadInput(format!("--target `{target}`: {}", error_chain(&e))))?
        .connect_timeout(timeout)
        .tcp_nodelay(true);
    if let Some(tls) = tls {
        endpoint = endpoint
            .tls_config(tls)
            .map_err(|e| CliError::BadInput(format!("TLS options: {}", error_chain(&e))))?;
    }
    match tokio::time::timeout(timeout, endpoint.connect()).await {
        Ok(Ok(c)) => Ok(InterceptedService::new(c, token)),
        Ok(Err(e)) => {
            let text = error_chain(&e);
            Err(CliError::Failure(format!(
                "cannot connect to {target}: {text}{}",
                tls_hint(&text, with_tls)
            )))
        }
        Err(_) => Err(CliError::Failure(format!(
            "cannot connect to {target}: no answer within {:.1} s",
            timeout.as_secs_f64()
        ))),
    }
}

/// What a connection or call error most likely means for TLS, as a
/// sentence to append to the error (empty when it is not about TLS):
/// `text` the error, `with_tls` whether the client used TLS.
pub(crate) fn tls_hint(text: &str, with_tls: bool) -> &'static str {
    if text.contains("CaUsedAsEndEntity") {
        "; the server's certificate is a CA certificate (what `openssl req -x509` makes), \
         which TLS refuses as a server's: make a test CA and a server certificate signed by \
         it (README, Security)"
    } else if with_tls && text.contains("InvalidContentType") {
        "; the server answered in plaintext: it does not use TLS (leave out --tls-ca)"
    } else if text.contains("Connection refused") {
        ""
    } else if !with_tls
        && ["transport error", "connection reset", "h2 protocol error"]
            .iter()
            .any(|m| text.contains(m))
    {
        "; if the server uses TLS, connect with --tls-ca CA.pem"
    } else {
        ""
    }
}

/// The health of `service` ("" for the whole server) on `channel`.
pub(crate) async fn health(
    channel: Connection,
    service: &str,
    timeout: Duration,
) -> Result<tonic_health::pb::health_check_response::ServingStatus, tonic::Status> {
    use tonic_health::pb::health_check_response::ServingStatus;
    let mut client = tonic_health::pb::health_client::HealthClient::new(channel);
    let req = tonic_health::pb::HealthCheckRequest {
        service: service.to_string(),
    };
    let call = client.check(req);
    let r = tokio::time::timeout(timeout, call)
        .await
        .map_err(|_| tonic::Status::deadline_exceeded("no health answer in time"))??;
    Ok(ServingStatus::try_from(r.into_inner().status).unwrap_or(ServingStatus::Unknown))
}

// ---------------------------------------------------------------------
// Running one session or batch client
// ---------------------------------------------------------------------

/// One session or batch client: what it is and what it got.
#[derive(Debug, Clone)]
pub struct Track {
    /// Index among sessions, then batch clients.
    pub index: usize,
    /// Its kind.
    pub kind: Kind,
    /// Index of its target.
    pub target: usize,
    /// Round trip of every completed step \[s\].
    pub latencies_s: Vec<f64>,
    /// Fingerprint of every completed step's answer.
    pub digests: Vec<Digest32>,
    /// The server's own time of each completed session step that reports
    /// one \[s\]: a wheel/rail step's search, geometry and solve
    /// (`WheelRailTiming`, summed over the threads that solved it), a
    /// patch step's `solve_time_s`.
    pub server_s: Vec<f64>,
    /// Failures (the track stops at the first).
    pub errors: Vec<String>,
    /// A wheel/rail session's `force_tolerance_of_wheel_load`.
    pub force_tolerance_of_wheel_load: Option<f64>,
}

/// When a track has to stop.
#[derive(Clone, Copy)]
struct Limits {
    steps: u64,
    deadline: Option<Instant>,
}

impl Limits {
    fn go_on(&self, k: u64) -> bool {
        k < self.steps
            && self.deadline.is_none_or(|d| Instant::now() < d)
            && !INTERRUPTED.load(Ordering::Relaxed)
    }
}

/// Set by the first Ctrl-C: every track stops after its step under way,
/// the report is made of what was done (a second Ctrl-C exits at once).
static INTERRUPTED: AtomicBool = AtomicBool::new(false);

/// Watches for Ctrl-C: the first sets [`INTERRUPTED`] and says so, the
/// second exits with 130 (128 + SIGINT).
fn watch_interrupts() {
    tokio::spawn(async {
        if tokio::signal::ctrl_c().await.is_err() {
            return;
        }
        INTERRUPTED.store(true, Ordering::Relaxed);
        eprintln!(
            "loadtest: interrupted: finishing the steps under way and reporting what was done \
             (Ctrl-C again to exit at once)"
        );
        if tokio::signal::ctrl_c().await.is_ok() {
            eprintln!("loadtest: interrupted twice: exiting without a report");
            std::process::exit(130);
        }
    });
}

fn session_label(run: &str, index: usize, kind: Kind) -> String {
    format!("{run}-{index}-{}", kind.name().replace(':', "-"))
}

fn with_session_header<T>(msg: T, label: &str) -> tonic::Request<T> {
    let mut req = tonic::Request::new(msg);
    if let Ok(v) = label.parse::<tonic::metadata::MetadataValue<tonic::metadata::Ascii>>() {
        req.metadata_mut().insert(SESSION_HEADER, v.clone());
        req.metadata_mut().insert("x-request-id", v);
    }
    req
}

/// Runs track `t` on `client` within `limits`; `tick` after every step.
async fn run_track(
    mut client: Client,
    mut t: Track,
    run: &str,
    limits: Limits,
    batch_items: usize,
    tick: &(dyn Fn() + Sync),
) -> Track {
    let label = session_label(run, t.index, t.kind);
    let r = match t.kind {
        Kind::WheelRail(model) => {
            wheelrail_session(&mut client, &mut t, &label, model, limits, tick).await
        }
        Kind::Patch(model, grid) => {
            patch_session(&mut client, &mut t, &label, model, grid, limits, tick).await
        }
        Kind::WheelRailBatch | Kind::PatchBatch => {
            batch_client(&mut client, &mut t, limits, batch_items, tick).await
        }
    };
    if let Err(e) = r {
        t.errors.push(e);
    }
    t
}

fn status_text(s: &tonic::Status) -> String {
    format!("{:?}: {}", s.code(), s.message())
}

fn item_error(e: &pb::ItemError) -> String {
    format!("code {}: {} ({})", e.code, e.message, e.field)
}

/// What a session's answer was.
enum Answer {
    /// The session is open.
    Opened,
    /// A step's result, fingerprinted, with the server's time in it (the
    /// solve time it reports, when it reports one) \[s\].
    Step(Digest32, Option<f64>),
    /// A step refused in-band.
    Refused(String),
    /// Anything else.
    Unexpected(String),
}

/// How a session talks: its open request, the call that starts its
/// stream (with the session header `label`), step `k`'s request, and how
/// to read a response.
struct Protocol<'a, Req, Call, Step, Read> {
    label: &'a str,
    open: Req,
    call: Call,
    step: Step,
    answer: Read,
}

/// Opens refused with RESOURCE_EXHAUSTED (the server's session or queue
/// limit) are tried again this many times.
const OPEN_RETRIES: u64 = 12;
/// The first pause before opening again; it doubles up to [`OPEN_MAX_PAUSE`].
const OPEN_FIRST_PAUSE: Duration = Duration::from_millis(20);
/// The longest pause between two opens (about 20 s in all over the retries).
const OPEN_MAX_PAUSE: Duration = Duration::from_secs(2);

/// A number in [0, 1) from `seed` (splitmix64): spreads the retries of
/// many sessions without a random-number crate.
fn unit_jitter(seed: u64) -> f64 {
    let mut z = seed.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    (z ^ (z >> 31)) as f64 / (u64::MAX as f64 + 1.0)
}

/// The step loop shared by both kinds of session.
async fn drive_session<Req, Resp, Call, Fut, Step, Read>(
    t: &mut Track,
    limits: Limits,
    tick: &(dyn Fn() + Sync),
    p: Protocol<'_, Req, Call, Step, Read>,
) -> Result<(), String>
where
    Req: Clone + Send + 'static,
    Call: Fn(tonic::Request<ReceiverStream<Req>>) -> Fut,
    Fut: std::future::Future<
        Output = Result<tonic::Response<tonic::Streaming<Resp>>, tonic::Status>,
    >,
    Step: Fn(u64) -> Req,
    Read: Fn(Resp) -> Answer,
{
    let Protocol {
        label,
        open,
        call,
        step,
        answer,
    } = p;
    // A server at its session or queue limit answers RESOURCE_EXHAUSTED:
    // open again after a pause that doubles, with jitter, up to
    // OPEN_RETRIES times.
    let mut pause = OPEN_FIRST_PAUSE;
    let mut tries = 0;
    let (tx, mut stream) = loop {
        let (tx, rx) = mpsc::channel(2);
        let _ = tx.send(open.clone()).await;
        let refusal = match call(with_session_header(ReceiverStream::new(rx), label)).await {
            Ok(response) => {
                let mut stream = response.into_inner();
                match stream.message().await {
                    Ok(Some(r)) => match answer(r) {
                        Answer::Opened => break (tx, stream),
                        Answer::Refused(e) | Answer::Unexpected(e) => {
                            return Err(format!("open: {e}"))
                        }
                        Answer::Step(..) => return Err("open: answered with a step".into()),
                    },
                    Ok(None) => return Err("open: the server ended the stream".into()),
                    Err(s) => s,
                }
            }
            Err(s) => s,
        };
        tries += 1;
        if refusal.code() != tonic::Code::ResourceExhausted || tries > OPEN_RETRIES {
            return Err(format!("open: {}", status_text(&refusal)));
        }
        let jitter = 0.5 + 0.5 * unit_jitter(t.index as u64 * 31 + tries);
        tokio::time::sleep(pause.mul_f64(jitter)).await;
        pause = (pause * 2).min(OPEN_MAX_PAUSE);
    };
    let mut k = 0;
    while limits.go_on(k) {
        let t0 = Instant::now();
        if tx.send(step(k)).await.is_err() {
            return Err(format!("step {k}: the stream closed"));
        }
        let response = stream.message().await;
        let dt = t0.elapsed().as_secs_f64();
        match response.map(|r| r.map(&answer)) {
            Ok(Some(Answer::Step(d, server_s))) => {
                t.latencies_s.push(dt);
                t.digests.push(d);
                t.server_s.extend(server_s);
            }
            Ok(Some(Answer::Refused(e) | Answer::Unexpected(e))) => {
                return Err(format!("step {k}: {e}"))
            }
            Ok(Some(Answer::Opened)) => return Err(format!("step {k}: answered with `opened`")),
            Ok(None) => return Err(format!("step {k}: the server ended the stream")),
            Err(s) => return Err(format!("step {k}: {}", status_text(&s))),
        }
        tick();
        k += 1;
    }
    Ok(())
}

async fn wheelrail_session(
    client: &mut Client,
    t: &mut Track,
    label: &str,
    model: pb::WheelRailModel,
    limits: Limits,
    tick: &(dyn Fn() + Sync),
) -> Result<(), String> {
    use pb::wheel_rail_session_request::Kind as In;
    use pb::wheel_rail_session_response::Kind as Out;
    let open = pb::WheelRailSessionRequest {
        kind: Some(In::Open(pb::WheelRailSessionOpen {
            pair_id: BUILTIN_PAIR.into(),
            model: model as i32,
            sides: pb::WheelSides::Both as i32,
            client_label: label.to_string(),
            force_tolerance_of_wheel_load: t.force_tolerance_of_wheel_load,
            ..Default::default()
        })),
    };
    let i = t.index;
    let step = |k: u64| {
        let (position, velocity, load) = wheelset_state(i, k);
        pb::WheelRailSessionRequest {
            kind: Some(In::Step(pb::WheelRailSessionStep {
                step_index: k,
                time_s: k as f64 * DT_S,
                position,
                velocity,
                load,
                mark: false,
            })),
        }
    };
    let answer = |r: pb::WheelRailSessionResponse| match r.kind {
        Some(Out::Opened(_)) => Answer::Opened,
        Some(Out::Step(pb::WheelRailSessionStepResult {
            result: Some(result),
            ..
        })) => {
            let server_s = result.timing.map(|t| t.search_s + t.geometry_s + t.solve_s);
            Answer::Step(wheelrail_digest(result), server_s)
        }
        Some(Out::Error(e)) => Answer::Refused(item_error(&e)),
        other => Answer::Unexpected(format!("unexpected answer {other:?}")),
    };
    let call = |req| {
        let mut c = client.clone();
        async move { c.wheel_rail_session(req).await }
    };
    let p = Protocol {
        label,
        open,
        call,
        step,
        answer,
    };
    drive_session(t, limits, tick, p).await
}

async fn patch_session(
    client: &mut Client,
    t: &mut Track,
    label: &str,
    model: pb::Model,
    grid: Option<u32>,
    limits: Limits,
    tick: &(dyn Fn() + Sync),
) -> Result<(), String> {
    use pb::session_request::Kind as In;
    use pb::session_response::Kind as Out;
    let case = patch_case(model, grid, creepages(t.index, 0), patch_load(0));
    let open = pb::SessionRequest {
        kind: Some(In::Open(pb::SessionOpen {
            case: Some(case),
            client_label: label.to_string(),
            ..Default::default()
        })),
    };
    let i = t.index;
    let step = |k: u64| pb::SessionRequest {
        kind: Some(In::Step(pb::SessionStep {
            step_index: k,
            time_s: k as f64 * DT_S,
            load: Some(pb::session_step::Load::NormalForceN(patch_load(k))),
            creepages: Some(creepages(i, k)),
            ..Default::default()
        })),
    };
    let answer = |r: pb::SessionResponse| match r.kind {
        Some(Out::Opened(_)) => Answer::Opened,
        Some(Out::Step(pb::SessionStepResult {
            result: Some(result),
            ..
        })) => {
            let server_s = result.info.as_ref().map(|i| i.solve_time_s);
            Answer::Step(step_digest(result), server_s)
        }
        Some(Out::Error(e)) => Answer::Refused(item_error(&e)),
        other => Answer::Unexpected(format!("unexpected answer {other:?}")),
    };
    let call = |req| {
        let mut c = client.clone();
        async move { c.patch_session(req).await }
    };
    let p = Protocol {
        label,
        open,
        call,
        step,
        answer,
    };
    drive_session(t, limits, tick, p).await
}

/// Batch `k` of a batch client: `items` wheelsets (or patches) at step k,
/// each with its own phase.
async fn batch_call(
    client: &mut Client,
    kind: Kind,
    k: u64,
    items: usize,
) -> Result<Digest32, String> {
    match kind {
        Kind::WheelRailBatch => {
            let req = pb::SolveWheelRailBatchRequest {
                items: (0..items)
                    .map(|i| wheelrail_query(i, k, pb::WheelRailModel::HertzFastsim))
                    .collect(),
            };
            let mut r = client
                .solve_wheel_rail_batch(req)
                .await
                .map_err(|s| status_text(&s))?
                .into_inner();
            for item in &mut r.items {
                match &mut item.outcome {
                    Some(pb::wheel_rail_batch_item::Outcome::Result(res)) => res.timing = None,
                    Some(pb::wheel_rail_batch_item::Outcome::Error(e)) => {
                        return Err(format!("item {}: {}", item.index, item_error(e)))
                    }
                    None => return Err(format!("item {}: empty", item.index)),
                }
            }
            Ok(digest(&r.encode_to_vec()))
        }
        Kind::PatchBatch => {
            let req = pb::SolvePatchBatchRequest {
                items: (0..items)
                    .map(|i| pb::SolvePatchRequest {
                        case: Some(patch_case(
                            pb::Model::Fastsim,
                            None,
                            creepages(i, k),
                            patch_load(k),
                        )),
                        ..Default::default()
                    })
                    .collect(),
            };
            let mut r = client
                .solve_patch_batch(req)
                .await
                .map_err(|s| status_text(&s))?
                .into_inner();
            for item in &mut r.items {
                match &mut item.outcome {
                    Some(pb::batch_item_result::Outcome::Result(res)) => clear_patch_timing(res),
                    Some(pb::batch_item_result::Outcome::Error(e)) => {
                        return Err(format!("item {}: {}", item.index, item_error(e)))
                    }
                    None => return Err(format!("item {}: empty", item.index)),
                }
            }
            Ok(digest(&r.encode_to_vec()))
        }
        _ => Err("not a batch kind".into()),
    }
}

async fn batch_client(
    client: &mut Client,
    t: &mut Track,
    limits: Limits,
    items: usize,
    tick: &(dyn Fn() + Sync),
) -> Result<(), String> {
    let mut k = 0;
    while limits.go_on(k) {
        let t0 = Instant::now();
        let d = batch_call(client, t.kind, k, items)
            .await
            .map_err(|e| format!("batch {k}: {e}"))?;
        t.latencies_s.push(t0.elapsed().as_secs_f64());
        t.digests.push(d);
        tick();
        k += 1;
    }
    Ok(())
}

// ---------------------------------------------------------------------
// Statistics and the report
// ---------------------------------------------------------------------

/// Latency figures of a set of samples \[s\].
#[derive(Debug, Clone, Default, Serialize)]
pub struct Latency {
    /// Median.
    pub p50_s: f64,
    /// 90th percentile.
    pub p90_s: f64,
    /// 99th percentile.
    pub p99_s: f64,
    /// Largest.
    pub max_s: f64,
    /// Mean.
    pub mean_s: f64,
}

impl Latency {
    /// Nearest-rank percentiles of `samples` (all 0 when empty).
    pub fn of(samples: &[f64]) -> Latency {
        if samples.is_empty() {
            return Latency::default();
        }
        let mut s = samples.to_vec();
        s.sort_by(f64::total_cmp);
        let rank = |p: f64| s[((p * s.len() as f64).ceil() as usize).clamp(1, s.len()) - 1];
        Latency {
            p50_s: rank(0.50),
            p90_s: rank(0.90),
            p99_s: rank(0.99),
            max_s: s[s.len() - 1],
            mean_s: s.iter().sum::<f64>() / s.len() as f64,
        }
    }
}

/// Figures of one kind (or one target).
#[derive(Debug, Clone, Serialize)]
pub struct Breakdown {
    /// Sessions (or batch clients) of this kind.
    pub clients: usize,
    /// Completed steps (batch calls).
    pub steps: usize,
    /// Latency.
    #[serde(flatten)]
    pub latency: Latency,
    /// The server's own time in the steps that report it (sessions:
    /// [`Track::server_s`]); the latency less it is the transport's and
    /// the service's share. None where no step reports one (batch calls).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub server: Option<Latency>,
    /// Steps per second of the run's wall time.
    pub throughput_per_s: f64,
    /// Failed sessions or calls.
    pub errors: usize,
    /// Steps whose answer differed from the baseline replay.
    pub mismatches: usize,
}

/// The whole report (`--json`).
#[derive(Debug, Clone, Serialize)]
pub struct Report {
    /// The targets, in the order sessions were spread over them.
    pub target_addrs: Vec<String>,
    /// Sessions.
    pub sessions: usize,
    /// Batch clients.
    pub batch_clients: usize,
    /// Queries per batch call.
    pub batch_items: usize,
    /// Step limit per session.
    pub steps_per_session: u64,
    /// Time limit \[s\].
    pub seconds_limit: f64,
    /// The mix asked for.
    pub mix: String,
    /// The wheel/rail sessions' `force_tolerance_of_wheel_load`.
    pub force_tolerance_of_wheel_load: Option<f64>,
    /// Wall time of the concurrent run \[s\].
    pub wall_s: f64,
    /// Completed steps and batch calls.
    pub steps: usize,
    /// Latency of all of them.
    #[serde(flatten)]
    pub latency: Latency,
    /// Steps and batch calls per second.
    pub throughput_per_s: f64,
    /// Failed sessions, steps and calls (concurrent run and baseline).
    pub errors: usize,
    /// Steps that differed from the baseline replay.
    pub mismatches: usize,
    /// Steps compared with the baseline.
    pub verified_steps: usize,
    /// Wall time of the baseline replay \[s\].
    pub baseline_s: f64,
    /// Whether Ctrl-C stopped the run: the figures are of the steps done
    /// before it, and they were not replayed against the baseline.
    pub interrupted: bool,
    /// Per kind.
    pub kinds: BTreeMap<String, Breakdown>,
    /// Per target (by address).
    pub targets: BTreeMap<String, Breakdown>,
    /// The first failures, for people (at most 10).
    pub first_errors: Vec<String>,
}

fn breakdown<'a>(tracks: impl Iterator<Item = (&'a Track, usize)>, wall_s: f64) -> Breakdown {
    let (mut samples, mut server) = (Vec::new(), Vec::new());
    let (mut clients, mut errors, mut mismatches) = (0, 0, 0);
    for (t, m) in tracks {
        clients += 1;
        samples.extend_from_slice(&t.latencies_s);
        server.extend_from_slice(&t.server_s);
        errors += t.errors.len();
        mismatches += m;
    }
    Breakdown {
        clients,
        steps: samples.len(),
        latency: Latency::of(&samples),
        server: (!server.is_empty()).then(|| Latency::of(&server)),
        throughput_per_s: if wall_s > 0.0 {
            samples.len() as f64 / wall_s
        } else {
            0.0
        },
        errors,
        mismatches,
    }
}

/// Replays every track's completed steps on `client`, four tracks at a
/// time per core of this machine (each track alone on its own stream, one
/// step after the other, as in the run: a few in flight keep the server's
/// workers busy between round trips); returns per track the mismatching
/// steps and the baseline's errors.
async fn baseline(
    client: &mut Client,
    tracks: &[Track],
    run: &str,
    batch_items: usize,
    bar: &ProgressBar,
) -> (Vec<usize>, Vec<String>) {
    let lanes = std::thread::available_parallelism()
        .map_or(1, |n| 4 * n.get())
        .clamp(1, tracks.len().max(1));
    let shared: Arc<Vec<Track>> = Arc::new(tracks.to_vec());
    let label = format!("{run}-baseline");
    let mut tasks = Vec::with_capacity(lanes);
    for lane in 0..lanes {
        let (tracks, client, bar, label) =
            (shared.clone(), client.clone(), bar.clone(), label.clone());
        tasks.push(tokio::spawn(async move {
            let mut out = Vec::new();
            for i in (lane..tracks.len()).step_by(lanes) {
                let r = replay_track(&client, &tracks[i], &label, batch_items, &bar).await;
                out.push((i, r));
            }
            out
        }));
    }
    let mut per_track = vec![(0, Vec::new()); tracks.len()];
    for task in tasks {
        match task.await {
            Ok(done) => {
                for (i, r) in done {
                    per_track[i] = r;
                }
            }
            Err(e) => per_track[0].1.push(format!("a baseline task failed: {e}")),
        }
    }
    let mismatches = per_track.iter().map(|(m, _)| *m).collect();
    let errors = per_track.into_iter().flat_map(|(_, e)| e).collect();
    (mismatches, errors)
}

/// Replays one track; its mismatching steps and the baseline's errors.
async fn replay_track(
    client: &Client,
    t: &Track,
    label: &str,
    batch_items: usize,
    bar: &ProgressBar,
) -> (usize, Vec<String>) {
    let steps = t.digests.len() as u64;
    let replay = Track {
        latencies_s: Vec::new(),
        server_s: Vec::new(),
        digests: Vec::new(),
        errors: Vec::new(),
        ..t.clone()
    };
    if steps == 0 {
        return (0, Vec::new());
    }
    let tick = || bar.inc(1);
    let limits = Limits {
        steps,
        deadline: None,
    };
    let replay = run_track(client.clone(), replay, label, limits, batch_items, &tick).await;
    let errors = replay
        .errors
        .iter()
        .map(|e| format!("baseline of #{} ({}): {e}", t.index, t.kind.name()))
        .collect();
    let m = t
        .digests
        .iter()
        .enumerate()
        .filter(|(k, d)| replay.digests.get(*k) != Some(d))
        .count();
    // Steps the baseline could not replay are its errors, not mismatches.
    let unreplayed = t.digests.len() - replay.digests.len().min(t.digests.len());
    (m - unreplayed, errors)
}

fn bar(total: u64, hidden: bool, what: &str) -> ProgressBar {
    let target = if hidden || !std::io::stderr().is_terminal() {
        ProgressDrawTarget::hidden()
    } else {
        ProgressDrawTarget::stderr()
    };
    let pb = ProgressBar::with_draw_target(Some(total), target);
    let style = ProgressStyle::with_template(&format!(
        "{what} {{elapsed_precise}} [{{bar:40}}] {{pos}}/{{len}} steps, eta {{eta}}"
    ))
    .unwrap_or_else(|_| ProgressStyle::default_bar())
    .progress_chars("=> ");
    pb.set_style(style);
    pb
}

/// Runs the load test of `args` on the current runtime.
pub async fn load(args: &LoadtestArgs) -> Result<Report, CliError> {
    let kinds =
        assign(&args.mix, args.sessions).map_err(|e| CliError::BadInput(format!("--mix: {e}")))?;
    if args.sessions + args.batch_clients == 0 {
        return Err(CliError::BadInput(
            "nothing to run: --sessions and --batch-clients are both 0".into(),
        ));
    }
    let positive = |v: f64| v.is_finite() && v > 0.0;
    if !positive(args.seconds) || !positive(args.connect_timeout) {
        return Err(CliError::BadInput(
            "--seconds and --connect-timeout must be > 0".into(),
        ));
    }
    if args.batch_clients > 0 && args.batch_items == 0 {
        return Err(CliError::BadInput("--batch-items must be >= 1".into()));
    }
    let targets: Vec<String> = args
        .target
        .iter()
        .map(|t| t.trim().to_string())
        .filter(|t| !t.is_empty())
        .collect();
    if targets.is_empty() {
        return Err(CliError::BadInput("--target: no address given".into()));
    }
    for t in &targets {
        target_uri(t, args.security.tls_ca.is_some())?;
    }
    // Every target reachable and its contact service serving (not
    // draining) before any load.
    let timeout = Duration::from_secs_f64(args.connect_timeout);
    for t in &targets {
        let channel = connect(t, timeout, &args.security).await?;
        use tonic_health::pb::health_check_response::ServingStatus;
        match health(channel, CONTACT_SERVICE, timeout).await {
            Ok(ServingStatus::Serving) => {}
            Ok(s) => {
                return Err(CliError::Failure(format!(
                    "{t} is not serving (health: {})",
                    s.as_str_name()
                )))
            }
            Err(s) => {
                return Err(CliError::Failure(format!(
                    "{t}: health check failed: {}",
                    status_text(&s)
                )))
            }
        }
    }

    let run = format!(
        "lt{}-{}",
        std::process::id(),
        std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map(|d| d.as_millis() % 1_000_000)
            .unwrap_or(0)
    );
    let mut tracks: Vec<Track> = kinds
        .iter()
        .enumerate()
        .map(|(i, &kind)| (i, kind))
        .chain((0..args.batch_clients).map(|b| {
            let kind = if b % 2 == 0 {
                Kind::WheelRailBatch
            } else {
                Kind::PatchBatch
            };
            (args.sessions + b, kind)
        }))
        .map(|(index, kind)| Track {
            index,
            kind,
            target: index % targets.len(),
            latencies_s: Vec::new(),
            server_s: Vec::new(),
            digests: Vec::new(),
            errors: Vec::new(),
            force_tolerance_of_wheel_load: match kind {
                Kind::WheelRail(_) => args.force_tolerance_of_wheel_load,
                _ => None,
            },
        })
        .collect();

    // One connection per session and batch client.
    let mut clients = Vec::with_capacity(tracks.len());
    for t in &tracks {
        let channel = connect(&targets[t.target], timeout, &args.security).await?;
        clients.push(
            ContactServiceClient::new(channel)
                .max_decoding_message_size(64 << 20)
                .max_encoding_message_size(64 << 20),
        );
    }

    watch_interrupts();
    let total = tracks.len() as u64 * args.steps;
    let progress = Arc::new(bar(total, args.json, "load"));
    let start = Instant::now();
    let limits = Limits {
        steps: args.steps,
        deadline: Some(start + Duration::from_secs_f64(args.seconds)),
    };
    let mut handles = Vec::with_capacity(tracks.len());
    for (t, client) in tracks.drain(..).zip(clients) {
        let progress = progress.clone();
        let run = run.clone();
        let items = args.batch_items;
        handles.push(tokio::spawn(async move {
            let tick = move || progress.inc(1);
            run_track(client, t, &run, limits, items, &tick).await
        }));
    }
    for h in handles {
        match h.await {
            Ok(t) => tracks.push(t),
            Err(e) => return Err(CliError::Failure(format!("a client task failed: {e}"))),
        }
    }
    let wall_s = start.elapsed().as_secs_f64();
    progress.finish_and_clear();

    // The baseline replay on one connection to the first target (not
    // after Ctrl-C: the user wants the figures now).
    let done: u64 = tracks.iter().map(|t| t.digests.len() as u64).sum();
    let interrupted = INTERRUPTED.load(Ordering::Relaxed);
    let (mismatches, baseline_errors, baseline_s, verified) = if interrupted {
        (vec![0; tracks.len()], Vec::new(), 0.0, 0)
    } else {
        let verify_bar = bar(done, args.json, "verify");
        let mut client =
            ContactServiceClient::new(connect(&targets[0], timeout, &args.security).await?)
                .max_decoding_message_size(64 << 20)
                .max_encoding_message_size(64 << 20);
        let b0 = Instant::now();
        let (mismatches, errors) =
            baseline(&mut client, &tracks, &run, args.batch_items, &verify_bar).await;
        verify_bar.finish_and_clear();
        (
            mismatches,
            errors,
            b0.elapsed().as_secs_f64(),
            done as usize,
        )
    };
    // A Ctrl-C during the replay stops it: then nothing counts as checked.
    let (interrupted, verified) = match INTERRUPTED.load(Ordering::Relaxed) {
        true => (true, 0),
        false => (false, verified),
    };

    let mut report = Report {
        target_addrs: targets.clone(),
        sessions: args.sessions,
        batch_clients: args.batch_clients,
        batch_items: args.batch_items,
        steps_per_session: args.steps,
        seconds_limit: args.seconds,
        mix: args.mix.clone(),
        force_tolerance_of_wheel_load: args.force_tolerance_of_wheel_load,
        wall_s,
        steps: 0,
        latency: Latency::default(),
        throughput_per_s: 0.0,
        errors: 0,
        mismatches: 0,
        verified_steps: verified,
        baseline_s,
        interrupted,
        kinds: BTreeMap::new(),
        targets: BTreeMap::new(),
        first_errors: Vec::new(),
    };
    let all = breakdown(tracks.iter().zip(mismatches.iter().copied()), wall_s);
    report.steps = all.steps;
    report.latency = all.latency;
    report.throughput_per_s = all.throughput_per_s;
    report.errors = all.errors + baseline_errors.len();
    report.mismatches = all.mismatches;
    let mut kind_names: Vec<(Kind, String)> =
        tracks.iter().map(|t| (t.kind, t.kind.name())).collect();
    kind_names.sort();
    kind_names.dedup();
    for (kind, name) in kind_names {
        let b = breakdown(
            tracks
                .iter()
                .zip(mismatches.iter().copied())
                .filter(|(t, _)| t.kind == kind),
            wall_s,
        );
        report.kinds.insert(name, b);
    }
    for (i, addr) in targets.iter().enumerate() {
        let b = breakdown(
            tracks
                .iter()
                .zip(mismatches.iter().copied())
                .filter(|(t, _)| t.target == i),
            wall_s,
        );
        report.targets.insert(addr.clone(), b);
    }
    for t in &tracks {
        for e in &t.errors {
            report.first_errors.push(format!(
                "#{} ({}) on {}: {e}",
                t.index,
                t.kind.name(),
                targets[t.target]
            ));
        }
    }
    for (t, &m) in tracks.iter().zip(&mismatches) {
        if m > 0 {
            report.first_errors.push(format!(
                "#{} ({}) on {}: {m} of {} steps differ from the baseline replay",
                t.index,
                t.kind.name(),
                targets[t.target],
                t.digests.len()
            ));
        }
    }
    report.first_errors.extend(baseline_errors);
    report.first_errors.truncate(10);
    Ok(report)
}

/// `n` with its noun: "1 session", "4 sessions".
fn counted(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

fn ms(s: f64) -> String {
    format!("{:.3}", s * 1e3)
}

/// The readable table of a report.
pub fn table(r: &Report) -> String {
    use std::fmt::Write as _;
    let mut out = String::new();
    let _ = writeln!(
        out,
        "railcontact loadtest: {} on {}; mix {}",
        counted(r.sessions, "session", "sessions")
            + &match r.batch_clients {
                0 => String::new(),
                n => format!(
                    " + {} ({} items)",
                    counted(n, "batch client", "batch clients"),
                    r.batch_items
                ),
            },
        r.target_addrs.join(", "),
        r.mix
    );
    let _ = writeln!(
        out,
        "up to {} steps each, at most {} s; ran {:.2} s, baseline {:.2} s\n",
        r.steps_per_session, r.seconds_limit, r.wall_s, r.baseline_s
    );
    let _ = writeln!(
        out,
        "{:<32} {:>7} {:>7} {:>9} {:>9} {:>9} {:>9} {:>9} {:>10} {:>6} {:>6}",
        "kind",
        "clients",
        "steps",
        "p50 ms",
        "p90 ms",
        "p99 ms",
        "max ms",
        "mean ms",
        "steps/s",
        "errors",
        "mism."
    );
    let row = |out: &mut String, name: &str, b: &Breakdown| {
        let _ = writeln!(
            out,
            "{:<32} {:>7} {:>7} {:>9} {:>9} {:>9} {:>9} {:>9} {:>10.1} {:>6} {:>6}",
            name,
            b.clients,
            b.steps,
            ms(b.latency.p50_s),
            ms(b.latency.p90_s),
            ms(b.latency.p99_s),
            ms(b.latency.max_s),
            ms(b.latency.mean_s),
            b.throughput_per_s,
            b.errors,
            b.mismatches
        );
    };
    for (name, b) in &r.kinds {
        row(&mut out, name, b);
    }
    if r.targets.len() > 1 {
        for (name, b) in &r.targets {
            row(&mut out, &format!("target {name}"), b);
        }
    }
    let all = Breakdown {
        clients: r.sessions + r.batch_clients,
        steps: r.steps,
        latency: r.latency.clone(),
        server: None,
        throughput_per_s: r.throughput_per_s,
        errors: r.errors,
        mismatches: r.mismatches,
    };
    row(&mut out, "all", &all);
    let served: Vec<_> = r
        .kinds
        .iter()
        .filter_map(|(name, b)| b.server.as_ref().map(|s| (name, s)))
        .collect();
    if !served.is_empty() {
        let _ = writeln!(
            out,
            "\nthe server's own time in the session steps (a wheel/rail step's search, geometry \
             and solve, summed over its threads; a patch step's solve; the round trip less it is \
             the transport's and the service's):"
        );
        for (name, s) in served {
            let _ = writeln!(
                out,
                "{:<32} {:>7} {:>7} {:>9} {:>9} {:>9} {:>9} {:>9}",
                name,
                "",
                "",
                ms(s.p50_s),
                ms(s.p90_s),
                ms(s.p99_s),
                ms(s.max_s),
                ms(s.mean_s)
            );
        }
    }
    if r.interrupted {
        let _ = writeln!(
            out,
            "\ninterrupted by Ctrl-C after {:.2} s: the figures are of the {} steps done; they \
             were not checked against the baseline replay ({} errors)",
            r.wall_s, r.steps, r.errors
        );
    } else {
        let _ = writeln!(
            out,
            "\n{} steps checked against the baseline replay: {} mismatches, {} errors",
            r.verified_steps, r.mismatches, r.errors
        );
    }
    for e in &r.first_errors {
        let _ = writeln!(out, "  {e}");
    }
    out
}

/// `railcontact loadtest`: runs, prints, and fails when anything failed or
/// differed.
pub fn run(args: &LoadtestArgs) -> Result<(), CliError> {
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .worker_threads(2)
        .thread_name("railcontact-load")
        .build()
        .map_err(|e| CliError::Failure(format!("cannot start the runtime: {e}")))?;
    let report = runtime.block_on(load(args))?;
    let text = if args.json {
        let mut s = serde_json::to_string(&report)
            .map_err(|e| CliError::Failure(format!("cannot write the report: {e}")))?;
        s.push('\n');
        s
    } else {
        table(&report)
    };
    super::write_stdout(&text)?;
    if report.interrupted {
        return Err(CliError::Failure(format!(
            "interrupted by Ctrl-C after {:.2} s ({} steps done, not verified)",
            report.wall_s, report.steps
        )));
    }
    if report.errors > 0 || report.mismatches > 0 {
        return Err(CliError::Failure(format!(
            "{} errors, {} mismatches",
            report.errors, report.mismatches
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_mix_is_a_train_of_sixteen_wheelsets_and_two_patches() {
        let kinds = assign(DEFAULT_MIX, 16).unwrap();
        let count = |k: Kind| kinds.iter().filter(|&&x| x == k).count();
        assert_eq!(count(Kind::WheelRail(pb::WheelRailModel::HertzFastsim)), 12);
        assert_eq!(count(Kind::WheelRail(pb::WheelRailModel::Exact)), 2);
        assert_eq!(count(Kind::Patch(pb::Model::Exact, Some(40))), 1);
        assert_eq!(count(Kind::Patch(pb::Model::Fastsim, None)), 1);
        // Few sessions: each kind still once.
        let four = assign(DEFAULT_MIX, 4).unwrap();
        let mut names: Vec<String> = four.iter().map(Kind::name).collect();
        names.dedup();
        assert_eq!(names.len(), 4, "{names:?}");
        assert_eq!(assign("patch:exact40", 3).unwrap().len(), 3);
    }

    #[test]
    fn mix_errors_name_the_entry() {
        for (mix, needle) in [
            ("wheelrail:fast=1", "wheelrail:fast"),
            ("patch:exact2", "patch:exact2"),
            ("patch:fastsim=x", "weight"),
            ("patch:fastsim=0", "positive"),
            ("bogus", "bogus"),
            ("patch:fastsim,patch:fastsim", "twice"),
        ] {
            let e = assign(mix, 4).unwrap_err();
            assert!(e.contains(needle), "{mix}: {e}");
        }
        for k in [
            "wheelrail:auto",
            "wheelrail:hertz_fastsim_table",
            "wheelrail:hertz_polach",
            "patch:exact64",
            "patch:hertz",
        ] {
            assert_eq!(Kind::parse(k).unwrap().name(), k);
        }
    }

    #[test]
    fn percentiles_are_nearest_rank() {
        let s: Vec<f64> = (1..=100).map(f64::from).collect();
        let l = Latency::of(&s);
        assert_eq!(
            (l.p50_s, l.p90_s, l.p99_s, l.max_s),
            (50.0, 90.0, 99.0, 100.0)
        );
        let one = Latency::of(&[3.0]);
        assert_eq!((one.p50_s, one.p99_s, one.max_s), (3.0, 3.0, 3.0));
    }

    /// The errors seen connecting (2026-12-06, tonic 0.14 with rustls): a
    /// self-signed CA certificate on the server, a TLS client on a
    /// plaintext port, a plaintext client on a TLS port.
    #[test]
    fn tls_mistakes_get_a_hint() {
        let ca = "transport error: invalid peer certificate: Other(OtherError(CaUsedAsEndEntity))";
        assert!(tls_hint(ca, true).contains("test CA"));
        let plain = "transport error: received corrupt message of type InvalidContentType";
        assert!(tls_hint(plain, true).contains("does not use TLS"));
        for text in ["transport error", "h2 protocol error: http2 error"] {
            assert!(tls_hint(text, false).contains("--tls-ca"), "{text}");
        }
        assert_eq!(tls_hint("Unavailable: too busy", false), "");
        let refused = "transport error: tcp connect error: Connection refused (os error 111)";
        assert_eq!(tls_hint(refused, false), "");
    }

    #[test]
    fn targets_need_a_port() {
        assert_eq!(
            target_uri("127.0.0.1:1", false).unwrap(),
            "http://127.0.0.1:1"
        );
        assert_eq!(
            target_uri("localhost:1", true).unwrap(),
            "https://localhost:1"
        );
        assert!(target_uri("localhost", false).is_err());
        assert!(target_uri("http://[::1]:50051", false).is_ok());
    }
}
