//! CONTACT's input files for a wheel on its rail, as `cntc_readinpfile`
//! reads them: a module 1 file (`CNTC_inp_modul1`, its first case) and the
//! file of CONTACT's Simpack user routine (`CNTC_inp_spck`). Values are in
//! CONTACT's units (mm, N, N/mm², mm/s, rad) whatever the element's unit
//! convention, as CONTACT writes them straight into its own data.
//!
//! [`parse`] reads a file's text into a [`WheelRailInp`]: the control
//! digits and each section the digits ask for, its values as the
//! corresponding `cntc_set*` call takes them, with its line number.
//! [`WheelRailInp::calls`] turns it into those calls ([`Call`]), which the
//! library applies to the element as it applies a caller's: one
//! conversion and validation for both, and a forwarding library sends
//! them to its server as any other calls.
//!
//! The line format is CONTACT's (`m_readline`): blank lines and lines
//! starting with `%` are skipped; values are separated by blanks, tabs,
//! commas or `=`; `%` starts a comment; whatever follows the values a line
//! is read for is ignored (the names CONTACT's files put there); a line
//! with too few values continues on the next line. Integers, reals
//! (Fortran's `1d-5` too), angles (`90d` in degrees, `0.1r` or plain in
//! radians) and strings in single quotes.

use std::path::Path;

use thiserror::Error;

use crate::call::Call;
use crate::config::Digits;
use crate::flags;
use crate::module1::{read_profile_file, read_slice_files};
use crate::subsurface;

/// The kinds of input file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InpType {
    /// `CNTC_inp_modul1` (1988): a module 1 input file, its first case.
    Module1,
    /// `CNTC_inp_spck` (1990): the input file of CONTACT's Simpack user
    /// routine (module number 11: no rail deviations, positions or
    /// velocities, which Simpack gives; 0: with them).
    Simpack,
}

impl InpType {
    /// The kind of `cntc_readinpfile`'s `inp_type` code.
    pub fn from_code(code: i32) -> Option<InpType> {
        match code {
            flags::INP_MODUL1 => Some(InpType::Module1),
            flags::INP_SPCK => Some(InpType::Simpack),
            _ => None,
        }
    }
}

/// What is wrong in an input file, and on which line.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error("line {line}: {message}")]
pub struct InpError {
    /// The line (1-based).
    pub line: usize,
    /// What is wrong, with the value read.
    pub message: String,
}

/// A section's values and the line they were read from (the last line,
/// when they continue over several).
#[derive(Debug, Clone, PartialEq)]
pub struct Lined<T> {
    /// The line (1-based).
    pub line: usize,
    /// The values.
    pub value: T,
}

/// The control digits of a module 1 case (`C-P-B-T-N-F-S`,
/// `V-L-D-C-M-Z-E [M2]`, `X-H-G-I-A-O-W-R`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct InpDigits {
    /// C1: 0 left, 1 right rail; 4, 5 roller rigs.
    pub config: i32,
    /// P.
    pub pvtime: i32,
    /// B.
    pub bound: i32,
    /// T.
    pub tang: i32,
    /// N: 0 position z, 1 vertical force.
    pub norm: i32,
    /// F1: 0 VPITCH, 1 FX_WS, 2 MY_WS, 3 massless rails.
    pub force: i32,
    /// S: subsurface stresses.
    pub stress: i32,
    /// V: friction variation.
    pub varfrc: i32,
    /// L: friction law (1 keeps the previous one).
    pub frclaw: i32,
    /// D: discretisation (0, 1 keep the previous one).
    pub discns: i32,
    /// C3: influence coefficients (0, 1 keep the material).
    pub inflcf: i32,
    /// M: material model.
    pub mater: i32,
    /// Z1: track data.
    pub ztrack: i32,
    /// E1: wheelset data.
    pub ewheel: i32,
    /// M2: damping (1 keeps the previous one).
    pub mater2: i32,
    /// Gap weighting (the tens of the M2 value).
    pub gapwgt: i32,
    /// X: debug output.
    pub xflow: i32,
    /// H: temperature.
    pub heat: i32,
    /// G: solver (1 keeps the previous parameters).
    pub gausei: i32,
    /// I.
    pub iestim: i32,
    /// A.
    pub matfil: i32,
    /// O.
    pub output: i32,
    /// W.
    pub flow: i32,
    /// R.
    pub ret: i32,
}

/// A profile line: file name and options, as `cntc_setprofileinputfname`
/// takes them.
#[derive(Debug, Clone, PartialEq)]
pub struct ProfileRef {
    /// The file name as written (relative: to the input file's folder).
    pub fname: String,
    /// `iparam`: ITYPE, 0, MIRRORY, MIRRORZ, and with extra options
    /// ERRHND, ISMOOTH.
    pub iparam: Vec<i32>,
    /// `rparam`: SCALE, SMOOTH, and with extra options F_MAX_OMIT,
    /// ZIG_THRS, KINK_HIGH, KINK_LOW, KINK_WID.
    pub rparam: Vec<f64>,
}

/// G != 1: the solver's parameters, as `cntc_setsolverflags` takes them.
#[derive(Debug, Clone, PartialEq)]
pub struct SolverInp {
    /// `iparam`: MAXGS, MAXIN, MAXNR, MAXOUT {, INISLP or KDOWFB}.
    pub ints: Vec<i32>,
    /// `rparam`: EPS and the G digit's reals.
    pub reals: Vec<f64>,
}

/// A control digit's check: its line, name, value and allowed ranges.
type DigitCheck<'a> = (usize, &'a str, i32, &'a [(i32, i32)]);

/// A wheel/rail case read from an input file: each section present when
/// the digits ask for it, its values as the `cntc_set*` call that sets
/// them takes them (CONTACT's units).
#[derive(Debug, Clone, PartialEq)]
pub struct WheelRailInp {
    /// The kind of file.
    pub kind: InpType,
    /// The control digits (a Simpack file's reverted ones replaced).
    pub digits: Lined<InpDigits>,
    /// What the digits ask for that no `cntc_set*` call carries and this
    /// library does not have, refused as `CNTC_err_notsupported` before
    /// anything is applied: a gap weighting, a new M digit without its
    /// material parameters (C3 = 0, 1).
    pub unsupported: Option<Lined<String>>,
    /// G: the solver's parameters.
    pub solver: Option<Lined<SolverInp>>,
    /// V, L: `cntc_setfrictionmethod`'s `params`.
    pub friction: Option<Lined<Vec<f64>>>,
    /// C3, M: `cntc_setmaterialparameters`'s `rparam` (POISS 1, 2, GG 1,
    /// 2 and the model's).
    pub material: Option<Lined<Vec<f64>>>,
    /// M2 = 2: CDAMPN, CDAMPT, DFNMAX, DFTMAX.
    pub damping: Option<Lined<Vec<f64>>>,
    /// H = 3: `cntc_settemperaturedata`'s `params`.
    pub heat: Option<Lined<Vec<f64>>>,
    /// D >= 2: DX, DS, A_SEP, D_SEP, D_COMB {, D_TURN {, G_MISS}}
    /// (`cntc_setpotcontact`, IPOTCN = -1) and DQREL.
    pub discretisation: Option<Lined<(Vec<f64>, f64)>>,
    /// Z1 = 1, 3: `cntc_settrackdimensions` Z = 1's `params`.
    pub track: Option<Lined<Vec<f64>>>,
    /// Z1 = 3: the rail profile.
    pub rail_profile: Option<Lined<ProfileRef>>,
    /// Z1 = 2, 3 (but Simpack files of module 11): the rail deviations DY, DZ, ROLL, VY,
    /// VZ, VROLL.
    pub rail_deviations: Option<Lined<Vec<f64>>>,
    /// The massless rail's KY_RAIL, FY_RAIL, KZ_RAIL, FZ_RAIL {, DYSTEP0}
    /// (Z = 2, 3 with F = 3).
    pub massless_rail: Option<Lined<Vec<f64>>>,
    /// E1 = 3, 5: FBDIST, FBPOS, NOMRAD {, YTAPE}.
    pub wheelset: Option<Lined<Vec<f64>>>,
    /// E1 = 3, 5: the wheel profile.
    pub wheel_profile: Option<Lined<ProfileRef>>,
    /// E1 = 1-5 (but Simpack files of module 11): S, Y, Z (N = 0) or FZ (N = 1), ROLL,
    /// YAW, PITCH.
    pub position: Option<Lined<[f64; 6]>>,
    /// E1 = 2-5 (but Simpack files of module 11): VS, VY, VZ, VROLL, VYAW, and VPITCH (F
    /// = 0, 3) or FX_WS (F = 1) or MY_WS (F = 2).
    pub velocity: Option<Lined<[f64; 6]>>,
    /// E1 = 4, 5: the wheel's position and velocity deviations.
    pub wheel_deviations: Option<Lined<Vec<f64>>>,
    /// S = 3: the blocks of subsurface points (each as `subs_addblock`
    /// takes it), replacing the element's; S = 1, 2 keep them (S = 2's
    /// A and O digits of the subsurface output are read and not used: the
    /// library writes no files). `subs_calculate` computes the stresses.
    pub subsurface: Option<Lined<Vec<SubsBlockInp>>>,
}

