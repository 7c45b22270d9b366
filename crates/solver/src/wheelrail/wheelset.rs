//! Track and wheelset: where the rail and wheel profiles sit, and where the
//! wheelset is and how it moves.
//!
//! # Frames (used by [`crate::wheelrail::search`] and
//! [`crate::wheelrail::contact`])
//!
//! * **Track frame** (x, y, z): origin on the track centre line at the
//!   height of the top of the rails, x along the track in the direction of
//!   travel, y to the **right**, z **down**; right-handed. The right rail
//!   lies at y > 0, the left rail at y < 0.
//! * **Side frame** (x, q, z) of one wheel/rail side: the track frame for the
//!   right side; for the left side its mirror image, q = -y. In its side
//!   frame every side looks like the right-hand side of the profile
//!   convention of [`crate::wheelrail`]: field side at +q, gauge side (track
//!   centre) at -q, and the same profile files serve both sides. Vectors
//!   map as v_side = (v_x, s v_y, v_z) and rotation rates (pseudo-vectors)
//!   as w_side = (s w_x, w_y, s w_z), with s = +1 right, -1 left.
//! * **Rail placement** ([`RailPlacement`]): the rail profile is inclined
//!   by the track's `cant_rad` (rail inclination, towards the track centre)
//!   about its origin, then shifted: at the gauge point
//!   ([`RailPlacement::GaugePoint`]) so that its highest point is at z = 0
//!   and its gauge face, `gauge_height_m` below that, lies at q = gauge/2;
//!   absolutely ([`RailPlacement::Origin`], CONTACT's GAUGHT <= 0) so that
//!   its origin lies at (q, z) = (`q_m`, `z_m`), wherever its top then is.
//!   A rail's [`RailDeviation`] then turns it about its origin and shifts
//!   it (CONTACT's DYRAIL, DZRAIL, DROLLR).
//! * **Wheel placement**: the wheel profile's y axis runs along the axle,
//!   outwards; its point at y = `flange_back_y_m` (the back of the flange,
//!   by default the profile's smallest y) lies at half the flange-back
//!   distance from the wheelset centre. The rolling radius at profile
//!   height z is `nominal_radius_m + z` (the profile's z = 0 is the
//!   nominal rolling circle, z grows towards the rail).
//! * **Wheelset position**: centre at (0, `lateral_m`, z), rotated by
//!   `roll_rad` about x, then by `yaw_rad` about z (so the axle direction is
//!   (-sin yaw cos roll, cos yaw cos roll, sin roll)). Positive roll lowers
//!   the right wheel, positive yaw turns the wheelset's forward direction
//!   towards the right.
//! * **Wheelset velocity**: forward speed V along x, lateral and vertical
//!   speeds, roll and yaw rates about x and z, and the rotation rate about
//!   the axle `pitch_rad_per_s` (free rolling at the nominal radius is
//!   -V / `nominal_radius_m`: negative, the bottom of the wheel moving
//!   backwards).

use std::sync::Arc;

use crate::core::error::{require_finite, require_positive, ContactError};
use crate::core::memory::{heap_bytes, HeapBytes};
use crate::wheelrail::search::{LocusSample, VerticalGap};
use crate::wheelrail::slices::WheelSlices;
use crate::wheelrail::spline::{ProfileSpline, SplineError, SplineOptions};
use crate::wheelrail::{Profile, ProfileKind};

/// Errors of the wheel/rail geometry and solution.
#[derive(Debug, thiserror::Error)]
pub enum WheelRailError {
    /// An input value is out of range; `key` names it as in the case file.
    #[error("{key}: {message}")]
    Invalid {
        /// Input key.
        key: String,
        /// What is wrong.
        message: String,
    },
    /// A profile could not be fitted.
    #[error("{side} {what} profile: {source}")]
    Spline {
        /// "left" or "right".
        side: &'static str,
        /// "rail" or "wheel".
        what: &'static str,
        /// Cause.
        #[source]
        source: SplineError,
    },
    /// The wheel and rail profiles do not face each other.
    #[error("{side} wheel: {message}")]
    Geometry {
        /// "left" or "right".
        side: &'static str,
        /// What is wrong.
        message: String,
    },
    /// The load needs more approach than the profiles allow at this
    /// position.
    #[error(
        "{side} wheel: the vertical approach needed exceeds {:.3} mm; the load cannot be carried",
        .max_approach_m * 1e3
    )]
    LoadNotCarried {
        /// "left" or "right".
        side: &'static str,
        /// The largest vertical approach the search allowed \[m\].
        max_approach_m: f64,
    },
    /// A contact patch could not be solved.
    #[error("{side} wheel, patch {patch}: {source}")]
    Contact {
        /// "left" or "right".
        side: &'static str,
        /// Patch index.
        patch: usize,
        /// Cause.
        #[source]
        source: crate::core::error::ContactError,
    },
    /// The caller cancelled the work before it finished (see
    /// [`crate::core::cancel`]).
    #[error("cancelled before it finished")]
    Cancelled,
}

/// Input errors of the core keep their key.
impl From<ContactError> for WheelRailError {
    fn from(e: ContactError) -> Self {
        match e {
            ContactError::InvalidInput { key, reason } => Self::Invalid {
                key,
                message: reason,
            },
            other => Self::invalid("input", other.to_string()),
        }
    }
}

