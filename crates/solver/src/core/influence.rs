//! Influence coefficients of the elastic half-space for uniform tractions on
//! rectangular elements (Kalker 1990, §5.2; Johnson 1985, §3.2–3.5).
//!
//! Body 1 occupies the half-space on the +n side of the contact plane, body 2
//! the other side. A traction `p = (p_x, p_y, p_n)` acts on body 1 (and `-p` on
//! body 2), `p_n > 0` pressing the bodies together. The displacement
//! difference `u = u(1) - u(2)` (tangential) and `u_n = u_n(1) - u_n(2)`
//! (normal, opening the gap) at element I due to a unit uniform traction on
//! element J depends only on the offset (X, Y) = centre(I) - centre(J):
//!
//! ```text
//! A_xx = 1/(pi G) [ (1-nu) F_1 + nu F_xx ]     A_xy = A_yx = 1/(pi G) nu F_xy
//! A_yy = 1/(pi G) [ (1-nu) F_1 + nu F_yy ]     A_nn = 1/(pi G) (1-nu) F_1
//! A_nx = +K/(pi G) F_x   A_xn = -K/(pi G) F_x  A_ny = +K/(pi G) F_y   A_yn = -K/(pi G) F_y
//! ```
//!
//! where F_* is the integral of the point-load kernel over the element
//! rectangle [X-dx/2, X+dx/2] x [Y-dy/2, Y+dy/2]: 1/r, x²/r³, y²/r³, xy/r³, x/r²
//! and y/r². The point-load kernels are the Boussinesq/Cerruti solutions
//! (Johnson eqs. 3.19 and 3.86), summed over both bodies with Kalker's combined
//! constants; the signs of the coupling terms follow from the Betti–Maxwell
//! reciprocity, which makes the 3N x 3N matrix symmetric. The primitives used
//! below differ from the textbook logarithms only by functions of one variable,
//! which cancel in the four-corner difference; they stay finite at r = 0.
//!
//! # Line contact (plane strain)
//!
//! A grid of one row ([`crate::core::grid::Grid::line`]) is a line contact:
//! cylinders with parallel axes along y, every field independent of y, the
//! one row standing for the unit length [`LINE_LENGTH_M`] (so that its totals
//! are forces per metre). Its coefficients are those of the elastic
//! half-plane in plane strain for a unit traction on the strip
//! [X-dx/2, X+dx/2] x (-inf, inf), the 3-D point kernels integrated along y
//! (Johnson 1985, §2.2):
//!
//! ```text
//! A_nn = A_xx = 2(1-nu)/(pi G) L(X)     A_yy = 2/(pi G) L(X)      A_xy = 0
//! A_nx = -A_xn = (K/G) S(X)             A_ny = A_yn = 0
//! L(X) = -int ln(|X - s| / R) ds,       S(X) = int sign(X - s) ds
//! ```
//!
//! (s over [-dx/2, dx/2]). The logarithm's displacement is defined only up
//! to a rigid-body constant, fixed here by the reference distance R =
//! [`LINE_REFERENCE_DISTANCE_M`]: the surface 1 m from a line load does not
//! move. Approaches, and the shifts of transient steps, are therefore
//! relative to the surface points 1 m away (Johnson 1985, §2.2, gives
//! the half-plane's displacements relative to such a datum; the approach
//! in CONTACT's `carter2d` reference output is that of a datum at the
//! cylinders' length `DY`, checked in the validation tests). For a normal load
//! P' \[N/m\] on a patch of half-width a the approach changes by
//! 2 P' ln(R'/R) / (pi E*) with another reference distance R'. The constant
//! cancels in steady rolling (the slip takes differences of
//! displacements). On a window shorter than 4 R the operator is positive
//! definite (the logarithmic capacity of an interval is a quarter of its
//! length); [`crate::core::grid::Grid::line`] keeps windows within R.
//! A_yy is the antiplane (lateral) shear of the half-plane.

use crate::core::cancel;
use crate::core::material::{CombinedMaterial, Material};
use crate::core::viscoelastic::{
    relaxed_average, relaxed_averages, Viscoelastic, QUADRATURE_TOLERANCE,
};

/// Traction / displacement components, in matrix order.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Component {
    /// Longitudinal (rolling) direction x.
    X = 0,
    /// Lateral direction y.
    Y = 1,
    /// Normal direction n.
    N = 2,
}

#[inline]
fn xasinh(x: f64, y: f64) -> f64 {
    // x * asinh(y/|x|), continuous extension 0 at x = 0.
    if x == 0.0 {
        0.0
    } else {
        x * (y / x.abs()).asinh()
    }
}

#[inline]
fn prim_1_over_r(x: f64, y: f64) -> f64 {
    xasinh(x, y) + xasinh(y, x)
}

#[inline]
fn prim_x2_over_r3(x: f64, y: f64) -> f64 {
    xasinh(y, x)
}

#[inline]
fn prim_y2_over_r3(x: f64, y: f64) -> f64 {
    xasinh(x, y)
}

#[inline]
fn prim_xy_over_r3(x: f64, y: f64) -> f64 {
    -(x * x + y * y).sqrt()
}

#[inline]
fn prim_x_over_r2(x: f64, y: f64) -> f64 {
    let r2 = x * x + y * y;
    let a = if y == 0.0 { 0.0 } else { 0.5 * y * r2.ln() };
    let b = if x == 0.0 { 0.0 } else { x * (y / x).atan() };
    a + b
}

