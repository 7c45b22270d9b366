//! Smoothing cubic spline of a profile curve, evaluated by arc length.
//!
//! # Method
//!
//! The profile points `p_i = (y_i, z_i)` get the chord-length parameter
//! `u_i` (cumulative distance between successive points, `u_0 = 0`). Both
//! coordinates are fitted as functions of `u` by a smoothing cubic spline
//! (Reinsch 1967; Green & Silverman, *Nonparametric Regression and
//! Generalized Linear Models*, 1994, §2.3), with knots at every point and
//! natural end conditions (zero second derivative at both ends). For each
//! coordinate `g` the spline minimises
//!
//! ```text
//! sum_i w_i (g_i - g(u_i))^2  +  lambda * integral g''(u)^2 du
//! ```
//!
//! with `w_i = c_i (u_{i+1} - u_{i-1}) / 2` (the length of curve that point
//! `i` stands for, times the point's own weight `c_i`, 1 unless the file
//! gives one), so that the data term approximates `integral (g - data)^2 du`
//! and the result does not depend on how densely the profile is sampled.
//! Both coordinates use the same `lambda`, so the fit does not depend on
//! how the profile is rotated or shifted in its plane. The Reinsch system
//! `(R + lambda Q^T W^-1 Q) gamma = Q^T g` is symmetric positive definite
//! and pentadiagonal; it is solved by a banded Cholesky factorisation, once
//! for both coordinates.
//!
//! # The smoothing parameter
//!
//! On a uniformly sampled curve the smoothing spline acts as the low-pass
//! filter `H(k) = 1 / (1 + lambda k^4)` on wavenumber `k`. The parameter is
//! given as the **cut-off wavelength** `l` \[m\] where `H = 1/2`, so
//! `lambda = (l / 2 pi)^4` (the same definition as CONTACT's `l_filt`):
//! undulations shorter than `l` are removed, longer ones kept (a wavelength
//! of `2 l` keeps 94 %, `4 l` keeps 99.6 %). `l = 0` interpolates the
//! points exactly (natural cubic spline).
//!
//! The default, [`DEFAULT_SMOOTHING_WAVELENGTH_M`] = 2 mm, is small
//! against everything contact depends on: contact patches are 5 to 20 mm
//! wide (a 10 mm wave keeps 99.8 %) and designed profiles have radii of 10
//! mm and more (the curvature of `circ_r10.prw`, R = 10 mm, is unchanged
//! within 0.01 % over the middle half of the arc, 0.2 % over the middle
//! 80 %). It is needed for measured profiles, whose noise
//! dominates the curvature at the scale of the point spacing: MiniProf's
//! 0.01 mm rounding at 0.25 mm spacing (`avg_wheel.whl`) gives curvature
//! noise of about 100/m when interpolating, 30/m with l = 1 mm and 5/m with
//! l = 2 mm on a tread whose true curvature is a few 1/m; even the 1e-6 mm
//! rounding of `circ_r100.prr` at 0.1 mm spacing scatters the interpolated
//! curvature by 4 %, 0.01 % with l = 2 mm. The curvature noise falls as
//! `l^(-5/2)`: use 3 to 8 mm for noisier measurements, 0 for exact
//! interpolation.
//!
//! # Arc length
//!
//! The spline is evaluated by the arc length `t` \[m\] of the *fitted* curve,
//! `t = 0` at its first point, `t = L` at its last: `t(u)` is integrated with
//! 5-point Gauss–Legendre per interval and inverted by safeguarded Newton
//! iteration. Beyond the ends, `t < 0` or `t > L`, the curve continues as
//! the straight line along the end tangent; because of the natural end
//! conditions this extension is itself continuous in slope and curvature
//! (curvature 0).
//!
//! # Signs
//!
//! With the profile frame of [`crate::wheelrail`] (y lateral, z down):
//!
//! * `tangent` is the unit vector `(dy/dt, dz/dt)`, in the direction of
//!   increasing t (the order of the points);
//! * `inclination_rad` is the angle of the surface against the y axis,
//!   `atan(dz/dy)` where the profile is a graph of y: zero where the surface
//!   is level, positive where it descends (z grows) towards +y. It is
//!   measured along the profile's overall direction (the sign of
//!   `y_last - y_first`), so it is continuous also through vertical and
//!   overhanging parts, where it passes ±pi/2;
//! * `curvature_per_m` is `d(theta)/dt`, theta the angle of the tangent:
//!   positive where the curve turns towards its right-hand side (seen with y
//!   to the right and z downwards). Profiles in the CONTACT point order
//!   have their material on the right-hand side, so the curvature is
//!   positive where the body is convex (a rail crown, a wheel tread bulging
//!   towards the rail) and negative where it is concave (a hollow worn
//!   tread, the flange root, a groove).

use thiserror::Error;

use crate::core::memory::{heap_bytes, HeapBytes};

/// Default cut-off wavelength of the smoothing \[m\]: 2 mm. See the module
/// documentation for the choice.
pub const DEFAULT_SMOOTHING_WAVELENGTH_M: f64 = 2e-3;

