//! Zero-padded 2-D convolutions by FFTs, and the influence-coefficient
//! operators built on them.
//!
//! A field on the `nx` x `ny` grid is embedded in a `px` x `py` array with
//! `px >= 2 nx - 1`, `py >= 2 ny - 1`, so the circular convolution equals the
//! linear (Toeplitz) one: no wrap-around. Kernels are transformed once, at
//! construction, and shared read-only ([`KernelSet`] is `Send + Sync` and kept in
//! an `Arc` by [`crate::core::cache::KernelCache`]); each solve owns an
//! [`OperatorWorkspace`] so that the hot loop never allocates.
//!
//! Layout of a spectrum: `nkx = px/2 + 1` columns of `py` complex values, column
//! kx contiguous (`spec[kx * py + ky]`). The `ny` non-zero rows of a field are
//! transformed first, two real rows per complex FFT, and written straight
//! into the columns; then the columns are transformed by complex FFTs. The
//! inverse transforms all columns and then only the `ny` rows that are kept,
//! again two per complex FFT.
//!
//! Plans, workspaces and spectra are generic over the floating-point type
//! ([`Real`]): [`KernelSet::apply`] works in `f64`; [`KernelSet::apply_with`]
//! [`Precision::Single`] runs the same product in `f32` (FFTs twice as wide per SIMD register, half
//! the memory traffic), for the Krylov products of the Newton solvers, whose
//! accuracy needs are far looser than the rounding of single precision.
//!
//! [`KernelSet::apply`] keeps its spectra in a blocked variant of this layout:
//! blocks of a few columns, each followed by a one-cache-line gap so that the
//! row transforms, which write and read across all columns, do not thrash a
//! single L1 set when `py` is a power of two. It runs the forward column
//! transforms, the spectral products and the inverse column transforms block
//! by block while the block is in cache.

use std::sync::Arc;

use realfft::{RealFftPlanner, RealToComplex};
use rustfft::num_complex::{Complex, Complex64};
use rustfft::num_traits::NumAssign;
use rustfft::{Fft, FftNum, FftPlanner};

use crate::core::influence::{Component, HalfSpaceInfluence, KernelKind};
use crate::core::memory::{heap_bytes, HeapBytes};
use crate::core::numerical_influence::{InfluenceFile, TableKernel};
use crate::core::simd::multiversion;

/// Smallest even 2-3-5-smooth number >= n (fast FFT sizes in `f64`).
pub fn fast_even_size(n: usize) -> usize {
    smallest_even_smooth(n, &[2, 3, 5])
}

/// Smallest fast FFT size >= n in `f32`: an even 3-smooth number, or a
/// power of two times 5 from 80 on. rustfft's vectorised `f32` transforms
/// are slow for other factors of 5 (lengths 30, 40, 60, 90, 100, 120 take
/// as long as, or longer than, the next 3-smooth length, some longer than
/// in `f64`, on AVX machines; 80 and 160 are faster than 96 and 192).
pub fn fast_even_size_single(n: usize) -> usize {
    let three = smallest_even_smooth(n, &[2, 3]);
    let five = smallest_even_smooth(n.div_ceil(5).max(16), &[2]) * 5;
    three.min(five)
}

fn smallest_even_smooth(n: usize, primes: &[usize]) -> usize {
    let mut m = n.max(2);
    loop {
        if m.is_multiple_of(2) {
            let mut k = m;
            for &p in primes {
                while k.is_multiple_of(p) {
                    k /= p;
                }
            }
            if k == 1 {
                return m;
            }
        }
        m += 1;
    }
}

/// The floating-point types of the transforms: `f64` for the operator
/// products, `f32` for the approximate ones of [`Precision::Single`] products.
/// Fields on the grid stay `f64` in either case; they are narrowed on the
/// way in and widened on the way out.
pub trait Real: FftNum + NumAssign {
    /// `x` in this type (rounded).
    fn narrow(x: f64) -> Self;
    /// This value as an `f64` (exact).
    fn widen(self) -> f64;
    /// The padded FFT length for a grid line of `n` elements (at least
    /// `2 n - 1`, so that products do not wrap around).
    fn padded_len(n: usize) -> usize;
}

impl Real for f64 {
    #[inline(always)]
    fn narrow(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn widen(self) -> f64 {
        self
    }
    fn padded_len(n: usize) -> usize {
        fast_even_size(2 * n - 1)
    }
}

impl Real for f32 {
    #[inline(always)]
    fn narrow(x: f64) -> Self {
        x as f32
    }
    #[inline(always)]
    fn widen(self) -> f64 {
        self as f64
    }
    fn padded_len(n: usize) -> usize {
        fast_even_size_single(2 * n - 1)
    }
}

/// Spectral columns per block of the layout of [`KernelSet::apply`]: the
/// block stays in L1 from the forward column transforms to the inverse ones.
const COLUMN_BLOCK: usize = 4;

/// Gap after each block of [`COLUMN_BLOCK`] columns [complex values]: one
/// cache line, so that consecutive blocks start in different L1 sets even
/// when `py` is a power of two.
const BLOCK_GAP: usize = 4;

/// Rows transformed together (four packed pairs): each column receives
/// eight consecutive values (two cache lines) per write.
const ROW_CHUNK: usize = 8;

/// FFT plans for one grid size (immutable, shareable).
pub struct ConvolutionPlan<T: Real = f64> {
    /// Grid elements in x.
    pub nx: usize,
    /// Grid elements in y.
    pub ny: usize,
    /// Padded size in x.
    pub px: usize,
    /// Padded size in y.
    pub py: usize,
    /// Number of spectral columns, px/2 + 1.
    pub nkx: usize,
    /// Real FFT of a padded row (kernel transforms only).
    r2c: Arc<dyn RealToComplex<T>>,
    /// Complex FFTs of length px (rows, two real rows per transform).
    row_fwd: Arc<dyn Fft<T>>,
    row_inv: Arc<dyn Fft<T>>,
    /// Complex FFTs of length py (columns).
    fwd: Arc<dyn Fft<T>>,
    inv: Arc<dyn Fft<T>>,
    /// Start of column kx in the blocked layout of [`KernelSet::apply`].
    block_offsets: Vec<usize>,
    /// Length of a spectrum in the blocked layout.
    block_len: usize,
}

impl<T: Real> std::fmt::Debug for ConvolutionPlan<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "ConvolutionPlan({}x{} padded {}x{})",
            self.nx, self.ny, self.px, self.py
        )
    }
}

/// Scratch buffers for one thread using a [`ConvolutionPlan`].
#[derive(Clone)]
pub struct Workspace<T: Real = f64> {
    /// A padded real row (kernel transforms).
    row: Vec<T>,
    /// Its half spectrum.
    rowspec: Vec<Complex<T>>,
    /// [`ROW_CHUNK`]`/2` complex rows of length px: packed pairs of real rows.
    crow: Vec<Complex<T>>,
    r2c_scratch: Vec<Complex<T>>,
    /// Scratch of the complex FFTs (rows and columns).
    scratch: Vec<Complex<T>>,
}

impl<T: Real> HeapBytes for Workspace<T> {
    fn heap_bytes(&self) -> usize {
        heap_bytes!(
            self.row,
            self.rowspec,
            self.crow,
            self.r2c_scratch,
            self.scratch
        )
    }
}

#[inline(always)]
fn czero<T: Real>() -> Complex<T> {
    Complex::new(T::zero(), T::zero())
}

impl<T: Real> ConvolutionPlan<T> {
    /// Plans for an `nx` x `ny` grid.
    pub fn new(nx: usize, ny: usize) -> Self {
        Self::with_padding(nx, ny, T::padded_len(nx), T::padded_len(ny))
    }

    /// Plans for an `nx` x `ny` grid embedded in a `px` x `py` array (`px`
    /// even, `px >= nx`, `py >= ny`). Without `px >= 2 nx - 1`, `py >= 2 ny - 1`
    /// the products are circular (wrap-around), which only the
    /// preconditioner of [`KernelSet::apply_normal_inverse`] uses.
    fn with_padding(nx: usize, ny: usize, px: usize, py: usize) -> Self {
        debug_assert!(px.is_multiple_of(2) && px >= nx && py >= ny);
        let nkx = px / 2 + 1;
        let mut rp = RealFftPlanner::<T>::new();
        let mut cp = FftPlanner::<T>::new();
        let stride = COLUMN_BLOCK * py + BLOCK_GAP;
        let block_offsets = (0..nkx)
            .map(|k| (k / COLUMN_BLOCK) * stride + (k % COLUMN_BLOCK) * py)
            .collect();
        Self {
            nx,
            ny,
            px,
            py,
            nkx,
            r2c: rp.plan_fft_forward(px),
            row_fwd: cp.plan_fft_forward(px),
            row_inv: cp.plan_fft_inverse(px),
            fwd: cp.plan_fft_forward(py),
            inv: cp.plan_fft_inverse(py),
            block_offsets,
            block_len: nkx.div_ceil(COLUMN_BLOCK) * stride,
        }
    }

    /// Length of a spectrum buffer.
    pub fn spectrum_len(&self) -> usize {
        self.nkx * self.py
    }

    /// Allocates the scratch buffers for this plan.
    pub fn workspace(&self) -> Workspace<T> {
        let zero = czero::<T>();
        let scratch = [&self.row_fwd, &self.row_inv, &self.fwd, &self.inv]
            .iter()
            .map(|f| {
                f.get_inplace_scratch_len()
                    .max(f.get_outofplace_scratch_len())
            })
            .max()
            .unwrap_or(0);
        Workspace {
            row: vec![T::zero(); self.px],
            rowspec: vec![zero; self.nkx],
            crow: vec![zero; ROW_CHUNK.div_ceil(2) * self.px],
            r2c_scratch: vec![zero; self.r2c.get_scratch_len()],
            scratch: vec![zero; scratch],
        }
    }

