//! The case file of `railcontact solve`: its TOML schema and its validation.
//!
//! All values are in SI units. Every table rejects unknown keys. See
//! `examples/cases/README.md` for a commented list of the keys and
//! [`CaseFile`] for the schema; [`Case::from_toml`] parses and validates a
//! file into a [`Case`] that the models can run without further checks.

use serde::{Deserialize, Serialize};

use crate::conformal::frictional::{ConformalKinematics, ConformalSettings};
use crate::conformal::geometry::{
    Circle, ConformalCreepages, ConformalGeometry, Curve, PointCurve, RigidSlipSurface,
};
use crate::conformal::operator::InfluenceModel;
use crate::core::error::{check_count, show, ContactError, Range};
use crate::core::force::PrescribedForce;
use crate::core::frame::{axis_turns, direction, Direction, RollingFrame, ROLLING_DIRECTION_KEY};
use crate::core::friclaw::{FallingShape, SlipStart, SlipVelocityLaw, DEFAULT_LAW_ITERATIONS};
use crate::core::grid::{Grid, MIN_ELEMENTS};
use crate::core::hertz::HertzSolution;
use crate::core::influence::{LINE_LENGTH_M, LINE_REFERENCE_DISTANCE_M};
use crate::core::layer::InterfacialLayer;
use crate::core::material::{soft_modulus_note, CombinedMaterial, Material};
use crate::core::normal::NormalLoad;
use crate::core::normal::NormalSettings;
use crate::core::problem::{
    check_viscoelastic_grid, rolling_elements, ContactProblem, Creepages, ExtraRigidSlip, Friction,
    Kinematics, ShiftStep, SolverSettings, CREEPAGE_RANGE, INTERFACIAL_LAYER_KEY, SPIN_RANGE,
    VISCOELASTIC_KEY,
};
use crate::core::tangential::TangentialSettings;
use crate::core::temperature::ThermalInput;
use crate::core::viscoelastic::Viscoelastic;
use crate::problem::reference_models::hertz_of;
use crate::problem::CaseError;
use crate::wheelrail::friction::{FrictionAxis, FrictionTable};
use crate::wheelrail::WheelRailError;

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
}

/// `[extra_rigid_slip]`: a rigid slip [-] added at each element to the
/// creepages' rigid slip w = (xi - phi y, eta + phi x), CONTACT's `EXRHS`
/// of a rolling case (E = 9): `slip_x` and `slip_y`, each nx * ny values
/// with index iy * nx + ix (x fastest) in [-1, 1]; and a rigid shift
/// \[m\] added at each element to the shift of every transient shift step,
/// `EXRHS` of a shift case: `shift_x_m` and `shift_y_m`, in [-0.01, 0.01]
/// m. One component of a pair may be left out (zeros). Exact model; steady
/// rolling and rolling steps need the slip (a rolling step of dq adds dq
/// times it to the rigid shift), shift steps the shift; the grid's `nx`
/// and `ny` must be given.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExtraRigidSlipSection {
    /// x component per element [-].
    pub slip_x: Option<Vec<f64>>,
    /// y component per element [-].
    pub slip_y: Option<Vec<f64>>,
    /// x component of each shift step's extra shift per element \[m\].
    pub shift_x_m: Option<Vec<f64>>,
    /// y component of each shift step's extra shift per element \[m\].
    pub shift_y_m: Option<Vec<f64>>,
}

/// `[conformal]`: options of the conformal models (`cect`,
/// `cect_halfspace`).
#[derive(Debug, Clone, Copy, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct ConformalSection {
    /// Where steady rolling takes the bodies' rigid velocities:
    /// `"actual_surface"` (default; the wheel's material point on each
    /// element's normal, slip along the surface where the bodies meet, as
    /// CONTACT does) or `"reference_section"` (the reference-curve point of
    /// the section x = 0 for every x, slip along x). See
    /// [`RigidSlipSurface`].
    pub rigid_slip: Option<RigidSlipSurface>,
}

/// `[temperature]`: the rolling speed `rolling_speed_m_per_s` \[m/s\] and
/// the tables `[temperature.body1]`, `[temperature.body2]`, each with
/// `bulk_temperature_k` \[K\], `conductivity_w_per_m_k` \[W/(m K)\],
/// `density_kg_per_m3` \[kg/m³\] and `specific_heat_j_per_kg_k` \[J/(kg
/// K)\] (all required; ranges in [`crate::core::temperature`]). The flash
/// temperatures follow Ertz & Knothe's model
/// ([`crate::core::temperature::flash_temperatures`]).
pub type TemperatureSection = ThermalInput;

/// The checked `[temperature]` of a case of `model` with `kinematics`
/// (errors name the key).
fn temperature_request(
    section: &TemperatureSection,
    model: Model,
    kinematics: &Kinematics,
) -> Result<ThermalInput, CaseError> {
    if model != Model::Exact {
        return Err(bad(
            "temperature",
            format!(
                "flash temperatures come from the frictional power of model = \"exact\", not \"{}\"",
                model.name()
            ),
        ));
    }
    if !matches!(kinematics, Kinematics::SteadyRolling(_)) {
        return Err(bad(
            "temperature",
            "flash temperatures need steady rolling: give `[rolling]` (a static or `[transient]` case has no steady frictional power)",
        ));
    }
    section.validate("temperature")?;
    Ok(*section)
}

/// The checked `[conformal]` of a case of `model` with `kinematics`: its
/// rigid slip surface (the default without the section). The section
/// belongs to the conformal models; outside steady rolling its rigid slip
/// is unused (a note says so).
/// The case's `[interfacial_layer]`, checked (each value naming its key
/// `interfacial_layer.<key>`, and against the friction law) for the exact
/// model; refused, naming `interfacial_layer`, with another model (FASTSIM,
/// the closed forms and the conformal solvers do not take it). A
/// frictionless case gets a note: the normal problem does not see the
/// layer.
fn interfacial_layer(
    section: Option<InterfacialLayer>,
    model: Model,
    friction: &Friction,
    kinematics: &Kinematics,
    notes: &mut Vec<String>,
) -> Result<Option<InterfacialLayer>, CaseError> {
    let Some(layer) = section else {
        return Ok(None);
    };
    if model != Model::Exact {
        return Err(bad(
            INTERFACIAL_LAYER_KEY,
            format!(
                "an interfacial layer is taken by model = \"exact\" only (steady rolling and \
                 transient steps), not by \"{}\"",
                model.name()
            ),
        ));
    }
    layer.validate(INTERFACIAL_LAYER_KEY)?;
    layer.check_friction(INTERFACIAL_LAYER_KEY, friction)?;
    if matches!(kinematics, Kinematics::Frictionless) {
        notes.push(
            "interfacial_layer: a frictionless normal problem does not see the layer (it acts on \
             the tangential tractions): give [rolling] or [transient]"
                .to_string(),
        );
    }
    Ok(Some(layer))
}

/// The case's `[viscoelastic]`, checked (each value naming its key
/// `viscoelastic.<key>`) for the exact model in steady rolling in +x or
/// frictionless; refused, naming `viscoelastic`, with another model or
/// transient steps, and naming `rolling_direction_rad` for another
/// rolling direction (CONTACT takes M = 1 in steady rolling with CHI = 0
/// only).
fn viscoelastic(
    section: Option<Viscoelastic>,
    model: Model,
    kinematics: &Kinematics,
    rolling_direction_rad: f64,
) -> Result<Option<Viscoelastic>, CaseError> {
    let Some(visc) = section else {
        return Ok(None);
    };
    if model != Model::Exact {
        return Err(bad(
            VISCOELASTIC_KEY,
            format!(
                "viscoelastic bodies are taken by model = \"exact\" only (steady rolling), not by \
                 \"{}\"",
                model.name()
            ),
        ));
    }
    visc.validate(VISCOELASTIC_KEY)?;
    if matches!(kinematics, Kinematics::Transient(_)) {
        return Err(bad(
            VISCOELASTIC_KEY,
            "viscoelastic bodies are taken in steady rolling ([rolling], or no [rolling] for its \
             frictionless normal problem) only, not with [transient]",
        ));
    }
    if rolling_direction_rad != 0.0 {
        return Err(bad(
            ROLLING_DIRECTION_KEY,
            "viscoelastic bodies roll in +x only: give 0",
        ));
    }
    Ok(Some(visc))
}

fn conformal_options(
    section: Option<ConformalSection>,
    model: Model,
    kinematics: &Kinematics,
    notes: &mut Vec<String>,
) -> Result<RigidSlipSurface, CaseError> {
    let Some(section) = section else {
        return Ok(RigidSlipSurface::default());
    };
    if !model.is_cect() {
        return Err(bad(
            "conformal",
            format!(
                "options of model = \"cect\" or \"cect_halfspace\", not \"{}\"",
                model.name()
            ),
        ));
    }
    if section.rigid_slip.is_some() && !matches!(kinematics, Kinematics::SteadyRolling(_)) {
        notes.push(
            "conformal.rigid_slip applies to steady rolling ([rolling]): unused here".to_string(),
        );
    }
    Ok(section.rigid_slip.unwrap_or_default())
}

/// `[subsurface]`: the depths below the surface at which to compute the
/// stresses and displacements of both bodies (under every element of the
/// grid), either as a list `depths_m` \[m\] or as `depth_count` depths
/// evenly spaced from 0 to `max_depth_m` \[m\]; and optionally the yield
/// stress in pure shear `shear_yield_stress_pa` \[Pa\] for the surface
/// fatigue index ([`crate::core::subsurface::surface_fatigue_index`]).
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SubsurfaceSection {
    /// Depths below the surface \[m\], each in [0, 1], 1 to
    /// [`crate::core::subsurface::MAX_DEPTHS`] of them.
    pub depths_m: Option<Vec<f64>>,
    /// Deepest of `depth_count` evenly spaced depths from 0 \[m\].
    pub max_depth_m: Option<f64>,
    /// Number of evenly spaced depths, 2 to [`crate::core::subsurface::MAX_DEPTHS`].
    pub depth_count: Option<usize>,
    /// Yield stress in pure shear k \[Pa\] (steel: about 300e6 to 600e6).
    pub shear_yield_stress_pa: Option<f64>,
}

/// A validated `[subsurface]` request.
#[derive(Debug, Clone, PartialEq)]
pub struct SubsurfaceRequest {
    /// Depths below the surface \[m\].
    pub depths_m: Vec<f64>,
    /// Yield stress in pure shear \[Pa\], for the surface fatigue index.
    pub shear_yield_stress_pa: Option<f64>,
}

impl SubsurfaceSection {
    /// The checked request of a case of `model` (errors name the key).
    pub fn request(&self, model: Model) -> Result<SubsurfaceRequest, CaseError> {
        use crate::core::subsurface::{check_depths, MAX_DEPTHS};
        if model != Model::Exact {
            return Err(bad(
                "subsurface",
                format!(
                    "subsurface stresses come from the tractions of model = \"exact\", not \"{}\"",
                    model.name()
                ),
            ));
        }
        let depths_m = match (&self.depths_m, self.max_depth_m, self.depth_count) {
            (Some(d), None, None) => d.clone(),
            (None, Some(max), Some(n)) => {
                ranges::WINDOW.check("subsurface.max_depth_m", max)?;
                let n = check_count("subsurface.depth_count", n, 2, MAX_DEPTHS)?;
                (0..n).map(|k| max * (k as f64 / (n - 1) as f64)).collect()
            }
            (Some(_), _, _) => {
                return Err(bad(
                    "subsurface.depths_m",
                    "give either `subsurface.depths_m` or `subsurface.max_depth_m` + \
                     `subsurface.depth_count`, not both",
                ))
            }
            (None, None, _) => {
                return Err(bad(
                    "subsurface.depths_m",
                    "missing: give `subsurface.depths_m` or `subsurface.max_depth_m` + `subsurface.depth_count`",
                ))
            }
            (None, Some(_), None) => {
                return Err(bad(
                    "subsurface.depth_count",
                    "missing (needed with `max_depth_m`)",
                ))
            }
        };
        check_depths("subsurface.depths_m", &depths_m)?;
        if let Some(k) = self.shear_yield_stress_pa {
            ranges::SHEAR_YIELD_STRESS.check("subsurface.shear_yield_stress_pa", k)?;
        }
        Ok(SubsurfaceRequest {
            depths_m,
            shear_yield_stress_pa: self.shear_yield_stress_pa,
        })
    }
}

/// `[rolling]`: per direction either the creepage or the prescribed total
/// tangential force on body 1 (signs as in [`crate::core::problem`]).
#[derive(Debug, Clone, Copy, Default, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RollingSection {
    /// Longitudinal creepage xi [-] (default 0 unless `force_x_n` is given).
    pub creepage_long: Option<f64>,
    /// Lateral creepage eta [-] (default 0 unless `force_y_n` is given).
    pub creepage_lat: Option<f64>,
    /// Spin creepage phi [1/m] (default 0).
    pub spin_per_m: f64,
    /// Prescribed longitudinal force Fx \[N\], |Fx| < mu Fn, instead of
    /// `creepage_long`.
    pub force_x_n: Option<f64>,
    /// Prescribed lateral force Fy \[N\], |Fy| < mu Fn, instead of
    /// `creepage_lat`.
    pub force_y_n: Option<f64>,
    /// Line contact (`geometry.kind = "line"`): prescribed longitudinal
    /// force per metre Fx' \[N/m\], |Fx'| < mu Fn', instead of
    /// `creepage_long`.
    pub force_x_n_per_m: Option<f64>,
}

impl RollingSection {
    /// Rolling with these creepages.
    pub fn creepages(c: Creepages) -> Self {
        Self {
            creepage_long: Some(c.creepage_long),
            creepage_lat: Some(c.creepage_lat),
            spin_per_m: c.spin_per_m,
            force_x_n: None,
            force_y_n: None,
            force_x_n_per_m: None,
        }
    }

    /// The creepages (0 in the directions of a prescribed force: the start
    /// of its iteration) and the prescribed forces (`force_x_n_per_m` as
    /// Fx: a line contact's totals are per metre); exactly one of creepage
    /// and force per direction.
    pub fn split(&self) -> Result<(Creepages, PrescribedForce), CaseError> {
        let (force_x, fx_key) = match (self.force_x_n, self.force_x_n_per_m) {
            (Some(_), Some(_)) => {
                return Err(bad(
                    "rolling.force_x_n_per_m",
                    "give either `rolling.force_x_n` or `rolling.force_x_n_per_m`, not both",
                ))
            }
            (None, Some(f)) => {
                ranges::TANGENTIAL_FORCE_PER_M.check("rolling.force_x_n_per_m", f)?;
                (Some(f), "force_x_n_per_m")
            }
            (f, None) => (f, "force_x_n"),
        };
        let one = |creep: Option<f64>, force: Option<f64>, ck: &str, fk: &str| match (creep, force)
        {
            (Some(_), Some(_)) => Err(bad(
                format!("rolling.{fk}"),
                format!("give either `rolling.{ck}` or `rolling.{fk}`, not both"),
            )),
            (c, None) => Ok((c.unwrap_or(0.0), None)),
            (None, Some(f)) => {
                if !fk.ends_with("_per_m") {
                    ranges::TANGENTIAL_FORCE.check(&format!("rolling.{fk}"), f)?;
                }
                Ok((0.0, Some(f)))
            }
        };
        let (xi, fx) = one(self.creepage_long, force_x, "creepage_long", fx_key)?;
        let (eta, fy) = one(
            self.creepage_lat,
            self.force_y_n,
            "creepage_lat",
            "force_y_n",
        )?;
        Ok((
            Creepages {
                creepage_long: xi,
                creepage_lat: eta,
                spin_per_m: self.spin_per_m,
            },
            PrescribedForce {
                force_x_n: fx,
                force_y_n: fy,
            },
        ))
    }
}

/// `[material]`: either `shear_modulus_pa` + `poisson_ratio` for both bodies,
/// or the sub-tables `[material.body1]` and `[material.body2]` for dissimilar
/// bodies (not both forms at once).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSection {
    /// Shear modulus G of both bodies \[Pa\], > 0 (steel: 81.0e9).
    pub shear_modulus_pa: Option<f64>,
    /// Poisson ratio nu of both bodies [-], in [0, 0.5) (steel: 0.30).
    pub poisson_ratio: Option<f64>,
    /// Body 1 (the rail; the body the tractions act on): `shear_modulus_pa`
    /// \[Pa\], `poisson_ratio` [-].
    pub body1: Option<Material>,
    /// Body 2 (the wheel), same keys.
    pub body2: Option<Material>,
}

/// The friction law of a `[friction]` section.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FrictionLawName {
    /// Coulomb's law: `coefficient`, or `static_coefficient` +
    /// `kinetic_coefficient` (the default).
    #[default]
    Coulomb,
    /// Linear falling friction ([`crate::core::friclaw`]).
    Linear,
    /// Rational falling friction.
    Rational,
    /// Exponential falling friction.
    Exponential,
}

