//! Kik and Piotrowski's approximate non-elliptic normal contact, and FASTSIM
//! on the area it gives.
//!
//! References: W. Kik, J. Piotrowski, "A fast, approximate method to
//! calculate normal load at contact between wheel and rail and creep forces
//! during rolling", 2nd Mini Conference on Contact Mechanics and Wear of
//! Rail/Wheel Systems, Budapest 1996; J. Piotrowski, W. Kik, "A simplified
//! model of wheel/rail contact mechanics for non-Hertzian problems and its
//! application in rail vehicle dynamic simulations", Vehicle System
//! Dynamics 46 (2008) 27–48.
//!
//! # What is sourced, and from where
//!
//! We had neither paper's full text. The method as implemented rests on:
//! the 2008 paper's abstract (a semi-elliptical pressure in the rolling
//! direction; the area from the virtual penetration of wheel and rail; the
//! pressure scale from the contact condition at the geometrical point of
//! contact; non-iterative), the penetration reduction factor 0.55 of the
//! original (the statement of the method; also the
//! `penetration_reduction_factor` of bytebunny/piotrowski-kik_model, a
//! public implementation of the 2008 paper), and CONTACT's implementation of
//! the method's normal part, read in eve70a/CONTACT `src/m_snorm.f90`
//! (`snorm_kpec_method`: per strip a semi-ellipse normalised by the longest
//! strip, its scale such that the elastic displacement at the element of
//! largest interpenetration equals the full penetration). The strip
//! integral below and the quadrature of the displacement are ours. The
//! tangential part's equivalent ellipse (same area, same ratio of length to
//! width as the area) is our reading of "Kalker's flexibility from an
//! equivalent ellipse"; the 2008 paper's own choice was not available to us.
//!
//! # Method
//!
//! The undeformed distance is given in lateral sections
//! ([`KpSection`]): `h(x, y) = h(y) + k(y)/2 (x - x_c(y))^2`, linear in `y`
//! between sections. With the approach `d` (rigid, relative to the same
//! datum as `h`), the penetration is `delta = d - h_min` and
//!
//! * the virtual interpenetration `g(y) = eps delta - (h(y) - h_min)`,
//!   `eps` the penetration reduction factor (0.55): the area is
//!   `|x - x_c(y)| < a(y) = sqrt(2 g(y)/k(y))` where `g > 0`;
//! * the pressure `p(x, y) = p0 sqrt(a(y)^2 - (x - x_c(y))^2)/a_max`, a
//!   semi-ellipse along each strip, `a_max` the longest half-length;
//! * `p0` from the displacement at the point of largest interpenetration
//!   `(x_c(y0), y0)` being `delta`:
//!   `delta = 1/(pi E*) ∫∫ p/r dA`, `E* = G/(1 - nu)` (the half-space
//!   kernel of two bodies as [`crate::core::hertz`] combines them);
//! * `Fn = p0 sum_j (pi/2) a_j^2 dy / a_max`.
//!
//! Under force control `delta` is found by a secant iteration on
//! `ln Fn(ln delta)`.
//!
//! # Discretisation (documented choices)
//!
//! * [`KikPiotrowskiSettings::strips`] strips of equal width `dy` over the
//!   lateral extent of `g > 0` (its ends interpolated between sections).
//! * The strip integral along `x` in closed form: for a strip at lateral
//!   distance `eta` from the point,
//!   `∫ sqrt(a^2 - s^2)/sqrt(s^2 + eta^2) ds = 2 sqrt(a^2 + eta^2) (K(m) - E(m))`,
//!   `m = a^2/(a^2 + eta^2)` (ours: write `a^2 - s^2 = (a^2 + eta^2) - (s^2 + eta^2)`,
//!   the two parts are then `K` and `E` by the substitution `s = a cos t`;
//!   checked against the far field and the logarithmic limit in the tests), which is
//!   `2 a^2 D(m)/sqrt(a^2 + eta^2)` with `D = (K - E)/m`. A strip whose
//!   middle is off the point's `x` by `c` takes `eta^2 + c^2` for `eta^2`
//!   (exact for `c = 0`).
//! * Across the strips: the strip holding the point subtracts the
//!   logarithmic singularity `2a (ln(4a/|eta|) - 1)` (the limit of the
//!   closed form as `eta -> 0`), integrates it in closed form and the rest
//!   by 4-point Gauss-Legendre on either side of the point; so do the next
//!   two strips on each side (without their offset `c`), the others take
//!   4-point Gauss-Legendre of the closed form. (The midpoint rule for the
//!   far strips is cheaper, but its switch to the near strips' quadrature
//!   as the strips slide past the point makes `Fn(delta)` jump by about
//!   1e-5, which stalls the force control's secant.)
//!
//! On a quadratic gap `h = A x^2 + B y^2` the area is the ellipse of
//! semi-axes `sqrt(eps delta/A)`, `sqrt(eps delta/B)` and the pressure
//! Hertz's elliptic shape on it, whose centre displacement is known in
//! closed form (`delta = p0 b K(e^2)/E*`, `b` the shorter semi-axis,
//! `e^2 = 1 - b^2/a^2`: Hertz's elliptical contact, Johnson, Contact
//! Mechanics, 1985, the relation [`crate::core::hertz`] solves): the tests
//! compare with that.
//! On a circle (`A = B = 1/(2R)`) under a given load the radius is
//! `(2 eps)^(1/3)` times Hertz's (`eps = 0.5` gives Hertz exactly; 0.55
//! gives a radius 3.2 % and an area 6.6 % larger).

