//! End-to-end tests of the root package: the command line, the gRPC
//! service (in-process and as a `railcontact serve` process), the load
//! generator, the Python and C++ clients, and the dependency boundary.
//!
//! One test binary with a module per subject, so that the package's test
//! code is compiled and linked once, and the tests of every subject run
//! side by side (`cargo test --test end_to_end MODULE::` runs one subject,
//! e.g. `cargo test --test end_to_end endurance::`). libtest starts tests
//! in the order of their names, so the longest, the soak, is in a module
//! whose name sorts early (`endurance`): the rest run beside it instead of
//! after it.
//!
//! | module | what |
//! |---|---|
//! | [`architecture`] | the solver crate's dependency boundary (`cargo tree`) |
//! | [`cli`] | `railcontact` subcommands on the example cases |
//! | [`service`] | SolvePatch, batches, creep curves, queue, deadlines, health, reflection |
//! | [`service_contact_library`] | `ContactLibrary` (CONTACT's library forwarding) against mismatched and hostile requests |
//! | [`service_influence`] | numerical influence coefficients (CONTACT's C3 = 9) sent inline: the case file's numbers, errors by field |
//! | [`service_fairness`] | one client hoarding each resource (solve slots, sessions, streams, connections, token guesses) while another is served |
//! | [`service_limits`] | per-request and per-solve limits |
//! | [`service_security`] | TLS, mutual TLS, tokens and roles, loopback-only defaults, escaped logs |
//! | [`service_sessions`] | co-simulation patch sessions: order, marks, rollback, memory |
//! | [`service_store`] | the profile-pair store: restart, damage, limits |
//! | [`service_wheelrail`] | wheel/rail queries and sessions |
//! | [`validation_fuzz`] | every numeric request field at extreme values; profile readers on mutated profiles; mutated influence-coefficient texts |
//! | [`loadtest`] | `railcontact loadtest` against a server process |
//! | [`scaleout`] | three replicas, sessions spread by the client |
//! | [`proxy_fleet`] | nginx (`deploy/nginx.conf`) in front of three replicas: routing, pinning, a drain |
//! | [`python_client`] | the Python client's pytest suite (a venv under `target/`) |
//! | [`cpp_client`] | the C++ client built with CMake and run (Debian packages) |
//! | [`endurance`] | the soak: 64 mixed sessions for 45 s, every answer replayed |
//!
//! [`common`] starts servers in-process; [`support`] starts `railcontact
//! serve` processes and runs the load generator.

mod common;
mod support;

mod architecture;
mod cli;
mod cpp_client;
mod endurance;
mod loadtest;
mod proxy_fleet;
mod python_client;
mod scaleout;
mod service;
mod service_contact_library;
mod service_fairness;
mod service_influence;
mod service_limits;
mod service_security;
mod service_sessions;
mod service_store;
mod service_wheelrail;
mod service_wheelrail_track;
mod validation_fuzz;
