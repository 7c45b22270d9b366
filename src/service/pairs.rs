//! Registered wheel/rail profile pairs: canonical form and content-derived
//! id, preparation (profiles parsed, checked, smoothed and placed: a
//! [`WheelRailPair`]), the in-memory registry and its store.
//!
//! # Identity
//!
//! A registration is first made canonical ([`canonicalize`]): a built-in
//! pair name is expanded to its full spec, built-in profiles are replaced
//! by their file content, defaults are filled in (materials, friction,
//! element size, smoothing), and a left profile equal to the right one is
//! dropped. The id is the first 32 hex digits of the SHA-256 of a version
//! tag and the protobuf encoding of that canonical spec (prost writes
//! fields in tag order, so equal specs give equal bytes). Equal inputs
//! therefore give equal ids, and registering twice prepares once.
//!
//! # Life of a pair
//!
//! Registering checks every number against its physical range
//! ([`canonicalize`]), inserts an entry (state PREPARING; within the
//! registry's limits, [`PairRegistry::begin`]), prepares it on the solve
//! pool (profiles of at most `max_profile_points` points, and one trial
//! solve at the centred position: [`prepare_with`]), builds its contact
//! table, writes the canonical registration to the store and marks it
//! READY. A failed preparation removes the entry again
//! (a table that cannot be built does not: only one model needs it). After
//! a restart the stored registrations come back as entries in state STORED
//! (each checked first: a record whose content no longer hashes to its id,
//! or that cannot be decoded, is a FAILED entry that is never served, see
//! [`PairRegistry::open`]) and are prepared, and their tables built, on
//! first use; the preparation of an entry runs once however
//! many requests ask for it at the same time (the entry's `preparing`
//! lock). The prepared pairs held stay within `max_prepared_bytes`: the
//! least recently used are let go and prepared again on their next use
//! ([`PairRegistry::prepared`]). Only the preparation lock is held across
//! an await or a preparation; store writes and the
//! registry's map change together under the store's lock, so a delete and
//! a registration of the same pair cannot leave them disagreeing.

use std::collections::BTreeMap;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex, OnceLock, RwLock, Weak};
use std::time::Instant;

use prost::Message;
use sha2::{Digest, Sha256};

use crate::core::cache::KernelCache;
use crate::core::error::show;
use crate::core::material::{CombinedMaterial, Material};
use crate::core::memory::HeapBytes;
use crate::core::problem::Friction;
use crate::problem::case::MaterialSection;
use crate::service::config::{ServeConfig, StoreDamaged};
use crate::service::convert;
use crate::service::metrics::Metrics;
use crate::service::pb;
use crate::service::pool::Admission;
use crate::service::status::ServiceError;
use crate::service::store::PairStore;
use crate::wheelrail::pair_cache::PairCache;
use crate::wheelrail::profile::{quote, ProfileError, SourceLocation};
use crate::wheelrail::ranges;
use crate::wheelrail::slices::{parse_slices_within, SlicesLimits};
use crate::wheelrail::{
    builtin, is_slices_file, parse_profile, ContactTable, LengthUnit, LoadOptions, MiniProfVariant,
    Profile, ProfileFormat, ProfileKind, RailDeviation, RailPlacement, RailSlices, SplineOptions,
    TableSettings, TrackData, WheelRailError, WheelRailPair, WheelsetData,
    DEFAULT_SMOOTHING_WAVELENGTH_M,
};
use crate::wheelrail::{
    solve_wheelset, RailMotion, SearchScratch, Side, WheelLoad, WheelRailInput, WheelRailModel,
    WheelRailSettings, WheelsetPosition, WheelsetVelocity,
};

pub use crate::shared::BUILTIN_PAIR;

/// Default shear modulus of wheel/rail pairs [Pa] (the case file's).
const DEFAULT_SHEAR_MODULUS_PA: f64 = 82.0e9;
/// Default Poisson ratio of wheel/rail pairs [-].
const DEFAULT_POISSON_RATIO: f64 = 0.28;
/// Default friction coefficient of wheel/rail pairs [-].
const DEFAULT_FRICTION: f64 = 0.3;
/// Default element size of the patch grids \[m\].
pub const DEFAULT_ELEMENT_SIZE_M: f64 = 2.0e-4;

/// Tag hashed before the canonical spec: changes when the canonical form
/// does.
const ID_TAG: &[u8] = b"railcontact.v1.ProfilePairSpec/1\n";

/// Range of the shear moduli \[Pa\] (steel: about 80e9).
pub const SHEAR_MODULUS_RANGE_PA: [f64; 2] = [1e9, 1e12];
/// Range of the Poisson ratios \[-\].
pub const POISSON_RATIO_RANGE: [f64; 2] = [0.0, 0.5];
/// Range of the friction coefficients \[-\].
pub const FRICTION_RANGE: [f64; 2] = [0.0, 2.0];
/// Range of the smoothing cut-off wavelength \[m\].
pub const SMOOTHING_WAVELENGTH_RANGE_M: [f64; 2] = [0.0, 0.05];
/// Most characters of a profile's file name.
pub const MAX_FILE_NAME_CHARS: usize = 255;
/// Most slices of a rail given as slices (CONTACT's crossing example has
/// 148).
pub const MAX_RAIL_SLICES: usize = 1000;
/// The points of a rail given as slices, read (its slices' profiles, each
/// distinct file read once) and of its surface (slices x points along the
/// interpolation paths), each at most this many times `max_profile_points`.
pub const SLICES_POINTS_PER_PROFILE_POINTS: usize = 50;
/// Vertical force per wheel of the trial solve at registration \[N\]: a
/// static wheel load of a 10 t axle.
pub const TRIAL_WHEEL_LOAD_N: f64 = 50e3;

/// Checks that `v` lies in `[lo, hi]` (NaN does not), naming `field`, the
/// range and the value.
fn check_range(field: &str, v: f64, [lo, hi]: [f64; 2], unit: &str) -> Result<(), ServiceError> {
    if v >= lo && v <= hi {
        Ok(())
    } else {
        Err(ServiceError::invalid(
            field,
            format!("must be from {lo:e} to {hi:e}{unit}, got {v:e}"),
        ))
    }
}

/// The library's track of a wire track, as a case file's `[track]`
/// becomes it: placed by the gauge or by the rail origins (exactly one),
/// each rail's deviation, a roller rig, the curvature. Field paths are
/// relative to the track (`gauge_m`, `rail_deviation_left.dy_m`); the
/// ranges of placement, cant and deviations are checked here
/// ([`ranges::check_track`]), the rest (a roller's radius and cant, the
/// curvature) when the pair is placed, as for a case file.
pub fn track_data(t: &pb::TrackSpec) -> Result<TrackData, ServiceError> {
    let placement = match (t.rail_origin_y_m, t.rail_origin_z_m) {
        (None, None) => RailPlacement::GaugePoint {
            gauge_m: t.gauge_m,
            gauge_height_m: t.gauge_height_m,
        },
        (Some(q_m), Some(z_m)) if t.gauge_m == 0.0 && t.gauge_height_m == 0.0 => {
            RailPlacement::Origin { q_m, z_m }
        }
        (Some(_), Some(_)) => {
            return Err(ServiceError::invalid(
                "rail_origin_y_m",
                "give either gauge_m and gauge_height_m (the rails placed by the gauge point) \
                 or rail_origin_y_m and rail_origin_z_m (the rail profiles' origins placed \
                 absolutely), not both",
            ))
        }
        (Some(_), None) => {
            return Err(ServiceError::invalid(
                "rail_origin_z_m",
                "missing: the rails placed by their origins need rail_origin_y_m and \
                 rail_origin_z_m",
            ))
        }
        (None, Some(_)) => {
            return Err(ServiceError::invalid(
                "rail_origin_y_m",
                "missing: the rails placed by their origins need rail_origin_y_m and \
                 rail_origin_z_m",
            ))
        }
    };
    let deviation = |d: Option<&pb::RailDeviation>| {
        d.map_or_else(RailDeviation::default, |d| RailDeviation {
            dy_m: d.dy_m,
            dz_m: d.dz_m,
            droll_rad: d.droll_rad,
        })
    };
    let track = TrackData {
        placement,
        cant_rad: t.cant_rad,
        deviations: [
            deviation(t.rail_deviation_left.as_ref()),
            deviation(t.rail_deviation_right.as_ref()),
        ],
        roller_radius_m: t.roller_radius_m,
        curvature_per_m: t.curvature_per_m,
    };
    ranges::check_track(&track).map_err(|e| ServiceError::from(e).rekey("track.", ""))?;
    Ok(track)
}

/// A wire track in canonical form: a deviation of zeros is none, so that
/// equal tracks give equal ids.
fn canonical_track(mut t: pb::TrackSpec) -> pb::TrackSpec {
    let none = |d: Option<pb::RailDeviation>| d.filter(|d| *d != pb::RailDeviation::default());
    t.rail_deviation_left = none(t.rail_deviation_left);
    t.rail_deviation_right = none(t.rail_deviation_right);
    t
}

