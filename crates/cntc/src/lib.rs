//! A drop-in for the C library of Vollebregt's CONTACT (`contact_addon`,
//! the `cntc_*` and `subs_*` calls), on railcontact's solver.
//!
//! Simulators, CONTACT's own Python and Matlab interfaces and Fortran or C
//! user routines load `contact_addon_linux64.so` and call it with CONTACT's
//! names, calling convention, units, flags and error codes; this crate
//! builds that file (`crates/cntc/build-lib.sh`) and answers those calls
//! with the solver crate, in process.
//!
//! * [`ffi`]: the exported functions (every argument by reference; a null
//!   pointer or a negative length is an error code, never a crash);
//! * [`library`]: result elements (`ire`) and their patches (`icp`),
//!   created on first use, each behind its own lock;
//! * [`config`]: control digits, materials, friction and solver parameters
//!   of a problem; [`units`]: the unit conventions and the one conversion
//!   to SI; [`flags`]: CONTACT's magic numbers and error codes;
//! * [`module3`]: one contact patch (Hertzian or given potential contact,
//!   undeformed distance, creepages, shifts or forces; exact solver or
//!   FASTSIM); [`module1`]: a wheel on its rail; [`subsurface`]: stresses
//!   below a patch;
//! * [`getters`] and [`outcome`]: what a calculation leaves and how each
//!   getter reads it; [`error`]: errors and their `ierror` codes; [`log`]:
//!   the library's messages.
//!
//! `docs/cntc.md` is the user's page: which calls and flag values are
//! supported and how to point an existing coupling at this library.

pub mod config;
pub mod error;
pub mod ffi;
pub mod flags;
pub mod getters;
pub mod library;
pub mod log;
pub mod module1;
pub mod module3;
pub mod outcome;
pub mod subsurface;
pub mod units;
