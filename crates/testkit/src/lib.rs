//! What the workspace's tests share: installing the Debian packages a
//! test of another language's program needs (as root or through `sudo
//! -n`, saying so on stderr first), and skipping those tests when
//! [`SKIP_CLIENT_TESTS`] asks.

use std::process::{Command, Output, Stdio};

/// Set to anything but "" or "0", skips the tests that install things
/// beyond the Rust toolchain: the Python client's (a venv and PyPI
/// packages), the C++ client's and the CONTACT-compatible library's C,
/// Fortran and Python examples (Debian packages); the nginx proxy test
/// (tests/end_to_end/proxy_fleet.rs) then runs only where nginx is
/// installed.
pub const SKIP_CLIENT_TESTS: &str = "RAILCONTACT_SKIP_CLIENT_TESTS";

/// Whether [`SKIP_CLIENT_TESTS`] asks to skip `what`; says so on stderr
/// (`cargo test -- --nocapture` shows it).
pub fn skip_client_test(what: &str) -> bool {
    let skip = std::env::var(SKIP_CLIENT_TESTS).is_ok_and(|v| !v.is_empty() && v != "0");
    if skip {
        eprintln!("skipped: {what} ({SKIP_CLIENT_TESTS} is set)");
    }
    skip
}

/// Whether this process runs as root.
pub fn is_root() -> bool {
    Command::new("id")
        .arg("-u")
        .output()
        .map(|o| String::from_utf8_lossy(&o.stdout).trim() == "0")
        .unwrap_or(false)
}

/// Whether `sudo -n` works without a password.
pub fn has_sudo() -> bool {
    Command::new("sudo")
        .args(["-n", "true"])
        .stdin(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success())
}

/// Whether Debian package `package` is installed.
pub fn installed(package: &str) -> bool {
    Command::new("dpkg-query")
        .args(["-W", "-f=${Status}", package])
        .output()
        .map(|o| o.status.success() && String::from_utf8_lossy(&o.stdout).contains("ok installed"))
        .unwrap_or(false)
}

/// Runs `args` as root: directly when we are root, else through `sudo -n`.
pub fn as_root(args: &[&str]) -> Output {
    let mut command = if is_root() {
        let mut c = Command::new(args[0]);
        c.args(&args[1..]);
        c
    } else {
        let mut c = Command::new("sudo");
        c.arg("-n").args(args);
        c
    };
    command
        .env("DEBIAN_FRONTEND", "noninteractive")
        .stdin(Stdio::null())
        .output()
        .unwrap_or_else(|e| panic!("cannot run {args:?} (as root or with sudo -n): {e}"))
}

/// Held while apt-get runs: the tests of this binary run side by side, and
/// two apt-gets at once would fail on dpkg's lock.
static APT: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// Installs Debian packages `missing` with apt-get (as root or with
/// `sudo -n`), saying so first on stderr with `why`; fails the test with
/// `how` when apt-get fails. One install at a time in this process, and
/// each waits up to 5 minutes for dpkg's lock held by another process.
pub fn apt_install(missing: &[&str], why: &str, how: &str) {
    let _one_at_a_time = APT.lock().unwrap_or_else(|e| e.into_inner());
    let missing: Vec<&str> = missing.iter().copied().filter(|p| !installed(p)).collect();
    if missing.is_empty() {
        return;
    }
    eprintln!(
        "{why}: installing Debian packages with apt-get: {}",
        missing.join(" ")
    );
    check(
        &format!("apt-get update ({how})"),
        &as_root(&["apt-get", "update", "-q"]),
    );
    let mut install = vec![
        "apt-get",
        "install",
        "-y",
        "-q",
        "--no-install-recommends",
        "-o",
        "DPkg::Lock::Timeout=300",
    ];
    install.extend(&missing);
    check(
        &format!("apt-get install {missing:?} ({how})"),
        &as_root(&install),
    );
    let still: Vec<&str> = missing.iter().copied().filter(|p| !installed(p)).collect();
    assert!(still.is_empty(), "still missing after apt-get: {still:?}");
}

/// Fails the test with `what`'s output unless it succeeded.
pub fn check(what: &str, output: &Output) {
    assert!(
        output.status.success(),
        "{what} failed ({}):\n--- stdout\n{}\n--- stderr\n{}",
        output.status,
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
}
