//! Wire <-> wheel/rail: a [`pb::SolveWheelRailRequest`] becomes the
//! library's [`WheelRailInput`] (the keys of a `railcontact wheelrail`
//! case file, with the pair's materials, friction and element size unless
//! the query overrides them), and a [`WheelRailSolution`] becomes a
//! [`pb::WheelRailResult`], with the solution's plausibility warnings
//! ([`check_plausibility`](crate::wheelrail::check_plausibility)) naming
//! the request's fields at fault. The numbers themselves are checked by
//! [`solve_wheelset`](crate::wheelrail::solve_wheelset), whose keys
//! (`position.yaw_rad`, `velocity.forward_m_per_s`, `load.approach_m`) are
//! the request's field paths.

use crate::conformal::geometry::RigidSlipSurface;
use crate::core::fastsim::SlopeReduction;
use crate::core::friclaw::{FallingShape, SlipStart};
use crate::core::material::CombinedMaterial;
use crate::core::polach::PolachParameters;
use crate::core::problem::Friction;
use crate::core::temperature::ThermalBody;
use crate::service::convert::{
    check_fields_finite, finite_values, grid_info, planar_fields, rigid_slip, temperature_result,
    thermal_input,
};
use crate::service::pairs::{self, PairSettings};
use crate::service::pb;
use crate::service::status::ServiceError;
use crate::wheelrail::grid_sizing;
use crate::wheelrail::temperature::{check_model, TEMPERATURE_KEY};
use crate::wheelrail::{
    FrictionAxis, FrictionTable, PatchResult, PlausibilityWarning, RailMotion, Side, WarningKind,
    WheelLoad, WheelRailInput, WheelRailModel, WheelRailSettings, WheelRailSolution,
    WheelRailThermal, WheelResult, WheelsetPosition, WheelsetVelocity,
};

/// The documented ranges of a wheel/rail query's motion and load (the
/// proto's `WheelsetPosition`, `WheelsetVelocity`, `WheelLoad`), checked
/// before anything is solved: the solver's, which the command line checks
/// too.
pub use crate::wheelrail::ranges;

/// The request field of a wheel/rail load: `load.vertical_force_n`,
/// `load.approach_m` or `load.center_z_m` (`load` when none is set).
pub fn load_field(load: Option<&pb::WheelLoad>) -> &'static str {
    match load.and_then(|l| l.load.as_ref()) {
        Some(pb::wheel_load::Load::VerticalForceN(_)) => "load.vertical_force_n",
        Some(pb::wheel_load::Load::ApproachM(_)) => "load.approach_m",
        Some(pb::wheel_load::Load::CenterZM(_)) => "load.center_z_m",
        None => "load",
    }
}

/// The library model of a wire model.
pub fn model(m: i32) -> Result<WheelRailModel, ServiceError> {
    match pb::WheelRailModel::try_from(m) {
        Ok(pb::WheelRailModel::Unspecified | pb::WheelRailModel::Exact) => {
            Ok(WheelRailModel::Exact)
        }
        Ok(pb::WheelRailModel::HertzFastsim | pb::WheelRailModel::HertzFastsimTable) => {
            Ok(WheelRailModel::HertzFastsim)
        }
        Ok(pb::WheelRailModel::HertzPolach) => Ok(WheelRailModel::HertzPolach),
        Ok(pb::WheelRailModel::HertzFastsimElliptic) => Ok(WheelRailModel::HertzFastsimElliptic),
        Ok(pb::WheelRailModel::HertzStrip) => Ok(WheelRailModel::HertzStrip),
        Ok(pb::WheelRailModel::HertzFastsimModified) => Ok(WheelRailModel::HertzFastsimModified),
        Ok(pb::WheelRailModel::KikPiotrowski) => Ok(WheelRailModel::KikPiotrowski),
        Ok(pb::WheelRailModel::Cect) => Ok(WheelRailModel::Cect),
        Ok(pb::WheelRailModel::Auto) => Ok(WheelRailModel::Auto),
        Err(_) => Err(ServiceError::invalid("model", format!("unknown model {m}"))),
    }
}

/// Whether a wire model asks for the pair's contact table.
pub fn tabulated(m: i32) -> bool {
    m == pb::WheelRailModel::HertzFastsimTable as i32
}

