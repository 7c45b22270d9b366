//! End-to-end tests of the track's options on the wire: rails placed by
//! their profiles' origins, each rail's deviation, a roller rig (its
//! radius in the pair, its rate in each solve's and step's velocity) and
//! track curvature. Each case solves through the service as
//! `railcontact wheelrail` solves the same case file (its parsed pair and
//! input, [`WheelrailRun`]), bit for bit, and each new field's bad value is
//! INVALID_ARGUMENT naming it.

use std::path::PathBuf;

use railcontact::cli::wheelrail::WheelrailRun;
use railcontact::core::cache::KernelCache;
use railcontact::service::pb;
use railcontact::service::wheelrail::query_of;
use railcontact::wheelrail::builtin::{mbench_a22_input, MBENCH_TRACK, MBENCH_WHEELSET};
use railcontact::wheelrail::{
    solve_wheelset, solve_wheelset_warm, RailDeviation, RailPlacement, SearchScratch, TrackData,
    WarmStart, WheelRailModel, WheelRailSolution,
};

use crate::service_wheelrail::{
    assert_invalid, assert_same, file_source, library_pair, register, register_ready, server_in,
    solve, solve_err, spec_request, wheelset, wr_request, wr_session,
};

fn cases_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples/cases")
}

/// The case file `name` of `examples/cases`, with each `(from, to)` of
/// `edits` replaced, parsed as `railcontact wheelrail` parses it.
fn run_of(name: &str, edits: &[(&str, &str)]) -> WheelrailRun {
    let mut text = std::fs::read_to_string(cases_dir().join(name)).unwrap();
    for (from, to) in edits {
        assert!(text.contains(from), "{name} has no {from:?}");
        text = text.replace(from, to);
    }
    WheelrailRun::from_toml(&text, &cases_dir()).unwrap_or_else(|e| panic!("{name}: {e:?}"))
}

/// What `railcontact wheelrail` answers to `run`.
fn cli_solution(run: &WheelrailRun) -> WheelRailSolution {
    let mut scratch = SearchScratch::default();
    solve_wheelset(run.pair(), run.input(), KernelCache::global(), &mut scratch).unwrap()
}

/// The wire track of a library track (every option).
fn track_spec(t: &TrackData) -> pb::TrackSpec {
    let (gauge_m, gauge_height_m, rail_origin_y_m, rail_origin_z_m) = match t.placement {
        RailPlacement::GaugePoint {
            gauge_m,
            gauge_height_m,
        } => (gauge_m, gauge_height_m, None, None),
        RailPlacement::Origin { q_m, z_m } => (0.0, 0.0, Some(q_m), Some(z_m)),
    };
    let deviation = |d: RailDeviation| {
        (d != RailDeviation::default()).then_some(pb::RailDeviation {
            dy_m: d.dy_m,
            dz_m: d.dz_m,
            droll_rad: d.droll_rad,
        })
    };
    pb::TrackSpec {
        gauge_m,
        gauge_height_m,
        cant_rad: t.cant_rad,
        rail_origin_y_m,
        rail_origin_z_m,
        rail_deviation_left: deviation(t.deviations[0]),
        rail_deviation_right: deviation(t.deviations[1]),
        roller_radius_m: t.roller_radius_m,
        curvature_per_m: t.curvature_per_m,
    }
}

/// Session step `k` of the query `q`'s motion.
fn step_of(k: usize, q: &pb::SolveWheelRailRequest) -> pb::WheelRailSessionRequest {
    wr_request(pb::wheel_rail_session_request::Kind::Step(
        pb::WheelRailSessionStep {
            step_index: k as u64,
            position: q.position,
            velocity: q.velocity,
            load: q.load,
            ..Default::default()
        },
    ))
}

/// Each step answer of a session (`r[0]` its opening) equals `wants`, bit
/// for bit.
fn assert_steps(
    what: &str,
    r: &[pb::wheel_rail_session_response::Kind],
    wants: &[WheelRailSolution],
) {
    for (k, want) in wants.iter().enumerate() {
        match &r[1 + k] {
            pb::wheel_rail_session_response::Kind::Step(s) => assert_same(
                &format!("{what} step {k}"),
                s.result.as_ref().unwrap(),
                want,
            ),
            other => panic!("{what} step {k}: {other:?}"),
        }
    }
}

