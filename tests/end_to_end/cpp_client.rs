//! The C++ co-simulation client (clients/cpp) end to end: installs the
//! Debian packages it builds with when any is missing, builds it with CMake
//! into `target/cpp-client` (incremental on re-runs), starts the real server
//! binary on an ephemeral loopback port and runs the example
//! `cosim_wheelset` against it: a wheelset's lateral dynamics stepped
//! through the C interface over a WheelRailSession, with one mark/rollback
//! round whose forces must come back bit-identical (checked by the example
//! itself, which exits non-zero otherwise). This test checks the exit
//! status and that the printed trajectory is physically sound.
//!
//! A second test provokes the server's plausibility warnings
//! (`WheelRailResult.warnings`) and checks that they reach a C caller
//! (`rc_wheel_forces.n_warnings`, `rc_step_warning`: the check program
//! `clients/cpp/tests/warnings_c.c`), a C++ caller
//! (`StepOutput::warnings`: `tests/warnings_cpp.cpp`) and the example's
//! stderr: a pitch rate 5 % off -V / r0 (LONGITUDINAL_FORCE, the
//! wheelset), a roll that lifts the left wheel off its rail (APPROACH, the
//! left wheel), and none for a plausible step.
//!
//! The packages it installs are said on stderr before apt-get runs (`cargo
//! test -- --nocapture`, and in the output of a failure).
//! `RAILCONTACT_SKIP_CLIENT_TESTS=1` skips both tests (they then pass, with a
//! `skipped:` line on stderr).

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::sync::OnceLock;
use std::time::{Duration, Instant};

use crate::support;

use support::{check, Server};

/// What the client's CMake project needs (Debian 12 names).
const PACKAGES: &[&str] = &[
    "cmake",
    "make",
    "pkg-config",
    "protobuf-compiler",
    "protobuf-compiler-grpc",
    "libprotobuf-dev",
    "libgrpc++-dev",
];

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Installs the packages that are missing; fails the test when it cannot.
fn ensure_packages() {
    let missing: Vec<&str> = PACKAGES
        .iter()
        .copied()
        .filter(|p| !support::installed(p))
        .collect();
    if missing.is_empty() {
        return;
    }
    support::apt_install(
        &missing,
        &format!(
            "C++ client test (skip with {}=1)",
            support::SKIP_CLIENT_TESTS
        ),
        "the C++ client test needs these Debian packages and could not install them \
         (run as root or with passwordless sudo, with access to the Debian mirrors, \
         or install them by hand)",
    );
}

/// Installs what is missing and builds the client, once for the tests of
/// this module (which run side by side); returns the build folder.
fn built_client() -> &'static Path {
    static BUILD: OnceLock<PathBuf> = OnceLock::new();
    BUILD.get_or_init(|| {
        let t0 = Instant::now();
        ensure_packages();
        let build = build_client();
        eprintln!("C++ client ready in {:.1} s", t0.elapsed().as_secs_f64());
        build
    })
}

/// Configures and builds clients/cpp into target/cpp-client; returns the
/// build folder.
fn build_client() -> PathBuf {
    let source = repo().join("clients/cpp");
    let build = repo().join("target/cpp-client");
    // A build folder configured for another checkout (a copied target/)
    // makes cmake refuse: start it afresh.
    let cache = std::fs::read_to_string(build.join("CMakeCache.txt")).unwrap_or_default();
    let home = format!("CMAKE_HOME_DIRECTORY:INTERNAL={}", source.display());
    if !cache.is_empty() && !cache.lines().any(|l| l == home) {
        std::fs::remove_dir_all(&build).expect("removes the stale C++ build folder");
    }
    let configure = Command::new("cmake")
        .arg("-S")
        .arg(&source)
        .arg("-B")
        .arg(&build)
        .arg("-DCMAKE_BUILD_TYPE=Release")
        .stdin(Stdio::null())
        .output()
        .expect("cmake runs");
    check("cmake configure", &configure);
    let make = Command::new("cmake")
        .arg("--build")
        .arg(&build)
        .args(["--parallel", "2"])
        .stdin(Stdio::null())
        .output()
        .expect("cmake --build runs");
    check("cmake --build", &make);
    build
}

