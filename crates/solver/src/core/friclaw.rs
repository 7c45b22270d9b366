//! Slip-velocity dependent ("falling") friction.
//!
//! The friction coefficient of a slipping element depends on its absolute
//! slip velocity s_a \[m/s\] (Vollebregt, *User guide for CONTACT*, report
//! 20-01, §"Friction description", subsection "Slip velocity dependent
//! friction", eqs. `exponential_law`, `linear_law`, `rational_law`;
//! Vollebregt & Schuttelaars 2012, J. Sound Vib. 331, 2141–2155):
//!
//! * exponential: mu_s(s_a) = mu_kin + sum_k mu_k exp(-ln 2 s_a / s_hk)
//! * linear: mu_s(s_a) = mu_kin + sum_k mu_k max(0, 1 - s_a / (2 s_hk))
//! * rational: mu_s(s_a) = mu_kin + mu_1 / (1 + s_a/s_h1)
//!   + mu_2 / (1 + (s_a/s_h2)²)
//!
//! with two terms k = 1, 2 (a zero coefficient disables one); s_hk is the
//! slip velocity at which term k is halved (the linear law's term reaches
//! 0 at 2 s_hk), and mu_s(0) = mu_kin + mu_1 + mu_2 is the static
//! coefficient.
//!
//! The slip velocity of an element is the rolling speed V times the
//! solver's slip: V |s| in steady rolling (s per unit rolled distance),
//! V |S| / dq in a transient rolling step of dq (S the slipped distance),
//! and |S| / (1 s) in a shift step, as CONTACT does for its shifts (the
//! user guide's footnote to eq. `exponential_law`: delta t = 1 s).
//!
//! Friction memory (same guide, subsection "Friction memory", eq.
//! `dmu_dt`): the coefficient relaxes towards mu_s(s_a) over a sliding
//! distance d_c rather than jumping,
//! dmu/dt = -max(s_a, s_0)/d_c (mu - mu_s(s_a)). Over a time step dt with
//! s_a held fixed this gives
//! mu = mu_s + (mu' - mu_s) exp(-max(s_a, s_0) dt / d_c), mu' the
//! coefficient the same material had one step before (in steady rolling:
//! the element upstream, dt = dx / V; material entering the patch has
//! mu' = mu_s(0)). d_c = 0 is the instantaneous law.
//!
//! The bound mu(s_a) p_n depends on the slip it bounds, so the problem is
//! no longer convex and may have several solutions (Vollebregt &
//! Schuttelaars 2012, §4). The driver ([`crate::core::solve`]) solves it by
//! a fixed-point iteration on the slip velocities, each pass a Coulomb
//! problem with the bounds of the last slip; which solution it reaches is
//! set by the start ([`SlipStart`]).

use serde::{Deserialize, Serialize};

use crate::core::error::{require_finite, require_positive, ContactError};
use crate::core::grid::Grid;
use crate::core::problem::check_friction_coefficient;

/// Iteration limit of the fixed-point iteration on the slip velocities
/// when [`SlipVelocityLaw::max_iterations`] is 0.
pub const DEFAULT_LAW_ITERATIONS: usize = 200;

/// How the friction coefficient falls with the slip velocity.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FallingShape {
    /// mu_kin + sum_k mu_k max(0, 1 - s_a / (2 s_hk)) (CONTACT's L = 2).
    Linear,
    /// mu_kin + mu_1 / (1 + s_a/s_h1) + mu_2 / (1 + (s_a/s_h2)²) (L = 3).
    Rational,
    /// mu_kin + sum_k mu_k exp(-ln 2 s_a / s_hk) (L = 4).
    Exponential,
}

impl FallingShape {
    /// The name used in case files: `"linear"`, `"rational"`, `"exponential"`.
    pub fn name(self) -> &'static str {
        match self {
            FallingShape::Linear => "linear",
            FallingShape::Rational => "rational",
            FallingShape::Exponential => "exponential",
        }
    }
}

