//! The contact problem as the solver sees it, in SI units.
//!
//! # Conventions (used everywhere in railcontact)
//!
//! * Axes: x is the rolling (longitudinal) direction, y lateral, n normal,
//!   pointing into body 1. In wheel/rail contact body 1 is the **rail** and
//!   body 2 the **wheel**.
//! * Tractions and forces are those **acting on body 1** (exerted by body 2):
//!   `p_n > 0` is compression; the wheel receives the opposite forces.
//! * Creepages are the rigid velocity of body 1 relative to body 2 at the
//!   contact reference point, divided by the rolling speed V: longitudinal
//!   `creepage_long` (xi) [-], lateral `creepage_lat` (eta) [-], spin
//!   `spin_per_m` (phi) [1/m]; rigid slip w_x = xi - phi y, w_y = eta + phi x.
//!   With these signs Kalker's linear theory reads Fx = -G ab C11 xi.
//! * Steady rolling: the contact patch travels in +x over both bodies;
//!   material enters at the leading edge (large x) and leaves at the
//!   trailing edge (small x).
//! * Transient (shift) steps: `shift_x_m`, `shift_y_m` and `rotation_rad` are
//!   the rigid displacement of body 1 relative to body 2 in the step (rotation
//!   about the n axis through the origin). The slip distance in the step is
//!   S(x) = W(x) + u(x) - u'(x), W the rigid shift, u the displacement
//!   difference of body 1 relative to body 2 now and u' that of the previous
//!   step at the same point.
//! * Transient rolling steps (moving coordinates): the grid moves with the
//!   contact patch, which rolls `rolling_m` = dq in +x over both bodies in
//!   the step, so the material now at x was at x + dq one step before. The
//!   rigid shift is W = dq w, w the creepages' rigid slip, and the slip per
//!   unit rolled distance is
//!   s(x) = S(x)/dq = w(x) + (u(x) - u'(x + dq))/dq,
//!   the previous step's tractions carried dq upstream. When the tractions
//!   no longer change, s = w + (u(x) - u(x + dq))/dq, which tends to the
//!   steady-rolling s = w - du/dx as dq -> 0. dq = 0 is a shift step. A
//!   step of more than one element corrects the material that entered the
//!   contact area during the step as CONTACT does
//!   ([`crate::core::leading_edge`]: S = facdt W + u - u_bnd).
//! * Rolling direction: `rolling_direction_rad` = chi is the direction in
//!   which the patch travels over both bodies, measured from +x towards +y
//!   (CONTACT's `CHI`); 0, the default, is the +x of the items above. The
//!   material enters at the leading edge, the side chi points to, and
//!   steady rolling's slip is s = w - du/dq with q along (cos chi, sin chi);
//!   a rolling step of dq carries the previous tractions dq against that
//!   direction. Creepages, shifts, tractions and forces stay in (x, y):
//!   the creepages are still body 1's rigid velocity relative to body 2
//!   over V. Steady rolling rolls along a grid axis: chi is a multiple of
//!   pi/2 ([`crate::core::frame`]); chi = pi mirrors a +x solution through
//!   the origin. Transient rolling steps take any chi: off the axes a step
//!   carries the previous tractions dq along -(cos chi, sin chi), between
//!   the element centres (interpolated, [`crate::core::frame`]).
//! * Extra rigid slip per element (`extra_rigid_slip`, CONTACT's `EXRHS`
//!   with E = 9): a velocity of body 1 relative to body 2 over V [-] added
//!   to the creepages' rigid slip w at each element, in (x, y); a rolling
//!   step of dq adds dq times it to the rigid shift. A shift step takes an
//!   extra rigid shift per element \[m\] instead, added to its rigid shift.
//! * Subsurface stresses and displacements ([`crate::core::subsurface`]) are
//!   reported for both bodies in this one frame (x, y, n), stresses tension
//!   positive; the depth runs into each body (n = +depth in body 1, −depth in
//!   body 2), so under a pressure both bodies have sigma_nn < 0, body 1 moves
//!   in +n and body 2 in −n.

use serde::{Deserialize, Serialize};

use crate::core::error::{require_finite, require_positive, ContactError, Range};
use crate::core::friclaw::SlipVelocityLaw;
use crate::core::memory::{heap_bytes, HeapBytes};

/// Range of a friction coefficient [-] (dry steel on steel: about 0.3–0.6).
pub const FRICTION_COEFFICIENT_RANGE: Range = Range::closed(0.0, 5.0, "");
/// Smallest non-zero friction coefficient [-]: below it the traction
/// bounds are denormal numbers the solver cannot divide by.
pub const MIN_NONZERO_FRICTION: f64 = 1e-6;