/// Options for [`ProfileSpline::new`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SplineOptions {
    /// Cut-off wavelength `l` of the smoothing \[m\]: undulations shorter than
    /// this are filtered out. `0` interpolates the points exactly. Must be
    /// finite and `>= 0`. Default [`DEFAULT_SMOOTHING_WAVELENGTH_M`].
    pub smoothing_wavelength_m: f64,
}

impl Default for SplineOptions {
    fn default() -> Self {
        Self {
            smoothing_wavelength_m: DEFAULT_SMOOTHING_WAVELENGTH_M,
        }
    }
}

impl SplineOptions {
    /// Options for exact interpolation of the points (no smoothing).
    pub fn interpolating() -> Self {
        Self {
            smoothing_wavelength_m: 0.0,
        }
    }

    /// Options with the given cut-off wavelength \[m\].
    pub fn smoothing(wavelength_m: f64) -> Self {
        Self {
            smoothing_wavelength_m: wavelength_m,
        }
    }
}

/// Errors of [`ProfileSpline::new`]. Indices count the points from 0.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SplineError {
    /// Fewer than two points.
    #[error("a profile spline needs at least 2 points, got {count}")]
    TooFewPoints {
        /// Number of points given.
        count: usize,
    },
    /// A coordinate is NaN or infinite.
    #[error("point {index} is not finite: ({y_m}, {z_m}) m")]
    NotFinite {
        /// Index of the point.
        index: usize,
        /// Its y \[m\].
        y_m: f64,
        /// Its z \[m\].
        z_m: f64,
    },
    /// Two successive points coincide (or lie closer than 1e-12 times the
    /// profile length), so the chord-length parameter does not advance.
    #[error("points {index} and {} coincide; remove duplicate points", index + 1)]
    CoincidentPoints {
        /// Index of the first of the two points.
        index: usize,
    },
    /// The smoothing wavelength is negative or not finite.
    #[error("smoothing_wavelength_m must be finite and >= 0, got {value}")]
    InvalidSmoothing {
        /// The offending value \[m\].
        value: f64,
    },
    /// Point weights are not one per point, or one is not finite and > 0.
    #[error("point weights must be one per point, finite and > 0: {reason}")]
    InvalidWeight {
        /// What is wrong.
        reason: String,
    },
    /// The Reinsch system lost positive definiteness in floating point
    /// (extremely uneven point spacing).
    #[error("the smoothing system is numerically singular at point {index}; the point spacing is too uneven")]
    Singular {
        /// Interior point where the factorisation failed.
        index: usize,
    },
}

/// Value of the spline at one arc length, see [`ProfileSpline::eval`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SplinePoint {
    /// Arc length along the fitted curve \[m\].
    pub t_m: f64,
    /// Lateral coordinate \[m\].
    pub y_m: f64,
    /// Vertical coordinate, positive down \[m\].
    pub z_m: f64,
    /// Unit tangent `(dy/dt, dz/dt)` [-].
    pub tangent: [f64; 2],
    /// Surface inclination `atan(dz/dy)`, continuous \[rad\]; see the module
    /// documentation.
    pub inclination_rad: f64,
    /// Signed curvature `d(theta)/dt` [1/m], positive where the curve turns
    /// to its right-hand side (convex body in CONTACT point order).
    pub curvature_per_m: f64,
}

/// Gauss–Legendre nodes and weights on [0, 1], 5 points.
const GL_NODES: [f64; 5] = [
    0.046_910_077_030_668_004,
    0.230_765_344_947_158_45,
    0.5,
    0.769_234_655_052_841_6,
    0.953_089_922_969_332,
];
const GL_WEIGHTS: [f64; 5] = [
    0.118_463_442_528_094_54,
    0.239_314_335_249_683_23,
    0.284_444_444_444_444_45,
    0.239_314_335_249_683_23,
    0.118_463_442_528_094_54,
];

/// Samples per interval used to split the curve into pieces monotone in y.
const SAMPLES_PER_INTERVAL: usize = 4;

/// A run of samples along which y is monotone, see [`ProfileSpline::t_at_y`].
#[derive(Debug, Clone, Copy, PartialEq)]
struct MonotonePiece {
    /// First and last sample index (inclusive).
    first: usize,
    last: usize,
    /// +1 where y increases with t, -1 where it decreases.
    sign: f64,
}

/// A smoothing cubic spline through profile points, evaluated by arc
/// length; see the module documentation for the method and sign
/// conventions. Build it with [`ProfileSpline::new`] or
/// [`crate::wheelrail::Profile::spline`].
#[derive(Debug, Clone, PartialEq)]
pub struct ProfileSpline {
    /// Knot parameters: chord length of the input points [m].
    u: Vec<f64>,
    /// Fitted values at the knots.
    gy: Vec<f64>,
    gz: Vec<f64>,
    /// Second derivatives d2/du2 at the knots (0 at both ends).
    cy: Vec<f64>,
    cz: Vec<f64>,
    /// Arc length of the fitted curve at the knots [m].
    s: Vec<f64>,
    /// Speed |dC/du| at the start and end of each interval.
    end_speed: Vec<[f64; 2]>,
    /// Overall direction: sign(y_last - y_first), +1 when equal.
    direction: f64,
    /// Samples (u, y) for the look-up of y, and their monotone pieces.
    samples: Vec<(f64, f64)>,
    pieces: Vec<MonotonePiece>,
    smoothing_wavelength_m: f64,
}

