//! The server's connections: accepted here, counted against
//! `max_connections` and each address's `client_max_connections`, and
//! closed when they start no call in time or when the server ends one of
//! their streams whose client reads nothing.
//!
//! tonic's own listener accepts every connection and keeps it as long as
//! the peer keeps its socket open: a client that connects (plain TCP, or
//! TLS without finishing its handshake) and never sends a byte holds a
//! descriptor forever. Here each accepted socket is:
//!
//! - refused (closed at once) when the server holds `max_connections`, or
//!   the peer's address `client_max_connections` (a quota by address:
//!   connections come before any token; a proxy of `trusted_proxies` has
//!   none); counted in `railcontact_quota_refused_total{quota}`;
//! - closed when it has not started its first call (a TLS handshake, the
//!   HTTP/2 preface and a request's headers) within
//!   `connection_first_call_timeout_s`; counted in
//!   `railcontact_connections_timed_out_total`. Once a call came, HTTP/2
//!   keepalive (`http2_keepalive_interval_s`) finds a peer that vanished;
//! - with TLS, given its handshake here (tokio-rustls, the configuration
//!   of [`crate::service::tls::server_tls`]), in a task of its own so that
//!   a slow client holds up no other; a handshake that fails is logged
//!   (WARN, with the peer and rustls' reason in plain words; at most 20
//!   lines per 10 s of each class, [`HandshakeFailure::log`])
//!   and counted in `railcontact_tls_handshakes_failed_total{reason}` by
//!   class ([`HandshakeFailure`]), one that times out too. A peer that
//!   closes without having sent a byte (a port check) is neither;
//! - counted in `railcontact_connections_failed_before_call_total` when it
//!   sent bytes but ended before its first call (a failed TLS handshake
//!   among them), and logged (rate-limited, with the peer) unless its
//!   failed handshake was: without TLS a client speaking something else
//!   (TLS to this plaintext port), with TLS a client that finished its
//!   handshake but spoke no gRPC. A connection that sent nothing is not;
//! - closed when a handler aborts it ([`ConnState::abort`]): a streamed
//!   response whose client read nothing for `stream_write_timeout_s`
//!   ([`crate::service::streams`]). HTTP/2 keeps what it has buffered for
//!   a stream until that stream or its connection ends, and only the
//!   client can end a stream it does not read; closing the connection
//!   gives all of it back.
//!
//! [`ConnInfo`] reaches every request's extensions (tonic puts the
//! connection's [`Connected::connect_info`] there): the token check marks
//! the connection as having started a call, and reads the peer's address
//! from it; with TLS it holds the client's certificates
//! ([`ConnInfo::peer_certs`]).

use std::future::Future;
use std::io;
use std::net::SocketAddr;
use std::pin::Pin;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::task::{Context, Poll, Waker};
use std::time::Duration;

use rustls_pki_types::CertificateDer;
use tokio::io::{AsyncRead, AsyncWrite, ReadBuf};
use tokio::net::{TcpListener, TcpStream};
use tokio::task::JoinSet;
use tokio::time::Sleep;
use tokio_rustls::server::TlsStream;
use tokio_rustls::TlsAcceptor;
use tokio_stream::Stream;
use tonic::transport::server::Connected;

use crate::service::metrics::Metrics;
use crate::service::quota::{ClientId, Quota, QuotaGuard, TrustedProxies, CONNECTIONS_LOG};
use crate::service::tls::HandshakeFailure;

/// What a connection's requests and its socket share.
#[derive(Debug, Default)]
pub struct ConnState {
    /// A call has started on it.
    called: AtomicBool,
    /// The server ends it.
    aborted: AtomicBool,
    /// The task reading the socket, woken to close it.
    reader: Mutex<Option<Waker>>,
}

impl ConnState {
    /// A call started on the connection: it stays open past
    /// `connection_first_call_timeout_s`.
    pub fn called(&self) {
        if !self.called.load(Ordering::Relaxed) {
            self.called.store(true, Ordering::Relaxed);
        }
    }

