//! Forwarding calculations to a railcontact server (`CNTC_if_mode` = 1, or
//! `RAILCONTACT_CNTC_SERVER` set): each result element gets a stream of
//! the service's `ContactLibrary` call, opened at its first calculation;
//! every `cntc_calculate` sends the configuring calls made since the last
//! one ([`crate::call::CallLog`]) and takes the server's results into the
//! library's own element, which the getters then read as in process. The
//! server applies the same calls with the same code
//! (`railcontact-cntc-core`), so both modes give the same numbers bit for
//! bit.
//!
//! Settings, from the environment when the library is first used:
//!
//! * `RAILCONTACT_CNTC_SERVER`: the server, `HOST:PORT` (or a URL); when
//!   set, forwarding is on from the start. `CNTC_if_mode` = 1 turns it on
//!   without it, to 127.0.0.1:50051;
//! * `RAILCONTACT_CNTC_TLS_CA`: a PEM file of the authorities to trust:
//!   TLS on (`RAILCONTACT_CNTC_TLS_SERVER_NAME` when the certificate names
//!   another host than the address);
//! * `RAILCONTACT_CNTC_TOKEN`: a bearer token sent with every call;
//! * `RAILCONTACT_CNTC_TIMEOUT_S`: the longest wait for a connection or an
//!   answer (default 300 s).
//!
//! A server that cannot be reached, refuses or goes away makes that
//! `cntc_calculate` return `CNTC_err_server` (-42) with the reason on the
//! log; the element's next calculation opens a new stream and sends every
//! call the element has had, so that the new copy equals the library's. A
//! transient sequence (T = 1, 2 continuing with P = 0, 1) cannot continue
//! on a new copy (its history was on the lost one): that calculation is
//! refused with -42 until the sequence starts again (P = 2). Steady
//! rolling resumes, its first solve on the new copy from a cold start.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Mutex, OnceLock};
use std::time::{Duration, Instant};

use railcontact_proto::contact_library_request::Kind as In;
use railcontact_proto::contact_library_response::Kind as Out;
use railcontact_proto::contact_service_client::ContactServiceClient;
use railcontact_proto::{
    ContactLibraryCalculate, ContactLibraryOpen, ContactLibraryRequest, ContactLibraryResponse,
};
use tokio::sync::mpsc;
use tokio_stream::wrappers::ReceiverStream;
use tonic::metadata::{Ascii, MetadataValue};
use tonic::service::interceptor::InterceptedService;
use tonic::transport::{Certificate, Channel, ClientTlsConfig, Endpoint};

use crate::error::{CntcError, Result};
use crate::library::Entry;
use crate::remote::{decode, encode, Reply, Request, FORMAT_VERSION};

/// Where the server is and how to reach it.
#[derive(Debug, Clone)]
pub struct Settings {
    /// `HOST:PORT` or a URL.
    pub target: String,
    /// The authorities' PEM file (TLS on).
    pub tls_ca: Option<String>,
    /// The host name the server's certificate names, when not the
    /// target's.
    pub tls_server_name: Option<String>,
    /// The bearer token.
    pub token: Option<String>,
    /// The longest wait for a connection or an answer.
    pub timeout: Duration,
}

/// The server's address when `CNTC_if_mode` = 1 is set without
/// `RAILCONTACT_CNTC_SERVER`.
pub const DEFAULT_TARGET: &str = "127.0.0.1:50051";

