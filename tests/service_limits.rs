//! The service's resource limits, end to end over gRPC: an oversize
//! request, a solve past the server's time limit, and a batch that must
//! not starve other requests.

use std::time::{Duration, Instant};

use railcontact::service::config::ServeConfig;
use railcontact::service::pb;
use railcontact::service::pb::contact_service_client::ContactServiceClient;
use railcontact::service::server::{start, RunningServer};
use tonic::transport::Channel;
use tonic::Code;

type Client = ContactServiceClient<Channel>;

/// A server on an ephemeral port with `config`; pairs in memory only.
async fn server_with(config: ServeConfig) -> (RunningServer, Client) {
    let server = start(&ServeConfig {
        listen: "127.0.0.1:0".parse().unwrap(),
        shutdown_grace_s: 10.0,
        data_dir: Default::default(),
        ..config
    })
    .await
    .expect("server starts");
    let client = ContactServiceClient::connect(format!("http://{}", server.addr))
        .await
        .expect("client connects")
        .max_encoding_message_size(64 << 20)
        .max_decoding_message_size(64 << 20);
    (server, client)
}

/// h = x² + y² (R = 0.5 m), 10 kN, steel on steel, exact model on n x n,
/// steady rolling when `creepage` is given.
fn sphere(n: u32, creepage: Option<f64>) -> pb::PatchCase {
    pb::PatchCase {
        model: pb::Model::Exact as i32,
        material: Some(pb::MaterialSection {
            shear_modulus_pa: Some(81.0e9),
            poisson_ratio: Some(0.30),
            ..Default::default()
        }),
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
        geometry: Some(pb::GeometrySection {
            kind: pb::GeometryKind::Quadratic as i32,
            a_per_m: Some(1.0),
            b_per_m: Some(1.0),
            ..Default::default()
        }),
        load: Some(pb::LoadSection {
            load: Some(pb::load_section::Load::NormalForceN(1.0e4)),
        }),
        grid: Some(pb::GridSection {
            nx: Some(n),
            ny: Some(n),
            ..Default::default()
        }),
        ..Default::default()
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
    let items: Vec<_> = (0..200).map(|_| request(sphere(8, None))).collect();
    let r = client
        .solve_patch_batch(pb::SolvePatchBatchRequest {
            items,
            ..Default::default()
        })
        .await;
    let s = r.expect_err("an oversize request is refused");
    assert_eq!(s.code(), Code::ResourceExhausted, "{s:?}");
    assert!(s.message().contains("max_message_bytes"), "{}", s.message());
    // The connection and the server serve the next request.
    let ok = client.solve_patch(request(sphere(8, None))).await;
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
        .solve_patch(request(sphere(256, Some(2e-4))))
        .await
        .expect_err("stopped at the limit");
    assert_eq!(s.code(), Code::ResourceExhausted, "{s:?}");
    assert!(s.message().contains("max_solve_time_s"), "{}", s.message());
    // The only worker is free again: a small solve succeeds.
    let ok = client.solve_patch(request(sphere(8, None))).await;
    assert!(ok.is_ok(), "{ok:?}");
    server.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_small_solve_does_not_wait_for_a_large_batch() {
    let (server, client) = server_with(ServeConfig::default()).await;
    let items: Vec<_> = (0..256)
        .map(|i| request(sphere(48, Some(1e-4 + 1e-7 * i as f64))))
        .collect();
    let mut batch_client = client.clone();
    let t0 = Instant::now();
    let batch = tokio::spawn(async move {
        let r = batch_client
            .solve_patch_batch(pb::SolvePatchBatchRequest {
                items,
                ..Default::default()
            })
            .await;
        (r, t0.elapsed())
    });
    // Let the batch occupy the workers, then ask for one small solve.
    tokio::time::sleep(Duration::from_millis(100)).await;
    let mut small_client = client.clone();
    let t1 = Instant::now();
    let small = small_client.solve_patch(request(sphere(16, None))).await;
    let waited = t1.elapsed();
    assert!(small.is_ok(), "{small:?}");
    let (batch, batch_took) = batch.await.unwrap();
    let batch = batch.expect("the batch solves").into_inner();
    assert_eq!(batch.items.len(), 256);
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
