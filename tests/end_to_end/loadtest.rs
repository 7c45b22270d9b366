//! `railcontact loadtest` and `railcontact health` as processes against a
//! real `railcontact serve` on a loopback port.

use crate::support;

use support::{assert_clean, loadtest_json, num, run, Server};

/// The mix of the tests: every kind of the default mix.
const MIX: &str = "wheelrail:hertz_fastsim=2,wheelrail:exact=1,patch:exact40=1,patch:fastsim=1";

#[test]
fn loadtest_json_has_sane_percentiles_no_errors_and_no_mismatches() {
    let server = Server::start();
    let (v, out) = loadtest_json(&[
        "--target",
        &server.addr,
        "--sessions",
        "4",
        "--steps",
        "10",
        "--batch-clients",
        "2",
        "--batch-items",
        "4",
        "--mix",
        MIX,
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_clean(&v);
    // 4 sessions and 2 batch clients, 10 steps each.
    assert_eq!(num(&v, "steps"), 60.0);
    assert_eq!(v["kinds"].as_object().unwrap().len(), 6, "{}", v["kinds"]);
    assert_eq!(num(&v["kinds"]["batch:patch:fastsim"], "steps"), 10.0);
    // The sessions' own server times: a patch step's solve time lies within
    // its round trip, so every percentile of it within the round trip's; a
    // wheel/rail step's is its work summed over threads (two on a debug
    // build's long steps), only positive here. Batch calls report none.
    let fastsim = &v["kinds"]["patch:fastsim"];
    for p in ["p50_s", "p90_s", "p99_s", "max_s", "mean_s"] {
        let server = num(&fastsim["server"], p);
        assert!(server > 0.0 && server <= num(fastsim, p), "{p}: {fastsim}");
    }
    assert!(
        num(&v["kinds"]["wheelrail:exact"]["server"], "p50_s") > 0.0,
        "{v}"
    );
    assert!(
        v["kinds"]["batch:patch:fastsim"].get("server").is_none(),
        "{v}"
    );
    // No progress bar without a terminal: stderr stays empty.
    assert!(
        out.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The conformal wheel/rail models along the load test's path: cect was
/// refused at step 5 ("the wheel profile does not cross the rail normal")
/// when its grid, rounded up, reached past the profile curves handed to the
/// conformal geometry.
#[test]
fn conformal_wheelset_sessions_step_along_the_path() {
    let server = Server::start();
    let (v, out) = loadtest_json(&[
        "--target",
        &server.addr,
        "--sessions",
        "2",
        "--steps",
        "8",
        "--batch-clients",
        "0",
        "--mix",
        "wheelrail:cect=1,wheelrail:auto=1",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_clean(&v);
    assert_eq!(num(&v, "steps"), 16.0, "{v}");
}

#[test]
fn loadtest_table_and_time_limit() {
    let server = Server::start();
    let out = run(&[
        "loadtest",
        "--target",
        &server.addr,
        "--sessions",
        "2",
        "--steps",
        "1000000",
        "--seconds",
        "1",
        "--batch-clients",
        "0",
        "--mix",
        "patch:fastsim",
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stdout}");
    for needle in ["p50 ms", "patch:fastsim", "0 mismatches, 0 errors"] {
        assert!(stdout.contains(needle), "{needle}: {stdout}");
    }
}

/// Ctrl-C during the load: the steps under way finish, the report of
/// what was done is printed (no baseline replay), and the exit code says
/// it was interrupted.
#[test]
fn loadtest_interrupted_reports_what_was_done() {
    use std::process::{Command, Stdio};
    let server = Server::start();
    let child = Command::new(support::BIN)
        .args([
            "loadtest",
            "--target",
            &server.addr,
            "--sessions",
            "2",
            "--steps",
            "1000000",
            "--seconds",
            "60",
            "--batch-clients",
            "0",
            "--mix",
            "patch:fastsim",
        ])
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Interrupt once the load runs (after the health checks and the
    // connections).
    std::thread::sleep(std::time::Duration::from_millis(1500));
    support::signal(child.id(), "INT");
    let start = std::time::Instant::now();
    let out = child.wait_with_output().unwrap();
    assert!(
        start.elapsed() < std::time::Duration::from_secs(20),
        "took {:?} after Ctrl-C",
        start.elapsed()
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stdout}\n{stderr}");
    assert!(
        stdout.contains("p50 ms") && stdout.contains("interrupted by Ctrl-C after"),
        "{stdout}"
    );
    assert!(stderr.contains("interrupted"), "{stderr}");
}

/// A loopback port with nothing listening on it.
fn closed_port() -> String {
    let l = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let addr = l.local_addr().unwrap();
    drop(l);
    addr.to_string()
}

#[test]
fn a_wrong_target_is_a_clear_error_and_a_failure() {
    let addr = closed_port();
    let out = run(&["loadtest", "--target", &addr, "--steps", "5"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains(&format!("cannot connect to {addr}")),
        "{stderr}"
    );
    assert!(out.stdout.is_empty());

    let out = run(&["loadtest", "--target", "localhost", "--steps", "5"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("expected HOST:PORT"), "{stderr}");

    let out = run(&["loadtest", "--target", &addr, "--mix", "patch:warp=1"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("patch:warp"), "{stderr}");
}

#[test]
fn health_exits_zero_only_when_serving() {
    let server = Server::start();
    let out = run(&["health", "--target", &server.addr]);
    assert!(out.status.success());
    assert_eq!(String::from_utf8_lossy(&out.stdout).trim(), "SERVING");
    let out = run(&[
        "health",
        "--target",
        &server.addr,
        "--service",
        "railcontact.v1.ContactService",
    ]);
    assert!(out.status.success());

    let out = run(&["health", "--target", &server.addr, "--service", "nope"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("NotFound"));

    let addr = closed_port();
    let out = run(&["health", "--target", &addr, "--timeout", "2"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("cannot connect"));
}

#[test]
fn sessions_refused_at_the_session_limit_open_again_with_backoff() {
    // Two session slots, six sessions: four are refused at first
    // (RESOURCE_EXHAUSTED) and open once earlier ones close.
    let server = Server::start_with(&[], &[("RAILCONTACT_MAX_SESSIONS", "2")]);
    let (v, out) = loadtest_json(&[
        "--target",
        &server.addr,
        "--sessions",
        "6",
        "--steps",
        "20",
        "--batch-clients",
        "0",
        "--mix",
        "patch:fastsim=1",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_clean(&v);
    assert_eq!(num(&v, "steps"), 120.0);
}
