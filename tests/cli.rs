//! End-to-end tests of `railcontact solve`: the built binary on the example
//! cases (grids <= 32 x 32) and on bad input.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use serde_json::Value;

const BIN: &str = env!("CARGO_BIN_EXE_railcontact");

/// Keys every `--json` report has at top level (and per transient step).
const KEYS: [&str; 16] = [
    "model",
    "normal_force_n",
    "fx_n",
    "fy_n",
    "mz_nm",
    "approach_m",
    "max_pressure_pa",
    "max_traction_pa",
    "contact_area_m2",
    "patch_length_m",
    "patch_width_m",
    "adhesion_fraction",
    "tgamma_n",
    "iterations",
    "solve_time_s",
    "status",
];

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples/cases")
        .join(name)
}

fn example_text(name: &str) -> String {
    std::fs::read_to_string(example(name)).unwrap()
}

/// Writes `text` to a fresh file in the test temp dir.
fn case_file(name: &str, text: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("cli-cases");
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

fn run(args: &[&str]) -> Output {
    Command::new(BIN)
        .args(args)
        .output()
        .expect("run railcontact")
}

/// Runs `solve CASE --json [extra]`, checks success and one JSON object.
fn solve_json(case: &Path, extra: &[&str]) -> Value {
    let mut args = vec!["solve", case.to_str().unwrap(), "--json"];
    args.extend_from_slice(extra);
    let out = run(&args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{case:?} failed: {stderr}");
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert_eq!(
        stdout.trim().lines().count(),
        1,
        "exactly one JSON line: {stdout}"
    );
    let v: Value = serde_json::from_str(stdout.trim()).unwrap();
    assert!(v.is_object());
    check_keys(&v);
    v
}

fn check_keys(v: &Value) {
    for k in KEYS {
        if k == "model" && v.get("model").is_none() {
            continue; // per-step entries carry no model
        }
        assert!(v.get(k).is_some(), "key {k} missing in {v}");
    }
    for k in KEYS.iter().filter(|&&k| k != "model" && k != "status") {
        assert!(
            v[k].as_f64().unwrap().is_finite(),
            "{k} not a finite number"
        );
    }
}

fn f(v: &Value, k: &str) -> f64 {
    v[k].as_f64()
        .unwrap_or_else(|| panic!("{k} not a number in {v}"))
}

/// Hertz circle (A = B = 1/m, F = 10 kN, steel): closed-form values.
fn hertz_circle_reference() -> (f64, f64, f64) {
    let e_star = 81.0e9 / (1.0 - 0.30);
    let r = 0.5;
    let force: f64 = 10000.0;
    let a = (3.0 * force * r / (4.0 * e_star)).cbrt();
    let p0 = 3.0 * force / (2.0 * std::f64::consts::PI * a * a);
    (a, p0, a * a / r)
}

#[test]
fn hertz_circle_matches_closed_form() {
    let v = solve_json(&example("hertz_circle.toml"), &[]);
    let (a, p0, delta) = hertz_circle_reference();
    assert_eq!(v["model"], "exact");
    assert_eq!(v["status"], "converged");
    assert!((f(&v, "max_pressure_pa") / p0 - 1.0).abs() < 0.02, "p0 {v}");
    assert!(
        (f(&v, "approach_m") / delta - 1.0).abs() < 0.02,
        "delta {v}"
    );
    assert!((f(&v, "normal_force_n") / 1e4 - 1.0).abs() < 1e-9);
    let area = f(&v, "contact_area_m2") / (std::f64::consts::PI * a * a);
    assert!((area - 1.0).abs() < 0.1, "area ratio {area}");
    assert_eq!(f(&v, "fx_n"), 0.0);
    assert!(v.get("fields").is_none(), "no fields without --fields");
    assert!(v.get("steps").is_none());
}

#[test]
fn fields_have_the_grid_size() {
    let v = solve_json(&example("hertz_circle.toml"), &["--fields"]);
    let fl = &v["fields"];
    let n = (fl["nx"].as_u64().unwrap() * fl["ny"].as_u64().unwrap()) as usize;
    for k in [
        "pressure_pa",
        "traction_x_pa",
        "traction_y_pa",
        "slip_x",
        "slip_y",
        "state",
    ] {
        assert_eq!(fl[k].as_array().unwrap().len(), n, "{k}");
    }
    for k in ["dx_m", "dy_m", "x0_m", "y0_m"] {
        assert!(fl[k].as_f64().is_some(), "{k}");
    }
    let sum: f64 = fl["pressure_pa"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p.as_f64().unwrap())
        .sum();
    let force = sum * f(fl, "dx_m") * f(fl, "dy_m");
    assert!((force / 1e4 - 1.0).abs() < 1e-6);
}

#[test]
fn steady_rolling_forces_oppose_creepage() {
    // The example's 40 x 40 grid, reduced for test time.
    let text = example_text("hertz_ellipse_rolling.toml")
        .replace("nx = 24", "nx = 16")
        .replace("ny = 24", "ny = 16");
    assert!(text.contains("nx = 16") && text.contains("ny = 16"));
    let v = solve_json(&case_file("rolling16.toml", &text), &[]);
    let mu_fn = 0.3 * f(&v, "normal_force_n");
    let (fx, fy) = (f(&v, "fx_n"), f(&v, "fy_n"));
    assert!(fx < 0.0, "creepage_long > 0 gives Fx < 0: {fx}");
    assert!(fy < 0.0, "creepage_lat > 0 gives Fy < 0: {fy}");
    assert!(fx.hypot(fy) <= mu_fn * 1.001, "|F| <= mu Fn");
    let adh = f(&v, "adhesion_fraction");
    assert!(adh > 0.0 && adh < 1.0, "partial slip: {adh}");
    assert!(f(&v, "tgamma_n") > 0.0);
    // Patch aspect ratio a/b about 0.5.
    let ratio = f(&v, "patch_length_m") / f(&v, "patch_width_m");
    assert!(ratio > 0.35 && ratio < 0.65, "a/b {ratio}");
}

#[test]
fn transient_shift_follows_cattaneo() {
    let v = solve_json(&example("transient_shift.toml"), &[]);
    let steps = v["steps"].as_array().unwrap();
    assert_eq!(steps.len(), 5);
    let mut last_fx = 0.0;
    let mut iterations = 0;
    for s in steps {
        check_keys(s);
        let fx = f(s, "fx_n");
        assert!(
            fx < last_fx,
            "|Fx| grows with the shift: {fx} after {last_fx}"
        );
        assert!(fx > -0.3 * 1e4 * 1.001);
        last_fx = fx;
        iterations += s["iterations"].as_u64().unwrap();
    }
    assert_eq!(f(&v, "fx_n"), last_fx, "top level = last step");
    assert_eq!(
        v["iterations"].as_u64().unwrap(),
        iterations,
        "top level iterations = total"
    );
    // Cattaneo–Mindlin: Fx = -mu Fn (1 - (1 - d/d*)^(3/2)), d* = 3 mu Fn (2 - nu)/(8 G a) (identical bodies).
    let (a, _, _) = hertz_circle_reference();
    let d_star = 3.0 * 0.3 * 1e4 * (2.0 - 0.3) / (8.0 * 81.0e9 * a);
    let shift: f64 = 5.0 * 1.0e-6;
    let expected = -0.3 * 1e4 * (1.0 - (1.0 - shift / d_star).powf(1.5));
    assert!(
        (last_fx / expected - 1.0).abs() < 0.05,
        "Fx {last_fx} vs Cattaneo {expected}"
    );
}

#[test]
fn fastsim_example_runs() {
    let v = solve_json(&example("fastsim_ellipse.toml"), &[]);
    assert_eq!(v["model"], "fastsim");
    assert!(f(&v, "fx_n") < 0.0 && f(&v, "fy_n") < 0.0);
    assert!(f(&v, "fx_n").hypot(f(&v, "fy_n")) <= 0.3 * 1e4 * 1.001);
    assert!(f(&v, "max_traction_pa") > 0.0);
}

#[test]
fn hertz_only_example_is_consistent() {
    let v = solve_json(&example("hertz_only.toml"), &[]);
    assert_eq!(v["model"], "hertz");
    let (a, b) = (f(&v, "patch_length_m") / 2.0, f(&v, "patch_width_m") / 2.0);
    // A = 0.6 < B = 1.4: the long axis lies along x.
    assert!(a > b);
    assert!((f(&v, "contact_area_m2") / (std::f64::consts::PI * a * b) - 1.0).abs() < 1e-9);
    let p0 = 1.5 * f(&v, "normal_force_n") / f(&v, "contact_area_m2");
    assert!((f(&v, "max_pressure_pa") / p0 - 1.0).abs() < 1e-9);
    assert_eq!(f(&v, "fx_n"), 0.0);
    assert!(v["notes"]
        .as_array()
        .unwrap()
        .iter()
        .any(|n| n.as_str().unwrap().contains("not computed")));
}

#[test]
fn plots_are_written() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"));
    for name in ["transient.png", "transient.svg"] {
        let p = dir.join(name);
        let _ = std::fs::remove_file(&p);
        let out = run(&[
            "solve",
            example("transient_shift.toml").to_str().unwrap(),
            "--plot",
            p.to_str().unwrap(),
        ]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let bytes = std::fs::read(&p).unwrap();
        if name.ends_with(".png") {
            assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
        } else {
            let s = String::from_utf8(bytes).unwrap();
            assert!(s.contains("<svg") && s.contains("centre line"));
        }
    }
}

#[test]
fn human_summary_has_units() {
    let out = run(&["solve", example("hertz_circle.toml").to_str().unwrap()]);
    assert!(out.status.success());
    let s = String::from_utf8(out.stdout).unwrap();
    for label in ["[N]", "[MPa]", "[mm]", "[mm²]", "converged"] {
        assert!(s.contains(label), "{label} in {s}");
    }
}

#[test]
fn help_documents_the_options() {
    let out = run(&["--help"]);
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stdout).contains("solve"));
    let out = run(&["solve", "--help"]);
    assert!(out.status.success());
    let s = String::from_utf8_lossy(&out.stdout);
    for opt in ["--json", "--fields", "--plot", "CASE.toml"] {
        assert!(s.contains(opt), "{opt} in {s}");
    }
}