impl WheelRailError {
    pub(crate) fn invalid(key: &str, message: impl Into<String>) -> Self {
        Self::Invalid {
            key: key.to_string(),
            message: message.into(),
        }
    }
}

/// One side of the track and wheelset.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Side {
    /// The left wheel and rail (y < 0).
    Left,
    /// The right wheel and rail (y > 0).
    Right,
}

impl Side {
    /// Both sides, left first.
    pub const BOTH: [Side; 2] = [Side::Left, Side::Right];

    /// +1 for the right side, -1 for the left side (q = sign y).
    pub fn sign(self) -> f64 {
        match self {
            Side::Left => -1.0,
            Side::Right => 1.0,
        }
    }

    /// "left" or "right".
    pub fn name(self) -> &'static str {
        match self {
            Side::Left => "left",
            Side::Right => "right",
        }
    }

    /// Index into per-side arrays (left 0, right 1).
    pub fn index(self) -> usize {
        match self {
            Side::Left => 0,
            Side::Right => 1,
        }
    }
}

/// Where the rail profiles sit on the track (both rails alike, each in its
/// side frame; see the module's frames).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RailPlacement {
    /// By the gauge (CONTACT's GAUGHT > 0): the inclined profile's highest
    /// point at z = 0 and its gauge face, `gauge_height_m` below that, at
    /// q = `gauge_m` / 2.
    GaugePoint {
        /// Track gauge between the gauge faces \[m\], > 0.
        gauge_m: f64,
        /// Depth below the top of the rail at which the gauge is measured
        /// \[m\], >= 0.
        gauge_height_m: f64,
    },
    /// Absolute (CONTACT's GAUGHT <= 0 with RAILY0, RAILZ0): the rail
    /// profile's origin at (q, z) = (`q_m`, `z_m`) of the side frame, the
    /// profile inclined by the cant about it and not shifted to touch
    /// z = 0. For a test rig or one wheel on one rail (a flat plane, a
    /// roller's profile), where there is no gauge face to measure.
    Origin {
        /// Lateral position of the origin \[m\], towards the field side
        /// (track y for the right rail, -y for the left; a case file's
        /// `track.rail_origin_y_m`).
        q_m: f64,
        /// Vertical position of the origin \[m\] (z down).
        z_m: f64,
    },
}

/// "gauge 1.435 m" or "rail origin at q = 0.2 m, z = 0 m".
impl std::fmt::Display for RailPlacement {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RailPlacement::GaugePoint { gauge_m, .. } => write!(f, "gauge {gauge_m} m"),
            RailPlacement::Origin { q_m, z_m } => {
                write!(f, "rail origin at q = {q_m} m, z = {z_m} m")
            }
        }
    }
}

/// A rail's deviation from its placement (CONTACT's rail irregularities
/// DYRAIL, DZRAIL, DROLLR), in the track frame: dy > 0 to the right
/// (towards the track centre for the left rail, to the field side for the
/// right one). Case files: `[track.rail_deviation_left]`, `_right`.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RailDeviation {
    /// Lateral shift of the rail profile's origin \[m\] (track y).
    pub dy_m: f64,
    /// Vertical shift \[m\] (z down).
    pub dz_m: f64,
    /// Rotation about the track's x axis, about the profile's origin
    /// \[rad\] (right-hand rule).
    pub droll_rad: f64,
}

/// Track data.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrackData {
    /// Where the rails sit.
    pub placement: RailPlacement,
    /// Rail inclination towards the track centre \[rad\] (1:40 is 0.025),
    /// applied to the rail profile as given; 0 for profiles already
    /// inclined, like `MBench_UIC60_v3.prr`.
    pub cant_rad: f64,
    /// Each rail's deviation from its placement (`[left, right]`, default
    /// none): the rail placed by `placement` and `cant_rad` (the gauge
    /// point found on the rail inclined by the cant alone), then turned by
    /// `droll_rad` about its profile's origin and shifted, as CONTACT's
    /// `wr_set_rail_marker` does.
    pub deviations: [RailDeviation; 2],
    /// A roller rig (CONTACT's C1 = 4, 5) instead of a track: the rail
    /// profiles lie on rollers of this nominal radius \[m\] whose axle runs
    /// along y at that distance below the track plane (z = radius), the
    /// profile's z an offset to it (see [`RailPlacement`]: the gauge point
    /// placement shifts such a rail laterally only). The roller's surface
    /// curves along x as well (radius `roller_radius_m - z` in the rail's
    /// profile frame, turned with a rail's deviation), which adds to the
    /// wheel's curvature in the gap of each patch (whose reference point,
    /// with yaw, moves to that gap's minimum along x, on the roller's
    /// surface), and the roller turns at
    /// [`RailMotion::roller_rad_per_s`](crate::wheelrail::RailMotion).
    /// No cant on a roller (`cant_rad` must be 0). `None`: a track.
    pub roller_radius_m: Option<f64>,
    /// Signed track curvature 1/R \[1/m\], positive in a right-hand
    /// curve (CONTACT's CURV): the track frame turns about z at the rolling
    /// speed times it, and the wheelset's yaw rate is relative to that
    /// turning frame. It enters the creepages only (the rails are
    /// prismatic), as a rotation of the rails about the track's z axis at
    /// -V k (V the forward speed; on a roller the roller's surface speed
    /// at the contact point), as CONTACT's `wr_creep_cref` does. 0: tangent
    /// track.
    pub curvature_per_m: f64,
}

