//! The memory co-simulation sessions hold between their steps, against
//! the server's limits: per session `max_session_bytes`, all sessions
//! together `max_sessions_total_bytes`.
//!
//! A session holds two kinds of memory: its live working state (the exact
//! solvers' buffers, FFT workspaces and Newton scratch, warm-start
//! pressures and tractions, the copy a refused step is undone from, the
//! gap and numerical influence coefficients sent with the case: what
//! the solver crate's `HeapBytes` counts, the kernels excepted, which the
//! kernel cache holds under its own cap) and its marks. Both are counted
//! here, in one count per server. A session's live bytes are known only
//! once a step has run (a wheel/rail patch grid follows the contact, the
//! Newton scratch is allocated by the first frictional solve), so each
//! session's share is settled after every step: a step that would leave the
//! session or the server beyond its limit is refused and undone, and the
//! session gives back the buffers the step allocated. While a step runs,
//! its solve may hold more (bounded by `max_grid_elements` and the solve
//! threads); between steps, the limits hold.
//!
//! `SessionBudget::reserve` (behind [`SessionMemory::open`] and
//! [`SessionMemory::reserve`]) is the one place that decides.

use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::Arc;

/// The memory the sessions of a server may hold \[bytes\]: per session
/// and all sessions together, their live working state and their marks.
/// Clones share the server's counts.
#[derive(Debug, Clone)]
pub struct SessionBudget {
    session_max_bytes: usize,
    total_max_bytes: usize,
    /// Live and mark bytes of all open sessions.
    total_bytes: Arc<AtomicUsize>,
    /// The part of `total_bytes` that marks hold.
    mark_bytes: Arc<AtomicUsize>,
    /// Session opens and steps refused by a limit.
    refused: Arc<AtomicU64>,
    /// Marked steps among them that would have fitted without their mark.
    refused_marks: Arc<AtomicU64>,
}

/// Which limit a session would go beyond.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Beyond {
    /// The config key: `max_session_bytes` or `max_sessions_total_bytes`.
    pub key: &'static str,
    /// Its value \[bytes\].
    pub max_bytes: usize,
    /// "this session's" or "all sessions'", for messages.
    pub whose: &'static str,
}

impl SessionBudget {
    /// At most `session_max_bytes` per session and `total_max_bytes` in
    /// all sessions together.
    pub fn new(session_max_bytes: usize, total_max_bytes: usize) -> Self {
        Self {
            session_max_bytes,
            total_max_bytes,
            total_bytes: Arc::default(),
            mark_bytes: Arc::default(),
            refused: Arc::default(),
            refused_marks: Arc::default(),
        }
    }

    /// Bytes held by all open sessions now, live state and marks.
    pub fn total_bytes(&self) -> usize {
        self.total_bytes.load(Ordering::Relaxed)
    }

    /// Bytes held by the marks of all open sessions now.
    pub fn mark_bytes(&self) -> usize {
        self.mark_bytes.load(Ordering::Relaxed)
    }

    /// Session opens and steps refused by a limit so far.
    pub fn refused(&self) -> u64 {
        self.refused.load(Ordering::Relaxed)
    }

    /// Marked steps refused so far that would have fitted without their
    /// mark.
    pub fn refused_marks(&self) -> u64 {
        self.refused_marks.load(Ordering::Relaxed)
    }

    /// Moves `share` to `live` and `marks` bytes if the session and the
    /// server stay within their limits (or the share does not grow); else
    /// nothing changes and the limit is named.
    fn reserve(&self, share: &mut Share, live: usize, marks: usize) -> Result<(), Beyond> {
        let (old, new) = (share.live + share.marks, live + marks);
        if new > old {
            if new > self.session_max_bytes {
                return Err(self.refuse(Beyond {
                    key: "max_session_bytes",
                    max_bytes: self.session_max_bytes,
                    whose: "this session's",
                }));
            }
            let max = self.total_max_bytes;
            let grown = self
                .total_bytes
                .fetch_update(Ordering::Relaxed, Ordering::Relaxed, |t| {
                    (t - old + new <= max).then_some(t - old + new)
                });
            if grown.is_err() {
                return Err(self.refuse(Beyond {
                    key: "max_sessions_total_bytes",
                    max_bytes: max,
                    whose: "all sessions'",
                }));
            }
        } else {
            shift(&self.total_bytes, old, new);
        }
        shift(&self.mark_bytes, share.marks, marks);
        (share.live, share.marks) = (live, marks);
        Ok(())
    }

