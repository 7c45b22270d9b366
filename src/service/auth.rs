//! Bearer tokens: who may call what (`auth_tokens_file`).
//!
//! The tokens file is TOML, one `[[token]]` table per token:
//!
//! ```toml
//! [[token]]
//! name = "mbs-cluster"   # a label for logs; the token itself is never logged
//! role = "solve"         # "solve" or "admin"
//! sha256 = "<64 hex digits: SHA-256 of the token>"   # or: token = "<plain token>"
//! ```
//!
//! Clients send `authorization: Bearer <token>` metadata on every call.
//! [`AuthLayer`] checks it on the whole server, for every call (unary and
//! streaming), before any handler runs, by the request's path and the one
//! table [`access`]:
//!
//! | path | needs |
//! |---|---|
//! | `grpc.health.v1.Health/*` | nothing |
//! | `grpc.reflection.*/*` | a token of any role |
//! | `railcontact.v1.ContactService/` + a method of [`CONTACT_METHODS`] | the role listed there (`admin` may call everything) |
//! | anything else | role `admin` |
//!
//! A call without a usable token is UNAUTHENTICATED, one whose token's
//! role may not call the method PERMISSION_DENIED naming the role needed;
//! both are counted in `railcontact_auth_refused_total{reason}` and
//! logged with the token's name, never the token (at most 20 lines per
//! 10 s, [`crate::service::quota::LogLimiter`], so that a flood of
//! refusals cannot flood the log). Presented tokens are hashed (SHA-256)
//! and compared with every known digest in constant time.
//!
//! Guessing is slowed per peer address ([`AuthBackoff`]): an address may
//! present `auth_failure_burst` unknown tokens, then one more every
//! `1 / auth_failure_rate_per_s` seconds; meanwhile its calls that need a
//! token are refused with RESOURCE_EXHAUSTED naming `auth_failure_burst`
//! and how long to wait, without their token being checked.
//!
//! The layer also says who the client is, for the quotas
//! ([`crate::service::quota::ClientId`] in the request's extensions): the
//! token's name when one was checked, else the peer's address (behind a
//! proxy of `trusted_proxies`, the address it forwarded, which the
//! back-off goes by too). And it
//! marks the connection as having started a call
//! ([`crate::service::connections`]).

use std::collections::HashSet;
use std::future::Future;
use std::net::{IpAddr, Ipv4Addr};
use std::path::{Path, PathBuf};
use std::pin::Pin;
use std::sync::Arc;
use std::task::{Context, Poll};

use serde::Deserialize;
use sha2::{Digest, Sha256};
use subtle::ConstantTimeEq;
use thiserror::Error;
use tonic::codegen::http;

use crate::service::connections::ConnInfo;
use crate::service::metrics::Metrics;
pub use crate::service::quota::AuthBackoff;
use crate::service::quota::{peer_key, ClientId, TrustedProxies, REFUSED_CALLS_LOG};

/// What a token may do.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Role {
    /// The query RPCs, the sessions and the read-only pair RPCs.
    Solve,
    /// Everything `solve` may, and registering and deleting pairs.
    Admin,
}

impl Role {
    /// The role's name in the tokens file.
    pub fn name(self) -> &'static str {
        match self {
            Role::Solve => "solve",
            Role::Admin => "admin",
        }
    }

    /// Whether this role may do what `needed` may.
    pub fn allows(self, needed: Role) -> bool {
        self >= needed
    }
}

/// The gRPC service whose methods [`CONTACT_METHODS`] lists.
pub const CONTACT_SERVICE: &str = "railcontact.v1.ContactService";

/// Every method of `railcontact.v1.ContactService` and the least role
/// that may call it. `tests/end_to_end/service_security.rs` checks this list against
/// the service's descriptor: a new RPC must be added here.
pub const CONTACT_METHODS: &[(&str, Role)] = &[
    ("SolvePatch", Role::Solve),
    ("SolvePatchBatch", Role::Solve),
    ("CreepCurve", Role::Solve),
    ("PatchSession", Role::Solve),
    ("SolveWheelRail", Role::Solve),
    ("SolveWheelRailBatch", Role::Solve),
    ("WheelRailSession", Role::Solve),
    ("ContactLibrary", Role::Solve),
    ("GetProfilePair", Role::Solve),
    ("ListProfilePairs", Role::Solve),
    ("RegisterProfilePair", Role::Admin),
    ("DeleteProfilePair", Role::Admin),
];

/// What a call needs, by its path.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Access {
    /// Nothing: health checks.
    Open,
    /// A known token of any role: reflection.
    AnyToken,
    /// A token of this role or above.
    Role(Role),
}

