//! Stresses and displacements below the contact surface of both bodies, from
//! the surface tractions of a solved patch.
//!
//! Each body is an elastic half-space loaded on its surface by the element
//! tractions, uniform over each element (as the surface problem assumes).
//! The stress tensor and the displacement at depth z below the centre of
//! every grid element are the sums over the loaded elements of closed-form
//! influence functions: Love's solution for a uniform pressure on a
//! rectangle and its tangential counterpart, obtained from the Boussinesq and
//! Cerruti potentials (Johnson 1985, eqs. 3.7; Love 1929), summed by FFT per
//! depth on the padded grid of [`crate::core::fft`] exactly as the surface
//! influence coefficients are.
//!
//! # Conventions
//!
//! * Frame: the axes of [`crate::core::problem`], x rolling, y lateral, n
//!   into body 1. Every body's stresses and displacements are reported in
//!   this one frame; the depth is measured into the body (n = +depth in
//!   body 1, n = −depth in body 2).
//! * Loads: the element tractions act on body 1 (p_n > 0 compression);
//!   body 2 carries their opposite.
//! * Stresses \[Pa\], tension positive. Under a pressure, sigma_nn < 0 in both
//!   bodies; sigma_xn and sigma_yn change sign between the bodies for the
//!   same tangential traction.
//! * Displacements \[m\] of the body's material relative to its points at
//!   infinity: under a pressure body 1 moves in +n, body 2 in −n.
//!
//! # Influence functions
//!
//! For a unit traction on the rectangle [x1, x2] x [y1, y2] of a
//! half-space z >= 0 (pressure p pushing into the body, shears q_x, q_y), with
//! X = xi − x, Y = eta − y, rho = sqrt(X² + Y² + z²), the potentials of
//! Johnson eq. 3.7 are corner sums C\[f\] = f(X2,Y2) − f(X1,Y2) − f(X2,Y1) +
//! f(X1,Y1) of double primitives: phi = ∫∫ 1/rho, H = ∫∫ ln(rho + z),
//! F1 = ∫∫ (z ln(rho + z) − rho), and every derivative with respect to the
//! field point is a corner sum of a closed form (each x-derivative a −d/dX of
//! the primitive). With these (Papkovich–Neuber form of Johnson eq. 3.7):
//!
//! ```text
//! pressure:  2 pi sigma_ij = −(1−2nu) H_ij − z phi_ij + (1−2nu)(d_iz phi_j + d_jz phi_i) + 2 nu phi_z d_ij
//!            4 pi G u      = −(1−2nu) grad H − z grad phi + (3−4nu) phi e_z
//! shear q_x: 2 pi sigma_ij = d_ix phi_j + d_jx phi_i + 2 nu psi1_ij − z psi_ij
//!                            − 2 nu (d_iz psi_j + d_jz psi_i) + 2 nu phi_x d_ij
//!            4 pi G u      = 2 phi e_x + 2 nu grad psi1 − z grad psi + (1−4nu) psi e_z
//! ```
//!
//! with psi1 = dF1/dx, psi = dF/dx, F = dF1/dz (q_y: x and y swapped). The
//! stresses depend on the body's Poisson ratio only; the displacements also
//! on its shear modulus. Each body has its own constants
//! ([`crate::core::material::CombinedMaterial::body1`], `body2`).
//!
//! # Cost
//!
//! Kernels ([`DepthKernels`]) are built once per depth, body material and
//! grid (closed forms on the (2 nx) x (2 ny) corner lattice, then 27
//! transforms); an evaluation ([`DepthKernels::apply`]) is three products
//! and nine inverse transforms per depth, after one forward transform of
//! the tractions per body ([`SubsurfaceWorkspace::load`]). Nothing
//! allocates in the evaluation.

use rustfft::num_complex::Complex64;
use serde::Serialize;

use crate::core::error::{require_positive, show, ContactError};
use crate::core::fft::{ConvolutionPlan, Spectrum, Workspace};
use crate::core::grid::Grid;
use crate::core::material::{CombinedMaterial, Material};
use crate::core::solution::ElementFields;

/// Most depths in one request.
pub const MAX_DEPTHS: usize = 256;
/// Largest depth \[m\] (a depth in mm, such as `2.5`, is out of range).
pub const MAX_DEPTH_M: f64 = 1.0;

/// The body whose field is computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Body {
    /// Body 1, on the +n side (the rail in wheel/rail contact).
    One,
    /// Body 2, on the −n side (the wheel).
    Two,
}

/// Stress components in storage order: xx, yy, nn, xy, xn, yn.
pub const STRESS_COMPONENTS: [&str; 6] = ["xx", "yy", "nn", "xy", "xn", "yn"];

/// A symmetric stress tensor \[Pa\] in the frame (x, y, n), tension positive.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Default)]
pub struct StressTensor {
    /// sigma_xx \[Pa\].
    pub xx: f64,
    /// sigma_yy \[Pa\].
    pub yy: f64,
    /// sigma_nn \[Pa\].
    pub nn: f64,
    /// sigma_xy \[Pa\].
    pub xy: f64,
    /// sigma_xn \[Pa\].
    pub xn: f64,
    /// sigma_yn \[Pa\].
    pub yn: f64,
}

impl StressTensor {
    /// Mean normal stress (sigma_xx + sigma_yy + sigma_nn) / 3 \[Pa\].
    pub fn hydrostatic(&self) -> f64 {
        (self.xx + self.yy + self.nn) / 3.0
    }

    /// Von Mises equivalent stress sqrt(3 J2) \[Pa\].
    pub fn von_mises(&self) -> f64 {
        let (a, b, c) = (self.xx - self.yy, self.yy - self.nn, self.nn - self.xx);
        let s = self.xy * self.xy + self.xn * self.xn + self.yn * self.yn;
        (0.5 * (a * a + b * b + c * c) + 3.0 * s).sqrt()
    }

    /// Principal stresses sigma_1 >= sigma_2 >= sigma_3 \[Pa\] (eigenvalues
    /// of the symmetric tensor by the trigonometric form of the cubic's
    /// roots: Smith, Comm. ACM 4 (1961) 168).
    pub fn principal(&self) -> [f64; 3] {
        let m = self.hydrostatic();
        let (a, b, c) = (self.xx - m, self.yy - m, self.nn - m);
        let off = self.xy * self.xy + self.xn * self.xn + self.yn * self.yn;
        let p2 = (a * a + b * b + c * c + 2.0 * off) / 6.0;
        if p2 <= f64::MIN_POSITIVE {
            return [m; 3];
        }
        let p = p2.sqrt();
        // det(deviator) / p^3 / 2, clamped to the domain of acos.
        let det = a * (b * c - self.yn * self.yn) - self.xy * (self.xy * c - self.yn * self.xn)
            + self.xn * (self.xy * self.yn - b * self.xn);
        let r = (det / (2.0 * p * p2)).clamp(-1.0, 1.0);
        let t = r.acos() / 3.0;
        let s1 = m + 2.0 * p * t.cos();
        let s3 = m + 2.0 * p * (t + 2.0 * std::f64::consts::FRAC_PI_3).cos();
        [s1, 3.0 * m - s1 - s3, s3]
    }