/// Checks the numeric fields of a registration's track, wheelset,
/// material and friction against their physical ranges; `f` makes the
/// field path.
fn check_ranges(
    spec: &pb::ProfilePairSpec,
    f: &dyn Fn(&str) -> String,
) -> Result<(), ServiceError> {
    // Track and wheelset: the solver's ranges, which the command line
    // checks too (unset parts are checked when defaulted).
    let track = match &spec.track {
        Some(t) => Some(track_data(t).map_err(|e| e.within(&f("track")))?),
        None => None,
    };
    let wheelset = spec.wheelset.as_ref().map(|w| WheelsetData {
        flange_back_distance_m: w.flange_back_distance_m,
        nominal_radius_m: w.nominal_radius_m,
        flange_back_y_m: w.flange_back_y_m,
    });
    let geometry = match (track, wheelset) {
        (Some(t), Some(w)) => ranges::check_geometry(&t, &w),
        (Some(t), None) => ranges::check_track(&t),
        (None, Some(w)) => ranges::check_wheelset(&w),
        (None, None) => Ok(()),
    };
    if let Err(crate::core::error::ContactError::InvalidInput { key, reason }) = geometry {
        return Err(ServiceError::invalid(f(&key), reason));
    }
    if let Some(m) = &spec.material {
        if m.influence_file_content.is_some() {
            return Err(ServiceError::invalid(
                f(convert::INFLUENCE_CONTENT_FIELD),
                "numerical influence coefficients are taken by patch cases (SolvePatch, \
                 SolvePatchBatch, CreepCurve, PatchSession), not by wheel/rail contact",
            ));
        }
        let body = |prefix: &str, g: Option<f64>, nu: Option<f64>| {
            if let Some(g) = g {
                let field = f(&format!("{prefix}.shear_modulus_pa"));
                check_range(&field, g, SHEAR_MODULUS_RANGE_PA, " Pa")?;
            }
            if let Some(nu) = nu {
                let field = f(&format!("{prefix}.poisson_ratio"));
                check_range(&field, nu, POISSON_RATIO_RANGE, "")?;
            }
            Ok::<_, ServiceError>(())
        };
        body("material", m.shear_modulus_pa, m.poisson_ratio)?;
        for (name, b) in [("material.body1", &m.body1), ("material.body2", &m.body2)] {
            if let Some(b) = b {
                body(name, Some(b.shear_modulus_pa), Some(b.poisson_ratio))?;
            }
        }
    }
    if let Some(fr) = &spec.friction {
        for (name, v) in [
            ("friction.coefficient", fr.coefficient),
            ("friction.static_coefficient", fr.static_coefficient),
            ("friction.kinetic_coefficient", fr.kinetic_coefficient),
        ] {
            if let Some(v) = v {
                check_range(&f(name), v, FRICTION_RANGE, "")?;
            }
        }
    }
    if let Some(w) = spec.smoothing_wavelength_m {
        check_range(
            &f("smoothing_wavelength_m"),
            w,
            SMOOTHING_WAVELENGTH_RANGE_M,
            " m",
        )?;
    }
    Ok(())
}

/// The solve settings a pair brings (queries may override friction and
/// element size).
#[derive(Debug, Clone)]
pub struct PairSettings {
    /// Materials (body 1 rail, body 2 wheel).
    pub material: CombinedMaterial,
    /// Default friction.
    pub friction: Friction,
    /// Default element size \[m\].
    pub element_size_m: f64,
    /// Smoothing cut-off wavelength \[m\].
    pub smoothing_wavelength_m: f64,
    /// Track.
    pub track: TrackData,
    /// Wheelset.
    pub wheelset: WheelsetData,
}

/// A checked registration in canonical form.
#[derive(Debug, Clone)]
pub struct PairSpec {
    /// Content-derived id.
    pub id: String,
    /// The canonical spec (profile contents included).
    pub canonical: pb::ProfilePairSpec,
    /// Label of the registration.
    pub label: String,
    /// The built-in pair's name, for the built-in pair.
    pub builtin_pair: Option<&'static str>,
    /// Solve settings.
    pub settings: PairSettings,
}

impl PairSpec {
    /// The registration as stored.
    pub fn registration(&self) -> pb::RegisterProfilePairRequest {
        pb::RegisterProfilePairRequest {
            pair: Some(pb::register_profile_pair_request::Pair::Spec(
                self.canonical.clone(),
            )),
            label: self.label.clone(),
        }
    }
}

/// The spec of the built-in pair (Manchester benchmark, S1002 on UIC60).
fn builtin_spec() -> pb::ProfilePairSpec {
    let src = |name: &str| pb::ProfileSource {
        source: Some(pb::profile_source::Source::BuiltinName(name.into())),
        mirror_y: false,
    };
    let t = builtin::MBENCH_TRACK;
    let w = builtin::MBENCH_WHEELSET;
    pb::ProfilePairSpec {
        wheel: Some(src("MBench_S1002_v3.prw")),
        rail: Some(src("MBench_UIC60_v3.prr")),
        track: Some(pb::TrackSpec {
            gauge_m: builtin::MBENCH_GAUGE_M,
            gauge_height_m: builtin::MBENCH_GAUGE_HEIGHT_M,
            cant_rad: t.cant_rad,
            ..Default::default()
        }),
        wheelset: Some(pb::WheelsetSpec {
            flange_back_distance_m: w.flange_back_distance_m,
            nominal_radius_m: w.nominal_radius_m,
            flange_back_y_m: w.flange_back_y_m,
        }),
        ..Default::default()
    }
}

/// The built-in pair's registration.
pub fn builtin_registration() -> pb::RegisterProfilePairRequest {
    pb::RegisterProfilePairRequest {
        pair: Some(pb::register_profile_pair_request::Pair::BuiltinPair(
            BUILTIN_PAIR.into(),
        )),
        label: String::new(),
    }
}

/// A profile source with built-in profiles replaced by their content;
/// field paths under `field`.
/// Checks a profile file's name (required, at most
/// [`MAX_FILE_NAME_CHARS`]) and format; field paths under `field`.
fn check_file(f: &pb::ProfileFile, field: &str) -> Result<(), ServiceError> {
    if f.file_name.trim().is_empty() {
        return Err(ServiceError::invalid(
            format!("{field}.file_name"),
            "missing: the file name tells rail from wheel and is named in messages",
        ));
    }
    let chars = f.file_name.chars().count();
    if chars > MAX_FILE_NAME_CHARS {
        return Err(ServiceError::invalid(
            format!("{field}.file_name"),
            format!("has {chars} characters, more than {MAX_FILE_NAME_CHARS}"),
        ));
    }
    load_format(f.format, &format!("{field}.format"))?;
    plain_unit(f.plain_unit, field)?;
    Ok(())
}

/// Rail slices in canonical form (profiles ordered by name, each once);
/// field paths under `field` (`spec.rail.slices`).
fn canonical_slices(sl: &pb::RailSlices, field: &str) -> Result<pb::RailSlices, ServiceError> {
    check_file(
        &pb::ProfileFile {
            file_name: sl.file_name.clone(),
            ..Default::default()
        },
        field,
    )?;
    if !is_slices_file(&sl.file_name) {
        return Err(ServiceError::invalid(
            format!("{field}.file_name"),
            format!(
                "{}: a rail slices file's name ends in .slcs",
                quote(&sl.file_name)
            ),
        ));
    }
    for (k, f) in sl.profiles.iter().enumerate() {
        check_file(f, &format!("{field}.profiles[{k}]"))?;
    }
    let mut profiles = sl.profiles.clone();
    profiles.sort_by(|a, b| a.file_name.cmp(&b.file_name));
    if let Some(w) = profiles
        .windows(2)
        .find(|w| w[0].file_name == w[1].file_name)
    {
        return Err(ServiceError::invalid(
            format!("{field}.profiles"),
            format!("{} is given twice", quote(&w[0].file_name)),
        ));
    }
    Ok(pb::RailSlices {
        file_name: sl.file_name.clone(),
        content: sl.content.clone(),
        profiles,
    })
}

fn canonical_source(
    src: Option<&pb::ProfileSource>,
    field: &str,
    kind: ProfileKind,
) -> Result<pb::ProfileSource, ServiceError> {
    use pb::profile_source::Source;
    let src = src.ok_or_else(|| ServiceError::invalid(field, "missing"))?;
    let file = match &src.source {
        Some(Source::Slices(sl)) => {
            let slices_field = format!("{field}.slices");
            if kind != ProfileKind::Rail {
                return Err(ServiceError::invalid(
                    slices_field,
                    "slices make a rail varying along the track: give a wheel profile `file` \
                     or `builtin_name`",
                ));
            }
            return Ok(pb::ProfileSource {
                source: Some(Source::Slices(canonical_slices(sl, &slices_field)?)),
                mirror_y: src.mirror_y,
            });
        }
        None => {
            return Err(ServiceError::invalid(
                field,
                "missing: give `file` or `builtin_name`",
            ))
        }
        Some(Source::BuiltinName(name)) => {
            let (n, content) = builtin::FILES
                .iter()
                .find(|(n, _)| n == name)
                .ok_or_else(|| {
                    let names: Vec<&str> = builtin::FILES.iter().map(|(n, _)| *n).collect();
                    ServiceError::invalid(
                        format!("{field}.builtin_name"),
                        format!(
                            "no built-in profile '{}' (there are: {})",
                            quote(name),
                            names.join(", ")
                        ),
                    )
                })?;
            pb::ProfileFile {
                format: pb::ProfileFormat::Unspecified as i32,
                content: content.to_string(),
                file_name: n.to_string(),
                plain_unit: pb::LengthUnit::Unspecified as i32,
            }
        }
        Some(Source::File(f)) => {
            check_file(f, &format!("{field}.file"))?;
            f.clone()
        }
    };
    Ok(pb::ProfileSource {
        source: Some(Source::File(file)),
        mirror_y: src.mirror_y,
    })
}

