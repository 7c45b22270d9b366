//! Readers for profile files: Simpack (`.prr`, `.prw`), MiniProf (`.ban`,
//! `.whl`) and plain two-column text/CSV.
//!
//! Each reader turns a file into points in metres in the profile frame of
//! [`crate::wheelrail`] (y lateral towards the field side of a right-hand
//! rail or wheel, z down), then [`crate::wheelrail::Profile::from_points`]'s
//! ordering and checks are applied. Errors name the file and the line and
//! say what was expected there. The conventions below follow CONTACT's
//! readers (Vollebregt, *User guide for CONTACT*, section on wheel/rail
//! profiles; `m_profile.f90`), which read the same files.
//!
//! # Simpack `.prr` / `.prw`
//!
//! * `!` (and `%`) start a comment anywhere outside quotes; commented-out
//!   points (`!7.0E+01 9.5E+00`) are ignored. Keywords and keys are
//!   case-insensitive.
//! * Structure: `header.begin` ... `header.end`, then `spline.begin` ...
//!   `spline.end` containing `key = value` lines and one
//!   `point.begin` ... `point.end` block with `y z [weight]` per line
//!   (whitespace or commas between the numbers; Fortran `D` exponents are
//!   accepted). A missing header, bad nesting, a file ending inside a block
//!   and a line that is not two or three numbers in the point block are
//!   errors. Content after `spline.end` is ignored with a warning.
//! * Header: `type` = 0 rail, 1 wheel; it must agree with the extension
//!   (`.prr` rail, `.prw` wheel) or [`LoadOptions::kind`].
//! * Spline keys are applied in the order Simpack numbers them in its own
//!   files: 1 `point.dist.min` (points closer than this are merged),
//!   2 `shift.y`, `shift.z` (added), 3 `rotate` (only 0 is supported,
//!   another value is an error), 4 `bound.y.min/max` (points outside are
//!   removed) and `bound.z.min/max` (z is clipped), both only when
//!   min < max, 5 `mirror.y`, `mirror.z` (negate y or z when 1),
//!   6 `inversion` (reverse the point order when 1), 7 `units.len.f`: the
//!   file's lengths are in units of `1/units.len.f` metre (user units per
//!   metre, 1000 for mm; default 1, metres); `units.ang.f` likewise for
//!   `rotate`. Lengths in keys are in the same user units as the points.
//!   `approx.smooth` is Simpack's own smoothing and is not used (a warning
//!   when it is not 0); the smoothing here is chosen with
//!   [`crate::wheelrail::spline::SplineOptions`]. `units.len`/`units.ang`
//!   (unit names), `file`, `file.mtime`, `type` are ignored, `comment`
//!   becomes the description; unknown keys are ignored with a warning.
//! * Simpack files are taken to be in the profile frame after these flags:
//!   z is never flipped automatically.
//!
//! # MiniProf `.ban` / `.whl`
//!
//! * Three variants ([`MiniProfVariant`]): the older text variant (first
//!   line `MINIPROF ...`, free text, a line `... (Sd/Sh/qR)`), the
//!   `Key=Value` variant (`XYPoints=147`, `ColumnDef=X,Y,A,C`,
//!   `XOffset=`, `YOffset=`, ... ; lines starting with `"` are commented-out
//!   keys) and the 2020 variant (first line `#MINIWHEELPROF`, a line
//!   `MINIPROF 2020`). The header ends at the first blank line; every
//!   following non-blank line (except comment lines starting with `#`, `!`,
//!   `%` or `"`) is a data line. A file without such a header is an error
//!   (use the plain format for bare point lists).
//! * Data lines hold the columns of `ColumnDef` (X lateral, Y vertical,
//!   A angle, C curvature, N, K; exactly that many numbers), or without
//!   `ColumnDef` at least two numbers of which the first two are X and Y
//!   (the text variants carry a third column that is ignored). Values are
//!   in mm; `XOffset`/`YOffset` \[mm\] are added. A count different from
//!   `XYPoints` is an error (truncated file), unless the data lines
//!   commented out with `"` make up the difference (a warning: points
//!   removed by hand, as in CONTACT's `MBench_UIC60_v3.ban`).
//! * Orientation: MiniProf's X is taken as y as it is; wheels have X = 0
//!   at the back of the flange, growing towards the field side, which is
//!   the profile frame already (origin at the flange back, the tape circle
//!   at y = 70 mm). Rails are measured with X in either direction: files
//!   with the gauge face at +X, like `avg_HR.BAN` (CONTACT's test bank reads
//!   it with `mirror_y`), need [`LoadOptions::mirror_y`].
//!   MiniProf's Y may point up or down; with [`MirrorZ::Auto`] it is
//!   flipped when the shape says it points up, by CONTACT's rules: for a
//!   rail, z must decrease from both ends towards the interior (the top of
//!   the rail lies above the ends; judged on the first change beyond 0.1 %
//!   of the height range within the outer 10 % of the points, and if
//!   undecided, flipped when the highest point lies in the outer 10 %); for
//!   a wheel, the flange tip (largest z) lies in the interior: z is kept
//!   when the smallest z lies in the outer 5 % of the points, flipped when
//!   the largest does, and otherwise flipped when the profile lies below
//!   the straight line between its extremes halfway between them. Without
//!   a known kind z is kept.
//!
//! # Plain two-column text/CSV
//!
//! * One point `y z` per line, separated by spaces, tabs, commas or
//!   semicolons; `#` starts a comment. Exactly two numbers per line.
//! * Units: metres, unless a comment line `# unit: mm` (or `# units = mm`;
//!   `m` for metres) or a header line of column names with a unit suffix
//!   (`y_mm, z_mm`, `y [mm]`, `y_m`) says otherwise, or
//!   [`LoadOptions::plain_unit`] overrides it. One first line of column
//!   names without numbers is allowed.
//! * The points are taken to be in the profile frame as they are (no
//!   automatic flip of z); the kind comes only from [`LoadOptions::kind`].

