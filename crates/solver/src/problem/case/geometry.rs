//! The `[geometry]` and `[conformal]` sections: the undeformed distance of
//! the two surfaces (quadratic, given per element, or the conformal
//! profiles), and the checks of a patch against its grid.

use serde::Deserialize;

use super::{
    bad, ranges, CaseFile, GridSection, Model, POINTS_ORIGIN_TOLERANCE_M,
    POINTS_TANGENT_TOLERANCE_DEG,
};
use crate::conformal::geometry::{Circle, ConformalGeometry, Curve, PointCurve, RigidSlipSurface};
use crate::core::error::{show, Range};
use crate::core::grid::Grid;
use crate::core::hertz::HertzSolution;
use crate::core::influence::LINE_REFERENCE_DISTANCE_M;
use crate::core::normal::NormalLoad;
use crate::core::problem::Kinematics;
use crate::problem::reference_models::hertz_of;
use crate::problem::CaseError;

/// `[conformal]`: options of the conformal models (`cect`,
/// `cect_halfspace`).
#[derive(Debug, Clone, Copy, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct ConformalSection {
    /// Where steady rolling takes the bodies' rigid velocities:
    /// `"actual_surface"` (default; the wheel's material point on each
    /// element's normal, slip along the surface where the bodies meet, as
    /// CONTACT does) or `"reference_section"` (the reference-curve point of
    /// the section x = 0 for every x, slip along x). See
    /// [`RigidSlipSurface`].
    pub rigid_slip: Option<RigidSlipSurface>,
}

pub(super) fn conformal_options(
    section: Option<ConformalSection>,
    model: Model,
    kinematics: &Kinematics,
    notes: &mut Vec<String>,
) -> Result<RigidSlipSurface, CaseError> {
    let Some(section) = section else {
        return Ok(RigidSlipSurface::default());
    };
    if !model.is_cect() {
        return Err(bad(
            "conformal",
            format!(
                "options of model = \"cect\" or \"cect_halfspace\", not \"{}\"",
                model.name()
            ),
        ));
    }
    if section.rigid_slip.is_some() && !matches!(kinematics, Kinematics::SteadyRolling(_)) {
        notes.push(
            "conformal.rigid_slip applies to steady rolling ([rolling]): unused here".to_string(),
        );
    }
    Ok(section.rigid_slip.unwrap_or_default())
}

/// Kind of undeformed geometry.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GeometryKind {
    /// h = a_per_m x² + b_per_m y².
    Quadratic,
    /// Circular lateral profiles of rail and wheel and a wheel rolling
    /// radius (conformal contact).
    ConformalCircular,
    /// Rail and wheel profiles given as points (y, z) and a wheel rolling
    /// radius (conformal contact).
    ConformalPoints,
    /// Line contact: two cylinders with parallel axes along y, h = a_per_m
    /// x², solved in two dimensions (plane strain) per metre of their
    /// length ([`crate::core::influence`]); exact model only.
    Line,
}

impl GeometryKind {
    /// The name used in the case file.
    pub fn name(self) -> &'static str {
        match self {
            GeometryKind::Quadratic => "quadratic",
            GeometryKind::ConformalCircular => "conformal_circular",
            GeometryKind::ConformalPoints => "conformal_points",
            GeometryKind::Line => "line",
        }
    }
}

