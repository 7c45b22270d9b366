//! A real gRPC proxy in front of a fleet: Debian's nginx running
//! deploy/nginx.conf (only its three replica addresses, its listen port and
//! its certificates' directory replaced) before three `railcontact serve`
//! processes on loopback, TLS from the clients to nginx and from nginx to
//! the replicas, bearer tokens checked by the replicas.
//!
//! It shows, each from what nginx logged (its access log names the
//! replicas it tried for every call and stream, and the gRPC status) and
//! what the replicas logged and counted:
//!
//! * the proxy serves TLS only, and passes the clients' tokens to the
//!   replicas, which check them: a call without a token is
//!   UNAUTHENTICATED, a plaintext connection gets nowhere;
//! * `railcontact loadtest` through the proxy, half of its sessions and
//!   batch clients through nginx and half straight to the first replica,
//!   answers every step exactly as that single server's replay;
//! * unary calls spread over all three replicas, and each replica's
//!   request counter agrees with nginx's access log;
//! * every session stream stays on the replica its key hashed to (the
//!   replica that logged its label is the one nginx named), sessions with
//!   distinct keys land on more than one replica, and two streams with
//!   the same key land on the same one;
//! * a replica stopped with SIGTERM drains: its listener refuses new
//!   connections at once, its open session goes on stepping and ends
//!   cleanly, while new sessions (one with the draining replica's own key)
//!   and unary calls go to the others (nginx's error log shows the refused
//!   connection); a session still open on it when its shutdown grace runs
//!   out ends with an error at the client;
//! * those sessions' and calls' answers equal a direct replay on one
//!   server;
//! * replicas killed (SIGKILL): a session whose replica died reopens on
//!   the survivor with its key; once no replica is left, a unary call in
//!   flight on the last one, a session opened again with its key, a new
//!   session, a new call and `railcontact health` all get UNAVAILABLE
//!   with nginx's message (a trailers-only gRPC response), never
//!   INTERNAL, UNKNOWN or an HTML page.
//!
//! nginx runs as the current user with its prefix, configuration, pid and
//! logs in a temporary directory, and is stopped when the test ends. Where
//! nginx is missing, the test installs Debian's `nginx` package with
//! apt-get as root or through `sudo -n`, saying so on stderr first; it is
//! skipped, with a `skipped:` line on stderr, where that is impossible
//! (neither root nor passwordless sudo), where `RAILCONTACT_SKIP_CLIENT_TESTS`
//! asks for no installs and nginx is missing, and where
//! `RAILCONTACT_SKIP_PROXY_TEST` is set (anything but empty or `0`).

use crate::common;
use crate::support;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use railcontact::service::pb;
use railcontact::service::pb::contact_service_client::ContactServiceClient;
use support::{assert_clean, loadtest_json, num, Server};
use tokio::sync::mpsc;
use tokio_stream::wrappers::ReceiverStream;
use tonic::metadata::{Ascii, MetadataValue};
use tonic::service::interceptor::InterceptedService;
use tonic::transport::{Certificate, Channel, ClientTlsConfig, Endpoint};

/// Set to anything but "" or "0", skips this test.
const SKIP_PROXY_TEST: &str = "RAILCONTACT_SKIP_PROXY_TEST";

/// The replicas' shutdown grace in this test \[s\]: long enough for the
/// drain's steps, short enough to wait for.
const GRACE_S: &str = "4";

/// The directory of the proxy's certificates in deploy/nginx.conf.
const TLS_DIR: &str = "/etc/railcontact/nginx-tls/";

/// The name deploy/nginx.conf checks in the replicas' certificate
/// (`grpc_ssl_name`).
const REPLICA_NAME: &str = "railcontact.default.svc";

/// The bearer token of the clients (role solve).
const TOKEN: &str = "proxy-fleet-test-token-7c1e";

/// The test's certificates and tokens, in one temporary directory laid
/// out as deploy/nginx.conf expects /etc/railcontact/nginx-tls/.
struct Pki {
    dir: tempfile::TempDir,
}

impl Pki {
    /// An authority (`replicas-ca.pem`, which the clients trust too), the
    /// proxy's certificate for localhost and 127.0.0.1 (`proxy.crt`,
    /// `proxy.key`), the replicas' for [`REPLICA_NAME`], localhost and
    /// 127.0.0.1 (`replica.crt`, `replica.key`; the load test reaches
    /// replica 0 straight), and `tokens.toml` with [`TOKEN`].
    fn new() -> Pki {
        let dir = tempfile::tempdir().unwrap();
        let path = |name: &str| dir.path().join(name);
        let ca = railcontact_testkit::TestAuthority::new("railcontact proxy test CA");
        ca.write(&path("replicas-ca.pem"));
        for (name, sans) in [
            ("proxy", vec!["localhost", "127.0.0.1"]),
            ("replica", vec![REPLICA_NAME, "localhost", "127.0.0.1"]),
        ] {
            ca.sign(
                &sans,
                true,
                &path(&format!("{name}.crt")),
                &path(&format!("{name}.key")),
            );
        }
        let write = |name: &str, text: String| std::fs::write(path(name), text).unwrap();
        write(
            "tokens.toml",
            format!("[[token]]\nname = \"proxy-fleet\"\nrole = \"solve\"\ntoken = \"{TOKEN}\"\n"),
        );
        Pki { dir }
    }