use super::profile::{
    quote, LengthUnit, LoadOptions, MiniProfVariant, MirrorZ, Profile, ProfileError, ProfileFormat,
    ProfileKind, ProfileWarning, RawPoint, RawProfile, SourceLocation, MAX_COORDINATE_M,
};

/// Largest Simpack point weight (third column) \[-\]; weights are
/// relative, commonly 1.
pub const MAX_POINT_WEIGHT: f64 = 1e6;

/// Range of Simpack's unit factors `units.len.f` and `units.ang.f` (user
/// units per SI unit): 1e-3 (kilometres) to 1e6 (micrometres).
pub const UNIT_FACTOR_RANGE: [f64; 2] = [1e-3, 1e6];

/// Parses Simpack profile text (default options; the kind from the
/// extension of `file_name` and the header's `type`).
pub fn parse_simpack(text: &str, file_name: &str) -> Result<Profile, ProfileError> {
    parse_as(text, file_name, ProfileFormat::Simpack)
}

/// Parses MiniProf profile text (any variant; default options).
pub fn parse_miniprof(text: &str, file_name: &str) -> Result<Profile, ProfileError> {
    parse_as(
        text,
        file_name,
        ProfileFormat::MiniProf(miniprof_variant(text)),
    )
}

/// Parses plain two-column text (default options: metres unless the file
/// says `# unit: mm`, no kind).
pub fn parse_plain(text: &str, file_name: &str) -> Result<Profile, ProfileError> {
    parse_as(text, file_name, ProfileFormat::Plain)
}

fn parse_as(text: &str, file_name: &str, format: ProfileFormat) -> Result<Profile, ProfileError> {
    let options = LoadOptions {
        format: Some(format),
        ..LoadOptions::default()
    };
    super::profile::parse_profile(text, file_name, &options)
}

// ------------------------------------------------------------------ helpers

fn syntax(file: &str, line: usize, expected: &str, found: &str) -> ProfileError {
    ProfileError::Syntax {
        at: SourceLocation::new(file, Some(line)),
        expected: expected.to_string(),
        found: quote(found),
    }
}

fn format_err(file: &str, line: Option<usize>, message: String) -> ProfileError {
    ProfileError::Format {
        at: SourceLocation::new(file, line),
        message,
    }
}

fn warn(file: &str, line: Option<usize>, message: String) -> ProfileWarning {
    ProfileWarning {
        at: SourceLocation::new(file, line),
        message,
    }
}

/// A finite number; accepts Fortran `D` exponents. `inf`/`nan` are rejected.
fn parse_number(token: &str) -> Option<f64> {
    let t = token.trim();
    if t.is_empty()
        || t.chars()
            .any(|c| c.is_ascii_alphabetic() && !"eEdD".contains(c))
    {
        return None;
    }
    let v: f64 = if t.contains(['d', 'D']) {
        t.replace(['d', 'D'], "e").parse().ok()?
    } else {
        t.parse().ok()?
    };
    v.is_finite().then_some(v)
}

/// Splits at whitespace, commas and semicolons.
fn fields(s: &str) -> Vec<&str> {
    s.split(|c: char| c.is_whitespace() || c == ',' || c == ';')
        .filter(|t| !t.is_empty())
        .collect()
}

/// All fields as numbers, or `None` if one is not a number.
fn numbers(s: &str) -> Option<Vec<f64>> {
    fields(s).into_iter().map(parse_number).collect()
}

/// The part of `line` before the first comment character outside quotes.
fn strip_comment<'a>(line: &'a str, comment: &[char]) -> &'a str {
    let mut quote: Option<char> = None;
    for (i, c) in line.char_indices() {
        match quote {
            Some(q) if c == q => quote = None,
            Some(_) => {}
            None if c == '\'' || c == '"' => quote = Some(c),
            None if comment.contains(&c) => return &line[..i],
            None => {}
        }
    }
    line
}

fn unquote(s: &str) -> &str {
    let s = s.trim();
    for q in ['\'', '"'] {
        if s.len() >= 2 && s.starts_with(q) && s.ends_with(q) {
            return &s[1..s.len() - 1];
        }
    }
    s
}

/// Format by content, for files whose extension does not tell.
pub(crate) fn sniff(text: &str) -> ProfileFormat {
    for line in text.lines().take(400) {
        let t = strip_comment(line, &['!', '%']).trim().to_ascii_lowercase();
        if t == "header.begin" || t == "spline.begin" {
            return ProfileFormat::Simpack;
        }
    }
    let first = text.lines().map(str::trim).find(|l| !l.is_empty());
    if let Some(f) = first {
        let u = f.to_ascii_uppercase();
        if u.starts_with("MINIPROF") || u.starts_with("#MINI") {
            return ProfileFormat::MiniProf(miniprof_variant(text));
        }
    }
    for line in text.lines() {
        let t = line.trim();
        if t.is_empty() {
            break;
        }
        if let Some((k, _)) = t.trim_matches('"').split_once('=') {
            let k = k.trim().to_ascii_lowercase();
            if k == "xypoints" || k == "columndef" {
                return ProfileFormat::MiniProf(MiniProfVariant::KeyValue);
            }
        }
    }
    ProfileFormat::Plain
}