/// Which solution the iteration on the slip velocities starts towards.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SlipStart {
    /// The slip velocities of the solver's previous solve (carried with the
    /// material in a rolling step): continuation, the default. Zero on a
    /// fresh solver, as `Sticking`; a wheel/rail session's exact patch
    /// starts from its previous time step's
    /// ([`crate::wheelrail::PatchTractions::slip_velocity_m_per_s`]).
    #[default]
    Previous,
    /// Zero slip velocity, the static coefficient everywhere: approaches
    /// the solution with the least slip from below (CONTACT's INISLP > 0,
    /// the `veldep_fric` example's "s^0 = 0").
    Sticking,
    /// A slip velocity equal to the rolling speed everywhere: approaches the
    /// solution with the most slip from above (CONTACT's INISLP < 0, "s^0 =
    /// V").
    Sliding,
}

/// A slip-velocity dependent friction law (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SlipVelocityLaw {
    /// Shape of the fall.
    pub shape: FallingShape,
    /// mu_kin [-], the limit at large slip velocity, > 0.
    pub kinetic_coefficient: f64,
    /// mu_1, mu_2 [-], the sizes of the two terms at s_a = 0, >= 0.
    pub falling_coefficients: [f64; 2],
    /// s_h1, s_h2 \[m/s\]: the slip velocity at which each term is halved,
    /// > 0 where its coefficient is not 0.
    pub half_velocities_m_per_s: [f64; 2],
    /// Rolling speed V \[m/s\], > 0: converts the solver's slip to a slip
    /// velocity (see the module docs).
    pub rolling_speed_m_per_s: f64,
    /// Memory distance d_c \[m\], >= 0 (0: instantaneous law).
    pub memory_distance_m: f64,
    /// Memory velocity s_0 \[m/s\], >= 0: the smallest rate at which the
    /// coefficient relaxes, also where the material sticks.
    pub memory_velocity_m_per_s: f64,
    /// Start of the iteration on the slip velocities.
    pub start: SlipStart,
    /// Limit of that iteration (0: [`DEFAULT_LAW_ITERATIONS`]).
    pub max_iterations: usize,
}

impl SlipVelocityLaw {
    /// The coefficient mu_s(s_a) at the absolute slip velocity `s_a`
    /// \[m/s\] (no memory).
    #[inline]
    pub fn coefficient(&self, s_a: f64) -> f64 {
        let [m1, m2] = self.falling_coefficients;
        let [h1, h2] = self.half_velocities_m_per_s;
        let term = |m: f64, h: f64, second: bool| -> f64 {
            if m == 0.0 {
                return 0.0;
            }
            let r = s_a / h;
            m * match self.shape {
                FallingShape::Exponential => (-std::f64::consts::LN_2 * r).exp(),
                FallingShape::Linear => (1.0 - 0.5 * r).max(0.0),
                FallingShape::Rational if second => 1.0 / (1.0 + r * r),
                FallingShape::Rational => 1.0 / (1.0 + r),
            }
        };
        self.kinetic_coefficient + term(m1, h1, false) + term(m2, h2, true)
    }

    /// The static coefficient mu_s(0) = mu_kin + mu_1 + mu_2 [-].
    pub fn static_coefficient(&self) -> f64 {
        self.kinetic_coefficient + self.falling_coefficients[0] + self.falling_coefficients[1]
    }

    /// The fixed-point iteration's limit.
    pub fn iteration_limit(&self) -> usize {
        if self.max_iterations == 0 {
            DEFAULT_LAW_ITERATIONS
        } else {
            self.max_iterations
        }
    }