/// Length of body the one row of a line-contact grid stands for \[m\]:
/// its totals are forces per metre.
pub const LINE_LENGTH_M: f64 = 1.0;
/// Distance from a line load at which the surface does not move \[m\]:
/// the datum of the half-plane's displacements (see the module docs).
pub const LINE_REFERENCE_DISTANCE_M: f64 = 1.0;

/// s ln(|s| / R) - s, the primitive of ln(|s| / R) (0 at s = 0).
#[inline]
fn prim_ln(s: f64) -> f64 {
    if s == 0.0 {
        0.0
    } else {
        s * (s.abs() / LINE_REFERENCE_DISTANCE_M).ln() - s
    }
}

/// The strip integral L(X) = -int_{-h}^{h} ln(|X - s| / R) ds.
#[inline]
fn strip_log(x: f64, h: f64) -> f64 {
    -(prim_ln(x + h) - prim_ln(x - h))
}

/// The strip integral S(X) = int_{-h}^{h} sign(X - s) ds.
#[inline]
fn strip_sign(x: f64, h: f64) -> f64 {
    2.0 * x.clamp(-h, h)
}

/// The integrals over an element of the point kernels 1/r, x²/r³, y²/r³,
/// xy/r³, x/r² and y/r² (see the module docs).
#[derive(Debug, Clone, Copy)]
enum ElementIntegral {
    One,
    Xx,
    Yy,
    Xy,
    X,
    Y,
}

/// Offsets from this many half-widths of an element on take the far-field
/// coefficient of [`HalfSpaceInfluence`] in the relaxation terms: the
/// 8-point Gauss rule is then exact to about 1e-16 (Bernstein ellipse of
/// parameter 16 for the nearest singularity).
pub const FAR_FIELD_HALF_WIDTHS: f64 = 8.0;

/// The 8-point Gauss-Legendre rule on [-1, 1] (node, weight).
const GAUSS_8: [(f64, f64); 8] = [
    (-0.960_289_856_497_536_3, 0.101_228_536_290_376_3),
    (-0.796_666_477_413_626_7, 0.222_381_034_453_374_5),
    (-0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (-0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (0.796_666_477_413_626_7, 0.222_381_034_453_374_5),
    (0.960_289_856_497_536_3, 0.101_228_536_290_376_3),
];

#[inline]
fn corners(f: impl Fn(f64, f64) -> f64, x: f64, y: f64, hx: f64, hy: f64) -> f64 {
    f(x + hx, y + hy) - f(x - hx, y + hy) - f(x + hx, y - hy) + f(x - hx, y - hy)
}

/// Which elastic body the coefficients describe.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Elasticity {
    /// The three-dimensional half-space (rectangular elements).
    HalfSpace,
    /// The half-plane in plane strain: a line contact, one row of strips
    /// (see the module docs).
    PlaneStrain,
}

/// Closed-form influence coefficients for one grid spacing and material pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HalfSpaceInfluence {
    dx: f64,
    dy: f64,
    inv_pi_g: f64,
    nu: f64,
    k: f64,
    elasticity: Elasticity,
    /// Tangential flexibility of an interfacial layer \[m/Pa\], added to
    /// the self-influence coefficients A_xx(I, I) and A_yy(I, I)
    /// ([`HalfSpaceInfluence::with_layer_flexibility`]).
    layer: f64,
    /// The viscoelastic bodies' relaxation terms
    /// ([`HalfSpaceInfluence::with_viscoelastic`]); None: elastic.
    visc: Option<ViscoTerms>,
    /// What the relaxation terms were built from.
    visc_input: Option<Viscoelastic>,
}

/// The relaxation terms of viscoelastic bodies (see
/// [`crate::core::viscoelastic`]): up to two (one per body; one for both
/// when they relax alike), each the elastic coefficients of its share
/// (`inv_pi_g`, `nu`, `k`), its ratio f_g and relaxation length L \[m\].
#[derive(Debug, Clone, Copy, PartialEq)]
struct ViscoTerms {
    terms: [ViscoTerm; 2],
    count: usize,
}

#[derive(Debug, Clone, Copy, PartialEq)]
struct ViscoTerm {
    inv_pi_g: f64,
    nu: f64,
    k: f64,
    ratio: f64,
    length_m: f64,
}

impl HalfSpaceInfluence {
    /// Coefficients for elements of `dx_m` x `dy_m`.
    pub fn new(dx_m: f64, dy_m: f64, material: &CombinedMaterial) -> Self {
        Self {
            dx: dx_m,
            dy: dy_m,
            inv_pi_g: 1.0 / (std::f64::consts::PI * material.shear_modulus_pa),
            nu: material.poisson_ratio,
            k: material.kalker_k,
            elasticity: Elasticity::HalfSpace,
            layer: 0.0,
            visc: None,
            visc_input: None,
        }
    }

