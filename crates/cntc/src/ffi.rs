//! The exported C functions: CONTACT's names and calling convention (every
//! argument by reference, `int` 32-bit, `double`, strings as `const char*`
//! with an `int*` length, all functions `void`). Each reads its arguments
//! (a null pointer or a negative length is an error, never a crash), calls
//! the library, writes the results, and logs an error on the library's log
//! ([`crate::log`]); a panic is caught here and reported as
//! `CNTC_err_other`. Calls with an `ierror` argument return the code there;
//! getters leave their outputs untouched on error, as CONTACT's do.
//!
//! Nothing here converts units or interprets values: that is the
//! library's ([`crate::library`], [`crate::config`], the modules).

#![allow(clippy::missing_safety_doc)]

use std::ffi::c_char;
use std::os::raw::c_int;
use std::panic::{catch_unwind, AssertUnwindSafe};

use crate::call::Call;
use crate::element::{Element, INTERFACE_VERSION};
use crate::error::{CntcError, Result};
use crate::getters;
use crate::library::{lock, Entry, Library};
use crate::log;

// ---------------------------------------------------------------------
// Reading and writing arguments.

/// `*p`, or an error naming `arg` when `p` is null.
unsafe fn int(p: *const c_int, arg: &'static str) -> Result<i32> {
    if p.is_null() {
        Err(CntcError::argument(arg, "is a null pointer"))
    } else {
        Ok(*p)
    }
}

/// `*p`, or an error naming `arg` when `p` is null.
unsafe fn real(p: *const f64, arg: &'static str) -> Result<f64> {
    if p.is_null() {
        Err(CntcError::argument(arg, "is a null pointer"))
    } else {
        Ok(*p)
    }
}

/// A length argument: >= 0.
unsafe fn len(p: *const c_int, arg: &'static str) -> Result<usize> {
    let n = int(p, arg)?;
    if n < 0 {
        return Err(CntcError::argument(arg, format!("is negative ({n})")));
    }
    Ok(n as usize)
}

/// The `n` values at `p` (none when `n` is 0, whatever `p`).
unsafe fn slice<'a, T>(p: *const T, n: usize, arg: &'static str) -> Result<&'a [T]> {
    if n == 0 {
        return Ok(&[]);
    }
    if p.is_null() {
        return Err(CntcError::argument(
            arg,
            format!("is a null pointer for {n} values"),
        ));
    }
    Ok(std::slice::from_raw_parts(p, n))
}

/// Writes `v` to `*p`.
unsafe fn put<T>(p: *mut T, v: T, arg: &'static str) -> Result<()> {
    if p.is_null() {
        return Err(CntcError::argument(arg, "is a null pointer"));
    }
    *p = v;
    Ok(())
}

