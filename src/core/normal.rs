//! The normal contact problem: a bound-constrained conjugate gradient method
//! with FFT matrix-vector products (Polonsky & Keer, Wear 231 (1999) 206–219,
//! §2.3, for load control; the same iteration without the mean-gap shift and
//! the load rescaling for approach control).
//!
//! Find p_n >= 0 with g = h - delta + u_n(p_n) >= 0 and p_n g = 0, where u_n =
//! A_nn p_n (plus a fixed contribution of the tangential tractions when the
//! materials differ, folded into h by the caller). Convergence: the relative
//! change of the pressures in one iteration, sum|p - p_old| / sum p, drops
//! below `tolerance` (default 1e-10).

use crate::core::fft::{KernelSet, OperatorWorkspace};
use crate::core::influence::Component;

/// Normal load control.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum NormalLoad {
    /// Prescribed total normal force [N], > 0.
    NormalForce(f64),
    /// Prescribed approach [m] (the rigid-body approach of the bodies).
    Approach(f64),
}

/// Settings of the normal solver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NormalSettings {
    /// Relative pressure change that ends the iteration [-] (default 1e-10).
    pub tolerance: f64,
    /// Iteration limit (default 1000).
    pub max_iterations: usize,
}

impl Default for NormalSettings {
    fn default() -> Self {
        Self {
            tolerance: 1e-10,
            max_iterations: 1000,
        }
    }
}

/// Outcome of [`solve_normal`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NormalOutcome {
    /// Iterations used.
    pub iterations: usize,
    /// FFT matvecs used.
    pub matvecs: usize,
    /// Approach [m].
    pub approach_m: f64,
    /// Final relative pressure change.
    pub residual: f64,
    /// Whether the tolerance was met.
    pub converged: bool,
}

/// Work arrays for [`solve_normal`] (allocated once per grid).
#[derive(Clone)]
pub struct NormalScratch {
    u: Vec<f64>,
    t: Vec<f64>,
    r: Vec<f64>,
    g: Vec<f64>,
    p_old: Vec<f64>,
}

impl NormalScratch {
    /// Buffers for `n` elements.
    pub fn new(n: usize) -> Self {
        Self {
            u: vec![0.0; n],
            t: vec![0.0; n],
            r: vec![0.0; n],
            g: vec![0.0; n],
            p_old: vec![0.0; n],
        }
    }
}

/// The linear map p_n -> u_n (normal displacement differences of normal
/// pressures) that [`solve_normal_with`] works with. It must be symmetric
/// positive definite on the pressures (a convex problem).
pub trait NormalOperator {
    /// `out = A p`.
    fn apply_normal(&mut self, p: &[f64], out: &mut [f64]);
    /// The self-influence coefficient A_II (> 0) [m/Pa].
    fn diagonal(&self) -> f64;
}

/// The planar half-space operator of a kernel set.
pub struct PlanarNormal<'a> {
    /// Displacement kernels.
    pub kernels: &'a KernelSet,
    /// Buffers.
    pub ows: &'a mut OperatorWorkspace,
}

impl NormalOperator for PlanarNormal<'_> {
    fn apply_normal(&mut self, p: &[f64], out: &mut [f64]) {
        self.kernels
            .apply(self.ows, &[(Component::N, p)], &mut [(Component::N, out)]);
    }

    fn diagonal(&self) -> f64 {
        self.kernels.value(Component::N, Component::N, 0, 0)
    }
}

/// Solves the normal problem on a planar patch. `h` is the undeformed
/// distance [m] per element; `pn` [Pa] is the initial guess on entry (zeros
/// allowed) and the solution on exit. `area` is the element area [m²]. No
/// allocation.
#[allow(clippy::too_many_arguments)]
pub fn solve_normal(
    k: &KernelSet,
    ows: &mut OperatorWorkspace,
    h: &[f64],
    area: f64,
    load: NormalLoad,
    pn: &mut [f64],
    scratch: &mut NormalScratch,
    settings: &NormalSettings,
) -> NormalOutcome {
    let mut op = PlanarNormal { kernels: k, ows };
    solve_normal_with(&mut op, h, None, area, load, pn, scratch, settings)
}

