//! A bounded soak: 64 concurrent co-simulation sessions of mixed kinds and
//! two batch clients against one `railcontact serve` for about a minute
//! (`railcontact loadtest`), every answer checked bit for bit against a
//! replay of each session alone; zero errors, zero mismatches, the server's peak
//! memory bounded.

use crate::support;

use support::{assert_clean, check, loadtest_json, num, Server};

/// Hertz+FASTSIM, exact and conformal (cect) wheelsets, exact, FASTSIM and
/// Hertz patches.
const MIX: &str = "wheelrail:hertz_fastsim=8,wheelrail:exact=2,wheelrail:cect=1,\
                   patch:exact32=2,patch:fastsim=2,patch:hertz=1";

/// How long the sessions run [s].
const SOAK_S: &str = "45";

/// The server's peak resident memory must stay below this \[bytes\].
const PEAK_RSS_LIMIT: u64 = 2 << 30;

#[test]
fn sixty_four_mixed_sessions_for_a_minute_stay_clean_and_bounded() {
    let server = Server::start();
    let (v, out) = loadtest_json(&[
        "--target",
        &server.addr,
        "--sessions",
        "64",
        "--steps",
        "1000000",
        "--seconds",
        SOAK_S,
        "--batch-clients",
        "2",
        "--batch-items",
        "8",
        "--mix",
        MIX,
    ]);
    check("loadtest", &out);
    assert_clean(&v);
    let rss = server.peak_rss_bytes();
    eprintln!(
        "soak: {} steps in {} s, {:.0} steps/s, p50 {:.2} ms, p99 {:.2} ms, errors {}, mismatches {}, \
         server peak RSS {}",
        num(&v, "steps"),
        SOAK_S,
        num(&v, "throughput_per_s"),
        num(&v, "p50_s") * 1e3,
        num(&v, "p99_s") * 1e3,
        num(&v, "errors"),
        num(&v, "mismatches"),
        rss.map_or("unknown".into(), |b| format!("{:.0} MiB", b as f64 / 1048576.0)),
    );
    if let Some(rss) = rss {
        assert!(rss < PEAK_RSS_LIMIT, "peak RSS {rss} bytes");
    }
    assert!(
        server.log().lines().all(|l| !l.contains("panicked")),
        "{}",
        server.log()
    );
}
