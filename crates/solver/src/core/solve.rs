//! The driver: normal and tangential solvers, their alternation for coupled
//! problems (Panagiotopoulos process, Kalker 1990 §5.3), transient stepping
//! and the evaluation of totals.

use std::sync::Arc;
use std::time::Instant;

use crate::core::cache::KernelCache;
use crate::core::cancel;
use crate::core::coupling::CouplingMonitor;
use crate::core::error::ContactError;
use crate::core::fft::{KernelSet, OperatorWorkspace};
use crate::core::frame::{direction, RollingFrame};
use crate::core::friclaw::{SlipStart, SlipVelocityLaw};
use crate::core::grid::Grid;
use crate::core::influence::{Component, KernelKind};
use crate::core::layer::{
    CoulombBound, InterfacialLayer, LayerFields, LayerState, MAX_LAYER_PASSES,
};
use crate::core::leading_edge;
use crate::core::memory::{heap_bytes, HeapBytes};
use crate::core::normal::{
    hertz_start, solve_normal_active_set, solve_normal_with, BlendedNormal, NormalBlend,
    NormalLoad, NormalOperator, NormalScratch, PlanarNormal,
};
use crate::core::predict::{PathPoint, WarmPath};
use crate::core::problem::{
    Carry, ContactProblem, Kinematics, ShiftStep, INTERFACIAL_LAYER_KEY, VISCOELASTIC_KEY,
};
use crate::core::solution::{
    ContactSolution, ElementFields, ElementState, IterationLimit, SolveInfo, SolveStatus, Totals,
};
use crate::core::steady::{
    solve_coulomb_newton, solve_steady_newton, LocalModel, PlanarTangential, SteadyScratch,
};
use crate::core::tangential::{
    carry_field, carry_field_nearest, shift_upstream, solve_steady_marching, solve_transient,
    FrictionBounds, MarchingScratch, TangentialInput, TangentialOutcome, TangentialOutput,
    TangentialScratch, TangentialSettings,
};
use crate::core::viscoelastic::Viscoelastic;

/// Iterations of the fallback (time marching in steady rolling, FISTA in
/// a transient step) between two Newton attempts of a tangential solve
/// that stalled: on Bentall's aluminium-on-steel rollers Newton converges
/// in 3 to 5 steps after 50 marching iterations, on a shifted line
/// contact after 50 of FISTA.
pub const MARCHING_RESTART: usize = 50;

/// A reusable solver for one grid and material pair. Keeps the tractions of
/// the last solve, which warm-start the next one (the service keeps one per
/// co-simulation session). Frictionless and steady-rolling solves of the
/// same geometry follow the path of their inputs: when the load and
/// creepages move along a line, the start is extrapolated from the last two
/// solutions (see `core::predict`); the result still meets the solve's own
/// tolerance. A clone is an independent solver in the same
/// state: solving the same inputs from it gives bit-identical results (the
/// service's session marks).
#[derive(Clone)]
pub struct ContactSolver {
    /// The grid in the rolling frame (the problem's when it rolls in +x).
    grid: Grid,
    /// The map from the problem's frame to the rolling frame the solver
    /// works in ([`crate::core::frame`]).
    frame: RollingFrame,
    displacement: Arc<KernelSet>,
    /// Buffers of the Newton Coulomb solver, allocated on first use.
    newton_scratch: Option<SteadyScratch>,
    ows: OperatorWorkspace,
    normal_scratch: NormalScratch,
    tangential_scratch: TangentialScratch,
    marching_scratch: MarchingScratch,
    pn: Vec<f64>,
    tr: Tractions,
    /// The kinetic set of the tangential solve under way: the elements
    /// marked [`ElementState::Slip`] are bounded by the kinetic coefficient
    /// (see [`ContactSolver::tangential_pass`]).
    kinetic: Vec<ElementState>,
    h_eff: Vec<f64>,
    cx: Vec<f64>,
    cy: Vec<f64>,
    tmp_x: Vec<f64>,
    tmp_y: Vec<f64>,
    old_ux: Vec<f64>,
    old_uy: Vec<f64>,
    last_pn: Vec<f64>,
    last_px: Vec<f64>,
    last_py: Vec<f64>,
    /// Transient steps solved since `new` or `reset` (0: the next step
    /// starts from the unloaded state).
    transient_steps: usize,
    /// Inputs and solution before last, for the warm start's prediction.
    path: WarmPath,
    /// A slip-velocity law's state: see [`LawState`].
    law: LawState,
    /// Factor on the friction coefficients of each grid row (empty: 1
    /// everywhere): [`ContactSolver::set_row_friction_scale`].
    row_scale: Vec<f64>,
    /// Sub-patches with reduced interaction in the normal problem, in the
    /// rolling frame, and their buffers:
    /// [`ContactSolver::set_normal_blend`].
    blend: Option<Box<BlendState>>,
    /// An elasto-plastic interfacial layer's history and buffers
    /// ([`crate::core::layer`]), allocated at the first solve with one.
    layer: Option<Box<LayerState>>,
}

/// A [`NormalBlend`] in the rolling frame and the buffers of its operator
/// ([`BlendedNormal`]).
#[derive(Clone)]
struct BlendState {
    blend: NormalBlend,
    part: Vec<f64>,
    product: Vec<f64>,
}

impl HeapBytes for BlendState {
    fn heap_bytes(&self) -> usize {
        heap_bytes!(self.blend, self.part, self.product)
    }
}

/// Buffers of a slip-velocity dependent friction law
/// ([`crate::core::friclaw`]), unused under Coulomb's law.
#[derive(Clone)]
struct LawState {
    /// Friction coefficient of each element [-] of the last solve.
    mu: Vec<f64>,
    /// The coefficient the material at each element had one transient step
    /// before [-] (0: none, fresh material, the static coefficient).
    mu_before: Vec<f64>,
    /// Slip velocity of each element \[m/s\]: the iterate, then the answer.
    velocity: Vec<f64>,
    /// The slip velocities of the last pass's solution \[m/s\].
    velocity_new: Vec<f64>,
    /// The bound mu p_n \[Pa\] handed to the Coulomb solvers as their
    /// pressure (with coefficient 1).
    bound: Vec<f64>,
    /// Whether a solve used a law (then a saved state holds `mu`,
    /// `mu_before` and `velocity`; under Coulomb's law it holds none).
    used: bool,
}

impl LawState {
    fn new(n: usize) -> Self {
        let z = || vec![0.0; n];
        Self {
            mu: z(),
            mu_before: z(),
            velocity: z(),
            velocity_new: z(),
            bound: z(),
            used: false,
        }
    }
}

/// What the solves of a [`ContactSolver`] read from the solves before
/// them: pressures, tractions, slips and element states, the transient
/// history and the path of inputs of the warm start's prediction. Not the
/// kernels or any buffer. Saving it before a solve and restoring it after
/// makes the solve leave no trace ([`ContactSolver::save_state`]); the
/// service keeps one per session mark.
#[derive(Clone, Default)]
pub struct SolverState {
    pn: Vec<f64>,
    px: Vec<f64>,
    py: Vec<f64>,
    sx: Vec<f64>,
    sy: Vec<f64>,
    state: Vec<ElementState>,
    transient_steps: usize,
    path: WarmPath,
    mu: Vec<f64>,
    mu_before: Vec<f64>,
    slip_velocity: Vec<f64>,
    /// An elasto-plastic layer's history (empty without one): hardening,
    /// plastic deformation (x, y), generalised slip, flow flags.
    layer: [Vec<f64>; 4],
    layer_flow: Vec<bool>,
    layer_used: bool,
}

impl SolverState {
    /// Memory held by its buffers \[bytes\].
    pub fn bytes(&self) -> usize {
        let f = |v: &Vec<f64>| std::mem::size_of_val(v.as_slice());
        let e = |v: &Vec<ElementState>| std::mem::size_of_val(v.as_slice());
        [
            &self.pn,
            &self.px,
            &self.py,
            &self.sx,
            &self.sy,
            &self.mu,
            &self.mu_before,
            &self.slip_velocity,
        ]
        .into_iter()
        .chain(&self.layer)
        .map(f)
        .sum::<usize>()
            + e(&self.state)
            + std::mem::size_of_val(self.layer_flow.as_slice())
            + self.path.bytes()
    }
}

impl HeapBytes for SolverState {
    fn heap_bytes(&self) -> usize {
        heap_bytes!(
            self.pn,
            self.px,
            self.py,
            self.sx,
            self.sy,
            self.state,
            self.path,
            self.mu,
            self.mu_before,
            self.slip_velocity,
            self.layer,
            self.layer_flow
        )
    }
}

/// The solver's own buffers: FFT workspaces, the normal, tangential,
/// marching and Newton scratch, fields, warm start and friction law; not
/// the kernels, which it shares with the [`KernelCache`] they came from.
/// On n elements: 331 bytes an element of fields and scratch, the FFT
/// workspaces of the padded grid (373 bytes an element on 256 x 256), and
/// once a frictional solve has run, the Newton scratch (969 bytes an
/// element) and the prediction's fields (24): 111 MB on 256 x 256 (the
/// test `a_solver_holds_its_buffers_and_not_its_kernels`).
impl HeapBytes for ContactSolver {
    fn heap_bytes(&self) -> usize {
        let (tr, law) = (&self.tr, &self.law);
        heap_bytes!(
            self.newton_scratch,
            self.ows,
            self.normal_scratch,
            self.tangential_scratch,
            self.marching_scratch,
            self.pn,
            tr.px,
            tr.py,
            tr.sx,
            tr.sy,
            tr.state,
            self.kinetic,
            self.h_eff,
            self.cx,
            self.cy,
            self.tmp_x,
            self.tmp_y,
            self.old_ux,
            self.old_uy,
            self.last_pn,
            self.last_px,
            self.last_py,
            self.path,
            law.mu,
            law.mu_before,
            law.velocity,
            law.velocity_new,
            law.bound,
            self.row_scale,
            self.blend,
            self.layer
        )
    }
}

/// A warm start's field `v`, named `key`, must hold one finite value per
/// element (`n`).
fn per_element(key: &str, v: &[f64], n: usize) -> Result<(), ContactError> {
    if v.len() != n || v.iter().any(|p| !p.is_finite()) {
        return Err(ContactError::invalid(
            key,
            format!("needs {n} finite values, one per element, got {}", v.len()),
        ));
    }
    Ok(())
}

impl ContactSolver {
    /// A solver for `problem`'s grid and materials, with kernels from `cache`.
    /// A rolling direction that is not finite builds the solver of +x;
    /// [`ContactSolver::solve`] then refuses the problem.
    pub fn new(problem: &ContactProblem, cache: &KernelCache) -> Self {
        let turns =
            direction(problem.rolling_direction_rad, problem.grid.is_line()).map_or(0, |d| d.turns);
        let frame = RollingFrame::new(turns, problem.grid);
        let grid = frame.rolling_grid();
        let displacement = displacement_kernels(problem, &grid, cache);
        let n = grid.len();
        let z = || vec![0.0; n];
        Self {
            grid,
            frame,
            ows: displacement.workspace(),
            displacement,
            newton_scratch: None,
            normal_scratch: NormalScratch::new(n),
            tangential_scratch: TangentialScratch::new(n),
            marching_scratch: MarchingScratch::new(n),
            pn: z(),
            tr: Tractions {
                px: z(),
                py: z(),
                sx: z(),
                sy: z(),
                state: vec![ElementState::Exterior; n],
            },
            kinetic: vec![ElementState::Exterior; n],
            h_eff: z(),
            cx: z(),
            cy: z(),
            tmp_x: z(),
            tmp_y: z(),
            old_ux: z(),
            old_uy: z(),
            last_pn: z(),
            last_px: z(),
            last_py: z(),
            transient_steps: 0,
            path: WarmPath::default(),
            law: LawState::new(n),
            row_scale: Vec::new(),
            blend: None,
            layer: None,
        }
    }

    /// Makes this solver the one [`ContactSolver::new`] builds for
    /// `problem`: in place, keeping its kernels and buffers, when it was
    /// built for a grid of the same shape and element sizes (anywhere),
    /// the same rolling direction and materials (the kernels `cache` gives
    /// for `problem` are its own); else a new solver. Everything the last
    /// solves left (pressures, tractions, states, history, warm start's
    /// path, row friction scale) is forgotten: the next solves give the
    /// same bits as on a new solver, without its allocations and first
    /// touches of memory. A wheel/rail session renews each wheel's solver
    /// from one time step to the next.
    pub fn renew(&mut self, problem: &ContactProblem, cache: &KernelCache) {
        let turns =
            direction(problem.rolling_direction_rad, problem.grid.is_line()).map_or(0, |d| d.turns);
        let frame = RollingFrame::new(turns, problem.grid);
        let grid = frame.rolling_grid();
        let same_shape = (grid.nx, grid.ny, grid.dx_m, grid.dy_m)
            == (self.grid.nx, self.grid.ny, self.grid.dx_m, self.grid.dy_m);
        let displacement = displacement_kernels(problem, &grid, cache);
        if !(same_shape && Arc::ptr_eq(&displacement, &self.displacement)) {
            *self = Self::new(problem, cache);
            return;
        }
        self.grid = grid;
        self.frame = frame;
        for v in [
            &mut self.pn,
            &mut self.tr.px,
            &mut self.tr.py,
            &mut self.tr.sx,
            &mut self.tr.sy,
            &mut self.h_eff,
            &mut self.cx,
            &mut self.cy,
            &mut self.tmp_x,
            &mut self.tmp_y,
            &mut self.old_ux,
            &mut self.old_uy,
            &mut self.last_pn,
            &mut self.last_px,
            &mut self.last_py,
        ] {
            v.fill(0.0);
        }
        self.tr.state.fill(ElementState::Exterior);
        self.kinetic.fill(ElementState::Exterior);
        self.transient_steps = 0;
        self.path.clear();
        let law = &mut self.law;
        for v in [
            &mut law.mu,
            &mut law.mu_before,
            &mut law.velocity,
            &mut law.velocity_new,
            &mut law.bound,
        ] {
            v.fill(0.0);
        }
        law.used = false;
        self.row_scale.clear();
        self.blend = None;
        if let Some(l) = &mut self.layer {
            l.clear();
        }
    }

