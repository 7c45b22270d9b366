//! The warm start of a solver that follows a path of inputs: a secant
//! predictor.
//!
//! An MBS client calls the same patch every time step with a slightly
//! different load and creepages. Starting each solve from the previous
//! solution leaves an error of the order of the input's change; the
//! Newton solvers then spend one step or more to remove it. When the
//! inputs move along a line (locally: consecutive steps of a smooth
//! trajectory, or a sweep), the solution moves along a line too to first
//! order, so the start
//!
//! ```text
//! p_start = p_k + theta (p_k - p_{k-1}),   u_{k+1} - u_k ≈ theta (u_k - u_{k-1})
//! ```
//!
//! leaves an error of the order of the change squared. `theta` is the
//! least-squares fit of the new input change on the previous one in the
//! scaled input space (load; creepages and spin times the grid's reach),
//! used only when the fit is close (otherwise the plain warm start,
//! theta = 0). Alternating inputs give theta = -1: the start is then the
//! solution of the repeated input itself.
//!
//! Only the start changes: every solve still converges to its own
//! tolerance, and the result is a function of the sequence of inputs
//! (deterministic, as session replays need).

use std::hash::{Hash, Hasher};

use crate::core::memory::{heap_bytes, HeapBytes};
use crate::core::normal::NormalLoad;
use crate::core::problem::{ContactProblem, Kinematics};

/// Largest relative misfit |d2 - theta d1| / |d2| at which the secant
/// start is used.
const MAX_MISFIT: f64 = 0.25;
/// The extrapolation factor is clamped to this range (beyond it the
/// linear model is not trusted; -1 repeats the solution before last).
const THETA_RANGE: (f64, f64) = (-1.0, 2.0);

/// The inputs of one solve as the predictor sees them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PathPoint {
    /// Fingerprint of everything that must not change along a path: the
    /// undeformed distance, friction, materials, grid and the kind of
    /// load control and kinematics.
    key: u64,
    /// Normal force [N] or approach [m].
    load: f64,
    /// Creepages, spin times the grid's reach [-].
    creep: [f64; 3],
}

impl PathPoint {
    /// The point of a frictionless or steady-rolling `problem`.
    pub(crate) fn of(problem: &ContactProblem) -> Self {
        let mut h = std::collections::hash_map::DefaultHasher::new();
        for v in &problem.gap_m {
            v.to_bits().hash(&mut h);
        }
        let g = &problem.grid;
        let f = &problem.friction;
        let m = &problem.material;
        for v in [
            f.static_coefficient,
            f.kinetic_coefficient,
            g.dx_m,
            g.dy_m,
            g.x0_m,
            g.y0_m,
            m.body1.shear_modulus_pa,
            m.body1.poisson_ratio,
            m.body2.shear_modulus_pa,
            m.body2.poisson_ratio,
        ] {
            v.to_bits().hash(&mut h);
        }
        (g.nx, g.ny).hash(&mut h);
        let (control, load) = match problem.load {
            NormalLoad::NormalForce(f) => (0u8, f),
            NormalLoad::Approach(d) => (1u8, d),
        };
        control.hash(&mut h);
        let reach = [
            g.x0_m,
            g.x0_m + g.nx as f64 * g.dx_m,
            g.y0_m,
            g.y0_m + g.ny as f64 * g.dy_m,
        ]
        .iter()
        .fold(0.0f64, |a, v| a.max(v.abs()));
        let creep = match &problem.kinematics {
            Kinematics::SteadyRolling(c) => {
                1u8.hash(&mut h);
                [c.creepage_long, c.creepage_lat, c.spin_per_m * reach]
            }
            _ => {
                0u8.hash(&mut h);
                [0.0; 3]
            }
        };
        Self {
            key: h.finish(),
            load,
            creep,
        }
    }
}