/// The wire model of a library model.
pub fn wire_model(m: WheelRailModel) -> pb::WheelRailModel {
    match m {
        WheelRailModel::Exact => pb::WheelRailModel::Exact,
        WheelRailModel::HertzFastsim => pb::WheelRailModel::HertzFastsim,
        WheelRailModel::HertzPolach => pb::WheelRailModel::HertzPolach,
        WheelRailModel::HertzFastsimElliptic => pb::WheelRailModel::HertzFastsimElliptic,
        WheelRailModel::HertzStrip => pb::WheelRailModel::HertzStrip,
        WheelRailModel::HertzFastsimModified => pb::WheelRailModel::HertzFastsimModified,
        WheelRailModel::KikPiotrowski => pb::WheelRailModel::KikPiotrowski,
        WheelRailModel::Cect => pb::WheelRailModel::Cect,
        WheelRailModel::Auto => pb::WheelRailModel::Auto,
    }
}

/// Name of a model in metrics.
pub fn model_name(m: WheelRailModel) -> &'static str {
    match m {
        WheelRailModel::Exact => "wheelrail_exact",
        WheelRailModel::HertzFastsim => "wheelrail_hertz_fastsim",
        WheelRailModel::HertzPolach => "wheelrail_hertz_polach",
        WheelRailModel::HertzFastsimElliptic => "wheelrail_hertz_fastsim_elliptic",
        WheelRailModel::HertzStrip => "wheelrail_hertz_strip",
        WheelRailModel::HertzFastsimModified => "wheelrail_hertz_fastsim_modified",
        WheelRailModel::KikPiotrowski => "wheelrail_kik_piotrowski",
        WheelRailModel::Cect => "wheelrail_cect",
        WheelRailModel::Auto => "wheelrail_auto",
    }
}

fn sides(s: i32) -> Result<Vec<Side>, ServiceError> {
    match pb::WheelSides::try_from(s) {
        Ok(pb::WheelSides::Unspecified | pb::WheelSides::Both) => Ok(Side::BOTH.to_vec()),
        Ok(pb::WheelSides::Left) => Ok(vec![Side::Left]),
        Ok(pb::WheelSides::Right) => Ok(vec![Side::Right]),
        Err(_) => Err(ServiceError::invalid("sides", format!("unknown sides {s}"))),
    }
}

/// What a query or a session fixes besides the wheelset's motion: the
/// wheels, materials, friction and solver settings.
#[derive(Debug, Clone)]
pub struct QuerySettings {
    sides: Vec<Side>,
    material: CombinedMaterial,
    friction: Friction,
    friction_table: Option<FrictionTable>,
    settings: WheelRailSettings,
    temperature: Option<WheelRailThermal>,
    /// The pair's roller rig: its rollers' nominal radius \[m\] (`None`:
    /// a track).
    roller_radius_m: Option<f64>,
}

/// The request field of the rollers' rate (a case file's
/// `track.roller_rad_per_s`, which the solver's checks name).
pub const ROLLER_RATE_FIELD: &str = "velocity.roller_rad_per_s";

/// A solver error with the case file's and the solver's keys of the
/// rollers' rate renamed to the request's field.
pub fn rollers_rekeyed(e: ServiceError) -> ServiceError {
    e.rekey("track.roller_rad_per_s", ROLLER_RATE_FIELD)
        .rekey("rail_motion.roller_rad_per_s", ROLLER_RATE_FIELD)
}

impl QuerySettings {
    /// The settings of a query or session on a pair with `pair`: the
    /// request's model and sides, its friction and element size or the
    /// pair's. Field paths are those of the request.
    pub fn new(
        model_field: i32,
        sides_field: i32,
        friction: Option<&pb::FrictionSection>,
        element_size_m: Option<f64>,
        pair: &PairSettings,
    ) -> Result<Self, ServiceError> {
        let friction = match friction {
            Some(f) => pairs::friction(f)?,
            None => pair.friction,
        };
        let element_size_m = match element_size_m {
            Some(e) => {
                pairs::check_element_size(e, "element_size_m")?;
                e
            }
            None => pair.element_size_m,
        };
        Ok(Self {
            sides: sides(sides_field)?,
            material: pair.material,
            friction,
            friction_table: None,
            settings: WheelRailSettings {
                model: model(model_field)?,
                element_size_m,
                ..WheelRailSettings::default()
            },
            temperature: None,
            roller_radius_m: pair.track.roller_radius_m,
        })
    }

