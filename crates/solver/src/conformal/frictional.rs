//! Frictional conformal contact: static compression in load steps and
//! steady-state rolling, with the normal and tangential problems coupled
//! as conformal contact requires even for identical materials (paper §3.2):
//!
//! * through the influence coefficients: lateral tractions displace along
//!   the normal (B_ns) and pressures displace tangentially (B_sn, B_xn) once
//!   the coefficients are combined by orientation (Blanco model);
//! * through equilibrium: the load along the approach direction n(0) is
//!   carried by the pressures (weight cos(delta - delta0)) and by the
//!   lateral tractions (weight sin(delta - delta0));
//! * through kinematics: in a load step the approach increment dd is a
//!   rigid displacement of the wheel along n(0), which the curved surface
//!   sees as a normal closure dd cos(delta - delta0) and a tangential shift
//!   -dd sin(delta - delta0) of the rail relative to the wheel.
//!
//! The two problems alternate (Panagiotopoulos process) until the
//! tractions' estimated distance to the coupled solution is below the
//! coupling tolerance ([`CouplingMonitor`]). The tangential problem is
//! solved by the Newton/GMRES Coulomb solver of the core
//! ([`crate::core::steady::solve_coulomb_newton`]) on the conformal operator,
//! at most `NEWTON_STEPS_PER_ALTERNATION` (2) Newton steps per alternation;
//! the inner tolerances tighten with the alternation's progress and the
//! answer comes from an alternation whose inner solves met the final
//! tolerances. The coupling products take only the components they need
//! ([`ConformalOperator::apply_parts`]).
//!
//! Tractions are those on body 1 (the rail) in each element's local frame
//! (x, s, n); slips are those of the rail relative to the wheel.

use std::sync::Arc;

use crate::conformal::geometry::{
    midplane_rail_weight, ConformalCreepages, ConformalGeometry, RigidSlipSurface,
};
use crate::conformal::operator::{ConformalOperator, InfluenceModel, Tractions};
use crate::conformal::solve::border_error;
use crate::core::cache::KernelCache;
use crate::core::cancel;
use crate::core::coupling::CouplingMonitor;
use crate::core::error::ContactError;
use crate::core::fft::Precision;
use crate::core::influence::Component;
use crate::core::influence::KernelKind;
use crate::core::material::CombinedMaterial;
use crate::core::memory::{heap_bytes, HeapBytes};
use crate::core::normal::{solve_normal_with, NormalLoad, NormalScratch, NormalSettings};
use crate::core::solution::{ElementState, SolveStatus};
use crate::core::steady::{solve_coulomb_newton, LocalModel, SteadyScratch, TangentialOperator};
use crate::core::tangential::{
    FrictionBounds, TangentialInput, TangentialOutput, TangentialSettings,
};

/// Newton steps of the tangential problem per alternation. The pressures
/// move after each tangential solve (by about 4 % of their largest value
/// after the first one in the paper's Case 1 at 80 kN, then by a few
/// hundredths of that per alternation), so converging the tangential
/// problem against pressures that are about to change wastes products; two
/// steps per alternation, each warm-started from the last, keep the
/// tangential and the coupling iterations in step. Measured on Case 1 at
/// 80 kN, 60 x 60 (benches/README.md): unlimited 8 alternations and 105
/// tangential products; one step 10 alternations; two steps 7 alternations
/// and 71 products; three 8 alternations.
const NEWTON_STEPS_PER_ALTERNATION: usize = 2;

/// What happens to the contact.
#[derive(Debug, Clone, PartialEq)]
pub enum ConformalKinematics {
    /// Static compression with friction: the force along n(0) rises through
    /// these values \[N\] (monotonic loading), with no tangential shift.
    StaticCompression(Vec<f64>),
    /// Steady-state rolling at this force \[N\] and these creepages.
    SteadyRolling {
        /// Force along n(0) \[N\].
        normal_force_n: f64,
        /// Creepages at the rigid contact point.
        creepages: ConformalCreepages,
    },
}

