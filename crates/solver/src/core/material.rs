//! Elastic materials of the two bodies and their combination (Kalker 1990, §1.6).
//!
//! | symbol | name | unit |
//! |---|---|---|
//! | G_i, nu_i | `shear_modulus_pa`, `poisson_ratio` of body i | Pa, [-] |
//! | G | combined modulus, 1/G = (1/G1 + 1/G2)/2 | Pa |
//! | nu | combined Poisson ratio, nu/G = (nu1/G1 + nu2/G2)/2 | [-] |
//! | K | Kalker's difference parameter, K = G/4 ((1-2nu1)/G1 - (1-2nu2)/G2) | [-] |
//! | E* | effective modulus E* = G/(1-nu), u_n = 1/(pi E*) ∫∫ p_n/r dA | Pa |
//!
//! K = 0 for elastically identical bodies (quasi-identity): the normal and
//! tangential problems then decouple on the half-space.

use serde::{Deserialize, Serialize};

use crate::core::error::{ContactError, Range, UnitHint};

/// Range of a shear modulus \[Pa\]: from soft rubber (1 MPa) to a body
/// that stands in for a rigid one (1e18 Pa). Below it, a value that is in
/// range times 1e9 is reported as a likely modulus in GPa.
pub const SHEAR_MODULUS_RANGE: Range = Range::closed(1e6, 1e18, "Pa").hint(UnitHint::GigaPascal);
/// Range of a Poisson ratio [-].
pub const POISSON_RATIO_RANGE: Range = Range {
    max_inclusive: false,
    ..Range::closed(0.0, 0.5, "")
};

/// Isotropic linear elastic material of one body.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Material {
    /// Shear modulus G \[Pa\], in [1e6, 1e18] ([`SHEAR_MODULUS_RANGE`]).
    /// Steel: about 80e9.
    pub shear_modulus_pa: f64,
    /// Poisson ratio nu [-], in [0, 0.5) ([`POISSON_RATIO_RANGE`]). Steel: about 0.28–0.30.
    pub poisson_ratio: f64,
}

impl Material {
    /// Wheel/rail steel as in the paper's study (G = 81 GPa, nu = 0.30).
    pub const STEEL: Material = Material {
        shear_modulus_pa: 81.0e9,
        poisson_ratio: 0.30,
    };

    /// Checks the values; `key` names the input field in error messages.
    pub fn validate(&self, key: &str) -> Result<(), ContactError> {
        SHEAR_MODULUS_RANGE.check(&format!("{key}.shear_modulus_pa"), self.shear_modulus_pa)?;
        POISSON_RATIO_RANGE.check(&format!("{key}.poisson_ratio"), self.poisson_ratio)?;
        Ok(())
    }
}

/// The two bodies' materials combined as Kalker does.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CombinedMaterial {
    /// Body 1 (the body the tractions act on; the rail in wheel/rail contact).
    pub body1: Material,
    /// Body 2 (the wheel in wheel/rail contact).
    pub body2: Material,
    /// Combined shear modulus G \[Pa\].
    pub shear_modulus_pa: f64,
    /// Combined Poisson ratio nu [-].
    pub poisson_ratio: f64,
    /// Kalker's difference parameter K [-]; 0 for identical bodies.
    pub kalker_k: f64,
}

impl CombinedMaterial {
    /// Combines two validated materials.
    pub fn new(body1: Material, body2: Material) -> Result<Self, ContactError> {
        body1.validate("material.body1")?;
        body2.validate("material.body2")?;
        let (g1, g2) = (body1.shear_modulus_pa, body2.shear_modulus_pa);
        let (n1, n2) = (body1.poisson_ratio, body2.poisson_ratio);
        let g = 2.0 / (1.0 / g1 + 1.0 / g2);
        let nu = g * 0.5 * (n1 / g1 + n2 / g2);
        let k = 0.25 * g * ((1.0 - 2.0 * n1) / g1 - (1.0 - 2.0 * n2) / g2);
        Ok(Self {
            body1,
            body2,
            shear_modulus_pa: g,
            poisson_ratio: nu,
            kalker_k: k,
        })
    }

    /// Both bodies of the same material.
    pub fn identical(m: Material) -> Result<Self, ContactError> {
        Self::new(m, m)
    }

    /// Effective (plane-strain) modulus E* = G/(1-nu) \[Pa\].
    pub fn effective_modulus_pa(&self) -> f64 {
        self.shear_modulus_pa / (1.0 - self.poisson_ratio)
    }

    /// True when the normal and tangential problems are coupled (K != 0).
    pub fn is_coupled(&self) -> bool {
        self.kalker_k.abs() > 1e-12
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identical_bodies_have_zero_k_and_same_constants() {
        let c = CombinedMaterial::identical(Material::STEEL).unwrap();
        assert!((c.shear_modulus_pa - 81.0e9).abs() < 1.0);
        assert!((c.poisson_ratio - 0.30).abs() < 1e-15);
        assert_eq!(c.kalker_k, 0.0);
        assert!(!c.is_coupled());
    }

    #[test]
    fn rigid_body2_gives_classic_k() {
        // Body 2 nearly rigid: G = 2 G1, nu = nu1, K = (1 - 2 nu1) / 2 (Kalker 1990, §1.6).
        let c = CombinedMaterial::new(
            Material {
                shear_modulus_pa: 1.0e9,
                poisson_ratio: 0.3,
            },
            Material {
                shear_modulus_pa: 1.0e18,
                poisson_ratio: 0.3,
            },
        )
        .unwrap();
        assert!((c.shear_modulus_pa / 2.0e9 - 1.0).abs() < 1e-8);
        assert!((c.poisson_ratio - 0.3).abs() < 1e-8);
        assert!((c.kalker_k - 0.2).abs() < 1e-8);
    }

    #[test]
    fn bad_values_name_the_key() {
        let e = Material {
            shear_modulus_pa: -1.0,
            poisson_ratio: 0.3,
        }
        .validate("material")
        .unwrap_err();
        assert!(e.to_string().contains("material.shear_modulus_pa"));
        let e = Material {
            shear_modulus_pa: 81e9,
            poisson_ratio: f64::NAN,
        }
        .validate("material")
        .unwrap_err();
        assert!(e.to_string().contains("poisson_ratio"));
        // A modulus in GPa: the message suggests the unit.
        let e = Material {
            shear_modulus_pa: 81.0,
            poisson_ratio: 0.3,
        }
        .validate("material")
        .unwrap_err()
        .to_string();
        assert!(e.contains("did you mean 81e9"), "{e}");
        assert!(e.contains("[1e6, 1e18] Pa, got 81"), "{e}");
    }
}
