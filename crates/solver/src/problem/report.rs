//! What `railcontact solve` reports: one JSON object (`--json`) or a readable
//! summary. JSON values are in SI units; the summary uses mm and MPa.

use std::fmt::Write as _;

use serde::Serialize;

use crate::core::error::ContactError;
use crate::core::force::{ForceSolution, PrescribedForce, StepForceSolution};
use crate::core::grid::Grid;
use crate::core::layer::LayerFields;
use crate::core::solution::{ContactSolution, ElementFields, ElementState, SolveStatus, Totals};
use crate::core::subsurface::SubsurfaceSummary;
use crate::core::temperature::TemperatureSummary;
use crate::problem::case::Model;
use crate::problem::CaseError;

/// The quantities of the conformal models (`cect`, `cect_halfspace`,
/// `hertz_corrected`, and `hertz` on conformal profiles) beyond
/// [`Totals`]. Forces act on the rail.
#[derive(Debug, Clone, Copy, Serialize, PartialEq, Default)]
pub struct ConformalKeys {
    /// Total variation of the contact angle over the loaded lateral lines
    /// \[deg\] (Hertz: 2 b / r, r the mean lateral radius).
    pub contact_angle_variation_deg: f64,
    /// Patch length in x over patch width along s [-] (Hertz: a/b).
    pub length_width_ratio: f64,
    /// Part of `normal_force_n` carried by the lateral tractions \[N\].
    pub normal_force_from_tractions_n: f64,
    /// Resultant of the pressures alone along n(0) \[N\].
    pub pressure_resultant_n: f64,
    /// Force on the rail along the global y (lateral) axis \[N\].
    pub fy_global_n: f64,
    /// Force on the rail along the global z axis (down, into the rail) \[N\].
    pub fz_global_n: f64,
    /// Normal/tangential alternations (frictional conformal solves).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub coupling_iterations: Option<usize>,
}

/// Frictional work per unit rail area of one wheel passage along the
/// lateral coordinate s (steady conformal rolling), one entry per lateral
/// grid line.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct WfricReport {
    /// s of each lateral grid line \[m\].
    pub s_m: Vec<f64>,
    /// W_fric(s) [J/m²].
    pub w_j_per_m2: Vec<f64>,
}

/// Per-element fields of the conformal models (`--fields`): the (x, s)
/// grid (its `y` is the curvilinear s) and arrays with index `iy * nx +
/// ix`, plus per lateral line the orientation and the reference point.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct ConformalFieldsReport<'a> {
    /// The (x, s) grid.
    #[serde(flatten)]
    pub grid: &'a Grid,
    /// Pressure on the rail along the local normal \[Pa\].
    pub pressure_pa: &'a [f64],
    /// Longitudinal traction on the rail \[Pa\].
    pub traction_x_pa: &'a [f64],
    /// Lateral traction on the rail along the local tangent t(s) \[Pa\].
    pub traction_s_pa: &'a [f64],
    /// Slip of the rail relative to the wheel in x (steady: per rolling
    /// speed [-]; static compression: in the step \[m\]).
    pub slip_x: &'a [f64],
    /// Slip along t(s), units as `slip_x`.
    pub slip_s: &'a [f64],
    /// Element states.
    pub state: &'a [ElementState],
    /// Undeformed distance along the local normals \[m\].
    pub gap_m: &'a [f64],
    /// Orientation delta(s) of each lateral line \[rad\] (length ny).
    pub delta_rad: &'a [f64],
    /// Reference-curve point (y, z) of each lateral line \[m\] (length ny).
    pub reference_yz_m: &'a [[f64; 2]],
}

