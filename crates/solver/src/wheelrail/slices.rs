//! Rails whose profile varies along the track (switches and crossings):
//! CONTACT's rail slices file (`.slcs`), a list of rail profiles at
//! positions u along the track, interpolated between them to a surface;
//! and out-of-round wheels (wheel flats, polygonisation): CONTACT's wheel
//! slices file (`.slcw`), wheel profiles at angles theta round the wheel
//! ([`WheelSlices`], whose docs give the convention of theta and the
//! wheelset's pitch).
//!
//! # The file (CONTACT's user guide, "Rail slices-file")
//!
//! Lines starting with `%` and blank lines are skipped; text after the
//! values of a line is a comment.
//!
//! ```text
//!    0.000    1000.0   U_OFFSET [usr], U_SCALE [mm/usr]
//!      148             NSLC
//!        0    0    0   NFEAT, NKINK, NACCEL
//!        1             U_INTPOL
//!  -75.00000   'uk_crossing/Crossing_1.txt'      (NSLC lines: U_SLC, RFNAME)
//!    ...
//! ```
//!
//! A slice lies at u = U_SCALE (U_OFFSET + U_SLC) millimetres; the slices
//! are in strictly increasing u, at least 0.001 mm apart (CONTACT's
//! rule). Each profile file name is relative to the slices file and read
//! by the profile readers ([`crate::wheelrail::parse_profile`]: Simpack,
//! MiniProf or plain). Built: one part per slice (NFEAT <= 1, no feature
//! table) and the interpolating spline along u (U_INTPOL = 1). Refused,
//! naming the line: NFEAT >= 2 (features dividing the slices into parts,
//! interruptions), U_INTPOL = 2 (the approximating spline) and a nonzero
//! PERTURB.
//!
//! A wheel slices file has the same lines with TH_OFFSET, TH_SCALE
//! (radians per unit), TH_INTPOL and TH_SLC; its slices at least 0.001
//! rad apart. Built for wheels: TH_INTPOL = 1 and 2 (CONTACT's
//! approximating spline, below), NFEAT <= 1; refused as for rails: NFEAT
//! >= 2 and PERTURB.
//!
//! # The surface
//!
//! Interpolation paths run along u through corresponding points of the
//! slices: point i of every slice when all slices have the same number of
//! points (the correspondence of slices generated together), otherwise
//! each slice resampled uniformly in its summed chord length to as many
//! points as the longest slice needs at [`RESAMPLE_SPACING_M`] (CONTACT's
//! `varprof_make_vj`: 1 + floor(L / 0.5 mm) segments per part, L the
//! part's largest length over the slices). Along each path, y and z are natural cubic splines in u
//! through the slices (CONTACT uses a tensor B-spline; both interpolate
//! the slices). The rail at a position u is the profile through the
//! paths' points there ([`RailSlices::profile_at`]); its height at a
//! lateral y is the visible (highest) surface over y
//! ([`RailSlices::z_at`]). A slices file whose slices are all one profile
//! is that profile bit for bit.
//!
//! The approximating spline (TH_INTPOL = 2, CONTACT's
//! `bspline_make_2d_bspline` with `use_approx`): along each path the cubic
//! B-spline whose control points are the slices' points themselves, on
//! knots at the slices (three more spaced as the first interval before the
//! first slice and as the last after the last), with a phantom control
//! point extrapolating linearly beyond each end. It passes near, not
//! through, the slices: on equally spaced slices it is (p_(k-1) + 4 p_k +
//! p_(k+1)) / 6 at slice k and reproduces a path linear in theta; on a
//! wheel flat sampled every 2 mrad it smooths over about two slices
//! (4 mm of circumference).

use std::path::Path;
use std::sync::Arc;

use crate::wheelrail::profile::{
    quote, LoadOptions, Profile, ProfileChecks, ProfileError, ProfileKind, SourceLocation,
};

/// Largest spacing of the points of resampled slices \[m\] (CONTACT's
/// `ds_max2d`, 0.5 mm).
pub const RESAMPLE_SPACING_M: f64 = 0.5e-3;

/// Smallest distance between successive slices \[m\] (CONTACT's 0.001 mm).
pub const MIN_SLICE_SPACING_M: f64 = 1e-6;

/// Half the range of angles round the one facing the rail over which
/// [`WheelSlices::facing_rail_points`] looks for the wheel's lowest points
/// \[rad\] (CONTACT's search range round -pitch, 0.2 rad).
pub const FACING_HALF_ANGLE_RAD: f64 = 0.2;

/// The step of those angles \[rad\] (0.25 mm on a wheel of 490 mm, an
/// eighth of the 2 mrad between the slices of CONTACT's wheel flat).
pub const FACING_STEP_RAD: f64 = 5e-4;

/// Smallest angle between successive wheel slices \[rad\] (CONTACT's
/// 0.001 rad).
pub const MIN_WHEEL_SLICE_SPACING_RAD: f64 = 1e-3;

/// A rail profile varying along the track: its slices and the paths
/// between them (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct RailSlices {
    name: String,
    /// The slices' paths along u \[m\] (natural cubic splines).
    paths: SlicePaths,
}

/// The slices of a surface along one coordinate (u along the track \[m\]
/// or theta round a wheel \[rad\]) and the paths through them: what rail
/// and wheel slices share.
#[derive(Debug, Clone, PartialEq)]
struct SlicePaths {
    /// Positions of the slices, strictly increasing.
    at: Vec<f64>,
    /// Per slice, its points along the interpolation paths (y, z) \[m\],
    /// as many in every slice.
    points: Vec<Vec<[f64; 2]>>,
    /// How the paths run between the slices.
    along: Along,
}

/// The spline of every path along the slices' coordinate.
#[derive(Debug, Clone, PartialEq)]
enum Along {
    /// The natural cubic spline through the slices: per slice, the second
    /// derivatives of y and z of every path (zero at the first and last).
    Interpolating { second: Vec<Vec<[f64; 2]>> },
    /// CONTACT's approximating spline (TH_INTPOL / U_INTPOL = 2): the
    /// cubic B-spline whose control points are the slices themselves,
    /// with knots at the slices (module docs).
    Approximating {
        /// The knots: three spaced as the first interval before the first
        /// slice, one at every slice, three after the last.
        knots: Vec<f64>,
        /// Control points per path: a phantom before the first slice,
        /// the slices, a phantom after the last.
        control: Vec<Vec<[f64; 2]>>,
    },
}

/// How the paths of a slices file run between the slices (its U_INTPOL or
/// TH_INTPOL).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SliceInterpolation {
    /// 1: a cubic spline through the slices.
    Interpolating,
    /// 2: CONTACT's approximating spline, which smooths a little and does
    /// not pass through the slices.
    Approximating,
}

/// One slice as read: its position and profile.
#[derive(Debug, Clone)]
pub struct Slice {
    /// Track position u \[m\].
    pub u_m: f64,
    /// The profile (canonical right-hand rail profile, metres).
    pub profile: Profile,
}

/// The header and slice lines of a slices file, before the profiles are
/// read: (position, profile file name, line) per slice.
#[derive(Debug, Clone, PartialEq)]
pub struct SlicesFile {
    /// The slices: position (u \[m\] of a rail slices file, theta \[rad\]
    /// of a wheel slices file), the profile file name as written, the
    /// line it is on.
    pub slices: Vec<(f64, String, usize)>,
    /// U_INTPOL or TH_INTPOL.
    pub interpolation: SliceInterpolation,
}

