//! End-to-end tests of the command line: `railcontact solve` and
//! `wheelrail` (the built binary on the example cases, grids <= 32 x 32, and
//! on bad input), the flags and logs of `serve`.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use serde_json::Value;

use crate::support;

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
fn transient_rolling_example_holds_contacts_force() {
    // The example is CONTACT's catt_to_cart cases 1-9 (github.com/eve70a/
    // CONTACT, examples/catt_to_cart.inp and .ref_out, commit 424e4e6): at
    // the shift and creepages CONTACT found, Fx = -0.657 mu Fn in every
    // step, and 305 (case 1) then 422 (case 2) of the 621 contact elements
    // adhere ("Tang: final element division: A, S=").
    let v = solve_json(&example("transient_rolling.toml"), &[]);
    let steps = v["steps"].as_array().unwrap();
    assert_eq!(steps.len(), 9);
    for (k, s) in steps.iter().enumerate() {
        check_keys(s);
        let ratio = f(s, "fx_n") / (0.4013 * f(s, "normal_force_n"));
        assert!(
            (ratio / -0.657 - 1.0).abs() < 0.01,
            "case {}: Fx/(mu Fn) {ratio}",
            k + 1
        );
    }
    for (k, adhesion) in [(0, 305.0), (1, 422.0)] {
        let got = f(&steps[k], "adhesion_fraction") * 621.0;
        assert!((got - adhesion).abs() < 0.5, "case {}: {got}", k + 1);
    }
}

