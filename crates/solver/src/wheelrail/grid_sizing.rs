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
//! and again when its patches change ([`SizeCheck::holds`]) to patches
//! none of its remembered checks saw (a periodic motion revisits its
//! states; where the pair's sides are alike, the other wheel's checks
//! count too); between checks the error drifts with the contact's place on
//! the grid, which the other half of the tolerance covers. A check's
//! solves start from the last step's contact (its box and its tractions
//! sampled on the other size), not cold. On the load test's path (50 kN a
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

/// Under `force_tolerance_of_wheel_load` the load iteration meets the
/// vertical force to this fraction of that tolerance (unless
/// `load_tolerance` asks for less): 5e-5 of the load at 5e-3, 2.5 N of 50
/// kN. The first solve of a warm step then meets it in most wheel steps:
/// on the load test's path (600 steps at 4 mm, 5e-3) 1,134 of 1,200 wheel
/// steps, against 635 at the default 1e-6 (benches/README.md, "Grids
/// sized for the forces asked").
pub const LOAD_TOLERANCE_DIVISOR: f64 = 100.0;

/// Under `force_tolerance_of_wheel_load` the exact patches' normal
/// solves stop at this relative change of the pressures per iteration
/// (unless the settings ask for less; 1e-6 without the option). On the
/// load test's path (600 steps at 4 mm, 5e-3) it and
/// [`SIZED_TANGENTIAL_TOLERANCE`] moved the wheels' forces by at most
/// 9.5e-5 of the load (median 2.5e-6) from the tolerances without the
/// option, and halved a step's normal iterations (benches/README.md,
/// "Solver tolerances sized for the forces asked").
pub const SIZED_NORMAL_TOLERANCE: f64 = 1e-4;

/// Under `force_tolerance_of_wheel_load` the exact patches' tangential
/// solves stop at this natural residual relative to mu p_max (unless the
/// settings ask for less; 1e-4 without the option). See
/// [`SIZED_NORMAL_TOLERANCE`].
pub const SIZED_TANGENTIAL_TOLERANCE: f64 = 1e-3;

/// The largest `force_tolerance_of_wheel_load` [-].
pub const MAX_FORCE_TOLERANCE: f64 = 0.1;

/// Key of the option (case file `grid` section and the wire).
pub const FORCE_TOLERANCE_KEY: &str = "grid.force_tolerance_of_wheel_load";

/// The most checks a wheel remembers ([`GridSizing::checks`]): a periodic
/// motion (hunting, a curve's entry and exit) revisits its contact states,
/// and a state a check has seen needs none again.
pub const MAX_CHECKS_KEPT: usize = 32;

/// One check of a wheel's element size: the size chosen and the patches it
/// was chosen for.
#[derive(Debug, Clone, PartialEq)]
pub struct SizeCheck {
    /// The element size chosen \[m\].
    pub element_size_m: f64,
    /// The largest difference of the forces (track x, y, z) on it from
    /// those on the reference size, relative to the wheel's vertical force
    /// [-] (0 when chosen equal to the reference).
    pub estimate: f64,
    /// Each patch's contact area \[m^2\] and contact angle \[rad\],
    /// field side first.
    pub patches: Vec<[f64; 2]>,
}

impl SizeCheck {
    fn new(element_size_m: f64, estimate: f64, wheel: &WheelResult) -> Self {
        Self {
            element_size_m,
            estimate,
            patches: wheel.patches.iter().map(patch_state).collect(),
        }
    }

    /// Whether `wheel` has the patches of this check: as many, none of a
    /// contact area changed by more than a factor [`RECHECK_AREA_RATIO`] or
    /// a contact angle by more than [`RECHECK_ANGLE_RAD`].
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
}