/// The MiniProf variant, from the first non-blank line.
pub(crate) fn miniprof_variant(text: &str) -> MiniProfVariant {
    let first = text
        .lines()
        .map(str::trim)
        .find(|l| !l.is_empty())
        .unwrap_or("")
        .to_ascii_uppercase();
    if first.starts_with("#MINI") {
        MiniProfVariant::Y2020
    } else if first.starts_with("MINIPROF") {
        if first.contains("2020") {
            MiniProfVariant::Y2020
        } else {
            MiniProfVariant::Text
        }
    } else {
        MiniProfVariant::KeyValue
    }
}

fn mirror_z_flip(options: &LoadOptions) -> bool {
    options.mirror_z == MirrorZ::Flip
}

// ------------------------------------------------------------------ Simpack

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Section {
    Outside,
    Header,
    Spline,
    Points,
}

struct SimpackKeys {
    point_dist_min: f64,
    shift_y: (f64, usize),
    shift_z: (f64, usize),
    rotate: (f64, usize),
    bound_y: (f64, f64),
    bound_z: (f64, f64),
    mirror_y: bool,
    mirror_z: bool,
    inversion: bool,
    units_len_f: (f64, usize),
    units_ang_f: f64,
}

fn simpack_flag(file: &str, line: usize, key: &str, value: &str) -> Result<bool, ProfileError> {
    match parse_number(value) {
        Some(0.0) => Ok(false),
        Some(1.0) => Ok(true),
        _ => Err(syntax(file, line, &format!("0 or 1 for `{key}`"), value)),
    }
}

fn simpack_number(file: &str, line: usize, key: &str, value: &str) -> Result<f64, ProfileError> {
    parse_number(value).ok_or_else(|| syntax(file, line, &format!("a number for `{key}`"), value))
}