    /// These coefficients for viscoelastic bodies: `material`'s shear
    /// moduli are the glassy ones G_g, `visc` the bodies' standard linear
    /// solids and the rolling speed ([`crate::core::viscoelastic`]; the
    /// coefficients of steady rolling in +x). Bodies with f_g = 0 add
    /// nothing; both elastic leave the coefficients as they are.
    pub fn with_viscoelastic(self, material: &CombinedMaterial, visc: &Viscoelastic) -> Self {
        let [(f1, l1), (f2, l2)] = visc.relaxation();
        let share = |m: &Material, sign: f64| {
            // A body's share of Kalker's combined constants: 1/G =
            // (1/G1 + 1/G2)/2, nu/G = (nu1/G1 + nu2/G2)/2, K/G = ((1 -
            // 2 nu1)/G1 - (1 - 2 nu2)/G2)/4 (crate::core::material).
            let g = 2.0 * m.shear_modulus_pa;
            ViscoTerm {
                inv_pi_g: 1.0 / (std::f64::consts::PI * g),
                nu: m.poisson_ratio,
                k: sign * 0.5 * (1.0 - 2.0 * m.poisson_ratio),
                ratio: 0.0,
                length_m: 0.0,
            }
        };
        let mut terms = [share(&material.body1, 1.0), share(&material.body2, -1.0)];
        terms[0].ratio = f1;
        terms[0].length_m = l1;
        terms[1].ratio = f2;
        terms[1].length_m = l2;
        let count = if (f1, l1) == (f2, l2) {
            // Both bodies relax alike: one term of the combined constants.
            terms[0] = ViscoTerm {
                inv_pi_g: self.inv_pi_g,
                nu: self.nu,
                k: self.k,
                ratio: f1,
                length_m: l1,
            };
            usize::from(f1 != 0.0)
        } else {
            if f1 == 0.0 {
                terms[0] = terms[1];
            }
            usize::from(f1 != 0.0) + usize::from(f2 != 0.0)
        };
        Self {
            visc: (count > 0).then_some(ViscoTerms { terms, count }),
            visc_input: (count > 0).then_some(*visc),
            ..self
        }
    }

    /// The viscoelastic bodies these coefficients were built for (None:
    /// elastic bodies).
    pub fn viscoelastic(&self) -> Option<Viscoelastic> {
        self.visc_input
    }

    /// Whether the coefficients are those of viscoelastic bodies (not
    /// symmetric: see [`crate::core::viscoelastic`]).
    pub fn is_viscoelastic(&self) -> bool {
        self.visc.is_some()
    }

    /// The elastic coefficients of the body of relaxation term `t` alone
    /// (its share of the combined constants), whose average upstream is
    /// the term.
    fn relaxing_body(&self, t: &ViscoTerm) -> Self {
        Self {
            inv_pi_g: t.inv_pi_g,
            nu: t.nu,
            k: t.k,
            layer: 0.0,
            visc: None,
            visc_input: None,
            ..*self
        }
    }

    /// The elastic coefficient (i, j) at (x, y) plus the viscoelastic
    /// bodies' relaxation terms.
    fn with_relaxation(&self, i: Component, j: Component, x: f64, y: f64, elastic: f64) -> f64 {
        let Some(v) = &self.visc else {
            return elastic;
        };
        // A cancelled caller's kernel build stops integrating (about 0.1 ms
        // a coefficient; the cache keeps no set built so:
        // [`crate::core::cache::KernelCache`]).
        if cancel::requested() {
            return elastic;
        }
        let h = 0.5 * self.dx;
        // Accuracy against the size of the self coefficient (A_xx >= A_nn).
        let tol = QUADRATURE_TOLERANCE * self.inv_pi_g * self.dx;
        let mut sum = elastic;
        for t in &v.terms[..v.count] {
            let body = self.relaxing_body(t);
            sum += t.ratio
                * relaxed_average(
                    |s| body.relaxation_integrand(i, j, s, y),
                    x,
                    t.length_m,
                    &[-h, h],
                    tol,
                );
        }
        sum
    }

    /// These coefficients with an interfacial layer of tangential
    /// flexibility `flexibility_m_per_pa` = h/G3 between the bodies
    /// ([`crate::core::layer`], CONTACT's M = 4): the layer shears by F p
    /// under the traction p of its own element, so F adds to A_xx and
    /// A_yy of every element on itself (offset 0) and to nothing else.
    /// 0 leaves the coefficients as they are.
    pub fn with_layer_flexibility(self, flexibility_m_per_pa: f64) -> Self {
        Self {
            layer: flexibility_m_per_pa,
            ..self
        }
    }

    /// The interfacial layer's flexibility \[m/Pa\] (0: none).
    pub fn layer_flexibility_m_per_pa(&self) -> f64 {
        self.layer
    }

    /// The layer's flexibility if (`x`, `y`) lies on the loaded element
    /// itself (its centre: offset 0), else 0.
    #[inline]
    fn layer_at(&self, x: f64, y: f64) -> f64 {
        if self.layer != 0.0 && x.abs() < 0.5 * self.dx && y.abs() < 0.5 * self.dy {
            self.layer
        } else {
            0.0
        }
    }

    /// Plane-strain coefficients of a line contact for strips of width
    /// `dx_m` (the row standing for [`LINE_LENGTH_M`]).
    pub fn plane_strain(dx_m: f64, material: &CombinedMaterial) -> Self {
        Self {
            elasticity: Elasticity::PlaneStrain,
            ..Self::new(dx_m, LINE_LENGTH_M, material)
        }
    }

    /// The elastic body of these coefficients.
    pub fn elasticity(&self) -> Elasticity {
        self.elasticity
    }

    /// The plane-strain coefficient (i, j) at offset x from the strip's
    /// centre.
    fn plane_strain_coefficient(&self, i: Component, j: Component, x: f64) -> f64 {
        let h = 0.5 * self.dx;
        self.plane_strain_of(i, j, x, strip_log(x, h), strip_sign(x, h))
    }

    /// The plane-strain coefficient (i, j) at offset x of the strip
    /// integrals `l` = L(x) and `s` = S(x).
    fn plane_strain_of(&self, i: Component, j: Component, x: f64, l: f64, s: f64) -> f64 {
        use Component::*;
        let c = self.inv_pi_g;
        let pi_c = std::f64::consts::PI * c;
        let layer = || self.layer_at(x, 0.0);
        match (i, j) {
            (X, X) => 2.0 * c * (1.0 - self.nu) * l + layer(),
            (N, N) => 2.0 * c * (1.0 - self.nu) * l,
            (Y, Y) => 2.0 * c * l + layer(),
            (N, X) => pi_c * self.k * s,
            (X, N) => -pi_c * self.k * s,
            (X, Y) | (Y, X) | (N, Y) | (Y, N) => 0.0,
        }
    }