/// What an element holds that a file may leave as it is: the digits a
/// Simpack file may not change, and the values a file does not give (Z_WS
/// under N = 1, VPITCH under F = 1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Held {
    /// The element's digits.
    pub digits: Digits,
    /// Z_WS \[mm\].
    pub z_mm: f64,
    /// VPITCH \[rad/s\].
    pub vpitch: f64,
}

// ---------------------------------------------------------------------
// Lines and values.

/// Values read from a line, by type, in order (CONTACT's `ints`, `dbles`
/// (reals and angles) and `strngs`), and how many were read.
#[derive(Debug, Default)]
struct Values {
    ints: Vec<i32>,
    reals: Vec<f64>,
    strs: Vec<String>,
    n: usize,
    line: usize,
}

impl Values {
    fn lined<T>(&self, value: T) -> Lined<T> {
        Lined {
            line: self.line,
            value,
        }
    }
}

/// A file's lines, read in order.
struct Reader<'a> {
    lines: std::iter::Enumerate<std::str::Lines<'a>>,
    line: usize,
}

/// The words of a line: its text before a `%` outside quotes, commas as
/// blanks, split at blanks, tabs and `=` outside quoted strings.
fn words(text: &str) -> Vec<String> {
    let mut in_str = false;
    let mut end = text.len();
    for (i, c) in text.char_indices() {
        if c == '\'' {
            in_str = !in_str;
        } else if c == '%' && !in_str {
            end = i;
            break;
        }
    }
    let mut out = Vec::new();
    let mut cur = String::new();
    let mut in_str = false;
    for c in text[..end].chars().map(|c| if c == ',' { ' ' } else { c }) {
        if in_str {
            cur.push(c);
            in_str = c != '\'';
        } else if c == ' ' || c == '\t' || c == '=' {
            if !cur.is_empty() {
                out.push(std::mem::take(&mut cur));
            }
        } else {
            in_str = c == '\'' && cur.is_empty();
            cur.push(c);
        }
    }
    if !cur.is_empty() {
        out.push(cur);
    }
    out
}

/// A Fortran real: `1.5`, `82000.`, `1e-5`, `1d-5`, `0`.
fn real(w: &str) -> Option<f64> {
    let first = w.chars().next()?;
    if !(first.is_ascii_digit() || matches!(first, '+' | '-' | '.')) {
        return None;
    }
    w.replace(['d', 'D'], "e")
        .parse::<f64>()
        .ok()
        .filter(|x| x.is_finite())
}

/// An angle: a real, in degrees when it ends in `d`, radians otherwise
/// (an `r` at the end allowed).
fn angle(w: &str) -> Option<f64> {
    match w.char_indices().last()? {
        (i, 'd' | 'D') => real(&w[..i]).map(|x| x * std::f64::consts::PI / 180.0),
        (i, 'r' | 'R') => real(&w[..i]),
        _ => real(w),
    }
}

/// A string in single quotes.
fn quoted(w: &str) -> Option<String> {
    (w.len() >= 2 && w.starts_with('\'') && w.ends_with('\''))
        .then(|| w[1..w.len() - 1].to_string())
}

impl<'a> Reader<'a> {
    fn new(text: &'a str) -> Self {
        Reader {
            lines: text.lines().enumerate(),
            line: 0,
        }
    }

    fn error(&self, message: impl Into<String>) -> InpError {
        InpError {
            line: self.line,
            message: message.into(),
        }
    }

    /// The words of the next line that has any.
    fn next_words(&mut self, what: &str) -> Result<Vec<String>, InpError> {
        for (i, text) in self.lines.by_ref() {
            self.line = i + 1;
            let w = words(text);
            if !w.is_empty() {
                return Ok(w);
            }
        }
        self.line += 1;
        Err(self.error(format!("the file ends where {what} is expected")))
    }

    /// Reads `what`: the values of `types` (`i` integer, `d` real, `a`
    /// angle, `s` quoted string; upper case: optional, after the
    /// mandatory ones), from as many lines as the mandatory values take.
    fn read(&mut self, what: &str, types: &str) -> Result<Values, InpError> {
        let types: Vec<char> = types.chars().collect();
        let required = types.iter().filter(|c| c.is_ascii_lowercase()).count();
        let mut v = Values::default();
        while v.n < required {
            let words = self.next_words(what)?;
            v.line = self.line;
            for w in &words {
                let Some(&t) = types.get(v.n) else { break };
                let (ok, kind) = match t.to_ascii_lowercase() {
                    'i' => (
                        w.parse::<i32>().map(|x| v.ints.push(x)).is_ok(),
                        "an integer",
                    ),
                    'd' => (real(w).map(|x| v.reals.push(x)).is_some(), "a number"),
                    'a' => (angle(w).map(|x| v.reals.push(x)).is_some(), "an angle"),
                    _ => (
                        quoted(w).map(|x| v.strs.push(x)).is_some(),
                        "a string in single quotes",
                    ),
                };
                if !ok {
                    if v.n >= required {
                        break;
                    }
                    return Err(self.error(format!(
                        "expected {what}: value {} \"{w}\" is not {kind}",
                        v.n + 1
                    )));
                }
                v.n += 1;
            }
        }
        Ok(v)
    }
}

/// Checks that digit or value `name` = `v` lies in one of `ranges`.
fn check<T: PartialOrd + std::fmt::Display + Copy>(
    line: usize,
    name: &str,
    v: T,
    ranges: &[(T, T)],
) -> Result<(), InpError> {
    if ranges.iter().any(|&(lo, hi)| lo <= v && v <= hi) {
        return Ok(());
    }
    let allowed: Vec<String> = ranges
        .iter()
        .map(|(lo, hi)| {
            if lo == hi {
                lo.to_string()
            } else {
                format!("{lo} to {hi}")
            }
        })
        .collect();
    Err(InpError {
        line,
        message: format!("{name} = {v} is out of range ({})", allowed.join(" or ")),
    })
}

