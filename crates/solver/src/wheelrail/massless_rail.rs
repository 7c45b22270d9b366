//! CONTACT's massless rail model (its F = 3): a rail held by springs,
//! whose lateral and vertical deflections balance the contact force,
//!
//! ```text
//! F_y(tr) + F*_y - k*_y dy = 0,    F_z(tr) + F*_z - k*_z dz = 0,
//! ```
//!
//! with `F(tr)` the wheel's force on the rail in the track frame, `F*` forces
//! prescribed on the rail and `k*` the rail's effective stiffnesses
//! (CONTACT's user guide, "Massless rail model": a massless rail with
//! stiffness k and damping c over a time step dt has k* = k + c / dt,
//! F* = c dy_prev / dt). The deflections `dy`, `dz` shift the rail in the
//! track frame (dy along track y, dz along z, down), on top of its
//! deviations.
//!
//! # The iteration
//!
//! Each contact solve places the rail with the lateral deflection `dy`
//! (not the vertical one: a vertical shift of the rail is one of the
//! wheelset the other way), prescribes the wheel's vertical force `F` (the
//! solver's [`WheelLoad::VerticalForce`]) and gives the lateral force and
//! the wheelset's height `c(F)` over the rail not deflected vertically.
//!
//! * Vertically, with the wheelset's height `c_t` prescribed (CONTACT's
//!   N = 0), the rail's deflection is `dz = c_t - c(F)` and the balance
//!   `g(F) = k*_z (c_t - c(F)) - F*_z - F = 0` is solved for `F > 0`
//!   ([`decreasing_root`]: g falls with slope `-(1 + k*_z dc/dF)`, first
//!   step along the estimate `dc/dF` of the first solve). With the vertical
//!   force `FZ` prescribed (N = 1) the deflection follows at once,
//!   `dz = (FZ + F*_z) / k*_z` (0 when k*_z = 0), and the wheelset's height
//!   over the deflected rail is found at that force: as CONTACT's
//!   `wr_contact_fy_brent` does.
//! * Laterally, `r(dy) = F_y(dy) + F*_y - k*_y dy = 0`, each evaluation a
//!   vertical balance as above; the secant method safeguarded by a bracket
//!   ([`decreasing_root`]), its first step `DYSTEP0` towards the root (as
//!   CONTACT's first step).
//!
//! Both balances are met to [`MASSLESS_RAIL_TOLERANCE`] of the force scale
//! (the largest of |F*_y|, |F*_z| and the wheel's vertical force at the
//! start), each within [`MASSLESS_RAIL_MAX_ITERATIONS`] steps; otherwise a
//! [`MasslessRailError::NotConverged`] names the balance. The lateral
//! deflection stays within [`MAX_LATERAL_DEFLECTION_M`].

use std::sync::Arc;

use thiserror::Error;

use crate::core::cache::KernelCache;
use crate::core::error::Range;
use crate::core::root::{decreasing_root, RootEnd, RootError, RootSettings};

use super::contact::{solve_wheelset_warm, WarmStart, WheelLoad, WheelRailInput};
use super::search::SearchScratch;
use super::wheelset::{WheelRailError, WheelRailPair};
use super::WheelRailSolution;

/// Relative tolerance of both force balances, of the force scale (the
/// largest of |F*_y|, |F*_z| and the wheel's vertical force at the start)
/// [-]: 1e-5, above the creep forces' own error (about 1e-5 of mu F_n, see
/// [`super::wheelrail_solver_settings`]).
pub const MASSLESS_RAIL_TOLERANCE: f64 = 1e-5;

/// Step limit of each balance's iteration (the lateral one's steps each
/// hold a vertical iteration).
pub const MASSLESS_RAIL_MAX_ITERATIONS: usize = 30;

/// Relative tolerance of the balances on the rail placed with both
/// deflections found (the caller's last solve), of the force scale [-]:
/// 1e-3. The iteration's last solve has the vertical deflection as a shift
/// of the wheelset instead, the same contact to the solver's tolerances and
/// the contact search's discretisation; where the contact jumps with a
/// shift of a micrometre, the two may differ by more.
pub const MASSLESS_RAIL_PLACED_TOLERANCE: f64 = 1e-3;

