//! The normal contact problem: a bound-constrained conjugate gradient method
//! with FFT matrix-vector products (Polonsky & Keer, Wear 231 (1999) 206–219,
//! §2.3, for load control; the same iteration without the mean-gap shift and
//! the load rescaling for approach control), preconditioned as in
//! Vollebregt's BCCG (J. Comput. Phys. 257 (2014) 333–351) by the inverse of
//! a circulant approximation of the influence matrix on the free set, and
//! started from a Hertz-like pressure (or from the pressure given: a cold
//! solve of [`crate::core::solve::ContactSolver`] under force control gives
//! Hertz's where the gap is Hertzian, [`hertz_start`]). With the
//! preconditioner the iteration count hardly grows with the grid (about 10
//! for the Hertz circle from 32x32 to 128x128 from the Hertz-like start,
//! against 28 to 62 without; 5 or 6 for CONTACT's `tractcurv` ellipse from
//! 48x44 to 575x647 from Hertz's).
//!
//! One operator product an iteration: the displacements A p are carried
//! along the steps, and after a step that clamped elements to zero pressure
//! the product of those few pressure changes is added from the real-space
//! kernel column by column ([`NormalOperator::add_columns`]); only a step
//! that clamps more elements than a product's worth of columns
//! ([`NormalOperator::column_limit`]) takes a second product.
//!
//! Find p_n >= 0 with g = h - delta + u_n(p_n) >= 0 and p_n g = 0, where u_n =
//! A_nn p_n (plus a fixed contribution of the tangential tractions when the
//! materials differ, folded into h by the caller). Convergence: the relative
//! change of the pressures in one iteration, sum|p - p_old| / sum p, drops
//! below `tolerance` (default 1e-6: the normal force and the maximum
//! pressure within 1e-7 of a solve to 1e-12 on the Hertz ellipse, the test
//! `the_default_normal_tolerance_gives_forces_and_p_max_to_seven_digits`).

use crate::core::cancel;
use crate::core::error::ContactError;
use crate::core::fft::{KernelSet, OperatorWorkspace};
use crate::core::grid::Grid;
use crate::core::hertz::{hertz, HertzLoad};
use crate::core::influence::{Component, KernelKind};
use crate::core::memory::{heap_bytes, HeapBytes};
use crate::core::simd::multiversion;

/// Normal load control.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum NormalLoad {
    /// Prescribed total normal force \[N\], > 0.
    NormalForce(f64),
    /// Prescribed approach \[m\] (the rigid-body approach of the bodies).
    Approach(f64),
}

/// Settings of the normal solver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NormalSettings {
    /// Relative pressure change that ends the iteration [-] (default 1e-6).
    pub tolerance: f64,
    /// Iteration limit (default 1000).
    pub max_iterations: usize,
}

impl Default for NormalSettings {
    fn default() -> Self {
        Self {
            tolerance: 1e-6,
            max_iterations: 1000,
        }
    }
}

/// Outcome of [`solve_normal`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NormalOutcome {
    /// Iterations used.
    pub iterations: usize,
    /// FFT products of the operator used.
    pub matvecs: usize,
    /// Preconditioner applications used (FFT products on the unpadded
    /// grid, about a quarter of an operator product each).
    pub preconditioner_applications: usize,
    /// Approach \[m\].
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
    z: Vec<f64>,
    free: Vec<bool>,
    /// Unit weights.
    ones: Vec<f64>,
    /// The elements an iteration clamped to zero pressure and their
    /// pressure changes beyond the step (see [`NormalOperator::add_columns`]).
    columns: Vec<(usize, f64)>,
    kept: Kept,
    /// Buffers of [`solve_normal_active_set`], allocated at its first use.
    active: Option<Box<ActiveSetScratch>>,
}

/// The last solve's pressures and the age of their product in `u` (see
/// [`NormalScratch::keep_product`]).
#[derive(Clone, Default)]
struct Kept {
    on: bool,
    valid: bool,
    p: Vec<f64>,
    age: usize,
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
            z: vec![0.0; n],
            free: vec![false; n],
            ones: vec![1.0; n],
            columns: Vec::with_capacity(column_capacity(n)),
            kept: Kept::default(),
            active: None,
        }
    }

    /// Keeps each solve's final pressures with their product A p, so that
    /// a later solve started from those pressures (rescaled to its force,
    /// any gap) starts from the rescaled product instead of a new one: one
    /// FFT product less per warm solve, as in the conformal alternation.
    /// Only for a scratch that serves one operator: the kept product is
    /// that of the operator of the last solve. Forgets what was kept.
    pub fn keep_product(&mut self) {
        self.kept.on = true;
        self.kept.valid = false;
        self.kept.p.resize(self.u.len(), 0.0);
    }

    /// Starts a solve (its normal/tangential alternation): the
    /// active-set method's calls within it continue each other
    /// ([`solve_normal_active_set`]); nothing carries over from an
    /// earlier solve, so that a solve's answer depends on its own inputs
    /// and start only.
    pub fn begin_solve(&mut self) {
        if let Some(a) = self.active.as_deref_mut() {
            a.carried = false;
        }
    }
}

impl HeapBytes for NormalScratch {
    fn heap_bytes(&self) -> usize {
        heap_bytes!(
            self.u,
            self.t,
            self.r,
            self.g,
            self.p_old,
            self.z,
            self.free,
            self.ones,
            self.columns,
            self.kept.p
        ) + self.active.as_ref().map_or(0, |a| a.heap_bytes())
    }
}

/// Room for the clamped elements of one iteration in a [`NormalScratch`]
/// of `n` elements: `3 log2(8 n) + 1`, at least the
/// [`NormalOperator::column_limit`] of a planar grid of `n` elements (its
/// FFT array pads each side to at most about 1.4 times twice the side, so
/// holds at most 8 n values), so that a solve never allocates.
pub(crate) fn column_capacity(n: usize) -> usize {
    (3.0 * (8.0 * n.max(1) as f64).log2()) as usize + 1
}

/// The linear map p_n -> u_n (normal displacement differences of normal
/// pressures) that [`solve_normal_with`] works with. It must be symmetric
/// positive definite on the pressures (a convex problem).
pub trait NormalOperator {
    /// `out = A p`.
    fn apply_normal(&mut self, p: &[f64], out: &mut [f64]);
    /// The self-influence coefficient A_II (> 0) [m/Pa].
    fn diagonal(&self) -> f64;
    /// `z = M⁻¹ r` for a symmetric positive definite approximation M of the
    /// operator, at the cost of about one product; false (and `z` left
    /// alone) when the operator has none, and the solver runs without.
    fn precondition(&mut self, _r: &[f64], _z: &mut [f64]) -> bool {
        false
    }
    /// `out += sum_k A(., j_k) c_k` for a few (element j_k, value c_k)
    /// pairs, in ascending element order: the product of a pressure change
    /// on those elements; false (and `out` left alone) when the operator
    /// cannot, and the solver makes a whole product instead.
    fn add_columns(&mut self, _columns: &[(usize, f64)], _out: &mut [f64]) -> bool {
        false
    }
    /// How many columns [`NormalOperator::add_columns`] adds in about the
    /// time of one product (0: none).
    fn column_limit(&self) -> usize {
        0
    }
}

/// Several planar patches that do not interact elastically (as the
/// patches of one wheel, each in its own frame) as one block-diagonal
/// operator on their concatenated pressures: [`solve_normal_with`] then
/// solves them together, with one approach and one force. Each block is a
/// [`PlanarNormal`] (its kernels and buffers, e.g. those of the patch's
/// [`crate::core::solve::ContactSolver`]); all must have the same
/// self-influence (same element size and materials).
pub struct BlockNormal<'a> {
    /// Per block: its operator and its element range.
    blocks: Vec<(PlanarNormal<'a>, std::ops::Range<usize>)>,
}

impl<'a> BlockNormal<'a> {
    /// The operator of `parts`, in this order; None when their
    /// self-influences differ (by more than 1e-12 relative) or a part's
    /// kernels are not of displacement kind.
    pub fn new(parts: Vec<PlanarNormal<'a>>) -> Option<Self> {
        let d0 = parts.first()?.diagonal();
        let mut at = 0;
        let mut blocks = Vec::with_capacity(parts.len());
        for part in parts {
            let k = part.kernels;
            if k.kind != KernelKind::Displacement || (part.diagonal() - d0).abs() > 1e-12 * d0.abs()
            {
                return None;
            }
            let n = k.plan.nx * k.plan.ny;
            blocks.push((part, at..at + n));
            at += n;
        }
        Some(Self { blocks })
    }

