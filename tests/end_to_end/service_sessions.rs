//! Sessions that no client can poison or bloat, end to end over gRPC (the
//! real server in-process on an ephemeral loopback port):
//!
//! - a refused step, whatever refused it (its inputs, the solver, a
//!   non-finite result) leaves the session bit for bit as it was: the
//!   steps after it equal a replay that never sent it, for every patch
//!   session kind and model and every wheel/rail model;
//! - a session's live working state and its marks count against the
//!   memory limits per session and per server, and return when it closes;
//! - a step response above the message limit is refused in-band;
//! - an idle session is closed with an in-band error and frees its slot.

use prost::Message;
use railcontact::service::config::ServeConfig;
use railcontact::service::pb;
use railcontact::service::server::RunningServer;
use railcontact::service::wheelrail::query_of;
use railcontact::wheelrail::builtin::mbench_a22_input;
use railcontact::wheelrail::WheelRailModel;
use tokio::sync::mpsc;
use tokio_stream::wrappers::ReceiverStream;
use tokio_stream::StreamExt;
use tonic::{Code, Status, Streaming};

use crate::common;
use common::{metrics_page, serve, server_with, sphere, Client};

type Step = pb::SessionStep;
use pb::session_response::Kind as Out;
use pb::session_step::Load;

/// A server on an ephemeral port with `config`'s limits; pairs in memory.
/// The messages of a response stream up to its end: all of them, and the
/// status it ended with unless OK.
async fn drain<R>(mut out: Streaming<R>) -> (Vec<R>, Option<Status>) {
    let mut messages = Vec::new();
    while let Some(r) = out.next().await {
        match r {
            Ok(m) => messages.push(m),
            Err(s) => return (messages, Some(s)),
        }
    }
    (messages, None)
}

/// The `n` responses of a stream that ends OK.
async fn complete<R>(out: Result<tonic::Response<Streaming<R>>, Status>, n: usize) -> Vec<R> {
    let (responses, status) = drain(out.unwrap().into_inner()).await;
    assert!(status.is_none(), "{status:?}");
    assert_eq!(responses.len(), n, "one response per request");
    responses
}

/// The value of the unlabelled metric `name` on the metrics page.
async fn metric(server: &RunningServer, name: &str) -> f64 {
    let page = metrics_page(server.metrics_addr.expect("a metrics port")).await;
    page.lines()
        .find_map(|l| l.strip_prefix(&format!("{name} ")))
        .unwrap_or_else(|| panic!("{name} not on the page:\n{page}"))
        .parse()
        .unwrap()
}

/// What the steps of a patch session prescribe.
#[derive(Clone, Copy, Debug)]
enum Kind {
    Frictionless,
    Rolling,
    Transient,
    /// A shift, then rolling steps of one element (0.6 mm of a 16 x 16
    /// grid over 9.6 mm).
    TransientRolling,
}

/// h = x² + y² (R = 0.5 m), 10 kN, steel on steel, `n` x `n` elements,
/// with friction 0.3 unless frictionless.
fn case(model: pb::Model, kind: Kind, n: u32) -> pb::PatchCase {
    let mut c = sphere(model, n);
    let friction = Some(pb::FrictionSection {
        coefficient: Some(0.3),
        ..Default::default()
    });
    match kind {
        Kind::Frictionless => {}
        Kind::Rolling => {
            c.friction = friction;
            c.kinematics = Some(pb::patch_case::Kinematics::Rolling(pb::Creepages::default()));
        }
        Kind::Transient | Kind::TransientRolling => {
            c.friction = friction;
            let rolling = matches!(kind, Kind::TransientRolling);
            c.kinematics = Some(pb::patch_case::Kinematics::Transient(
                pb::TransientSection {
                    steps: vec![pb::ShiftStep {
                        shift_x_m: Some(1e-6),
                        ..Default::default()
                    }],
                    rolling_step_m: rolling.then_some(6e-4),
                    steady_start: None,
                },
            ));
            if rolling {
                let g = c.grid.as_mut().unwrap();
                g.window_x_m = Some(9.6e-3);
                g.window_y_m = Some(9.6e-3);
            }
        }
    }
    c
}

