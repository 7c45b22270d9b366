//! `[fastsim]`: the variants of model `fastsim` on a single patch: the
//! method (FASTSIM or FaStrip), the flexibilities (Kalker's, with the
//! modified FASTSIM's slope reduction and falling friction, or one given
//! flexibility), the traction bound (parabolic or elliptic) and the
//! discretisation (strips of the Hertz ellipse, or CONTACT's rectangular
//! grid over it). Without the section model `fastsim` is Kalker's FASTSIM
//! on strips with the parabolic bound, as before it existed.

use serde::Deserialize;

use crate::core::error::Range;
use crate::core::fastsim::{SlopeReduction, TractionBound};
use crate::core::frame::ROLLING_DIRECTION_KEY;
use crate::core::problem::Friction;

use super::{bad, CaseError, Model};

/// The key of the section (errors name `fastsim.<field>`).
pub const FASTSIM_KEY: &str = "fastsim";

/// `fastsim.flexibility_m_per_pa` \[m/Pa\]: Kalker's `L = 8a/(3 C11 G)` of
/// steel wheel/rail patches is about 1e-13 m/Pa; far smaller ones overflow
/// the tractions' increments (`5e-324` did).
const FLEXIBILITY: Range = Range::closed(1e-20, 1e-6, "m/Pa");
/// `fastsim.window_scale` [-]: CONTACT's SCALE.
const WINDOW_SCALE: Range = Range::closed(1.0, 10.0, "");
/// `fastsim.rolling_speed_m_per_s` \[m/s\].
const ROLLING_SPEED: Range = Range::positive(1000.0, "m/s");
/// `fastsim.transition_rate` beta [-].
const TRANSITION_RATE: Range = Range::closed(0.0, 1e6, "");
/// `fastsim.friction_decay_s_per_m` B \[s/m\].
const FRICTION_DECAY: Range = Range::closed(0.0, 1e6, "s/m");

/// The algorithm of the tangential problem.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FastsimMethod {
    /// Kalker's FASTSIM (with the slope reduction: the modified FASTSIM).
    #[default]
    Fastsim,
    /// Modified FaStrip (CONTACT's `M = 5`, [`crate::core::fastrip`]):
    /// on the grid only.
    Fastrip,
}

/// Where the simplified theory is integrated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FastsimDiscretisation {
    /// `grid.ny` strips of the Hertz ellipse, `grid.nx` elements along
    /// each ([`crate::core::fastsim`]).
    #[default]
    Strips,
    /// CONTACT's rectangular grid of `grid.nx` x `grid.ny` elements over
    /// `fastsim.window_scale` times the Hertz ellipse, centred on it
    /// ([`crate::core::fastsim_grid`]).
    Grid,
}

/// The pressure whose multiple `mu pn` bounds the tractions, as written.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TractionBoundName {
    /// Kalker's parabolic pressure, peak `2 Fn/(pi a b) = 4/3 p0`
    /// (CONTACT's `B = 3`).
    #[default]
    Parabolic,
    /// Hertz's elliptic pressure, peak `p0` (CONTACT's `B = 2`).
    Elliptic,
}

/// `[fastsim]` as written (model `fastsim` only); every key optional.
#[derive(Debug, Clone, Copy, Default, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct FastsimSection {
    /// `"fastsim"` (default) or `"fastrip"` (grid only).
    pub method: Option<FastsimMethod>,
    /// `"strips"` (default) or `"grid"`.
    pub discretisation: Option<FastsimDiscretisation>,
    /// `"parabolic"` (default) or `"elliptic"`.
    pub traction_bound: Option<TractionBoundName>,
    /// Slope reduction `k0` [-], in (0, 1] (default 1).
    pub initial_factor: Option<f64>,
    /// `alpha_inf` [-], in (0, 1] (default 1).
    pub limit_ratio: Option<f64>,
    /// `beta` [-], in [0, 1e6] (default 0).
    pub transition_rate: Option<f64>,
    /// Falling friction's `A` [-], in (0, 1] (default 1: none).
    pub friction_limit_ratio: Option<f64>,
    /// Falling friction's `B` \[s/m\], in [0, 1e6] (default 0).
    pub friction_decay_s_per_m: Option<f64>,
    /// Rolling speed `V` \[m/s\] of the slip velocity `V sqrt(xi^2 +
    /// eta^2)` of the falling friction, in (0, 1000]; required with it.
    pub rolling_speed_m_per_s: Option<f64>,
    /// One flexibility `L` for all three \[m/Pa\], in [1e-20, 1e-6] (CONTACT's
    /// `M = 2`; grid only); absent: Kalker's three.
    pub flexibility_m_per_pa: Option<f64>,
    /// The grid's window over the ellipse's extent [-], in [1, 10]
    /// (CONTACT's SCALE; grid only; default 1.1).
    pub window_scale: Option<f64>,
}

