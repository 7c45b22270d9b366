//! An interfacial (third-body) layer between the two bodies, elastic or
//! elasto-plastic with linear hardening or softening: CONTACT's material
//! model M = 4 (Vollebregt's user guide, §"Interfacial layer of
//! contaminants" and example `plastic_3bl`; the rheology after Hou et al.,
//! Wear 1997, as the user guide's figure "hou1997"; the elasto-plastic
//! tangential problem as in Vollebregt, "A new solver for the
//! elastoplastic tangential contact problem").
//!
//! # The model
//!
//! A layer of thickness h and shear modulus G3 lies between the bodies
//! (metal oxides, friction modifiers, sand, clay). Under the tangential
//! traction p (on body 1) it shears elastically,
//!
//! ```text
//! u_el = (h / G3) p = F p,
//! ```
//!
//! and plastically where |p| reaches its yield limit tau_c, which hardens
//! (k_tau > 0) or softens (k_tau < 0) linearly with the plastic
//! deformation u*_pl accumulated by the material passing through:
//!
//! ```text
//! tau_c = tau_c0 + k_tau u*_pl,   u*_pl = ∫ |du_pl/dt| dt,   du_pl ∥ p,
//! ```
//!
//! with tau_c0 the yield limit of fresh material ([`InterfacialLayer`]:
//! `thickness_m` h, `shear_modulus_pa` G3, `yield_limit_pa` tau_c0 (0: no
//! plasticity), `hardening_pa_per_m` k_tau). Softening stops at 0.1
//! tau_c0 ([`MIN_YIELD_FRACTION`], as CONTACT). Both u_el and u_pl add to
//! the displacement difference of body 1 relative to body 2, so the slip
//! at the interface (Coulomb's law, bound g = mu p_n) is, in a transient
//! step (Kalker 1990 §5.2),
//!
//! ```text
//! S = W + (A + F)(p - p') + Δu_pl,
//! ```
//!
//! W the rigid shift, A the half-spaces' influence coefficients, p' the
//! previous step's tractions, Δu_pl the step's plastic increment. h = 0
//! with tau_c0 > 0 is plasticity near the surface of the softer body
//! without a layer (the user guide: "using the tangential plasticity
//! feature of CONTACT without using a third body layer").
//!
//! # How the solver takes it
//!
//! *Elastic part.* F is local: it adds to the tangential self-influence
//! coefficients, A_xx(I, I) and A_yy(I, I), and to nothing else (the
//! normal problem does not see the layer). The kernels carry it
//! ([`crate::core::influence::HalfSpaceInfluence::with_layer_flexibility`],
//! cached per flexibility), so every product, the steady operator
//! A(I - S)/dx (where F contributes F (p(x) - p(x + dx))/dx), the
//! diagonals and preconditioners of the Newton solvers and the periodic
//! inverse include it exactly, as CONTACT adds its `flx_3bl` to the
//! coefficients of element I. h = 0 gives the plain problem's kernels: the
//! same bits.
//!
//! *Plastic part.* Write sigma = W + (A + F)(p - p') = S - Δu_pl, the
//! generalised slip: what the plain problem's solvers compute as "slip"
//! with the layer's kernels. Coulomb's law makes S antiparallel to p, the
//! flow rule makes Δu_pl parallel to p, so sigma = -lambda p/|p| with
//! lambda = |S| + |Δu_pl| >= 0, and per element (tau' the yield limit of
//! the material before the step, m = mu p_n):
//!
//! * lambda = 0: |p| <= min(m, tau') (adhesion, no flow);
//! * lambda > 0: |p| = g(lambda), where
//!   - tau' >= m: g = m, Coulomb slip, Δu_pl = 0;
//!   - tau' < m, k_tau = 0: g = tau', plastic flow only, |Δu_pl| = lambda;
//!   - tau' < m, k_tau > 0: g = min(m, tau' + k_tau lambda): flow hardens
//!     the layer until its yield limit reaches m, then the interface slips
//!     (|Δu_pl| = min(lambda, (m - tau')/k_tau));
//!   - tau' < m, k_tau < 0: g = max(tau' + k_tau lambda, 0.1 tau_c0), flow
//!     only.
//!
//! That is Coulomb's problem with a bound that depends on each element's
//! own generalised slip (a slip-hardening or -softening friction law):
//! the solver iterates on the bounds, each pass a Coulomb problem with
//! fixed bounds solved by the plain solvers, the next bounds from the
//! answer's lambda by one local Newton step, g = (tau' + k_tau (lambda +
//! c g_old))/(1 + k_tau c), with c the element's own compliance (its
//! self-influence coefficient with F; dx times the steady operator's in
//! steady rolling): exact for one element (plastic_3bl in one step), a
//! Jacobi step for a patch, relaxed when the change grows, until the
//! bounds of the answer's own lambda differ from those it was solved with
//! by less than ten times the tangential tolerance (root mean square,
//! relative). k_tau = 0 needs one pass: the bound is min(m, tau_c0).
//! Then each element's lambda splits into the slip S and the plastic flow
//! Δu_pl, the flow accumulates into u_pl and hardens tau_c.
//!
//! *Steady rolling* is the same with the increments of one element of
//! rolling (CONTACT's steady state with dq = dx): the material enters at
//! the leading edge fresh (tau_c0, u_pl = 0), and along each grid row
//! tau' of an element is tau_c of the element upstream; lambda = dx |s|,
//! s the slip per unit rolled distance. *Transient steps* take tau' and
//! u_pl of the material from the step before (the solver's history,
//! carried upstream with the material by a rolling step, fresh material
//! entering at the leading edge); a [`crate::core::solve::ContactSolver`]
//! keeps it between steps, in its saved states, and from a steady
//! solution it continues.
//!
//! The results: the tractions, the slip S (zero where the layer flows
//! without slip: those elements are [`crate::core::solution::ElementState::Adhesion`],
//! the interface sticking), and per element [`LayerFields`]: tau_c
//! (CONTACT's TAUCRT), u_pl (UPLSX, UPLSY) and whether it flowed without
//! slip (CONTACT's plasticity area "P"). The frictional work (power) of
//! the totals includes the plastic work p . Δu_pl.

