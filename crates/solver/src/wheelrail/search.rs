//! Contact search: where the wheel's surface comes closest to the rail, the
//! rigid position of the wheelset, and the contact patches with their local
//! geometry.
//!
//! Method (the contact-locus approach, as in CONTACT's wheel/rail module,
//! Vollebregt, VSD 2020, doi 10.1080/00423114.2020.1853180):
//!
//! 1. **Contact locus.** The rail is a prismatic body, so at a contact point
//!    its normal lies in the (q, z) plane. On every circle of the wheel (one
//!    per profile point) the point where the wheel's normal also lies in
//!    that plane is the only candidate; with yaw it lies ahead of or behind
//!    the axle (x != 0). These points form the locus curve, which is
//!    compared with the rail profile in the (q, z) plane.
//! 2. **Vertical gap.** g(q) = z_rail(q) - z_locus(q), sampled every
//!    [`SAMPLE_SPACING_M`]; the wheelset height (and roll, when not given)
//!    puts the smallest gap of each wheel at 0 (rigid contact).
//! 3. **Patches.** The parts of the q axis where g is below a cap (the
//!    expected approach with a margin) are the potential contact areas;
//!    parts closer than `merge_distance_m` (in x, q and height, as CONTACT
//!    measures it) are combined, parts farther apart are separate patches
//!    (tread, flange root, flange).
//! 4. **Patch geometry.** Per patch: the reference point where g is
//!    smallest (between the samples: the vertex of a parabola), the contact
//!    angle there (angle of the rail normal from the vertical, positive
//!    where the rail surface faces the gauge side, i.e. flange contact),
//!    the tangent plane, and the undeformed distance measured along the
//!    reference normal between rail and locus at lateral coordinates s in
//!    the tangent plane, with the wheel moved vertically into touch at the
//!    reference, plus the wheel's normal curvature along x:
//!    h(x, s) = h(s) + k_x(s) (x - dx(s))^2 / 2 (planar contact approach; k_x from the
//!    circle's and the profile's curvatures, see [`LocusFrame::point`]).
//!    With [`ReferencePoint::InterpenetrationCentre`]
//!    ([`SearchSettings::reference_point`]) the reference point is instead
//!    CONTACT's, the weighted centre of the interpenetration at the
//!    approach that carries the load, with the weighted mean contact angle
//!    ([`interpenetration_centre`], [`patch_geometry_about`]), and the
//!    wheel is sampled where that approach puts it, overlapping the rail,
//!    as CONTACT takes its undeformed distance. The exact model's grids
//!    take the wheel's part of h(x, s) from its surface of revolution
//!    itself (`WheelSurface`) rather than from the parabola along x.

use crate::core::memory::{heap_bytes, HeapBytes};
use crate::core::solve::ContactSolver;
use crate::wheelrail::wheelset::{
    CurveSample, PlacedRail, PlacedWheel, Side, WheelRailError, WheelRailPair, WheelsetPosition,
    SAMPLE_SPACING_M,
};

/// The wheelset seen from one side (side frame, see
/// [`crate::wheelrail::wheelset`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SidePose {
    /// Lateral position of the wheelset centre in the side frame \[m\].
    pub center_q_m: f64,
    /// Height of the wheelset centre \[m\] (z down, so negative).
    pub center_z_m: f64,
    /// Yaw angle in the side frame \[rad\].
    pub yaw_rad: f64,
    /// Roll angle in the side frame \[rad\].
    pub roll_rad: f64,
}

impl SidePose {
    /// The pose of `side` for the wheelset at track position (y, z, roll, yaw).
    pub fn new(side: Side, lateral_m: f64, center_z_m: f64, roll_rad: f64, yaw_rad: f64) -> Self {
        let s = side.sign();
        Self {
            center_q_m: s * lateral_m,
            center_z_m,
            yaw_rad: s * yaw_rad,
            roll_rad: s * roll_rad,
        }
    }

    /// Axle direction (x, q, z), outwards for this side's wheel.
    pub fn axle(&self) -> [f64; 3] {
        let (sy, cy) = self.yaw_rad.sin_cos();
        let (sr, cr) = self.roll_rad.sin_cos();
        [-sy * cr, cy * cr, sr]
    }

    /// Wheelset centre (x, q, z).
    pub fn center(&self) -> [f64; 3] {
        [0.0, self.center_q_m, self.center_z_m]
    }
}

/// One point of the contact locus (side frame).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LocusPoint {
    /// Longitudinal position \[m\] (ahead of the axle when > 0).
    pub x_m: f64,
    /// Lateral position \[m\].
    pub q_m: f64,
    /// Height \[m\].
    pub z_m: f64,
    /// Normal curvature of the wheel surface along x [1/m] (see
    /// [`LocusFrame::point`]): its circle's, cos(angle)/r, without yaw.
    pub kx_per_m: f64,
    /// Rolling radius \[m\].
    pub radius_m: f64,
    /// Wheel profile y of the point \[m\].
    pub profile_y_m: f64,
    /// Distance along the point's circle about the axle from the circle's
    /// lowest point (direction e1) \[m\], positive ahead: nonzero with yaw
    /// (the lead of the contact point, about r tan(delta) tan(psi) on a
    /// cone of contact angle delta).
    pub lead_m: f64,
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Largest tilt of the locus point round the wheel [rad]; beyond it the
/// wheel surface is nearly parallel to the axle (flange back) and cannot
/// touch a rail.
const MAX_LOCUS_ANGLE_RAD: f64 = 0.5;

/// The contact-locus construction of one wheel in one pose: the locus
/// point of any profile sample (see [`wheel_locus`]).
#[derive(Debug, Clone, Copy)]
pub struct LocusFrame {
    axle: [f64; 3],
    center: [f64; 3],
    e1: [f64; 3],
    e2: [f64; 3],
    rm: f64,
    /// 1 / rm (0 where rm is).
    inv_rm: f64,
    /// cos and sin of theta0, the angle round the axle of the direction
    /// whose x part is largest.
    cos_theta0: f64,
    sin_theta0: f64,
    axial_offset_m: f64,
    nominal_radius_m: f64,
}

impl LocusFrame {
    /// The frame of `wheel` in `pose`.
    pub fn new(wheel: &PlacedWheel, nominal_radius_m: f64, pose: &SidePose) -> Self {
        Self::with_offset(wheel.axial_offset_m(), nominal_radius_m, pose)
    }

    /// The frame of a wheel whose profile y = 0 lies `axial_offset_m`
    /// \[m\] from the wheelset centre along the axle.
    fn with_offset(axial_offset_m: f64, nominal_radius_m: f64, pose: &SidePose) -> Self {
        let a = pose.axle();
        // e1: "down" perpendicular to the axle; e2 = a x e1 (about +x).
        let mut e1 = [-a[2] * a[0], -a[2] * a[1], 1.0 - a[2] * a[2]];
        let n1 = (e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]).sqrt();
        e1.iter_mut().for_each(|v| *v /= n1);
        let e2 = cross(a, e1);
        let (ca, cb) = (e1[0], e2[0]);
        let rm = ca.hypot(cb);
        let (cos_theta0, sin_theta0) = if rm > 0.0 {
            (ca / rm, cb / rm)
        } else {
            (1.0, 0.0)
        };
        Self {
            axle: a,
            center: pose.center(),
            e1,
            e2,
            rm,
            inv_rm: if rm > 0.0 { 1.0 / rm } else { 0.0 },
            cos_theta0,
            sin_theta0,
            axial_offset_m,
            nominal_radius_m,
        }
    }

    /// The locus point of the wheel profile sample `s` (profile frame).
    ///
    /// Its `kx_per_m` is the wheel's normal curvature along x, Euler's
    /// k_c cos²(theta) + k_p sin²(theta): the parallel circle and the
    /// profile are the principal directions of a body of revolution, with
    /// normal curvatures k_c = -ty/r (Meusnier's, the circle's 1/r times
    /// the cosine between its plane and the normal) and k_p the profile's
    /// curvature, and theta is the angle in the tangent plane between the
    /// circle and x. Without yaw the locus point is the lowest point of
    /// its circle, whose tangent is x (theta = 0); with yaw psi (and no
    /// roll) cos(theta) = cos(psi) cos(phi), phi = asin(sigma/r) the
    /// point's angle round its circle from the lowest point (sigma its
    /// lead). On a flange of 13 mm profile radius at 1.15 rad contact
    /// angle and 15.6 mrad of yaw, k_p sin²(theta) is 0.111 1/m beside
    /// k_c = 0.859 1/m: the test of a yawed torus in
    /// [`crate::conformal::geometry`] finds the true undeformed distance
    /// along x at fixed s with this curvature.
    pub fn point(&self, s: &CurveSample) -> LocusPoint {
        self.point_of(&LocusSample::of(
            s,
            self.axial_offset_m,
            self.nominal_radius_m,
        ))
    }

    /// [`LocusFrame::point`] of a sample's pose-independent part (the same
    /// bits).
    pub(crate) fn point_of(&self, s: &LocusSample) -> LocusPoint {
        let (a, c, e1, e2, rm) = (self.axle, self.center, self.e1, self.e2, self.rm);
        let limit = MAX_LOCUS_ANGLE_RAD.sin();
        // The outward wheel normal tz a - ty e_r(theta) (profile y along
        // the axle, z along e_r) has no x part:
        // ty (A cos theta + B sin theta) = ty rm cos(theta - theta0) = tz a_x,
        // so theta = theta0 -+ d with cos d = tz a_x / (ty rm); of the
        // two, the one with the larger cos theta (the lower point). No
        // trigonometric function is evaluated: with (cos d, sin d) the
        // angle sums give cos theta and sin theta directly.
        let rhs = (s.slope * a[0]).clamp(-limit * rm, limit * rm);
        let cd = if rm > 0.0 {
            (rhs * self.inv_rm).clamp(-1.0, 1.0)
        } else {
            0.0
        };
        let sd = (1.0 - cd * cd).max(0.0).sqrt();
        let (c0, s0) = (self.cos_theta0, self.sin_theta0);
        // cos(theta0 - d) - cos(theta0 + d) = 2 sin(theta0) sin(d) >= 0
        // picks theta0 - d (also on a tie).
        let sd = if s0 >= 0.0 { -sd } else { sd };
        let (ct, st) = (c0 * cd - s0 * sd, s0 * cd + c0 * sd);
        let er = [
            ct * e1[0] + st * e2[0],
            ct * e1[1] + st * e2[1],
            ct * e1[2] + st * e2[2],
        ];
        let (u, r) = (s.axial_m, s.radius_m);
        // sin²(theta): the circle's unit tangent a x e_r has (1, 0, 0)
        // without yaw, exactly (a_x = e_r,x = 0), and then k_x is k_c bit
        // for bit.
        let tc = cross(a, er);
        let sin2 = tc[1] * tc[1] + tc[2] * tc[2];
        LocusPoint {
            x_m: c[0] + u * a[0] + r * er[0],
            q_m: c[1] + u * a[1] + r * er[1],
            z_m: c[2] + u * a[2] + r * er[2],
            kx_per_m: s.circle_curvature_per_m
                + (s.curvature_per_m - s.circle_curvature_per_m) * sin2,
            radius_m: r,
            profile_y_m: s.profile_y_m,
            lead_m: r * st,
        }
    }
}

/// The part of a wheel profile sample's locus point that does not depend
/// on the pose, computed once per sample when the wheel is placed
/// ([`PlacedWheel::locus_samples`]): a locus point then takes no division.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LocusSample {
    /// tz / ty of the sample's unit tangent (0 where ty is 0 to 1e-12).
    slope: f64,
    /// Axial coordinate from the wheelset centre \[m\].
    axial_m: f64,
    /// Radius of its circle \[m\].
    radius_m: f64,
    /// The circle's normal curvature, -ty / r \[1/m\].
    circle_curvature_per_m: f64,
    /// The profile's curvature \[1/m\].
    curvature_per_m: f64,
    /// Profile y \[m\].
    profile_y_m: f64,
}

impl LocusSample {
    /// The sample `s` of a wheel whose profile y = 0 lies `axial_offset_m`
    /// from the wheelset centre, on a wheelset of `nominal_radius_m`.
    pub(crate) fn of(s: &CurveSample, axial_offset_m: f64, nominal_radius_m: f64) -> Self {
        let [ty, tz] = s.tangent;
        let radius_m = nominal_radius_m + s.z_m;
        Self {
            slope: if ty.abs() > 1e-12 { tz / ty } else { 0.0 },
            axial_m: axial_offset_m + s.q_m,
            radius_m,
            circle_curvature_per_m: -ty / radius_m,
            curvature_per_m: s.curvature_per_m,
            profile_y_m: s.q_m,
        }
    }
}

/// Computes the contact locus of `wheel` in `pose` into `out`.
pub fn wheel_locus(
    wheel: &PlacedWheel,
    nominal_radius_m: f64,
    pose: &SidePose,
    out: &mut Vec<LocusPoint>,
) {
    out.clear();
    locus_part(wheel, nominal_radius_m, pose, 0..wheel.samples().len(), out);
}

/// Appends to `out` the locus points of `wheel`'s dense samples `part` in
/// `pose`.
fn locus_part(
    wheel: &PlacedWheel,
    nominal_radius_m: f64,
    pose: &SidePose,
    part: std::ops::Range<usize>,
    out: &mut Vec<LocusPoint>,
) {
    let frame = LocusFrame::new(wheel, nominal_radius_m, pose);
    match wheel.locus_samples(nominal_radius_m) {
        Some(pre) => out.extend(pre[part].iter().map(|s| frame.point_of(s))),
        None => out.extend(wheel.samples()[part].iter().map(|s| frame.point(s))),
    }
}

/// The vertical gap of one side, sampled in q on the lattice q = k
/// [`SAMPLE_SPACING_M`] (integer k), so that samples of different ranges
/// at the same q have the same bits.
#[derive(Debug, Clone, Default)]
pub struct VerticalGap {
    /// First q \[m\] and spacing \[m\].
    pub q0_m: f64,
    /// Spacing \[m\].
    pub dq_m: f64,
    /// Rail surface height per sample \[m\] (NaN where no rail).
    pub z_rail_m: Vec<f64>,
    /// Locus height per sample \[m\] (NaN where no wheel).
    pub z_wheel_m: Vec<f64>,
    /// Index of the locus point nearest below each sample.
    pub locus_index: Vec<usize>,
    /// Lattice index of the first sample: q0 = k0 dq.
    k0: i64,
}