/// The validated `[fastsim]` of a case: what model `fastsim` solves.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FastsimOptions {
    /// FASTSIM or FaStrip.
    pub method: FastsimMethod,
    /// Strips or CONTACT's grid.
    pub discretisation: FastsimDiscretisation,
    /// The traction bound's pressure.
    pub bound: TractionBound,
    /// The slope reduction and falling friction
    /// ([`SlopeReduction::NONE`]: Kalker's FASTSIM).
    pub reduction: SlopeReduction,
    /// Rolling speed of the falling friction's slip velocity \[m/s\] (0
    /// without falling friction).
    pub rolling_speed_m_per_s: f64,
    /// One given flexibility \[m/Pa\]; None: Kalker's three.
    pub flexibility_m_per_pa: Option<f64>,
    /// The grid's window over the ellipse's extent [-].
    pub window_scale: f64,
}

/// CONTACT's SCALE of its examples (`fastsim.inp`, `tractcurv.inp`).
pub const DEFAULT_WINDOW_SCALE: f64 = 1.1;

impl Default for FastsimOptions {
    /// Kalker's FASTSIM on strips, parabolic bound: model `fastsim`
    /// without `[fastsim]`.
    fn default() -> Self {
        FastsimOptions {
            method: FastsimMethod::Fastsim,
            discretisation: FastsimDiscretisation::Strips,
            bound: TractionBound::Parabolic,
            reduction: SlopeReduction::NONE,
            rolling_speed_m_per_s: 0.0,
            flexibility_m_per_pa: None,
            window_scale: DEFAULT_WINDOW_SCALE,
        }
    }
}

impl FastsimOptions {
    /// Whether the reduction has falling friction (`A < 1` and `B > 0`).
    pub fn has_falling_friction(&self) -> bool {
        self.reduction.has_falling_friction()
    }

    /// One line naming what solves the case.
    pub fn describe(&self, nx: usize, ny: usize) -> String {
        let method = match (self.method, self.reduction == SlopeReduction::NONE) {
            (FastsimMethod::Fastrip, _) => "modified FaStrip (CONTACT's M = 5)",
            (FastsimMethod::Fastsim, true) => "Kalker's FASTSIM",
            (FastsimMethod::Fastsim, false) => "the modified FASTSIM",
        };
        let place = match self.discretisation {
            FastsimDiscretisation::Strips => {
                format!("on {ny} strips of the Hertz ellipse, {nx} elements each")
            }
            FastsimDiscretisation::Grid => format!(
                "on CONTACT's rectangular grid of {nx} x {ny} elements over {} times the Hertz ellipse",
                self.window_scale
            ),
        };
        let flex = match self.flexibility_m_per_pa {
            Some(l) => format!("one flexibility L = {l:e} m/Pa (CONTACT's M = 2)"),
            None if self.discretisation == FastsimDiscretisation::Grid => {
                "Kalker's three flexibilities, blended towards one at large creepage as CONTACT's"
                    .into()
            }
            None => "Kalker's three flexibilities".into(),
        };
        let r = self.reduction;
        let mut s = format!(
            "solved by {method} {place}, {flex}, {} traction bound",
            match self.bound {
                TractionBound::Parabolic => "parabolic",
                TractionBound::Elliptic => "elliptic",
            }
        );
        if r.initial_factor != 1.0 || r.limit_ratio != 1.0 || r.transition_rate != 0.0 {
            s.push_str(&format!(
                ", slope reduction k0 = {}, alpha_inf = {}, beta = {}",
                r.initial_factor, r.limit_ratio, r.transition_rate
            ));
        }
        if self.has_falling_friction() {
            s.push_str(&format!(
                ", falling friction mu ((1 - {a}) exp(-{b} s/m w) + {a}) at the global slip velocity w = {v} m/s |(xi, eta)|",
                a = r.friction_limit_ratio,
                b = r.friction_decay_s_per_m,
                v = self.rolling_speed_m_per_s
            ));
        }
        s
    }
}

fn key(field: &str) -> String {
    format!("{FASTSIM_KEY}.{field}")
}