use serde::{Deserialize, Serialize};

use crate::core::error::{show, ContactError};
use crate::core::grid::Grid;
use crate::core::memory::{heap_bytes, HeapBytes};
use crate::core::problem::{Carry, Friction};
use crate::core::solution::ElementState;
use crate::core::tangential::carry_field;

/// Softening stops at this fraction of the fresh yield limit tau_c0
/// (CONTACT's floor, `max(0.1 tau_c0, tau_c)`).
pub const MIN_YIELD_FRACTION: f64 = 0.1;

/// Largest number of passes (Coulomb solves with fixed bounds) of the
/// iteration on an elasto-plastic layer's bounds; the passes also share
/// the tangential iteration limit.
pub const MAX_LAYER_PASSES: usize = 100;

/// The layer between the bodies (see the module docs), SI.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InterfacialLayer {
    /// Thickness h \[m\], >= 0 (0: no layer, plasticity at the surface
    /// when `yield_limit_pa` > 0).
    pub thickness_m: f64,
    /// Shear modulus G3 \[Pa\], > 0. Only h/G3 enters.
    pub shear_modulus_pa: f64,
    /// Yield limit tau_c0 of fresh material \[Pa\]; 0: an elastic layer.
    #[serde(default)]
    pub yield_limit_pa: f64,
    /// Hardening k_tau \[Pa/m\]: the rise of the yield limit per unit of
    /// accumulated plastic deformation (< 0: softening, 0: perfectly
    /// plastic).
    #[serde(default)]
    pub hardening_pa_per_m: f64,
}

impl InterfacialLayer {
    /// An elastic layer of `thickness_m` \[m\] and `shear_modulus_pa`
    /// \[Pa\].
    pub fn elastic(thickness_m: f64, shear_modulus_pa: f64) -> Self {
        Self {
            thickness_m,
            shear_modulus_pa,
            yield_limit_pa: 0.0,
            hardening_pa_per_m: 0.0,
        }
    }

    /// Its tangential flexibility F = h/G3 \[m/Pa\] (0 without thickness).
    pub fn flexibility_m_per_pa(&self) -> f64 {
        if self.thickness_m == 0.0 {
            0.0
        } else {
            self.thickness_m / self.shear_modulus_pa
        }
    }

