//! TLS of the gRPC port (rustls with the ring provider, through tonic):
//! the server's certificate and key (`tls_cert`, `tls_key`) and, for
//! mutual TLS, the authorities of the client certificates
//! (`tls_client_ca`). The files are read and checked once, at start; a
//! changed certificate takes effect at the next start.

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
