//! The case file of `railcontact solve`: its TOML schema and its validation.
//!
//! All values are in SI units. Every table rejects unknown keys. See
//! `examples/cases/README.md` for a commented list of the keys and
//! [`CaseFile`] for the schema; [`Case::from_toml`] parses and validates a
//! file into a [`Case`] that the models can run without further checks.

use std::path::Path;
use std::sync::Arc;

use serde::{Deserialize, Serialize};

use crate::conformal::frictional::{ConformalKinematics, ConformalSettings};
use crate::conformal::geometry::{ConformalCreepages, ConformalGeometry, RigidSlipSurface};
use crate::conformal::operator::InfluenceModel;
use crate::core::error::ContactError;
use crate::core::force::PrescribedForce;
use crate::core::friclaw::SlipStart;
use crate::core::grid::Grid;
use crate::core::hertz::HertzSolution;
use crate::core::layer::InterfacialLayer;
use crate::core::material::{soft_modulus_note, CombinedMaterial};
use crate::core::normal::NormalLoad;
use crate::core::numerical_influence::InfluenceFile;
use crate::core::problem::{
    check_viscoelastic_grid, ContactProblem, Creepages, ExtraRigidSlip, Friction, Kinematics,
    SolverSettings, NUMERICAL_INFLUENCE_KEY,
};
use crate::core::temperature::ThermalInput;
use crate::core::viscoelastic::Viscoelastic;
use crate::problem::reference_models::hertz_of;
use crate::problem::CaseError;

mod fastsim;
mod friction;
mod geometry;
mod grid;
mod kinematics;
mod materials;
mod outputs;

use fastsim::fastsim_options;
pub use fastsim::{
    FastsimDiscretisation, FastsimMethod, FastsimOptions, FastsimSection, TractionBoundName,
    DEFAULT_WINDOW_SCALE, FASTSIM_KEY,
};
use friction::{case_friction, needs_friction};
pub use friction::{FrictionLawName, FrictionSection};
use geometry::{
    check_hertz_patch, check_line_patch, check_model_geometry, conformal_options, given_gap,
    per_element_values,
};
pub use geometry::{CaseGeometry, ConformalSection, GeometryKind, GeometrySection};
use grid::{case_grid, solver_settings, CaseGrid};
pub use grid::{GridSection, SolverSection};
use kinematics::{case_motion, extra_rigid_slip, one_load, rolling_direction, CaseMotion};
pub use kinematics::{
    check_shift_step, transient_step, ExtraRigidSlipSection, LoadSection, RollingSection,
    StepSection, TransientSection, TransientStep,
};
pub use materials::MaterialSection;
use materials::{interfacial_layer, viscoelastic};
use outputs::temperature_request;
pub use outputs::{SubsurfaceRequest, SubsurfaceSection, TemperatureSection};

/// Default grid of the exact model in each direction (elements).
pub const DEFAULT_EXACT_ELEMENTS: usize = 64;
/// Default number of FASTSIM strips / elements per strip.
pub const DEFAULT_FASTSIM_ELEMENTS: usize = 40;
/// The automatic window is this multiple of the Hertz semi-axis in each
/// direction (1.2 times the Hertz patch).
pub const AUTO_WINDOW_PER_SEMI_AXIS: f64 = 2.4;
/// Conformal models: the automatic window in x is this multiple of the
/// plain Hertz semi-axis in x (1.6 times the Hertz patch length: the
/// conformal patch is longer than Hertz's).
pub const CONFORMAL_WINDOW_X_PER_SEMI_AXIS: f64 = 3.2;
/// Conformal models: the automatic window along s is this multiple of the
/// plain Hertz semi-axis in y (1.3 times the Hertz patch width: Hertz
/// overestimates the width of conformal patches) ...
pub const CONFORMAL_WINDOW_S_PER_SEMI_AXIS: f64 = 2.6;
/// ... but at most the arc of +- this angle \[deg\] on the mean lateral radius.
pub const CONFORMAL_WINDOW_MAX_HALF_ANGLE_DEG: f64 = 75.0;
/// Largest distance of a profile's nearest point from the origin (the rigid
/// contact point) in `geometry.*_points_m` \[m\].
pub const POINTS_ORIGIN_TOLERANCE_M: f64 = 1e-7;
/// Largest angle between the rail and wheel tangents at the origin in
/// `geometry.*_points_m` \[deg\]: the profiles must touch there.
pub const POINTS_TANGENT_TOLERANCE_DEG: f64 = 1.0;

/// The documented ranges of the case's numeric keys (the same for the
/// service's `PatchCase`); `examples/cases/README.md` lists them. Materials,
/// friction and creepages have the core's ranges
/// ([`crate::core::material::SHEAR_MODULUS_RANGE`],
/// [`crate::core::problem::FRICTION_COEFFICIENT_RANGE`],
/// [`crate::core::problem::CREEPAGE_RANGE`], [`crate::core::problem::SPIN_RANGE`]).
pub mod ranges {
    use crate::core::error::{Range, UnitHint};

