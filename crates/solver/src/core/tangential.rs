//! The tangential contact problem with Coulomb friction.
//!
//! Slip of body 1 relative to body 2 at element I (Kalker 1990, §2.2 and eq. 7
//! of Blanco-Lorenzo et al. 2018): s = w - du/dx (steady rolling, per unit
//! rolling speed) or s = w + u - u' (transient, per step, u' the previous
//! displacement difference). Coulomb's law per element, with bound g = mu p_n:
//! |p_t| <= g; |p_t| < g implies s = 0 (adhesion); |p_t| = g implies
//! p_t = -g s/|s| (slip).
//!
//! Solvers:
//!
//! * [`solve_transient`]: the shift (transient) problem is the convex program
//!   min ½ pᵀ A p + cᵀ p over |p_I| <= g_I (Kalker's variational principle), solved by
//!   accelerated projected gradients (FISTA, Beck & Teboulle 2009) with
//!   gradient restart (O'Donoghue & Candès 2015) and step 1/L, L the spectral
//!   bound of the FFT symbol. Convergence to the unique minimiser is
//!   guaranteed for any convex problem; each iteration is one FFT matvec.
//!   The driver ([`crate::core::solve`]) tries the Newton solver of
//!   [`crate::core::steady`] first (about half the products) and falls back
//!   to this one.
//!
//! * [`solve_steady_marching`]: steady rolling as the limit of transient
//!   rolling with steps of one element, each step a convex problem as above,
//!   stopped by the residual of Kalker's steady-state operator
//!   (A(X) - A(X+dx))/dx. Robust but costly (hundreds of steps, thousands
//!   of matvecs): the fallback of the fast steady solver,
//!   [`crate::core::steady::solve_steady_newton`], and its reference in tests.
//!
//! All stop when the natural residual max_I |p_I - P_I(p_I - s_I / d)| / max g,
//! with P_I the projection on the disk of radius g_I and d the mean of the
//! two diagonal influence coefficients, is below the tolerance. It is zero
//! exactly when Coulomb's law holds at every element.
//!
//! Static and kinetic friction: every solver here bounds each element by
//! one fixed coefficient during a solve, the kinetic one on the elements
//! marked [`ElementState::Slip`] in [`TangentialInput::previous_state`]
//! (the kinetic set), the static one elsewhere: each solve is Coulomb's
//! problem with fixed bounds. The driver ([`crate::core::solve`]) grows the
//! kinetic set from pass to pass by the rule of Coulomb's law with two
//! coefficients: the static coefficient bounds sticking elements, the
//! kinetic one sliding elements; an element enters slip when its traction
//! would exceed mu_static p_n, and once in slip it keeps the kinetic bound
//! (it sticks again only within mu_kinetic p_n).

use crate::core::cancel;
use crate::core::fft::{KernelSet, OperatorWorkspace};
use crate::core::grid::Grid;
use crate::core::influence::Component;
use crate::core::memory::{heap_bytes, HeapBytes};
use crate::core::problem::Carry;
use crate::core::solution::ElementState;

/// Settings of the tangential solvers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TangentialSettings {
    /// Natural-residual tolerance relative to max mu p_n [-] (default 1e-7).
    pub tolerance: f64,
    /// Iteration limit of one tangential solve (default 2000): its Newton
    /// steps and the time-marching or FISTA iterations of a fallback count
    /// together.
    pub max_iterations: usize,
    /// Precondition the Newton steps' GMRES (steady rolling and transient
    /// steps, planar and conformal) with the inverse of the circulant
    /// tangential operator as well as the local model (default true; see
    /// `core::steady`). It changes the number of products, not the answer
    /// beyond the tolerance; false is for comparisons.
    pub global_preconditioner: bool,
}

impl Default for TangentialSettings {
    fn default() -> Self {
        Self {
            tolerance: 1e-7,
            max_iterations: 2000,
            global_preconditioner: true,
        }
    }
}

