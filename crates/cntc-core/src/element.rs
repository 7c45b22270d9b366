//! A result element (`ire`): a module 1 wheel/rail problem or a set of
//! module 3 patches (`icp`, 1..=9), and the values read from it that do not
//! depend on the library's process state.

use std::collections::BTreeMap;

use railcontact_solver::core::cache::KernelCache;
use railcontact_solver::core::fastsim_grid::GridFlexibility;
use serde::{Deserialize, Serialize};

use crate::config::Config;
use crate::error::{CntcError, Result};
use crate::module1::{Solved, WheelRail};
use crate::module3::Patch;
use crate::outcome::Outcome;
use crate::units::Units;

/// Largest result element number (CONTACT's: below 1000).
pub const MAX_IRE: i32 = 999;
/// Largest module 3 patch number (CONTACT's: below 10).
pub const MAX_ICP: i32 = 9;
/// The interface version this library reports (`ifcver`): CONTACT's
/// 25.2 interface (100 major + 10 minor), the version its open-source
/// library reports.
pub const INTERFACE_VERSION: i32 = 2520;

/// A result element.
pub enum Element {
    /// Module 1: one wheel on its rail.
    WheelRail(Box<WheelRail>),
    /// Module 3: basic contact problems by `icp`.
    Basic(BTreeMap<i32, Patch>),
}

impl Element {
    /// A new element of module `imodul` (1 or 3).
    pub fn new(imodul: i32) -> Result<Element> {
        match imodul {
            1 => Ok(Element::WheelRail(Box::default())),
            3 => Ok(Element::Basic(BTreeMap::new())),
            m => Err(CntcError::Input(format!(
                "module {m} (cntc_initialize): this library has modules 1 (wheel/rail) and 3 (basic contact)"
            ))),
        }
    }

    /// 1 or 3.
    pub fn module(&self) -> u8 {
        match self {
            Element::WheelRail(_) => 1,
            Element::Basic(_) => 3,
        }
    }

    /// Module 3's patch `icp`, created on first use.
    pub fn patch_mut(&mut self, icp: i32) -> Result<&mut Patch> {
        match self {
            Element::Basic(patches) => {
                check_icp(icp)?;
                Ok(patches.entry(icp).or_default())
            }
            Element::WheelRail(_) => Err(CntcError::Icp(
                "this call is for module 3 (basic contact); the result element is a module 1 \
                 (wheel/rail) problem"
                    .into(),
            )),
        }
    }

    /// Module 1's wheel/rail problem.
    pub fn wheelrail_mut(&mut self) -> Result<&mut WheelRail> {
        match self {
            Element::WheelRail(w) => Ok(w),
            Element::Basic(_) => Err(CntcError::Icp(
                "this call is for module 1 (wheel/rail); the result element is a module 3 \
                 (basic contact) problem"
                    .into(),
            )),
        }
    }

    /// Module 1's wheel/rail problem, to read.
    pub fn wheelrail(&self) -> Result<&WheelRail> {
        match self {
            Element::WheelRail(w) => Ok(w),
            Element::Basic(_) => Err(CntcError::Icp(
                "this call is for module 1 (wheel/rail); the result element is a module 3 \
                 (basic contact) problem"
                    .into(),
            )),
        }
    }

    /// The configuration a setter changes: module 3's patch `icp` (created
    /// on first use), module 1's whole problem (any `icp`: module 1 sets
    /// all its patches at once).
    pub fn config_mut(&mut self, icp: i32) -> Result<&mut Config> {
        match self {
            Element::WheelRail(w) => Ok(&mut w.config),
            Element::Basic(_) => Ok(&mut self.patch_mut(icp)?.config),
        }
    }

    /// The configuration to read (module 3: patch `icp` must exist).
    pub fn config(&self, icp: i32) -> Result<&Config> {
        match self {
            Element::WheelRail(w) => Ok(&w.config),
            Element::Basic(p) => {
                check_icp(icp)?;
                p.get(&icp)
                    .map(|p| &p.config)
                    .ok_or_else(|| unknown_icp(icp))
            }
        }
    }

    /// The unit convention of (this element, `icp`); CONTACT's for a patch
    /// not yet configured.
    pub fn units(&self, icp: i32) -> Units {
        self.config(icp).map(|c| c.units).unwrap_or_default()
    }

    /// `cntc_calculate` of patch `icp` (module 3, created on first use)
    /// or of the wheel (module 1): `Ok(n)`, n >= 0 contact elements on the
    /// border of the potential contact area.
    pub fn calculate(&mut self, icp: i32, cache: &KernelCache) -> Result<i32> {
        match self {
            Element::WheelRail(w) => w.calculate(cache),
            Element::Basic(_) => self.patch_mut(icp)?.calculate(cache),
        }
    }