/// `[geometry]`: the undeformed distance of the bodies. Which keys are
/// required depends on `kind`; keys of another kind are rejected.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GeometrySection {
    /// Geometry kind: `"quadratic"`, `"conformal_circular"`,
    /// `"conformal_points"` or `"line"`.
    pub kind: GeometryKind,
    /// `quadratic`, `line`: curvature coefficient A in x (rolling
    /// direction) [1/m], > 0 (A = 1/(2 R_x) for combined radius R_x).
    pub a_per_m: Option<f64>,
    /// `quadratic`: curvature coefficient B in y (lateral) [1/m], > 0.
    pub b_per_m: Option<f64>,
    /// `conformal_circular`: lateral radius of the rail profile \[m\], convex
    /// (crown) > 0, concave < 0, `inf` straight.
    pub rail_lateral_radius_m: Option<f64>,
    /// `conformal_circular`: lateral radius of the wheel profile \[m\],
    /// convex > 0, concave (hollow, wrapping the rail) < 0.
    pub wheel_lateral_radius_m: Option<f64>,
    /// Conformal kinds: wheel rolling radius at the rigid contact point \[m\], > 0.
    pub wheel_rolling_radius_m: Option<f64>,
    /// `conformal_points`: rail profile points `[y, z]` \[m\] in the plane
    /// x = 0, z down into the rail, ordered by increasing y, one of them
    /// at the rigid contact point (the origin).
    pub rail_points_m: Option<Vec<[f64; 2]>>,
    /// `conformal_points`: wheel profile points `[y, z]` \[m\], same rules.
    pub wheel_points_m: Option<Vec<[f64; 2]>>,
    /// `quadratic`, `line`, exact model: the undeformed distance given per
    /// element \[m\] (CONTACT's `IBASE = 9`), replacing A x² + B y²:
    /// nx * ny values with index iy * nx + ix (x fastest; a line contact
    /// nx), each in [-1, 1] m, at the element centres of the grid, which
    /// must be given (`nx`, `ny`, and the windows). A and B still estimate
    /// the Hertz patch that checks the window, so give those of the
    /// best-fitting quadric; the patch may span fewer elements than a
    /// quadratic gap needs (the grid is the user's).
    #[serde(default)]
    pub gap_m: Option<Vec<f64>>,
}

/// A validated geometry.
#[derive(Debug, Clone, PartialEq)]
pub enum CaseGeometry {
    /// h = A x² + B y² (the case's `a_per_m`, `b_per_m`).
    Quadratic,
    /// Line contact: h = A x² per metre of two cylinders (plane strain).
    Line,
    /// Circular lateral profiles.
    ConformalCircular {
        /// Rail lateral radius \[m\] (convex > 0).
        rail_lateral_radius_m: f64,
        /// Wheel lateral radius \[m\] (concave < 0).
        wheel_lateral_radius_m: f64,
        /// Wheel rolling radius \[m\].
        wheel_rolling_radius_m: f64,
    },
    /// Profiles through points.
    ConformalPoints {
        /// Rail profile.
        rail: Box<PointCurve>,
        /// Wheel profile.
        wheel: Box<PointCurve>,
        /// Number of rail points.
        rail_points: usize,
        /// Number of wheel points.
        wheel_points: usize,
        /// Rail lateral radius at the origin estimated from the points \[m\]
        /// (infinite for a straight profile).
        rail_lateral_radius_m: f64,
        /// Wheel lateral radius at the origin estimated from the points \[m\].
        wheel_lateral_radius_m: f64,
        /// Wheel rolling radius \[m\].
        wheel_rolling_radius_m: f64,
    },
}

impl CaseGeometry {
    /// Whether the geometry is conformal (curved lateral profiles).
    pub fn is_conformal(&self) -> bool {
        !matches!(self, CaseGeometry::Quadratic | CaseGeometry::Line)
    }

    /// Whether the geometry is a line contact (two dimensions).
    pub fn is_line(&self) -> bool {
        matches!(self, CaseGeometry::Line)
    }

    /// Lateral radii of rail and wheel and the wheel rolling radius \[m\]
    /// (given or, for points, estimated at the origin); `None` for
    /// `quadratic`.
    pub fn radii(&self) -> Option<(f64, f64, f64)> {
        match *self {
            CaseGeometry::Quadratic | CaseGeometry::Line => None,
            CaseGeometry::ConformalCircular {
                rail_lateral_radius_m,
                wheel_lateral_radius_m,
                wheel_rolling_radius_m,
            }
            | CaseGeometry::ConformalPoints {
                rail_lateral_radius_m,
                wheel_lateral_radius_m,
                wheel_rolling_radius_m,
                ..
            } => Some((
                rail_lateral_radius_m,
                wheel_lateral_radius_m,
                wheel_rolling_radius_m,
            )),
        }
    }

    /// Mean lateral radius r = (|R_yr| + |R_yw|)/2 \[m\] (infinite for
    /// `quadratic` or a straight profile).
    pub fn mean_lateral_radius_m(&self) -> f64 {
        match self.radii() {
            Some((r, w, _)) => 0.5 * (r.abs() + w.abs()),
            None => f64::INFINITY,
        }
    }