/// Runs `command`, killing it after `limit`.
fn run_with_limit(command: &mut Command, limit: Duration) -> Output {
    let mut child = command
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawns");
    let mut out_pipe = child.stdout.take().unwrap();
    let mut err_pipe = child.stderr.take().unwrap();
    let out_reader = std::thread::spawn(move || {
        let mut v = Vec::new();
        out_pipe.read_to_end(&mut v).map(|_| v)
    });
    let err_reader = std::thread::spawn(move || {
        let mut v = Vec::new();
        err_pipe.read_to_end(&mut v).map(|_| v)
    });
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().expect("waits") {
            break status;
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            panic!("{command:?} did not finish within {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    Output {
        status,
        stdout: out_reader.join().unwrap().unwrap(),
        stderr: err_reader.join().unwrap().unwrap(),
    }
}

struct Row {
    time_s: f64,
    lateral_m: f64,
    lateral_m_per_s: f64,
    contact_force_y_n: f64,
    spring_force_y_n: f64,
}

fn parse_csv(text: &str) -> Vec<Row> {
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some("step,time_s,lateral_m,lateral_m_per_s,contact_force_y_n,spring_force_y_n"),
        "CSV header"
    );
    lines
        .enumerate()
        .map(|(i, line)| {
            let cells: Vec<&str> = line.split(',').collect();
            assert_eq!(cells.len(), 6, "row {i}: {line:?}");
            assert_eq!(cells[0], i.to_string(), "row {i}: step index");
            let v: Vec<f64> = cells[1..]
                .iter()
                .map(|c| {
                    c.parse::<f64>()
                        .unwrap_or_else(|e| panic!("row {i}: {c:?}: {e}"))
                })
                .collect();
            assert!(v.iter().all(|x| x.is_finite()), "row {i}: {line:?}");
            Row {
                time_s: v[0],
                lateral_m: v[1],
                lateral_m_per_s: v[2],
                contact_force_y_n: v[3],
                spring_force_y_n: v[4],
            }
        })
        .collect()
}

fn check_trajectory(rows: &[Row]) {
    const STEPS: usize = 200;
    const Y0: f64 = 3.0e-3;
    assert_eq!(rows.len(), STEPS, "one row per step");
    assert_eq!(rows[0].lateral_m, Y0);
    assert_eq!(rows[0].lateral_m_per_s, 0.0);
    for (i, r) in rows.iter().enumerate() {
        assert!((r.time_s - i as f64 * 1e-3).abs() < 1e-9, "row {i}: time");
        // Bounded: never beyond the initial offset, with a margin.
        assert!(
            r.lateral_m.abs() <= 1.2 * Y0,
            "row {i}: |y| = {}",
            r.lateral_m
        );
        assert!(r.contact_force_y_n.abs() < 1.0e5, "row {i}: contact force");
    }
    // At rest 3 mm to the right, the contact forces alone push the
    // wheelset back to the centre (the profiles' gravitational stiffness).
    assert!(
        rows[0].contact_force_y_n < 0.0,
        "restoring at rest: {} N",
        rows[0].contact_force_y_n
    );
    // The creep forces damp it heavily (lateral creep coefficient over the
    // speed, far above the critical damping of the spring): it creeps back
    // to the centre without overshoot ...
    for (i, pair) in rows.windows(2).enumerate() {
        assert!(
            pair[1].lateral_m <= pair[0].lateral_m && pair[1].lateral_m > 0.0,
            "row {}: y = {} after {}",
            i + 1,
            pair[1].lateral_m,
            pair[0].lateral_m
        );
    }
    let last = rows.last().unwrap();
    assert!(
        last.lateral_m.abs() < 0.9 * Y0,
        "the offset decays: {} m after {} s",
        last.lateral_m,
        last.time_s
    );
    // ... with the contact forces taking energy out (on balance over the
    // run, so their power is negative).
    let power: f64 = rows
        .iter()
        .map(|r| r.contact_force_y_n * r.lateral_m_per_s)
        .sum();
    assert!(
        power < 0.0,
        "contact forces damp the motion: sum F v = {power}"
    );
    // The spring's force is the one the example applied.
    for r in rows {
        assert!((r.spring_force_y_n + 2.0e6 * r.lateral_m).abs() <= 1e-6);
    }
}