/// The `fields` of `--fields`: planar (exact) or conformal.
#[derive(Debug, Clone, Copy, Serialize)]
#[serde(untagged)]
pub enum Fields<'a> {
    /// Exact model.
    Planar(FieldsReport<'a>),
    /// Conformal models.
    Conformal(ConformalFieldsReport<'a>),
}

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
    /// Wall time \[s\].
    pub solve_time_s: f64,
    /// `"converged"` or `"max_iterations"`.
    pub status: SolveStatus,
    /// Conformal models: their additional quantities.
    #[serde(flatten)]
    pub conformal: Option<ConformalKeys>,
    /// A step with a prescribed force: the shift found.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub force_control: Option<StepForceReport>,
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
            conformal: None,
            force_control: None,
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
            conformal: None,
            force_control: None,
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
    /// `"hertz"`, `"hertz_corrected"`, `"fastsim"`, `"exact"`, `"cect"` or
    /// `"cect_halfspace"`.
    pub model: Model,
    /// Totals (see the type's doc for transient cases).
    #[serde(flatten)]
    pub totals: StepReport,
    /// Kinetic friction coefficient used [-] (0 for frictionless cases).
    pub friction_coefficient: f64,
    /// Model `fastsim`: the peak of the pressure whose multiple mu p
    /// bounds FASTSIM's tractions \[Pa\] (the maximum pressure CONTACT's
    /// FASTSIM reports, its PMAX): by default Kalker's parabolic pressure
    /// of the simplified theory, 2 Fn/(pi a b) = 4/3 p0, with
    /// `fastsim.traction_bound = "elliptic"` Hertz's, p0; on strips scaled
    /// so that the elements' pressures sum to Fn (within O(1/nx + 1/ny) of
    /// it), on CONTACT's grid (`fastsim.discretisation = "grid"`) the
    /// largest element value, unscaled. The totals' `max_pressure_pa`
    /// stays Hertz's p0 = 3 Fn/(2 pi a b). None for the other models.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fastsim_max_pressure_pa: Option<f64>,
    /// Grid used: `[nx, ny]` (elements of the exact model, strips x elements of FASTSIM).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub grid: Option<[usize; 2]>,
    /// Window of the exact or conformal model's grid `[x, y]` \[m\] (y: along
    /// s for the conformal models).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub window_m: Option<[f64; 2]>,
    /// Steady conformal rolling: W_fric(s) per lateral grid line.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub wfric_lateral: Option<WfricReport>,
    /// Remarks: ignored sections, quantities a model does not compute.
    pub notes: Vec<String>,
    /// The steady rolling state the transient steps started from
    /// (`transient.steady_start`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub steady_start: Option<StepReport>,
    /// One entry per transient step.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub steps: Option<Vec<StepReport>>,
    /// Per-element fields of the (last) solution, with `--fields`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fields: Option<Fields<'a>>,
    /// Steady rolling with a prescribed force: the creepages found.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub force_control: Option<ForceControlReport>,
    /// One line describing a conformal geometry (readable summary only).
    #[serde(skip)]
    pub geometry: Option<String>,
    /// Peaks of the subsurface stresses, with `[subsurface]` (exact model).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub subsurface: Option<SubsurfaceReport>,
    /// The flash temperatures' peaks, with `[temperature]` (exact model,
    /// steady rolling; see [`crate::core::temperature`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub temperature: Option<TemperatureSummary>,
    /// The interfacial layer's state after the (last) solve, with an
    /// elasto-plastic `[interfacial_layer]` (exact model; an elastic layer
    /// has no state).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub interfacial_layer: Option<LayerReport<'a>>,
}

/// An elasto-plastic interfacial layer's state after a solve (see
/// [`crate::core::layer`]): CONTACT's plasticity area and the extremes of
/// TAUCRT and the plastic deformation, with `--fields` the fields.
#[derive(Debug, Clone, Serialize)]
pub struct LayerReport<'a> {
    /// Elements where the layer flowed without slip at the interface
    /// (CONTACT's plasticity area, NPLAST) [-].
    pub plastic_elements: usize,
    /// Their area \[m²\] (a line contact: per metre, \[m²/m\]).
    pub plastic_area_m2: f64,
    /// Largest yield limit tau_c of the material on the grid \[Pa\].
    pub max_yield_limit_pa: f64,
    /// Smallest yield limit tau_c on the grid \[Pa\].
    pub min_yield_limit_pa: f64,
    /// Largest magnitude of the accumulated plastic deformation u_pl \[m\].
    pub max_plastic_deformation_m: f64,
    /// The per-element fields (`--fields`): `yield_limit_pa`,
    /// `plastic_x_m`, `plastic_y_m` and `plastic` (bool), index
    /// `iy * nx + ix`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fields: Option<&'a LayerFields>,
}