impl Settings {
    /// The settings of the environment (see the module's documentation);
    /// `None` target when `RAILCONTACT_CNTC_SERVER` is not set.
    fn from_env() -> (Option<String>, Settings) {
        let var = |k: &str| {
            std::env::var(k)
                .ok()
                .map(|v| v.trim().to_string())
                .filter(|v| !v.is_empty())
        };
        let server = var("RAILCONTACT_CNTC_SERVER");
        let timeout = var("RAILCONTACT_CNTC_TIMEOUT_S")
            .and_then(|v| v.parse::<f64>().ok())
            .filter(|v| v.is_finite() && *v > 0.0)
            .map_or(Duration::from_secs(300), Duration::from_secs_f64);
        let settings = Settings {
            target: server.clone().unwrap_or_else(|| DEFAULT_TARGET.into()),
            tls_ca: var("RAILCONTACT_CNTC_TLS_CA"),
            tls_server_name: var("RAILCONTACT_CNTC_TLS_SERVER_NAME"),
            token: var("RAILCONTACT_CNTC_TOKEN"),
            timeout,
        };
        (server, settings)
    }
}

/// Whether calculations are forwarded, and where.
struct State {
    on: AtomicBool,
    settings: Settings,
}

fn state() -> &'static State {
    static STATE: OnceLock<State> = OnceLock::new();
    STATE.get_or_init(|| {
        let (server, settings) = Settings::from_env();
        State {
            on: AtomicBool::new(server.is_some()),
            settings,
        }
    })
}

/// Whether calculations are forwarded to a server.
pub fn enabled() -> bool {
    state().on.load(Ordering::Relaxed)
}

/// Turns forwarding on or off (`CNTC_if_mode` 1 or 0); it applies from
/// each element's next calculation.
pub fn set_enabled(on: bool) {
    state().on.store(on, Ordering::Relaxed);
}

/// The settings in force.
pub fn settings() -> &'static Settings {
    &state().settings
}

/// The runtime the streams run on (one thread, started on first use).
fn runtime() -> Result<&'static tokio::runtime::Runtime> {
    static RT: OnceLock<std::result::Result<tokio::runtime::Runtime, String>> = OnceLock::new();
    RT.get_or_init(|| {
        tokio::runtime::Builder::new_multi_thread()
            .worker_threads(1)
            .thread_name("contact_addon-forward")
            .enable_all()
            .build()
            .map_err(|e| e.to_string())
    })
    .as_ref()
    .map_err(|e| CntcError::Server(format!("cannot start the forwarding thread: {e}")))
}

/// Runs `fut` on the runtime and waits for it on this thread (which may
/// be any thread, also one inside another runtime).
fn block_on<T: Send + 'static>(
    fut: impl std::future::Future<Output = Result<T>> + Send + 'static,
) -> Result<T> {
    let rt = runtime()?;
    let (tx, rx) = std::sync::mpsc::sync_channel(1);
    rt.spawn(async move {
        let _ = tx.send(fut.await);
    });
    rx.recv()
        .unwrap_or_else(|_| Err(CntcError::Server("the forwarding thread stopped".into())))
}

/// Adds `authorization: Bearer TOKEN` to every call, when there is a
/// token.
#[derive(Clone)]
struct Bearer(Option<MetadataValue<Ascii>>);

impl tonic::service::Interceptor for Bearer {
    fn call(
        &mut self,
        mut req: tonic::Request<()>,
    ) -> std::result::Result<tonic::Request<()>, tonic::Status> {
        if let Some(v) = &self.0 {
            req.metadata_mut().insert("authorization", v.clone());
        }
        Ok(req)
    }
}

type Client = ContactServiceClient<InterceptedService<Channel, Bearer>>;

/// The connection every element's stream shares (HTTP/2 multiplexes
/// them), made at the first need and again after a failure.
static CHANNEL: Mutex<Option<Client>> = Mutex::new(None);

/// The shared client, connected when there is none.
async fn client(s: &Settings) -> Result<Client> {
    if let Some(c) = CHANNEL.lock().unwrap_or_else(|p| p.into_inner()).clone() {
        return Ok(c);
    }
    let c = connect(s).await?;
    *CHANNEL.lock().unwrap_or_else(|p| p.into_inner()) = Some(c.clone());
    Ok(c)
}

/// Forgets the shared connection (after a transport failure).
fn drop_client() {
    *CHANNEL.lock().unwrap_or_else(|p| p.into_inner()) = None;
}

