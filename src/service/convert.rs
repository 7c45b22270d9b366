//! Wire <-> domain conversion: the only place that reads the proto types.
//!
//! A [`pb::PatchCase`] becomes the case file's [`CaseFile`] field by field
//! and is validated by [`Case::from_file`], so the service and
//! `railcontact solve` accept exactly the same cases with the same
//! messages (one place for validation). Results go the other way: core
//! solutions and the CLI's reports become [`pb::PatchResult`]s, and a
//! non-finite total is refused here, never sent.

use std::sync::Arc;

use crate::conformal::geometry::RigidSlipSurface;
use crate::core::friclaw::SlipStart;
use crate::core::grid::Grid;
use crate::core::layer::{InterfacialLayer, LayerFields};
use crate::core::material::Material;
use crate::core::normal::NormalLoad;
use crate::core::numerical_influence::{InfluenceFile, MAX_FILE_BYTES};
use crate::core::problem::{Creepages, NUMERICAL_INFLUENCE_KEY};
use crate::core::sensitivity::ForceJacobian;
use crate::core::solution::{ContactSolution, ElementFields, ElementState, SolveStatus, Totals};
use crate::core::subsurface::{BodySubsurface, FieldPeak};
use crate::core::temperature::{SurfaceTemperatures, TemperaturePeak, ThermalBody, ThermalInput};
use crate::core::viscoelastic::{Sls, Viscoelastic};
use crate::problem::case::{
    ranges, Case, CaseFile, ConformalSection, ExtraRigidSlipSection, FastsimDiscretisation,
    FastsimMethod, FastsimSection, FrictionLawName, FrictionSection, GeometryKind, GeometrySection,
    GridSection, LoadSection, MaterialSection, Model, RollingSection, SolverSection, StepSection,
    SubsurfaceSection, TractionBoundName, TransientSection,
};
use crate::problem::report::{
    ConformalFieldsReport, ConformalKeys, Fields, ForceControlReport, Report, StepForceReport,
    StepReport,
};
use crate::service::pb;
use crate::service::status::ServiceError;

/// A validated patch case and its per-element extra gap (empty: none).
pub struct ValidCase {
    /// The case, as `railcontact solve` would run it.
    pub case: Case,
    /// `geometry.extra_gap_m` \[m\], nx * ny values or none.
    pub extra_gap_m: Vec<f64>,
}

/// Limits of the server that a case must respect.
#[derive(Debug, Clone, Copy)]
pub struct CaseLimits {
    /// Largest nx * ny of a grid.
    pub max_grid_elements: usize,
}

/// The case model of a wire model.
pub fn model(m: i32) -> Result<Model, ServiceError> {
    match pb::Model::try_from(m) {
        Ok(pb::Model::Unspecified | pb::Model::Exact) => Ok(Model::Exact),
        Ok(pb::Model::Hertz) => Ok(Model::Hertz),
        Ok(pb::Model::HertzCorrected) => Ok(Model::HertzCorrected),
        Ok(pb::Model::Fastsim) => Ok(Model::Fastsim),
        Ok(pb::Model::Cect) => Ok(Model::Cect),
        Ok(pb::Model::CectHalfspace) => Ok(Model::CectHalfspace),
        Err(_) => Err(ServiceError::invalid("model", format!("unknown model {m}"))),
    }
}

/// The rigid slip surface of a wire `conformal.rigid_slip` (None: not set,
/// the default).
pub fn rigid_slip(r: i32) -> Result<Option<RigidSlipSurface>, ServiceError> {
    match pb::RigidSlip::try_from(r) {
        Ok(pb::RigidSlip::Unspecified) => Ok(None),
        Ok(pb::RigidSlip::ActualSurface) => Ok(Some(RigidSlipSurface::ActualSurface)),
        Ok(pb::RigidSlip::ReferenceSection) => Ok(Some(RigidSlipSurface::ReferenceSection)),
        Err(_) => Err(ServiceError::invalid(
            "conformal.rigid_slip",
            format!("unknown value {r}"),
        )),
    }
}

/// The wire model of a case model.
pub fn wire_model(m: Model) -> pb::Model {
    match m {
        Model::Hertz => pb::Model::Hertz,
        Model::HertzCorrected => pb::Model::HertzCorrected,
        Model::Fastsim => pb::Model::Fastsim,
        Model::Exact => pb::Model::Exact,
        Model::Cect => pb::Model::Cect,
        Model::CectHalfspace => pb::Model::CectHalfspace,
    }
}

fn material(m: &pb::Material) -> Material {
    Material {
        shear_modulus_pa: m.shear_modulus_pa,
        poisson_ratio: m.poisson_ratio,
    }
}

/// A repeated field's values, None when empty.
fn values(v: &[f64]) -> Option<Vec<f64>> {
    (!v.is_empty()).then(|| v.to_vec())
}

fn points(p: &[pb::ProfilePoint]) -> Option<Vec<[f64; 2]>> {
    (!p.is_empty()).then(|| p.iter().map(|q| [q.y_m, q.z_m]).collect())
}