/// `mu` if it is 0 or in [[`MIN_NONZERO_FRICTION`], 5]
/// ([`FRICTION_COEFFICIENT_RANGE`]), else an error naming `key`.
pub fn check_friction_coefficient(key: &str, mu: f64) -> Result<f64, ContactError> {
    let mu = FRICTION_COEFFICIENT_RANGE.check(key, mu)?;
    if mu != 0.0 && mu < MIN_NONZERO_FRICTION {
        return Err(ContactError::invalid(
            key,
            format!(
                "must be 0 or in [{MIN_NONZERO_FRICTION:e}, {}], got {}",
                FRICTION_COEFFICIENT_RANGE.max,
                crate::core::error::show(mu)
            ),
        ));
    }
    Ok(mu)
}

/// Range of the longitudinal and lateral creepages [-] of an input
/// (1: a slip velocity equal to the rolling speed).
pub const CREEPAGE_RANGE: Range = Range::symmetric(1.0, "");
/// Range of the spin creepage of an input \[1/m\].
pub const SPIN_RANGE: Range = Range::symmetric(1e3, "1/m");
use crate::core::grid::Grid;
use crate::core::layer::InterfacialLayer;
use crate::core::material::CombinedMaterial;
use crate::core::normal::{NormalLoad, NormalSettings};
use crate::core::numerical_influence::InfluenceFile;
use crate::core::tangential::TangentialSettings;
use crate::core::viscoelastic::Viscoelastic;
use std::sync::Arc;

/// Friction: Coulomb's law with static and kinetic coefficients, or a
/// slip-velocity dependent law ([`crate::core::friclaw`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Friction {
    /// Static coefficient [-], the bound of sticking elements: an element
    /// enters slip when its traction would exceed it (with a slip-velocity
    /// law: its mu_s(0)).
    pub static_coefficient: f64,
    /// Kinetic coefficient [-], the bound of sliding elements; an element
    /// that slid in a solve sticks again only within it (the rule in
    /// `ContactSolver`'s tangential solve, `core::solve`; with a
    /// slip-velocity law: its limit mu_kin at large slip velocity).
    pub kinetic_coefficient: f64,
    /// A slip-velocity dependent law (exact model only): then the bound of
    /// every element is mu(s_a) p_n, and the two coefficients above are
    /// the law's (see [`Friction::falling`]). None: Coulomb.
    #[serde(default)]
    pub slip_velocity_law: Option<SlipVelocityLaw>,
}

impl Friction {
    /// Equal static and kinetic coefficients.
    pub fn coulomb(mu: f64) -> Self {
        Self {
            static_coefficient: mu,
            kinetic_coefficient: mu,
            slip_velocity_law: None,
        }
    }

    /// Static and kinetic coefficients (Coulomb's law with the static bound
    /// on sticking elements, the kinetic one on sliding elements).
    pub fn static_kinetic(static_coefficient: f64, kinetic_coefficient: f64) -> Self {
        Self {
            static_coefficient,
            kinetic_coefficient,
            slip_velocity_law: None,
        }
    }

    /// The slip-velocity dependent `law`, its static coefficient mu_s(0)
    /// and kinetic coefficient mu_kin.
    pub fn falling(law: SlipVelocityLaw) -> Self {
        Self {
            static_coefficient: law.static_coefficient(),
            kinetic_coefficient: law.kinetic_coefficient,
            slip_velocity_law: Some(law),
        }
    }

    /// This law with its static coefficient `static_coefficient` and the
    /// rest scaled with it: the kinetic coefficient in proportion, a
    /// slip-velocity law's kinetic and falling coefficients by the same
    /// factor (its shape in slip velocity kept). Coulomb's law with equal
    /// coefficients is [`Friction::coulomb`] of it, bit for bit. The static
    /// coefficient must be > 0 unless both are equal (a wheel/rail
    /// friction table's coefficients scale the section's law this way,
    /// [`crate::wheelrail::friction`]).
    pub fn scaled_to(&self, static_coefficient: f64) -> Self {
        let f = static_coefficient / self.static_coefficient;
        match self.slip_velocity_law {
            None if self.static_coefficient == self.kinetic_coefficient => {
                Self::coulomb(static_coefficient)
            }
            None => Self::static_kinetic(static_coefficient, self.kinetic_coefficient * f),
            Some(law) => Self::falling(SlipVelocityLaw {
                kinetic_coefficient: law.kinetic_coefficient * f,
                falling_coefficients: law.falling_coefficients.map(|c| c * f),
                ..law
            }),
        }
    }