/// The `N` decimal digits of `v`, most significant first (the first takes
/// whatever is above).
fn digits_of<const N: usize>(v: i32) -> [i32; N] {
    std::array::from_fn(|k| {
        let p = 10i32.pow((N - 1 - k) as u32);
        if k == 0 {
            v / p
        } else {
            (v / p) % 10
        }
    })
}

// ---------------------------------------------------------------------
// The file.

/// Reads an input file's text: the module number, the control digits and
/// the sections they ask for. `held` gives the digits a Simpack file may
/// not change. `Ok` also holds the warnings (digits reverted or
/// adjusted, as CONTACT warns of them).
pub fn parse(
    text: &str,
    kind: InpType,
    held: &Held,
) -> Result<(WheelRailInp, Vec<String>), InpError> {
    let mut r = Reader::new(text);
    let mut warnings = Vec::new();
    let m = r.read("the module number", "i")?;
    let module = m.ints[0];
    let ok = match kind {
        InpType::Module1 => module == 1,
        InpType::Simpack => module == 0 || module == 11,
    };
    if !ok {
        return Err(InpError {
            line: m.line,
            message: format!(
                "module number {module}: {}",
                match kind {
                    InpType::Module1 => "a module 1 input file (CNTC_inp_modul1) starts with 1",
                    InpType::Simpack => "a Simpack input file (CNTC_inp_spck) starts with 0 or 11",
                }
            ),
        });
    }
    let (digits, unsupported) = read_digits(&mut r, kind, held, &mut warnings)?;
    let d = digits.value;
    let mut inp = WheelRailInp {
        kind,
        unsupported,
        digits,
        solver: None,
        friction: None,
        material: None,
        damping: None,
        heat: None,
        discretisation: None,
        track: None,
        rail_profile: None,
        rail_deviations: None,
        massless_rail: None,
        wheelset: None,
        wheel_profile: None,
        position: None,
        velocity: None,
        wheel_deviations: None,
        subsurface: None,
    };
    if d.gausei != 1 {
        inp.solver = Some(read_solver(&mut r, d.gausei)?);
    }
    if d.frclaw != 1 {
        inp.friction = Some(read_friction(&mut r, d.varfrc, d.frclaw)?);
    }
    if (2..=4).contains(&d.inflcf) {
        inp.material = Some(read_material(&mut r, &d)?);
    }
    if d.mater2 >= 2 {
        let v = r.read(
            "the damping parameters CDAMPN, CDAMPT, DFNMAX, DFTMAX",
            "dddd",
        )?;
        for (name, x) in ["CDAMPN", "CDAMPT", "DFNMAX", "DFTMAX"]
            .iter()
            .zip(&v.reals)
        {
            check(v.line, name, *x, &[(0.0, 1e20)])?;
        }
        inp.damping = Some(v.lined(v.reals.clone()));
    }
    if d.heat == 3 {
        inp.heat = Some(read_heat(&mut r, d.mater)?);
    }
    if (2..=9).contains(&d.discns) {
        inp.discretisation = Some(read_discretisation(&mut r)?);
    }
    // CONTACT reads a Simpack file of module number 11 without the rail
    // deviations and the wheelset's position and velocity; one of module
    // number 0 with them, as a module 1 file.
    let kinematics = !(kind == InpType::Simpack && module == 11);
    read_track(&mut r, &d, kinematics, &mut inp)?;
    read_wheelset(&mut r, &d, kinematics, &mut inp)?;
    if d.stress >= 2 {
        inp.subsurface = read_subsurface(&mut r, d.stress)?;
    }
    Ok((inp, warnings))
}

/// One block of subsurface points read from an input file: ISUBS and the
/// `xparam`, `yparam`, `zparam` of `subs_addblock`.
#[derive(Debug, Clone, PartialEq)]
pub struct SubsBlockInp {
    /// ISUBS: 1-3 (z regular), 5-7 (z listed) with all, a regular or a
    /// listed selection of the grid's elements; 9: x, y and z listed.
    pub isubs: i32,
    /// `xparam`: IXL, IXINC, IXH (ISUBS = 2, 6), IX (3, 7), X (9).
    pub x: Vec<f64>,
    /// `yparam`: as `x`, in y.
    pub y: Vec<f64>,
    /// `zparam`: NZ, ZL, DZ (ISUBS = 1-3), Z (5-7, 9).
    pub z: Vec<f64>,
}

/// S >= 2: the A and O digits of the subsurface output, then (S = 3) the
/// blocks up to ISUBS = 0 (at most [`subsurface::MAX_BLOCKS`]), the
/// lists sorted (the element numbers also without repeats), as CONTACT
/// reads them (user guide, "Subsurface-stress input"). `None` for S = 2.
fn read_subsurface(
    r: &mut Reader,
    stress: i32,
) -> Result<Option<Lined<Vec<SubsBlockInp>>>, InpError> {
    let ao = r.read("the A, O digits of the subsurface output", "ii")?;
    if stress < 3 {
        return Ok(None);
    }
    let first = r.read("the subsurface input option ISUBS", "i")?;
    let mut isubs = first.ints[0];
    let mut blocks = Vec::new();
    while isubs != 0 {
        let line = r.line;
        check(line, "ISUBS", isubs, &[(1, 3), (5, 7), (9, 9)])?;
        if blocks.len() == subsurface::MAX_BLOCKS {
            return Err(InpError {
                line,
                message: format!(
                    "more than {} blocks of subsurface points",
                    subsurface::MAX_BLOCKS
                ),
            });
        }
        blocks.push(read_subsurface_block(r, isubs)?);
        isubs = r.read("the subsurface input option ISUBS", "i")?.ints[0];
    }
    Ok(Some(ao.lined(blocks)))
}

/// A count NX, NY or NZ of subsurface points at `line`: 1 to
/// [`subsurface::MAX_LIST`].
fn subs_count(line: usize, name: &str, n: i32) -> Result<usize, InpError> {
    check(line, name, n, &[(1, subsurface::MAX_LIST as i32)])?;
    Ok(n as usize)
}

/// `n` numbers (`what`), sorted; without repeats when `unique`.
fn sorted_list(r: &mut Reader, what: &str, n: usize, unique: bool) -> Result<Vec<f64>, InpError> {
    let mut v = r.read(what, &"d".repeat(n))?.reals;
    v.sort_by(f64::total_cmp);
    if unique {
        v.dedup();
    }
    Ok(v)
}

