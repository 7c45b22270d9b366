//! Fixtures of the process-level tests: `railcontact serve` as a child
//! process on an ephemeral loopback port, and `railcontact` runs.

#![allow(dead_code)]

use std::io::{BufRead, BufReader};
use std::path::PathBuf;
use std::process::{Child, ChildStdout, Command, Output, Stdio};

use serde_json::Value;

pub use railcontact_testkit::{
    apt_install, check, has_sudo, installed, is_root, skip_client_test, SKIP_CLIENT_TESTS,
};

/// The built command.
pub const BIN: &str = env!("CARGO_BIN_EXE_railcontact");

/// A `railcontact serve` child process, killed when dropped.
pub struct Server {
    /// HOST:PORT it listens on.
    pub addr: String,
    /// HOST:PORT of its metrics page, when started with `--metrics-listen`.
    pub metrics: Option<String>,
    child: Child,
    _stdout: BufReader<ChildStdout>,
    /// Its standard error.
    log: PathBuf,
    _dir: tempfile::TempDir,
}

impl Server {
    /// Starts a server on 127.0.0.1, port 0, with its store in a fresh
    /// temporary directory and its log (`RUST_LOG=warn`) in a file there;
    /// waits for its `listening on` line.
    pub fn start() -> Server {
        Server::start_with(&[], &[])
    }

    /// [`Server::start`] with more arguments after `serve --listen
    /// 127.0.0.1:0` and more environment variables (set after, so they
    /// override, `RAILCONTACT_DATA_DIR` and `RUST_LOG`).
    pub fn start_with(args: &[&str], env: &[(&str, &str)]) -> Server {
        let dir = tempfile::tempdir().unwrap();
        let log = dir.path().join("server.log");
        let mut child = Command::new(BIN)
            .args(["serve", "--listen", "127.0.0.1:0"])
            .args(args)
            .env("RAILCONTACT_DATA_DIR", dir.path().join("store"))
            .env("RUST_LOG", "warn")
            .envs(env.iter().copied())
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(std::fs::File::create(&log).expect("create the server log"))
            .spawn()
            .expect("start railcontact serve");
        let mut stdout = BufReader::new(child.stdout.take().unwrap());
        let mut line = String::new();
        stdout
            .read_line(&mut line)
            .expect("read the listening line");
        let addr = line
            .trim()
            .strip_prefix("railcontact listening on ")
            .unwrap_or_else(|| {
                let _ = child.kill();
                panic!(
                    "unexpected first line {line:?}; server log:\n{}",
                    std::fs::read_to_string(&log).unwrap_or_default()
                )
            })
            .to_string();
        // With a metrics port the server says where on a second line.
        let metrics = args.contains(&"--metrics-listen").then(|| {
            line.clear();
            stdout.read_line(&mut line).expect("read the metrics line");
            line.trim()
                .strip_prefix("railcontact metrics on ")
                .unwrap_or_else(|| panic!("unexpected second line {line:?}"))
                .to_string()
        });
        Server {
            addr,
            metrics,
            child,
            _stdout: stdout,
            log,
            _dir: dir,
        }
    }

    /// The temporary directory of its store and log.
    pub fn dir(&self) -> &std::path::Path {
        self._dir.path()
    }

    /// What the server wrote to its standard error so far.
    pub fn log(&self) -> String {
        std::fs::read_to_string(&self.log).unwrap_or_default()
    }

    /// Sends SIGTERM (the graceful shutdown).
    pub fn terminate(&self) {
        signal(self.child.id(), "TERM");
    }

    /// Sends SIGINT (Ctrl-C).
    pub fn interrupt(&self) {
        signal(self.child.id(), "INT");
    }

    /// Its exit status once it has exited, waiting at most `limit`.
    pub fn wait_exit(&mut self, limit: std::time::Duration) -> Option<std::process::ExitStatus> {
        let start = std::time::Instant::now();
        loop {
            if let Some(status) = self.child.try_wait().expect("waits") {
                return Some(status);
            }
            if start.elapsed() > limit {
                return None;
            }
            std::thread::sleep(std::time::Duration::from_millis(20));
        }
    }