    /// Checks both coefficients are finite, and 0 or at least
    /// [`MIN_NONZERO_FRICTION`] (what the solver needs; a large
    /// coefficient models full adhesion). Any such pair is valid: a
    /// kinetic coefficient below the static one (also 0) bounds the
    /// traction where the material slides.
    pub fn validate(&self) -> Result<(), ContactError> {
        if let Some(law) = &self.slip_velocity_law {
            law.validate()?;
            if *self != Friction::falling(*law) {
                return Err(ContactError::invalid(
                    "friction.static_coefficient",
                    "with a slip-velocity law the coefficients are the law's: build it with Friction::falling",
                ));
            }
        }
        for (key, mu) in [
            ("friction.static_coefficient", self.static_coefficient),
            ("friction.kinetic_coefficient", self.kinetic_coefficient),
        ] {
            if !(mu.is_finite() && (mu == 0.0 || mu >= MIN_NONZERO_FRICTION)) {
                return Err(ContactError::invalid(
                    key,
                    format!(
                        "must be finite, and 0 or >= {MIN_NONZERO_FRICTION:e}, got {}",
                        crate::core::error::show(mu)
                    ),
                ));
            }
        }
        Ok(())
    }

    /// Checks coefficients given as input against their documented range
    /// ([`check_friction_coefficient`]).
    pub fn check_input(&self) -> Result<(), ContactError> {
        check_friction_coefficient("friction.static_coefficient", self.static_coefficient)?;
        check_friction_coefficient("friction.kinetic_coefficient", self.kinetic_coefficient)?;
        Ok(())
    }
}

/// Creepages of steady rolling (see the module conventions). Each defaults
/// to 0 when deserialised.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, Default)]
#[serde(default, deny_unknown_fields)]
pub struct Creepages {
    /// Longitudinal creepage xi [-].
    pub creepage_long: f64,
    /// Lateral creepage eta [-].
    pub creepage_lat: f64,
    /// Spin creepage phi [1/m].
    pub spin_per_m: f64,
}

impl Creepages {
    /// Checks that all creepages are finite; keys are named `rolling.*`.
    pub fn validate(&self) -> Result<(), ContactError> {
        require_finite("rolling.creepage_long", self.creepage_long)?;
        require_finite("rolling.creepage_lat", self.creepage_lat)?;
        require_finite("rolling.spin_per_m", self.spin_per_m)
    }

    /// Checks creepages given as input against their documented ranges
    /// ([`CREEPAGE_RANGE`], [`SPIN_RANGE`]); keys are named `rolling.*`.
    pub fn check_input(&self) -> Result<(), ContactError> {
        CREEPAGE_RANGE.check("rolling.creepage_long", self.creepage_long)?;
        CREEPAGE_RANGE.check("rolling.creepage_lat", self.creepage_lat)?;
        SPIN_RANGE.check("rolling.spin_per_m", self.spin_per_m)?;
        Ok(())
    }
}

/// One step of a transient (shift) problem.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ShiftStep {
    /// Normal load during the step.
    pub load: NormalLoad,
    /// Rigid shift of body 1 relative to body 2 in x during the step \[m\].
    pub shift_x_m: f64,
    /// Rigid shift in y during the step \[m\].
    pub shift_y_m: f64,
    /// Rigid rotation about the n axis during the step \[rad\].
    pub rotation_rad: f64,
    /// Distance the contact patch rolls over both bodies during the step
    /// \[m\], in +x or the problem's rolling direction, in moving
    /// coordinates (see the module conventions): the previous step's
    /// tractions are carried this far upstream. 0 (the default) is a shift
    /// step; otherwise, along an axis, a whole number of elements of the
    /// grid along the rolling direction (`dx_m`, `dy_m` rolling along y),
    /// and any distance below the grid's extent off the axes, checked by
    /// [`ShiftStep::carry`]. Along an axis a step of more than one element
    /// takes CONTACT's leading-edge correction for the material that
    /// entered the contact area during the step
    /// ([`crate::core::leading_edge`]); one element a step needs none.
    #[serde(default)]
    pub rolling_m: f64,
}

/// Relative distance to a whole number of elements below which a rolling
/// distance counts as whole (rounding of dq = k dx in decimal input).
const WHOLE_ELEMENTS_TOLERANCE: f64 = 1e-6;

impl ShiftStep {
    /// A transient rolling step of `rolling_m` \[m\] at `creepages`: the
    /// rigid shift is the creepages' rigid slip times the distance rolled
    /// (shift_x = xi dq, shift_y = eta dq, rotation = phi dq).
    pub fn rolling(load: NormalLoad, rolling_m: f64, creepages: &Creepages) -> Self {
        Self {
            load,
            shift_x_m: creepages.creepage_long * rolling_m,
            shift_y_m: creepages.creepage_lat * rolling_m,
            rotation_rad: creepages.spin_per_m * rolling_m,
            rolling_m,
        }
    }