    /// Whether it deforms plastically (a yield limit > 0).
    pub fn is_plastic(&self) -> bool {
        self.yield_limit_pa > 0.0
    }

    /// The lowest yield limit softening reaches \[Pa\].
    pub fn min_yield_pa(&self) -> f64 {
        MIN_YIELD_FRACTION * self.yield_limit_pa
    }

    /// Checks the values; `key` names the layer in errors (e.g.
    /// `interfacial_layer`).
    pub fn validate(&self, key: &str) -> Result<(), ContactError> {
        let bad = |field: &str, v: f64, want: &str| {
            Err(ContactError::invalid(
                format!("{key}.{field}"),
                format!("must be {want}, got {}", show(v)),
            ))
        };
        if !(self.thickness_m.is_finite() && self.thickness_m >= 0.0) {
            return bad("thickness_m", self.thickness_m, "finite and >= 0");
        }
        if !(self.shear_modulus_pa.is_finite() && self.shear_modulus_pa > 0.0) {
            return bad("shear_modulus_pa", self.shear_modulus_pa, "finite and > 0");
        }
        let f = self.flexibility_m_per_pa();
        if !f.is_finite() {
            return bad(
                "shear_modulus_pa",
                self.shear_modulus_pa,
                "large enough that thickness / modulus is finite",
            );
        }
        if !(self.yield_limit_pa.is_finite() && self.yield_limit_pa >= 0.0) {
            return bad(
                "yield_limit_pa",
                self.yield_limit_pa,
                "finite and >= 0 (0: an elastic layer)",
            );
        }
        if !self.hardening_pa_per_m.is_finite() {
            return bad("hardening_pa_per_m", self.hardening_pa_per_m, "finite");
        }
        Ok(())
    }

    /// Checks that `friction` goes with it: a plastic layer takes
    /// Coulomb's law with one coefficient (its bound min(mu p_n, tau_c)
    /// is iterated on as a slip-velocity law's would be, and the two do
    /// not combine here). `key` names the layer.
    pub fn check_friction(&self, key: &str, friction: &Friction) -> Result<(), ContactError> {
        if !self.is_plastic() {
            return Ok(());
        }
        if friction.slip_velocity_law.is_some() {
            return Err(ContactError::invalid(
                format!("{key}.yield_limit_pa"),
                "a plastic layer (yield limit > 0) with a slip-velocity dependent friction law is \
                 not supported: give Coulomb's law, or an elastic layer (yield limit 0)",
            ));
        }
        if friction.static_coefficient != friction.kinetic_coefficient {
            return Err(ContactError::invalid(
                format!("{key}.yield_limit_pa"),
                "a plastic layer (yield limit > 0) needs equal static and kinetic friction \
                 coefficients",
            ));
        }
        Ok(())
    }

    /// The traction bound \[Pa\] of an element of Coulomb bound `coulomb`
    /// = mu p_n \[Pa\] whose material had the yield limit `tau_before`
    /// \[Pa\] and slid the generalised distance `slid_m` \[m\] (see the
    /// module docs).
    pub fn bound(&self, tau_before: f64, coulomb: f64, slid_m: f64) -> f64 {
        if tau_before >= coulomb {
            return coulomb;
        }
        let k = self.hardening_pa_per_m;
        if k > 0.0 {
            (tau_before + k * slid_m).min(coulomb)
        } else if k < 0.0 {
            (tau_before + k * slid_m).max(self.min_yield_pa().min(tau_before))
        } else {
            tau_before
        }
    }

    /// The plastic part \[m\] of the generalised slip `slid_m` \[m\] of
    /// such an element (the rest is slip at the interface).
    pub fn plastic_part(&self, tau_before: f64, coulomb: f64, slid_m: f64) -> f64 {
        if tau_before >= coulomb || slid_m <= 0.0 {
            return 0.0;
        }
        let k = self.hardening_pa_per_m;
        if k > 0.0 {
            slid_m.min((coulomb - tau_before) / k)
        } else {
            slid_m
        }
    }

