//! Cooperative cancellation of long solves.
//!
//! A caller that may give up on a solve (the service, when a request's
//! deadline passes or its client goes away) runs it inside
//! [`CancelToken::scope`] and cancels the token from elsewhere. The solvers
//! look at the token of their thread between iterations (Newton and CG
//! steps, alternations, load iterations, time steps, contact table nodes):
//! once it is cancelled they stop iterating, and the entry points return
//! [`ContactError::Cancelled`] instead of a half-converged answer. A thread
//! without a token is never cancelled, so library users and the CLI see no
//! difference.
//!
//! The token is per thread (a thread-local), so that no solver signature
//! carries it; code that spreads a solve over threads of its own passes
//! [`CancelToken::current`] on (see `wheelrail::table`). Checking costs a
//! thread-local read and a relaxed atomic load, nanoseconds next to an
//! iteration's FFT products.

use std::cell::RefCell;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use crate::core::error::ContactError;

/// A flag shared between the thread that solves and whoever may cancel it
/// (cheap to clone).
#[derive(Debug, Clone, Default)]
pub struct CancelToken(Arc<AtomicBool>);

thread_local! {
    static CURRENT: RefCell<Option<CancelToken>> = const { RefCell::new(None) };
}

impl CancelToken {
    /// A token that is not cancelled.
    pub fn new() -> Self {
        Self::default()
    }

    /// Asks every solve running under this token to stop (idempotent).
    pub fn cancel(&self) {
        self.0.store(true, Ordering::Relaxed);
    }

    /// Whether [`CancelToken::cancel`] was called.
    pub fn is_cancelled(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }

    /// Runs `f` on this thread with this token installed; the previous
    /// token (if any) is back afterwards, also when `f` panics.
    pub fn scope<T>(&self, f: impl FnOnce() -> T) -> T {
        struct Restore(Option<CancelToken>);
        impl Drop for Restore {
            fn drop(&mut self) {
                let previous = self.0.take();
                CURRENT.with(|c| *c.borrow_mut() = previous);
            }
        }
        let previous = CURRENT.with(|c| c.borrow_mut().replace(self.clone()));
        let _restore = Restore(previous);
        f()
    }

    /// The token installed on this thread, if any: for handing on to
    /// threads that a solve starts.
    pub fn current() -> Option<CancelToken> {
        CURRENT.with(|c| c.borrow().clone())
    }
}

/// Whether the solve on this thread has been cancelled (false without a
/// token). Loops test it to stop early.
pub fn requested() -> bool {
    CURRENT.with(|c| c.borrow().as_ref().is_some_and(CancelToken::is_cancelled))
}

/// `Err(ContactError::Cancelled)` when the solve on this thread has been
/// cancelled: entry points call it after loops that [`requested`] may have
/// cut short, so that a partial answer never passes for a solution.
pub fn check() -> Result<(), ContactError> {
    if requested() {
        Err(ContactError::Cancelled)
    } else {
        Ok(())
    }
}

/// Runs `a` on this thread and `b` on a scoped thread of its own at the
/// same time, `b` under this thread's token (so a cancelled solve stops
/// both); returns both results. A panic in `b` resumes on this thread
/// once `a` is done.
pub fn join<A, B>(a: impl FnOnce() -> A, b: impl FnOnce() -> B + Send) -> (A, B)
where
    B: Send,
{
    let token = CancelToken::current();
    std::thread::scope(|scope| {
        let other = scope.spawn(move || match token {
            Some(t) => t.scope(b),
            None => b(),
        });
        let ra = a();
        let rb = other
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
        (ra, rb)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn join_runs_both_and_hands_the_token_on() {
        let token = CancelToken::new();
        token.cancel();
        let (a, b) = token.scope(|| join(|| (requested(), 1), || (requested(), 2)));
        assert_eq!((a, b), ((true, 1), (true, 2)));
        let (a, b) = join(requested, requested);
        assert!(!a && !b);
    }

    #[test]
    fn a_token_is_seen_only_inside_its_scope_and_nests() {
        assert!(!requested());
        assert!(check().is_ok());
        let outer = CancelToken::new();
        let inner = CancelToken::new();
        outer.scope(|| {
            assert!(!requested());
            inner.scope(|| {
                inner.cancel();
                assert!(requested());
                assert_eq!(check(), Err(ContactError::Cancelled));
            });
            // The outer token is back, and it was not cancelled.
            assert!(!requested());
            outer.cancel();
            assert!(requested());
        });
        assert!(!requested());
        assert!(CancelToken::current().is_none());
    }

    #[test]
    fn a_panic_inside_a_scope_restores_the_previous_token() {
        let token = CancelToken::new();
        token.cancel();
        let r = std::panic::catch_unwind(|| token.scope(|| panic!("solver fault")));
        assert!(r.is_err());
        assert!(!requested());
    }
}
