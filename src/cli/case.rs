//! The case file of `railcontact solve`: its TOML schema and its validation.
//!
//! All values are in SI units. Every table rejects unknown keys. See
//! `examples/cases/README.md` for a commented list of the keys and
//! [`CaseFile`] for the schema; [`Case::from_toml`] parses and validates a
//! file into a [`Case`] that the models can run without further checks.

use serde::{Deserialize, Serialize};

use crate::cli::reference::hertz_of;
use crate::cli::CliError;
use crate::core::error::{require_positive, ContactError};
use crate::core::grid::Grid;
use crate::core::hertz::HertzSolution;
use crate::core::material::{CombinedMaterial, Material};
use crate::core::normal::NormalLoad;
use crate::core::normal::NormalSettings;
use crate::core::problem::{
    ContactProblem, Creepages, Friction, Kinematics, ShiftStep, SolverSettings,
};
use crate::core::tangential::TangentialSettings;

/// Default grid of the exact model in each direction (elements).
pub const DEFAULT_EXACT_ELEMENTS: usize = 64;
/// Default number of FASTSIM strips / elements per strip.
pub const DEFAULT_FASTSIM_ELEMENTS: usize = 40;
/// The automatic window is this multiple of the Hertz semi-axis in each
/// direction (1.2 times the Hertz patch).
pub const AUTO_WINDOW_PER_SEMI_AXIS: f64 = 2.4;

/// The contact model a case is solved with.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Model {
    /// Hertz's closed-form normal solution; no tangential forces.
    Hertz,
    /// Kalker's simplified theory (FASTSIM) on the Hertz ellipse.
    Fastsim,
    /// Kalker's exact theory on the half-space (the core solver).
    #[default]
    Exact,
}

impl Model {
    /// The name used in the case file and the JSON output.
    pub fn name(self) -> &'static str {
        match self {
            Model::Hertz => "hertz",
            Model::Fastsim => "fastsim",
            Model::Exact => "exact",
        }
    }
}

/// The whole case file, as written.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CaseFile {
    /// Contact model: `"hertz"`, `"fastsim"` or `"exact"` (default `"exact"`).
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
    /// `spin_per_m` [1/m] (each defaults to 0); omit for a static or
    /// transient case.
    pub rolling: Option<Creepages>,
    /// Transient shift steps; alternative to `[rolling]`.
    pub transient: Option<TransientSection>,
    /// Potential contact grid (optional; defaults below).
    pub grid: Option<GridSection>,
    /// Solver tolerances and limits (optional; core defaults).
    pub solver: Option<SolverSection>,
}

/// `[material]`: either `shear_modulus_pa` + `poisson_ratio` for both bodies,
/// or the sub-tables `[material.body1]` and `[material.body2]` for dissimilar
/// bodies (not both forms at once).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSection {
    /// Shear modulus G of both bodies [Pa], > 0 (steel: 81.0e9).
    pub shear_modulus_pa: Option<f64>,
    /// Poisson ratio nu of both bodies [-], in [0, 0.5) (steel: 0.30).
    pub poisson_ratio: Option<f64>,
    /// Body 1 (the rail; the body the tractions act on): `shear_modulus_pa`
    /// [Pa], `poisson_ratio` [-].
    pub body1: Option<Material>,
    /// Body 2 (the wheel), same keys.
    pub body2: Option<Material>,
}

/// `[friction]`: `coefficient`, or `static_coefficient` + `kinetic_coefficient`.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrictionSection {
    /// Coulomb coefficient mu [-], >= 0 (static = kinetic).
    pub coefficient: Option<f64>,
    /// Static coefficient [-], >= 0 (with `kinetic_coefficient`).
    pub static_coefficient: Option<f64>,
    /// Kinetic coefficient [-], >= 0 (with `static_coefficient`).
    pub kinetic_coefficient: Option<f64>,
}

/// Kind of undeformed geometry.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum GeometryKind {
    /// h = a_per_m x² + b_per_m y².
    Quadratic,
}