    /// Closes the connection (its socket reports an error to HTTP/2 at the
    /// next read, which ends every stream on it and frees their buffers).
    pub fn abort(&self) {
        self.aborted.store(true, Ordering::Relaxed);
        let waker = self.reader.lock().unwrap_or_else(|e| e.into_inner()).take();
        if let Some(w) = waker {
            w.wake();
        }
    }

    /// Whether [`ConnState::abort`] was called.
    pub fn is_aborted(&self) -> bool {
        self.aborted.load(Ordering::Relaxed)
    }
}

/// The connect info of a connection, in every request's extensions.
#[derive(Debug, Clone)]
pub struct ConnInfo {
    /// The peer's address.
    pub remote: SocketAddr,
    /// Shared with the socket.
    pub state: Arc<ConnState>,
    /// With TLS, the certificate chain the client presented (mTLS), as
    /// tonic's `TlsConnectInfo::peer_certs` gives it; None without TLS or
    /// without a client certificate.
    pub peer_certs: Option<Arc<Vec<CertificateDer<'static>>>>,
}

/// An accepted connection: the socket, its count in the quotas (given back
/// when it closes), and the time limit for its first call.
pub struct Conn {
    io: TcpStream,
    info: ConnInfo,
    first_call: Option<Pin<Box<Sleep>>>,
    metrics: Arc<Metrics>,
    /// The server speaks TLS on it.
    tls: bool,
    /// Its TLS handshake is under way (or failed, and was logged then).
    in_handshake: bool,
    /// The peer sent at least one byte.
    sent_bytes: bool,
    _counted: QuotaGuard,
}

impl Drop for Conn {
    fn drop(&mut self) {
        let state = &self.info.state;
        if !self.sent_bytes || state.called.load(Ordering::Relaxed) || state.is_aborted() {
            return;
        }
        self.metrics.connection_failed_before_call();
        if self.in_handshake {
            // Logged with its reason when the handshake failed.
            return;
        }
        if let Some(left_out) = CONNECTIONS_LOG.allow() {
            let why = match self.tls {
                true => "it finished its TLS handshake but did not speak gRPC over HTTP/2",
                false => {
                    "it did not speak gRPC over plaintext HTTP/2 (TLS sent to this plaintext port?)"
                }
            };
            tracing::info!(peer = %self.info.remote, left_out, "connection ended before its first call: {why}");
        }
    }
}

impl Connected for Conn {
    type ConnectInfo = ConnInfo;

    fn connect_info(&self) -> ConnInfo {
        self.info.clone()
    }
}

impl Conn {
    /// An error when the connection is to be closed: the server aborted
    /// it, or it started no call in time (registering the timer's wake-up
    /// while it waits).
    fn check(&mut self, cx: &mut Context<'_>) -> io::Result<()> {
        let state = &self.info.state;
        if state.is_aborted() {
            return Err(io::Error::new(
                io::ErrorKind::ConnectionAborted,
                "closed by the server",
            ));
        }
        if let Some(timer) = &mut self.first_call {
            if state.called.load(Ordering::Relaxed) {
                self.first_call = None;
            } else if timer.as_mut().poll(cx).is_ready() {
                self.first_call = None;
                self.metrics.connection_timed_out();
                // A handshake that times out is logged as a failed one.
                let logged = self.in_handshake;
                if let Some(left_out) = (!logged).then(|| CONNECTIONS_LOG.allow()).flatten() {
                    tracing::info!(
                        peer = %self.info.remote,
                        left_out,
                        "connection closed: no call within connection_first_call_timeout_s"
                    );
                }
                // Not counted as called: the next poll fails again.
                state.aborted.store(true, Ordering::Relaxed);
                return Err(io::Error::new(
                    io::ErrorKind::TimedOut,
                    "no call within connection_first_call_timeout_s",
                ));
            }
        }
        Ok(())
    }
}

