//! The Python client's test suite (clients/python/tests) as part of
//! `cargo test`: a virtual environment at `target/py-venv` (made with
//! `python3 -m venv` if missing), the package installed into it with its
//! test extras (editable, from this checkout) when its pyproject.toml or
//! the checkout changed (a stamp file holds the hash of the one installed
//! and its path), then pytest against this build's server
//! binary. Anything missing (python3, pip, a package) fails the test. What
//! it creates and installs is said on stderr (`cargo test -- --nocapture`,
//! and in the output of a failure).
//!
//! `RAILCONTACT_PYTHON` names another interpreter than `python3`;
//! `RAILCONTACT_SKIP_CLIENT_TESTS=1` skips the test (it then passes, with a
//! `skipped:` line on stderr).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use sha2::{Digest, Sha256};

use crate::support;

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Runs `command`, failing the test with its output unless it succeeds.
fn run(what: &str, command: &mut Command) -> Output {
    let output = command
        .output()
        .unwrap_or_else(|e| panic!("{what}: cannot run {command:?}: {e}"));
    support::check(what, &output);
    output
}

/// The venv's interpreter, the venv made and the package installed as
/// needed.
fn python_with_client(venv: &Path) -> PathBuf {
    let python = venv.join("bin").join("python");
    if !python.is_file() {
        let base = std::env::var("RAILCONTACT_PYTHON").unwrap_or_else(|_| "python3".into());
        eprintln!(
            "Python client test: creating a virtual environment {} with {base} \
             (skip with {}=1)",
            venv.display(),
            support::SKIP_CLIENT_TESTS
        );
        run(
            "creating the venv",
            Command::new(base).args(["-m", "venv"]).arg(venv),
        );
    }
    let client = repo().join("clients").join("python");
    let pyproject = std::fs::read(client.join("pyproject.toml")).expect("pyproject.toml");
    let stamp = venv.join("railcontact-client.stamp");
    let hash: String = Sha256::digest(&pyproject)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect();
    // The checkout is part of the stamp: an editable install points at one
    // checkout's sources, and a venv copied with target/ from another
    // checkout would test that one's client.
    let want = format!("{hash} {}\n", client.display());
    if std::fs::read_to_string(&stamp).ok().as_deref() != Some(want.as_str()) {
        eprintln!(
            "Python client test: installing clients/python[test] and its dependencies \
             from PyPI into {} (pip; skip with {}=1)",
            venv.display(),
            support::SKIP_CLIENT_TESTS
        );
        run(
            "installing clients/python[test]",
            Command::new(&python)
                .args([
                    "-m",
                    "pip",
                    "install",
                    "-q",
                    "--disable-pip-version-check",
                    "-e",
                ])
                .arg(format!("{}[test]", client.display())),
        );
        std::fs::write(&stamp, want).expect("stamp written");
    }
    python
}

#[test]
fn python_client_tests_pass_against_this_server() {
    if support::skip_client_test("the Python client's tests") {
        return;
    }
    let venv = repo().join("target").join("py-venv");
    let python = python_with_client(&venv);
    let output = run(
        "pytest clients/python/tests",
        Command::new(&python)
            .args(["-m", "pytest", "-q", "-p", "no:cacheprovider"])
            .arg(repo().join("clients").join("python").join("tests"))
            .current_dir(repo().join("clients").join("python"))
            .env("RAILCONTACT_BIN", support::BIN)
            .env("PYTHONDONTWRITEBYTECODE", "1"),
    );
    let stdout = String::from_utf8_lossy(&output.stdout);
    println!("{stdout}");
    assert!(stdout.contains(" passed"), "pytest ran no test:\n{stdout}");
}
