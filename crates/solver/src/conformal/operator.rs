//! Influence operators of a conformal patch on the curvilinear (x, s) grid.
//!
//! Displacement differences and tractions are in each element's local
//! frame (x, s, n). Two models:
//!
//! * [`InfluenceModel::HalfSpace`] (`cect_halfspace`): the half-space
//!   coefficients used directly with curvilinear distances, u_I = sum_J
//!   A(X_I - X_J) p_J: the planar operator.
//! * [`InfluenceModel::Blanco`] (`cect`): the traction on element J is
//!   decomposed along element I's directions, p' = R(delta_I - delta_J) p_J,
//!   and each component acts through the half-space coefficients (Blanco-
//!   Lorenzo et al. 2018, §2.2, and their Ref. \[23\]):
//!   u_I = sum_J A(X_I - X_J) R(delta_I - delta_J) p_J, where R rotates the
//!   (s, n) components: p'_s = cos D p_s + sin D p_n, p'_n = -sin D p_s +
//!   cos D p_n, D = delta_I - delta_J.
//!
//! Fast Blanco product: with the global components Y = cos(delta_J) p_s -
//! sin(delta_J) p_n and Z = sin(delta_J) p_s + cos(delta_J) p_n of the
//! traction (lateral and vertical), p'_s = c_I Y + s_I Z and p'_n = -s_I Y +
//! c_I Z (c_I = cos delta_I, s_I = sin delta_I), so
//! u_I = [A (p_x, 0, 0)]_I + c_I [A (0, Y, Z)]_I + s_I [A (0, Z, -Y)]_I:
//! three ordinary convolutions with the cached half-space kernels, whatever
//! the contact location.
//!
//! The Newton steps of the tangential solver take the half-space block as
//! an approximate Jacobian of the Blanco one (identical materials; see the
//! `jacobian_product` of the [`crate::core::steady::TangentialOperator`]
//! implementation), while every residual uses the exact product.

use std::sync::Arc;

use crate::core::fft::{KernelSet, OperatorWorkspace, Precision};
use crate::core::influence::Component;
#[cfg(test)]
use crate::core::influence::KernelKind;
use crate::core::memory::{heap_bytes, HeapBytes};
use crate::core::steady::{PlanarTangential, TangentialOperator};

/// Which influence coefficients a conformal solve uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum InfluenceModel {
    /// Half-space coefficients with curvilinear distances.
    HalfSpace,
    /// Blanco's approximation: half-space coefficients combined by the
    /// orientation difference of the elements.
    Blanco,
}

/// The influence operator of one conformal grid (kernels shared, buffers
/// owned; the products do not allocate).
pub struct ConformalOperator {
    kernels: Arc<KernelSet>,
    model: InfluenceModel,
    nx: usize,
    cos: Vec<f64>,
    sin: Vec<f64>,
    ows: OperatorWorkspace,
    b: [Vec<f64>; 9],
    zero: Vec<f64>,
}

/// Its buffers, not its kernels (the cache's).
impl HeapBytes for ConformalOperator {
    fn heap_bytes(&self) -> usize {
        heap_bytes!(self.cos, self.sin, self.ows, self.b, self.zero)
    }
}

impl ConformalOperator {
    /// An operator for a grid whose lateral line `iy` has orientation
    /// `delta_rad[iy]`. With the displacement kernels of the (x, s) grid it
    /// gives displacement differences; with the steady-rolling kernels the
    /// steady-state operator (A - S A)/dx (the rotations do not depend on x).
    pub fn new(kernels: Arc<KernelSet>, model: InfluenceModel, delta_rad: &[f64]) -> Self {
        Self::reusing(None, kernels, model, delta_rad)
    }

