//! Kalker's creep coefficients `C11, C22, C23, C33` of the linear theory of
//! rolling contact for elliptical contact areas.
//!
//! # Conventions (Kalker's)
//!
//! * Semi-axes `a` along `x` (rolling direction) and `b` along `y` (lateral)
//!   \[m\]; `c = sqrt(a b)` \[m\]. Combined shear modulus `G` \[Pa\] and Poisson
//!   ratio `nu` [-] as Kalker combines two bodies (see
//!   [`crate::core::material::CombinedMaterial`]).
//! * Tractions act on body 1; creepages are the rigid velocity of body 1
//!   relative to body 2 divided by the rolling speed: longitudinal `xi` [-],
//!   lateral `eta` [-], spin `phi` [1/m]. Rigid slip `w_x = xi - phi y`,
//!   `w_y = eta + phi x`.
//! * Linear theory (vanishing creepage, full adhesion):
//!   `Fx = -G c^2 C11 xi`, `Fy = -G c^2 (C22 eta + c C23 phi)`,
//!   `Mz = G c^3 (C23 eta - c C33 phi)`. See [`kalker_linear_forces`].
//!   The signs of `Mz` agree with Kalker's simplified theory
//!   (FASTSIM, [`crate::core::fastsim`]): pure `eta > 0` gives `Mz > 0`, pure
//!   `phi > 0` gives `Mz < 0` and `Fy < 0`.
//!
//! # Source of the table
//!
//! J. J. Kalker, *Three-dimensional elastic bodies in rolling contact*,
//! Kluwer, 1990, Table E3 (also Kalker, *On the rolling contact of two elastic
//! bodies in the presence of dry friction*, thesis, Delft 1967; reproduced in
//! K. L. Johnson, *Contact Mechanics*, 1985, Table 8.1). `C11, C22, C23` were
//! checked against the table as used in E. A. H. Vollebregt's CONTACT
//! program; the `C33` columns for `nu = 0.25, 0.5` were checked against an
//! independent reproduction. Note: some copies of the table carry a typo
//! `C23(g = 0.8, nu = 0.25) = 1.15`; the correct value is `1.25`.
//!
//! # Interpolation (documented choices)
//!
//! * Aspect ratio: for each tabulated `nu`, `ln C` is interpolated in
//!   `ln(a/b)` with a shape-preserving piecewise cubic Hermite interpolant
//!   (Fritsch–Carlson "PCHIP") over all 19 nodes `a/b = 0.1 .. 1 .. 10`.
//!   It is exact at the nodes, C1-continuous (also at `a/b = 1`) and keeps the
//!   monotonicity of the tabulated data.
//! * Poisson ratio: `1/C` is interpolated quadratically (Lagrange) through
//!   `nu = 0, 0.25, 0.5`. `1/C` is almost linear in `nu` (second differences
//!   ~1% of first differences, whereas `C` itself is clearly curved), so this
//!   is more accurate than piecewise-linear interpolation of `C`; at the
//!   nodes the table is reproduced exactly.
//! * Beyond the table (`a/b < 0.1` or `a/b > 10`, accepted down to `1e-4` and
//!   up to `1e4`): Kalker's asymptotic expressions for `g = min(a/b, b/a) -> 0`
//!   (see [`kalker_creep_coefficients`]) are scaled by a constant so they meet
//!   the table value at `g = 0.1` exactly (continuous, correct growth rate).
//!   For `C33` with `a > b` no asymptote is used; instead a power law
//!   `C33 ~ g^p` fitted to the rows `g = 0.1, 0.2` is continued (heuristic,
//!   only matters for extremely long ellipses).

use thiserror::Error;

/// Poisson ratios of the table columns [-].
pub const KALKER_POISSON: [f64; 3] = [0.0, 0.25, 0.5];

/// Smallest accepted `a/b` [-] (largest is its inverse).
pub const MIN_ASPECT_RATIO: f64 = 1e-4;

