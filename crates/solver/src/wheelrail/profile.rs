//! The in-memory wheel/rail profile, its checks, and loading from files.
//!
//! The profile frame, the point order and the sign conventions are those of
//! the [`crate::wheelrail`] module documentation. The file formats and how
//! each is mapped to that frame are documented in
//! [`crate::wheelrail::readers`].

use std::fmt;
use std::path::{Path, PathBuf};

use thiserror::Error;

use super::readers;
use super::spline::{ProfileSpline, SplineError, SplineOptions};

/// Whether a profile belongs to a rail or to a wheel.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ProfileKind {
    /// A rail (or roller) profile: material below the curve (+z).
    Rail,
    /// A wheel profile: material above the curve (-z).
    Wheel,
}

impl fmt::Display for ProfileKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            ProfileKind::Rail => "rail",
            ProfileKind::Wheel => "wheel",
        })
    }
}

/// The variants of MiniProf files that are read.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum MiniProfVariant {
    /// The older text variant: a first line `MINIPROF ...`, free text, a
    /// line ending in `(Sd/Sh/qR)`, a blank line and the points.
    Text,
    /// The `Key=Value` variant (as `avg_HR.BAN`): header keys such as
    /// `XYPoints`, `ColumnDef`, `XOffset`, a blank line and the points.
    KeyValue,
    /// The 2020 variant: a first line `#MINIWHEELPROF` (or
    /// `#MINIRAILPROF`), a line `MINIPROF 2020`, free text, a blank line and
    /// the points.
    Y2020,
}

/// File formats for profiles.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ProfileFormat {
    /// Simpack rail or wheel profile (`.prr`, `.prw`).
    Simpack,
    /// MiniProf rail or wheel profile (`.ban`, `.whl`).
    MiniProf(MiniProfVariant),
    /// Plain two-column text/CSV: y, z per line.
    Plain,
}

impl fmt::Display for ProfileFormat {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ProfileFormat::Simpack => f.write_str("Simpack"),
            ProfileFormat::MiniProf(MiniProfVariant::Text) => f.write_str("MiniProf (text)"),
            ProfileFormat::MiniProf(MiniProfVariant::KeyValue) => {
                f.write_str("MiniProf (key=value)")
            }
            ProfileFormat::MiniProf(MiniProfVariant::Y2020) => f.write_str("MiniProf 2020"),
            ProfileFormat::Plain => f.write_str("plain y,z"),
        }
    }
}

/// Length unit of the plain two-column format (case files: `"m"`,
/// `"mm"`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Deserialize)]
pub enum LengthUnit {
    /// Metres (the default).
    #[serde(rename = "m")]
    Metre,
    /// Millimetres.
    #[serde(rename = "mm")]
    Millimetre,
}

impl LengthUnit {
    /// Metres per unit.
    pub fn metres(self) -> f64 {
        match self {
            LengthUnit::Metre => 1.0,
            LengthUnit::Millimetre => 1e-3,
        }
    }
}

/// What to do with the sign of z when reading a file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum MirrorZ {
    /// MiniProf: detect from the shape whether z points up and flip it if
    /// so (see [`crate::wheelrail::readers`]); Simpack: apply the file's
    /// `mirror.z`; plain: keep z as given.
    #[default]
    Auto,
    /// Never flip z beyond what the file itself says (Simpack `mirror.z`).
    Keep,
    /// Flip z (in addition to Simpack's `mirror.z`, which it cancels).
    Flip,
}

/// Limits of the profile checks; see [`Profile::from_points`] for what is
/// checked and repaired.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProfileChecks {
    /// Successive points closer than this are merged (the first is kept,
    /// with a warning) \[m\]. Default 1e-7 m = 0.1 µm, CONTACT's default
    /// minimum point distance. Exactly coincident points are always merged.
    pub merge_distance_m: f64,
    /// Largest distance between successive points \[m\]; a larger gap is an
    /// error (missing data). Default 5 mm; `f64::INFINITY` disables the check.
    pub max_gap_m: f64,
    /// A turn of the profile by more than this angle at one point is a
    /// reversal of direction: a spike or a backtracking pair of points
    /// \[rad\]. Default 120 degrees (real profiles turn by less than 15
    /// degrees between points; sharp designed corners by at most 90).
    pub reversal_angle_rad: f64,
    /// Largest defect repaired automatically \[m\]: a spike that sticks out
    /// at most this far from its neighbours is removed, a pair of points
    /// out of order that goes back at most this far is replaced by its
    /// mean, each with a warning. Larger defects are errors. Default 1 mm
    /// (the measured flange tip of `Car7216_0001r.whl` goes back 0.6 mm).
    pub max_repair_m: f64,
    /// Largest extent of the profile in y or z \[m\]; a larger profile is an
    /// error, usually a wrong length unit. Default 1 m.
    pub max_extent_m: f64,
    /// Smallest extent of the profile in y \[m\]; a narrower profile is an
    /// error, usually a table in metres read as millimetres. Default 1 mm
    /// (a rail head or a wheel tread spans 60 to 150 mm).
    pub min_width_m: f64,
}