impl<'a> LayerReport<'a> {
    /// The summary of `layer` on `grid`, with the fields when `fields`.
    pub fn of(grid: &Grid, layer: &'a LayerFields, fields: bool) -> Self {
        let plastic_elements = layer.plastic.iter().filter(|&&p| p).count();
        let fold =
            |init: f64, f: fn(f64, f64) -> f64| layer.yield_limit_pa.iter().copied().fold(init, f);
        LayerReport {
            plastic_elements,
            plastic_area_m2: plastic_elements as f64 * grid.element_area_m2(),
            max_yield_limit_pa: fold(0.0, f64::max),
            min_yield_limit_pa: fold(f64::INFINITY, f64::min),
            max_plastic_deformation_m: layer
                .plastic_x_m
                .iter()
                .zip(&layer.plastic_y_m)
                .map(|(x, y)| x.hypot(*y))
                .fold(0.0, f64::max),
            fields: fields.then_some(layer),
        }
    }
}

/// The peaks of the subsurface stresses of both bodies (see
/// [`crate::core::subsurface`] for the frame and signs) and the surface
/// fatigue index.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct SubsurfaceReport {
    /// The depths computed \[m\].
    pub depths_m: Vec<f64>,
    /// Body 1 (the rail in wheel/rail contact).
    pub body1: SubsurfaceSummary,
    /// Body 2 (the wheel).
    pub body2: SubsurfaceSummary,
    /// Ekberg's surface fatigue index FI_surf [-] (positive: surface
    /// fatigue predicted), when `shear_yield_stress_pa` was given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub surface_fatigue_index: Option<f64>,
}

/// The outcome of a prescribed-force solve (`[rolling] force_x_n`,
/// `force_y_n`): the creepages that give the forces (the given ones in
/// the other directions) and the outer iteration's counts.
#[derive(Debug, Clone, Copy, Serialize, PartialEq)]
pub struct ForceControlReport {
    /// Longitudinal creepage xi [-].
    pub creepage_long: f64,
    /// Lateral creepage eta [-].
    pub creepage_lat: f64,
    /// Spin creepage phi [1/m] (as given).
    pub spin_per_m: f64,
    /// Outer (secant or Newton) iterations.
    pub force_iterations: usize,
    /// Exact solves of the outer iteration, all included.
    pub force_solves: usize,
}

impl ForceControlReport {
    /// The report of a prescribed-force solve; a force the outer iteration
    /// did not reach is a failure naming its iterations and last creepages.
    pub fn of(f: &ForceSolution) -> Result<Self, CaseError> {
        if !f.converged {
            return Err(CaseError::Failure(format!(
                "the prescribed force was not reached in {} outer iterations (last creepages \
                 xi = {}, eta = {})",
                f.outer_iterations, f.creepages.creepage_long, f.creepages.creepage_lat
            )));
        }
        Ok(ForceControlReport {
            creepage_long: f.creepages.creepage_long,
            creepage_lat: f.creepages.creepage_lat,
            spin_per_m: f.creepages.spin_per_m,
            force_iterations: f.outer_iterations,
            force_solves: f.solves,
        })
    }
}

/// The outcome of a transient step with a prescribed force
/// (`transient.steps[k].force_x_n`, ...): the step's shift found (the
/// given one in the other direction) and, in a rolling step, the
/// creepages it stands for (shift over rolling distance).
#[derive(Debug, Clone, Copy, Serialize, PartialEq)]
pub struct StepForceReport {
    /// Rigid shift in x of the step \[m\].
    pub shift_x_m: f64,
    /// Rigid shift in y of the step \[m\].
    pub shift_y_m: f64,
    /// Distance the step rolled \[m\] (0: a shift step).
    pub rolling_m: f64,
    /// Rolling steps: longitudinal creepage xi = shift_x / rolling [-].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub creepage_long: Option<f64>,
    /// Rolling steps: lateral creepage eta = shift_y / rolling [-].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub creepage_lat: Option<f64>,
    /// Outer (secant) iterations.
    pub force_iterations: usize,
    /// Solves of the step, all included.
    pub force_solves: usize,
}