/// Largest lateral deflection the iteration tries \[m\] (0.1 m: no rail
/// deflects that far; a step beyond it is an error).
pub const MAX_LATERAL_DEFLECTION_M: f64 = 0.1;

/// The rail's springs and the forces prescribed on it (CONTACT's KYRAIL,
/// FYRAIL, KZRAIL, FZRAIL, DYSTEP0), SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MasslessRail {
    /// Effective lateral stiffness k*_y \[N/m\], > 0.
    pub lateral_stiffness_n_per_m: f64,
    /// Lateral force F*_y prescribed on the rail \[N\] (track y).
    pub lateral_force_n: f64,
    /// Effective vertical stiffness k*_z \[N/m\], >= 0; > 0 when the
    /// wheelset's height is prescribed.
    pub vertical_stiffness_n_per_m: f64,
    /// Vertical force F*_z prescribed on the rail \[N\] (z down).
    pub vertical_force_n: f64,
    /// The first lateral step of the iteration \[m\], > 0 (CONTACT's
    /// DYSTEP0, default 1 mm): the size of deflection expected.
    pub first_lateral_step_m: f64,
}

/// The rail's deflection in the track frame \[m\].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RailDeflection {
    /// Along track y (CONTACT's DY_DEFL).
    pub lateral_m: f64,
    /// Along z, down (CONTACT's DZ_DEFL).
    pub vertical_m: f64,
}

/// How the wheel is held vertically.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RailLoad {
    /// The wheelset's height over the rail not deflected vertically
    /// \[m\] (the solver's centre height, z down).
    CenterHeight(f64),
    /// The wheel's vertical force on the rail \[N\], > 0.
    VerticalForce(f64),
}

/// One contact solve: the wheel on the rail shifted by a lateral
/// deflection, under a vertical force.
#[derive(Debug, Clone)]
pub struct RailContact<S> {
    /// The wheel's lateral force on the rail \[N\] (track y).
    pub lateral_force_n: f64,
    /// The wheelset's height over the rail not deflected vertically \[m\]
    /// (z down).
    pub center_z_m: f64,
    /// An estimate of d(center_z_m)/d(force) \[m/N\], > 0: the first step of
    /// the vertical balance.
    pub compliance_m_per_n: f64,
    /// The solve's result.
    pub state: S,
}

/// The balance found.
#[derive(Debug, Clone)]
pub struct Deflected<S> {
    /// The rail's deflection.
    pub deflection: RailDeflection,
    /// The wheel's lateral and vertical force on the rail there \[N\].
    pub force_n: [f64; 2],
    /// The last contact solve's result (on the undeflected rail, shifted).
    pub state: S,
    /// Contact solves spent.
    pub contact_solves: usize,
}

/// Why no balance was found.
#[derive(Debug, Error)]
pub enum MasslessRailError<E> {
    /// A parameter of the rail is out of range.
    #[error("massless rail: {field} = {value}: {reason}")]
    Invalid {
        /// The field (the solver's name; CONTACT's in the message).
        field: &'static str,
        /// Its value.
        value: f64,
        /// What it must be.
        reason: &'static str,
    },
    /// A balance was not met.
    #[error(
        "massless rail: the {balance} force balance was not met ({why}) after {steps} steps: \
         residual {residual_n} N, tolerance {tolerance_n} N"
    )]
    NotConverged {
        /// "lateral" or "vertical".
        balance: &'static str,
        /// Why it stopped.
        why: &'static str,
        /// Steps taken.
        steps: usize,
        /// The last residual \[N\].
        residual_n: f64,
        /// The tolerance \[N\].
        tolerance_n: f64,
    },
    /// The balance lies where the wheel does not touch the rail, or beyond
    /// the lateral limit.
    #[error("massless rail: {0}")]
    OutOfReach(String),
    /// A contact solve failed.
    #[error("{0}")]
    Contact(E),
}

impl MasslessRail {
    /// The balances' residuals F_y + F*_y - k*_y dy and F_z + F*_z - k*_z dz
    /// \[N\] of the wheel's force `force_n` (lateral, vertical) on the rail
    /// deflected by `d`.
    pub fn residuals_n(&self, d: RailDeflection, force_n: [f64; 2]) -> [f64; 2] {
        [
            force_n[0] + self.lateral_force_n - self.lateral_stiffness_n_per_m * d.lateral_m,
            force_n[1] + self.vertical_force_n - self.vertical_stiffness_n_per_m * d.vertical_m,
        ]
    }