/// Errors for creep-coefficient look-up.
#[derive(Debug, Clone, Copy, PartialEq, Error)]
pub enum CreepError {
    /// `a/b` is not finite or not > 0.
    #[error("aspect ratio a/b must be finite and > 0, got {0}")]
    InvalidAspectRatio(f64),
    /// `a/b` is outside `[1e-4, 1e4]`.
    #[error("aspect ratio a/b = {0} outside the supported range [1e-4, 1e4]")]
    AspectRatioOutOfRange(f64),
    /// Poisson ratio outside `[0, 0.5]` or not finite.
    #[error("Poisson ratio must lie in [0, 0.5], got {0}")]
    InvalidPoissonRatio(f64),
    /// Another input (named) is out of range.
    #[error("{name} must be {requirement}, got {value}")]
    InvalidInput {
        /// Parameter name.
        name: &'static str,
        /// What is required.
        requirement: &'static str,
        /// The offending value.
        value: f64,
    },
}

/// Kalker's creep coefficients at one `a/b` and `nu` [-].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CreepCoefficients {
    /// Longitudinal coefficient `C11` [-].
    pub c11: f64,
    /// Lateral coefficient `C22` [-].
    pub c22: f64,
    /// Lateral/spin coupling coefficient `C23` [-].
    pub c23: f64,
    /// Spin/moment coefficient `C33` [-].
    pub c33: f64,
}

/// One row of Kalker's Table E3: coefficients at `nu = 0, 0.25, 0.5`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KalkerTableRow {
    /// `g = min(a/b, b/a)` as printed in the table [-].
    pub g: f64,
    /// `true` for the `a <= b` half of the table (`a/b = g`), `false` for
    /// `a > b` (`a/b = 1/g`).
    pub a_le_b: bool,
    /// `C11` at `nu = 0, 0.25, 0.5` [-].
    pub c11: [f64; 3],
    /// `C22` at `nu = 0, 0.25, 0.5` [-].
    pub c22: [f64; 3],
    /// `C23` at `nu = 0, 0.25, 0.5` [-].
    pub c23: [f64; 3],
    /// `C33` at `nu = 0, 0.25, 0.5` [-].
    pub c33: [f64; 3],
}

impl KalkerTableRow {
    /// The row's `a/b` [-].
    pub fn a_over_b(&self) -> f64 {
        if self.a_le_b {
            self.g
        } else {
            1.0 / self.g
        }
    }

    /// The row's coefficients at tabulated Poisson ratio index `i`
    /// (`0 -> nu = 0`, `1 -> 0.25`, `2 -> 0.5`); `None` if `i > 2`.
    pub fn at_nu_index(&self, i: usize) -> Option<CreepCoefficients> {
        Some(CreepCoefficients {
            c11: *self.c11.get(i)?,
            c22: *self.c22.get(i)?,
            c23: *self.c23.get(i)?,
            c33: *self.c33.get(i)?,
        })
    }

    fn coef(&self, which: usize) -> &[f64; 3] {
        match which {
            0 => &self.c11,
            1 => &self.c22,
            2 => &self.c23,
            _ => &self.c33,
        }
    }
}

const fn row(
    g: f64,
    a_le_b: bool,
    c11: [f64; 3],
    c22: [f64; 3],
    c23: [f64; 3],
    c33: [f64; 3],
) -> KalkerTableRow {
    KalkerTableRow {
        g,
        a_le_b,
        c11,
        c22,
        c23,
        c33,
    }
}