    /// Total number of elements.
    pub fn len(&self) -> usize {
        self.blocks.last().map_or(0, |b| b.1.end)
    }

    /// True without blocks.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

impl NormalOperator for BlockNormal<'_> {
    fn apply_normal(&mut self, p: &[f64], out: &mut [f64]) {
        for (op, r) in &mut self.blocks {
            op.apply_normal(&p[r.clone()], &mut out[r.clone()]);
        }
    }

    fn diagonal(&self) -> f64 {
        self.blocks[0].0.diagonal()
    }

    fn precondition(&mut self, r: &[f64], z: &mut [f64]) -> bool {
        let mut all = true;
        for (op, range) in &mut self.blocks {
            all &= op.precondition(&r[range.clone()], &mut z[range.clone()]);
        }
        all
    }

    fn add_columns(&mut self, columns: &[(usize, f64)], out: &mut [f64]) -> bool {
        if self.column_limit() == 0 {
            return false;
        }
        let mut rest = columns;
        for (op, range) in &self.blocks {
            let here = rest.partition_point(|&(j, _)| j < range.end);
            op.kernels
                .add_normal_columns(&rest[..here], range.start, &mut out[range.clone()]);
            rest = &rest[here..];
        }
        true
    }

    /// The smallest block's limit: a column costs its block's elements, a
    /// product all blocks' products.
    fn column_limit(&self) -> usize {
        self.blocks
            .iter()
            .map(|(op, _)| op.column_limit())
            .min()
            .unwrap_or(0)
    }
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

    fn precondition(&mut self, r: &[f64], z: &mut [f64]) -> bool {
        self.kernels.apply_normal_inverse(self.ows, r, z)
    }

    fn add_columns(&mut self, columns: &[(usize, f64)], out: &mut [f64]) -> bool {
        self.kernels.add_normal_columns(columns, 0, out)
    }

    fn column_limit(&self) -> usize {
        self.kernels.normal_column_limit()
    }
}

/// Sub-patches of one grid whose pressures act on each other's elements
/// reduced: CONTACT's blended patch (`m_wr_locatecp.f90`,
/// `combine_cpatches`; its normal solver's planform IPLAN = 4), two regions
/// of contact that lie too close together to be separate patches and too
/// far apart to be one. The displacement of element I in sub-patch k of
/// the pressure of element J in sub-patch l is A_IJ f_kl, f_kk = 1; an
/// element in no sub-patch (label 0) takes every sub-patch's displacement
/// in full, and its pressure acts on nothing (the caller keeps it out of
/// contact). With f symmetric, the map stays symmetric, and positive
/// definite where f is (always for two sub-patches with f < 1).
#[derive(Debug, Clone, PartialEq)]
pub struct NormalBlend {
    /// Per element (index `iy * nx + ix`): its sub-patch 1..=n, or 0.
    labels: Vec<u16>,
    /// Number of sub-patches n.
    n: usize,
    /// f_kl, row-major n x n.
    factors: Vec<f64>,
}

impl NormalBlend {
    /// The blend of sub-patch `labels` (0 for none, else 1..=n) and the
    /// n x n factors f_kl `factors` (row-major): symmetric, 1 on the
    /// diagonal, in [0, 1] elsewhere; an error names what is not so.
    pub fn new(labels: Vec<u16>, factors: Vec<f64>) -> Result<Self, ContactError> {
        const KEY: &str = "normal_blend";
        let n = (factors.len() as f64).sqrt().round() as usize;
        if n * n != factors.len() || n == 0 || n > usize::from(u16::MAX) {
            return Err(ContactError::invalid(
                KEY,
                format!("needs n x n factors, n >= 1, got {} values", factors.len()),
            ));
        }
        for k in 0..n {
            for l in 0..n {
                let (f, g) = (factors[k * n + l], factors[l * n + k]);
                let fine = if k == l {
                    f == 1.0
                } else {
                    (0.0..=1.0).contains(&f) && f == g
                };
                if !fine {
                    return Err(ContactError::invalid(
                        KEY,
                        format!(
                            "factor ({}, {}) = {f}: needs 1 on the diagonal, symmetric values in \
                             [0, 1] elsewhere",
                            k + 1,
                            l + 1
                        ),
                    ));
                }
            }
        }
        if let Some(i) = labels.iter().position(|&l| usize::from(l) > n) {
            return Err(ContactError::invalid(
                KEY,
                format!("element {i}: sub-patch {} of {n}", labels[i]),
            ));
        }
        Ok(Self { labels, n, factors })
    }

    /// Per element: its sub-patch 1..=n, or 0.
    pub fn labels(&self) -> &[u16] {
        &self.labels
    }

    /// The number of sub-patches.
    pub fn len(&self) -> usize {
        self.n
    }

    /// Never true: a blend has at least one sub-patch.
    pub fn is_empty(&self) -> bool {
        self.n == 0
    }

    /// f_kl of sub-patches `k`, `l` (1-based).
    pub fn factor(&self, k: usize, l: usize) -> f64 {
        self.factors[(k - 1) * self.n + (l - 1)]
    }

    /// The same factors on other labels (the same grid in another frame).
    pub fn with_labels(&self, labels: Vec<u16>) -> Result<Self, ContactError> {
        Self::new(labels, self.factors.clone())
    }
}

impl HeapBytes for NormalBlend {
    fn heap_bytes(&self) -> usize {
        heap_bytes!(self.labels, self.factors)
    }
}

/// The planar operator of a [`NormalBlend`]: one product per sub-patch
/// that carries pressure (`part`, `product`: buffers of one value per
/// element). Preconditioned with the planar operator's inverse; no
/// columns.
pub struct BlendedNormal<'a> {
    /// The operator without the blend.
    pub planar: PlanarNormal<'a>,
    /// The sub-patches.
    pub blend: &'a NormalBlend,
    /// Buffers.
    pub part: &'a mut [f64],
    /// Buffers.
    pub product: &'a mut [f64],
}

impl NormalOperator for BlendedNormal<'_> {
    fn apply_normal(&mut self, p: &[f64], out: &mut [f64]) {
        let labels = &self.blend.labels;
        out.fill(0.0);
        for k in 1..=self.blend.n {
            let mut loaded = false;
            for ((q, &v), &l) in self.part.iter_mut().zip(p).zip(labels) {
                *q = if usize::from(l) == k { v } else { 0.0 };
                loaded |= *q != 0.0;
            }
            if !loaded {
                continue;
            }
            self.planar.apply_normal(self.part, self.product);
            for ((o, &u), &l) in out.iter_mut().zip(self.product.iter()).zip(labels) {
                let l = usize::from(l);
                let f = if l == 0 || l == k {
                    1.0
                } else {
                    self.blend.factor(k, l)
                };
                *o += f * u;
            }
        }
    }

    fn diagonal(&self) -> f64 {
        self.planar.diagonal()
    }

    fn precondition(&mut self, r: &[f64], z: &mut [f64]) -> bool {
        self.planar.precondition(r, z)
    }
}

/// Solves the normal problem on a planar patch. `h` is the undeformed
/// distance \[m\] per element; `pn` \[Pa\] is the initial guess on entry (zeros
/// allowed) and the solution on exit. `area` is the element area \[m²\]. No
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

multiversion! {
    /// The general normal solver: operator `op`, and per-element approach
    /// weights `w` (None: all 1). The gap is h - delta w + A p, and force
    /// control prescribes sum w p_n area = F: for a conformal patch w is
    /// cos(delta(s) - delta(0)), the approach is along the normal at the
    /// reference point and F the force along it (paper Eq. 1).
    ///
    /// Projected, preconditioned conjugate gradients: the free set is the
    /// contact set plus the overlapping elements outside it; the residual (the
    /// gap less its weighted fit, under force control) on the free set is
    /// preconditioned by [`NormalOperator::precondition`] when the operator
    /// has one (plain Polonsky–Keer CG otherwise), projected on the directions
    /// that keep the force, and combined with the previous direction while no
    /// element enters; the step is the exact minimiser along the direction,
    /// followed by the projection on p >= 0 and the force rescaling.
    ///
    /// With AVX2 and FMA when the CPU has them (`core::simd`).
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
    ) -> NormalOutcome => solve_normal_body
}