fn geometry(g: &pb::GeometrySection) -> Result<GeometrySection, ServiceError> {
    let kind =
        match pb::GeometryKind::try_from(g.kind) {
            Ok(pb::GeometryKind::Quadratic) => GeometryKind::Quadratic,
            Ok(pb::GeometryKind::ConformalCircular) => GeometryKind::ConformalCircular,
            Ok(pb::GeometryKind::ConformalPoints) => GeometryKind::ConformalPoints,
            Ok(pb::GeometryKind::Line) => GeometryKind::Line,
            _ => return Err(ServiceError::invalid(
                "geometry.kind",
                "missing: give GEOMETRY_KIND_QUADRATIC, _CONFORMAL_CIRCULAR, _CONFORMAL_POINTS or _LINE",
            )),
        };
    Ok(GeometrySection {
        kind,
        a_per_m: g.a_per_m,
        b_per_m: g.b_per_m,
        rail_lateral_radius_m: g.rail_lateral_radius_m,
        wheel_lateral_radius_m: g.wheel_lateral_radius_m,
        wheel_rolling_radius_m: g.wheel_rolling_radius_m,
        rail_points_m: points(&g.rail_points_m),
        wheel_points_m: points(&g.wheel_points_m),
        gap_m: values(&g.gap_m),
    })
}

/// The normal load of a wire load, `None` when not set (a force per metre
/// is a line contact's normal force: its totals are per metre).
pub fn load(l: Option<&pb::load_section::Load>) -> Option<NormalLoad> {
    l.map(|l| match *l {
        pb::load_section::Load::NormalForceN(f) => NormalLoad::NormalForce(f),
        pb::load_section::Load::NormalForceNPerM(f) => NormalLoad::NormalForce(f),
        pb::load_section::Load::ApproachM(d) => NormalLoad::Approach(d),
    })
}

/// The core creepages of wire creepages.
pub fn creepages(c: &pb::Creepages) -> Creepages {
    Creepages {
        creepage_long: c.creepage_long,
        creepage_lat: c.creepage_lat,
        spin_per_m: c.spin_per_m,
    }
}

/// The `[rolling]` section of wire creepages: a creepage or a prescribed
/// force per direction (`force_x_n`, `force_y_n`).
pub fn rolling(c: &pb::Creepages) -> RollingSection {
    RollingSection {
        creepage_long: (c.force_x_n.is_none() && c.force_x_n_per_m.is_none()
            || c.creepage_long != 0.0)
            .then_some(c.creepage_long),
        creepage_lat: (c.force_y_n.is_none() || c.creepage_lat != 0.0).then_some(c.creepage_lat),
        spin_per_m: c.spin_per_m,
        force_x_n: c.force_x_n,
        force_y_n: c.force_y_n,
        force_x_n_per_m: c.force_x_n_per_m,
    }
}

/// A request of something SolvePatch and SolvePatchBatch alone solve
/// (`thing`: "a prescribed force", "a line contact"), made in `what`
/// (sessions, creep curves), naming `key`.
fn solve_patch_only(key: impl Into<String>, thing: &str, what: &str, hint: &str) -> ServiceError {
    ServiceError::invalid(
        key,
        format!("{thing} is solved by SolvePatch and SolvePatchBatch only, not in {what}{hint}"),
    )
}

/// The hint of a refused prescribed force.
const GIVE_THE_CREEPAGE: &str = ": give the creepage";

/// Refuses a prescribed force in wire creepages `c` at field `key` (sessions
/// and creep curves: they step or sweep creepages).
pub fn no_prescribed_force(c: &pb::Creepages, key: &str, what: &str) -> Result<(), ServiceError> {
    for (name, f) in [
        ("force_x_n", c.force_x_n),
        ("force_y_n", c.force_y_n),
        ("force_x_n_per_m", c.force_x_n_per_m),
    ] {
        if f.is_some() {
            return Err(solve_patch_only(
                format!("{key}.{name}"),
                "a prescribed force",
                what,
                GIVE_THE_CREEPAGE,
            ));
        }
    }
    Ok(())
}

/// Refuses a case that SolvePatch and SolvePatchBatch alone solve, in
/// `what` (sessions and creep curves): a prescribed force, a line contact.
pub fn refuse_solve_patch_only(case: &Case, what: &str) -> Result<(), ServiceError> {
    let f = case.prescribed_force;
    let force_key = match (f.force_x_n, f.force_y_n) {
        (Some(_), _) if case.geometry.is_line() => Some("rolling.force_x_n_per_m"),
        (Some(_), _) => Some("rolling.force_x_n"),
        (None, Some(_)) => Some("rolling.force_y_n"),
        (None, None) => None,
    };
    if let Some(key) = force_key {
        return Err(solve_patch_only(
            key,
            "a prescribed force",
            what,
            GIVE_THE_CREEPAGE,
        ));
    }
    if case.geometry.is_line() {
        return Err(solve_patch_only(
            "geometry.kind",
            "a line contact",
            what,
            "",
        ));
    }
    Ok(())
}

/// The wire outcome of a prescribed-force solve.
pub fn force_control(f: &ForceControlReport) -> pb::ForceControl {
    pb::ForceControl {
        creepage_long: f.creepage_long,
        creepage_lat: f.creepage_lat,
        spin_per_m: f.spin_per_m,
        force_iterations: u32::try_from(f.force_iterations).unwrap_or(u32::MAX),
        force_solves: u32::try_from(f.force_solves).unwrap_or(u32::MAX),
    }
}

/// The wire creepages of core creepages.
pub fn wire_creepages(c: &Creepages) -> pb::Creepages {
    pb::Creepages {
        creepage_long: c.creepage_long,
        creepage_lat: c.creepage_lat,
        spin_per_m: c.spin_per_m,
        ..Default::default()
    }
}