/// Kalker's Table E3, rows ordered by increasing `a/b` (0.1 ... 1 ... 10).
// The tabulated value 3.14 is data, not an approximation of pi.
#[allow(clippy::approx_constant)]
pub const KALKER_TABLE: [KalkerTableRow; 19] = [
    // a <= b, g = a/b
    row(
        0.1,
        true,
        [2.51, 3.31, 4.85],
        [2.51, 2.52, 2.53],
        [0.334, 0.473, 0.731],
        [6.42, 8.28, 11.7],
    ),
    row(
        0.2,
        true,
        [2.59, 3.37, 4.81],
        [2.59, 2.63, 2.66],
        [0.483, 0.603, 0.809],
        [3.46, 4.27, 5.66],
    ),
    row(
        0.3,
        true,
        [2.68, 3.44, 4.80],
        [2.68, 2.75, 2.81],
        [0.607, 0.715, 0.889],
        [2.49, 2.96, 3.72],
    ),
    row(
        0.4,
        true,
        [2.78, 3.53, 4.82],
        [2.78, 2.88, 2.98],
        [0.720, 0.823, 0.977],
        [2.02, 2.32, 2.77],
    ),
    row(
        0.5,
        true,
        [2.88, 3.62, 4.83],
        [2.88, 3.01, 3.14],
        [0.827, 0.929, 1.07],
        [1.74, 1.93, 2.22],
    ),
    row(
        0.6,
        true,
        [2.98, 3.72, 4.91],
        [2.98, 3.14, 3.31],
        [0.930, 1.03, 1.18],
        [1.56, 1.68, 1.86],
    ),
    row(
        0.7,
        true,
        [3.09, 3.81, 4.97],
        [3.09, 3.28, 3.48],
        [1.03, 1.14, 1.29],
        [1.43, 1.50, 1.60],
    ),
    row(
        0.8,
        true,
        [3.19, 3.91, 5.05],
        [3.19, 3.41, 3.65],
        [1.13, 1.25, 1.40],
        [1.34, 1.37, 1.42],
    ),
    row(
        0.9,
        true,
        [3.29, 4.01, 5.12],
        [3.29, 3.54, 3.82],
        [1.23, 1.36, 1.51],
        [1.27, 1.27, 1.27],
    ),
    row(
        1.0,
        true,
        [3.40, 4.12, 5.20],
        [3.40, 3.67, 3.98],
        [1.33, 1.47, 1.63],
        [1.21, 1.19, 1.16],
    ),
    // a > b, g = b/a
    row(
        0.9,
        false,
        [3.51, 4.22, 5.30],
        [3.51, 3.81, 4.16],
        [1.44, 1.59, 1.77],
        [1.16, 1.11, 1.06],
    ),
    row(
        0.8,
        false,
        [3.65, 4.36, 5.42],
        [3.65, 3.99, 4.39],
        [1.58, 1.75, 1.94],
        [1.10, 1.04, 0.954],
    ),
    row(
        0.7,
        false,
        [3.82, 4.54, 5.58],
        [3.82, 4.21, 4.67],
        [1.76, 1.95, 2.18],
        [1.05, 0.965, 0.852],
    ),
    row(
        0.6,
        false,
        [4.06, 4.78, 5.80],
        [4.06, 4.50, 5.04],
        [2.01, 2.23, 2.50],
        [1.01, 0.892, 0.751],
    ),
    row(
        0.5,
        false,
        [4.37, 5.10, 6.11],
        [4.37, 4.90, 5.56],
        [2.35, 2.62, 2.96],
        [0.958, 0.819, 0.650],
    ),
    row(
        0.4,
        false,
        [4.84, 5.57, 6.57],
        [4.84, 5.48, 6.31],
        [2.88, 3.24, 3.70],
        [0.912, 0.747, 0.549],
    ),
    row(
        0.3,
        false,
        [5.57, 6.34, 7.34],
        [5.57, 6.40, 7.51],
        [3.79, 4.32, 5.01],
        [0.868, 0.674, 0.446],
    ),
    row(
        0.2,
        false,
        [6.96, 7.78, 8.82],
        [6.96, 8.14, 9.79],
        [5.72, 6.63, 7.89],
        [0.828, 0.601, 0.341],
    ),
    row(
        0.1,
        false,
        [10.7, 11.7, 12.9],
        [10.7, 12.8, 16.0],
        [12.2, 14.6, 18.0],
        [0.795, 0.526, 0.228],
    ),
];

