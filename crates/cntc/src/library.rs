//! The library's state: result elements (`ire`, 1..=999), each a module 1
//! wheel/rail problem or a set of module 3 patches (`icp`, 1..=9), created
//! on first use as CONTACT creates them.
//!
//! Threads: the element map is behind a read-write lock taken only to find
//! or create an element; each element has its own lock, held for the whole
//! call. Calls on different `ire` run at once; calls on one `ire` from
//! several threads run one after the other (CONTACT forbids them; here
//! they are merely serialised).

use std::collections::BTreeMap;
use std::sync::{Arc, Mutex, MutexGuard, OnceLock, RwLock};

use railcontact_solver::core::cache::KernelCache;

use crate::config::Config;
use crate::error::{CntcError, Result};
use crate::module1::WheelRail;
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

/// The library's state.
pub struct Library {
    elements: RwLock<BTreeMap<i32, Arc<Mutex<Element>>>>,
    /// Influence kernels shared by every element (memory-capped).
    pub cache: &'static KernelCache,
}

impl Library {
    /// The process's library.
    pub fn get() -> &'static Library {
        static LIB: OnceLock<Library> = OnceLock::new();
        LIB.get_or_init(|| Library {
            elements: RwLock::new(BTreeMap::new()),
            cache: KernelCache::global(),
        })
    }

    /// Element `ire`, created on first use as module 1 when `icp <= 0`,
    /// module 3 otherwise (CONTACT's rule), and locked.
    pub fn element(&self, ire: i32, icp: i32) -> Result<Arc<Mutex<Element>>> {
        if !(1..=MAX_IRE).contains(&ire) {
            return Err(CntcError::Ire(ire));
        }
        if let Some(e) = self.read().get(&ire) {
            return Ok(e.clone());
        }
        let mut map = self.write();
        let e = map
            .entry(ire)
            .or_insert_with(|| {
                let module = if icp <= 0 { 1 } else { 3 };
                Arc::new(Mutex::new(Element::new(module).expect("1 or 3")))
            })
            .clone();
        Ok(e)
    }

    /// An existing element `ire` (getters do not create).
    pub fn existing(&self, ire: i32) -> Result<Arc<Mutex<Element>>> {
        if !(1..=MAX_IRE).contains(&ire) {
            return Err(CntcError::Ire(ire));
        }
        self.read().get(&ire).cloned().ok_or_else(|| {
            CntcError::Icp(format!(
                "result element ire = {ire} does not exist: configure it before reading results"
            ))
        })
    }

    /// `cntc_initialize`: element `ire` of module `imodul`, new or
    /// re-initialised when it had another module.
    pub fn initialize(&self, ire: i32, imodul: i32) -> Result<()> {
        if !(1..=MAX_IRE).contains(&ire) {
            return Err(CntcError::Ire(ire));
        }
        let fresh = Element::new(imodul)?;
        let mut map = self.write();
        match map.get(&ire) {
            Some(e) if lock(e).module() as i32 == imodul => {}
            _ => {
                map.insert(ire, Arc::new(Mutex::new(fresh)));
            }
        }
        Ok(())
    }

    /// `cntc_finalize`: forgets element `ire`.
    pub fn finalize(&self, ire: i32) -> Result<()> {
        if !(1..=MAX_IRE).contains(&ire) {
            return Err(CntcError::Ire(ire));
        }
        self.write().remove(&ire);
        Ok(())
    }

    /// `cntc_finalizelast`: forgets every element.
    pub fn finalize_all(&self) {
        self.write().clear();
    }

    /// The numbers of the existing elements.
    pub fn elements(&self) -> Vec<i32> {
        self.read().keys().copied().collect()
    }

    fn read(&self) -> std::sync::RwLockReadGuard<'_, BTreeMap<i32, Arc<Mutex<Element>>>> {
        self.elements.read().unwrap_or_else(|p| p.into_inner())
    }

    fn write(&self) -> std::sync::RwLockWriteGuard<'_, BTreeMap<i32, Arc<Mutex<Element>>>> {
        self.elements.write().unwrap_or_else(|p| p.into_inner())
    }
}