/// Validates `[fastsim]` for `model`, its friction and rolling direction
/// (`rolling_direction_rad`, already one of the axes).
pub(super) fn fastsim_options(
    section: Option<FastsimSection>,
    model: Model,
    friction: &Friction,
    rolling_direction_rad: f64,
    notes: &mut Vec<String>,
) -> Result<FastsimOptions, CaseError> {
    let Some(s) = section else {
        if model == Model::Fastsim && rolling_direction_rad != 0.0 {
            return Err(direction_refused());
        }
        return Ok(FastsimOptions::default());
    };
    if model != Model::Fastsim {
        return Err(bad(
            FASTSIM_KEY,
            format!(
                "the section chooses the variant of model = \"fastsim\", not of \"{}\": leave it out",
                model.name()
            ),
        ));
    }
    let method = s.method.unwrap_or_default();
    let discretisation = s.discretisation.unwrap_or_default();
    let grid = discretisation == FastsimDiscretisation::Grid;
    let bound = match s.traction_bound.unwrap_or_default() {
        TractionBoundName::Parabolic => TractionBound::Parabolic,
        TractionBoundName::Elliptic => TractionBound::Elliptic,
    };
    let reduction = SlopeReduction {
        initial_factor: s.initial_factor.unwrap_or(1.0),
        limit_ratio: s.limit_ratio.unwrap_or(1.0),
        transition_rate: s.transition_rate.unwrap_or(0.0),
        friction_limit_ratio: s.friction_limit_ratio.unwrap_or(1.0),
        friction_decay_s_per_m: s.friction_decay_s_per_m.unwrap_or(0.0),
    };
    reduction.validate_as(FASTSIM_KEY)?;
    TRANSITION_RATE.check(&key("transition_rate"), reduction.transition_rate)?;
    FRICTION_DECAY.check(
        &key("friction_decay_s_per_m"),
        reduction.friction_decay_s_per_m,
    )?;
    let grid_only = |field: &str, what: &str| {
        bad(
            key(field),
            format!(
                "{what} is solved on CONTACT's grid only: add `fastsim.discretisation = \"grid\"`"
            ),
        )
    };
    if method == FastsimMethod::Fastrip && !grid {
        return Err(grid_only("method", "FaStrip"));
    }
    if let Some(l) = s.flexibility_m_per_pa {
        FLEXIBILITY.check(&key("flexibility_m_per_pa"), l)?;
        if !grid {
            return Err(grid_only("flexibility_m_per_pa", "one given flexibility"));
        }
    }
    let window_scale = match s.window_scale {
        Some(_) if !grid => {
            return Err(bad(
                key("window_scale"),
                "sizes CONTACT's grid: used with `fastsim.discretisation = \"grid\"` only",
            ));
        }
        Some(v) => WINDOW_SCALE.check(&key("window_scale"), v)?,
        None => DEFAULT_WINDOW_SCALE,
    };
    let mut options = FastsimOptions {
        method,
        discretisation,
        bound,
        reduction,
        rolling_speed_m_per_s: 0.0,
        flexibility_m_per_pa: s.flexibility_m_per_pa,
        window_scale,
    };
    if let Some(v) = s.rolling_speed_m_per_s {
        options.rolling_speed_m_per_s = ROLLING_SPEED.check(&key("rolling_speed_m_per_s"), v)?;
    }
    if options.has_falling_friction() {
        if method == FastsimMethod::Fastrip {
            return Err(bad(
                key("friction_limit_ratio"),
                "FaStrip bounds the tractions by the static coefficient: falling friction is FASTSIM's only (leave out `friction_limit_ratio` and `friction_decay_s_per_m`)",
            ));
        }
        if s.rolling_speed_m_per_s.is_none() {
            return Err(bad(
                key("rolling_speed_m_per_s"),
                "missing: the falling friction (`friction_limit_ratio` < 1, `friction_decay_s_per_m` > 0) needs the rolling speed of its slip velocity",
            ));
        }
    } else if s.rolling_speed_m_per_s.is_some() {
        notes.push(
            "fastsim.rolling_speed_m_per_s unused: no falling friction (friction_limit_ratio < 1 and friction_decay_s_per_m > 0)"
                .into(),
        );
    }
    if grid && friction.static_coefficient != friction.kinetic_coefficient {
        return Err(bad(
            "friction.static_coefficient",
            "CONTACT's grid FASTSIM bounds the tractions with one coefficient: give `friction.coefficient` (strips take a static and a kinetic one)",
        ));
    }
    if rolling_direction_rad != 0.0 && !grid {
        return Err(direction_refused());
    }
    Ok(options)
}

fn direction_refused() -> CaseError {
    bad(
        ROLLING_DIRECTION_KEY,
        "model = \"fastsim\" rolls along -x (pi) on CONTACT's grid only (`fastsim.discretisation = \"grid\"`); on strips leave it 0",
    )
}

