//! Who may reach the service, end to end: TLS (certificates made here
//! with rcgen), mutual TLS, bearer tokens and their roles, the refusal to
//! listen beyond loopback unprotected, and client strings escaped in the
//! log.
//!
//! - a plaintext client gets nothing from a TLS server; a TLS client that
//!   trusts the CA does;
//! - with `tls_client_ca`, a client without a certificate is refused, one
//!   with a certificate the CA signed is served;
//! - a failed handshake is logged with the peer and its reason and counted
//!   by reason: plaintext to the TLS port, a client certificate of another
//!   CA, none, a client that does not trust the server's certificate (its
//!   alert), a silent connection at `connection_first_call_timeout_s`; a
//!   port check is none; a good client is still served;
//! - without a token a call is UNAUTHENTICATED (unary, streaming,
//!   reflection); a `solve` token may solve and read pairs but not
//!   register or delete them (PERMISSION_DENIED naming `admin`); an
//!   `admin` token given by its SHA-256 may; health needs no token;
//!   refusals are counted by reason;
//! - every RPC of the service descriptor is in the access table;
//! - 0.0.0.0 without TLS and tokens is refused unless `insecure` (the
//!   command exits 2 saying how to override; with `--insecure` it starts
//!   and logs a warning); a missing key, an invalid PEM file are start
//!   errors naming the file;
//! - metrics on an address other than loopback are refused unless
//!   `metrics_insecure` (TLS, tokens or `insecure` for the gRPC port do not
//!   allow them; the command exits 2 saying how to override);
//! - a client label holding a newline is logged escaped;
//! - `railcontact health` and `railcontact loadtest` reach a server with
//!   TLS and tokens through `--tls-ca` and `--token`;
//! - `reflection = false` serves no reflection (UNIMPLEMENTED).

use std::path::{Path, PathBuf};

use railcontact::service::auth::{self, Access, Role};
use railcontact::service::config::{ServeConfig, ServeFlags};
use railcontact::service::pb;
use railcontact::service::pb::contact_service_client::ContactServiceClient;
use railcontact::service::server::{start, RunningServer};
use sha2::{Digest, Sha256};
use tokio_stream::StreamExt;
use tonic::service::interceptor::InterceptedService;
use tonic::transport::{Certificate, Channel, ClientTlsConfig, Endpoint, Identity};
use tonic::Code;

use crate::common;
use crate::support;
use common::{metrics_page, sphere};

/// A CA, a server certificate for localhost and 127.0.0.1 and a client
/// certificate, as PEM files in a temporary directory
/// ([`support::write_test_pki`]).
struct Pki {
    dir: tempfile::TempDir,
}

impl Pki {
    fn new() -> Pki {
        let dir = tempfile::tempdir().unwrap();
        support::write_test_pki(dir.path());
        Pki { dir }
    }

    fn path(&self, name: &str) -> PathBuf {
        self.dir.path().join(name)
    }

    /// `config` with TLS on (and mutual TLS when `mutual`).
    fn tls(&self, mutual: bool, config: ServeConfig) -> ServeConfig {
        ServeConfig {
            tls_cert: Some(self.path("server.pem")),
            tls_key: Some(self.path("server-key.pem")),
            tls_client_ca: mutual.then(|| self.path("ca.pem")),
            ..config
        }
    }

    /// A TLS connection trusting the CA, with the client certificate when
    /// `identity`.
    async fn connect(
        &self,
        server: &RunningServer,
        identity: bool,
    ) -> Result<Channel, tonic::transport::Error> {
        let client = identity.then(|| (self.path("client.pem"), self.path("client-key.pem")));
        self.connect_as(server.addr.port(), &self.path("ca.pem"), client)
            .await
    }

    /// A TLS connection to `port` of localhost trusting the authorities of
    /// `ca`, with the client certificate and key of `identity`.
    async fn connect_as(
        &self,
        port: u16,
        ca: &Path,
        identity: Option<(PathBuf, PathBuf)>,
    ) -> Result<Channel, tonic::transport::Error> {
        let read = |path: &Path| std::fs::read(path).unwrap();
        let mut tls = ClientTlsConfig::new()
            .ca_certificate(Certificate::from_pem(read(ca)))
            .domain_name("localhost");
        if let Some((cert, key)) = identity {
            tls = tls.identity(Identity::from_pem(read(&cert), read(&key)));
        }
        Endpoint::from_shared(format!("https://localhost:{port}"))
            .unwrap()
            .tls_config(tls)
            .unwrap()
            .connect()
            .await
    }