    /// One line describing the geometry (mm) for the readable summary.
    pub fn describe(&self) -> String {
        match self {
            CaseGeometry::Quadratic => "quadratic gap".to_string(),
            CaseGeometry::Line => "line contact of cylinders (plane strain, per metre)".to_string(),
            CaseGeometry::ConformalCircular {
                rail_lateral_radius_m: r,
                wheel_lateral_radius_m: w,
                wheel_rolling_radius_m: x,
            } => format!(
                "circular profiles R_yr = {:.4} mm, R_yw = {:.4} mm, R_xw = {:.2} mm",
                r * 1e3,
                w * 1e3,
                x * 1e3
            ),
            CaseGeometry::ConformalPoints {
                rail_points,
                wheel_points,
                rail_lateral_radius_m: r,
                wheel_lateral_radius_m: w,
                wheel_rolling_radius_m: x,
                ..
            } => format!(
                "profiles through {rail_points} rail and {wheel_points} wheel points \
                 (at the origin R_yr ≈ {:.4} mm, R_yw ≈ {:.4} mm), R_xw = {:.2} mm",
                r * 1e3,
                w * 1e3,
                x * 1e3
            ),
        }
    }

    /// The conformal geometry on the (x, s) grid `grid`.
    pub fn conformal(&self, grid: Grid) -> Result<ConformalGeometry, CaseError> {
        let g = match self {
            CaseGeometry::Quadratic | CaseGeometry::Line => return Err(bad(
                "geometry.kind",
                "the conformal models need `kind = \"conformal_circular\"` or \"conformal_points\"",
            )),
            CaseGeometry::ConformalCircular {
                rail_lateral_radius_m,
                wheel_lateral_radius_m,
                wheel_rolling_radius_m,
            } => ConformalGeometry::new(
                &Circle::rail(*rail_lateral_radius_m),
                &Circle::wheel(*wheel_lateral_radius_m),
                *wheel_rolling_radius_m,
                grid,
            )?,
            CaseGeometry::ConformalPoints {
                rail,
                wheel,
                wheel_rolling_radius_m,
                ..
            } => ConformalGeometry::new(
                rail.as_ref(),
                wheel.as_ref(),
                *wheel_rolling_radius_m,
                grid,
            )?,
        };
        Ok(g)
    }
}

/// Signed curvature [1/m] of `curve` at the origin (t = 0), positive
/// when it bends towards +z for a tangent along +y: the tangent angle's
/// derivative by central differences over +-`h_m`.
fn curvature_at_origin(curve: &dyn Curve, h_m: f64) -> f64 {
    let angle = |t: f64| {
        let (_, d) = curve.eval(t);
        d[1].atan2(d[0])
    };
    (angle(h_m) - angle(-h_m)) / (2.0 * h_m)
}

/// A profile through `points` with the checks of `conformal_points`:
/// the curve, its curvature at the origin [1/m] and its tangent there.
fn profile_from_points(
    points: &[[f64; 2]],
    key: &str,
) -> Result<(PointCurve, f64, [f64; 2]), CaseError> {
    for (i, p) in points.iter().enumerate() {
        ranges::PROFILE_COORDINATE.check(&format!("{key}[{i}].y_m"), p[0])?;
        ranges::PROFILE_COORDINATE.check(&format!("{key}[{i}].z_m"), p[1])?;
    }
    let curve = PointCurve::new(points, key)?;
    let dist = |p: &[f64; 2]| p[0].hypot(p[1]);
    let nearest = (0..points.len())
        .min_by(|&a, &b| dist(&points[a]).total_cmp(&dist(&points[b])))
        .unwrap_or(0);
    let p = points[nearest];
    if dist(&p) > POINTS_ORIGIN_TOLERANCE_M {
        return Err(bad(
            key,
            format!(
                "the rigid contact point must be the origin and one of the points: the point \
                 nearest to it is [{:e}, {:e}] m; shift the profile so that it passes through [0.0, 0.0]",
                p[0], p[1]
            ),
        ));
    }
    if nearest == 0 || nearest + 1 == points.len() {
        return Err(bad(
            key,
            "the origin (the rigid contact point) is an end point: give points on both sides of it",
        ));
    }
    let (_, tangent) = curve.eval(0.0);
    if tangent[0] <= 0.0 {
        return Err(bad(
            key,
            "order the points by increasing y (the profile's tangent at the origin must point towards +y)",
        ));
    }
    let spacing =
        |a: usize, b: usize| (points[a][0] - points[b][0]).hypot(points[a][1] - points[b][1]);
    let h = 0.5 * spacing(nearest - 1, nearest).min(spacing(nearest, nearest + 1));
    let curvature = curvature_at_origin(&curve, h);
    Ok((curve, curvature, tangent))
}

