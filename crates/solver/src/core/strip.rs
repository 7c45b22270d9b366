//! Strip theory on a Hertzian patch with Kalker's creep coefficients: the
//! tangential forces in closed form per strip, as MBS codes use it in
//! place of FASTSIM.
//!
//! References:
//! * D. J. Haines, E. Ollerton, "Contact stress distributions on elliptical
//!   contact surfaces subjected to radial and tangential forces", Proc.
//!   IMechE 177 (1963) 95–114, and J. J. Kalker, "Rolling with slip and
//!   spin in the presence of dry friction", Wear 9 (1966) 20–38: the strip
//!   theory (each strip `y` = const of the ellipse solved as Carter's
//!   two-dimensional rolling contact);
//! * O. Sichani, R. Enblom, M. Berg, "An alternative to FASTSIM for
//!   tangential solution of the wheel–rail contact", Vehicle System
//!   Dynamics 54 (2016) 748–764 (FaStrip): strip theory with Kalker's
//!   linear-theory coefficients in place of the plane-strain ones, so that
//!   small creepages give Kalker's linear theory. Their paper's treatment
//!   of spin was not available to us: the spin terms below are this
//!   module's own (stated in full), not FaStrip's. Searched (2026-11-26,
//!   the stored public pages, documentation, code and issues this project
//!   reads): the paper's title, "FaStrip", "FaStrip spin", "Sichani strip
//!   theory spin creepage", and Sichani's KTH theses (licentiate 2013,
//!   DiVA 646708; doctoral 2016, "On efficient modelling of wheel-rail
//!   contact in vehicle dynamics simulation", DiVA 899731): of the
//!   theses only the title pages and abstracts are stored, of the paper
//!   nothing; third-party implementations were not used. How far the
//!   spin terms below are from the exact model is measured (section
//!   "Accuracy with spin").
//!
//! # Conventions
//!
//! Those of [`crate::core::problem`] and [`crate::core::fastsim`]: semi-axes
//! `a` (rolling direction `x`) and `b` (`y`), `c = sqrt(a b)`; creepages
//! `xi`, `eta` [-], spin `phi` \[1/m\] of body 1 relative to body 2, rigid
//! slip `w = (xi - phi y, eta + phi x)`; tractions act on body 1; material
//! enters at the leading edge `x = +a(y)`.
//!
//! # The model
//!
//! Hertz's pressure on strip `y`, `a(y) = a sqrt(1 - y^2/b^2)`, is
//! `p0(y) sqrt(1 - x^2/a(y)^2)` with `p0(y) = p0 sqrt(1 - y^2/b^2)`,
//! `p0 = 3 Fn/(2 pi a b)`. Each strip carries Carter's solution: adhesion
//! over the leading share `k` of the strip, `a(y)(1 - 2k) <= x <= a(y)`,
//! slip behind it, the traction along the unit vector `u` opposing the
//! strip's normalised creepage `e = (kx wx, ky wy)`,
//!
//! `|p| = mu p0(y) (sqrt(1 - x^2/a(y)^2) - k sqrt(1 - (x - d)^2/(k a(y))^2))`
//! with `d = a(y)(1 - k)` (second term in the adhesion zone only) and
//! `k = max(0, 1 - |e|)`. Per unit width the strip's force is
//! `mu p0(y) (pi a(y)/2) (1 - k^2)` and its first moment `∫ x |p| dx` is
//! `-mu p0(y) (pi/2) a(y)^2 k^2 (1 - k)`.
//!
//! Because `p0(y)/a(y)` is the same on every strip, a uniform creepage
//! gives the same `k` on every strip and `|F| = mu Fn (1 - k^2)`, slope
//! `2 mu Fn |e|` at small creepage. The normalisation makes that slope
//! Kalker's linear theory (`Fx = -G c^2 C11 xi`,
//! `Fy = -G c^2 (C22 eta + c C23 phi)`):
//! `kx = G c^2 C11/(2 mu Fn)`, `ky = G c^2 C22/(2 mu Fn)`.
//!
//! The strip's creepage: `wx = xi - phi y`, the rigid slip along `x`,
//! constant on the strip, so the spin's longitudinal part is exact in
//! strip theory and gives the spin moment `-sum y Fx(y)`; `wy = eta +
//! c (C23/C22) phi`, the uniform lateral creepage with the linear theory's
//! lateral force of the spin (strip theory cannot carry the lateral slip
//! `phi x` that varies along a strip). Hence, at small creepage, `Fx`,
//! `Fy` are Kalker's linear theory exactly. The spin moment is the strip
//! theory's: the lateral tractions' first moments of `eta`'s share, and
//! the longitudinal strip forces' moment `-sum y Fx(y)`. The spin's
//! equivalent lateral creepage carries force but no moment: its uniform
//! traction would give the moment of a lateral creepage, the opposite sign
//! of the spin's own (slip `phi x` changes sign along the strip). Pure
//! `eta` gives `Mz = (9 pi/64) G a^2 b C22 eta` (Kalker: `G c^3 C23 eta`;
//! FASTSIM: `(3 pi/32) G a^2 b C22 eta`), pure `phi`
//! `Mz = -(1/5) G c^2 C11 b^2 phi` (Kalker: `-G c^4 C33 phi`): the signs
//! agree, the magnitudes do not.
//!
//! In full sliding (`|e| >= 1` on every strip) `|F| = mu Fn` for a
//! creepage without spin, directed along `-(C11 xi, C22 eta)` as
//! FASTSIM's separate flexibilities are (see
//! [`crate::core::fastsim::FlexibilityModel::Separate`]).
//!
//! # Accuracy with spin
//!
//! Against the exact model on a Hertzian ellipse, a/b = 1.96 (A = 1.087,
//! B = 3.0 1/m, 10 kN, nu = 0.28, G = 80 GPa, mu = 0.3; the exact model
//! on 64 x 64 elements, 100 strips, FASTSIM on 40 x 40 for comparison),
//! the spin in units of phi_sat = mu Fn/(G c³ C23) (0.80 1/m), the
//! spin whose linear-theory lateral force is mu Fn; differences in units
//! of mu Fn (test `strip_theory_with_spin_against_the_exact_model` in
//! `crates/solver/tests/validation/physics.rs`, which holds these rows
//! within 0.01 mu Fn and 0.03 in the ratio, the exact model's own error
//! on that grid):
//!
//! | xi | eta | phi/phi_sat | exact Fy \[N\] | strip ΔFy | FASTSIM ΔFy | strip Mz/exact | FASTSIM Mz/exact |
//! |---|---|---|---|---|---|---|---|
//! | 0 | 0 | 0.1 | -300.8 | +0.003 | +0.000 | 0.60 | 0.73 |
//! | 0 | 0 | 0.3 | -883.6 | +0.021 | -0.003 | 0.61 | 0.74 |
//! | 0 | 0 | 1 | -2242.3 | +0.040 | -0.079 | 0.45 | 0.71 |
//! | 0 | 0 | 3 | -1351.3 | -0.420 | -0.103 | 0.30 | 0.80 |
//! | 0 | 0 | 10 | -549.5 | -0.687 | -0.105 | 0.25 | 0.86 |
//! | 0 | 1e-3 | 1 | -2736.3 | -0.040 | -0.001 | 0.62 | 0.91 |
//! | 0 | -1e-3 | 1 | -605.0 | +0.115 | -0.051 | 1.07 | 0.79 |
//! | 1e-3 | 0 | 1 | -1958.5 | +0.017 | -0.070 | 0.36 | 0.77 |
//!
//! (The last row's Fx: exact -1524.0 N, strip theory -0.032 mu Fn from
//! it, FASTSIM +0.032.) For spin alone up to phi_sat the lateral force is
//! within 0.04 mu Fn of the exact one (FASTSIM: 0.08 at phi_sat);
//! beyond, the spin's equivalent lateral creepage saturates the force at
//! 0.87 mu Fn while the exact lateral force of a large spin falls (its
//! slip turns round the patch): 0.42 mu Fn too large at 3 phi_sat, 0.69
//! at 10. With a lateral creepage of the opposite sign the error is 0.11
//! mu Fn at phi_sat. The spin moment is a quarter to two thirds of the
//! exact one where the spin dominates (the strips carry no lateral slip
//! varying along x).
//!
//! # Discretisation
//!
//! `n` strips of width `2b/n` at their centres (midpoint rule), the
//! strips' weights rescaled so that the normal pressure sums to `Fn`
//! exactly (a relative change of about `1/(2 n^2)`): full sliding gives
//! `mu Fn` to rounding. Per strip a square root and a few products: no
//! allocation, no iteration.
//!
//! The frictional power per unit rolling speed is the strips' forces on
//! their creepages, `T gamma = -sum F(y) . (wx, wy) dy >= 0`: for a single
//! creepage `xi` or `eta` the creep work `-(Fx xi + Fy eta)` exactly.