pub(crate) fn read_simpack(
    text: &str,
    file: &str,
    expected_kind: Option<ProfileKind>,
    options: &LoadOptions,
) -> Result<RawProfile, ProfileError> {
    let mut section = Section::Outside;
    let mut header_at: Option<usize> = None;
    let mut spline_at: Option<usize> = None;
    let mut points_at: Option<usize> = None;
    let mut done = false;
    let mut ignored_after = false;
    let mut last_line = 0;
    let mut file_kind: Option<(ProfileKind, usize)> = None;
    let mut description = None;
    let mut warnings = Vec::new();
    let mut points: Vec<RawPoint> = Vec::new();
    let mut keys = SimpackKeys {
        point_dist_min: 0.0,
        shift_y: (0.0, 0),
        shift_z: (0.0, 0),
        rotate: (0.0, 0),
        bound_y: (1.0, 0.0),
        bound_z: (1.0, 0.0),
        mirror_y: false,
        mirror_z: false,
        inversion: false,
        units_len_f: (1.0, 0),
        units_ang_f: 1.0,
    };

    for (idx, raw_line) in text.lines().enumerate() {
        let line = idx + 1;
        last_line = line;
        let content = strip_comment(raw_line, &['!', '%']).trim();
        if content.is_empty() {
            continue;
        }
        if done {
            if !ignored_after {
                warnings.push(warn(
                    file,
                    Some(line),
                    format!("ignored content after spline.end: '{}'", quote(content)),
                ));
                ignored_after = true;
            }
            continue;
        }
        let lower = content.to_ascii_lowercase();
        let expected_here = match section {
            Section::Outside => "header.begin or spline.begin",
            Section::Header => "`key = value` or header.end",
            Section::Spline => "`key = value`, point.begin or spline.end",
            Section::Points => "two numbers (y z) or three (y z weight), or point.end",
        };
        let keyword = matches!(
            lower.as_str(),
            "header.begin"
                | "header.end"
                | "spline.begin"
                | "spline.end"
                | "point.begin"
                | "point.end"
        );
        if keyword {
            match (section, lower.as_str()) {
                (Section::Outside, "header.begin") => {
                    if let Some(h) = header_at {
                        return Err(format_err(
                            file,
                            Some(line),
                            format!("second header.begin (the first is at line {h})"),
                        ));
                    }
                    header_at = Some(line);
                    section = Section::Header;
                }
                (Section::Header, "header.end") => section = Section::Outside,
                (Section::Outside, "spline.begin") => {
                    if header_at.is_none() {
                        return Err(format_err(
                            file,
                            Some(line),
                            "missing header: expected a header block (header.begin, \
                             version = 1, type = 0 or 1, header.end) before spline.begin"
                                .to_string(),
                        ));
                    }
                    spline_at = Some(line);
                    section = Section::Spline;
                }
                (Section::Spline, "point.begin") => {
                    if let Some(p) = points_at {
                        return Err(format_err(
                            file,
                            Some(line),
                            format!("second point.begin (the first is at line {p})"),
                        ));
                    }
                    points_at = Some(line);
                    section = Section::Points;
                }
                (Section::Points, "point.end") => section = Section::Spline,
                (Section::Spline, "spline.end") => done = true,
                (Section::Points, _) => {
                    return Err(format_err(
                        file,
                        Some(line),
                        format!(
                            "expected point.end to close the point block opened at line {}, \
                             found '{}'",
                            points_at.unwrap_or(0),
                            quote(content)
                        ),
                    ))
                }
                _ => {
                    return Err(format_err(
                        file,
                        Some(line),
                        format!(
                            "badly nested sections: expected {expected_here}, found '{}'",
                            quote(content)
                        ),
                    ))
                }
            }
            continue;
        }

        if section == Section::Points {
            let expected = "two numbers (y z) or three (y z weight)";
            let Some(v) = numbers(content) else {
                return Err(syntax(file, line, expected, content));
            };
            if v.len() < 2 || v.len() > 3 {
                return Err(syntax(file, line, expected, content));
            }
            let weight = if v.len() == 3 { v[2] } else { 1.0 };
            if !(weight > 0.0 && weight <= MAX_POINT_WEIGHT) {
                return Err(syntax(
                    file,
                    line,
                    &format!("a weight > 0 and <= {MAX_POINT_WEIGHT:e} in the third column"),
                    content,
                ));
            }
            points.push(RawPoint {
                y: v[0],
                z: v[1],
                weight,
                line: Some(line),
            });
            continue;
        }

        let Some((k, v)) = content.split_once('=') else {
            return Err(syntax(file, line, expected_here, content));
        };
        let key = k.trim().to_ascii_lowercase();
        let value = v.trim();
        match section {
            Section::Outside | Section::Points => {
                return Err(syntax(file, line, expected_here, content))
            }
            Section::Header => match key.as_str() {
                "version" => {
                    simpack_number(file, line, "version", value)?;
                }
                "type" => {
                    let kind = match parse_number(value) {
                        Some(0.0) => ProfileKind::Rail,
                        Some(1.0) => ProfileKind::Wheel,
                        _ => {
                            return Err(syntax(file, line, "type = 0 (rail) or 1 (wheel)", content))
                        }
                    };
                    file_kind = Some((kind, line));
                }
                _ => warnings.push(warn(
                    file,
                    Some(line),
                    format!("unknown header key `{}` ignored", quote(k.trim())),
                )),
            },
            Section::Spline => match key.as_str() {
                "approx.smooth" => {
                    let s = simpack_number(file, line, "approx.smooth", value)?;
                    if s != 0.0 {
                        warnings.push(warn(
                            file,
                            Some(line),
                            format!(
                                "approx.smooth = {s} (Simpack's smoothing) is not used; \
                                 choose the smoothing with SplineOptions"
                            ),
                        ));
                    }
                }
                "comment" => description = Some(unquote(value).trim().to_string()),
                "file" | "file.mtime" | "type" | "units.len" | "units.ang" => {}
                "point.dist.min" => {
                    keys.point_dist_min = simpack_number(file, line, "point.dist.min", value)?
                }
                "shift.y" => keys.shift_y = (simpack_number(file, line, "shift.y", value)?, line),
                "shift.z" => keys.shift_z = (simpack_number(file, line, "shift.z", value)?, line),
                "rotate" => keys.rotate = (simpack_number(file, line, "rotate", value)?, line),
                "bound.y.min" => keys.bound_y.0 = simpack_number(file, line, "bound.y.min", value)?,
                "bound.y.max" => keys.bound_y.1 = simpack_number(file, line, "bound.y.max", value)?,
                "bound.z.min" => keys.bound_z.0 = simpack_number(file, line, "bound.z.min", value)?,
                "bound.z.max" => keys.bound_z.1 = simpack_number(file, line, "bound.z.max", value)?,
                "mirror.y" => keys.mirror_y = simpack_flag(file, line, "mirror.y", value)?,
                "mirror.z" => keys.mirror_z = simpack_flag(file, line, "mirror.z", value)?,
                "inversion" => keys.inversion = simpack_flag(file, line, "inversion", value)?,
                "units.len.f" | "units.ang.f" => {
                    let f = simpack_number(file, line, &key, value)?;
                    let [lo, hi] = UNIT_FACTOR_RANGE;
                    if !(lo..=hi).contains(&f) {
                        return Err(syntax(
                            file,
                            line,
                            &format!(
                                "a unit factor from {lo:e} to {hi:e} for `{key}` (user units \
                                 per SI unit: 1000 for mm)"
                            ),
                            value,
                        ));
                    }
                    if key == "units.len.f" {
                        keys.units_len_f = (f, line);
                    } else {
                        keys.units_ang_f = f;
                    }
                }
                _ => warnings.push(warn(
                    file,
                    Some(line),
                    format!("unknown spline key `{}` ignored", quote(k.trim())),
                )),
            },
        }
    }

    if !done {
        let at = Some(last_line.max(1));
        let message = match section {
            Section::Points => format!(
                "truncated point block: the file ends inside the point block opened at line {}; \
                 expected point.end and spline.end",
                points_at.unwrap_or(0)
            ),
            Section::Spline => format!(
                "truncated file: the file ends inside the spline block opened at line {}; \
                 expected spline.end",
                spline_at.unwrap_or(0)
            ),
            Section::Header => format!(
                "truncated file: the file ends inside the header block opened at line {}; \
                 expected header.end",
                header_at.unwrap_or(0)
            ),
            Section::Outside if header_at.is_none() => {
                "missing header: expected a Simpack profile (header.begin ... header.end, \
                 spline.begin ... spline.end)"
                    .to_string()
            }
            Section::Outside => {
                "no spline block: expected spline.begin with a point.begin ... point.end block"
                    .to_string()
            }
        };
        return Err(format_err(file, at, message));
    }
    if points_at.is_none() {
        return Err(format_err(
            file,
            spline_at,
            "the spline block has no point.begin ... point.end block".to_string(),
        ));
    }

    let kind = match (expected_kind, file_kind) {
        (Some(e), Some((k, line))) if e != k => {
            return Err(format_err(
                file,
                Some(line),
                format!(
                    "header type says {k}, but a {e} profile was expected (from the file \
                     extension or LoadOptions::kind)"
                ),
            ))
        }
        (Some(e), _) => Some(e),
        (None, k) => k.map(|(k, _)| k),
    };

    // 2: shift, 3: rotate, 4: bounds, 5: mirror, 6: inversion, 7: units.
    let (rot, rot_line) = keys.rotate;
    if (rot / keys.units_ang_f).abs() > 1e-12 {
        return Err(format_err(
            file,
            Some(rot_line),
            format!(
                "rotate = {rot} is not supported; expected rotate = 0 (rotate the points instead)"
            ),
        ));
    }
    let f = keys.units_len_f.0;
    for (key, (shift, at)) in [("shift.y", keys.shift_y), ("shift.z", keys.shift_z)] {
        if (shift / f).abs() > MAX_COORDINATE_M {
            return Err(format_err(
                file,
                Some(at),
                format!(
                    "{key} = {shift} is {:e} m (units.len.f = {f}), more than \
                     {MAX_COORDINATE_M} m; expected a shift of the profile's origin",
                    shift / f
                ),
            ));
        }
    }
    for p in &mut points {
        p.y += keys.shift_y.0;
        p.z += keys.shift_z.0;
    }
    let (ylo, yhi) = keys.bound_y;
    if ylo < yhi {
        let before = points.len();
        points.retain(|p| p.y >= ylo && p.y <= yhi);
        if points.len() < before {
            warnings.push(warn(
                file,
                None,
                format!(
                    "removed {} points outside bound.y.min/max = [{ylo}, {yhi}]",
                    before - points.len()
                ),
            ));
        }
    }
    let (zlo, zhi) = keys.bound_z;
    if zlo < zhi {
        for p in &mut points {
            p.z = p.z.clamp(zlo, zhi);
        }
    }
    if keys.mirror_y != options.mirror_y {
        for p in &mut points {
            p.y = -p.y;
        }
    }
    if keys.mirror_z != mirror_z_flip(options) {
        for p in &mut points {
            p.z = -p.z;
        }
    }
    if keys.inversion {
        points.reverse();
    }
    for p in &mut points {
        p.y /= f;
        p.z /= f;
    }

    Ok(RawProfile {
        kind,
        format: Some(ProfileFormat::Simpack),
        description,
        points,
        warnings,
        merge_distance_m: keys.point_dist_min.max(0.0) / f,
    })
}