/// What the slices of a file lie along.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SliceAxis {
    /// A rail slices file (`.slcs`): positions u along the track, U_SCALE
    /// millimetres per unit.
    Track,
    /// A wheel slices file (`.slcw`): angles theta round the wheel,
    /// TH_SCALE radians per unit.
    Wheel,
}

impl SliceAxis {
    /// The prefix of the file's keywords (U_OFFSET, TH_OFFSET, ...).
    fn key(self) -> &'static str {
        match self {
            SliceAxis::Track => "U",
            SliceAxis::Wheel => "TH",
        }
    }

    /// The name of a slice's profile file in CONTACT's user guide.
    fn file_key(self) -> &'static str {
        match self {
            SliceAxis::Track => "RFNAME",
            SliceAxis::Wheel => "WFNAME",
        }
    }

    /// SI units (m, rad) per unit of the scaled position (mm, rad).
    fn si_per_unit(self) -> f64 {
        match self {
            SliceAxis::Track => 1e-3,
            SliceAxis::Wheel => 1.0,
        }
    }

    /// Smallest distance between successive slices, SI (held to a relative
    /// 1e-9 below it: slices given exactly that far apart pass whatever the
    /// rounding of their positions).
    fn min_spacing(self) -> f64 {
        match self {
            SliceAxis::Track => MIN_SLICE_SPACING_M,
            SliceAxis::Wheel => MIN_WHEEL_SLICE_SPACING_RAD,
        }
    }

    /// A position (SI) as the messages give it: `u = 12 mm`, `theta =
    /// 0.5 rad`.
    fn show(self, v: f64) -> String {
        match self {
            SliceAxis::Track => format!("u = {} mm", v * 1e3),
            SliceAxis::Wheel => format!("theta = {v} rad"),
        }
    }

    /// The profile kind of its slices.
    fn kind(self) -> ProfileKind {
        match self {
            SliceAxis::Track => ProfileKind::Rail,
            SliceAxis::Wheel => ProfileKind::Wheel,
        }
    }
}

fn syntax(file: &str, line: usize, expected: &str, found: &str) -> ProfileError {
    ProfileError::Syntax {
        at: SourceLocation::new(file, Some(line)),
        expected: expected.to_string(),
        found: quote(found.trim()),
    }
}

fn format_err(file: &str, line: Option<usize>, message: String) -> ProfileError {
    ProfileError::Format {
        at: SourceLocation::new(file, line),
        message,
    }
}

/// The value lines of the file: (line number from 1, text), skipping
/// blank lines and `%` comments.
fn value_lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    text.lines().enumerate().filter_map(|(i, l)| {
        let t = l.trim();
        (!t.is_empty() && !t.starts_with('%')).then_some((i + 1, t))
    })
}

/// The first `n` whitespace-separated numbers of `line` (more may follow
/// as a comment).
fn numbers(
    file: &str,
    (line, text): (usize, &str),
    n: usize,
    what: &str,
) -> Result<Vec<f64>, ProfileError> {
    let v: Vec<f64> = text
        .split_whitespace()
        .take(n)
        .map_while(|w| w.parse::<f64>().ok().filter(|x| x.is_finite()))
        .collect();
    if v.len() < n {
        return Err(syntax(file, line, what, text));
    }
    Ok(v)
}

/// Integers (as the numbers of [`numbers`], whole).
fn integers(file: &str, l: (usize, &str), n: usize, what: &str) -> Result<Vec<i64>, ProfileError> {
    let v = numbers(file, l, n, what)?;
    if v.iter().any(|x| x.fract() != 0.0) {
        return Err(syntax(file, l.0, what, l.1));
    }
    Ok(v.iter().map(|x| *x as i64).collect())
}

/// A slice line: U_SLC and the profile file name (quoted with ' or ", or
/// one word).
fn slice_line(
    file: &str,
    (line, text): (usize, &str),
    axis: SliceAxis,
) -> Result<(f64, String), ProfileError> {
    let what = format!(
        "a slice position {}_SLC and a profile file name {}",
        axis.key(),
        axis.file_key()
    );
    let what = what.as_str();
    let mut words = text.splitn(2, char::is_whitespace);
    let u = words
        .next()
        .and_then(|w| w.parse::<f64>().ok())
        .filter(|u| u.is_finite())
        .ok_or_else(|| syntax(file, line, what, text))?;
    let rest = words.next().unwrap_or("").trim_start();
    let name = match rest.chars().next() {
        Some(q @ ('\'' | '"')) => {
            let body = &rest[1..];
            let end = body.find(q).ok_or_else(|| syntax(file, line, what, text))?;
            &body[..end]
        }
        Some(_) => rest.split_whitespace().next().unwrap_or(""),
        None => "",
    };
    if name.is_empty() {
        return Err(syntax(file, line, what, text));
    }
    Ok((u, name.to_string()))
}

/// Reads the header and slice lines of a rail slices file named
/// `file_name` (for messages); see the module docs for what is refused.
pub fn parse_slices_file(text: &str, file_name: &str) -> Result<SlicesFile, ProfileError> {
    parse_slices_file_along(text, file_name, SliceAxis::Track)
}

/// Reads the header and slice lines of a slices file named `file_name`
/// whose slices lie along `axis`; see the module docs for what is
/// refused.
pub fn parse_slices_file_along(
    text: &str,
    file_name: &str,
    axis: SliceAxis,
) -> Result<SlicesFile, ProfileError> {
    let f = file_name;
    let k = axis.key();
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut lines = value_lines(text);
    let mut next = |what: &str| {
        lines
            .next()
            .ok_or_else(|| format_err(f, None, format!("the file ends before {what}")))
    };
    let l = next(&format!("{k}_OFFSET, {k}_SCALE"))?;
    let unit = match axis {
        SliceAxis::Track => "mm",
        SliceAxis::Wheel => "rad",
    };
    let v = numbers(
        f,
        l,
        2,
        &format!("two numbers {k}_OFFSET [usr], {k}_SCALE [{unit}/usr]"),
    )?;
    let (offset, scale) = (v[0], v[1]);
    if scale <= 0.0 {
        let per = match axis {
            SliceAxis::Track => "millimetres",
            SliceAxis::Wheel => "radians",
        };
        return Err(format_err(
            f,
            Some(l.0),
            format!("{k}_SCALE = {scale} must be positive ({per} per unit of {k}_SLC)"),
        ));
    }
    let l = next("NSLC")?;
    let nslc = integers(f, l, 1, "the number of slices NSLC")?[0];
    if nslc < 1 {
        return Err(format_err(
            f,
            Some(l.0),
            format!("NSLC = {nslc} must be at least 1"),
        ));
    }
    let l = next("NFEAT, NKINK, NACCEL")?;
    let nfeat = integers(f, l, 1, "NFEAT, NKINK, NACCEL")?[0];
    if nfeat >= 2 {
        return Err(format_err(
            f,
            Some(l.0),
            format!(
                "NFEAT = {nfeat}: slices divided into parts by features (and interruptions) \
                 are not supported; NFEAT <= 1 (one part per slice) is"
            ),
        ));
    }
    if nfeat < 0 {
        return Err(format_err(
            f,
            Some(l.0),
            format!("NFEAT = {nfeat} must be 0 or more"),
        ));
    }
    let l = next(&format!("{k}_INTPOL"))?;
    let w: Vec<&str> = l.1.split_whitespace().collect();
    let intpol = integers(
        f,
        l,
        1,
        &format!("the method along the slices {k}_INTPOL (1 or 2)"),
    )?[0];
    let interpolation = match (intpol, axis) {
        (1, _) => SliceInterpolation::Interpolating,
        (2, SliceAxis::Wheel) => SliceInterpolation::Approximating,
        (2, SliceAxis::Track) => {
            return Err(format_err(
                f,
                Some(l.0),
                "U_INTPOL = 2 (the approximating spline along u) is not supported; \
                 U_INTPOL = 1 (interpolating) is"
                    .into(),
            ))
        }
        (m, _) => {
            return Err(format_err(
                f,
                Some(l.0),
                format!("{k}_INTPOL = {m} does not exist (1 interpolating, 2 approximating)"),
            ))
        }
    };
    // An optional PERTURB after the method.
    if let Some(p) = w.get(1).and_then(|x| x.parse::<f64>().ok()) {
        if p != 0.0 {
            return Err(format_err(
                f,
                Some(l.0),
                format!("PERTURB = {p}: perturbations of the surface are not supported"),
            ));
        }
    }
    // NSLC is the file's word: room for the lines the text can hold at
    // most, not for NSLC (a huge NSLC must not reserve memory).
    let mut slices: Vec<(f64, String, usize)> =
        Vec::with_capacity((nslc as usize).min(text.lines().count()));
    for n in 0..nslc {
        let l = next(&format!("slice {} of NSLC = {nslc}", n + 1))?;
        let (u, name) = slice_line(f, l, axis)?;
        let at = scale * (offset + u) * axis.si_per_unit();
        if let Some((prev, _, pl)) = slices.last() {
            if at - prev < axis.min_spacing() * (1.0 - 1e-9) {
                return Err(format_err(
                    f,
                    Some(l.0),
                    format!(
                        "slice {} at {} does not follow the slice of line {pl} ({}) by at \
                         least 0.001 {unit}: slices go in increasing {}",
                        n + 1,
                        axis.show(at),
                        axis.show(*prev),
                        match axis {
                            SliceAxis::Track => "u",
                            SliceAxis::Wheel => "theta",
                        }
                    ),
                ));
            }
        }
        slices.push((at, name, l.0));
    }
    Ok(SlicesFile {
        slices,
        interpolation,
    })
}

