//! What the library's tests share: the shared library's folder, scratch
//! folders, compilers, building and running a C or Fortran program against
//! the library, and a railcontact server in the test process for the
//! forwarding mode.
#![allow(dead_code)]

use std::net::SocketAddr;
use std::path::{Path, PathBuf};
use std::process::Command;

use railcontact::service::config::ServeConfig;
use railcontact::service::server::{start, RunningServer};
use railcontact_testkit::{apt_install, check, skip_client_test};

/// The package's folder.
pub fn package() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The folder of the shared library `libcontact_addon.so` cargo built for
/// these tests (beside the test executable).
pub fn library_dir() -> PathBuf {
    let exe = std::env::current_exe().unwrap();
    let dir = exe.parent().unwrap().to_path_buf();
    assert!(
        dir.join("libcontact_addon.so").exists(),
        "no libcontact_addon.so in {}",
        dir.display()
    );
    dir
}

/// A fresh folder for a test's build products.
pub fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("railcontact-cntc-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Makes sure the program `tool` exists, installing Debian `package` when
/// it does not; false when the client tests are to be skipped.
pub fn tool(tool: &str, package: &str, what: &str) -> bool {
    if Command::new(tool).arg("--version").output().is_ok() {
        return true;
    }
    if skip_client_test(what) {
        return false;
    }
    apt_install(&[package], what, &format!("{tool} builds the example"));
    true
}

/// Links `source` (C or Fortran) with `compiler` against the library;
/// the program.
pub fn build(compiler: &str, source: &Path, name: &str) -> PathBuf {
    let lib = library_dir();
    let dir = scratch(name);
    let exe = dir.join(name);
    let mut cc = Command::new(compiler);
    cc.arg(source)
        .arg("-I")
        .arg(package().join("include"))
        .arg("-o")
        .arg(&exe)
        .arg("-L")
        .arg(&lib)
        .arg("-lcontact_addon")
        .arg(format!("-Wl,-rpath,{}", lib.display()))
        .current_dir(&dir);
    if compiler == "cc" {
        cc.args(["-Wall", "-Werror"]);
    }
    check(
        &format!("{compiler} {}", source.display()),
        &cc.output().unwrap(),
    );
    exe
}

/// Runs program `exe` with `args` and the environment `env`; its
/// standard output.
pub fn run(exe: &Path, args: &[&Path], env: &[(&str, &str)]) -> String {
    let out = Command::new(exe)
        .args(args)
        .envs(env.iter().copied())
        .current_dir(exe.parent().unwrap())
        .output()
        .unwrap();
    check(&format!("running {}", exe.display()), &out);
    String::from_utf8(out.stdout).unwrap()
}

/// [`build`] and [`run`] in process mode.
pub fn build_and_run(compiler: &str, source: &Path, name: &str, args: &[&Path]) -> String {
    let exe = build(compiler, source, name);
    let out = run(&exe, args, &[]);
    let _ = std::fs::remove_dir_all(exe.parent().unwrap());
    out
}

/// A railcontact server (the service of this repository) running in the
/// test process on a loopback port, memory-only, for the library's
/// forwarding mode.
pub struct TestServer {
    /// HOST:PORT it listens on.
    pub addr: SocketAddr,
    server: Option<RunningServer>,
    rt: tokio::runtime::Runtime,
}

impl TestServer {
    /// A server on `listen` (`127.0.0.1:0`: any free port).
    pub fn start(listen: &str) -> TestServer {
        let rt = tokio::runtime::Builder::new_multi_thread()
            .worker_threads(2)
            .enable_all()
            .build()
            .unwrap();
        let config = ServeConfig {
            listen: listen.parse().unwrap(),
            data_dir: Default::default(),
            shutdown_grace_s: 1.0,
            ..ServeConfig::default()
        };
        let server = rt.block_on(start(&config)).expect("the server starts");
        TestServer {
            addr: server.addr,
            server: Some(server),
            rt,
        }
    }

    /// Stops the server at once, dropping its streams (as a killed one).
    pub fn kill(mut self) {
        if let Some(s) = self.server.take() {
            self.rt.block_on(s.shutdown_or(async {}));
        }
    }
}
