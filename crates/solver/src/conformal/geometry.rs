//! Geometry of a conformal (laterally curved) contact patch: profile curves,
//! the contact reference curve with its curvilinear coordinate s and local
//! frames, the undeformed distance measured along local normals, and the
//! rigid slip projected on local tangent planes (Blanco-Lorenzo et al.,
//! Tribology International 2018, §2.2).
//!
//! # Frames and conventions
//!
//! * Global frame (x, y, z), right-handed: x the rolling direction, y
//!   lateral, z **down**, into body 1 (the rail). Both profiles are curves in
//!   the (y, z) plane x = 0, given with the rigid (first) contact point at
//!   the origin.
//! * The rail (body 1) is prismatic along x. The wheel (body 2) is a body
//!   of revolution about an axis parallel to y at height z = -R_xw, R_xw the
//!   wheel's rolling radius at the rigid contact point; its profile is its
//!   section in the plane x = 0.
//! * The contact reference curve lies midway between the profiles (each rail
//!   point is paired with the wheel point on its normal); s is the arc length
//!   along it, zero at the rigid contact point, increasing with y there.
//!   Its tangent is t(s) = (0, cos delta, sin delta) and its normal
//!   n(s) = (0, -sin delta, cos delta), pointing into the rail, so that
//!   (x, t, n) is right-handed. The mean contact angle is delta(0).
//! * Undeformed distance h(x, s): intersect both bodies with the plane x and
//!   measure the distance between the rail and the wheel point on the normal
//!   line through the reference point (x, s), positive when apart. A rigid
//!   approach d of the wheel towards the rail along n(0) closes it by
//!   d cos(delta(s) - delta(0)) (paper Eq. 1).
//! * Rigid slip: the velocity of the rail relative to the wheel divided by
//!   the rolling speed V, projected on (x, t(s)). In the frame of the contact
//!   patch the rail moves at -V e_x; the wheel turns about its axis at the
//!   rate that gives the longitudinal creepage xi at the rigid point
//!   (omega = -V (1 + xi)/R_xw about +y). The lateral creepage eta is a
//!   relative velocity eta V along t(0) and the spin phi a relative rotation
//!   rate phi V about n(0) through the origin. Points farther from the wheel
//!   axis than the rigid point (larger rolling radius) get a larger
//!   longitudinal rigid slip, and the wheel's velocity component along z,
//!   -omega x, projects on t(s) as a lateral slip: the geometric spin of
//!   conformal contact.
//! * Where the rigid velocities are taken ([`RigidSlipSurface`]): by
//!   default on the actual surfaces, as CONTACT does for its conformal and
//!   "planar with rigid slip on actual surfaces" discretisations
//!   (eve70a/CONTACT, `src/m_wr_rigslip.f90`: `wr_rigslip_wrsurf`,
//!   `project_midplane`). The rail translates, so its velocity is the same
//!   everywhere; the wheel's is that of its material point W on the normal
//!   line through (x, c(s)), on the undeformed wheel surface in the section
//!   x, with the wheel moved by the approach d along n(0). A material point
//!   keeps the rigid velocity of its undeformed position, the elastic
//!   displacement adding only the -du/dx of steady rolling. The wheel's
//!   velocity omega x (W - A) is tangent to the wheel's surface, which in
//!   the section x is inclined by about x/rho to the rail's (rho the
//!   distance from the axis); the slip that matters is the one along the
//!   surface where the two meet, so w_x is the relative velocity's
//!   component along fac t_rail + (1 - fac) t_wheel in the plane
//!   (x, n(s)) ([`midplane_rail_weight`]). Worked by hand for a wheel
//!   rolling on a plane with W at angle theta (sin theta = x/rho) and
//!   identical bodies: the relative velocity per V is
//!   (-1 + f rho cos theta, -f rho sin theta) in (x, n), f = (1 + xi)/R_xw;
//!   the surface direction is that of (1 + f rho cos theta,
//!   -f rho sin theta), so w_x = (F² - 1)/sqrt(1 + 2 F cos theta + F²)
//!   ≈ cos(theta/2) (F - 1) with F = f rho. Along x the drop of the surface,
//!   rho (1 - cos theta) ≈ x²/(2 rho), is cancelled by its inclination: a
//!   cylinder (rho = R_xw) rolling freely has no rigid slip. What remains
//!   is the rolling radius of the wheel's own surface: a sphere of radius
//!   R on a plane at omega R = V has rho = sqrt(R² - y²), so
//!   w_x ≈ -y²/(2 R²) (CONTACT's `test-rollers3` case 1).
//!   [`RigidSlipSurface::ReferenceSection`] takes instead the velocities
//!   at the reference-curve point c(s) of the section x = 0 for every x,
//!   components along x and t(s). The reference curve lies midway
//!   between the profiles, so it keeps half of the wheel's lateral drop:
//!   w_x ≈ -y²/(4 R²) for the sphere.
//! * Yaw ([`ConformalGeometry::new_yawed`]): the wheel's axis turned by
//!   psi about z, along a = (-sin psi, cos psi, 0). The wheel curve is then
//!   the curve of the wheel's points closest to the prismatic rail (the
//!   contact locus of the wheel/rail search, where the wheel's normal has
//!   no x part) projected on the plane x = 0, each point with its lead:
//!   its longitudinal position x_l relative to the origin's, and its
//!   distance sigma along its circle about the axis from the circle's
//!   lowest point (on a cone of half-angle delta, sigma ≈ R tan(delta)
//!   tan(psi): the lead of the contact point). The circle of radius
//!   rho = sqrt((z - z_a)² + sigma²) through a point turns with the yaw:
//!   moving along it by x - x_l in x moves it by (x - x_l) tan(psi) in y,
//!   and its height is z_a + sqrt(rho² - (sigma + (x - x_l)/cos psi)²).
//!   That is the wheel's section in the plane x, where its distance to the
//!   rail is measured; the patch's valley then follows x_l(s), as the
//!   planar approach's h(x, s) = h(s) + k_x (x - x_l(s))²/2 does. The axis
//!   passes through A, the centre of the origin's circle, h = sqrt(R_xw² -
//!   sigma0²) above the origin; the wheel turns at the rate f V about it
//!   that gives xi at the origin, f = (1 + xi)/(h cos psi), and its
//!   velocity -f V a x (P - A) has a lateral part f sin(psi) (z - z_a) V
//!   (the yaw's lateral creepage, varying over the patch with the local
//!   t(s)) and a vertical one -f (sin(psi) (y - y_a) + cos(psi) (x - x_a))
//!   V. Its value at the origin is part of the creepages a caller knows
//!   there ([`ConformalGeometry::wheel_rotation_creepages`]). A rolled
//!   wheel's circles lean: along a circle y changes by lean = -tan(roll)
//!   per z as well, which at the point's slope -sigma/(rho cos psi) adds
//!   -lean sigma/(rho cos psi) to the tan(psi) above ([`WheelYaw::lean`];
//!   at 4 mrad of roll on a flange, sigma = 17 mm, the valley moves by
//!   0.15 mm). Its second-order part, a drift of lean x²/(2 rho) (below a
//!   tenth of a micrometre over a patch), is left out, with or without
//!   yaw; the rigid slip's axis stays horizontal (the roll's spin at the
//!   origin comes with the creepages).

use crate::core::error::ContactError;
use crate::core::grid::Grid;
use crate::core::material::{CombinedMaterial, Material};

/// A smooth profile curve in the (y, z) plane, parametrised by arc length t
/// \[m\], through the origin at t = 0.
pub trait Curve: Send + Sync {
    /// Point (y, z) \[m\] and unit tangent (dy/dt, dz/dt) at arc length `t`.
    fn eval(&self, t: f64) -> ([f64; 2], [f64; 2]);
}

/// A circular arc (or straight line) through the origin with tangent +y
/// there. `curvature_per_m` > 0 bends it towards +z (down, into the rail).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Circle {
    /// Signed curvature towards +z [1/m].
    pub curvature_per_m: f64,
}