#[test]
fn fastsim_example_runs() {
    let v = solve_json(&example("fastsim_ellipse.toml"), &[]);
    assert_eq!(v["model"], "fastsim");
    assert!(f(&v, "fx_n") < 0.0 && f(&v, "fy_n") < 0.0);
    assert!(f(&v, "fx_n").hypot(f(&v, "fy_n")) <= 0.3 * 1e4 * 1.001);
    assert!(f(&v, "max_traction_pa") > 0.0);
    // The reported maximum pressure is Hertz's p0 = 3 Fn / (2 pi a b), and
    // the notes say so (FASTSIM's parabolic bound peaks at 4/3 p0).
    let (a, b) = (f(&v, "patch_length_m") / 2.0, f(&v, "patch_width_m") / 2.0);
    let p0 = 3.0 * f(&v, "normal_force_n") / (2.0 * std::f64::consts::PI * a * b);
    assert!((f(&v, "max_pressure_pa") / p0 - 1.0).abs() < 1e-12, "{v}");
    assert!(v["notes"].to_string().contains("4/3 p0"), "{}", v["notes"]);
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

#[test]
fn no_help_shows_rustdoc_escapes() {
    for command in ["solve", "wheelrail", "serve", "loadtest", "health"] {
        let out = run(&[command, "--help"]);
        assert!(out.status.success(), "{command} --help");
        let s = String::from_utf8_lossy(&out.stdout);
        assert!(!s.contains('\\'), "{command} --help:\n{s}");
    }
}

#[test]
fn serve_help_lists_every_settings_key_and_its_variable() {
    let keys = railcontact::service::command::settings_keys();
    assert!(keys.contains(&"data_dir") && keys.contains(&"kernel_cache_max_bytes"));
    let out = run(&["serve", "--help"]);
    assert!(out.status.success());
    let s = String::from_utf8_lossy(&out.stdout);
    for key in keys {
        let var = railcontact::service::command::env_var(key);
        assert!(
            s.lines()
                .any(|l| l.split_whitespace().eq([*key, var.as_str()])),
            "no line `{key} {var}` in\n{s}"
        );
    }
    assert!(s.contains("deploy/serve.toml"), "{s}");
}

#[test]
fn the_sample_settings_file_names_every_key_at_its_default() {
    use railcontact::service::config::{ServeConfig, ServeFlags};
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("deploy/serve.toml");
    let loaded = ServeConfig::load(Some(&path), &|_| None, &ServeFlags::default())
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(loaded, ServeConfig::default());
    let text = std::fs::read_to_string(&path).unwrap();
    for key in railcontact::service::command::settings_keys() {
        // Set, or shown commented out where the default is "not set".
        let set = format!("{key} = ");
        assert!(
            text.lines().any(|l| l.starts_with(&set)
                || l.strip_prefix("# ").is_some_and(|l| l.starts_with(&set))),
            "deploy/serve.toml has no line for `{key}`"
        );
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
fn model_names_are_read_in_any_case() {
    let lower = solve_json(&example("hertz_circle.toml"), &[]);
    let upper = case_file(
        "upper_model.toml",
        &circle().replace("model = \"exact\"", "model = \"EXACT\""),
    );
    assert_ne!(circle(), std::fs::read_to_string(&upper).unwrap());
    let v = solve_json(&upper, &[]);
    assert_eq!(v["model"], "exact");
    assert_eq!(v["normal_force_n"], lower["normal_force_n"]);
    assert_eq!(v["max_pressure_pa"], lower["max_pressure_pa"]);
    // An unknown name lists the known ones.
    expect_bad(
        "unknown_model.toml",
        &circle().replace("model = \"exact\"", "model = \"exakt\""),
        "expected one of hertz, hertz_corrected, fastsim, exact, cect, cect_halfspace",
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

/// The three values out of range in a wheelset case: each named
/// with the file, key and value (and the likely millimetres), as the
/// service names them (one check: `wheelrail::ranges`), exit code 2.
#[test]
fn wheelset_values_out_of_range_name_file_key_and_value() {
    for (from, to, needle) in [
        (
            "lateral_m = 0.0065",
            "lateral_m = 6.5",
            "`position.lateral_m`: must be in [-0.02, 0.02] m, got 6.5 (this looks like millimetres: did you mean 0.0065 m?)",
        ),
        (
            "nominal_radius_m = 0.460",
            "nominal_radius_m = 460",
            "`wheelset.nominal_radius_m`: must be in [0.05, 2] m, got 460 (this looks like millimetres: did you mean 0.46 m?)",
        ),
        (
            "roll_rad = -0.004376",
            "roll_rad = -0.25",
            "`position.roll_rad`: must be in [-0.05, 0.05] rad, got -0.25",
        ),
    ] {
        let text = example_text("wheelset_a22.toml");
        assert!(text.contains(from), "{from}");
        let case = case_file("out_of_range.toml", &text.replace(from, to));
        let out = run(&["wheelrail", case.to_str().unwrap()]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{to}: {stderr}");
        assert!(
            stderr.contains(case.to_str().unwrap()) && stderr.contains(needle),
            "{to}: {stderr}"
        );
    }
}

/// Profile-format mistakes are named with their likely cause: a wheel
/// file as the rail, a rail file as the wheel, a MiniProf rail measured
/// from the gauge side without `rail_mirror_y`.
#[test]
fn profile_mistakes_name_their_likely_cause() {
    let profiles = crate::common::profiles_dir();
    let text = example_text("wheelset_a22.toml")
        .lines()
        .filter(|l| !l.starts_with("roll_rad") && !l.starts_with("pitch_rad_per_s"))
        .collect::<Vec<_>>()
        .join("\n");
    let rail = "rail_profile = \"builtin:MBench_UIC60_v3.prr\"";
    let wheel = "wheel_profile = \"builtin:MBench_S1002_v3.prw\"";
    let file = |name: &str| profiles.join(name).display().to_string();
    for (from, to, needle) in [
        (
            rail,
            format!("rail_profile = \"{}\"", file("MBench_S1002_v3.prw")),
            "track.rail_profile: 'MBench_S1002_v3.prw' is a wheel profile",
        ),
        (
            wheel,
            format!("wheel_profile = \"{}\"", file("MBench_UIC60_v3.prr")),
            "wheelset.wheel_profile: 'MBench_UIC60_v3.prr' is a rail profile",
        ),
        (
            rail,
            format!("rail_profile = \"{}\"", file("avg_HR.BAN")),
            "its gauge face is at +y, as in a MiniProf rail measured from the gauge side",
        ),
    ] {
        assert!(text.contains(from), "{from}");
        let case = case_file("profile_mistake.toml", &text.replace(from, &to));
        let out = run(&["wheelrail", case.to_str().unwrap()]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{to}: {stderr}");
        assert!(stderr.contains(needle), "{to}: {stderr}");
    }
}

/// An output file that cannot be written is refused before the solve
/// (exit 2, naming the option and the path), for `solve` and `wheelrail`;
/// no empty file is left behind by the check.
#[test]
fn unwritable_outputs_are_refused_before_solving() {
    let missing = Path::new(env!("CARGO_TARGET_TMPDIR")).join("no-such-dir/plot.png");
    for (command, case, flag) in [
        ("solve", "hertz_circle.toml", "--plot"),
        ("solve", "subsurface_rolling.toml", "--subsurface-csv"),
        ("wheelrail", "wheelset_a22.toml", "--plot"),
    ] {
        let out = run(&[
            command,
            example(case).to_str().unwrap(),
            flag,
            missing.to_str().unwrap(),
        ]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{command} {flag}: {stderr}");
        assert!(
            stderr.contains(&format!(
                "invalid option `{flag}`: cannot write {}",
                missing.display()
            )),
            "{command} {flag}: {stderr}"
        );
        assert!(out.stdout.is_empty(), "{command} {flag}: solved anyway");
    }
    // A writable new file passes the check and is written by the run only.
    let fresh = Path::new(env!("CARGO_TARGET_TMPDIR")).join("fresh-plot.png");
    let _ = std::fs::remove_file(&fresh);
    let out = run(&[
        "solve",
        example("hertz_circle.toml").to_str().unwrap(),
        "--plot",
        fresh.to_str().unwrap(),
    ]);
    assert!(out.status.success());
    assert!(std::fs::metadata(&fresh).unwrap().len() > 10_000);
}

// ---------------------------------------------------------------------
// Conformal contact (cect, cect_halfspace, hertz_corrected): paper Case 1
// of Blanco-Lorenzo et al., Tribology International 2018; reference
// numbers as in crates/solver/tests/validation/conformal.rs.

/// Keys every conformal `--json` report has in addition to [`KEYS`].
const CONFORMAL_KEYS: [&str; 7] = [
    "contact_angle_variation_deg",
    "length_width_ratio",
    "normal_force_from_tractions_n",
    "pressure_resultant_n",
    "fy_global_n",
    "fz_global_n",
    "friction_coefficient",
];

fn check_conformal_keys(v: &Value) {
    for k in CONFORMAL_KEYS {
        if k == "friction_coefficient" && v.get("model").is_none() {
            continue; // per-step entries
        }
        assert!(
            v.get(k).and_then(Value::as_f64).is_some_and(f64::is_finite),
            "conformal key {k} missing or not finite in {v}"
        );
    }
    let ratio = f(v, "patch_length_m") / f(v, "patch_width_m");
    if v["model"] != "hertz" && v["model"] != "hertz_corrected" {
        assert!((f(v, "length_width_ratio") / ratio - 1.0).abs() < 1e-12);
    }
}

/// The frictionless Case 1 example with another model and grid.
fn case1_with(model: &str, nx: usize, ny: usize) -> String {
    let text = example_text("conformal_case1_frictionless.toml");
    let out = text
        .replace("model = \"cect\"", &format!("model = \"{model}\""))
        .replacen("nx = 72", &format!("nx = {nx}"), 1)
        .replacen("ny = 94", &format!("ny = {ny}"), 1);
    assert!(out.contains(&format!("nx = {nx}")) && out.contains(&format!("ny = {ny}")));
    out
}

#[test]
fn conformal_frictionless_example_matches_the_paper() {
    let v = solve_json(&example("conformal_case1_frictionless.toml"), &[]);
    check_conformal_keys(&v);
    assert_eq!(v["model"], "cect");
    assert_eq!(v["status"], "converged");
    let fn_ = f(&v, "normal_force_n");
    assert!((fn_ / 80e3 - 1.0).abs() < 1e-9);
    // §3.3: about 88° of contact angle variation at 80 kN (one element is
    // about 1.4° here).
    let var = f(&v, "contact_angle_variation_deg");
    assert!((var - 88.0).abs() < 6.0, "variation {var}");
    assert_eq!(f(&v, "fx_n"), 0.0);
    assert_eq!(f(&v, "mz_nm"), 0.0);
    assert_eq!(f(&v, "normal_force_from_tractions_n"), 0.0);
    assert!((f(&v, "fz_global_n") / fn_ - 1.0).abs() < 1e-9);
    assert!(f(&v, "fy_global_n").abs() < 1e-6 * fn_);
    assert!(v.get("wfric_lateral").is_none() && v.get("steps").is_none());
    assert_eq!(v["grid"], serde_json::json!([72, 94]));

    // Hertz and corrected Hertz (closed form) on the same file: plain Hertz
    // underestimates p0 and overestimates the angle variation; the
    // corrected one is within a few percent above (paper §3.1).
    let hertz = solve_json(
        &case_file("c1_hertz.toml", &case1_with("hertz", 72, 94)),
        &[],
    );
    let corr = solve_json(
        &case_file("c1_hertz_corr.toml", &case1_with("hertz_corrected", 72, 94)),
        &[],
    );
    for h in [&hertz, &corr] {
        check_conformal_keys(h);
        assert!(h.get("grid").is_none());
    }
    assert_eq!(corr["model"], "hertz_corrected");
    let rel = |h: &Value, k: &str| f(h, k) / f(&v, k) - 1.0;
    assert!(rel(&hertz, "max_pressure_pa") < -0.08);
    assert!(rel(&hertz, "contact_angle_variation_deg") > 0.12);
    let (ep, ed) = (rel(&corr, "max_pressure_pa"), rel(&corr, "approach_m"));
    assert!(ep > 0.0 && ep < 0.05, "corrected Hertz p0 error {ep}");
    assert!(ed > 0.0 && ed < 0.05, "corrected Hertz approach error {ed}");
}

#[test]
fn conformal_rolling_example_gives_the_papers_tractive_force() {
    let v = solve_json(&example("conformal_case1_rolling.toml"), &[]);
    check_conformal_keys(&v);
    assert_eq!(v["status"], "converged");
    // Grid of about 0.25 mm, as the reference in crates/solver/tests/validation/conformal.rs.
    let (w, g) = (&v["window_m"], &v["grid"]);
    for k in 0..2 {
        let d = w[k].as_f64().unwrap() / g[k].as_f64().unwrap();
        assert!((d / 2.5e-4 - 1.0).abs() < 0.03, "element size {d}");
    }
    // creepage_long = +0.086 %: the rail is driven backwards relative to
    // the wheel, so the force on the rail is negative (braking sign on the
    // rail, tractive on the wheel) at about 0.65 mu Fn.
    let fn_ = f(&v, "normal_force_n");
    assert!((fn_ / 80e3 - 1.0).abs() < 1e-6);
    let fx = f(&v, "fx_n");
    assert!(fx < 0.0, "fx_n on the rail {fx}");
    let unit = fx.abs() / (0.3 * fn_);
    assert!((0.62..=0.68).contains(&unit), "|Fx|/(mu Fn) = {unit}");
    assert!(f(&v, "fy_n").abs() < 1e-6 * fn_, "laterally symmetric");
    assert_eq!(f(&v, "friction_coefficient"), 0.3);
    let adh = f(&v, "adhesion_fraction");
    assert!(adh > 0.0 && adh < 1.0, "partial slip {adh}");
    assert!(f(&v, "tgamma_n") > 0.0);
    assert!(f(&v, "normal_force_from_tractions_n") > 0.0);
    assert!(v["coupling_iterations"].as_u64().unwrap() >= 1);
    // W_fric(s) on every lateral line, peaking at the sides (Fig. 13).
    let wf = &v["wfric_lateral"];
    let s: Vec<f64> = wf["s_m"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    let wj: Vec<f64> = wf["w_j_per_m2"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert_eq!(s.len(), 94);
    assert_eq!(wj.len(), s.len());
    assert!(s.windows(2).all(|p| p[1] > p[0]));
    let mid = wj.len() / 2;
    let peak = wj.iter().cloned().fold(0.0, f64::max);
    assert!(peak > 0.0 && 0.5 * (wj[mid - 1] + wj[mid]) < 0.3 * peak);
}

#[test]
fn conformal_static_compression_with_fields() {
    let text = format!(
        "{}\n[friction]\ncoefficient = 0.30\n\n[transient]\nsteps = [\n  {{ normal_force_n = 20000.0 }},\n  {{ normal_force_n = 40000.0, shift_x_m = 0.0 }},\n  {{ normal_force_n = 60000.0 }},\n]\n",
        case1_with("cect", 32, 40)
    );
    let v = solve_json(&case_file("c1_static.toml", &text), &["--fields"]);
    check_conformal_keys(&v);
    let steps = v["steps"].as_array().unwrap();
    assert_eq!(steps.len(), 3);
    let mut last = 0.0;
    for (k, s) in steps.iter().enumerate() {
        check_keys(s);
        check_conformal_keys(s);
        let fn_ = f(s, "normal_force_n");
        assert!((fn_ / (20e3 * (k + 1) as f64) - 1.0).abs() < 1e-6);
        assert!(f(s, "approach_m") > last);
        last = f(s, "approach_m");
        // Lateral tractions carry part of the load; no net tangential force.
        assert!(f(s, "normal_force_from_tractions_n") > 0.0);
        assert!(f(s, "fx_n").abs() < 1e-6 * fn_ && f(s, "fy_n").abs() < 1e-6 * fn_);
    }
    assert!(v.get("wfric_lateral").is_none());
    let fl = &v["fields"];
    let (nx, ny) = (
        fl["nx"].as_u64().unwrap() as usize,
        fl["ny"].as_u64().unwrap() as usize,
    );
    assert_eq!((nx, ny), (32, 40));
    for k in [
        "pressure_pa",
        "traction_x_pa",
        "traction_s_pa",
        "slip_x",
        "slip_s",
        "state",
        "gap_m",
    ] {
        assert_eq!(fl[k].as_array().unwrap().len(), nx * ny, "{k}");
    }
    for k in ["delta_rad", "reference_yz_m"] {
        assert_eq!(fl[k].as_array().unwrap().len(), ny, "{k}");
    }
    // delta(s) increases across the patch, antisymmetric about s = 0.
    let d: Vec<f64> = fl["delta_rad"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert!(d.windows(2).all(|p| p[1] > p[0]));
    assert!((d[0] + d[ny - 1]).abs() < 1e-9);
    assert!(fl["state"]
        .as_array()
        .unwrap()
        .iter()
        .any(|s| s == "adhesion"));
}

#[test]
fn conformal_influence_models_and_flattened_exact() {
    let cect = solve_json(
        &case_file("c1_cect32.toml", &case1_with("cect", 32, 40)),
        &[],
    );
    let half = solve_json(
        &case_file("c1_half32.toml", &case1_with("cect_halfspace", 32, 40)),
        &[],
    );
    check_conformal_keys(&half);
    assert_eq!(half["model"], "cect_halfspace");
    // Half-space coefficients: higher max pressure and approach (§3.1).
    assert!(f(&half, "max_pressure_pa") > f(&cect, "max_pressure_pa"));
    assert!(f(&half, "approach_m") > f(&cect, "approach_m"));
    // The planar exact model on the flattened gap is Hertz's problem.
    let exact = solve_json(
        &case_file("c1_exact32.toml", &case1_with("exact", 32, 32)),
        &[],
    );
    let hertz = solve_json(
        &case_file("c1_hertz32.toml", &case1_with("hertz", 32, 32)),
        &[],
    );
    assert_eq!(exact["model"], "exact");
    assert!((f(&exact, "max_pressure_pa") / f(&hertz, "max_pressure_pa") - 1.0).abs() < 0.03);
    assert!(exact["notes"]
        .as_array()
        .unwrap()
        .iter()
        .any(|n| n.as_str().unwrap().contains("flattened")));
}

/// `[[y, z], ...]` of a circular arc through the origin with tangent +y,
/// bending towards +z with curvature `k` [1/m], every `step` m up to
/// +-`half` m of arc.
fn arc_points(k: f64, half: f64, step: f64) -> String {
    let n = (half / step).round() as i64;
    let pts: Vec<String> = (-n..=n)
        .map(|i| {
            let t = i as f64 * step;
            format!("[{:e}, {:e}]", (k * t).sin() / k, (1.0 - (k * t).cos()) / k)
        })
        .collect();
    format!("[{}]", pts.join(", "))
}

/// Case 1 text with the profiles given as points.
fn case1_points(rail: &str, wheel: &str) -> String {
    case1_with("cect", 32, 40).replace(
        "rail_lateral_radius_m = 0.010     # R_yr, convex rail crown\nwheel_lateral_radius_m = -0.0101  # R_yw, concave wheel profile",
        &format!("rail_points_m = {rail}\nwheel_points_m = {wheel}"),
    ).replace("kind = \"conformal_circular\"", "kind = \"conformal_points\"")
}

#[test]
fn conformal_points_reproduce_the_circles() {
    // Circle::rail(R) bends towards +z with curvature 1/R,
    // Circle::wheel(R) with -1/R (a concave wheel bends towards +z too).
    let text = case1_points(
        &arc_points(1.0 / 0.010, 0.016, 2e-4),
        &arc_points(1.0 / 0.0101, 0.016, 2e-4),
    );
    assert!(text.contains("conformal_points") && !text.contains("lateral_radius"));
    let pts = solve_json(&case_file("c1_points.toml", &text), &[]);
    let circ = solve_json(
        &case_file("c1_circ32.toml", &case1_with("cect", 32, 40)),
        &[],
    );
    for k in [
        "max_pressure_pa",
        "approach_m",
        "contact_area_m2",
        "contact_angle_variation_deg",
    ] {
        let e = f(&pts, k) / f(&circ, k) - 1.0;
        assert!(e.abs() < 0.005, "{k}: points vs circles {e}");
    }
}

#[test]
fn conformal_human_summary_has_units() {
    let out = run(&[
        "solve",
        example("conformal_case1_frictionless.toml")
            .to_str()
            .unwrap(),
    ]);
    assert!(out.status.success());
    let s = String::from_utf8(out.stdout).unwrap();
    for label in [
        "CECT",
        "[N]",
        "[MPa]",
        "[mm]",
        "[mm²]",
        "contact angle variation [deg]",
        "length/width ratio",
        "R_yr = 10.0000 mm",
        "converged",
    ] {
        assert!(s.contains(label), "{label} in {s}");
    }
}

#[test]
fn conformal_bad_input_names_the_key() {
    let fr = example_text("conformal_case1_frictionless.toml");
    expect_bad(
        "c_no_rail_radius.toml",
        &fr.replace("rail_lateral_radius_m = 0.010", ""),
        "geometry.rail_lateral_radius_m",
    );
    expect_bad(
        "c_cect_quadratic.toml",
        &circle().replace("model = \"exact\"", "model = \"cect\""),
        "`model`",
    );
    expect_bad(
        "c_corrected_quadratic.toml",
        &circle().replace("model = \"exact\"", "model = \"hertz_corrected\""),
        "`model`",
    );
    let static_steps = |steps: &str| {
        format!("{fr}\n[friction]\ncoefficient = 0.30\n\n[transient]\nsteps = [{steps}]\n")
    };
    expect_bad(
        "c_shifted.toml",
        &static_steps("{ normal_force_n = 1.0e4 }, { normal_force_n = 2.0e4, shift_x_m = 1.0e-6 }"),
        "transient.steps[1].shift_x_m",
    );
    expect_bad(
        "c_rotated.toml",
        &static_steps("{ normal_force_n = 1.0e4, rotation_rad = 1.0e-4 }"),
        "transient.steps[0].rotation_rad",
    );
    expect_bad(
        "c_decreasing.toml",
        &static_steps("{ normal_force_n = 2.0e4 }, { normal_force_n = 1.0e4 }"),
        "transient.steps[1].normal_force_n",
    );
    expect_bad(
        "c_a_per_m.toml",
        &fr.replace(
            "wheel_rolling_radius_m = 0.5",
            "wheel_rolling_radius_m = 0.5\na_per_m = 1.0",
        ),
        "geometry.a_per_m",
    );
    expect_bad(
        "c_not_touching.toml",
        &fr.replace("-0.0101", "-0.0099"),
        "geometry.wheel_lateral_radius_m",
    );
    let rolling = example_text("conformal_case1_rolling.toml");
    expect_bad(
        "c_no_friction.toml",
        &rolling.replace("[friction]\ncoefficient = 0.30", ""),
        "friction.coefficient",
    );
    expect_bad(
        "c_rolling_approach.toml",
        &rolling.replace("normal_force_n = 80000.0", "approach_m = 7.0e-5"),
        "load.approach_m",
    );
    let arc = arc_points(1.0 / 0.010, 0.016, 1e-3);
    let points = case1_points(&arc, &arc_points(1.0 / 0.0101, 0.016, 1e-3));
    expect_bad(
        "c_points_exact.toml",
        &points.replace("model = \"cect\"", "model = \"exact\""),
        "`model`",
    );
    let off_origin = points.replace("[0e0, 0e0]", "[1e-5, 0e0]");
    assert_ne!(off_origin, points);
    expect_bad(
        "c_points_origin.toml",
        &off_origin,
        "geometry.rail_points_m",
    );
}

#[test]
fn conformal_plot_is_rejected() {
    let out = run(&[
        "solve",
        example("conformal_case1_frictionless.toml")
            .to_str()
            .unwrap(),
        "--plot",
        "conformal.png",
    ]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("--plot") && stderr.contains("conformal"),
        "{stderr}"
    );
    assert!(!Path::new("conformal.png").exists());
}

// ------------------------------------------------------------- wheelrail

/// Runs `wheelrail CASE --json`, checks success and one JSON object.
fn wheelrail_json(case: &Path) -> Value {
    let out = run(&["wheelrail", case.to_str().unwrap(), "--json"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{case:?} failed: {stderr}");
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert_eq!(stdout.trim().lines().count(), 1, "one JSON line: {stdout}");
    serde_json::from_str(stdout.trim()).unwrap()
}

#[test]
fn wheelrail_model_and_side_names_are_read_in_any_case() {
    let text = example_text("wheelset_a22.toml")
        .replace("model = \"exact\"", "model = \"Hertz_FASTSIM\"")
        .replace("side = \"both\"", "side = \"LEFT\"");
    assert!(text.contains("Hertz_FASTSIM") && text.contains("LEFT"));
    let v = wheelrail_json(&case_file("wheelset_upper.toml", &text));
    assert_eq!(v["model"], "hertz_fastsim", "{v}");
    assert!(v["wheels"]["left"].is_object(), "{v}");
    assert!(v["wheels"]["right"].is_null(), "{v}");
}

#[test]
fn wheelrail_example_reports_every_wheel_and_patch() {
    let v = wheelrail_json(&example("wheelset_a22.toml"));
    for side in ["left", "right"] {
        let w = &v["wheels"][side];
        let fz = w["force_track_n"][2].as_f64().unwrap();
        assert!((fz - 10_000.0).abs() < 0.1, "{side}: Fz {fz}");
        let patches = w["patches"].as_array().unwrap();
        assert_eq!(patches.len(), 1, "{side}");
        for k in [
            "normal_force_n",
            "fx_n",
            "fs_n",
            "contact_angle_rad",
            "rail_y_m",
            "rail_z_m",
            "creepage_long",
            "creepage_lat",
            "spin_per_m",
            "max_pressure_pa",
        ] {
            assert!(patches[0][k].is_number(), "{side} patch: key {k}");
        }
    }
    // Shift 6.5 mm to the right: flange contact on the right wheel (CONTACT:
    // contact angle 1.159 rad, mbench_a22_right.ref_out case 14).
    let delta = f(&v["wheels"]["right"]["patches"][0], "contact_angle_rad");
    assert!((delta - 1.159).abs() < 0.01, "right contact angle {delta}");
}

/// `wheelset_a22_reversing.toml` is `wheelset_a22.toml` mirrored along
/// the track (rolling backwards): per wheel the same vertical and lateral
/// forces on the rail and Fx of opposite sign, per patch the same normal
/// force and contact angle, x and the longitudinal creepage of opposite
/// sign, rolling direction pi against 0; to 1e-6 of the wheel's load (the
/// solver's mirror image is within 1.5e-10 of it on at 6 mm,
/// crates/solver/tests/validation/wheelrail_backward.rs).
#[test]
fn wheelrail_reversing_example_is_the_mirror_image_of_a22() {
    let a = wheelrail_json(&example("wheelset_a22.toml"));
    let b = wheelrail_json(&example("wheelset_a22_reversing.toml"));
    let tol = 1e-6 * 1e4;
    for side in ["left", "right"] {
        let (wa, wb) = (&a["wheels"][side], &b["wheels"][side]);
        for (k, sign) in [(0, -1.0), (1, 1.0), (2, 1.0)] {
            let (x, y) = (
                wa["force_track_n"][k].as_f64().unwrap(),
                wb["force_track_n"][k].as_f64().unwrap(),
            );
            assert!(
                (x - sign * y).abs() < tol,
                "{side} force {k}: {x} against {y}"
            );
        }
        let (pa, pb) = (&wa["patches"][0], &wb["patches"][0]);
        for (k, sign, t) in [
            ("normal_force_n", 1.0, tol),
            ("fx_n", -1.0, tol),
            ("fs_n", 1.0, tol),
            ("contact_angle_rad", 1.0, 1e-12),
            ("track_x_m", -1.0, 1e-12),
            ("creepage_long", -1.0, 1e-12),
        ] {
            let (x, y) = (f(pa, k), f(pb, k));
            assert!(
                (x - sign * y).abs() <= t,
                "{side} patch {k}: {x} against {y}"
            );
        }
        assert_eq!(f(pa, "rolling_direction_rad"), 0.0);
        assert_eq!(f(pb, "rolling_direction_rad"), std::f64::consts::PI);
    }
}

#[test]
fn wheelrail_plot_and_summary() {
    let png = Path::new(env!("CARGO_TARGET_TMPDIR")).join("wheelrail.png");
    let _ = std::fs::remove_file(&png);
    let out = run(&[
        "wheelrail",
        example("wheelset_a22.toml").to_str().unwrap(),
        "--plot",
        png.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(std::fs::metadata(&png).unwrap().len() > 10_000);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("right wheel: 1 patch(es)"), "{text}");
    assert!(text.contains("Fz 10000.0 N"), "{text}");
    for label in [
        "xi ",
        "[-], eta ",
        "[-], phi ",
        "[1/m]",
        "track frame",
        "mirrored for the left wheel",
    ] {
        assert!(text.contains(label), "{label:?} in {text}");
    }
    assert!(
        text.contains(&format!("plot written to {}", png.display())),
        "{text}"
    );
}

/// `wheelset_a22.toml` with issue 43's measured profiles in place of
/// S1002 on UIC60 (`crates/solver/profiles`: the MiniProf rail measured
/// from the gauge side, mirrored, and `wheel`), the flange back at the
/// MiniProf wheel's smallest y; the benchmark's roll and pitch rate kept.
fn measured_a22(wheel: &str) -> String {
    let profiles = Path::new(env!("CARGO_MANIFEST_DIR")).join("crates/solver/profiles");
    let text = example_text("wheelset_a22.toml")
        .replace(
            "rail_profile = \"builtin:MBench_UIC60_v3.prr\"",
            &format!(
                "rail_profile = {:?}\nrail_mirror_y = true",
                profiles.join("avg_HR.BAN")
            ),
        )
        .replace(
            "wheel_profile = \"builtin:MBench_S1002_v3.prw\"",
            &format!("wheel_profile = {:?}", profiles.join(wheel)),
        )
        .replace("flange_back_y_m = -0.070\n", "");
    assert!(
        text.contains("avg_HR.BAN") && text.contains(wheel) && !text.contains("flange_back_y_m =")
    );
    text
}

/// The `warning: ` lines of stderr.
fn warning_lines(stderr: &[u8]) -> Vec<String> {
    String::from_utf8_lossy(stderr)
        .lines()
        .filter(|l| l.starts_with("warning: "))
        .map(str::to_string)
        .collect()
}

#[test]
fn the_wheelrail_summary_names_fastsims_traction_bound_peak() {
    // Model hertz_fastsim: each patch's pmax is Hertz's p0, and the line
    // names the peak of FASTSIM's parabolic traction bound, 4/3 p0, the
    // JSON's fastsim_max_pressure_pa.
    let text =
        example_text("wheelset_a22.toml").replace("model = \"exact\"", "model = \"hertz_fastsim\"");
    let case = case_file("wr_a22_fastsim.toml", &text);
    let out = run(&["wheelrail", case.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let summary = String::from_utf8(out.stdout).unwrap();
    let v = wheelrail_json(&case);
    let patch = &v["wheels"]["left"]["patches"][0];
    let (p0, bound) = (
        f(patch, "max_pressure_pa") * 1e-6,
        f(patch, "fastsim_max_pressure_pa") * 1e-6,
    );
    assert!((bound / p0 - 4.0 / 3.0).abs() < 0.01, "{p0} {bound}");
    let want =
        format!("pmax {p0:.0} MPa (Hertz p0; FASTSIM's traction bound peaks at {bound:.0} MPa)");
    assert!(summary.contains(&want), "{want}\n{summary}");
}

#[test]
fn wheelrail_warns_of_answers_no_elastic_contact_gives_naming_the_key() {
    // Issue 43: the example's roll and pitch rate (CONTACT's for S1002 on
    // UIC60) on measured profiles: the right wheel pressed 5.6 mm into its
    // rail at 10 kN, both wheels' Fx the same way. Exit 0, the answer as
    // before, and warnings naming the keys.
    let case = case_file("wr_measured_avg.toml", &measured_a22("avg_wheel.whl"));
    let out = run(&["wheelrail", case.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let summary = String::from_utf8(out.stdout).unwrap();
    assert!(summary.contains("approach 5.6279 mm"), "{summary}");
    assert!(summary.contains("Fx 2310.8 N"), "{summary}");
    let lines = warning_lines(&out.stderr);
    assert_eq!(lines.len(), 2, "{lines:#?}");
    assert!(
        lines[0].starts_with("warning: position.roll_rad: the right wheel is pressed 5.628 mm"),
        "{}",
        lines[0]
    );
    assert!(
        lines[0].contains("Leave position.roll_rad out"),
        "{}",
        lines[0]
    );
    assert!(
        lines[1].starts_with("warning: velocity.pitch_rad_per_s: "),
        "{}",
        lines[1]
    );
    assert!(
        lines[1].contains("set load.total_longitudinal_force_n = 0"),
        "{}",
        lines[1]
    );

    // --json: the same in `warnings`, the stdout one JSON object.
    let out = run(&["wheelrail", case.to_str().unwrap(), "--json"]);
    assert!(out.status.success());
    assert_eq!(warning_lines(&out.stderr), lines);
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    let w = v["warnings"].as_array().unwrap();
    assert_eq!(w.len(), 2, "{v}");
    assert_eq!(
        (&w[0]["kind"], &w[0]["key"], &w[0]["side"]),
        (
            &Value::from("approach"),
            &Value::from("position.roll_rad"),
            &Value::from("right")
        ),
        "{w:?}"
    );
    assert!(
        f(&w[0], "value") > 100.0 && f(&w[0], "limit") == 10.0,
        "{w:?}"
    );
    assert_eq!(
        (&w[1]["kind"], &w[1]["key"], &w[1]["side"]),
        (
            &Value::from("longitudinal_force"),
            &Value::from("velocity.pitch_rad_per_s"),
            &Value::Null
        ),
        "{w:?}"
    );
    assert_eq!(
        format!(
            "warning: {}: {}",
            w[1]["key"].as_str().unwrap(),
            w[1]["message"].as_str().unwrap()
        ),
        lines[1]
    );

    // The other measured wheel: its left wheel hangs above its rail.
    let case = case_file("wr_measured_car.toml", &measured_a22("Car7216_0001r.whl"));
    let v = wheelrail_json(&case);
    let w = v["warnings"].as_array().unwrap();
    assert!(
        w.iter()
            .any(|w| w["key"] == "position.roll_rad" && w["side"] == "left"),
        "{v}"
    );

    // Doing what the warnings say: the roll found, free rolling by a zero
    // total longitudinal force. No warning.
    let text = measured_a22("avg_wheel.whl")
        .replace("roll_rad = -0.004376\n", "")
        .replace("pitch_rad_per_s = -4.2748834\n", "")
        .replace("[load]\n", "[load]\ntotal_longitudinal_force_n = 0.0\n");
    let case = case_file("wr_measured_found.toml", &text);
    let out = run(&["wheelrail", case.to_str().unwrap(), "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        out.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["warnings"], Value::Array(Vec::new()), "{v}");
    assert!(v["roll_rad"].as_f64().unwrap() != -0.004376, "{v}");
}

#[test]
fn wheelrail_examples_do_not_warn() {
    for name in [
        "wheelset_a22.toml",
        "wheelset_a22_reversing.toml",
        "wheelset_a22_temperature.toml",
        "wheelset_a22_varfric.toml",
        "roller_rig.toml",
    ] {
        let out = run(&["wheelrail", example(name).to_str().unwrap(), "--json"]);
        assert!(out.status.success(), "{name}");
        assert!(
            out.stderr.is_empty(),
            "{name}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let v: Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(v["warnings"], Value::Array(Vec::new()), "{name}: {v}");
    }
}

/// `examples/cases/roller_rig.toml` (test-rollers2.inp case 2a at ten
/// times its speeds): one patch on the right roller at track y 0.2 m, FN
/// within 0.05 % of the `.ref_out`'s 9.719E+04 N (Case 6; the grids'
/// alignment, as for the sphere on the plane), free rolling (CKSI
/// -2.5E-08 there) and the mean surface speed 1 m/s as the rolling speed;
/// its keys refused by name when bad.
#[test]
fn wheelrail_roller_rig_example_and_its_keys() {
    let v = wheelrail_json(&example("roller_rig.toml"));
    let patches = v["wheels"]["right"]["patches"].as_array().unwrap();
    assert_eq!(patches.len(), 1, "{v}");
    let p = &patches[0];
    let f = p["normal_force_n"].as_f64().unwrap();
    assert!((f - 9.719e4).abs() < 5e-4 * 9.719e4, "{f}");
    let y = p["track_y_m"].as_f64().unwrap();
    assert!((y - 0.2).abs() < 1e-9, "{y}");
    let xi = p["creepage_long"].as_f64().unwrap();
    assert!((xi + 2.5e-8).abs() < 1e-7, "{xi}");
    let speed = p["rolling_speed_m_per_s"].as_f64().unwrap();
    assert!((speed - 1.0).abs() < 1e-5, "{speed}");
    let good = example_text("roller_rig.toml").replace("../../", "");
    let root = |t: String| {
        t.replace(
            "\"crates/",
            &format!("\"{}/crates/", env!("CARGO_MANIFEST_DIR")),
        )
    };
    for (name, from, to, key) in [
        (
            "wr_roller_r.toml",
            "roller_radius_m = 0.4",
            "roller_radius_m = -0.4",
            "track.roller_radius_m",
        ),
        (
            "wr_roller_w.toml",
            "roller_rad_per_s = 2.5",
            "roller_rad_per_s = 0.0",
            "track.roller_rad_per_s",
        ),
        (
            "wr_roller_k.toml",
            "roller_rad_per_s = 2.5",
            "roller_rad_per_s = 2.5\ncurvature_per_m = 1.0",
            "track.curvature_per_m",
        ),
    ] {
        expect_bad_wheelrail(name, &root(good.replace(from, to)), key);
    }
}

/// A bad wheelrail case: exit code 2, stderr names `key`.
fn expect_bad_wheelrail(name: &str, text: &str, key: &str) {
    let p = case_file(name, text);
    let out = run(&["wheelrail", p.to_str().unwrap(), "--json"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{name}: stderr {stderr}");
    assert!(
        stderr.contains(key),
        "{name}: should name `{key}`: {stderr}"
    );
    assert!(out.stdout.is_empty(), "{name}: nothing on stdout");
}

#[test]
fn wheelrail_bad_inputs_name_the_key() {
    let good = example_text("wheelset_a22.toml");
    expect_bad_wheelrail(
        "wr_builtin.toml",
        &good.replace("builtin:MBench_UIC60_v3.prr", "builtin:UIC54.prr"),
        "track.rail_profile",
    );
    expect_bad_wheelrail(
        "wr_missing.toml",
        &good.replace(
            "rail_profile = \"builtin:MBench_UIC60_v3.prr\"",
            "rail_profile = \"no_such_file.prr\"",
        ),
        "track.rail_profile",
    );
    expect_bad_wheelrail(
        "wr_load.toml",
        &good.replace("vertical_force_n = 10000.0", ""),
        "load",
    );
    expect_bad_wheelrail(
        "wr_force.toml",
        &good.replace("vertical_force_n = 10000.0", "vertical_force_n = -5.0"),
        "load.vertical_force_n",
    );
    expect_bad_wheelrail(
        "wr_model.toml",
        &good.replace("model = \"exact\"", "model = \"kalker\""),
        "model",
    );
    expect_bad_wheelrail(
        "wr_gauge.toml",
        &good.replace("gauge_m = 1.435", "gauge_m = 0.0"),
        "track.gauge_m",
    );
    expect_bad_wheelrail(
        "wr_unknown.toml",
        &good.replace("[grid]", "[grid]\nelement_size = 0.1"),
        "element_size",
    );
    expect_bad_wheelrail(
        "wr_conformal.toml",
        &format!("{good}\n[conformal]\nrigid_slip = \"reference_section\"\n"),
        "conformal",
    );
}

#[test]
fn wheelrail_temperatures_per_patch_in_json_and_summary() {
    // examples/cases/wheelset_a22_temperature.toml: at 6.5 mm, the
    // rail at 20 °C, the wheel at 60 °C.
    let case = example("wheelset_a22_temperature.toml");
    let text = example_text("wheelset_a22_temperature.toml");
    let v = wheelrail_json(&case);
    for side in ["left", "right"] {
        let p = &v["wheels"][side]["patches"][0];
        let t = &p["temperature"];
        // Equal effusivities: the contact at the mean bulk temperature,
        // half the heat into the rail.
        assert!((f(t, "contact_temperature_k") - 313.15).abs() < 1e-9, "{t}");
        assert!((f(t, "heat_share_rail") - 0.5).abs() < 1e-15, "{t}");
        let rail = f(&t["max_rail"], "temperature_k");
        assert!(rail > 313.15 + 10.0 && rail < 1000.0, "{side}: {t}");
        assert!(f(&t["max_wheel"], "temperature_k") >= 333.15, "{side}: {t}");
        // The heat flux sums to the patch's frictional power.
        let (q, w) = (f(t, "frictional_power_w"), f(p, "frictional_power_w"));
        assert!((q - w).abs() <= 1e-9 * w, "{side}: {q} W against {w} W");
    }
    // Without the sections: no temperature key.
    let plain = wheelrail_json(&example("wheelset_a22.toml"));
    assert!(plain["wheels"]["right"]["patches"][0]["temperature"].is_null());
    let out = run(&["wheelrail", case.to_str().unwrap()]);
    assert!(out.status.success());
    let summary = String::from_utf8(out.stdout).unwrap();
    assert_eq!(
        summary.matches("flash temperature: rail max").count(),
        2,
        "{summary}"
    );
    assert!(summary.contains("; wheel max"), "{summary}");

    expect_bad_wheelrail(
        "wr_temperature_value.toml",
        &text.replace(
            "bulk_temperature_k = 333.15\nconductivity_w_per_m_k = 50.0",
            "bulk_temperature_k = 333.15\nconductivity_w_per_m_k = 0.0",
        ),
        "temperature.wheel.conductivity_w_per_m_k",
    );
    expect_bad_wheelrail(
        "wr_temperature_model.toml",
        &text.replace("model = \"exact\"", "model = \"hertz_fastsim\""),
        "temperature: flash temperatures come from the tractions and slips per element of models \"exact\", \"cect\" and \"auto\"; model \"hertz_fastsim\"",
    );
    expect_bad_wheelrail(
        "wr_temperature_body.toml",
        &text.replace("[temperature.rail]", "[temperature.body1]"),
        "body1",
    );
}

/// `examples/cases/wheelset_a22_varfric.toml`: CONTACT's
/// mbench_a22_varfric case 4 (github.com/eve70a/CONTACT,
/// examples/mbench_a22_varfric.ref_out, commit eb670a7): one flange-root
/// patch with FSTAT 0.2076, FN 9907, FX -608.6, FS -1963 N; each within
/// 1 %. Bad table keys exit with code 2 naming the key.
#[test]
fn wheelrail_friction_table_from_the_case_file() {
    let v = wheelrail_json(&example("wheelset_a22_varfric.toml"));
    let p = &v["wheels"]["right"]["patches"][0];
    for (key, want) in [
        ("friction_coefficient", 0.2076),
        ("normal_force_n", 9907.0),
        ("fx_n", -608.6),
        ("fs_n", -1963.0),
    ] {
        let got = f(p, key);
        assert!(
            (got - want).abs() <= 0.01 * want.abs(),
            "{key}: {got}, CONTACT {want}"
        );
    }
    let good = example_text("wheelset_a22_varfric.toml");
    // A falling law of static coefficient 0.4 (0.1 + 0.3) scaled to the
    // table: its kinetic coefficient at the patch is 0.1 x mu_table / 0.4.
    let falling = case_file(
        "wr_table_falling.toml",
        &good.replace(
            "coefficients = [0.3, 0.2]",
            "coefficients = [0.3, 0.2]\nlaw = \"exponential\"\nkinetic_coefficient = 0.1\n\
             falling_coefficients = [0.3]\nhalf_velocities_m_per_s = [0.05]",
        ),
    );
    let v = wheelrail_json(&falling);
    let q = &v["wheels"]["right"]["patches"][0];
    let want = 0.1 * f(p, "friction_coefficient") / 0.4;
    let got = f(q, "friction_coefficient");
    assert!((got - want).abs() < 1e-12, "{got} against {want}");
    expect_bad_wheelrail(
        "wr_table_order.toml",
        &good.replace("[0.17453292519943295, 0.3490658503988659]", "[0.3, 0.2]"),
        "friction.contact_angles_rad",
    );
    expect_bad_wheelrail(
        "wr_table_count.toml",
        &good.replace("coefficients = [0.3, 0.2]", "coefficients = [0.3]"),
        "friction.coefficients",
    );
    expect_bad_wheelrail(
        "wr_table_and_mu.toml",
        &good.replace(
            "coefficients = [0.3, 0.2]",
            "coefficients = [0.3, 0.2]\ncoefficient = 0.3",
        ),
        "friction.coefficient",
    );
    // A patch case has no rail profile: its table keys are refused.
    expect_bad(
        "patch_table.toml",
        &example_text("hertz_ellipse_rolling.toml").replace(
            "coefficient = 0.30",
            "coefficient = 0.30\ncontact_angles_rad = [0.0]",
        ),
        "friction.contact_angles_rad",
    );
    expect_bad_wheelrail(
        "wr_falling_hertz.toml",
        &example_text("wheelset_a22.toml")
            .replace("model = \"exact\"", "model = \"hertz_fastsim\"")
            .replace(
                "coefficient = 0.3",
                "law = \"exponential\"\nkinetic_coefficient = 0.2\nfalling_coefficients = [0.1]\nhalf_velocities_m_per_s = [0.05]",
            ),
        "friction.law",
    );
}

/// Measured profiles read from files next to the case: a MiniProf wheel on a
/// `load.total_longitudinal_force_n`: the pitch rate is found and
/// reported; with a pitch rate as well, or beyond saturation, exit code 2
/// naming the key.
#[test]
fn wheelrail_finds_the_pitch_rate_of_a_braking_force() {
    let text = example_text("wheelset_a22.toml")
        .replace("model = \"exact\"", "model = \"hertz_fastsim\"")
        .replace(
            "vertical_force_n = 10000.0",
            "vertical_force_n = 10000.0\ntotal_longitudinal_force_n = 1500.0",
        );
    let both = case_file("wr_brake_both.toml", &text);
    let out = run(&["wheelrail", both.to_str().unwrap(), "--json"]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("load.total_longitudinal_force_n") && stderr.contains("pitch_rad_per_s"),
        "{stderr}"
    );
    let braking = text.replace("pitch_rad_per_s = -4.2748834\n", "");
    let v = wheelrail_json(&case_file("wr_brake.toml", &braking));
    let c = &v["pitch_control"];
    assert_eq!(c["converged"], Value::Bool(true), "{c}");
    let fx: f64 = ["left", "right"]
        .iter()
        .map(|s| v["wheels"][*s]["force_track_n"][0].as_f64().unwrap())
        .sum();
    // The force tolerance of the exact model at the wheel/rail defaults:
    // 1e-4 of mu Fn (wheelrail::contact's docs), mu Fn about 7.6 kN.
    assert!((fx - 1500.0).abs() < 1e-4 * 0.3 * 25.5e3, "{fx}");
    // Braked: the wheels turn slower than free rolling (-V / 0.46 m).
    assert!(v["pitch_rad_per_s"].as_f64().unwrap() > -2.0 / 0.46, "{v}");
    // mu Fn: 0.3 x about 25.5 kN (the flange patch carries 15 kN normal).
    let beyond = braking.replace("= 1500.0", "= 9000.0");
    let out = run(&[
        "wheelrail",
        case_file("wr_brake_beyond.toml", &beyond).to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("saturation"), "{stderr}");
}

/// Model hertz_polach with `[polach]`: every patch says so, the wheels
/// carry their load; a parameter out of range is bad input naming it.
#[test]
fn wheelrail_solves_with_polachs_model_and_checks_its_parameters() {
    let text = example_text("wheelset_a22.toml")
        .replace("model = \"exact\"", "model = \"hertz_polach\"")
        + "\n[polach]\nk_adhesion = 1.0\nk_slip = 0.4\nlimit_ratio = 0.4\ndecay_s_per_m = 0.6\n";
    let v = wheelrail_json(&case_file("wr_polach.toml", &text));
    for side in ["left", "right"] {
        let w = &v["wheels"][side];
        let fz = w["force_track_n"][2].as_f64().unwrap();
        assert!((fz - 10_000.0).abs() < 0.1, "{side}: Fz {fz}");
        for p in w["patches"].as_array().unwrap() {
            assert_eq!(p["method"], "hertz_polach", "{p}");
            assert_eq!(p["mz_nm"].as_f64(), Some(0.0), "{p}");
        }
    }
    expect_bad_wheelrail(
        "wr_polach_bad.toml",
        &text.replace("k_slip = 0.4", "k_slip = 1.5"),
        "polach.k_slip",
    );
}

/// Model hertz_fastsim_modified with `[modified_fastsim]` (keys left out
/// take the defaults): every patch says so, the wheels carry their load;
/// a parameter out of range is bad input naming it.
#[test]
fn wheelrail_solves_with_the_modified_fastsim_and_checks_its_parameters() {
    let text = example_text("wheelset_a22.toml")
        .replace("model = \"exact\"", "model = \"hertz_fastsim_modified\"")
        + "\n[modified_fastsim]\ninitial_factor = 0.6\nfriction_limit_ratio = 0.4\n\
           friction_decay_s_per_m = 0.6\n";
    let v = wheelrail_json(&case_file("wr_modified_fastsim.toml", &text));
    for side in ["left", "right"] {
        let w = &v["wheels"][side];
        let fz = w["force_track_n"][2].as_f64().unwrap();
        assert!((fz - 10_000.0).abs() < 0.1, "{side}: Fz {fz}");
        for p in w["patches"].as_array().unwrap() {
            assert_eq!(p["method"], "hertz_fastsim_modified", "{p}");
        }
    }
    expect_bad_wheelrail(
        "wr_modified_fastsim_bad.toml",
        &text.replace("initial_factor = 0.6", "initial_factor = 1.5"),
        "modified_fastsim.initial_factor",
    );
}

/// Models hertz_fastsim_elliptic, hertz_strip and kik_piotrowski: every patch names its
/// model, the wheels carry their load, the flange patch's creep force is
/// near saturation (mu FN) as FASTSIM's; an unknown model is bad input
/// listing the names.
#[test]
fn wheelrail_solves_with_the_elliptic_bound_strip_theory_and_kik_piotrowski() {
    for model in ["hertz_fastsim_elliptic", "hertz_strip", "kik_piotrowski"] {
        let text = example_text("wheelset_a22.toml")
            .replace("model = \"exact\"", &format!("model = \"{model}\""));
        let v = wheelrail_json(&case_file(&format!("wr_{model}.toml"), &text));
        for side in ["left", "right"] {
            let w = &v["wheels"][side];
            let fz = w["force_track_n"][2].as_f64().unwrap();
            assert!((fz - 10_000.0).abs() < 0.1, "{model} {side}: Fz {fz}");
            for p in w["patches"].as_array().unwrap() {
                assert_eq!(p["method"], model, "{p}");
            }
        }
        let flange = &v["wheels"]["right"]["patches"][0];
        let (fx, fs, fnn) = (
            flange["fx_n"].as_f64().unwrap(),
            flange["fs_n"].as_f64().unwrap(),
            flange["normal_force_n"].as_f64().unwrap(),
        );
        let t = fx.hypot(fs);
        assert!(
            t <= 0.3 * fnn * (1.0 + 1e-9) && t > 0.25 * fnn,
            "{model}: {t} of {fnn}"
        );
    }
    expect_bad_wheelrail(
        "wr_unknown_model.toml",
        &example_text("wheelset_a22.toml").replace("model = \"exact\"", "model = \"fastrip\""),
        "hertz_strip",
    );
}

/// MiniProf rail (mirrored into the right-hand convention), hertz_fastsim.
#[test]
fn wheelrail_reads_measured_profiles_by_path() {
    let profiles = crate::common::profiles_dir();
    let text = example_text("wheelset_a22.toml")
        .replace(
            "rail_profile = \"builtin:MBench_UIC60_v3.prr\"",
            &format!(
                "rail_profile = \"{}\"\nrail_mirror_y = true",
                profiles.join("avg_HR.BAN").display()
            ),
        )
        .replace("cant_rad = 0.0", "cant_rad = 0.025")
        .replace(
            "wheel_profile = \"builtin:MBench_S1002_v3.prw\"",
            &format!(
                "wheel_profile = \"{}\"",
                profiles.join("Car7216_0001r.whl").display()
            ),
        )
        .replace("flange_back_y_m = -0.070\n", "")
        .replace("roll_rad = -0.004376\n", "")
        .replace("pitch_rad_per_s = -4.2748834\n", "")
        .replace("model = \"exact\"", "model = \"hertz_fastsim\"");
    let p = case_file("wr_measured.toml", &text);
    let v = wheelrail_json(&p);
    for side in ["left", "right"] {
        let fz = v["wheels"][side]["force_track_n"][2].as_f64().unwrap();
        assert!((fz - 10_000.0).abs() < 0.1, "{side}: Fz {fz}");
    }
}

#[test]
fn serve_logs_plain_text_off_a_terminal_and_says_where_the_store_is() {
    let server = support::Server::start_with(&[], &[("RUST_LOG", "info")]);
    let store = server.dir().join("store").join("pairs.redb");
    let log = server.log();
    assert!(!log.contains('\x1b'), "ANSI codes in a log file:\n{log}");
    let serving = log
        .lines()
        .find(|l| l.contains("railcontact serving"))
        .unwrap_or_else(|| panic!("no start-up line:\n{log}"));
    assert!(
        serving.contains(&format!("store={}", store.display())),
        "{serving}"
    );
    drop(server);
    let memory =
        support::Server::start_with(&[], &[("RUST_LOG", "info"), ("RAILCONTACT_DATA_DIR", "")]);
    let log = memory.log();
    assert!(log.contains("store=memory only"), "{log}");
}

#[test]
fn a_case_file_given_to_the_other_command_names_the_right_one() {
    let wheelset = example("wheelset_a22.toml");
    let out = run(&["solve", wheelset.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("this is a wheelset case") && err.contains("use `railcontact wheelrail "),
        "{err}"
    );
    let patch = example("hertz_circle.toml");
    let out = run(&["wheelrail", patch.to_str().unwrap(), "--json"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("this is a contact-patch case") && err.contains("use `railcontact solve "),
        "{err}"
    );
}

#[test]
fn prescribed_force_gives_back_the_creepage() {
    // The rolling example on 16 x 16: its Fx with the creepage given, then
    // that Fx prescribed instead gives the creepage back (core::force).
    // Inner tolerance 1e-10: the force tolerance is then 1e-9 mu Fn.
    let text = example_text("hertz_ellipse_rolling.toml")
        .replace("nx = 24", "nx = 16")
        .replace("ny = 24", "ny = 16")
        + "\n[solver]\ntangential_tolerance = 1e-10\n";
    let forward = solve_json(&case_file("force_fw.toml", &text), &[]);
    let fx = f(&forward, "fx_n");
    let inverse_text = text.replace("creepage_long = 0.001", &format!("force_x_n = {fx:e}"));
    assert!(inverse_text.contains("force_x_n"));
    let inverse = solve_json(&case_file("force_inv.toml", &inverse_text), &[]);
    let c = &inverse["force_control"];
    let xi = c["creepage_long"].as_f64().unwrap();
    assert!((xi - 0.001).abs() <= 1e-6 * 0.001, "{c}");
    assert_eq!(c["creepage_lat"].as_f64(), Some(0.0005));
    assert!(c["force_iterations"].as_u64().unwrap() >= 1, "{c}");
    assert!((f(&inverse, "fx_n") - fx).abs() <= 1e-6 * 0.3 * 1e4);
    // Both keys of a direction, and a force beyond mu Fn, are refused
    // naming the keys.
    let both = text.replace(
        "creepage_long = 0.001",
        "creepage_long = 0.001\nforce_x_n = -100.0",
    );
    let out = run(&[
        "solve",
        case_file("force_both.toml", &both).to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        err.contains("rolling.creepage_long") && err.contains("rolling.force_x_n"),
        "{err}"
    );
    let beyond = text.replace("creepage_long = 0.001", "force_x_n = -3300.0");
    let out = run(&[
        "solve",
        case_file("force_beyond.toml", &beyond).to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        err.contains("rolling.force_x_n") && err.contains("saturation mu Fn"),
        "{err}"
    );
}

#[test]
fn subsurface_example_writes_peaks_csv_and_plot() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("cli-subsurface");
    std::fs::create_dir_all(&dir).unwrap();
    let (csv, png) = (dir.join("sub.csv"), dir.join("sub.png"));
    let v = solve_json(
        &example("subsurface_rolling.toml"),
        &[
            "--subsurface-csv",
            csv.to_str().unwrap(),
            "--subsurface-plot",
            png.to_str().unwrap(),
        ],
    );
    let s = &v["subsurface"];
    assert_eq!(s["depths_m"].as_array().unwrap().len(), 16);
    // The largest shear below a lightly tractive circle: about 0.31 p0
    // about 0.48 a deep (Johnson 1985 §4.2); a = 3.19 mm here.
    let p0 = f(&v, "max_pressure_pa");
    let tau = s["body1"]["max_shear"]["value_pa"].as_f64().unwrap();
    let depth = s["body1"]["max_shear"]["depth_m"].as_f64().unwrap();
    assert!((tau / p0 - 0.31).abs() < 0.02, "{}", tau / p0);
    assert!((depth / 3.19e-3 - 0.48).abs() < 0.1, "{depth}");
    assert!(s["surface_fatigue_index"].as_f64().unwrap() < 0.0);
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    assert!(lines
        .next()
        .unwrap()
        .starts_with("body,x_m,y_m,depth_m,n_m,"));
    assert_eq!(lines.count(), 2 * 16 * 32 * 32);
    assert!(std::fs::metadata(&png).unwrap().len() > 10_000);
}

#[test]
fn subsurface_options_need_the_section() {
    let out = run(&[
        "solve",
        example("hertz_circle.toml").to_str().unwrap(),
        "--subsurface-csv",
        "/dev/null",
    ]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("`--subsurface-csv`") && err.contains("[subsurface]"),
        "{err}"
    );
}

#[test]
fn the_falling_friction_example_is_contacts_veldep_fric_case_1() {
    // examples/cases/line_veldep_fric.toml: CONTACT's veldep_fric case 1
    // (veldep_fric.ref_out, revision 2356: FX 1.109E+05 N over DY = 200 mm,
    // 5.545e5 N/m; NCON 81, NADH 45, NSLIP 36).
    let v = solve_json(&example("line_veldep_fric.toml"), &["--fields"]);
    assert_eq!(v["status"], "converged");
    let fx = f(&v, "fx_n");
    assert!((fx / 5.545e5 - 1.0).abs() < 0.01, "Fx {fx} N/m");
    let states = v["fields"]["state"].as_array().unwrap();
    let count = |s: &str| states.iter().filter(|e| *e == s).count();
    assert_eq!(
        [count("adhesion"), count("slip")],
        [45, 36],
        "adhesion/slip"
    );
    // A falling-law key under Coulomb's law is refused naming it.
    let bad = case_file(
        "veldep_coulomb.toml",
        &example_text("line_veldep_fric.toml").replace("law = \"exponential\"", ""),
    );
    let out = run(&["solve", bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("friction.falling_coefficients"), "{err}");
}

/// Adhesion and slip element counts of a report entry of a line contact
/// on 0.1 mm elements (its area per metre over the element length).
fn line_counts(s: &Value) -> [usize; 2] {
    let n = f(s, "contact_area_m2") / 1e-4;
    let adhesion = n * f(s, "adhesion_fraction");
    [adhesion.round() as usize, (n - adhesion).round() as usize]
}

#[test]
fn transient_steps_start_from_a_steady_state_each_at_its_own_friction_start() {
    // examples/cases/line_veldep_fric_steps.toml: CONTACT's veldep_fric,
    // case 3 (steady, INISLP 1) then cases 4-6 (rolling steps from the
    // slip velocity V, INISLP -1); veldep_fric.ref_out, revision 2356: FX
    // over DY = 200 mm and "final element division: A, S=". Per metre:
    // case 3 1.109E+05 -> 5.545e5 N/m, 45/36; case 4 1.064E+05 -> 5.320e5,
    // 34/47; case 5 1.071E+05 -> 5.355e5, 79/2; case 6 1.078E+05 ->
    // 5.390e5, 77/4; case 2 (one step from case 1 at INISLP 1) 1.116E+05
    // -> 5.580e5, 77/4. The validation suite holds all 53 cases within
    // 0.83 % (crates/solver/tests/validation/falling_friction.rs); the
    // grid here has one element more (93 centred against CONTACT's 92).
    let check = |what: &str, s: &Value, fx: f64, counts: [usize; 2]| {
        let got = f(s, "fx_n");
        assert!(
            (got / fx - 1.0).abs() < 0.01,
            "{what}: Fx {got} N/m vs {fx}"
        );
        assert_eq!(line_counts(s), counts, "{what}: adhesion/slip");
    };
    let v = solve_json(&example("line_veldep_fric_steps.toml"), &[]);
    assert_eq!(v["status"], "converged");
    check("case 3", &v["steady_start"], 5.545e5, [45, 36]);
    let steps = v["steps"].as_array().unwrap();
    assert_eq!(steps.len(), 3);
    for (k, (fx, counts)) in [(5.320e5, [34, 47]), (5.355e5, [79, 2]), (5.390e5, [77, 4])]
        .into_iter()
        .enumerate()
    {
        check(&format!("case {}", k + 4), &steps[k], fx, counts);
    }
    // The first step from the slip velocity 0: the low-slip branch.
    let text = example_text("line_veldep_fric_steps.toml").replacen(
        "friction_start = \"sliding\"",
        "friction_start = \"sticking\"",
        1,
    );
    let v = solve_json(&case_file("veldep_sticking.toml", &text), &[]);
    check("case 2", &v["steps"][0], 5.580e5, [77, 4]);
    // A friction start without a falling law is refused naming it, and a
    // line contact's steady start rolls in x only.
    let coulomb = {
        let (i, j) = (
            text.find("[friction]").unwrap(),
            text.find("[geometry]").unwrap(),
        );
        format!(
            "{}[friction]\ncoefficient = 0.3\n\n{}",
            &text[..i],
            &text[j..]
        )
    };
    for (name, text, key) in [
        (
            "veldep_coulomb_steps.toml",
            coulomb,
            "transient.steps[0].friction_start",
        ),
        (
            "veldep_lateral_start.toml",
            text.replace("{ creepage_long = -0.0009999 }", "{ creepage_lat = 0.001 }"),
            "transient.steady_start.creepage_lat",
        ),
    ] {
        let out = run(&["solve", case_file(name, &text).to_str().unwrap()]);
        assert_eq!(out.status.code(), Some(2), "{name}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(key), "{name}: {err}");
    }
}

#[test]
fn the_line_contact_example_is_carters_rolling_per_metre() {
    // examples/cases/line_carter.toml: CONTACT's carter2d on 200 strips.
    // Carter (1926), Johnson 1985 §8.2: xi = 0.4 mu a/R leaves c/a = 0.6,
    // Fx = (1 - 0.6²) mu Fn = 0.64 mu Fn, the creepage being negative.
    let v = solve_json(&example("line_carter.toml"), &[]);
    assert_eq!(v["status"], "converged");
    assert!((f(&v, "normal_force_n") / 178_900.0 - 1.0).abs() < 1e-9);
    let ratio = f(&v, "fx_n") / (0.3 * f(&v, "normal_force_n"));
    assert!((ratio / 0.64 - 1.0).abs() < 5e-3, "Fx/(mu Fn) {ratio}");
    assert_eq!(v["grid"], serde_json::json!([200, 1]), "{v}");
    let notes = v["notes"].to_string();
    assert!(notes.contains("per metre"), "{notes}");
    // A 3-D key is refused naming it (exit code 2).
    let bad = case_file(
        "line_with_ny.toml",
        &example_text("line_carter.toml").replace("nx = 200", "nx = 200\nny = 8"),
    );
    let out = run(&["solve", bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("grid.ny"));
}

#[test]
fn the_bentall_example_rolls_in_minus_x_as_contact_states_it() {
    // examples/cases/line_bentall_minus_x.toml: CONTACT's bentall case 4
    // with CHI = 180 deg as given. bentall.ref_out, case 4: CREEP X
    // 4.294e-4, NCON 200, NADH 125, NSLIP 75 (adhesion fraction 0.625).
    let v = solve_json(&example("line_bentall_minus_x.toml"), &[]);
    assert_eq!(v["status"], "converged");
    let xi = v["force_control"]["creepage_long"].as_f64().unwrap();
    assert!((xi / 4.294e-4 - 1.0).abs() < 0.01, "creepage {xi}");
    let adhesion = f(&v, "adhesion_fraction") * 200.0;
    assert!(
        (adhesion - 125.0).abs() <= 1.0 + 1e-9,
        "adhesion elements {adhesion}"
    );
    // A direction off the grid's axes is refused naming the key.
    let bad = case_file(
        "bentall_oblique.toml",
        &example_text("line_bentall_minus_x.toml").replace(
            "rolling_direction_rad = 3.141592653589793",
            "rolling_direction_rad = 1.0",
        ),
    );
    let out = run(&["solve", bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("rolling_direction_rad"));
}

#[test]
fn flash_temperature_example_writes_peaks_and_csv() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("cli-temperature");
    std::fs::create_dir_all(&dir).unwrap();
    let (csv, png) = (dir.join("temp.csv"), dir.join("temp.png"));
    let v = solve_json(
        &example("flash_temperature.toml"),
        &[
            "--temperature-csv",
            csv.to_str().unwrap(),
            "--plot",
            png.to_str().unwrap(),
        ],
    );
    let t = &v["temperature"];
    // CONTACT's ertz_temperature case 1 on the same elements: FRIC.POWER
    // = -2.994E+04 W (eve70a/CONTACT, examples/ertz_temperature.ref_out).
    let power = t["frictional_power_w"].as_f64().unwrap();
    assert!((power / 2.994e4 - 1.0).abs() < 1e-3, "{power}");
    // Equal steels at 0 C: the contact starts at 273.15 K, both surfaces
    // share the frictional rise in the contact and one maximum.
    assert!((t["contact_temperature_k"].as_f64().unwrap() - 273.15).abs() < 1e-9);
    let max1 = t["max_body1"]["temperature_k"].as_f64().unwrap();
    let max2 = t["max_body2"]["temperature_k"].as_f64().unwrap();
    assert_eq!(max1, max2);
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        "x_m,y_m,heat_flux_w_per_m2,body1_k,body2_k"
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 73 * 45);
    let csv_max = rows.iter().map(|r| r[3]).fold(f64::NEG_INFINITY, f64::max);
    assert_eq!(csv_max, max1);
    // sum q dA over the rows is the frictional power (0.2 x 0.5 mm elements).
    let sum: f64 = rows.iter().map(|r| r[2]).sum::<f64>() * 0.2e-3 * 0.5e-3;
    assert!((sum / power - 1.0).abs() < 1e-6, "{sum} {power}");
    // The centre line carries the temperatures on a second axis.
    assert!(std::fs::metadata(&png).unwrap().len() > 10_000);
}

#[test]
fn temperature_csv_needs_the_section() {
    let out = run(&[
        "solve",
        example("hertz_circle.toml").to_str().unwrap(),
        "--temperature-csv",
        "/dev/null",
    ]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("`--temperature-csv`") && err.contains("[temperature]"),
        "{err}"
    );
}