/// The case file's step section of a wire step (`key` names it).
pub fn step_section(key: &str, s: &pb::ShiftStep) -> Result<StepSection, ServiceError> {
    Ok(StepSection {
        shift_x_m: s.shift_x_m,
        shift_y_m: s.shift_y_m,
        rotation_rad: s.rotation_rad,
        normal_force_n: s.normal_force_n,
        normal_force_n_per_m: s.normal_force_n_per_m,
        approach_m: s.approach_m,
        creepage_long: s.creepage_long,
        creepage_lat: s.creepage_lat,
        spin_per_m: s.spin_per_m,
        force_x_n: s.force_x_n,
        force_y_n: s.force_y_n,
        force_x_n_per_m: s.force_x_n_per_m,
        rolling_m: s.rolling_m,
        gap_travel_x_m: s.gap_travel_x_m,
        friction_start: slip_start(&format!("{key}.friction_start"), s.friction_start)?,
    })
}

/// A wire slip start named `key` (unspecified: None, the default).
fn slip_start(key: &str, v: i32) -> Result<Option<SlipStart>, ServiceError> {
    match pb::SlipStart::try_from(v) {
        Ok(pb::SlipStart::Unspecified) => Ok(None),
        Ok(pb::SlipStart::Previous) => Ok(Some(SlipStart::Previous)),
        Ok(pb::SlipStart::Sticking) => Ok(Some(SlipStart::Sticking)),
        Ok(pb::SlipStart::Sliding) => Ok(Some(SlipStart::Sliding)),
        Err(_) => Err(ServiceError::invalid(key, format!("unknown value {v}"))),
    }
}

/// The wire outcome of a transient step solved for a prescribed force.
pub fn step_force_control(f: &StepForceReport) -> pb::StepForceControl {
    pb::StepForceControl {
        shift_x_m: f.shift_x_m,
        shift_y_m: f.shift_y_m,
        rolling_m: f.rolling_m,
        creepage_long: f.creepage_long,
        creepage_lat: f.creepage_lat,
        force_iterations: u32::try_from(f.force_iterations).unwrap_or(u32::MAX),
        force_solves: u32::try_from(f.force_solves).unwrap_or(u32::MAX),
    }
}

/// The case file a wire case stands for (not yet validated).
pub fn case_file(c: &pb::PatchCase) -> Result<CaseFile, ServiceError> {
    let m = c
        .material
        .as_ref()
        .ok_or_else(|| ServiceError::invalid("material", "missing"))?;
    let g = c
        .geometry
        .as_ref()
        .ok_or_else(|| ServiceError::invalid("geometry", "missing"))?;
    let (mut normal_force_n, mut normal_force_n_per_m, mut approach_m) = (None, None, None);
    match c.load.as_ref().and_then(|l| l.load.as_ref()) {
        Some(&pb::load_section::Load::NormalForceN(f)) => normal_force_n = Some(f),
        Some(&pb::load_section::Load::NormalForceNPerM(f)) => normal_force_n_per_m = Some(f),
        Some(&pb::load_section::Load::ApproachM(d)) => approach_m = Some(d),
        None => {}
    }
    let size = |n: Option<u32>| n.map(|n| n as usize);
    Ok(CaseFile {
        model: model(c.model)?,
        material: MaterialSection {
            shear_modulus_pa: m.shear_modulus_pa,
            poisson_ratio: m.poisson_ratio,
            body1: m.body1.as_ref().map(material),
            body2: m.body2.as_ref().map(material),
            influence_file: None,
        },
        friction: c.friction.as_ref().map(friction_section).transpose()?,
        geometry: geometry(g)?,
        load: LoadSection {
            normal_force_n,
            normal_force_n_per_m,
            approach_m,
        },
        rolling: match &c.kinematics {
            Some(pb::patch_case::Kinematics::Rolling(r)) => Some(rolling(r)),
            _ => None,
        },
        transient: match &c.kinematics {
            Some(pb::patch_case::Kinematics::Transient(t)) => Some(TransientSection {
                rolling_step_m: t.rolling_step_m,
                steady_start: t.steady_start.as_ref().map(|s| Creepages {
                    creepage_long: s.creepage_long,
                    creepage_lat: s.creepage_lat,
                    spin_per_m: s.spin_per_m,
                }),
                steps: t
                    .steps
                    .iter()
                    .enumerate()
                    .map(|(k, s)| step_section(&format!("transient.steps[{k}]"), s))
                    .collect::<Result<_, _>>()?,
            }),
            _ => None,
        },
        grid: c.grid.as_ref().map(|g| GridSection {
            nx: size(g.nx),
            ny: size(g.ny),
            window_x_m: g.window_x_m,
            window_y_m: g.window_y_m,
        }),
        solver: c.solver.as_ref().map(|s| SolverSection {
            normal_tolerance: s.normal_tolerance,
            tangential_tolerance: s.tangential_tolerance,
            max_iterations: size(s.max_iterations),
            coupling_tolerance: s.coupling_tolerance,
            coupling_max_iterations: size(s.coupling_max_iterations),
        }),
        subsurface: c.subsurface.as_ref().map(|s| SubsurfaceSection {
            depths_m: (!s.depths_m.is_empty()).then(|| s.depths_m.clone()),
            max_depth_m: s.max_depth_m,
            depth_count: size(s.depth_count),
            shear_yield_stress_pa: s.shear_yield_stress_pa,
        }),
        temperature: c.temperature.as_ref().map(thermal_input).transpose()?,
        rolling_direction_rad: c.rolling_direction_rad,
        extra_rigid_slip: c.extra_rigid_slip.as_ref().map(|e| ExtraRigidSlipSection {
            slip_x: values(&e.slip_x),
            slip_y: values(&e.slip_y),
            shift_x_m: values(&e.shift_x_m),
            shift_y_m: values(&e.shift_y_m),
        }),
        conformal: c
            .conformal
            .as_ref()
            .map(|s| {
                Ok::<_, ServiceError>(ConformalSection {
                    rigid_slip: rigid_slip(s.rigid_slip)?,
                })
            })
            .transpose()?,
        interfacial_layer: c.interfacial_layer.as_ref().map(|l| InterfacialLayer {
            thickness_m: l.thickness_m,
            shear_modulus_pa: l.shear_modulus_pa,
            yield_limit_pa: l.yield_limit_pa,
            hardening_pa_per_m: l.hardening_pa_per_m,
        }),
        viscoelastic: c.viscoelastic.as_ref().map(|v| {
            let body = |b: &Option<pb::ViscoelasticBody>| {
                b.as_ref().map_or_else(Sls::default, |b| Sls {
                    relaxation_ratio: b.relaxation_ratio,
                    creep_relaxation_time_s: b.creep_relaxation_time_s,
                })
            };
            Viscoelastic {
                rolling_speed_m_per_s: v.rolling_speed_m_per_s,
                body1: body(&v.body1),
                body2: body(&v.body2),
            }
        }),
        fastsim: c.fastsim.as_ref().map(fastsim_section).transpose()?,
    })
}

