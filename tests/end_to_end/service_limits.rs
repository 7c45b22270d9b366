//! The service's resource limits, end to end over gRPC: an oversize
//! request, a solve past the server's time limit, and a batch that must
//! not starve other requests.

use crate::common;

use std::time::{Duration, Instant};

use common::{sphere, Client};
use railcontact::service::config::ServeConfig;
use railcontact::service::pb;
use railcontact::service::server::RunningServer;
use tokio_stream::StreamExt;
use tonic::Code;

/// A server with `config` (pairs in memory only) and a client that sends
/// and accepts messages of up to 64 MiB.
async fn server_with(config: ServeConfig) -> (RunningServer, Client) {
    let (server, client) = common::server_with(config).await;
    let client = client
        .max_encoding_message_size(64 << 20)
        .max_decoding_message_size(64 << 20);
    (server, client)
}

/// `sphere` with the exact model on n x n, in steady rolling with mu = 0.3
/// when `creepage` is given.
fn exact(n: u32, creepage: Option<f64>) -> pb::PatchCase {
    pb::PatchCase {
        friction: creepage.map(|_| pb::FrictionSection {
            coefficient: Some(0.3),
            ..Default::default()
        }),
        kinematics: creepage.map(|c| {
            pb::patch_case::Kinematics::Rolling(pb::Creepages {
                creepage_long: c,
                ..Default::default()
            })
        }),
        ..sphere(pb::Model::Exact, n)
    }
}