impl VerticalGap {
    /// Number of samples.
    pub fn len(&self) -> usize {
        self.z_rail_m.len()
    }

    /// True when empty.
    pub fn is_empty(&self) -> bool {
        self.z_rail_m.is_empty()
    }

    /// q of sample k \[m\].
    pub fn q_m(&self, k: usize) -> f64 {
        (self.k0 + k as i64) as f64 * self.dq_m
    }

    /// Gap at sample k \[m\] (+inf where either body is missing).
    pub fn gap_m(&self, k: usize) -> f64 {
        let g = self.z_rail_m[k] - self.z_wheel_m[k];
        if g.is_nan() {
            f64::INFINITY
        } else {
            g
        }
    }

    /// Index and value of the smallest gap.
    pub fn min(&self) -> Option<(usize, f64)> {
        (0..self.len())
            .map(|k| (k, self.gap_m(k)))
            .filter(|(_, g)| g.is_finite())
            .min_by(|a, b| a.1.total_cmp(&b.1))
    }

    /// Fills the gap between `rail` and `locus` (the rail's heights copied
    /// from its surface, [`PlacedRail::surface`]).
    pub fn compute(&mut self, rail: &PlacedRail, locus: &[LocusPoint]) {
        let surface = rail.surface();
        let (wlo, whi) = range(locus.iter().map(|p| p.q_m));
        let last = surface.k0.saturating_add(surface.len() as i64 - 1);
        self.set_lattice(
            surface.k0.max(lattice_ceil(wlo)),
            last.min(lattice_floor(whi)),
        );
        let from = self.k0.saturating_sub(surface.k0).max(0) as usize;
        let n = self.len();
        if n > 0 {
            self.z_rail_m
                .copy_from_slice(&surface.z_rail_m[from..from + n]);
        }
        // Wheel locus (field face first): segments running towards -q face
        // down; keep the lowest.
        for (i, w) in locus.windows(2).enumerate() {
            if w[1].q_m < w[0].q_m {
                self.raster(
                    w[1].q_m,
                    w[1].z_m,
                    w[0].q_m,
                    w[0].z_m,
                    |old, new| old.is_nan() || new > old,
                    Some(i),
                );
            }
        }
    }

    /// The rail surface alone, over the rail's whole lateral range (no
    /// wheel: `z_wheel_m` is NaN).
    pub fn rail_surface(rail: &PlacedRail) -> Self {
        rail.surface().clone()
    }

    /// The surface of a rail sampled by `samples` (side frame, gauge face
    /// first): per lattice sample the highest of the segments running
    /// towards +q (they face up).
    pub(crate) fn surface_of(samples: &[CurveSample]) -> Self {
        let (lo, hi) = range(samples.iter().map(|s| s.q_m));
        let mut g = Self::default();
        g.set_lattice(lattice_ceil(lo), lattice_floor(hi));
        for w in samples.windows(2) {
            if w[1].q_m > w[0].q_m {
                g.raster(
                    w[0].q_m,
                    w[0].z_m,
                    w[1].q_m,
                    w[1].z_m,
                    |old, new| old.is_nan() || new < old,
                    None,
                );
            }
        }
        g
    }

    /// Rail surface height at `q_m` \[m\], linear between samples (NaN
    /// outside the rail).
    pub fn rail_z_at(&self, q_m: f64) -> f64 {
        let f = (q_m - self.q0_m) / self.dq_m;
        if self.len() < 2 || !(f >= 0.0 && f <= (self.len() - 1) as f64) {
            return f64::NAN;
        }
        let k = (f as usize).min(self.len().saturating_sub(2));
        let w = f - k as f64;
        self.z_rail_m[k] + w * (self.z_rail_m[k + 1] - self.z_rail_m[k])
    }

    /// Makes the samples those of lattice indices `first..=last` (none when
    /// `last < first`), all NaN.
    fn set_lattice(&mut self, first: i64, last: i64) {
        self.dq_m = SAMPLE_SPACING_M;
        self.k0 = first;
        self.q0_m = first as f64 * self.dq_m;
        let n = last.saturating_sub(first).saturating_add(1).max(0) as usize;
        self.z_rail_m.clear();
        self.z_rail_m.resize(n, f64::NAN);
        self.z_wheel_m.clear();
        self.z_wheel_m.resize(n, f64::NAN);
        self.locus_index.clear();
        self.locus_index.resize(n, 0);
    }

    fn raster(
        &mut self,
        qa: f64,
        za: f64,
        qb: f64,
        zb: f64,
        better: impl Fn(f64, f64) -> bool,
        locus: Option<usize>,
    ) {
        let n = self.len();
        if n == 0 {
            return;
        }
        let k0 = lattice_ceil(qa).saturating_sub(self.k0).max(0) as usize;
        let k1 = lattice_floor(qb).saturating_sub(self.k0);
        if k1 < 0 {
            return;
        }
        let k1 = (k1 as usize).min(n - 1);
        for k in k0..=k1 {
            let q = self.q_m(k);
            let z = za + (zb - za) * (q - qa) / (qb - qa);
            let slot = match locus {
                Some(_) => &mut self.z_wheel_m[k],
                None => &mut self.z_rail_m[k],
            };
            if better(*slot, z) {
                *slot = z;
                if let Some(i) = locus {
                    self.locus_index[k] = i;
                }
            }
        }
    }
}

/// The smallest lattice index k with k [`SAMPLE_SPACING_M`] >= `q_m`
/// (saturating for infinite `q_m`).
fn lattice_ceil(q_m: f64) -> i64 {
    let f = q_m / SAMPLE_SPACING_M;
    // f.ceil() as i64 without the call to libm's ceil that the baseline
    // x86-64 target makes of it (two a locus segment: most of a raster's
    // time); the same value for every f.
    let t = f as i64;
    if (t as f64) < f {
        t.saturating_add(1)
    } else {
        t
    }
}

/// The largest lattice index k with k [`SAMPLE_SPACING_M`] <= `q_m`.
fn lattice_floor(q_m: f64) -> i64 {
    let f = q_m / SAMPLE_SPACING_M;
    // f.floor() as i64, as in lattice_ceil.
    let t = f as i64;
    if (t as f64) > f {
        t.saturating_sub(1)
    } else {
        t
    }
}

fn range(it: impl Iterator<Item = f64>) -> (f64, f64) {
    it.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    })
}

/// Buffers of a wheelset solve, reused between calls: the contact search's,
/// and each wheel's last exact patch solver, which the next solve of a
/// patch grid of the same shape renews ([`ContactSolver::renew`]: its
/// kernels and buffers, none of its state). Nothing in them changes a
/// result.
#[derive(Debug, Clone, Default)]
pub struct SearchScratch {
    /// Contact locus per side (left, right).
    pub locus: [Vec<LocusPoint>; 2],
    /// Vertical gap per side.
    pub gap: [VerticalGap; 2],
    /// Per side: the last exact patch solver.
    pub(crate) solvers: SpareSolvers,
    /// Whether a wheelset solve may solve its two wheels at once, on the
    /// calling thread and one more (models other than the fast ones, whose
    /// wheels take less than a thread costs to start). The results are the
    /// same bits either way; the step's wall time is about that of its
    /// slower wheel instead of their sum. Default false: one thread.
    pub parallel_wheels: bool,
    /// The roll search's first look: a part of a locus and its gap (one
    /// side at a time).
    window_locus: Vec<LocusPoint>,
    window_gap: VerticalGap,
}

/// One wheel's part of a [`SearchScratch`]: its contact locus and vertical
/// gap (read) and its kept patch solver.
pub(crate) struct WheelScratch<'a> {
    pub(crate) locus: &'a [LocusPoint],
    pub(crate) gap: &'a VerticalGap,
    pub(crate) solver: &'a mut Option<Box<ContactSolver>>,
}

impl HeapBytes for VerticalGap {
    fn heap_bytes(&self) -> usize {
        heap_bytes!(self.z_rail_m, self.z_wheel_m, self.locus_index)
    }
}

/// The loci, gaps and kept solvers' buffers (not the solvers' kernels,
/// the cache's).
impl HeapBytes for SearchScratch {
    fn heap_bytes(&self) -> usize {
        let gaps = self
            .gap
            .iter()
            .chain([&self.window_gap])
            .map(HeapBytes::heap_bytes)
            .sum::<usize>();
        gaps + heap_bytes!(self.locus, self.window_locus, self.solvers.0)
    }
}

impl SearchScratch {
    /// Drops each wheel's kept patch solver (buffers only: the next step
    /// builds them again, to the same answers).
    pub fn release_solvers(&mut self) {
        self.solvers = SpareSolvers::default();
    }

    /// The wheels' parts (left, right), each borrowed on its own.
    pub(crate) fn wheels(&mut self) -> [WheelScratch<'_>; 2] {
        let [l, r] = &mut self.solvers.0;
        let part = |i: usize, solver| WheelScratch {
            locus: &self.locus[i],
            gap: &self.gap[i],
            solver,
        };
        [part(0, l), part(1, r)]
    }
}

/// Per side (left, right): a patch solver kept for its kernels and buffers.
#[derive(Clone, Default)]
pub(crate) struct SpareSolvers(pub(crate) [Option<Box<ContactSolver>>; 2]);

impl std::fmt::Debug for SpareSolvers {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let kept = self.0.each_ref().map(|s| s.is_some());
        f.debug_tuple("SpareSolvers").field(&kept).finish()
    }
}

/// The rigid position of the wheelset: both wheels touch their rails (or,
/// with a given roll, the closer one touches).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidPosition {
    /// Wheelset centre height \[m\].
    pub center_z_m: f64,
    /// Roll angle \[rad\].
    pub roll_rad: f64,
    /// Smallest vertical gap per side (left, right) at that position \[m\].
    pub min_gap_m: [f64; 2],
    /// Where the roll was searched: the slope of the left wheel's smallest
    /// gap less the right's over roll at the search's last step \[m/rad\]
    /// (about the track width), the next time step's first slope.
    pub roll_slope_m_per_rad: Option<f64>,
    /// Per side, the dense wheel-profile sample ([`PlacedWheel::samples`])
    /// of the smallest vertical gap.
    pub contact_sample: [usize; 2],
}

impl RigidPosition {
    /// The pose of `side`'s wheel at this rigid position, the wheelset at
    /// `position` (its lateral shift and yaw).
    pub fn pose(&self, side: Side, position: &WheelsetPosition) -> SidePose {
        SidePose::new(
            side,
            position.lateral_m,
            self.center_z_m,
            self.roll_rad,
            position.yaw_rad,
        )
    }
}

/// Settings of the contact search.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SearchSettings {
    /// Potential contact parts closer than this are combined into one
    /// patch \[m\]; the distance is CONTACT's D_SEP's, of the parts' boxes
    /// along x, along q and in height ([`gap_intervals`]).
    pub merge_distance_m: f64,
    /// Roll iteration: tolerance on the difference of the two smallest gaps \[m\].
    pub roll_tolerance_m: f64,
    /// Where each patch's contact reference point (and with it its contact
    /// frame) lies; default [`ReferencePoint::SmallestGap`]. Used by
    /// [`crate::wheelrail::solve_wheelset`] and its warm and pitch-control
    /// forms; contact tables ([`crate::wheelrail::table`]) keep their
    /// tabulated smallest-gap references whatever it says.
    pub reference_point: ReferencePoint,
    /// With [`ReferencePoint::InterpenetrationCentre`]: regions of
    /// interpenetration of one patch farther apart than this \[m\] (and
    /// closer than `merge_distance_m`) are its sub-patches, whose pressures
    /// act on each other reduced in the normal problem, CONTACT's blended
    /// patch of D_COMB < d <= D_SEP ([`sub_patches`]). None (the default):
    /// each patch is one region.
    pub combine_distance_m: Option<f64>,
    /// With [`ReferencePoint::InterpenetrationCentre`]: CONTACT's turning
    /// of the contact angles of neighbouring patches towards each other
    /// (D_TURN, A_SEP; [`turn_reference_angles`]). None (the default):
    /// each patch keeps its own mean angle.
    pub angle_turning: Option<AngleTurning>,
}

/// CONTACT's turning of the contact reference angles of neighbouring
/// patches (`turn_cpatch_refangle`, `m_wr_locatecp.f90`): two patches
/// whose facing ends lie between D_SEP (`SearchSettings::merge_distance_m`)
/// and D_TURN apart turn their contact angles towards their common mean,
/// fully at D_SEP, not at all at D_TURN, so that a patch's frame does not
/// jump where it splits off its neighbour or merges with it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AngleTurning {
    /// D_TURN \[m\]: patches farther apart do not turn (none turn when it
    /// is not larger than D_SEP).
    pub distance_m: f64,
    /// A_SEP \[rad\]: patches whose contact angles differ by more do not
    /// turn.
    pub max_angle_difference_rad: f64,
}

impl Default for SearchSettings {
    fn default() -> Self {
        Self {
            merge_distance_m: 1.0e-3,
            roll_tolerance_m: 1.0e-10,
            reference_point: ReferencePoint::SmallestGap,
            combine_distance_m: None,
            angle_turning: None,
        }
    }
}

