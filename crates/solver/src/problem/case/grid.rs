//! The `[grid]` and `[solver]` sections: the elements, the window and the
//! solvers' iteration settings.

use serde::Deserialize;

use super::{
    bad, check_hertz_patch, check_line_patch, ranges, CaseFile, CaseGeometry, Model,
    AUTO_WINDOW_PER_SEMI_AXIS, CONFORMAL_WINDOW_MAX_HALF_ANGLE_DEG,
    CONFORMAL_WINDOW_S_PER_SEMI_AXIS, CONFORMAL_WINDOW_X_PER_SEMI_AXIS, DEFAULT_EXACT_ELEMENTS,
    DEFAULT_FASTSIM_ELEMENTS,
};
use crate::core::error::{check_count, show, ContactError};
use crate::core::frame::{Direction, RollingFrame};
use crate::core::grid::{Grid, MIN_ELEMENTS};
use crate::core::influence::{LINE_LENGTH_M, LINE_REFERENCE_DISTANCE_M};
use crate::core::material::CombinedMaterial;
use crate::core::normal::NormalLoad;
use crate::core::normal::NormalSettings;
use crate::core::problem::{rolling_elements, Kinematics, SolverSettings};
use crate::core::tangential::TangentialSettings;
use crate::problem::CaseError;

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

/// The elements and the window of a case, validated.
pub(super) struct CaseGrid {
    pub(super) nx: usize,
    pub(super) ny: usize,
    pub(super) window_x_m: f64,
    pub(super) window_y_m: f64,
}

/// The `[grid]` of a case of `model` with `geometry` (curvatures `a_per_m`,
/// `b_per_m`), `material`, `kinematics`, `[load]` and rolling `direction`:
/// the element counts, and the window given or sized to the Hertz patch of
/// the largest load, each checked against that patch.
#[allow(clippy::too_many_arguments)]
pub(super) fn case_grid(
    file: &CaseFile,
    model: Model,
    geometry: &CaseGeometry,
    [a_per_m, b_per_m]: [f64; 2],
    material: &CombinedMaterial,
    kinematics: &Kinematics,
    load: NormalLoad,
    direction: &Direction,
    notes: &mut Vec<String>,
) -> Result<CaseGrid, CaseError> {
    let line = geometry.is_line();
    let turns = direction.turns;
    let grid = file.grid.unwrap_or_default();
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
    let loads: Vec<(String, NormalLoad)> = match kinematics {
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
    Ok(CaseGrid {
        nx,
        ny,
        window_x_m,
        window_y_m,
    })
}

/// The solvers' settings of a case of `model`: the defaults, with the
/// `[solver]` section's values where given.
pub(super) fn solver_settings(
    section: Option<SolverSection>,
    model: Model,
    notes: &mut Vec<String>,
) -> Result<SolverSettings, CaseError> {
    let mut settings = SolverSettings::default();
    if let Some(s) = section {
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
    Ok(settings)
}
