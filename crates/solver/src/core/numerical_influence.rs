//! Influence coefficients given as a table: CONTACT's file of numerical
//! influence coefficients (control digit C3 = 9; CONTACT user guide,
//! "Specification of the file of numerical influence coefficients"), e.g.
//! computed with finite elements for conformal bodies.
//!
//! The file gives the coefficients C of u_i(I) = (1/G) sum_j sum_J
//! C_ij(I - J) p_j(J) in CONTACT's units: C and the element sizes in mm,
//! G the combined shear modulus of the case's materials. They are total
//! values for both bodies, as the half-space's coefficients of
//! [`crate::core::influence`] (the same directions and signs), which they
//! replace: the kernel is C \[mm\] · 1e-3 / G \[m/Pa\].
//!
//! # Format
//!
//! ```text
//! nmatrix  iaconvex          (1 or my; 1: the rail, 2: the wheel is the upper body,
//!                             informative, as in CONTACT)
//! lquasid  xyzorder          (0 and 312: nine coefficients per line, order n, x, y)
//! lsymmx   lsymmy            (1 and 0: the file holds offsets ix >= 0 only)
//! mx  my  dx  dy             (the file's grid; dx, dy in mm)
//! for each matrix (nmatrix > 1: first a line "imatrix xcentr ycentr"):
//!   for iyofs = -my+1 .. my-1, ixofs = 0 .. mx-1:
//!     ixofs  xrel  Cnn Cnx Cny  Cxn Cxx Cxy  Cyn Cyx Cyy
//! ```
//!
//! `Cij` is the displacement difference along i for a unit traction along
//! j on the loaded element, at offset (ixofs, iyofs) from it. Offsets
//! -ixofs take the same values, with the sign changed for nx, xn, xy and
//! yx (symmetry in x). A `%` starts a comment; empty and comment lines are
//! skipped wherever they are (CONTACT's reader skips exactly two lines
//! before each block of one iyofs and four at the start of each matrix:
//! files for both must put comment lines there). Values are separated by
//! blanks or commas; a Fortran exponent `1.0D-3` is read as `1.0e-3`;
//! values after the first 11 of a line are ignored, as CONTACT does.
//!
//! A file of one matrix holds the same coefficients for all loaded
//! elements: a convolution, the FFT products of the planar solvers, at the
//! half-space's cost. A file of my matrices, one per loaded row jy = 1 ..
//! my of the case's grid (my its number of rows), holds coefficients that
//! depend on the loaded row: no longer a convolution in y. Its product is
//! the sum over the rows jy of the FFT product of row jy's kernels with the
//! tractions of row jy alone (rows without tractions skipped): exact, up to
//! my products instead of one, and my + 1 kernel sets in memory
//! ([`crate::core::fft::KernelSet::from_table`]; at most
//! [`crate::core::problem::MAX_PER_ROW_WORK`] rows x elements). The
//! solvers' local scalars and preconditioners (self-influence, circulant
//! inverses) take the middle row's matrix: they change the iterations, not
//! the answer. Steady rolling on 21 x 17 elements (about 11 rows loaded):
//! 1.4 ms with one matrix, 13.8 ms with 17 (medians of 7 alternating
//! release runs, 106 products each, 2-core VM).
//!
//! # Grids
//!
//! The file's grid may differ from the case's, as in CONTACT: offsets the
//! file does not hold are zero (a smaller file: an approximation), offsets
//! beyond the case's grid are not used. The element sizes must be the
//! case's within [`SPACING_TOLERANCE_M`] (CONTACT stops with "inconsistent
//! dx,dy" beyond 1e-5 mm).
//!
//! # Limits
//!
//! A file larger than [`MAX_FILE_BYTES`] or holding more than
//! [`MAX_COEFFICIENT_LINES`] coefficient lines is refused before its
//! coefficients are stored (72 bytes a line: at most 75 MB), and so is a
//! coefficient beyond [`MAX_COEFFICIENT_MM`] in magnitude. Memory is
//! reserved for the lines the text can hold, not for those its header
//! declares.

use std::collections::hash_map::DefaultHasher;
use std::hash::{Hash, Hasher};
use std::io::Read;
use std::path::Path;

use thiserror::Error;

use crate::core::influence::{Component, KernelKind};
use crate::core::memory::HeapBytes;