/// `[friction]`: Coulomb's law (`coefficient`, or `static_coefficient` +
/// `kinetic_coefficient`), or with `law = "linear" | "rational" |
/// "exponential"` a slip-velocity dependent law ([`crate::core::friclaw`],
/// exact model only): `kinetic_coefficient`, `falling_coefficients`,
/// `half_velocities_m_per_s`, `rolling_speed_m_per_s` and the optional
/// `memory_distance_m`, `memory_velocity_m_per_s`, `start`,
/// `max_iterations`. Wheel/rail cases also take a friction table over the
/// rail profile ([`crate::wheelrail::friction`]): `contact_angles_rad` or
/// `rail_y_m`, `coefficients`, and the optional `track_s_m`
/// ([`FrictionSection::table`]).
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrictionSection {
    /// `"coulomb"` (default), `"linear"`, `"rational"` or `"exponential"`.
    #[serde(default)]
    pub law: FrictionLawName,
    /// Coulomb coefficient mu [-], >= 0 (static = kinetic).
    pub coefficient: Option<f64>,
    /// Static coefficient [-], >= 0 (with `kinetic_coefficient`).
    pub static_coefficient: Option<f64>,
    /// Kinetic coefficient [-], >= 0 (with `static_coefficient`); with a
    /// falling law its limit mu_kin at large slip velocity, > 0.
    pub kinetic_coefficient: Option<f64>,
    /// Falling law: the sizes mu_1 (, mu_2) [-] >= 0 of its one or two
    /// terms at slip velocity 0; static coefficient mu_kin + mu_1 + mu_2 <= 5.
    pub falling_coefficients: Option<Vec<f64>>,
    /// Falling law: the slip velocities s_h1 (, s_h2) \[m/s\] > 0 at which
    /// each term is halved, one per term.
    pub half_velocities_m_per_s: Option<Vec<f64>>,
    /// Falling law: rolling speed V \[m/s\] > 0, converting slip to slip
    /// velocity.
    pub rolling_speed_m_per_s: Option<f64>,
    /// Falling law: memory distance d_c \[m\] >= 0 over which the
    /// coefficient relaxes (default 0: instantaneous).
    pub memory_distance_m: Option<f64>,
    /// Falling law: memory velocity s_0 \[m/s\] >= 0, the least relaxation
    /// rate (default 0).
    pub memory_velocity_m_per_s: Option<f64>,
    /// Falling law: the slip velocities the iteration starts from,
    /// `"previous"` (default: continuation), `"sticking"` (0: the
    /// low-slip solution) or `"sliding"` (V: the high-slip solution).
    pub start: Option<SlipStart>,
    /// Falling law: limit of the iteration on the slip velocities
    /// (default 200).
    pub max_iterations: Option<usize>,
    /// Wheel/rail friction table: contact angles \[rad\], strictly
    /// increasing, in \[-1.6, 1.6\] (or `rail_y_m`).
    pub contact_angles_rad: Option<Vec<f64>>,
    /// Wheel/rail friction table: lateral coordinates on the rail profile
    /// \[m\], strictly increasing (or `contact_angles_rad`).
    pub rail_y_m: Option<Vec<f64>>,
    /// Wheel/rail friction table: static coefficients [-] in \[1e-6, 5\],
    /// one per position, row after row for each of `track_s_m`; the
    /// section's law is scaled to them ([`FrictionSection::table_law`]).
    pub coefficients: Option<Vec<f64>>,
    /// Wheel/rail friction table: track coordinates \[m\] of its rows,
    /// strictly increasing (default: one row for the whole track).
    pub track_s_m: Option<Vec<f64>>,
}

/// Kind of undeformed geometry.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GeometryKind {
    /// h = a_per_m x² + b_per_m y².
    Quadratic,
    /// Circular lateral profiles of rail and wheel and a wheel rolling
    /// radius (conformal contact).
    ConformalCircular,
    /// Rail and wheel profiles given as points (y, z) and a wheel rolling
    /// radius (conformal contact).
    ConformalPoints,
    /// Line contact: two cylinders with parallel axes along y, h = a_per_m
    /// x², solved in two dimensions (plane strain) per metre of their
    /// length ([`crate::core::influence`]); exact model only.
    Line,
}

impl GeometryKind {
    /// The name used in the case file.
    pub fn name(self) -> &'static str {
        match self {
            GeometryKind::Quadratic => "quadratic",
            GeometryKind::ConformalCircular => "conformal_circular",
            GeometryKind::ConformalPoints => "conformal_points",
            GeometryKind::Line => "line",
        }
    }
}

/// `[geometry]`: the undeformed distance of the bodies. Which keys are
/// required depends on `kind`; keys of another kind are rejected.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GeometrySection {
    /// Geometry kind: `"quadratic"`, `"conformal_circular"`,
    /// `"conformal_points"` or `"line"`.
    pub kind: GeometryKind,
    /// `quadratic`, `line`: curvature coefficient A in x (rolling
    /// direction) [1/m], > 0 (A = 1/(2 R_x) for combined radius R_x).
    pub a_per_m: Option<f64>,
    /// `quadratic`: curvature coefficient B in y (lateral) [1/m], > 0.
    pub b_per_m: Option<f64>,
    /// `conformal_circular`: lateral radius of the rail profile \[m\], convex
    /// (crown) > 0, concave < 0, `inf` straight.
    pub rail_lateral_radius_m: Option<f64>,
    /// `conformal_circular`: lateral radius of the wheel profile \[m\],
    /// convex > 0, concave (hollow, wrapping the rail) < 0.
    pub wheel_lateral_radius_m: Option<f64>,
    /// Conformal kinds: wheel rolling radius at the rigid contact point \[m\], > 0.
    pub wheel_rolling_radius_m: Option<f64>,
    /// `conformal_points`: rail profile points `[y, z]` \[m\] in the plane
    /// x = 0, z down into the rail, ordered by increasing y, one of them
    /// at the rigid contact point (the origin).
    pub rail_points_m: Option<Vec<[f64; 2]>>,
    /// `conformal_points`: wheel profile points `[y, z]` \[m\], same rules.
    pub wheel_points_m: Option<Vec<[f64; 2]>>,
    /// `quadratic`, `line`, exact model: the undeformed distance given per
    /// element \[m\] (CONTACT's `IBASE = 9`), replacing A x² + B y²:
    /// nx * ny values with index iy * nx + ix (x fastest; a line contact
    /// nx), each in [-1, 1] m, at the element centres of the grid, which
    /// must be given (`nx`, `ny`, and the windows). A and B still estimate
    /// the Hertz patch that checks the window, so give those of the
    /// best-fitting quadric; the patch may span fewer elements than a
    /// quadratic gap needs (the grid is the user's).
    #[serde(default)]
    pub gap_m: Option<Vec<f64>>,
}

/// A validated geometry.
#[derive(Debug, Clone, PartialEq)]
pub enum CaseGeometry {
    /// h = A x² + B y² (the case's `a_per_m`, `b_per_m`).
    Quadratic,
    /// Line contact: h = A x² per metre of two cylinders (plane strain).
    Line,
    /// Circular lateral profiles.
    ConformalCircular {
        /// Rail lateral radius \[m\] (convex > 0).
        rail_lateral_radius_m: f64,
        /// Wheel lateral radius \[m\] (concave < 0).
        wheel_lateral_radius_m: f64,
        /// Wheel rolling radius \[m\].
        wheel_rolling_radius_m: f64,
    },
    /// Profiles through points.
    ConformalPoints {
        /// Rail profile.
        rail: Box<PointCurve>,
        /// Wheel profile.
        wheel: Box<PointCurve>,
        /// Number of rail points.
        rail_points: usize,
        /// Number of wheel points.
        wheel_points: usize,
        /// Rail lateral radius at the origin estimated from the points \[m\]
        /// (infinite for a straight profile).
        rail_lateral_radius_m: f64,
        /// Wheel lateral radius at the origin estimated from the points \[m\].
        wheel_lateral_radius_m: f64,
        /// Wheel rolling radius \[m\].
        wheel_rolling_radius_m: f64,
    },
}

impl CaseGeometry {
    /// Whether the geometry is conformal (curved lateral profiles).
    pub fn is_conformal(&self) -> bool {
        !matches!(self, CaseGeometry::Quadratic | CaseGeometry::Line)
    }

    /// Whether the geometry is a line contact (two dimensions).
    pub fn is_line(&self) -> bool {
        matches!(self, CaseGeometry::Line)
    }

    /// Lateral radii of rail and wheel and the wheel rolling radius \[m\]
    /// (given or, for points, estimated at the origin); `None` for
    /// `quadratic`.
    pub fn radii(&self) -> Option<(f64, f64, f64)> {
        match *self {
            CaseGeometry::Quadratic | CaseGeometry::Line => None,
            CaseGeometry::ConformalCircular {
                rail_lateral_radius_m,
                wheel_lateral_radius_m,
                wheel_rolling_radius_m,
            }
            | CaseGeometry::ConformalPoints {
                rail_lateral_radius_m,
                wheel_lateral_radius_m,
                wheel_rolling_radius_m,
                ..
            } => Some((
                rail_lateral_radius_m,
                wheel_lateral_radius_m,
                wheel_rolling_radius_m,
            )),
        }
    }

    /// Mean lateral radius r = (|R_yr| + |R_yw|)/2 \[m\] (infinite for
    /// `quadratic` or a straight profile).
    pub fn mean_lateral_radius_m(&self) -> f64 {
        match self.radii() {
            Some((r, w, _)) => 0.5 * (r.abs() + w.abs()),
            None => f64::INFINITY,
        }
    }

    /// One line describing the geometry (mm) for the readable summary.
    pub fn describe(&self) -> String {
        match self {
            CaseGeometry::Quadratic => "quadratic gap".to_string(),
            CaseGeometry::Line => "line contact of cylinders (plane strain, per metre)".to_string(),
            CaseGeometry::ConformalCircular {
                rail_lateral_radius_m: r,
                wheel_lateral_radius_m: w,
                wheel_rolling_radius_m: x,
            } => format!(
                "circular profiles R_yr = {:.4} mm, R_yw = {:.4} mm, R_xw = {:.2} mm",
                r * 1e3,
                w * 1e3,
                x * 1e3
            ),
            CaseGeometry::ConformalPoints {
                rail_points,
                wheel_points,
                rail_lateral_radius_m: r,
                wheel_lateral_radius_m: w,
                wheel_rolling_radius_m: x,
                ..
            } => format!(
                "profiles through {rail_points} rail and {wheel_points} wheel points \
                 (at the origin R_yr ≈ {:.4} mm, R_yw ≈ {:.4} mm), R_xw = {:.2} mm",
                r * 1e3,
                w * 1e3,
                x * 1e3
            ),
        }
    }

    /// The conformal geometry on the (x, s) grid `grid`.
    pub fn conformal(&self, grid: Grid) -> Result<ConformalGeometry, CaseError> {
        let g = match self {
            CaseGeometry::Quadratic | CaseGeometry::Line => return Err(bad(
                "geometry.kind",
                "the conformal models need `kind = \"conformal_circular\"` or \"conformal_points\"",
            )),
            CaseGeometry::ConformalCircular {
                rail_lateral_radius_m,
                wheel_lateral_radius_m,
                wheel_rolling_radius_m,
            } => ConformalGeometry::new(
                &Circle::rail(*rail_lateral_radius_m),
                &Circle::wheel(*wheel_lateral_radius_m),
                *wheel_rolling_radius_m,
                grid,
            )?,
            CaseGeometry::ConformalPoints {
                rail,
                wheel,
                wheel_rolling_radius_m,
                ..
            } => ConformalGeometry::new(
                rail.as_ref(),
                wheel.as_ref(),
                *wheel_rolling_radius_m,
                grid,
            )?,
        };
        Ok(g)
    }
}

/// Signed curvature [1/m] of `curve` at the origin (t = 0), positive
/// when it bends towards +z for a tangent along +y: the tangent angle's
/// derivative by central differences over +-`h_m`.
fn curvature_at_origin(curve: &dyn Curve, h_m: f64) -> f64 {
    let angle = |t: f64| {
        let (_, d) = curve.eval(t);
        d[1].atan2(d[0])
    };
    (angle(h_m) - angle(-h_m)) / (2.0 * h_m)
}

/// A profile through `points` with the checks of `conformal_points`:
/// the curve, its curvature at the origin [1/m] and its tangent there.
fn profile_from_points(
    points: &[[f64; 2]],
    key: &str,
) -> Result<(PointCurve, f64, [f64; 2]), CaseError> {
    for (i, p) in points.iter().enumerate() {
        ranges::PROFILE_COORDINATE.check(&format!("{key}[{i}].y_m"), p[0])?;
        ranges::PROFILE_COORDINATE.check(&format!("{key}[{i}].z_m"), p[1])?;
    }
    let curve = PointCurve::new(points, key)?;
    let dist = |p: &[f64; 2]| p[0].hypot(p[1]);
    let nearest = (0..points.len())
        .min_by(|&a, &b| dist(&points[a]).total_cmp(&dist(&points[b])))
        .unwrap_or(0);
    let p = points[nearest];
    if dist(&p) > POINTS_ORIGIN_TOLERANCE_M {
        return Err(bad(
            key,
            format!(
                "the rigid contact point must be the origin and one of the points: the point \
                 nearest to it is [{:e}, {:e}] m; shift the profile so that it passes through [0.0, 0.0]",
                p[0], p[1]
            ),
        ));
    }
    if nearest == 0 || nearest + 1 == points.len() {
        return Err(bad(
            key,
            "the origin (the rigid contact point) is an end point: give points on both sides of it",
        ));
    }
    let (_, tangent) = curve.eval(0.0);
    if tangent[0] <= 0.0 {
        return Err(bad(
            key,
            "order the points by increasing y (the profile's tangent at the origin must point towards +y)",
        ));
    }
    let spacing =
        |a: usize, b: usize| (points[a][0] - points[b][0]).hypot(points[a][1] - points[b][1]);
    let h = 0.5 * spacing(nearest - 1, nearest).min(spacing(nearest, nearest + 1));
    let curvature = curvature_at_origin(&curve, h);
    Ok((curve, curvature, tangent))
}

/// A lateral radius: non-zero and not NaN (`inf`: straight).
fn lateral_radius(key: &str, v: f64) -> Result<f64, CaseError> {
    if v.is_infinite() || ranges::LATERAL_RADIUS.contains(v.abs()) {
        return Ok(v);
    }
    let r = ranges::LATERAL_RADIUS;
    Err(bad(
        key,
        format!(
            "must be convex > 0 or concave < 0 with a size in {}, or inf for a straight profile, got {}",
            r.describe(),
            show(v)
        ),
    ))
}

