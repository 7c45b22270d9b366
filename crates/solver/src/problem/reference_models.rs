//! The reference models of `railcontact solve`: `model = "hertz"` (closed
//! form, normal problem only), `model = "hertz_corrected"` (Hertz with the
//! corrected lateral curvature of conformal contact) and `model =
//! "fastsim"` (Kalker's simplified theory on the Hertz ellipse), and the
//! Hertz semi-axes that size the automatic windows.

use std::time::Instant;

use crate::conformal::solve::conformal_hertz;
use crate::core::error::ContactError;
use crate::core::fastrip::GridSimplified;
use crate::core::fastsim::{Fastsim, FastsimInput, SlopeReduction, TractionBound};
use crate::core::fastsim_grid::{
    BoundScaling, CreepInterpolation, GridFastsimInput, GridFlexibility, GridFriction,
    GridPressure, RollingSense,
};
use crate::core::grid::Grid;
use crate::core::hertz::{hertz, HertzLoad, HertzSolution};
use crate::core::normal::NormalLoad;
use crate::core::solution::Totals;
use crate::problem::case::{Case, FastsimDiscretisation, FastsimMethod, FastsimOptions, Model};
use crate::problem::report::{ConformalKeys, Report, StepReport};
use crate::problem::CaseError;

fn hertz_load(load: NormalLoad) -> HertzLoad {
    match load {
        NormalLoad::NormalForce(f) => HertzLoad::NormalForce { normal_force_n: f },
        NormalLoad::Approach(d) => HertzLoad::Approach { approach_m: d },
    }
}

/// Hertz solution of h = A x² + B y² under `load`; errors name the load's
/// key (`load.normal_force_n`, `load.approach_m`) and the model.
pub fn hertz_of(
    a_per_m: f64,
    b_per_m: f64,
    e_star_pa: f64,
    load: NormalLoad,
) -> Result<HertzSolution, CaseError> {
    // Hertz rejects only inputs, of which the load is the one that varies
    // between solves of a case (session steps, Jacobian columns).
    let key = match load {
        NormalLoad::NormalForce(_) => "load.normal_force_n",
        NormalLoad::Approach(_) => "load.approach_m",
    };
    hertz(a_per_m, b_per_m, e_star_pa, hertz_load(load))
        .map_err(|e| CaseError::BadInput(format!("invalid input `{key}`: Hertz model: {e}")))
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

/// What the Hertz models do not compute.
const NOTE_HERTZ: &str = "the Hertz model solves the normal problem only: fx_n, fy_n, mz_nm, max_traction_pa, adhesion_fraction and tgamma_n are not computed (reported as 0)";

/// Model `hertz`: Hertz's closed-form normal solution.
pub fn solve_hertz(case: &Case) -> Result<Report<'static>, CaseError> {
    let t0 = Instant::now();
    let h = case.hertz()?;
    let totals = StepReport::closed_form(hertz_totals(&h), t0.elapsed().as_secs_f64());
    Ok(closed_form_report(
        Model::Hertz,
        totals,
        vec![NOTE_HERTZ.to_string()],
    ))
}

/// The report of a closed-form model: its totals and notes, no grid,
/// fields or per-step parts.
fn closed_form_report(model: Model, totals: StepReport, notes: Vec<String>) -> Report<'static> {
    Report {
        model,
        totals,
        friction_coefficient: 0.0,
        fastsim_max_pressure_pa: None,
        grid: None,
        window_m: None,
        wfric_lateral: None,
        notes,
        steady_start: None,
        steps: None,
        fields: None,
        geometry: None,
        force_control: None,
        subsurface: None,
        temperature: None,
        interfacial_layer: None,
    }
}

/// What the FASTSIM model reports, and which pressure.
pub const NOTE_FASTSIM: &str = "normal quantities from Hertz; tangential from FASTSIM (Kalker's simplified theory); max_pressure_pa is Hertz's p0 = 3 Fn / (2 pi a b); FASTSIM's traction bound mu p uses the parabolic pressure of the simplified theory, whose maximum 2 Fn / (pi a b) = 4/3 p0 is fastsim_max_pressure_pa (the maximum pressure CONTACT's FASTSIM reports)";

