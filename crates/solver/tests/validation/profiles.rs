//! Wheel/rail profiles: every test-bank file loads into the profile frame,
//! malformed files give errors naming file and line, and the smoothing
//! spline reproduces known curvatures.

use railcontact_solver::wheelrail::{
    load_profile, load_profile_with, parse_miniprof, parse_plain, parse_profile, parse_simpack,
    CheckKind, LengthUnit, LoadOptions, MiniProfVariant, Profile, ProfileError, ProfileFormat,
    ProfileKind, ProfileSpline, SplineOptions,
};

fn path(name: &str) -> String {
    crate::profile_path(name)
}

fn text(name: &str) -> String {
    std::fs::read_to_string(path(name)).unwrap()
}

fn load(name: &str) -> Profile {
    load_profile(path(name)).unwrap_or_else(|e| panic!("{e}"))
}

/// Replaces line `line` (from 1) of `text`.
fn replace_line(text: &str, line: usize, new: &str) -> String {
    text.lines()
        .enumerate()
        .map(|(i, l)| if i + 1 == line { new } else { l })
        .collect::<Vec<_>>()
        .join("\n")
}

/// The first `n` lines of `text`.
fn head(text: &str, n: usize) -> String {
    text.lines().take(n).collect::<Vec<_>>().join("\n")
}

fn line_of(text: &str, needle: &str) -> usize {
    text.lines().position(|l| l.contains(needle)).unwrap() + 1
}

/// y values [m] where the profile crosses depth `z` [m] (linear between points).
fn crossings_at_z(p: &Profile, z: f64) -> Vec<f64> {
    p.points()
        .windows(2)
        .filter(|w| (w[0][1] - z) * (w[1][1] - z) <= 0.0 && w[0][1] != w[1][1])
        .map(|w| w[0][0] + (z - w[0][1]) / (w[1][1] - w[0][1]) * (w[1][0] - w[0][0]))
        .collect()
}

fn is_monotone(p: &Profile, increasing: bool) -> bool {
    let pts = p.points();
    let (a, b) = (pts[0][0], pts[pts.len() - 1][0]);
    if increasing {
        b > a
    } else {
        b < a
    }
}

// ------------------------------------------------------------ real files

#[test]
fn every_test_bank_file_loads() {
    let files = [
        (
            "MBench_S1002_v3.prw",
            ProfileKind::Wheel,
            ProfileFormat::Simpack,
            399,
        ),
        (
            "MBench_UIC60_v3.prr",
            ProfileKind::Rail,
            ProfileFormat::Simpack,
            492,
        ),
        (
            "circ_r10.prw",
            ProfileKind::Wheel,
            ProfileFormat::Simpack,
            199,
        ),
        (
            "circ_r100.prr",
            ProfileKind::Rail,
            ProfileFormat::Simpack,
            1999,
        ),
        (
            "avg_wheel.whl",
            ProfileKind::Wheel,
            ProfileFormat::MiniProf(MiniProfVariant::Text),
            728,
        ),
        (
            "Car7216_0001r.whl",
            ProfileKind::Wheel,
            ProfileFormat::MiniProf(MiniProfVariant::Y2020),
            644,
        ),
        (
            "avg_HR.BAN",
            ProfileKind::Rail,
            ProfileFormat::MiniProf(MiniProfVariant::KeyValue),
            146,
        ),
        (
            "MBench_UIC60_v3.ban",
            ProfileKind::Rail,
            ProfileFormat::MiniProf(MiniProfVariant::KeyValue),
            476,
        ),
    ];
    for (name, kind, format, n) in files {
        let p = load(name);
        assert_eq!(p.name(), name);
        assert_eq!(p.kind(), Some(kind), "{name}");
        assert_eq!(p.format(), Some(format), "{name}");
        assert_eq!(p.len(), n, "{name}");
        assert!(p.path().is_some());
        // CONTACT order: rails with increasing y, wheels decreasing.
        assert!(is_monotone(&p, kind == ProfileKind::Rail), "{name}");
        // Sane sizes in metres: 19 to 210 mm wide, 8 to 100 mm deep.
        let (y0, y1) = p.y_range_m();
        let (z0, z1) = p.z_range_m();
        assert!(y1 - y0 > 0.019 && y1 - y0 < 0.21, "{name}: {y0} {y1}");
        assert!(z1 - z0 > 0.008 && z1 - z0 < 0.1, "{name}: {z0} {z1}");
        // Every point remembers its line in the file.
        assert!(p.source_lines().iter().all(|l| l.is_some()), "{name}");
        // The default spline builds and covers the profile.
        let sp = p.spline(&SplineOptions::default()).unwrap();
        assert!(sp.length_m() > y1 - y0);
    }
}