/// The reader format of a wire format (`None`: detect).
fn load_format(format: i32, field: &str) -> Result<Option<ProfileFormat>, ServiceError> {
    match pb::ProfileFormat::try_from(format) {
        Ok(pb::ProfileFormat::Unspecified) => Ok(None),
        Ok(pb::ProfileFormat::Simpack) => Ok(Some(ProfileFormat::Simpack)),
        // The variant is always taken from the content.
        Ok(pb::ProfileFormat::Miniprof) => Ok(Some(ProfileFormat::MiniProf(MiniProfVariant::Text))),
        Ok(pb::ProfileFormat::Plain) => Ok(Some(ProfileFormat::Plain)),
        Err(_) => Err(ServiceError::invalid(
            field,
            format!("unknown profile format {format}"),
        )),
    }
}

/// A profile file's `plain_unit` (errors at `field.plain_unit`).
fn plain_unit(unit: i32, field: &str) -> Result<Option<LengthUnit>, ServiceError> {
    match pb::LengthUnit::try_from(unit) {
        Ok(pb::LengthUnit::Unspecified) => Ok(None),
        Ok(pb::LengthUnit::M) => Ok(Some(LengthUnit::Metre)),
        Ok(pb::LengthUnit::Mm) => Ok(Some(LengthUnit::Millimetre)),
        Err(_) => Err(ServiceError::invalid(
            format!("{field}.plain_unit"),
            format!("unknown length unit {unit}"),
        )),
    }
}

fn cli_material(m: &pb::MaterialSection) -> MaterialSection {
    let body = |b: &pb::Material| Material {
        shear_modulus_pa: b.shear_modulus_pa,
        poisson_ratio: b.poisson_ratio,
    };
    MaterialSection {
        shear_modulus_pa: m.shear_modulus_pa,
        poisson_ratio: m.poisson_ratio,
        body1: m.body1.as_ref().map(body),
        body2: m.body2.as_ref().map(body),
        influence_file: None,
    }
}

/// The checked friction of a wire friction section for wheel/rail
/// contact; keys `friction.*`
/// ([`crate::problem::case::FrictionSection::wheelrail_friction`]).
pub fn friction(f: &pb::FrictionSection) -> Result<Friction, ServiceError> {
    Ok(convert::friction_section(f)?.wheelrail_friction()?)
}

/// Checks an element size \[m\] (the wheel/rail solver's range).
pub fn check_element_size(e: f64, field: &str) -> Result<(), ServiceError> {
    if e.is_finite() && e > 1e-6 && e < 5e-3 {
        Ok(())
    } else {
        Err(ServiceError::invalid(
            field,
            format!("must be between 1e-6 and 5e-3 m, got {e}"),
        ))
    }
}

/// Checks a registration and puts it in canonical form. Field paths are
/// those of the request (`spec.track.gauge_m`, `builtin_pair`).
pub fn canonicalize(req: &pb::RegisterProfilePairRequest) -> Result<PairSpec, ServiceError> {
    use pb::register_profile_pair_request::Pair;
    let (spec, builtin_pair, prefix) = match &req.pair {
        None => {
            return Err(ServiceError::invalid(
                "pair",
                "missing: give `spec` or `builtin_pair`",
            ))
        }
        Some(Pair::BuiltinPair(name)) if name == BUILTIN_PAIR => {
            (builtin_spec(), Some(BUILTIN_PAIR), "builtin_pair")
        }
        Some(Pair::BuiltinPair(name)) => {
            return Err(ServiceError::invalid(
                "builtin_pair",
                format!(
                    "no built-in pair '{}' (there is: {BUILTIN_PAIR})",
                    quote(name)
                ),
            ))
        }
        Some(Pair::Spec(s)) => (s.clone(), None, "spec"),
    };
    let f = |name: &str| format!("{prefix}.{name}");
    check_ranges(&spec, &f)?;
    let wheel = canonical_source(spec.wheel.as_ref(), &f("wheel"), ProfileKind::Wheel)?;
    let rail = canonical_source(spec.rail.as_ref(), &f("rail"), ProfileKind::Rail)?;
    let left = |s: Option<&pb::ProfileSource>, right: &pb::ProfileSource, name, kind| {
        s.map(|s| canonical_source(Some(s), &f(name), kind))
            .transpose()
            .map(|l| l.filter(|l| l != right))
    };
    let wheel_left = left(
        spec.wheel_left.as_ref(),
        &wheel,
        "wheel_left",
        ProfileKind::Wheel,
    )?;
    let rail_left = left(
        spec.rail_left.as_ref(),
        &rail,
        "rail_left",
        ProfileKind::Rail,
    )?;
    let material = spec.material.unwrap_or(pb::MaterialSection {
        shear_modulus_pa: Some(DEFAULT_SHEAR_MODULUS_PA),
        poisson_ratio: Some(DEFAULT_POISSON_RATIO),
        ..Default::default()
    });
    let combined = cli_material(&material)
        .combine()
        .map_err(|e| ServiceError::from(e).within(prefix))?;
    let friction_section = spec.friction.unwrap_or(pb::FrictionSection {
        coefficient: Some(DEFAULT_FRICTION),
        ..Default::default()
    });
    let friction = friction(&friction_section).map_err(|e| e.within(prefix))?;
    let element_size_m = spec
        .grid
        .and_then(|g| g.element_size_m)
        .unwrap_or(DEFAULT_ELEMENT_SIZE_M);
    check_element_size(element_size_m, &f("grid.element_size_m"))?;
    let smoothing_wavelength_m = spec
        .smoothing_wavelength_m
        .unwrap_or(DEFAULT_SMOOTHING_WAVELENGTH_M);
    let track = canonical_track(
        spec.track
            .ok_or_else(|| ServiceError::invalid(f("track"), "missing"))?,
    );
    let track_data = track_data(&track).map_err(|e| e.within(&f("track")))?;
    let wheelset = spec
        .wheelset
        .ok_or_else(|| ServiceError::invalid(f("wheelset"), "missing"))?;
    let canonical = pb::ProfilePairSpec {
        wheel: Some(wheel),
        rail: Some(rail),
        material: Some(material),
        friction: Some(friction_section),
        grid: Some(pb::WheelRailGrid {
            element_size_m: Some(element_size_m),
        }),
        wheel_left,
        rail_left,
        track: Some(track),
        wheelset: Some(wheelset),
        smoothing_wavelength_m: Some(smoothing_wavelength_m),
    };
    let id = id_of(&canonical);
    let label = if req.label.is_empty() && builtin_pair.is_some() {
        "Manchester benchmark: S1002 wheel on UIC60 rail".to_string()
    } else {
        req.label.clone()
    };
    Ok(PairSpec {
        id,
        canonical,
        label,
        builtin_pair,
        settings: PairSettings {
            material: combined,
            friction,
            element_size_m,
            smoothing_wavelength_m,
            track: track_data,
            wheelset: WheelsetData {
                flange_back_distance_m: wheelset.flange_back_distance_m,
                nominal_radius_m: wheelset.nominal_radius_m,
                flange_back_y_m: wheelset.flange_back_y_m,
            },
        },
    })
}

/// The id of a canonical spec: 32 hex digits of the SHA-256 of the tag and
/// its encoding.
fn id_of(canonical: &pb::ProfilePairSpec) -> String {
    let mut hasher = Sha256::new();
    hasher.update(ID_TAG);
    hasher.update(canonical.encode_to_vec());
    let digest = hasher.finalize();
    digest[..16].iter().map(|b| format!("{b:02x}")).collect()
}

/// A pair ready to solve on.
pub struct PreparedPair {
    /// The placed profiles (of a rail given as slices: its profile at the
    /// slices' first position).
    pub pair: WheelRailPair,
    /// A rail varying along the track: what places it at each solve's
    /// position.
    varying: Option<VaryingRails>,
    /// Wheel, rail, left wheel, left rail (when different).
    summaries: [Option<pb::ProfileSummary>; 4],
    /// Preparation time [s].
    prepare_time_s: f64,
    /// Heap memory of `pair` \[bytes\].
    pair_bytes: usize,
    /// The contact table: built at registration, or on first use (pairs
    /// restored after a restart).
    table: tokio::sync::OnceCell<Arc<ContactTable>>,
    /// Heap memory of `table` once built \[bytes\], counted on the pool
    /// where it is built.
    table_bytes: OnceLock<usize>,
}