use crate::core::creep::{kalker_creep_coefficients, CreepCoefficients};
use crate::core::fastsim::{validate, FastsimError, FastsimInput};

/// Largest accepted number of strips.
pub const MAX_STRIPS: usize = 1 << 20;

/// Result of one strip-theory solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StripOutput {
    /// Longitudinal force on body 1 \[N\].
    pub fx_n: f64,
    /// Lateral force on body 1 \[N\].
    pub fy_n: f64,
    /// Spin moment on body 1 about the patch centre \[N m\].
    pub mz_nm: f64,
    /// Fraction of the ellipse's area in adhesion [-].
    pub adhesion_fraction: f64,
    /// Frictional power per unit rolling speed (module docs) \[N\].
    pub tgamma_n: f64,
    /// Creep coefficients used [-].
    pub coefficients: CreepCoefficients,
}

/// Solves the tangential problem of `input` by strip theory on `strips`
/// strips (>= 2, at most [`MAX_STRIPS`]) with the kinetic friction
/// coefficient `input.friction_coefficient` (the static one is not used:
/// Carter's slip zone is one connected trailing zone per strip). No
/// allocation.
pub fn strip_theory(input: &FastsimInput, strips: usize) -> Result<StripOutput, FastsimError> {
    if !(2..=MAX_STRIPS).contains(&strips) {
        return Err(FastsimError::InvalidInput {
            name: "strips",
            requirement: "in [2, 2^20]",
            value: strips as f64,
        });
    }
    validate(input)?;
    let (a, b) = (input.semi_axis_x_m, input.semi_axis_y_m);
    let (fn_n, g, mu) = (
        input.normal_force_n,
        input.shear_modulus_pa,
        input.friction_coefficient,
    );
    let (xi, eta, phi) = (input.creepage_long, input.creepage_lat, input.spin_per_m);
    let coef = kalker_creep_coefficients(a / b, input.poisson_ratio)?;
    let c = (a * b).sqrt();
    let dy = 2.0 * b / strips as f64;
    // Strip weights p0(y) a(y) dy up to a constant: (1 - y^2/b^2) dy; the
    // force of a sliding strip is mu p0(y) (pi/2) a(y) dy.
    let mut weight_sum = 0.0;
    for j in 0..strips {
        let s = strip_shape(b, dy, j);
        weight_sum += s * s;
    }
    // mu p0(y) (pi/2) a(y) dy = mu force_scale (1 - y^2/b^2), summing to
    // mu Fn; the first moment carries a(y) = a sqrt(1 - y^2/b^2) more.
    let force_scale = fn_n / weight_sum;
    if mu == 0.0 {
        return Ok(StripOutput {
            fx_n: 0.0,
            fy_n: 0.0,
            mz_nm: 0.0,
            adhesion_fraction: 0.0,
            tgamma_n: 0.0,
            coefficients: coef,
        });
    }
    let kx = g * c * c * coef.c11 / (2.0 * mu * fn_n);
    let ky = g * c * c * coef.c22 / (2.0 * mu * fn_n);
    let wy = eta + c * coef.c23 / coef.c22 * phi;
    let ey = ky * wy;
    let (mut fx, mut fy, mut mz, mut tgamma) = (0.0, 0.0, 0.0, 0.0);
    let (mut adhesion, mut area) = (0.0, 0.0);
    for j in 0..strips {
        let y = -b + (j as f64 + 0.5) * dy;
        let s = strip_shape(b, dy, j);
        let wx = xi - phi * y;
        let ex = kx * wx;
        let tau = ex.hypot(ey);
        area += s;
        if tau == 0.0 {
            adhesion += s;
            continue;
        }
        let k = (1.0 - tau).max(0.0);
        adhesion += k * s;
        let (ux, uy) = (-ex / tau, -ey / tau);
        let f = mu * force_scale * s * s * (1.0 - k * k);
        // The lateral traction's first moment, -mu p0(y) (pi/2) a(y)^2
        // k^2 (1 - k) uy dy, of eta's share of ey: (1 - k)/tau = 1 while
        // k > 0.
        let m = mu * force_scale * s * s * (a * s) * k * k * ky * eta;
        fx += f * ux;
        fy += f * uy;
        mz += m - y * f * ux;
        tgamma -= f * (ux * wx + uy * wy);
    }
    Ok(StripOutput {
        fx_n: fx,
        fy_n: fy,
        mz_nm: mz,
        adhesion_fraction: adhesion / area,
        tgamma_n: tgamma,
        coefficients: coef,
    })
}