/// Where a patch's contact reference point lies. The point carries the
/// patch's contact frame: the contact angle (the normal), the rolling
/// radius, the point where the creepages are computed, the origin of the
/// patch grid (about which the spin moment is taken) and the location
/// reported.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ReferencePoint {
    /// The point of smallest vertical gap of the patch at the rigid
    /// position (between the samples: the vertex of a parabola), on the
    /// rail surface, with the rail's contact angle there.
    #[default]
    SmallestGap,
    /// CONTACT's place (its `m_wr_locatecp.f90`, `compute_wgt_center_1d`
    /// with the default weighting, and `set_cpatch_reference`): the
    /// weighted centre of the patch's interpenetration area at the
    /// approach that carries the load ([`interpenetration_centre`]), on
    /// the rail surface, with the weighted mean of the rail's contact
    /// angle over that area as the contact angle (not the rail's angle at
    /// the centre). The creepages are then CONTACT's too
    /// (`m_wr_rigslip.f90`, `wr_creep_cref`): the wheel's velocity is
    /// taken with the wheel lowered by its vertical approach, at the point
    /// the patch's normal interpenetration from the reference along the
    /// normal, into the rail (where the default takes the wheel at the
    /// rigid position, at the reference: a rolling radius that differs
    /// by up to the approach, 0.08 mm on a flange, and changes the
    /// longitudinal creepage by 1.6e-4 there). Where the gap is nearly
    /// flat (a centred wheel on its rail) the smallest gap is ill-defined
    /// and the two places lie 1.4-2.5 mm apart on the Manchester
    /// benchmark's profiles; elsewhere 0.1-0.4 mm. The undeformed
    /// distance is CONTACT's too (`m_wr_undefdist.f90`): taken with the
    /// wheel where the approach puts it, overlapping the rail, not
    /// touching it (on a flank the two differ by the approach's part
    /// along the tangent plane: on the benchmark's flange at 1 rad, the
    /// patch lay 21 um to the side and its spin moment 12-30 % apart). The
    /// centre depends on
    /// the approach, and the approach on the frame: a wheel's load
    /// iteration is repeated from the approach found until the centres
    /// and that approach stay (within a thousandth of an element, and
    /// 1e-6 rad), at most four more times, usually once (the first places
    /// them at the estimated approach, or at the given one); from the
    /// third placement on at the secant step's approach where the answers
    /// converge slowly.
    InterpenetrationCentre,
}

/// The weighted centre of a patch's interpenetration area (side frame),
/// see [`interpenetration_centre`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InterpenetrationCentre {
    /// Lateral position \[m\].
    pub q_m: f64,
    /// Longitudinal position: the weighted mean of the contact locus' x
    /// \[m\].
    pub x_m: f64,
    /// The weighted mean of the rail's contact angle \[rad\] (see
    /// [`PatchGeometry::contact_angle_rad`]).
    pub contact_angle_rad: f64,
    /// The sum of the weights, pen^(5/2) per sample \[m^(5/2)\].
    pub weight: f64,
}

/// The weighted sums of an [`InterpenetrationCentre`].
#[derive(Debug, Clone, Copy, Default)]
struct CentreSums {
    w: f64,
    wq: f64,
    wx: f64,
    wa: f64,
}

impl CentreSums {
    /// Adds a sample at lateral position `q_m` with interpenetration
    /// `pen_m` > 0, locus x `x_m` and rail contact angle `angle_rad`.
    ///
    /// Its weight is CONTACT's: the integral along x of the squared
    /// interpenetration where the wheel's gap along x is taken as
    /// pen - a t^2 with a = 1/(2 r_nom) the same for every sample,
    /// int_{-t0}^{t0} (pen - a t^2)^2 dt = (16/15) pen^2 t0 with
    /// t0 = sqrt(pen/a): proportional to pen^(5/2), the constant
    /// (16/15)/sqrt(a) dropping out of the means.
    fn add(&mut self, q_m: f64, pen_m: f64, x_m: f64, angle_rad: f64) {
        let w = pen_m * pen_m * pen_m.sqrt();
        self.w += w;
        self.wq += w * q_m;
        self.wx += w * x_m;
        self.wa += w * angle_rad;
    }

    fn centre(&self) -> Option<InterpenetrationCentre> {
        (self.w > 0.0 && self.w.is_finite()).then(|| InterpenetrationCentre {
            q_m: self.wq / self.w,
            x_m: self.wx / self.w,
            contact_angle_rad: self.wa / self.w,
            weight: self.w,
        })
    }
}

/// The weighted centre of the interpenetration of the samples `k0..=k1`
/// of `gap` at the vertical approach `delta_m` (from the rigid position
/// of `gap`): the means of the samples' q, their contact locus' x and the
/// contact angle of the rail surface `rail` (its dense samples) below
/// them, each sample weighted by pen^(5/2), pen = `delta_m` - gap > 0
/// (see [`ReferencePoint::InterpenetrationCentre`]). CONTACT weights the
/// same integral on its own lattice of the gap (0.3 DS) and takes the
/// angle from its rail spline; the sums here run over the search's
/// lattice ([`SAMPLE_SPACING_M`]). None where no sample interpenetrates.
pub fn interpenetration_centre(
    rail: &[CurveSample],
    locus: &[LocusPoint],
    gap: &VerticalGap,
    (k0, k1): (usize, usize),
    delta_m: f64,
) -> Option<InterpenetrationCentre> {
    let mut sums = CentreSums::default();
    // The rail segment of the last sample: the samples run towards +q, and
    // so does the rail surface seen from above.
    let mut j = None;
    for k in k0..=k1.min(gap.len().checked_sub(1)?) {
        let pen = delta_m - gap.gap_m(k);
        if !(pen > 0.0 && pen.is_finite()) {
            continue;
        }
        let q = gap.q_m(k);
        let Some((jk, normal)) = rail_normal_from(rail, q, j) else {
            continue;
        };
        j = Some(jk);
        let x = locus_on_segment(locus, gap.locus_index[k], q).x_m;
        sums.add(q, pen, x, normal[0].atan2(normal[1]));
    }
    sums.centre()
}

/// The bounding box of a region of interpenetration (side frame): its
/// extent along x, its lateral extent along q, and the rail surface's
/// height at either lateral end (CONTACT's `xsta .. zend` of a contact
/// patch, `m_wr_locatecp.f90`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RegionBox {
    /// Longitudinal extent \[m\].
    pub x_m: [f64; 2],
    /// Lateral extent \[m\], increasing.
    pub q_m: [f64; 2],
    /// The rail surface's height z at `q_m[0]` and `q_m[1]` \[m\].
    pub z_m: [f64; 2],
}

impl RegionBox {
    /// CONTACT's distance of two patches (`cpatch_distance`): the gap
    /// between the boxes along x, along q, and the difference of the
    /// rail's heights at their facing ends, in quadrature (0 along an axis
    /// where they overlap).
    pub fn distance(&self, other: &Self) -> f64 {
        let apart = |a: [f64; 2], b: [f64; 2]| {
            if a[0] > b[1] {
                a[0] - b[1]
            } else if b[0] > a[1] {
                b[0] - a[1]
            } else {
                0.0
            }
        };
        let dx = apart(self.x_m, other.x_m);
        let [dq, dz] = self.across(other);
        (dx * dx + dq * dq + dz * dz).sqrt()
    }

    /// How far the boxes lie apart across the track: the gap between them
    /// along q and the difference of the rail's heights at their facing
    /// ends (0, 0 where they overlap along q).
    fn across(&self, other: &Self) -> [f64; 2] {
        if self.q_m[0] > other.q_m[1] {
            [self.q_m[0] - other.q_m[1], self.z_m[0] - other.z_m[1]]
        } else if other.q_m[0] > self.q_m[1] {
            [other.q_m[0] - self.q_m[1], other.z_m[0] - self.z_m[1]]
        } else {
            [0.0, 0.0]
        }
    }

    /// The box of both, the heights those of the outer ends.
    fn union(&mut self, other: &Self) {
        self.x_m = [self.x_m[0].min(other.x_m[0]), self.x_m[1].max(other.x_m[1])];
        if other.q_m[0] < self.q_m[0] {
            (self.q_m[0], self.z_m[0]) = (other.q_m[0], other.z_m[0]);
        }
        if other.q_m[1] > self.q_m[1] {
            (self.q_m[1], self.z_m[1]) = (other.q_m[1], other.z_m[1]);
        }
    }
}

/// The box of the region of samples `start..=end` of `gap` whose gap
/// lies below `level_m`, CONTACT's way: its lateral ends where the
/// interpolated interpenetration `level_m` - gap vanishes towards the
/// neighbouring samples (within `bounds`, else at the end samples), its
/// extent along x that of the wheel taken as pen - a t^2 along x about
/// each sample's locus x (a = 1/(2 r_nom) with `nominal_radius_m`,
/// CONTACT's `compute_contact_length_1d`).
fn region_box(
    locus: &[LocusPoint],
    gap: &VerticalGap,
    bounds: (usize, usize),
    (start, end): (usize, usize),
    level_m: f64,
    nominal_radius_m: f64,
) -> RegionBox {
    let pen = |k: usize| level_m - gap.gap_m(k);
    let a = 0.5 / nominal_radius_m;
    let mut x_m = [f64::INFINITY, f64::NEG_INFINITY];
    for k in start..=end {
        let x = locus_on_segment(locus, gap.locus_index[k], gap.q_m(k)).x_m;
        let t = (pen(k) / a).sqrt();
        x_m = [x_m[0].min(x - t), x_m[1].max(x + t)];
    }
    // Where the interpolated interpenetration vanishes between the end
    // sample `inside` and its neighbour `outside`.
    let at_end = |inside: usize, outside: Option<usize>| match outside {
        Some(o) if o >= bounds.0 && o <= bounds.1 && pen(o).is_finite() => {
            let f = pen(inside) / (pen(inside) - pen(o));
            let mix = |u: f64, v: f64| u + f * (v - u);
            (
                mix(gap.q_m(inside), gap.q_m(o)),
                mix(gap.z_rail_m[inside], gap.z_rail_m[o]),
            )
        }
        _ => (gap.q_m(inside), gap.z_rail_m[inside]),
    };
    let (q0, z0) = at_end(start, start.checked_sub(1));
    let (q1, z1) = at_end(end, Some(end + 1));
    RegionBox {
        x_m,
        q_m: [q0, q1],
        z_m: [z0, z1],
    }
}

/// The regions of interpenetration of one patch that lie apart, its
/// sub-patches: CONTACT's blended patch (`combine_cpatches`), whose
/// regions are kept one patch with a reduced interaction between them in
/// the normal problem ([`crate::core::normal::NormalBlend`]).
#[derive(Debug, Clone, PartialEq)]
pub struct SubPatches {
    /// Per sub-patch, its box.
    pub boxes: Vec<RegionBox>,
    /// The interaction factors f_kl of the sub-patches, row-major n x n:
    /// 1 on the diagonal, elsewhere ((d_sep - d)/(d_sep - d_comb))^0.8 for
    /// the boxes' distance d, 0 from d_sep on.
    pub factors: Vec<f64>,
}

/// The sub-patches of the samples `k0..=k1` of `gap` at the vertical
/// approach `delta_m`, CONTACT's way: each run of interpenetrating
/// samples is a region, its lateral ends where the interpolated
/// interpenetration vanishes, its extent along x that of the wheel taken
/// as pen - a t^2 along x at each sample's locus x (a = 1/(2 r_nom) with
/// `nominal_radius_m`, CONTACT's `compute_contact_length_1d`); regions
/// within `combine_m` of each other ([`RegionBox::distance`]) are one
/// region, and the rest are the sub-patches, their factors from
/// `separate_m` (d_sep) and `combine_m` (d_comb). None for fewer than two
/// regions.
pub fn sub_patches(
    locus: &[LocusPoint],
    gap: &VerticalGap,
    (k0, k1): (usize, usize),
    delta_m: f64,
    nominal_radius_m: f64,
    combine_m: f64,
    separate_m: f64,
) -> Option<SubPatches> {
    let k1 = k1.min(gap.len().checked_sub(1)?);
    let mut boxes: Vec<RegionBox> = runs_below(gap, k0, k1 + 1, delta_m)
        .map(|(start, end, _)| {
            region_box(
                locus,
                gap,
                (k0, k1),
                (start, end),
                delta_m,
                nominal_radius_m,
            )
        })
        .collect();
    // CONTACT's first pass: regions within d_comb are one.
    let mut i = 0;
    while i < boxes.len() {
        let mut j = i + 1;
        while j < boxes.len() {
            if boxes[i].distance(&boxes[j]) <= combine_m {
                let b = boxes.remove(j);
                boxes[i].union(&b);
            } else {
                j += 1;
            }
        }
        i += 1;
    }
    if boxes.len() < 2 {
        return None;
    }
    // The rest: its second pass keeps regions within d_sep one patch of
    // sub-patches, the others separate patches (no interaction: f = 0
    // from d_sep on, as the distance to a group's box is at most that to
    // any of its members).
    let n = boxes.len();
    let mut factors = vec![0.0; n * n];
    for k in 0..n {
        for l in 0..n {
            let d = boxes[k].distance(&boxes[l]);
            factors[k * n + l] = if k == l {
                1.0
            } else if d < separate_m {
                ((separate_m - d) / (separate_m - combine_m))
                    .powf(0.8)
                    .min(1.0)
            } else {
                0.0
            };
        }
    }
    Some(SubPatches { boxes, factors })
}

/// The box of the interpenetration of the samples `k0..=k1` of `gap` at
/// the vertical approach `delta_m`: the box of all its runs of
/// interpenetrating samples (each as in [`sub_patches`]). None where no
/// sample interpenetrates.
pub fn interpenetration_box(
    locus: &[LocusPoint],
    gap: &VerticalGap,
    (k0, k1): (usize, usize),
    delta_m: f64,
    nominal_radius_m: f64,
) -> Option<RegionBox> {
    let last = gap.len().checked_sub(1)?;
    runs_below(gap, k0, k1.min(last) + 1, delta_m)
        // Its ends interpolated towards the samples beyond them, inside
        // the patch's interval or not.
        .map(|(start, end, _)| {
            region_box(
                locus,
                gap,
                (0, last),
                (start, end),
                delta_m,
                nominal_radius_m,
            )
        })
        .reduce(|mut a, b| {
            a.union(&b);
            a
        })
}