#[test]
fn cpp_cosim_wheelset_against_the_server() {
    if support::skip_client_test("the C++ client's test") {
        return;
    }
    let example = built_client().join("cosim_wheelset");
    assert!(Path::new(&example).is_file(), "{example:?} was built");

    let server = Server::start();
    let output = run_with_limit(
        Command::new(&example).args([server.addr.as_str(), "--model", "hertz_fastsim"]),
        Duration::from_secs(300),
    );
    let stdout = String::from_utf8_lossy(&output.stdout);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        output.status.success(),
        "cosim_wheelset failed ({}):\n--- stderr\n{stderr}\n--- server log\n{}",
        output.status,
        server.log()
    );
    assert!(
        stderr.contains("forces bit-identical"),
        "the rollback round ran: {stderr}"
    );
    // The server's default pitch rate is not checked: no warnings.
    assert!(!stderr.contains("warning"), "no warnings: {stderr}");
    check_trajectory(&parse_csv(&stdout));
    drop(server);

    // A port with nothing listening: refused at once, not after the 10 s
    // connect timeout.
    let closed = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let addr = closed.local_addr().unwrap().to_string();
    drop(closed);
    let t = Instant::now();
    let output = run_with_limit(
        Command::new(&example).args([addr.as_str(), "--model", "hertz_fastsim"]),
        Duration::from_secs(60),
    );
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        !output.status.success() && stderr.contains("refused or unreachable"),
        "{stderr}"
    );
    assert!(
        t.elapsed() < Duration::from_secs(5),
        "a refused port took {:.1} s",
        t.elapsed().as_secs_f64()
    );

    // The same over TLS with a bearer token (`--tls-ca`,
    // RAILCONTACT_TOKEN); without the token the session is refused.
    let dir = tempfile::tempdir().unwrap();
    support::write_test_pki(dir.path());
    let tokens = dir.path().join("tokens.toml");
    std::fs::write(
        &tokens,
        "[[token]]\nname = \"cpp\"\nrole = \"solve\"\ntoken = \"cpp-test-token\"\n",
    )
    .unwrap();
    let file = |name: &str| dir.path().join(name).display().to_string();
    let server = Server::start_with(
        &[
            "--tls-cert",
            &file("server.pem"),
            "--tls-key",
            &file("server-key.pem"),
            "--auth-tokens-file",
            &file("tokens.toml"),
        ],
        &[],
    );
    let target = server.addr.replace("127.0.0.1", "localhost");
    let secured = |token: Option<&str>| {
        let mut c = Command::new(&example);
        c.args([
            target.as_str(),
            "--steps",
            "120",
            "--tls-ca",
            &file("ca.pem"),
        ])
        .env_remove("RAILCONTACT_TOKEN");
        if let Some(t) = token {
            c.env("RAILCONTACT_TOKEN", t);
        }
        run_with_limit(&mut c, Duration::from_secs(120))
    };
    let output = secured(Some("cpp-test-token"));
    assert!(
        output.status.success(),
        "cosim_wheelset over TLS with a token failed ({}):\n{}\n--- server log\n{}",
        output.status,
        String::from_utf8_lossy(&output.stderr),
        server.log()
    );
    let output = secured(None);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        !output.status.success() && stderr.contains("UNAUTHENTICATED"),
        "without a token: {stderr}"
    );
}

/// The pitch rate the warnings test prescribes: 5 % faster than -V / r0 at
/// 30 m/s (r0 = 0.46 m, the built-in pair's nominal radius), as
/// `clients/cpp/tests/warnings_c.c` and `warnings_cpp.cpp` do.
const FAR_PITCH_RAD_PER_S: f64 = -30.0 / 0.46 * 1.05;

/// One warning as the check programs print it.
#[derive(Debug, PartialEq)]
struct WarningLine {
    kind: i32,
    side: i32,
    /// Printed by warnings_cpp only.
    field: Option<String>,
    value: f64,
    limit: f64,
    message: String,
}