    /// Spectrum of an `nx*ny` field (zero-padded). No allocation.
    pub fn forward(&self, ws: &mut Workspace<T>, field: &[f64], spec: &mut [Complex<T>]) {
        debug_assert_eq!(field.len(), self.nx * self.ny);
        debug_assert_eq!(spec.len(), self.spectrum_len());
        let (ny, py) = (self.ny, self.py);
        self.rows_forward(ws, field, spec, |k| k * py);
        for c in spec.chunks_exact_mut(py) {
            c[ny..].fill(czero());
        }
        self.fwd.process_with_scratch(spec, &mut ws.scratch);
    }

    /// Field (first `nx*ny` of the padded array) of a spectrum; `spec` is
    /// overwritten. No allocation.
    pub fn inverse(&self, ws: &mut Workspace<T>, spec: &mut [Complex<T>], out: &mut [f64]) {
        debug_assert_eq!(out.len(), self.nx * self.ny);
        debug_assert_eq!(spec.len(), self.spectrum_len());
        let py = self.py;
        self.inv.process_with_scratch(spec, &mut ws.scratch);
        self.rows_inverse(ws, spec, |k| k * py, out);
    }

    /// Spectrum of the kernel `k(ox, oy)` for element offsets |ox| < nx,
    /// |oy| < ny, normalised so that `inverse(K * forward(p))` is the plain
    /// Toeplitz product.
    pub fn kernel_spectrum(
        &self,
        ws: &mut Workspace<T>,
        k: impl Fn(i64, i64) -> f64,
    ) -> Vec<Complex<T>> {
        let (px, py, nkx) = (self.px, self.py, self.nkx);
        let scale = 1.0 / (px * py) as f64;
        let mut spec = vec![czero(); self.spectrum_len()];
        for jy in 0..py {
            let oy = if jy < self.ny {
                Some(jy as i64)
            } else if jy + self.ny > py {
                Some(jy as i64 - py as i64)
            } else {
                None
            };
            ws.row.fill(T::zero());
            if let Some(oy) = oy {
                for jx in 0..px {
                    let ox = if jx < self.nx {
                        jx as i64
                    } else if jx + self.nx > px {
                        jx as i64 - px as i64
                    } else {
                        continue;
                    };
                    ws.row[jx] = T::narrow(k(ox, oy) * scale);
                }
            }
            let _ =
                self.r2c
                    .process_with_scratch(&mut ws.row, &mut ws.rowspec, &mut ws.r2c_scratch);
            for kx in 0..nkx {
                spec[kx * py + jy] = ws.rowspec[kx];
            }
        }
        self.fwd.process_with_scratch(&mut spec, &mut ws.scratch);
        spec
    }

    /// Row transforms of an `nx*ny` field into the first `ny` values of the
    /// spectral columns, column kx starting at `spec[offset(kx)]`.
    ///
    /// Two real rows `a`, `b` share one complex FFT of `z = a + i b`:
    /// `A[k] = (Z[k] + conj Z[-k]) / 2`, `B[k] = (Z[k] - conj Z[-k]) / 2i`.
    /// Rows go [`ROW_CHUNK`] at a time, so that each column receives
    /// consecutive values in one write.
    #[inline(always)]
    fn rows_forward(
        &self,
        ws: &mut Workspace<T>,
        field: &[f64],
        spec: &mut [Complex<T>],
        offset: impl Fn(usize) -> usize,
    ) {
        let (nx, px) = (self.nx, self.px);
        for (q, src) in field.chunks(ROW_CHUNK * nx).enumerate() {
            let rows = src.len() / nx;
            let z = &mut ws.crow[..rows.div_ceil(2) * px];
            for (zc, s) in z.chunks_exact_mut(px).zip(src.chunks(2 * nx)) {
                let (a, b) = s.split_at(nx);
                if b.is_empty() {
                    for (zi, &ai) in zc.iter_mut().zip(a) {
                        *zi = Complex::new(T::narrow(ai), T::zero());
                    }
                } else {
                    for ((zi, &ai), &bi) in zc.iter_mut().zip(a).zip(b) {
                        *zi = Complex::new(T::narrow(ai), T::narrow(bi));
                    }
                }
                zc[nx..].fill(czero());
            }
            self.row_fwd.process_with_scratch(z, &mut ws.scratch);
            let (z, iy) = (&*z, ROW_CHUNK * q);
            match rows {
                8 => self.split_rows::<8>(z, spec, iy, &offset),
                7 => self.split_rows::<7>(z, spec, iy, &offset),
                6 => self.split_rows::<6>(z, spec, iy, &offset),
                5 => self.split_rows::<5>(z, spec, iy, &offset),
                4 => self.split_rows::<4>(z, spec, iy, &offset),
                3 => self.split_rows::<3>(z, spec, iy, &offset),
                2 => self.split_rows::<2>(z, spec, iy, &offset),
                _ => self.split_rows::<1>(z, spec, iy, &offset),
            }
        }
    }

    /// The spectra of `R` consecutive rows from the FFTs `z` of their packed
    /// pairs (and of the last row alone when `R` is odd), into the values
    /// `iy..iy + R` of every column.
    #[inline(always)]
    fn split_rows<const R: usize>(
        &self,
        z: &[Complex<T>],
        spec: &mut [Complex<T>],
        iy: usize,
        offset: &impl Fn(usize) -> usize,
    ) {
        let px = self.px;
        let half = T::narrow(0.5);
        for k in 0..self.nkx {
            let mk = if k == 0 { 0 } else { px - k };
            let mut v = [czero(); R];
            for i in 0..R / 2 {
                let (p, q) = (z[i * px + k], z[i * px + mk]);
                v[2 * i] = Complex::new(half * (p.re + q.re), half * (p.im - q.im));
                v[2 * i + 1] = Complex::new(half * (p.im + q.im), half * (q.re - p.re));
            }
            if R % 2 == 1 {
                // A row alone: z was real, Z is its spectrum.
                v[R - 1] = z[(R / 2) * px + k];
            }
            let o = offset(k) + iy;
            spec[o..o + R].copy_from_slice(&v);
        }
    }

    /// Inverse of [`Self::rows_forward`]: the first `nx` values of the `ny`
    /// kept rows, from the first `ny` values of the inverse-transformed
    /// columns. Two rows per complex FFT of `Z = A + i B` (Hermitian
    /// extensions); the DC and Nyquist bins of a real row are taken as real
    /// (their imaginary parts are rounding noise).
    #[inline(always)]
    fn rows_inverse(
        &self,
        ws: &mut Workspace<T>,
        spec: &[Complex<T>],
        offset: impl Fn(usize) -> usize,
        out: &mut [f64],
    ) {
        let (nx, px) = (self.nx, self.px);
        for (q, dst) in out.chunks_mut(ROW_CHUNK * nx).enumerate() {
            let rows = dst.len() / nx;
            let z = &mut ws.crow[..rows.div_ceil(2) * px];
            let iy = ROW_CHUNK * q;
            match rows {
                8 => self.join_rows::<8>(spec, iy, &offset, z),
                7 => self.join_rows::<7>(spec, iy, &offset, z),
                6 => self.join_rows::<6>(spec, iy, &offset, z),
                5 => self.join_rows::<5>(spec, iy, &offset, z),
                4 => self.join_rows::<4>(spec, iy, &offset, z),
                3 => self.join_rows::<3>(spec, iy, &offset, z),
                2 => self.join_rows::<2>(spec, iy, &offset, z),
                _ => self.join_rows::<1>(spec, iy, &offset, z),
            }
            self.row_inv.process_with_scratch(z, &mut ws.scratch);
            for (zc, d) in z.chunks_exact(px).zip(dst.chunks_mut(2 * nx)) {
                let (da, db) = d.split_at_mut(nx);
                for (d, zi) in da.iter_mut().zip(zc) {
                    *d = zi.re.widen();
                }
                for (d, zi) in db.iter_mut().zip(zc) {
                    *d = zi.im.widen();
                }
            }
        }
    }

    /// The packed full spectra `z` of `R` consecutive rows (pairs, and the
    /// last row alone when `R` is odd) from the values `iy..iy + R` of every
    /// column.
    #[inline(always)]
    fn join_rows<const R: usize>(
        &self,
        spec: &[Complex<T>],
        iy: usize,
        offset: &impl Fn(usize) -> usize,
        z: &mut [Complex<T>],
    ) {
        let px = self.px;
        let h = px / 2;
        for k in 0..=h {
            let o = offset(k) + iy;
            let mut v = [czero(); R];
            v.copy_from_slice(&spec[o..o + R]);
            if k == 0 || k == h {
                for v in &mut v {
                    v.im = T::zero();
                }
            }
            let mk = if k == 0 { 0 } else { px - k };
            for i in 0..R.div_ceil(2) {
                let (a, b) = if 2 * i + 1 < R {
                    (v[2 * i], v[2 * i + 1])
                } else {
                    (v[2 * i], czero())
                };
                // Z[-k] first: equal to Z[k] for k = 0 and k = h.
                z[i * px + mk] = Complex::new(a.re + b.im, b.re - a.im);
                z[i * px + k] = Complex::new(a.re - b.im, a.im + b.re);
            }
        }
    }
}

const COMPONENTS: [Component; 3] = [Component::X, Component::Y, Component::N];

/// Relative size [-] below which the imaginary (real) part of a kernel
/// spectrum is dropped, measured against the largest modulus of the
/// spectrum. That largest modulus is the norm of the circulant extension of
/// the kernel, so dropping the part changes the operator by at most this
/// fraction of that norm. Point-symmetric kernels (the Displacement kernels
/// (X,X), (Y,Y), (N,N), (X,Y)) have real spectra and point-antisymmetric
/// ones (the Displacement couplings) imaginary spectra, up to the rounding
/// of the closed-form coefficients (about 1e-15 to 1e-14 for moderate
/// element aspect ratios); SteadyRolling kernels are neither and stay
/// complex.
const SYMMETRY_TOL: f64 = 1e-13;