fn builtin_source(name: &str) -> pb::ProfileSource {
    pb::ProfileSource {
        source: Some(pb::profile_source::Source::BuiltinName(name.into())),
        mirror_y: false,
    }
}

/// `examples/cases/roller_rig.toml`'s pair: a flat wheel on a roller with
/// a 100 mm section, its origin placed 0.2 m right of the centre.
fn roller_spec(run: &WheelrailRun) -> pb::ProfilePairSpec {
    pb::ProfilePairSpec {
        wheel: Some(file_source("flat_plane.prw", false)),
        rail: Some(file_source("circ_r100.prr", false)),
        track: Some(track_spec(run.pair().track())),
        wheelset: Some(wheelset(*run.pair().wheelset())),
        ..Default::default()
    }
}

/// The Manchester benchmark's pair (built-in profiles) on `track`.
fn mbench_spec(track: &TrackData) -> pb::ProfilePairSpec {
    pb::ProfilePairSpec {
        wheel: Some(builtin_source("MBench_S1002_v3.prw")),
        rail: Some(builtin_source("MBench_UIC60_v3.prr")),
        track: Some(track_spec(track)),
        wheelset: Some(wheelset(MBENCH_WHEELSET)),
        ..Default::default()
    }
}

/// The roller rig case of `examples/cases` (CONTACT's test-rollers2 case
/// 2a) through the service: the same bits as `railcontact wheelrail`, in
/// a query and in a session's first step; the pair's info echoes its
/// track.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_roller_rig_case_solves_as_the_command_line_bit_for_bit() {
    use pb::wheel_rail_session_request::Kind as In;
    let dir = tempfile::tempdir().unwrap();
    let (server, mut client) = server_in(dir.path()).await;
    let run = run_of("roller_rig.toml", &[]);
    assert_eq!(run.pair().track().roller_radius_m, Some(0.4));
    let want = cli_solution(&run);
    let spec = roller_spec(&run);
    let ready = register_ready(&mut client, spec_request(spec.clone(), "roller")).await;
    let info = ready.pair.unwrap();
    assert_eq!(info.track, spec.track, "the pair echoes its track");
    let q = query_of(&ready.pair_id, run.input());
    assert_eq!(q.velocity.unwrap().roller_rad_per_s, Some(2.5));
    let got = solve(&mut client, q.clone()).await;
    assert_same("roller rig", &got, &want);
    // CONTACT's test-rollers2 case 2a (.ref_out: FN = 9.719E+04 N): the
    // command line's figure, within the case's documented 0.1 %.
    let fn_n: f64 = got.wheels[0].patches.iter().map(|p| p.normal_force_n).sum();
    assert!((fn_n / 9.719e4 - 1.0).abs() < 1e-3, "{fn_n}");

    // A session's first step is the same solve.
    let open = pb::WheelRailSessionOpen {
        pair_id: ready.pair_id.clone(),
        model: q.model,
        sides: q.sides,
        element_size_m: q.element_size_m,
        min_elements_across: q.min_elements_across,
        friction: q.friction.clone(),
        ..Default::default()
    };
    let r = wr_session(
        &mut client,
        vec![wr_request(In::Open(open)), step_of(0, &q)],
    )
    .await
    .unwrap();
    let first = solve_wheelset_warm(
        run.pair(),
        run.input(),
        KernelCache::global(),
        &mut SearchScratch::default(),
        &mut WarmStart::default(),
    )
    .unwrap();
    assert_steps("roller rig", &r, &[first]);
    server.shutdown().await;
}