/// Its knots, samples and monotone pieces.
impl HeapBytes for ProfileSpline {
    fn heap_bytes(&self) -> usize {
        heap_bytes!(
            self.u,
            self.gy,
            self.gz,
            self.cy,
            self.cz,
            self.s,
            self.end_speed,
            self.samples,
            self.pieces
        )
    }
}

/// Value, first and second derivative in u of one coordinate on interval i.
#[inline]
fn cubic(h: f64, g0: f64, g1: f64, c0: f64, c1: f64, du: f64) -> (f64, f64, f64) {
    let b = du / h;
    let a = 1.0 - b;
    let v = a * g0 + b * g1 + ((a * a * a - a) * c0 + (b * b * b - b) * c1) * h * h / 6.0;
    let d = (g1 - g0) / h - (3.0 * a * a - 1.0) * h * c0 / 6.0 + (3.0 * b * b - 1.0) * h * c1 / 6.0;
    let dd = a * c0 + b * c1;
    (v, d, dd)
}

impl ProfileSpline {
    /// Fits the spline through `points` (y, z) \[m\], all with weight 1.
    pub fn new(points: &[[f64; 2]], options: &SplineOptions) -> Result<Self, SplineError> {
        Self::with_weights(points, None, options)
    }

    /// Fits the spline through `points` (y, z) \[m\] with relative point
    /// weights (one per point, finite and > 0; `None` for all 1). A larger
    /// weight pulls the smoothed curve closer to that point; weights do not
    /// matter when interpolating.
    pub fn with_weights(
        points: &[[f64; 2]],
        weights: Option<&[f64]>,
        options: &SplineOptions,
    ) -> Result<Self, SplineError> {
        let n = points.len();
        if n < 2 {
            return Err(SplineError::TooFewPoints { count: n });
        }
        let l = options.smoothing_wavelength_m;
        if !(l.is_finite() && l >= 0.0) {
            return Err(SplineError::InvalidSmoothing { value: l });
        }
        for (index, p) in points.iter().enumerate() {
            if !(p[0].is_finite() && p[1].is_finite()) {
                return Err(SplineError::NotFinite {
                    index,
                    y_m: p[0],
                    z_m: p[1],
                });
            }
        }
        if let Some(w) = weights {
            if w.len() != n {
                return Err(SplineError::InvalidWeight {
                    reason: format!("{} weights for {} points", w.len(), n),
                });
            }
            if let Some((i, v)) = w
                .iter()
                .enumerate()
                .find(|(_, v)| !(v.is_finite() && **v > 0.0))
            {
                return Err(SplineError::InvalidWeight {
                    reason: format!("weight {i} is {v}"),
                });
            }
        }

        // Chord-length parameter.
        let mut u = Vec::with_capacity(n);
        u.push(0.0);
        for i in 1..n {
            let d = dist(points[i - 1], points[i]);
            u.push(u[i - 1] + d);
        }
        let total = u[n - 1];
        let tiny = 1e-12 * total.max(f64::MIN_POSITIVE);
        for i in 0..n - 1 {
            if u[i + 1] - u[i] <= tiny {
                return Err(SplineError::CoincidentPoints { index: i });
            }
        }

        let ys: Vec<f64> = points.iter().map(|p| p[0]).collect();
        let zs: Vec<f64> = points.iter().map(|p| p[1]).collect();
        let lambda = (l / (2.0 * std::f64::consts::PI)).powi(4);
        let (gy, gz, cy, cz) = reinsch(&u, weights, &ys, &zs, lambda)?;

        let mut spline = Self {
            u,
            gy,
            gz,
            cy,
            cz,
            s: Vec::new(),
            end_speed: Vec::new(),
            direction: 1.0,
            samples: Vec::new(),
            pieces: Vec::new(),
            smoothing_wavelength_m: l,
        };
        spline.direction = if spline.gy[n - 1] < spline.gy[0] {
            -1.0
        } else {
            1.0
        };

        // Arc length at the knots.
        let mut s = Vec::with_capacity(n);
        s.push(0.0);
        for i in 0..n - 1 {
            let len = spline.length_in(i, spline.u[i + 1]);
            s.push(s[i] + len);
        }
        spline.s = s;
        spline.end_speed = (0..n - 1)
            .map(|i| {
                [
                    spline.speed(i, spline.u[i]),
                    spline.speed(i, spline.u[i + 1]),
                ]
            })
            .collect();
        spline.build_pieces();
        Ok(spline)
    }

    /// Number of knots (input points).
    pub fn knot_count(&self) -> usize {
        self.u.len()
    }

    /// Arc length of the fitted curve at each input point \[m\], one per
    /// point, starting at 0.
    pub fn knot_arc_lengths_m(&self) -> &[f64] {
        &self.s
    }

