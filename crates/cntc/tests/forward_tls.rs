//! The forwarding mode to a server that speaks TLS only and checks bearer
//! tokens, as a fleet is deployed: with the authority
//! (`RAILCONTACT_CNTC_TLS_CA`) and an accepted token
//! (`RAILCONTACT_CNTC_TOKEN`) every getter reads the in-process values bit
//! for bit; a refused token, a missing token and a plaintext attempt on
//! the TLS port are each `CNTC_err_server` with a message that names the
//! setting to mend; so is a calculation beyond the server's
//! `max_solve_time_s`, after which the element calculates again.
//!
//! The library reads its environment once per process, so each case runs
//! in a child process of this test executable ([`client`], ignored when
//! run on its own) against one server started here.

mod common;

use std::path::Path;
use std::process::Command;

use common::{calculate, mode, patch_values, tractcurv, TestServer};
use contact_addon::ffi::*;
use contact_addon::flags::err;

/// What the child process is to find (`same` or `server_error`).
const EXPECT: &str = "RAILCONTACT_TEST_FORWARD_EXPECT";

/// The token the server accepts (role solve).
const TOKEN: &str = "cntc-test-token-0123456789abcdef";

/// One child process's case: calculations in process and forwarded, as
/// [`EXPECT`] says they must compare.
#[test]
#[ignore = "a child process of tls_and_tokens_as_a_fleet_is_deployed"]
fn client() {
    let expect = std::env::var(EXPECT).expect("run by tls_and_tokens_as_a_fleet_is_deployed");
    if expect == "time_limit" {
        // 400 x 400 elements in steady rolling take more than a second
        // here; the server stops them at its limit. The element's next
        // calculation, on the usual grid, goes on a new session.
        mode(true);
        tractcurv(3, 3, 2);
        let hz = [400.0, 400.0, 0.0008, 0.5, 1.1];
        unsafe { cntc_sethertzcontact(&3, &1, &-2, &5, hz.as_ptr()) };
        assert_eq!(calculate(3, [1e-3, 0.0, 0.0]), err::SERVER, "400 x 400");
        let hz = [48.0, 44.0, 0.0008, 0.5, 1.1];
        unsafe { cntc_sethertzcontact(&3, &1, &-2, &5, hz.as_ptr()) };
        assert_eq!(calculate(3, [1e-3, 0.0, 0.0]), 0, "48 x 44 after it");
        mode(false);
        unsafe { cntc_finalize(&3) };
        return;
    }
    let creepages = [[1e-4, 0.0, 0.0], [1e-3, 2e-4, 1e-4]];
    mode(false);
    tractcurv(1, 3, 2);
    let local: Vec<_> = creepages
        .iter()
        .map(|c| (calculate(1, *c), patch_values(1)))
        .collect();
    mode(true);
    tractcurv(2, 3, 2);
    for (k, c) in creepages.iter().enumerate() {
        let ierror = calculate(2, *c);
        match expect.as_str() {
            "same" => {
                assert_eq!(ierror, local[k].0, "calculation {k}: ierror");
                assert!(
                    patch_values(2) == local[k].1,
                    "calculation {k}: forwarded values differ from the in-process ones"
                );
            }
            "server_error" => assert_eq!(ierror, err::SERVER, "calculation {k}: ierror"),
            other => panic!("{EXPECT} = {other}"),
        }
    }
    mode(false);
    for e in [1, 2] {
        unsafe { cntc_finalize(&e) };
    }
}

/// Runs [`client`] in a child process with `env`; its standard error
/// (the library's log).
fn run_client(expect: &str, env: &[(&str, &str)]) -> String {
    let out = Command::new(std::env::current_exe().unwrap())
        .args(["--exact", "client", "--ignored", "--nocapture"])
        .env(EXPECT, expect)
        .env_remove("RAILCONTACT_CNTC_TLS_CA")
        .env_remove("RAILCONTACT_CNTC_TOKEN")
        .env_remove("RAILCONTACT_CNTC_TLS_SERVER_NAME")
        .env("RAILCONTACT_CNTC_TIMEOUT_S", "30")
        .envs(env.iter().copied())
        .output()
        .unwrap();
    let (stdout, stderr) = (
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr),
    );
    assert!(
        out.status.success(),
        "the client expecting {expect} with {env:?} failed:\n{stdout}\n{stderr}"
    );
    assert!(
        stdout.contains("1 passed"),
        "the client did not run:\n{stdout}"
    );
    format!("{stdout}\n{stderr}")
}