impl Default for ProfileChecks {
    fn default() -> Self {
        Self {
            merge_distance_m: 1e-7,
            max_gap_m: 5e-3,
            reversal_angle_rad: 120f64.to_radians(),
            max_repair_m: 1e-3,
            max_extent_m: 1.0,
            min_width_m: 1e-3,
        }
    }
}

/// Options for [`load_profile_with`] and [`parse_profile`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LoadOptions {
    /// Expected kind. `None`: from the file extension (`.prr`, `.ban`:
    /// rail; `.prw`, `.whl`: wheel) or the file content (Simpack header
    /// `type`, `#MINIWHEELPROF`); plain files then have no kind. A Simpack
    /// header `type` that contradicts the expected kind is an error.
    pub kind: Option<ProfileKind>,
    /// Format. `None`: from the extension, sniffing the content where the
    /// extension does not tell (see [`detect_format`]). The MiniProf variant
    /// is always taken from the content.
    pub format: Option<ProfileFormat>,
    /// Mirror y (y -> -y): turns a left-hand profile into a right-hand one
    /// (combined with Simpack's `mirror.y`, which it cancels). Needed for
    /// MiniProf rail files measured with X towards the gauge side, like
    /// `avg_HR.BAN`.
    pub mirror_y: bool,
    /// Sign of z; see [`MirrorZ`].
    pub mirror_z: MirrorZ,
    /// Length unit of plain files. `None`: the file's `# unit: mm` comment
    /// or unit-suffixed column names (`y_mm`), else metres.
    pub plain_unit: Option<LengthUnit>,
    /// Limits of the checks.
    pub checks: ProfileChecks,
}

/// A file name and, where known, a line number (counted from 1), as shown
/// in messages: `avg_HR.BAN line 52` or `avg_HR.BAN`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SourceLocation {
    /// File name (or a name given to text that was parsed directly).
    pub file: String,
    /// Line number, from 1.
    pub line: Option<usize>,
}

impl SourceLocation {
    /// Location in `file` (shortened to [`MAX_QUOTE_CHARS`] characters:
    /// see [`quote`]), optionally at `line`.
    pub fn new(file: &str, line: Option<usize>) -> Self {
        Self {
            file: quote(file),
            line,
        }
    }
}

/// Most characters of any input text (a line, a key, a file name) that a
/// message or warning quotes; longer text is cut there (see [`quote`]).
pub const MAX_QUOTE_CHARS: usize = 100;

/// `text` as quoted in messages: whole when it has at most
/// [`MAX_QUOTE_CHARS`] characters, else its first ones followed by
/// `... (N characters)`, so that an error about a 10 kB line stays short.
pub fn quote(text: &str) -> String {
    match text.char_indices().nth(MAX_QUOTE_CHARS) {
        None => text.to_string(),
        Some((end, _)) => format!("{}... ({} characters)", &text[..end], text.chars().count()),
    }
}

/// Largest magnitude of a profile coordinate, y or z, after the file's
/// shifts, offsets and unit factors \[m\]: profiles are a few centimetres
/// from their origin; 10 m leaves room for any origin convention and
/// keeps the points' rounding far below a micrometre. Larger values are
/// a wrong offset or unit, and are rejected with the line of the point.
pub const MAX_COORDINATE_M: f64 = 10.0;

impl fmt::Display for SourceLocation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(l) => write!(f, "{} line {}", self.file, l),
            None => f.write_str(&self.file),
        }
    }
}

/// Which profile check failed, see [`ProfileError::Check`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum CheckKind {
    /// Fewer than 2 points.
    TooFewPoints,
    /// Two successive points are farther apart than `max_gap_m`.
    Gap,
    /// A pair of points out of order goes back against the profile's
    /// direction by more than `max_repair_m`.
    Backtracking,
    /// A single point sticks out by more than `max_repair_m`.
    Spike,
    /// The profile is larger than `max_extent_m` or narrower than
    /// `min_width_m` (wrong length unit?).
    Extent,
    /// A point lies farther than [`MAX_COORDINATE_M`] from the origin
    /// (wrong offset or unit factor?).
    Coordinate,
}