    /// Friction varying across the rolling direction, one grid row at a
    /// time (CONTACT's friction per grid row, user guide §"Friction
    /// description", variable friction `VARFRC`): the friction
    /// coefficients of every element of grid row `iy` (lateral position
    /// `grid.y_m(iy)`) are the problem's coefficients times `scale[iy]`,
    /// its static and kinetic ones under Coulomb's law, mu(s_a) under a
    /// slip-velocity law. `scale` has one finite factor > 0 per grid row, or
    /// is empty for the problem's coefficients everywhere (the default).
    /// Kept for every later solve of this solver; needs rolling along the
    /// rows (`rolling_direction_rad` 0 or pi: turned by pi, row `iy` is the
    /// rolling grid's row `ny - 1 - iy`).
    pub fn set_row_friction_scale(&mut self, scale: &[f64]) -> Result<(), ContactError> {
        const KEY: &str = "row_friction_scale";
        if scale.is_empty() {
            self.row_scale.clear();
            return Ok(());
        }
        if !matches!(self.frame.turns(), 0 | 2) {
            return Err(ContactError::invalid(
                KEY,
                "friction per grid row needs rolling_direction_rad = 0 or pi (rolling along \
                 the rows)",
            ));
        }
        if scale.len() != self.grid.ny || scale.iter().any(|f| !(f.is_finite() && *f > 0.0)) {
            return Err(ContactError::invalid(
                KEY,
                format!(
                    "needs {} finite factors > 0, one per grid row, got {} values",
                    self.grid.ny,
                    scale.len()
                ),
            ));
        }
        self.row_scale.clear();
        if self.frame.turns() == 2 {
            self.row_scale.extend(scale.iter().rev());
        } else {
            self.row_scale.extend_from_slice(scale);
        }
        Ok(())
    }

    /// The factor on the friction coefficients of element `i` (1 without a
    /// row scale).
    #[inline]
    fn row_factor(&self, i: usize) -> f64 {
        if self.row_scale.is_empty() {
            1.0
        } else {
            self.row_scale[i / self.grid.nx]
        }
    }

    /// Sub-patches of the grid whose pressures act on each other reduced
    /// in the normal problem ([`NormalBlend`], CONTACT's blended patch),
    /// its labels in the problem's frame; None for none (the default).
    /// Kept for every later solve of this solver; the tangential problem
    /// and the displacements reported see the full interaction (as in
    /// CONTACT, whose blending is in its normal solver alone). The caller
    /// keeps the elements of label 0 out of contact (a large undeformed
    /// distance).
    pub fn set_normal_blend(&mut self, blend: Option<&NormalBlend>) -> Result<(), ContactError> {
        let Some(b) = blend else {
            self.blend = None;
            return Ok(());
        };
        let n = self.pn.len();
        if b.labels().len() != n {
            return Err(ContactError::invalid(
                "normal_blend",
                format!(
                    "needs {n} labels, one per element, got {}",
                    b.labels().len()
                ),
            ));
        }
        let mut labels = vec![0; n];
        self.frame.field_to_rolling(b.labels(), &mut labels);
        self.blend = Some(Box::new(BlendState {
            blend: b.with_labels(labels)?,
            part: vec![0.0; n],
            product: vec![0.0; n],
        }));
        Ok(())
    }

    /// Whether the normal problem has sub-patches
    /// ([`ContactSolver::set_normal_blend`]).
    pub fn has_normal_blend(&self) -> bool {
        self.blend.is_some()
    }

