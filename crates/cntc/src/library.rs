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
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, MutexGuard, OnceLock, RwLock};

use railcontact_solver::core::cache::KernelCache;

use crate::call::{Call, CallLog};
use crate::config::Config;
use crate::element::{Element, MAX_IRE};
use crate::error::{CntcError, Result};
use crate::flags;
use crate::inp::{self, Held, InpType};
use crate::units::Units;

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

/// The working folder `cntc_initializefirst` gave (empty: the process's).
static WORK_DIR: Mutex<String> = Mutex::new(String::new());

/// `cntc_initializefirst`'s working folder, which relative input file
/// names are taken in (as CONTACT's `make_absolute_path` takes them).
pub fn set_work_dir(dir: &str) {
    *WORK_DIR.lock().unwrap_or_else(|p| p.into_inner()) = dir.to_string();
}

/// `fname` in the working folder, when relative and one was given.
fn in_work_dir(fname: &str) -> PathBuf {
    let dir = WORK_DIR.lock().unwrap_or_else(|p| p.into_inner()).clone();
    Path::new(&dir).join(fname)
}

impl Entry {
    /// `cntc_readinpfile`: configures this wheel/rail element from input
    /// file `fname` of code `inp_type`, applying the calls the file stands
    /// for ([`crate::inp`]) in CONTACT's units, and then the element's own
    /// unit convention again. `warn` gets each warning. A value the
    /// library does not have is applied and then refused, as a setter's
    /// is; any other error stops at its line.
    pub fn read_inp(
        &mut self,
        inp_type: i32,
        fname: &str,
        warn: &mut dyn FnMut(String),
    ) -> Result<()> {
        let w = self.element.wheelrail()?;
        let kind = InpType::from_code(inp_type).ok_or_else(|| {
            CntcError::InputFile(format!(
                "unknown input file type inp_type = {inp_type}: {} (CNTC_inp_modul1) or {} \
                 (CNTC_inp_spck)",
                flags::INP_MODUL1,
                flags::INP_SPCK
            ))
        })?;
        let path = in_work_dir(fname);
        let shown = path.display().to_string();
        let text = std::fs::read(&path).map_err(|e| {
            CntcError::InputFile(format!("cannot open the input file \"{shown}\": {e}"))
        })?;
        let (z_m, vpitch) = w.held_z_and_vpitch();
        let held = Held {
            digits: w.config.digits,
            z_mm: Units::Contact.len_out(z_m),
            vpitch,
        };
        let units = w.config.units;
        let at = |line: usize| format!("\"{shown}\", line {line}");
        let (inp, warnings) = inp::parse(&String::from_utf8_lossy(&text), kind, &held)
            .map_err(|e| CntcError::InputFile(format!("\"{shown}\", {e}")))?;
        warnings
            .into_iter()
            .for_each(|m| warn(format!("\"{shown}\", {m}")));
        if let Some(u) = &inp.unsupported {
            return Err(CntcError::NotSupported(format!(
                "{}: {}",
                at(u.line),
                u.value
            )));
        }
        let dir = path.parent().unwrap_or(Path::new(""));
        let calls = inp.calls(dir, &held);
        let unit_flag = |u: Units| Call::SetFlag {
            code: flags::IF_UNITS,
            value: u.code(),
        };
        if units != Units::Contact {
            self.apply(-1, unit_flag(Units::Contact))?;
        }
        let unsupported = |e: &Entry| {
            e.element
                .config(-1)
                .ok()
                .and_then(|c| c.unsupported.clone())
        };
        let mut refused = None;
        let mut result = Ok(());
        for (line, call) in calls {
            let name = call.name();
            match self.apply(-1, call) {
                Ok(ws) => ws
                    .into_iter()
                    .for_each(|m| warn(format!("{} ({name}): {m}", at(line)))),
                Err(e) => {
                    // A setter's message may name the call already.
                    let detail = e.detail();
                    let detail = detail
                        .strip_prefix(name)
                        .and_then(|d| d.strip_prefix(": "))
                        .unwrap_or(&detail);
                    let msg = format!("{} ({name}): {detail}", at(line));
                    result = Err(match e {
                        CntcError::NotSupported(_) => CntcError::NotSupported(msg),
                        _ => CntcError::InputFile(msg),
                    });
                    break;
                }
            }
            // The configuration this call left unsupported, if any (its
            // setter's mark).
            if let Some((tag, what)) = unsupported(self) {
                if tag.starts_with(name) {
                    refused = Some((line, name, what));
                }
            }
        }
        if result.is_ok() {
            if let Some(blocks) = &inp.subsurface {
                result = self.add_subsurface_blocks(&blocks.value).map_err(|e| {
                    CntcError::InputFile(format!(
                        "{} (subs_addblock): {}",
                        at(blocks.line),
                        e.detail()
                    ))
                });
            }
        }
        if units != Units::Contact {
            self.apply(-1, unit_flag(units))?;
        }
        result?;
        match (refused, unsupported(self)) {
            (Some((line, name, what)), Some((_, now))) if now == what => Err(
                CntcError::NotSupported(format!("{} ({name}): {what}", at(line))),
            ),
            _ => Ok(()),
        }
    }

    /// An input file's subsurface blocks (S = 3), in CONTACT's units:
    /// they replace the element's blocks of every patch (`subs_addblock`
    /// with ICP = -1, IBLK = 0 and then 1, 2, ...).
    fn add_subsurface_blocks(&mut self, blocks: &[inp::SubsBlockInp]) -> Result<()> {
        let w = self.element.wheelrail_mut()?;
        w.subs_add(-1, 0, 0, &[], &[], &[])?;
        for (k, b) in blocks.iter().enumerate() {
            w.subs_add(-1, k as i32 + 1, b.isubs, &b.x, &b.y, &b.z)?;
        }
        Ok(())
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