impl StepForceReport {
    /// The report of the step named `key` (`transient.steps[3]`) solved
    /// for `target`: None when the step prescribes no force. A force the
    /// secant did not reach within its iteration limit is refused naming
    /// the force's key (it lies too close to saturation for the step).
    pub fn of(
        key: &str,
        target: PrescribedForce,
        f: &StepForceSolution,
    ) -> Result<Option<Self>, CaseError> {
        if !target.any() {
            return Ok(None);
        }
        let s = &f.step;
        if !f.converged {
            let name = if target.force_x_n.is_some() {
                "force_x_n"
            } else {
                "force_y_n"
            };
            return Err(CaseError::from(ContactError::invalid(
                format!("{key}.{name}"),
                format!(
                    "not reached in {} outer iterations (last shifts x = {} m, y = {} m): the \
                     force is too close to saturation (mu Fn) for this step; prescribe a smaller \
                     one or the shift",
                    f.outer_iterations, s.shift_x_m, s.shift_y_m
                ),
            )));
        }
        let rolled = |shift: f64| (s.rolling_m > 0.0).then(|| shift / s.rolling_m);
        Ok(Some(StepForceReport {
            shift_x_m: s.shift_x_m,
            shift_y_m: s.shift_y_m,
            rolling_m: s.rolling_m,
            creepage_long: rolled(s.shift_x_m),
            creepage_lat: rolled(s.shift_y_m),
            force_iterations: f.outer_iterations,
            force_solves: f.solves,
        }))
    }
}

/// The summary lines shared by the planar and conformal reports: approach,
/// max pressure (and traction), area and patch size.
fn patch_lines(line: &mut dyn FnMut(&str, String), t: &Totals, traction: bool, width_note: &str) {
    line("approach delta [mm]", format!("{:.6}", mm(t.approach_m)));
    line(
        "max pressure p0 [MPa]",
        format!("{:.2}", mpa(t.max_pressure_pa)),
    );
    if traction {
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
        format!(
            "{:.4} x {:.4}{width_note}",
            mm(t.patch_length_m),
            mm(t.patch_width_m)
        ),
    );
}

fn mm(v: f64) -> f64 {
    v * 1e3
}

fn mpa(v: f64) -> f64 {
    v * 1e-6
}

/// `v` with `decimals` decimals, without the sign of a value that rounds
/// to zero (round-off of a symmetric patch prints as 0.00, not -0.00).
fn fixed(v: f64, decimals: usize) -> String {
    let s = format!("{v:.decimals$}");
    match s.strip_prefix('-') {
        Some(rest) if rest.chars().all(|c| c == '0' || c == '.') => rest.to_string(),
        _ => s,
    }
}