    /// Tresca equivalent stress sigma_1 − sigma_3 \[Pa\].
    pub fn tresca(&self) -> f64 {
        let [s1, _, s3] = self.principal();
        s1 - s3
    }

    /// Maximum shear stress (sigma_1 − sigma_3) / 2 \[Pa\].
    pub fn max_shear(&self) -> f64 {
        0.5 * self.tresca()
    }
}

/// Number of corner primitives.
const NPRIM: usize = 25;

// Indices of the corner primitives (see `corner`).
const LY: usize = 0;
const LX: usize = 1;
const AT: usize = 2;
const P0XX: usize = 3;
const P0YY: usize = 4;
const IR: usize = 5;
const P0XZ: usize = 6;
const P0YZ: usize = 7;
const QXX: usize = 8;
const QYY: usize = 9;
const LN: usize = 10;
const RXXX: usize = 11;
const RYYY: usize = 12;
const OX: usize = 13;
const OY: usize = 14;
const QXXX: usize = 15;
const QYYY: usize = 16;
const QXXY: usize = 17;
const QXYY: usize = 18;
const P0: usize = 19;
const QX: usize = 20;
const QY: usize = 21;
const RXX: usize = 22;
const RYY: usize = 23;
const OM: usize = 24;

/// 1 / (a + rho) for rho = sqrt(a² + s2), without cancellation for a < 0.
#[inline]
fn inv_plus(a: f64, rho: f64, s2: f64) -> f64 {
    if a >= 0.0 {
        1.0 / (a + rho)
    } else {
        (rho - a) / s2
    }
}

/// ln(a + rho) for rho = sqrt(a² + s2), without cancellation for a < 0.
#[inline]
fn ln_plus(a: f64, rho: f64, s2: f64) -> f64 {
    if a >= 0.0 {
        (a + rho).ln()
    } else {
        (s2 / (rho - a)).ln()
    }
}

/// The primitives at one corner (X, Y) of an element, depth z >= 0; each is
/// a derivative of phi, H or F1's double primitive (up to functions of X or
/// Y alone, which cancel in the corner sum).
#[inline]
fn corner(x: f64, y: f64, z: f64) -> [f64; NPRIM] {
    let (x2, y2, z2) = (x * x, y * y, z * z);
    let rho = (x2 + y2 + z2).sqrt();
    let ir = 1.0 / rho;
    let rz = rho + z;
    let irz = 1.0 / rz;
    // rho − z without cancellation.
    let rmz = (x2 + y2) * irz;
    let (xz2, yz2) = (x2 + z2, y2 + z2);
    let ly = ln_plus(y, rho, xz2);
    let lx = ln_plus(x, rho, yz2);
    let iyr = inv_plus(y, rho, xz2);
    let ixr = inv_plus(x, rho, yz2);
    let at = (x * y).atan2(z * rho);
    let qxx = (x * y * rmz).atan2(x2 * rho + z * y2);
    let qyy = (x * y * rmz).atan2(y2 * rho + z * x2);
    let ln = rz.ln();
    let qxxx = y * (z * rho - x2) * ir * irz / xz2;
    let qyyy = x * (z * rho - y2) * ir * irz / yz2;
    let mut c = [0.0; NPRIM];
    c[LY] = ly;
    c[LX] = lx;
    c[AT] = at;
    c[P0XX] = x * ir * iyr;
    c[P0YY] = y * ir * ixr;
    c[IR] = ir;
    c[P0XZ] = z * ir * iyr;
    c[P0YZ] = z * ir * ixr;
    c[QXX] = qxx;
    c[QYY] = qyy;
    c[LN] = ln;
    c[RXXX] = -ly - x2 * ir * iyr + z * qxxx;
    c[RYYY] = -lx - y2 * ir * ixr + z * qyyy;
    c[OX] = x * irz;
    c[OY] = y * irz;
    c[QXXX] = qxxx;
    c[QYYY] = qyyy;
    c[QXXY] = x * ir * irz;
    c[QXYY] = y * ir * irz;
    c[P0] = x * ly + y * lx - z * at;
    c[QX] = y * ln + z * ly + x * qxx;
    c[QY] = x * ln + z * lx + y * qyy;
    c[RXX] = z * qxx - x * ly;
    c[RYY] = z * qyy - y * lx;
    c[OM] = z * ln - rho;
    c
}

/// Responses to a unit uniform traction on one element, in the body's own
/// frame (z into the body): `stress[j]` (order of [`STRESS_COMPONENTS`])
/// [Pa/Pa] and `displacement[j]` (x, y, z) \[m/Pa\] for the load j = 0: q_x,
/// 1: q_y, 2: pressure.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnitResponse {
    /// Stresses per unit traction [-], `stress[load][component]`.
    pub stress: [[f64; 6]; 3],
    /// Displacements per unit traction \[m/Pa\], `displacement[load][axis]`.
    pub displacement: [[f64; 3]; 3],
}