/// Connects to the server of `s`.
async fn connect(s: &Settings) -> Result<Client> {
    let bad = |what: String| CntcError::Server(what);
    let token =
        match &s.token {
            None => Bearer(None),
            Some(t) => Bearer(Some(
                format!("Bearer {t}")
                    .parse::<MetadataValue<Ascii>>()
                    .map_err(|_| {
                        bad("RAILCONTACT_CNTC_TOKEN is not a valid token (printable ASCII, no line \
                     breaks)"
                    .into())
                    })?,
            )),
        };
    let uri = if s.target.contains("://") {
        s.target.clone()
    } else if s.tls_ca.is_some() {
        format!("https://{}", s.target)
    } else {
        format!("http://{}", s.target)
    };
    let mut endpoint = Endpoint::from_shared(uri.clone())
        .map_err(|e| bad(format!("RAILCONTACT_CNTC_SERVER = {}: {e}", s.target)))?
        .connect_timeout(s.timeout)
        .tcp_nodelay(true);
    if let Some(ca) = &s.tls_ca {
        let pem = std::fs::read(ca).map_err(|e| {
            bad(format!(
                "RAILCONTACT_CNTC_TLS_CA = {ca}: cannot read it: {e}"
            ))
        })?;
        let mut tls = ClientTlsConfig::new().ca_certificate(Certificate::from_pem(pem));
        if let Some(name) = &s.tls_server_name {
            tls = tls.domain_name(name.clone());
        }
        endpoint = endpoint
            .tls_config(tls)
            .map_err(|e| bad(format!("RAILCONTACT_CNTC_TLS_CA = {ca}: {}", chain(&e))))?;
    }
    match tokio::time::timeout(s.timeout, endpoint.connect()).await {
        Ok(Ok(channel)) => Ok(ContactServiceClient::with_interceptor(channel, token)
            .max_decoding_message_size(usize::MAX)
            .max_encoding_message_size(usize::MAX)),
        Ok(Err(e)) => {
            let text = chain(&e);
            let hint = tls_hint(&text, s.tls_ca.is_some());
            Err(bad(format!("cannot connect to {uri}: {text}{hint}")))
        }
        Err(_) => Err(bad(format!(
            "cannot connect to {uri}: no answer within {:.0} s",
            s.timeout.as_secs_f64()
        ))),
    }
}

/// An error with its sources.
fn chain(e: &dyn std::error::Error) -> String {
    let mut s = e.to_string();
    let mut source = e.source();
    while let Some(c) = source {
        let t = c.to_string();
        if !s.contains(&t) {
            s.push_str(": ");
            s.push_str(&t);
        }
        source = c.source();
    }
    s
}

/// What a status from the server `s` names means to the caller.
fn status_error(s: &Settings, st: &tonic::Status) -> CntcError {
    let hint = match st.code() {
        tonic::Code::Unauthenticated | tonic::Code::PermissionDenied => {
            " (RAILCONTACT_CNTC_TOKEN: a token the server accepts)"
        }
        tonic::Code::Unimplemented => " (the server is older than this library)",
        _ => tls_hint(st.message(), s.tls_ca.is_some()),
    };
    CntcError::Server(format!(
        "{} answered {:?}: {}{hint}",
        s.target,
        st.code(),
        st.message()
    ))
}

/// What a connection or call error most likely means for TLS, as words to
/// append to it ("" when it is not about TLS): `text` the error,
/// `with_tls` whether the library used TLS.
fn tls_hint(text: &str, with_tls: bool) -> &'static str {
    if text.contains("CaUsedAsEndEntity") {
        " (the server's certificate is an authority's, which TLS refuses as a server's: sign \
         a server certificate with a test authority, as railcontact's README shows)"
    } else if with_tls && text.contains("InvalidContentType") {
        " (the server answered in plaintext: it does not use TLS; unset \
         RAILCONTACT_CNTC_TLS_CA)"
    } else if text.contains("Connection refused") {
        " (no server listens there: start one, or set RAILCONTACT_CNTC_SERVER to its HOST:PORT)"
    } else if !with_tls
        && ["transport error", "connection reset", "h2 protocol error"]
            .iter()
            .any(|m| text.contains(m))
    {
        " (if the server uses TLS, set RAILCONTACT_CNTC_TLS_CA to the authority of its \
         certificate)"
    } else {
        ""
    }
}

