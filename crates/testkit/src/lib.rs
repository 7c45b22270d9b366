//! What the workspace's tests share: installing the Debian packages a
//! test of another language's program needs (as root or through `sudo
//! -n`, saying so on stderr first), and skipping those tests when
//! [`SKIP_CLIENT_TESTS`] asks; and a test PKI for the TLS tests
//! ([`write_test_pki`]).

use std::path::Path;
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

/// A certificate authority for tests (rcgen, ring): its certificate and
/// the certificates it signs are written as PEM files.
pub struct TestAuthority {
    params: rcgen::CertificateParams,
    key: rcgen::KeyPair,
}

impl TestAuthority {
    /// A new authority named `common_name`.
    pub fn new(common_name: &str) -> TestAuthority {
        use rcgen::{BasicConstraints, CertificateParams, DnType, IsCa, KeyPair, KeyUsagePurpose};
        let mut params = CertificateParams::new(Vec::<String>::new()).unwrap();
        params.is_ca = IsCa::Ca(BasicConstraints::Unconstrained);
        params
            .distinguished_name
            .push(DnType::CommonName, common_name);
        params.key_usages = vec![
            KeyUsagePurpose::KeyCertSign,
            KeyUsagePurpose::CrlSign,
            KeyUsagePurpose::DigitalSignature,
        ];
        TestAuthority {
            params,
            key: KeyPair::generate().unwrap(),
        }
    }

    /// Writes the authority's certificate to `path`.
    pub fn write(&self, path: &Path) {
        let cert = self.params.self_signed(&self.key).unwrap();
        std::fs::write(path, cert.pem()).unwrap();
    }

    /// Writes a certificate it signs for `names` (subject alternative
    /// names, DNS names or IP addresses) to `cert` and its key to `key`:
    /// a server's (`server` true) or a client's.
    pub fn sign(&self, names: &[&str], server: bool, cert: &Path, key: &Path) {
        use rcgen::{CertificateParams, DnType, ExtendedKeyUsagePurpose, Issuer, KeyPair};
        let issuer = Issuer::from_params(&self.params, &self.key);
        let pair = KeyPair::generate().unwrap();
        let names: Vec<String> = names.iter().map(|n| n.to_string()).collect();
        let mut params = CertificateParams::new(names.clone()).unwrap();
        params
            .distinguished_name
            .push(DnType::CommonName, names.first().map_or("", String::as_str));
        params.extended_key_usages = vec![if server {
            ExtendedKeyUsagePurpose::ServerAuth
        } else {
            ExtendedKeyUsagePurpose::ClientAuth
        }];
        let signed = params.signed_by(&pair, &issuer).unwrap();
        std::fs::write(cert, signed.pem()).unwrap();
        std::fs::write(key, pair.serialize_pem()).unwrap();
    }
}

/// Writes a test PKI into `dir`: `ca.pem` (a [`TestAuthority`]),
/// `server.pem` and `server-key.pem` (for localhost and 127.0.0.1, signed
/// by it), `client.pem` and `client-key.pem` (a client certificate signed
/// by it).
pub fn write_test_pki(dir: &Path) {
    let ca = TestAuthority::new("railcontact test CA");
    ca.write(&dir.join("ca.pem"));
    ca.sign(
        &["localhost", "127.0.0.1"],
        true,
        &dir.join("server.pem"),
        &dir.join("server-key.pem"),
    );
    ca.sign(
        &["railcontact-test-client"],
        false,
        &dir.join("client.pem"),
        &dir.join("client-key.pem"),
    );
}