    fn path(&self, name: &str) -> String {
        self.dir.path().join(name).display().to_string()
    }

    /// The authority clients trust.
    fn ca(&self) -> String {
        self.path("replicas-ca.pem")
    }
}

fn set(var: &str) -> bool {
    std::env::var(var).is_ok_and(|v| !v.is_empty() && v != "0")
}

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// nginx on PATH or where Debian and nginx.org put it.
fn find_nginx() -> Option<PathBuf> {
    let on_path = std::env::var_os("PATH")
        .map(|p| std::env::split_paths(&p).collect::<Vec<_>>())
        .unwrap_or_default();
    on_path
        .into_iter()
        .map(|d| d.join("nginx"))
        .chain(
            [
                "/usr/sbin/nginx",
                "/usr/local/sbin/nginx",
                "/usr/local/nginx/sbin/nginx",
            ]
            .map(PathBuf::from),
        )
        .find(|p| p.is_file())
}

/// nginx's binary, installed first if need be; None when the test is
/// skipped (said on stderr).
fn nginx_binary() -> Option<PathBuf> {
    const WHAT: &str = "the nginx proxy test";
    if set(SKIP_PROXY_TEST) {
        eprintln!("skipped: {WHAT} ({SKIP_PROXY_TEST} is set)");
        return None;
    }
    let nginx = match find_nginx() {
        Some(n) => n,
        None if set(support::SKIP_CLIENT_TESTS) => {
            eprintln!(
                "skipped: {WHAT}: nginx is not installed and {} asks for no installs",
                support::SKIP_CLIENT_TESTS
            );
            return None;
        }
        None if !(support::is_root() || support::has_sudo()) => {
            eprintln!(
                "skipped: {WHAT}: nginx is not installed, and installing it \
                 (apt-get install nginx) needs root or passwordless sudo"
            );
            return None;
        }
        None => {
            support::apt_install(
                &["nginx"],
                &format!("nginx proxy test (skip with {SKIP_PROXY_TEST}=1)"),
                "the nginx proxy test needs Debian's nginx and could not install it \
                 (access to the Debian mirrors, or install nginx by hand)",
            );
            find_nginx().expect("nginx is there after apt-get install nginx")
        }
    };
    // Debian's and nginx.org's builds have both modules; others may not.
    let version = Command::new(&nginx)
        .arg("-V")
        .output()
        .expect("nginx -V runs");
    let build = String::from_utf8_lossy(&version.stderr).to_string();
    if !build.contains("--with-http_v2_module") || build.contains("--without-http_grpc_module") {
        eprintln!(
            "skipped: {WHAT}: {} lacks HTTP/2 or gRPC proxying:\n{build}",
            nginx.display()
        );
        return None;
    }
    Some(nginx)
}

/// A free loopback port (free when asked; nginx binds it right after).
fn free_port() -> u16 {
    std::net::TcpListener::bind("127.0.0.1:0")
        .and_then(|l| l.local_addr())
        .expect("a free port")
        .port()
}

/// deploy/nginx.conf with its replicas `192.0.2.11-13:50051` replaced by
/// `replicas`, `listen 8443` by `listen` and its certificates' directory
/// by `tls_dir`; fails when the file no longer has what this replaces.
fn render(template: &str, replicas: &[String], listen: &str, tls_dir: &str) -> String {
    let mut conf = template.to_string();
    for (i, addr) in replicas.iter().enumerate() {
        let example = format!("server 192.0.2.{}:50051 ", 11 + i);
        assert_eq!(
            conf.matches(&example).count(),
            2,
            "deploy/nginx.conf names `{example}` once in each upstream"
        );
        conf = conf.replace(&example, &format!("server {addr} "));
    }
    assert_eq!(
        conf.matches("listen 8443 ssl http2;").count(),
        1,
        "the listen line"
    );
    conf = conf.replace(
        "listen 8443 ssl http2;",
        &format!("listen {listen} ssl http2;"),
    );
    let code = |conf: &str, what: &str| -> Vec<String> {
        conf.lines()
            .filter(|l| !l.trim_start().starts_with('#') && l.contains(what))
            .map(str::to_string)
            .collect()
    };
    assert_eq!(
        code(&conf, TLS_DIR).len(),
        3,
        "the proxy's certificate, its key and the replicas' authority in {TLS_DIR}"
    );
    conf = conf.replace(TLS_DIR, tls_dir);
    let left = code(&conf, "192.0.2.");
    assert!(left.is_empty(), "example addresses left: {left:?}");
    let left = code(&conf, "/etc/");
    assert!(left.is_empty(), "example paths left: {left:?}");
    conf
}

/// An nginx master process and its files, stopped when dropped.
struct Nginx {
    /// HOST:PORT it listens on.
    addr: String,
    child: Child,
    dir: tempfile::TempDir,
}