    /// A solve over [`Pki::connect_as`]: Ok when served, else what the
    /// client was told.
    async fn solve_as(
        &self,
        port: u16,
        ca: &Path,
        identity: Option<(PathBuf, PathBuf)>,
    ) -> Result<(), String> {
        let channel = self
            .connect_as(port, ca, identity)
            .await
            .map_err(|e| e.to_string())?;
        client(channel, None)
            .solve_patch(solve_request())
            .await
            .map(drop)
            .map_err(|s| s.to_string())
    }
}

/// A server of `config` on 127.0.0.1, any port, pairs in memory.
async fn server(config: ServeConfig) -> RunningServer {
    start(&ServeConfig {
        listen: "127.0.0.1:0".parse().unwrap(),
        data_dir: PathBuf::new(),
        shutdown_grace_s: 5.0,
        ..config
    })
    .await
    .expect("server starts")
}

/// Adds `authorization: Bearer TOKEN` when there is a token.
#[derive(Clone)]
struct Token(Option<String>);

impl tonic::service::Interceptor for Token {
    fn call(&mut self, mut req: tonic::Request<()>) -> Result<tonic::Request<()>, tonic::Status> {
        if let Some(t) = &self.0 {
            req.metadata_mut()
                .insert("authorization", format!("Bearer {t}").parse().unwrap());
        }
        Ok(req)
    }
}

type Client = ContactServiceClient<InterceptedService<Channel, Token>>;

async fn plain_channel(server: &RunningServer) -> Channel {
    Endpoint::from_shared(format!("http://{}", server.addr))
        .unwrap()
        .connect()
        .await
        .unwrap()
}

fn client(channel: Channel, token: Option<&str>) -> Client {
    ContactServiceClient::with_interceptor(channel, Token(token.map(str::to_string)))
}

fn solve_request() -> pb::SolvePatchRequest {
    pb::SolvePatchRequest {
        case: Some(sphere(pb::Model::Hertz, 16)),
        ..Default::default()
    }
}