fn request(case: pb::PatchCase) -> pb::SolvePatchRequest {
    pb::SolvePatchRequest {
        case: Some(case),
        ..Default::default()
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_oversize_request_is_resource_exhausted_and_the_server_goes_on() {
    let (server, mut client) = server_with(ServeConfig {
        max_message_bytes: 4096,
        ..Default::default()
    })
    .await;
    let items: Vec<_> = (0..200).map(|_| request(exact(8, None))).collect();
    let r = client
        .solve_patch_batch(pb::SolvePatchBatchRequest { items })
        .await;
    let s = r.expect_err("an oversize request is refused");
    assert_eq!(s.code(), Code::ResourceExhausted, "{s:?}");
    assert!(s.message().contains("max_message_bytes"), "{}", s.message());
    // The connection and the server serve the next request.
    let ok = client.solve_patch(request(exact(8, None))).await;
    assert!(ok.is_ok(), "{ok:?}");
    server.shutdown().await;
}

/// An answer larger than `max_message_bytes` (fields of a 64 x 64 grid,
/// about 200 kB, against 64 kB): RESOURCE_EXHAUSTED saying its size and
/// naming `include_fields`, not tonic's OUT_OF_RANGE, for a batch as soon
/// as the results built are too large; without the fields the same case
/// is answered.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_oversize_answer_is_resource_exhausted_naming_include_fields() {
    let (server, mut client) = server_with(ServeConfig {
        max_message_bytes: 64 * 1024,
        workers: 2,
        ..Default::default()
    })
    .await;
    let with_fields = pb::SolvePatchRequest {
        include_fields: true,
        ..request(exact(64, None))
    };
    let s = client
        .solve_patch(with_fields.clone())
        .await
        .expect_err("an oversize answer is refused");
    assert_eq!(s.code(), Code::ResourceExhausted, "{s:?}");
    let m = s.message();
    assert!(
        m.contains("max_message_bytes (65536)") && m.contains("`include_fields`"),
        "{m}"
    );
    // A batch is refused once the results built exceed the limit: the
    // items not started by then are not solved (at most one item per
    // worker is in flight when the first result arrives).
    let s = client
        .solve_patch_batch(pb::SolvePatchBatchRequest {
            items: vec![with_fields; 64],
        })
        .await
        .expect_err("an oversize batch answer is refused");
    assert_eq!(s.code(), Code::ResourceExhausted, "{s:?}");
    let m = s.message();
    assert!(m.contains("split the batch"), "{m}");
    let solved: usize = m
        .split("the results of ")
        .nth(1)
        .and_then(|t| t.split(" of the batch's 64 items").next())
        .and_then(|k| k.parse().ok())
        .unwrap_or_else(|| panic!("no count of solved items: {m}"));
    assert!((1..=4).contains(&solved), "{solved} solved: {m}");
    let ok = client.solve_patch(request(exact(64, None))).await;
    assert!(ok.is_ok(), "{ok:?}");
    server.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_solve_past_the_servers_time_limit_is_stopped_with_resource_exhausted() {
    let (server, mut client) = server_with(ServeConfig {
        max_solve_time_s: 0.05,
        workers: 1,
        ..Default::default()
    })
    .await;
    // Steady rolling on 256 x 256: about half a second on the development
    // machine, ten times the limit.
    let s = client
        .solve_patch(request(exact(256, Some(2e-4))))
        .await
        .expect_err("stopped at the limit");
    assert_eq!(s.code(), Code::ResourceExhausted, "{s:?}");
    assert!(s.message().contains("max_solve_time_s"), "{}", s.message());
    // The only worker is free again: a small solve succeeds.
    let ok = client.solve_patch(request(exact(8, None))).await;
    assert!(ok.is_ok(), "{ok:?}");
    server.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_small_solve_does_not_wait_for_a_large_batch() {
    let (server, client) = server_with(ServeConfig::default()).await;
    let items: Vec<_> = (0..256)
        .map(|i| request(exact(48, Some(1e-4 + 1e-7 * i as f64))))
        .collect();
    let mut batch_client = client.clone();
    let t0 = Instant::now();
    let batch = tokio::spawn(async move {
        let r = batch_client
            .solve_patch_batch(pb::SolvePatchBatchRequest { items })
            .await;
        (r, t0.elapsed())
    });
    // Let the batch occupy the workers, then ask for one small solve.
    tokio::time::sleep(Duration::from_millis(100)).await;
    let mut small_client = client.clone();
    let t1 = Instant::now();
    let small = small_client.solve_patch(request(exact(16, None))).await;
    let waited = t1.elapsed();
    assert!(small.is_ok(), "{small:?}");
    let (batch, batch_took) = batch.await.unwrap();
    let batch = batch.expect("the batch solves").into_inner();
    assert_eq!(batch.items.len(), 256);
    assert!(
        batch
            .items
            .iter()
            .all(|i| matches!(i.outcome, Some(pb::batch_item_result::Outcome::Result(_)))),
        "every item solves"
    );
    eprintln!(
        "a 16x16 solve behind a 256-item 48x48 batch ({:.0} ms): {:.1} ms",
        batch_took.as_secs_f64() * 1e3,
        waited.as_secs_f64() * 1e3
    );
    // It did not wait for the rest of the batch.
    assert!(
        waited < batch_took.saturating_sub(Duration::from_millis(100)) / 2,
        "waited {waited:?} of the batch's {batch_took:?}"
    );
    server.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_silent_session_stream_is_ended_and_an_oversize_open_is_resource_exhausted() {
    let (server, mut client) = server_with(ServeConfig {
        stream_first_message_timeout_s: 0.2,
        max_message_bytes: 4096,
        ..Default::default()
    })
    .await;
    // A stream that sends nothing: DEADLINE_EXCEEDED naming the setting.
    let (tx, rx) = tokio::sync::mpsc::channel::<pb::SessionRequest>(1);
    let t0 = Instant::now();
    let mut stream = client
        .patch_session(tokio_stream::wrappers::ReceiverStream::new(rx))
        .await
        .expect("the stream starts")
        .into_inner();
    let s = stream
        .next()
        .await
        .expect("an answer")
        .expect_err("the silent stream is ended");
    assert_eq!(s.code(), Code::DeadlineExceeded, "{s:?}");
    assert!(
        s.message().contains("stream_first_message_timeout_s"),
        "{}",
        s.message()
    );
    assert!(t0.elapsed() < Duration::from_secs(10), "{:?}", t0.elapsed());
    drop(tx);
    // An `open` larger than max_message_bytes: RESOURCE_EXHAUSTED.
    let open = pb::SessionRequest {
        kind: Some(pb::session_request::Kind::Open(pb::SessionOpen {
            case: Some(exact(8, None)),
            client_label: "x".repeat(8000),
            ..Default::default()
        })),
    };
    let mut stream = client
        .patch_session(tokio_stream::iter(vec![open]))
        .await
        .expect("the stream starts")
        .into_inner();
    let s = stream
        .next()
        .await
        .expect("an answer")
        .expect_err("the oversize open is refused");
    assert_eq!(s.code(), Code::ResourceExhausted, "{s:?}");
    assert!(s.message().contains("max_message_bytes"), "{}", s.message());
    server.shutdown().await;
}