impl Circle {
    /// A rail profile of lateral radius `radius_m` \[m\]: convex (a crown)
    /// when positive, concave (a groove) when negative, straight when infinite.
    pub fn rail(radius_m: f64) -> Self {
        Self {
            curvature_per_m: 1.0 / radius_m,
        }
    }

    /// A wheel profile of lateral radius `radius_m` \[m\]: convex when
    /// positive, concave (hollow, wrapping a rail crown) when negative.
    pub fn wheel(radius_m: f64) -> Self {
        Self {
            curvature_per_m: -1.0 / radius_m,
        }
    }
}

impl Curve for Circle {
    fn eval(&self, t: f64) -> ([f64; 2], [f64; 2]) {
        let k = self.curvature_per_m;
        let a = k * t;
        let (sa, ca) = a.sin_cos();
        if k.abs() * t.abs() < 1e-6 {
            // Series for small angles (and straight lines).
            let p = [t - k * k * t * t * t / 6.0, 0.5 * k * t * t];
            return (p, [ca, sa]);
        }
        ([sa / k, (1.0 - ca) / k], [ca, sa])
    }
}

/// A smooth curve through given points: natural cubic splines y(t), z(t)
/// in the chord-length parameter, shifted so that t = 0 is the point
/// nearest to the origin (the rigid contact point). Accurate for point
/// spacings well below the radius of curvature.
#[derive(Debug, Clone, PartialEq)]
pub struct PointCurve {
    t: Vec<f64>,
    y: Spline,
    z: Spline,
    /// A yawed wheel's lead (x, sigma) per point ([`PointCurve::with_lead`]).
    lead: Option<[Spline; 2]>,
}

impl PointCurve {
    /// A curve through `points` (y, z) \[m\], ordered along the curve, at
    /// least 4, without repeated points.
    pub fn new(points: &[[f64; 2]], key: &str) -> Result<Self, ContactError> {
        if points.len() < 4 {
            return Err(ContactError::invalid(
                key,
                format!("needs at least 4 points, got {}", points.len()),
            ));
        }
        if let Some(i) = points
            .iter()
            .position(|p| !(p[0].is_finite() && p[1].is_finite()))
        {
            return Err(ContactError::invalid(
                key,
                format!("point {i} is not finite"),
            ));
        }
        let mut t = vec![0.0; points.len()];
        for i in 1..points.len() {
            let d = (points[i][0] - points[i - 1][0]).hypot(points[i][1] - points[i - 1][1]);
            if d <= 0.0 {
                return Err(ContactError::invalid(
                    key,
                    format!("points {} and {i} coincide", i - 1),
                ));
            }
            t[i] = t[i - 1] + d;
        }
        let nearest = (0..points.len())
            .min_by(|&a, &b| {
                let da = points[a][0].hypot(points[a][1]);
                let db = points[b][0].hypot(points[b][1]);
                da.total_cmp(&db)
            })
            .unwrap_or(0);
        let t0 = t[nearest];
        t.iter_mut().for_each(|v| *v -= t0);
        let ys: Vec<f64> = points.iter().map(|p| p[0]).collect();
        let zs: Vec<f64> = points.iter().map(|p| p[1]).collect();
        Ok(Self {
            y: Spline::natural(&t, &ys),
            z: Spline::natural(&t, &zs),
            t,
            lead: None,
        })
    }

    /// A yawed wheel's curve through `points` (y, z) \[m\], as
    /// [`PointCurve::new`], with the `lead` (x, sigma) \[m\] of each point
    /// (see the module docs, "Yaw"): its longitudinal position relative
    /// to the origin's, and its distance along its circle about the
    /// wheel's axis from the circle's lowest point, positive ahead.
    pub fn with_lead(
        points: &[[f64; 2]],
        lead: &[[f64; 2]],
        key: &str,
    ) -> Result<Self, ContactError> {
        let mut curve = Self::new(points, key)?;
        if lead.len() != points.len() {
            return Err(ContactError::invalid(
                key,
                format!("{} leads for {} points", lead.len(), points.len()),
            ));
        }
        if let Some(i) = lead
            .iter()
            .position(|l| !(l[0].is_finite() && l[1].is_finite()))
        {
            return Err(ContactError::invalid(
                key,
                format!("the lead of point {i} is not finite"),
            ));
        }
        let xs: Vec<f64> = lead.iter().map(|l| l[0]).collect();
        let sigmas: Vec<f64> = lead.iter().map(|l| l[1]).collect();
        curve.lead = Some([
            Spline::natural(&curve.t, &xs),
            Spline::natural(&curve.t, &sigmas),
        ]);
        Ok(curve)
    }

    /// The point, unit tangent (those of [`Curve::eval`]), lead (x,
    /// sigma) \[m\] and the lead's rate along the unit tangent at arc
    /// length `t`, the four splines on one knot interval; zeros without a
    /// lead.
    fn eval_with_lead(&self, t: f64) -> WheelPoint {
        let i = Spline::interval(&self.t, t);
        let (y, dy) = self.y.eval_in(&self.t, i, t);
        let (z, dz) = self.z.eval_in(&self.t, i, t);
        let n = dy.hypot(dz).max(f64::MIN_POSITIVE);
        let (lead, rate) = match &self.lead {
            Some([x, sigma]) => {
                let (xv, dx) = x.eval_in(&self.t, i, t);
                let (sv, ds) = sigma.eval_in(&self.t, i, t);
                ([xv, sv], [dx / n, ds / n])
            }
            None => ([0.0; 2], [0.0; 2]),
        };
        ([y, z], [dy / n, dz / n], lead, rate)
    }
}

impl Curve for PointCurve {
    fn eval(&self, t: f64) -> ([f64; 2], [f64; 2]) {
        let (y, dy) = self.y.eval(&self.t, t);
        let (z, dz) = self.z.eval(&self.t, t);
        let n = dy.hypot(dz).max(f64::MIN_POSITIVE);
        ([y, z], [dy / n, dz / n])
    }
}

/// A wheel curve's point (y, z) \[m\], unit tangent, lead (x, sigma) \[m\]
/// and the lead's rate along the tangent [-] at one arc length.
type WheelPoint = ([f64; 2], [f64; 2], [f64; 2], [f64; 2]);

/// Natural cubic spline values and second derivatives on given knots.
#[derive(Debug, Clone, PartialEq)]
struct Spline {
    v: Vec<f64>,
    m: Vec<f64>,
}

impl Spline {
    fn natural(t: &[f64], v: &[f64]) -> Self {
        let n = t.len();
        let mut m = vec![0.0; n];
        // Tridiagonal system for the second derivatives (Thomas algorithm).
        let mut c = vec![0.0; n];
        let mut d = vec![0.0; n];
        for i in 1..n - 1 {
            let h0 = t[i] - t[i - 1];
            let h1 = t[i + 1] - t[i];
            let a = h0 / 6.0;
            let b = (h0 + h1) / 3.0;
            let cc = h1 / 6.0;
            let r = (v[i + 1] - v[i]) / h1 - (v[i] - v[i - 1]) / h0;
            let den = b - a * c[i - 1];
            c[i] = cc / den;
            d[i] = (r - a * d[i - 1]) / den;
        }
        for i in (1..n - 1).rev() {
            m[i] = d[i] - c[i] * m[i + 1];
        }
        Self { v: v.to_vec(), m }
    }

    /// Value and derivative at `x` (linear extrapolation outside the knots).
    fn eval(&self, t: &[f64], x: f64) -> (f64, f64) {
        self.eval_in(t, Self::interval(t, x), x)
    }

    /// The knot interval [t_i, t_(i+1)] that [`Spline::eval`] takes for `x`.
    fn interval(t: &[f64], x: f64) -> usize {
        let n = t.len();
        match t.partition_point(|&k| k <= x) {
            0 => 0,
            k if k >= n => n - 2,
            k => k - 1,
        }
    }

