//! Steady rolling by a semismooth (active-set) Newton method with
//! right-preconditioned, restarted GMRES on FFT matvecs.
//!
//! The steady-state slip of body 1 relative to body 2 is s = w + B p with
//! B = A(I - S)/dx, Kalker's discretisation of -du/dx (S takes the value one
//! element upstream; see [`crate::core::influence::KernelKind::SteadyRolling`]).
//! B is not symmetric, so the problem is not a minimisation and projected
//! gradient methods do not apply; it is solved as the nonlinear system of
//! Coulomb's law instead.
//!
//! Each Newton step:
//!
//! 1. Classify every loaded element by the natural map z = p - s/d (d the
//!    diagonal of B): |z| <= g is adhesion, otherwise slip, and the slip
//!    element's traction is put on the bound in the direction n = z/|z|.
//! 2. Linearise Coulomb's law about that state, in reduced coordinates:
//!    an adhesion element has two unknowns (dp) and the equations s = 0; a
//!    slip element has one unknown, the traction's movement v along the
//!    circle (tangent t = n rotated by +90°), and the equation t·s = 0 (slip
//!    parallel to the traction). The Jacobian is P B P + E, with P the
//!    projection on the free directions and E = diag(max(-n·s, 0)/g) on the
//!    slip elements (the turning of t with the traction).
//! 3. Solve it inexactly by GMRES (restart [`RESTART`]), right-preconditioned
//!    by the exact inverse of the local upwind part of the operator,
//!    diag(B)(I - S), restricted to the free directions: one sweep from the
//!    leading edge along every grid line; before the sweep, by the inverse
//!    of the circulant extension of the
//!    displacement operator, which takes care of the low frequencies that
//!    the sweep leaves (see `Linear::precondition`: the products per
//!    Newton step then hardly grow with the grid). The Krylov vectors hold
//!    the loaded elements only; the forcing term follows Eisenstat and
//!    Walker, bounded by what the tolerance needs.
//!    Its products run in single precision
//!    ([`TangentialOperator::tangential_product`], about 1e-6 of the
//!    largest output): the forcing terms are 1e-4 or looser, and every
//!    Newton residual, which decides convergence, uses the `f64` product.
//! 4. Update: adhesion tractions by dp, slip tractions by a rotation v/g.
//!
//! The planar driver applies B through the displacement kernels,
//! A (I - S)/dx ([`PlanarSteady`]): real kernel spectra, cheaper than the
//! complex ones of the steady-rolling kernels.
//!
//! Near the solution the active set is fixed and the iteration is Newton's
//! method for a smooth system, so it converges fast; a step that increases
//! the residual is halved (at most [`MAX_HALVINGS`] times).

use crate::core::cancel;
use crate::core::creep::kalker_creep_coefficients;
use crate::core::fft::{KernelSet, OperatorWorkspace, Precision};
use crate::core::influence::{Component, KernelKind};
use crate::core::memory::{heap_bytes, HeapBytes};
use crate::core::simd::multiversion;
use crate::core::solution::ElementState;
use crate::core::tangential::{
    natural_residual, TangentialInput, TangentialOutcome, TangentialOutput, TangentialSettings,
};

/// GMRES restart length (Krylov vectors kept).
pub const RESTART: usize = 40;
/// The Krylov vectors the GMRES basis grows by beyond the one it needs
/// (a cycle that outgrows it copies the vectors before).
pub const BASIS_SPARE: usize = 8;
/// Largest number of step halvings per Newton step.
pub const MAX_HALVINGS: usize = 4;
/// Largest number of Newton steps (also bounded by the settings' iteration
/// limit); the caller falls back to time marching when they do not suffice.
pub const MAX_NEWTON_STEPS: usize = 50;
/// Curvature term of a slipping element whose friction bound is zero,
/// relative to its diagonal: large enough to keep its (zero) traction.
const ZERO_BOUND_STIFFNESS: f64 = 1e12;
/// The global part of the preconditioner (see `Linear::precondition`) is
/// left out of a Newton step whose elements' mean weight is below this: on
/// a mostly sliding patch (mean weight 0.13 at 20 times the bench case's
/// creepages) the local sweep does about as well alone, and the circulant
/// inverse costs a quarter of a product per GMRES iteration (32x32: 0.56
/// ms with it, 0.50 ms without).
pub const GLOBAL_MIN_SHARE: f64 = 0.25;
/// Tolerances from this one up are checked on single-precision products.
pub const SINGLE_RESIDUAL_TOLERANCE: f64 = 1e-4;
/// A Newton step recomputes the slips after projecting tractions on their
/// bounds only when the move is above this share of the linear residual its
/// forcing term allows (see [`solve_coulomb_newton`]).
pub const PROJECTION_SHARE: f64 = 0.5;
/// Largest number of FFT matvecs of one Newton solve.
pub const MAX_NEWTON_MATVECS: usize = 4000;

/// The tangential block of an influence operator, (p_x, p_y) -> (u_x, u_y)
/// with the normal pressure held fixed: what the Newton solver multiplies by.
pub trait TangentialOperator {
    /// `(ux, uy) = A_tt (px, py)` with transforms in `precision`
    /// ([`Precision::Single`]: within about 1e-6 of the largest output, for
    /// the products of the Krylov iterations, whose tolerances are looser).
    fn tangential_product(
        &mut self,
        precision: Precision,
        px: &[f64],
        py: &[f64],
        ux: &mut [f64],
        uy: &mut [f64],
    );
    /// `(ux, uy) = A_tt (px, py)` in `f64`.
    fn apply_tangential(&mut self, px: &[f64], py: &[f64], ux: &mut [f64], uy: &mut [f64]) {
        self.tangential_product(Precision::Double, px, py, ux, uy)
    }
    /// The product of the Newton steps' linear systems (the GMRES
    /// iterations): by default the [`Precision::Single`] product. An
    /// operator may give a cheaper approximation of its Jacobian here
    /// (inexact Newton): convergence is decided on residuals computed with
    /// [`TangentialOperator::apply_tangential`] alone, so the answer and
    /// its tolerance do not depend on it, only the number of steps.
    fn jacobian_product(&mut self, px: &[f64], py: &[f64], ux: &mut [f64], uy: &mut [f64]) {
        self.tangential_product(Precision::Single, px, py, ux, uy)
    }
    /// The self-influence coefficients (xx, yy) [m/Pa or 1/Pa].
    fn diagonal(&self) -> [f64; 2];
    /// `z = C⁻¹ r` on the full grid, C the circulant extension of the
    /// displacement operator's tangential block A_tt
    /// ([`KernelSet::apply_tangential_inverse`]): the global part of the
    /// Newton solver's preconditioner (see `Linear::precondition`), which
    /// scales it by the local model.
    fn circulant_inverse(&mut self, r: [&[f64]; 2], z: [&mut [f64]; 2]);
}

/// The tangential block of a planar kernel set.
pub struct PlanarTangential<'a> {
    /// Kernels (displacement or steady rolling).
    pub kernels: &'a KernelSet,
    /// Buffers.
    pub ows: &'a mut OperatorWorkspace,
}

impl TangentialOperator for PlanarTangential<'_> {
    fn circulant_inverse(&mut self, r: [&[f64]; 2], z: [&mut [f64]; 2]) {
        self.kernels.apply_tangential_inverse(self.ows, r, z);
    }

    fn tangential_product(
        &mut self,
        precision: Precision,
        px: &[f64],
        py: &[f64],
        ux: &mut [f64],
        uy: &mut [f64],
    ) {
        self.kernels.apply_with(
            precision,
            self.ows,
            &[(Component::X, px), (Component::Y, py)],
            &mut [(Component::X, ux), (Component::Y, uy)],
        );
    }

    fn diagonal(&self) -> [f64; 2] {
        [
            self.kernels.value(Component::X, Component::X, 0, 0),
            self.kernels.value(Component::Y, Component::Y, 0, 0),
        ]
    }
}

/// The local part of the operator that preconditions GMRES.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LocalModel {
    /// Steady rolling: diag(B)(I - S), S one element upstream.
    Upwind,
    /// Transient step: diag(A).
    Diagonal,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Role {
    Exterior,
    Adhesion,
    Slip,
}