    /// The elastic coefficient far from the element (|x| at least
    /// [`FAR_FIELD_HALF_WIDTHS`] times its larger half-width), from Gauss
    /// quadrature of the point kernels over the element instead of the
    /// closed forms' differences of primitives, which lose the digits of
    /// a coefficient 1e5 element widths away or more to cancellation
    /// (the relaxation terms of a viscoelastic body reach that far).
    /// None nearer.
    fn far_coefficient(&self, i: Component, j: Component, x: f64, y: f64) -> Option<f64> {
        let (hx, hy) = (0.5 * self.dx, 0.5 * self.dy);
        let reach = match self.elasticity {
            Elasticity::PlaneStrain => hx,
            Elasticity::HalfSpace => hx.max(hy),
        };
        if x.abs() < FAR_FIELD_HALF_WIDTHS * reach {
            return None;
        }
        if self.elasticity == Elasticity::PlaneStrain {
            let l: f64 = GAUSS_8
                .iter()
                .map(|&(t, w)| -w * hx * ((x - hx * t).abs() / LINE_REFERENCE_DISTANCE_M).ln())
                .sum();
            return Some(self.plane_strain_of(i, j, x, l, 2.0 * hx * x.signum()));
        }
        Some(self.half_space_of(i, j, x, y, |kernel| {
            let mut sum = 0.0;
            for &(a, wa) in &GAUSS_8 {
                for &(b, wb) in &GAUSS_8 {
                    let (px, py) = (x - hx * a, y - hy * b);
                    let r2 = px * px + py * py;
                    let r = r2.sqrt();
                    let v = match kernel {
                        ElementIntegral::One => 1.0 / r,
                        ElementIntegral::Xx => px * px / (r2 * r),
                        ElementIntegral::Yy => py * py / (r2 * r),
                        ElementIntegral::Xy => px * py / (r2 * r),
                        ElementIntegral::X => px / r2,
                        ElementIntegral::Y => py / r2,
                    };
                    sum += wa * wb * v;
                }
            }
            sum * hx * hy
        }))
    }

    /// The elastic coefficient for the relaxation terms of viscoelastic
    /// bodies: [`HalfSpaceInfluence::far_coefficient`] far from the
    /// element, the closed forms nearer.
    fn relaxation_integrand(&self, i: Component, j: Component, x: f64, y: f64) -> f64 {
        self.far_coefficient(i, j, x, y)
            .unwrap_or_else(|| self.elastic_coefficient(i, j, x, y))
    }

    /// Displacement difference component `i` \[m\] at offset (x, y) \[m\] from the
    /// centre of an element loaded by a unit uniform traction \[Pa\] in `j`
    /// (on the element itself, with an interfacial layer's shear:
    /// [`HalfSpaceInfluence::with_layer_flexibility`]).
    /// A line contact's coefficients do not depend on y.
    /// With viscoelastic bodies ([`HalfSpaceInfluence::with_viscoelastic`]),
    /// their relaxation terms included.
    pub fn coefficient(&self, i: Component, j: Component, x: f64, y: f64) -> f64 {
        let elastic = self.elastic_coefficient(i, j, x, y);
        self.with_relaxation(i, j, x, y, elastic)
    }

    /// [`HalfSpaceInfluence::coefficient`] of the elastic bodies (the
    /// glassy moduli of viscoelastic ones).
    fn elastic_coefficient(&self, i: Component, j: Component, x: f64, y: f64) -> f64 {
        if self.elasticity == Elasticity::PlaneStrain {
            return self.plane_strain_coefficient(i, j, x);
        }
        let (hx, hy) = (0.5 * self.dx, 0.5 * self.dy);
        self.half_space_of(i, j, x, y, |kernel| match kernel {
            ElementIntegral::One => corners(prim_1_over_r, x, y, hx, hy),
            ElementIntegral::Xx => corners(prim_x2_over_r3, x, y, hx, hy),
            ElementIntegral::Yy => corners(prim_y2_over_r3, x, y, hx, hy),
            ElementIntegral::Xy => corners(prim_xy_over_r3, x, y, hx, hy),
            ElementIntegral::X => corners(prim_x_over_r2, x, y, hx, hy),
            // y/r² is x/r² with the axes swapped.
            ElementIntegral::Y => corners(prim_x_over_r2, y, x, hy, hx),
        })
    }

    /// The half-space coefficient (i, j) at (x, y) of the element
    /// integrals `f` of the point kernels.
    fn half_space_of(
        &self,
        i: Component,
        j: Component,
        x: f64,
        y: f64,
        f: impl Fn(ElementIntegral) -> f64,
    ) -> f64 {
        use Component::*;
        use ElementIntegral as F;
        let c = self.inv_pi_g;
        let nu = self.nu;
        match (i, j) {
            (X, X) => c * ((1.0 - nu) * f(F::One) + nu * f(F::Xx)) + self.layer_at(x, y),
            (Y, Y) => c * ((1.0 - nu) * f(F::One) + nu * f(F::Yy)) + self.layer_at(x, y),
            (X, Y) | (Y, X) => c * nu * f(F::Xy),
            (N, N) => c * (1.0 - nu) * f(F::One),
            (N, X) => c * self.k * f(F::X),
            (X, N) => -c * self.k * f(F::X),
            (N, Y) => c * self.k * f(F::Y),
            (Y, N) => -c * self.k * f(F::Y),
        }
    }