/// Everything that can go wrong when reading or checking a profile. Every
/// message names the file and, where it applies, the line.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ProfileError {
    /// The file could not be read.
    #[error("{file}: cannot read the file: {message}")]
    Io {
        /// File name.
        file: String,
        /// The operating system's message.
        message: String,
    },
    /// A line does not have the expected content.
    #[error("{at}: expected {expected}, found '{found}'")]
    Syntax {
        /// Where.
        at: SourceLocation,
        /// What was expected, e.g. `two numbers (y z)`.
        expected: String,
        /// The offending text.
        found: String,
    },
    /// The file's structure is wrong: missing header, truncated point block,
    /// badly nested sections, inconsistent or unsupported header values.
    #[error("{at}: {message}")]
    Format {
        /// Where.
        at: SourceLocation,
        /// What is wrong and what was expected.
        message: String,
    },
    /// The points were read but fail a profile check.
    #[error("{at}: {message}")]
    Check {
        /// Where (the line of the offending point, if it came from a file).
        at: SourceLocation,
        /// Which check.
        kind: CheckKind,
        /// What is wrong, with the limit that was exceeded.
        message: String,
    },
}

impl ProfileError {
    /// The location the error refers to (`None` for I/O errors).
    pub fn location(&self) -> Option<&SourceLocation> {
        match self {
            ProfileError::Io { .. } => None,
            ProfileError::Syntax { at, .. }
            | ProfileError::Format { at, .. }
            | ProfileError::Check { at, .. } => Some(at),
        }
    }
}

/// Something a reader repaired or ignored, kept with the profile.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ProfileWarning {
    /// Where.
    pub at: SourceLocation,
    /// What was done.
    pub message: String,
}

impl fmt::Display for ProfileWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.at, self.message)
    }
}

/// A point on its way from a file to a [`Profile`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct RawPoint {
    pub y: f64,
    pub z: f64,
    pub weight: f64,
    pub line: Option<usize>,
}

/// What a reader hands to [`finish`], in metres and already mirrored.
#[derive(Debug, Clone)]
pub(crate) struct RawProfile {
    pub kind: Option<ProfileKind>,
    pub format: Option<ProfileFormat>,
    pub description: Option<String>,
    pub points: Vec<RawPoint>,
    pub warnings: Vec<ProfileWarning>,
    /// Extra merge distance from the file (Simpack `point.dist.min`) [m].
    pub merge_distance_m: f64,
}

/// A checked wheel or rail profile: points (y, z) in metres in the profile
/// frame of [`crate::wheelrail`], in CONTACT point order when the kind is
/// known (rails with increasing y, wheels with decreasing y).
#[derive(Debug, Clone, PartialEq)]
pub struct Profile {
    name: String,
    path: Option<PathBuf>,
    kind: Option<ProfileKind>,
    format: Option<ProfileFormat>,
    description: Option<String>,
    points: Vec<[f64; 2]>,
    weights: Vec<f64>,
    lines: Vec<Option<usize>>,
    warnings: Vec<ProfileWarning>,
}

impl Profile {
    /// Builds a checked profile from points (y, z) \[m\] in the profile frame.
    ///
    /// If `kind` is given the points are put in CONTACT order (reversed if
    /// needed). Then, with the limits in `checks`:
    ///
    /// * more than `max_extent_m` in y or z, less than `min_width_m` in y,
    ///   or fewer than 2 points, is an error;
    /// * successive points closer than `merge_distance_m` are merged;
    /// * a turn of more than `reversal_angle_rad` at two successive points
    ///   marks a pair out of order (backtracking), at a single point a
    ///   spike; defects up to `max_repair_m` are repaired (the pair replaced
    ///   by its mean, the spike removed), larger ones are errors;
    /// * a gap larger than `max_gap_m` between successive points is an error.
    ///
    /// Repairs are listed in [`Profile::warnings`].
    pub fn from_points(
        name: &str,
        kind: Option<ProfileKind>,
        points_m: &[[f64; 2]],
        checks: &ProfileChecks,
    ) -> Result<Profile, ProfileError> {
        for (i, p) in points_m.iter().enumerate() {
            if !(p[0].is_finite() && p[1].is_finite()) {
                return Err(ProfileError::Syntax {
                    at: SourceLocation::new(name, None),
                    expected: format!("finite coordinates for point {i}"),
                    found: format!("({}, {})", p[0], p[1]),
                });
            }
        }
        let raw = RawProfile {
            kind,
            format: None,
            description: None,
            points: points_m
                .iter()
                .map(|p| RawPoint {
                    y: p[0],
                    z: p[1],
                    weight: 1.0,
                    line: None,
                })
                .collect(),
            warnings: Vec::new(),
            merge_distance_m: 0.0,
        };
        finish(name, raw, checks)
    }