/// Turns the contact angles of a wheel's patches as CONTACT does
/// ([`AngleTurning`]; its `turn_cpatch_refangle`). `patches`: per patch
/// its interpenetration centre and box (None: it does not
/// interpenetrate, CONTACT's near miss, which neither turns nor is turned
/// to). The patches are taken in the order of their centres' q,
/// decreasing (CONTACT's field side first); each neighbouring pair whose
/// facing ends lie d apart (their boxes' gap along q and the rail's
/// heights there, in quadrature: not along x), D_SEP <= d <= D_TURN, and
/// whose angles differ by at most A_SEP, turns each of its two angles by
/// f (a_comb - a), f = (D_TURN - d) / (D_TURN - D_SEP), a_comb the mean of
/// the two weighted by the centres' weights; the angles compared and
/// combined are those before any turning.
pub fn turn_reference_angles(
    patches: &mut [(Option<InterpenetrationCentre>, Option<RegionBox>)],
    separate_m: f64,
    turning: AngleTurning,
) {
    let turn_m = turning.distance_m;
    if turn_m <= separate_m + 1e-15 {
        return;
    }
    let mut order: Vec<usize> = (0..patches.len())
        .filter(|&k| patches[k].0.is_some() && patches[k].1.is_some())
        .collect();
    let q = |k: usize| patches[k].0.map_or(f64::NAN, |c| c.q_m);
    order.sort_by(|&a, &b| q(b).total_cmp(&q(a)));
    let before: Vec<(f64, f64, RegionBox)> = order
        .iter()
        .filter_map(|&k| match patches[k] {
            (Some(c), Some(b)) => Some((c.contact_angle_rad, c.weight, b)),
            _ => None,
        })
        .collect();
    for (i, pair) in before.windows(2).enumerate() {
        let [(a1, w1, outer), (a2, w2, inner)] = [pair[0], pair[1]];
        let [dq, dz] = outer.across(&inner);
        let d = dq.hypot(dz);
        if (a1 - a2).abs() > turning.max_angle_difference_rad || d < separate_m || d > turn_m {
            continue;
        }
        let comb = (a1 * w1 + a2 * w2) / (w1 + w2);
        let f = (turn_m - d) / (turn_m - separate_m);
        for (k, a) in [(order[i], a1), (order[i + 1], a2)] {
            if let Some(c) = patches[k].0.as_mut() {
                c.contact_angle_rad += f * (comb - a);
            }
        }
    }
}

/// [`rail_normal_at`] searching forward from the segment `from` (the
/// segment of a smaller q), from the start when it finds none there.
fn rail_normal_from(
    rs: &[CurveSample],
    q_m: f64,
    from: Option<usize>,
) -> Option<(usize, [f64; 2])> {
    let Some(from) = from else {
        return rail_normal_at(rs, q_m);
    };
    let Some(j) =
        (from..rs.len().saturating_sub(1)).find(|&j| rs[j].q_m <= q_m && rs[j + 1].q_m > q_m)
    else {
        return rail_normal_at(rs, q_m);
    };
    Some((j, segment_normal(rs, j, q_m)))
}

/// The point of the contact locus at `q_m` on its segment from point
/// `i + 1` to point `i` (the segment that rasters a lattice sample,
/// [`VerticalGap::locus_index`]), linear in q (beyond the segment's ends:
/// extrapolated).
fn locus_on_segment(locus: &[LocusPoint], i: usize, q_m: f64) -> LocusPoint {
    let a = locus[(i + 1).min(locus.len() - 1)];
    let b = locus[i];
    let f = if b.q_m != a.q_m {
        (q_m - a.q_m) / (b.q_m - a.q_m)
    } else {
        0.0
    };
    let mix = |u: f64, v: f64| u + f * (v - u);
    LocusPoint {
        x_m: mix(a.x_m, b.x_m),
        q_m,
        z_m: mix(a.z_m, b.z_m),
        kx_per_m: mix(a.kx_per_m, b.kx_per_m),
        radius_m: mix(a.radius_m, b.radius_m),
        profile_y_m: mix(a.profile_y_m, b.profile_y_m),
        lead_m: mix(a.lead_m, b.lead_m),
    }
}

/// The smallest vertical gaps of both wheels (left, right).
#[derive(Debug, Clone, Copy)]
struct MinGaps {
    gap_m: [f64; 2],
    /// Per side, the dense wheel-profile sample where it lies.
    sample: [usize; 2],
}

/// Smallest gaps with the centre at `z` and roll `roll`; the loci and gaps
/// are left in `scratch`.
fn min_gaps(
    pair: &WheelRailPair,
    lateral_m: f64,
    yaw_rad: f64,
    roll_rad: f64,
    center_z_m: f64,
    scratch: &mut SearchScratch,
) -> Result<MinGaps, WheelRailError> {
    let mut out = MinGaps {
        gap_m: [0.0; 2],
        sample: [0; 2],
    };
    for side in Side::BOTH {
        let i = side.index();
        let pose = SidePose::new(side, lateral_m, center_z_m, roll_rad, yaw_rad);
        wheel_locus(
            pair.wheel(side),
            pair.wheelset().nominal_radius_m,
            &pose,
            &mut scratch.locus[i],
        );
        let gap = &mut scratch.gap[i];
        gap.compute(pair.rail(side), &scratch.locus[i]);
        let (k, g) = gap.min().ok_or_else(|| WheelRailError::Geometry {
            side: side.name(),
            message: format!(
                "the wheel does not lie above its rail at lateral shift {:.2} mm: \
                 the profiles do not overlap laterally (check gauge, flange-back distance \
                 and profile origins)",
                lateral_m * 1e3
            ),
        })?;
        out.gap_m[i] = g;
        out.sample[i] = gap.locus_index[k];
    }
    Ok(out)
}

/// Half the width of the roll search's first look, in dense wheel-profile
/// samples ([`SAMPLE_SPACING_M`] each: 10 mm of profile).
const NEAR_SAMPLES: usize = 200;

/// [`min_gaps`] over the parts of the loci within [`NEAR_SAMPLES`] of the
/// dense wheel-profile samples `near` (per side) only: a fifth of the
/// work, for the roll search's first estimate. It misses a smaller gap
/// farther away (the other point of a two-point contact, or a contact that
/// jumped). None where a part finds no gap (it lies beside the rail).
#[allow(clippy::too_many_arguments)]
fn min_gaps_near(
    pair: &WheelRailPair,
    lateral_m: f64,
    yaw_rad: f64,
    roll_rad: f64,
    center_z_m: f64,
    near: [usize; 2],
    scratch: &mut SearchScratch,
) -> Option<[f64; 2]> {
    let mut out = [0.0; 2];
    for side in Side::BOTH {
        let i = side.index();
        let pose = SidePose::new(side, lateral_m, center_z_m, roll_rad, yaw_rad);
        let wheel = pair.wheel(side);
        let n = wheel.samples().len();
        let lo = near[i].saturating_sub(NEAR_SAMPLES).min(n);
        let hi = near[i].saturating_add(NEAR_SAMPLES + 1).min(n);
        scratch.window_locus.clear();
        let radius = pair.wheelset().nominal_radius_m;
        locus_part(wheel, radius, &pose, lo..hi, &mut scratch.window_locus);
        scratch
            .window_gap
            .compute(pair.rail(side), &scratch.window_locus);
        out[i] = scratch.window_gap.min()?.1;
    }
    Some(out)
}

/// Where a roll search starts: the roll \[rad\] and, when known, the slope
/// of the gap difference d over roll \[m/rad\] there (the previous time
/// step's, [`RollFound::slope_m_per_rad`]) and the dense wheel-profile
/// samples of the contacts (left, right; the previous step's,
/// [`RigidPosition::contact_sample`]), near which the first look goes.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct RollStart {
    pub roll_rad: f64,
    pub slope_m_per_rad: Option<f64>,
    pub contact_sample: Option<[usize; 2]>,
}

/// What a roll search found: the roll \[rad\] and the slope of d over roll
/// at its last secant step \[m/rad\] (the start's where it took none).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct RollFound {
    pub roll_rad: f64,
    pub slope_m_per_rad: f64,
}

/// The roll angle at which `d(roll)`, the smallest vertical gap of the left
/// wheel minus that of the right, vanishes (to `tolerance_m`): secant steps
/// from `start` (0, or extrapolated from the previous time steps), the
/// first along the start's slope. `d(roll, rough)` returns d and whether
/// it is exact; with `rough` (the first look only) it may be an estimate,
/// which the search never returns on: the roll it returns is that of its
/// last call, an exact one. D grows with roll (positive roll lowers
/// the right wheel) at about the track width `gauge_m` per radian
/// ([`TrackData::rail_spacing_m`](crate::wheelrail::TrackData::rail_spacing_m)); a
/// slope below a tenth of that is not used (the start's slope or `gauge_m`
/// instead). `lateral_m` names the position in the error.
pub(crate) fn find_roll(
    mut d: impl FnMut(f64, bool) -> Result<(f64, bool), WheelRailError>,
    gauge_m: f64,
    tolerance_m: f64,
    lateral_m: f64,
    start: RollStart,
) -> Result<RollFound, WheelRailError> {
    let usable = |s: f64| s.is_finite() && s > 0.1 * gauge_m;
    let slope0 = start
        .slope_m_per_rad
        .filter(|&s| usable(s))
        .unwrap_or(gauge_m);
    let mut r0 = start.roll_rad;
    let (mut d0, exact) = d(r0, true)?;
    if d0.abs() <= tolerance_m {
        if !exact {
            d0 = d(r0, false)?.0;
        }
        if d0.abs() <= tolerance_m {
            return Ok(RollFound {
                roll_rad: r0,
                slope_m_per_rad: slope0,
            });
        }
    }
    let mut slope = slope0;
    let mut r1 = r0 - d0 / slope;
    let mut d1 = d(r1, false)?.0;
    let mut it = 0;
    loop {
        let secant = if (d1 - d0).abs() > 1e-15 && (r1 - r0).abs() > 1e-15 {
            (d1 - d0) / (r1 - r0)
        } else {
            slope0
        };
        slope = if usable(secant) { secant } else { slope0 };
        if d1.abs() <= tolerance_m {
            break;
        }
        it += 1;
        if it > 50 {
            return Err(WheelRailError::Geometry {
                side: "both",
                message: format!(
                    "no roll angle puts both wheels on their rails at lateral shift \
                     {:.2} mm (last difference of the gaps {:.3e} m)",
                    lateral_m * 1e3,
                    d1
                ),
            });
        }
        (r0, d0) = (r1, d1);
        r1 -= d1 / slope;
        d1 = d(r1, false)?.0;
    }
    Ok(RollFound {
        roll_rad: r1,
        slope_m_per_rad: slope,
    })
}

/// Finds the rigid position for `position`; leaves the loci and gaps of that
/// position in `scratch`.
pub fn rigid_position(
    pair: &WheelRailPair,
    position: &WheelsetPosition,
    settings: &SearchSettings,
    scratch: &mut SearchScratch,
) -> Result<RigidPosition, WheelRailError> {
    rigid_position_from(pair, position, settings, scratch, RollStart::default())
}

/// [`rigid_position`] with the roll search starting at `roll_start` (when
/// the position leaves the roll free).
pub(crate) fn rigid_position_from(
    pair: &WheelRailPair,
    position: &WheelsetPosition,
    settings: &SearchSettings,
    scratch: &mut SearchScratch,
    roll_start: RollStart,
) -> Result<RigidPosition, WheelRailError> {
    let z0 = -pair.wheelset().nominal_radius_m;
    let (y, yaw) = (position.lateral_m, position.yaw_rad);
    // The roll search's last evaluation is an exact one at the roll it
    // returns: its loci and gaps are already in `scratch`.
    let mut last: Option<(f64, MinGaps)> = None;
    let mut roll_slope_m_per_rad = None;
    let roll = match position.roll_rad {
        Some(r) => r,
        None => {
            let found = find_roll(
                |r, rough| {
                    if let (true, Some(near)) = (rough, roll_start.contact_sample) {
                        if let Some(g) = min_gaps_near(pair, y, yaw, r, z0, near, scratch) {
                            return Ok((g[0] - g[1], false));
                        }
                    }
                    let g = min_gaps(pair, y, yaw, r, z0, scratch)?;
                    last = Some((r, g));
                    Ok((g.gap_m[0] - g.gap_m[1], true))
                },
                pair.track().rail_spacing_m(),
                settings.roll_tolerance_m,
                y,
                roll_start,
            )?;
            roll_slope_m_per_rad = Some(found.slope_m_per_rad);
            found.roll_rad
        }
    };
    let MinGaps {
        gap_m: g,
        sample: contact_sample,
    } = match last {
        Some((r, g)) if r.to_bits() == roll.to_bits() => g,
        _ => min_gaps(pair, y, yaw, roll, z0, scratch)?,
    };
    // Translating the wheelset in z shifts every vertical gap equally.
    let dz = g[0].min(g[1]);
    let center_z_m = z0 + dz;
    for i in 0..2 {
        scratch.locus[i].iter_mut().for_each(|p| p.z_m += dz);
        scratch.gap[i].z_wheel_m.iter_mut().for_each(|z| *z += dz);
    }
    // The smallest gaps of the shifted samples, bit for bit those that the
    // patches' caps are compared with (g - dz may differ by a rounding).
    let g = [0, 1].map(|i| scratch.gap[i].min().map_or(g[i] - dz, |(_, g)| g));
    Ok(RigidPosition {
        center_z_m,
        roll_rad: roll,
        min_gap_m: g,
        roll_slope_m_per_rad,
        contact_sample,
    })
}

/// One lateral sample of a patch's undeformed distance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LateralSample {
    /// Lateral coordinate in the tangent plane \[m\].
    pub s_m: f64,
    /// Normal distance between rail and wheel \[m\], the wheel sampled
    /// [`PatchGeometry::wheel_drop_m`] below its rigid position, plus that
    /// drop's normal part (so the distance at the rigid position where the
    /// drop is the smallest vertical gap).
    pub gap_m: f64,
    /// Longitudinal position of the wheel's closest point, relative to the
    /// reference's \[m\].
    pub dx_m: f64,
    /// Wheel curvature along x [1/m].
    pub kx_per_m: f64,
}