/// One step as the check programs print it, with its warnings.
#[derive(Debug)]
struct StepLine {
    step: u64,
    label: String,
    n_warnings: usize,
    warnings: Vec<WarningLine>,
}

/// Parses `step=K label=L n_warnings=N` lines, each followed by its
/// `warning step=K index=I kind=.. side=.. [field=..] value=.. limit=..
/// message=TEXT` lines.
fn parse_warning_report(text: &str) -> Vec<StepLine> {
    let mut steps: Vec<StepLine> = Vec::new();
    for line in text.lines() {
        let (head, message) = match line.split_once(" message=") {
            Some((h, m)) => (h, Some(m)),
            None => (line, None),
        };
        let mut words = head.split_whitespace().peekable();
        let is_warning = words.peek() == Some(&"warning");
        if is_warning {
            words.next();
        }
        let kv: std::collections::HashMap<&str, &str> = words
            .map(|w| {
                w.split_once('=')
                    .unwrap_or_else(|| panic!("{w:?} in {line:?}"))
            })
            .collect();
        let get = |k: &str| *kv.get(k).unwrap_or_else(|| panic!("no {k} in {line:?}"));
        let step: u64 = get("step").parse().unwrap();
        if is_warning {
            let current = steps
                .last_mut()
                .unwrap_or_else(|| panic!("a warning before any step: {line:?}"));
            assert_eq!(current.step, step, "{line:?}");
            assert_eq!(
                get("index").parse::<usize>().unwrap(),
                current.warnings.len(),
                "{line:?}"
            );
            current.warnings.push(WarningLine {
                kind: get("kind").parse().unwrap(),
                side: get("side").parse().unwrap(),
                field: kv.get("field").map(|f| f.to_string()),
                value: get("value").parse().unwrap(),
                limit: get("limit").parse().unwrap(),
                message: message
                    .unwrap_or_else(|| panic!("no message in {line:?}"))
                    .to_string(),
            });
        } else {
            steps.push(StepLine {
                step,
                label: get("label").to_string(),
                n_warnings: get("n_warnings").parse().unwrap(),
                warnings: Vec::new(),
            });
        }
    }
    steps
}

/// Checks the warnings of the check programs' steps against what the
/// server finds for them.
fn check_warning_report(who: &str, steps: &[StepLine], labels: &[&str]) {
    let got: Vec<&str> = steps.iter().map(|s| s.label.as_str()).collect();
    assert_eq!(got, labels, "{who}: the steps");
    for s in steps {
        assert_eq!(
            s.n_warnings,
            s.warnings.len(),
            "{who}: step {} ({}): n_warnings against the warnings read",
            s.step,
            s.label
        );
        match s.label.as_str() {
            "plausible" | "again" => {
                assert_eq!(s.n_warnings, 0, "{who}: a plausible step: {s:?}")
            }
            "pitch" => {
                assert_eq!(s.n_warnings, 1, "{who}: the pitch step: {s:?}");
                let w = &s.warnings[0];
                assert_eq!(w.kind, 2, "{who}: RC_WARNING_LONGITUDINAL_FORCE: {w:?}");
                assert_eq!(w.side, -1, "{who}: RC_WHEELSET: {w:?}");
                assert_eq!(w.limit, 0.9, "{who}: {w:?}");
                // Both wheels driven to saturation: 0.99995 of the adhesion.
                assert!(
                    (0.99..=1.0 + 1e-9).contains(&w.value),
                    "{who}: the share of the adhesion: {w:?}"
                );
                assert!(
                    w.message.contains("velocity.pitch_rad_per_s")
                        && w.message.contains(&format!("{FAR_PITCH_RAD_PER_S}")),
                    "{who}: the message names the pitch rate: {w:?}"
                );
                if let Some(field) = &w.field {
                    assert_eq!(field, "step.velocity.pitch_rad_per_s", "{who}: {w:?}");
                }
            }
            "roll" => {
                assert_eq!(s.n_warnings, 1, "{who}: the roll step: {s:?}");
                let w = &s.warnings[0];
                assert_eq!(w.kind, 1, "{who}: RC_WARNING_APPROACH: {w:?}");
                assert_eq!(w.side, 0, "{who}: RC_LEFT: {w:?}");
                assert_eq!(w.limit, 10.0, "{who}: {w:?}");
                // 1 mrad lifts the left wheel 1.7 mm off its rail, which its
                // 60 kN press through alone: 26 times its elastic approach.
                assert!(
                    (15.0..40.0).contains(&w.value),
                    "{who}: the approach ratio: {w:?}"
                );
                assert!(
                    w.message.contains("left wheel") && w.message.contains("position.roll_rad"),
                    "{who}: the message names the wheel and the roll: {w:?}"
                );
                if let Some(field) = &w.field {
                    assert_eq!(field, "step.position.roll_rad", "{who}: {w:?}");
                }
            }
            other => panic!("{who}: unexpected step label {other:?}"),
        }
    }
}