    fn refuse(&self, beyond: Beyond) -> Beyond {
        self.refused.fetch_add(1, Ordering::Relaxed);
        beyond
    }
}

/// Moves `counter` by `to - from` (either sign).
fn shift(counter: &AtomicUsize, from: usize, to: usize) {
    if to >= from {
        counter.fetch_add(to - from, Ordering::Relaxed);
    } else {
        counter.fetch_sub(from - to, Ordering::Relaxed);
    }
}

/// What one session holds \[bytes\].
#[derive(Debug, Default)]
struct Share {
    live: usize,
    marks: usize,
}

/// One session's share of the [`SessionBudget`]: its live bytes and its
/// marks' bytes, both in the server's count until it is dropped (the
/// session closed, however: by its client, idle, gone, or at shutdown).
#[derive(Debug)]
pub struct SessionMemory {
    budget: SessionBudget,
    share: Share,
}

impl Drop for SessionMemory {
    fn drop(&mut self) {
        let b = &self.budget;
        b.total_bytes
            .fetch_sub(self.share.live + self.share.marks, Ordering::Relaxed);
        b.mark_bytes.fetch_sub(self.share.marks, Ordering::Relaxed);
    }
}

impl SessionMemory {
    /// A new session holding `live` bytes, or the limit it would go
    /// beyond.
    pub fn open(budget: SessionBudget, live: usize) -> Result<Self, Beyond> {
        let mut m = Self {
            budget,
            share: Share::default(),
        };
        m.budget.reserve(&mut m.share, live, 0)?;
        Ok(m)
    }

    /// Live bytes counted for this session.
    pub fn live_bytes(&self) -> usize {
        self.share.live
    }

    /// Bytes counted for this session's marks.
    pub fn mark_bytes(&self) -> usize {
        self.share.marks
    }

    /// This session would hold `live` bytes and `marks` bytes of marks
    /// after a step: counted if within the limits, else the limit it would
    /// go beyond and nothing changed. `mark_bytes` of the marks are the
    /// step's own (0 without a mark): a refusal that they make counts as a
    /// refused mark.
    pub fn reserve(&mut self, live: usize, marks: usize, mark_bytes: usize) -> Result<(), Beyond> {
        let Self { budget, share } = self;
        let r = budget.reserve(share, live, marks);
        if let Err(b) = r {
            let without = live + marks - mark_bytes;
            let fits_session = without <= budget.session_max_bytes;
            let fits_total =
                budget.total_bytes() + without <= budget.total_max_bytes + share.live + share.marks;
            if mark_bytes > 0 && fits_session && fits_total {
                budget.refused_marks.fetch_add(1, Ordering::Relaxed);
            }
            return Err(b);
        }
        Ok(())
    }

    /// Marks of `bytes` were dropped (a rollback).
    pub fn drop_marks(&mut self, bytes: usize) {
        let b = &self.budget;
        b.total_bytes.fetch_sub(bytes, Ordering::Relaxed);
        b.mark_bytes.fetch_sub(bytes, Ordering::Relaxed);
        self.share.marks -= bytes;
    }

    /// Counts `live` bytes for the session whatever the limits: what it
    /// holds after a refused step gave back its buffers (no more than
    /// before the step).
    pub fn settle(&mut self, live: usize) {
        shift(&self.budget.total_bytes, self.share.live, live);
        self.share.live = live;
    }
}

/// Hands the memory that ended sessions and streams freed back to the
/// operating system. glibc's allocator keeps freed memory of its arenas
/// for reuse, so a server whose sessions held hundreds of MB kept that
/// resident after they closed; `malloc_trim` returns the free pages. Runs
/// on a blocking thread (it takes milliseconds on a large heap), at most
/// one at a time: calls while one is pending are folded into it. Other
/// platforms and allocators: nothing to do.
///
/// [`ReturnMemoryOnDrop`] calls it when a session, stream or batch ends.
pub fn return_freed_memory() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    {
        use std::sync::atomic::AtomicBool;
        static PENDING: AtomicBool = AtomicBool::new(false);
        if PENDING.swap(true, Ordering::AcqRel) {
            return;
        }
        tokio::task::spawn_blocking(|| {
            PENDING.store(false, Ordering::Release);
            // SAFETY: malloc_trim only walks and releases the allocator's
            // own free lists; it takes no pointer of ours.
            unsafe { libc::malloc_trim(0) };
        });
    }
}