/// The response from the corner sums `c` of the primitives at depth z.
fn response(c: &[f64; NPRIM], z: f64, material: &Material) -> UnitResponse {
    let nu = material.poisson_ratio;
    let k = 0.5 / std::f64::consts::PI;
    let g = 0.25 / (std::f64::consts::PI * material.shear_modulus_pa);
    let (phi_x, phi_y, phi_z) = (-c[LY], -c[LX], -c[AT]);
    let (phi_xx, phi_yy, phi_xy) = (c[P0XX], c[P0YY], c[IR]);
    let phi_zz = -phi_xx - phi_yy;
    let (phi_xz, phi_yz) = (-c[P0XZ], -c[P0YZ]);
    let (h_xx, h_yy, h_xy) = (c[QXX], c[QYY], c[LN]);
    let m = 1.0 - 2.0 * nu;
    let pressure = [
        k * (-m * h_xx - z * phi_xx + 2.0 * nu * phi_z),
        k * (-m * h_yy - z * phi_yy + 2.0 * nu * phi_z),
        k * (phi_z - z * phi_zz),
        k * (-m * h_xy - z * phi_xy),
        k * (-z * phi_xz),
        k * (-z * phi_yz),
    ];
    // q_x: psi1 = F1_x, psi = F_x.
    let p1xx = -c[RXXX];
    let p1xy = c[OX];
    let p1yy = -p1xx - phi_x;
    let pxx = -c[QXXX];
    let pxy = -c[QXXY];
    let pyy = -pxx - phi_xz;
    let shear_x = [
        k * ((2.0 + 2.0 * nu) * phi_x + 2.0 * nu * p1xx - z * pxx),
        k * (2.0 * nu * p1yy - z * pyy + 2.0 * nu * phi_x),
        k * (-z * phi_xz),
        k * (phi_y + 2.0 * nu * p1xy - z * pxy),
        k * (phi_z - z * phi_xx),
        k * (-z * phi_xy),
    ];
    // q_y: the same with x and y swapped.
    let r1yy = -c[RYYY];
    let r1xy = c[OY];
    let r1xx = -r1yy - phi_y;
    let ryy = -c[QYYY];
    let rxy = -c[QXYY];
    let rxx = -ryy - phi_yz;
    let shear_y = [
        k * (2.0 * nu * r1xx - z * rxx + 2.0 * nu * phi_y),
        k * ((2.0 + 2.0 * nu) * phi_y + 2.0 * nu * r1yy - z * ryy),
        k * (-z * phi_yz),
        k * (phi_x + 2.0 * nu * r1xy - z * rxy),
        k * (-z * phi_xy),
        k * (phi_z - z * phi_yy),
    ];
    let phi = c[P0];
    let (h_x, h_y) = (-c[QX], -c[QY]);
    let displacement = [
        [
            g * (2.0 * phi + 2.0 * nu * c[RXX] - z * h_xx),
            g * (2.0 * nu * c[OM] - z * h_xy),
            g * (m * h_x - z * phi_x),
        ],
        [
            g * (2.0 * nu * c[OM] - z * h_xy),
            g * (2.0 * phi + 2.0 * nu * c[RYY] - z * h_yy),
            g * (m * h_y - z * phi_y),
        ],
        [
            g * (-m * h_x - z * phi_x),
            g * (-m * h_y - z * phi_y),
            g * (2.0 * (1.0 - nu) * phi - z * phi_z),
        ],
    ];
    UnitResponse {
        stress: [shear_x, shear_y, pressure],
        displacement,
    }
}

/// The response at the field point offset (`x`, `y`) \[m\] from the centre of
/// an element of `dx` x `dy` \[m\], depth `z` >= 0 \[m\], in a body of
/// `material` (its own frame: z into the body, the load a unit traction
/// acting on the body). At `z` = 0 the point must not lie on an edge of the
/// element, where the surface stresses are singular (grid points, at
/// element centres, never do).
pub fn element_response(
    x: f64,
    y: f64,
    z: f64,
    dx: f64,
    dy: f64,
    material: &Material,
) -> UnitResponse {
    let (hx, hy) = (0.5 * dx, 0.5 * dy);
    let (x1, x2, y1, y2) = (-x - hx, -x + hx, -y - hy, -y + hy);
    let (a, b, c, d) = (
        corner(x2, y2, z),
        corner(x1, y2, z),
        corner(x2, y1, z),
        corner(x1, y1, z),
    );
    let mut s = [0.0; NPRIM];
    for i in 0..NPRIM {
        s[i] = a[i] - b[i] - c[i] + d[i];
    }
    response(&s, z, material)
}

/// Outputs per depth: six stresses, three displacements.
const OUTPUTS: usize = 9;

/// The transformed influence kernels of one body at one depth on one grid
/// (27 spectra: nine outputs times three loads). Immutable once built.
pub struct DepthKernels {
    /// Depth below the surface \[m\].
    pub depth_m: f64,
    /// `spectra[output * 3 + load]`.
    spectra: Vec<Spectrum<f64>>,
}

impl std::fmt::Debug for DepthKernels {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "DepthKernels(depth {} m)", self.depth_m)
    }
}

impl DepthKernels {
    /// Kernels of a body of `material` at `depth_m` >= 0 on `grid`, for the
    /// FFT `plan` of the grid's size.
    pub fn new(plan: &ConvolutionPlan, grid: &Grid, material: &Material, depth_m: f64) -> Self {
        let (nx, ny) = (grid.nx, grid.ny);
        let (dx, dy, z) = (grid.dx_m, grid.dy_m, depth_m);
        // Corner lattice: X = (m + 1/2) dx for m in [−nx, nx), Y likewise.
        let (cx, cy) = (2 * nx, 2 * ny);
        let mut lattice = Vec::with_capacity(cx * cy);
        for n in 0..cy {
            let y = (n as f64 - ny as f64 + 0.5) * dy;
            for m in 0..cx {
                let x = (m as f64 - nx as f64 + 0.5) * dx;
                lattice.push(corner(x, y, z));
            }
        }
        // Responses for offsets ox = ix(field) − ix(element) in (−nx, nx):
        // X2 = −ox dx + dx/2 is lattice column nx − ox, X1 the one before.
        let (wx, wy) = (2 * nx - 1, 2 * ny - 1);
        let mut table = Vec::with_capacity(wx * wy);
        for jy in 0..wy {
            let oy = jy as i64 - (ny as i64 - 1);
            let n2 = (ny as i64 - oy) as usize;
            for jx in 0..wx {
                let ox = jx as i64 - (nx as i64 - 1);
                let m2 = (nx as i64 - ox) as usize;
                let (a, b) = (&lattice[n2 * cx + m2], &lattice[n2 * cx + m2 - 1]);
                let (c, d) = (
                    &lattice[(n2 - 1) * cx + m2],
                    &lattice[(n2 - 1) * cx + m2 - 1],
                );
                let mut s = [0.0; NPRIM];
                for i in 0..NPRIM {
                    s[i] = a[i] - b[i] - c[i] + d[i];
                }
                let r = response(&s, z, material);
                let mut v = [0.0; OUTPUTS * 3];
                for load in 0..3 {
                    for o in 0..6 {
                        v[o * 3 + load] = r.stress[load][o];
                    }
                    for o in 0..3 {
                        v[(6 + o) * 3 + load] = r.displacement[load][o];
                    }
                }
                table.push(v);
            }
        }
        drop(lattice);
        let mut ws = plan.workspace();
        let spectra = (0..OUTPUTS * 3)
            .map(|q| {
                Spectrum::new(plan.kernel_spectrum(&mut ws, |ox, oy| {
                    let jx = (ox + nx as i64 - 1) as usize;
                    let jy = (oy + ny as i64 - 1) as usize;
                    table[jy * wx + jx][q]
                }))
            })
            .collect();
        Self { depth_m, spectra }
    }

