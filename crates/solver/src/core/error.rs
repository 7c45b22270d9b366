//! Errors of the contact core. Input errors name the offending key so that a
//! user can fix the case file or request; non-convergence is *not* an error
//! (it is reported in [`crate::core::solution::SolveInfo::status`]).

use thiserror::Error;

/// Everything that can go wrong when setting up or solving a contact problem.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ContactError {
    /// A value in the input is out of range, not finite, or inconsistent.
    /// Fix the named key.
    #[error("invalid input `{key}`: {reason}")]
    InvalidInput { key: String, reason: String },
    /// The potential contact grid does not hold the contact patch: loaded
    /// elements touch its border. Enlarge the window (`grid.window_*`);
    /// an unset window is sized from a Hertz estimate, which a patch can
    /// outgrow (the quasi-identity coupling, large shifts, a coarse grid).
    #[error("the contact patch reaches the border of the potential contact grid ({detail}); enlarge `{key}` (an unset window is sized from the Hertz patch, which this contact outgrows: set it larger)")]
    GridTooSmall {
        /// The window to enlarge: `grid.window_x_m` when the loaded
        /// border element is on a border in x, else `grid.window_y_m`.
        key: &'static str,
        /// Which element is loaded, and where.
        detail: String,
    },
    /// The bodies do not touch at the prescribed approach (no element
    /// penetrates): raise `load.approach_m` or use a normal force.
    #[error("no contact: {detail}")]
    NoContact { detail: String },
    /// A reference model (Hertz, FASTSIM, creep table) rejected its input.
    #[error("{0}")]
    Reference(String),
    /// The caller cancelled the solve before it finished (see
    /// [`crate::core::cancel`]); there is no answer.
    #[error("the solve was cancelled before it finished")]
    Cancelled,
}

impl ContactError {
    /// The error for a loaded element (`ix`, `iy`) on the border of a grid
    /// of `nx` elements in x at x = `x_m`, y (or s) = `y_m`.
    pub fn grid_too_small(ix: usize, iy: usize, nx: usize, x_m: f64, y_m: f64) -> Self {
        ContactError::GridTooSmall {
            key: if ix == 0 || ix + 1 == nx {
                "grid.window_x_m"
            } else {
                "grid.window_y_m"
            },
            detail: format!("element ({ix}, {iy}) at x = {x_m:.4e} m, y = {y_m:.4e} m is loaded"),
        }
    }

    /// The input key the error is about, when it names one.
    pub fn key(&self) -> Option<&str> {
        match self {
            ContactError::InvalidInput { key, .. } => Some(key),
            ContactError::GridTooSmall { key, .. } => Some(key),
            // Without contact at a prescribed approach (a force always
            // makes contact), the approach is too small.
            ContactError::NoContact { .. } => Some("load.approach_m"),
            ContactError::Reference(_) | ContactError::Cancelled => None,
        }
    }

    /// The error with an input key `from` or `from.…` renamed to `to` or
    /// `to.…` (a step's `step.shift_x_m` as `transient.steps[3].shift_x_m`;
    /// each of several keys joined by ", "); other errors unchanged.
    pub fn with_key_prefix(self, from: &str, to: &str) -> Self {
        match self {
            ContactError::InvalidInput { key, reason } => {
                let key = key
                    .split(", ")
                    .map(|k| match k.strip_prefix(from) {
                        Some(rest) if rest.is_empty() || rest.starts_with('.') => {
                            format!("{to}{rest}")
                        }
                        _ => k.to_string(),
                    })
                    .collect::<Vec<_>>()
                    .join(", ");
                ContactError::InvalidInput { key, reason }
            }
            other => other,
        }
    }

    /// Shorthand for [`ContactError::InvalidInput`].
    pub fn invalid(key: impl Into<String>, reason: impl Into<String>) -> Self {
        ContactError::InvalidInput {
            key: key.into(),
            reason: reason.into(),
        }
    }
}

/// Returns an error naming `key` unless `v` is finite and > 0.
pub fn require_positive(key: &str, v: f64) -> Result<(), ContactError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(ContactError::invalid(
            key,
            format!("must be finite and > 0, got {}", show(v)),
        ))
    }
}

/// Returns an error naming `key` unless `v` is finite.
pub fn require_finite(key: &str, v: f64) -> Result<(), ContactError> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(ContactError::invalid(
            key,
            format!("must be finite, got {}", show(v)),
        ))
    }
}