#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn solve_normal_body(
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
    let a_self = op.diagonal();
    let NormalScratch {
        u,
        t: d,
        r: q,
        g,
        p_old,
        z,
        free,
        ones,
        columns,
        kept,
        active: _,
    } = scratch;
    // Unit weights are exact: w x = x, w w = 1.
    let w: &[f64] = weights.unwrap_or(ones);
    debug_assert_eq!(w.len(), n);
    let mut matvecs = 0;
    let mut preconditioner_applications = 0;
    let force_control = matches!(load, NormalLoad::NormalForce(_));
    // u holds A p of the kept pressures when the start is those pressures.
    let same_start = kept.on && kept.valid && kept.p[..] == pn[..];
    let start_scale = initial_guess(h, &|i| w[i], area, load, a_self, pn);
    let delta_fixed = match load {
        NormalLoad::Approach(d) => d,
        NormalLoad::NormalForce(_) => 0.0,
    };
    let mut rz_old = 1.0;
    let mut conj = false;
    let mut approach = delta_fixed;
    let mut residual = f64::INFINITY;
    let mut iterations = 0;
    d.fill(0.0);
    // u = A p is carried along (u <- c (u - alpha A d)) while the step is a
    // plain CG step; after a projection that set a few elements' pressures
    // to zero, the product of those changes is added column by column
    // (NormalOperator::add_columns); it is recomputed after larger
    // projections, and every REFRESH iterations against drift.
    const REFRESH: usize = 25;
    let column_limit = op.column_limit().min(columns.capacity());
    let mut u_valid = false;
    let mut since_refresh = 0;
    if let (true, Some(c)) = (same_start, start_scale) {
        u.iter_mut().for_each(|v| *v *= c);
        u_valid = true;
        since_refresh = kept.age;
    }
    kept.valid = false;
    // Projection of v on the weights' orthogonal complement over the free
    // set (force control keeps sum w p fixed along such directions).
    let project = |v: &mut [f64], free: &[bool], wsum2: f64| {
        if force_control && wsum2 > 0.0 {
            let mut s = 0.0;
            for ((&v, &w), &f) in v.iter().zip(w).zip(free) {
                if f {
                    s += w * v;
                }
            }
            let c = s / wsum2;
            for ((v, &w), &f) in v.iter_mut().zip(w).zip(free) {
                if f {
                    *v -= c * w;
                }
            }
        }
    };
    for it in 0..settings.max_iterations {
        if cancel::requested() {
            break;
        }
        iterations = it + 1;
        if !u_valid || since_refresh >= REFRESH {
            op.apply_normal(pn, u);
            matvecs += 1;
            since_refresh = 0;
        }
        since_refresh += 1;
        // Force control: the approach is the weighted least-squares fit of
        // the gap over the contact set (its mean when all weights are 1).
        let (mut gsum, mut wsum2) = (0.0, 0.0);
        for ((g, (&u, &h)), (&p, &w)) in g.iter_mut().zip(u.iter().zip(h)).zip(pn.iter().zip(w)) {
            *g = u + h;
            if p > 0.0 {
                gsum += w * *g;
                wsum2 += w * w;
            }
        }
        if force_control {
            if wsum2 <= 0.0 {
                break;
            }
            approach = gsum / wsum2;
        }
        // Free set and its residual.
        let mut entering = false;
        let mut fsum2 = 0.0;
        for ((g, free), (&p, &w)) in g.iter_mut().zip(free.iter_mut()).zip(pn.iter().zip(w)) {
            *g -= approach * w;
            let f = p > 0.0 || *g < 0.0;
            entering |= f && p <= 0.0;
            *free = f;
            if f {
                fsum2 += w * w;
            } else {
                *g = 0.0;
            }
        }
        project(g, free, fsum2);
        if op.precondition(g, z) {
            preconditioner_applications += 1;
            for (z, &f) in z.iter_mut().zip(free.iter()) {
                if !f {
                    *z = 0.0;
                }
            }
            project(z, free, fsum2);
        } else {
            z.copy_from_slice(g);
        }
        let rz: f64 = g
            .iter()
            .zip(z.iter())
            .zip(free.iter())
            .filter(|(_, &f)| f)
            .map(|((&g, &z), _)| g * z)
            .sum();
        let beta = if conj && !entering && rz_old > 0.0 {
            rz / rz_old
        } else {
            0.0
        };
        rz_old = rz;
        for ((d, &z), &f) in d.iter_mut().zip(z.iter()).zip(free.iter()) {
            *d = if f { z + beta * *d } else { 0.0 };
        }
        if beta != 0.0 {
            project(d, free, fsum2);
        }
        op.apply_normal(d, q);
        matvecs += 1;
        let (mut num, mut den) = (0.0, 0.0);
        for (((&g, &d), &q), &f) in g.iter().zip(d.iter()).zip(q.iter()).zip(free.iter()) {
            if f {
                num += g * d;
                den += q * d;
            }
        }
        let alpha = if den > 0.0 { num / den } else { 0.0 };
        p_old.copy_from_slice(pn);
        // Clamped elements and their pressure changes beyond the step, while
        // there are at most column_limit of them.
        columns.clear();
        let mut clamped = false;
        let mut few = true;
        for (i, ((p, &p_old), (&d, &f))) in pn
            .iter_mut()
            .zip(p_old.iter())
            .zip(d.iter().zip(free.iter()))
            .enumerate()
        {
            if f {
                let v = p_old - alpha * d;
                if v > 0.0 {
                    *p = v;
                } else {
                    *p = 0.0;
                    if v < 0.0 {
                        clamped = true;
                        few &= columns.len() < column_limit;
                        if few {
                            columns.push((i, -v));
                        }
                    }
                }
            }
        }
        if alpha == 0.0 && entering {
            // No progress along d (degenerate): enter the overlapping
            // elements by their self-influence.
            for i in 0..n {
                if free[i] && p_old[i] <= 0.0 {
                    pn[i] = -g[i] / a_self;
                }
            }
            clamped = true;
            few = false;
        }
        conj = true;
        let mut scale = 1.0;
        if let NormalLoad::NormalForce(f) = load {
            let s: f64 = w.iter().zip(pn.iter()).map(|(&w, &p)| w * p).sum::<f64>() * area;
            if s > 0.0 {
                scale = f / s;
                pn.iter_mut().for_each(|p| *p *= scale);
            }
        }
        u_valid = !clamped;
        if u_valid {
            for (u, &q) in u.iter_mut().zip(q.iter()) {
                *u = scale * (*u - alpha * q);
            }
        } else if few {
            for (u, &q) in u.iter_mut().zip(q.iter()) {
                *u -= alpha * q;
            }
            u_valid = op.add_columns(columns, u);
            if u_valid {
                u.iter_mut().for_each(|u| *u *= scale);
            }
        }
        let mut change = 0.0;
        let mut total = 0.0;
        for (&p, &p_old) in pn.iter().zip(p_old.iter()) {
            change += (p - p_old).abs();
            total += p;
        }
        residual = if total > 0.0 {
            change / total
        } else {
            f64::INFINITY
        };
        if residual < settings.tolerance && !entering {
            break;
        }
    }
    // Final approach from the converged pressures.
    if force_control {
        if !u_valid {
            op.apply_normal(pn, u);
            matvecs += 1;
            u_valid = true;
            since_refresh = 0;
        }
        let (mut s, mut c) = (0.0, 0.0);
        for ((&p, &w), (&u, &h)) in pn.iter().zip(w).zip(u.iter().zip(h)) {
            if p > 0.0 {
                s += w * (u + h);
                c += w * w;
            }
        }
        if c > 0.0 {
            approach = s / c;
        }
    }
    if kept.on && u_valid {
        kept.p.copy_from_slice(pn);
        kept.valid = true;
        kept.age = since_refresh;
    }
    NormalOutcome {
        iterations,
        matvecs,
        preconditioner_applications,
        approach_m: approach,
        residual,
        converged: residual < settings.tolerance,
    }
}

/// The initial pressures: a given guess (rescaled to the force under force
/// control), or from zero a Hertz-like pressure. Returns the factor that
/// scaled a given guess, `None` for a new start.
fn initial_guess(
    h: &[f64],
    w: &impl Fn(usize) -> f64,
    area: f64,
    load: NormalLoad,
    a_self: f64,
    pn: &mut [f64],
) -> Option<f64> {
    let n = h.len();
    let sum: f64 = pn.iter().sum();
    // Negated so that a NaN sum counts as no start too.
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    let no_start = !(sum > 0.0);
    match load {
        NormalLoad::NormalForce(f) => {
            if no_start {
                hertz_like_guess(h, f, area, a_self, pn);
            }
            let ws: f64 = (0..n).map(|i| w(i) * pn[i]).sum();
            let s = f / (ws.max(f64::MIN_POSITIVE) * area);
            pn.iter_mut().for_each(|p| *p *= s);
            (!no_start).then_some(s)
        }
        NormalLoad::Approach(delta) => {
            if no_start {
                // Hertz-like in the overlap o = delta w - h: p = p0
                // sqrt(2 o/omax - 1), p0 = 2 omax / (c pi² a) (see
                // hertz_like_guess).
                let omax = (0..n).fold(0.0f64, |m, i| m.max(delta * w(i) - h[i]));
                let mut cnt = 0usize;
                for i in 0..n {
                    let r = 2.0 * (delta * w(i) - h[i]) / omax - 1.0;
                    pn[i] = if r > 0.0 { r.sqrt() } else { 0.0 };
                    cnt += usize::from(r > 0.0);
                }
                let a = (cnt as f64 * area / std::f64::consts::PI).sqrt();
                let c = a_self / (4.0 * area.sqrt() * 1f64.asinh());
                let p0 = 2.0 * omax / (c * std::f64::consts::PI.powi(2) * a.max(f64::MIN_POSITIVE));
                pn.iter_mut().for_each(|p| *p *= p0);
                None
            } else {
                Some(1.0)
            }
        }
    }
}

