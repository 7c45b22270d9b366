//! Friction varying over the rail profile and along the track.
//!
//! CONTACT offers a friction coefficient that varies with the contact
//! angle or the lateral position on the rail profile, and per rail section
//! along the track (Vollebregt, *User guide for CONTACT*, report 20-01,
//! §"Friction description", variable friction `VARFRC` with `NVF` values;
//! its example `mbench_a22_varfric`: 0.2 at a contact angle of 20 degrees,
//! 0.3 at 10 degrees). A [`FrictionTable`] holds such a table, piecewise
//! linear in both directions and constant beyond its ends:
//!
//! * across the profile, by the contact angle \[rad\] or by the lateral
//!   coordinate on the rail profile \[m\], both in each side's own profile
//!   frame as [`crate::wheelrail::PatchResult`] reports them (the contact
//!   angle positive towards the gauge face, the flange contacts of either
//!   wheel at positive angles);
//! * optionally along the track, by the wheelset's track coordinate
//!   [`crate::wheelrail::WheelsetPosition::track_s_m`] \[m\]: one row of
//!   coefficients per track position.
//!
//! Every patch takes the coefficient at its reference point (the one
//! [`crate::wheelrail::PatchResult::friction_coefficient`] reports); an
//! exact patch reads the table once per grid row, at the row's own point
//! of the rail profile ([`crate::core::solve::ContactSolver::set_row_friction_scale`]).
//! The table's coefficients are static coefficients, and the friction's
//! law is scaled to them ([`crate::core::problem::Friction::scaled_to`]):
//! Coulomb's law with equal coefficients takes the table's; static and
//! kinetic coefficients keep their ratio; a slip-velocity law (exact model)
//! keeps its shape in slip velocity, its kinetic and falling coefficients
//! scaled by the same factor. CONTACT's `VARFRC` gives every entry a law
//! of its own; here one law's shape holds over the whole table.
//!
//! Why the contact angle and the rail's lateral coordinate: friction
//! modifiers and flange lubrication act on parts of the rail head, which
//! these two name without depending on the wheelset's position.

use serde::Serialize;

use crate::core::error::show;
use crate::core::problem::check_friction_coefficient;
use crate::wheelrail::WheelRailError;

/// What the positions across the profile of a [`FrictionTable`] measure.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FrictionAxis {
    /// The contact angle \[rad\] (side frame, positive towards the gauge
    /// face): case-file key `friction.contact_angles_rad`.
    ContactAngle,
    /// The lateral coordinate on the rail profile \[m\] (the side's own
    /// profile frame): case-file key `friction.rail_y_m`.
    RailLateral,
}

impl FrictionAxis {
    /// The field of the positions (`contact_angles_rad`, `rail_y_m`).
    pub fn field(self) -> &'static str {
        match self {
            FrictionAxis::ContactAngle => "contact_angles_rad",
            FrictionAxis::RailLateral => "rail_y_m",
        }
    }
}

/// Friction coefficients over the rail profile and along the track (see
/// the module docs).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FrictionTable {
    /// What `positions` measure.
    pub axis: FrictionAxis,
    /// Positions across the profile, strictly increasing: contact angles
    /// \[rad\] or lateral rail coordinates \[m\] (`axis`); at least one.
    pub positions: Vec<f64>,
    /// Track coordinates \[m\] of the rows of `coefficients`, strictly
    /// increasing; empty: one row for the whole track.
    pub track_s_m: Vec<f64>,
    /// Coefficients [-], each in \[1e-6, 5\]: `positions.len()` per row,
    /// row after row (one row per `track_s_m`, or one).
    pub coefficients: Vec<f64>,
}

/// Where `x` falls in the increasing `at`: (lower index, weight of the
/// next), constant beyond the ends.
fn bracket(at: &[f64], x: f64) -> (usize, f64) {
    let k = at.partition_point(|&a| a <= x);
    if k == 0 {
        return (0, 0.0);
    }
    if k >= at.len() {
        return (at.len() - 1, 0.0);
    }
    (k - 1, (x - at[k - 1]) / (at[k] - at[k - 1]))
}

impl FrictionTable {
    /// One coefficient over the whole profile and track.
    pub fn constant(axis: FrictionAxis, mu: f64) -> Self {
        Self {
            axis,
            positions: vec![0.0],
            track_s_m: Vec::new(),
            coefficients: vec![mu],
        }
    }

    /// The coefficient [-] at `position` across the profile (in `axis`'s
    /// unit) and track coordinate `track_s_m` \[m\]: linear between the
    /// table's points, constant beyond its ends.
    pub fn coefficient(&self, position: f64, track_s_m: f64) -> f64 {
        let n = self.positions.len();
        let across = |row: usize| {
            let c = &self.coefficients[row * n..(row + 1) * n];
            let (k, f) = bracket(&self.positions, position);
            if f == 0.0 {
                c[k]
            } else {
                c[k] + f * (c[k + 1] - c[k])
            }
        };
        if self.track_s_m.is_empty() {
            return across(0);
        }
        let (k, f) = bracket(&self.track_s_m, track_s_m);
        if f == 0.0 {
            across(k)
        } else {
            let (a, b) = (across(k), across(k + 1));
            a + f * (b - a)
        }
    }