    /// The settings with the request's `min_elements_across` (not set: the
    /// solver's default, [`WheelRailSettings::min_elements_across`]).
    pub fn with_min_elements_across(mut self, n: Option<u32>) -> Self {
        if let Some(n) = n {
            self.settings.min_elements_across = n as usize;
        }
        self
    }

    /// The settings with the request's `force_tolerance_of_wheel_load`
    /// (checked as the solver checks it, for this model; not set: every
    /// patch on the element size).
    pub fn with_force_tolerance(mut self, tolerance: Option<f64>) -> Result<Self, ServiceError> {
        if let Some(t) = tolerance {
            grid_sizing::validate(t, self.settings.model).map_err(|e| {
                ServiceError::from(e).rekey(
                    grid_sizing::FORCE_TOLERANCE_KEY,
                    "force_tolerance_of_wheel_load",
                )
            })?;
        }
        self.settings.force_tolerance_of_wheel_load = tolerance;
        Ok(self)
    }

    /// The settings with the request's flash temperatures (field
    /// `temperature`: body1 the rail, body2 the wheel, the rolling speed
    /// left 0; models exact, cect and auto; not set: none).
    pub fn with_temperature(
        mut self,
        t: Option<&pb::TemperatureSection>,
    ) -> Result<Self, ServiceError> {
        let Some(t) = t else { return Ok(self) };
        check_model(self.settings.model)?;
        if t.rolling_speed_m_per_s != 0.0 {
            return Err(ServiceError::invalid(
                format!("{TEMPERATURE_KEY}.rolling_speed_m_per_s"),
                format!(
                    "leave it 0 on wheel/rail queries: each patch rolls at its own speed, from \
                     velocity.forward_m_per_s and the wheel's rotation (got {})",
                    t.rolling_speed_m_per_s
                ),
            ));
        }
        let bodies = thermal_input(t)?;
        bodies.body1.validate(&format!("{TEMPERATURE_KEY}.body1"))?;
        bodies.body2.validate(&format!("{TEMPERATURE_KEY}.body2"))?;
        self.temperature = Some(WheelRailThermal {
            rail: bodies.body1,
            wheel: bodies.body2,
        });
        Ok(self)
    }

    /// The settings with the request's friction table (field
    /// `friction_table`; not set: none).
    pub fn with_friction_table(
        mut self,
        t: Option<&pb::FrictionTable>,
    ) -> Result<Self, ServiceError> {
        let Some(t) = t else { return Ok(self) };
        const KEY: &str = "friction_table";
        let (axis, positions) = match (t.contact_angles_rad.is_empty(), t.rail_y_m.is_empty()) {
            (false, true) => (FrictionAxis::ContactAngle, &t.contact_angles_rad),
            (true, false) => (FrictionAxis::RailLateral, &t.rail_y_m),
            _ => {
                return Err(ServiceError::invalid(
                    format!("{KEY}.contact_angles_rad"),
                    "give one of contact_angles_rad and rail_y_m",
                ))
            }
        };
        let table = FrictionTable {
            axis,
            positions: positions.clone(),
            track_s_m: t.track_s_m.clone(),
            coefficients: t.coefficients.clone(),
        };
        table.validate_as(KEY)?;
        self.friction_table = Some(table);
        Ok(self)
    }

    /// The settings with the conformal method's options of the request
    /// (field `conformal`, models cect and auto only; not set: the
    /// defaults).
    pub fn with_conformal(
        mut self,
        c: Option<&pb::ConformalSection>,
    ) -> Result<Self, ServiceError> {
        if let Some(c) = c {
            if !matches!(
                self.settings.model,
                WheelRailModel::Cect | WheelRailModel::Auto
            ) {
                return Err(ServiceError::invalid(
                    "conformal",
                    "options of the conformal method: models cect and auto only",
                ));
            }
            if let Some(r) = rigid_slip(c.rigid_slip)? {
                self.settings.rigid_slip = r;
            }
        }
        Ok(self)
    }