/// `sqrt(1 - y^2/b^2)` at the centre of strip `j`.
fn strip_shape(b: f64, dy: f64, j: usize) -> f64 {
    let t = (-b + (j as f64 + 0.5) * dy) / b;
    (1.0 - t * t).max(0.0).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::creep::kalker_linear_forces;
    use crate::core::fastsim::tests::{base, rel, with};
    use std::f64::consts::PI;

    /// Small creepage: Kalker's linear theory, `Fx = -G c^2 C11 xi`,
    /// `Fy = -G c^2 (C22 eta + c C23 phi)` (Kalker, Three-dimensional
    /// elastic bodies in rolling contact, 1990, sec. 1.6), by construction
    /// of the normalisation; and the strip theory's spin moments of the
    /// module docs.
    #[test]
    fn small_creepage_is_linear_theory() {
        let (a, b, g) = (6e-3, 4e-3, 8e10);
        for &(xi, eta, phi) in &[(1e-8, 0.0, 0.0), (0.0, 1e-8, 0.0), (0.0, 0.0, 1e-6)] {
            let o = strip_theory(&with(xi, eta, phi), 400).unwrap();
            let lin = kalker_linear_forces(a, b, g, 0.28, xi, eta, phi).unwrap();
            if xi != 0.0 {
                assert!(rel(o.fx_n, lin.fx_n) < 1e-6, "{} vs {}", o.fx_n, lin.fx_n);
                assert!(o.fy_n.abs() < 1e-12 * o.fx_n.abs());
            } else {
                assert!(rel(o.fy_n, lin.fy_n) < 1e-6, "{} vs {}", o.fy_n, lin.fy_n);
                assert!(o.fx_n.abs() < 1e-9 * o.fy_n.abs());
            }
            assert!(o.adhesion_fraction > 0.999);
        }
        let o = strip_theory(&with(0.0, 1e-8, 0.0), 400).unwrap();
        let expect = 9.0 * PI / 64.0 * g * a * a * b * o.coefficients.c22 * 1e-8;
        assert!(rel(o.mz_nm, expect) < 1e-4, "{} vs {expect}", o.mz_nm);
        let phi = 1e-6;
        let o = strip_theory(&with(0.0, 0.0, phi), 400).unwrap();
        let c = (a * b).sqrt();
        // The longitudinal strip forces' moment alone.
        let expect = -0.2 * g * c * c * o.coefficients.c11 * b * b * phi;
        assert!(rel(o.mz_nm, expect) < 1e-4, "{} vs {expect}", o.mz_nm);
        assert!(o.mz_nm < 0.0 && o.fy_n < 0.0);
    }

    /// Uniform creepage: `|F| = mu Fn (1 - (1 - |e|)^2)` (Haines and
    /// Ollerton's result, every strip with the same adhesion share), the
    /// adhesion fraction `1 - |e|`, and `mu Fn` in full sliding.
    #[test]
    fn uniform_creepage_follows_the_closed_form() {
        let (a, b, g, mu, fnn) = (6e-3, 4e-3, 8e10, 0.3, 1e5);
        let o = strip_theory(&with(1e-3, 0.0, 0.0), 200).unwrap();
        let c2 = a * b;
        let e = g * c2 * o.coefficients.c11 * 1e-3 / (2.0 * mu * fnn);
        assert!(e < 1.0);
        let expect = -mu * fnn * (1.0 - (1.0 - e) * (1.0 - e));
        assert!(rel(o.fx_n, expect) < 1e-12, "{} vs {expect}", o.fx_n);
        assert!((o.adhesion_fraction - (1.0 - e)).abs() < 1e-12);
        // Single creepage: T gamma is the creep work.
        assert!(rel(o.tgamma_n, -o.fx_n * 1e-3) < 1e-12);
        let o = strip_theory(&with(0.5, 0.0, 0.0), 7).unwrap();
        assert!(rel(o.fx_n, -mu * fnn) < 1e-12);
        assert_eq!(o.adhesion_fraction, 0.0);
        // Combined without spin: along -(C11 xi, C22 eta), |F| = mu Fn.
        let o = strip_theory(&with(0.3, -0.4, 0.0), 20).unwrap();
        let (cx, cy) = (0.3 * o.coefficients.c11, -0.4 * o.coefficients.c22);
        let n = cx.hypot(cy);
        assert!(rel(o.fx_n, -mu * fnn * cx / n) < 1e-12);
        assert!(rel(o.fy_n, -mu * fnn * cy / n) < 1e-12);
        // With spin the resultant stays below mu Fn.
        let o = strip_theory(&with(0.01, 0.0, 20.0), 100).unwrap();
        assert!(o.fx_n.hypot(o.fy_n) < mu * fnn && o.tgamma_n > 0.0);
    }

    #[test]
    fn reversal_zero_friction_and_bad_input() {
        for &(xi, eta, phi) in &[(1e-3, 2e-3, 0.5), (-2e-4, 1e-3, -1.0), (0.0, 0.0, 3.0)] {
            let o = strip_theory(&with(xi, eta, phi), 50).unwrap();
            let r = strip_theory(&with(-xi, -eta, -phi), 50).unwrap();
            assert_eq!((r.fx_n, r.fy_n, r.mz_nm), (-o.fx_n, -o.fy_n, -o.mz_nm));
            assert_eq!(r.tgamma_n, o.tgamma_n);
            assert!(o.tgamma_n > 0.0);
        }
        let o = strip_theory(&with(0.0, 0.0, 0.0), 10).unwrap();
        assert_eq!(
            (o.fx_n, o.fy_n, o.mz_nm, o.adhesion_fraction),
            (0.0, 0.0, 0.0, 1.0)
        );
        let dry = FastsimInput {
            friction_coefficient: 0.0,
            ..with(1e-3, 0.0, 0.0)
        };
        let o = strip_theory(&dry, 10).unwrap();
        assert_eq!((o.fx_n, o.adhesion_fraction), (0.0, 0.0));
        let msg = strip_theory(&with(1e-3, 0.0, 0.0), 1)
            .unwrap_err()
            .to_string();
        assert!(msg.contains("strips"), "{msg}");
        let bad = FastsimInput {
            creepage_lat: f64::NAN,
            ..base()
        };
        let msg = strip_theory(&bad, 10).unwrap_err().to_string();
        assert!(msg.contains("creepage_lat"), "{msg}");
    }

    /// Monotone growth to saturation, and the strip count converging.
    #[test]
    fn monotone_and_converging() {
        let mut prev = 0.0;
        for k in 1..=40 {
            let o = strip_theory(&with(1e-4 * k as f64, 5e-5 * k as f64, 0.2), 64).unwrap();
            let f = o.fx_n.hypot(o.fy_n);
            assert!(f > prev && f <= 0.3e5, "{k}: {f}");
            prev = f;
        }
        let inp = with(1e-3, 1e-3, 0.5);
        let fine = strip_theory(&inp, 4000).unwrap();
        let coarse = strip_theory(&inp, 64).unwrap();
        assert!(rel(coarse.fx_n, fine.fx_n) < 1e-3);
        assert!(rel(coarse.fy_n, fine.fy_n) < 1e-3);
        assert!(rel(coarse.mz_nm, fine.mz_nm) < 1e-2);
    }
}