async fn health(channel: Channel) -> i32 {
    use tonic_health::pb::health_client::HealthClient;
    HealthClient::new(channel)
        .check(tonic_health::pb::HealthCheckRequest {
            service: String::new(),
        })
        .await
        .expect("health answers")
        .into_inner()
        .status
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn tls_refuses_plaintext_and_serves_clients_that_trust_its_ca() {
    let pki = Pki::new();
    let server = server(pki.tls(
        false,
        ServeConfig {
            metrics_listen: Some("127.0.0.1:0".parse().unwrap()),
            ..ServeConfig::default()
        },
    ))
    .await;
    // Connections that ended before a call after sending bytes (a failed
    // handshake), once the server has dropped them.
    let failed = || async {
        let page = metrics_page(server.metrics_addr.unwrap()).await;
        page.lines()
            .find_map(|l| l.strip_prefix("railcontact_connections_failed_before_call_total "))
            .and_then(|v| v.trim().parse::<f64>().ok())
            .unwrap_or_else(|| panic!("no failed-connections counter in {page}"))
    };
    // A port check (connect, send nothing, close) is no failed handshake.
    drop(tokio::net::TcpStream::connect(server.addr).await.unwrap());
    tokio::time::sleep(std::time::Duration::from_millis(200)).await;
    assert_eq!(failed().await, 0.0);
    // A client that trusts the CA is served, and is no failure either
    // (before any plaintext attempt, whose client may still be retrying
    // when the count is read).
    let channel = pki.connect(&server, false).await.expect("TLS connects");
    let r = client(channel.clone(), None)
        .solve_patch(solve_request())
        .await
        .expect("served over TLS");
    assert!(r.into_inner().result.is_some());
    assert_eq!(health(channel).await, 1, "SERVING");
    assert_eq!(failed().await, 0.0, "a served TLS client is no failure");
    // Plaintext HTTP/2 to a TLS port: no answer of the service.
    let plain = async {
        let channel = Endpoint::from_shared(format!("http://{}", server.addr))
            .unwrap()
            .connect()
            .await
            .map_err(|e| e.to_string())?;
        client(channel, None)
            .solve_patch(solve_request())
            .await
            .map_err(|s| s.to_string())
    };
    let refused = tokio::time::timeout(std::time::Duration::from_secs(10), plain)
        .await
        .expect("the plaintext attempt ends");
    assert!(refused.is_err(), "a plaintext client was served");
    // Counted (and logged) as a connection that failed before a call.
    let mut counted = 0.0;
    for _ in 0..50 {
        counted = failed().await;
        if counted >= 1.0 {
            break;
        }
        tokio::time::sleep(std::time::Duration::from_millis(100)).await;
    }
    assert!(counted >= 1.0, "the failed handshake was not counted");

    server.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn mutual_tls_refuses_a_client_without_a_certificate() {
    let pki = Pki::new();
    let server = server(pki.tls(true, ServeConfig::default())).await;
    // TLS 1.3: the server checks the client's certificate after the
    // client's handshake is done, so the refusal may come with the call.
    let without = async {
        let channel = pki
            .connect(&server, false)
            .await
            .map_err(|e| e.to_string())?;
        client(channel, None)
            .solve_patch(solve_request())
            .await
            .map_err(|s| s.to_string())
    };
    assert!(
        without.await.is_err(),
        "a client without a certificate was served"
    );
    let channel = pki
        .connect(&server, true)
        .await
        .expect("mutual TLS connects");
    client(channel, None)
        .solve_patch(solve_request())
        .await
        .expect("a client with a certificate of the CA is served");
    server.shutdown().await;
}

/// `railcontact_tls_handshakes_failed_total` of `reason` on `server`'s
/// metrics page (0 before the first).
fn handshakes_failed(server: &support::Server, reason: &str) -> f64 {
    let prefix = format!("railcontact_tls_handshakes_failed_total{{reason=\"{reason}\"}} ");
    server
        .metrics_page()
        .lines()
        .find_map(|l| l.strip_prefix(&prefix))
        .map_or(0.0, |v| v.trim().parse().unwrap())
}

/// Waits up to 30 s (a loaded machine can starve the server's process
/// for seconds; the wait ends as soon as both are there) for a failed
/// handshake of `reason` beyond `before` and for its log line holding
/// `words`.
async fn handshake_failure_seen(server: &support::Server, reason: &str, before: f64, words: &str) {
    let line = |log: String| {
        log.lines()
            .find(|l| {
                l.contains("TLS handshake failed") && l.contains(&format!("reason=\"{reason}\""))
            })
            .map(str::to_string)
    };
    for _ in 0..300 {
        if handshakes_failed(server, reason) > before && line(server.log()).is_some() {
            break;
        }
        tokio::time::sleep(std::time::Duration::from_millis(100)).await;
    }
    assert!(
        handshakes_failed(server, reason) > before,
        "no failed handshake counted as {reason}:\n{}",
        server.metrics_page()
    );
    let line =
        line(server.log()).unwrap_or_else(|| panic!("no log line of {reason}:\n{}", server.log()));
    assert!(
        line.contains("WARN") && line.contains("peer=127.0.0.1:") && line.contains(words),
        "{reason}: {line}"
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn failed_handshakes_are_logged_and_counted_by_reason() {
    use tokio::io::{AsyncReadExt, AsyncWriteExt};
    let pki = Pki::new();
    // A second authority: a client certificate it signs is not trusted by
    // the server, and a client trusting only it does not trust the
    // server's certificate.
    let other = railcontact_testkit::TestAuthority::new("another CA");
    other.write(&pki.path("other-ca.pem"));
    other.sign(
        &["stranger"],
        false,
        &pki.path("stranger.pem"),
        &pki.path("stranger-key.pem"),
    );
    let path = |name: &str| pki.path(name).display().to_string();
    let server = support::Server::start_with(
        &[
            "--tls-cert",
            &path("server.pem"),
            "--tls-key",
            &path("server-key.pem"),
            "--tls-client-ca",
            &path("ca.pem"),
            "--metrics-listen",
            "127.0.0.1:0",
        ],
        &[("RAILCONTACT_CONNECTION_FIRST_CALL_TIMEOUT_S", "1")],
    );
    let port: u16 = server.addr.rsplit(':').next().unwrap().parse().unwrap();
    let client_cert = || Some((pki.path("client.pem"), pki.path("client-key.pem")));
    let ca = pki.path("ca.pem");
    let served = || async {
        pki.solve_as(port, &ca, client_cert())
            .await
            .expect("a client with a certificate of the CA is served")
    };
    served().await;

    // A port check (connect, close) is no failed handshake.
    drop(tokio::net::TcpStream::connect(&server.addr).await.unwrap());
    tokio::time::sleep(std::time::Duration::from_millis(300)).await;
    assert_eq!(handshakes_failed(&server, "closed"), 0.0);

    // Plaintext: the HTTP/2 preface to the TLS port.
    let mut plain = tokio::net::TcpStream::connect(&server.addr).await.unwrap();
    plain
        .write_all(b"PRI * HTTP/2.0\r\n\r\nSM\r\n\r\n")
        .await
        .unwrap();
    let mut answer = Vec::new();
    let _ = plain.read_to_end(&mut answer).await;
    handshake_failure_seen(&server, "not_tls", 0.0, "plaintext").await;

    // mTLS: a client certificate of another authority, and none.
    let stranger = Some((pki.path("stranger.pem"), pki.path("stranger-key.pem")));
    let refused = pki.solve_as(port, &ca, stranger).await;
    assert!(refused.is_err(), "a stranger was served");
    handshake_failure_seen(&server, "client_cert_untrusted", 0.0, "UnknownIssuer").await;
    let refused = pki.solve_as(port, &ca, None).await;
    assert!(
        refused.is_err(),
        "a client without a certificate was served"
    );
    handshake_failure_seen(&server, "no_client_cert", 0.0, "no client certificate").await;

    // A client that does not trust the server's certificate refuses it
    // with an alert (rustls: unknown_ca for an unknown issuer).
    let distrust = pki
        .solve_as(port, &pki.path("other-ca.pem"), client_cert())
        .await;
    assert!(distrust.is_err(), "a client trusting another CA was served");
    handshake_failure_seen(
        &server,
        "client_alert",
        0.0,
        "unknown_ca (the client does not trust this server's certificate",
    )
    .await;

    // A connection that sends nothing: closed at
    // connection_first_call_timeout_s, its handshake timed out.
    let mut silent = tokio::net::TcpStream::connect(&server.addr).await.unwrap();
    let mut byte = [0u8; 1];
    let read = tokio::time::timeout(std::time::Duration::from_secs(5), silent.read(&mut byte))
        .await
        .expect("the silent connection is closed");
    assert!(!matches!(read, Ok(1)), "{read:?}");
    handshake_failure_seen(&server, "timeout", 0.0, "handshake timed out").await;

    // None of them left the server unable to serve.
    served().await;
    assert_eq!(handshakes_failed(&server, "closed"), 0.0);
}

const SOLVE_TOKEN: &str = "solve-token-0123456789";
const ADMIN_TOKEN: &str = "admin-token-9876543210";

/// A tokens file: a `solve` token in plain text, an `admin` token by its
/// SHA-256.
fn tokens_file(dir: &Path) -> PathBuf {
    let hex: String = Sha256::digest(ADMIN_TOKEN.as_bytes())
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect();
    let path = dir.join("tokens.toml");
    std::fs::write(
        &path,
        format!(
            "[[token]]\nname = \"mbs-cluster\"\nrole = \"solve\"\ntoken = \"{SOLVE_TOKEN}\"\n\n\
             [[token]]\nname = \"operator\"\nrole = \"admin\"\nsha256 = \"{hex}\"\n"
        ),
    )
    .unwrap();
    path
}

/// The value of `railcontact_auth_refused_total{reason="..."}`.
fn refused(page: &str, reason: &str) -> f64 {
    let prefix = format!("railcontact_auth_refused_total{{reason=\"{reason}\"}} ");
    page.lines()
        .find_map(|l| l.strip_prefix(&prefix))
        .map_or(0.0, |v| v.parse().unwrap())
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn tokens_decide_who_may_call_what() {
    let dir = tempfile::tempdir().unwrap();
    let server = server(ServeConfig {
        auth_tokens_file: Some(tokens_file(dir.path())),
        metrics_listen: Some("127.0.0.1:0".parse().unwrap()),
        ..ServeConfig::default()
    })
    .await;
    let channel = plain_channel(&server).await;
    let mut anonymous = client(channel.clone(), None);
    let mut stranger = client(channel.clone(), Some("not-a-token"));
    let mut solver = client(channel.clone(), Some(SOLVE_TOKEN));
    let mut admin = client(channel.clone(), Some(ADMIN_TOKEN));

    let s = anonymous.solve_patch(solve_request()).await.unwrap_err();
    assert_eq!(s.code(), Code::Unauthenticated, "{s:?}");
    assert!(s.message().contains("authorization: Bearer"), "{s:?}");
    let s = stranger.solve_patch(solve_request()).await.unwrap_err();
    assert_eq!(s.code(), Code::Unauthenticated, "{s:?}");
    solver
        .solve_patch(solve_request())
        .await
        .expect("a solve token may solve");
    admin
        .solve_patch(solve_request())
        .await
        .expect("an admin token may solve");

    // Streams are checked before the handler runs.
    let open = pb::SessionRequest {
        kind: Some(pb::session_request::Kind::Open(pb::SessionOpen {
            case: Some(sphere(pb::Model::Hertz, 16)),
            ..Default::default()
        })),
    };
    let s = anonymous
        .patch_session(tokio_stream::iter([open.clone()]))
        .await
        .unwrap_err();
    assert_eq!(s.code(), Code::Unauthenticated, "{s:?}");
    let mut out = solver
        .patch_session(tokio_stream::iter([open]))
        .await
        .expect("a solve token may open a session")
        .into_inner();
    assert!(matches!(
        out.next().await.unwrap().unwrap().kind,
        Some(pb::session_response::Kind::Opened(_))
    ));

    // Pairs: reading for solve, changing for admin.
    let listed = solver
        .list_profile_pairs(pb::ListProfilePairsRequest {})
        .await
        .expect("a solve token may list pairs");
    assert!(!listed.into_inner().pairs.is_empty());
    solver
        .get_profile_pair(pb::GetProfilePairRequest {
            pair_id: "mbench_s1002_uic60".into(),
        })
        .await
        .expect("a solve token may read a pair");
    let registration = railcontact::service::pairs::builtin_registration();
    let s = solver
        .register_profile_pair(registration.clone())
        .await
        .unwrap_err();
    assert_eq!(s.code(), Code::PermissionDenied, "{s:?}");
    assert!(s.message().contains("`admin`"), "{s:?}");
    let s = solver
        .delete_profile_pair(pb::DeleteProfilePairRequest {
            pair_id: "no-such-pair".into(),
        })
        .await
        .unwrap_err();
    assert_eq!(s.code(), Code::PermissionDenied, "{s:?}");
    let mut progress = admin
        .register_profile_pair(registration)
        .await
        .expect("an admin token (given by its SHA-256) may register")
        .into_inner();
    let mut last = None;
    while let Some(p) = progress.next().await {
        last = Some(p.expect("registration progresses").stage);
    }
    assert_eq!(last, Some(pb::RegistrationStage::Ready as i32));
    let s = admin
        .delete_profile_pair(pb::DeleteProfilePairRequest {
            pair_id: "no-such-pair".into(),
        })
        .await
        .unwrap_err();
    assert_eq!(
        s.code(),
        Code::NotFound,
        "admin passes, the pair is unknown"
    );

    // Health is open; reflection needs a token.
    assert_eq!(health(channel.clone()).await, 1, "SERVING without a token");
    let reflect = |token: Option<&str>| {
        use tonic_reflection::pb::v1::server_reflection_client::ServerReflectionClient;
        use tonic_reflection::pb::v1::server_reflection_request::MessageRequest;
        use tonic_reflection::pb::v1::ServerReflectionRequest;
        let mut c = ServerReflectionClient::with_interceptor(
            channel.clone(),
            Token(token.map(str::to_string)),
        );
        async move {
            let ask = ServerReflectionRequest {
                host: String::new(),
                message_request: Some(MessageRequest::ListServices(String::new())),
            };
            let mut answers = c
                .server_reflection_info(tokio_stream::iter([ask]))
                .await?
                .into_inner();
            answers.next().await.expect("an answer").map(|_| ())
        }
    };
    let s = reflect(None).await.unwrap_err();
    assert_eq!(s.code(), Code::Unauthenticated, "{s:?}");
    reflect(Some(SOLVE_TOKEN))
        .await
        .expect("reflection with a token");

    let page = metrics_page(server.metrics_addr.unwrap()).await;
    assert_eq!(refused(&page, "missing"), 3.0, "{page}");
    assert_eq!(refused(&page, "unknown"), 1.0, "{page}");
    assert_eq!(refused(&page, "forbidden"), 2.0, "{page}");
    assert!(!page.contains(SOLVE_TOKEN) && !page.contains(ADMIN_TOKEN));
    server.shutdown().await;
}

#[test]
fn every_rpc_of_the_service_is_in_the_access_table() {
    use prost::Message;
    let set = prost_types::FileDescriptorSet::decode(pb::FILE_DESCRIPTOR_SET).unwrap();
    let (package, name) = auth::CONTACT_SERVICE.rsplit_once('.').unwrap();
    let service = set
        .file
        .iter()
        .filter(|f| f.package() == package)
        .flat_map(|f| &f.service)
        .find(|s| s.name() == name)
        .expect("the contact service in the descriptor");
    let mut in_descriptor: Vec<&str> = service.method.iter().map(|m| m.name()).collect();
    let mut in_table: Vec<&str> = auth::CONTACT_METHODS.iter().map(|(m, _)| *m).collect();
    in_descriptor.sort_unstable();
    in_table.sort_unstable();
    assert_eq!(
        in_descriptor, in_table,
        "src/service/auth.rs CONTACT_METHODS must list every RPC of the service with its role"
    );
    // The table decides by path; anything else needs admin.
    let path = |m: &str| format!("/{}/{m}", auth::CONTACT_SERVICE);
    assert_eq!(auth::access(&path("SolvePatch")), Access::Role(Role::Solve));
    assert_eq!(
        auth::access(&path("DeleteProfilePair")),
        Access::Role(Role::Admin)
    );
    assert_eq!(auth::access(&path("Unknown")), Access::Role(Role::Admin));
    assert_eq!(auth::access("/grpc.health.v1.Health/Watch"), Access::Open);
    assert_eq!(
        auth::access("/grpc.reflection.v1alpha.ServerReflection/ServerReflectionInfo"),
        Access::AnyToken
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn beyond_loopback_needs_tls_and_tokens_or_insecure() {
    let everywhere = |config: ServeConfig| ServeConfig {
        listen: "0.0.0.0:0".parse().unwrap(),
        data_dir: PathBuf::new(),
        shutdown_grace_s: 1.0,
        ..config
    };
    let e = start(&everywhere(ServeConfig::default()))
        .await
        .err()
        .expect("refused");
    let m = e.to_string();
    assert!(
        m.contains("tls_cert") && m.contains("auth_tokens_file") && m.contains("--insecure"),
        "{m}"
    );
    let s = start(&everywhere(ServeConfig {
        insecure: true,
        ..ServeConfig::default()
    }))
    .await
    .expect("insecure overrides");
    s.shutdown().await;

    // TLS alone is not enough; TLS and tokens are.
    let pki = Pki::new();
    let e = start(&everywhere(pki.tls(false, ServeConfig::default())))
        .await
        .err()
        .expect("refused without tokens");
    assert!(e.to_string().contains("auth_tokens_file"), "{e}");
    let s = start(&everywhere(pki.tls(
        false,
        ServeConfig {
            auth_tokens_file: Some(tokens_file(pki.dir.path())),
            ..ServeConfig::default()
        },
    )))
    .await
    .expect("TLS and tokens");
    s.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn bad_tls_settings_stop_the_start_naming_the_key_and_file() {
    let pki = Pki::new();
    let env = |name: &str| match name {
        "RAILCONTACT_TLS_CERT" => Some(pki.path("server.pem").display().to_string()),
        _ => None,
    };
    let e = ServeConfig::load(None, &env, &ServeFlags::default()).unwrap_err();
    assert!(e.contains("tls_cert") && e.contains("tls_key"), "{e}");
    let flags = ServeFlags {
        tls_client_ca: Some(pki.path("ca.pem")),
        ..ServeFlags::default()
    };
    let e = ServeConfig::load(None, &|_| None, &flags).unwrap_err();
    assert!(e.contains("tls_client_ca"), "{e}");

    let junk = pki.path("junk.pem");
    std::fs::write(&junk, "not a certificate\n").unwrap();
    for (config, key, file) in [
        (
            ServeConfig {
                tls_cert: Some(junk.clone()),
                ..pki.tls(false, ServeConfig::default())
            },
            "tls_cert",
            &junk,
        ),
        (
            ServeConfig {
                tls_key: Some(pki.path("server.pem")),
                ..pki.tls(false, ServeConfig::default())
            },
            "tls_key",
            &pki.path("server.pem"),
        ),
        (
            ServeConfig {
                tls_key: Some(pki.path("client-key.pem")),
                ..pki.tls(false, ServeConfig::default())
            },
            "tls_key",
            &pki.path("client-key.pem"),
        ),
        (
            ServeConfig {
                tls_client_ca: Some(pki.path("missing.pem")),
                ..pki.tls(false, ServeConfig::default())
            },
            "tls_client_ca",
            &pki.path("missing.pem"),
        ),
        (
            ServeConfig {
                auth_tokens_file: Some(junk.clone()),
                ..ServeConfig::default()
            },
            "auth_tokens_file",
            &junk,
        ),
    ] {
        let e = start(&ServeConfig {
            listen: "127.0.0.1:0".parse().unwrap(),
            data_dir: PathBuf::new(),
            ..config
        })
        .await
        .err()
        .unwrap_or_else(|| panic!("{key}: started"));
        let m = e.to_string();
        assert!(
            m.contains(key) && m.contains(&file.display().to_string()),
            "{key}: {m}"
        );
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn client_strings_are_escaped_in_the_log() {
    let server = support::Server::start_with(&[], &[("RUST_LOG", "info")]);
    let channel = Endpoint::from_shared(format!("http://{}", server.addr))
        .unwrap()
        .connect()
        .await
        .unwrap();
    let label = "evil\nINFO forged: line \u{1b}[31m";
    let open = pb::SessionRequest {
        kind: Some(pb::session_request::Kind::Open(pb::SessionOpen {
            case: Some(sphere(pb::Model::Hertz, 16)),
            client_label: label.into(),
            ..Default::default()
        })),
    };
    let mut out = client(channel, None)
        .patch_session(tokio_stream::iter([open]))
        .await
        .unwrap()
        .into_inner();
    while let Some(r) = out.next().await {
        r.unwrap();
    }
    let mut log = String::new();
    for _ in 0..50 {
        log = server.log();
        if log.contains("session opened") {
            break;
        }
        tokio::time::sleep(std::time::Duration::from_millis(100)).await;
    }
    assert!(
        log.contains("evil\\nINFO forged: line \\u{1b}[31m"),
        "label not escaped:\n{log}"
    );
    assert!(
        !log.lines().any(|l| l.starts_with("INFO forged")) && !log.contains('\u{1b}'),
        "{log}"
    );
}

#[test]
fn health_and_loadtest_reach_a_server_with_tls_and_tokens() {
    let pki = Pki::new();
    let tokens = tokens_file(pki.dir.path());
    let path = |p: PathBuf| p.display().to_string();
    let (cert, key, ca, tokens) = (
        path(pki.path("server.pem")),
        path(pki.path("server-key.pem")),
        path(pki.path("ca.pem")),
        path(tokens),
    );
    let server = support::Server::start_with(
        &[
            "--tls-cert",
            &cert,
            "--tls-key",
            &key,
            "--auth-tokens-file",
            &tokens,
        ],
        &[],
    );
    let target = server.addr.replace("127.0.0.1", "localhost");
    let out = support::run(&["health", "--target", &target, "--tls-ca", &ca]);
    support::check("health over TLS", &out);
    assert_eq!(String::from_utf8_lossy(&out.stdout).trim(), "SERVING");
    let plain = support::run(&["health", "--target", &server.addr]);
    assert!(!plain.status.success(), "plaintext health of a TLS server");

    let args = [
        "--target",
        &target,
        "--tls-ca",
        &ca,
        "--mix",
        "patch:fastsim=1",
        "--sessions",
        "1",
        "--steps",
        "20",
        "--batch-clients",
        "1",
        "--batch-items",
        "2",
    ];
    let mut with_token = args.to_vec();
    with_token.extend(["--token", SOLVE_TOKEN]);
    let (report, out) = support::loadtest_json(&with_token);
    support::check("loadtest over TLS with a token", &out);
    support::assert_clean(&report);
    let (report, out) = support::loadtest_json(&args);
    assert!(!out.status.success(), "loadtest without a token");
    assert!(support::num(&report, "errors") > 0.0, "{report}");
    let first = report["first_errors"].to_string();
    assert!(first.contains("nauthenticated"), "{first}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn metrics_beyond_loopback_need_their_own_override() {
    // gRPC on loopback or protected: only the metrics port is in question.
    let pki = Pki::new();
    let metrics_everywhere = |config: ServeConfig| ServeConfig {
        metrics_listen: Some("0.0.0.0:0".parse().unwrap()),
        data_dir: PathBuf::new(),
        shutdown_grace_s: 1.0,
        ..config
    };
    let loopback = ServeConfig {
        listen: "127.0.0.1:0".parse().unwrap(),
        ..ServeConfig::default()
    };
    let protected = pki.tls(
        false,
        ServeConfig {
            listen: "0.0.0.0:0".parse().unwrap(),
            auth_tokens_file: Some(tokens_file(pki.dir.path())),
            ..ServeConfig::default()
        },
    );
    for (what, config) in [
        ("gRPC on loopback", loopback.clone()),
        ("gRPC with TLS and tokens", protected),
        (
            "gRPC insecure",
            ServeConfig {
                listen: "0.0.0.0:0".parse().unwrap(),
                insecure: true,
                ..ServeConfig::default()
            },
        ),
    ] {
        let e = start(&metrics_everywhere(config))
            .await
            .err()
            .unwrap_or_else(|| panic!("{what}: metrics on 0.0.0.0 refused"));
        assert_eq!(e.kind(), std::io::ErrorKind::InvalidInput, "{what}: {e}");
        let m = e.to_string();
        assert!(
            m.contains("metrics on 0.0.0.0:0") && m.contains("--metrics-insecure"),
            "{what}: {m}"
        );
    }
    // With the override it serves them there.
    let s = start(&metrics_everywhere(ServeConfig {
        metrics_insecure: true,
        ..loopback
    }))
    .await
    .expect("metrics_insecure allows them");
    let addr = s.metrics_addr.expect("a metrics address");
    assert!(addr.ip().is_unspecified(), "{addr}");
    let page = metrics_page(std::net::SocketAddr::from(([127, 0, 0, 1], addr.port()))).await;
    assert!(page.contains("railcontact_sessions_active"), "{page}");
    s.shutdown().await;

    // The command: exit code 2 and how to override.
    let out = support::run(&["serve", "--metrics-listen", "0.0.0.0:0", "--data-dir", ""]);
    assert_eq!(out.status.code(), Some(2), "{out:?}");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("--metrics-insecure")
            && stderr.contains("RAILCONTACT_METRICS_INSECURE=true"),
        "{stderr}"
    );
}

#[test]
fn serve_refuses_a_public_address_without_protection_with_exit_code_2() {
    let out = support::run(&["serve", "--listen", "0.0.0.0:0", "--data-dir", ""]);
    assert_eq!(out.status.code(), Some(2), "{out:?}");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("--insecure") && stderr.contains("RAILCONTACT_INSECURE=true"),
        "{stderr}"
    );

    // With --insecure it starts, and says so in its log.
    use std::io::{BufRead, BufReader};
    use std::process::{Command, Stdio};
    let dir = tempfile::tempdir().unwrap();
    let log = dir.path().join("server.log");
    let mut child = Command::new(support::BIN)
        .args([
            "serve",
            "--listen",
            "0.0.0.0:0",
            "--insecure",
            "--data-dir",
            "",
        ])
        .env("RUST_LOG", "warn")
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(std::fs::File::create(&log).unwrap())
        .spawn()
        .unwrap();
    let mut line = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    let _ = child.kill();
    let _ = child.wait();
    assert!(
        line.starts_with("railcontact listening on 0.0.0.0:"),
        "{line:?}"
    );
    let text = std::fs::read_to_string(&log).unwrap();
    assert!(
        text.contains("WARN") && text.contains("insecure = true"),
        "{text}"
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn reflection_can_be_turned_off() {
    use tonic_reflection::pb::v1::server_reflection_client::ServerReflectionClient;
    use tonic_reflection::pb::v1::server_reflection_request::MessageRequest;
    use tonic_reflection::pb::v1::ServerReflectionRequest;
    let server = server(ServeConfig {
        reflection: false,
        ..ServeConfig::default()
    })
    .await;
    let ask = ServerReflectionRequest {
        host: String::new(),
        message_request: Some(MessageRequest::ListServices(String::new())),
    };
    let s = ServerReflectionClient::new(plain_channel(&server).await)
        .server_reflection_info(tokio_stream::iter([ask]))
        .await
        .unwrap_err();
    assert_eq!(s.code(), Code::Unimplemented, "{s:?}");
    server.shutdown().await;
}