    /// `load.normal_force_n`, `transient.steps[k].normal_force_n` \[N\].
    pub const NORMAL_FORCE: Range = Range::positive(1e8, "N");
    /// `load.normal_force_n_per_m`, `transient.steps[k].normal_force_n_per_m`
    /// \[N/m\] (line contact).
    pub const NORMAL_FORCE_PER_M: Range = Range::positive(1e10, "N/m");
    /// `load.approach_m`, `transient.steps[k].approach_m` \[m\].
    pub const APPROACH: Range = Range::positive(1e-2, "m").hint(UnitHint::Millimetre);
    /// `geometry.a_per_m`, `geometry.b_per_m` \[1/m\] (radii of 5 µm to 500 m).
    pub const CURVATURE: Range = Range::closed(1e-3, 1e5, "1/m");
    /// `geometry.wheel_rolling_radius_m` \[m\].
    pub const ROLLING_RADIUS: Range = Range::closed(0.01, 5.0, "m").hint(UnitHint::Millimetre);
    /// |`geometry.*_lateral_radius_m`| \[m\] (or `inf`: a straight profile).
    pub const LATERAL_RADIUS: Range = Range::closed(1e-4, 1e4, "m");
    /// Coordinates of `geometry.*_points_m` \[m\].
    pub const PROFILE_COORDINATE: Range = Range::symmetric(1.0, "m").hint(UnitHint::Millimetre);
    /// Values of the service's `geometry.extra_gap_m` \[m\].
    pub const EXTRA_GAP: Range = Range::symmetric(1e-2, "m");
    /// Values of `geometry.gap_m` \[m\].
    pub const GAP: Range = Range::symmetric(1.0, "m");
    /// `rolling.force_x_n`, `rolling.force_y_n` \[N\] (a prescribed
    /// tangential force; a solve further needs |F| < mu Fn).
    pub const TANGENTIAL_FORCE: Range = Range::symmetric(1e8, "N");
    /// `rolling.force_x_n_per_m` \[N/m\] (a prescribed tangential force of a
    /// line contact; a solve further needs |F| < mu Fn).
    pub const TANGENTIAL_FORCE_PER_M: Range = Range::symmetric(1e10, "N/m");
    /// `transient.steps[k].shift_x_m`, `shift_y_m` \[m\] (one step).
    pub const SHIFT: Range = Range::symmetric(1e-2, "m").hint(UnitHint::Millimetre);
    /// `transient.steps[k].rotation_rad` \[rad\] (one step).
    pub const ROTATION: Range = Range::symmetric(0.1, "rad");
    /// `transient.steps[k].gap_travel_x_m` \[m\] (one step).
    pub const GAP_TRAVEL: Range = Range::symmetric(1.0, "m").hint(UnitHint::Millimetre);
    /// `transient.rolling_step_m` \[m\] (one step; further a whole number
    /// of elements of the grid).
    pub const ROLLING_STEP: Range = Range::positive(1.0, "m").hint(UnitHint::Millimetre);
    /// `grid.window_x_m`, `grid.window_y_m` \[m\].
    pub const WINDOW: Range = Range::positive(1.0, "m").hint(UnitHint::Millimetre);
    /// `subsurface.shear_yield_stress_pa` \[Pa\] (steel: 300e6 to 600e6).
    pub const SHEAR_YIELD_STRESS: Range = Range::positive(1e11, "Pa");
    /// `solver.normal_tolerance`, `tangential_tolerance`,
    /// `coupling_tolerance` [-].
    pub const TOLERANCE: Range = Range::closed(1e-14, 0.1, "");
    /// Largest `solver.max_iterations`.
    pub const MAX_ITERATIONS: usize = 10_000;
    /// Largest `solver.coupling_max_iterations`.
    pub const MAX_COUPLING_ITERATIONS: usize = 1_000;
    /// Semi-axes of the Hertz patch of a load on the case's geometry and
    /// material \[m\]: outside, a unit is wrong (a force in kN, a
    /// modulus in GPa, a curvature in 1/mm).
    pub const HERTZ_SEMI_AXIS: Range = Range::closed(1e-5, 0.5, "m");
    /// Fewest elements the Hertz patch must span in each direction of a
    /// given window (exact and conformal models).
    pub const MIN_ELEMENTS_ACROSS_PATCH: f64 = 3.0;
}

/// The contact model a case is solved with. In a case file by its
/// [`Model::name`] in any case (`"exact"`, `"Exact"`, `"EXACT"`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, Default)]
#[serde(rename_all = "snake_case", try_from = "String")]
pub enum Model {
    /// Hertz's closed-form normal solution; no tangential forces. On
    /// circular conformal profiles: the paper's Hertz on the flattened
    /// curvatures.
    Hertz,
    /// Hertz with the corrected lateral curvature of conformal contact
    /// (Blanco-Lorenzo et al. 2018, Eq. 5); `conformal_circular` only.
    HertzCorrected,
    /// Kalker's simplified theory (FASTSIM) on the Hertz ellipse.
    Fastsim,
    /// Kalker's exact theory on the half-space (the core solver).
    #[default]
    Exact,
    /// Conformal exact theory (CECT) with Blanco's influence coefficients
    /// (half-space coefficients combined by the orientation difference).
    Cect,
    /// Conformal exact theory with plain half-space coefficients on
    /// curvilinear distances.
    CectHalfspace,
}

impl TryFrom<String> for Model {
    type Error = String;

    /// The model named `name`, in any case.
    fn try_from(name: String) -> Result<Self, String> {
        Model::ALL
            .into_iter()
            .find(|m| m.name().eq_ignore_ascii_case(&name))
            .ok_or_else(|| {
                let names: Vec<_> = Model::ALL.iter().map(|m| m.name()).collect();
                format!(
                    "unknown model \"{name}\"; expected one of {}",
                    names.join(", ")
                )
            })
    }
}

impl Model {
    /// Every model, in the order of the documentation.
    pub const ALL: [Model; 6] = [
        Model::Hertz,
        Model::HertzCorrected,
        Model::Fastsim,
        Model::Exact,
        Model::Cect,
        Model::CectHalfspace,
    ];

    /// The name used in the case file and the JSON output.
    pub fn name(self) -> &'static str {
        match self {
            Model::Hertz => "hertz",
            Model::HertzCorrected => "hertz_corrected",
            Model::Fastsim => "fastsim",
            Model::Exact => "exact",
            Model::Cect => "cect",
            Model::CectHalfspace => "cect_halfspace",
        }
    }

    /// The conformal solver's influence coefficients (`cect`,
    /// `cect_halfspace`); `None` for the other models.
    pub fn influence(self) -> Option<InfluenceModel> {
        match self {
            Model::Cect => Some(InfluenceModel::Blanco),
            Model::CectHalfspace => Some(InfluenceModel::HalfSpace),
            _ => None,
        }
    }

    /// Whether the model is a conformal solver (`cect`, `cect_halfspace`).
    pub fn is_cect(self) -> bool {
        self.influence().is_some()
    }

    /// Whether the model iterates (and reads `[solver]`).
    fn is_iterative(self) -> bool {
        matches!(self, Model::Exact | Model::Cect | Model::CectHalfspace)
    }
}