    /// Memory held by the spectra \[bytes\].
    pub fn bytes(&self) -> usize {
        self.spectra.iter().map(Spectrum::bytes).sum()
    }

    /// The stresses (xx, yy, nn, xy, xn, yn) \[Pa\] and displacements (x, y,
    /// n) \[m\] at this depth, in the frame of [`crate::core::problem`], from
    /// the tractions loaded in `ws` ([`SubsurfaceWorkspace::load`]), into
    /// `out` (nine slices of `nx * ny`, the grid's order). No allocation.
    pub fn apply(
        &self,
        plan: &ConvolutionPlan,
        ws: &mut SubsurfaceWorkspace,
        out: [&mut [f64]; OUTPUTS],
    ) {
        for (o, dst) in out.into_iter().enumerate() {
            let mut first = true;
            for load in 0..3 {
                if ws.zero[load] {
                    continue;
                }
                self.spectra[o * 3 + load].apply(0, &ws.spec[load], &mut ws.acc, first);
                first = false;
            }
            if first {
                dst.fill(0.0);
                continue;
            }
            plan.inverse(&mut ws.fft, &mut ws.acc, dst);
            // Body 2's frame has z = −n: its xz, yz stresses and its
            // z displacement change sign in the common frame.
            if ws.body == Body::Two && matches!(o, 4 | 5 | 8) {
                for v in dst.iter_mut() {
                    *v = -*v;
                }
            }
        }
    }
}

/// Scratch space and the transformed tractions of one body (allocated once
/// per grid size).
pub struct SubsurfaceWorkspace {
    fft: Workspace,
    /// Spectra of the loads (q_x, q_y, p) on the body, in its frame.
    spec: [Vec<Complex64>; 3],
    /// Which loads are zero everywhere (not transformed, not applied).
    zero: [bool; 3],
    acc: Vec<Complex64>,
    body: Body,
}

impl SubsurfaceWorkspace {
    /// Buffers for `plan`.
    pub fn new(plan: &ConvolutionPlan) -> Self {
        let n = plan.spectrum_len();
        let z = Complex64::new(0.0, 0.0);
        Self {
            fft: plan.workspace(),
            spec: [vec![z; n], vec![z; n], vec![z; n]],
            zero: [true; 3],
            acc: vec![z; n],
            body: Body::One,
        }
    }

    /// Transforms the tractions (p_x, p_y, p_n) on body 1 \[Pa\] (grid order)
    /// as `body` sees them: body 2 carries (−p_x, −p_y) and, in its frame
    /// (x, y, −n), the same pressure. No allocation.
    pub fn load(&mut self, plan: &ConvolutionPlan, body: Body, tractions: [&[f64]; 3]) {
        self.body = body;
        for (load, field) in tractions.into_iter().enumerate() {
            self.zero[load] = field.iter().all(|&v| v == 0.0);
            if self.zero[load] {
                continue;
            }
            plan.forward(&mut self.fft, field, &mut self.spec[load]);
            if body == Body::Two && load < 2 {
                for v in &mut self.spec[load] {
                    *v = -*v;
                }
            }
        }
    }
}

/// Where and what a field's largest value is.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FieldPeak {
    /// The value \[Pa\].
    pub value_pa: f64,
    /// x of the element centre \[m\].
    pub x_m: f64,
    /// y of the element centre \[m\].
    pub y_m: f64,
    /// Depth below the surface \[m\].
    pub depth_m: f64,
}

/// Peaks of one body's subsurface field.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SubsurfaceSummary {
    /// Largest von Mises stress.
    pub max_von_mises: FieldPeak,
    /// Largest maximum shear stress (sigma_1 − sigma_3) / 2.
    pub max_shear: FieldPeak,
    /// Largest (most tensile) principal stress sigma_1.
    pub max_principal: FieldPeak,
    /// Smallest (most compressive) principal stress sigma_3.
    pub min_principal: FieldPeak,
}

/// The subsurface field of one body on the grid at a list of depths.
/// Values at depth k, element (ix, iy) are at index `(k * ny + iy) * nx + ix`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BodySubsurface {
    /// Which body.
    pub body: Body,
    /// The body's material.
    pub material: Material,
    /// The depths \[m\], in the order of the request.
    pub depths_m: Vec<f64>,
    /// Stresses \[Pa\], tension positive, in the order of
    /// [`STRESS_COMPONENTS`] (xx, yy, nn, xy, xn, yn).
    pub stress_pa: [Vec<f64>; 6],
    /// Displacements (x, y, n) \[m\].
    pub displacement_m: [Vec<f64>; 3],
}

impl BodySubsurface {
    /// The stress tensor at flat index `i`.
    pub fn stress(&self, i: usize) -> StressTensor {
        let s = &self.stress_pa;
        StressTensor {
            xx: s[0][i],
            yy: s[1][i],
            nn: s[2][i],
            xy: s[3][i],
            xn: s[4][i],
            yn: s[5][i],
        }
    }

    /// Peaks of the von Mises, maximum shear and principal stresses.
    pub fn summary(&self, grid: &Grid) -> SubsurfaceSummary {
        let n = grid.len();
        let peak = |value_pa, i: usize| {
            let (k, e) = (i / n, i % n);
            FieldPeak {
                value_pa,
                x_m: grid.x_m(e % grid.nx),
                y_m: grid.y_m(e / grid.nx),
                depth_m: self.depths_m[k],
            }
        };
        let mut best = [(f64::NEG_INFINITY, 0); 3];
        let mut low = (f64::INFINITY, 0);
        for i in 0..self.stress_pa[0].len() {
            let t = self.stress(i);
            let [s1, _, s3] = t.principal();
            for (b, v) in best.iter_mut().zip([t.von_mises(), 0.5 * (s1 - s3), s1]) {
                if v > b.0 {
                    *b = (v, i);
                }
            }
            if s3 < low.0 {
                low = (s3, i);
            }
        }
        SubsurfaceSummary {
            max_von_mises: peak(best[0].0, best[0].1),
            max_shear: peak(best[1].0, best[1].1),
            max_principal: peak(best[2].0, best[2].1),
            min_principal: peak(low.0, low.1),
        }
    }
}