/// One element's stream to the server.
pub struct Link {
    requests: mpsc::Sender<ContactLibraryRequest>,
    responses: tonic::Streaming<ContactLibraryResponse>,
    /// The server's copy holds none of the element's history (opened after
    /// a lost one) until its first calculation.
    fresh_after_loss: bool,
}

impl Link {
    /// Opens the stream of element `ire` of `module`.
    async fn open(s: Settings, module: u8, ire: i32) -> Result<Link> {
        let mut client = client(&s).await?;
        let (tx, rx) = mpsc::channel(2);
        tx.send(ContactLibraryRequest {
            kind: Some(In::Open(ContactLibraryOpen {
                format_version: FORMAT_VERSION,
                module: module as i32,
                ire,
                client_label: format!("contact_addon pid {}", std::process::id()),
            })),
        })
        .await
        .map_err(|_| CntcError::Server("the stream closed at once".into()))?;
        let call = client.contact_library(ReceiverStream::new(rx));
        let mut responses = match tokio::time::timeout(s.timeout, call).await {
            Ok(Ok(r)) => r.into_inner(),
            Ok(Err(st)) => {
                if st.code() == tonic::Code::Unavailable {
                    drop_client();
                }
                return Err(status_error(&s, &st));
            }
            Err(_) => return Err(timeout_error(&s)),
        };
        match tokio::time::timeout(s.timeout, responses.message()).await {
            Ok(Ok(Some(ContactLibraryResponse {
                kind: Some(Out::Opened(o)),
            }))) if o.format_version == FORMAT_VERSION => Ok(Link {
                requests: tx,
                responses,
                fresh_after_loss: false,
            }),
            Ok(Ok(Some(ContactLibraryResponse {
                kind: Some(Out::Opened(o)),
            }))) => Err(CntcError::Server(format!(
                "the server speaks payload version {}, this library {FORMAT_VERSION}: use a \
                 library and a server of the same release",
                o.format_version
            ))),
            Ok(Ok(_)) => Err(CntcError::Server(
                "the server did not open the element's stream".into(),
            )),
            Ok(Err(st)) => Err(status_error(&s, &st)),
            Err(_) => Err(timeout_error(&s)),
        }
    }

    /// Sends `request` and waits for its reply.
    async fn exchange(&mut self, s: &Settings, request: Vec<u8>) -> Result<Reply> {
        let timeout = s.timeout;
        let msg = ContactLibraryRequest {
            kind: Some(In::Calculate(ContactLibraryCalculate { request })),
        };
        if self.requests.send(msg).await.is_err() {
            return Err(CntcError::Server(
                "the server closed the element's stream".into(),
            ));
        }
        match tokio::time::timeout(timeout, self.responses.message()).await {
            Ok(Ok(Some(ContactLibraryResponse {
                kind: Some(Out::Reply(bytes)),
            }))) => decode(&bytes, "server's reply"),
            Ok(Ok(Some(ContactLibraryResponse {
                kind: Some(Out::Error(e)),
            }))) => Err(CntcError::Server(format!(
                "the server refused the calculation: {}",
                e.message
            ))),
            Ok(Ok(_)) => Err(CntcError::Server(
                "the server closed the element's stream".into(),
            )),
            Ok(Err(st)) => Err(status_error(s, &st)),
            Err(_) => Err(CntcError::Server(format!(
                "no answer within {:.0} s (RAILCONTACT_CNTC_TIMEOUT_S)",
                timeout.as_secs_f64()
            ))),
        }
    }
}