/// The whole case file, as written.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CaseFile {
    /// Contact model: `"hertz"`, `"hertz_corrected"`, `"fastsim"`,
    /// `"exact"`, `"cect"` or `"cect_halfspace"` (default `"exact"`).
    #[serde(default)]
    pub model: Model,
    /// Elastic materials (required).
    pub material: MaterialSection,
    /// Coulomb friction; required for rolling, transient and FASTSIM cases.
    pub friction: Option<FrictionSection>,
    /// Undeformed geometry of the bodies (required).
    pub geometry: GeometrySection,
    /// Normal load (required; transient steps may override it).
    pub load: LoadSection,
    /// Steady rolling creepages `creepage_long` [-], `creepage_lat` [-],
    /// `spin_per_m` [1/m] (each defaults to 0), or instead of a creepage
    /// the prescribed force `force_x_n` / `force_y_n` \[N\] (exact model);
    /// omit for a static or transient case.
    pub rolling: Option<RollingSection>,
    /// Transient shift steps; alternative to `[rolling]`.
    pub transient: Option<TransientSection>,
    /// Potential contact grid (optional; defaults below).
    pub grid: Option<GridSection>,
    /// Solver tolerances and limits (optional; core defaults).
    pub solver: Option<SolverSection>,
    /// Subsurface stresses of both bodies below the solved patch (exact
    /// model; optional: computed only when present).
    #[serde(default)]
    pub subsurface: Option<SubsurfaceSection>,
    /// Flash temperatures of both surfaces from the frictional heat
    /// (exact model, steady rolling; optional: computed only when present).
    #[serde(default)]
    pub temperature: Option<TemperatureSection>,
    /// Rolling direction chi \[rad\] of steady rolling and of transient
    /// rolling steps, from +x towards +y (CONTACT's `CHI`): a multiple of
    /// pi/2 within 1e-6 rad, 0 (+x, the default), pi/2 (+y), pi (-x) or
    /// 3 pi/2 (-y); a line contact 0 or pi. Exact model only. Creepages,
    /// forces and fields stay in (x, y) (see [`crate::core::problem`]).
    #[serde(default)]
    pub rolling_direction_rad: f64,
    /// Extra rigid slip per element (exact model, rolling; optional).
    #[serde(default)]
    pub extra_rigid_slip: Option<ExtraRigidSlipSection>,
    /// Options of the conformal models (`cect`, `cect_halfspace`;
    /// optional).
    #[serde(default)]
    pub conformal: Option<ConformalSection>,
    /// `[interfacial_layer]`: a third-body layer between the bodies,
    /// elastic or elasto-plastic (CONTACT's M = 4; exact model, see
    /// [`crate::core::layer`]): `thickness_m` \[m\], `shear_modulus_pa`
    /// \[Pa\], optional `yield_limit_pa` \[Pa\] (absent or 0: elastic) and
    /// `hardening_pa_per_m` \[Pa/m\] (absent: 0, perfectly plastic).
    #[serde(default)]
    pub interfacial_layer: Option<InterfacialLayer>,
    /// `[viscoelastic]`: viscoelastic bodies, standard linear solids
    /// (CONTACT's M = 1; exact model, steady rolling in +x or its
    /// frictionless normal problem, see [`crate::core::viscoelastic`]):
    /// `rolling_speed_m_per_s` \[m/s\] and per body `[viscoelastic.body1]`,
    /// `[viscoelastic.body2]` (absent: elastic) with `relaxation_ratio`
    /// f_g = C_v/C_g [-] and `creep_relaxation_time_s` \[s\]. The bodies'
    /// `shear_modulus_pa` are then their initial (glassy) moduli G_g; the
    /// final ones are G_g/(1 + f_g).
    #[serde(default)]
    pub viscoelastic: Option<Viscoelastic>,
    /// `[fastsim]`: the variant model `fastsim` solves (method,
    /// flexibilities, slope reduction and falling friction, traction
    /// bound, strips or CONTACT's grid; see [`FastsimSection`]). Absent:
    /// Kalker's FASTSIM on strips with the parabolic bound.
    #[serde(default)]
    pub fastsim: Option<FastsimSection>,
}

/// A validated case, ready to be solved.
#[derive(Debug, Clone)]
pub struct Case {
    /// The model to run.
    pub model: Model,
    /// Combined materials.
    pub material: CombinedMaterial,
    /// Friction (Coulomb 0 when the case has none: frictionless normal contact).
    pub friction: Friction,
    /// Whether `[friction]` was given.
    pub has_friction: bool,
    /// The geometry (kind and profiles).
    pub geometry: CaseGeometry,
    /// Curvature coefficient A [1/m] (conformal kinds: of the flattened
    /// gap, A = 1/(2 R_xw)).
    pub a_per_m: f64,
    /// Curvature coefficient B [1/m] (conformal kinds: of the flattened
    /// gap, B = (1/R_yr + 1/R_yw)/2).
    pub b_per_m: f64,
    /// The `[load]`.
    pub load: NormalLoad,
    /// Kinematics (frictionless, steady rolling or transient; for the
    /// conformal models transient steps are static compression: zero
    /// shifts, increasing forces).
    pub kinematics: Kinematics,
    /// `transient.rolling_step_m` \[m\]: the distance each rolling step
    /// of a transient case rolls (a whole number of elements); None when
    /// not given.
    pub rolling_step_m: Option<f64>,
    /// Prescribed tangential forces of steady rolling (exact model); the
    /// creepages of their directions in `kinematics` are the iteration's
    /// start.
    pub prescribed_force: PrescribedForce,
    /// The forces prescribed in the transient steps (`transient.steps[k].
    /// force_x_n`, ...), one per step; empty when no step prescribes one.
    pub step_forces: Vec<PrescribedForce>,
    /// Where the undeformed distance has travelled in +x over the grid in
    /// each transient step \[m\] (the sums of `transient.steps[k].
    /// gap_travel_x_m`), one per step; empty when no step gives one.
    pub step_gap_offsets_m: Vec<f64>,
    /// Elements in x.
    pub nx: usize,
    /// Elements in y.
    pub ny: usize,
    /// Window in x \[m\] (given or automatic).
    pub window_x_m: f64,
    /// Window in y \[m\] (given or automatic; along s for the conformal models).
    pub window_y_m: f64,
    /// Solver settings.
    pub settings: SolverSettings,
    /// Remarks for the user (ignored sections and the like).
    pub notes: Vec<String>,
    /// The subsurface stresses to compute after the solve, if asked for.
    pub subsurface: Option<SubsurfaceRequest>,
    /// The flash temperatures to compute after the solve, if asked for.
    pub temperature: Option<ThermalInput>,
    /// Rolling direction chi \[rad\] (`rolling_direction_rad`; exact model).
    pub rolling_direction_rad: f64,
    /// The undeformed distance per element \[m\] (`geometry.gap_m`)
    /// replacing the quadratic one; None: h = A x² + B y².
    pub gap_m: Option<Vec<f64>>,
    /// Extra rigid slip per element (`[extra_rigid_slip]`).
    pub extra_rigid_slip: Option<ExtraRigidSlip>,
    /// Conformal models: where steady rolling takes the rigid velocities
    /// (`conformal.rigid_slip`).
    pub rigid_slip: RigidSlipSurface,
    /// `transient.steady_start`: the transient steps start from the steady
    /// rolling state at these creepages (exact model).
    pub steady_start: Option<Creepages>,
    /// Each transient step's `friction_start`: where its falling law's
    /// iteration starts (None: `friction.start`); empty when no step
    /// gives one.
    pub step_slip_starts: Vec<Option<SlipStart>>,
    /// `material.influence_file`: numerical influence coefficients
    /// replacing the half-space's (exact model); None: the half-space.
    pub numerical_influence: Option<Arc<InfluenceFile>>,
    /// Model `fastsim`: the variant it solves (`[fastsim]`).
    pub fastsim: FastsimOptions,
}

fn bad(key: impl Into<String>, reason: impl Into<String>) -> CaseError {
    CaseError::from(ContactError::invalid(key, reason))
}

impl Case {
    /// Parses and validates a case file's text. Errors are
    /// [`CaseError::BadInput`] and name the offending key.
    pub fn from_toml(text: &str) -> Result<Case, CaseError> {
        Case::from_toml_in(text, Path::new("."))
    }