    /// [`Spline::eval`] on the knot interval `i`.
    fn eval_in(&self, t: &[f64], i: usize, x: f64) -> (f64, f64) {
        let h = t[i + 1] - t[i];
        let a = (t[i + 1] - x) / h;
        let b = (x - t[i]) / h;
        let (m0, m1) = (self.m[i], self.m[i + 1]);
        let v = a * self.v[i]
            + b * self.v[i + 1]
            + ((a * a * a - a) * m0 + (b * b * b - b) * m1) * h * h / 6.0;
        let dv = (self.v[i + 1] - self.v[i]) / h - (3.0 * a * a - 1.0) * h * m0 / 6.0
            + (3.0 * b * b - 1.0) * h * m1 / 6.0;
        (v, dv)
    }
}

/// Longitudinal and lateral creepages and spin at the rigid contact point.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ConformalCreepages {
    /// Longitudinal creepage xi [-] (rail relative to wheel, over V).
    pub creepage_long: f64,
    /// Lateral creepage eta [-] along t(0).
    pub creepage_lat: f64,
    /// Spin phi [1/m] about n(0).
    pub spin_per_m: f64,
}

/// Where the conformal model takes the rigid velocities of the bodies
/// (see the module docs, "Where the rigid velocities are taken").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RigidSlipSurface {
    /// At the wheel's material point on the actual (undeformed, approached)
    /// wheel surface of each element, the longitudinal slip along the
    /// surface where rail and wheel meet: the wheel's own rolling radius
    /// at each point sets the slip. CONTACT's choice and the default.
    #[default]
    ActualSurface,
    /// At the reference-curve point c(s) of the section x = 0, the same for
    /// every x, slip along x: the rolling radius of the curve midway
    /// between the profiles (half the wheel's lateral drop).
    ReferenceSection,
}

impl RigidSlipSurface {
    /// The name in case files: `"actual_surface"`, `"reference_section"`.
    pub fn name(self) -> &'static str {
        match self {
            RigidSlipSurface::ActualSurface => "actual_surface",
            RigidSlipSurface::ReferenceSection => "reference_section",
        }
    }
}

/// The weight fac of the rail in the direction of the contact surface
/// along x, fac t_rail + (1 - fac) t_wheel: under the pressures the
/// surfaces meet where their normal displacements split the gap in the
/// ratio of the bodies' compliances c_i = (1 - nu_i)/G_i, so
/// fac = c_2/(c_1 + c_2), 1/2 for identical bodies, 1 for a rigid rail.
pub fn midplane_rail_weight(material: &CombinedMaterial) -> f64 {
    let compliance = |m: &Material| (1.0 - m.poisson_ratio) / m.shear_modulus_pa;
    let (c1, c2) = (compliance(&material.body1), compliance(&material.body2));
    c2 / (c1 + c2)
}

/// The geometry of one conformal contact on a curvilinear grid: x along
/// rolling, the grid's y coordinate is the curvilinear s.
#[derive(Debug, Clone, PartialEq)]
pub struct ConformalGeometry {
    /// The (x, s) grid; `grid.y_m(iy)` is s.
    pub grid: Grid,
    /// Orientation delta(s) of each lateral grid line \[rad\].
    pub delta_rad: Vec<f64>,
    /// Reference-curve point (y, z) of each lateral grid line \[m\].
    pub reference_yz_m: Vec<[f64; 2]>,
    /// Undeformed distance per element \[m\] (before the approach).
    pub gap_m: Vec<f64>,
    /// cos(delta(s) - delta(0)) per element: the approach closes the gap
    /// by d times this.
    pub approach_weight: Vec<f64>,
    /// Per element: the wheel's surface point (y, z) \[m\] on the normal
    /// line through (x, c(s)), in the section x of the unloaded wheel (axis
    /// at z = -R_xw).
    pub wheel_point_yz_m: Vec<[f64; 2]>,
    /// Per element: the rate of change (dy/dd, dz/dd) [-] of that point with
    /// the approach d, the wheel moved by d along n(0) (its point on the
    /// normal line slides along the profile by -d sin(delta - delta0)).
    pub wheel_point_per_approach: Vec<[f64; 2]>,
    /// Wheel rolling radius at the rigid contact point \[m\]: its distance
    /// from the wheel's axis.
    pub wheel_rolling_radius_m: f64,
    /// Mean contact angle delta(0) \[rad\].
    pub mean_contact_angle_rad: f64,
    /// Yaw of the wheel's axis about z \[rad\]: the axis runs along
    /// (-sin psi, cos psi, 0) (see the module docs, "Yaw").
    pub yaw_rad: f64,
    /// The centre of the wheel's circle through the origin (x, y, z) \[m\],
    /// a point of its axis: (0, 0, -R_xw) without yaw.
    pub wheel_axis_point_m: [f64; 3],
}

/// How the wheel of [`ConformalGeometry::new_yawed`] is turned (see the
/// module docs, "Yaw").
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WheelYaw {
    /// Yaw of the wheel's axis about z \[rad\], within (-pi/2, pi/2).
    pub yaw_rad: f64,
    /// Lean of the wheel's circles from the roll [-]: the change of y per
    /// change of z along a circle's plane at its lowest point, -tan(roll)
    /// cos(psi) for the axle (-sin psi cos roll, cos psi cos roll, sin
    /// roll).
    pub lean: f64,
}

/// Arc-length sampling step of the reference curve relative to the grid's s step.
const REFERENCE_SAMPLES_PER_ELEMENT: usize = 8;

/// Finds t with (P(t) - c) x n = 0 (the curve point on the line c + lambda n)
/// by Newton's method from `t0`; returns (t, lambda). Where Newton's steps
/// do not settle (they cycle about a root where the curve's tangent turns
/// sharply, as a wheel's contact locus does at a steep flange) but two of
/// its iterates lie on both sides of the line, the root between them is
/// found by bisection.
fn intersect_normal(
    eval: &dyn Fn(f64) -> ([f64; 2], [f64; 2]),
    c: [f64; 2],
    n: [f64; 2],
    t0: f64,
) -> Option<(f64, f64)> {
    let side = |t: f64| {
        let (p, d) = eval(t);
        ((p[0] - c[0]) * n[1] - (p[1] - c[1]) * n[0], d, p)
    };
    let along = |p: [f64; 2]| (p[0] - c[0]) * n[0] + (p[1] - c[1]) * n[1];
    // The closest iterates seen on either side of the line: (t, f).
    let mut below: Option<(f64, f64)> = None;
    let mut above: Option<(f64, f64)> = None;
    let mut t = t0;
    for _ in 0..50 {
        let (f, d, _) = side(t);
        if f < 0.0 && below.is_none_or(|(_, g)| f > g) {
            below = Some((t, f));
        } else if f > 0.0 && above.is_none_or(|(_, g)| f < g) {
            above = Some((t, f));
        }
        let df = d[0] * n[1] - d[1] * n[0];
        if df.abs() < 1e-12 {
            break;
        }
        let step = f / df;
        t -= step;
        if step.abs() < 1e-15 + 1e-13 * t.abs() {
            return Some((t, along(side(t).2)));
        }
    }
    let (Some((mut lo, _)), Some((mut hi, _))) = (below, above) else {
        return None;
    };
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        let (f, _, p) = side(mid);
        if !f.is_finite() {
            return None;
        }
        if f == 0.0 || (hi - lo).abs() < 1e-15 + 1e-13 * mid.abs() {
            return Some((mid, along(p)));
        }
        if f < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    None
}

impl ConformalGeometry {
    /// Arc length of the rail profile on each side of the origin that
    /// [`ConformalGeometry::new`] samples for `grid` \[m\]. The curves handed
    /// to it must reach that far (the wheel a little further: its points on
    /// the rail's normals lie beyond the rail's where the profiles diverge).
    pub fn reach_m(grid: &Grid) -> f64 {
        let s_lo = grid.y_m(0) - grid.dy_m;
        let s_hi = grid.y_m(grid.ny - 1) + grid.dy_m;
        s_lo.abs().max(s_hi.abs()) * 1.2 + grid.dy_m
    }

    /// Builds the geometry of `rail` and `wheel` profiles on `grid` (x, s).
    pub fn new(
        rail: &dyn Curve,
        wheel: &dyn Curve,
        wheel_rolling_radius_m: f64,
        grid: Grid,
    ) -> Result<Self, ContactError> {
        let no_lead = |t: f64| {
            let (p, d) = wheel.eval(t);
            (p, d, [0.0; 2], [0.0; 2])
        };
        let yaw = WheelYaw::default();
        Self::build(rail, wheel, &no_lead, yaw, wheel_rolling_radius_m, grid)
    }