impl AsyncRead for Conn {
    fn poll_read(
        self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &mut ReadBuf<'_>,
    ) -> Poll<io::Result<()>> {
        let this = self.get_mut();
        {
            let mut reader = this
                .info
                .state
                .reader
                .lock()
                .unwrap_or_else(|e| e.into_inner());
            if !reader.as_ref().is_some_and(|w| w.will_wake(cx.waker())) {
                *reader = Some(cx.waker().clone());
            }
        }
        this.check(cx)?;
        let before = buf.filled().len();
        let r = Pin::new(&mut this.io).poll_read(cx, buf);
        if buf.filled().len() > before {
            this.sent_bytes = true;
        }
        r
    }
}

impl AsyncWrite for Conn {
    fn poll_write(
        self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &[u8],
    ) -> Poll<io::Result<usize>> {
        let this = self.get_mut();
        this.check(cx)?;
        Pin::new(&mut this.io).poll_write(cx, buf)
    }

    fn poll_write_vectored(
        self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        bufs: &[io::IoSlice<'_>],
    ) -> Poll<io::Result<usize>> {
        let this = self.get_mut();
        this.check(cx)?;
        Pin::new(&mut this.io).poll_write_vectored(cx, bufs)
    }

    fn is_write_vectored(&self) -> bool {
        self.io.is_write_vectored()
    }

    fn poll_flush(self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        Pin::new(&mut self.get_mut().io).poll_flush(cx)
    }

    fn poll_shutdown(self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        Pin::new(&mut self.get_mut().io).poll_shutdown(cx)
    }
}

/// The listener's connections, as tonic takes them
/// (`serve_with_incoming_shutdown`): counted, with TCP_NODELAY (without
/// it, a response written in two segments waits for the client's delayed
/// ACK, about 40 ms a call), and with their first-call timer. Dropping it
/// closes the listening socket.
pub struct Incoming {
    listener: TcpListener,
    quota: Arc<Quota>,
    proxies: TrustedProxies,
    first_call: Duration,
    metrics: Arc<Metrics>,
    /// The server speaks TLS on these connections.
    tls: Option<TlsAcceptor>,
    /// The TLS handshakes under way (aborted when this is dropped).
    handshakes: JoinSet<Option<TlsStream<Conn>>>,
    /// After an accept error such as too many open files: a pause, so that
    /// the loop does not spin while the error lasts.
    pause: Option<Pin<Box<Sleep>>>,
}

impl Incoming {
    /// Accepts on `listener`, counting into `quota` (the connections of
    /// `proxies` against its server-wide cap only), closing connections
    /// without a call after `first_call` (their TLS handshake included);
    /// with `tls`, the server's TLS configuration, it speaks TLS on them.
    pub fn new(
        listener: TcpListener,
        quota: Arc<Quota>,
        proxies: TrustedProxies,
        first_call: Duration,
        metrics: Arc<Metrics>,
        tls: Option<Arc<tokio_rustls::rustls::ServerConfig>>,
    ) -> Self {
        Self {
            listener,
            quota,
            proxies,
            first_call,
            metrics,
            tls: tls.map(TlsAcceptor::from),
            handshakes: JoinSet::new(),
            pause: None,
        }
    }
}

/// The TLS handshake of `conn`: the stream once done; on failure, the
/// reason logged and counted, and None.
async fn handshake(acceptor: TlsAcceptor, conn: Conn) -> Option<TlsStream<Conn>> {
    match acceptor.accept(conn).into_fallible().await {
        Ok(mut stream) => {
            stream.get_mut().0.in_handshake = false;
            Some(stream)
        }
        Err((e, conn)) => {
            let (failure, why) = HandshakeFailure::of(&e);
            if failure == HandshakeFailure::Closed && !conn.sent_bytes {
                // A port check: connected, sent nothing, closed.
                return None;
            }
            conn.metrics.tls_handshake_failed(failure.label());
            if let Some(left_out) = failure.log().allow() {
                tracing::warn!(
                    peer = %conn.info.remote,
                    reason = failure.label(),
                    left_out,
                    "TLS handshake failed: {why}"
                );
            }
            None
        }
    }
}

/// A connection as tonic serves it: the accepted socket, or the TLS
/// stream on it once its handshake succeeded.
pub enum ServerConn {
    /// Without TLS.
    Plain(Conn),
    /// With TLS.
    Tls(Box<TlsStream<Conn>>),
}

impl Connected for ServerConn {
    type ConnectInfo = ConnInfo;

