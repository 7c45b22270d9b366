//! The profile-pair registry against a hostile client and a damaged disk:
//! damaged and edited records of the store (FAILED with the reason, never
//! served, the others served; or the start refused), 0-byte, foreign and
//! locked store files (the start refused naming the file), absurd
//! registrations (INVALID_ARGUMENT naming the field, never a panic), pairs
//! whose profiles do not touch, and the registry's limits. The real server
//! runs in-process on an ephemeral loopback port with its store in a
//! temporary directory (one test runs the binary); profiles come from
//! `crates/solver/profiles`.

use crate::common;
use crate::support;

use std::path::Path;

use prost::Message;

use railcontact::service::config::{ServeConfig, StoreDamaged};
use railcontact::service::pairs;
use railcontact::service::pb;
use railcontact::service::pb::contact_service_client::ContactServiceClient;
use railcontact::service::server::{start, RunningServer};
use railcontact::service::wheelrail::query_of;
use railcontact::wheelrail::builtin::mbench_a22_input;
use railcontact::wheelrail::{parse_profile, LoadOptions, WheelRailModel};
use tonic::transport::Channel;
use tonic::Code;

type Client = ContactServiceClient<Channel>;

fn profile_path(name: &str) -> String {
    common::profile_path(name)
}

fn config(dir: &Path) -> ServeConfig {
    ServeConfig {
        listen: "127.0.0.1:0".parse().unwrap(),
        metrics_listen: Some("127.0.0.1:0".parse().unwrap()),
        shutdown_grace_s: 10.0,
        data_dir: dir.to_path_buf(),
        ..ServeConfig::default()
    }
}

async fn server_with(config: &ServeConfig) -> (RunningServer, Client) {
    let server = start(config).await.expect("server starts");
    let client = ContactServiceClient::connect(format!("http://{}", server.addr))
        .await
        .expect("client connects");
    (server, client)
}

/// A profile file's content with `extra` appended.
fn file_source(name: &str, mirror_y: bool, extra: &str) -> pb::ProfileSource {
    let content = std::fs::read_to_string(profile_path(name)).unwrap() + extra;
    pb::ProfileSource {
        source: Some(pb::profile_source::Source::File(pb::ProfileFile {
            format: pb::ProfileFormat::Unspecified as i32,
            content,
            file_name: name.into(),
            ..Default::default()
        })),
        mirror_y,
    }
}

/// Measured worn profiles (MiniProf wheel, MiniProf rail measured from the
/// gauge side), rails inclined 1:40; `marker` is appended to the wheel file
/// as a comment line, which makes another pair of the same geometry.
fn worn_spec(marker: &str) -> pb::ProfilePairSpec {
    pb::ProfilePairSpec {
        wheel: Some(file_source(
            "Car7216_0001r.whl",
            false,
            &format!("\n# {marker}\n"),
        )),
        rail: Some(file_source("avg_HR.BAN", true, "")),
        ..standard_track(0.025)
    }
}

/// Standard gauge with rails inclined by `cant_rad`, a wheelset of flange
/// backs 1.360 m apart and radius 0.46 m; no profiles.
fn standard_track(cant_rad: f64) -> pb::ProfilePairSpec {
    pb::ProfilePairSpec {
        track: Some(pb::TrackSpec {
            gauge_m: 1.435,
            gauge_height_m: 0.014,
            cant_rad,
            ..Default::default()
        }),
        wheelset: Some(pb::WheelsetSpec {
            flange_back_distance_m: 1.360,
            nominal_radius_m: 0.46,
            flange_back_y_m: None,
        }),
        ..Default::default()
    }
}

/// The Manchester benchmark's profiles, given as files.
fn mbench_spec(friction: f64) -> pb::ProfilePairSpec {
    pb::ProfilePairSpec {
        wheel: Some(file_source("MBench_S1002_v3.prw", false, "")),
        rail: Some(file_source("MBench_UIC60_v3.prr", false, "")),
        friction: Some(pb::FrictionSection {
            coefficient: Some(friction),
            ..Default::default()
        }),
        ..standard_track(0.0)
    }
}

