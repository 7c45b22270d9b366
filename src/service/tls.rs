//! TLS of the gRPC port (rustls with the ring provider, through
//! tokio-rustls): the server's certificate and key (`tls_cert`, `tls_key`)
//! and, for mutual TLS, the authorities of the client certificates
//! (`tls_client_ca`, then required). The files are read and checked once,
//! at start; a changed certificate takes effect at the next start. The
//! validity of the certificates read is checked then and once a day while
//! the server runs ([`Validity`]): one that has expired, is not valid yet,
//! or expires within [`EXPIRY_WARNING_DAYS`] is a warning on the log.
//!
//! The server does each handshake itself ([`crate::service::connections`])
//! with the configuration tonic's `ServerTlsConfig` would build from the
//! same files ([`server_tls`]), so that a failed one is logged and counted
//! with its reason ([`HandshakeFailure`]): a client that refuses the
//! server's certificate says so in an alert, which is the only way the
//! server learns of it.

use std::io;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Duration;

use rustls_pki_types::pem::PemObject;
use rustls_pki_types::{CertificateDer, PrivateKeyDer};
use thiserror::Error;
use tokio_rustls::rustls;
use tokio_rustls::rustls::server::WebPkiClientVerifier;
use tokio_rustls::rustls::{CertificateError, RootCertStore, ServerConfig};

use crate::service::config::ServeConfig;
use crate::service::quota::LogLimiter;

/// Why the TLS settings cannot be used; each names the setting and its
/// file.
#[derive(Debug, Error)]
pub enum TlsError {
    /// The file cannot be read.
    #[error("{key} {}: cannot read it: {source}", .path.display())]
    Read {
        /// The setting (`tls_cert`, `tls_key`, `tls_client_ca`).
        key: &'static str,
        /// Its file.
        path: PathBuf,
        /// What reading said.
        source: std::io::Error,
    },
    /// The file holds no valid PEM item of the kind the setting needs.
    #[error("{key} {}: {reason}", .path.display())]
    Pem {
        /// The setting.
        key: &'static str,
        /// Its file.
        path: PathBuf,
        /// What is wrong.
        reason: String,
    },
    /// rustls refused the certificate and key together (e.g. the key is
    /// not the certificate's).
    #[error("tls_cert {} with tls_key {}: {reason}", .cert.display(), .key.display())]
    Identity {
        /// The certificate file.
        cert: PathBuf,
        /// The key file.
        key: PathBuf,
        /// What rustls said.
        reason: String,
    },
    /// rustls cannot check client certificates with these authorities
    /// (none of them usable as a trust anchor).
    #[error("tls_client_ca {}: {reason}", .path.display())]
    ClientCa {
        /// The file of the authorities.
        path: PathBuf,
        /// What rustls said.
        reason: String,
    },
}

fn read(key: &'static str, path: &Path) -> Result<Vec<u8>, TlsError> {
    std::fs::read(path).map_err(|source| TlsError::Read {
        key,
        path: path.to_path_buf(),
        source,
    })
}

/// Reads a PEM file of certificates: at least one, all valid.
fn certificates(key: &'static str, path: &Path) -> Result<Vec<CertificateDer<'static>>, TlsError> {
    let pem = read(key, path)?;
    let bad = |reason: String| TlsError::Pem {
        key,
        path: path.to_path_buf(),
        reason,
    };
    let certs = CertificateDer::pem_slice_iter(&pem)
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| bad(format!("not valid PEM: {e}")))?;
    if certs.is_empty() {
        return Err(bad("holds no PEM certificate (BEGIN CERTIFICATE)".into()));
    }
    Ok(certs)
}

/// Reads a PEM file holding a private key.
fn private_key(path: &Path) -> Result<PrivateKeyDer<'static>, TlsError> {
    let pem = read("tls_key", path)?;
    PrivateKeyDer::from_pem_slice(&pem).map_err(|e| TlsError::Pem {
        key: "tls_key",
        path: path.to_path_buf(),
        reason: format!("holds no valid PEM private key (PKCS#8, PKCS#1 or SEC1): {e}"),
    })
}