    /// Checks the load and that the shifts are finite and the rolling
    /// distance finite and >= 0; `key` names the step (e.g.
    /// `transient.steps[3]`).
    pub fn validate(&self, key: &str) -> Result<(), ContactError> {
        validate_load(key, &self.load)?;
        require_finite(&format!("{key}.shift_x_m"), self.shift_x_m)?;
        require_finite(&format!("{key}.shift_y_m"), self.shift_y_m)?;
        require_finite(&format!("{key}.rotation_rad"), self.rotation_rad)?;
        let rolling_key = format!("{key}.rolling_m");
        require_finite(&rolling_key, self.rolling_m)?;
        if self.rolling_m < 0.0 {
            return Err(ContactError::invalid(
                rolling_key,
                format!(
                    "must be >= 0 (the patch rolls in +x), got {}",
                    crate::core::error::show(self.rolling_m)
                ),
            ));
        }
        Ok(())
    }

    /// The rolling distance in elements of `grid` ([`rolling_elements`]);
    /// `key` names the step.
    pub fn rolled_elements(&self, grid: &Grid, key: &str) -> Result<usize, ContactError> {
        rolling_elements(&format!("{key}.rolling_m"), self.rolling_m, grid)
    }

    /// How far this step carries the previous tractions on `grid` of the
    /// rolling frame, the patch rolling at `oblique_rad` from its x axis
    /// ([`crate::core::frame::Direction`]): along x by whole elements
    /// ([`ShiftStep::rolled_elements`]) when `oblique_rad` is 0, else by
    /// (dq cos theta / dx, dq sin theta / dy) elements, each below the
    /// grid's count; `key` names the step.
    pub fn carry(&self, grid: &Grid, oblique_rad: f64, key: &str) -> Result<Carry, ContactError> {
        if oblique_rad == 0.0 || self.rolling_m == 0.0 {
            return Ok(Carry::Whole(self.rolled_elements(grid, key)?));
        }
        let (s, c) = oblique_rad.sin_cos();
        let elements = [
            self.rolling_m * c / grid.dx_m,
            self.rolling_m * s / grid.dy_m,
        ];
        if !(elements[0] < grid.nx as f64 && elements[1].abs() < grid.ny as f64) {
            return Err(ContactError::invalid(
                format!("{key}.rolling_m"),
                format!(
                    "must roll less than the grid's length along each axis: {} m at {} rad is \
                     {} x {} elements of a grid of {} x {}",
                    crate::core::error::show(self.rolling_m),
                    crate::core::error::show(oblique_rad),
                    crate::core::error::show(elements[0]),
                    crate::core::error::show(elements[1]),
                    grid.nx,
                    grid.ny
                ),
            ));
        }
        Ok(Carry::Oblique(elements))
    }
}

/// How far a transient step carries the previous tractions upstream
/// ([`ShiftStep::carry`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Carry {
    /// Whole elements along x (0: a shift step).
    Whole(usize),
    /// Elements along x (> 0) and y, off the element centres.
    Oblique([f64; 2]),
}

/// A rolling distance in elements of `grid`: `rolling_m / dx_m`, which
/// must be a whole number (within 1e-6 of an element) below `nx` (the
/// tractions are carried by whole elements, without interpolation); the
/// error names `key`.
pub fn rolling_elements(key: &str, rolling_m: f64, grid: &Grid) -> Result<usize, ContactError> {
    let k = rolling_m / grid.dx_m;
    let whole = k.round();
    if !(k.is_finite() && k >= 0.0)
        || (k - whole).abs() > WHOLE_ELEMENTS_TOLERANCE * whole.max(1.0)
        || whole >= grid.nx as f64
    {
        return Err(ContactError::invalid(
            key,
            format!(
                "must be a whole number of elements dx = {} m below the grid length ({} \
                 elements): the tractions roll by whole elements; got {} m = {} dx",
                crate::core::error::show(grid.dx_m),
                grid.nx,
                crate::core::error::show(rolling_m),
                crate::core::error::show(k)
            ),
        ));
    }
    Ok(whole as usize)
}

/// What moves.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Kinematics {
    /// Normal problem only, no friction.
    Frictionless,
    /// Steady-state rolling with the given creepages.
    SteadyRolling(Creepages),
    /// A sequence of shift and rolling steps starting from the unloaded
    /// state; each step starts from the previous step's tractions (carried
    /// upstream by the distance rolled).
    Transient(Vec<ShiftStep>),
}