fn request(spec: pb::ProfilePairSpec) -> pb::RegisterProfilePairRequest {
    pb::RegisterProfilePairRequest {
        pair: Some(pb::register_profile_pair_request::Pair::Spec(spec)),
        label: String::new(),
    }
}

/// The last progress message of a registration, or the status that ended
/// it (at the call or in the stream).
async fn register(
    client: &mut Client,
    spec: pb::ProfilePairSpec,
) -> Result<pb::RegistrationProgress, tonic::Status> {
    let mut stream = client
        .register_profile_pair(request(spec))
        .await?
        .into_inner();
    let mut last = None;
    while let Some(m) = stream.message().await? {
        last = Some(m);
    }
    let last = last.expect("progress");
    assert_eq!(last.stage, pb::RegistrationStage::Ready as i32, "{last:?}");
    Ok(last)
}

async fn solve(client: &mut Client, id: &str) -> Result<pb::WheelRailResult, tonic::Status> {
    let q = query_of(
        id,
        &mbench_a22_input(0.0, None, None, WheelRailModel::HertzFastsim),
    );
    Ok(client
        .solve_wheel_rail(q)
        .await?
        .into_inner()
        .result
        .unwrap())
}

/// A figure of the metrics page (the first line starting with `name`).
async fn metric(server: &RunningServer, name: &str) -> f64 {
    let page = common::metrics_page(server.metrics_addr.unwrap()).await;
    page.lines()
        .find_map(|l| l.strip_prefix(name))
        .and_then(|v| v.trim().parse().ok())
        .unwrap_or_else(|| panic!("{name} not on the metrics page:\n{page}"))
}

/// Applies `edit` to every place of the file where `marker` occurs (the
/// record, and any stale copy in pages redb has not reused yet); how many.
fn edit_file(path: &Path, marker: &[u8], edit: impl Fn(&mut [u8], usize)) -> usize {
    let mut bytes = std::fs::read(path).unwrap();
    let at: Vec<usize> = bytes
        .windows(marker.len())
        .enumerate()
        .filter(|(_, w)| *w == marker)
        .map(|(i, _)| i)
        .collect();
    for &i in &at {
        edit(&mut bytes, i);
    }
    std::fs::write(path, bytes).unwrap();
    at.len()
}