// ----------------------------------------------------------------- MiniProf

/// A MiniProf offset key's value \[mm\], at most [`MAX_COORDINATE_M`].
fn miniprof_offset(file: &str, line: usize, key: &str, value: &str) -> Result<f64, ProfileError> {
    let limit_mm = MAX_COORDINATE_M * 1e3;
    parse_number(value)
        .filter(|v| v.abs() <= limit_mm)
        .ok_or_else(|| {
            syntax(
                file,
                line,
                &format!("a number [mm] from -{limit_mm} to {limit_mm} for {key}"),
                value,
            )
        })
}

fn is_miniprof_comment(t: &str) -> bool {
    t.starts_with(['#', '!', '%', '"'])
}

pub(crate) fn read_miniprof(
    text: &str,
    file: &str,
    expected_kind: Option<ProfileKind>,
    options: &LoadOptions,
) -> Result<RawProfile, ProfileError> {
    let variant = miniprof_variant(text);
    let mut warnings = Vec::new();
    let mut description: Option<String> = None;
    let mut content_kind: Option<ProfileKind> = None;
    let mut xy_points: Option<(usize, usize)> = None;
    let mut columns: Option<(Vec<char>, String)> = None;
    let mut x_offset = 0.0;
    let mut y_offset = 0.0;
    let mut in_header = true;
    let mut header_lines = 0;
    let mut data_start: Option<usize> = None;
    let mut last_line = 0;
    let mut commented_points = 0usize;
    let mut points: Vec<RawPoint> = Vec::new();

    for (idx, raw_line) in text.lines().enumerate() {
        let line = idx + 1;
        last_line = line;
        let t = raw_line.trim();
        if in_header {
            if t.is_empty() {
                if header_lines > 0 {
                    in_header = false;
                }
                continue;
            }
            header_lines += 1;
            let fully_numeric = numbers(t).is_some_and(|v| v.len() >= 2);
            if header_lines == 1 {
                let u = t.to_ascii_uppercase();
                let marker = u.starts_with("MINIPROF") || u.starts_with("#MINI");
                let key_value = !fully_numeric && (t.contains('=') || t.starts_with('"'));
                if !(marker || key_value) {
                    return Err(format_err(
                        file,
                        Some(line),
                        format!(
                            "missing header: expected a MiniProf header (a line `MINIPROF ...`, \
                             `#MINIWHEELPROF` or `Key=Value` lines, then a blank line) before \
                             the data, found '{}'",
                            quote(t)
                        ),
                    ));
                }
                if u.starts_with("#MINI") {
                    if u.contains("WHEEL") {
                        content_kind = Some(ProfileKind::Wheel);
                    } else if u.contains("RAIL") {
                        content_kind = Some(ProfileKind::Rail);
                    }
                }
                continue;
            }
            if fully_numeric {
                warnings.push(warn(
                    file,
                    Some(line),
                    "no blank line between header and data; data taken to start here".into(),
                ));
                in_header = false;
                // Fall through to the data handling below.
            } else {
                if header_lines == 2
                    && matches!(variant, MiniProfVariant::Text | MiniProfVariant::Y2020)
                {
                    description = Some(t.to_string());
                }
                if t.starts_with('"') {
                    continue;
                }
                if let Some((k, v)) = t.split_once('=') {
                    let key = k.trim().to_ascii_lowercase();
                    let value = v.trim();
                    match key.as_str() {
                        "xypoints" if !value.is_empty() => match parse_number(value) {
                            Some(n) if n >= 0.0 && n.fract() == 0.0 => {
                                xy_points = Some((n as usize, line))
                            }
                            _ => {
                                return Err(syntax(
                                    file,
                                    line,
                                    "a whole number of points for XYPoints",
                                    value,
                                ))
                            }
                        },
                        "columndef" => {
                            let cols: Vec<&str> = value.split(',').map(str::trim).collect();
                            let ok = cols.iter().all(|c| c.len() == 1)
                                && cols.contains(&"X")
                                && cols.contains(&"Y");
                            if !ok {
                                return Err(syntax(
                                    file,
                                    line,
                                    "ColumnDef with one letter per column including X and Y, \
                                     e.g. X,Y,A,C",
                                    value,
                                ));
                            }
                            let letters = cols.iter().filter_map(|c| c.chars().next()).collect();
                            columns = Some((letters, value.to_string()));
                        }
                        "xoffset" if !value.is_empty() => {
                            x_offset = miniprof_offset(file, line, "XOffset", value)?
                        }
                        "yoffset" if !value.is_empty() => {
                            y_offset = miniprof_offset(file, line, "YOffset", value)?
                        }
                        "filename" if !value.is_empty() => description = Some(value.to_string()),
                        _ => {}
                    }
                } else if matches!(variant, MiniProfVariant::KeyValue) && !is_miniprof_comment(t) {
                    // The other variants' headers hold free text; this
                    // one's are keys (a line that lost its `=` is one).
                    warnings.push(warn(
                        file,
                        Some(line),
                        format!(
                            "header line '{}' is not `Key=Value`: ignored (give `Key=Value`, or \
                             start it with `\"` to keep it as a comment)",
                            quote(t)
                        ),
                    ));
                }
                continue;
            }
        }

        // Data section.
        if t.is_empty() {
            continue;
        }
        if is_miniprof_comment(t) {
            // A data line commented out with `"` (MiniProf's way of
            // removing a point): counted against XYPoints below.
            if t.starts_with('"') && numbers(t[1..].trim()).is_some_and(|v| v.len() >= 2) {
                commented_points += 1;
            }
            continue;
        }
        let content = strip_comment(t, &['!', '#', '%']).trim();
        if content.is_empty() {
            continue;
        }
        data_start.get_or_insert(line);
        if let Some((k, _)) = content.split_once('=') {
            return Err(format_err(
                file,
                Some(line),
                format!(
                    "found header key `{}` after the data started at line {}; expected data lines \
                     (the header ends at the first blank line)",
                    quote(k.trim()),
                    data_start.unwrap_or(line)
                ),
            ));
        }
        let (expected, ncol) = match &columns {
            Some((c, def)) => (
                format!("{} numbers (ColumnDef {def})", c.len()),
                Some(c.len()),
            ),
            None => ("two numbers (X Y)".to_string(), None),
        };
        let Some(v) = numbers(content) else {
            return Err(syntax(file, line, &expected, content));
        };
        let count_ok = match ncol {
            Some(n) => v.len() == n,
            None => v.len() >= 2,
        };
        if !count_ok {
            return Err(syntax(file, line, &expected, content));
        }
        let (ix, iy) = match &columns {
            Some((c, _)) => (
                c.iter().position(|&l| l == 'X').unwrap_or(0),
                c.iter().position(|&l| l == 'Y').unwrap_or(1),
            ),
            None => (0, 1),
        };
        points.push(RawPoint {
            y: v[ix] + x_offset,
            z: v[iy] + y_offset,
            weight: 1.0,
            line: Some(line),
        });
    }

    if in_header || points.is_empty() {
        return Err(format_err(
            file,
            Some(last_line.max(1)),
            "no profile points: the file ends in the header; expected a blank line followed by \
             the data lines"
                .to_string(),
        ));
    }
    if let Some((n, n_line)) = xy_points {
        if n == points.len() + commented_points && commented_points > 0 {
            // XYPoints counts the points commented out as well (CONTACT's
            // MBench_UIC60_v3.ban: 495 = 476 + 19).
            warnings.push(warn(
                file,
                Some(n_line),
                format!(
                    "XYPoints = {n} counts {commented_points} data lines commented out with `\"`; \
                     read the other {}",
                    points.len()
                ),
            ));
        } else if n != points.len() {
            let what = if points.len() < n {
                "truncated data: "
            } else {
                ""
            };
            return Err(format_err(
                file,
                Some(last_line),
                format!(
                    "{what}XYPoints = {n} (line {n_line}) but the file has {} data lines",
                    points.len()
                ),
            ));
        }
    }

    let kind = expected_kind.or(content_kind);
    if kind.is_none() && options.mirror_z == MirrorZ::Auto {
        warnings.push(warn(
            file,
            None,
            "rail or wheel unknown (extension and header do not say): the direction of z was \
             not checked; set LoadOptions::kind"
                .into(),
        ));
    }
    let flip_z = match options.mirror_z {
        MirrorZ::Flip => true,
        MirrorZ::Keep => false,
        MirrorZ::Auto => kind.is_some_and(|k| z_points_up(k, &points)),
    };
    if flip_z {
        for p in &mut points {
            p.z = -p.z;
        }
        if options.mirror_z == MirrorZ::Auto {
            warnings.push(warn(
                file,
                None,
                "MiniProf Y points up here: flipped to z positive down".into(),
            ));
        }
    }
    if options.mirror_y {
        for p in &mut points {
            p.y = -p.y;
        }
    }
    for p in &mut points {
        p.y *= 1e-3;
        p.z *= 1e-3;
    }
    Ok(RawProfile {
        kind,
        format: Some(ProfileFormat::MiniProf(variant)),
        description,
        points,
        warnings,
        merge_distance_m: 0.0,
    })
}