    /// [`ConformalOperator::new`], with the buffers of `old` when they fit
    /// the new grid (a solve after another on a grid of the same size
    /// allocates nothing then).
    pub fn reusing(
        old: Option<Self>,
        kernels: Arc<KernelSet>,
        model: InfluenceModel,
        delta_rad: &[f64],
    ) -> Self {
        let (nx, ny) = (kernels.plan.nx, kernels.plan.ny);
        debug_assert_eq!(delta_rad.len(), ny);
        let n = nx * ny;
        let (ows, b, zero) = match old {
            Some(o) if kernels.fits(&o.ows) && o.zero.len() == n => (o.ows, o.b, o.zero),
            _ => (
                kernels.workspace(),
                std::array::from_fn(|_| vec![0.0; n]),
                vec![0.0; n],
            ),
        };
        let (mut cos, mut sin) = (Vec::with_capacity(ny), Vec::with_capacity(ny));
        for d in delta_rad {
            let (s, c) = d.sin_cos();
            cos.push(c);
            sin.push(s);
        }
        Self {
            ows,
            kernels,
            model,
            nx,
            cos,
            sin,
            b,
            zero,
        }
    }

    /// The kernels.
    pub fn kernels(&self) -> &KernelSet {
        &self.kernels
    }

    /// The influence model.
    pub fn model(&self) -> InfluenceModel {
        self.model
    }

    /// The self-influence of the normal component [m/Pa].
    pub fn normal_diagonal(&self) -> f64 {
        self.kernels.value(Component::N, Component::N, 0, 0)
    }

    /// Normal displacement differences of normal pressures alone (the
    /// frictionless problem): for Blanco and identical materials,
    /// u_n,I = sum_J A_nn(X_I - X_J) cos(delta_I - delta_J) p_J. Two FFT
    /// products.
    pub fn apply_normal(&mut self, pn: &[f64], un: &mut [f64]) {
        self.apply_parts(
            Precision::Double,
            Tractions {
                n: Some(pn),
                ..Tractions::default()
            },
            &mut [(Component::N, un)],
        );
    }

    /// All three displacement components of all three traction components
    /// (local frames).
    #[allow(clippy::too_many_arguments)]
    pub fn apply(
        &mut self,
        px: &[f64],
        ps: &[f64],
        pn: &[f64],
        ux: &mut [f64],
        us: &mut [f64],
        un: &mut [f64],
    ) {
        self.apply_parts(
            Precision::Double,
            Tractions {
                x: Some(px),
                s: Some(ps),
                n: Some(pn),
            },
            &mut [(Component::X, ux), (Component::Y, us), (Component::N, un)],
        )
    }