fn assert_invalid(e: &tonic::Status, needles: &[&str]) {
    assert_eq!(e.code(), Code::InvalidArgument, "{e:?}");
    for n in needles {
        assert!(e.message().contains(n), "{n:?} not in {:?}", e.message());
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn damaged_and_edited_records_are_failed_pairs_never_served_and_the_others_are() {
    let dir = tempfile::tempdir().unwrap();
    let ids = {
        let (server, mut client) = server_with(&config(dir.path())).await;
        let mut ids = Vec::new();
        for k in 1..=3 {
            let spec = worn_spec(&format!("pair-{k}-of-the-damage-test"));
            ids.push(register(&mut client, spec).await.unwrap().pair_id);
        }
        server.shutdown().await;
        ids
    };
    let file = dir.path().join("pairs.redb");
    // Pair 2: 64 bytes flipped from its marker on.
    let n = edit_file(&file, b"pair-2-of-the-damage-test", |b, i| {
        for x in &mut b[i..i + 64] {
            *x ^= 0xa5;
        }
    });
    assert!(n >= 1);
    // Pair 3: a digit of its wheel profile edited (the last data line
    // before its marker).
    let n = edit_file(&file, b"pair-3-of-the-damage-test", |b, i| {
        let d = (0..i).rev().find(|&j| b[j].is_ascii_digit()).unwrap();
        b[d] = if b[d] == b'9' { b'1' } else { b[d] + 1 };
    });
    assert!(n >= 1);

    // store_damaged = "fail": no start, the records named.
    let mut strict = config(dir.path());
    strict.store_damaged = StoreDamaged::Fail;
    let e = start(&strict).await.err().expect("start refused");
    let m = e.to_string();
    assert!(
        m.contains(&ids[1]) && m.contains(&ids[2]) && !m.contains(&ids[0]),
        "{m}"
    );
    assert!(
        m.contains("2 damaged records") && m.contains("pairs.redb"),
        "{m}"
    );

    // The default: start, the damaged pairs FAILED with the reason.
    let (server, mut client) = server_with(&config(dir.path())).await;
    let listed = support::list_pairs(&mut client).await;
    let info = |id: &str| listed.iter().find(|p| p.pair_id == id).unwrap().clone();
    assert_eq!(info(&ids[0]).state, pb::ProfilePairState::Stored as i32);
    for (id, why) in [(&ids[1], "damaged"), (&ids[2], "no longer matches its id")] {
        let p = info(id);
        assert_eq!(p.state, pb::ProfilePairState::Failed as i32, "{p:?}");
        assert!(p.error.contains(why), "{}", p.error);
        // Never served: not the altered geometry under the old id.
        let e = solve(&mut client, id).await.unwrap_err();
        assert_eq!(e.code(), Code::FailedPrecondition, "{e:?}");
        assert!(e.message().contains("damaged"), "{e:?}");
    }
    assert!(p_wheel_is_empty(&info(&ids[2])));
    assert_eq!(
        metric(&server, "railcontact_store_damaged_records ").await,
        2.0
    );
    let good = solve(&mut client, &ids[0]).await.unwrap();
    assert_eq!(good.wheels.len(), 2);
    // Registering pair 3 again repairs it; deleting pair 2 removes it.
    let again = register(&mut client, worn_spec("pair-3-of-the-damage-test"))
        .await
        .unwrap();
    assert_eq!(again.pair_id, ids[2]);
    assert!(!again.already_registered);
    solve(&mut client, &ids[2]).await.unwrap();
    client
        .delete_profile_pair(pb::DeleteProfilePairRequest {
            pair_id: ids[1].clone(),
        })
        .await
        .unwrap();
    assert_eq!(
        metric(&server, "railcontact_store_damaged_records ").await,
        0.0
    );
    server.shutdown().await;

    // Nothing damaged is left: the strict start works.
    let (server, mut client) = server_with(&strict).await;
    let listed = support::list_pairs(&mut client).await;
    assert_eq!(listed.len(), 3, "built-in, pairs 1 and 3: {listed:?}");
    assert!(listed
        .iter()
        .all(|p| p.state != pb::ProfilePairState::Failed as i32));
    server.shutdown().await;
}

/// A FAILED record shows no profile of its (untrusted) content.
fn p_wheel_is_empty(p: &pb::ProfilePairInfo) -> bool {
    p.wheel.is_none() && p.track.is_none()
}

#[tokio::test]
async fn empty_foreign_and_shared_store_files_refuse_the_start_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("pairs.redb");
    std::fs::write(&file, b"").unwrap();
    let e = start(&config(dir.path())).await.err().expect("refused");
    let m = e.to_string();
    assert!(
        m.contains(&file.display().to_string()) && m.contains("empty (0 bytes)"),
        "{m}"
    );
    assert_eq!(std::fs::metadata(&file).unwrap().len(), 0, "left as it was");
    std::fs::write(&file, "a text file, not a database\n".repeat(300)).unwrap();
    let m = start(&config(dir.path()))
        .await
        .err()
        .expect("refused")
        .to_string();
    assert!(m.contains("not a railcontact profile pair store"), "{m}");
    // Two servers on one data directory: the second is told why.
    std::fs::remove_file(&file).unwrap();
    let (first, _client) = server_with(&config(dir.path())).await;
    let m = start(&config(dir.path()))
        .await
        .err()
        .expect("second server refused")
        .to_string();
    assert!(
        m.contains(&file.display().to_string())
            && m.contains("another railcontact server")
            && m.contains("--data-dir"),
        "{m}"
    );
    first.shutdown().await;

    // The binary: exits with the message, never listens.
    std::fs::write(&file, b"").unwrap();
    let out = std::process::Command::new(support::BIN)
        .args(["serve", "--listen", "127.0.0.1:0", "--data-dir"])
        .arg(dir.path())
        .env("RUST_LOG", "warn")
        .stdin(std::process::Stdio::null())
        .output()
        .unwrap();
    assert!(!out.status.success());
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stdout.contains("listening"), "{stdout}");
    assert!(
        stderr.contains("pairs.redb") && stderr.contains("empty (0 bytes)"),
        "{stderr}"
    );
}

