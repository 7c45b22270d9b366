//! Scale-out on loopback: three `railcontact serve` processes, and
//! `railcontact loadtest` spreading its sessions over them (session k on
//! replica k mod 3, batch clients after them). Every answer of every
//! replica must equal the replay on the first replica, bit for
//! bit. Throughput against one and against three replicas is printed, not
//! asserted: the machine is shared and noisy, and three servers on two
//! cores share the same CPUs anyway.

use crate::support;

use support::{assert_clean, loadtest_json, num, Server};

const MIX: &str = "wheelrail:hertz_fastsim=4,wheelrail:exact=1,patch:exact40=1";

fn args(targets: &str) -> Vec<&str> {
    vec![
        "--target",
        targets,
        "--sessions",
        "6",
        "--steps",
        "8",
        "--batch-clients",
        "3",
        "--batch-items",
        "4",
        "--mix",
        MIX,
    ]
}

#[test]
fn sessions_spread_over_three_replicas_match_a_single_server_baseline() {
    let servers: Vec<Server> = (0..3).map(|_| Server::start()).collect();
    let targets = servers
        .iter()
        .map(|s| s.addr.as_str())
        .collect::<Vec<_>>()
        .join(",");

    let (three, out) = loadtest_json(&args(&targets));
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_clean(&three);
    // 6 sessions + 3 batch clients over 3 replicas: 3 clients each.
    let per_target = three["targets"].as_object().unwrap();
    assert_eq!(per_target.len(), 3);
    for s in &servers {
        let b = &per_target[&s.addr];
        assert_eq!(num(b, "clients"), 3.0, "{}: {b}", s.addr);
        assert_eq!(num(b, "steps"), 24.0, "{}: {b}", s.addr);
        assert_eq!(num(b, "mismatches"), 0.0);
    }

    let (one, out) = loadtest_json(&args(&servers[0].addr));
    assert!(out.status.success());
    assert_clean(&one);

    let (t1, t3) = (
        num(&one, "throughput_per_s"),
        num(&three, "throughput_per_s"),
    );
    println!(
        "throughput: 1 replica {t1:.1} steps/s (p50 {:.2} ms), 3 replicas {t3:.1} steps/s \
         (p50 {:.2} ms), ratio {:.2} on {} cores",
        num(&one, "p50_s") * 1e3,
        num(&three, "p50_s") * 1e3,
        t3 / t1,
        std::thread::available_parallelism().map_or(0, |n| n.get())
    );
}