use thiserror::Error;

use crate::core::fastsim::{Fastsim, FastsimError, FastsimInput, FastsimOutput, PatchStrip};
use crate::core::hertz::elliptic_d;
use crate::core::normal::NormalLoad;

/// Kik and Piotrowski's penetration reduction factor `eps` of the original
/// method [-].
pub const PENETRATION_FACTOR: f64 = 0.55;

/// Default of [`KikPiotrowskiSettings::strips`].
pub const DEFAULT_STRIPS: usize = 48;

/// Relative tolerance on the normal force under force control [-].
const FORCE_TOLERANCE: f64 = 1e-9;

/// Iteration limit of the force control.
const MAX_ITERATIONS: usize = 60;

/// 4-point Gauss-Legendre nodes and weights on [-1, 1].
const GAUSS4: [(f64, f64); 4] = [
    (-0.861_136_311_594_052_6, 0.347_854_845_137_453_9),
    (-0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
    (0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
    (0.861_136_311_594_052_6, 0.347_854_845_137_453_9),
];

/// Errors of the method.
#[derive(Debug, Clone, Copy, PartialEq, Error)]
pub enum KikPiotrowskiError {
    /// An input value is out of range.
    #[error("{name} must be {requirement}, got {value}")]
    InvalidInput {
        /// The input: a field of [`KikPiotrowskiSettings`] or
        /// [`KpSection`] (`sections`), `load`, `e_star_pa`.
        name: &'static str,
        /// What is required.
        requirement: &'static str,
        /// The offending value.
        value: f64,
    },
    /// The approach does not reach the smallest gap: no contact.
    #[error("approach {approach_m} m does not reach the smallest gap {min_gap_m} m")]
    NoContact {
        /// Approach \[m\].
        approach_m: f64,
        /// Smallest undeformed distance \[m\].
        min_gap_m: f64,
    },
    /// The force control did not converge.
    #[error("normal force {normal_force_n} N not reached in {iterations} steps")]
    NotConverged {
        /// Prescribed normal force \[N\].
        normal_force_n: f64,
        /// Steps taken.
        iterations: usize,
    },
    /// FASTSIM on the area refused its input.
    #[error("fastsim: {0}")]
    Fastsim(#[from] FastsimError),
}

/// One lateral section of the undeformed distance:
/// `h(x, y_m) = gap_m + curvature_x_per_m/2 (x - centre_x_m)^2`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KpSection {
    /// Lateral position \[m\]; sections in increasing `y`.
    pub y_m: f64,
    /// Smallest undeformed distance along `x` at `y_m` \[m\].
    pub gap_m: f64,
    /// `x` of that smallest distance \[m\].
    pub centre_x_m: f64,
    /// Curvature of the distance along `x` [1/m], > 0 (a wheel of radius
    /// `R` on a straight rail: `1/R`).
    pub curvature_x_per_m: f64,
}

/// Settings of the method.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KikPiotrowskiSettings {
    /// Penetration reduction factor `eps` [-], in (0, 1] (default
    /// [`PENETRATION_FACTOR`], 0.55): the virtual penetration is
    /// `eps delta`. Larger gives a larger area and, at the same load, a
    /// lower peak pressure.
    pub penetration_factor: f64,
    /// Number of strips across the area, in 4..=4096 (default
    /// [`DEFAULT_STRIPS`]). More strips: a finer area boundary and
    /// displacement quadrature, more time.
    pub strips: usize,
}

impl Default for KikPiotrowskiSettings {
    fn default() -> Self {
        Self {
            penetration_factor: PENETRATION_FACTOR,
            strips: DEFAULT_STRIPS,
        }
    }
}

/// The normal solution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KpNormal {
    /// Approach \[m\] (same datum as the sections' gaps).
    pub approach_m: f64,
    /// Penetration `delta` = approach minus the smallest gap \[m\].
    pub penetration_m: f64,
    /// Normal force \[N\].
    pub normal_force_n: f64,
    /// Largest pressure `p0` \[Pa\].
    pub max_pressure_pa: f64,
    /// Contact area, `sum 2 a_j dy` [m^2].
    pub contact_area_m2: f64,
    /// Lateral extent of the area \[m\].
    pub y_range_m: [f64; 2],
    /// Longest strip half-length `a_max` \[m\].
    pub max_half_length_m: f64,
    /// Width of each strip \[m\].
    pub strip_width_m: f64,
    /// Semi-axes `(a, b)` of the equivalent ellipse \[m\]: the area's,
    /// with `a/b` the ratio of the longest half-length to the half-width.
    pub equivalent_semi_axes_m: [f64; 2],
    /// Force-control steps (0 under approach control).
    pub iterations: usize,
}

