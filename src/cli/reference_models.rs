//! The reference models of `railcontact solve`: `model = "hertz"` (closed
//! form, normal problem only) and `model = "fastsim"` (Kalker's simplified
//! theory on the Hertz ellipse), and the Hertz semi-axes that size the
//! automatic window of the exact model.

use std::time::Instant;

use crate::cli::case::{Case, Model};
use crate::cli::report::{Report, StepReport};
use crate::cli::CliError;
use crate::core::fastsim::{Fastsim, FastsimInput};
use crate::core::hertz::{hertz, HertzLoad, HertzSolution};
use crate::core::normal::NormalLoad;
use crate::core::solution::Totals;

fn hertz_load(load: NormalLoad) -> HertzLoad {
    match load {
        NormalLoad::NormalForce(f) => HertzLoad::NormalForce { normal_force_n: f },
        NormalLoad::Approach(d) => HertzLoad::Approach { approach_m: d },
    }
}

/// Hertz solution of h = A x² + B y² under `load`; errors name the model.
pub(crate) fn hertz_of(
    a_per_m: f64,
    b_per_m: f64,
    e_star_pa: f64,
    load: NormalLoad,
) -> Result<HertzSolution, CliError> {
    // Hertz rejects only inputs: name the model in the message.
    hertz(a_per_m, b_per_m, e_star_pa, hertz_load(load))
        .map_err(|e| CliError::BadInput(format!("Hertz model: {e}")))
}

/// The totals of a Hertz solution; tangential quantities are 0.
fn hertz_totals(h: &HertzSolution) -> Totals {
    Totals {
        normal_force_n: h.normal_force_n,
        approach_m: h.approach_m,
        max_pressure_pa: h.max_pressure_pa,
        contact_area_m2: h.contact_area_m2,
        patch_length_m: 2.0 * h.semi_axis_x_m,
        patch_width_m: 2.0 * h.semi_axis_y_m,
        ..Totals::default()
    }
}

/// Model `hertz`: Hertz's closed-form normal solution.
pub(crate) fn solve_hertz(case: &Case) -> Result<Report<'static>, CliError> {
    let t0 = Instant::now();
    let h = case.hertz()?;
    let totals = StepReport::closed_form(hertz_totals(&h), t0.elapsed().as_secs_f64());
    Ok(Report {
        model: Model::Hertz,
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
pub(crate) fn solve_fastsim(case: &Case) -> Result<Report<'static>, CliError> {
    let t0 = Instant::now();
    let h = case.hertz()?;
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
    let totals = Totals {
        fx_n: out.fx_n,
        fy_n: out.fy_n,
        mz_nm: out.mz_nm,
        adhesion_fraction: out.adhesion_fraction,
        tgamma_n: out.tgamma_n,
        max_traction_pa: out.max_traction_pa,
        ..hertz_totals(&h)
    };
    Ok(Report {
        model: Model::Fastsim,
        totals: StepReport::closed_form(totals, t0.elapsed().as_secs_f64()),
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