/// One block after its ISUBS: the selection of grid elements (ISUBS 2, 3,
/// 6, 7), the z values (1-7), or the x, y and z lists (9).
fn read_subsurface_block(r: &mut Reader, isubs: i32) -> Result<SubsBlockInp, InpError> {
    let mut b = SubsBlockInp {
        isubs,
        x: Vec::new(),
        y: Vec::new(),
        z: Vec::new(),
    };
    match isubs {
        2 | 6 => {
            let range = |r: &mut Reader, what: &str| {
                r.read(what, "iii")
                    .map(|v| v.ints.iter().map(|&i| f64::from(i)).collect::<Vec<f64>>())
            };
            b.x = range(r, "the grid columns IXL, IXINC, IXH")?;
            b.y = range(r, "the grid rows IYL, IYINC, IYH")?;
        }
        3 | 7 => {
            let v = r.read("the numbers of grid columns and rows NX, NY", "ii")?;
            let nx = subs_count(v.line, "NX", v.ints[0])?;
            let ny = subs_count(v.line, "NY", v.ints[1])?;
            b.x = sorted_list(r, "the grid columns IX(1..NX)", nx, true)?;
            b.y = sorted_list(r, "the grid rows IY(1..NY)", ny, true)?;
        }
        _ => {}
    }
    match isubs {
        1..=3 => {
            let v = r.read("the points in z NZ, ZL, DZ", "idd")?;
            let nz = subs_count(v.line, "NZ", v.ints[0])?;
            b.z = vec![nz as f64, v.reals[0], v.reals[1]];
        }
        5..=7 => {
            let v = r.read("the number of points in z NZ", "i")?;
            let nz = subs_count(v.line, "NZ", v.ints[0])?;
            b.z = sorted_list(r, "the z coordinates Z(1..NZ)", nz, false)?;
        }
        _ => {
            let v = r.read("the numbers of points NX, NY, NZ", "iii")?;
            let nx = subs_count(v.line, "NX", v.ints[0])?;
            let ny = subs_count(v.line, "NY", v.ints[1])?;
            let nz = subs_count(v.line, "NZ", v.ints[2])?;
            b.x = sorted_list(r, "the x coordinates X(1..NX)", nx, false)?;
            b.y = sorted_list(r, "the y coordinates Y(1..NY)", ny, false)?;
            b.z = sorted_list(r, "the z coordinates Z(1..NZ)", nz, false)?;
        }
    }
    Ok(b)
}

/// The three (four with X = 1) lines of control digits, checked as
/// CONTACT checks a module 1 case's; a Simpack file's digits C1, P, N,
/// F1, H, S and I reverted to the element's, and T, S, Z1, E1 limited;
/// and what they ask for that the library does not have
/// ([`unsupported_digits`]).
fn read_digits(
    r: &mut Reader,
    kind: InpType,
    held: &Held,
    warnings: &mut Vec<String>,
) -> Result<(Lined<InpDigits>, Option<Lined<String>>), InpError> {
    let what1 = "the control digits C-P-B-T-N-F-S (an integer of 7 digits)";
    let v1 = r.read(what1, "i")?;
    let v2 = r.read(
        "the control digits V-L-D-C-M-Z-E (an integer of 7 digits) {and M2}",
        "iI",
    )?;
    let v3 = r.read(
        "the control digits H-G-I-A-O-W-R (an integer of 7 or 8 digits)",
        "i",
    )?;
    for v in [&v1, &v2, &v3] {
        if v.ints[0] < 0 {
            return Err(InpError {
                line: v.line,
                message: format!("control digits {}: must not be negative", v.ints[0]),
            });
        }
    }
    let [c, p, b, t, n, f, s] = digits_of::<7>(v1.ints[0]);
    let [vv, l, dd, c3, m, z, e] = digits_of::<7>(v2.ints[0]);
    let [x, h, g, i, a, o, w, rr] = digits_of::<8>(v3.ints[0]);
    let (gapwgt, mater2) = match v2.ints.get(1) {
        Some(&m2) => (m2 / 10, m2 % 10),
        None => (0, 1),
    };
    if x >= 1 {
        // The debug digits P-S-F-L-C-I-N {READLN}: CONTACT's own output.
        r.read("the debug digits P-S-F-L-C-I-N", "iI")?;
    }
    let mut d = InpDigits {
        config: c,
        pvtime: p,
        bound: b,
        tang: t,
        norm: n,
        force: f,
        stress: s,
        varfrc: vv,
        frclaw: l,
        discns: dd,
        inflcf: c3,
        mater: m,
        ztrack: z,
        ewheel: e,
        mater2,
        gapwgt,
        xflow: x,
        heat: h,
        gausei: g,
        iestim: i,
        matfil: a,
        output: o,
        flow: w,
        ret: rr,
    };
    if kind == InpType::Simpack {
        let h = &held.digits;
        // CONTACT's stress digit S is not an element's digit here: 0.
        let reverts: [(usize, &str, &mut i32, i32, bool); 7] = [
            (v1.line, "C1 (CONFIG)", &mut d.config, h.config, false),
            (v1.line, "P (PVTIME)", &mut d.pvtime, h.pvtime, true),
            (v1.line, "N (NORM)", &mut d.norm, h.norm, true),
            (v1.line, "F1 (FORCE)", &mut d.force, h.force, true),
            (v3.line, "H (HEAT)", &mut d.heat, h.heat, true),
            (v1.line, "S (STRESS)", &mut d.stress, 0, true),
            (v3.line, "I (IESTIM)", &mut d.iestim, h.iestim, false),
        ];
        for (line, name, digit, was, tell) in reverts {
            if *digit != was {
                if tell {
                    warnings.push(format!(
                        "line {line}: control digit {name} = {} cannot be changed through the \
                         Simpack input file; it stays {was}",
                        *digit
                    ));
                }
                *digit = was;
            }
        }
    }
    let checks: [DigitCheck; 24] = [
        (v1.line, "control digit C1", d.config, &[(0, 1), (4, 5)]),
        (v1.line, "control digit P", d.pvtime, &[(0, 3)]),
        (v1.line, "control digit B", d.bound, &[(0, 1), (5, 6)]),
        (v1.line, "control digit T", d.tang, &[(0, 3)]),
        (v1.line, "control digit N", d.norm, &[(0, 1)]),
        (v1.line, "control digit F1", d.force, &[(0, 1), (3, 3)]),
        (v1.line, "control digit S", d.stress, &[(0, 3)]),
        (v2.line, "control digit V", d.varfrc, &[(0, 2)]),
        (v2.line, "control digit L", d.frclaw, &[(0, 4), (6, 6)]),
        (v2.line, "control digit D", d.discns, &[(0, 9)]),
        (v2.line, "control digit C3", d.inflcf, &[(0, 4)]),
        (v2.line, "control digit M", d.mater, &[(0, 7)]),
        (v2.line, "control digit Z1", d.ztrack, &[(0, 3)]),
        (v2.line, "control digit E1", d.ewheel, &[(0, 5)]),
        (
            v2.line,
            "the gap weighting (tens of M2)",
            d.gapwgt,
            &[(0, 2)],
        ),
        (v2.line, "control digit M2", d.mater2, &[(0, 9)]),
        (v3.line, "control digit X", d.xflow, &[(0, 1)]),
        (v3.line, "control digit H", d.heat, &[(0, 1), (3, 3)]),
        (v3.line, "control digit G", d.gausei, &[(0, 5)]),
        (v3.line, "control digit I", d.iestim, &[(0, 3)]),
        (v3.line, "control digit A", d.matfil, &[(0, 2)]),
        (v3.line, "control digit O", d.output, &[(0, 5)]),
        (v3.line, "control digit W", d.flow, &[(0, 9)]),
        (v3.line, "control digit R", d.ret, &[(0, 3)]),
    ];
    for (line, name, v, ranges) in checks {
        check(line, name, v, ranges)?;
    }
    if kind == InpType::Simpack {
        check(v1.line, "control digit S (Simpack)", d.stress, &[(0, 0)])?;
        check(
            v2.line,
            "control digit Z1 (Simpack)",
            d.ztrack,
            &[(0, 0), (3, 3)],
        )?;
        check(
            v2.line,
            "control digit E1 (Simpack)",
            d.ewheel,
            &[(0, 0), (3, 3)],
        )?;
    }
    if d.inflcf == 0 {
        d.inflcf = 1;
        warnings.push(format!(
            "line {}: module 1 requires new influence functions, setting C3 := 1",
            v2.line
        ));
    }
    let fail =
        |line: usize, message: String| -> Result<_, InpError> { Err(InpError { line, message }) };
    if d.force == 1 && d.norm != 1 {
        return fail(
            v1.line,
            format!("the total force F1 = 1 requires N = 1, got N = {}", d.norm),
        );
    }
    if d.mater == 1 && d.tang != 3 {
        return fail(
            v1.line,
            format!(
                "visco-elastic materials (M = 1) require steady rolling, T = 3, got T = {}",
                d.tang
            ),
        );
    }
    if d.heat >= 1 && d.tang != 3 {
        return fail(
            v3.line,
            format!(
                "temperatures (H = {}) require steady rolling, T = 3, got T = {}",
                d.heat, d.tang
            ),
        );
    }
    if d.frclaw == 6 && d.heat == 0 {
        return fail(
            v2.line,
            "temperature-dependent friction (L = 6) requires temperatures, H >= 1".into(),
        );
    }
    if d.frclaw == 1 && d.varfrc != held.digits.varfrc {
        return fail(
            v2.line,
            format!(
                "a new friction variation V = {} (was {}) needs new friction parameters, L != 1",
                d.varfrc, held.digits.varfrc
            ),
        );
    }
    let unsupported = unsupported_digits(&d, held, v2.line);
    Ok((
        Lined {
            line: v1.line,
            value: d,
        },
        unsupported,
    ))
}