/// Largest file read \[bytes\].
pub const MAX_FILE_BYTES: u64 = 256 << 20;
/// Largest number of coefficient lines, `nmatrix (2 my - 1) mx`.
pub const MAX_COEFFICIENT_LINES: usize = 1 << 20;
/// Largest magnitude of a coefficient \[mm\]: the half-space's are below
/// one element size (0.34 mm, its self-influence Cnn for elements of
/// 0.4 mm), so 1e6 mm is a body millions of times more compliant than a
/// half-space: a unit or format error. Far beyond it (1e300 mm) the
/// solvers' products and norms overflow: non-finite forces.
pub const MAX_COEFFICIENT_MM: f64 = 1e6;
/// Largest element size mismatch between the file and the case \[m\]:
/// CONTACT's 1e-5 mm.
pub const SPACING_TOLERANCE_M: f64 = 1e-8;

/// Coefficients per line, in the file's order nn nx ny xn xx xy yn yx yy.
const PER_LINE: usize = 9;

/// Why a file of influence coefficients was not read.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum InfluenceFileError {
    /// The file could not be opened or read.
    #[error("cannot read the influence-coefficient file {path}: {reason}")]
    Io {
        /// The path as given.
        path: String,
        /// The system's message.
        reason: String,
    },
    /// The file exceeds [`MAX_FILE_BYTES`].
    #[error("the influence-coefficient file {path} is larger than {limit} bytes")]
    TooLarge {
        /// The path as given.
        path: String,
        /// [`MAX_FILE_BYTES`].
        limit: u64,
    },
    /// A value is missing, not a number, or out of range.
    #[error("influence-coefficient file, line {line}: `{field}` {reason}")]
    Field {
        /// 1-based line number.
        line: usize,
        /// The field as the format names it (`nmatrix`, `mxfile`, `Cxx`, ...).
        field: &'static str,
        /// What is wrong.
        reason: String,
    },
    /// The file ended before all coefficient lines were read.
    #[error("influence-coefficient file ends at line {line}, before `{field}` (expected {expected} coefficient lines)")]
    Truncated {
        /// Lines read.
        line: usize,
        /// The field expected next.
        field: &'static str,
        /// Coefficient lines the header announces.
        expected: usize,
    },
    /// Data follows the last coefficient line.
    #[error("influence-coefficient file, line {line}: data after the last coefficient line")]
    Trailing {
        /// 1-based line number.
        line: usize,
    },
}

/// Which body is the upper one in the file (`iaconvex`; informative).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum UpperBody {
    /// `iaconvex = 1`.
    Rail,
    /// `iaconvex = 2`.
    Wheel,
}

/// A file of numerical influence coefficients, as read (CONTACT's units:
/// mm).
#[derive(Clone, PartialEq)]
pub struct InfluenceFile {
    upper_body: UpperBody,
    matrices: usize,
    mx: usize,
    my: usize,
    dx_mm: f64,
    dy_mm: f64,
    /// `[matrix][iyofs + my - 1][ixofs][9]`, the file's order.
    values: Vec<f64>,
    fingerprint: u64,
}

impl std::fmt::Debug for InfluenceFile {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "InfluenceFile({} matrices, {}x{}, dx {} mm, dy {} mm, {:016x})",
            self.matrices, self.mx, self.my, self.dx_mm, self.dy_mm, self.fingerprint
        )
    }
}

/// The column of (i, j) in a coefficient line (order n, x, y).
fn column(i: Component, j: Component) -> usize {
    let k = |c: Component| match c {
        Component::N => 0,
        Component::X => 1,
        Component::Y => 2,
    };
    3 * k(i) + k(j)
}

/// Whether (i, j) changes sign with the offset in x.
fn odd_in_x(i: Component, j: Component) -> bool {
    use Component::*;
    matches!((i, j), (N, X) | (X, N) | (X, Y) | (Y, X))
}

/// The names of the coefficient columns, for errors.
const COLUMN_NAMES: [&str; PER_LINE] = [
    "Cnn", "Cnx", "Cny", "Cxn", "Cxx", "Cxy", "Cyn", "Cyx", "Cyy",
];

/// The file's non-comment lines, numbered.
struct Lines<'a> {
    inner: std::iter::Enumerate<std::str::Lines<'a>>,
    last: usize,
}

impl<'a> Lines<'a> {
    fn new(text: &'a str) -> Self {
        Self {
            inner: text.lines().enumerate(),
            last: 0,
        }
    }