impl GeometrySection {
    /// Validates the section for its `kind`: the geometry and the
    /// curvature coefficients A, B [1/m] of its (flattened) quadratic gap,
    /// A = 1/(2 R_xw), B = (1/R_yr + 1/R_yw)/2 for the conformal kinds.
    fn validate(&self) -> Result<(CaseGeometry, f64, f64), CaseError> {
        let kind = self.kind;
        let keys: [(&str, bool, GeometryKind); 7] = [
            ("a_per_m", self.a_per_m.is_some(), GeometryKind::Quadratic),
            ("b_per_m", self.b_per_m.is_some(), GeometryKind::Quadratic),
            (
                "rail_lateral_radius_m",
                self.rail_lateral_radius_m.is_some(),
                GeometryKind::ConformalCircular,
            ),
            (
                "wheel_lateral_radius_m",
                self.wheel_lateral_radius_m.is_some(),
                GeometryKind::ConformalCircular,
            ),
            (
                "wheel_rolling_radius_m",
                self.wheel_rolling_radius_m.is_some(),
                kind,
            ),
            (
                "rail_points_m",
                self.rail_points_m.is_some(),
                GeometryKind::ConformalPoints,
            ),
            (
                "wheel_points_m",
                self.wheel_points_m.is_some(),
                GeometryKind::ConformalPoints,
            ),
        ];
        for (key, given, owner) in keys {
            // A line contact's gap is A x².
            let line_a = kind == GeometryKind::Line && key == "a_per_m";
            if given && owner != kind && !line_a {
                return Err(bad(
                    format!("geometry.{key}"),
                    format!(
                        "not used with `kind = \"{}\"` (it belongs to `kind = \"{}\"`)",
                        kind.name(),
                        owner.name()
                    ),
                ));
            }
        }
        if matches!(kind, GeometryKind::Quadratic | GeometryKind::Line)
            && self.wheel_rolling_radius_m.is_some()
        {
            return Err(bad(
                "geometry.wheel_rolling_radius_m",
                format!(
                    "not used with `kind = \"{}\"` (it belongs to the conformal kinds)",
                    kind.name()
                ),
            ));
        }
        let need = |key: &str, v: Option<f64>| {
            v.ok_or_else(|| {
                bad(
                    format!("geometry.{key}"),
                    format!("missing: required with `kind = \"{}\"`", kind.name()),
                )
            })
        };
        match kind {
            GeometryKind::Quadratic => {
                let a = need("a_per_m", self.a_per_m)?;
                let b = need("b_per_m", self.b_per_m)?;
                ranges::CURVATURE.check("geometry.a_per_m", a)?;
                ranges::CURVATURE.check("geometry.b_per_m", b)?;
                Ok((CaseGeometry::Quadratic, a, b))
            }
            GeometryKind::Line => {
                let a = need("a_per_m", self.a_per_m)?;
                ranges::CURVATURE.check("geometry.a_per_m", a)?;
                Ok((CaseGeometry::Line, a, 0.0))
            }
            GeometryKind::ConformalCircular => {
                let r = need("rail_lateral_radius_m", self.rail_lateral_radius_m)?;
                let w = need("wheel_lateral_radius_m", self.wheel_lateral_radius_m)?;
                let x = need("wheel_rolling_radius_m", self.wheel_rolling_radius_m)?;
                let r = lateral_radius("geometry.rail_lateral_radius_m", r)?;
                let w = lateral_radius("geometry.wheel_lateral_radius_m", w)?;
                ranges::ROLLING_RADIUS.check("geometry.wheel_rolling_radius_m", x)?;
                let b = 0.5 * (1.0 / r + 1.0 / w);
                if b.is_nan() || b <= 0.0 {
                    // The concave one of the two is named: a wheel/rail
                    // pair has a convex rail, so a concave rail is the
                    // likely slip.
                    let (field, hint) = match r < 0.0 {
                        true => (
                            "geometry.rail_lateral_radius_m",
                            "a concave rail, R_yr < 0, must be wider than a convex wheel: |R_yr| > R_yw",
                        ),
                        false => (
                            "geometry.wheel_lateral_radius_m",
                            "a concave wheel, R_yw < 0, must be wider than a convex rail: |R_yw| > R_yr",
                        ),
                    };
                    return Err(bad(
                        field,
                        format!(
                            "the profiles do not touch in one point: 1/R_yr + 1/R_yw = {:.6e} 1/m must \
                             be > 0 ({hint})",
                            2.0 * b
                        ),
                    ));
                }
                let geometry = CaseGeometry::ConformalCircular {
                    rail_lateral_radius_m: r,
                    wheel_lateral_radius_m: w,
                    wheel_rolling_radius_m: x,
                };
                Ok((geometry, 0.5 / x, b))
            }
            GeometryKind::ConformalPoints => {
                let missing = |key: &str| {
                    bad(
                        format!("geometry.{key}"),
                        "missing: required with `kind = \"conformal_points\"`",
                    )
                };
                let rp = self
                    .rail_points_m
                    .as_deref()
                    .ok_or_else(|| missing("rail_points_m"))?;
                let wp = self
                    .wheel_points_m
                    .as_deref()
                    .ok_or_else(|| missing("wheel_points_m"))?;
                let x = need("wheel_rolling_radius_m", self.wheel_rolling_radius_m)?;
                ranges::ROLLING_RADIUS.check("geometry.wheel_rolling_radius_m", x)?;
                let (rail, kr, tr) = profile_from_points(rp, "geometry.rail_points_m")?;
                let (wheel, kw, tw) = profile_from_points(wp, "geometry.wheel_points_m")?;
                let angle = (tr[0] * tw[1] - tr[1] * tw[0])
                    .atan2(tr[0] * tw[0] + tr[1] * tw[1])
                    .to_degrees();
                if angle.abs() > POINTS_TANGENT_TOLERANCE_DEG {
                    return Err(bad(
                        "geometry.wheel_points_m",
                        format!(
                            "the profiles must touch at the origin with a common tangent: the wheel's \
                             tangent there is {angle:.3}° off the rail's (at most {POINTS_TANGENT_TOLERANCE_DEG}°)"
                        ),
                    ));
                }
                // Rail: Circle::rail(R) bends towards +z with curvature 1/R;
                // wheel: Circle::wheel(R) with -1/R.
                let b = 0.5 * (kr - kw);
                if b.is_nan() || b <= 0.0 {
                    return Err(bad(
                        "geometry.wheel_points_m",
                        format!(
                            "the profiles do not touch in one point at the origin: the estimated \
                             curvatures (rail {kr:.4e} 1/m, wheel {:.4e} 1/m towards the rail) leave \
                             1/R_yr + 1/R_yw = {:.4e} 1/m, which must be > 0",
                            -kw,
                            2.0 * b
                        ),
                    ));
                }
                let geometry = CaseGeometry::ConformalPoints {
                    rail: Box::new(rail),
                    wheel: Box::new(wheel),
                    rail_points: rp.len(),
                    wheel_points: wp.len(),
                    rail_lateral_radius_m: 1.0 / kr,
                    wheel_lateral_radius_m: -1.0 / kw,
                    wheel_rolling_radius_m: x,
                };
                Ok((geometry, 0.5 / x, b))
            }
        }
    }
}

/// `[load]`: exactly one of `normal_force_n` (`normal_force_n_per_m` for a
/// line contact) and `approach_m`.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadSection {
    /// Total normal force \[N\], > 0.
    pub normal_force_n: Option<f64>,
    /// Line contact (`geometry.kind = "line"`): normal force per metre of
    /// the cylinders \[N/m\], > 0.
    #[serde(default)]
    pub normal_force_n_per_m: Option<f64>,
    /// Approach of the bodies \[m\], > 0 (line contact: relative to the
    /// surface points 1 m from the load, see [`crate::core::influence`]).
    pub approach_m: Option<f64>,
}

/// `[transient]`: a sequence of shift and rolling steps from the unloaded
/// state, each from the tractions of the step before.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TransientSection {
    /// Distance the contact patch rolls in +x in each rolling step \[m\]
    /// (moving coordinates, see [`crate::core::problem`]): a whole number
    /// of elements `grid.window_x_m / grid.nx`, in (0, 1] m. Needed when a
    /// step gives creepages (exact model only).
    pub rolling_step_m: Option<f64>,
    /// The steps, at least one.
    pub steps: Vec<StepSection>,
}

/// One step in `transient.steps`: a shift step (`shift_*`,
/// `rotation_rad`) or a rolling step (creepages, rolling
/// `transient.rolling_step_m` or the step's `rolling_m`), never both. A
/// shift step with `rolling_m` rolls that far by its shift: the potential
/// contact area moves with the bodies, in world-fixed terms (the
/// tractions stay where they are on the bodies). In either kind the
/// tangential forces may be prescribed instead of the shifts or creepages
/// of their directions (exact model): the step is solved for the shifts
/// that give them, reported with the step.
#[derive(Debug, Clone, Copy, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StepSection {
    /// Rigid shift of body 1 relative to body 2 in x during the step \[m\]
    /// (required in a shift step unless `force_x_n` is given, except for
    /// the conformal models, which take 0 only).
    pub shift_x_m: Option<f64>,
    /// Rigid shift in y during the step \[m\] (default 0).
    #[serde(default)]
    pub shift_y_m: f64,
    /// Rigid rotation about the normal axis during the step \[rad\] (default 0).
    #[serde(default)]
    pub rotation_rad: f64,
    /// Normal force in the step \[N\], > 0 (default: the `[load]`).
    pub normal_force_n: Option<f64>,
    /// Line contact: normal force per metre in the step \[N/m\], > 0
    /// (default: the `[load]`).
    #[serde(default)]
    pub normal_force_n_per_m: Option<f64>,
    /// Approach in the step \[m\], > 0 (default: the `[load]`).
    pub approach_m: Option<f64>,
    /// Longitudinal creepage xi of a rolling step [-], in [-1, 1] (default
    /// 0 when another creepage is given).
    pub creepage_long: Option<f64>,
    /// Lateral creepage eta of a rolling step [-], in [-1, 1] (default 0).
    pub creepage_lat: Option<f64>,
    /// Spin creepage phi of a rolling step \[1/m\], in [-1000, 1000]
    /// (default 0).
    pub spin_per_m: Option<f64>,
    /// Prescribed longitudinal force Fx on body 1 in the step \[N\],
    /// |Fx| < mu Fn, instead of `shift_x_m` (a shift step) or
    /// `creepage_long` (a rolling step); exact model.
    #[serde(default)]
    pub force_x_n: Option<f64>,
    /// Prescribed lateral force Fy \[N\], |(Fx, Fy)| < mu Fn, instead of
    /// `shift_y_m` or `creepage_lat` (with `force_x_n` or alone).
    #[serde(default)]
    pub force_y_n: Option<f64>,
    /// Line contact: prescribed longitudinal force per metre Fx' \[N/m\],
    /// |Fx'| < mu Fn', as `force_x_n` otherwise.
    #[serde(default)]
    pub force_x_n_per_m: Option<f64>,
    /// Distance this step rolls \[m\]: a whole number of elements, in
    /// (0, 1] (default: `transient.rolling_step_m` in a step with
    /// creepages, 0 in a shift step). A shift step with `rolling_m` is a
    /// rolling step given by its shift (the creepages are the shifts over
    /// `rolling_m`).
    #[serde(default)]
    pub rolling_m: Option<f64>,
    /// Distance the bodies' undeformed distance travels in +x over the
    /// grid in this shift step \[m\], in [-1, 1] (default 0): world-fixed
    /// steps on a fixed potential contact area, the tractions staying where
    /// they are on the grid. It accumulates over the steps: after steps
    /// with travels t_1..t_k the gap is A (x - s)² + B y², s = t_1 + ... +
    /// t_k (exact model, without `geometry.gap_m`).
    #[serde(default)]
    pub gap_travel_x_m: Option<f64>,
}

impl StepSection {
    /// The forces prescribed in the step (`force_x_n_per_m` as Fx when
    /// `line`: a line contact's totals are per metre), checked against
    /// their ranges; `key` names the step.
    fn force(&self, key: &str, line: bool) -> Result<PrescribedForce, CaseError> {
        let force_x_n = match (line, self.force_x_n, self.force_x_n_per_m) {
            (true, Some(_), _) => {
                return Err(bad(
                    format!("{key}.force_x_n"),
                    format!(
                        "a line contact's forces are per metre: give `{key}.force_x_n_per_m` [N/m]"
                    ),
                ))
            }
            (false, _, Some(_)) => {
                return Err(bad(
                    format!("{key}.force_x_n_per_m"),
                    format!(
                        "a force per metre is for `geometry.kind = \"line\"`: give `{key}.force_x_n` [N]"
                    ),
                ))
            }
            (true, None, f) => {
                if let Some(f) = f {
                    ranges::TANGENTIAL_FORCE_PER_M.check(&format!("{key}.force_x_n_per_m"), f)?;
                }
                f
            }
            (false, f, None) => {
                if let Some(f) = f {
                    ranges::TANGENTIAL_FORCE.check(&format!("{key}.force_x_n"), f)?;
                }
                f
            }
        };
        if let Some(f) = self.force_y_n {
            ranges::TANGENTIAL_FORCE.check(&format!("{key}.force_y_n"), f)?;
        }
        Ok(PrescribedForce {
            force_x_n,
            force_y_n: self.force_y_n,
        })
    }

    /// The creepages of a rolling step, None for a shift step; `key` names
    /// the step.
    fn creepages(&self, key: &str) -> Result<Option<Creepages>, CaseError> {
        if self.creepage_long.is_none() && self.creepage_lat.is_none() && self.spin_per_m.is_none()
        {
            return Ok(None);
        }
        let c = Creepages {
            creepage_long: self.creepage_long.unwrap_or(0.0),
            creepage_lat: self.creepage_lat.unwrap_or(0.0),
            spin_per_m: self.spin_per_m.unwrap_or(0.0),
        };
        CREEPAGE_RANGE.check(&format!("{key}.creepage_long"), c.creepage_long)?;
        CREEPAGE_RANGE.check(&format!("{key}.creepage_lat"), c.creepage_lat)?;
        SPIN_RANGE.check(&format!("{key}.spin_per_m"), c.spin_per_m)?;
        Ok(Some(c))
    }
}

/// `[grid]`: the potential contact grid, centred on the origin.
#[derive(Debug, Clone, Copy, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct GridSection {
    /// Elements in x (default 64 for `exact`, `cect`, `cect_halfspace`, 40
    /// strips for `fastsim`).
    pub nx: Option<usize>,
    /// Elements in y, along s for the conformal models (default 64; 40 for
    /// `fastsim`; a line contact has one row: not given).
    pub ny: Option<usize>,
    /// Window length in x \[m\] (default 2.4 x the Hertz semi-axis in x;
    /// conformal models 3.2 x).
    pub window_x_m: Option<f64>,
    /// Window width in y \[m\] (default 2.4 x the Hertz semi-axis in y);
    /// conformal models: curvilinear width along s (default 2.6 x the plain
    /// Hertz semi-axis, at most the arc of +-75° on the mean lateral radius);
    /// a line contact's row is 1 m long: not given.
    pub window_y_m: Option<f64>,
}

/// `[solver]`: tolerances and iteration limits of the exact model.
#[derive(Debug, Clone, Copy, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct SolverSection {
    /// Relative pressure change that ends the normal iteration [-] (default 1e-6).
    pub normal_tolerance: Option<f64>,
    /// Friction-law residual relative to max mu p_n that ends the tangential
    /// iteration [-] (default 1e-7).
    pub tangential_tolerance: Option<f64>,
    /// Iteration limit of each solver, normal and tangential, in each
    /// normal/tangential alternation (default 1000 normal, 2000
    /// tangential: Newton steps and fallback iterations together).
    pub max_iterations: Option<usize>,
    /// Estimated distance of the tractions to the coupled solution,
    /// relative to the pressures' L1 norm, that ends the normal/tangential
    /// alternation [-] (`exact` with dissimilar materials, `cect`,
    /// `cect_halfspace`; default 1e-8): the last change times q/(1 - q),
    /// q the alternation's contraction.
    pub coupling_tolerance: Option<f64>,
    /// Limit of normal/tangential alternations (default 30 for `exact`, 50
    /// for the conformal models).
    pub coupling_max_iterations: Option<usize>,
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
}

fn bad(key: impl Into<String>, reason: impl Into<String>) -> CaseError {
    CaseError::from(ContactError::invalid(key, reason))
}

/// The load of a `[load]` or a step named `key`: per metre
/// (`normal_force_n_per_m`) for a line contact, else total
/// (`normal_force_n`); the other force key is refused.
fn one_load(
    key: &str,
    force: Option<f64>,
    force_per_m: Option<f64>,
    approach: Option<f64>,
    line: bool,
) -> Result<Option<NormalLoad>, CaseError> {
    match (line, force, force_per_m) {
        (true, Some(_), _) => {
            return Err(bad(
                format!("{key}.normal_force_n"),
                format!("a line contact's load is per metre: give `{key}.normal_force_n_per_m` [N/m]"),
            ))
        }
        (false, _, Some(_)) => {
            return Err(bad(
                format!("{key}.normal_force_n_per_m"),
                format!("a force per metre is for `geometry.kind = \"line\"`: give `{key}.normal_force_n` [N]"),
            ))
        }
        (true, None, Some(f)) => {
            if approach.is_some() {
                return Err(bad(
                    format!("{key}.normal_force_n_per_m"),
                    format!("give either `{key}.normal_force_n_per_m` or `{key}.approach_m`, not both"),
                ));
            }
            ranges::NORMAL_FORCE_PER_M.check(&format!("{key}.normal_force_n_per_m"), f)?;
            return Ok(Some(NormalLoad::NormalForce(f)));
        }
        _ => {}
    }
    match (force, approach) {
        (Some(_), Some(_)) => Err(bad(
            format!("{key}.normal_force_n"),
            format!("give either `{key}.normal_force_n` or `{key}.approach_m`, not both"),
        )),
        (Some(f), None) => {
            ranges::NORMAL_FORCE.check(&format!("{key}.normal_force_n"), f)?;
            Ok(Some(NormalLoad::NormalForce(f)))
        }
        (None, Some(d)) => {
            ranges::APPROACH.check(&format!("{key}.approach_m"), d)?;
            Ok(Some(NormalLoad::Approach(d)))
        }
        (None, None) => Ok(None),
    }
}

impl MaterialSection {
    /// The checked materials of the two bodies (errors name the key).
    pub fn combine(&self) -> Result<CombinedMaterial, CaseError> {
        let direct = self.shear_modulus_pa.is_some() || self.poisson_ratio.is_some();
        let bodies = self.body1.is_some() || self.body2.is_some();
        if direct && bodies {
            return Err(bad(
                "material",
                "give either `material.shear_modulus_pa` + `material.poisson_ratio` (both bodies) \
                 or the tables `[material.body1]` + `[material.body2]`, not both",
            ));
        }
        if bodies {
            let b1 = self.body1.ok_or_else(|| {
                bad(
                    "material.body1",
                    "missing: `[material.body2]` was given, give `[material.body1]` too",
                )
            })?;
            let b2 = self.body2.ok_or_else(|| {
                bad(
                    "material.body2",
                    "missing: `[material.body1]` was given, give `[material.body2]` too",
                )
            })?;
            return Ok(CombinedMaterial::new(b1, b2)?);
        }
        let g = self
            .shear_modulus_pa
            .ok_or_else(|| bad("material.shear_modulus_pa", "missing"))?;
        let nu = self
            .poisson_ratio
            .ok_or_else(|| bad("material.poisson_ratio", "missing"))?;
        let m = Material {
            shear_modulus_pa: g,
            poisson_ratio: nu,
        };
        m.validate("material")?;
        Ok(CombinedMaterial::identical(m)?)
    }
}