    /// The yield limit \[Pa\] after a plastic deformation of `plastic_m`
    /// \[m\] of material whose yield limit was `tau_before`.
    pub fn yield_after(&self, tau_before: f64, plastic_m: f64) -> f64 {
        let k = self.hardening_pa_per_m;
        if plastic_m <= 0.0 || k == 0.0 {
            tau_before
        } else if k > 0.0 {
            tau_before + k * plastic_m
        } else {
            (tau_before + k * plastic_m).max(self.min_yield_pa().min(tau_before))
        }
    }

    /// The next bound of the iteration (see the module docs): one local
    /// Newton step on g = bound(lambda(g)), with lambda(g) = `slid_m` -
    /// `compliance` (g - `current`) the element's own response (its other
    /// neighbours held), `current` the bound the last pass used.
    fn bound_step(
        &self,
        tau_before: f64,
        coulomb: f64,
        slid_m: f64,
        current: f64,
        compliance: f64,
    ) -> f64 {
        if tau_before >= coulomb {
            return coulomb;
        }
        let k = self.hardening_pa_per_m;
        if k == 0.0 {
            return tau_before;
        }
        let denominator = 1.0 + k * compliance;
        let g = if denominator > 0.1 {
            (tau_before + k * (slid_m + compliance * current)) / denominator
        } else {
            // Softening faster than the element's own stiffness: the
            // local problem snaps back; the plain step.
            tau_before + k * slid_m
        };
        if k > 0.0 {
            g.clamp(tau_before, coulomb)
        } else {
            g.clamp(self.min_yield_pa().min(tau_before), tau_before)
        }
    }
}

/// The layer's state per element after a solve (index `iy * nx + ix`),
/// in the problem's frame: what CONTACT's library returns as TAUCRT,
/// UPLSX, UPLSY and its plasticity area.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct LayerFields {
    /// Yield limit tau_c of the material at each element \[Pa\] (tau_c0
    /// where it is fresh).
    pub yield_limit_pa: Vec<f64>,
    /// Accumulated plastic deformation u_pl, x \[m\]: part of the
    /// displacement difference of body 1 relative to body 2, parallel to
    /// the tractions that made it.
    pub plastic_x_m: Vec<f64>,
    /// See `plastic_x_m`, y \[m\].
    pub plastic_y_m: Vec<f64>,
    /// Whether the layer flowed at the element in this solve without slip
    /// at the interface (CONTACT's plasticity area; its element state is
    /// adhesion).
    pub plastic: Vec<bool>,
}

/// Coulomb's bound mu p_n r_iy of each element: the pressures, the
/// coefficient and the factors per grid row (empty: 1).
#[derive(Clone, Copy)]
pub(crate) struct CoulombBound<'a> {
    pub pn: &'a [f64],
    pub mu: f64,
    pub row_scale: &'a [f64],
    pub nx: usize,
}

impl CoulombBound<'_> {
    #[inline]
    fn at(&self, i: usize) -> f64 {
        let r = if self.row_scale.is_empty() {
            1.0
        } else {
            self.row_scale[i / self.nx]
        };
        self.pn[i] * self.mu * r
    }
}

/// A solver's elasto-plastic layer: the history (the material's yield
/// limit and plastic deformation at each element, in the rolling frame)
/// and the buffers of the iteration on the bounds. Allocated once, at
/// the first solve with a plastic layer.
#[derive(Clone)]
pub(crate) struct LayerState {
    /// tau_c - tau_c0 of the material at each element after the last
    /// solve \[Pa\] (0: fresh).
    pub hardening: Vec<f64>,
    /// Accumulated plastic deformation after the last solve \[m\].
    pub plastic_x: Vec<f64>,
    /// See `plastic_x`.
    pub plastic_y: Vec<f64>,
    /// Flow without slip in the last solve.
    pub flow: Vec<bool>,
    /// The generalised slip lambda of each element in the last pass \[m\]
    /// (the start of the next solve's iteration).
    pub slid: Vec<f64>,
    /// The material's state before the solve under way (a transient step:
    /// the history, carried with the material by a rolling step).
    before_hardening: Vec<f64>,
    before_x: Vec<f64>,
    before_y: Vec<f64>,
    /// The next bounds of the iteration \[Pa\].
    pub next: Vec<f64>,
    /// Whether the last solve had a plastic layer (its fields are then
    /// the history).
    pub used: bool,
    /// That layer's fresh yield limit tau_c0 \[Pa\].
    pub yield_limit: f64,
}

