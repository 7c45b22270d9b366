//! The `railcontact` command line: `railcontact solve CASE.toml [--json]
//! [--fields] [--plot FILE]` (one contact patch) and `railcontact wheelrail
//! CASE.toml [--json] [--plot FILE]` (a wheelset on its track); `loadtest`
//! (drives a running service, see [`loadtest`]) and `health` (asks its gRPC
//! health service). The binary puts `serve` (`crate::service::command`)
//! beside these; the command line does not import the service, and speaks
//! to it through the wire types of [`crate::shared`].
//!
//! [`Command`] is the clap definition, [`run`] executes it and returns the
//! process exit code: 0 on success, [`EXIT_BAD_INPUT`] (2) for bad input (the
//! message on stderr names the offending key), [`EXIT_FAILURE`] (1) for any
//! other failure.

pub mod health;
pub mod loadtest;
pub mod plot;
pub mod subsurface;
pub mod temperature;
pub mod wheelrail;

use std::path::{Path, PathBuf};

use clap::{Args, Subcommand};

use crate::conformal::frictional::FrictionalWorkspace;
use crate::core::problem::Kinematics;
use crate::problem::case::{Case, Model};
use crate::problem::{CaseError, ModelRun};
pub use crate::shared::{EXIT_BAD_INPUT, EXIT_FAILURE};

/// The subcommands of the command line (`serve` is the service's).
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Solve one contact case read from a TOML file (SI units; see
    /// examples/cases/README.md for the keys).
    ///
    /// Prints a readable summary (mm, MPa), or with --json exactly one JSON
    /// object in SI units. Exit code 2 on bad input (the message names the
    /// key), 1 on other failures.
    Solve(SolveArgs),
    /// Solve a wheelset on its track read from a TOML file: profiles, track
    /// and wheelset data, position, velocity and load per wheel (SI units;
    /// see examples/cases/README.md). Finds every contact patch of each
    /// wheel and solves it.
    ///
    /// Prints a readable summary, or with --json one JSON object in SI units
    /// (per wheel: its patches and its total force on the rail in the track
    /// frame). Exit code 2 on bad input, 1 on other failures.
    Wheelrail(wheelrail::WheelrailArgs),
    /// Drive a running server (or several replicas) with concurrent
    /// co-simulation sessions and batch clients; report latency
    /// percentiles and throughput, and check every answer bit for bit
    /// against a replay of each session alone (see docs/loadtest.md).
    ///
    /// Exit code 1 when any step failed or differed, or a target cannot be
    /// reached; 2 for bad options.
    Loadtest(loadtest::LoadtestArgs),
    /// Ask a server's gRPC health service (grpc.health.v1) whether it is
    /// serving: prints the status, exit code 0 when SERVING, 1 otherwise.
    /// For container health checks and exec probes.
    Health(health::HealthArgs),
}

/// Options of `railcontact solve`.
#[derive(Debug, Args)]
pub struct SolveArgs {
    /// The case file (TOML).
    #[arg(value_name = "CASE.toml")]
    pub case: PathBuf,
    /// Print one JSON object (SI units) on stdout instead of the summary.
    #[arg(long)]
    pub json: bool,
    /// With --json: add the per-element fields (pressure_pa, traction_x_pa,
    /// traction_y_pa, slip_x, slip_y, state, gap_m, nx, ny, dx_m, dy_m, x0_m,
    /// y0_m) of the (last) solution. Models exact, cect and cect_halfspace
    /// (these two: traction_s_pa, slip_s, and per lateral line delta_rad,
    /// reference_yz_m).
    #[arg(long, requires = "json")]
    pub fields: bool,
    /// Write pressure and traction maps and a centre-line plot to FILE (.png
    /// or .svg, by extension), with a case's `[temperature]` both bodies'
    /// surface temperatures along the centre line on a second axis. Exact
    /// model only (not yet the conformal models).
    #[arg(long, value_name = "FILE")]
    pub plot: Option<PathBuf>,
    /// Write the subsurface fields of both bodies (a case with
    /// `[subsurface]`) to FILE as CSV: one row per body, depth and element,
    /// SI units, stresses tension positive in the frame (x, y, n), with the
    /// principal, von Mises, Tresca, maximum shear and mean stresses.
    #[arg(long, value_name = "FILE")]
    pub subsurface_csv: Option<PathBuf>,
    /// Write von Mises maps below the surface (a case with `[subsurface]`)
    /// to FILE (.png or .svg): the x-n and y-n mid-planes of both bodies
    /// and each body at one depth.
    #[arg(long, value_name = "FILE")]
    pub subsurface_plot: Option<PathBuf>,
    /// The depth of --subsurface-plot's depth maps, in metres: the computed depth
    /// nearest to it (default: the depth of body 1's largest von Mises
    /// stress).
    #[arg(long, value_name = "M", requires = "subsurface_plot")]
    pub subsurface_depth_m: Option<f64>,
    /// Write the flash temperatures of both surfaces (a case with
    /// `[temperature]`) to FILE as CSV: one row per element, its centre
    /// x_m, y_m, the frictional power density heat_flux_w_per_m2 and the
    /// surface temperatures body1_k, body2_k (kelvin).
    #[arg(long, value_name = "FILE")]
    pub temperature_csv: Option<PathBuf>,
}