    /// The force scale of the tolerances \[N\]: the largest of |F*_y|,
    /// |F*_z|, the wheel's vertical force `fz_n` and 1 N.
    pub fn force_scale_n(&self, fz_n: f64) -> f64 {
        self.lateral_force_n
            .abs()
            .max(self.vertical_force_n.abs())
            .max(fz_n)
            .max(1.0)
    }

    /// Checks the parameters for `load`.
    pub fn validate<E>(&self, load: RailLoad) -> Result<(), MasslessRailError<E>> {
        let invalid = |field, value, reason| {
            Err(MasslessRailError::Invalid {
                field,
                value,
                reason,
            })
        };
        let fields = [
            ("lateral_stiffness_n_per_m", self.lateral_stiffness_n_per_m),
            ("lateral_force_n", self.lateral_force_n),
            (
                "vertical_stiffness_n_per_m",
                self.vertical_stiffness_n_per_m,
            ),
            ("vertical_force_n", self.vertical_force_n),
            ("first_lateral_step_m", self.first_lateral_step_m),
        ];
        for (field, value) in fields {
            if !value.is_finite() {
                return invalid(field, value, "must be finite");
            }
        }
        if self.lateral_stiffness_n_per_m <= 0.0 {
            return invalid(
                "lateral_stiffness_n_per_m",
                self.lateral_stiffness_n_per_m,
                "the lateral stiffness (KYRAIL) must be > 0",
            );
        }
        if self.first_lateral_step_m <= 0.0 {
            return invalid(
                "first_lateral_step_m",
                self.first_lateral_step_m,
                "the first lateral step (DYSTEP0) must be > 0",
            );
        }
        let kz = self.vertical_stiffness_n_per_m;
        match load {
            RailLoad::CenterHeight(_) if kz <= 0.0 => invalid(
                "vertical_stiffness_n_per_m",
                kz,
                "the vertical stiffness (KZRAIL) must be > 0 with the wheelset's height \
                 prescribed (N = 0)",
            ),
            _ if kz < 0.0 => invalid(
                "vertical_stiffness_n_per_m",
                kz,
                "the vertical stiffness (KZRAIL) must be >= 0",
            ),
            RailLoad::VerticalForce(f) if !(f > 0.0 && f.is_finite()) => invalid(
                "vertical_force",
                f,
                "the wheel's vertical force must be > 0",
            ),
            _ => Ok(()),
        }
    }
}