    /// The planar normal operator of this solver's kernels and buffers: for
    /// a caller that solves this grid's normal problem together with
    /// others ([`crate::core::normal::BlockNormal`]).
    pub fn normal_operator(&mut self) -> PlanarNormal<'_> {
        PlanarNormal {
            kernels: &self.displacement,
            ows: &mut self.ows,
        }
    }

    /// Makes `pn` \[Pa\] the pressures the next solve starts from (the
    /// tractions are kept): for a caller that solved this grid's normal
    /// problem by other means, as the wheel/rail load iteration does for
    /// several patches at once. `pn` must have one value per element.
    pub fn set_pressure_warm_start(&mut self, pn: &[f64]) -> Result<(), ContactError> {
        per_element("pressure_pa", pn, self.pn.len())?;
        self.frame.field_to_rolling(pn, &mut self.pn);
        self.path.clear();
        Ok(())
    }

    /// Starts a cold steady-rolling solve of `problem` on a large grid from
    /// the solution of the same problem on the grid of twice the element
    /// size (each element a 2 x 2 block of this grid's, its undeformed
    /// distance their mean; started the same way while that grid is still
    /// large), its tangential tractions interpolated bilinearly onto this
    /// grid. The semismooth Newton method's active set settles in fewer
    /// steps from there: on CONTACT's performance wheel (`benches/perfc.rs`)
    /// 28 Newton steps at 575 x 647 become 12 and the solve, the coarse
    /// ones included, takes 30 % less (8 % at 287 x 323). The result meets
    /// the same tolerances as a cold solve.
    ///
    /// Does nothing and returns false unless the problem rolls steadily in
    /// +x with Coulomb friction, no extra rigid slip and no per-row
    /// friction, the grid has at least [`NESTED_START_ELEMENTS`] elements
    /// and 8 per direction, and this solver is cold (no tractions, no path
    /// of earlier solves): call it before the first solve. A coarse solve
    /// that fails leaves the solver cold; a cancelled one returns the
    /// error.
    pub fn start_nested(
        &mut self,
        problem: &ContactProblem,
        cache: &KernelCache,
    ) -> Result<bool, ContactError> {
        self.start_nested_from(problem, cache, NESTED_START_ELEMENTS)
    }

    fn start_nested_from(
        &mut self,
        problem: &ContactProblem,
        cache: &KernelCache,
        min_elements: usize,
    ) -> Result<bool, ContactError> {
        let g = problem.grid;
        let plain = matches!(problem.kinematics, Kinematics::SteadyRolling(_))
            && problem.extra_rigid_slip.is_none()
            && problem.friction.slip_velocity_law.is_none()
            && plastic_layer(problem).is_none()
            && self.row_scale.is_empty()
            && self.frame.is_identity()
            && g == self.grid;
        let cold = self.path.is_empty() && self.tr.px.iter().chain(&self.tr.py).all(|&t| t == 0.0);
        if !(plain && cold && g.len() >= min_elements && g.nx >= 8 && g.ny >= 8) {
            return Ok(false);
        }
        let coarse_grid = Grid::new(
            g.nx.div_ceil(2),
            g.ny.div_ceil(2),
            2.0 * g.dx_m,
            2.0 * g.dy_m,
            g.x0_m,
            g.y0_m,
        )?;
        let mut coarse_gap = vec![0.0; coarse_grid.len()];
        for (iy, row) in coarse_gap.chunks_mut(coarse_grid.nx).enumerate() {
            for (ix, h) in row.iter_mut().enumerate() {
                let fine = (2 * iy..(2 * iy + 2).min(g.ny))
                    .flat_map(|y| (2 * ix..(2 * ix + 2).min(g.nx)).map(move |x| (x, y)));
                let (sum, count) = fine.fold((0.0, 0.0), |(s, c), (x, y)| {
                    (s + problem.gap_m[g.index(x, y)], c + 1.0)
                });
                *h = sum / count;
            }
        }
        let coarse = ContactProblem {
            grid: coarse_grid,
            gap_m: coarse_gap,
            ..problem.clone()
        };
        let mut solver = ContactSolver::new(&coarse, cache);
        let solved = solver
            .start_nested_from(&coarse, cache, min_elements)
            .and_then(|_| solver.solve(&coarse));
        let fields = match solved {
            Ok(mut s) => match s.pop() {
                Some(s) => s.fields,
                None => return Ok(false),
            },
            Err(ContactError::Cancelled) => return Err(ContactError::Cancelled),
            Err(_) => return Ok(false),
        };
        interpolate(&coarse_grid, &fields.traction_x_pa, &g, &mut self.tr.px);
        interpolate(&coarse_grid, &fields.traction_y_pa, &g, &mut self.tr.py);
        Ok(true)
    }

    /// Makes (`px`, `py`) \[Pa\] the tangential tractions the next
    /// frictional solve starts from (the pressures are kept): for a caller
    /// that carries them over from a solve on another solver of the same
    /// grid, as a wheel/rail session does from one time step to the next.
    /// One finite value per element each. A frictionless solve in between
    /// clears them.
    pub fn set_traction_warm_start(&mut self, px: &[f64], py: &[f64]) -> Result<(), ContactError> {
        per_element("traction_x_pa", px, self.tr.px.len())?;
        per_element("traction_y_pa", py, self.tr.py.len())?;
        if self.frame.is_identity() {
            self.tr.px.copy_from_slice(px);
            self.tr.py.copy_from_slice(py);
        } else {
            [self.tr.px, self.tr.py] = self.frame.vectors_to_rolling(px, py);
        }
        self.path.clear();
        Ok(())
    }

    /// Makes `v` \[m/s\] the slip velocities a slip-velocity law's next
    /// solve starts its iteration from when the law starts from the
    /// previous solve ([`crate::core::friclaw::SlipStart::Previous`]): for
    /// a caller that carries them over from a solve on another solver of
    /// the same grid, as a wheel/rail session does from one time step to
    /// the next. One finite value >= 0 per element.
    pub fn set_slip_velocity_warm_start(&mut self, v: &[f64]) -> Result<(), ContactError> {
        per_element("slip_velocity_m_per_s", v, self.law.velocity.len())?;
        if let Some(i) = v.iter().position(|&s| s < 0.0) {
            return Err(ContactError::invalid(
                format!("slip_velocity_m_per_s[{i}]"),
                "must be >= 0",
            ));
        }
        self.frame.field_to_rolling(v, &mut self.law.velocity);
        Ok(())
    }

    /// Copies the state later solves read into `to` (reusing its buffers:
    /// no allocation once they have this solver's size).
    pub fn save_state(&self, to: &mut SolverState) {
        to.pn.clone_from(&self.pn);
        to.px.clone_from(&self.tr.px);
        to.py.clone_from(&self.tr.py);
        to.sx.clone_from(&self.tr.sx);
        to.sy.clone_from(&self.tr.sy);
        to.state.clone_from(&self.tr.state);
        to.transient_steps = self.transient_steps;
        to.path.copy_from(&self.path);
        for (to, from) in [
            (&mut to.mu, &self.law.mu),
            (&mut to.mu_before, &self.law.mu_before),
            (&mut to.slip_velocity, &self.law.velocity),
        ] {
            if self.law.used {
                to.clone_from(from);
            } else {
                to.clear();
            }
        }
        match &self.layer {
            Some(l) => {
                for (to, from) in
                    to.layer
                        .iter_mut()
                        .zip([&l.hardening, &l.plastic_x, &l.plastic_y, &l.slid])
                {
                    to.clone_from(from);
                }
                to.layer_flow.clone_from(&l.flow);
                to.layer_used = l.used;
            }
            None => {
                to.layer.iter_mut().for_each(Vec::clear);
                to.layer_flow.clear();
                to.layer_used = false;
            }
        }
    }

    /// Puts back a state saved from this solver (or one of the same grid):
    /// the next solve gives the same bits as it would have given right
    /// after the save. A state of another size is refused.
    pub fn restore_state(&mut self, from: &SolverState) -> Result<(), ContactError> {
        per_element("pressure_pa", &from.pn, self.pn.len())?;
        self.pn.copy_from_slice(&from.pn);
        self.tr.px.copy_from_slice(&from.px);
        self.tr.py.copy_from_slice(&from.py);
        self.tr.sx.copy_from_slice(&from.sx);
        self.tr.sy.copy_from_slice(&from.sy);
        self.tr.state.copy_from_slice(&from.state);
        self.transient_steps = from.transient_steps;
        self.path.copy_from(&from.path);
        for (to, from) in [
            (&mut self.law.mu, &from.mu),
            (&mut self.law.mu_before, &from.mu_before),
            (&mut self.law.velocity, &from.slip_velocity),
        ] {
            // A state saved before any solve holds empty fields.
            if from.len() == to.len() {
                to.copy_from_slice(from);
            } else {
                to.fill(0.0);
            }
        }
        let n = self.pn.len();
        if from.layer_flow.len() == n {
            let l = self
                .layer
                .get_or_insert_with(|| Box::new(LayerState::new(n)));
            for (to, from) in [
                &mut l.hardening,
                &mut l.plastic_x,
                &mut l.plastic_y,
                &mut l.slid,
            ]
            .into_iter()
            .zip(&from.layer)
            {
                to.copy_from_slice(from);
            }
            l.flow.copy_from_slice(&from.layer_flow);
            l.used = from.layer_used;
        } else if let Some(l) = &mut self.layer {
            l.clear();
        }
        Ok(())
    }

    /// The friction coefficient of each element [-] in the last solve
    /// under a slip-velocity dependent law (its memory included), in the
    /// problem's element order (index `iy * nx + ix`); None under
    /// Coulomb's law (the coefficients are the problem's).
    pub fn friction_coefficients(&self) -> Option<Vec<f64>> {
        if !self.law.used {
            return None;
        }
        let mut mu = vec![0.0; self.law.mu.len()];
        self.frame.field_to_user(&self.law.mu, &mut mu);
        Some(mu)
    }

    /// The size of [`ContactSolver::save_state`]'s copy \[bytes\].
    pub fn state_bytes(&self) -> usize {
        let n = self.grid.len();
        // pn, px, py, sx, sy (and a law's mu, mu_before and slip velocity);
        // the element states; the path's three fields.
        let fields = if self.law.used { 8 } else { 5 };
        // An elasto-plastic layer's four fields and flags.
        let layer = if self.layer.is_some() {
            4 * 8 + std::mem::size_of::<bool>()
        } else {
            0
        };
        n * (fields * 8 + std::mem::size_of::<ElementState>() + layer) + self.path.bytes()
    }

    /// Frees the buffers that solves allocate on first use and that hold
    /// no state (the Newton scratch, the prediction's fields before a
    /// second solve): the next solve gives the same bits and allocates
    /// them again. For a caller that budgets memory and puts back the
    /// state of a solve it refuses ([`ContactSolver::restore_state`]).
    pub fn release_scratch(&mut self) {
        self.newton_scratch = None;
        self.path.release();
    }

    /// Makes the solution of the last solve the history the next transient
    /// step ([`ContactSolver::solve_next_step`]) continues from, as if it
    /// had been a transient step: a steady rolling solution is the state
    /// of material that has rolled long enough, so transient rolling steps
    /// continue the steady state in moving coordinates (Kalker 1990, §5.4;
    /// CONTACT's sequences of a steady case followed by transient ones).
    pub fn continue_from_last_solution(&mut self) {
        self.transient_steps = self.transient_steps.max(1);
        self.law.mu_before.copy_from_slice(&self.law.mu);
    }

    /// Forgets the warm start.
    pub fn reset(&mut self) {
        for v in [&mut self.pn, &mut self.tr.px, &mut self.tr.py] {
            v.fill(0.0);
        }
        self.tr.state.fill(ElementState::Exterior);
        self.transient_steps = 0;
        self.path.clear();
        for v in [&mut self.law.mu_before, &mut self.law.velocity] {
            v.fill(0.0);
        }
        if let Some(l) = &mut self.layer {
            l.clear();
        }
    }

    /// Solves `problem` (which must have this solver's grid and materials):
    /// one solution, or one per step of a transient problem.
    pub fn solve(
        &mut self,
        problem: &ContactProblem,
    ) -> Result<Vec<ContactSolution>, ContactError> {
        problem.validate()?;
        self.check_frame(problem)?;
        if self.frame.is_identity() {
            return self.solve_rolling(problem);
        }
        let turned = self.frame.problem(problem);
        let solutions = self
            .solve_rolling(&turned)
            .map_err(|e| self.frame.error(e))?;
        Ok(solutions
            .into_iter()
            .map(|s| self.frame.solution(s, &problem.gap_m))
            .collect())
    }

    /// Refuses a problem of another grid or rolling direction than the
    /// solver's (validated before).
    fn check_frame(&self, problem: &ContactProblem) -> Result<(), ContactError> {
        if problem.grid != self.frame.user_grid() {
            return Err(ContactError::invalid(
                "grid",
                "differs from the grid this solver was built for",
            ));
        }
        if direction(problem.rolling_direction_rad, problem.grid.is_line())?.turns
            != self.frame.turns()
        {
            return Err(ContactError::invalid(
                crate::core::frame::ROLLING_DIRECTION_KEY,
                "differs from the rolling direction this solver was built for",
            ));
        }
        let built = self.displacement.influence.layer_flexibility_m_per_pa();
        if layer_flexibility(problem) != built {
            return Err(ContactError::invalid(
                INTERFACIAL_LAYER_KEY,
                format!(
                    "has the flexibility thickness / shear modulus = {:e} m/Pa; this solver was \
                     built for {:e} m/Pa (its kernels include it): build a solver for the problem",
                    layer_flexibility(problem),
                    built
                ),
            ));
        }
        let relaxation = |v: Option<Viscoelastic>| {
            v.filter(|v| !(v.body1.is_elastic() && v.body2.is_elastic()))
                .map(|v| v.relaxation())
        };
        if relaxation(problem.settings.viscoelastic)
            != relaxation(self.displacement.influence.viscoelastic())
        {
            return Err(ContactError::invalid(
                VISCOELASTIC_KEY,
                "differs from the viscoelastic bodies (relaxation ratios and lengths) this solver \
                 was built for (its kernels include them): build a solver for the problem",
            ));
        }
        Ok(())
    }

    /// [`ContactSolver::solve`] of a validated problem of the rolling frame.
    fn solve_rolling(
        &mut self,
        problem: &ContactProblem,
    ) -> Result<Vec<ContactSolution>, ContactError> {
        let t0 = Instant::now();
        match &problem.kinematics {
            Kinematics::Frictionless | Kinematics::SteadyRolling(_) => {
                let point = PathPoint::of(problem);
                self.path
                    .predict(&point, [&mut self.pn, &mut self.tr.px, &mut self.tr.py]);
                let solved = self.solve_one(problem, problem.load, None, 0.0, Carry::Whole(0));
                match &solved {
                    Ok(_) => self.path.push(point),
                    Err(_) => self.path.clear(),
                }
                let mut sol = solved?;
                sol.info.solve_time_s = t0.elapsed().as_secs_f64();
                Ok(vec![sol])
            }
            Kinematics::Transient(steps) => {
                self.reset();
                let mut out = Vec::with_capacity(steps.len());
                for step in steps {
                    let ts = Instant::now();
                    let mut sol = self.transient_step(problem, step)?;
                    // The first step carries the set-up time.
                    let since = if out.is_empty() { t0 } else { ts };
                    sol.info.solve_time_s = since.elapsed().as_secs_f64();
                    out.push(sol);
                }
                Ok(out)
            }
        }
    }

    /// Solves one more step of a transient problem, continuing from the
    /// tractions of the step this solver solved last (from the unloaded
    /// state after [`ContactSolver::new`] or [`ContactSolver::reset`]).
    /// `problem` supplies everything but the step and must be transient
    /// (its own steps are not solved). Its undeformed distance `gap_m` may
    /// change from one step to the next: world-fixed shift steps in which
    /// the geometry moves with the bodies over the grid (the tractions stay
    /// where they are, unlike a rolling step's). This is how a co-simulation session
    /// advances one time step at a time; [`ContactSolver::solve`] of a
    /// transient problem is `reset` followed by one call per step.
    ///
    /// A step the solver rejects after it started (the patch reaches the
    /// grid border) leaves the history changed: restore a state saved
    /// before the step ([`ContactSolver::save_state`]) to retry.
    pub fn solve_next_step(
        &mut self,
        problem: &ContactProblem,
        step: &ShiftStep,
    ) -> Result<ContactSolution, ContactError> {
        let t0 = Instant::now();
        problem.validate()?;
        step.validate("step")?;
        self.check_frame(problem)?;
        if !matches!(problem.kinematics, Kinematics::Transient(_)) {
            return Err(ContactError::invalid(
                "kinematics",
                "solve_next_step needs a transient problem",
            ));
        }
        if let Some(extra) = &problem.extra_rigid_slip {
            // A rolling step takes the extra slip, a shift step the shift.
            extra.check_step(step, "step")?;
        }
        self.path.clear();
        let mut sol = if self.frame.is_identity() {
            self.transient_step(problem, step)?
        } else {
            let turned = self.frame.problem(problem);
            let s = self
                .transient_step(&turned, &self.frame.step(step))
                .map_err(|e| self.frame.error(e))?;
            self.frame.solution(s, &problem.gap_m)
        };
        sol.info.solve_time_s = t0.elapsed().as_secs_f64();
        Ok(sol)
    }

    /// One transient step from the current history (Kalker 1990 §5.2: the
    /// slip is the rigid shift plus the change of the displacement
    /// difference since the previous step; a rolling step first carries
    /// the previous tractions upstream by the distance rolled,
    /// see [`crate::core::problem`]).
    fn transient_step(
        &mut self,
        problem: &ContactProblem,
        step: &ShiftStep,
    ) -> Result<ContactSolution, ContactError> {
        let first = self.transient_steps == 0;
        let oblique = direction(problem.rolling_direction_rad, self.grid.is_line())?.oblique_rad;
        let carry = step.carry(&self.grid, oblique, "step")?;
        let grid = self.grid;
        // The previous pressures where the material now at each element
        // was (`h_eff` is free until the normal solve).
        let previous_pn: &[f64] = if carry != Carry::Whole(0) {
            carry_field(&grid, carry, &self.tr.px, &mut self.tmp_x);
            carry_field(&grid, carry, &self.tr.py, &mut self.tmp_y);
            std::mem::swap(&mut self.tr.px, &mut self.tmp_x);
            std::mem::swap(&mut self.tr.py, &mut self.tmp_y);
            carry_field(&grid, carry, &self.pn, &mut self.h_eff);
            if problem.friction.slip_velocity_law.is_some() {
                // A law's memory does not interpolate (0 is fresh material).
                let law = &mut self.law;
                carry_field_nearest(&grid, carry, &law.mu_before, &mut law.velocity_new);
                std::mem::swap(&mut law.mu_before, &mut law.velocity_new);
                carry_field_nearest(&grid, carry, &law.velocity, &mut law.velocity_new);
                std::mem::swap(&mut law.velocity, &mut law.velocity_new);
            }
            &self.h_eff
        } else {
            &self.pn
        };
        if plastic_layer(problem).is_some() {
            // The layer's history: the material's yield limit and plastic
            // deformation before the step, carried with it.
            let n = grid.len();
            let l = self
                .layer
                .get_or_insert_with(|| Box::new(LayerState::new(n)));
            if first {
                l.clear();
            }
            l.begin_step(&grid, carry);
        }
        // Displacement difference of the previous state.
        if first {
            self.old_ux.fill(0.0);
            self.old_uy.fill(0.0);
        } else {
            // The normal pressure displaces tangentially only when K != 0.
            let inputs: &[(Component, &[f64])] = &[
                (Component::X, &self.tr.px),
                (Component::Y, &self.tr.py),
                (Component::N, previous_pn),
            ];
            let used = if problem.material.is_coupled() { 3 } else { 2 };
            self.displacement.apply(
                &mut self.ows,
                &inputs[..used],
                &mut [
                    (Component::X, &mut self.old_ux),
                    (Component::Y, &mut self.old_uy),
                ],
            );
        }
        let mut sol = self.solve_one(
            problem,
            step.load,
            Some((step.shift_x_m, step.shift_y_m, step.rotation_rad)),
            step.rolling_m,
            carry,
        )?;
        sol.info.matvecs += usize::from(!first);
        self.transient_steps += 1;
        if problem.friction.slip_velocity_law.is_some() {
            self.law.mu_before.copy_from_slice(&self.law.mu);
        }
        Ok(sol)
    }

    /// One solve: steady (`shift` None) or a transient step of the rigid
    /// `shift` (x, y, rotation) that rolls `rolling_m` \[m\], carrying the
    /// previous tractions by `carry` (the leading-edge correction of
    /// [`leading_edge::fixed_slip`] with more than one element).
    fn solve_one(
        &mut self,
        problem: &ContactProblem,
        load: NormalLoad,
        shift: Option<(f64, f64, f64)>,
        rolling_m: f64,
        carry: Carry,
    ) -> Result<ContactSolution, ContactError> {
        let grid = self.grid;
        let n = grid.len();
        let area = grid.element_area_m2();
        // Viscoelastic bodies that relax differently couple through their
        // shares even when elastically alike.
        let coupled = self.displacement.influence.coupled();
        let frictional = !matches!(problem.kinematics, Kinematics::Frictionless);
        if let NormalLoad::Approach(d) = load {
            if problem.gap_m.iter().all(|&h| h >= d) {
                return Err(ContactError::NoContact {
                    detail: format!(
                        "the approach {d:e} m is smaller than the smallest undeformed distance {:e} m",
                        problem.gap_m.iter().cloned().fold(f64::INFINITY, f64::min)
                    ),
                });
            }
        }
        if !frictional {
            self.tr.px.fill(0.0);
            self.tr.py.fill(0.0);
        }
        let s = &problem.settings;
        let ctol = if s.coupling_tolerance > 0.0 {
            s.coupling_tolerance
        } else {
            1e-8
        };
        let cmax = if s.coupling_max_iterations > 0 {
            s.coupling_max_iterations
        } else {
            30
        };
        let mut info = SolveInfo {
            status: SolveStatus::Converged,
            limit: None,
            normal_iterations: 0,
            tangential_iterations: 0,
            coupling_iterations: 0,
            matvecs: 0,
            normal_residual: 0.0,
            tangential_residual: 0.0,
            solve_time_s: 0.0,
            normal_time_s: 0.0,
        };
        let mut approach = 0.0;
        let mut normal_ok = true;
        let mut tangential_ok = true;
        let law = problem.friction.slip_velocity_law;
        // A slip-velocity law hands its bounds mu p_n to the solvers as
        // their pressure, with coefficient 1.
        let friction = match law {
            Some(_) => FrictionBounds {
                static_coefficient: 1.0,
                kinetic_coefficient: 1.0,
            },
            None => FrictionBounds {
                static_coefficient: problem.friction.static_coefficient,
                kinetic_coefficient: problem.friction.kinetic_coefficient,
            },
        };
        let mut law_ok = true;
        // An elasto-plastic layer (friction then has one coefficient).
        let plastic = plastic_layer(problem).filter(|_| frictional);
        match (&plastic, &mut self.layer) {
            (Some(_), l) => {
                l.get_or_insert_with(|| Box::new(LayerState::new(n)));
            }
            (None, Some(l)) => l.used = false,
            (None, None) => {}
        }
        let mut monitor = CouplingMonitor::default();
        self.normal_scratch.begin_solve();
        for c in 0..cmax {
            cancel::check()?;
            info.coupling_iterations = c + 1;
            self.last_pn.copy_from_slice(&self.pn);
            self.last_px.copy_from_slice(&self.tr.px);
            self.last_py.copy_from_slice(&self.tr.py);
            // Normal problem with the normal displacement of the tangential tractions.
            self.h_eff.copy_from_slice(&problem.gap_m);
            if coupled && frictional {
                self.displacement.apply(
                    &mut self.ows,
                    &[(Component::X, &self.tr.px), (Component::Y, &self.tr.py)],
                    &mut [(Component::N, &mut self.tmp_x)],
                );
                info.matvecs += 1;
                for i in 0..n {
                    self.h_eff[i] += self.tmp_x[i];
                }
            }
            let tn = Instant::now();
            let mut planar = PlanarNormal {
                kernels: &self.displacement,
                ows: &mut self.ows,
            };
            let mut blended;
            let op: &mut dyn NormalOperator = match self.blend.as_deref_mut() {
                Some(BlendState {
                    blend,
                    part,
                    product,
                }) => {
                    blended = BlendedNormal {
                        planar,
                        blend,
                        part,
                        product,
                    };
                    &mut blended
                }
                None => &mut planar,
            };
            let (h, pn, scratch) = (&self.h_eff, &mut self.pn, &mut self.normal_scratch);
            let ic = &self.displacement.influence;
            if matches!(load, NormalLoad::NormalForce(_)) && pn.iter().all(|&p| p == 0.0) {
                // A cold start under force control: Hertz's pressure where
                // the gap is Hertzian (see `hertz_start` for approach
                // control).
                let e_star = ic.shear_modulus_pa() / (1.0 - ic.poisson_ratio());
                hertz_start(&grid, h, load, e_star, pn);
            }
            let no = if self.displacement.influence.is_viscoelastic() {
                // Not symmetric: the active-set method.
                solve_normal_active_set(op, h, area, load, pn, scratch, &s.normal)
            } else {
                solve_normal_with(op, h, None, area, load, pn, scratch, &s.normal)
            };
            info.normal_time_s += tn.elapsed().as_secs_f64();
            info.normal_iterations += no.iterations;
            info.matvecs += no.matvecs;
            info.normal_residual = no.residual;
            normal_ok = no.converged;
            approach = no.approach_m;
            if !frictional {
                break;
            }
            // Fixed part of the slip.
            let steady = match (&problem.kinematics, shift) {
                (Kinematics::SteadyRolling(cr), _) => {
                    rigid_slip(
                        &grid,
                        [cr.creepage_long, cr.creepage_lat],
                        cr.spin_per_m,
                        &mut self.cx,
                        &mut self.cy,
                    );
                    if let Some(e) = &problem.extra_rigid_slip {
                        add_scaled(1.0, [&e.slip_x, &e.slip_y], [&mut self.cx, &mut self.cy]);
                    }
                    if coupled {
                        // Steady-rolling slip of the normal pressure,
                        // (A_tn p_n - A_tn S p_n)/dx with S the shift by one
                        // element upstream (exact: the patch does not touch
                        // the grid border).
                        let dx = grid.dx_m;
                        shift_upstream(&grid, 1, &self.pn, &mut self.h_eff);
                        for (p, f) in [(&self.pn, 1.0 / dx), (&self.h_eff, -1.0 / dx)] {
                            add_tangential_of_normal(
                                &self.displacement,
                                &mut self.ows,
                                p,
                                f,
                                [&mut self.tmp_x, &mut self.tmp_y],
                                [&mut self.cx, &mut self.cy],
                            );
                        }
                        info.matvecs += 2;
                    }
                    true
                }
                (Kinematics::Transient(_), Some((shx, shy, rot))) => {
                    rigid_slip(&grid, [shx, shy], rot, &mut self.cx, &mut self.cy);
                    if let Some(e) = &problem.extra_rigid_slip {
                        let (factor, [x, y]) = if rolling_m > 0.0 {
                            (rolling_m, [&e.slip_x, &e.slip_y])
                        } else {
                            (1.0, [&e.shift_x_m, &e.shift_y_m])
                        };
                        add_scaled(factor, [x, y], [&mut self.cx, &mut self.cy]);
                    }
                    leading_edge::fixed_slip(
                        &grid,
                        carry,
                        &self.pn,
                        [&self.old_ux, &self.old_uy],
                        [&mut self.cx, &mut self.cy],
                    );
                    if coupled {
                        add_tangential_of_normal(
                            &self.displacement,
                            &mut self.ows,
                            &self.pn,
                            1.0,
                            [&mut self.tmp_x, &mut self.tmp_y],
                            [&mut self.cx, &mut self.cy],
                        );
                        info.matvecs += 1;
                    }
                    false
                }
                _ => {
                    return Err(ContactError::invalid(
                        "kinematics",
                        "internal: inconsistent kinematics",
                    ))
                }
            };
            let outcome = match &law {
                None if plastic.is_some() => self.plastic_layer_passes(
                    plastic.as_ref().expect("matched"),
                    problem.friction.static_coefficient,
                    &s.tangential,
                    steady,
                ),
                None if !self.row_scale.is_empty() => {
                    // The row factors go into the bounds handed over as
                    // pressures, with the problem's coefficients.
                    for i in 0..n {
                        self.law.bound[i] = self.pn[i] * self.row_factor(i);
                    }
                    self.tangential_pass(&s.tangential, friction, steady, true)
                }
                None => self.tangential_pass(&s.tangential, friction, steady, false),
                Some(law) => {
                    let (o, ok) = self.falling_friction(law, &s.tangential, steady, rolling_m, c);
                    law_ok = ok;
                    o
                }
            };
            info.tangential_iterations += outcome.iterations;
            info.matvecs += outcome.matvecs;
            info.tangential_residual = outcome.residual;
            tangential_ok = outcome.converged;
            if !coupled {
                break;
            }
            monitor.record(
                [&self.pn, &self.tr.px, &self.tr.py],
                [&self.last_pn, &self.last_px, &self.last_py],
            );
            if monitor.converged(ctol) {
                break;
            }
            if c + 1 == cmax {
                info.status = SolveStatus::MaxIterations;
                info.limit = Some(IterationLimit::Coupling);
            }
        }
        // The loops above stop early once cancelled: no answer then.
        cancel::check()?;
        // The layer's plastic flow out of the generalised slips, and its
        // work: per element rolled in steady rolling, per unit rolled
        // distance in the totals.
        let plastic_work = match &plastic {
            Some(layer) => {
                let steady = matches!(problem.kinematics, Kinematics::SteadyRolling(_));
                let coulomb = CoulombBound {
                    pn: &self.pn,
                    mu: problem.friction.static_coefficient,
                    row_scale: &self.row_scale,
                    nx: grid.nx,
                };
                let l = self.layer.as_mut().expect("allocated above");
                let work = l.finish(
                    layer,
                    &grid,
                    steady,
                    coulomb,
                    [&self.tr.px, &self.tr.py],
                    [&mut self.tr.sx, &mut self.tr.sy],
                    &mut self.tr.state,
                );
                area * if steady { work / grid.dx_m } else { work }
            }
            None => 0.0,
        };
        if !(normal_ok && tangential_ok && law_ok) {
            info.status = SolveStatus::MaxIterations;
            if info.limit.is_none() {
                info.limit = Some(if !normal_ok {
                    IterationLimit::Normal
                } else if !tangential_ok {
                    IterationLimit::Tangential
                } else {
                    IterationLimit::FrictionLaw
                });
            }
        }
        if !frictional {
            self.tr
                .state
                .iter_mut()
                .zip(self.pn.iter())
                .for_each(|(s, &p)| {
                    *s = if p > 0.0 {
                        ElementState::Slip
                    } else {
                        ElementState::Exterior
                    }
                });
            self.tr.sx.fill(0.0);
            self.tr.sy.fill(0.0);
        }
        // The patch must not touch the border of the grid (unless the
        // caller counts those elements itself).
        for iy in (0..grid.ny).filter(|_| !problem.settings.allow_border_contact) {
            for ix in 0..grid.nx {
                if grid.on_border(ix, iy) && self.pn[grid.index(ix, iy)] > 0.0 {
                    return Err(ContactError::grid_too_small(
                        ix,
                        iy,
                        grid.nx,
                        grid.x_m(ix),
                        grid.y_m(iy),
                    ));
                }
            }
        }
        let totals = self.totals(approach, frictional, shift.is_some(), plastic_work);
        Ok(ContactSolution {
            totals,
            info,
            fields: ElementFields {
                pressure_pa: self.pn.clone(),
                traction_x_pa: self.tr.px.clone(),
                traction_y_pa: self.tr.py.clone(),
                slip_x: self.tr.sx.clone(),
                slip_y: self.tr.sy.clone(),
                state: self.tr.state.clone(),
                gap_m: problem.gap_m.clone(),
            },
        })
    }

    /// The tangential problem under Coulomb's law whose fixed slip is in
    /// `cx`, `cy`: steady rolling or a transient step; the bounds are
    /// `friction` times the pressures, or times `law.bound` when
    /// `law_bounds`.
    ///
    /// Static and kinetic coefficients: the static coefficient bounds the
    /// traction of a sticking element, the kinetic one that of a sliding
    /// element. An element enters slip when its traction would exceed
    /// mu_static p_n; in slip its traction is mu_kinetic p_n opposite to
    /// its slip; an element in slip keeps the kinetic bound for the rest of
    /// the solve and sticks again only within mu_kinetic p_n. This is the
    /// limit of CONTACT's slip-velocity laws (user guide, "Slip velocity
    /// dependent friction") as the fall from mu_static at zero slip
    /// velocity to mu_kinetic becomes a step, solved as CONTACT solves them
    /// from zero slip velocity (INISLP 1): where both states are possible
    /// (an adhesion traction between the two bounds) the element sticks
    /// unless it has slid in an earlier pass. (CONTACT's Coulomb law, L 0,
    /// takes one coefficient: it replaces FKIN by FSTAT.)
    ///
    /// The solve runs in passes, each a Coulomb problem with fixed bounds
    /// ([`Self::coulomb_pass`]): mu_kinetic p_n on the kinetic set,
    /// mu_static p_n elsewhere. The set starts empty and takes in, after
    /// each pass, the elements in slip in its answer; the solve ends when a
    /// pass adds none. Every element in slip is then bounded by mu_kinetic
    /// p_n, every sticking one by mu_static p_n (by mu_kinetic p_n where it
    /// slid in an earlier pass). The set only grows, so no element flips
    /// between the two bounds from pass to pass (bounds that followed the
    /// Newton iterate's states, kinetic behind an element sorted into slip,
    /// did, and steady solves ran into their iteration limit), and each
    /// pass's problem has one solution: the answer depends on the warm
    /// start only through elements at the edge of slip within the
    /// tolerance. Steady rolling and transient steps follow the same rule,
    /// without a memory of the element upstream or the step before: a
    /// steady state that transient rolling reaches meets the steady rule,
    /// but with the static coefficient well above the kinetic one transient
    /// rolling may instead settle into a stick-slip cycle, as it does in
    /// CONTACT (`tests/validation/static_kinetic.rs`). Each pass starts from
    /// the last one's tractions; the passes share
    /// `settings.max_iterations`, and a pass that does not converge ends the
    /// solve with its outcome. Equal coefficients take one pass.
    fn tangential_pass(
        &mut self,
        settings: &TangentialSettings,
        friction: FrictionBounds,
        steady: bool,
        law_bounds: bool,
    ) -> TangentialOutcome {
        self.kinetic.fill(ElementState::Exterior);
        let mut outcome = self.coulomb_pass(settings, friction, steady, law_bounds);
        if friction.static_coefficient == friction.kinetic_coefficient {
            return outcome;
        }
        while outcome.converged && !cancel::requested() && self.grow_kinetic_set() {
            let left = settings.max_iterations.saturating_sub(outcome.iterations);
            if left == 0 {
                // The last pass's answer does not meet the grown set's
                // bounds: the solve ends on its iteration limit.
                outcome.converged = false;
                break;
            }
            let limited = TangentialSettings {
                max_iterations: left,
                ..*settings
            };
            outcome = self
                .coulomb_pass(&limited, friction, steady, law_bounds)
                .after(&outcome);
        }
        outcome
    }

    /// Adds the elements in slip in the current answer to the kinetic set;
    /// returns whether it grew.
    fn grow_kinetic_set(&mut self) -> bool {
        let mut grew = false;
        for (k, &s) in self.kinetic.iter_mut().zip(&self.tr.state) {
            if s == ElementState::Slip && *k != ElementState::Slip {
                *k = ElementState::Slip;
                grew = true;
            }
        }
        grew
    }

    /// One Coulomb solve of the tangential problem with the bounds fixed by
    /// the kinetic set (see [`Self::tangential_pass`]).
    fn coulomb_pass(
        &mut self,
        settings: &TangentialSettings,
        friction: FrictionBounds,
        steady: bool,
        law_bounds: bool,
    ) -> TangentialOutcome {
        let grid = self.grid;
        let n = grid.len();
        let input = TangentialInput {
            grid: &grid,
            pn: if law_bounds {
                &self.law.bound
            } else {
                &self.pn
            },
            friction,
            cx: &self.cx,
            cy: &self.cy,
            previous_state: &self.kinetic,
        };
        if steady {
            // The steady operator through the displacement kernels (real
            // spectra; exact, the patch being off the border); time
            // marching when Newton stalls (dissimilar materials with
            // little friction: Bentall's rollers).
            newton_with_restarts(settings, |newton, limited| {
                if newton {
                    solve_steady_newton(
                        &self.displacement,
                        &mut self.ows,
                        &input,
                        self.tr.output(),
                        self.newton_scratch
                            .get_or_insert_with(|| SteadyScratch::new(n)),
                        limited,
                    )
                } else {
                    solve_steady_marching(
                        &self.displacement,
                        &mut self.ows,
                        &input,
                        self.tr.output(),
                        &mut self.tangential_scratch,
                        &mut self.marching_scratch,
                        limited,
                    )
                }
            })
        } else {
            // Newton on the step's Coulomb system (about half the products
            // of FISTA); FISTA when it stalls.
            newton_with_restarts(settings, |newton, limited| {
                if newton {
                    let mut op = PlanarTangential {
                        kernels: &self.displacement,
                        ows: &mut self.ows,
                    };
                    solve_coulomb_newton(
                        &mut op,
                        LocalModel::Diagonal,
                        None,
                        &input,
                        self.tr.output(),
                        self.newton_scratch
                            .get_or_insert_with(|| SteadyScratch::new(n)),
                        limited,
                    )
                } else {
                    solve_transient(
                        &self.displacement,
                        &mut self.ows,
                        &input,
                        self.tr.output(),
                        &mut self.tangential_scratch,
                        limited,
                    )
                }
            })
        }
    }

    /// The tangential problem under the slip-velocity dependent `law`
    /// (steady, or a transient step rolling `rolling_m` \[m\]): a
    /// fixed-point iteration on the slip velocities, each pass a Coulomb
    /// problem with the bounds mu(s_a) p_n of the last pass's slip
    /// velocities, until the bounds of the answer's own slip velocities
    /// differ from those it was solved with by less than ten times the
    /// tangential tolerance (root mean square, relative to that of the
    /// bounds). The first coupling pass (`coupling` 0) starts from
    /// `law.start`; later ones continue. A pass whose change grows halves
    /// the step towards the new slip velocities (relaxation, down to 1/16),
    /// one whose change shrinks lengthens it again (up to 1); the iteration
    /// stops at `law.iteration_limit()` passes. Returns the passes' outcome
    /// (iterations and products summed) and whether the bounds converged.
    fn falling_friction(
        &mut self,
        law: &SlipVelocityLaw,
        settings: &TangentialSettings,
        steady: bool,
        rolling_m: f64,
        coupling: usize,
    ) -> (TangentialOutcome, bool) {
        let grid = self.grid;
        self.law.used = true;
        let speed = law.rolling_speed_m_per_s;
        // Slip velocity per unit of the solver's slip, and the step's time:
        // steady s [-] at V; a rolling step's S [m] over dq/V; a shift's S
        // over 1 s (CONTACT's convention, see core::friclaw).
        let (per_slip, dt_s) = if steady {
            (speed, grid.dx_m / speed)
        } else if rolling_m > 0.0 {
            (speed / rolling_m, rolling_m / speed)
        } else {
            (1.0, 1.0)
        };
        if coupling == 0 {
            match law.start {
                SlipStart::Previous => {}
                SlipStart::Sticking => self.law.velocity.fill(0.0),
                SlipStart::Sliding => self.law.velocity.fill(speed),
            }
        }
        let tol = 10.0 * settings.tolerance;
        let mut total = TangentialOutcome::default();
        let mut omega = 1.0f64;
        let mut last_change = f64::INFINITY;
        for _ in 0..law.iteration_limit() {
            self.law_coefficients(law, steady, dt_s);
            for i in 0..grid.len() {
                self.law.bound[i] = self.pn[i] * self.law.mu[i] * self.row_factor(i);
            }
            let bound = FrictionBounds {
                static_coefficient: 1.0,
                kinetic_coefficient: 1.0,
            };
            let o = self.tangential_pass(settings, bound, steady, true);
            total = o.after(&total);
            if cancel::requested() {
                return (total, false);
            }
            // The slip velocities of this pass's solution and the bounds
            // they give.
            let law_state = &mut self.law;
            for i in 0..grid.len() {
                let (sx, sy) = (self.tr.sx[i], self.tr.sy[i]);
                law_state.velocity_new[i] = per_slip * (sx * sx + sy * sy).sqrt();
            }
            std::mem::swap(&mut law_state.velocity, &mut law_state.velocity_new);
            self.law_coefficients(law, steady, dt_s);
            let (mut change, mut size) = (0.0f64, 0.0f64);
            for i in 0..grid.len() {
                let new_bound = self.law.mu[i] * self.pn[i] * self.row_factor(i);
                change += (new_bound - self.law.bound[i]).powi(2);
                size += self.law.bound[i].powi(2);
            }
            let law_state = &mut self.law;
            let change = if size > 0.0 {
                (change / size).sqrt()
            } else {
                0.0
            };
            if change <= tol {
                // This pass's tractions meet the bounds of their own slip.
                return (total, o.converged);
            }
            omega = if change > last_change {
                (0.5 * omega).max(1.0 / 16.0)
            } else {
                (1.5 * omega).min(1.0)
            };
            last_change = change;
            // Relaxed step: velocity <- old + omega (new - old).
            for i in 0..grid.len() {
                let old = law_state.velocity_new[i];
                law_state.velocity[i] = old + omega * (law_state.velocity[i] - old);
            }
        }
        // Leave the coefficients of the slip velocities of the answer.
        let law_state = &mut self.law;
        for i in 0..grid.len() {
            let (sx, sy) = (self.tr.sx[i], self.tr.sy[i]);
            law_state.velocity[i] = per_slip * (sx * sx + sy * sy).sqrt();
        }
        self.law_coefficients(law, steady, dt_s);
        (total, false)
    }

    /// The tangential problem with the elasto-plastic interfacial `layer`
    /// and Coulomb's coefficient `mu` (steady rolling or a transient
    /// step): passes of Coulomb's problem with fixed bounds, the bounds
    /// from the last pass's generalised slips by one local Newton step of
    /// the layer's law, relaxed (halved, down to 1/16, when the law's
    /// residual grows; lengthened again when it shrinks), until the bounds
    /// of an answer's own slips differ from those it was solved with by
    /// at most ten times the tangential tolerance (root mean square,
    /// relative), at most [`MAX_LAYER_PASSES`] passes sharing
    /// `settings.max_iterations` (see [`crate::core::layer`]). The first
    /// pass takes the law's bounds of the slips the last solve left.
    fn plastic_layer_passes(
        &mut self,
        layer: &InterfacialLayer,
        mu: f64,
        settings: &TangentialSettings,
        steady: bool,
    ) -> TangentialOutcome {
        let grid = self.grid;
        // Each element's own compliance: the response of its generalised
        // slip to its bound, the others held (with the layer's F).
        let compliance = if steady {
            let b = self.displacement.steady_diagonal();
            grid.dx_m * 0.5 * (b[0] + b[1])
        } else {
            0.5 * (self.displacement.value(Component::X, Component::X, 0, 0)
                + self.displacement.value(Component::Y, Component::Y, 0, 0))
        };
        let scale = if steady { grid.dx_m } else { 1.0 };
        let tol = 10.0 * settings.tolerance;
        let unit = FrictionBounds {
            static_coefficient: 1.0,
            kinetic_coefficient: 1.0,
        };
        fn coulomb<'a>(
            pn: &'a [f64],
            mu: f64,
            row_scale: &'a [f64],
            nx: usize,
        ) -> CoulombBound<'a> {
            CoulombBound {
                pn,
                mu,
                row_scale,
                nx,
            }
        }
        let l = self.layer.as_mut().expect("allocated by the caller");
        l.bounds(
            layer,
            &grid,
            steady,
            coulomb(&self.pn, mu, &self.row_scale, grid.nx),
            None,
            &mut self.law.bound,
        );
        let mut total = TangentialOutcome::default();
        let (mut omega, mut last_change) = (1.0f64, f64::INFINITY);
        for _ in 0..MAX_LAYER_PASSES {
            let left = settings.max_iterations.saturating_sub(total.iterations);
            if left == 0 {
                total.converged = false;
                return total;
            }
            let limited = TangentialSettings {
                max_iterations: left,
                ..*settings
            };
            let o = self.tangential_pass(&limited, unit, steady, true);
            total = o.after(&total);
            if cancel::requested() || !o.converged {
                return total;
            }
            let l = self.layer.as_mut().expect("allocated by the caller");
            l.set_slid(&self.tr.sx, &self.tr.sy, scale);
            let (change, size) = l.bounds(
                layer,
                &grid,
                steady,
                coulomb(&self.pn, mu, &self.row_scale, grid.nx),
                Some(compliance),
                &mut self.law.bound,
            );
            let change = if size > 0.0 {
                (change / size).sqrt()
            } else {
                0.0
            };
            if change <= tol {
                // This pass's tractions meet the bounds of their own slips.
                return total;
            }
            omega = if change > last_change {
                (0.5 * omega).max(1.0 / 16.0)
            } else {
                (1.5 * omega).min(1.0)
            };
            last_change = change;
            for (g, &next) in self.law.bound.iter_mut().zip(&l.next) {
                *g += omega * (next - *g);
            }
        }
        total.converged = false;
        total
    }

    /// The interfacial layer's state per element after the last solve,
    /// in the problem's frame (index `iy * nx + ix`): the yield limit,
    /// the accumulated plastic deformation and where the layer flowed
    /// without slip (CONTACT's TAUCRT, UPLSX, UPLSY and plasticity area;
    /// [`crate::core::layer`]). None unless the last solve had an
    /// elasto-plastic layer (an elastic one has no state).
    pub fn layer_fields(&self) -> Option<LayerFields> {
        let l = self.layer.as_ref().filter(|l| l.used)?;
        let n = l.hardening.len();
        let mut f = LayerFields {
            yield_limit_pa: vec![0.0; n],
            plastic_x_m: vec![0.0; n],
            plastic_y_m: vec![0.0; n],
            plastic: vec![false; n],
        };
        let tau: Vec<f64> = l.hardening.iter().map(|h| l.yield_limit + h).collect();
        self.frame.field_to_user(&tau, &mut f.yield_limit_pa);
        self.frame.field_to_user(&l.flow, &mut f.plastic);
        let (mut x, mut y) = (vec![0.0; n], vec![0.0; n]);
        for i in 0..n {
            [x[i], y[i]] = self.frame.to_user([l.plastic_x[i], l.plastic_y[i]]);
        }
        self.frame.field_to_user(&x, &mut f.plastic_x_m);
        self.frame.field_to_user(&y, &mut f.plastic_y_m);
        Some(f)
    }

    /// `law.mu` from `law.velocity`: along the rows in steady rolling, from
    /// the previous step's coefficients in a transient step of `dt_s` \[s\].
    fn law_coefficients(&mut self, law: &SlipVelocityLaw, steady: bool, dt_s: f64) {
        let st = &mut self.law;
        if steady {
            law.steady_coefficients(&self.grid, &st.velocity, &mut st.mu);
        } else {
            law.step_coefficients(&st.velocity, &st.mu_before, dt_s, &mut st.mu);
        }
    }

    /// The totals of the current solution; `plastic_work` an interfacial
    /// layer's plastic work \[J\] (steady rolling: per unit rolled
    /// distance, \[N\]), part of the frictional work.
    fn totals(
        &self,
        approach: f64,
        frictional: bool,
        transient: bool,
        plastic_work: f64,
    ) -> Totals {
        let g = &self.grid;
        let area = g.element_area_m2();
        let mut t = Totals {
            approach_m: approach,
            ..Default::default()
        };
        let (mut ncontact, mut nadh) = (0usize, 0usize);
        let mut dissipation = 0.0;
        for iy in 0..g.ny {
            let y = g.y_m(iy);
            for ix in 0..g.nx {
                let x = g.x_m(ix);
                let i = g.index(ix, iy);
                let (pn, px, py) = (self.pn[i], self.tr.px[i], self.tr.py[i]);
                t.normal_force_n += pn * area;
                t.fx_n += px * area;
                t.fy_n += py * area;
                t.mz_nm += (x * py - y * px) * area;
                t.max_pressure_pa = t.max_pressure_pa.max(pn);
                t.max_traction_pa = t.max_traction_pa.max((px * px + py * py).sqrt());
                if pn > 0.0 {
                    ncontact += 1;
                    if self.tr.state[i] == ElementState::Adhesion {
                        nadh += 1;
                    }
                    dissipation -= (px * self.tr.sx[i] + py * self.tr.sy[i]) * area;
                }
            }
        }
        t.contact_area_m2 = ncontact as f64 * area;
        if let Some([length, width]) = g.loaded_extent_m(&self.pn) {
            t.patch_length_m = length;
            t.patch_width_m = width;
            t.adhesion_fraction = nadh as f64 / ncontact as f64;
        }
        if frictional {
            dissipation += plastic_work;
            if transient {
                t.frictional_work_j = dissipation;
            } else {
                t.tgamma_n = dissipation;
            }
        }
        t
    }
}

