//! The gRPC contact service (`railcontact serve`): package
//! `railcontact.v1` of `proto/railcontact/v1/railcontact.proto` over the
//! numeric core.
//!
//! | module | what |
//! |---|---|
//! | [`pb`] | generated wire types, client and server (`crate::shared::pb`) |
//! | [`convert`] | wire <-> case file and results (the only place wire types are read) |
//! | [`engine`] | one patch: a validated case and its persistent exact solver |
//! | [`session`] | co-simulation sessions: step order, marks, rollback |
//! | [`contact_library`] | the server's copy of a result element of CONTACT's library (`ContactLibrary`) |
//! | [`memory`] | the memory sessions hold (live state and marks) against the server's limits |
//! | [`pairs`] | wheel/rail profile pairs: canonical form, content id, preparation, registry |
//! | [`store`] | the embedded store (redb) of registered pairs |
//! | [`wheelrail`] | wire <-> wheel/rail queries and results |
//! | [`pool`] | solve threads, bounded admission, deadlines, the clients' turns |
//! | [`quota`] | who a client is; each client's share of sessions, solves, calls and connections |
//! | [`streams`] | calls open per client and server; streamed responses whose client stops reading |
//! | [`connections`] | accepting connections: their caps, first-call timeout, closing |
//! | [`status`] | errors and their gRPC codes, in one place |
//! | [`handlers`] | the RPC handlers |
//! | [`auth`] | bearer tokens: roles, the table of who may call what, the tower layer |
//! | [`tls`] | TLS of the gRPC port: certificate, key, client authorities |
//! | [`command`] | `railcontact serve`: its options and settings help, start, exit code |
//! | [`config`] | layered settings (defaults, file, environment, flags) |
//! | [`metrics`] | Prometheus metrics |
//! | [`server`] | start, serve, graceful shutdown |
//!
//! The core (`crate::core`, `crate::conformal`) knows nothing of this
//! module: no async, no network there.

pub mod auth;
pub mod command;
pub mod config;
pub mod connections;
pub mod contact_library;
pub mod convert;
pub mod engine;
pub mod handlers;
pub mod memory;
pub mod metrics;
pub mod pairs;
pub mod pool;
pub mod quota;
pub mod server;
pub mod session;
pub mod status;
pub mod store;
pub mod streams;
pub mod tls;
pub mod wheelrail;
pub mod wheelrail_session;

pub use crate::shared::{error_chain, pb};

/// Longest text of a client quoted in a log line, in characters.
const MAX_LOGGED_CHARS: usize = 1000;

/// Text that came from a client (a label, an id, a file name, a header,
/// an error message quoting them), as it may appear in a log line: control
/// characters, quotes and backslashes escaped as Rust does
/// ([`str::escape_debug`]: a newline is `\n`), so that a client cannot
/// forge or split log lines; at most 1000 characters, then `... (N
/// characters)`.
pub fn escaped(text: &str) -> String {
    match text.char_indices().nth(MAX_LOGGED_CHARS) {
        None => text.escape_debug().to_string(),
        Some((end, _)) => format!(
            "{}... ({} characters)",
            text[..end].escape_debug(),
            text.chars().count()
        ),
    }
}