    /// The settings with Polach's parameters of the request (field
    /// `polach`; not set: his 1999 model).
    pub fn with_polach(mut self, p: Option<&pb::PolachParameters>) -> Result<Self, ServiceError> {
        if let Some(p) = p {
            let parameters = PolachParameters {
                k_adhesion: p.k_adhesion,
                k_slip: p.k_slip,
                limit_ratio: p.limit_ratio,
                decay_s_per_m: p.decay_s_per_m,
            };
            parameters.validate("polach")?;
            self.settings.polach = parameters;
        }
        Ok(self)
    }

    /// The settings with the modified FASTSIM's parameters of the request
    /// (field `modified_fastsim`; not set: [`SlopeReduction::TRACTCURV`]).
    pub fn with_modified_fastsim(
        mut self,
        m: Option<&pb::ModifiedFastsimParameters>,
    ) -> Result<Self, ServiceError> {
        if let Some(m) = m {
            let r = SlopeReduction {
                initial_factor: m.initial_factor,
                limit_ratio: m.limit_ratio,
                transition_rate: m.transition_rate,
                friction_limit_ratio: m.friction_limit_ratio,
                friction_decay_s_per_m: m.friction_decay_s_per_m,
            };
            r.validate_as("modified_fastsim")?;
            self.settings.modified_fastsim = r;
        }
        Ok(self)
    }

    /// The settings with patch grids of at most `max` elements (the
    /// server's `max_grid_elements`).
    pub fn with_max_grid_elements(mut self, max: usize) -> Self {
        self.settings.max_grid_elements = max;
        self
    }

    /// The model.
    pub fn model(&self) -> WheelRailModel {
        self.settings.model
    }

    /// The solver input of a motion under these settings. Field paths are
    /// `position`, `velocity` and `load`.
    pub fn input(
        &self,
        position: Option<pb::WheelsetPosition>,
        velocity: Option<pb::WheelsetVelocity>,
        load: Option<pb::WheelLoad>,
    ) -> Result<WheelRailInput, ServiceError> {
        let p = position.unwrap_or_default();
        let v = velocity.ok_or_else(|| {
            ServiceError::invalid(
                "velocity",
                format!(
                    "missing: give the velocity, forward_m_per_s in {}",
                    ranges::describe_forward_speed()
                ),
            )
        })?;
        let total_longitudinal_force_n = load.and_then(|l| l.total_longitudinal_force_n);
        let load = match load.and_then(|l| l.load) {
            Some(pb::wheel_load::Load::VerticalForceN(f)) => WheelLoad::VerticalForce(f),
            Some(pb::wheel_load::Load::ApproachM(d)) => WheelLoad::Approach(d),
            Some(pb::wheel_load::Load::CenterZM(z)) => WheelLoad::CenterHeight(z),
            None => {
                return Err(ServiceError::invalid(
                    "load",
                    "missing: give vertical_force_n, approach_m or center_z_m",
                ))
            }
        };
        let position = WheelsetPosition {
            lateral_m: p.lateral_m,
            yaw_rad: p.yaw_rad,
            roll_rad: p.roll_rad,
            track_s_m: p.track_s_m,
        };
        let velocity = WheelsetVelocity {
            forward_m_per_s: v.forward_m_per_s,
            lateral_m_per_s: v.lateral_m_per_s,
            vertical_m_per_s: v.vertical_m_per_s,
            roll_rad_per_s: v.roll_rad_per_s,
            yaw_rad_per_s: v.yaw_rad_per_s,
            pitch_rad_per_s: v.pitch_rad_per_s,
        };
        // A roller rig turns its rollers; a track has none (the case
        // file's rules for track.roller_rad_per_s).
        let rollers = match (self.roller_radius_m, v.roller_rad_per_s) {
            (Some(radius_m), Some(rad_per_s)) => Some(ranges::Rollers {
                radius_m,
                rad_per_s,
            }),
            (Some(_), None) => {
                return Err(ServiceError::invalid(
                    ROLLER_RATE_FIELD,
                    "missing: the pair is a roller rig (track.roller_radius_m), whose rollers \
                     need their angular velocity",
                ))
            }
            (None, Some(_)) => {
                return Err(ServiceError::invalid(
                    ROLLER_RATE_FIELD,
                    "needs a roller rig (the pair's track.roller_radius_m): leave it unset on \
                     a track",
                ))
            }
            (None, None) => None,
        };
        ranges::check_motion(
            &position,
            &velocity,
            &load,
            total_longitudinal_force_n,
            rollers,
        )
        .map_err(|e| rollers_rekeyed(e.into()))?;
        Ok(WheelRailInput {
            position,
            velocity,
            load,
            sides: self.sides.clone(),
            material: self.material,
            friction: self.friction,
            friction_table: self.friction_table.clone(),
            settings: self.settings,
            total_longitudinal_force_n,
            temperature: self.temperature,
            rail_motion: [RailMotion {
                roller_rad_per_s: rollers.map_or(0.0, |r| r.rad_per_s),
                ..RailMotion::default()
            }; 2],
            rail_slices: Default::default(),
        })
    }
}

