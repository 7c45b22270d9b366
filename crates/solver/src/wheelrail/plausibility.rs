//! Plausibility of a wheelset solution: answers that no elastic wheel/rail
//! contact gives, and forces inconsistent with the kinematics given, each
//! reported as a [`PlausibilityWarning`] naming the input that causes it.
//!
//! [`solve_wheelset`](crate::wheelrail::solve_wheelset) solves what it is
//! asked: a roll angle or a pitch rate that suits one profile pair (the
//! Manchester benchmark's S1002 on UIC60, whose roll and pitch rate
//! `examples/cases/wheelset_a22.toml` gives as CONTACT found them) is solved
//! as faithfully on another, where it means something else. The front ends
//! (`railcontact wheelrail`, the service's wheel/rail answers, and through
//! them the clients) call [`check_plausibility`] on every solution and pass
//! its warnings on; the solution itself is unchanged.
//!
//! # The checks
//!
//! **Approach** ([`WarningKind::Approach`], load given as a vertical force
//! only). Each wheel of a [`WheelLoad::VerticalForce`] load is pressed onto
//! its rail on its own, from the rigid position, until it carries its load.
//! Where the two wheels both touch at the rigid position (the roll found
//! from the profiles), each wheel's approach is the elastic approach of its
//! patches. Where a prescribed roll leaves one wheel above its rail, its
//! approach also closes that rigid gap: the wheel moves relative to the
//! other by the gap, which no rigid wheelset does, and its contact point and
//! forces are not those of the wheelset. The measure: per patch, its
//! approach along its normal (`approach_m`, which includes the patch's
//! rigid gap) over the elastic approach of its normal force on its contact
//! area, [`elastic_approach_m`] = 3 F / (4 E* c) with c = sqrt(A / pi),
//! Hertz's approach of a circle of the same force and area (a Hertz ellipse
//! of the same force and area has 1.0 to 0.74 times it for a/b from 1 to
//! 10). A wheel's ratio is its patches' smallest (its most loaded patch
//! starts at the rigid contact point; another patch of the same wheel
//! starts at a gap of its own). A wheel warns above [`APPROACH_LIMIT`] = 10.
//! Seen on the Manchester benchmark's case A-2.2 (S1002 on UIC60, 10 kN a
//! wheel, shifts 0 to 10 mm, models `exact` and `hertz_fastsim`): 0.61-1.15
//! with the roll found (0.6-0.7 on the flange), 0.61-3.87 with CONTACT's
//! rolls (3.87 at 6.5 mm, where our profiles' smoothing leaves 0.069 mm
//! between the left wheel and its rail at CONTACT's roll); 0.96-1.00 along
//! the load test's motion (50 kN a wheel, Hertz+FASTSIM). With the measured profiles `Car7216_0001r.whl` and
//! `avg_wheel.whl` on `avg_HR.BAN` at the benchmark's roll at 6.5 mm: 44.7
//! and 224.6 (1.32 and 5.60 mm of rigid gap closed by 10 kN, whose elastic
//! approach is 0.025-0.030 mm). The warning names `position.roll_rad` when
//! the roll is prescribed and the wheel's rigid gap is at least half its
//! approach, else `load.vertical_force_n`. With the approach or the
//! wheelset centre's height given (an MBS integrator's state) the load
//! follows the approach and both wheels share it, so a wheel above its rail
//! at a prescribed roll only carries less: that is the motion asked for,
//! and not checked.
//!
//! **Longitudinal force** ([`WarningKind::LongitudinalForce`], a prescribed
//! pitch rate, both wheels solved). A free-rolling wheelset carries no
//! total longitudinal force: its wheels' creep forces along the track
//! cancel, whatever each wheel's own (A-2.2's flange and tread contacts
//! each saturate, in opposite directions). A pitch rate far from free
//! rolling drives or brakes both wheels the same way until their creep
//! forces saturate: the wheelset slides on its rails. Two measures of the
//! total longitudinal force F = sum of the wheels' `force_track_n[0]`: its
//! share of the adhesion the lateral forces leave, |F| / sum over the
//! patches of sqrt((mu Fn)^2 - Fs^2) (1 when both wheels slide the same
//! way), and its share of the adhesion of the load, |F| / sum of mu Fn.
//! The warning needs both: the first at least [`SATURATION_LIMIT`] = 0.9,
//! the second at least [`LONGITUDINAL_SHARE_LIMIT`] = 0.25 (so that a
//! remainder of adhesion that large lateral forces leave does not count).
//! Seen: the sweep at CONTACT's pitch rates 0.075 and 0.038 at most
//! (exact), 0.162 and 0.161 (Hertz+FASTSIM, 0 mm); the measured
//! `avg_wheel.whl` on `avg_HR.BAN` at the benchmark's pitch rate at 6.5 mm
//! 1.00 and 0.47 (1.00 and 0.74 with the roll found: the pitch rate alone
//! is off). The warning names `velocity.pitch_rad_per_s` and says how to
//! leave it to the solver: `load.total_longitudinal_force_n = 0` finds the
//! free-rolling pitch rate (or give the traction or braking force meant).
//! Not checked: one wheel solved alone (its own longitudinal force says
//! nothing of the wheelset's), a pitch rate found for a prescribed total
//! longitudinal force, and the default pitch rate -V / nominal radius,
//! which is documented as what it is: free rolling only where the wheels
//! roll on the nominal radius (on in flange contact, 6.5 to 10 mm,
//! it brakes the wheelset with 0.36-0.44 of mu times its normal force, the
//! first measure 0.895-0.915; along the load test's motion, 4 mm at 20 m/s
//! and 50 kN a wheel, 0.41 and 0.40 with Hertz+FASTSIM).
//!
//! **Iteration limit** ([`WarningKind::Unconverged`], models `exact`,
//! `cect` and `auto`). A patch whose exact or conformal solver stopped at
//! its iteration limit before its tolerances were met reports its last
//! iterate ([`PatchResult::unconverged`]); its wheel warns once, naming
//! [`MODEL_KEY`], with the number of such patches. Seen: none on at
//! CONTACT's rolls and pitch rates (exact, 0 to 10 mm).
//!
//! **Opposed surfaces** ([`WarningKind::OpposedSurfaces`]). The creepages
//! are relative speeds over the rolling speed, the mean of the two
//! surfaces' speeds at the contact; a locked wheel on a moving rail
//! slides at a longitudinal creepage of 2. Beyond
//! [`SLIDING_CREEPAGE_LIMIT`] the two surfaces move against each other:
//! on a roller rig the rollers and the wheel turn the same way (a sign
//! slip in one of the two rates), and the rolling speed tends to 0, the
//! creepage to infinity (test-rollers2's bus at its rates with the
//! rollers' reversed: 2.3e8); the patch slides fully, Fx = mu Fn. The
//! wheel warns once, naming [`PITCH_RATE_KEY`], with the largest
//! creepage's size.