/// `[geometry]`: the undeformed distance of the bodies.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GeometrySection {
    /// Geometry kind; only `"quadratic"`: h = a_per_m x² + b_per_m y².
    pub kind: GeometryKind,
    /// Curvature coefficient A in x (rolling direction) [1/m], > 0
    /// (A = 1/(2 R_x) for combined radius R_x).
    pub a_per_m: f64,
    /// Curvature coefficient B in y (lateral) [1/m], > 0.
    pub b_per_m: f64,
}

/// `[load]`: exactly one of `normal_force_n` and `approach_m`.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadSection {
    /// Total normal force [N], > 0.
    pub normal_force_n: Option<f64>,
    /// Approach of the bodies [m], > 0.
    pub approach_m: Option<f64>,
}

/// `[transient]`: a sequence of shift steps from the unloaded state.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TransientSection {
    /// The steps, at least one.
    pub steps: Vec<StepSection>,
}

/// One shift step in `transient.steps`.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StepSection {
    /// Rigid shift of body 1 relative to body 2 in x during the step [m] (required).
    pub shift_x_m: f64,
    /// Rigid shift in y during the step [m] (default 0).
    #[serde(default)]
    pub shift_y_m: f64,
    /// Rigid rotation about the normal axis during the step [rad] (default 0).
    #[serde(default)]
    pub rotation_rad: f64,
    /// Normal force in the step [N], > 0 (default: the `[load]`).
    pub normal_force_n: Option<f64>,
    /// Approach in the step [m], > 0 (default: the `[load]`).
    pub approach_m: Option<f64>,
}

/// `[grid]`: the potential contact grid, centred on the origin.
#[derive(Debug, Clone, Copy, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct GridSection {
    /// Elements in x (default 64 for `exact`, 40 strips for `fastsim`).
    pub nx: Option<usize>,
    /// Elements in y (default 64 for `exact`, 40 for `fastsim`).
    pub ny: Option<usize>,
    /// Window length in x [m] (default 2.4 x the Hertz semi-axis in x).
    pub window_x_m: Option<f64>,
    /// Window width in y [m] (default 2.4 x the Hertz semi-axis in y).
    pub window_y_m: Option<f64>,
}

/// `[solver]`: tolerances and iteration limits of the exact model.
#[derive(Debug, Clone, Copy, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct SolverSection {
    /// Relative pressure change that ends the normal iteration [-] (default 1e-10).
    pub normal_tolerance: Option<f64>,
    /// Friction-law residual relative to max mu p_n that ends the tangential
    /// iteration [-] (default 1e-7).
    pub tangential_tolerance: Option<f64>,
    /// Iteration limit of each solver, normal and tangential (default 1000
    /// normal, 2000 tangential).
    pub max_iterations: Option<usize>,
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
    /// Curvature coefficient A [1/m].
    pub a_per_m: f64,
    /// Curvature coefficient B [1/m].
    pub b_per_m: f64,
    /// The `[load]`.
    pub load: NormalLoad,
    /// Kinematics (frictionless, steady rolling or transient).
    pub kinematics: Kinematics,
    /// Elements in x.
    pub nx: usize,
    /// Elements in y.
    pub ny: usize,
    /// Window in x [m] (given or automatic).
    pub window_x_m: f64,
    /// Window in y [m] (given or automatic).
    pub window_y_m: f64,
    /// Solver settings.
    pub settings: SolverSettings,
    /// Remarks for the user (ignored sections and the like).
    pub notes: Vec<String>,
}

fn bad(key: impl Into<String>, reason: impl Into<String>) -> CliError {
    CliError::from(ContactError::invalid(key, reason))
}

fn one_load(
    key: &str,
    force: Option<f64>,
    approach: Option<f64>,
) -> Result<Option<NormalLoad>, CliError> {
    match (force, approach) {
        (Some(_), Some(_)) => Err(bad(
            format!("{key}.normal_force_n"),
            format!("give either `{key}.normal_force_n` or `{key}.approach_m`, not both"),
        )),
        (Some(f), None) => {
            require_positive(&format!("{key}.normal_force_n"), f)?;
            Ok(Some(NormalLoad::NormalForce(f)))
        }
        (None, Some(d)) => {
            require_positive(&format!("{key}.approach_m"), d)?;
            Ok(Some(NormalLoad::Approach(d)))
        }
        (None, None) => Ok(None),
    }
}