/// A port in use is said at once, naming the address and the setting to
/// change, before the store is opened (no store file is created); a
/// misspelt `RAILCONTACT_*` variable is named with the setting it most
/// likely meant.
#[test]
fn a_busy_port_and_a_misspelt_variable_are_named() {
    let busy = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let addr = busy.local_addr().unwrap();
    let dir = tempfile::tempdir().unwrap();
    let out = std::process::Command::new(support::BIN)
        .args(["serve", "--listen", &addr.to_string(), "--data-dir"])
        .arg(dir.path())
        .env("RAILCONTACT_WORKRES", "2")
        .env("RUST_LOG", "warn")
        .stdin(std::process::Stdio::null())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains(&format!("cannot listen on {addr}"))
            && stderr.contains("another process listens there")
            && stderr.contains("--listen / RAILCONTACT_LISTEN"),
        "{stderr}"
    );
    assert!(
        stderr.contains("RAILCONTACT_WORKRES is not a setting (did you mean RAILCONTACT_WORKERS?)"),
        "{stderr}"
    );
    assert!(
        !dir.path()
            .join(railcontact::service::store::FILE_NAME)
            .exists(),
        "the store was opened before the port was checked"
    );
}

/// `log_format = "json"`: every log line on stderr is one JSON object with
/// the level and the event's fields (the start-up line's too).
#[test]
fn logs_can_be_json_lines() {
    let server = support::Server::start_with(
        &[],
        &[("RAILCONTACT_LOG_FORMAT", "json"), ("RUST_LOG", "info")],
    );
    let log = server.log();
    let lines: Vec<&str> = log.lines().filter(|l| !l.trim().is_empty()).collect();
    assert!(!lines.is_empty());
    for line in &lines {
        let v: serde_json::Value =
            serde_json::from_str(line).unwrap_or_else(|e| panic!("not JSON ({e}): {line}"));
        assert!(v["level"].is_string() && v["fields"].is_object(), "{line}");
    }
    let serving = lines
        .iter()
        .map(|l| serde_json::from_str::<serde_json::Value>(l).unwrap())
        .find(|v| v["fields"]["message"] == "railcontact serving")
        .unwrap_or_else(|| panic!("no start-up line: {log}"));
    assert_eq!(serving["fields"]["metrics"], "off", "{serving}");
}