/// The method's workspace: strips kept between the normal and the
/// tangential solve. Solves allocate nothing.
#[derive(Debug, Clone)]
pub struct KikPiotrowski {
    settings: KikPiotrowskiSettings,
    strips: Vec<PatchStrip>,
    /// The last force-controlled solve's penetration \[m\], force \[N\]
    /// and slope `d ln Fn/d ln delta` [-]: the next one's start.
    last_force_solve: Option<(f64, f64, f64)>,
}

impl KikPiotrowski {
    /// A workspace for `settings` (checked: ranges in the field docs).
    pub fn new(settings: KikPiotrowskiSettings) -> Result<Self, KikPiotrowskiError> {
        let eps = settings.penetration_factor;
        if !(eps.is_finite() && eps > 0.0 && eps <= 1.0) {
            return Err(KikPiotrowskiError::InvalidInput {
                name: "penetration_factor",
                requirement: "in (0, 1]",
                value: eps,
            });
        }
        if !(4..=4096).contains(&settings.strips) {
            return Err(KikPiotrowskiError::InvalidInput {
                name: "strips",
                requirement: "in 4..=4096",
                value: settings.strips as f64,
            });
        }
        Ok(Self {
            settings,
            strips: vec![PatchStrip::default(); settings.strips],
            last_force_solve: None,
        })
    }

    /// The settings.
    pub fn settings(&self) -> &KikPiotrowskiSettings {
        &self.settings
    }

    /// The strips of the last normal solve.
    pub fn strips(&self) -> &[PatchStrip] {
        &self.strips
    }