impl MaterialSection {
    fn combine(&self) -> Result<CombinedMaterial, CliError> {
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
    fn friction(&self) -> Result<Friction, CliError> {
        let f = match (
            self.coefficient,
            self.static_coefficient,
            self.kinetic_coefficient,
        ) {
            (Some(mu), None, None) => {
                if !(mu.is_finite() && mu >= 0.0) {
                    return Err(bad(
                        "friction.coefficient",
                        format!("must be finite and >= 0, got {mu}"),
                    ));
                }
                Friction::coulomb(mu)
            }
            (None, Some(s), Some(k)) => Friction {
                static_coefficient: s,
                kinetic_coefficient: k,
            },
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
        f.validate()?;
        Ok(f)
    }
}

impl Case {
    /// Parses and validates a case file's text. Errors are
    /// [`CliError::BadInput`] and name the offending key.
    pub fn from_toml(text: &str) -> Result<Case, CliError> {
        let file: CaseFile = toml::from_str(text)
            .map_err(|e| CliError::BadInput(format!("case file: {}", e.to_string().trim_end())))?;
        Case::from_file(file)
    }

    /// Validates a parsed case file.
    pub fn from_file(file: CaseFile) -> Result<Case, CliError> {
        let mut notes = Vec::new();
        let model = file.model;
        let material = file.material.combine()?;

        let geo = file.geometry;
        require_positive("geometry.a_per_m", geo.a_per_m)?;
        require_positive("geometry.b_per_m", geo.b_per_m)?;

        let load =
            one_load("load", file.load.normal_force_n, file.load.approach_m)?.ok_or_else(|| {
                bad(
                    "load.normal_force_n",
                    "missing: give `load.normal_force_n` or `load.approach_m`",
                )
            })?;

        let kinematics = match (&file.rolling, &file.transient) {
            (Some(_), Some(_)) => {
                return Err(bad(
                    "transient",
                    "`[rolling]` and `[transient]` exclude each other; give one of them",
                ));
            }
            (Some(r), None) => {
                r.validate()?;
                Kinematics::SteadyRolling(*r)
            }
            (None, Some(t)) => {
                if t.steps.is_empty() {
                    return Err(bad("transient.steps", "needs at least one step"));
                }
                let mut steps = Vec::with_capacity(t.steps.len());
                for (k, s) in t.steps.iter().enumerate() {
                    let key = format!("transient.steps[{k}]");
                    let step = ShiftStep {
                        load: one_load(&key, s.normal_force_n, s.approach_m)?.unwrap_or(load),
                        shift_x_m: s.shift_x_m,
                        shift_y_m: s.shift_y_m,
                        rotation_rad: s.rotation_rad,
                    };
                    step.validate(&key)?;
                    steps.push(step);
                }
                Kinematics::Transient(steps)
            }
            (None, None) => Kinematics::Frictionless,
        };

        let needs_friction = match model {
            Model::Hertz => false,
            Model::Fastsim => true,
            Model::Exact => !matches!(kinematics, Kinematics::Frictionless),
        };
        let (friction, has_friction) = match (&file.friction, needs_friction) {
            (Some(f), _) => (f.friction()?, true),
            (None, true) => {
                return Err(bad(
                    "friction.coefficient",
                    "missing: `[friction]` is needed for rolling, transient and FASTSIM cases",
                ));
            }
            (None, false) => (Friction::coulomb(0.0), false),
        };

        match model {
            Model::Hertz => {
                if file.rolling.is_some() || file.transient.is_some() {
                    notes.push("the Hertz model solves the normal problem only: [rolling]/[transient] ignored".into());
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
            Model::Exact => {
                if file.friction.is_some() && matches!(kinematics, Kinematics::Frictionless) {
                    notes.push("static case without [rolling]/[transient]: frictionless normal contact, [friction] unused".into());
                }
            }
        }

        let grid = file.grid.unwrap_or_default();
        let default_n = if model == Model::Fastsim {
            DEFAULT_FASTSIM_ELEMENTS
        } else {
            DEFAULT_EXACT_ELEMENTS
        };
        let nx = grid.nx.unwrap_or(default_n);
        let ny = grid.ny.unwrap_or(default_n);
        for (key, n) in [("grid.nx", nx), ("grid.ny", ny)] {
            let (lo, hi) = (
                crate::core::grid::MIN_ELEMENTS,
                crate::core::grid::MAX_ELEMENTS_PER_DIRECTION,
            );
            if !(lo..=hi).contains(&n) {
                return Err(bad(key, format!("must be between {lo} and {hi}, got {n}")));
            }
        }
        if let Some(w) = grid.window_x_m {
            require_positive("grid.window_x_m", w)?;
        }
        if let Some(w) = grid.window_y_m {
            require_positive("grid.window_y_m", w)?;
        }

        // Hertz patch of the largest load: sizes the automatic window and
        // checks a given one.
        let e_star = material.effective_modulus_pa();
        let (mut patch_x_m, mut patch_y_m) = (0.0f64, 0.0f64);
        let loads: Vec<NormalLoad> = match &kinematics {
            Kinematics::Transient(steps) if model == Model::Exact => {
                steps.iter().map(|s| s.load).collect()
            }
            _ => vec![load],
        };
        for l in loads {
            let h = hertz_of(geo.a_per_m, geo.b_per_m, e_star, l)?;
            patch_x_m = patch_x_m.max(h.semi_axis_x_m);
            patch_y_m = patch_y_m.max(h.semi_axis_y_m);
        }
        let window_x_m = grid
            .window_x_m
            .unwrap_or(AUTO_WINDOW_PER_SEMI_AXIS * patch_x_m);
        let window_y_m = grid
            .window_y_m
            .unwrap_or(AUTO_WINDOW_PER_SEMI_AXIS * patch_y_m);
        if model == Model::Exact {
            for (key, w, s) in [
                ("grid.window_x_m", window_x_m, patch_x_m),
                ("grid.window_y_m", window_y_m, patch_y_m),
            ] {
                if w < 2.0 * s {
                    return Err(bad(
                        key,
                        format!(
                            "the window ({:.4} mm) is smaller than the Hertz contact patch ({:.4} mm): enlarge it or leave it unset",
                            w * 1e3,
                            2.0 * s * 1e3
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
                require_positive("solver.normal_tolerance", t)?;
                normal.tolerance = t;
            }
            if let Some(t) = s.tangential_tolerance {
                require_positive("solver.tangential_tolerance", t)?;
                tangential.tolerance = t;
            }
            if let Some(m) = s.max_iterations {
                if m == 0 {
                    return Err(bad("solver.max_iterations", "must be at least 1"));
                }
                normal.max_iterations = m;
                tangential.max_iterations = m;
            }
            settings.normal = normal;
            settings.tangential = tangential;
            if model != Model::Exact {
                notes.push(format!(
                    "the {} model has no iterative solver: [solver] ignored",
                    model.name()
                ));
            }
        }

        Ok(Case {
            model,
            material,
            friction,
            has_friction,
            a_per_m: geo.a_per_m,
            b_per_m: geo.b_per_m,
            load,
            kinematics,
            nx,
            ny,
            window_x_m,
            window_y_m,
            settings,
            notes,
        })
    }

    /// The potential contact grid of the exact model.
    pub fn grid(&self) -> Result<Grid, CliError> {
        Ok(Grid::centered(
            self.nx,
            self.ny,
            self.window_x_m,
            self.window_y_m,
        )?)
    }

    /// The core contact problem (exact model).
    pub fn problem(&self) -> Result<ContactProblem, CliError> {
        let grid = self.grid()?;
        Ok(ContactProblem {
            material: self.material,
            friction: self.friction,
            grid,
            gap_m: ContactProblem::quadratic_gap(&grid, self.a_per_m, self.b_per_m),
            load: self.load,
            kinematics: self.kinematics.clone(),
            settings: self.settings,
        })
    }

    /// The Hertz solution of the case's geometry and `[load]`.
    pub fn hertz(&self) -> Result<HertzSolution, CliError> {
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
}