/// A failure of the command, sorted by exit code.
#[derive(Debug, Clone, PartialEq)]
pub enum CliError {
    /// Bad input: the message names the key or option to fix (exit code 2).
    BadInput(String),
    /// Anything else (exit code 1).
    Failure(String),
}

impl CliError {
    /// The process exit code of this error.
    pub fn exit_code(&self) -> i32 {
        match self {
            CliError::BadInput(_) => EXIT_BAD_INPUT,
            CliError::Failure(_) => EXIT_FAILURE,
        }
    }
}

impl std::fmt::Display for CliError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            CliError::BadInput(m) | CliError::Failure(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for CliError {}

impl From<CaseError> for CliError {
    fn from(e: CaseError) -> Self {
        match e {
            CaseError::BadInput(m) => CliError::BadInput(m),
            e @ (CaseError::Failure(_) | CaseError::Cancelled) => CliError::Failure(e.to_string()),
        }
    }
}

/// Runs the parsed command line; returns the process exit code. Output goes
/// to stdout, errors to stderr.
pub fn run(command: Command) -> i32 {
    let result = match command {
        Command::Solve(args) => run_solve(&args),
        Command::Wheelrail(args) => wheelrail::run(&args),
        Command::Loadtest(args) => loadtest::run(&args),
        Command::Health(args) => health::run(&args),
    };
    match result {
        Ok(()) => 0,
        Err(e) => {
            eprintln!("error: {e}");
            e.exit_code()
        }
    }
}

/// The plot format chosen by `--plot`'s extension.
fn plot_format(path: &Path) -> Result<plot::Format, CliError> {
    match path
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase())
        .as_deref()
    {
        Some("png") => Ok(plot::Format::Png),
        Some("svg") => Ok(plot::Format::Svg),
        _ => Err(CliError::BadInput(format!(
            "invalid option `--plot`: {} must end in .png or .svg",
            path.display()
        ))),
    }
}

/// The two kinds of case file, told apart by their top-level sections.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum CaseKind {
    /// One contact patch (`railcontact solve`): has `[geometry]`.
    Patch,
    /// A wheelset on its track (`railcontact wheelrail`): has `[track]` or
    /// `[wheelset]`.
    Wheelset,
}

impl CaseKind {
    /// The kind `text` looks like; None when it is not TOML or has neither
    /// kind's sections (the case reader then says what is wrong).
    fn of(text: &str) -> Option<Self> {
        let table: toml::Table = text.parse().ok()?;
        if table.contains_key("track") || table.contains_key("wheelset") {
            Some(CaseKind::Wheelset)
        } else if table.contains_key("geometry") {
            Some(CaseKind::Patch)
        } else {
            None
        }
    }