    /// Its metrics page (Prometheus text); needs `--metrics-listen`.
    pub fn metrics_page(&self) -> String {
        use std::io::{Read, Write};
        let addr = self
            .metrics
            .as_deref()
            .expect("started with --metrics-listen");
        let mut s = std::net::TcpStream::connect(addr).expect("connect to the metrics port");
        s.write_all(b"GET /metrics HTTP/1.1\r\nhost: x\r\nconnection: close\r\n\r\n")
            .expect("send the metrics request");
        let mut page = String::new();
        s.read_to_string(&mut page).expect("read the metrics page");
        page
    }
}

/// Sends signal `name` (TERM, KILL, ...) to process `pid` with kill(1).
pub fn signal(pid: u32, name: &str) {
    let _ = Command::new("kill")
        .arg(format!("-{name}"))
        .arg(pid.to_string())
        .stdin(Stdio::null())
        .stderr(Stdio::null())
        .status();
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// Every profile pair the server at `client` lists.
pub async fn list_pairs(
    client: &mut railcontact::service::pb::contact_service_client::ContactServiceClient<
        tonic::transport::Channel,
    >,
) -> Vec<railcontact::service::pb::ProfilePairInfo> {
    let req = railcontact::service::pb::ListProfilePairsRequest {};
    client
        .list_profile_pairs(req)
        .await
        .unwrap()
        .into_inner()
        .pairs
}

/// Runs `railcontact ARGS`.
pub fn run(args: &[&str]) -> Output {
    Command::new(BIN)
        .args(args)
        .stdin(Stdio::null())
        .output()
        .expect("run railcontact")
}

/// Runs `railcontact loadtest --json ARGS`; the parsed report and the
/// output.
pub fn loadtest_json(args: &[&str]) -> (Value, Output) {
    let mut all = vec!["loadtest", "--json"];
    all.extend_from_slice(args);
    let out = run(&all);
    let stdout = String::from_utf8_lossy(&out.stdout);
    let report: Value = serde_json::from_str(stdout.trim()).unwrap_or_else(|e| {
        panic!(
            "not one JSON object ({e}): {stdout}\nstderr: {}",
            String::from_utf8_lossy(&out.stderr)
        )
    });
    (report, out)
}

/// A number of the report.
pub fn num(v: &Value, key: &str) -> f64 {
    v[key]
        .as_f64()
        .unwrap_or_else(|| panic!("{key} missing in {v}"))
}

/// Checks what every clean report must hold: no errors, no mismatches,
/// ordered percentiles, positive throughput, every step verified.
pub fn assert_clean(v: &Value) {
    assert_eq!(num(v, "errors"), 0.0, "errors: {}", v["first_errors"]);
    assert_eq!(num(v, "mismatches"), 0.0, "{}", v["first_errors"]);
    let (p50, p90, p99, max) = (
        num(v, "p50_s"),
        num(v, "p90_s"),
        num(v, "p99_s"),
        num(v, "max_s"),
    );
    assert!(
        0.0 < p50 && p50 <= p90 && p90 <= p99 && p99 <= max,
        "{p50} {p90} {p99} {max}"
    );
    assert!(num(v, "throughput_per_s") > 0.0);
    assert_eq!(num(v, "verified_steps"), num(v, "steps"));
    for (kind, b) in v["kinds"].as_object().expect("kinds") {
        assert!(num(b, "steps") > 0.0, "{kind}: no steps");
        assert!(num(b, "p50_s") <= num(b, "max_s"), "{kind}");
    }
}

impl Server {
    /// The server process's peak resident memory so far (VmHWM) \[bytes\];
    /// None where /proc is not there.
    pub fn peak_rss_bytes(&self) -> Option<u64> {
        let status = std::fs::read_to_string(format!("/proc/{}/status", self.child.id())).ok()?;
        let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
        let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
        Some(kib * 1024)
    }
}

pub use railcontact_testkit::write_test_pki;