impl HeapBytes for LayerState {
    fn heap_bytes(&self) -> usize {
        heap_bytes!(
            self.hardening,
            self.plastic_x,
            self.plastic_y,
            self.flow,
            self.slid,
            self.before_hardening,
            self.before_x,
            self.before_y,
            self.next
        )
    }
}

impl LayerState {
    /// Fresh material on `n` elements.
    pub fn new(n: usize) -> Self {
        let z = || vec![0.0; n];
        Self {
            hardening: z(),
            plastic_x: z(),
            plastic_y: z(),
            flow: vec![false; n],
            slid: z(),
            before_hardening: z(),
            before_x: z(),
            before_y: z(),
            next: z(),
            used: false,
            yield_limit: 0.0,
        }
    }

    /// Forgets the history: fresh material everywhere.
    pub fn clear(&mut self) {
        for v in [
            &mut self.hardening,
            &mut self.plastic_x,
            &mut self.plastic_y,
            &mut self.slid,
            &mut self.before_hardening,
            &mut self.before_x,
            &mut self.before_y,
            &mut self.next,
        ] {
            v.fill(0.0);
        }
        self.flow.fill(false);
        self.used = false;
    }

    /// The start of a transient step: the material's state before it is
    /// the history, carried with the material by `carry` (fresh material,
    /// 0, entering at the leading edge).
    pub fn begin_step(&mut self, grid: &Grid, carry: Carry) {
        for (from, to) in [
            (&self.hardening, &mut self.before_hardening),
            (&self.plastic_x, &mut self.before_x),
            (&self.plastic_y, &mut self.before_y),
        ] {
            if carry == Carry::Whole(0) {
                to.copy_from_slice(from);
            } else {
                carry_field(grid, carry, from, to);
            }
        }
        if carry != Carry::Whole(0) {
            let (a, b) = (&self.slid, &mut self.next);
            carry_field(grid, carry, a, b);
            std::mem::swap(&mut self.slid, &mut self.next);
        }
    }

    /// The generalised slip of each element from the slips (`sx`, `sy`)
    /// of a pass: |s| times `scale` (dx in steady rolling, 1 in a step).
    pub fn set_slid(&mut self, sx: &[f64], sy: &[f64], scale: f64) {
        for ((l, &x), &y) in self.slid.iter_mut().zip(sx).zip(sy) {
            *l = scale * (x * x + y * y).sqrt();
        }
    }

    /// The bounds of the slips in `slid`: without `compliance`, the
    /// law's, written to `bound` (the start of an iteration); with the
    /// elements' `compliance` \[m/Pa\], `bound` holds the bounds of the
    /// last pass: the law's residual is returned (the sums of squares of
    /// the law's bounds minus those, and of those) and the bounds of one
    /// local Newton step go to [`LayerState::next`]. Steady rolling
    /// (`steady`) marches each grid row from its leading edge, the yield
    /// limit before an element that after the element upstream; a
    /// transient step takes the history.
    pub fn bounds(
        &mut self,
        layer: &InterfacialLayer,
        grid: &Grid,
        steady: bool,
        coulomb: CoulombBound<'_>,
        compliance: Option<f64>,
        bound: &mut [f64],
    ) -> (f64, f64) {
        let tau0 = layer.yield_limit_pa;
        let nx = grid.nx;
        let (mut change, mut size) = (0.0, 0.0);
        for iy in 0..grid.ny {
            // The yield limit of the material arriving (steady rolling):
            // of the plain law's bounds and of the Newton step's.
            let (mut up_plain, mut up_step) = (tau0, tau0);
            for ix in (0..nx).rev() {
                let i = iy * nx + ix;
                let m = coulomb.at(i);
                if m <= 0.0 {
                    match compliance {
                        Some(_) => self.next[i] = 0.0,
                        None => bound[i] = 0.0,
                    }
                    continue;
                }
                let (tau_plain, tau_step) = if steady {
                    (up_plain, up_step)
                } else {
                    let t = tau0 + self.before_hardening[i];
                    (t, t)
                };
                let lambda = self.slid[i];
                let plain = layer.bound(tau_plain, m, lambda);
                match compliance {
                    None => bound[i] = plain,
                    Some(c) => {
                        let current = bound[i];
                        change += (plain - current).powi(2);
                        size += current * current;
                        let g = layer.bound_step(tau_step, m, lambda, current, c);
                        self.next[i] = g;
                        if tau_step < m {
                            up_step = g;
                        }
                    }
                }
                // The yield limit after the element: its bound where it
                // may flow (the traction of a flowing element is its
                // yield limit), else unchanged.
                if tau_plain < m {
                    up_plain = plain;
                }
            }
        }
        (change, size)
    }

