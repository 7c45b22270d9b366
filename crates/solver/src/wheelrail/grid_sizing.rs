//! Element sizes chosen for the forces asked
//! ([`crate::wheelrail::WheelRailSettings::force_tolerance_of_wheel_load`]).
//!
//! A multibody step needs a wheel's forces to a fraction of its load, not
//! the pressure's detail. Under the option a wheel's patches are solved on
//! the coarsest of [`GRID_COARSENINGS`] times `element_size_m` whose forces
//! (track x, y, z) lie within half the tolerance of those on
//! `element_size_m`: two grid levels, the user's and a coarser one, and
//! their difference is the error the tolerance is stated against (the
//! reference is the solve on the user's grid, so no extrapolation to a
//! finer one is needed). The check is made when a wheel has no choice yet
//! and again when its patches change ([`GridSizing::holds`]); between
//! checks the error drifts with the contact's place on the grid, which the
//! other half of the tolerance covers. On the load test's path (50 kN a
//! wheel, lateral 4 mm and yaw 2 mrad at 2 Hz) warm steps on fixed sizes
//! stay within 5.1e-4 / 7.5e-4 / 1.25e-3 / 2.0e-3 / 3.0e-3 of the load of
//! cold solves on 0.2 mm at 0.2 / 0.25 / 0.3 / 0.4 / 0.5 mm (every 10th
//! of 600 steps; benches/README.md, "Grids sized for the forces asked").

use crate::wheelrail::contact::{PatchResult, PatchTractions, WheelResult};
use crate::wheelrail::wheelset::WheelRailError;
use crate::wheelrail::WheelRailModel;

/// The coarser element sizes a check tries, as multiples of
/// `element_size_m`, coarsest first.
pub const GRID_COARSENINGS: [f64; 4] = [2.5, 2.0, 1.5, 1.25];

/// A patch whose contact area grows or shrinks by more than this factor
/// since its wheel's check is checked again [-]: the discretisation error
/// of the forces follows the elements across the patch.
pub const RECHECK_AREA_RATIO: f64 = 1.5;

/// A patch whose contact angle turns by more than this since its wheel's
/// check is checked again \[rad\] (another part of the profiles, of
/// other curvatures).
pub const RECHECK_ANGLE_RAD: f64 = 0.05;

/// The smallest `force_tolerance_of_wheel_load` [-]. Below it the drift
/// between checks and the warm steps' own scatter (5e-4 of the load on
/// 0.2 mm, against cold solves) outgrow the half of the tolerance left to
/// them: at 2e-3 the load test's path reached 2.16e-3 of the load, at
/// 1e-3 (a check on a contact's position instead of its area) 1.41e-3.
pub const MIN_FORCE_TOLERANCE: f64 = 5e-3;

/// The largest `force_tolerance_of_wheel_load` [-].
pub const MAX_FORCE_TOLERANCE: f64 = 0.1;

/// Key of the option (case file `grid` section and the wire).
pub const FORCE_TOLERANCE_KEY: &str = "grid.force_tolerance_of_wheel_load";

/// One wheel's element size chosen at its last check, kept across a
/// session's steps while [`Self::holds`].
#[derive(Debug, Clone, PartialEq)]
pub struct GridSizing {
    /// The element size the wheel's patches are solved on \[m\].
    pub element_size_m: f64,
    /// The `element_size_m` of the settings it was chosen for \[m\].
    pub reference_element_size_m: f64,
    /// The `force_tolerance_of_wheel_load` it was chosen for [-].
    pub tolerance: f64,
    /// At the check: the largest difference of the forces (track x, y, z)
    /// from those on `reference_element_size_m`, relative to the wheel's
    /// vertical force [-] (0 when chosen equal to it).
    pub estimate: f64,
    /// At the check: each patch's contact area \[m^2\] and contact angle
    /// \[rad\], field side first.
    pub patches: Vec<[f64; 2]>,
}

impl GridSizing {
    fn new(
        element_size_m: f64,
        reference: f64,
        tolerance: f64,
        estimate: f64,
        wheel: &WheelResult,
    ) -> Self {
        Self {
            element_size_m,
            reference_element_size_m: reference,
            tolerance,
            estimate,
            patches: wheel.patches.iter().map(patch_state).collect(),
        }
    }

    /// Whether `wheel`, solved on this size, has the patches of the check:
    /// as many, none of a contact area changed by more than a factor
    /// [`RECHECK_AREA_RATIO`] or a contact angle by more than
    /// [`RECHECK_ANGLE_RAD`].
    pub fn holds(&self, wheel: &WheelResult) -> bool {
        wheel.patches.len() == self.patches.len()
            && wheel
                .patches
                .iter()
                .zip(&self.patches)
                .all(|(p, &[a, angle])| {
                    let [area, now] = patch_state(p);
                    area <= RECHECK_AREA_RATIO * a
                        && area * RECHECK_AREA_RATIO >= a
                        && (now - angle).abs() <= RECHECK_ANGLE_RAD
                })
    }

    /// Heap memory it holds \[bytes\].
    pub(crate) fn heap_bytes(&self) -> usize {
        16 * self.patches.capacity()
    }
}

fn patch_state(p: &PatchResult) -> [f64; 2] {
    [p.contact_area_m2, p.contact_angle_rad]
}

