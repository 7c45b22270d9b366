//! A drop-in for the C library of Vollebregt's CONTACT (`contact_addon`,
//! the `cntc_*` and `subs_*` calls), on railcontact's solver.
//!
//! Simulators, CONTACT's own Python and Matlab interfaces and Fortran or C
//! user routines load `contact_addon_linux64.so` and call it with CONTACT's
//! names, calling convention, units, flags and error codes; this crate
//! builds that file (`crates/cntc/build-lib.sh`) and answers those calls
//! with the solver crate, in process or, forwarded, on a railcontact
//! server with the same code (`railcontact-cntc-core`).
//!
//! * [`ffi`]: the exported functions (every argument by reference; a null
//!   pointer or a negative length is an error code, never a crash);
//! * [`library`]: the process's result elements (`ire`), created on first
//!   use, each behind its own lock, and the global flags; [`log`]: the
//!   library's messages; [`forward`]: calculations forwarded to a
//!   railcontact server;
//! * re-exported from `railcontact-cntc-core` (`crates/cntc-core`), what
//!   a calculation is: [`element`] (a result element and its patches
//!   `icp`), [`config`], [`units`], [`flags`], [`module3`], [`module1`],
//!   [`subsurface`], [`inp`], [`getters`], [`outcome`], [`error`].
//!
//! `docs/cntc.md` is the user's page: which calls and flag values are
//! supported and how to point an existing coupling at this library.

pub mod ffi;
pub mod forward;
pub mod library;
pub mod log;

pub use railcontact_cntc_core::{
    call, config, element, error, flags, getters, inp, module1, module3, outcome, remote,
    subsurface, units,
};