/// One wheel's element sizes chosen by its checks, kept across a session's
/// steps: the last check in force while it [`holds`](SizeCheck::holds), an
/// earlier one whose patches the wheel has again recalled instead of a new
/// check.
#[derive(Debug, Clone, PartialEq)]
pub struct GridSizing {
    /// The `element_size_m` of the settings the sizes were chosen for \[m\].
    pub reference_element_size_m: f64,
    /// The `force_tolerance_of_wheel_load` they were chosen for [-].
    pub tolerance: f64,
    /// The wheel's checks, the one in force last; at most
    /// [`MAX_CHECKS_KEPT`], the least recently used dropped first.
    pub checks: Vec<SizeCheck>,
}

impl GridSizing {
    /// The element size the wheel's patches are solved on \[m\].
    pub fn element_size_m(&self) -> f64 {
        self.in_force().element_size_m
    }

    /// The check in force.
    pub fn in_force(&self) -> &SizeCheck {
        self.checks
            .last()
            .expect("a sizing holds at least one check")
    }

    /// Puts in force the most recent check of `element_size_m` whose
    /// patches `wheel` has ([`SizeCheck::holds`]): of this wheel's checks
    /// (moved last), else of `other`'s (the other wheel's, made for the
    /// same reference size and tolerance; copied). Whether one was found.
    fn recall(
        &mut self,
        other: Option<&GridSizing>,
        element_size_m: f64,
        wheel: &WheelResult,
    ) -> bool {
        let fits = |c: &SizeCheck| c.element_size_m == element_size_m && c.holds(wheel);
        if let Some(k) = self.checks.iter().rposition(fits) {
            let c = self.checks.remove(k);
            self.checks.push(c);
            return true;
        }
        let copy = self.others(other).find(|c| fits(c)).cloned();
        copy.map(|c| self.push(c)).is_some()
    }