/// Buffers of [`solve_steady_newton`], allocated once per grid.
#[derive(Clone)]
pub struct SteadyScratch {
    n: usize,
    role: Vec<Role>,
    g: Vec<f64>,
    tx: Vec<f64>,
    ty: Vec<f64>,
    ux: Vec<f64>,
    uy: Vec<f64>,
    sx: Vec<f64>,
    sy: Vec<f64>,
    px_old: Vec<f64>,
    py_old: Vec<f64>,
    rhs: Vec<f64>,
    sol: Vec<f64>,
    krylov: Krylov,
    /// Differenced tractions of [`PlanarSteady`].
    diff: [Vec<f64>; 2],
    /// The loaded elements (grid indices, in grid order) of the compressed
    /// vectors, their coefficients and the rows of the preconditioner's
    /// sweep in its order (see [`Linear`]).
    loaded: Vec<usize>,
    coef: Vec<Coef>,
    sweep: Vec<SweepRow>,
    /// Loaded elements per grid column (counting sort of `sweep`).
    column_count: Vec<usize>,
    /// Full-grid inputs of the products of compressed vectors.
    xin: Vec<f64>,
    yin: Vec<f64>,
}

/// GMRES work space.
#[derive(Clone)]
struct Krylov {
    /// The preconditioner's intermediate vector.
    tmp: Vec<f64>,
    work: Vec<f64>,
    zvec: Vec<f64>,
    /// The Krylov vectors of the current cycle, one compressed vector
    /// after the other: grown to what the solves have used (see
    /// [`basis_for`]), at most `RESTART + 1` vectors.
    basis: Vec<f64>,
    hess: Vec<f64>,
    cs: Vec<f64>,
    sn: Vec<f64>,
    gam: Vec<f64>,
}

/// Makes the GMRES `basis` hold at least `vectors` vectors of `len`,
/// keeping the ones it holds: grown by [`BASIS_SPARE`] vectors more (at
/// most `RESTART + 1`), so that a solver allocates it only while its cycles
/// get longer than before.
#[inline(always)]
fn basis_for(basis: &mut Vec<f64>, vectors: usize, len: usize) {
    let need = vectors * len;
    if basis.len() < need {
        let grown = ((vectors + BASIS_SPARE).min(RESTART + 1) * len).max(need);
        basis.reserve_exact(grown - basis.len());
        basis.resize(grown, 0.0);
    }
}

impl SteadyScratch {
    /// Buffers for `n` elements.
    pub fn new(n: usize) -> Self {
        let z = |m: usize| vec![0.0; m];
        Self {
            n,
            role: vec![Role::Exterior; n],
            g: z(n),
            tx: z(n),
            ty: z(n),
            ux: z(n),
            uy: z(n),
            sx: z(n),
            sy: z(n),
            px_old: z(n),
            py_old: z(n),
            rhs: z(2 * n),
            sol: z(2 * n),
            diff: [z(n), z(n)],
            loaded: Vec::with_capacity(n),
            coef: Vec::with_capacity(n),
            sweep: Vec::with_capacity(n),
            column_count: Vec::with_capacity(n + 1),
            xin: z(n),
            yin: z(n),
            krylov: Krylov {
                tmp: z(2 * n),
                work: z(2 * n),
                zvec: z(2 * n),
                basis: Vec::new(),
                hess: z((RESTART + 1) * RESTART),
                cs: z(RESTART + 1),
                sn: z(RESTART + 1),
                gam: z(RESTART + 1),
            },
        }
    }
}

/// About 310 bytes an element when new, and the GMRES basis: as many
/// compressed vectors (2 f64 a loaded element) as the longest GMRES cycle
/// so far has used plus [`BASIS_SPARE`], up to `RESTART + 1` (656 bytes an
/// element).
impl HeapBytes for SteadyScratch {
    fn heap_bytes(&self) -> usize {
        let k = &self.krylov;
        heap_bytes!(
            self.role,
            self.g,
            self.tx,
            self.ty,
            self.ux,
            self.uy,
            self.sx,
            self.sy,
            self.px_old,
            self.py_old,
            self.rhs,
            self.sol,
            self.diff,
            self.loaded,
            self.coef,
            self.sweep,
            self.column_count,
            self.xin,
            self.yin,
            k.tmp,
            k.work,
            k.zvec,
            k.basis,
            k.hess,
            k.cs,
            k.sn,
            k.gam
        )
    }
}

/// No upwind neighbour in [`Coef::up`].
const NONE: usize = usize::MAX;

/// The linearised problem of one Newton step (borrowed views of the
/// scratch), on compressed vectors: the loaded elements only, in grid
/// order, element k at `loaded[k]` with its values at k and m + k (m the
/// number of loaded elements): (dp_x, dp_y) for an adhesion element, (v, 0)
/// for a slip element, v its traction's movement along t (the norm of the
/// full vector (v t_x, v t_y)).
struct Linear<'a> {
    loaded: &'a [usize],
    /// By compressed element.
    coef: &'a [Coef],
    /// The compressed elements' rows of the preconditioner's sweep, in its
    /// order.
    sweep: &'a [SweepRow],
    /// The scale (x, y) of the preconditioner's global part before the
    /// sweep (see [`Linear::precondition`]), None without it.
    global: Option<[f64; 2]>,
}

/// The coefficients of one compressed element k of [`Linear`], written so
/// that adhesion and slip elements take the same branch-free arithmetic.
/// The sweep's own are in [`SweepRow`], in the sweep's order, so that
/// each pass over the elements reads only what it uses, in the order it
/// goes.
#[derive(Clone, Copy, Default)]
struct Coef {
    /// Full-grid tractions from the compressed values (a, b) = (x[k],
    /// x[m + k]): (f0 a + f1 b, f2 a + f3 b); (1, 0, 0, 1) for adhesion,
    /// (t_x, 0, t_y, 0) for slip. The rows of the product take the
    /// transpose: (f0 u_x + f2 u_y, f1 u_x + f3 u_y).
    full: [f64; 4],
    /// E, the turning of a slip element's direction (0 for adhesion).
    e: f64,
    /// The weight of the global part of the preconditioner in this
    /// element's row (see [`Linear::precondition`]): 1 for adhesion.
    global: f64,
}

/// One compressed element's row of the preconditioner's sweep
/// ([`Linear::sweep`]).
#[derive(Clone, Copy, Default)]
struct SweepRow {
    /// The element's compressed index.
    k: usize,
    /// Compressed index of the upwind neighbour (ix + 1) when loaded and
    /// the local model is upwind, else [`NONE`].
    up: usize,
    /// The local inverse: z0 = s0 (r0 + s1 a_x + s2 a_y), z1 = s3 (r1 + s4
    /// a_x + s5 a_y), with (a_x, a_y) the full tractions of the upwind
    /// neighbour. Adhesion: (1/d_x, d_x, 0, 1/d_y, 0, d_y); slip: (1/(d_x
    /// t_x² + d_y t_y² + e), d_x t_x, d_y t_y, 0, 0, 0).
    s: [f64; 6],
}