    /// Combined shear modulus G \[Pa\].
    pub fn shear_modulus_pa(&self) -> f64 {
        1.0 / (std::f64::consts::PI * self.inv_pi_g)
    }

    /// Combined Poisson ratio [-].
    pub fn poisson_ratio(&self) -> f64 {
        self.nu
    }

    /// Element size in x \[m\].
    pub fn dx_m(&self) -> f64 {
        self.dx
    }

    /// Element size in y \[m\].
    pub fn dy_m(&self) -> f64 {
        self.dy
    }

    /// True when the normal/tangential coupling coefficients are non-zero.
    pub fn coupled(&self) -> bool {
        // Viscoelastic bodies that relax differently: each body's share.
        self.k.abs() > 1e-12
            || self
                .visc
                .is_some_and(|v| v.terms[..v.count].iter().any(|t| t.k.abs() > 1e-12))
    }
}

/// Which operator a convolution kernel represents.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum KernelKind {
    /// Displacement differences u = A p (static, transient and normal problems).
    Displacement,
    /// Steady rolling: the upwind difference (u(x) - u(x + dx)) / dx of
    /// Kalker's discretisation of the slip s = w - du/dx, i.e. the kernel
    /// (A(X) - A(X + dx)) / dx [1/Pa]. Material enters the grid at large x.
    SteadyRolling,
}

impl HalfSpaceInfluence {
    /// The value of kernel `kind`, component (i, j), at element offset (kx, ky).
    pub fn kernel(&self, kind: KernelKind, i: Component, j: Component, kx: i64, ky: i64) -> f64 {
        let x = kx as f64 * self.dx;
        let y = ky as f64 * self.dy;
        match kind {
            KernelKind::Displacement => self.coefficient(i, j, x, y),
            KernelKind::SteadyRolling => {
                (self.coefficient(i, j, x, y) - self.coefficient(i, j, x + self.dx, y)) / self.dx
            }
        }
    }

    /// [`HalfSpaceInfluence::kernel`] at the offsets (kx_lo + k, ky) for k
    /// in 0..out.len(). Elastic bodies: each as `kernel` gives it.
    /// Viscoelastic ones: their relaxation terms in one sweep along x
    /// ([`relaxed_averages`]), each to the accuracy of a single
    /// coefficient's quadrature, instead of a quadrature to the tail per
    /// offset (the kernel build's cost).
    pub fn kernel_row(
        &self,
        kind: KernelKind,
        i: Component,
        j: Component,
        kx_lo: i64,
        ky: i64,
        out: &mut [f64],
    ) {
        let Some(v) = &self.visc else {
            for (k, o) in out.iter_mut().enumerate() {
                *o = self.kernel(kind, i, j, kx_lo + k as i64, ky);
            }
            return;
        };
        let y = ky as f64 * self.dy;
        let n = out.len() + usize::from(kind == KernelKind::SteadyRolling);
        let x_at = |k: usize| (kx_lo + k as i64) as f64 * self.dx;
        let mut c: Vec<f64> = (0..n)
            .map(|k| self.elastic_coefficient(i, j, x_at(k), y))
            .collect();
        // A cancelled caller's kernel build stops integrating, as
        // `with_relaxation`.
        if !cancel::requested() {
            let h = 0.5 * self.dx;
            let tol = QUADRATURE_TOLERANCE * self.inv_pi_g * self.dx;
            let mut part = vec![0.0; n];
            for t in &v.terms[..v.count] {
                let body = self.relaxing_body(t);
                relaxed_averages(
                    |s| body.relaxation_integrand(i, j, s, y),
                    x_at(0),
                    self.dx,
                    t.length_m,
                    &[-h, h],
                    tol,
                    &mut part,
                );
                for (c, p) in c.iter_mut().zip(&part) {
                    *c += t.ratio * p;
                }
            }
        }
        match kind {
            KernelKind::Displacement => out.copy_from_slice(&c[..out.len()]),
            KernelKind::SteadyRolling => {
                for (k, o) in out.iter_mut().enumerate() {
                    *o = (c[k] - c[k + 1]) / self.dx;
                }
            }
        }
    }