/// The solver input of a query on a pair with `settings`, with patch
/// grids of at most `max_grid_elements`. Field paths are relative to the
/// query.
pub fn input(
    req: &pb::SolveWheelRailRequest,
    settings: &PairSettings,
    max_grid_elements: usize,
) -> Result<WheelRailInput, ServiceError> {
    let q = QuerySettings::new(
        req.model,
        req.sides,
        req.friction.as_ref(),
        req.element_size_m,
        settings,
    )?
    .with_polach(req.polach.as_ref())?
    .with_modified_fastsim(req.modified_fastsim.as_ref())?
    .with_conformal(req.conformal.as_ref())?
    .with_friction_table(req.friction_table.as_ref())?
    .with_temperature(req.temperature.as_ref())?
    .with_min_elements_across(req.min_elements_across)
    .with_force_tolerance(req.force_tolerance_of_wheel_load)?
    .with_max_grid_elements(max_grid_elements);
    q.input(req.position, req.velocity, req.load)
}

/// The wire query of a library input on the pair `pair_id` (the inverse
/// of [`input`] for the input's own friction, element size and narrow
/// patches' refinement, which it always sends): for clients written in Rust, tests and benchmarks.
pub fn query_of(pair_id: &str, input: &WheelRailInput) -> pb::SolveWheelRailRequest {
    let p = input.position;
    let v = input.velocity;
    let f = input.friction;
    pb::SolveWheelRailRequest {
        pair_id: pair_id.into(),
        model: wire_model(input.settings.model) as i32,
        sides: match input.sides.as_slice() {
            [Side::Left] => pb::WheelSides::Left,
            [Side::Right] => pb::WheelSides::Right,
            _ => pb::WheelSides::Both,
        } as i32,
        position: Some(pb::WheelsetPosition {
            lateral_m: p.lateral_m,
            yaw_rad: p.yaw_rad,
            roll_rad: p.roll_rad,
            track_s_m: p.track_s_m,
        }),
        velocity: Some(pb::WheelsetVelocity {
            forward_m_per_s: v.forward_m_per_s,
            lateral_m_per_s: v.lateral_m_per_s,
            vertical_m_per_s: v.vertical_m_per_s,
            roll_rad_per_s: v.roll_rad_per_s,
            yaw_rad_per_s: v.yaw_rad_per_s,
            pitch_rad_per_s: v.pitch_rad_per_s,
            roller_rad_per_s: input
                .rail_motion
                .iter()
                .map(|m| m.roller_rad_per_s)
                .find(|&w| w != 0.0),
        }),
        load: Some(pb::WheelLoad {
            load: Some(match input.load {
                WheelLoad::VerticalForce(f) => pb::wheel_load::Load::VerticalForceN(f),
                WheelLoad::Approach(d) => pb::wheel_load::Load::ApproachM(d),
                WheelLoad::CenterHeight(z) => pb::wheel_load::Load::CenterZM(z),
            }),
            total_longitudinal_force_n: input.total_longitudinal_force_n,
        }),
        friction: Some(friction_section_of(&f)),
        friction_table: input.friction_table.as_ref().map(|t| {
            let positions = t.positions.clone();
            let (contact_angles_rad, rail_y_m) = match t.axis {
                FrictionAxis::ContactAngle => (positions, Vec::new()),
                FrictionAxis::RailLateral => (Vec::new(), positions),
            };
            pb::FrictionTable {
                contact_angles_rad,
                rail_y_m,
                coefficients: t.coefficients.clone(),
                track_s_m: t.track_s_m.clone(),
            }
        }),
        element_size_m: Some(input.settings.element_size_m),
        min_elements_across: u32::try_from(input.settings.min_elements_across).ok(),
        force_tolerance_of_wheel_load: input.settings.force_tolerance_of_wheel_load,
        include_fields: false,
        polach: (input.settings.model == WheelRailModel::HertzPolach).then(|| {
            let p = input.settings.polach;
            pb::PolachParameters {
                k_adhesion: p.k_adhesion,
                k_slip: p.k_slip,
                limit_ratio: p.limit_ratio,
                decay_s_per_m: p.decay_s_per_m,
            }
        }),
        modified_fastsim: (input.settings.model == WheelRailModel::HertzFastsimModified).then(
            || {
                let r = input.settings.modified_fastsim;
                pb::ModifiedFastsimParameters {
                    initial_factor: r.initial_factor,
                    limit_ratio: r.limit_ratio,
                    transition_rate: r.transition_rate,
                    friction_limit_ratio: r.friction_limit_ratio,
                    friction_decay_s_per_m: r.friction_decay_s_per_m,
                }
            },
        ),
        temperature: input.temperature.map(|t| {
            let body = |b: ThermalBody| pb::ThermalBody {
                bulk_temperature_k: b.bulk_temperature_k,
                conductivity_w_per_m_k: b.conductivity_w_per_m_k,
                density_kg_per_m3: b.density_kg_per_m3,
                specific_heat_j_per_kg_k: b.specific_heat_j_per_kg_k,
            };
            pb::TemperatureSection {
                rolling_speed_m_per_s: 0.0,
                body1: Some(body(t.rail)),
                body2: Some(body(t.wheel)),
            }
        }),
        conformal: matches!(
            input.settings.model,
            WheelRailModel::Cect | WheelRailModel::Auto
        )
        .then(|| pb::ConformalSection {
            rigid_slip: match input.settings.rigid_slip {
                RigidSlipSurface::ActualSurface => pb::RigidSlip::ActualSurface,
                RigidSlipSurface::ReferenceSection => pb::RigidSlip::ReferenceSection,
            } as i32,
        }),
    }
}