    /// Builds the geometry of `rail` and a wheel yawed by `yaw_rad` \[rad\]
    /// on `grid` (x, s): `wheel` is the curve of the wheel's points closest
    /// to the rail, with their lead ([`PointCurve::with_lead`]; see the
    /// module docs, "Yaw"). Without a lead and at yaw 0 it is
    /// [`ConformalGeometry::new`] bit for bit.
    pub fn new_yawed(
        rail: &dyn Curve,
        wheel: &PointCurve,
        yaw: WheelYaw,
        wheel_rolling_radius_m: f64,
        grid: Grid,
    ) -> Result<Self, ContactError> {
        crate::core::error::require_finite("geometry.yaw_rad", yaw.yaw_rad)?;
        crate::core::error::require_finite("geometry.lean", yaw.lean)?;
        if yaw.yaw_rad.abs() >= 0.5 * std::f64::consts::PI {
            return Err(ContactError::invalid(
                "geometry.yaw_rad",
                format!("{} rad: must lie within (-pi/2, pi/2)", yaw.yaw_rad),
            ));
        }
        let lead = |t: f64| wheel.eval_with_lead(t);
        Self::build(rail, wheel, &lead, yaw, wheel_rolling_radius_m, grid)
    }

    fn build(
        rail: &dyn Curve,
        wheel: &dyn Curve,
        wheel_with_lead: &dyn Fn(f64) -> WheelPoint,
        yaw: WheelYaw,
        wheel_rolling_radius_m: f64,
        grid: Grid,
    ) -> Result<Self, ContactError> {
        let WheelYaw { yaw_rad, lean } = yaw;
        crate::core::error::require_positive(
            "geometry.wheel_rolling_radius_m",
            wheel_rolling_radius_m,
        )?;
        let (nx, ny) = (grid.nx, grid.ny);
        // 1. Reference curve: midpoints between each rail point and the wheel
        // point on its normal, sampled finely on both sides of the origin.
        let step = grid.dy_m / REFERENCE_SAMPLES_PER_ELEMENT as f64;
        let reach = Self::reach_m(&grid);
        let nsamp = (2.0 * reach / step).ceil() as usize + 1;
        let mut mids: Vec<[f64; 2]> = Vec::with_capacity(nsamp);
        let mut tw = 0.0;
        let t_start = -reach;
        let wheel_at = |t: f64| wheel.eval(t);
        let mut k0 = 0;
        for k in 0..nsamp {
            let t = t_start + k as f64 * step;
            let (p, d) = rail.eval(t);
            let n = [-d[1], d[0]];
            if k == 0 {
                tw = t;
            }
            let (t_hit, lam) = intersect_normal(&wheel_at, p, n, tw).ok_or_else(|| {
                ContactError::invalid(
                    "geometry",
                    format!(
                        "the wheel profile does not cross the rail normal at rail arc length {t:.4e} m"
                    ),
                )
            })?;
            tw = t_hit;
            mids.push([p[0] + 0.5 * lam * n[0], p[1] + 0.5 * lam * n[1]]);
            if t <= 0.0 {
                k0 = k;
            }
        }
        // Arc length along the midpoints, zero at the origin sample.
        let mut arc = vec![0.0; nsamp];
        for k in 1..nsamp {
            arc[k] = arc[k - 1] + (mids[k][0] - mids[k - 1][0]).hypot(mids[k][1] - mids[k - 1][1]);
        }
        // The origin lies between samples k0 and k0 + 1 (t = 0 exactly when step divides).
        let t0 = t_start + k0 as f64 * step;
        let a0 = arc[k0] + (arc[k0 + 1] - arc[k0]) * (-t0 / step);
        arc.iter_mut().for_each(|a| *a -= a0);
        let reference = |s: f64| -> ([f64; 2], f64) {
            let k = arc.partition_point(|&a| a <= s).clamp(1, nsamp - 1) - 1;
            let f = (s - arc[k]) / (arc[k + 1] - arc[k]);
            let p = [
                mids[k][0] + f * (mids[k + 1][0] - mids[k][0]),
                mids[k][1] + f * (mids[k + 1][1] - mids[k][1]),
            ];
            // Tangent angle from central differences around the point.
            let (ka, kb) = (k.saturating_sub(1), (k + 2).min(nsamp - 1));
            let d0 = [mids[k + 1][0] - mids[ka][0], mids[k + 1][1] - mids[ka][1]];
            let d1 = [mids[kb][0] - mids[k][0], mids[kb][1] - mids[k][1]];
            let a_0 = d0[1].atan2(d0[0]);
            let a_1 = d1[1].atan2(d1[0]);
            (p, a_0 + f * (a_1 - a_0))
        };
        let (_, delta0) = reference(0.0);
        // 2. Per lateral line: frame and intersections.
        let mut delta_rad = vec![0.0; ny];
        let mut reference_yz_m = vec![[0.0; 2]; ny];
        let n = grid.len();
        let mut gap_m = vec![0.0; n];
        let mut approach_weight = vec![0.0; n];
        let mut wheel_point_yz_m = vec![[0.0; 2]; n];
        let mut wheel_point_per_approach = vec![[0.0; 2]; n];
        // The origin's circle: its lowest point lies sigma0 behind it
        // along the circle, the axis h below... above it (z down).
        let (sin_yaw, cos_yaw) = yaw_rad.sin_cos();
        let tan_yaw = sin_yaw / cos_yaw;
        let sigma0 = wheel_with_lead(0.0).2[1];
        let h = if sigma0 == 0.0 {
            wheel_rolling_radius_m
        } else {
            let r = wheel_rolling_radius_m;
            (r * r - sigma0 * sigma0).max(0.0).sqrt()
        };
        let z_axis = -h;
        let wheel_axis_point_m = [-sigma0 * cos_yaw, -sigma0 * sin_yaw, z_axis];
        let (mut tr, mut tw0) = (grid.y_m(0), grid.y_m(0));
        for iy in 0..ny {
            let s = grid.y_m(iy);
            let (c, delta) = reference(s);
            delta_rad[iy] = delta;
            reference_yz_m[iy] = c;
            let nv = [-delta.sin(), delta.cos()];
            let fail = |what: &str| {
                ContactError::invalid(
                    "geometry",
                    format!("the {what} profile does not cross the normal at s = {s:.4e} m"),
                )
            };
            let (t_r, lam_r) =
                intersect_normal(&|t| rail.eval(t), c, nv, tr).ok_or_else(|| fail("rail"))?;
            tr = t_r;
            let (t_w, _) = intersect_normal(&wheel_at, c, nv, tw0).ok_or_else(|| fail("wheel"))?;
            tw0 = t_w;
            let mut tx = t_w;
            for ix in 0..nx {
                let x = grid.x_m(ix);
                // The wheel's section in the plane x: every profile point
                // keeps its distance rho from the axis, rho² = (z -
                // z_axis)² + sigma², its circle turned by the yaw (along
                // it y changes by tan psi per x, the arc from the lowest
                // point by 1/cos psi per x).
                let section = |t: f64| -> ([f64; 2], [f64; 2]) {
                    let (p, d, [xl, sl], [dxl, dsl]) = wheel_with_lead(t);
                    let rho = p[1] - z_axis;
                    let w = sl + (x - xl) / cos_yaw;
                    let dw = dsl - dxl / cos_yaw;
                    let q = (rho * rho + sl * sl - w * w).max(0.0).sqrt();
                    let dz = if q > 0.0 {
                        (rho * d[1] + sl * dsl - w * dw) / q
                    } else {
                        0.0
                    };
                    // y along the circle: tan psi per x, and the lean times
                    // the circle's slope -sigma/(rho cos psi) there.
                    let slope = tan_yaw - lean * sl / (rho * cos_yaw);
                    let dslope = -lean * (dsl * rho - sl * d[1]) / (rho * rho * cos_yaw);
                    let dy = d[0] - dxl * slope + (x - xl) * dslope;
                    let norm = dy.hypot(dz);
                    (
                        [p[0] + (x - xl) * slope, z_axis + q],
                        [dy / norm, dz / norm],
                    )
                };
                let (t_x, lam_w) =
                    intersect_normal(&section, c, nv, tx).ok_or_else(|| fail("wheel"))?;
                tx = t_x;
                let i = grid.index(ix, iy);
                gap_m[i] = lam_r - lam_w;
                approach_weight[i] = (delta - delta0).cos();
                wheel_point_yz_m[i] = [c[0] + lam_w * nv[0], c[1] + lam_w * nv[1]];
                // Moving the wheel by d n(0) moves the normal line by
                // -d sin(delta - delta0) along t(s) relative to it: the
                // point slides along the section's tangent tau by that over
                // tau . t(s).
                let (_, tau) = section(t_x);
                let along = tau[0] * delta.cos() + tau[1] * delta.sin();
                let slide = if along.abs() > f64::EPSILON {
                    -(delta - delta0).sin() / along
                } else {
                    0.0
                };
                wheel_point_per_approach[i] = [slide * tau[0], slide * tau[1]];
            }
        }
        Ok(Self {
            grid,
            delta_rad,
            reference_yz_m,
            gap_m,
            approach_weight,
            wheel_point_yz_m,
            wheel_point_per_approach,
            wheel_rolling_radius_m,
            mean_contact_angle_rad: delta0,
            yaw_rad,
            wheel_axis_point_m,
        })
    }