/// Days before a certificate's end from which the log warns of it.
pub const EXPIRY_WARNING_DAYS: i64 = 30;

/// When the certificates the server uses are valid: those of `tls_cert`
/// and `tls_client_ca`, as read at start.
#[derive(Debug, Clone, Default)]
pub struct Validity {
    /// (setting, file, subject, not before, not after \[s since 1970\]).
    certificates: Vec<(&'static str, PathBuf, String, i64, i64)>,
}

impl Validity {
    /// The validity of the certificates of `config`'s TLS files (none
    /// without TLS); a certificate that cannot be parsed is left out
    /// (rustls checks the files: [`server_tls`]).
    pub fn of(config: &ServeConfig) -> Self {
        let mut certificates = Vec::new();
        let files = [
            ("tls_cert", &config.tls_cert),
            ("tls_client_ca", &config.tls_client_ca),
        ];
        for (key, path) in files {
            let Some(path) = path else { continue };
            let Ok(pem) = std::fs::read(path) else {
                continue;
            };
            for der in CertificateDer::pem_slice_iter(&pem).flatten() {
                if let Ok((_, c)) = x509_parser::parse_x509_certificate(&der) {
                    let v = c.validity();
                    certificates.push((
                        key,
                        path.clone(),
                        c.subject().to_string(),
                        v.not_before.timestamp(),
                        v.not_after.timestamp(),
                    ));
                }
            }
        }
        Self { certificates }
    }

    /// A warning for each certificate that at `now` (s since 1970) has
    /// expired, is not valid yet, or expires within
    /// [`EXPIRY_WARNING_DAYS`].
    pub fn warnings(&self, now: i64) -> Vec<String> {
        const DAY: i64 = 86_400;
        let date = |t: i64| {
            x509_parser::time::ASN1Time::from_timestamp(t)
                .map_or_else(|_| format!("{t} s after 1970"), |d| d.to_string())
        };
        self.certificates
            .iter()
            .filter_map(|(key, path, subject, from, to)| {
                let what = format!("{key} {} (certificate of {subject})", path.display());
                if now > *to {
                    Some(format!(
                        "{what} expired on {}: clients refuse it; renew it and restart",
                        date(*to)
                    ))
                } else if now < *from {
                    Some(format!(
                        "{what} is not valid before {}: clients refuse it until then",
                        date(*from)
                    ))
                } else if *to - now < EXPIRY_WARNING_DAYS * DAY {
                    Some(format!(
                        "{what} expires on {} (in {} days): renew it and restart",
                        date(*to),
                        (*to - now) / DAY
                    ))
                } else {
                    None
                }
            })
            .collect()
    }
}

/// The TLS configuration of `config`; None without `tls_cert`. The files
/// are read and parsed here, and the certificate and key tried together,
/// so that a bad file stops the start naming it.
///
/// It is what tonic's `ServerTlsConfig` builds from an identity and a
/// client CA (tonic 0.14, `TlsAcceptor::new`): rustls' defaults of the
/// process's crypto provider (ring), client certificates required and
/// checked by webpki against `tls_client_ca` when it is set, none asked
/// otherwise, and ALPN `h2`.
pub fn server_tls(config: &ServeConfig) -> Result<Option<Arc<ServerConfig>>, TlsError> {
    let (Some(cert), Some(key)) = (&config.tls_cert, &config.tls_key) else {
        return Ok(None);
    };
    let chain = certificates("tls_cert", cert)?;
    let private = private_key(key)?;
    let builder = ServerConfig::builder();
    let builder = match &config.tls_client_ca {
        None => builder.with_no_client_auth(),
        Some(ca) => {
            let mut roots = RootCertStore::empty();
            roots.add_parsable_certificates(certificates("tls_client_ca", ca)?);
            let verifier = WebPkiClientVerifier::builder(roots.into())
                .build()
                .map_err(|e| TlsError::ClientCa {
                    path: ca.clone(),
                    reason: e.to_string(),
                })?;
            builder.with_client_cert_verifier(verifier)
        }
    };
    // A key that is not the certificate's, or a certificate rustls cannot
    // use, fails here.
    let mut tls = builder
        .with_single_cert(chain, private)
        .map_err(|e| TlsError::Identity {
            cert: cert.clone(),
            key: key.clone(),
            reason: e.to_string(),
        })?;
    tls.alpn_protocols.push(b"h2".to_vec());
    Ok(Some(Arc::new(tls)))
}

/// Why a TLS handshake of the gRPC port failed, in classes: the `reason`
/// label of `railcontact_tls_handshakes_failed_total`
/// ([`HandshakeFailure::label`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HandshakeFailure {
    /// The client did not speak TLS (plaintext HTTP/2 or HTTP/1 to the TLS
    /// port): `not_tls`.
    NotTls,
    /// The client sent an alert: most often it does not trust the server's
    /// certificate (`unknown_ca`, `bad_certificate`) or finds it expired
    /// (`certificate_expired`): `client_alert`.
    ClientAlert,
    /// mTLS: the client sent no certificate: `no_client_cert`.
    NoClientCert,
    /// mTLS: the client's certificate is not signed by `tls_client_ca`
    /// (or is otherwise invalid): `client_cert_untrusted`.
    ClientCertUntrusted,
    /// mTLS: the client's certificate has expired or is not valid yet:
    /// `client_cert_expired`.
    ClientCertExpired,
    /// No protocol version, cipher suite, key exchange group, signature
    /// scheme or application protocol (`h2`) in common: `incompatible`.
    Incompatible,
    /// No handshake within `connection_first_call_timeout_s`: `timeout`.
    Timeout,
    /// The client closed the connection during the handshake without an
    /// alert: `closed`.
    Closed,
    /// Anything else (a malformed or unexpected TLS message, a socket
    /// error): `other`.
    Other,
}