/// What a call to `path` (`/package.Service/Method`) needs.
pub fn access(path: &str) -> Access {
    let (service, method) = path
        .strip_prefix('/')
        .and_then(|p| p.split_once('/'))
        .unwrap_or(("", ""));
    match service {
        "grpc.health.v1.Health" => Access::Open,
        "grpc.reflection.v1.ServerReflection" | "grpc.reflection.v1alpha.ServerReflection" => {
            Access::AnyToken
        }
        CONTACT_SERVICE => CONTACT_METHODS
            .iter()
            .find(|(m, _)| *m == method)
            .map_or(Access::Role(Role::Admin), |&(_, r)| Access::Role(r)),
        _ => Access::Role(Role::Admin),
    }
}

/// Why the tokens file cannot be used; each names the file.
#[derive(Debug, Error)]
pub enum TokensError {
    /// The file cannot be read.
    #[error("auth_tokens_file {}: cannot read it: {source}", .path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// What reading said.
        source: std::io::Error,
    },
    /// The file is not what [`crate::service::auth`] describes.
    #[error("auth_tokens_file {}: {reason}", .path.display())]
    Invalid {
        /// The file.
        path: PathBuf,
        /// What is wrong, naming the entry and key (`token[2].sha256`).
        reason: String,
    },
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TokensFile {
    #[serde(default)]
    token: Vec<TokenEntry>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TokenEntry {
    name: String,
    role: Role,
    #[serde(default)]
    sha256: Option<String>,
    #[serde(default)]
    token: Option<String>,
}

/// One known token: its name, role and the SHA-256 of the token.
#[derive(Clone)]
struct Known {
    name: Arc<str>,
    role: Role,
    digest: [u8; 32],
}

/// The known tokens.
#[derive(Clone)]
pub struct Tokens {
    known: Vec<Known>,
}

impl std::fmt::Debug for Tokens {
    /// Names and roles only.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_list()
            .entries(self.known.iter().map(|k| (&k.name, k.role)))
            .finish()
    }
}

fn sha256(text: &str) -> [u8; 32] {
    Sha256::digest(text.as_bytes()).into()
}

fn hex_digest(hex: &str) -> Option<[u8; 32]> {
    let hex = hex.trim();
    if hex.len() != 64 || !hex.is_ascii() {
        return None;
    }
    let mut out = [0u8; 32];
    for (k, byte) in out.iter_mut().enumerate() {
        *byte = u8::from_str_radix(&hex[2 * k..2 * k + 2], 16).ok()?;
    }
    Some(out)
}

impl Tokens {
    /// Reads the tokens file `path`.
    pub fn load(path: &Path) -> Result<Self, TokensError> {
        let text = std::fs::read_to_string(path).map_err(|source| TokensError::Read {
            path: path.to_path_buf(),
            source,
        })?;
        Self::parse(&text).map_err(|reason| TokensError::Invalid {
            path: path.to_path_buf(),
            reason,
        })
    }

    /// Parses a tokens file's text; the error names the entry and key.
    pub fn parse(text: &str) -> Result<Self, String> {
        let file: TokensFile =
            toml::from_str(text).map_err(|e| e.to_string().trim().to_string())?;
        if file.token.is_empty() {
            return Err("no [[token]] entry: every call would be refused".into());
        }
        let mut known = Vec::with_capacity(file.token.len());
        let mut digests = HashSet::new();
        for (k, t) in file.token.into_iter().enumerate() {
            let at = |key: &str| format!("token[{k}].{key}");
            if t.name.trim().is_empty() {
                return Err(format!(
                    "{}: empty; give the token a name for logs",
                    at("name")
                ));
            }
            let digest = match (&t.sha256, &t.token) {
                (Some(h), None) => hex_digest(h).ok_or_else(|| {
                    format!(
                        "{}: expected 64 hexadecimal digits (the SHA-256 of the token)",
                        at("sha256")
                    )
                })?,
                (None, Some(plain)) if !plain.is_empty() => sha256(plain),
                (None, Some(_)) => return Err(format!("{}: empty", at("token"))),
                (Some(_), Some(_)) => {
                    return Err(format!(
                        "token[{k}]: give either `sha256` or `token`, not both"
                    ))
                }
                (None, None) => {
                    return Err(format!(
                        "token[{k}]: missing `sha256` (the token's SHA-256 in hex) or `token`"
                    ))
                }
            };
            if !digests.insert(digest) {
                return Err(format!(
                    "token[{k}] ({}): the same token as an earlier entry",
                    t.name
                ));
            }
            known.push(Known {
                name: t.name.into(),
                role: t.role,
                digest,
            });
        }
        Ok(Tokens { known })
    }

