//! Viscoelastic bodies in steady rolling: CONTACT's material model M = 1
//! (Vollebregt's user guide, §"Viscoelastic materials" and the example
//! "Steady rolling of two viscoelastic cylinders"; Kalker 1990, appendix
//! D).
//!
//! # The model
//!
//! Each body is a standard linear solid (SLS) with a constant Poisson
//! ratio: its creep compliance (strain per unit stress held from t = 0) is
//!
//! ```text
//! C(t) = C_g + C_v (1 - exp(-t / tau_c)),
//! ```
//!
//! C_g the initial ("glassy") compliance, C_g + C_v the final ("rubbery")
//! one, tau_c the creep relaxation time. The body's shear modulus
//! (`shear_modulus_pa` of its material) is the glassy one, G_g = 1/C_g;
//! [`Sls`] holds the relaxation ratio f_g = C_v/C_g (CONTACT's `FG`) and
//! tau_c (`TC`). The final modulus is G_r = G_g/(1 + f_g).
//!
//! By the correspondence principle a surface point's displacement under a
//! traction history p(t) is u(t) = C(0) U p(t) + ∫ C'(s) U p(t - s) ds
//! over s > 0, U the elastic half-space operator of unit compliance:
//!
//! ```text
//! u(t) = u_g(t) + f_g ∫_0^∞ exp(-s/tau_c)/tau_c u_g(t - s) ds,
//! ```
//!
//! u_g the elastic displacement with G_g. In steady rolling at speed V in
//! +x (the solver's rolling frame, [`crate::core::problem`]) the material
//! flows through the contact towards -x: the material point now at x was
//! at x + V s a time s ago, and the tractions are fixed in the contact's
//! frame, so, with the relaxation length L = V tau_c and xi = V s,
//!
//! ```text
//! u(x) = u_g(x) + f_g ∫_0^∞ exp(-xi/L)/L u_g(x + xi) dxi.
//! ```
//!
//! The influence coefficients follow: for each component pair and each
//! body's share of the combined elastic coefficients (Kalker's constants
//! are the sum of the two bodies' shares, [`crate::core::influence`]),
//!
//! ```text
//! A(X, Y) = A_g(X, Y) + sum_b f_g(b) ∫_0^∞ exp(-xi/L_b)/L_b A_g(b)(X + xi, Y) dxi.
//! ```
//!
//! They stay translation invariant (FFT products apply) but are not
//! symmetric: the normal problem is solved by an active-set method
//! ([`crate::core::normal::solve_normal_active_set`]) instead of the
//! conjugate gradients of the elastic one, and the steady-rolling
//! tangential solver, made for Kalker's non-symmetric operator A(I - S)/dx,
//! takes them as they are. Limits: tau_c = 0 (L = 0) is the elastic body
//! with G_r, the integral then being f_g A_g(X); tau_c -> ∞ the elastic
//! body with G_g (the integral's weight spreads over ever larger
//! distances). In a line contact (plane strain) the half-plane's
//! logarithmic displacements make the integral tend to a constant, not
//! to 0: the tractions tend to those of G_g, the approach differs by a
//! rigid-body displacement that grows with ln L (the half-plane has no
//! datum at infinity; see [`crate::core::influence`]).
//!
//! # Quadrature
//!
//! With u = 1 - exp(-xi/L) the integral is ∫_0^1 A_g(X + xi(u)) du, xi(u) =
//! -L ln(1 - u). The elastic coefficient of an element is continuous in X
//! but its derivative has logarithmic singularities at the element's edges
//! X + xi = ±dx/2; the interval is split there and each piece integrated
//! by adaptive Gauss-Kronrod (7/15 points) to [`QUADRATURE_TOLERANCE`] of
//! the size of the self coefficient. As u -> 1 the integrand grows like
//! ln ln(1/(1 - u)) in a line contact and decays like 1/xi on the
//! half-space: the quadrature ends at 1 - u = 1e-15 (xi = 34.5 L), the
//! weight beyond is negligible.
//!
//! Only the surface's influence coefficients are viscoelastic: subsurface
//! stresses stay those of the elastic half-space (as CONTACT's). Other
//! problem kinds are refused (as CONTACT does): transient steps, rolling
//! in another direction than +x, and the models other than the exact one.

use serde::{Deserialize, Serialize};

use crate::core::error::{show, ContactError};

/// Relative accuracy of the viscoelastic part of an influence
/// coefficient, against the size of the elastic self coefficient.
pub const QUADRATURE_TOLERANCE: f64 = 1e-12;