    /// Solves the normal problem on `sections` (at least 2, increasing
    /// `y`, curvatures > 0) at `load`, with the effective modulus
    /// `e_star_pa` \[Pa\] (`G/(1 - nu)`). Under force control the
    /// iteration starts from the last force-controlled solve of this
    /// workspace (a wheel/rail load iteration solves one patch at nearby
    /// forces), else from Hertz's circle on the curvature at the smallest
    /// gap; either way it ends within the relative tolerance 1e-9 of the
    /// force.
    pub fn solve_normal(
        &mut self,
        sections: &[KpSection],
        load: NormalLoad,
        e_star_pa: f64,
    ) -> Result<KpNormal, KikPiotrowskiError> {
        let (k_min, min_gap) = validate(sections, e_star_pa)?;
        match load {
            NormalLoad::Approach(d) => {
                if !d.is_finite() {
                    return Err(invalid("load", "a finite approach", d));
                }
                if d <= min_gap {
                    return Err(KikPiotrowskiError::NoContact {
                        approach_m: d,
                        min_gap_m: min_gap,
                    });
                }
                Ok(self.at_penetration(sections, k_min, d - min_gap, min_gap, e_star_pa))
            }
            NormalLoad::NormalForce(f) => {
                if !(f.is_finite() && f > 0.0) {
                    return Err(invalid("load", "a finite normal force > 0", f));
                }
                // Start: the last solve's power law, or Hertz's circle on
                // the curvature at the minimum, delta = (9 F^2 k/(32
                // E*^2))^(1/3) (R = 1/k, A = B = k/2), where Fn grows as
                // delta^(3/2).
                let (mut delta, mut slope) = match self.last_force_solve {
                    Some((d, f0, slope)) => (d * (f / f0).powf(1.0 / slope), slope),
                    None => {
                        let k0 = sections[k_min].curvature_x_per_m;
                        let e2 = e_star_pa * e_star_pa;
                        ((9.0 * f * f * k0 / (32.0 * e2)).cbrt(), 1.5)
                    }
                };
                let mut last: Option<(f64, f64)> = None;
                for step in 1..=MAX_ITERATIONS {
                    let mut n = self.at_penetration(sections, k_min, delta, min_gap, e_star_pa);
                    n.iterations = step;
                    let (ld, lf) = (delta.ln(), n.normal_force_n.ln());
                    if (n.normal_force_n / f - 1.0).abs() <= FORCE_TOLERANCE {
                        self.last_force_solve = Some((delta, n.normal_force_n, slope));
                        return Ok(n);
                    }
                    if let Some((ld0, lf0)) = last {
                        if (ld - ld0).abs() > 0.0 && lf != lf0 {
                            slope = ((lf - lf0) / (ld - ld0)).clamp(0.5, 4.0);
                        }
                    }
                    last = Some((ld, lf));
                    delta = (ld + (f.ln() - lf) / slope).exp();
                }
                Err(KikPiotrowskiError::NotConverged {
                    normal_force_n: f,
                    iterations: MAX_ITERATIONS,
                })
            }
        }
    }

    /// The normal solution at penetration `delta` > 0 of validated
    /// sections whose smallest gap `min_gap` is at section `k_min`.
    fn at_penetration(
        &mut self,
        sections: &[KpSection],
        k_min: usize,
        delta: f64,
        min_gap: f64,
        e_star_pa: f64,
    ) -> KpNormal {
        let virtual_pen = self.settings.penetration_factor * delta;
        // g(y) at section k.
        let g = |k: usize| virtual_pen - (sections[k].gap_m - min_gap);
        // Lateral extent of g > 0: the outermost crossings (the area may
        // have gaps inside; its strips are then empty there).
        let first = (0..sections.len()).find(|&k| g(k) > 0.0).unwrap_or(k_min);
        let last = (0..sections.len())
            .rev()
            .find(|&k| g(k) > 0.0)
            .unwrap_or(k_min);
        let crossing = |inside: usize, outside: usize| {
            let (gi, go) = (g(inside), g(outside));
            let t = gi / (gi - go);
            sections[inside].y_m + t * (sections[outside].y_m - sections[inside].y_m)
        };
        let y_lo = if first > 0 {
            crossing(first, first - 1)
        } else {
            sections[0].y_m
        };
        let y_hi = if last + 1 < sections.len() {
            crossing(last, last + 1)
        } else {
            sections[sections.len() - 1].y_m
        };
        let n = self.strips.len();
        let dy = (y_hi - y_lo) / n as f64;
        let mut a_max = 0.0_f64;
        let mut area = 0.0;
        let mut k = 0;
        for (j, strip) in self.strips.iter_mut().enumerate() {
            let y = y_lo + (j as f64 + 0.5) * dy;
            while k + 2 < sections.len() && sections[k + 1].y_m < y {
                k += 1;
            }
            let (s0, s1) = (&sections[k], &sections[k + 1]);
            let t = ((y - s0.y_m) / (s1.y_m - s0.y_m)).clamp(0.0, 1.0);
            let mix = |u: f64, v: f64| u + t * (v - u);
            let gap = mix(s0.gap_m, s1.gap_m);
            let curvature = mix(s0.curvature_x_per_m, s1.curvature_x_per_m);
            let gj = virtual_pen - (gap - min_gap);
            let half = if gj > 0.0 {
                (2.0 * gj / curvature).sqrt()
            } else {
                0.0
            };
            *strip = PatchStrip {
                y_m: y,
                half_length_m: half,
                centre_x_m: mix(s0.centre_x_m, s1.centre_x_m),
            };
            a_max = a_max.max(half);
            area += 2.0 * half * dy;
        }
        // The point of largest interpenetration.
        let (y0, x0) = (sections[k_min].y_m, sections[k_min].centre_x_m);
        let mut displacement = 0.0;
        let mut force_shape = 0.0;
        for s in &self.strips {
            let a = s.half_length_m;
            if a <= 0.0 {
                continue;
            }
            force_shape += 0.5 * std::f64::consts::PI * a * a * dy;
            let eta = s.y_m - y0;
            let c2 = (s.centre_x_m - x0).powi(2);
            displacement += if eta.abs() < 2.5 * dy {
                near_strip_integral(a, eta - 0.5 * dy, eta + 0.5 * dy)
            } else {
                GAUSS4
                    .iter()
                    .map(|&(t, w)| 0.5 * dy * w * strip_integral(a, eta + 0.5 * dy * t, c2))
                    .sum::<f64>()
            };
        }
        // delta = p0 displacement/(pi a_max E*).
        let p0 = delta * std::f64::consts::PI * a_max * e_star_pa / displacement;
        let width = 0.5 * (y_hi - y_lo);
        let ratio = a_max / width;
        let a_e = (area / std::f64::consts::PI * ratio).sqrt();
        KpNormal {
            approach_m: min_gap + delta,
            penetration_m: delta,
            normal_force_n: p0 * force_shape / a_max,
            max_pressure_pa: p0,
            contact_area_m2: area,
            y_range_m: [y_lo, y_hi],
            max_half_length_m: a_max,
            strip_width_m: dy,
            equivalent_semi_axes_m: [a_e, a_e / ratio],
            iterations: 0,
        }
    }