/// Largest track curvature accepted \[1/m\] (a radius of 10 m).
pub const MAX_TRACK_CURVATURE_PER_M: f64 = 0.1;

/// Smallest distance between the rails taken as the roll search's scale
/// with [`RailPlacement::Origin`] \[m\] (see [`TrackData::rail_spacing_m`]).
const MIN_RAIL_SPACING_M: f64 = 0.1;

impl TrackData {
    /// Rails placed by the gauge point ([`RailPlacement::GaugePoint`]).
    pub const fn gauge_point(gauge_m: f64, gauge_height_m: f64, cant_rad: f64) -> Self {
        Self {
            placement: RailPlacement::GaugePoint {
                gauge_m,
                gauge_height_m,
            },
            cant_rad,
            deviations: [RailDeviation {
                dy_m: 0.0,
                dz_m: 0.0,
                droll_rad: 0.0,
            }; 2],
            roller_radius_m: None,
            curvature_per_m: 0.0,
        }
    }

    /// The distance between the rails that scales the roll search (the
    /// roll that levels both wheels changes their gap difference by about
    /// this much per radian) \[m\]: the gauge, or twice the origins' `q_m`
    /// (at least 0.1 m).
    pub fn rail_spacing_m(&self) -> f64 {
        match self.placement {
            RailPlacement::GaugePoint { gauge_m, .. } => gauge_m,
            RailPlacement::Origin { q_m, .. } => (2.0 * q_m.abs()).max(MIN_RAIL_SPACING_M),
        }
    }

    /// Checks the numbers, naming the field (`track.gauge_m`, ...).
    fn validate(&self) -> Result<(), WheelRailError> {
        match self.placement {
            RailPlacement::GaugePoint {
                gauge_m,
                gauge_height_m,
            } => {
                require_positive("track.gauge_m", gauge_m)?;
                require_finite("track.gauge_height_m", gauge_height_m)?;
                if gauge_height_m < 0.0 {
                    return Err(WheelRailError::invalid(
                        "track.gauge_height_m",
                        "must be >= 0 (a depth below the top of the rail)",
                    ));
                }
            }
            RailPlacement::Origin { q_m, z_m } => {
                require_finite("track.rail_origin_y_m", q_m)?;
                require_finite("track.rail_origin_z_m", z_m)?;
            }
        }
        require_finite("track.cant_rad", self.cant_rad)?;
        if let Some(r) = self.roller_radius_m {
            require_positive("track.roller_radius_m", r)?;
            if self.cant_rad != 0.0 {
                return Err(WheelRailError::invalid(
                    "track.cant_rad",
                    "a roller rig has no cant (CONTACT ignores it there): give 0 with \
                     track.roller_radius_m",
                ));
            }
        }
        require_finite("track.curvature_per_m", self.curvature_per_m)?;
        if self.curvature_per_m.abs() > MAX_TRACK_CURVATURE_PER_M {
            return Err(WheelRailError::invalid(
                "track.curvature_per_m",
                format!(
                    "{} 1/m is a curve radius below {} m",
                    self.curvature_per_m,
                    1.0 / MAX_TRACK_CURVATURE_PER_M
                ),
            ));
        }
        for d in &self.deviations {
            require_finite("track.rail_deviation.dy_m", d.dy_m)?;
            require_finite("track.rail_deviation.dz_m", d.dz_m)?;
            require_finite("track.rail_deviation.droll_rad", d.droll_rad)?;
        }
        if self.cant_rad.abs() > 0.2 {
            return Err(WheelRailError::invalid(
                "track.cant_rad",
                format!("{} rad is not a rail inclination", self.cant_rad),
            ));
        }
        Ok(())
    }
}

/// Wheelset data.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WheelsetData {
    /// Distance between the backs of the two flanges \[m\].
    pub flange_back_distance_m: f64,
    /// Rolling radius at the wheel profile's z = 0 \[m\].
    pub nominal_radius_m: f64,
    /// Profile y of the back of the flange \[m\]; `None` for the profile's
    /// smallest y.
    pub flange_back_y_m: Option<f64>,
}

/// Dense samples of a profile curve, in the side frame: point (q, z) and
/// outward unit normal (pointing away from the body's material).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurveSample {
    /// Arc length along the fitted profile \[m\].
    pub t_m: f64,
    /// Lateral coordinate \[m\].
    pub q_m: f64,
    /// Vertical coordinate, down \[m\].
    pub z_m: f64,
    /// Unit tangent in CONTACT point order (dq/dt, dz/dt).
    pub tangent: [f64; 2],
    /// Signed curvature of the fitted profile [1/m], positive where the
    /// body is convex (see [`crate::wheelrail::spline`], "Signs").
    pub curvature_per_m: f64,
}