    /// Total arc length `L` of the fitted curve \[m\].
    pub fn length_m(&self) -> f64 {
        self.s[self.s.len() - 1]
    }

    /// The smoothing wavelength the spline was built with \[m\].
    pub fn smoothing_wavelength_m(&self) -> f64 {
        self.smoothing_wavelength_m
    }

    /// +1 if the fitted curve ends at larger y than it starts (rails in
    /// CONTACT order), -1 otherwise (wheels).
    pub fn direction(&self) -> f64 {
        self.direction
    }

    /// Position, tangent, inclination and curvature at arc length `t` \[m\].
    /// Outside `[0, L]` the curve continues along its end tangents.
    pub fn eval(&self, t_m: f64) -> SplinePoint {
        let len = self.length_m();
        if t_m < 0.0 || t_m > len {
            let (tt, i, uu) = if t_m < 0.0 {
                (0.0, 0, self.u[0])
            } else {
                (len, self.u.len() - 2, self.u[self.u.len() - 1])
            };
            let (p, d, _) = self.derivs(i, uu);
            let speed = d[0].hypot(d[1]);
            let tan = [d[0] / speed, d[1] / speed];
            let dt = t_m - tt;
            return SplinePoint {
                t_m,
                y_m: p[0] + dt * tan[0],
                z_m: p[1] + dt * tan[1],
                tangent: tan,
                inclination_rad: self.inclination_of(tan),
                curvature_per_m: 0.0,
            };
        }
        let (i, uu) = self.u_at_t(t_m);
        self.point_at(t_m, i, uu)
    }

    /// Position (y, z) at arc length `t` \[m\].
    pub fn position(&self, t_m: f64) -> [f64; 2] {
        let p = self.eval(t_m);
        [p.y_m, p.z_m]
    }

    /// Unit tangent (dy/dt, dz/dt) at arc length `t` \[m\].
    pub fn tangent(&self, t_m: f64) -> [f64; 2] {
        self.eval(t_m).tangent
    }

    /// Surface inclination `atan(dz/dy)` at arc length `t` \[rad\],
    /// continuous along the profile (see the module documentation).
    pub fn inclination_rad(&self, t_m: f64) -> f64 {
        self.eval(t_m).inclination_rad
    }

    /// Signed curvature at arc length `t` [1/m] (see the module
    /// documentation for the sign).
    pub fn curvature_per_m(&self, t_m: f64) -> f64 {
        self.eval(t_m).curvature_per_m
    }

    /// Arc length \[m\] of the point of the surface at lateral position `y`
    /// \[m\] that faces the opposite body, or `None` if the profile does not
    /// reach `y`.
    ///
    /// Only parts of the curve that run in the profile's overall direction
    /// (see [`ProfileSpline::direction`]) are surfaces facing the other
    /// body: in CONTACT point order, where the material lies on the
    /// right-hand side, those are the parts facing up for rails and down
    /// for wheels. Where several of them lie above each other (an
    /// overhang), the outermost is taken: the smallest z for a rail
    /// (direction +1), the largest z for a wheel (direction -1). Where the
    /// profile is a graph z(y) this is simply the one point at `y`.
    pub fn t_at_y(&self, y_m: f64) -> Option<f64> {
        self.locate_y(y_m).map(|(t, _)| t)
    }

    /// Height z \[m\] of the surface at lateral position `y` \[m\], chosen as
    /// in [`ProfileSpline::t_at_y`]; `None` if the profile does not reach
    /// `y`.
    pub fn z_at_y(&self, y_m: f64) -> Option<f64> {
        self.locate_y(y_m).map(|(_, z)| z)
    }

    /// Lateral range (min y, max y) of the fitted curve \[m\], taken from its
    /// samples (four per interval).
    pub fn y_range_m(&self) -> (f64, f64) {
        let mut lo = f64::INFINITY;
        let mut hi = f64::NEG_INFINITY;
        for &(_, y) in &self.samples {
            lo = lo.min(y);
            hi = hi.max(y);
        }
        (lo, hi)
    }

    // ---------------------------------------------------------------- private

    /// Interval containing parameter u (clamped).
    fn interval_of_u(&self, uu: f64) -> usize {
        let n = self.u.len();
        let k = self.u.partition_point(|&x| x <= uu);
        k.saturating_sub(1).min(n - 2)
    }

    /// Position, first and second derivatives (in u) on interval i at u.
    fn derivs(&self, i: usize, uu: f64) -> ([f64; 2], [f64; 2], [f64; 2]) {
        let h = self.u[i + 1] - self.u[i];
        let du = uu - self.u[i];
        let (y, dy, ddy) = cubic(
            h,
            self.gy[i],
            self.gy[i + 1],
            self.cy[i],
            self.cy[i + 1],
            du,
        );
        let (z, dz, ddz) = cubic(
            h,
            self.gz[i],
            self.gz[i + 1],
            self.cz[i],
            self.cz[i + 1],
            du,
        );
        ([y, z], [dy, dz], [ddy, ddz])
    }