    /// The next line with data: its number and its values (comment cut).
    fn next_values(&mut self) -> Option<(usize, Vec<&'a str>)> {
        for (k, l) in self.inner.by_ref() {
            self.last = k + 1;
            let data = l.split('%').next().unwrap_or("");
            let words: Vec<&str> = data
                .split(|c: char| c.is_whitespace() || c == ',')
                .filter(|w| !w.is_empty())
                .collect();
            if !words.is_empty() {
                return Some((k + 1, words));
            }
        }
        None
    }
}

fn field_error(line: usize, field: &'static str, reason: impl Into<String>) -> InfluenceFileError {
    InfluenceFileError::Field {
        line,
        field,
        reason: reason.into(),
    }
}

/// Word `k` of a line, parsed by `parse` (`kind` names what it must be).
fn value<T>(
    line: usize,
    words: &[&str],
    k: usize,
    field: &'static str,
    kind: &str,
    parse: impl Fn(&str) -> Option<T>,
) -> Result<T, InfluenceFileError> {
    let w = words
        .get(k)
        .ok_or_else(|| field_error(line, field, "is missing"))?;
    parse(w).ok_or_else(|| {
        // A word of 100 kB is not quoted whole.
        let head: String = w.chars().take(MAX_QUOTED_CHARS).collect();
        let cut = if head.len() < w.len() { "..." } else { "" };
        field_error(line, field, format!("is not {kind}: \"{head}\"{cut}"))
    })
}

/// Most characters of a word an error quotes.
const MAX_QUOTED_CHARS: usize = 40;

fn integer(
    line: usize,
    words: &[&str],
    k: usize,
    field: &'static str,
) -> Result<i64, InfluenceFileError> {
    value(line, words, k, field, "an integer", |w| w.parse().ok())
}

/// A finite number; a Fortran exponent (`1.5D-3`) is read as `1.5e-3`.
fn real(
    line: usize,
    words: &[&str],
    k: usize,
    field: &'static str,
) -> Result<f64, InfluenceFileError> {
    value(line, words, k, field, "a finite number", |w| {
        w.replace(['D', 'd'], "e")
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
    })
}

/// `v` must be `want`.
fn exactly(
    line: usize,
    field: &'static str,
    v: i64,
    want: i64,
    meaning: &str,
) -> Result<(), InfluenceFileError> {
    if v == want {
        Ok(())
    } else {
        Err(field_error(
            line,
            field,
            format!("must be {want} ({meaning}), got {v}"),
        ))
    }
}

impl InfluenceFile {
    /// Reads the file at `path` ([`InfluenceFile::parse`]).
    pub fn read(path: &Path) -> Result<Self, InfluenceFileError> {
        let shown = path.display().to_string();
        let io = |e: std::io::Error| InfluenceFileError::Io {
            path: shown.clone(),
            reason: e.to_string(),
        };
        let file = std::fs::File::open(path).map_err(io)?;
        let mut text = String::new();
        file.take(MAX_FILE_BYTES + 1)
            .read_to_string(&mut text)
            .map_err(io)?;
        if text.len() as u64 > MAX_FILE_BYTES {
            return Err(InfluenceFileError::TooLarge {
                path: shown,
                limit: MAX_FILE_BYTES,
            });
        }
        Self::parse(&text)
    }