    /// File name the profile was read from (or the name given to
    /// [`Profile::from_points`] / the `parse_*` functions).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Full path, when read by [`load_profile`].
    pub fn path(&self) -> Option<&Path> {
        self.path.as_deref()
    }

    /// Rail or wheel, when the file or the caller says so.
    pub fn kind(&self) -> Option<ProfileKind> {
        self.kind
    }

    /// The file format, `None` for profiles built from points.
    pub fn format(&self) -> Option<ProfileFormat> {
        self.format
    }

    /// Free-text description from the file (Simpack `comment`, MiniProf
    /// file name line or `Filename`), if any.
    pub fn description(&self) -> Option<&str> {
        self.description.as_deref()
    }

    /// The points (y, z) \[m\].
    pub fn points(&self) -> &[[f64; 2]] {
        &self.points
    }

    /// Relative weight of each point for smoothing (Simpack's third
    /// column; 1 elsewhere).
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// Line of the file each point came from (`None` for points built in
    /// memory; a point averaged from two out-of-order points has the first
    /// of their lines).
    pub fn source_lines(&self) -> &[Option<usize>] {
        &self.lines
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// Whether the profile has no points (never true for a checked profile).
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// What the reader and the checks repaired or ignored.
    pub fn warnings(&self) -> &[ProfileWarning] {
        &self.warnings
    }

    /// Range (min, max) of y \[m\].
    pub fn y_range_m(&self) -> (f64, f64) {
        range(self.points.iter().map(|p| p[0]))
    }

    /// Range (min, max) of z \[m\].
    pub fn z_range_m(&self) -> (f64, f64) {
        range(self.points.iter().map(|p| p[1]))
    }

    /// The profile mirrored in y (y -> -y), e.g. the left-hand profile of a
    /// right-hand one; the point order is reversed so that it stays in
    /// CONTACT order.
    pub fn mirrored_y(&self) -> Profile {
        let mut p = self.clone();
        for q in &mut p.points {
            q[0] = -q[0];
        }
        p.points.reverse();
        p.weights.reverse();
        p.lines.reverse();
        p
    }

    /// The profile shifted by `dy_m`, `dz_m` \[m\], e.g. to put a MiniProf
    /// wheel's origin (the flange back) at the tape circle.
    pub fn translated(&self, dy_m: f64, dz_m: f64) -> Profile {
        let mut p = self.clone();
        for q in &mut p.points {
            q[0] += dy_m;
            q[1] += dz_m;
        }
        p
    }

    /// The smoothing spline through the points (with their weights); see
    /// [`crate::wheelrail::spline`].
    pub fn spline(&self, options: &SplineOptions) -> Result<ProfileSpline, SplineError> {
        ProfileSpline::with_weights(&self.points, Some(&self.weights), options)
    }
}

fn range(it: impl Iterator<Item = f64>) -> (f64, f64) {
    it.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    })
}

/// Reads a profile file with default [`LoadOptions`], choosing the reader
/// by extension and content (see [`detect_format`]).
pub fn load_profile(path: impl AsRef<Path>) -> Result<Profile, ProfileError> {
    load_profile_with(path, &LoadOptions::default())
}

/// Reads a profile file with the given options.
pub fn load_profile_with(
    path: impl AsRef<Path>,
    options: &LoadOptions,
) -> Result<Profile, ProfileError> {
    let path = path.as_ref();
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| path.display().to_string());
    let bytes = std::fs::read(path).map_err(|e| ProfileError::Io {
        file: path.display().to_string(),
        message: e.to_string(),
    })?;
    // Profile files are ASCII; tolerate other code pages in free text.
    let text = String::from_utf8_lossy(&bytes);
    let mut profile = parse_profile(&text, &name, options)?;
    profile.path = Some(path.to_path_buf());
    Ok(profile)
}