/// A MiniProf wheel (key=value variant) with its header keys `keys` and one
/// data line replaced by `line`.
fn miniprof_wheel(keys: &str, line: &str) -> pb::ProfileSource {
    let text = std::fs::read_to_string(profile_path("Car7216_0001r.whl")).unwrap();
    let (header, data) = text.split_once("\n\n").expect("header and data");
    let mut lines: Vec<&str> = data.lines().collect();
    let k = lines.len() / 2;
    if !line.is_empty() {
        lines[k] = line;
    }
    let content = format!("{header}\n{keys}\n\n{}\n", lines.join("\n"));
    pb::ProfileSource {
        source: Some(pb::profile_source::Source::File(pb::ProfileFile {
            format: pb::ProfileFormat::Unspecified as i32,
            content,
            file_name: "w.whl".into(),
            ..Default::default()
        })),
        mirror_y: false,
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn absurd_registrations_are_invalid_argument_naming_the_field() {
    let dir = tempfile::tempdir().unwrap();
    let (server, mut client) = server_with(&config(dir.path())).await;
    let mut cases: Vec<(pb::ProfilePairSpec, Vec<&str>)> = Vec::new();
    let with = |f: &dyn Fn(&mut pb::ProfilePairSpec)| {
        let mut s = mbench_spec(0.3);
        f(&mut s);
        s
    };
    cases.push((
        with(&|s| s.track.as_mut().unwrap().gauge_m = 100.0),
        vec!["spec.track.gauge_m", "got 100"],
    ));
    cases.push((
        with(&|s| s.wheelset.as_mut().unwrap().flange_back_distance_m = 1e300),
        vec!["spec.wheelset.flange_back_distance_m", "1e300"],
    ));
    cases.push((
        with(&|s| s.wheelset.as_mut().unwrap().nominal_radius_m = 40.0),
        vec!["spec.wheelset.nominal_radius_m"],
    ));
    // In millimetres: the same check as the command line's, with the hint.
    cases.push((
        with(&|s| s.wheelset.as_mut().unwrap().nominal_radius_m = 460.0),
        vec!["spec.wheelset.nominal_radius_m", "did you mean 0.46 m"],
    ));
    cases.push((
        with(&|s| {
            s.material = Some(pb::MaterialSection {
                shear_modulus_pa: Some(5e-324),
                poisson_ratio: Some(0.28),
                ..Default::default()
            })
        }),
        vec!["spec.material.shear_modulus_pa", "5e-324"],
    ));
    cases.push((
        with(&|s| {
            s.material = Some(pb::MaterialSection {
                body1: Some(pb::Material {
                    shear_modulus_pa: 80e9,
                    poisson_ratio: 0.7,
                }),
                body2: Some(pb::Material {
                    shear_modulus_pa: 80e9,
                    poisson_ratio: 0.3,
                }),
                ..Default::default()
            })
        }),
        vec!["spec.material.body1.poisson_ratio"],
    ));
    cases.push((
        with(&|s| s.friction.as_mut().unwrap().coefficient = Some(1e300)),
        vec!["spec.friction.coefficient"],
    ));
    cases.push((
        with(&|s| s.smoothing_wavelength_m = Some(1e300)),
        vec!["spec.smoothing_wavelength_m"],
    ));
    // Profiles: offsets of 1e20 and 1e300 mm, a point 1e15 mm out, a line
    // of 10 kB (quoted short).
    cases.push((
        with(&|s| s.wheel = Some(miniprof_wheel("XOffset=1e20", ""))),
        vec!["spec.wheel", "w.whl line", "XOffset"],
    ));
    cases.push((
        with(&|s| s.wheel = Some(miniprof_wheel("YOffset=1e300", ""))),
        vec!["spec.wheel", "w.whl line", "YOffset"],
    ));
    cases.push((
        with(&|s| s.wheel = Some(miniprof_wheel("", "1e15,0"))),
        vec!["spec.wheel", "w.whl line", "outside"],
    ));
    let long = "1".repeat(10_000) + ",x";
    cases.push((
        with(&|s| s.wheel = Some(miniprof_wheel("", &long))),
        vec!["spec.wheel", "w.whl line", "(10002 characters)"],
    ));
    // A wheel file as the rail: the reader says so, naming the source.
    cases.push((
        with(&|s| s.rail = s.wheel.clone()),
        vec!["spec.rail", "says wheel, but a rail profile was expected"],
    ));
    // Within every range, but the wheels sit beside their rails: the trial
    // solve at the centred position refuses the pair.
    cases.push((
        with(&|s| s.track.as_mut().unwrap().gauge_m = 1.0),
        vec!["spec", "centred position", "gauge 1 m"],
    ));
    for (spec, needles) in cases {
        let e = register(&mut client, spec).await.unwrap_err();
        assert_invalid(&e, &needles);
        assert!(e.message().len() < 1000, "{}", e.message());
    }
    let pairs = support::list_pairs(&mut client).await;
    assert_eq!(pairs.len(), 1, "only the built-in pair: {pairs:?}");
    // The same geometry in its place registers.
    register(&mut client, mbench_spec(0.3)).await.unwrap();
    server.shutdown().await;
}

/// The largest point count of the two profiles of `spec`.
fn points(spec: &pb::ProfilePairSpec) -> usize {
    let count = |src: &pb::ProfileSource| {
        let Some(pb::profile_source::Source::File(f)) = &src.source else {
            unreachable!()
        };
        let options = LoadOptions {
            mirror_y: src.mirror_y,
            ..Default::default()
        };
        parse_profile(&f.content, &f.file_name, &options)
            .unwrap()
            .len()
    };
    count(spec.wheel.as_ref().unwrap()).max(count(spec.rail.as_ref().unwrap()))
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn registry_limits_answer_resource_exhausted_or_invalid_argument() {
    // The pair of fewer points passes the point limit; the other not.
    let (a, b) = (mbench_spec(0.3), worn_spec("limits"));
    let (small, big) = if points(&a) < points(&b) {
        (a, b)
    } else {
        (b, a)
    };
    let size = |s: &pb::ProfilePairSpec| {
        pairs::canonicalize(&request(s.clone()))
            .unwrap()
            .registration()
            .encoded_len() as u64
    };
    let dir = tempfile::tempdir().unwrap();
    let mut c = config(dir.path());
    c.max_profile_points = points(&small);
    c.max_store_bytes = size(&small) + size(&small) / 2;
    let (server, mut client) = server_with(&c).await;
    let e = register(&mut client, big.clone()).await.unwrap_err();
    assert_invalid(
        &e,
        &[
            "max_profile_points",
            &format!("limit of {}", points(&small)),
        ],
    );
    assert!(e.message().contains("spec.wheel") || e.message().contains("spec.rail"));
    register(&mut client, small.clone()).await.unwrap();
    let mut other = small.clone();
    other.friction = Some(pb::FrictionSection {
        coefficient: Some(0.25),
        ..Default::default()
    });
    let e = register(&mut client, other.clone()).await.unwrap_err();
    assert_eq!(e.code(), Code::ResourceExhausted, "{e:?}");
    assert!(e.message().contains("max_store_bytes"), "{e:?}");
    let refused =
        |limit: &str| format!("railcontact_registrations_refused_total{{limit=\"{limit}\"}} ");
    assert_eq!(metric(&server, &refused("max_profile_points")).await, 1.0);
    assert_eq!(metric(&server, &refused("max_store_bytes")).await, 1.0);
    server.shutdown().await;

    // Without a store, the same budget holds for the registrations in
    // memory.
    let mut c = config(dir.path());
    c.data_dir = Default::default();
    c.max_store_bytes = size(&small) + size(&small) / 2;
    let (server, mut client) = server_with(&c).await;
    register(&mut client, small.clone()).await.unwrap();
    let e = register(&mut client, other.clone()).await.unwrap_err();
    assert_eq!(e.code(), Code::ResourceExhausted, "{e:?}");
    assert!(
        e.message().contains("max_store_bytes") && e.message().contains("in memory"),
        "{e:?}"
    );
    server.shutdown().await;

    // At most one pair (the built-in one not counted).
    let dir = tempfile::tempdir().unwrap();
    let mut c = config(dir.path());
    c.max_profile_pairs = 1;
    let (server, mut client) = server_with(&c).await;
    let first = register(&mut client, small.clone()).await.unwrap();
    let e = register(&mut client, other.clone()).await.unwrap_err();
    assert_eq!(e.code(), Code::ResourceExhausted, "{e:?}");
    assert!(e.message().contains("max_profile_pairs"), "{e:?}");
    // Registering the same pair again is no new pair.
    assert!(
        register(&mut client, small)
            .await
            .unwrap()
            .already_registered
    );
    client
        .delete_profile_pair(pb::DeleteProfilePairRequest {
            pair_id: first.pair_id,
        })
        .await
        .unwrap();
    register(&mut client, other).await.unwrap();
    assert_eq!(metric(&server, &refused("max_profile_pairs")).await, 1.0);
    server.shutdown().await;
}

/// Memory of `spec`'s pair prepared, without its contact table \[bytes\].
fn prepared_bytes(spec: &pb::ProfilePairSpec) -> u64 {
    let s = pairs::canonicalize(&request(spec.clone())).unwrap();
    pairs::prepare(&s, &|_, _| {}).unwrap().bytes() as u64
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn prepared_pairs_stay_within_max_prepared_bytes_and_are_prepared_again_on_use() {
    // A limit that holds one benchmark pair: of the built-in pair and two
    // registered ones, only the one used last is held.
    let (a, b) = (mbench_spec(0.25), mbench_spec(0.35));
    let limit = prepared_bytes(&a);
    let big = worn_spec("prepared");
    let big_bytes = prepared_bytes(&big);
    assert!(big_bytes > limit, "{big_bytes} against {limit}");
    let mut c = config(Path::new(""));
    c.data_dir = Default::default();
    c.max_prepared_bytes = limit;
    let (server, mut client) = server_with(&c).await;
    let id_a = register(&mut client, a).await.unwrap().pair_id;
    let untimed = |mut r: pb::WheelRailResult| {
        r.timing = None;
        r
    };
    let first = untimed(solve(&mut client, &id_a).await.unwrap());
    let id_b = register(&mut client, b).await.unwrap().pair_id;
    solve(&mut client, &id_b).await.unwrap();
    assert_eq!(metric(&server, "railcontact_prepared_pairs ").await, 1.0);
    let released = metric(&server, "railcontact_prepared_pairs_released_total ").await;
    assert!(released >= 2.0, "{released}");
    // A, let go, is prepared again and answers the same bits; it is
    // still READY.
    let again = untimed(solve(&mut client, &id_a).await.unwrap());
    assert_eq!(again, first);
    let info = client
        .get_profile_pair(pb::GetProfilePairRequest {
            pair_id: id_b.clone(),
        })
        .await
        .unwrap()
        .into_inner();
    assert_eq!(info.state, pb::ProfilePairState::Ready as i32, "{info:?}");
    assert!(info.prepare_time_s > 0.0, "{info:?}");
    assert_eq!(metric(&server, "railcontact_prepared_pairs ").await, 1.0);
    assert!(metric(&server, "railcontact_prepared_pairs_released_total ").await > released);
    // A pair larger than the limit alone is refused, naming it, and is
    // not registered.
    let e = register(&mut client, big).await.unwrap_err();
    assert_eq!(e.code(), Code::ResourceExhausted, "{e:?}");
    assert!(
        e.message().contains("max_prepared_bytes") && e.message().contains(&big_bytes.to_string()),
        "{e:?}"
    );
    let listed = client
        .list_profile_pairs(pb::ListProfilePairsRequest::default())
        .await
        .unwrap()
        .into_inner()
        .pairs
        .len();
    assert_eq!(listed, 3, "the built-in pair, A and B");
    server.shutdown().await;
    // A limit below the built-in pair: the server does not start, and
    // says so.
    c.max_prepared_bytes = 1000;
    let e = start(&c).await.err().expect("refused").to_string();
    assert!(
        e.contains("the built-in pair") && e.contains("max_prepared_bytes"),
        "{e}"
    );
}
