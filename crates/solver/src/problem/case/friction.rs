//! The `[friction]` section: Coulomb friction, the falling laws with
//! memory, and friction varying with the contact angle.

use serde::Deserialize;

use super::bad;
use super::{Kinematics, Model};
use crate::core::error::check_count;
use crate::core::friclaw::{FallingShape, SlipStart, SlipVelocityLaw, DEFAULT_LAW_ITERATIONS};
use crate::core::problem::Friction;
use crate::problem::CaseError;
use crate::wheelrail::friction::{FrictionAxis, FrictionTable};
use crate::wheelrail::WheelRailError;

/// The friction law of a `[friction]` section.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FrictionLawName {
    /// Coulomb's law: `coefficient`, or `static_coefficient` +
    /// `kinetic_coefficient` (the default).
    #[default]
    Coulomb,
    /// Linear falling friction ([`crate::core::friclaw`]).
    Linear,
    /// Rational falling friction.
    Rational,
    /// Exponential falling friction.
    Exponential,
}

/// `[friction]`: Coulomb's law (`coefficient`, or `static_coefficient` +
/// `kinetic_coefficient`), or with `law = "linear" | "rational" |
/// "exponential"` a slip-velocity dependent law ([`crate::core::friclaw`],
/// exact model only): `kinetic_coefficient`, `falling_coefficients`,
/// `half_velocities_m_per_s`, `rolling_speed_m_per_s` and the optional
/// `memory_distance_m`, `memory_velocity_m_per_s`, `start`,
/// `max_iterations`. Wheel/rail cases also take a friction table over the
/// rail profile ([`crate::wheelrail::friction`]): `contact_angles_rad` or
/// `rail_y_m`, `coefficients`, and the optional `track_s_m`
/// ([`FrictionSection::table`]).
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrictionSection {
    /// `"coulomb"` (default), `"linear"`, `"rational"` or `"exponential"`.
    #[serde(default)]
    pub law: FrictionLawName,
    /// Coulomb coefficient mu [-], >= 0 (static = kinetic).
    pub coefficient: Option<f64>,
    /// Static coefficient [-], >= 0 (with `kinetic_coefficient`).
    pub static_coefficient: Option<f64>,
    /// Kinetic coefficient [-], >= 0 (with `static_coefficient`); with a
    /// falling law its limit mu_kin at large slip velocity, > 0.
    pub kinetic_coefficient: Option<f64>,
    /// Falling law: the sizes mu_1 (, mu_2) [-] >= 0 of its one or two
    /// terms at slip velocity 0; static coefficient mu_kin + mu_1 + mu_2 <= 5.
    pub falling_coefficients: Option<Vec<f64>>,
    /// Falling law: the slip velocities s_h1 (, s_h2) \[m/s\] > 0 at which
    /// each term is halved, one per term.
    pub half_velocities_m_per_s: Option<Vec<f64>>,
    /// Falling law: rolling speed V \[m/s\] > 0, converting slip to slip
    /// velocity.
    pub rolling_speed_m_per_s: Option<f64>,
    /// Falling law: memory distance d_c \[m\] >= 0 over which the
    /// coefficient relaxes (default 0: instantaneous).
    pub memory_distance_m: Option<f64>,
    /// Falling law: memory velocity s_0 \[m/s\] >= 0, the least relaxation
    /// rate (default 0).
    pub memory_velocity_m_per_s: Option<f64>,
    /// Falling law: the slip velocities the iteration starts from,
    /// `"previous"` (default: continuation), `"sticking"` (0: the
    /// low-slip solution) or `"sliding"` (V: the high-slip solution).
    pub start: Option<SlipStart>,
    /// Falling law: limit of the iteration on the slip velocities
    /// (default 200).
    pub max_iterations: Option<usize>,
    /// Wheel/rail friction table: contact angles \[rad\], strictly
    /// increasing, in \[-1.6, 1.6\] (or `rail_y_m`).
    pub contact_angles_rad: Option<Vec<f64>>,
    /// Wheel/rail friction table: lateral coordinates on the rail profile
    /// \[m\], strictly increasing (or `contact_angles_rad`).
    pub rail_y_m: Option<Vec<f64>>,
    /// Wheel/rail friction table: static coefficients [-] in \[1e-6, 5\],
    /// one per position, row after row for each of `track_s_m`; the
    /// section's law is scaled to them ([`FrictionSection::table_law`]).
    pub coefficients: Option<Vec<f64>>,
    /// Wheel/rail friction table: track coordinates \[m\] of its rows,
    /// strictly increasing (default: one row for the whole track).
    pub track_s_m: Option<Vec<f64>>,
}