    /// [`Case::from_toml`] for a case file in directory `dir`: the files
    /// it names (`material.influence_file`) are read relative to it.
    pub fn from_toml_in(text: &str, dir: &Path) -> Result<Case, CaseError> {
        let file: CaseFile = toml::from_str(text)
            .map_err(|e| CaseError::BadInput(format!("case file: {}", e.to_string().trim_end())))?;
        let table = match &file.material.influence_file {
            Some(name) => Some(Arc::new(
                InfluenceFile::read(&dir.join(name))
                    .map_err(|e| bad(NUMERICAL_INFLUENCE_KEY, e.to_string()))?,
            )),
            None => None,
        };
        Case::from_file_with(file, table)
    }

    /// Validates a parsed case file. A body softer than rubber gets a note
    /// ([`soft_modulus_note`]), which a refusal of the case also carries:
    /// a modulus in GPa written as Pa is valid physics, but usually makes
    /// the load's patch absurd.
    /// A file named by `material.influence_file` is refused here (nothing
    /// is read from disk): case files give it ([`Case::from_toml_in`]).
    pub fn from_file(file: CaseFile) -> Result<Case, CaseError> {
        if file.material.influence_file.is_some() {
            return Err(bad(
                NUMERICAL_INFLUENCE_KEY,
                "a file of influence coefficients is read from case files only (railcontact solve)",
            ));
        }
        Case::from_file_with(file, None)
    }

    /// [`Case::from_file`] with numerical influence coefficients already
    /// read (e.g. sent inline to the service rather than named as a file):
    /// validated as [`Case::from_toml_in`] validates the file it reads,
    /// errors naming [`NUMERICAL_INFLUENCE_KEY`]. `file` must name no file
    /// (`material.influence_file`), which is refused here as by
    /// [`Case::from_file`].
    pub fn from_file_with_influence(
        file: CaseFile,
        table: Arc<InfluenceFile>,
    ) -> Result<Case, CaseError> {
        if file.material.influence_file.is_some() {
            return Case::from_file(file);
        }
        Case::from_file_with(file, Some(table))
    }

    fn from_file_with(
        file: CaseFile,
        table: Option<Arc<InfluenceFile>>,
    ) -> Result<Case, CaseError> {
        let material = file.material.combine()?;
        let bodies = if file.material.body1.is_some() {
            vec![
                ("material.body1.shear_modulus_pa", material.body1),
                ("material.body2.shear_modulus_pa", material.body2),
            ]
        } else {
            vec![("material.shear_modulus_pa", material.body1)]
        };
        let soft: Vec<String> = bodies
            .into_iter()
            .filter_map(|(key, m)| soft_modulus_note(key, m.shear_modulus_pa))
            .collect();
        match Case::validate(file, material, table, soft.clone()) {
            Err(CaseError::BadInput(m)) if !soft.is_empty() => Err(CaseError::BadInput(format!(
                "{m} (note: {})",
                soft.join("; ")
            ))),
            r => r,
        }
    }

    fn validate(
        file: CaseFile,
        material: CombinedMaterial,
        numerical_influence: Option<Arc<InfluenceFile>>,
        mut notes: Vec<String>,
    ) -> Result<Case, CaseError> {
        let model = file.model;
        if numerical_influence.is_some() && model != Model::Exact {
            return Err(bad(
                NUMERICAL_INFLUENCE_KEY,
                format!(
                    "numerical influence coefficients are taken by model = \"exact\" only, not by \"{}\"",
                    model.name()
                ),
            ));
        }

        let (geometry, a_per_m, b_per_m) = file.geometry.validate()?;
        check_model_geometry(model, &geometry)?;
        let line = geometry.is_line();
        if geometry.is_conformal() && matches!(model, Model::Exact | Model::Fastsim) {
            notes.push(format!(
                "the {} model runs on the flattened quadratic gap h = A x² + B y², A = 1/(2 R_xw) = {a_per_m:.6} 1/m, \
                 B = (1/R_yr + 1/R_yw)/2 = {b_per_m:.6} 1/m: no conformal effects",
                model.name()
            ));
        }

        let l = &file.load;
        let load = one_load(
            "load",
            l.normal_force_n,
            l.normal_force_n_per_m,
            l.approach_m,
            line,
        )?
        .ok_or_else(|| {
            let force = if line {
                "normal_force_n_per_m"
            } else {
                "normal_force_n"
            };
            bad(
                format!("load.{force}"),
                format!("missing: give `load.{force}` or `load.approach_m`"),
            )
        })?;

        let CaseMotion {
            kinematics,
            prescribed_force,
            step_forces,
            step_gap_offsets_m,
            steady_start,
            step_slip_starts,
        } = case_motion(&file, model, load, line)?;

        let needs_friction = needs_friction(model, &kinematics);
        let (friction, has_friction) =
            case_friction(file.friction.as_ref(), model, needs_friction)?;
        if friction.slip_velocity_law.is_none() {
            if let Some(k) = step_slip_starts.iter().position(Option::is_some) {
                return Err(bad(
                    format!("transient.steps[{k}].friction_start"),
                    "belongs to a falling law: set `friction.law` to \"linear\", \"rational\" or \"exponential\"",
                ));
            }
        }

        match model {
            Model::Hertz | Model::HertzCorrected => {
                if file.rolling.is_some() || file.transient.is_some() {
                    notes.push(format!(
                        "the {} model solves the normal problem only: [rolling]/[transient] ignored",
                        model.name()
                    ));
                }
                if let (Model::HertzCorrected, NormalLoad::Approach(_)) = (model, load) {
                    return Err(bad(
                        "load.approach_m",
                        "the hertz_corrected model (paper Eq. 5) starts from a normal force: give `load.normal_force_n`",
                    ));
                }
            }
            Model::Fastsim => {
                if file.transient.is_some() {
                    return Err(bad(
                        "transient",
                        "the FASTSIM model does steady rolling only; use `[rolling]`",
                    ));
                }
                if file.rolling.is_none() {
                    return Err(bad(
                        "rolling",
                        "missing: the FASTSIM model needs `[rolling]` creepages",
                    ));
                }
            }
            Model::Exact | Model::Cect | Model::CectHalfspace => {
                if file.friction.is_some() && matches!(kinematics, Kinematics::Frictionless) {
                    notes.push("static case without [rolling]/[transient]: frictionless normal contact, [friction] unused".into());
                }
            }
        }
        if model.is_cect() && needs_friction {
            if let Kinematics::Transient(steps) = &kinematics {
                if let Some(NormalLoad::NormalForce(last)) = steps.last().map(|s| s.load) {
                    if load != NormalLoad::NormalForce(last) {
                        notes.push(
                            "static compression follows the steps' normal_force_n: [load] unused"
                                .into(),
                        );
                    }
                }
            }
        }

        let direction = rolling_direction(&file, model, line)?;
        let CaseGrid {
            nx,
            ny,
            window_x_m,
            window_y_m,
        } = case_grid(
            &file,
            model,
            &geometry,
            [a_per_m, b_per_m],
            &material,
            &kinematics,
            load,
            &direction,
            &mut notes,
        )?;
        let grid_given = file.grid.unwrap_or_default();
        let mut settings = solver_settings(file.solver, model, &mut notes)?;

        let temperature = file
            .temperature
            .as_ref()
            .map(|t| temperature_request(t, model, &kinematics))
            .transpose()?;
        let gap_m = given_gap(&file, model, &geometry, [nx, ny], grid_given)?;
        let extra_rigid_slip = extra_rigid_slip(&file, model, &kinematics, [nx, ny], grid_given)?;
        let rigid_slip = conformal_options(file.conformal, model, &kinematics, &mut notes)?;
        settings.interfacial_layer = interfacial_layer(
            file.interfacial_layer,
            model,
            &friction,
            &kinematics,
            &mut notes,
        )?;
        settings.viscoelastic = viscoelastic(
            file.viscoelastic,
            model,
            &kinematics,
            file.rolling_direction_rad,
        )?;
        let fastsim = fastsim_options(
            file.fastsim,
            model,
            &friction,
            file.rolling_direction_rad,
            &mut notes,
        )?;
        if let Some(visc) = &settings.viscoelastic {
            // Before any solver integrates the coefficients (seconds).
            check_viscoelastic_grid(visc, nx, ny, geometry.is_line())?;
        }
        let mut case = Case {
            rolling_direction_rad: file.rolling_direction_rad,
            gap_m,
            extra_rigid_slip,
            rolling_step_m: file.transient.as_ref().and_then(|t| t.rolling_step_m),
            model,
            material,
            friction,
            has_friction,
            prescribed_force,
            step_forces,
            step_gap_offsets_m,
            steady_start,
            step_slip_starts,
            geometry,
            a_per_m,
            b_per_m,
            load,
            kinematics,
            nx,
            ny,
            window_x_m,
            window_y_m,
            settings,
            notes,
            subsurface: file
                .subsurface
                .as_ref()
                .map(|s| s.request(model))
                .transpose()?,
            temperature,
            rigid_slip,
            numerical_influence,
            fastsim,
        };
        if let Some(t) = case.numerical_influence.clone() {
            // The file against the grid and the problem (element sizes,
            // its kind, line contact, layer, rolling direction) when the
            // case is read, before a solve.
            case.problem()?.validate()?;
            let (mx, my) = t.size();
            let note = format!(
                "material.influence_file: the influence coefficients are the file's (nmatrix = {}, \
                 mxfile x myfile = {mx} x {my}), not the half-space's",
                t.matrices()
            );
            case.notes.push(note);
        }
        Ok(case)
    }