/// The flexibility of `problem`'s interfacial layer \[m/Pa\] (0 without
/// one, and for a layer that validation refuses): the one the kernels of
/// [`ContactSolver::new`] include
/// ([`KernelCache::get_layered`]).
pub fn layer_flexibility(problem: &ContactProblem) -> f64 {
    let f = problem
        .settings
        .interfacial_layer
        .map_or(0.0, |l| l.flexibility_m_per_pa());
    if f.is_finite() && f > 0.0 {
        f
    } else {
        0.0
    }
}

/// The displacement kernels of `problem` on its rolling frame's `grid`:
/// the half-space's (with the problem's layer and viscoelastic bodies), or
/// a file's of numerical influence coefficients.
fn displacement_kernels(
    problem: &ContactProblem,
    grid: &Grid,
    cache: &KernelCache,
) -> Arc<KernelSet> {
    match &problem.numerical_influence {
        Some(table) => cache.get_numerical(
            grid,
            &problem.material,
            Some(table),
            KernelKind::Displacement,
        ),
        None => cache.get_viscoelastic(
            grid,
            &problem.material,
            layer_flexibility(problem),
            problem.settings.viscoelastic.as_ref(),
            KernelKind::Displacement,
        ),
    }
}

/// `problem`'s interfacial layer when it deforms plastically.
fn plastic_layer(problem: &ContactProblem) -> Option<InterfacialLayer> {
    problem
        .settings
        .interfacial_layer
        .filter(InterfacialLayer::is_plastic)
}