impl HandshakeFailure {
    /// Every class, in declaration order ([`HandshakeFailure::log`]
    /// indexes a limiter per class by it).
    pub const ALL: [Self; 9] = [
        Self::NotTls,
        Self::ClientAlert,
        Self::NoClientCert,
        Self::ClientCertUntrusted,
        Self::ClientCertExpired,
        Self::Incompatible,
        Self::Timeout,
        Self::Closed,
        Self::Other,
    ];

    /// The limiter of this class's log lines: 20 per 10 s for each class,
    /// so that a client that fails its handshake in a loop (one whose
    /// certificate is refused reconnects at once) hides no failure of
    /// another class.
    pub fn log(self) -> &'static LogLimiter {
        static LOGS: [LogLimiter; HandshakeFailure::ALL.len()] =
            [const { LogLimiter::new(20, Duration::from_secs(10)) }; HandshakeFailure::ALL.len()];
        &LOGS[self as usize]
    }

    /// The metric's label.
    pub fn label(self) -> &'static str {
        match self {
            Self::NotTls => "not_tls",
            Self::ClientAlert => "client_alert",
            Self::NoClientCert => "no_client_cert",
            Self::ClientCertUntrusted => "client_cert_untrusted",
            Self::ClientCertExpired => "client_cert_expired",
            Self::Incompatible => "incompatible",
            Self::Timeout => "timeout",
            Self::Closed => "closed",
            Self::Other => "other",
        }
    }

    /// The class of the error a handshake ended with (tokio-rustls gives
    /// rustls' error inside an `InvalidData` I/O error) and the reason in
    /// plain words for the log.
    pub fn of(e: &io::Error) -> (Self, String) {
        use rustls::Error as E;
        let Some(tls) = e.get_ref().and_then(|i| i.downcast_ref::<rustls::Error>()) else {
            return match e.kind() {
                io::ErrorKind::TimedOut => (
                    Self::Timeout,
                    "handshake timed out (no handshake within connection_first_call_timeout_s)"
                        .into(),
                ),
                io::ErrorKind::UnexpectedEof
                | io::ErrorKind::ConnectionReset
                | io::ErrorKind::BrokenPipe => (
                    Self::Closed,
                    format!("the client closed the connection during the handshake ({e})"),
                ),
                _ => (
                    Self::Other,
                    format!("socket error during the handshake: {e}"),
                ),
            };
        };
        match tls {
            E::InvalidMessage(
                rustls::InvalidMessage::InvalidContentType
                | rustls::InvalidMessage::UnknownProtocolVersion,
            ) => (
                Self::NotTls,
                format!(
                    "the client sent plaintext, not a TLS record (a client without TLS?): {tls}"
                ),
            ),
            E::AlertReceived(alert) => (
                Self::ClientAlert,
                format!(
                    "the client sent the alert {}{}",
                    alert_name(*alert),
                    match alert {
                        rustls::AlertDescription::BadCertificate
                        | rustls::AlertDescription::UnknownCA
                        | rustls::AlertDescription::UnsupportedCertificate
                        | rustls::AlertDescription::CertificateUnknown => {
                            " (the client does not trust this server's certificate: tls_cert \
                             not signed by an authority it trusts, or not for the name it \
                             connected to)"
                        }
                        rustls::AlertDescription::CertificateExpired => {
                            " (the client finds this server's certificate expired or not \
                             valid yet: renew tls_cert, or check the client's clock)"
                        }
                        _ => "",
                    }
                ),
            ),
            E::NoCertificatesPresented => (
                Self::NoClientCert,
                "no client certificate (tls_client_ca asks every client for one)".into(),
            ),
            E::InvalidCertificate(
                c @ (CertificateError::Expired
                | CertificateError::ExpiredContext { .. }
                | CertificateError::NotValidYet
                | CertificateError::NotValidYetContext { .. }),
            ) => (
                Self::ClientCertExpired,
                format!("client certificate expired or not valid yet ({c:?})"),
            ),
            E::InvalidCertificate(c) => (
                Self::ClientCertUntrusted,
                format!("client certificate not trusted under tls_client_ca ({c:?})"),
            ),
            E::PeerIncompatible(_) | E::NoApplicationProtocol => (
                Self::Incompatible,
                format!(
                    "no common protocol version, cipher suite, key exchange or application \
                     protocol (h2): {tls}"
                ),
            ),
            _ => (Self::Other, format!("TLS error: {tls}")),
        }
    }
}