#[test]
fn cpp_client_warnings_reach_c_and_cpp() {
    if support::skip_client_test("the C++ client's warnings test") {
        return;
    }
    let build = built_client();
    let server = Server::start();
    let run = |program: &str, args: &[&str]| {
        let output = run_with_limit(
            Command::new(build.join(program))
                .arg(server.addr.as_str())
                .args(args),
            Duration::from_secs(120),
        );
        let stdout = String::from_utf8_lossy(&output.stdout).into_owned();
        let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
        assert!(
            output.status.success(),
            "{program} failed ({}):\n--- stdout\n{stdout}\n--- stderr\n{stderr}\n--- server log\n{}",
            output.status,
            server.log()
        );
        (stdout, stderr)
    };

    // Through the C interface; warnings_c itself checks bad indices, a NULL
    // session, truncation, and the warnings over a refused step, a rollback
    // and the next plausible step.
    let (stdout, _) = run("warnings_c", &[]);
    eprintln!("warnings_c:\n{stdout}");
    let c = parse_warning_report(&stdout);
    check_warning_report("C", &c, &["plausible", "pitch", "roll", "again"]);

    // Through the C++ class: the same warnings, with their fields.
    let (stdout, _) = run("warnings_cpp", &[]);
    let cpp = parse_warning_report(&stdout);
    check_warning_report("C++", &cpp, &["plausible", "pitch", "roll"]);
    for (c, cpp) in c.iter().zip(&cpp) {
        assert_eq!(c.warnings.len(), cpp.warnings.len(), "step {}", c.step);
        for (a, b) in c.warnings.iter().zip(&cpp.warnings) {
            assert_eq!(
                (a.kind, a.side, a.value, a.limit, &a.message),
                (b.kind, b.side, b.value, b.limit, &b.message),
                "step {}: C and C++ agree",
                c.step
            );
        }
    }

    // The example with the far pitch rate: every step warns, printed once
    // on stderr (not again for the steps solved again after the rollback),
    // nothing of it on the CSV.
    let pitch = format!("{FAR_PITCH_RAD_PER_S}");
    let (stdout, stderr) = run(
        "cosim_wheelset",
        &[
            "--model",
            "hertz_fastsim",
            "--steps",
            "120",
            "--pitch-rad-per-s",
            &pitch,
        ],
    );
    assert!(!stdout.contains("warning"), "no warnings on the CSV");
    let rows = stdout.lines().count() - 1;
    assert_eq!(rows, 120, "one CSV row per step");
    let warned: Vec<u64> = stderr
        .lines()
        .filter(|l| l.contains(": warning: "))
        .map(|l| {
            assert!(
                l.contains("warning: longitudinal_force (wheelset), measure ")
                    && l.contains("limit 0.9: ")
                    && l.contains("velocity.pitch_rad_per_s"),
                "{l}"
            );
            l.strip_prefix("step ")
                .and_then(|r| r.split_once(':'))
                .and_then(|(k, _)| k.parse().ok())
                .unwrap_or_else(|| panic!("step number of {l:?}"))
        })
        .collect();
    assert_eq!(
        warned,
        (0..120).collect::<Vec<u64>>(),
        "each step's warning once, in order:\n{stderr}"
    );
}