/// The case file's `[fastsim]` of a wire section (the values are checked
/// with the case).
pub fn fastsim_section(f: &pb::FastsimSection) -> Result<FastsimSection, ServiceError> {
    let unknown = |key: &str, v: i32| ServiceError::invalid(key, format!("unknown value {v}"));
    let method = match pb::FastsimMethod::try_from(f.method) {
        Ok(pb::FastsimMethod::Unspecified) => None,
        Ok(pb::FastsimMethod::Fastsim) => Some(FastsimMethod::Fastsim),
        Ok(pb::FastsimMethod::Fastrip) => Some(FastsimMethod::Fastrip),
        Err(_) => return Err(unknown("fastsim.method", f.method)),
    };
    let discretisation = match pb::FastsimDiscretisation::try_from(f.discretisation) {
        Ok(pb::FastsimDiscretisation::Unspecified) => None,
        Ok(pb::FastsimDiscretisation::Strips) => Some(FastsimDiscretisation::Strips),
        Ok(pb::FastsimDiscretisation::Grid) => Some(FastsimDiscretisation::Grid),
        Err(_) => return Err(unknown("fastsim.discretisation", f.discretisation)),
    };
    let traction_bound = match pb::FastsimTractionBound::try_from(f.traction_bound) {
        Ok(pb::FastsimTractionBound::Unspecified) => None,
        Ok(pb::FastsimTractionBound::Parabolic) => Some(TractionBoundName::Parabolic),
        Ok(pb::FastsimTractionBound::Elliptic) => Some(TractionBoundName::Elliptic),
        Err(_) => return Err(unknown("fastsim.traction_bound", f.traction_bound)),
    };
    Ok(FastsimSection {
        method,
        discretisation,
        traction_bound,
        initial_factor: f.initial_factor,
        limit_ratio: f.limit_ratio,
        transition_rate: f.transition_rate,
        friction_limit_ratio: f.friction_limit_ratio,
        friction_decay_s_per_m: f.friction_decay_s_per_m,
        rolling_speed_m_per_s: f.rolling_speed_m_per_s,
        flexibility_m_per_pa: f.flexibility_m_per_pa,
        window_scale: f.window_scale,
    })
}

/// The case's `[temperature]` of a wire section (both bodies required;
/// the values are checked by the caller).
pub fn thermal_input(t: &pb::TemperatureSection) -> Result<ThermalInput, ServiceError> {
    let body = |key: &str, b: &Option<pb::ThermalBody>| {
        b.as_ref()
            .map(|b| ThermalBody {
                bulk_temperature_k: b.bulk_temperature_k,
                conductivity_w_per_m_k: b.conductivity_w_per_m_k,
                density_kg_per_m3: b.density_kg_per_m3,
                specific_heat_j_per_kg_k: b.specific_heat_j_per_kg_k,
            })
            .ok_or_else(|| {
                ServiceError::invalid(
                    format!("temperature.{key}"),
                    "missing: give the body's bulk temperature, conductivity, density and specific heat",
                )
            })
    };
    Ok(ThermalInput {
        body1: body("body1", &t.body1)?,
        body2: body("body2", &t.body2)?,
        rolling_speed_m_per_s: t.rolling_speed_m_per_s,
    })
}

/// The wire form of the flash temperatures: their peaks, and the fields
/// with `fields`.
pub fn temperature_result(t: &SurfaceTemperatures, fields: bool) -> pb::TemperatureResult {
    let peak = |p: TemperaturePeak| pb::TemperaturePeak {
        temperature_k: p.temperature_k,
        x_m: p.x_m,
        y_m: p.y_m,
    };
    let f = |v: &Vec<f64>| if fields { v.clone() } else { Vec::new() };
    let s = &t.summary;
    pb::TemperatureResult {
        max_body1: Some(peak(s.max_body1)),
        max_body2: Some(peak(s.max_body2)),
        contact_temperature_k: s.contact_temperature_k,
        heat_share_body1: s.heat_share_body1,
        frictional_power_w: s.frictional_power_w,
        peclet_number: s.peclet_number,
        body1_k: f(&t.body1_k),
        body2_k: f(&t.body2_k),
        heat_flux_w_per_m2: f(&t.heat_flux_w_per_m2),
    }
}