use std::fmt;

use serde::Serialize;

use crate::core::material::CombinedMaterial;
use crate::wheelrail::contact::{
    PatchResult, WheelLoad, WheelRailInput, WheelRailSolution, WheelResult,
    TOTAL_LONGITUDINAL_FORCE_KEY,
};
use crate::wheelrail::wheelset::Side;

/// Key of the prescribed roll angle (case file and wire).
pub const ROLL_KEY: &str = "position.roll_rad";
/// Key of the prescribed pitch rate (case file and wire).
pub const PITCH_RATE_KEY: &str = "velocity.pitch_rad_per_s";
/// Key of the vertical force per wheel (case file and wire).
pub const VERTICAL_FORCE_KEY: &str = "load.vertical_force_n";
/// Key of the contact model (case file and wire).
pub const MODEL_KEY: &str = "model";

/// A wheel's approach above this multiple of its patches' elastic approach
/// ([`elastic_approach_m`]) warns (see the module docs).
pub const APPROACH_LIMIT: f64 = 10.0;

/// The total longitudinal force warns at this share of the adhesion the
/// lateral forces leave, |F| / sum sqrt((mu Fn)^2 - Fs^2), or above, ...
pub const SATURATION_LIMIT: f64 = 0.9;

/// ... when it is also at least this share of mu times the normal forces
/// (see the module docs).
pub const LONGITUDINAL_SHARE_LIMIT: f64 = 0.25;

/// A patch's longitudinal creepage warns above this size [-]: a locked
/// wheel (no rotation) on a moving rail slides at 2 (the relative speed
/// over the mean of the two surfaces' speeds); beyond it the two surfaces
/// move against each other at the contact.
pub const SLIDING_CREEPAGE_LIMIT: f64 = 2.0;

/// What a [`PlausibilityWarning`] finds implausible.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum WarningKind {
    /// A wheel's approach beyond what its load and the materials allow.
    Approach,
    /// The wheels' total longitudinal force saturates in one direction:
    /// the pitch rate is far from free rolling.
    LongitudinalForce,
    /// A patch's exact or conformal solver stopped at its iteration limit:
    /// the wheel's forces include a last iterate, not a solution.
    Unconverged,
    /// A patch's longitudinal creepage beyond [`SLIDING_CREEPAGE_LIMIT`]:
    /// the wheel's and the rail's (a roller's) surfaces move against each
    /// other at the contact, and the patch slides fully.
    OpposedSurfaces,
}