/// Outcome of a tangential solve.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TangentialOutcome {
    /// Outer iterations.
    pub iterations: usize,
    /// FFT matvecs.
    pub matvecs: usize,
    /// Final natural residual relative to max bound.
    pub residual: f64,
    /// Whether the tolerance was met.
    pub converged: bool,
}

impl TangentialOutcome {
    /// This outcome of a solve that continued from `earlier`'s iterate:
    /// its residual and convergence, the iterations and matvecs of both.
    pub fn after(self, earlier: &TangentialOutcome) -> Self {
        Self {
            iterations: earlier.iterations + self.iterations,
            matvecs: earlier.matvecs + self.matvecs,
            ..self
        }
    }
}

/// Friction coefficients applied by the solvers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrictionBounds {
    /// Static coefficient [-].
    pub static_coefficient: f64,
    /// Kinetic coefficient [-].
    pub kinetic_coefficient: f64,
}

/// Exact solution of one element's Coulomb problem s = q + d∘p.
/// Returns (p, state, slip).
#[inline]
pub fn local_coulomb(
    q: [f64; 2],
    d: [f64; 2],
    g_static: f64,
    g_kinetic: f64,
) -> ([f64; 2], ElementState, [f64; 2]) {
    let pa = [-q[0] / d[0], -q[1] / d[1]];
    if pa[0] * pa[0] + pa[1] * pa[1] <= g_static * g_static {
        return (pa, ElementState::Adhesion, [0.0, 0.0]);
    }
    let g = g_kinetic;
    if g <= 0.0 {
        return ([0.0, 0.0], ElementState::Slip, q);
    }
    // p = -g (c, s) with s_vec = lam (c, s), lam >= 0:
    // q_i = (lam + g d_i) e_i, |e| = 1  =>  phi(lam) = sum (q_i/(lam + g d_i))² - 1 = 0.
    let qn = (q[0] * q[0] + q[1] * q[1]).sqrt();
    let mut lam = (qn - g * d[0].max(d[1])).max(0.0);
    for _ in 0..30 {
        let a0 = lam + g * d[0];
        let a1 = lam + g * d[1];
        let t0 = q[0] / a0;
        let t1 = q[1] / a1;
        let phi = t0 * t0 + t1 * t1 - 1.0;
        let dphi = -2.0 * (t0 * t0 / a0 + t1 * t1 / a1);
        if dphi == 0.0 {
            break;
        }
        let step = phi / dphi;
        lam -= step;
        if lam < 0.0 {
            lam = 0.0;
        }
        if step.abs() <= 1e-15 * (lam + g * d[0]) {
            break;
        }
    }
    let e = [q[0] / (lam + g * d[0]), q[1] / (lam + g * d[1])];
    let en = (e[0] * e[0] + e[1] * e[1]).sqrt().max(f64::MIN_POSITIVE);
    let e = [e[0] / en, e[1] / en];
    (
        [-g * e[0], -g * e[1]],
        ElementState::Slip,
        [lam * e[0], lam * e[1]],
    )
}

/// Natural residual of element I: |p - P(p - s/d)|, with one scalar d > 0
/// for both components. (A per-component scaling would not do: p = P(p -
/// D⁻¹s) makes p antiparallel to D⁻¹s, not to s, when D is not a multiple
/// of the identity, so it is not Coulomb's law.)
#[inline]
pub(crate) fn natural_residual(p: [f64; 2], s: [f64; 2], d: f64, g: f64) -> f64 {
    let mut z = [p[0] - s[0] / d, p[1] - s[1] / d];
    let zn = (z[0] * z[0] + z[1] * z[1]).sqrt();
    if zn > g {
        let c = if zn > 0.0 { g / zn } else { 0.0 };
        z = [z[0] * c, z[1] * c];
    }
    ((p[0] - z[0]).powi(2) + (p[1] - z[1]).powi(2)).sqrt()
}

/// Tangential state and buffers (allocated once per grid).
#[derive(Clone)]
pub struct TangentialScratch {
    sx: Vec<f64>,
    sy: Vec<f64>,
    yx: Vec<f64>,
    yy: Vec<f64>,
    qx: Vec<f64>,
    qy: Vec<f64>,
}

