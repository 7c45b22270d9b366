//! CONTACT's "magic numbers": the codes of `cntc_setflags`,
//! `cntc_setglobalflags`, `cntc_setmetadata` and `cntc_getfielddata`, and
//! the error codes a call returns in `ierror`. The values are CONTACT's
//! (its `caddon_flags.inc`, `python_intfc/cntc_getmagicnumbers.py`), so
//! that a caller's existing constants keep working; `include/contact_addon.h`
//! gives them to C callers.

/// Unit convention flag (values [`UN_CNTC`], [`UN_SPCK`], [`UN_SI`]).
pub const IF_UNITS: i32 = 1933;
/// CONTACT's units: mm, mm/s, N, N/mm², forces on body 1.
pub const UN_CNTC: i32 = 1934;
/// SIMPACK's units: m, m/s, N, Pa, forces on body 2 (the wheel).
pub const UN_SPCK: i32 = 1935;
/// SI units: m, m/s, N, Pa, forces on body 1.
pub const UN_SI: i32 = 1936;
/// Imperial units (CONTACT has none either): refused.
pub const UN_IMPER: i32 = 1937;

/// C1 digit: configuration (0 left rail, 1 right rail, 4/5 rollers).
pub const IC_CONFIG: i32 = 1967;
/// P digit: previous time (0 continuation, 2 first case).
pub const IC_PVTIME: i32 = 1970;
/// B digit: traction bound.
pub const IC_BOUND: i32 = 1971;
/// T digit: tangential problem (0 frictionless, 1 shift, 2 transient
/// rolling, 3 steady rolling).
pub const IC_TANG: i32 = 1972;
/// N digit: normal problem (module 1: 0 position, 1 vertical force;
/// module 3: 0 approach, 1 normal force).
pub const IC_NORM: i32 = 1973;
/// F digit: tangential forces instead of creepages.
pub const IC_FORCE: i32 = 1974;
/// L digit (read with `cntc_getflags`).
pub const IC_FRCLAW: i32 = 1976;
/// D digit: discretisation of module 1.
pub const IC_DISCNS: i32 = 1977;
/// C3 digit: influence coefficients.
pub const IC_INFLCF: i32 = 1978;
/// M digit (read with `cntc_getflags`; set with
/// `cntc_setmaterialparameters`).
pub const IC_MATER: i32 = 1979;
/// E digit: extra rigid slip.
pub const IC_EXRHS: i32 = 1980;
/// X: debug output codes.
pub const IC_XFLOW: i32 = 1981;
/// H digit (read with `cntc_getflags`).
pub const IC_HEAT: i32 = 1982;
/// I digit: initial estimate.
pub const IC_IESTIM: i32 = 1983;
/// O digit: output to the out-file.
pub const IC_OUTPUT: i32 = 1984;
/// W digit: flow output.
pub const IC_FLOW: i32 = 1985;
/// R digit: 0-1 solve, 2-3 check only.
pub const IC_RETURN: i32 = 1986;
/// A digit: mat-file.
pub const IC_MATFIL: i32 = 1987;
/// S2 digit: sensitivities.
pub const IC_SENS: i32 = 1988;
/// IF_METH of the conformal influence coefficients (C3 = 4).
pub const IC_IFMETH: i32 = 1989;
/// VARIANT of the conformal influence coefficients (C3 = 4).
pub const IC_IFVARI: i32 = 1990;
/// O_s digit: subsurface output to the out-file.
pub const IC_SBSOUT: i32 = 1991;
/// A_s digit: subs-file.
pub const IC_SBSFIL: i32 = 1992;
/// Largest number of elements of a potential contact area (module 1).
pub const IC_NPOMAX: i32 = 1993;

/// `cntc_readinpfile`'s `inp_type`: a module 1 input file.
pub const INP_MODUL1: i32 = 1988;
/// `cntc_readinpfile`'s `inp_type`: the input file of CONTACT's Simpack
/// user routine.
pub const INP_SPCK: i32 = 1990;

/// Print level of the library itself (global).
pub const IF_IDEBUG: i32 = 2000;
/// Licence tracing (global; there is no licence).
pub const IF_LICDBG: i32 = 2001;
/// Writing a CONTACT input file (not written by this library).
pub const IF_WRTINP: i32 = 2002;
/// Threads per contact problem (global).
pub const IF_OPENMP: i32 = 2003;
/// Timer output level (global).
pub const IF_TIMERS: i32 = 2004;
/// Case number of a result element.
pub const IF_NCASE: i32 = 2005;
/// This library's own global flag: where calculations run. Value
/// [`MODE_IN_PROCESS`] (the default) or [`MODE_SERVER`].
pub const IF_MODE: i32 = 2099;
/// [`IF_MODE`] value: solve in this process.
pub const MODE_IN_PROCESS: i32 = 0;
/// [`IF_MODE`] value: forward to a railcontact server.
pub const MODE_SERVER: i32 = 1;

