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
//! roller rigs and track curvature against analytic results (`rollers`),
//! and the FASTSIM variants of a case file's `[fastsim]` against CONTACT's
//! `fastsim.inp` and `tractcurv.inp` reference outputs (`fastsim_variants`).
//! Each reference number names its source.

/// A profile file of this crate's `profiles/` (test data with its licence
/// and source beside it).
pub fn profile_path(name: &str) -> String {
    format!("{}/profiles/{}", env!("CARGO_MANIFEST_DIR"), name)
}

/// A number CONTACT printed (`"262.4"`, `"-1.680E-02"`) and half a unit
/// of its last digit: the interval its exact value lies in.
pub fn printed(s: &str) -> (f64, f64) {
    let value: f64 = s.parse().expect("a number");
    let (mantissa, exponent) = match s.find(['E', 'e']) {
        Some(i) => (&s[..i], s[i + 1..].parse::<i32>().expect("an exponent")),
        None => (s, 0),
    };
    let decimals = mantissa.find('.').map_or(0, |i| mantissa.len() - i - 1) as i32;
    (value, 0.5 * 10f64.powi(exponent - decimals))
}

mod conformal;
mod falling_friction;
mod fastsim_variants;
mod interfacial_layer;
mod line_contact;
mod numerical_influence;
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