/// The rail deflection that balances the contact force, from `start`;
/// `contact(dy, f)` solves the wheel on the rail shifted laterally by `dy`
/// \[m\] (the rail not deflected vertically) under the vertical force `f`
/// \[N\]. See the module docs.
pub fn rail_deflection<S, E>(
    rail: &MasslessRail,
    load: RailLoad,
    start: RailDeflection,
    mut contact: impl FnMut(f64, f64) -> Result<RailContact<S>, E>,
) -> Result<Deflected<S>, MasslessRailError<E>> {
    rail.validate(load)?;
    let kz = rail.vertical_stiffness_n_per_m;
    let fz_rail = rail.vertical_force_n;
    let mut solves = 0usize;
    // The first vertical force: the prescribed one, or the spring's at the
    // start (at least |F*_z| or 1 kN when that is not positive).
    let mut force_guess = match load {
        RailLoad::VerticalForce(f) => f,
        RailLoad::CenterHeight(_) => {
            let f = kz * start.vertical_m - fz_rail;
            if f > 0.0 {
                f
            } else {
                fz_rail.abs().max(1e3)
            }
        }
    };
    let tolerance_n = MASSLESS_RAIL_TOLERANCE * rail.force_scale_n(force_guess);

    // The vertical balance at the lateral deflection dy: (F, dz, contact).
    let mut vertical = |dy: f64,
                        force_guess: &mut f64,
                        solves: &mut usize|
     -> Result<(f64, f64, RailContact<S>), MasslessRailError<E>> {
        match load {
            RailLoad::VerticalForce(f) => {
                *solves += 1;
                let c = contact(dy, f).map_err(MasslessRailError::Contact)?;
                let dz = if kz > 0.0 { (f + fz_rail) / kz } else { 0.0 };
                Ok((f, dz, c))
            }
            RailLoad::CenterHeight(ct) => {
                let mut eval = |f: f64| -> Result<(f64, RailContact<S>), E> {
                    *solves += 1;
                    let c = contact(dy, f)?;
                    Ok((kz * (ct - c.center_z_m) - fz_rail - f, c))
                };
                let f0 = *force_guess;
                let (g0, c0) = eval(f0).map_err(MasslessRailError::Contact)?;
                let slope = -(1.0 + kz * c0.compliance_m_per_n.max(0.0));
                let settings = RootSettings {
                    tolerance: tolerance_n,
                    max_iterations: MASSLESS_RAIL_MAX_ITERATIONS,
                    slope,
                };
                let root =
                    decreasing_root(f0, g0, c0, settings, Range::positive(f64::MAX, "N"), eval)
                        .map_err(|e| match e {
                            RootError::Eval(e) => MasslessRailError::Contact(e),
                            RootError::OutOfRange { next } => {
                                MasslessRailError::OutOfReach(format!(
                        "the vertical balance at the lateral deflection {dy} m needs a wheel \
                         force of {next} N or less: the wheel does not touch the rail there"
                    ))
                            }
                        })?;
                converged(
                    "vertical",
                    root.end,
                    root.iterations,
                    root.residual,
                    tolerance_n,
                )?;
                *force_guess = root.x;
                Ok((root.x, ct - root.state.center_z_m, root.state))
            }
        }
    };

    let dy0 = start.lateral_m;
    let lateral_residual = |dy: f64, c: &RailContact<S>| {
        let d = RailDeflection {
            lateral_m: dy,
            vertical_m: 0.0,
        };
        rail.residuals_n(d, [c.lateral_force_n, 0.0])[0]
    };
    let first = vertical(dy0, &mut force_guess, &mut solves)?;
    let r0 = lateral_residual(dy0, &first.2);
    // The first step is DYSTEP0 towards the root (r falls with dy).
    let settings = RootSettings {
        tolerance: tolerance_n,
        max_iterations: MASSLESS_RAIL_MAX_ITERATIONS,
        slope: -(r0.abs().max(f64::MIN_POSITIVE)) / rail.first_lateral_step_m,
    };
    let mut inner_error = None;
    let root = decreasing_root(
        dy0,
        r0,
        first,
        settings,
        Range::symmetric(MAX_LATERAL_DEFLECTION_M, "m"),
        |dy| match vertical(dy, &mut force_guess, &mut solves) {
            Ok(v) => Ok((lateral_residual(dy, &v.2), v)),
            Err(e) => {
                inner_error = Some(e);
                Err(())
            }
        },
    );
    let root = match root {
        Ok(root) => root,
        Err(RootError::Eval(())) => {
            return Err(inner_error.expect("the evaluation's error is kept"));
        }
        Err(RootError::OutOfRange { next }) => {
            return Err(MasslessRailError::OutOfReach(format!(
                "the lateral balance needs a deflection beyond {MAX_LATERAL_DEFLECTION_M} m \
                 (next step {next} m)"
            )))
        }
    };
    converged(
        "lateral",
        root.end,
        root.iterations,
        root.residual,
        tolerance_n,
    )?;
    let (f, dz, c) = root.state;
    Ok(Deflected {
        deflection: RailDeflection {
            lateral_m: root.x,
            vertical_m: dz,
        },
        force_n: [c.lateral_force_n, f],
        state: c.state,
        contact_solves: solves,
    })
}

/// `Ok` when a balance converged, else its error.
fn converged<E>(
    balance: &'static str,
    end: RootEnd,
    steps: usize,
    residual_n: f64,
    tolerance_n: f64,
) -> Result<(), MasslessRailError<E>> {
    let why = match end {
        RootEnd::Converged => return Ok(()),
        RootEnd::BracketCollapsed => "the force jumps at the balance: a patch comes or goes",
        RootEnd::IterationLimit => "the step limit was reached",
    };
    Err(MasslessRailError::NotConverged {
        balance,
        why,
        steps,
        residual_n,
        tolerance_n,
    })
}

