//! The gRPC contact service (`railcontact serve`): package
//! `railcontact.v1` of `proto/railcontact/v1/railcontact.proto` over the
//! numeric core.
//!
//! | module | what |
//! |---|---|
//! | [`pb`] | generated wire types, client and server |
//! | [`convert`] | wire <-> case file and results (the only place wire types are read) |
//! | [`engine`] | one patch: a validated case and its persistent exact solver |
//! | [`session`] | co-simulation sessions: step order, marks, rollback |
//! | [`pairs`] | wheel/rail profile pairs: canonical form, content id, preparation, registry |
//! | [`store`] | the embedded store (redb) of registered pairs |
//! | [`wheelrail`] | wire <-> wheel/rail queries and results |
//! | [`pool`] | solve threads, bounded admission, deadlines |
//! | [`status`] | errors and their gRPC codes, in one place |
//! | [`handlers`] | the RPC handlers |
//! | [`config`] | layered settings (defaults, file, environment, flags) |
//! | [`metrics`] | Prometheus metrics |
//! | [`server`] | start, serve, graceful shutdown |
//!
//! The core (`crate::core`, `crate::conformal`) knows nothing of this
//! module: no async, no network there.

pub mod config;
pub mod convert;
pub mod engine;
pub mod handlers;
pub mod metrics;
pub mod pairs;
pub mod pb;
pub mod pool;
pub mod server;
pub mod session;
pub mod status;
pub mod store;
pub mod wheelrail;
pub mod wheelrail_session;
