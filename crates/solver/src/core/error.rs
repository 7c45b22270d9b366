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
    /// elements touch its border. Enlarge the window (`grid.window_*`), or
    /// leave it unset so it is sized from a Hertz estimate.
    #[error("the contact patch reaches the border of the potential contact grid ({detail}); enlarge `grid.window_x_m`/`grid.window_y_m` or leave them unset")]
    GridTooSmall { detail: String },
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
            format!("must be finite and > 0, got {v}"),
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
            format!("must be finite, got {v}"),
        ))
    }
}
