//! Loopback round trips of the gRPC service: the real server in-process on
//! 127.0.0.1, the generated tonic client, one call or one session step per
//! iteration (encode, HTTP/2, decode, solve on the pool, and back). Run
//! with `cargo bench --bench service`.
//!
//! | bench | what it measures |
//! |---|---|
//! | `service/solve_patch/fastsim` | SolvePatch, model fastsim (Hertz ellipse + FASTSIM 40 x 40), steel circle 10 kN, xi = 1e-3, eta = 5e-4, phi = 0.1 /m |
//! | `service/session_step/fastsim` | one PatchSession step of the same case, creepages along a smooth path (up to 1.9 % a step) |
//! | `service/solve_patch/exact_40x40` | SolvePatch, exact model, 40 x 40 grid, steady rolling xi = 1e-3, cold solver (kernels cached) |
//! | `service/session_step/exact_40x40` | one PatchSession step of the same case, warm-started, creepages along the same path |
//!
//! | `service/solve_wheel_rail/hertz_fastsim` | SolveWheelRail on the built-in pair `mbench_s1002_uic60`: Manchester at 6.5 mm (roll and pitch rate given), both wheels, Hertz+FASTSIM per patch |
//! | `service/solve_wheel_rail/exact` | the same with the exact model at 0.2 mm elements |
//! | `service/register_pair/builtin_new` | RegisterProfilePair round trip of the built-in pair's spec made new each time (smoothing wavelength changed by 1e-12 m): read, smooth, place, build the contact table, all progress messages |
//! | `service/prepare_pair/builtin` | the preparation alone, in process: canonical form and id, profiles read, smoothed and placed |
//!
//! Targets (issue 5): Hertz+FASTSIM step under 150 µs, planar exact 40 x 40
//! step under 5 ms, registration of the built-in pair under 2 s.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use tokio::sync::mpsc;
use tokio_stream::wrappers::ReceiverStream;
use tokio_stream::StreamExt;

use railcontact::service::config::ServeConfig;
use railcontact::service::pairs;
use railcontact::service::pb;
use railcontact::service::pb::contact_service_client::ContactServiceClient;
use railcontact::service::server::start;
use railcontact::service::wheelrail::query_of;
use railcontact::wheelrail::builtin::mbench_a22_input;
use railcontact::wheelrail::WheelRailModel;

