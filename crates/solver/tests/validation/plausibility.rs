//! The plausibility checks of wheelset solutions
//! (`wheelrail::plausibility`): silent on the Manchester benchmark's case
//! A-2.2 (CONTACT's rolls and pitch rates, and both found) and along the
//! load test's motion; warning, with the key at fault, when the benchmark's
//! roll and pitch rate are given to measured profiles (issue 43: S1002/UIC60
//! replaced by MiniProf measurements, "approach 5.6279 mm" at 10 kN).

use railcontact_solver::core::cache::KernelCache;
use railcontact_solver::wheelrail::builtin::{load_test_input, mbench_a22_input};
use railcontact_solver::wheelrail::plausibility::{
    elastic_approach_m, APPROACH_LIMIT, LONGITUDINAL_SHARE_LIMIT, MODEL_KEY, PITCH_RATE_KEY,
    ROLL_KEY, SATURATION_LIMIT,
};
use railcontact_solver::wheelrail::{
    check_plausibility, load_profile, load_profile_with, solve_wheelset, LoadOptions,
    PlausibilityWarning, SearchScratch, Side, SplineOptions, TrackData, WarningKind,
    WheelRailInput, WheelRailModel, WheelRailPair, WheelRailSolution, WheelsetData,
};

use crate::wheelrail::mbench_pair;

/// CONTACT's roll [rad] and pitch rate [rad/s] of case per lateral
/// shift [mm] (`docs/data/mbench_a22_contact.csv`, from CONTACT's
/// `mbench_a22_*.inp`).
const A22: [(f64, f64, f64); 21] = [
    (0.0, 0.0, -4.34811810),
    (0.5, -0.00002304, -4.34741340),
    (1.0, -0.00005049, -4.34657520),
    (1.5, -0.00008103, -4.34624400),
    (2.0, -0.00011280, -4.34591970),
    (2.5, -0.00014570, -4.34556270),
    (3.0, -0.00018030, -4.34515030),
    (3.5, -0.00021680, -4.34466880),
    (4.0, -0.00025570, -4.34409300),
    (4.5, -0.00029770, -4.34337150),
    (5.0, -0.00035540, -4.33536370),
    (5.5, -0.00047770, -4.33188640),
    (6.0, -0.00062720, -4.32937180),
    (6.5, -0.00437600, -4.27488340),
    (7.0, -0.00639300, -4.26356290),
    (7.5, -0.00764200, -4.25757470),
    (8.0, -0.00860600, -4.25348570),
    (8.5, -0.00940800, -4.25032450),
    (9.0, -0.01010113, -4.24775610),
    (9.5, -0.01071386, -4.24556650),
    (10.0, -0.01126431, -4.24363750),
];

/// The roll and pitch rate of `examples/cases/wheelset_a22.toml` (A-2.2 at
/// 6.5 mm).
const A22_ROLL: f64 = -0.004376;
const A22_PITCH: f64 = -4.2748834;

fn solve(pair: &WheelRailPair, input: &WheelRailInput) -> WheelRailSolution {
    solve_wheelset(
        pair,
        input,
        &KernelCache::default(),
        &mut SearchScratch::default(),
    )
    .unwrap()
}

fn warnings(pair: &WheelRailPair, input: &WheelRailInput) -> Vec<PlausibilityWarning> {
    check_plausibility(input, &solve(pair, input))
}

/// The checks' two measures of a solution: the largest over the wheels of
/// a wheel's smallest approach ratio, and the total longitudinal force over
/// the adhesion the lateral forces leave and over mu Fn.
fn measures(input: &WheelRailInput, s: &WheelRailSolution) -> (f64, f64, f64) {
    let ratio = s
        .wheels
        .iter()
        .filter_map(|w| {
            w.patches
                .iter()
                .map(|p| {
                    let e =
                        elastic_approach_m(p.normal_force_n, p.contact_area_m2, &input.material);
                    p.approach_m / e
                })
                .min_by(f64::total_cmp)
        })
        .fold(0.0, f64::max);
    let patches = || s.wheels.iter().flat_map(|w| &w.patches);
    let total: f64 = s.wheels.iter().map(|w| w.force_track_n[0]).sum();
    let mu_fn: f64 = patches()
        .map(|p| p.friction_coefficient * p.normal_force_n)
        .sum();
    let left: f64 = patches()
        .map(|p| {
            let m = p.friction_coefficient * p.normal_force_n;
            (m * m - p.fs_n * p.fs_n).max(0.0).sqrt()
        })
        .sum();
    (ratio, total.abs() / left, total.abs() / mu_fn)
}