/// A curved track (R = 500 m, as `track.curvature_per_m` of the
/// Manchester case file) solves as the command line does, bit for
/// bit, and not as the tangent track; rails with deviations solve as the
/// library's pair with them, in a query and in a warm-started session.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn curved_track_and_rail_deviations_solve_as_the_library_bit_for_bit() {
    use pb::wheel_rail_session_request::Kind as In;
    let dir = tempfile::tempdir().unwrap();
    let (server, mut client) = server_in(dir.path()).await;

    let curved = run_of(
        "wheelset_a22.toml",
        &[("cant_rad = 0.0", "cant_rad = 0.0\ncurvature_per_m = 0.002")],
    );
    assert_eq!(curved.pair().track().curvature_per_m, 0.002);
    let want = cli_solution(&curved);
    let ready = register_ready(
        &mut client,
        spec_request(mbench_spec(curved.pair().track()), "curved"),
    )
    .await;
    let got = solve(&mut client, query_of(&ready.pair_id, curved.input())).await;
    assert_same("curved track", &got, &want);
    let tangent = cli_solution(&run_of("wheelset_a22.toml", &[]));
    assert_ne!(
        tangent.wheels[1].patches[0].creepage_long, want.wheels[1].patches[0].creepage_long,
        "the curvature changes the creepages"
    );

    // Each rail shifted and rolled.
    let track = TrackData {
        deviations: [
            RailDeviation {
                dy_m: 1e-3,
                dz_m: -0.2e-3,
                droll_rad: 2e-3,
            },
            RailDeviation {
                dy_m: -0.5e-3,
                dz_m: 0.3e-3,
                droll_rad: -1e-3,
            },
        ],
        ..MBENCH_TRACK
    };
    let pair = library_pair(
        "MBench_UIC60_v3.prr",
        false,
        "MBench_S1002_v3.prw",
        track,
        MBENCH_WHEELSET,
    );
    let ready = register_ready(&mut client, spec_request(mbench_spec(&track), "deviated")).await;
    let shifts = [3.0, 5.0];
    let mut scratch = SearchScratch::default();
    // The session's sequence: its own scratch and warm start.
    let (mut session_scratch, mut warm) = (SearchScratch::default(), WarmStart::default());
    let mut steps = vec![wr_request(In::Open(pb::WheelRailSessionOpen {
        pair_id: ready.pair_id.clone(),
        ..Default::default()
    }))];
    let mut wants = Vec::new();
    for (k, &mm) in shifts.iter().enumerate() {
        let input = mbench_a22_input(mm, None, None, WheelRailModel::Exact);
        let q = query_of(&ready.pair_id, &input);
        if k == 0 {
            let want = solve_wheelset(&pair, &input, KernelCache::global(), &mut scratch).unwrap();
            assert_same(
                "deviated rails",
                &solve(&mut client, q.clone()).await,
                &want,
            );
            let undeviated = solve_wheelset(
                &library_pair(
                    "MBench_UIC60_v3.prr",
                    false,
                    "MBench_S1002_v3.prw",
                    MBENCH_TRACK,
                    MBENCH_WHEELSET,
                ),
                &input,
                KernelCache::global(),
                &mut scratch,
            )
            .unwrap();
            assert_ne!(
                undeviated.center_z_m, want.center_z_m,
                "the deviations count"
            );
        }
        wants.push(
            solve_wheelset_warm(
                &pair,
                &input,
                KernelCache::global(),
                &mut session_scratch,
                &mut warm,
            )
            .unwrap(),
        );
        steps.push(step_of(k, &q));
    }
    let r = wr_session(&mut client, steps).await.unwrap();
    assert_steps("deviated", &r, &wants);
    server.shutdown().await;
}