impl TangentialScratch {
    /// Buffers for `n` elements.
    pub fn new(n: usize) -> Self {
        Self {
            sx: vec![0.0; n],
            sy: vec![0.0; n],
            yx: vec![0.0; n],
            yy: vec![0.0; n],
            qx: vec![0.0; n],
            qy: vec![0.0; n],
        }
    }
}

impl HeapBytes for TangentialScratch {
    fn heap_bytes(&self) -> usize {
        heap_bytes!(self.sx, self.sy, self.yx, self.yy, self.qx, self.qy)
    }
}

/// Inputs shared by both tangential solvers.
pub struct TangentialInput<'a> {
    /// The grid.
    pub grid: &'a Grid,
    /// Normal pressure \[Pa\] (fixed during the tangential solve).
    pub pn: &'a [f64],
    /// Friction coefficients.
    pub friction: FrictionBounds,
    /// Fixed part of the slip, x: rigid slip plus contributions that do not
    /// depend on p_t (normal coupling, previous displacements).
    pub cx: &'a [f64],
    /// Fixed part of the slip, y.
    pub cy: &'a [f64],
    /// The kinetic set: the elements marked [`ElementState::Slip`] are
    /// bounded by the kinetic coefficient, the others by the static one,
    /// for the whole solve (see the module docs; the driver passes the
    /// elements that slid in its earlier passes). Any marking will do when
    /// the two coefficients are equal.
    pub previous_state: &'a [ElementState],
}

/// Output buffers of a tangential solve.
pub struct TangentialOutput<'a> {
    /// Traction x \[Pa\]: initial guess in, solution out.
    pub px: &'a mut [f64],
    /// Traction y \[Pa\]: initial guess in, solution out.
    pub py: &'a mut [f64],
    /// Slip x out.
    pub sx: &'a mut [f64],
    /// Slip y out.
    pub sy: &'a mut [f64],
    /// Element states out.
    pub state: &'a mut [ElementState],
}

fn tangential_matvec(
    k: &KernelSet,
    ows: &mut OperatorWorkspace,
    px: &[f64],
    py: &[f64],
    ux: &mut [f64],
    uy: &mut [f64],
) {
    k.apply(
        ows,
        &[(Component::X, px), (Component::Y, py)],
        &mut [(Component::X, ux), (Component::Y, uy)],
    );
}