/// A TLS alert as its RFC 8446 name (`unknown_ca`, `bad_certificate`).
fn alert_name(alert: rustls::AlertDescription) -> String {
    // rustls names them in CamelCase (UnknownCA, BadCertificate).
    let camel = format!("{alert:?}");
    let mut name = String::with_capacity(camel.len() + 4);
    let mut prev_lower = false;
    for ch in camel.chars() {
        if ch.is_ascii_uppercase() && prev_lower {
            name.push('_');
        }
        prev_lower = ch.is_ascii_lowercase() || ch.is_ascii_digit();
        name.push(ch.to_ascii_lowercase());
    }
    name
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `ALL` lists each class once, at its own index: each has its own
    /// log limiter, and a flood of one leaves another's lines logged.
    #[test]
    fn each_handshake_failure_class_has_its_own_log_limiter() {
        for (i, f) in HandshakeFailure::ALL.iter().enumerate() {
            assert_eq!(*f as usize, i, "{f:?}");
        }
        let flood = HandshakeFailure::ClientCertUntrusted;
        while flood.log().allow().is_some() {}
        assert!(HandshakeFailure::NoClientCert.log().allow().is_some());
    }

    /// Seconds since 1970 of a date (00:00 UTC).
    fn at(y: i32, m: u8, d: u8) -> i64 {
        rcgen::date_time_ymd(y, m, d).unix_timestamp()
    }

    #[test]
    fn an_expired_or_expiring_certificate_is_a_warning() {
        let dir = tempfile::tempdir().unwrap();
        let mut params = rcgen::CertificateParams::new(vec!["localhost".into()]).unwrap();
        params.not_before = rcgen::date_time_ymd(2030, 1, 1);
        params.not_after = rcgen::date_time_ymd(2031, 1, 1);
        let key = rcgen::KeyPair::generate().unwrap();
        let cert = params.self_signed(&key).unwrap();
        let path = dir.path().join("server.pem");
        std::fs::write(&path, cert.pem()).unwrap();
        let config = ServeConfig {
            tls_cert: Some(path.clone()),
            ..ServeConfig::default()
        };
        let v = Validity::of(&config);
        assert!(v.warnings(at(2030, 6, 1)).is_empty());
        let w = v.warnings(at(2030, 12, 20));
        assert_eq!(w.len(), 1, "{w:?}");
        assert!(
            w[0].contains("tls_cert") && w[0].contains("in 12 days"),
            "{w:?}"
        );
        let w = v.warnings(at(2031, 2, 1));
        assert!(
            w[0].contains("expired on") && w[0].contains("2031"),
            "{w:?}"
        );
        let w = v.warnings(at(2029, 12, 1));
        assert!(w[0].contains("not valid before"), "{w:?}");
        // Without TLS, nothing to check.
        assert!(Validity::of(&ServeConfig::default())
            .warnings(at(2031, 2, 1))
            .is_empty());
    }

    /// The class of each handshake error the server meets, as
    /// tokio-rustls gives it: rustls' error inside `InvalidData`, the
    /// connection's own timer and end of file as plain I/O errors.
    #[test]
    fn handshake_errors_fall_in_their_class() {
        use rustls::{AlertDescription, Error as E, InvalidMessage, PeerIncompatible};
        let tls = |e: E| io::Error::new(io::ErrorKind::InvalidData, e);
        let cases = [
            (
                tls(E::InvalidMessage(InvalidMessage::InvalidContentType)),
                HandshakeFailure::NotTls,
                "plaintext",
            ),
            (
                tls(E::AlertReceived(AlertDescription::UnknownCA)),
                HandshakeFailure::ClientAlert,
                "alert unknown_ca (the client does not trust this server's certificate",
            ),
            (
                tls(E::AlertReceived(AlertDescription::CertificateExpired)),
                HandshakeFailure::ClientAlert,
                "alert certificate_expired (the client finds",
            ),
            (
                tls(E::NoCertificatesPresented),
                HandshakeFailure::NoClientCert,
                "no client certificate",
            ),
            (
                tls(E::InvalidCertificate(CertificateError::UnknownIssuer)),
                HandshakeFailure::ClientCertUntrusted,
                "not trusted under tls_client_ca (UnknownIssuer)",
            ),
            (
                tls(E::InvalidCertificate(CertificateError::Expired)),
                HandshakeFailure::ClientCertExpired,
                "client certificate expired",
            ),
            (
                tls(E::PeerIncompatible(
                    PeerIncompatible::NoCipherSuitesInCommon,
                )),
                HandshakeFailure::Incompatible,
                "no common protocol version, cipher suite",
            ),
            (tls(E::DecryptError), HandshakeFailure::Other, "TLS error: "),
            (
                io::Error::new(io::ErrorKind::TimedOut, "no call"),
                HandshakeFailure::Timeout,
                "handshake timed out",
            ),
            (
                io::Error::new(io::ErrorKind::UnexpectedEof, "tls handshake eof"),
                HandshakeFailure::Closed,
                "closed the connection during the handshake",
            ),
        ];
        for (e, class, words) in cases {
            let (got, why) = HandshakeFailure::of(&e);
            assert_eq!(got, class, "{e}: {why}");
            assert!(why.contains(words), "{e}: {why}");
        }
    }
}