/// A pair whose rails (one or both) vary along the track: the slices and
/// the profiles, placed again at each solve's position
/// ([`PreparedPair::pair_at`]).
struct VaryingRails {
    /// The rails' slices (`[left, right]`; `None`: a fixed rail).
    slices: [Option<Arc<RailSlices>>; 2],
    /// The rails (a varying one's at its first slice) and wheels as read.
    rails: [Profile; 2],
    wheels: [Profile; 2],
    /// The pair's track, wheelset and smoothing.
    track: TrackData,
    wheelset: WheelsetData,
    smoothing_wavelength_m: f64,
}

/// The memory of a profile's points, weights and source lines \[bytes\].
fn profile_bytes(p: &Profile) -> usize {
    p.len() * (std::mem::size_of::<[f64; 2]>() + 8 + std::mem::size_of::<Option<usize>>())
}

/// The memory of a rail's slices: each slice's points along the
/// interpolation paths and their second derivatives, and its position
/// \[bytes\].
fn slices_bytes(s: &RailSlices) -> usize {
    s.slice_positions_m().len() * (s.points_per_slice() * 2 * std::mem::size_of::<[f64; 2]>() + 8)
}

impl VaryingRails {
    fn bytes(&self) -> usize {
        let slices = match &self.slices {
            [Some(l), Some(r)] if Arc::ptr_eq(l, r) => slices_bytes(r),
            [l, r] => [l, r]
                .iter()
                .flat_map(|s| s.as_deref())
                .map(slices_bytes)
                .sum(),
        };
        slices
            + self
                .rails
                .iter()
                .chain(&self.wheels)
                .map(profile_bytes)
                .sum::<usize>()
    }
}

impl PreparedPair {
    /// Memory it holds: itself, the placed profiles, a varying rail's
    /// slices and profiles, and the contact table once built \[bytes\].
    pub fn bytes(&self) -> usize {
        std::mem::size_of::<Self>()
            + self.pair_bytes
            + self.varying.as_ref().map_or(0, VaryingRails::bytes)
            + self.table_bytes.get().copied().unwrap_or(0)
    }

    /// The rails' slices, for the solver input's `rail_slices` (`None`s:
    /// fixed rails).
    pub fn rail_slices(&self) -> [Option<Arc<RailSlices>>; 2] {
        self.varying
            .as_ref()
            .map(|v| v.slices.clone())
            .unwrap_or_default()
    }

    /// The placed pair at the track position `track_s_m` \[m\]: `None` for
    /// fixed rails (the prepared [`PreparedPair::pair`] serves), else the
    /// pair with each varying rail's profile there, shared by content
    /// ([`PairCache`]: a caller that holds it, a session, makes the next
    /// call with the same position cheap). As `railcontact wheelrail`
    /// places a slices rail at its case's `position.track_s_m`; a position
    /// outside the slices is an error naming `position.track_s_m`.
    pub fn pair_at(&self, track_s_m: f64) -> Result<Option<Arc<WheelRailPair>>, WheelRailError> {
        let Some(v) = &self.varying else {
            return Ok(None);
        };
        let at = |k: usize| match &v.slices[k] {
            Some(s) => s
                .profile_at(track_s_m)
                .map_err(|e| WheelRailError::Invalid {
                    key: "position.track_s_m".into(),
                    message: e.to_string(),
                }),
            None => Ok(v.rails[k].clone()),
        };
        let rails = [at(0)?, at(1)?];
        PairCache::global()
            .get_or_build(
                [&rails[0], &rails[1]],
                [&v.wheels[0], &v.wheels[1]],
                v.track,
                v.wheelset,
                &SplineOptions::smoothing(v.smoothing_wavelength_m),
            )
            .map(Some)
    }

    /// The pair's contact table (default grid), built on the pool on the
    /// first call; concurrent first calls build it once.
    async fn table(&self, admission: &Admission) -> Result<Arc<ContactTable>, ServiceError> {
        // A table is of one prismatic rail: none is built for a rail varying
        // along the track (whose solves refuse the table's model anyway).
        if self.varying.is_some() {
            return Err(ServiceError::invalid(
                "model",
                "a contact table (model hertz_fastsim_table) is built for a prismatic rail, \
                 not a rail given as slices",
            ));
        }
        self.table
            .get_or_try_init(|| async {
                let pair = self.pair.clone();
                admission
                    .run(move || {
                        let t = ContactTable::build(&pair, &TableSettings::default())?;
                        tracing::info!(
                            seconds = t.build_time_s(),
                            nodes = t.node_count(),
                            "contact table built"
                        );
                        let bytes = t.heap_bytes();
                        Ok::<_, ServiceError>((Arc::new(t), bytes))
                    })
                    .await
                    .and_then(|r| r)
                    .map(|(t, bytes)| {
                        let _ = self.table_bytes.set(bytes);
                        t
                    })
            })
            .await
            .cloned()
    }
}

/// Stages of a preparation, for progress messages.
pub type Progress = dyn Fn(pb::RegistrationStage, &str) + Send + Sync;

fn file_of(src: &pb::ProfileSource) -> Option<&pb::ProfileFile> {
    match &src.source {
        Some(pb::profile_source::Source::File(f)) => Some(f),
        _ => None,
    }
}

fn is_builtin(f: &pb::ProfileFile) -> bool {
    builtin::FILES
        .iter()
        .any(|(n, c)| *n == f.file_name && *c == f.content)
}

/// The summary of a canonical source, with the profile's details when read.
fn summary(src: &pb::ProfileSource, profile: Option<&Profile>) -> pb::ProfileSummary {
    let file = file_of(src);
    let file_name = match &src.source {
        Some(pb::profile_source::Source::Slices(s)) => s.file_name.clone(),
        _ => file.map(|f| f.file_name.clone()).unwrap_or_default(),
    };
    pb::ProfileSummary {
        file_name,
        builtin: file.is_some_and(is_builtin),
        mirror_y: src.mirror_y,
        format: profile
            .and_then(|p| p.format())
            .map(|f| f.to_string())
            .unwrap_or_default(),
        point_count: profile.map_or(0, |p| p.len() as u32),
        warnings: profile
            .map(|p| {
                p.warnings()
                    .iter()
                    .map(|w| format!("{}: {}", w.at, w.message))
                    .collect()
            })
            .unwrap_or_default(),
    }
}

/// The limit on the points of one profile, for [`prepare_with`].
#[derive(Clone, Copy)]
pub struct PointLimit<'a> {
    /// Most points of one profile (`max_profile_points`).
    pub max_points: usize,
    /// Told when the limit refuses a profile.
    pub metrics: Option<&'a Metrics>,
}

/// Reads one profile file as `kind`, mirrored in y when `mirror_y`, of at
/// most `limit` points; errors at `field`.
fn read_file(
    f: &pb::ProfileFile,
    mirror_y: bool,
    kind: ProfileKind,
    field: &str,
    limit: PointLimit,
) -> Result<Profile, ServiceError> {
    let options = LoadOptions {
        kind: Some(kind),
        format: load_format(f.format, field)?,
        mirror_y,
        plain_unit: plain_unit(f.plain_unit, field)?,
        ..LoadOptions::default()
    };
    if is_slices_file(&f.file_name) {
        return Err(ServiceError::invalid(
            field,
            format!(
                "{}: a rail slices file (a rail varying along the track) is not a profile: \
                 give it as the rail's `slices` with the profile files it names",
                quote(&f.file_name)
            ),
        ));
    }
    let p = parse_profile(&f.content, &f.file_name, &options)
        .map_err(|e| ServiceError::profile(field, &e))?;
    if p.len() > limit.max_points {
        if let Some(m) = limit.metrics {
            m.registration_refused("max_profile_points");
        }
        return Err(ServiceError::invalid(
            field,
            format!(
                "{}: {} points, more than this server's limit of {} a profile \
                 (max_profile_points)",
                quote(&f.file_name),
                p.len(),
                limit.max_points
            ),
        ));
    }
    Ok(p)
}

/// Reads one canonical profile source as `kind`; errors at `field`.
fn read(
    src: &pb::ProfileSource,
    kind: ProfileKind,
    field: &str,
    limit: PointLimit,
) -> Result<Profile, ServiceError> {
    let f = file_of(src)
        .ok_or_else(|| ServiceError::Internal(format!("{field}: not in canonical form")))?;
    read_file(f, src.mirror_y, kind, field, limit)
}

/// The bounds on a slices file read from a client, for a server of
/// `max_profile_points`: [`MAX_RAIL_SLICES`] slices, `max_profile_points`
/// along each interpolation path, [`SLICES_POINTS_PER_PROFILE_POINTS`]
/// times that in the surface.
pub fn slices_limits(max_profile_points: usize) -> SlicesLimits {
    SlicesLimits {
        max_slices: MAX_RAIL_SLICES,
        max_path_points: max_profile_points,
        max_surface_points: max_profile_points.saturating_mul(SLICES_POINTS_PER_PROFILE_POINTS),
    }
}