/// The wire friction of a library friction (its falling law, if any,
/// without its rolling speed: each patch rolls at its own).
fn friction_section_of(f: &Friction) -> pb::FrictionSection {
    let Some(law) = f.slip_velocity_law else {
        return pb::FrictionSection {
            static_coefficient: Some(f.static_coefficient),
            kinetic_coefficient: Some(f.kinetic_coefficient),
            ..Default::default()
        };
    };
    pb::FrictionSection {
        kinetic_coefficient: Some(law.kinetic_coefficient),
        law: match law.shape {
            FallingShape::Linear => pb::FrictionLaw::Linear,
            FallingShape::Rational => pb::FrictionLaw::Rational,
            FallingShape::Exponential => pb::FrictionLaw::Exponential,
        } as i32,
        falling_coefficients: law.falling_coefficients.to_vec(),
        half_velocities_m_per_s: law.half_velocities_m_per_s.to_vec(),
        memory_distance_m: Some(law.memory_distance_m),
        memory_velocity_m_per_s: Some(law.memory_velocity_m_per_s),
        start: match law.start {
            SlipStart::Previous => pb::SlipStart::Previous,
            SlipStart::Sticking => pb::SlipStart::Sticking,
            SlipStart::Sliding => pb::SlipStart::Sliding,
        } as i32,
        max_iterations: Some(law.iteration_limit() as u32),
        ..Default::default()
    }
}

fn force(f: [f64; 3]) -> pb::TrackForce {
    pb::TrackForce {
        x_n: f[0],
        y_n: f[1],
        z_n: f[2],
    }
}

fn method(m: &str) -> pb::WheelRailModel {
    match WheelRailModel::from_name(m) {
        Some(WheelRailModel::Auto) | None => pb::WheelRailModel::Unspecified,
        Some(model) => wire_model(model),
    }
}