    /// The potential contact grid of the exact model (one row for a line
    /// contact, [`Grid::line`]).
    pub fn grid(&self) -> Result<Grid, CaseError> {
        if self.geometry.is_line() {
            return Ok(Grid::line(self.nx, self.window_x_m)?);
        }
        Ok(Grid::centered(
            self.nx,
            self.ny,
            self.window_x_m,
            self.window_y_m,
        )?)
    }

    /// The core contact problem (exact model).
    pub fn problem(&self) -> Result<ContactProblem, CaseError> {
        let grid = self.grid()?;
        Ok(ContactProblem {
            material: self.material,
            friction: self.friction,
            grid,
            gap_m: match &self.gap_m {
                Some(h) => h.clone(),
                None => ContactProblem::quadratic_gap(&grid, self.a_per_m, self.b_per_m),
            },
            load: self.load,
            kinematics: self.kinematics.clone(),
            settings: self.settings,
            rolling_direction_rad: self.rolling_direction_rad,
            extra_rigid_slip: self.extra_rigid_slip.clone(),
            numerical_influence: self.numerical_influence.clone(),
        })
    }

    /// The Hertz solution of the case's geometry and `[load]`.
    pub fn hertz(&self) -> Result<HertzSolution, CaseError> {
        hertz_of(
            self.a_per_m,
            self.b_per_m,
            self.material.effective_modulus_pa(),
            self.load,
        )
    }

    /// The creepages of a rolling case (zero otherwise).
    pub fn creepages(&self) -> Creepages {
        match &self.kinematics {
            Kinematics::SteadyRolling(c) => *c,
            _ => Creepages::default(),
        }
    }

    /// The (x, s) grid and the conformal geometry of a conformal case.
    pub fn conformal_geometry(&self) -> Result<ConformalGeometry, CaseError> {
        self.geometry.conformal(self.grid()?)
    }

    /// What the conformal models solve: `None` for frictionless normal
    /// contact (no `[rolling]`, no `[transient]`), else static compression
    /// through the steps' forces or steady rolling at the `[load]`'s force.
    pub fn conformal_kinematics(&self) -> Result<Option<ConformalKinematics>, CaseError> {
        let force = |load: NormalLoad, key: &str| match load {
            NormalLoad::NormalForce(f) => Ok(f),
            NormalLoad::Approach(_) => Err(bad(
                format!("{key}.approach_m"),
                "the frictional conformal models need a normal force: give `normal_force_n`",
            )),
        };
        Ok(match &self.kinematics {
            Kinematics::Frictionless => None,
            Kinematics::SteadyRolling(c) => Some(ConformalKinematics::SteadyRolling {
                normal_force_n: force(self.load, "load")?,
                creepages: ConformalCreepages {
                    creepage_long: c.creepage_long,
                    creepage_lat: c.creepage_lat,
                    spin_per_m: c.spin_per_m,
                },
            }),
            Kinematics::Transient(steps) => Some(ConformalKinematics::StaticCompression(
                steps
                    .iter()
                    .enumerate()
                    .map(|(k, s)| force(s.load, &format!("transient.steps[{k}]")))
                    .collect::<Result<_, _>>()?,
            )),
        })
    }