/// `cntc_getfielddata` codes.
pub mod field {
    /// Undeformed distance h \[length\].
    pub const H: i32 = 1;
    /// Friction coefficient \[-\].
    pub const MU: i32 = 2;
    /// Traction px \[force/area\].
    pub const PX: i32 = 3;
    /// Traction py \[force/area\].
    pub const PY: i32 = 4;
    /// Pressure pn \[force/area\].
    pub const PN: i32 = 5;
    /// Displacement difference ux \[length\].
    pub const UX: i32 = 7;
    /// Displacement difference uy \[length\].
    pub const UY: i32 = 8;
    /// Displacement difference un \[length\].
    pub const UN: i32 = 9;
    /// Critical shear stress of an interfacial layer \[force/area\].
    pub const TAUCRT: i32 = 11;
    /// Plastic deformation x \[length\].
    pub const UPLSX: i32 = 12;
    /// Plastic deformation y \[length\].
    pub const UPLSY: i32 = 13;
    /// Micro-slip sx \[-\] (shift: \[length\]).
    pub const SX: i32 = 15;
    /// Micro-slip sy.
    pub const SY: i32 = 16;
    /// Surface temperature of body 1 \[C or K\].
    pub const TEMP1: i32 = 20;
    /// Surface temperature of body 2.
    pub const TEMP2: i32 = 21;
    /// Extra rigid slip wx \[-\].
    pub const WX: i32 = 22;
    /// Extra rigid slip wy \[-\].
    pub const WY: i32 = 23;
}

/// `cntc_setmetadata` codes (stored, not used in the calculation).
pub mod meta {
    /// Simulation time.
    pub const TIM: i32 = 2011;
    /// x of the contact point on the rail.
    pub const XR: i32 = 2012;
    /// y of the contact point on the rail.
    pub const YR: i32 = 2013;
    /// x of the contact point on the wheel.
    pub const XW: i32 = 2014;
    /// y of the contact point on the wheel.
    pub const YW: i32 = 2015;
    /// Wheel position along the track.
    pub const SW: i32 = 2016;
    /// Run number.
    pub const RUN: i32 = 2021;
    /// Axle number.
    pub const AXLE: i32 = 2022;
    /// Side number.
    pub const SIDE: i32 = 2023;
}

/// Error codes returned in `ierror` (negative), CONTACT's values; a
/// positive `ierror` of `cntc_calculate` counts the contact elements on the
/// border of the potential contact area (a warning: the patch may be cut).
pub mod err {
    /// No licence (never returned: there is none).
    pub const ALLOW: i32 = -12;
    /// Failure in the contact search.
    pub const SEARCH: i32 = -25;
    /// No solution of the total force iteration.
    pub const FTOT: i32 = -26;
    /// No convergence of the normal problem.
    pub const NORM: i32 = -27;
    /// No convergence of the tangential problem.
    pub const TANG: i32 = -28;
    /// Iteration stopped with the residual above the tolerance.
    pub const TOL: i32 = -29;
    /// Invalid ire/icp combination.
    pub const ICP: i32 = -31;
    /// A wheel or rail profile could not be read.
    pub const PROFIL: i32 = -32;
    /// Invalid friction parameters.
    pub const FRCLAW: i32 = -33;
    /// Invalid discretisation parameters.
    pub const DISCR: i32 = -34;
    /// Error reading an input file.
    pub const INPUT: i32 = -39;
    /// This library's own: the call asks for a flag value or method this
    /// library does not have (the log names it).
    pub const NOT_SUPPORTED: i32 = -40;
    /// This library's own: a null pointer or a negative length (the log
    /// names the argument).
    pub const ARGUMENT: i32 = -41;
    /// This library's own: the railcontact server could not be reached
    /// (server mode; the next call reconnects).
    pub const SERVER: i32 = -42;
    /// Other error.
    pub const OTHER: i32 = -99;
    /// Result element number out of range \[1, 999\] (CONTACT's -101).
    pub const IRE: i32 = -101;
}
