//! End-to-end tests of the gRPC service: the real server on an ephemeral
//! loopback port, in-process, talked to through the generated tonic client.
//! Grids are small so that the whole file runs in seconds.

use std::time::Duration;

use railcontact::conformal::frictional::FrictionalWorkspace;
use railcontact::core::creep::kalker_creep_coefficients;
use railcontact::core::problem::Creepages;
use railcontact::core::sensitivity::{central_differences, JacobianPoint, JacobianSteps};
use railcontact::core::solution::Totals;
use railcontact::core::solve::solve;
use railcontact::core::viscoelastic::Sls;
use railcontact::problem::case::{Case, CaseFile};
use railcontact::problem::ModelRun;
use railcontact::service::config::ServeConfig;
use railcontact::service::convert::{result_of_report, total_values};
use railcontact::service::pb;
use railcontact::service::server::RunningServer;
use tokio_stream::StreamExt;
use tonic::transport::Channel;
use tonic::Code;

use crate::common;
use common::{metrics_page, rolling, server_with, sphere, steel, Client};

/// A server on an ephemeral port; pairs in memory only (no store).
async fn server() -> (RunningServer, Client) {
    server_with(ServeConfig::default()).await
}

fn shift(x: f64) -> pb::ShiftStep {
    pb::ShiftStep {
        shift_x_m: Some(x),
        ..Default::default()
    }
}

/// A transient rolling step at creepages (xi, 0.5 xi, 0).
fn roll(xi: f64) -> pb::ShiftStep {
    pb::ShiftStep {
        creepage_long: Some(xi),
        creepage_lat: Some(0.5 * xi),
        ..Default::default()
    }
}

/// A transient step rolling 0.5 mm at the prescribed force Fx [N].
fn force_roll(fx: f64) -> pb::ShiftStep {
    pb::ShiftStep {
        force_x_n: Some(fx),
        rolling_m: Some(5e-4),
        ..Default::default()
    }
}

/// `sphere` with transient shift steps of the rail in x [m].
fn transient(n: u32, shifts: &[f64]) -> pb::PatchCase {
    pb::PatchCase {
        friction: Some(pb::FrictionSection {
            coefficient: Some(0.3),
            ..Default::default()
        }),
        kinematics: Some(pb::patch_case::Kinematics::Transient(
            pb::TransientSection {
                steps: shifts.iter().map(|&x| shift(x)).collect(),
                ..Default::default()
            },
        )),
        ..sphere(pb::Model::Exact, n)
    }
}

fn request(case: pb::PatchCase) -> pb::SolvePatchRequest {
    pb::SolvePatchRequest {
        case: Some(case),
        ..Default::default()
    }
}

async fn solve_patch(client: &mut Client, case: pb::PatchCase) -> pb::PatchResult {
    client
        .solve_patch(request(case))
        .await
        .expect("solves")
        .into_inner()
        .result
        .unwrap()
}

/// SolvePatch of `case` with `include_fields`.
async fn solve_patch_with_fields(client: &mut Client, case: pb::PatchCase) -> pb::PatchResult {
    client
        .solve_patch(pb::SolvePatchRequest {
            case: Some(case),
            include_fields: true,
            ..Default::default()
        })
        .await
        .unwrap()
        .into_inner()
        .result
        .unwrap()
}

fn totals(r: &pb::StepResult) -> &pb::PatchTotals {
    r.totals.as_ref().unwrap()
}

/// The bits of every total: results compare bit for bit.
fn bits(t: &pb::PatchTotals) -> Vec<u64> {
    total_values(t).iter().map(|v| v.to_bits()).collect()
}

