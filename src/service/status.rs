//! The service's errors and their gRPC status codes, in one place.
//!
//! Every failure a handler can meet becomes a [`ServiceError`]; the one
//! `From<ServiceError> for tonic::Status` and [`ServiceError::item_error`]
//! (batch slots, session steps) use the same [`ServiceError::code`]. Input
//! errors carry the path of the offending field in the request, built up
//! as the error travels outwards ([`ServiceError::within`]): the core
//! names case-file keys (`geometry.a_per_m`), the handler adds where the
//! case sits in its request (`items[3].case.`).

use thiserror::Error;
use tonic::Code;

use crate::core::error::ContactError;
use crate::problem::CaseError;
use crate::service::pb;
use crate::wheelrail::{ProfileError, WheelRailError};

/// Why a request (or one item or step of it) failed.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ServiceError {
    /// The request is invalid: fix `field` (INVALID_ARGUMENT).
    #[error("invalid `{field}`: {reason}")]
    Invalid {
        /// Path of the field in the request (empty: the request as a whole).
        field: String,
        /// What is wrong and how to fix it.
        reason: String,
    },
    /// The request names something that does not exist, e.g. an unknown
    /// profile pair id (NOT_FOUND).
    #[error("{0}")]
    NotFound(String),
    /// The request does not fit the current state, e.g. a session step out
    /// of order or a rollback to an unmarked step (FAILED_PRECONDITION).
    #[error("{reason}")]
    Precondition {
        /// Path of the request field that does not fit the state
        /// (`step.step_index`); empty when no field of the request is at
        /// fault.
        field: String,
        /// What does not fit and what to do.
        reason: String,
    },
    /// The solve queue is full or too many sessions are open; retry later
    /// (RESOURCE_EXHAUSTED).
    #[error("{0}")]
    Exhausted(String),
    /// The client's deadline passed before the result was ready, or a
    /// session idled for the server's `session_idle_timeout_s`
    /// (DEADLINE_EXCEEDED).
    #[error("{0}")]
    Deadline(String),
    /// The solve was stopped before it finished, because its request
    /// ended while it ran (CANCELLED; see [`crate::core::cancel`]). No
    /// client receives it: by then the request was answered with
    /// DEADLINE_EXCEEDED or its client is gone, and the solve's result is
    /// dropped. `railcontact_solves_cancelled_total` counts these solves.
    #[error(
        "the solve was stopped before it finished: its deadline passed or its client went away"
    )]
    Cancelled,
    /// A valid request whose answer holds a number that is not finite
    /// (OUT_OF_RANGE): `output` names it in the result
    /// (`result.info.normal_residual`). The documented input ranges are
    /// meant to make this impossible; it is refused, never sent.
    #[error("the answer's `{output}` is {value}, not a finite number: this input is beyond what the solver can represent; bring it closer to the documented ranges")]
    NonFinite {
        /// Path of the output in the result message.
        output: String,
        /// The value (NaN or an infinity), as text.
        value: String,
    },
    /// The server is shutting down (UNAVAILABLE).
    #[error("{0}")]
    Unavailable(String),
    /// A fault of the server, not of the request (INTERNAL).
    #[error("internal error: {0}")]
    Internal(String),
}

impl ServiceError {
    /// Shorthand for [`ServiceError::Precondition`].
    pub fn precondition(field: impl Into<String>, reason: impl Into<String>) -> Self {
        ServiceError::Precondition {
            field: field.into(),
            reason: reason.into(),
        }
    }

    /// Shorthand for [`ServiceError::Invalid`].
    pub fn invalid(field: impl Into<String>, reason: impl Into<String>) -> Self {
        ServiceError::Invalid {
            field: field.into(),
            reason: reason.into(),
        }
    }

    /// The gRPC status code of this error.
    pub fn code(&self) -> Code {
        match self {
            ServiceError::Invalid { .. } => Code::InvalidArgument,
            ServiceError::NotFound(_) => Code::NotFound,
            ServiceError::Precondition { .. } => Code::FailedPrecondition,
            ServiceError::Exhausted(_) => Code::ResourceExhausted,
            ServiceError::Deadline(_) => Code::DeadlineExceeded,
            ServiceError::Cancelled => Code::Cancelled,
            ServiceError::NonFinite { .. } => Code::OutOfRange,
            ServiceError::Unavailable(_) => Code::Unavailable,
            ServiceError::Internal(_) => Code::Internal,
        }
    }