/// One transformed kernel, stored in the smallest form that is exact to
/// [`SYMMETRY_TOL`] (half the memory traffic and a third of the arithmetic
/// of a complex product for the real and imaginary forms).
pub(crate) enum Spectrum<T: Real> {
    /// General spectrum.
    Complex(Vec<Complex<T>>),
    /// Real spectrum: the real parts.
    Real(Vec<T>),
    /// Imaginary spectrum: the imaginary parts.
    Imag(Vec<T>),
}

impl<T: Real> Spectrum<T> {
    /// Memory held [bytes].
    pub(crate) fn bytes(&self) -> usize {
        match self {
            Spectrum::Complex(v) => std::mem::size_of_val(v.as_slice()),
            Spectrum::Real(v) | Spectrum::Imag(v) => std::mem::size_of_val(v.as_slice()),
        }
    }

    /// `dst (+)= K s` over the spectral range `at..at + dst.len()` of the
    /// kernel; assigns when `first`, accumulates otherwise.
    #[inline(always)]
    pub(crate) fn apply(&self, at: usize, s: &[Complex<T>], dst: &mut [Complex<T>], first: bool) {
        #[inline(always)]
        fn pass<K: Copy, T: Real>(
            k: &[K],
            s: &[Complex<T>],
            dst: &mut [Complex<T>],
            first: bool,
            f: impl Fn(K, Complex<T>) -> Complex<T>,
        ) {
            if first {
                for ((d, &k), &s) in dst.iter_mut().zip(k).zip(s) {
                    *d = f(k, s);
                }
            } else {
                for ((d, &k), &s) in dst.iter_mut().zip(k).zip(s) {
                    *d += f(k, s);
                }
            }
        }
        let r = at..at + dst.len();
        match self {
            Spectrum::Complex(k) => pass(&k[r], s, dst, first, |k, s| k * s),
            Spectrum::Real(k) => pass(&k[r], s, dst, first, |k, s| s * k),
            Spectrum::Imag(k) => pass(&k[r], s, dst, first, |k, s| {
                Complex::new(-(k * s.im), k * s.re)
            }),
        }
    }
}

impl Spectrum<f64> {
    /// The spectrum `k` in its smallest exact form (see [`SYMMETRY_TOL`]).
    pub(crate) fn new(k: Vec<Complex64>) -> Self {
        let (mut m, mut re, mut im) = (0.0f64, 0.0f64, 0.0f64);
        for v in &k {
            m = m.max(v.norm());
            re = re.max(v.re.abs());
            im = im.max(v.im.abs());
        }
        if im <= SYMMETRY_TOL * m {
            Spectrum::Real(k.iter().map(|v| v.re).collect())
        } else if re <= SYMMETRY_TOL * m {
            Spectrum::Imag(k.iter().map(|v| v.im).collect())
        } else {
            Spectrum::Complex(k)
        }
    }

    /// The same spectrum rounded to `f32`.
    fn narrow(&self) -> Spectrum<f32> {
        let n = |v: &[f64]| v.iter().map(|&x| x as f32).collect();
        match self {
            Spectrum::Complex(v) => Spectrum::Complex(
                v.iter()
                    .map(|c| Complex::new(c.re as f32, c.im as f32))
                    .collect(),
            ),
            Spectrum::Real(v) => Spectrum::Real(n(v)),
            Spectrum::Imag(v) => Spectrum::Imag(n(v)),
        }
    }
}

/// The floating-point precision of an operator product.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Precision {
    /// `f64` transforms.
    Double,
    /// `f32` transforms: the fields are rounded to `f32`, transformed,
    /// multiplied by the rounded kernel spectra and transformed back. The
    /// result differs from the `f64` product by about 2e-7 of the largest
    /// output value (grids 23x31 to 128x100; the tests bound it by 1e-6),
    /// at 40 to 70 % of the cost. For products whose accuracy needs are
    /// loose: the Krylov iterations of the Newton solvers, whose residuals
    /// are then evaluated in `f64`.
    Single,
}

/// The kernels of a [`KernelSet`] in single precision, on their own plan
/// (3-smooth padded sizes, fast in `f32`), indexed like the `f64` ones.
struct SingleKernels {
    plan: ConvolutionPlan<f32>,
    spectra: Vec<Spectrum<f32>>,
}

/// The transformed influence kernels of one operator kind for one grid size,
/// spacing and material pair. Immutable after construction.
pub struct KernelSet {
    /// FFT plans.
    pub plan: Arc<ConvolutionPlan>,
    /// Which operator this is.
    pub kind: KernelKind,
    /// The closed-form coefficients the kernels were built from (with a
    /// [`KernelSet::table`], its element sizes and materials only).
    pub influence: HalfSpaceInfluence,
    /// Coefficients from a file of numerical influence coefficients
    /// ([`crate::core::numerical_influence`]) replacing the half-space's
    /// ([`KernelSet::from_table`]); None: the half-space.
    pub table: Option<Arc<InfluenceFile>>,
    /// With a file of one matrix per loaded row: the set of each row's
    /// matrix (the products sum them, [`KernelSet::apply_with`]); empty
    /// otherwise.
    rows: Vec<KernelSet>,
    /// Distinct kernel spectra ([`ConvolutionPlan::kernel_spectrum`]).
    spectra: Vec<Spectrum<f64>>,
    /// `index[i][j]`: the entry of `spectra` holding kernel (i, j), if present.
    index: [[Option<usize>; 3]; 3],
    /// The same kernels in single precision ([`Precision::Single`]).
    single: SingleKernels,
    /// Largest eigenvalue of the 2x2 tangential symbol over all frequencies:
    /// an upper bound of the spectral norm of the tangential block [m/Pa].
    pub tangential_norm_bound: f64,
    /// The plan and the entry of `spectra` of the normal preconditioner
    /// (displacement kernels only): see [`KernelSet::apply_normal_inverse`].
    normal_inverse: Option<(Arc<ConvolutionPlan>, usize)>,
    /// The periodic inverse of the displacement operator's tangential
    /// block: see [`KernelSet::apply_tangential_inverse`]. The same for
    /// both kinds of one grid and material pair, so shared when built with
    /// [`KernelSet::sharing_inverse_of`].
    tangential_inverse: Arc<TangentialInverse>,
    /// The real-space normal kernel A_nn at every offset of the grid, for
    /// [`KernelSet::add_normal_columns`] (None without a normal kernel).
    normal_table: Option<KernelTable>,
    /// Self-influence coefficients (x, y, n) of this kind, and (x, y) of
    /// the steady-rolling kind (evaluated once: the closed forms cost
    /// several logarithms).
    diagonal: [f64; 3],
    steady_diagonal: [f64; 2],
}

/// The inverse of the circulant extension of the tangential block, in
/// single precision, on the periodic array of a fast size that holds the
/// grid: spectra (xx, xy, yy) of [`periodic_inverse_2x2`].
struct TangentialInverse {
    plan: ConvolutionPlan<f32>,
    spectra: Vec<Spectrum<f32>>,
}

impl std::fmt::Debug for KernelSet {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "KernelSet({:?}, {:?})", self.kind, self.plan)
    }
}

/// Real-space kernel values for all offsets |ox| < nx, |oy| < ny, evaluated
/// once from the closed form and transformed for both precisions.
struct KernelTable {
    nx: usize,
    ny: usize,
    values: Vec<f64>,
}

impl KernelTable {
    /// Kernel `kind` (i, j) of `source` at every offset of an nx x ny
    /// grid, row after row ([`HalfSpaceInfluence::kernel_table`], else
    /// [`HalfSpaceInfluence::kernel_row`], for the half-space).
    fn of(
        source: &Source<'_>,
        kind: KernelKind,
        i: Component,
        j: Component,
        nx: usize,
        ny: usize,
    ) -> Self {
        let (wx, wy) = (2 * nx - 1, 2 * ny - 1);
        let mut values = vec![0.0; wx * wy];
        // The half-space's whole table at once where it can (its closed
        // forms once per element corner), else row by row.
        if source.table.is_none()
            && source
                .influence
                .kernel_table(kind, i, j, [nx, ny], &mut values)
        {
            return Self { nx, ny, values };
        }
        for (jy, row) in values.chunks_exact_mut(wx).enumerate() {
            let ky = jy as i64 - (ny as i64 - 1);
            let kx_lo = -(nx as i64 - 1);
            match &source.table {
                None => source.influence.kernel_row(kind, i, j, kx_lo, ky, row),
                Some(t) => {
                    for (k, o) in row.iter_mut().enumerate() {
                        *o = t.kernel(kind, i, j, kx_lo + k as i64, ky);
                    }
                }
            }
        }
        Self { nx, ny, values }
    }

    /// The value at (ox, oy) if the table holds it.
    fn get(&self, ox: i64, oy: i64) -> Option<f64> {
        (ox.unsigned_abs() < self.nx as u64 && oy.unsigned_abs() < self.ny as u64)
            .then(|| self.at(ox, oy))
    }

    #[inline]
    fn at(&self, ox: i64, oy: i64) -> f64 {
        let jx = (ox + self.nx as i64 - 1) as usize;
        let jy = (oy + self.ny as i64 - 1) as usize;
        self.values[jy * (2 * self.nx - 1) + jx]
    }
}

/// Where a set's kernel values come from: the half-space's closed forms,
/// or a table of numerical coefficients.
struct Source<'a> {
    influence: &'a HalfSpaceInfluence,
    table: Option<TableKernel<'a>>,
}

impl<'a> Source<'a> {
    /// The half-space's kernels, or (with `table`) those of its matrix
    /// `matrix`.
    fn new(
        influence: &'a HalfSpaceInfluence,
        table: Option<&'a InfluenceFile>,
        (nx, ny): (usize, usize),
        matrix: usize,
    ) -> Self {
        Self {
            influence,
            table: table.map(|file| TableKernel {
                file,
                matrix,
                nx,
                ny,
                dx_m: influence.dx_m(),
                shear_modulus_pa: influence.shear_modulus_pa(),
            }),
        }
    }

    fn kernel(&self, kind: KernelKind, i: Component, j: Component, ox: i64, oy: i64) -> f64 {
        match &self.table {
            None => self.influence.kernel(kind, i, j, ox, oy),
            Some(t) => t.kernel(kind, i, j, ox, oy),
        }
    }

