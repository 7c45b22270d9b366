//! Two simulator processes forwarding to one railcontact server share the
//! server's placed profile pair: the second process's element gets the
//! pair the first one's had placed (the server's pair cache counts one
//! build and a hit), and both get the same bits.
//!
//! The simulators are this test binary run again as child processes
//! ([`child_forwarded_wheel`]), each with `RAILCONTACT_CNTC_SERVER` set,
//! as a simulator would start with the library in forwarding mode. The
//! server runs in this process, alone in this test binary, so that the
//! cache's counts are the children's only.

mod common;

use std::io::{BufRead, BufReader, Read, Write};
use std::process::{Child, ChildStdout, Command, Stdio};

use common::{mbench_right_wheel, TestServer};
use railcontact_solver::wheelrail::PairCache;

/// Set in the children's environment: only they compute.
const CHILD: &str = "RAILCONTACT_CNTC_TEST_CHILD";

/// The simulator process: the Manchester benchmark's right wheel in flange
/// contact, forwarded; prints its ierror and values, then keeps its
/// element (and so the server's session and pair) until its standard
/// input closes.
#[test]
#[ignore = "a child process of two_simulator_processes_share_the_servers_pair"]
fn child_forwarded_wheel() {
    if std::env::var_os(CHILD).is_none() {
        return;
    }
    let (ierror, bits) = mbench_right_wheel(1, 7.5, None);
    let values: Vec<String> = bits.iter().map(|b| format!("{b:x}")).collect();
    println!("RESULT {ierror} {}", values.join(","));
    std::io::stdout().flush().unwrap();
    let mut rest = String::new();
    while std::io::stdin().read_line(&mut rest).unwrap_or(0) > 0 {}
}

/// A child started on `server`, its result line and the rest of its
/// output (read to the end before it is waited for: the harness writes
/// its summary there).
fn simulator(server: &TestServer) -> (Child, String, BufReader<ChildStdout>) {
    let mut child = Command::new(std::env::current_exe().unwrap())
        .args([
            "--exact",
            "child_forwarded_wheel",
            "--ignored",
            "--nocapture",
            "--test-threads=1",
        ])
        .env(CHILD, "1")
        .env("RAILCONTACT_CNTC_SERVER", server.addr.to_string())
        .env("RAILCONTACT_CNTC_TIMEOUT_S", "60")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .expect("the test binary runs again");
    let mut out = BufReader::new(child.stdout.take().unwrap());
    // The harness prints the test's name before the test's own output, on
    // the same line.
    let line = (&mut out)
        .lines()
        .map_while(Result::ok)
        .find_map(|l| l.find("RESULT ").map(|at| l[at..].to_string()))
        .expect("the child prints its result");
    (child, line, out)
}

#[test]
fn two_simulator_processes_share_the_servers_pair() {
    let server = TestServer::start("127.0.0.1:0");
    let before = PairCache::global().stats();
    let (first, a, first_out) = simulator(&server);
    // The first process still holds its element when the second computes.
    let (second, b, second_out) = simulator(&server);
    let after = PairCache::global().stats();
    for (mut child, mut out) in [(first, first_out), (second, second_out)] {
        // Closing its input lets it finish.
        drop(child.stdin.take());
        let mut rest = String::new();
        out.read_to_string(&mut rest).unwrap();
        assert!(child.wait().unwrap().success(), "a child failed: {rest}");
    }
    assert!(a.starts_with("RESULT 0 "), "the calculation succeeds: {a}");
    assert_eq!(a, b, "both processes get the same bits");
    // The second process's element got the first one's pair: one build.
    assert_eq!(after.builds - before.builds, 1, "one pair placed");
    assert!(
        after.hits > before.hits,
        "a request answered by the placed pair"
    );
    assert!(after.live >= 1, "held while both elements live");
}