impl FrictionSection {
    /// The wheel/rail friction table of `contact_angles_rad` or `rail_y_m`,
    /// `coefficients` and `track_s_m`, checked; None without one. A table
    /// excludes `coefficient`: its coefficients are static coefficients,
    /// and the section's other keys (a falling law, or static and kinetic
    /// coefficients) give the law they scale ([`FrictionSection::table_law`]).
    pub fn table(&self) -> Result<Option<FrictionTable>, CaseError> {
        let (axis, positions) =
            match (&self.contact_angles_rad, &self.rail_y_m) {
                (None, None) => {
                    for (key, given) in [
                        ("friction.coefficients", self.coefficients.is_some()),
                        ("friction.track_s_m", self.track_s_m.is_some()),
                    ] {
                        if given {
                            return Err(bad(
                            key,
                            "belongs to a friction table: give `friction.contact_angles_rad` or \
                             `friction.rail_y_m`",
                        ));
                        }
                    }
                    return Ok(None);
                }
                (Some(a), None) => (FrictionAxis::ContactAngle, a),
                (None, Some(y)) => (FrictionAxis::RailLateral, y),
                (Some(_), Some(_)) => return Err(bad(
                    "friction.rail_y_m",
                    "give either `friction.contact_angles_rad` or `friction.rail_y_m`, not both",
                )),
            };
        if self.coefficient.is_some() {
            return Err(bad(
                "friction.coefficient",
                "not with a friction table (its coefficients are the static ones; a law's other \
                 keys, or static_coefficient with kinetic_coefficient, give the shape it scales)",
            ));
        }
        let table = FrictionTable {
            axis,
            positions: positions.clone(),
            track_s_m: self.track_s_m.clone().unwrap_or_default(),
            coefficients: self
                .coefficients
                .clone()
                .ok_or_else(|| bad("friction.coefficients", "missing (needed with a table)"))?,
        };
        table.validate().map_err(|e| match e {
            WheelRailError::Invalid { key, message } => bad(key, message),
            other => bad("friction", other.to_string()),
        })?;
        Ok(Some(table))
    }

    /// The law a friction table scales (see [`FrictionSection::table`]):
    /// the section without its table keys, Coulomb's law with equal
    /// coefficients when it gives none.
    pub fn table_law(&self) -> Result<Friction, CaseError> {
        let shape = FrictionSection {
            contact_angles_rad: None,
            rail_y_m: None,
            coefficients: None,
            track_s_m: None,
            ..self.clone()
        };
        let none_given = shape.law == FrictionLawName::Coulomb
            && shape.static_coefficient.is_none()
            && shape.kinetic_coefficient.is_none();
        if none_given {
            return Ok(Friction::coulomb(1.0));
        }
        shape.wheelrail_friction()
    }

    /// [`FrictionSection::friction`] for wheel/rail contact: a falling
    /// law's rolling speed is not needed (each patch replaces it with its
    /// own; 1 m/s stands in when it is not given).
    pub fn wheelrail_friction(&self) -> Result<Friction, CaseError> {
        if self.law != FrictionLawName::Coulomb && self.rolling_speed_m_per_s.is_none() {
            let given = FrictionSection {
                rolling_speed_m_per_s: Some(1.0),
                ..self.clone()
            };
            return given.friction();
        }
        self.friction()
    }