/// A lateral radius: non-zero and not NaN (`inf`: straight).
fn lateral_radius(key: &str, v: f64) -> Result<f64, CaseError> {
    if v.is_infinite() || ranges::LATERAL_RADIUS.contains(v.abs()) {
        return Ok(v);
    }
    let r = ranges::LATERAL_RADIUS;
    Err(bad(
        key,
        format!(
            "must be convex > 0 or concave < 0 with a size in {}, or inf for a straight profile, got {}",
            r.describe(),
            show(v)
        ),
    ))
}

impl GeometrySection {
    /// Validates the section for its `kind`: the geometry and the
    /// curvature coefficients A, B [1/m] of its (flattened) quadratic gap,
    /// A = 1/(2 R_xw), B = (1/R_yr + 1/R_yw)/2 for the conformal kinds.
    pub(super) fn validate(&self) -> Result<(CaseGeometry, f64, f64), CaseError> {
        let kind = self.kind;
        let keys: [(&str, bool, GeometryKind); 7] = [
            ("a_per_m", self.a_per_m.is_some(), GeometryKind::Quadratic),
            ("b_per_m", self.b_per_m.is_some(), GeometryKind::Quadratic),
            (
                "rail_lateral_radius_m",
                self.rail_lateral_radius_m.is_some(),
                GeometryKind::ConformalCircular,
            ),
            (
                "wheel_lateral_radius_m",
                self.wheel_lateral_radius_m.is_some(),
                GeometryKind::ConformalCircular,
            ),
            (
                "wheel_rolling_radius_m",
                self.wheel_rolling_radius_m.is_some(),
                kind,
            ),
            (
                "rail_points_m",
                self.rail_points_m.is_some(),
                GeometryKind::ConformalPoints,
            ),
            (
                "wheel_points_m",
                self.wheel_points_m.is_some(),
                GeometryKind::ConformalPoints,
            ),
        ];
        for (key, given, owner) in keys {
            // A line contact's gap is A x².
            let line_a = kind == GeometryKind::Line && key == "a_per_m";
            if given && owner != kind && !line_a {
                return Err(bad(
                    format!("geometry.{key}"),
                    format!(
                        "not used with `kind = \"{}\"` (it belongs to `kind = \"{}\"`)",
                        kind.name(),
                        owner.name()
                    ),
                ));
            }
        }
        if matches!(kind, GeometryKind::Quadratic | GeometryKind::Line)
            && self.wheel_rolling_radius_m.is_some()
        {
            return Err(bad(
                "geometry.wheel_rolling_radius_m",
                format!(
                    "not used with `kind = \"{}\"` (it belongs to the conformal kinds)",
                    kind.name()
                ),
            ));
        }
        let need = |key: &str, v: Option<f64>| {
            v.ok_or_else(|| {
                bad(
                    format!("geometry.{key}"),
                    format!("missing: required with `kind = \"{}\"`", kind.name()),
                )
            })
        };
        match kind {
            GeometryKind::Quadratic => {
                let a = need("a_per_m", self.a_per_m)?;
                let b = need("b_per_m", self.b_per_m)?;
                ranges::CURVATURE.check("geometry.a_per_m", a)?;
                ranges::CURVATURE.check("geometry.b_per_m", b)?;
                Ok((CaseGeometry::Quadratic, a, b))
            }
            GeometryKind::Line => {
                let a = need("a_per_m", self.a_per_m)?;
                ranges::CURVATURE.check("geometry.a_per_m", a)?;
                Ok((CaseGeometry::Line, a, 0.0))
            }
            GeometryKind::ConformalCircular => {
                let r = need("rail_lateral_radius_m", self.rail_lateral_radius_m)?;
                let w = need("wheel_lateral_radius_m", self.wheel_lateral_radius_m)?;
                let x = need("wheel_rolling_radius_m", self.wheel_rolling_radius_m)?;
                let r = lateral_radius("geometry.rail_lateral_radius_m", r)?;
                let w = lateral_radius("geometry.wheel_lateral_radius_m", w)?;
                ranges::ROLLING_RADIUS.check("geometry.wheel_rolling_radius_m", x)?;
                let b = 0.5 * (1.0 / r + 1.0 / w);
                if b.is_nan() || b <= 0.0 {
                    // The concave one of the two is named: a wheel/rail
                    // pair has a convex rail, so a concave rail is the
                    // likely slip.
                    let (field, hint) = match r < 0.0 {
                        true => (
                            "geometry.rail_lateral_radius_m",
                            "a concave rail, R_yr < 0, must be wider than a convex wheel: |R_yr| > R_yw",
                        ),
                        false => (
                            "geometry.wheel_lateral_radius_m",
                            "a concave wheel, R_yw < 0, must be wider than a convex rail: |R_yw| > R_yr",
                        ),
                    };
                    return Err(bad(
                        field,
                        format!(
                            "the profiles do not touch in one point: 1/R_yr + 1/R_yw = {:.6e} 1/m must \
                             be > 0 ({hint})",
                            2.0 * b
                        ),
                    ));
                }
                let geometry = CaseGeometry::ConformalCircular {
                    rail_lateral_radius_m: r,
                    wheel_lateral_radius_m: w,
                    wheel_rolling_radius_m: x,
                };
                Ok((geometry, 0.5 / x, b))
            }
            GeometryKind::ConformalPoints => {
                let missing = |key: &str| {
                    bad(
                        format!("geometry.{key}"),
                        "missing: required with `kind = \"conformal_points\"`",
                    )
                };
                let rp = self
                    .rail_points_m
                    .as_deref()
                    .ok_or_else(|| missing("rail_points_m"))?;
                let wp = self
                    .wheel_points_m
                    .as_deref()
                    .ok_or_else(|| missing("wheel_points_m"))?;
                let x = need("wheel_rolling_radius_m", self.wheel_rolling_radius_m)?;
                ranges::ROLLING_RADIUS.check("geometry.wheel_rolling_radius_m", x)?;
                let (rail, kr, tr) = profile_from_points(rp, "geometry.rail_points_m")?;
                let (wheel, kw, tw) = profile_from_points(wp, "geometry.wheel_points_m")?;
                let angle = (tr[0] * tw[1] - tr[1] * tw[0])
                    .atan2(tr[0] * tw[0] + tr[1] * tw[1])
                    .to_degrees();
                if angle.abs() > POINTS_TANGENT_TOLERANCE_DEG {
                    return Err(bad(
                        "geometry.wheel_points_m",
                        format!(
                            "the profiles must touch at the origin with a common tangent: the wheel's \
                             tangent there is {angle:.3}° off the rail's (at most {POINTS_TANGENT_TOLERANCE_DEG}°)"
                        ),
                    ));
                }
                // Rail: Circle::rail(R) bends towards +z with curvature 1/R;
                // wheel: Circle::wheel(R) with -1/R.
                let b = 0.5 * (kr - kw);
                if b.is_nan() || b <= 0.0 {
                    return Err(bad(
                        "geometry.wheel_points_m",
                        format!(
                            "the profiles do not touch in one point at the origin: the estimated \
                             curvatures (rail {kr:.4e} 1/m, wheel {:.4e} 1/m towards the rail) leave \
                             1/R_yr + 1/R_yw = {:.4e} 1/m, which must be > 0",
                            -kw,
                            2.0 * b
                        ),
                    ));
                }
                let geometry = CaseGeometry::ConformalPoints {
                    rail: Box::new(rail),
                    wheel: Box::new(wheel),
                    rail_points: rp.len(),
                    wheel_points: wp.len(),
                    rail_lateral_radius_m: 1.0 / kr,
                    wheel_lateral_radius_m: -1.0 / kw,
                    wheel_rolling_radius_m: x,
                };
                Ok((geometry, 0.5 / x, b))
            }
        }
    }
}