/// Steady rolling by time marching: transient rolling steps of one element
/// length (dq = dx), each a convex shift problem solved by
/// [`solve_transient`], until the steady-state residual with the exact
/// steady operator is below the tolerance. Every step is convergent, and
/// the marching reaches the steady state once the material has crossed the
/// patch (Kalker 1990, §5.4: the steady state is the limit of transient
/// rolling). `k` is the displacement kernel set; `cx`, `cy` in `input` hold
/// the steady rigid slip w (plus coupling) [-]. Every step bounds the
/// elements by `input`'s kinetic set, so the limit is the steady problem
/// [`crate::core::steady::solve_steady_newton`] solves with those bounds.
#[allow(clippy::too_many_arguments)]
pub fn solve_steady_marching(
    k: &KernelSet,
    ows: &mut OperatorWorkspace,
    input: &TangentialInput<'_>,
    out: TangentialOutput<'_>,
    scratch: &mut TangentialScratch,
    marching: &mut MarchingScratch,
    settings: &TangentialSettings,
) -> TangentialOutcome {
    let grid = input.grid;
    let (nx, ny) = (grid.nx, grid.ny);
    let n = nx * ny;
    let dx = grid.dx_m;
    let TangentialOutput {
        px,
        py,
        sx,
        sy,
        state,
    } = out;
    let MarchingScratch {
        shx,
        shy,
        ashx,
        ashy,
        cx,
        cy,
        apx,
        apy,
    } = marching;
    // Diagonal of the steady operator A(I - S)/dx.
    let d = [
        (k.value(Component::X, Component::X, 0, 0) - k.value(Component::X, Component::X, 1, 0))
            / dx,
        (k.value(Component::Y, Component::Y, 0, 0) - k.value(Component::Y, Component::Y, 1, 0))
            / dx,
    ];
    let dbar = 0.5 * (d[0] + d[1]);
    let (mus, muk) = (
        input.friction.static_coefficient,
        input.friction.kinetic_coefficient,
    );
    let gmax = input.pn.iter().fold(0.0f64, |a, &v| a.max(v)) * mus.max(muk);
    let mut matvecs = 0;
    let mut iterations = 0;
    let mut residual = f64::INFINITY;
    // The material crosses the grid in nx steps; ten crossings are plenty
    // when the marching converges at all.
    let max_steps = settings.max_iterations.min(10 * nx);
    let mut inner = TangentialSettings {
        tolerance: 0.25 * settings.tolerance,
        ..*settings
    };
    for i in 0..n {
        if input.pn[i] <= 0.0 {
            px[i] = 0.0;
            py[i] = 0.0;
        }
    }
    for step in 0..=max_steps {
        if cancel::requested() {
            break;
        }
        // Shifted tractions: material at I was at I+1 (upstream) one step ago.
        shift_upstream(grid, 1, px, shx);
        shift_upstream(grid, 1, py, shy);
        tangential_matvec(k, ows, shx, shy, ashx, ashy);
        matvecs += 1;
        if step > 0 {
            // Steady residual of the current iterate: s = w + (A p - A S p)/dx.
            let mut res: f64 = 0.0;
            for i in 0..n {
                if input.pn[i] <= 0.0 {
                    continue;
                }
                let kinetic = input.previous_state[i] == ElementState::Slip;
                let g = input.pn[i] * if kinetic { muk } else { mus };
                let s = [
                    input.cx[i] + (apx[i] - ashx[i]) / dx,
                    input.cy[i] + (apy[i] - ashy[i]) / dx,
                ];
                res = res.max(natural_residual([px[i], py[i]], s, dbar, g));
            }
            residual = if gmax > 0.0 { res / gmax } else { 0.0 };
            if residual <= settings.tolerance || step == max_steps {
                for i in 0..n {
                    sx[i] = input.cx[i] + (apx[i] - ashx[i]) / dx;
                    sy[i] = input.cy[i] + (apy[i] - ashy[i]) / dx;
                    if state[i] != ElementState::Slip {
                        sx[i] = 0.0;
                        sy[i] = 0.0;
                    }
                }
                break;
            }
        }
        iterations = step + 1;
        // Inner accuracy follows the outer residual: early steps need little.
        inner.tolerance = (0.1 * residual).clamp(0.25 * settings.tolerance, 1e-2);
        for i in 0..n {
            cx[i] = dx * input.cx[i] - ashx[i];
            cy[i] = dx * input.cy[i] - ashy[i];
        }
        // Warm start: the shifted tractions. The steps keep the solve's
        // kinetic set (not the states carried from the step before): their
        // limit is the steady problem with those bounds.
        px.copy_from_slice(shx);
        py.copy_from_slice(shy);
        let step_input = TangentialInput {
            grid,
            pn: input.pn,
            friction: input.friction,
            cx,
            cy,
            previous_state: input.previous_state,
        };
        let o = solve_transient(
            k,
            ows,
            &step_input,
            TangentialOutput {
                px,
                py,
                sx: apx,
                sy: apy,
                state,
            },
            scratch,
            &inner,
        );
        matvecs += o.matvecs;
        // A p of the step's answer (solve_transient leaves it in its scratch).
        apx.copy_from_slice(&scratch.sx);
        apy.copy_from_slice(&scratch.sy);
        for i in 0..n {
            apx[i] -= cx[i];
            apy[i] -= cy[i];
        }
    }
    TangentialOutcome {
        iterations,
        matvecs,
        residual,
        converged: residual <= settings.tolerance,
    }
}