    /// Checks every parameter; errors name the key under `friction.`.
    pub fn validate(&self) -> Result<(), ContactError> {
        let kin =
            check_friction_coefficient("friction.kinetic_coefficient", self.kinetic_coefficient)?;
        if kin == 0.0 {
            return Err(ContactError::invalid(
                "friction.kinetic_coefficient",
                "must be > 0 with a falling law (the limit at large slip velocity bounds every slipping element)",
            ));
        }
        for k in 0..2 {
            let m = self.falling_coefficients[k];
            let key = format!("friction.falling_coefficients[{k}]");
            require_finite(&key, m)?;
            if m < 0.0 {
                return Err(ContactError::invalid(key, "must be >= 0"));
            }
            if m != 0.0 {
                require_positive(
                    &format!("friction.half_velocities_m_per_s[{k}]"),
                    self.half_velocities_m_per_s[k],
                )?;
            }
        }
        check_friction_coefficient("friction.falling_coefficients", self.static_coefficient())
            .map_err(|_| {
                ContactError::invalid(
                    "friction.falling_coefficients",
                    format!(
                        "the static coefficient kinetic_coefficient + falling_coefficients = {} \
                         must be at most 5",
                        crate::core::error::show(self.static_coefficient())
                    ),
                )
            })?;
        require_positive("friction.rolling_speed_m_per_s", self.rolling_speed_m_per_s)?;
        for (key, v) in [
            ("friction.memory_distance_m", self.memory_distance_m),
            (
                "friction.memory_velocity_m_per_s",
                self.memory_velocity_m_per_s,
            ),
        ] {
            require_finite(key, v)?;
            if v < 0.0 {
                return Err(ContactError::invalid(key, "must be >= 0"));
            }
        }
        Ok(())
    }

    /// The coefficient after a step of `dt_s` \[s\] at slip velocity `s_a`
    /// from `before` (the memory law over the step; mu_s(s_a) without
    /// memory).
    #[inline]
    pub fn relaxed(&self, s_a: f64, before: f64, dt_s: f64) -> f64 {
        let target = self.coefficient(s_a);
        if self.memory_distance_m == 0.0 {
            return target;
        }
        let rate = s_a.max(self.memory_velocity_m_per_s) / self.memory_distance_m;
        target + (before - target) * (-rate * dt_s).exp()
    }

    /// The coefficients `mu` of a steady rolling solution with slip
    /// velocities `s_a` \[m/s\] on `grid`: each element relaxes from its
    /// upstream neighbour over dt = dx / V; material enters at the leading
    /// edge with the static coefficient.
    pub fn steady_coefficients(&self, grid: &Grid, s_a: &[f64], mu: &mut [f64]) {
        let dt = grid.dx_m / self.rolling_speed_m_per_s;
        let fresh = self.static_coefficient();
        for (v, m) in s_a.chunks_exact(grid.nx).zip(mu.chunks_exact_mut(grid.nx)) {
            let mut up = fresh;
            for ix in (0..grid.nx).rev() {
                m[ix] = self.relaxed(v[ix], up, dt);
                up = m[ix];
            }
        }
    }