    /// Whether the normal/tangential coupling kernels are non-zero.
    fn coupled(&self) -> bool {
        match &self.table {
            None => self.influence.coupled(),
            Some(t) => t.file.coupled(),
        }
    }

    /// Whether kernel (y, x) equals kernel (x, y) (one spectrum for both).
    fn symmetric_xy(&self) -> bool {
        self.table.as_ref().is_none_or(|t| t.file.symmetric_xy())
    }
}

impl KernelSet {
    /// Memory held by the transformed kernels \[bytes\] (the FFT plans are
    /// shared and not counted; the tangential inverse is counted in each
    /// set that holds it, an over-count for a cache that holds both kinds
    /// of a grid).
    pub fn bytes(&self) -> usize {
        self.spectra.iter().map(Spectrum::bytes).sum::<usize>()
            + self
                .single
                .spectra
                .iter()
                .chain(&self.tangential_inverse.spectra)
                .map(Spectrum::bytes)
                .sum::<usize>()
            + self
                .normal_table
                .as_ref()
                .map_or(0, |t| t.values.len() * std::mem::size_of::<f64>())
            + self.rows.iter().map(KernelSet::bytes).sum::<usize>()
    }

    /// Builds and transforms all kernels (tangential block, normal, and the
    /// normal/tangential coupling when the materials differ), in double and
    /// in single precision.
    pub fn new(
        plan: Arc<ConvolutionPlan>,
        influence: HalfSpaceInfluence,
        kind: KernelKind,
    ) -> Self {
        Self::build(plan, influence, kind, None, None, 0)
    }

    /// [`KernelSet::new`] with the coefficients of a file of numerical
    /// influence coefficients instead of the half-space's ([`TableKernel`]);
    /// `influence` gives the element sizes and the combined shear modulus
    /// that scales them. With `other` (a set of the same grid, materials
    /// and table), its tangential inverse is shared as in
    /// [`KernelSet::sharing_inverse_of`]. A file of one matrix per loaded
    /// row (as many as the grid's rows, checked by the caller) builds a set
    /// per row as well, whose products [`KernelSet::apply_with`] sums; its
    /// own kernels, preconditioners and [`KernelSet::value`] are the middle
    /// row's.
    pub fn from_table(
        plan: Arc<ConvolutionPlan>,
        influence: HalfSpaceInfluence,
        kind: KernelKind,
        table: Arc<InfluenceFile>,
        other: Option<&KernelSet>,
    ) -> Self {
        let shared = other
            .filter(|o| {
                o.influence == influence
                    && (o.plan.nx, o.plan.ny) == (plan.nx, plan.ny)
                    && o.table
                        .as_ref()
                        .is_some_and(|t| Arc::ptr_eq(t, &table) || **t == *table)
            })
            .map(|o| o.tangential_inverse.clone());
        if table.matrices() == 1 {
            return Self::build(plan, influence, kind, shared, Some(table), 0);
        }
        // One matrix per loaded row: the middle row's set for the
        // preconditioners and the local scalars, and a set per row for the
        // products (whose preconditioners are not used: the tangential
        // inverse is shared).
        let ny = plan.ny;
        let mut main = Self::build(
            plan.clone(),
            influence,
            kind,
            shared,
            Some(table.clone()),
            ny / 2,
        );
        main.rows = (0..ny)
            .map(|m| {
                let inverse = Some(main.tangential_inverse.clone());
                Self::build(
                    plan.clone(),
                    influence,
                    kind,
                    inverse,
                    Some(table.clone()),
                    m,
                )
            })
            .collect();
        main
    }

    /// [`KernelSet::new`], taking the tangential inverse (the displacement
    /// operator's, the same for both kinds) from `other` when it has the
    /// same grid and materials instead of building it again (for a
    /// steady-rolling set, 12 % of its build at 128x128).
    pub fn sharing_inverse_of(
        plan: Arc<ConvolutionPlan>,
        influence: HalfSpaceInfluence,
        kind: KernelKind,
        other: &KernelSet,
    ) -> Self {
        let same = other.influence == influence
            && other.table.is_none()
            && (other.plan.nx, other.plan.ny) == (plan.nx, plan.ny);
        Self::build(
            plan,
            influence,
            kind,
            same.then(|| other.tangential_inverse.clone()),
            None,
            0,
        )
    }

    fn build(
        plan: Arc<ConvolutionPlan>,
        influence: HalfSpaceInfluence,
        kind: KernelKind,
        shared_inverse: Option<Arc<TangentialInverse>>,
        table: Option<Arc<InfluenceFile>>,
        matrix: usize,
    ) -> Self {
        let (nx, ny) = (plan.nx, plan.ny);
        let source = Source::new(&influence, table.as_deref(), (nx, ny), matrix);
        let mut ws = plan.workspace();
        let single_plan = ConvolutionPlan::<f32>::new(nx, ny);
        // The single-precision spectra are transformed in f64 on a plan of
        // their sizes (so that their symmetry is detected as for the f64
        // ones) and then rounded.
        let wide = ConvolutionPlan::<f64>::with_padding(nx, ny, single_plan.px, single_plan.py);
        let mut wide_ws = wide.workspace();
        let coupled = source.coupled();
        let symmetric_xy = source.symmetric_xy();
        let mut spectra = Vec::new();
        let mut single = Vec::new();
        let mut index = [[None; 3]; 3];
        // The displacement kind's tangential tables (xx, xy, yy), kept for
        // the periodic inverse: the closed forms cost several logarithms.
        let mut tangential_tables: [Option<KernelTable>; 3] = [None, None, None];
        let mut normal_table = None;
        for (a, &i) in COMPONENTS.iter().enumerate() {
            for (b, &j) in COMPONENTS.iter().enumerate() {
                let needed = (a < 2 && b < 2) || (a == 2 && b == 2) || coupled;
                if !needed {
                    continue;
                }
                if a == 1 && b == 0 && symmetric_xy {
                    // A_yx(X) = A_xy(X) (both are nu F_xy): share the spectrum.
                    continue;
                }
                index[a][b] = Some(spectra.len());
                let t = KernelTable::of(&source, kind, i, j, nx, ny);
                spectra.push(plan.kernel_spectrum(&mut ws, |ox, oy| t.at(ox, oy)));
                single.push(
                    Spectrum::new(wide.kernel_spectrum(&mut wide_ws, |ox, oy| t.at(ox, oy)))
                        .narrow(),
                );
                if kind == KernelKind::Displacement && a < 2 && b < 2 && !(a == 1 && b == 0) {
                    // (y, x) of a table that is not symmetric: the
                    // preconditioner takes (x, y) for both.
                    tangential_tables[a + b] = Some(t);
                } else if a == 2 && b == 2 {
                    normal_table = Some(t);
                }
            }
        }
        if symmetric_xy {
            index[1][0] = index[0][1];
        }
        let mut bound: f64 = 0.0;
        if let (Some(xx), Some(xy), Some(yy)) = (index[0][0], index[0][1], index[1][1]) {
            let (kxx, kxy, kyy) = (&spectra[xx], &spectra[xy], &spectra[yy]);
            let s = (plan.px * plan.py) as f64;
            for k in 0..kxx.len() {
                // Hermitian part's largest eigenvalue bounds the symbol's
                // action for symmetric kernels (Displacement kind).
                let (a, d, b) = (kxx[k].norm(), kyy[k].norm(), kxy[k].norm());
                let lam = 0.5 * (a + d) + (0.25 * (a - d) * (a - d) + b * b).sqrt();
                bound = bound.max(lam * s);
            }
        }
        let mut normal_inverse = None;
        if let (KernelKind::Displacement, Some(_)) = (kind, index[2][2]) {
            let pc = Arc::new(ConvolutionPlan::with_padding(
                nx,
                ny,
                fast_even_size(nx),
                periodic_rows(ny, fast_even_size),
            ));
            // The table's values where it holds them (the same as
            // `kernel`'s for elastic bodies).
            let table = normal_table.as_ref();
            spectra.push(periodic_inverse(&pc, |ox, oy| {
                table
                    .and_then(|t: &KernelTable| t.get(ox, oy))
                    .unwrap_or_else(|| source.kernel(kind, Component::N, Component::N, ox, oy))
            }));
            normal_inverse = Some((pc, spectra.len() - 1));
        }
        let tangential_inverse = shared_inverse.unwrap_or_else(|| {
            // The displacement operator's, whatever this set's kind.
            // Inverted in f64 on a plan of the single-precision sizes, then
            // rounded (as the single-precision kernels).
            let (px, py) = (
                fast_even_size_single(nx),
                periodic_rows(ny, fast_even_size_single),
            );
            let wide_pc = ConvolutionPlan::<f64>::with_padding(nx, ny, px, py);
            // Wrapped offsets stay within the tables: |o| <= p/2 < n.
            let inverse = periodic_inverse_2x2(&wide_pc, |i, j, ox, oy| {
                match &tangential_tables[i as usize + j as usize] {
                    Some(t) => t.at(ox, oy),
                    None => source.kernel(KernelKind::Displacement, i, j, ox, oy),
                }
            });
            Arc::new(TangentialInverse {
                plan: ConvolutionPlan::with_padding(nx, ny, px, py),
                spectra: inverse
                    .into_iter()
                    .map(|k| Spectrum::new(k).narrow())
                    .collect(),
            })
        });
        let spectra = spectra.into_iter().map(Spectrum::new).collect();
        let diagonal = COMPONENTS.map(|c| source.kernel(kind, c, c, 0, 0));
        let steady_diagonal = [Component::X, Component::Y]
            .map(|c| source.kernel(KernelKind::SteadyRolling, c, c, 0, 0));
        Self {
            plan,
            kind,
            influence,
            table,
            rows: Vec::new(),
            spectra,
            index,
            single: SingleKernels {
                plan: single_plan,
                spectra: single,
            },
            tangential_norm_bound: bound,
            normal_inverse,
            tangential_inverse,
            normal_table,
            diagonal,
            steady_diagonal,
        }
    }