/// Checks a list of depths \[m\]: 1 to [`MAX_DEPTHS`] values, each in [0,
/// [`MAX_DEPTH_M`]]; `key` names the input.
pub fn check_depths(key: &str, depths_m: &[f64]) -> Result<(), ContactError> {
    if depths_m.is_empty() || depths_m.len() > MAX_DEPTHS {
        return Err(ContactError::invalid(
            key,
            format!("must hold 1 to {MAX_DEPTHS} depths, got {}", depths_m.len()),
        ));
    }
    for (i, &z) in depths_m.iter().enumerate() {
        if !(0.0..=MAX_DEPTH_M).contains(&z) {
            return Err(ContactError::invalid(
                format!("{key}[{i}]"),
                format!(
                    "must be in [0, {MAX_DEPTH_M}] m (a depth below the surface), got {}",
                    show(z)
                ),
            ));
        }
    }
    Ok(())
}

/// The subsurface fields of both bodies at `depths_m` below the surface,
/// from the solved element tractions `fields` on `grid` (tractions on body 1).
/// Builds the kernels of each depth, evaluates and drops them (memory: 27
/// spectra at a time); body 2 shares body 1's kernels when their materials
/// are equal.
pub fn subsurface_fields(
    grid: &Grid,
    material: &CombinedMaterial,
    fields: &ElementFields,
    depths_m: &[f64],
) -> Result<[BodySubsurface; 2], ContactError> {
    check_depths("subsurface.depths_m", depths_m)?;
    let n = grid.len();
    for (key, f) in [
        ("fields.traction_x_pa", &fields.traction_x_pa),
        ("fields.traction_y_pa", &fields.traction_y_pa),
        ("fields.pressure_pa", &fields.pressure_pa),
    ] {
        if f.len() != n {
            return Err(ContactError::invalid(
                key,
                format!(
                    "must hold {n} values (the grid's elements), got {}",
                    f.len()
                ),
            ));
        }
        if let Some(v) = f.iter().find(|v| !v.is_finite()) {
            return Err(ContactError::invalid(
                key,
                format!("must be finite, got {}", show(*v)),
            ));
        }
    }
    require_positive("grid.dx_m", grid.dx_m)?;
    let plan = ConvolutionPlan::new(grid.nx, grid.ny);
    let tractions = [
        &fields.traction_x_pa[..],
        &fields.traction_y_pa[..],
        &fields.pressure_pa[..],
    ];
    let mut ws = [
        SubsurfaceWorkspace::new(&plan),
        SubsurfaceWorkspace::new(&plan),
    ];
    ws[0].load(&plan, Body::One, tractions);
    ws[1].load(&plan, Body::Two, tractions);
    let size = depths_m.len() * n;
    let mut out = [(Body::One, material.body1), (Body::Two, material.body2)].map(|(body, m)| {
        BodySubsurface {
            body,
            material: m,
            depths_m: depths_m.to_vec(),
            stress_pa: std::array::from_fn(|_| vec![0.0; size]),
            displacement_m: std::array::from_fn(|_| vec![0.0; size]),
        }
    });
    let same = material.body1 == material.body2;
    for (k, &z) in depths_m.iter().enumerate() {
        let r = k * n..(k + 1) * n;
        let k1 = DepthKernels::new(&plan, grid, &material.body1, z);
        let k2 = (!same).then(|| DepthKernels::new(&plan, grid, &material.body2, z));
        for (b, o) in out.iter_mut().enumerate() {
            let kernels = if b == 1 {
                k2.as_ref().unwrap_or(&k1)
            } else {
                &k1
            };
            let [s0, s1, s2, s3, s4, s5] = &mut o.stress_pa;
            let [u0, u1, u2] = &mut o.displacement_m;
            kernels.apply(
                &plan,
                &mut ws[b],
                [
                    &mut s0[r.clone()],
                    &mut s1[r.clone()],
                    &mut s2[r.clone()],
                    &mut s3[r.clone()],
                    &mut s4[r.clone()],
                    &mut s5[r.clone()],
                    &mut u0[r.clone()],
                    &mut u1[r.clone()],
                    &mut u2[r.clone()],
                ],
            );
        }
    }
    Ok(out)
}