#[test]
fn the_benchmark_at_contacts_roll_and_pitch_rate_and_found_does_not_warn() {
    let pair = mbench_pair();
    let mut worst = (0.0f64, 0.0f64, 0.0f64);
    for model in [WheelRailModel::Exact, WheelRailModel::HertzFastsim] {
        for (y_mm, roll, pitch) in A22 {
            let given = mbench_a22_input(y_mm, Some(roll), Some(pitch), model);
            let s = solve(&pair, &given);
            let w = check_plausibility(&given, &s);
            assert!(w.is_empty(), "{model:?} at {y_mm} mm: {w:#?}");
            let (r, used, share) = measures(&given, &s);
            worst = (worst.0.max(r), worst.1.max(used), worst.2.max(share));
            // Each wheel alone, as examples/mbench_a22.rs solves them.
            for side in Side::BOTH {
                let alone = WheelRailInput {
                    sides: vec![side],
                    ..given.clone()
                };
                let w = warnings(&pair, &alone);
                assert!(w.is_empty(), "{model:?} at {y_mm} mm, {side:?}: {w:#?}");
            }
            // Roll and pitch rate found (free rolling by a zero total
            // longitudinal force), and the pitch rate from the nominal
            // radius, which is not checked.
            let mut found = mbench_a22_input(y_mm, None, None, model);
            let w = warnings(&pair, &found);
            assert!(w.is_empty(), "{model:?} at {y_mm} mm, nominal: {w:#?}");
            found.total_longitudinal_force_n = Some(0.0);
            let w = warnings(&pair, &found);
            assert!(w.is_empty(), "{model:?} at {y_mm} mm, free: {w:#?}");
        }
    }
    // The margins the module docs quote: approach ratio 3.87 (6.5 mm, where
    // CONTACT's roll leaves our left wheel 0.069 mm above its rail), the
    // longitudinal measures 0.162 and 0.161 (Hertz+FASTSIM at 0 mm).
    assert!(worst.0 < 0.5 * APPROACH_LIMIT, "{worst:?}");
    assert!(worst.1 < 0.25 * SATURATION_LIMIT, "{worst:?}");
    assert!(worst.2 < 0.7 * LONGITUDINAL_SHARE_LIMIT, "{worst:?}");
}

#[test]
fn other_models_on_the_benchmark_do_not_warn() {
    let pair = mbench_pair();
    for model in [
        WheelRailModel::HertzPolach,
        WheelRailModel::HertzFastsimElliptic,
        WheelRailModel::HertzStrip,
        WheelRailModel::HertzFastsimModified,
        WheelRailModel::KikPiotrowski,
        WheelRailModel::Cect,
        WheelRailModel::Auto,
    ] {
        for (y_mm, roll, pitch) in [A22[4], A22[10], A22[13], A22[20]] {
            let input = mbench_a22_input(y_mm, Some(roll), Some(pitch), model);
            let w = warnings(&pair, &input);
            assert!(w.is_empty(), "{model:?} at {y_mm} mm: {w:#?}");
        }
    }
}

#[test]
fn the_load_tests_motion_does_not_warn() {
    let pair = mbench_pair();
    for (model, every) in [
        (WheelRailModel::HertzFastsim, 20),
        (WheelRailModel::Exact, 50),
    ] {
        for k in (0..500).step_by(every) {
            let input = load_test_input(k, 0.004, model);
            let w = warnings(&pair, &input);
            assert!(w.is_empty(), "{model:?}, load test step {k}: {w:#?}");
        }
    }
}

/// Issue 43's profiles: measured MiniProf ones in place of the benchmark's,
/// on the benchmark's track and wheelset, the flange back at the MiniProf
/// wheel's smallest y.
fn measured_pair(wheel: &str) -> WheelRailPair {
    let rail = load_profile_with(
        crate::profile_path("avg_HR.BAN"),
        &LoadOptions {
            mirror_y: true,
            ..LoadOptions::default()
        },
    )
    .unwrap();
    let wheel = load_profile(crate::profile_path(wheel)).unwrap();
    WheelRailPair::new(
        [&rail, &rail],
        [&wheel, &wheel],
        TrackData::gauge_point(1.435, 0.014, 0.0),
        WheelsetData {
            flange_back_distance_m: 1.360,
            nominal_radius_m: 0.46,
            flange_back_y_m: None,
        },
        &SplineOptions::default(),
    )
    .unwrap()
}

fn of_kind(w: &[PlausibilityWarning], kind: WarningKind) -> Vec<&PlausibilityWarning> {
    w.iter().filter(|w| w.kind == kind).collect()
}