    /// The lateral creepage along t(0) \[-\] and the spin about n(0)
    /// \[1/m\] that the rigid slip's own wheel rotation makes at the origin
    /// for longitudinal creepage `creepage_long` (see
    /// [`ConformalGeometry::rigid_slip`]): those of the wheel's rotation
    /// alone, without the creepages handed to it. A caller that has the
    /// creepages of all motions at the origin hands on the rest.
    pub fn wheel_rotation_creepages(&self, creepage_long: f64) -> (f64, f64) {
        let d0 = self.mean_contact_angle_rad;
        let [_, _, z_axis] = self.wheel_axis_point_m;
        let (w_y, w_z) = self.wheel_rotation_slip(creepage_long, [0.0; 3]);
        let lateral = w_y * d0.cos() + w_z * d0.sin();
        // The rotation -(1 + xi)/(h cos psi) V (-sin psi, cos psi, 0)
        // of the wheel relative to the rail, along n(0).
        let spin = -(1.0 + creepage_long) * d0.sin() / -z_axis;
        (lateral, spin)
    }

    /// The (y, z) parts of the rigid slip per V of the rail relative to
    /// the wheel's rotation alone at the wheel point `p` (x, y, z) \[m\]
    /// (the rail's own velocity, -e_x, has none).
    fn wheel_rotation_slip(&self, creepage_long: f64, p: [f64; 3]) -> (f64, f64) {
        let (fs, fc) = self.rotation_rates(creepage_long);
        let [xa, ya, za] = self.wheel_axis_point_m;
        (fs * (p[2] - za), -(fs * (p[1] - ya) + fc * (p[0] - xa)))
    }

    /// The wheel's rotation rate per V, f = (1 + xi)/(h cos psi) [1/m]
    /// with h the axis' height above the origin (the rate that gives the
    /// longitudinal creepage xi at the origin), times sin psi and cos psi.
    fn rotation_rates(&self, creepage_long: f64) -> (f64, f64) {
        let (sin_yaw, cos_yaw) = self.yaw_rad.sin_cos();
        let h = -self.wheel_axis_point_m[2];
        let f = (1.0 + creepage_long) / (h * cos_yaw);
        (f * sin_yaw, f * cos_yaw)
    }

    /// Rigid slip (w_x, w_s) per element [-] for creepages at the rigid
    /// point, with the rigid velocities taken on `surface`. With
    /// [`RigidSlipSurface::ActualSurface`] the wheel is moved by
    /// `approach_m` \[m\] along n(0), and the longitudinal slip is taken
    /// along the contact surface's direction in the plane (x, n(s)), the
    /// direction of the velocities fac v_rail + (1 - fac) v_wheel with
    /// `rail_weight` = fac (see [`midplane_rail_weight`]).
    pub fn rigid_slip(
        &self,
        c: &ConformalCreepages,
        surface: RigidSlipSurface,
        approach_m: f64,
        rail_weight: f64,
        wx: &mut [f64],
        ws: &mut [f64],
    ) {
        let g = &self.grid;
        let (_, fc) = self.rotation_rates(c.creepage_long);
        let z_axis = self.wheel_axis_point_m[2];
        let d0 = self.mean_contact_angle_rad;
        let (t0, n0) = ([d0.cos(), d0.sin()], [-d0.sin(), d0.cos()]);
        for iy in 0..g.ny {
            let d = self.delta_rad[iy];
            let t = [d.cos(), d.sin()];
            for ix in 0..g.nx {
                let i = g.index(ix, iy);
                let x = g.x_m(ix);
                // The wheel point whose rigid velocity counts, in the frame
                // of the wheel (axis at z_axis; the approach moves the axis
                // with it, and the spin's n(0) x d n(0) vanishes).
                let [py, pz] = match surface {
                    RigidSlipSurface::ReferenceSection => self.reference_yz_m[iy],
                    RigidSlipSurface::ActualSurface => {
                        let [y0, z0] = self.wheel_point_yz_m[i];
                        let [dy, dz] = self.wheel_point_per_approach[i];
                        [y0 + approach_m * dy, z0 + approach_m * dz]
                    }
                };
                // Wheel rotation -f V a about the axis through A,
                // a = (-sin psi, cos psi, 0): w = -e_x + f a x (P - A).
                let (wy, wz) = self.wheel_rotation_slip(c.creepage_long, [x, py, pz]);
                let mut w = [-1.0 + fc * (pz - z_axis), wy, wz];
                // Lateral creepage along t(0).
                w[1] += c.creepage_lat * t0[0];
                w[2] += c.creepage_lat * t0[1];
                // Spin about n(0) = (0, n0y, n0z) through the origin: phi n0 x P.
                let p = [x, py, pz];
                let nn = [0.0, n0[0], n0[1]];
                let cross = [
                    nn[1] * p[2] - nn[2] * p[1],
                    nn[2] * p[0] - nn[0] * p[2],
                    nn[0] * p[1] - nn[1] * p[0],
                ];
                for k in 0..3 {
                    w[k] += c.spin_per_m * cross[k];
                }
                ws[i] = w[1] * t[0] + w[2] * t[1];
                wx[i] = match surface {
                    RigidSlipSurface::ReferenceSection => w[0],
                    RigidSlipSurface::ActualSurface => {
                        // Rail velocity -e_x, wheel velocity -e_x - w (per
                        // V): the contact surface runs along
                        // -(fac v_rail + (1 - fac) v_wheel) = e_x + (1 - fac) w,
                        // taken in the plane (x, n(s)).
                        let wn = w[2] * t[0] - w[1] * t[1];
                        let k = 1.0 - rail_weight;
                        let (mx, mn) = (1.0 + k * w[0], k * wn);
                        (w[0] * mx + wn * mn) / mx.hypot(mn)
                    }
                };
            }
        }
    }