/// Runs a bad case and checks exit code 2 and that stderr names `key`.
fn expect_bad(name: &str, text: &str, key: &str) {
    let p = case_file(name, text);
    let out = run(&["solve", p.to_str().unwrap(), "--json"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(
        out.status.code(),
        Some(2),
        "{name}: exit code, stderr {stderr}"
    );
    assert!(
        stderr.contains(key),
        "{name}: stderr should name `{key}`: {stderr}"
    );
    assert!(out.stdout.is_empty(), "{name}: nothing on stdout");
}

fn circle() -> String {
    example_text("hertz_circle.toml")
}

#[test]
fn unknown_key_is_rejected() {
    expect_bad(
        "unknown.toml",
        &circle().replace("ny = 32", "ny = 32\nnz = 4"),
        "nz",
    );
    expect_bad(
        "unknown_top.toml",
        &format!("modle = \"exact\"\n{}", circle()),
        "modle",
    );
}

#[test]
fn negative_force_is_rejected() {
    expect_bad(
        "negative.toml",
        &circle().replace("normal_force_n = 10000.0", "normal_force_n = -1.0"),
        "load.normal_force_n",
    );
}

#[test]
fn nan_is_rejected() {
    expect_bad(
        "nan.toml",
        &circle().replace("poisson_ratio = 0.30", "poisson_ratio = nan"),
        "material.poisson_ratio",
    );
    let rolling =
        example_text("transient_shift.toml").replace("coefficient = 0.30", "coefficient = nan");
    expect_bad("nan_mu.toml", &rolling, "friction.coefficient");
}

#[test]
fn force_and_approach_together_are_rejected() {
    let text = circle().replace(
        "normal_force_n = 10000.0",
        "normal_force_n = 10000.0\napproach_m = 2.0e-5",
    );
    expect_bad("both.toml", &text, "load.approach_m");
}

#[test]
fn missing_key_is_rejected() {
    expect_bad(
        "missing.toml",
        &circle().replace("b_per_m = 1.0", ""),
        "b_per_m",
    );
    expect_bad(
        "noload.toml",
        &circle().replace("normal_force_n = 10000.0", ""),
        "load.normal_force_n",
    );
}

#[test]
fn tiny_window_is_rejected() {
    let text = circle().replace(
        "ny = 32",
        "ny = 32\nwindow_x_m = 1.0e-4\nwindow_y_m = 1.0e-4",
    );
    expect_bad("tiny.toml", &text, "grid.window_x_m");
}

#[test]
fn inconsistent_sections_are_rejected() {
    let mixed = circle().replace(
        "poisson_ratio = 0.30",
        "poisson_ratio = 0.30\n[material.body1]\nshear_modulus_pa = 1e9\npoisson_ratio = 0.3",
    );
    expect_bad("mixed_material.toml", &mixed, "material");
    let both = format!(
        "{}\n[rolling]\ncreepage_long = 0.001\n",
        example_text("transient_shift.toml")
    );
    expect_bad("rolling_and_transient.toml", &both, "transient");
    let no_friction =
        example_text("transient_shift.toml").replace("[friction]\ncoefficient = 0.30", "");
    expect_bad("no_friction.toml", &no_friction, "friction.coefficient");
}

#[test]
fn bad_plot_extension_is_rejected() {
    let out = run(&[
        "solve",
        example("hertz_circle.toml").to_str().unwrap(),
        "--plot",
        "out.jpg",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--plot"));
}