/// The same with the elliptic bound (`fastsim.traction_bound`).
pub const NOTE_FASTSIM_ELLIPTIC: &str = "normal quantities from Hertz; tangential from the simplified theory; max_pressure_pa is Hertz's p0 = 3 Fn / (2 pi a b); the traction bound mu p uses Hertz's elliptic pressure, whose maximum p0 on the elements is fastsim_max_pressure_pa (the maximum pressure CONTACT reports with B = 2)";

/// On CONTACT's grid (`fastsim.discretisation = "grid"`).
pub const NOTE_FASTSIM_GRID: &str = "on the grid: the bound's pressure at the element centres, not rescaled (CONTACT's), fastsim_max_pressure_pa its largest element value; contact_area_m2 is Hertz's, adhesion_fraction the elements'; Kalker's coefficients read from his table as CONTACT reads them (linear in min(a/b, b/a))";

/// Model `fastsim`: the Hertz ellipse, then the simplified theory with the
/// case's creepages, as `[fastsim]` chooses ([`FastsimOptions`]): on
/// strips ([`Fastsim`]) or on CONTACT's grid
/// ([`GridSimplified`]: FASTSIM or FaStrip).
pub fn solve_fastsim(case: &Case) -> Result<Report<'static>, CaseError> {
    let t0 = Instant::now();
    let h = case.hertz()?;
    let o = case.fastsim;
    let (out, grid_note) = match o.discretisation {
        FastsimDiscretisation::Strips => (fastsim_on_strips(case, &h, &o)?, None),
        FastsimDiscretisation::Grid => {
            let (out, note) = fastsim_on_grid(case, &h, &o)?;
            (out, Some(note))
        }
    };
    let totals = out.totals;
    let mut notes = vec![match o.bound {
        TractionBound::Parabolic => NOTE_FASTSIM.to_string(),
        TractionBound::Elliptic => NOTE_FASTSIM_ELLIPTIC.to_string(),
    }];
    notes.push(o.describe(case.nx, case.ny));
    let window_m = match grid_note {
        Some(counts) => {
            notes.push(NOTE_FASTSIM_GRID.to_string());
            notes.push(counts);
            Some([
                2.0 * o.window_scale * h.semi_axis_x_m,
                2.0 * o.window_scale * h.semi_axis_y_m,
            ])
        }
        None => None,
    };
    let totals = StepReport::closed_form(totals, t0.elapsed().as_secs_f64());
    Ok(Report {
        friction_coefficient: out.friction_coefficient,
        fastsim_max_pressure_pa: Some(out.bound_peak_pa),
        grid: Some([case.nx, case.ny]),
        window_m,
        ..closed_form_report(Model::Fastsim, totals, notes)
    })
}

/// What one FASTSIM variant gives: Hertz's normal totals with its
/// tangential ones, the bound's peak pressure \[Pa\] and the friction
/// coefficient [-].
struct FastsimTotals {
    totals: Totals,
    bound_peak_pa: f64,
    friction_coefficient: f64,
}