    /// Reads the case file `path`; bad input when it is a case of the other
    /// kind than `want`, with the command that reads it.
    fn read(path: &Path, want: CaseKind) -> Result<String, CliError> {
        let text = std::fs::read_to_string(path).map_err(|e| {
            CliError::BadInput(format!("cannot read case file {}: {e}", path.display()))
        })?;
        match CaseKind::of(&text) {
            Some(kind) if kind != want => {
                let (what, sections, command) = match kind {
                    CaseKind::Wheelset => ("a wheelset case", "[track], [wheelset]", "wheelrail"),
                    CaseKind::Patch => ("a contact-patch case", "[geometry]", "solve"),
                };
                Err(CliError::BadInput(format!(
                    "{}: this is {what} ({sections}): use `railcontact {command} {}`",
                    path.display(),
                    path.display()
                )))
            }
            _ => Ok(text),
        }
    }
}

fn run_solve(args: &SolveArgs) -> Result<(), CliError> {
    let format = args.plot.as_deref().map(plot_format).transpose()?;
    let text = CaseKind::read(&args.case, CaseKind::Patch)?;
    let case = Case::from_toml_in(&text, args.case.parent().unwrap_or(Path::new("."))).map_err(
        |e| match e {
            CaseError::BadInput(m) => CliError::BadInput(format!("{}: {m}", args.case.display())),
            other => other.into(),
        },
    )?;
    if case.model.is_cect() && args.plot.is_some() {
        return Err(CliError::BadInput(format!(
            "invalid option `--plot`: plots of the conformal models are not available yet (model = \"{}\"); \
             use --json --fields for the per-element fields",
            case.model.name()
        )));
    }
    if case.model != Model::Exact && !case.model.is_cect() {
        if args.fields {
            return Err(CliError::BadInput(format!(
                "invalid option `--fields`: per-element fields come from model = \"exact\", \"cect\" or \"cect_halfspace\" only, not \"{}\"",
                case.model.name()
            )));
        }
        if args.plot.is_some() {
            return Err(CliError::BadInput(format!(
                "invalid option `--plot`: plots need the per-element fields of model = \"exact\", not \"{}\"",
                case.model.name()
            )));
        }
    }
    let sub_format = args
        .subsurface_plot
        .as_deref()
        .map(plot_format)
        .transpose()
        .map_err(|e| {
            CliError::BadInput(e.to_string().replace("`--plot`", "`--subsurface-plot`"))
        })?;
    if case.subsurface.is_none() {
        for (flag, given) in [
            ("--subsurface-csv", args.subsurface_csv.is_some()),
            ("--subsurface-plot", args.subsurface_plot.is_some()),
        ] {
            if given {
                return Err(CliError::BadInput(format!(
                    "invalid option `{flag}`: the case has no `[subsurface]` section (give `depths_m`, \
                     or `max_depth_m` and `depth_count`)"
                )));
            }
        }
    }
    if case.temperature.is_none() && args.temperature_csv.is_some() {
        return Err(CliError::BadInput(
            "invalid option `--temperature-csv`: the case has no `[temperature]` section (give \
             `rolling_speed_m_per_s`, `[temperature.body1]` and `[temperature.body2]`)"
                .to_string(),
        ));
    }
    if let Some(d) = args.subsurface_depth_m {
        if !(d.is_finite() && d >= 0.0) {
            return Err(CliError::BadInput(format!(
                "invalid option `--subsurface-depth-m`: must be finite and >= 0 (m), got {d}"
            )));
        }
    }
    // Every output file writable before the solve, which may take long.
    for (flag, path) in [
        ("--plot", &args.plot),
        ("--subsurface-csv", &args.subsurface_csv),
        ("--subsurface-plot", &args.subsurface_plot),
        ("--temperature-csv", &args.temperature_csv),
    ] {
        if let Some(path) = path {
            check_writable(flag, path)?;
        }
    }
    let run = ModelRun::solve(&case, &mut FrictionalWorkspace::default())?;
    let mut report = run.report(&case, args.fields);
    if report.geometry.is_none() && case.geometry.is_conformal() {
        report.geometry = Some(case.geometry.describe());
    }
    report.notes.extend(case.notes.iter().cloned());
    // The answer first: a file that then fails to write loses nothing.
    write_stdout(&if args.json {
        let mut s = serde_json::to_string(&report)
            .map_err(|e| CliError::Failure(format!("cannot write JSON: {e}")))?;
        s.push('\n');
        s
    } else {
        report.human()
    })?;
    let mut out = String::new();
    if let (Some(path), Some(format), ModelRun::Exact(run)) = (&args.plot, format, &run) {
        plot::write_plot(
            path,
            format,
            &run.grid,
            run.last(),
            plot::PlotCase {
                title: &plot_title(&case),
                mu: case.friction.kinetic_coefficient,
                rolling: matches!(case.kinematics, Kinematics::SteadyRolling(_)),
                temperature: run.temperature.as_deref(),
            },
        )
        .map_err(|e| CliError::Failure(format!("cannot write plot {}: {e}", path.display())))?;
        if !args.json {
            out.push_str(&format!("  plot written to {}\n", path.display()));
        }
    }
    if let (ModelRun::Exact(run), Some(path)) = (&run, &args.temperature_csv) {
        if let Some(t) = &run.temperature {
            temperature::write_csv(path, &run.grid, t)
                .map_err(|e| CliError::Failure(format!("cannot write {}: {e}", path.display())))?;
            if !args.json {
                out.push_str(&format!(
                    "  temperature CSV written to {}\n",
                    path.display()
                ));
            }
        }
    }
    if let ModelRun::Exact(run) = &run {
        if let Some(bodies) = run.subsurface.as_ref().map(|s| &s.bodies) {
            if let Some(path) = &args.subsurface_csv {
                subsurface::write_csv(path, &run.grid, bodies).map_err(|e| {
                    CliError::Failure(format!("cannot write {}: {e}", path.display()))
                })?;
                if !args.json {
                    out.push_str(&format!("  subsurface CSV written to {}\n", path.display()));
                }
            }
            if let (Some(path), Some(format)) = (&args.subsurface_plot, sub_format) {
                let k = subsurface::plot_depth(&run.grid, bodies, args.subsurface_depth_m);
                subsurface::write_plot(path, format, &run.grid, bodies, k).map_err(|e| {
                    CliError::Failure(format!("cannot write plot {}: {e}", path.display()))
                })?;
                if !args.json {
                    out.push_str(&format!(
                        "  subsurface plot written to {}\n",
                        path.display()
                    ));
                }
            }
        }
    }
    write_stdout(&out)
}