/// The deflection of the rail of the wheel `input` solves (one side),
/// its load the wheelset's centre height (over the rail not deflected
/// vertically) or the wheel's vertical force, from `start`; `place(dy)`
/// gives the pair whose rail is placed with the lateral deflection `dy`
/// \[m\] (track y) and without a vertical one (called again only when dy
/// changes). Every solve is a warm start from the one before. The solution
/// returned is that of the last solve, on the rail not deflected
/// vertically; the caller solves again on the rail placed with both
/// deflections for the track frame's positions.
pub fn solve_on_massless_rail(
    mut place: impl FnMut(f64) -> Result<Arc<WheelRailPair>, WheelRailError>,
    input: &WheelRailInput,
    rail: &MasslessRail,
    start: RailDeflection,
    cache: &KernelCache,
    scratch: &mut SearchScratch,
) -> Result<Deflected<WheelRailSolution>, MasslessRailError<WheelRailError>> {
    let [side] = input.sides[..] else {
        return Err(MasslessRailError::Invalid {
            field: "sides",
            value: input.sides.len() as f64,
            reason: "the massless rail model solves one wheel",
        });
    };
    let load = match input.load {
        WheelLoad::CenterHeight(c) => RailLoad::CenterHeight(c),
        WheelLoad::VerticalForce(f) => RailLoad::VerticalForce(f),
        WheelLoad::Approach(a) => {
            return Err(MasslessRailError::Invalid {
                field: "load",
                value: a,
                reason: "the massless rail model takes a centre height or a vertical force",
            })
        }
    };
    let mut warm = WarmStart::default();
    let mut loaded = input.clone();
    let mut placed: Option<(f64, Arc<WheelRailPair>)> = None;
    rail_deflection(rail, load, start, |dy, f| {
        let pair = match &placed {
            Some((at, pair)) if *at == dy => pair.clone(),
            _ => {
                let pair = place(dy)?;
                placed = Some((dy, pair.clone()));
                pair
            }
        };
        loaded.load = WheelLoad::VerticalForce(f);
        let sol = solve_wheelset_warm(&pair, &loaded, cache, scratch, &mut warm)?;
        let wheel = sol.wheels.iter().find(|w| w.side == side);
        let (fy, approach) =
            wheel.map_or((0.0, 0.0), |w| (w.force_track_n[1], w.vertical_approach_m));
        Ok(RailContact {
            lateral_force_n: fy,
            // The loaded wheelset: the rigid position's centre lowered by
            // the wheel's approach.
            center_z_m: sol.center_z_m + approach,
            // Hertz: F ~ approach^1.5, dc/dF = approach / (1.5 F).
            compliance_m_per_n: approach.max(0.0) / (1.5 * f),
            state: sol,
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A linear contact law standing in for the solver: the wheel's
    /// vertical force kc (c - c0) over the rail, its lateral force
    /// `a - b dy` (falling as the rail moves away from the flange). The
    /// balance is then linear and known in closed form.
    struct Linear {
        kc: f64,
        c0: f64,
        a: f64,
        b: f64,
    }

    impl Linear {
        fn contact(&self, dy: f64, f: f64) -> Result<RailContact<()>, String> {
            Ok(RailContact {
                lateral_force_n: self.a - self.b * dy,
                center_z_m: self.c0 + f / self.kc,
                compliance_m_per_n: 1.0 / self.kc,
                state: (),
            })
        }
    }

    fn rail() -> MasslessRail {
        // testbank.inp case 36's springs and forces (N/mm as N/m * 1e-3).
        MasslessRail {
            lateral_stiffness_n_per_m: 1e7,
            lateral_force_n: -68230.0,
            vertical_stiffness_n_per_m: 1e7,
            vertical_force_n: -30000.0,
            first_lateral_step_m: 0.75e-3,
        }
    }

    #[test]
    fn linear_law_with_height_prescribed_meets_the_closed_form() {
        let law = Linear {
            kc: 5e8,
            c0: 1.0e-3,
            a: 1.6e5,
            b: 1.2e8,
        };
        let r = rail();
        let ct = 2.0884e-3;
        let d = rail_deflection(
            &r,
            RailLoad::CenterHeight(ct),
            RailDeflection::default(),
            |dy, f| law.contact(dy, f),
        )
        .unwrap();
        // Lateral: a - b dy + F*_y = ky dy.
        let dy = (law.a + r.lateral_force_n) / (law.b + r.lateral_stiffness_n_per_m);
        // Vertical: F = kc (ct - dz - c0), F + F*_z = kz dz.
        let kz = r.vertical_stiffness_n_per_m;
        let dz = (law.kc * (ct - law.c0) + r.vertical_force_n) / (law.kc + kz);
        let f = kz * dz - r.vertical_force_n;
        let tol = MASSLESS_RAIL_TOLERANCE * f;
        assert!((d.deflection.lateral_m - dy).abs() * r.lateral_stiffness_n_per_m <= tol);
        assert!((d.deflection.vertical_m - dz).abs() * kz <= 2.0 * tol);
        assert!((d.force_n[1] - f).abs() <= tol);
        // Linear: a secant step lands on the root.
        assert!(d.contact_solves <= 10, "{} solves", d.contact_solves);
    }

    #[test]
    fn vertical_force_prescribed_gives_the_vertical_deflection_at_once() {
        let law = Linear {
            kc: 5e8,
            c0: 0.0,
            a: 1.0e5,
            b: 3.0e7,
        };
        let r = rail();
        let fz = 40_000.0;
        let d = rail_deflection(
            &r,
            RailLoad::VerticalForce(fz),
            RailDeflection::default(),
            |dy, f| law.contact(dy, f),
        )
        .unwrap();
        assert_eq!(
            d.deflection.vertical_m,
            (fz + r.vertical_force_n) / r.vertical_stiffness_n_per_m
        );
        let dy = (law.a + r.lateral_force_n) / (law.b + r.lateral_stiffness_n_per_m);
        assert!((d.deflection.lateral_m - dy).abs() * 4e7 <= MASSLESS_RAIL_TOLERANCE * 68230.0);
        assert_eq!(d.force_n[1], fz);
    }

    #[test]
    fn a_lateral_force_that_pushes_the_rail_away_stops_at_the_limit() {
        // A lateral force growing with the deflection faster than the
        // spring: no balance within 0.1 m.
        let r = rail();
        let err = rail_deflection(
            &r,
            RailLoad::VerticalForce(1e4),
            RailDeflection::default(),
            |dy, _| {
                Ok::<_, String>(RailContact {
                    lateral_force_n: 1e5 + 2e7 * dy,
                    center_z_m: 0.0,
                    compliance_m_per_n: 1e-9,
                    state: (),
                })
            },
        )
        .unwrap_err();
        assert!(matches!(err, MasslessRailError::OutOfReach(_)), "{err}");
    }

    #[test]
    fn a_wheel_lifted_off_its_rail_is_out_of_reach() {
        // The rail pushed up less than the wheel's height: F*_z = +30 kN
        // down on the rail with the wheel 10 mm above the rail's reach.
        let law = Linear {
            kc: 5e8,
            c0: 10e-3,
            a: 0.0,
            b: 0.0,
        };
        let r = MasslessRail {
            vertical_force_n: 30_000.0,
            lateral_force_n: 0.0,
            ..rail()
        };
        let err = rail_deflection(
            &r,
            RailLoad::CenterHeight(0.0),
            RailDeflection::default(),
            |dy, f| law.contact(dy, f),
        )
        .unwrap_err();
        assert!(matches!(err, MasslessRailError::OutOfReach(_)), "{err}");
    }

    #[test]
    fn parameters_are_checked_by_name() {
        let r = MasslessRail {
            lateral_stiffness_n_per_m: 0.0,
            ..rail()
        };
        let e = r
            .validate::<String>(RailLoad::CenterHeight(0.0))
            .unwrap_err();
        assert!(e.to_string().contains("KYRAIL"), "{e}");
        let r = MasslessRail {
            vertical_stiffness_n_per_m: 0.0,
            ..rail()
        };
        assert!(r.validate::<String>(RailLoad::VerticalForce(1e4)).is_ok());
        let e = r
            .validate::<String>(RailLoad::CenterHeight(0.0))
            .unwrap_err();
        assert!(e.to_string().contains("KZRAIL"), "{e}");
        let r = MasslessRail {
            first_lateral_step_m: f64::NAN,
            ..rail()
        };
        assert!(r.validate::<String>(RailLoad::VerticalForce(1e4)).is_err());
    }
}
