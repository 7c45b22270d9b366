//! What `railcontact solve` reports: one JSON object (`--json`) or a readable
//! summary. JSON values are in SI units; the summary uses mm and MPa.

use std::fmt::Write as _;

use serde::Serialize;

use crate::cli::case::Model;
use crate::core::grid::Grid;
use crate::core::solution::{ContactSolution, ElementFields, SolveStatus, Totals};

/// The totals of one solution (one step of a transient case): the core's
/// [`Totals`] with the solver's counters.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct StepReport {
    /// Forces, moment, approach, pressures, areas (keys as in [`Totals`]).
    #[serde(flatten)]
    pub totals: Totals,
    /// Normal + tangential iterations.
    pub iterations: usize,
    /// Normal (conjugate-gradient) iterations.
    pub normal_iterations: usize,
    /// Tangential iterations.
    pub tangential_iterations: usize,
    /// Wall time [s].
    pub solve_time_s: f64,
    /// `"converged"` or `"max_iterations"`.
    pub status: SolveStatus,
}

impl StepReport {
    /// A converged report of `totals` without iterations (closed-form models).
    pub fn closed_form(totals: Totals, solve_time_s: f64) -> Self {
        StepReport {
            totals,
            iterations: 0,
            normal_iterations: 0,
            tangential_iterations: 0,
            solve_time_s,
            status: SolveStatus::Converged,
        }
    }

    /// The report of one core solution.
    pub fn from_solution(s: &ContactSolution) -> Self {
        let i = &s.info;
        StepReport {
            totals: s.totals,
            iterations: i.normal_iterations + i.tangential_iterations,
            normal_iterations: i.normal_iterations,
            tangential_iterations: i.tangential_iterations,
            solve_time_s: i.solve_time_s,
            status: i.status,
        }
    }
}

/// Per-element fields of the exact model (`--fields`): the grid's `nx, ny,
/// dx_m, dy_m, x0_m, y0_m` and the arrays of [`ElementFields`], index
/// `iy * nx + ix`.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct FieldsReport<'a> {
    /// The grid.
    #[serde(flatten)]
    pub grid: &'a Grid,
    /// The fields of the (last) solution.
    #[serde(flatten)]
    pub fields: &'a ElementFields,
}

/// The whole result of `railcontact solve`. Serialised, it is the one JSON
/// object printed with `--json`: the keys of [`StepReport`] at top level
/// (those of the last step for a transient case, except `iterations`,
/// `normal_iterations`, `tangential_iterations` and `solve_time_s`, which are
/// totals, and `status`, which is the worst of the steps), plus `model`,
/// `friction_coefficient`, `notes`, and `steps` / `fields` where present.
#[derive(Debug, Clone, Serialize)]
pub struct Report<'a> {
    /// `"hertz"`, `"fastsim"` or `"exact"`.
    pub model: Model,
    /// Totals (see the type's doc for transient cases).
    #[serde(flatten)]
    pub totals: StepReport,
    /// Kinetic friction coefficient used [-] (0 for frictionless cases).
    pub friction_coefficient: f64,
    /// Grid used: `[nx, ny]` (elements of the exact model, strips x elements of FASTSIM).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub grid: Option<[usize; 2]>,
    /// Window of the exact model's grid `[x, y]` [m].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub window_m: Option<[f64; 2]>,
    /// Remarks: ignored sections, quantities a model does not compute.
    pub notes: Vec<String>,
    /// One entry per transient step.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub steps: Option<Vec<StepReport>>,
    /// Per-element fields of the (last) solution, with `--fields`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fields: Option<FieldsReport<'a>>,
}

fn mm(v: f64) -> f64 {
    v * 1e3
}

fn mpa(v: f64) -> f64 {
    v * 1e-6
}