/// Locks an element; a lock poisoned by a panic caught at the boundary is
/// taken over (the element's state is whatever the panicking call left,
/// which the next `cntc_calculate` replaces).
pub fn lock(e: &Mutex<Element>) -> MutexGuard<'_, Element> {
    e.lock().unwrap_or_else(|p| p.into_inner())
}

/// `cntc_setglobalflags`: one (code, value).
pub fn set_global_flag(code: i32, value: i32) -> Result<()> {
    use crate::flags;
    match code {
        0 => {}
        flags::IF_IDEBUG => crate::log::set_level(value),
        flags::IF_LICDBG | flags::IF_OPENMP | flags::IF_TIMERS => {}
        flags::IF_MODE => {
            if value != flags::MODE_IN_PROCESS {
                return Err(CntcError::NotSupported(format!(
                    "CNTC_if_mode = {value}: forwarding to a railcontact server is not available \
                     in this build; 0 solves in process"
                )));
            }
        }
        other => crate::log::warning(
            "cntc_setglobalflags",
            None,
            None,
            &format!("unknown global flag code {other} is ignored"),
        ),
    }
    Ok(())
}

/// The global flags `cntc_setflags` passes on (as CONTACT's does).
pub fn set_global_flag_from_setflags(code: i32, value: i32) -> Result<()> {
    use crate::flags;
    match code {
        flags::IF_IDEBUG | flags::IF_LICDBG | flags::IF_OPENMP | flags::IF_MODE => {
            set_global_flag(code, value)
        }
        _ => Ok(()),
    }
}

/// `cntc_getflags`: the value of flag `code` (0 for an unknown code).
pub fn flag_value(cfg: &Config, code: i32) -> i32 {
    use crate::flags;
    let d = &cfg.digits;
    match code {
        flags::IF_UNITS => cfg.units.code(),
        flags::IC_CONFIG => d.config,
        flags::IC_PVTIME => d.pvtime,
        flags::IC_BOUND => d.bound,
        flags::IC_TANG => d.tang,
        flags::IC_NORM => d.norm,
        flags::IC_FORCE => d.force,
        flags::IC_SENS => d.sens,
        flags::IC_FRCLAW => d.frclaw,
        flags::IC_DISCNS => d.discns,
        flags::IC_INFLCF => d.inflcf,
        flags::IC_MATER => d.mater,
        flags::IC_EXRHS => d.exrhs,
        flags::IC_HEAT => d.heat,
        flags::IC_IESTIM => d.iestim,
        flags::IC_OUTPUT => d.output,
        flags::IC_FLOW => d.flow,
        flags::IC_RETURN => d.ret,
        flags::IC_MATFIL => d.matfil,
        flags::IC_SBSOUT => d.sbsout,
        flags::IC_SBSFIL => d.sbsfil,
        flags::IF_WRTINP => d.wrtinp,
        flags::IF_IDEBUG => crate::log::level(),
        _ => 0,
    }
}

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
                Element::WheelRail(w) => (
                    w.outcomes.first().map_or(0.0, |o| o.rolling_speed_m_per_s),
                    0.0,
                    0.0,
                ),
            };
            Ok(vec![
                u.velocity_out(veloc),
                chi,
                u.len_out(dq),
                0.0,
                0.0,
                0.0,
            ])
        }
        2 => {
            let c = m.combined()?;
            let g_out = |g: f64| u.stress_out(g);
            let mut v = vec![
                g_out(m.shear_modulus_pa[0]),
                g_out(m.shear_modulus_pa[1]),
                g_out(c.shear_modulus_pa),
                m.poisson[0],
                m.poisson[1],
                c.poisson_ratio,
                c.kalker_k,
                0.0,
                0.0,
                0.0,
            ];
            let (k0, a, b) = match m.model {
                crate::config::MaterialModel::ModifiedFastsim(r) => {
                    (r.initial_factor, r.limit_ratio, r.transition_rate)
                }
                crate::config::MaterialModel::Elastic => (1.0, 1.0, 1.0),
            };
            v.extend([k0, a, b]);
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
    put(20, &l.wheel_marker_track, 3);
    put(25, &l.rail_marker_track, 2);
    put(29, &l.wheelset, 3);
    put(33, &l.wheel_marker_wheelset, 3);
    v
}