/// CONTACT's `MBench_UIC60_v3.ban` says `XYPoints=495` and has 476 data
/// lines and 19 more commented out with `"`: read, with a warning naming
/// the 19 and the key's line.
#[test]
fn miniprof_points_commented_out_count_in_xypoints() {
    let p = load("MBench_UIC60_v3.ban");
    assert_eq!(p.len(), 476);
    let w: Vec<String> = p.warnings().iter().map(|w| w.to_string()).collect();
    assert!(
        w.iter().any(|w| w.contains("line 7")
            && w.contains("XYPoints = 495 counts 19 data lines commented out")),
        "{w:?}"
    );
}

#[test]
fn uic60_head_width_and_orientation() {
    let p = load("MBench_UIC60_v3.prr");
    assert_eq!(p.description().map(|d| d.starts_with("UIC60")), Some(true));
    // Top of rail at z = 0 (z down), the head going down to 38.5 mm.
    let (z0, z1) = p.z_range_m();
    assert!(z0.abs() < 1e-4 && (z1 - 0.0385).abs() < 1e-3, "{z0} {z1}");
    // Head width at the gauge height, 14 mm below the top: UIC60 is 72 mm.
    let ys = crossings_at_z(&p, 0.014);
    assert_eq!(ys.len(), 2, "{ys:?}");
    let width = ys[1] - ys[0];
    assert!((width - 0.072).abs() < 1.5e-3, "head width {width}");
    // Gauge face at -y (the field side at +y).
    assert!(ys[0] < -0.04 && ys[1] > 0.025, "{ys:?}");
    // The surface seen from above at the centre is the top.
    let sp = p.spline(&SplineOptions::default()).unwrap();
    assert!(sp.z_at_y(0.0).unwrap().abs() < 1e-4);
    assert!(sp.z_at_y(0.05).is_none());
    // The gauge corner (radius 13 mm nominally) is convex: positive curvature.
    let t = sp.t_at_y(-0.040).unwrap();
    let k = sp.curvature_per_m(t);
    assert!(k > 40.0 && k < 100.0, "gauge corner curvature {k}");
}

#[test]
fn s1002_flange_is_below_the_tread_on_the_gauge_side() {
    let p = load("MBench_S1002_v3.prw");
    let sp = p.spline(&SplineOptions::default()).unwrap();
    // Tape circle at the origin.
    assert!(sp.z_at_y(0.0).unwrap().abs() < 2e-5);
    // Flange tip: largest z, 28 mm below the tread, on the -y side
    // (S1002: flange tip about 15.5 mm from the flange back at y = -70 mm).
    let tip =
        p.points().iter().copied().fold(
            [0.0, f64::NEG_INFINITY],
            |a, b| if b[1] > a[1] { b } else { a },
        );
    assert!((tip[1] - 0.028).abs() < 0.2e-3, "{tip:?}");
    assert!(tip[0] < -0.050 && tip[0] > -0.058, "{tip:?}");
    let (y0, y1) = p.y_range_m();
    assert!((y0 + 0.0696).abs() < 1e-4 && (y1 - 0.060).abs() < 1e-4);
    // The tread descends (z grows) towards the flange: inclination < 0 at
    // y = -10 mm (1:40-like tread, atan(dz/dy) < 0).
    let t = sp.t_at_y(-0.010).unwrap();
    let a = sp.inclination_rad(t);
    assert!(a < 0.0 && a > -0.1, "tread inclination {a}");
    // The flange root is concave, the flange tip convex.
    let k_root = sp.curvature_per_m(sp.t_at_y(-0.034).unwrap());
    assert!(k_root < -20.0, "flange root curvature {k_root}");
    let t_tip = sp.knot_arc_lengths_m()[p.points().iter().position(|q| q[1] == tip[1]).unwrap()];
    assert!(sp.curvature_per_m(t_tip) > 20.0);
}