impl WarningKind {
    /// `"approach"`, `"longitudinal_force"`, `"unconverged"` or
    /// `"opposed_surfaces"`.
    pub fn name(self) -> &'static str {
        match self {
            WarningKind::Approach => "approach",
            WarningKind::LongitudinalForce => "longitudinal_force",
            WarningKind::Unconverged => "unconverged",
            WarningKind::OpposedSurfaces => "opposed_surfaces",
        }
    }
}

/// One finding of [`check_plausibility`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlausibilityWarning {
    /// What is implausible.
    pub kind: WarningKind,
    /// The input that causes it, by its case-file key, which is also its
    /// path in a wire request: [`ROLL_KEY`], [`PITCH_RATE_KEY`],
    /// [`VERTICAL_FORCE_KEY`] or [`MODEL_KEY`].
    pub key: &'static str,
    /// The wheel concerned; `None` for the wheelset as a whole.
    pub side: Option<Side>,
    /// The measure that exceeded its limit [-]: a wheel's approach over its
    /// elastic approach ([`WarningKind::Approach`]), or the total
    /// longitudinal force's share of the adhesion the lateral forces leave
    /// ([`WarningKind::LongitudinalForce`]).
    pub value: f64,
    /// Its limit: [`APPROACH_LIMIT`], [`SATURATION_LIMIT`],
    /// [`SLIDING_CREEPAGE_LIMIT`], or 0 for [`WarningKind::Unconverged`]
    /// (whose value counts the patches).
    pub limit: f64,
    /// What was found, with its numbers, why, and what to do.
    pub message: String,
}

impl fmt::Display for PlausibilityWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.key, self.message)
    }
}

/// The elastic approach of a normal force `normal_force_n` \[N\] on a
/// contact area `contact_area_m2` \[m^2\] between bodies of `material` \[m\]:
/// Hertz's approach of a circular contact of that force and area,
/// 3 F / (4 E* c) with c = sqrt(A / pi) and E* = G / (1 - nu) (Kalker's
/// combined constants); a Hertz ellipse of the same force and area has 1.0
/// to 0.74 times it for a/b from 1 to 10. 0 without force or area.
pub fn elastic_approach_m(
    normal_force_n: f64,
    contact_area_m2: f64,
    material: &CombinedMaterial,
) -> f64 {
    if !(normal_force_n > 0.0 && contact_area_m2 > 0.0) {
        return 0.0;
    }
    let radius = (contact_area_m2 / std::f64::consts::PI).sqrt();
    3.0 * normal_force_n / (4.0 * material.effective_modulus_pa() * radius)
}

/// The warnings of `solution`, solved for `input` (none for a plausible
/// answer): see the module docs for the checks and their limits.
pub fn check_plausibility(
    input: &WheelRailInput,
    solution: &WheelRailSolution,
) -> Vec<PlausibilityWarning> {
    let mut out = Vec::new();
    if let WheelLoad::VerticalForce(load) = input.load {
        for w in &solution.wheels {
            out.extend(approach_warning(input, w, load));
        }
    }
    out.extend(longitudinal_warning(input, solution));
    out.extend(solution.wheels.iter().filter_map(unconverged_warning));
    out.extend(solution.wheels.iter().filter_map(opposed_warning));
    out
}

/// A wheel whose patch with the largest longitudinal creepage exceeds
/// [`SLIDING_CREEPAGE_LIMIT`] in size: one warning, naming
/// [`PITCH_RATE_KEY`], its value that creepage's size.
fn opposed_warning(w: &WheelResult) -> Option<PlausibilityWarning> {
    let p = w
        .patches
        .iter()
        .max_by(|a, b| a.creepage_long.abs().total_cmp(&b.creepage_long.abs()))?;
    let size = p.creepage_long.abs();
    if size.is_nan() || size <= SLIDING_CREEPAGE_LIMIT * (1.0 + 1e-9) {
        return None;
    }
    Some(PlausibilityWarning {
        kind: WarningKind::OpposedSurfaces,
        key: PITCH_RATE_KEY,
        side: Some(w.side),
        value: size,
        limit: SLIDING_CREEPAGE_LIMIT,
        message: format!(
            "the {} wheel's patch at track y = {:.2} mm has a longitudinal creepage of {:.3e} \
             at a rolling speed of {:.3e} m/s, beyond the {SLIDING_CREEPAGE_LIMIT} of a locked \
             wheel: the wheel's surface and the rail's (a roller's) move against each other \
             at the contact, and the patch slides fully. Check the signs of {PITCH_RATE_KEY}, \
             velocity.forward_m_per_s and, on a roller rig, velocity.roller_rad_per_s",
            w.side.name(),
            p.track_y_m * 1e3,
            p.creepage_long,
            p.rolling_speed_m_per_s,
        ),
    })
}