#[cfg(test)]
mod tests {
    const BASE: &str = "model = \"fastsim\"\n[material]\nshear_modulus_pa = 81.0e9\n\
                        poisson_ratio = 0.3\n[friction]\ncoefficient = 0.3\n[geometry]\n\
                        kind = \"quadratic\"\na_per_m = 2.6\nb_per_m = 0.92\n[load]\n\
                        normal_force_n = 1e4\n[rolling]\ncreepage_long = 1e-3\n";

    fn error(extra: &str) -> String {
        crate::problem::case::Case::from_toml(&format!("{BASE}{extra}"))
            .map(|_| String::from("accepted"))
            .unwrap_or_else(|e| e.to_string())
    }

    /// Every key out of its range, or where it is not used, is refused
    /// naming it.
    #[test]
    fn bad_keys_are_refused_naming_them() {
        let grid = "[fastsim]\ndiscretisation = \"grid\"\n";
        for (extra, key) in [
            (
                "[fastsim]\ninitial_factor = 0.0\n",
                "fastsim.initial_factor",
            ),
            (
                "[fastsim]\ninitial_factor = 1.5\n",
                "fastsim.initial_factor",
            ),
            ("[fastsim]\nlimit_ratio = -0.1\n", "fastsim.limit_ratio"),
            (
                "[fastsim]\ntransition_rate = -1.0\n",
                "fastsim.transition_rate",
            ),
            (
                "[fastsim]\ntransition_rate = 1e7\n",
                "fastsim.transition_rate",
            ),
            (
                "[fastsim]\nfriction_limit_ratio = 0.0\n",
                "fastsim.friction_limit_ratio",
            ),
            (
                "[fastsim]\nfriction_decay_s_per_m = -1.0\n",
                "fastsim.friction_decay_s_per_m",
            ),
            (
                "[fastsim]\nfriction_limit_ratio = 0.5\nfriction_decay_s_per_m = 1.0\n",
                "fastsim.rolling_speed_m_per_s",
            ),
            (
                "[fastsim]\nrolling_speed_m_per_s = 0.0\n",
                "fastsim.rolling_speed_m_per_s",
            ),
            ("[fastsim]\nmethod = \"fastrip\"\n", "fastsim.method"),
            (
                "[fastsim]\nflexibility_m_per_pa = 1e-13\n",
                "fastsim.flexibility_m_per_pa",
            ),
            ("[fastsim]\nwindow_scale = 1.1\n", "fastsim.window_scale"),
            (
                &format!("{grid}flexibility_m_per_pa = 0.0\n"),
                "fastsim.flexibility_m_per_pa",
            ),
            (
                &format!("{grid}flexibility_m_per_pa = 5e-324\n"),
                "fastsim.flexibility_m_per_pa",
            ),
            (
                &format!("{grid}window_scale = 0.9\n"),
                "fastsim.window_scale",
            ),
            (
                &format!(
                    "{grid}method = \"fastrip\"\nfriction_limit_ratio = 0.5\n\
                     friction_decay_s_per_m = 1.0\nrolling_speed_m_per_s = 10.0\n"
                ),
                "fastsim.friction_limit_ratio",
            ),
            ("[fastsim]\nmethod = \"fasttrip\"\n", "method"),
            ("[fastsim]\nbound = \"elliptic\"\n", "bound"),
            (
                "rolling_direction_rad = 3.141592653589793\n",
                "rolling_direction_rad",
            ),
        ] {
            // The top-level key goes before the tables.
            let e = if extra.starts_with("rolling_direction_rad") {
                crate::problem::case::Case::from_toml(&format!("{extra}{BASE}"))
                    .map(|_| String::from("accepted"))
                    .unwrap_or_else(|e| e.to_string())
            } else {
                error(extra)
            };
            assert!(e.contains(key), "{extra}: {e}");
        }
        // One coefficient on the grid.
        let two = BASE.replace(
            "coefficient = 0.3",
            "static_coefficient = 0.35\nkinetic_coefficient = 0.3",
        );
        let e = crate::problem::case::Case::from_toml(&format!("{two}{grid}"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("friction.static_coefficient"), "{e}");
        // Accepted: -x on the grid, and the full modified FASTSIM.
        let ok = crate::problem::case::Case::from_toml(&format!(
            "rolling_direction_rad = 3.141592653589793\n{BASE}{grid}initial_factor = 0.54\n\
             limit_ratio = 0.02\ntransition_rate = 0.62\nfriction_limit_ratio = 0.38\n\
             friction_decay_s_per_m = 0.7\nrolling_speed_m_per_s = 10.0\n\
             traction_bound = \"elliptic\"\nwindow_scale = 1.2\n"
        ))
        .unwrap();
        assert!(ok.fastsim.has_falling_friction());
        assert_eq!(ok.fastsim.window_scale, 1.2);
    }
}