    /// Allocates the buffers to apply this operator (they depend on the plan
    /// only: any kernel set of the same plan may use them).
    pub fn workspace(&self) -> OperatorWorkspace {
        OperatorWorkspace {
            shape: self.workspace_shape(),
            main: Buffers::new(&self.plan),
            pc: self
                .normal_inverse
                .as_ref()
                .map(|(pc, _)| Box::new(Buffers::new(pc))),
            single: Box::new(Buffers::new(&self.single.plan)),
            tangential_pc: Box::new(Buffers::new(&self.tangential_inverse.plan)),
            rows: (!self.rows.is_empty())
                .then(|| Box::new(RowScratch::new(self.plan.nx * self.plan.ny))),
        }
    }

    /// Whether `ws` (from the [`KernelSet::workspace`] of this or another
    /// set) serves this set: same grid, and a preconditioner's buffers if
    /// this set has a preconditioner.
    pub fn fits(&self, ws: &OperatorWorkspace) -> bool {
        let (nx, ny, pc) = self.workspace_shape();
        ws.shape.0 == nx
            && ws.shape.1 == ny
            && (ws.shape.2 || !pc)
            && (ws.rows.is_some() || self.rows.is_empty())
    }

    fn workspace_shape(&self) -> (usize, usize, bool) {
        (self.plan.nx, self.plan.ny, self.normal_inverse.is_some())
    }

    /// The real-space kernel value (i, j) at element offset (ox, oy) (with
    /// one matrix per loaded row: for a load on the middle row).
    pub fn value(&self, i: Component, j: Component, ox: i64, oy: i64) -> f64 {
        if i == j && ox == 0 && oy == 0 {
            return self.diagonal[i as usize];
        }
        Source::new(
            &self.influence,
            self.table.as_deref(),
            (self.plan.nx, self.plan.ny),
            self.rows.len() / 2,
        )
        .kernel(self.kind, i, j, ox, oy)
    }

    /// `out[I - offset] += sum_k A_nn(I, J_k - offset) c_k` over the grid's
    /// elements I, for the pairs (J_k, c_k) of `columns` (J_k - offset an
    /// element of this grid): the product of a pressure change on a few
    /// elements, from the real-space kernel, exact where an FFT product
    /// rounds. It costs about `nx * ny` multiply-adds a column against
    /// [`KernelSet::normal_column_limit`] columns for one FFT product.
    /// Returns false (and leaves `out` alone) for a set without a normal
    /// kernel.
    pub fn add_normal_columns(
        &self,
        columns: &[(usize, f64)],
        offset: usize,
        out: &mut [f64],
    ) -> bool {
        if !self.rows.is_empty() {
            // Each column through its row's matrix.
            let nx = self.plan.nx;
            return columns.iter().all(|&(j, c)| {
                let row = &self.rows[((j - offset) / nx).min(self.rows.len() - 1)];
                row.add_normal_columns(&[(j, c)], offset, out)
            });
        }
        let Some(t) = &self.normal_table else {
            return false;
        };
        add_columns(&t.values, t.nx, t.ny, columns, offset, out);
        true
    }

    /// How many columns [`KernelSet::add_normal_columns`] may add before
    /// one normal FFT product would be cheaper (0 without a normal kernel):
    /// `3 log2(px py)` of the padded array. A column is `nx * ny`
    /// multiply-adds streaming one kernel row per grid row, a product two
    /// transforms of `px * py` values: on the 2-core machine of
    /// `benches/README.md` (benches `matvec/normal` and
    /// `matvec/normal_columns_16`) a product costs 48 to 76 columns from
    /// 32x32 to 128x128, 3.4 to 5.7 log2(px py); the limit keeps below.
    pub fn normal_column_limit(&self) -> usize {
        if self.normal_table.is_none() {
            return 0;
        }
        (3.0 * ((self.plan.px * self.plan.py) as f64).log2()) as usize
    }

    /// The self-influence coefficients (xx, yy) of the steady-rolling
    /// kernels of this set's grid and materials, whatever its kind [1/Pa].
    pub fn steady_diagonal(&self) -> [f64; 2] {
        self.steady_diagonal
    }

    /// True when kernel (i, j) is present (coupling kernels only for K != 0).
    pub fn has(&self, i: Component, j: Component) -> bool {
        self.index[i as usize][j as usize].is_some()
    }

    /// `out_i = sum_j K_ij * in_j` for every requested output component and
    /// every given input (absent coupling kernels count as zero). Components
    /// must not repeat within `inputs` or within `outputs`. Inputs that no
    /// requested output depends on are not transformed. No allocation.
    pub fn apply(
        &self,
        ows: &mut OperatorWorkspace,
        inputs: &[(Component, &[f64])],
        outputs: &mut [(Component, &mut [f64])],
    ) {
        self.apply_with(Precision::Double, ows, inputs, outputs)
    }

    /// [`KernelSet::apply`] in the given precision (see [`Precision`]).
    /// With one matrix per loaded row: up to ny products
    /// (`apply_rows`).
    pub fn apply_with(
        &self,
        precision: Precision,
        ows: &mut OperatorWorkspace,
        inputs: &[(Component, &[f64])],
        outputs: &mut [(Component, &mut [f64])],
    ) {
        if !self.rows.is_empty() {
            return self.apply_rows(precision, ows, inputs, outputs);
        }
        let index = &self.index;
        match precision {
            Precision::Double => apply_indexed(
                &self.plan,
                &self.spectra,
                index,
                &mut ows.main,
                inputs,
                outputs,
            ),
            Precision::Single => {
                let single = &self.single;
                apply_indexed(
                    &single.plan,
                    &single.spectra,
                    index,
                    &mut ows.single,
                    inputs,
                    outputs,
                )
            }
        }
    }

    /// [`KernelSet::apply_with`] of a set with one matrix per loaded row:
    /// the sum over the grid's rows jy of the products of row jy's kernels
    /// with the inputs restricted to row jy (rows whose inputs are all zero
    /// skipped): up to ny FFT products, exact. No allocation with a
    /// workspace of this set ([`KernelSet::workspace`]).
    fn apply_rows(
        &self,
        precision: Precision,
        ows: &mut OperatorWorkspace,
        inputs: &[(Component, &[f64])],
        outputs: &mut [(Component, &mut [f64])],
    ) {
        let nx = self.plan.nx;
        let mut scratch = ows
            .rows
            .take()
            .unwrap_or_else(|| Box::new(RowScratch::new(nx * self.plan.ny)));
        for (_, o) in outputs.iter_mut() {
            o.fill(0.0);
        }
        let RowScratch { masked, out } = &mut *scratch;
        for (jy, set) in self.rows.iter().enumerate() {
            let span = jy * nx..(jy + 1) * nx;
            if inputs
                .iter()
                .all(|(_, v)| v[span.clone()].iter().all(|&x| x == 0.0))
            {
                continue;
            }
            for ((_, v), m) in inputs.iter().zip(masked.iter_mut()) {
                m[span.clone()].copy_from_slice(&v[span.clone()]);
            }
            {
                let [m0, m1, m2] = &*masked;
                let mut ins = [
                    (Component::X, &m0[..]),
                    (Component::Y, &m1[..]),
                    (Component::N, &m2[..]),
                ];
                for (k, (c, _)) in inputs.iter().enumerate() {
                    ins[k].0 = *c;
                }
                let [o0, o1, o2] = &mut *out;
                let mut outs = [
                    (Component::X, &mut o0[..]),
                    (Component::Y, &mut o1[..]),
                    (Component::N, &mut o2[..]),
                ];
                for (k, (c, _)) in outputs.iter().enumerate() {
                    outs[k].0 = *c;
                }
                set.apply_with(
                    precision,
                    ows,
                    &ins[..inputs.len()],
                    &mut outs[..outputs.len()],
                );
                for ((_, o), (_, t)) in outputs.iter_mut().zip(outs.iter()) {
                    for (a, b) in o.iter_mut().zip(t.iter()) {
                        *a += b;
                    }
                }
            }
            for m in masked.iter_mut().take(inputs.len()) {
                m[span.clone()].fill(0.0);
            }
        }
        ows.rows = Some(scratch);
    }

    /// `z = C⁻¹ r` on the grid, with C the circulant extension of the normal
    /// operator (the padded convolution whose leading block is A_nn), its
    /// eigenvalues bounded below by the one at the highest frequency (the
    /// truncated kernel's spectrum dips below it, and can even turn negative
    /// for elongated elements, at a few frequencies). An FFT-based
    /// preconditioner of the normal problem (Vollebregt, J. Comput. Phys.
    /// 257 (2014) 333–351): symmetric positive definite, one product's cost.
    /// Returns false (and leaves `z` alone) for kernel sets without it
    /// (steady-rolling kernels).
    pub fn apply_normal_inverse(
        &self,
        ows: &mut OperatorWorkspace,
        r: &[f64],
        z: &mut [f64],
    ) -> bool {
        let (Some((pc, k)), Some(pcws)) = (&self.normal_inverse, ows.pc.as_deref_mut()) else {
            return false;
        };
        let mut index = [[None; 3]; 3];
        index[2][2] = Some(*k);
        apply_indexed(
            pc,
            &self.spectra,
            &index,
            pcws,
            &[(Component::N, r)],
            &mut [(Component::N, z)],
        );
        true
    }

    /// `(zx, zy) = C⁻¹ (rx, ry)` on the grid, with C the circulant extension
    /// of the tangential block of the displacement operator, A_tt (for sets
    /// of either kind), on a periodic array that holds the grid (its 2x2
    /// symbol inverted at each frequency, see `periodic_inverse_2x2`), in
    /// single precision (about 1e-6 of the largest output): a global
    /// preconditioner of the tangential problems, about a quarter of a
    /// single-precision product.
    pub fn apply_tangential_inverse(
        &self,
        ows: &mut OperatorWorkspace,
        [rx, ry]: [&[f64]; 2],
        [zx, zy]: [&mut [f64]; 2],
    ) {
        let index = [
            [Some(0), Some(1), None],
            [Some(1), Some(2), None],
            [None, None, None],
        ];
        apply_indexed(
            &self.tangential_inverse.plan,
            &self.tangential_inverse.spectra,
            &index,
            &mut ows.tangential_pc,
            &[(Component::X, rx), (Component::Y, ry)],
            &mut [(Component::X, zx), (Component::Y, zy)],
        );
    }
}