/// A wheel with patches whose iterative solver stopped at its iteration
/// limit: one warning, naming [`MODEL_KEY`], its value the number of such
/// patches (limit 0).
fn unconverged_warning(w: &WheelResult) -> Option<PlausibilityWarning> {
    let stopped: Vec<&PatchResult> = w.patches.iter().filter(|p| p.unconverged).collect();
    let first = stopped.first()?;
    Some(PlausibilityWarning {
        kind: WarningKind::Unconverged,
        key: MODEL_KEY,
        side: Some(w.side),
        value: stopped.len() as f64,
        limit: 0.0,
        message: format!(
            "{} of the {} wheel's {} patches (the first at track y = {:.2} mm, model {}) \
             stopped at the solver's iteration limit before its tolerances were met: their \
             forces are the last iterate, not a solution; a coarser `element_size_m` or a fast \
             model gives a converged answer",
            stopped.len(),
            w.side.name(),
            w.patches.len(),
            first.track_y_m * 1e3,
            first.method
        ),
    })
}

/// A wheel's approach check (load given as a vertical force `load_n`).
fn approach_warning(
    input: &WheelRailInput,
    w: &WheelResult,
    load_n: f64,
) -> Option<PlausibilityWarning> {
    // The patch whose approach its elastic approach explains best.
    let (ratio, p, elastic) = w
        .patches
        .iter()
        .filter_map(|p| {
            let e = elastic_approach_m(p.normal_force_n, p.contact_area_m2, &input.material);
            (e > 0.0 && p.approach_m.is_finite()).then(|| (p.approach_m / e, p, e))
        })
        .min_by(|a, b| a.0.total_cmp(&b.0))?;
    if ratio <= APPROACH_LIMIT {
        return None;
    }
    let side = w.side.name();
    let found = format!(
        "the {side} wheel is pressed {:.3} mm onto its rail to carry {} N: its patch's approach \
         ({:.3} mm along the normal) is {ratio:.1} times the elastic approach of the patch's \
         {:.0} N on {:.2} mm^2 ({:.4} mm, Hertz's for that force and area; limit \
         {APPROACH_LIMIT}), which no elastic contact gives",
        w.vertical_approach_m * 1e3,
        fmt_force(load_n),
        p.approach_m * 1e3,
        p.normal_force_n,
        p.contact_area_m2 * 1e6,
        elastic * 1e3,
    );
    let (key, message) = match input.position.roll_rad {
        Some(roll) if w.min_gap_m >= 0.5 * w.vertical_approach_m => {
            // Contact points about 2 |y| apart, y from the wheelset centre.
            let span = 2.0 * (p.track_y_m - input.position.lateral_m).abs();
            let offset = if span > 0.0 {
                format!(
                    " (about {:.2} mrad from a roll at which both wheels touch)",
                    w.min_gap_m / span * 1e3
                )
            } else {
                String::new()
            };
            (
                ROLL_KEY,
                format!(
                    "{found}. The prescribed roll {ROLL_KEY} = {:.4} mrad leaves this wheel \
                     {:.3} mm above its rail at the rigid position{offset}, and its load \
                     pressed it through that gap alone, which no rigid wheelset does: its \
                     contact and forces are not this wheelset's. Leave {ROLL_KEY} out to have \
                     the roll found from these profiles (a roll suits one profile pair: that \
                     of examples/cases/wheelset_a22.toml is CONTACT's for S1002 on UIC60)",
                    roll * 1e3,
                    w.min_gap_m * 1e3,
                ),
            )
        }
        _ => (
            VERTICAL_FORCE_KEY,
            format!(
                "{found}; its rigid gap was {:.3} mm: check the load and the profiles' \
                 placement (track.gauge_m, wheelset.flange_back_distance_m, the profiles' \
                 mirroring)",
                w.min_gap_m * 1e3
            ),
        ),
    };
    Some(PlausibilityWarning {
        kind: WarningKind::Approach,
        key,
        side: Some(w.side),
        value: ratio,
        limit: APPROACH_LIMIT,
        message,
    })
}