/// Where the quadrature in u = 1 - exp(-xi/L) ends: the weight beyond,
/// exp(-xi/L) = 1e-15, is left out (an integrand bounded there, or growing
/// like ln xi in a line contact, adds less than [`QUADRATURE_TOLERANCE`]),
/// and the integrand stays finite (xi <= 34.5 L).
const TAIL_END: f64 = 1.0 - 1e-15;

/// Largest bisection depth of the adaptive quadrature.
const MAX_DEPTH: u32 = 30;

/// A piece whose Kronrod and Gauss estimates agree to this fraction of
/// its integral is accepted whatever the absolute tolerance (the rounding
/// of the integrand's values).
const RELATIVE_FLOOR: f64 = 1e-13;

/// Largest relaxation ratio f_g [-]: the final modulus G_g/(1 + f_g) at
/// least a millionth of the initial one. Beyond, the relaxed compliance
/// outgrows the arithmetic (f_g = 1e300 gives non-finite forces).
pub const MAX_RELAXATION_RATIO: f64 = 1e6;

/// The standard linear solid of one body (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Sls {
    /// f_g = C_v/C_g [-], in [0, [`MAX_RELAXATION_RATIO`]] (CONTACT's
    /// `FG`): the final modulus is G_r = G_g/(1 + f_g). 0: an elastic body.
    pub relaxation_ratio: f64,
    /// The creep relaxation time tau_c \[s\], >= 0 (CONTACT's `TC`); 0:
    /// the body relaxes at once, elastic with G_r.
    pub creep_relaxation_time_s: f64,
}

impl Sls {
    /// Checks the values; `key` names the body in errors.
    pub fn validate(&self, key: &str) -> Result<(), ContactError> {
        for (field, v) in [
            ("relaxation_ratio", self.relaxation_ratio),
            ("creep_relaxation_time_s", self.creep_relaxation_time_s),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(ContactError::invalid(
                    format!("{key}.{field}"),
                    format!("must be finite and >= 0, got {}", show(v)),
                ));
            }
        }
        if self.relaxation_ratio > MAX_RELAXATION_RATIO {
            return Err(ContactError::invalid(
                format!("{key}.relaxation_ratio"),
                format!(
                    "must be at most {MAX_RELAXATION_RATIO:e} (a final modulus G_g/(1 + f_g) of at \
                     least a millionth of the initial one), got {}",
                    show(self.relaxation_ratio)
                ),
            ));
        }
        Ok(())
    }

    /// Whether the body is elastic (f_g = 0).
    pub fn is_elastic(&self) -> bool {
        self.relaxation_ratio == 0.0
    }
}

/// Both bodies' standard linear solids and the rolling speed that turns
/// their relaxation times into relaxation lengths (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Viscoelastic {
    /// The rolling speed V \[m/s\], > 0 (CONTACT's `VELOC`).
    pub rolling_speed_m_per_s: f64,
    /// Body 1 (absent: elastic).
    #[serde(default)]
    pub body1: Sls,
    /// Body 2 (absent: elastic).
    #[serde(default)]
    pub body2: Sls,
}

impl Viscoelastic {
    /// Checks the values; `key` names the section in errors.
    pub fn validate(&self, key: &str) -> Result<(), ContactError> {
        let v = self.rolling_speed_m_per_s;
        if !(v.is_finite() && v > 0.0) {
            return Err(ContactError::invalid(
                format!("{key}.rolling_speed_m_per_s"),
                format!("must be finite and > 0, got {}", show(v)),
            ));
        }
        self.body1.validate(&format!("{key}.body1"))?;
        self.body2.validate(&format!("{key}.body2"))?;
        for (b, sls) in [("body1", &self.body1), ("body2", &self.body2)] {
            if !(sls.creep_relaxation_time_s * v).is_finite() {
                return Err(ContactError::invalid(
                    format!("{key}.{b}.creep_relaxation_time_s"),
                    "times the rolling speed must be finite",
                ));
            }
        }
        Ok(())
    }

    /// Each body's (f_g, relaxation length L = V tau_c \[m\]).
    pub fn relaxation(&self) -> [(f64, f64); 2] {
        [self.body1, self.body2].map(|s| {
            (
                s.relaxation_ratio,
                s.creep_relaxation_time_s * self.rolling_speed_m_per_s,
            )
        })
    }
}

/// ∫_0^∞ exp(-xi/L)/L f(x + xi) dxi for a function `f` continuous
/// everywhere and smooth but at `edges` (its argument's points of
/// non-smoothness), to the absolute accuracy `tol`; `f(x)` for L = 0.
pub fn relaxed_average(
    f: impl Fn(f64) -> f64,
    x: f64,
    length_m: f64,
    edges: &[f64; 2],
    tol: f64,
) -> f64 {
    if length_m == 0.0 {
        return f(x);
    }
    relaxed_part(&f, x, length_m, edges, tol, TAIL_END)
}