/// A value as an error message quotes it: short (`1e300`, not 301
/// digits), at most a few dozen characters whatever the input.
pub fn show(v: f64) -> String {
    let a = v.abs();
    if v == 0.0 || !v.is_finite() || (1e-3..1e5).contains(&a) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// 0 degrees Celsius in kelvin \[K\].
pub const CELSIUS_ZERO_K: f64 = 273.15;

/// A unit mistake a [`Range`] recognises in a value outside it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UnitHint {
    /// No guess.
    None,
    /// A modulus in Pa given in GPa (`81` for 81e9).
    GigaPascal,
    /// A length in m given in mm (`460` for 0.46).
    Millimetre,
    /// A temperature in K given in degrees Celsius (`20` for 293.15).
    Celsius,
}

/// The documented range of a numeric input: `min` .. `max` (each bound
/// included or not), in `unit`. Non-finite values are never inside.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Range {
    /// Lower bound.
    pub min: f64,
    /// Whether `min` itself is allowed.
    pub min_inclusive: bool,
    /// Upper bound.
    pub max: f64,
    /// Whether `max` itself is allowed.
    pub max_inclusive: bool,
    /// Unit as written after the bounds (`"Pa"`, `"m"`, `"1/m"`, `""`).
    pub unit: &'static str,
    /// The unit mistake to suggest for a value outside.
    pub hint: UnitHint,
}

impl Range {
    /// `[min, max]`.
    pub const fn closed(min: f64, max: f64, unit: &'static str) -> Self {
        Range {
            min,
            min_inclusive: true,
            max,
            max_inclusive: true,
            unit,
            hint: UnitHint::None,
        }
    }

    /// `(0, max]`: a strictly positive quantity.
    pub const fn positive(max: f64, unit: &'static str) -> Self {
        Range {
            min: 0.0,
            min_inclusive: false,
            max,
            max_inclusive: true,
            unit,
            hint: UnitHint::None,
        }
    }

    /// `[-limit, limit]`.
    pub const fn symmetric(limit: f64, unit: &'static str) -> Self {
        Range::closed(-limit, limit, unit)
    }

    /// The range with a unit mistake to suggest.
    pub const fn hint(self, hint: UnitHint) -> Self {
        Range { hint, ..self }
    }

    /// Whether `v` is inside.
    pub fn contains(&self, v: f64) -> bool {
        let above = if self.min_inclusive {
            v >= self.min
        } else {
            v > self.min
        };
        let below = if self.max_inclusive {
            v <= self.max
        } else {
            v < self.max
        };
        v.is_finite() && above && below
    }

    /// The range as written in messages and documentation: `(0, 1e8] N`.
    pub fn describe(&self) -> String {
        let unit = if self.unit.is_empty() {
            String::new()
        } else {
            format!(" {}", self.unit)
        };
        format!(
            "{}{}, {}{}{unit}",
            if self.min_inclusive { "[" } else { "(" },
            show(self.min),
            show(self.max),
            if self.max_inclusive { "]" } else { ")" },
        )
    }

    /// `v` if inside, else an error naming `key` that states the range,
    /// the value and, where it recognises one, the likely unit mistake.
    pub fn check(&self, key: &str, v: f64) -> Result<f64, ContactError> {
        if self.contains(v) {
            return Ok(v);
        }
        let hint = match self.hint {
            UnitHint::GigaPascal if v > 0.0 && v < self.min && self.contains(v * 1e9) => {
                format!(
                    " (did you mean {} Pa, i.e. {} GPa?)",
                    show(v * 1e9),
                    show(v)
                )
            }
            // Divided (not multiplied by 1e-3): 6.5 mm is 0.0065 m, not
            // 0.006500000000000001.
            UnitHint::Millimetre if v.abs() > self.max && self.contains(v / 1e3) => format!(
                " (this looks like millimetres: did you mean {} m?)",
                show(v / 1e3)
            ),
            UnitHint::Celsius if self.contains(v + CELSIUS_ZERO_K) => format!(
                " (this looks like degrees Celsius: did you mean {} K?)",
                show(v + CELSIUS_ZERO_K)
            ),
            _ => String::new(),
        };
        Err(ContactError::invalid(
            key,
            format!("must be in {}, got {}{hint}", self.describe(), show(v)),
        ))
    }
}

/// `n` if it is in `min..=max`, else an error naming `key` that states the
/// range and the value.
pub fn check_count(key: &str, n: usize, min: usize, max: usize) -> Result<usize, ContactError> {
    if (min..=max).contains(&n) {
        Ok(n)
    } else {
        Err(ContactError::invalid(
            key,
            format!("must be in [{min}, {max}], got {n}"),
        ))
    }
}
