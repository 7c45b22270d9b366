//! `railcontact wheelrail CASE.toml [--json] [--plot FILE]`: a wheelset on
//! its track, from profile files, position, velocity and load, with every
//! contact patch of each wheel solved. Keys: see `examples/cases/README.md`.
//! Answers that no elastic contact gives, and forces inconsistent with the
//! kinematics given ([`check_plausibility`]), are said on stderr as
//! `warning: KEY: ...` lines naming the case file's key at fault, and in
//! the JSON's `warnings` array; the exit code stays 0.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use clap::Args;
use plotters::prelude::*;
use serde::{Deserialize, Serialize};

use crate::cli::plot::{panel_note, register_fonts, Format, Frame, FONT, SIZE};
use crate::cli::{plot_format, write_stdout, CliError};
use crate::conformal::geometry::RigidSlipSurface;
use crate::core::cache::KernelCache;
use crate::core::fastsim::SlopeReduction;
use crate::core::material::{CombinedMaterial, Material};
use crate::core::polach::PolachParameters;
use crate::core::problem::Friction;
use crate::problem::case::FrictionSection;
use crate::wheelrail::contact::{PitchControl, Timing, MIN_ELEMENTS_ACROSS};
use crate::wheelrail::ranges;
use crate::wheelrail::{
    builtin, check_plausibility, is_slices_file, is_wheel_slices_file, load_profile_with,
    load_slices, load_wheel_slices, solve_wheelset, FrictionTable, LengthUnit, LoadOptions,
    PatchResult, PlausibilityWarning, Profile, RailDeviation, RailMotion, RailPlacement,
    RailSlices, SearchScratch, Side, SplineOptions, TrackData, WheelLoad, WheelRailError,
    WheelRailInput, WheelRailModel, WheelRailPair, WheelRailSettings, WheelRailSolution,
    WheelRailThermal, WheelSlices, WheelsetData, WheelsetPosition, WheelsetVelocity,
    DEFAULT_SMOOTHING_WAVELENGTH_M,
};

/// Options of `railcontact wheelrail`.
#[derive(Debug, Args)]
pub struct WheelrailArgs {
    /// The case file (TOML).
    #[arg(value_name = "CASE.toml")]
    pub case: PathBuf,
    /// Print one JSON object (SI units) on stdout instead of the summary.
    #[arg(long)]
    pub json: bool,
    /// Write a plot of the profiles, contact points and lateral pressure
    /// distributions to FILE (.png or .svg).
    #[arg(long, value_name = "FILE")]
    pub plot: Option<PathBuf>,
}

/// The case file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct WheelrailCase {
    /// "exact" (default), "hertz_fastsim", "hertz_polach",
    /// "hertz_fastsim_elliptic", "hertz_strip", "hertz_fastsim_modified",
    /// "kik_piotrowski", "cect" or "auto".
    #[serde(default = "default_model")]
    model: String,
    /// "both" (default), "left" or "right".
    #[serde(default = "default_side")]
    side: String,
    #[serde(default)]
    material: MaterialKeys,
    /// `[friction]`: the patch cases' keys (Coulomb, or a falling law for
    /// the exact model, its rolling speed optional: each patch rolls at its
    /// own), or a friction table over the rail profile. Default: Coulomb
    /// 0.3.
    friction: Option<FrictionSection>,
    track: TrackKeys,
    wheelset: WheelsetKeys,
    #[serde(default)]
    position: PositionKeys,
    velocity: VelocityKeys,
    load: LoadKeys,
    #[serde(default)]
    grid: GridKeys,
    /// Model hertz_polach: its parameters (default: Polach's 1999 model).
    polach: Option<PolachKeys>,
    /// Model hertz_fastsim_modified: its slope reduction and falling
    /// friction (default: [`SlopeReduction::TRACTCURV`]).
    modified_fastsim: Option<ModifiedFastsimKeys>,
    /// Models cect and auto: options of the conformal method.
    conformal: Option<ConformalKeys>,
    /// `[temperature.rail]` and `[temperature.wheel]`: flash temperatures
    /// per patch (models exact, cect, auto; each patch rolls at its own
    /// speed).
    temperature: Option<WheelRailThermal>,
}

/// `[conformal]`: the conformal method's rigid slip (models cect, auto).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ConformalKeys {
    /// "actual_surface" (default) or "reference_section".
    #[serde(default)]
    rigid_slip: RigidSlipSurface,
}

/// `[polach]`: every key required when the section is given.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct PolachKeys {
    k_adhesion: f64,
    k_slip: f64,
    limit_ratio: f64,
    decay_s_per_m: f64,
}

/// `[modified_fastsim]`: each key defaults to
/// [`SlopeReduction::TRACTCURV`]'s value.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields, default)]
struct ModifiedFastsimKeys {
    initial_factor: f64,
    limit_ratio: f64,
    transition_rate: f64,
    friction_limit_ratio: f64,
    friction_decay_s_per_m: f64,
}

impl Default for ModifiedFastsimKeys {
    fn default() -> Self {
        let r = SlopeReduction::TRACTCURV;
        Self {
            initial_factor: r.initial_factor,
            limit_ratio: r.limit_ratio,
            transition_rate: r.transition_rate,
            friction_limit_ratio: r.friction_limit_ratio,
            friction_decay_s_per_m: r.friction_decay_s_per_m,
        }
    }
}

fn default_model() -> String {
    "exact".into()
}