    /// The checks of `other` made for this sizing's reference size and
    /// tolerance, most recent first.
    fn others<'a>(&self, other: Option<&'a GridSizing>) -> impl Iterator<Item = &'a SizeCheck> {
        other
            .filter(|o| {
                o.reference_element_size_m == self.reference_element_size_m
                    && o.tolerance == self.tolerance
            })
            .into_iter()
            .flat_map(|o| o.checks.iter().rev())
    }

    /// The size of the most recent check of another size than
    /// `element_size_m` whose patches `wheel` has, of this wheel's checks,
    /// then of `other`'s.
    fn recalled_size(
        &self,
        other: Option<&GridSizing>,
        element_size_m: f64,
        wheel: &WheelResult,
    ) -> Option<f64> {
        self.checks
            .iter()
            .rev()
            .chain(self.others(other))
            .find(|c| c.element_size_m != element_size_m && c.holds(wheel))
            .map(|c| c.element_size_m)
    }

    /// Adds `check` in force, dropping the least recently used beyond
    /// [`MAX_CHECKS_KEPT`].
    fn push(&mut self, check: SizeCheck) {
        if self.checks.len() >= MAX_CHECKS_KEPT {
            self.checks.remove(0);
        }
        self.checks.push(check);
    }

    /// Heap memory it holds \[bytes\].
    pub(crate) fn heap_bytes(&self) -> usize {
        self.checks.capacity() * std::mem::size_of::<SizeCheck>()
            + self
                .checks
                .iter()
                .map(|c| 16 * c.patches.capacity())
                .sum::<usize>()
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
/// wheel) the size in force is solved and kept when its check still
/// [`holds`](SizeCheck::holds) or an earlier check of that size is
/// recalled; else, where an earlier check of another size holds for the
/// patches found, that size is solved and kept if its check holds there
/// too. Otherwise (and with no sizing yet) the size is chosen again: the
/// wheel solved on `reference_m`, then on each of [`GRID_COARSENINGS`]
/// coarsest first up to the first whose forces lie within half the
/// tolerance of the reference's (with as many patches); that solve is the
/// answer, else the reference's. The step's solves already made are not
/// made again. A coarser solve that fails (other than cancelled) ends the
/// check on the reference, and a kept size that fails is checked again.
/// Without `check` (the pitch iteration's further solves) the size in
/// force is kept. With `other`, the other wheel's sizing (of a pair whose
/// sides are alike, [`crate::wheelrail::WheelRailPair::sides_alike`]), its
/// checks are recalled too (copied to this wheel's).
pub(crate) fn solve_sized(
    reference_m: f64,
    tolerance: Option<f64>,
    sizing: &mut Option<GridSizing>,
    other: Option<&GridSizing>,
    check: bool,
    mut solve_at: impl FnMut(f64) -> Result<WheelSolved, WheelRailError>,
) -> Result<WheelSolved, WheelRailError> {
    let Some(tol) = tolerance else {
        return solve_at(reference_m);
    };
    if sizing
        .as_ref()
        .is_some_and(|s| s.reference_element_size_m != reference_m || s.tolerance != tol)
    {
        *sizing = None;
    }
    // This step's solves by element size, which the check takes up.
    let mut made: Vec<(f64, WheelSolved)> = Vec::new();
    match sizing.as_mut() {
        Some(s) => {
            let e = s.element_size_m();
            if let Some(solved) = attempt(e, reference_m, &mut solve_at)? {
                if !check || s.recall(other, e, &solved.0) {
                    return Ok(solved);
                }
                // A state an earlier check of another size has seen.
                if let Some(size) = s.recalled_size(other, e, &solved.0) {
                    if let Some(again) = attempt(size, reference_m, &mut solve_at)? {
                        if s.recall(other, size, &again.0) {
                            return Ok(again);
                        }
                        made.push((size, again));
                    }
                }
                made.push((e, solved));
            }
        }
        None if !check => return solve_at(reference_m),
        None => {}
    }
    let mut take = |e: f64| {
        let k = made.iter().position(|(m, _)| *m == e)?;
        Some(made.swap_remove(k).1)
    };
    let fine = match take(reference_m) {
        Some(solved) => solved,
        None => solve_at(reference_m)?,
    };
    let load = fine.0.force_track_n[2].abs();
    if fine.0.patches.is_empty() || load.is_nan() || load <= 0.0 {
        // Nothing to size: checked again at the next step.
        return Ok(fine);
    }
    let mut choose = |check: SizeCheck| match sizing {
        Some(s) => s.push(check),
        None => {
            *sizing = Some(GridSizing {
                reference_element_size_m: reference_m,
                tolerance: tol,
                checks: vec![check],
            })
        }
    };
    for m in GRID_COARSENINGS {
        let e = m * reference_m;
        let coarse = match take(e) {
            Some(solved) => solved,
            None => match attempt(e, reference_m, &mut solve_at)? {
                Some(solved) => solved,
                None => break,
            },
        };
        let estimate = (0..3)
            .map(|q| (coarse.0.force_track_n[q] - fine.0.force_track_n[q]).abs() / load)
            .fold(0.0, f64::max);
        if estimate <= 0.5 * tol && coarse.0.patches.len() == fine.0.patches.len() {
            choose(SizeCheck::new(e, estimate, &coarse.0));
            return Ok(coarse);
        }
    }
    choose(SizeCheck::new(reference_m, 0.0, &fine.0));
    Ok(fine)
}

/// `solve_at(e)`, None where it fails on a coarser size than `reference_m`:
/// a coarser grid may fail where the reference does not (a flange patch's
/// load not carried on 0.3 mm and coarser elements, on the load test's
/// motion at 12 mm).
fn attempt(
    e: f64,
    reference_m: f64,
    solve_at: &mut impl FnMut(f64) -> Result<WheelSolved, WheelRailError>,
) -> Result<Option<WheelSolved>, WheelRailError> {
    match solve_at(e) {
        Ok(solved) => Ok(Some(solved)),
        Err(WheelRailError::Cancelled) => Err(WheelRailError::Cancelled),
        Err(err) if e == reference_m => Err(err),
        Err(_) => Ok(None),
    }
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