/// The wire form of both bodies' subsurface fields: their peaks, and the
/// fields with `fields`.
pub fn subsurface_result(
    grid: &Grid,
    bodies: &[BodySubsurface; 2],
    surface_fatigue_index: Option<f64>,
    fields: bool,
) -> pb::SubsurfaceResult {
    let peak = |p: FieldPeak| pb::StressPeak {
        value_pa: p.value_pa,
        x_m: p.x_m,
        y_m: p.y_m,
        depth_m: p.depth_m,
    };
    let body = |b: &BodySubsurface| {
        let s = b.summary(grid);
        let f = |v: &Vec<f64>| if fields { v.clone() } else { Vec::new() };
        let [xx, yy, nn, xy, xn, yn] = &b.stress_pa;
        let [ux, uy, un] = &b.displacement_m;
        pb::BodySubsurface {
            max_von_mises: Some(peak(s.max_von_mises)),
            max_shear: Some(peak(s.max_shear)),
            max_principal: Some(peak(s.max_principal)),
            min_principal: Some(peak(s.min_principal)),
            sigma_xx_pa: f(xx),
            sigma_yy_pa: f(yy),
            sigma_nn_pa: f(nn),
            sigma_xy_pa: f(xy),
            sigma_xn_pa: f(xn),
            sigma_yn_pa: f(yn),
            ux_m: f(ux),
            uy_m: f(uy),
            un_m: f(un),
        }
    };
    pb::SubsurfaceResult {
        depths_m: bodies[0].depths_m.clone(),
        body1: Some(body(&bodies[0])),
        body2: Some(body(&bodies[1])),
        surface_fatigue_index,
    }
}

/// The wire field of numerical influence coefficients (the case files'
/// `material.influence_file`, [`NUMERICAL_INFLUENCE_KEY`], sent as text).
pub const INFLUENCE_CONTENT_FIELD: &str = "material.influence_file_content";

/// Whether a wire case carries numerical influence coefficients
/// (`material.influence_file_content`), whose parse is the costly part of
/// its validation.
pub fn carries_influence_content(c: &pb::PatchCase) -> bool {
    c.material
        .as_ref()
        .is_some_and(|m| m.influence_file_content.is_some())
}

/// The numerical influence coefficients of a wire case (None: the
/// half-space's): its `material.influence_file_content` read by the case
/// files' reader ([`InfluenceFile::parse`]), at most [`MAX_FILE_BYTES`] of
/// text as a file. Errors name the field, and the text's line and field.
fn influence_table(c: &pb::PatchCase) -> Result<Option<Arc<InfluenceFile>>, ServiceError> {
    let Some(text) = c
        .material
        .as_ref()
        .and_then(|m| m.influence_file_content.as_deref())
    else {
        return Ok(None);
    };
    if text.len() as u64 > MAX_FILE_BYTES {
        return Err(ServiceError::invalid(
            INFLUENCE_CONTENT_FIELD,
            format!(
                "has {} bytes, more than {MAX_FILE_BYTES} (a file of influence coefficients)",
                text.len()
            ),
        ));
    }
    InfluenceFile::parse(text)
        .map(|t| Some(Arc::new(t)))
        .map_err(|e| ServiceError::invalid(INFLUENCE_CONTENT_FIELD, e.to_string()))
}

/// `text` with the case files' key of the influence coefficients
/// (`material.influence_file`, alone or followed by `: ` and the file's
/// field) replaced by the wire's field, when it starts with it.
fn wire_influence_key(text: &str) -> Option<String> {
    let rest = text.strip_prefix(NUMERICAL_INFLUENCE_KEY)?;
    (rest.is_empty() || rest.starts_with(": ")).then(|| format!("{INFLUENCE_CONTENT_FIELD}{rest}"))
}

/// A case error that names the case files' key of the influence
/// coefficients named by the wire's field instead (the file's field, as
/// `dxfile`, goes into the reason).
fn on_the_wire(e: ServiceError) -> ServiceError {
    match e {
        ServiceError::Invalid { field, reason } => match wire_influence_key(&field) {
            Some(wire) => match wire.split_once(": ") {
                Some((key, file_field)) => {
                    ServiceError::invalid(key, format!("{file_field}: {reason}"))
                }
                None => ServiceError::invalid(wire, reason),
            },
            None => ServiceError::Invalid { field, reason },
        },
        e => e,
    }
}

