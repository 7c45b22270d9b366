//! What a solve returns: per-element fields, totals and solver information.

use serde::{Deserialize, Serialize};

/// State of one element of the potential contact grid.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum ElementState {
    /// Outside the contact area (p_n = 0).
    #[default]
    Exterior,
    /// In contact, sticking: slip is zero, |p_t| <= mu p_n.
    Adhesion,
    /// In contact, sliding: |p_t| = mu p_n, traction opposite to the slip.
    Slip,
}

/// Whether a solver met its tolerance.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SolveStatus {
    /// All tolerances met.
    Converged,
    /// An iteration limit was hit first; the result is the last iterate and the
    /// residuals say how far it is from a solution.
    MaxIterations,
}

impl SolveStatus {
    /// The name used in JSON output: `"converged"` or `"max_iterations"`.
    pub fn as_str(self) -> &'static str {
        match self {
            SolveStatus::Converged => "converged",
            SolveStatus::MaxIterations => "max_iterations",
        }
    }

    /// The worse of two statuses (for a sequence of steps).
    pub fn worst(self, other: SolveStatus) -> SolveStatus {
        if self == SolveStatus::Converged {
            other
        } else {
            self
        }
    }
}

/// The iteration limit a solve stopped at ([`SolveStatus::MaxIterations`]),
/// with the setting that raises it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum IterationLimit {
    /// The normal solver's limit
    /// ([`crate::core::normal::NormalSettings::max_iterations`]).
    Normal,
    /// The tangential solver's limit
    /// ([`crate::core::tangential::TangentialSettings::max_iterations`]).
    Tangential,
    /// The limit of normal/tangential alternations of dissimilar
    /// materials ([`crate::core::problem::SolverSettings::coupling_max_iterations`]).
    Coupling,
    /// The limit of the fixed-point iteration on the slip velocities of a
    /// slip-velocity dependent friction law
    /// ([`crate::core::friclaw::SlipVelocityLaw::max_iterations`]).
    FrictionLaw,
}

impl IterationLimit {
    /// The case file's key of the limit: `solver.max_iterations` (normal
    /// and tangential), `solver.coupling_max_iterations` or
    /// `friction.max_iterations`.
    pub fn key(self) -> &'static str {
        match self {
            IterationLimit::Normal | IterationLimit::Tangential => "solver.max_iterations",
            IterationLimit::Coupling => "solver.coupling_max_iterations",
            IterationLimit::FrictionLaw => "friction.max_iterations",
        }
    }
}

/// Counters and residuals of one solve (the core counts, it does not log).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SolveInfo {
    /// Overall status.
    pub status: SolveStatus,
    /// The limit the solve stopped at when `status` is
    /// [`SolveStatus::MaxIterations`] (the alternation's, when it hit
    /// its own; else the normal or the tangential solver's of its last
    /// pass).
    pub limit: Option<IterationLimit>,
    /// Conjugate-gradient iterations of the normal problem (all coupling passes).
    pub normal_iterations: usize,
    /// Outer iterations of the tangential problem (all coupling passes).
    pub tangential_iterations: usize,
    /// Normal/tangential alternations (Panagiotopoulos process); 1 when uncoupled.
    pub coupling_iterations: usize,
    /// FFT operator applications (one per matvec of any block size).
    pub matvecs: usize,
    /// Final relative change of the pressures in the normal solver [-].
    pub normal_residual: f64,
    /// Final natural residual of the friction law, relative to max mu p_n [-].
    pub tangential_residual: f64,
    /// Wall time of the solve \[s\], kernel construction included.
    pub solve_time_s: f64,
    /// Of `solve_time_s`, the time in the normal problem's solver (all
    /// passes) \[s\].
    pub normal_time_s: f64,
}

/// Per-element results on the potential contact grid (index `iy * nx + ix`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
pub struct ElementFields {
    /// Normal pressure p_n on body 1 \[Pa\], >= 0.
    pub pressure_pa: Vec<f64>,
    /// Longitudinal traction p_x on body 1 \[Pa\].
    pub traction_x_pa: Vec<f64>,
    /// Lateral traction p_y on body 1 \[Pa\].
    pub traction_y_pa: Vec<f64>,
    /// Slip of body 1 relative to body 2, x. Steady rolling: slip velocity
    /// divided by the rolling speed [-]; transient: slip distance in the step \[m\].
    pub slip_x: Vec<f64>,
    /// Slip of body 1 relative to body 2, y (units as `slip_x`).
    pub slip_y: Vec<f64>,
    /// Element states.
    pub state: Vec<ElementState>,
    /// Undeformed distance used \[m\] (after any approach-independent offsets).
    pub gap_m: Vec<f64>,
}

/// Totals of one contact solution. Forces and moment act on body 1.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Default)]
pub struct Totals {
    /// Normal force \[N\].
    pub normal_force_n: f64,
    /// Longitudinal tangential force \[N\].
    pub fx_n: f64,
    /// Lateral tangential force \[N\].
    pub fy_n: f64,
    /// Spin moment about the n axis through the grid origin [N m].
    pub mz_nm: f64,
    /// Approach of the bodies \[m\].
    pub approach_m: f64,
    /// Largest pressure \[Pa\].
    pub max_pressure_pa: f64,
    /// Largest tangential traction magnitude \[Pa\].
    pub max_traction_pa: f64,
    /// Contact area \[m²\] (elements with p_n > 0).
    pub contact_area_m2: f64,
    /// Extent of the contact elements in x \[m\] (resolution: one element).
    pub patch_length_m: f64,
    /// Extent of the contact elements in y \[m\] (resolution: one element).
    pub patch_width_m: f64,
    /// Share of the contact area in adhesion [-].
    pub adhesion_fraction: f64,
    /// T-gamma: frictional power per unit rolling speed, -sum p_t . s dA \[N\]
    /// (steady rolling; 0 otherwise).
    pub tgamma_n: f64,
    /// Frictional work dissipated in the step, -sum p_t . s dA \[J\] (transient; 0 otherwise).
    pub frictional_work_j: f64,
}

/// A solved contact problem (one step of a transient problem).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ContactSolution {
    /// Totals.
    pub totals: Totals,
    /// Solver information.
    pub info: SolveInfo,
    /// Per-element fields.
    pub fields: ElementFields,
}