/// Largest misfit of the quadratic fitted at the gap's minimum over the
/// Hertz ellipse of [`hertz_start`], relative to Hertz's approach, for
/// which that start is taken.
const HERTZ_START_MISFIT: f64 = 0.05;

/// A cold start on a planar grid from Hertz's elliptic pressure: the
/// curvatures A, B and the vertex of `h` from its second differences at its
/// smallest element, Hertz's ellipse for them (`e_star_pa` = G / (1 - nu)
/// of the combined bodies) and `load` (the approach counted from the
/// fitted minimum), its pressure at the element centres. Taken when `h`
/// departs from that quadratic by at most `HERTZ_START_MISFIT` (5 %) of
/// Hertz's approach over the ellipse (a Hertzian gap such as the
/// `quadratic` geometry, a wheel/rail patch only where it is close to one);
/// else `pn` is left at zero and false returned, and
/// [`solve_normal_with`] starts from its Hertz-like pressure on the gap's
/// level sets, whose aspect differs from Hertz's ellipse (b/a 1.69 against
/// 2.0 for A/B = 2.84). As CONTACT does for its Hertzian geometries
/// (`m_sdis.f90`, `use_iestim_hertz`). No allocation.
///
/// [`crate::core::solve::ContactSolver`] takes it for cold solves under
/// force control only: under approach control it moved the cold central
/// differences of the validation test
/// `jacobian_in_partial_slip_matches_cold_finite_differences` (Mz per
/// approach 1.8e-5 off the warm Jacobian against its bound of 1e-5),
/// which was not looked into.
pub fn hertz_start(
    grid: &Grid,
    h: &[f64],
    load: NormalLoad,
    e_star_pa: f64,
    pn: &mut [f64],
) -> bool {
    let (nx, ny) = (grid.nx, grid.ny);
    if grid.is_line() || h.len() != nx * ny || pn.len() != h.len() {
        return false;
    }
    let Some((i0, &h0)) = h.iter().enumerate().min_by(|a, b| a.1.total_cmp(b.1)) else {
        return false;
    };
    let (ix, iy) = (i0 % nx, i0 / nx);
    if ix == 0 || iy == 0 || ix + 1 == nx || iy + 1 == ny {
        return false;
    }
    // Second differences and the parabolas' vertices.
    let fit = |lo: f64, hi: f64, d: f64| {
        let c = hi + lo - 2.0 * h0;
        (c / (2.0 * d * d), -0.5 * d * (hi - lo) / c)
    };
    let (a, sx) = fit(h[i0 - 1], h[i0 + 1], grid.dx_m);
    let (b, sy) = fit(h[i0 - nx], h[i0 + nx], grid.dy_m);
    let (x0, y0) = (grid.x_m(ix) + sx, grid.y_m(iy) + sy);
    let hmin = h0 - a * sx * sx - b * sy * sy;
    let hertz_load = match load {
        NormalLoad::NormalForce(f) => HertzLoad::NormalForce { normal_force_n: f },
        NormalLoad::Approach(d) => HertzLoad::Approach {
            approach_m: d - hmin,
        },
    };
    // Refused for curvatures or loads out of its range (not a start).
    let Ok(hz) = hertz(a, b, e_star_pa, hertz_load) else {
        return false;
    };
    let mut misfit: f64 = 0.0;
    let mut loaded = false;
    for jy in 0..ny {
        let y = grid.y_m(jy) - y0;
        for jx in 0..nx {
            let x = grid.x_m(jx) - x0;
            let i = grid.index(jx, jy);
            let p = hz.pressure_at(x, y);
            pn[i] = p;
            if p > 0.0 {
                loaded = true;
                misfit = misfit.max((h[i] - hmin - a * x * x - b * y * y).abs());
            }
        }
    }
    if loaded && misfit <= HERTZ_START_MISFIT * hz.approach_m {
        return true;
    }
    pn.fill(0.0);
    false
}

/// A Hertz-like start for force control: p = p0 sqrt(1 - (h - hmin)/t) on
/// {h - hmin < t}, the pressure of a paraboloid's Hertz contact (t is half
/// the approach), with t chosen so that Hertz's relation between force,
/// approach and contact radius holds for the area of that set. The
/// compliance c = (1 - nu)/(pi G) of u = c ∫ p/r dA is taken from the
/// self-influence of a square element of the same area; then, for a circle
/// of radius a, u(0) = c p0 pi² a / 2 = 2 t and F = 2/3 pi a² p0 =
/// 8 a t / (3 pi c), increasing in t (bisection).
fn hertz_like_guess(h: &[f64], force: f64, area: f64, a_self: f64, pn: &mut [f64]) {
    let hmin = h.iter().fold(f64::INFINITY, |a, &v| a.min(v));
    let hmax = h.iter().fold(f64::NEG_INFINITY, |a, &v| a.max(v));
    let c = a_self / (4.0 * area.sqrt() * 1f64.asinh());
    let force_of = |t: f64| {
        let cnt = h.iter().filter(|&&v| v - hmin < t).count();
        let a = (cnt as f64 * area / std::f64::consts::PI).sqrt();
        8.0 * a * t / (3.0 * std::f64::consts::PI * c)
    };
    let (mut lo, mut hi) = (0.0, (hmax - hmin).max(f64::MIN_POSITIVE));
    if force_of(hi) > force {
        for _ in 0..40 {
            let mid = 0.5 * (lo + hi);
            if force_of(mid) < force {
                lo = mid;
            } else {
                hi = mid;
            }
        }
    }
    let t = hi;
    let mut s = 0.0;
    for (p, &hv) in pn.iter_mut().zip(h) {
        let r = 1.0 - (hv - hmin) / t;
        *p = if r > 0.0 { r.sqrt() } else { 0.0 };
        s += *p;
    }
    if s <= 0.0 {
        // Degenerate gap: the element of smallest gap carries the load.
        let i = h.iter().position(|&v| v == hmin).unwrap_or(0);
        pn[i] = 1.0;
    }
}

/// Krylov vectors of the GMRES of [`solve_normal_active_set`] between
/// restarts.
pub const ACTIVE_SET_RESTART: usize = 30;

/// Active-set iterations of [`solve_normal_active_set`] after which each
/// iteration adds at most one element (the most penetrating), against
/// cycling.
const ACTIVE_SET_FREE_ADDS: usize = 20;

/// Buffers of [`solve_normal_active_set`], allocated at its first use.
#[derive(Clone)]
struct ActiveSetScratch {
    krylov: Krylov,
    /// Solutions of the two systems (gap, unit approach), a right-hand
    /// side, the displacements.
    x: Vec<f64>,
    y: Vec<f64>,
    b: Vec<f64>,
    u: Vec<f64>,
    /// The contact set.
    on: Vec<bool>,
    /// The set `y` solves the unit-approach system on, to the relative
    /// residual `y_residual` (infinite: not solved): the system depends on
    /// the operator and the set only.
    y_on: Vec<bool>,
    y_residual: f64,
    /// The last call's final pressures; `carried` while the calls belong
    /// to one solve ([`NormalScratch::begin_solve`]), so that a call
    /// starting from them continues it: its `x` and `y` start from the last
    /// call's, and `y` is not solved again on the same set.
    p_end: Vec<f64>,
    carried: bool,
}

/// The GMRES buffers of [`gmres_on`].
#[derive(Clone)]
struct Krylov {
    /// Basis, (restart + 1) vectors of n.
    basis: Vec<f64>,
    /// Hessenberg matrix, column-major (restart + 1) x restart.
    hess: Vec<f64>,
    /// Givens rotations and the rotated right-hand side.
    cs: Vec<f64>,
    sn: Vec<f64>,
    rhs: Vec<f64>,
    /// Work vectors.
    w: Vec<f64>,
    z: Vec<f64>,
}

