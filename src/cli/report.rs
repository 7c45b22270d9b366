//! What `railcontact solve` reports: one JSON object (`--json`) or a readable
//! summary. JSON values are in SI units; the summary uses mm and MPa.

use std::fmt::Write as _;

use serde::Serialize;

use crate::core::grid::Grid;
use crate::core::solution::{ContactSolution, ElementState, SolveStatus};

/// The totals of one solution (one step of a transient case).
#[derive(Debug, Clone, Serialize, Default, PartialEq)]
pub struct StepReport {
    /// Normal force on body 1 [N].
    pub normal_force_n: f64,
    /// Longitudinal tangential force on body 1 [N].
    pub fx_n: f64,
    /// Lateral tangential force on body 1 [N].
    pub fy_n: f64,
    /// Spin moment about the normal axis through the origin [N m].
    pub mz_nm: f64,
    /// Approach of the bodies [m].
    pub approach_m: f64,
    /// Largest pressure [Pa].
    pub max_pressure_pa: f64,
    /// Largest tangential traction magnitude [Pa].
    pub max_traction_pa: f64,
    /// Contact area [m²].
    pub contact_area_m2: f64,
    /// Extent of the contact patch in x [m].
    pub patch_length_m: f64,
    /// Extent of the contact patch in y [m].
    pub patch_width_m: f64,
    /// Share of the contact area in adhesion [-].
    pub adhesion_fraction: f64,
    /// Frictional power per unit rolling speed [N] (steady rolling; else 0).
    pub tgamma_n: f64,
    /// Frictional work in the step [J] (transient; else 0).
    pub frictional_work_j: f64,
    /// Normal + tangential iterations.
    pub iterations: usize,
    /// Normal (conjugate-gradient) iterations.
    pub normal_iterations: usize,
    /// Tangential iterations.
    pub tangential_iterations: usize,
    /// Wall time [s].
    pub solve_time_s: f64,
    /// `"converged"` or `"max_iterations"`.
    pub status: String,
}

impl StepReport {
    /// The report of one core solution.
    pub fn from_solution(s: &ContactSolution) -> Self {
        let t = &s.totals;
        let i = &s.info;
        StepReport {
            normal_force_n: t.normal_force_n,
            fx_n: t.fx_n,
            fy_n: t.fy_n,
            mz_nm: t.mz_nm,
            approach_m: t.approach_m,
            max_pressure_pa: t.max_pressure_pa,
            max_traction_pa: t.max_traction_pa,
            contact_area_m2: t.contact_area_m2,
            patch_length_m: t.patch_length_m,
            patch_width_m: t.patch_width_m,
            adhesion_fraction: t.adhesion_fraction,
            tgamma_n: t.tgamma_n,
            frictional_work_j: t.frictional_work_j,
            iterations: i.normal_iterations + i.tangential_iterations,
            normal_iterations: i.normal_iterations,
            tangential_iterations: i.tangential_iterations,
            solve_time_s: i.solve_time_s,
            status: status_name(i.status).to_string(),
        }
    }
}

/// The JSON name of a solver status.
pub fn status_name(s: SolveStatus) -> &'static str {
    match s {
        SolveStatus::Converged => "converged",
        SolveStatus::MaxIterations => "max_iterations",
    }
}

/// Per-element fields of the exact model (`--fields`), index `iy * nx + ix`.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct FieldsReport {
    /// Elements in x.
    pub nx: usize,
    /// Elements in y.
    pub ny: usize,
    /// Element size in x [m].
    pub dx_m: f64,
    /// Element size in y [m].
    pub dy_m: f64,
    /// x of the grid's lower-left corner [m].
    pub x0_m: f64,
    /// y of the grid's lower-left corner [m].
    pub y0_m: f64,
    /// Normal pressure [Pa].
    pub pressure_pa: Vec<f64>,
    /// Longitudinal traction [Pa].
    pub traction_x_pa: Vec<f64>,
    /// Lateral traction [Pa].
    pub traction_y_pa: Vec<f64>,
    /// Slip in x (steady rolling: [-]; transient: [m]).
    pub slip_x: Vec<f64>,
    /// Slip in y (units as `slip_x`).
    pub slip_y: Vec<f64>,
    /// Element states: `"exterior"`, `"adhesion"` or `"slip"`.
    pub state: Vec<ElementState>,
}

impl FieldsReport {
    /// The fields of `s` on `grid`.
    pub fn new(grid: &Grid, s: &ContactSolution) -> Self {
        let f = &s.fields;
        FieldsReport {
            nx: grid.nx,
            ny: grid.ny,
            dx_m: grid.dx_m,
            dy_m: grid.dy_m,
            x0_m: grid.x0_m,
            y0_m: grid.y0_m,
            pressure_pa: f.pressure_pa.clone(),
            traction_x_pa: f.traction_x_pa.clone(),
            traction_y_pa: f.traction_y_pa.clone(),
            slip_x: f.slip_x.clone(),
            slip_y: f.slip_y.clone(),
            state: f.state.clone(),
        }
    }
}

/// The whole result of `railcontact solve`. Serialised, it is the one JSON
/// object printed with `--json`: the keys of [`StepReport`] at top level
/// (those of the last step for a transient case, except `iterations`,
/// `normal_iterations`, `tangential_iterations` and `solve_time_s`, which are
/// totals, and `status`, which is the worst of the steps), plus `model`,
/// `friction_coefficient`, `notes`, and `steps` / `fields` where present.
#[derive(Debug, Clone, Serialize)]
pub struct Report {
    /// `"hertz"`, `"fastsim"` or `"exact"`.
    pub model: String,
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
    pub fields: Option<FieldsReport>,
}

fn mm(v: f64) -> f64 {
    v * 1e3
}

fn mpa(v: f64) -> f64 {
    v * 1e-6
}

impl Report {
    /// The readable summary (mm, MPa, with units in the labels).
    pub fn human(&self) -> String {
        let mut o = String::new();
        let t = &self.totals;
        let title = match self.model.as_str() {
            "hertz" => "Hertz (closed form)",
            "fastsim" => "FASTSIM (Kalker's simplified theory)",
            _ => "exact (Kalker's exact theory, half-space)",
        };
        let _ = writeln!(o, "railcontact solve: model {title}, status {}", t.status);
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
            for (k, s) in steps.iter().enumerate() {
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
                    s.iterations,
                    s.status
                );
            }
            let _ = writeln!(o, "  last step:");
        }
        let mu = self.friction_coefficient;
        let tangential = self.model != "hertz";
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
        if self.model == "exact" {
            line(
                "iterations",
                format!(
                    "{} ({} normal + {} tangential){}",
                    t.iterations,
                    t.normal_iterations,
                    t.tangential_iterations,
                    if self.steps.is_some() {
                        ", all steps"
                    } else {
                        ""
                    }
                ),
            );
        }
        line("solve time [s]", format!("{:.3}", t.solve_time_s));
        for n in &self.notes {
            let _ = writeln!(o, "  note: {n}");
        }
        o
    }
}