    /// Reads a file's text (see the module docs for the format).
    pub fn parse(text: &str) -> Result<Self, InfluenceFileError> {
        let mut lines = Lines::new(text);
        let mut header = |field: &'static str| {
            let last = lines.last;
            lines.next_values().ok_or(InfluenceFileError::Truncated {
                line: last,
                field,
                expected: 0,
            })
        };
        let (l1, w) = header("nmatrix")?;
        let matrices = integer(l1, &w, 0, "nmatrix")?;
        let upper = match integer(l1, &w, 1, "iaconvex")? {
            1 => UpperBody::Rail,
            2 => UpperBody::Wheel,
            v => {
                return Err(field_error(
                    l1,
                    "iaconvex",
                    format!("must be 1 or 2, got {v}"),
                ))
            }
        };
        // The format's fixed flags: (line, its values, column, field,
        // value, meaning).
        let (l2, w2) = header("lquasid")?;
        let (l3, w3) = header("lsymmx")?;
        for (l, w, k, field, want, meaning) in [
            (l2, &w2, 0, "lquasid", 0, "nine coefficients per line"),
            (l2, &w2, 1, "xyzorder", 312, "the order n, x, y"),
            (l3, &w3, 0, "lsymmx", 1, "offsets ixofs >= 0, symmetry in x"),
            (
                l3,
                &w3,
                1,
                "lsymmy",
                0,
                "all offsets iyofs, no symmetry in y",
            ),
        ] {
            exactly(l, field, integer(l, w, k, field)?, want, meaning)?;
        }
        let (l4, w) = header("mxfile")?;
        let mx = integer(l4, &w, 0, "mxfile")?;
        let my = integer(l4, &w, 1, "myfile")?;
        let dx_mm = real(l4, &w, 2, "dxfile")?;
        let dy_mm = real(l4, &w, 3, "dyfile")?;
        let limit = MAX_COEFFICIENT_LINES as i64;
        for (v, field, line) in [
            (matrices, "nmatrix", l1),
            (mx, "mxfile", l4),
            (my, "myfile", l4),
        ] {
            if !(1..=limit).contains(&v) {
                return Err(field_error(
                    line,
                    field,
                    format!("must be in 1..={limit}, got {v}"),
                ));
            }
        }
        for (v, field) in [(dx_mm, "dxfile"), (dy_mm, "dyfile")] {
            if v <= 0.0 {
                return Err(field_error(l4, field, format!("must be > 0 mm, got {v}")));
            }
        }
        let (matrices, mx, my) = (matrices as usize, mx as usize, my as usize);
        let rows = 2 * my - 1;
        let count = matrices
            .checked_mul(rows)
            .and_then(|c| c.checked_mul(mx))
            .filter(|&c| c <= MAX_COEFFICIENT_LINES)
            .ok_or_else(|| {
                field_error(
                    l4,
                    "mxfile",
                    format!(
                        "nmatrix (2 myfile - 1) mxfile = {matrices} x {rows} x {mx} coefficient lines exceed the limit {MAX_COEFFICIENT_LINES}"
                    ),
                )
            })?;
        // Reserved for the lines the text can hold (a coefficient line has
        // at least 11 one-character words and 10 separators), not for the
        // count a header declares: a short text declaring 2^20 lines
        // reserves nothing near 75 MB.
        let room = text.len() / 21;
        let mut values = Vec::with_capacity(count.min(room) * PER_LINE);
        for imat in 1..=matrices {
            if matrices > 1 {
                let last = lines.last;
                let (l, w) = lines.next_values().ok_or(InfluenceFileError::Truncated {
                    line: last,
                    field: "imatrix",
                    expected: count,
                })?;
                let id = integer(l, &w, 0, "imatrix")?;
                exactly(
                    l,
                    "imatrix",
                    id,
                    imat as i64,
                    "the matrices in order 1 .. nmatrix",
                )?;
            }
            for _iy in 0..rows {
                for ix in 0..mx {
                    let last = lines.last;
                    let (l, w) = lines.next_values().ok_or(InfluenceFileError::Truncated {
                        line: last,
                        field: "ixofs",
                        expected: count,
                    })?;
                    exactly(
                        l,
                        "ixofs",
                        integer(l, &w, 0, "ixofs")?,
                        ix as i64,
                        "offsets 0 .. mxfile-1 in order",
                    )?;
                    real(l, &w, 1, "xrel")?;
                    for (k, name) in COLUMN_NAMES.iter().enumerate() {
                        let v = real(l, &w, 2 + k, name)?;
                        if v.abs() > MAX_COEFFICIENT_MM {
                            return Err(field_error(
                                l,
                                name,
                                format!("must be within +-{MAX_COEFFICIENT_MM:e} mm, got {v:e}"),
                            ));
                        }
                        values.push(v);
                    }
                }
            }
        }
        if let Some((l, _)) = lines.next_values() {
            return Err(InfluenceFileError::Trailing { line: l });
        }
        let mut h = DefaultHasher::new();
        (matrices, mx, my, dx_mm.to_bits(), dy_mm.to_bits()).hash(&mut h);
        for v in &values {
            v.to_bits().hash(&mut h);
        }
        Ok(Self {
            upper_body: upper,
            matrices,
            mx,
            my,
            dx_mm,
            dy_mm,
            values,
            fingerprint: h.finish(),
        })
    }

    /// A file of `matrices` matrices of an mx x my grid of elements dx x dy
    /// \[m\], coefficient (matrix, i, j, ox, oy) \[mm\] from `coefficient`
    /// for ox in 0..mx, |oy| < my (the file's values; -ox mirrors them).
    /// Refused as [`InfluenceFile::parse`] refuses the same header.
    pub fn from_coefficients(
        matrices: usize,
        (mx, my): (usize, usize),
        (dx_m, dy_m): (f64, f64),
        upper_body: UpperBody,
        coefficient: impl Fn(usize, Component, Component, i64, i64) -> f64,
    ) -> Result<Self, InfluenceFileError> {
        let mut text = String::new();
        let body = match upper_body {
            UpperBody::Rail => 1,
            UpperBody::Wheel => 2,
        };
        let header = format!(
            "{matrices} {body}\n0 312\n1 0\n{mx} {my} {} {}\n",
            dx_m * 1e3,
            dy_m * 1e3
        );
        // The header's checks first (sizes), then the values, written
        // exactly (shortest round-trip form).
        Self::parse_header_only(&header)?;
        text.push_str(&header);
        let cols = [Component::N, Component::X, Component::Y];
        for m in 0..matrices {
            if matrices > 1 {
                text.push_str(&format!("{} 0 0\n", m + 1));
            }
            for oy in -(my as i64 - 1)..my as i64 {
                for ox in 0..mx as i64 {
                    text.push_str(&format!("{ox} {}", ox as f64 * dx_m * 1e3));
                    for i in cols {
                        for j in cols {
                            text.push_str(&format!(" {:e}", coefficient(m, i, j, ox, oy)));
                        }
                    }
                    text.push('\n');
                }
            }
        }
        Self::parse(&text)
    }

    /// Checks a header's four lines alone.
    fn parse_header_only(header: &str) -> Result<(), InfluenceFileError> {
        match Self::parse(header) {
            Err(InfluenceFileError::Truncated { .. }) => Ok(()),
            Err(e) => Err(e),
            Ok(_) => Ok(()),
        }
    }

    /// The file's text in the format CONTACT reads (the module docs):
    /// `significant` significant digits per coefficient, four comment
    /// lines before each matrix of a file of several (the last of them the
    /// matrix line, which CONTACT skips), two before each block of one
    /// iyofs.
    pub fn to_text(&self, significant: usize) -> String {
        let body = match self.upper_body {
            UpperBody::Rail => 1,
            UpperBody::Wheel => 2,
        };
        let p = significant.clamp(1, 17) - 1;
        let mut t = format!(
            "{:4} {:4}      % nmatrix, iaconvex\n   0  312      % lquasid, xyzorder\n   1    0      % lsymmx, lsymmy\n{:4} {:4} {} {}  % mx, my, dx, dy [mm]\n",
            self.matrices, body, self.mx, self.my, self.dx_mm, self.dy_mm
        );
        let rows = 2 * self.my - 1;
        for m in 0..self.matrices {
            if self.matrices > 1 {
                t.push_str(&format!(
                    "%%%%%%%%\n% matrix {}, loaded row jy = {}\n%%%%%%%%\n{:4} {:8.3} {:8.3}\n",
                    m + 1,
                    m + 1,
                    m + 1,
                    0.0,
                    (m as f64 - (self.matrices / 2) as f64) * self.dy_mm
                ));
            }
            for r in 0..rows {
                let oy = r as i64 - (self.my as i64 - 1);
                t.push_str(&format!(
                    "% offset iy = {oy}\n%  ix     x      Cnn Cnx Cny  Cxn Cxx Cxy  Cyn Cyx Cyy\n"
                ));
                for ix in 0..self.mx {
                    t.push_str(&format!("{ix:4} {:9.4}", ix as f64 * self.dx_mm));
                    let base = ((m * rows + r) * self.mx + ix) * PER_LINE;
                    for v in &self.values[base..base + PER_LINE] {
                        t.push_str(&format!(" {v:.p$e}"));
                    }
                    t.push('\n');
                }
            }
        }
        t
    }

    /// The number of matrices: 1, or one per loaded row of the case's grid.
    pub fn matrices(&self) -> usize {
        self.matrices
    }

    /// The upper body (`iaconvex`).
    pub fn upper_body(&self) -> UpperBody {
        self.upper_body
    }

    /// The file's grid (mxfile, myfile).
    pub fn size(&self) -> (usize, usize) {
        (self.mx, self.my)
    }

    /// The file's element sizes (dx, dy) \[m\].
    pub fn spacing_m(&self) -> (f64, f64) {
        (self.dx_mm * 1e-3, self.dy_mm * 1e-3)
    }

    /// A 64-bit hash of the contents (equal files, equal fingerprints; not
    /// the converse): part of the kernel cache's key, whose hits compare
    /// the contents too.
    pub fn fingerprint(&self) -> u64 {
        self.fingerprint
    }

    /// This file claiming fingerprint `f` (tests of a collision).
    #[cfg(test)]
    pub(crate) fn with_fingerprint(self, f: u64) -> Self {
        Self {
            fingerprint: f,
            ..self
        }
    }

    /// Coefficient C_ij \[mm\] of matrix `matrix` (0-based) at offset (ox, oy):
    /// zero where the file does not hold it.
    pub fn coefficient_mm(
        &self,
        matrix: usize,
        i: Component,
        j: Component,
        ox: i64,
        oy: i64,
    ) -> f64 {
        let ax = ox.unsigned_abs();
        let ay = oy.unsigned_abs();
        if matrix >= self.matrices || ax >= self.mx as u64 || ay >= self.my as u64 {
            return 0.0;
        }
        let ax = ax as usize;
        let rows = 2 * self.my - 1;
        let row = (oy + self.my as i64 - 1) as usize;
        let v = self.values[((matrix * rows + row) * self.mx + ax) * PER_LINE + column(i, j)];
        if ox < 0 && odd_in_x(i, j) {
            -v
        } else {
            v
        }
    }

    /// Whether any normal/tangential coupling coefficient is non-zero.
    pub fn coupled(&self) -> bool {
        self.values
            .chunks_exact(PER_LINE)
            .any(|c| [1, 2, 3, 6].iter().any(|&k| c[k] != 0.0))
    }

    /// Whether C_xy = C_yx at every offset.
    pub fn symmetric_xy(&self) -> bool {
        self.values.chunks_exact(PER_LINE).all(|c| c[5] == c[7])
    }

    /// Checks the file against a grid of ny rows of dx x dy \[m\]:
    /// the element sizes (within [`SPACING_TOLERANCE_M`]) and the number
    /// of matrices (1 or ny). nx does not matter. Returns the field at fault and why.
    pub fn check_grid(
        &self,
        ny: usize,
        dx_m: f64,
        dy_m: f64,
    ) -> Result<(), (&'static str, String)> {
        let (fdx, fdy) = self.spacing_m();
        for (field, f, g) in [("dxfile", fdx, dx_m), ("dyfile", fdy, dy_m)] {
            // NaN sizes are not within.
            let within = (f - g).abs() <= SPACING_TOLERANCE_M;
            if !within {
                return Err((
                    field,
                    format!(
                        "the file's element size {:.6} mm differs from the grid's {:.6} mm by more than {} mm",
                        f * 1e3,
                        g * 1e3,
                        SPACING_TOLERANCE_M * 1e3
                    ),
                ));
            }
        }
        if self.matrices != 1 && self.matrices != ny {
            return Err((
                "nmatrix",
                format!(
                    "must be 1 or the grid's number of rows {ny}, got {}",
                    self.matrices
                ),
            ));
        }
        Ok(())
    }
}