    /// Number of tokens.
    pub fn len(&self) -> usize {
        self.known.len()
    }

    /// Whether there are none (never, once parsed).
    pub fn is_empty(&self) -> bool {
        self.known.is_empty()
    }

    /// The name and role of `presented`, if it is a known token. Compares
    /// its SHA-256 with every known digest, in constant time each, without
    /// stopping at a match.
    fn find(&self, presented: &str) -> Option<(&Arc<str>, Role)> {
        let digest = sha256(presented);
        let mut found = None;
        for k in &self.known {
            if bool::from(k.digest.ct_eq(&digest)) {
                found = Some((&k.name, k.role));
            }
        }
        found
    }

    /// Whether a call to `path` with these `authorization` metadata may
    /// go ahead, with the name of the token checked (None for a call that
    /// needs none); else the refusal's reason (a metrics label) and
    /// status.
    pub fn check(
        &self,
        path: &str,
        authorization: Option<&[u8]>,
    ) -> Result<Option<Arc<str>>, (&'static str, tonic::Status)> {
        let needed = access(path);
        if needed == Access::Open {
            return Ok(None);
        }
        let token = authorization
            .and_then(|v| std::str::from_utf8(v).ok())
            .and_then(|v| {
                let (scheme, token) = v.trim().split_once(' ')?;
                scheme.eq_ignore_ascii_case("bearer").then(|| token.trim())
            })
            .filter(|t| !t.is_empty());
        let Some(token) = token else {
            return Err((
                "missing",
                tonic::Status::unauthenticated(
                    "this server needs a token: send the metadata `authorization: Bearer TOKEN`",
                ),
            ));
        };
        let Some((name, role)) = self.find(token) else {
            return Err((
                "unknown",
                tonic::Status::unauthenticated("the bearer token is not known to this server"),
            ));
        };
        match needed {
            Access::Role(r) if !role.allows(r) => {
                if let Some(left_out) = REFUSED_CALLS_LOG.allow() {
                    tracing::info!(
                        path = %crate::service::escaped(path),
                        token = %crate::service::escaped(name),
                        role = role.name(),
                        left_out,
                        "call refused: role"
                    );
                }
                Err((
                    "forbidden",
                    tonic::Status::permission_denied(format!(
                        "{} needs a token of role `{}`; this token's role is `{}`",
                        path.trim_start_matches('/'),
                        r.name(),
                        role.name()
                    )),
                ))
            }
            _ => Ok(Some(name.clone())),
        }
    }
}

/// The tower layer that checks the bearer tokens of every call of the
/// server (see the module documentation); without tokens it passes every
/// call through. Either way it puts the call's
/// [`ClientId`] in the request's extensions.
#[derive(Clone)]
pub struct AuthLayer {
    tokens: Option<Arc<Tokens>>,
    backoff: Arc<AuthBackoff>,
    proxies: Arc<TrustedProxies>,
    metrics: Arc<Metrics>,
}

impl AuthLayer {
    /// Checks against `tokens` (None: no checks), slowing peers that fail
    /// by `backoff` (the clients behind `proxies` by the address each
    /// forwarded), counting refusals into `metrics`.
    pub fn new(
        tokens: Option<Tokens>,
        backoff: AuthBackoff,
        proxies: TrustedProxies,
        metrics: Arc<Metrics>,
    ) -> Self {
        Self {
            tokens: tokens.map(Arc::new),
            backoff: Arc::new(backoff),
            proxies: Arc::new(proxies),
            metrics,
        }
    }
}

impl<S> tower::Layer<S> for AuthLayer {
    type Service = Auth<S>;

    fn layer(&self, inner: S) -> Auth<S> {
        Auth {
            inner,
            layer: self.clone(),
        }
    }
}

/// The service of [`AuthLayer`].
#[derive(Clone)]
pub struct Auth<S> {
    inner: S,
    layer: AuthLayer,
}

type BoxFuture<T> = Pin<Box<dyn Future<Output = T> + Send>>;