impl ActiveSetScratch {
    fn new(n: usize) -> Self {
        let m = ACTIVE_SET_RESTART;
        Self {
            krylov: Krylov {
                basis: vec![0.0; (m + 1) * n],
                hess: vec![0.0; (m + 1) * m],
                cs: vec![0.0; m],
                sn: vec![0.0; m],
                rhs: vec![0.0; m + 1],
                w: vec![0.0; n],
                z: vec![0.0; n],
            },
            x: vec![0.0; n],
            y: vec![0.0; n],
            b: vec![0.0; n],
            u: vec![0.0; n],
            on: vec![false; n],
            y_on: vec![false; n],
            y_residual: f64::INFINITY,
            p_end: vec![0.0; n],
            carried: false,
        }
    }
}

impl HeapBytes for ActiveSetScratch {
    fn heap_bytes(&self) -> usize {
        let k = &self.krylov;
        heap_bytes!(
            k.basis, k.hess, k.cs, k.sn, k.rhs, k.w, k.z, self.x, self.y, self.b, self.u, self.on,
            self.y_on, self.p_end
        )
    }
}

/// Counts of one GMRES solve.
#[derive(Default)]
struct Counts {
    iterations: usize,
    matvecs: usize,
    preconditioner_applications: usize,
}

/// `out = M v` on the set `on` (zero elsewhere), M the operator's
/// preconditioner, the identity without one.
fn precondition_on(
    op: &mut dyn NormalOperator,
    on: &[bool],
    v: &[f64],
    out: &mut [f64],
    c: &mut Counts,
) {
    if op.precondition(v, out) {
        c.preconditioner_applications += 1;
    } else {
        out.copy_from_slice(v);
    }
    out.iter_mut().zip(on).for_each(|(o, &on)| {
        if !on {
            *o = 0.0;
        }
    });
}

/// `out = A v` on the set `on` (zero elsewhere).
fn apply_on(op: &mut dyn NormalOperator, on: &[bool], v: &[f64], out: &mut [f64], c: &mut Counts) {
    op.apply_normal(v, out);
    c.matvecs += 1;
    out.iter_mut().zip(on).for_each(|(o, &on)| {
        if !on {
            *o = 0.0;
        }
    });
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(a, b)| a * b).sum()
}

/// Solves A x = b on the set `on` (b and x zero elsewhere; x the start on
/// entry) by restarted GMRES, right-preconditioned by the operator's
/// preconditioner, to the relative residual `tol` or `max_iterations`
/// iterations. Returns the relative residual reached.
#[allow(clippy::too_many_arguments)]
fn gmres_on(
    op: &mut dyn NormalOperator,
    on: &[bool],
    b: &[f64],
    x: &mut [f64],
    s: &mut Krylov,
    tol: f64,
    max_iterations: usize,
    c: &mut Counts,
) -> f64 {
    let n = b.len();
    let m = ACTIVE_SET_RESTART;
    let b_norm = dot(b, b).sqrt();
    if b_norm == 0.0 {
        x.fill(0.0);
        return 0.0;
    }
    let Krylov {
        basis,
        hess,
        cs,
        sn,
        rhs,
        w,
        z,
    } = s;
    let mut done = 0;
    loop {
        // r = b - A x into the first basis vector.
        apply_on(op, on, x, w, c);
        let v0 = &mut basis[..n];
        for i in 0..n {
            v0[i] = b[i] - w[i];
        }
        let beta = dot(v0, v0).sqrt();
        if beta <= tol * b_norm || done >= max_iterations || cancel::requested() {
            return beta / b_norm;
        }
        v0.iter_mut().for_each(|v| *v /= beta);
        rhs.fill(0.0);
        rhs[0] = beta;
        let mut k_used = 0;
        for k in 0..m {
            let (head, tail) = basis.split_at_mut((k + 1) * n);
            precondition_on(op, on, &head[k * n..], z, c);
            let next = &mut tail[..n];
            apply_on(op, on, z, next, c);
            // Modified Gram-Schmidt.
            let col = &mut hess[k * (m + 1)..(k + 1) * (m + 1)];
            for j in 0..=k {
                let vj = &head[j * n..(j + 1) * n];
                let hj = dot(next, vj);
                col[j] = hj;
                next.iter_mut().zip(vj).for_each(|(v, &q)| *v -= hj * q);
            }
            let hk = dot(next, next).sqrt();
            col[k + 1] = hk;
            if hk > 0.0 {
                next.iter_mut().for_each(|v| *v /= hk);
            }
            // The previous rotations, then a new one zeroing col[k + 1].
            for j in 0..k {
                let (a, bb) = (col[j], col[j + 1]);
                col[j] = cs[j] * a + sn[j] * bb;
                col[j + 1] = -sn[j] * a + cs[j] * bb;
            }
            let r = col[k].hypot(col[k + 1]);
            (cs[k], sn[k]) = if r > 0.0 {
                (col[k] / r, col[k + 1] / r)
            } else {
                (1.0, 0.0)
            };
            col[k] = r;
            col[k + 1] = 0.0;
            rhs[k + 1] = -sn[k] * rhs[k];
            rhs[k] *= cs[k];
            c.iterations += 1;
            done += 1;
            k_used = k + 1;
            if rhs[k + 1].abs() <= tol * b_norm || hk == 0.0 || done >= max_iterations {
                break;
            }
        }
        // Back substitution H y = rhs (y into rhs), then x += M V y.
        for k in (0..k_used).rev() {
            let mut v = rhs[k];
            for j in k + 1..k_used {
                v -= hess[j * (m + 1) + k] * rhs[j];
            }
            rhs[k] = v / hess[k * (m + 1) + k];
        }
        w.fill(0.0);
        for k in 0..k_used {
            let vk = &basis[k * n..(k + 1) * n];
            w.iter_mut().zip(vk).for_each(|(w, &v)| *w += rhs[k] * v);
        }
        precondition_on(op, on, w, z, c);
        x.iter_mut().zip(z.iter()).for_each(|(x, &z)| *x += z);
    }
}