impl CurveSample {
    /// The outward normal (away from the material) in (q, z): with the
    /// material on the right-hand side of the walking direction (see the
    /// profile conventions), (dz, -dq): up on a rail's crown, down on a
    /// wheel's tread.
    pub fn outward_normal(&self) -> [f64; 2] {
        [self.tangent[1], -self.tangent[0]]
    }
}

/// Spacing of the dense profile samples used by the contact search \[m\].
pub const SAMPLE_SPACING_M: f64 = 5.0e-5;

fn sample(spline: &ProfileSpline, map: impl Fn(f64, f64) -> [f64; 2]) -> Vec<CurveSample> {
    let len = spline.length_m();
    let n = (len / SAMPLE_SPACING_M).ceil().max(2.0) as usize;
    (0..=n)
        .map(|k| {
            let t = len * k as f64 / n as f64;
            let p = spline.eval(t);
            let [q, z] = map(p.y_m, p.z_m);
            let o = map(p.y_m + p.tangent[0], p.z_m + p.tangent[1]);
            let tan = [o[0] - q, o[1] - z];
            let norm = tan[0].hypot(tan[1]);
            CurveSample {
                t_m: t,
                q_m: q,
                z_m: z,
                tangent: [tan[0] / norm, tan[1] / norm],
                // `map` turns and shifts (the rail's cant): the curvature
                // is that of the profile.
                curvature_per_m: p.curvature_per_m,
            }
        })
        .collect()
}

/// A rail profile placed on the track (side frame).
#[derive(Debug, Clone)]
pub struct PlacedRail {
    spline: ProfileSpline,
    cant_rad: f64,
    /// Shift from the inclined profile to the side frame (q, z) [m].
    offset_m: [f64; 2],
    samples: Vec<CurveSample>,
    /// The surface on the search's lattice, which every contact search
    /// copies instead of sampling the rail again.
    surface: VerticalGap,
    /// [`TrackData::roller_radius_m`].
    roller_radius_m: Option<f64>,
    /// The samples' arc length where the profile's y is 0 \[m\]
    /// ([`Self::arc_at_profile_origin_m`]).
    arc_at_profile_origin_m: f64,
}

/// Its spline, samples and surface.
impl HeapBytes for PlacedRail {
    fn heap_bytes(&self) -> usize {
        heap_bytes!(self.spline, self.samples, self.surface)
    }
}

impl PlacedRail {
    /// Side-frame point (q, z) of a profile point (y, z).
    pub fn to_side(&self, y: f64, z: f64) -> [f64; 2] {
        let (s, c) = self.cant_rad.sin_cos();
        [
            c * y + s * z + self.offset_m[0],
            -s * y + c * z + self.offset_m[1],
        ]
    }

    /// Profile point (y, z) of a side-frame point (q, z).
    pub fn to_profile(&self, q: f64, z: f64) -> [f64; 2] {
        let (s, c) = self.cant_rad.sin_cos();
        let (a, b) = (q - self.offset_m[0], z - self.offset_m[1]);
        [c * a - s * b, s * a + c * b]
    }

    /// The rail's inclination in the side frame \[rad\]: the track's cant
    /// less the deviation's roll (towards the gauge side positive).
    pub fn inclination_rad(&self) -> f64 {
        self.cant_rad
    }

    /// Dense samples in the side frame, gauge face first.
    pub fn samples(&self) -> &[CurveSample] {
        &self.samples
    }

    /// The arc length of the samples \[m\] where the profile's y is 0
    /// (CONTACT's rail profile reference s_r = 0), interpolated between
    /// the samples on either side; the first sample's (0) where y does not
    /// pass 0.
    pub fn arc_at_profile_origin_m(&self) -> f64 {
        self.arc_at_profile_origin_m
    }

    /// The fitted profile (profile frame).
    pub fn spline(&self) -> &ProfileSpline {
        &self.spline
    }

    /// The surface height on the contact search's lattice (no wheel).
    pub fn surface(&self) -> &VerticalGap {
        &self.surface
    }

    /// The nominal radius of the roller this rail lies on \[m\] (None on a
    /// track; see [`TrackData::roller_radius_m`]).
    pub fn roller_radius_m(&self) -> Option<f64> {
        self.roller_radius_m
    }

    /// Where the roller's surface lies at `x_m` from its top, relative to
    /// its profile's point (q, z) (side frame) \[m\]: lower by x^2 / (2 r)
    /// along the profile frame's z (the roller's radius r, the nominal
    /// radius less the profile's z, turned with the rail). Zero on a
    /// track.
    pub fn roller_drop_m(&self, q_m: f64, z_m: f64, x_m: f64) -> [f64; 2] {
        let Some(radius) = self.roller_radius_m else {
            return [0.0, 0.0];
        };
        let r = radius - self.to_profile(q_m, z_m)[1];
        if r <= x_m.abs() {
            return [0.0, 0.0];
        }
        let drop = r - (r * r - x_m * x_m).sqrt();
        let (s, c) = self.cant_rad.sin_cos();
        [s * drop, c * drop]
    }

    /// Whether the rail is a roller (a roller rig's), not a track's rail.
    pub fn is_roller(&self) -> bool {
        self.roller_radius_m.is_some()
    }

