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

use crate::core::error::{show, ContactError, Range, UnitHint};

/// Range of a shear modulus \[Pa\]: from the softest gels (1 Pa) to a body
/// that stands in for a rigid one (1e18 Pa). Below it, a value that is in
/// range times 1e9 is reported as a likely modulus in GPa. A modulus below
/// [`SOFT_SHEAR_MODULUS_PA`] is solved as given, with a note
/// ([`soft_modulus_note`]).
pub const SHEAR_MODULUS_RANGE: Range = Range::closed(1.0, 1e18, "Pa").hint(UnitHint::GigaPascal);

/// A shear modulus below this is as soft as rubber or softer \[Pa\]
/// (natural rubber about 0.4 MPa, CONTACT's scaled example spence35 0.5
/// MPa, steel 81 GPa).
pub const SOFT_SHEAR_MODULUS_PA: f64 = 1e6;

/// A note on a shear modulus `g` \[Pa\] given as `key`, below
/// [`SOFT_SHEAR_MODULUS_PA`]: valid physics (rubber, polymers, gels, scaled
/// cases), and also what a modulus in GPa (`81`) or MPa (`81000`) written
/// as Pa gives, so the note names both readings; `None` at or above it.
pub fn soft_modulus_note(key: &str, g: f64) -> Option<String> {
    if g.is_nan() || g >= SOFT_SHEAR_MODULUS_PA {
        return None;
    }
    let (unit, factor) = if g <= 1e3 { ("GPa", 1e9) } else { ("MPa", 1e6) };
    Some(format!(
        "`{key}` = {} Pa ({} MPa) is as soft as rubber or softer: solved as given; if it is in \
         {unit}, write {}",
        show(g),
        show(g / 1e6),
        show(g * factor)
    ))
}
/// Range of a Poisson ratio [-].
pub const POISSON_RATIO_RANGE: Range = Range {
    max_inclusive: false,
    ..Range::closed(0.0, 0.5, "")
};

/// Isotropic linear elastic material of one body.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Material {
    /// Shear modulus G \[Pa\], in [1, 1e18] ([`SHEAR_MODULUS_RANGE`]; below
    /// 1e6, rubber-soft, with a note: [`soft_modulus_note`]).
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
        // Below the range: the message suggests the unit, formatted.
        let e = Material {
            shear_modulus_pa: 0.081,
            poisson_ratio: 0.3,
        }
        .validate("material")
        .unwrap_err()
        .to_string();
        assert!(e.contains("[1, 1e18] Pa, got 0.081"), "{e}");
        assert!(e.contains("did you mean 8.1e7 Pa, i.e. 0.081 GPa"), "{e}");
    }

    #[test]
    fn soft_bodies_are_accepted_with_a_note() {
        // CONTACT's spence35 (G = 0.5 MPa), a modulus in GPa, one in MPa.
        for (g, says) in [
            (5e5, "5e5 Pa (0.5 MPa) is as soft as rubber or softer: solved as given; if it is in MPa, write 5e11"),
            (81.0, "81 Pa (8.1e-5 MPa)"),
            (81.0, "if it is in GPa, write 8.1e10"),
            (81e3, "if it is in MPa, write 8.1e10"),
        ] {
            let m = Material {
                shear_modulus_pa: g,
                poisson_ratio: 0.3,
            };
            m.validate("material").unwrap();
            let note = soft_modulus_note("material.shear_modulus_pa", g).unwrap();
            assert!(note.contains(says) && note.contains("`material.shear_modulus_pa`"), "{note}");
        }
        assert_eq!(soft_modulus_note("k", 1e6), None);
        assert_eq!(soft_modulus_note("k", 81e9), None);
    }
}