impl SlicePaths {
    /// The paths through `profiles` at positions `at` (increasing by at
    /// least `axis`'s spacing, at least one), run along as `along`;
    /// `name` in messages.
    fn new(
        name: &str,
        at: &[f64],
        profiles: &[&Profile],
        axis: SliceAxis,
        along: SliceInterpolation,
    ) -> Result<Self, ProfileError> {
        if profiles.is_empty() {
            return Err(format_err(name, None, "no slices".into()));
        }
        for w in at.windows(2) {
            if w[1] - w[0] < axis.min_spacing() * (1.0 - 1e-9) {
                return Err(format_err(
                    name,
                    None,
                    format!(
                        "slices at {} and {} are not in increasing order, 0.001 {} apart",
                        axis.show(w[0]),
                        axis.show(w[1]),
                        match axis {
                            SliceAxis::Track => "mm",
                            SliceAxis::Wheel => "rad",
                        }
                    ),
                ));
            }
        }
        let most = profiles.iter().map(|p| p.len()).max().unwrap_or(0);
        if most < 2 {
            return Err(format_err(
                name,
                None,
                "the slices have fewer than 2 points".into(),
            ));
        }
        let same = profiles.iter().all(|p| p.len() == most);
        let n = path_points(profiles);
        let points: Vec<Vec<[f64; 2]>> = profiles
            .iter()
            .map(|p| {
                if same {
                    p.points().to_vec()
                } else {
                    resample(p.points(), n)
                }
            })
            .collect();
        let along = match along {
            SliceInterpolation::Interpolating => Along::Interpolating {
                second: natural_second_derivatives(at, &points),
            },
            SliceInterpolation::Approximating => approximating(at, &points),
        };
        Ok(Self {
            at: at.to_vec(),
            points,
            along,
        })
    }

    /// The range of positions covered.
    fn range(&self) -> (f64, f64) {
        (self.at[0], self.at[self.at.len() - 1])
    }

    /// Writes the points at position `p` (within the range) into `out`.
    fn points_at(&self, p: f64, out: &mut Vec<[f64; 2]>) {
        let n = self.points[0].len();
        out.clear();
        if self.at.len() == 1 {
            out.extend_from_slice(&self.points[0]);
            return;
        }
        let k = self
            .at
            .partition_point(|u| *u <= p)
            .clamp(1, self.at.len() - 1)
            - 1;
        match &self.along {
            Along::Interpolating { second } => {
                let h = self.at[k + 1] - self.at[k];
                let a = (self.at[k + 1] - p) / h;
                let b = (p - self.at[k]) / h;
                let ca = (a * a * a - a) * h * h / 6.0;
                let cb = (b * b * b - b) * h * h / 6.0;
                let (p0, p1) = (&self.points[k], &self.points[k + 1]);
                let (m0, m1) = (&second[k], &second[k + 1]);
                out.extend((0..n).map(|i| {
                    // p0 + b (p1 - p0): exactly p0 where a path is constant.
                    let c = |d: usize| {
                        p0[i][d] + b * (p1[i][d] - p0[i][d]) + ca * m0[i][d] + cb * m1[i][d]
                    };
                    [c(0), c(1)]
                }));
            }
            Along::Approximating { knots, control } => {
                let w = bspline_weights(knots, k, p);
                let c = &control[k..k + 4];
                out.extend((0..n).map(|i| {
                    let v = |d: usize| {
                        // c1 + sum w_j (c_j - c1): exactly c1 where a path
                        // is constant (the weights sum to one).
                        let base = c[1][i][d];
                        base + (0..4).map(|j| w[j] * (c[j][i][d] - base)).sum::<f64>()
                    };
                    [v(0), v(1)]
                }));
            }
        }
    }
}

/// CONTACT's approximating spline along the slices at `at` through the
/// paths' `points` (its `bspline_make_2d_bspline` with `use_approx`): the
/// cubic B-spline on the knots at the slices (three more before the first
/// and after the last, spaced as the first and last intervals), whose
/// control points are the slices' points, with a phantom point before the
/// first slice, 2 p_1 - p_2, and after the last, 2 p_n - p_(n-1) (linear
/// extrapolation; CONTACT's code takes the first slice's point in the
/// last phantom in place of the last's, which differs only where the
/// last slices differ from the first).
fn approximating(at: &[f64], points: &[Vec<[f64; 2]>]) -> Along {
    let m = at.len();
    let (h0, h1) = (at[1] - at[0], at[m - 1] - at[m - 2]);
    let mut knots = Vec::with_capacity(m + 6);
    knots.extend((1..=3).rev().map(|j| at[0] - j as f64 * h0));
    knots.extend_from_slice(at);
    knots.extend((1..=3).map(|j| at[m - 1] + j as f64 * h1));
    let phantom = |a: &[[f64; 2]], b: &[[f64; 2]]| -> Vec<[f64; 2]> {
        a.iter()
            .zip(b)
            .map(|(p, q)| [2.0 * p[0] - q[0], 2.0 * p[1] - q[1]])
            .collect()
    };
    let mut control = Vec::with_capacity(m + 2);
    control.push(phantom(&points[0], &points[1]));
    control.extend(points.iter().cloned());
    control.push(phantom(&points[m - 1], &points[m - 2]));
    Along::Approximating { knots, control }
}

