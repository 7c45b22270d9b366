//! The stopping rule of the normal/tangential alternation (Panagiotopoulos
//! process), shared by the planar loop of dissimilar bodies
//! ([`crate::core::solve`]) and the conformal one
//! ([`crate::conformal::frictional`]).
//!
//! Each alternation's change is the L1 norm of the traction change
//! (p_n, p_x, p_y) relative to that of the pressures. The alternation is a
//! fixed-point iteration that converges linearly: with q the ratio of
//! successive changes, the distance of the last iterate to the coupled
//! solution is at most change · q/(1 − q) (the a-posteriori bound of a
//! contraction). The loop ends when that estimate, or the change itself
//! when smaller, is below the coupling tolerance. The estimate takes the
//! larger of the last two ratios, and is used only while they are below
//! 1/2; before two changes are known, and when the alternation does not
//! contract, the change alone decides.

/// The alternation's changes so far.
#[derive(Debug, Clone, Copy)]
pub struct CouplingMonitor {
    change: f64,
    /// The last two ratios of successive changes (newest first); 1 until
    /// known.
    ratios: [f64; 2],
    count: usize,
}

impl Default for CouplingMonitor {
    fn default() -> Self {
        Self {
            change: 1.0,
            ratios: [1.0; 2],
            count: 0,
        }
    }
}

/// The largest ratio of successive changes for which the estimate is used.
const MAX_RATIO: f64 = 0.5;

impl CouplingMonitor {
    /// Records one alternation: the new tractions against the last ones,
    /// each `[p_n, p_x, p_y]`. Returns the change.
    pub fn record(&mut self, new: [&[f64]; 3], last: [&[f64]; 3]) -> f64 {
        let (mut num, mut den) = (0.0, 0.0);
        for i in 0..new[0].len() {
            num += (new[0][i] - last[0][i]).abs()
                + (new[1][i] - last[1][i]).abs()
                + (new[2][i] - last[2][i]).abs();
            den += new[0][i].abs();
        }
        let change = if den > 0.0 { num / den } else { 0.0 };
        if self.count > 0 && self.change > 0.0 {
            self.ratios = [(change / self.change).min(1.0), self.ratios[0]];
        }
        self.change = change;
        self.count += 1;
        change
    }

    /// The last change (1 before any).
    pub fn change(&self) -> f64 {
        self.change
    }

    /// The last ratio of successive changes (1 until two are known).
    pub fn contraction(&self) -> f64 {
        self.ratios[0]
    }

    /// The estimated distance of the last iterate to the coupled solution,
    /// relative as the change (see the module's documentation).
    pub fn estimated_error(&self) -> f64 {
        let q = self.ratios[0].max(self.ratios[1]);
        if self.count >= 3 && q < MAX_RATIO {
            self.change.min(self.change * q / (1.0 - q))
        } else {
            self.change
        }
    }

    /// Whether the estimate is below `tolerance`.
    pub fn converged(&self, tolerance: f64) -> bool {
        self.count > 0 && self.estimated_error() < tolerance
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A geometric sequence of changes: the estimate is the remaining sum.
    #[test]
    fn the_estimate_of_a_contraction_is_the_remaining_sum() {
        let mut m = CouplingMonitor::default();
        let last = [vec![1.0; 4], vec![0.0; 4], vec![0.0; 4]];
        let mut change = 0.5;
        for _ in 0..4 {
            let new = [vec![1.0; 4], vec![change; 4], vec![0.0; 4]];
            let got = m.record([&new[0], &new[1], &new[2]], [&last[0], &last[1], &last[2]]);
            assert!((got - change).abs() < 1e-15);
            change *= 0.1;
        }
        // Changes 0.5, 0.05, 0.005, 0.0005: ratio 0.1, the remaining sum
        // 0.0005 (0.1 + 0.01 + ...) = 0.0005 / 9.
        assert!((m.estimated_error() - 0.0005 / 9.0).abs() < 1e-12);
        assert!(m.converged(1e-4));
        assert!(!m.converged(5e-5));
    }

    /// Without contraction (or before it is known) the change decides.
    #[test]
    fn without_contraction_the_change_decides() {
        let mut m = CouplingMonitor::default();
        assert!(!m.converged(1.0));
        let zero = vec![0.0; 2];
        let one = vec![1.0; 2];
        let half = vec![0.6; 2];
        m.record([&one, &half, &zero], [&one, &zero, &zero]);
        assert!((m.estimated_error() - 0.6).abs() < 1e-15);
        m.record([&one, &half, &zero], [&one, &zero, &zero]);
        m.record([&one, &half, &zero], [&one, &zero, &zero]);
        // Ratio 1: no estimate below the change.
        assert!((m.estimated_error() - 0.6).abs() < 1e-15);
        assert_eq!(m.contraction(), 1.0);
    }
}