fn case(model: pb::Model, n: Option<u32>) -> pb::PatchCase {
    pb::PatchCase {
        model: model as i32,
        material: Some(pb::MaterialSection {
            shear_modulus_pa: Some(81.0e9),
            poisson_ratio: Some(0.30),
            ..Default::default()
        }),
        friction: Some(pb::FrictionSection {
            coefficient: Some(0.3),
            ..Default::default()
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
        kinematics: Some(pb::patch_case::Kinematics::Rolling(creepages(0))),
        grid: n.map(|n| pb::GridSection {
            nx: Some(n),
            ny: Some(n),
            ..Default::default()
        }),
        ..Default::default()
    }
}

/// Creepages of step `k`: a smooth path, 1 + 0.3 sin(2 pi k / 100) times
/// the base values (up to 1.9 % a step), as consecutive time steps.
fn creepages(k: u64) -> pb::Creepages {
    let f = 1.0 + 0.3 * (2.0 * std::f64::consts::PI * k as f64 / 100.0).sin();
    pb::Creepages {
        creepage_long: 1e-3 * f,
        creepage_lat: 5e-4 * f,
        spin_per_m: 0.1 * f,
        ..Default::default()
    }
}

fn round_trips(c: &mut Criterion) {
    let rt = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
        .unwrap();
    let server = rt
        .block_on(start(&ServeConfig {
            listen: "127.0.0.1:0".parse().unwrap(),
            data_dir: Default::default(),
            // register_pair/builtin_new registers a new pair each iteration.
            max_profile_pairs: usize::MAX,
            ..ServeConfig::default()
        }))
        .unwrap();
    let mut client = rt
        .block_on(ContactServiceClient::connect(format!(
            "http://{}",
            server.addr
        )))
        .unwrap();
    let mut group = c.benchmark_group("service");
    for (name, model, n) in [
        ("fastsim", pb::Model::Fastsim, None),
        ("exact_40x40", pb::Model::Exact, Some(40)),
    ] {
        let request = pb::SolvePatchRequest {
            case: Some(case(model, n)),
            ..Default::default()
        };
        group.bench_function(format!("solve_patch/{name}"), |b| {
            b.iter(|| {
                let r = rt.block_on(client.solve_patch(request.clone())).unwrap();
                black_box(r);
            })
        });
        // A session, one step per iteration.
        let (tx, rx) = mpsc::channel(4);
        let open = pb::SessionRequest {
            kind: Some(pb::session_request::Kind::Open(pb::SessionOpen {
                case: Some(case(model, n)),
                client_label: "bench".into(),
                ..Default::default()
            })),
        };
        rt.block_on(tx.send(open)).unwrap();
        let mut responses = rt
            .block_on(client.patch_session(ReceiverStream::new(rx)))
            .unwrap()
            .into_inner();
        rt.block_on(responses.next()).unwrap().unwrap();
        let mut k = 0u64;
        group.bench_function(format!("session_step/{name}"), |b| {
            b.iter(|| {
                let step = pb::SessionRequest {
                    kind: Some(pb::session_request::Kind::Step(pb::SessionStep {
                        step_index: k,
                        time_s: k as f64 * 1e-3,
                        creepages: Some(creepages(k)),
                        ..Default::default()
                    })),
                };
                k += 1;
                rt.block_on(async {
                    tx.send(step).await.unwrap();
                    let r = responses.next().await.unwrap().unwrap();
                    assert!(
                        matches!(r.kind, Some(pb::session_response::Kind::Step(_))),
                        "{r:?}"
                    );
                    black_box(r);
                })
            })
        });
    }
    wheel_rail(&rt, &mut client, &mut group);
    group.finish();
    rt.block_on(server.shutdown());
}

type Group<'a> = criterion::BenchmarkGroup<'a, criterion::measurement::WallTime>;

/// Wheel/rail round trips and the registration of a pair.
fn wheel_rail(
    rt: &tokio::runtime::Runtime,
    client: &mut ContactServiceClient<tonic::transport::Channel>,
    group: &mut Group<'_>,
) {
    group.sample_size(30);
    for (name, model) in [
        ("hertz_fastsim", WheelRailModel::HertzFastsim),
        ("exact", WheelRailModel::Exact),
    ] {
        let input = mbench_a22_input(6.5, Some(-0.004376), Some(-4.2748834), model);
        let request = query_of(pairs::BUILTIN_PAIR, &input);
        group.bench_function(format!("solve_wheel_rail/{name}"), |b| {
            b.iter(|| {
                let r = rt
                    .block_on(client.solve_wheel_rail(request.clone()))
                    .unwrap();
                black_box(r);
            })
        });
    }
    let mut k = 0u64;
    group.bench_function("register_pair/builtin_new", |b| {
        b.iter(|| {
            k += 1;
            let mut spec = pairs::canonicalize(&pairs::builtin_registration())
                .unwrap()
                .canonical;
            spec.smoothing_wavelength_m = Some(2e-3 + k as f64 * 1e-12);
            let req = pb::RegisterProfilePairRequest {
                pair: Some(pb::register_profile_pair_request::Pair::Spec(spec)),
                label: String::new(),
            };
            rt.block_on(async {
                let mut s = client
                    .register_profile_pair(req)
                    .await
                    .unwrap()
                    .into_inner();
                let mut last = None;
                while let Some(m) = s.message().await.unwrap() {
                    last = Some(m);
                }
                let last = last.unwrap();
                assert!(!last.already_registered);
                black_box(last);
            })
        })
    });
    group.bench_function("prepare_pair/builtin", |b| {
        b.iter(|| {
            let spec = pairs::canonicalize(&pairs::builtin_registration()).unwrap();
            black_box(pairs::prepare(&spec, &|_, _| {}).unwrap());
        })
    });
}

criterion_group!(benches, round_trips);
criterion_main!(benches);