impl FrictionSection {
    /// The wheel/rail friction table of `contact_angles_rad` or `rail_y_m`,
    /// `coefficients` and `track_s_m`, checked; None without one. A table
    /// excludes `coefficient`: its coefficients are static coefficients,
    /// and the section's other keys (a falling law, or static and kinetic
    /// coefficients) give the law they scale ([`FrictionSection::table_law`]).
    pub fn table(&self) -> Result<Option<FrictionTable>, CaseError> {
        let (axis, positions) =
            match (&self.contact_angles_rad, &self.rail_y_m) {
                (None, None) => {
                    for (key, given) in [
                        ("friction.coefficients", self.coefficients.is_some()),
                        ("friction.track_s_m", self.track_s_m.is_some()),
                    ] {
                        if given {
                            return Err(bad(
                            key,
                            "belongs to a friction table: give `friction.contact_angles_rad` or \
                             `friction.rail_y_m`",
                        ));
                        }
                    }
                    return Ok(None);
                }
                (Some(a), None) => (FrictionAxis::ContactAngle, a),
                (None, Some(y)) => (FrictionAxis::RailLateral, y),
                (Some(_), Some(_)) => return Err(bad(
                    "friction.rail_y_m",
                    "give either `friction.contact_angles_rad` or `friction.rail_y_m`, not both",
                )),
            };
        if self.coefficient.is_some() {
            return Err(bad(
                "friction.coefficient",
                "not with a friction table (its coefficients are the static ones; a law's other \
                 keys, or static_coefficient with kinetic_coefficient, give the shape it scales)",
            ));
        }
        let table = FrictionTable {
            axis,
            positions: positions.clone(),
            track_s_m: self.track_s_m.clone().unwrap_or_default(),
            coefficients: self
                .coefficients
                .clone()
                .ok_or_else(|| bad("friction.coefficients", "missing (needed with a table)"))?,
        };
        table.validate().map_err(|e| match e {
            WheelRailError::Invalid { key, message } => bad(key, message),
            other => bad("friction", other.to_string()),
        })?;
        Ok(Some(table))
    }

    /// The law a friction table scales (see [`FrictionSection::table`]):
    /// the section without its table keys, Coulomb's law with equal
    /// coefficients when it gives none.
    pub fn table_law(&self) -> Result<Friction, CaseError> {
        let shape = FrictionSection {
            contact_angles_rad: None,
            rail_y_m: None,
            coefficients: None,
            track_s_m: None,
            ..self.clone()
        };
        let none_given = shape.law == FrictionLawName::Coulomb
            && shape.static_coefficient.is_none()
            && shape.kinetic_coefficient.is_none();
        if none_given {
            return Ok(Friction::coulomb(1.0));
        }
        shape.wheelrail_friction()
    }

    /// [`FrictionSection::friction`] for wheel/rail contact: a falling
    /// law's rolling speed is not needed (each patch replaces it with its
    /// own; 1 m/s stands in when it is not given).
    pub fn wheelrail_friction(&self) -> Result<Friction, CaseError> {
        if self.law != FrictionLawName::Coulomb && self.rolling_speed_m_per_s.is_none() {
            let given = FrictionSection {
                rolling_speed_m_per_s: Some(1.0),
                ..self.clone()
            };
            return given.friction();
        }
        self.friction()
    }

    /// The checked friction law (errors name the key).
    pub fn friction(&self) -> Result<Friction, CaseError> {
        for (key, given) in [
            (
                "friction.contact_angles_rad",
                self.contact_angles_rad.is_some(),
            ),
            ("friction.rail_y_m", self.rail_y_m.is_some()),
            ("friction.coefficients", self.coefficients.is_some()),
            ("friction.track_s_m", self.track_s_m.is_some()),
        ] {
            if given {
                return Err(bad(
                    key,
                    "belongs to a wheel/rail friction table (`railcontact wheelrail` cases)",
                ));
            }
        }
        let shape = match self.law {
            FrictionLawName::Coulomb => {
                for (key, given) in [
                    (
                        "friction.falling_coefficients",
                        self.falling_coefficients.is_some(),
                    ),
                    (
                        "friction.half_velocities_m_per_s",
                        self.half_velocities_m_per_s.is_some(),
                    ),
                    (
                        "friction.rolling_speed_m_per_s",
                        self.rolling_speed_m_per_s.is_some(),
                    ),
                    (
                        "friction.memory_distance_m",
                        self.memory_distance_m.is_some(),
                    ),
                    (
                        "friction.memory_velocity_m_per_s",
                        self.memory_velocity_m_per_s.is_some(),
                    ),
                    ("friction.start", self.start.is_some()),
                    ("friction.max_iterations", self.max_iterations.is_some()),
                ] {
                    if given {
                        return Err(bad(
                            key,
                            "belongs to a falling law: set `friction.law` to \"linear\", \"rational\" or \"exponential\"",
                        ));
                    }
                }
                return self.coulomb();
            }
            FrictionLawName::Linear => FallingShape::Linear,
            FrictionLawName::Rational => FallingShape::Rational,
            FrictionLawName::Exponential => FallingShape::Exponential,
        };
        for (key, given) in [
            ("friction.coefficient", self.coefficient.is_some()),
            (
                "friction.static_coefficient",
                self.static_coefficient.is_some(),
            ),
        ] {
            if given {
                return Err(bad(
                    key,
                    format!(
                        "not with law = \"{}\": its static coefficient is kinetic_coefficient + falling_coefficients",
                        shape.name()
                    ),
                ));
            }
        }
        let need = |key: &str, v: Option<f64>| {
            v.ok_or_else(|| bad(key, "missing (needed with a falling law)"))
        };
        let falling = self.falling_coefficients.as_deref().ok_or_else(|| {
            bad(
                "friction.falling_coefficients",
                "missing (needed with a falling law)",
            )
        })?;
        let half = self.half_velocities_m_per_s.as_deref().ok_or_else(|| {
            bad(
                "friction.half_velocities_m_per_s",
                "missing (needed with a falling law)",
            )
        })?;
        check_count("friction.falling_coefficients", falling.len(), 1, 2)?;
        if half.len() != falling.len() {
            return Err(bad(
                "friction.half_velocities_m_per_s",
                format!(
                    "needs one value per falling coefficient ({}), got {}",
                    falling.len(),
                    half.len()
                ),
            ));
        }
        let two = |v: &[f64]| [v[0], v.get(1).copied().unwrap_or(0.0)];
        let law = SlipVelocityLaw {
            shape,
            kinetic_coefficient: need("friction.kinetic_coefficient", self.kinetic_coefficient)?,
            falling_coefficients: two(falling),
            half_velocities_m_per_s: two(half),
            rolling_speed_m_per_s: need(
                "friction.rolling_speed_m_per_s",
                self.rolling_speed_m_per_s,
            )?,
            memory_distance_m: self.memory_distance_m.unwrap_or(0.0),
            memory_velocity_m_per_s: self.memory_velocity_m_per_s.unwrap_or(0.0),
            start: self.start.unwrap_or_default(),
            max_iterations: self.max_iterations.unwrap_or(DEFAULT_LAW_ITERATIONS),
        };
        if law.max_iterations == 0 {
            return Err(bad("friction.max_iterations", "must be >= 1"));
        }
        law.validate()?;
        Ok(Friction::falling(law))
    }

    /// Coulomb's coefficients (errors name the key).
    fn coulomb(&self) -> Result<Friction, CaseError> {
        let f = match (
            self.coefficient,
            self.static_coefficient,
            self.kinetic_coefficient,
        ) {
            (Some(mu), None, None) => Friction::coulomb(
                crate::core::problem::check_friction_coefficient("friction.coefficient", mu)?,
            ),
            (None, Some(s), Some(k)) => Friction::static_kinetic(s, k),
            (Some(_), _, _) => {
                return Err(bad(
                    "friction.coefficient",
                    "give either `friction.coefficient` or `friction.static_coefficient` + \
                     `friction.kinetic_coefficient`, not both",
                ))
            }
            (None, None, None) => return Err(bad("friction.coefficient", "missing")),
            (None, None, Some(_)) => {
                return Err(bad(
                    "friction.static_coefficient",
                    "missing (needed with `kinetic_coefficient`)",
                ))
            }
            (None, Some(_), None) => {
                return Err(bad(
                    "friction.kinetic_coefficient",
                    "missing (needed with `static_coefficient`)",
                ))
            }
        };
        f.check_input()?;
        Ok(f)
    }
}

impl Case {
    /// Parses and validates a case file's text. Errors are
    /// [`CaseError::BadInput`] and name the offending key.
    pub fn from_toml(text: &str) -> Result<Case, CaseError> {
        let file: CaseFile = toml::from_str(text)
            .map_err(|e| CaseError::BadInput(format!("case file: {}", e.to_string().trim_end())))?;
        Case::from_file(file)
    }

