//! No client can starve the others (issue 45): for each resource a client
//! could hoard, a hoarding client and a legitimate client that is still
//! served promptly, against small limits.
//!
//! - creep curves whose client reads nothing take at most the client's
//!   share of the solve queue (`client_max_admitted`), and are ended after
//!   `stream_write_timeout_s`, their slots freed;
//! - one client opens at most `client_max_sessions` sessions (clients
//!   told apart by their tokens);
//! - silent streams count against `client_max_streams` and `max_streams`,
//!   health checks answered at the cap, everything given back when the
//!   streams end;
//! - connections that never start a call are closed after
//!   `connection_first_call_timeout_s` (plain TCP and TLS), and an address
//!   holds at most `client_max_connections`, the server `max_connections`;
//! - a peer guessing tokens is slowed to `auth_failure_rate_per_s` after
//!   `auth_failure_burst`, and its refusals are logged at a bounded rate,
//!   while a known token from another address is served;
//! - behind a proxy of `trusted_proxies`, clients are told apart by the
//!   address it forwards (a guesser does not slow another client; the
//!   proxy's connections have no per-address share), and nobody else's
//!   `x-forwarded-for` is believed;
//! - a client with many solves waiting delays another client's solve by
//!   the one running and one more, not by all of them (the workers serve
//!   the clients in turn);
//! - viscoelastic coefficients whose callers gave up (their deadline
//!   passed) stop being integrated, and the workers are free for the next
//!   solve at once.
//!
//! Clients are told apart by address: the hoarders connect through a
//! relay ([`relay`]) whose connections to the server come from another
//! loopback address (127.0.0.2 to 127.0.0.4), or bind their sockets there.

use std::net::{IpAddr, SocketAddr};
use std::time::{Duration, Instant};

use railcontact::service::config::ServeConfig;
use railcontact::service::pb;
use railcontact::service::pb::contact_service_client::ContactServiceClient;
use railcontact::service::server::RunningServer;
use tokio::io::AsyncReadExt;
use tokio::net::{TcpListener, TcpSocket, TcpStream};
use tokio_stream::StreamExt;
use tonic::transport::{Channel, Endpoint};
use tonic::Code;

use crate::common;
use crate::support;
use common::{metrics_page, sphere, Client};

/// Listens on 127.0.0.1 and forwards each connection to `target` from a
/// socket bound to `source` (another loopback address), so that the
/// server sees the peer `source`. Runs until the test's runtime ends.
async fn relay(source: &str, target: SocketAddr) -> SocketAddr {
    let listener = TcpListener::bind("127.0.0.1:0").await.unwrap();
    let addr = listener.local_addr().unwrap();
    let source: IpAddr = source.parse().unwrap();
    tokio::spawn(async move {
        while let Ok((mut inbound, _)) = listener.accept().await {
            tokio::spawn(async move {
                let Ok(mut outbound) = connect_from(source, target).await else {
                    return;
                };
                let _ = tokio::io::copy_bidirectional(&mut inbound, &mut outbound).await;
            });
        }
    });
    addr
}

/// A TCP connection to `target` from `source`.
async fn connect_from(source: IpAddr, target: SocketAddr) -> std::io::Result<TcpStream> {
    let socket = TcpSocket::new_v4()?;
    socket.bind(SocketAddr::new(source, 0))?;
    socket.connect(target).await
}

/// A client of the server at `addr` on a connection of its own.
async fn client_at(addr: SocketAddr) -> Client {
    ContactServiceClient::new(channel_at(addr).await)
}

async fn channel_at(addr: SocketAddr) -> Channel {
    Endpoint::from_shared(format!("http://{addr}"))
        .unwrap()
        .connect()
        .await
        .expect("connects")
}

/// A server of `config` with a metrics port, pairs in memory.
async fn server(config: ServeConfig) -> RunningServer {
    common::server_with(ServeConfig {
        metrics_listen: Some("127.0.0.1:0".parse().unwrap()),
        ..config
    })
    .await
    .0
}

/// The value of the metric line `name` (with its labels, if any) on the
/// page; 0 when absent (a label set never counted).
async fn metric(server: &RunningServer, name: &str) -> f64 {
    let page = metrics_page(server.metrics_addr.expect("a metrics port")).await;
    page.lines()
        .find_map(|l| l.strip_prefix(&format!("{name} ")))
        .map_or(0.0, |v| v.trim().parse().unwrap())
}