/// The weights of the four control points k .. k + 3 of a cubic B-spline
/// on `knots` (those of [`approximating`]) at `p` in the interval between
/// slices k and k + 1 (de Boor's recursion on unit control points).
fn bspline_weights(knots: &[f64], k: usize, p: f64) -> [f64; 4] {
    // The span: knots[k + 3] <= p < knots[k + 4], the slices k and k + 1.
    let i = k + 3;
    let mut w = [0.0; 4];
    for (j, wj) in w.iter_mut().enumerate() {
        let mut d = [0.0; 4];
        d[j] = 1.0;
        for r in 1..=3 {
            for jj in (r..=3).rev() {
                let lo = knots[jj + i - 3];
                let hi = knots[jj + 1 + i - r];
                let a = (p - lo) / (hi - lo);
                d[jj] = (1.0 - a) * d[jj - 1] + a * d[jj];
            }
        }
        *wj = d[3];
    }
    w
}

impl RailSlices {
    /// The surface through `slices` (increasing u, at least one), named
    /// `name` in messages.
    pub fn new(name: &str, slices: &[Slice]) -> Result<Self, ProfileError> {
        let at: Vec<f64> = slices.iter().map(|s| s.u_m).collect();
        let profiles: Vec<&Profile> = slices.iter().map(|s| &s.profile).collect();
        Ok(Self {
            name: name.to_string(),
            paths: SlicePaths::new(
                name,
                &at,
                &profiles,
                SliceAxis::Track,
                SliceInterpolation::Interpolating,
            )?,
        })
    }

    fn of(name: &str, paths: SlicePaths) -> Self {
        Self {
            name: name.to_string(),
            paths,
        }
    }

    /// Name (the slices file's).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Track positions of the slices \[m\].
    pub fn slice_positions_m(&self) -> &[f64] {
        &self.paths.at
    }

    /// The range of u covered \[m\].
    pub fn u_range_m(&self) -> (f64, f64) {
        self.paths.range()
    }

    /// Points per slice (along the interpolation paths).
    pub fn points_per_slice(&self) -> usize {
        self.paths.points[0].len()
    }

    /// Writes the points of the rail at `u_m` into `out` (resized to
    /// [`RailSlices::points_per_slice`]); `None` when `u_m` lies outside
    /// the slices.
    pub fn points_at(&self, u_m: f64, out: &mut Vec<[f64; 2]>) -> Option<()> {
        let (lo, hi) = self.u_range_m();
        if !(u_m >= lo && u_m <= hi) {
            return None;
        }
        self.paths.points_at(u_m, out);
        Some(())
    }

    /// The rail profile at track position `u_m` \[m\] (checked as any
    /// profile), or an error when `u_m` lies outside the slices.
    pub fn profile_at(&self, u_m: f64) -> Result<Profile, ProfileError> {
        let mut pts = Vec::new();
        self.points_at(u_m, &mut pts)
            .ok_or_else(|| self.outside(u_m))?;
        Profile::from_points(
            &format!("{} at u = {} mm", self.name, u_m * 1e3),
            Some(ProfileKind::Rail),
            &pts,
            &ProfileChecks::default(),
        )
    }

    /// The error of a position outside the slices.
    pub fn outside(&self, u_m: f64) -> ProfileError {
        let (lo, hi) = self.u_range_m();
        format_err(
            &self.name,
            None,
            format!(
                "u = {} mm lies outside the slices (u from {} to {} mm)",
                u_m * 1e3,
                lo * 1e3,
                hi * 1e3
            ),
        )
    }

    /// Height z (down) of the visible surface of the rail points `pts`
    /// (from [`RailSlices::points_at`]) over `y_m`: the smallest z of the
    /// segments spanning y; `None` where none does.
    pub fn z_at(pts: &[[f64; 2]], y_m: f64) -> Option<f64> {
        Self::z_at_among(pts, 0..pts.len().saturating_sub(1), y_m)
    }

    /// [`RailSlices::z_at`] among the segments (i, i + 1) of `pts` whose
    /// first points `segments` gives (those that may span `y_m`).
    pub fn z_at_among(
        pts: &[[f64; 2]],
        segments: impl IntoIterator<Item = usize>,
        y_m: f64,
    ) -> Option<f64> {
        visible_z(pts, segments, y_m, f64::min)
    }
}

/// One wheel slice as read: its angle and profile.
#[derive(Debug, Clone)]
pub struct WheelSlice {
    /// Angle theta round the wheel \[rad\] (see [`WheelSlices`]).
    pub theta_rad: f64,
    /// The profile (canonical right-hand wheel profile, metres; its z is
    /// the radius less the nominal radius).
    pub profile: Profile,
}

/// An out-of-round wheel: wheel profiles at angles theta round the wheel
/// and the paths between them (CONTACT's wheel slices file, `.slcw`).
///
/// # Angles and the pitch (CONTACT's convention, user guide "Wheel
/// out-of-roundness")
///
/// A slice at angle theta describes the wheel's cross-section through the
/// axle at theta, its profile z the radius less the nominal radius
/// (radius = nominal radius + z, as for a round wheel). theta = 0 points
/// down (track z) when the wheelset's pitch angle is 0, and theta grows
/// from z towards x: in the wheel's frame the point at theta lies at
/// x = r sin(theta), z = r cos(theta) from the axle. The wheelset pitched
/// by `pitch` (right-hand about the axle, which points to the field side
/// of the right wheel; CONTACT's PITCH, theta_ws) turns it to
/// x = r sin(theta + pitch): the slice facing the rail (the lowest) is at
/// theta = -pitch and the surface at x along the track is that at
/// theta = -pitch + asin(x / r). A wheel rolling forward turns with a
/// negative pitch rate (-V / r), so the angle at the rail grows: CONTACT's
/// wheel flat example has the flat at theta from 0.49 to 0.81 rad reach
/// the rail from ahead (x > 0) at pitch -28 degrees, and leave behind at
/// pitch -47 degrees.
///
/// Outside [-pi, pi) an angle is taken back into it (periodically); within
/// it, outside the slices' range the wheel is the nearest end slice's
/// profile (CONTACT's constant extrapolation). A wheel out of round all
/// round is given on a range covering [-pi, pi) with its slices repeated
/// periodically by the user (CONTACT's rule).
#[derive(Debug, Clone, PartialEq)]
pub struct WheelSlices {
    name: String,
    paths: SlicePaths,
}

impl WheelSlices {
    /// The surface through `slices` (increasing theta, at least 0.001 rad
    /// apart, at least one) run along as `along`, named `name` in
    /// messages.
    pub fn new(
        name: &str,
        slices: &[WheelSlice],
        along: SliceInterpolation,
    ) -> Result<Self, ProfileError> {
        let at: Vec<f64> = slices.iter().map(|s| s.theta_rad).collect();
        let profiles: Vec<&Profile> = slices.iter().map(|s| &s.profile).collect();
        Ok(Self {
            name: name.to_string(),
            paths: SlicePaths::new(name, &at, &profiles, SliceAxis::Wheel, along)?,
        })
    }

    /// Name (the slices file's).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The angles of the slices \[rad\].
    pub fn slice_angles_rad(&self) -> &[f64] {
        &self.paths.at
    }

    /// Points per slice (along the interpolation paths).
    pub fn points_per_slice(&self) -> usize {
        self.paths.points[0].len()
    }

    /// The angle at which the surface is evaluated for `theta_rad`: taken
    /// into [-pi, pi), then onto the slices' range.
    pub fn effective_angle_rad(&self, theta_rad: f64) -> f64 {
        use std::f64::consts::PI;
        let t = (theta_rad + PI).rem_euclid(2.0 * PI) - PI;
        let (lo, hi) = self.paths.range();
        t.clamp(lo, hi)
    }