/// Whether the points have z pointing up (CONTACT's rules, see the module
/// documentation).
fn z_points_up(kind: ProfileKind, p: &[RawPoint]) -> bool {
    let n = p.len();
    if n < 3 {
        return false;
    }
    let (mut imin, mut imax) = (0, 0);
    for i in 0..n {
        if p[i].z < p[imin].z {
            imin = i;
        }
        if p[i].z > p[imax].z {
            imax = i;
        }
    }
    let frac = |i: usize| (i + 1) as f64 / n as f64;
    match kind {
        ProfileKind::Wheel => {
            let outer = |f: f64| !(0.05..=0.95).contains(&f);
            if outer(frac(imin)) {
                false
            } else if outer(frac(imax)) {
                true
            } else {
                let im =
                    (((frac(imin) + frac(imax)) / 2.0 * n as f64).round() as usize).clamp(1, n) - 1;
                p[im].z > 0.5 * (p[imin].z + p[imax].z)
            }
        }
        ProfileKind::Rail => {
            let dz_tot = (p[imax].z - p[imin].z).max(1e-12);
            let reach = ((0.1 * n as f64).round() as usize).max(2).min(n - 1);
            let first_change = |order: &mut dyn Iterator<Item = usize>, origin: usize| -> i32 {
                for i in order {
                    let dz = p[i].z - p[origin].z;
                    if dz.abs() > 1e-3 * dz_tot {
                        return if dz > 0.0 { 1 } else { -1 };
                    }
                }
                0
            };
            let start = first_change(&mut (1..=reach), 0);
            let end = first_change(&mut (n - 1 - reach..n - 1).rev(), n - 1);
            let decision = if start == end || end == 0 {
                start
            } else if start == 0 {
                end
            } else {
                -1
            };
            if decision == 0 {
                // Undecided: z points up if the lowest z lies near an end.
                !(0.1..=0.9).contains(&frac(imin))
            } else {
                decision > 0
            }
        }
    }
}