impl Linear<'_> {
    /// Length of a compressed vector.
    fn len(&self) -> usize {
        2 * self.loaded.len()
    }

    /// The full-grid tractions of compressed element k of `x`.
    #[inline(always)]
    fn full(&self, x: &[f64], k: usize) -> (f64, f64) {
        let m = self.loaded.len();
        let f = &self.coef[k].full;
        let (a, b) = (x[k], x[m + k]);
        (f[0] * a + f[1] * b, f[2] * a + f[3] * b)
    }

    /// y = (P B P + E) x. One FFT matvec; `xin` are full-grid buffers, zero
    /// outside the loaded elements.
    #[inline(always)]
    fn apply(
        &self,
        op: &mut dyn TangentialOperator,
        x: &[f64],
        y: &mut [f64],
        [xin, yin]: [&mut [f64]; 2],
        [ux, uy]: [&mut [f64]; 2],
    ) {
        let m = self.loaded.len();
        for (k, &i) in self.loaded.iter().enumerate() {
            (xin[i], yin[i]) = self.full(x, k);
        }
        op.jacobian_product(xin, yin, ux, uy);
        let (y0, y1) = y.split_at_mut(m);
        for ((((&i, c), y0), y1), &x0) in self
            .loaded
            .iter()
            .zip(self.coef)
            .zip(y0)
            .zip(&mut y1[..m])
            .zip(&x[..m])
        {
            let (f, u0, u1) = (&c.full, ux[i], uy[i]);
            *y0 = f[0] * u0 + f[2] * u1 + c.e * x0;
            *y1 = f[1] * u0 + f[3] * u1;
        }
    }

    /// z = M⁻¹ r, the preconditioner, without a product of the operator.
    ///
    /// Without the global part, M = P diag(B)(I - S) P + E, the local
    /// upwind model (or P diag(A) P + E, the diagonal one, for a transient
    /// step), inverted exactly by [`Linear::sweep`]. That leaves to GMRES
    /// the operator after it, B M⁻¹, which on an adhesion area is
    /// A/(dx diag(B)) (A/diag(A) for a transient step): the conditioning of
    /// the displacement operator, which grows with the grid (its low
    /// frequencies have the large eigenvalues), so that GMRES needed twice
    /// the products per Newton step at 128x128 as at 32x32. With the global
    /// part, `r` first goes through W ≈ (B M⁻¹)⁻¹ = dx diag(B) A⁻¹
    /// (diag(A) A⁻¹), with A⁻¹ the inverse of the circulant extension of A
    /// ([`TangentialOperator::circulant_inverse`], a quarter of a product in
    /// single precision), projected on the free directions P, as Vollebregt's FFT
    /// preconditioner of the normal problem (J. Comput. Phys. 257 (2014)
    /// 333–351) but on the tangential block: z = M⁻¹ (w P W P r + (1 - w) r)
    /// element by element. A slip element's row is the operator's plus E,
    /// which keeps its low frequencies bounded where E is large next to the
    /// element's diagonal d_t = t·diag(B) t; there W would overshoot, so
    /// its weight is w = (d_t/(d_t + e))^(3/4) (1 on adhesion). The
    /// exponent was chosen on the steady bench case (creepages 5e-4, 3e-4,
    /// spin 0.3/m): 1/2 and 1 took 10–20 % more products at 128x128.
    #[inline(always)]
    fn precondition(
        &self,
        op: &mut dyn TangentialOperator,
        r: &[f64],
        tmp: &mut [f64],
        z: &mut [f64],
        [xin, yin]: [&mut [f64]; 2],
        [ux, uy]: [&mut [f64]; 2],
    ) {
        let Some([s0, s1]) = self.global else {
            self.sweep(r, z);
            return;
        };
        let m = self.loaded.len();
        for (k, &i) in self.loaded.iter().enumerate() {
            (xin[i], yin[i]) = self.full(r, k);
        }
        op.circulant_inverse([xin, yin], [ux, uy]);
        let (t0, t1) = tmp[..2 * m].split_at_mut(m);
        for (((((&i, c), a), b), &r0), &r1) in self
            .loaded
            .iter()
            .zip(self.coef)
            .zip(t0)
            .zip(t1)
            .zip(&r[..m])
            .zip(&r[m..2 * m])
        {
            let (f, u0, u1, w) = (&c.full, ux[i] * s0, uy[i] * s1, c.global);
            *a = w * (f[0] * u0 + f[2] * u1) + (1.0 - w) * r0;
            *b = w * (f[1] * u0 + f[3] * u1) + (1.0 - w) * r1;
        }
        self.sweep(&tmp[..2 * m], z);
    }

    /// z = M⁻¹ r with M = P diag(B)(I - S) P + E: exact forward substitution
    /// from the leading edge (large x) along every grid line. The sweep
    /// goes column by column ([`Linear::sweep`]'s rows), so that the
    /// elements in flight are on different lines and independent (along a
    /// line, each waits for its upwind neighbour). No matvec.
    #[inline(always)]
    fn sweep(&self, r: &[f64], z: &mut [f64]) {
        let m = self.loaded.len();
        for row in self.sweep {
            let (ax, ay) = if row.up != NONE {
                self.full(z, row.up)
            } else {
                (0.0, 0.0)
            };
            let (s, k) = (&row.s, row.k);
            z[k] = s[0] * (r[k] + s[1] * ax + s[2] * ay);
            z[m + k] = s[3] * (r[m + k] + s[4] * ax + s[5] * ay);
        }
    }
}

/// |(a, b)| without the care of `f64::hypot` against overflow (tractions
/// and slips are far from it), which costs several times as much.
#[inline(always)]
fn norm(a: f64, b: f64) -> f64 {
    (a * a + b * b).sqrt()
}

/// Dot product with eight independent partial sums (vectorised; a single
/// running sum is bound by the latency of the addition).
#[inline(always)]
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut acc = [0.0; 8];
    let (ac, bc) = (a.chunks_exact(8), b.chunks_exact(8));
    let tail: f64 = ac
        .remainder()
        .iter()
        .zip(bc.remainder())
        .map(|(x, y)| x * y)
        .sum();
    for (x, y) in ac.zip(bc) {
        for k in 0..8 {
            acc[k] += x[k] * y[k];
        }
    }
    acc.iter().sum::<f64>() + tail
}

multiversion! {
    /// Right-preconditioned restarted GMRES for `lin` x = rhs, from x = 0,
    /// to a residual `rel_tol`·|rhs| or `max_matvecs` products. Returns the
    /// matvecs used. With AVX2 and FMA when the CPU has them
    /// (`core::simd`).
    #[allow(clippy::too_many_arguments)]
    fn gmres(
        lin: &Linear<'_>,
        op: &mut dyn TangentialOperator,
        rhs: &[f64],
        x: &mut [f64],
        sc: &mut Krylov,
        bufs: [&mut [f64]; 4],
        rel_tol: f64,
        max_matvecs: usize,
    ) -> usize => gmres_body
}

#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn gmres_body(
    lin: &Linear<'_>,
    op: &mut dyn TangentialOperator,
    rhs: &[f64],
    x: &mut [f64],
    sc: &mut Krylov,
    [ux, uy, xin, yin]: [&mut [f64]; 4],
    rel_tol: f64,
    max_matvecs: usize,
) -> usize {
    let m2 = lin.len();
    let (rhs, x) = (&rhs[..m2], &mut x[..m2]);
    let (work, zvec) = (&mut sc.work[..m2], &mut sc.zvec[..m2]);
    x.fill(0.0);
    let beta0 = dot(rhs, rhs).sqrt();
    if beta0 == 0.0 {
        return 0;
    }
    let target = rel_tol * beta0;
    let mut matvecs = 0;
    // Residual of the current x (x = 0 at the first cycle).
    work.copy_from_slice(rhs);
    let mut beta = beta0;
    loop {
        basis_for(&mut sc.basis, 1, m2);
        let v0 = &mut sc.basis[..m2];
        for (v, r) in v0.iter_mut().zip(work.iter()) {
            *v = r / beta;
        }
        sc.gam.fill(0.0);
        sc.gam[0] = beta;
        let mut used = 0;
        let mut estimate = beta;
        for j in 0..RESTART {
            // w = A M⁻¹ v_j
            basis_for(&mut sc.basis, j + 2, m2);
            let (head, tail) = sc.basis.split_at_mut((j + 1) * m2);
            let w = &mut tail[..m2];
            lin.precondition(
                op,
                &head[j * m2..(j + 1) * m2],
                w,
                zvec,
                [xin, yin],
                [ux, uy],
            );
            lin.apply(op, zvec, w, [xin, yin], [ux, uy]);
            matvecs += 1;
            // Modified Gram–Schmidt.
            for i in 0..=j {
                let vi = &head[i * m2..(i + 1) * m2];
                let h = dot(w, vi);
                sc.hess[i * RESTART + j] = h;
                for (a, b) in w.iter_mut().zip(vi) {
                    *a -= h * b;
                }
            }
            let hn = dot(w, w).sqrt();
            sc.hess[(j + 1) * RESTART + j] = hn;
            if hn > 0.0 {
                for a in w.iter_mut() {
                    *a /= hn;
                }
            }
            // Previous Givens rotations on column j, then a new one.
            for i in 0..j {
                let (a, b) = (sc.hess[i * RESTART + j], sc.hess[(i + 1) * RESTART + j]);
                sc.hess[i * RESTART + j] = sc.cs[i] * a + sc.sn[i] * b;
                sc.hess[(i + 1) * RESTART + j] = -sc.sn[i] * a + sc.cs[i] * b;
            }
            let (a, b) = (sc.hess[j * RESTART + j], sc.hess[(j + 1) * RESTART + j]);
            let r = a.hypot(b);
            let (c, s) = if r > 0.0 { (a / r, b / r) } else { (1.0, 0.0) };
            sc.cs[j] = c;
            sc.sn[j] = s;
            sc.hess[j * RESTART + j] = r;
            sc.hess[(j + 1) * RESTART + j] = 0.0;
            sc.gam[j + 1] = -s * sc.gam[j];
            sc.gam[j] *= c;
            used = j + 1;
            estimate = sc.gam[j + 1].abs();
            if estimate <= target || matvecs >= max_matvecs || hn == 0.0 {
                break;
            }
        }
        // Back substitution H y = gam (y stored in gam).
        for i in (0..used).rev() {
            let mut acc = sc.gam[i];
            for l in i + 1..used {
                acc -= sc.hess[i * RESTART + l] * sc.gam[l];
            }
            let h = sc.hess[i * RESTART + i];
            sc.gam[i] = if h != 0.0 { acc / h } else { 0.0 };
        }
        // x += M⁻¹ (V y)
        work.fill(0.0);
        for i in 0..used {
            let yi = sc.gam[i];
            for (a, b) in work.iter_mut().zip(&sc.basis[i * m2..(i + 1) * m2]) {
                *a += yi * b;
            }
        }
        lin.precondition(op, work, &mut sc.tmp, zvec, [xin, yin], [ux, uy]);
        for (a, b) in x.iter_mut().zip(zvec.iter()) {
            *a += b;
        }
        if matvecs >= max_matvecs || estimate <= target {
            return matvecs;
        }
        // True residual for the restart.
        lin.apply(op, x, work, [xin, yin], [ux, uy]);
        matvecs += 1;
        for (w, r) in work.iter_mut().zip(rhs) {
            *w = r - *w;
        }
        beta = dot(work, work).sqrt();
        if beta <= target || matvecs >= max_matvecs {
            return matvecs;
        }
    }
}