/// The status of a failed call, with the message for assertions.
fn failure<T: std::fmt::Debug>(r: Result<T, tonic::Status>) -> (Code, String) {
    let s = r.expect_err("the call must fail");
    (s.code(), s.message().to_string())
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn solve_patch_agrees_with_hertz_the_cli_path_and_the_fx_sign() {
    let (server, mut client) = server().await;
    // Hertz: a = (3 F R / (4 E*))^(1/3), p0 = 3 F / (2 pi a²), E* = G / (1 - nu).
    let h = solve_patch(&mut client, sphere(pb::Model::Hertz, 32)).await;
    let e_star: f64 = 81.0e9 / (1.0 - 0.30);
    let a = (3.0 * 1.0e4 * 0.5 / (4.0 * e_star)).cbrt();
    let p0 = 3.0 * 1.0e4 / (2.0 * std::f64::consts::PI * a * a);
    let th = totals(h.result.as_ref().unwrap());
    assert!(
        (th.max_pressure_pa / p0 - 1.0).abs() < 1e-9,
        "{} vs {p0}",
        th.max_pressure_pa
    );
    assert!((th.patch_length_m / (2.0 * a) - 1.0).abs() < 1e-9);
    assert_eq!(h.model, pb::Model::Hertz as i32);
    assert!(h.fields.is_none() && h.grid.is_none());

    // Exact: the same numbers as `railcontact solve` on the same case file,
    // bit for bit, and close to Hertz.
    let exact = solve_patch(&mut client, sphere(pb::Model::Exact, 32)).await;
    let te = totals(exact.result.as_ref().unwrap());
    let toml = "model = \"exact\"\n[material]\nshear_modulus_pa = 81.0e9\npoisson_ratio = 0.30\n\
                [geometry]\nkind = \"quadratic\"\na_per_m = 1.0\nb_per_m = 1.0\n\
                [load]\nnormal_force_n = 10000.0\n[grid]\nnx = 32\nny = 32\n";
    let cli = solve(&Case::from_toml(toml).unwrap().problem().unwrap()).unwrap();
    assert_eq!(
        te.max_pressure_pa.to_bits(),
        cli[0].totals.max_pressure_pa.to_bits()
    );
    assert_eq!(te.approach_m.to_bits(), cli[0].totals.approach_m.to_bits());
    assert!((te.normal_force_n / 1.0e4 - 1.0).abs() < 1e-9);
    assert!(
        (te.max_pressure_pa / p0 - 1.0).abs() < 0.05,
        "{} vs {p0}",
        te.max_pressure_pa
    );
    let grid = exact.grid.unwrap();
    assert_eq!((grid.nx, grid.ny), (32, 32));

    // Fx = -G a b C11 xi: a positive longitudinal creepage pulls the rail
    // backwards, in the exact model and in FASTSIM.
    for model in [pb::Model::Exact, pb::Model::Fastsim] {
        let r = solve_patch(&mut client, rolling(model, 24, 2e-4)).await;
        let t = totals(r.result.as_ref().unwrap());
        assert!(t.fx_n < 0.0, "{model:?}: fx {}", t.fx_n);
        assert!(-t.fx_n < 0.3 * t.normal_force_n, "{model:?}: partial slip");
        assert_eq!(r.friction_coefficient, 0.3);
    }
    server.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn batch_keeps_request_order_and_reports_item_errors_in_their_slots() {
    let (server, mut client) = server_with(ServeConfig {
        max_batch_items: 4,
        ..ServeConfig::default()
    })
    .await;
    let mut bad = sphere(pb::Model::Hertz, 16);
    bad.geometry.as_mut().unwrap().a_per_m = Some(f64::NAN);
    let force = |f: f64| {
        let mut c = sphere(pb::Model::Hertz, 16);
        c.load = Some(pb::LoadSection {
            load: Some(pb::load_section::Load::NormalForceN(f)),
        });
        request(c)
    };
    let items = vec![
        force(1.0e4),
        request(bad),
        request(sphere(pb::Model::Exact, 16)),
        force(3.0e4),
    ];
    let out = client
        .solve_patch_batch(pb::SolvePatchBatchRequest { items })
        .await
        .unwrap()
        .into_inner()
        .items;
    assert_eq!(out.len(), 4);
    use pb::batch_item_result::Outcome;
    let force_of = |i: usize| match &out[i].outcome {
        Some(Outcome::Result(r)) => totals(r.result.as_ref().unwrap()).normal_force_n,
        other => panic!("item {i}: {other:?}"),
    };
    assert_eq!(force_of(0), 1.0e4);
    assert!((force_of(2) / 1.0e4 - 1.0).abs() < 1e-9);
    assert_eq!(force_of(3), 3.0e4);
    match &out[1].outcome {
        Some(Outcome::Error(e)) => {
            assert_eq!(e.code, Code::InvalidArgument as i32);
            assert_eq!(e.field, "items[1].case.geometry.a_per_m");
        }
        other => panic!("{other:?}"),
    }
    assert!(out.iter().enumerate().all(|(i, s)| s.index as usize == i));
    // Over the batch limit: the whole call is refused.
    let items = (0..5).map(|_| force(1.0e4)).collect();
    let (code, msg) = failure(
        client
            .solve_patch_batch(pb::SolvePatchBatchRequest { items })
            .await,
    );
    assert_eq!(code, Code::InvalidArgument);
    assert!(
        msg.contains("`items`") && msg.contains("limit of 4"),
        "{msg}"
    );
    server.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn creep_curve_streams_one_point_each_in_order_and_saturates() {
    let (server, mut client) = server().await;
    let req = pb::CreepCurveRequest {
        case: Some(rolling(pb::Model::Exact, 20, 0.0)),
        sweep: common::linear_sweep(4e-3, 5),
        include_fields: false,
    };
    let mut stream = client.creep_curve(req).await.unwrap().into_inner();
    let mut points = Vec::new();
    while let Some(p) = stream.next().await {
        points.push(p.unwrap());
    }
    assert_eq!(points.len(), 5);
    let fx: Vec<f64> = points
        .iter()
        .enumerate()
        .map(|(k, p)| {
            assert_eq!(p.index as usize, k);
            let c = p.creepages.as_ref().unwrap().creepage_long;
            assert!((c - 1e-3 * k as f64).abs() < 1e-15, "{c}");
            totals(p.result.as_ref().unwrap().result.as_ref().unwrap()).fx_n
        })
        .collect();
    assert!(
        fx[0].abs() < 1e-6 * 1.0e4,
        "no creepage, no force: {}",
        fx[0]
    );
    for w in fx.windows(2) {
        assert!(w[1] < w[0], "|Fx| grows with the creepage: {fx:?}");
    }
    assert!(
        -fx[4] <= 0.3 * 1.0e4 * (1.0 + 1e-6),
        "Coulomb bound: {fx:?}"
    );
    // A warm-started point equals a cold solve within the solver tolerance.
    let cold = solve_patch(&mut client, rolling(pb::Model::Exact, 20, 2e-3)).await;
    let cold_fx = totals(cold.result.as_ref().unwrap()).fx_n;
    assert!(
        (fx[2] / cold_fx - 1.0).abs() < 1e-5,
        "{} vs {cold_fx}",
        fx[2]
    );

    // The Hertz model has no creep forces.
    let req = pb::CreepCurveRequest {
        case: Some(rolling(pb::Model::Hertz, 20, 0.0)),
        sweep: Some(pb::creep_curve_request::Sweep::List(pb::CreepageList {
            points: vec![pb::Creepages::default()],
        })),
        include_fields: false,
    };
    let (code, msg) = failure(client.creep_curve(req).await);
    assert_eq!(
        (code, msg.contains("`case.model`")),
        (Code::InvalidArgument, true),
        "{msg}"
    );
    server.shutdown().await;
}

fn open(case: pb::PatchCase, fields: bool) -> pb::SessionRequest {
    pb::SessionRequest {
        kind: Some(pb::session_request::Kind::Open(pb::SessionOpen {
            case: Some(case),
            include_fields: fields,
            client_label: "test".into(),
            ..Default::default()
        })),
    }
}

fn step(index: u64, motion: StepMotion, mark: bool) -> pb::SessionRequest {
    let mut s = pb::SessionStep {
        step_index: index,
        time_s: index as f64 * 1e-3,
        mark,
        ..Default::default()
    };
    match motion {
        StepMotion::Shift(x) => s.shift = Some(shift(x)),
        StepMotion::Roll(c) => s.shift = Some(roll(c)),
        StepMotion::ForceRoll(f) => s.shift = Some(force_roll(f)),
        StepMotion::Creep(c) => {
            s.creepages = Some(pb::Creepages {
                creepage_long: c,
                creepage_lat: 0.5 * c,
                ..Default::default()
            })
        }
    }
    pb::SessionRequest {
        kind: Some(pb::session_request::Kind::Step(s)),
    }
}

#[derive(Clone, Copy)]
enum StepMotion {
    Shift(f64),
    /// A transient rolling step at this longitudinal creepage.
    Roll(f64),
    /// A transient step rolling one element (0.5 mm) at this prescribed Fx.
    ForceRoll(f64),
    Creep(f64),
}

fn rollback(to: u64) -> pb::SessionRequest {
    pb::SessionRequest {
        kind: Some(pb::session_request::Kind::Rollback(pb::SessionRollback {
            to_step_index: to,
        })),
    }
}

/// Runs a whole session: sends `messages` (the first opens it) and returns
/// every response (the first is `opened`).
async fn session(
    client: &mut Client,
    messages: Vec<pb::SessionRequest>,
) -> Vec<pb::SessionResponse> {
    let n = messages.len();
    let stream = tokio_stream::iter(messages);
    let mut out = client.patch_session(stream).await.unwrap().into_inner();
    let mut responses = Vec::new();
    while let Some(r) = out.next().await {
        responses.push(r.expect("no stream error"));
    }
    assert_eq!(responses.len(), n, "one response per request");
    responses
}

fn step_result(r: &pb::SessionResponse) -> &pb::SessionStepResult {
    match &r.kind {
        Some(pb::session_response::Kind::Step(s)) => s,
        other => panic!("expected a step, got {other:?}"),
    }
}

/// A session on `case` (with fields): step 0 `first`, marked, then the
/// `rest` twice, each pass followed by a rollback to step 0.
fn marked_twice(
    case: pb::PatchCase,
    first: StepMotion,
    rest: &[StepMotion],
) -> Vec<pb::SessionRequest> {
    let mut msgs = vec![open(case, true), step(0, first, true)];
    for _ in 0..2 {
        msgs.extend((1..).zip(rest).map(|(k, m)| step(k, *m, false)));
        msgs.push(rollback(0));
    }
    msgs
}

/// The first pass of [`marked_twice`]'s responses `r` gives the bits of
/// the batch solve `whole`, step by step.
fn assert_first_pass_is_the_batch(r: &[pb::SessionResponse], whole: &pb::PatchResult) {
    for (k, want) in whole.steps.iter().enumerate() {
        assert_eq!(
            bits(totals(step_result(&r[1 + k]).result.as_ref().unwrap())),
            bits(totals(want)),
            "step {k}"
        );
    }
}

/// Steps `steps` of a session's responses `r` (step k at `r[1 + k]`)
/// replayed `offset` responses later (after a rollback to step 0's mark)
/// give the same bits, their fields included.
fn assert_replayed(r: &[pb::SessionResponse], steps: std::ops::Range<usize>, offset: usize) {
    for k in steps {
        let (a, b) = (step_result(&r[1 + k]), step_result(&r[1 + offset + k]));
        assert_eq!(
            bits(totals(a.result.as_ref().unwrap())),
            bits(totals(b.result.as_ref().unwrap())),
            "step {k}"
        );
        assert_eq!(a.fields, b.fields, "step {k}");
    }
}

fn error(r: &pb::SessionResponse) -> &pb::ItemError {
    match &r.kind {
        Some(pb::session_response::Kind::Error(e)) => e,
        other => panic!("expected an error, got {other:?}"),
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn transient_rolling_session_matches_the_batch_solve_and_replays_bit_for_bit() {
    let (server, mut client) = server().await;
    // A shift, then rolling steps of one element (0.5 mm of 20 x 10 mm).
    let creepages = [1e-3, 1.2e-3, 1.2e-3];
    let mut case = transient(20, &[1e-6]);
    if let Some(pb::patch_case::Kinematics::Transient(t)) = case.kinematics.as_mut() {
        t.rolling_step_m = Some(5e-4);
        t.steps.extend(creepages.iter().map(|&c| roll(c)));
    }
    let g = case.grid.as_mut().unwrap();
    g.window_x_m = Some(1e-2);
    g.window_y_m = Some(1e-2);
    let whole = solve_patch(&mut client, case.clone()).await;
    assert_eq!(whole.steps.len(), 4);
    let rest: Vec<_> = creepages.iter().map(|&c| StepMotion::Roll(c)).collect();
    let r = session(
        &mut client,
        marked_twice(case, StepMotion::Shift(1e-6), &rest),
    )
    .await;
    assert_first_pass_is_the_batch(&r, &whole);
    // The tractions roll along: the same creepage, another answer.
    assert_ne!(bits(totals(&whole.steps[2])), bits(totals(&whole.steps[3])));
    // Replayed from the mark: the same bits, fields included.
    assert_replayed(&r, 1..4, 4);
    server.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn prescribed_step_forces_report_their_shifts_in_solves_and_sessions() {
    let (server, mut client) = server().await;
    // A shift, then rolling steps of one element at prescribed forces.
    let forces = [-150.0, -160.0, -160.0];
    let mut case = transient(20, &[1e-6]);
    if let Some(pb::patch_case::Kinematics::Transient(t)) = case.kinematics.as_mut() {
        t.steps.extend(forces.iter().map(|&f| force_roll(f)));
    }
    let g = case.grid.as_mut().unwrap();
    g.window_x_m = Some(1e-2);
    g.window_y_m = Some(1e-2);
    let whole = solve_patch(&mut client, case.clone()).await;
    assert_eq!(whole.steps.len(), 4);
    assert_eq!(whole.steps[0].force_control, None);
    for k in 1..4 {
        let f = whole.steps[k].force_control.unwrap();
        let t = totals(&whole.steps[k]);
        assert!(
            (t.fx_n - forces[k - 1]).abs() < 1e-5 * 0.3 * t.normal_force_n,
            "step {k}: Fx {} against {}",
            t.fx_n,
            forces[k - 1]
        );
        assert_eq!(f.rolling_m, 5e-4);
        assert_eq!(f.creepage_long, Some(f.shift_x_m / 5e-4));
        assert!(f.force_solves >= 2, "{f:?}");
    }
    // A session gives the same bits step by step; a force beyond mu Fn is
    // refused naming its field and leaves the session as it was.
    let mut msgs = vec![open(case, false), step(0, StepMotion::Shift(1e-6), false)];
    msgs.push(step(1, StepMotion::ForceRoll(forces[0]), false));
    msgs.push(step(2, StepMotion::ForceRoll(-1e6), false));
    msgs.extend((2..4).map(|k| step(k, StepMotion::ForceRoll(forces[k as usize - 1]), false)));
    let r = session(&mut client, msgs).await;
    let e = error(&r[3]);
    assert_eq!(e.code, Code::InvalidArgument as i32);
    assert_eq!(e.field, "step.shift.force_x_n", "{}", e.message);
    for (k, i) in [(0, 1), (1, 2), (2, 4), (3, 5)] {
        let s = step_result(&r[i]).result.as_ref().unwrap();
        assert_eq!(bits(totals(s)), bits(totals(&whole.steps[k])), "step {k}");
        assert_eq!(s.force_control, whole.steps[k].force_control, "step {k}");
    }
    server.shutdown().await;
}

/// A steady-rolling session step prescribing Fx [N] (lateral creepage
/// 0.5e-3).
fn force_step(index: u64, fx: f64, mark: bool) -> pb::SessionRequest {
    pb::SessionRequest {
        kind: Some(pb::session_request::Kind::Step(pb::SessionStep {
            step_index: index,
            mark,
            creepages: Some(pb::Creepages {
                creepage_lat: 0.5e-3,
                force_x_n: Some(fx),
                ..Default::default()
            }),
            ..Default::default()
        })),
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn steady_session_steps_prescribe_forces_and_replay_bit_for_bit() {
    let (server, mut client) = server().await;
    let case = rolling(pb::Model::Exact, 16, 1e-3);
    // The forces of SolvePatch at two creepages.
    let fx_at = |xi: f64| {
        let mut c = case.clone();
        c.kinematics = Some(pb::patch_case::Kinematics::Rolling(pb::Creepages {
            creepage_long: xi,
            creepage_lat: 0.5e-3,
            ..Default::default()
        }));
        c
    };
    let f1 = totals(
        solve_patch(&mut client, fx_at(-4e-4))
            .await
            .result
            .as_ref()
            .unwrap(),
    )
    .fx_n;
    let f2 = totals(
        solve_patch(&mut client, fx_at(-5e-4))
            .await
            .result
            .as_ref()
            .unwrap(),
    )
    .fx_n;
    let msgs = vec![
        open(case, false),
        step(0, StepMotion::Creep(1e-3), false),
        force_step(1, f1, true),
        force_step(2, f2, false),
        force_step(3, -1e7, false),
        rollback(1),
        force_step(2, f2, false),
    ];
    let r = session(&mut client, msgs).await;
    let limit = 0.3 * 1e4;
    for (i, f, xi) in [(2, f1, -4e-4), (3, f2, -5e-4)] {
        let s = step_result(&r[i]);
        let fc = s.force_control.unwrap();
        let fx = totals(s.result.as_ref().unwrap()).fx_n;
        assert!((fx - f).abs() <= 1e-5 * limit, "Fx {fx} against {f}");
        assert!((fc.creepage_long - xi).abs() <= 1e-4 * xi.abs(), "{fc:?}");
        assert_eq!(fc.creepage_lat, 0.5e-3);
    }
    // The force beyond mu Fn names its field and changes nothing; the
    // replay after the rollback gives the same bits.
    let e = error(&r[4]);
    assert_eq!(e.code, Code::InvalidArgument as i32);
    assert_eq!(e.field, "step.creepages.force_x_n", "{}", e.message);
    let (a, b) = (step_result(&r[3]), step_result(&r[6]));
    assert_eq!(
        bits(totals(a.result.as_ref().unwrap())),
        bits(totals(b.result.as_ref().unwrap()))
    );
    assert_eq!(a.force_control, b.force_control);
    // Only the exact model solves forces.
    let r = session(
        &mut client,
        vec![
            open(rolling(pb::Model::Fastsim, 16, 1e-3), false),
            force_step(0, f1, false),
        ],
    )
    .await;
    assert_eq!(error(&r[1]).field, "step.creepages.force_x_n");
    server.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn bodies_travelling_over_the_grid_replay_bit_for_bit_in_sessions() {
    let (server, mut client) = server().await;
    // Shift steps on a fixed 20 x 10 mm grid over which the bodies travel
    // 0.5 mm (one element) a step, from 2 mm left of its centre.
    let travel = |x: f64, t: f64| pb::ShiftStep {
        gap_travel_x_m: Some(t),
        ..shift(x)
    };
    let steps = [travel(1e-6, -2e-3), travel(1e-6, 5e-4), travel(0.0, 5e-4)];
    let mut case = transient(20, &[]);
    if let Some(pb::patch_case::Kinematics::Transient(t)) = case.kinematics.as_mut() {
        t.steps = steps.to_vec();
    }
    let g = case.grid.as_mut().unwrap();
    g.window_x_m = Some(2e-2);
    g.window_y_m = Some(1e-2);
    let whole = solve_patch(&mut client, case.clone()).await;
    assert_eq!(whole.steps.len(), 3);
    // Step by step in a session, and again after a rollback over a step
    // that moved the bodies: the same bits.
    let msg = |k: u64, mark: bool| {
        let mut s = pb::SessionStep {
            step_index: k,
            mark,
            shift: Some(steps[k as usize]),
            ..Default::default()
        };
        s.time_s = k as f64;
        pb::SessionRequest {
            kind: Some(pb::session_request::Kind::Step(s)),
        }
    };
    let msgs = vec![
        open(case, false),
        msg(0, false),
        msg(1, true),
        msg(2, false),
        rollback(1),
        msg(2, false),
    ];
    let r = session(&mut client, msgs).await;
    for (k, i) in [(0, 1), (1, 2), (2, 3), (2, 5)] {
        let s = step_result(&r[i]).result.as_ref().unwrap();
        assert_eq!(bits(totals(s)), bits(totals(&whole.steps[k])), "step {k}");
    }
    server.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn transient_session_matches_the_batch_solve_and_rolls_back_bit_for_bit() {
    let (server, mut client) = server().await;
    let shifts = [1e-6, 2e-6, 2e-6];
    let case = transient(20, &shifts);
    let whole = solve_patch(&mut client, case.clone()).await;
    assert_eq!(whole.steps.len(), 3);

    let mut msgs = vec![open(case, true)];
    msgs.push(step(0, StepMotion::Shift(shifts[0]), true));
    msgs.push(step(1, StepMotion::Shift(shifts[1]), false));
    msgs.push(step(2, StepMotion::Shift(shifts[2]), false));
    msgs.push(step(7, StepMotion::Shift(1e-6), false)); // out of order
    msgs.push(rollback(1)); // never marked
    msgs.push(rollback(0));
    msgs.push(step(1, StepMotion::Shift(shifts[1]), false));
    msgs.push(step(2, StepMotion::Shift(shifts[2]), false));
    let first = msgs.remove(0);
    let mut all = vec![first];
    all.extend(msgs);
    let stream = tokio_stream::iter(all);
    let mut out = client.patch_session(stream).await.unwrap().into_inner();
    let mut r = Vec::new();
    while let Some(m) = out.next().await {
        r.push(m.unwrap());
    }
    assert_eq!(r.len(), 9);
    match &r[0].kind {
        Some(pb::session_response::Kind::Opened(o)) => {
            assert!(o.session_id.starts_with('s'));
            assert_eq!(o.grid.as_ref().unwrap().nx, 20);
        }
        other => panic!("{other:?}"),
    }
    // Step by step equals the transient solve of all steps at once.
    for k in 0..3 {
        let s = step_result(&r[1 + k]);
        assert_eq!(s.step_index, k as u64);
        assert_eq!(
            bits(totals(s.result.as_ref().unwrap())),
            bits(totals(&whole.steps[k])),
            "step {k}"
        );
    }
    // History matters: steps 1 and 2 have the same shift, not the same result.
    assert_ne!(
        bits(totals(step_result(&r[2]).result.as_ref().unwrap())),
        bits(totals(step_result(&r[3]).result.as_ref().unwrap()))
    );
    let e = error(&r[4]);
    assert_eq!(e.code, Code::FailedPrecondition as i32);
    assert!(
        e.message.contains("step_index 7 is out of order") && e.message.contains("expects step 3"),
        "{}",
        e.message
    );
    assert_eq!(e.field, "step.step_index");
    let e = error(&r[5]);
    assert_eq!(e.code, Code::FailedPrecondition as i32);
    assert!(e.message.contains("marked: 0"), "{}", e.message);
    assert_eq!(e.field, "rollback.to_step_index");
    match &r[6].kind {
        Some(pb::session_response::Kind::RolledBack(b)) => assert_eq!(b.next_step_index, 1),
        other => panic!("{other:?}"),
    }
    // After the rollback the same steps give the same bits, fields included.
    for (again, first) in [(7, 2), (8, 3)] {
        let (a, b) = (step_result(&r[again]), step_result(&r[first]));
        assert_eq!(a.step_index, b.step_index);
        assert_eq!(
            bits(totals(a.result.as_ref().unwrap())),
            bits(totals(b.result.as_ref().unwrap()))
        );
        let (fa, fb) = (a.fields.as_ref().unwrap(), b.fields.as_ref().unwrap());
        assert_eq!(fa.traction_x_pa.len(), 400);
        assert!(fa
            .traction_x_pa
            .iter()
            .zip(&fb.traction_x_pa)
            .all(|(x, y)| x.to_bits() == y.to_bits()));
        assert_eq!(fa.state, fb.state);
    }
    server.shutdown().await;
}

/// The paper's Case 1 (R_yr 10 mm, R_yw -10.1 mm, R_xw 0.5 m) at 80 kN
/// with the cect model, rolling with the creepages of `step`'s Creep
/// motion, on a coarse grid.
fn cect_rolling(c: f64) -> pb::PatchCase {
    pb::PatchCase {
        model: pb::Model::Cect as i32,
        material: Some(steel()),
        friction: Some(pb::FrictionSection {
            coefficient: Some(0.3),
            ..Default::default()
        }),
        geometry: Some(pb::GeometrySection {
            kind: pb::GeometryKind::ConformalCircular as i32,
            rail_lateral_radius_m: Some(0.010),
            wheel_lateral_radius_m: Some(-0.0101),
            wheel_rolling_radius_m: Some(0.5),
            ..Default::default()
        }),
        load: Some(pb::LoadSection {
            load: Some(pb::load_section::Load::NormalForceN(8.0e4)),
        }),
        kinematics: Some(pb::patch_case::Kinematics::Rolling(pb::Creepages {
            creepage_long: c,
            creepage_lat: 0.5 * c,
            ..Default::default()
        })),
        grid: Some(pb::GridSection {
            nx: Some(24),
            ny: Some(24),
            ..Default::default()
        }),
        ..Default::default()
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn cect_takes_the_rigid_slip_on_the_actual_surfaces_unless_asked_otherwise() {
    let (server, mut client) = server().await;
    let with = |r: pb::RigidSlip| {
        let mut c = cect_rolling(0.86e-3);
        c.conformal = Some(pb::ConformalSection {
            rigid_slip: r as i32,
        });
        c
    };
    let default = solve_patch(&mut client, cect_rolling(0.86e-3)).await;
    let actual = solve_patch(&mut client, with(pb::RigidSlip::ActualSurface)).await;
    let section = solve_patch(&mut client, with(pb::RigidSlip::ReferenceSection)).await;
    let t = |r: &pb::PatchResult| bits(totals(r.result.as_ref().unwrap()));
    assert_eq!(t(&default), t(&actual));
    assert_ne!(t(&default), t(&section));
    server.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_cect_session_equals_single_solves_bit_for_bit() {
    // The session keeps its conformal buffers from step to step; a single
    // solve starts with new ones. The answers must not tell them apart.
    let (server, mut client) = server().await;
    let creep = [0.86e-3, -1.53e-3, 0.3e-3];
    let mut msgs = vec![open(cect_rolling(0.0), false)];
    for (k, &c) in creep.iter().enumerate() {
        msgs.push(step(k as u64, StepMotion::Creep(c), false));
    }
    let r = session(&mut client, msgs).await;
    for (k, &c) in creep.iter().enumerate() {
        let alone = solve_patch(&mut client, cect_rolling(c)).await;
        let s = step_result(&r[1 + k]);
        let t = totals(s.result.as_ref().unwrap());
        assert!(t.fx_n.abs() > 0.0 && t.adhesion_fraction < 1.0, "{t:?}");
        assert_eq!(
            bits(t),
            bits(totals(alone.result.as_ref().unwrap())),
            "step {k}"
        );
    }
    server.shutdown().await;
}

fn rolling_steps(seed: f64) -> Vec<pb::SessionRequest> {
    let mut m = vec![open(rolling(pb::Model::Exact, 16, 0.0), false)];
    for k in 0..4u64 {
        m.push(step(k, StepMotion::Creep(seed * (1.0 + k as f64)), false));
    }
    m
}

fn step_bits(responses: &[pb::SessionResponse]) -> Vec<Vec<u64>> {
    responses[1..]
        .iter()
        .map(|r| bits(totals(step_result(r).result.as_ref().unwrap())))
        .collect()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn parallel_sessions_equal_sequential_ones_bit_for_bit() {
    let (server, client) = server().await;
    let seeds = [1e-4, 3e-4, 7e-4];
    let mut sequential = Vec::new();
    for s in seeds {
        sequential.push(step_bits(
            &session(&mut client.clone(), rolling_steps(s)).await,
        ));
    }
    let runs = seeds.map(|s| {
        let mut c = client.clone();
        tokio::spawn(async move { step_bits(&session(&mut c, rolling_steps(s)).await) })
    });
    for (k, run) in runs.into_iter().enumerate() {
        assert_eq!(run.await.unwrap(), sequential[k], "session {k}");
    }
    // Different inputs do give different outputs (the comparison can fail).
    assert_ne!(sequential[0], sequential[1]);
    server.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_rolling_direction_a_given_gap_and_an_extra_slip_reach_the_solver() {
    // The wire fields become the case file's keys (service::convert):
    // rolling in -x with creepage xi is rolling in +x with -xi turned half
    // a turn (core::frame), so Fx changes sign; the quadratic gap given per
    // element is the quadratic case; a uniform extra slip e_x is the
    // creepage xi + e_x.
    let (server, mut client) = server().await;
    let fx = |r: &pb::PatchResult| totals(r.result.as_ref().unwrap()).fx_n;
    let plus = solve_patch(&mut client, rolling(pb::Model::Exact, 16, -2e-4)).await;
    let mut c = rolling(pb::Model::Exact, 16, 2e-4);
    c.rolling_direction_rad = std::f64::consts::PI;
    let minus = solve_patch(&mut client, c).await;
    assert!(
        (fx(&minus) + fx(&plus)).abs() < 1e-9 * 1e4,
        "{} {}",
        fx(&minus),
        fx(&plus)
    );
    let quadratic = solve_patch_with_fields(&mut client, rolling(pb::Model::Exact, 16, 2e-4)).await;
    let mut c = rolling(pb::Model::Exact, 16, 2e-4);
    c.geometry.as_mut().unwrap().gap_m = quadratic.fields.as_ref().unwrap().gap_m.clone();
    let given = solve_patch(&mut client, c).await;
    assert_eq!(fx(&given), fx(&quadratic));
    let mut c = rolling(pb::Model::Exact, 16, 1e-4);
    c.extra_rigid_slip = Some(pb::ExtraRigidSlip {
        slip_x: vec![1e-4; 256],
        slip_y: Vec::new(),
        ..Default::default()
    });
    let extra = solve_patch(&mut client, c).await;
    assert!(
        (fx(&extra) - fx(&quadratic)).abs() < 1e-8 * 1e4,
        "{} {}",
        fx(&extra),
        fx(&quadratic)
    );
    // Shift steps take an extra shift: a uniform 1e-7 m is each step's
    // shift plus 1e-7 m.
    let moved = solve_patch(&mut client, transient(16, &[2e-7, 4e-7])).await;
    let mut c = transient(16, &[1e-7, 3e-7]);
    c.extra_rigid_slip = Some(pb::ExtraRigidSlip {
        shift_x_m: vec![1e-7; 256],
        ..Default::default()
    });
    let extra = solve_patch(&mut client, c).await;
    assert!(
        (fx(&extra) - fx(&moved)).abs() < 1e-8 * 1e4,
        "{} {}",
        fx(&extra),
        fx(&moved)
    );
    server.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn bad_inputs_get_invalid_argument_naming_the_field() {
    let (server, mut client) = server().await;
    let mut cases: Vec<(pb::SolvePatchRequest, &str)> = Vec::new();
    cases.push((pb::SolvePatchRequest::default(), "`case`"));
    let mut c = rolling(pb::Model::Exact, 16, 1e-3);
    c.friction.as_mut().unwrap().coefficient = Some(f64::NAN);
    cases.push((request(c), "`case.friction.coefficient`"));
    let mut c = sphere(pb::Model::Exact, 16);
    c.load = Some(pb::LoadSection {
        load: Some(pb::load_section::Load::NormalForceN(-5.0)),
    });
    cases.push((request(c), "`case.load.normal_force_n`"));
    cases.push((request(sphere(pb::Model::Exact, 512)), "`case.grid.nx`"));
    let mut c = sphere(pb::Model::Exact, 16);
    c.grid.as_mut().unwrap().window_x_m = Some(1e-4);
    cases.push((request(c), "`case.grid.window_x_m`"));
    let mut c = sphere(pb::Model::Exact, 16);
    c.geometry.as_mut().unwrap().kind = 0;
    cases.push((request(c), "`case.geometry.kind`"));
    let mut c = sphere(pb::Model::Exact, 16);
    c.geometry.as_mut().unwrap().extra_gap_m = vec![0.0; 7];
    cases.push((request(c), "`case.geometry.extra_gap_m`"));
    let mut c = rolling(pb::Model::Exact, 16, 1e-3);
    c.rolling_direction_rad = 0.3;
    cases.push((request(c), "`case.rolling_direction_rad`"));
    let mut c = rolling(pb::Model::Exact, 16, 1e-3);
    c.geometry.as_mut().unwrap().gap_m = vec![0.0; 7];
    cases.push((request(c), "`case.geometry.gap_m`"));
    let mut c = rolling(pb::Model::Exact, 16, 1e-3);
    c.extra_rigid_slip = Some(pb::ExtraRigidSlip {
        slip_x: vec![f64::NAN; 256],
        slip_y: Vec::new(),
        ..Default::default()
    });
    cases.push((request(c), "`case.extra_rigid_slip.slip_x[0]`"));
    cases.push((
        pb::SolvePatchRequest {
            case: Some(sphere(pb::Model::Hertz, 16)),
            include_fields: true,
            ..Default::default()
        },
        "`include_fields`",
    ));
    let mut c = sphere(pb::Model::Exact, 16);
    c.conformal = Some(pb::ConformalSection {
        rigid_slip: pb::RigidSlip::ReferenceSection as i32,
    });
    cases.push((request(c), "`case.conformal`"));
    let mut c = cect_rolling(1e-3);
    c.conformal = Some(pb::ConformalSection { rigid_slip: 7 });
    cases.push((request(c), "`case.conformal.rigid_slip`"));
    for (req, field) in cases {
        let (code, msg) = failure(client.solve_patch(req).await);
        assert_eq!(code, Code::InvalidArgument, "{field}: {msg}");
        assert!(msg.contains(field), "{field}: {msg}");
    }
    // A session must start with `open`.
    let stream = tokio_stream::iter(vec![step(0, StepMotion::Creep(0.0), false)]);
    let mut out = client.patch_session(stream).await.unwrap().into_inner();
    let (code, msg) = failure(out.next().await.unwrap());
    assert_eq!(code, Code::InvalidArgument);
    assert!(msg.contains("`open`"), "{msg}");
    // A bad step is refused in-band and names the field; the session goes on.
    let mut msgs = rolling_steps(1e-4);
    msgs.truncate(2);
    if let Some(pb::session_request::Kind::Step(s)) = &mut msgs[1].kind {
        s.creepages.as_mut().unwrap().spin_per_m = f64::INFINITY;
    }
    msgs.push(step(0, StepMotion::Creep(1e-4), false));
    let r = session(&mut client, msgs).await;
    let e = error(&r[1]);
    assert_eq!(
        (e.code, e.field.as_str()),
        (Code::InvalidArgument as i32, "step.creepages.spin_per_m")
    );
    assert_eq!(step_result(&r[2]).step_index, 0);
    server.shutdown().await;
}

/// The server's `railcontact_solves_cancelled_total`.
async fn cancelled_solves(server: &RunningServer) -> u64 {
    let page = metrics_page(server.metrics_addr.unwrap()).await;
    page.lines()
        .find_map(|l| l.strip_prefix("railcontact_solves_cancelled_total "))
        .and_then(|v| v.trim().parse().ok())
        .unwrap_or_else(|| panic!("no cancelled-solves counter in {page}"))
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_full_queue_is_resource_exhausted_and_a_passed_deadline_is_deadline_exceeded() {
    let (server, mut client) = server_with(ServeConfig {
        workers: 1,
        queue_capacity: 1,
        metrics_listen: Some("127.0.0.1:0".parse().unwrap()),
        // The slow solve below is 512 x 512.
        max_grid_elements: 512 * 512,
        ..ServeConfig::default()
    })
    .await;
    // A creep curve holds its queue slot while its client does not read
    // (per-element fields fill the stream's flow-control window quickly).
    let points = (0..1000)
        .map(|k| pb::Creepages {
            creepage_long: 1e-6 * k as f64,
            ..Default::default()
        })
        .collect();
    let curve = pb::CreepCurveRequest {
        case: Some(rolling(pb::Model::Exact, 16, 0.0)),
        sweep: Some(pb::creep_curve_request::Sweep::List(pb::CreepageList {
            points,
        })),
        include_fields: true,
    };
    let held = client.creep_curve(curve).await.unwrap();
    let (code, msg) = failure(
        client
            .solve_patch(request(sphere(pb::Model::Hertz, 8)))
            .await,
    );
    assert_eq!(code, Code::ResourceExhausted, "{msg}");
    let page = metrics_page(server.metrics_addr.unwrap()).await;
    assert!(
        page.contains("railcontact_solve_queue_admitted 1"),
        "{page}"
    );
    assert!(
        page.contains("method=\"SolvePatch\",code=\"ResourceExhausted\"} 1"),
        "{page}"
    );
    drop(held);
    // The slot comes back once the curve's task sees the client gone.
    let mut ok = None;
    for _ in 0..200 {
        match client
            .solve_patch(request(sphere(pb::Model::Hertz, 8)))
            .await
        {
            Ok(r) => {
                ok = Some(r);
                break;
            }
            Err(s) if s.code() == Code::ResourceExhausted => {
                tokio::time::sleep(Duration::from_millis(10)).await
            }
            Err(s) => panic!("{s:?}"),
        }
    }
    assert!(ok.is_some(), "the queue slot was never released");

    // 500 ms is far less than this solve takes (steady rolling on 512 x 512
    // takes seconds), and far more than the request
    // needs to reach its solve thread even when other tests load both
    // cores, so the solve surely starts and is surely cut short. (With
    // 100 ms on 256 x 256, a loaded machine sometimes let the deadline pass
    // before the solve started: answered in time, but never counted.) The
    // server answers 10 % before the client's timeout, ahead of the
    // transport's own CANCELLED.
    let before = cancelled_solves(&server).await;
    let mut slow = request(rolling(pb::Model::Exact, 512, 1e-3));
    slow.include_fields = false;
    let mut req = tonic::Request::new(slow);
    req.set_timeout(Duration::from_millis(500));
    let (code, msg) = failure(client.solve_patch(req).await);
    assert_eq!(code, Code::DeadlineExceeded, "{msg}");
    // The abandoned solve is told to stop (core::cancel) and counted once
    // its thread has ended.
    let mut counted = false;
    for _ in 0..1000 {
        if cancelled_solves(&server).await > before {
            counted = true;
            break;
        }
        tokio::time::sleep(Duration::from_millis(10)).await;
    }
    assert!(counted, "the abandoned solve was never counted");
    server.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn health_and_reflection_answer_without_our_protos() {
    use tonic_health::pb::health_check_response::ServingStatus;
    use tonic_health::pb::health_client::HealthClient;
    use tonic_health::pb::HealthCheckRequest;
    use tonic_reflection::pb::v1::server_reflection_client::ServerReflectionClient;
    use tonic_reflection::pb::v1::server_reflection_request::MessageRequest;
    use tonic_reflection::pb::v1::server_reflection_response::MessageResponse;
    use tonic_reflection::pb::v1::ServerReflectionRequest;

    let (server, _) = server().await;
    let channel = Channel::from_shared(format!("http://{}", server.addr))
        .unwrap()
        .connect()
        .await
        .unwrap();
    let mut health = HealthClient::new(channel.clone());
    let status = health
        .check(HealthCheckRequest {
            service: "railcontact.v1.ContactService".into(),
        })
        .await
        .unwrap()
        .into_inner()
        .status;
    assert_eq!(status, ServingStatus::Serving as i32);

    let mut reflection = ServerReflectionClient::new(channel);
    let asks = [
        MessageRequest::ListServices(String::new()),
        MessageRequest::FileContainingSymbol("railcontact.v1.ContactService".into()),
    ];
    let requests = asks.map(|m| ServerReflectionRequest {
        host: String::new(),
        message_request: Some(m),
    });
    let mut answers = reflection
        .server_reflection_info(tokio_stream::iter(requests))
        .await
        .unwrap()
        .into_inner();
    match answers.next().await.unwrap().unwrap().message_response {
        Some(MessageResponse::ListServicesResponse(l)) => {
            let names: Vec<&str> = l.service.iter().map(|s| s.name.as_str()).collect();
            assert!(
                names.contains(&"railcontact.v1.ContactService"),
                "{names:?}"
            );
            assert!(names.contains(&"grpc.health.v1.Health"), "{names:?}");
        }
        other => panic!("{other:?}"),
    }
    match answers.next().await.unwrap().unwrap().message_response {
        Some(MessageResponse::FileDescriptorResponse(f)) => {
            assert!(!f.file_descriptor_proto.is_empty())
        }
        other => panic!("{other:?}"),
    }
    server.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn shutdown_finishes_the_call_in_flight() {
    let (server, client) = server_with(ServeConfig {
        metrics_listen: Some("127.0.0.1:0".parse().unwrap()),
        ..ServeConfig::default()
    })
    .await;
    let metrics = server.metrics_addr.unwrap();
    let mut c = client.clone();
    let call = tokio::spawn(async move {
        c.solve_patch(request(rolling(pb::Model::Exact, 96, 1e-3)))
            .await
    });
    // Wait until the solve is admitted, then stop the server.
    let mut admitted = false;
    for _ in 0..500 {
        if metrics_page(metrics)
            .await
            .contains("railcontact_solve_queue_admitted 1")
        {
            admitted = true;
            break;
        }
        tokio::time::sleep(Duration::from_millis(2)).await;
    }
    assert!(admitted, "the call never reached the solve pool");
    server.shutdown().await;
    let r = call.await.unwrap().expect("the call in flight completes");
    assert!(
        totals(
            r.into_inner()
                .result
                .as_ref()
                .unwrap()
                .result
                .as_ref()
                .unwrap()
        )
        .fx_n
            < 0.0
    );
}

/// SolvePatch with include_sensitivities: the solution.
async fn solve_with_jacobian(client: &mut Client, case: pb::PatchCase) -> pb::StepResult {
    let request = pb::SolvePatchRequest {
        case: Some(case),
        include_sensitivities: true,
        ..Default::default()
    };
    let r = client.solve_patch(request).await.unwrap().into_inner();
    r.result.unwrap().result.unwrap()
}

fn jacobian_columns(s: &pb::Sensitivities) -> [[f64; 4]; 4] {
    [
        s.per_approach_m,
        s.per_creepage_long,
        s.per_creepage_lat,
        s.per_spin_per_m,
    ]
    .map(|c| {
        let c = c.expect("column");
        [c.normal_force, c.fx, c.fy, c.mz]
    })
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn sensitivities_match_finite_differences_over_the_wire_and_kalkers_linear_theory() {
    let (server, mut client) = server().await;
    let cr = pb::Creepages {
        creepage_long: 6e-4,
        creepage_lat: -3e-4,
        spin_per_m: 0.05,
        ..Default::default()
    };
    // A fixed window: the default one follows the load, and the finite
    // differences below control the approach instead.
    let case = |model, c: pb::Creepages| {
        let mut case = pb::PatchCase {
            kinematics: Some(pb::patch_case::Kinematics::Rolling(c)),
            ..rolling(model, 24, 0.0)
        };
        if model == pb::Model::Exact {
            let g = case.grid.as_mut().unwrap();
            g.window_x_m = Some(0.014);
            g.window_y_m = Some(0.014);
        }
        case
    };
    for model in [pb::Model::Exact, pb::Model::Fastsim] {
        let solved = solve_with_jacobian(&mut client, case(model, cr)).await;
        let t = solved.totals.unwrap();
        let s = solved.sensitivities.expect("sensitivities asked for");
        assert_eq!(s.solves, 8);
        let got = jacobian_columns(&s);
        // Cold central differences through the wire, approach-controlled
        // at the solution's approach, with the core's steps: the same
        // numbers to the solver's tolerances (1e-5 of each column).
        let steps = JacobianSteps::for_solution(
            &Totals {
                normal_force_n: t.normal_force_n,
                approach_m: t.approach_m,
                contact_area_m2: t.contact_area_m2,
                ..Default::default()
            },
            0.3,
            81.0e9,
        );
        let point = JacobianPoint {
            approach_m: t.approach_m,
            creepages: Creepages {
                creepage_long: cr.creepage_long,
                creepage_lat: cr.creepage_lat,
                spin_per_m: cr.spin_per_m,
            },
        };
        let mut fd_client = client.clone();
        let fd = {
            let mut calls = Vec::new();
            central_differences(point, steps, |d, c| {
                calls.push((d, c));
                Ok::<_, ()>([0.0; 4])
            })
            .unwrap();
            let mut values = Vec::new();
            for (d, c) in calls {
                let mut q = case(
                    model,
                    pb::Creepages {
                        creepage_long: c.creepage_long,
                        creepage_lat: c.creepage_lat,
                        spin_per_m: c.spin_per_m,
                        ..Default::default()
                    },
                );
                q.load = Some(pb::LoadSection {
                    load: Some(pb::load_section::Load::ApproachM(d)),
                });
                let r = solve_patch(&mut fd_client, q).await;
                let t = r.result.unwrap().totals.unwrap();
                values.push([t.normal_force_n, t.fx_n, t.fy_n, t.mz_nm]);
            }
            let mut it = values.into_iter();
            central_differences(point, steps, |_, _| Ok::<_, ()>(it.next().unwrap())).unwrap()
        };
        let want = [
            fd.per_approach_m,
            fd.per_creepage_long,
            fd.per_creepage_lat,
            fd.per_spin_per_m,
        ];
        for (col, (g, w)) in got.iter().zip(&want).enumerate() {
            let scale = w[..3].iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for k in 0..4 {
                let scale = if k == 3 { w[3].abs() } else { scale };
                assert!(
                    (g[k] - w[k]).abs() <= 1e-5 * scale,
                    "{model:?} column {col}[{k}]: {g:?} vs {w:?}"
                );
            }
        }
    }

    // FASTSIM at vanishing creepage is Kalker's linear theory by
    // construction (flexibility 8a / (3 C11 G), Kalker 1982): dFx/dxi =
    // -G ab C11 with Kalker 1990 Table E3 (core::creep), a/b = 1, and the
    // steel() material, G = 81 GPa, nu = 0.3.
    let solved =
        solve_with_jacobian(&mut client, case(pb::Model::Fastsim, Default::default())).await;
    let t = solved.totals.unwrap();
    let ab = t.contact_area_m2 / std::f64::consts::PI;
    let c11 = kalker_creep_coefficients(1.0, 0.30).unwrap().c11;
    let got = jacobian_columns(&solved.sensitivities.unwrap());
    let want = -81.0e9 * ab * c11;
    assert!(
        (got[1][1] / want - 1.0).abs() < 0.01,
        "dFx/dxi {} vs {want}",
        got[1][1]
    );

    // Not for other models or kinematics: INVALID_ARGUMENT naming the flag.
    let e = client
        .solve_patch(pb::SolvePatchRequest {
            case: Some(sphere(pb::Model::Exact, 16)),
            include_sensitivities: true,
            ..Default::default()
        })
        .await
        .unwrap_err();
    assert_eq!(e.code(), Code::InvalidArgument);
    assert!(
        e.message().contains("include_sensitivities"),
        "{}",
        e.message()
    );
    // A session computes them with every step.
    let mut open_msg = open(case(pb::Model::Exact, cr), false);
    if let Some(pb::session_request::Kind::Open(o)) = open_msg.kind.as_mut() {
        o.include_sensitivities = true;
    }
    let responses = session(
        &mut client,
        vec![
            open_msg,
            step(0, StepMotion::Creep(cr.creepage_long), false),
        ],
    )
    .await;
    let s = step_result(&responses[1]);
    assert!(s.result.as_ref().unwrap().sensitivities.is_some());
    server.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn solve_patch_finds_the_creepage_of_a_prescribed_force() {
    let (server, mut client) = server().await;
    // Fx of creepage_long = 2e-4, then that Fx prescribed: the creepage
    // comes back in `force_control` (core::force).
    // Inner tolerance 1e-10: the force tolerance is then 1e-9 mu Fn.
    let tight = |mut case: pb::PatchCase| {
        case.solver = Some(pb::SolverSection {
            tangential_tolerance: Some(1e-10),
            ..Default::default()
        });
        case
    };
    let forward = solve_patch(&mut client, tight(rolling(pb::Model::Exact, 24, 2e-4))).await;
    let fx = totals(forward.result.as_ref().unwrap()).fx_n;
    assert!(forward.force_control.is_none());
    let with_force = |f: f64| {
        let mut case = tight(rolling(pb::Model::Exact, 24, 0.0));
        case.kinematics = Some(pb::patch_case::Kinematics::Rolling(pb::Creepages {
            force_x_n: Some(f),
            ..Default::default()
        }));
        case
    };
    let r = solve_patch(&mut client, with_force(fx)).await;
    let c = r.force_control.expect("force_control");
    assert!((c.creepage_long - 2e-4).abs() <= 1e-6 * 2e-4, "{c:?}");
    assert!(c.force_iterations >= 1);
    let t = totals(r.result.as_ref().unwrap());
    assert!((t.fx_n - fx).abs() <= 1e-6 * 0.3 * t.normal_force_n);
    // At mu Fn: INVALID_ARGUMENT naming the field.
    let fn_ = t.normal_force_n;
    let (code, msg) = failure(
        client
            .solve_patch(request(with_force(-0.3 * fn_ * 1.01)))
            .await,
    );
    assert_eq!(code, Code::InvalidArgument, "{msg}");
    assert!(
        msg.contains("rolling.force_x_n") && msg.contains("saturation"),
        "{msg}"
    );
    // FASTSIM does not solve for a force: refused naming the field.
    let mut fastsim = with_force(fx);
    fastsim.model = pb::Model::Fastsim as i32;
    let (code, msg) = failure(client.solve_patch(request(fastsim)).await);
    assert_eq!(code, Code::InvalidArgument, "{msg}");
    assert!(
        msg.contains("rolling.force_x_n") && msg.contains("exact model only"),
        "{msg}"
    );
    // Creep curves and sessions step creepages: a prescribed force is
    // refused there, in the case and in a sweep point.
    let curve = |case: pb::PatchCase, point: pb::Creepages| pb::CreepCurveRequest {
        case: Some(case),
        sweep: Some(pb::creep_curve_request::Sweep::List(pb::CreepageList {
            points: vec![point],
        })),
        include_fields: false,
    };
    let point_force = pb::Creepages {
        force_x_n: Some(fx),
        ..Default::default()
    };
    for (req, field) in [
        (
            curve(with_force(fx), pb::Creepages::default()),
            "`case.rolling.force_x_n`",
        ),
        (
            curve(rolling(pb::Model::Exact, 24, 0.0), point_force),
            "force_x_n`",
        ),
    ] {
        let (code, msg) = failure(client.creep_curve(req).await);
        assert_eq!(code, Code::InvalidArgument, "{msg}");
        assert!(
            msg.contains(field) && msg.contains("not in creep curves"),
            "{msg}"
        );
    }
    let stream = tokio_stream::iter(vec![open(with_force(fx), false)]);
    let mut out = client.patch_session(stream).await.unwrap().into_inner();
    let (code, msg) = failure(out.next().await.unwrap());
    assert_eq!(code, Code::InvalidArgument, "{msg}");
    assert!(
        msg.contains("`open.case.rolling.force_x_n`") && msg.contains("not in sessions"),
        "{msg}"
    );
    server.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn subsurface_stresses_only_when_asked_and_fields_only_with_include_fields() {
    let (server, mut client) = server().await;
    let sub = |depths_m: Vec<f64>| pb::SubsurfaceSection {
        depths_m,
        shear_yield_stress_pa: Some(300e6),
        ..Default::default()
    };
    let n = 20;
    let plain = solve_patch(&mut client, rolling(pb::Model::Exact, n, 5e-4)).await;
    assert!(plain.subsurface.is_none(), "not asked: not computed");
    let mut case = rolling(pb::Model::Exact, n, 5e-4);
    case.subsurface = Some(sub(vec![0.5e-3, 1.5e-3, 3e-3]));
    let peaks = solve_patch(&mut client, case.clone()).await;
    let s = peaks.subsurface.as_ref().unwrap();
    let b1 = s.body1.as_ref().unwrap();
    assert!(b1.sigma_xx_pa.is_empty(), "fields only with include_fields");
    assert!(s.surface_fatigue_index.is_some());
    // The largest shear below a lightly tractive circle is about 0.3 p0
    // (0.31 p0 at 0.48 a, Johnson 1985 §4.2; a = 3.19 mm here, so the
    // depth 1.5 mm is the nearest).
    let p0 = totals(peaks.result.as_ref().unwrap()).max_pressure_pa;
    let tau = b1.max_shear.as_ref().unwrap();
    assert!(
        (tau.value_pa / p0 - 0.3).abs() < 0.03,
        "{}",
        tau.value_pa / p0
    );
    assert_eq!(tau.depth_m, 1.5e-3);
    let full = solve_patch_with_fields(&mut client, case).await;
    let f = full.subsurface.as_ref().unwrap();
    for b in [f.body1.as_ref().unwrap(), f.body2.as_ref().unwrap()] {
        for v in [&b.sigma_xx_pa, &b.sigma_nn_pa, &b.sigma_yn_pa, &b.un_m] {
            assert_eq!(v.len(), 3 * (n * n) as usize);
        }
    }
    assert_eq!(
        f.body1,
        s.body1.as_ref().map(|b| pb::BodySubsurface {
            sigma_xx_pa: f.body1.as_ref().unwrap().sigma_xx_pa.clone(),
            sigma_yy_pa: f.body1.as_ref().unwrap().sigma_yy_pa.clone(),
            sigma_nn_pa: f.body1.as_ref().unwrap().sigma_nn_pa.clone(),
            sigma_xy_pa: f.body1.as_ref().unwrap().sigma_xy_pa.clone(),
            sigma_xn_pa: f.body1.as_ref().unwrap().sigma_xn_pa.clone(),
            sigma_yn_pa: f.body1.as_ref().unwrap().sigma_yn_pa.clone(),
            ux_m: f.body1.as_ref().unwrap().ux_m.clone(),
            uy_m: f.body1.as_ref().unwrap().uy_m.clone(),
            un_m: f.body1.as_ref().unwrap().un_m.clone(),
            ..b.clone()
        })
    );
    // Refusals name the field.
    let mut bad = rolling(pb::Model::Exact, n, 5e-4);
    bad.subsurface = Some(sub(vec![-1e-3]));
    let (code, msg) = failure(client.solve_patch(request(bad)).await);
    assert_eq!(code, Code::InvalidArgument);
    assert!(msg.contains("subsurface.depths_m[0]"), "{msg}");
    let mut bad = rolling(pb::Model::Fastsim, n, 5e-4);
    bad.subsurface = Some(sub(vec![1e-3]));
    let (code, msg) = failure(client.solve_patch(request(bad)).await);
    assert_eq!(code, Code::InvalidArgument);
    assert!(msg.contains("subsurface") && msg.contains("exact"), "{msg}");
    server.shutdown().await;
}

/// CONTACT's carter2d (examples/carter2d.inp): steel cylinders, R = 0.5 m,
/// 178 900 N/m, mu 0.3, 55 strips, on the wire.
fn carter_line(kin: pb::Creepages) -> pb::PatchCase {
    pb::PatchCase {
        model: pb::Model::Exact as i32,
        material: Some(pb::MaterialSection {
            shear_modulus_pa: Some(82.0e9),
            poisson_ratio: Some(0.28),
            ..Default::default()
        }),
        friction: Some(pb::FrictionSection {
            coefficient: Some(0.3),
            ..Default::default()
        }),
        geometry: Some(pb::GeometrySection {
            kind: pb::GeometryKind::Line as i32,
            a_per_m: Some(1.0),
            ..Default::default()
        }),
        load: Some(pb::LoadSection {
            load: Some(pb::load_section::Load::NormalForceNPerM(178_900.0)),
        }),
        grid: Some(pb::GridSection {
            nx: Some(55),
            ..Default::default()
        }),
        kinematics: Some(pb::patch_case::Kinematics::Rolling(kin)),
        ..Default::default()
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn solve_patch_solves_a_line_contact_per_metre() {
    let (_server, mut client) = server().await;
    let r = solve_patch(
        &mut client,
        carter_line(pb::Creepages {
            creepage_long: -2.4e-4,
            ..Default::default()
        }),
    )
    .await;
    // carter2d.ref_out: FX = 6955 N over DY = 200 mm, 34 775 N/m (our
    // centred window differs from CONTACT's grid by a quarter strip).
    let t = totals(r.result.as_ref().unwrap());
    assert!((t.normal_force_n / 178_900.0 - 1.0).abs() < 1e-9);
    assert!((t.fx_n / 34_775.0 - 1.0).abs() < 0.01, "Fx {} N/m", t.fx_n);
    assert_eq!(r.grid.as_ref().map(|g| (g.nx, g.ny)), Some((55, 1)));
    // The force per metre prescribed: the creepage comes back.
    let r = solve_patch(
        &mut client,
        carter_line(pb::Creepages {
            force_x_n_per_m: Some(t.fx_n),
            ..Default::default()
        }),
    )
    .await;
    let xi = r.force_control.unwrap().creepage_long;
    assert!((xi / -2.4e-4 - 1.0).abs() < 1e-4, "creepage {xi}");
    // A total force on a line contact is refused naming the field.
    let (code, msg) = failure(
        client
            .solve_patch(request(carter_line(pb::Creepages {
                force_x_n: Some(1000.0),
                ..Default::default()
            })))
            .await,
    );
    assert_eq!(code, Code::InvalidArgument);
    assert!(msg.contains("rolling.force_x_n"), "{msg}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn solve_patch_solves_falling_friction_as_contacts_veldep_fric() {
    // CONTACT's veldep_fric case 1 (examples/veldep_fric.inp, .ref_out,
    // revision 2356): R = 460 mm on a flat rail, 622 216 N over 200 mm,
    // V = 45 m/s, CKSI -0.0009999, exponential law FKIN 0.18, FEXP1 0.12,
    // SABSH1 100 mm/s; FX 1.109E+05 N over 200 mm (5.545e5 N/m).
    let (_server, mut client) = server().await;
    let mut case = carter_line(pb::Creepages {
        creepage_long: -0.0009999,
        ..Default::default()
    });
    case.friction = Some(pb::FrictionSection {
        law: pb::FrictionLaw::Exponential as i32,
        kinetic_coefficient: Some(0.18),
        falling_coefficients: vec![0.12],
        half_velocities_m_per_s: vec![0.1],
        rolling_speed_m_per_s: Some(45.0),
        start: pb::SlipStart::Sticking as i32,
        ..Default::default()
    });
    case.geometry.as_mut().unwrap().a_per_m = Some(1.0 / (2.0 * 0.46));
    case.load = Some(pb::LoadSection {
        load: Some(pb::load_section::Load::NormalForceNPerM(622_216.0 / 0.2)),
    });
    case.grid = Some(pb::GridSection {
        nx: Some(93),
        window_x_m: Some(9.3e-3),
        ..Default::default()
    });
    let r = solve_patch(&mut client, case.clone()).await;
    let t = totals(r.result.as_ref().unwrap());
    assert!((t.fx_n / 5.545e5 - 1.0).abs() < 0.01, "Fx {} N/m", t.fx_n);
    // A falling law without its rolling speed is refused naming the field.
    case.friction.as_mut().unwrap().rolling_speed_m_per_s = None;
    let (code, msg) = failure(client.solve_patch(request(case)).await);
    assert_eq!(code, Code::InvalidArgument);
    assert!(msg.contains("friction.rolling_speed_m_per_s"), "{msg}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn flash_temperatures_only_when_asked_and_fields_only_with_include_fields() {
    let (server, mut client) = server().await;
    let steel = |bulk_temperature_k| pb::ThermalBody {
        bulk_temperature_k,
        conductivity_w_per_m_k: 50.0,
        density_kg_per_m3: 7850.0,
        specific_heat_j_per_kg_k: 450.0,
    };
    let section = pb::TemperatureSection {
        rolling_speed_m_per_s: 30.0,
        body1: Some(steel(293.15)),
        body2: Some(steel(333.15)),
    };
    let n = 20;
    let plain = solve_patch(&mut client, rolling(pb::Model::Exact, n, 2e-3)).await;
    assert!(plain.temperature.is_none(), "not asked: not computed");
    let mut case = rolling(pb::Model::Exact, n, 2e-3);
    case.temperature = Some(section);
    let peaks = solve_patch(&mut client, case.clone()).await;
    let t = peaks.temperature.as_ref().unwrap();
    assert!(t.body1_k.is_empty(), "fields only with include_fields");
    // Equal steels: the bulk temperatures meet at their mean; the frictional
    // power is T-gamma times the rolling speed.
    assert!((t.contact_temperature_k - 313.15).abs() < 1e-9);
    let tgamma = totals(peaks.result.as_ref().unwrap()).tgamma_n;
    assert!(
        (t.frictional_power_w - 30.0 * tgamma).abs() < 1e-9 * 30.0 * tgamma,
        "{} {tgamma}",
        t.frictional_power_w
    );
    assert!(t.max_body1.unwrap().temperature_k > 313.15);
    let full = solve_patch_with_fields(&mut client, case.clone()).await;
    let f = full.temperature.as_ref().unwrap();
    for v in [&f.body1_k, &f.body2_k, &f.heat_flux_w_per_m2] {
        assert_eq!(v.len(), (n * n) as usize);
    }
    let hottest = f.body1_k.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    assert_eq!(hottest, t.max_body1.unwrap().temperature_k);
    // Refusals name the field.
    let mut bad = case.clone();
    bad.temperature.as_mut().unwrap().body2 = Some(steel(60.0));
    let (code, msg) = failure(client.solve_patch(request(bad)).await);
    assert_eq!(code, Code::InvalidArgument);
    assert!(
        msg.contains("temperature.body2.bulk_temperature_k") && msg.contains("Celsius"),
        "{msg}"
    );
    let mut bad = case.clone();
    bad.temperature.as_mut().unwrap().body1 = None;
    let (code, msg) = failure(client.solve_patch(request(bad)).await);
    assert_eq!(code, Code::InvalidArgument);
    assert!(msg.contains("temperature.body1"), "{msg}");
    let mut bad = case;
    bad.model = pb::Model::Fastsim as i32;
    let (code, msg) = failure(client.solve_patch(request(bad)).await);
    assert_eq!(code, Code::InvalidArgument);
    assert!(
        msg.contains("temperature") && msg.contains("exact"),
        "{msg}"
    );
    server.shutdown().await;
}

/// gzip both ways: a compressed request is read, and a client that
/// accepts gzip gets its answer compressed, with the numbers of a plain
/// call.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn gzip_requests_are_read_and_answers_compressed_on_request() {
    use tonic::codec::CompressionEncoding::Gzip;
    let (server, client) = server_with(ServeConfig::default()).await;
    let request = || pb::SolvePatchRequest {
        case: Some(rolling(pb::Model::Exact, 24, 1e-3)),
        ..Default::default()
    };
    let plain = client
        .clone()
        .solve_patch(request())
        .await
        .expect("plain call")
        .into_inner();
    let answer = client
        .clone()
        .send_compressed(Gzip)
        .accept_compressed(Gzip)
        .solve_patch(request())
        .await
        .expect("gzip call");
    assert_eq!(
        answer
            .metadata()
            .get("grpc-encoding")
            .and_then(|v| v.to_str().ok()),
        Some("gzip"),
        "{:?}",
        answer.metadata()
    );
    let totals = |r: Option<pb::PatchResult>| r.and_then(|r| r.result).and_then(|s| s.totals);
    assert_eq!(totals(answer.into_inner().result), totals(plain.result));
    server.shutdown().await;
}

/// An interfacial layer (`case.interfacial_layer`, CONTACT's M = 4) on the
/// wire: a rolling sphere under a plastic layer gives the numbers of
/// `railcontact solve` on the same case file bit for bit, with the layer's
/// fields; a bad value is refused naming its field.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_interfacial_layer_on_the_wire_solves_as_the_case_file() {
    let (server, mut client) = server().await;
    // A thin layer whose yield limit (30 MPa) is below mu p0 (the Hertz
    // p0 of this sphere: 3 F / (2 pi a^2) = 468 MPa, a = 3.19 mm), so it
    // flows where the rolling traction reaches it (300 of the 24 x 24
    // elements at a creepage of 1e-3).
    let layer = pb::InterfacialLayerSection {
        thickness_m: 2.0e-5,
        shear_modulus_pa: 1.0e10,
        yield_limit_pa: 3.0e7,
        hardening_pa_per_m: 0.0,
    };
    let case = pb::PatchCase {
        interfacial_layer: Some(layer),
        ..rolling(pb::Model::Exact, 24, 1e-3)
    };
    let r = solve_patch_with_fields(&mut client, case.clone()).await;
    let toml = "model = \"exact\"\n[material]\nshear_modulus_pa = 81.0e9\npoisson_ratio = 0.30\n\
                [friction]\ncoefficient = 0.3\n\
                [geometry]\nkind = \"quadratic\"\na_per_m = 1.0\nb_per_m = 1.0\n\
                [load]\nnormal_force_n = 10000.0\n[grid]\nnx = 24\nny = 24\n\
                [rolling]\ncreepage_long = 1e-3\n\
                [interfacial_layer]\nthickness_m = 2.0e-5\nshear_modulus_pa = 1.0e10\n\
                yield_limit_pa = 3.0e7\n";
    let cli = solve(&Case::from_toml(toml).unwrap().problem().unwrap()).unwrap();
    let t = totals(r.result.as_ref().unwrap());
    assert_eq!(t.fx_n.to_bits(), cli[0].totals.fx_n.to_bits());
    assert_eq!(t.approach_m.to_bits(), cli[0].totals.approach_m.to_bits());
    let f = r.fields.as_ref().expect("fields");
    assert_eq!(f.layer_yield_limit_pa.len(), 24 * 24);
    assert!(f.layer_plastic.iter().any(|p| *p), "the layer flowed");
    assert!(f.layer_yield_limit_pa.iter().all(|t| *t == 3.0e7));
    // Without the layer the same case gives another force.
    let plain = solve_patch(&mut client, rolling(pb::Model::Exact, 24, 1e-3)).await;
    assert_ne!(totals(plain.result.as_ref().unwrap()).fx_n, t.fx_n);
    for (bad, field) in [
        (
            pb::InterfacialLayerSection {
                shear_modulus_pa: -1.0,
                ..layer
            },
            "case.interfacial_layer.shear_modulus_pa",
        ),
        (
            pb::InterfacialLayerSection {
                thickness_m: f64::NAN,
                ..layer
            },
            "case.interfacial_layer.thickness_m",
        ),
    ] {
        let c = pb::PatchCase {
            interfacial_layer: Some(bad),
            ..case.clone()
        };
        let (code, msg) = failure(client.solve_patch(request(c)).await);
        assert_eq!(code, Code::InvalidArgument, "{field}: {msg}");
        assert!(msg.contains(field), "{field}: {msg}");
    }
    let c = pb::PatchCase {
        interfacial_layer: Some(layer),
        ..rolling(pb::Model::Fastsim, 24, 1e-3)
    };
    let (code, msg) = failure(client.solve_patch(request(c)).await);
    assert_eq!(code, Code::InvalidArgument, "{msg}");
    assert!(msg.contains("case.interfacial_layer"), "{msg}");
    server.shutdown().await;
}

/// Transient steps from a steady rolling state on the wire
/// (`TransientSection.steady_start`, `ShiftStep.friction_start`):
/// SolvePatch of `examples/cases/line_veldep_fric_steps.toml`'s values
/// gives the command line's numbers bit for bit, the steady state as
/// `steady_start` and each step; a friction start outside the enum is
/// refused naming its step.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn transient_steps_from_a_steady_state_on_the_wire_solve_as_the_case_file() {
    let (server, mut client) = server().await;
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/cases/line_veldep_fric_steps.toml"
    );
    let file = Case::from_toml(&std::fs::read_to_string(path).unwrap()).expect("a valid case");
    let cli = match ModelRun::solve(&file, &mut FrictionalWorkspace::default()) {
        Ok(ModelRun::Exact(run)) => result_of_report(&run.report(&file, false)),
        Ok(_) => panic!("the exact model"),
        Err(e) => panic!("{e}"),
    };
    let sliding = pb::ShiftStep {
        creepage_long: Some(-0.001),
        friction_start: pb::SlipStart::Sliding as i32,
        ..Default::default()
    };
    let case = pb::PatchCase {
        model: pb::Model::Exact as i32,
        material: Some(pb::MaterialSection {
            shear_modulus_pa: Some(82.0e9),
            poisson_ratio: Some(0.28),
            ..Default::default()
        }),
        friction: Some(pb::FrictionSection {
            law: pb::FrictionLaw::Exponential as i32,
            kinetic_coefficient: Some(0.18),
            falling_coefficients: vec![0.12],
            half_velocities_m_per_s: vec![0.1],
            rolling_speed_m_per_s: Some(45.0),
            start: pb::SlipStart::Sticking as i32,
            ..Default::default()
        }),
        geometry: Some(pb::GeometrySection {
            kind: pb::GeometryKind::Line as i32,
            a_per_m: Some(1.0869565217391304),
            ..Default::default()
        }),
        load: Some(pb::LoadSection {
            load: Some(pb::load_section::Load::NormalForceNPerM(3111080.0)),
        }),
        kinematics: Some(pb::patch_case::Kinematics::Transient(
            pb::TransientSection {
                steps: vec![sliding; 3],
                rolling_step_m: Some(1.0e-4),
                steady_start: Some(pb::SteadyStart {
                    creepage_long: -0.0009999,
                    ..Default::default()
                }),
            },
        )),
        grid: Some(pb::GridSection {
            nx: Some(93),
            window_x_m: Some(9.3e-3),
            ..Default::default()
        }),
        ..Default::default()
    };
    let r = solve_patch(&mut client, case.clone()).await;
    let start = |r: &pb::PatchResult| bits(totals(r.steady_start.as_ref().unwrap()));
    assert_eq!(start(&r), start(&cli));
    assert_eq!(r.steps.len(), 3);
    for (k, (a, b)) in r.steps.iter().zip(&cli.steps).enumerate() {
        assert_eq!(bits(totals(a)), bits(totals(b)), "step {k}");
    }
    let mut bad = case;
    if let Some(pb::patch_case::Kinematics::Transient(t)) = &mut bad.kinematics {
        t.steps[1].friction_start = 7;
    }
    let (code, msg) = failure(client.solve_patch(request(bad)).await);
    assert_eq!(code, Code::InvalidArgument, "{msg}");
    assert!(
        msg.contains("case.transient.steps[1].friction_start"),
        "{msg}"
    );
    server.shutdown().await;
}

/// `examples/cases/visc_cylindr.toml` (CONTACT's `visc_cylindr` case 3:
/// two viscoelastic PA6 cylinders braked at Fx = -0.6 mu Fn) read as the
/// command line reads it, and its wire form built section by section from
/// the file's values.
fn visc_cylindr() -> (Case, pb::PatchCase) {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/cases/visc_cylindr.toml"
    );
    let text = std::fs::read_to_string(path).expect("the example case file");
    let f: CaseFile = toml::from_str(&text).expect("a case file");
    let body = |s: Sls| {
        Some(pb::ViscoelasticBody {
            relaxation_ratio: s.relaxation_ratio,
            creep_relaxation_time_s: s.creep_relaxation_time_s,
        })
    };
    let visc = f.viscoelastic.expect("[viscoelastic]");
    let rolling = f.rolling.as_ref().expect("[rolling]");
    let grid = f.grid.as_ref().expect("[grid]");
    let wire = pb::PatchCase {
        model: pb::Model::Exact as i32,
        material: Some(pb::MaterialSection {
            shear_modulus_pa: f.material.shear_modulus_pa,
            poisson_ratio: f.material.poisson_ratio,
            ..Default::default()
        }),
        friction: Some(pb::FrictionSection {
            coefficient: f.friction.as_ref().and_then(|f| f.coefficient),
            ..Default::default()
        }),
        geometry: Some(pb::GeometrySection {
            kind: pb::GeometryKind::Line as i32,
            a_per_m: f.geometry.a_per_m,
            gap_m: f.geometry.gap_m.clone().expect("gap_m"),
            ..Default::default()
        }),
        load: Some(pb::LoadSection {
            load: f
                .load
                .normal_force_n_per_m
                .map(pb::load_section::Load::NormalForceNPerM),
        }),
        kinematics: Some(pb::patch_case::Kinematics::Rolling(pb::Creepages {
            force_x_n_per_m: rolling.force_x_n_per_m,
            ..Default::default()
        })),
        grid: Some(pb::GridSection {
            nx: grid.nx.map(|n| n as u32),
            window_x_m: grid.window_x_m,
            ..Default::default()
        }),
        viscoelastic: Some(pb::ViscoelasticSection {
            rolling_speed_m_per_s: visc.rolling_speed_m_per_s,
            body1: body(visc.body1),
            body2: body(visc.body2),
        }),
        ..Default::default()
    };
    (Case::from_file(f).expect("a valid case"), wire)
}

/// Viscoelastic bodies (`case.viscoelastic`, CONTACT's M = 1) on the wire:
/// SolvePatch of `examples/cases/visc_cylindr.toml` gives the numbers of
/// `railcontact solve` on the file bit for bit (totals, the creepage of
/// the prescribed force, every field); bad values are refused naming
/// their field, and another model, transient steps, another rolling
/// direction and a surface grid over 64 x 64 naming what refuses them.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn viscoelastic_bodies_on_the_wire_solve_as_the_case_file() {
    let (server, mut client) = server().await;
    let (file, case) = visc_cylindr();
    let r = solve_patch_with_fields(&mut client, case.clone()).await;
    let cli = match ModelRun::solve(&file, &mut FrictionalWorkspace::default()) {
        Ok(ModelRun::Exact(run)) => result_of_report(&run.report(&file, true)),
        Ok(_) => panic!("the exact model"),
        Err(e) => panic!("{e}"),
    };
    let (t, want) = (r.result.as_ref().unwrap(), cli.result.as_ref().unwrap());
    assert_eq!(bits(totals(t)), bits(totals(want)));
    let creepage = |r: &pb::PatchResult| r.force_control.as_ref().unwrap().creepage_long;
    assert_eq!(creepage(&r).to_bits(), creepage(&cli).to_bits());
    let (f, g) = (r.fields.as_ref().unwrap(), cli.fields.as_ref().unwrap());
    let field_bits = |f: &pb::ElementFields| -> Vec<u64> {
        [&f.pressure_pa, &f.traction_x_pa, &f.slip_x]
            .iter()
            .flat_map(|v| v.iter().map(|x| x.to_bits()))
            .collect()
    };
    assert_eq!(field_bits(f), field_bits(g));
    assert_eq!(f.state, g.state);
    // CONTACT's visc_cylindr.ref_out, case 3: 57 elements in contact, 36
    // in adhesion, 21 in slip.
    let count = |s: pb::ElementState| f.state.iter().filter(|&&e| e == s as i32).count();
    assert_eq!(
        (
            count(pb::ElementState::Adhesion),
            count(pb::ElementState::Slip)
        ),
        (36, 21)
    );
    // Elastic cylinders of the same (glassy) modulus give another creepage.
    let elastic = solve_patch(
        &mut client,
        pb::PatchCase {
            viscoelastic: None,
            ..case.clone()
        },
    )
    .await;
    assert_ne!(creepage(&elastic).to_bits(), creepage(&r).to_bits());

    let visc = case.viscoelastic.unwrap();
    let body = visc.body1.unwrap();
    let with = |v: pb::ViscoelasticSection| pb::PatchCase {
        viscoelastic: Some(v),
        ..case.clone()
    };
    for (bad, field) in [
        (
            with(pb::ViscoelasticSection {
                rolling_speed_m_per_s: 0.0,
                ..visc
            }),
            "case.viscoelastic.rolling_speed_m_per_s",
        ),
        (
            with(pb::ViscoelasticSection {
                body1: Some(pb::ViscoelasticBody {
                    relaxation_ratio: -1.0,
                    ..body
                }),
                ..visc
            }),
            "case.viscoelastic.body1.relaxation_ratio",
        ),
        (
            with(pb::ViscoelasticSection {
                body2: Some(pb::ViscoelasticBody {
                    creep_relaxation_time_s: f64::NAN,
                    ..body
                }),
                ..visc
            }),
            "case.viscoelastic.body2.creep_relaxation_time_s",
        ),
        (
            with(pb::ViscoelasticSection {
                rolling_speed_m_per_s: 1e300,
                body2: Some(pb::ViscoelasticBody {
                    creep_relaxation_time_s: 1e300,
                    ..body
                }),
                ..visc
            }),
            "case.viscoelastic.body2.creep_relaxation_time_s",
        ),
        (
            pb::PatchCase {
                rolling_direction_rad: std::f64::consts::PI,
                ..case.clone()
            },
            "case.rolling_direction_rad",
        ),
        (
            pb::PatchCase {
                viscoelastic: Some(visc),
                ..transient(16, &[1e-5])
            },
            "case.viscoelastic",
        ),
        // A surface grid of 129 x 129 elements: over the 16384 (128 x
        // 128) whose coefficients are integrated, refused before any work.
        (
            pb::PatchCase {
                viscoelastic: Some(visc),
                ..rolling(pb::Model::Exact, 129, 1e-3)
            },
            "case.viscoelastic",
        ),
    ] {
        let (code, msg) = failure(client.solve_patch(request(bad)).await);
        assert_eq!(code, Code::InvalidArgument, "{field}: {msg}");
        assert!(msg.contains(&format!("`{field}`")), "{field}: {msg}");
    }
    // The exact model only: every other refuses the section by its name
    // (the conformal ones on a conformal geometry, which they need).
    let conformal = Some(pb::GeometrySection {
        kind: pb::GeometryKind::ConformalCircular as i32,
        rail_lateral_radius_m: Some(0.010),
        wheel_lateral_radius_m: Some(-0.0101),
        wheel_rolling_radius_m: Some(0.5),
        ..Default::default()
    });
    for (model, geometry) in [
        (pb::Model::Hertz, None),
        (pb::Model::Fastsim, None),
        (pb::Model::HertzCorrected, conformal.clone()),
        (pb::Model::Cect, conformal.clone()),
        (pb::Model::CectHalfspace, conformal),
    ] {
        let mut c = pb::PatchCase {
            viscoelastic: Some(visc),
            ..rolling(model, 16, 1e-3)
        };
        if geometry.is_some() {
            c.geometry = geometry;
        }
        let (code, msg) = failure(client.solve_patch(request(c)).await);
        assert_eq!(code, Code::InvalidArgument, "{model:?}: {msg}");
        assert!(msg.contains("`case.viscoelastic`"), "{model:?}: {msg}");
    }
    server.shutdown().await;
}

/// A plastic interfacial layer's history in a session: transient shift
/// steps under a layer that flows give the batch solve's numbers, and a
/// rollback to a mark brings the layer's state back with the tractions
/// (the replay gives the same bits, the layer's fields included).
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_plastic_layers_history_rolls_back_with_its_session() {
    let (server, mut client) = server().await;
    let shifts = [1e-6, 1e-6, -2e-6, 1e-6];
    let case = pb::PatchCase {
        interfacial_layer: Some(pb::InterfacialLayerSection {
            thickness_m: 2.0e-5,
            shear_modulus_pa: 1.0e10,
            yield_limit_pa: 2.0e7,
            hardening_pa_per_m: 1.0e12,
        }),
        ..transient(20, &shifts)
    };
    let whole = solve_patch(&mut client, case.clone()).await;
    assert_eq!(whole.steps.len(), 4);
    let rest: Vec<_> = shifts[1..].iter().map(|&x| StepMotion::Shift(x)).collect();
    let r = session(
        &mut client,
        marked_twice(case, StepMotion::Shift(shifts[0]), &rest),
    )
    .await;
    assert_first_pass_is_the_batch(&r, &whole);
    let fields = |k: usize| step_result(&r[k]).fields.clone().expect("fields");
    assert!(
        fields(2).layer_plastic.iter().any(|p| *p),
        "the layer flows in the second step"
    );
    // Hardened where it flowed: the yield limit rose above tau_c0.
    assert!(fields(4).layer_yield_limit_pa.iter().any(|t| *t > 2.0e7));
    assert_replayed(&r, 1..4, 4);
    server.shutdown().await;
}