/// Ekberg, Kabo and Andersson's surface fatigue index (Fatigue Fract. Engng
/// Mater. Struct. 25 (2002) 899–909, eq. 3), from Johnson's shakedown map
/// for a Hertzian contact: FI_surf = f − 2 pi a b k / (3 F_n), with f =
/// |F_t| / F_n the traction coefficient and k the material's yield stress
/// in pure shear. Surface-initiated fatigue is predicted for FI_surf > 0.
/// Here pi a b is the computed contact area `contact_area_m2` (for a Hertz
/// patch the index is f − k / p0). Returns None without normal force or
/// contact area.
pub fn surface_fatigue_index(
    normal_force_n: f64,
    tangential_force_n: f64,
    contact_area_m2: f64,
    shear_yield_stress_pa: f64,
) -> Option<f64> {
    (normal_force_n > 0.0 && contact_area_m2 > 0.0).then(|| {
        tangential_force_n.abs() / normal_force_n
            - 2.0 * contact_area_m2 * shear_yield_stress_pa / (3.0 * normal_force_n)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const S: [&str; 6] = STRESS_COMPONENTS;

    /// CONTACT's example `subsurf` (eve70a/CONTACT, examples/subsurf.inp,
    /// case 2; values from examples/subsurf.ref_subs): one element
    /// [-0.4999, 0.5001] x [-0.4998, 0.5002], p_n = 1, p_x = 0.999, G = 1,
    /// nu = 0.28 (lengths and stresses in consistent units). Rows: x, y, z,
    /// then UX UY UZ SIGXX SIGXY SIGXZ SIGYY SIGYZ SIGZZ as printed there
    /// (4 significant digits).
    const CONTACT_SUBSURF: [[f64; 12]; 7] = [
        [
            1e-5, 1e-5, 0.1, 0.3833, 0.9057e-5, 0.3796, -0.5559, 0.1078e-3, -0.7364, -0.5561,
            0.1572e-4, -0.9943,
        ],
        [
            1e-5, 1e-5, 0.5, 0.1753, -0.1049e-4, 0.2651, -0.7618e-1, 0.3147e-4, -0.1494,
            -0.7622e-1, 0.9310e-4, -0.7008,
        ],
        [
            1e-5, 1e-5, 1.0, 0.9495e-1, -0.7196e-5, 0.1705, 0.3977e-2, 0.5479e-5, -0.2418e-1,
            0.3971e-2, 0.4477e-4, -0.3361,
        ],
        [
            1e-5, 1e-5, 2.5, 0.3869e-1, -0.1726e-5, 0.7585e-1, 0.4458e-2, 0.2629e-6, -0.9270e-3,
            0.4458e-2, 0.5101e-5, -0.7161e-1,
        ],
        [
            0.2, -1.0, 0.5, 0.9858e-1, -0.1570e-1, 0.1265, -0.3742e-1, 0.5627e-1, -0.3070e-1,
            -0.1134, 0.9778e-1, -0.6626e-1,
        ],
        [
            -1.0, -2.0, 0.5, 0.5448e-1, 0.1317e-1, 0.4334e-1, 0.4347e-2, 0.1909e-1, -0.2084e-2,
            0.1097e-1, -0.3510e-2, 0.9465e-3,
        ],
        [
            0.0, -0.6, 0.5, 0.1348, -0.2027e-1, 0.1863, -0.4237e-1, 0.6564e-1, -0.6660e-1, -0.1212,
            0.1934, -0.2927,
        ],
    ];

    #[test]
    fn one_element_matches_contact_subsurf_example() {
        let m = Material {
            shear_modulus_pa: 1.0,
            poisson_ratio: 0.28,
        };
        let (cx, cy) = (0.0001, 0.0002);
        let (pn, px) = (1.0, 0.999);
        let mut worst: f64 = 0.0;
        for row in CONTACT_SUBSURF {
            let r = element_response(row[0] - cx, row[1] - cy, row[2], 1.0, 1.0, &m);
            let s = |c: usize| pn * r.stress[2][c] + px * r.stress[0][c];
            let u = |c: usize| pn * r.displacement[2][c] + px * r.displacement[0][c];
            // Reference order: ux uy uz xx xy xz yy yz zz.
            let ours = [u(0), u(1), u(2), s(0), s(3), s(4), s(1), s(5), s(2)];
            // The largest printed value of the row sets the absolute
            // tolerance: 4 significant digits, and CONTACT prints its
            // tiny values (1e-5) from the 1e-4 offset of its element.
            let scale = row[3..].iter().fold(0.0f64, |a, v| a.max(v.abs()));
            for (k, (&o, &r)) in ours.iter().zip(&row[3..]).enumerate() {
                let err = (o - r).abs() / scale;
                worst = worst.max(err);
                assert!(
                    err < 1e-3,
                    "point ({}, {}, {}) value {k}: ours {o:.5e}, CONTACT {r:.4e}",
                    row[0],
                    row[1],
                    row[2]
                );
            }
        }
        eprintln!(
            "largest difference from CONTACT's subsurf: {worst:.2e} of the row's largest value"
        );
    }

    #[test]
    fn surface_limits_are_the_applied_tractions() {
        // Just below a loaded element: sigma_nn = -p, sigma_xn = -q_x,
        // sigma_yn = -q_y (traction on the surface with outward normal -n);
        // below an unloaded one they vanish.
        let m = Material::STEEL;
        let z = 1e-9;
        let inside = element_response(1e-4, -2e-4, z, 1e-3, 1.2e-3, &m);
        let outside = element_response(2e-3, 0.0, z, 1e-3, 1.2e-3, &m);
        // Load j gives its own surface component -1 (xn, yn, nn).
        for (load, comp) in [(0, 4), (1, 5), (2, 2)] {
            assert!(
                (inside.stress[load][comp] + 1.0).abs() < 1e-5,
                "{load} {}",
                S[comp]
            );
            assert!(
                outside.stress[load][comp].abs() < 1e-5,
                "{load} {}",
                S[comp]
            );
        }
        for load in 0..3 {
            for comp in [2, 4, 5] {
                if (load, comp) != (0, 4) && (load, comp) != (1, 5) && (load, comp) != (2, 2) {
                    assert!(inside.stress[load][comp].abs() < 1e-5, "{load} {}", S[comp]);
                }
            }
        }
    }

    #[test]
    fn surface_displacements_match_the_surface_influence_coefficients() {
        // With a rigid body 2 the combined coefficients of core::influence
        // are body 1's surface displacements (Kalker 1990 §1.6: G = 2 G1,
        // K = (1 - 2 nu1)/2 ... ) for all nine pairs.
        use crate::core::influence::{Component, HalfSpaceInfluence};
        let body1 = Material {
            shear_modulus_pa: 80e9,
            poisson_ratio: 0.28,
        };
        let rigid = Material {
            shear_modulus_pa: 1e18,
            poisson_ratio: 0.28,
        };
        let cm = CombinedMaterial::new(body1, rigid).unwrap();
        let (dx, dy) = (1e-4, 1.5e-4);
        let ic = HalfSpaceInfluence::new(dx, dy, &cm);
        let comps = [Component::X, Component::Y, Component::N];
        for (x, y) in [(0.0, 0.0), (3e-4, -1.5e-4), (-2e-4, 4.5e-4)] {
            let r = element_response(x, y, 0.0, dx, dy, &body1);
            let scale = ic.coefficient(Component::N, Component::N, 0.0, 0.0);
            for (i, &ci) in comps.iter().enumerate() {
                for (j, &cj) in comps.iter().enumerate() {
                    let want = ic.coefficient(ci, cj, x, y);
                    let got = r.displacement[j][i];
                    assert!(
                        (got - want).abs() < 1e-6 * scale,
                        "u_{ci:?} from p_{cj:?} at ({x}, {y}): {got:e} vs {want:e}"
                    );
                }
            }
        }
    }

    /// A Hertz circle of radius `a` on an odd n x n grid (an element centred
    /// on the axis), pressure p0 sqrt(1 - r²/a²) at the element centres and
    /// a shear `mu` times it in +x.
    fn hertz_fields(n: usize, a: f64, p0: f64, mu: f64) -> (Grid, ElementFields) {
        let d = 2.4 * a / n as f64;
        let grid = Grid::new(n, n, d, d, -0.5 * n as f64 * d, -0.5 * n as f64 * d).unwrap();
        let mut f = ElementFields {
            pressure_pa: vec![0.0; grid.len()],
            traction_x_pa: vec![0.0; grid.len()],
            traction_y_pa: vec![0.0; grid.len()],
            ..Default::default()
        };
        for iy in 0..n {
            for ix in 0..n {
                let (x, y) = (grid.x_m(ix), grid.y_m(iy));
                let r2 = (x * x + y * y) / (a * a);
                let p = if r2 < 1.0 {
                    p0 * (1.0 - r2).sqrt()
                } else {
                    0.0
                };
                f.pressure_pa[grid.index(ix, iy)] = p;
                f.traction_x_pa[grid.index(ix, iy)] = mu * p;
            }
        }
        (grid, f)
    }

    /// Stresses on the axis of a Hertz circle, nu = 0.3 (Johnson 1985,
    /// Contact Mechanics, §3.4 and Fig. 4.3): sigma_z = -p0 / (1 + z²/a²),
    /// sigma_r = -p0 [(1 + nu)(1 - (z/a) atan(a/z)) - 1/(2 (1 + z²/a²))];
    /// the largest shear (sigma_r - sigma_z)/2 is about 0.31 p0 at 0.48 a.
    #[test]
    fn hertz_axis_stresses_and_largest_shear() {
        let (a, p0) = (1e-3, 1e9);
        let (grid, f) = hertz_fields(65, a, p0, 0.0);
        let m = CombinedMaterial::identical(Material::STEEL).unwrap();
        let nu = m.body1.poisson_ratio;
        let depths: Vec<f64> = (1..=30).map(|k| k as f64 * 0.05 * a).collect();
        let [b1, b2] = subsurface_fields(&grid, &m, &f, &depths).unwrap();
        let axis = grid.index(32, 32);
        let n = grid.len();
        let exact = |z: f64| {
            let t = z / a;
            let sz = -p0 / (1.0 + t * t);
            let sr = -p0 * ((1.0 + nu) * (1.0 - t * (1.0 / t).atan()) - 0.5 / (1.0 + t * t));
            (sz, sr)
        };
        let (mut worst_z, mut worst_r): (f64, f64) = (0.0, 0.0);
        for (k, &z) in depths.iter().enumerate() {
            let (sz, sr) = exact(z);
            let t = b1.stress(k * n + axis);
            worst_z = worst_z.max((t.nn - sz).abs() / p0);
            worst_r = worst_r.max((t.xx - sr).abs().max((t.yy - sr).abs()) / p0);
            // Body 2 (same steel, same pressure): the same normal stresses.
            let t2 = b2.stress(k * n + axis);
            assert!((t2.nn - t.nn).abs() < 1e-9 * p0 && (t2.xx - t.xx).abs() < 1e-9 * p0);
        }
        eprintln!(
            "Hertz axis, 65x65: |d sigma_z| <= {worst_z:.2e} p0, |d sigma_r| <= {worst_r:.2e} p0"
        );
        assert!(worst_z < 1e-3, "{worst_z}");
        assert!(worst_r < 1e-3, "{worst_r}");
        // The closed form's peak of the shear on the axis, by a fine scan.
        let (mut tau_ref, mut z_ref) = (0.0, 0.0);
        for i in 1..4000 {
            let z = i as f64 * 5e-4 * a;
            let (sz, sr) = exact(z);
            if 0.5 * (sr - sz) > tau_ref {
                (tau_ref, z_ref) = (0.5 * (sr - sz), z);
            }
        }
        let s = b1.summary(&grid);
        eprintln!(
            "largest shear: ours {:.4} p0 at {:.3} a, closed form {:.4} p0 at {:.3} a",
            s.max_shear.value_pa / p0,
            s.max_shear.depth_m / a,
            tau_ref / p0,
            z_ref / a
        );
        assert!((tau_ref / p0 - 0.31).abs() < 0.005 && (z_ref / a - 0.48).abs() < 0.01);
        assert!((s.max_shear.value_pa - tau_ref).abs() < 3e-3 * p0);
        assert!((s.max_shear.depth_m - z_ref).abs() <= 0.05 * a);
        assert!(s.max_shear.x_m.abs() < 1e-12 && s.max_shear.y_m.abs() < 1e-12);
    }

    /// Sliding Hertz circle, q_x = mu p on body 1: the largest tensile
    /// stress sits on the surface at the trailing edge x = -a,
    /// sigma_x = p0 [(1 - 2 nu)/3 + (4 + nu) pi mu / 8] (Hamilton and
    /// Goodman, J. Appl. Mech. 33 (1966) 371; Hamilton, Proc. IMechE 197C
    /// (1983) 53; Johnson 1985 §7.1). The two terms are checked apart: the
    /// pressure's, which is (1 - 2 nu) p0 a² / (3 r²) outside the circle
    /// (Johnson 1985 §3.4), at the first element outside; the shear's peak
    /// at the edge, which converges slowly (the traction has a square-root
    /// edge, the elements are uniform): the error falls with the mesh.
    #[test]
    fn sliding_circle_trailing_edge_tension_matches_hamilton() {
        let (a, p0) = (1e-3, 1e9);
        let m = CombinedMaterial::identical(Material::STEEL).unwrap();
        let nu = m.body1.poisson_ratio;
        let want_shear = (4.0 + nu) * std::f64::consts::PI / 8.0;
        let mut errors = Vec::new();
        for n in [129, 257] {
            let (grid, mut f) = hertz_fields(n, a, p0, 1.0);
            let pressure = std::mem::replace(&mut f.pressure_pa, vec![0.0; grid.len()]);
            let [shear, _] = subsurface_fields(&grid, &m, &f, &[0.0]).unwrap();
            f.pressure_pa = pressure;
            f.traction_x_pa.fill(0.0);
            let [normal, _] = subsurface_fields(&grid, &m, &f, &[0.0]).unwrap();
            let row = n / 2;
            let (mut peak, mut at) = (f64::NEG_INFINITY, 0.0);
            for ix in 0..row {
                let v = shear.stress_pa[0][grid.index(ix, row)] / p0;
                if v > peak {
                    (peak, at) = (v, grid.x_m(ix));
                }
            }
            // The first element centre outside the circle on the axis y = 0.
            let ix = (0..row).rev().find(|&ix| grid.x_m(ix) < -a).unwrap();
            let r = -grid.x_m(ix);
            let want_normal = (1.0 - 2.0 * nu) / 3.0 * (a * a) / (r * r);
            let got_normal = normal.stress_pa[0][grid.index(ix, row)] / p0;
            eprintln!(
                "{n}x{n}: shear term {peak:.4} at x = {:.3} a (Hamilton {want_shear:.4}); \
                 pressure term {got_normal:.4} at {:.3} a (closed form {want_normal:.4})",
                at / a,
                -r / a
            );
            assert!((got_normal / want_normal - 1.0).abs() < 0.02);
            assert!((at / a + 1.0).abs() < 0.03);
            errors.push((peak / want_shear - 1.0).abs());
        }
        assert!(
            errors[1] < 0.03 && errors[1] < 0.7 * errors[0],
            "{errors:?}"
        );
    }

    #[test]
    fn body_two_mirrors_body_one() {
        // Identical steel: body 2 under (-p_x, -p_y, p_n) in its frame
        // (x, y, -n) has the field of body 1 under the same loads with
        // sigma_xn, sigma_yn and u_n negated; for a load p_x alone, body 2's
        // field is body 1's with the tangential load reversed.
        let (a, p0) = (1e-3, 1e9);
        let (grid, mut f) = hertz_fields(17, a, p0, 0.2);
        f.traction_y_pa
            .iter_mut()
            .zip(&f.pressure_pa)
            .for_each(|(t, p)| *t = -0.1 * p);
        let m = CombinedMaterial::identical(Material::STEEL).unwrap();
        let depths = [0.2 * a, 0.6 * a];
        let [b1, b2] = subsurface_fields(&grid, &m, &f, &depths).unwrap();
        let mut g = f.clone();
        g.traction_x_pa.iter_mut().for_each(|v| *v = -*v);
        g.traction_y_pa.iter_mut().for_each(|v| *v = -*v);
        let [c1, _] = subsurface_fields(&grid, &m, &g, &depths).unwrap();
        for i in 0..b1.stress_pa[0].len() {
            for c in 0..6 {
                let sign = if c == 4 || c == 5 { -1.0 } else { 1.0 };
                assert!((b2.stress_pa[c][i] - sign * c1.stress_pa[c][i]).abs() < 1e-9 * p0);
            }
            assert!((b2.displacement_m[2][i] + c1.displacement_m[2][i]).abs() < 1e-20);
            assert!((b2.displacement_m[0][i] - c1.displacement_m[0][i]).abs() < 1e-20);
        }
        // And under pressure alone both bodies compress along n.
        let k = grid.index(8, 8);
        assert!(b1.stress_pa[2][k] < 0.0 && b2.stress_pa[2][k] < 0.0);
        assert!(b1.displacement_m[2][k] > 0.0 && b2.displacement_m[2][k] < 0.0);
    }

    #[test]
    fn dissimilar_bodies_use_their_own_constants() {
        // Stresses depend on nu only, displacements scale with 1/G: a soft
        // body 2 with body 1's Poisson ratio has body 1's stress magnitudes
        // and ten times its normal displacement.
        let (a, p0) = (1e-3, 1e9);
        let (grid, f) = hertz_fields(17, a, p0, 0.0);
        let soft = Material {
            shear_modulus_pa: Material::STEEL.shear_modulus_pa / 10.0,
            poisson_ratio: Material::STEEL.poisson_ratio,
        };
        let m = CombinedMaterial::new(Material::STEEL, soft).unwrap();
        let [b1, b2] = subsurface_fields(&grid, &m, &f, &[0.5 * a]).unwrap();
        let k = grid.index(8, 8);
        assert!((b2.stress_pa[2][k] - b1.stress_pa[2][k]).abs() < 1e-9 * p0);
        assert!((b2.displacement_m[2][k] / b1.displacement_m[2][k] + 10.0).abs() < 1e-9);
    }

    #[test]
    fn principal_stresses_are_the_eigenvalues() {
        let t = StressTensor {
            xx: -3.0,
            yy: 1.5,
            nn: 0.2,
            xy: 0.7,
            xn: -1.1,
            yn: 0.4,
        };
        let [s1, s2, s3] = t.principal();
        assert!(s1 >= s2 && s2 >= s3);
        assert!((s1 + s2 + s3 - (t.xx + t.yy + t.nn)).abs() < 1e-12);
        for s in [s1, s2, s3] {
            let (a, b, c) = (t.xx - s, t.yy - s, t.nn - s);
            let det = a * (b * c - t.yn * t.yn) - t.xy * (t.xy * c - t.yn * t.xn)
                + t.xn * (t.xy * t.yn - b * t.xn);
            assert!(det.abs() < 1e-10, "{s}: {det}");
        }
        // Von Mises from the principal stresses.
        let vm = (0.5 * ((s1 - s2).powi(2) + (s2 - s3).powi(2) + (s3 - s1).powi(2))).sqrt();
        assert!((t.von_mises() - vm).abs() < 1e-12);
        assert!((t.max_shear() - 0.5 * (s1 - s3)).abs() < 1e-15);
        let hydro = StressTensor {
            xx: -2.0,
            yy: -2.0,
            nn: -2.0,
            ..Default::default()
        };
        assert_eq!(hydro.principal(), [-2.0; 3]);
        assert_eq!(hydro.tresca(), 0.0);
    }

    #[test]
    fn bad_depths_and_fields_name_the_key() {
        let (grid, f) = hertz_fields(9, 1e-3, 1e9, 0.0);
        let m = CombinedMaterial::identical(Material::STEEL).unwrap();
        let e = subsurface_fields(&grid, &m, &f, &[]).unwrap_err();
        assert_eq!(e.key(), Some("subsurface.depths_m"));
        let e = subsurface_fields(&grid, &m, &f, &[1e-4, -1e-4]).unwrap_err();
        assert_eq!(e.key(), Some("subsurface.depths_m[1]"));
        let e = subsurface_fields(&grid, &m, &f, &[f64::NAN]).unwrap_err();
        assert_eq!(e.key(), Some("subsurface.depths_m[0]"));
        let e = subsurface_fields(&grid, &m, &f, &[0.0, 2.5]).unwrap_err();
        assert_eq!(e.key(), Some("subsurface.depths_m[1]"));
        let mut g = f.clone();
        g.traction_y_pa.pop();
        let e = subsurface_fields(&grid, &m, &g, &[1e-4]).unwrap_err();
        assert_eq!(e.key(), Some("fields.traction_y_pa"));
        let mut g = f;
        g.pressure_pa[3] = f64::INFINITY;
        let e = subsurface_fields(&grid, &m, &g, &[1e-4]).unwrap_err();
        assert_eq!(e.key(), Some("fields.pressure_pa"));
    }

    #[test]
    fn surface_fatigue_index_of_a_hertz_patch_is_f_minus_k_over_p0() {
        // Hertz circle: p0 = 3 Fn / (2 pi a²), so 2 pi a² k / (3 Fn) = k / p0.
        let (a, fn_) = (5e-3, 100e3);
        let p0 = 1.5 * fn_ / (std::f64::consts::PI * a * a);
        let k = 300e6;
        let fi = surface_fatigue_index(fn_, 0.35 * fn_, std::f64::consts::PI * a * a, k).unwrap();
        assert!((fi - (0.35 - k / p0)).abs() < 1e-12);
        assert!(surface_fatigue_index(0.0, 1.0, 1.0, k).is_none());
    }
}