/// Parses profile text; `file_name` is used for the format (by its
/// extension) and in messages. A wheel slices file (`.slcw`) is refused
/// by name: it is read by [`crate::wheelrail::load_wheel_slices`].
pub fn parse_profile(
    text: &str,
    file_name: &str,
    options: &LoadOptions,
) -> Result<Profile, ProfileError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    if crate::wheelrail::slices::is_wheel_slices_file(file_name) {
        return Err(ProfileError::Format {
            at: SourceLocation::new(file_name, None),
            message: "a wheel slices file (an out-of-round wheel) is not a single profile; \
                      the command line's case files and the CONTACT library take it"
                .into(),
        });
    }
    let format = options
        .format
        .unwrap_or_else(|| detect_format(file_name, text));
    let kind = options.kind.or_else(|| kind_from_extension(file_name));
    let raw = match format {
        ProfileFormat::Simpack => readers::read_simpack(text, file_name, kind, options)?,
        ProfileFormat::MiniProf(_) => readers::read_miniprof(text, file_name, kind, options)?,
        ProfileFormat::Plain => readers::read_plain(text, file_name, kind, options)?,
    };
    finish(file_name, raw, &options.checks)
}

/// The format of a file: by extension (`.prr`/`.prw` Simpack, `.ban`/`.whl`
/// MiniProf, case-insensitive); for other extensions by content: a line
/// `header.begin` or `spline.begin` means Simpack; a first line starting
/// with `MINIPROF` or `#MINI`, or a header key `XYPoints=`/`ColumnDef=`
/// before the first blank line, means MiniProf; anything else is plain.
pub fn detect_format(file_name: &str, text: &str) -> ProfileFormat {
    match extension(file_name).as_deref() {
        Some("prr") | Some("prw") => ProfileFormat::Simpack,
        Some("ban") | Some("whl") => ProfileFormat::MiniProf(readers::miniprof_variant(text)),
        _ => readers::sniff(text),
    }
}

/// Rail or wheel from the extension: `.prr`, `.ban` rail; `.prw`, `.whl`
/// wheel.
pub fn kind_from_extension(file_name: &str) -> Option<ProfileKind> {
    match extension(file_name).as_deref() {
        Some("prr") | Some("ban") => Some(ProfileKind::Rail),
        Some("prw") | Some("whl") => Some(ProfileKind::Wheel),
        _ => None,
    }
}

fn extension(file_name: &str) -> Option<String> {
    Path::new(file_name)
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
}

/// Puts the points in CONTACT order, runs the checks and builds the profile.
pub(crate) fn finish(
    name: &str,
    mut raw: RawProfile,
    checks: &ProfileChecks,
) -> Result<Profile, ProfileError> {
    let at = |line: Option<usize>| SourceLocation::new(name, line);
    let pts = &mut raw.points;
    if pts.len() < 2 {
        return Err(ProfileError::Check {
            at: at(None),
            kind: CheckKind::TooFewPoints,
            message: format!("a profile needs at least 2 points, found {}", pts.len()),
        });
    }

    // CONTACT order: rails with increasing y, wheels with decreasing y.
    if let Some(kind) = raw.kind {
        let rising = pts[pts.len() - 1].y > pts[0].y;
        let want_rising = kind == ProfileKind::Rail;
        if rising != want_rising {
            pts.reverse();
        }
    }

    // A point beyond MAX_COORDINATE_M: a wrong offset or unit factor.
    let far = pts
        .iter()
        .find(|p| !(p.y.abs() <= MAX_COORDINATE_M && p.z.abs() <= MAX_COORDINATE_M))
        .copied();
    let outside = |p: &RawPoint| {
        format!(
            "point (y = {:e} m, z = {:e} m) lies outside +-{MAX_COORDINATE_M} m, after the \
             file's offsets, shifts and unit factor",
            p.y, p.z
        )
    };
    let (ylo, yhi) = range(pts.iter().map(|p| p.y));
    let (zlo, zhi) = range(pts.iter().map(|p| p.z));
    if yhi - ylo > checks.max_extent_m || zhi - zlo > checks.max_extent_m {
        return Err(ProfileError::Check {
            at: at(far.and_then(|p| p.line)),
            kind: CheckKind::Extent,
            message: format!(
                "the profile spans {:.4} m in y and {:.4} m in z, more than the limit of {} m \
                 (ProfileChecks::max_extent_m); wrong length unit? (Simpack `units.len.f`, \
                 plain files `# unit: mm`){}",
                yhi - ylo,
                zhi - zlo,
                checks.max_extent_m,
                far.map(|p| format!("; {}", outside(&p)))
                    .unwrap_or_default()
            ),
        });
    }
    if let Some(p) = far {
        return Err(ProfileError::Check {
            at: at(p.line),
            kind: CheckKind::Coordinate,
            message: format!("{}; wrong offset or length unit?", outside(&p)),
        });
    }
    if yhi - ylo < checks.min_width_m {
        return Err(ProfileError::Check {
            at: at(None),
            kind: CheckKind::Extent,
            message: format!(
                "the profile spans {:e} m in y, less than the limit of {} m \
                 (ProfileChecks::min_width_m); wrong length unit? (a table in metres read as \
                 millimetres)",
                yhi - ylo,
                checks.min_width_m,
            ),
        });
    }
    merge_close_points(name, &mut raw, checks);
    repair_reversals(name, &mut raw, checks)?;

    let pts = &raw.points;
    for k in 1..pts.len() {
        let d = (pts[k].y - pts[k - 1].y).hypot(pts[k].z - pts[k - 1].z);
        if d > checks.max_gap_m {
            return Err(ProfileError::Check {
                at: at(pts[k].line),
                kind: CheckKind::Gap,
                message: format!(
                    "gap of {} mm between point ({}) and the previous point ({}), more than \
                     the limit of {} mm (ProfileChecks::max_gap_m); missing data?",
                    mm(d),
                    fmt_point_mm(&pts[k]),
                    fmt_point_mm(&pts[k - 1]),
                    mm(checks.max_gap_m)
                ),
            });
        }
    }
    if pts.len() < 2 {
        return Err(ProfileError::Check {
            at: at(None),
            kind: CheckKind::TooFewPoints,
            message: format!(
                "a profile needs at least 2 distinct points, {} left after merging",
                pts.len()
            ),
        });
    }

    Ok(Profile {
        name: name.to_string(),
        path: None,
        kind: raw.kind,
        format: raw.format,
        description: raw.description,
        points: pts.iter().map(|p| [p.y, p.z]).collect(),
        weights: pts.iter().map(|p| p.weight).collect(),
        lines: pts.iter().map(|p| p.line).collect(),
        warnings: raw.warnings,
    })
}