/// Solver settings (tolerances and iteration limits).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SolverSettings {
    /// Normal problem.
    pub normal: NormalSettings,
    /// Tangential problem.
    pub tangential: TangentialSettings,
    /// Ends the normal/tangential alternation when the tractions'
    /// estimated distance to the coupled solution, relative to the
    /// pressures' L1 norm, is below it (default 1e-8 when 0; see
    /// [`crate::core::coupling::CouplingMonitor`]).
    pub coupling_tolerance: f64,
    /// Alternation limit (default 30 when 0).
    pub coupling_max_iterations: usize,
    /// Whether a patch may reach the border of the grid. False (the
    /// default): a loaded border element is [`ContactError::GridTooSmall`]
    /// naming the window to enlarge. True: the solution is returned, as
    /// CONTACT does, and the caller counts the loaded border elements
    /// ([`crate::core::grid::Grid::loaded_border_elements`]); the pressure
    /// outside the grid is missing from it.
    pub allow_border_contact: bool,
    /// An interfacial (third-body) layer between the bodies, elastic or
    /// elasto-plastic (CONTACT's M = 4, [`crate::core::layer`]); None (the
    /// default): the bodies touch. Part of the problem's physics, kept
    /// here so that every problem carries it without a change of its
    /// statement: the exact model's solver takes it (its kernels include
    /// the layer's flexibility, its history the plastic state), checked
    /// by [`ContactProblem::validate`]; so do the exact wheel/rail patches,
    /// whose problems take the wheel/rail settings' solver settings (their
    /// plastic state: [`crate::wheelrail::PatchResult::layer`]). The
    /// other models (FASTSIM, the conformal solvers) do not read it.
    pub interfacial_layer: Option<InterfacialLayer>,
    /// Viscoelastic bodies (CONTACT's M = 1, [`crate::core::viscoelastic`]):
    /// the materials' shear moduli are then the glassy ones; None (the
    /// default): elastic bodies. Steady rolling in +x and the frictionless
    /// normal problem of bodies rolling so, exact model: checked by
    /// [`ContactProblem::validate`] (a transient problem, or rolling in
    /// another direction, is refused naming [`VISCOELASTIC_KEY`]). Kept
    /// here, as the layer, so that every problem carries it; the other
    /// models do not read it.
    pub viscoelastic: Option<Viscoelastic>,
}

/// A complete, validated contact problem.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactProblem {
    /// Materials of both bodies.
    pub material: CombinedMaterial,
    /// Friction.
    pub friction: Friction,
    /// Potential contact grid.
    pub grid: Grid,
    /// Undeformed distance h per element \[m\] (index `iy * nx + ix`).
    pub gap_m: Vec<f64>,
    /// Normal load (steady rolling and frictionless problems; transient steps
    /// carry their own).
    pub load: NormalLoad,
    /// Kinematics.
    pub kinematics: Kinematics,
    /// Solver settings.
    pub settings: SolverSettings,
    /// Rolling direction chi \[rad\] (see the module conventions): 0
    /// rolling in +x; a multiple of pi/2 in steady rolling.
    pub rolling_direction_rad: f64,
    /// Extra rigid slip per element (see the module conventions); None: none.
    pub extra_rigid_slip: Option<ExtraRigidSlip>,
    /// Influence coefficients from a file of numerical influence
    /// coefficients (CONTACT's C3 = 9, [`crate::core::numerical_influence`])
    /// instead of the half-space's; None: the half-space. The exact model
    /// takes files of one matrix or of one per row of the grid, on a
    /// surface grid whose element sizes are the file's, elastic bodies in contact (no interfacial layer),
    /// rolling in +x (0): checked by [`ContactProblem::validate`], naming
    /// [`NUMERICAL_INFLUENCE_KEY`]. The materials' combined shear modulus
    /// scales the coefficients.
    pub numerical_influence: Option<Arc<InfluenceFile>>,
}

/// An extra rigid slip per element [-] added to the creepages' rigid slip
/// in rolling, and an extra rigid shift per element \[m\] added to the
/// rigid shift of each transient shift step (index `iy * nx + ix`, one
/// value per element in each component): CONTACT's `EXRHS` (E = 9) of a
/// rolling case and of a shift case, relevant for conformal contact and
/// coupling with finite elements. Steady rolling and rolling steps need the
/// slip, shift steps the shift; a pair not needed may be empty.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ExtraRigidSlip {
    /// x component [-] (empty: no slip).
    pub slip_x: Vec<f64>,
    /// y component [-] (empty with `slip_x`).
    pub slip_y: Vec<f64>,
    /// x component of the shift of each shift step \[m\] (empty: no shift).
    pub shift_x_m: Vec<f64>,
    /// y component \[m\] (empty with `shift_x_m`).
    pub shift_y_m: Vec<f64>,
}