/// `dst[I] = src[I + k]` along every grid line (x), with the default value
/// past the leading edge: the field `k` elements upstream, where the
/// material at I was one rolling step of k dx ago. `k` must be below `nx`.
pub fn shift_upstream<T: Copy + Default>(grid: &Grid, k: usize, src: &[T], dst: &mut [T]) {
    let nx = grid.nx;
    for (s, d) in src.chunks_exact(nx).zip(dst.chunks_exact_mut(nx)) {
        d[..nx - k].copy_from_slice(&s[k..]);
        d[nx - k..].fill(T::default());
    }
}

/// `dst` = `src` where the material now at each element was before a
/// transient step that carries its fields by `carry`
/// ([`crate::core::problem::ShiftStep::carry`]): [`shift_upstream`] by
/// whole elements, else [`carry_upstream`] between element centres.
pub fn carry_field(grid: &Grid, carry: Carry, src: &[f64], dst: &mut [f64]) {
    match carry {
        Carry::Whole(k) => shift_upstream(grid, k, src, dst),
        Carry::Oblique(e) => carry_upstream(grid, e, src, dst),
    }
}

/// [`carry_field`] of a field that does not interpolate (element states, a
/// friction law's memory): [`carry_upstream_nearest`] off the element
/// centres.
pub fn carry_field_nearest<T: Copy + Default>(grid: &Grid, carry: Carry, src: &[T], dst: &mut [T]) {
    match carry {
        Carry::Whole(k) => shift_upstream(grid, k, src, dst),
        Carry::Oblique(e) => carry_upstream_nearest(grid, e, src, dst),
    }
}

/// `dst(x, y) = src(x + ex dx, y + ey dy)` for `[ex, ey]` = `elements`
/// (ex in [0, nx), |ey| < ny): the field where the material at each element
/// was one oblique rolling step ago ([`crate::core::frame`]), bilinear
/// between the four element centres around that point, those outside the
/// grid counting 0 (no traction or pressure outside the potential contact
/// area). A whole number of elements along x gives [`shift_upstream`]'s
/// values.
pub fn carry_upstream(grid: &Grid, elements: [f64; 2], src: &[f64], dst: &mut [f64]) {
    let (nx, ny) = (grid.nx as isize, grid.ny as isize);
    let at = |ix: isize, iy: isize| {
        if (0..nx).contains(&ix) && (0..ny).contains(&iy) {
            src[(iy * nx + ix) as usize]
        } else {
            0.0
        }
    };
    let (fx, fy) = (elements[0].floor(), elements[1].floor());
    let (tx, ty) = (elements[0] - fx, elements[1] - fy);
    let (kx, ky) = (fx as isize, fy as isize);
    for iy in 0..ny {
        for ix in 0..nx {
            let (x0, y0) = (ix + kx, iy + ky);
            let lower = (1.0 - tx) * at(x0, y0) + tx * at(x0 + 1, y0);
            let upper = (1.0 - tx) * at(x0, y0 + 1) + tx * at(x0 + 1, y0 + 1);
            dst[(iy * nx + ix) as usize] = (1.0 - ty) * lower + ty * upper;
        }
    }
}

/// [`carry_upstream`] of a field that does not interpolate (element states,
/// a friction law's memory): the value of the element nearest to where the
/// material was, the default outside the grid.
pub fn carry_upstream_nearest<T: Copy + Default>(
    grid: &Grid,
    elements: [f64; 2],
    src: &[T],
    dst: &mut [T],
) {
    let (nx, ny) = (grid.nx as isize, grid.ny as isize);
    let (kx, ky) = (elements[0].round() as isize, elements[1].round() as isize);
    for iy in 0..ny {
        for ix in 0..nx {
            let (jx, jy) = (ix + kx, iy + ky);
            dst[(iy * nx + ix) as usize] = if (0..nx).contains(&jx) && (0..ny).contains(&jy) {
                src[(jy * nx + jx) as usize]
            } else {
                T::default()
            };
        }
    }
}

