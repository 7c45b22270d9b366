//! Polach's creep-force model: the tangential forces of a Hertzian patch
//! in closed form, as MBS codes use it for traction and adhesion studies.
//!
//! References:
//! * O. Polach, "A fast wheel-rail forces calculation computer code",
//!   Vehicle System Dynamics 33 (Suppl.) (1999) 728–739: the model for
//!   longitudinal, lateral and spin creepage;
//! * O. Polach, "Creep forces in simulations of traction vehicles running
//!   on adhesion limit", Wear 258 (2005) 992–1000: the reduction factors
//!   k_A, k_S of the adhesion and slip parts and the friction coefficient
//!   falling with the slip velocity.
//!
//! # Conventions
//!
//! Those of [`crate::core::problem`] and [`crate::core::fastsim`]: semi-axes
//! a (rolling direction x) and b (y), c = sqrt(a b); creepages xi, eta [-],
//! spin phi \[1/m\] of body 1 relative to body 2; the forces act on body 1,
//! so small creepages give Kalker's linear theory Fx = -G c² C11 xi,
//! Fy = -G c² (C22 eta + c C23 phi). Polach's own forces have the sign of
//! the creepage; here they are negated once, at the end.
//!
//! # The model
//!
//! With s = sqrt(xi² + eta²), Q the normal force and mu the friction
//! coefficient, the tangential stress grows linearly from the leading edge
//! in adhesion with the gradient
//! eps = (1/4) G pi a b C_s s / (Q mu), C_s = sqrt((C11 xi)² + (C22 eta)²)/s
//! (Polach 1999, eq. 3 with his C = 3 G C_s / (8 a)), and is bounded by
//! mu times the Hertz pressure; the total tangential force is
//!
//! F = (2 Q mu / pi) (k_A eps / (1 + (k_A eps)²) + atan(k_S eps)),
//!
//! split as Fx = F xi / s, Fy = F eta / s (k_A = k_S = 1: Polach 1999;
//! 2005: k_S <= k_A <= 1). So the force opposes the creepage also when xi
//! and eta combine, where Kalker's linear theory turns it by C11 / C22. The adhesion zone is the leading share
//! 1 / (1 + (k_A eps)²) of each strip, which is the adhesion fraction
//! reported. Spin adds a lateral force (Polach 1999, eqs. 8–12):
//!
//! * eta_C = eta + phi a where that has the larger magnitude, else eta;
//!   s_C = sqrt(xi² + eta_C²);
//! * eps_M = (8/3) G b c C23 s_C / (Q mu (1 + 6.3 (1 - exp(-a/b))));
//! * delta = (eps_M² - 1) / (eps_M² + 1);
//! * K_M = |eps_M| (delta³/3 - delta²/2 + 1/6) - sqrt((1 - delta²)³) / 3;
//! * F_yS = -(9/16) a Q mu K_M (1 + 6.3 (1 - exp(-a/b))) phi / s_C
//!   (Polach's sign), which tends to G c³ C23 phi for small creepage.
//!
//! With falling friction (2005) mu = mu0 ((1 - A) exp(-B w) + A) at the
//! slip velocity w = V s_C (V the rolling speed).
//!
//! The model gives no spin moment (Mz = 0) and no traction distribution;
//! the frictional power is -(Fx xi + Fy eta) V, the power of the forces
//! alone (the spin moment's share is left out with it).

use crate::core::creep::{kalker_creep_coefficients, CreepError};
use crate::core::error::{require_finite, require_positive, ContactError};
use crate::core::fastsim::FastsimInput;

/// The parameters of Polach's 2005 extension. The default (k_A = k_S = 1,
/// A = 1) is the 1999 model with Coulomb friction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PolachParameters {
    /// Reduction factor of the adhesion part k_A [-], in (0, 1].
    pub k_adhesion: f64,
    /// Reduction factor of the slip part k_S [-], in (0, k_A].
    pub k_slip: f64,
    /// Ratio A of the friction coefficient at infinite slip velocity to
    /// the maximum mu0 [-], in (0, 1] (1: no falling friction).
    pub limit_ratio: f64,
    /// Decay rate B of the friction coefficient with the slip velocity
    /// \[s/m\], >= 0.
    pub decay_s_per_m: f64,
}

