//! railcontact: frictional wheel/rail contact after Kalker's exact theory.
//!
//! The numeric core ([`core`]) solves one contact patch: given the undeformed
//! distance h on a grid of elements, the materials, friction and kinematics,
//! find the pressures p_n >= 0 and tangential tractions p_t such that
//!
//! * h - delta + u_n(p) >= 0 with equality where p_n > 0 (normal problem),
//! * |p_t| <= mu p_n, with slip s = 0 where |p_t| < mu p_n and p_t = -mu p_n s/|s|
//!   where the element slips (Coulomb),
//!
//! where u = A p are the elastic displacement differences given by the
//! half-space influence coefficients A, and the slip is s = w - du/dx in
//! steady rolling or s = w + u - u' in a transient step.

pub mod cli;
pub mod service;
pub mod shared;

pub use railcontact_solver::{conformal, core, problem, wheelrail};