multiversion! {
    /// The product of [`KernelSet::apply`] with the kernels `spectra` (entry
    /// `index[o][c]` for output o and input c) on `plan`, in precision `T`
    /// (with AVX2 and FMA when the CPU has them: `core::simd`).
    fn apply_indexed<T: Real>(
        plan: &ConvolutionPlan<T>,
        spectra: &[Spectrum<T>],
        index: &[[Option<usize>; 3]; 3],
        bufs: &mut Buffers<T>,
        inputs: &[(Component, &[f64])],
        outputs: &mut [(Component, &mut [f64])],
    ) => apply_indexed_body
}

#[inline(always)]
fn apply_indexed_body<T: Real>(
    plan: &ConvolutionPlan<T>,
    spectra: &[Spectrum<T>],
    index: &[[Option<usize>; 3]; 3],
    bufs: &mut Buffers<T>,
    inputs: &[(Component, &[f64])],
    outputs: &mut [(Component, &mut [f64])],
) {
    let (ny, py, nkx) = (plan.ny, plan.py, plan.nkx);
    debug_assert!(inputs
        .iter()
        .enumerate()
        .all(|(a, x)| inputs[..a].iter().all(|y| y.0 != x.0)));
    debug_assert!(outputs
        .iter()
        .enumerate()
        .all(|(a, x)| outputs[..a].iter().all(|y| y.0 != x.0)));
    let Buffers {
        ws,
        spec,
        out: outspec,
        block,
    } = bufs;
    // used[c]: input c feeds a requested output; active[o]: output o has
    // at least one term; in_place[o]: its result goes to spec[o] (the
    // input of the same component, dead once the block's products are
    // done) rather than to outspec[o].
    let mut used = [false; 3];
    let mut active = [false; 3];
    for (o, _) in outputs.iter() {
        for (c, _) in inputs {
            if index[*o as usize][*c as usize].is_some() {
                used[*c as usize] = true;
                active[*o as usize] = true;
            }
        }
    }
    let mut in_place = [false; 3];
    for (o, _) in outputs.iter() {
        in_place[*o as usize] = used[*o as usize];
    }
    // The tangential block (X, Y) -> (X, Y) with one shared K_xy = K_yx:
    // one pass for both outputs.
    let xy = match (index[0][0], index[0][1], index[1][1]) {
        (Some(xx), Some(xy), Some(yy))
            if used == [true, true, false]
                && active == [true, true, false]
                && index[1][0] == Some(xy) =>
        {
            Some((xx, xy, yy))
        }
        _ => None,
    };
    let offsets = &plan.block_offsets[..];
    for (c, field) in inputs {
        debug_assert_eq!(field.len(), plan.nx * plan.ny);
        if used[*c as usize] {
            plan.rows_forward(ws, field, &mut spec[*c as usize], |k| offsets[k]);
        }
    }
    if active.iter().any(|&a| a) {
        let stride = COLUMN_BLOCK * py + BLOCK_GAP;
        for (b, kx0) in (0..nkx).step_by(COLUMN_BLOCK).enumerate() {
            let len = COLUMN_BLOCK.min(nkx - kx0) * py;
            let at = b * stride;
            let kat = kx0 * py;
            for (c, _) in inputs {
                let c = *c as usize;
                if !used[c] {
                    continue;
                }
                let cols = &mut spec[c][at..at + len];
                for col in cols.chunks_exact_mut(py) {
                    col[ny..].fill(czero());
                }
                plan.fwd.process_with_scratch(cols, &mut ws.scratch);
            }
            if let Some((xx, xy, yy)) = xy {
                let [bx, by, _] = block;
                let (bx, by) = (&mut bx[..len], &mut by[..len]);
                let (sx, sy) = (&spec[0][at..at + len], &spec[1][at..at + len]);
                let r = kat..kat + len;
                match (&spectra[xx], &spectra[xy], &spectra[yy]) {
                    (Spectrum::Real(kxx), Spectrum::Real(kxy), Spectrum::Real(kyy)) => {
                        for ((((dx, dy), (&x, &y)), (&kxx, &kxy)), &kyy) in bx
                            .iter_mut()
                            .zip(by.iter_mut())
                            .zip(sx.iter().zip(sy))
                            .zip(kxx[r.clone()].iter().zip(&kxy[r.clone()]))
                            .zip(&kyy[r])
                        {
                            *dx = x * kxx + y * kxy;
                            *dy = x * kxy + y * kyy;
                        }
                    }
                    (Spectrum::Complex(kxx), Spectrum::Complex(kxy), Spectrum::Complex(kyy)) => {
                        for ((((dx, dy), (&x, &y)), (&kxx, &kxy)), &kyy) in bx
                            .iter_mut()
                            .zip(by.iter_mut())
                            .zip(sx.iter().zip(sy))
                            .zip(kxx[r.clone()].iter().zip(&kxy[r.clone()]))
                            .zip(&kyy[r])
                        {
                            *dx = kxx * x + kxy * y;
                            *dy = kxy * x + kyy * y;
                        }
                    }
                    (kxx, kxy, kyy) => {
                        kxx.apply(kat, sx, bx, true);
                        kxy.apply(kat, sy, bx, false);
                        kxy.apply(kat, sx, by, true);
                        kyy.apply(kat, sy, by, false);
                    }
                }
            }
            for (o, _) in outputs.iter() {
                let o = *o as usize;
                if !active[o] || xy.is_some() {
                    continue;
                }
                let dst = &mut block[o][..len];
                let mut first = true;
                for (c, _) in inputs {
                    let c = *c as usize;
                    if let Some(k) = index[o][c] {
                        spectra[k].apply(kat, &spec[c][at..at + len], dst, first);
                        first = false;
                    }
                }
            }
            for (o, _) in outputs.iter() {
                let o = *o as usize;
                if !active[o] {
                    continue;
                }
                let dst = if in_place[o] {
                    &mut spec[o][at..at + len]
                } else {
                    &mut outspec[o][at..at + len]
                };
                plan.inv.process_outofplace_with_scratch(
                    &mut block[o][..len],
                    dst,
                    &mut ws.scratch,
                );
            }
        }
    }
    for (o, out) in outputs.iter_mut() {
        let o = *o as usize;
        debug_assert_eq!(out.len(), plan.nx * plan.ny);
        if !active[o] {
            out.fill(0.0);
            continue;
        }
        let src = if in_place[o] { &spec[o] } else { &outspec[o] };
        plan.rows_inverse(ws, src, |k| offsets[k], out);
    }
}

/// The rows of a periodic array holding `ny` rows: `fast(ny)`, or 1 for
/// the single row of a line contact (whose kernels do not depend on y:
/// a periodic neighbour row would count the same strip twice).
fn periodic_rows(ny: usize, fast: fn(usize) -> usize) -> usize {
    if ny == 1 {
        1
    } else {
        fast(ny)
    }
}

/// The spectrum, in the normalisation of [`ConvolutionPlan::kernel_spectrum`],
/// of the inverse of the circulant of the symmetric kernel `k` on the
/// periodic `px` x `py` array of `pc` (offsets wrapped to |o| <= p/2): its
/// eigenvalues lambda are the kernel's transform, bounded below by the one
/// at the highest frequency (both Nyquist indices; the truncated kernel's
/// transform dips below it at a few frequencies, and can turn negative for
/// elongated elements); the inverse's spectrum is 1/(lambda px py).
fn periodic_inverse(pc: &ConvolutionPlan, k: impl Fn(i64, i64) -> f64) -> Vec<Complex64> {
    let mut spec = periodic_symbol(pc, k);
    let s = (pc.px * pc.py) as f64;
    let floor = symbol_floor(pc, &spec);
    for v in &mut spec {
        *v = Complex64::new(1.0 / (v.re.max(floor) * s), 0.0);
    }
    spec
}

/// The lower bound of a periodic symbol `spec` of `pc`: its value at the
/// highest frequency (both Nyquist indices), or, should that not be
/// positive (not expected for a positive definite kernel), 1e-3 of its
/// largest value.
fn symbol_floor(pc: &ConvolutionPlan, spec: &[Complex64]) -> f64 {
    let top = spec[(pc.nkx - 1) * pc.py + pc.py / 2].re;
    // Negated so that NaN takes the fallback too.
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    if !(top > 0.0) {
        return 1e-3 * spec.iter().fold(0.0f64, |m, v| m.max(v.re));
    }
    top
}

/// The transform of the kernel `k` wrapped on the periodic `px` x `py`
/// array of `pc` (offsets wrapped to |o| <= p/2): the eigenvalues of its
/// circulant (real for kernels even in (ox, oy) together).
fn periodic_symbol(pc: &ConvolutionPlan, k: impl Fn(i64, i64) -> f64) -> Vec<Complex64> {
    let (px, py) = (pc.px, pc.py);
    let wrap = |j: usize, p: usize| {
        if 2 * j <= p {
            j as i64
        } else {
            j as i64 - p as i64
        }
    };
    let mut ws = pc.workspace();
    let mut spec = vec![Complex64::new(0.0, 0.0); pc.spectrum_len()];
    for jy in 0..py {
        for jx in 0..px {
            ws.row[jx] = k(wrap(jx, px), wrap(jy, py));
        }
        let _ = pc
            .r2c
            .process_with_scratch(&mut ws.row, &mut ws.rowspec, &mut ws.r2c_scratch);
        for kx in 0..pc.nkx {
            spec[kx * py + jy] = ws.rowspec[kx];
        }
    }
    pc.fwd.process_with_scratch(&mut spec, &mut ws.scratch);
    spec
}