#[test]
fn miniprof_wheels_are_referenced_to_the_flange_back() {
    for name in ["avg_wheel.whl", "Car7216_0001r.whl"] {
        let p = load(name);
        let (y0, y1) = p.y_range_m();
        // y = 0 at the flange back, field face at 131 to 140 mm.
        assert!(
            y0.abs() < 2e-3 && y1 > 0.13 && y1 < 0.141,
            "{name}: {y0} {y1}"
        );
        let sp = p.spline(&SplineOptions::default()).unwrap();
        // z = 0 at the tape circle, 70 mm from the flange back.
        assert!(sp.z_at_y(0.070).unwrap().abs() < 0.3e-3, "{name}");
        // Flange 27 to 29 mm below the tread, 10 to 20 mm from the back.
        let (_, z1) = p.z_range_m();
        assert!(z1 > 0.027 && z1 < 0.029, "{name}: {z1}");
        let t = sp.t_at_y(0.016).unwrap();
        assert!((sp.position(t)[1] - z1).abs() < 1.5e-3, "{name}");
        // Moved to the tape circle, the wheel lines up with S1002.
        let moved = p.translated(-0.070, 0.0);
        let sm = moved.spline(&SplineOptions::default()).unwrap();
        assert!(sm.z_at_y(0.0).unwrap().abs() < 0.3e-3);
    }
    // The measured flange tip of Car7216 has a pair of points out of order;
    // it is repaired with a warning naming the lines.
    let p = load("Car7216_0001r.whl");
    assert_eq!(p.warnings().len(), 1);
    let w = p.warnings()[0].to_string();
    assert!(
        w.contains("Car7216_0001r.whl line 222") && w.contains("222, 223"),
        "{w}"
    );
}

#[test]
fn miniprof_rail_needs_mirroring_to_the_right_hand_side() {
    // avg_HR.BAN has MiniProf's Y up (flipped automatically) and its gauge
    // face at +X (CONTACT reads it with mirror_y too).
    let p = load("avg_HR.BAN");
    assert!(p.warnings().iter().any(|w| w.message.contains("flipped")));
    let (z0, z1) = p.z_range_m();
    assert!(
        z0 > 0.0 && z0 < 0.5e-3 && (z1 - 0.02542).abs() < 1e-6,
        "{z0} {z1}"
    );
    let opts = LoadOptions {
        mirror_y: true,
        ..LoadOptions::default()
    };
    let m = load_profile_with(path("avg_HR.BAN"), &opts).unwrap();
    assert!(is_monotone(&m, true));
    let (y0, y1) = m.y_range_m();
    assert!((y0 + 0.04659).abs() < 1e-7 && (y1 - 0.01173).abs() < 1e-7);
    // The deep gauge face is now at -y.
    let first = m.points()[0];
    assert!(first[0] < -0.046 && first[1] > 0.025, "{first:?}");
}

// ------------------------------------------------------------ curvature

/// Largest relative deviation of the curvature from `k` over the middle
/// `frac` of the arc length.
fn curvature_error(sp: &ProfileSpline, k: f64, frac: f64) -> f64 {
    let l = sp.length_m();
    (0..=400)
        .map(|i| {
            let t = l * (0.5 - frac / 2.0 + frac * i as f64 / 400.0);
            (sp.curvature_per_m(t) - k).abs() / k.abs()
        })
        .fold(0.0, f64::max)
}