const N_ROWS: usize = KALKER_TABLE.len();

/// Kalker's creep coefficients for aspect ratio `a_over_b = a/b` [-] (`a`
/// along the rolling direction) and Poisson ratio `poisson_ratio` in
/// `[0, 0.5]` [-].
///
/// Inside the table range `0.1 <= a/b <= 10` the table is interpolated (see
/// module docs). Outside, down to `a/b = 1e-4` and up to `1e4`, Kalker's
/// asymptotic forms for `g -> 0` are used, scaled to meet the table at
/// `g = 0.1`:
///
/// * `a < b`, `g = a/b`: `C11 = pi^2/(4(1-nu))`, `C22 = pi^2/4`,
///   `C23 = pi sqrt(g)/(3(1-nu)) (1 + nu (ln(16/g) - 5))`,
///   `C33 = pi^2/(16 (1-nu) g)`;
/// * `a > b`, `g = b/a`, `L = ln(16/g^2)`:
///   `C11 = 2 pi/((L - 2nu) g) (1 + (3 - ln 4)/(L - 2nu))`,
///   `C22 = 2 pi/(((1-nu)L + 2nu) g) (1 + (1-nu)(3 - ln 4)/((1-nu)L + 2nu))`,
///   `C23 = 2 pi/(3 g^1.5 ((1-nu)L - 2 + 4nu))`, and `C33` continued as a
///   power law in `g` through the table rows `g = 0.1, 0.2`.
pub fn kalker_creep_coefficients(
    a_over_b: f64,
    poisson_ratio: f64,
) -> Result<CreepCoefficients, CreepError> {
    if !(a_over_b.is_finite() && a_over_b > 0.0) {
        return Err(CreepError::InvalidAspectRatio(a_over_b));
    }
    if !(MIN_ASPECT_RATIO..=1.0 / MIN_ASPECT_RATIO).contains(&a_over_b) {
        return Err(CreepError::AspectRatioOutOfRange(a_over_b));
    }
    if !(0.0..=0.5).contains(&poisson_ratio) {
        return Err(CreepError::InvalidPoissonRatio(poisson_ratio));
    }
    let mut out = [0.0; 4];
    if let Some(i) = KALKER_POISSON.iter().position(|&n| n == poisson_ratio) {
        for (which, o) in out.iter_mut().enumerate() {
            *o = coefficient_at_node(which, i, a_over_b);
        }
    } else {
        let nu = poisson_ratio;
        let w = [
            8.0 * (nu - 0.25) * (nu - 0.5),
            -16.0 * nu * (nu - 0.5),
            8.0 * nu * (nu - 0.25),
        ];
        for (which, o) in out.iter_mut().enumerate() {
            let inv: f64 = (0..3)
                .map(|i| w[i] / coefficient_at_node(which, i, a_over_b))
                .sum();
            *o = 1.0 / inv;
        }
    }
    Ok(CreepCoefficients {
        c11: out[0],
        c22: out[1],
        c23: out[2],
        c33: out[3],
    })
}

/// Linear-theory creep forces and spin moment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearCreepForces {
    /// Longitudinal force on body 1 \[N\].
    pub fx_n: f64,
    /// Lateral force on body 1 \[N\].
    pub fy_n: f64,
    /// Spin moment on body 1 about the contact centre [N m].
    pub mz_nm: f64,
    /// The coefficients used [-].
    pub coefficients: CreepCoefficients,
}