    /// Writes the points of the wheel's cross-section at `theta_rad` into
    /// `out` (resized to [`WheelSlices::points_per_slice`]).
    pub fn points_at(&self, theta_rad: f64, out: &mut Vec<[f64; 2]>) {
        self.paths
            .points_at(self.effective_angle_rad(theta_rad), out);
    }

    /// The wheel profile at `theta_rad` (checked as any profile).
    pub fn profile_at(&self, theta_rad: f64) -> Result<Profile, ProfileError> {
        let mut pts = Vec::new();
        self.points_at(theta_rad, &mut pts);
        Profile::from_points(
            &format!("{} at theta = {theta_rad} rad", self.name),
            Some(ProfileKind::Wheel),
            &pts,
            &ProfileChecks::default(),
        )
    }

    /// The profile the wheel shows a prismatic rail at the wheelset's
    /// pitch `pitch_rad` on a wheelset of `nominal_radius_m`: along each
    /// interpolation path, the lowest point of the wheel over the angles
    /// within [`FACING_HALF_ANGLE_RAD`] of theta0 = -pitch (every
    /// [`FACING_STEP_RAD`]): z = max over phi of (r_n + z(theta0 + phi))
    /// cos(phi) - r_n, at the path's y at theta0. Of a round wheel, its
    /// profile; on a flat facing the rail, the flat's edges where they
    /// reach lower than its centre. The contact search on it finds where
    /// the wheel comes closest to the rail at any x, which the profile at
    /// theta0 alone misses when a flat lifts the wheel's lowest point off
    /// x = 0 (CONTACT searches the surface over +-0.2 rad round theta0).
    pub fn facing_rail_points(&self, pitch_rad: f64, nominal_radius_m: f64) -> Vec<[f64; 2]> {
        let theta0 = -pitch_rad;
        let mut out = Vec::with_capacity(self.points_per_slice());
        self.points_at(theta0, &mut out);
        let mut at = Vec::with_capacity(out.len());
        let steps = (FACING_HALF_ANGLE_RAD / FACING_STEP_RAD).round() as i64;
        for k in -steps..=steps {
            if k == 0 {
                continue;
            }
            let phi = k as f64 * FACING_STEP_RAD;
            let c = phi.cos();
            self.points_at(theta0 + phi, &mut at);
            for (o, p) in out.iter_mut().zip(&at) {
                let z = (nominal_radius_m + p[1]) * c - nominal_radius_m;
                if z > o[1] {
                    o[1] = z;
                }
            }
        }
        out
    }

    /// [`WheelSlices::facing_rail_points`] as a profile (checked as any
    /// profile).
    pub fn profile_facing_rail(
        &self,
        pitch_rad: f64,
        nominal_radius_m: f64,
    ) -> Result<Profile, ProfileError> {
        Profile::from_points(
            &format!("{} facing the rail at pitch {pitch_rad} rad", self.name),
            Some(ProfileKind::Wheel),
            &self.facing_rail_points(pitch_rad, nominal_radius_m),
            &ProfileChecks::default(),
        )
    }

    /// Radius less the nominal radius (the profile z) of the wheel points
    /// `pts` (from [`WheelSlices::points_at`]) at profile `y_m`: the
    /// largest z of the segments spanning y (the outermost surface);
    /// `None` where none does.
    pub fn z_at_among(
        pts: &[[f64; 2]],
        segments: impl IntoIterator<Item = usize>,
        y_m: f64,
    ) -> Option<f64> {
        visible_z(pts, segments, y_m, f64::max)
    }
}

/// The height z over `y_m` of the segments (i, i + 1) of `pts` whose
/// first points `segments` gives, the one `pick` chooses of those
/// spanning y (of a vertical segment, of its ends); `None` where none
/// does.
fn visible_z(
    pts: &[[f64; 2]],
    segments: impl IntoIterator<Item = usize>,
    y_m: f64,
    pick: fn(f64, f64) -> f64,
) -> Option<f64> {
    let mut best: Option<f64> = None;
    for i in segments {
        let (a, b) = (pts[i], pts[i + 1]);
        let (lo, hi) = if a[0] <= b[0] { (a, b) } else { (b, a) };
        if y_m < lo[0] || y_m > hi[0] {
            continue;
        }
        let z = if hi[0] > lo[0] {
            lo[1] + (y_m - lo[0]) / (hi[0] - lo[0]) * (hi[1] - lo[1])
        } else {
            pick(lo[1], hi[1])
        };
        best = Some(best.map_or(z, |v: f64| pick(v, z)));
    }
    best
}

/// Points along each interpolation path of the surface through `slices`
/// (module docs): the slices' common count, or as many as the longest
/// slice needs at [`RESAMPLE_SPACING_M`].
fn path_points(profiles: &[&Profile]) -> usize {
    let most = profiles.iter().map(|p| p.len()).max().unwrap_or(0);
    if profiles.iter().all(|p| p.len() == most) {
        return most;
    }
    let longest = profiles
        .iter()
        .map(|p| chord_length(p.points()))
        .fold(0.0, f64::max);
    2 + (longest / RESAMPLE_SPACING_M + 1e-9).floor() as usize
}

/// The summed chord length of `pts` \[m\].
fn chord_length(pts: &[[f64; 2]]) -> f64 {
    pts.windows(2)
        .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
        .sum()
}

/// `pts` resampled to `n` points uniformly in summed chord length.
fn resample(pts: &[[f64; 2]], n: usize) -> Vec<[f64; 2]> {
    let mut s = Vec::with_capacity(pts.len());
    s.push(0.0);
    for w in pts.windows(2) {
        let last = s[s.len() - 1];
        s.push(last + (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]));
    }
    let total = s[s.len() - 1];
    let mut j = 0;
    (0..n)
        .map(|i| {
            let t = total * i as f64 / (n - 1) as f64;
            while j + 2 < pts.len() && s[j + 1] < t {
                j += 1;
            }
            let ds = s[j + 1] - s[j];
            let f = if ds > 0.0 {
                ((t - s[j]) / ds).clamp(0.0, 1.0)
            } else {
                0.0
            };
            [
                pts[j][0] + f * (pts[j + 1][0] - pts[j][0]),
                pts[j][1] + f * (pts[j + 1][1] - pts[j][1]),
            ]
        })
        .collect()
}

/// Second derivatives along u of the natural cubic splines through the
/// points of every path (one tridiagonal system, solved for all paths).
fn natural_second_derivatives(u: &[f64], points: &[Vec<[f64; 2]>]) -> Vec<Vec<[f64; 2]>> {
    let m = u.len();
    let n = points[0].len();
    let mut second = vec![vec![[0.0; 2]; n]; m];
    if m < 3 {
        return second;
    }
    // Interior unknowns 1..m-1: h_{k-1} M_{k-1} + 2 (h_{k-1} + h_k) M_k +
    // h_k M_{k+1} = 6 (d_k - d_{k-1}), d_k = (p_{k+1} - p_k) / h_k.
    let h: Vec<f64> = u.windows(2).map(|w| w[1] - w[0]).collect();
    let mut diag = vec![0.0; m];
    let mut upper = vec![0.0; m];
    for k in 1..m - 1 {
        diag[k] = 2.0 * (h[k - 1] + h[k]);
        upper[k] = h[k];
    }
    // Forward elimination of the matrix (shared by all paths).
    let mut factor = vec![0.0; m];
    for k in 2..m - 1 {
        factor[k] = h[k - 1] / diag[k - 1];
        diag[k] -= factor[k] * upper[k - 1];
    }
    let mut rhs = vec![[0.0; 2]; m];
    for i in 0..n {
        for k in 1..m - 1 {
            for d in 0..2 {
                let dk = (points[k + 1][i][d] - points[k][i][d]) / h[k];
                let dk1 = (points[k][i][d] - points[k - 1][i][d]) / h[k - 1];
                rhs[k][d] = 6.0 * (dk - dk1);
            }
        }
        for k in 2..m - 1 {
            let prev = rhs[k - 1];
            for (r, p) in rhs[k].iter_mut().zip(prev) {
                *r -= factor[k] * p;
            }
        }
        for k in (1..m - 1).rev() {
            for d in 0..2 {
                let next = if k + 1 < m - 1 {
                    second[k + 1][i][d]
                } else {
                    0.0
                };
                second[k][i][d] = (rhs[k][d] - upper[k] * next) / diag[k];
            }
        }
    }
    second
}