/// What the digits (of the line V-L-D-C-M-Z-E `line2`) ask for that no
/// call carries and the library does not have.
fn unsupported_digits(d: &InpDigits, held: &Held, line2: usize) -> Option<Lined<String>> {
    let (line, what) = if d.gapwgt != 0 {
        (
            line2,
            format!(
                "gap weighting {} (the tens of the M2 value) is not supported; 0",
                d.gapwgt
            ),
        )
    } else if d.inflcf <= 1 && d.mater != held.digits.mater {
        (
            line2,
            format!(
            "M = {} (was {}) with C3 = {}: a new M digit is read with its material parameters, \
             C3 = 2 or 3",
            d.mater, held.digits.mater, d.inflcf
        ),
        )
    } else {
        return None;
    };
    Some(Lined { line, value: what })
}

/// G != 1: the iteration parameters, as `cntc_setsolverflags` takes them.
fn read_solver(r: &mut Reader, g: i32) -> Result<Lined<SolverInp>, InpError> {
    let v = r.read(
        "the iteration parameters MAXGS, MAXIN, MAXNR, MAXOUT, EPS {, NPOMAX}",
        "iiiidI",
    )?;
    for (k, (name, hi)) in [
        ("MAXGS", 9999),
        ("MAXIN", 999_999),
        ("MAXNR", 9999),
        ("MAXOUT", 9999),
    ]
    .iter()
    .enumerate()
    {
        check(v.line, name, v.ints[k], &[(1, *hi)])?;
    }
    // NPOMAX (ints(5)) is CONTACT's limit of its grid: not used.
    let mut ints = v.ints[..4].to_vec();
    let mut reals = vec![v.reals[0]];
    let mut line = v.line;
    match g {
        2 | 3 => {
            let w = r.read(
                "the relaxation parameters OMEGAH, OMEGAS, INISLP, OMGSLP",
                "ddid",
            )?;
            ints.push(w.ints[0]);
            reals.extend([w.reals[0], w.reals[1], w.reals[2]]);
            line = w.line;
        }
        4 => {
            let w = r.read("the parameters INISLP, OMGSLP", "id")?;
            ints.push(w.ints[0]);
            reals.push(w.reals[0]);
            line = w.line;
        }
        5 => {
            let w = r.read(
                "the parameters FDECAY, BETATH, KDOWFB, D_IFC, D_LIN, D_CNS, D_SLP, POW_S",
                "ddiddddd",
            )?;
            ints.push(w.ints[0]);
            reals.extend(&w.reals);
            line = w.line;
        }
        _ => {}
    }
    Ok(Lined {
        line,
        value: SolverInp { ints, reals },
    })
}

/// L != 1: the friction law(s), as `cntc_setfrictionmethod` takes them.
fn read_friction(r: &mut Reader, varfrc: i32, frclaw: i32) -> Result<Lined<Vec<f64>>, InpError> {
    let mut params = Vec::new();
    let nvf = if varfrc == 0 {
        1
    } else {
        let v = r.read("the number of rows NVF of the friction variation", "i")?;
        check(v.line, "NVF", v.ints[0], &[(1, 1000)])?;
        params.push(v.ints[0] as f64);
        v.ints[0] as usize
    };
    // The row's first value: the contact angle ALPHA (V = 1), the
    // position SVF along the rail (V = 2).
    let lead = ["", "a", "d"][varfrc as usize];
    let (what, types) = match frclaw {
        0 => ("the friction coefficients FSTAT, FKIN", "dd"),
        6 => (
            "the temperature-dependent friction FREF, TREF, DFHEAT, DTHEAT",
            "dddd",
        ),
        _ => (
            "the slip-velocity-dependent friction FKIN, F1, SABSH1, F2, SABSH2",
            "ddddd",
        ),
    };
    let mut rows = Vec::with_capacity(nvf);
    let mut line = 0;
    let mut angles = Vec::new();
    for _ in 0..nvf {
        let v = r.read(what, &format!("{lead}{types}"))?;
        line = v.line;
        let mut row = v.reals.clone();
        if varfrc != 0 {
            angles.push(row[0]);
            row.remove(0);
        }
        if frclaw == 0 {
            check(line, "FKIN", row[1], &[(1e-4, 1e10)])?;
            if row[0] < 0.999 * row[1] || row[0] > 1.001 * row[1] {
                return Err(InpError {
                    line,
                    message: format!("FSTAT and FKIN must be the same: {}, {}", row[0], row[1]),
                });
            }
        } else if frclaw != 6 {
            check(line, "FKIN", row[0], &[(0.0, 1e10)])?;
            for (k, name) in [(1, "F1"), (3, "F2")] {
                check(line, name, row[k], &[(0.0, 1e20)])?;
                if row[k] < 1e-8 {
                    row[k + 1] = row[k + 1].max(1e-4);
                }
            }
            check(line, "SABSH1", row[2], &[(1e-5, 1e20)])?;
            check(line, "SABSH2", row[4], &[(1e-5, 1e20)])?;
        }
        rows.push(row);
    }
    if angles.windows(2).any(|w| w[1] <= w[0]) {
        return Err(InpError {
            line,
            message: format!(
                "for variable friction the {} must increase strictly, got {angles:?}",
                if varfrc == 1 {
                    "angles ALPHA"
                } else {
                    "positions SVF"
                }
            ),
        });
    }
    if frclaw >= 2 {
        let v = r.read("the friction memory MEMDST, MEM_S0", "dd")?;
        line = v.line;
        check(line, "MEMDST", v.reals[0], &[(0.0, 1e20)])?;
        check(line, "MEM_S0", v.reals[1], &[(0.0, 1e20)])?;
        rows.iter_mut().for_each(|row| row.extend(&v.reals));
    }
    for (k, row) in rows.into_iter().enumerate() {
        if varfrc != 0 {
            params.push(angles[k]);
        }
        params.extend(row);
    }
    Ok(Lined {
        line,
        value: params,
    })
}