    fn speed(&self, i: usize, uu: f64) -> f64 {
        let (_, d, _) = self.derivs(i, uu);
        d[0].hypot(d[1])
    }

    /// Arc length from the start of interval i to parameter `uu`.
    fn length_in(&self, i: usize, uu: f64) -> f64 {
        let a = self.u[i];
        let w = uu - a;
        let mut sum = 0.0;
        for k in 0..5 {
            sum += GL_WEIGHTS[k] * self.speed(i, a + GL_NODES[k] * w);
        }
        sum * w
    }

    fn inclination_of(&self, tan: [f64; 2]) -> f64 {
        (self.direction * tan[1]).atan2(self.direction * tan[0])
    }

    fn point_at(&self, t_m: f64, i: usize, uu: f64) -> SplinePoint {
        let (p, d, dd) = self.derivs(i, uu);
        let speed = d[0].hypot(d[1]);
        let tan = [d[0] / speed, d[1] / speed];
        let curv = (d[0] * dd[1] - d[1] * dd[0]) / (speed * speed * speed);
        SplinePoint {
            t_m,
            y_m: p[0],
            z_m: p[1],
            tangent: tan,
            inclination_rad: self.inclination_of(tan),
            curvature_per_m: curv,
        }
    }

    /// Interval and parameter u for arc length t in [0, L].
    fn u_at_t(&self, t_m: f64) -> (usize, f64) {
        let n = self.u.len();
        let k = self.s.partition_point(|&x| x <= t_m);
        let i = k.saturating_sub(1).min(n - 2);
        let (a, b) = (self.u[i], self.u[i + 1]);
        let (sa, sb) = (self.s[i], self.s[i + 1]);
        if sb <= sa {
            return (i, a);
        }
        let target = t_m - sa;
        let ds = sb - sa;
        // Initial guess: cubic Hermite interpolation of u(t) with the slopes
        // du/dt = 1/speed at both ends; then safeguarded Newton.
        let sg = (target / ds).clamp(0.0, 1.0);
        let (s2, s3) = (sg * sg, sg * sg * sg);
        let mut uu = a * (2.0 * s3 - 3.0 * s2 + 1.0)
            + ds / self.end_speed[i][0] * (s3 - 2.0 * s2 + sg)
            + b * (3.0 * s2 - 2.0 * s3)
            + ds / self.end_speed[i][1] * (s3 - s2);
        if !(uu >= a && uu <= b) {
            uu = a + (b - a) * sg;
        }
        let mut lo = a;
        let mut hi = b;
        let tol_s = 1e-12 * ds;
        let tol_u = 1e-15 * (b - a);
        for _ in 0..40 {
            let f = self.length_in(i, uu) - target;
            if f.abs() <= tol_s {
                break;
            }
            if f > 0.0 {
                hi = uu;
            } else {
                lo = uu;
            }
            let sp = self.speed(i, uu);
            let mut next = if sp > 0.0 { uu - f / sp } else { f64::NAN };
            if !(next > lo && next < hi) {
                next = 0.5 * (lo + hi);
            }
            let step = (next - uu).abs();
            uu = next;
            if step <= tol_u || hi - lo <= tol_u {
                break;
            }
        }
        (i, uu)
    }

    /// Builds the (u, y) samples and the pieces along which y is monotone.
    fn build_pieces(&mut self) {
        let n = self.u.len();
        let mut samples = Vec::with_capacity((n - 1) * SAMPLES_PER_INTERVAL + 1);
        for i in 0..n - 1 {
            let (a, b) = (self.u[i], self.u[i + 1]);
            for k in 0..SAMPLES_PER_INTERVAL {
                let uu = a + (b - a) * k as f64 / SAMPLES_PER_INTERVAL as f64;
                let (p, _, _) = self.derivs(i, uu);
                samples.push((uu, p[0]));
            }
        }
        samples.push((self.u[n - 1], self.gy[n - 1]));

        let mut pieces = Vec::new();
        let mut first = 0;
        let mut sign = 0.0;
        for k in 1..samples.len() {
            let dy = samples[k].1 - samples[k - 1].1;
            let sk = if dy > 0.0 {
                1.0
            } else if dy < 0.0 {
                -1.0
            } else {
                0.0
            };
            if sk == 0.0 || sk == sign || sign == 0.0 {
                if sign == 0.0 && sk != 0.0 {
                    sign = sk;
                }
                continue;
            }
            pieces.push(MonotonePiece {
                first,
                last: k - 1,
                sign,
            });
            first = k - 1;
            sign = sk;
        }
        pieces.push(MonotonePiece {
            first,
            last: samples.len() - 1,
            sign,
        });
        self.samples = samples;
        self.pieces = pieces;
    }