/// A potential contact patch and its planar geometry (side frame).
#[derive(Debug, Clone, PartialEq)]
pub struct PatchGeometry {
    /// Reference point on the rail surface (q, z) \[m\].
    pub reference_m: [f64; 2],
    /// Longitudinal position of the reference point \[m\].
    pub x_m: f64,
    /// Contact normal, into the rail, (q, z) components.
    pub normal: [f64; 2],
    /// Contact angle \[rad\]: angle of the normal from the vertical, positive
    /// towards +q (rail surface facing the gauge side).
    pub contact_angle_rad: f64,
    /// Smallest vertical gap in the patch at the rigid position \[m\].
    pub min_vertical_gap_m: f64,
    /// Rolling radius of the wheel at the reference point \[m\].
    pub rolling_radius_m: f64,
    /// Wheel profile y of the reference point \[m\].
    pub wheel_profile_y_m: f64,
    /// Lateral extent of the potential contact area in the tangent plane \[m\].
    pub s_range_m: [f64; 2],
    /// Undeformed distance samples, increasing s: the normal distance with
    /// the wheel moved down by `wheel_drop_m`, plus that drop's normal part
    /// (see [`patch_geometry_about`]).
    pub lateral: Vec<LateralSample>,
    /// Index of the rail sample at the reference point.
    pub rail_index: usize,
    /// Index of the locus point at the reference point.
    pub locus_index: usize,
    /// How far the wheel was moved down from the rigid position when
    /// `lateral` was sampled \[m\]: into touch (the smallest vertical
    /// gap), or to the interpenetration centre's approach.
    pub wheel_drop_m: f64,
}

impl PatchGeometry {
    /// Unit lateral tangent (q, z): n x e_x.
    pub fn tangent(&self) -> [f64; 2] {
        [self.normal[1], -self.normal[0]]
    }

    /// Linear interpolation of the lateral samples at `s` (clamped).
    pub fn lateral_at(&self, s_m: f64) -> LateralSample {
        let l = &self.lateral;
        let k = l.partition_point(|p| p.s_m < s_m);
        if k == 0 {
            return l[0];
        }
        if k >= l.len() {
            return l[l.len() - 1];
        }
        let (a, b) = (l[k - 1], l[k]);
        let f = (s_m - a.s_m) / (b.s_m - a.s_m);
        let mix = |u: f64, v: f64| u + f * (v - u);
        LateralSample {
            s_m,
            gap_m: mix(a.gap_m, b.gap_m),
            dx_m: mix(a.dx_m, b.dx_m),
            kx_per_m: mix(a.kx_per_m, b.kx_per_m),
        }
    }

    /// Undeformed distance at (x, s) relative to the reference \[m\].
    pub fn gap_at(&self, x_m: f64, s_m: f64) -> f64 {
        self.lateral_at(s_m).gap_at(x_m)
    }
}

impl LateralSample {
    /// Undeformed distance at `x_m` along its row \[m\]: the wheel a
    /// parabola along x about its closest point.
    pub fn gap_at(&self, x_m: f64) -> f64 {
        let dx = x_m - self.dx_m;
        self.gap_m + 0.5 * self.kx_per_m * dx * dx
    }
}

/// A round wheel's surface seen from a patch's tangent plane: where the
/// line along the patch normal through the plane's point (x, s) meets the
/// wheel, a surface of revolution about the pose's axle, moved down by the
/// geometry's [`PatchGeometry::wheel_drop_m`] (CONTACT's undeformed
/// distance from a 3-D mesh of the wheel, `m_wr_undefdist.f90`, here
/// without the mesh). [`PatchGeometry::gap_at`] takes the wheel along x at
/// fixed s as a parabola about its closest point; on a yawed flange the
/// section is not one: on the Manchester benchmark's flange (1.0-1.16 rad,
/// yaw 0.016-0.025 rad) the two differ by at most 0.9 um in the contact
/// area against an approach of 34-36 um, odd in x, which moves the patch
/// along x: the spin moment, 19 % from CONTACT's with the parabola, comes
/// within 3 % of it (cases 14-21 of CONTACT's `python_mbench.py`).
pub(crate) struct WheelSurface<'a> {
    samples: &'a [CurveSample],
    nominal_radius_m: f64,
    axial_offset_m: f64,
    /// The wheelset centre, moved down, and the axle (x, q, z).
    center: [f64; 3],
    axle: [f64; 3],
    /// The reference point and the plane's lateral tangent and normal
    /// (x, q, z).
    origin: [f64; 3],
    tangent: [f64; 3],
    normal: [f64; 3],
    /// The profile segment of the last point.
    hint: usize,
}

impl<'a> WheelSurface<'a> {
    /// The surface of `wheel` (on a wheelset of `nominal_radius_m`) in
    /// `pose`, seen from the tangent plane of `geom`.
    pub(crate) fn new(
        wheel: &'a PlacedWheel,
        nominal_radius_m: f64,
        pose: &SidePose,
        geom: &PatchGeometry,
    ) -> Self {
        let c = pose.center();
        let t = geom.tangent();
        Self {
            samples: wheel.samples(),
            nominal_radius_m,
            axial_offset_m: wheel.axial_offset_m(),
            center: [c[0], c[1], c[2] + geom.wheel_drop_m],
            axle: pose.axle(),
            origin: [geom.x_m, geom.reference_m[0], geom.reference_m[1]],
            tangent: [0.0, t[0], t[1]],
            normal: [0.0, geom.normal[0], geom.normal[1]],
            hint: geom
                .locus_index
                .min(wheel.samples().len().saturating_sub(2)),
        }
    }

    /// The wheel's radius and its derivative at profile y `y_m`, on the
    /// profile segment bracketing y nearest the last one (a cubic on the
    /// end points' slopes); None beyond the profile or where it turns
    /// vertical.
    fn radius_at(&mut self, y_m: f64) -> Option<(f64, f64)> {
        let p = self.samples;
        if p.len() < 2 {
            return None;
        }
        let brackets = |j: usize| {
            let (a, b) = (p[j].q_m, p[j + 1].q_m);
            a.min(b) <= y_m && y_m <= a.max(b)
        };
        let last = p.len() - 2;
        let mut j = self.hint.min(last);
        let mut step = 1;
        while !brackets(j) {
            // Look on either side, nearest first.
            let down = j.checked_sub(step).filter(|&k| brackets(k));
            let up = (j + step <= last)
                .then_some(j + step)
                .filter(|&k| brackets(k));
            match (down, up) {
                (Some(k), _) | (None, Some(k)) => j = k,
                (None, None) if step > last => return None,
                (None, None) => {
                    step += 1;
                    continue;
                }
            }
            break;
        }
        self.hint = j;
        let (a, b) = (&p[j], &p[j + 1]);
        let h = b.q_m - a.q_m;
        let slope =
            |c: &CurveSample| (c.tangent[0].abs() > 0.05).then(|| c.tangent[1] / c.tangent[0]);
        let (m0, m1) = (slope(a)?, slope(b)?);
        if h.abs() < 1e-15 {
            return Some((self.nominal_radius_m + a.z_m, m0));
        }
        // Cubic Hermite on [a, b].
        let f = (y_m - a.q_m) / h;
        let (f2, f3) = (f * f, f * f * f);
        let z = (2.0 * f3 - 3.0 * f2 + 1.0) * a.z_m
            + (f3 - 2.0 * f2 + f) * h * m0
            + (-2.0 * f3 + 3.0 * f2) * b.z_m
            + (f3 - f2) * h * m1;
        let dz = ((6.0 * f2 - 6.0 * f) * (a.z_m - b.z_m)) / h
            + (3.0 * f2 - 4.0 * f + 1.0) * m0
            + (3.0 * f2 - 2.0 * f) * m1;
        Some((self.nominal_radius_m + z, dz))
    }

    /// The normal coordinate (along the patch normal, into the rail, from
    /// the tangent plane) of the wheel's surface above the plane's point
    /// (`x_m` from the reference along the track, `s_m` along the plane's
    /// lateral tangent) \[m\]; None where Newton's method finds none.
    pub(crate) fn normal_position(&mut self, x_m: f64, s_m: f64) -> Option<f64> {
        self.normal_position_from(x_m, s_m, 0.0)
    }

    /// [`WheelSurface::normal_position`] from the guess `lambda_m` (the
    /// parabola's, which leaves Newton's method a step or two).
    pub(crate) fn normal_position_from(
        &mut self,
        x_m: f64,
        s_m: f64,
        lambda_m: f64,
    ) -> Option<f64> {
        let (o, t, n, c, a) = (
            self.origin,
            self.tangent,
            self.normal,
            self.center,
            self.axle,
        );
        let dot = |u: [f64; 3], v: [f64; 3]| u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
        let an = dot(a, n);
        let p = [
            o[0] + x_m - c[0],
            o[1] + s_m * t[1] - c[1],
            o[2] + s_m * t[2] - c[2],
        ];
        let mut lambda = lambda_m;
        for _ in 0..12 {
            let w = [
                p[0] + lambda * n[0],
                p[1] + lambda * n[1],
                p[2] + lambda * n[2],
            ];
            let u = dot(w, a);
            let rv = [w[0] - u * a[0], w[1] - u * a[1], w[2] - u * a[2]];
            let rho = dot(rv, rv).sqrt();
            let (r, dr) = self.radius_at(u - self.axial_offset_m)?;
            let f = rho - r;
            let df = dot(rv, n) / rho - dr * an;
            if df.abs() <= 1e-6 || !df.is_finite() {
                return None;
            }
            let d = f / df;
            lambda -= d;
            if d.abs() < 1e-13 {
                return Some(lambda);
            }
        }
        None
    }
}

/// The runs of samples `first..n` of `gap` whose gap lies below
/// `level_m`: (first, last, index of the smallest gap).
fn runs_below(
    gap: &VerticalGap,
    first: usize,
    n: usize,
    level_m: f64,
) -> impl Iterator<Item = (usize, usize, usize)> + '_ {
    let below = move |k: usize| gap.gap_m(k) < level_m;
    let mut k = first;
    std::iter::from_fn(move || {
        while k < n && !below(k) {
            k += 1;
        }
        if k >= n {
            return None;
        }
        let start = k;
        let mut kmin = k;
        while k < n && below(k) {
            if gap.gap_m(k) < gap.gap_m(kmin) {
                kmin = k;
            }
            k += 1;
        }
        Some((start, k - 1, kmin))
    })
}

/// The potential contact areas of one wheel: the parts of the q axis
/// where the vertical gap is below `level_m`, those within `merge_m` of
/// each other taken together (first, last, index of the smallest gap).
///
/// Two parts lie within `merge_m` when their boxes at `level_m` do
/// ([`RegionBox::distance`], CONTACT's `cpatch_distance` with its D_SEP):
/// apart along x (the wheel's extent along x about its contact locus,
/// with `locus` and `nominal_radius_m`), along q, and in the rail's height
/// at their facing ends. A tread and a flange region a few millimetres
/// apart along q lie farther apart than that when yaw puts them on either
/// side of the axle or the flange rises steeply between them. The parts
/// are taken in order along q, each joined to the box of the parts
/// before it where that lies within `merge_m`; CONTACT also joins parts
/// that are not neighbours, whose patch then spans the ones between.
pub fn gap_intervals(
    gap: &VerticalGap,
    locus: &[LocusPoint],
    nominal_radius_m: f64,
    level_m: f64,
    merge_m: f64,
) -> Vec<(usize, usize, usize)> {
    gap_intervals_range(
        gap,
        locus,
        nominal_radius_m,
        (0, gap.len()),
        level_m,
        merge_m,
    )
}

fn gap_intervals_range(
    gap: &VerticalGap,
    locus: &[LocusPoint],
    nominal_radius_m: f64,
    (first, n): (usize, usize),
    level_m: f64,
    merge_m: f64,
) -> Vec<(usize, usize, usize)> {
    let mut runs = runs_below(gap, first, n, level_m);
    let Some(run) = runs.next() else {
        return Vec::new();
    };
    let mut out = vec![run];
    let bounds = (first, n - 1);
    let box_of = |(start, end, _): (usize, usize, usize)| {
        region_box(locus, gap, bounds, (start, end), level_m, nominal_radius_m)
    };
    // The box of the last interval, made only where a second run exists.
    let mut last_box = None;
    for run in runs {
        let b = box_of(run);
        let joined = last_box.get_or_insert_with(|| box_of(out[0]));
        let last = out.last_mut().expect("one interval at least");
        if joined.distance(&b) <= merge_m {
            joined.union(&b);
            last.1 = run.1;
            if gap.gap_m(run.2) < gap.gap_m(last.2) {
                last.2 = run.2;
            }
        } else {
            *joined = b;
            out.push(run);
        }
    }
    out
}

/// Splits the intervals of [`gap_intervals`] where, at the vertical
/// approach `delta_m`, the interpenetration inside one interval falls apart
/// into parts farther apart than `merge_m` (as [`gap_intervals`] measures
/// it): the cut goes through the largest gap between the parts.
pub fn split_intervals(
    gap: &VerticalGap,
    locus: &[LocusPoint],
    nominal_radius_m: f64,
    intervals: &[(usize, usize, usize)],
    delta_m: f64,
    merge_m: f64,
) -> Vec<(usize, usize, usize)> {
    let mut out = Vec::new();
    for &iv in intervals {
        let (k0, k1, _) = iv;
        let range = (k0, k1 + 1);
        let mut parts = gap_intervals_range(gap, locus, nominal_radius_m, range, delta_m, merge_m);
        if parts.len() < 2 {
            out.push(iv);
            continue;
        }
        // Cut at the largest gap between successive parts.
        let mut start = k0;
        for w in 0..parts.len() - 1 {
            let (a, b) = (parts[w].1, parts[w + 1].0);
            let cut = (a..=b)
                .max_by(|&i, &j| gap.gap_m(i).total_cmp(&gap.gap_m(j)))
                .unwrap_or(a);
            parts[w].0 = start;
            parts[w].1 = cut;
            start = cut + 1;
        }
        if let Some(last) = parts.last_mut() {
            last.0 = start;
            last.1 = k1;
        }
        out.extend(parts);
    }
    out
}

/// A lateral sample of the gap to a prismatic rail, `sample` (the wheel's
/// closest point at `dx_m` from the reference, which lies at `x_ref_m`),
/// with a roller's curvature `kr` along x (the roller's top at x = 0)
/// added: k_w (x - dx)^2 / 2 + k_r (x + x_ref)^2 / 2 is
/// (k_w + k_r) (x - d)^2 / 2 plus a constant, d = (k_w dx - k_r x_ref) /
/// (k_w + k_r) and the constant k_w k_r (dx + x_ref)^2 / (2 (k_w + k_r)),
/// so that the patch's gap keeps its form with the combined curvature
/// (both bodies curved along x, as two crossed cylinders). The sample
/// unchanged for kr = 0 (a track).
fn with_roller(sample: LateralSample, kr: f64, x_ref_m: f64) -> LateralSample {
    let kw = sample.kx_per_m;
    let k = kw + kr;
    if kr == 0.0 || k <= 0.0 {
        return sample;
    }
    let e = sample.dx_m + x_ref_m;
    LateralSample {
        gap_m: sample.gap_m + 0.5 * kw * kr * e * e / k,
        dx_m: (kw * sample.dx_m - kr * x_ref_m) / k,
        kx_per_m: k,
        ..sample
    }
}