/// Extra buffers of [`solve_steady_marching`].
#[derive(Clone)]
pub struct MarchingScratch {
    shx: Vec<f64>,
    shy: Vec<f64>,
    ashx: Vec<f64>,
    ashy: Vec<f64>,
    cx: Vec<f64>,
    cy: Vec<f64>,
    apx: Vec<f64>,
    apy: Vec<f64>,
}

impl MarchingScratch {
    /// Buffers for `n` elements.
    pub fn new(n: usize) -> Self {
        let z = || vec![0.0; n];
        Self {
            shx: z(),
            shy: z(),
            ashx: z(),
            ashy: z(),
            cx: z(),
            cy: z(),
            apx: z(),
            apy: z(),
        }
    }
}

impl HeapBytes for MarchingScratch {
    fn heap_bytes(&self) -> usize {
        heap_bytes!(self.shx, self.shy, self.ashx, self.ashy, self.cx, self.cy, self.apx, self.apy)
    }
}

/// States and slips of a transient step's answer: each element sorted by
/// its local problem with the bound it was solved with (the kinetic set's).
#[allow(clippy::too_many_arguments)]
fn finish_states(
    input: &TangentialInput<'_>,
    px: &[f64],
    py: &[f64],
    ux: &[f64],
    uy: &[f64],
    d: [f64; 2],
    sx: &mut [f64],
    sy: &mut [f64],
    state: &mut [ElementState],
) {
    let (mus, muk) = (
        input.friction.static_coefficient,
        input.friction.kinetic_coefficient,
    );
    for i in 0..input.pn.len() {
        if input.pn[i] <= 0.0 {
            state[i] = ElementState::Exterior;
            sx[i] = 0.0;
            sy[i] = 0.0;
            continue;
        }
        let kinetic = input.previous_state[i] == ElementState::Slip;
        let g = input.pn[i] * if kinetic { muk } else { mus };
        let q = [ux[i] - d[0] * px[i], uy[i] - d[1] * py[i]];
        let (_, st, _) = local_coulomb(q, d, g, g);
        state[i] = st;
        if st == ElementState::Adhesion {
            sx[i] = 0.0;
            sy[i] = 0.0;
        } else {
            sx[i] = ux[i];
            sy[i] = uy[i];
        }
    }
}