/// Each new field's bad value is INVALID_ARGUMENT naming it: at the
/// registration (the call or its stream), in a query and in a session
/// step.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn bad_track_and_roller_values_are_invalid_argument_naming_the_field() {
    use pb::wheel_rail_session_request::Kind as In;
    use pb::wheel_rail_session_response::Kind as Out;
    let dir = tempfile::tempdir().unwrap();
    let (server, mut client) = server_in(dir.path()).await;
    let run = run_of("roller_rig.toml", &[]);
    let good = roller_spec(&run);
    type Edit = fn(&mut pb::TrackSpec);
    let edits: [(Edit, &str); 11] = [
        (
            |t| t.rail_origin_y_m = Some(200.0),
            "spec.track.rail_origin_y_m",
        ),
        (|t| t.rail_origin_z_m = None, "spec.track.rail_origin_z_m"),
        (
            |t| t.rail_origin_z_m = Some(f64::NAN),
            "spec.track.rail_origin_z_m",
        ),
        (|t| t.gauge_m = 1.435, "spec.track.rail_origin_y_m"),
        (
            |t| {
                t.rail_deviation_left = Some(pb::RailDeviation {
                    dy_m: 0.5,
                    ..Default::default()
                })
            },
            "spec.track.rail_deviation_left.dy_m",
        ),
        (
            |t| {
                t.rail_deviation_right = Some(pb::RailDeviation {
                    dz_m: f64::INFINITY,
                    ..Default::default()
                })
            },
            "spec.track.rail_deviation_right.dz_m",
        ),
        (
            |t| {
                t.rail_deviation_right = Some(pb::RailDeviation {
                    droll_rad: -1.0,
                    ..Default::default()
                })
            },
            "spec.track.rail_deviation_right.droll_rad",
        ),
        (
            |t| t.roller_radius_m = Some(-0.4),
            "spec.track.roller_radius_m",
        ),
        (
            |t| t.roller_radius_m = Some(f64::NAN),
            "spec.track.roller_radius_m",
        ),
        (|t| t.cant_rad = 0.025, "spec.track.cant_rad"),
        (|t| t.curvature_per_m = 0.5, "spec.track.curvature_per_m"),
    ];
    for (edit, field) in edits {
        let mut spec = good.clone();
        edit(spec.track.as_mut().unwrap());
        let e = register(&mut client, spec_request(spec, ""))
            .await
            .expect_err(field);
        assert_invalid(&e, &[field]);
    }

    // The roller's rate: required on a roller rig, > 0, its surface speed
    // in range; refused on a track; a model that cannot lay a roller.
    let ready = register_ready(&mut client, spec_request(good, "roller")).await;
    let q = query_of(&ready.pair_id, run.input());
    let rate = |r: Option<f64>| {
        let mut q = q.clone();
        q.velocity.as_mut().unwrap().roller_rad_per_s = r;
        q
    };
    for r in [None, Some(0.0), Some(f64::NAN), Some(1e6)] {
        let e = solve_err(&mut client, rate(r)).await;
        assert_invalid(&e, &["velocity.roller_rad_per_s"]);
    }
    let mut on_track = query_of(
        "mbench_s1002_uic60",
        &mbench_a22_input(3.0, None, None, WheelRailModel::Exact),
    );
    on_track.velocity.as_mut().unwrap().roller_rad_per_s = Some(2.5);
    assert_invalid(
        &solve_err(&mut client, on_track).await,
        &["velocity.roller_rad_per_s"],
    );
    let mut cect = q.clone();
    cect.model = pb::WheelRailModel::Cect as i32;
    assert_invalid(&solve_err(&mut client, cect).await, &["model"]);

    // In a session step, under `step.`.
    let bad = rate(Some(0.0));
    let r = wr_session(
        &mut client,
        vec![
            wr_request(In::Open(pb::WheelRailSessionOpen {
                pair_id: ready.pair_id.clone(),
                ..Default::default()
            })),
            step_of(0, &bad),
        ],
    )
    .await
    .unwrap();
    match &r[1] {
        Out::Error(e) => {
            assert_eq!(e.field, "step.velocity.roller_rad_per_s", "{e:?}");
            assert_eq!(e.code, tonic::Code::InvalidArgument as i32);
        }
        other => panic!("{other:?}"),
    }
    server.shutdown().await;
}

/// `examples/cases/crossing_nose.toml` (a wheel on a crossing nose given
/// as rail slices) at `track_s_m` instead of its 0.239 m.
fn crossing_run(track_s_m: f64) -> WheelrailRun {
    let at = format!("track_s_m = {track_s_m}");
    run_of("crossing_nose.toml", &[("track_s_m = 0.239", &at)])
}