/// Reads a rail given as slices (`sl`, canonical), each distinct profile
/// file once, within this server's limits: [`MAX_RAIL_SLICES`] slices,
/// each profile within `limit`, the points read and the surface's within
/// [`SLICES_POINTS_PER_PROFILE_POINTS`] x `limit`. Errors at
/// `field.slices` (a profile's at `field.slices.profiles[k]`).
fn read_slices(
    sl: &pb::RailSlices,
    mirror_y: bool,
    field: &str,
    limit: PointLimit,
) -> Result<RailSlices, ServiceError> {
    let field = format!("{field}.slices");
    let max_points = limit
        .max_points
        .saturating_mul(SLICES_POINTS_PER_PROFILE_POINTS);
    let mut parsed: BTreeMap<usize, Profile> = BTreeMap::new();
    let mut points_read = 0usize;
    // A profile's own error, with its field, passes the slices reader as
    // text; the first is kept to be returned as it is.
    let mut first: Option<ServiceError> = None;
    let slices = parse_slices_within(
        &sl.content,
        &sl.file_name,
        |name| {
            let k = sl
                .profiles
                .iter()
                .position(|f| f.file_name == name)
                .ok_or_else(|| ProfileError::Format {
                    at: SourceLocation::new(name, None),
                    message: "not among the slices' profiles given (RailSlices.profiles)".into(),
                })?;
            // Every slice holds its profile while the slices are read.
            let mut count = |p: &Profile, first: &mut Option<ServiceError>| {
                points_read += p.len();
                if points_read <= max_points {
                    return Ok(());
                }
                let e = ServiceError::invalid(
                    format!("{field}.profiles[{k}]"),
                    format!(
                        "the slices' profiles hold {points_read} points or more, more than \
                         this server's limit of {max_points} ({SLICES_POINTS_PER_PROFILE_POINTS} \
                         x max_profile_points)"
                    ),
                );
                let message = e.to_string();
                first.get_or_insert(e);
                Err(ProfileError::Format {
                    at: SourceLocation::new(name, None),
                    message,
                })
            };
            if let Some(p) = parsed.get(&k) {
                count(p, &mut first)?;
                return Ok(p.clone());
            }
            let pfield = format!("{field}.profiles[{k}]");
            let refuse = |e: ServiceError, first: &mut Option<ServiceError>| {
                let message = e.to_string();
                first.get_or_insert(e);
                ProfileError::Format {
                    at: SourceLocation::new(name, None),
                    message,
                }
            };
            let p = read_file(&sl.profiles[k], mirror_y, ProfileKind::Rail, &pfield, limit)
                .map_err(|e| refuse(e, &mut first))?;
            count(&p, &mut first)?;
            parsed.insert(k, p.clone());
            Ok(p)
        },
        slices_limits(limit.max_points),
    );
    match (slices, first) {
        (Ok(s), _) => Ok(s),
        (Err(_), Some(e)) => Err(e),
        (Err(e), None) => Err(ServiceError::profile(&field, &e)),
    }
}

/// Reads a canonical rail source: a profile, or slices with their profile
/// at their first position (the prepared pair's) and the slices.
fn read_rail(
    src: &pb::ProfileSource,
    field: &str,
    limit: PointLimit,
) -> Result<(Profile, Option<Arc<RailSlices>>), ServiceError> {
    let Some(pb::profile_source::Source::Slices(sl)) = &src.source else {
        return Ok((read(src, ProfileKind::Rail, field, limit)?, None));
    };
    let slices = read_slices(sl, src.mirror_y, field, limit)?;
    let profile = slices
        .profile_at(slices.u_range_m().0)
        .map_err(|e| ServiceError::profile(&format!("{field}.slices"), &e))?;
    Ok((profile, Some(Arc::new(slices))))
}

/// "gauge 1.435 m" or "rail origin at q = 0.2 m, z = 0 m", each number
/// short however small or large ([`show`]).
fn placement(p: &RailPlacement) -> String {
    match *p {
        RailPlacement::GaugePoint { gauge_m, .. } => format!("gauge {} m", show(gauge_m)),
        RailPlacement::Origin { q_m, z_m } => {
            format!("rail origin at q = {} m, z = {} m", show(q_m), show(z_m))
        }
    }
}

/// Solves the pair once, Hertz+FASTSIM on both wheels at the centred
/// position (no shift, yaw or roll given) with [`TRIAL_WHEEL_LOAD_N`] on
/// each: a pair whose profiles do not touch there, or that the contact
/// search cannot solve, is refused before it is called ready.
fn trial_solve(pair: &WheelRailPair, s: &PairSettings) -> Result<(), ServiceError> {
    // 1 m/s: the track's under a rolling wheelset, or a roller rig's
    // surface under a wheelset standing still.
    let (forward_m_per_s, roller_rad_per_s) = match s.track.roller_radius_m {
        Some(r) => (0.0, 1.0 / r),
        None => (1.0, 0.0),
    };
    let input = WheelRailInput {
        position: WheelsetPosition::default(),
        velocity: WheelsetVelocity::rolling(forward_m_per_s),
        load: WheelLoad::VerticalForce(TRIAL_WHEEL_LOAD_N),
        sides: Side::BOTH.to_vec(),
        material: s.material,
        // The trial's Hertz model takes Coulomb's law.
        friction: Friction::coulomb(s.friction.kinetic_coefficient),
        friction_table: None,
        settings: WheelRailSettings {
            model: WheelRailModel::HertzFastsim,
            element_size_m: s.element_size_m,
            ..WheelRailSettings::default()
        },
        total_longitudinal_force_n: None,
        temperature: None,
        rail_motion: [RailMotion {
            roller_rad_per_s,
            ..RailMotion::default()
        }; 2],
        rail_slices: Default::default(),
    };
    let mut scratch = SearchScratch::default();
    let solution =
        solve_wheelset(pair, &input, KernelCache::global(), &mut scratch).map_err(|e| match e {
            WheelRailError::Cancelled => ServiceError::Cancelled,
            e => ServiceError::invalid(
                "spec",
                format!(
                    "the wheels do not make contact with their rails at the centred position \
                     ({}, flange backs {} m apart, flange back at wheel profile y = \
                     {}): {e}; check spec.track, spec.wheelset and the profiles' origins",
                    placement(&s.track.placement),
                    s.wheelset.flange_back_distance_m,
                    s.wheelset
                        .flange_back_y_m
                        .map_or("the profile's smallest y".into(), |y| format!("{y} m")),
                ),
            ),
        })?;
    let carried = solution.wheels.iter().all(|w| {
        w.vertical_approach_m.is_finite()
            && w.patches.iter().map(|p| p.normal_force_n).sum::<f64>() > 0.0
    });
    if carried && solution.center_z_m.is_finite() {
        Ok(())
    } else {
        Err(ServiceError::invalid(
            "spec",
            "the trial solve at the centred position carries no load on a wheel: the profiles \
             do not touch there; check spec.track, spec.wheelset and the profiles' origins",
        ))
    }
}

/// [`prepare_with`] with the default limit on the points of a profile.
pub fn prepare(spec: &PairSpec, progress: &Progress) -> Result<PreparedPair, ServiceError> {
    let limit = PointLimit {
        max_points: ServeConfig::default().max_profile_points,
        metrics: None,
    };
    prepare_with(spec, progress, limit)
}