    /// The error with its field path put under `prefix` (`"case"`,
    /// `"items[3]"`): `geometry.a_per_m` becomes `case.geometry.a_per_m`. An
    /// empty prefix changes nothing.
    pub fn within(self, prefix: &str) -> Self {
        match self {
            ServiceError::Invalid { field, reason } if !prefix.is_empty() => {
                ServiceError::Invalid {
                    field: if field.is_empty() {
                        prefix.to_string()
                    } else {
                        format!("{prefix}.{field}")
                    },
                    reason,
                }
            }
            other => other,
        }
    }

    /// The error with the field path `from` itself (not a child of it)
    /// renamed `to`: `load` -> `load.center_z_m`.
    pub fn rename(self, from: &str, to: &str) -> Self {
        match self {
            ServiceError::Invalid { field, reason } if field == from => ServiceError::Invalid {
                field: to.to_string(),
                reason,
            },
            other => other,
        }
    }

    /// The error with a field path starting with `from` renamed to start
    /// with `to` (`rolling.spin_per_m` -> `step.creepages.spin_per_m`).
    pub fn rekey(self, from: &str, to: &str) -> Self {
        match self {
            ServiceError::Invalid { field, reason } if field.starts_with(from) => {
                ServiceError::Invalid {
                    field: format!("{to}{}", &field[from.len()..]),
                    reason,
                }
            }
            other => other,
        }
    }

    /// The error in a batch slot or a session response.
    pub fn item_error(&self) -> pb::ItemError {
        pb::ItemError {
            code: self.code() as i32,
            message: self.to_string(),
            field: match self {
                ServiceError::Invalid { field, .. } | ServiceError::Precondition { field, .. } => {
                    field.clone()
                }
                _ => String::new(),
            },
        }
    }
}

impl From<ContactError> for ServiceError {
    /// Input errors keep the key they name ([`ContactError::key`]): a key
    /// out of range, the window of a patch that reaches the grid's border,
    /// the approach that makes no contact.
    fn from(e: ContactError) -> Self {
        match e {
            ContactError::InvalidInput { key, reason } => {
                ServiceError::Invalid { field: key, reason }
            }
            ContactError::Cancelled => ServiceError::Cancelled,
            e => ServiceError::invalid(e.key().unwrap_or_default(), e.to_string()),
        }
    }
}

impl From<CaseError> for ServiceError {
    /// The case validation's errors are messages; those that name a key
    /// (`invalid input `key`: reason`) keep it as the field.
    fn from(e: CaseError) -> Self {
        match e {
            CaseError::BadInput(m) => {
                let keyed = m
                    .strip_prefix("invalid input `")
                    .and_then(|rest| rest.split_once("`: "));
                match keyed {
                    Some((key, reason)) => ServiceError::invalid(key, reason),
                    None => ServiceError::invalid("", m),
                }
            }
            CaseError::Failure(m) => ServiceError::Internal(m),
            CaseError::Cancelled => ServiceError::Cancelled,
        }
    }
}

impl ServiceError {
    /// A profile that could not be read, at `field` of the request; the
    /// reader's message names the file and line.
    pub fn profile(field: &str, e: &ProfileError) -> Self {
        ServiceError::invalid(field, e.to_string())
    }
}

