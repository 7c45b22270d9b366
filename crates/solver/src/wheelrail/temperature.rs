//! Flash temperatures of the wheel and rail surfaces per contact patch, from
//! each patch's traction and slip fields (Ertz & Knothe's model of
//! [`crate::core::temperature`], the one the patch problems use).
//!
//! # Bodies, speed and frame
//!
//! * The rail is body 1 and the wheel body 2, as in every wheel/rail patch
//!   ([`crate::wheelrail::contact`], "Conventions"): the inputs are named
//!   `rail` and `wheel` ([`WheelRailThermal`]) so that no key depends on
//!   that numbering, and so are the results ([`PatchTemperatures`]); the
//!   fields ([`PatchTemperatures::surface`]) keep the core's `body1_k`
//!   (the rail) and `body2_k` (the wheel).
//! * The rolling speed is not an input: each patch rolls at its own
//!   `rolling_speed_m_per_s` ([`PatchResult::rolling_speed_m_per_s`]), the
//!   mean of the wheelset's forward speed and the wheel's circumferential
//!   speed at the patch (about the forward speed; on the flange 1.6 %
//!   above it at free rolling), the speed its slips are divided by. So the
//!   heat flux |p_t| |s| V sums to the patch's `frictional_power_w` (T-gamma
//!   times V), and the patch travels over both surfaces at that speed
//!   (Ertz & Knothe's equal surface speeds).
//! * The fields are on the patch grid: x along the track (the rolling
//!   direction, material entering at large x), y the lateral coordinate s
//!   (in the contact plane of an `exact` patch, the arc length along the
//!   curved surface of a `cect` patch); the peaks' `y_m` is that s.
//!
//! # Which models
//!
//! Models `exact`, `cect` and `auto` (whose patches are one or the
//! other): the temperatures need the tractions and slips per element on a
//! grid whose rows run in the rolling direction. An exact patch has them
//! on its planar grid; a `cect` patch on its curved one, whose rows also
//! run along x at a fixed s: the model is 1-D heat conduction into the
//! depth under each surface point, fed along each row, so the surface's
//! curvature across the rows does not enter it (the heat a surface
//! element takes is |p_t| |s| V times its area dx ds on the curved
//! surface, as the conformal frictional power counts it). The others are
//! refused naming `temperature`: the Hertz models and `kik_piotrowski`
//! give their forces in closed form or from FASTSIM strips, not a traction
//! field on a grid (a flash temperature from a patch's total power alone
//! would be a Jaeger-type estimate, another model).
//!
//! # Cost
//!
//! Nothing when `temperature` is absent (the solve does not look at it).
//! With it, one [`flash_temperatures`] per patch after the last solve of
//! the wheelset (O(nx² ny) square roots, and three fields of the patch
//! grid's size); a `cect` patch keeps its last solve's tractions and slips
//! (moved, not copied) instead of dropping them.

use serde::{Deserialize, Serialize};

use crate::core::error::ContactError;
use crate::core::temperature::{
    flash_temperatures, SurfaceTemperatures, TemperaturePeak, ThermalBody, ThermalInput,
    ROLLING_SPEED_RANGE,
};
use crate::wheelrail::contact::{PatchResult, WheelRailModel, WheelResult};
use crate::wheelrail::wheelset::WheelRailError;

/// The key of a wheel/rail query's flash temperatures (case file section
/// `[temperature]`).
pub const TEMPERATURE_KEY: &str = "temperature";

/// The thermal inputs of a wheel/rail query: both bodies (the rolling
/// speed is each patch's own, see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WheelRailThermal {
    /// The rail (body 1 of the patches).
    pub rail: ThermalBody,
    /// The wheel (body 2 of the patches).
    pub wheel: ThermalBody,
}

impl WheelRailThermal {
    /// Checks both bodies; `key` names the section (`temperature`), the
    /// bodies `{key}.rail` and `{key}.wheel`.
    pub fn validate(&self, key: &str) -> Result<(), ContactError> {
        self.rail.validate(&format!("{key}.rail"))?;
        self.wheel.validate(&format!("{key}.wheel"))
    }