/// The wheelset's longitudinal force check (both wheels, pitch rate
/// prescribed).
fn longitudinal_warning(
    input: &WheelRailInput,
    solution: &WheelRailSolution,
) -> Option<PlausibilityWarning> {
    let rate = input.velocity.pitch_rad_per_s?;
    let both = Side::BOTH
        .iter()
        .all(|s| solution.wheels.iter().any(|w| w.side == *s));
    if !both {
        return None;
    }
    let patches = || solution.wheels.iter().flat_map(|w| &w.patches);
    let adhesion = |p: &PatchResult| p.friction_coefficient * p.normal_force_n;
    let total: f64 = solution.wheels.iter().map(|w| w.force_track_n[0]).sum();
    let limit: f64 = patches().map(adhesion).sum();
    let left: f64 = patches()
        .map(|p| (adhesion(p).powi(2) - p.fs_n.powi(2)).max(0.0).sqrt())
        .sum();
    if !(limit > 0.0 && left > 0.0) {
        return None;
    }
    let (used, share) = (total.abs() / left, total.abs() / limit);
    // (False for NaN forces too.)
    let saturated = used >= SATURATION_LIMIT && share >= LONGITUDINAL_SHARE_LIMIT;
    if !saturated {
        return None;
    }
    let per_wheel: Vec<String> = solution
        .wheels
        .iter()
        .map(|w| format!("{} {:.0} N", w.side.name(), w.force_track_n[0]))
        .collect();
    let message = format!(
        "the wheels' total longitudinal force on the rails, {total:.0} N ({}), is {:.0} % of the \
         adhesion their lateral forces leave ({left:.0} N) and {:.0} % of mu times their normal \
         force ({limit:.0} N; limits {:.0} % and {:.0} %): both wheels are driven or braked the \
         same way to near saturation, where a free-rolling wheelset has no total longitudinal \
         force. The prescribed pitch rate {PITCH_RATE_KEY} = {rate} rad/s is far from free \
         rolling for these profiles and this position: leave it out and set \
         {TOTAL_LONGITUDINAL_FORCE_KEY} = 0 to have the free-rolling pitch rate found (or to the \
         traction or braking force meant)",
        per_wheel.join(", "),
        100.0 * used,
        100.0 * share,
        100.0 * SATURATION_LIMIT,
        100.0 * LONGITUDINAL_SHARE_LIMIT,
    );
    Some(PlausibilityWarning {
        kind: WarningKind::LongitudinalForce,
        key: PITCH_RATE_KEY,
        side: None,
        value: used,
        limit: SATURATION_LIMIT,
        message,
    })
}

/// A force in N without a needless fraction.
fn fmt_force(f: f64) -> String {
    if f == f.round() && f.abs() < 1e15 {
        format!("{f:.0}")
    } else {
        format!("{f:.1}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::material::Material;

    // The checks on solved wheelsets (the benchmark, the load test's
    // motion, the measured profiles) are in the validation tests
    // (`tests/validation/plausibility.rs`).

    #[test]
    fn elastic_approach_is_hertzs_of_a_circle() {
        // Hertz, a sphere of radius R on a plane: a^3 = 3 F R / (4 E*),
        // delta = a^2 / R.
        let m = CombinedMaterial::identical(Material {
            shear_modulus_pa: 82e9,
            poisson_ratio: 0.28,
        })
        .unwrap();
        let (f, r) = (1e4, 0.3);
        let e = m.effective_modulus_pa();
        let a = (3.0 * f * r / (4.0 * e)).cbrt();
        let area = std::f64::consts::PI * a * a;
        let d = elastic_approach_m(f, area, &m);
        assert!(
            (d - a * a / r).abs() < 1e-12 * d,
            "{d} against {}",
            a * a / r
        );
        assert_eq!(elastic_approach_m(0.0, area, &m), 0.0);
        assert_eq!(elastic_approach_m(f, 0.0, &m), 0.0);
    }

    #[test]
    fn a_warning_shows_its_key_first() {
        let w = PlausibilityWarning {
            kind: WarningKind::LongitudinalForce,
            key: PITCH_RATE_KEY,
            side: None,
            value: 1.0,
            limit: SATURATION_LIMIT,
            message: "the message".into(),
        };
        assert_eq!(w.to_string(), "velocity.pitch_rad_per_s: the message");
        assert_eq!(WarningKind::Approach.name(), "approach");
        assert_eq!(
            serde_json::to_value(&w).unwrap()["kind"],
            "longitudinal_force"
        );
    }
}