/// C3 = 2-4: the material, as `cntc_setmaterialparameters` takes it
/// (POISS 1, 2, GG 1, 2, then the M digit's parameters).
fn read_material(r: &mut Reader, d: &InpDigits) -> Result<Lined<Vec<f64>>, InpError> {
    if d.inflcf == 4 {
        // IF_METH, VARIANT of the conformal influence coefficients
        // (refused by the C3 digit).
        r.read("the influence-function method IF_METH, VARIANT", "ii")?;
    }
    let v = r.read("the material POISS1, POISS2, GG1, GG2", "dddd")?;
    for (k, (name, lo, hi)) in [
        ("POISS1", 0.0, 0.5),
        ("POISS2", 0.0, 0.5),
        ("GG1", 1e-5, 1e20),
        ("GG2", 1e-5, 1e20),
    ]
    .iter()
    .enumerate()
    {
        check(v.line, name, v.reals[k], &[(*lo, *hi)])?;
    }
    let mut params = v.reals.clone();
    let mut line = v.line;
    if d.bound == 1 {
        // FLX_Z of a thin sheet (B = 1, refused by the B digit).
        line = r.read("the thin sheet compressibility FLX_Z", "d")?.line;
    }
    let model = match d.mater {
        1 => Some(("the viscoelastic constants FG1, FG2, TC1, TC2", "dddd")),
        2 => Some((
            "the flexibility FLX and slope reduction K0_MF, ALFAMF, BETAMF",
            "dddd",
        )),
        3 | 5 => Some(("the slope reduction K0_MF, ALFAMF, BETAMF", "ddd")),
        4 => Some(("the layer GG3, LAYTHK, TAU_C0, K_TAU", "dddd")),
        _ => None,
    };
    if let Some((what, types)) = model {
        let w = r.read(what, types)?;
        line = w.line;
        if d.mater == 2 {
            check(line, "FLX", w.reals[0], &[(1e-10, 1e20)])?;
        }
        if matches!(d.mater, 2 | 3 | 5) {
            let k = if d.mater == 2 { 1 } else { 0 };
            check(line, "K0_MF", w.reals[k], &[(1e-10, 1.0)])?;
            check(line, "ALFAMF", w.reals[k + 1], &[(0.0, 1.0)])?;
            check(line, "BETAMF", w.reals[k + 2], &[(0.0, 1e20)])?;
        }
        params.extend(&w.reals);
    }
    Ok(Lined {
        line,
        value: params,
    })
}

/// H = 3: the bodies' temperatures and thermal properties, as
/// `cntc_settemperaturedata` takes them.
fn read_heat(r: &mut Reader, mater: i32) -> Result<Lined<Vec<f64>>, InpError> {
    let mut params = Vec::with_capacity(9);
    let mut line = 0;
    for body in ["1", "2"] {
        let v = r.read(
            &format!("the temperature BKTEMP, HEATCP, LAMBDA, DENS of body {body}"),
            "dddd",
        )?;
        line = v.line;
        check(line, &format!("HEATCP{body}"), v.reals[1], &[(1e-5, 1e20)])?;
        check(line, &format!("LAMBDA{body}"), v.reals[2], &[(1e-5, 1e20)])?;
        check(line, &format!("DENS{body}"), v.reals[3], &[(1e-12, 1e20)])?;
        params.extend(&v.reals);
    }
    let betapl = if mater == 4 {
        let v = r.read("the partitioning of plastic work BETAPL", "d")?;
        line = v.line;
        check(line, "BETAPL", v.reals[0], &[(0.0, 1.0)])?;
        v.reals[0]
    } else {
        0.0
    };
    params.push(betapl);
    Ok(Lined {
        line,
        value: params,
    })
}

/// D >= 2: the discretisation, as `cntc_setpotcontact` (IPOTCN = -1)
/// and `cntc_setrollingstepsize` take it.
fn read_discretisation(r: &mut Reader) -> Result<Lined<(Vec<f64>, f64)>, InpError> {
    let v = r.read(
        "the discretisation DX, DS, DQREL, A_SEP, D_SEP, D_COMB {, D_TURN {, G_MISS}}",
        "dddaddDD",
    )?;
    let x = &v.reals;
    check(v.line, "DX", x[0], &[(1e-8, 1e20)])?;
    check(v.line, "DS", x[1], &[(1e-8, 1e20)])?;
    check(v.line, "DQREL", x[2], &[(5e-7, 10.0)])?;
    let (a_sep, d_sep) = (x[3].max(0.0), x[4].max(0.0));
    if d_sep < x[5] {
        return Err(InpError {
            line: v.line,
            message: format!("D_SEP = {d_sep} must be >= D_COMB = {}", x[5]),
        });
    }
    let mut params = vec![x[0], x[1], a_sep, d_sep, x[5]];
    params.extend(&x[6..]);
    Ok(v.lined((params, x[2])))
}

/// Z1: the track's dimensions, rail profile and (with `kinematics`)
/// deviations.
fn read_track(
    r: &mut Reader,
    d: &InpDigits,
    kinematics: bool,
    inp: &mut WheelRailInp,
) -> Result<(), InpError> {
    if d.ztrack == 1 || d.ztrack == 3 {
        let rig = d.config >= 4;
        let v = if rig {
            r.read(
                "the roller rig dimensions GAUGHT, GAUGSQ, GAUGWD, NOMRAD {, CURV}",
                "ddddD",
            )?
        } else {
            r.read(
                "the track dimensions GAUGHT, GAUGSQ, GAUGWD, CANT {, CURV}",
                "dddaD",
            )?
        };
        let x = &v.reals;
        // cntc_settrackdimensions Z = 1: GAUGHT, GAUGSQ, GAUGWD, CANT,
        // NOMRAD {, CURV}.
        let (cant, nomrad) = if rig { (0.0, x[3]) } else { (x[3], 0.0) };
        let mut params = vec![x[0], x[1], x[2], cant, nomrad];
        params.extend(&x[4..]);
        inp.track = Some(v.lined(params));
    }
    if d.ztrack == 3 {
        inp.rail_profile = Some(read_profile(r, "rail", 0)?);
    }
    if kinematics && (d.ztrack == 2 || d.ztrack == 3) {
        let v = r.read("the rail deviations DY, DZ, ROLL, VY, VZ, VROLL", "ddadda")?;
        inp.rail_deviations = Some(v.lined(v.reals.clone()));
        if d.force == 3 {
            // KY_RAIL, FY_RAIL, KZ_RAIL, FZ_RAIL {, DYSTEP0} of the massless
            // rail (F1 = 3): cntc_settrackdimensions with Z = 32.
            let v = r.read(
                "the rail deflection parameters KY_RAIL, FY_RAIL, KZ_RAIL, FZ_RAIL {, DYSTEP0}",
                "ddddD",
            )?;
            inp.massless_rail = Some(v.lined(v.reals.clone()));
        }
    }
    Ok(())
}