    /// The requested displacement components (`Component::Y` stands for s)
    /// of the given traction components (absent ones are zero), in
    /// `precision`. Only the transforms the request needs are made: for
    /// identical materials the normal displacement of the tangential
    /// tractions (or the tangential ones of the pressures) takes two
    /// forward and two (four) inverse transforms instead of the full
    /// product's three and nine. Components must not repeat within
    /// `outputs` (a repeated one panics: a caller's error, as for
    /// [`KernelSet::apply`]).
    pub fn apply_parts(
        &mut self,
        precision: Precision,
        p: Tractions<'_>,
        outputs: &mut [(Component, &mut [f64])],
    ) {
        let k = &self.kernels;
        if self.model == InfluenceModel::HalfSpace {
            let all = [
                (Component::X, p.x),
                (Component::Y, p.s),
                (Component::N, p.n),
            ];
            let mut inputs: [(Component, &[f64]); 3] = [(Component::X, &[]); 3];
            let mut len = 0;
            for (c, f) in all {
                if let Some(f) = f {
                    inputs[len] = (c, f);
                    len += 1;
                }
            }
            k.apply_with(precision, &mut self.ows, &inputs[..len], outputs);
            return;
        }
        // Term 1: A (p_x, 0, 0), straight into the outputs.
        match p.x {
            Some(px) => k.apply_with(precision, &mut self.ows, &[(Component::X, px)], outputs),
            None => outputs.iter_mut().for_each(|(_, o)| o.fill(0.0)),
        }
        if p.s.is_none() && p.n.is_none() {
            return;
        }
        let nx = self.nx;
        let [y, z, my, t2x, t2s, t2n, t3x, t3s, t3n] = &mut self.b;
        // Absent components read as zeros (the buffer stays zero).
        let zero = &self.zero[..];
        let (ps, pn) = (p.s.unwrap_or(zero), p.n.unwrap_or(zero));
        let lines = y
            .chunks_exact_mut(nx)
            .zip(z.chunks_exact_mut(nx))
            .zip(my.chunks_exact_mut(nx))
            .zip(ps.chunks_exact(nx).zip(pn.chunks_exact(nx)));
        for (l, (((y, z), my), (ps, pn))) in lines.enumerate() {
            let (c, s) = (self.cos[l], self.sin[l]);
            for j in 0..nx {
                y[j] = c * ps[j] - s * pn[j];
                z[j] = s * ps[j] + c * pn[j];
                my[j] = -y[j];
            }
        }
        // Term c: A (0, Y, Z); term s: A (0, Z, -Y); each on the requested
        // components only.
        let comps: [Component; 3] =
            std::array::from_fn(|j| outputs.get(j).map_or(Component::X, |o| o.0));
        let m = outputs.len();
        for (inputs, t) in [
            (
                [(Component::Y, &y[..]), (Component::N, &z[..])],
                [&mut *t2x, &mut *t2s, &mut *t2n],
            ),
            (
                [(Component::Y, &z[..]), (Component::N, &my[..])],
                [&mut *t3x, &mut *t3s, &mut *t3n],
            ),
        ] {
            let mut t = t.map(Some);
            let mut list: [(Component, &mut [f64]); 3] = [
                (Component::X, &mut []),
                (Component::X, &mut []),
                (Component::X, &mut []),
            ];
            for j in 0..m {
                list[j] = (
                    comps[j],
                    t[comps[j] as usize].take().expect("components repeat"),
                );
            }
            k.apply_with(precision, &mut self.ows, &inputs, &mut list[..m]);
        }
        for (o, out) in outputs.iter_mut() {
            let (a, b) = match o {
                Component::X => (&t2x, &t3x),
                Component::Y => (&t2s, &t3s),
                Component::N => (&t2n, &t3n),
            };
            let lines = out
                .chunks_exact_mut(nx)
                .zip(a.chunks_exact(nx).zip(b.chunks_exact(nx)));
            for (l, (out, (a, b))) in lines.enumerate() {
                let (c, s) = (self.cos[l], self.sin[l]);
                for j in 0..nx {
                    out[j] += c * a[j] + s * b[j];
                }
            }
        }
    }
}

/// Traction components of a [`ConformalOperator::apply_parts`] product
/// (x, s, n in the elements' local frames; `None` = zero).
#[derive(Debug, Clone, Copy, Default)]
pub struct Tractions<'a> {
    /// Longitudinal traction \[Pa\].
    pub x: Option<&'a [f64]>,
    /// Lateral traction along s \[Pa\].
    pub s: Option<&'a [f64]>,
    /// Pressure \[Pa\].
    pub n: Option<&'a [f64]>,
}

impl TangentialOperator for ConformalOperator {
    /// The tangential block (p_n = 0): for identical materials 3 forward
    /// and 6 inverse transforms.
    fn tangential_product(
        &mut self,
        precision: Precision,
        px: &[f64],
        ps: &[f64],
        ux: &mut [f64],
        us: &mut [f64],
    ) {
        self.apply_parts(
            precision,
            Tractions {
                x: Some(px),
                s: Some(ps),
                n: None,
            },
            &mut [(Component::X, ux), (Component::Y, us)],
        );
    }

