//! The dependency boundary: the solver crate (`crates/solver`, everything
//! transport-free) depends on no network, async, protocol, storage,
//! command-line or plotting crate, so that it can be embedded in-process
//! with `cargo add railcontact-solver` alone. Asked of cargo itself
//! (`cargo tree`), so a dependency added to the solver's manifest, directly
//! or through another crate, fails this test.

use std::collections::BTreeSet;
use std::process::Command;

/// Crates the solver must never depend on, directly or transitively.
const FORBIDDEN: &[&str] = &[
    "tonic",
    "tokio",
    "prost",
    "hyper",
    "h2",
    "axum",
    "redb",
    "clap",
    "plotters",
    "tracing",
    "indicatif",
];

/// The names of the crates `package` depends on with `edges` (`cargo tree
/// -e EDGES`), itself included.
fn dependencies(package: &str, edges: &str) -> BTreeSet<String> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let out = Command::new(cargo)
        .args([
            "tree",
            "--manifest-path",
            concat!(env!("CARGO_MANIFEST_DIR"), "/Cargo.toml"),
            "-p",
            package,
            "-e",
            edges,
            "--prefix",
            "none",
            "--format",
            "{p}",
        ])
        .output()
        .expect("run cargo tree");
    assert!(
        out.status.success(),
        "cargo tree failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout)
        .expect("cargo tree prints UTF-8")
        .lines()
        .filter_map(|l| l.split_whitespace().next())
        .map(str::to_string)
        .collect()
}

#[test]
fn the_solver_crate_depends_on_no_transport_storage_or_front_end_crate() {
    let deps = dependencies("railcontact-solver", "normal,build");
    // The listing is real: the solver's own FFT and linear-algebra crates
    // are in it.
    for needed in ["railcontact-solver", "rustfft", "faer", "serde"] {
        assert!(deps.contains(needed), "{needed} missing from {deps:?}");
    }
    let bad: Vec<&str> = FORBIDDEN
        .iter()
        .copied()
        .filter(|f| deps.contains(*f))
        .collect();
    assert!(
        bad.is_empty(),
        "railcontact-solver depends on {bad:?}; keep transport, storage and front ends in the root package"
    );
}

#[test]
fn the_front_ends_stand_on_the_solver_crate() {
    let deps = dependencies("railcontact", "normal");
    for needed in ["railcontact-solver", "tonic", "clap"] {
        assert!(deps.contains(needed), "{needed} missing from {deps:?}");
    }
}

/// The CONTACT-compatible library (`crates/cntc`) is a front end of its
/// own over the solver crate and `railcontact-cntc-core`: it names neither
/// the service nor the command line (it cannot: they are not in its
/// dependencies). Its forwarding client brings the gRPC client stack
/// (tonic's channel, tokio, hyper, h2, prost, and tonic's tracing), never
/// the server's router, storage, command line or plots.
#[test]
fn the_contact_library_stands_on_the_solver_and_its_core() {
    let deps = dependencies("railcontact-cntc", "normal,build");
    for needed in [
        "railcontact-cntc",
        "railcontact-cntc-core",
        "railcontact-solver",
        "railcontact-proto",
        "tonic",
    ] {
        assert!(deps.contains(needed), "{needed} missing from {deps:?}");
    }
    let client_stack = ["tonic", "tokio", "prost", "hyper", "h2", "tracing"];
    let bad: Vec<&str> = FORBIDDEN
        .iter()
        .copied()
        .filter(|f| !client_stack.contains(f))
        .chain(["railcontact", "tracing-subscriber"])
        .filter(|f| deps.contains(*f))
        .collect();
    assert!(
        bad.is_empty(),
        "railcontact-cntc depends on {bad:?}; it is a front end over the solver crate with a \
         gRPC client"
    );
}

/// What the CONTACT library computes (`crates/cntc-core`), shared with
/// the service, is as transport-free as the solver crate.
#[test]
fn the_contact_library_core_depends_on_no_transport() {
    let deps = dependencies("railcontact-cntc-core", "normal,build");
    assert!(deps.contains("railcontact-solver"), "{deps:?}");
    let bad: Vec<&str> = FORBIDDEN
        .iter()
        .copied()
        .chain(["railcontact", "railcontact-cntc", "railcontact-proto"])
        .filter(|f| deps.contains(*f))
        .collect();
    assert!(
        bad.is_empty(),
        "railcontact-cntc-core depends on {bad:?}; keep transport in the front ends"
    );
}

/// The code lines (comments left out) of the sources under `src/DIR` that
/// name any of `names`.
fn lines_naming(dir: &str, names: &[&str]) -> Vec<String> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("src")
        .join(dir);
    let mut offenders = Vec::new();
    for entry in std::fs::read_dir(&dir).expect("read a source directory") {
        let path = entry.expect("a directory entry").path();
        let text = std::fs::read_to_string(&path).expect("read a source");
        for (i, line) in text.lines().enumerate() {
            let code = !line.trim_start().starts_with("//");
            if code && names.iter().any(|n| line.contains(n)) {
                offenders.push(format!("{}:{}: {}", path.display(), i + 1, line.trim()));
            }
        }
    }
    offenders
}

#[test]
fn the_service_does_not_import_the_command_line() {
    let offenders = lines_naming("service", &["crate::cli", "super::cli"]);
    assert!(
        offenders.is_empty(),
        "the service imports the command line:\n{}",
        offenders.join("\n")
    );
}

#[test]
fn the_command_line_does_not_import_the_service() {
    // The command line reaches a server through `crate::shared` (the wire
    // types); the binary's `main.rs` is the one place naming both.
    let offenders = lines_naming("cli", &["crate::service", "super::service"]);
    assert!(
        offenders.is_empty(),
        "the command line imports the service:\n{}",
        offenders.join("\n")
    );
    let shared = lines_naming("shared", &["crate::service", "crate::cli"]);
    assert!(
        shared.is_empty(),
        "shared names a front end:\n{}",
        shared.join("\n")
    );
}