/// Validates a wire case: the case file's rules, the server's grid limit
/// and the extra gap. Field paths are relative to the case.
pub fn validate_case(c: &pb::PatchCase, limits: CaseLimits) -> Result<ValidCase, ServiceError> {
    let file = case_file(c)?;
    let mut case = match influence_table(c)? {
        Some(table) => Case::from_file_with_influence(file, table)
            .map_err(|e| on_the_wire(ServiceError::from(e)))?,
        None => Case::from_file(file)?,
    };
    for note in &mut case.notes {
        if let Some(wire) = wire_influence_key(note) {
            *note = wire;
        }
    }
    let elements = case.nx * case.ny;
    if elements > limits.max_grid_elements {
        return Err(ServiceError::invalid(
            "grid.nx",
            format!(
                "the grid has {} x {} = {elements} elements, more than this server's limit of {}",
                case.nx, case.ny, limits.max_grid_elements
            ),
        ));
    }
    let extra = c
        .geometry
        .as_ref()
        .map(|g| g.extra_gap_m.clone())
        .unwrap_or_default();
    if !extra.is_empty() {
        let key = "geometry.extra_gap_m";
        if case.gap_m.is_some() {
            return Err(ServiceError::invalid(
                key,
                "give either geometry.gap_m (the whole gap) or geometry.extra_gap_m (an addition), not both",
            ));
        }
        if case.model != Model::Exact || case.geometry.is_conformal() || case.geometry.is_line() {
            return Err(ServiceError::invalid(
                key,
                "only the exact model on a quadratic geometry takes a per-element gap",
            ));
        }
        let given = c
            .grid
            .as_ref()
            .is_some_and(|g| g.nx.is_some() && g.ny.is_some());
        if !given {
            return Err(ServiceError::invalid(
                key,
                "give grid.nx and grid.ny with a per-element gap",
            ));
        }
        if extra.len() != elements {
            return Err(ServiceError::invalid(
                key,
                format!(
                    "has {} values for a grid of {} x {} = {elements} elements",
                    extra.len(),
                    case.nx,
                    case.ny
                ),
            ));
        }
        for (i, &v) in extra.iter().enumerate() {
            ranges::EXTRA_GAP.check(&format!("{key}[{i}]"), v)?;
        }
    }
    Ok(ValidCase {
        case,
        extra_gap_m: extra,
    })
}

/// Refuses `include_fields` for models without per-element fields (all but
/// exact, cect and cect_halfspace).
pub fn check_fields(case: &Case, fields: bool) -> Result<(), ServiceError> {
    if fields && !(case.model == Model::Exact || case.model.is_cect()) {
        return Err(ServiceError::invalid(
            "include_fields",
            format!(
                "per-element fields come from the exact, cect and cect_halfspace models, not {}",
                case.model.name()
            ),
        ));
    }
    Ok(())
}

/// The wire grid.
pub fn grid_info(g: &Grid) -> pb::GridInfo {
    pb::GridInfo {
        nx: g.nx as u32,
        ny: g.ny as u32,
        element_size_x_m: g.dx_m,
        element_size_y_m: g.dy_m,
        x0_m: g.x0_m,
        y0_m: g.y0_m,
    }
}

fn totals(t: &Totals) -> pb::PatchTotals {
    pb::PatchTotals {
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
    }
}

fn status(s: SolveStatus) -> i32 {
    match s {
        SolveStatus::Converged => pb::SolveStatus::Converged as i32,
        SolveStatus::MaxIterations => pb::SolveStatus::MaxIterations as i32,
    }
}

fn conformal(c: &ConformalKeys) -> pb::ConformalTotals {
    pb::ConformalTotals {
        contact_angle_variation_deg: c.contact_angle_variation_deg,
        length_width_ratio: c.length_width_ratio,
        normal_force_from_tractions_n: c.normal_force_from_tractions_n,
        pressure_resultant_n: c.pressure_resultant_n,
        fy_global_n: c.fy_global_n,
        fz_global_n: c.fz_global_n,
    }
}

/// The wire result of one exact-model solution: the report's figures and
/// the core's counters that the report does not carry.
pub fn step_of_solution(s: &ContactSolution) -> pb::StepResult {
    let mut step = step_of_report(&StepReport::from_solution(s));
    if let Some(info) = step.info.as_mut() {
        info.coupling_iterations = s.info.coupling_iterations as u64;
        info.matvecs = s.info.matvecs as u64;
        info.normal_residual = s.info.normal_residual;
        info.tangential_residual = s.info.tangential_residual;
    }
    step
}

/// The wire form of a force Jacobian.
pub fn sensitivities(j: &ForceJacobian) -> pb::Sensitivities {
    let [a, l, t, s] = j.columns().map(|c| {
        Some(pb::ForceDerivatives {
            normal_force: c[0],
            fx: c[1],
            fy: c[2],
            mz: c[3],
        })
    });
    pb::Sensitivities {
        per_approach_m: a,
        per_creepage_long: l,
        per_creepage_lat: t,
        per_spin_per_m: s,
        solves: j.solves as u32,
    }
}

/// The wire result of one step of a CLI report.
pub fn step_of_report(r: &StepReport) -> pb::StepResult {
    pb::StepResult {
        totals: Some(totals(&r.totals)),
        info: Some(pb::SolverInfo {
            status: status(r.status),
            normal_iterations: r.normal_iterations as u64,
            tangential_iterations: r.tangential_iterations as u64,
            coupling_iterations: r.conformal.and_then(|c| c.coupling_iterations).unwrap_or(0)
                as u64,
            solve_time_s: r.solve_time_s,
            ..Default::default()
        }),
        conformal: r.conformal.as_ref().map(conformal),
        sensitivities: None,
        force_control: r.force_control.as_ref().map(step_force_control),
    }
}

fn element_state(s: &ElementState) -> i32 {
    match s {
        ElementState::Exterior => pb::ElementState::Exterior as i32,
        ElementState::Adhesion => pb::ElementState::Adhesion as i32,
        ElementState::Slip => pb::ElementState::Slip as i32,
    }
}

/// The wire fields of a planar (exact) solution.
pub fn planar_fields(f: &ElementFields) -> pb::ElementFields {
    pb::ElementFields {
        pressure_pa: f.pressure_pa.clone(),
        traction_x_pa: f.traction_x_pa.clone(),
        traction_y_pa: f.traction_y_pa.clone(),
        slip_x: f.slip_x.clone(),
        slip_y: f.slip_y.clone(),
        state: f.state.iter().map(element_state).collect(),
        gap_m: f.gap_m.clone(),
        ..Default::default()
    }
}