impl Nginx {
    /// Starts `nginx` on deploy/nginx.conf rendered for `replicas` and
    /// the certificates of `pki`, as the current user, everything under a
    /// temporary prefix; waits until it accepts connections.
    fn start(nginx: &Path, replicas: &[String], pki: &Pki) -> Nginx {
        let dir = tempfile::tempdir().unwrap();
        for sub in ["logs", "tmp"] {
            std::fs::create_dir(dir.path().join(sub)).unwrap();
        }
        let template = std::fs::read_to_string(repo().join("deploy/nginx.conf")).unwrap();
        let addr = format!("127.0.0.1:{}", free_port());
        let conf = dir.path().join("nginx.conf");
        let tls_dir = format!("{}/", pki.dir.path().display());
        std::fs::write(&conf, render(&template, replicas, &addr, &tls_dir)).unwrap();
        // Started as root, nginx would run its workers as nobody: keep
        // them as the current user.
        let globals = if support::is_root() {
            "daemon off; user root;"
        } else {
            "daemon off;"
        };
        let prefix = format!("{}/", dir.path().display());
        let error_log = dir.path().join("logs/error.log");
        let command = |test: bool| {
            let mut c = Command::new(nginx);
            c.arg("-p")
                .arg(&prefix)
                .arg("-c")
                .arg(&conf)
                .arg("-e")
                .arg(&error_log)
                .arg("-g")
                .arg(globals)
                .stdin(Stdio::null());
            if test {
                c.arg("-t");
            }
            c
        };
        support::check("nginx -t", &command(true).output().expect("nginx -t runs"));
        let child = command(false)
            .stdout(Stdio::null())
            .stderr(std::fs::File::create(dir.path().join("stderr.log")).unwrap())
            .spawn()
            .expect("nginx starts");
        let mut nginx = Nginx { addr, child, dir };
        let start = Instant::now();
        while std::net::TcpStream::connect(&nginx.addr).is_err() {
            if let Some(status) = nginx.child.try_wait().unwrap() {
                panic!("nginx exited ({status}):\n{}", nginx.error_log());
            }
            assert!(
                start.elapsed() < Duration::from_secs(10),
                "nginx does not listen on {}:\n{}",
                nginx.addr,
                nginx.error_log()
            );
            std::thread::sleep(Duration::from_millis(20));
        }
        nginx
    }

    fn error_log(&self) -> String {
        std::fs::read_to_string(self.dir.path().join("logs/error.log")).unwrap_or_default()
    }

    /// Its access log, one entry per finished call or stream (lines of
    /// anything else, such as a plaintext client's garbage on the TLS
    /// port, left out).
    fn access(&self) -> Vec<Entry> {
        std::fs::read_to_string(self.dir.path().join("logs/access.log"))
            .unwrap_or_default()
            .lines()
            .filter(|l| l.contains("\"POST "))
            .map(Entry::parse)
            .collect()
    }
}