#[test]
fn the_benchmarks_roll_and_pitch_rate_on_measured_profiles_warn() {
    let input = mbench_a22_input(6.5, Some(A22_ROLL), Some(A22_PITCH), WheelRailModel::Exact);
    let avg = measured_pair("avg_wheel.whl");
    let s = solve(&avg, &input);
    // The figures: the right wheel pressed 5.63 mm, the left
    // wheel's Fx 2311 N.
    let right = s.wheels.iter().find(|w| w.side == Side::Right).unwrap();
    assert!(
        (right.vertical_approach_m - 5.628e-3).abs() < 0.01e-3,
        "{}",
        right.vertical_approach_m
    );
    let w = check_plausibility(&input, &s);
    let approach = of_kind(&w, WarningKind::Approach);
    assert_eq!(approach.len(), 1, "{w:#?}");
    let a = approach[0];
    assert_eq!((a.key, a.side), (ROLL_KEY, Some(Side::Right)), "{a:#?}");
    assert!(a.value > 100.0 && a.limit == APPROACH_LIMIT, "{a:#?}");
    assert!(a.message.contains("Leave position.roll_rad out"), "{a}");
    let pitch = of_kind(&w, WarningKind::LongitudinalForce);
    assert_eq!(pitch.len(), 1, "{w:#?}");
    let p = pitch[0];
    assert_eq!((p.key, p.side), (PITCH_RATE_KEY, None), "{p:#?}");
    assert!(p.value > 0.95 && p.limit == SATURATION_LIMIT, "{p:#?}");
    assert!(
        p.message
            .contains("set load.total_longitudinal_force_n = 0"),
        "{p}"
    );

    // The other measured wheel: its left wheel hangs 1.3 mm above its rail.
    let w = warnings(&measured_pair("Car7216_0001r.whl"), &input);
    let a = of_kind(&w, WarningKind::Approach);
    assert_eq!(a.len(), 1, "{w:#?}");
    assert_eq!(
        (a[0].key, a[0].side),
        (ROLL_KEY, Some(Side::Left)),
        "{w:#?}"
    );
    assert!(a[0].value > 20.0, "{w:#?}");

    // The roll found: the pitch rate alone is still far off.
    let mut roll_found = input.clone();
    roll_found.position.roll_rad = None;
    let w = warnings(&avg, &roll_found);
    assert_eq!(w.len(), 1, "{w:#?}");
    assert_eq!(
        (w[0].kind, w[0].key),
        (WarningKind::LongitudinalForce, PITCH_RATE_KEY)
    );

    // Both found, the pitch rate by a zero total longitudinal force:
    // nothing to say; the left wheel's Fx (2311 N above) is now 188 N.
    let mut found = roll_found;
    found.velocity.pitch_rad_per_s = None;
    found.total_longitudinal_force_n = Some(0.0);
    let s = solve(&avg, &found);
    let w = check_plausibility(&found, &s);
    assert!(w.is_empty(), "{w:#?}");
    let left = s.wheels.iter().find(|w| w.side == Side::Left).unwrap();
    assert!(
        left.force_track_n[0].abs() < 300.0,
        "{:?}",
        left.force_track_n
    );
}

#[test]
fn patches_stopped_at_the_iteration_limit_warn_naming_the_model() {
    // at 6.5 mm (tread and flange), exact, at CONTACT's roll and
    // pitch rate: converged, no warning of this kind.
    let mut input = mbench_a22_input(6.5, Some(A22_ROLL), Some(A22_PITCH), WheelRailModel::Exact);
    let pair = mbench_pair();
    let s = solve(&pair, &input);
    assert!(s
        .wheels
        .iter()
        .flat_map(|w| &w.patches)
        .all(|p| !p.unconverged));
    assert!(of_kind(&check_plausibility(&input, &s), WarningKind::Unconverged).is_empty());
    // The tangential solver held to one iteration and a tolerance it
    // cannot reach in one: every frictional patch stops at the limit, and
    // each wheel says so once, naming the model.
    input.settings.solver.tangential.max_iterations = 1;
    input.settings.solver.tangential.tolerance = 1e-14;
    let s = solve(&pair, &input);
    let w = check_plausibility(&input, &s);
    let stopped = of_kind(&w, WarningKind::Unconverged);
    assert_eq!(stopped.len(), 2, "{w:#?}");
    for (warning, wheel) in stopped.iter().zip(&s.wheels) {
        let n = wheel.patches.iter().filter(|p| p.unconverged).count();
        assert!(n >= 1, "{wheel:#?}");
        assert_eq!(warning.key, MODEL_KEY);
        assert_eq!(warning.side, Some(wheel.side));
        assert_eq!((warning.value, warning.limit), (n as f64, 0.0));
        assert!(warning.message.contains("iteration limit"), "{warning}");
    }
}