fn conformal_fields(f: &ConformalFieldsReport<'_>) -> pb::ElementFields {
    pb::ElementFields {
        pressure_pa: f.pressure_pa.to_vec(),
        traction_x_pa: f.traction_x_pa.to_vec(),
        traction_y_pa: f.traction_s_pa.to_vec(),
        slip_x: f.slip_x.to_vec(),
        slip_y: f.slip_s.to_vec(),
        state: f.state.iter().map(element_state).collect(),
        gap_m: f.gap_m.to_vec(),
        delta_rad: f.delta_rad.to_vec(),
        reference_points_m: f
            .reference_yz_m
            .iter()
            .map(|p| pb::ProfilePoint {
                y_m: p[0],
                z_m: p[1],
            })
            .collect(),
        wfric_lateral_j_per_m2: Vec::new(),
        ..Default::default()
    }
}

/// Adds an elasto-plastic interfacial layer's fields to the wire fields.
pub fn add_layer_fields(f: &mut pb::ElementFields, layer: &LayerFields) {
    f.layer_yield_limit_pa = layer.yield_limit_pa.clone();
    f.layer_plastic_x_m = layer.plastic_x_m.clone();
    f.layer_plastic_y_m = layer.plastic_y_m.clone();
    f.layer_plastic = layer.plastic.clone();
}

/// The wire result of a CLI report (models hertz, hertz_corrected,
/// fastsim, cect, cect_halfspace). Steps are sent for multi-step cases.
pub fn result_of_report(r: &Report<'_>) -> pb::PatchResult {
    let grid = match &r.fields {
        Some(Fields::Conformal(f)) => Some(grid_info(f.grid)),
        Some(Fields::Planar(f)) => Some(grid_info(f.grid)),
        None => None,
    };
    let mut fields = r.fields.as_ref().map(|f| match f {
        Fields::Planar(p) => planar_fields(p.fields),
        Fields::Conformal(c) => conformal_fields(c),
    });
    if let (Some(f), Some(l)) = (
        fields.as_mut(),
        r.interfacial_layer.as_ref().and_then(|l| l.fields),
    ) {
        add_layer_fields(f, l);
    }
    if let (Some(f), Some(w)) = (fields.as_mut(), &r.wfric_lateral) {
        f.wfric_lateral_j_per_m2 = w.w_j_per_m2.clone();
    }
    let steps = r.steps.as_deref().unwrap_or_default();
    pb::PatchResult {
        model: wire_model(r.model) as i32,
        result: Some(step_of_report(&r.totals)),
        steps: if steps.len() > 1 {
            steps.iter().map(step_of_report).collect()
        } else {
            Vec::new()
        },
        friction_coefficient: r.friction_coefficient,
        grid,
        notes: r.notes.clone(),
        fields,
        force_control: r.force_control.as_ref().map(force_control),
        steady_start: r.steady_start.as_ref().map(step_of_report),
        subsurface: None,
        temperature: None,
        fastsim_max_pressure_pa: r.fastsim_max_pressure_pa,
    }
}

/// Every value of a wire totals message with its field name, in field
/// order.
pub fn named_totals(t: &pb::PatchTotals) -> [(&'static str, f64); 13] {
    [
        ("normal_force_n", t.normal_force_n),
        ("fx_n", t.fx_n),
        ("fy_n", t.fy_n),
        ("mz_nm", t.mz_nm),
        ("approach_m", t.approach_m),
        ("max_pressure_pa", t.max_pressure_pa),
        ("max_traction_pa", t.max_traction_pa),
        ("contact_area_m2", t.contact_area_m2),
        ("patch_length_m", t.patch_length_m),
        ("patch_width_m", t.patch_width_m),
        ("adhesion_fraction", t.adhesion_fraction),
        ("tgamma_n", t.tgamma_n),
        ("frictional_work_j", t.frictional_work_j),
    ]
}

/// Every value of a wire totals message, in field order.
pub fn total_values(t: &pb::PatchTotals) -> [f64; 13] {
    named_totals(t).map(|(_, v)| v)
}

/// The first value of `values` (named, in a message at `path`) that is
/// not finite, as the error that names it.
pub fn finite_values<'a>(
    path: &str,
    values: impl IntoIterator<Item = (&'a str, f64)>,
) -> Result<(), ServiceError> {
    match values.into_iter().find(|(_, v)| !v.is_finite()) {
        None => Ok(()),
        Some((name, v)) => Err(ServiceError::NonFinite {
            output: if path.is_empty() {
                name.to_string()
            } else {
                format!("{path}.{name}")
            },
            value: v.to_string(),
        }),
    }
}

/// The first non-finite value of a repeated field at `path`.
fn finite_list(path: &str, values: &[f64]) -> Result<(), ServiceError> {
    match values.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(i) => Err(ServiceError::NonFinite {
            output: format!("{path}[{i}]"),
            value: values[i].to_string(),
        }),
    }
}