/// Kalker's linear theory: `Fx = -G c^2 C11 xi`,
/// `Fy = -G c^2 (C22 eta + c C23 phi)`, `Mz = G c^3 (C23 eta - c C33 phi)`
/// with `c = sqrt(a b)`.
///
/// * `semi_axis_x_m`, `semi_axis_y_m`: `a`, `b` \[m\], finite and > 0.
/// * `shear_modulus_pa`: combined `G` \[Pa\], finite and > 0.
/// * `poisson_ratio`: combined `nu` in `[0, 0.5]` [-].
/// * `creepage_long` `xi` [-], `creepage_lat` `eta` [-], `spin_per_m`
///   `phi` [1/m], finite.
pub fn kalker_linear_forces(
    semi_axis_x_m: f64,
    semi_axis_y_m: f64,
    shear_modulus_pa: f64,
    poisson_ratio: f64,
    creepage_long: f64,
    creepage_lat: f64,
    spin_per_m: f64,
) -> Result<LinearCreepForces, CreepError> {
    for (name, v) in [
        ("semi_axis_x_m", semi_axis_x_m),
        ("semi_axis_y_m", semi_axis_y_m),
        ("shear_modulus_pa", shear_modulus_pa),
    ] {
        if !(v.is_finite() && v > 0.0) {
            return Err(CreepError::InvalidInput {
                name,
                requirement: "finite and > 0",
                value: v,
            });
        }
    }
    for (name, v) in [
        ("creepage_long", creepage_long),
        ("creepage_lat", creepage_lat),
        ("spin_per_m", spin_per_m),
    ] {
        if !v.is_finite() {
            return Err(CreepError::InvalidInput {
                name,
                requirement: "finite",
                value: v,
            });
        }
    }
    let coef = kalker_creep_coefficients(semi_axis_x_m / semi_axis_y_m, poisson_ratio)?;
    let c = (semi_axis_x_m * semi_axis_y_m).sqrt();
    let g = shear_modulus_pa;
    Ok(LinearCreepForces {
        fx_n: -g * c * c * coef.c11 * creepage_long,
        fy_n: -g * c * c * (coef.c22 * creepage_lat + c * coef.c23 * spin_per_m),
        mz_nm: g * c * c * c * (coef.c23 * creepage_lat - c * coef.c33 * spin_per_m),
        coefficients: coef,
    })
}

/// Node abscissa `ln(a/b)` of table row `k`.
fn node_t(k: usize) -> f64 {
    let r = &KALKER_TABLE[k];
    if r.a_le_b {
        r.g.ln()
    } else {
        -r.g.ln()
    }
}

/// Node value `ln C` of coefficient `which` at table row `k`, nu index `i`.
fn node_v(which: usize, i: usize, k: usize) -> f64 {
    KALKER_TABLE[k].coef(which)[i].ln()
}