/// Tangential tractions, slips and element states of the current solution.
#[derive(Clone)]
struct Tractions {
    px: Vec<f64>,
    py: Vec<f64>,
    sx: Vec<f64>,
    sy: Vec<f64>,
    state: Vec<ElementState>,
}

impl Tractions {
    fn output(&mut self) -> TangentialOutput<'_> {
        TangentialOutput {
            px: &mut self.px,
            py: &mut self.py,
            sx: &mut self.sx,
            sy: &mut self.sy,
            state: &mut self.state,
        }
    }
}

/// A tangential solve by Newton (`attempt(true, settings)`) that, while
/// it stalls, continues with [`MARCHING_RESTART`] iterations of the
/// fallback (`attempt(false, settings)`: time marching or FISTA, from the
/// last iterate) and tries Newton again: all attempts together within
/// `settings.max_iterations` (each is given what is left).
fn newton_with_restarts(
    settings: &TangentialSettings,
    mut attempt: impl FnMut(bool, &TangentialSettings) -> TangentialOutcome,
) -> TangentialOutcome {
    let mut outcome = TangentialOutcome::default();
    let mut newton = true;
    let mut idle = 0;
    loop {
        let left = settings.max_iterations.saturating_sub(outcome.iterations);
        if left == 0 {
            return outcome;
        }
        let mut limited = *settings;
        limited.max_iterations = if newton {
            left
        } else {
            MARCHING_RESTART.min(left)
        };
        let before = outcome.iterations;
        outcome = attempt(newton, &limited).after(&outcome);
        if outcome.converged {
            return outcome;
        }
        // A cancelled solve's attempts stop at once, without iterations:
        // the caller's check answers Cancelled. Two attempts in a row
        // without an iteration would alternate for ever.
        idle = if outcome.iterations == before {
            idle + 1
        } else {
            0
        };
        if cancel::requested() || idle >= 2 {
            return outcome;
        }
        newton = !newton;
    }
}