/// Bounds on what reading a slices file may hold, for a reader of files
/// it does not trust (a server reading a client's): the slices, the
/// points along each interpolation path (those of the rail at any u,
/// [`RailSlices::profile_at`]), and the points of the surface, slices x
/// points along each path (its memory: 32 bytes a point).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SlicesLimits {
    /// Most slices (slice lines).
    pub max_slices: usize,
    /// Most points along each interpolation path.
    pub max_path_points: usize,
    /// Most points of the surface.
    pub max_surface_points: usize,
}

impl SlicesLimits {
    /// No bounds (files of one's own).
    pub const NONE: Self = Self {
        max_slices: usize::MAX,
        max_path_points: usize::MAX,
        max_surface_points: usize::MAX,
    };
}

/// No bounds ([`SlicesLimits::NONE`]).
impl Default for SlicesLimits {
    fn default() -> Self {
        Self::NONE
    }
}

/// The paths of a slices file along `axis` within `limits`: the slice
/// lines of `text` ([`parse_slices_file_along`]), counted before any
/// profile is read, each profile by `read` (given the file name as written
/// in the slices file; its error names the slice's line), the surface's
/// points counted before it is built.
fn read_paths(
    text: &str,
    file_name: &str,
    axis: SliceAxis,
    mut read: impl FnMut(&str) -> Result<Profile, ProfileError>,
    limits: SlicesLimits,
) -> Result<SlicePaths, ProfileError> {
    let file = parse_slices_file_along(text, file_name, axis)?;
    if file.slices.len() > limits.max_slices {
        return Err(format_err(
            file_name,
            None,
            format!(
                "{} slices, more than the limit of {}",
                file.slices.len(),
                limits.max_slices
            ),
        ));
    }
    let mut profiles = Vec::with_capacity(file.slices.len());
    for (_, name, line) in &file.slices {
        profiles.push(read(name).map_err(|e| {
            format_err(
                file_name,
                Some(*line),
                format!("the profile of this slice: {e}"),
            )
        })?);
    }
    let profiles: Vec<&Profile> = profiles.iter().collect();
    let n = path_points(&profiles);
    if n > limits.max_path_points {
        return Err(format_err(
            file_name,
            None,
            format!(
                "its surface has {n} points along the interpolation paths (the slices \
                 resampled at {} mm over the longest), more than the limit of {}",
                RESAMPLE_SPACING_M * 1e3,
                limits.max_path_points
            ),
        ));
    }
    let points = n.saturating_mul(profiles.len());
    if points > limits.max_surface_points {
        return Err(format_err(
            file_name,
            None,
            format!(
                "its surface has {points} points ({} slices of {n} points along the \
                 interpolation paths), more than the limit of {}",
                profiles.len(),
                limits.max_surface_points
            ),
        ));
    }
    let at: Vec<f64> = file.slices.iter().map(|s| s.0).collect();
    SlicePaths::new(file_name, &at, &profiles, axis, file.interpolation)
}

/// Reads a rail slices file and its profiles: the slice lines of `text`
/// ([`parse_slices_file`]), each profile by `read` (given the file name as
/// written in the slices file).
pub fn parse_slices(
    text: &str,
    file_name: &str,
    read: impl FnMut(&str) -> Result<Profile, ProfileError>,
) -> Result<RailSlices, ProfileError> {
    parse_slices_within(text, file_name, read, SlicesLimits::NONE)
}

/// [`parse_slices`] within `limits`: the slices counted before any profile
/// is read, the surface's points before it is built. `read` may take the
/// profiles' contents from memory (a server given the files with the
/// slices file).
pub fn parse_slices_within(
    text: &str,
    file_name: &str,
    read: impl FnMut(&str) -> Result<Profile, ProfileError>,
    limits: SlicesLimits,
) -> Result<RailSlices, ProfileError> {
    let paths = read_paths(text, file_name, SliceAxis::Track, read, limits)?;
    Ok(RailSlices::of(file_name, paths))
}

/// Reads a wheel slices file (`.slcw`) and its profiles: the slice lines
/// of `text` (as a rail slices file's, with TH_ in place of U_ and
/// TH_SCALE in radians per unit; TH_INTPOL = 2 built), each profile by
/// `read` (given the file name as written in the slices file).
pub fn parse_wheel_slices(
    text: &str,
    file_name: &str,
    read: impl FnMut(&str) -> Result<Profile, ProfileError>,
) -> Result<WheelSlices, ProfileError> {
    parse_wheel_slices_within(text, file_name, read, SlicesLimits::NONE)
}

/// [`parse_wheel_slices`] within `limits`, as [`parse_slices_within`].
pub fn parse_wheel_slices_within(
    text: &str,
    file_name: &str,
    read: impl FnMut(&str) -> Result<Profile, ProfileError>,
    limits: SlicesLimits,
) -> Result<WheelSlices, ProfileError> {
    let name = file_name.to_string();
    read_paths(text, file_name, SliceAxis::Wheel, read, limits)
        .map(|paths| WheelSlices { name, paths })
}

/// Reads the slices file at `path` (along `axis`) with its profile files,
/// relative to its folder, with `options` (the kind the axis's), into
/// `build` (the file's text, its name and a reader of its profiles).
fn load_along<T>(
    path: &Path,
    options: &LoadOptions,
    axis: SliceAxis,
    build: impl FnOnce(
        &str,
        &str,
        &mut dyn FnMut(&str) -> Result<Profile, ProfileError>,
    ) -> Result<T, ProfileError>,
) -> Result<Arc<T>, ProfileError> {
    let name = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|e| ProfileError::Io {
        file: name.clone(),
        message: e.to_string(),
    })?;
    let text = String::from_utf8_lossy(&bytes);
    let dir = path.parent().unwrap_or(Path::new("")).to_path_buf();
    let options = LoadOptions {
        kind: Some(axis.kind()),
        ..*options
    };
    let mut read = |f: &str| crate::wheelrail::load_profile_with(dir.join(f), &options);
    build(&text, &name, &mut read).map(Arc::new)
}

/// Reads a rail slices file from disk; its profile files, relative to its
/// folder, with `options` (the kind is a rail's).
pub fn load_slices(
    path: impl AsRef<Path>,
    options: &LoadOptions,
) -> Result<Arc<RailSlices>, ProfileError> {
    load_along(path.as_ref(), options, SliceAxis::Track, |t, n, r| {
        parse_slices(t, n, r)
    })
}