impl HeapBytes for ExtraRigidSlip {
    fn heap_bytes(&self) -> usize {
        heap_bytes!(self.slip_x, self.slip_y, self.shift_x_m, self.shift_y_m)
    }
}

impl ExtraRigidSlip {
    /// The same extra slip (`x`, `y`) [-] in every element of `grid`.
    pub fn uniform(grid: &Grid, x: f64, y: f64) -> Self {
        Self {
            slip_x: vec![x; grid.len()],
            slip_y: vec![y; grid.len()],
            ..Self::default()
        }
    }

    /// The same extra shift (`x`, `y`) \[m\] of every shift step in every
    /// element of `grid`.
    pub fn uniform_shift(grid: &Grid, x: f64, y: f64) -> Self {
        Self {
            shift_x_m: vec![x; grid.len()],
            shift_y_m: vec![y; grid.len()],
            ..Self::default()
        }
    }

    /// Whether it has a slip (for rolling).
    pub fn has_slip(&self) -> bool {
        !self.slip_x.is_empty()
    }

    /// Whether it has a shift (for shift steps).
    pub fn has_shift(&self) -> bool {
        !self.shift_x_m.is_empty()
    }

    /// Checks that `kinematics` finds what it needs: a slip for steady
    /// rolling and rolling steps (`rolling_m > 0`), a shift for shift
    /// steps; errors name the missing pair and the step.
    pub fn check_kinematics(&self, kinematics: &Kinematics) -> Result<(), ContactError> {
        match kinematics {
            Kinematics::Frictionless => Err(ContactError::invalid(
                "extra_rigid_slip",
                "needs rolling or transient steps (the problem is frictionless)",
            )),
            Kinematics::SteadyRolling(_) => {
                if self.has_shift() {
                    return Err(ContactError::invalid(
                        "extra_rigid_slip.shift_x_m",
                        "is the shift of transient shift steps: steady rolling takes slip_x, slip_y",
                    ));
                }
                self.check_step_kind(true, "steady rolling")
            }
            Kinematics::Transient(steps) => {
                for (k, s) in steps.iter().enumerate() {
                    self.check_step(s, &format!("transient.steps[{k}]"))?;
                }
                Ok(())
            }
        }
    }

    /// Checks that transient `step` (named `key`) finds what it needs (see
    /// [`ExtraRigidSlip::check_kinematics`]).
    pub fn check_step(&self, step: &ShiftStep, key: &str) -> Result<(), ContactError> {
        self.check_step_kind(step.rolling_m > 0.0, key)
    }

    fn check_step_kind(&self, rolls: bool, what: &str) -> Result<(), ContactError> {
        match (rolls, self.has_slip(), self.has_shift()) {
            (true, false, _) => Err(ContactError::invalid(
                "extra_rigid_slip.slip_x",
                format!(
                    "missing: {what} rolls, and takes the extra slip per unit rolled distance \
                     (slip_x, slip_y)"
                ),
            )),
            (false, _, false) => Err(ContactError::invalid(
                "extra_rigid_slip.shift_x_m",
                format!("missing: {what} is a shift step, and takes the extra shift (shift_x_m, shift_y_m)"),
            )),
            _ => Ok(()),
        }
    }

    /// Checks one finite value per element of `grid` in each component of
    /// each pair given (both components of a pair, or neither), and one
    /// pair at least; keys are named `extra_rigid_slip.slip_x` and so on.
    pub fn validate(&self, grid: &Grid) -> Result<(), ContactError> {
        if !self.has_slip() && !self.has_shift() {
            return Err(ContactError::invalid(
                "extra_rigid_slip",
                "is empty: give slip_x, slip_y (rolling) or shift_x_m, shift_y_m (shift steps)",
            ));
        }
        for (key, v, given) in [
            ("extra_rigid_slip.slip_x", &self.slip_x, self.has_slip()),
            ("extra_rigid_slip.slip_y", &self.slip_y, self.has_slip()),
            (
                "extra_rigid_slip.shift_x_m",
                &self.shift_x_m,
                self.has_shift(),
            ),
            (
                "extra_rigid_slip.shift_y_m",
                &self.shift_y_m,
                self.has_shift(),
            ),
        ] {
            // A pair is given whole (its x component non-empty) or not at all.
            if !given && v.is_empty() {
                continue;
            }
            if !given {
                return Err(ContactError::invalid(
                    key,
                    "is given without its x component: give both components of the pair",
                ));
            }
            if v.len() != grid.len() {
                return Err(ContactError::invalid(
                    key,
                    format!(
                        "has {} values for a grid of {} x {} = {} elements",
                        v.len(),
                        grid.nx,
                        grid.ny,
                        grid.len()
                    ),
                ));
            }
            if let Some(i) = v.iter().position(|x| !x.is_finite()) {
                return Err(ContactError::invalid(
                    format!("{key}[{i}]"),
                    format!("must be finite, got {}", crate::core::error::show(v[i])),
                ));
            }
        }
        Ok(())
    }
}