/// A profile line (and its extra option lines): `itype` 0 rail, 1 wheel.
fn read_profile(r: &mut Reader, name: &str, itype: i32) -> Result<Lined<ProfileRef>, InpError> {
    let v = r.read(
        &format!("the {name} profile: 'FILE', MIRRORY, SCALE, SMOOTH {{, MIRRORZ {{, PRFOPT}}}}"),
        "siddII",
    )?;
    let mirror_y = v.ints[0];
    let mirror_z = v.ints.get(1).copied().unwrap_or(0);
    let prfopt = v.ints.get(2).copied().unwrap_or(0);
    check(v.line, "MIRRORY", mirror_y, &[(-1, 1)])?;
    check(v.line, "MIRRORZ", mirror_z, &[(-1, 1)])?;
    check(v.line, "PRFOPT", prfopt, &[(0, 2)])?;
    let mut iparam = vec![itype, 0, mirror_y, mirror_z];
    let mut rparam = vec![v.reals[0].max(1e-6), v.reals[1].max(0.0)];
    let mut line = v.line;
    if prfopt >= 1 {
        let w = r.read(
            &format!(
                "the {name} profile's options ISMOOTH, ZIG_THRS, KINK_HIGH, KINK_LOW, KINK_WID"
            ),
            "iaaad",
        )?;
        line = w.line;
        let (err_hnd, f_max_omit) = if prfopt >= 2 {
            let e = r.read(
                &format!("the {name} profile's options ERRHND, F_MAX_OMIT"),
                "id",
            )?;
            line = e.line;
            (e.ints[0].clamp(-2, 1), e.reals[0].clamp(0.0, 1.0))
        } else {
            (0, 0.0)
        };
        iparam.extend([err_hnd, w.ints[0].clamp(0, 2)]);
        rparam.push(f_max_omit);
        rparam.extend(&w.reals);
    }
    Ok(Lined {
        line,
        value: ProfileRef {
            fname: v.strs[0].clone(),
            iparam,
            rparam,
        },
    })
}

/// E1: the wheelset's dimensions and wheel profile, and (with
/// `kinematics`) its position, velocity and deviations.
fn read_wheelset(
    r: &mut Reader,
    d: &InpDigits,
    kinematics: bool,
    inp: &mut WheelRailInp,
) -> Result<(), InpError> {
    if d.ewheel == 3 || d.ewheel == 5 {
        let v = r.read(
            "the wheelset dimensions FBDIST, FBPOS, NOMRAD {, YTAPE}",
            "dddD",
        )?;
        check(v.line, "NOMRAD", v.reals[2], &[(1e-3, 1e20)])?;
        inp.wheelset = Some(v.lined(v.reals.clone()));
        inp.wheel_profile = Some(read_profile(r, "wheel", 1)?);
    }
    if !kinematics || d.ewheel == 0 {
        return Ok(());
    }
    let six = |v: &Values| -> [f64; 6] { std::array::from_fn(|k| v.reals[k]) };
    let v = r.read(
        "the wheelset position S, Y, Z (N = 0) or FZ (N = 1), ROLL, YAW, PITCH",
        "dddaaa",
    )?;
    inp.position = Some(v.lined(six(&v)));
    if d.ewheel >= 2 {
        let first = if d.config >= 4 { 'a' } else { 'd' };
        let last = if d.force == 1 || d.force == 2 {
            'd'
        } else {
            'a'
        };
        let v = r.read(
            "the wheelset velocity VS, VY, VZ, VROLL, VYAW, and VPITCH (F = 0) or FX_WS (F = 1)",
            &format!("{first}ddaa{last}"),
        )?;
        inp.velocity = Some(v.lined(six(&v)));
    }
    if d.ewheel >= 4 {
        let p = r.read(
            "the wheel position deviations DX, DY, DZ, DROLL, DYAW, DPITCH",
            "dddaaa",
        )?;
        let v = r.read(
            "the wheel velocity deviations VX, VY, VZ, VROLL, VYAW, VPITCH",
            "dddaaa",
        )?;
        let mut dev = p.reals.clone();
        dev.extend(&v.reals);
        inp.wheel_deviations = Some(v.lined(dev));
    }
    Ok(())
}

// ---------------------------------------------------------------------
// The calls.