/// FASTSIM on `case.ny` strips of the Hertz ellipse `h`.
fn fastsim_on_strips(
    case: &Case,
    h: &HertzSolution,
    o: &FastsimOptions,
) -> Result<FastsimTotals, CaseError> {
    let c = case.creepages();
    let input = FastsimInput {
        semi_axis_x_m: h.semi_axis_x_m,
        semi_axis_y_m: h.semi_axis_y_m,
        normal_force_n: h.normal_force_n,
        shear_modulus_pa: case.material.shear_modulus_pa,
        poisson_ratio: case.material.poisson_ratio,
        friction_coefficient: case.friction.kinetic_coefficient,
        static_friction_coefficient: case.friction.static_coefficient,
        creepage_long: c.creepage_long,
        creepage_lat: c.creepage_lat,
        spin_per_m: c.spin_per_m,
    };
    let mut fastsim = Fastsim::new(case.nx, case.ny)
        .map_err(|e| CaseError::BadInput(format!("invalid input `grid`: FASTSIM: {e}")))?;
    fastsim.set_traction_bound(o.bound);
    let out = if o.reduction == SlopeReduction::NONE {
        fastsim.solve(&input)
    } else {
        fastsim.solve_modified(&input, o.rolling_speed_m_per_s, &o.reduction)
    }
    .map_err(|e| CaseError::BadInput(format!("FASTSIM model: {e}")))?;
    let friction_coefficient = if o.has_falling_friction() {
        let w = o.rolling_speed_m_per_s * c.creepage_long.hypot(c.creepage_lat);
        case.friction.kinetic_coefficient * o.reduction.friction_factor(w)
    } else {
        case.friction.kinetic_coefficient
    };
    Ok(FastsimTotals {
        totals: Totals {
            fx_n: out.fx_n,
            fy_n: out.fy_n,
            mz_nm: out.mz_nm,
            adhesion_fraction: out.adhesion_fraction,
            tgamma_n: out.tgamma_n,
            max_traction_pa: out.max_traction_pa,
            ..hertz_totals(h)
        },
        bound_peak_pa: out.bound_peak_pressure_pa,
        friction_coefficient,
    })
}

/// FASTSIM or FaStrip on CONTACT's grid of `case.nx` x `case.ny` elements
/// over `o.window_scale` times the Hertz ellipse `h`; the second value
/// names the element counts.
fn fastsim_on_grid(
    case: &Case,
    h: &HertzSolution,
    o: &FastsimOptions,
) -> Result<(FastsimTotals, String), CaseError> {
    let (a, b) = (h.semi_axis_x_m, h.semi_axis_y_m);
    let grid = Grid::centered(
        case.nx,
        case.ny,
        2.0 * o.window_scale * a,
        2.0 * o.window_scale * b,
    )?;
    let c = case.creepages();
    let input = GridFastsimInput {
        semi_axis_x_m: a,
        semi_axis_y_m: b,
        normal_force_n: h.normal_force_n,
        shear_modulus_pa: case.material.shear_modulus_pa,
        poisson_ratio: case.material.poisson_ratio,
        creepage_long: c.creepage_long,
        creepage_lat: c.creepage_lat,
        spin_per_m: c.spin_per_m,
        rolling_speed_m_per_s: o.rolling_speed_m_per_s,
        friction: GridFriction::Coulomb(case.friction.kinetic_coefficient),
        reduction: o.reduction,
        flexibility: match o.flexibility_m_per_pa {
            Some(l) => GridFlexibility::Given {
                flexibility_m_per_pa: l,
            },
            None => GridFlexibility::Kalker { blending: true },
        },
        rolling: if case.rolling_direction_rad == 0.0 {
            RollingSense::PlusX
        } else {
            RollingSense::MinusX
        },
        creep_table: CreepInterpolation::Contact,
    };
    let pressure = GridPressure::Hertz {
        bound: o.bound,
        scaling: BoundScaling::Analytic,
    };
    let solve_error = |e: ContactError| CaseError::BadInput(format!("FASTSIM model: {e}"));
    let out = GridSimplified::new(grid, o.method == FastsimMethod::Fastrip)?
        .solve(&input, pressure)
        .map_err(solve_error)?;
    let da = grid.element_area_m2();
    let count = |area: f64| (area / da).round() as u64;
    let counts = format!(
        "elements: {} in contact, {} in adhesion, {} in slip (of {} x {}, {:.4e} m x {:.4e} m each)",
        count(out.contact_area_m2),
        count(out.adhesion_area_m2),
        count(out.slip_area_m2),
        grid.nx,
        grid.ny,
        grid.dx_m,
        grid.dy_m
    );
    let adhesion_fraction = if out.contact_area_m2 > 0.0 {
        out.adhesion_area_m2 / out.contact_area_m2
    } else {
        0.0
    };
    Ok((
        FastsimTotals {
            totals: Totals {
                fx_n: out.fx_n,
                fy_n: out.fy_n,
                mz_nm: out.mz_nm,
                adhesion_fraction,
                tgamma_n: out.tgamma_n,
                max_traction_pa: out.max_traction_pa,
                ..hertz_totals(h)
            },
            bound_peak_pa: out.max_pressure_pa,
            friction_coefficient: out.friction_coefficient,
        },
        counts,
    ))
}

