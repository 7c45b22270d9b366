//! The library's errors, and their one mapping to CONTACT's `ierror`
//! codes ([`CntcError::ierror`]).

use railcontact_solver::core::error::ContactError;
use railcontact_solver::wheelrail::{ProfileError, WheelRailError, VISCOELASTIC_SETTINGS_KEY};
use thiserror::Error;

use crate::flags::err;

/// Why a call failed. The message names the call's argument or CONTACT's
/// parameter to fix; [`CntcError::ierror`] is the code the caller reads.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum CntcError {
    /// A null pointer or a negative length.
    #[error("argument `{arg}`: {reason}")]
    Argument {
        /// The C argument's name.
        arg: &'static str,
        /// What is wrong with it.
        reason: String,
    },
    /// The result element number is outside \[1, 999\].
    #[error("ire = {0} is out of range [1, 999]")]
    Ire(i32),
    /// The contact patch does not exist or does not suit the call (module
    /// 3 needs icp in \[1, 9\]; module 1 reads patches 1..npatch).
    #[error("{0}")]
    Icp(String),
    /// A flag value or method this library does not have.
    #[error("not supported: {0}")]
    NotSupported(String),
    /// Invalid friction parameters.
    #[error("friction: {0}")]
    Friction(String),
    /// Invalid discretisation parameters.
    #[error("discretisation: {0}")]
    Discretisation(String),
    /// A profile could not be read or placed.
    #[error("profile: {0}")]
    Profile(String),
    /// The contact search failed.
    #[error("contact search: {0}")]
    Search(String),
    /// The total force iteration found no solution.
    #[error("total force iteration: {0}")]
    ForceIteration(String),
    /// The normal problem did not converge.
    #[error("normal problem: {0}")]
    Normal(String),
    /// The tangential problem did not converge.
    #[error("tangential problem: {0}")]
    Tangential(String),
    /// An input value is out of range or missing.
    #[error("{0}")]
    Input(String),
    /// An input file (`cntc_readinpfile`) could not be opened or read, or
    /// a value in it is wrong (named with its file and line).
    #[error("{0}")]
    InputFile(String),
    /// A railcontact server could not be reached or refused the call
    /// (server mode).
    #[error("server: {0}")]
    Server(String),
    /// Anything else (a panic caught at the boundary included).
    #[error("{0}")]
    Other(String),
}

impl CntcError {
    /// CONTACT's error code (negative) of this error.
    pub fn ierror(&self) -> i32 {
        match self {
            CntcError::Argument { .. } => err::ARGUMENT,
            CntcError::Ire(_) => err::IRE,
            CntcError::Icp(_) => err::ICP,
            CntcError::NotSupported(_) => err::NOT_SUPPORTED,
            CntcError::Friction(_) => err::FRCLAW,
            CntcError::Discretisation(_) => err::DISCR,
            CntcError::Profile(_) => err::PROFIL,
            CntcError::Search(_) => err::SEARCH,
            CntcError::ForceIteration(_) => err::FTOT,
            CntcError::Normal(_) => err::NORM,
            CntcError::Tangential(_) => err::TANG,
            CntcError::Input(_) => err::OTHER,
            CntcError::InputFile(_) => err::INPUT,
            CntcError::Server(_) => err::SERVER,
            CntcError::Other(_) => err::OTHER,
        }
    }

    /// The message without the variant's prefix (what
    /// [`CntcError::from_ierror`] takes back).
    pub fn detail(&self) -> String {
        match self {
            CntcError::Icp(m)
            | CntcError::NotSupported(m)
            | CntcError::Friction(m)
            | CntcError::Discretisation(m)
            | CntcError::Profile(m)
            | CntcError::Search(m)
            | CntcError::ForceIteration(m)
            | CntcError::Normal(m)
            | CntcError::Tangential(m)
            | CntcError::Input(m)
            | CntcError::InputFile(m)
            | CntcError::Server(m)
            | CntcError::Other(m) => m.clone(),
            CntcError::Argument { .. } | CntcError::Ire(_) => self.to_string(),
        }
    }

    /// The error of code `ierror` with `detail` (an error that crossed
    /// the wire); a code of no variant is [`CntcError::Other`].
    pub fn from_ierror(ierror: i32, detail: String) -> Self {
        match ierror {
            err::ICP => CntcError::Icp(detail),
            err::NOT_SUPPORTED => CntcError::NotSupported(detail),
            err::FRCLAW => CntcError::Friction(detail),
            err::DISCR => CntcError::Discretisation(detail),
            err::PROFIL => CntcError::Profile(detail),
            err::SEARCH => CntcError::Search(detail),
            err::FTOT => CntcError::ForceIteration(detail),
            err::NORM => CntcError::Normal(detail),
            err::TANG => CntcError::Tangential(detail),
            err::SERVER => CntcError::Server(detail),
            err::INPUT => CntcError::InputFile(detail),
            _ => CntcError::Other(detail),
        }
    }

    /// A null or negative argument.
    pub fn argument(arg: &'static str, reason: impl Into<String>) -> Self {
        CntcError::Argument {
            arg,
            reason: reason.into(),
        }
    }

    /// The solver's error in `call`, as the caller reads it: its input key
    /// decides the code (a grid key is a discretisation error, a friction
    /// key a friction error).
    pub fn from_contact(e: ContactError) -> Self {
        let key = e.key().unwrap_or("").to_string();
        let msg = e.to_string();
        if key.starts_with("grid") {
            CntcError::Discretisation(msg)
        } else if key.starts_with("friction") {
            CntcError::Friction(msg)
        } else {
            CntcError::Input(msg)
        }
    }

    /// The wheel/rail layer's error.
    pub fn from_wheelrail(e: WheelRailError) -> Self {
        let msg = e.to_string();
        match &e {
            WheelRailError::Invalid { key, .. } if key.contains("profile") => {
                CntcError::Profile(msg)
            }
            WheelRailError::Invalid { key, .. } if key.starts_with("friction") => {
                CntcError::Friction(msg)
            }
            WheelRailError::Invalid { key, .. } if key.starts_with("position") => {
                CntcError::Search(msg)
            }
            // Transient contact of another number of patches than one.
            WheelRailError::Invalid { key, .. } if key == "exact_tangential" => {
                CntcError::NotSupported(msg)
            }
            // Viscoelastic bodies (M = 1) where the patches cannot take
            // them: rolling backwards, too large a grid.
            WheelRailError::Invalid { key, .. } if key == VISCOELASTIC_SETTINGS_KEY => {
                CntcError::NotSupported(msg)
            }
            WheelRailError::Invalid { .. } => CntcError::Input(msg),
            WheelRailError::Spline { .. } => CntcError::Profile(msg),
            WheelRailError::Geometry { .. } => CntcError::Search(msg),
            WheelRailError::LoadNotCarried { .. } => CntcError::ForceIteration(msg),
            WheelRailError::Contact { source, .. } => match CntcError::from_contact(source.clone())
            {
                CntcError::Input(_) => CntcError::Other(msg),
                other => other,
            },
            WheelRailError::Cancelled => CntcError::Other(msg),
        }
    }

    /// A profile's reading error.
    pub fn from_profile(e: ProfileError) -> Self {
        CntcError::Profile(e.to_string())
    }
}

/// Results of the library's calls.
pub type Result<T, E = CntcError> = std::result::Result<T, E>;