/// Prepares a pair: reads the profiles (at most `limit` points each),
/// fits and places them, and solves it once at the centred position
/// (`trial_solve`). Field paths of errors are those of a `spec`
/// registration.
pub fn prepare_with(
    spec: &PairSpec,
    progress: &Progress,
    limit: PointLimit,
) -> Result<PreparedPair, ServiceError> {
    let t0 = Instant::now();
    let c = &spec.canonical;
    let missing = || ServiceError::Internal("canonical spec without profiles".into());
    let wheel_src = c.wheel.as_ref().ok_or_else(missing)?;
    let rail_src = c.rail.as_ref().ok_or_else(missing)?;
    let wheel = read(wheel_src, ProfileKind::Wheel, "spec.wheel", limit)?;
    let wheel_left = match &c.wheel_left {
        Some(s) => Some(read(s, ProfileKind::Wheel, "spec.wheel_left", limit)?),
        None => None,
    };
    progress(pb::RegistrationStage::WheelParsed, "wheel profile read");
    let (rail, rail_slices) = read_rail(rail_src, "spec.rail", limit)?;
    let (rail_left, rail_left_slices) = match &c.rail_left {
        Some(s) => {
            let (p, slices) = read_rail(s, "spec.rail_left", limit)?;
            (Some(p), slices)
        }
        None => (None, rail_slices.clone()),
    };
    progress(pb::RegistrationStage::RailParsed, "rail profile read");
    let s = &spec.settings;
    let varying = (rail_slices.is_some() || rail_left_slices.is_some()).then(|| VaryingRails {
        slices: [rail_left_slices, rail_slices],
        rails: [
            rail_left.clone().unwrap_or_else(|| rail.clone()),
            rail.clone(),
        ],
        wheels: [
            wheel_left.clone().unwrap_or_else(|| wheel.clone()),
            wheel.clone(),
        ],
        track: s.track,
        wheelset: s.wheelset,
        smoothing_wavelength_m: s.smoothing_wavelength_m,
    });
    let pair = WheelRailPair::new(
        [rail_left.as_ref().unwrap_or(&rail), &rail],
        [wheel_left.as_ref().unwrap_or(&wheel), &wheel],
        s.track,
        s.wheelset,
        &SplineOptions::smoothing(s.smoothing_wavelength_m),
    )
    .map_err(|e| match e {
        // The case file's profile keys are the spec's sources.
        WheelRailError::Invalid { key, message } => {
            let field = match key.as_str() {
                "track.rail_profile" => "spec.rail".to_string(),
                "wheelset.wheel_profile" => "spec.wheel".to_string(),
                _ => format!("spec.{key}"),
            };
            ServiceError::invalid(field, message)
        }
        other => ServiceError::invalid("spec", other.to_string()),
    })?;
    trial_solve(&pair, s)?;
    let prepare_time_s = t0.elapsed().as_secs_f64();
    progress(
        pb::RegistrationStage::Placed,
        &format!(
            "profiles smoothed and placed in {:.1} ms",
            prepare_time_s * 1e3
        ),
    );
    let summaries = [
        Some(summary(wheel_src, Some(&wheel))),
        Some(summary(rail_src, Some(&rail))),
        c.wheel_left
            .as_ref()
            .map(|s| summary(s, wheel_left.as_ref())),
        c.rail_left.as_ref().map(|s| summary(s, rail_left.as_ref())),
    ];
    Ok(PreparedPair {
        pair_bytes: pair.heap_bytes(),
        pair,
        varying,
        summaries,
        prepare_time_s,
        table: tokio::sync::OnceCell::new(),
        table_bytes: OnceLock::new(),
    })
}

/// One registered pair.
pub struct PairEntry {
    /// Its registration (for a damaged record, a placeholder with the
    /// record's id: see `PairEntry::damaged`).
    pub spec: PairSpec,
    /// The prepared pair, while the registry holds it.
    held: Mutex<Held>,
    /// One preparation at a time.
    preparing: tokio::sync::Mutex<()>,
    /// Set at the first preparation: READY, and what `info` reports even
    /// when the registry has let the prepared pair go.
    ready: OnceLock<ReadyInfo>,
    /// When it was last used, on the registry's clock.
    last_used: AtomicU64,
    persisted: AtomicBool,
    /// Restored from the store (not registered in this run).
    restored: bool,
    failure: Mutex<Option<String>>,
    /// Why its stored record cannot be used (damaged, or invalid in this
    /// version): it is FAILED, never prepared and never served.
    broken: Option<String>,
    /// Whether its stored record is damaged.
    damaged: bool,
}

impl PairEntry {
    fn new(spec: PairSpec, restored: bool) -> Self {
        Self {
            spec,
            held: Mutex::new(Held::default()),
            preparing: tokio::sync::Mutex::new(()),
            ready: OnceLock::new(),
            last_used: AtomicU64::new(0),
            persisted: AtomicBool::new(restored),
            restored,
            failure: Mutex::new(None),
            broken: None,
            damaged: false,
        }
    }

    /// The entry of a stored record under `id` that cannot be used, or is
    /// damaged (`damaged`), for `reason`: FAILED, never served, listed with
    /// the reason until it is registered again or deleted.
    fn failed(id: &str, reason: String, damaged: bool) -> Result<Self, ServiceError> {
        // The placeholder's settings are the built-in pair's; they are never
        // used, since the entry is never prepared.
        let mut spec = canonicalize(&builtin_registration())?;
        spec.id = id.to_string();
        spec.canonical = pb::ProfilePairSpec::default();
        spec.label = String::new();
        spec.builtin_pair = None;
        Ok(Self {
            failure: Mutex::new(Some(reason.clone())),
            broken: Some(reason),
            damaged,
            ..Self::new(spec, true)
        })
    }

    /// Whether the pair has been prepared (it is READY, even when the
    /// registry has let the prepared pair go since).
    pub fn is_ready(&self) -> bool {
        self.ready.get().is_some()
    }

    fn held(&self) -> std::sync::MutexGuard<'_, Held> {
        self.held.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// The prepared pair if the registry holds it, or a session still
    /// holds it (then the registry holds it again).
    fn current(&self) -> Option<Arc<PreparedPair>> {
        let mut held = self.held();
        if held.pair.is_none() {
            held.pair = held.released.upgrade();
        }
        held.pair.clone()
    }

    /// Whether its stored record is damaged.
    pub fn is_damaged(&self) -> bool {
        self.damaged
    }

    /// The wire description.
    pub fn info(&self) -> pb::ProfilePairInfo {
        let c = &self.spec.canonical;
        let prepared = self.ready.get();
        let failure = self
            .failure
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .clone();
        let state = match (prepared, &failure) {
            (Some(_), _) => pb::ProfilePairState::Ready,
            (None, Some(_)) => pb::ProfilePairState::Failed,
            (None, None) if self.restored => pb::ProfilePairState::Stored,
            (None, None) => pb::ProfilePairState::Preparing,
        };
        let summaries = match prepared {
            Some(p) => p.summaries.clone(),
            None => [
                c.wheel.as_ref().map(|s| summary(s, None)),
                c.rail.as_ref().map(|s| summary(s, None)),
                c.wheel_left.as_ref().map(|s| summary(s, None)),
                c.rail_left.as_ref().map(|s| summary(s, None)),
            ],
        };
        let [wheel, rail, wheel_left, rail_left] = summaries;
        pb::ProfilePairInfo {
            pair_id: self.spec.id.clone(),
            label: self.spec.label.clone(),
            builtin_pair: self.spec.builtin_pair.unwrap_or_default().to_string(),
            state: state as i32,
            error: failure.unwrap_or_default(),
            wheel,
            rail,
            wheel_left,
            rail_left,
            track: c.track,
            wheelset: c.wheelset,
            material: c.material.clone(),
            friction: c.friction.clone(),
            element_size_m: self.spec.settings.element_size_m,
            smoothing_wavelength_m: self.spec.settings.smoothing_wavelength_m,
            prepare_time_s: prepared.map_or(0.0, |p| p.prepare_time_s),
            persisted: self.persisted.load(Ordering::Relaxed),
        }
    }
}

/// What a pair's first preparation found, kept while the pair is
/// registered.
struct ReadyInfo {
    summaries: [Option<pb::ProfileSummary>; 4],
    prepare_time_s: f64,
}

/// A pair's prepared state: held by the registry, or let go (then only
/// sessions that still use it keep it alive).
#[derive(Default)]
struct Held {
    pair: Option<Arc<PreparedPair>>,
    released: Weak<PreparedPair>,
}

/// Limits and policies of the registry, from the server settings.
#[derive(Debug, Clone, Copy)]
pub struct RegistryLimits {
    /// Most registered pairs, the built-in one not counted.
    pub max_pairs: usize,
    /// Most points of one profile.
    pub max_profile_points: usize,
    /// Most encoded bytes of the registrations held (in the store, or in
    /// memory without one).
    pub max_store_bytes: u64,
    /// Most memory of the prepared pairs held.
    pub max_prepared_bytes: u64,
    /// What a start does with damaged records.
    pub store_damaged: StoreDamaged,
}

impl RegistryLimits {
    /// The limits of `config`.
    pub fn of(config: &ServeConfig) -> Self {
        Self {
            max_pairs: config.max_profile_pairs,
            max_profile_points: config.max_profile_points,
            max_store_bytes: config.max_store_bytes,
            max_prepared_bytes: config.max_prepared_bytes,
            store_damaged: config.store_damaged,
        }
    }
}

/// The registered pairs and their store.
pub struct PairRegistry {
    entries: RwLock<BTreeMap<String, Arc<PairEntry>>>,
    store: Mutex<Option<PairStore>>,
    limits: RegistryLimits,
    metrics: Arc<Metrics>,
    /// Ticks at each use of a prepared pair, for least-recently-used.
    clock: AtomicU64,
}

/// Why a stored record under `id` cannot be served: it cannot be decoded,
/// it is not a canonical registration, or its content no longer hashes to
/// its id. `None`: intact.
fn damage(id: &str, record: &Result<pb::RegisterProfilePairRequest, String>) -> Option<String> {
    use pb::register_profile_pair_request::Pair;
    match record {
        Err(e) => Some(e.clone()),
        Ok(r) => match &r.pair {
            Some(Pair::Spec(c)) if id_of(c) == id => None,
            Some(Pair::Spec(c)) => Some(format!(
                "its content no longer matches its id (the content hashes to {}): the record \
                 was damaged or edited",
                id_of(c)
            )),
            _ => Some("not a canonical registration".into()),
        },
    }
}