    /// The checked friction law (errors name the key).
    pub fn friction(&self) -> Result<Friction, CaseError> {
        for (key, given) in [
            (
                "friction.contact_angles_rad",
                self.contact_angles_rad.is_some(),
            ),
            ("friction.rail_y_m", self.rail_y_m.is_some()),
            ("friction.coefficients", self.coefficients.is_some()),
            ("friction.track_s_m", self.track_s_m.is_some()),
        ] {
            if given {
                return Err(bad(
                    key,
                    "belongs to a wheel/rail friction table (`railcontact wheelrail` cases)",
                ));
            }
        }
        let shape = match self.law {
            FrictionLawName::Coulomb => {
                for (key, given) in [
                    (
                        "friction.falling_coefficients",
                        self.falling_coefficients.is_some(),
                    ),
                    (
                        "friction.half_velocities_m_per_s",
                        self.half_velocities_m_per_s.is_some(),
                    ),
                    (
                        "friction.rolling_speed_m_per_s",
                        self.rolling_speed_m_per_s.is_some(),
                    ),
                    (
                        "friction.memory_distance_m",
                        self.memory_distance_m.is_some(),
                    ),
                    (
                        "friction.memory_velocity_m_per_s",
                        self.memory_velocity_m_per_s.is_some(),
                    ),
                    ("friction.start", self.start.is_some()),
                    ("friction.max_iterations", self.max_iterations.is_some()),
                ] {
                    if given {
                        return Err(bad(
                            key,
                            "belongs to a falling law: set `friction.law` to \"linear\", \"rational\" or \"exponential\"",
                        ));
                    }
                }
                return self.coulomb();
            }
            FrictionLawName::Linear => FallingShape::Linear,
            FrictionLawName::Rational => FallingShape::Rational,
            FrictionLawName::Exponential => FallingShape::Exponential,
        };
        for (key, given) in [
            ("friction.coefficient", self.coefficient.is_some()),
            (
                "friction.static_coefficient",
                self.static_coefficient.is_some(),
            ),
        ] {
            if given {
                return Err(bad(
                    key,
                    format!(
                        "not with law = \"{}\": its static coefficient is kinetic_coefficient + falling_coefficients",
                        shape.name()
                    ),
                ));
            }
        }
        let need = |key: &str, v: Option<f64>| {
            v.ok_or_else(|| bad(key, "missing (needed with a falling law)"))
        };
        let falling = self.falling_coefficients.as_deref().ok_or_else(|| {
            bad(
                "friction.falling_coefficients",
                "missing (needed with a falling law)",
            )
        })?;
        let half = self.half_velocities_m_per_s.as_deref().ok_or_else(|| {
            bad(
                "friction.half_velocities_m_per_s",
                "missing (needed with a falling law)",
            )
        })?;
        check_count("friction.falling_coefficients", falling.len(), 1, 2)?;
        if half.len() != falling.len() {
            return Err(bad(
                "friction.half_velocities_m_per_s",
                format!(
                    "needs one value per falling coefficient ({}), got {}",
                    falling.len(),
                    half.len()
                ),
            ));
        }
        let two = |v: &[f64]| [v[0], v.get(1).copied().unwrap_or(0.0)];
        let law = SlipVelocityLaw {
            shape,
            kinetic_coefficient: need("friction.kinetic_coefficient", self.kinetic_coefficient)?,
            falling_coefficients: two(falling),
            half_velocities_m_per_s: two(half),
            rolling_speed_m_per_s: need(
                "friction.rolling_speed_m_per_s",
                self.rolling_speed_m_per_s,
            )?,
            memory_distance_m: self.memory_distance_m.unwrap_or(0.0),
            memory_velocity_m_per_s: self.memory_velocity_m_per_s.unwrap_or(0.0),
            start: self.start.unwrap_or_default(),
            max_iterations: self.max_iterations.unwrap_or(DEFAULT_LAW_ITERATIONS),
        };
        if law.max_iterations == 0 {
            return Err(bad("friction.max_iterations", "must be >= 1"));
        }
        law.validate()?;
        Ok(Friction::falling(law))
    }

    /// Coulomb's coefficients (errors name the key).
    fn coulomb(&self) -> Result<Friction, CaseError> {
        let f = match (
            self.coefficient,
            self.static_coefficient,
            self.kinetic_coefficient,
        ) {
            (Some(mu), None, None) => Friction::coulomb(
                crate::core::problem::check_friction_coefficient("friction.coefficient", mu)?,
            ),
            (None, Some(s), Some(k)) => Friction::static_kinetic(s, k),
            (Some(_), _, _) => {
                return Err(bad(
                    "friction.coefficient",
                    "give either `friction.coefficient` or `friction.static_coefficient` + \
                     `friction.kinetic_coefficient`, not both",
                ))
            }
            (None, None, None) => return Err(bad("friction.coefficient", "missing")),
            (None, None, Some(_)) => {
                return Err(bad(
                    "friction.static_coefficient",
                    "missing (needed with `kinetic_coefficient`)",
                ))
            }
            (None, Some(_), None) => {
                return Err(bad(
                    "friction.kinetic_coefficient",
                    "missing (needed with `static_coefficient`)",
                ))
            }
        };
        f.check_input()?;
        Ok(f)
    }
}

/// Whether a case of `model` with `kinematics` needs a `[friction]`.
pub(super) fn needs_friction(model: Model, kinematics: &Kinematics) -> bool {
    match model {
        Model::Hertz | Model::HertzCorrected => false,
        Model::Fastsim => true,
        Model::Exact | Model::Cect | Model::CectHalfspace => {
            !matches!(kinematics, Kinematics::Frictionless)
        }
    }
}

/// The `[friction]` of a case of `model` (`needed`: see [`needs_friction`])
/// and whether it was given; Coulomb 0 when neither given nor needed.
pub(super) fn case_friction(
    section: Option<&FrictionSection>,
    model: Model,
    needed: bool,
) -> Result<(Friction, bool), CaseError> {
    let (friction, given) = match (section, needed) {
        (Some(f), _) => {
            let friction = f.friction()?;
            if friction.slip_velocity_law.is_some() && model != Model::Exact {
                return Err(bad(
                    "friction.law",
                    format!(
                        "a falling law is solved by the exact model only, not by `{}`",
                        model.name()
                    ),
                ));
            }
            (friction, true)
        }
        (None, true) => {
            return Err(bad(
                "friction.coefficient",
                "missing: `[friction]` is needed for rolling, transient and FASTSIM cases",
            ));
        }
        (None, false) => (Friction::coulomb(0.0), false),
    };
    if model.is_cect() && needed && friction.static_coefficient != friction.kinetic_coefficient {
        return Err(bad(
            "friction.static_coefficient",
            format!(
                "the {} model takes one Coulomb coefficient: give `friction.coefficient` \
                 (or equal static and kinetic coefficients)",
                model.name()
            ),
        ));
    }
    Ok((friction, given))
}