/// A cold start: Kalker's simplified theory (FASTSIM) on the grid, with the
/// flexibilities L_i = 8a/(3 C_ii G) of the ellipse that has the contact
/// area's length and width (spin uses the lateral one: only a start). Each
/// grid line is integrated from the leading edge, p(x) = P_g(p(x + dx) - dx w / L).
fn fastsim_guess(
    [g_mod, nu]: [f64; 2],
    input: &TangentialInput<'_>,
    px: &mut [f64],
    py: &mut [f64],
) {
    let grid = input.grid;
    let (nx, ny) = (grid.nx, grid.ny);
    let pn = input.pn;
    let Some([length, width]) = grid.loaded_extent_m(pn) else {
        return;
    };
    let (a, b) = (0.5 * length, 0.5 * width);
    let c = kalker_creep_coefficients((a / b).clamp(0.05, 20.0), nu)
        .map(|c| [c.c11, c.c22])
        .unwrap_or([4.12, 3.67]);
    let l1 = 8.0 * a / (3.0 * c[0] * g_mod);
    let l2 = 8.0 * a / (3.0 * c[1] * g_mod);
    let (mus, muk) = (
        input.friction.static_coefficient,
        input.friction.kinetic_coefficient,
    );
    let dx = grid.dx_m;
    for iy in 0..ny {
        let (mut ux, mut uy) = (0.0, 0.0);
        for ix in (0..nx).rev() {
            let i = iy * nx + ix;
            if pn[i] <= 0.0 {
                ux = 0.0;
                uy = 0.0;
                continue;
            }
            let (wx, wy) = (input.cx[i], input.cy[i]);
            ux -= dx * wx / l1;
            uy -= dx * wy / l2;
            let g = pn[i] * mus.min(muk);
            let m = norm(ux, uy);
            if m > g {
                ux *= g / m;
                uy *= g / m;
            }
            px[i] = ux;
            py[i] = uy;
        }
    }
}

/// The steady operator B = A_tt (I - S)/dx through the displacement
/// kernels: the upwind difference of the tractions, then the displacement
/// product, whose kernel spectra are real (a third of the arithmetic of
/// the complex spectra of [`KernelKind::SteadyRolling`] in the spectral
/// products). Equal to the steady kernels' product when the tractions
/// vanish on the trailing column ix = 0, which S drops (the driver requires
/// the loaded elements to stay off the grid border).
pub struct PlanarSteady<'a> {
    /// Displacement kernels.
    pub kernels: &'a KernelSet,
    /// Buffers.
    pub ows: &'a mut OperatorWorkspace,
    /// The differenced tractions.
    pub diff: [&'a mut [f64]; 2],
}

impl TangentialOperator for PlanarSteady<'_> {
    /// `(ux, uy) = A (I - S)/dx (px, py)`.
    fn tangential_product(
        &mut self,
        precision: Precision,
        px: &[f64],
        py: &[f64],
        ux: &mut [f64],
        uy: &mut [f64],
    ) {
        let nx = self.kernels.plan.nx;
        let inv_dx = 1.0 / self.kernels.influence.dx_m();
        let [dxv, dyv] = &mut self.diff;
        for (p, d) in [(px, &mut **dxv), (py, &mut **dyv)] {
            for (s, t) in p.chunks_exact(nx).zip(d.chunks_exact_mut(nx)) {
                for ix in 0..nx - 1 {
                    t[ix] = (s[ix] - s[ix + 1]) * inv_dx;
                }
                t[nx - 1] = s[nx - 1] * inv_dx;
            }
        }
        self.kernels.apply_with(
            precision,
            self.ows,
            &[(Component::X, dxv), (Component::Y, dyv)],
            &mut [(Component::X, ux), (Component::Y, uy)],
        );
    }

    fn diagonal(&self) -> [f64; 2] {
        self.kernels.steady_diagonal()
    }

    fn circulant_inverse(&mut self, r: [&[f64]; 2], z: [&mut [f64]; 2]) {
        self.kernels.apply_tangential_inverse(self.ows, r, z);
    }
}

/// Steady rolling: `k` is the [`KernelKind::Displacement`] kernel set (the
/// operator is then [`PlanarSteady`]) or the [`KernelKind::SteadyRolling`]
/// one; `cx`, `cy` in `input` hold the rigid slip w (plus any normal
/// coupling) [-]. `out.px`, `out.py` are the initial guess (warm start) on
/// entry.
pub fn solve_steady_newton(
    k: &KernelSet,
    ows: &mut OperatorWorkspace,
    input: &TangentialInput<'_>,
    out: TangentialOutput<'_>,
    scratch: &mut SteadyScratch,
    settings: &TangentialSettings,
) -> TangentialOutcome {
    let material = [k.influence.shear_modulus_pa(), k.influence.poisson_ratio()];
    let run = |op: &mut dyn TangentialOperator, scratch: &mut SteadyScratch| {
        solve_coulomb_newton(
            op,
            LocalModel::Upwind,
            Some(material),
            input,
            out,
            scratch,
            settings,
        )
    };
    match k.kind {
        KernelKind::SteadyRolling => run(&mut PlanarTangential { kernels: k, ows }, scratch),
        KernelKind::Displacement => {
            // Moved out and back: the operator and the solver both borrow
            // the scratch.
            let [mut a, mut b] = std::mem::take(&mut scratch.diff);
            let outcome = run(
                &mut PlanarSteady {
                    kernels: k,
                    ows,
                    diff: [&mut a, &mut b],
                },
                scratch,
            );
            scratch.diff = [a, b];
            outcome
        }
    }
}