impl PairRegistry {
    /// The bounds on the slices files clients send this server
    /// ([`slices_limits`] of its `max_profile_points`).
    pub fn slices_limits(&self) -> SlicesLimits {
        slices_limits(self.limits.max_profile_points)
    }

    /// A registry persisting into `store` (none: memory only) with the
    /// stored registrations restored (state STORED). Each record is checked:
    /// one that cannot be decoded, or whose content does not hash to its id,
    /// is damaged; one that is no longer valid cannot be used. Both become
    /// FAILED entries with the reason (logged as errors; damaged ones
    /// counted in `railcontact_store_damaged_records`), never served; with
    /// `store_damaged = "fail"` a damaged record stops the start instead.
    pub fn open(
        store: Option<PairStore>,
        limits: RegistryLimits,
        metrics: Arc<Metrics>,
    ) -> std::io::Result<Self> {
        let mut entries = BTreeMap::new();
        let mut damaged = Vec::new();
        if let Some(s) = &store {
            let path = s.path().display().to_string();
            for (id, record) in s.load_all().map_err(std::io::Error::other)? {
                let entry = match (damage(&id, &record), record) {
                    (Some(reason), _) => {
                        tracing::error!(pair_id = %crate::service::escaped(&id), store = %path, reason = %crate::service::escaped(&reason), "stored profile pair is damaged: listed as FAILED, never served; register it again or delete it");
                        damaged.push(format!("{}: {reason}", quote(&id)));
                        let reason = format!("the stored record is damaged: {reason}; register the pair again or delete it");
                        PairEntry::failed(&id, reason, true)
                    }
                    (None, Ok(reg)) => match canonicalize(&reg) {
                        Ok(mut spec) => {
                            if spec.id != id {
                                tracing::warn!(pair_id = %crate::service::escaped(&id), now = %spec.id, "stored profile pair has another id under this version; kept under its stored id");
                                spec.id = id.clone();
                            }
                            Ok(PairEntry::new(spec, true))
                        }
                        Err(e) => {
                            tracing::error!(pair_id = %crate::service::escaped(&id), error = %crate::service::escaped(&e.to_string()), "stored profile pair is not valid in this version: listed as FAILED, never served");
                            let reason = format!("the stored registration is not valid in this version: {e}; register the pair again or delete it");
                            PairEntry::failed(&id, reason, false)
                        }
                    },
                    (None, Err(_)) => unreachable!("an undecodable record is damaged"),
                };
                entries.insert(id, Arc::new(entry.map_err(std::io::Error::other)?));
            }
            if !damaged.is_empty() && limits.store_damaged == StoreDamaged::Fail {
                return Err(std::io::Error::other(format!(
                    "profile pair store {path}: {} damaged record{} ({}); not starting \
                     (store_damaged = \"fail\"). Restore the file from a backup, or start with \
                     store_damaged = \"start\" to serve the other pairs and then delete or \
                     register again the damaged ones",
                    damaged.len(),
                    if damaged.len() == 1 { "" } else { "s" },
                    damaged.join("; ")
                )));
            }
            tracing::info!(
                store = %path,
                pairs = entries.len(),
                damaged = damaged.len(),
                bytes = s.bytes(),
                "profile pairs restored from the store"
            );
        }
        metrics.store_damaged_records(damaged.len() as u64);
        Ok(Self {
            entries: RwLock::new(entries),
            store: Mutex::new(store),
            limits,
            metrics,
            clock: AtomicU64::new(0),
        })
    }

