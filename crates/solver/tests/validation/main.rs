//! Validation of the solver crate against analytic and published results,
//! one test binary: the physics of the planar core (`physics`), conformal
//! contact (`conformal`), the profile readers (`profiles`), transient rolling
//! against CONTACT (`transient`), wheel/rail contact (`wheelrail`), its
//! friction varying over the profile (`variable_friction`), its flash
//! temperatures (`wheelrail_temperature`), the plausibility warnings of
//! its solutions (`plausibility`), Coulomb friction with static and
//! kinetic coefficients against CONTACT (`static_kinetic`) and the
//! interfacial (third-body) layer, elastic and elasto-plastic, against
//! CONTACT (`interfacial_layer`), and viscoelastic bodies in steady
//! rolling against their elastic limits and CONTACT (`viscoelastic`), and
//! roller rigs and track curvature against analytic results (`rollers`).
//! Each reference number names its source.

/// A profile file of this crate's `profiles/` (test data with its licence
/// and source beside it).
pub fn profile_path(name: &str) -> String {
    format!("{}/profiles/{}", env!("CARGO_MANIFEST_DIR"), name)
}

mod conformal;
mod falling_friction;
mod interfacial_layer;
mod line_contact;
mod perfc;
mod perfc_case;
mod physics;
mod plausibility;
mod profiles;
mod rollers;
mod rolling_direction;
mod static_kinetic;
mod transient;
mod variable_friction;
mod viscoelastic;
mod wheelrail;
mod wheelrail_backward;
mod wheelrail_temperature;