    /// Solver settings of the frictional conformal models.
    pub fn conformal_settings(&self) -> ConformalSettings {
        let s = &self.settings;
        let mut c = ConformalSettings {
            normal: s.normal,
            tangential: s.tangential,
            rigid_slip: self.rigid_slip,
            ..ConformalSettings::default()
        };
        if s.coupling_tolerance > 0.0 {
            c.coupling_tolerance = s.coupling_tolerance;
        }
        if s.coupling_max_iterations > 0 {
            c.coupling_max_iterations = s.coupling_max_iterations;
        }
        c
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::friclaw::{FallingShape, SlipStart, DEFAULT_LAW_ITERATIONS};
    use crate::core::problem::ShiftStep;
    use crate::core::solution::SolveStatus;

    const CASE_1: &str = r#"
model = "cect"
[material]
shear_modulus_pa = 81.0e9
poisson_ratio = 0.30
[geometry]
kind = "conformal_circular"
rail_lateral_radius_m = 0.010
wheel_lateral_radius_m = -0.0101
wheel_rolling_radius_m = 0.5
[load]
normal_force_n = 80000.0
"#;

    pub(super) fn bad_key(text: &str) -> String {
        match Case::from_toml(text) {
            Err(CaseError::BadInput(m)) => m,
            other => panic!("expected bad input, got {other:?}"),
        }
    }

    /// Profiles that do not touch in one point: the concave one is named.
    #[test]
    fn a_non_touching_conformal_pair_names_its_concave_profile() {
        let concave_rail = CASE_1.replace(
            "rail_lateral_radius_m = 0.010",
            "rail_lateral_radius_m = -1.0",
        );
        let m = bad_key(&concave_rail);
        assert!(
            m.contains("`geometry.rail_lateral_radius_m`") && m.contains("concave rail"),
            "{m}"
        );
        let narrow_wheel = CASE_1.replace("-0.0101", "-0.0099");
        let m = bad_key(&narrow_wheel);
        assert!(
            m.contains("`geometry.wheel_lateral_radius_m`") && m.contains("concave wheel"),
            "{m}"
        );
    }

    #[test]
    fn model_names_round_trip() {
        for m in Model::ALL {
            // With friction and rolling, which FASTSIM needs.
            let text = format!(
                "{}[friction]\ncoefficient = 0.3\n[rolling]\ncreepage_long = 1e-3\n",
                CASE_1.replace("\"cect\"", &format!("\"{}\"", m.name()))
            );
            let model = match Case::from_toml(&text) {
                Ok(c) => c.model,
                // Every model parses; only its checks may fail.
                Err(e) => panic!("{}: {e}", m.name()),
            };
            assert_eq!(model, m);
        }
        assert_eq!(
            Model::CectHalfspace.influence(),
            Some(InfluenceModel::HalfSpace)
        );
        assert_eq!(Model::Cect.influence(), Some(InfluenceModel::Blanco));
        assert!(!Model::HertzCorrected.is_cect());
    }

    #[test]
    fn circular_profiles_flatten_and_size_the_window() {
        let c = Case::from_toml(CASE_1).unwrap();
        assert!(c.geometry.is_conformal());
        assert!((c.a_per_m - 1.0).abs() < 1e-12);
        assert!((c.b_per_m - 0.5 * (100.0 - 1.0 / 0.0101)).abs() < 1e-12);
        assert_eq!((c.nx, c.ny), (64, 64));
        assert_eq!(c.conformal_kinematics().unwrap(), None);
        let h = c.hertz().unwrap();
        assert!((c.window_x_m / (3.2 * h.semi_axis_x_m) - 1.0).abs() < 1e-12);
        assert!((c.window_y_m / (2.6 * h.semi_axis_y_m) - 1.0).abs() < 1e-12);
        // A much heavier load: the lateral window stops at +-75° of arc.
        let heavy = Case::from_toml(&CASE_1.replace("80000.0", "800000.0")).unwrap();
        let cap = 2.0 * 75f64.to_radians() * 0.5 * (0.010 + 0.0101);
        assert!((heavy.window_y_m / cap - 1.0).abs() < 1e-12);
        let geo = c.conformal_geometry().unwrap();
        assert_eq!(geo.delta_rad.len(), 64);
    }

    #[test]
    fn kinematics_of_the_conformal_models() {
        let rolling = format!(
            "{CASE_1}[friction]\ncoefficient = 0.3\n[rolling]\ncreepage_long = 1e-3\nspin_per_m = 0.5\n"
        );
        let c = Case::from_toml(&rolling).unwrap();
        match c.conformal_kinematics().unwrap() {
            Some(ConformalKinematics::SteadyRolling {
                normal_force_n,
                creepages,
            }) => {
                assert_eq!(normal_force_n, 80e3);
                assert_eq!(creepages.creepage_long, 1e-3);
                assert_eq!(creepages.spin_per_m, 0.5);
            }
            other => panic!("{other:?}"),
        }
        let stat = format!(
            "{CASE_1}[friction]\ncoefficient = 0.3\n[transient]\nsteps = [{{ normal_force_n = 1e4 }}, {{ normal_force_n = 3e4, shift_y_m = 0.0 }}]\n"
        );
        let c = Case::from_toml(&stat).unwrap();
        assert_eq!(
            c.conformal_kinematics().unwrap(),
            Some(ConformalKinematics::StaticCompression(vec![1e4, 3e4]))
        );
        // The windows follow the largest step, and [load] is unused.
        assert!(c.notes.iter().any(|n| n.contains("[load] unused")));
        let m = bad_key(&stat.replace("3e4", "5e3"));
        assert!(m.contains("`transient.steps[1].normal_force_n`"), "{m}");
        let m = bad_key(&stat.replace("shift_y_m = 0.0", "shift_y_m = 1e-6"));
        assert!(m.contains("`transient.steps[1].shift_y_m`"), "{m}");
        let m = bad_key(&stat.replace("{ normal_force_n = 1e4 }", "{ approach_m = 1e-5 }"));
        assert!(m.contains("`transient.steps[0].approach_m`"), "{m}");
    }

    #[test]
    fn the_conformal_section_chooses_the_rigid_slip_of_the_conformal_models() {
        let rolling =
            format!("{CASE_1}[friction]\ncoefficient = 0.3\n[rolling]\ncreepage_long = 1e-3\n");
        let c = Case::from_toml(&rolling).unwrap();
        assert_eq!(c.rigid_slip, RigidSlipSurface::ActualSurface);
        assert_eq!(
            c.conformal_settings().rigid_slip,
            RigidSlipSurface::ActualSurface
        );
        let chosen = format!("{rolling}[conformal]\nrigid_slip = \"reference_section\"\n");
        let c = Case::from_toml(&chosen).unwrap();
        assert_eq!(
            c.conformal_settings().rigid_slip,
            RigidSlipSurface::ReferenceSection
        );
        assert!(c.notes.iter().all(|n| !n.contains("rigid_slip")));
        let m = bad_key(&chosen.replace("reference_section", "midway"));
        assert!(
            m.contains("rigid_slip") && m.contains("actual_surface"),
            "{m}"
        );
        let m = bad_key(&chosen.replace("rigid_slip", "rigid"));
        assert!(m.contains("rigid"), "{m}");
        let m = bad_key(&chosen.replace("model = \"cect\"", "model = \"hertz\""));
        assert!(m.contains("`conformal`") && m.contains("hertz"), "{m}");
        // Without rolling the choice is unused, and a note says so.
        let c = Case::from_toml(&format!(
            "{CASE_1}[conformal]\nrigid_slip = \"actual_surface\"\n"
        ))
        .unwrap();
        assert!(c.notes.iter().any(|n| n.contains("conformal.rigid_slip")));
    }

    #[test]
    fn geometry_keys_are_checked_per_kind() {
        let m = bad_key(&CASE_1.replace("wheel_rolling_radius_m = 0.5", ""));
        assert!(m.contains("`geometry.wheel_rolling_radius_m`") && m.contains("missing"));
        let m = bad_key(&CASE_1.replace("conformal_circular", "quadratic"));
        assert!(m.contains("`geometry.rail_lateral_radius_m`"), "{m}");
        let m = bad_key(&CASE_1.replace("conformal_circular", "conformal_points"));
        assert!(m.contains("`geometry.rail_lateral_radius_m`"), "{m}");
        let m = bad_key(&CASE_1.replace(
            "rail_lateral_radius_m = 0.010",
            "rail_lateral_radius_m = nan",
        ));
        assert!(m.contains("`geometry.rail_lateral_radius_m`"), "{m}");
        let m = bad_key(
            &CASE_1
                .replace("\"cect\"", "\"hertz_corrected\"")
                .replace("normal_force_n = 80000.0", "approach_m = 7e-5"),
        );
        assert!(m.contains("`load.approach_m`"), "{m}");
    }

    fn arc(k: f64, n: i64, step: f64) -> Vec<[f64; 2]> {
        (-n..=n)
            .map(|i| {
                let t = i as f64 * step;
                [(k * t).sin() / k, (1.0 - (k * t).cos()) / k]
            })
            .collect()
    }

    fn points_section(rail: &[[f64; 2]], wheel: &[[f64; 2]]) -> GeometrySection {
        GeometrySection {
            kind: GeometryKind::ConformalPoints,
            a_per_m: None,
            b_per_m: None,
            rail_lateral_radius_m: None,
            wheel_lateral_radius_m: None,
            wheel_rolling_radius_m: Some(0.5),
            rail_points_m: Some(rail.to_vec()),
            wheel_points_m: Some(wheel.to_vec()),
            gap_m: None,
        }
    }

    #[test]
    fn points_give_the_curvatures_at_the_origin() {
        let (rail, wheel) = (arc(100.0, 60, 2.5e-4), arc(1.0 / 0.0101, 60, 2.5e-4));
        let (g, a, b) = points_section(&rail, &wheel).validate().unwrap();
        let (rr, rw, rx) = g.radii().unwrap();
        assert!((rr / 0.010 - 1.0).abs() < 1e-3, "{rr}");
        assert!((rw / -0.0101 - 1.0).abs() < 1e-3, "{rw}");
        assert_eq!(rx, 0.5);
        assert_eq!(a, 1.0);
        assert!(
            (b / (0.5 * (100.0 - 1.0 / 0.0101)) - 1.0).abs() < 0.05,
            "{b}"
        );
        // Reversed order, a profile missing the origin, crossing profiles.
        let rev: Vec<[f64; 2]> = rail.iter().rev().cloned().collect();
        let err = |r: &[[f64; 2]], w: &[[f64; 2]]| match points_section(r, w).validate() {
            Err(CaseError::BadInput(m)) => m,
            other => panic!("{other:?}"),
        };
        assert!(err(&rev, &wheel).contains("increasing y"));
        let off: Vec<[f64; 2]> = rail.iter().map(|p| [p[0] + 1e-4, p[1]]).collect();
        assert!(err(&off, &wheel).contains("`geometry.rail_points_m`"));
        let tilted: Vec<[f64; 2]> = wheel.iter().map(|p| [p[0], p[1] + 0.1 * p[0]]).collect();
        assert!(err(&rail, &tilted).contains("`geometry.wheel_points_m`"));
        assert!(err(&wheel, &rail).contains("do not touch"));
    }

    pub(super) const ROLLING: &str = r#"
[material]
shear_modulus_pa = 81.0e9
poisson_ratio = 0.30
[friction]
coefficient = 0.3
[geometry]
kind = "quadratic"
a_per_m = 2.6
b_per_m = 0.92
[load]
normal_force_n = 10000.0
[rolling]
creepage_long = 0.001
[grid]
nx = 16
ny = 16
"#;

    #[test]
    fn transient_rolling_steps_read_from_a_case_file() {
        let text = include_str!("../../../../../examples/cases/transient_rolling.toml");
        let c = Case::from_toml(text).unwrap();
        let Kinematics::Transient(steps) = &c.kinematics else {
            panic!("{:?}", c.kinematics)
        };
        assert_eq!(steps.len(), 9);
        assert_eq!((steps[0].rolling_m, steps[0].shift_x_m), (0.0, 1.774e-5));
        assert_eq!(
            steps[1],
            ShiftStep::rolling(
                c.load,
                2.5e-4,
                &Creepages {
                    creepage_long: 1.824e-3,
                    ..Creepages::default()
                }
            )
        );
        c.problem().unwrap().validate().unwrap();
        // The rolling distance and the step's kind, each named when wrong.
        let steps_at = text.find("steps = [").unwrap();
        for (from, to, key) in [
            (
                "rolling_step_m = 2.5e-4",
                "rolling_step_m = 3.0e-4",
                "`transient.rolling_step_m`",
            ),
            (
                "rolling_step_m = 2.5e-4",
                "rolling_step_m = 1e-9",
                "`transient.rolling_step_m`",
            ),
            ("rolling_step_m = 2.5e-4", "", "`transient.rolling_step_m`"),
            (
                "rolling_step_m = 2.5e-4",
                "rolling_step_m = -2.5e-4",
                "`transient.rolling_step_m`",
            ),
            (
                "{ creepage_long = 1.824e-3 }",
                "{ creepage_long = 1.824e-3, shift_x_m = 1e-6 }",
                "`transient.steps[1].shift_x_m`",
            ),
            (
                "{ creepage_long = 1.882e-3 }",
                "{ creepage_long = 2.0 }",
                "`transient.steps[2].creepage_long`",
            ),
            (
                "{ creepage_long = 1.882e-3 }",
                "{ normal_force_n = 0.5 }",
                "`transient.steps[2].shift_x_m`",
            ),
        ] {
            let (head, tail) = text.split_at(steps_at);
            let changed = if from.starts_with("rolling") {
                format!("{}{tail}", head.replace(from, to))
            } else {
                format!("{head}{}", tail.replace(from, to))
            };
            let m = bad_key(&changed);
            assert!(m.contains(key), "{to}: {m}");
        }
        // The conformal models compress statically: no rolling.
        let m = bad_key(&format!(
            "{CASE_1}[friction]\ncoefficient = 0.3\n[transient]\n\
             steps = [{{ normal_force_n = 8e4, creepage_long = 1e-3 }}]\n"
        ));
        assert!(m.contains("`transient.steps[0].creepage_long`"), "{m}");
    }

    #[test]
    fn every_key_has_a_range_that_the_message_states() {
        for (from, to, key, says) in [
            (
                "creepage_long = 0.001",
                "creepage_long = 1e300",
                "rolling.creepage_long",
                "[-1, 1], got 1e300",
            ),
            (
                "coefficient = 0.3",
                "coefficient = 1e300",
                "friction.coefficient",
                "[0, 5], got 1e300",
            ),
            (
                "normal_force_n = 10000.0",
                "normal_force_n = 1e300",
                "load.normal_force_n",
                "(0, 1e8] N, got 1e300",
            ),
            (
                "a_per_m = 2.6",
                "a_per_m = 1e300",
                "geometry.a_per_m",
                "[0.001, 1e5] 1/m",
            ),
            (
                "ny = 16",
                "ny = 16\nwindow_x_m = 1e300",
                "grid.window_x_m",
                "(0, 1] m, got 1e300",
            ),
            (
                "ny = 16",
                "ny = 16\n[solver]\nmax_iterations = 4294967295",
                "solver.max_iterations",
                "[1, 10000], got 4294967295",
            ),
            (
                "ny = 16",
                "ny = 16\n[solver]\nnormal_tolerance = 5e-324",
                "solver.normal_tolerance",
                "[1e-14, 0.1], got 5e-324",
            ),
            (
                "ny = 16",
                "ny = 16\n[solver]\ncoupling_tolerance = 0.5",
                "solver.coupling_tolerance",
                "got 0.5",
            ),
            (
                "ny = 16",
                "ny = 16\n[solver]\ncoupling_max_iterations = 100000",
                "solver.coupling_max_iterations",
                "[1, 1000]",
            ),
        ] {
            let m = bad_key(&ROLLING.replace(from, to));
            assert!(
                m.contains(&format!("`{key}`")) && m.contains(says),
                "{key}: {m}"
            );
            assert!(m.len() < 300, "{m}");
        }
    }

    #[test]
    fn likely_unit_mistakes_are_named() {
        // A modulus in GPa: valid physics (a gel), but this load's patch
        // would be metres long; the refusal names the likely unit.
        let m = bad_key(&ROLLING.replace("81.0e9", "81"));
        assert!(
            m.contains("check the units")
                && m.contains("`material.shear_modulus_pa` = 81 Pa")
                && m.contains("if it is in GPa, write 8.1e10"),
            "{m}"
        );
        // A soft body whose load suits it: solved, with the note.
        let soft = ROLLING
            .replace("81.0e9", "5e5")
            .replace("normal_force_n = 10000.0", "normal_force_n = 0.01");
        let c = Case::from_toml(&soft).unwrap();
        assert!(
            c.notes.iter().any(|n| n.contains("5e5 Pa (0.5 MPa)")),
            "{:?}",
            c.notes
        );
        // Steel has none.
        let c = Case::from_toml(ROLLING).unwrap();
        assert!(!c.notes.iter().any(|n| n.contains("shear_modulus")));
        // A rolling radius in mm.
        let m = bad_key(&CASE_1.replace(
            "wheel_rolling_radius_m = 0.5",
            "wheel_rolling_radius_m = 460",
        ));
        assert!(
            m.contains("`geometry.wheel_rolling_radius_m`") && m.contains("did you mean 0.46 m"),
            "{m}"
        );
        // A window in mm: the patch spans less than one element.
        let m = bad_key(&ROLLING.replace("ny = 16", "ny = 16\nwindow_x_m = 0.9"));
        assert!(
            m.contains("`grid.window_x_m`") && m.contains("grid.nx = 16"),
            "{m}"
        );
        // A patch of metres: a force in the wrong unit on the geometry.
        let m = bad_key(
            &ROLLING
                .replace("a_per_m = 2.6", "a_per_m = 1e-3")
                .replace("10000.0", "1e8"),
        );
        assert!(
            m.contains("`load.normal_force_n`") && m.contains("check the units"),
            "{m}"
        );
    }

    #[test]
    fn a_falling_law_reads_from_the_friction_section() {
        let falling = "law = \"exponential\"\nkinetic_coefficient = 0.18\n\
                       falling_coefficients = [0.12]\nhalf_velocities_m_per_s = [0.1]\n\
                       rolling_speed_m_per_s = 45.0\nstart = \"sliding\"";
        let text = ROLLING.replace("coefficient = 0.3", falling);
        let case = Case::from_toml(&text).unwrap();
        let law = case.friction.slip_velocity_law.unwrap();
        assert_eq!(law.shape, FallingShape::Exponential);
        assert_eq!(law.falling_coefficients, [0.12, 0.0]);
        assert_eq!(law.start, SlipStart::Sliding);
        assert_eq!(law.max_iterations, DEFAULT_LAW_ITERATIONS);
        assert!((case.friction.static_coefficient - 0.30).abs() < 1e-15);
        let s = crate::core::solve::solve(&case.problem().unwrap()).unwrap();
        assert_eq!(s[0].info.status, SolveStatus::Converged, "{:?}", s[0].info);
        // Refusals name the key.
        for (change, key) in [
            (("law = \"exponential\"", "law = \"quadratic\""), "law"),
            (
                ("falling_coefficients = [0.12]", ""),
                "`friction.falling_coefficients`",
            ),
            (
                (
                    "half_velocities_m_per_s = [0.1]",
                    "half_velocities_m_per_s = [0.1, 1.0]",
                ),
                "`friction.half_velocities_m_per_s`",
            ),
            (
                ("rolling_speed_m_per_s = 45.0", ""),
                "`friction.rolling_speed_m_per_s`",
            ),
            (
                ("kinetic_coefficient = 0.18", "coefficient = 0.18"),
                "`friction.coefficient`",
            ),
            (
                ("start = \"sliding\"", "max_iterations = 0"),
                "`friction.max_iterations`",
            ),
            (
                (
                    "rolling_speed_m_per_s = 45.0",
                    "rolling_speed_m_per_s = -45.0",
                ),
                "`friction.rolling_speed_m_per_s`",
            ),
        ] {
            let m = bad_key(&text.replace(change.0, change.1));
            assert!(m.contains(key), "{change:?}: {m}");
        }
        // Falling-law keys need a falling law; other models refuse the law.
        let m = bad_key(&ROLLING.replace(
            "coefficient = 0.3",
            "coefficient = 0.3\nstart = \"sticking\"",
        ));
        assert!(m.contains("`friction.start`"), "{m}");
        let m = bad_key(&format!("model = \"fastsim\"\n{text}"));
        assert!(m.contains("`friction.law`"), "{m}");
    }

    #[test]
    fn static_and_kinetic_pairs_solve_in_steady_rolling() {
        let text = ROLLING.replace(
            "coefficient = 0.3",
            "static_coefficient = 0.35\nkinetic_coefficient = 0.0",
        );
        let case = Case::from_toml(&text).unwrap();
        let s = crate::core::solve::solve(&case.problem().unwrap()).unwrap();
        let t = &s[0].totals;
        for v in [t.fx_n, t.fy_n, t.mz_nm, t.tgamma_n, t.frictional_work_j] {
            assert!(v.is_finite(), "{t:?}");
        }
        // The adhesion zone carries traction, the slip zone none.
        assert!(
            t.fx_n.abs() > 0.0 && t.fx_n.abs() < 0.35 * t.normal_force_n,
            "{t:?}"
        );
    }
}