    /// The profile curvature along x of a roller's surface at the rail
    /// sample `sample` \[1/m\]: cos(phi) / r, r the distance of
    /// the point from the roller's axle (the nominal radius less the
    /// profile's z, in the rail's profile frame) and phi the angle of the
    /// surface normal from that radius (the normal curvature of a body of
    /// revolution along its circle). 0 on a track.
    pub fn roller_curvature_per_m(&self, sample: &CurveSample) -> f64 {
        let Some(radius) = self.roller_radius_m else {
            return 0.0;
        };
        let [_, z] = self.to_profile(sample.q_m, sample.z_m);
        let [nq, nz] = sample.outward_normal();
        let (s, c) = self.cant_rad.sin_cos();
        // The normal in the profile frame (to_profile without the shift);
        // the radius points up, -z.
        let cos_phi = -(s * nq + c * nz);
        let r = radius - z;
        if r > 0.0 {
            cos_phi / r
        } else {
            0.0
        }
    }
}

/// A wheel profile placed on the axle.
#[derive(Debug, Clone)]
pub struct PlacedWheel {
    spline: ProfileSpline,
    /// Axial coordinate (from the wheelset centre, outwards) of profile y = 0 [m].
    axial_offset_m: f64,
    /// Dense samples in the profile frame (q = profile y), field face first.
    samples: Vec<CurveSample>,
    /// Their locus points' pose-independent parts on a wheelset of
    /// `locus_radius_m`.
    locus_samples: Vec<LocusSample>,
    locus_radius_m: f64,
    /// An out-of-round wheel ([`WheelRailPair::with_wheel_slices`]).
    slices: Option<WheelSlicesAt>,
}

/// An out-of-round wheel on the pair: its slices and the wheelset's pitch
/// angle, whose slice facing the rail (theta = -pitch) is the pair's
/// wheel profile.
#[derive(Debug, Clone)]
pub struct WheelSlicesAt {
    /// The wheel's slices.
    pub slices: Arc<WheelSlices>,
    /// The wheelset's pitch angle \[rad\] (CONTACT's PITCH, theta_ws; see
    /// [`WheelSlices`] for the convention).
    pub pitch_rad: f64,
    /// The points of the profile the pair's wheel was placed from,
    /// [`WheelSlices::facing_rail_points`] (profile frame, unsmoothed).
    pub facing_points: Vec<[f64; 2]>,
}

/// Its spline and samples.
impl HeapBytes for PlacedWheel {
    fn heap_bytes(&self) -> usize {
        heap_bytes!(self.spline, self.samples, self.locus_samples)
    }
}

impl PlacedWheel {
    /// Axial coordinate of profile y = 0 \[m\] (the tape circle for S1002).
    pub fn axial_offset_m(&self) -> f64 {
        self.axial_offset_m
    }

    /// Dense samples in the profile frame.
    pub fn samples(&self) -> &[CurveSample] {
        &self.samples
    }

    /// The fitted profile.
    pub fn spline(&self) -> &ProfileSpline {
        &self.spline
    }

    /// The pose-independent parts of the samples' locus points
    /// ([`LocusFrame::point`](crate::wheelrail::search::LocusFrame::point)),
    /// one per sample, on a wheelset of `nominal_radius_m` (None on
    /// another than the one the wheel was placed for).
    /// The out-of-round wheel's slices and pitch, if any.
    pub fn slices(&self) -> Option<&WheelSlicesAt> {
        self.slices.as_ref()
    }

    pub(crate) fn locus_samples(&self, nominal_radius_m: f64) -> Option<&[LocusSample]> {
        (nominal_radius_m.to_bits() == self.locus_radius_m.to_bits())
            .then_some(&self.locus_samples[..])
    }
}

/// The prepared geometry of a track and wheelset: both rails and wheels
/// placed, fitted and sampled. Costly to build (a few ms), cheap to use; the
/// service keeps one per profile pair.
#[derive(Debug, Clone)]
pub struct WheelRailPair {
    rails: [PlacedRail; 2],
    wheels: [PlacedWheel; 2],
    track: TrackData,
    wheelset: WheelsetData,
    /// Whether the two sides are mirror images ([`Self::sides_alike`]).
    sides_alike: bool,
}

/// The placed profiles: what a registered pair keeps in memory (1.1 MB
/// for the Manchester benchmark's profiles, growing with the points).
impl HeapBytes for WheelRailPair {
    fn heap_bytes(&self) -> usize {
        heap_bytes!(self.rails, self.wheels)
    }
}