/// Transient (shift) problem: `k` must be the displacement kernel set; `cx`,
/// `cy` hold the rigid shift minus the previous displacement difference plus
/// any normal-coupling displacement \[m\].
pub fn solve_transient(
    k: &KernelSet,
    ows: &mut OperatorWorkspace,
    input: &TangentialInput<'_>,
    out: TangentialOutput<'_>,
    scratch: &mut TangentialScratch,
    settings: &TangentialSettings,
) -> TangentialOutcome {
    let n = input.pn.len();
    let (mus, muk) = (
        input.friction.static_coefficient,
        input.friction.kinetic_coefficient,
    );
    let pn = input.pn;
    let bound = |i: usize| -> f64 {
        if pn[i] <= 0.0 {
            0.0
        } else if input.previous_state[i] == ElementState::Slip {
            pn[i] * muk
        } else {
            pn[i] * mus
        }
    };
    let gmax = (0..n).map(bound).fold(0.0f64, f64::max);
    let d = [
        k.value(Component::X, Component::X, 0, 0),
        k.value(Component::Y, Component::Y, 0, 0),
    ];
    let dbar = 0.5 * (d[0] + d[1]);
    let TangentialOutput {
        px,
        py,
        sx,
        sy,
        state,
    } = out;
    let TangentialScratch {
        sx: ux,
        sy: uy,
        yx,
        yy,
        qx,
        qy,
    } = scratch;
    let step = 1.0 / k.tangential_norm_bound;
    // Project the initial guess.
    for i in 0..n {
        let g = bound(i);
        let m = (px[i] * px[i] + py[i] * py[i]).sqrt();
        if m > g {
            let c = if m > 0.0 { g / m } else { 0.0 };
            px[i] *= c;
            py[i] *= c;
        }
    }
    yx.copy_from_slice(px);
    yy.copy_from_slice(py);
    let mut t = 1.0f64;
    let mut matvecs = 0;
    let mut iterations = 0;
    for it in 0..=settings.max_iterations {
        if cancel::requested() {
            break;
        }
        // Gradient at the extrapolated point y.
        tangential_matvec(k, ows, yx, yy, ux, uy);
        matvecs += 1;
        for i in 0..n {
            ux[i] += input.cx[i];
            uy[i] += input.cy[i];
        }
        // qx, qy <- previous iterate; px, py <- projected gradient step from y.
        qx.copy_from_slice(px);
        qy.copy_from_slice(py);
        let mut res: f64 = 0.0;
        for i in 0..n {
            let g = bound(i);
            // Residual at y (cheap and a good proxy; exact check at the end).
            res = res.max(natural_residual([yx[i], yy[i]], [ux[i], uy[i]], dbar, g));
            let mut zx = yx[i] - step * ux[i];
            let mut zy = yy[i] - step * uy[i];
            let m = (zx * zx + zy * zy).sqrt();
            if m > g {
                let c = if m > 0.0 { g / m } else { 0.0 };
                zx *= c;
                zy *= c;
            }
            px[i] = zx;
            py[i] = zy;
        }
        let r = if gmax > 0.0 { res / gmax } else { 0.0 };
        if r <= settings.tolerance || it == settings.max_iterations {
            // y satisfied the tolerance: keep it as the answer.
            px.copy_from_slice(yx);
            py.copy_from_slice(yy);
            break;
        }
        iterations = it + 1;
        // Restart when the momentum points uphill.
        let mut dot = 0.0;
        for i in 0..n {
            dot += (yx[i] - px[i]) * (px[i] - qx[i]) + (yy[i] - py[i]) * (py[i] - qy[i]);
        }
        let t_new = if dot > 0.0 {
            1.0
        } else {
            0.5 * (1.0 + (1.0 + 4.0 * t * t).sqrt())
        };
        let beta = if dot > 0.0 { 0.0 } else { (t - 1.0) / t_new };
        t = t_new;
        for i in 0..n {
            yx[i] = px[i] + beta * (px[i] - qx[i]);
            yy[i] = py[i] + beta * (py[i] - qy[i]);
        }
    }
    // Exact slips of the answer.
    tangential_matvec(k, ows, px, py, ux, uy);
    matvecs += 1;
    let mut res: f64 = 0.0;
    for i in 0..n {
        ux[i] += input.cx[i];
        uy[i] += input.cy[i];
        res = res.max(natural_residual(
            [px[i], py[i]],
            [ux[i], uy[i]],
            dbar,
            bound(i),
        ));
    }
    let residual = if gmax > 0.0 { res / gmax } else { 0.0 };
    finish_states(input, px, py, ux, uy, d, sx, sy, state);
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

    #[test]
    fn local_problem_adhesion_and_slip() {
        let d = [2.0, 3.0];
        let (p, st, s) = local_coulomb([1.0, 1.5], d, 10.0, 10.0);
        assert_eq!(st, ElementState::Adhesion);
        assert!((p[0] + 0.5).abs() < 1e-15 && (p[1] + 0.5).abs() < 1e-15 && s == [0.0, 0.0]);
        let q = [10.0, -4.0];
        let (p, st, s) = local_coulomb(q, d, 1.0, 1.0);
        assert_eq!(st, ElementState::Slip);
        // |p| = g, s = q + d p, p antiparallel to s.
        assert!(((p[0] * p[0] + p[1] * p[1]).sqrt() - 1.0).abs() < 1e-13);
        let sv = [q[0] + d[0] * p[0], q[1] + d[1] * p[1]];
        assert!((sv[0] - s[0]).abs() < 1e-12 && (sv[1] - s[1]).abs() < 1e-12);
        let cross = p[0] * sv[1] - p[1] * sv[0];
        assert!(cross.abs() < 1e-12 && p[0] * sv[0] + p[1] * sv[1] < 0.0);
    }
}