// -------------------------------------------------------------------- plain

fn unit_from_name(s: &str) -> Option<LengthUnit> {
    match s.trim().to_ascii_lowercase().as_str() {
        "mm" | "millimetre" | "millimetres" | "millimeter" | "millimeters" => {
            Some(LengthUnit::Millimetre)
        }
        "m" | "metre" | "metres" | "meter" | "meters" => Some(LengthUnit::Metre),
        _ => None,
    }
}

/// Unit from column names such as `y_mm`, `y [mm]`, `y(m)`.
fn unit_from_columns(names: &[&str]) -> Option<LengthUnit> {
    let mut unit = None;
    for n in names {
        let l = n.to_ascii_lowercase();
        let u = if l.ends_with("_mm") || l.contains("[mm]") || l.contains("(mm)") {
            Some(LengthUnit::Millimetre)
        } else if l.ends_with("_m") || l.contains("[m]") || l.contains("(m)") {
            Some(LengthUnit::Metre)
        } else {
            None
        };
        if u.is_some() {
            unit = u;
        }
    }
    unit
}

pub(crate) fn read_plain(
    text: &str,
    file: &str,
    expected_kind: Option<ProfileKind>,
    options: &LoadOptions,
) -> Result<RawProfile, ProfileError> {
    let mut file_unit: Option<(LengthUnit, usize)> = None;
    let mut set_unit = |u: LengthUnit, line: usize| -> Result<(), ProfileError> {
        match file_unit {
            Some((prev, at)) if prev != u => Err(format_err(
                file,
                Some(line),
                format!("unit {u:?} contradicts unit {prev:?} given at line {at}"),
            )),
            _ => {
                file_unit = Some((u, line));
                Ok(())
            }
        }
    };
    let mut points: Vec<RawPoint> = Vec::new();
    let mut seen_content = false;
    for (idx, raw_line) in text.lines().enumerate() {
        let line = idx + 1;
        if let Some(pos) = raw_line.find('#') {
            let comment = raw_line[pos + 1..].trim();
            let lower = comment.to_ascii_lowercase();
            if let Some(rest) = lower
                .strip_prefix("units")
                .or_else(|| lower.strip_prefix("unit"))
            {
                let rest = rest.trim_start();
                if let Some(value) = rest.strip_prefix([':', '=']) {
                    let u = unit_from_name(value).ok_or_else(|| {
                        syntax(file, line, "`# unit: m` or `# unit: mm`", comment)
                    })?;
                    set_unit(u, line)?;
                }
            }
        }
        let content = strip_comment(raw_line, &['#']).trim();
        if content.is_empty() {
            continue;
        }
        let f = fields(content);
        let first = !seen_content;
        seen_content = true;
        if first && f.iter().all(|t| parse_number(t).is_none()) {
            if let Some(u) = unit_from_columns(&f) {
                set_unit(u, line)?;
            }
            continue;
        }
        let expected = "two numbers (y z)";
        let Some(v) = numbers(content) else {
            return Err(syntax(file, line, expected, content));
        };
        if v.len() != 2 {
            return Err(syntax(file, line, expected, content));
        }
        points.push(RawPoint {
            y: v[0],
            z: v[1],
            weight: 1.0,
            line: Some(line),
        });
    }
    let unit = options
        .plain_unit
        .or(file_unit.map(|(u, _)| u))
        .unwrap_or(LengthUnit::Metre);
    let s = unit.metres();
    let flip_z = mirror_z_flip(options);
    for p in &mut points {
        p.y *= if options.mirror_y { -s } else { s };
        p.z *= if flip_z { -s } else { s };
    }
    Ok(RawProfile {
        kind: expected_kind,
        format: Some(ProfileFormat::Plain),
        description: None,
        points,
        warnings: Vec::new(),
        merge_distance_m: 0.0,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_and_comments() {
        assert_eq!(parse_number("+1.0D+03"), Some(1000.0));
        assert_eq!(parse_number("1000."), Some(1000.0));
        assert_eq!(parse_number("inf"), None);
        assert_eq!(parse_number("nan"), None);
        assert_eq!(parse_number("1e999"), None);
        assert_eq!(parse_number("abc"), None);
        assert_eq!(
            strip_comment("comment = 'a ! b' ! real comment", &['!']).trim(),
            "comment = 'a ! b'"
        );
        assert_eq!(fields("1.0;2.0\t3, 4"), vec!["1.0", "2.0", "3", "4"]);
    }

    /// A MiniProf rail in the key=value variant with the given offsets and
    /// one data line replaced by `line3`.
    fn miniprof(x_offset: &str, y_offset: &str, line3: &str) -> String {
        let mut s = format!("XYPoints=5\nXOffset={x_offset}\nYOffset={y_offset}\n\n");
        for k in 0..5 {
            if k == 2 {
                s.push_str(line3);
            } else {
                s.push_str(&format!("{} {}", k as f64, 0.01 * (k as f64 - 2.0).powi(2)));
            }
            s.push('\n');
        }
        s
    }

    #[test]
    fn a_miniprof_header_line_that_is_not_a_key_is_named() {
        // `XOffset 1.5` lost its `=`: read without it, with a warning that
        // names the line.
        let text = miniprof("0", "0", "2 0").replace("XOffset=0\n", "XOffset 1.5\n");
        let p = parse_miniprof(&text, "r.ban").unwrap();
        let w: Vec<String> = p.warnings().iter().map(|w| w.to_string()).collect();
        assert!(
            w.iter()
                .any(|w| w.contains("r.ban line 2")
                    && w.contains("'XOffset 1.5' is not `Key=Value`")),
            "{w:?}"
        );
        // Comments and a well-formed header give none.
        let p = parse_miniprof(
            &miniprof("0", "0", "2 0").replace("XOffset=0\n", "\"note\n"),
            "r.ban",
        )
        .unwrap();
        assert!(p.warnings().is_empty(), "{:?}", p.warnings());
    }

    #[test]
    fn absurd_offsets_scales_and_points_are_errors_with_file_and_line() {
        use crate::wheelrail::profile::MAX_QUOTE_CHARS;
        let ok = parse_miniprof(&miniprof("1.5", "-2", "2 0"), "r.ban").unwrap();
        assert_eq!(ok.len(), 5);
        for (x, y, at) in [
            ("1e20", "0", "r.ban line 2"),
            ("0", "1e300", "r.ban line 3"),
        ] {
            let e = parse_miniprof(&miniprof(x, y, "2 0"), "r.ban").unwrap_err();
            let m = e.to_string();
            assert!(m.starts_with(at) && m.contains("10000"), "{m}");
        }
        // A point 1e15 mm out: the extent check names its line; every
        // point 1e15 mm out (the extent is small): the coordinate check.
        let e = parse_miniprof(&miniprof("0", "0", "1e15 0"), "r.ban").unwrap_err();
        assert!(e.to_string().starts_with("r.ban line 7"), "{e}");
        assert!(e.to_string().contains("outside"), "{e}");
        let mut far = String::from("XYPoints=3\n\n");
        for k in 0..3 {
            far.push_str(&format!("{} 0\n", 1e15 + k as f64 * 0.5));
        }
        let e = parse_miniprof(&far, "r.ban").unwrap_err();
        assert!(
            matches!(
                e,
                ProfileError::Check {
                    kind: crate::wheelrail::CheckKind::Coordinate,
                    ..
                }
            ),
            "{e}"
        );
        assert!(e.to_string().starts_with("r.ban line 3"), "{e}");
        // Simpack: a shift of 1e20 m, a unit factor of 1e-300, a weight of
        // 1e300.
        let simpack = |key: &str, point: &str| {
            format!(
                "header.begin\nversion = 1\ntype = 0\nheader.end\nspline.begin\n{key}\n\
                 point.begin\n0 0\n0.001 0\n{point}\npoint.end\nspline.end\n"
            )
        };
        for (key, point, line) in [
            ("shift.y = 1e20", "0.002 0", 6),
            ("units.len.f = 1e-300", "0.002 0", 6),
            ("units.len.f = 1", "0.002 0 1e300", 10),
        ] {
            let e = parse_simpack(&simpack(key, point), "r.prr").unwrap_err();
            assert!(
                e.to_string().starts_with(&format!("r.prr line {line}")),
                "{key}: {e}"
            );
        }
        parse_simpack(&simpack("shift.y = 0.5", "0.002 0"), "r.prr").unwrap();
        // A 10 kB line is quoted with its first characters only.
        let long = "7".repeat(10_000) + " x";
        let e = parse_miniprof(&miniprof("0", "0", &long), "r.ban").unwrap_err();
        let m = e.to_string();
        assert!(m.len() < 300 && m.contains("(10002 characters)"), "{m}");
        assert!(m.contains(&"7".repeat(MAX_QUOTE_CHARS)), "{m}");
        // So is a long file name.
        let e = parse_plain("1 2 3\n", &"f".repeat(5000)).unwrap_err();
        assert!(e.to_string().len() < 300, "{e}");
    }

    #[test]
    fn sniffing() {
        assert_eq!(sniff("! x\n  header.begin\n"), ProfileFormat::Simpack);
        assert_eq!(
            sniff("MINIPROF 101\nx\n"),
            ProfileFormat::MiniProf(MiniProfVariant::Text)
        );
        assert_eq!(
            sniff("#MINIWHEELPROF\nx\nMINIPROF 2020\n"),
            ProfileFormat::MiniProf(MiniProfVariant::Y2020)
        );
        assert_eq!(
            sniff("Filename=a\nXYPoints=3\n\n1 2\n"),
            ProfileFormat::MiniProf(MiniProfVariant::KeyValue)
        );
        assert_eq!(sniff("# unit: mm\n1, 2\n"), ProfileFormat::Plain);
    }
}