    /// The coefficients `mu` of a transient step of `dt_s` \[s\] with slip
    /// velocities `s_a` \[m/s\], from the coefficients `before` of the same
    /// material one step before (0: no history, fresh material with the
    /// static coefficient).
    pub fn step_coefficients(&self, s_a: &[f64], before: &[f64], dt_s: f64, mu: &mut [f64]) {
        let fresh = self.static_coefficient();
        for ((m, &v), &b) in mu.iter_mut().zip(s_a).zip(before) {
            *m = self.relaxed(v, if b > 0.0 { b } else { fresh }, dt_s);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn law(shape: FallingShape) -> SlipVelocityLaw {
        // CONTACT's veldep_fric.inp: FKIN 0.18, FEXP1 0.12, SABSH1 100 mm/s,
        // V = 45 m/s, MEMDST 0.
        SlipVelocityLaw {
            shape,
            kinetic_coefficient: 0.18,
            falling_coefficients: [0.12, 0.0],
            half_velocities_m_per_s: [0.1, 0.0],
            rolling_speed_m_per_s: 45.0,
            memory_distance_m: 0.0,
            memory_velocity_m_per_s: 0.0,
            start: SlipStart::Previous,
            max_iterations: 0,
        }
    }

    #[test]
    fn each_term_is_halved_at_its_half_velocity() {
        // User guide eqs. exponential_law, linear_law, rational_law: mu_s(0)
        // = mu_kin + mu_1 + mu_2; the first term is halved at s_h1.
        for shape in [
            FallingShape::Exponential,
            FallingShape::Linear,
            FallingShape::Rational,
        ] {
            let l = law(shape);
            assert!((l.coefficient(0.0) - 0.30).abs() < 1e-15, "{shape:?}");
            assert!((l.coefficient(0.1) - 0.24).abs() < 1e-15, "{shape:?}");
        }
        // Far out: the exponential law at 10 s_h is mu_kin + mu_1/1024, the
        // linear one reaches mu_kin at 2 s_h, the rational one at 9 s_h is
        // mu_kin + mu_1/10.
        let e = law(FallingShape::Exponential).coefficient(1.0);
        assert!((e - (0.18 + 0.12 / 1024.0)).abs() < 1e-15);
        assert_eq!(law(FallingShape::Linear).coefficient(0.2), 0.18);
        assert_eq!(law(FallingShape::Linear).coefficient(5.0), 0.18);
        let r = law(FallingShape::Rational).coefficient(0.9);
        assert!((r - 0.192).abs() < 1e-15);
        // The rational law's second term falls with the square.
        let mut l = law(FallingShape::Rational);
        l.falling_coefficients = [0.0, 0.06];
        l.half_velocities_m_per_s = [0.0, 0.3162];
        assert!((l.coefficient(3.0 * 0.3162) - (0.18 + 0.006)).abs() < 1e-15);
    }

    #[test]
    fn memory_relaxes_over_the_memory_distance() {
        let mut l = law(FallingShape::Exponential);
        l.memory_distance_m = 1e-6;
        l.memory_velocity_m_per_s = 1e-3;
        // Sliding at 0.1 m/s for the time it takes to slide d_c: the gap to
        // mu_s(0.1) = 0.24 shrinks by e.
        let mu = l.relaxed(0.1, 0.30, 1e-5);
        assert!((mu - (0.24 + 0.06 / std::f64::consts::E)).abs() < 1e-14);
        // Sticking relaxes at s_0 only.
        let mu = l.relaxed(0.0, 0.20, 1e-3);
        assert!((mu - (0.30 - 0.10 / std::f64::consts::E)).abs() < 1e-14);
        // Without memory the coefficient is mu_s.
        assert_eq!(law(FallingShape::Exponential).relaxed(0.1, 0.3, 1.0), 0.24);
    }

    #[test]
    fn rejects_bad_parameters_by_key() {
        let key = |l: SlipVelocityLaw| l.validate().unwrap_err().key().unwrap().to_string();
        let mut l = law(FallingShape::Exponential);
        l.kinetic_coefficient = 0.0;
        assert_eq!(key(l), "friction.kinetic_coefficient");
        let mut l = law(FallingShape::Exponential);
        l.half_velocities_m_per_s = [0.0, 0.0];
        assert_eq!(key(l), "friction.half_velocities_m_per_s[0]");
        let mut l = law(FallingShape::Exponential);
        l.falling_coefficients = [-0.1, 0.0];
        assert_eq!(key(l), "friction.falling_coefficients[0]");
        let mut l = law(FallingShape::Exponential);
        l.falling_coefficients = [6.0, 0.0];
        assert_eq!(key(l), "friction.falling_coefficients");
        let mut l = law(FallingShape::Exponential);
        l.rolling_speed_m_per_s = 0.0;
        assert_eq!(key(l), "friction.rolling_speed_m_per_s");
        let mut l = law(FallingShape::Exponential);
        l.memory_distance_m = f64::NAN;
        assert_eq!(key(l), "friction.memory_distance_m");
        // The unused second term needs no half velocity.
        assert!(law(FallingShape::Linear).validate().is_ok());
    }
}