/// Models `hertz` (`corrected` false) and `hertz_corrected` on circular
/// conformal profiles: the paper's Hertz solution on the flattened
/// curvatures A = 1/(2 R_xw), B = (1/R_yr + 1/R_yw)/2, and with the
/// corrected B_corr = B + d/(2 r²) (Blanco-Lorenzo et al. 2018, Eq. 5).
/// The contact angle variation is 2 b / r, r the mean lateral radius.
pub fn solve_conformal_hertz(case: &Case, corrected: bool) -> Result<Report<'static>, CaseError> {
    let t0 = Instant::now();
    let (rail, wheel, rolling) = case.geometry.radii().ok_or_else(|| {
        CaseError::BadInput(format!(
            "invalid input `model`: \"{}\" on conformal profiles needs `geometry.kind = \"conformal_circular\"`",
            case.model.name()
        ))
    })?;
    let r = case.geometry.mean_lateral_radius_m();
    let (h, variation_deg) = match case.load {
        NormalLoad::NormalForce(f) => {
            conformal_hertz(rail, wheel, rolling, &case.material, f, corrected)
                .map_err(|e| CaseError::BadInput(format!("Hertz model: {e}")))?
        }
        NormalLoad::Approach(_) if !corrected => {
            let h = case.hertz()?;
            let v = (2.0 * h.semi_axis_y_m / r).to_degrees();
            (h, v)
        }
        NormalLoad::Approach(_) => {
            return Err(CaseError::BadInput(
                "invalid input `load.approach_m`: the hertz_corrected model starts from a normal force: give `load.normal_force_n`".into(),
            ))
        }
    };
    let totals = hertz_totals(&h);
    let mut step = StepReport::closed_form(totals, t0.elapsed().as_secs_f64());
    step.conformal = Some(ConformalKeys {
        contact_angle_variation_deg: variation_deg,
        length_width_ratio: h.semi_axis_x_m / h.semi_axis_y_m,
        normal_force_from_tractions_n: 0.0,
        pressure_resultant_n: h.normal_force_n,
        // Circular profiles touch with a lateral tangent: n(0) is +z.
        fy_global_n: 0.0,
        fz_global_n: h.normal_force_n,
        coupling_iterations: None,
    });
    let flattened = format!(
        "Hertz on the flattened curvatures A = 1/(2 R_xw) = {:.6} 1/m, B = (1/R_yr + 1/R_yw)/2 = {:.6} 1/m",
        case.a_per_m, case.b_per_m
    );
    let mut notes = vec![NOTE_HERTZ.to_string()];
    if corrected {
        notes.push(format!(
            "{flattened}, B corrected to B + d/(2 r²) with d the plain Hertz approach and r = {:.4} mm the mean lateral radius (Blanco-Lorenzo et al. 2018, Eq. 5)",
            r * 1e3
        ));
    } else {
        notes.push(flattened);
    }
    notes.push("contact_angle_variation_deg = 2 b / r (b the lateral semi-axis)".to_string());
    Ok(Report {
        model: case.model,
        totals: step,
        friction_coefficient: 0.0,
        fastsim_max_pressure_pa: None,
        grid: None,
        window_m: None,
        wfric_lateral: None,
        notes,
        steady_start: None,
        steps: None,
        fields: None,
        geometry: Some(case.geometry.describe()),
        force_control: None,
        subsurface: None,
        temperature: None,
        interfacial_layer: None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Model `fastsim` reports both maxima, named: Hertz's p0 in the
    /// totals and FASTSIM's parabolic bound's peak 2 Fn/(pi a b) = 4/3 p0
    /// in `fastsim_max_pressure_pa` (within the bound's discrete scaling,
    /// O(1/n²) on 24 x 24), in the JSON and the summary; the other models
    /// have no such number.
    #[test]
    fn fastsim_reports_hertz_p0_and_its_bound_peak() {
        let case = |model: &str| {
            Case::from_toml(&format!(
                "model = \"{model}\"\n[material]\nshear_modulus_pa = 81.0e9\npoisson_ratio = 0.3\n\
                 [friction]\ncoefficient = 0.3\n[geometry]\nkind = \"quadratic\"\na_per_m = 2.6\n\
                 b_per_m = 0.92\n[load]\nnormal_force_n = 1e4\n[rolling]\ncreepage_long = 1e-3\n\
                 [grid]\nnx = 24\nny = 24\n"
            ))
            .unwrap()
        };
        let r = solve_fastsim(&case("fastsim")).unwrap();
        let h = case("fastsim").hertz().unwrap();
        let p0 = h.max_pressure_pa;
        let pi = std::f64::consts::PI;
        let parabolic = 2.0 * h.normal_force_n / (pi * h.semi_axis_x_m * h.semi_axis_y_m);
        assert_eq!(r.totals.totals.max_pressure_pa, p0);
        let peak = r.fastsim_max_pressure_pa.expect("FASTSIM's bound peak");
        assert!(
            (peak / parabolic - 1.0).abs() < 2e-3,
            "{peak} vs {parabolic}"
        );
        assert!((peak / p0 - 4.0 / 3.0).abs() < 3e-3, "{peak} vs {p0}");
        let json = serde_json::to_value(&r).unwrap();
        assert_eq!(json["fastsim_max_pressure_pa"].as_f64(), Some(peak));
        assert!(r.human().contains("FASTSIM bound max p [MPa]"));
        let hertz = solve_hertz(&case("hertz")).unwrap();
        assert!(hertz.fastsim_max_pressure_pa.is_none());
        let json = serde_json::to_value(&hertz).unwrap();
        assert!(json.get("fastsim_max_pressure_pa").is_none());
    }

    /// On strips, the modified FASTSIM with k0 alone (alpha_inf = 1)
    /// divides every flexibility by k0: in full adhesion (xi = 1e-7) the
    /// force is k0 times Kalker's. The elliptic bound leaves that force
    /// alone, and its peak tends to Hertz's p0 as the strips refine.
    #[test]
    fn strips_take_the_slope_reduction_and_the_elliptic_bound() {
        let case = |n: usize, section: &str| {
            Case::from_toml(&format!(
                "model = \"fastsim\"\n[material]\nshear_modulus_pa = 81.0e9\npoisson_ratio = 0.3\n\
                 [friction]\ncoefficient = 0.3\n[geometry]\nkind = \"quadratic\"\na_per_m = 2.6\n\
                 b_per_m = 0.92\n[load]\nnormal_force_n = 1e4\n[rolling]\ncreepage_long = 1e-7\n\
                 [grid]\nnx = {n}\nny = {n}\n{section}"
            ))
            .unwrap()
        };
        let plain = solve_fastsim(&case(24, "")).unwrap();
        let reduced = solve_fastsim(&case(24, "[fastsim]\ninitial_factor = 0.54\n")).unwrap();
        let ratio = reduced.totals.totals.fx_n / plain.totals.totals.fx_n;
        assert!((ratio - 0.54).abs() < 1e-12, "{ratio}");
        assert!(reduced.notes.iter().any(|n| n.contains("k0 = 0.54")));
        let elliptic = "[fastsim]\ntraction_bound = \"elliptic\"\n";
        let coarse = solve_fastsim(&case(24, elliptic)).unwrap();
        assert_eq!(coarse.totals.totals.fx_n, plain.totals.totals.fx_n);
        let deviation = |n: usize| {
            let r = solve_fastsim(&case(n, elliptic)).unwrap();
            r.fastsim_max_pressure_pa.unwrap() / r.totals.totals.max_pressure_pa - 1.0
        };
        // Measured -3.5e-3, -3.8e-4, -4.5e-5: the scaling's error, like
        // n^-1.5.
        let (d24, d96, d384) = (deviation(24), deviation(96), deviation(384));
        assert!(d384.abs() < d96.abs() && d96.abs() < d24.abs());
        assert!(d384.abs() < 1e-4, "{d24} {d96} {d384}");
    }
}