    /// Validates a parsed case file. A body softer than rubber gets a note
    /// ([`soft_modulus_note`]), which a refusal of the case also carries:
    /// a modulus in GPa written as Pa is valid physics, but usually makes
    /// the load's patch absurd.
    pub fn from_file(file: CaseFile) -> Result<Case, CaseError> {
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
        match Case::validate(file, material, soft.clone()) {
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
        mut notes: Vec<String>,
    ) -> Result<Case, CaseError> {
        let model = file.model;

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

        let mut prescribed_force = PrescribedForce::default();
        let mut step_forces = Vec::new();
        let mut step_gap_offsets_m = Vec::new();
        let kinematics = match (&file.rolling, &file.transient) {
            (Some(_), Some(_)) => {
                return Err(bad(
                    "transient",
                    "`[rolling]` and `[transient]` exclude each other; give one of them",
                ));
            }
            (Some(rs), None) => {
                let (r, force) = rs.split()?;
                r.check_input()?;
                check_line_rolling(rs, line)?;
                if force.any() && model != Model::Exact {
                    let key = if force.force_x_n.is_some() {
                        "rolling.force_x_n"
                    } else {
                        "rolling.force_y_n"
                    };
                    return Err(bad(
                        key,
                        format!(
                            "a prescribed force is solved with the exact model only, not {}{}: give \
                             `rolling.creepage_long`/`creepage_lat`, or `model = \"exact\"`",
                            model.name(),
                            if matches!(model, Model::Hertz | Model::HertzCorrected) {
                                " (it has no tangential forces)"
                            } else {
                                ""
                            }
                        ),
                    ));
                }
                prescribed_force = force;
                if model.is_cect() {
                    if let NormalLoad::Approach(_) = load {
                        return Err(bad(
                            "load.approach_m",
                            format!(
                                "the {} model rolls at a prescribed normal force: give `load.normal_force_n`",
                                model.name()
                            ),
                        ));
                    }
                }
                Kinematics::SteadyRolling(r)
            }
            (None, Some(t)) => {
                if t.steps.is_empty() {
                    return Err(bad("transient.steps", "needs at least one step"));
                }
                if let Some(dq) = t.rolling_step_m {
                    ranges::ROLLING_STEP.check("transient.rolling_step_m", dq)?;
                }
                if model.is_cect() {
                    Kinematics::Transient(static_compression(model, t)?)
                } else {
                    let mut steps = Vec::with_capacity(t.steps.len());
                    let mut forces = Vec::with_capacity(t.steps.len());
                    let mut offsets = Vec::with_capacity(t.steps.len());
                    let mut offset = 0.0;
                    for (k, s) in t.steps.iter().enumerate() {
                        let key = format!("transient.steps[{k}]");
                        let given_gap = file.geometry.gap_m.is_some();
                        let t = transient_step(
                            &key,
                            s,
                            load,
                            t.rolling_step_m,
                            line,
                            model,
                            given_gap,
                        )?;
                        offset += t.gap_travel_x_m;
                        offsets.push(offset);
                        if t.force.any() && model != Model::Exact {
                            return Err(bad(
                                format!("{key}.force_x_n"),
                                format!(
                                    "a prescribed force is solved with the exact model only, not {}",
                                    model.name()
                                ),
                            ));
                        }
                        steps.push(t.step);
                        forces.push(t.force);
                    }
                    if forces.iter().any(PrescribedForce::any) {
                        step_forces = forces;
                    }
                    if t.steps.iter().any(|s| s.gap_travel_x_m.is_some()) {
                        step_gap_offsets_m = offsets;
                    }
                    Kinematics::Transient(steps)
                }
            }
            (None, None) => Kinematics::Frictionless,
        };

        let needs_friction = match model {
            Model::Hertz | Model::HertzCorrected => false,
            Model::Fastsim => true,
            Model::Exact | Model::Cect | Model::CectHalfspace => {
                !matches!(kinematics, Kinematics::Frictionless)
            }
        };
        let (friction, has_friction) = match (&file.friction, needs_friction) {
            (Some(f), _) => {
                let friction = f.friction()?;
                if friction.slip_velocity_law.is_some() && model != Model::Exact {
                    return Err(bad(
                        "friction.law",
                        format!(
                            "a falling law is solved by the exact model only, not by `{}`",
                            model.name()
                        ),
                    ));
                }
                (friction, true)
            }
            (None, true) => {
                return Err(bad(
                    "friction.coefficient",
                    "missing: `[friction]` is needed for rolling, transient and FASTSIM cases",
                ));
            }
            (None, false) => (Friction::coulomb(0.0), false),
        };

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
            if friction.static_coefficient != friction.kinetic_coefficient {
                return Err(bad(
                    "friction.static_coefficient",
                    format!(
                        "the {} model takes one Coulomb coefficient: give `friction.coefficient` \
                         (or equal static and kinetic coefficients)",
                        model.name()
                    ),
                ));
            }
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
        let turns = direction.turns;
        let grid_given = file.grid.unwrap_or_default();
        let grid = grid_given;
        let default_n = if model == Model::Fastsim {
            DEFAULT_FASTSIM_ELEMENTS
        } else {
            DEFAULT_EXACT_ELEMENTS
        };
        if line {
            for (key, given) in [
                ("grid.ny", grid.ny.is_some()),
                ("grid.window_y_m", grid.window_y_m.is_some()),
            ] {
                if given {
                    return Err(bad(
                        key,
                        "a line contact has one row of strips standing for 1 m of the cylinders: leave it out",
                    ));
                }
            }
        }
        let nx = grid.nx.unwrap_or(default_n);
        let ny = grid
            .ny
            .unwrap_or(if line { MIN_ELEMENTS } else { default_n });
        for (key, n) in [("grid.nx", nx), ("grid.ny", ny)] {
            check_count(
                key,
                n,
                crate::core::grid::MIN_ELEMENTS,
                crate::core::grid::MAX_ELEMENTS_PER_DIRECTION,
            )?;
        }
        if let Some(w) = grid.window_x_m {
            ranges::WINDOW.check("grid.window_x_m", w)?;
        }
        if let Some(w) = grid.window_y_m {
            ranges::WINDOW.check("grid.window_y_m", w)?;
        }

        // Hertz patch of the largest load (on the flattened gap for the
        // conformal kinds): sizes the automatic window and checks a given one.
        let e_star = material.effective_modulus_pa();
        let (mut patch_x_m, mut patch_y_m) = (0.0f64, 0.0f64);
        let loads: Vec<(String, NormalLoad)> = match &kinematics {
            Kinematics::Transient(steps) if model == Model::Exact || model.is_cect() => steps
                .iter()
                .enumerate()
                .map(|(k, s)| {
                    let own = match &file.transient {
                        Some(t) => t
                            .steps
                            .get(k)
                            .is_some_and(|s| s.normal_force_n.is_some() || s.approach_m.is_some()),
                        None => false,
                    };
                    let key = if own {
                        format!("transient.steps[{k}]")
                    } else {
                        "load".to_string()
                    };
                    (key, s.load)
                })
                .collect(),
            _ => vec![("load".to_string(), load)],
        };
        for (key, l) in loads {
            if line {
                patch_x_m = patch_x_m.max(check_line_patch(&key, l, a_per_m, e_star)?);
                continue;
            }
            let h = check_hertz_patch(&key, l, a_per_m, b_per_m, e_star)?;
            patch_x_m = patch_x_m.max(h.semi_axis_x_m);
            patch_y_m = patch_y_m.max(h.semi_axis_y_m);
        }
        let (auto_x_m, auto_y_m) = if model.is_cect() {
            let cap = 2.0
                * CONFORMAL_WINDOW_MAX_HALF_ANGLE_DEG.to_radians()
                * geometry.mean_lateral_radius_m();
            (
                CONFORMAL_WINDOW_X_PER_SEMI_AXIS * patch_x_m,
                (CONFORMAL_WINDOW_S_PER_SEMI_AXIS * patch_y_m).min(cap),
            )
        } else {
            (
                AUTO_WINDOW_PER_SEMI_AXIS * patch_x_m,
                AUTO_WINDOW_PER_SEMI_AXIS * patch_y_m,
            )
        };
        let window_x_m = grid.window_x_m.unwrap_or(auto_x_m);
        let window_y_m = if line {
            LINE_LENGTH_M
        } else {
            grid.window_y_m.unwrap_or(auto_y_m)
        };
        if line && window_x_m > LINE_REFERENCE_DISTANCE_M {
            return Err(bad(
                "grid.window_x_m",
                format!(
                    "a line contact's window must be at most {LINE_REFERENCE_DISTANCE_M} m (the reference distance \
                     of its displacements), got {} m",
                    show(window_x_m)
                ),
            ));
        }
        let (nx_rows, ny) = if line { (1, 1) } else { (2, ny) };
        if model == Model::Exact || model.is_cect() {
            for (key, w, s, n, n_key) in [
                ("grid.window_x_m", window_x_m, patch_x_m, nx, "grid.nx"),
                ("grid.window_y_m", window_y_m, patch_y_m, ny, "grid.ny"),
            ]
            .into_iter()
            .take(nx_rows)
            {
                if model == Model::Exact && w < 2.0 * s {
                    return Err(bad(
                        key,
                        format!(
                            "the window ({:.4} mm) is smaller than the Hertz contact patch ({:.4} mm): enlarge it or leave it unset",
                            w * 1e3,
                            2.0 * s * 1e3
                        ),
                    ));
                }
                // A gap given per element (CONTACT's IBASE = 9) comes
                // with the grid it was given on: its user chose the
                // elements, down to CONTACT's one-element stiffness cases.
                let across = 2.0 * s / (w / n as f64);
                if across < ranges::MIN_ELEMENTS_ACROSS_PATCH && file.geometry.gap_m.is_none() {
                    return Err(bad(
                        key,
                        format!(
                            "the Hertz contact patch ({:.4} mm) spans only {across:.2} elements of this \
                             window ({} m over {n_key} = {n} elements); it needs at least {}: \
                             give the window in m (not mm), make it smaller, raise {n_key} or leave the window unset",
                            2.0 * s * 1e3,
                            show(w),
                            ranges::MIN_ELEMENTS_ACROSS_PATCH
                        ),
                    ));
                }
            }
            let axis_step = file.transient.as_ref().and_then(|t| t.rolling_step_m);
            if let Some(dq) = axis_step.filter(|_| direction.is_axis()) {
                let grid = if line {
                    Grid::line(nx, window_x_m)?
                } else {
                    Grid::centered(nx, ny, window_x_m, window_y_m)?
                };
                // Whole elements along the rolling direction.
                let grid = RollingFrame::new(turns, grid).rolling_grid();
                let key = "transient.rolling_step_m";
                let (w, n, axis) = if turns % 2 == 1 {
                    (window_y_m, ny, "y")
                } else {
                    (window_x_m, nx, "x")
                };
                let reason = match rolling_elements(key, dq, &grid) {
                    Ok(0) => format!("{} m is less than one element", show(dq)),
                    Err(ContactError::InvalidInput { reason, .. }) => reason,
                    _ => String::new(),
                };
                if !reason.is_empty() {
                    return Err(bad(
                        key,
                        format!(
                            "{reason} (grid.window_{axis}_m / grid.n{axis} = {} m / {n}): give \
                             grid.window_{axis}_m = n{axis} x rolling_step_m / k for a whole k",
                            show(w)
                        ),
                    ));
                }
            }
        } else if grid.window_x_m.is_some() || grid.window_y_m.is_some() {
            notes.push(format!(
                "the {} model uses the Hertz ellipse: grid.window_* ignored",
                model.name()
            ));
        }

        let mut settings = SolverSettings::default();
        if let Some(s) = file.solver {
            let mut normal = NormalSettings::default();
            let mut tangential = TangentialSettings::default();
            if let Some(t) = s.normal_tolerance {
                normal.tolerance = ranges::TOLERANCE.check("solver.normal_tolerance", t)?;
            }
            if let Some(t) = s.tangential_tolerance {
                tangential.tolerance = ranges::TOLERANCE.check("solver.tangential_tolerance", t)?;
            }
            if let Some(m) = s.max_iterations {
                let m = check_count("solver.max_iterations", m, 1, ranges::MAX_ITERATIONS)?;
                normal.max_iterations = m;
                tangential.max_iterations = m;
            }
            if let Some(t) = s.coupling_tolerance {
                settings.coupling_tolerance =
                    ranges::TOLERANCE.check("solver.coupling_tolerance", t)?;
            }
            if let Some(m) = s.coupling_max_iterations {
                settings.coupling_max_iterations = check_count(
                    "solver.coupling_max_iterations",
                    m,
                    1,
                    ranges::MAX_COUPLING_ITERATIONS,
                )?;
            }
            settings.normal = normal;
            settings.tangential = tangential;
            if !model.is_iterative() {
                notes.push(format!(
                    "the {} model has no iterative solver: [solver] ignored",
                    model.name()
                ));
            }
        }

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
        if let Some(visc) = &settings.viscoelastic {
            // Before any solver integrates the coefficients (seconds).
            check_viscoelastic_grid(visc, nx, ny, geometry.is_line())?;
        }
        Ok(Case {
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
        })
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

/// Rejects a load whose Hertz patch on the case's geometry and material
/// is outside [`ranges::HERTZ_SEMI_AXIS`] (a unit mistake in one of them);
/// the error names the load `key` (`load`, `transient.steps[k]`) and quotes
/// the values it depends on.
fn check_hertz_patch(
    key: &str,
    load: NormalLoad,
    a_per_m: f64,
    b_per_m: f64,
    e_star: f64,
) -> Result<HertzSolution, CaseError> {
    let r = ranges::HERTZ_SEMI_AXIS;
    let h = hertz_of(a_per_m, b_per_m, e_star, load);
    let axes = match &h {
        Ok(h) if r.contains(h.semi_axis_x_m) && r.contains(h.semi_axis_y_m) => return Ok(*h),
        Ok(h) => format!(
            "has semi-axes {} x {} m",
            show(h.semi_axis_x_m),
            show(h.semi_axis_y_m)
        ),
        Err(_) => "has no finite semi-axes".to_string(),
    };
    let (field, value) = match load {
        NormalLoad::NormalForce(f) => ("normal_force_n", format!("{} N", show(f))),
        NormalLoad::Approach(d) => ("approach_m", format!("{} m", show(d))),
    };
    Err(bad(
        format!("{key}.{field}"),
        format!(
            "the Hertz patch of {value} on this geometry (A = {} 1/m, B = {} 1/m) and material \
             (E* = {} Pa) {axes}, outside {}: check the units \
             (forces in N, lengths in m, curvatures in 1/m, moduli in Pa)",
            show(a_per_m),
            show(b_per_m),
            show(e_star),
            r.describe()
        ),
    ))
}

/// The half-width \[m\] of the contact of a line load on cylinders with
/// h = A x² (2-D Hertz, Johnson 1985 §4.3: a² = 4 P' R /
/// (pi E*), R = 1/(2A)), rejected outside [`ranges::HERTZ_SEMI_AXIS`] as
/// [`check_hertz_patch`] does. For an approach d the half-width solves
/// d = A a² (ln(2 R0 / a) + 1/2), R0 the reference distance of the
/// displacements ([`LINE_REFERENCE_DISTANCE_M`]): the approach of the
/// Hertz pressure on the half-plane (Johnson 1985 §5.2).
fn check_line_patch(
    key: &str,
    load: NormalLoad,
    a_per_m: f64,
    e_star: f64,
) -> Result<f64, CaseError> {
    let r0 = LINE_REFERENCE_DISTANCE_M;
    let half = match load {
        NormalLoad::NormalForce(f) => (2.0 * f / (std::f64::consts::PI * a_per_m * e_star)).sqrt(),
        NormalLoad::Approach(d) => {
            // d(a) increases on (0, 2 R0): bisection on a logarithmic scale.
            let approach = |a: f64| a_per_m * a * a * ((2.0 * r0 / a).ln() + 0.5);
            let (mut lo, mut hi) = (1e-12_f64, r0);
            if approach(hi) < d {
                lo = hi;
            }
            for _ in 0..200 {
                let mid = (lo * hi).sqrt();
                if approach(mid) < d {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            hi
        }
    };
    let r = ranges::HERTZ_SEMI_AXIS;
    if r.contains(half) {
        return Ok(half);
    }
    let (field, value) = match load {
        NormalLoad::NormalForce(f) => ("normal_force_n_per_m", format!("{} N/m", show(f))),
        NormalLoad::Approach(d) => ("approach_m", format!("{} m", show(d))),
    };
    Err(bad(
        format!("{key}.{field}"),
        format!(
            "the 2-D Hertz contact of {value} on these cylinders (A = {} 1/m) and material \
             (E* = {} Pa) has the half-width {} m, outside {}: check the units \
             (forces per metre in N/m, lengths in m, curvatures in 1/m, moduli in Pa)",
            show(a_per_m),
            show(e_star),
            show(half),
            r.describe()
        ),
    ))
}

/// Refuses what a line contact cannot roll with (lateral creepage, spin,
/// a lateral or total force), and a force per metre on other geometries.
fn check_line_rolling(r: &RollingSection, line: bool) -> Result<(), CaseError> {
    if !line {
        if r.force_x_n_per_m.is_some() {
            return Err(bad(
                "rolling.force_x_n_per_m",
                "a force per metre is for `geometry.kind = \"line\"`: give `rolling.force_x_n` [N]",
            ));
        }
        return Ok(());
    }
    refuse_lateral(
        "rolling",
        "rolls",
        &[
            ("creepage_lat", r.creepage_lat.is_some_and(|v| v != 0.0)),
            ("spin_per_m", r.spin_per_m != 0.0),
            ("force_y_n", r.force_y_n.is_some()),
        ],
    )?;
    if r.force_x_n.is_some() {
        return Err(bad(
            "rolling.force_x_n",
            "a line contact's forces are per metre: give `rolling.force_x_n_per_m` [N/m]",
        ));
    }
    Ok(())
}

/// A line contact moves in x only: the first of `lateral` (a key under
/// `section` and whether it is given) that is given is refused, naming
/// it; `moves` is "rolls" or "shifts".
fn refuse_lateral(section: &str, moves: &str, lateral: &[(&str, bool)]) -> Result<(), CaseError> {
    match lateral.iter().find(|(_, given)| *given) {
        Some((key, _)) => Err(bad(
            format!("{section}.{key}"),
            format!("a line contact {moves} in x only: give 0 or leave it out"),
        )),
        None => Ok(()),
    }
}

/// Rejects a model that cannot run on the geometry; the error names `model`.
/// The [`Direction`] of `rolling_direction_rad` (see
/// [`crate::core::frame`]): the exact model rolls in any direction (a line
/// contact 0 or pi), steady rolling along a grid axis (a multiple of pi/2)
/// and transient rolling steps in any; the other models roll in +x; flash
/// temperatures roll in +x.
fn rolling_direction(file: &CaseFile, model: Model, line: bool) -> Result<Direction, CaseError> {
    let key = ROLLING_DIRECTION_KEY;
    let d = direction(file.rolling_direction_rad, line)?;
    let along_x = d.turns == 0 && d.is_axis();
    if !along_x && model != Model::Exact {
        return Err(bad(
            key,
            format!(
                "the exact model rolls in other directions than +x, not {}: leave it 0",
                model.name()
            ),
        ));
    }
    if !along_x && file.temperature.is_some() {
        return Err(bad(
            key,
            "the flash temperatures are computed for rolling in +x: leave it 0 or leave out [temperature]",
        ));
    }
    if !d.is_axis() && file.transient.is_none() {
        axis_turns(file.rolling_direction_rad, line)?;
    }
    Ok(d)
}

/// Checks that `values` (named `key`) hold one value per element of an
/// `n[0]` x `n[1]` grid that the case gives (`grid`), each in `range`.
fn per_element_values(
    key: &str,
    values: &[f64],
    n: [usize; 2],
    grid: GridSection,
    line: bool,
    range: Range,
) -> Result<(), CaseError> {
    let given = grid.nx.is_some() && (line || grid.ny.is_some());
    if !given {
        return Err(bad(
            key,
            "gives values per element: give the grid's `grid.nx` and `grid.ny` too",
        ));
    }
    let elements = if line { n[0] } else { n[0] * n[1] };
    if values.len() != elements {
        return Err(bad(
            key,
            format!(
                "has {} values for a grid of {elements} elements (nx = {}{})",
                values.len(),
                n[0],
                if line {
                    String::new()
                } else {
                    format!(", ny = {}", n[1])
                }
            ),
        ));
    }
    for (i, &v) in values.iter().enumerate() {
        range.check(&format!("{key}[{i}]"), v)?;
    }
    Ok(())
}

/// `geometry.gap_m`, checked: exact model on a quadratic or line geometry.
fn given_gap(
    file: &CaseFile,
    model: Model,
    geometry: &CaseGeometry,
    n: [usize; 2],
    grid: GridSection,
) -> Result<Option<Vec<f64>>, CaseError> {
    let Some(h) = &file.geometry.gap_m else {
        return Ok(None);
    };
    let key = "geometry.gap_m";
    if model != Model::Exact || geometry.is_conformal() {
        return Err(bad(
            key,
            format!(
                "a gap per element is solved by the exact model on `kind = \"quadratic\"` or `\"line\"`, \
                 not {} on `{}`",
                model.name(),
                file.geometry.kind.name()
            ),
        ));
    }
    per_element_values(key, h, n, grid, geometry.is_line(), ranges::GAP)?;
    Ok(Some(h.clone()))
}

/// `[extra_rigid_slip]`, checked: exact model, rolling kinematics.
fn extra_rigid_slip(
    file: &CaseFile,
    model: Model,
    kinematics: &Kinematics,
    n: [usize; 2],
    grid: GridSection,
) -> Result<Option<ExtraRigidSlip>, CaseError> {
    let Some(e) = &file.extra_rigid_slip else {
        return Ok(None);
    };
    let key = "extra_rigid_slip";
    if model != Model::Exact {
        return Err(bad(
            key,
            format!(
                "an extra rigid slip is solved by the exact model only, not {}",
                model.name()
            ),
        ));
    }
    let line = file.geometry.kind == GeometryKind::Line;
    let elements = if line { n[0] } else { n[0] * n[1] };
    // One pair: both components, zeros for one left out; empty without.
    let pair = |names: [&str; 2], given: [&Option<Vec<f64>>; 2], range: Range| {
        let mut out = [Vec::new(), Vec::new()];
        if given.iter().all(|v| v.is_none()) {
            return Ok(out);
        }
        for (k, (name, v)) in names.into_iter().zip(given).enumerate() {
            out[k] = match v {
                Some(v) => {
                    per_element_values(&format!("{key}.{name}"), v, n, grid, line, range)?;
                    v.clone()
                }
                None => vec![0.0; elements],
            };
        }
        Ok::<_, CaseError>(out)
    };
    let [slip_x, slip_y] = pair(["slip_x", "slip_y"], [&e.slip_x, &e.slip_y], CREEPAGE_RANGE)?;
    let [shift_x_m, shift_y_m] = pair(
        ["shift_x_m", "shift_y_m"],
        [&e.shift_x_m, &e.shift_y_m],
        ranges::SHIFT,
    )?;
    let extra = ExtraRigidSlip {
        slip_x,
        slip_y,
        shift_x_m,
        shift_y_m,
    };
    if !extra.has_slip() && !extra.has_shift() {
        return Err(bad(
            key,
            "give `extra_rigid_slip.slip_x` and/or `slip_y` (rolling), or `shift_x_m` and/or \
             `shift_y_m` (shift steps)",
        ));
    }
    extra.check_kinematics(kinematics)?;
    Ok(Some(extra))
}

fn check_model_geometry(model: Model, geometry: &CaseGeometry) -> Result<(), CaseError> {
    match (model, geometry) {
        (Model::Exact, CaseGeometry::Line) => Ok(()),
        (_, CaseGeometry::Line) => Err(bad(
            "model",
            format!(
                "model = \"{}\": a line contact (`geometry.kind = \"line\"`) is solved with the exact model only",
                model.name()
            ),
        )),
        (Model::Cect | Model::CectHalfspace | Model::HertzCorrected, CaseGeometry::Quadratic) => {
            Err(bad(
                "model",
                format!(
                    "model = \"{}\" is a conformal model: it needs `geometry.kind = \"conformal_circular\"` \
                     or `\"conformal_points\"`, not \"quadratic\"",
                    model.name()
                ),
            ))
        }
        (
            Model::Hertz | Model::HertzCorrected | Model::Exact | Model::Fastsim,
            CaseGeometry::ConformalPoints { .. },
        ) => Err(bad(
            "model",
            format!(
                "model = \"{}\" needs circular profiles (`geometry.kind = \"conformal_circular\"`) \
                 or a quadratic gap; profiles given as points run with model = \"cect\" or \"cect_halfspace\"",
                model.name()
            ),
        )),
        _ => Ok(()),
    }
}

/// A transient step as the core solves it: the step and the force
/// prescribed in it (none: the step is solved as given).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TransientStep {
    /// The step; in a direction with a prescribed force its shift is the
    /// iteration's start (0).
    pub step: ShiftStep,
    /// The force prescribed in the step.
    pub force: PrescribedForce,
    /// How far the bodies' undeformed distance travels over the grid in
    /// the step \[m\] (`gap_travel_x_m`, 0 when not given).
    pub gap_travel_x_m: f64,
}

/// The core step of a step section `s` named `key`: a rolling step of
/// the step's `rolling_m` or `rolling_step_m` (`transient.rolling_step_m`)
/// when it gives creepages, else a shift step (rolling its own
/// `rolling_m`, if given); its load defaults to `default_load` (per metre
/// when `line`, a line contact, which shifts and rolls in x only); with
/// the force it prescribes. Checks the ranges and that a step is one kind
/// or the other and gives either the shift (creepage) or the force of a
/// direction, and its `gap_travel_x_m` (only in a shift step of the exact
/// `model` without a gap given per element, `given_gap`), naming the key.
pub fn transient_step(
    key: &str,
    s: &StepSection,
    default_load: NormalLoad,
    rolling_step_m: Option<f64>,
    line: bool,
    model: Model,
    given_gap: bool,
) -> Result<TransientStep, CaseError> {
    let gap_travel_x_m = gap_travel(key, s, model, given_gap)?;
    let load = one_load(
        key,
        s.normal_force_n,
        s.normal_force_n_per_m,
        s.approach_m,
        line,
    )?
    .unwrap_or(default_load);
    if line {
        refuse_lateral(
            key,
            "shifts",
            &[
                ("shift_y_m", s.shift_y_m != 0.0),
                ("rotation_rad", s.rotation_rad != 0.0),
                ("force_y_n", s.force_y_n.is_some()),
            ],
        )?;
    }
    let force = s.force(key, line)?;
    if let Some(dq) = s.rolling_m {
        ranges::ROLLING_STEP.check(&format!("{key}.rolling_m"), dq)?;
    }
    let fx_key = if line { "force_x_n_per_m" } else { "force_x_n" };
    let either = |given: &str, force: &str| {
        bad(
            format!("{key}.{force}"),
            format!("give either `{key}.{given}` or `{key}.{force}`, not both"),
        )
    };
    let step = match s.creepages(key)? {
        Some(c) => {
            if line {
                refuse_lateral(
                    key,
                    "rolls",
                    &[
                        ("creepage_lat", c.creepage_lat != 0.0),
                        ("spin_per_m", c.spin_per_m != 0.0),
                    ],
                )?;
            }
            for (name, given) in [
                ("shift_x_m", s.shift_x_m.is_some()),
                ("shift_y_m", s.shift_y_m != 0.0),
                ("rotation_rad", s.rotation_rad != 0.0),
            ] {
                if given {
                    return Err(bad(
                        format!("{key}.{name}"),
                        "a rolling step (one with creepages) takes no shift: its shift is the \
                         creepages times its rolling distance",
                    ));
                }
            }
            if force.force_x_n.is_some() && s.creepage_long.is_some() {
                return Err(either("creepage_long", fx_key));
            }
            if force.force_y_n.is_some() && s.creepage_lat.is_some() {
                return Err(either("creepage_lat", "force_y_n"));
            }
            let dq = s.rolling_m.or(rolling_step_m).ok_or_else(|| {
                bad(
                    "transient.rolling_step_m",
                    format!(
                        "missing: {key} gives creepages, so it rolls `transient.rolling_step_m` m \
                         (or its own `{key}.rolling_m`)"
                    ),
                )
            })?;
            ShiftStep::rolling(load, dq, &c)
        }
        None => {
            let shift_x_m = match (s.shift_x_m, force.force_x_n) {
                (Some(_), Some(_)) => return Err(either("shift_x_m", fx_key)),
                (Some(x), None) => x,
                (None, Some(_)) => 0.0,
                (None, None) => {
                    return Err(bad(
                        format!("{key}.shift_x_m"),
                        format!(
                            "missing: give the shift (a shift step), `{fx_key}` (a prescribed \
                             force) or creepages (a rolling step)"
                        ),
                    ))
                }
            };
            if force.force_y_n.is_some() && s.shift_y_m != 0.0 {
                return Err(either("shift_y_m", "force_y_n"));
            }
            ShiftStep {
                load,
                shift_x_m,
                shift_y_m: s.shift_y_m,
                rotation_rad: s.rotation_rad,
                rolling_m: s.rolling_m.unwrap_or(0.0),
            }
        }
    };
    check_shift_step(key, &step)?;
    Ok(TransientStep {
        step,
        force,
        gap_travel_x_m,
    })
}

/// The `gap_travel_x_m` of step `s` named `key` (0 when not given),
/// checked: a shift step of the exact `model` whose gap is the quadratic
/// one (`given_gap`: an undeformed distance given per element, which does
/// not travel).
fn gap_travel(key: &str, s: &StepSection, model: Model, given_gap: bool) -> Result<f64, CaseError> {
    let Some(t) = s.gap_travel_x_m else {
        return Ok(0.0);
    };
    let name = format!("{key}.gap_travel_x_m");
    ranges::GAP_TRAVEL.check(&name, t)?;
    let rolls = s.rolling_m.is_some()
        || s.creepage_long.is_some()
        || s.creepage_lat.is_some()
        || s.spin_per_m.is_some();
    let reason = if rolls {
        "is for shift steps on a fixed grid: a rolling step's grid moves with the bodies"
    } else if model != Model::Exact {
        "is solved by the exact model only"
    } else if given_gap {
        "moves the quadratic undeformed distance: not with a gap given per element \
         (`geometry.gap_m`, `geometry.extra_gap_m`)"
    } else {
        return Ok(t);
    };
    Err(bad(name, reason))
}

/// Checks a transient step's shifts and rotation against their ranges
/// (its load is checked where it is read); `key` names the step.
pub fn check_shift_step(key: &str, s: &ShiftStep) -> Result<(), CaseError> {
    ranges::SHIFT.check(&format!("{key}.shift_x_m"), s.shift_x_m)?;
    ranges::SHIFT.check(&format!("{key}.shift_y_m"), s.shift_y_m)?;
    ranges::ROTATION.check(&format!("{key}.rotation_rad"), s.rotation_rad)?;
    Ok(())
}

/// The steps of a static compression (conformal models): every shift zero,
/// no rolling, every step with a `normal_force_n`, increasing.
fn static_compression(model: Model, t: &TransientSection) -> Result<Vec<ShiftStep>, CaseError> {
    let no_rolling = |key: String| {
        bad(
            key,
            format!(
                "the {} model runs static compression only: no rolling steps",
                model.name()
            ),
        )
    };
    if t.rolling_step_m.is_some() {
        return Err(no_rolling("transient.rolling_step_m".into()));
    }
    let mut out: Vec<ShiftStep> = Vec::with_capacity(t.steps.len());
    let mut previous = 0.0;
    for (k, s) in t.steps.iter().enumerate() {
        let key = format!("transient.steps[{k}]");
        if s.creepages(&key)?.is_some() {
            return Err(no_rolling(format!("{key}.creepage_long")));
        }
        if s.rolling_m.is_some() {
            return Err(no_rolling(format!("{key}.rolling_m")));
        }
        for (name, given) in [
            ("force_x_n", s.force_x_n.is_some()),
            ("force_y_n", s.force_y_n.is_some()),
            ("force_x_n_per_m", s.force_x_n_per_m.is_some()),
        ] {
            if given {
                return Err(bad(
                    format!("{key}.{name}"),
                    format!(
                        "the {} model runs static compression only: no tangential forces",
                        model.name()
                    ),
                ));
            }
        }
        for (name, v) in [
            ("shift_x_m", s.shift_x_m.unwrap_or(0.0)),
            ("shift_y_m", s.shift_y_m),
            ("rotation_rad", s.rotation_rad),
        ] {
            if v != 0.0 {
                return Err(bad(
                    format!("{key}.{name}"),
                    format!(
                        "the {} model runs static compression only: shifts and rotations must be 0, got {v}",
                        model.name()
                    ),
                ));
            }
        }
        if s.approach_m.is_some() {
            return Err(bad(
                format!("{key}.approach_m"),
                format!(
                    "the {} model's load steps are forces: give `normal_force_n` instead",
                    model.name()
                ),
            ));
        }
        let f = s.normal_force_n.ok_or_else(|| {
            bad(
                format!("{key}.normal_force_n"),
                "missing: every static compression step gives its normal force",
            )
        })?;
        ranges::NORMAL_FORCE.check(&format!("{key}.normal_force_n"), f)?;
        if f <= previous {
            return Err(bad(
                format!("{key}.normal_force_n"),
                format!("static compression loads monotonically: {f} N must exceed the previous step's {previous} N"),
            ));
        }
        previous = f;
        out.push(ShiftStep {
            load: NormalLoad::NormalForce(f),
            shift_x_m: 0.0,
            shift_y_m: 0.0,
            rotation_rad: 0.0,
            rolling_m: 0.0,
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
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
        let text = include_str!("../../../../examples/cases/transient_rolling.toml");
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

#[cfg(test)]
mod prescribed_force_tests {
    use super::*;

    fn case(model: &str, rolling: &str) -> Result<Case, CaseError> {
        Case::from_toml(&format!(
            "model = \"{model}\"\n[material]\nshear_modulus_pa = 81.0e9\npoisson_ratio = 0.3\n\
             [friction]\ncoefficient = 0.3\n[geometry]\nkind = \"quadratic\"\na_per_m = 1.0\n\
             b_per_m = 1.0\n[load]\nnormal_force_n = 1e4\n[rolling]\n{rolling}\n"
        ))
    }

    fn message(r: Result<Case, CaseError>) -> String {
        match r {
            Err(CaseError::BadInput(m)) => m,
            other => panic!("expected bad input, got {other:?}"),
        }
    }

    #[test]
    fn a_force_replaces_the_creepage_of_its_direction() {
        let c = case(
            "exact",
            "force_x_n = -500.0\ncreepage_lat = 2e-4\nspin_per_m = 0.1",
        )
        .unwrap();
        assert_eq!(c.prescribed_force.force_x_n, Some(-500.0));
        assert_eq!(c.prescribed_force.force_y_n, None);
        // The iteration starts from creepage 0; the other ones are kept.
        assert_eq!(
            c.kinematics,
            Kinematics::SteadyRolling(Creepages {
                creepage_long: 0.0,
                creepage_lat: 2e-4,
                spin_per_m: 0.1
            })
        );
        let c = case("exact", "force_x_n = -500.0\nforce_y_n = 100.0").unwrap();
        assert_eq!(c.prescribed_force.force_y_n, Some(100.0));
    }

    #[test]
    fn both_keys_of_a_direction_and_other_models_are_refused_naming_the_keys() {
        for (creep, force) in [
            ("creepage_long", "force_x_n"),
            ("creepage_lat", "force_y_n"),
        ] {
            let m = message(case("exact", &format!("{creep} = 1e-3\n{force} = -10.0")));
            assert!(
                m.contains(&format!("`rolling.{force}`"))
                    && m.contains(&format!("`rolling.{creep}`")),
                "{m}"
            );
        }
        let m = message(case("exact", "force_y_n = 1e300"));
        assert!(m.contains("rolling.force_y_n"), "{m}");
        let m = message(case("hertz", "force_x_n = -10.0"));
        assert!(
            m.contains("rolling.force_x_n") && m.contains("no tangential forces"),
            "{m}"
        );
        let m = message(case("fastsim", "force_y_n = -10.0"));
        assert!(
            m.contains("rolling.force_y_n") && m.contains("exact model only"),
            "{m}"
        );
    }
}

#[cfg(test)]
mod step_force_tests {
    use super::*;
    use crate::problem::ExactRun;

    /// A transient exact case (0.5 mm elements on 16 x 16) with `steps`.
    fn case(steps: &str) -> Result<Case, CaseError> {
        Case::from_toml(&format!(
            "model = \"exact\"\n[material]\nshear_modulus_pa = 81.0e9\npoisson_ratio = 0.3\n\
             [friction]\ncoefficient = 0.3\n[geometry]\nkind = \"quadratic\"\na_per_m = 1.0\n\
             b_per_m = 1.0\n[load]\nnormal_force_n = 1e4\n[grid]\nnx = 16\nny = 16\n\
             window_x_m = 8e-3\nwindow_y_m = 8e-3\n[transient]\nrolling_step_m = 5e-4\n\
             steps = [{steps}]\n"
        ))
    }

    fn message(r: Result<Case, CaseError>) -> String {
        match r {
            Err(CaseError::BadInput(m)) => m,
            other => panic!("expected bad input, got {other:?}"),
        }
    }

    #[test]
    fn a_step_force_replaces_the_shift_or_creepage_of_its_direction() {
        let c = case(
            "{ shift_x_m = 1e-6 }, { force_x_n = -300.0, shift_y_m = 1e-7 }, \
             { force_y_n = 200.0, creepage_long = 1e-3 }, { force_x_n = -100.0, rolling_m = 1e-3 }",
        )
        .unwrap();
        let x = |f: f64| PrescribedForce {
            force_x_n: Some(f),
            force_y_n: None,
        };
        assert_eq!(
            c.step_forces,
            [
                PrescribedForce::default(),
                x(-300.0),
                PrescribedForce {
                    force_x_n: None,
                    force_y_n: Some(200.0)
                },
                x(-100.0)
            ]
        );
        let Kinematics::Transient(steps) = &c.kinematics else {
            panic!("{:?}", c.kinematics)
        };
        // The prescribed directions start from 0; a rolling step rolls
        // `transient.rolling_step_m` or its own `rolling_m`.
        let shifts: Vec<[f64; 3]> = steps
            .iter()
            .map(|s| [s.shift_x_m, s.shift_y_m, s.rolling_m])
            .collect();
        assert_eq!(
            shifts,
            [
                [1e-6, 0.0, 0.0],
                [0.0, 1e-7, 0.0],
                [1e-3 * 5e-4, 0.0, 5e-4],
                [0.0, 0.0, 1e-3]
            ]
        );
        assert!(case("{ shift_x_m = 1e-6 }").unwrap().step_forces.is_empty());
        // Travel accumulates over the steps.
        let c = case(
            "{ shift_x_m = 0.0, gap_travel_x_m = -1e-3 }, { shift_x_m = 0.0 }, \
             { shift_x_m = 0.0, gap_travel_x_m = 5e-4 }",
        )
        .unwrap();
        assert_eq!(c.step_gap_offsets_m, [-1e-3, -1e-3, -5e-4]);
        assert!(case("{ shift_x_m = 1e-6 }")
            .unwrap()
            .step_gap_offsets_m
            .is_empty());
    }

    #[test]
    fn conflicting_step_keys_are_refused_naming_them() {
        for (steps, keys) in [
            (
                "{ shift_x_m = 1e-6, force_x_n = 10.0 }",
                &[
                    "transient.steps[0].force_x_n",
                    "transient.steps[0].shift_x_m",
                ][..],
            ),
            (
                "{ shift_x_m = 0.0, shift_y_m = 1e-6, force_y_n = 10.0 }",
                &["transient.steps[0].force_y_n"],
            ),
            (
                "{ creepage_long = 1e-3, force_x_n = 10.0 }",
                &["transient.steps[0].force_x_n", "creepage_long"],
            ),
            (
                "{ force_x_n = 10.0, force_y_n = 10.0, shift_y_m = 1e-7 }",
                &["transient.steps[0].force_y_n", "shift_y_m"],
            ),
            (
                "{ force_x_n_per_m = 10.0 }",
                &["transient.steps[0].force_x_n_per_m", "line"],
            ),
            ("{ force_x_n = 1e300 }", &["transient.steps[0].force_x_n"]),
            ("{ force_x_n = nan }", &["transient.steps[0].force_x_n"]),
            (
                "{ shift_x_m = 0.0 }, { force_x_n = 1.0, rolling_m = -1e-4 }",
                &["transient.steps[1].rolling_m"],
            ),
            (
                "{ rolling_m = 5e-4 }",
                &["transient.steps[0].shift_x_m", "force_x_n"],
            ),
            (
                "{ shift_x_m = 0.0 }, { creepage_long = 1e-3, gap_travel_x_m = 5e-4 }",
                &["transient.steps[1].gap_travel_x_m", "rolling step"],
            ),
            (
                "{ shift_x_m = 0.0, gap_travel_x_m = 2.0 }",
                &["transient.steps[0].gap_travel_x_m"],
            ),
        ] {
            let m = message(case(steps));
            for k in keys {
                assert!(m.contains(k), "{steps}: {m}");
            }
        }
    }

    #[test]
    fn bodies_travelling_off_the_grid_are_told_how_far_they_went() {
        // A patch of radius 3.2 mm on a window of 8 mm: 1.5 mm of travel
        // puts it on the grid's border.
        let c = case("{ shift_x_m = 0.0 }, { shift_x_m = 0.0, gap_travel_x_m = 1.5e-3 }").unwrap();
        let m = ExactRun::solve(&c).err().unwrap().to_string();
        assert!(
            m.contains("grid.window_x_m")
                && m.contains("transient.steps[1]")
                && m.contains("0.0015 m"),
            "{m}"
        );
    }

    #[test]
    fn step_forces_are_solved_and_reported_per_step() {
        // The Fx of a forward step, prescribed, gives back its shift.
        let forward = case("{ shift_x_m = 0.0 }, { shift_x_m = 2e-6 }").unwrap();
        let run = ExactRun::solve(&forward).unwrap();
        let fx = run.last().totals.fx_n;
        let c = case(&format!("{{ shift_x_m = 0.0 }}, {{ force_x_n = {fx:e} }}")).unwrap();
        let run = ExactRun::solve(&c).unwrap();
        let report = run.report(&c, false);
        let steps = report.steps.as_ref().unwrap();
        assert_eq!(steps[0].force_control, None);
        let f = steps[1].force_control.unwrap();
        assert!((f.shift_x_m - 2e-6).abs() < 1e-6 * 2e-6, "{f:?}");
        assert_eq!((f.creepage_long, f.rolling_m), (None, 0.0));
        let text = report.human();
        assert!(
            text.contains("step 2 prescribed force: shift x, y"),
            "{text}"
        );
        // Saturation names the step.
        let c = case("{ shift_x_m = 0.0 }, { force_x_n = -3000.0 }").unwrap();
        let e = ExactRun::solve(&c).err().unwrap().to_string();
        assert!(e.contains("transient.steps[1].force_x_n"), "{e}");
    }
}

#[cfg(test)]
mod subsurface_tests {
    use super::tests::ROLLING;
    use super::*;
    use crate::conformal::frictional::FrictionalWorkspace;
    use crate::problem::ModelRun;

    fn bad(extra: &str) -> String {
        match Case::from_toml(&format!("{ROLLING}{extra}")) {
            Err(CaseError::BadInput(m)) => m,
            other => panic!("expected bad input, got {other:?}"),
        }
    }

    #[test]
    fn subsurface_section_is_checked_and_names_the_key() {
        let c = Case::from_toml(&format!(
            "{ROLLING}[subsurface]\nmax_depth_m = 3e-3\ndepth_count = 4\n"
        ))
        .unwrap();
        let r = c.subsurface.unwrap();
        assert_eq!(r.depths_m.len(), 4);
        for (got, want) in r.depths_m.iter().zip([0.0, 1e-3, 2e-3, 3e-3]) {
            assert!((got - want).abs() < 1e-18);
        }
        assert!(bad("[subsurface]\n").contains("`subsurface.depths_m`"));
        assert!(
            bad("[subsurface]\ndepths_m = [1e-3, -1e-3]\n").contains("`subsurface.depths_m[1]`")
        );
        assert!(
            bad("[subsurface]\ndepths_m = [1e-3]\nmax_depth_m = 1e-3\ndepth_count = 2\n")
                .contains("not both")
        );
        assert!(bad("[subsurface]\nmax_depth_m = 1e-3\n").contains("`subsurface.depth_count`"));
        assert!(bad("[subsurface]\nmax_depth_m = 3\ndepth_count = 4\n")
            .contains("`subsurface.max_depth_m`"));
        assert!(
            bad("[subsurface]\ndepths_m = [1e-3]\nshear_yield_stress_pa = -1.0\n")
                .contains("`subsurface.shear_yield_stress_pa`")
        );
        assert!(bad("[subsurface]\ndepths = [1e-3]\n").contains("depths"));
        let m = match Case::from_toml(&format!(
            "model = \"fastsim\"\n{ROLLING}[subsurface]\ndepths_m = [1e-3]\n"
        )) {
            Err(CaseError::BadInput(m)) => m,
            other => panic!("expected bad input, got {other:?}"),
        };
        assert!(m.contains("`subsurface`") && m.contains("exact"), "{m}");
    }

    #[test]
    fn exact_run_reports_the_subsurface_peaks() {
        let c = Case::from_toml(&format!(
            "{ROLLING}[subsurface]\ndepths_m = [0.0, 1e-3, 2e-3, 3e-3, 4e-3]\nshear_yield_stress_pa = 300e6\n"
        ))
        .unwrap();
        let run = ModelRun::solve(&c, &mut FrictionalWorkspace::default()).unwrap();
        let report = run.report(&c, false);
        let s = report.subsurface.as_ref().unwrap();
        let t = &report.totals.totals;
        // Below a Hertz-like patch with little traction (Fx < 0.3 Fn) the
        // largest shear sits under the surface and is about 0.3 p0
        // (Johnson 1985 §4.2: 0.31 p0 for a circle).
        let ratio = s.body1.max_shear.value_pa / t.max_pressure_pa;
        assert!((0.27..0.34).contains(&ratio), "{ratio}");
        assert!(s.body1.max_shear.depth_m > 0.0);
        assert_eq!(s.body1.max_shear.depth_m, s.body2.max_shear.depth_m);
        let fi = s.surface_fatigue_index.unwrap();
        let f = t.fx_n.hypot(t.fy_n) / t.normal_force_n;
        assert!(
            (fi - (f - 2.0 * t.contact_area_m2 * 300e6 / (3.0 * t.normal_force_n))).abs() < 1e-12
        );
        assert!(report.human().contains("body 2 max von Mises [MPa]"));
        let json = serde_json::to_string(&report).unwrap();
        assert!(json.contains("\"subsurface\":{\"depths_m\""), "{json}");
    }
}

#[cfg(test)]
mod line_contact_tests {
    use super::*;

    /// CONTACT's carter2d (examples/carter2d.inp) as a case: 178 900 N/m.
    const LINE: &str = r#"
[material]
shear_modulus_pa = 82.0e9
poisson_ratio = 0.28
[friction]
coefficient = 0.3
[geometry]
kind = "line"
a_per_m = 1.0
[load]
normal_force_n_per_m = 178900.0
[rolling]
creepage_long = -2.4e-4
[grid]
nx = 55
"#;

    fn err(text: &str) -> String {
        match Case::from_toml(text) {
            Err(CaseError::BadInput(m)) => m,
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn a_line_case_has_one_row_and_the_2d_hertz_window() {
        let c = Case::from_toml(LINE).unwrap();
        assert!(c.geometry.is_line());
        assert_eq!((c.nx, c.ny), (55, 1));
        // 2.4 x the 2-D Hertz half-width a = sqrt(4 P' R / (pi E*)) = 1 mm
        // (R = 0.5 m, E* = G/(1 - nu)).
        assert!(
            (c.window_x_m / 2.4e-3 - 1.0).abs() < 1e-3,
            "{}",
            c.window_x_m
        );
        let g = c.grid().unwrap();
        assert!(g.is_line() && g.ny == 1 && g.dy_m == LINE_LENGTH_M);
        assert_eq!(c.load, NormalLoad::NormalForce(178_900.0));
        // An approach gives the window of the load with that approach:
        // d = A a² (ln(2 R0 / a) + 1/2) at a = 1 mm.
        let d = 1e-6 * ((2.0f64 / 1e-3).ln() + 0.5);
        let by_approach = LINE.replace(
            "normal_force_n_per_m = 178900.0",
            &format!("approach_m = {d:e}"),
        );
        let c = Case::from_toml(&by_approach).unwrap();
        assert!(
            (c.window_x_m / 2.4e-3 - 1.0).abs() < 1e-6,
            "{}",
            c.window_x_m
        );
    }

    #[test]
    fn a_line_case_refuses_three_dimensional_keys_naming_them() {
        for (from, to, key) in [
            (
                "normal_force_n_per_m",
                "normal_force_n",
                "`load.normal_force_n`",
            ),
            ("nx = 55", "nx = 55\nny = 8", "`grid.ny`"),
            ("nx = 55", "nx = 55\nwindow_y_m = 0.01", "`grid.window_y_m`"),
            (
                "a_per_m = 1.0",
                "a_per_m = 1.0\nb_per_m = 1.0",
                "`geometry.b_per_m`",
            ),
            (
                "creepage_long = -2.4e-4",
                "creepage_lat = 1e-4",
                "`rolling.creepage_lat`",
            ),
            (
                "creepage_long = -2.4e-4",
                "spin_per_m = 0.1",
                "`rolling.spin_per_m`",
            ),
            (
                "creepage_long = -2.4e-4",
                "force_x_n = 100.0",
                "`rolling.force_x_n`",
            ),
            ("nx = 55", "nx = 55\nwindow_x_m = 2.0", "`grid.window_x_m`"),
            ("model", "model", "`model`"),
        ] {
            let text = if key == "`model`" {
                format!("model = \"fastsim\"\n{LINE}")
            } else {
                LINE.replace(from, to)
            };
            let m = err(&text);
            assert!(m.contains(key), "{key}: {m}");
        }
        // A force per metre on a three-dimensional geometry.
        let quad = LINE
            .replace("kind = \"line\"", "kind = \"quadratic\"\nb_per_m = 1.0")
            .replace("nx = 55", "nx = 16\nny = 16");
        assert!(err(&quad).contains("`load.normal_force_n_per_m`"));
        // A prescribed force per metre is the core's Fx.
        let force = LINE.replace("creepage_long = -2.4e-4", "force_x_n_per_m = 30000.0");
        let c = Case::from_toml(&force).unwrap();
        assert_eq!(c.prescribed_force.force_x_n, Some(30_000.0));
    }

    #[test]
    fn a_line_case_rolls_transient_steps_of_whole_elements() {
        // 55 elements over 2.2 mm: 0.04 mm each.
        let transient = LINE
            .replace("[rolling]\ncreepage_long = -2.4e-4\n", "")
            .replace(
                "nx = 55",
                "nx = 55\nwindow_x_m = 2.2e-3\n[transient]\nrolling_step_m = 4e-5\nsteps = [ \
             { shift_x_m = 1e-7 }, { creepage_long = -2.4e-4 } ]",
            );
        let c = Case::from_toml(&transient).unwrap();
        assert_eq!(c.rolling_step_m, Some(4e-5));
        // Half an element: named as the step, with the line's own grid.
        let m = err(&transient.replace("rolling_step_m = 4e-5", "rolling_step_m = 2e-5"));
        assert!(
            m.contains("`transient.rolling_step_m`") && m.contains("grid.window_x_m / grid.nx"),
            "{m}"
        );
        assert!(!m.contains("grid.ny"), "{m}");
    }
}

#[cfg(test)]
mod temperature_tests {
    use super::tests::ROLLING;
    use super::*;
    use crate::conformal::frictional::FrictionalWorkspace;
    use crate::problem::ModelRun;

    /// Steel on steel (Ertz & Knothe's values), rail at 20 C, wheel at 60 C,
    /// 30 m/s.
    const TEMPERATURE: &str = r#"
[temperature]
rolling_speed_m_per_s = 30.0
[temperature.body1]
bulk_temperature_k = 293.15
conductivity_w_per_m_k = 50.0
density_kg_per_m3 = 7850.0
specific_heat_j_per_kg_k = 450.0
[temperature.body2]
bulk_temperature_k = 333.15
conductivity_w_per_m_k = 50.0
density_kg_per_m3 = 7850.0
specific_heat_j_per_kg_k = 450.0
"#;

    fn bad(text: &str) -> String {
        match Case::from_toml(text) {
            Err(CaseError::BadInput(m)) => m,
            other => panic!("expected bad input, got {other:?}"),
        }
    }

    #[test]
    fn temperature_section_is_checked_and_names_the_key() {
        let c = Case::from_toml(&format!("{ROLLING}{TEMPERATURE}")).unwrap();
        let t = c.temperature.unwrap();
        assert_eq!(t.rolling_speed_m_per_s, 30.0);
        assert_eq!(t.body2.bulk_temperature_k, 333.15);
        let m = bad(&format!(
            "{ROLLING}{}",
            TEMPERATURE.replace("333.15", "60.0")
        ));
        assert!(
            m.contains("`temperature.body2.bulk_temperature_k`") && m.contains("Celsius"),
            "{m}"
        );
        let m = bad(&format!(
            "{ROLLING}{}",
            TEMPERATURE.replace(
                "rolling_speed_m_per_s = 30.0",
                "rolling_speed_m_per_s = -1.0"
            )
        ));
        assert!(m.contains("`temperature.rolling_speed_m_per_s`"), "{m}");
        let m = bad(&format!(
            "{ROLLING}{}",
            TEMPERATURE.replacen("density_kg_per_m3 = 7850.0\n", "", 1)
        ));
        assert!(m.contains("density_kg_per_m3"), "{m}");
        let m = bad(&format!(
            "{ROLLING}{}",
            TEMPERATURE.replacen("density_kg_per_m3", "density", 1)
        ));
        assert!(m.contains("density"), "{m}");
        let m = bad(&format!("model = \"fastsim\"\n{ROLLING}{TEMPERATURE}"));
        assert!(m.contains("`temperature`") && m.contains("exact"), "{m}");
        let m = bad(&format!(
            "{}{TEMPERATURE}",
            ROLLING.replace("[rolling]\ncreepage_long = 0.001\n", "")
        ));
        assert!(
            m.contains("`temperature`") && m.contains("steady rolling"),
            "{m}"
        );
    }

    #[test]
    fn exact_run_reports_the_flash_temperatures() {
        let c = Case::from_toml(&format!("{ROLLING}{TEMPERATURE}")).unwrap();
        let run = ModelRun::solve(&c, &mut FrictionalWorkspace::default()).unwrap();
        let report = run.report(&c, false);
        let t = report.temperature.unwrap();
        // The frictional power is T-gamma times the rolling speed
        // (-sum p_t . s dA V; |p_t||s| = -p_t . s where the material slips).
        let tgamma = report.totals.totals.tgamma_n;
        assert!(tgamma > 0.0);
        assert!(
            (t.frictional_power_w - 30.0 * tgamma).abs() < 1e-9 * 30.0 * tgamma,
            "{} {tgamma}",
            t.frictional_power_w
        );
        // Equal steels: the contact temperature is the mean bulk
        // temperature, the heat splits in halves, the rail heats above it
        // and the wheel is nowhere below its bulk temperature.
        assert!((t.contact_temperature_k - 313.15).abs() < 1e-9);
        assert!((t.heat_share_body1 - 0.5).abs() < 1e-12);
        assert!(t.max_body1.temperature_k > 313.15);
        assert!(t.max_body2.temperature_k >= 333.15);
        assert!(report.human().contains("body 1 max temperature [K]"));
        let json = serde_json::to_string(&report).unwrap();
        assert!(json.contains("\"temperature\":{\"max_body1\""), "{json}");
    }
}

#[cfg(test)]
mod rolling_frame_tests {
    use super::tests::bad_key;
    use super::*;
    use crate::core::solution::SolveStatus;

    /// An exact steady-rolling case on a 24 x 20 grid with `extra` lines.
    fn rolling_case(extra: &str) -> String {
        format!(
            r#"
model = "exact"
{extra}
[material]
shear_modulus_pa = 80.0e9
poisson_ratio = 0.25
[friction]
coefficient = 0.3
[geometry]
kind = "quadratic"
a_per_m = 1.0
b_per_m = 0.6
[load]
normal_force_n = 10000.0
[rolling]
creepage_long = 3e-4
creepage_lat = -1e-4
spin_per_m = 0.5
[grid]
nx = 24
ny = 20
window_x_m = 12e-3
window_y_m = 14e-3
"#
        )
    }

    #[test]
    fn a_hertz_gap_given_per_element_is_the_quadratic_case_bit_for_bit() {
        // CONTACT's IBASE = 9 (user guide §"Non-Hertzian geometry
        // specification"): the values h(x_I) at the element centres.
        let quadratic = Case::from_toml(&rolling_case("")).unwrap();
        let h = quadratic.problem().unwrap().gap_m;
        let list: Vec<String> = h.iter().map(|v| format!("{v:?}")).collect();
        let text = rolling_case("").replace(
            "b_per_m = 0.6\n",
            &format!("b_per_m = 0.6\ngap_m = [{}]\n", list.join(", ")),
        );
        let given = Case::from_toml(&text).unwrap();
        assert_eq!(given.problem().unwrap().gap_m, h);
        let a = crate::core::solve::solve(&quadratic.problem().unwrap()).unwrap();
        let b = crate::core::solve::solve(&given.problem().unwrap()).unwrap();
        assert_eq!(a[0].info.status, SolveStatus::Converged);
        assert_eq!(format!("{:?}", a[0].totals), format!("{:?}", b[0].totals));
        assert_eq!(a[0].fields, b[0].fields);
    }

    #[test]
    fn a_rolling_direction_and_an_extra_slip_reach_the_problem() {
        let n = 24 * 20;
        let slip = |v: f64| vec![format!("{v:?}"); n].join(", ");
        let text = rolling_case(&format!(
            "rolling_direction_rad = 3.141592653589793\n[extra_rigid_slip]\nslip_x = [{}]\n",
            slip(1e-4)
        ));
        let p = Case::from_toml(&text).unwrap().problem().unwrap();
        assert_eq!(p.rolling_direction_rad, std::f64::consts::PI);
        let e = p.extra_rigid_slip.unwrap();
        assert_eq!(e.slip_x, vec![1e-4; n]);
        assert_eq!(e.slip_y, vec![0.0; n]);
    }

    #[test]
    fn bad_gaps_directions_and_slips_are_refused_naming_the_key() {
        let n = 24 * 20;
        let list = |k: usize, v: &str| vec![v; k].join(", ");
        let slip = |extra: &str| format!("[extra_rigid_slip]\n{extra}\n");
        for (text, key) in [
            (
                rolling_case("").replace(
                    "b_per_m = 0.6\n",
                    &format!("b_per_m = 0.6\ngap_m = [{}]\n", list(7, "0.0")),
                ),
                "`geometry.gap_m`",
            ),
            (
                rolling_case("").replace(
                    "b_per_m = 0.6\n",
                    &format!("b_per_m = 0.6\ngap_m = [nan, {}]\n", list(n - 1, "0.0")),
                ),
                "`geometry.gap_m[0]`",
            ),
            (
                rolling_case("rolling_direction_rad = nan"),
                "`rolling_direction_rad`",
            ),
            (
                rolling_case("rolling_direction_rad = 0.3"),
                "`rolling_direction_rad`",
            ),
            (
                rolling_case("rolling_direction_rad = 3.141592653589793")
                    .replace("model = \"exact\"", "model = \"fastsim\""),
                "`rolling_direction_rad`",
            ),
            (
                rolling_case(&slip(&format!("slip_y = [{}]", list(n + 1, "0.0")))),
                "`extra_rigid_slip.slip_y`",
            ),
            (
                rolling_case(&slip(&format!("slip_x = [inf, {}]", list(n - 1, "0.0")))),
                "`extra_rigid_slip.slip_x[0]`",
            ),
            (rolling_case(&slip("")), "`extra_rigid_slip`"),
            (
                rolling_case(&slip(&format!("shift_x_m = [{}]", list(n, "0.0")))),
                "`extra_rigid_slip.shift_x_m`",
            ),
            (
                rolling_case(&slip(&format!("shift_y_m = [{}]", list(n, "0.5")))),
                "`extra_rigid_slip.shift_y_m[0]`",
            ),
            (
                rolling_case(&slip(&format!("slip_x = [{}]", list(n, "0.0"))))
                    .replace("nx = 24\n", ""),
                "`extra_rigid_slip.slip_x`",
            ),
        ] {
            let m = bad_key(&text);
            assert!(m.contains(key), "{key}: {m}");
        }
    }

    #[test]
    fn rolling_along_y_steps_whole_elements_in_y() {
        // dx = 0.5 mm, dy = 0.7 mm: rolling in +y, a step of 0.5 mm is no
        // whole number of elements, one of 0.7 mm is.
        let text = |dq: f64| {
            rolling_case("rolling_direction_rad = 1.5707963267948966").replace(
                "[rolling]\ncreepage_long = 3e-4\ncreepage_lat = -1e-4\nspin_per_m = 0.5\n",
                &format!(
                    "[transient]\nrolling_step_m = {dq:?}\nsteps = [{{ creepage_lat = 3e-4 }}]\n"
                ),
            )
        };
        let m = bad_key(&text(0.5e-3));
        assert!(
            m.contains("`transient.rolling_step_m`") && m.contains("window_y_m"),
            "{m}"
        );
        assert!(Case::from_toml(&text(0.7e-3)).is_ok());
    }

    #[test]
    fn transient_steps_roll_any_distance_off_the_axes() {
        // chi = 0.5 rad: a step of 0.37 mm is 0.57 dx along x and 0.26 dy
        // along y (dx = 0.5 mm, dy = 0.7 mm), carried by interpolation;
        // steady rolling at 0.5 rad is refused.
        let text = |dq: f64| {
            rolling_case("rolling_direction_rad = 0.5").replace(
                "[rolling]\ncreepage_long = 3e-4\ncreepage_lat = -1e-4\nspin_per_m = 0.5\n",
                &format!(
                    "[transient]\nrolling_step_m = {dq:?}\nsteps = [{{ creepage_long = 3e-4 }}, \
                     {{ creepage_long = 3e-4 }}]\n"
                ),
            )
        };
        let run = |dq: f64| crate::problem::ExactRun::solve(&Case::from_toml(&text(dq)).unwrap());
        assert_eq!(run(0.37e-3).ok().unwrap().solutions.len(), 2);
        let m = run(0.1).err().unwrap().to_string();
        assert!(m.contains("transient.steps[0].rolling_m"), "{m}");
        let m = bad_key(&rolling_case("rolling_direction_rad = 0.5"));
        assert!(
            m.contains("`rolling_direction_rad`") && m.contains("steady"),
            "{m}"
        );
    }
}

#[cfg(test)]
mod layer_tests {
    use super::*;
    use crate::core::solution::SolveStatus;
    use crate::problem::ExactRun;

    const EXAMPLE: &str = include_str!("../../../../examples/cases/layer_plastic_3bl.toml");

    /// CONTACT's FX \[N\] of `plastic_3bl.ref_out` cases 15-31 as printed
    /// (the clay series the example states), and whether the element flows
    /// (NPLAST = 1).
    const CLAY_FX: [(&str, bool); 17] = [
        ("200.0", false),
        ("216.0", true),
        ("232.0", true),
        ("248.0", true),
        ("262.4", true),
        ("262.4", false),
        ("82.43", false),
        ("82.43", false),
        ("266.4", true),
        ("284.0", true),
        ("304.0", true),
        ("324.1", true),
        ("344.1", true),
        ("364.1", true),
        ("384.1", true),
        ("404.1", true),
        ("424.1", true),
    ];

    /// Half a unit of the last digit of a printed decimal.
    fn half_unit(s: &str) -> f64 {
        let decimals = s.find('.').map_or(0, |i| s.len() - i - 1) as i32;
        0.5 * 10f64.powi(-decimals)
    }

    /// The message of a case refused as bad input.
    pub(super) fn message(r: Result<Case, CaseError>) -> String {
        match r {
            Err(CaseError::BadInput(m)) => m,
            other => panic!("expected bad input, got {:?}", other.map(|c| c.model)),
        }
    }

    #[test]
    fn layer_plastic_3bl_example_matches_contacts_forces() {
        let case = Case::from_toml(EXAMPLE).unwrap();
        let layer = case.settings.interfacial_layer.expect("the layer");
        assert_eq!(layer.thickness_m, 2.0e-5);
        assert_eq!(layer.hardening_pa_per_m, 4.35e11);
        let run = ExactRun::solve(&case).unwrap();
        assert_eq!(run.solutions().len(), CLAY_FX.len());
        for (k, (s, (fx, _))) in run.solutions().iter().zip(CLAY_FX).enumerate() {
            let want: f64 = fx.parse().unwrap();
            assert_eq!(s.info.status, SolveStatus::Converged, "case {}", 15 + k);
            assert!(
                (s.totals.fx_n - want).abs() <= half_unit(fx) * (1.0 + 1e-9),
                "case {}: FX {} N against CONTACT's {fx}",
                15 + k,
                s.totals.fx_n
            );
            assert!((s.totals.normal_force_n - 900.0).abs() < 1e-6 * 900.0);
        }
        // The last step (case 31) flows: one plastic element of 1 mm²,
        // tau_c = FX / 1 mm² = 424.1 N/mm² as CONTACT prints.
        let report = run.report(&case, true);
        let l = report
            .interfacial_layer
            .as_ref()
            .expect("a plastic layer's state");
        assert_eq!(l.plastic_elements, 1);
        assert!((l.plastic_area_m2 - 1e-6).abs() < 1e-15);
        assert!((l.max_yield_limit_pa - 424.1e6).abs() <= 0.05e6 * (1.0 + 1e-9));
        assert_eq!(l.min_yield_limit_pa, 2.0e8);
        // tau_c = tau_c0 + k_tau u_pl.
        let u_pl = (l.max_yield_limit_pa - 2.0e8) / 4.35e11;
        assert!((l.max_plastic_deformation_m - u_pl).abs() <= 1e-9 * u_pl);
        let json = serde_json::to_value(&report).unwrap();
        let fields = &json["interfacial_layer"]["fields"];
        assert_eq!(fields["yield_limit_pa"].as_array().unwrap().len(), 25);
        assert_eq!(fields["plastic"][12], serde_json::Value::Bool(true));
        assert!(run
            .report(&case, false)
            .interfacial_layer
            .unwrap()
            .fields
            .is_none());
        assert!(report.human().contains("layer plastic area"));
    }

    /// A rolling ellipse with `section` (TOML) under models fastsim and
    /// hertz: refused naming `key` and the model (only the exact model
    /// takes the section).
    pub(super) fn only_the_exact_model_takes(key: &str, section: &str) {
        for model in ["fastsim", "hertz"] {
            let m = message(Case::from_toml(&format!(
                "model = \"{model}\"\n[material]\nshear_modulus_pa = 81.0e9\npoisson_ratio = 0.3\n\
                 [friction]\ncoefficient = 0.3\n[geometry]\nkind = \"quadratic\"\na_per_m = 1.0\n\
                 b_per_m = 1.0\n[load]\nnormal_force_n = 1e4\n[rolling]\ncreepage_long = 1e-3\n\
                 {section}"
            )));
            assert!(m.contains(&format!("`{key}`")) && m.contains(model), "{m}");
        }
    }

    #[test]
    fn a_bad_layer_value_is_refused_naming_its_key() {
        for (from, to, key) in [
            (
                "thickness_m = 2.0e-5",
                "thickness_m = -1e-5",
                "interfacial_layer.thickness_m",
            ),
            (
                "shear_modulus_pa = 1.0625e8",
                "shear_modulus_pa = 0.0",
                "interfacial_layer.shear_modulus_pa",
            ),
            (
                "yield_limit_pa = 2.0e8",
                "yield_limit_pa = -1.0",
                "interfacial_layer.yield_limit_pa",
            ),
            (
                "hardening_pa_per_m = 4.35e11",
                "hardening_pa_per_m = nan",
                "interfacial_layer.hardening_pa_per_m",
            ),
            // A plastic layer needs one friction coefficient.
            (
                "coefficient = 0.7",
                "static_coefficient = 0.7\nkinetic_coefficient = 0.6",
                "interfacial_layer.yield_limit_pa",
            ),
            (
                "hardening_pa_per_m = 4.35e11",
                "hardening = 1.0",
                "hardening",
            ),
        ] {
            assert!(EXAMPLE.contains(from), "{from}");
            let m = message(Case::from_toml(&EXAMPLE.replacen(from, to, 1)));
            assert!(m.contains(key), "{to}: {m}");
        }
        only_the_exact_model_takes(
            "interfacial_layer",
            "[interfacial_layer]\nthickness_m = 2e-5\nshear_modulus_pa = 1e8\n",
        );
        // Without a yield limit the layer is elastic; without thickness_m
        // the section is incomplete.
        let elastic = EXAMPLE
            .replacen("yield_limit_pa = 2.0e8\n", "", 1)
            .replacen("hardening_pa_per_m = 4.35e11\n", "", 1);
        let c = Case::from_toml(&elastic).unwrap();
        assert!(!c.settings.interfacial_layer.unwrap().is_plastic());
        let m = message(Case::from_toml(&EXAMPLE.replacen(
            "thickness_m = 2.0e-5\n",
            "",
            1,
        )));
        assert!(m.contains("thickness_m"), "{m}");
    }
}

#[cfg(test)]
mod viscoelastic_tests {
    use super::*;
    use crate::core::solution::{ElementState, SolveStatus};
    use crate::problem::ExactRun;

    use super::layer_tests::{message, only_the_exact_model_takes};

    const EXAMPLE: &str = include_str!("../../../../examples/cases/visc_cylindr.toml");

    #[test]
    fn visc_cylindr_example_matches_contacts_case_3() {
        // visc_cylindr.ref_out, case 3 (TC = 0.045 s): CREEP X 1.152E-02,
        // PMAX 84.72 N/mm², NCON 57, NADH 36, NSLIP 21 (the example gives
        // CONTACT's gap at its element centres).
        let case = Case::from_toml(EXAMPLE).unwrap();
        let visc = case.settings.viscoelastic.expect("viscoelastic bodies");
        assert_eq!(visc.body2.creep_relaxation_time_s, 0.045);
        let run = ExactRun::solve(&case).unwrap();
        let s = run.last();
        assert_eq!(s.info.status, SolveStatus::Converged);
        let xi = run
            .force_control
            .as_ref()
            .expect("Fx prescribed")
            .creepage_long;
        assert!((xi / 1.152e-2 - 1.0).abs() < 0.01, "creepage {xi}");
        assert!((s.totals.max_pressure_pa / 84.72e6 - 1.0).abs() < 0.01);
        let n = |st: ElementState| s.fields.state.iter().filter(|&&e| e == st).count();
        let contact = s.fields.pressure_pa.iter().filter(|&&p| p > 0.0).count();
        for (got, want) in [
            (contact, 57),
            (n(ElementState::Adhesion), 36),
            (n(ElementState::Slip), 21),
        ] {
            assert!(got.abs_diff(want) <= 2, "{got} vs CONTACT's {want}");
        }
    }

    #[test]
    fn viscoelastic_bodies_are_refused_where_they_are_not_taken() {
        for (from, to, key) in [
            (
                "relaxation_ratio = 1.0",
                "relaxation_ratio = -1.0",
                "viscoelastic.body1.relaxation_ratio",
            ),
            // Over 1e6 (1e300 made the forces non-finite).
            (
                "relaxation_ratio = 1.0",
                "relaxation_ratio = 1.0e7",
                "viscoelastic.body1.relaxation_ratio",
            ),
            (
                "creep_relaxation_time_s = 0.045\n\n[grid]",
                "creep_relaxation_time_s = inf\n\n[grid]",
                "viscoelastic.body2.creep_relaxation_time_s",
            ),
            (
                "rolling_speed_m_per_s = 1.0",
                "rolling_speed_m_per_s = 0.0",
                "viscoelastic.rolling_speed_m_per_s",
            ),
            // CONTACT's M = 1 rolls in +x only (CHI = 0).
            (
                "model = \"exact\"",
                "model = \"exact\"\nrolling_direction_rad = 3.141592653589793",
                "`rolling_direction_rad`",
            ),
            // Steady rolling only: not transient steps.
            (
                "[rolling]\nforce_x_n_per_m = -1.08e5",
                "[transient]\nsteps = [{ shift_x_m = 1e-6 }]",
                "`viscoelastic`",
            ),
            ("relaxation_ratio = 1.0", "ratio = 1.0", "ratio"),
        ] {
            assert!(EXAMPLE.contains(from), "{from}");
            let m = message(Case::from_toml(&EXAMPLE.replacen(from, to, 1)));
            assert!(m.contains(key), "{to}: {m}");
        }
        only_the_exact_model_takes(
            "viscoelastic",
            "[viscoelastic]\nrolling_speed_m_per_s = 1.0\n[viscoelastic.body1]\n\
             relaxation_ratio = 1.0\ncreep_relaxation_time_s = 0.01\n",
        );
        // The frictionless normal problem of the rolling bodies is taken;
        // a body left out is elastic.
        let c = Case::from_toml(
            &EXAMPLE
                .replacen("[rolling]\nforce_x_n_per_m = -1.08e5\n", "", 1)
                .replacen(
                    "[viscoelastic.body2]\nrelaxation_ratio = 1.0\ncreep_relaxation_time_s = 0.045\n",
                    "",
                    1,
                ),
        )
        .unwrap();
        assert!(matches!(c.kinematics, Kinematics::Frictionless));
        assert!(c.settings.viscoelastic.unwrap().body2.is_elastic());
        assert!(ExactRun::solve(&c).is_ok());
    }

    #[test]
    fn a_surface_grid_over_64_x_64_is_refused_by_the_case_before_a_solver_is_built() {
        // The case's validation refuses it (in microseconds), not the
        // solve after `ContactSolver::new` integrated the coefficients
        // (14 s at 65 x 65); 64 x 64 and elastic bodies on 65 x 65 pass it.
        let sphere = |n: usize, ratio: f64| {
            format!(
                "model = \"exact\"\n[material]\nshear_modulus_pa = 81.0e9\npoisson_ratio = 0.3\n\
                 [friction]\ncoefficient = 0.3\n[geometry]\nkind = \"quadratic\"\na_per_m = 1.0\n\
                 b_per_m = 1.0\n[load]\nnormal_force_n = 1e4\n[rolling]\ncreepage_long = 1e-3\n\
                 [grid]\nnx = {n}\nny = {n}\n\
                 [viscoelastic]\nrolling_speed_m_per_s = 1.0\n[viscoelastic.body1]\n\
                 relaxation_ratio = {ratio:?}\ncreep_relaxation_time_s = 0.01\n"
            )
        };
        let m = message(Case::from_toml(&sphere(65, 1.0)));
        assert!(m.contains("`viscoelastic`") && m.contains("65 x 65"), "{m}");
        assert!(Case::from_toml(&sphere(64, 1.0)).is_ok());
        assert!(Case::from_toml(&sphere(65, 0.0)).is_ok());
    }
}