/// A rail given as slices solves at each query's track_s_m as the command
/// line does at its case's, bit for bit, and a session moving along the
/// track as the library's warm-started sequence of those pairs; a
/// position outside the slices and malformed slices are refused naming
/// the field.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_rail_given_as_slices_solves_at_each_position_as_the_command_line() {
    use pb::wheel_rail_session_request::Kind as In;
    let dir = tempfile::tempdir().unwrap();
    let (server, mut client) = server_in(dir.path()).await;
    let first = crossing_run(0.239);
    let spec = pb::ProfilePairSpec {
        wheel: Some(builtin_source("MBench_S1002_v3.prw")),
        rail: Some(crate::common::crossing_slices()),
        track: Some(track_spec(first.pair().track())),
        wheelset: Some(wheelset(*first.pair().wheelset())),
        smoothing_wavelength_m: Some(0.0),
        ..Default::default()
    };
    let ready = register_ready(&mut client, spec_request(spec.clone(), "crossing")).await;
    let info = ready.pair.unwrap();
    assert_eq!(info.rail.unwrap().file_name, "uk_crossing_nose.slcs");

    let positions = [0.225, 0.239, 0.28];
    let (mut scratch, mut warm) = (SearchScratch::default(), WarmStart::default());
    let mut steps = vec![wr_request(In::Open(pb::WheelRailSessionOpen {
        pair_id: ready.pair_id.clone(),
        sides: pb::WheelSides::Right as i32,
        ..Default::default()
    }))];
    let mut wants = Vec::new();
    let mut normal = Vec::new();
    for (k, &s_m) in positions.iter().enumerate() {
        let run = crossing_run(s_m);
        let want = cli_solution(&run);
        let q = query_of(&ready.pair_id, run.input());
        assert_eq!(q.position.unwrap().track_s_m, s_m);
        let got = solve(&mut client, q.clone()).await;
        assert_same(&format!("slices at {s_m} m"), &got, &want);
        normal.push(
            want.wheels[0]
                .patches
                .iter()
                .map(|p| p.normal_force_n)
                .sum::<f64>(),
        );
        wants.push(
            solve_wheelset_warm(
                run.pair(),
                run.input(),
                KernelCache::global(),
                &mut scratch,
                &mut warm,
            )
            .unwrap(),
        );
        steps.push(step_of(k, &q));
    }
    // The rail changes along the track: the patches do too.
    let y: Vec<f64> = wants
        .iter()
        .map(|w| w.wheels[0].patches[0].rail_y_m)
        .collect();
    assert!(y[0] != y[2], "{y:?} {normal:?}");
    let r = wr_session(&mut client, steps).await.unwrap();
    assert_steps("slices", &r, &wants);

    // Outside the slices (u from 0.20875 to 0.32696 m).
    let mut far = query_of(&ready.pair_id, first.input());
    far.position.as_mut().unwrap().track_s_m = 0.5;
    assert_invalid(
        &solve_err(&mut client, far).await,
        &["position.track_s_m", "outside the slices"],
    );
    // A model other than the exact one.
    let mut hertz = query_of(&ready.pair_id, first.input());
    hertz.model = pb::WheelRailModel::HertzFastsim as i32;
    assert_invalid(&solve_err(&mut client, hertz).await, &["model"]);

    // Malformed slices, each named.
    type Edit = fn(&mut pb::RailSlices);
    let edits: [(Edit, &[&str]); 5] = [
        (
            |s| s.profiles.retain(|p| !p.file_name.ends_with("_70.txt")),
            &["spec.rail.slices", "Crossing_70.txt", "line 16"],
        ),
        (
            |s| s.profiles[3].content = "0.0 zero\n".into(),
            &["spec.rail.slices.profiles[3]", "Crossing_69.txt line 1"],
        ),
        (
            |s| s.content = s.content.replace("0.24836", "0.2"),
            &["spec.rail.slices", "increasing u"],
        ),
        (
            |s| s.file_name = "nose.txt".into(),
            &["spec.rail.slices.file_name"],
        ),
        (
            |s| {
                // 1001 slices 0.1 mm apart, all of one profile.
                let lines: String = (0..1001)
                    .map(|k| format!("{} 'uk_crossing/Crossing_66.txt'\n", 0.2 + 1e-4 * k as f64))
                    .collect();
                s.content = format!("0.0 1000.0\n1001\n0 0 0\n1\n{lines}");
            },
            &[
                "spec.rail.slices",
                "1001 slices, more than the limit of 1000",
            ],
        ),
    ];
    for (edit, needles) in edits {
        let mut bad = spec.clone();
        if let Some(pb::profile_source::Source::Slices(s)) =
            bad.rail.as_mut().unwrap().source.as_mut()
        {
            edit(s);
        }
        let e = register(&mut client, spec_request(bad, ""))
            .await
            .expect_err(needles[0]);
        assert_invalid(&e, needles);
    }
    // A wheel given as slices.
    let mut wheel = spec.clone();
    wheel.wheel = Some(crate::common::crossing_slices());
    let e = register(&mut client, spec_request(wheel, ""))
        .await
        .unwrap_err();
    assert_invalid(&e, &["spec.wheel.slices"]);
    server.shutdown().await;
}