    /// Total contact angle variation over the loaded elements \[rad\]:
    /// max delta - min delta over the lateral lines with p_n > 0.
    pub fn contact_angle_variation_rad(&self, pn: &[f64]) -> f64 {
        let g = &self.grid;
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for iy in 0..g.ny {
            if (0..g.nx).any(|ix| pn[g.index(ix, iy)] > 0.0) {
                lo = lo.min(self.delta_rad[iy]);
                hi = hi.max(self.delta_rad[iy]);
            }
        }
        if hi >= lo {
            hi - lo
        } else {
            0.0
        }
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    fn grid(n: usize, half_x: f64, half_s: f64) -> Grid {
        Grid::centered(n, n, 2.0 * half_x, 2.0 * half_s).unwrap()
    }

    /// The rigid slip (w_x, w_s) of identical bodies at longitudinal
    /// creepage `xi` with the wheel moved by `approach_m`.
    fn slip(
        geo: &ConformalGeometry,
        xi: f64,
        surface: RigidSlipSurface,
        approach_m: f64,
    ) -> (Vec<f64>, Vec<f64>) {
        let n = geo.grid.len();
        let (mut wx, mut ws) = (vec![0.0; n], vec![0.0; n]);
        let creep = ConformalCreepages {
            creepage_long: xi,
            ..Default::default()
        };
        geo.rigid_slip(&creep, surface, approach_m, 0.5, &mut wx, &mut ws);
        (wx, ws)
    }

    /// Newton's steps on a curve whose crossing of the line is a cusp of
    /// its parameter (x = sign(t) sqrt|t|: each step lands at -t) cycle
    /// for ever; the two sides they visit bracket the crossing, which
    /// bisection finds. Where the steps settle, they give the crossing as
    /// before (a straight curve: one step).
    #[test]
    fn intersect_normal_bisects_where_newton_cycles() {
        let cusp = |t: f64| ([t.signum() * t.abs().sqrt(), 1.0], [1.0, 0.0]);
        let (t, lambda) = intersect_normal(&cusp, [0.0, 0.0], [0.0, 1.0], 0.25).unwrap();
        assert!(t.abs() < 1e-12, "t {t}");
        assert_eq!(lambda, 1.0);
        let line = |t: f64| ([t, 2.0], [1.0, 0.0]);
        let (t, lambda) = intersect_normal(&line, [0.5, 0.0], [0.0, 1.0], 3.0).unwrap();
        assert_eq!((t, lambda), (0.5, 2.0));
        // No crossing on either side: none.
        let away = |t: f64| ([t * t + 1.0, 0.0], [1.0, 0.0]);
        assert!(intersect_normal(&away, [0.0, 0.0], [0.0, 1.0], 1.0).is_none());
    }

    #[test]
    fn point_curve_through_circle_samples_stays_on_the_circle() {
        let r = 0.01;
        let c = Circle::rail(r);
        let pts: Vec<[f64; 2]> = (-200..=200).map(|k| c.eval(k as f64 * 1e-4).0).collect();
        let pc = PointCurve::new(&pts, "rail").unwrap();
        for k in -40..=40 {
            let (q, e) = pc.eval(k as f64 * 3.7e-4);
            // Distance to the centre (0, r) and tangent perpendicular to the radius.
            let (dy, dz) = (q[0], q[1] - r);
            assert!((dy.hypot(dz) - r).abs() < 1e-9, "{k}");
            assert!((dy * e[0] + dz * e[1]).abs() < 1e-5 * r, "{k}");
        }
        assert!(PointCurve::new(&pts[..3], "rail").is_err());
        let mut dup = pts.clone();
        dup[5] = dup[4];
        assert!(PointCurve::new(&dup, "rail").is_err());
    }

    /// A straight wheel profile (a cylinder of radius `r`) yawed by `psi`
    /// on a plane, with the lead of its closest points: at lateral y they
    /// lie at x = -y tan(psi), at the lowest points of their circles.
    fn yawed_cylinder(r: f64, psi: f64, g: Grid) -> ConformalGeometry {
        let pts: Vec<[f64; 2]> = (-300..=300).map(|k| [k as f64 * 5e-5, 0.0]).collect();
        let lead: Vec<[f64; 2]> = pts.iter().map(|p| [-p[0] * psi.tan(), 0.0]).collect();
        let wheel = PointCurve::with_lead(&pts, &lead, "wheel").unwrap();
        let rail = Circle::rail(f64::INFINITY);
        let yaw = WheelYaw {
            yaw_rad: psi,
            lean: 0.0,
        };
        ConformalGeometry::new_yawed(&rail, &wheel, yaw, r, g).unwrap()
    }

    #[test]
    fn a_yawed_cylinder_on_a_plane_has_its_closed_form_gap_and_lateral_slip() {
        // By hand: the cylinder's surface lies sqrt(r² - u²) below its
        // axis, u = x cos(psi) + y sin(psi) the horizontal distance from
        // the axis' vertical plane, so h = r - sqrt(r² - u²). It turns at
        // f V = (1 + xi) V/(r cos psi) about (-sin psi, cos psi, 0): the
        // rail moves relative to its point sqrt(r² - u²) below the axis
        // laterally by f sin(psi) sqrt(r² - u²) per V, (1 + xi) tan(psi)
        // at the origin.
        let (r, psi, xi) = (0.46, 0.02, 1e-3);
        let g = grid(21, 5e-3, 5e-3);
        let geo = yawed_cylinder(r, psi, g);
        let n = g.len();
        let (mut wx, mut ws) = (vec![0.0; n], vec![0.0; n]);
        let creep = ConformalCreepages {
            creepage_long: xi,
            ..Default::default()
        };
        geo.rigid_slip(
            &creep,
            RigidSlipSurface::ActualSurface,
            0.0,
            0.5,
            &mut wx,
            &mut ws,
        );
        for iy in 0..g.ny {
            assert!(geo.delta_rad[iy].abs() < 1e-12);
            for ix in 0..g.nx {
                let (x, s) = (g.x_m(ix), g.y_m(iy));
                let i = g.index(ix, iy);
                let u = x * psi.cos() + s * psi.sin();
                let q = (r * r - u * u).sqrt();
                let want = r - q;
                let got = geo.gap_m[i];
                assert!(
                    (got - want).abs() < 1e-14 + 1e-9 * want,
                    "({x}, {s}): {got} vs {want}"
                );
                let want_s = (1.0 + xi) * psi.tan() * q / r;
                assert!(
                    (ws[i] - want_s).abs() < 1e-14,
                    "({x}, {s}): {} vs {want_s}",
                    ws[i]
                );
            }
        }
        let (lat, spin) = geo.wheel_rotation_creepages(xi);
        assert!((lat - (1.0 + xi) * psi.tan()).abs() < 1e-16);
        assert_eq!(spin, 0.0);
        // Without yaw the lead vanishes and the geometry is that of
        // `new`, bit for bit.
        let plain = yawed_cylinder(r, 0.0, g);
        let straight = Circle::rail(f64::INFINITY);
        assert_eq!(
            plain,
            ConformalGeometry::new(&straight, &straight, r, g).unwrap()
        );
    }

    #[test]
    fn gap_of_non_conformal_circles_is_the_quadratic_form() {
        // Far from conformal (small angles), h = A x² + B s² with
        // A = 1/(2 R_xw), B = (1/R_r + 1/R_w)/2 (paper Eq. 3), to third order.
        let (rr, rw, rx) = (0.3, -0.5, 0.46);
        let g = grid(16, 2e-3, 2e-3);
        let geo = ConformalGeometry::new(&Circle::rail(rr), &Circle::wheel(rw), rx, g).unwrap();
        let (a, b) = (0.5 / rx, 0.5 * (1.0 / rr + 1.0 / rw));
        for iy in 0..g.ny {
            for ix in 0..g.nx {
                let (x, s) = (g.x_m(ix), g.y_m(iy));
                let want = a * x * x + b * s * s;
                let got = geo.gap_m[g.index(ix, iy)];
                assert!(
                    (got - want).abs() < 2e-3 * want + 1e-12,
                    "({x}, {s}): {got} vs {want}"
                );
            }
        }
        assert!(geo.mean_contact_angle_rad.abs() < 1e-12);
    }

    #[test]
    fn conformal_circles_have_the_papers_cosine_law() {
        // Paper Eq. 2: h ≈ A cos(alpha) x² + B s² for constant curvatures. The
        // x part is exact to O(x⁴): the wheel section drops by x²/(2 rho) at
        // distance rho from the axis, seen along the normal as cos(delta)
        // times that. The s part of two circles through the origin with
        // centres e = |R_w| - R_r apart is e (1 - cos(s/r)) (B s² to first
        // order), r the mean radius, which also gives delta = s/r.
        let (rr, rw, rx) = (0.010, -0.0101, 0.5);
        let g = grid(20, 3e-3, 9e-3);
        let geo = ConformalGeometry::new(&Circle::rail(rr), &Circle::wheel(rw), rx, g).unwrap();
        let r = 0.5 * (rr + rw.abs());
        let e = rw.abs() - rr;
        for iy in 0..g.ny {
            let s = g.y_m(iy);
            let d = geo.delta_rad[iy];
            assert!(
                (d - s / r).abs() < 2e-3 * (s / r).abs() + 1e-9,
                "delta {d} at s {s}"
            );
            let h0 = e * (1.0 - (s / r).cos());
            let z = geo.reference_yz_m[iy][1];
            for ix in 0..g.nx {
                let x = g.x_m(ix);
                let want = h0 + d.cos() * x * x / (2.0 * (rx + z));
                let got = geo.gap_m[g.index(ix, iy)];
                assert!(
                    (got - want).abs() < 1e-2 * want + 1e-10,
                    "({x}, {s}): {got} vs {want}"
                );
            }
        }
    }

    #[test]
    fn rigid_slip_shows_geometric_spin() {
        // Concave wheel on a convex rail: the lateral parts of the patch lie
        // farther from the wheel axis, so w_x grows like z/R_xw, and the
        // vertical wheel velocity -x/R_xw projects on t(s) as a spin-like
        // lateral slip -x sin(delta)/R_xw.
        let (rr, rw, rx) = (0.010, -0.0101, 0.5);
        let g = grid(10, 3e-3, 8e-3);
        let geo = ConformalGeometry::new(&Circle::rail(rr), &Circle::wheel(rw), rx, g).unwrap();
        let xi = -1.5e-3;
        let (wx, ws) = slip(&geo, xi, RigidSlipSurface::ReferenceSection, 0.0);
        for iy in 0..g.ny {
            for ix in 0..g.nx {
                let i = g.index(ix, iy);
                let [_, z] = geo.reference_yz_m[iy];
                let x = g.x_m(ix);
                let d = geo.delta_rad[iy];
                let want_x = -1.0 + (1.0 + xi) * (z + rx) / rx;
                let want_s = -(1.0 + xi) * x / rx * d.sin();
                assert!((wx[i] - want_x).abs() < 1e-12);
                assert!((ws[i] - want_s).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn a_cylinder_rolling_freely_on_a_plane_has_no_rigid_slip() {
        // A wheel of constant radius R (straight profile) on a plane: its
        // surface in the section x lies x²/(2R) above the rail, but it
        // moves along itself, inclined by theta = asin(x/R); along the
        // contact surface (half-way, identical bodies) the slip is, by
        // hand with F = 1 + xi the wheel's speed over V, the relative
        // velocity (-1 + F cos theta, -F sin theta) along the direction of
        // (1 + F cos theta, -F sin theta):
        // (F² - 1)/sqrt(1 + 2 F cos theta + F²), 0 at omega R = V
        // (F = 1). The x component alone would be -x²/(2R²).
        let r = 0.1;
        let g = grid(21, 5e-3, 5e-3);
        let straight = Circle::rail(f64::INFINITY);
        let geo = ConformalGeometry::new(&straight, &straight, r, g).unwrap();
        for xi in [0.0, 2e-3] {
            let (wx, ws) = slip(&geo, xi, RigidSlipSurface::ActualSurface, 1e-5);
            for iy in 0..g.ny {
                for ix in 0..g.nx {
                    let i = g.index(ix, iy);
                    let theta = (g.x_m(ix) / r).asin();
                    let f = 1.0 + xi;
                    let want = (f * f - 1.0) / (1.0 + 2.0 * f * theta.cos() + f * f).sqrt();
                    assert!((wx[i] - want).abs() < 1e-14, "{} vs {want}", wx[i]);
                    assert!(ws[i].abs() < 1e-14);
                }
            }
        }
    }

    #[test]
    fn rigid_slip_of_a_sphere_rolling_on_a_plane_follows_its_rolling_radius() {
        // A sphere of radius R (profile radius R about an axis R above the
        // plane) rolling at omega R = V. Its material point at lateral y
        // is rho = sqrt(R² - y²) from the axis, at angle theta
        // (sin theta = x/rho) in its section: by hand (as for the
        // cylinder, with F = rho/R) w_x = (F² - 1)/sqrt(1 + 2 F cos theta
        // + F²) ≈ cos(theta/2) (F - 1) ≈ -y²/(2 R²), whatever x; the
        // velocity -omega x along z gives w_s = -x sin(delta)/R. The
        // reference section keeps the midway curve's drop -s²/(4 R):
        // w_x ≈ -s²/(4 R²).
        let r = 0.1;
        let g = grid(21, 5e-3, 5e-3);
        let geo =
            ConformalGeometry::new(&Circle::rail(f64::INFINITY), &Circle::wheel(r), r, g).unwrap();
        let (wx, ws) = slip(&geo, 0.0, RigidSlipSurface::ActualSurface, 0.0);
        let (rx, rs) = slip(&geo, 0.0, RigidSlipSurface::ReferenceSection, 0.0);
        for iy in 0..g.ny {
            let s = g.y_m(iy);
            let d = geo.delta_rad[iy];
            for ix in 0..g.nx {
                let i = g.index(ix, iy);
                let x = g.x_m(ix);
                let [y, _] = geo.wheel_point_yz_m[i];
                let rho = (r * r - y * y).sqrt();
                let theta = (x / rho).asin();
                // (n(s) leans by delta ≈ -s/(2R) from z: a relative
                // change of order delta² in the projection.)
                let f = rho / r;
                let hand = (f * f - 1.0) / (1.0 + 2.0 * f * theta.cos() + f * f).sqrt();
                assert!(
                    (wx[i] - hand).abs() < 1e-3 * hand.abs() + 1e-12,
                    "({x}, {s}): {} vs {hand}",
                    wx[i]
                );
                let simple = -s * s / (2.0 * r * r);
                assert!(
                    (wx[i] - simple).abs() < 1e-2 * simple.abs() + 1e-9,
                    "({x}, {s}): {} vs {simple}",
                    wx[i]
                );
                assert!((ws[i] + x * d.sin() / r).abs() < 1e-15);
                assert_eq!(rs[i], ws[i]);
                // (The reference curve is interpolated between samples
                // dy/8 apart: about 2e-9 m off the midway curve.)
                let midway = -s * s / (4.0 * r * r);
                assert!(
                    (rx[i] - midway).abs() < 1e-2 * midway.abs() + 1e-7,
                    "({x}, {s}): {} vs {midway}",
                    rx[i]
                );
            }
        }
        // The approach d moves the sphere along n(0) = z: relative to it
        // the normal line through c(s) moves by -d sin(delta) along t(s),
        // and the sphere's point on it slides as far along the profile,
        // whose slope there is about 2 delta (delta ≈ -s/(2R) on the
        // midway curve, the profile's slope -s/R): its height changes by
        // -2 d delta², w_x by -2 d delta²/R.
        let d = 1.6e-4;
        let (ax, _) = slip(&geo, 0.0, RigidSlipSurface::ActualSurface, d);
        for iy in 0..g.ny {
            let delta = geo.delta_rad[iy];
            for ix in 0..g.nx {
                let i = g.index(ix, iy);
                let hand = -2.0 * d * delta * delta / r;
                assert!(
                    (ax[i] - wx[i] - hand).abs() < 5e-2 * hand.abs() + 1e-15,
                    "{} vs {hand}",
                    ax[i] - wx[i]
                );
            }
        }
    }

    /// A torus (a wheel whose profile is a circle of radius `rho_w` about
    /// a point `r_t` from its axis) yawed by `psi`, touching a prismatic
    /// rail at its locus point of profile angle `alpha0`, in the frame of
    /// the module docs with the contact point at the origin. Its outward
    /// normal is sin(alpha) a + cos(alpha) e_r(phi), e_r(phi) = cos(phi)
    /// e1 + sin(phi) e2, e1 = (0, 0, 1), e2 = a x e1 = (cos psi, sin psi,
    /// 0); on the locus (no x part) sin(phi) = tan(alpha) tan(psi).
    pub(crate) struct YawedTorus {
        r_t: f64,
        rho_w: f64,
        psi: f64,
        /// The centre of the profile circle's plane on the axis, relative
        /// to the contact point.
        axis: [f64; 3],
        /// The contact normal into the rail, (0, -sin delta, cos delta).
        normal: [f64; 3],
        alpha0: f64,
        /// The contact point's angle round its circle from the lowest point.
        pub(crate) phi0: f64,
    }

    impl YawedTorus {
        /// The point and outward normal of profile angle `alpha` on the
        /// locus, axis centre at the origin, and its phi.
        fn locus(r_t: f64, rho_w: f64, psi: f64, alpha: f64) -> ([f64; 3], [f64; 3], f64) {
            let a = [-psi.sin(), psi.cos(), 0.0];
            let phi = (alpha.tan() * psi.tan()).asin();
            let er = [phi.sin() * psi.cos(), phi.sin() * psi.sin(), phi.cos()];
            let r = r_t + rho_w * alpha.cos();
            let u = rho_w * alpha.sin();
            let p = [0, 1, 2].map(|k| u * a[k] + r * er[k]);
            let n = [0, 1, 2].map(|k| alpha.sin() * a[k] + alpha.cos() * er[k]);
            (p, n, phi)
        }

        pub(crate) fn new(r_t: f64, rho_w: f64, psi: f64, alpha0: f64) -> Self {
            let (p0, normal, phi0) = Self::locus(r_t, rho_w, psi, alpha0);
            Self {
                r_t,
                rho_w,
                psi,
                axis: p0.map(|v| -v),
                normal,
                alpha0,
                phi0,
            }
        }

        /// The true undeformed distance at (x, s = 0): from the rail point
        /// (x, 0, 0) along -normal to the torus (Newton on its implicit
        /// equation (rho - r_t)² + u² = rho_w², rho the distance from the
        /// axis and u the position along it).
        fn gap(&self, x: f64) -> f64 {
            let a = [-self.psi.sin(), self.psi.cos(), 0.0];
            let n = self.normal;
            let dot = |p: [f64; 3], q: [f64; 3]| p[0] * q[0] + p[1] * q[1] + p[2] * q[2];
            let mut lam = 0.0;
            for _ in 0..100 {
                let d = [0, 1, 2].map(|k| [x, 0.0, 0.0][k] - lam * n[k] - self.axis[k]);
                let u = dot(d, a);
                let perp = [0, 1, 2].map(|k| d[k] - u * a[k]);
                let rho = dot(perp, perp).sqrt();
                let f = (rho - self.r_t).powi(2) + u * u - self.rho_w * self.rho_w;
                let grad =
                    [0, 1, 2].map(|k| 2.0 * (rho - self.r_t) * perp[k] / rho + 2.0 * u * a[k]);
                let step = f / -dot(grad, n);
                lam -= step;
                if step.abs() < 1e-20 {
                    break;
                }
            }
            lam
        }

        /// The curvature of the true undeformed distance along x at s = 0
        /// [1/m]: second differences at 0.2 and 0.4 mm, Richardson-extrapolated.
        pub(crate) fn curvature_along_x(&self) -> f64 {
            let k2 = |d: f64| (self.gap(d) + self.gap(-d) - 2.0 * self.gap(0.0)) / (d * d);
            (4.0 * k2(2e-4) - k2(4e-4)) / 3.0
        }

        /// The wheel's locus curve (y, z) with its lead (x, sigma), and the
        /// rail's profile (a circle of radius `rho_r`), sampled every `ds`
        /// over +-`reach`.
        fn curves(&self, rho_r: f64, ds: f64, reach: f64) -> (PointCurve, PointCurve) {
            let m = (reach / ds).ceil() as i64;
            let (mut pts, mut lead) = (Vec::new(), Vec::new());
            for k in -m..=m {
                let alpha = self.alpha0 + k as f64 * ds / self.rho_w;
                let (p, _, phi) = Self::locus(self.r_t, self.rho_w, self.psi, alpha);
                let q = [0, 1, 2].map(|i| p[i] + self.axis[i]);
                pts.push([q[1], q[2]]);
                lead.push([q[0], (self.r_t + self.rho_w * alpha.cos()) * phi.sin()]);
            }
            let wheel = PointCurve::with_lead(&pts, &lead, "wheel").unwrap();
            let delta = (-self.normal[1]).atan2(self.normal[2]);
            let c = [rho_r * self.normal[1], rho_r * self.normal[2]];
            let rail: Vec<[f64; 2]> = (-m..=m)
                .map(|k| {
                    let b = delta + k as f64 * ds / rho_r;
                    [c[0] + rho_r * b.sin(), c[1] - rho_r * b.cos()]
                })
                .collect();
            (PointCurve::new(&rail, "rail").unwrap(), wheel)
        }
    }

    /// Euler's normal curvature along x of a torus of profile radius
    /// `rho_w` at profile angle `alpha0`, `r0` from its axis, whose circle
    /// runs at cos(theta) = `cos_theta` to x: cos(alpha0)/r0 cos²(theta) +
    /// sin²(theta)/rho_w.
    pub(crate) fn euler_curvature(alpha0: f64, r0: f64, rho_w: f64, cos_theta: f64) -> f64 {
        let sin2 = 1.0 - cos_theta * cos_theta;
        alpha0.cos() / r0 * (1.0 - sin2) + sin2 / rho_w
    }

    #[test]
    fn a_yawed_torus_has_euler_s_curvature_along_x_and_so_has_the_geometry() {
        // The rail is prismatic along x, so the undeformed distance along x
        // at fixed s curves as the wheel's surface does in its tangent
        // plane: Euler's theorem with the principal curvatures of a body of
        // revolution, the parallel circle's cos(alpha)/r (Meusnier) and the
        // profile's 1/rho_w, at the angle theta between the circle and x
        // (cos(theta) = cos(phi) cos(psi)). A flange-like torus (13 mm
        // profile radius, 0.47 m from the axis) on a 13 mm rail corner,
        // yawed by 0, 15.6 and 24 mrad (A-2.2 at 6.5 and 10 mm), contact
        // angles 0.3, 0.8 and 1.15 rad. The true distance comes from the
        // analytic surfaces (Newton on the torus' implicit equation), the
        // geometry's from the locus sampled every 0.02 mm (cubic splines).
        // Tolerances: the brute force's Richardson step leaves 1e-7
        // relative, the splines 1e-6 (measured agreement 7 digits).
        let (r_t, rho_w, rho_r) = (0.47, 0.013, 0.013);
        for &psi in &[0.0, 0.0156, 0.024] {
            for &alpha0 in &[-0.3, -0.8, -1.15] {
                let t = YawedTorus::new(r_t, rho_w, psi, alpha0);
                let brute = t.curvature_along_x();
                let r0 = r_t + rho_w * alpha0.cos();
                let euler = euler_curvature(alpha0, r0, rho_w, t.phi0.cos() * psi.cos());
                let g = Grid::centered(41, 5, 8.2e-3, 1e-3).unwrap();
                let (rail, wheel) = t.curves(rho_r, 2e-5, 4e-3);
                let yaw = WheelYaw {
                    yaw_rad: psi,
                    lean: 0.0,
                };
                let geo = ConformalGeometry::new_yawed(&rail, &wheel, yaw, r0, g).unwrap();
                let gap = |ix: usize| geo.gap_m[g.index(ix, 2)];
                let k2 = |k: usize| {
                    (gap(20 + k) + gap(20 - k) - 2.0 * gap(20)) / (k as f64 * g.dx_m).powi(2)
                };
                let cect = (4.0 * k2(1) - k2(2)) / 3.0;
                eprintln!(
                    "psi {psi}, alpha0 {alpha0}: true {brute:.7}, Euler {euler:.7}, geometry {cect:.7}, circle alone {:.7} [1/m]",
                    alpha0.cos() / r0
                );
                assert!((brute / euler - 1.0).abs() < 1e-6, "{brute} vs {euler}");
                assert!((cect / brute - 1.0).abs() < 1e-5, "{cect} vs {brute}");
                assert!(gap(20).abs() < 1e-15);
            }
        }
    }
}