/// `u = A p` on the grid of `kernels` (a [`KernelKind::Displacement`] set):
/// the displacement differences (x, y, n) \[m\] of the tractions (x, y, n)
/// \[Pa\] `p`, every element, in one product (a traction component that
/// is zero everywhere is not transformed; an output nothing feeds is
/// zero). `ows` must fit `kernels` ([`KernelSet::fits`]).
pub fn displacement_differences(
    kernels: &KernelSet,
    ows: &mut OperatorWorkspace,
    [px, py, pn]: [&[f64]; 3],
    [ux, uy, un]: &mut [Vec<f64>; 3],
) {
    let loaded = [(Component::X, px), (Component::Y, py), (Component::N, pn)];
    let mut inputs: [(Component, &[f64]); 3] = loaded;
    let mut used = 0;
    for (c, p) in loaded {
        if p.iter().any(|&v| v != 0.0) {
            inputs[used] = (c, p);
            used += 1;
        }
    }
    kernels.apply(
        ows,
        &inputs[..used],
        &mut [
            (Component::X, ux.as_mut_slice()),
            (Component::Y, uy.as_mut_slice()),
            (Component::N, un.as_mut_slice()),
        ],
    );
}

/// Rigid slip of body 1 relative to body 2 at every element centre:
/// w = (a_x - rot y, a_y + rot x), for creepages and spin (steady rolling) or
/// shifts and rotation (transient step).
fn rigid_slip(grid: &Grid, a: [f64; 2], rot: f64, wx: &mut [f64], wy: &mut [f64]) {
    for iy in 0..grid.ny {
        let y = grid.y_m(iy);
        for ix in 0..grid.nx {
            let i = grid.index(ix, iy);
            wx[i] = a[0] - rot * y;
            wy[i] = a[1] + rot * grid.x_m(ix);
        }
    }
}

/// `c += factor * e`, component by component.
fn add_scaled(factor: f64, e: [&[f64]; 2], c: [&mut [f64]; 2]) {
    for (c, e) in c.into_iter().zip(e) {
        for (c, e) in c.iter_mut().zip(e) {
            *c += factor * e;
        }
    }
}

/// `c += factor * A_tn p_n`: the tangential displacement difference of a
/// normal pressure field (non-zero for dissimilar materials only).
fn add_tangential_of_normal(
    k: &KernelSet,
    ows: &mut OperatorWorkspace,
    pn: &[f64],
    factor: f64,
    [tmp_x, tmp_y]: [&mut [f64]; 2],
    [cx, cy]: [&mut [f64]; 2],
) {
    k.apply(
        ows,
        &[(Component::N, pn)],
        &mut [(Component::X, tmp_x), (Component::Y, tmp_y)],
    );
    for i in 0..cx.len() {
        cx[i] += factor * tmp_x[i];
        cy[i] += factor * tmp_y[i];
    }
}

/// Cold steady-rolling solves on grids of at least this many elements may
/// start from the solution on the grid of twice the element size
/// ([`ContactSolver::start_nested`]). Measured below it: at 128 x 128 the
/// coarse solve cost what it saved (5 Newton steps instead of 8, the same
/// time), at 143 x 163 it saved 10-15 %; the threshold lies above both.
pub const NESTED_START_ELEMENTS: usize = 50_000;

/// Bilinear interpolation of `v` on the element centres of `from` onto
/// those of `to` (`out`); beyond the outermost centres of `from` its
/// border values.
fn interpolate(from: &Grid, v: &[f64], to: &Grid, out: &mut [f64]) {
    let at = |x: f64, n: usize| {
        let f = x.clamp(0.0, (n - 1) as f64);
        let i = (f as usize).min(n.saturating_sub(2));
        (i, f - i as f64)
    };
    for iy in 0..to.ny {
        let (j, wy) = at((to.y_m(iy) - from.y_m(0)) / from.dy_m, from.ny);
        for ix in 0..to.nx {
            let (i, wx) = at((to.x_m(ix) - from.x_m(0)) / from.dx_m, from.nx);
            let g = |a: usize, b: usize| v[from.index(a, b)];
            out[to.index(ix, iy)] = (1.0 - wy) * ((1.0 - wx) * g(i, j) + wx * g(i + 1, j))
                + wy * ((1.0 - wx) * g(i, j + 1) + wx * g(i + 1, j + 1));
        }
    }
}

