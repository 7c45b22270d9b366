//! The library's log: one line per error (and, at higher `if_idebug`
//! levels, per call) on standard error, each starting with
//! `railcontact-cntc:` and naming the call, `ire` and `icp`.
//!
//! `cntc_setglobalflags(CNTC_if_idebug, level)`: below 0 nothing, 0 errors
//! only, 1 (the default, as CONTACT's) errors and warnings, 2 and more a
//! line per calculation as well.

use std::io::Write;
use std::sync::atomic::{AtomicI32, Ordering};

static LEVEL: AtomicI32 = AtomicI32::new(1);

/// Sets the print level (`CNTC_if_idebug`).
pub fn set_level(level: i32) {
    LEVEL.store(level, Ordering::Relaxed);
}

/// The print level.
pub fn level() -> i32 {
    LEVEL.load(Ordering::Relaxed)
}

/// Writes `message` when the level is at least `min_level` (0: an error,
/// 1: a warning, 2: information).
pub fn write(min_level: i32, message: &str) {
    if level() >= min_level {
        // One write per line: lines of different threads do not mix.
        let line = format!("railcontact-cntc: {message}\n");
        let _ = std::io::stderr().lock().write_all(line.as_bytes());
    }
}

/// An error of `call` on (`ire`, `icp`).
pub fn error(call: &str, ire: Option<i32>, icp: Option<i32>, message: &str) {
    write(0, &format!("ERROR in {}: {message}", site(call, ire, icp)));
}

/// A warning of `call` on (`ire`, `icp`).
pub fn warning(call: &str, ire: Option<i32>, icp: Option<i32>, message: &str) {
    write(
        1,
        &format!("warning in {}: {message}", site(call, ire, icp)),
    );
}

fn site(call: &str, ire: Option<i32>, icp: Option<i32>) -> String {
    match (ire, icp) {
        (Some(ire), Some(icp)) => format!("{call}(ire={ire}, icp={icp})"),
        (Some(ire), None) => format!("{call}(ire={ire})"),
        _ => call.to_string(),
    }
}