    fn read(&self) -> std::sync::RwLockReadGuard<'_, BTreeMap<String, Arc<PairEntry>>> {
        self.entries.read().unwrap_or_else(|e| e.into_inner())
    }

    fn write(&self) -> std::sync::RwLockWriteGuard<'_, BTreeMap<String, Arc<PairEntry>>> {
        self.entries.write().unwrap_or_else(|e| e.into_inner())
    }

    fn store(&self) -> std::sync::MutexGuard<'_, Option<PairStore>> {
        self.store.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Tells the metrics how many damaged records the registry holds.
    fn count_damaged(&self, entries: &BTreeMap<String, Arc<PairEntry>>) {
        let n = entries.values().filter(|e| e.damaged).count();
        self.metrics.store_damaged_records(n as u64);
    }

    /// The pair with this id, or the built-in pair of this name.
    pub fn lookup(&self, id: &str) -> Result<Arc<PairEntry>, ServiceError> {
        let entries = self.read();
        entries
            .get(id)
            .or_else(|| {
                entries
                    .values()
                    .find(|e| e.spec.builtin_pair == Some(id))
            })
            .cloned()
            .ok_or_else(|| {
                ServiceError::NotFound(format!(
                    "no profile pair '{}' on this server: register it first (ListProfilePairs lists the pairs)",
                    quote(id)
                ))
            })
    }

    /// Every pair, by id.
    pub fn list(&self) -> Vec<Arc<PairEntry>> {
        self.read().values().cloned().collect()
    }

    fn refuse(&self, limit: &'static str, message: String) -> ServiceError {
        self.metrics.registration_refused(limit);
        ServiceError::Exhausted(message)
    }

    /// The entry of `spec`: the existing one (true) or a new one in state
    /// PREPARING (false). A stored record that could not be used is
    /// replaced by the new registration. A new pair beyond
    /// `max_profile_pairs`, or whose registration would take the
    /// registrations held (in the store, or in memory without one) beyond
    /// `max_store_bytes`, gets RESOURCE_EXHAUSTED (the built-in pair is not
    /// counted).
    pub fn begin(&self, spec: PairSpec) -> Result<(Arc<PairEntry>, bool), ServiceError> {
        let store = self.store();
        let mut entries = self.write();
        if let Some(e) = entries.get(&spec.id).filter(|e| e.broken.is_none()) {
            return Ok((e.clone(), true));
        }
        let replaced = entries.remove(&spec.id);
        let limits = self.limits;
        let refused = if spec.builtin_pair.is_some() {
            None
        } else if entries
            .values()
            .filter(|e| e.spec.builtin_pair.is_none())
            .count()
            >= limits.max_pairs
        {
            Some(self.refuse(
                "max_profile_pairs",
                format!(
                    "this server holds its limit of {} registered profile pairs \
                     (max_profile_pairs): delete one first (DeleteProfilePair)",
                    limits.max_pairs
                ),
            ))
        } else {
            // The registrations held: the store's records plus those not
            // written yet, or without a store every registration in memory.
            let held: u64 = entries
                .values()
                .filter(|e| {
                    e.spec.builtin_pair.is_none()
                        && (store.is_none() || !e.persisted.load(Ordering::Relaxed))
                })
                .map(|e| e.spec.registration().encoded_len() as u64)
                .sum();
            let size = spec.registration().encoded_len() as u64;
            let total = store.as_ref().map_or(0, |s| s.bytes()) + held + size;
            let whose = match store.as_ref() {
                Some(_) => "the profile pair store",
                None => "the registrations this server holds in memory",
            };
            (total > limits.max_store_bytes).then(|| {
                self.refuse(
                    "max_store_bytes",
                    format!(
                        "the registration ({size} bytes) would take {whose} to {total} bytes, \
                         more than the limit of {} (max_store_bytes): delete pairs first \
                         (DeleteProfilePair)",
                        limits.max_store_bytes
                    ),
                )
            })
        };
        if let Some(e) = refused {
            if let Some(old) = replaced {
                entries.insert(old.spec.id.clone(), old);
            }
            return Err(e);
        }
        let e = Arc::new(PairEntry::new(spec, false));
        entries.insert(e.spec.id.clone(), e.clone());
        self.count_damaged(&entries);
        Ok((e, false))
    }

    /// Removes an entry whose first preparation failed.
    pub fn abandon(&self, entry: &Arc<PairEntry>) {
        let mut entries = self.write();
        if entries
            .get(&entry.spec.id)
            .is_some_and(|e| Arc::ptr_eq(e, entry) && !e.is_ready())
        {
            entries.remove(&entry.spec.id);
        }
    }

    /// The prepared pair of `entry`, preparing it on `admission`'s worker
    /// if the registry does not hold it (concurrent callers wait for the
    /// one preparation): at first use, or again after the registry let it
    /// go to stay within `max_prepared_bytes`.
    /// A pair alone larger than that limit gets RESOURCE_EXHAUSTED. A
    /// restored pair whose preparation fails gets FAILED_PRECONDITION (the
    /// request did nothing wrong) and state FAILED; so does a stored record
    /// that cannot be used, at once.
    pub async fn prepared(
        &self,
        entry: &Arc<PairEntry>,
        admission: &Admission,
        progress: Arc<Progress>,
    ) -> Result<Arc<PreparedPair>, ServiceError> {
        if let Some(reason) = &entry.broken {
            return Err(ServiceError::precondition(
                "",
                format!("profile pair {}: {reason}", entry.spec.id),
            ));
        }
        if let Some(p) = self.use_held(entry) {
            return Ok(p);
        }
        let _one = entry.preparing.lock().await;
        if let Some(p) = self.use_held(entry) {
            return Ok(p);
        }
        let e = entry.clone();
        let (max_points, metrics) = (self.limits.max_profile_points, self.metrics.clone());
        let r = admission
            .run(move || {
                let limit = PointLimit {
                    max_points,
                    metrics: Some(&metrics),
                };
                prepare_with(&e.spec, &*progress, limit).map(Arc::new)
            })
            .await
            .and_then(|r| r);
        match r {
            Ok(p) => {
                let bytes = p.bytes() as u64;
                if bytes > self.limits.max_prepared_bytes {
                    let (pair, advice) = match entry.spec.builtin_pair {
                        Some(name) => (format!("the built-in pair '{name}'"), "raise the limit"),
                        None => (
                            format!("profile pair {}", entry.spec.id),
                            "register profiles with fewer points, or raise the limit",
                        ),
                    };
                    return Err(ServiceError::Exhausted(format!(
                        "{pair} takes {bytes} bytes prepared, more than the limit of {} for all \
                         prepared pairs (max_prepared_bytes): {advice}",
                        self.limits.max_prepared_bytes
                    )));
                }
                entry.ready.get_or_init(|| ReadyInfo {
                    summaries: p.summaries.clone(),
                    prepare_time_s: p.prepare_time_s,
                });
                entry.held().pair = Some(p.clone());
                self.use_held(entry);
                self.hold_within_budget();
                Ok(p)
            }
            Err(ServiceError::Invalid { field, reason }) if entry.restored => {
                let m = format!(
                    "profile pair {} was restored from the store but cannot be prepared: {field}: {reason}",
                    entry.spec.id
                );
                *entry.failure.lock().unwrap_or_else(|e| e.into_inner()) = Some(m.clone());
                Err(ServiceError::precondition("", m))
            }
            Err(e) => Err(e),
        }
    }

    /// The contact table of `entry`'s `prepared` pair, built on
    /// `admission`'s worker on first use; a
    /// table built now counts against `max_prepared_bytes`.
    pub async fn table(
        &self,
        prepared: &PreparedPair,
        admission: &Admission,
    ) -> Result<Arc<ContactTable>, ServiceError> {
        let built = prepared.table.initialized();
        let t = prepared.table(admission).await?;
        if !built {
            self.hold_within_budget();
        }
        Ok(t)
    }

    /// `entry`'s prepared pair if held (or still alive in a session), as
    /// used now.
    fn use_held(&self, entry: &PairEntry) -> Option<Arc<PreparedPair>> {
        let p = entry.current()?;
        let now = self.clock.fetch_add(1, Ordering::Relaxed) + 1;
        entry.last_used.store(now, Ordering::Relaxed);
        Some(p)
    }

    /// Lets go of the least recently used prepared pairs until those held
    /// take at most `max_prepared_bytes` (a pair let go stays alive while a
    /// session uses it, and is prepared again on its next use otherwise);
    /// tells the metrics.
    fn hold_within_budget(&self) {
        let entries = self.read();
        let mut held: Vec<(u64, usize, &Arc<PairEntry>)> = entries
            .values()
            .filter_map(|e| {
                let bytes = e.held().pair.as_ref()?.bytes();
                Some((e.last_used.load(Ordering::Relaxed), bytes, e))
            })
            .collect();
        held.sort_by_key(|&(used, _, _)| used);
        let mut total: usize = held.iter().map(|&(_, b, _)| b).sum();
        let mut released = 0;
        // The most recently used is kept whatever its size: it is in use.
        let keep = held.len().saturating_sub(1);
        for &(_, bytes, e) in &held[..keep] {
            if total as u64 <= self.limits.max_prepared_bytes {
                break;
            }
            let mut h = e.held();
            if let Some(p) = h.pair.take() {
                h.released = Arc::downgrade(&p);
                total -= bytes;
                released += 1;
                tracing::info!(pair_id = %e.spec.id, bytes, "prepared profile pair let go to stay within max_prepared_bytes; it is prepared again on its next use");
            }
        }
        self.metrics
            .prepared_pairs(held.len() - released as usize, total, released);
    }

    /// Writes the registration of a prepared `entry` to the store (on the
    /// calling thread: run it on the pool) if it is still registered and
    /// not stored yet; whether it was written now.
    pub fn persist(&self, entry: &Arc<PairEntry>) -> Result<bool, ServiceError> {
        if entry.spec.builtin_pair.is_some() || entry.persisted.load(Ordering::Relaxed) {
            return Ok(false);
        }
        let store = self.store();
        let Some(s) = store.as_ref() else {
            return Ok(false);
        };
        let current = self
            .read()
            .get(&entry.spec.id)
            .is_some_and(|e| Arc::ptr_eq(e, entry));
        if !current {
            return Ok(false);
        }
        s.put(&entry.spec.id, &entry.spec.registration())
            .map_err(|e| ServiceError::Internal(e.to_string()))?;
        entry.persisted.store(true, Ordering::Relaxed);
        Ok(true)
    }

    /// Removes the pair `id` from the registry and the store (on the
    /// calling thread: run it on the pool).
    pub fn delete(&self, id: &str) -> Result<(), ServiceError> {
        let store = self.store();
        let entry = self.lookup(id)?;
        if let Some(name) = entry.spec.builtin_pair {
            return Err(ServiceError::precondition(
                "pair_id",
                format!("'{name}' is a built-in pair and cannot be deleted"),
            ));
        }
        {
            let mut entries = self.write();
            entries.remove(&entry.spec.id);
            self.count_damaged(&entries);
        }
        if let Some(s) = store.as_ref() {
            s.remove(&entry.spec.id)
                .map_err(|e| ServiceError::Internal(e.to_string()))?;
        }
        Ok(())
    }

    /// Closes the store (at shutdown): later registrations stay in memory.
    pub fn close_store(&self) {
        self.store().take();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A rail slices file is refused by name, not read as a profile.
    #[test]
    fn a_rail_slices_file_is_refused_naming_the_field() {
        let src = pb::ProfileSource {
            source: Some(pb::profile_source::Source::File(pb::ProfileFile {
                format: pb::ProfileFormat::Unspecified as i32,
                content: "0 1000\n1\n0 0 0\n1\n0 'a.txt'\n".into(),
                file_name: "crossing.slcs".into(),
                ..Default::default()
            })),
            mirror_y: false,
        };
        let limit = PointLimit {
            max_points: 10_000,
            metrics: None,
        };
        let e = read(&src, ProfileKind::Rail, "rail", limit).err().unwrap();
        let text = e.to_string();
        assert!(
            text.contains("rail") && text.contains("slices file"),
            "{text}"
        );
    }

    /// A plain table's `plain_unit` scales it; an unknown unit is refused
    /// naming the field.
    #[test]
    fn a_plain_tables_unit_is_the_files_plain_unit() {
        let file = |plain_unit: i32| pb::ProfileSource {
            source: Some(pb::profile_source::Source::File(pb::ProfileFile {
                format: pb::ProfileFormat::Plain as i32,
                content: (0..16)
                    .map(|k| format!("{} {}\n", 2 * k, 0.02 * (k * k) as f64))
                    .collect(),
                file_name: "rail.txt".into(),
                plain_unit,
            })),
            mirror_y: false,
        };
        let limit = || PointLimit {
            max_points: 10_000,
            metrics: None,
        };
        let mm = read(
            &file(pb::LengthUnit::Mm as i32),
            ProfileKind::Rail,
            "rail",
            limit(),
        )
        .unwrap();
        let (lo, hi) = (mm.points()[0][0], mm.points()[mm.len() - 1][0]);
        assert!(((hi - lo).abs() - 0.03).abs() < 1e-12, "{lo} {hi}");
        let e = read(&file(7), ProfileKind::Rail, "rail", limit())
            .err()
            .unwrap();
        assert!(e.to_string().contains("rail.plain_unit"), "{e}");
    }

    #[test]
    fn ids_follow_the_canonical_content() {
        let builtin = canonicalize(&builtin_registration()).unwrap();
        assert_eq!(builtin.id.len(), 32);
        // The same pair spelled out, with the defaults given explicitly and
        // the left profiles repeated: the same id.
        let mut spec = builtin_spec();
        spec.friction = Some(pb::FrictionSection {
            coefficient: Some(0.3),
            ..Default::default()
        });
        spec.wheel_left = spec.wheel.clone();
        let explicit = canonicalize(&pb::RegisterProfilePairRequest {
            pair: Some(pb::register_profile_pair_request::Pair::Spec(spec.clone())),
            label: "mine".into(),
        })
        .unwrap();
        assert_eq!(explicit.id, builtin.id);
        // Another friction coefficient: another pair.
        spec.friction = Some(pb::FrictionSection {
            coefficient: Some(0.25),
            ..Default::default()
        });
        let other = canonicalize(&pb::RegisterProfilePairRequest {
            pair: Some(pb::register_profile_pair_request::Pair::Spec(spec)),
            label: String::new(),
        })
        .unwrap();
        assert_ne!(other.id, builtin.id);
    }
}