/// The key of [`SolverSettings::interfacial_layer`] in errors.
pub const INTERFACIAL_LAYER_KEY: &str = "interfacial_layer";

/// Most elements of a surface grid (not a line contact) with viscoelastic
/// bodies: their coefficients are integrated numerically for each element
/// offset (2 nx x 2 ny of them), a cost proportional to the elements:
/// 3.0 s at 128 x 128 (0.93 s at 64 x 64, 4.6 s at 160 x 160) on a 2-core
/// Xeon under a load of 4-6, release build, 2026-12-07; this bounds what
/// one problem costs (a cancelled caller's build stops at once:
/// [`crate::core::cache`]).
pub const MAX_VISCOELASTIC_ELEMENTS: usize = 16384;

/// The key of [`ContactProblem::numerical_influence`] in errors (the
/// case file's key).
pub const NUMERICAL_INFLUENCE_KEY: &str = "material.influence_file";

/// Largest rows x elements of a grid with a file of one matrix per loaded
/// row: the solver holds a kernel set per row (under 0.5 kB an element
/// each, 285 B at 21 x 17: 2^20 at most about 0.5 GB) and a product costs
/// up to a product per row.
pub const MAX_PER_ROW_WORK: usize = 1 << 20;

/// Refuses a file of numerical influence coefficients the exact model
/// cannot take with this problem (see
/// [`ContactProblem::numerical_influence`]), naming
/// [`NUMERICAL_INFLUENCE_KEY`] and the file's field at fault.
fn check_numerical_influence(p: &ContactProblem, file: &InfluenceFile) -> Result<(), ContactError> {
    let refuse = |what: &str| {
        Err(ContactError::invalid(
            NUMERICAL_INFLUENCE_KEY,
            format!("numerical influence coefficients are taken {what}"),
        ))
    };
    if p.grid.is_line() {
        return refuse("on a surface grid, not in line contact");
    }
    if p.settings.interfacial_layer.is_some() {
        return refuse("for bodies in contact, not with an interfacial layer");
    }
    if p.settings.viscoelastic.is_some() {
        return refuse("for elastic bodies, not viscoelastic ones");
    }
    if p.rolling_direction_rad != 0.0 {
        return refuse("rolling in +x only (rolling direction 0)");
    }
    file.check_grid(p.grid.ny, p.grid.dx_m, p.grid.dy_m)
        .map_err(|(field, reason)| {
            ContactError::invalid(format!("{NUMERICAL_INFLUENCE_KEY}: {field}"), reason)
        })?;
    let work = p.grid.ny.saturating_mul(p.grid.len());
    if file.matrices() > 1 && work > MAX_PER_ROW_WORK {
        return Err(ContactError::invalid(
            NUMERICAL_INFLUENCE_KEY,
            format!(
                "a file of one matrix per loaded row on a grid of {} x {} elements: rows x \
                 elements = {work} over {MAX_PER_ROW_WORK} (one kernel set per row: memory and \
                 the cost of a product grow with it)",
                p.grid.nx, p.grid.ny
            ),
        ));
    }
    Ok(())
}

/// The key of [`SolverSettings::viscoelastic`] in errors.
pub const VISCOELASTIC_KEY: &str = "viscoelastic";

/// Refuses viscoelastic bodies (not both elastic) on a surface grid of
/// `nx` x `ny` elements over [`MAX_VISCOELASTIC_ELEMENTS`], naming
/// [`VISCOELASTIC_KEY`]; a line contact (`line`) has no limit. Checked
/// before any coefficient is integrated (by [`ContactProblem::validate`]
/// and by the case file's validation, before a solver is built).
pub fn check_viscoelastic_grid(
    visc: &Viscoelastic,
    nx: usize,
    ny: usize,
    line: bool,
) -> Result<(), ContactError> {
    let elements = nx.saturating_mul(ny);
    let elastic = visc.body1.is_elastic() && visc.body2.is_elastic();
    if !elastic && !line && elements > MAX_VISCOELASTIC_ELEMENTS {
        return Err(ContactError::invalid(
            VISCOELASTIC_KEY,
            format!(
                "viscoelastic bodies on a grid of {nx} x {ny} = {elements} elements: at most \
                 {MAX_VISCOELASTIC_ELEMENTS} (128 x 128) on a surface, whose coefficients are \
                 integrated numerically per element offset (about 3 s at 128 x 128, growing with \
                 the elements); line contact has no limit"
            ),
        ));
    }
    Ok(())
}