/// Reads a wheel slices file from disk; its profile files, relative to
/// its folder, with `options` (the kind is a wheel's).
pub fn load_wheel_slices(
    path: impl AsRef<Path>,
    options: &LoadOptions,
) -> Result<Arc<WheelSlices>, ProfileError> {
    load_along(path.as_ref(), options, SliceAxis::Wheel, |t, n, r| {
        parse_wheel_slices(t, n, r)
    })
}

/// Whether `file_name` names a rail slices file (extension `.slcs`, any
/// case).
pub fn is_slices_file(file_name: &str) -> bool {
    has_extension(file_name, "slcs")
}

/// Whether `file_name` names a wheel slices file (extension `.slcw`, any
/// case).
pub fn is_wheel_slices_file(file_name: &str) -> bool {
    has_extension(file_name, "slcw")
}

fn has_extension(file_name: &str, ext: &str) -> bool {
    Path::new(file_name)
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case(ext))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn checked(kind: ProfileKind, points: &[[f64; 2]]) -> Profile {
        Profile::from_points("p", Some(kind), points, &ProfileChecks::default()).unwrap()
    }

    fn rail(points: &[[f64; 2]]) -> Profile {
        checked(ProfileKind::Rail, points)
    }

    /// 41 points (y, z(y)) from y = `from` to -`from` [m].
    fn sampled(from: f64, z: impl Fn(f64) -> f64) -> Vec<[f64; 2]> {
        (0..41)
            .map(|i| {
                let y = from - 2.0 * from * i as f64 / 40.0;
                [y, z(y)]
            })
            .collect()
    }

    /// A small crowned rail, heights shifted by `dz` [m].
    fn crown(dz: f64) -> Vec<[f64; 2]> {
        sampled(-0.035, |y| y * y / 0.6 + dz)
    }

    const GOOD: &str = "% a test\n\n   0.0  1000.0   U_OFFSET, U_SCALE\n  3   NSLC\n  \
                        0 0 0  NFEAT\n  1   U_INTPOL\n% slices\n  -0.1  'a.prr'\n  0.0 \"b b.prr\"\n  0.2  c.txt\n";

    #[test]
    fn a_good_file_gives_its_slices() {
        let f = parse_slices_file(GOOD, "t.slcs").unwrap();
        let u: Vec<f64> = f.slices.iter().map(|s| s.0).collect();
        assert_eq!(u, vec![-0.1, 0.0, 0.2]);
        let names: Vec<&str> = f.slices.iter().map(|s| s.1.as_str()).collect();
        assert_eq!(names, vec!["a.prr", "b b.prr", "c.txt"]);
        assert_eq!(f.slices[0].2, 8);
    }

    /// Each malformed line is named by its number and what it should hold.
    #[test]
    fn each_malformed_line_is_named() {
        let cases: &[(&str, &str, &str)] = &[
            ("3", "  x 1000.0", "U_OFFSET"),
            ("3", "  0.0 -1", "U_SCALE = -1"),
            ("4", "  0 0 0", "NSLC = 0"),
            ("4", "  2.5", "NSLC"),
            ("5", "  7 0 0", "NFEAT = 7"),
            ("6", "  2", "U_INTPOL = 2"),
            ("6", "  3", "U_INTPOL = 3"),
            ("6", "  1 1", "PERTURB"),
            ("8", "  -0.1", "RFNAME"),
            ("8", "  -0.1 'a.prr", "RFNAME"),
            ("9", "  -0.1 'b.prr'", "increasing u"),
        ];
        let lines: Vec<&str> = GOOD.lines().collect();
        for (line, text, says) in cases {
            // Lines of GOOD: 3 offset, 4 NSLC, 5 NFEAT, 6 U_INTPOL, 8.. slices.
            let at: usize = line.parse().unwrap();
            let mut l = lines.clone();
            l[at - 1] = text;
            let e = parse_slices_file(&l.join("\n"), "t.slcs")
                .unwrap_err()
                .to_string();
            assert!(e.contains(&format!("t.slcs line {at}")), "{text}: {e}");
            assert!(e.contains(says), "{text}: {e}");
        }
        let e = parse_slices_file(&GOOD.replace("  0.2  c.txt\n", ""), "t.slcs").unwrap_err();
        assert!(e.to_string().contains("ends before slice 3"), "{e}");
        // A huge NSLC reserves nothing: the file ends first.
        let huge = GOOD.replace("  3   NSLC", "  1e15   NSLC");
        let e = parse_slices_file(&huge, "t.slcs").unwrap_err();
        assert!(e.to_string().contains("ends before slice 4"), "{e}");
    }

    #[test]
    fn a_profile_error_names_the_slice_line() {
        let e = parse_slices(GOOD, "t.slcs", |f| {
            if f == "b b.prr" {
                Err(ProfileError::Io {
                    file: f.into(),
                    message: "gone".into(),
                })
            } else {
                Ok(rail(&crown(0.0)))
            }
        })
        .unwrap_err()
        .to_string();
        assert!(e.contains("t.slcs line 9") && e.contains("gone"), "{e}");
    }

    /// Limits refuse a file with more slices before any profile is read,
    /// and a rail or a surface with more points before it is built; at the
    /// limits the file reads as without them.
    #[test]
    fn limits_bound_the_slices_and_the_surface() {
        let mut reads = 0;
        let limits = SlicesLimits {
            max_slices: 2,
            ..SlicesLimits::NONE
        };
        let e = parse_slices_within(
            GOOD,
            "t.slcs",
            |_| {
                reads += 1;
                Ok(rail(&crown(0.0)))
            },
            limits,
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("3 slices, more than the limit of 2"), "{e}");
        assert_eq!(reads, 0);
        // Three slices of 41 points: 123 points.
        let read = |_: &str| Ok(rail(&crown(0.0)));
        let at = |max_path_points, max_surface_points| SlicesLimits {
            max_slices: 3,
            max_path_points,
            max_surface_points,
        };
        let e = parse_slices_within(GOOD, "t.slcs", read, at(40, 123))
            .unwrap_err()
            .to_string();
        assert!(e.contains("41 points") && e.contains("limit of 40"), "{e}");
        let e = parse_slices_within(GOOD, "t.slcs", read, at(41, 122))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("123 points") && e.contains("limit of 122"),
            "{e}"
        );
        let within = parse_slices_within(GOOD, "t.slcs", read, at(41, 123)).unwrap();
        assert_eq!(within, parse_slices(GOOD, "t.slcs", read).unwrap());
    }

    /// The same profile at every slice is that profile at any u, bit for
    /// bit.
    #[test]
    fn constant_slices_are_the_profile() {
        let p = rail(&crown(0.0));
        let s = parse_slices(GOOD, "t.slcs", |_| Ok(p.clone())).unwrap();
        for u in [-0.1, -0.03, 0.0, 0.117, 0.2] {
            let q = s.profile_at(u).unwrap();
            assert_eq!(q.points(), p.points());
        }
        assert!(s.profile_at(0.2001).is_err());
        assert!(s
            .profile_at(-0.1001)
            .unwrap_err()
            .to_string()
            .contains("outside the slices"));
    }

    /// Slices whose height is linear in u (1 mm per 100 mm) give that
    /// height between them: the natural spline through points on a line is
    /// the line.
    #[test]
    fn heights_linear_in_u_are_interpolated_linearly() {
        let s = parse_slices(GOOD, "t.slcs", |f| {
            let u: f64 = match f {
                "a.prr" => -0.1,
                "b b.prr" => 0.0,
                _ => 0.2,
            };
            Ok(rail(&crown(0.01 * u)))
        })
        .unwrap();
        let mut pts = Vec::new();
        for u in [-0.07, 0.05, 0.19] {
            s.points_at(u, &mut pts).unwrap();
            // At a point of the profiles (between them z_at is linear).
            let y = crown(0.0)[25][0];
            let z = RailSlices::z_at(&pts, y).unwrap();
            let want = y * y / 0.6 + 0.01 * u;
            assert!((z - want).abs() < 1e-15, "u {u}: {z} against {want}");
        }
    }

    /// Slices of different point counts are resampled uniformly along
    /// their chords: the points stay on the profile.
    #[test]
    fn slices_of_other_point_counts_are_resampled() {
        let lines: Vec<[f64; 2]> = (0..16).map(|i| [-0.03 + 0.004 * i as f64, 0.0]).collect();
        let fine: Vec<[f64; 2]> = (0..31).map(|i| [-0.03 + 0.002 * i as f64, 0.0]).collect();
        let s = RailSlices::new(
            "t",
            &[
                Slice {
                    u_m: 0.0,
                    profile: rail(&lines),
                },
                Slice {
                    u_m: 1.0,
                    profile: rail(&fine),
                },
            ],
        )
        .unwrap();
        // 60 mm at 0.5 mm: CONTACT's 1 + floor(60 / 0.5) segments, 122
        // points.
        assert_eq!(s.points_per_slice(), 122);
        let mut pts = Vec::new();
        s.points_at(0.0, &mut pts).unwrap();
        for (i, p) in pts.iter().enumerate() {
            let want = -0.03 + 0.06 * i as f64 / 121.0;
            assert!((p[0] - want).abs() < 1e-15, "{i}: {} against {want}", p[0]);
        }
    }

    fn wheel(points: &[[f64; 2]]) -> Profile {
        checked(ProfileKind::Wheel, points)
    }

    /// A small tread (y descending, a wheel's order), radii grown by `dr`
    /// [m].
    fn tread(dr: f64) -> Vec<[f64; 2]> {
        sampled(0.035, |y| 0.05 * y + dr)
    }

    const WHEEL: &str = "% wheel\n 0.0 0.0174532925199433  TH_OFFSET, TH_SCALE (degrees)\n 5 NSLC\n \
                         0 0 0\n 2 TH_INTPOL\n 10 'a.txt'\n 20 'a.txt'\n 30 b.txt\n 40 'a.txt'\n 50 'a.txt'\n";

    #[test]
    fn a_good_wheel_file_gives_its_slices_in_radians() {
        let f = parse_slices_file_along(WHEEL, "t.slcw", SliceAxis::Wheel).unwrap();
        assert_eq!(f.interpolation, SliceInterpolation::Approximating);
        assert_eq!(f.slices.len(), 5);
        assert!((f.slices[2].0 - 30f64.to_radians()).abs() < 1e-15);
        assert_eq!(f.slices[2].1, "b.txt");
        assert_eq!(f.slices[2].2, 8);
    }

    /// A wheel file's malformed lines are named with its own keywords.
    #[test]
    fn each_malformed_wheel_line_is_named() {
        let cases: &[(usize, &str, &str)] = &[
            (2, " x 1.0", "TH_OFFSET"),
            (2, " 0.0 0", "TH_SCALE = 0"),
            (4, " 2 0 0", "NFEAT = 2"),
            (5, " 3", "TH_INTPOL = 3"),
            (5, " 2 1", "PERTURB"),
            (6, " 10", "WFNAME"),
            // 0.0005 degrees after the slice before: less than 0.001 rad.
            (7, " 10.0005 'a.txt'", "increasing theta"),
        ];
        let lines: Vec<&str> = WHEEL.lines().collect();
        for (at, text, says) in cases {
            let mut l = lines.clone();
            l[at - 1] = text;
            let e = parse_slices_file_along(&l.join("\n"), "t.slcw", SliceAxis::Wheel)
                .unwrap_err()
                .to_string();
            assert!(e.contains(&format!("t.slcw line {at}")), "{text}: {e}");
            assert!(e.contains(says), "{text}: {e}");
        }
    }

    /// The same profile at every slice is that profile at any angle, bit
    /// for bit (the approximating spline too: its weights sum to one).
    #[test]
    fn constant_wheel_slices_are_the_profile() {
        let p = wheel(&tread(0.0));
        let s = parse_wheel_slices(WHEEL, "t.slcw", |_| Ok(p.clone())).unwrap();
        for t in [-3.0, 0.0, 0.2, 0.31, 0.5, 0.87, 1.2, 7.0] {
            assert_eq!(s.profile_at(t).unwrap().points(), p.points(), "theta {t}");
        }
    }

    /// The approximating spline on equally spaced slices: a radius linear
    /// in theta is reproduced (the B-spline's control points lie at its
    /// Greville abscissae, the slices), and at a slice the spline is
    /// (p_(k-1) + 4 p_k + p_(k+1)) / 6 (the uniform cubic B-spline), so a
    /// bump of 1 mm at one slice gives 2/3 mm there and 1/6 mm at its
    /// neighbours; outside the slices the end slice's profile (constant
    /// extrapolation), and an angle is taken into [-pi, pi) first.
    #[test]
    fn the_approximating_spline_smooths_as_cubic_b_splines() {
        let deg = 1f64.to_radians();
        let mk = |dr: &dyn Fn(usize) -> f64| {
            let slices: Vec<WheelSlice> = (0..5)
                .map(|k| WheelSlice {
                    theta_rad: (10 + 10 * k) as f64 * deg,
                    profile: wheel(&tread(dr(k))),
                })
                .collect();
            WheelSlices::new("t", &slices, SliceInterpolation::Approximating).unwrap()
        };
        let mut pts = Vec::new();
        let z_at = |s: &WheelSlices, theta: f64, pts: &mut Vec<[f64; 2]>| {
            s.points_at(theta, pts);
            pts[20][1] - tread(0.0)[20][1]
        };
        let lin = mk(&|k| 1e-3 * k as f64);
        for t in [10.0, 13.0, 27.5, 40.0, 49.9] {
            let want = 1e-3 * (t - 10.0) / 10.0;
            let got = z_at(&lin, t * deg, &mut pts);
            assert!(
                (got - want).abs() < 1e-15,
                "theta {t}: {got} against {want}"
            );
        }
        let bump = mk(&|k| if k == 2 { 1e-3 } else { 0.0 });
        for (t, want) in [(30.0, 2e-3 / 3.0), (20.0, 1e-3 / 6.0), (40.0, 1e-3 / 6.0)] {
            let got = z_at(&bump, t * deg, &mut pts);
            assert!(
                (got - want).abs() < 1e-15,
                "theta {t}: {got} against {want}"
            );
        }
        // Outside [10, 50] degrees: the end slices (here at the nominal).
        assert_eq!(z_at(&bump, 5.0 * deg, &mut pts), 0.0);
        let end = z_at(&lin, 60.0 * deg, &mut pts);
        assert!((end - 4e-3).abs() < 1e-15, "{end}");
        // 390 degrees is 30 degrees.
        let a = z_at(&bump, 390.0 * deg, &mut pts);
        assert!((a - 2e-3 / 3.0).abs() < 1e-15, "{a}");
    }

    /// A wheel slices file read as a single profile (as the service's
    /// profile registration reads files) is refused by name.
    #[test]
    fn a_wheel_slices_file_is_no_single_profile() {
        let e = crate::wheelrail::parse_profile(WHEEL, "flat.slcw", &LoadOptions::default())
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("flat.slcw") && e.contains("wheel slices file"),
            "{e}"
        );
    }
}
