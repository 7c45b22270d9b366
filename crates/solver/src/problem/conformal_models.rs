//! The conformal models of `railcontact solve`: `model = "cect"` (Blanco's
//! influence coefficients) and `model = "cect_halfspace"` (half-space
//! coefficients on curvilinear distances) on `geometry.kind =
//! "conformal_circular"` or `"conformal_points"`.
//!
//! Without `[rolling]`/`[transient]` they solve frictionless normal contact,
//! with `[rolling]` steady rolling, with `[transient]` (all shifts zero) a
//! static compression through the steps' forces. Forces act on the rail;
//! `fy_n` is the lateral force along the tangent t(0) at the rigid contact
//! point (the library's `fs_n`).

use std::time::Instant;

use crate::conformal::frictional::{
    solve_frictional, ConformalKinematics, ConformalSolution, ConformalTotals, FrictionalWorkspace,
};
use crate::conformal::geometry::ConformalGeometry;
use crate::conformal::solve::{solve_frictionless, ConformalNormalSolution};
use crate::core::cache::KernelCache;
use crate::core::solution::{ElementState, SolveStatus, Totals};
use crate::problem::case::Case;
use crate::problem::report::{
    ConformalFieldsReport, ConformalKeys, Fields, Report, StepReport, WfricReport,
};
use crate::problem::CaseError;

/// Note added to every conformal report.
const NOTE_NO_SPIN_MOMENT: &str =
    "the conformal models do not compute the spin moment: mz_nm is reported as 0";
/// Note on the meaning of `fy_n`.
const NOTE_FY: &str =
    "fy_n is the lateral force on the rail along the tangent t(0) at the rigid contact point; \
     fy_global_n, fz_global_n are its global components (z down)";

/// The solutions of a conformal case.
pub struct ConformalRun {
    /// Geometry on the (x, s) grid.
    pub geometry: ConformalGeometry,
    /// One solution, or one per static compression step (never empty).
    pub solutions: Vec<ConformalSolution>,
    /// Conjugate-gradient iterations of a frictionless solve (`None` for
    /// the frictional solves, which count alternations and Newton steps).
    normal_iterations: Option<usize>,
    /// Steady rolling (W_fric(s) is reported).
    steady: bool,
    /// Wall time from the validated case to the solutions [s].
    elapsed_s: f64,
}

/// A frictionless solution in the frictional solver's form: zero
/// tractions and slips, loaded elements marked as slipping (as the planar
/// core does).
fn frictionless_solution(
    geometry: &ConformalGeometry,
    s: ConformalNormalSolution,
) -> ConformalSolution {
    let grid = geometry.grid;
    let n = grid.len();
    let area = grid.element_area_m2();
    let d0 = geometry.mean_contact_angle_rad;
    let (mut fs, mut fy, mut fz) = (0.0, 0.0, 0.0);
    for iy in 0..grid.ny {
        let d = geometry.delta_rad[iy];
        for ix in 0..grid.nx {
            let p = s.pressure_pa[grid.index(ix, iy)];
            if p > 0.0 {
                // Pressure on the rail along n(s) = (0, -sin d, cos d).
                fs -= p * (d - d0).sin() * area;
                fy -= p * d.sin() * area;
                fz += p * d.cos() * area;
            }
        }
    }
    let m = &s.summary;
    let totals = ConformalTotals {
        normal_force_n: m.normal_force_n,
        normal_force_from_tractions_n: 0.0,
        pressure_resultant_n: m.normal_force_n,
        fx_n: 0.0,
        fs_n: fs,
        fy_global_n: fy,
        fz_global_n: fz,
        approach_m: m.approach_m,
        max_pressure_pa: m.max_pressure_pa,
        max_traction_pa: 0.0,
        contact_area_m2: m.contact_area_m2,
        patch_length_m: m.patch_length_m,
        patch_width_m: m.patch_width_m,
        contact_angle_variation_deg: m.contact_angle_variation_deg,
        adhesion_fraction: 0.0,
        tgamma_n: 0.0,
    };
    let state = s
        .pressure_pa
        .iter()
        .map(|&p| {
            if p > 0.0 {
                ElementState::Slip
            } else {
                ElementState::Exterior
            }
        })
        .collect();
    ConformalSolution {
        totals,
        pressure_pa: s.pressure_pa,
        traction_x_pa: vec![0.0; n],
        traction_s_pa: vec![0.0; n],
        slip_x: vec![0.0; n],
        slip_s: vec![0.0; n],
        state,
        wfric_lateral_j_per_m2: vec![0.0; grid.ny],
        coupling_iterations: 0,
        tangential_iterations: 0,
        status: if m.converged {
            SolveStatus::Converged
        } else {
            SolveStatus::MaxIterations
        },
    }
}

/// Patch length over width, 0 without a patch.
fn length_width_ratio(length_m: f64, width_m: f64) -> f64 {
    if width_m > 0.0 {
        length_m / width_m
    } else {
        0.0
    }
}

