//! The root of a decreasing function of one variable, f(x) = 0, when each
//! evaluation is a contact solve: the secant method safeguarded by a
//! bracket. Used for a prescribed tangential force of a patch
//! ([`crate::core::force`]) and a prescribed longitudinal force of a
//! wheelset ([`crate::wheelrail::contact`]).
//!
//! * Until the root is bracketed, a step moves away from the known bound by
//!   at most 4 times the previous step (the first step: the given slope's
//!   estimate), so that a saturating f (flat far from the root) cannot send
//!   x far out.
//! * Once bracketed, a secant step that leaves the bracket is replaced by
//!   bisection.
//! * It stops when |f| <= `tolerance`, when the bracket is narrower than
//!   1e-14 of x, or at `max_iterations` (then [`RootEnd::IterationLimit`]:
//!   the caller must say so); a step that would leave `allowed` ends it
//!   with [`RootError::OutOfRange`].

use crate::core::error::Range;

/// How the iteration ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RootEnd {
    /// |f| <= tolerance.
    Converged,
    /// The bracket shrank below 1e-14 of x with |f| above the tolerance
    /// (f jumps there, or the evaluations are no more exact than that).
    BracketCollapsed,
    /// `max_iterations` steps without either.
    IterationLimit,
}

/// The last iterate.
#[derive(Debug, Clone)]
pub struct Root<S> {
    /// x of the last evaluation.
    pub x: f64,
    /// f(x).
    pub residual: f64,
    /// What the evaluation at x returned besides f.
    pub state: S,
    /// Steps taken.
    pub iterations: usize,
    /// Evaluations, the first included.
    pub evaluations: usize,
    /// Why it stopped.
    pub end: RootEnd,
}

/// Why there is no root.
#[derive(Debug)]
pub enum RootError<E> {
    /// An evaluation failed.
    Eval(E),
    /// The next step would leave the allowed range of x (`next` is that
    /// step): f does not reach 0 there.
    OutOfRange {
        /// The step that would have left the range.
        next: f64,
    },
}

/// Settings of [`decreasing_root`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RootSettings {
    /// Absolute tolerance on f.
    pub tolerance: f64,
    /// Step limit.
    pub max_iterations: usize,
    /// Estimate of df/dx at the start (< 0), for the first step.
    pub slope: f64,
}

/// The root of the decreasing f from x0, where f(x0) = `r0` with `state0`;
/// `eval(x)` returns f(x) and its state. See the module docs.
pub fn decreasing_root<S, E>(
    x0: f64,
    r0: f64,
    state0: S,
    settings: RootSettings,
    allowed: Range,
    mut eval: impl FnMut(f64) -> Result<(f64, S), E>,
) -> Result<Root<S>, RootError<E>> {
    let (mut x, mut r, mut state) = (x0, r0, state0);
    let slope0 = settings.slope;
    // f decreases: r > 0 means x is below the root.
    let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
    let mut prev: Option<(f64, f64)> = None;
    let mut iterations = 0;
    let mut evaluations = 1;
    let end = loop {
        if r.abs() <= settings.tolerance {
            break RootEnd::Converged;
        }
        if r > 0.0 {
            lo = lo.max(x);
        } else {
            hi = hi.min(x);
        }
        if (hi - lo).abs() <= 1e-14 * x.abs().max(f64::MIN_POSITIVE) {
            break RootEnd::BracketCollapsed;
        }
        if iterations == settings.max_iterations {
            break RootEnd::IterationLimit;
        }
        iterations += 1;
        let slope = match prev {
            Some((xp, rp)) if xp != x => (r - rp) / (x - xp),
            _ => slope0,
        };
        let mut next = if slope < 0.0 && slope.is_finite() {
            x - r / slope
        } else {
            f64::NAN
        };
        if lo.is_finite() && hi.is_finite() {
            if !(next > lo.min(hi) && next < lo.max(hi)) {
                next = 0.5 * (lo + hi);
            }
        } else {
            // Not bracketed yet: move away from the known bound, at most 4
            // times the last step (the first: the slope's estimate).
            let step_max = match prev {
                Some((xp, _)) => 4.0 * (x - xp).abs(),
                None => (r / slope0).abs(),
            };
            let dir = if r > 0.0 { 1.0 } else { -1.0 };
            if !(next.is_finite() && (next - x) * dir > 0.0) || (next - x).abs() > step_max {
                next = x + dir * step_max;
            }
        }
        if !allowed.contains(next) {
            return Err(RootError::OutOfRange { next });
        }
        prev = Some((x, r));
        x = next;
        (r, state) = eval(x).map_err(RootError::Eval)?;
        evaluations += 1;
    };
    Ok(Root {
        x,
        residual: r,
        state,
        iterations,
        evaluations,
        end,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const ALL: Range = Range::symmetric(1e6, "");

    fn settings(slope: f64) -> RootSettings {
        RootSettings {
            tolerance: 1e-12,
            max_iterations: 60,
            slope,
        }
    }

    /// f(x) = a - tanh(x): decreasing, saturating at +-1 like a creep force.
    fn tanh_root(a: f64, slope: f64) -> Result<Root<()>, RootError<()>> {
        decreasing_root(0.0, a, (), settings(slope), ALL, |x| Ok((a - x.tanh(), ())))
    }

    #[test]
    fn finds_the_root_of_a_saturating_function() {
        for a in [0.1, 0.5, 0.9, 0.999, -0.95] {
            let root = tanh_root(a, -1.0).unwrap();
            assert_eq!(root.end, RootEnd::Converged, "{a}");
            // atanh(a), the exact root.
            assert!((root.x - a.atanh()).abs() < 1e-9, "{a}: {}", root.x);
            assert!(root.evaluations < 40, "{a}: {}", root.evaluations);
        }
    }

    #[test]
    fn a_wrong_first_slope_is_recovered_by_the_bracket() {
        // Slope estimates 100 times too steep and too flat.
        for slope in [-100.0, -0.01] {
            let root = tanh_root(0.8, slope).unwrap();
            assert_eq!(root.end, RootEnd::Converged, "{slope}");
            assert!((root.x - 0.8f64.atanh()).abs() < 1e-9);
        }
    }

    #[test]
    fn an_unreachable_value_leaves_the_allowed_range() {
        let allowed = Range::symmetric(1.0, "");
        let e = decreasing_root(0.0, 0.99, (), settings(-1.0), allowed, |x| {
            Ok::<_, ()>((0.99 - x.tanh(), ()))
        });
        // atanh(0.99) = 2.65 lies outside [-1, 1].
        assert!(matches!(e, Err(RootError::OutOfRange { .. })));
    }

    #[test]
    fn the_iteration_limit_is_reported() {
        let s = RootSettings {
            max_iterations: 2,
            ..settings(-1.0)
        };
        let root =
            decreasing_root(0.0, 0.9, (), s, ALL, |x| Ok::<_, ()>((0.9 - x.tanh(), ()))).unwrap();
        assert_eq!(root.end, RootEnd::IterationLimit);
        assert_eq!(root.iterations, 2);
        assert_eq!(root.evaluations, 3);
    }

    #[test]
    fn a_jump_across_zero_collapses_the_bracket() {
        // f jumps from +1 to -1 at x = 0.3: no x has |f| below the tolerance.
        let root = decreasing_root(0.0, 1.0, (), settings(-1.0), ALL, |x| {
            Ok::<_, ()>((if x < 0.3 { 1.0 } else { -1.0 }, ()))
        })
        .unwrap();
        assert_eq!(root.end, RootEnd::BracketCollapsed);
        assert!((root.x - 0.3).abs() < 1e-12);
    }
}
