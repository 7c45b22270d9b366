//! TLS of the gRPC port (rustls with the ring provider, through tonic):
//! the server's certificate and key (`tls_cert`, `tls_key`) and, for
//! mutual TLS, the authorities of the client certificates
//! (`tls_client_ca`). The files are read and checked once, at start; a
//! changed certificate takes effect at the next start. The validity of the
//! certificates read is checked then and once a day while the server runs
//! ([`Validity`]): one that has expired, is not valid yet, or expires
//! within [`EXPIRY_WARNING_DAYS`] is a warning on the log (clients refuse
//! an expired certificate in their handshake, which the server does not
//! see).

use std::path::{Path, PathBuf};

use rustls_pki_types::pem::PemObject;
use rustls_pki_types::{CertificateDer, PrivateKeyDer};
use thiserror::Error;
use tonic::transport::{Certificate, Identity, ServerTlsConfig};

use crate::service::config::ServeConfig;

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
}

fn read(key: &'static str, path: &Path) -> Result<Vec<u8>, TlsError> {
    std::fs::read(path).map_err(|source| TlsError::Read {
        key,
        path: path.to_path_buf(),
        source,
    })
}

/// Reads a PEM file of certificates: at least one, all valid.
fn certificates(key: &'static str, path: &Path) -> Result<Vec<u8>, TlsError> {
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
    Ok(pem)
}

/// Reads a PEM file holding a private key.
fn private_key(path: &Path) -> Result<Vec<u8>, TlsError> {
    let pem = read("tls_key", path)?;
    PrivateKeyDer::from_pem_slice(&pem).map_err(|e| TlsError::Pem {
        key: "tls_key",
        path: path.to_path_buf(),
        reason: format!("holds no valid PEM private key (PKCS#8, PKCS#1 or SEC1): {e}"),
    })?;
    Ok(pem)
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
pub fn server_tls(config: &ServeConfig) -> Result<Option<ServerTlsConfig>, TlsError> {
    let (Some(cert), Some(key)) = (&config.tls_cert, &config.tls_key) else {
        return Ok(None);
    };
    let cert_pem = certificates("tls_cert", cert)?;
    let key_pem = private_key(key)?;
    let mut tls = ServerTlsConfig::new().identity(Identity::from_pem(cert_pem, key_pem));
    if let Some(ca) = &config.tls_client_ca {
        tls = tls.client_ca_root(Certificate::from_pem(certificates("tls_client_ca", ca)?));
    }
    // rustls builds its configuration here: a key that is not the
    // certificate's, or a certificate it cannot use, fails now.
    tonic::transport::Server::builder()
        .tls_config(tls.clone())
        .map_err(|e| TlsError::Identity {
            cert: cert.clone(),
            key: key.clone(),
            reason: crate::service::error_chain(&e),
        })?;
    Ok(Some(tls))
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