/// The spectra (xx, xy, yy), in the normalisation of
/// [`ConvolutionPlan::kernel_spectrum`], of the inverse of the circulant of
/// the 2x2 tangential block (kernels `k(i, j, ox, oy)`, each even in (ox,
/// oy) together, so that the symbols are real) on the periodic array of
/// `pc`. At each frequency the real symmetric 2x2 symbol is inverted, its
/// diagonal first bounded below by [`symbol_floor`] (as in
/// [`periodic_inverse`]) and its off-diagonal term bounded by 0.9 of the
/// diagonal's geometric mean, which keeps the symbol positive definite.
fn periodic_inverse_2x2(
    pc: &ConvolutionPlan,
    k: impl Fn(Component, Component, i64, i64) -> f64,
) -> [Vec<Complex64>; 3] {
    let (x, y) = (Component::X, Component::Y);
    let mut a = periodic_symbol(pc, |ox, oy| k(x, x, ox, oy));
    let mut b = periodic_symbol(pc, |ox, oy| k(x, y, ox, oy));
    let mut c = periodic_symbol(pc, |ox, oy| k(y, y, ox, oy));
    let s = (pc.px * pc.py) as f64;
    let (fa, fc) = (symbol_floor(pc, &a), symbol_floor(pc, &c));
    for ((va, vb), vc) in a.iter_mut().zip(b.iter_mut()).zip(c.iter_mut()) {
        let (aa, cc) = (va.re.max(fa), vc.re.max(fc));
        let bb = vb.re.clamp(-0.9 * (aa * cc).sqrt(), 0.9 * (aa * cc).sqrt());
        let det = (aa * cc - bb * bb) * s;
        *va = Complex64::new(cc / det, 0.0);
        *vb = Complex64::new(-bb / det, 0.0);
        *vc = Complex64::new(aa / det, 0.0);
    }
    [a, b, c]
}

/// Buffers of one plan for [`apply_indexed`].
#[derive(Clone)]
struct Buffers<T: Real> {
    ws: Workspace<T>,
    /// Spectra of the inputs by component, in the blocked layout; the
    /// results of outputs of the same component replace them.
    spec: [Vec<Complex<T>>; 3],
    /// Spectra of outputs whose component is not among the used inputs.
    out: [Vec<Complex<T>>; 3],
    /// Spectral products of one block of columns, by output component.
    block: [Vec<Complex<T>>; 3],
}

impl<T: Real> Buffers<T> {
    fn new(p: &ConvolutionPlan<T>) -> Self {
        let z = czero::<T>();
        Self {
            ws: p.workspace(),
            spec: std::array::from_fn(|_| vec![z; p.block_len]),
            out: std::array::from_fn(|_| vec![z; p.block_len]),
            block: std::array::from_fn(|_| vec![z; COLUMN_BLOCK * p.py]),
        }
    }
}

impl<T: Real> HeapBytes for Buffers<T> {
    fn heap_bytes(&self) -> usize {
        heap_bytes!(self.ws, self.spec, self.out, self.block)
    }
}

/// Buffers for [`KernelSet::apply`], [`KernelSet::apply_with`] and
/// [`KernelSet::apply_normal_inverse`] (from [`KernelSet::workspace`]).
#[derive(Clone)]
pub struct OperatorWorkspace {
    /// Grid (nx, ny) of the plan, and whether `pc` is there.
    shape: (usize, usize, bool),
    main: Buffers<f64>,
    /// Buffers of the normal preconditioner's plan.
    pc: Option<Box<Buffers<f64>>>,
    /// Buffers of the single-precision plan.
    single: Box<Buffers<f32>>,
    /// Buffers of the tangential preconditioner's plan.
    tangential_pc: Box<Buffers<f32>>,
    /// The row-by-row products of a set with one matrix per loaded row.
    rows: Option<Box<RowScratch>>,
}

/// Buffers of [`KernelSet::apply_with`] for a set with one matrix per
/// loaded row: up to three inputs restricted to one row, and the outputs
/// of that row's product.
#[derive(Clone)]
struct RowScratch {
    masked: [Vec<f64>; 3],
    out: [Vec<f64>; 3],
}

impl RowScratch {
    fn new(n: usize) -> Self {
        Self {
            masked: std::array::from_fn(|_| vec![0.0; n]),
            out: std::array::from_fn(|_| vec![0.0; n]),
        }
    }
}

impl HeapBytes for RowScratch {
    fn heap_bytes(&self) -> usize {
        heap_bytes!(self.masked, self.out)
    }
}

multiversion! {
    /// `out += sum_k K(., J_k - offset) c_k` for the real-space table
    /// `values` of a kernel on an `nx x ny` grid, output row by output row
    /// (the row stays in the first-level cache while the columns add to
    /// it, each column in the order given).
    fn add_columns(
        values: &[f64],
        nx: usize,
        ny: usize,
        columns: &[(usize, f64)],
        offset: usize,
        out: &mut [f64],
    ) => add_columns_body
}

#[inline(always)]
fn add_columns_body(
    values: &[f64],
    nx: usize,
    ny: usize,
    columns: &[(usize, f64)],
    offset: usize,
    out: &mut [f64],
) {
    let w = 2 * nx - 1;
    for (ty, row) in out.chunks_exact_mut(nx).take(ny).enumerate() {
        for &(j, c) in columns {
            let j = j - offset;
            let (sx, sy) = (j % nx, j / nx);
            // Offset (tx - sx, ty - sy) lies at (tx - sx + nx - 1, ty - sy
            // + ny - 1) of the table: tx = 0..nx is one contiguous run.
            let start = (ty + ny - 1 - sy) * w + (nx - 1 - sx);
            for (o, &k) in row.iter_mut().zip(&values[start..start + nx]) {
                *o += c * k;
            }
        }
    }
}

/// The buffers of all four plans (not the kernels, which the set holds).
impl HeapBytes for OperatorWorkspace {
    fn heap_bytes(&self) -> usize {
        heap_bytes!(
            self.main,
            self.pc,
            self.single,
            self.tangential_pc,
            self.rows
        )
    }
}