/// Rejects a load whose Hertz patch on the case's geometry and material
/// is outside [`ranges::HERTZ_SEMI_AXIS`] (a unit mistake in one of them);
/// the error names the load `key` (`load`, `transient.steps[k]`) and quotes
/// the values it depends on.
pub(super) fn check_hertz_patch(
    key: &str,
    load: NormalLoad,
    a_per_m: f64,
    b_per_m: f64,
    e_star: f64,
) -> Result<HertzSolution, CaseError> {
    let r = ranges::HERTZ_SEMI_AXIS;
    let h = hertz_of(a_per_m, b_per_m, e_star, load);
    let axes = match &h {
        Ok(h) if r.contains(h.semi_axis_x_m) && r.contains(h.semi_axis_y_m) => return Ok(*h),
        Ok(h) => format!(
            "has semi-axes {} x {} m",
            show(h.semi_axis_x_m),
            show(h.semi_axis_y_m)
        ),
        Err(_) => "has no finite semi-axes".to_string(),
    };
    let (field, value) = match load {
        NormalLoad::NormalForce(f) => ("normal_force_n", format!("{} N", show(f))),
        NormalLoad::Approach(d) => ("approach_m", format!("{} m", show(d))),
    };
    Err(bad(
        format!("{key}.{field}"),
        format!(
            "the Hertz patch of {value} on this geometry (A = {} 1/m, B = {} 1/m) and material \
             (E* = {} Pa) {axes}, outside {}: check the units \
             (forces in N, lengths in m, curvatures in 1/m, moduli in Pa)",
            show(a_per_m),
            show(b_per_m),
            show(e_star),
            r.describe()
        ),
    ))
}