/// Solves `problem` with the process-wide kernel cache, a large
/// steady-rolling one from its nested start
/// ([`ContactSolver::start_nested`]) as the command line and the service do.
pub fn solve(problem: &ContactProblem) -> Result<Vec<ContactSolution>, ContactError> {
    let cache = KernelCache::global();
    let mut s = ContactSolver::new(problem, cache);
    s.start_nested(problem, cache)?;
    s.solve(problem)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::hertz::{hertz, HertzLoad};
    use crate::core::material::{CombinedMaterial, Material};
    use crate::core::problem::{Creepages, Friction};

    /// Steel on steel, A = B = 1/m on a 32 x 32 grid, rolling with creepages
    /// and load `f` times the base values (10 kN, xi = 5e-4, eta = 3e-4,
    /// phi = 0.3/m: partial slip).
    fn rolling(f_load: f64, f_creep: f64) -> ContactProblem {
        let m = CombinedMaterial::identical(Material::STEEL).unwrap();
        let e = m.effective_modulus_pa();
        let hz = hertz(
            1.0,
            1.0,
            e,
            HertzLoad::NormalForce {
                normal_force_n: 1.1e4,
            },
        )
        .unwrap();
        let w = 2.4 * hz.semi_axis_x_m;
        let grid = Grid::centered(32, 32, w, w).unwrap();
        ContactProblem {
            material: m,
            friction: Friction::coulomb(0.3),
            gap_m: ContactProblem::quadratic_gap(&grid, 1.0, 1.0),
            grid,
            load: NormalLoad::NormalForce(1e4 * f_load),
            kinematics: Kinematics::SteadyRolling(Creepages {
                creepage_long: 5e-4 * f_creep,
                creepage_lat: 3e-4 * f_creep,
                spin_per_m: 0.3 * f_creep,
            }),
            settings: Default::default(),
            rolling_direction_rad: 0.0,
            extra_rigid_slip: None,
            numerical_influence: None,
        }
    }

    /// [`rolling`] (base load and creepages) on `n` x `n` elements over
    /// the same window.
    fn rolling_on(n: usize) -> ContactProblem {
        let mut p = rolling(1.0, 1.0);
        let (g, f) = (p.grid, 32.0 / n as f64);
        p.grid = Grid::new(n, n, f * g.dx_m, f * g.dy_m, g.x0_m, g.y0_m).unwrap();
        p.gap_m = ContactProblem::quadratic_gap(&p.grid, 1.0, 1.0);
        p
    }

    /// What a solver holds between solves on 256 x 256 elements (the
    /// service's largest grid by default): its fields and scratch, one
    /// buffer of n items each, counted from the lists below; the FFT
    /// workspaces; after a frictional solve, the Newton scratch and the
    /// prediction's three fields. `release_scratch` gives the Newton
    /// scratch back. Printed with `--nocapture`.
    #[test]
    fn a_solver_holds_its_buffers_and_not_its_kernels() {
        let cache = KernelCache::default();
        let mut p = rolling(1.0, 1.0);
        let g = p.grid;
        p.grid = Grid::centered(256, 256, 8.0 * g.dx_m * 32.0, 8.0 * g.dy_m * 32.0).unwrap();
        p.gap_m = ContactProblem::quadratic_gap(&p.grid, 1.0, 1.0);
        let n = p.grid.len();
        let mut s = ContactSolver::new(&p, &cache);
        // Per element: pn, px, py, sx, sy, h_eff, cx, cy, tmp_x, tmp_y,
        // old_ux, old_uy, last_pn, last_px, last_py; the law's mu,
        // mu_before, velocity, velocity_new, bound; the normal scratch's u,
        // t, r, g, p_old, z, ones (and `free`); the tangential scratch's
        // six; the marching scratch's eight; the solver's two element
        // states (the answer's and the kinetic set).
        let f64s = 15 + 5 + 7 + 6 + 8;
        let per_element = 8 * f64s + 2 * std::mem::size_of::<ElementState>() + 1;
        let ows = s.ows.heap_bytes();
        // The normal solver's list of the elements one iteration clamps.
        let columns = std::mem::size_of::<(usize, f64)>() * crate::core::normal::column_capacity(n);
        assert_eq!(s.heap_bytes(), per_element * n + ows + columns);
        // The FFT workspaces: per plan, six spectra (inputs and outputs of
        // three components) of at most the padded grid's half spectrum;
        // four plans (double, its preconditioner, single, the tangential
        // preconditioner), none padded beyond 2 (nx + 1) x 2 (ny + 1).
        let padded = 2 * (g.nx * 8 + 1) * 2 * (g.ny * 8 + 1);
        assert!(ows < 4 * 6 * 16 * padded, "{ows}");
        let kernels = s.displacement.bytes();
        let fresh = s.heap_bytes();
        solve_last(&mut s, &p);
        let newton = s.newton_scratch.heap_bytes();
        // The Newton scratch: its buffers, and the GMRES basis of the
        // vectors used, at most RESTART + 1 of 2 n.
        let buffers = crate::core::steady::SteadyScratch::new(n).heap_bytes();
        let basis = newton - buffers;
        assert!(
            newton > buffers && basis <= 8 * (crate::core::steady::RESTART + 1) * 2 * n,
            "{newton}"
        );
        assert_eq!(s.heap_bytes(), fresh + newton + 3 * 8 * n);
        println!(
            "256 x 256 solver: {fresh} bytes new ({} an element: {} fields and scratch, \
             FFT workspaces {ows}), {} after a rolling solve (Newton scratch {newton}, {} an \
             element, of which the GMRES basis {basis}); the kernels it shares with the cache: \
             {kernels}",
            fresh / n,
            per_element,
            s.heap_bytes(),
            newton / n
        );
        // After one solve the prediction's fields hold nothing yet.
        s.release_scratch();
        assert_eq!(s.heap_bytes(), fresh);
    }

    fn solve_last(s: &mut ContactSolver, p: &ContactProblem) -> ContactSolution {
        s.solve(p).unwrap().pop().unwrap()
    }

    /// A nested start (the solve on the grid of twice the element size,
    /// its tractions interpolated) gives the cold solve's answer to the
    /// tolerances: the 32 x 32 rolling case on 64 x 64 elements, nested
    /// down to 16 x 16 (the threshold lowered to reach these grids). The
    /// forces agree within 1e-6 of mu Fn (the tangential tolerance is 1e-7
    /// of mu p_max), the slip elements within 1 % of them. It does
    /// nothing on a warm solver, for other kinematics and below the
    /// threshold.
    #[test]
    fn a_nested_start_gives_the_cold_answer() {
        let cache = KernelCache::default();
        let p = rolling_on(64);
        let cold = solve_last(&mut ContactSolver::new(&p, &cache), &p);
        let mut s = ContactSolver::new(&p, &cache);
        assert!(s.start_nested_from(&p, &cache, 256).unwrap());
        assert!(s.tr.px.iter().any(|&t| t != 0.0));
        let nested = solve_last(&mut s, &p);
        let scale = 0.3 * cold.totals.normal_force_n;
        for (a, b) in [
            (cold.totals.fx_n, nested.totals.fx_n),
            (cold.totals.fy_n, nested.totals.fy_n),
            (cold.totals.normal_force_n, nested.totals.normal_force_n),
        ] {
            assert!((a - b).abs() <= 1e-6 * scale, "{a} against {b}");
        }
        let slip = |sol: &ContactSolution| {
            sol.fields
                .state
                .iter()
                .filter(|&&e| e == ElementState::Slip)
                .count() as f64
        };
        assert!((slip(&cold) - slip(&nested)).abs() <= 0.01 * slip(&cold));
        println!(
            "64 x 64: cold {} Newton steps, {} products; nested {} Newton steps, {} products",
            cold.info.tangential_iterations,
            cold.info.matvecs,
            nested.info.tangential_iterations,
            nested.info.matvecs
        );
        // Warm now: nothing to do.
        assert!(!s.start_nested_from(&p, &cache, 256).unwrap());
        // Below the threshold, or not steady rolling.
        let mut fresh = ContactSolver::new(&p, &cache);
        assert!(!fresh.start_nested(&p, &cache).unwrap());
        let mut frictionless = p.clone();
        frictionless.kinematics = Kinematics::Frictionless;
        assert!(!fresh.start_nested_from(&frictionless, &cache, 256).unwrap());
    }

    /// A steady-rolling solve cancelled while its Newton method runs
    /// returns Cancelled (its attempts stop at once, and the restarts
    /// between Newton and marching no longer alternate without iterations
    /// for ever; the service's solve time limit hit such a phase and kept
    /// its worker), with or without a nested start: the cancel comes 20
    /// and 50 ms into a 256 x 256 solve (kernels cached). Liveness only:
    /// each must end within 60 s.
    #[test]
    fn a_steady_solve_cancelled_in_its_newton_steps_stops() {
        let cache = KernelCache::default();
        let mut p = rolling_on(256);
        p.kinematics = Kinematics::SteadyRolling(Creepages {
            creepage_long: 2e-4,
            creepage_lat: 0.0,
            spin_per_m: 0.0,
        });
        let cache = std::sync::Arc::new(cache);
        let p = std::sync::Arc::new(p);
        ContactSolver::new(&p, &cache);
        for (delay_ms, nested) in [(20, false), (50, false), (20, true), (50, true)] {
            let token = crate::core::cancel::CancelToken::new();
            let (tx, rx) = std::sync::mpsc::channel();
            let (c, q, t) = (cache.clone(), p.clone(), token.clone());
            std::thread::spawn(move || {
                let r = t.scope(|| {
                    let mut s = ContactSolver::new(&q, &c);
                    if nested {
                        s.start_nested_from(&q, &c, 256)?;
                    }
                    s.solve(&q).map(|_| ())
                });
                let _ = tx.send(r);
            });
            std::thread::sleep(std::time::Duration::from_millis(delay_ms));
            token.cancel();
            match rx.recv_timeout(std::time::Duration::from_secs(60)) {
                Ok(r) => assert!(
                    matches!(r, Ok(()) | Err(ContactError::Cancelled)),
                    "{delay_ms} ms, nested {nested}: {r:?}"
                ),
                Err(_) => {
                    panic!("{delay_ms} ms, nested {nested}: the cancelled solve did not stop")
                }
            }
        }
    }

    /// A renewed solver solves as a new one, bit for bit: one that solved
    /// other loads and creepages with a row friction scale, renewed for a
    /// grid of the same shape one element and a half away, and a new solver
    /// for that grid, solve the same sequence to the same bits.
    #[test]
    fn a_renewed_solver_solves_as_a_new_one() {
        let cache = KernelCache::default();
        let first = rolling(1.0, 1.0);
        let mut used = ContactSolver::new(&first, &cache);
        used.set_row_friction_scale(&[0.9; 32]).unwrap();
        solve_last(&mut used, &first);
        solve_last(&mut used, &rolling(1.2, 3.0));
        used.continue_from_last_solution();
        let moved = |f_load: f64, f_creep: f64| {
            let mut p = rolling(f_load, f_creep);
            let g = p.grid;
            p.grid = Grid::new(
                g.nx,
                g.ny,
                g.dx_m,
                g.dy_m,
                g.x0_m + g.dx_m,
                g.y0_m - 0.5 * g.dy_m,
            )
            .unwrap();
            p.gap_m = ContactProblem::quadratic_gap(&p.grid, 1.0, 1.0);
            p
        };
        used.renew(&moved(0.9, 2.0), &cache);
        let mut fresh = ContactSolver::new(&moved(0.9, 2.0), &cache);
        let mut frictionless = moved(1.1, 2.0);
        frictionless.kinematics = Kinematics::Frictionless;
        for p in [
            moved(0.9, 2.0),
            frictionless,
            moved(1.0, 2.5),
            moved(1.05, 2.6),
        ] {
            let (a, b) = (solve_last(&mut used, &p), solve_last(&mut fresh, &p));
            assert_eq!(a.fields, b.fields);
            assert_eq!(format!("{:?}", a.totals), format!("{:?}", b.totals));
            assert_eq!(a.info.matvecs, b.info.matvecs);
        }
    }

    /// A row scale of 2 everywhere is the coefficients doubled; a scale that differs by row bounds each row
    /// by its own coefficient; a scale of the wrong length is refused naming
    /// the key.
    #[test]
    fn row_friction_scale_bounds_each_row_by_its_coefficient() {
        let cache = KernelCache::default();
        let mut p = rolling(1.0, 20.0);
        p.friction = Friction::coulomb(0.15);
        let mut scaled = ContactSolver::new(&p, &cache);
        scaled
            .set_row_friction_scale(&vec![2.0; p.grid.ny])
            .unwrap();
        let a = solve_last(&mut scaled, &p);
        let mut q = p.clone();
        q.friction = Friction::coulomb(0.3);
        let b = solve_last(&mut ContactSolver::new(&q, &cache), &q);
        // Not to the bit: the bounds reach the solvers as their pressures
        // (measured on Fx: 2.8e-12 of mu Fn).
        let limit = 1e-9 * 0.3 * b.totals.normal_force_n;
        assert!((a.totals.fx_n - b.totals.fx_n).abs() < limit);
        assert!((a.totals.fy_n - b.totals.fy_n).abs() < limit);
        // Rows below the centre at 0.1, above at 0.3 (of 0.15 x 2/3, 2): in
        // full slip each element carries its row's mu p_n.
        let g = p.grid;
        let scale: Vec<f64> = (0..g.ny)
            .map(|iy| if g.y_m(iy) < 0.0 { 2.0 / 3.0 } else { 2.0 })
            .collect();
        scaled.set_row_friction_scale(&scale).unwrap();
        let c = solve_last(&mut scaled, &p);
        let f = &c.fields;
        for (iy, row_scale) in scale.iter().enumerate() {
            for ix in 0..g.nx {
                let i = g.index(ix, iy);
                if f.pressure_pa[i] > 0.0 && f.state[i] == ElementState::Slip {
                    let t = f.traction_x_pa[i].hypot(f.traction_y_pa[i]);
                    let bound = 0.15 * row_scale * f.pressure_pa[i];
                    assert!(
                        (t - bound).abs() <= 1e-6 * bound,
                        "row {iy}: {t} against {bound}"
                    );
                }
            }
        }
        let err = scaled.set_row_friction_scale(&[1.0; 3]).unwrap_err();
        assert!(err.to_string().contains("row_friction_scale"), "{err}");
        let err = scaled.set_row_friction_scale(&vec![0.0; g.ny]).unwrap_err();
        assert!(err.to_string().contains("row_friction_scale"), "{err}");
        scaled.set_row_friction_scale(&[]).unwrap();
        let d = solve_last(&mut scaled, &p);
        let e = solve_last(&mut ContactSolver::new(&p, &cache), &p);
        // The same answer from another start (the last solve's tractions),
        // to the tangential tolerance.
        let mu_fn = 0.15 * e.totals.normal_force_n;
        assert!((d.totals.fx_n - e.totals.fx_n).abs() < 1e-5 * mu_fn);
        assert!((d.totals.fy_n - e.totals.fy_n).abs() < 1e-5 * mu_fn);
    }

    #[test]
    fn a_cancelled_solve_has_no_answer_and_leaves_the_solver_usable() {
        let cache = KernelCache::default();
        let p = rolling(1.0, 1.0);
        let mut s = ContactSolver::new(&p, &cache);
        let token = crate::core::cancel::CancelToken::new();
        token.cancel();
        assert_eq!(token.scope(|| s.solve(&p)), Err(ContactError::Cancelled));
        // The same answer as a solver that was never cancelled, to the
        // solver's tolerances (different starts: the cancelled solve left
        // its prediction in place).
        let a = solve_last(&mut s, &p);
        let b = solve_last(&mut ContactSolver::new(&p, &cache), &p);
        assert_eq!(a.info.status, SolveStatus::Converged);
        for (x, y) in [
            (a.totals.fx_n, b.totals.fx_n),
            (a.totals.fy_n, b.totals.fy_n),
        ] {
            assert!((x - y).abs() <= 1e-6 * y.abs(), "{x} against {y}");
        }
    }

    #[test]
    fn a_restored_state_gives_the_bits_of_a_solver_that_never_saw_the_failed_solve() {
        let cache = KernelCache::default();
        let path = [rolling(1.0, 1.0), rolling(1.01, 1.02), rolling(1.02, 1.04)];
        let mut replay = ContactSolver::new(&path[0], &cache);
        let want: Vec<Totals> = path
            .iter()
            .map(|p| solve_last(&mut replay, p).totals)
            .collect();
        let mut s = ContactSolver::new(&path[0], &cache);
        let mut saved = SolverState::default();
        for p in &path[..2] {
            solve_last(&mut s, p);
        }
        s.save_state(&mut saved);
        assert_eq!(saved.bytes(), s.state_bytes());
        // Refused after the prediction moved the start (no contact) and
        // after a whole solve (the patch beyond the grid).
        let mut none = rolling(1.0, 1.0);
        none.load = NormalLoad::Approach(1e-12);
        let mut huge = rolling(100.0, 1.0);
        huge.load = NormalLoad::NormalForce(1e7);
        for bad in [none, huge] {
            assert!(s.solve(&bad).is_err());
            s.restore_state(&saved).unwrap();
        }
        let got = solve_last(&mut s, &path[2]).totals;
        assert_eq!(format!("{got:?}"), format!("{:?}", want[2]));
    }

    /// The creepages of [`rolling`] with factor 1.
    fn base_creepages() -> Creepages {
        match rolling(1.0, 1.0).kinematics {
            Kinematics::SteadyRolling(c) => c,
            _ => unreachable!(),
        }
    }

    #[test]
    fn a_rolling_step_from_rest_is_the_shift_by_the_creepages_times_the_distance() {
        let cache = KernelCache::default();
        let mut p = rolling(1.0, 1.0);
        let c = base_creepages();
        let mut solve_step = |dq: f64, rolls: bool| {
            let roll = ShiftStep::rolling(p.load, dq, &c);
            assert_eq!(roll.shift_x_m, c.creepage_long * dq);
            assert_eq!(roll.rotation_rad, c.spin_per_m * dq);
            let step = if rolls {
                roll
            } else {
                ShiftStep {
                    rolling_m: 0.0,
                    ..roll
                }
            };
            p.kinematics = Kinematics::Transient(vec![step]);
            solve_last(&mut ContactSolver::new(&p, &cache), &p)
        };
        // One element: nothing to carry from rest, the same solve, the
        // same bits.
        let dx = rolling(1.0, 1.0).grid.dx_m;
        let (a, b) = (solve_step(dx, false), solve_step(dx, true));
        assert_eq!(format!("{:?}", a.totals), format!("{:?}", b.totals));
        assert_eq!(a.fields, b.fields);
        // Two elements: the last element before each row's leading edge
        // was in contact for half the step and takes half the shift
        // (CONTACT's leading-edge correction), less force than the shift.
        let (a, b) = (solve_step(2.0 * dx, false), solve_step(2.0 * dx, true));
        assert!(
            b.totals.fx_n.abs() < a.totals.fx_n.abs(),
            "{:?} {:?}",
            a.totals,
            b.totals
        );
    }

    #[test]
    fn transient_rolling_tends_to_steady_rolling() {
        // Steps of one element, dq = dx: when the tractions stop changing,
        // the slip w + (u(x) - u(x + dx))/dx is the steady solver's
        // discrete slip, so the limit is the steady solution itself (to the
        // solvers' tolerances, 1e-7 of max mu p_n).
        let cache = KernelCache::default();
        let steady_problem = rolling(1.0, 1.0);
        let steady = solve_last(
            &mut ContactSolver::new(&steady_problem, &cache),
            &steady_problem,
        );
        let c = base_creepages();
        let mut p = steady_problem.clone();
        let step = ShiftStep::rolling(p.load, p.grid.dx_m, &c);
        // The patch is 32 / 2.4 x 2 = 27 elements long: six crossings. The
        // distance to the steady forces shrinks by about 7 % per step here
        // (0.56 of mu Fn after the first step, 1e-3 after 80).
        p.kinematics = Kinematics::Transient(vec![step; 160]);
        let sols = ContactSolver::new(&p, &cache).solve(&p).unwrap();
        let fmax = 0.3 * steady.totals.normal_force_n;
        let gap = |s: &ContactSolution| {
            (s.totals.fx_n - steady.totals.fx_n)
                .abs()
                .max((s.totals.fy_n - steady.totals.fy_n).abs())
                / fmax
        };
        // From rest the first step is far from it (a shift of dx w) ...
        assert!(gap(&sols[0]) > 0.1, "{}", gap(&sols[0]));
        let last = sols.last().unwrap();
        assert_eq!(last.info.status, SolveStatus::Converged);
        assert!(gap(last) < 1e-5, "{:e}", gap(last));
        let d_mz = (last.totals.mz_nm - steady.totals.mz_nm).abs();
        assert!(d_mz < 1e-4 * steady.totals.mz_nm.abs(), "{d_mz:e}");
        // ... and the adhesion and slip areas are the steady ones.
        assert_eq!(last.fields.state, steady.fields.state);
    }

    /// [`rolling`] with an elasto-plastic layer: 10 um of G3 = 1 GPa
    /// (F = 1e-14 m/Pa, about three times an element's own compliance),
    /// yield limit 50 MPa (a third of mu p_n at the centre) hardening by
    /// 1e13 Pa/m.
    fn rolling_on_a_layer() -> ContactProblem {
        let mut p = rolling(1.0, 1.0);
        p.settings.interfacial_layer = Some(InterfacialLayer {
            thickness_m: 10e-6,
            shear_modulus_pa: 1e9,
            yield_limit_pa: 50e6,
            hardening_pa_per_m: 1e13,
        });
        p
    }

    #[test]
    fn transient_rolling_on_a_plastic_layer_tends_to_its_steady_state() {
        // As without a layer (above): steps of dq = dx carry the tractions
        // and the material's yield limit and plastic deformation upstream;
        // once they stop changing, the step is the steady problem, whose
        // material enters fresh at the leading edge and hardens along each
        // row.
        let cache = KernelCache::default();
        let steady_problem = rolling_on_a_layer();
        let mut solver = ContactSolver::new(&steady_problem, &cache);
        let steady = solve_last(&mut solver, &steady_problem);
        let steady_layer = solver.layer_fields().expect("a plastic layer");
        let flowing = steady_layer.plastic.iter().filter(|&&f| f).count();
        let hardened = steady_layer
            .yield_limit_pa
            .iter()
            .filter(|&&t| t > 50e6)
            .count();
        assert!(flowing > 0 && hardened > flowing, "{flowing} {hardened}");
        let mut p = steady_problem.clone();
        let step = ShiftStep::rolling(p.load, p.grid.dx_m, &base_creepages());
        p.kinematics = Kinematics::Transient(vec![step; 160]);
        let mut transient = ContactSolver::new(&p, &cache);
        let last = transient.solve(&p).unwrap().pop().unwrap();
        let layer = transient.layer_fields().expect("a plastic layer");
        assert_eq!(last.info.status, SolveStatus::Converged);
        let fmax = 0.3 * steady.totals.normal_force_n;
        let gap = (last.totals.fx_n - steady.totals.fx_n)
            .abs()
            .max((last.totals.fy_n - steady.totals.fy_n).abs())
            / fmax;
        let tau_gap = layer
            .yield_limit_pa
            .iter()
            .zip(&steady_layer.yield_limit_pa)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
            / 50e6;
        let u_max = steady_layer
            .plastic_x_m
            .iter()
            .chain(&steady_layer.plastic_y_m)
            .fold(0.0f64, |m, u| m.max(u.abs()));
        let u_gap = layer
            .plastic_x_m
            .iter()
            .zip(&steady_layer.plastic_x_m)
            .chain(layer.plastic_y_m.iter().zip(&steady_layer.plastic_y_m))
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
            / u_max;
        eprintln!(
            "forces {gap:e} of mu Fn, yield limits {tau_gap:e} of tau_c0, plastic deformation \
             {u_gap:e} of its largest ({u_max:e} m); {flowing} elements flowing, {hardened} \
             hardened"
        );
        // Measured after 160 steps: 2.5e-7, 4.7e-7 and 8.7e-7 (331
        // elements flowing, 511 hardened); the bounds' iteration stops at
        // ten times the tangential tolerance.
        assert!(gap < 1e-5, "{gap:e}");
        assert!(tau_gap < 1e-5, "{tau_gap:e}");
        assert!(u_gap < 1e-5, "{u_gap:e}");
        assert_eq!(layer.plastic, steady_layer.plastic);
        assert_eq!(last.fields.state, steady.fields.state);
    }

    #[test]
    fn a_layer_without_thickness_or_yield_limit_is_no_layer() {
        // h = 0 adds no flexibility (the plain kernels) and tau_c0 = 0 no
        // plasticity: the bits of the problem without a layer; a layer
        // of some thickness softens the tangential problem.
        let cache = KernelCache::default();
        let plain = rolling(1.0, 1.0);
        let mut none = plain.clone();
        none.settings.interfacial_layer = Some(InterfacialLayer::elastic(0.0, 1e9));
        let a = solve_last(&mut ContactSolver::new(&plain, &cache), &plain);
        let b = solve_last(&mut ContactSolver::new(&none, &cache), &none);
        assert_eq!(format!("{:?}", a.totals), format!("{:?}", b.totals));
        assert_eq!(a.fields, b.fields);
        let mut soft = plain.clone();
        soft.settings.interfacial_layer = Some(InterfacialLayer::elastic(10e-6, 1e9));
        let c = solve_last(&mut ContactSolver::new(&soft, &cache), &soft);
        // The normal problem does not see the layer (identical bodies: no
        // coupling), the tangential one is softer.
        assert_eq!(c.fields.pressure_pa, a.fields.pressure_pa);
        assert!(c.totals.fx_n.abs() < a.totals.fx_n.abs());
    }

    #[test]
    fn a_restored_state_carries_the_plastic_layers_history() {
        // Two shift steps on the layer; the second again after restoring
        // the state saved between them: the same bits, tractions and the
        // layer's state.
        let cache = KernelCache::default();
        let mut p = rolling_on_a_layer();
        let c = base_creepages();
        let step = ShiftStep::rolling(p.load, 4.0 * p.grid.dx_m, &c);
        let shift = ShiftStep {
            rolling_m: 0.0,
            ..step
        };
        p.kinematics = Kinematics::Transient(vec![shift]);
        let mut s = ContactSolver::new(&p, &cache);
        s.solve_next_step(&p, &shift).unwrap();
        let mut saved = SolverState::default();
        s.save_state(&mut saved);
        assert_eq!(saved.bytes(), s.state_bytes());
        let a = s.solve_next_step(&p, &step).unwrap();
        let a_layer = s.layer_fields().unwrap();
        assert!(a_layer.plastic_x_m.iter().any(|&u| u != 0.0));
        // Another step in between, then back.
        s.solve_next_step(&p, &shift).unwrap();
        s.restore_state(&saved).unwrap();
        let b = s.solve_next_step(&p, &step).unwrap();
        assert_eq!(format!("{:?}", a.totals), format!("{:?}", b.totals));
        assert_eq!(a.fields, b.fields);
        assert_eq!(s.layer_fields().unwrap(), a_layer);
    }

    /// Coulomb's law with static and kinetic coefficients checked element
    /// by element: every traction within mu_static p_n, every slipping one
    /// on mu_kinetic p_n opposite to its slip. Returns the adhesion and slip
    /// counts and the adhesion elements whose traction is above
    /// mu_kinetic p_n (those only the static coefficient allows).
    fn check_static_kinetic(s: &ContactSolution, mus: f64, muk: f64) -> [usize; 3] {
        let f = &s.fields;
        let mut counts = [0; 3];
        for i in 0..f.pressure_pa.len() {
            let (pn, m) = (
                f.pressure_pa[i],
                f.traction_x_pa[i].hypot(f.traction_y_pa[i]),
            );
            assert!(
                m <= mus * pn * (1.0 + 1e-12),
                "element {i}: |p| {m} > mu_s p_n"
            );
            match f.state[i] {
                ElementState::Slip => {
                    counts[1] += 1;
                    assert!(
                        (m - muk * pn).abs() <= 1e-9 * muk * pn,
                        "element {i} off mu_k p_n"
                    );
                    let s = f.slip_x[i].hypot(f.slip_y[i]);
                    let cos = (f.traction_x_pa[i] * f.slip_x[i] + f.traction_y_pa[i] * f.slip_y[i])
                        / (m * s);
                    assert!(cos < -1.0 + 1e-6, "element {i}: traction not opposite slip");
                }
                ElementState::Adhesion => {
                    counts[0] += 1;
                    counts[2] += usize::from(m > muk * pn * (1.0 + 1e-6));
                }
                ElementState::Exterior => assert_eq!(pn, 0.0),
            }
        }
        counts
    }

    #[test]
    fn static_and_kinetic_coefficients_bound_adhesion_and_slip_whatever_the_start() {
        // Static 0.35, kinetic 0.1 (issue 45: bounds that followed each
        // Newton iterate's upstream states flipped elements between the
        // two, and the solve ran its 2000 iterations). Every element in slip
        // is on the kinetic bound; adhesion goes beyond it, up to the
        // static one. The kinetic set only grows from empty, so the answer
        // is the same from a cold start and from another solution's
        // tractions (to the tolerance).
        let cache = KernelCache::default();
        let mut p = rolling(1.0, 0.4);
        p.friction = Friction::static_kinetic(0.35, 0.1);
        let cold = solve_last(&mut ContactSolver::new(&p, &cache), &p);
        assert_eq!(cold.info.status, SolveStatus::Converged, "{:?}", cold.info);
        let [nadh, nslip, above] = check_static_kinetic(&cold, 0.35, 0.1);
        assert!(
            nadh > 20 && nslip > 20 && above > 10,
            "{nadh} {nslip} {above}"
        );
        let mut warm = ContactSolver::new(&p, &cache);
        let mut other = p.clone();
        other.kinematics = rolling(1.0, 1.5).kinematics;
        solve_last(&mut warm, &other);
        let again = solve_last(&mut warm, &p);
        assert_eq!(again.info.status, SolveStatus::Converged);
        assert_eq!(again.fields.state, cold.fields.state);
        let fmax = 0.35 * cold.totals.normal_force_n;
        for (a, b) in [
            (again.totals.fx_n, cold.totals.fx_n),
            (again.totals.fy_n, cold.totals.fy_n),
        ] {
            assert!((a - b).abs() < 1e-6 * fmax, "{a} against {b}");
        }
        // In full slip the kinetic coefficient bounds every element,
        // whatever the static one.
        let mut full = p.clone();
        full.kinematics = Kinematics::SteadyRolling(Creepages {
            creepage_long: 5e-3,
            creepage_lat: 2e-3,
            spin_per_m: 0.0,
        });
        let s = solve_last(&mut ContactSolver::new(&full, &cache), &full);
        assert_eq!(s.info.status, SolveStatus::Converged);
        assert_eq!(check_static_kinetic(&s, 0.35, 0.1)[0], 0);
        let f = s.totals.fx_n.hypot(s.totals.fy_n);
        assert!(f < 0.1 * s.totals.normal_force_n, "{f}");
    }

    #[test]
    fn static_and_kinetic_passes_end_on_the_iteration_limit_with_its_status() {
        // The passes share the tangential iteration limit: a limit below
        // what they need ends the solve on it, reported as such, without
        // running further.
        let cache = KernelCache::default();
        let mut p = rolling(1.0, 0.4);
        p.friction = Friction::static_kinetic(0.35, 0.1);
        let whole = solve_last(&mut ContactSolver::new(&p, &cache), &p);
        let need = whole.info.tangential_iterations;
        assert_eq!(whole.info.status, SolveStatus::Converged);
        for limit in [need / 2, need - 1] {
            p.settings.tangential.max_iterations = limit;
            let s = solve_last(&mut ContactSolver::new(&p, &cache), &p);
            assert_eq!(s.info.status, SolveStatus::MaxIterations, "{limit}");
            assert_eq!(s.info.limit, Some(IterationLimit::Tangential));
            assert!(s.info.tangential_iterations <= limit, "{:?}", s.info);
        }
    }

    #[test]
    fn transient_rolling_steps_bound_slip_by_the_kinetic_coefficient() {
        // The same rule in every transient step: the steps' slip on mu_k
        // p_n, adhesion within mu_s p_n, from rest over three crossings.
        let cache = KernelCache::default();
        let mut p = rolling(1.0, 0.4);
        p.friction = Friction::static_kinetic(0.35, 0.1);
        let c = match p.kinematics {
            Kinematics::SteadyRolling(c) => c,
            _ => unreachable!(),
        };
        p.kinematics = Kinematics::Transient(vec![ShiftStep::rolling(p.load, p.grid.dx_m, &c); 80]);
        let sols = ContactSolver::new(&p, &cache).solve(&p).unwrap();
        let mut above = 0;
        for s in &sols {
            assert_eq!(s.info.status, SolveStatus::Converged, "{:?}", s.info);
            above += check_static_kinetic(s, 0.35, 0.1)[2];
        }
        let [_, nslip, _] = check_static_kinetic(sols.last().unwrap(), 0.35, 0.1);
        assert!(nslip > 20 && above > 0, "{nslip} {above}");
    }

    #[test]
    fn a_rolling_distance_of_a_fraction_of_an_element_is_refused_naming_it() {
        let mut p = rolling(1.0, 1.0);
        let step = ShiftStep::rolling(p.load, 1.5 * p.grid.dx_m, &base_creepages());
        p.kinematics = Kinematics::Transient(vec![step]);
        match p.validate() {
            Err(ContactError::InvalidInput { key, .. }) => {
                assert_eq!(key, "transient.steps[0].rolling_m")
            }
            other => panic!("{other:?}"),
        }
        let mut s = ContactSolver::new(&p, &KernelCache::default());
        p.kinematics = Kinematics::Transient(vec![ShiftStep {
            rolling_m: 0.0,
            ..step
        }]);
        assert!(s.solve_next_step(&p, &step).is_err());
    }

    #[test]
    fn a_path_of_inputs_predicts_the_warm_start() {
        let cache = KernelCache::default();
        let mut s = ContactSolver::new(&rolling(1.0, 1.0), &cache);
        // Steps of 1 % in load and 2 % in creepage, as consecutive time steps.
        for k in 0..4 {
            let k = f64::from(k);
            solve_last(&mut s, &rolling(1.0 + 0.01 * k, 1.0 + 0.02 * k));
        }
        let next = rolling(1.04, 1.08);
        // The same state without the path: the plain warm start.
        let mut plain = s.clone();
        plain.path.clear();
        let a = solve_last(&mut s, &next);
        let b = solve_last(&mut plain, &next);
        assert!(
            a.info.matvecs < b.info.matvecs,
            "predicted {} products, plain warm start {}",
            a.info.matvecs,
            b.info.matvecs
        );
        // Both meet the tolerance: the same forces within it.
        let (ta, tb) = (a.totals, b.totals);
        let fmax = 0.3 * ta.normal_force_n;
        for (x, y) in [(ta.fx_n, tb.fx_n), (ta.fy_n, tb.fy_n)] {
            assert!((x - y).abs() < 1e-5 * fmax, "{x} against {y}");
        }
        // Back to the input before last: its own solution is the start.
        let c = solve_last(&mut s, &rolling(1.03, 1.06));
        assert!(
            c.info.tangential_iterations <= 1 && c.info.matvecs < a.info.matvecs / 2,
            "{:?}",
            c.info
        );
        // Another geometry is another path: no prediction, and a reset
        // forgets it.
        s.reset();
        assert_eq!(
            s.path
                .predict(&PathPoint::of(&next), [&mut [], &mut [], &mut []]),
            0.0
        );
    }
}