impl From<WheelRailError> for ServiceError {
    /// Keyed input errors keep their key (`position.yaw_rad`); profiles
    /// that cannot be fitted or placed name the pair's `spec`; a patch that
    /// cannot be solved is an input error of the query like the core's
    /// (grid too small: `element_size_m`; no contact: `load`).
    fn from(e: WheelRailError) -> Self {
        match e {
            WheelRailError::Invalid { key, message } => ServiceError::invalid(key, message),
            WheelRailError::Spline { .. } => ServiceError::invalid("pair_id", e.to_string()),
            // The profiles do not face each other at this lateral shift
            // (with this yaw and roll).
            WheelRailError::Geometry { .. } => {
                ServiceError::invalid("position.lateral_m", e.to_string())
            }
            // The load needs more approach than the profiles allow.
            WheelRailError::LoadNotCarried { .. } => ServiceError::invalid("load", e.to_string()),
            WheelRailError::Cancelled
            | WheelRailError::Contact {
                source: ContactError::Cancelled,
                ..
            } => ServiceError::Cancelled,
            WheelRailError::Contact {
                side,
                patch,
                source,
            } => {
                let field = match &source {
                    ContactError::InvalidInput { key, .. } => key.clone(),
                    ContactError::GridTooSmall { .. } => "element_size_m".into(),
                    ContactError::NoContact { .. } => "load".into(),
                    ContactError::Reference(_) | ContactError::Cancelled => String::new(),
                };
                ServiceError::invalid(field, format!("{side} wheel, patch {patch}: {source}"))
            }
        }
    }
}

/// The start of tonic's message when it refuses a request message larger
/// than `max_message_bytes` (with OUT_OF_RANGE, before any handler sees it).
const OVERSIZE_REQUEST: &str = "Error, decoded message length too large";

/// RESOURCE_EXHAUSTED for tonic's refusal of a request message larger than
/// `max_message_bytes` (`tonic_message`, percent-decoded); None for any
/// other message. gRPC's status table has RESOURCE_EXHAUSTED for this, and
/// clients retry it differently from OUT_OF_RANGE: split the request.
pub fn oversize_request(tonic_message: &str) -> Option<tonic::Status> {
    let detail = tonic_message.strip_prefix("Error, ")?;
    tonic_message.starts_with(OVERSIZE_REQUEST).then(|| {
        tonic::Status::resource_exhausted(format!(
            "the request is larger than this server accepts (max_message_bytes): {detail}; \
             split it into smaller requests"
        ))
    })
}

/// A status that reading a request stream gave, as the client should see
/// it (an oversize message is RESOURCE_EXHAUSTED, see [`oversize_request`]).
pub fn inbound(s: tonic::Status) -> tonic::Status {
    match s.code() {
        Code::OutOfRange => oversize_request(s.message()).unwrap_or(s),
        _ => s,
    }
}

impl From<ServiceError> for tonic::Status {
    fn from(e: ServiceError) -> Self {
        tonic::Status::new(e.code(), e.to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn case_errors_keep_their_key_under_the_request_path() {
        let e = ServiceError::from(CaseError::BadInput(
            "invalid input `geometry.a_per_m`: must be finite and > 0, got NaN".into(),
        ))
        .within("case")
        .within("items[2]");
        assert_eq!(e.code(), Code::InvalidArgument);
        let item = e.item_error();
        assert_eq!(item.field, "items[2].case.geometry.a_per_m");
        assert!(item.message.contains("must be finite"), "{}", item.message);
        // A message without a key names the case as a whole.
        let e = ServiceError::from(CaseError::BadInput("Hertz model: bad".into())).within("case");
        assert_eq!(e.item_error().field, "case");
        let e = ServiceError::from(ContactError::invalid(
            "rolling.spin_per_m",
            "must be finite",
        ))
        .rekey("rolling.", "step.creepages.");
        assert_eq!(e.item_error().field, "step.creepages.spin_per_m");
        let s = tonic::Status::from(ServiceError::Exhausted("full".into()));
        assert_eq!(s.code(), Code::ResourceExhausted);
    }

    #[test]
    fn wheel_rail_errors_name_the_field_by_their_kind() {
        let load = ServiceError::from(WheelRailError::LoadNotCarried {
            side: "left",
            max_approach_m: 2e-3,
        });
        assert_eq!(load.code(), Code::InvalidArgument);
        let item = load.item_error();
        assert_eq!(item.field, "load");
        assert!(
            item.message.contains("exceeds 2.000 mm"),
            "{}",
            item.message
        );
        let apart = ServiceError::from(WheelRailError::Geometry {
            side: "right",
            message: "the profiles do not face each other".into(),
        });
        assert_eq!(apart.item_error().field, "position.lateral_m");
    }
}