/// Checks that `path` (the value of option `flag`) can be written, before
/// any work: an existing file is opened for writing (not truncated), a
/// new one created and removed again. An error names the option and the
/// path.
pub(crate) fn check_writable(flag: &str, path: &Path) -> Result<(), CliError> {
    let existed = path.exists();
    let opened = std::fs::OpenOptions::new()
        .write(true)
        .create(!existed)
        .truncate(false)
        .open(path);
    match opened {
        Ok(_) => {
            if !existed {
                let _ = std::fs::remove_file(path);
            }
            Ok(())
        }
        Err(e) => Err(CliError::BadInput(format!(
            "invalid option `{flag}`: cannot write {}: {e}",
            path.display()
        ))),
    }
}

/// Writes `text` to stdout; a closed pipe (`| head`) is not an error.
fn write_stdout(text: &str) -> Result<(), CliError> {
    use std::io::Write;
    let mut stdout = std::io::stdout().lock();
    match stdout
        .write_all(text.as_bytes())
        .and_then(|()| stdout.flush())
    {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        Err(e) => Err(CliError::Failure(format!("cannot write to stdout: {e}"))),
    }
}

fn plot_title(case: &Case) -> String {
    match &case.kinematics {
        Kinematics::Frictionless => "static, frictionless".to_string(),
        Kinematics::SteadyRolling(_) if case.prescribed_force.any() => format!(
            "steady rolling, prescribed force Fx = {}, Fy = {}, mu = {}",
            case.prescribed_force
                .force_x_n
                .map_or("-".to_string(), |f| format!("{f} N")),
            case.prescribed_force
                .force_y_n
                .map_or("-".to_string(), |f| format!("{f} N")),
            case.friction.kinetic_coefficient
        ),
        Kinematics::SteadyRolling(c) => format!(
            "steady rolling: xi = {:.3e}, eta = {:.3e}, phi = {:.3e} 1/m, mu = {}",
            c.creepage_long, c.creepage_lat, c.spin_per_m, case.friction.kinetic_coefficient
        ),
        Kinematics::Transient(s) => format!(
            "transient, last of {} steps, mu = {}",
            s.len(),
            case.friction.kinetic_coefficient
        ),
    }
}
