//! CONTACT's library semantics on railcontact's solver, without its C
//! boundary: what the CONTACT library (`crates/cntc`) computes in process
//! and what the service computes for a library that forwards its
//! calculations (the same code, so the same numbers bit for bit).
//!
//! * [`element`]: a result element (`ire`), module 1 or module 3, and the
//!   values read from it; [`call`]: the calls that configure it, as
//!   values; [`remote`]: the payload a forwarding library and the service
//!   exchange;
//! * [`config`]: control digits, materials, friction and solver parameters
//!   of a problem; [`units`]: the unit conventions and the one conversion
//!   to SI; [`flags`]: CONTACT's magic numbers and error codes;
//! * [`module3`]: one contact patch (Hertzian or given potential contact,
//!   undeformed distance, creepages, shifts or forces; exact solver or
//!   FASTSIM); [`module1`]: a wheel on its rail; [`subsurface`]: stresses
//!   below a patch;
//! * [`inp`]: CONTACT's input files of a wheel on its rail
//!   (`cntc_readinpfile`), read into the calls that configure an element;
//! * [`getters`] and [`outcome`]: what a calculation leaves and how each
//!   getter reads it; [`error`]: errors and their `ierror` codes.

pub mod call;
pub mod config;
pub mod element;
pub mod error;
pub mod flags;
pub mod getters;
pub mod inp;
pub mod module1;
pub mod module3;
pub mod outcome;
pub mod remote;
pub mod subsurface;
pub mod units;