/// Samples (s, lambda) of a curve in the patch frame, increasing s, within
/// `s_lim`, from its `len` points (`point(i)`: q, z and what rides along):
/// the run of points through point `start` along which s is
/// monotone (the part of the surface that faces the other body near the
/// reference; a line along the normal may cross the profile again farther
/// away, e.g. at the back of a flange).
fn to_patch_frame<T: Copy>(
    len: usize,
    point: impl Fn(usize) -> (f64, f64, T),
    start: usize,
    origin: [f64; 2],
    normal: [f64; 2],
    s_lim: [f64; 2],
) -> Vec<(f64, f64, T)> {
    let t = [normal[1], -normal[0]];
    let map = |i: usize| {
        let (q, z, p) = point(i);
        let d = [q - origin[0], z - origin[1]];
        (
            d[0] * t[0] + d[1] * t[1],
            d[0] * normal[0] + d[1] * normal[1],
            p,
        )
    };
    let inside = |s: f64| s >= s_lim[0] && s <= s_lim[1];
    let mut v = Vec::new();
    if len == 0 {
        return v;
    }
    let start = start.min(len - 1);
    let first = map(start);
    v.push(first);
    // Direction of s along increasing index, from the neighbours.
    let dir = |a: f64, b: f64| (b - a).signum();
    let up = if start + 1 < len {
        dir(first.0, map(start + 1).0)
    } else {
        -dir(first.0, map(start - 1).0)
    };
    let mut last = first.0;
    for i in start + 1..len {
        let m = map(i);
        if !inside(m.0) || dir(last, m.0) != up {
            break;
        }
        last = m.0;
        v.push(m);
    }
    last = first.0;
    for i in (0..start).rev() {
        let m = map(i);
        if !inside(m.0) || dir(last, m.0) != -up {
            break;
        }
        last = m.0;
        v.push(m);
    }
    v.sort_by(|a, b| a.0.total_cmp(&b.0));
    v
}

fn interp<T: Copy>(v: &[(f64, f64, T)], s: f64) -> Option<(f64, T, T, f64)> {
    let k = v.partition_point(|p| p.0 < s);
    if k == 0 || k >= v.len() {
        return None;
    }
    let (a, b) = (v[k - 1], v[k]);
    let f = if b.0 > a.0 {
        (s - a.0) / (b.0 - a.0)
    } else {
        0.0
    };
    Some((a.1 + f * (b.1 - a.1), a.2, b.2, f))
}

/// The vertex of the parabola through (-1, `gm`), (0, `g0`), (1, `gp`),
/// its abscissa clamped to [-`limit`, `limit`]: (abscissa, value); (0,
/// `g0`) where the three are not convex (or not finite).
pub(crate) fn parabola_vertex(gm: f64, g0: f64, gp: f64, limit: f64) -> (f64, f64) {
    let curv = gm - 2.0 * g0 + gp;
    if !(curv.is_finite() && curv > 0.0) {
        return (0.0, g0);
    }
    let f = (0.5 * (gm - gp) / curv).clamp(-limit, limit);
    (f, g0 + 0.5 * (gp - gm) * f + 0.5 * curv * f * f)
}

/// The vertex (q, gap) [m] of the parabola through the vertical gap at
/// sample `k` and its neighbours, within half a sample of `k`; sample `k`
/// itself at the ends of the samples or where the gap is not convex.
fn refined_minimum(gap: &VerticalGap, k: usize) -> (f64, f64) {
    let (q, g0) = (gap.q_m(k), gap.gap_m(k));
    if k == 0 || k + 1 >= gap.len() {
        return (q, g0);
    }
    let (f, g) = parabola_vertex(gap.gap_m(k - 1), g0, gap.gap_m(k + 1), 0.5);
    (q + f * gap.dq_m, g)
}

/// The rail sample segment (index of its first sample) over `q_m` and the
/// unit contact normal into the rail there, interpolated between the
/// segment's sample normals; `None` off the rail.
pub(crate) fn rail_normal_at(rs: &[CurveSample], q_m: f64) -> Option<(usize, [f64; 2])> {
    let j = rs
        .windows(2)
        .position(|w| w[0].q_m <= q_m && w[1].q_m > q_m)?;
    Some((j, segment_normal(rs, j, q_m)))
}

/// The unit contact normal into the rail at `q_m` on the rail sample
/// segment `j` (see [`rail_normal_at`]).
fn segment_normal(rs: &[CurveSample], j: usize, q_m: f64) -> [f64; 2] {
    let f = (q_m - rs[j].q_m) / (rs[j + 1].q_m - rs[j].q_m);
    let (a, b) = (rs[j].outward_normal(), rs[j + 1].outward_normal());
    let n = [-(a[0] + f * (b[0] - a[0])), -(a[1] + f * (b[1] - a[1]))];
    let len = n[0].hypot(n[1]);
    [n[0] / len, n[1] / len]
}

/// The geometry of the patch around the interval `[k0, k1]` of `gap` with
/// its minimum at `kmin`, for an expected vertical approach up to `cap_m`.
pub fn patch_geometry(
    rail: &PlacedRail,
    locus: &[LocusPoint],
    gap: &VerticalGap,
    interval: (usize, usize, usize),
    margin_m: f64,
) -> Option<PatchGeometry> {
    patch_geometry_about(rail, locus, gap, interval, margin_m, None, None)
}

