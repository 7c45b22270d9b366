//! Profiles compiled into the binary (see `profiles/README.md` of this
//! crate): the S1002 wheel and UIC60 rail of the Manchester Contact
//! Benchmark, and the benchmark's track and wheelset data.

use crate::core::material::{CombinedMaterial, Material};
use crate::core::problem::Friction;
use crate::wheelrail::contact::{WheelLoad, WheelRailInput, WheelRailModel, WheelRailSettings};
use crate::wheelrail::profile::{parse_profile, LoadOptions, Profile, ProfileError};
use crate::wheelrail::spline::SplineOptions;
use crate::wheelrail::wheelset::{
    Side, TrackData, WheelRailError, WheelRailPair, WheelsetData, WheelsetPosition,
    WheelsetVelocity,
};

/// Prefix of built-in profile names in case files: `builtin:NAME`.
pub const PREFIX: &str = "builtin:";

/// Built-in profile files: (name, content).
pub const FILES: [(&str, &str); 2] = [
    (
        "MBench_S1002_v3.prw",
        include_str!("../../profiles/MBench_S1002_v3.prw"),
    ),
    (
        "MBench_UIC60_v3.prr",
        include_str!("../../profiles/MBench_UIC60_v3.prr"),
    ),
];

/// The built-in profile `name` (without the prefix), parsed with `options`;
/// `None` if there is no such profile.
pub fn profile(name: &str, options: &LoadOptions) -> Option<Result<Profile, ProfileError>> {
    FILES
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(n, text)| parse_profile(text, n, options))
}

/// Track of the Manchester benchmark: gauge 1435 mm measured 14 mm below the
/// top of rail; the rail profile is already inclined 1:40.
pub const MBENCH_TRACK: TrackData =
    TrackData::gauge_point(MBENCH_GAUGE_M, MBENCH_GAUGE_HEIGHT_M, 0.0);

/// The Manchester benchmark's gauge \[m\] ([`MBENCH_TRACK`]).
pub const MBENCH_GAUGE_M: f64 = 1.435;

/// The depth below the top of rail where the Manchester benchmark's gauge
/// is measured \[m\] ([`MBENCH_TRACK`]).
pub const MBENCH_GAUGE_HEIGHT_M: f64 = 0.014;

/// Wheelset of the Manchester benchmark: flange-back distance 1360 mm with
/// the flange back at profile y = -70 mm, nominal rolling radius 460 mm.
pub const MBENCH_WHEELSET: WheelsetData = WheelsetData {
    flange_back_distance_m: 1.360,
    nominal_radius_m: 0.460,
    flange_back_y_m: Some(-0.070),
};

/// The Manchester benchmark's pair: the built-in S1002 wheel on the
/// built-in UIC60 rail on both sides, [`MBENCH_TRACK`] and
/// [`MBENCH_WHEELSET`], default spline options.
pub fn mbench_pair() -> Result<WheelRailPair, WheelRailError> {
    let o = LoadOptions::default();
    let load = |name: &str| {
        profile(name, &o)
            .expect("a built-in profile")
            .map_err(|e| WheelRailError::invalid("profile", e.to_string()))
    };
    let (rail, wheel) = (load("MBench_UIC60_v3.prr")?, load("MBench_S1002_v3.prw")?);
    WheelRailPair::new(
        [&rail, &rail],
        [&wheel, &wheel],
        MBENCH_TRACK,
        MBENCH_WHEELSET,
        &SplineOptions::default(),
    )
}

/// The input of Manchester benchmark case at lateral shift `y_mm`
/// \[mm\] (Shackleton & Iwnicki, VSD 46, 2008): yaw 2.4 mrad per mm, 10 kN per
/// wheel, 2 m/s, G = 82 GPa, nu = 0.28, mu = 0.3, 0.2 mm elements, both
/// wheels. `roll_rad` and `pitch_rad_per_s`: `None` to find the roll from
/// the profiles and roll freely at the nominal radius.
pub fn mbench_a22_input(
    y_mm: f64,
    roll_rad: Option<f64>,
    pitch_rad_per_s: Option<f64>,
    model: WheelRailModel,
) -> WheelRailInput {
    WheelRailInput {
        position: WheelsetPosition {
            lateral_m: y_mm * 1e-3,
            yaw_rad: 2.4e-3 * y_mm,
            roll_rad,
            track_s_m: 0.0,
        },
        velocity: WheelsetVelocity {
            pitch_rad_per_s,
            ..WheelsetVelocity::rolling(2.0)
        },
        load: WheelLoad::VerticalForce(10_000.0),
        sides: Side::BOTH.to_vec(),
        material: CombinedMaterial::identical(Material {
            shear_modulus_pa: 82e9,
            poisson_ratio: 0.28,
        })
        .expect("valid steel"),
        friction: Friction::coulomb(0.3),
        friction_table: None,
        settings: WheelRailSettings {
            model,
            ..WheelRailSettings::default()
        },
        total_longitudinal_force_n: None,
        temperature: None,
        rail_motion: Default::default(),
        rail_slices: Default::default(),
    }
}

/// Step `k` (1 ms steps) of the wheelset motion of `railcontact loadtest`'s
/// wheel/rail sessions (its first session's phase) with `model`, on
/// [`mbench_a22_input`]'s materials and friction: lateral shift
/// `amplitude_m` sin(2 pi f t) (the load test's is 4 mm) and yaw 2 mrad
/// cos(2 pi f t) with f = 2 Hz, their rates, 20 m/s forward, the roll found,
/// free rolling, and a vertical load of 50 kN + 2 kN sin(6 pi f t) a wheel.
pub fn load_test_input(k: usize, amplitude_m: f64, model: WheelRailModel) -> WheelRailInput {
    let w = 2.0 * std::f64::consts::PI * 2.0;
    let t = k as f64 * 1e-3;
    let a = w * t;
    let mut input = mbench_a22_input(0.0, None, None, model);
    input.position.lateral_m = amplitude_m * a.sin();
    input.position.yaw_rad = 2e-3 * a.cos();
    input.velocity.forward_m_per_s = 20.0;
    input.velocity.lateral_m_per_s = amplitude_m * w * a.cos();
    input.velocity.yaw_rad_per_s = -2e-3 * w * a.sin();
    input.load = WheelLoad::VerticalForce(50e3 + 2e3 * (3.0 * w * t).sin());
    input
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtin_profiles_parse_and_unknown_names_are_none() {
        for (name, _) in FILES {
            let p = profile(name, &LoadOptions::default()).unwrap().unwrap();
            assert!(p.len() > 50, "{name}: {} points", p.len());
        }
        assert!(profile("S1002.prw", &LoadOptions::default()).is_none());
    }
}