impl WheelRailPair {
    /// Places the profiles (`[left, right]`, both in the right-hand profile
    /// convention) with the smoothing `spline` options.
    pub fn new(
        rails: [&Profile; 2],
        wheels: [&Profile; 2],
        track: TrackData,
        wheelset: WheelsetData,
        spline: &SplineOptions,
    ) -> Result<Self, WheelRailError> {
        track.validate()?;
        require_positive(
            "wheelset.flange_back_distance_m",
            wheelset.flange_back_distance_m,
        )?;
        require_positive("wheelset.nominal_radius_m", wheelset.nominal_radius_m)?;
        if let Some(y) = wheelset.flange_back_y_m {
            require_finite("wheelset.flange_back_y_m", y)?;
        }
        // A wheel file as the rail, or a rail file as the wheel (by their
        // extension or content; plain files have no kind): said at once.
        for (profiles, key, wrong, right) in [
            (
                rails,
                "track.rail_profile",
                ProfileKind::Wheel,
                "a rail's (.prr, .ban)",
            ),
            (
                wheels,
                "wheelset.wheel_profile",
                ProfileKind::Rail,
                "a wheel's (.prw, .whl)",
            ),
        ] {
            if let Some(p) = profiles.iter().find(|p| p.kind() == Some(wrong)) {
                return Err(WheelRailError::invalid(
                    key,
                    format!(
                        "'{}' is a {} profile (by its extension or content): give {right}",
                        p.name(),
                        if wrong == ProfileKind::Wheel {
                            "wheel"
                        } else {
                            "rail"
                        }
                    ),
                ));
            }
        }
        let place = |side: Side| -> Result<(PlacedRail, PlacedWheel), WheelRailError> {
            let i = side.index();
            let rail = place_rail(rails[i], &track, spline, side)?;
            let wheel = place_wheel(wheels[i], &wheelset, spline, side)?;
            Ok((rail, wheel))
        };
        let (rl, wl) = place(Side::Left)?;
        let (rr, wr) = place(Side::Right)?;
        let sides_alike = rl.samples == rr.samples
            && rl.cant_rad == rr.cant_rad
            && rl.offset_m == rr.offset_m
            && rl.roller_radius_m() == rr.roller_radius_m()
            && wl.samples == wr.samples
            && wl.axial_offset_m == wr.axial_offset_m;
        Ok(Self {
            rails: [rl, rr],
            wheels: [wl, wr],
            track,
            wheelset,
            sides_alike,
        })
    }

    /// The pair with the wheel of `side` out of round: `slices` at the
    /// wheelset's pitch angle `pitch_rad` (CONTACT's PITCH; see
    /// [`WheelSlices`]). The placed wheel of that side must be the slices'
    /// profile facing the rail, [`WheelSlices::profile_facing_rail`] at
    /// this pitch and the wheelset's nominal radius (the caller places it,
    /// smoothed or not: the contact search and each patch's geometry use
    /// it as a round wheel's profile); each element (x, s) of a patch's
    /// grid (exact model) then sees the true wheel: the change of radius
    /// between that profile and the wheel's cross-section at its own angle
    /// -pitch + asin(x / r), along the patch's normal (a wheel flat
    /// changes over a patch's length), and the grid reaches along x as far
    /// as the true wheel comes within the patch's reach of the rail.
    pub fn with_wheel_slices(
        mut self,
        side: Side,
        slices: Arc<WheelSlices>,
        pitch_rad: f64,
    ) -> Result<Self, WheelRailError> {
        require_finite("position.pitch_rad", pitch_rad)?;
        let facing_points = slices.facing_rail_points(pitch_rad, self.wheelset.nominal_radius_m);
        self.wheels[side.index()].slices = Some(WheelSlicesAt {
            slices,
            pitch_rad,
            facing_points,
        });
        self.sides_alike = false;
        Ok(self)
    }

    /// Whether the two sides are mirror images: the same rail and wheel
    /// samples in their side frames (the same profiles, cant, placement and
    /// rollers) and no out-of-round wheel; a contact state of one wheel is
    /// then the other's mirrored.
    pub fn sides_alike(&self) -> bool {
        self.sides_alike
    }

    /// The placed rail of `side`.
    pub fn rail(&self, side: Side) -> &PlacedRail {
        &self.rails[side.index()]
    }

    /// The placed wheel of `side`.
    pub fn wheel(&self, side: Side) -> &PlacedWheel {
        &self.wheels[side.index()]
    }

    /// Track data.
    pub fn track(&self) -> &TrackData {
        &self.track
    }

    /// Wheelset data.
    pub fn wheelset(&self) -> &WheelsetData {
        &self.wheelset
    }
}

fn fit(
    profile: &Profile,
    options: &SplineOptions,
    side: Side,
    what: &'static str,
) -> Result<ProfileSpline, WheelRailError> {
    profile
        .spline(options)
        .map_err(|source| WheelRailError::Spline {
            side: side.name(),
            what,
            source,
        })
}

fn place_rail(
    profile: &Profile,
    track: &TrackData,
    options: &SplineOptions,
    side: Side,
) -> Result<PlacedRail, WheelRailError> {
    let spline = fit(profile, options, side, "rail")?;
    let mut rail = PlacedRail {
        spline,
        cant_rad: track.cant_rad,
        offset_m: [0.0, 0.0],
        samples: Vec::new(),
        surface: VerticalGap::default(),
        roller_radius_m: track.roller_radius_m,
        arc_at_profile_origin_m: 0.0,
    };
    let [q, z] = match track.placement {
        RailPlacement::GaugePoint {
            gauge_m,
            gauge_height_m,
        } => {
            let [q, z] = gauge_point_offset(&rail, profile.name(), gauge_m, gauge_height_m, side)?;
            // On a roller the gauge places the rail laterally only: its
            // profile's z = 0 lies at the nominal radius (CONTACT's
            // `wr_set_rail_marker`, user guide on NOMRADR).
            [
                q,
                if track.roller_radius_m.is_some() {
                    0.0
                } else {
                    z
                },
            ]
        }
        RailPlacement::Origin { q_m, z_m } => [q_m, z_m],
    };
    // The deviation in the side frame: q = s y, a roll about x turns by s
    // droll (a rotation of -cant_rad inclines the rail).
    let d = track.deviations[side.index()];
    let s = side.sign();
    rail.offset_m = [q + s * d.dy_m, z + d.dz_m];
    rail.cant_rad = track.cant_rad - s * d.droll_rad;
    rail.samples = sample(&rail.spline, |y, z| rail.to_side(y, z));
    rail.surface = VerticalGap::surface_of(&rail.samples);
    let y = |c: &CurveSample| rail.to_profile(c.q_m, c.z_m)[0];
    rail.arc_at_profile_origin_m = (rail.samples.windows(2))
        .find_map(|w| {
            let (ya, yb) = (y(&w[0]), y(&w[1]));
            ((ya <= 0.0) != (yb <= 0.0)).then(|| w[0].t_m + ya / (ya - yb) * (w[1].t_m - w[0].t_m))
        })
        .unwrap_or(0.0);
    Ok(rail)
}