impl Report<'_> {
    /// The readable summary (mm, MPa, with units in the labels).
    pub fn human(&self) -> String {
        let mut o = String::new();
        let r = &self.totals;
        let t = &r.totals;
        let title = match self.model {
            Model::Hertz => "Hertz (closed form)",
            Model::Fastsim => "FASTSIM (Kalker's simplified theory)",
            Model::Exact => "exact (Kalker's exact theory, half-space)",
        };
        let _ = writeln!(
            o,
            "railcontact solve: model {title}, status {}",
            r.status.as_str()
        );
        if let (Some([nx, ny]), Some([wx, wy])) = (self.grid, self.window_m) {
            let _ = writeln!(
                o,
                "  grid: {nx} x {ny} elements over {:.4} x {:.4} mm",
                mm(wx),
                mm(wy)
            );
        } else if let Some([nx, ny]) = self.grid {
            let _ = writeln!(o, "  FASTSIM grid: {ny} strips along x, {nx} elements each");
        }
        if let Some(steps) = &self.steps {
            let _ = writeln!(o, "  transient steps (forces on body 1):");
            let _ = writeln!(
                o,
                "    {:>4} {:>11} {:>11} {:>11} {:>12} {:>10} {:>9} {:>12} {:>6} {:>15}",
                "step",
                "Fn [N]",
                "Fx [N]",
                "Fy [N]",
                "approach[mm]",
                "p0 [MPa]",
                "adh. [-]",
                "work [J]",
                "iter",
                "status"
            );
            for (k, step) in steps.iter().enumerate() {
                let s = &step.totals;
                let _ = writeln!(
                    o,
                    "    {:>4} {:>11.2} {:>11.2} {:>11.2} {:>12.6} {:>10.2} {:>9.3} {:>12.4e} {:>6} {:>15}",
                    k + 1,
                    s.normal_force_n,
                    s.fx_n,
                    s.fy_n,
                    mm(s.approach_m),
                    mpa(s.max_pressure_pa),
                    s.adhesion_fraction,
                    s.frictional_work_j,
                    step.iterations,
                    step.status.as_str()
                );
            }
            let _ = writeln!(o, "  last step:");
        }
        let mu = self.friction_coefficient;
        let tangential = self.model != Model::Hertz;
        let mut line = |label: &str, value: String| {
            let _ = writeln!(o, "  {label:<30} {value}");
        };
        let of_mu_fn = |f: f64| {
            if mu > 0.0 && t.normal_force_n > 0.0 {
                format!("   ({:+.4} mu Fn)", f / (mu * t.normal_force_n))
            } else {
                String::new()
            }
        };
        let not_computed = || "not computed (Hertz: normal problem only)".to_string();
        line("normal force Fn [N]", format!("{:.2}", t.normal_force_n));
        if tangential {
            line(
                "long. force Fx [N]",
                format!("{:.2}{}", t.fx_n, of_mu_fn(t.fx_n)),
            );
            line(
                "lateral force Fy [N]",
                format!("{:.2}{}", t.fy_n, of_mu_fn(t.fy_n)),
            );
            line("spin moment Mz [N m]", format!("{:.4}", t.mz_nm));
        } else {
            line("tangential forces Fx, Fy, Mz", not_computed());
        }
        line("approach delta [mm]", format!("{:.6}", mm(t.approach_m)));
        line(
            "max pressure p0 [MPa]",
            format!("{:.2}", mpa(t.max_pressure_pa)),
        );
        if tangential {
            line(
                "max traction |p_t| [MPa]",
                format!("{:.2}", mpa(t.max_traction_pa)),
            );
        }
        line(
            "contact area [mm²]",
            format!("{:.4}", t.contact_area_m2 * 1e6),
        );
        line(
            "patch length x width [mm]",
            format!("{:.4} x {:.4}", mm(t.patch_length_m), mm(t.patch_width_m)),
        );
        if tangential && mu > 0.0 {
            line(
                "adhesion fraction [-]",
                format!("{:.3}", t.adhesion_fraction),
            );
        }
        if t.tgamma_n != 0.0 {
            line(
                "T-gamma (friction power/V) [N]",
                format!("{:.4}", t.tgamma_n),
            );
        }
        if t.frictional_work_j != 0.0 {
            line(
                "frictional work in step [J]",
                format!("{:.4e}", t.frictional_work_j),
            );
        }
        if self.model == Model::Exact {
            line(
                "iterations",
                format!(
                    "{} ({} normal + {} tangential){}",
                    r.iterations,
                    r.normal_iterations,
                    r.tangential_iterations,
                    if self.steps.is_some() {
                        ", all steps"
                    } else {
                        ""
                    }
                ),
            );
        }
        line("solve time [s]", format!("{:.3}", r.solve_time_s));
        for n in &self.notes {
            let _ = writeln!(o, "  note: {n}");
        }
        o
    }
}