/// Calls [`return_freed_memory`] when dropped: held first by the task of
/// a session, stream or batch, so that it is dropped after the task's
/// state, however the task ends.
pub struct ReturnMemoryOnDrop;

impl Drop for ReturnMemoryOnDrop {
    fn drop(&mut self) {
        return_freed_memory();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sessions_share_the_server_limit_and_return_their_bytes_when_dropped() {
        let budget = SessionBudget::new(100, 150);
        let mut a = SessionMemory::open(budget.clone(), 60).unwrap();
        let e = SessionMemory::open(budget.clone(), 101).unwrap_err();
        assert_eq!(e.key, "max_session_bytes");
        let mut b = SessionMemory::open(budget.clone(), 50).unwrap();
        assert_eq!(budget.total_bytes(), 110);
        // 60 live and a mark of 60: beyond the session's 100, and a
        // refused mark (60 alone fits).
        assert_eq!(a.reserve(60, 60, 60).unwrap_err().key, "max_session_bytes");
        // 110 + 40 fits the server's 150; 10 more does not.
        a.reserve(60, 40, 40).unwrap();
        assert_eq!((budget.total_bytes(), budget.mark_bytes()), (150, 40));
        let e = b.reserve(60, 0, 0).unwrap_err();
        assert_eq!((e.key, e.max_bytes), ("max_sessions_total_bytes", 150));
        assert_eq!((budget.refused(), budget.refused_marks()), (3, 1));
        // Shrinking is always allowed; settling counts what is held.
        b.reserve(20, 0, 0).unwrap();
        b.settle(10);
        assert_eq!(budget.total_bytes(), 110);
        drop(a);
        assert_eq!((budget.total_bytes(), budget.mark_bytes()), (10, 0));
        drop(b);
        assert_eq!(budget.total_bytes(), 0);
    }

    /// The child process's part of
    /// [`ended_sessions_memory_goes_back_to_the_system`].
    const CHILD: &str = "RAILCONTACT_TEST_MEMORY_CHILD";

    fn resident_kb() -> u64 {
        let status = std::fs::read_to_string("/proc/self/status").unwrap();
        status
            .lines()
            .find_map(|l| l.strip_prefix("VmRSS:"))
            .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
            .unwrap()
    }

    /// 200 MB in 2 kB blocks on a solve thread (as a session's solvers and
    /// marks allocate), one block in 64 kept (so the allocator cannot give
    /// the memory back by shrinking its heap from the top), the rest
    /// freed: resident until [`return_freed_memory`], then returned. Run
    /// in a child process of this test executable, alone, so that no
    /// other test's memory is counted.
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    #[test]
    fn ended_sessions_memory_goes_back_to_the_system() {
        if std::env::var(CHILD).is_err() {
            let out = std::process::Command::new(std::env::current_exe().unwrap())
                .args([
                    "--exact",
                    "service::memory::tests::ended_sessions_memory_goes_back_to_the_system",
                    "--nocapture",
                ])
                .env(CHILD, "1")
                .output()
                .unwrap();
            let text = format!(
                "{}\n{}",
                String::from_utf8_lossy(&out.stdout),
                String::from_utf8_lossy(&out.stderr)
            );
            assert!(out.status.success() && text.contains("1 passed"), "{text}");
            return;
        }
        let rt = tokio::runtime::Builder::new_multi_thread()
            .worker_threads(1)
            .enable_time()
            .build()
            .unwrap();
        let kept = rt.block_on(async {
            tokio::task::spawn_blocking(|| {
                let blocks: Vec<Vec<u8>> = (0..100_000).map(|i| vec![i as u8; 2048]).collect();
                blocks.into_iter().step_by(64).collect::<Vec<_>>()
            })
            .await
            .unwrap()
        });
        let held = resident_kb();
        rt.block_on(async {
            return_freed_memory();
            // The trim runs on a blocking thread; let it finish.
            tokio::time::sleep(std::time::Duration::from_millis(500)).await;
        });
        let after = resident_kb();
        println!("resident {held} kB with the freed blocks, {after} kB after the trim");
        assert!(
            held > 150_000,
            "{held} kB: the freed blocks should still be resident"
        );
        assert!(after + 100_000 < held, "{held} kB -> {after} kB");
        drop(kept);
    }
}