/// The half-width \[m\] of the contact of a line load on cylinders with
/// h = A x² (2-D Hertz, Johnson 1985 §4.3: a² = 4 P' R /
/// (pi E*), R = 1/(2A)), rejected outside [`ranges::HERTZ_SEMI_AXIS`] as
/// [`check_hertz_patch`] does. For an approach d the half-width solves
/// d = A a² (ln(2 R0 / a) + 1/2), R0 the reference distance of the
/// displacements ([`LINE_REFERENCE_DISTANCE_M`]): the approach of the
/// Hertz pressure on the half-plane (Johnson 1985 §5.2).
pub(super) fn check_line_patch(
    key: &str,
    load: NormalLoad,
    a_per_m: f64,
    e_star: f64,
) -> Result<f64, CaseError> {
    let r0 = LINE_REFERENCE_DISTANCE_M;
    let half = match load {
        NormalLoad::NormalForce(f) => (2.0 * f / (std::f64::consts::PI * a_per_m * e_star)).sqrt(),
        NormalLoad::Approach(d) => {
            // d(a) increases on (0, 2 R0): bisection on a logarithmic scale.
            let approach = |a: f64| a_per_m * a * a * ((2.0 * r0 / a).ln() + 0.5);
            let (mut lo, mut hi) = (1e-12_f64, r0);
            if approach(hi) < d {
                lo = hi;
            }
            for _ in 0..200 {
                let mid = (lo * hi).sqrt();
                if approach(mid) < d {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            hi
        }
    };
    let r = ranges::HERTZ_SEMI_AXIS;
    if r.contains(half) {
        return Ok(half);
    }
    let (field, value) = match load {
        NormalLoad::NormalForce(f) => ("normal_force_n_per_m", format!("{} N/m", show(f))),
        NormalLoad::Approach(d) => ("approach_m", format!("{} m", show(d))),
    };
    Err(bad(
        format!("{key}.{field}"),
        format!(
            "the 2-D Hertz contact of {value} on these cylinders (A = {} 1/m) and material \
             (E* = {} Pa) has the half-width {} m, outside {}: check the units \
             (forces per metre in N/m, lengths in m, curvatures in 1/m, moduli in Pa)",
            show(a_per_m),
            show(e_star),
            show(half),
            r.describe()
        ),
    ))
}

/// Checks that `values` (named `key`) hold one value per element of an
/// `n[0]` x `n[1]` grid that the case gives (`grid`), each in `range`.
pub(super) fn per_element_values(
    key: &str,
    values: &[f64],
    n: [usize; 2],
    grid: GridSection,
    line: bool,
    range: Range,
) -> Result<(), CaseError> {
    let given = grid.nx.is_some() && (line || grid.ny.is_some());
    if !given {
        return Err(bad(
            key,
            "gives values per element: give the grid's `grid.nx` and `grid.ny` too",
        ));
    }
    let elements = if line { n[0] } else { n[0] * n[1] };
    if values.len() != elements {
        return Err(bad(
            key,
            format!(
                "has {} values for a grid of {elements} elements (nx = {}{})",
                values.len(),
                n[0],
                if line {
                    String::new()
                } else {
                    format!(", ny = {}", n[1])
                }
            ),
        ));
    }
    for (i, &v) in values.iter().enumerate() {
        range.check(&format!("{key}[{i}]"), v)?;
    }
    Ok(())
}

/// `geometry.gap_m`, checked: exact model on a quadratic or line geometry.
pub(super) fn given_gap(
    file: &CaseFile,
    model: Model,
    geometry: &CaseGeometry,
    n: [usize; 2],
    grid: GridSection,
) -> Result<Option<Vec<f64>>, CaseError> {
    let Some(h) = &file.geometry.gap_m else {
        return Ok(None);
    };
    let key = "geometry.gap_m";
    if model != Model::Exact || geometry.is_conformal() {
        return Err(bad(
            key,
            format!(
                "a gap per element is solved by the exact model on `kind = \"quadratic\"` or `\"line\"`, \
                 not {} on `{}`",
                model.name(),
                file.geometry.kind.name()
            ),
        ));
    }
    per_element_values(key, h, n, grid, geometry.is_line(), ranges::GAP)?;
    Ok(Some(h.clone()))
}

pub(super) fn check_model_geometry(model: Model, geometry: &CaseGeometry) -> Result<(), CaseError> {
    match (model, geometry) {
        (Model::Exact, CaseGeometry::Line) => Ok(()),
        (_, CaseGeometry::Line) => Err(bad(
            "model",
            format!(
                "model = \"{}\": a line contact (`geometry.kind = \"line\"`) is solved with the exact model only",
                model.name()
            ),
        )),
        (Model::Cect | Model::CectHalfspace | Model::HertzCorrected, CaseGeometry::Quadratic) => {
            Err(bad(
                "model",
                format!(
                    "model = \"{}\" is a conformal model: it needs `geometry.kind = \"conformal_circular\"` \
                     or `\"conformal_points\"`, not \"quadratic\"",
                    model.name()
                ),
            ))
        }
        (
            Model::Hertz | Model::HertzCorrected | Model::Exact | Model::Fastsim,
            CaseGeometry::ConformalPoints { .. },
        ) => Err(bad(
            "model",
            format!(
                "model = \"{}\" needs circular profiles (`geometry.kind = \"conformal_circular\"`) \
                 or a quadratic gap; profiles given as points run with model = \"cect\" or \"cect_halfspace\"",
                model.name()
            ),
        )),
        _ => Ok(()),
    }
}

#[cfg(test)]
mod line_contact_tests {
    use crate::core::influence::LINE_LENGTH_M;
    use crate::problem::case::*;

    /// CONTACT's carter2d (examples/carter2d.inp) as a case: 178 900 N/m.
    const LINE: &str = r#"
[material]
shear_modulus_pa = 82.0e9
poisson_ratio = 0.28
[friction]
coefficient = 0.3
[geometry]
kind = "line"
a_per_m = 1.0
[load]
normal_force_n_per_m = 178900.0
[rolling]
creepage_long = -2.4e-4
[grid]
nx = 55
"#;

    fn err(text: &str) -> String {
        match Case::from_toml(text) {
            Err(CaseError::BadInput(m)) => m,
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn a_line_case_has_one_row_and_the_2d_hertz_window() {
        let c = Case::from_toml(LINE).unwrap();
        assert!(c.geometry.is_line());
        assert_eq!((c.nx, c.ny), (55, 1));
        // 2.4 x the 2-D Hertz half-width a = sqrt(4 P' R / (pi E*)) = 1 mm
        // (R = 0.5 m, E* = G/(1 - nu)).
        assert!(
            (c.window_x_m / 2.4e-3 - 1.0).abs() < 1e-3,
            "{}",
            c.window_x_m
        );
        let g = c.grid().unwrap();
        assert!(g.is_line() && g.ny == 1 && g.dy_m == LINE_LENGTH_M);
        assert_eq!(c.load, NormalLoad::NormalForce(178_900.0));
        // An approach gives the window of the load with that approach:
        // d = A a² (ln(2 R0 / a) + 1/2) at a = 1 mm.
        let d = 1e-6 * ((2.0f64 / 1e-3).ln() + 0.5);
        let by_approach = LINE.replace(
            "normal_force_n_per_m = 178900.0",
            &format!("approach_m = {d:e}"),
        );
        let c = Case::from_toml(&by_approach).unwrap();
        assert!(
            (c.window_x_m / 2.4e-3 - 1.0).abs() < 1e-6,
            "{}",
            c.window_x_m
        );
    }

    #[test]
    fn a_line_case_refuses_three_dimensional_keys_naming_them() {
        for (from, to, key) in [
            (
                "normal_force_n_per_m",
                "normal_force_n",
                "`load.normal_force_n`",
            ),
            ("nx = 55", "nx = 55\nny = 8", "`grid.ny`"),
            ("nx = 55", "nx = 55\nwindow_y_m = 0.01", "`grid.window_y_m`"),
            (
                "a_per_m = 1.0",
                "a_per_m = 1.0\nb_per_m = 1.0",
                "`geometry.b_per_m`",
            ),
            (
                "creepage_long = -2.4e-4",
                "creepage_lat = 1e-4",
                "`rolling.creepage_lat`",
            ),
            (
                "creepage_long = -2.4e-4",
                "spin_per_m = 0.1",
                "`rolling.spin_per_m`",
            ),
            (
                "creepage_long = -2.4e-4",
                "force_x_n = 100.0",
                "`rolling.force_x_n`",
            ),
            ("nx = 55", "nx = 55\nwindow_x_m = 2.0", "`grid.window_x_m`"),
            ("model", "model", "`model`"),
        ] {
            let text = if key == "`model`" {
                format!("model = \"fastsim\"\n{LINE}")
            } else {
                LINE.replace(from, to)
            };
            let m = err(&text);
            assert!(m.contains(key), "{key}: {m}");
        }
        // A force per metre on a three-dimensional geometry.
        let quad = LINE
            .replace("kind = \"line\"", "kind = \"quadratic\"\nb_per_m = 1.0")
            .replace("nx = 55", "nx = 16\nny = 16");
        assert!(err(&quad).contains("`load.normal_force_n_per_m`"));
        // A prescribed force per metre is the core's Fx.
        let force = LINE.replace("creepage_long = -2.4e-4", "force_x_n_per_m = 30000.0");
        let c = Case::from_toml(&force).unwrap();
        assert_eq!(c.prescribed_force.force_x_n, Some(30_000.0));
    }

    #[test]
    fn a_line_case_rolls_transient_steps_of_whole_elements() {
        // 55 elements over 2.2 mm: 0.04 mm each.
        let transient = LINE
            .replace("[rolling]\ncreepage_long = -2.4e-4\n", "")
            .replace(
                "nx = 55",
                "nx = 55\nwindow_x_m = 2.2e-3\n[transient]\nrolling_step_m = 4e-5\nsteps = [ \
             { shift_x_m = 1e-7 }, { creepage_long = -2.4e-4 } ]",
            );
        let c = Case::from_toml(&transient).unwrap();
        assert_eq!(c.rolling_step_m, Some(4e-5));
        // Half an element: named as the step, with the line's own grid.
        let m = err(&transient.replace("rolling_step_m = 4e-5", "rolling_step_m = 2e-5"));
        assert!(
            m.contains("`transient.rolling_step_m`") && m.contains("grid.window_x_m / grid.nx"),
            "{m}"
        );
        assert!(!m.contains("grid.ny"), "{m}");
    }
}