fn default_side() -> String {
    "both".into()
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct MaterialKeys {
    shear_modulus_pa: f64,
    poisson_ratio: f64,
}

impl Default for MaterialKeys {
    fn default() -> Self {
        Self {
            shear_modulus_pa: 82.0e9,
            poisson_ratio: 0.28,
        }
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct TrackKeys {
    rail_profile: String,
    rail_profile_left: Option<String>,
    #[serde(default)]
    rail_mirror_y: bool,
    gauge_m: Option<f64>,
    gauge_height_m: Option<f64>,
    rail_origin_y_m: Option<f64>,
    rail_origin_z_m: Option<f64>,
    #[serde(default)]
    cant_rad: f64,
    roller_radius_m: Option<f64>,
    roller_rad_per_s: Option<f64>,
    #[serde(default)]
    curvature_per_m: f64,
    rail_profile_unit: Option<LengthUnit>,
    #[serde(default)]
    rail_deviation_left: RailDeviation,
    #[serde(default)]
    rail_deviation_right: RailDeviation,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct WheelsetKeys {
    wheel_profile: String,
    wheel_profile_left: Option<String>,
    #[serde(default)]
    wheel_mirror_y: bool,
    flange_back_distance_m: f64,
    flange_back_y_m: Option<f64>,
    nominal_radius_m: f64,
    smoothing_wavelength_m: Option<f64>,
    wheel_profile_unit: Option<LengthUnit>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct PositionKeys {
    #[serde(default)]
    lateral_m: f64,
    #[serde(default)]
    yaw_rad: f64,
    roll_rad: Option<f64>,
    #[serde(default)]
    track_s_m: f64,
    #[serde(default)]
    pitch_rad: f64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct VelocityKeys {
    forward_m_per_s: Option<f64>,
    #[serde(default)]
    lateral_m_per_s: f64,
    #[serde(default)]
    vertical_m_per_s: f64,
    #[serde(default)]
    roll_rad_per_s: f64,
    #[serde(default)]
    yaw_rad_per_s: f64,
    pitch_rad_per_s: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct LoadKeys {
    vertical_force_n: Option<f64>,
    approach_m: Option<f64>,
    center_z_m: Option<f64>,
    total_longitudinal_force_n: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields, default)]
struct GridKeys {
    element_size_m: f64,
    min_elements_across: usize,
    force_tolerance_of_wheel_load: Option<f64>,
}

impl Default for GridKeys {
    fn default() -> Self {
        Self {
            element_size_m: 2.0e-4,
            min_elements_across: MIN_ELEMENTS_ACROSS,
            force_tolerance_of_wheel_load: None,
        }
    }
}

fn bad(m: impl Into<String>) -> CliError {
    CliError::BadInput(m.into())
}

impl From<WheelRailError> for CliError {
    fn from(e: WheelRailError) -> Self {
        match e {
            WheelRailError::Invalid { .. }
            | WheelRailError::Spline { .. }
            | WheelRailError::Geometry { .. }
            | WheelRailError::LoadNotCarried { .. } => CliError::BadInput(e.to_string()),
            WheelRailError::Contact { .. } | WheelRailError::Cancelled => {
                CliError::Failure(e.to_string())
            }
        }
    }
}

/// Reads `name` (a path relative to `dir`, or `builtin:NAME`).
fn read_profile(
    name: &str,
    dir: &Path,
    options: &LoadOptions,
    key: &str,
) -> Result<Profile, CliError> {
    let result = match name.strip_prefix(builtin::PREFIX) {
        Some(b) => builtin::profile(b, options).ok_or_else(|| {
            let names: Vec<&str> = builtin::FILES.iter().map(|(n, _)| *n).collect();
            bad(format!(
                "invalid input `{key}`: no built-in profile '{b}' (there are: {})",
                names.join(", ")
            ))
        })?,
        None => load_profile_with(dir.join(name), options),
    };
    result.map_err(|e| bad(format!("invalid input `{key}`: {e}")))
}

/// How a side's profile files are read: mirrored in y or not, plain
/// tables in `unit` (`track.rail_profile_unit`,
/// `wheelset.wheel_profile_unit`; unset: the file's own unit line or
/// column names, else metres), the same for a slices file's tables.
fn profile_options(mirror_y: bool, unit: Option<LengthUnit>) -> LoadOptions {
    LoadOptions {
        mirror_y,
        plain_unit: unit,
        ..LoadOptions::default()
    }
}

/// Reads the rail profile `name` as [`read_profile`] does; a rail slices
/// file (`.slcs`, a rail varying along the track) gives its profile at
/// the wheelset's position `track_s_m` and the slices themselves.
fn read_rail(
    name: &str,
    dir: &Path,
    options: &LoadOptions,
    key: &str,
    track_s_m: f64,
) -> Result<(Profile, Option<Arc<RailSlices>>), CliError> {
    if !is_slices_file(name) {
        return Ok((read_profile(name, dir, options, key)?, None));
    }
    let slices = load_slices(dir.join(name), options)
        .map_err(|e| bad(format!("invalid input `{key}`: {e}")))?;
    let profile = slices
        .profile_at(track_s_m)
        .map_err(|e| bad(format!("invalid input `position.track_s_m`: {e}")))?;
    Ok((profile, Some(slices)))
}

/// Reads the wheel profile `name` as [`read_profile`] does; a wheel slices
/// file (`.slcw`, an out-of-round wheel) gives its profile facing the
/// rail at the wheelset's pitch angle `pitch_rad` on a wheelset of
/// `nominal_radius_m` (`WheelSlices::profile_facing_rail`) and the slices
/// themselves.
fn read_wheel(
    name: &str,
    dir: &Path,
    options: &LoadOptions,
    key: &str,
    pitch_rad: f64,
    nominal_radius_m: f64,
) -> Result<(Profile, Option<Arc<WheelSlices>>), CliError> {
    if !is_wheel_slices_file(name) {
        return Ok((read_profile(name, dir, options, key)?, None));
    }
    if !pitch_rad.is_finite() {
        return Err(bad(format!(
            "invalid input `position.pitch_rad`: must be finite, got {pitch_rad}"
        )));
    }
    let slices = load_wheel_slices(dir.join(name), options)
        .map_err(|e| bad(format!("invalid input `{key}`: {e}")))?;
    let profile = slices
        .profile_facing_rail(pitch_rad, nominal_radius_m)
        .map_err(|e| bad(format!("invalid input `{key}`: {e}")))?;
    Ok((profile, Some(slices)))
}

/// The friction of a wheel/rail case's `[friction]` (Coulomb 0.3 without
/// one), or its table.
fn wheelrail_friction(
    section: Option<FrictionSection>,
) -> Result<(Friction, Option<FrictionTable>), CliError> {
    let Some(f) = section else {
        return Ok((Friction::coulomb(0.3), None));
    };
    if let Some(table) = f.table()? {
        // The table's coefficients scale the section's law.
        return Ok((f.table_law()?, Some(table)));
    }
    Ok((f.wheelrail_friction()?, None))
}

/// A parsed and checked case: the pair and the solver input.
pub struct WheelrailRun {
    pair: WheelRailPair,
    input: WheelRailInput,
    model: &'static str,
}

impl WheelrailRun {
    /// The placed profile pair.
    pub fn pair(&self) -> &WheelRailPair {
        &self.pair
    }

    /// The solver input.
    pub fn input(&self) -> &WheelRailInput {
        &self.input
    }

    /// Parses `text` (TOML); profile paths are relative to `dir`.
    pub fn from_toml(text: &str, dir: &Path) -> Result<Self, CliError> {
        let c: WheelrailCase = toml::from_str(text).map_err(|e| bad(e.to_string()))?;
        // Names in any case, as the Python client takes them.
        let model = WheelRailModel::from_name(&c.model).ok_or_else(|| {
            let names: Vec<String> = WheelRailModel::ALL
                .iter()
                .map(|m| format!("\"{}\"", m.name()))
                .collect();
            bad(format!(
                "invalid input `model`: \"{}\"; expected one of {}",
                c.model.to_ascii_lowercase(),
                names.join(", ")
            ))
        })?;
        let model_name = model.name();
        if c.conformal.is_some() && !matches!(model, WheelRailModel::Cect | WheelRailModel::Auto) {
            return Err(bad(format!(
                "invalid input `conformal`: options of the conformal method, models \"cect\" \
                 and \"auto\", not \"{model_name}\""
            )));
        }
        let sides = match c.side.to_ascii_lowercase().as_str() {
            "both" => Side::BOTH.to_vec(),
            "left" => vec![Side::Left],
            "right" => vec![Side::Right],
            other => {
                return Err(bad(format!(
                    "invalid input `side`: \"{other}\"; expected \"both\", \"left\" or \"right\""
                )))
            }
        };
        let l = &c.load;
        let load =
            match (l.vertical_force_n, l.approach_m, l.center_z_m) {
                (Some(f), None, None) => WheelLoad::VerticalForce(f),
                (None, Some(d), None) => WheelLoad::Approach(d),
                (None, None, Some(z)) => WheelLoad::CenterHeight(z),
                _ => return Err(bad(
                    "invalid input `load`: give exactly one of vertical_force_n, approach_m and \
                     center_z_m",
                )),
            };
        let t = &c.track;
        let w = &c.wheelset;
        let placement = match (
            t.gauge_m,
            t.gauge_height_m,
            t.rail_origin_y_m,
            t.rail_origin_z_m,
        ) {
            (Some(gauge_m), Some(gauge_height_m), None, None) => RailPlacement::GaugePoint {
                gauge_m,
                gauge_height_m,
            },
            (None, None, Some(q_m), Some(z_m)) => RailPlacement::Origin { q_m, z_m },
            _ => {
                return Err(bad(
                    "invalid input `track`: give either gauge_m and gauge_height_m (the rails \
                     placed by the gauge point) or rail_origin_y_m and rail_origin_z_m (the rail \
                     profiles' origins placed absolutely)",
                ))
            }
        };
        let s_m = c.position.track_s_m;
        let rail_options = profile_options(t.rail_mirror_y, t.rail_profile_unit);
        let (rail_r, slices_r) = read_rail(
            &t.rail_profile,
            dir,
            &rail_options,
            "track.rail_profile",
            s_m,
        )?;
        let (rail_l, slices_l) = match &t.rail_profile_left {
            Some(n) => read_rail(n, dir, &rail_options, "track.rail_profile_left", s_m)?,
            None => (rail_r.clone(), slices_r.clone()),
        };
        let pitch = c.position.pitch_rad;
        let wheel_options = profile_options(w.wheel_mirror_y, w.wheel_profile_unit);
        let (wheel_r, oor_r) = read_wheel(
            &w.wheel_profile,
            dir,
            &wheel_options,
            "wheelset.wheel_profile",
            pitch,
            w.nominal_radius_m,
        )?;
        let (wheel_l, oor_l) = match &w.wheel_profile_left {
            Some(n) => read_wheel(
                n,
                dir,
                &wheel_options,
                "wheelset.wheel_profile_left",
                pitch,
                w.nominal_radius_m,
            )?,
            None => (wheel_r.clone(), oor_r.clone()),
        };
        let wavelength = w
            .smoothing_wavelength_m
            .unwrap_or(DEFAULT_SMOOTHING_WAVELENGTH_M);
        if !(wavelength.is_finite() && wavelength >= 0.0) {
            return Err(bad(format!(
                "invalid input `wheelset.smoothing_wavelength_m`: must be >= 0, got {wavelength}"
            )));
        }
        let track = TrackData {
            placement,
            cant_rad: t.cant_rad,
            deviations: [t.rail_deviation_left, t.rail_deviation_right],
            roller_radius_m: t.roller_radius_m,
            curvature_per_m: t.curvature_per_m,
        };
        // A roller rig turns its rollers (track.roller_rad_per_s) and the
        // wheelset's forward speed is 0 unless given; on a track the
        // forward speed is needed.
        let (forward_m_per_s, roller_rad_per_s) =
            match (t.roller_radius_m, t.roller_rad_per_s, c.velocity.forward_m_per_s) {
                (Some(_), Some(w), v) => (v.unwrap_or(0.0), w),
                (Some(_), None, _) => {
                    return Err(bad(
                        "invalid input `track.roller_rad_per_s`: a roller rig (track.roller_radius_m) needs \
                         its rollers' angular velocity",
                    ))
                }
                (None, Some(_), _) => {
                    return Err(bad(
                        "invalid input `track.roller_rad_per_s`: needs a roller rig (track.roller_radius_m)",
                    ))
                }
                (None, None, Some(v)) => (v, 0.0),
                (None, None, None) => {
                    return Err(bad(
                        "invalid input `velocity.forward_m_per_s`: missing (the wheelset's \
                         forward speed on a track)",
                    ))
                }
            };
        let wheelset = WheelsetData {
            flange_back_distance_m: w.flange_back_distance_m,
            nominal_radius_m: w.nominal_radius_m,
            flange_back_y_m: w.flange_back_y_m,
        };
        // The service's checks: the same ranges, the same keys.
        ranges::check_geometry(&track, &wheelset).map_err(|e| bad(e.to_string()))?;
        let mut pair = WheelRailPair::new(
            [&rail_l, &rail_r],
            [&wheel_l, &wheel_r],
            track,
            wheelset,
            &SplineOptions::smoothing(wavelength),
        )?;
        for (side, oor) in [(Side::Left, oor_l), (Side::Right, oor_r)] {
            if let Some(oor) = oor {
                pair = pair.with_wheel_slices(side, oor, pitch)?;
            }
        }
        let material = CombinedMaterial::identical(Material {
            shear_modulus_pa: c.material.shear_modulus_pa,
            poisson_ratio: c.material.poisson_ratio,
        })
        .map_err(|e| bad(e.to_string().replace("material.body1", "material")))?;
        let v = &c.velocity;
        let (friction, friction_table) = wheelrail_friction(c.friction)?;
        let input = WheelRailInput {
            position: WheelsetPosition {
                lateral_m: c.position.lateral_m,
                yaw_rad: c.position.yaw_rad,
                roll_rad: c.position.roll_rad,
                track_s_m: c.position.track_s_m,
            },
            velocity: WheelsetVelocity {
                forward_m_per_s,
                lateral_m_per_s: v.lateral_m_per_s,
                vertical_m_per_s: v.vertical_m_per_s,
                roll_rad_per_s: v.roll_rad_per_s,
                yaw_rad_per_s: v.yaw_rad_per_s,
                pitch_rad_per_s: v.pitch_rad_per_s,
            },
            load,
            sides,
            material,
            friction,
            friction_table,
            settings: WheelRailSettings {
                model,
                element_size_m: c.grid.element_size_m,
                min_elements_across: c.grid.min_elements_across,
                force_tolerance_of_wheel_load: c.grid.force_tolerance_of_wheel_load,
                polach: match &c.polach {
                    Some(p) => PolachParameters {
                        k_adhesion: p.k_adhesion,
                        k_slip: p.k_slip,
                        limit_ratio: p.limit_ratio,
                        decay_s_per_m: p.decay_s_per_m,
                    },
                    None => PolachParameters::default(),
                },
                modified_fastsim: match &c.modified_fastsim {
                    Some(m) => SlopeReduction {
                        initial_factor: m.initial_factor,
                        limit_ratio: m.limit_ratio,
                        transition_rate: m.transition_rate,
                        friction_limit_ratio: m.friction_limit_ratio,
                        friction_decay_s_per_m: m.friction_decay_s_per_m,
                    },
                    None => SlopeReduction::TRACTCURV,
                },
                rigid_slip: c
                    .conformal
                    .as_ref()
                    .map(|k| k.rigid_slip)
                    .unwrap_or_default(),
                ..WheelRailSettings::default()
            },
            total_longitudinal_force_n: l.total_longitudinal_force_n,
            temperature: c.temperature,
            rail_motion: [RailMotion {
                roller_rad_per_s,
                ..RailMotion::default()
            }; 2],
            rail_slices: [slices_l, slices_r],
        };
        ranges::check_motion(
            &input.position,
            &input.velocity,
            &input.load,
            input.total_longitudinal_force_n,
            t.roller_radius_m.map(|radius_m| ranges::Rollers {
                radius_m,
                rad_per_s: roller_rad_per_s,
            }),
        )
        .map_err(|e| bad(e.to_string()))?;
        Ok(Self {
            pair,
            input,
            model: model_name,
        })
    }
}

/// The JSON output.
#[derive(Serialize)]
struct JsonReport<'a> {
    model: &'a str,
    center_z_m: f64,
    roll_rad: f64,
    pitch_rad_per_s: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    pitch_control: Option<PitchControl>,
    wheels: serde_json::Map<String, serde_json::Value>,
    timing: Timing,
    /// The solution's plausibility warnings (empty when it is plausible):
    /// `kind`, `key`, `side`, `value`, `limit`, `message`.
    warnings: &'a [PlausibilityWarning],
}

fn human(sol: &WheelRailSolution, model: &str) -> String {
    let mut s = format!(
        "model {model}: wheelset centre z {:.4} mm, roll {:.4} mrad, rotation {:.4} rad/s\n",
        sol.center_z_m * 1e3,
        sol.roll_rad * 1e3,
        sol.pitch_rad_per_s
    );
    if let Some(c) = sol.pitch_control {
        s += &format!(
            "rotation found for the total longitudinal force {:.1} N: reached {:.1} N at nominal \
             creepage {:.4e} in {} steps ({} solves){}\n",
            c.target_force_n,
            c.force_n,
            c.nominal_creepage,
            c.iterations,
            c.solves,
            if c.converged { "" } else { ", NOT CONVERGED" }
        );
    }
    s += "wheel forces act on the rail, in the track frame (x forward, y to the right, z down); \
          per patch: rail y and wheel y in profile coordinates, creepages and forces in the \
          patch's side frame (eta, FS positive towards the field side: mirrored for the left wheel)\n";
    for w in &sol.wheels {
        let f = w.force_track_n;
        s += &format!(
            "{} wheel: {} patch(es), approach {:.4} mm, force on the rail \
             Fx {:.1} N, Fy {:.1} N, Fz {:.1} N\n",
            w.side.name(),
            w.patches.len(),
            w.vertical_approach_m * 1e3,
            f[0],
            f[1],
            f[2]
        );
        for (k, p) in w.patches.iter().enumerate() {
            s += &format!(
                "  patch {k}: rail y {:.2} mm, wheel y {:.2} mm, contact angle {:.2} deg, \
                 rolling radius {:.2} mm\n    creepages xi {:.3e} [-], eta {:.3e} [-], \
                 phi {:.3e} [1/m]; FN {:.1} N, FX {:.1} N, FS {:.1} N; pmax {:.0} MPa{}, \
                 area {:.2} mm^2\n",
                p.rail_y_m * 1e3,
                p.wheel_y_m * 1e3,
                p.contact_angle_rad.to_degrees(),
                p.rolling_radius_m * 1e3,
                p.creepage_long,
                p.creepage_lat,
                p.spin_per_m,
                p.normal_force_n,
                p.fx_n,
                p.fs_n,
                p.max_pressure_pa * 1e-6,
                match (p.fastsim_max_pressure_pa, p.method) {
                    (Some(b), _) => format!(
                        " (Hertz p0; FASTSIM's traction bound peaks at {:.0} MPa)",
                        b * 1e-6
                    ),
                    (None, m) if m.starts_with("hertz_") => " (Hertz p0)".into(),
                    _ => String::new(),
                },
                p.contact_area_m2 * 1e6
            );
            if let Some(t) = &p.temperature {
                s += &format!(
                    "    flash temperature: rail max {:.1} K at x {:.2} mm, s {:.2} mm; wheel max \
                     {:.1} K at x {:.2} mm, s {:.2} mm; contact {:.1} K, rail's heat share {:.3}, \
                     frictional power {:.1} W, Peclet {:.0}\n",
                    t.max_rail.temperature_k,
                    t.max_rail.x_m * 1e3,
                    t.max_rail.y_m * 1e3,
                    t.max_wheel.temperature_k,
                    t.max_wheel.x_m * 1e3,
                    t.max_wheel.y_m * 1e3,
                    t.contact_temperature_k,
                    t.heat_share_rail,
                    t.frictional_power_w,
                    t.peclet_number
                );
            }
        }
    }
    let t = sol.timing;
    s += &format!(
        "time: search {:.2} ms, geometry {:.2} ms, solve {:.2} ms\n",
        t.search_s * 1e3,
        t.geometry_s * 1e3,
        t.solve_s * 1e3
    );
    s
}

/// Runs `railcontact wheelrail`.
pub fn run(args: &WheelrailArgs) -> Result<(), CliError> {
    let format = args.plot.as_deref().map(plot_format).transpose()?;
    let text = super::CaseKind::read(&args.case, super::CaseKind::Wheelset)?;
    let dir = args.case.parent().unwrap_or(Path::new("."));
    let run = WheelrailRun::from_toml(&text, dir).map_err(|e| match e {
        CliError::BadInput(m) => bad(format!("{}: {m}", args.case.display())),
        other => other,
    })?;
    if let Some(path) = &args.plot {
        super::check_writable("--plot", path)?;
    }
    let mut scratch = SearchScratch::default();
    // The two wheels at once where the machine has a second core.
    scratch.parallel_wheels = std::thread::available_parallelism().is_ok_and(|n| n.get() > 1);
    let sol = solve_wheelset(&run.pair, &run.input, KernelCache::global(), &mut scratch)?;
    let warnings = check_plausibility(&run.input, &sol);
    for w in &warnings {
        eprintln!("warning: {w}");
    }
    // The answer first, then the plot: a plot that fails loses nothing.
    if args.json {
        let mut wheels = serde_json::Map::new();
        for w in &sol.wheels {
            let v = serde_json::to_value(w).map_err(|e| CliError::Failure(e.to_string()))?;
            wheels.insert(w.side.name().to_string(), v);
        }
        let report = JsonReport {
            model: run.model,
            center_z_m: sol.center_z_m,
            roll_rad: sol.roll_rad,
            pitch_rad_per_s: sol.pitch_rad_per_s,
            pitch_control: sol.pitch_control,
            wheels,
            timing: sol.timing,
            warnings: &warnings,
        };
        let json = serde_json::to_string(&report).map_err(|e| CliError::Failure(e.to_string()))?;
        write_stdout(&format!("{json}\n"))?;
    } else {
        write_stdout(&human(&sol, run.model))?;
    }
    if let (Some(path), Some(format)) = (&args.plot, format) {
        write_plot(path, format, &run, &sol, &scratch)
            .map_err(|e| CliError::Failure(format!("cannot write {}: {e}", path.display())))?;
        if !args.json {
            write_stdout(&format!("plot written to {}\n", path.display()))?;
        }
    }
    Ok(())
}

/// Lateral pressure distribution of a patch: (track y [mm], largest
/// pressure along x [MPa]) per lateral grid line.
fn lateral_pressure(p: &PatchResult, side: Side) -> Vec<(f64, f64)> {
    let (Some(sol), Some(grid)) = (&p.solution, &p.grid_geometry) else {
        return Vec::new();
    };
    let ca = p.contact_angle_rad.cos();
    (0..grid.ny)
        .map(|is| {
            let pmax = (0..grid.nx)
                .map(|ix| sol.fields.pressure_pa[grid.index(ix, is)])
                .fold(0.0, f64::max);
            // Lateral tangent (q, z) = (cos, -sin) of the contact angle.
            let q = side.sign() * p.track_y_m + grid.y_m(is) * ca;
            (side.sign() * q * 1e3, pmax * 1e-6)
        })
        .collect()
}

/// Caption of the lower panels.
const PRESSURE_CAPTION: &str = "largest pressure across each lateral grid line";

fn write_plot(
    path: &Path,
    format: Format,
    run: &WheelrailRun,
    sol: &WheelRailSolution,
    scratch: &SearchScratch,
) -> Result<(), String> {
    register_fonts()?;
    match format {
        Format::Png => {
            let root = BitMapBackend::new(path, SIZE).into_drawing_area();
            draw(&root, run, sol, scratch)?;
            root.present().map_err(|e| e.to_string())
        }
        Format::Svg => {
            let root = SVGBackend::new(path, SIZE).into_drawing_area();
            draw(&root, run, sol, scratch)?;
            root.present().map_err(|e| e.to_string())
        }
    }
}

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, plotters::coord::Shift>,
    run: &WheelrailRun,
    sol: &WheelRailSolution,
    scratch: &SearchScratch,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(err)?;
    let cols = root.split_evenly((2, sol.wheels.len().max(1)));
    for (k, w) in sol.wheels.iter().enumerate() {
        let side = w.side;
        let s = side.sign();
        let i = side.index();
        // Window, in the side frame (gauge side at -q): at least 70 mm
        // around the patches, reaching 15 mm beyond the flange tip (the
        // wheel's lowest point) so that gauge face and flange show on
        // either wheel; then in track y.
        let qc: f64 = w.patches.iter().map(|p| s * p.track_y_m).sum::<f64>()
            / w.patches.len().max(1) as f64
            * 1e3;
        let tip_q = scratch.locus[i]
            .iter()
            .max_by(|a, b| a.z_m.total_cmp(&b.z_m))
            .map_or(qc, |p| p.q_m * 1e3);
        let qlo = (qc - 35.0).min(tip_q - 15.0);
        let qhi = (qlo + 70.0).max(qc + 25.0);
        let (ylo, yhi) = if s > 0.0 { (qlo, qhi) } else { (-qhi, -qlo) };
        let rail_all: Vec<(f64, f64)> = run
            .pair
            .rail(side)
            .samples()
            .iter()
            .map(|p| (s * p.q_m * 1e3, -p.z_m * 1e3))
            .collect();
        let wheel_all: Vec<(f64, f64)> = scratch.locus[i]
            .iter()
            .map(|p| (s * p.q_m * 1e3, -(p.z_m + w.vertical_approach_m) * 1e3))
            .collect();
        let inside = |lo: f64, hi: f64| move |p: &&(f64, f64)| p.0 >= lo && p.0 <= hi;
        let zs = rail_all
            .iter()
            .chain(&wheel_all)
            .filter(inside(ylo, yhi))
            .map(|p| p.1);
        let (zlo, zhi) = zs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), z| {
            (a.min(z), b.max(z))
        });
        let (zlo, zhi) = if zlo.is_finite() {
            (zlo.max(-40.0), zhi.min(30.0))
        } else {
            (-20.0, 20.0)
        };
        // Equal scale, so that flanks and flange are as steep as they are;
        // the pressure panel below shares the widened y range.
        let upper = cols[k]
            .titled(
                &format!(
                    "{} wheel ({}): profiles, contact points",
                    side.name(),
                    run.model
                ),
                (FONT, 22),
            )
            .map_err(err)?;
        let frame = Frame {
            margin: 12,
            x_labels: 40,
            y_labels: 70,
        };
        let (yr, zr) = frame.ranges(upper.dim_in_pixel(), ylo..yhi, zlo..zhi);
        let (ylo, yhi) = (yr.start, yr.end);
        let rail: Vec<(f64, f64)> = rail_all.iter().filter(inside(ylo, yhi)).copied().collect();
        let wheel: Vec<(f64, f64)> = wheel_all.iter().filter(inside(ylo, yhi)).copied().collect();
        let mut chart = frame.chart(&upper, yr, zr).map_err(err)?;
        chart
            .configure_mesh()
            .x_desc("track y [mm]")
            .y_desc("height [mm]")
            .label_style((FONT, 15))
            .draw()
            .map_err(err)?;
        chart
            .draw_series(LineSeries::new(rail, BLUE.stroke_width(2)))
            .map_err(err)?
            .label("rail")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLUE));
        chart
            .draw_series(LineSeries::new(wheel, RED.stroke_width(2)))
            .map_err(err)?
            .label("wheel (contact locus, pressed)")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RED));
        chart
            .draw_series(
                w.patches.iter().map(|p| {
                    Circle::new((p.track_y_m * 1e3, -p.track_z_m * 1e3), 6, BLACK.filled())
                }),
            )
            .map_err(err)?;
        // Away from the flange: lower left on the left wheel (flange to the
        // right), middle right on the right wheel (flange to the left).
        let legend = if s > 0.0 {
            SeriesLabelPosition::MiddleRight
        } else {
            SeriesLabelPosition::LowerLeft
        };
        chart
            .configure_series_labels()
            .position(legend)
            .label_font((FONT, 15))
            .border_style(BLACK)
            .background_style(WHITE.mix(0.8))
            .draw()
            .map_err(err)?;
        // Lower row: lateral pressure distributions.
        let curves: Vec<Vec<(f64, f64)>> = w
            .patches
            .iter()
            .map(|p| lateral_pressure(p, side))
            .collect();
        let pmax = curves
            .iter()
            .flatten()
            .map(|p| p.1)
            .fold(0.0, f64::max)
            .max(1.0);
        let lower = &cols[k + sol.wheels.len()];
        if curves.iter().all(|c| c.is_empty()) {
            // Closed-form models give no per-element pressures.
            let note = format!(
                "no pressure distribution from model {}: pmax per patch in the summary",
                run.model
            );
            panel_note(lower, PRESSURE_CAPTION, 20, &note)?;
            continue;
        }
        let mut chart = ChartBuilder::on(lower)
            .caption(PRESSURE_CAPTION, (FONT, 20))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d(ylo..yhi, 0.0..pmax * 1.1)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc("track y [mm]")
            .y_desc("pressure [MPa]")
            .y_label_formatter(&|v| format!("{v:.0}"))
            .label_style((FONT, 15))
            .draw()
            .map_err(err)?;
        for (c, curve) in curves.into_iter().enumerate() {
            let color = Palette99::pick(c).to_rgba();
            chart
                .draw_series(LineSeries::new(curve, color.stroke_width(2)))
                .map_err(err)?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::wheelrail::solve_wheelset;

    /// CONTACT's test-rollers2.inp case 1a as a case file: the sphere of
    /// radius 100 mm (`circ_r100.prw` at a nominal radius of 0.1 m, its
    /// profile y = 0 at 0.2 m from the wheelset centre) on the flat plane
    /// whose origin is placed at y = 0.2 m, z = 0 (`rail_origin_y_m`), at
    /// an approach of 0.16 mm.
    const SPHERE_ON_PLANE: &str = r#"
model = "exact"
side = "right"
[track]
rail_profile = "crates/solver/profiles/flat_plane.prr"
rail_origin_y_m = 0.2
rail_origin_z_m = 0.0
[wheelset]
wheel_profile = "crates/solver/profiles/circ_r100.prw"
flange_back_distance_m = 0.3
flange_back_y_m = -0.05
nominal_radius_m = 0.1
[position]
roll_rad = 0.0
[velocity]
forward_m_per_s = 1.0
pitch_rad_per_s = -10.0
[load]
approach_m = 0.16e-3
[grid]
element_size_m = 0.0002
"#;

    fn root() -> &'static Path {
        Path::new(env!("CARGO_MANIFEST_DIR"))
    }

    /// The case solved: its one patch (of its one wheel).
    fn only_patch(run: &WheelrailRun) -> PatchResult {
        let mut scratch = SearchScratch::default();
        let sol =
            solve_wheelset(&run.pair, &run.input, KernelCache::global(), &mut scratch).unwrap();
        let patches = &sol.wheels[0].patches;
        assert_eq!(patches.len(), 1);
        patches[0].clone()
    }

    /// The one patch of the case file `text`, checked to lie at track y =
    /// 0.2 m.
    fn one_patch_at_200_mm(text: &str) -> PatchResult {
        let run = WheelrailRun::from_toml(text, root()).unwrap();
        let p = only_patch(&run);
        assert!((p.track_y_m - 0.2).abs() < 1e-9, "{}", p.track_y_m);
        p
    }

    /// test-rollers2.ref_out, Case 1: FN 9.722E+04 N at track y 200 mm.
    /// Within 0.05 %: the patch's grid has no element centred on the
    /// sphere's lowest point (CONTACT's has), whose h(0.1 mm) = 0.1^2 /
    /// (2 R) = 5e-5 mm of the approach is not loaded.
    #[test]
    fn a_rail_placed_by_its_origin_carries_contacts_sphere() {
        let p = one_patch_at_200_mm(SPHERE_ON_PLANE);
        let fn_n = p.normal_force_n;
        assert!((fn_n - 9.722e4).abs() < 5e-4 * 9.722e4, "{fn_n}");
    }

    /// A case file rolling backwards (`velocity.forward_m_per_s` < 0): the
    /// sphere on the plane braked while rolling at -1 m/s is the mirror
    /// image of it braked at +1 m/s (the pitch rate turned over with the
    /// speed, a lateral speed kept): Fx and the longitudinal creepage of
    /// opposite sign, the same Fs and Fn, and the patch reports rolling
    /// direction pi. About 0 is refused naming the key.
    #[test]
    fn a_case_file_rolling_backwards_is_the_mirror_image() {
        // At `v` m/s, the wheel turning 0.1 % slower than free rolling.
        let at = |v: f64| {
            let velocity = format!(
                "forward_m_per_s = {v}\npitch_rad_per_s = {}\nlateral_m_per_s = 0.002",
                -9.99 * v
            );
            SPHERE_ON_PLANE.replace("forward_m_per_s = 1.0\npitch_rad_per_s = -10.0", &velocity)
        };
        let (a, b) = (
            one_patch_at_200_mm(&at(1.0)),
            one_patch_at_200_mm(&at(-1.0)),
        );
        assert!(a.fx_n.abs() > 100.0 && a.fs_n.abs() > 100.0, "{a:?}");
        assert_eq!(
            (a.rolling_direction_rad, b.rolling_direction_rad),
            (0.0, std::f64::consts::PI)
        );
        let f = 1e-6 * a.normal_force_n;
        for (what, x, y, tol) in [
            ("xi", a.creepage_long, -b.creepage_long, 1e-12),
            ("eta", a.creepage_lat, b.creepage_lat, 1e-12),
            ("Fn", a.normal_force_n, b.normal_force_n, f),
            ("Fx", a.fx_n, -b.fx_n, f),
            ("Fs", a.fs_n, b.fs_n, f),
        ] {
            assert!((x - y).abs() <= tol, "{what}: {x} against {y}");
        }
        let e = WheelrailRun::from_toml(&at(-0.5), root())
            .err()
            .unwrap()
            .to_string();
        assert!(
            e.contains("velocity.forward_m_per_s") && e.contains("[-150, -1] m/s"),
            "{e}"
        );
    }

    /// The S1002 wheel on the UK crossing nose given as a rail slices file
    /// (`uk_crossing_nose.slcs`, CONTACT's `mbench_locus.inp` case at S =
    /// 239 mm): one patch on the nose's top. CONTACT's library on the same
    /// slices (`crates/cntc/bench/slices_cases.py`, case s239): FN 10076.7,
    /// FX 2754.59 N, YCP 788.608 mm; the differences, from the tangent plane
    /// taken on the slice at S, are those of `crates/cntc/tests/slices.rs`
    /// (FN 0.41 %, FX 0.14 %, YCP 0.36 mm through the CONTACT library).
    #[test]
    fn a_rail_given_as_slices_is_the_rail_at_the_wheelsets_position() {
        let cases = root().join("examples/cases");
        let case = &std::fs::read_to_string(cases.join("crossing_nose.toml")).unwrap();
        let run = WheelrailRun::from_toml(case, &cases).unwrap();
        assert!(run.input.rail_slices[Side::Right.index()].is_some());
        let p = &only_patch(&run);
        assert!(
            (p.normal_force_n - 10076.7).abs() < 5e-3 * 10076.7,
            "{}",
            p.normal_force_n
        );
        assert!((p.track_y_m - 0.788608).abs() < 4e-4, "{}", p.track_y_m);
        let fx = p.force_track_n[0];
        assert!((fx - 2754.59).abs() < 7e-3 * 2754.59, "{fx}");
        // Beyond the slices: refused naming the wheelset's position.
        let far = case.replace("track_s_m = 0.239", "track_s_m = 0.5");
        let e = WheelrailRun::from_toml(&far, &cases).err().unwrap();
        assert!(e.to_string().contains("position.track_s_m"), "{e}");
    }

    /// `examples/cases/wheel_flat.toml`: Chalmers' wheel flat (a wheel
    /// slices file, `S1002_flat.slcw`) at pitch -37 degrees, its deepest
    /// part facing the rail. CONTACT's examples/wheelflat.ref_out case 13
    /// (its library's digits, `crates/cntc/bench/wheelflat_cases.py`): FN
    /// 124930 N, FX 19784.1 N, YCP 773.459 mm, the contact 14 mm to the
    /// field side of the round wheel's (759.33 mm, case 1). The case file
    /// smooths the profile facing the rail (and the rail) with CONTACT's
    /// wavelength where CONTACT smooths each slice (the CONTACT library
    /// here smooths as CONTACT does: FX within 0.16 %,
    /// `crates/cntc/tests/wheelflat.rs`): FN within 1e-3, FX 1 % (0.57 %
    /// measured), YCP 0.1 mm (0.01 mm). At pitch 0 (the flat half a turn
    /// away) the wheel is round: the contact within 1 mm of CONTACT's round
    /// wheel's (0.8 mm measured: the case file smooths the rail too). A
    /// pitch that is not a number is refused naming its key.
    #[test]
    fn an_out_of_round_wheel_case_meets_contacts_wheel_flat() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/cases");
        let text = std::fs::read_to_string(dir.join("wheel_flat.toml")).unwrap();
        let run = WheelrailRun::from_toml(&text, &dir).unwrap();
        assert!(run.pair.wheel(Side::Right).slices().is_some());
        let p = &only_patch(&run);
        let fx = p.force_track_n[0];
        let fn_n = p.normal_force_n;
        assert!((fn_n - 124930.0).abs() < 1e-3 * 124930.0, "{fn_n}");
        assert!((fx - 19784.1).abs() < 0.01 * 19784.1, "{fx}");
        assert!((p.track_y_m - 0.773459).abs() < 1e-4, "{}", p.track_y_m);
        let round = text.replace("pitch_rad = -0.6457718232379019", "pitch_rad = 0.0");
        let run = WheelrailRun::from_toml(&round, &dir).unwrap();
        let p = &only_patch(&run);
        assert!((p.track_y_m - 0.75933).abs() < 1e-3, "{}", p.track_y_m);
        let bad = text.replace("pitch_rad = -0.6457718232379019", "pitch_rad = nan");
        let e = WheelrailRun::from_toml(&bad, &dir).err().unwrap();
        assert!(e.to_string().contains("position.pitch_rad"), "{e}");
    }

    /// The slices' plain tables of `wheel_flat.toml` are in millimetres:
    /// read in metres (the default, as every plain table's without a unit
    /// line), the 60 mm wide profiles would be 60 m wide and are refused
    /// naming the wheel's key.
    #[test]
    fn a_slices_files_tables_are_read_in_the_unit_the_case_gives() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/cases");
        let text = std::fs::read_to_string(dir.join("wheel_flat.toml")).unwrap();
        let metres = text.replace("wheel_profile_unit = \"mm\"", "");
        assert_ne!(metres, text);
        let e = WheelrailRun::from_toml(&metres, &dir).err().unwrap();
        assert!(e.to_string().contains("`wheelset.wheel_profile`"), "{e}");
        let bad = text.replace("wheel_profile_unit = \"mm\"", "wheel_profile_unit = \"cm\"");
        let e = WheelrailRun::from_toml(&bad, &dir).err().unwrap();
        assert!(e.to_string().contains("wheel_profile_unit"), "{e}");
    }

    /// Both rails shifted 1 mm to the right (`track.rail_deviation_*`)
    /// under a wheelset shifted 1 mm alike: the same contact as without
    /// either, 1 mm further right; a deviation beyond its range is refused
    /// naming its key, as on the wire.
    #[test]
    fn rail_deviations_move_the_rails() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/cases");
        let text = std::fs::read_to_string(dir.join("wheelset_a22.toml")).unwrap();
        let solve = |text: &str| {
            let run = WheelrailRun::from_toml(text, &dir).unwrap();
            let mut scratch = SearchScratch::default();
            solve_wheelset(&run.pair, &run.input, KernelCache::global(), &mut scratch).unwrap()
        };
        let plain = solve(&text);
        let shifted = solve(
            &text
                .replace("lateral_m = 0.0065", "lateral_m = 0.0075")
                .replace(
                    "[wheelset]",
                    "[track.rail_deviation_left]\ndy_m = 0.001\n\
                     [track.rail_deviation_right]\ndy_m = 0.001\n\n[wheelset]",
                ),
        );
        for (a, b) in plain.wheels.iter().zip(&shifted.wheels) {
            assert_eq!(a.patches.len(), b.patches.len());
            for (p, q) in a.patches.iter().zip(&b.patches) {
                assert!(
                    (q.track_y_m - p.track_y_m - 1e-3).abs() < 1e-9,
                    "{}",
                    q.track_y_m
                );
                for k in 0..3 {
                    let (f, g) = (p.force_track_n[k], q.force_track_n[k]);
                    assert!((f - g).abs() < 1e-6 * 1e4, "{k}: {f} {g}");
                }
            }
        }
        let far = text.replace(
            "[wheelset]",
            "[track.rail_deviation_right]\ndy_m = 6.0\n\n[wheelset]",
        );
        let e = WheelrailRun::from_toml(&far, &dir).err().unwrap();
        let m = e.to_string();
        assert!(
            m.contains("`track.rail_deviation_right.dy_m`") && m.contains("millimetres"),
            "{m}"
        );
    }

    /// CONTACT's test-rollers2.inp case 2a as a case file: the "bus" (the
    /// flat wheel `flat_plane.prw` at a nominal radius of 133.3 mm, a
    /// cylinder) on a roller of 400 mm whose profile is `circ_r100.prr`
    /// (an ellipsoid), at an approach of 0.16 mm, the roller turning at
    /// 2.5 rad/s and the wheel at -7.5 rad/s (both surfaces at 1 m/s, the
    /// case's 0.25 and -0.75 rad/s ten times: the same creepages, at the
    /// speed range's lower end): the sphere's case file with the roller's
    /// keys.
    fn bus_on_roller() -> String {
        SPHERE_ON_PLANE
            .replace("flat_plane.prr", "circ_r100.prr")
            .replace(
                "rail_origin_z_m = 0.0",
                "rail_origin_z_m = 0.0\nroller_radius_m = 0.4\nroller_rad_per_s = 2.5",
            )
            .replace("circ_r100.prw", "flat_plane.prw")
            .replace("nominal_radius_m = 0.1", "nominal_radius_m = 0.13333333")
            .replace(
                "forward_m_per_s = 1.0\npitch_rad_per_s = -10.0",
                "pitch_rad_per_s = -7.5",
            )
    }

    /// The bus with its rollers turning the other way (-2.5 rad/s) under
    /// the same wheel rate: the surfaces move against each other at the
    /// contact, the rolling speed nearly 0, and the answer warns naming
    /// the pitch rate; at the example's rates it does not.
    #[test]
    fn rollers_turning_against_the_wheel_warn() {
        let warnings = |text: &str| {
            let run = WheelrailRun::from_toml(text, root()).unwrap();
            let mut scratch = SearchScratch::default();
            let sol =
                solve_wheelset(&run.pair, &run.input, KernelCache::global(), &mut scratch).unwrap();
            check_plausibility(&run.input, &sol)
        };
        assert!(warnings(&bus_on_roller()).is_empty());
        let against = bus_on_roller().replace("roller_rad_per_s = 2.5", "roller_rad_per_s = -2.5");
        let w = warnings(&against);
        assert_eq!(w.len(), 1, "{w:?}");
        assert_eq!(w[0].key, "velocity.pitch_rad_per_s");
        assert!(
            w[0].value > 1e3 && w[0].message.contains("against each other"),
            "{w:?}"
        );
    }

    /// test-rollers2.ref_out, Case 6 (test 2a): FN 9.719E+04 N, CKSI
    /// -2.500E-08, at track y 200 mm, VELOC 100.0 mm/s. FN within 0.05 %
    /// as for the sphere on the plane (an element centred on the contact
    /// point in CONTACT's grid, not in ours); the creepage to 1e-7 (the
    /// contact point's radii, 0.08 mm into each surface, differ from the
    /// nominal ones by 6e-4 and 2e-4 of a percent).
    #[test]
    fn a_roller_rig_case_carries_contacts_bus_on_its_roller() {
        let p = one_patch_at_200_mm(&bus_on_roller());
        let fn_n = p.normal_force_n;
        assert!((fn_n - 9.719e4).abs() < 5e-4 * 9.719e4, "{fn_n}");
        assert!(
            (p.creepage_long + 2.5e-8).abs() < 1e-7,
            "{}",
            p.creepage_long
        );
        assert!((p.rolling_speed_m_per_s - 1.0).abs() < 1e-5);
    }

    /// A roller rig's keys are refused naming them: a negative radius, a
    /// roller without its rate or a rate without a roller, a cant on a
    /// roller, a curvature beyond 0.1 /m, a roller turning slower than the
    /// speed range either way (0.5 rad/s on 0.4 m: 0.2 m/s; backwards it
    /// turns at -1 m/s or faster).
    #[test]
    fn bad_roller_and_curvature_keys_are_refused_naming_them() {
        let bus = bus_on_roller();
        let with = |from: &str, to: &str| bus.replace(from, to);
        for (text, key) in [
            (
                with("roller_radius_m = 0.4", "roller_radius_m = -0.4"),
                "track.roller_radius_m",
            ),
            (
                with(
                    "roller_rad_per_s = 2.5
",
                    "",
                ),
                "track.roller_rad_per_s",
            ),
            (
                with(
                    "roller_radius_m = 0.4
",
                    "",
                ),
                "track.roller_rad_per_s",
            ),
            (
                with(
                    "roller_rad_per_s = 2.5",
                    "roller_rad_per_s = 2.5
cant_rad = 0.025",
                ),
                "track.cant_rad",
            ),
            (
                with(
                    "roller_rad_per_s = 2.5",
                    "roller_rad_per_s = 2.5
curvature_per_m = 0.5",
                ),
                "track.curvature_per_m",
            ),
        ] {
            let e = WheelrailRun::from_toml(&text, root()).err().unwrap();
            assert!(e.to_string().contains(key), "{key}: {e}");
        }
        for rate in ["-0.5", "0.5"] {
            let text = with(
                "roller_rad_per_s = 2.5",
                &format!("roller_rad_per_s = {rate}"),
            );
            let e = WheelrailRun::from_toml(&text, root()).err().unwrap();
            assert!(e.to_string().contains("track.roller_rad_per_s"), "{e}");
        }
        // A rail varying along the track is no roller's.
        let slices = bus
            .replace(
                "crates/solver/profiles/circ_r100.prr",
                "crates/solver/profiles/uk_crossing_nose.slcs",
            )
            .replace("roll_rad = 0.0", "roll_rad = 0.0\ntrack_s_m = 0.239");
        assert_ne!(slices, bus);
        let e = match WheelrailRun::from_toml(&slices, root()) {
            Err(e) => e.to_string(),
            Ok(run) => solve_wheelset(
                &run.pair,
                &run.input,
                KernelCache::global(),
                &mut SearchScratch::default(),
            )
            .unwrap_err()
            .to_string(),
        };
        assert!(e.contains("track.rail_profile"), "{e}");
    }

    /// `grid.force_tolerance_of_wheel_load` reaches the settings; one out
    /// of range is refused naming it.
    #[test]
    fn the_force_tolerance_of_a_case_is_read_and_checked() {
        let with = |t: &str| {
            let grid = "[grid]\nelement_size_m = 0.0002\n";
            let text = SPHERE_ON_PLANE.replace(
                grid,
                &format!("{grid}force_tolerance_of_wheel_load = {t}\n"),
            );
            assert_ne!(text, SPHERE_ON_PLANE);
            WheelrailRun::from_toml(&text, root()).unwrap()
        };
        let run = with("0.01");
        assert_eq!(run.input.settings.force_tolerance_of_wheel_load, Some(0.01));
        let run = with("0.001");
        let e = solve_wheelset(
            &run.pair,
            &run.input,
            KernelCache::global(),
            &mut SearchScratch::default(),
        )
        .unwrap_err();
        assert!(
            e.to_string().contains("grid.force_tolerance_of_wheel_load"),
            "{e}"
        );
    }

    /// Both placements, or neither, are refused naming `track`.
    #[test]
    fn a_track_is_placed_one_way() {
        let both = SPHERE_ON_PLANE.replace(
            "rail_origin_z_m = 0.0",
            "rail_origin_z_m = 0.0\ngauge_m = 1.435\ngauge_height_m = 0.014",
        );
        let neither = SPHERE_ON_PLANE
            .replace("rail_origin_y_m = 0.2\n", "")
            .replace("rail_origin_z_m = 0.0\n", "");
        for text in [both, neither] {
            let e = WheelrailRun::from_toml(&text, root()).err().unwrap();
            assert!(e.to_string().contains("`track`"), "{e}");
        }
        let far = SPHERE_ON_PLANE.replace("rail_origin_y_m = 0.2", "rail_origin_y_m = 200.0");
        let e = WheelrailRun::from_toml(&far, root()).err().unwrap();
        assert!(e.to_string().contains("track.rail_origin_y_m"), "{e}");
    }
}