fn fmt_point_mm(p: &RawPoint) -> String {
    format!("y = {} mm, z = {} mm", mm(p.y), mm(p.z))
}

/// A length [m] in mm with at most 4 decimals, without trailing zeros.
fn mm(v_m: f64) -> String {
    let s = format!("{:.4}", v_m * 1e3);
    let s = if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    };
    if s == "-0" {
        "0".to_string()
    } else {
        s
    }
}

fn fmt_lines(lines: &[Option<usize>]) -> String {
    let known: Vec<String> = lines.iter().flatten().map(|l| l.to_string()).collect();
    if known.is_empty() {
        return String::new();
    }
    let shown = known.len().min(8);
    let mut s = format!(
        " (line{} {}",
        if known.len() > 1 { "s" } else { "" },
        known[..shown].join(", ")
    );
    if known.len() > shown {
        s.push_str(&format!(", and {} more", known.len() - shown));
    }
    s.push(')');
    s
}

/// Drops points closer than the merge distance to the last kept point.
fn merge_close_points(name: &str, raw: &mut RawProfile, checks: &ProfileChecks) {
    let limit = checks.merge_distance_m.max(raw.merge_distance_m).max(0.0);
    let mut kept: Vec<RawPoint> = Vec::with_capacity(raw.points.len());
    let mut dropped: Vec<Option<usize>> = Vec::new();
    for &p in &raw.points {
        match kept.last() {
            Some(q) if ((p.y - q.y).hypot(p.z - q.z)) <= limit => dropped.push(p.line),
            _ => kept.push(p),
        }
    }
    if !dropped.is_empty() {
        raw.warnings.push(ProfileWarning {
            at: SourceLocation::new(name, dropped[0]),
            message: format!(
                "dropped {} point{} closer than {} mm to the previous one{}",
                dropped.len(),
                if dropped.len() > 1 { "s" } else { "" },
                mm(limit),
                fmt_lines(&dropped)
            ),
        });
        raw.points = kept;
    }
}

/// Turn angle [rad] at point i between segments (i-1, i) and (i, i+1).
fn turn_angle(p: &[RawPoint], i: usize) -> f64 {
    let (ax, ay) = (p[i].y - p[i - 1].y, p[i].z - p[i - 1].z);
    let (bx, by) = (p[i + 1].y - p[i].y, p[i + 1].z - p[i].z);
    let na = ax.hypot(ay);
    let nb = bx.hypot(by);
    if na == 0.0 || nb == 0.0 {
        return 0.0;
    }
    ((ax * bx + ay * by) / (na * nb)).clamp(-1.0, 1.0).acos()
}