#[test]
fn circle_files_have_curvature_one_over_r() {
    // Both headers say units.len.f = 1000: the data are in mm, rounded to
    // 1e-6 mm. At 0.1 mm spacing that rounding alone makes the curvature of
    // the interpolating spline of circ_r100 scatter by up to 4 %; the
    // default smoothing (2 mm) removes it.
    for (name, radius_m) in [("circ_r10.prw", 0.010), ("circ_r100.prr", 0.100)] {
        let p = load(name);
        for (opts, tol) in [
            (SplineOptions::interpolating(), 0.05),
            (SplineOptions::default(), 0.005),
        ] {
            let sp = p.spline(&opts).unwrap();
            // Both circles are convex: positive curvature in CONTACT order.
            let err = curvature_error(&sp, 1.0 / radius_m, 0.8);
            assert!(err < tol, "{name} {opts:?}: curvature error {err}");
            // Arc length of the section from y = -(R - 0.1 mm) to R - 0.1 mm.
            let half = ((radius_m - 1e-4) / radius_m).asin();
            assert!((sp.length_m() - 2.0 * radius_m * half).abs() < 2e-3 * sp.length_m());
            // Apex at the origin, level.
            let t = sp.t_at_y(0.0).unwrap();
            let q = sp.eval(t);
            assert!(
                q.z_m.abs() < 1e-7 && q.inclination_rad.abs() < 1e-4,
                "{q:?}"
            );
        }
    }
    // Over the middle half the default smoothing leaves R = 10 mm exact.
    let sp = load("circ_r10.prw")
        .spline(&SplineOptions::default())
        .unwrap();
    assert!(curvature_error(&sp, 100.0, 0.5) < 1e-3);
}