fn tokens_file(dir: &Path) -> String {
    let path = dir.join("tokens.toml");
    std::fs::write(
        &path,
        format!("[[token]]\nname = \"simulator\"\nrole = \"solve\"\ntoken = \"{TOKEN}\"\n"),
    )
    .unwrap();
    path.display().to_string()
}

#[test]
fn tls_and_tokens_as_a_fleet_is_deployed() {
    let dir = common::scratch("tls");
    railcontact_testkit::write_test_pki(&dir);
    let tokens = tokens_file(&dir);
    let server = TestServer::start_with("127.0.0.1:0", |c| {
        c.tls_cert = Some(dir.join("server.pem"));
        c.tls_key = Some(dir.join("server-key.pem"));
        c.auth_tokens_file = Some(tokens.clone().into());
    });
    let addr = server.addr.to_string();
    let ca = dir.join("ca.pem").display().to_string();
    let target = ("RAILCONTACT_CNTC_SERVER", addr.as_str());

    run_client(
        "same",
        &[
            target,
            ("RAILCONTACT_CNTC_TLS_CA", &ca),
            ("RAILCONTACT_CNTC_TOKEN", TOKEN),
        ],
    );
    // The certificate names localhost and 127.0.0.1: a name it holds is
    // accepted, one it does not hold refused (at the end).
    run_client(
        "same",
        &[
            target,
            ("RAILCONTACT_CNTC_TLS_CA", &ca),
            ("RAILCONTACT_CNTC_TLS_SERVER_NAME", "localhost"),
            ("RAILCONTACT_CNTC_TOKEN", TOKEN),
        ],
    );
    let log = run_client(
        "server_error",
        &[
            target,
            ("RAILCONTACT_CNTC_TLS_CA", &ca),
            ("RAILCONTACT_CNTC_TOKEN", "not-the-token-0123456789abcdef"),
        ],
    );
    assert!(log.contains("RAILCONTACT_CNTC_TOKEN"), "{log}");
    let log = run_client("server_error", &[target, ("RAILCONTACT_CNTC_TLS_CA", &ca)]);
    assert!(log.contains("RAILCONTACT_CNTC_TOKEN"), "{log}");
    // Plaintext to the TLS port.
    let log = run_client("server_error", &[target, ("RAILCONTACT_CNTC_TOKEN", TOKEN)]);
    assert!(log.contains(&addr), "{log}");
    assert!(log.contains("RAILCONTACT_CNTC_TLS_CA"), "{log}");
    let log = run_client(
        "server_error",
        &[
            target,
            ("RAILCONTACT_CNTC_TLS_CA", &ca),
            ("RAILCONTACT_CNTC_TLS_SERVER_NAME", "elsewhere.example"),
            ("RAILCONTACT_CNTC_TOKEN", TOKEN),
        ],
    );
    assert!(log.contains(&addr), "{log}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A forwarded calculation longer than the server's `max_solve_time_s`
/// is stopped there: `CNTC_err_server` with the limit named on the log,
/// and the element calculates again at its next call.
#[test]
fn a_calculation_beyond_the_servers_time_limit_is_a_server_error() {
    let server = TestServer::start_with("127.0.0.1:0", |c| {
        c.max_solve_time_s = 0.3;
        c.max_grid_elements = 200_000;
    });
    let addr = server.addr.to_string();
    let log = run_client("time_limit", &[("RAILCONTACT_CNTC_SERVER", &addr)]);
    assert!(log.contains("max_solve_time_s"), "{log}");
}