    /// Ends a solve: splits each element's generalised slip (`sx`, `sy`,
    /// per unit rolled distance in steady rolling) into the slip at the
    /// interface, written back, and the layer's plastic flow; the flow
    /// accumulates into the plastic deformation and hardens the yield
    /// limit, which become the history. An element that flowed without
    /// slip turns to adhesion in `state` (flagged in `flow`). Returns
    /// the plastic work sum |p| |Δu_pl| over the elements \[Pa m\] (times
    /// the element area: \[J\]; in steady rolling per element rolled).
    #[allow(clippy::too_many_arguments)]
    pub fn finish(
        &mut self,
        layer: &InterfacialLayer,
        grid: &Grid,
        steady: bool,
        coulomb: CoulombBound<'_>,
        [px, py]: [&[f64]; 2],
        [sx, sy]: [&mut [f64]; 2],
        state: &mut [ElementState],
    ) -> f64 {
        let tau0 = layer.yield_limit_pa;
        let (nx, dx) = (grid.nx, grid.dx_m);
        let scale = if steady { dx } else { 1.0 };
        let mut work = 0.0;
        for iy in 0..grid.ny {
            // The material arriving at the leading edge is fresh.
            let (mut up_h, mut up_x, mut up_y) = (0.0, 0.0, 0.0);
            for ix in (0..nx).rev() {
                let i = iy * nx + ix;
                if steady {
                    self.before_hardening[i] = up_h;
                    self.before_x[i] = up_x;
                    self.before_y[i] = up_y;
                }
                let (h, ux, uy) = (self.before_hardening[i], self.before_x[i], self.before_y[i]);
                let m = coulomb.at(i);
                let (mut h_after, mut ux_after, mut uy_after) = (h, ux, uy);
                self.flow[i] = false;
                if m > 0.0 {
                    let (s0, s1) = (sx[i], sy[i]);
                    let norm = (s0 * s0 + s1 * s1).sqrt();
                    let lambda = scale * norm;
                    let tau = tau0 + h;
                    let kappa = layer.plastic_part(tau, m, lambda);
                    if kappa > 0.0 {
                        // Δu_pl = kappa p/|p| = -kappa s/|s|.
                        ux_after -= kappa * s0 / norm;
                        uy_after -= kappa * s1 / norm;
                        h_after = layer.yield_after(tau, kappa) - tau0;
                        work += (px[i] * px[i] + py[i] * py[i]).sqrt() * kappa;
                        let rest = 1.0 - kappa / lambda;
                        if rest <= 1e-12 {
                            sx[i] = 0.0;
                            sy[i] = 0.0;
                            state[i] = ElementState::Adhesion;
                            self.flow[i] = true;
                        } else {
                            sx[i] = s0 * rest;
                            sy[i] = s1 * rest;
                        }
                    }
                }
                self.hardening[i] = h_after;
                self.plastic_x[i] = ux_after;
                self.plastic_y[i] = uy_after;
                (up_h, up_x, up_y) = (h_after, ux_after, uy_after);
            }
        }
        self.used = true;
        self.yield_limit = tau0;
        work
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn clay() -> InterfacialLayer {
        // plastic_3bl's clay: G3 = 106.25 N/mm², h = 0.020 mm, tau_c0 =
        // 200 N/mm², k_tau = 435 N/mm³.
        InterfacialLayer {
            thickness_m: 20e-6,
            shear_modulus_pa: 106.25e6,
            yield_limit_pa: 200e6,
            hardening_pa_per_m: 435e9,
        }
    }

    #[test]
    fn the_law_hardens_to_the_coulomb_bound_and_then_slips() {
        let l = clay();
        let m = 630e6; // 0.7 * 900 N/mm²
        assert_eq!(l.bound(200e6, m, 0.0), 200e6);
        assert!((l.bound(200e6, m, 1e-5) - 204.35e6).abs() < 1.0);
        // Hardened to m after (m - tau)/k = 0.98851 mm; beyond, slip.
        let reach = (m - 200e6) / 435e9;
        assert_eq!(l.bound(200e6, m, 2.0 * reach), m);
        assert_eq!(l.plastic_part(200e6, m, 2.0 * reach), reach);
        assert_eq!(l.plastic_part(200e6, m, 0.5 * reach), 0.5 * reach);
        assert!((l.yield_after(200e6, reach) - m).abs() < 1e-6 * m);
        // Material already as strong as m: Coulomb's law.
        assert_eq!(l.bound(m, m, 1.0), m);
        assert_eq!(l.plastic_part(m, m, 1.0), 0.0);
        // Softening stops at 0.1 tau_c0.
        let sand = InterfacialLayer {
            hardening_pa_per_m: -195e9,
            ..l
        };
        assert_eq!(sand.bound(200e6, m, 1.0), 20e6);
        assert_eq!(sand.yield_after(200e6, 1.0), 20e6);
    }

    #[test]
    fn one_newton_step_solves_one_element() {
        // One element of compliance c sheared by lambda0 beyond its yield
        // limit: g = tau + k lambda with lambda = lambda0 - c (g - tau).
        let l = clay();
        let (c, lambda0, tau) = (2.0e-13, 0.04e-3, 200e6);
        let g = l.bound_step(tau, 630e6, lambda0, tau, c);
        let lambda = lambda0 - c * (g - tau);
        assert!((g - (tau + 435e9 * lambda)).abs() < 1e-6, "{g}");
        // plastic_3bl case 16: 216.0 N/mm².
        assert!((g / 1e6 - 216.0).abs() < 0.01, "{g}");
    }

    #[test]
    fn bad_values_name_their_key() {
        for (l, key) in [
            (
                InterfacialLayer {
                    thickness_m: -1.0,
                    ..clay()
                },
                "layer.thickness_m",
            ),
            (
                InterfacialLayer {
                    shear_modulus_pa: 0.0,
                    ..clay()
                },
                "layer.shear_modulus_pa",
            ),
            (
                InterfacialLayer {
                    yield_limit_pa: f64::NAN,
                    ..clay()
                },
                "layer.yield_limit_pa",
            ),
            (
                InterfacialLayer {
                    hardening_pa_per_m: f64::INFINITY,
                    ..clay()
                },
                "layer.hardening_pa_per_m",
            ),
        ] {
            assert_eq!(l.validate("layer").unwrap_err().key(), Some(key));
        }
        assert!(clay().validate("layer").is_ok());
        assert_eq!(
            InterfacialLayer::elastic(0.0, 1.0).flexibility_m_per_pa(),
            0.0
        );
        let law = crate::core::friclaw::SlipVelocityLaw {
            shape: crate::core::friclaw::FallingShape::Exponential,
            kinetic_coefficient: 0.1,
            falling_coefficients: [0.2, 0.0],
            half_velocities_m_per_s: [1.0, 1.0],
            rolling_speed_m_per_s: 1.0,
            memory_distance_m: 0.0,
            memory_velocity_m_per_s: 0.0,
            start: crate::core::friclaw::SlipStart::Previous,
            max_iterations: 0,
        };
        for f in [Friction::falling(law), Friction::static_kinetic(0.4, 0.3)] {
            let e = clay().check_friction("layer", &f).unwrap_err();
            assert_eq!(e.key(), Some("layer.yield_limit_pa"));
            assert!(InterfacialLayer::elastic(1e-3, 1e9)
                .check_friction("layer", &f)
                .is_ok());
        }
    }
}