/// Refuses a `force_tolerance_of_wheel_load` out of
/// [[`MIN_FORCE_TOLERANCE`], [`MAX_FORCE_TOLERANCE`]] (or NaN) or with a
/// model without grids, naming [`FORCE_TOLERANCE_KEY`]: the check of
/// every solve, of case files and of the wire.
pub fn validate(tolerance: f64, model: WheelRailModel) -> Result<(), WheelRailError> {
    if !(MIN_FORCE_TOLERANCE..=MAX_FORCE_TOLERANCE).contains(&tolerance) {
        return Err(WheelRailError::invalid(
            FORCE_TOLERANCE_KEY,
            format!(
                "must be between {MIN_FORCE_TOLERANCE} and {MAX_FORCE_TOLERANCE} (a fraction of \
                 the wheel's vertical force), got {tolerance}"
            ),
        ));
    }
    if model.is_fast() {
        return Err(WheelRailError::invalid(
            FORCE_TOLERANCE_KEY,
            format!(
                "model '{}' solves no patch grid to size: give it to models exact, auto or cect",
                model.name()
            ),
        ));
    }
    Ok(())
}

/// A wheel's solve: its patches, the load iteration's last ratio and the
/// tractions a session carries.
pub(crate) type WheelSolved = (WheelResult, Option<f64>, Option<PatchTractions>);

/// One wheel solved under `tolerance` (`force_tolerance_of_wheel_load`,
/// None: on `reference_m`, the settings' `element_size_m`), `solve_at(e)`
/// solving it on elements of e. With `check` (a step's first solve of the
/// wheel) a kept `sizing` that no longer [`GridSizing::holds`], or none,
/// is chosen again: the wheel solved on `reference_m`, then on each of
/// [`GRID_COARSENINGS`] coarsest first up to the first whose forces lie
/// within half the tolerance of the reference's (with as many patches);
/// that solve is the answer, else the reference's. A coarser solve that
/// fails (other than cancelled) ends the check on the reference, and a
/// kept size that fails is checked again. Without `check` (the pitch
/// iteration's further solves) the size of `sizing` is kept.
pub(crate) fn solve_sized(
    reference_m: f64,
    tolerance: Option<f64>,
    sizing: &mut Option<GridSizing>,
    check: bool,
    mut solve_at: impl FnMut(f64) -> Result<WheelSolved, WheelRailError>,
) -> Result<WheelSolved, WheelRailError> {
    let Some(tol) = tolerance else {
        return solve_at(reference_m);
    };
    let kept = sizing
        .as_ref()
        .filter(|s| s.reference_element_size_m == reference_m && s.tolerance == tol);
    let mut on_reference = None;
    match kept {
        Some(s) => match solve_at(s.element_size_m) {
            Ok(solved) if !check || s.holds(&solved.0) => return Ok(solved),
            Ok(solved) if s.element_size_m == reference_m => on_reference = Some(solved),
            // Checked again: a coarser grid may fail where the reference
            // does not (a flange patch's load not carried on 0.3 mm and
            // coarser elements, on the load test's motion at 12 mm).
            Ok(_) => {}
            Err(WheelRailError::Cancelled) => return Err(WheelRailError::Cancelled),
            Err(e) if s.element_size_m == reference_m => return Err(e),
            Err(_) => {}
        },
        None if !check => return solve_at(reference_m),
        None => {}
    }
    let fine = match on_reference {
        Some(solved) => solved,
        None => solve_at(reference_m)?,
    };
    let load = fine.0.force_track_n[2].abs();
    if fine.0.patches.is_empty() || load.is_nan() || load <= 0.0 {
        // Nothing to size: checked again at the next step.
        *sizing = None;
        return Ok(fine);
    }
    for m in GRID_COARSENINGS {
        let e = m * reference_m;
        let coarse = match solve_at(e) {
            Ok(coarse) => coarse,
            Err(WheelRailError::Cancelled) => return Err(WheelRailError::Cancelled),
            Err(_) => break,
        };
        let estimate = (0..3)
            .map(|q| (coarse.0.force_track_n[q] - fine.0.force_track_n[q]).abs() / load)
            .fold(0.0, f64::max);
        if estimate <= 0.5 * tol && coarse.0.patches.len() == fine.0.patches.len() {
            *sizing = Some(GridSizing::new(e, reference_m, tol, estimate, &coarse.0));
            return Ok(coarse);
        }
    }
    *sizing = Some(GridSizing::new(reference_m, reference_m, tol, 0.0, &fine.0));
    Ok(fine)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tolerances_out_of_range_and_fast_models_are_refused_naming_the_key() {
        let exact = WheelRailModel::Exact;
        assert!(validate(5e-3, exact).is_ok());
        assert!(validate(MAX_FORCE_TOLERANCE, WheelRailModel::Auto).is_ok());
        for bad in [0.0, -1e-2, 1e-3, 0.2, f64::NAN, f64::INFINITY] {
            let err = validate(bad, exact).unwrap_err().to_string();
            assert!(err.contains(FORCE_TOLERANCE_KEY), "{bad}: {err}");
        }
        let err = validate(1e-2, WheelRailModel::HertzFastsim).unwrap_err();
        assert!(err.to_string().contains(FORCE_TOLERANCE_KEY), "{err}");
    }
}