/// The shift (q, z) of the inclined profile of `rail` (offset still zero)
/// that puts its highest point at z = 0 and its gauge face at q = gauge/2.
fn gauge_point_offset(
    rail: &PlacedRail,
    name: &str,
    gauge_m: f64,
    gauge_height_m: f64,
    side: Side,
) -> Result<[f64; 2], WheelRailError> {
    let inclined = sample(&rail.spline, |y, z| rail.to_side(y, z));
    let top = inclined.iter().map(|s| s.z_m).fold(f64::INFINITY, f64::min);
    // Gauge face: the first point, walking from the gauge side (CONTACT
    // order for rails), that rises to the gauge height.
    let level = top + gauge_height_m;
    let gauge_q = inclined
        .windows(2)
        .find(|w| w[0].z_m > level && w[1].z_m <= level)
        .map(|w| {
            let f = (w[0].z_m - level) / (w[0].z_m - w[1].z_m);
            w[0].q_m + f * (w[1].q_m - w[0].q_m)
        })
        .ok_or_else(|| WheelRailError::Geometry {
            side: side.name(),
            message: format!(
                "the rail profile '{name}' does not reach {:.1} mm below its top on the gauge side, \
                 where the gauge is measured (track.gauge_height_m){}",
                gauge_height_m * 1e3,
                rail_hint(&inclined, level)
            ),
        })?;
    Ok([0.5 * gauge_m - gauge_q, -top])
}

/// The likely cause of a rail profile without a gauge face at the gauge
/// height (`level`, in the side frame of the samples `inclined`): a rail
/// whose gauge face is on its +y side (a MiniProf rail measured from the
/// gauge side, not mirrored).
fn rail_hint(inclined: &[CurveSample], level: f64) -> String {
    let field_side_reaches = inclined
        .windows(2)
        .rev()
        .any(|w| w[1].z_m > level && w[0].z_m <= level);
    if field_side_reaches {
        "; it reaches that depth on its +y side instead: its gauge face is at +y, as in a \
         MiniProf rail measured from the gauge side; mirror it in y (case files: \
         `track.rail_mirror_y = true`; the wire: the rail source's `mirror_y`)"
            .to_string()
    } else {
        String::new()
    }
}

fn place_wheel(
    profile: &Profile,
    ws: &WheelsetData,
    options: &SplineOptions,
    side: Side,
) -> Result<PlacedWheel, WheelRailError> {
    let spline = fit(profile, options, side, "wheel")?;
    let back = ws.flange_back_y_m.unwrap_or_else(|| profile.y_range_m().0);
    let (lo, hi) = profile.y_range_m();
    if back < lo - 1e-3 || back > hi {
        return Err(WheelRailError::invalid(
            "wheelset.flange_back_y_m",
            format!(
                "{back} m lies outside the wheel profile '{}' (y from {lo} to {hi} m)",
                profile.name()
            ),
        ));
    }
    let z_max = profile.z_range_m().1;
    if ws.nominal_radius_m + z_max <= 0.0 || ws.nominal_radius_m + profile.z_range_m().0 <= 0.0 {
        return Err(WheelRailError::invalid(
            "wheelset.nominal_radius_m",
            "gives a negative rolling radius on the wheel profile",
        ));
    }
    let samples = sample(&spline, |y, z| [y, z]);
    let axial_offset_m = 0.5 * ws.flange_back_distance_m - back;
    let locus_samples = samples
        .iter()
        .map(|s| LocusSample::of(s, axial_offset_m, ws.nominal_radius_m))
        .collect();
    Ok(PlacedWheel {
        spline,
        axial_offset_m,
        samples,
        locus_samples,
        locus_radius_m: ws.nominal_radius_m,
        slices: None,
    })
}

/// Wheelset position relative to the track (see the module conventions).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WheelsetPosition {
    /// Lateral displacement of the centre \[m\].
    pub lateral_m: f64,
    /// Yaw angle \[rad\].
    pub yaw_rad: f64,
    /// Roll angle \[rad\]; `None` to find it from the profiles (both wheels
    /// touching their rails).
    pub roll_rad: Option<f64>,
    /// Position of the wheelset along the track \[m\]: where a friction
    /// table along the track is read ([`crate::wheelrail::FrictionTable`]);
    /// nothing else depends on it (default 0).
    pub track_s_m: f64,
}