    /// [`Element::calculate`] on grids of at most `max_grid_elements`
    /// elements (a server's limit): a larger one is refused, named, before
    /// anything is solved.
    pub fn calculate_within(
        &mut self,
        icp: i32,
        cache: &KernelCache,
        max_grid_elements: usize,
    ) -> Result<i32> {
        match self {
            Element::WheelRail(w) => w.limit_grid_elements(max_grid_elements),
            Element::Basic(_) => {
                let n = self.patch_mut(icp)?.grid_elements().unwrap_or(0);
                if n > max_grid_elements {
                    return Err(CntcError::Discretisation(format!(
                        "the potential contact grid of {n} elements (MX x MY) is more than the \
                         server's max_grid_elements = {max_grid_elements}: use fewer elements or \
                         solve in process"
                    )));
                }
            }
        }
        self.calculate(icp, cache)
    }

    /// What the last calculation of `icp` left, to send to a library that
    /// forwards its calculations.
    pub fn calculation_result(&mut self, icp: i32) -> Result<CalculationResult> {
        Ok(match self {
            Element::WheelRail(w) => {
                let (outcomes, solved) = w.calculation_result();
                CalculationResult::WheelRail { outcomes, solved }
            }
            Element::Basic(_) => CalculationResult::Patch {
                outcome: self.patch_mut(icp)?.outcome.clone().map(Box::new),
            },
        })
    }

    /// Takes what a server's calculation of `icp` left, as
    /// [`Element::calculate`] leaves it, counting the calculation and its
    /// `seconds`.
    pub fn accept_calculation(
        &mut self,
        icp: i32,
        r: CalculationResult,
        seconds: f64,
    ) -> Result<()> {
        match (self, r) {
            (Element::WheelRail(w), CalculationResult::WheelRail { outcomes, solved }) => {
                w.accept_calculation(outcomes, solved, seconds);
                Ok(())
            }
            (e @ Element::Basic(_), CalculationResult::Patch { outcome }) => {
                e.patch_mut(icp)?
                    .accept_calculation(outcome.map(|o| *o), seconds);
                Ok(())
            }
            _ => Err(CntcError::Server(
                "the server answered for the other module".into(),
            )),
        }
    }

    /// The solved patch `icp` (module 1: 1..=npatch of the last
    /// calculation).
    pub fn outcome(&self, icp: i32) -> Result<&Outcome> {
        let none = || {
            CntcError::Input(format!(
                "contact problem icp = {icp} has no results: call cntc_calculate first"
            ))
        };
        match self {
            Element::WheelRail(w) => {
                let n = w.outcomes.len();
                if icp < 1 || icp as usize > n {
                    return Err(CntcError::Icp(format!(
                        "icp = {icp}: the last calculation found {n} contact patch(es), numbered 1 to {n}"
                    )));
                }
                Ok(&w.outcomes[icp as usize - 1])
            }
            Element::Basic(p) => {
                check_icp(icp)?;
                let patch = p.get(&icp).ok_or_else(|| unknown_icp(icp))?;
                patch.outcome.as_ref().ok_or_else(none)
            }
        }
    }
}

fn check_icp(icp: i32) -> Result<()> {
    if (1..=MAX_ICP).contains(&icp) {
        Ok(())
    } else {
        Err(CntcError::Icp(format!(
            "icp = {icp}: module 3 contact problems are numbered 1 to {MAX_ICP}"
        )))
    }
}

fn unknown_icp(icp: i32) -> CntcError {
    CntcError::Icp(format!(
        "contact problem icp = {icp} has not been configured on this result element"
    ))
}

/// FLX(1:3) \[m/Pa\] that CONTACT's library returns with M = 3 before a
/// calculation: its initial values (`mater_init`: 1e-5, 1e-5, 0 mm³/N).
const UNCALCULATED_FLX_M_PER_PA: [f64; 3] = [1e-14, 1e-14, 0.0];