/// The secant factor theta for the path `a`, `b`, `c` (oldest first), or
/// 0 when the points are not on one path or not close to a line.
fn secant_factor(a: &PathPoint, b: &PathPoint, c: &PathPoint) -> f64 {
    if a.key != c.key || b.key != c.key {
        return 0.0;
    }
    let ls = a.load.abs().max(b.load.abs()).max(c.load.abs());
    let cs = [a, b, c]
        .iter()
        .flat_map(|p| p.creep.iter())
        .fold(0.0f64, |m, v| m.max(v.abs()));
    let scaled = |p: &PathPoint| {
        let s = |v: f64, scale: f64| if scale > 0.0 { v / scale } else { 0.0 };
        [
            s(p.load, ls),
            s(p.creep[0], cs),
            s(p.creep[1], cs),
            s(p.creep[2], cs),
        ]
    };
    let (ua, ub, uc) = (scaled(a), scaled(b), scaled(c));
    let d1: [f64; 4] = std::array::from_fn(|j| ub[j] - ua[j]);
    let d2: [f64; 4] = std::array::from_fn(|j| uc[j] - ub[j]);
    let dot = |x: &[f64; 4], y: &[f64; 4]| x.iter().zip(y).map(|(a, b)| a * b).sum::<f64>();
    let (n1, n2, d12) = (dot(&d1, &d1), dot(&d2, &d2), dot(&d1, &d2));
    if !(n1 > 0.0 && n2 > 0.0) {
        return 0.0;
    }
    // Least squares: |d2 - theta d1|² = |d2|² - theta (d1.d2).
    let theta = d12 / n1;
    let misfit2 = n2 - theta * d12;
    if misfit2 > MAX_MISFIT * MAX_MISFIT * n2 || !theta.is_finite() {
        return 0.0;
    }
    theta.clamp(THETA_RANGE.0, THETA_RANGE.1)
}

/// The path memory of a solver: the inputs of its last two solves and the
/// solution of the one before last (the last one is the solver's own
/// state).
#[derive(Debug, Clone, Default)]
pub(crate) struct WarmPath {
    /// Inputs of the solve before last and of the last solve.
    points: [Option<PathPoint>; 2],
    /// The solution of `points[0]`: pressure and tractions [Pa] (empty
    /// until the first solve).
    pn: Vec<f64>,
    px: Vec<f64>,
    py: Vec<f64>,
}

impl WarmPath {
    /// Forgets the path (after a reset, a failed solve, or a start the
    /// caller set).
    pub(crate) fn clear(&mut self) {
        self.points = [None, None];
    }

    /// Whether no solve is remembered.
    pub(crate) fn is_empty(&self) -> bool {
        self.points.iter().all(Option::is_none)
    }

    /// Before solving `next`: turns the solver's state (`pn`, `px`, `py`,
    /// the last solution) into the predicted start and keeps the last
    /// solution. Returns theta (0: the plain warm start).
    pub(crate) fn predict(&mut self, next: &PathPoint, [pn, px, py]: [&mut [f64]; 3]) -> f64 {
        let theta = match &self.points {
            [Some(a), Some(b)] => secant_factor(a, b, next),
            _ => 0.0,
        };
        if self.pn.len() != pn.len() {
            // First use (allocated once per solver).
            self.pn = vec![0.0; pn.len()];
            self.px = vec![0.0; pn.len()];
            self.py = vec![0.0; pn.len()];
        }
        let extrapolate = |cur: &mut [f64], old: &mut [f64], floor: f64| {
            for (c, o) in cur.iter_mut().zip(old.iter_mut()) {
                let v = *c;
                *c = (v + theta * (v - *o)).max(floor);
                *o = v;
            }
        };
        extrapolate(pn, &mut self.pn, 0.0);
        extrapolate(px, &mut self.px, f64::NEG_INFINITY);
        extrapolate(py, &mut self.py, f64::NEG_INFINITY);
        theta
    }

    /// Becomes a copy of `other` (reusing its buffers).
    pub(crate) fn copy_from(&mut self, other: &Self) {
        self.points = other.points;
        self.pn.clone_from(&other.pn);
        self.px.clone_from(&other.px);
        self.py.clone_from(&other.py);
    }