/// `railcontact_quota_refused_total` of the setting `quota`.
async fn refused(server: &RunningServer, quota: &str) -> f64 {
    metric(
        server,
        &format!("railcontact_quota_refused_total{{quota=\"{quota}\"}}"),
    )
    .await
}

/// Polls `condition` every 50 ms for at most `limit`; whether it held.
async fn eventually<F, Fut>(limit: Duration, mut condition: F) -> bool
where
    F: FnMut() -> Fut,
    Fut: std::future::Future<Output = bool>,
{
    let t0 = Instant::now();
    while t0.elapsed() < limit {
        if condition().await {
            return true;
        }
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
    false
}

fn solve_request(case: pb::PatchCase) -> pb::SolvePatchRequest {
    pb::SolvePatchRequest {
        case: Some(case),
        ..Default::default()
    }
}

/// `sphere` with the exact model on n x n in steady rolling, mu = 0.3.
fn rolling(n: u32, creepage_long: f64) -> pb::PatchCase {
    common::rolling(pb::Model::Exact, n, creepage_long)
}

/// The legitimate client's check: a small solve answered within
/// `limit`.
async fn served_within(client: &mut Client, limit: Duration) {
    let t0 = Instant::now();
    let r = tokio::time::timeout(
        limit,
        client.solve_patch(solve_request(sphere(pb::Model::Hertz, 8))),
    )
    .await
    .unwrap_or_else(|_| panic!("not answered within {limit:?}"));
    r.unwrap_or_else(|s| panic!("refused after {:?}: {s:?}", t0.elapsed()));
}

fn assert_exhausted(s: &tonic::Status, setting: &str) {
    assert_eq!(s.code(), Code::ResourceExhausted, "{s:?}");
    assert!(s.message().contains(setting), "{s:?}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn creep_curves_whose_client_reads_nothing_hold_a_share_and_are_ended() {
    let server = server(ServeConfig {
        workers: 1,
        queue_capacity: 4,
        stream_write_timeout_s: 1.0,
        ..ServeConfig::default()
    })
    .await;
    let mut hoarder = client_at(relay("127.0.0.2", server.addr).await).await;
    // 1000 points of 16 x 16 with per-element fields: the flow-control
    // windows fill after a few hundred, then the curve waits for a reader.
    let curve = || pb::CreepCurveRequest {
        case: Some(rolling(16, 0.0)),
        sweep: common::linear_sweep(1e-3, 1000),
        include_fields: true,
    };
    let mut held = Vec::new();
    let mut refusals = Vec::new();
    for _ in 0..4 {
        match hoarder.creep_curve(curve()).await {
            Ok(r) => held.push(r.into_inner()),
            Err(s) => refusals.push(s),
        }
    }
    // Half of the queue (2 of 4): the rest are refused naming the share.
    assert_eq!(held.len(), 2, "{refusals:?}");
    for s in &refusals {
        assert_exhausted(s, "client_max_admitted");
    }
    assert_eq!(refused(&server, "client_max_admitted").await, 2.0);
    // Another client is admitted and served meanwhile, its own curve too.
    let mut legit = client_at(server.addr).await;
    served_within(&mut legit, Duration::from_secs(10)).await;
    let mut mine = legit
        .creep_curve(pb::CreepCurveRequest {
            sweep: common::linear_sweep(1e-3, 20),
            ..curve()
        })
        .await
        .expect("admitted")
        .into_inner();
    let mut points = 0;
    while let Some(p) = mine.next().await {
        p.expect("a point");
        points += 1;
    }
    assert_eq!(points, 20);
    // The reader stalls: the first of its curves to wait
    // stream_write_timeout_s is ended and its connection closed, which
    // ends the other curve on it too (with both waiting, both may time
    // out before the connection goes); their slots are freed.
    assert!(
        eventually(Duration::from_secs(60), || async {
            metric(&server, "railcontact_streams_write_timed_out_total").await >= 1.0
        })
        .await,
        "the stalled curves were not ended"
    );
    assert!(
        eventually(Duration::from_secs(10), || async {
            metric(&server, "railcontact_solve_queue_admitted").await == 0.0
        })
        .await,
        "their queue slots were not freed"
    );
    // What the hoarder finally reads ends in an error (the stream ended,
    // then the connection closed).
    for mut stream in held {
        let ended = tokio::time::timeout(Duration::from_secs(20), async {
            while let Some(r) = stream.next().await {
                if r.is_err() {
                    return true;
                }
            }
            false
        })
        .await
        .expect("the stream ends");
        assert!(ended, "a stalled curve ended as if complete");
    }
    served_within(&mut legit, Duration::from_secs(10)).await;
    server.shutdown().await;
}

/// A tokens file of two `solve` tokens, `hoarder` and `legit`.
fn two_tokens(dir: &std::path::Path) -> std::path::PathBuf {
    let path = dir.join("tokens.toml");
    std::fs::write(
        &path,
        "[[token]]\nname = \"hoarder\"\nrole = \"solve\"\ntoken = \"hoarder-token-0123456789\"\n\n\
         [[token]]\nname = \"legit\"\nrole = \"solve\"\ntoken = \"legit-token-0123456789\"\n",
    )
    .unwrap();
    path
}

/// Fixed metadata added to every call: a token, a forwarded address.
#[derive(Clone)]
struct WithMetadata(Vec<(&'static str, String)>);

impl tonic::service::Interceptor for WithMetadata {
    fn call(&mut self, mut r: tonic::Request<()>) -> Result<tonic::Request<()>, tonic::Status> {
        for (key, value) in &self.0 {
            r.metadata_mut().insert(*key, value.parse().unwrap());
        }
        Ok(r)
    }
}

type TokenClient =
    ContactServiceClient<tonic::service::interceptor::InterceptedService<Channel, WithMetadata>>;

/// A client on `channel` presenting the token of [`two_tokens`] named
/// `name`.
fn with_token(channel: Channel, name: &str) -> TokenClient {
    let token = match name {
        "hoarder" => "hoarder-token-0123456789",
        _ => "legit-token-0123456789",
    };
    ContactServiceClient::with_interceptor(
        channel,
        WithMetadata(vec![("authorization", format!("Bearer {token}"))]),
    )
}

fn hertz_open() -> pb::SessionRequest {
    pb::SessionRequest {
        kind: Some(pb::session_request::Kind::Open(pb::SessionOpen {
            case: Some(sphere(pb::Model::Hertz, 16)),
            client_label: "fairness".into(),
            ..Default::default()
        })),
    }
}

fn hertz_step(k: u64) -> pb::SessionRequest {
    pb::SessionRequest {
        kind: Some(pb::session_request::Kind::Step(pb::SessionStep {
            step_index: k,
            time_s: k as f64 * 1e-3,
            load: Some(pb::session_step::Load::NormalForceN(1e4)),
            ..Default::default()
        })),
    }
}

/// Opens a patch session on `client`, keeping its stream open (the
/// sender); the first response or the status that ended it.
async fn open_session(
    client: &mut TokenClient,
) -> (
    tokio::sync::mpsc::Sender<pb::SessionRequest>,
    tonic::Streaming<pb::SessionResponse>,
    Result<pb::session_response::Kind, tonic::Status>,
) {
    let (tx, rx) = tokio::sync::mpsc::channel(4);
    tx.send(hertz_open()).await.unwrap();
    let mut out = client
        .patch_session(tokio_stream::wrappers::ReceiverStream::new(rx))
        .await
        .expect("the stream starts")
        .into_inner();
    let first = match out.next().await.expect("an answer") {
        Ok(r) => Ok(r.kind.expect("a kind")),
        Err(s) => Err(s),
    };
    (tx, out, first)
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn one_token_cannot_take_every_session() {
    let dir = tempfile::tempdir().unwrap();
    let server = server(ServeConfig {
        max_sessions: 6,
        auth_tokens_file: Some(two_tokens(dir.path())),
        ..ServeConfig::default()
    })
    .await;
    // Both clients come from 127.0.0.1: their tokens tell them apart.
    let channel = channel_at(server.addr).await;
    let mut hoarder = with_token(channel.clone(), "hoarder");
    let mut kept = Vec::new();
    let mut refusals = Vec::new();
    for _ in 0..6 {
        let (tx, out, first) = open_session(&mut hoarder).await;
        match first {
            Ok(pb::session_response::Kind::Opened(_)) => kept.push((tx, out)),
            Ok(other) => panic!("{other:?}"),
            Err(s) => refusals.push(s),
        }
    }
    assert_eq!(kept.len(), 3, "half of max_sessions: {refusals:?}");
    assert_eq!(refusals.len(), 3);
    for s in &refusals {
        assert_exhausted(s, "client_max_sessions");
        assert!(s.message().contains("token `hoarder`"), "{s:?}");
    }
    // The other token opens a session and steps at once.
    let mut legit = with_token(channel, "legit");
    let t0 = Instant::now();
    let (tx, mut out, first) = open_session(&mut legit).await;
    assert!(
        matches!(first, Ok(pb::session_response::Kind::Opened(_))),
        "{first:?}"
    );
    tx.send(hertz_step(0)).await.unwrap();
    let step = out.next().await.expect("a step").expect("answered");
    assert!(
        matches!(step.kind, Some(pb::session_response::Kind::Step(_))),
        "{step:?}"
    );
    assert!(t0.elapsed() < Duration::from_secs(10), "{:?}", t0.elapsed());
    assert_eq!(refused(&server, "client_max_sessions").await, 3.0);
    // A hoarder's session that closes gives its place back.
    drop(kept.pop());
    assert!(
        eventually(Duration::from_secs(10), || async {
            metric(&server, "railcontact_sessions_active").await == 3.0
        })
        .await
    );
    let (_tx, _out, first) = open_session(&mut hoarder).await;
    assert!(
        matches!(first, Ok(pb::session_response::Kind::Opened(_))),
        "{first:?}"
    );
    drop((tx, out, kept));
    server.shutdown().await;
}

/// Opens `n` patch-session streams on `client` that send nothing; the
/// streams the server took (their senders and responses, to keep them
/// open) and the refusals.
async fn silent_streams(
    client: &mut Client,
    n: usize,
) -> (
    Vec<(
        tokio::sync::mpsc::Sender<pb::SessionRequest>,
        tonic::Streaming<pb::SessionResponse>,
    )>,
    Vec<tonic::Status>,
) {
    let (mut open, mut refused) = (Vec::new(), Vec::new());
    for _ in 0..n {
        let (tx, rx) = tokio::sync::mpsc::channel(1);
        match client
            .patch_session(tokio_stream::wrappers::ReceiverStream::new(rx))
            .await
        {
            Ok(out) => open.push((tx, out.into_inner())),
            Err(s) => refused.push(s),
        }
    }
    (open, refused)
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn silent_streams_are_capped_per_client_and_per_server() {
    let server = server(ServeConfig {
        max_streams: 40,
        // The silent streams stay for the whole test.
        stream_first_message_timeout_s: 60.0,
        ..ServeConfig::default()
    })
    .await;
    let mut a = client_at(relay("127.0.0.2", server.addr).await).await;
    let (a_open, a_refused) = silent_streams(&mut a, 25).await;
    assert_eq!(a_open.len(), 20, "half of max_streams");
    assert_eq!(a_refused.len(), 5);
    for s in &a_refused {
        assert_exhausted(s, "client_max_streams");
        assert!(s.message().contains("address 127.0.0.2"), "{s:?}");
    }
    // Another client is served meanwhile.
    let mut legit = client_at(server.addr).await;
    served_within(&mut legit, Duration::from_secs(10)).await;
    // Its call is given back once its response has ended.
    assert!(
        eventually(Duration::from_secs(10), || async {
            metric(&server, "railcontact_streams_open").await == 20.0
        })
        .await
    );
    // A second hoarder takes what is left: the server's cap.
    let mut b = client_at(relay("127.0.0.3", server.addr).await).await;
    let (b_open, b_refused) = silent_streams(&mut b, 25).await;
    assert_eq!(b_open.len(), 20, "{b_refused:?}");
    assert!(
        b_refused
            .iter()
            .all(|s| s.code() == Code::ResourceExhausted),
        "{b_refused:?}"
    );
    let s = legit
        .solve_patch(solve_request(sphere(pb::Model::Hertz, 8)))
        .await
        .expect_err("the server is at its cap");
    assert_exhausted(&s, "max_streams");
    assert!(refused(&server, "max_streams").await >= 1.0);
    // Health is answered at the cap.
    let health = tonic_health::pb::health_client::HealthClient::new(channel_at(server.addr).await)
        .check(tonic_health::pb::HealthCheckRequest {
            service: String::new(),
        })
        .await
        .expect("health answers at the cap")
        .into_inner();
    assert_eq!(health.status, 1, "SERVING");
    // When the hoarders' streams end, everything comes back.
    drop((a_open, b_open));
    assert!(
        eventually(Duration::from_secs(10), || async {
            metric(&server, "railcontact_streams_open").await == 0.0
        })
        .await,
        "the streams were not given back"
    );
    served_within(&mut legit, Duration::from_secs(10)).await;
    server.shutdown().await;
}

/// Whether the server closed `s` (EOF or an error) within `limit`. What
/// it sends before (an HTTP/2 server's SETTINGS, a GOAWAY) is read and
/// ignored.
async fn closed_within(s: &mut TcpStream, limit: Duration) -> bool {
    let mut buf = [0u8; 256];
    tokio::time::timeout(limit, async {
        loop {
            match s.read(&mut buf).await {
                Ok(0) | Err(_) => return,
                Ok(_) => {}
            }
        }
    })
    .await
    .is_ok()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn silent_connections_are_closed_and_capped() {
    let server = server(ServeConfig {
        max_connections: 8,
        connection_first_call_timeout_s: 3.0,
        ..ServeConfig::default()
    })
    .await;
    // The legitimate client connects first and calls.
    let mut legit = client_at(server.addr).await;
    served_within(&mut legit, Duration::from_secs(10)).await;
    // A hoarder opens connections from 127.0.0.2 and sends nothing: four
    // (half of max_connections) are taken, the fifth closed at once.
    let a: IpAddr = "127.0.0.2".parse().unwrap();
    let t0 = Instant::now();
    let mut silent = Vec::new();
    for _ in 0..4 {
        silent.push(connect_from(a, server.addr).await.unwrap());
    }
    let mut fifth = connect_from(a, server.addr).await.unwrap();
    assert!(
        closed_within(&mut fifth, Duration::from_secs(2)).await,
        "an address beyond client_max_connections was kept"
    );
    // Another address fills the server: its fourth is refused by the cap.
    let b: IpAddr = "127.0.0.3".parse().unwrap();
    for _ in 0..3 {
        silent.push(connect_from(b, server.addr).await.unwrap());
    }
    let mut last = connect_from(b, server.addr).await.unwrap();
    assert!(
        closed_within(&mut last, Duration::from_secs(2)).await,
        "a connection beyond max_connections was kept"
    );
    assert!(refused(&server, "client_max_connections").await >= 1.0);
    assert!(refused(&server, "max_connections").await >= 1.0);
    // The legitimate client's connection is served meanwhile.
    served_within(&mut legit, Duration::from_secs(10)).await;
    // The silent ones are closed after connection_first_call_timeout_s.
    for s in &mut silent {
        assert!(
            closed_within(s, Duration::from_secs(10)).await,
            "a silent connection was kept"
        );
    }
    let waited = t0.elapsed();
    assert!(waited >= Duration::from_millis(2900), "{waited:?}");
    // All seven closed by their timer, none by a refusal: the page says
    // which if not.
    let page = metrics_page(server.metrics_addr.expect("a metrics port")).await;
    assert_eq!(
        metric(&server, "railcontact_connections_timed_out_total").await,
        7.0,
        "{page}"
    );
    assert!(
        eventually(Duration::from_secs(5), || async {
            metric(&server, "railcontact_connections_open").await <= 2.0
        })
        .await
    );
    // A client that connected and called nothing for longer still gets
    // its call answered: its channel connects again.
    let mut late = client_at(server.addr).await;
    tokio::time::sleep(Duration::from_millis(3500)).await;
    served_within(&mut late, Duration::from_secs(10)).await;
    served_within(&mut legit, Duration::from_secs(10)).await;
    server.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_silent_tls_connection_is_closed() {
    let dir = tempfile::tempdir().unwrap();
    support::write_test_pki(dir.path());
    let server = server(ServeConfig {
        tls_cert: Some(dir.path().join("server.pem")),
        tls_key: Some(dir.path().join("server-key.pem")),
        connection_first_call_timeout_s: 0.5,
        ..ServeConfig::default()
    })
    .await;
    // Nothing at all, and a handshake begun but never finished.
    let mut silent = TcpStream::connect(server.addr).await.unwrap();
    let mut half = TcpStream::connect(server.addr).await.unwrap();
    tokio::io::AsyncWriteExt::write_all(&mut half, &[0x16, 0x03, 0x01, 0x00, 0x40])
        .await
        .unwrap();
    assert!(closed_within(&mut silent, Duration::from_secs(10)).await);
    assert!(closed_within(&mut half, Duration::from_secs(10)).await);
    assert_eq!(
        metric(&server, "railcontact_connections_timed_out_total").await,
        2.0
    );
    // A TLS client is served.
    let read = |name: &str| std::fs::read(dir.path().join(name)).unwrap();
    let tls = tonic::transport::ClientTlsConfig::new()
        .ca_certificate(tonic::transport::Certificate::from_pem(read("ca.pem")))
        .domain_name("localhost");
    let channel = Endpoint::from_shared(format!("https://localhost:{}", server.addr.port()))
        .unwrap()
        .tls_config(tls)
        .unwrap()
        .connect()
        .await
        .expect("TLS connects");
    served_within(
        &mut ContactServiceClient::new(channel),
        Duration::from_secs(10),
    )
    .await;
    server.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn token_guessing_is_slowed_and_its_refusals_logged_sparingly() {
    let dir = tempfile::tempdir().unwrap();
    let tokens = two_tokens(dir.path());
    let server = support::Server::start_with(
        &[
            "--auth-tokens-file",
            tokens.to_str().unwrap(),
            "--metrics-listen",
            "127.0.0.1:0",
        ],
        &[
            ("RUST_LOG", "info"),
            ("RAILCONTACT_AUTH_FAILURE_BURST", "5"),
            ("RAILCONTACT_AUTH_FAILURE_RATE_PER_S", "2"),
        ],
    );
    let target: SocketAddr = server.addr.parse().unwrap();
    let guesser = ContactServiceClient::with_interceptor(
        channel_at(relay("127.0.0.2", target).await).await,
        |mut r: tonic::Request<()>| {
            let guess = format!("Bearer guess-{:016x}", rand_u64());
            r.metadata_mut()
                .insert("authorization", guess.parse().unwrap());
            Ok(r)
        },
    );
    // Guess for 1.5 s, 8 guesses in flight.
    let t0 = Instant::now();
    let mut tasks = tokio::task::JoinSet::new();
    for _ in 0..8 {
        let mut g = guesser.clone();
        tasks.spawn(async move {
            let (mut checked, mut slowed) = (0u32, 0u32);
            while t0.elapsed() < Duration::from_millis(1500) {
                let s = g
                    .solve_patch(solve_request(sphere(pb::Model::Hertz, 8)))
                    .await
                    .expect_err("a guess is refused");
                match s.code() {
                    Code::Unauthenticated => checked += 1,
                    Code::ResourceExhausted => {
                        assert!(s.message().contains("auth_failure_burst"), "{s:?}");
                        slowed += 1;
                    }
                    other => panic!("{other:?}: {s:?}"),
                }
            }
            (checked, slowed)
        });
    }
    // A known token from another address is served meanwhile.
    let mut legit = with_token(channel_at(target).await, "legit");
    tokio::time::sleep(Duration::from_millis(300)).await;
    let t1 = Instant::now();
    legit
        .solve_patch(solve_request(sphere(pb::Model::Hertz, 8)))
        .await
        .expect("a known token from another address is served");
    assert!(t1.elapsed() < Duration::from_secs(5), "{:?}", t1.elapsed());
    let (mut checked, mut slowed) = (0, 0);
    while let Some(r) = tasks.join_next().await {
        let (c, s) = r.unwrap();
        checked += c;
        slowed += s;
    }
    let seconds = t0.elapsed().as_secs_f64();
    eprintln!("token guessing: {checked} checked, {slowed} refused unchecked in {seconds:.2} s");
    // 5 at once, then 2 a second (and a little for the timing).
    assert!(
        f64::from(checked) <= 5.0 + 2.0 * seconds + 2.0,
        "{checked} guesses checked in {seconds:.2} s"
    );
    assert!(slowed > 20, "{slowed}");
    // The log holds a bounded number of refusal lines, not one each.
    let lines = server
        .log()
        .lines()
        .filter(|l| l.contains("call refused"))
        .count();
    assert!(
        lines <= 45 && lines as u32 <= checked + slowed,
        "{lines} log lines for {} refusals",
        checked + slowed
    );
    let page = server.metrics_page();
    assert!(
        page.lines().any(|l| l
            .strip_prefix("railcontact_quota_refused_total{quota=\"auth_failure_burst\"} ")
            .is_some_and(|v| v.trim().parse::<f64>().unwrap() == f64::from(slowed))),
        "{page}"
    );
}

/// A different number each call (the guesses).
fn rand_u64() -> u64 {
    use std::sync::atomic::{AtomicU64, Ordering};
    static NEXT: AtomicU64 = AtomicU64::new(0x9e37_79b9_7f4a_7c15);
    NEXT.fetch_add(0x9e37_79b9_7f4a_7c15, Ordering::Relaxed)
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_client_with_many_solves_waiting_delays_another_by_about_one() {
    let server = server(ServeConfig {
        workers: 1,
        queue_capacity: 32,
        ..ServeConfig::default()
    })
    .await;
    let hoarder = client_at(relay("127.0.0.2", server.addr).await).await;
    let big = |k: usize| solve_request(rolling(160, 1e-4 + 1e-7 * k as f64));
    // One solve alone (after one that fills the kernel cache): how long
    // each of the hoarder's takes, for the record.
    let mut h = hoarder.clone();
    h.solve_patch(big(0)).await.unwrap();
    let t = Instant::now();
    h.solve_patch(big(1)).await.unwrap();
    let one = t.elapsed();
    // Its share of the queue at once (16 of 32), each counted when
    // answered; then another client's small exact solve, which waits for
    // the same worker.
    const HOARDED: usize = 16;
    let answered = std::sync::Arc::new(std::sync::atomic::AtomicUsize::new(0));
    let mut tasks = tokio::task::JoinSet::new();
    for k in 0..HOARDED {
        let (mut h, answered) = (hoarder.clone(), answered.clone());
        tasks.spawn(async move {
            let r = h.solve_patch(big(2 + k)).await.map(|_| ());
            answered.fetch_add(1, std::sync::atomic::Ordering::SeqCst);
            r
        });
    }
    assert!(
        eventually(Duration::from_secs(10), || async {
            metric(&server, "railcontact_solve_queue_admitted").await == HOARDED as f64
        })
        .await,
        "the hoarder's solves were not all admitted"
    );
    let mut legit = client_at(server.addr).await;
    let before = answered.load(std::sync::atomic::Ordering::SeqCst);
    let t1 = Instant::now();
    legit
        .solve_patch(solve_request(rolling(16, 1e-4)))
        .await
        .expect("served");
    let waited = t1.elapsed();
    let ahead = answered.load(std::sync::atomic::Ordering::SeqCst) - before;
    while let Some(r) = tasks.join_next().await {
        r.unwrap().expect("the hoarder's solves are answered too");
    }
    eprintln!(
        "one 160 x 160 solve {:.0} ms; another client's 16 x 16 waited {:.0} ms, {ahead} of the \
         hoarder's {} solves waiting were answered before it",
        one.as_secs_f64() * 1e3,
        waited.as_secs_f64() * 1e3,
        HOARDED - before
    );
    // First come, first served, all of those waiting would go first; in
    // turn, the one running and one more (the hoarder was in turn first),
    // plus one answered just before the other client called but read
    // after, and one for a request slow to reach the lane. Counted, not
    // timed: a loaded machine slows both clients alike.
    assert!(
        HOARDED - before >= 8,
        "{before} of the hoarder's solves were answered before the other client called"
    );
    assert!(ahead <= 4, "{ahead} of the hoarder's solves went first");
    server.shutdown().await;
}

/// A client through `channel` presenting `bearer` as its token and
/// `forwarded` as `x-forwarded-for` (what a proxy would add).
fn forwarded_client(channel: Channel, bearer: &str, forwarded: &str) -> TokenClient {
    ContactServiceClient::with_interceptor(
        channel,
        WithMetadata(vec![
            ("authorization", bearer.to_string()),
            ("x-forwarded-for", forwarded.to_string()),
        ]),
    )
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_trusted_proxy_tells_its_clients_apart() {
    let dir = tempfile::tempdir().unwrap();
    let server = server(ServeConfig {
        auth_tokens_file: Some(two_tokens(dir.path())),
        auth_failure_burst: 3,
        // No refill within the test.
        auth_failure_rate_per_s: 0.001,
        max_connections: 12,
        // A range (127.0.0.2-3), as a pod network is given.
        trusted_proxies: vec!["127.0.0.2/31".parse().unwrap()],
        ..ServeConfig::default()
    })
    .await;
    let solve = || solve_request(sphere(pb::Model::Hertz, 8));
    // Behind the proxy (127.0.0.2), a guesser at 192.0.2.1 spends its
    // burst; the proxy appended that address after one the client wrote.
    let proxy = relay("127.0.0.2", server.addr).await;
    let mut guesser = forwarded_client(
        channel_at(proxy).await,
        "Bearer guess-0123456789",
        "203.0.113.9, 192.0.2.1",
    );
    for _ in 0..3 {
        let s = guesser.solve_patch(solve()).await.unwrap_err();
        assert_eq!(s.code(), Code::Unauthenticated, "{s:?}");
    }
    let s = guesser.solve_patch(solve()).await.unwrap_err();
    assert_exhausted(&s, "auth_failure_burst");
    assert!(s.message().contains("address 192.0.2.1"), "{s:?}");
    // Another client behind the same proxy, with a known token, is served.
    let mut legit = forwarded_client(
        channel_at(proxy).await,
        "Bearer legit-token-0123456789",
        "192.0.2.2",
    );
    legit
        .solve_patch(solve())
        .await
        .expect("a client behind the proxy is not slowed by another");
    // Anyone else's x-forwarded-for is ignored: a guesser at 127.0.0.4
    // (outside the range) naming a new address each time is slowed after
    // its burst all the same.
    let untrusted = channel_at(relay("127.0.0.4", server.addr).await).await;
    let names = ["192.0.2.11", "192.0.2.12", "192.0.2.13", "192.0.2.14"];
    let mut codes = Vec::new();
    for name in names {
        let mut g = forwarded_client(untrusted.clone(), "Bearer guess-0123456789", name);
        codes.push(g.solve_patch(solve()).await.unwrap_err().code());
    }
    assert_eq!(
        codes,
        [
            Code::Unauthenticated,
            Code::Unauthenticated,
            Code::Unauthenticated,
            Code::ResourceExhausted
        ]
    );
    // The proxy's connections have no per-address share (6 of 12 here):
    // with its two above, six more from its address are all kept.
    let proxy_ip: IpAddr = "127.0.0.2".parse().unwrap();
    let mut held = Vec::new();
    for _ in 0..6 {
        held.push(connect_from(proxy_ip, server.addr).await.unwrap());
    }
    assert!(
        eventually(Duration::from_secs(10), || async {
            metric(&server, "railcontact_connections_open").await >= 9.0
        })
        .await
    );
    assert_eq!(refused(&server, "client_max_connections").await, 0.0);
    drop(held);
    server.shutdown().await;
}

/// Two viscoelastic 64 x 64 solves (about 0.5 s of
/// coefficient integration each, one per heavy worker) whose clients give
/// up after 100 ms: a running one is told to stop (the second may not
/// have started; a build told so stops integrating: `core::cache`'s
/// `a_cancelled_viscoelastic_build_is_cut_short_and_not_kept`), and the
/// next exact solve is served.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn abandoned_viscoelastic_builds_free_their_workers() {
    let server = server(ServeConfig::default()).await;
    let addr = server.addr;
    let visc = |tc: f64| {
        let mut case = rolling(64, 1e-3);
        case.viscoelastic = Some(pb::ViscoelasticSection {
            rolling_speed_m_per_s: 10.0,
            body1: Some(pb::ViscoelasticBody {
                relaxation_ratio: 2.0,
                creep_relaxation_time_s: tc,
            }),
            body2: None,
        });
        case
    };
    let abandon = |case: pb::PatchCase| async move {
        let mut client = client_at(addr).await;
        let mut request = tonic::Request::new(solve_request(case));
        request.set_timeout(Duration::from_millis(100));
        client.solve_patch(request).await
    };
    let (a, b) = tokio::join!(abandon(visc(1e-4)), abandon(visc(2e-4)));
    for r in [a, b] {
        assert_eq!(r.unwrap_err().code(), Code::DeadlineExceeded);
    }
    assert!(
        eventually(Duration::from_secs(5), || async {
            metric(&server, "railcontact_solves_cancelled_total").await >= 1.0
        })
        .await,
        "the abandoned solves were not told to stop:\n{}",
        metrics_page(server.metrics_addr.expect("a metrics port")).await
    );
    let mut client = client_at(addr).await;
    let t0 = Instant::now();
    let r = tokio::time::timeout(
        Duration::from_secs(5),
        client.solve_patch(solve_request(rolling(16, 1e-3))),
    )
    .await
    .unwrap_or_else(|_| panic!("the exact solve waited for the abandoned builds"));
    r.unwrap_or_else(|s| panic!("refused after {:?}: {s:?}", t0.elapsed()));
}