/// The paper's conformal Case 1 at 80 kN (model cect), rolling, 20 x 20.
fn cect_case() -> pb::PatchCase {
    pb::PatchCase {
        model: pb::Model::Cect as i32,
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
        ..case(pb::Model::Cect, Kind::Rolling, 20)
    }
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

fn request(kind: pb::session_request::Kind) -> pb::SessionRequest {
    pb::SessionRequest { kind: Some(kind) }
}

/// Valid step `k` of a session of `kind`: load, creepages and shifts
/// moving along a smooth path (so that the warm start's prediction is in
/// use).
fn valid(kind: Kind, k: u64) -> Step {
    let f = k as f64;
    let mut s = Step {
        step_index: k,
        time_s: f * 1e-3,
        load: Some(Load::NormalForceN(1e4 * (1.0 + 0.02 * f))),
        ..Default::default()
    };
    match kind {
        Kind::Frictionless => {}
        Kind::Rolling => {
            s.creepages = Some(pb::Creepages {
                creepage_long: 1e-3 * (1.0 + 0.1 * f),
                creepage_lat: 0.5e-3 * (1.0 + 0.1 * f),
                spin_per_m: 0.2,
                ..Default::default()
            })
        }
        Kind::Transient => {
            s.shift = Some(pb::ShiftStep {
                shift_x_m: Some(1e-6 * (1.0 + 0.2 * f)),
                ..Default::default()
            })
        }
        Kind::TransientRolling if k == 0 => {
            s.shift = Some(pb::ShiftStep {
                shift_x_m: Some(1e-6),
                ..Default::default()
            })
        }
        Kind::TransientRolling => {
            s.shift = Some(pb::ShiftStep {
                creepage_long: Some(1e-3 * (1.0 + 0.1 * f)),
                creepage_lat: Some(0.5e-3),
                spin_per_m: Some(0.2),
                ..Default::default()
            })
        }
    }
    s
}

/// A step that the server refuses: what changes a valid step, the code and
/// the field path it must name.
struct Refusal {
    what: &'static str,
    change: fn(&mut Step),
    code: Code,
    field: &'static str,
}

fn negative_load(s: &mut Step) {
    s.load = Some(Load::NormalForceN(-1.0));
}
/// An approach below the smallest undeformed distance: no contact.
fn no_contact(s: &mut Step) {
    s.load = Some(Load::ApproachM(1e-12));
}
/// A patch far larger than the grid.
fn beyond_grid(s: &mut Step) {
    s.load = Some(Load::NormalForceN(1e6));
}
fn huge_spin(s: &mut Step) {
    s.creepages.as_mut().unwrap().spin_per_m = 1e300;
}

/// A prescribed force beyond mu Fn: no finite creepage gives it.
fn prescribed_force(s: &mut Step) {
    s.creepages.as_mut().unwrap().force_x_n = Some(-1e7);
}

/// A rolling step that also gives a shift.
fn rolling_shift(s: &mut Step) {
    s.shift.as_mut().unwrap().shift_x_m = Some(1e-6);
}

/// A step that sets its own falling-law start (a case's transient steps
/// take one; a session's take the case's friction.start).
fn friction_start(s: &mut Step) {
    s.shift.as_mut().unwrap().friction_start = pb::SlipStart::Sliding as i32;
}

const FRICTION_START: Refusal = Refusal {
    what: "a step's own friction start",
    change: friction_start,
    code: Code::InvalidArgument,
    field: "step.shift.friction_start",
};
const ROLLING_SHIFT: Refusal = Refusal {
    what: "rolling step with a shift",
    change: rolling_shift,
    code: Code::InvalidArgument,
    field: "step.shift.shift_x_m",
};
const PRESCRIBED_FORCE: Refusal = Refusal {
    what: "prescribed force beyond saturation",
    change: prescribed_force,
    code: Code::InvalidArgument,
    field: "step.creepages.force_x_n",
};
const NEGATIVE_LOAD: Refusal = Refusal {
    what: "negative load",
    change: negative_load,
    code: Code::InvalidArgument,
    field: "step.normal_force_n",
};
const NO_CONTACT: Refusal = Refusal {
    what: "no contact",
    change: no_contact,
    code: Code::InvalidArgument,
    field: "step.approach_m",
};
const BEYOND_GRID: Refusal = Refusal {
    what: "patch beyond the grid",
    change: beyond_grid,
    code: Code::InvalidArgument,
    field: "open.case.grid.window_x_m",
};
const HUGE_SPIN: Refusal = Refusal {
    what: "spin 1e300",
    change: huge_spin,
    code: Code::InvalidArgument,
    field: "step.creepages.spin_per_m",
};

/// Sends `messages` on one session and returns every response (the first
/// is `opened`); the stream must end without an error.
async fn session(client: &mut Client, messages: Vec<pb::SessionRequest>) -> Vec<Out> {
    let n = messages.len();
    let out = client.patch_session(tokio_stream::iter(messages)).await;
    let responses = complete(out, n).await;
    responses.into_iter().map(|r| r.kind.unwrap()).collect()
}

/// A step's answer as bytes, its solve time cleared: equal bytes are equal
/// bits of every total, counter and field.
fn step_bytes(r: &Out) -> Vec<u8> {
    let Out::Step(s) = r else {
        panic!("expected a step, got {r:?}")
    };
    let mut s = s.clone();
    if let Some(info) = s.result.as_mut().and_then(|r| r.info.as_mut()) {
        info.solve_time_s = 0.0;
    }
    s.encode_to_vec()
}

fn item_error(r: &Out) -> &pb::ItemError {
    match r {
        Out::Error(e) => e,
        Out::Step(s) => panic!("expected an error, got step {}", s.step_index),
        other => panic!("expected an error, got {other:?}"),
    }
}

/// Steps 0-2, then each refusal in turn at index 3 (every other one), then
/// steps 3-5: each refusal is answered in-band with its code and field,
/// and the valid steps equal those of a session that never sent them, bit
/// for bit.
async fn refusals_leave_no_trace(
    client: &mut Client,
    case: pb::PatchCase,
    kind: Kind,
    fields: bool,
    refusals: &[Refusal],
) {
    let step = |s: Step| request(pb::session_request::Kind::Step(s));
    let mut plain = vec![open(case.clone(), fields)];
    plain.extend((0..6).map(|k| step(valid(kind, k))));
    let replay = session(client, plain).await;
    let mut msgs = vec![open(case.clone(), fields)];
    msgs.extend((0..3).map(|k| step(valid(kind, k))));
    for r in refusals {
        let mut s = valid(kind, 3);
        (r.change)(&mut s);
        msgs.push(step(s));
    }
    msgs.extend((3..6).map(|k| step(valid(kind, k))));
    let got = session(client, msgs).await;
    let n = refusals.len();
    for (i, r) in refusals.iter().enumerate() {
        let Out::Error(e) = &got[4 + i] else {
            panic!("{kind:?} {:?}, {}: not refused", case.model, r.what)
        };
        assert_eq!(
            (Code::from(e.code), e.field.as_str()),
            (r.code, r.field),
            "{kind:?} {:?}, {}: {}",
            case.model,
            r.what,
            e.message
        );
    }
    for k in 1..=3 {
        assert_eq!(
            step_bytes(&got[k]),
            step_bytes(&replay[k]),
            "{kind:?} {:?} step {}",
            case.model,
            k - 1
        );
    }
    for k in 4..=6 {
        assert_eq!(
            step_bytes(&got[n + k]),
            step_bytes(&replay[k]),
            "{kind:?} {:?}: step {} after the refusals",
            case.model,
            k - 1
        );
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn refused_patch_steps_leave_exact_sessions_bit_for_bit_as_they_were() {
    let (server, mut client) = server_with(ServeConfig::default()).await;
    let exact = pb::Model::Exact;
    refusals_leave_no_trace(
        &mut client,
        case(exact, Kind::Frictionless, 16),
        Kind::Frictionless,
        true,
        &[NEGATIVE_LOAD, NO_CONTACT, BEYOND_GRID],
    )
    .await;
    refusals_leave_no_trace(
        &mut client,
        case(exact, Kind::Rolling, 16),
        Kind::Rolling,
        true,
        &[
            NEGATIVE_LOAD,
            NO_CONTACT,
            BEYOND_GRID,
            HUGE_SPIN,
            PRESCRIBED_FORCE,
        ],
    )
    .await;
    refusals_leave_no_trace(
        &mut client,
        case(exact, Kind::Transient, 16),
        Kind::Transient,
        true,
        &[NEGATIVE_LOAD, NO_CONTACT, BEYOND_GRID],
    )
    .await;
    refusals_leave_no_trace(
        &mut client,
        case(exact, Kind::TransientRolling, 16),
        Kind::TransientRolling,
        true,
        &[NEGATIVE_LOAD, NO_CONTACT, BEYOND_GRID, ROLLING_SHIFT],
    )
    .await;
    server.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn refused_steps_leave_falling_friction_sessions_bit_for_bit_as_they_were() {
    // A transient rolling session under exponential falling friction: the
    // law's coefficients and slip velocities travel with the material from
    // step to step, and a step refused after it was solved (the patch
    // beyond the grid) puts them back with the rest.
    let (server, mut client) = server_with(ServeConfig::default()).await;
    let mut c = case(pb::Model::Exact, Kind::TransientRolling, 16);
    c.friction = Some(pb::FrictionSection {
        law: pb::FrictionLaw::Exponential as i32,
        kinetic_coefficient: Some(0.2),
        falling_coefficients: vec![0.1],
        half_velocities_m_per_s: vec![0.05],
        rolling_speed_m_per_s: Some(10.0),
        ..Default::default()
    });
    refusals_leave_no_trace(
        &mut client,
        c,
        Kind::TransientRolling,
        true,
        &[NEGATIVE_LOAD, BEYOND_GRID, ROLLING_SHIFT, FRICTION_START],
    )
    .await;
    server.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn refused_patch_steps_leave_fastsim_hertz_and_cect_sessions_as_they_were() {
    let (server, mut client) = server_with(ServeConfig::default()).await;
    refusals_leave_no_trace(
        &mut client,
        case(pb::Model::Fastsim, Kind::Rolling, 16),
        Kind::Rolling,
        false,
        &[NEGATIVE_LOAD],
    )
    .await;
    refusals_leave_no_trace(
        &mut client,
        case(pb::Model::Hertz, Kind::Frictionless, 16),
        Kind::Frictionless,
        false,
        &[NEGATIVE_LOAD],
    )
    .await;
    refusals_leave_no_trace(
        &mut client,
        cect_case(),
        Kind::Rolling,
        false,
        &[NEGATIVE_LOAD],
    )
    .await;
    server.shutdown().await;
}

/// A server with `config`'s limits and a metrics port.
async fn metered(config: ServeConfig) -> (RunningServer, Client) {
    server_with(ServeConfig {
        metrics_listen: Some("127.0.0.1:0".parse().unwrap()),
        ..config
    })
    .await
}

/// A patch session's call: the sender of its requests and its responses.
async fn patch_call(
    client: &mut Client,
) -> (
    mpsc::Sender<pb::SessionRequest>,
    Streaming<pb::SessionResponse>,
) {
    let (tx, rx) = mpsc::channel(8);
    let out = client.patch_session(ReceiverStream::new(rx)).await;
    (tx, out.unwrap().into_inner())
}

/// The memory a session of `c` holds once opened, after its first and
/// after its second (unmarked) step \[bytes\], its live working state:
/// measured on a server of its own, from `railcontact_session_bytes` while
/// it is the only session. (The first step allocates the solver's Newton
/// scratch and prediction, the second the undo copy of the prediction.)
async fn live_bytes(c: &pb::PatchCase, kind: Kind) -> [usize; 3] {
    let (server, mut client) = metered(ServeConfig::default()).await;
    let (tx, mut out) = patch_call(&mut client).await;
    let mut held = Vec::new();
    for m in [
        open(c.clone(), false),
        request(pb::session_request::Kind::Step(valid(kind, 0))),
        request(pb::session_request::Kind::Step(valid(kind, 1))),
    ] {
        tx.send(m).await.unwrap();
        let r = out.next().await.unwrap().unwrap().kind.unwrap();
        assert!(matches!(r, Out::Opened(_) | Out::Step(_)), "{r:?}");
        held.push(metric(&server, "railcontact_session_bytes").await as usize);
    }
    drop(tx);
    assert!(out.next().await.is_none());
    server.shutdown().await;
    [held[0], held[1], held[2]]
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn marks_count_against_the_session_and_server_budgets() {
    // A mark of an exact session on n elements keeps 5 f64 fields, two
    // element states and the prediction's 3 f64 fields: 66 bytes an
    // element and the few bytes of the state itself. The limits hold the
    // session's live working state besides (its solver's buffers).
    let n = 16 * 16;
    let mark = 66 * n;
    let kind = Kind::Rolling;
    let [_, _, live] = live_bytes(&case(pb::Model::Exact, kind, 16), kind).await;
    let (server, mut client) = metered(ServeConfig {
        max_session_bytes: live + 3 * mark + mark / 2,
        max_sessions_total_bytes: 2 * live + 4 * mark + mark / 2,
        ..ServeConfig::default()
    })
    .await;
    let marked = |k: u64| {
        let mut s = valid(kind, k);
        s.mark = true;
        request(pb::session_request::Kind::Step(s))
    };
    let step = |k: u64| request(pb::session_request::Kind::Step(valid(kind, k)));
    let back = |to: u64| {
        request(pb::session_request::Kind::Rollback(pb::SessionRollback {
            to_step_index: to,
        }))
    };
    let c = case(pb::Model::Exact, kind, 16);
    // Marks 0, 1 and 2 fit; the fourth is refused and its step not applied
    // (step 3 comes again, unmarked, and equals the replay); after a
    // rollback to 1 (mark 2 dropped) a mark fits again.
    let msgs = vec![
        open(c.clone(), false),
        marked(0),
        marked(1),
        marked(2),
        marked(3),
        step(3),
        step(4),
        back(1),
        marked(2),
    ];
    let got = session(&mut client, msgs).await;
    let replay = session(
        &mut client,
        vec![
            open(c.clone(), false),
            step(0),
            step(1),
            step(2),
            step(3),
            step(4),
        ],
    )
    .await;
    let e = item_error(&got[4]);
    assert_eq!(Code::from(e.code), Code::ResourceExhausted, "{}", e.message);
    assert!(
        e.message.contains("max_session_bytes") && e.message.contains("marked: 0, 1, 2"),
        "{}",
        e.message
    );
    for (a, b) in [(5, 4), (6, 5)] {
        assert_eq!(step_bytes(&got[a]), step_bytes(&replay[b]));
    }
    assert!(matches!(got[7], Out::RolledBack(_)), "{:?}", got[7]);
    assert_eq!(step_bytes(&got[8]), step_bytes(&got[3]), "step 2 again");
    assert_eq!(
        metric(&server, "railcontact_session_marks_refused_total").await,
        1.0
    );
    assert_eq!(metric(&server, "railcontact_session_mark_bytes").await, 0.0);

    // The server's total: a session holding three marks leaves room for one
    // more in another session, not two; closing it frees its marks.
    let (tx, mut first) = patch_call(&mut client).await;
    for m in [open(c.clone(), false), marked(0), marked(1), marked(2)] {
        tx.send(m).await.unwrap();
        let r = first.next().await.unwrap().unwrap().kind.unwrap();
        assert!(matches!(r, Out::Opened(_) | Out::Step(_)), "{r:?}");
    }
    let held = metric(&server, "railcontact_session_mark_bytes").await;
    assert!(
        held > 3.0 * mark as f64 && held < 3.5 * mark as f64,
        "{held}"
    );
    let other = vec![open(c.clone(), false), marked(0), marked(1)];
    let got = session(&mut client, other.clone()).await;
    assert!(matches!(got[1], Out::Step(_)), "{:?}", got[1]);
    let e = item_error(&got[2]);
    assert_eq!(Code::from(e.code), Code::ResourceExhausted);
    assert!(
        e.message.contains("max_sessions_total_bytes"),
        "{}",
        e.message
    );
    drop(tx);
    assert!(first.next().await.is_none());
    let got = session(&mut client, other).await;
    assert!(matches!(got[2], Out::Step(_)), "{:?}", got[2]);
    server.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn live_state_counts_against_the_server_and_returns_when_sessions_close() {
    // An exact rolling session on 24 x 24: its solver's buffers once
    // opened, and after its first step also the Newton scratch and the
    // prediction's fields. The server holds one such session and a second
    // one opened, not two that have stepped.
    let kind = Kind::Rolling;
    let c = case(pb::Model::Exact, kind, 24);
    let [opened, stepped, steady] = live_bytes(&c, kind).await;
    assert!(
        opened < stepped && stepped <= steady,
        "{opened} {stepped} {steady}"
    );
    let total = steady + (opened + stepped) / 2;
    let (server, client) = metered(ServeConfig {
        max_sessions_total_bytes: total,
        ..ServeConfig::default()
    })
    .await;
    let step = |k: u64| request(pb::session_request::Kind::Step(valid(kind, k)));
    let held = || metric(&server, "railcontact_session_bytes");
    let start = |c: pb::PatchCase| {
        let mut client = client.clone();
        async move {
            let (tx, out) = patch_call(&mut client).await;
            tx.send(open(c, false)).await.unwrap();
            (tx, out)
        }
    };
    async fn answer(out: &mut Streaming<pb::SessionResponse>) -> Out {
        out.next().await.unwrap().unwrap().kind.unwrap()
    }
    let (first_tx, mut first) = start(c.clone()).await;
    assert!(matches!(answer(&mut first).await, Out::Opened(_)));
    for k in 0..2 {
        first_tx.send(step(k)).await.unwrap();
        assert!(matches!(answer(&mut first).await, Out::Step(_)));
    }
    assert_eq!(held().await as usize, steady);

    // The second session opens; its first step would take the server
    // beyond its total: refused in-band, twice, and it gives back what the
    // step allocated. The first session keeps stepping meanwhile.
    let (second_tx, mut second) = start(c.clone()).await;
    assert!(matches!(answer(&mut second).await, Out::Opened(_)));
    for k in 2..4 {
        second_tx.send(step(0)).await.unwrap();
        let e = item_error(&answer(&mut second).await).clone();
        assert_eq!(Code::from(e.code), Code::ResourceExhausted, "{}", e.message);
        assert!(
            e.message.contains("max_sessions_total_bytes")
                && e.message.contains(&format!("({total} bytes)"))
                && e.message
                    .contains(&format!("{stepped} bytes of working state")),
            "{}",
            e.message
        );
        assert_eq!(held().await as usize, steady + opened);
        first_tx.send(step(k)).await.unwrap();
        assert!(matches!(answer(&mut first).await, Out::Step(_)));
    }
    assert_eq!(
        metric(&server, "railcontact_session_memory_refused_total").await,
        2.0
    );

    // The first session closes: its bytes return, and the second one's
    // step fits.
    drop(first_tx);
    assert!(first.next().await.is_none());
    second_tx.send(step(0)).await.unwrap();
    assert!(matches!(answer(&mut second).await, Out::Step(_)));
    assert_eq!(held().await as usize, stepped);
    drop(second_tx);
    assert!(second.next().await.is_none());
    assert_eq!(held().await, 0.0);
    assert_eq!(metric(&server, "railcontact_session_mark_bytes").await, 0.0);
    server.shutdown().await;
}

/// An exact steady-rolling session on 256 x 256 elements (the largest
/// grid by default), h = x² + y² (R = 0.5 m), 10 kN, mu 0.3, in process:
/// after two steps its live state is the solver's buffers (the Newton
/// scratch included), the gap and the undo copy; with `MAX_MARKS` marks
/// of its state it fits the default `max_session_bytes`, and its live
/// state alone is more than the 64 MiB that limit was when it counted
/// marks only. Printed with `--nocapture`.
#[test]
fn an_exact_session_on_the_largest_grid_fits_the_default_limit() {
    use railcontact::core::cache::KernelCache;
    use railcontact::service::convert::{validate_case, CaseLimits};
    use railcontact::service::engine::PatchEngine;
    use railcontact::service::memory::SessionBudget;
    use railcontact::service::session::{Session, SessionLimits, MAX_MARKS};
    let n = 256;
    let c = case(pb::Model::Exact, Kind::Rolling, n);
    let config = ServeConfig::default();
    let limits = CaseLimits {
        max_grid_elements: config.max_grid_elements,
    };
    let engine = PatchEngine::new(validate_case(&c, limits).unwrap(), &KernelCache::default());
    let budget = SessionBudget::new(config.max_session_bytes, config.max_sessions_total_bytes);
    let limits = SessionLimits {
        max_response_bytes: config.max_message_bytes,
        memory: budget.clone(),
        max_grid_elements: config.max_grid_elements,
    };
    let mut session = Session::open(engine.unwrap(), false, limits).unwrap();
    let opened = session.live_bytes();
    for k in 0..2 {
        let input = session.check_step(&valid(Kind::Rolling, k)).unwrap();
        session.step(input).unwrap();
    }
    let live = session.live_bytes();
    assert_eq!(budget.total_bytes(), live);
    let mark = session.engine().state_bytes();
    let full = live + MAX_MARKS * mark;
    println!(
        "exact 256 x 256 session: {opened} bytes opened, {live} after two steps ({} an \
         element), a mark {mark}: {full} with {MAX_MARKS} marks",
        live / (n * n) as usize
    );
    assert!(full <= config.max_session_bytes, "{full}");
    assert!(live > 64 << 20, "{live}");
    drop(session);
    assert_eq!(budget.total_bytes(), 0);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_session_whose_solver_does_not_fit_is_not_opened() {
    let kind = Kind::Rolling;
    let c = case(pb::Model::Exact, kind, 24);
    let [opened, _, _] = live_bytes(&c, kind).await;
    let (server, mut client) = metered(ServeConfig {
        max_session_bytes: opened - 1,
        ..ServeConfig::default()
    })
    .await;
    let out = client
        .patch_session(tokio_stream::iter([open(c, false)]))
        .await
        .unwrap()
        .into_inner();
    let (messages, status) = drain(out).await;
    assert!(messages.is_empty(), "{messages:?}");
    let status = status.expect("the stream ends with a status");
    assert_eq!(status.code(), Code::ResourceExhausted, "{status:?}");
    assert!(
        status.message().contains("max_session_bytes")
            && status
                .message()
                .contains(&format!("takes {opened} bytes of working state")),
        "{}",
        status.message()
    );
    assert_eq!(metric(&server, "railcontact_session_bytes").await, 0.0);
    server.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_step_response_above_the_message_limit_is_refused_in_band() {
    // 16 x 16 fields take about 12 kB; the session's requests far less.
    let (server, mut client) = server_with(ServeConfig {
        max_message_bytes: 4000,
        ..ServeConfig::default()
    })
    .await;
    let kind = Kind::Rolling;
    let step = |k: u64| request(pb::session_request::Kind::Step(valid(kind, k)));
    let got = session(
        &mut client,
        vec![
            open(case(pb::Model::Exact, kind, 16), true),
            step(0),
            step(0),
        ],
    )
    .await;
    for r in &got[1..] {
        let e = item_error(r);
        assert_eq!(Code::from(e.code), Code::ResourceExhausted, "{}", e.message);
        assert!(
            e.message.contains("max_message_bytes") && e.message.contains("open.include_fields"),
            "{}",
            e.message
        );
    }
    // Without fields the same steps are answered.
    let got = session(
        &mut client,
        vec![open(case(pb::Model::Exact, kind, 16), false), step(0)],
    )
    .await;
    assert!(matches!(got[1], Out::Step(_)), "{:?}", got[1]);
    server.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn idle_sessions_are_closed_in_band_and_free_their_slots() {
    let (server, mut client) = metered(ServeConfig {
        session_idle_timeout_s: 0.3,
        max_sessions: 1,
        ..ServeConfig::default()
    })
    .await;
    // A patch session that opens, steps once and then sends nothing while
    // keeping its stream open.
    let (tx, rx) = mpsc::channel(8);
    let out = client.patch_session(ReceiverStream::new(rx)).await;
    tx.send(open(case(pb::Model::Hertz, Kind::Frictionless, 16), false))
        .await
        .unwrap();
    tx.send(request(pb::session_request::Kind::Step(valid(
        Kind::Frictionless,
        0,
    ))))
    .await
    .unwrap();
    let (messages, status) = drain(out.unwrap().into_inner()).await;
    let status = status.expect("the stream ends with a status");
    let kinds: Vec<Out> = messages.into_iter().map(|r| r.kind.unwrap()).collect();
    assert!(matches!(kinds[0], Out::Opened(_)) && matches!(kinds[1], Out::Step(_)));
    let e = item_error(&kinds[2]);
    assert_eq!(Code::from(e.code), Code::DeadlineExceeded);
    assert!(
        e.message.contains("session_idle_timeout_s"),
        "{}",
        e.message
    );
    assert_eq!(kinds.len(), 3);
    assert_eq!(status.code(), Code::DeadlineExceeded, "{status:?}");
    assert!(status.message().contains("idle"), "{status:?}");
    // Its slot is free: a session opens on this one-session server.
    let got = session(
        &mut client,
        vec![open(case(pb::Model::Hertz, Kind::Frictionless, 16), false)],
    )
    .await;
    assert!(matches!(got[0], Out::Opened(_)), "{:?}", got[0]);

    // A wheel/rail session that idles after opening.
    let (wtx, wrx) = mpsc::channel(8);
    let wout = client.wheel_rail_session(ReceiverStream::new(wrx)).await;
    wtx.send(wr_open(pb::WheelRailModel::HertzFastsim))
        .await
        .unwrap();
    let (messages, status) = drain(wout.unwrap().into_inner()).await;
    let status = status.expect("the stream ends with a status");
    let kinds: Vec<WrOut> = messages.into_iter().map(|r| r.kind.unwrap()).collect();
    assert!(matches!(kinds[0], WrOut::Opened(_)), "{:?}", kinds[0]);
    match &kinds[1] {
        WrOut::Error(e) => assert_eq!(Code::from(e.code), Code::DeadlineExceeded),
        other => panic!("{other:?}"),
    }
    assert_eq!(status.code(), Code::DeadlineExceeded, "{status:?}");
    assert_eq!(
        metric(&server, "railcontact_sessions_idle_closed_total").await,
        2.0
    );
    assert_eq!(metric(&server, "railcontact_sessions_active").await, 0.0);
    drop((tx, wtx));
    server.shutdown().await;
}

// ---------------------------------------------------------------------
// Wheel/rail sessions
// ---------------------------------------------------------------------

use pb::wheel_rail_session_request::Kind as WrIn;
use pb::wheel_rail_session_response::Kind as WrOut;

fn wr_open(model: pb::WheelRailModel) -> pb::WheelRailSessionRequest {
    pb::WheelRailSessionRequest {
        kind: Some(WrIn::Open(pb::WheelRailSessionOpen {
            pair_id: "mbench_s1002_uic60".into(),
            model: model as i32,
            client_label: "test".into(),
            ..Default::default()
        })),
    }
}

/// Step `k` of a wheelset drifting 0.05 mm a step from 3 mm (Manchester
/// A-2.2's inputs, roll from the profiles).
fn wr_step(k: u64) -> pb::WheelRailSessionStep {
    let mm = 3.0 + 0.05 * k as f64;
    let q = query_of(
        "mbench_s1002_uic60",
        &mbench_a22_input(mm, None, None, WheelRailModel::Exact),
    );
    pb::WheelRailSessionStep {
        step_index: k,
        time_s: k as f64 * 1e-3,
        position: q.position,
        velocity: q.velocity,
        load: q.load,
        mark: false,
    }
}

fn wr_request(s: pb::WheelRailSessionStep) -> pb::WheelRailSessionRequest {
    pb::WheelRailSessionRequest {
        kind: Some(WrIn::Step(s)),
    }
}

/// A wheel/rail step's answer as bytes, its timing cleared.
fn wr_step_bytes(r: &WrOut) -> Vec<u8> {
    let WrOut::Step(s) = r else {
        panic!("expected a step, got {r:?}")
    };
    let mut s = s.clone();
    if let Some(r) = s.result.as_mut() {
        r.timing = None;
    }
    s.encode_to_vec()
}

async fn wr_session(client: &mut Client, messages: Vec<pb::WheelRailSessionRequest>) -> Vec<WrOut> {
    let n = messages.len();
    let out = client
        .wheel_rail_session(tokio_stream::iter(messages))
        .await;
    let responses = complete(out, n).await;
    responses.into_iter().map(|r| r.kind.unwrap()).collect()
}

/// Wheel/rail steps that the server refuses.
type WrRefusal = (
    &'static str,
    fn(&mut pb::WheelRailSessionStep),
    &'static str,
);

fn wr_no_velocity(s: &mut pb::WheelRailSessionStep) {
    s.velocity = None;
}
fn wr_huge_yaw(s: &mut pb::WheelRailSessionStep) {
    s.position.as_mut().unwrap().yaw_rad = 0.5;
}
/// A lateral shift no wheel touches its rail at.
fn wr_off_track(s: &mut pb::WheelRailSessionStep) {
    s.position.as_mut().unwrap().lateral_m = 0.2;
}

const WR_REFUSALS: [WrRefusal; 3] = [
    ("no velocity", wr_no_velocity, "step.velocity"),
    ("yaw 0.5 rad", wr_huge_yaw, "step.position"),
    ("off the track", wr_off_track, "step"),
];

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn refused_wheel_rail_steps_leave_every_model_as_it_was() {
    let (server, mut client) = server_with(ServeConfig::default()).await;
    for model in [
        pb::WheelRailModel::Exact,
        pb::WheelRailModel::HertzFastsim,
        pb::WheelRailModel::HertzFastsimTable,
        pb::WheelRailModel::Auto,
    ] {
        let mut plain = vec![wr_open(model)];
        plain.extend((0..5).map(|k| wr_request(wr_step(k))));
        let replay = wr_session(&mut client, plain).await;
        let mut msgs = vec![wr_open(model)];
        msgs.extend((0..3).map(|k| wr_request(wr_step(k))));
        for (_, change, _) in &WR_REFUSALS {
            let mut s = wr_step(3);
            change(&mut s);
            msgs.push(wr_request(s));
        }
        msgs.extend((3..5).map(|k| wr_request(wr_step(k))));
        let got = wr_session(&mut client, msgs).await;
        for (i, (what, _, field)) in WR_REFUSALS.iter().enumerate() {
            match &got[4 + i] {
                WrOut::Error(e) => assert!(
                    Code::from(e.code) == Code::InvalidArgument && e.field.starts_with(field),
                    "{model:?}, {what}: {e:?}"
                ),
                other => panic!("{model:?}, {what}: {other:?}"),
            }
        }
        let n = WR_REFUSALS.len();
        for (a, b) in [(1, 1), (2, 2), (3, 3), (4 + n, 4), (5 + n, 5)] {
            assert_eq!(
                wr_step_bytes(&got[a]),
                wr_step_bytes(&replay[b]),
                "{model:?}: response {a}"
            );
        }
    }
    server.shutdown().await;
}

/// Two steps of a session opened by `open` (steps `step(0)`, `step(1)`)
/// on a server that runs no other: what the server counts for it
/// then, and after it closed \[bytes\].
async fn held_by<I, O: std::fmt::Debug>(
    server: &RunningServer,
    run: impl FnOnce(ReceiverStream<I>) -> BoxFuture<Streaming<O>>,
    messages: [I; 3],
) -> (f64, f64) {
    let (tx, rx) = mpsc::channel(8);
    let mut out = run(ReceiverStream::new(rx)).await;
    for m in messages {
        tx.send(m).await.unwrap();
        let r = out.next().await.unwrap().unwrap();
        assert!(!format!("{r:?}").contains("Error("), "{r:?}");
    }
    let held = metric(server, "railcontact_session_bytes").await;
    drop(tx);
    assert!(out.next().await.is_none());
    (held, metric(server, "railcontact_session_bytes").await)
}

type BoxFuture<T> = std::pin::Pin<Box<dyn std::future::Future<Output = T> + Send>>;

/// What each kind of session holds between steps, counted by the server
/// (printed with `--nocapture`), and given back when it closes: the exact
/// model's solver buffers (steady and transient), a conformal patch's
/// workspace, nothing for the fast patch models; on a wheelset (A-2.2
/// near 3 mm) the exact model's two patch solvers and warm start, the
/// others' contact search and warm start.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn every_session_kind_counts_what_it_holds_and_gives_it_back() {
    let (server, client) = metered(ServeConfig::default()).await;
    let patch = |c: pb::PatchCase, kind: Kind| {
        let step = |k| request(pb::session_request::Kind::Step(valid(kind, k)));
        [open(c, false), step(0), step(1)]
    };
    let patches = [
        (
            "exact rolling 24 x 24",
            patch(case(pb::Model::Exact, Kind::Rolling, 24), Kind::Rolling),
        ),
        (
            "exact transient 16 x 16",
            patch(
                case(pb::Model::Exact, Kind::TransientRolling, 16),
                Kind::TransientRolling,
            ),
        ),
        ("cect rolling 20 x 20", patch(cect_case(), Kind::Rolling)),
        (
            "fastsim rolling 16 x 16",
            patch(case(pb::Model::Fastsim, Kind::Rolling, 16), Kind::Rolling),
        ),
        (
            "hertz",
            patch(
                case(pb::Model::Hertz, Kind::Frictionless, 16),
                Kind::Frictionless,
            ),
        ),
    ];
    for (what, messages) in patches {
        let mut c = client.clone();
        let run = move |rx| -> BoxFuture<_> {
            Box::pin(async move { c.patch_session(rx).await.unwrap().into_inner() })
        };
        let (held, after) = held_by(&server, run, messages).await;
        println!("patch session, {what}: {held} bytes");
        assert_eq!(after, 0.0, "{what}");
        if what.starts_with("exact") || what.starts_with("cect") {
            assert!(held > 0.0, "{what}");
        }
    }
    for model in [
        pb::WheelRailModel::Exact,
        pb::WheelRailModel::Cect,
        pb::WheelRailModel::HertzFastsim,
        pb::WheelRailModel::HertzFastsimTable,
    ] {
        let mut c = client.clone();
        let run = move |rx| -> BoxFuture<_> {
            Box::pin(async move { c.wheel_rail_session(rx).await.unwrap().into_inner() })
        };
        let messages = [
            wr_open(model),
            wr_request(wr_step(0)),
            wr_request(wr_step(1)),
        ];
        let (held, after) = held_by(&server, run, messages).await;
        println!("wheel/rail session, {model:?}: {held} bytes");
        assert!(held > 0.0, "{model:?}");
        assert_eq!(after, 0.0, "{model:?}");
    }
    server.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_wheel_rail_step_beyond_the_session_limit_is_refused_and_gives_back_its_solvers() {
    // An exact wheel/rail session on holds megabytes of patch
    // solvers after a step (see the test above), its contact search alone
    // 0.4 MB: with 2 MB a session, its steps are refused in-band and the
    // session keeps only the search; a Hertz+FASTSIM session fits.
    let max = 2 << 20;
    let (server, mut client) = metered(ServeConfig {
        max_session_bytes: max,
        ..ServeConfig::default()
    })
    .await;
    let (tx, rx) = mpsc::channel(8);
    let mut out = client
        .wheel_rail_session(ReceiverStream::new(rx))
        .await
        .unwrap()
        .into_inner();
    tx.send(wr_open(pb::WheelRailModel::Exact)).await.unwrap();
    let r = out.next().await.unwrap().unwrap().kind.unwrap();
    assert!(matches!(r, WrOut::Opened(_)), "{r:?}");
    for _ in 0..2 {
        tx.send(wr_request(wr_step(0))).await.unwrap();
        let r = out.next().await.unwrap().unwrap().kind.unwrap();
        let WrOut::Error(e) = r else {
            panic!("expected a refusal, got {r:?}")
        };
        assert_eq!(Code::from(e.code), Code::ResourceExhausted, "{}", e.message);
        assert!(
            e.message
                .contains(&format!("max_session_bytes ({max} bytes)")),
            "{}",
            e.message
        );
        let held = metric(&server, "railcontact_session_bytes").await;
        assert!(held > 0.0 && held < 0.5e6, "{held}");
    }
    let fast = wr_session(
        &mut client,
        vec![
            wr_open(pb::WheelRailModel::HertzFastsim),
            wr_request(wr_step(0)),
        ],
    )
    .await;
    assert!(matches!(fast[1], WrOut::Step(_)), "{:?}", fast[1]);
    drop(tx);
    assert!(out.next().await.is_none());
    assert_eq!(metric(&server, "railcontact_session_bytes").await, 0.0);
    server.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn idle_and_vanished_sessions_give_their_memory_back() {
    let (server, mut client) = metered(ServeConfig {
        session_idle_timeout_s: 0.3,
        ..ServeConfig::default()
    })
    .await;
    let kind = Kind::Rolling;
    let c = case(pb::Model::Exact, kind, 16);
    let step = request(pb::session_request::Kind::Step(valid(kind, 0)));
    // Idle: opens, steps, then sends nothing.
    let (tx, mut out) = patch_call(&mut client).await;
    for m in [open(c.clone(), false), step.clone()] {
        tx.send(m).await.unwrap();
        out.next().await.unwrap().unwrap();
    }
    assert!(metric(&server, "railcontact_session_bytes").await > 0.0);
    let (_, status) = drain(out).await;
    assert_eq!(status.unwrap().code(), Code::DeadlineExceeded);
    assert_eq!(metric(&server, "railcontact_session_bytes").await, 0.0);
    drop(tx);
    // Vanished: opens, steps, then drops its call.
    let (tx, mut out) = patch_call(&mut client).await;
    for m in [open(c, false), step] {
        tx.send(m).await.unwrap();
        out.next().await.unwrap().unwrap();
    }
    assert!(metric(&server, "railcontact_session_bytes").await > 0.0);
    drop((tx, out));
    let t = std::time::Instant::now();
    while metric(&server, "railcontact_session_bytes").await > 0.0 {
        assert!(
            t.elapsed().as_secs_f64() < 5.0,
            "the session's bytes stay counted"
        );
        tokio::time::sleep(std::time::Duration::from_millis(20)).await;
    }
    server.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn wheel_rail_session_patches_obey_max_grid_elements() {
    let (server, mut client) = serve(ServeConfig {
        data_dir: Default::default(),
        max_grid_elements: 400,
        ..Default::default()
    })
    .await;
    let open = pb::WheelRailSessionRequest {
        kind: Some(WrIn::Open(pb::WheelRailSessionOpen {
            pair_id: "mbench_s1002_uic60".into(),
            model: pb::WheelRailModel::Exact as i32,
            element_size_m: Some(6e-5),
            ..Default::default()
        })),
    };
    let responses: Vec<_> = client
        .wheel_rail_session(tokio_stream::iter(vec![open, wr_request(wr_step(0))]))
        .await
        .expect("the stream starts")
        .into_inner()
        .collect()
        .await;
    let Some(Ok(pb::WheelRailSessionResponse {
        kind: Some(WrOut::Error(e)),
    })) = responses.get(1)
    else {
        panic!("expected the step refused in-band, got {responses:?}")
    };
    assert_eq!(Code::from(e.code), Code::InvalidArgument, "{}", e.message);
    assert!(
        e.field.ends_with("element_size_m"),
        "{}: {}",
        e.field,
        e.message
    );
    assert!(e.message.contains("400"), "{}", e.message);
    server.shutdown().await;
}

/// Ctrl-C while a session is open: the server refuses new calls and gives
/// the session its grace period (60 s here), saying so in its log; a
/// second Ctrl-C stops it at once.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_second_ctrl_c_stops_at_once() {
    let mut server = crate::support::Server::start_with(
        &["--data-dir", ""],
        &[("RAILCONTACT_SHUTDOWN_GRACE_S", "60"), ("RUST_LOG", "info")],
    );
    let channel = tonic::transport::Endpoint::from_shared(format!("http://{}", server.addr))
        .unwrap()
        .connect()
        .await
        .unwrap();
    let mut client = Client::new(channel);
    let (tx, rx) = mpsc::channel(4);
    tx.send(open(sphere(pb::Model::Exact, 16), false))
        .await
        .unwrap();
    let mut answers = client
        .patch_session(ReceiverStream::new(rx))
        .await
        .unwrap()
        .into_inner();
    assert!(matches!(
        answers.next().await,
        Some(Ok(pb::SessionResponse {
            kind: Some(Out::Opened(_))
        }))
    ));
    server.interrupt();
    // The open session holds the server in its grace period.
    assert!(
        server
            .wait_exit(std::time::Duration::from_millis(700))
            .is_none(),
        "{}",
        server.log()
    );
    assert!(server.log().contains("a second Ctrl-C"), "{}", server.log());
    server.interrupt();
    let status = server.wait_exit(std::time::Duration::from_secs(10));
    assert!(
        status.is_some(),
        "still running 10 s after the second Ctrl-C: {}",
        server.log()
    );
    assert!(server.log().contains("stopping now"), "{}", server.log());
    drop(tx);
}