/// `cntc_getparameters`: 1 (VELOC, CHI, DQ, SPINXO, SPINYO, TAU_C0), 2
/// (materials), 3 (friction), in the caller's units.
pub fn parameters(e: &Element, icp: i32, itask: i32) -> Result<Vec<f64>> {
    let cfg = e.config(icp)?;
    let u = cfg.units;
    let m = &cfg.material;
    match itask {
        1 => {
            let (veloc, chi, dq) = match e {
                Element::Basic(p) => {
                    let k = &p.get(&icp).expect("config found it").kin;
                    (k.veloc, k.chi, k.dq)
                }
                Element::WheelRail(w) => w.outcomes.first().map_or((0.0, 0.0, 0.0), |o| {
                    (o.rolling_speed_m_per_s, o.rolling_direction_rad, 0.0)
                }),
            };
            Ok(vec![
                u.velocity_out(veloc),
                chi,
                u.len_out(dq),
                0.0,
                0.0,
                m.model
                    .layer()
                    .map_or(0.0, |l| u.stress_out(l.yield_limit_pa)),
            ])
        }
        2 => {
            let c = m.combined()?;
            let g_out = |g: f64| u.stress_out(g);
            // FLX(1:3) \[volume/force\] and K_EFF (value 14) as CONTACT's
            // gd%mater holds them: M = 2, 3 after a calculation the
            // flexibilities and slope reduction factor the modified FASTSIM
            // used; before one M = 2's given FLX, M = 3's CONTACT's initial
            // values, and K_EFF 0; M = 4's layer, LAYTHK / GG3 (its
            // parameters in values 15-18); 0 otherwise.
            let layer = m.model.layer();
            let applied = e.outcome(icp).ok().and_then(|o| o.fastsim);
            let (flx_m_per_pa, k_eff) = match (m.model.fastsim(), applied) {
                (Some(_), Some(a)) => (a.flexibilities_m_per_pa, a.slope_factor),
                (Some(f), None) => match f.flexibility {
                    GridFlexibility::Given {
                        flexibility_m_per_pa,
                    } => ([flexibility_m_per_pa; 3], 0.0),
                    GridFlexibility::Kalker { .. } => (UNCALCULATED_FLX_M_PER_PA, 0.0),
                },
                (None, _) => ([layer.map_or(0.0, |l| l.flexibility_m_per_pa()); 3], 0.0),
            };
            let [flx1, flx2, flx3] = flx_m_per_pa.map(|l| u.flexibility_out(l));
            let mut v = vec![
                g_out(m.shear_modulus_pa[0]),
                g_out(m.shear_modulus_pa[1]),
                g_out(c.shear_modulus_pa),
                m.poisson[0],
                m.poisson[1],
                c.poisson_ratio,
                c.kalker_k,
                flx1,
                flx2,
                flx3,
            ];
            let (k0, a, b) = m.model.fastsim().map_or((1.0, 1.0, 1.0), |f| {
                let r = f.reduction;
                (r.initial_factor, r.limit_ratio, r.transition_rate)
            });
            v.extend([k0, a, b, k_eff]);
            if let Some(l) = layer {
                v.extend([
                    g_out(l.shear_modulus_pa),
                    u.len_out(l.thickness_m),
                    g_out(l.yield_limit_pa),
                    g_out(l.hardening_pa_per_m) * u.length_m(),
                ]);
            }
            Ok(v)
        }
        3 => {
            let laws: Vec<(f64, crate::config::FrictionLaw)> = match &cfg.friction_by_angle {
                Some((angles, laws)) => angles.iter().copied().zip(laws.iter().copied()).collect(),
                None => vec![(0.0, cfg.friction)],
            };
            let (memdst, mem_s0) = match cfg.friction {
                crate::config::FrictionLaw::Falling(l) => (
                    u.len_out(l.memory_distance_m),
                    u.velocity_out(l.memory_velocity_m_per_s),
                ),
                crate::config::FrictionLaw::Coulomb(_) => (0.0, 0.0),
            };
            let mut v = vec![cfg.digits.frclaw as f64, laws.len() as f64, memdst, mem_s0];
            for (angle, law) in laws {
                let kinetic = match law {
                    crate::config::FrictionLaw::Coulomb(mu) => mu,
                    crate::config::FrictionLaw::Falling(l) => l.kinetic_coefficient,
                };
                v.extend([angle, law.static_coefficient(), kinetic]);
            }
            Ok(v)
        }
        t => Err(CntcError::Input(format!(
            "itask = {t} (cntc_getparameters): 1 kinematics, 2 material, 3 friction"
        ))),
    }
}

/// `cntc_getcontactlocation`'s values 1-38 of a wheel/rail patch, in the
/// caller's units (zeros where the patch has no location).
pub fn location_values(o: &Outcome, u: Units) -> Vec<f64> {
    let Some(l) = o.location else {
        return vec![0.0; 38];
    };
    let mut v = vec![0.0; 38];
    // Each group from its (0-based) position: its first `lengths` values
    // are lengths, the rest angles.
    let mut put = |at: usize, values: &[f64], lengths: usize| {
        for (k, x) in values.iter().enumerate() {
            v[at + k] = if k < lengths { u.len_out(*x) } else { *x };
        }
    };
    put(0, &l.track, 3);
    put(4, &l.rail, 4);
    put(9, &l.wheel, 4);
    put(14, &l.pressure_centre, 2);
    put(17, &l.rail_deflection_m, 2);
    put(20, &l.wheel_marker_track, 3);
    put(25, &l.rail_marker_track, 2);
    put(29, &l.wheelset, 3);
    put(33, &l.wheel_marker_wheelset, 3);
    v
}

/// What a calculation leaves on an element: the outcome of a module 3
/// patch, or a module 1 wheel's patches and frames.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub enum CalculationResult {
    /// Module 3: the patch's outcome (`None`: no result yet).
    Patch {
        /// The outcome.
        outcome: Option<Box<Outcome>>,
    },
    /// Module 1: the wheel's patches and what `cntc_getglobalforces` reads.
    WheelRail {
        /// One outcome per patch.
        outcomes: Vec<Outcome>,
        /// The frames and forces (`None` after a failed calculation).
        solved: Option<Solved>,
    },
}
