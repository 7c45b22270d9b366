//! The reference models of `railcontact solve`: `model = "hertz"` (closed
//! form, normal problem only) and `model = "fastsim"` (Kalker's simplified
//! theory on the Hertz ellipse), and the Hertz semi-axes that size the
//! automatic window of the exact model.

use std::time::Instant;

use crate::cli::case::{Case, Model, SemiAxes};
use crate::cli::report::{Report, StepReport};
use crate::cli::CliError;
use crate::core::fastsim::{Fastsim, FastsimInput};
use crate::core::hertz::{hertz, HertzLoad, HertzSolution};
use crate::core::normal::NormalLoad;

fn hertz_load(load: NormalLoad) -> HertzLoad {
    match load {
        NormalLoad::NormalForce(f) => HertzLoad::NormalForce { normal_force_n: f },
        NormalLoad::Approach(d) => HertzLoad::Approach { approach_m: d },
    }
}

fn hertz_of(
    a_per_m: f64,
    b_per_m: f64,
    e_star_pa: f64,
    load: NormalLoad,
) -> Result<HertzSolution, CliError> {
    // Hertz rejects only inputs: name the model in the message.
    hertz(a_per_m, b_per_m, e_star_pa, hertz_load(load))
        .map_err(|e| CliError::BadInput(format!("Hertz model: {e}")))
}

/// Hertz semi-axes of h = A x² + B y² under `load` (sizes the automatic window).
pub(crate) fn hertz_semi_axes(
    a_per_m: f64,
    b_per_m: f64,
    e_star_pa: f64,
    load: NormalLoad,
) -> Result<SemiAxes, CliError> {
    let h = hertz_of(a_per_m, b_per_m, e_star_pa, load)?;
    Ok(SemiAxes {
        x_m: h.semi_axis_x_m,
        y_m: h.semi_axis_y_m,
    })
}

/// The totals of a Hertz solution; tangential quantities are 0.
fn hertz_totals(h: &HertzSolution) -> StepReport {
    StepReport {
        normal_force_n: h.normal_force_n,
        approach_m: h.approach_m,
        max_pressure_pa: h.max_pressure_pa,
        contact_area_m2: h.contact_area_m2,
        patch_length_m: 2.0 * h.semi_axis_x_m,
        patch_width_m: 2.0 * h.semi_axis_y_m,
        status: "converged".to_string(),
        ..StepReport::default()
    }
}

/// Model `hertz`: Hertz's closed-form normal solution.
pub(crate) fn solve_hertz(case: &Case) -> Result<Report, CliError> {
    let t0 = Instant::now();
    let h = hertz_of(
        case.a_per_m,
        case.b_per_m,
        case.material.effective_modulus_pa(),
        case.load,
    )?;
    let mut totals = hertz_totals(&h);
    totals.solve_time_s = t0.elapsed().as_secs_f64();
    Ok(Report {
        model: Model::Hertz.name().to_string(),
        totals,
        friction_coefficient: 0.0,
        grid: None,
        window_m: None,
        notes: vec![
            "the Hertz model solves the normal problem only: fx_n, fy_n, mz_nm, max_traction_pa, adhesion_fraction and tgamma_n are not computed (reported as 0)".to_string(),
        ],
        steps: None,
        fields: None,
    })
}

/// Model `fastsim`: the Hertz ellipse, then FASTSIM with the case's creepages
/// on `nx` x `ny` elements.
pub(crate) fn solve_fastsim(case: &Case) -> Result<Report, CliError> {
    let t0 = Instant::now();
    let h = hertz_of(
        case.a_per_m,
        case.b_per_m,
        case.material.effective_modulus_pa(),
        case.load,
    )?;
    let c = case.creepages();
    let input = FastsimInput {
        semi_axis_x_m: h.semi_axis_x_m,
        semi_axis_y_m: h.semi_axis_y_m,
        normal_force_n: h.normal_force_n,
        shear_modulus_pa: case.material.shear_modulus_pa,
        poisson_ratio: case.material.poisson_ratio,
        friction_coefficient: case.friction.kinetic_coefficient,
        creepage_long: c.creepage_long,
        creepage_lat: c.creepage_lat,
        spin_per_m: c.spin_per_m,
    };
    let mut fastsim = Fastsim::new(case.nx, case.ny)
        .map_err(|e| CliError::BadInput(format!("invalid input `grid`: FASTSIM: {e}")))?;
    let out = fastsim
        .solve(&input)
        .map_err(|e| CliError::BadInput(format!("FASTSIM model: {e}")))?;
    let mut totals = hertz_totals(&h);
    totals.fx_n = out.fx_n;
    totals.fy_n = out.fy_n;
    totals.mz_nm = out.mz_nm;
    totals.adhesion_fraction = out.adhesion_fraction;
    totals.tgamma_n = out.tgamma_n;
    totals.max_traction_pa = out.max_traction_pa;
    totals.solve_time_s = t0.elapsed().as_secs_f64();
    Ok(Report {
        model: Model::Fastsim.name().to_string(),
        totals,
        friction_coefficient: case.friction.kinetic_coefficient,
        grid: Some([case.nx, case.ny]),
        window_m: None,
        notes: vec![
            "normal quantities from Hertz; tangential from FASTSIM (Kalker's simplified theory)"
                .to_string(),
        ],
        steps: None,
        fields: None,
    })
}
