//! Validation of the solver crate against analytic and published results,
//! one test binary: the physics of the planar core (`physics`), conformal
//! contact (`conformal`), the profile readers (`profiles`), transient rolling
//! against CONTACT (`transient`) and wheel/rail contact (`wheelrail`). Each
//! reference number names its source.

mod conformal;
mod falling_friction;
mod line_contact;
mod perfc;
mod perfc_case;
mod physics;
mod profiles;
mod rolling_direction;
mod transient;
mod wheelrail;