    /// FASTSIM on the area of `normal`, the last normal solve of this
    /// workspace ([`Fastsim::solve_strips`]): `input`'s friction, material
    /// and creepages (about `x = 0`, `y = 0` of the sections), its
    /// semi-axes and normal force replaced by `normal`'s equivalent ellipse
    /// and force.
    pub fn solve_tangential(
        &self,
        normal: &KpNormal,
        input: &FastsimInput,
        fastsim: &mut Fastsim,
    ) -> Result<FastsimOutput, KikPiotrowskiError> {
        let [a, b] = normal.equivalent_semi_axes_m;
        let input = FastsimInput {
            semi_axis_x_m: a,
            semi_axis_y_m: b,
            normal_force_n: normal.normal_force_n,
            ..*input
        };
        Ok(fastsim.solve_strips(&input, &self.strips, normal.strip_width_m)?)
    }
}

fn invalid(name: &'static str, requirement: &'static str, value: f64) -> KikPiotrowskiError {
    KikPiotrowskiError::InvalidInput {
        name,
        requirement,
        value,
    }
}

/// Checks the sections and modulus; the index of the smallest gap and the
/// gap.
fn validate(sections: &[KpSection], e_star_pa: f64) -> Result<(usize, f64), KikPiotrowskiError> {
    if !(e_star_pa.is_finite() && e_star_pa > 0.0) {
        return Err(invalid("e_star_pa", "finite and > 0", e_star_pa));
    }
    if sections.len() < 2 {
        return Err(invalid(
            "sections",
            "at least 2 sections",
            sections.len() as f64,
        ));
    }
    let (mut k_min, mut min_gap) = (0, f64::INFINITY);
    for (k, s) in sections.iter().enumerate() {
        if !(s.y_m.is_finite() && s.gap_m.is_finite() && s.centre_x_m.is_finite()) {
            return Err(invalid("sections", "finite positions and gaps", s.gap_m));
        }
        if !(s.curvature_x_per_m.is_finite() && s.curvature_x_per_m > 0.0) {
            return Err(invalid(
                "sections",
                "curvatures finite and > 0",
                s.curvature_x_per_m,
            ));
        }
        if k > 0 && s.y_m <= sections[k - 1].y_m {
            return Err(invalid("sections", "y_m increasing", s.y_m));
        }
        if s.gap_m < min_gap {
            (k_min, min_gap) = (k, s.gap_m);
        }
    }
    Ok((k_min, min_gap))
}

/// `∫ sqrt(a^2 - s^2)/sqrt(s^2 + eta^2 + c2) ds` over `|s| < a`
/// (module docs), `eta^2 + c2 > 0`.
fn strip_integral(a: f64, eta: f64, c2: f64) -> f64 {
    let r2 = a * a + eta * eta + c2;
    // m < 1 since eta^2 + c2 > 0.
    let m = (a * a / r2).min(1.0 - f64::EPSILON);
    let d = elliptic_d(m);
    2.0 * a * a * d / r2.sqrt()
}