impl WheelRailInp {
    /// The `cntc_set*` calls (icp = -1, CONTACT's units) that configure
    /// an element as the file does, each with its line; profile files
    /// named relative to `dir` (the input file's folder), read here as
    /// `cntc_setprofileinputfname` reads them. Digits and values the
    /// library does not have are passed on as given: the calls refuse
    /// them as they refuse a caller's.
    pub fn calls(&self, dir: &Path, held: &Held) -> Vec<(usize, Call)> {
        let d = &self.digits.value;
        let dl = self.digits.line;
        let mut out = Vec::new();
        let flag = |code: i32, value: i32| Call::SetFlag { code, value };
        out.extend(
            [
                (flags::IC_CONFIG, d.config),
                (flags::IC_PVTIME, d.pvtime),
                (flags::IC_BOUND, d.bound),
                (flags::IC_TANG, d.tang),
                (flags::IC_NORM, d.norm),
                (flags::IC_FORCE, d.force),
                (flags::IC_INFLCF, d.inflcf),
                (flags::IC_IESTIM, d.iestim),
                (flags::IC_MATFIL, d.matfil),
                (flags::IC_OUTPUT, d.output),
                (flags::IC_FLOW, d.flow),
                (flags::IC_RETURN, d.ret),
            ]
            .map(|(code, value)| (dl, flag(code, value))),
        );
        if d.discns >= 2 {
            out.push((dl, flag(flags::IC_DISCNS, d.discns)));
        }
        if let Some(s) = &self.solver {
            out.push((
                s.line,
                Call::SetSolverFlags {
                    gdigit: d.gausei,
                    ints: s.value.ints.clone(),
                    reals: s.value.reals.clone(),
                },
            ));
        }
        if let Some(f) = &self.friction {
            out.push((
                f.line,
                Call::SetFriction {
                    imeth: 10 * d.varfrc + d.frclaw,
                    params: f.value.clone(),
                },
            ));
        }
        if let Some(m) = &self.material {
            out.push((
                m.line,
                Call::SetMaterial {
                    mdigit: d.mater,
                    params: m.value.clone(),
                },
            ));
        }
        match (&self.damping, d.mater2) {
            (Some(m), _) => out.push((
                m.line,
                Call::SetMaterial {
                    mdigit: 10 + d.mater2,
                    params: m.value.clone(),
                },
            )),
            (None, 0) => out.push((
                dl,
                Call::SetMaterial {
                    mdigit: 10,
                    params: Vec::new(),
                },
            )),
            (None, _) => {}
        }
        out.push(match &self.heat {
            Some(h) => (
                h.line,
                Call::SetTemperature {
                    imeth: 3,
                    params: h.value.clone(),
                },
            ),
            None => (
                dl,
                Call::SetTemperature {
                    imeth: d.heat,
                    params: Vec::new(),
                },
            ),
        });
        if let Some(s) = &self.discretisation {
            let (params, dqrel) = &s.value;
            out.push((
                s.line,
                Call::SetPotcon {
                    ipotcn: -1,
                    params: params.clone(),
                },
            ));
            out.push((
                s.line,
                Call::SetRollingStep {
                    chi: None,
                    dq: *dqrel,
                },
            ));
        }
        if let Some(t) = &self.track {
            out.push((
                t.line,
                Call::SetTrackDimensions {
                    ztrack: 1,
                    params: t.value.clone(),
                },
            ));
        }
        let profile = |p: &Lined<ProfileRef>| {
            let path = dir.join(&p.value.fname);
            let fname = path.to_string_lossy().into_owned();
            let content = read_profile_file(&fname);
            (
                p.line,
                Call::SetProfileFile {
                    slice_files: read_slice_files(&fname, content.as_deref()),
                    fname,
                    content,
                    ints: p.value.iparam.clone(),
                    reals: p.value.rparam.clone(),
                },
            )
        };
        out.extend(self.rail_profile.as_ref().map(profile));
        if let Some(t) = &self.rail_deviations {
            out.push((
                t.line,
                Call::SetTrackDimensions {
                    ztrack: 2,
                    params: t.value.clone(),
                },
            ));
        }
        if let Some(t) = &self.massless_rail {
            out.push((
                t.line,
                Call::SetTrackDimensions {
                    ztrack: 32,
                    params: t.value.clone(),
                },
            ));
        }
        if let Some(w) = &self.wheelset {
            out.push((
                w.line,
                Call::SetWheelsetDimensions {
                    ewheel: 3,
                    params: w.value.clone(),
                },
            ));
        }
        out.extend(self.wheel_profile.as_ref().map(profile));
        if let Some(p) = &self.position {
            let mut x = p.value.to_vec();
            if d.norm == 1 {
                x[2] = held.z_mm;
            }
            out.push((
                p.line,
                Call::SetWheelsetPosition {
                    ewheel: 1,
                    params: x,
                },
            ));
            if d.norm == 1 {
                out.push((p.line, Call::SetVerticalForce { fz: p.value[2] }));
            }
        }
        if let Some(v) = &self.velocity {
            let mut x = v.value.to_vec();
            if d.force == 1 || d.force == 2 {
                x[5] = held.vpitch;
            }
            out.push((
                v.line,
                Call::SetWheelsetVelocity {
                    ewheel: 2,
                    params: x,
                },
            ));
            if d.force == 1 {
                out.push((
                    v.line,
                    Call::SetTangentialForces {
                        fx: v.value[5],
                        fy: 0.0,
                    },
                ));
            }
        }
        if let Some(w) = &self.wheel_deviations {
            out.push((
                w.line,
                Call::SetWheelsetFlexibility {
                    ewheel: d.ewheel,
                    params: w.value.clone(),
                },
            ));
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_and_values_read_as_contacts_readline() {
        assert_eq!(
            words("  'MBench UIC60.prr'   0, 1.0 0.0 % RFNAME"),
            ["'MBench UIC60.prr'", "0", "1.0", "0.0"]
        );
        assert_eq!(words("a=1\tb % c"), ["a", "1", "b"]);
        assert_eq!(real("1d-5"), Some(1e-5));
        assert_eq!(real("82000."), Some(82000.0));
        assert_eq!(real("MAXGS"), None);
        assert_eq!(angle("90d"), Some(90.0 * std::f64::consts::PI / 180.0));
        assert_eq!(angle("0.5r"), Some(0.5));
        let mut r = Reader::new("% c\n\n 1 2\n 3 x y\n");
        let v = r.read("four", "iiiD").unwrap();
        assert_eq!((v.ints, v.n, v.line), (vec![1, 2, 3], 3, 4));
        let mut r = Reader::new("1 x\n");
        let e = r.read("two", "ii").unwrap_err();
        assert_eq!(e.line, 1);
        assert!(e.message.contains("value 2 \"x\""), "{e}");
        assert_eq!(digits_of::<7>(203100), [0, 2, 0, 3, 1, 0, 0]);
    }

    /// The sections the digits ask for become their calls' arguments:
    /// friction by contact angle (V = 1, L = 4) with its memory on every
    /// row, G = 2's relaxation, M = 3's slope reduction, D_TURN and G_MISS,
    /// N = 0's height, E1 = 5's deviations.
    #[test]
    fn sections_become_their_calls() {
        let text = "\
  1 MODULE
 0200000     C-P-B-T-N-F-S
 1423335  1  V-L-D-C-M-Z-E  M2
 0200021     H-G-I-A-O-W-R
 999 100 30 5 1e-6 5000
 0.7 0.8 1 0.1
 2
 -90d 0.2 0.1 10 0 5000
  90d 0.25, 0.1, 10, 0, 5000
 0.01 5
 0.28 0.28 82000 82000
 0.54 0.02 0.62
 0.2 0.2 1 30d 8 4 7 0.1
 14 0 1435 0.001
 'r.prr' 0 1 0
 0 0 0 0 0 0
 1360 -70 460
 'w.prw' 0 1 0
 0 1 -0.5 0 0.002 0
 2000 0 0 0 0 -4.3
 0 0 0 0 0 0
 0 0 0 0 0 0
";
        let held = Held {
            digits: Digits::default(),
            z_mm: 0.0,
            vpitch: 0.0,
        };
        let (inp, warnings) = parse(text, InpType::Module1, &held).unwrap();
        assert!(warnings.is_empty(), "{warnings:?}");
        assert_eq!(inp.unsupported, None);
        let calls: Vec<Call> = inp
            .calls(Path::new("/p"), &held)
            .into_iter()
            .map(|(_, c)| c)
            .collect();
        let deg = |x: f64| x * std::f64::consts::PI / 180.0;
        for want in [
            Call::SetFlag {
                code: flags::IC_DISCNS,
                value: 2,
            },
            Call::SetSolverFlags {
                gdigit: 2,
                ints: vec![999, 100, 30, 5, 1],
                reals: vec![1e-6, 0.7, 0.8, 0.1],
            },
            Call::SetFriction {
                imeth: 14,
                // NVF, then per row ALPHA, FKIN, FEXP1, SABSH1, FEXP2,
                // SABSH2, MEMDST, MEM_S0.
                params: [(-90.0, 0.2), (90.0, 0.25)].iter().fold(
                    vec![2.0],
                    |mut p, &(alpha, fkin)| {
                        p.extend([deg(alpha), fkin, 0.1, 10.0, 0.0, 5000.0, 0.01, 5.0]);
                        p
                    },
                ),
            },
            Call::SetMaterial {
                mdigit: 3,
                params: vec![0.28, 0.28, 82000.0, 82000.0, 0.54, 0.02, 0.62],
            },
            Call::SetPotcon {
                ipotcn: -1,
                params: vec![0.2, 0.2, deg(30.0), 8.0, 4.0, 7.0, 0.1],
            },
            Call::SetRollingStep { chi: None, dq: 1.0 },
            Call::SetTrackDimensions {
                ztrack: 1,
                params: vec![14.0, 0.0, 1435.0, 0.001, 0.0],
            },
            Call::SetWheelsetPosition {
                ewheel: 1,
                params: vec![0.0, 1.0, -0.5, 0.0, 0.002, 0.0],
            },
            Call::SetWheelsetFlexibility {
                ewheel: 5,
                params: vec![0.0; 12],
            },
        ] {
            assert!(calls.contains(&want), "{want:?} not in {calls:#?}");
        }
        assert!(!calls
            .iter()
            .any(|c| matches!(c, Call::SetVerticalForce { .. })));
        let rail = calls.iter().find_map(|c| match c {
            Call::SetProfileFile { fname, ints, .. } => Some((fname.clone(), ints.clone())),
            _ => None,
        });
        assert_eq!(rail, Some(("/p/r.prr".to_string(), vec![0, 0, 0, 0])));
    }
}