/// Checks that all output pointers are non-null before anything is
/// written.
fn outputs(ptrs: &[(bool, &'static str)]) -> Result<()> {
    match ptrs.iter().find(|(null, _)| *null) {
        Some((_, arg)) => Err(CntcError::argument(arg, "is a null pointer")),
        None => Ok(()),
    }
}

/// Writes the first `n` of `values` to `p` (CONTACT's "if permitted by
/// the length of the array"); positions beyond `values` are set to 0.
unsafe fn put_array(p: *mut f64, n: usize, values: &[f64], arg: &'static str) -> Result<()> {
    if n == 0 {
        return Ok(());
    }
    if p.is_null() {
        return Err(CntcError::argument(
            arg,
            format!("is a null pointer for {n} values"),
        ));
    }
    let out = std::slice::from_raw_parts_mut(p, n);
    for (i, o) in out.iter_mut().enumerate() {
        *o = values.get(i).copied().unwrap_or(0.0);
    }
    Ok(())
}

/// A string of `len` bytes at `p` (without a terminating NUL, as Fortran
/// passes them), trimmed of surrounding blanks.
unsafe fn string(p: *const c_char, len_p: *const c_int, arg: &'static str) -> Result<String> {
    let n = len(len_p, "len")?;
    let bytes = slice(p as *const u8, n, arg)?;
    let bytes = match bytes.iter().position(|b| *b == 0) {
        Some(end) => &bytes[..end],
        None => bytes,
    };
    String::from_utf8(bytes.to_vec())
        .map(|s| s.trim().to_string())
        .map_err(|_| CntcError::argument(arg, "is not UTF-8 text"))
}

// ---------------------------------------------------------------------
// Running a call.

/// Reads `*p` for the log, when it can.
unsafe fn peek(p: *const c_int) -> Option<i32> {
    (!p.is_null()).then(|| *p)
}

/// Runs `body` as call `name` on (`ire`, `icp`), catching a panic, and
/// logs its error. Returns the error code (0 on success, the body's value
/// when it gives one).
unsafe fn run(
    name: &'static str,
    ire: *const c_int,
    icp: *const c_int,
    body: impl FnOnce() -> Result<i32>,
) -> i32 {
    let result = catch_unwind(AssertUnwindSafe(body)).unwrap_or_else(|panic| {
        let what = panic
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| panic.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "unknown".into());
        Err(CntcError::Other(format!(
            "internal error (please report it): {what}"
        )))
    });
    match result {
        Ok(code) => code,
        Err(e) => {
            log::error(name, peek(ire), peek(icp), &e.to_string());
            e.ierror()
        }
    }
}

/// [`run`] for a call with an `ierror` argument, which gets the code.
unsafe fn run_ierror(
    name: &'static str,
    ire: *const c_int,
    icp: *const c_int,
    ierror: *mut c_int,
    body: impl FnOnce() -> Result<i32>,
) {
    let code = run(name, ire, icp, body);
    if ierror.is_null() {
        log::error(
            name,
            peek(ire),
            peek(icp),
            "argument `ierror` is a null pointer",
        );
    } else {
        *ierror = code;
    }
}

/// Runs `f` on element `ire` (created on first use by `icp`'s rule).
fn with_element<T>(ire: i32, icp: i32, f: impl FnOnce(&mut Element) -> Result<T>) -> Result<T> {
    with_entry(ire, icp, |e| f(&mut e.element))
}

/// Runs `f` on an existing element `ire`.
fn with_existing<T>(ire: i32, f: impl FnOnce(&mut Element) -> Result<T>) -> Result<T> {
    let e = Library::get().existing(ire)?;
    let mut guard = lock(&e);
    f(&mut guard.element)
}

/// Runs `f` on the entry of element `ire` (created on first use by
/// `icp`'s rule): the element, its calls and its link to a server.
fn with_entry<T>(ire: i32, icp: i32, f: impl FnOnce(&mut Entry) -> Result<T>) -> Result<T> {
    let e = Library::get().element(ire, icp)?;
    let mut guard = lock(&e);
    f(&mut guard)
}

/// Applies `call` to (ire, icp) and logs its warnings as `name`'s.
fn apply(name: &'static str, ire: i32, icp: i32, call: Call) -> Result<i32> {
    with_entry(ire, icp, |e| {
        for w in e.apply(icp, call)? {
            log::warning(name, Some(ire), Some(icp), &w);
        }
        Ok(0)
    })
}

/// Runs setter `name` of (ire, icp): `args` reads its arguments into the
/// call applied.
unsafe fn setter(
    name: &'static str,
    ire: *const c_int,
    icp: *const c_int,
    args: impl FnOnce() -> Result<Call>,
) {
    run(name, ire, icp, || {
        let (r, c) = (int(ire, "ire")?, int(icp, "icp")?);
        apply(name, r, c, args()?)
    });
}

/// Runs module 1 setter `name` of `ire` (icp = -1).
unsafe fn wheelrail_setter(
    name: &'static str,
    ire: *const c_int,
    args: impl FnOnce() -> Result<Call>,
) {
    run(name, ire, std::ptr::null(), || {
        apply(name, int(ire, "ire")?, -1, args()?)
    });
}

// ---------------------------------------------------------------------
// Preparations.

/// `cntc_initializefirst`: the interface version; the working folder (that
/// of relative input file names, `cntc_readinpfile`); the output folder
/// and the experiment name are accepted (this library writes no files).
#[no_mangle]
pub unsafe extern "C" fn cntc_initializefirst(
    ifcver: *mut c_int,
    ierror: *mut c_int,
    _ioutput: *const c_int,
    c_wrkdir: *const c_char,
    c_outdir: *const c_char,
    c_expnam: *const c_char,
    len_wrkdir: *const c_int,
    len_outdir: *const c_int,
    len_expnam: *const c_int,
) {
    run_ierror(
        "cntc_initializefirst",
        std::ptr::null(),
        std::ptr::null(),
        ierror,
        || {
            let wrkdir = string(c_wrkdir, len_wrkdir, "c_wrkdir")?;
            string(c_outdir, len_outdir, "c_outdir")?;
            string(c_expnam, len_expnam, "c_expnam")?;
            put(ifcver, INTERFACE_VERSION, "ifcver")?;
            Library::get();
            crate::library::set_work_dir(&wrkdir);
            Ok(0)
        },
    )
}

/// `cntc_initializefirst_new`: as [`cntc_initializefirst`].
#[no_mangle]
pub unsafe extern "C" fn cntc_initializefirst_new(
    ifcver: *mut c_int,
    ierror: *mut c_int,
    ioutput: *const c_int,
    c_wrkdir: *const c_char,
    c_outdir: *const c_char,
    c_expnam: *const c_char,
    len_wrkdir: *const c_int,
    len_outdir: *const c_int,
    len_expnam: *const c_int,
) {
    cntc_initializefirst(
        ifcver, ierror, ioutput, c_wrkdir, c_outdir, c_expnam, len_wrkdir, len_outdir, len_expnam,
    )
}

/// `cntc_initialize`: result element `ire` of module `imodul` (1, 3).
#[no_mangle]
pub unsafe extern "C" fn cntc_initialize(
    ire: *const c_int,
    imodul: *const c_int,
    ifcver: *mut c_int,
    ierror: *mut c_int,
    _c_outdir: *const c_char,
    _len_outdir: *const c_int,
) {
    run_ierror("cntc_initialize", ire, std::ptr::null(), ierror, || {
        let (ire, m) = (int(ire, "ire")?, int(imodul, "imodul")?);
        put(ifcver, INTERFACE_VERSION, "ifcver")?;
        Library::get().initialize(ire, m)?;
        Ok(0)
    })
}

/// `cntc_setfileunits`: Fortran file units (this library opens no files).
#[no_mangle]
pub unsafe extern "C" fn cntc_setfileunits(nunits: *const c_int, iunits: *const c_int) {
    run(
        "cntc_setfileunits",
        std::ptr::null(),
        std::ptr::null(),
        || {
            let n = len(nunits, "nunits")?;
            slice(iunits, n, "iunits")?;
            Ok(0)
        },
    );
}

/// `cntc_getmaxnumthreads`: the number of threads that may call at once
/// (on different `ire`): the machine's.
#[no_mangle]
pub unsafe extern "C" fn cntc_getmaxnumthreads(mxthrd: *mut c_int) {
    run(
        "cntc_getmaxnumthreads",
        std::ptr::null(),
        std::ptr::null(),
        || {
            let n = std::thread::available_parallelism().map_or(1, |n| n.get());
            put(mxthrd, n.min(i32::MAX as usize) as i32, "mxthrd")?;
            Ok(0)
        },
    );
}

/// `cntc_setglobalflags`: the library's print level (`CNTC_if_idebug`);
/// the other global flags are accepted.
#[no_mangle]
pub unsafe extern "C" fn cntc_setglobalflags(
    lenflg: *const c_int,
    params: *const c_int,
    values: *const c_int,
) {
    run(
        "cntc_setglobalflags",
        std::ptr::null(),
        std::ptr::null(),
        || {
            let n = len(lenflg, "lenflg")?;
            let (p, v) = (slice(params, n, "params")?, slice(values, n, "values")?);
            for (code, value) in p.iter().zip(v) {
                crate::library::set_global_flag(*code, *value)?;
            }
            Ok(0)
        },
    );
}

/// `cntc_readinpfile`: configures wheel/rail element `ire` from a CONTACT
/// input file (`inp_type` 1988 module 1, 1990 Simpack's), as the
/// `cntc_set*` calls the file stands for would.
#[no_mangle]
pub unsafe extern "C" fn cntc_readinpfile(
    ire: *const c_int,
    inp_type: *const c_int,
    c_fname: *const c_char,
    len_fname: *const c_int,
    ierror: *mut c_int,
) {
    const NAME: &str = "cntc_readinpfile";
    run_ierror(NAME, ire, std::ptr::null(), ierror, || {
        let (r, t) = (int(ire, "ire")?, int(inp_type, "inp_type")?);
        let f = string(c_fname, len_fname, "c_fname")?;
        with_entry(r, -1, |e| {
            e.read_inp(t, &f, &mut |m| log::warning(NAME, Some(r), None, &m))
        })?;
        Ok(0)
    })
}

// ---------------------------------------------------------------------
// Configuration of a contact problem.

/// `cntc_setflags`: control digits and flags of (ire, icp).
#[no_mangle]
pub unsafe extern "C" fn cntc_setflags(
    ire: *const c_int,
    icp: *const c_int,
    lenflg: *const c_int,
    params: *const c_int,
    values: *const c_int,
) {
    run("cntc_setflags", ire, icp, || {
        let (r, c) = (int(ire, "ire")?, int(icp, "icp")?);
        let n = len(lenflg, "lenflg")?;
        let (p, v) = (slice(params, n, "params")?, slice(values, n, "values")?);
        for (&code, &value) in p.iter().zip(v) {
            apply("cntc_setflags", r, c, Call::SetFlag { code, value })?;
            crate::library::set_global_flag_from_setflags(code, value)?;
        }
        Ok(0)
    });
}

/// `cntc_setmetadata`: metadata for output files (stored nowhere: this
/// library writes no mat-files).
#[no_mangle]
pub unsafe extern "C" fn cntc_setmetadata(
    ire: *const c_int,
    icp: *const c_int,
    lenmta: *const c_int,
    params: *const c_int,
    values: *const f64,
) {
    run("cntc_setmetadata", ire, icp, || {
        let (r, c) = (int(ire, "ire")?, int(icp, "icp")?);
        let n = len(lenmta, "lenmta")?;
        slice(params, n, "params")?;
        slice(values, n, "values")?;
        apply("cntc_setmetadata", r, c, Call::SetMetadata)
    });
}

/// `cntc_setsolverflags`: the G digit and its parameters.
#[no_mangle]
pub unsafe extern "C" fn cntc_setsolverflags(
    ire: *const c_int,
    icp: *const c_int,
    gdigit: *const c_int,
    nints: *const c_int,
    iparam: *const c_int,
    nreals: *const c_int,
    rparam: *const f64,
) {
    setter("cntc_setsolverflags", ire, icp, || {
        Ok(Call::SetSolverFlags {
            gdigit: int(gdigit, "gdigit")?,
            ints: slice(iparam, len(nints, "nints")?, "iparam")?.to_vec(),
            reals: slice(rparam, len(nreals, "nreals")?, "rparam")?.to_vec(),
        })
    });
}

/// `cntc_setmaterialparameters`: the M digit and its parameters.
#[no_mangle]
pub unsafe extern "C" fn cntc_setmaterialparameters(
    ire: *const c_int,
    icp: *const c_int,
    mdigit: *const c_int,
    nparam: *const c_int,
    rparam: *const f64,
) {
    setter("cntc_setmaterialparameters", ire, icp, || {
        Ok(Call::SetMaterial {
            mdigit: int(mdigit, "mdigit")?,
            params: slice(rparam, len(nparam, "nparam")?, "rparam")?.to_vec(),
        })
    });
}

/// `cntc_settemperaturedata`: the H digit and its parameters.
#[no_mangle]
pub unsafe extern "C" fn cntc_settemperaturedata(
    ire: *const c_int,
    icp: *const c_int,
    imeth: *const c_int,
    nparam: *const c_int,
    params: *const f64,
) {
    setter("cntc_settemperaturedata", ire, icp, || {
        Ok(Call::SetTemperature {
            imeth: int(imeth, "imeth")?,
            params: slice(params, len(nparam, "nparam")?, "params")?.to_vec(),
        })
    });
}

/// `cntc_setfrictionmethod`: the V and L digits and their parameters.
#[no_mangle]
pub unsafe extern "C" fn cntc_setfrictionmethod(
    ire: *const c_int,
    icp: *const c_int,
    imeth: *const c_int,
    nparam: *const c_int,
    params: *const f64,
) {
    setter("cntc_setfrictionmethod", ire, icp, || {
        Ok(Call::SetFriction {
            imeth: int(imeth, "imeth")?,
            params: slice(params, len(nparam, "nparam")?, "params")?.to_vec(),
        })
    });
}

/// `cntc_settimestep`: DT.
#[no_mangle]
pub unsafe extern "C" fn cntc_settimestep(ire: *const c_int, icp: *const c_int, dt: *const f64) {
    setter("cntc_settimestep", ire, icp, || {
        Ok(Call::SetTimestep {
            dt: real(dt, "dt")?,
        })
    });
}

/// `cntc_setreferencevelocity`: VELOC (module 3).
#[no_mangle]
pub unsafe extern "C" fn cntc_setreferencevelocity(
    ire: *const c_int,
    icp: *const c_int,
    veloc: *const f64,
) {
    setter("cntc_setreferencevelocity", ire, icp, || {
        Ok(Call::SetReferenceVelocity {
            veloc: real(veloc, "veloc")?,
        })
    });
}

/// `cntc_setrollingstepsize`: CHI and DQ (module 3), DQREL (module 1).
#[no_mangle]
pub unsafe extern "C" fn cntc_setrollingstepsize(
    ire: *const c_int,
    icp: *const c_int,
    chi: *const f64,
    dq: *const f64,
) {
    setter("cntc_setrollingstepsize", ire, icp, || {
        // Module 1 reads DQREL only (CONTACT's Python passes no chi).
        Ok(Call::SetRollingStep {
            chi: (!chi.is_null()).then(|| *chi),
            dq: real(dq, "dq")?,
        })
    });
}

/// `cntc_sethertzcontact`: a Hertzian potential contact area (module 3).
#[no_mangle]
pub unsafe extern "C" fn cntc_sethertzcontact(
    ire: *const c_int,
    icp: *const c_int,
    ipotcn: *const c_int,
    nparam: *const c_int,
    params: *const f64,
) {
    setter("cntc_sethertzcontact", ire, icp, || {
        Ok(Call::SetHertz {
            ipotcn: int(ipotcn, "ipotcn")?,
            params: slice(params, len(nparam, "nparam")?, "params")?.to_vec(),
        })
    });
}

/// `cntc_setpotcontact`: the potential contact area (module 3, IPOTCN
/// 1-4) or the discretisation of module 1 (icp = -1).
#[no_mangle]
pub unsafe extern "C" fn cntc_setpotcontact(
    ire: *const c_int,
    icp: *const c_int,
    ipotcn: *const c_int,
    nparam: *const c_int,
    params: *const f64,
) {
    setter("cntc_setpotcontact", ire, icp, || {
        Ok(Call::SetPotcon {
            ipotcn: int(ipotcn, "ipotcn")?,
            params: slice(params, len(nparam, "nparam")?, "params")?.to_vec(),
        })
    });
}

/// `cntc_setverticalforce`: FZ of a wheel/rail problem (module 1).
#[no_mangle]
pub unsafe extern "C" fn cntc_setverticalforce(ire: *const c_int, fz: *const f64) {
    wheelrail_setter("cntc_setverticalforce", ire, || {
        Ok(Call::SetVerticalForce {
            fz: real(fz, "fz")?,
        })
    });
}

/// `cntc_setpenetration`: PEN (module 3).
#[no_mangle]
pub unsafe extern "C" fn cntc_setpenetration(
    ire: *const c_int,
    icp: *const c_int,
    pen: *const f64,
) {
    setter("cntc_setpenetration", ire, icp, || {
        Ok(Call::SetPenetration {
            pen: real(pen, "pen")?,
        })
    });
}

/// `cntc_setnormalforce`: FN (module 3).
#[no_mangle]
pub unsafe extern "C" fn cntc_setnormalforce(
    ire: *const c_int,
    icp: *const c_int,
    fn_: *const f64,
) {
    setter("cntc_setnormalforce", ire, icp, || {
        Ok(Call::SetNormalForce {
            fn_: real(fn_, "fn")?,
        })
    });
}

/// `cntc_setundeformeddistc`: the undeformed distance (module 3).
#[no_mangle]
pub unsafe extern "C" fn cntc_setundeformeddistc(
    ire: *const c_int,
    icp: *const c_int,
    ibase: *const c_int,
    nparam: *const c_int,
    prmudf: *const f64,
) {
    setter("cntc_setundeformeddistc", ire, icp, || {
        Ok(Call::SetUndeformedDistance {
            ibase: int(ibase, "ibase")?,
            params: slice(prmudf, len(nparam, "nparam")?, "prmudf")?.to_vec(),
        })
    });
}

/// `cntc_setcreepages`: CKSI, CETA, CPHI (module 3).
#[no_mangle]
pub unsafe extern "C" fn cntc_setcreepages(
    ire: *const c_int,
    icp: *const c_int,
    vx: *const f64,
    vy: *const f64,
    phi: *const f64,
) {
    setter("cntc_setcreepages", ire, icp, || {
        Ok(Call::SetCreepages {
            vx: real(vx, "vx")?,
            vy: real(vy, "vy")?,
            phi: real(phi, "phi")?,
        })
    });
}

/// `cntc_setextrarigidslip`: WX, WY per element (module 3).
#[no_mangle]
pub unsafe extern "C" fn cntc_setextrarigidslip(
    ire: *const c_int,
    icp: *const c_int,
    lenarr: *const c_int,
    wx: *const f64,
    wy: *const f64,
) {
    setter("cntc_setextrarigidslip", ire, icp, || {
        let n = len(lenarr, "lenarr")?;
        Ok(Call::SetExtraRigidSlip {
            wx: slice(wx, n, "wx")?.to_vec(),
            wy: slice(wy, n, "wy")?.to_vec(),
        })
    });
}

/// `cntc_settangentialforces`: FX, FY relative to FSTAT FN (module 3).
#[no_mangle]
pub unsafe extern "C" fn cntc_settangentialforces(
    ire: *const c_int,
    icp: *const c_int,
    fx: *const f64,
    fy: *const f64,
) {
    setter("cntc_settangentialforces", ire, icp, || {
        Ok(Call::SetTangentialForces {
            fx: real(fx, "fx")?,
            fy: real(fy, "fy")?,
        })
    });
}

// ---------------------------------------------------------------------
// Wheel/rail configuration (module 1).

/// `cntc_setprofileinputfname`: a profile from a file.
#[no_mangle]
pub unsafe extern "C" fn cntc_setprofileinputfname(
    ire: *const c_int,
    c_fname: *const c_char,
    len_fname: *const c_int,
    nints: *const c_int,
    iparam: *const c_int,
    nreals: *const c_int,
    rparam: *const f64,
) {
    wheelrail_setter("cntc_setprofileinputfname", ire, || {
        let fname = string(c_fname, len_fname, "c_fname")?;
        let content = crate::module1::read_profile_file(&fname);
        Ok(Call::SetProfileFile {
            slice_files: crate::module1::read_slice_files(&fname, content.as_deref()),
            content,
            fname,
            ints: slice(iparam, len(nints, "nints")?, "iparam")?.to_vec(),
            reals: slice(rparam, len(nreals, "nreals")?, "rparam")?.to_vec(),
        })
    });
}

/// `cntc_setprofileinputvalues`: a profile from (y, z) values.
#[no_mangle]
pub unsafe extern "C" fn cntc_setprofileinputvalues(
    ire: *const c_int,
    npoint: *const c_int,
    values: *const f64,
    nints: *const c_int,
    iparam: *const c_int,
    nreals: *const c_int,
    rparam: *const f64,
) {
    wheelrail_setter("cntc_setprofileinputvalues", ire, || {
        let n = len(npoint, "npoint")?;
        Ok(Call::SetProfileValues {
            npoint: n,
            values: slice(values, 2 * n, "values")?.to_vec(),
            ints: slice(iparam, len(nints, "nints")?, "iparam")?.to_vec(),
            reals: slice(rparam, len(nreals, "nreals")?, "rparam")?.to_vec(),
        })
    });
}

/// `cntc_settrackdimensions`.
#[no_mangle]
pub unsafe extern "C" fn cntc_settrackdimensions(
    ire: *const c_int,
    ztrack: *const c_int,
    nparam: *const c_int,
    params: *const f64,
) {
    wheelrail_setter("cntc_settrackdimensions", ire, || {
        Ok(Call::SetTrackDimensions {
            ztrack: int(ztrack, "ztrack")?,
            params: slice(params, len(nparam, "nparam")?, "params")?.to_vec(),
        })
    });
}

macro_rules! wheelset_setter {
    ($name:ident, $call:ident) => {
        #[doc = concat!("`", stringify!($name), "`.")]
        #[no_mangle]
        pub unsafe extern "C" fn $name(
            ire: *const c_int,
            ewheel: *const c_int,
            nparam: *const c_int,
            params: *const f64,
        ) {
            wheelrail_setter(stringify!($name), ire, || {
                Ok(Call::$call {
                    ewheel: int(ewheel, "ewheel")?,
                    params: slice(params, len(nparam, "nparam")?, "params")?.to_vec(),
                })
            });
        }
    };
}

wheelset_setter!(cntc_setwheelsetdimensions, SetWheelsetDimensions);
wheelset_setter!(cntc_setwheelsetposition, SetWheelsetPosition);
wheelset_setter!(cntc_setwheelsetvelocity, SetWheelsetVelocity);
wheelset_setter!(cntc_setwheelsetflexibility, SetWheelsetFlexibility);

// ---------------------------------------------------------------------
// Subsurface stresses.

/// `subs_addblock`: a block of points for subsurface stresses.
#[no_mangle]
pub unsafe extern "C" fn subs_addblock(
    ire: *const c_int,
    icp: *const c_int,
    iblk: *const c_int,
    isubs: *const c_int,
    npx: *const c_int,
    npy: *const c_int,
    npz: *const c_int,
    xparam: *const f64,
    yparam: *const f64,
    zparam: *const f64,
) {
    run("subs_addblock", ire, icp, || {
        let (r, c) = (int(ire, "ire")?, int(icp, "icp")?);
        let (b, s) = (int(iblk, "iblk")?, int(isubs, "isubs")?);
        let x = slice(xparam, len(npx, "npx")?, "xparam")?;
        let y = slice(yparam, len(npy, "npy")?, "yparam")?;
        let z = slice(zparam, len(npz, "npz")?, "zparam")?;
        with_element(r, c, |e| match e {
            Element::WheelRail(w) => w.subs_add(c, b, s, x, y, z).map(|_| 0),
            Element::Basic(_) => {
                let p = e.patch_mut(c)?;
                p.subs.add(p.config.units, b, s, x, y, z).map(|_| 0)
            }
        })
    });
}

/// `subs_calculate`: subsurface stresses below the solved patch(es).
#[no_mangle]
pub unsafe extern "C" fn subs_calculate(ire: *const c_int, icp: *const c_int, ierror: *mut c_int) {
    run_ierror("subs_calculate", ire, icp, ierror, || {
        let (r, c) = (int(ire, "ire")?, int(icp, "icp")?);
        with_existing(r, |e| match e {
            Element::WheelRail(w) => w.subs_calculate(c).map(|_| 0),
            Element::Basic(_) => {
                let p = e.patch_mut(c)?;
                let o = p.outcome.as_ref().ok_or_else(|| {
                    CntcError::Input(
                        "subs_calculate needs a solved contact problem: call cntc_calculate first"
                            .into(),
                    )
                })?;
                let m = p.config.material.combined()?;
                p.subs.calculate_with(o, &m, false).map(|_| 0)
            }
        })
    })
}

/// `subs_getblocksize`: points of block `iblk` in x, y, z.
#[no_mangle]
pub unsafe extern "C" fn subs_getblocksize(
    ire: *const c_int,
    icp: *const c_int,
    iblk: *const c_int,
    nx: *mut c_int,
    ny: *mut c_int,
    nz: *mut c_int,
) {
    run("subs_getblocksize", ire, icp, || {
        let (r, c, b) = (int(ire, "ire")?, int(icp, "icp")?, int(iblk, "iblk")?);
        outputs(&[
            (nx.is_null(), "nx"),
            (ny.is_null(), "ny"),
            (nz.is_null(), "nz"),
        ])?;
        let n = with_existing(r, |e| match e {
            Element::WheelRail(w) => w.subs_block_size(c, b),
            Element::Basic(_) => e.patch_mut(c)?.subs.block_size(b),
        })?;
        *nx = n[0] as i32;
        *ny = n[1] as i32;
        *nz = n[2] as i32;
        Ok(0)
    });
}

/// `subs_getresults`: columns `icol` of block `iblk`, column after column.
#[no_mangle]
pub unsafe extern "C" fn subs_getresults(
    ire: *const c_int,
    icp: *const c_int,
    iblk: *const c_int,
    lenarr: *const c_int,
    ncol: *const c_int,
    icol: *const c_int,
    values: *mut f64,
) {
    run("subs_getresults", ire, icp, || {
        let (r, c, b) = (int(ire, "ire")?, int(icp, "icp")?, int(iblk, "iblk")?);
        let n = len(lenarr, "lenarr")?;
        let cols = slice(icol, len(ncol, "ncol")?, "icol")?;
        let table = with_existing(r, |e| match e {
            Element::WheelRail(w) => w.subs_results(c, b, cols),
            Element::Basic(_) => {
                let p = e.patch_mut(c)?;
                p.subs.results(p.config.units, b, cols)
            }
        })?;
        // lenarr values per column.
        let rows = table.len() / cols.len().max(1);
        let mut out = vec![0.0; n * cols.len()];
        for k in 0..cols.len() {
            for i in 0..rows.min(n) {
                out[k * n + i] = table[k * rows + i];
            }
        }
        put_array(values, n * cols.len(), &out, "values")?;
        Ok(0)
    });
}

// ---------------------------------------------------------------------
// Calculation.

/// `cntc_calculate`: solves (ire, icp) (module 3) or the wheel/rail
/// problem `ire` (module 1, icp <= 0). `ierror`: 0, a positive count of
/// contact elements on the border of the potential contact area, or a
/// negative error code.
#[no_mangle]
pub unsafe extern "C" fn cntc_calculate(ire: *const c_int, icp: *const c_int, ierror: *mut c_int) {
    run_ierror("cntc_calculate", ire, icp, ierror, || {
        let (r, c) = (int(ire, "ire")?, int(icp, "icp")?);
        calculate(r, c)
    })
}

/// `cntc_calculate1`: the wheel/rail problem `ire` (module 1).
#[no_mangle]
pub unsafe extern "C" fn cntc_calculate1(ire: *const c_int, ierror: *mut c_int) {
    run_ierror("cntc_calculate1", ire, std::ptr::null(), ierror, || {
        calculate(int(ire, "ire")?, -1)
    })
}

/// `cntc_calculate3`: the basic contact problem (ire, icp) (module 3).
#[no_mangle]
pub unsafe extern "C" fn cntc_calculate3(ire: *const c_int, icp: *const c_int, ierror: *mut c_int) {
    run_ierror("cntc_calculate3", ire, icp, ierror, || {
        let (r, c) = (int(ire, "ire")?, int(icp, "icp")?);
        with_element(r, c, |e| e.patch_mut(c).map(|_| ()))?;
        calculate(r, c)
    })
}

fn calculate(ire: i32, icp: i32) -> Result<i32> {
    let lib = Library::get();
    with_entry(ire, icp, |e| {
        let code = if crate::forward::enabled() {
            crate::forward::calculate(e, ire, icp)
        } else {
            e.element.calculate(icp, lib.cache)
        }?;
        if code > 0 {
            log::warning(
                "cntc_calculate",
                Some(ire),
                Some(icp),
                &format!(
                    "{code} contact element(s) on the border of the potential contact area: the \
                     patch may be cut off; enlarge the area"
                ),
            );
        }
        Ok(code)
    })
}

// ---------------------------------------------------------------------
// Getters.

/// Runs getter `f` on the solved patch (ire, icp) with its units.
unsafe fn outcome_getter(
    name: &'static str,
    ire: *const c_int,
    icp: *const c_int,
    f: impl FnOnce(&crate::outcome::Outcome, crate::units::Units) -> Result<()>,
) {
    run(name, ire, icp, || {
        let (r, c) = (int(ire, "ire")?, int(icp, "icp")?);
        with_existing(r, |e| {
            let u = e.units(c);
            f(e.outcome(c)?, u).map(|_| 0)
        })
    });
}

/// `cntc_getflags`: the values of control digits and flags.
#[no_mangle]
pub unsafe extern "C" fn cntc_getflags(
    ire: *const c_int,
    icp: *const c_int,
    lenflg: *const c_int,
    params: *const c_int,
    values: *mut c_int,
) {
    run("cntc_getflags", ire, icp, || {
        let (r, c) = (int(ire, "ire")?, int(icp, "icp")?);
        let n = len(lenflg, "lenflg")?;
        let p = slice(params, n, "params")?;
        if n > 0 && values.is_null() {
            return Err(CntcError::argument("values", "is a null pointer"));
        }
        let got: Vec<i32> = with_existing(r, |e| {
            let cfg = e.config(c)?;
            Ok(p.iter()
                .map(|code| crate::library::flag_value(cfg, *code))
                .collect())
        })?;
        std::slice::from_raw_parts_mut(values, n).copy_from_slice(&got);
        Ok(0)
    });
}

/// `cntc_getparameters`: groups of parameters (1 kinematics, 2 material,
/// 3 friction).
#[no_mangle]
pub unsafe extern "C" fn cntc_getparameters(
    ire: *const c_int,
    icp: *const c_int,
    itask: *const c_int,
    lenarr: *const c_int,
    values: *mut f64,
) {
    run("cntc_getparameters", ire, icp, || {
        let (r, c, t) = (int(ire, "ire")?, int(icp, "icp")?, int(itask, "itask")?);
        let n = len(lenarr, "lenarr")?;
        let v = with_existing(r, |e| crate::element::parameters(e, c, t))?;
        put_array(values, n, &v, "values").map(|_| 0)
    });
}

/// `cntc_getprofilevalues`: a profile as a table of values (module 1).
#[no_mangle]
pub unsafe extern "C" fn cntc_getprofilevalues(
    ire: *const c_int,
    itask: *const c_int,
    nints: *const c_int,
    iparam: *const c_int,
    nreals: *const c_int,
    rparam: *const f64,
    lenarr: *const c_int,
    val: *mut f64,
) {
    run("cntc_getprofilevalues", ire, std::ptr::null(), || {
        let (r, t) = (int(ire, "ire")?, int(itask, "itask")?);
        let ip = slice(iparam, len(nints, "nints")?, "iparam")?;
        let rp = slice(rparam, len(nreals, "nreals")?, "rparam")?;
        let n = len(lenarr, "lenarr")?;
        let v = with_existing(r, |e| e.wheelrail()?.profile_values(t, ip, rp))?;
        put_array(val, n, &v, "val").map(|_| 0)
    });
}

/// `cntc_getprofilevalues_new`: as [`cntc_getprofilevalues`].
#[no_mangle]
pub unsafe extern "C" fn cntc_getprofilevalues_new(
    ire: *const c_int,
    itask: *const c_int,
    nints: *const c_int,
    iparam: *const c_int,
    nreals: *const c_int,
    rparam: *const f64,
    lenarr: *const c_int,
    val: *mut f64,
) {
    cntc_getprofilevalues(ire, itask, nints, iparam, nreals, rparam, lenarr, val)
}

/// `cntc_getwheelsetposition`: s, y, z, roll, yaw, pitch.
#[no_mangle]
pub unsafe extern "C" fn cntc_getwheelsetposition(
    ire: *const c_int,
    lenarr: *const c_int,
    values: *mut f64,
) {
    run("cntc_getwheelsetposition", ire, std::ptr::null(), || {
        let (r, n) = (int(ire, "ire")?, len(lenarr, "lenarr")?);
        let v = with_existing(r, |e| e.wheelrail()?.wheelset_position())?;
        put_array(values, n, &v, "values").map(|_| 0)
    });
}

/// `cntc_getwheelsetvelocity`: vs, vy, vz, vroll, vyaw, vpitch.
#[no_mangle]
pub unsafe extern "C" fn cntc_getwheelsetvelocity(
    ire: *const c_int,
    lenarr: *const c_int,
    values: *mut f64,
) {
    run("cntc_getwheelsetvelocity", ire, std::ptr::null(), || {
        let (r, n) = (int(ire, "ire")?, len(lenarr, "lenarr")?);
        let v = with_existing(r, |e| e.wheelrail()?.wheelset_velocity())?;
        put_array(values, n, &v, "values").map(|_| 0)
    });
}

/// `cntc_getnumcontactpatches`: patches of the last calculation (module 1).
#[no_mangle]
pub unsafe extern "C" fn cntc_getnumcontactpatches(ire: *const c_int, npatch: *mut c_int) {
    run("cntc_getnumcontactpatches", ire, std::ptr::null(), || {
        let r = int(ire, "ire")?;
        let n = with_existing(r, |e| Ok(e.wheelrail()?.outcomes.len()))?;
        put(npatch, n as i32, "npatch").map(|_| 0)
    });
}

/// `cntc_getcontactlocation`: where patch `icp` lies (module 1); zeros for
/// a patch number beyond the last calculation's, as CONTACT.
#[no_mangle]
pub unsafe extern "C" fn cntc_getcontactlocation(
    ire: *const c_int,
    icp: *const c_int,
    lenarr: *const c_int,
    values: *mut f64,
) {
    run("cntc_getcontactlocation", ire, icp, || {
        let (r, c, n) = (int(ire, "ire")?, int(icp, "icp")?, len(lenarr, "lenarr")?);
        let v = with_existing(r, |e| {
            let w = e.wheelrail()?;
            if c < 1 || c as usize > w.outcomes.len() {
                return Ok(Vec::new());
            }
            Ok(crate::element::location_values(
                &w.outcomes[c as usize - 1],
                w.config.units,
            ))
        })?;
        put_array(values, n, &v, "values").map(|_| 0)
    });
}

/// `cntc_getreferencevelocity`: VELOC of the patch.
#[no_mangle]
pub unsafe extern "C" fn cntc_getreferencevelocity(
    ire: *const c_int,
    icp: *const c_int,
    veloc: *mut f64,
) {
    outcome_getter("cntc_getreferencevelocity", ire, icp, |o, u| {
        put(veloc, u.velocity_out(o.rolling_speed_m_per_s), "veloc")
    });
}

/// `cntc_gethertzcontact`: the Hertzian solution behind the grid (module 3).
#[no_mangle]
pub unsafe extern "C" fn cntc_gethertzcontact(
    ire: *const c_int,
    icp: *const c_int,
    lenarr: *const c_int,
    values: *mut f64,
) {
    run("cntc_gethertzcontact", ire, icp, || {
        let (r, c, n) = (int(ire, "ire")?, int(icp, "icp")?, len(lenarr, "lenarr")?);
        let v = with_existing(r, |e| e.patch_mut(c)?.hertz_values())?;
        put_array(values, n, &v, "values").map(|_| 0)
    });
}

/// `cntc_getnumelements`: MX, MY of the patch's grid.
#[no_mangle]
pub unsafe extern "C" fn cntc_getnumelements(
    ire: *const c_int,
    icp: *const c_int,
    mx: *mut c_int,
    my: *mut c_int,
) {
    outcome_getter("cntc_getnumelements", ire, icp, |o, _| {
        outputs(&[(mx.is_null(), "mx"), (my.is_null(), "my")])?;
        put(mx, o.grid.nx as i32, "mx")?;
        put(my, o.grid.ny as i32, "my")
    });
}

/// `cntc_getgriddiscretization`: DX, DY of the patch's grid.
#[no_mangle]
pub unsafe extern "C" fn cntc_getgriddiscretization(
    ire: *const c_int,
    icp: *const c_int,
    dx: *mut f64,
    dy: *mut f64,
) {
    run("cntc_getgriddiscretization", ire, icp, || {
        let (r, c) = (int(ire, "ire")?, int(icp, "icp")?);
        outputs(&[(dx.is_null(), "dx"), (dy.is_null(), "dy")])?;
        let v = with_existing(r, |e| match e {
            Element::WheelRail(w) if c <= 0 => w.grid_size(),
            _ => {
                let u = e.units(c);
                let g = e.outcome(c)?.grid;
                Ok([u.len_out(g.dx_m), u.len_out(g.dy_m)])
            }
        })?;
        *dx = v[0];
        *dy = v[1];
        Ok(0)
    });
}

/// `cntc_getpotcontact`: MX, MY, XC1, YC1, DX, DY.
#[no_mangle]
pub unsafe extern "C" fn cntc_getpotcontact(
    ire: *const c_int,
    icp: *const c_int,
    lenarr: *const c_int,
    values: *mut f64,
) {
    run("cntc_getpotcontact", ire, icp, || {
        let (r, c, n) = (int(ire, "ire")?, int(icp, "icp")?, len(lenarr, "lenarr")?);
        let v = with_existing(r, |e| Ok(getters::potcontact(e.outcome(c)?, e.units(c))))?;
        put_array(values, n, &v, "values").map(|_| 0)
    });
}

/// `cntc_getpenetration`: the approach PEN.
#[no_mangle]
pub unsafe extern "C" fn cntc_getpenetration(ire: *const c_int, icp: *const c_int, pen: *mut f64) {
    outcome_getter("cntc_getpenetration", ire, icp, |o, u| {
        put(pen, u.len_out(o.approach_m), "pen")
    });
}

/// `cntc_getcreepages`: CKSI, CETA, CPHI.
#[no_mangle]
pub unsafe extern "C" fn cntc_getcreepages(
    ire: *const c_int,
    icp: *const c_int,
    vx: *mut f64,
    vy: *mut f64,
    phi: *mut f64,
) {
    outcome_getter("cntc_getcreepages", ire, icp, |o, u| {
        outputs(&[
            (vx.is_null(), "vx"),
            (vy.is_null(), "vy"),
            (phi.is_null(), "phi"),
        ])?;
        let [a, b, c] = getters::creepages(o, u);
        *vx = a;
        *vy = b;
        *phi = c;
        Ok(())
    });
}

/// `cntc_getcontactforces`: FN, FX, FY, MZ.
#[no_mangle]
pub unsafe extern "C" fn cntc_getcontactforces(
    ire: *const c_int,
    icp: *const c_int,
    fn_: *mut f64,
    tx: *mut f64,
    ty: *mut f64,
    mz: *mut f64,
) {
    outcome_getter("cntc_getcontactforces", ire, icp, |o, u| {
        outputs(&[
            (fn_.is_null(), "fn"),
            (tx.is_null(), "tx"),
            (ty.is_null(), "ty"),
            (mz.is_null(), "mz"),
        ])?;
        let [a, b, c, d] = getters::contact_forces(o, u);
        *fn_ = a;
        *tx = b;
        *ty = c;
        *mz = d;
        Ok(())
    });
}

/// `cntc_getglobalforces`: the 24 forces and moments of a wheel/rail
/// problem (module 1; icp = -1 all patches, else one).
#[no_mangle]
pub unsafe extern "C" fn cntc_getglobalforces(
    ire: *const c_int,
    icp: *const c_int,
    lenarr: *const c_int,
    values: *mut f64,
) {
    run("cntc_getglobalforces", ire, icp, || {
        let (r, c, n) = (int(ire, "ire")?, int(icp, "icp")?, len(lenarr, "lenarr")?);
        let v = with_existing(r, |e| {
            e.wheelrail()?.global_forces((c > 0).then_some(c as usize))
        })?;
        put_array(values, n, &v, "values").map(|_| 0)
    });
}

/// `cntc_getcontactpatchareas`: contact, adhesion and slip areas.
#[no_mangle]
pub unsafe extern "C" fn cntc_getcontactpatchareas(
    ire: *const c_int,
    icp: *const c_int,
    carea: *mut f64,
    harea: *mut f64,
    sarea: *mut f64,
) {
    outcome_getter("cntc_getcontactpatchareas", ire, icp, |o, u| {
        outputs(&[
            (carea.is_null(), "carea"),
            (harea.is_null(), "harea"),
            (sarea.is_null(), "sarea"),
        ])?;
        let [c, h, s] = getters::areas(o, u);
        *carea = c;
        *harea = h;
        *sarea = s;
        Ok(())
    });
}

/// `cntc_getelementdivision`: 0 exterior, 1 adhesion, 2 slip per element.
#[no_mangle]
pub unsafe extern "C" fn cntc_getelementdivision(
    ire: *const c_int,
    icp: *const c_int,
    lenarr: *const c_int,
    eldiv: *mut c_int,
) {
    outcome_getter("cntc_getelementdivision", ire, icp, |o, _| {
        let n = len(lenarr, "lenarr")?;
        let v = getters::element_division(o)?;
        if n == 0 {
            return Ok(());
        }
        if eldiv.is_null() {
            return Err(CntcError::argument("eldiv", "is a null pointer"));
        }
        let out = std::slice::from_raw_parts_mut(eldiv, n);
        for (i, x) in out.iter_mut().enumerate() {
            *x = v.get(i).copied().unwrap_or(0);
        }
        Ok(())
    });
}

/// `cntc_getmaximumpressure`: the largest pressure.
#[no_mangle]
pub unsafe extern "C" fn cntc_getmaximumpressure(
    ire: *const c_int,
    icp: *const c_int,
    pnmax: *mut f64,
) {
    outcome_getter("cntc_getmaximumpressure", ire, icp, |o, u| {
        put(pnmax, u.stress_out(o.max_pressure_pa), "pnmax")
    });
}

/// `cntc_getmaximumtraction`: the largest tangential traction.
#[no_mangle]
pub unsafe extern "C" fn cntc_getmaximumtraction(
    ire: *const c_int,
    icp: *const c_int,
    ptmax: *mut f64,
) {
    outcome_getter("cntc_getmaximumtraction", ire, icp, |o, u| {
        put(ptmax, u.stress_out(o.max_traction_pa), "ptmax")
    });
}

/// `cntc_getmaximumtemperature`: the largest surface temperatures (H = 3).
#[no_mangle]
pub unsafe extern "C" fn cntc_getmaximumtemperature(
    ire: *const c_int,
    icp: *const c_int,
    t1max: *mut f64,
    t2max: *mut f64,
) {
    outcome_getter("cntc_getmaximumtemperature", ire, icp, |o, u| {
        outputs(&[(t1max.is_null(), "t1max"), (t2max.is_null(), "t2max")])?;
        let t = o.max_temperature_k.ok_or_else(|| {
            CntcError::Input(
                "temperatures were not computed: set H = 3 with cntc_settemperaturedata".into(),
            )
        })?;
        *t1max = u.temperature_from_k(t[0]);
        *t2max = u.temperature_from_k(t[1]);
        Ok(())
    });
}

/// `cntc_getfielddata`: one field per element.
#[no_mangle]
pub unsafe extern "C" fn cntc_getfielddata(
    ire: *const c_int,
    icp: *const c_int,
    ifld: *const c_int,
    lenarr: *const c_int,
    fld: *mut f64,
) {
    outcome_getter("cntc_getfielddata", ire, icp, |o, u| {
        let (f, n) = (int(ifld, "ifld")?, len(lenarr, "lenarr")?);
        let v = getters::field_data(o, u, f)?;
        put_array(fld, n, &v, "fld")
    });
}

/// Writes fields `codes` of the patch to the arrays `outs`.
unsafe fn fields(
    o: &crate::outcome::Outcome,
    u: crate::units::Units,
    n: usize,
    codes: &[i32],
    outs: &[(*mut f64, &'static str)],
) -> Result<()> {
    if n > 0 {
        outputs(
            &outs
                .iter()
                .map(|(p, a)| (p.is_null(), *a))
                .collect::<Vec<_>>(),
        )?;
    }
    for (code, (p, arg)) in codes.iter().zip(outs) {
        put_array(*p, n, &getters::field_data(o, u, *code)?, arg)?;
    }
    Ok(())
}

/// `cntc_gettractions`: PN, PX, PY per element.
#[no_mangle]
pub unsafe extern "C" fn cntc_gettractions(
    ire: *const c_int,
    icp: *const c_int,
    lenarr: *const c_int,
    pn: *mut f64,
    px: *mut f64,
    py: *mut f64,
) {
    use crate::flags::field::{PN, PX, PY};
    outcome_getter("cntc_gettractions", ire, icp, |o, u| {
        let n = len(lenarr, "lenarr")?;
        fields(
            o,
            u,
            n,
            &[PN, PX, PY],
            &[(pn, "pn"), (px, "px"), (py, "py")],
        )
    });
}

/// `cntc_getmicroslip`: SX, SY per element.
#[no_mangle]
pub unsafe extern "C" fn cntc_getmicroslip(
    ire: *const c_int,
    icp: *const c_int,
    lenarr: *const c_int,
    sx: *mut f64,
    sy: *mut f64,
) {
    use crate::flags::field::{SX, SY};
    outcome_getter("cntc_getmicroslip", ire, icp, |o, u| {
        let n = len(lenarr, "lenarr")?;
        fields(o, u, n, &[SX, SY], &[(sx, "sx"), (sy, "sy")])
    });
}

/// `cntc_getdisplacements`: UN, UX, UY per element.
#[no_mangle]
pub unsafe extern "C" fn cntc_getdisplacements(
    ire: *const c_int,
    icp: *const c_int,
    lenarr: *const c_int,
    un: *mut f64,
    ux: *mut f64,
    uy: *mut f64,
) {
    use crate::flags::field::{UN, UX, UY};
    outcome_getter("cntc_getdisplacements", ire, icp, |o, u| {
        let n = len(lenarr, "lenarr")?;
        fields(
            o,
            u,
            n,
            &[UN, UX, UY],
            &[(un, "un"), (ux, "ux"), (uy, "uy")],
        )
    });
}

/// `cntc_getsensitivities`: dF/d(input) (S >= 2).
#[no_mangle]
pub unsafe extern "C" fn cntc_getsensitivities(
    ire: *const c_int,
    icp: *const c_int,
    lenout: *const c_int,
    lenin: *const c_int,
    sens: *mut f64,
) {
    outcome_getter("cntc_getsensitivities", ire, icp, |o, u| {
        let (no, ni) = (len(lenout, "lenout")?, len(lenin, "lenin")?);
        let v = getters::sensitivities(o, u, no, ni)?;
        put_array(sens, no * ni, &v, "sens")
    });
}

/// `cntc_getcalculationtime`: time spent in calculations since the last
/// reset \[s\] (CPU, wall: both the calculations' wall time).
#[no_mangle]
pub unsafe extern "C" fn cntc_getcalculationtime(
    ire: *const c_int,
    icp: *const c_int,
    tcpu: *mut f64,
    twall: *mut f64,
) {
    run("cntc_getcalculationtime", ire, icp, || {
        let (r, c) = (int(ire, "ire")?, int(icp, "icp")?);
        outputs(&[(tcpu.is_null(), "tcpu"), (twall.is_null(), "twall")])?;
        let t = with_existing(r, |e| match e {
            Element::WheelRail(w) => Ok(w.time_s),
            Element::Basic(_) => Ok(e.patch_mut(c)?.time_s),
        })?;
        *tcpu = t;
        *twall = t;
        Ok(0)
    });
}

/// `cntc_resetcalculationtime`.
#[no_mangle]
pub unsafe extern "C" fn cntc_resetcalculationtime(ire: *const c_int, icp: *const c_int) {
    run("cntc_resetcalculationtime", ire, icp, || {
        let (r, c) = (int(ire, "ire")?, int(icp, "icp")?);
        with_existing(r, |e| {
            match e {
                Element::WheelRail(w) => w.time_s = 0.0,
                Element::Basic(_) => e.patch_mut(c)?.time_s = 0.0,
            }
            Ok(0)
        })
    });
}

// ---------------------------------------------------------------------
// Finalisation.

/// `cntc_finalize`: forgets result element `ire`.
#[no_mangle]
pub unsafe extern "C" fn cntc_finalize(ire: *const c_int) {
    run("cntc_finalize", ire, std::ptr::null(), || {
        Library::get().finalize(int(ire, "ire")?).map(|_| 0)
    });
}

/// `cntc_finalizelast`: forgets every result element.
#[no_mangle]
pub extern "C" fn cntc_finalizelast() {
    // SAFETY: no pointers are read.
    unsafe {
        run(
            "cntc_finalizelast",
            std::ptr::null(),
            std::ptr::null(),
            || {
                Library::get().finalize_all();
                Ok(0)
            },
        );
    }
}