    /// For Blanco coefficients and identical materials, the half-space
    /// tangential block (`f32`, 2 forward and 2 inverse transforms instead
    /// of 3 and 6). The two differ only by the factor cos(delta_I -
    /// delta_J) on the lateral tractions' columns (the n part of the
    /// rotated traction acts on u_x, u_s only through coupling kernels,
    /// absent for identical materials): 1 between neighbours, where the
    /// kernel is largest, and smaller only between elements far apart.
    /// The Newton steps then solve a slightly different linear system;
    /// their residuals, and so the answer and its tolerance, still use the
    /// exact product. Measured on the paper's Cases 1 and 2 from 20 to
    /// 162 kN (contact angle variation 27 to 98 degrees, mu = 0.3, xi
    /// 0.086 % and 0.3 %): the same Newton steps or one more, the same
    /// forces to 7 digits, 7 to 28 % less time (benches/README.md).
    fn jacobian_product(&mut self, px: &[f64], ps: &[f64], ux: &mut [f64], us: &mut [f64]) {
        if self.model == InfluenceModel::Blanco && !self.kernels.has(Component::X, Component::N) {
            PlanarTangential {
                kernels: &self.kernels,
                ows: &mut self.ows,
            }
            .tangential_product(Precision::Single, px, ps, ux, us);
        } else {
            self.tangential_product(Precision::Single, px, ps, ux, us);
        }
    }

    fn diagonal(&self) -> [f64; 2] {
        [
            self.kernels.value(Component::X, Component::X, 0, 0),
            self.kernels.value(Component::Y, Component::Y, 0, 0),
        ]
    }

    /// The planar operator's (the half-space circulant inverse): the
    /// conformal one differs from it by the factors cos(delta_I - delta_J),
    /// 1 between neighbours.
    fn circulant_inverse(&mut self, r: [&[f64]; 2], z: [&mut [f64]; 2]) {
        self.kernels.apply_tangential_inverse(&mut self.ows, r, z);
    }
}

impl crate::core::normal::NormalOperator for ConformalOperator {
    fn apply_normal(&mut self, p: &[f64], out: &mut [f64]) {
        ConformalOperator::apply_normal(self, p, out)
    }

    fn diagonal(&self) -> f64 {
        self.normal_diagonal()
    }

    /// The planar preconditioner of the half-space kernels: the conformal
    /// normal block is the planar one scaled by the orientation differences,
    /// close enough for the inverse of its periodic circulant to serve.
    fn precondition(&mut self, r: &[f64], z: &mut [f64]) -> bool {
        self.kernels.apply_normal_inverse(&mut self.ows, r, z)
    }
}