/// The strip integral's logarithmic limit `2a (ln(4a/|eta|) - 1)`.
fn strip_log_limit(a: f64, eta: f64) -> f64 {
    2.0 * a * ((4.0 * a / eta.abs()).ln() - 1.0)
}

/// `∫ strip_integral(a, eta, 0) d eta` over `lo < eta < hi`: the
/// logarithmic limit in closed form (`∫_0^t 2a (ln(4a/|eta|) - 1) d eta =
/// 2a t ln(4a/|t|)`), the rest, bounded, by Gauss-Legendre on either side
/// of `eta = 0`.
fn near_strip_integral(a: f64, lo: f64, hi: f64) -> f64 {
    let closed = |t: f64| {
        if t != 0.0 {
            2.0 * a * t * (4.0 * a / t.abs()).ln()
        } else {
            0.0
        }
    };
    let rest = |from: f64, to: f64| {
        let half = 0.5 * (to - from);
        GAUSS4
            .iter()
            .map(|&(u, w)| {
                let eta = from + half * (u + 1.0);
                half * w * (strip_integral(a, eta, 0.0) - strip_log_limit(a, eta))
            })
            .sum::<f64>()
    };
    let rest = if lo < 0.0 && hi > 0.0 {
        rest(lo, 0.0) + rest(0.0, hi)
    } else {
        rest(lo, hi)
    };
    closed(hi) - closed(lo) + rest
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::hertz::{complete_elliptic, hertz, HertzLoad};

    const G: f64 = 8.0e10;
    const NU: f64 = 0.28;

    fn e_star() -> f64 {
        G / (1.0 - NU)
    }

    /// Sections of `h = A x^2 + B y^2` over `|y| < half_width`.
    fn quadratic(a_per_m: f64, b_per_m: f64, half_width: f64, n: usize) -> Vec<KpSection> {
        (0..n)
            .map(|k| {
                let y = -half_width + 2.0 * half_width * k as f64 / (n - 1) as f64;
                KpSection {
                    y_m: y,
                    gap_m: b_per_m * y * y,
                    centre_x_m: 0.0,
                    curvature_x_per_m: 2.0 * a_per_m,
                }
            })
            .collect()
    }

    fn rel(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs()
    }

    #[test]
    fn strip_integral_matches_its_limits() {
        // Far away: the line load of the strip's force, (pi a^2/2)/eta.
        let (a, eta) = (1e-3, 1.0);
        let far = strip_integral(a, eta, 0.0);
        assert!(rel(far, 0.5 * std::f64::consts::PI * a * a / eta) < 1e-6);
        // Close: the logarithmic limit.
        let eta = 1e-7;
        assert!(rel(strip_integral(a, eta, 0.0), strip_log_limit(a, eta)) < 1e-6);
    }

    /// On a quadratic gap the area is an ellipse with Hertz's pressure
    /// shape on it, whose centre displacement is `p0 b K(1 - b^2/a^2)/E*`
    /// (Hertz's elliptical contact as [`crate::core::hertz`] solves it; `b`
    /// the shorter semi-axis), so
    /// `Fn = (2/3) pi a b p0` with `p0 = E* delta/(b K)`.
    #[test]
    fn quadratic_gap_matches_the_closed_form() {
        for (a_per_m, b_per_m) in [(1.0, 1.0), (1.0, 4.0), (3.0, 0.7)] {
            let sections = quadratic(a_per_m, b_per_m, 0.02, 401);
            let mut kp = KikPiotrowski::new(KikPiotrowskiSettings::default()).unwrap();
            let delta = 1e-4;
            let n = kp
                .solve_normal(&sections, NormalLoad::Approach(delta), e_star())
                .unwrap();
            let eps = PENETRATION_FACTOR;
            let (sa, sb) = (
                (eps * delta / a_per_m).sqrt(),
                (eps * delta / b_per_m).sqrt(),
            );
            let (long, short) = (sa.max(sb), sa.min(sb));
            let k = complete_elliptic(1.0 - (short / long).powi(2)).unwrap().k;
            let p0 = e_star() * delta / (short * k);
            let fn_closed = 2.0 / 3.0 * std::f64::consts::PI * sa * sb * p0;
            println!(
                "A {a_per_m} B {b_per_m}: Fn {} closed {fn_closed}, p0 {} closed {p0}, area {} closed {}",
                n.normal_force_n,
                n.max_pressure_pa,
                n.contact_area_m2,
                std::f64::consts::PI * sa * sb
            );
            assert!(rel(n.normal_force_n, fn_closed) < 1.5e-3);
            assert!(rel(n.max_pressure_pa, p0) < 1.5e-3);
            assert!(rel(n.contact_area_m2, std::f64::consts::PI * sa * sb) < 1.5e-3);
        }
    }

    /// Under a given load a circle's radius is `(2 eps)^(1/3)` times
    /// Hertz's (module docs: Fn = (4/3) E* a delta with a = sqrt(2 eps R
    /// delta), against Hertz's a^3 = 3 Fn R/(4 E*) for a circle, Johnson,
    /// Contact Mechanics, 1985), and the force is met to the tolerance.
    #[test]
    fn circle_under_load_has_the_known_bias() {
        let r = 0.46;
        let sections = quadratic(0.5 / r, 0.5 / r, 0.02, 401);
        let f = 1e5;
        let h = hertz(
            0.5 / r,
            0.5 / r,
            e_star(),
            HertzLoad::NormalForce { normal_force_n: f },
        )
        .unwrap();
        for eps in [0.5, 0.55] {
            let mut kp = KikPiotrowski::new(KikPiotrowskiSettings {
                penetration_factor: eps,
                ..KikPiotrowskiSettings::default()
            })
            .unwrap();
            let n = kp
                .solve_normal(&sections, NormalLoad::NormalForce(f), e_star())
                .unwrap();
            assert!(rel(n.normal_force_n, f) < 1e-9);
            let radius = n.max_half_length_m;
            let expected = h.semi_axis_x_m * (2.0 * eps).cbrt();
            println!(
                "eps {eps}: radius {radius} expected {expected}, area {} Hertz {}, {} steps",
                n.contact_area_m2, h.contact_area_m2, n.iterations
            );
            assert!(rel(radius, expected) < 2e-3);
        }
    }

    fn tangential(
        kp: &KikPiotrowski,
        n: &KpNormal,
        creepages: [f64; 3],
    ) -> (FastsimOutput, FastsimInput) {
        let input = FastsimInput {
            semi_axis_x_m: 1.0,
            semi_axis_y_m: 1.0,
            normal_force_n: 1.0,
            shear_modulus_pa: G,
            poisson_ratio: NU,
            friction_coefficient: 0.3,
            static_friction_coefficient: 0.3,
            creepage_long: creepages[0],
            creepage_lat: creepages[1],
            spin_per_m: creepages[2],
        };
        let mut fastsim = Fastsim::totals_only(40, 2).unwrap();
        let out = kp.solve_tangential(n, &input, &mut fastsim).unwrap();
        (out, input)
    }

    /// Small creepage: Kalker's linear theory on the area's ellipse
    /// (`Fx = -G a b C11 xi`, `Fy = -G a b C22 eta`, the coefficients of
    /// [`crate::core::creep::kalker_creep_coefficients`]) —
    /// FASTSIM's flexibilities reproduce it, on a quadratic gap the area
    /// and the equivalent ellipse are that ellipse. Large creepage: full
    /// sliding, `|F| = mu Fn`.
    #[test]
    fn tangential_limits() {
        use crate::core::creep::kalker_creep_coefficients;
        let sections = quadratic(1.0, 2.5, 0.02, 401);
        let mut kp = KikPiotrowski::new(KikPiotrowskiSettings::default()).unwrap();
        let n = kp
            .solve_normal(&sections, NormalLoad::NormalForce(1e5), e_star())
            .unwrap();
        let [a, b] = n.equivalent_semi_axes_m;
        let coef = kalker_creep_coefficients(a / b, NU).unwrap();
        let xi = 1e-6;
        let (out, _) = tangential(&kp, &n, [xi, 0.0, 0.0]);
        let fx = -G * a * b * coef.c11 * xi;
        println!("Fx {} linear {fx}", out.fx_n);
        assert!(rel(out.fx_n, fx) < 2e-3);
        let (out, _) = tangential(&kp, &n, [0.0, xi, 0.0]);
        let fy = -G * a * b * coef.c22 * xi;
        println!("Fy {} linear {fy}", out.fy_n);
        assert!(rel(out.fy_n, fy) < 2e-3);
        for creep in [[0.05, 0.0, 0.0], [0.03, -0.04, 0.0], [0.0, 0.05, 1.0]] {
            let (out, input) = tangential(&kp, &n, creep);
            let f = out.fx_n.hypot(out.fy_n);
            let limit = input.friction_coefficient * n.normal_force_n;
            println!("{creep:?}: |F| {f} mu Fn {limit}");
            assert!(rel(f, limit) < 2e-3);
        }
    }

    /// The area may be anything the gap gives: a gap with two minima at
    /// the same depth gives two lobes of equal force, each carried by the
    /// strips on its side, and the load is met.
    #[test]
    fn two_lobes_share_the_load() {
        let sections: Vec<KpSection> = (0..401)
            .map(|k| {
                let y = -0.02 + 0.04 * k as f64 / 400.0;
                let d = y.abs() - 0.006;
                KpSection {
                    y_m: y,
                    gap_m: 3.0 * d * d,
                    centre_x_m: 0.0,
                    curvature_x_per_m: 2.0,
                }
            })
            .collect();
        let mut kp = KikPiotrowski::new(KikPiotrowskiSettings {
            strips: 200,
            ..KikPiotrowskiSettings::default()
        })
        .unwrap();
        let n = kp
            .solve_normal(&sections, NormalLoad::NormalForce(5e4), e_star())
            .unwrap();
        assert!(rel(n.normal_force_n, 5e4) < 1e-9);
        let strips = kp.strips();
        let side = |neg: bool| -> f64 {
            strips
                .iter()
                .filter(|s| (s.y_m < 0.0) == neg)
                .map(|s| s.half_length_m * s.half_length_m)
                .sum()
        };
        assert!(strips.iter().any(|s| s.half_length_m == 0.0));
        assert!(rel(side(true), side(false)) < 1e-2);
    }

    /// A force-controlled solve started from the workspace's last one ends
    /// where a cold start does, within the force tolerance, in fewer steps.
    #[test]
    fn warm_start_agrees_with_a_cold_one() {
        let sections = quadratic(1.0, 2.5, 0.02, 401);
        let e = e_star();
        let mut cold = KikPiotrowski::new(KikPiotrowskiSettings::default()).unwrap();
        let c = cold
            .solve_normal(&sections, NormalLoad::NormalForce(1e5), e)
            .unwrap();
        let mut warm = KikPiotrowski::new(KikPiotrowskiSettings::default()).unwrap();
        warm.solve_normal(&sections, NormalLoad::NormalForce(0.97e5), e)
            .unwrap();
        let w = warm
            .solve_normal(&sections, NormalLoad::NormalForce(1e5), e)
            .unwrap();
        assert!(rel(w.normal_force_n, 1e5) < 1e-9);
        assert!(rel(w.penetration_m, c.penetration_m) < 1e-8);
        assert!(rel(w.max_pressure_pa, c.max_pressure_pa) < 1e-8);
        assert!(
            w.iterations <= c.iterations,
            "{} {}",
            w.iterations,
            c.iterations
        );
    }

    #[test]
    fn rejects_bad_input() {
        assert!(KikPiotrowski::new(KikPiotrowskiSettings {
            penetration_factor: 0.0,
            ..KikPiotrowskiSettings::default()
        })
        .is_err());
        let mut kp = KikPiotrowski::new(KikPiotrowskiSettings::default()).unwrap();
        let good = quadratic(1.0, 1.0, 0.01, 11);
        let e = e_star();
        assert!(matches!(
            kp.solve_normal(&good, NormalLoad::Approach(-1e-5), e),
            Err(KikPiotrowskiError::NoContact { .. })
        ));
        assert!(kp
            .solve_normal(&good, NormalLoad::NormalForce(f64::NAN), e)
            .is_err());
        assert!(kp
            .solve_normal(&good[..1], NormalLoad::NormalForce(1.0), e)
            .is_err());
        let mut bad = good.clone();
        bad[3].curvature_x_per_m = 0.0;
        assert!(kp
            .solve_normal(&bad, NormalLoad::NormalForce(1.0), e)
            .is_err());
        let mut bad = good;
        bad[3].y_m = bad[2].y_m;
        assert!(kp
            .solve_normal(&bad, NormalLoad::NormalForce(1.0), e)
            .is_err());
    }
}
