//! Rails whose profile varies along the track (switches and crossings):
//! CONTACT's rail slices file (`.slcs`), a list of rail profiles at
//! positions u along the track, interpolated between them to a surface.
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

/// A rail profile varying along the track: its slices and the paths
/// between them (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct RailSlices {
    name: String,
    /// Track positions of the slices \[m\], strictly increasing.
    u_m: Vec<f64>,
    /// Per slice, its points along the interpolation paths (y, z) \[m\],
    /// as many in every slice.
    points: Vec<Vec<[f64; 2]>>,
    /// Per slice, the second derivatives along u of y and z of every path
    /// (natural cubic spline; zero at the first and last slice).
    second: Vec<Vec<[f64; 2]>>,
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
/// read: (u \[m\], profile file name, line) per slice.
#[derive(Debug, Clone, PartialEq)]
pub struct SlicesFile {
    /// The slices: position u \[m\], the profile file name as written, the
    /// line it is on.
    pub slices: Vec<(f64, String, usize)>,
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
fn slice_line(file: &str, (line, text): (usize, &str)) -> Result<(f64, String), ProfileError> {
    const WHAT: &str = "a slice position U_SLC and a profile file name RFNAME";
    let mut words = text.splitn(2, char::is_whitespace);
    let u = words
        .next()
        .and_then(|w| w.parse::<f64>().ok())
        .filter(|u| u.is_finite())
        .ok_or_else(|| syntax(file, line, WHAT, text))?;
    let rest = words.next().unwrap_or("").trim_start();
    let name = match rest.chars().next() {
        Some(q @ ('\'' | '"')) => {
            let body = &rest[1..];
            let end = body.find(q).ok_or_else(|| syntax(file, line, WHAT, text))?;
            &body[..end]
        }
        Some(_) => rest.split_whitespace().next().unwrap_or(""),
        None => "",
    };
    if name.is_empty() {
        return Err(syntax(file, line, WHAT, text));
    }
    Ok((u, name.to_string()))
}

/// Reads the header and slice lines of a slices file named `file_name`
/// (for messages); see the module docs for what is refused.
pub fn parse_slices_file(text: &str, file_name: &str) -> Result<SlicesFile, ProfileError> {
    let f = file_name;
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut lines = value_lines(text);
    let mut next = |what: &str| {
        lines
            .next()
            .ok_or_else(|| format_err(f, None, format!("the file ends before {what}")))
    };
    let l = next("U_OFFSET, U_SCALE")?;
    let v = numbers(f, l, 2, "two numbers U_OFFSET [usr], U_SCALE [mm/usr]")?;
    let (offset, scale) = (v[0], v[1]);
    if scale <= 0.0 {
        return Err(format_err(
            f,
            Some(l.0),
            format!("U_SCALE = {scale} must be positive (millimetres per unit of U_SLC)"),
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
    let l = next("U_INTPOL")?;
    let w: Vec<&str> = l.1.split_whitespace().collect();
    let intpol = integers(f, l, 1, "the method along u U_INTPOL (1 or 2)")?[0];
    match intpol {
        1 => {}
        2 => {
            return Err(format_err(
                f,
                Some(l.0),
                "U_INTPOL = 2 (the approximating spline along u) is not supported; \
                 U_INTPOL = 1 (interpolating) is"
                    .into(),
            ))
        }
        m => {
            return Err(format_err(
                f,
                Some(l.0),
                format!("U_INTPOL = {m} does not exist (1 interpolating, 2 approximating)"),
            ))
        }
    }
    // An optional PERTURB after U_INTPOL.
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
    for k in 0..nslc {
        let l = next(&format!("slice {} of NSLC = {nslc}", k + 1))?;
        let (u, name) = slice_line(f, l)?;
        let u_m = scale * (offset + u) * 1e-3;
        if let Some((prev, _, pl)) = slices.last() {
            if u_m - prev < MIN_SLICE_SPACING_M {
                return Err(format_err(
                    f,
                    Some(l.0),
                    format!(
                        "slice {} at u = {} mm does not follow the slice of line {pl} \
                         (u = {} mm) by at least 0.001 mm: slices go in increasing u",
                        k + 1,
                        u_m * 1e3,
                        prev * 1e3
                    ),
                ));
            }
        }
        slices.push((u_m, name, l.0));
    }
    Ok(SlicesFile { slices })
}

impl RailSlices {
    /// The surface through `slices` (increasing u, at least one), named
    /// `name` in messages.
    pub fn new(name: &str, slices: &[Slice]) -> Result<Self, ProfileError> {
        if slices.is_empty() {
            return Err(format_err(name, None, "no slices".into()));
        }
        for w in slices.windows(2) {
            if w[1].u_m - w[0].u_m < MIN_SLICE_SPACING_M {
                return Err(format_err(
                    name,
                    None,
                    format!(
                        "slices at u = {} and {} mm are not in increasing u, 0.001 mm apart",
                        w[0].u_m * 1e3,
                        w[1].u_m * 1e3
                    ),
                ));
            }
        }
        let most = slices.iter().map(|s| s.profile.len()).max().unwrap_or(0);
        if most < 2 {
            return Err(format_err(
                name,
                None,
                "the slices have fewer than 2 points".into(),
            ));
        }
        let same = slices.iter().all(|s| s.profile.len() == most);
        let n = path_points(slices);
        let points: Vec<Vec<[f64; 2]>> = slices
            .iter()
            .map(|s| {
                if same {
                    s.profile.points().to_vec()
                } else {
                    resample(s.profile.points(), n)
                }
            })
            .collect();
        let u_m: Vec<f64> = slices.iter().map(|s| s.u_m).collect();
        let second = natural_second_derivatives(&u_m, &points);
        Ok(Self {
            name: name.to_string(),
            u_m,
            points,
            second,
        })
    }

    /// Name (the slices file's).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Track positions of the slices \[m\].
    pub fn slice_positions_m(&self) -> &[f64] {
        &self.u_m
    }

    /// The range of u covered \[m\].
    pub fn u_range_m(&self) -> (f64, f64) {
        (self.u_m[0], self.u_m[self.u_m.len() - 1])
    }

    /// Points per slice (along the interpolation paths).
    pub fn points_per_slice(&self) -> usize {
        self.points[0].len()
    }

    /// Writes the points of the rail at `u_m` into `out` (resized to
    /// [`RailSlices::points_per_slice`]); `None` when `u_m` lies outside
    /// the slices.
    pub fn points_at(&self, u_m: f64, out: &mut Vec<[f64; 2]>) -> Option<()> {
        let (lo, hi) = self.u_range_m();
        if !(u_m >= lo && u_m <= hi) {
            return None;
        }
        let n = self.points_per_slice();
        out.clear();
        if self.u_m.len() == 1 {
            out.extend_from_slice(&self.points[0]);
            return Some(());
        }
        let k = self
            .u_m
            .partition_point(|u| *u <= u_m)
            .clamp(1, self.u_m.len() - 1)
            - 1;
        let h = self.u_m[k + 1] - self.u_m[k];
        let a = (self.u_m[k + 1] - u_m) / h;
        let b = (u_m - self.u_m[k]) / h;
        let ca = (a * a * a - a) * h * h / 6.0;
        let cb = (b * b * b - b) * h * h / 6.0;
        let (p0, p1) = (&self.points[k], &self.points[k + 1]);
        let (m0, m1) = (&self.second[k], &self.second[k + 1]);
        out.extend((0..n).map(|i| {
            // p0 + b (p1 - p0): exactly p0 where a path is constant.
            let c = |d: usize| p0[i][d] + b * (p1[i][d] - p0[i][d]) + ca * m0[i][d] + cb * m1[i][d];
            [c(0), c(1)]
        }));
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
                lo[1].min(hi[1])
            };
            best = Some(best.map_or(z, |v: f64| v.min(z)));
        }
        best
    }
}

/// Points along each interpolation path of the surface through `slices`
/// (module docs): the slices' common count, or as many as the longest
/// slice needs at [`RESAMPLE_SPACING_M`].
fn path_points(slices: &[Slice]) -> usize {
    let most = slices.iter().map(|s| s.profile.len()).max().unwrap_or(0);
    if slices.iter().all(|s| s.profile.len() == most) {
        return most;
    }
    let longest = slices
        .iter()
        .map(|s| chord_length(s.profile.points()))
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

/// Reads a slices file and its profiles: the slice lines of `text`
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
    mut read: impl FnMut(&str) -> Result<Profile, ProfileError>,
    limits: SlicesLimits,
) -> Result<RailSlices, ProfileError> {
    let file = parse_slices_file(text, file_name)?;
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
    let mut slices = Vec::with_capacity(file.slices.len());
    for (u_m, name, line) in &file.slices {
        let profile = read(name).map_err(|e| {
            format_err(
                file_name,
                Some(*line),
                format!("the profile of this slice: {e}"),
            )
        })?;
        slices.push(Slice { u_m: *u_m, profile });
    }
    let n = path_points(&slices);
    if n > limits.max_path_points {
        return Err(format_err(
            file_name,
            None,
            format!(
                "its rail has {n} points along the interpolation paths (the slices resampled \
                 at {} mm over the longest), more than the limit of {}",
                RESAMPLE_SPACING_M * 1e3,
                limits.max_path_points
            ),
        ));
    }
    let points = n.saturating_mul(slices.len());
    if points > limits.max_surface_points {
        return Err(format_err(
            file_name,
            None,
            format!(
                "its surface has {points} points ({} slices of {n} points along the \
                 interpolation paths), more than the limit of {}",
                slices.len(),
                limits.max_surface_points
            ),
        ));
    }
    RailSlices::new(file_name, &slices)
}

/// Reads a slices file from disk; its profile files, relative to its
/// folder, with `options` (the kind is a rail's).
pub fn load_slices(
    path: impl AsRef<Path>,
    options: &LoadOptions,
) -> Result<Arc<RailSlices>, ProfileError> {
    let path = path.as_ref();
    let name = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|e| ProfileError::Io {
        file: name.clone(),
        message: e.to_string(),
    })?;
    let text = String::from_utf8_lossy(&bytes);
    let dir = path.parent().unwrap_or(Path::new("")).to_path_buf();
    let options = LoadOptions {
        kind: Some(ProfileKind::Rail),
        ..*options
    };
    parse_slices(&text, &name, |f| {
        crate::wheelrail::load_profile_with(dir.join(f), &options)
    })
    .map(Arc::new)
}

/// Whether `file_name` names a rail slices file (extension `.slcs`, any
/// case).
pub fn is_slices_file(file_name: &str) -> bool {
    Path::new(file_name)
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("slcs"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rail(points: &[[f64; 2]]) -> Profile {
        Profile::from_points(
            "r",
            Some(ProfileKind::Rail),
            points,
            &ProfileChecks::default(),
        )
        .unwrap()
    }

    /// A small crowned rail, heights shifted by `dz` [m].
    fn crown(dz: f64) -> Vec<[f64; 2]> {
        (0..41)
            .map(|i| {
                let y = -0.035 + 0.07 * i as f64 / 40.0;
                [y, y * y / 0.6 + dz]
            })
            .collect()
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
}