/// The coefficients held (72 bytes a coefficient line).
impl HeapBytes for InfluenceFile {
    fn heap_bytes(&self) -> usize {
        self.values.heap_bytes()
    }
}

/// The kernels of one matrix of a file on a grid of nx x ny elements of
/// length dx, for materials of combined shear modulus G: the file's
/// coefficients C \[mm\] · 1e-3 / G \[m/Pa\] at offsets |ox| < min(mxfile,
/// nx), |oy| < min(myfile, ny), zero elsewhere (CONTACT's padding and
/// discarding).
#[derive(Debug, Clone, Copy)]
pub struct TableKernel<'a> {
    /// The file.
    pub file: &'a InfluenceFile,
    /// Its matrix (0-based; of a one-matrix file: 0).
    pub matrix: usize,
    /// Elements of the grid along x.
    pub nx: usize,
    /// Elements of the grid along y.
    pub ny: usize,
    /// Element length along x \[m\].
    pub dx_m: f64,
    /// Combined shear modulus G \[Pa\].
    pub shear_modulus_pa: f64,
}

impl TableKernel<'_> {
    /// The displacement coefficient (i, j) at offset (ox, oy) \[m/Pa\].
    pub fn displacement(&self, i: Component, j: Component, ox: i64, oy: i64) -> f64 {
        if ox.unsigned_abs() >= self.nx as u64 || oy.unsigned_abs() >= self.ny as u64 {
            return 0.0;
        }
        self.file.coefficient_mm(self.matrix, i, j, ox, oy) * 1e-3 / self.shear_modulus_pa
    }

    /// The value of kernel `kind` (i, j) at offset (ox, oy), as
    /// [`crate::core::influence::HalfSpaceInfluence::kernel`] gives it for
    /// the half-space.
    pub fn kernel(&self, kind: KernelKind, i: Component, j: Component, ox: i64, oy: i64) -> f64 {
        match kind {
            KernelKind::Displacement => self.displacement(i, j, ox, oy),
            KernelKind::SteadyRolling => {
                (self.displacement(i, j, ox, oy) - self.displacement(i, j, ox + 1, oy)) / self.dx_m
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use Component::*;

    /// A 2x2 file, one matrix: coefficient 100 iy + 10 ix + column.
    fn small(matrices: usize) -> InfluenceFile {
        InfluenceFile::from_coefficients(
            matrices,
            (2, 2),
            (2e-4, 3e-4),
            UpperBody::Rail,
            |m, i, j, ox, oy| (1000 * m as i64 + 100 * oy + 10 * ox) as f64 + column(i, j) as f64,
        )
        .unwrap()
    }

    #[test]
    fn text_round_trips_and_mirrors_in_x() {
        for matrices in [1, 3] {
            let f = small(matrices);
            let g = InfluenceFile::parse(&f.to_text(17)).unwrap();
            assert_eq!(f, g);
            assert_eq!(g.spacing_m(), (2e-4, 3e-4));
            let m = matrices - 1;
            let base = 1000.0 * m as f64;
            assert_eq!(g.coefficient_mm(m, X, Y, 1, -1), base - 100.0 + 10.0 + 5.0);
            // Odd pairs change sign at -ox, even ones do not.
            assert_eq!(
                g.coefficient_mm(m, X, Y, -1, -1),
                -(base - 100.0 + 10.0 + 5.0)
            );
            assert_eq!(g.coefficient_mm(m, N, Y, -1, 1), base + 100.0 + 10.0 + 2.0);
            assert_eq!(g.coefficient_mm(m, N, X, -1, 0), -(base + 10.0 + 1.0));
            assert_eq!(g.coefficient_mm(m, Y, X, -1, 0), -(base + 10.0 + 7.0));
            assert_eq!(g.coefficient_mm(m, X, N, -1, 0), -(base + 10.0 + 3.0));
            // Offsets the file does not hold are zero.
            assert_eq!(g.coefficient_mm(m, N, N, 2, 0), 0.0);
            assert_eq!(g.coefficient_mm(m, N, N, 0, -2), 0.0);
        }
    }

    #[test]
    fn table_kernel_pads_discards_and_differences() {
        let f = small(1);
        let k = TableKernel {
            file: &f,
            matrix: 0,
            nx: 4,
            ny: 1,
            dx_m: 2e-4,
            shear_modulus_pa: 1e9,
        };
        // C [mm] 1e-3 / G.
        assert_eq!(k.displacement(X, X, 1, 0), 14.0 * 1e-3 / 1e9);
        // Beyond the grid's rows (ny = 1) and the file's columns: zero.
        assert_eq!(k.displacement(X, X, 0, 1), 0.0);
        assert_eq!(k.displacement(X, X, 2, 0), 0.0);
        let steady = k.kernel(KernelKind::SteadyRolling, X, X, 0, 0);
        let expect = (4.0 * 1e-3 / 1e9 - 14.0 * 1e-3 / 1e9) / 2e-4;
        assert_eq!(steady, expect);
        // A grid of one column discards the file's ix = 1.
        let narrow = TableKernel { nx: 1, ..k };
        assert_eq!(narrow.displacement(X, X, 1, 0), 0.0);
    }

    fn error(text: &str) -> InfluenceFileError {
        InfluenceFile::parse(text).unwrap_err()
    }

    fn line_field(e: InfluenceFileError) -> (usize, &'static str) {
        match e {
            InfluenceFileError::Field { line, field, .. } => (line, field),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn errors_name_the_line_and_field() {
        let good = small(1).to_text(6);
        let lines: Vec<&str> = good.lines().collect();
        let with = |k: usize, l: &str| {
            let mut v = lines.clone();
            v[k] = l;
            v.join("\n")
        };
        // (line index, its text, the line and field named).
        for (k, text, named) in [
            (0, "1 3", (1, "iaconvex")),
            (1, "1 312", (2, "lquasid")),
            (1, "0 123", (2, "xyzorder")),
            (2, "0 0", (3, "lsymmx")),
            (3, "2 2 0.2", (4, "dyfile")),
            (3, "2 2 -0.2 0.3", (4, "dxfile")),
            (3, "2 x 0.2 0.3", (4, "myfile")),
            // Line 7 is the first coefficient line (two comment lines
            // before).
            (6, "1 0 1 2 3 4 5 6 7 8 9", (7, "ixofs")),
            (6, "0 0 1 2 3 4 5 6 7 8", (7, "Cyy")),
            (6, "0 0 1 2 3 4 nan 6 7 8 9", (7, "Cxx")),
            (6, "0 0 1 2 3 4 5 z 7 8 9", (7, "Cxy")),
            (6, "0 0 1 2 3 4 5 6 7 -1.5e6 9", (7, "Cyx")),
            (6, "0 0 1e300 2 3 4 5 6 7 8 9", (7, "Cnn")),
        ] {
            assert_eq!(line_field(error(&with(k, text))), named, "{text}");
        }
        assert_eq!(lines[6].split_whitespace().next(), Some("0"));
        // The bound itself is a coefficient; a long word is quoted cut.
        assert!(InfluenceFile::parse(&with(6, "0 0 1e6 2 3 4 5 6 7 8 -1e6")).is_ok());
        let long = format!("0 0 {} 2 3 4 5 6 7 8 9", "7".repeat(100_000));
        let m = error(&with(6, &long)).to_string();
        assert!(
            m.len() < 150 && m.ends_with("...") && m.contains("`Cnn`"),
            "{m}"
        );
        // Fortran exponents, commas and extra values are read.
        let f = InfluenceFile::parse(&with(6, "0, 0, 1D0 2 3 4 5 6 7 8 9.5d-1 99")).unwrap();
        assert_eq!(f.coefficient_mm(0, Y, Y, 0, -1), 0.95);
        // Truncated and trailing data.
        let cut = lines[..lines.len() - 1].join("\n");
        assert!(matches!(
            error(&cut),
            InfluenceFileError::Truncated { field: "ixofs", .. }
        ));
        let more = format!("{good}1 2 3\n");
        assert!(matches!(error(&more), InfluenceFileError::Trailing { .. }));
        // A per-row file checks its matrix numbers.
        let rows = small(3)
            .to_text(6)
            .replace("\n   2    0.000", "\n   5    0.000");
        assert_eq!(line_field(error(&rows)).1, "imatrix");
    }

    #[test]
    fn sizes_are_limited_before_storing() {
        let e = error("1 1\n0 312\n1 0\n2000 2000 0.1 0.1\n");
        assert_eq!(line_field(e), (4, "mxfile"));
        let e = error("1 1\n0 312\n1 0\n0 2 0.1 0.1\n");
        assert_eq!(line_field(e), (4, "mxfile"));
        let e = error("99999999999 1\n0 312\n1 0\n2 2 0.1 0.1\n");
        assert_eq!(line_field(e), (1, "nmatrix"));
    }

    #[test]
    fn grid_check_follows_contact() {
        let f = small(3);
        assert!(f.check_grid(3, 2e-4, 3e-4).is_ok());
        assert!(f.check_grid(3, 2e-4 + 0.9e-8, 3e-4).is_ok());
        assert_eq!(
            f.check_grid(3, 2e-4 + 1.1e-8, 3e-4).unwrap_err().0,
            "dxfile"
        );
        assert_eq!(f.check_grid(3, 2e-4, 3.1e-4).unwrap_err().0, "dyfile");
        assert_eq!(f.check_grid(4, 2e-4, 3e-4).unwrap_err().0, "nmatrix");
        assert!(small(1).check_grid(7, 2e-4, 3e-4).is_ok());
    }
}