/// [`relaxed_average`] at the points x_k = x0 + k dx, k = 0..out.len(), in
/// one sweep from the last: the average at x_k is the part over xi in [0,
/// dx) plus exp(-dx/L) times the average at x_{k+1}, so that only the last
/// point's integral reaches the tail; each part to `tol` / out.len(), the
/// sum to `tol` (the sweep damps earlier parts' errors). `f(x_k)` for L =
/// 0.
pub fn relaxed_averages(
    f: impl Fn(f64) -> f64,
    x0: f64,
    dx: f64,
    length_m: f64,
    edges: &[f64; 2],
    tol: f64,
    out: &mut [f64],
) {
    let n = out.len();
    let at = |k: usize| x0 + k as f64 * dx;
    if length_m == 0.0 {
        for (k, o) in out.iter_mut().enumerate() {
            *o = f(at(k));
        }
        return;
    }
    let Some(last) = n.checked_sub(1) else {
        return;
    };
    let tol_part = tol / n as f64;
    out[last] = relaxed_part(&f, at(last), length_m, edges, tol_part, TAIL_END);
    // u = 1 - exp(-xi/L) at xi = dx, and the weight beyond it.
    let u_step = (-(-dx / length_m).exp_m1()).min(TAIL_END);
    let carry = 1.0 - u_step;
    for k in (0..last).rev() {
        out[k] = relaxed_part(&f, at(k), length_m, edges, tol_part, u_step) + carry * out[k + 1];
    }
}

/// ∫ f(x + xi(u)) du over u in [0, `u_end`], xi(u) = -L ln(1 - u): the
/// average's part over xi < -L ln(1 - u_end), split at `edges`.
fn relaxed_part(
    f: &impl Fn(f64) -> f64,
    x: f64,
    length_m: f64,
    edges: &[f64; 2],
    tol: f64,
    u_end: f64,
) -> f64 {
    // The edges as u = 1 - exp(-xi/L) in (0, u_end), ascending.
    let mut cuts = [0.0, u_end, u_end, u_end];
    let mut n = 1;
    for &e in edges {
        let xi = e - x;
        if xi > 0.0 {
            let u = -(-xi / length_m).exp_m1();
            if u < u_end {
                cuts[n] = u;
                n += 1;
            }
        }
    }
    cuts[1..n].sort_by(f64::total_cmp);
    cuts[n] = u_end;
    let g = |u: f64| f(x - length_m * (-u).ln_1p());
    let mut sum = 0.0;
    for k in 0..n {
        let (a, b) = (cuts[k], cuts[k + 1]);
        if b > a {
            let whole = kronrod(&g, a, b);
            sum += adaptive(&g, a, b, whole, tol, MAX_DEPTH);
        }
    }
    sum
}

/// Gauss-Kronrod nodes on [-1, 1] (the 15-point rule's, positive half):
/// the odd ones are the 7-point Gauss rule's.
const XK: [f64; 8] = [
    0.991_455_371_120_812_6,
    0.949_107_912_342_758_5,
    0.864_864_423_359_769_1,
    0.741_531_185_599_394_4,
    0.586_087_235_467_691_1,
    0.405_845_151_377_397_2,
    0.207_784_955_007_898_5,
    0.0,
];
/// Kronrod weights of [`XK`].
const WK: [f64; 8] = [
    0.022_935_322_010_529_22,
    0.063_092_092_629_978_55,
    0.104_790_010_322_250_2,
    0.140_653_259_715_525_9,
    0.169_004_726_639_267_9,
    0.190_350_578_064_785_4,
    0.204_432_940_075_298_9,
    0.209_482_141_084_728,
];
/// Gauss weights of the 7-point rule (nodes XK[1], XK[3], XK[5], XK[7]).
const WG: [f64; 4] = [
    0.129_484_966_168_869_7,
    0.279_705_391_489_276_7,
    0.381_830_050_505_118_9,
    0.417_959_183_673_469_4,
];

/// The (Kronrod, Gauss) estimates of ∫_a^b g.
fn kronrod(g: &impl Fn(f64) -> f64, a: f64, b: f64) -> (f64, f64) {
    let (c, h) = (0.5 * (a + b), 0.5 * (b - a));
    let fc = g(c);
    let mut k = WK[7] * fc;
    let mut gs = WG[3] * fc;
    for j in 0..7 {
        let s = g(c - h * XK[j]) + g(c + h * XK[j]);
        k += WK[j] * s;
        if j % 2 == 1 {
            gs += WG[j / 2] * s;
        }
    }
    (k * h, gs * h)
}