    /// Memory held by the kept solution \[bytes\].
    pub(crate) fn bytes(&self) -> usize {
        8 * (self.pn.len() + self.px.len() + self.py.len())
    }

    /// Frees the kept solution's buffers when they hold none (no solve
    /// before last); the next prediction allocates them again.
    pub(crate) fn release(&mut self) {
        if self.points[0].is_none() {
            (self.pn, self.px, self.py) = Default::default();
        }
    }

    /// After a successful solve of `p`.
    pub(crate) fn push(&mut self, p: PathPoint) {
        self.points = [self.points[1], Some(p)];
    }
}

impl HeapBytes for WarmPath {
    fn heap_bytes(&self) -> usize {
        heap_bytes!(self.pn, self.px, self.py)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(load: f64, xi: f64) -> PathPoint {
        PathPoint {
            key: 7,
            load,
            creep: [xi, 0.5 * xi, 0.0],
        }
    }

    #[test]
    fn secant_factor_of_lines_alternations_and_bends() {
        // Equal steps along a line: theta = 1; half a step: 0.5.
        let (a, b) = (point(1e4, 1e-3), point(1.01e4, 1.1e-3));
        assert!((secant_factor(&a, &b, &point(1.02e4, 1.2e-3)) - 1.0).abs() < 1e-9);
        assert!((secant_factor(&a, &b, &point(1.015e4, 1.15e-3)) - 0.5).abs() < 1e-9);
        // Back to the first input: -1.
        assert!((secant_factor(&a, &b, &a) + 1.0).abs() < 1e-12);
        // A right angle in input space (creepage, then load): none.
        let b2 = point(1e4, 1.1e-3);
        assert_eq!(secant_factor(&a, &b2, &point(1.01e4, 1.1e-3)), 0.0);
        // A far step along the line is clamped.
        assert_eq!(secant_factor(&a, &b, &point(1.1e4, 2e-3)), THETA_RANGE.1);
        // No change, or another problem: none.
        assert_eq!(secant_factor(&a, &b, &b), 0.0);
        let other = PathPoint {
            key: 8,
            ..point(1.02e4, 1.2e-3)
        };
        assert_eq!(secant_factor(&a, &b, &other), 0.0);
    }

    #[test]
    fn predict_extrapolates_and_keeps_the_last_solution() {
        let mut w = WarmPath::default();
        let (mut pn, mut px, mut py) = (vec![0.0; 2], vec![0.0; 2], vec![0.0; 2]);
        // The order of a solver: predict, solve, push. No history yet:
        // the start is the state itself.
        for (k, s) in [
            ([1.0, 2.0], [0.5, 0.0], [0.0, 0.1]),
            ([1.5, 1.0], [0.6, 0.0], [0.0, 0.3]),
        ]
        .into_iter()
        .enumerate()
        {
            let p = point(1.0 + k as f64, 1e-3 * (1.0 + k as f64));
            assert_eq!(w.predict(&p, [&mut pn, &mut px, &mut py]), 0.0);
            (pn, px, py) = (s.0.to_vec(), s.1.to_vec(), s.2.to_vec());
            w.push(p);
        }
        let theta = w.predict(&point(3.0, 3e-3), [&mut pn, &mut px, &mut py]);
        assert!((theta - 1.0).abs() < 1e-12);
        assert_eq!(pn, [2.0, 0.0]); // 1.0 + (1.0 - 2.0) = 0, and never below
        assert!((px[0] - 0.7).abs() < 1e-12 && (py[1] - 0.5).abs() < 1e-12);
        assert_eq!(w.pn, [1.5, 1.0]);
        // A failed solve forgets the path.
        w.clear();
        assert_eq!(
            w.predict(&point(4.0, 4e-3), [&mut pn, &mut px, &mut py]),
            0.0
        );
    }
}