/// Solver settings of a frictional conformal solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConformalSettings {
    /// Normal solver.
    pub normal: NormalSettings,
    /// Tangential solver.
    pub tangential: TangentialSettings,
    /// Ends the alternation when the tractions' estimated distance to the
    /// coupled solution (the last change, relative to the pressures' L1
    /// norm, times q/(1 - q) with q the contraction per alternation; see
    /// [`CouplingMonitor`]) is below it (default 1e-8).
    pub coupling_tolerance: f64,
    /// Alternation limit (default 50).
    pub coupling_max_iterations: usize,
    /// Where steady rolling takes the rigid velocities (default
    /// [`RigidSlipSurface::ActualSurface`]).
    pub rigid_slip: RigidSlipSurface,
}

impl Default for ConformalSettings {
    fn default() -> Self {
        Self {
            normal: NormalSettings::default(),
            tangential: TangentialSettings::default(),
            coupling_tolerance: 1e-8,
            coupling_max_iterations: 50,
            rigid_slip: RigidSlipSurface::default(),
        }
    }
}

/// Totals of one frictional conformal solution.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize)]
pub struct ConformalTotals {
    /// Force on the rail along the approach direction n(0) \[N\] (pressures
    /// and lateral tractions).
    pub normal_force_n: f64,
    /// Part of it carried by the lateral tractions \[N\].
    pub normal_force_from_tractions_n: f64,
    /// Resultant of the pressures alone along n(0) \[N\].
    pub pressure_resultant_n: f64,
    /// Longitudinal force on the rail \[N\].
    pub fx_n: f64,
    /// Lateral force on the rail along t(0) \[N\].
    pub fs_n: f64,
    /// Force on the rail in the global frame: y (lateral) and z (down) \[N\].
    pub fy_global_n: f64,
    /// See `fy_global_n`.
    pub fz_global_n: f64,
    /// Approach along n(0) \[m\].
    pub approach_m: f64,
    /// Largest pressure \[Pa\].
    pub max_pressure_pa: f64,
    /// Largest tangential traction \[Pa\].
    pub max_traction_pa: f64,
    /// Loaded area (curvilinear) \[m²\].
    pub contact_area_m2: f64,
    /// Extent along x \[m\].
    pub patch_length_m: f64,
    /// Extent along s \[m\].
    pub patch_width_m: f64,
    /// Total contact angle variation \[deg\].
    pub contact_angle_variation_deg: f64,
    /// Share of loaded elements in adhesion [-].
    pub adhesion_fraction: f64,
    /// Frictional power per unit rolling speed, sum of -p_t.s dA \[N\]
    /// (steady rolling).
    pub tgamma_n: f64,
}

/// One frictional conformal solution.
#[derive(Debug, Clone, PartialEq)]
pub struct ConformalSolution {
    /// Totals.
    pub totals: ConformalTotals,
    /// Pressure \[Pa\], longitudinal and lateral traction \[Pa\] per element.
    pub pressure_pa: Vec<f64>,
    /// See `pressure_pa`.
    pub traction_x_pa: Vec<f64>,
    /// See `pressure_pa`.
    pub traction_s_pa: Vec<f64>,
    /// Slip of the rail relative to the wheel (steady: per rolling speed;
    /// static: displacement in the step \[m\]), x and s.
    pub slip_x: Vec<f64>,
    /// See `slip_x`.
    pub slip_s: Vec<f64>,
    /// Element states.
    pub state: Vec<ElementState>,
    /// Frictional work per unit area of rail after one wheel passage,
    /// W_fric(s) = sum over the line of -p_t.s dx [J/m²], per lateral line
    /// (steady rolling; zeros for static compression).
    pub wfric_lateral_j_per_m2: Vec<f64>,
    /// Alternations, Newton steps and FFT products used; status.
    pub coupling_iterations: usize,
    /// See `coupling_iterations`.
    pub tangential_iterations: usize,
    /// See `coupling_iterations`.
    pub status: SolveStatus,
}