    fn connect_info(&self) -> ConnInfo {
        match self {
            ServerConn::Plain(conn) => conn.info.clone(),
            ServerConn::Tls(stream) => {
                let (conn, session) = stream.get_ref();
                ConnInfo {
                    peer_certs: session.peer_certificates().map(|c| Arc::new(c.to_vec())),
                    ..conn.info.clone()
                }
            }
        }
    }
}

impl AsyncRead for ServerConn {
    fn poll_read(
        self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &mut ReadBuf<'_>,
    ) -> Poll<io::Result<()>> {
        match self.get_mut() {
            ServerConn::Plain(c) => Pin::new(c).poll_read(cx, buf),
            ServerConn::Tls(s) => Pin::new(s.as_mut()).poll_read(cx, buf),
        }
    }
}

impl AsyncWrite for ServerConn {
    fn poll_write(
        self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &[u8],
    ) -> Poll<io::Result<usize>> {
        match self.get_mut() {
            ServerConn::Plain(c) => Pin::new(c).poll_write(cx, buf),
            ServerConn::Tls(s) => Pin::new(s.as_mut()).poll_write(cx, buf),
        }
    }

    fn poll_write_vectored(
        self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        bufs: &[io::IoSlice<'_>],
    ) -> Poll<io::Result<usize>> {
        match self.get_mut() {
            ServerConn::Plain(c) => Pin::new(c).poll_write_vectored(cx, bufs),
            ServerConn::Tls(s) => Pin::new(s.as_mut()).poll_write_vectored(cx, bufs),
        }
    }

    fn is_write_vectored(&self) -> bool {
        match self {
            ServerConn::Plain(c) => c.is_write_vectored(),
            ServerConn::Tls(s) => s.is_write_vectored(),
        }
    }

    fn poll_flush(self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        match self.get_mut() {
            ServerConn::Plain(c) => Pin::new(c).poll_flush(cx),
            ServerConn::Tls(s) => Pin::new(s.as_mut()).poll_flush(cx),
        }
    }

    fn poll_shutdown(self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        match self.get_mut() {
            ServerConn::Plain(c) => Pin::new(c).poll_shutdown(cx),
            ServerConn::Tls(s) => Pin::new(s.as_mut()).poll_shutdown(cx),
        }
    }
}

impl Stream for Incoming {
    type Item = io::Result<ServerConn>;

