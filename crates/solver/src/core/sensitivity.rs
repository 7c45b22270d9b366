//! Sensitivities of a steady-rolling solution: the Jacobian of the patch
//! forces (Fn, Fx, Fy, Mz, on body 1) with respect to the approach and the
//! three creepages, at FIXED APPROACH (the one the solution reached,
//! whatever its load control), as implicit MBS integrators need it.
//!
//! # Method
//!
//! Central differences about the converged solution, each perturbed solve
//! warm-started from it (a clone of the solver that produced it), so that a
//! perturbed solve costs a few Newton steps instead of a cold solve: 8
//! extra solves, in a fixed order (deterministic). The forces are smooth in
//! their inputs wherever the adhesion/slip split moves continuously (the
//! whole range of Kalker's theory but the exact onset of full slip), and
//! central differences are second-order accurate there.
//!
//! Step sizes scale with the problem so that the truncation error and the
//! solver's tolerance both stay small:
//! - approach: 1e-3 of the approach;
//! - longitudinal and lateral creepage: 1e-2 of the creepage at which
//!   Kalker's linear theory reaches full slip, mu Fn / (G c^2 C), with
//!   c^2 the contact area over pi and C = 4 (C11, C22 of a round patch);
//!   with no friction, 1e-6;
//! - spin: the creepage step divided by c.

use crate::core::error::ContactError;
use crate::core::normal::NormalLoad;
use crate::core::problem::{ContactProblem, Creepages, Kinematics};
use crate::core::solution::{ContactSolution, Totals};
use crate::core::solve::ContactSolver;

/// Derivatives of (Fn, Fx, Fy, Mz) with respect to each input; units: the
/// force's per the input's (N/m, N, N, N m for the approach column's Fn,
/// ..., see the fields).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ForceJacobian {
    /// d(Fn, Fx, Fy, Mz) / d(approach) [N/m, N/m, N/m, N m/m].
    pub per_approach_m: [f64; 4],
    /// d(Fn, Fx, Fy, Mz) / d(longitudinal creepage) [N, N, N, N m].
    pub per_creepage_long: [f64; 4],
    /// d(Fn, Fx, Fy, Mz) / d(lateral creepage) [N, N, N, N m].
    pub per_creepage_lat: [f64; 4],
    /// d(Fn, Fx, Fy, Mz) / d(spin) [N m, N m, N m, N m^2].
    pub per_spin_per_m: [f64; 4],
    /// Extra solves the Jacobian cost.
    pub solves: usize,
}

impl ForceJacobian {
    /// The columns: approach, longitudinal, lateral, spin creepage; each
    /// (Fn, Fx, Fy, Mz).
    pub fn columns(&self) -> [[f64; 4]; 4] {
        [
            self.per_approach_m,
            self.per_creepage_long,
            self.per_creepage_lat,
            self.per_spin_per_m,
        ]
    }
}

/// The inputs a Jacobian is taken about.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JacobianPoint {
    /// Approach \[m\].
    pub approach_m: f64,
    /// Creepages.
    pub creepages: Creepages,
}

/// Step sizes of the central differences (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JacobianSteps {
    /// Approach step \[m\].
    pub approach_m: f64,
    /// Longitudinal and lateral creepage step [-].
    pub creepage: f64,
    /// Spin step [1/m].
    pub spin_per_m: f64,
}

impl JacobianSteps {
    /// The steps for a solution with these totals, friction coefficient
    /// `mu` and combined shear modulus `g_pa`.
    pub fn for_solution(totals: &Totals, mu: f64, g_pa: f64) -> Self {
        let c2 = (totals.contact_area_m2 / std::f64::consts::PI).max(f64::MIN_POSITIVE);
        let saturation = mu * totals.normal_force_n / (g_pa * c2 * 4.0);
        let creepage = if saturation.is_finite() && saturation > 0.0 {
            1e-2 * saturation
        } else {
            1e-6
        };
        Self {
            approach_m: 1e-3 * totals.approach_m.abs().max(1e-12),
            creepage,
            spin_per_m: creepage / c2.sqrt(),
        }
    }
}