/// The Newton solver for any tangential operator: steady rolling
/// ([`LocalModel::Upwind`], `op` the steady operator B, slips per unit
/// rolling speed) or one transient step ([`LocalModel::Diagonal`], `op` the
/// displacement operator A, slips as displacements per step). `cx`, `cy` in
/// `input` hold everything of the slip that does not depend on p_t.
/// Each element's bound is fixed for the solve: the kinetic coefficient on
/// `input`'s kinetic set (`previous_state`, see [`crate::core::tangential`]),
/// the static one elsewhere. `fastsim_material` = [G, nu] enables the
/// FASTSIM cold start of steady rolling.
pub fn solve_coulomb_newton(
    op: &mut dyn TangentialOperator,
    local: LocalModel,
    fastsim_material: Option<[f64; 2]>,
    input: &TangentialInput<'_>,
    out: TangentialOutput<'_>,
    scratch: &mut SteadyScratch,
    settings: &TangentialSettings,
) -> TangentialOutcome {
    let grid = input.grid;
    let (nx, ny) = (grid.nx, grid.ny);
    let n = nx * ny;
    debug_assert_eq!(scratch.n, n);
    let TangentialOutput {
        px,
        py,
        sx: sx_out,
        sy: sy_out,
        state,
    } = out;
    let SteadyScratch {
        role,
        g,
        tx,
        ty,
        ux,
        uy,
        sx,
        sy,
        px_old,
        py_old,
        rhs,
        sol,
        krylov,
        loaded,
        coef,
        sweep,
        column_count,
        xin,
        yin,
        ..
    } = scratch;
    let d = op.diagonal();
    // The global preconditioner's scale: W = dx diag(B) C⁻¹ after the
    // upwind model, diag(A) C⁻¹ after the diagonal one.
    let global = settings.global_preconditioner.then(|| match local {
        LocalModel::Upwind => d.map(|v| v * grid.dx_m),
        LocalModel::Diagonal => d,
    });
    let dbar = 0.5 * (d[0] + d[1]);
    let (mus, muk) = (
        input.friction.static_coefficient,
        input.friction.kinetic_coefficient,
    );
    let pn = input.pn;
    let gmax = pn.iter().fold(0.0f64, |a, &v| a.max(v)) * mus.max(muk);
    // Start: the warm start, zero outside the contact area, within the bound.
    for i in 0..n {
        role[i] = if pn[i] > 0.0 {
            Role::Adhesion
        } else {
            Role::Exterior
        };
        if pn[i] <= 0.0 {
            px[i] = 0.0;
            py[i] = 0.0;
        }
    }
    if let (LocalModel::Upwind, Some(m)) = (local, fastsim_material) {
        if px.iter().chain(py.iter()).all(|&v| v == 0.0) {
            fastsim_guess(m, input, px, py);
        }
    }
    // The bounds, fixed for the whole solve: the kinetic coefficient on the
    // kinetic set (see `core::tangential`), the static one elsewhere. (Bounds
    // that followed the iterate's own states, e.g. kinetic behind an
    // element sorted into slip, would flip elements between the two from
    // one Newton step to the next.)
    for i in 0..n {
        let kinetic = input.previous_state[i] == ElementState::Slip;
        g[i] = if pn[i] > 0.0 {
            pn[i] * if kinetic { muk } else { mus }
        } else {
            0.0
        };
    }
    for i in 0..n {
        let m = norm(px[i], py[i]);
        if m > g[i] {
            let c = if m > 0.0 { g[i] / m } else { 0.0 };
            px[i] *= c;
            py[i] *= c;
        }
    }
    // A loose tolerance (the conformal alternation's early inner solves)
    // takes its residuals from single-precision products, whose error,
    // about 1e-6 of the largest slip, is a hundredth of it.
    let residual_precision = if settings.tolerance >= SINGLE_RESIDUAL_TOLERANCE {
        Precision::Single
    } else {
        Precision::Double
    };
    let slip = |op: &mut dyn TangentialOperator,
                px: &[f64],
                py: &[f64],
                sx: &mut [f64],
                sy: &mut [f64]| {
        op.tangential_product(residual_precision, px, py, sx, sy);
        for i in 0..n {
            sx[i] += input.cx[i];
            sy[i] += input.cy[i];
        }
    };
    // (max, root-sum-square) of the natural residual, relative to max g.
    let residual_of = |px: &[f64], py: &[f64], sx: &[f64], sy: &[f64], g: &[f64]| -> (f64, f64) {
        let mut r: f64 = 0.0;
        let mut r2 = 0.0;
        for i in 0..n {
            if pn[i] > 0.0 {
                let e = natural_residual([px[i], py[i]], [sx[i], sy[i]], dbar, g[i]);
                r = r.max(e);
                r2 += e * e;
            }
        }
        if gmax > 0.0 {
            (r / gmax, r2.sqrt() / gmax)
        } else {
            (0.0, 0.0)
        }
    };
    // The scale of the natural map that sorts elements into adhesion and
    // slip, z = p - s / d_class. Every positive scale has the same fixed
    // point (Coulomb's law); the scale decides how a step far from it is
    // sorted. In steady rolling the upwind model's d = dbar fits. In a
    // transient step the slip is a displacement difference, and a traction
    // error spread over the patch moves it about (patch width / element
    // size) times more than the same error at one element: with
    // d_class = dbar, a cold shift on a fine grid sorts every element into
    // slip after every step and Newton cycles until the FISTA fallback
    // takes over (CONTACT's perfc wheel at 287 x 323 elements: 106 steps
    // and 329 products; at 575 x 647: 709 steps, 2,325 products, 150 s).
    // Scaled by the patch width in elements, sqrt(loaded elements), the
    // same shifts take 8, 10, 12 and 13 Newton steps from 71 x 81 to
    // 575 x 647 (41, 50, 67, 72 products); the counts hardly change for
    // any factor from 30 to 1000 on those grids (benches/README.md).
    let d_class = match local {
        LocalModel::Upwind => dbar,
        LocalModel::Diagonal => {
            let loaded_count = pn.iter().filter(|&&v| v > 0.0).count();
            dbar * (loaded_count as f64).sqrt().max(1.0)
        }
    };
    let mut matvecs = 0;
    slip(op, px, py, sx, sy);
    matvecs += 1;
    let (mut residual, mut merit) = residual_of(px, py, sx, sy, g);
    let mut iterations = 0;
    let mut eta_prev = 0.5;
    let mut merit_prev = merit;
    let max_newton = settings.max_iterations.clamp(1, MAX_NEWTON_STEPS);
    let matvec_budget = MAX_NEWTON_MATVECS;
    while residual > settings.tolerance
        && iterations < max_newton
        && matvecs < matvec_budget
        && !cancel::requested()
    {
        iterations += 1;
        // Forcing term: Eisenstat and Walker's choice 2 (SIAM J. Sci.
        // Comput. 17 (1996) 16–32), eta = 0.9 (merit / previous merit)²
        // with their safeguard, loose while the active set settles and
        // superlinear after; at most the merit itself (eta_k <= |F_k|:
        // quadratic local convergence, Dembo, Eisenstat and Steihaug, SIAM
        // J. Numer. Anal. 19 (1982) 400–408), without which a start close
        // to the solution (a warm start) keeps eta near 0.5 and crawls one
        // product per step; but no tighter than the tolerance needs: the
        // step's linear residual, eta times the root-sum-square one, bounds
        // its largest element.
        let mut eta = if iterations == 1 {
            0.5
        } else {
            0.9 * (merit / merit_prev).powi(2)
        };
        if 0.9 * eta_prev * eta_prev > 0.1 {
            eta = eta.max(0.9 * eta_prev * eta_prev);
        }
        let eta = eta
            .min(merit)
            .max(0.7 * settings.tolerance / merit)
            .clamp(1e-4, 0.5);
        eta_prev = eta;
        merit_prev = merit;
        // 1. Active set and slip directions from the natural map. A slip
        // element already on its bound keeps its traction (its direction is
        // a Newton unknown); others are projected on the bound along z.
        let mut moved = 0.0;
        for i in 0..n {
            if pn[i] <= 0.0 {
                role[i] = Role::Exterior;
                continue;
            }
            let z = [px[i] - sx[i] / d_class, py[i] - sy[i] / d_class];
            let zn = norm(z[0], z[1]);
            role[i] = if zn <= g[i] || zn == 0.0 {
                Role::Adhesion
            } else {
                Role::Slip
            };
        }
        for i in 0..n {
            if role[i] != Role::Slip {
                continue;
            }
            let m = norm(px[i], py[i]);
            let (n0, n1) = if m > 0.0 && (m - g[i]).abs() <= 1e-12 * g[i] {
                (px[i] / m, py[i] / m)
            } else {
                let z = [px[i] - sx[i] / d_class, py[i] - sy[i] / d_class];
                let zn = norm(z[0], z[1]);
                let (a, b) = (g[i] * z[0] / zn - px[i], g[i] * z[1] / zn - py[i]);
                moved += a * a + b * b;
                (z[0] / zn, z[1] / zn)
            };
            px[i] = g[i] * n0;
            py[i] = g[i] * n1;
            tx[i] = -n1;
            ty[i] = n0;
        }
        // The slips after the projection: a product, unless, in steady
        // rolling, the projection moved the tractions so little that the
        // slips' change (about dbar times the move: the steady kernel
        // decays as 1/r², so the diagonal dominates) is at most half the
        // linear residual the forcing term allows (eta times the merit, as
        // a traction): then the step starts from the slips before it, and
        // the residual after the step is exact again. On the steady bench
        // case this saves the product in the settling steps of a cold
        // start at 128x128 (66 -> 63 products) and in the first steps of
        // warm starts (50 -> 43 after a 1.9 % creepage change). A share of
        // 1, or skipping always, cost Newton steps on cold starts; 0.1 and
        // 0.3 saved less. Not in transient steps: the displacement kernel
        // decays as 1/r, its off-diagonal sum outweighs the diagonal, and
        // transient_2_steps at 64x64 took 6.4 -> 9.9 ms with the skip.
        let estimable =
            local == LocalModel::Upwind && moved.sqrt() <= PROJECTION_SHARE * eta * merit * gmax;
        if moved > 0.0 && !estimable {
            slip(op, px, py, sx, sy);
            matvecs += 1;
        }
        // 2. Linearised system on the loaded elements.
        loaded.clear();
        loaded.extend((0..n).filter(|&i| role[i] != Role::Exterior));
        let m = loaded.len();
        // The sweep's order: by grid column from the leading edge (a
        // counting sort on the column's rank r = nx - 1 - ix; start[r] is
        // where column r begins in `sweep`, then where its next goes).
        let rank = |i: usize| nx - 1 - i % nx;
        let start = &mut *column_count;
        start.clear();
        start.resize(nx + 1, 0);
        for &i in loaded.iter() {
            start[rank(i) + 1] += 1;
        }
        for r in 1..=nx {
            start[r] += start[r - 1];
        }
        sweep.clear();
        sweep.resize(m, SweepRow::default());
        for (k, &i) in loaded.iter().enumerate() {
            let slot = &mut start[rank(i)];
            sweep[*slot].k = k;
            *slot += 1;
        }
        coef.clear();
        coef.resize(m, Coef::default());
        for row in sweep.iter_mut() {
            let k = row.k;
            let i = loaded[k];
            row.up = if local == LocalModel::Upwind
                && k + 1 < m
                && loaded[k + 1] == i + 1
                && (i + 1) % nx != 0
            {
                k + 1
            } else {
                NONE
            };
            (coef[k], row.s) = match role[i] {
                Role::Slip => {
                    let (t0, t1) = (tx[i], ty[i]);
                    // n = (t1, -t0): e = max(-n·s, 0)/g.
                    let ns = t1 * sx[i] - t0 * sy[i];
                    let dt = d[0] * t0 * t0 + d[1] * t1 * t1;
                    // A bound of zero (kinetic coefficient 0 behind a
                    // slipping element) holds the traction at zero: the
                    // limit g -> 0 of the curvature term, a stiffness that
                    // leaves the element's unknown at 0.
                    let e = if g[i] > 0.0 {
                        (-ns).max(0.0) / g[i]
                    } else {
                        ZERO_BOUND_STIFFNESS * dt
                    };
                    rhs[k] = -(t0 * sx[i] + t1 * sy[i]);
                    rhs[m + k] = 0.0;
                    let coef = Coef {
                        full: [t0, 0.0, t1, 0.0],
                        e,
                        global: {
                            // (d_t/(d_t + e))^(3/4) without powf.
                            let r = (dt / (dt + e)).sqrt();
                            r * r.sqrt()
                        },
                    };
                    let s = [1.0 / (dt + e), d[0] * t0, d[1] * t1, 0.0, 0.0, 0.0];
                    (coef, s)
                }
                _ => {
                    rhs[k] = -sx[i];
                    rhs[m + k] = -sy[i];
                    let coef = Coef {
                        full: [1.0, 0.0, 0.0, 1.0],
                        e: 0.0,
                        global: 1.0,
                    };
                    (coef, [1.0 / d[0], d[0], 0.0, 1.0 / d[1], 0.0, d[1]])
                }
            };
        }
        xin.fill(0.0);
        yin.fill(0.0);
        // The global part's mean weight: small on a mostly sliding patch.
        let share = coef.iter().map(|c| c.global).sum::<f64>() / m.max(1) as f64;
        let lin = Linear {
            loaded,
            coef,
            sweep,
            global: global.filter(|_| share >= GLOBAL_MIN_SHARE),
        };
        matvecs += gmres(
            &lin,
            op,
            rhs,
            sol,
            krylov,
            [ux, uy, xin, yin],
            eta,
            matvec_budget.saturating_sub(matvecs).max(1),
        );
        // 3. Update with step halving on a residual increase.
        px_old.copy_from_slice(px);
        py_old.copy_from_slice(py);
        let mut lambda = 1.0;
        for halving in 0..=MAX_HALVINGS {
            for (k, &i) in loaded.iter().enumerate() {
                match role[i] {
                    Role::Slip => {
                        let (t0, t1) = (tx[i], ty[i]);
                        let ang = if g[i] > 0.0 {
                            (lambda * sol[k] / g[i]).clamp(-1.0, 1.0)
                        } else {
                            0.0
                        };
                        let (sa, ca) = ang.sin_cos();
                        // n = (t1, -t0)
                        let (n0, n1) = (t1, -t0);
                        px[i] = g[i] * (n0 * ca + t0 * sa);
                        py[i] = g[i] * (n1 * ca + t1 * sa);
                    }
                    _ => {
                        px[i] = px_old[i] + lambda * sol[k];
                        py[i] = py_old[i] + lambda * sol[m + k];
                        let a = norm(px[i], py[i]);
                        if a > g[i] {
                            px[i] *= g[i] / a;
                            py[i] *= g[i] / a;
                        }
                    }
                }
            }
            slip(op, px, py, sx, sy);
            matvecs += 1;
            let (r, mr) = residual_of(px, py, sx, sy, g);
            if mr < merit || halving == MAX_HALVINGS {
                merit = mr;
                residual = r;
                break;
            }
            lambda *= 0.5;
        }
    }
    // States and slips of the answer.
    for iy in 0..ny {
        for ix in (0..nx).rev() {
            let i = iy * nx + ix;
            if pn[i] <= 0.0 {
                state[i] = ElementState::Exterior;
                px[i] = 0.0;
                py[i] = 0.0;
                sx_out[i] = 0.0;
                sy_out[i] = 0.0;
                continue;
            }
            let z = [px[i] - sx[i] / dbar, py[i] - sy[i] / dbar];
            if norm(z[0], z[1]) > g[i] {
                state[i] = ElementState::Slip;
                sx_out[i] = sx[i];
                sy_out[i] = sy[i];
            } else {
                state[i] = ElementState::Adhesion;
                sx_out[i] = 0.0;
                sy_out[i] = 0.0;
            }
        }
    }
    TangentialOutcome {
        iterations,
        matvecs,
        residual,
        converged: residual <= settings.tolerance,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::fft::ConvolutionPlan;
    use crate::core::grid::Grid;
    use crate::core::influence::HalfSpaceInfluence;
    use crate::core::material::{CombinedMaterial, Material};
    use crate::core::tangential::{
        solve_steady_marching, FrictionBounds, MarchingScratch, TangentialScratch,
    };
    use std::sync::Arc;

    struct Case {
        grid: Grid,
        pn: Vec<f64>,
        cx: Vec<f64>,
        cy: Vec<f64>,
        steady: KernelSet,
        displacement: KernelSet,
    }

    /// Elliptic Hertz pressure (a = 4 mm, b = 3 mm, p0 = 1 GPa) on a grid
    /// 1.25 times the patch, with rigid slip from creepages and spin.
    fn case(n: usize, xi: f64, eta: f64, phi: f64) -> Case {
        let (a, b, p0) = (4e-3, 3e-3, 1e9);
        let grid = Grid::centered(n, n, 2.5 * a, 2.5 * b).unwrap();
        let mut pn = vec![0.0; grid.len()];
        let mut cx = vec![0.0; grid.len()];
        let mut cy = vec![0.0; grid.len()];
        for iy in 0..n {
            for ix in 0..n {
                let (x, y) = (grid.x_m(ix), grid.y_m(iy));
                let i = grid.index(ix, iy);
                let r = 1.0 - (x / a).powi(2) - (y / b).powi(2);
                pn[i] = if r > 0.0 { p0 * r.sqrt() } else { 0.0 };
                cx[i] = xi - phi * y;
                cy[i] = eta + phi * x;
            }
        }
        let mat = CombinedMaterial::identical(Material {
            shear_modulus_pa: 80e9,
            poisson_ratio: 0.28,
        })
        .unwrap();
        let plan = Arc::new(ConvolutionPlan::new(n, n));
        let inf = HalfSpaceInfluence::new(grid.dx_m, grid.dy_m, &mat);
        Case {
            grid,
            pn,
            cx,
            cy,
            steady: KernelSet::new(plan.clone(), inf, KernelKind::SteadyRolling),
            displacement: KernelSet::new(plan, inf, KernelKind::Displacement),
        }
    }

    impl Case {
        /// The tangential input with Coulomb friction `mu`.
        fn input<'a>(&'a self, mu: f64, prev: &'a [ElementState]) -> TangentialInput<'a> {
            TangentialInput {
                grid: &self.grid,
                pn: &self.pn,
                friction: FrictionBounds {
                    static_coefficient: mu,
                    kinetic_coefficient: mu,
                },
                cx: &self.cx,
                cy: &self.cy,
                previous_state: prev,
            }
        }
    }

    struct Answer {
        px: Vec<f64>,
        py: Vec<f64>,
        sx: Vec<f64>,
        sy: Vec<f64>,
        state: Vec<ElementState>,
        outcome: TangentialOutcome,
    }

    fn run(c: &Case, mu: f64, newton: bool) -> Answer {
        run_with(c, mu, newton.then_some(&c.steady), true)
    }

    /// Newton with the kernel set `newton` (and the global preconditioner
    /// when `global` and the set has it), or time marching when None.
    fn run_with(c: &Case, mu: f64, newton: Option<&KernelSet>, global: bool) -> Answer {
        let prev = vec![ElementState::Exterior; c.grid.len()];
        run_input(c, &c.input(mu, &prev), newton, global)
    }

    /// [`run_with`] of any input on `c`'s grid.
    fn run_input(
        c: &Case,
        input: &TangentialInput<'_>,
        newton: Option<&KernelSet>,
        global: bool,
    ) -> Answer {
        let n = c.grid.len();
        let mut a = Answer {
            px: vec![0.0; n],
            py: vec![0.0; n],
            sx: vec![0.0; n],
            sy: vec![0.0; n],
            state: vec![ElementState::Exterior; n],
            outcome: TangentialOutcome {
                iterations: 0,
                matvecs: 0,
                residual: 0.0,
                converged: false,
            },
        };
        let out = TangentialOutput {
            px: &mut a.px,
            py: &mut a.py,
            sx: &mut a.sx,
            sy: &mut a.sy,
            state: &mut a.state,
        };
        let settings = TangentialSettings {
            tolerance: 1e-9,
            max_iterations: 2000,
            global_preconditioner: global,
        };
        a.outcome = if let Some(k) = newton {
            let mut ows = k.workspace();
            let mut sc = SteadyScratch::new(n);
            solve_steady_newton(k, &mut ows, input, out, &mut sc, &settings)
        } else {
            let mut ows = c.displacement.workspace();
            solve_steady_marching(
                &c.displacement,
                &mut ows,
                input,
                out,
                &mut TangentialScratch::new(n),
                &mut MarchingScratch::new(n),
                &settings,
            )
        };
        a
    }

    /// Coulomb's law checked element by element on the returned fields:
    /// |p| <= mu p_n; slip elements on the bound with the traction opposite
    /// to the slip.
    fn check_coulomb(c: &Case, a: &Answer, mu: f64) -> (usize, usize) {
        check_coulomb_bounds(c, a, |_| mu)
    }

    /// [`check_coulomb`] with the coefficient `mu(i)` of each element.
    fn check_coulomb_bounds(c: &Case, a: &Answer, mu: impl Fn(usize) -> f64) -> (usize, usize) {
        let (mut nadh, mut nslip) = (0, 0);
        for i in 0..c.grid.len() {
            let g = mu(i) * c.pn[i];
            let m = a.px[i].hypot(a.py[i]);
            assert!(
                m <= g * (1.0 + 1e-12) + 1e-300,
                "element {i}: |p| {m} > g {g}"
            );
            match a.state[i] {
                ElementState::Slip => {
                    nslip += 1;
                    let s = a.sx[i].hypot(a.sy[i]);
                    assert!((m - g).abs() <= 1e-9 * g, "slip element {i} off the bound");
                    let cos = (a.px[i] * a.sx[i] + a.py[i] * a.sy[i]) / (m * s);
                    assert!(
                        cos < -1.0 + 1e-6,
                        "element {i}: traction not opposite slip ({cos})"
                    );
                }
                ElementState::Adhesion => nadh += 1,
                ElementState::Exterior => assert_eq!(c.pn[i], 0.0),
            }
        }
        (nadh, nslip)
    }

    #[test]
    fn newton_agrees_with_time_marching_in_partial_slip_with_spin() {
        // Two independent methods for the same discrete problem: the
        // Newton/GMRES solution and the limit of transient rolling.
        let mu = 0.3;
        let c = case(24, 4e-4, 3e-4, 0.5);
        let newton = run(&c, mu, true);
        let march = run(&c, mu, false);
        assert!(newton.outcome.converged, "{:?}", newton.outcome);
        assert!(march.outcome.converged, "{:?}", march.outcome);
        let (nadh, nslip) = check_coulomb(&c, &newton, mu);
        assert!(
            nadh > 20 && nslip > 20,
            "not a mixed patch: {nadh} adhesion, {nslip} slip"
        );
        let fmax = c.pn.iter().fold(0.0f64, |m, &v| m.max(v)) * mu;
        for i in 0..c.grid.len() {
            let d = (newton.px[i] - march.px[i]).hypot(newton.py[i] - march.py[i]);
            assert!(d <= 1e-6 * fmax, "element {i} differs by {d}");
        }
        // Far fewer products than marching.
        assert!(newton.outcome.matvecs * 10 < march.outcome.matvecs);
    }

    #[test]
    fn newton_and_time_marching_bound_the_kinetic_set_by_the_kinetic_coefficient() {
        // Static 0.35 and kinetic 0.1 with the kinetic set fixed (the
        // elements behind the patch's centre line x < 0, where slip
        // starts): both solvers solve Coulomb's problem with those bounds,
        // and agree; the slip elements sit on their own element's bound.
        let (mus, muk) = (0.35, 0.1);
        let c = case(24, 4e-4, 3e-4, 0.5);
        let n = c.grid.len();
        let kinetic: Vec<ElementState> = (0..n)
            .map(|i| match c.grid.x_m(i % c.grid.nx) < 0.0 {
                true => ElementState::Slip,
                false => ElementState::Exterior,
            })
            .collect();
        let input = TangentialInput {
            friction: FrictionBounds {
                static_coefficient: mus,
                kinetic_coefficient: muk,
            },
            ..c.input(mus, &kinetic)
        };
        let mu = |i: usize| match kinetic[i] {
            ElementState::Slip => muk,
            _ => mus,
        };
        let newton = run_input(&c, &input, Some(&c.displacement), true);
        let march = run_input(&c, &input, None, true);
        assert!(newton.outcome.converged, "{:?}", newton.outcome);
        assert!(march.outcome.converged, "{:?}", march.outcome);
        let (nadh, nslip) = check_coulomb_bounds(&c, &newton, mu);
        assert!(nadh > 20 && nslip > 20, "{nadh} adhesion, {nslip} slip");
        // Slip on both sides of the line: both bounds are met.
        let slip_at = |kin: bool| {
            (0..n).any(|i| newton.state[i] == ElementState::Slip && (mu(i) == muk) == kin)
        };
        assert!(slip_at(true) && slip_at(false));
        check_coulomb_bounds(&c, &march, mu);
        let fmax = c.pn.iter().fold(0.0f64, |m, &v| m.max(v)) * mus;
        for i in 0..n {
            let d = (newton.px[i] - march.px[i]).hypot(newton.py[i] - march.py[i]);
            assert!(d <= 1e-6 * fmax, "element {i} differs by {d}");
        }
    }

    #[test]
    fn both_vector_widths_give_bit_identical_solutions() {
        // The AVX2 copies of the FFT products and of GMRES (core::simd)
        // change only the number of independent lanes, never an operation
        // or its order. (Without AVX2 both runs take the baseline copy.)
        let c = case(24, 4e-4, 3e-4, 0.5);
        crate::core::simd::force_baseline(true);
        let base = run(&c, 0.3, true);
        crate::core::simd::force_baseline(false);
        let wide = run(&c, 0.3, true);
        assert!(base.outcome.converged);
        assert_eq!(base.outcome.matvecs, wide.outcome.matvecs);
        for (a, b) in base
            .px
            .iter()
            .zip(&wide.px)
            .chain(base.py.iter().zip(&wide.py))
        {
            assert_eq!(a.to_bits(), b.to_bits());
        }
    }

    #[test]
    fn newton_solves_a_transient_step_like_fista() {
        // One shift step from the unloaded state (shift 5 µm along x and
        // 4 µm along y, rotation 1 mrad): the convex program solved by
        // FISTA and the same Coulomb system by Newton with the diagonal
        // local model.
        let mu = 0.3;
        let c = case(24, 5e-6, 4e-6, 1e-3);
        let n = c.grid.len();
        let prev = vec![ElementState::Exterior; n];
        let input = c.input(mu, &prev);
        // Newton with (Some(true)) or without (Some(false)) the global
        // preconditioner, or FISTA (None).
        let fields = |newton: Option<bool>| {
            let settings = TangentialSettings {
                tolerance: 1e-9,
                max_iterations: 5000,
                global_preconditioner: newton.unwrap_or(false),
            };
            let (mut px, mut py, mut sx, mut sy) =
                (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
            let mut state = vec![ElementState::Exterior; n];
            let out = TangentialOutput {
                px: &mut px,
                py: &mut py,
                sx: &mut sx,
                sy: &mut sy,
                state: &mut state,
            };
            let mut ows = c.displacement.workspace();
            let o = if newton.is_some() {
                let mut op = PlanarTangential {
                    kernels: &c.displacement,
                    ows: &mut ows,
                };
                let mut sc = SteadyScratch::new(n);
                solve_coulomb_newton(
                    &mut op,
                    LocalModel::Diagonal,
                    None,
                    &input,
                    out,
                    &mut sc,
                    &settings,
                )
            } else {
                crate::core::tangential::solve_transient(
                    &c.displacement,
                    &mut ows,
                    &input,
                    out,
                    &mut TangentialScratch::new(n),
                    &settings,
                )
            };
            assert!(o.converged, "newton {newton:?}: {o:?}");
            (px, py, state, o.matvecs)
        };
        let (nx_, ny_, ns, nm) = fields(Some(true));
        let (fx_, fy_, fs, fm) = fields(None);
        let (gx_, gy_, _, gm) = fields(Some(false));
        let slips = ns.iter().filter(|s| **s == ElementState::Slip).count();
        assert!(slips > 20 && ns.contains(&ElementState::Adhesion));
        let fmax = c.pn.iter().fold(0.0f64, |m, &v| m.max(v)) * mu;
        for i in 0..n {
            let d = (nx_[i] - fx_[i]).hypot(ny_[i] - fy_[i]);
            assert!(d <= 1e-6 * fmax, "element {i} differs by {d}");
            let d = (nx_[i] - gx_[i]).hypot(ny_[i] - gy_[i]);
            assert!(
                d <= 1e-7 * fmax,
                "element {i}: the preconditioners differ by {d}"
            );
        }
        assert_eq!(
            ns.iter().filter(|s| **s == ElementState::Slip).count(),
            fs.iter().filter(|s| **s == ElementState::Slip).count()
        );
        eprintln!(
            "transient step: Newton {nm} matvecs ({gm} without the global preconditioner), FISTA {fm}"
        );
        assert!(
            nm < gm,
            "{nm} products with the global preconditioner, {gm} without"
        );
    }

    #[test]
    fn steady_operator_through_displacement_kernels_gives_the_same_solution() {
        // B = A (I - S)/dx by the displacement kernels (what the driver
        // uses) against the steady-rolling kernels.
        let mu = 0.3;
        let c = case(24, 4e-4, 3e-4, 0.5);
        let a = run_with(&c, mu, Some(&c.displacement), true);
        let b = run_with(&c, mu, Some(&c.steady), true);
        assert!(a.outcome.converged && b.outcome.converged);
        assert_eq!(a.state, b.state);
        let fmax = c.pn.iter().fold(0.0f64, |m, &v| m.max(v)) * mu;
        for i in 0..c.grid.len() {
            let d = (a.px[i] - b.px[i]).hypot(a.py[i] - b.py[i]);
            assert!(d <= 1e-7 * fmax, "element {i} differs by {d}");
        }
    }

    #[test]
    fn cancelled_solves_take_no_step() {
        // core::cancel: the Newton loop and the time marching look at the
        // thread's token before each step.
        let c = case(24, 4e-4, 3e-4, 0.5);
        let token = crate::core::cancel::CancelToken::new();
        token.cancel();
        for newton in [Some(&c.displacement), None] {
            let whole = run_with(&c, 0.3, newton, true);
            assert!(whole.outcome.converged && whole.outcome.iterations > 0);
            let cut = token.scope(|| run_with(&c, 0.3, newton, true));
            assert!(!cut.outcome.converged);
            assert_eq!(cut.outcome.iterations, 0);
        }
    }

    #[test]
    fn the_global_preconditioner_saves_products_and_keeps_the_answer() {
        // The circulant inverse in the preconditioner (Linear::precondition)
        // changes the Krylov iterations, not the discrete problem: the same
        // tractions to the tolerance, with fewer products (56 -> 38 on the
        // 32x32 bench case; here a partial-slip patch with spin on 48x48).
        let mu = 0.3;
        let c = case(48, 4e-4, 3e-4, 0.5);
        let with = run_with(&c, mu, Some(&c.displacement), true);
        let without = run_with(&c, mu, Some(&c.displacement), false);
        assert!(with.outcome.converged && without.outcome.converged);
        let (nadh, nslip) = check_coulomb(&c, &with, mu);
        assert!(nadh > 100 && nslip > 100, "{nadh} adhesion, {nslip} slip");
        let fmax = c.pn.iter().fold(0.0f64, |m, &v| m.max(v)) * mu;
        for i in 0..c.grid.len() {
            let d = (with.px[i] - without.px[i]).hypot(with.py[i] - without.py[i]);
            assert!(d <= 1e-7 * fmax, "element {i} differs by {d}");
        }
        eprintln!(
            "48x48 steady: {} products with the global preconditioner, {} without",
            with.outcome.matvecs, without.outcome.matvecs
        );
        assert!(
            with.outcome.matvecs * 4 < without.outcome.matvecs * 3,
            "{} products with, {} without",
            with.outcome.matvecs,
            without.outcome.matvecs
        );
    }

    #[test]
    fn full_slip_and_full_adhesion_limits() {
        // Large creepage: every loaded element slides, the traction is mu p_n
        // opposite the (uniform) rigid slip where the elastic part is small.
        let c = case(20, 0.05, 0.0, 0.0);
        let a = run(&c, 0.3, true);
        assert!(a.outcome.converged, "{:?}", a.outcome);
        let (nadh, _) = check_coulomb(&c, &a, 0.3);
        assert_eq!(nadh, 0);
        // Huge friction: all adhesion, slip zero everywhere.
        let a = run(&c, 1e6, true);
        assert!(a.outcome.converged, "{:?}", a.outcome);
        let (_, nslip) = check_coulomb(&c, &a, 1e6);
        assert_eq!(nslip, 0);
    }
}
