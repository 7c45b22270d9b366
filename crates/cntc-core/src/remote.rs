//! What a library that forwards its calculations and the service exchange,
//! as bytes inside the service's `ContactLibrary` stream: the calls made on
//! an element since the last calculation and the patch to calculate in,
//! the calculation's code and result out. Both ends are this crate, so the
//! element the server calculates is the one the library configured.
//!
//! The encoding is postcard (compact, every f64 exact);
//! [`FORMAT_VERSION`] changes whenever a type in it changes, and each end
//! refuses another version by name.

use serde::{Deserialize, Serialize};

use crate::call::Call;
use crate::element::CalculationResult;
use crate::error::{CntcError, Result};

/// The version of the payload's encoding (of [`Call`], [`Request`] and
/// [`Reply`] and the types they hold).
pub const FORMAT_VERSION: u32 = 5;

/// A calculation asked of the server.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Request {
    /// Calls to apply first, each on its patch `icp`, in order.
    pub calls: Vec<(i32, Call)>,
    /// The patch to calculate (module 1: any).
    pub icp: i32,
}

/// The server's answer to a [`Request`].
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Reply {
    /// The calculation's code (>= 0) or its error.
    pub code: std::result::Result<i32, WireError>,
    /// What the calculation left on the element.
    pub result: CalculationResult,
    /// The calculation's time on the server \[s\].
    pub seconds: f64,
}

/// An error as it crosses the wire: its `ierror` code and message.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct WireError {
    /// CONTACT's code ([`CntcError::ierror`]).
    pub ierror: i32,
    /// The message without the variant's prefix.
    pub message: String,
}

impl From<&CntcError> for WireError {
    fn from(e: &CntcError) -> Self {
        WireError {
            ierror: e.ierror(),
            message: e.detail(),
        }
    }
}

impl From<WireError> for CntcError {
    fn from(w: WireError) -> Self {
        CntcError::from_ierror(w.ierror, w.message)
    }
}

/// Encodes `v`.
pub fn encode<T: Serialize>(v: &T) -> Result<Vec<u8>> {
    postcard::to_stdvec(v).map_err(|e| CntcError::Other(format!("encoding the payload: {e}")))
}

/// Decodes a `what` from `bytes`.
pub fn decode<'a, T: Deserialize<'a>>(bytes: &'a [u8], what: &str) -> Result<T> {
    postcard::from_bytes(bytes).map_err(|e| {
        CntcError::Input(format!(
            "the {what} is not a version {FORMAT_VERSION} payload of railcontact-cntc-core: {e}"
        ))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::outcome::{DisplacementSource, Outcome};
    use railcontact_solver::core::grid::Grid;
    use railcontact_solver::core::material::Material;

    #[test]
    fn a_reply_crosses_bit_for_bit() {
        let grid = Grid::new(5, 4, 1e-3, 2e-3, -2.5e-3, -4e-3).unwrap();
        let mut outcome = Outcome::no_contact(grid, vec![0.1 + 0.2; 20], 1.0 / 3.0);
        outcome.fields.pressure_pa[3] = f64::MIN_POSITIVE;
        outcome.fx_n = -0.0;
        outcome.fields.pressure_pa[7] = 1e6 / 3.0;
        outcome.fields.traction_x_pa[7] = -1e5 / 3.0;
        outcome.displacement_source = Some(DisplacementSource::Influence {
            body1: Material::STEEL,
            body2: Material::STEEL,
            layer_flexibility_m_per_pa: 1e-12 / 3.0,
            viscoelastic: None,
        });
        // Computed before sending: the memo does not travel, the receiver
        // computes the same from the source.
        let sent = outcome.displacements_m().unwrap().clone();
        let reply = Reply {
            code: Err(WireError::from(&CntcError::Friction("mu < 0".into()))),
            result: CalculationResult::Patch {
                outcome: Some(Box::new(outcome.clone())),
            },
            seconds: 1e-3,
        };
        let back: Reply = decode(&encode(&reply).unwrap(), "reply").unwrap();
        let CalculationResult::Patch { outcome: Some(o) } = back.result else {
            panic!("a patch's result")
        };
        assert_eq!(o.grid, grid);
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&o.fields.gap_m), bits(&outcome.fields.gap_m));
        assert_eq!(
            bits(&o.fields.pressure_pa),
            bits(&outcome.fields.pressure_pa)
        );
        assert_eq!(o.displacement_source, outcome.displacement_source);
        let received = o.displacements_m().unwrap();
        assert!(sent[0][7] < 0.0 && sent[2][7] > 0.0);
        for (d, e) in received.iter().zip(&sent) {
            assert_eq!(bits(d), bits(e));
        }
        assert_eq!(o.approach_m.to_bits(), (1.0f64 / 3.0).to_bits());
        assert_eq!(o.fx_n.to_bits(), (-0.0f64).to_bits());
        let e = CntcError::from(back.code.unwrap_err());
        assert_eq!(e, CntcError::Friction("mu < 0".into()));
    }

    #[test]
    fn a_grid_out_of_range_is_refused_when_decoded() {
        let grid = Grid::new(5, 4, 1e-3, 2e-3, -2.5e-3, -4e-3).unwrap();
        let mut bytes = encode(&grid).unwrap();
        // nx is the first varint: 5 -> 0 elements.
        assert_eq!(bytes[0], 5);
        bytes[0] = 0;
        assert!(decode::<Grid>(&bytes, "grid").is_err());
    }
}
