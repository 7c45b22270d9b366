//! Zero-padded 2-D convolutions by real FFTs, and the influence-coefficient
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
//! kx contiguous (`spec[kx * py + ky]`). Rows of the field are transformed by
//! a real-to-complex FFT (only the `ny` non-zero rows), columns by a complex FFT;
//! the inverse transforms all columns and then only the `ny` rows that are kept.

use std::sync::Arc;

use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::num_complex::Complex64;
use rustfft::{Fft, FftPlanner};

use crate::core::influence::{Component, HalfSpaceInfluence, KernelKind};

/// Smallest even 2-3-5-smooth number >= n (fast FFT sizes).
pub fn fast_even_size(n: usize) -> usize {
    let mut m = n.max(2);
    loop {
        if m % 2 == 0 {
            let mut k = m;
            for p in [2, 3, 5] {
                while k % p == 0 {
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

/// FFT plans for one grid size (immutable, shareable).
pub struct ConvolutionPlan {
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
    r2c: Arc<dyn RealToComplex<f64>>,
    c2r: Arc<dyn ComplexToReal<f64>>,
    fwd: Arc<dyn Fft<f64>>,
    inv: Arc<dyn Fft<f64>>,
}

impl std::fmt::Debug for ConvolutionPlan {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "ConvolutionPlan({}x{} padded {}x{})",
            self.nx, self.ny, self.px, self.py
        )
    }
}

/// Scratch buffers for one thread using a [`ConvolutionPlan`].
pub struct Workspace {
    row: Vec<f64>,
    rowspec: Vec<Complex64>,
    r2c_scratch: Vec<Complex64>,
    c2r_scratch: Vec<Complex64>,
    col_scratch: Vec<Complex64>,
}

impl ConvolutionPlan {
    /// Plans for an `nx` x `ny` grid.
    pub fn new(nx: usize, ny: usize) -> Self {
        let px = fast_even_size(2 * nx - 1);
        let py = fast_even_size(2 * ny - 1);
        let mut rp = RealFftPlanner::<f64>::new();
        let mut cp = FftPlanner::<f64>::new();
        Self {
            nx,
            ny,
            px,
            py,
            nkx: px / 2 + 1,
            r2c: rp.plan_fft_forward(px),
            c2r: rp.plan_fft_inverse(px),
            fwd: cp.plan_fft_forward(py),
            inv: cp.plan_fft_inverse(py),
        }
    }

    /// Length of a spectrum buffer.
    pub fn spectrum_len(&self) -> usize {
        self.nkx * self.py
    }

    /// Allocates the scratch buffers for this plan.
    pub fn workspace(&self) -> Workspace {
        let zero = Complex64::new(0.0, 0.0);
        Workspace {
            row: vec![0.0; self.px],
            rowspec: vec![zero; self.nkx],
            r2c_scratch: vec![zero; self.r2c.get_scratch_len()],
            c2r_scratch: vec![zero; self.c2r.get_scratch_len()],
            col_scratch: vec![
                zero;
                self.fwd
                    .get_inplace_scratch_len()
                    .max(self.inv.get_inplace_scratch_len())
            ],
        }
    }

    /// Spectrum of an `nx*ny` field (zero-padded). No allocation.
    pub fn forward(&self, ws: &mut Workspace, field: &[f64], spec: &mut [Complex64]) {
        debug_assert_eq!(field.len(), self.nx * self.ny);
        debug_assert_eq!(spec.len(), self.spectrum_len());
        let (nx, ny, py) = (self.nx, self.ny, self.py);
        for iy in 0..ny {
            ws.row[..nx].copy_from_slice(&field[iy * nx..(iy + 1) * nx]);
            ws.row[nx..].fill(0.0);
            // Lengths are consistent by construction; realfft only fails on
            // mismatched lengths.
            let _ =
                self.r2c
                    .process_with_scratch(&mut ws.row, &mut ws.rowspec, &mut ws.r2c_scratch);
            for (kx, v) in ws.rowspec.iter().enumerate() {
                spec[kx * py + iy] = *v;
            }
        }
        for kx in 0..self.nkx {
            spec[kx * py + ny..(kx + 1) * py].fill(Complex64::new(0.0, 0.0));
        }
        self.fwd.process_with_scratch(spec, &mut ws.col_scratch);
    }

    /// Field (first `nx*ny` of the padded array) of a spectrum; `spec` is
    /// overwritten. No allocation.
    pub fn inverse(&self, ws: &mut Workspace, spec: &mut [Complex64], out: &mut [f64]) {
        debug_assert_eq!(out.len(), self.nx * self.ny);
        let (nx, ny, py, nkx) = (self.nx, self.ny, self.py, self.nkx);
        self.inv.process_with_scratch(spec, &mut ws.col_scratch);
        for iy in 0..ny {
            for kx in 0..nkx {
                ws.rowspec[kx] = spec[kx * py + iy];
            }
            // The DC and Nyquist bins of a real signal are real; drop rounding noise.
            ws.rowspec[0].im = 0.0;
            ws.rowspec[nkx - 1].im = 0.0;
            let _ =
                self.c2r
                    .process_with_scratch(&mut ws.rowspec, &mut ws.row, &mut ws.c2r_scratch);
            out[iy * nx..(iy + 1) * nx].copy_from_slice(&ws.row[..nx]);
        }
    }

    /// Spectrum of the kernel `k(ox, oy)` for element offsets |ox| < nx,
    /// |oy| < ny, normalised so that `inverse(K * forward(p))` is the plain
    /// Toeplitz product.
    pub fn kernel_spectrum(
        &self,
        ws: &mut Workspace,
        k: impl Fn(i64, i64) -> f64,
    ) -> Vec<Complex64> {
        let (px, py, nkx) = (self.px, self.py, self.nkx);
        let scale = 1.0 / (px * py) as f64;
        let mut spec = vec![Complex64::new(0.0, 0.0); self.spectrum_len()];
        for jy in 0..py {
            let oy = if jy < self.ny {
                Some(jy as i64)
            } else if jy + self.ny > py {
                Some(jy as i64 - py as i64)
            } else {
                None
            };
            ws.row.fill(0.0);
            if let Some(oy) = oy {
                for jx in 0..px {
                    let ox = if jx < self.nx {
                        jx as i64
                    } else if jx + self.nx > px {
                        jx as i64 - px as i64
                    } else {
                        continue;
                    };
                    ws.row[jx] = k(ox, oy) * scale;
                }
            }
            let _ =
                self.r2c
                    .process_with_scratch(&mut ws.row, &mut ws.rowspec, &mut ws.r2c_scratch);
            for kx in 0..nkx {
                spec[kx * py + jy] = ws.rowspec[kx];
            }
        }
        self.fwd
            .process_with_scratch(&mut spec, &mut ws.col_scratch);
        spec
    }
}

const COMPONENTS: [Component; 3] = [Component::X, Component::Y, Component::N];

/// The transformed influence kernels of one operator kind for one grid size,
/// spacing and material pair. Immutable after construction.
pub struct KernelSet {
    /// FFT plans.
    pub plan: Arc<ConvolutionPlan>,
    /// Which operator this is.
    pub kind: KernelKind,
    /// The closed-form coefficients the kernels were built from.
    pub influence: HalfSpaceInfluence,
    spectra: [[Option<Vec<Complex64>>; 3]; 3],
    /// Largest eigenvalue of the 2x2 tangential symbol over all frequencies:
    /// an upper bound of the spectral norm of the tangential block [m/Pa].
    pub tangential_norm_bound: f64,
}

impl std::fmt::Debug for KernelSet {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "KernelSet({:?}, {:?})", self.kind, self.plan)
    }
}

impl KernelSet {
    /// Builds and transforms all kernels (tangential block, normal, and the
    /// normal/tangential coupling when the materials differ).
    pub fn new(
        plan: Arc<ConvolutionPlan>,
        influence: HalfSpaceInfluence,
        kind: KernelKind,
    ) -> Self {
        let mut ws = plan.workspace();
        let coupled = influence.coupled();
        let mut spectra: [[Option<Vec<Complex64>>; 3]; 3] = Default::default();
        for (a, &i) in COMPONENTS.iter().enumerate() {
            for (b, &j) in COMPONENTS.iter().enumerate() {
                let needed = (a < 2 && b < 2) || (a == 2 && b == 2) || coupled;
                if !needed {
                    continue;
                }
                if a == 1 && b == 0 {
                    // A_yx(X) = A_xy(X) (both are nu F_xy): reuse below.
                    continue;
                }
                spectra[a][b] = Some(
                    plan.kernel_spectrum(&mut ws, |ox, oy| influence.kernel(kind, i, j, ox, oy)),
                );
            }
        }
        spectra[1][0] = spectra[0][1].clone();
        let mut bound: f64 = 0.0;
        if let (Some(kxx), Some(kxy), Some(kyy)) = (&spectra[0][0], &spectra[0][1], &spectra[1][1])
        {
            let s = (plan.px * plan.py) as f64;
            for k in 0..kxx.len() {
                // Hermitian part's largest eigenvalue bounds the symbol's
                // action for symmetric kernels (Displacement kind).
                let (a, d, b) = (kxx[k].norm(), kyy[k].norm(), kxy[k].norm());
                let lam = 0.5 * (a + d) + (0.25 * (a - d) * (a - d) + b * b).sqrt();
                bound = bound.max(lam * s);
            }
        }
        Self {
            plan,
            kind,
            influence,
            spectra,
            tangential_norm_bound: bound,
        }
    }

    /// Allocates the buffers to apply this operator.
    pub fn workspace(&self) -> OperatorWorkspace {
        let n = self.plan.spectrum_len();
        let z = Complex64::new(0.0, 0.0);
        OperatorWorkspace {
            ws: self.plan.workspace(),
            input: [vec![z; n], vec![z; n], vec![z; n]],
            output: [vec![z; n], vec![z; n], vec![z; n]],
        }
    }

    /// The real-space kernel value (i, j) at element offset (ox, oy).
    pub fn value(&self, i: Component, j: Component, ox: i64, oy: i64) -> f64 {
        self.influence.kernel(self.kind, i, j, ox, oy)
    }

    /// True when kernel (i, j) is present (coupling kernels only for K != 0).
    pub fn has(&self, i: Component, j: Component) -> bool {
        self.spectra[i as usize][j as usize].is_some()
    }

    /// `out_i = sum_j K_ij * in_j` for every requested output component and
    /// every given input (absent coupling kernels count as zero). Two forward
    /// and two inverse FFTs for the tangential block; no allocation.
    pub fn apply(
        &self,
        ows: &mut OperatorWorkspace,
        inputs: &[(Component, &[f64])],
        outputs: &mut [(Component, &mut [f64])],
    ) {
        let plan = &*self.plan;
        for (c, field) in inputs {
            plan.forward(&mut ows.ws, field, &mut ows.input[*c as usize]);
        }
        for (oc, out) in outputs.iter_mut() {
            let o = *oc as usize;
            let dst = &mut ows.output[o];
            dst.fill(Complex64::new(0.0, 0.0));
            let mut any = false;
            for (ic, _) in inputs {
                if let Some(k) = &self.spectra[o][*ic as usize] {
                    let src = &ows.input[*ic as usize];
                    for ((d, kk), s) in dst.iter_mut().zip(k.iter()).zip(src.iter()) {
                        *d += kk * s;
                    }
                    any = true;
                }
            }
            if any {
                plan.inverse(&mut ows.ws, dst, out);
            } else {
                out.fill(0.0);
            }
        }
    }
}

/// Buffers for [`KernelSet::apply`].
pub struct OperatorWorkspace {
    ws: Workspace,
    input: [Vec<Complex64>; 3],
    output: [Vec<Complex64>; 3],
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
        crate::core::tangential::shift_upstream(&grid, &p, &mut sp);
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
    }
}