    fn poll_next(self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<Option<Self::Item>> {
        let this = self.get_mut();
        loop {
            // Handshakes done first (a failed one has been logged; a task
            // that panicked has dropped its connection).
            while let Poll::Ready(Some(done)) = this.handshakes.poll_join_next(cx) {
                if let Ok(Some(stream)) = done {
                    return Poll::Ready(Some(Ok(ServerConn::Tls(Box::new(stream)))));
                }
            }
            if let Some(pause) = &mut this.pause {
                std::task::ready!(pause.as_mut().poll(cx));
                this.pause = None;
            }
            match std::task::ready!(this.listener.poll_accept(cx)) {
                Ok((io, remote)) => {
                    let client = match this.proxies.trusts(remote.ip()) {
                        true => ClientId::Proxy(remote.ip()),
                        false => ClientId::peer(remote.ip()),
                    };
                    match this.quota.take(&client) {
                        Ok(counted) => {
                            let _ = io.set_nodelay(true);
                            let info = ConnInfo {
                                remote,
                                state: Arc::default(),
                                peer_certs: None,
                            };
                            let conn = Conn {
                                io,
                                info,
                                first_call: Some(Box::pin(tokio::time::sleep(this.first_call))),
                                metrics: this.metrics.clone(),
                                tls: this.tls.is_some(),
                                in_handshake: this.tls.is_some(),
                                sent_bytes: false,
                                _counted: counted,
                            };
                            match &this.tls {
                                None => return Poll::Ready(Some(Ok(ServerConn::Plain(conn)))),
                                Some(acceptor) => {
                                    this.handshakes.spawn(handshake(acceptor.clone(), conn));
                                }
                            }
                        }
                        Err(refusal) => {
                            if let Some(left_out) = CONNECTIONS_LOG.allow() {
                                tracing::info!(
                                    peer = %remote,
                                    quota = refusal.setting,
                                    left_out,
                                    "connection refused: {}",
                                    refusal.message
                                );
                            }
                            drop(io);
                        }
                    }
                }
                Err(e) => {
                    // Connection errors (reset before accepted) concern one
                    // connection; resource errors (descriptors, memory)
                    // last a while.
                    use io::ErrorKind as K;
                    let transient = matches!(
                        e.kind(),
                        K::ConnectionAborted | K::ConnectionReset | K::Interrupted | K::WouldBlock
                    );
                    if !transient {
                        if let Some(left_out) = CONNECTIONS_LOG.allow() {
                            tracing::warn!(
                                error = %e,
                                left_out,
                                "cannot accept a connection (out of file descriptors? raise the \
                                 limit or lower max_connections); pausing 100 ms"
                            );
                        }
                        this.pause = Some(Box::pin(tokio::time::sleep(Duration::from_millis(100))));
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use rustls_pki_types::pem::PemObject;
    use rustls_pki_types::PrivateKeyDer;
    use tokio_rustls::rustls::{ClientConfig, RootCertStore};
    use tokio_stream::StreamExt;

    use super::*;
    use crate::service::config::ServeConfig;
    use crate::service::quota::Resource;

    /// Under mutual TLS the client's certificate chain reaches the connect
    /// info that every request of the connection carries (what tonic's
    /// `TlsConnectInfo::peer_certs` gave when tonic did the handshake).
    #[tokio::test]
    async fn a_client_certificate_reaches_the_connect_info() {
        let dir = tempfile::tempdir().unwrap();
        railcontact_testkit::write_test_pki(dir.path());
        let path = |name: &str| dir.path().join(name);
        let config = ServeConfig {
            tls_cert: Some(path("server.pem")),
            tls_key: Some(path("server-key.pem")),
            tls_client_ca: Some(path("ca.pem")),
            ..ServeConfig::default()
        };
        let tls = crate::service::tls::server_tls(&config).unwrap();
        let listener = TcpListener::bind("127.0.0.1:0").await.unwrap();
        let addr = listener.local_addr().unwrap();
        let metrics = Arc::new(Metrics::default());
        let quota = Quota::new(Resource::Connections, Some(4), 4, metrics.clone());
        let mut incoming = Incoming::new(
            listener,
            quota,
            TrustedProxies::new(&[]),
            Duration::from_secs(10),
            metrics,
            tls,
        );

        let pem = |name: &str| std::fs::read(path(name)).unwrap();
        let certs = |name: &str| -> Vec<CertificateDer<'static>> {
            CertificateDer::pem_slice_iter(&pem(name))
                .map(Result::unwrap)
                .collect()
        };
        let mut roots = RootCertStore::empty();
        roots.add_parsable_certificates(certs("ca.pem"));
        let chain = certs("client.pem");
        let key = PrivateKeyDer::from_pem_slice(&pem("client-key.pem")).unwrap();
        let client = ClientConfig::builder()
            .with_root_certificates(roots)
            .with_client_auth_cert(chain.clone(), key)
            .unwrap();
        let connector = tokio_rustls::TlsConnector::from(Arc::new(client));
        let dial = async {
            let tcp = TcpStream::connect(addr).await.unwrap();
            let local = tcp.local_addr().unwrap();
            let name = "localhost".try_into().unwrap();
            (connector.connect(name, tcp).await.unwrap(), local)
        };
        let ((_stream, local), accepted) = tokio::join!(dial, incoming.next());
        let conn = accepted.expect("a connection").expect("accepted");
        assert!(matches!(conn, ServerConn::Tls(_)));
        let info = conn.connect_info();
        assert_eq!(info.remote, local);
        assert_eq!(info.peer_certs.as_deref(), Some(&chain));
    }
}