/// Buffers of frictional conformal solves, kept from one solve to the next
/// by [`solve_frictional`]: a solve on a grid of the size of the last
/// one allocates nothing but its answer (a fresh 60 x 60 solve spends
/// about 4 % of its time allocating and first touching its buffers, the
/// GMRES basis above all).
#[derive(Default)]
pub struct FrictionalWorkspace {
    a_op: Option<ConformalOperator>,
    b_op: Option<ConformalOperator>,
    fields: Option<Fields>,
}

/// A clone is an empty workspace: it holds buffers, no state (answers do
/// not depend on it), so a copy of its contents would only cost memory.
impl Clone for FrictionalWorkspace {
    fn clone(&self) -> Self {
        Self::default()
    }
}

/// The buffers of the last solve (operators, fields, normal and Newton
/// scratch); not the kernels, which its operators share with the cache.
impl HeapBytes for FrictionalWorkspace {
    fn heap_bytes(&self) -> usize {
        let f = self.fields.as_ref().map_or(0, |f| {
            heap_bytes!(
                f.pn,
                f.px,
                f.ps,
                f.sx,
                f.ss,
                f.h_eff,
                f.cx,
                f.cs,
                f.old_ux,
                f.old_us,
                f.last_pn,
                f.last_px,
                f.last_ps,
                f.wx,
                f.ws,
                f.v,
                f.state,
                f.prev_state,
                f.normal,
                f.steady
            )
        });
        f + heap_bytes!(self.a_op, self.b_op)
    }
}

/// The per-element arrays of a solve.
struct Fields {
    pn: Vec<f64>,
    px: Vec<f64>,
    ps: Vec<f64>,
    sx: Vec<f64>,
    ss: Vec<f64>,
    h_eff: Vec<f64>,
    cx: Vec<f64>,
    cs: Vec<f64>,
    old_ux: Vec<f64>,
    old_us: Vec<f64>,
    last_pn: Vec<f64>,
    last_px: Vec<f64>,
    last_ps: Vec<f64>,
    wx: Vec<f64>,
    ws: Vec<f64>,
    v: Vec<f64>,
    state: Vec<ElementState>,
    prev_state: Vec<ElementState>,
    normal: NormalScratch,
    steady: SteadyScratch,
}

impl Fields {
    /// Zeroed arrays for `n` elements: the kept ones when they have that
    /// size, new ones otherwise.
    fn for_grid(kept: Option<Fields>, n: usize) -> Self {
        let Some(mut f) = kept.filter(|f| f.pn.len() == n) else {
            let z = || vec![0.0; n];
            return Self {
                pn: z(),
                px: z(),
                ps: z(),
                sx: z(),
                ss: z(),
                h_eff: z(),
                cx: z(),
                cs: z(),
                old_ux: z(),
                old_us: z(),
                last_pn: z(),
                last_px: z(),
                last_ps: z(),
                wx: z(),
                ws: z(),
                v: z(),
                state: vec![ElementState::Exterior; n],
                prev_state: vec![ElementState::Exterior; n],
                normal: NormalScratch::new(n),
                steady: SteadyScratch::new(n),
            };
        };
        for a in [
            &mut f.pn,
            &mut f.px,
            &mut f.ps,
            &mut f.sx,
            &mut f.ss,
            &mut f.h_eff,
            &mut f.cx,
            &mut f.cs,
            &mut f.old_ux,
            &mut f.old_us,
            &mut f.last_pn,
            &mut f.last_px,
            &mut f.last_ps,
            &mut f.wx,
            &mut f.ws,
            &mut f.v,
        ] {
            a.fill(0.0);
        }
        f.state.fill(ElementState::Exterior);
        f.prev_state.fill(ElementState::Exterior);
        f
    }
}