impl Report<'_> {
    /// The readable summary (mm, MPa, with units in the labels).
    pub fn human(&self) -> String {
        if self.totals.conformal.is_some() {
            return self.human_conformal();
        }
        let mut o = String::new();
        let r = &self.totals;
        let t = &r.totals;
        let title = match self.model {
            Model::Hertz => "Hertz (closed form)",
            Model::Fastsim => "FASTSIM (Kalker's simplified theory)",
            Model::Exact => "exact (Kalker's exact theory, half-space)",
            Model::HertzCorrected => "Hertz with corrected lateral curvature (closed form)",
            Model::Cect => "CECT (conformal, Blanco's influence coefficients)",
            Model::CectHalfspace => "CECT (conformal, half-space influence coefficients)",
        };
        let _ = writeln!(
            o,
            "railcontact solve: model {title}, status {}",
            r.status.as_str()
        );
        if let Some(g) = &self.geometry {
            let _ = writeln!(o, "  geometry: {g}");
        }
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
            for (k, step) in steps.iter().enumerate() {
                if let Some(f) = &step.force_control {
                    let creep = match (f.creepage_long, f.creepage_lat) {
                        (Some(xi), Some(eta)) => format!(" (xi, eta {xi:.6e}, {eta:.6e})"),
                        _ => String::new(),
                    };
                    let _ = writeln!(
                        o,
                        "    step {} prescribed force: shift x, y {:.6e}, {:.6e} mm{creep} in {} \
                         secant steps ({} solves)",
                        k + 1,
                        mm(f.shift_x_m),
                        mm(f.shift_y_m),
                        f.force_iterations,
                        f.force_solves
                    );
                }
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
        if let Some(f) = &self.force_control {
            line(
                "creepages found xi, eta [-]",
                format!("{:.6e}, {:.6e}", f.creepage_long, f.creepage_lat),
            );
            line(
                "force iterations (solves)",
                format!("{} ({})", f.force_iterations, f.force_solves),
            );
        }
        patch_lines(&mut line, t, tangential, "");
        if let Some(p) = self.fastsim_max_pressure_pa {
            line(
                "FASTSIM bound max p [MPa]",
                format!("{:.2}   ({:.4} p0)", mpa(p), p / t.max_pressure_pa),
            );
        }
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
        if let Some(sub) = &self.subsurface {
            for (body, b) in [("body 1", &sub.body1), ("body 2", &sub.body2)] {
                for (what, p) in [
                    ("max von Mises", &b.max_von_mises),
                    ("max shear", &b.max_shear),
                    ("max principal", &b.max_principal),
                ] {
                    line(
                        &format!("{body} {what} [MPa]"),
                        format!(
                            "{:.2} at x {:.4}, y {:.4}, depth {:.4} mm",
                            mpa(p.value_pa),
                            mm(p.x_m),
                            mm(p.y_m),
                            mm(p.depth_m)
                        ),
                    );
                }
            }
            if let Some(fi) = sub.surface_fatigue_index {
                line("surface fatigue index [-]", format!("{fi:.4}"));
            }
        }
        if let Some(t) = &self.temperature {
            for (body, p) in [("body 1", &t.max_body1), ("body 2", &t.max_body2)] {
                line(
                    &format!("{body} max temperature [K]"),
                    format!(
                        "{:.2} at x {:.4}, y {:.4} mm",
                        p.temperature_k,
                        mm(p.x_m),
                        mm(p.y_m)
                    ),
                );
            }
            line(
                "contact temperature [K]",
                format!("{:.2} (before frictional heating)", t.contact_temperature_k),
            );
            line(
                "frictional power [W]",
                format!("{:.4e}", t.frictional_power_w),
            );
            line(
                "heat share body 1 [-]",
                format!("{:.4}", t.heat_share_body1),
            );
            line("Peclet number [-]", format!("{:.1}", t.peclet_number));
        }
        if let Some(l) = &self.interfacial_layer {
            line(
                "layer plastic area [mm²]",
                format!(
                    "{:.4} ({} elements)",
                    l.plastic_area_m2 * 1e6,
                    l.plastic_elements
                ),
            );
            line(
                "layer yield limit [MPa]",
                format!(
                    "{:.4} to {:.4}",
                    mpa(l.min_yield_limit_pa),
                    mpa(l.max_yield_limit_pa)
                ),
            );
            line(
                "layer max plastic def. [mm]",
                format!("{:.6e}", mm(l.max_plastic_deformation_m)),
            );
        }
        for n in &self.notes {
            let _ = writeln!(o, "  note: {n}");
        }
        o
    }
}