fn finite_step(path: &str, s: &pb::StepResult) -> Result<(), ServiceError> {
    if let Some(t) = &s.totals {
        finite_values(&format!("{path}.totals"), named_totals(t))?;
    }
    if let Some(i) = &s.info {
        finite_values(
            &format!("{path}.info"),
            [
                ("normal_residual", i.normal_residual),
                ("tangential_residual", i.tangential_residual),
                ("solve_time_s", i.solve_time_s),
            ],
        )?;
    }
    if let Some(c) = &s.conformal {
        finite_values(
            &format!("{path}.conformal"),
            [
                ("contact_angle_variation_deg", c.contact_angle_variation_deg),
                ("length_width_ratio", c.length_width_ratio),
                (
                    "normal_force_from_tractions_n",
                    c.normal_force_from_tractions_n,
                ),
                ("pressure_resultant_n", c.pressure_resultant_n),
                ("fy_global_n", c.fy_global_n),
                ("fz_global_n", c.fz_global_n),
            ],
        )?;
    }
    if let Some(j) = &s.sensitivities {
        for (name, d) in [
            ("per_approach_m", j.per_approach_m),
            ("per_creepage_long", j.per_creepage_long),
            ("per_creepage_lat", j.per_creepage_lat),
            ("per_spin_per_m", j.per_spin_per_m),
        ] {
            if let Some(d) = d {
                finite_values(
                    &format!("{path}.sensitivities.{name}"),
                    [
                        ("normal_force", d.normal_force),
                        ("fx", d.fx),
                        ("fy", d.fy),
                        ("mz", d.mz),
                    ],
                )?;
            }
        }
    }
    Ok(())
}

/// Checks every number of `r`: a non-finite one is refused
/// ([`ServiceError::NonFinite`], naming it by its path in the result,
/// `steps[2].info.normal_residual`), never sent as a silent NaN or
/// infinity.
pub fn check_finite(r: &pb::PatchResult) -> Result<(), ServiceError> {
    if let Some(s) = &r.result {
        finite_step("result", s)?;
    }
    for (k, s) in r.steps.iter().enumerate() {
        finite_step(&format!("steps[{k}]"), s)?;
    }
    finite_values("", [("friction_coefficient", r.friction_coefficient)])?;
    if let Some(g) = &r.grid {
        finite_values(
            "grid",
            [
                ("element_size_x_m", g.element_size_x_m),
                ("element_size_y_m", g.element_size_y_m),
                ("x0_m", g.x0_m),
                ("y0_m", g.y0_m),
            ],
        )?;
    }
    if let Some(f) = &r.fields {
        check_fields_finite("fields", f)?;
    }
    if let Some(t) = &r.temperature {
        for (name, p) in [("max_body1", &t.max_body1), ("max_body2", &t.max_body2)] {
            if let Some(p) = p {
                finite_values(
                    &format!("temperature.{name}"),
                    [
                        ("temperature_k", p.temperature_k),
                        ("x_m", p.x_m),
                        ("y_m", p.y_m),
                    ],
                )?;
            }
        }
        finite_values(
            "temperature",
            [
                ("contact_temperature_k", t.contact_temperature_k),
                ("heat_share_body1", t.heat_share_body1),
                ("frictional_power_w", t.frictional_power_w),
                ("peclet_number", t.peclet_number),
            ],
        )?;
        for (name, v) in [
            ("body1_k", &t.body1_k),
            ("body2_k", &t.body2_k),
            ("heat_flux_w_per_m2", &t.heat_flux_w_per_m2),
        ] {
            finite_list(&format!("temperature.{name}"), v)?;
        }
    }
    Ok(())
}

/// Checks every value of per-element fields at `path`.
pub fn check_fields_finite(path: &str, f: &pb::ElementFields) -> Result<(), ServiceError> {
    for (name, v) in [
        ("pressure_pa", &f.pressure_pa),
        ("traction_x_pa", &f.traction_x_pa),
        ("traction_y_pa", &f.traction_y_pa),
        ("slip_x", &f.slip_x),
        ("slip_y", &f.slip_y),
        ("gap_m", &f.gap_m),
        ("delta_rad", &f.delta_rad),
        ("wfric_lateral_j_per_m2", &f.wfric_lateral_j_per_m2),
    ] {
        finite_list(&format!("{path}.{name}"), v)?;
    }
    Ok(())
}

/// The case file's `[friction]` of a wire friction section; keys
/// `friction.*`.
pub fn friction_section(f: &pb::FrictionSection) -> Result<FrictionSection, ServiceError> {
    let law = match pb::FrictionLaw::try_from(f.law) {
        Ok(pb::FrictionLaw::Unspecified | pb::FrictionLaw::Coulomb) => FrictionLawName::Coulomb,
        Ok(pb::FrictionLaw::Linear) => FrictionLawName::Linear,
        Ok(pb::FrictionLaw::Rational) => FrictionLawName::Rational,
        Ok(pb::FrictionLaw::Exponential) => FrictionLawName::Exponential,
        Err(_) => {
            return Err(ServiceError::invalid(
                "friction.law",
                format!("unknown value {}", f.law),
            ))
        }
    };
    let start = slip_start("friction.start", f.start)?;
    let list = |v: &[f64]| (!v.is_empty()).then(|| v.to_vec());
    Ok(FrictionSection {
        law,
        coefficient: f.coefficient,
        static_coefficient: f.static_coefficient,
        kinetic_coefficient: f.kinetic_coefficient,
        falling_coefficients: list(&f.falling_coefficients),
        half_velocities_m_per_s: list(&f.half_velocities_m_per_s),
        rolling_speed_m_per_s: f.rolling_speed_m_per_s,
        memory_distance_m: f.memory_distance_m,
        memory_velocity_m_per_s: f.memory_velocity_m_per_s,
        start,
        max_iterations: f.max_iterations.map(|n| n as usize),
        // The wire's table is its own message (wheel/rail `friction_table`).
        contact_angles_rad: None,
        rail_y_m: None,
        coefficients: None,
        track_s_m: None,
    })
}