    /// (t, z) of the surface point at `y` facing the other body.
    fn locate_y(&self, y_m: f64) -> Option<(f64, f64)> {
        if !y_m.is_finite() {
            return None;
        }
        let mut best: Option<(f64, f64)> = None;
        for piece in &self.pieces {
            if piece.sign != self.direction {
                continue;
            }
            let y_first = self.samples[piece.first].1;
            let y_last = self.samples[piece.last].1;
            let (lo, hi) = if y_first <= y_last {
                (y_first, y_last)
            } else {
                (y_last, y_first)
            };
            if !(y_m >= lo && y_m <= hi) {
                continue;
            }
            // Bracketing samples: first k in the piece past y.
            let run = &self.samples[piece.first..=piece.last];
            if run.len() < 2 {
                continue;
            }
            let k = run.partition_point(|&(_, y)| (y - y_m) * piece.sign < 0.0);
            let k = k.clamp(1, run.len() - 1);
            let (ua, ya) = run[k - 1];
            let (ub, yb) = run[k];
            let uu = self.solve_y(ua, ya, ub, yb, y_m);
            let i = self.interval_of_u(0.5 * (ua + ub));
            let (p, _, _) = self.derivs(i, uu);
            let t = self.s[i] + self.length_in(i, uu);
            let better = match best {
                None => true,
                Some((_, z)) => {
                    if self.direction > 0.0 {
                        p[1] < z
                    } else {
                        p[1] > z
                    }
                }
            };
            if better {
                best = Some((t, p[1]));
            }
        }
        best
    }

    /// Root of y(u) = y_m between two samples of the same interval.
    fn solve_y(&self, ua: f64, ya: f64, ub: f64, yb: f64, y_m: f64) -> f64 {
        let i = self.interval_of_u(0.5 * (ua + ub));
        let (mut a, mut fa) = (ua, ya - y_m);
        let (mut b, mut fb) = (ub, yb - y_m);
        if fa == 0.0 {
            return a;
        }
        if fb == 0.0 {
            return b;
        }
        // Regula falsi (Illinois) with bisection fallback.
        let tol = 1e-15 * (self.length_m() + 1.0);
        let mut side = 0;
        let mut uu = 0.5 * (a + b);
        for _ in 0..100 {
            uu = if fb != fa {
                (a * fb - b * fa) / (fb - fa)
            } else {
                0.5 * (a + b)
            };
            if !(uu > a.min(b) && uu < a.max(b)) {
                uu = 0.5 * (a + b);
            }
            let (p, _, _) = self.derivs(i, uu);
            let f = p[0] - y_m;
            if f == 0.0 || (b - a).abs() <= tol {
                break;
            }
            if (f > 0.0) == (fb > 0.0) {
                b = uu;
                fb = f;
                if side == -1 {
                    fa *= 0.5;
                }
                side = -1;
            } else {
                a = uu;
                fa = f;
                if side == 1 {
                    fb *= 0.5;
                }
                side = 1;
            }
        }
        uu
    }
}

fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    (b[0] - a[0]).hypot(b[1] - a[1])
}

type Fit = (Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>);