/// ∫_a^b g by bisection until the Kronrod and Gauss estimates of a piece
/// agree to `tol` (the piece's estimates `whole` given).
fn adaptive(
    g: &impl Fn(f64) -> f64,
    a: f64,
    b: f64,
    whole: (f64, f64),
    tol: f64,
    depth: u32,
) -> f64 {
    if (whole.0 - whole.1).abs() <= tol.max(RELATIVE_FLOOR * whole.0.abs()) || depth == 0 {
        return whole.0;
    }
    let m = 0.5 * (a + b);
    let (l, r) = (kronrod(g, a, m), kronrod(g, m, b));
    adaptive(g, a, m, l, 0.5 * tol, depth - 1) + adaptive(g, m, b, r, 0.5 * tol, depth - 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exponential_average_of_smooth_functions_is_exact() {
        // ∫ exp(-xi/L)/L (x + xi) = x + L; of exp(-k xi): 1/(1 + k L).
        let l = 0.37;
        let v = relaxed_average(|t| t, 0.2, l, &[-1.0, 1.0], 1e-14);
        assert!((v - (0.2 + l)).abs() < 1e-13, "{v}");
        let v = relaxed_average(|t| (-2.0 * (t - 0.2)).exp(), 0.2, l, &[-1.0, 1.0], 1e-14);
        assert!((v - 1.0 / (1.0 + 2.0 * l)).abs() < 1e-13, "{v}");
        assert_eq!(
            relaxed_average(|t| t * t, 3.0, 0.0, &[0.0, 0.0], 1e-14),
            9.0
        );
    }

    /// The sweep gives each point's own average to the tolerance.
    #[test]
    fn the_sweep_gives_each_points_average() {
        let f = |t: f64| 1.0 / (1.0 + (t - 0.3).powi(2)) + (t + 0.1).abs();
        let edges = [-0.1, 0.1];
        for l in [0.0, 0.02, 0.4, 30.0] {
            let mut out = [0.0; 9];
            relaxed_averages(f, -0.8, 0.2, l, &edges, 1e-12, &mut out);
            for (k, v) in out.iter().enumerate() {
                let x = -0.8 + k as f64 * 0.2;
                let want = relaxed_average(f, x, l, &edges, 1e-14);
                assert!(
                    (v - want).abs() < 2e-12 * want.abs().max(1.0),
                    "L {l} x {x}: {v} {want}"
                );
            }
        }
    }

    #[test]
    fn a_kink_inside_the_range_converges() {
        // |t - 1| averaged from x = 0: ∫ exp(-xi/L)/L |xi - 1| dxi
        // = 1 - L + 2 L exp(-1/L).
        for l in [0.01, 0.3, 1.0, 50.0] {
            let v = relaxed_average(|t| (t - 1.0).abs(), 0.0, l, &[1.0, 1.0], 1e-13);
            let want = 1.0 - l + 2.0 * l * (-1.0 / l).exp();
            assert!(
                (v - want).abs() < 1e-11 * want.abs().max(1.0),
                "L {l}: {v} vs {want}"
            );
        }
    }

    #[test]
    fn bad_values_name_the_field() {
        let v = Viscoelastic {
            rolling_speed_m_per_s: 1.0,
            body1: Sls {
                relaxation_ratio: -1.0,
                creep_relaxation_time_s: 0.0,
            },
            body2: Sls::default(),
        };
        let e = v.validate("viscoelastic").unwrap_err().to_string();
        assert!(e.contains("viscoelastic.body1.relaxation_ratio"), "{e}");
        let v = Viscoelastic {
            rolling_speed_m_per_s: 1.0,
            body2: Sls {
                relaxation_ratio: 1.0,
                creep_relaxation_time_s: f64::NAN,
            },
            ..v
        };
        let e = v.validate("viscoelastic").unwrap_err().to_string();
        assert!(e.contains("viscoelastic.body1.relaxation_ratio"), "{e}");
        let v = Viscoelastic {
            body1: Sls::default(),
            ..v
        };
        let e = v.validate("viscoelastic").unwrap_err().to_string();
        assert!(
            e.contains("viscoelastic.body2.creep_relaxation_time_s"),
            "{e}"
        );
        let v = Viscoelastic {
            rolling_speed_m_per_s: 0.0,
            ..v
        };
        let e = v.validate("viscoelastic").unwrap_err().to_string();
        assert!(e.contains("viscoelastic.rolling_speed_m_per_s"), "{e}");
    }
}