impl Default for PolachParameters {
    fn default() -> Self {
        Self {
            k_adhesion: 1.0,
            k_slip: 1.0,
            limit_ratio: 1.0,
            decay_s_per_m: 0.0,
        }
    }
}

impl PolachParameters {
    /// Polach's recommended parameters for dry rail (Wear 258 (2005),
    /// Table 2): k_A = 1.0, k_S = 0.4, A = 0.4, B = 0.6 s/m (with mu0 =
    /// 0.55, the friction coefficient of the case).
    pub const DRY: Self = Self {
        k_adhesion: 1.0,
        k_slip: 0.4,
        limit_ratio: 0.4,
        decay_s_per_m: 0.6,
    };
    /// Polach's recommended parameters for wet rail (ibid.): k_A = 0.3,
    /// k_S = 0.1, A = 0.4, B = 0.2 s/m (with mu0 = 0.30).
    pub const WET: Self = Self {
        k_adhesion: 0.3,
        k_slip: 0.1,
        limit_ratio: 0.4,
        decay_s_per_m: 0.2,
    };

    /// Checks the ranges above, naming `key.field`.
    pub fn validate(&self, key: &str) -> Result<(), ContactError> {
        let bad = |field: &str, what: &str, v: f64| {
            Err(ContactError::invalid(
                format!("{key}.{field}"),
                format!("{what}, got {}", crate::core::error::show(v)),
            ))
        };
        let (ka, ks) = (self.k_adhesion, self.k_slip);
        if !(ka.is_finite() && ka > 0.0 && ka <= 1.0) {
            return bad("k_adhesion", "must be in (0, 1]", ka);
        }
        if !(ks.is_finite() && ks > 0.0 && ks <= ka) {
            return bad("k_slip", "must be in (0, k_adhesion]", ks);
        }
        let a = self.limit_ratio;
        if !(a.is_finite() && a > 0.0 && a <= 1.0) {
            return bad("limit_ratio", "must be in (0, 1]", a);
        }
        let b = self.decay_s_per_m;
        if !(b.is_finite() && b >= 0.0) {
            return bad("decay_s_per_m", "must be finite and >= 0", b);
        }
        Ok(())
    }
}

/// The forces on body 1.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PolachOutput {
    /// Longitudinal force \[N\].
    pub fx_n: f64,
    /// Lateral force \[N\].
    pub fy_n: f64,
    /// Share of the patch in adhesion [-].
    pub adhesion_fraction: f64,
    /// The friction coefficient used (falling with the slip velocity) [-].
    pub friction_coefficient: f64,
    /// Frictional power per rolling speed, -(Fx xi + Fy eta) \[N\].
    pub tgamma_n: f64,
}