/// Checks a normal load; `key` names it.
pub fn validate_load(key: &str, load: &NormalLoad) -> Result<(), ContactError> {
    match *load {
        NormalLoad::NormalForce(f) => require_positive(&format!("{key}.normal_force_n"), f),
        NormalLoad::Approach(d) => require_finite(&format!("{key}.approach_m"), d),
    }
}

impl ContactProblem {
    /// Validates everything a solve relies on.
    pub fn validate(&self) -> Result<(), ContactError> {
        self.friction.validate()?;
        if self.gap_m.len() != self.grid.len() {
            return Err(ContactError::invalid(
                "geometry.gap_m",
                format!(
                    "has {} values for a grid of {} elements",
                    self.gap_m.len(),
                    self.grid.len()
                ),
            ));
        }
        if let Some(i) = self.gap_m.iter().position(|v| !v.is_finite()) {
            return Err(ContactError::invalid(
                "geometry.gap_m",
                format!("value {i} is not finite"),
            ));
        }
        validate_load("load", &self.load)?;
        if let Some(file) = &self.numerical_influence {
            check_numerical_influence(self, file)?;
        }
        if let Some(layer) = &self.settings.interfacial_layer {
            layer.validate(INTERFACIAL_LAYER_KEY)?;
            layer.check_friction(INTERFACIAL_LAYER_KEY, &self.friction)?;
        }
        if let Some(visc) = &self.settings.viscoelastic {
            visc.validate(VISCOELASTIC_KEY)?;
            if matches!(self.kinematics, Kinematics::Transient(_)) {
                return Err(ContactError::invalid(
                    VISCOELASTIC_KEY,
                    "viscoelastic bodies are taken in steady rolling (and its frictionless \
                     normal problem) only, not in transient steps",
                ));
            }
            if self.rolling_direction_rad != 0.0 {
                return Err(ContactError::invalid(
                    crate::core::frame::ROLLING_DIRECTION_KEY,
                    "viscoelastic bodies roll in +x only (0)",
                ));
            }
            check_viscoelastic_grid(visc, self.grid.nx, self.grid.ny, self.grid.is_line())?;
        }
        // Rolling steps roll whole elements of the rolling frame's grid, or
        // any distance off its axes.
        let direction =
            crate::core::frame::direction(self.rolling_direction_rad, self.grid.is_line())?;
        let rolling_grid =
            crate::core::frame::RollingFrame::new(direction.turns, self.grid).rolling_grid();
        if !direction.is_axis() && matches!(self.kinematics, Kinematics::SteadyRolling(_)) {
            crate::core::frame::quarter_turns(self.rolling_direction_rad, &self.grid)?;
        }
        if let Some(extra) = &self.extra_rigid_slip {
            extra.validate(&self.grid)?;
            extra.check_kinematics(&self.kinematics)?;
        }
        match &self.kinematics {
            Kinematics::Frictionless => {}
            Kinematics::SteadyRolling(c) => c.validate()?,
            Kinematics::Transient(steps) => {
                if steps.is_empty() {
                    return Err(ContactError::invalid(
                        "transient.steps",
                        "needs at least one step",
                    ));
                }
                for (k, s) in steps.iter().enumerate() {
                    let key = format!("transient.steps[{k}]");
                    s.validate(&key)?;
                    s.carry(&rolling_grid, direction.oblique_rad, &key)?;
                }
            }
        }
        Ok(())
    }

    /// The quadratic undeformed distance h = A x² + B y² on `grid`.
    pub fn quadratic_gap(grid: &Grid, a_per_m: f64, b_per_m: f64) -> Vec<f64> {
        let mut h = vec![0.0; grid.len()];
        Self::quadratic_gap_at(grid, a_per_m, b_per_m, 0.0, &mut h);
        h
    }

    /// Writes h = A (x - `x_offset_m`)² + B y² on `grid` into `h` (one value
    /// per element): the quadratic gap of bodies moved `x_offset_m` in +x
    /// over the grid.
    pub fn quadratic_gap_at(
        grid: &Grid,
        a_per_m: f64,
        b_per_m: f64,
        x_offset_m: f64,
        h: &mut [f64],
    ) {
        for iy in 0..grid.ny {
            let y = grid.y_m(iy);
            for ix in 0..grid.nx {
                let x = grid.x_m(ix) - x_offset_m;
                h[grid.index(ix, iy)] = a_per_m * x * x + b_per_m * y * y;
            }
        }
    }
}