/// Reinsch's algorithm for both coordinates: fitted values and second
/// derivatives at the knots.
fn reinsch(
    u: &[f64],
    weights: Option<&[f64]>,
    ys: &[f64],
    zs: &[f64],
    lambda: f64,
) -> Result<Fit, SplineError> {
    let n = u.len();
    if n == 2 {
        return Ok((ys.to_vec(), zs.to_vec(), vec![0.0; 2], vec![0.0; 2]));
    }
    let m = n - 2;
    let h: Vec<f64> = (0..n - 1).map(|i| u[i + 1] - u[i]).collect();
    // Data weights: length represented by each point times its own weight.
    let w: Vec<f64> = (0..n)
        .map(|i| {
            let left = if i > 0 { h[i - 1] } else { 0.0 };
            let right = if i < n - 1 { h[i] } else { 0.0 };
            let c = weights.map_or(1.0, |w| w[i]);
            0.5 * (left + right) * c
        })
        .collect();
    // Column j of Q (interior knot j + 1) has a_j, b_j, c_j in rows j..j+2.
    let qa: Vec<f64> = (0..m).map(|j| 1.0 / h[j]).collect();
    let qb: Vec<f64> = (0..m).map(|j| -1.0 / h[j] - 1.0 / h[j + 1]).collect();
    let qc: Vec<f64> = (0..m).map(|j| 1.0 / h[j + 1]).collect();

    // Bands of M = R + lambda Q^T W^-1 Q.
    let mut d0 = vec![0.0; m];
    let mut d1 = vec![0.0; m];
    let mut d2 = vec![0.0; m];
    for j in 0..m {
        d0[j] = (h[j] + h[j + 1]) / 3.0
            + lambda * (qa[j] * qa[j] / w[j] + qb[j] * qb[j] / w[j + 1] + qc[j] * qc[j] / w[j + 2]);
        if j + 1 < m {
            d1[j] = h[j + 1] / 6.0
                + lambda * (qb[j] * qa[j + 1] / w[j + 1] + qc[j] * qb[j + 1] / w[j + 2]);
        }
        if j + 2 < m {
            d2[j] = lambda * qc[j] * qa[j + 2] / w[j + 2];
        }
    }

    // Banded Cholesky M = L L^T, L with diagonal l0 and subdiagonals l1, l2.
    let mut l0 = vec![0.0; m];
    let mut l1 = vec![0.0; m];
    let mut l2 = vec![0.0; m];
    for i in 0..m {
        if i >= 2 {
            l2[i] = d2[i - 2] / l0[i - 2];
        }
        if i >= 1 {
            l1[i] = (d1[i - 1] - l2[i] * l1[i - 1]) / l0[i - 1];
        }
        let piv = d0[i] - l1[i] * l1[i] - l2[i] * l2[i];
        if !(piv > 0.0 && piv.is_finite()) {
            return Err(SplineError::Singular { index: i + 1 });
        }
        l0[i] = piv.sqrt();
    }
    let solve = |rhs: Vec<f64>| -> Vec<f64> {
        let mut x = rhs;
        for i in 0..m {
            let mut v = x[i];
            if i >= 1 {
                v -= l1[i] * x[i - 1];
            }
            if i >= 2 {
                v -= l2[i] * x[i - 2];
            }
            x[i] = v / l0[i];
        }
        for i in (0..m).rev() {
            let mut v = x[i];
            if i + 1 < m {
                v -= l1[i + 1] * x[i + 1];
            }
            if i + 2 < m {
                v -= l2[i + 2] * x[i + 2];
            }
            x[i] = v / l0[i];
        }
        x
    };
    let fit = |g: &[f64]| -> (Vec<f64>, Vec<f64>) {
        let rhs: Vec<f64> = (0..m)
            .map(|j| qa[j] * g[j] + qb[j] * g[j + 1] + qc[j] * g[j + 2])
            .collect();
        let gamma = solve(rhs);
        let mut values = g.to_vec();
        if lambda > 0.0 {
            for (i, v) in values.iter_mut().enumerate() {
                let mut qg = 0.0;
                if i >= 2 {
                    qg += qc[i - 2] * gamma[i - 2];
                }
                if i >= 1 && i - 1 < m {
                    qg += qb[i - 1] * gamma[i - 1];
                }
                if i < m {
                    qg += qa[i] * gamma[i];
                }
                *v -= lambda * qg / w[i];
            }
        }
        let mut second = vec![0.0; n];
        second[1..=m].copy_from_slice(&gamma);
        (values, second)
    };
    let (gy, cy) = fit(ys);
    let (gz, cz) = fit(zs);
    Ok((gy, gz, cy, cz))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn circle(r: f64, n: usize, half_angle: f64) -> Vec<[f64; 2]> {
        // Rail-like crown: y increasing, z = r - sqrt(r^2 - y^2) (z down),
        // material below: curvature +1/r.
        (0..n)
            .map(|k| {
                let a = -half_angle + 2.0 * half_angle * k as f64 / (n - 1) as f64;
                [r * a.sin(), r - r * a.cos()]
            })
            .collect()
    }

    #[test]
    fn interpolation_reproduces_points_and_circle_curvature() {
        let pts = circle(0.1, 81, 0.6);
        let sp = ProfileSpline::new(&pts, &SplineOptions::interpolating()).unwrap();
        let exact_len = 0.1 * 1.2;
        assert!((sp.length_m() - exact_len).abs() < 1e-7 * exact_len);
        for (k, &t) in sp.knot_arc_lengths_m().iter().enumerate() {
            let p = sp.position(t);
            assert!((p[0] - pts[k][0]).abs() < 1e-12 && (p[1] - pts[k][1]).abs() < 1e-12);
        }
        let l = sp.length_m();
        for k in 1..20 {
            let t = l * (0.2 + 0.6 * k as f64 / 20.0);
            let c = sp.curvature_per_m(t);
            assert!((c - 10.0).abs() < 1e-3 * 10.0, "curvature {c} at {t}");
        }
        // Inclination = angle along the arc from the apex.
        let mid = sp.eval(0.5 * l);
        assert!(mid.inclination_rad.abs() < 1e-6);
        assert!((sp.inclination_rad(0.5 * l + 0.01) - 0.1).abs() < 1e-5);
    }

    #[test]
    fn arc_length_is_exact_along_a_line() {
        let pts: Vec<[f64; 2]> = [0.0, 0.001, 0.003, 0.004, 0.01]
            .iter()
            .map(|&y| [y, 0.5 * y])
            .collect();
        for opts in [
            SplineOptions::interpolating(),
            SplineOptions::smoothing(2e-3),
        ] {
            let sp = ProfileSpline::new(&pts, &opts).unwrap();
            let l = 0.01 * 1.25f64.sqrt();
            assert!((sp.length_m() - l).abs() < 1e-12);
            let p = sp.eval(0.3 * l);
            assert!((p.y_m - 0.003).abs() < 1e-12 && (p.z_m - 0.0015).abs() < 1e-12);
            assert!(p.curvature_per_m.abs() < 1e-9);
            assert!((p.inclination_rad - 0.5f64.atan()).abs() < 1e-12);
            // Extension beyond the ends.
            let q = sp.eval(l + 0.001);
            assert!((q.y_m - (0.01 + 0.001 / 1.25f64.sqrt())).abs() < 1e-12);
            assert_eq!(q.curvature_per_m, 0.0);
        }
    }

    #[test]
    fn z_at_y_picks_the_visible_surface() {
        // A rail-like curve with an overhang: up the gauge face with an
        // undercut, over the top, down the field side.
        let pts = vec![
            [0.000, 0.020],
            [0.002, 0.015],
            [-0.001, 0.010],
            [0.000, 0.005],
            [0.005, 0.001],
            [0.010, 0.000],
            [0.020, 0.001],
            [0.030, 0.010],
        ];
        let sp = ProfileSpline::new(&pts, &SplineOptions::interpolating()).unwrap();
        assert_eq!(sp.direction(), 1.0);
        let z = sp.z_at_y(0.010).unwrap();
        assert!(z.abs() < 1e-12);
        // y = 0.001 is crossed three times; the top one is visible.
        let z = sp.z_at_y(0.001).unwrap();
        assert!(z < 0.005, "z = {z}");
        assert!(sp.z_at_y(0.05).is_none());
        assert!(sp.z_at_y(f64::NAN).is_none());
        let t = sp.t_at_y(0.02).unwrap();
        assert!((sp.position(t)[0] - 0.02).abs() < 1e-12);
    }

    #[test]
    fn wheel_order_gives_positive_curvature_on_a_convex_tread() {
        let mut pts = circle(0.05, 41, 0.5);
        // A convex wheel: mirror z (material above) and reverse the order.
        for p in &mut pts {
            p[1] = -p[1];
        }
        pts.reverse();
        let sp = ProfileSpline::new(&pts, &SplineOptions::interpolating()).unwrap();
        assert_eq!(sp.direction(), -1.0);
        let l = sp.length_m();
        assert!((sp.curvature_per_m(0.5 * l) - 20.0).abs() < 0.05);
        // Inclination atan(dz/dy), continuous through the apex: before it
        // (y > 0) the tread rises towards +y (z = -y^2/2r), after it falls.
        let a = sp.inclination_rad(0.5 * l - 0.005);
        let b = sp.inclination_rad(0.5 * l + 0.005);
        assert!((a + 0.1).abs() < 1e-3 && (b - 0.1).abs() < 1e-3, "{a} {b}");
        assert!(sp.z_at_y(0.0).unwrap().abs() < 1e-12);
    }

    #[test]
    fn bad_input_is_an_error_not_a_panic() {
        let o = SplineOptions::default();
        assert!(matches!(
            ProfileSpline::new(&[[0.0, 0.0]], &o),
            Err(SplineError::TooFewPoints { count: 1 })
        ));
        assert!(matches!(
            ProfileSpline::new(&[[0.0, 0.0], [0.0, 0.0], [1.0, 0.0]], &o),
            Err(SplineError::CoincidentPoints { index: 0 })
        ));
        assert!(matches!(
            ProfileSpline::new(&[[0.0, 0.0], [f64::NAN, 0.0]], &o),
            Err(SplineError::NotFinite { index: 1, .. })
        ));
        assert!(matches!(
            ProfileSpline::new(&[[0.0, 0.0], [1.0, 0.0]], &SplineOptions::smoothing(-1.0)),
            Err(SplineError::InvalidSmoothing { .. })
        ));
        assert!(matches!(
            ProfileSpline::with_weights(&[[0.0, 0.0], [1.0, 0.0]], Some(&[1.0, 0.0]), &o),
            Err(SplineError::InvalidWeight { .. })
        ));
        let sp = ProfileSpline::new(&[[0.0, 0.0], [1.0, 0.0]], &o).unwrap();
        assert!(sp.eval(f64::NAN).y_m.is_nan());
    }

    #[test]
    fn smoothing_filters_short_waves_and_keeps_long_ones() {
        // z = a sin(2 pi y / wl) sampled densely: the filter H = 1/(1 + (l/wl)^4).
        let check = |wl: f64, l: f64| {
            let n = 2001;
            let span = 20.0 * wl;
            let pts: Vec<[f64; 2]> = (0..n)
                .map(|k| {
                    let y = span * k as f64 / (n - 1) as f64;
                    [y, 1e-6 * (2.0 * std::f64::consts::PI * y / wl).sin()]
                })
                .collect();
            let sp = ProfileSpline::new(&pts, &SplineOptions::smoothing(l)).unwrap();
            // Amplitude in the middle of the curve.
            let mut amp: f64 = 0.0;
            for k in 0..200 {
                let y = 0.4 * span + 0.2 * span * k as f64 / 200.0;
                amp = amp.max(sp.z_at_y(y).unwrap().abs());
            }
            amp / 1e-6
        };
        let h = check(1e-3, 1e-3);
        assert!((h - 0.5).abs() < 0.02, "H at cut-off {h}");
        let h = check(4e-3, 1e-3);
        assert!((h - 1.0 / (1.0 + 1.0 / 256.0)).abs() < 0.01, "H at 4 l {h}");
        let h = check(0.5e-3, 1e-3);
        assert!((h - 1.0 / 17.0).abs() < 0.01, "H at l/2 {h}");
    }
}