    /// Checks the table; errors name the case-file key under `friction.`.
    pub fn validate(&self) -> Result<(), WheelRailError> {
        self.validate_as("friction")
    }

    /// Checks the table; errors name its fields under `prefix`
    /// (`friction.coefficients` in case files, `friction_table.coefficients`
    /// in requests).
    pub fn validate_as(&self, prefix: &str) -> Result<(), WheelRailError> {
        let increasing = |key: &str, v: &[f64]| -> Result<(), WheelRailError> {
            if let Some(x) = v.iter().find(|x| !x.is_finite()) {
                return Err(WheelRailError::invalid(
                    key,
                    format!("must be finite, got {}", show(*x)),
                ));
            }
            if let Some(w) = v.windows(2).find(|w| w[1] <= w[0]) {
                return Err(WheelRailError::invalid(
                    key,
                    format!(
                        "must be strictly increasing, got {} then {}",
                        show(w[0]),
                        show(w[1])
                    ),
                ));
            }
            Ok(())
        };
        let key = &format!("{prefix}.{}", self.axis.field());
        if self.positions.is_empty() {
            return Err(WheelRailError::invalid(key, "needs at least one position"));
        }
        increasing(key, &self.positions)?;
        if self.axis == FrictionAxis::ContactAngle {
            if let Some(a) = self.positions.iter().find(|a| a.abs() > 1.6) {
                return Err(WheelRailError::invalid(
                    key,
                    format!(
                        "contact angles are in radians within [-1.6, 1.6], got {}",
                        show(*a)
                    ),
                ));
            }
        }
        increasing(&format!("{prefix}.track_s_m"), &self.track_s_m)?;
        let rows = self.track_s_m.len().max(1);
        let want = rows * self.positions.len();
        let coefficients_key = &format!("{prefix}.coefficients");
        if self.coefficients.len() != want {
            return Err(WheelRailError::invalid(
                coefficients_key,
                format!(
                    "needs {want} values ({} per track position x {rows} track position(s)), \
                     got {}",
                    self.positions.len(),
                    self.coefficients.len()
                ),
            ));
        }
        for &mu in &self.coefficients {
            if check_friction_coefficient(coefficients_key, mu)? == 0.0 {
                return Err(WheelRailError::invalid(
                    coefficients_key,
                    "must be > 0 (a table scales the coefficient row by row)",
                ));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table() -> FrictionTable {
        FrictionTable {
            axis: FrictionAxis::ContactAngle,
            positions: vec![0.1, 0.3],
            track_s_m: vec![0.0, 10.0],
            coefficients: vec![0.3, 0.2, 0.4, 0.1],
        }
    }

    #[test]
    fn piecewise_linear_and_constant_beyond_the_ends() {
        let t = table();
        t.validate().unwrap();
        assert_eq!(t.coefficient(0.1, 0.0), 0.3);
        assert_eq!(t.coefficient(-1.0, -5.0), 0.3);
        assert_eq!(t.coefficient(0.5, 0.0), 0.2);
        assert!((t.coefficient(0.2, 0.0) - 0.25).abs() < 1e-15);
        assert!((t.coefficient(0.3, 5.0) - 0.15).abs() < 1e-15);
        assert!((t.coefficient(0.2, 5.0) - 0.25).abs() < 1e-15);
        assert_eq!(t.coefficient(0.3, 20.0), 0.1);
        let c = FrictionTable::constant(FrictionAxis::RailLateral, 0.27);
        c.validate().unwrap();
        assert_eq!(c.coefficient(-0.02, 3.0), 0.27);
    }

    #[test]
    fn bad_tables_name_their_key() {
        let err = |t: FrictionTable| t.validate().unwrap_err().to_string();
        let mut t = table();
        t.positions = vec![0.3, 0.1];
        assert!(err(t).starts_with("friction.contact_angles_rad: must be strictly increasing"));
        let mut t = table();
        t.positions = vec![10.0, 20.0];
        assert!(err(t).contains("radians"));
        let mut t = table();
        t.track_s_m = vec![1.0, f64::NAN];
        assert!(err(t).starts_with("friction.track_s_m: must be finite"));
        let mut t = table();
        t.coefficients.pop();
        assert!(err(t).starts_with("friction.coefficients: needs 4 values"));
        let mut t = table();
        t.coefficients[2] = 0.0;
        assert!(err(t).starts_with("friction.coefficients: must be > 0"));
        let mut t = table();
        t.axis = FrictionAxis::RailLateral;
        t.positions.clear();
        assert!(err(t).starts_with("friction.rail_y_m: needs at least one"));
    }
}