/// The normal problem for an operator that is not symmetric (viscoelastic
/// bodies in steady rolling, [`crate::core::viscoelastic`]), where the
/// conjugate gradients of [`solve_normal_with`] do not apply: Kalker's
/// active-set iteration (Kalker 1990, §5.3, NORM). Each iteration solves
/// the contact conditions g = h - delta + A p = 0 on the contact set by
/// GMRES (right-preconditioned like the conjugate gradients; under force
/// control a second solve for the approach, so that sum p area = F), then
/// drops the elements of negative pressure from the set and adds those
/// outside it that penetrate, until the set stays. The same arguments as
/// [`solve_normal`] (unit approach weights); the residual is GMRES's
/// relative residual, to a thousandth of `settings.tolerance`. A call that
/// starts from the last call's final pressures continues it (a solve's
/// normal/tangential alternation): the two systems start from the last
/// call's solutions, and the unit-approach system, which depends on the
/// operator and the set only, is not solved again on the same set;
/// [`NormalScratch::begin_solve`] ends that, so that each solve depends on
/// its own start only (a viscoelastic steady solve of 32 x 32 elements with
/// four alternations: 261 operator products instead of 318).
#[allow(clippy::too_many_arguments)]
pub fn solve_normal_active_set(
    op: &mut dyn NormalOperator,
    h: &[f64],
    area: f64,
    load: NormalLoad,
    pn: &mut [f64],
    scratch: &mut NormalScratch,
    settings: &NormalSettings,
) -> NormalOutcome {
    let n = h.len();
    let ActiveSetScratch {
        krylov,
        x,
        y,
        b,
        u,
        on,
        y_on,
        y_residual,
        p_end,
        carried,
    } = &mut **scratch
        .active
        .get_or_insert_with(|| Box::new(ActiveSetScratch::new(n)));
    let tol = (1e-3 * settings.tolerance).max(1e-14);
    // A call of the same solve from the last one's pressures continues it.
    let continued = *carried && p_end[..] == pn[..];
    initial_guess(h, &|_| 1.0, area, load, op.diagonal(), pn);
    for (on, &p) in on.iter_mut().zip(pn.iter()) {
        *on = p > 0.0;
    }
    // Warm starts of the two solves: the last call's solutions, or the
    // pressures (x) and nothing (y).
    if !continued {
        x.copy_from_slice(pn);
        y.fill(0.0);
        *y_residual = f64::INFINITY;
    }
    let mut c = Counts::default();
    // The approach in the gap's system: the prescribed one, or 0 (and
    // the force's approach from the second system).
    let (base, force) = match load {
        NormalLoad::Approach(d) => (d, None),
        NormalLoad::NormalForce(f) => (0.0, Some(f)),
    };
    let mut delta = base;
    let mut residual = f64::INFINITY;
    let mut settled = false;
    let mut outer = 0;
    while outer < settings.max_iterations && !cancel::requested() {
        outer += 1;
        for i in 0..n {
            b[i] = if on[i] { base - h[i] } else { 0.0 };
            if !on[i] {
                x[i] = 0.0;
                y[i] = 0.0;
            }
        }
        residual = gmres_on(op, on, b, x, krylov, tol, settings.max_iterations, &mut c);
        if let Some(f) = force {
            // The unit-approach system, unless solved on this set already.
            if !(*y_residual <= tol && y_on[..] == on[..]) {
                for i in 0..n {
                    b[i] = if on[i] { 1.0 } else { 0.0 };
                }
                let r = gmres_on(op, on, b, y, krylov, tol, settings.max_iterations, &mut c);
                residual = residual.max(r);
                y_on.copy_from_slice(on);
                *y_residual = r;
            }
            let (sx, sy): (f64, f64) = (x.iter().sum(), y.iter().sum());
            delta = (f / area - sx) / sy;
            for i in 0..n {
                pn[i] = x[i] + delta * y[i];
            }
        } else {
            pn.copy_from_slice(x);
        }
        // The gaps, and the changes of the set.
        op.apply_normal(pn, u);
        c.matvecs += 1;
        let (umax, pmax) = u
            .iter()
            .zip(pn.iter())
            .fold((0.0f64, 0.0f64), |(m, q), (&a, &p)| {
                (m.max(a.abs()), q.max(p))
            });
        let (gap_tol, p_tol) = (1e-9 * umax, 1e-9 * pmax);
        let mut changed = false;
        let mut deepest: Option<(usize, f64)> = None;
        for i in 0..n {
            if on[i] {
                if pn[i] < -p_tol {
                    on[i] = false;
                    changed = true;
                }
            } else {
                let g = h[i] - delta + u[i];
                if g < -gap_tol {
                    if outer <= ACTIVE_SET_FREE_ADDS {
                        on[i] = true;
                        changed = true;
                    } else if deepest.is_none_or(|(_, d)| g < d) {
                        deepest = Some((i, g));
                    }
                }
            }
        }
        if let Some((i, _)) = deepest {
            on[i] = true;
            changed = true;
        }
        for (p, &on) in pn.iter_mut().zip(on.iter()) {
            if !on || *p < 0.0 {
                *p = 0.0;
            }
        }
        if !changed {
            settled = true;
            break;
        }
    }
    p_end.copy_from_slice(pn);
    *carried = true;
    NormalOutcome {
        iterations: outer,
        matvecs: c.matvecs,
        preconditioner_applications: c.preconditioner_applications,
        approach_m: delta,
        residual,
        converged: settled && residual <= tol,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::fft::{dense_matrix, ConvolutionPlan};
    use crate::core::influence::{HalfSpaceInfluence, KernelKind};
    use crate::core::material::{CombinedMaterial, Material};
    use std::sync::Arc;

    /// The dense influence matrix as an operator, without a preconditioner.
    struct Dense(faer::Mat<f64>);

    impl NormalOperator for Dense {
        fn apply_normal(&mut self, p: &[f64], out: &mut [f64]) {
            let pv = faer::Col::<f64>::from_fn(p.len(), |i| p[i]);
            let u = &self.0 * &pv;
            for (o, i) in out.iter_mut().zip(0..) {
                *o = u[i];
            }
        }

        fn diagonal(&self) -> f64 {
            self.0[(0, 0)]
        }
    }

    /// An operator that cancels its thread's solve after `left` products.
    struct CancelAfter {
        inner: Dense,
        left: usize,
    }

    impl NormalOperator for CancelAfter {
        fn apply_normal(&mut self, p: &[f64], out: &mut [f64]) {
            self.left = self.left.saturating_sub(1);
            if self.left == 0 {
                crate::core::cancel::CancelToken::current()
                    .expect("a token")
                    .cancel();
            }
            self.inner.apply_normal(p, out)
        }

        fn diagonal(&self) -> f64 {
            self.inner.diagonal()
        }
    }

    #[test]
    fn a_cancelled_solve_stops_at_its_next_iteration() {
        let n = 16;
        let mat = CombinedMaterial::identical(Material::STEEL).unwrap();
        let dx = 1e-4;
        let set = KernelSet::new(
            Arc::new(ConvolutionPlan::new(n, n)),
            HalfSpaceInfluence::new(dx, dx, &mat),
            KernelKind::Displacement,
        );
        let h: Vec<f64> = (0..n * n)
            .map(|i| {
                let x = ((i % n) as f64 - 7.5) * dx;
                let y = ((i / n) as f64 - 7.5) * dx;
                0.5 * (x * x + y * y)
            })
            .collect();
        let run = |left: usize| {
            let mut op = CancelAfter {
                inner: Dense(dense_matrix(&set, &[Component::N])),
                left,
            };
            let mut p = vec![0.0; n * n];
            let token = crate::core::cancel::CancelToken::new();
            token.scope(|| {
                solve_normal_with(
                    &mut op,
                    &h,
                    None,
                    dx * dx,
                    NormalLoad::NormalForce(100.0),
                    &mut p,
                    &mut NormalScratch::new(n * n),
                    &NormalSettings::default(),
                )
            })
        };
        let whole = run(usize::MAX);
        assert!(whole.converged);
        assert!(whole.iterations > 3, "{} iterations", whole.iterations);
        // Cancelled at the second product: the iteration that made it ends,
        // the next one does not start.
        let cut = run(2);
        assert!(!cut.converged);
        assert!(cut.iterations <= 2, "{} iterations", cut.iterations);
    }

    /// The normal problem of a paraboloid h = x²/(2 rx) + y²/(2 ry) on an
    /// n x n grid of elements dx by dy (centred), force or approach control.
    fn check(n: usize, dx: f64, dy: f64, rx: f64, ry: f64, load: NormalLoad) {
        let mat = CombinedMaterial::identical(Material::STEEL).unwrap();
        let ic = HalfSpaceInfluence::new(dx, dy, &mat);
        let set = KernelSet::new(
            Arc::new(ConvolutionPlan::new(n, n)),
            ic,
            KernelKind::Displacement,
        );
        let h: Vec<f64> = (0..n * n)
            .map(|i| {
                let x = ((i % n) as f64 - 0.5 * (n - 1) as f64) * dx;
                let y = ((i / n) as f64 - 0.5 * (n - 1) as f64) * dy;
                x * x / (2.0 * rx) + y * y / (2.0 * ry)
            })
            .collect();
        // Compared to each other: both solved well below the default tolerance.
        let settings = NormalSettings {
            tolerance: 1e-10,
            ..NormalSettings::default()
        };
        let area = dx * dy;
        // FFT products with the preconditioner.
        let mut ows = set.workspace();
        let mut p_fft = vec![0.0; n * n];
        let fast = solve_normal(
            &set,
            &mut ows,
            &h,
            area,
            load,
            &mut p_fft,
            &mut NormalScratch::new(n * n),
            &settings,
        );
        // The portable copy of the solver and the products gives the same
        // bits as the AVX2 one (core::simd).
        crate::core::simd::force_baseline(true);
        let mut p_base = vec![0.0; n * n];
        solve_normal(
            &set,
            &mut ows,
            &h,
            area,
            load,
            &mut p_base,
            &mut NormalScratch::new(n * n),
            &settings,
        );
        crate::core::simd::force_baseline(false);
        assert!(p_base
            .iter()
            .zip(&p_fft)
            .all(|(a, b)| a.to_bits() == b.to_bits()));
        // Dense products, no preconditioner.
        let mut dense = Dense(dense_matrix(&set, &[Component::N]));
        let mut p_dense = vec![0.0; n * n];
        let plain = solve_normal_with(
            &mut dense,
            &h,
            None,
            area,
            load,
            &mut p_dense,
            &mut NormalScratch::new(n * n),
            &settings,
        );
        assert!(fast.converged && plain.converged, "{fast:?} {plain:?}");
        assert!(fast.preconditioner_applications > 0 && plain.preconditioner_applications == 0);
        let pmax = p_dense.iter().fold(0.0f64, |m, &v| m.max(v));
        let mut contact = 0;
        for i in 0..n * n {
            // The same contact set and pressures to the solver's tolerance.
            assert_eq!(p_fft[i] > 0.0, p_dense[i] > 0.0, "element {i}");
            assert!(
                (p_fft[i] - p_dense[i]).abs() <= 1e-8 * pmax,
                "element {i}: {} vs {}",
                p_fft[i],
                p_dense[i]
            );
            contact += usize::from(p_dense[i] > 0.0);
        }
        assert!(
            contact > n * n / 8 && contact < n * n / 2,
            "{contact} in contact"
        );
        let da = (fast.approach_m - plain.approach_m).abs();
        assert!(da <= 1e-9 * plain.approach_m.abs(), "approach {da:e}");
        // Fewer than half the iterations, and fewer products even with the
        // preconditioner's (about a quarter of a product each) counted in
        // full.
        let cost = fast.matvecs + fast.preconditioner_applications;
        assert!(
            2 * fast.iterations < plain.iterations && cost < plain.matvecs,
            "preconditioned {fast:?}, plain {plain:?}"
        );
        eprintln!(
            "{n}x{n} {:?}: preconditioned {} iterations, {} + {} products; plain {} iterations, {} products",
            load, fast.iterations, fast.matvecs, fast.preconditioner_applications, plain.iterations, plain.matvecs
        );
    }

    #[test]
    fn preconditioned_fft_solver_matches_the_plain_dense_one() {
        // Hertz circle, force control.
        check(32, 1e-4, 1e-4, 0.5, 0.5, NormalLoad::NormalForce(400.0));
        // Elongated elements and an elliptic patch, force control.
        check(
            32,
            2.5e-4,
            0.75e-4,
            0.3,
            0.05,
            NormalLoad::NormalForce(3000.0),
        );
        // Approach control.
        check(24, 1e-4, 1e-4, 0.5, 0.3, NormalLoad::Approach(2e-6));
    }

    /// Two patches that do not interact, solved as one block operator with
    /// one approach delta (weighted per patch) and one force, give what each
    /// patch gives alone at its approach w_k delta, and their weighted
    /// forces add up to the load.
    #[test]
    fn a_kept_product_saves_the_first_product_of_a_warm_solve() {
        let n = 32;
        let (dx, r) = (1e-4, 0.5);
        let mat = CombinedMaterial::identical(Material::STEEL).unwrap();
        let set = KernelSet::new(
            Arc::new(ConvolutionPlan::new(n, n)),
            HalfSpaceInfluence::new(dx, dx, &mat),
            KernelKind::Displacement,
        );
        let gap = |tilt: f64| -> Vec<f64> {
            (0..n * n)
                .map(|i| {
                    let x = ((i % n) as f64 - 0.5 * (n - 1) as f64) * dx;
                    let y = ((i / n) as f64 - 0.5 * (n - 1) as f64) * dx;
                    (x * x + y * y) / (2.0 * r) + tilt * x
                })
                .collect()
        };
        let settings = NormalSettings::default();
        let mut ows = set.workspace();
        let mut solve = |h: &[f64], f: f64, p: &mut [f64], scratch: &mut NormalScratch| {
            let load = NormalLoad::NormalForce(f);
            solve_normal(&set, &mut ows, h, dx * dx, load, p, scratch, &settings)
        };
        let mut kept = NormalScratch::new(n * n);
        kept.keep_product();
        let mut p0 = vec![0.0; n * n];
        solve(&gap(0.0), 400.0, &mut p0, &mut kept);
        // A warm solve from the kept pressures (another force, another gap)
        // against the same solve with a fresh scratch.
        let h = gap(1e-5);
        let mut p_kept = p0.clone();
        let a = solve(&h, 440.0, &mut p_kept, &mut kept);
        let mut p_fresh = p0.clone();
        let b = solve(&h, 440.0, &mut p_fresh, &mut NormalScratch::new(n * n));
        assert!(a.converged && b.converged);
        assert_eq!(a.matvecs + 1, b.matvecs, "{a:?} {b:?}");
        let pmax = p_fresh.iter().fold(0.0f64, |m, &v| m.max(v));
        let diff = p_kept
            .iter()
            .zip(&p_fresh)
            .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
        assert!(diff <= 1e-8 * pmax, "{diff:e} of {pmax:e}");
        assert!((a.approach_m - b.approach_m).abs() <= 1e-8 * b.approach_m.abs());
        // A start other than the kept pressures takes its own product.
        let mut p_other = p0.clone();
        p_other[n * n / 2] *= 1.01;
        let c = solve(&h, 440.0, &mut p_other, &mut kept);
        let mut p_other2 = p0.clone();
        p_other2[n * n / 2] *= 1.01;
        let d = solve(&h, 440.0, &mut p_other2, &mut NormalScratch::new(n * n));
        assert_eq!(c.matvecs, d.matvecs);
        assert!(p_other
            .iter()
            .zip(&p_other2)
            .all(|(x, y)| x.to_bits() == y.to_bits()));
    }

    #[test]
    fn block_operator_solves_patches_together() {
        let mat = CombinedMaterial::identical(Material::STEEL).unwrap();
        let (dx, dy) = (1e-4, 1.2e-4);
        let ic = HalfSpaceInfluence::new(dx, dy, &mat);
        // (nx, ny, rx, ry, offset of the gap [m], weight)
        let patches = [(28, 20, 0.4, 0.3, 0.0, 1.0), (20, 30, 0.5, 0.1, 1e-6, 0.8)];
        let sets: Vec<KernelSet> = patches
            .iter()
            .map(|&(nx, ny, ..)| {
                KernelSet::new(
                    Arc::new(ConvolutionPlan::new(nx, ny)),
                    ic,
                    KernelKind::Displacement,
                )
            })
            .collect();
        let mut buffers: Vec<OperatorWorkspace> = sets.iter().map(KernelSet::workspace).collect();
        let gap = |&(nx, ny, rx, ry, h0, _): &(usize, usize, f64, f64, f64, f64)| -> Vec<f64> {
            (0..nx * ny)
                .map(|i| {
                    let x = ((i % nx) as f64 - 0.5 * (nx - 1) as f64) * dx;
                    let y = ((i / nx) as f64 - 0.5 * (ny - 1) as f64) * dy;
                    h0 + x * x / (2.0 * rx) + y * y / (2.0 * ry)
                })
                .collect()
        };
        let h: Vec<f64> = patches.iter().flat_map(gap).collect();
        let w: Vec<f64> = patches
            .iter()
            .flat_map(|p| std::iter::repeat_n(p.5, p.0 * p.1))
            .collect();
        let mut op = BlockNormal::new(
            sets.iter()
                .zip(buffers.iter_mut())
                .map(|(kernels, ows)| PlanarNormal { kernels, ows })
                .collect(),
        )
        .unwrap();
        assert_eq!(op.len(), h.len());
        let (area, force) = (dx * dy, 2000.0);
        // Compared to each other: both solved well below the default tolerance.
        let settings = NormalSettings {
            tolerance: 1e-10,
            ..NormalSettings::default()
        };
        let mut pn = vec![0.0; h.len()];
        let both = solve_normal_with(
            &mut op,
            &h,
            Some(&w),
            area,
            NormalLoad::NormalForce(force),
            &mut pn,
            &mut NormalScratch::new(h.len()),
            &settings,
        );
        assert!(
            both.converged && both.preconditioner_applications > 0,
            "{both:?}"
        );
        let mut at = 0;
        let mut total = 0.0;
        for (p, set) in patches.iter().zip(&sets) {
            let n = p.0 * p.1;
            let mut alone = vec![0.0; n];
            let out = solve_normal(
                set,
                &mut set.workspace(),
                &gap(p),
                area,
                NormalLoad::Approach(both.approach_m * p.5),
                &mut alone,
                &mut NormalScratch::new(n),
                &settings,
            );
            assert!(out.converged);
            let pmax = alone.iter().fold(0.0f64, |m, &v| m.max(v));
            assert!(pmax > 0.0, "both patches carry load");
            for (a, b) in alone.iter().zip(&pn[at..at + n]) {
                assert!((a - b).abs() <= 1e-7 * pmax, "{a} vs {b}");
            }
            total += p.5 * alone.iter().sum::<f64>() * area;
            at += n;
        }
        assert!((total - force).abs() <= 1e-6 * force, "{total} vs {force}");
        // Different element sizes cannot share one approach solve.
        let other = KernelSet::new(
            Arc::new(ConvolutionPlan::new(8, 8)),
            HalfSpaceInfluence::new(2e-4, dy, &mat),
            KernelKind::Displacement,
        );
        let (mut w0, mut w1) = (sets[0].workspace(), other.workspace());
        let parts = vec![
            PlanarNormal {
                kernels: &sets[0],
                ows: &mut w0,
            },
            PlanarNormal {
                kernels: &other,
                ows: &mut w1,
            },
        ];
        assert!(BlockNormal::new(parts).is_none());
    }

    /// The operator of `blend` on `kernels` with `buffers`.
    fn blended<'a>(
        kernels: &'a KernelSet,
        ows: &'a mut OperatorWorkspace,
        blend: &'a NormalBlend,
        buffers: &'a mut [Vec<f64>; 2],
    ) -> BlendedNormal<'a> {
        let [part, product] = buffers;
        BlendedNormal {
            planar: PlanarNormal { kernels, ows },
            blend,
            part,
            product,
        }
    }

    /// A blend of two sub-patches (the grid's left and right halves, a
    /// paraboloid in each) at a fixed approach: with f = 0 each half's
    /// pressure is that of its half alone (the other out of contact,
    /// exactly the same problem); with f = 1 the plain operator's; in
    /// between the force lies between those two (less interaction, less
    /// displacement, more force at the same approach). The operator is
    /// symmetric for any f.
    #[test]
    fn a_blend_interpolates_between_separate_and_one_patch() {
        let mat = CombinedMaterial::identical(Material::STEEL).unwrap();
        let (nx, ny, d) = (40, 24, 1e-4);
        let n = nx * ny;
        let kernels = KernelSet::new(
            Arc::new(ConvolutionPlan::new(nx, ny)),
            HalfSpaceInfluence::new(d, d, &mat),
            KernelKind::Displacement,
        );
        let mut ows = kernels.workspace();
        let x = |i: usize| ((i % nx) as f64 - 0.5 * (nx - 1) as f64) * d;
        let y = |i: usize| ((i / nx) as f64 - 0.5 * (ny - 1) as f64) * d;
        let labels: Vec<u16> = (0..n)
            .map(|i| if i % nx < nx / 2 { 1 } else { 2 })
            .collect();
        // Bumps at x = -1 mm and +1 mm, the second 1 um higher.
        let h: Vec<f64> = (0..n)
            .map(|i| {
                let (xc, h0) = if labels[i] == 1 {
                    (-1e-3, 0.0)
                } else {
                    (1e-3, 1e-6)
                };
                h0 + (x(i) - xc).powi(2) / 0.6 + y(i).powi(2) / 0.4
            })
            .collect();
        let settings = NormalSettings {
            tolerance: 1e-10,
            ..NormalSettings::default()
        };
        let approach = NormalLoad::Approach(5e-6);
        let mut buffers = [vec![0.0; n], vec![0.0; n]];
        let mut solve_blended = |f: f64, pn: &mut [f64]| {
            let blend = NormalBlend::new(labels.clone(), vec![1.0, f, f, 1.0]).unwrap();
            let mut op = blended(&kernels, &mut ows, &blend, &mut buffers);
            let out = solve_normal_with(
                &mut op,
                &h,
                None,
                d * d,
                approach,
                pn,
                &mut NormalScratch::new(n),
                &settings,
            );
            assert!(out.converged, "{out:?}");
            pn.iter().sum::<f64>() * d * d
        };
        let mut separate = vec![0.0; n];
        let f0 = solve_blended(0.0, &mut separate);
        let mut half = vec![0.0; n];
        let f_half = solve_blended(0.5, &mut half);
        let mut one = vec![0.0; n];
        let f1 = solve_blended(1.0, &mut one);
        let pmax = one.iter().fold(0.0f64, |m, &v| m.max(v));
        // The plain operator's solution of gap `h`.
        let plain = |h: &[f64]| {
            let mut pn = vec![0.0; n];
            let out = solve_normal(
                &kernels,
                &mut kernels.workspace(),
                h,
                d * d,
                approach,
                &mut pn,
                &mut NormalScratch::new(n),
                &settings,
            );
            assert!(out.converged);
            pn
        };
        for (a, b) in one.iter().zip(&plain(&h)) {
            assert!((a - b).abs() <= 1e-7 * pmax, "f = 1: {a} vs {b}");
        }
        for k in [1u16, 2] {
            let h_alone: Vec<f64> = (0..n)
                .map(|i| if labels[i] == k { h[i] } else { 1.0 })
                .collect();
            let alone = plain(&h_alone);
            assert!(
                alone.iter().sum::<f64>() > 0.0,
                "sub-patch {k} carries load"
            );
            for i in (0..n).filter(|&i| labels[i] == k) {
                assert!(
                    (alone[i] - separate[i]).abs() <= 1e-7 * pmax,
                    "f = 0, element {i}: {} vs {}",
                    alone[i],
                    separate[i]
                );
            }
        }
        assert!(f0 > f_half && f_half > f1, "{f0} > {f_half} > {f1}");
        // Symmetric: q.(A p) = p.(A q).
        let blend = NormalBlend::new(labels.clone(), vec![1.0, 0.3, 0.3, 1.0]).unwrap();
        let mut op = blended(&kernels, &mut ows, &blend, &mut buffers);
        let p: Vec<f64> = (0..n).map(|i| ((i * 37 % 101) as f64).sin()).collect();
        let q: Vec<f64> = (0..n).map(|i| ((i * 53 % 89) as f64).cos()).collect();
        let (mut ap, mut aq) = (vec![0.0; n], vec![0.0; n]);
        op.apply_normal(&p, &mut ap);
        op.apply_normal(&q, &mut aq);
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(u, v)| u * v).sum::<f64>();
        let (qap, paq) = (dot(&q, &ap), dot(&p, &aq));
        assert!(
            (qap - paq).abs() <= 1e-12 * qap.abs().max(paq.abs()),
            "{qap} vs {paq}"
        );
    }

    /// A blend's factors must be symmetric with 1 on the diagonal and in
    /// [0, 1]; its labels at most the number of sub-patches.
    #[test]
    fn a_blend_refuses_factors_and_labels_it_cannot_use() {
        for (labels, factors, says) in [
            (vec![1, 2], vec![1.0, 0.5, 0.4, 1.0], "factor (1, 2) = 0.5"),
            (vec![1, 2], vec![0.9, 0.5, 0.5, 1.0], "factor (1, 1) = 0.9"),
            (vec![1, 2], vec![1.0, 1.5, 1.5, 1.0], "factor (1, 2) = 1.5"),
            (
                vec![1, 3],
                vec![1.0, 0.5, 0.5, 1.0],
                "element 1: sub-patch 3 of 2",
            ),
            (vec![1, 2], vec![1.0, 0.5, 0.5], "got 3 values"),
        ] {
            let e = NormalBlend::new(labels, factors).unwrap_err().to_string();
            assert!(e.contains("normal_blend") && e.contains(says), "{e}");
        }
        assert!(NormalBlend::new(vec![0, 1, 2], vec![1.0, 0.0, 0.0, 1.0]).is_ok());
    }

    /// On a Hertzian gap (an ellipse off the grid's centre) the start is
    /// Hertz's pressure; on a gap that is not (a quartic term as large as
    /// the quadratic over the patch) there is none and `pn` stays zero.
    #[test]
    fn the_hertz_start_is_taken_on_hertzian_gaps_only() {
        use crate::core::hertz::{hertz, HertzLoad};
        let grid = Grid::centered(48, 40, 0.016, 0.032).unwrap();
        let (a, b, x0, y0) = (0.8, 0.2814, 3.1e-4, -4.3e-4);
        let e_star = 82e9 / (1.0 - 0.28);
        let force = NormalLoad::NormalForce(106_700.0);
        let gap = |quartic: f64| -> Vec<f64> {
            let mut h = vec![0.0; grid.len()];
            for iy in 0..grid.ny {
                for ix in 0..grid.nx {
                    let (x, y) = (grid.x_m(ix) - x0, grid.y_m(iy) - y0);
                    h[grid.index(ix, iy)] = 2e-6 + a * x * x + b * y * y + quartic * y.powi(4);
                }
            }
            h
        };
        let hz = hertz(
            a,
            b,
            e_star,
            HertzLoad::NormalForce {
                normal_force_n: 106_700.0,
            },
        )
        .unwrap();
        let mut pn = vec![0.0; grid.len()];
        assert!(hertz_start(&grid, &gap(0.0), force, e_star, &mut pn));
        for iy in 0..grid.ny {
            for ix in 0..grid.nx {
                let want = hz.pressure_at(grid.x_m(ix) - x0, grid.y_m(iy) - y0);
                let got = pn[grid.index(ix, iy)];
                assert!(
                    (got - want).abs() < 1e-9 * hz.max_pressure_pa,
                    "{got} {want}"
                );
            }
        }
        // b y^2 = q y^4 at y = 5 mm, inside the patch (b = 6.3 mm).
        let q = b / 25e-6;
        assert!(!hertz_start(&grid, &gap(q), force, e_star, &mut pn));
        assert!(pn.iter().all(|&p| p == 0.0));
    }
}