/// Finds spikes and pairs of points out of order; repairs small ones.
fn repair_reversals(
    name: &str,
    raw: &mut RawProfile,
    checks: &ProfileChecks,
) -> Result<(), ProfileError> {
    let limit = checks.reversal_angle_rad;
    let mut start = 1;
    loop {
        let p = &raw.points;
        let n = p.len();
        if n < 3 {
            return Ok(());
        }
        let Some(i) = (start.max(1)..n - 1).find(|&i| turn_angle(p, i) > limit) else {
            return Ok(());
        };
        let turn_deg = turn_angle(p, i).to_degrees();
        if i + 1 < n - 1 && turn_angle(p, i + 1) > limit {
            // Points i and i+1 out of order: i+1 lies behind i.
            let (dx, dz) = (p[i].y - p[i - 1].y, p[i].z - p[i - 1].z);
            let len = dx.hypot(dz);
            let back = -((p[i + 1].y - p[i].y) * dx + (p[i + 1].z - p[i].z) * dz) / len;
            if back > checks.max_repair_m {
                return Err(ProfileError::Check {
                    at: SourceLocation::new(name, p[i + 1].line),
                    kind: CheckKind::Backtracking,
                    message: format!(
                        "point ({}) goes back {} mm against the direction of the profile \
                         after point ({}){}: the points are out of order (turns of {:.0} and \
                         {:.0} degrees; repaired automatically only up to {} mm, \
                         ProfileChecks::max_repair_m)",
                        fmt_point_mm(&p[i + 1]),
                        mm(back),
                        fmt_point_mm(&p[i]),
                        fmt_lines(&[p[i].line]),
                        turn_deg,
                        turn_angle(p, i + 1).to_degrees(),
                        mm(checks.max_repair_m)
                    ),
                });
            }
            let mean = RawPoint {
                y: 0.5 * (p[i].y + p[i + 1].y),
                z: 0.5 * (p[i].z + p[i + 1].z),
                weight: 0.5 * (p[i].weight + p[i + 1].weight),
                line: p[i].line,
            };
            let mut pair = [p[i].line, p[i + 1].line];
            pair.sort();
            let msg = format!(
                "pair of points out of order{}, one {} mm behind the other; replaced both by \
                 their mean",
                fmt_lines(&pair),
                mm(back.max(0.0))
            );
            raw.warnings.push(ProfileWarning {
                at: SourceLocation::new(name, pair[0].or(pair[1])),
                message: msg,
            });
            raw.points[i] = mean;
            raw.points.remove(i + 1);
        } else {
            // Spike at point i: distance from the chord of its neighbours.
            let (ax, az) = (p[i + 1].y - p[i - 1].y, p[i + 1].z - p[i - 1].z);
            let (bx, bz) = (p[i].y - p[i - 1].y, p[i].z - p[i - 1].z);
            let l2 = ax * ax + az * az;
            let s = if l2 > 0.0 {
                ((ax * bx + az * bz) / l2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let height = (bx - s * ax).hypot(bz - s * az);
            if height > checks.max_repair_m {
                return Err(ProfileError::Check {
                    at: SourceLocation::new(name, p[i].line),
                    kind: CheckKind::Spike,
                    message: format!(
                        "spike: point ({}) sticks out {} mm from its neighbours, turning the \
                         profile by {:.0} degrees (repaired automatically only up to {} mm, \
                         ProfileChecks::max_repair_m)",
                        fmt_point_mm(&p[i]),
                        mm(height),
                        turn_deg,
                        mm(checks.max_repair_m)
                    ),
                });
            }
            raw.warnings.push(ProfileWarning {
                at: SourceLocation::new(name, p[i].line),
                message: format!(
                    "removed a spike sticking out {} mm (turn of {:.0} degrees)",
                    mm(height),
                    turn_deg
                ),
            });
            raw.points.remove(i);
        }
        start = i.saturating_sub(2).max(1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line_points(n: usize) -> Vec<[f64; 2]> {
        (0..n).map(|k| [k as f64 * 1e-3, 0.0]).collect()
    }

    #[test]
    fn contact_order_and_mirroring() {
        let pts = line_points(5);
        let w = Profile::from_points(
            "w",
            Some(ProfileKind::Wheel),
            &pts,
            &ProfileChecks::default(),
        )
        .unwrap();
        assert!(w.points()[0][0] > w.points()[4][0]);
        let r = Profile::from_points(
            "r",
            Some(ProfileKind::Rail),
            &pts,
            &ProfileChecks::default(),
        )
        .unwrap();
        assert!(r.points()[0][0] < r.points()[4][0]);
        let m = r.mirrored_y();
        assert!(m.points()[0][0] < m.points()[4][0]);
        assert_eq!(m.points()[0][0], -0.004);
        let t = r.translated(0.07, -0.001);
        assert_eq!(t.points()[0], [0.07, -0.001]);
    }

    #[test]
    fn duplicates_are_merged_with_a_warning() {
        let mut pts = line_points(5);
        pts.insert(2, pts[2]);
        let p = Profile::from_points("d", None, &pts, &ProfileChecks::default()).unwrap();
        assert_eq!(p.len(), 5);
        assert_eq!(p.warnings().len(), 1);
    }

    #[test]
    fn small_defects_are_repaired_large_ones_rejected() {
        let checks = ProfileChecks::default();
        // A pair out of order by 0.2 mm: repaired.
        let mut pts = line_points(8);
        pts[4][0] = 0.0028;
        let p = Profile::from_points("b", None, &pts, &checks).unwrap();
        assert_eq!(p.len(), 7);
        assert!(
            p.warnings()[0].message.contains("out of order"),
            "{}",
            p.warnings()[0]
        );
        // Out of order by 2.5 mm: error.
        let mut pts = line_points(8);
        pts[4][0] = 0.0005;
        let e = Profile::from_points("b", None, &pts, &checks).unwrap_err();
        assert!(
            matches!(
                e,
                ProfileError::Check {
                    kind: CheckKind::Backtracking,
                    ..
                }
            ),
            "{e}"
        );
        // A spike: 0.5 mm high between neighbours 0.2 mm apart turns the
        // profile by 136 degrees and is removed; 3 mm high is an error.
        let fine: Vec<[f64; 2]> = (0..20).map(|k| [k as f64 * 0.2e-3, 0.0]).collect();
        let mut pts = fine.clone();
        pts[10][1] = -0.5e-3;
        let p = Profile::from_points("s", None, &pts, &checks).unwrap();
        assert_eq!(p.len(), 19);
        assert!(p.warnings()[0].message.contains("spike"));
        let mut pts = fine.clone();
        pts[10][1] = -3e-3;
        let e = Profile::from_points("s", None, &pts, &checks).unwrap_err();
        assert!(
            matches!(
                e,
                ProfileError::Check {
                    kind: CheckKind::Spike,
                    ..
                }
            ),
            "{e}"
        );
        // A bump of 0.3 mm over 1 mm spacing is not a reversal: kept.
        let mut pts = line_points(8);
        pts[4][1] = 0.3e-3;
        let p = Profile::from_points("s", None, &pts, &checks).unwrap();
        assert_eq!(p.len(), 8);
        assert!(p.warnings().is_empty());
    }

    #[test]
    fn gaps_extent_and_count() {
        let checks = ProfileChecks::default();
        let pts = vec![[0.0, 0.0], [0.001, 0.0], [0.010, 0.0]];
        let e = Profile::from_points("g", None, &pts, &checks).unwrap_err();
        assert!(
            matches!(
                e,
                ProfileError::Check {
                    kind: CheckKind::Gap,
                    ..
                }
            ),
            "{e}"
        );
        let pts: Vec<[f64; 2]> = (0..2000).map(|k| [k as f64 * 1e-3, 0.0]).collect();
        let e = Profile::from_points("x", None, &pts, &checks).unwrap_err();
        assert!(
            matches!(
                e,
                ProfileError::Check {
                    kind: CheckKind::Extent,
                    ..
                }
            ),
            "{e}"
        );
        // A 60 mm rail head given in metres and read as millimetres: 60 um.
        let pts: Vec<[f64; 2]> = (0..61).map(|k| [k as f64 * 1e-6, 0.0]).collect();
        let e = Profile::from_points("mm", None, &pts, &checks).unwrap_err();
        assert!(
            matches!(
                e,
                ProfileError::Check {
                    kind: CheckKind::Extent,
                    ..
                }
            ) && e.to_string().contains("min_width_m"),
            "{e}"
        );
        let e = Profile::from_points("c", None, &[[0.0, 0.0]], &checks).unwrap_err();
        assert!(matches!(
            e,
            ProfileError::Check {
                kind: CheckKind::TooFewPoints,
                ..
            }
        ));
        let e =
            Profile::from_points("n", None, &[[0.0, f64::NAN], [1.0, 0.0]], &checks).unwrap_err();
        assert!(matches!(e, ProfileError::Syntax { .. }));
    }
}