/// The Jacobian about `point` by central differences of `forces(approach,
/// creepages) -> [Fn, Fx, Fy, Mz]` with `steps`: 8 evaluations, approach
/// first, then the creepages in order, minus before plus.
pub fn central_differences<E>(
    point: JacobianPoint,
    steps: JacobianSteps,
    mut forces: impl FnMut(f64, Creepages) -> Result<[f64; 4], E>,
) -> Result<ForceJacobian, E> {
    let JacobianPoint {
        approach_m: d,
        creepages: c,
    } = point;
    let mut column = |lo: (f64, Creepages), hi: (f64, Creepages), h: f64| {
        let a = forces(lo.0, lo.1)?;
        let b = forces(hi.0, hi.1)?;
        Ok::<_, E>(std::array::from_fn(|k| (b[k] - a[k]) / (2.0 * h)))
    };
    // Creepages with component k (long, lat, spin) moved by v.
    let with = |k: usize, v: f64| {
        let mut c2 = c;
        match k {
            0 => c2.creepage_long += v,
            1 => c2.creepage_lat += v,
            _ => c2.spin_per_m += v,
        }
        c2
    };
    let h = steps.approach_m;
    let per_approach_m = column((d - h, c), (d + h, c), h)?;
    let h = steps.creepage;
    let per_creepage_long = column((d, with(0, -h)), (d, with(0, h)), h)?;
    let per_creepage_lat = column((d, with(1, -h)), (d, with(1, h)), h)?;
    let h = steps.spin_per_m;
    let per_spin_per_m = column((d, with(2, -h)), (d, with(2, h)), h)?;
    Ok(ForceJacobian {
        per_approach_m,
        per_creepage_long,
        per_creepage_lat,
        per_spin_per_m,
        solves: 8,
    })
}

/// The forces of a solution as a Jacobian row: [Fn, Fx, Fy, Mz].
pub fn forces_of(t: &Totals) -> [f64; 4] {
    [t.normal_force_n, t.fx_n, t.fy_n, t.mz_nm]
}

/// The Jacobian of the exact model's steady-rolling solution `base` of
/// `problem`, solved last by `solver` (whose state is the warm start of
/// every perturbed solve; the solver itself is left untouched).
pub fn exact_jacobian(
    solver: &ContactSolver,
    problem: &ContactProblem,
    base: &ContactSolution,
) -> Result<ForceJacobian, ContactError> {
    let Kinematics::SteadyRolling(creepages) = problem.kinematics else {
        return Err(ContactError::invalid(
            "sensitivities",
            "are computed for steady rolling only",
        ));
    };
    let steps = JacobianSteps::for_solution(
        &base.totals,
        problem.friction.kinetic_coefficient,
        problem.material.shear_modulus_pa,
    );
    let point = JacobianPoint {
        approach_m: base.totals.approach_m,
        creepages,
    };
    let mut perturbed = problem.clone();
    central_differences(point, steps, |approach_m, c| {
        perturbed.load = NormalLoad::Approach(approach_m);
        perturbed.kinematics = Kinematics::SteadyRolling(c);
        let mut s = solver.clone();
        let sol = s.solve(&perturbed)?;
        Ok(forces_of(&sol[0].totals))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn central_differences_of_a_quadratic_are_exact() {
        // F = (d^2, 3 xi, eta^2 + d, phi xi): exact derivatives at
        // d = 2, xi = 0.5, eta = 1, phi = 4.
        let point = JacobianPoint {
            approach_m: 2.0,
            creepages: Creepages {
                creepage_long: 0.5,
                creepage_lat: 1.0,
                spin_per_m: 4.0,
            },
        };
        let steps = JacobianSteps {
            approach_m: 1e-3,
            creepage: 1e-3,
            spin_per_m: 1e-3,
        };
        let mut calls = 0;
        let j = central_differences(point, steps, |d, c| {
            calls += 1;
            Ok::<_, ()>([
                d * d,
                3.0 * c.creepage_long,
                c.creepage_lat * c.creepage_lat + d,
                c.spin_per_m * c.creepage_long,
            ])
        })
        .unwrap();
        assert_eq!(calls, 8);
        let close = |a: [f64; 4], b: [f64; 4]| a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-9);
        assert!(close(j.per_approach_m, [4.0, 0.0, 1.0, 0.0]), "{j:?}");
        assert!(close(j.per_creepage_long, [0.0, 3.0, 0.0, 4.0]), "{j:?}");
        assert!(close(j.per_creepage_lat, [0.0, 0.0, 2.0, 0.0]), "{j:?}");
        assert!(close(j.per_spin_per_m, [0.0, 0.0, 0.0, 0.5]), "{j:?}");
    }
}