fn patch(p: &PatchResult, fields: bool) -> pb::WheelRailPatch {
    let with_fields = fields && p.solution.is_some() && p.grid_geometry.is_some();
    // The grid also locates a cect patch's temperature fields.
    let with_grid = with_fields || (fields && p.temperature.is_some() && p.grid_geometry.is_some());
    pb::WheelRailPatch {
        method: method(p.method) as i32,
        contact_angle_rad: p.contact_angle_rad,
        friction_coefficient: p.friction_coefficient,
        contact_angle_variation_rad: p.contact_angle_variation_rad,
        rail_y_m: p.rail_y_m,
        rail_z_m: p.rail_z_m,
        wheel_y_m: p.wheel_y_m,
        track_x_m: p.track_x_m,
        track_y_m: p.track_y_m,
        track_z_m: p.track_z_m,
        rolling_radius_m: p.rolling_radius_m,
        creepage_long: p.creepage_long,
        creepage_lat: p.creepage_lat,
        spin_per_m: p.spin_per_m,
        rolling_speed_m_per_s: p.rolling_speed_m_per_s,
        normal_force_n: p.normal_force_n,
        fx_n: p.fx_n,
        fs_n: p.fs_n,
        mz_nm: p.mz_nm,
        approach_m: p.approach_m,
        max_pressure_pa: p.max_pressure_pa,
        fastsim_max_pressure_pa: p.fastsim_max_pressure_pa,
        contact_area_m2: p.contact_area_m2,
        adhesion_fraction: p.adhesion_fraction,
        frictional_power_w: p.frictional_power_w,
        force_track_n: Some(force(p.force_track_n)),
        grid_nx: p.grid[0] as u32,
        grid_ns: p.grid[1] as u32,
        grid: p
            .grid_geometry
            .as_ref()
            .filter(|_| with_grid)
            .map(grid_info),
        fields: p
            .solution
            .as_ref()
            .filter(|_| with_fields)
            .map(|s| planar_fields(&s.fields)),
        temperature: p
            .temperature
            .as_ref()
            .map(|t| temperature_result(&t.surface, fields)),
    }
}

fn wire_side(side: Side) -> pb::WheelSide {
    match side {
        Side::Left => pb::WheelSide::Left,
        Side::Right => pb::WheelSide::Right,
    }
}

fn wheel(w: &WheelResult, fields: bool) -> pb::WheelRailWheel {
    pb::WheelRailWheel {
        side: wire_side(w.side) as i32,
        vertical_approach_m: w.vertical_approach_m,
        min_gap_m: w.min_gap_m,
        patches: w.patches.iter().map(|p| patch(p, fields)).collect(),
        force_track_n: Some(force(w.force_track_n)),
        load_iterations: w.load_iterations as u32,
    }
}

/// The wire form of plausibility warnings, each naming its input by its
/// path in the request under `prefix` (`""` for SolveWheelRail,
/// `items[3]` in a batch, `step` in a session, whose model is
/// `open.model`).
pub fn warnings(w: &[PlausibilityWarning], prefix: &str) -> Vec<pb::WheelRailWarning> {
    w.iter()
        .map(|w| pb::WheelRailWarning {
            kind: match w.kind {
                WarningKind::Approach => pb::WheelRailWarningKind::Approach,
                WarningKind::LongitudinalForce => pb::WheelRailWarningKind::LongitudinalForce,
                WarningKind::Unconverged => pb::WheelRailWarningKind::Unconverged,
                WarningKind::OpposedSurfaces => pb::WheelRailWarningKind::OpposedSurfaces,
            } as i32,
            field: match (prefix, w.kind) {
                ("", _) => w.key.to_string(),
                // A session's model is its opening's.
                ("step", WarningKind::Unconverged) => format!("open.{}", w.key),
                _ => format!("{prefix}.{}", w.key),
            },
            side: w.side.map_or(pb::WheelSide::Unspecified, wire_side) as i32,
            value: w.value,
            limit: w.limit,
            message: w.message.clone(),
        })
        .collect()
}