/// PCHIP derivative at node `k` (Fritsch–Carlson, non-uniform spacing).
fn pchip_slope(which: usize, i: usize, k: usize) -> f64 {
    let h = |j: usize| node_t(j + 1) - node_t(j);
    let delta = |j: usize| (node_v(which, i, j + 1) - node_v(which, i, j)) / h(j);
    if k == 0 || k == N_ROWS - 1 {
        // One-sided three-point estimate, made shape preserving.
        let (h0, h1, d0, d1) = if k == 0 {
            (h(0), h(1), delta(0), delta(1))
        } else {
            (h(k - 1), h(k - 2), delta(k - 1), delta(k - 2))
        };
        let d = ((2.0 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
        if d * d0 <= 0.0 {
            0.0
        } else if d0 * d1 <= 0.0 && d.abs() > 3.0 * d0.abs() {
            3.0 * d0
        } else {
            d
        }
    } else {
        let (h0, h1) = (h(k - 1), h(k));
        let (d0, d1) = (delta(k - 1), delta(k));
        if d0 * d1 <= 0.0 {
            0.0
        } else {
            let w1 = 2.0 * h1 + h0;
            let w2 = h1 + 2.0 * h0;
            (w1 + w2) / (w1 / d0 + w2 / d1)
        }
    }
}

/// Table interpolation of coefficient `which` at nu index `i` for
/// `t = ln(a/b)` within the table range.
fn interpolate_table(which: usize, i: usize, t: f64) -> f64 {
    // Interval k with node_t(k) <= t <= node_t(k + 1).
    let mut k = 0;
    while k + 2 < N_ROWS && t > node_t(k + 1) {
        k += 1;
    }
    let (t0, t1) = (node_t(k), node_t(k + 1));
    let h = t1 - t0;
    let s = ((t - t0) / h).clamp(0.0, 1.0);
    let (v0, v1) = (node_v(which, i, k), node_v(which, i, k + 1));
    let (m0, m1) = (pchip_slope(which, i, k), pchip_slope(which, i, k + 1));
    let s2 = s * s;
    let s3 = s2 * s;
    let h00 = 2.0 * s3 - 3.0 * s2 + 1.0;
    let h10 = s3 - 2.0 * s2 + s;
    let h01 = -2.0 * s3 + 3.0 * s2;
    let h11 = s3 - s2;
    (h00 * v0 + h10 * h * m0 + h01 * v1 + h11 * h * m1).exp()
}

/// Kalker's asymptote for `a < b`, `g = a/b -> 0`.
fn asymptote_a_lt_b(which: usize, nu: f64, g: f64) -> f64 {
    use std::f64::consts::PI;
    match which {
        0 => PI * PI / (4.0 * (1.0 - nu)),
        1 => PI * PI / 4.0,
        2 => PI * g.sqrt() / (3.0 * (1.0 - nu)) * (1.0 + nu * ((16.0 / g).ln() - 5.0)),
        _ => PI * PI / (16.0 * (1.0 - nu) * g),
    }
}

/// Kalker's asymptote for `a > b`, `g = b/a -> 0` (not used for `C33`).
fn asymptote_a_gt_b(which: usize, nu: f64, g: f64) -> f64 {
    use std::f64::consts::PI;
    let l = (16.0 / (g * g)).ln();
    let c = 3.0 - 4.0_f64.ln();
    match which {
        0 => 2.0 * PI / ((l - 2.0 * nu) * g) * (1.0 + c / (l - 2.0 * nu)),
        1 => {
            let q = (1.0 - nu) * l + 2.0 * nu;
            2.0 * PI / (q * g) * (1.0 + (1.0 - nu) * c / q)
        }
        _ => 2.0 * PI / (3.0 * g * g.sqrt() * ((1.0 - nu) * l - 2.0 + 4.0 * nu)),
    }
}

/// Coefficient `which` (0: C11, 1: C22, 2: C23, 3: C33) at tabulated nu
/// index `i` for any accepted `a/b`.
fn coefficient_at_node(which: usize, i: usize, a_over_b: f64) -> f64 {
    let nu = KALKER_POISSON[i];
    let first = &KALKER_TABLE[0];
    let last = &KALKER_TABLE[N_ROWS - 1];
    if a_over_b < first.a_over_b() {
        let edge = first.coef(which)[i];
        edge * asymptote_a_lt_b(which, nu, a_over_b) / asymptote_a_lt_b(which, nu, first.g)
    } else if a_over_b > last.a_over_b() {
        let g = 1.0 / a_over_b;
        let edge = last.coef(which)[i];
        if which == 3 {
            let prev = KALKER_TABLE[N_ROWS - 2].coef(3)[i];
            let p = (prev / edge).ln() / (KALKER_TABLE[N_ROWS - 2].g / last.g).ln();
            edge * (g / last.g).powf(p)
        } else {
            edge * asymptote_a_gt_b(which, nu, g) / asymptote_a_gt_b(which, nu, last.g)
        }
    } else {
        interpolate_table(which, i, a_over_b.ln())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rel(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs()
    }

    fn get(c: &CreepCoefficients, which: usize) -> f64 {
        [c.c11, c.c22, c.c23, c.c33][which]
    }

    #[test]
    fn exact_table_hits() {
        for r in KALKER_TABLE.iter() {
            for (i, &nu) in KALKER_POISSON.iter().enumerate() {
                let c = kalker_creep_coefficients(r.a_over_b(), nu).unwrap();
                let t = r.at_nu_index(i).unwrap();
                for w in 0..4 {
                    assert!(
                        rel(get(&c, w), get(&t, w)) < 1e-13,
                        "a/b {} nu {nu} coef {w}: {} vs {}",
                        r.a_over_b(),
                        get(&c, w),
                        get(&t, w)
                    );
                }
            }
        }
        assert!(KALKER_TABLE[0].at_nu_index(3).is_none());
    }

    #[test]
    fn specific_published_entries() {
        // Kalker (1990) Table E3, spot checks.
        let c = kalker_creep_coefficients(1.0, 0.25).unwrap();
        assert!(rel(c.c11, 4.12) < 1e-13 && rel(c.c22, 3.67) < 1e-13);
        assert!(rel(c.c23, 1.47) < 1e-13 && rel(c.c33, 1.19) < 1e-13);
        let c = kalker_creep_coefficients(0.8, 0.25).unwrap();
        assert!(rel(c.c23, 1.25) < 1e-13, "typo 1.15 must not appear");
        let c = kalker_creep_coefficients(10.0, 0.5).unwrap();
        assert!(rel(c.c22, 16.0) < 1e-13 && rel(c.c33, 0.228) < 1e-13);
    }

    #[test]
    fn table_sanity() {
        // Ordered by a/b; C11 == C22 at nu = 0; all coefficients positive;
        // C22, C23 increase and C33 decreases with a/b (C11 too, except at
        // nu = 0.5 where it has a shallow minimum near a/b = 0.3); C11, C22,
        // C23 increase with nu.
        for k in 0..N_ROWS {
            let r = &KALKER_TABLE[k];
            assert_eq!(r.c11[0], r.c22[0]);
            for i in 0..3 {
                for w in 0..4 {
                    assert!(r.coef(w)[i] > 0.0);
                }
            }
            for w in 0..3 {
                assert!(r.coef(w)[0] < r.coef(w)[1] && r.coef(w)[1] < r.coef(w)[2]);
            }
            if k > 0 {
                let p = &KALKER_TABLE[k - 1];
                assert!(r.a_over_b() > p.a_over_b());
                for i in 0..3 {
                    for w in 0..3 {
                        if w == 0 && i == 2 && k <= 2 {
                            assert!(r.coef(w)[i] < p.coef(w)[i]);
                        } else {
                            assert!(r.coef(w)[i] > p.coef(w)[i], "row {k} coef {w}");
                        }
                    }
                    assert!(r.coef(3)[i] <= p.coef(3)[i], "row {k} C33");
                }
            }
        }
    }

    #[test]
    fn interpolation_is_shape_preserving() {
        // At the tabulated nu, between two nodes the interpolant stays within
        // the node values (PCHIP property).
        for (i, &nu) in KALKER_POISSON.iter().enumerate() {
            for k in 0..N_ROWS - 1 {
                let (t0, t1) = (node_t(k), node_t(k + 1));
                for j in 1..50 {
                    let ab = (t0 + (t1 - t0) * j as f64 / 50.0).exp();
                    let c = kalker_creep_coefficients(ab, nu).unwrap();
                    for w in 0..4 {
                        let (v0, v1) = (KALKER_TABLE[k].coef(w)[i], KALKER_TABLE[k + 1].coef(w)[i]);
                        let v = get(&c, w);
                        assert!(
                            v >= v0.min(v1) * (1.0 - 1e-12) && v <= v0.max(v1) * (1.0 + 1e-12),
                            "a/b {ab} nu index {i} coef {w}: {v} not in [{v0}, {v1}]"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn continuity_at_unit_ratio_and_table_edges() {
        for &nu in &[0.0, 0.28, 0.5] {
            for &x in &[1.0, 0.1, 10.0] {
                let lo = kalker_creep_coefficients(x * (1.0 - 1e-9), nu).unwrap();
                let hi = kalker_creep_coefficients(x * (1.0 + 1e-9), nu).unwrap();
                for w in 0..4 {
                    assert!(rel(get(&lo, w), get(&hi, w)) < 1e-7, "x {x} coef {w}");
                }
            }
            // C1 at a/b = 1: one-sided difference quotients agree.
            let h = 1e-5;
            let f = |ab: f64| kalker_creep_coefficients(ab, nu).unwrap();
            let (c0, cm, cp) = (f(1.0), f(1.0 - h), f(1.0 + h));
            for w in 0..4 {
                let dl = (get(&c0, w) - get(&cm, w)) / h;
                let dr = (get(&cp, w) - get(&c0, w)) / h;
                assert!((dl - dr).abs() < 1e-3 * (1.0 + dl.abs()), "coef {w}");
            }
        }
    }

    #[test]
    fn nu_interpolation_between_columns() {
        // Between columns the value lies between the neighbouring columns.
        for r in KALKER_TABLE.iter() {
            let c = kalker_creep_coefficients(r.a_over_b(), 0.3).unwrap();
            for w in 0..4 {
                let (lo, hi) = (r.coef(w)[1], r.coef(w)[2]);
                let v = get(&c, w);
                assert!(v >= lo.min(hi) - 1e-12 && v <= lo.max(hi) + 1e-12);
            }
        }
    }

    #[test]
    fn asymptotes_scale_correctly() {
        // a << b: C11, C22 constant, C33 ~ 1/g.
        let a = kalker_creep_coefficients(0.01, 0.25).unwrap();
        let b = kalker_creep_coefficients(0.001, 0.25).unwrap();
        assert!(rel(a.c11, 3.31) < 1e-13 && rel(b.c22, 2.52) < 1e-13);
        assert!(rel(b.c33 / a.c33, 10.0) < 1e-12);
        // a >> b: C11 grows roughly like 1/(g ln(1/g)).
        let c = kalker_creep_coefficients(100.0, 0.0).unwrap();
        assert!(c.c11 > 50.0 && c.c11 < 150.0, "{}", c.c11);
    }

    #[test]
    fn rejects_bad_input() {
        for ab in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert!(matches!(
                kalker_creep_coefficients(ab, 0.3),
                Err(CreepError::InvalidAspectRatio(_))
            ));
        }
        for ab in [1e-5, 1e5] {
            assert!(matches!(
                kalker_creep_coefficients(ab, 0.3),
                Err(CreepError::AspectRatioOutOfRange(_))
            ));
        }
        for nu in [-0.01, 0.51, f64::NAN] {
            assert!(matches!(
                kalker_creep_coefficients(1.0, nu),
                Err(CreepError::InvalidPoissonRatio(_))
            ));
        }
        assert!(kalker_linear_forces(0.0, 1.0, 1.0, 0.3, 0.0, 0.0, 0.0).is_err());
        assert!(kalker_linear_forces(1.0, 1.0, 1.0, 0.3, f64::NAN, 0.0, 0.0).is_err());
    }

    #[test]
    fn linear_forces_signs() {
        let (a, b, g) = (6e-3, 4e-3, 8e10);
        let f = kalker_linear_forces(a, b, g, 0.25, 1e-4, 0.0, 0.0).unwrap();
        assert!(f.fx_n < 0.0 && f.fy_n == 0.0 && f.mz_nm == 0.0);
        let f = kalker_linear_forces(a, b, g, 0.25, 0.0, 1e-4, 0.0).unwrap();
        assert!(f.fy_n < 0.0 && f.mz_nm > 0.0);
        let f = kalker_linear_forces(a, b, g, 0.25, 0.0, 0.0, 0.1).unwrap();
        assert!(f.fy_n < 0.0 && f.mz_nm < 0.0);
        let c = (a * b).sqrt();
        assert!(rel(f.fy_n, -g * c * c * c * f.coefficients.c23 * 0.1) < 1e-15);
    }
}