/// The dense influence matrix of `set` for the listed components, row
/// (component a, element I) = a * N + I. For tests and small checks only: it
/// costs O(N²) memory.
pub fn dense_matrix(set: &KernelSet, comps: &[Component]) -> faer::Mat<f64> {
    let (nx, ny) = (set.plan.nx, set.plan.ny);
    let n = nx * ny;
    faer::Mat::from_fn(comps.len() * n, comps.len() * n, |r, c| {
        let (a, i) = (r / n, r % n);
        let (b, j) = (c / n, c % n);
        let (ix, iy) = ((i % nx) as i64, (i / nx) as i64);
        let (jx, jy) = ((j % nx) as i64, (j / nx) as i64);
        if set.has(comps[a], comps[b]) {
            set.value(comps[a], comps[b], ix - jx, iy - jy)
        } else {
            0.0
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::material::{CombinedMaterial, Material};

    fn lcg(seed: &mut u64) -> f64 {
        *seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((*seed >> 11) as f64) / ((1u64 << 53) as f64) - 0.5
    }

    fn dissimilar() -> CombinedMaterial {
        CombinedMaterial::new(
            Material {
                shear_modulus_pa: 80e9,
                poisson_ratio: 0.28,
            },
            Material {
                shear_modulus_pa: 50e9,
                poisson_ratio: 0.33,
            },
        )
        .unwrap()
    }

    fn check_fft_equals_dense(nx: usize, ny: usize, kind: KernelKind) {
        let m = dissimilar();
        let ic = HalfSpaceInfluence::new(1e-4, 1.3e-4, &m);
        let plan = Arc::new(ConvolutionPlan::new(nx, ny));
        let set = KernelSet::new(plan, ic, kind);
        let n = nx * ny;
        let mut seed = 7u64;
        let p: Vec<Vec<f64>> = (0..3)
            .map(|_| (0..n).map(|_| 1e6 * lcg(&mut seed)).collect())
            .collect();
        let mut ows = set.workspace();
        let mut u = vec![vec![0.0; n]; 3];
        {
            let (u0, rest) = u.split_at_mut(1);
            let (u1, u2) = rest.split_at_mut(1);
            set.apply(
                &mut ows,
                &[
                    (Component::X, &p[0]),
                    (Component::Y, &p[1]),
                    (Component::N, &p[2]),
                ],
                &mut [
                    (Component::X, &mut u0[0]),
                    (Component::Y, &mut u1[0]),
                    (Component::N, &mut u2[0]),
                ],
            );
        }
        let comps = [Component::X, Component::Y, Component::N];
        let a = dense_matrix(&set, &comps);
        let pv = faer::Col::<f64>::from_fn(3 * n, |r| p[r / n][r % n]);
        let ud = &a * &pv;
        let mut err: f64 = 0.0;
        let mut norm: f64 = 0.0;
        for r in 0..3 * n {
            err = err.max((ud[r] - u[r / n][r % n]).abs());
            norm = norm.max(ud[r].abs());
        }
        assert!(
            err <= 1e-10 * norm,
            "{nx}x{ny} {kind:?}: max err {err:e} vs {norm:e}"
        );
    }

    #[test]
    fn fft_matvec_equals_dense_matvec() {
        check_fft_equals_dense(12, 9, KernelKind::Displacement);
        check_fft_equals_dense(7, 16, KernelKind::Displacement);
        check_fft_equals_dense(11, 10, KernelKind::SteadyRolling);
    }

    /// A few columns of the normal kernel added from the real-space table
    /// equal the dense matrix's columns (to rounding), on a rectangular
    /// grid with elements of unequal sides, as part of a larger vector
    /// (offset) and in both kinds.
    #[test]
    fn normal_columns_equal_the_dense_matrix_columns() {
        for (nx, ny, kind) in [
            (13, 7, KernelKind::Displacement),
            (6, 11, KernelKind::SteadyRolling),
        ] {
            let ic = HalfSpaceInfluence::new(1e-4, 1.3e-4, &dissimilar());
            let set = KernelSet::new(Arc::new(ConvolutionPlan::new(nx, ny)), ic, kind);
            let n = nx * ny;
            let offset = 5;
            let columns = [
                (offset, 2e6),
                (offset + nx + 2, -1e6),
                (offset + n - 1, 3e5),
            ];
            let mut seed = 3u64;
            let start: Vec<f64> = (0..n).map(|_| 1e-6 * lcg(&mut seed)).collect();
            let mut out = start.clone();
            assert!(set.add_normal_columns(&columns, offset, &mut out));
            let a = dense_matrix(&set, &[Component::N]);
            let (mut err, mut norm) = (0.0f64, 0.0f64);
            for i in 0..n {
                let want = start[i]
                    + columns
                        .iter()
                        .map(|&(j, c)| a[(i, j - offset)] * c)
                        .sum::<f64>();
                err = err.max((out[i] - want).abs());
                norm = norm.max(want.abs());
            }
            assert!(err <= 1e-14 * norm, "{nx}x{ny}: {err:e} of {norm:e}");
            assert!(set.normal_column_limit() > 0);
        }
    }

    /// Every input/output combination the solvers use (and a few more),
    /// against the dense product, for coupled and uncoupled materials, odd and
    /// even grid sizes, and both kernel kinds; also the public
    /// forward/inverse pair against the same product.
    #[test]
    fn fft_matvec_subsets_equal_dense_matvec() {
        use Component::{N, X, Y};
        let combos: [(&[Component], &[Component]); 8] = [
            (&[N], &[N]),
            (&[X, Y], &[X, Y]),
            (&[Y, X], &[Y, X]),
            (&[X, Y, N], &[X, Y]),
            (&[X, Y], &[N]),
            (&[N], &[X, Y]),
            (&[X], &[Y, N]),
            (&[N, Y], &[X, Y, N]),
        ];
        let steel = CombinedMaterial::identical(Material::STEEL).unwrap();
        for m in [dissimilar(), steel] {
            for (nx, ny, kind) in [
                (9, 7, KernelKind::Displacement),
                (8, 13, KernelKind::SteadyRolling),
                (1, 5, KernelKind::Displacement),
                (6, 1, KernelKind::SteadyRolling),
                (5, 6, KernelKind::Displacement),
            ] {
                let ic = HalfSpaceInfluence::new(1e-4, 1.3e-4, &m);
                let plan = Arc::new(ConvolutionPlan::new(nx, ny));
                let set = KernelSet::new(plan.clone(), ic, kind);
                let n = nx * ny;
                let mut seed = 11u64;
                let p: Vec<Vec<f64>> = (0..3)
                    .map(|_| (0..n).map(|_| 1e6 * lcg(&mut seed)).collect())
                    .collect();
                let a = dense_matrix(&set, &COMPONENTS);
                let pv = |ins: &[Component]| {
                    faer::Col::<f64>::from_fn(3 * n, |r| {
                        let c = COMPONENTS[r / n];
                        if ins.contains(&c) {
                            p[c as usize][r % n]
                        } else {
                            0.0
                        }
                    })
                };
                let mut ows = set.workspace();
                for (ins, outs) in combos {
                    let ud = &a * &pv(ins);
                    let inputs: Vec<(Component, &[f64])> =
                        ins.iter().map(|&c| (c, &p[c as usize][..])).collect();
                    let mut u = vec![vec![f64::NAN; n]; outs.len()];
                    let mut outputs: Vec<(Component, &mut [f64])> = outs
                        .iter()
                        .zip(u.iter_mut())
                        .map(|(&c, v)| (c, &mut v[..]))
                        .collect();
                    set.apply(&mut ows, &inputs, &mut outputs);
                    let norm = (0..3 * n).fold(0.0f64, |s, r| s.max(ud[r].abs()));
                    for (&c, v) in outs.iter().zip(&u) {
                        for i in 0..n {
                            let e = (v[i] - ud[c as usize * n + i]).abs();
                            assert!(
                                e <= 1e-10 * norm,
                                "{nx}x{ny} {kind:?} {ins:?} -> {outs:?}: {c:?}[{i}] err {e:e} vs {norm:e}"
                            );
                        }
                    }
                }
                // Public transforms: inverse(K_nn * forward(p_n)).
                let mut ws = plan.workspace();
                let k = plan.kernel_spectrum(&mut ws, |ox, oy| ic.kernel(kind, N, N, ox, oy));
                let mut spec = vec![Complex64::new(0.0, 0.0); plan.spectrum_len()];
                plan.forward(&mut ws, &p[2], &mut spec);
                for (s, k) in spec.iter_mut().zip(&k) {
                    *s *= k;
                }
                let mut u = vec![0.0; n];
                plan.inverse(&mut ws, &mut spec, &mut u);
                let ud = &a * &pv(&[N]);
                let norm = (0..3 * n).fold(0.0f64, |s, r| s.max(ud[r].abs()));
                for i in 0..n {
                    assert!(
                        (u[i] - ud[2 * n + i]).abs() <= 1e-10 * norm,
                        "forward/inverse {i}"
                    );
                }
            }
        }
    }

    /// The single-precision product against the double one: the
    /// difference stays within a small multiple of f32's rounding (6e-8)
    /// of the largest output, for both kernel kinds, coupled materials and
    /// grids whose f32 padding differs from the f64 one.
    #[test]
    fn single_precision_product_is_close_to_the_double_one() {
        use Component::{N, X, Y};
        let steel = CombinedMaterial::identical(Material::STEEL).unwrap();
        for (m, nx, ny, kind) in [
            (steel, 48, 44, KernelKind::Displacement),
            (dissimilar(), 23, 31, KernelKind::SteadyRolling),
            (dissimilar(), 64, 64, KernelKind::Displacement),
            (steel, 128, 100, KernelKind::Displacement),
        ] {
            let ic = HalfSpaceInfluence::new(1e-4, 1.3e-4, &m);
            let set = KernelSet::new(Arc::new(ConvolutionPlan::new(nx, ny)), ic, kind);
            let n = nx * ny;
            let mut seed = 5u64;
            let p: Vec<Vec<f64>> = (0..3)
                .map(|_| (0..n).map(|_| 1e6 * lcg(&mut seed)).collect())
                .collect();
            let mut ows = set.workspace();
            let ins = [(X, &p[0][..]), (Y, &p[1][..]), (N, &p[2][..])];
            let (mut a, mut b) = (vec![vec![0.0; n]; 3], vec![vec![0.0; n]; 3]);
            for (u, single) in [(&mut a, false), (&mut b, true)] {
                let [ux, uy, un] = &mut u[..] else {
                    unreachable!()
                };
                let mut outs = [(X, &mut ux[..]), (Y, &mut uy[..]), (N, &mut un[..])];
                if single {
                    set.apply_with(Precision::Single, &mut ows, &ins, &mut outs);
                } else {
                    set.apply(&mut ows, &ins, &mut outs);
                }
            }
            let norm = a.iter().flatten().fold(0.0f64, |s, v| s.max(v.abs()));
            let err = a
                .iter()
                .flatten()
                .zip(b.iter().flatten())
                .fold(0.0f64, |s, (x, y)| s.max((x - y).abs()));
            eprintln!(
                "{nx}x{ny} {kind:?}: single-precision error {:.2e}",
                err / norm
            );
            assert!(
                err <= 1e-6 * norm,
                "{nx}x{ny} {kind:?}: {err:e} vs {norm:e}"
            );
            assert!(err > 0.0, "the product did run in single precision");
        }
    }

    #[test]
    fn steady_kernel_is_the_upwind_difference_of_the_displacement_kernel() {
        // (A(X) - A(X + dx))/dx p = (A p - A S p)/dx, S the shift by one
        // element upstream, when p vanishes on the trailing column (the
        // driver relies on this: loaded elements never touch the border).
        let m = dissimilar();
        let (nx, ny, dx) = (9, 7, 1e-4);
        let ic = HalfSpaceInfluence::new(dx, 1.3e-4, &m);
        let plan = Arc::new(ConvolutionPlan::new(nx, ny));
        let steady = KernelSet::new(plan.clone(), ic, KernelKind::SteadyRolling);
        let disp = KernelSet::new(plan, ic, KernelKind::Displacement);
        let grid = crate::core::grid::Grid::new(nx, ny, dx, 1.3e-4, 0.0, 0.0).unwrap();
        let mut seed = 3u64;
        let mut p: Vec<f64> = (0..nx * ny).map(|_| 1e6 * lcg(&mut seed)).collect();
        for iy in 0..ny {
            p[iy * nx] = 0.0;
        }
        let mut sp = vec![0.0; nx * ny];
        crate::core::tangential::shift_upstream(&grid, 1, &p, &mut sp);
        let (mut b, mut a, mut a_s) = (vec![0.0; nx * ny], vec![0.0; nx * ny], vec![0.0; nx * ny]);
        let mut ws = steady.workspace();
        steady.apply(
            &mut ws,
            &[(Component::N, &p)],
            &mut [(Component::X, &mut b)],
        );
        disp.apply(
            &mut ws,
            &[(Component::N, &p)],
            &mut [(Component::X, &mut a)],
        );
        disp.apply(
            &mut ws,
            &[(Component::N, &sp)],
            &mut [(Component::X, &mut a_s)],
        );
        let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for i in 0..nx * ny {
            assert!(
                (b[i] - (a[i] - a_s[i]) / dx).abs() <= 1e-9 * scale,
                "element {i}"
            );
        }
    }

    #[test]
    fn fast_sizes() {
        assert_eq!(fast_even_size(127), 128);
        assert_eq!(fast_even_size(87), 90);
        assert_eq!(fast_even_size(95), 96);
        assert_eq!(fast_even_size_single(87), 96);
        assert_eq!(fast_even_size_single(127), 128);
        assert_eq!(fast_even_size_single(63), 64);
        assert_eq!(fast_even_size_single(129), 144);
        assert_eq!(fast_even_size_single(79), 80);
        assert_eq!(fast_even_size_single(39), 48);
        assert_eq!(fast_even_size_single(119), 128);
        assert_eq!(fast_even_size_single(150), 160);
        assert_eq!(fast_even_size_single(3), 4);
    }
}