impl Drop for Nginx {
    fn drop(&mut self) {
        // SIGTERM: the master stops its workers and exits. Only if it
        // hangs, its workers and then itself are killed.
        let pid = self.child.id();
        support::signal(pid, "TERM");
        let start = Instant::now();
        while start.elapsed() < Duration::from_secs(5) {
            if let Ok(Some(_)) = self.child.try_wait() {
                return;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        let children =
            std::fs::read_to_string(format!("/proc/{pid}/task/{pid}/children")).unwrap_or_default();
        for worker in children.split_whitespace().filter_map(|p| p.parse().ok()) {
            support::signal(worker, "KILL");
        }
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// One line of the access log (deploy/nginx.conf's `log_format`).
#[derive(Debug)]
struct Entry {
    /// The gRPC method's path.
    path: String,
    /// The HTTP status nginx sent.
    status: String,
    /// The `x-railcontact-session` header ("-" without).
    session: String,
    /// The replicas nginx tried, in order (the last one answered), or
    /// the upstream's name where none was left to try.
    upstreams: Vec<String>,
    /// The gRPC status nginx sent, from the trailers or the headers ("-"
    /// where none).
    grpc_status: String,
    line: String,
}

impl Entry {
    fn parse(line: &str) -> Entry {
        let between = |start: &str, end: &str| {
            let from = line
                .find(start)
                .unwrap_or_else(|| panic!("no {start} in {line}"))
                + start.len();
            let len = line[from..]
                .find(end)
                .unwrap_or_else(|| panic!("no {end} after {start} in {line}"));
            line[from..from + len].to_string()
        };
        Entry {
            path: between("\"POST ", " "),
            status: between("HTTP/2.0\" ", " "),
            session: between("session=\"", "\""),
            upstreams: between("upstream=\"", "\"")
                .split(", ")
                .map(str::to_string)
                .collect(),
            grpc_status: between("grpc_status=", " "),
            line: line.to_string(),
        }
    }

    fn method(&self) -> &str {
        self.path.rsplit('/').next().unwrap_or("")
    }

    fn answered_by(&self) -> &str {
        self.upstreams.last().map(String::as_str).unwrap_or("")
    }
}

/// How many sessions labelled `label` each replica opened (from its log).
fn opened(servers: &[Server], label: &str) -> Vec<usize> {
    let needle = format!("label={label} ");
    servers
        .iter()
        .map(|s| s.log().matches(&needle).count())
        .collect()
}

/// A counter's value on a metrics page (0 when absent).
fn counter(page: &str, series: &str) -> f64 {
    page.lines()
        .find_map(|l| l.strip_prefix(series)?.strip_prefix(' '))
        .map_or(0.0, |v| v.trim().parse().unwrap())
}

#[test]
fn nginx_spreads_calls_pins_sessions_and_routes_around_a_draining_replica() {
    let t0 = Instant::now();
    let Some(nginx_bin) = nginx_binary() else {
        return;
    };
    let pki = Pki::new();
    let (cert, key, tokens) = (
        pki.path("replica.crt"),
        pki.path("replica.key"),
        pki.path("tokens.toml"),
    );
    let mut servers: Vec<Server> = std::thread::scope(|s| {
        let starts: Vec<_> = (0..3)
            .map(|_| {
                s.spawn(|| {
                    // As on a network: TLS and tokens.
                    Server::start_with(
                        &[
                            "--metrics-listen",
                            "127.0.0.1:0",
                            "--tls-cert",
                            &cert,
                            "--tls-key",
                            &key,
                            "--auth-tokens-file",
                            &tokens,
                        ],
                        &[
                            ("RUST_LOG", "warn,railcontact=info"),
                            ("RAILCONTACT_SHUTDOWN_GRACE_S", GRACE_S),
                        ],
                    )
                })
            })
            .collect();
        starts.into_iter().map(|h| h.join().unwrap()).collect()
    });
    let replicas: Vec<String> = servers.iter().map(|s| s.addr.clone()).collect();
    let nginx = Nginx::start(&nginx_bin, &replicas, &pki);
    eprintln!("fleet and nginx up in {:.1} s", t0.elapsed().as_secs_f64());

    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .unwrap();
    runtime.block_on(tls_and_tokens(&nginx, &pki));

    load_through_the_proxy(&servers, &nginx, &pki);
    eprintln!("load test done at {:.1} s", t0.elapsed().as_secs_f64());

    let (v, replay) = runtime.block_on(drain(&mut servers, &nginx, &pki));
    eprintln!("drain done at {:.1} s", t0.elapsed().as_secs_f64());
    runtime.block_on(kill(servers, v, &replay, &nginx, &pki));
    eprintln!("proxy fleet test: {:.1} s", t0.elapsed().as_secs_f64());
}

/// The proxy serves TLS only and passes the token on: with it a call is
/// answered, without it the replica refuses it, and a plaintext client
/// gets no answer at all.
async fn tls_and_tokens(nginx: &Nginx, pki: &Pki) {
    let solve = || pb::SolvePatchRequest {
        case: Some(patch_case()),
        ..Default::default()
    };
    client_of(&nginx.addr, pki, true)
        .await
        .solve_patch(solve())
        .await
        .unwrap_or_else(|s| panic!("SolvePatch through the proxy with TLS and a token: {s:?}"));
    let refused = client_of(&nginx.addr, pki, false)
        .await
        .solve_patch(solve())
        .await
        .expect_err("a call without a token");
    assert_eq!(refused.code(), tonic::Code::Unauthenticated, "{refused:?}");
    // Health needs no token (what a load balancer's check would ask).
    let out = support::run(&["health", "--target", &nginx.addr, "--tls-ca", &pki.ca()]);
    support::check("railcontact health through the proxy", &out);
    assert_eq!(String::from_utf8_lossy(&out.stdout).trim(), "SERVING");

    let plain = async {
        let channel = Endpoint::from_shared(format!("http://{}", nginx.addr))
            .unwrap()
            .connect()
            .await
            .map_err(|e| format!("connect: {e}"))?;
        match ContactServiceClient::new(channel)
            .solve_patch(solve())
            .await
        {
            Ok(_) => Ok(()),
            Err(s) => Err(format!("{:?}: {}", s.code(), s.message())),
        }
    };
    match tokio::time::timeout(Duration::from_secs(10), plain).await {
        Ok(Err(e)) => eprintln!("plaintext gRPC to the proxy: {e}"),
        Ok(Ok(())) => panic!("the proxy answered a plaintext call"),
        Err(_) => panic!("a plaintext call to the proxy hangs"),
    }
}

/// `railcontact loadtest` with targets [replica 0, nginx]: even sessions
/// and batch clients straight to replica 0, odd ones through nginx; the
/// replay of all on replica 0 alone.
fn load_through_the_proxy(servers: &[Server], nginx: &Nginx, pki: &Pki) {
    let proxy = nginx.addr.as_str();
    let ca = pki.ca();
    let (report, out) = loadtest_json(&[
        "--tls-ca",
        &ca,
        "--token",
        TOKEN,
        "--target",
        &servers[0].addr,
        "--target",
        proxy,
        "--sessions",
        "24",
        "--steps",
        "20",
        "--batch-clients",
        "6",
        "--batch-items",
        "2",
        "--mix",
        "patch:fastsim=1,wheelrail:hertz_fastsim=1",
    ]);
    assert!(
        out.status.success(),
        "{}\nnginx:\n{}",
        String::from_utf8_lossy(&out.stderr),
        nginx.error_log()
    );
    // Every answer, through nginx or not, equals replica 0's replay.
    assert_clean(&report);
    let via = &report["targets"][proxy];
    // 12 sessions and 3 batch clients (PatchBatch), 20 steps each.
    assert_eq!(num(via, "clients"), 15.0, "{via}");
    assert_eq!(num(via, "steps"), 300.0, "{via}");
    assert_eq!(num(via, "mismatches"), 0.0);

    let entries = nginx.access();
    // The sessions: the odd ones, each one stream through nginx.
    let mut placed: BTreeMap<usize, (String, String)> = BTreeMap::new();
    for e in entries.iter().filter(|e| e.method().ends_with("Session")) {
        let index: usize = e
            .session
            .split('-')
            .nth(2)
            .and_then(|i| i.parse().ok())
            .unwrap_or_else(|| panic!("a session label of the load test: {}", e.line));
        assert_eq!(e.upstreams.len(), 1, "one replica tried: {}", e.line);
        assert!(
            placed
                .insert(index, (e.session.clone(), e.answered_by().to_string()))
                .is_none(),
            "session {index} went through nginx once"
        );
    }
    let odd: Vec<usize> = (1..24).step_by(2).collect();
    assert_eq!(
        placed.keys().copied().collect::<Vec<_>>(),
        odd,
        "the odd sessions, and only those, went through nginx"
    );
    let mut per_replica = vec![0; servers.len()];
    for (label, upstream) in placed.values() {
        let r = servers
            .iter()
            .position(|s| &s.addr == upstream)
            .unwrap_or_else(|| panic!("{upstream} is not a replica"));
        per_replica[r] += 1;
        // The replica nginx named opened it, and no other did.
        let mut expected = vec![0; servers.len()];
        expected[r] = 1;
        assert_eq!(opened(servers, label), expected, "{label} on {upstream}");
    }
    eprintln!("sessions per replica through nginx: {per_replica:?}");
    assert!(
        per_replica.iter().filter(|&&n| n > 0).count() >= 2,
        "12 session keys hash to more than one replica: {per_replica:?}"
    );

    // Unary calls: 3 batch clients x 20 SolvePatchBatch calls, per call
    // over the replicas.
    let mut batches = vec![0.0; servers.len()];
    for e in entries.iter().filter(|e| e.method() == "SolvePatchBatch") {
        let r = servers
            .iter()
            .position(|s| s.addr == e.answered_by())
            .unwrap_or_else(|| panic!("not a replica: {}", e.line));
        batches[r] += 1.0;
    }
    eprintln!("SolvePatchBatch calls per replica through nginx: {batches:?}");
    assert_eq!(batches.iter().sum::<f64>(), 60.0);
    assert!(
        batches.iter().all(|&n| n > 0.0),
        "unary calls reach every replica: {batches:?}"
    );
    // The replicas counted what nginx says it sent them (replica 0 also
    // ran the 60 batches of the replay).
    for (r, s) in servers.iter().enumerate() {
        let page = s.metrics_page();
        let ok = counter(
            &page,
            "railcontact_requests_total{method=\"SolvePatchBatch\",code=\"Ok\"}",
        );
        let replay = if r == 0 { 60.0 } else { 0.0 };
        assert_eq!(
            ok,
            batches[r] + replay,
            "replica {r}'s SolvePatchBatch count"
        );
    }
}

type Client = ContactServiceClient<InterceptedService<Channel, Bearer>>;

/// Adds `authorization: Bearer TOKEN` to every call, or nothing.
#[derive(Clone)]
struct Bearer(Option<MetadataValue<Ascii>>);

impl tonic::service::Interceptor for Bearer {
    fn call(&mut self, mut req: tonic::Request<()>) -> Result<tonic::Request<()>, tonic::Status> {
        if let Some(v) = &self.0 {
            req.metadata_mut().insert("authorization", v.clone());
        }
        Ok(req)
    }
}
use pb::session_response::Kind as Out;

/// Steady rolling with FASTSIM on `common::sphere`, mu = 0.3.
fn patch_case() -> pb::PatchCase {
    pb::PatchCase {
        friction: Some(pb::FrictionSection {
            coefficient: Some(0.3),
            ..Default::default()
        }),
        kinematics: Some(pb::patch_case::Kinematics::Rolling(creepages(0))),
        ..common::sphere(pb::Model::Fastsim, 16)
    }
}

fn creepages(k: u64) -> pb::Creepages {
    let f = k as f64;
    pb::Creepages {
        creepage_long: 1e-3 * (1.0 + 0.1 * f),
        creepage_lat: 5e-4 * (1.0 - 0.05 * f),
        spin_per_m: 0.1,
        ..Default::default()
    }
}

/// A patch session stepped one message at a time.
struct Session {
    tx: mpsc::Sender<pb::SessionRequest>,
    rx: tonic::Streaming<pb::SessionResponse>,
    next: u64,
}

impl Session {
    /// Opens a session with the session header `label`.
    async fn open(client: &Client, label: &str) -> Session {
        Session::try_open(client, label)
            .await
            .unwrap_or_else(|s| panic!("open {label}: {s:?}"))
    }

    /// Opens a session with the session header `label`, or says how the
    /// call ended.
    async fn try_open(client: &Client, label: &str) -> Result<Session, tonic::Status> {
        let (tx, rx) = mpsc::channel(4);
        let open = pb::SessionRequest {
            kind: Some(pb::session_request::Kind::Open(pb::SessionOpen {
                case: Some(patch_case()),
                client_label: label.to_string(),
                ..Default::default()
            })),
        };
        tx.send(open).await.unwrap();
        let mut req = tonic::Request::new(ReceiverStream::new(rx));
        req.metadata_mut()
            .insert("x-railcontact-session", label.parse().unwrap());
        let mut rx = client.clone().patch_session(req).await?.into_inner();
        match rx.message().await {
            Ok(Some(pb::SessionResponse {
                kind: Some(Out::Opened(_)),
            })) => {}
            Err(s) => return Err(s),
            other => panic!("open {label}: {other:?}"),
        }
        Ok(Session { tx, rx, next: 0 })
    }

    /// The next step's result (its solve time cleared), or how the stream
    /// ended.
    async fn step(&mut self) -> Result<pb::StepResult, tonic::Status> {
        let k = self.next;
        let step = pb::SessionStep {
            step_index: k,
            time_s: k as f64 * 1e-3,
            load: Some(pb::session_step::Load::NormalForceN(5e4 + 1e3 * k as f64)),
            creepages: Some(creepages(k)),
            ..Default::default()
        };
        let sent = self
            .tx
            .send(pb::SessionRequest {
                kind: Some(pb::session_request::Kind::Step(step)),
            })
            .await;
        if sent.is_err() {
            // tonic closed the request stream because the call ended: say
            // how it ended.
            return match self.rx.message().await {
                Err(s) => Err(s),
                Ok(_) => Err(tonic::Status::unavailable("the request stream is closed")),
            };
        }
        match self.rx.message().await? {
            Some(pb::SessionResponse {
                kind:
                    Some(Out::Step(pb::SessionStepResult {
                        result: Some(mut r),
                        ..
                    })),
            }) => {
                self.next += 1;
                if let Some(info) = r.info.as_mut() {
                    info.solve_time_s = 0.0;
                }
                Ok(r)
            }
            None => Err(tonic::Status::unavailable("the stream ended")),
            Some(other) => panic!("step {k}: {other:?}"),
        }
    }

    /// `n` steps that must all be answered.
    async fn steps(&mut self, n: usize, what: &str) -> Vec<pb::StepResult> {
        let mut out = Vec::with_capacity(n);
        for _ in 0..n {
            let k = self.next;
            out.push(
                self.step()
                    .await
                    .unwrap_or_else(|s| panic!("{what}, step {k}: {s:?}")),
            );
        }
        out
    }

    /// Ends the request stream; the response stream must end cleanly.
    async fn close(self, what: &str) {
        let Session { tx, mut rx, .. } = self;
        drop(tx);
        match rx.message().await {
            Ok(Some(m)) => panic!("{what}: unexpected {m:?}"),
            Ok(None) => {}
            Err(s) => panic!("{what} did not end cleanly: {s:?}"),
        }
    }
}

/// A TLS connection to `addr` (127.0.0.1:PORT) trusting the test's
/// authority, with the token on every call when `token`.
async fn client_of(addr: &str, pki: &Pki, token: bool) -> Client {
    let tls = ClientTlsConfig::new().ca_certificate(Certificate::from_pem(
        std::fs::read(pki.ca()).expect("the test authority"),
    ));
    let channel = Endpoint::from_shared(format!("https://{addr}"))
        .unwrap()
        .tls_config(tls)
        .unwrap()
        .connect()
        .await
        .unwrap_or_else(|e| panic!("connect to {addr}: {e}"));
    let bearer = Bearer(token.then(|| format!("Bearer {TOKEN}").parse().unwrap()));
    ContactServiceClient::with_interceptor(channel, bearer)
}

/// The replica that opened the sessions labelled `label`; checks that
/// it opened `count` of them and no other replica any.
fn replica_of(servers: &[Server], label: &str, count: usize) -> usize {
    let per = opened(servers, label);
    let r = per
        .iter()
        .position(|&n| n > 0)
        .unwrap_or_else(|| panic!("no replica opened {label}"));
    let mut expected = vec![0; servers.len()];
    expected[r] = count;
    assert_eq!(per, expected, "{label}");
    r
}

/// One replica stopped with SIGTERM while sessions run through nginx.
/// Returns the stopped replica and the first 10 steps of the session
/// replayed straight on a survivor.
async fn drain(servers: &mut [Server], nginx: &Nginx, pki: &Pki) -> (usize, Vec<pb::StepResult>) {
    let proxy = client_of(&nginx.addr, pki, true).await;
    const KEY: &str = "drain-victim";

    // Two sessions with one key: the same replica, V.
    let mut s1 = Session::open(&proxy, KEY).await;
    let v = replica_of(servers, KEY, 1);
    let mut s2 = Session::open(&proxy, KEY).await;
    replica_of(servers, KEY, 2);
    let mut answers = s1.steps(5, "s1").await;
    answers.extend(s2.steps(1, "s2").await);

    // SIGTERM: V's listener closes at once.
    servers[v].terminate();
    let t = Instant::now();
    while std::net::TcpStream::connect(&servers[v].addr).is_ok() {
        assert!(t.elapsed() < Duration::from_secs(5), "V keeps listening");
        tokio::time::sleep(Duration::from_millis(10)).await;
    }

    // Its open session goes on.
    answers.extend(s1.steps(5, "s1 while its replica drains").await);

    // New sessions go elsewhere, the one with V's key too: nginx's
    // connection to V is refused and it takes the next replica.
    let mut s3 = Session::open(&proxy, KEY).await;
    let per = opened(servers, KEY);
    assert_eq!(per[v], 2, "no new session on the draining replica: {per:?}");
    assert_eq!(per.iter().sum::<usize>(), 3, "{per:?}");
    answers.extend(s3.steps(3, "s3").await);
    for i in 0..6 {
        let label = format!("drain-new-{i}");
        let mut s = Session::open(&proxy, &label).await;
        assert_eq!(
            opened(servers, &label)[v],
            0,
            "{label} on the draining replica"
        );
        answers.extend(s.steps(3, &label).await);
        s.close(&label).await;
    }
    s3.close("s3").await;
    // Unary calls too.
    let mut unary = Vec::new();
    for _ in 0..6 {
        let req = pb::SolvePatchRequest {
            case: Some(patch_case()),
            ..Default::default()
        };
        let r = proxy
            .clone()
            .solve_patch(req)
            .await
            .unwrap_or_else(|s| panic!("SolvePatch while a replica drains: {s:?}"));
        unary.push(r.into_inner());
    }
    // The draining replica's session ends cleanly.
    s1.close("s1").await;
    let drained_at = Instant::now();

    // s2 stays open past V's grace: V drops it, and the client sees an
    // error, not a hang.
    let status = servers[v]
        .wait_exit(Duration::from_secs(20))
        .expect("the draining replica exits after its grace");
    assert!(status.success(), "{status}");
    let log = servers[v].log();
    assert!(
        log.contains("grace period over"),
        "V dropped the open session at the end of its grace:\n{log}"
    );
    let cut = s2.step().await.expect_err("the session cut at V's grace");
    eprintln!(
        "session left on the stopped replica: {:?} \"{}\" ({:.1} s after the other drained)",
        cut.code(),
        cut.message(),
        drained_at.elapsed().as_secs_f64()
    );

    // nginx routed around V by refusal.
    let errors = nginx.error_log();
    assert!(
        errors.contains("Connection refused") && errors.contains(&servers[v].addr),
        "nginx's error log names V's refused connection:\n{errors}"
    );
    let entries = nginx.access();
    let reopened: Vec<&Entry> = entries.iter().filter(|e| e.session == KEY).collect();
    // s1 and s3 ended (s2's line comes when nginx gives up on it).
    assert!(
        reopened.iter().any(|e| e.upstreams.len() == 2
            && e.upstreams[0] == servers[v].addr
            && e.answered_by() != servers[v].addr),
        "s3 tried V first, then another replica: {reopened:#?}"
    );

    // Every answer equals a direct replay on one surviving replica.
    let w = (v + 1) % servers.len();
    let direct = client_of(&servers[w].addr, pki, true).await;
    let mut replay = Session::open(&direct, "direct-replay").await;
    let expected = replay.steps(10, "direct replay").await;
    replay.close("direct replay").await;
    // In the order they were collected: s1 0-4, s2 0, s1 5-9, s3 0-2,
    // then six new sessions' 0-2.
    let mut want = Vec::new();
    for steps in [0..5, 0..1, 5..10, 0..3] {
        want.extend_from_slice(&expected[steps]);
    }
    for _ in 0..6 {
        want.extend_from_slice(&expected[0..3]);
    }
    assert_eq!(answers.len(), want.len());
    for (i, (got, want)) in answers.iter().zip(&want).enumerate() {
        assert_eq!(got, want, "answer {i} through nginx");
    }
    let mut one = direct
        .clone()
        .solve_patch(pb::SolvePatchRequest {
            case: Some(patch_case()),
            ..Default::default()
        })
        .await
        .unwrap()
        .into_inner();
    let clear = |r: &mut pb::SolvePatchResponse| {
        let r = r.result.as_mut().expect("a result");
        for s in r.result.iter_mut().chain(r.steps.iter_mut()) {
            if let Some(info) = s.info.as_mut() {
                info.solve_time_s = 0.0;
            }
        }
    };
    clear(&mut one);
    for mut u in unary {
        clear(&mut u);
        assert_eq!(u, one, "SolvePatch through nginx");
    }
    (v, expected)
}

/// The value of a gauge or counter of `server`'s metrics page.
fn metric(server: &Server, series: &str) -> f64 {
    counter(&server.metrics_page(), series)
}

/// Replicas killed (SIGKILL, as a crash or the OOM killer would) while a
/// session and a unary call run on them through nginx; `v`, stopped by
/// [`drain`], is gone already, `replay` the first steps of a session
/// replayed straight on one server.
///
/// The session's replica X dies first: its stream is cut, and the session
/// opened again with its key reaches the survivor Y. Then Y dies while
/// it runs a batch: the batch, a session opened again with the key, a new
/// session, a new call and `railcontact health` all get UNAVAILABLE from
/// nginx, with its message.
async fn kill(servers: Vec<Server>, v: usize, replay: &[pb::StepResult], nginx: &Nginx, pki: &Pki) {
    const KEY: &str = "kill-victim";
    let proxy = client_of(&nginx.addr, pki, true).await;
    let addrs: Vec<String> = servers.iter().map(|s| s.addr.clone()).collect();
    let unavailable = |what: &str, s: &tonic::Status| {
        assert_eq!(
            s.code(),
            tonic::Code::Unavailable,
            "{what}: UNAVAILABLE from nginx, not {s:?}"
        );
        assert!(
            s.message().starts_with("railcontact proxy: "),
            "{what}: nginx's message: {s:?}"
        );
    };

    let mut s1 = Session::open(&proxy, KEY).await;
    let x = replica_of(&servers, KEY, 1);
    assert_ne!(x, v, "no session on the stopped replica");
    let y = (0..servers.len()).find(|&i| i != v && i != x).unwrap();
    let mut answers = s1.steps(3, "s1 on X").await;
    let mut fleet: Vec<Option<Server>> = servers.into_iter().map(Some).collect();

    // X killed: s1's stream is cut. nginx had passed X's response
    // headers on when s1 opened, so it cannot send a status any more: it
    // resets the stream (INTERNAL_ERROR, which gRPC reads as INTERNAL).
    let cut_stream = |what: &str, s: &tonic::Status| {
        eprintln!("{what}: {:?} \"{}\"", s.code(), s.message());
        assert!(
            matches!(s.code(), tonic::Code::Internal | tonic::Code::Unavailable),
            "{what}: the stream reset, not {s:?}"
        );
    };
    drop(fleet[x].take());
    let cut = s1.step().await.expect_err("s1 cut when X died");
    cut_stream("session whose replica was killed", &cut);
    // Opened again with its key: X refuses, nginx takes Y.
    let mut s2 = Session::open(&proxy, KEY).await;
    let on_y = |fleet: &[Option<Server>], label: &str| {
        let needle = format!("label={label} ");
        fleet[y].as_ref().unwrap().log().matches(&needle).count()
    };
    assert_eq!(on_y(&fleet, KEY), 1, "the session reopened on the survivor");
    answers.extend(s2.steps(3, "s2 on Y").await);
    for (i, (got, want)) in answers.iter().zip(replay[0..3].iter().cycle()).enumerate() {
        assert_eq!(got, want, "answer {i} through nginx after X died");
    }

    // A batch long enough to be killed under: 1024 exact steady-rolling
    // patches (about a second on two workers).
    let exact = pb::SolvePatchRequest {
        case: Some(pb::PatchCase {
            model: pb::Model::Exact as i32,
            grid: common::sphere(pb::Model::Exact, 48).grid,
            ..patch_case()
        }),
        ..Default::default()
    };
    let batch = pb::SolvePatchBatchRequest {
        items: vec![exact; 1024],
    };
    let mut client = proxy.clone();
    let call = tokio::spawn(async move { client.solve_patch_batch(batch).await });
    let t = Instant::now();
    let admitted = "railcontact_solve_queue_admitted";
    while metric(fleet[y].as_ref().unwrap(), admitted) < 1.0 {
        assert!(
            t.elapsed() < Duration::from_secs(20) && !call.is_finished(),
            "the batch never ran on Y"
        );
        tokio::time::sleep(Duration::from_millis(5)).await;
    }
    // Y killed with the batch on its workers: no replica is left.
    drop(fleet[y].take());
    let lost = call
        .await
        .unwrap()
        .expect_err("the batch whose replica was killed");
    eprintln!(
        "batch whose replica was killed: {:?} \"{}\"",
        lost.code(),
        lost.message()
    );
    unavailable("the batch in flight on the killed replica", &lost);
    let cut = s2.step().await.expect_err("s2 cut when Y died");
    cut_stream("second session whose replica was killed", &cut);

    // Nothing left: every new call is UNAVAILABLE, from nginx.
    let again = Session::try_open(&proxy, KEY)
        .await
        .err()
        .expect("no replica left for the session's key");
    unavailable("the session opened again", &again);
    let new = Session::try_open(&proxy, "kill-new")
        .await
        .err()
        .expect("no replica left for a new session");
    unavailable("a new session", &new);
    let solve = proxy
        .clone()
        .solve_patch(pb::SolvePatchRequest {
            case: Some(patch_case()),
            ..Default::default()
        })
        .await
        .expect_err("no replica left for a call");
    unavailable("SolvePatch", &solve);
    let out = support::run(&["health", "--target", &nginx.addr, "--tls-ca", &pki.ca()]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.code() == Some(1)
            && stderr.contains("Unavailable")
            && stderr.contains("railcontact proxy: "),
        "railcontact health through the proxy without replicas: {out:?}"
    );

    // What nginx logged: gRPC status 14 in HTTP 200 responses (its own,
    // trailers-only), the batch's after trying Y.
    let entries = nginx.access();
    let ours: Vec<&Entry> = entries.iter().filter(|e| e.grpc_status == "14").collect();
    for e in &ours {
        assert_eq!(
            e.status, "200",
            "a gRPC response, not an error page: {}",
            e.line
        );
    }
    assert!(
        ours.iter()
            .any(|e| e.method() == "SolvePatchBatch" && e.upstreams.contains(&addrs[y])),
        "the batch's line names Y and status 14: {ours:#?}"
    );
    assert!(
        ours.iter().filter(|e| e.session == KEY).count() >= 1,
        "the session's key refused with 14: {ours:#?}"
    );
    let errors = nginx.error_log();
    for what in ["SolvePatchBatch", "no live upstreams"] {
        if let Some(line) = errors.lines().find(|l| l.contains(what)) {
            eprintln!("nginx: {line}");
        }
    }
}