/// Deterministic pseudo-random numbers in [-1, 1].
fn noise(seed: &mut u64) -> f64 {
    *seed = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    ((*seed >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
}

#[test]
fn noisy_circle_is_smoothed() {
    // A rail crown of radius 50 mm sampled every 0.25 mm, with measurement
    // noise of +-5 µm normal to the surface.
    let r = 0.050;
    let n = 241;
    let mut seed = 42;
    let pts: Vec<[f64; 2]> = (0..n)
        .map(|i| {
            let a = (i as f64 - 120.0) * 0.25e-3 / r;
            let rr = r + 5e-6 * noise(&mut seed);
            [rr * a.sin(), r - rr * a.cos()]
        })
        .collect();
    let p =
        Profile::from_points("noisy", Some(ProfileKind::Rail), &pts, &Default::default()).unwrap();
    // Interpolated, the noise swamps the curvature (errors of 3000 %); the
    // curvature noise falls as l^(-5/2): 110 % at 2 mm, 18 % at 4 mm, 2.5 %
    // at 8 mm.
    let raw = p.spline(&SplineOptions::interpolating()).unwrap();
    let smooth = p.spline(&SplineOptions::smoothing(8e-3)).unwrap();
    let e_raw = curvature_error(&raw, 1.0 / r, 0.6);
    let e_smooth = curvature_error(&smooth, 1.0 / r, 0.6);
    assert!(e_raw > 5.0, "interpolated noise should show: {e_raw}");
    assert!(e_smooth < 0.05, "smoothed curvature error {e_smooth}");
    // The smoothed curve lies closer to the true circle than the data.
    let l = smooth.length_m();
    let dev = (0..=200)
        .map(|i| {
            let q = smooth.position(l * (0.2 + 0.6 * i as f64 / 200.0));
            (q[0].hypot(q[1] - r) - r).abs()
        })
        .fold(0.0, f64::max);
    assert!(dev < 2e-6, "max deviation from the circle {dev}");
}

#[test]
fn straight_line_has_zero_curvature() {
    // Unevenly spaced points on a 1:40 line.
    let mut y = -0.03;
    let mut pts = Vec::new();
    let mut seed = 7;
    while y < 0.03 {
        pts.push([y, y / 40.0]);
        y += 0.3e-3 * (1.0 + 0.5 * noise(&mut seed));
    }
    let p =
        Profile::from_points("line", Some(ProfileKind::Rail), &pts, &Default::default()).unwrap();
    for opts in [
        SplineOptions::interpolating(),
        SplineOptions::default(),
        SplineOptions::smoothing(10e-3),
    ] {
        let sp = p.spline(&opts).unwrap();
        let l = sp.length_m();
        for i in 0..=100 {
            let q = sp.eval(l * i as f64 / 100.0);
            assert!(q.curvature_per_m.abs() < 1e-6, "{opts:?}: {q:?}");
            assert!((q.inclination_rad - (1.0f64 / 40.0).atan()).abs() < 1e-9);
            assert!((q.z_m - q.y_m / 40.0).abs() < 1e-12);
        }
    }
}

// ------------------------------------------------------------ malformed

fn expect_err(r: Result<Profile, ProfileError>) -> ProfileError {
    match r {
        Ok(p) => panic!("expected an error, got a profile of {} points", p.len()),
        Err(e) => e,
    }
}

#[test]
fn truncated_simpack_point_block_names_file_and_line() {
    let t = head(&text("MBench_UIC60_v3.prr"), 100);
    let e = expect_err(parse_simpack(&t, "MBench_UIC60_v3.prr"));
    let msg = e.to_string();
    assert!(matches!(e, ProfileError::Format { .. }), "{msg}");
    assert!(
        msg.starts_with("MBench_UIC60_v3.prr line 100: truncated point block"),
        "{msg}"
    );
    assert!(
        msg.contains("opened at line 39") && msg.contains("expected point.end"),
        "{msg}"
    );
}

#[test]
fn bad_numbers_name_file_and_line() {
    // Simpack point block.
    let t = replace_line(&text("circ_r10.prw"), 20, "   9.0  -5.6x");
    let e = expect_err(parse_simpack(&t, "circ_r10.prw"));
    assert_eq!(
        e.to_string(),
        "circ_r10.prw line 20: expected two numbers (y z) or three (y z weight), found '9.0  -5.6x'"
    );
    // MiniProf with ColumnDef X,Y,A,C.
    let t = replace_line(&text("avg_HR.BAN"), 60, "1.0 abc");
    let e = expect_err(parse_miniprof(&t, "avg_HR.BAN"));
    assert_eq!(
        e.to_string(),
        "avg_HR.BAN line 60: expected 4 numbers (ColumnDef X,Y,A,C), found '1.0 abc'"
    );
    // MiniProf text variant, too few columns.
    let t = replace_line(&text("avg_wheel.whl"), 30, "12.5");
    let e = expect_err(parse_miniprof(&t, "avg_wheel.whl"));
    assert_eq!(
        e.to_string(),
        "avg_wheel.whl line 30: expected two numbers (X Y), found '12.5'"
    );
    // Plain.
    let e = expect_err(parse_plain("# y z\n0 0\n0.001 abc\n", "p.csv"));
    assert_eq!(
        e.to_string(),
        "p.csv line 3: expected two numbers (y z), found '0.001 abc'"
    );
    // A bad value of a Simpack key.
    let t = text("MBench_S1002_v3.prw");
    let l = line_of(&t, "mirror.y");
    let t = replace_line(&t, l, "    mirror.y = 2");
    let e = expect_err(parse_simpack(&t, "MBench_S1002_v3.prw"));
    assert_eq!(
        e.to_string(),
        format!("MBench_S1002_v3.prw line {l}: expected 0 or 1 for `mirror.y`, found '2'")
    );
}

#[test]
fn missing_headers_are_errors() {
    // Simpack without its header block.
    let t: String = text("circ_r100.prr")
        .lines()
        .skip(4)
        .collect::<Vec<_>>()
        .join("\n");
    let e = expect_err(parse_simpack(&t, "circ_r100.prr"));
    let msg = e.to_string();
    assert!(
        msg.starts_with("circ_r100.prr line 1: missing header"),
        "{msg}"
    );
    // MiniProf without a header.
    let e = expect_err(parse_miniprof("1.0 2.0\n1.1 2.1\n", "bare.ban"));
    let msg = e.to_string();
    assert!(msg.starts_with("bare.ban line 1: missing header"), "{msg}");
    // Empty file.
    let e = expect_err(parse_simpack("", "empty.prr"));
    assert!(e.to_string().contains("missing header"), "{e}");
}

#[test]
fn backtracking_points_are_errors() {
    // Move one point of the rail crown 3 mm back: line 200 has y = -81 mm,
    // line 201 gets y = -84 mm (on the circle).
    let t = text("circ_r100.prr");
    assert!(t.lines().nth(199).unwrap().contains("-81.000000"));
    let t = replace_line(&t, 201, "    -84.000000   45.741");
    let e = expect_err(parse_simpack(&t, "circ_r100.prr"));
    let msg = e.to_string();
    assert!(
        matches!(
            e,
            ProfileError::Check {
                kind: CheckKind::Backtracking,
                ..
            }
        ),
        "{msg}"
    );
    assert!(msg.starts_with("circ_r100.prr line 201: point"), "{msg}");
    assert!(
        msg.contains("goes back") && msg.contains("line 200"),
        "{msg}"
    );
}

#[test]
fn other_checks_name_the_line() {
    // A gap: 40 points (4 mm of y, more along the steep flank) missing.
    let t = text("circ_r100.prr");
    let cut: String = t
        .lines()
        .enumerate()
        .filter(|(i, _)| !(100..140).contains(i))
        .map(|(_, l)| l)
        .collect::<Vec<_>>()
        .join("\n");
    let e = expect_err(parse_simpack(&cut, "circ_r100.prr"));
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
    assert!(
        e.to_string().starts_with("circ_r100.prr line 101: gap of"),
        "{e}"
    );
    // A spike of 3 mm in a plain file in mm.
    let mut s = String::from("# unit: mm\n");
    for i in 0..30 {
        let z = if i == 15 { -3.0 } else { 0.0 };
        s.push_str(&format!("{}, {}\n", i as f64 * 0.2, z));
    }
    let e = expect_err(parse_plain(&s, "spike.csv"));
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
    assert!(e.to_string().starts_with("spike.csv line 17: spike"), "{e}");
    // A rail file whose header says wheel.
    let t = text("circ_r10.prw");
    let e = expect_err(parse_simpack(&t, "circ_r10.prr"));
    assert_eq!(
        e.location().map(|l| l.to_string()),
        Some("circ_r10.prr line 3".to_string())
    );
    // MiniProf file shorter than XYPoints says.
    let t = head(&text("avg_HR.BAN"), 150);
    let e = expect_err(parse_miniprof(&t, "avg_HR.BAN"));
    let msg = e.to_string();
    assert!(
        msg.contains("truncated data: XYPoints = 147") && msg.contains("line 150"),
        "{msg}"
    );
    // mm data read as metres.
    let e = expect_err(parse_plain("0 0\n10 1\n20 3\n", "mm.txt"));
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
    // Key lines after the data in MiniProf.
    let t = format!("{}\nXOffset=1.0\n", text("avg_HR.BAN").trim_end());
    let e = expect_err(parse_miniprof(&t, "avg_HR.BAN"));
    assert!(e.to_string().contains("after the data started"), "{e}");
    // Missing file.
    let e = expect_err(load_profile(path("no_such_profile.prr")));
    assert!(matches!(e, ProfileError::Io { .. }));
    assert!(e.to_string().contains("no_such_profile.prr"));
}

// ------------------------------------------------------------ formats

#[test]
fn plain_format_separators_units_and_headers() {
    let m =
        "# a rail crown\n# unit: mm\n-1.0, 0.01\n-0.5;0.0025\n0\t0\n0.5 0.0025\n1.0 , 0.01 # c\n";
    let p = parse_plain(m, "crown.txt").unwrap();
    assert_eq!(p.len(), 5);
    assert_eq!(p.format(), Some(ProfileFormat::Plain));
    assert_eq!(p.kind(), None);
    assert!((p.points()[0][0] + 0.001).abs() < 1e-15);
    let h = parse_plain("y_mm,z_mm\n0,0\n1,0.1\n2,0.3\n", "h.csv").unwrap();
    assert!((h.points()[2][0] - 0.002).abs() < 1e-15);
    let metres = parse_plain("y [m]; z [m]\n0;0\n0.001;0.0001\n", "m.csv").unwrap();
    assert!((metres.points()[1][1] - 0.0001).abs() < 1e-15);
    let e = expect_err(parse_plain("# unit: mm\ny_m z_m\n0 0\n1 1\n", "c.csv"));
    assert!(e.to_string().contains("line 2"), "{e}");
    // The option overrides the file.
    let opts = LoadOptions {
        plain_unit: Some(LengthUnit::Millimetre),
        kind: Some(ProfileKind::Wheel),
        ..LoadOptions::default()
    };
    let p = parse_profile("0 0\n1 0.1\n2 0.3\n", "w.dat", &opts).unwrap();
    assert_eq!(p.kind(), Some(ProfileKind::Wheel));
    let first = p.points()[0];
    assert!((first[0] - 0.002).abs() < 1e-15 && (first[1] - 0.0003).abs() < 1e-15);
}

#[test]
fn simpack_keys_are_applied_in_order() {
    let body = "header.begin\n version = 1\n type = 0\nheader.end\nspline.begin\n \
                comment = 'test ! not a comment'\n shift.y = 1.0\n shift.z = -0.5\n \
                mirror.y = 1\n inversion = 1\n units.len.f = 1000.\n \
                bound.y.min = -3.0 ! keep y in [-3, 10]\n bound.y.max = 10.0\n point.begin\n \
                ! y z weight\n  5.0 1.0\n  4.0 0.5 2.0\n !3.0 0.0\n  3.0 0.25\n  \
                2.0 0.0D0\n  -9.0 3.0\npoint.end\nspline.end\n! end\n";
    let p = parse_simpack(body, "t.prr").unwrap();
    assert_eq!(p.description(), Some("test ! not a comment"));
    // shift (user units), bounds (y + 1 in [-3, 10] drops -9), mirror y,
    // invert, then mm -> m; a rail ends with increasing y.
    let ys: Vec<f64> = p.points().iter().map(|q| q[0] * 1e3).collect();
    let zs: Vec<f64> = p.points().iter().map(|q| q[1] * 1e3).collect();
    let close = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-9);
    assert!(close(&ys, &[-6.0, -5.0, -4.0, -3.0]), "{ys:?}");
    assert!(close(&zs, &[0.5, 0.0, -0.25, -0.5]), "{zs:?}");
    assert_eq!(p.weights(), &[1.0, 2.0, 1.0, 1.0]);
    assert_eq!(p.source_lines()[1], Some(17));
    assert!(p.warnings().iter().any(|w| w.message.contains("bound.y")));
    // Content sniffing picks Simpack for a .txt file.
    let dir = std::env::temp_dir().join(format!("railcontact_profiles_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let f = dir.join("rail_profile.txt");
    std::fs::write(&f, body).unwrap();
    let q = load_profile(&f).unwrap();
    assert_eq!(q.format(), Some(ProfileFormat::Simpack));
    assert_eq!(q.kind(), Some(ProfileKind::Rail));
    assert_eq!(q.points(), p.points());
    std::fs::remove_dir_all(&dir).ok();
    // rotate is not supported.
    let r = body.replace("shift.y = 1.0", "rotate = 0.1");
    let e = expect_err(parse_simpack(&r, "t.prr"));
    assert_eq!(e.location().unwrap().line, Some(7), "{e}");
}