/// Checks every number of a wire wheel/rail result: a non-finite one is
/// refused ([`ServiceError::NonFinite`] naming its path,
/// `wheels[0].patches[1].frictional_power_w`), never sent.
pub fn check_finite(r: &pb::WheelRailResult) -> Result<(), ServiceError> {
    finite_values(
        "",
        [
            ("center_z_m", r.center_z_m),
            ("roll_rad", r.roll_rad),
            ("pitch_rad_per_s", r.pitch_rad_per_s),
        ],
    )?;
    if let Some(c) = &r.pitch_control {
        finite_values(
            "pitch_control",
            [
                ("target_force_n", c.target_force_n),
                ("force_n", c.force_n),
                ("nominal_creepage", c.nominal_creepage),
            ],
        )?;
    }
    for (i, w) in r.warnings.iter().enumerate() {
        finite_values(
            &format!("warnings[{i}]"),
            [("value", w.value), ("limit", w.limit)],
        )?;
    }
    let track = |f: &Option<pb::TrackForce>| {
        let f = f.unwrap_or_default();
        [("x_n", f.x_n), ("y_n", f.y_n), ("z_n", f.z_n)]
    };
    for (i, w) in r.wheels.iter().enumerate() {
        let at = format!("wheels[{i}]");
        finite_values(
            &at,
            [
                ("vertical_approach_m", w.vertical_approach_m),
                ("min_gap_m", w.min_gap_m),
            ],
        )?;
        finite_values(&format!("{at}.force_track_n"), track(&w.force_track_n))?;
        for (k, p) in w.patches.iter().enumerate() {
            let at = format!("{at}.patches[{k}]");
            finite_values(
                &at,
                [
                    ("contact_angle_rad", p.contact_angle_rad),
                    ("contact_angle_variation_rad", p.contact_angle_variation_rad),
                    ("rail_y_m", p.rail_y_m),
                    ("rail_z_m", p.rail_z_m),
                    ("wheel_y_m", p.wheel_y_m),
                    ("track_x_m", p.track_x_m),
                    ("track_y_m", p.track_y_m),
                    ("track_z_m", p.track_z_m),
                    ("rolling_radius_m", p.rolling_radius_m),
                    ("creepage_long", p.creepage_long),
                    ("creepage_lat", p.creepage_lat),
                    ("spin_per_m", p.spin_per_m),
                    ("normal_force_n", p.normal_force_n),
                    ("fx_n", p.fx_n),
                    ("fs_n", p.fs_n),
                    ("mz_nm", p.mz_nm),
                    ("approach_m", p.approach_m),
                    ("max_pressure_pa", p.max_pressure_pa),
                    ("contact_area_m2", p.contact_area_m2),
                    ("adhesion_fraction", p.adhesion_fraction),
                    ("frictional_power_w", p.frictional_power_w),
                ],
            )?;
            finite_values(&format!("{at}.force_track_n"), track(&p.force_track_n))?;
            if let Some(f) = &p.fields {
                check_fields_finite(&format!("{at}.fields"), f)?;
            }
            if let Some(t) = &p.temperature {
                let peak = |p: &Option<pb::TemperaturePeak>| p.unwrap_or_default().temperature_k;
                finite_values(
                    &format!("{at}.temperature"),
                    [
                        ("max_body1.temperature_k", peak(&t.max_body1)),
                        ("max_body2.temperature_k", peak(&t.max_body2)),
                        ("frictional_power_w", t.frictional_power_w),
                        ("peclet_number", t.peclet_number),
                    ],
                )?;
            }
        }
    }
    Ok(())
}

/// The wire result of a solution with its plausibility warnings (the
/// wire's form, [`warnings`]); a non-finite number is refused
/// ([`check_finite`]), never sent as a silent NaN.
pub fn result(
    pair_id: &str,
    model: WheelRailModel,
    s: &WheelRailSolution,
    warnings: Vec<pb::WheelRailWarning>,
    fields: bool,
) -> Result<pb::WheelRailResult, ServiceError> {
    let r = pb::WheelRailResult {
        pair_id: pair_id.to_string(),
        model: wire_model(model) as i32,
        center_z_m: s.center_z_m,
        roll_rad: s.roll_rad,
        pitch_rad_per_s: s.pitch_rad_per_s,
        wheels: s.wheels.iter().map(|w| wheel(w, fields)).collect(),
        timing: Some(pb::WheelRailTiming {
            search_s: s.timing.search_s,
            geometry_s: s.timing.geometry_s,
            solve_s: s.timing.solve_s,
        }),
        pitch_control: s.pitch_control.map(|c| pb::PitchControl {
            target_force_n: c.target_force_n,
            force_n: c.force_n,
            nominal_creepage: c.nominal_creepage,
            iterations: c.iterations as u32,
            solves: c.solves as u32,
            converged: c.converged,
        }),
        warnings,
    };
    check_finite(&r)?;
    Ok(r)
}