/// The general normal solver: operator `op`, and per-element approach
/// weights `w` (None: all 1). The gap is h - delta w + A p, and force
/// control prescribes sum w p_n area = F: for a conformal patch w is
/// cos(delta(s) - delta(0)), the approach is along the normal at the
/// reference point and F the force along it (paper Eq. 1).
#[allow(clippy::too_many_arguments)]
pub fn solve_normal_with(
    op: &mut dyn NormalOperator,
    h: &[f64],
    weights: Option<&[f64]>,
    area: f64,
    load: NormalLoad,
    pn: &mut [f64],
    scratch: &mut NormalScratch,
    settings: &NormalSettings,
) -> NormalOutcome {
    let n = h.len();
    let w = |i: usize| weights.map_or(1.0, |w| w[i]);
    let a_self = op.diagonal();
    let NormalScratch { u, t, r, g, p_old } = scratch;
    let mut matvecs = 0;
    let force_control = matches!(load, NormalLoad::NormalForce(_));
    // Initial guess.
    let sum: f64 = pn.iter().sum();
    match load {
        NormalLoad::NormalForce(f) => {
            if !(sum > 0.0) {
                // Uniform pressure over the elements of smallest gap (a quarter of the grid).
                let (hmin, hmax) = h
                    .iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                        (a.min(v), b.max(v))
                    });
                let thr = hmin + 0.25 * (hmax - hmin);
                let cnt = h.iter().filter(|&&v| v <= thr).count().max(1);
                for (p, &hv) in pn.iter_mut().zip(h.iter()) {
                    *p = if hv <= thr {
                        f / (area * cnt as f64)
                    } else {
                        0.0
                    };
                }
            } else {
                let ws: f64 = (0..n).map(|i| w(i) * pn[i]).sum();
                let s = f / (ws.max(f64::MIN_POSITIVE) * area);
                pn.iter_mut().for_each(|p| *p *= s);
            }
        }
        NormalLoad::Approach(_) => {}
    }
    let delta_fixed = match load {
        NormalLoad::Approach(d) => d,
        NormalLoad::NormalForce(_) => 0.0,
    };
    if !force_control && !(sum > 0.0) {
        // Start from the overlap scaled by the self-influence coefficient.
        for i in 0..n {
            pn[i] = (delta_fixed * w(i) - h[i]).max(0.0) / a_self * 0.5;
        }
    }
    let mut g_old = 1.0;
    let mut conj = false;
    let mut approach = delta_fixed;
    let mut residual = f64::INFINITY;
    let mut iterations = 0;
    t.fill(0.0);
    // u = A p is carried along (u <- c (u - tau A t)) while the step is a
    // plain CG step; it is recomputed after a projection or an entering
    // element changed p otherwise, and every REFRESH iterations against drift.
    const REFRESH: usize = 25;
    let mut u_valid = false;
    let mut since_refresh = 0;
    for it in 0..settings.max_iterations {
        iterations = it + 1;
        if !u_valid || since_refresh >= REFRESH {
            op.apply_normal(pn, u);
            matvecs += 1;
            since_refresh = 0;
        }
        since_refresh += 1;
        for i in 0..n {
            g[i] = u[i] + h[i];
        }
        // Force control: the approach is the weighted least-squares fit of
        // the gap over the contact set (its mean when all weights are 1).
        let mut nc = 0usize;
        let (mut gsum, mut wsum2) = (0.0, 0.0);
        for i in 0..n {
            if pn[i] > 0.0 {
                nc += 1;
                gsum += w(i) * g[i];
                wsum2 += w(i) * w(i);
            }
        }
        if force_control {
            if nc == 0 || wsum2 <= 0.0 {
                break;
            }
            approach = gsum / wsum2;
        }
        for (i, gi) in g.iter_mut().enumerate() {
            *gi -= approach * w(i);
        }
        let mut gg = 0.0;
        for i in 0..n {
            if pn[i] > 0.0 {
                gg += g[i] * g[i];
            }
        }
        let beta = if conj { gg / g_old } else { 0.0 };
        for i in 0..n {
            t[i] = if pn[i] > 0.0 { g[i] + beta * t[i] } else { 0.0 };
        }
        g_old = gg;
        op.apply_normal(t, r);
        matvecs += 1;
        // Force control works with the gap relative to its weighted fit
        // over the contact set (the approach is unknown).
        let rm = if force_control && wsum2 > 0.0 {
            (0..n)
                .filter(|&i| pn[i] > 0.0)
                .map(|i| w(i) * r[i])
                .sum::<f64>()
                / wsum2
        } else {
            0.0
        };
        let (mut num, mut den) = (0.0, 0.0);
        for i in 0..n {
            if pn[i] > 0.0 {
                num += g[i] * t[i];
                den += (r[i] - rm * w(i)) * t[i];
            }
        }
        let tau = if den > 0.0 { num / den } else { 0.0 };
        p_old.copy_from_slice(pn);
        let mut overlap = false;
        let mut clamped = false;
        for i in 0..n {
            let old = p_old[i];
            let mut v = if old > 0.0 { old - tau * t[i] } else { 0.0 };
            if v < 0.0 {
                v = 0.0;
                clamped = true;
            }
            if old <= 0.0 && g[i] < 0.0 {
                // Overlapping element outside the contact set: enter with a
                // gradient step (Polonsky & Keer step 8).
                v = -tau.max(0.0) * g[i];
                if v == 0.0 {
                    v = -g[i] / a_self;
                }
                overlap = true;
            }
            pn[i] = v;
        }
        conj = !overlap;
        let mut scale = 1.0;
        if let NormalLoad::NormalForce(f) = load {
            let s: f64 = (0..n).map(|i| w(i) * pn[i]).sum::<f64>() * area;
            if s > 0.0 {
                scale = f / s;
                pn.iter_mut().for_each(|p| *p *= scale);
            }
        }
        u_valid = !(overlap || clamped);
        if u_valid {
            for i in 0..n {
                u[i] = scale * (u[i] - tau * r[i]);
            }
        }
        let mut change = 0.0;
        let mut total = 0.0;
        for i in 0..n {
            change += (pn[i] - p_old[i]).abs();
            total += pn[i];
        }
        residual = if total > 0.0 {
            change / total
        } else {
            f64::INFINITY
        };
        if residual < settings.tolerance && !overlap {
            break;
        }
    }
    // Final approach from the converged pressures.
    if force_control {
        if !u_valid {
            op.apply_normal(pn, u);
            matvecs += 1;
        }
        let (mut s, mut c) = (0.0, 0.0);
        for i in 0..n {
            if pn[i] > 0.0 {
                s += w(i) * (u[i] + h[i]);
                c += w(i) * w(i);
            }
        }
        if c > 0.0 {
            approach = s / c;
        }
    }
    NormalOutcome {
        iterations,
        matvecs,
        approach_m: approach,
        residual,
        converged: residual < settings.tolerance,
    }
}