/// Polach's forces of one Hertz patch (see the module docs), the static
/// friction coefficient of `input` being mu0 (its kinetic one is not
/// used); `rolling_speed_m_per_s` (V, > 0; slip
/// velocity = V x creepage) enters only with falling friction.
pub fn polach(
    input: &FastsimInput,
    rolling_speed_m_per_s: f64,
    p: &PolachParameters,
) -> Result<PolachOutput, ContactError> {
    for (key, v) in [
        ("semi_axis_x_m", input.semi_axis_x_m),
        ("semi_axis_y_m", input.semi_axis_y_m),
        ("shear_modulus_pa", input.shear_modulus_pa),
        ("rolling_speed_m_per_s", rolling_speed_m_per_s),
    ] {
        require_positive(key, v)?;
    }
    for (key, v) in [
        ("normal_force_n", input.normal_force_n),
        (
            "static_friction_coefficient",
            input.static_friction_coefficient,
        ),
        ("creepage_long", input.creepage_long),
        ("creepage_lat", input.creepage_lat),
        ("spin_per_m", input.spin_per_m),
    ] {
        require_finite(key, v)?;
    }
    let (a, b, g, v) = (
        input.semi_axis_x_m,
        input.semi_axis_y_m,
        input.shear_modulus_pa,
        rolling_speed_m_per_s,
    );
    let (q, mu0) = (input.normal_force_n, input.static_friction_coefficient);
    let (xi, eta, phi) = (input.creepage_long, input.creepage_lat, input.spin_per_m);
    let k = kalker_creep_coefficients(a / b, input.poisson_ratio).map_err(|e: CreepError| {
        ContactError::invalid("polach", format!("creep coefficients: {e}"))
    })?;
    if q <= 0.0 || mu0 <= 0.0 {
        // No load or no friction: no tangential force; all adhesion is
        // meaningless, so none is reported.
        return Ok(PolachOutput {
            friction_coefficient: mu0,
            ..PolachOutput::default()
        });
    }
    let eta_spin = eta + phi * a;
    let eta_c = if eta_spin.abs() > eta.abs() {
        eta_spin
    } else {
        eta
    };
    let s_c = xi.hypot(eta_c);
    let mu = mu0 * ((1.0 - p.limit_ratio) * (-p.decay_s_per_m * v * s_c).exp() + p.limit_ratio);
    let s = xi.hypot(eta);
    let (mut fx, mut fy, mut adhesion) = (0.0, 0.0, 1.0);
    if s > 0.0 {
        let c_s = (k.c11 * xi).hypot(k.c22 * eta) / s;
        let eps = 0.25 * g * std::f64::consts::PI * a * b * c_s * s / (q * mu);
        let ka = p.k_adhesion * eps;
        let f =
            2.0 * q * mu / std::f64::consts::PI * (ka / (1.0 + ka * ka) + (p.k_slip * eps).atan());
        fx = f * xi / s;
        fy = f * eta / s;
        adhesion = 1.0 / (1.0 + ka * ka);
    }
    if phi != 0.0 && s_c > 0.0 {
        let shape = 1.0 + 6.3 * (1.0 - (-a / b).exp());
        let c = (a * b).sqrt();
        let eps_m = 8.0 / 3.0 * g * b * c * k.c23 * s_c / (q * mu * shape);
        let e2 = eps_m * eps_m;
        let delta = (e2 - 1.0) / (e2 + 1.0);
        let k_m = eps_m.abs() * (delta.powi(3) / 3.0 - delta * delta / 2.0 + 1.0 / 6.0)
            - (1.0 - delta * delta).powi(3).sqrt() / 3.0;
        fy += -9.0 / 16.0 * a * q * mu * k_m * shape * phi / s_c;
    }
    // Polach's forces have the sign of the creepage; on body 1 they oppose it.
    let (fx, fy) = (-fx, -fy);
    Ok(PolachOutput {
        fx_n: fx,
        fy_n: fy,
        adhesion_fraction: adhesion,
        friction_coefficient: mu,
        tgamma_n: -(fx * xi + fy * eta),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::creep::kalker_linear_forces;

    /// Rolling speed of the tests [m/s].
    const V: f64 = 30.0;

    /// The wheel/rail-like ellipse of FASTSIM's tests (a = 6 mm, b = 4 mm,
    /// 100 kN, steel, mu 0.3) with these creepages.
    fn input(xi: f64, eta: f64, phi: f64) -> FastsimInput {
        FastsimInput {
            creepage_long: xi,
            creepage_lat: eta,
            spin_per_m: phi,
            ..crate::core::fastsim::tests::base()
        }
    }

    fn linear(i: &FastsimInput) -> (f64, f64) {
        let l = kalker_linear_forces(
            i.semi_axis_x_m,
            i.semi_axis_y_m,
            i.shear_modulus_pa,
            i.poisson_ratio,
            i.creepage_long,
            i.creepage_lat,
            i.spin_per_m,
        )
        .unwrap();
        (l.fx_n, l.fy_n)
    }

    #[test]
    fn small_creepages_give_kalkers_linear_theory() {
        // Kalker's linear theory is the small-creepage limit of Polach's
        // model (Polach 1999, section 2): relative difference O(eps^2).
        for (xi, eta, phi) in [
            (1e-6, 0.0, 0.0),
            (0.0, 1e-6, 0.0),
            (0.0, 0.0, 1e-4),
            (0.0, 1e-6, 1e-4),
        ] {
            let i = input(xi, eta, phi);
            let got = polach(&i, V, &PolachParameters::default()).unwrap();
            let (fx, fy) = linear(&i);
            for (what, g, w) in [("Fx", got.fx_n, fx), ("Fy", got.fy_n, fy)] {
                assert!(
                    (g - w).abs() <= 1e-3 * w.abs() + 1e-9,
                    "{what} at ({xi}, {eta}, {phi}): {g} against linear {w}"
                );
            }
            assert!(got.adhesion_fraction > 0.999);
        }
        // Combined xi and eta: the force opposes the creepage, of magnitude
        // G a b sqrt((C11 xi)^2 + (C22 eta)^2) (Polach 1999, eq. 3), where
        // Kalker's linear theory turns it by C11 / C22.
        let i = input(0.7e-6, -0.4e-6, 0.0);
        let got = polach(&i, V, &PolachParameters::default()).unwrap();
        let k = crate::core::creep::kalker_creep_coefficients(1.5, 0.28).unwrap();
        let want = 8e10 * 6e-3 * 4e-3 * (k.c11 * 0.7e-6).hypot(k.c22 * 0.4e-6);
        let magnitude = got.fx_n.hypot(got.fy_n);
        assert!(
            (magnitude - want).abs() < 1e-3 * want,
            "{magnitude} against {want}"
        );
        assert!((got.fy_n / got.fx_n - (-0.4 / 0.7)).abs() < 1e-12);
    }

    #[test]
    fn full_slip_saturates_at_mu_q_and_adhesion_vanishes() {
        // eps -> infinity: F -> (2 Q mu / pi)(pi / 2) = mu Q.
        let got = polach(&input(-0.5, 0.0, 0.0), V, &PolachParameters::default()).unwrap();
        assert!((got.fx_n - 0.3 * 1e5).abs() < 1e-3 * 0.3 * 1e5, "{got:?}");
        assert!(got.adhesion_fraction < 1e-4);
        // Monotone in the creepage, below saturation.
        let mut last = 0.0;
        for k in 1..=200 {
            let xi = -1e-4 * k as f64;
            let f = polach(&input(xi, 0.0, 0.0), V, &PolachParameters::default())
                .unwrap()
                .fx_n;
            assert!(f > last && f < 0.3 * 1e5, "{xi}: {f}");
            last = f;
        }
    }

    #[test]
    fn falling_friction_gives_an_adhesion_optimum() {
        // Polach 2005 (fig. 6, dry): with k_S < k_A and mu falling with the
        // slip velocity the force has a maximum at a small creepage, then
        // falls towards A mu0 Q (mu -> A mu0 as w -> infinity, and the
        // bracket (k_A eps/(1 + (k_A eps)^2) + atan(k_S eps)) -> pi/2).
        let mut i = input(0.0, 0.0, 0.0);
        i.static_friction_coefficient = 0.55;
        let force = |xi: f64| {
            let mut i = i;
            i.creepage_long = xi;
            -polach(&i, V, &PolachParameters::DRY).unwrap().fx_n
        };
        let curve: Vec<f64> = (1..=400).map(|k| force(1e-3 * k as f64)).collect();
        let (at, peak) =
            curve.iter().copied().enumerate().fold(
                (0, 0.0),
                |(j, m), (k, f)| if f > m { (k, f) } else { (j, m) },
            );
        assert!(
            at > 0 && at < 100,
            "optimum at xi = {}",
            1e-3 * (at + 1) as f64
        );
        assert!(curve[399] < 0.9 * peak, "{} against {peak}", curve[399]);
        // xi = 20: w = 600 m/s, exp(-360) = 0; eps ~ 1e5.
        let limit = 0.4 * 0.55 * 1e5;
        assert!(
            (force(20.0) - limit).abs() < 1e-3 * limit,
            "{}",
            force(20.0)
        );
    }

    #[test]
    fn the_parameters_are_checked_by_name() {
        let mut p = PolachParameters::WET;
        p.k_slip = 0.5;
        let e = p.validate("polach").unwrap_err().to_string();
        assert!(e.contains("polach.k_slip"), "{e}");
        assert!(PolachParameters::DRY.validate("polach").is_ok());
    }
}
