//! Helpers shared by the service's end-to-end tests (each test binary uses
//! some of them).
#![allow(dead_code)]

use railcontact::service::config::ServeConfig;
use railcontact::service::pb;
use railcontact::service::pb::contact_service_client::ContactServiceClient;
use railcontact::service::server::{start, RunningServer};
use tonic::transport::Channel;

pub type Client = ContactServiceClient<Channel>;

/// A profile file of the repository's test data
/// (`crates/solver/profiles`, with its licence and source).
pub fn profile_path(name: &str) -> String {
    profiles_dir().join(name).display().to_string()
}

/// The repository's profile test data: `crates/solver/profiles`.
pub fn profiles_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("crates/solver/profiles")
}

/// The rail slices of `crates/solver/profiles/uk_crossing_nose.slcs` (ten
/// slices of a crossing nose) with the profile files it names, as the wire
/// takes a rail varying along the track.
pub fn crossing_slices() -> pb::ProfileSource {
    let dir = profiles_dir();
    let content = std::fs::read_to_string(dir.join("uk_crossing_nose.slcs")).unwrap();
    let profiles = (66..=75)
        .map(|k| {
            let name = format!("uk_crossing/Crossing_{k}.txt");
            pb::ProfileFile {
                format: pb::ProfileFormat::Unspecified as i32,
                content: std::fs::read_to_string(dir.join(&name)).unwrap(),
                file_name: name,
                ..Default::default()
            }
        })
        .collect();
    pb::ProfileSource {
        source: Some(pb::profile_source::Source::Slices(pb::RailSlices {
            file_name: "uk_crossing_nose.slcs".into(),
            content,
            profiles,
        })),
        mirror_y: false,
    }
}

/// The server of `config` on an ephemeral loopback port (10 s shutdown
/// grace) and a client of it.
pub async fn serve(config: ServeConfig) -> (RunningServer, Client) {
    let server = start(&ServeConfig {
        listen: "127.0.0.1:0".parse().unwrap(),
        shutdown_grace_s: 10.0,
        ..config
    })
    .await
    .expect("server starts");
    let client = ContactServiceClient::connect(format!("http://{}", server.addr))
        .await
        .expect("client connects");
    (server, client)
}

/// [`serve`] with `config` and no store (pairs in memory only).
pub async fn server_with(config: ServeConfig) -> (RunningServer, Client) {
    serve(ServeConfig {
        data_dir: Default::default(),
        ..config
    })
    .await
}

/// Reads the metrics page.
pub async fn metrics_page(addr: std::net::SocketAddr) -> String {
    use tokio::io::{AsyncReadExt, AsyncWriteExt};
    let mut s = tokio::net::TcpStream::connect(addr).await.unwrap();
    s.write_all(b"GET /metrics HTTP/1.1\r\nhost: x\r\nconnection: close\r\n\r\n")
        .await
        .unwrap();
    let mut page = String::new();
    s.read_to_string(&mut page).await.unwrap();
    page
}

/// `sphere` in steady rolling with mu = 0.3.
pub fn rolling(model: pb::Model, n: u32, creepage_long: f64) -> pb::PatchCase {
    pb::PatchCase {
        friction: Some(pb::FrictionSection {
            coefficient: Some(0.3),
            ..Default::default()
        }),
        kinematics: Some(pb::patch_case::Kinematics::Rolling(pb::Creepages {
            creepage_long,
            ..Default::default()
        })),
        ..sphere(model, n)
    }
}

/// A creep curve's sweep from zero creepage to `creepage_long` [-] in
/// `points` points.
pub fn linear_sweep(creepage_long: f64, points: u32) -> Option<pb::creep_curve_request::Sweep> {
    Some(pb::creep_curve_request::Sweep::Linear(pb::LinearSweep {
        from: Some(pb::Creepages::default()),
        to: Some(pb::Creepages {
            creepage_long,
            ..Default::default()
        }),
        points,
    }))
}

pub fn steel() -> pb::MaterialSection {
    pb::MaterialSection {
        shear_modulus_pa: Some(81.0e9),
        poisson_ratio: Some(0.30),
        ..Default::default()
    }
}

/// h = x² + y² (R = 0.5 m), 10 kN, steel on steel.
pub fn sphere(model: pb::Model, n: u32) -> pb::PatchCase {
    pb::PatchCase {
        model: model as i32,
        material: Some(steel()),
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
