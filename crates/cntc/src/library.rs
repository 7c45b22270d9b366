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

use crate::call::{Call, CallLog};
use crate::config::Config;
use crate::element::{Element, MAX_IRE};
use crate::error::{CntcError, Result};

/// A result element with the calls that configured it and, when the
/// library forwards its calculations, its link to the server.
pub struct Entry {
    /// The element: its configuration, and the results the getters read.
    pub element: Element,
    /// The calls made on it since it was created (what a server needs).
    pub log: CallLog,
    /// The element's stream to the server (forwarding, once used).
    pub link: Option<crate::forward::Link>,
    /// The last stream to the server was lost (the next one starts a copy
    /// without the element's history).
    pub lost: bool,
}

impl Entry {
    fn new(element: Element) -> Arc<Mutex<Entry>> {
        Arc::new(Mutex::new(Entry {
            element,
            log: CallLog::default(),
            link: None,
            lost: false,
        }))
    }

    /// Applies `call` to patch `icp` and keeps it for a server: its
    /// warnings, or its error.
    pub fn apply(&mut self, icp: i32, call: Call) -> Result<Vec<String>> {
        let r = call.apply(&mut self.element, icp);
        self.log.push(icp, call, r.is_ok());
        r
    }
}

/// The library's state.
pub struct Library {
    elements: RwLock<BTreeMap<i32, Arc<Mutex<Entry>>>>,
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
    pub fn element(&self, ire: i32, icp: i32) -> Result<Arc<Mutex<Entry>>> {
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
                Entry::new(Element::new(module).expect("1 or 3"))
            })
            .clone();
        Ok(e)
    }

    /// An existing element `ire` (getters do not create).
    pub fn existing(&self, ire: i32) -> Result<Arc<Mutex<Entry>>> {
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
            Some(e) if lock(e).element.module() as i32 == imodul => {}
            _ => {
                map.insert(ire, Entry::new(fresh));
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

    fn read(&self) -> std::sync::RwLockReadGuard<'_, BTreeMap<i32, Arc<Mutex<Entry>>>> {
        self.elements.read().unwrap_or_else(|p| p.into_inner())
    }

    fn write(&self) -> std::sync::RwLockWriteGuard<'_, BTreeMap<i32, Arc<Mutex<Entry>>>> {
        self.elements.write().unwrap_or_else(|p| p.into_inner())
    }
}

/// Locks an element; a lock poisoned by a panic caught at the boundary is
/// taken over (the element's state is whatever the panicking call left,
/// which the next `cntc_calculate` replaces).
pub fn lock(e: &Mutex<Entry>) -> MutexGuard<'_, Entry> {
    e.lock().unwrap_or_else(|p| p.into_inner())
}

/// `cntc_setglobalflags`: one (code, value).
pub fn set_global_flag(code: i32, value: i32) -> Result<()> {
    use crate::flags;
    match code {
        0 => {}
        flags::IF_IDEBUG => crate::log::set_level(value),
        flags::IF_LICDBG | flags::IF_OPENMP | flags::IF_TIMERS => {}
        flags::IF_MODE => match value {
            flags::MODE_IN_PROCESS => crate::forward::set_enabled(false),
            flags::MODE_SERVER => crate::forward::set_enabled(true),
            _ => {
                return Err(CntcError::Input(format!(
                    "CNTC_if_mode = {value}: 0 solves in process, 1 forwards to a railcontact \
                     server (RAILCONTACT_CNTC_SERVER, default {})",
                    crate::forward::DEFAULT_TARGET
                )))
            }
        },
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