fn timeout_error(s: &Settings) -> CntcError {
    CntcError::Server(format!(
        "no answer from {} within {:.0} s (RAILCONTACT_CNTC_TIMEOUT_S)",
        s.target,
        s.timeout.as_secs_f64()
    ))
}

/// `cntc_calculate` of patch `icp` of element `ire` on the server: sends
/// the calls the server has not had, takes the results into the element
/// and returns the calculation's code.
pub fn calculate(entry: &mut Entry, ire: i32, icp: i32) -> Result<i32> {
    let s = settings().clone();
    let t0 = Instant::now();
    let mut link = match entry.link.take() {
        Some(l) => l,
        None => {
            if !entry.log.complete() {
                return Err(CntcError::Server(
                    "the element has had more configuring calls than a new server copy can be \
                     given; configure it anew (cntc_initialize) to forward it"
                        .into(),
                ));
            }
            let module = entry.element.module();
            let mut l = block_on(Link::open(s.clone(), module, ire))?;
            l.fresh_after_loss = entry.lost;
            entry.log.mark_unsent();
            l
        }
    };
    if link.fresh_after_loss && continues_transient(entry, icp) {
        entry.link = Some(link);
        return Err(CntcError::Server(
            "the server copy of this element was lost with its transient history: start the \
             sequence again (P = 2)"
                .into(),
        ));
    }
    let request = match encode(&Request {
        calls: entry.log.unsent().to_vec(),
        icp,
    }) {
        Ok(r) => r,
        Err(e) => {
            entry.link = Some(link);
            return Err(e);
        }
    };
    let settings = s.clone();
    let (result, link) = block_on(async move {
        let r = link.exchange(&settings, request).await;
        Ok((r, link))
    })?;
    match result {
        Ok(reply) => {
            let mut link = link;
            link.fresh_after_loss = false;
            entry.log.mark_sent();
            entry.link = Some(link);
            entry.lost = false;
            let seconds = t0.elapsed().as_secs_f64();
            entry
                .element
                .accept_calculation(icp, reply.result, seconds)?;
            reply.code.map_err(CntcError::from)
        }
        Err(e) => {
            // The stream is gone: the next calculation opens another and
            // sends everything again.
            entry.lost = true;
            drop_client();
            Err(e)
        }
    }
}

/// Whether calculating `icp` of `entry` continues a transient sequence
/// (T = 1, 2 with P = 0, 1 after an earlier result).
fn continues_transient(entry: &mut Entry, icp: i32) -> bool {
    match &mut entry.element {
        crate::element::Element::Basic(_) => entry
            .element
            .patch_mut(icp)
            .map(|p| {
                let d = p.config.digits;
                (d.tang == 1 || d.tang == 2) && d.pvtime <= 1 && p.outcome.is_some()
            })
            .unwrap_or(false),
        crate::element::Element::WheelRail(_) => false,
    }
}

#[cfg(test)]
mod tests {
    use super::tls_hint;

    /// The errors seen connecting (tonic 0.14 with rustls): a CA
    /// certificate as the server's, TLS to a plaintext port, plaintext to
    /// a TLS port (the text varies with when the server's alert arrives),
    /// no server at all.
    #[test]
    fn connection_mistakes_get_a_hint() {
        let ca = "transport error: invalid peer certificate: Other(OtherError(CaUsedAsEndEntity))";
        assert!(tls_hint(ca, true).contains("test authority"));
        let plain = "transport error: received corrupt message of type InvalidContentType";
        assert!(tls_hint(plain, true).contains("unset RAILCONTACT_CNTC_TLS_CA"));
        for text in ["transport error", "h2 protocol error: http2 error"] {
            assert!(
                tls_hint(text, false).contains("set RAILCONTACT_CNTC_TLS_CA"),
                "{text}"
            );
        }
        let refused = "transport error: tcp connect error: Connection refused (os error 111)";
        assert!(tls_hint(refused, false).contains("no server listens"));
        assert_eq!(tls_hint("Unavailable: too busy", false), "");
    }
}