impl<S, B> tower::Service<http::Request<B>> for Auth<S>
where
    S: tower::Service<http::Request<B>, Response = http::Response<tonic::body::Body>>,
    S::Future: Send + 'static,
    S::Error: Send + 'static,
{
    type Response = http::Response<tonic::body::Body>;
    type Error = S::Error;
    type Future = BoxFuture<Result<Self::Response, S::Error>>;

    fn poll_ready(&mut self, cx: &mut Context<'_>) -> Poll<Result<(), S::Error>> {
        self.inner.poll_ready(cx)
    }

    fn call(&mut self, mut req: http::Request<B>) -> Self::Future {
        let peer = match req.extensions().get::<ConnInfo>() {
            Some(conn) => {
                conn.state.called();
                let forwarded = req.headers().get("x-forwarded-for").map(|v| v.as_bytes());
                peer_key(
                    self.layer
                        .proxies
                        .client_address(conn.remote.ip(), forwarded),
                )
            }
            None => IpAddr::V4(Ipv4Addr::UNSPECIFIED),
        };
        let mut client = ClientId::Peer(peer);
        if let Some(tokens) = &self.layer.tokens {
            let refuse = |status: tonic::Status| -> Self::Future {
                Box::pin(std::future::ready(Ok(status.into_http())))
            };
            let path = req.uri().path();
            if access(path) != Access::Open {
                if let Some(wait) = self.layer.backoff.wait(peer) {
                    self.layer.metrics.quota_refused("auth_failure_burst");
                    let message = format!(
                        "too many unknown tokens from {client}: its next token is checked in \
                         {:.1} s (auth_failure_burst, auth_failure_rate_per_s); retry then",
                        wait.as_secs_f64().max(0.1)
                    );
                    if let Some(left_out) = REFUSED_CALLS_LOG.allow() {
                        tracing::info!(
                            path = %crate::service::escaped(path),
                            left_out,
                            "call refused: {message}"
                        );
                    }
                    return refuse(tonic::Status::resource_exhausted(message));
                }
            }
            let authorization = req
                .headers()
                .get(http::header::AUTHORIZATION)
                .map(|v| v.as_bytes());
            match tokens.check(path, authorization) {
                Ok(Some(name)) => client = ClientId::Token(name),
                Ok(None) => {}
                Err((reason, status)) => {
                    self.layer.metrics.auth_refused(reason);
                    if reason == "unknown" {
                        self.layer.backoff.failed(peer);
                    }
                    // A `forbidden` refusal was logged with the token's name.
                    if reason != "forbidden" {
                        if let Some(left_out) = REFUSED_CALLS_LOG.allow() {
                            tracing::info!(
                                path = %crate::service::escaped(path),
                                peer = %client,
                                reason,
                                left_out,
                                "call refused: token"
                            );
                        }
                    }
                    return refuse(status);
                }
            }
        }
        req.extensions_mut().insert(client);
        Box::pin(self.inner.call(req))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tokens_file_errors_name_the_entry() {
        let ok = Tokens::parse(
            "[[token]]\nname = \"a\"\nrole = \"solve\"\ntoken = \"s3cret\"\n\
             [[token]]\nname = \"b\"\nrole = \"admin\"\nsha256 = \"2bb80d537b1da3e38bd30361aa855686bde0eacd7162fef6a25fe97bf527a25b\"\n",
        )
        .unwrap();
        assert_eq!(ok.len(), 2);
        // sha256("secret")
        assert_eq!(ok.find("secret").map(|f| f.1), Some(Role::Admin));
        assert_eq!(ok.find("s3cret").map(|f| f.1), Some(Role::Solve));
        assert!(ok.find("nope").is_none());
        for (text, needle) in [
            (
                "[[token]]\nname = \"a\"\nrole = \"solve\"\nsha256 = \"ab\"\n",
                "token[0].sha256",
            ),
            (
                "[[token]]\nname = \"a\"\nrole = \"root\"\ntoken = \"x\"\n",
                "root",
            ),
            (
                "[[token]]\nname = \"a\"\nrole = \"solve\"\n",
                "token[0]: missing",
            ),
            ("", "no [[token]]"),
        ] {
            let e = Tokens::parse(text).unwrap_err();
            assert!(e.contains(needle), "{e}");
        }
        let t = ok;
        let bearer = |s: &str| format!("Bearer {s}");
        let path = "/railcontact.v1.ContactService/RegisterProfilePair";
        assert_eq!(t.check(path, None).unwrap_err().0, "missing");
        assert_eq!(
            t.check(path, Some(bearer("x").as_bytes())).unwrap_err().0,
            "unknown"
        );
        let (reason, status) = t
            .check(path, Some(bearer("s3cret").as_bytes()))
            .unwrap_err();
        assert_eq!(reason, "forbidden");
        assert!(status.message().contains("`admin`"), "{}", status.message());
        assert!(t.check(path, Some(bearer("secret").as_bytes())).is_ok());
        assert!(t.check("/grpc.health.v1.Health/Check", None).is_ok());
    }
}