/// Wheelset velocity (see the module conventions).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WheelsetVelocity {
    /// Forward speed V [m/s]: > 0 rolling along the track's +x, < 0
    /// rolling backwards (see "Rolling backwards" in
    /// [`crate::wheelrail::contact`]), not 0.
    pub forward_m_per_s: f64,
    /// Lateral speed [m/s].
    pub lateral_m_per_s: f64,
    /// Vertical speed [m/s].
    pub vertical_m_per_s: f64,
    /// Roll rate [rad/s].
    pub roll_rad_per_s: f64,
    /// Yaw rate [rad/s].
    pub yaw_rad_per_s: f64,
    /// Rotation rate about the axle [rad/s]; `None` for free rolling at the
    /// nominal radius (-V / nominal radius).
    pub pitch_rad_per_s: Option<f64>,
}

impl WheelsetVelocity {
    /// Rolling at `forward_m_per_s` with free rolling at the nominal radius.
    pub fn rolling(forward_m_per_s: f64) -> Self {
        Self {
            forward_m_per_s,
            lateral_m_per_s: 0.0,
            vertical_m_per_s: 0.0,
            roll_rad_per_s: 0.0,
            yaw_rad_per_s: 0.0,
            pitch_rad_per_s: None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::wheelrail::builtin::{self, MBENCH_TRACK, MBENCH_WHEELSET};
    use crate::wheelrail::parse_profile;

    /// The built-in rail and wheel.
    fn mbench_profiles() -> (Profile, Profile) {
        let load = |name| {
            builtin::profile(name, &Default::default())
                .unwrap()
                .unwrap()
        };
        (load("MBench_UIC60_v3.prr"), load("MBench_S1002_v3.prw"))
    }

    /// `rail` on both sides of `track` under the built-in wheels.
    fn placed(rail: &Profile, track: TrackData) -> Result<WheelRailPair, WheelRailError> {
        let (_, wheel) = mbench_profiles();
        WheelRailPair::new(
            [rail, rail],
            [&wheel, &wheel],
            track,
            MBENCH_WHEELSET,
            &SplineOptions::default(),
        )
    }

    /// The absolute placement puts the profile's origin where it is told,
    /// inclined by the cant about it: a plane rail at (0.2, 0.5e-3) with
    /// a cant of 0.05 rad has its origin there and its surface sloping by
    /// the cant (z = z0 - tan(0.05) (q - q0) seen from the side frame).
    #[test]
    fn an_origin_placement_puts_the_profile_origin_there() {
        let text = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/profiles/flat_plane.prr"
        ))
        .unwrap();
        let plane = parse_profile(&text, "flat_plane.prr", &Default::default()).unwrap();
        assert_eq!(plane.points()[0][0], -0.05);
        let track = TrackData {
            placement: RailPlacement::Origin {
                q_m: 0.2,
                z_m: 0.5e-3,
            },
            cant_rad: 0.05,
            deviations: Default::default(),
            roller_radius_m: None,
            curvature_per_m: 0.0,
        };
        let pair = placed(&plane, track).unwrap();
        for side in Side::BOTH {
            let rail = pair.rail(side);
            let [q, z] = rail.to_side(0.0, 0.0);
            assert!((q - 0.2).abs() < 1e-15 && (z - 0.5e-3).abs() < 1e-15);
            for s in rail.samples() {
                let slope = -(0.05f64).tan() * (s.q_m - 0.2);
                assert!((s.z_m - 0.5e-3 - slope).abs() < 1e-12, "{s:?}");
            }
        }
        // The roll search's scale: twice the origin's q.
        assert_eq!(track.rail_spacing_m(), 0.4);
    }

    /// The gauge point placement is an origin placement at the origin it
    /// finds: placed there absolutely, the rail is the same bit for bit.
    #[test]
    fn the_gauge_point_placement_is_an_origin_placement() {
        let (rail, _) = mbench_profiles();
        let by_gauge = placed(&rail, MBENCH_TRACK).unwrap();
        let [q_m, z_m] = by_gauge.rail(Side::Right).offset_m;
        let origin = TrackData {
            placement: RailPlacement::Origin { q_m, z_m },
            cant_rad: MBENCH_TRACK.cant_rad,
            deviations: Default::default(),
            roller_radius_m: None,
            curvature_per_m: 0.0,
        };
        let by_origin = placed(&rail, origin).unwrap();
        for side in Side::BOTH {
            assert_eq!(
                by_gauge.rail(side).samples(),
                by_origin.rail(side).samples()
            );
        }
    }

    /// A non-finite origin is refused naming the case file's key.
    #[test]
    fn a_bad_origin_is_refused_naming_its_key() {
        let (rail, _) = mbench_profiles();
        let track = TrackData {
            placement: RailPlacement::Origin {
                q_m: f64::NAN,
                z_m: 0.0,
            },
            cant_rad: 0.0,
            deviations: Default::default(),
            roller_radius_m: None,
            curvature_per_m: 0.0,
        };
        let e = placed(&rail, track).unwrap_err();
        assert!(e.to_string().contains("track.rail_origin_y_m"), "{e}");
    }
}