    /// The core's input of a patch rolling at `rolling_speed_m_per_s`:
    /// body 1 the rail, body 2 the wheel.
    pub fn input(&self, rolling_speed_m_per_s: f64) -> ThermalInput {
        ThermalInput {
            body1: self.rail,
            body2: self.wheel,
            rolling_speed_m_per_s,
        }
    }
}

/// The flash temperatures of one wheel/rail patch.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PatchTemperatures {
    /// Highest surface temperature of the rail and where it is on the
    /// patch grid (x, s) \[K, m\].
    pub max_rail: TemperaturePeak,
    /// Highest surface temperature of the wheel \[K, m\].
    pub max_wheel: TemperaturePeak,
    /// Common surface temperature in the contact before frictional heating
    /// \[K\]: the bulk temperatures weighted by the effusivities.
    pub contact_temperature_k: f64,
    /// Share of the frictional heat into the rail [-].
    pub heat_share_rail: f64,
    /// Frictional power of the patch from the heat flux, sum q dA \[W\].
    pub frictional_power_w: f64,
    /// Peclet number V a / (2 kappa) [-] (module docs of
    /// [`crate::core::temperature`]).
    pub peclet_number: f64,
    /// The fields on the patch grid: `body1_k` the rail's, `body2_k` the
    /// wheel's \[K\], and the heat flux \[W/m²\].
    #[serde(skip)]
    pub surface: SurfaceTemperatures,
}

/// The flash temperatures of an `exact` or `cect` `patch` (None for a
/// patch without per-element fields).
pub fn patch_temperatures(
    patch: &PatchResult,
    thermal: &WheelRailThermal,
) -> Result<Option<PatchTemperatures>, ContactError> {
    let fields = match (&patch.solution, &patch.conformal_fields) {
        (Some(s), _) => &s.fields,
        (None, Some(f)) => f,
        (None, None) => return Ok(None),
    };
    let Some(grid) = &patch.grid_geometry else {
        return Ok(None);
    };
    let v = patch.rolling_speed_m_per_s;
    ROLLING_SPEED_RANGE.check("velocity.forward_m_per_s", v)?;
    let surface = flash_temperatures(grid, fields, &thermal.input(v))?;
    let s = surface.summary;
    Ok(Some(PatchTemperatures {
        max_rail: s.max_body1,
        max_wheel: s.max_body2,
        contact_temperature_k: s.contact_temperature_k,
        heat_share_rail: s.heat_share_body1,
        frictional_power_w: s.frictional_power_w,
        peclet_number: s.peclet_number,
        surface,
    }))
}

/// Refuses, naming `temperature`, a model whose patches have no traction
/// and slip fields for the temperatures (all but `exact`, `cect` and
/// `auto`: see the module docs).
pub fn check_model(model: WheelRailModel) -> Result<(), WheelRailError> {
    if matches!(
        model,
        WheelRailModel::Exact | WheelRailModel::Cect | WheelRailModel::Auto
    ) {
        return Ok(());
    }
    Err(WheelRailError::invalid(
        TEMPERATURE_KEY,
        format!(
            "flash temperatures come from the tractions and slips per element of models \
             \"exact\", \"cect\" and \"auto\"; model \"{}\" has none on a patch grid",
            model.name()
        ),
    ))
}

/// [`check_model`], then the bodies (keys `temperature.rail.*`,
/// `temperature.wheel.*`).
pub(crate) fn validate(
    thermal: &WheelRailThermal,
    model: WheelRailModel,
) -> Result<(), WheelRailError> {
    check_model(model)?;
    Ok(thermal.validate(TEMPERATURE_KEY)?)
}

/// Sets the flash temperatures of every patch of `wheels`.
pub(crate) fn add_temperatures(
    wheels: &mut [WheelResult],
    thermal: &WheelRailThermal,
) -> Result<(), WheelRailError> {
    for p in wheels.iter_mut().flat_map(|w| &mut w.patches) {
        p.temperature = patch_temperatures(p, thermal)?;
    }
    Ok(())
}