/// Solves a frictional conformal problem: one solution per load step of a
/// static compression, one for steady rolling, on the buffers of
/// `workspace` (the same answer, bit for bit, whatever it held; pass
/// `&mut FrictionalWorkspace::default()` for a single solve).
#[allow(clippy::too_many_arguments)]
pub fn solve_frictional(
    workspace: &mut FrictionalWorkspace,
    geometry: &ConformalGeometry,
    material: &CombinedMaterial,
    friction_coefficient: f64,
    model: InfluenceModel,
    kinematics: &ConformalKinematics,
    settings: &ConformalSettings,
    cache: &KernelCache,
) -> Result<Vec<ConformalSolution>, ContactError> {
    if !(friction_coefficient.is_finite() && friction_coefficient >= 0.0) {
        return Err(ContactError::invalid(
            "friction.coefficient",
            format!("must be finite and >= 0, got {friction_coefficient}"),
        ));
    }
    let grid = geometry.grid;
    let n = grid.len();
    let disp: Arc<_> = cache.get(&grid, material, KernelKind::Displacement);
    let g_mod = disp.influence.shear_modulus_pa();
    let nu = disp.influence.poisson_ratio();
    let mut a_op =
        ConformalOperator::reusing(workspace.a_op.take(), disp, model, &geometry.delta_rad);
    let steady = matches!(kinematics, ConformalKinematics::SteadyRolling { .. });
    let mut b_op = steady.then(|| {
        ConformalOperator::reusing(
            workspace.b_op.take(),
            cache.get_sharing_inverse(&grid, material, KernelKind::SteadyRolling, a_op.kernels()),
            model,
            &geometry.delta_rad,
        )
    });
    let mut fields = Fields::for_grid(workspace.fields.take(), n);
    let Fields {
        pn,
        px,
        ps,
        sx,
        ss,
        h_eff,
        cx,
        cs,
        old_ux,
        old_us,
        last_pn,
        last_px,
        last_ps,
        wx,
        ws,
        v,
        state,
        prev_state,
        normal: normal_scratch,
        steady: steady_scratch,
    } = &mut fields;
    let d0 = geometry.mean_contact_angle_rad;
    // Equilibrium weight of the lateral tractions along n(0).
    for (i, v) in v.iter_mut().enumerate() {
        *v = (geometry.delta_rad[i / grid.nx] - d0).sin();
    }
    let w = &geometry.approach_weight;
    let area = grid.element_area_m2();
    // Every normal solve here uses `a_op`: the next alternation's solve
    // starts from the kept pressures' product (none kept from the
    // workspace's last solve).
    normal_scratch.keep_product();
    let friction = FrictionBounds {
        static_coefficient: friction_coefficient,
        kinetic_coefficient: friction_coefficient,
    };
    let steps: Vec<(f64, Option<ConformalCreepages>)> = match kinematics {
        ConformalKinematics::StaticCompression(loads) => {
            if loads.is_empty() {
                return Err(ContactError::invalid(
                    "static_compression.loads",
                    "needs at least one load",
                ));
            }
            loads.iter().map(|&f| (f, None)).collect()
        }
        ConformalKinematics::SteadyRolling {
            normal_force_n,
            creepages,
        } => vec![(*normal_force_n, Some(*creepages))],
    };
    let mut out = Vec::with_capacity(steps.len());
    // Approach of the previous load step (static compression starts unloaded).
    let mut prev_approach = 0.0;
    let rail_weight = midplane_rail_weight(material);
    for (k, &(force, creep)) in steps.iter().enumerate() {
        crate::core::error::require_positive("load.normal_force_n", force)?;
        if let Some(c) = &creep {
            // On the reference section the rigid slip is the step's; on the
            // actual surfaces it moves with the approach (below).
            if settings.rigid_slip == RigidSlipSurface::ReferenceSection {
                geometry.rigid_slip(c, settings.rigid_slip, 0.0, rail_weight, wx, ws);
            }
        } else if k > 0 {
            // Displacement difference of the previous step's tractions.
            a_op.apply_parts(
                Precision::Double,
                Tractions {
                    x: Some(px),
                    s: Some(ps),
                    n: Some(pn),
                },
                &mut [(Component::X, old_ux), (Component::Y, old_us)],
            );
        }
        prev_state.copy_from_slice(state);
        // Converged only when the alternation ends with tight inner solves
        // that met their tolerances.
        let mut status = SolveStatus::MaxIterations;
        let mut coupling = 0;
        let mut newton_steps = 0;
        let mut approach = 0.0;
        // Inner tolerances follow the alternation's progress: loose while
        // the tractions still change a lot, the settings' at the end. They
        // are set from the change this alternation is expected to make
        // (the last change times the last ratio of successive changes: the
        // alternation converges linearly, by a factor of 0.01 to 0.06 per
        // alternation on the paper's cases), so that the alternation that
        // meets the coupling tolerance already runs at the final inner
        // tolerances: one or two alternations fewer than scheduling from
        // the last change, on Cases 1 and 2 from 20 to 162 kN.
        let mut monitor = CouplingMonitor::default();
        for c in 0..settings.coupling_max_iterations.max(1) {
            cancel::check()?;
            coupling = c + 1;
            let expected = monitor.change() * monitor.contraction();
            let normal_settings = NormalSettings {
                tolerance: (1e-3 * expected).clamp(settings.normal.tolerance, 1e-6),
                ..settings.normal
            };
            let tangential_settings = TangentialSettings {
                tolerance: (0.1 * expected).clamp(settings.tangential.tolerance, 1e-3),
                max_iterations: settings
                    .tangential
                    .max_iterations
                    .min(NEWTON_STEPS_PER_ALTERNATION),
                ..settings.tangential
            };
            let inner_final = normal_settings.tolerance == settings.normal.tolerance
                && tangential_settings.tolerance == settings.tangential.tolerance;
            last_pn.copy_from_slice(pn);
            last_px.copy_from_slice(px);
            last_ps.copy_from_slice(ps);
            // Normal problem: gap with the normal displacement of the
            // tangential tractions, load less the tractions' share.
            a_op.apply_parts(
                Precision::Double,
                Tractions {
                    x: Some(px),
                    s: Some(ps),
                    n: None,
                },
                &mut [(Component::N, h_eff)],
            );
            let mut carried = 0.0;
            for i in 0..n {
                h_eff[i] += geometry.gap_m[i];
                carried += v[i] * ps[i] * area;
            }
            let target = force - carried;
            if target <= 0.0 {
                return Err(ContactError::NoContact {
                    detail: format!(
                        "the lateral tractions carry {carried:.4e} N of the {force:.4e} N load"
                    ),
                });
            }
            let no = solve_normal_with(
                &mut a_op,
                h_eff,
                Some(w),
                area,
                NormalLoad::NormalForce(target),
                pn,
                normal_scratch,
                &normal_settings,
            );
            let mut inner_ok = no.converged;
            approach = no.approach_m;
            if let (Some(c), RigidSlipSurface::ActualSurface) = (&creep, settings.rigid_slip) {
                // The wheel's points on the elements' normals move with the
                // approach.
                geometry.rigid_slip(c, settings.rigid_slip, approach, rail_weight, wx, ws);
            }
            // Tangential problem: fixed slip from the pressures (and, for a
            // static step, minus the previous displacements).
            // The pressures' tangential displacements, through the operator
            // of the tangential problem (steady-rolling kernels or not).
            b_op.as_mut().unwrap_or(&mut a_op).apply_parts(
                Precision::Double,
                Tractions {
                    n: Some(pn),
                    ..Tractions::default()
                },
                &mut [(Component::X, cx), (Component::Y, cs)],
            );
            let (op, local, start): (&mut dyn TangentialOperator, _, _) =
                if let Some(b) = b_op.as_mut() {
                    for i in 0..n {
                        cx[i] += wx[i];
                        cs[i] += ws[i];
                    }
                    (b, LocalModel::Upwind, Some([g_mod, nu]))
                } else {
                    // The rigid approach increment moves the wheel along
                    // n(0): the rail shifts by -dd n(0) relative to it,
                    // which has the component -dd sin(delta - delta0) along t(s).
                    let dd = approach - prev_approach;
                    for i in 0..n {
                        cx[i] -= old_ux[i];
                        cs[i] -= old_us[i] + dd * v[i];
                    }
                    (&mut a_op, LocalModel::Diagonal, None)
                };
            let input = TangentialInput {
                grid: &grid,
                pn,
                friction,
                cx,
                cy: cs,
                previous_state: prev_state,
            };
            let outcome = solve_coulomb_newton(
                op,
                local,
                start,
                &input,
                TangentialOutput {
                    px,
                    py: ps,
                    sx,
                    sy: ss,
                    state,
                },
                steady_scratch,
                &tangential_settings,
            );
            newton_steps += outcome.iterations;
            inner_ok &= outcome.converged;
            monitor.record([pn, px, ps], [last_pn, last_px, last_ps]);
            // The Newton solve may stop at its step cap short of its
            // tolerance: the alternation goes on from where it stopped.
            if monitor.converged(settings.coupling_tolerance) && inner_final && inner_ok {
                status = SolveStatus::Converged;
                break;
            }
        }
        prev_approach = approach;
        out.push(finish(
            geometry,
            pn,
            px,
            ps,
            sx,
            ss,
            state,
            v,
            creep.is_some(),
            approach,
            coupling,
            newton_steps,
            status,
        )?);
    }
    workspace.a_op = Some(a_op);
    if b_op.is_some() {
        workspace.b_op = b_op;
    }
    workspace.fields = Some(fields);
    Ok(out)
}