impl ConformalRun {
    /// Solves a `cect` or `cect_halfspace` case on the buffers of
    /// `workspace` (see [`solve_frictional`]).
    pub fn solve(workspace: &mut FrictionalWorkspace, case: &Case) -> Result<Self, CaseError> {
        let t0 = Instant::now();
        let model = case.model.influence().ok_or_else(|| {
            CaseError::Failure(format!(
                "model \"{}\" is not a conformal solver",
                case.model.name()
            ))
        })?;
        let geometry = case.conformal_geometry()?;
        let cache = KernelCache::global();
        let kinematics = case.conformal_kinematics()?;
        let steady = matches!(kinematics, Some(ConformalKinematics::SteadyRolling { .. }));
        let (solutions, normal_iterations) = match kinematics {
            None => {
                let s = solve_frictionless(
                    &geometry,
                    &case.material,
                    model,
                    case.load,
                    &case.settings.normal,
                    cache,
                )?;
                let iterations = s.summary.iterations;
                (vec![frictionless_solution(&geometry, s)], Some(iterations))
            }
            Some(k) => (
                solve_frictional(
                    workspace,
                    &geometry,
                    &case.material,
                    case.friction.kinetic_coefficient,
                    model,
                    &k,
                    &case.conformal_settings(),
                    cache,
                )?,
                None,
            ),
        };
        if solutions.is_empty() {
            return Err(CaseError::Failure("the solver returned no solution".into()));
        }
        Ok(ConformalRun {
            geometry,
            solutions,
            normal_iterations,
            steady,
            elapsed_s: t0.elapsed().as_secs_f64(),
        })
    }

    /// The (last) solution.
    fn last(&self) -> &ConformalSolution {
        &self.solutions[self.solutions.len() - 1]
    }

    /// The report of one solution (`solve_time_s` 0: the steps of a static
    /// compression are solved in one call).
    fn step_report(&self, s: &ConformalSolution) -> StepReport {
        let t = &s.totals;
        let totals = Totals {
            normal_force_n: t.normal_force_n,
            fx_n: t.fx_n,
            fy_n: t.fs_n,
            mz_nm: 0.0,
            approach_m: t.approach_m,
            max_pressure_pa: t.max_pressure_pa,
            max_traction_pa: t.max_traction_pa,
            contact_area_m2: t.contact_area_m2,
            patch_length_m: t.patch_length_m,
            patch_width_m: t.patch_width_m,
            adhesion_fraction: t.adhesion_fraction,
            tgamma_n: t.tgamma_n,
            frictional_work_j: 0.0,
        };
        let (iterations, normal_iterations, tangential_iterations, coupling) =
            match self.normal_iterations {
                Some(k) => (k, k, 0, None),
                None => (
                    s.tangential_iterations,
                    0,
                    s.tangential_iterations,
                    Some(s.coupling_iterations),
                ),
            };
        StepReport {
            totals,
            iterations,
            normal_iterations,
            tangential_iterations,
            solve_time_s: 0.0,
            status: s.status,
            conformal: Some(ConformalKeys {
                contact_angle_variation_deg: t.contact_angle_variation_deg,
                length_width_ratio: length_width_ratio(t.patch_length_m, t.patch_width_m),
                normal_force_from_tractions_n: t.normal_force_from_tractions_n,
                pressure_resultant_n: t.pressure_resultant_n,
                fy_global_n: t.fy_global_n,
                fz_global_n: t.fz_global_n,
                coupling_iterations: coupling,
            }),
            force_control: None,
        }
    }

    /// The report: the last step's totals with counters summed over steps.
    pub fn report(&self, case: &Case, with_fields: bool) -> Report<'_> {
        let steps: Vec<StepReport> = self.solutions.iter().map(|s| self.step_report(s)).collect();
        let mut totals = self.step_report(self.last());
        totals.solve_time_s = self.elapsed_s;
        totals.iterations = steps.iter().map(|s| s.iterations).sum();
        totals.normal_iterations = steps.iter().map(|s| s.normal_iterations).sum();
        totals.tangential_iterations = steps.iter().map(|s| s.tangential_iterations).sum();
        if let Some(c) = totals.conformal.as_mut() {
            if c.coupling_iterations.is_some() {
                c.coupling_iterations = Some(
                    steps
                        .iter()
                        .filter_map(|s| s.conformal.and_then(|c| c.coupling_iterations))
                        .sum(),
                );
            }
        }
        totals.status = steps
            .iter()
            .fold(SolveStatus::Converged, |a, s| a.worst(s.status));
        let mut notes = vec![NOTE_NO_SPIN_MOMENT.to_string(), NOTE_FY.to_string()];
        if totals.status != SolveStatus::Converged {
            notes.push("a solver hit its iteration limit: the result is the last iterate ([solver] max_iterations, coupling_max_iterations)".to_string());
        }
        let frictional = self.normal_iterations.is_none();
        let grid = &self.geometry.grid;
        let last = self.last();
        Report {
            model: case.model,
            totals,
            fastsim_max_pressure_pa: None,
            friction_coefficient: if frictional {
                case.friction.kinetic_coefficient
            } else {
                0.0
            },
            grid: Some([grid.nx, grid.ny]),
            window_m: Some([case.window_x_m, case.window_y_m]),
            wfric_lateral: self.steady.then(|| WfricReport {
                s_m: (0..grid.ny).map(|iy| grid.y_m(iy)).collect(),
                w_j_per_m2: last.wfric_lateral_j_per_m2.clone(),
            }),
            notes,
            steady_start: None,
            steps: (frictional && !self.steady).then_some(steps),
            fields: with_fields.then_some(Fields::Conformal(ConformalFieldsReport {
                grid,
                pressure_pa: &last.pressure_pa,
                traction_x_pa: &last.traction_x_pa,
                traction_s_pa: &last.traction_s_pa,
                slip_x: &last.slip_x,
                slip_s: &last.slip_s,
                state: &last.state,
                gap_m: &self.geometry.gap_m,
                delta_rad: &self.geometry.delta_rad,
                reference_yz_m: &self.geometry.reference_yz_m,
            })),
            geometry: Some(case.geometry.describe()),
            force_control: None,
            subsurface: None,
            temperature: None,
            interfacial_layer: None,
        }
    }
}