/// [`patch_geometry`] with its reference point at `centre` when given
/// ([`ReferencePoint::InterpenetrationCentre`]): on the rail surface at
/// the centre's q, at its x, the centre's contact angle giving the normal;
/// the rolling radius and wheel profile y those of the contact locus at
/// that q. Without, at the smallest gap ([`ReferencePoint::SmallestGap`]).
/// The undeformed distance is measured along the reference's normal with
/// the wheel moved down by `wheel_drop_m` from the rigid position (where
/// the load puts it), or without, into touch at the smallest gap.
pub fn patch_geometry_about(
    rail: &PlacedRail,
    locus: &[LocusPoint],
    gap: &VerticalGap,
    (k0, k1, kmin): (usize, usize, usize),
    margin_m: f64,
    centre: Option<&InterpenetrationCentre>,
    wheel_drop_m: Option<f64>,
) -> Option<PatchGeometry> {
    // The smallest gap between the samples (a sample of 0.05 mm in q is
    // 0.15 mm of a flank at 1.2 rad, 0.006 rad of contact angle on a
    // 13 mm flange root).
    let (qmin, g) = refined_minimum(gap, kmin);
    let rs = rail.samples();
    // The reference: that minimum, where the contact angle is taken, or
    // the centre.
    let (qref, j, normal, contact_angle_rad, li, lref) = match centre {
        None => {
            let (j, normal) = rail_normal_at(rs, qmin)?;
            let li = gap.locus_index[kmin];
            (qmin, j, normal, normal[0].atan2(normal[1]), li, locus[li])
        }
        Some(c) => {
            let (j, _) = rail_normal_at(rs, c.q_m)?;
            let (sa, ca) = c.contact_angle_rad.sin_cos();
            // The lattice sample at or below the centre (within the
            // interval) and its locus segment.
            let f = ((c.q_m - gap.q0_m) / gap.dq_m).floor().max(0.0) as usize;
            let li = gap.locus_index[f.clamp(k0, k1)];
            let lref = LocusPoint {
                x_m: c.x_m,
                ..locus_on_segment(locus, li, c.q_m)
            };
            (c.q_m, j, [sa, ca], c.contact_angle_rad, li, lref)
        }
    };
    // On a roller the gap's minimum along x lies between the wheel's
    // closest point (the locus, for a prismatic rail) and the roller's top
    // (x = 0), at kw / (kw + kr) of the locus point's x (CONTACT's
    // reference point there): the reference is moved to it.
    let kr = rail.roller_curvature_per_m(&rs[j]);
    let lref = if kr > 0.0 && lref.kx_per_m + kr > 0.0 {
        LocusPoint {
            x_m: lref.x_m * lref.kx_per_m / (lref.kx_per_m + kr),
            ..lref
        }
    } else {
        lref
    };
    let zref = gap.rail_z_at(qref);
    let t = [normal[1], -normal[0]];
    let proj = |k: usize| (gap.q_m(k) - qref) * t[0] + (gap.z_rail_m[k] - zref) * t[1];
    let s_range_m = [proj(k0) - margin_m, proj(k1) + margin_m];
    let lim = [s_range_m[0] - 1e-3, s_range_m[1] + 1e-3];
    let origin = [qref, zref];
    // A roller's curvature along x rides along with its samples (0 on a
    // track).
    let rail_pts = to_patch_frame(
        rs.len(),
        |i| (rs[i].q_m, rs[i].z_m, rail.roller_curvature_per_m(&rs[i])),
        j,
        origin,
        normal,
        lim,
    );
    // The wheel as the load will place it: moved vertically into touch at
    // the minimum (by its vertical gap g there), its distance to the rail
    // then offset back by g's normal part. Sampled at the rigid position
    // instead, the wheel's curve would sit g sin(angle) to the side of
    // where it lands (0.5 mm for a flank 1.8 mm off at 0.29 rad, as a
    // wheel lifted by a given roll is), which moves the minimum by tens of
    // micrometres and changes the curvature B on real profiles.
    // With `wheel_drop_m` the wheel is where the load puts it, moved down
    // by that approach, overlapping the rail (CONTACT's undeformed
    // distance, taken at the wheel's position). The overlap is then exact
    // where the wheel sits, not the touching wheel's gap moved along the
    // normal: on a flank the two lie apart by the approach's part along
    // the tangent plane (on the Manchester benchmark's flange at 1 rad,
    // the patch moved 21 um to the side).
    let drop = wheel_drop_m.map_or(g, |d| d.max(g));
    let wheel_pts = to_patch_frame(
        locus.len(),
        |i| (locus[i].q_m, locus[i].z_m + drop, locus[i]),
        li,
        origin,
        normal,
        lim,
    );
    // Samples at whole multiples of the spacing from the reference, so
    // that they (and the curvature and minimum taken from them) do not
    // depend on the extent asked for: a wheel loaded by its approach and
    // the same wheel loaded by the force that needs that approach (another
    // extent) then see the same geometry (they differed by 1.7e-5 of the
    // force).
    let ds = SAMPLE_SPACING_M;
    let first = (s_range_m[0] / ds).floor();
    let n = ((s_range_m[1] / ds).ceil() - first).max(0.0) as usize + 1;
    let mut lateral = Vec::with_capacity(n);
    for i in 0..n {
        let s = (first + i as f64) * ds;
        let (Some((lr, ra, rb, fr)), Some((lw, pa, pb, f))) =
            (interp(&rail_pts, s), interp(&wheel_pts, s))
        else {
            continue;
        };
        let mix = |u: f64, v: f64| u + f * (v - u);
        lateral.push(with_roller(
            LateralSample {
                s_m: s,
                gap_m: lr - lw + drop * normal[1],
                dx_m: mix(pa.x_m, pb.x_m) - lref.x_m,
                kx_per_m: mix(pa.kx_per_m, pb.kx_per_m),
            },
            ra + fr * (rb - ra),
            lref.x_m,
        ));
    }
    if lateral.len() < 2 {
        return None;
    }
    // On a roller the reference lies on its surface at the reference's x
    // (CONTACT's contact point), below the profile's point.
    let [dq, dz] = rail.roller_drop_m(origin[0], origin[1], lref.x_m);
    Some(PatchGeometry {
        reference_m: [origin[0] + dq, origin[1] + dz],
        x_m: lref.x_m,
        normal,
        contact_angle_rad,
        min_vertical_gap_m: g,
        rolling_radius_m: lref.radius_m,
        wheel_profile_y_m: lref.profile_y_m,
        s_range_m,
        lateral,
        rail_index: j,
        locus_index: li,
        wheel_drop_m: drop,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::conformal::geometry::tests::{euler_curvature, YawedTorus};
    use crate::wheelrail::builtin::{load_test_input, mbench_pair};
    use crate::wheelrail::{WarmStart, WheelRailModel};

    /// The roll search never ends on a rough first look: on d(r) = 1.5 x +
    /// 40 x^2 \[m\] with x = r - 1e-3, a rough look that says 0 (within the
    /// tolerance) is looked at again exactly and the search goes on; one
    /// that is off by 1 mm still ends on the exact root; and the start's
    /// slope is used when it is plausible (one secant step from a good
    /// slope), the track width when not.
    #[test]
    fn the_roll_search_ends_on_an_exact_look() {
        let exact = |r: f64| 1.5 * (r - 1e-3) + 40.0 * (r - 1e-3).powi(2);
        let tol = 1e-10;
        for (rough, slope, start) in [
            (0.0, None, 0.0),
            (1e-3, None, 2e-3),
            (0.0, Some(1.5), 1.2e-3),
            (0.0, Some(1e-9), 1.2e-3),
        ] {
            let mut calls = Vec::new();
            let found = find_roll(
                |r, rough_ok| {
                    calls.push(rough_ok);
                    Ok(if rough_ok {
                        (rough, false)
                    } else {
                        (exact(r), true)
                    })
                },
                1.5,
                tol,
                0.0,
                RollStart {
                    roll_rad: start,
                    slope_m_per_rad: slope,
                    contact_sample: None,
                },
            )
            .unwrap();
            assert!(
                exact(found.roll_rad).abs() <= tol,
                "{rough} {slope:?}: {found:?}"
            );
            // Only the first look may be rough.
            assert!(calls[0] && calls[1..].iter().all(|&r| !r), "{calls:?}");
            assert!(calls.len() <= 6, "{rough} {slope:?}: {} looks", calls.len());
            assert!((found.slope_m_per_rad - 1.5 - 80.0 * (found.roll_rad - 1e-3)).abs() < 0.1);
        }
    }

    /// The warm roll search (started from the roll extrapolated from the
    /// last three steps, the last search's slope, and a first look near
    /// the last contacts) finds the roll of the cold search (from 0 with
    /// the track width as the slope, the whole loci every time) along the
    /// load test's motion at 12 mm amplitude, which reaches flange contact
    /// and jumps between tread and flange. Both end within the tolerance
    /// on the gap difference d (1e-10 m), so their rolls differ by at most
    /// 2e-10 m over the slope of d (which falls to 0.167 m/rad on this
    /// path, 0.11 times the track width), and the centre heights by less
    /// than a nanometre.
    #[test]
    fn a_warm_roll_search_finds_the_cold_roll() {
        let pair = mbench_pair().unwrap();
        let settings = SearchSettings::default();
        let (mut cold, mut warm_scratch) = (SearchScratch::default(), SearchScratch::default());
        let mut warm = WarmStart::default();
        let mut worst = [0.0f64; 2];
        for k in 0..400 {
            let input = load_test_input(3 * k, 12e-3, WheelRailModel::HertzFastsim);
            let a = rigid_position(&pair, &input.position, &settings, &mut cold).unwrap();
            let b = rigid_position_from(
                &pair,
                &input.position,
                &settings,
                &mut warm_scratch,
                warm.roll_start(),
            )
            .unwrap();
            warm.advance(
                b.roll_rad,
                b.roll_slope_m_per_rad,
                Some(b.contact_sample),
                [None, None],
                [None, None],
            );
            let slope = a
                .roll_slope_m_per_rad
                .unwrap()
                .min(b.roll_slope_m_per_rad.unwrap());
            worst[0] = worst[0].max((a.roll_rad - b.roll_rad).abs() * slope);
            worst[1] = worst[1].max((a.center_z_m - b.center_z_m).abs());
        }
        assert!(worst[0] <= 2e-10 * 1.001, "{worst:?}");
        assert!(worst[1] <= 1e-9, "{worst:?}");
    }

    /// The planar approach's k_x is the normal curvature of the wheel along
    /// x: on a yawed torus (a wheel whose profile is a circle of 13 mm
    /// radius, 0.47 m from the axis, the profile of a flange) the true
    /// undeformed distance to a prismatic rail along x at fixed s has this
    /// curvature (brute force on the analytic surfaces,
    /// `conformal::geometry`'s `YawedTorus`), within 1e-6 (the brute
    /// force's own error); the circle's own cos(alpha)/r misses the
    /// profile's part, 11 % of the curvature at 1.15 rad and 15.6 mrad.
    /// Without yaw k_x is the circle's, bit for bit.
    #[test]
    fn locus_curvature_along_x_is_the_true_one_on_a_yawed_torus() {
        let (r_t, rho_w) = (0.47, 0.013);
        for &psi in &[0.0, 0.0156, 0.024] {
            let pose = SidePose {
                center_q_m: 0.0,
                center_z_m: -r_t,
                yaw_rad: psi,
                roll_rad: 0.0,
            };
            let frame = LocusFrame::with_offset(0.0, r_t, &pose);
            for &alpha in &[-0.3f64, -0.8, -1.15] {
                // The profile circle about (0, 0) of the profile frame (y
                // along the axle, z radial): material on the right of
                // the walking direction (-cos alpha, sin alpha), convex.
                let s = CurveSample {
                    t_m: 0.0,
                    q_m: rho_w * alpha.sin(),
                    z_m: rho_w * alpha.cos(),
                    tangent: [-alpha.cos(), alpha.sin()],
                    curvature_per_m: 1.0 / rho_w,
                };
                let p = frame.point(&s);
                let torus = YawedTorus::new(r_t, rho_w, psi, alpha);
                let truth = torus.curvature_along_x();
                let r0 = r_t + rho_w * alpha.cos();
                assert!((p.radius_m - r0).abs() < 1e-15);
                assert!((p.lead_m - r0 * torus.phi0.sin()).abs() < 1e-12);
                assert!(
                    (p.kx_per_m / truth - 1.0).abs() < 1e-6,
                    "psi {psi}, alpha {alpha}: {} vs {truth}",
                    p.kx_per_m
                );
                let euler = euler_curvature(alpha, r0, rho_w, torus.phi0.cos() * psi.cos());
                assert!((p.kx_per_m / euler - 1.0).abs() < 1e-12);
                if psi == 0.0 {
                    assert_eq!(p.kx_per_m, alpha.cos() / r0);
                }
            }
        }
    }

    /// A hand-made gap on `pens_um.len()` lattice samples from lattice
    /// index 15000 (q = 0.75 m) at the approach `delta_um` (the gap of
    /// sample k is delta - pen_k, in micrometres), its rail's contact angle
    /// `angle(k)` at sample k (the rail's dense samples lie on the lattice,
    /// one beyond each end, so that sample k starts rail segment k + 1),
    /// and a locus whose point at sample k has x = `x(k)` (the locus runs
    /// towards -q, as a wheel's does: locus point n - 1 - k lies at sample
    /// k, whose segment ends there).
    fn hand_gap(
        pens_um: &[f64],
        delta_um: f64,
        angle: impl Fn(f64) -> f64,
        x: impl Fn(f64) -> f64,
    ) -> (VerticalGap, Vec<CurveSample>, Vec<LocusPoint>) {
        let n = pens_um.len();
        let k0 = 15000;
        let mut gap = VerticalGap::default();
        gap.set_lattice(k0, k0 + n as i64 - 1);
        for (k, pen) in pens_um.iter().enumerate() {
            gap.z_rail_m[k] = 0.0;
            gap.z_wheel_m[k] = -(delta_um - pen) * 1e-6;
            gap.locus_index[k] = n - 1 - k;
        }
        // Tangent (cos a, -sin a): contact normal (sin a, cos a), angle a.
        let rail = (-1..=n as i64)
            .map(|k| {
                let a = angle(k as f64);
                CurveSample {
                    t_m: 0.0,
                    q_m: (k0 + k) as f64 * SAMPLE_SPACING_M,
                    z_m: 0.0,
                    tangent: [a.cos(), -a.sin()],
                    curvature_per_m: 0.0,
                }
            })
            .collect();
        let locus = (0..n)
            .rev()
            .map(|k| LocusPoint {
                x_m: x(k as f64),
                q_m: gap.q_m(k),
                radius_m: 0.46,
                ..LocusPoint::default()
            })
            .collect();
        (gap, rail, locus)
    }

    /// Two regions of interpenetration 6 mm apart along q (samples of
    /// -1, then 1, 4, 9, 4, 1 um, -1 elsewhere; the rail flat, the locus at
    /// x = 0): each region's box runs from the midpoints to its outer
    /// neighbours (where the interpolated interpenetration vanishes) and
    /// along x over +-sqrt(2 r_nom pen) of its deepest sample (r_nom 0.46
    /// m: +-2.877 mm); with D_COMB 4 mm and D_SEP 8 mm they are two
    /// sub-patches with f = ((8 - 6)/(8 - 4))^0.8 (CONTACT's
    /// `combine_cpatches`). 3 mm apart they are one region (no
    /// sub-patches); 9 mm apart, f = 0.
    #[test]
    fn regions_between_d_comb_and_d_sep_are_sub_patches() {
        let bump = [1.0, 4.0, 9.0, 4.0, 1.0];
        let regions = |apart_samples: usize| {
            let n = 40 + apart_samples + 10;
            let mut pens = vec![-1.0; n];
            pens[20..25].copy_from_slice(&bump);
            // The first region ends at 24.5, the second starts at b - 0.5.
            let b = 25 + apart_samples;
            pens[b..b + 5].copy_from_slice(&bump);
            let (gap, _, locus) = hand_gap(&pens, 10.0, |_| 0.0, |_| 0.0);
            sub_patches(&locus, &gap, (0, n - 1), 10e-6, 0.46, 4e-3, 8e-3)
        };
        let dq = SAMPLE_SPACING_M;
        // 6 mm: 120 samples of 50 um.
        let sub = regions(120).expect("two sub-patches");
        assert_eq!(sub.boxes.len(), 2);
        let first = sub.boxes[0];
        let q0 = (15000.0 + 19.5) * dq;
        assert!(
            (first.q_m[0] - q0).abs() < 1e-12 && (first.q_m[1] - (q0 + 5.0 * dq)).abs() < 1e-12
        );
        let t = (2.0 * 0.46 * 9e-6f64).sqrt();
        assert!((first.x_m[0] + t).abs() < 1e-12 && (first.x_m[1] - t).abs() < 1e-12);
        let d = first.distance(&sub.boxes[1]);
        assert!((d - 6e-3).abs() < 1e-12, "{d}");
        let f = 0.5f64.powf(0.8);
        assert_eq!(sub.factors.len(), 4);
        assert_eq!((sub.factors[0], sub.factors[3]), (1.0, 1.0));
        assert!((sub.factors[1] - f).abs() < 1e-12 && sub.factors[2] == sub.factors[1]);
        assert!(regions(60).is_none(), "3 mm: one region");
        assert_eq!(regions(180).expect("9 mm").factors[1], 0.0);
    }

    /// Two regions of interpenetration 5 mm apart along q (the bumps of
    /// `regions_between_d_comb_and_d_sep_are_sub_patches`, each +-2.877 mm
    /// long along x about its locus x) are one potential contact area
    /// under CONTACT's D_SEP of 8 mm while they lie side by side (locus x
    /// -4 and +4 mm: 2.25 mm apart along x, 5.5 mm in all), and two when
    /// yaw puts them on either side of the axle (x -10 and +12 mm: 16.2
    /// mm apart along x, 17.0 mm in all), as CONTACT's `cpatch_distance`
    /// measures them; by q alone they would be one.
    #[test]
    fn potential_contact_areas_apart_along_x_are_separate_patches() {
        let bump = [1.0, 4.0, 9.0, 4.0, 1.0];
        let n = 160;
        let mut pens = vec![-1.0; n];
        pens[20..25].copy_from_slice(&bump);
        pens[125..130].copy_from_slice(&bump);
        let areas = |x_first: f64, x_second: f64| {
            let x = move |k: f64| if k < 70.0 { x_first } else { x_second };
            let (gap, _, locus) = hand_gap(&pens, 10.0, |_| 0.0, x);
            gap_intervals(&gap, &locus, 0.46, 10e-6, 8e-3)
        };
        let side_by_side = areas(-4e-3, 4e-3);
        assert_eq!(side_by_side, vec![(20, 129, 22)], "one area");
        let apart = areas(-10e-3, 12e-3);
        assert_eq!(apart, vec![(20, 24, 22), (125, 129, 127)], "two areas");
        // The same under the search's default of 1 mm: two either way.
        let (gap, _, locus) = hand_gap(&pens, 10.0, |_| 0.0, |_| 0.0);
        assert_eq!(gap_intervals(&gap, &locus, 0.46, 10e-6, 1e-3).len(), 2);
    }

    /// On a symmetric interpenetration the weighted centre is the point of
    /// smallest gap and its angle the rail's there: penetrations 0, 1, 4,
    /// 1, 0 micrometres (gaps 4, 3, 0, 3, 4 at the approach 4), weights
    /// pen^(5/2) = 0, 1, 32, 1, 0 (in 1e-15 m^(5/2)), and the rail's
    /// angle rising by 0.01 rad a sample: the centre is sample 2 (the
    /// parabola through the gaps 3, 0, 3 has its vertex there too), its
    /// angle 0.02 rad and its x that of sample 2, 2e-4 m (x = 1e-4 m a
    /// sample); to rounding of the sums (a few ulp of 0.75 m).
    #[test]
    fn a_symmetric_interpenetration_is_centred_on_its_smallest_gap() {
        let (gap, rail, locus) =
            hand_gap(&[0.0, 1.0, 4.0, 1.0, 0.0], 4.0, |k| 0.01 * k, |k| 1e-4 * k);
        let c = interpenetration_centre(&rail, &locus, &gap, (0, 4), 4e-6).unwrap();
        let (q_min, g_min) = refined_minimum(&gap, 2);
        assert_eq!((q_min, g_min), (gap.q_m(2), 0.0));
        assert!((c.q_m - q_min).abs() <= 1e-15, "{c:?}");
        assert!((c.contact_angle_rad - 0.02).abs() <= 1e-15, "{c:?}");
        assert!((c.x_m - 2e-4).abs() <= 1e-18, "{c:?}");
        assert!((c.weight / 34e-15 - 1.0).abs() <= 1e-12, "{c:?}");
        // Nothing interpenetrates at an approach below the smallest gap.
        assert_eq!(
            interpenetration_centre(&rail, &locus, &gap, (0, 4), 0.0),
            None
        );
    }

    /// On an asymmetric interpenetration the centre moves from the smallest
    /// gap towards the side that carries more of it, and the contact angle
    /// is the weighted mean of the rail's, not its angle at the centre:
    /// penetrations 0, 1, 1, 1, 1, 4, 0 micrometres at samples 0..6 (a
    /// broad shallow side and a deep edge: gaps 4, 3, 3, 3, 3, 0, 4 at the
    /// approach 4), weights 0, 1, 1, 1, 1, 32, 0, so the centre lies at
    /// (1 + 2 + 3 + 4 + 5 x 32) / 36 = 170/36 = 4.7222 samples, while the
    /// parabola through the gaps 3, 0, 4 around sample 5 has its vertex
    /// at 5 + (3 - 4) / (2 (3 - 0 + 4)) = 5 - 1/14 = 4.9286 samples: 0.206
    /// samples (10.3 micrometres) farther towards +q. With the rail's angle
    /// 1e-3 k^2 rad the centre's angle is 1e-3 (1 + 4 + 9 + 16 + 25 x 32)
    /// / 36 = 0.830/36 = 0.023056 rad, where the rail's own angle at 4.72
    /// samples lies between 0.016 and 0.025 rad, at 0.0225 (its normals
    /// interpolated between samples 4 and 5: 0.016 + 0.7222 x 0.009 to
    /// first order); x = 1e-4 k m gives 4.7222e-4 m. Tolerances: rounding
    /// of the sums.
    #[test]
    fn an_asymmetric_interpenetration_is_centred_on_its_weight() {
        let pens = [0.0, 1.0, 1.0, 1.0, 1.0, 4.0, 0.0];
        let (gap, rail, locus) = hand_gap(&pens, 4.0, |k| 1e-3 * k * k, |k| 1e-4 * k);
        let c = interpenetration_centre(&rail, &locus, &gap, (0, 6), 4e-6).unwrap();
        let dq = SAMPLE_SPACING_M;
        let at = |k: f64| gap.q_m(0) + k * dq;
        assert!((c.q_m - at(170.0 / 36.0)).abs() <= 1e-15, "{c:?}");
        let (q_min, _) = refined_minimum(&gap, 5);
        assert!((q_min - at(5.0 - 1.0 / 14.0)).abs() <= 1e-15, "{q_min}");
        assert!((q_min - c.q_m - 0.2063 * dq).abs() <= 1e-4 * dq);
        assert!((c.contact_angle_rad - 0.830 / 36.0).abs() <= 1e-15, "{c:?}");
        let (_, n) = rail_normal_at(&rail, c.q_m).unwrap();
        let at_centre = n[0].atan2(n[1]);
        // To first order in the 9 mrad between the two normals (the
        // angle of their normalised mix departs from the mix of their
        // angles at third order: 1.1e-8 rad here).
        assert!((at_centre - (0.016 + (170.0 / 36.0 - 4.0) * 0.009)).abs() <= 1e-6);
        assert!(c.contact_angle_rad - at_centre > 5e-4);
        assert!((c.x_m - 1e-4 * 170.0 / 36.0).abs() <= 1e-18, "{c:?}");
        assert!((c.weight / 36e-15 - 1.0).abs() <= 1e-12, "{c:?}");
    }

    /// The patch geometry about a centre puts its reference there: on the
    /// rail surface at the centre's q, at its x, with its contact angle
    /// and the normal of that angle (not the rail's normal there), and
    /// the lateral samples about that origin. On the Manchester
    /// benchmark's centred wheelset (y = 0, a nearly flat gap on the
    /// tread) at 20 micrometres of approach the centre lies 1.85 mm from
    /// the smallest gap, its angle 6.4 mrad from the rail's there (CONTACT's
    /// python_mbench.py case 1 reports its reference 1.38 mm from ours at
    /// the smallest gap, at its own approach; more than 1 mm is asked
    /// here). The smallest normal gap over s is 0 at the rigid position
    /// whichever the origin, to the interpolation of samples 0.05 mm
    /// apart seen along normals 6.4 mrad apart: 0.6e-10 and 1.1e-10 m here,
    /// 1e-8 asked.
    #[test]
    fn the_patch_geometry_about_a_centre_has_its_reference_there() {
        let pair = mbench_pair().unwrap();
        let mut scratch = SearchScratch::default();
        let input =
            crate::wheelrail::builtin::mbench_a22_input(0.0, None, None, WheelRailModel::Exact);
        let settings = SearchSettings::default();
        rigid_position(&pair, &input.position, &settings, &mut scratch).unwrap();
        let side = Side::Right;
        let (gap, locus) = (&scratch.gap[side.index()], &scratch.locus[side.index()]);
        let rail = pair.rail(side);
        let delta = 20e-6;
        let r = pair.wheelset().nominal_radius_m;
        let [iv] = gap_intervals(gap, locus, r, 2.0 * delta, 1e-3)[..] else {
            panic!("one patch");
        };
        let c = interpenetration_centre(rail.samples(), locus, gap, (iv.0, iv.1), delta).unwrap();
        let at_min = patch_geometry(rail, locus, gap, iv, 4e-4).unwrap();
        let about = patch_geometry_about(rail, locus, gap, iv, 4e-4, Some(&c), None).unwrap();
        assert_eq!(about.reference_m, [c.q_m, gap.rail_z_at(c.q_m)]);
        assert_eq!(about.x_m, c.x_m);
        assert_eq!(about.contact_angle_rad, c.contact_angle_rad);
        let (sa, ca) = c.contact_angle_rad.sin_cos();
        assert_eq!(about.normal, [sa, ca]);
        assert!((at_min.reference_m[0] - c.q_m).abs() > 1e-3, "{c:?}");
        // The same undeformed distance, seen from the other origin: the
        // smallest over s is the same to the samples' interpolation.
        let min = |g: &PatchGeometry| {
            g.lateral
                .iter()
                .map(|l| l.gap_m)
                .fold(f64::INFINITY, f64::min)
        };
        assert!((min(&about) - min(&at_min)).abs() < 1e-8);
        // Without a centre: the smallest gap's, bit for bit.
        assert_eq!(
            patch_geometry_about(rail, locus, gap, iv, 4e-4, None, None),
            Some(at_min)
        );
    }

    /// The wheel's surface found along the patch normal ([`WheelSurface`])
    /// agrees with the contact locus, found from the wheel's normals
    /// ([`LocusFrame::point`]): on a yawed flange (Manchester benchmark
    /// A-2.2, the steeper wheel at 8 mm, yaw 0.02 rad) the surface is
    /// parallel to x within 2 um of where the lateral samples put the
    /// wheel's closest point (measured 1.3 um; the samples lie 50 um apart
    /// in s, where that point moves millimetres along x per mm of s), and its
    /// curvature along x is Euler's k_x of the samples within 0.5 %
    /// (measured 0.11 %).
    #[test]
    fn the_wheel_surface_is_flat_along_x_on_the_contact_locus() {
        let pair = mbench_pair().unwrap();
        let mut scratch = SearchScratch::default();
        let mut input =
            crate::wheelrail::builtin::mbench_a22_input(8.0, None, None, WheelRailModel::Exact);
        input.position.yaw_rad = 0.02;
        let settings = SearchSettings::default();
        let rigid = rigid_position(&pair, &input.position, &settings, &mut scratch).unwrap();
        // The flange's patch: the steepest of either wheel.
        let (side, geom) = Side::BOTH
            .into_iter()
            .flat_map(|side| {
                let (gap, locus) = (&scratch.gap[side.index()], &scratch.locus[side.index()]);
                let rail = pair.rail(side);
                let r = pair.wheelset().nominal_radius_m;
                gap_intervals(gap, locus, r, 4e-5, 1e-3)
                    .into_iter()
                    .filter_map(move |iv| patch_geometry(rail, locus, gap, iv, 4e-4))
                    .map(move |g| (side, g))
            })
            .max_by(|a, b| a.1.contact_angle_rad.total_cmp(&b.1.contact_angle_rad))
            .unwrap();
        assert!(
            geom.contact_angle_rad > 0.9,
            "{side:?}: {}",
            geom.contact_angle_rad
        );
        let pose = rigid.pose(side, &input.position);
        let nominal = pair.wheelset().nominal_radius_m;
        let mut surface = WheelSurface::new(pair.wheel(side), nominal, &pose, &geom);
        let (mut checked, mut worst) = (0, [0.0f64; 2]);
        for l in geom.lateral.iter().filter(|l| l.s_m.abs() < 1e-3) {
            let at =
                |surface: &mut WheelSurface, x: f64| surface.normal_position(x, l.s_m).unwrap();
            let h = 1e-3;
            let (lo, mid, hi) = (
                at(&mut surface, l.dx_m - h),
                at(&mut surface, l.dx_m),
                at(&mut surface, l.dx_m + h),
            );
            let slope = (hi - lo) / (2.0 * h);
            let curvature = -(hi - 2.0 * mid + lo) / (h * h);
            // Where the surface is parallel to x, from the slope.
            worst[0] = worst[0].max((slope / curvature).abs());
            worst[1] = worst[1].max((curvature / l.kx_per_m - 1.0).abs());
            checked += 1;
        }
        eprintln!(
            "valley off the locus by {:.3e} m, curvature {:.3e}",
            worst[0], worst[1]
        );
        assert!(checked > 20, "{checked}");
        assert!(worst[0] < 2e-6, "{worst:?}");
        assert!(worst[1] < 0.005, "{worst:?}");
    }

    /// With [`ReferencePoint::InterpenetrationCentre`] a solved wheel's
    /// patch lies where the centre of its interpenetration at the wheel's
    /// final vertical approach lies: within the solver's stopping
    /// tolerances (`contact::REFERENCE_TOLERANCE`, a thousandth of the 0.2 mm
    /// element, and 1e-6 rad), here with a margin of 2 for the centre
    /// recomputed from the reported figures. Manchester benchmark A-2.2 at
    /// y = 0 (the flat gap) and 3 mm (the tread), both wheels, the roll
    /// found.
    #[test]
    fn a_solved_patch_lies_at_the_centre_of_its_interpenetration() {
        let pair = mbench_pair().unwrap();
        let cache = crate::core::cache::KernelCache::default();
        for y_mm in [0.0, 3.0] {
            let mut input = crate::wheelrail::builtin::mbench_a22_input(
                y_mm,
                None,
                None,
                WheelRailModel::Exact,
            );
            input.settings.search.reference_point = ReferencePoint::InterpenetrationCentre;
            let mut scratch = SearchScratch::default();
            let sol =
                crate::wheelrail::solve_wheelset(&pair, &input, &cache, &mut scratch).unwrap();
            let mut look = SearchScratch::default();
            rigid_position(&pair, &input.position, &input.settings.search, &mut look).unwrap();
            for w in &sol.wheels {
                let i = w.side.index();
                let (gap, locus) = (&look.gap[i], &look.locus[i]);
                let delta = w.vertical_approach_m;
                let r = pair.wheelset().nominal_radius_m;
                let [iv] = gap_intervals(gap, locus, r, delta, 1e-3)[..] else {
                    panic!("one region of interpenetration");
                };
                let rail = pair.rail(w.side).samples();
                let c = interpenetration_centre(rail, locus, gap, (iv.0, iv.1), delta).unwrap();
                let [p] = &w.patches[..] else {
                    panic!("one patch");
                };
                let tol = 2.0 * 1e-3 * input.settings.element_size_m;
                let q = w.side.sign() * p.track_y_m;
                assert!((q - c.q_m).abs() <= tol, "y {y_mm} {:?}: {q} {c:?}", w.side);
                assert!((p.track_x_m - c.x_m).abs() <= tol, "{:?}: {c:?}", w.side);
                let da = (p.contact_angle_rad - c.contact_angle_rad).abs();
                assert!(da <= 2e-6, "{:?}: {da}", w.side);
            }
        }
    }

    /// CONTACT's turning (`turn_cpatch_refangle`) with D_SEP 6 mm, D_TURN
    /// 9 mm: two patches whose facing ends lie 7.5 mm apart along q turn
    /// halfway ((9 - 7.5)/(9 - 6)) towards their weighted mean angle, the
    /// height difference of the ends counting; at 5 and 9.5 mm, across
    /// more than A_SEP, or with a patch that does not interpenetrate,
    /// nothing turns; a patch between two turns by both, each from the
    /// angles before turning.
    #[test]
    fn neighbouring_patches_turn_their_angles_as_contacts_do() {
        let turning = AngleTurning {
            distance_m: 9e-3,
            max_angle_difference_rad: 1.0,
        };
        let centre = |q_m: f64, contact_angle_rad: f64, weight: f64| InterpenetrationCentre {
            q_m,
            x_m: 0.0,
            contact_angle_rad,
            weight,
        };
        let boxed = |q0: f64, q1: f64, z0: f64, z1: f64| RegionBox {
            x_m: [-5e-3, 5e-3],
            q_m: [q0, q1],
            z_m: [z0, z1],
        };
        let pair = |gap_m: f64, dz_m: f64, inner_angle: f64| {
            // Listed inner (smaller q) first: the order is the centres'.
            vec![
                (
                    Some(centre(0.720, inner_angle, 1.0)),
                    Some(boxed(0.715, 0.725, 0.0, 0.0)),
                ),
                (
                    Some(centre(0.740, -0.1, 3.0)),
                    Some(boxed(0.725 + gap_m, 0.750, dz_m, 0.0)),
                ),
            ]
        };
        let angles = |p: &[(Option<InterpenetrationCentre>, Option<RegionBox>)]| {
            p.iter()
                .map(|(c, _)| c.map(|c| c.contact_angle_rad))
                .collect::<Vec<_>>()
        };
        let mut p = pair(7.5e-3, 0.0, -0.5);
        turn_reference_angles(&mut p, 6e-3, turning);
        let comb = (-0.5 * 1.0 - 0.1 * 3.0) / 4.0;
        let [inner, outer] = [-0.5 + 0.5 * (comb + 0.5), -0.1 + 0.5 * (comb + 0.1)];
        let got = angles(&p);
        assert!((got[0].unwrap() - inner).abs() < 1e-12, "{got:?}");
        assert!((got[1].unwrap() - outer).abs() < 1e-12, "{got:?}");
        // 4.5 mm along q and 6 mm in height: 7.5 mm apart, the same turn.
        let mut h = pair(4.5e-3, 6e-3, -0.5);
        turn_reference_angles(&mut h, 6e-3, turning);
        for (a, b) in angles(&h).into_iter().zip(&got) {
            assert!((a.unwrap() - b.unwrap()).abs() < 1e-12, "{a:?} {b:?}");
        }
        for (gap, inner_angle) in [(5e-3, -0.5), (9.5e-3, -0.5), (7.5e-3, -1.2)] {
            let mut q = pair(gap, 0.0, inner_angle);
            turn_reference_angles(&mut q, 6e-3, turning);
            assert_eq!(
                angles(&q),
                [Some(inner_angle), Some(-0.1)],
                "{gap} {inner_angle}"
            );
        }
        let mut miss = pair(7.5e-3, 0.0, -0.5);
        miss[0].0 = None;
        turn_reference_angles(&mut miss, 6e-3, turning);
        assert_eq!(angles(&miss), [None, Some(-0.1)]);
        // A third patch 7.5 mm outside the outer one: the outer one turns
        // towards both from its own angle before either turn.
        let mut three = pair(7.5e-3, 0.0, -0.5);
        three.push((
            Some(centre(0.765, 0.0, 1.0)),
            Some(boxed(0.7575, 0.770, 0.0, 0.0)),
        ));
        turn_reference_angles(&mut three, 6e-3, turning);
        let comb2 = (-0.1 * 3.0 + 0.0) / 4.0;
        let got = angles(&three);
        let outer2 = outer + 0.5 * (comb2 + 0.1);
        assert!((got[1].unwrap() - outer2).abs() < 1e-12, "{got:?}");
        assert!((got[2].unwrap() - 0.5 * comb2).abs() < 1e-12, "{got:?}");
    }
}