#[allow(clippy::too_many_arguments)]
fn finish(
    geometry: &ConformalGeometry,
    pn: &[f64],
    px: &[f64],
    ps: &[f64],
    sx: &[f64],
    ss: &[f64],
    state: &[ElementState],
    v: &[f64],
    steady: bool,
    approach_m: f64,
    coupling_iterations: usize,
    tangential_iterations: usize,
    status: SolveStatus,
) -> Result<ConformalSolution, ContactError> {
    // The loops stop early once cancelled: no answer then.
    cancel::check()?;
    let grid = geometry.grid;
    let area = grid.element_area_m2();
    let w = &geometry.approach_weight;
    let mut t = ConformalTotals::default();
    let (mut count, mut adh) = (0usize, 0usize);
    let mut wfric = vec![0.0; grid.ny];
    let d0 = geometry.mean_contact_angle_rad;
    for (iy, wf) in wfric.iter_mut().enumerate() {
        let d = geometry.delta_rad[iy];
        // Local t and n in the global (y, z) plane.
        let (ty, tz) = (d.cos(), d.sin());
        let (ny_, nz_) = (-d.sin(), d.cos());
        for ix in 0..grid.nx {
            let i = grid.index(ix, iy);
            if pn[i] <= 0.0 {
                continue;
            }
            if grid.on_border(ix, iy) {
                return Err(border_error(&grid, ix, iy));
            }
            count += 1;
            if state[i] == ElementState::Adhesion {
                adh += 1;
            }
            t.pressure_resultant_n += w[i] * pn[i] * area;
            t.normal_force_from_tractions_n += v[i] * ps[i] * area;
            t.fx_n += px[i] * area;
            t.fs_n += (ps[i] * (d - d0).cos() - pn[i] * (d - d0).sin()) * area;
            t.fy_global_n += (ps[i] * ty + pn[i] * ny_) * area;
            t.fz_global_n += (ps[i] * tz + pn[i] * nz_) * area;
            t.max_pressure_pa = t.max_pressure_pa.max(pn[i]);
            t.max_traction_pa = t.max_traction_pa.max(px[i].hypot(ps[i]));
            if steady {
                let p = -(px[i] * sx[i] + ps[i] * ss[i]);
                t.tgamma_n += p * area;
                *wf += p * grid.dx_m;
            }
        }
    }
    t.normal_force_n = t.pressure_resultant_n + t.normal_force_from_tractions_n;
    t.approach_m = approach_m;
    if let Some([length, width]) = grid.loaded_extent_m(pn) {
        t.contact_area_m2 = count as f64 * area;
        t.patch_length_m = length;
        t.patch_width_m = width;
        t.adhesion_fraction = adh as f64 / count as f64;
    }
    t.contact_angle_variation_deg = geometry.contact_angle_variation_rad(pn).to_degrees();
    Ok(ConformalSolution {
        totals: t,
        pressure_pa: pn.to_vec(),
        traction_x_pa: px.to_vec(),
        traction_s_pa: ps.to_vec(),
        slip_x: sx.to_vec(),
        slip_s: ss.to_vec(),
        state: state.to_vec(),
        wfric_lateral_j_per_m2: wfric,
        coupling_iterations,
        tangential_iterations,
        status,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::conformal::geometry::Circle;
    use crate::conformal::solve::conformal_hertz;
    use crate::core::grid::Grid;
    use crate::core::material::Material;

    #[test]
    fn a_kept_workspace_gives_the_bits_of_a_fresh_solve() {
        // The paper's Case 1 (R_yr 10 mm, R_yw -10.1 mm, R_xw 0.5 m) at
        // 80 kN, on coarse grids.
        let mat = CombinedMaterial::identical(Material::STEEL).unwrap();
        let cache = KernelCache::default();
        let (rr, rw, rx, f) = (0.010, -0.0101, 0.5, 80e3);
        let (h, _) = conformal_hertz(rr, rw, rx, &mat, f, false).unwrap();
        let geometry = |n: usize| {
            let (wx, ws) = (3.2 * h.semi_axis_x_m, 2.6 * h.semi_axis_y_m);
            let grid = Grid::centered(n, n, wx, ws).unwrap();
            ConformalGeometry::new(&Circle::rail(rr), &Circle::wheel(rw), rx, grid).unwrap()
        };
        let rolling = ConformalKinematics::SteadyRolling {
            normal_force_n: f,
            creepages: ConformalCreepages {
                creepage_long: 0.86e-3,
                ..Default::default()
            },
        };
        let settings = ConformalSettings::default();
        let solve = |ws: &mut FrictionalWorkspace, geo: &ConformalGeometry, k| {
            solve_frictional(
                ws,
                geo,
                &mat,
                0.3,
                InfluenceModel::Blanco,
                k,
                &settings,
                &cache,
            )
            .unwrap()
            .pop()
            .unwrap()
        };
        let geo = geometry(24);
        let fresh = solve(&mut FrictionalWorkspace::default(), &geo, &rolling);
        assert_eq!(fresh.status, SolveStatus::Converged);
        let mut ws = FrictionalWorkspace::default();
        // Another grid and a static compression first, then twice the
        // rolling case (the second on the buffers of the first).
        let other = ConformalKinematics::StaticCompression(vec![0.5 * f, f]);
        solve(&mut ws, &geometry(20), &other);
        for _ in 0..2 {
            let s = solve(&mut ws, &geo, &rolling);
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            for (a, b) in [
                (&s.pressure_pa, &fresh.pressure_pa),
                (&s.traction_x_pa, &fresh.traction_x_pa),
                (&s.traction_s_pa, &fresh.traction_s_pa),
                (&s.slip_x, &fresh.slip_x),
                (&s.slip_s, &fresh.slip_s),
            ] {
                assert_eq!(bits(a), bits(b));
            }
            assert_eq!(s.state, fresh.state);
            assert_eq!(s.totals, fresh.totals);
            assert_eq!(s.coupling_iterations, fresh.coupling_iterations);
        }
    }
}
