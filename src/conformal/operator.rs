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
//!   Lorenzo et al. 2018, §2.2, and their Ref. [23]):
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

use std::sync::Arc;

use crate::core::fft::{KernelSet, OperatorWorkspace, Precision};
use crate::core::influence::Component;
#[cfg(test)]
use crate::core::influence::KernelKind;

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
    un_scratch: Vec<f64>,
}

impl ConformalOperator {
    /// An operator for a grid whose lateral line `iy` has orientation
    /// `delta_rad[iy]`. With the displacement kernels of the (x, s) grid it
    /// gives displacement differences; with the steady-rolling kernels the
    /// steady-state operator (A - S A)/dx (the rotations do not depend on x).
    pub fn new(kernels: Arc<KernelSet>, model: InfluenceModel, delta_rad: &[f64]) -> Self {
        let (nx, ny) = (kernels.plan.nx, kernels.plan.ny);
        debug_assert_eq!(delta_rad.len(), ny);
        let n = nx * ny;
        Self {
            ows: kernels.workspace(),
            kernels,
            model,
            nx,
            cos: delta_rad.iter().map(|d| d.cos()).collect(),
            sin: delta_rad.iter().map(|d| d.sin()).collect(),
            b: std::array::from_fn(|_| vec![0.0; n]),
            zero: vec![0.0; n],
            un_scratch: vec![0.0; n],
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
        match self.model {
            InfluenceModel::HalfSpace => {
                self.kernels.apply(
                    &mut self.ows,
                    &[(Component::N, pn)],
                    &mut [(Component::N, un)],
                );
            }
            InfluenceModel::Blanco => {
                // Y = -s_J p, Z = c_J p; u_n = c_I [A (0, Y, Z)]_n + s_I [A (0, Z, -Y)]_n.
                let nx = self.nx;
                let [y, z, my, t2, t3, ..] = &mut self.b;
                for (i, &p) in pn.iter().enumerate() {
                    let l = i / nx;
                    y[i] = -self.sin[l] * p;
                    z[i] = self.cos[l] * p;
                    my[i] = -y[i];
                }
                let k = &self.kernels;
                // The lateral inputs act on u_n only for dissimilar materials.
                let used = if k.has(Component::N, Component::Y) {
                    2
                } else {
                    1
                };
                k.apply(
                    &mut self.ows,
                    &[(Component::N, &z[..]), (Component::Y, &y[..])][..used],
                    &mut [(Component::N, t2)],
                );
                k.apply(
                    &mut self.ows,
                    &[(Component::N, &my[..]), (Component::Y, &z[..])][..used],
                    &mut [(Component::N, t3)],
                );
                for i in 0..un.len() {
                    let l = i / nx;
                    un[i] = self.cos[l] * t2[i] + self.sin[l] * t3[i];
                }
            }
        }
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
        self.product(Precision::Double, px, ps, pn, ux, us, un)
    }

    /// [`ConformalOperator::apply`] in the given precision.
    #[allow(clippy::too_many_arguments)]
    fn product(
        &mut self,
        precision: Precision,
        px: &[f64],
        ps: &[f64],
        pn: &[f64],
        ux: &mut [f64],
        us: &mut [f64],
        un: &mut [f64],
    ) {
        let k = &self.kernels;
        match self.model {
            InfluenceModel::HalfSpace => {
                k.apply_with(
                    precision,
                    &mut self.ows,
                    &[(Component::X, px), (Component::Y, ps), (Component::N, pn)],
                    &mut [(Component::X, ux), (Component::Y, us), (Component::N, un)],
                );
            }
            InfluenceModel::Blanco => {
                let nx = self.nx;
                let [y, z, my, t2x, t2s, t2n, t3x, t3s, t3n] = &mut self.b;
                for i in 0..px.len() {
                    let l = i / nx;
                    let (c, s) = (self.cos[l], self.sin[l]);
                    y[i] = c * ps[i] - s * pn[i];
                    z[i] = s * ps[i] + c * pn[i];
                    my[i] = -y[i];
                }
                // Term 1: A (p_x, 0, 0), straight into the outputs.
                k.apply_with(
                    precision,
                    &mut self.ows,
                    &[(Component::X, px)],
                    &mut [(Component::X, ux), (Component::Y, us), (Component::N, un)],
                );
                // Term c: A (0, Y, Z); term s: A (0, Z, -Y).
                k.apply_with(
                    precision,
                    &mut self.ows,
                    &[(Component::Y, y), (Component::N, z)],
                    &mut [
                        (Component::X, t2x),
                        (Component::Y, t2s),
                        (Component::N, t2n),
                    ],
                );
                k.apply_with(
                    precision,
                    &mut self.ows,
                    &[(Component::Y, z), (Component::N, my)],
                    &mut [
                        (Component::X, t3x),
                        (Component::Y, t3s),
                        (Component::N, t3n),
                    ],
                );
                for i in 0..px.len() {
                    let l = i / nx;
                    let (c, s) = (self.cos[l], self.sin[l]);
                    ux[i] += c * t2x[i] + s * t3x[i];
                    us[i] += c * t2s[i] + s * t3s[i];
                    un[i] += c * t2n[i] + s * t3n[i];
                }
            }
        }
    }
}

impl crate::core::steady::TangentialOperator for ConformalOperator {
    /// The tangential block (p_n = 0).
    fn tangential_product(
        &mut self,
        precision: Precision,
        px: &[f64],
        ps: &[f64],
        ux: &mut [f64],
        us: &mut [f64],
    ) {
        let k = &self.kernels;
        if self.model == InfluenceModel::HalfSpace || k.has(Component::X, Component::N) {
            // Planar, or dissimilar materials (the n components couple back):
            // the general product.
            let zero = std::mem::take(&mut self.zero);
            let mut un = std::mem::take(&mut self.un_scratch);
            self.product(precision, px, ps, &zero, ux, us, &mut un);
            self.zero = zero;
            self.un_scratch = un;
            return;
        }
        // Identical materials, p_n = 0: Y = c_J p_s and Z = s_J p_s reach
        // u_x, u_s only through A_xs, A_ss, so
        // u_t = A_t(p_x, 0) + c_I A_t(0, Y) + s_I A_t(0, Z): 3 forward and
        // 6 inverse transforms.
        let nx = self.nx;
        let [y, z, _, t2x, t2s, _, t3x, t3s, _] = &mut self.b;
        for i in 0..px.len() {
            let l = i / nx;
            y[i] = self.cos[l] * ps[i];
            z[i] = self.sin[l] * ps[i];
        }
        k.apply_with(
            precision,
            &mut self.ows,
            &[(Component::X, px)],
            &mut [(Component::X, ux), (Component::Y, us)],
        );
        k.apply_with(
            precision,
            &mut self.ows,
            &[(Component::Y, &y[..])],
            &mut [(Component::X, t2x), (Component::Y, t2s)],
        );
        k.apply_with(
            precision,
            &mut self.ows,
            &[(Component::Y, &z[..])],
            &mut [(Component::X, t3x), (Component::Y, t3s)],
        );
        for i in 0..px.len() {
            let l = i / nx;
            let (c, s) = (self.cos[l], self.sin[l]);
            ux[i] += c * t2x[i] + s * t3x[i];
            us[i] += c * t2s[i] + s * t3s[i];
        }
    }

    fn diagonal(&self) -> [f64; 2] {
        [
            self.kernels.value(Component::X, Component::X, 0, 0),
            self.kernels.value(Component::Y, Component::Y, 0, 0),
        ]
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