    /// [`HalfSpaceInfluence::kernel_row`] for every row of an `nx` x `ny`
    /// grid's offsets at once: `out` holds rows ky = -(ny - 1) ..= ny - 1
    /// of 2 nx - 1 values each, kx from -(nx - 1). For elastic half-space
    /// bodies the primitives of the element integrals are evaluated once
    /// per element corner, on a quarter of the corner lattice (each is
    /// even or odd in x and in y), instead of at four corners per
    /// coefficient and again for each component (two logarithms per corner
    /// instead of about 32 per offset for A_xx, A_yy and A_nn; the same
    /// closed forms, rounded differently by about 1e-16 of the corner
    /// values). False, and `out` untouched, for viscoelastic bodies and
    /// plane strain: [`HalfSpaceInfluence::kernel_row`] then.
    pub fn kernel_table(
        &self,
        kind: KernelKind,
        i: Component,
        j: Component,
        [nx, ny]: [usize; 2],
        out: &mut [f64],
    ) -> bool {
        if self.visc.is_some() || self.elasticity != Elasticity::HalfSpace {
            return false;
        }
        let steady = usize::from(kind == KernelKind::SteadyRolling);
        // Corner m (any integer) lies at (m - 1/2) d; the lattice holds
        // m = 1 ..= mx in x, 1 ..= ny in y, the rest by parity.
        let (mx, my) = (nx + steady, ny);
        let lattice = |integral: ElementIntegral| -> (Vec<f64>, [f64; 2]) {
            let (f, parity): (fn(f64, f64) -> f64, [f64; 2]) = match integral {
                ElementIntegral::One => (prim_1_over_r, [-1.0, -1.0]),
                ElementIntegral::Xx => (prim_x2_over_r3, [-1.0, -1.0]),
                ElementIntegral::Yy => (prim_y2_over_r3, [-1.0, -1.0]),
                ElementIntegral::Xy => (prim_xy_over_r3, [1.0, 1.0]),
                ElementIntegral::X => (prim_x_over_r2, [1.0, -1.0]),
                ElementIntegral::Y => (|x, y| prim_x_over_r2(y, x), [-1.0, 1.0]),
            };
            let mut v = Vec::with_capacity(mx * my);
            for b in 1..=my {
                let cy = (b as f64 - 0.5) * self.dy;
                v.extend((1..=mx).map(|a| f((a as f64 - 0.5) * self.dx, cy)));
            }
            (v, parity)
        };
        // The integrals (i, j) combines, each's lattice once.
        let used = std::cell::Cell::new(0u8);
        self.half_space_of(i, j, 0.0, 0.0, |k| {
            used.set(used.get() | 1 << k as u8);
            0.0
        });
        let all = [
            ElementIntegral::One,
            ElementIntegral::Xx,
            ElementIntegral::Yy,
            ElementIntegral::Xy,
            ElementIntegral::X,
            ElementIntegral::Y,
        ];
        let lattices: Vec<Option<(Vec<f64>, [f64; 2])>> = all
            .iter()
            .map(|&k| (used.get() & 1 << k as u8 != 0).then(|| lattice(k)))
            .collect();
        let corner = |(v, [sx, sy]): &(Vec<f64>, [f64; 2]), a: i64, b: i64| {
            let (a, fx) = if a >= 1 { (a, 1.0) } else { (1 - a, *sx) };
            let (b, fy) = if b >= 1 { (b, 1.0) } else { (1 - b, *sy) };
            fx * fy * v[(b as usize - 1) * mx + (a as usize - 1)]
        };
        let value = |kx: i64, ky: i64| {
            self.half_space_of(i, j, kx as f64 * self.dx, ky as f64 * self.dy, |k| {
                lattices[k as usize].as_ref().map_or(0.0, |l| {
                    corner(l, kx + 1, ky + 1) - corner(l, kx, ky + 1) - corner(l, kx + 1, ky)
                        + corner(l, kx, ky)
                })
            })
        };
        let wx = 2 * nx - 1;
        for (row, ky) in out.chunks_exact_mut(wx).zip(-(ny as i64 - 1)..) {
            for (o, kx) in row.iter_mut().zip(-(nx as i64 - 1)..) {
                *o = match kind {
                    KernelKind::Displacement => value(kx, ky),
                    KernelKind::SteadyRolling => (value(kx, ky) - value(kx + 1, ky)) / self.dx,
                };
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::material::{CombinedMaterial, Material};

    fn steel() -> CombinedMaterial {
        CombinedMaterial::identical(Material {
            shear_modulus_pa: 80e9,
            poisson_ratio: 0.25,
        })
        .unwrap()
    }

    #[test]
    fn self_coefficient_of_square_matches_love() {
        // Centre deflection of a uniformly loaded square of side 2c on the
        // half-space: w = 4 c p ln(1 + sqrt 2) (1 - nu^2) / (pi E) per body
        // (Love 1929; Johnson 1985 §3.3). Combined: 8 c ln(1+sqrt2) / (pi E*).
        let m = steel();
        let d = 1e-4;
        let ic = HalfSpaceInfluence::new(d, d, &m);
        let estar = m.effective_modulus_pa();
        let expect = 4.0 * d * (1.0 + 2f64.sqrt()).ln() / (std::f64::consts::PI * estar);
        let got = ic.coefficient(Component::N, Component::N, 0.0, 0.0);
        assert!((got / expect - 1.0).abs() < 1e-13, "{got} vs {expect}");
    }

    #[test]
    fn far_field_tends_to_point_loads() {
        // Far from the element the coefficients approach the point-load
        // kernels times the element area (Johnson eqs. 3.19, 3.86).
        let m = CombinedMaterial::new(
            Material {
                shear_modulus_pa: 80e9,
                poisson_ratio: 0.28,
            },
            Material {
                shear_modulus_pa: 40e9,
                poisson_ratio: 0.2,
            },
        )
        .unwrap();
        let (dx, dy) = (1e-4, 2e-4);
        let ic = HalfSpaceInfluence::new(dx, dy, &m);
        let (x, y): (f64, f64) = (3e-2, -2e-2);
        let r = (x * x + y * y).sqrt();
        let c = dx * dy / (std::f64::consts::PI * m.shear_modulus_pa);
        let (nu, k) = (m.poisson_ratio, m.kalker_k);
        use Component::*;
        let cases = [
            (X, X, c * ((1.0 - nu) / r + nu * x * x / r.powi(3))),
            (Y, Y, c * ((1.0 - nu) / r + nu * y * y / r.powi(3))),
            (X, Y, c * nu * x * y / r.powi(3)),
            (N, N, c * (1.0 - nu) / r),
            (N, X, c * k * x / (r * r)),
            (X, N, -c * k * x / (r * r)),
            (N, Y, c * k * y / (r * r)),
            (Y, N, -c * k * y / (r * r)),
        ];
        for (i, j, expect) in cases {
            let got = ic.coefficient(i, j, x, y);
            assert!(
                (got / expect - 1.0).abs() < 1e-4,
                "{i:?}{j:?}: {got} vs {expect}"
            );
        }
    }

    /// Steel on a softer body (K != 0).
    fn dissimilar() -> CombinedMaterial {
        CombinedMaterial::new(
            Material {
                shear_modulus_pa: 80e9,
                poisson_ratio: 0.28,
            },
            Material {
                shear_modulus_pa: 30e9,
                poisson_ratio: 0.35,
            },
        )
        .unwrap()
    }

    /// The corner-lattice table holds the coefficients `kernel` gives, for
    /// every component and both kinds, with an interfacial layer.
    #[test]
    fn the_corner_lattice_table_matches_the_coefficients() {
        use Component::*;
        let ic = HalfSpaceInfluence::new(1e-4, 1.5e-4, &dissimilar()).with_layer_flexibility(2e-15);
        let (nx, ny) = (6usize, 5usize);
        let scale = ic.coefficient(X, X, 0.0, 0.0);
        for kind in [KernelKind::Displacement, KernelKind::SteadyRolling] {
            let scale = match kind {
                KernelKind::Displacement => scale,
                KernelKind::SteadyRolling => scale / ic.dx_m(),
            };
            for i in [X, Y, N] {
                for j in [X, Y, N] {
                    let mut t = vec![f64::NAN; (2 * nx - 1) * (2 * ny - 1)];
                    assert!(ic.kernel_table(kind, i, j, [nx, ny], &mut t));
                    for (r, ky) in t.chunks_exact(2 * nx - 1).zip(-(ny as i64 - 1)..) {
                        for (&got, kx) in r.iter().zip(-(nx as i64 - 1)..) {
                            let want = ic.kernel(kind, i, j, kx, ky);
                            assert!(
                                (got - want).abs() <= 1e-13 * scale,
                                "{kind:?} {i:?}{j:?} ({kx}, {ky}): {got:e} vs {want:e}"
                            );
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn matrix_is_symmetric_by_reciprocity() {
        let m = dissimilar();
        let ic = HalfSpaceInfluence::new(1e-4, 1.5e-4, &m);
        use Component::*;
        let comps = [X, Y, N];
        for &(x, y) in &[(0.0, 0.0), (1e-4, 0.0), (3e-4, -4.5e-4), (-2e-4, 1.5e-4)] {
            for &i in &comps {
                for &j in &comps {
                    let a = ic.coefficient(i, j, x, y);
                    let b = ic.coefficient(j, i, -x, -y);
                    assert!(
                        (a - b).abs() <= 1e-12 * a.abs().max(1e-30),
                        "{i:?}{j:?} at ({x},{y})"
                    );
                }
            }
        }
    }

    #[test]
    fn far_field_quadrature_matches_the_closed_forms() {
        // Where the closed forms are still accurate (tens of elements),
        // the Gauss rule of far_coefficient agrees with them.
        let m = dissimilar();
        use Component::*;
        let comps = [X, Y, N];
        for ic in [
            HalfSpaceInfluence::new(1e-4, 1.5e-4, &m),
            HalfSpaceInfluence::plane_strain(1e-4, &m),
        ] {
            for &(x, y) in &[(6e-4, 0.0), (-1.3e-3, 4.5e-4), (5e-3, -3e-4)] {
                for &i in &comps {
                    for &j in &comps {
                        let exact = ic.coefficient(i, j, x, y);
                        let far = ic.far_coefficient(i, j, x, y).unwrap();
                        let scale = ic.coefficient(N, N, 0.0, 0.0);
                        assert!(
                            (far - exact).abs() <= 1e-12 * scale,
                            "{:?} {i:?}{j:?} at ({x},{y}): {far} vs {exact}",
                            ic.elasticity
                        );
                    }
                }
            }
            assert!(ic.far_coefficient(N, N, 7e-5, 0.0).is_none());
        }
    }

    #[test]
    fn viscoelastic_coefficients_tend_to_the_elastic_limits() {
        use crate::core::viscoelastic::{Sls, Viscoelastic};
        use Component::*;
        let m = steel();
        let visc = |ratio: f64, tc: f64| Viscoelastic {
            rolling_speed_m_per_s: 1.0,
            body1: Sls {
                relaxation_ratio: ratio,
                creep_relaxation_time_s: tc,
            },
            body2: Sls {
                relaxation_ratio: ratio,
                creep_relaxation_time_s: tc,
            },
        };
        let (dx, dy) = (1e-4, 1.2e-4);
        let ic = HalfSpaceInfluence::new(dx, dy, &m);
        // Relaxing at once: (1 + f_g) times the elastic coefficients.
        let v = ic.with_viscoelastic(&m, &visc(3.0, 0.0));
        for &(x, y) in &[(0.0, 0.0), (2e-4, -1.2e-4), (-5e-4, 0.0)] {
            for (i, j) in [(X, X), (Y, Y), (N, N), (X, Y)] {
                let want = 4.0 * ic.coefficient(i, j, x, y);
                let got = v.coefficient(i, j, x, y);
                assert!(
                    (got - want).abs() <= 1e-14 * want.abs().max(1e-20),
                    "{got} {want}"
                );
            }
        }
        // Relaxing slowly (L = 1e4 m on 0.1 mm elements): the relaxation
        // term fades like ln(L)/L on the half-space.
        let v = ic.with_viscoelastic(&m, &visc(1.0, 1e4));
        let a = ic.coefficient(N, N, 0.0, 0.0);
        let got = v.coefficient(N, N, 0.0, 0.0);
        assert!((got / a - 1.0).abs() < 1e-6, "{got} vs {a}");
        // In between, the term adds the average upstream (+x), where the
        // material was: not symmetric. Downstream of the loaded element
        // (X < 0) the material passed under it and remembers,
        // A(-X) > A(X) for X > 0; upstream it lies between the glassy and
        // the relaxed coefficient.
        let v = ic.with_viscoelastic(&m, &visc(1.0, 5e-4));
        let (up, down) = (
            v.coefficient(N, N, 3e-4, 0.0),
            v.coefficient(N, N, -3e-4, 0.0),
        );
        let (g, r) = (
            ic.coefficient(N, N, 3e-4, 0.0),
            2.0 * ic.coefficient(N, N, 3e-4, 0.0),
        );
        assert!(g < up && up < r && up < down, "{g} {up} {r} {down}");
        assert!(v.is_viscoelastic() && !ic.is_viscoelastic());
        // A relaxation length below the element size (0.1 mm on 0.55 mm):
        // finite coefficients near (1 + f_g) times the elastic ones.
        let ic = HalfSpaceInfluence::new(0.55e-3, 1.1e-3, &m);
        let v = ic.with_viscoelastic(&m, &visc(1.0, 1e-4));
        for k in -3..4 {
            for (i, j) in [(X, X), (Y, Y), (N, N)] {
                let x = k as f64 * 0.55e-3;
                let ratio = v.coefficient(i, j, x, 0.0) / ic.coefficient(i, j, x, 0.0);
                assert!((1.8..2.3).contains(&ratio), "{i:?}{j:?} at {x}: {ratio}");
            }
        }
        // The quadrature converges: to a thousandth of its tolerance the
        // coefficients change by less than the tolerance (relative to the
        // self coefficient), on the half-space and the half-plane, for
        // relaxation lengths from a fifth of an element to 10^4 elements.
        for ic in [
            HalfSpaceInfluence::new(0.55e-3, 1.1e-3, &m),
            HalfSpaceInfluence::plane_strain(0.55e-3, &m),
        ] {
            let scale = ic.coefficient(N, N, 0.0, 0.0);
            for l in [1e-4, 3e-3, 5.0] {
                let v = ic.with_viscoelastic(&m, &visc(1.0, l));
                let Some(t) = v.visc.map(|t| t.terms[0]) else {
                    panic!("no relaxation term")
                };
                let body = HalfSpaceInfluence {
                    visc: None,
                    visc_input: None,
                    ..v
                };
                for k in [-7, -1, 0, 1, 4] {
                    let x = k as f64 * 0.55e-3;
                    let at = |tol: f64| {
                        relaxed_average(
                            |s| body.relaxation_integrand(X, X, s, 0.0),
                            x,
                            t.length_m,
                            &[-0.275e-3, 0.275e-3],
                            tol * ic.inv_pi_g * ic.dx,
                        )
                    };
                    let (normal, tight) =
                        (at(QUADRATURE_TOLERANCE), at(1e-3 * QUADRATURE_TOLERANCE));
                    assert!(
                        (normal - tight).abs() <= QUADRATURE_TOLERANCE * scale,
                        "{:?} L {l} at {x}: {normal} vs {tight}",
                        ic.elasticity
                    );
                }
            }
        }
        // Elastic bodies given as viscoelastic (f_g = 0): the same bits.
        assert_eq!(ic.with_viscoelastic(&m, &visc(0.0, 1.0)), ic);
    }

    /// A kernel row is its offsets' kernels: the same bits for elastic
    /// bodies, within twice the quadrature's tolerance (each value's and
    /// the sweep's) for viscoelastic ones, from a relaxation length below
    /// an element to 10^4 elements.
    #[test]
    fn kernel_rows_are_their_offsets_kernels() {
        use crate::core::viscoelastic::{Sls, Viscoelastic};
        use Component::*;
        let m = steel();
        let ic = HalfSpaceInfluence::new(0.55e-3, 1.1e-3, &m);
        let scale = ic.coefficient(N, N, 0.0, 0.0);
        let mut row = [0.0; 11];
        for l in [None, Some(1e-4), Some(3e-3), Some(5.0)] {
            let v = match l {
                None => ic,
                Some(l) => ic.with_viscoelastic(
                    &m,
                    &Viscoelastic {
                        rolling_speed_m_per_s: 1.0,
                        body1: Sls {
                            relaxation_ratio: 1.0,
                            creep_relaxation_time_s: l,
                        },
                        body2: Sls::default(),
                    },
                ),
            };
            for kind in [KernelKind::Displacement, KernelKind::SteadyRolling] {
                let unit = match kind {
                    KernelKind::Displacement => scale,
                    KernelKind::SteadyRolling => scale / ic.dx,
                };
                for (i, j, ky) in [(X, X, 0), (Y, Y, -2), (N, N, 1), (X, N, 0), (X, Y, 3)] {
                    v.kernel_row(kind, i, j, -5, ky, &mut row);
                    for (k, got) in row.iter().enumerate() {
                        let want = v.kernel(kind, i, j, k as i64 - 5, ky);
                        if l.is_none() {
                            assert_eq!(got.to_bits(), want.to_bits());
                        } else {
                            assert!(
                                (got - want).abs() <= 2.0 * QUADRATURE_TOLERANCE * unit,
                                "{l:?} {kind:?} {i:?}{j:?} ({}, {ky}): {got} vs {want}",
                                k as i64 - 5
                            );
                        }
                    }
                }
            }
        }
    }
}