impl Report<'_> {
    /// The readable summary of a conformal model (mm, MPa, degrees).
    fn human_conformal(&self) -> String {
        let mut o = String::new();
        let r = &self.totals;
        let t = &r.totals;
        let c = r.conformal.unwrap_or_default();
        let closed_form = matches!(self.model, Model::Hertz | Model::HertzCorrected);
        let title = match self.model {
            Model::Hertz => "Hertz on the flattened conformal profiles (closed form)",
            Model::HertzCorrected => {
                "Hertz with corrected lateral curvature (closed form, Blanco-Lorenzo et al. Eq. 5)"
            }
            Model::CectHalfspace => "CECT (conformal, half-space influence coefficients)",
            _ => "CECT (conformal, Blanco's influence coefficients)",
        };
        let _ = writeln!(
            o,
            "railcontact solve: model {title}, status {}",
            r.status.as_str()
        );
        if let Some(g) = &self.geometry {
            let _ = writeln!(o, "  geometry: {g}");
        }
        if let (Some([nx, ny]), Some([wx, wy])) = (self.grid, self.window_m) {
            let _ = writeln!(
                o,
                "  grid: {nx} x {ny} elements over x {:.4} mm by s {:.4} mm (s curvilinear)",
                mm(wx),
                mm(wy)
            );
        }
        if let Some(steps) = &self.steps {
            let _ = writeln!(o, "  static compression steps (forces on the rail):");
            let _ = writeln!(
                o,
                "    {:>4} {:>11} {:>13} {:>12} {:>10} {:>9} {:>10} {:>6} {:>15}",
                "step",
                "Fn [N]",
                "tractions[N]",
                "approach[mm]",
                "p0 [MPa]",
                "adh. [-]",
                "var [deg]",
                "iter",
                "status"
            );
            for (k, step) in steps.iter().enumerate() {
                let s = &step.totals;
                let sc = step.conformal.unwrap_or_default();
                let _ = writeln!(
                    o,
                    "    {:>4} {:>11.2} {:>13.2} {:>12.6} {:>10.2} {:>9.3} {:>10.1} {:>6} {:>15}",
                    k + 1,
                    s.normal_force_n,
                    sc.normal_force_from_tractions_n,
                    mm(s.approach_m),
                    mpa(s.max_pressure_pa),
                    s.adhesion_fraction,
                    sc.contact_angle_variation_deg,
                    step.iterations,
                    step.status.as_str()
                );
            }
            let _ = writeln!(o, "  last step:");
        }
        let mu = self.friction_coefficient;
        let frictional = mu > 0.0 && !closed_form;
        let mut line = |label: &str, value: String| {
            let _ = writeln!(o, "  {label:<34} {value}");
        };
        let of_mu_fn = |f: f64| {
            if mu > 0.0 && t.normal_force_n > 0.0 {
                let u = f / (mu * t.normal_force_n);
                let sign = if fixed(u, 4).starts_with('-') {
                    ""
                } else {
                    "+"
                };
                format!("   ({sign}{} mu Fn)", fixed(u, 4))
            } else {
                String::new()
            }
        };
        line(
            "normal force Fn [N]",
            format!(
                "{:.2}   (along n(0), the approach direction)",
                t.normal_force_n
            ),
        );
        if frictional {
            line(
                "  carried by lateral tractions [N]",
                format!("{:.2}", c.normal_force_from_tractions_n),
            );
        }
        if closed_form {
            line(
                "tangential forces Fx, Fs",
                "not computed (Hertz: normal problem only)".to_string(),
            );
        } else {
            line(
                "long. force Fx [N]",
                format!("{}{}", fixed(t.fx_n, 2), of_mu_fn(t.fx_n)),
            );
            line(
                "lateral force Fs [N] (along t(0))",
                format!("{}{}", fixed(t.fy_n, 2), of_mu_fn(t.fy_n)),
            );
        }
        line(
            "global force Fy, Fz [N] (z down)",
            format!("{}, {}", fixed(c.fy_global_n, 2), fixed(c.fz_global_n, 2)),
        );
        patch_lines(&mut line, t, frictional, "   (width along s)");
        line(
            "length/width ratio [-]",
            format!("{:.4}", c.length_width_ratio),
        );
        line(
            "contact angle variation [deg]",
            format!("{:.2}", c.contact_angle_variation_deg),
        );
        if frictional {
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
        if let Some(w) = &self.wfric_lateral {
            if let Some((k, peak)) = w
                .w_j_per_m2
                .iter()
                .cloned()
                .enumerate()
                .max_by(|a, b| a.1.total_cmp(&b.1))
            {
                line(
                    "max W_fric(s) [J/m²]",
                    format!("{peak:.4} at s = {:.4} mm", mm(w.s_m[k])),
                );
            }
        }
        if !closed_form {
            let it = match c.coupling_iterations {
                Some(k) => format!(
                    "{} tangential Newton steps in {k} normal/tangential alternations{}",
                    r.tangential_iterations,
                    if self.steps.is_some() {
                        ", all steps"
                    } else {
                        ""
                    }
                ),
                None => format!("{} (normal, conjugate gradient)", r.normal_iterations),
            };
            line("iterations", it);
        }
        line("solve time [s]", format!("{:.3}", r.solve_time_s));
        for n in &self.notes {
            let _ = writeln!(o, "  note: {n}");
        }
        o
    }
}