/// The dense Blanco or half-space matrix, built element by element from
/// the closed-form coefficients (tests only): rows and columns ordered
/// (x of all elements, s of all elements, n of all elements).
pub fn dense_matrix(
    kernels: &KernelSet,
    model: InfluenceModel,
    delta_rad: &[f64],
) -> faer::Mat<f64> {
    let (nx, ny) = (kernels.plan.nx, kernels.plan.ny);
    let n = nx * ny;
    let comps = [Component::X, Component::Y, Component::N];
    faer::Mat::from_fn(3 * n, 3 * n, |r, c| {
        let (a, i) = (r / n, r % n);
        let (b, j) = (c / n, c % n);
        let (ix, iy) = ((i % nx) as i64, (i / nx) as i64);
        let (jx, jy) = ((j % nx) as i64, (j / nx) as i64);
        let coef = |p: usize, q: usize| kernels.value(comps[p], comps[q], ix - jx, iy - jy);
        match model {
            InfluenceModel::HalfSpace => coef(a, b),
            InfluenceModel::Blanco => {
                // Column b of A R(D): R maps (x, s, n) of J to I's frame.
                let d = delta_rad[iy as usize] - delta_rad[jy as usize];
                let (cd, sd) = (d.cos(), d.sin());
                // R e_b expressed in I's frame.
                let rb = match b {
                    0 => [1.0, 0.0, 0.0],
                    1 => [0.0, cd, -sd],
                    _ => [0.0, sd, cd],
                };
                (0..3).map(|q| coef(a, q) * rb[q]).sum()
            }
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::fft::ConvolutionPlan;
    use crate::core::influence::HalfSpaceInfluence;
    use crate::core::material::{CombinedMaterial, Material};

    fn kernels(nx: usize, ny: usize, mat: CombinedMaterial) -> Arc<KernelSet> {
        Arc::new(KernelSet::new(
            Arc::new(ConvolutionPlan::new(nx, ny)),
            HalfSpaceInfluence::new(2e-4, 3e-4, &mat),
            KernelKind::Displacement,
        ))
    }

    fn check(mat: CombinedMaterial, model: InfluenceModel) {
        let (nx, ny) = (7, 6);
        let n = nx * ny;
        let k = kernels(nx, ny, mat);
        let delta: Vec<f64> = (0..ny).map(|l| -0.8 + 0.3 * l as f64).collect();
        let mut op = ConformalOperator::new(k.clone(), model, &delta);
        let field = |seed: f64| -> Vec<f64> {
            (0..n)
                .map(|i| 1e6 * ((i as f64 * 0.37 + seed).sin() + 0.3))
                .collect()
        };
        let (px, ps, pn) = (field(0.1), field(1.3), field(2.9));
        let (mut ux, mut us, mut un) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        op.apply(&px, &ps, &pn, &mut ux, &mut us, &mut un);
        let m = dense_matrix(&k, model, &delta);
        let p: Vec<f64> = px.iter().chain(&ps).chain(&pn).copied().collect();
        let scale = ux
            .iter()
            .chain(&us)
            .chain(&un)
            .fold(0.0f64, |a, &v| a.max(v.abs()));
        for r in 0..3 * n {
            let want: f64 = (0..3 * n).map(|c| m[(r, c)] * p[c]).sum();
            let got = [&ux, &us, &un][r / n][r % n];
            assert!(
                (got - want).abs() <= 1e-10 * scale,
                "{model:?} row {r}: {got} vs {want}"
            );
        }
        // The tangential block equals the full product with p_n = 0.
        let z0 = vec![0.0; n];
        op.apply(&px, &ps, &z0, &mut ux, &mut us, &mut un);
        let (mut tx, mut ts) = (vec![0.0; n], vec![0.0; n]);
        crate::core::steady::TangentialOperator::apply_tangential(
            &mut op, &px, &ps, &mut tx, &mut ts,
        );
        for i in 0..n {
            assert!(
                (ux[i] - tx[i]).abs() <= 1e-12 * scale && (us[i] - ts[i]).abs() <= 1e-12 * scale
            );
        }
        // The normal-only product equals the full one with p_x = p_s = 0.
        let z = vec![0.0; n];
        op.apply(&z, &z, &pn, &mut ux, &mut us, &mut un);
        let mut un2 = vec![0.0; n];
        op.apply_normal(&pn, &mut un2);
        for i in 0..n {
            assert!((un[i] - un2[i]).abs() <= 1e-12 * scale);
        }
        // Partial products (the conformal alternation's couplings): the
        // tangential displacements of the pressures, in either order of
        // the requested components, ...
        let (mut sx, mut ss) = (vec![1.0; n], vec![1.0; n]);
        op.apply_parts(
            Precision::Double,
            Tractions {
                n: Some(&pn),
                ..Tractions::default()
            },
            &mut [(Component::Y, &mut ss), (Component::X, &mut sx)],
        );
        for i in 0..n {
            assert!(
                (ux[i] - sx[i]).abs() <= 1e-12 * scale && (us[i] - ss[i]).abs() <= 1e-12 * scale
            );
        }
        // ... and the normal displacement of the tangential tractions.
        op.apply(&px, &ps, &z, &mut ux, &mut us, &mut un);
        un2.fill(1.0);
        op.apply_parts(
            Precision::Double,
            Tractions {
                x: Some(&px),
                s: Some(&ps),
                n: None,
            },
            &mut [(Component::N, &mut un2)],
        );
        for i in 0..n {
            assert!((un[i] - un2[i]).abs() <= 1e-12 * scale);
        }
    }

    #[test]
    fn fast_products_equal_dense_matrices() {
        let steel = Material {
            shear_modulus_pa: 81e9,
            poisson_ratio: 0.3,
        };
        let same = CombinedMaterial::identical(steel).unwrap();
        let other = CombinedMaterial::new(
            steel,
            Material {
                shear_modulus_pa: 30e9,
                poisson_ratio: 0.25,
            },
        )
        .unwrap();
        for mat in [same, other] {
            check(mat, InfluenceModel::Blanco);
            check(mat, InfluenceModel::HalfSpace);
        }
    }
}
