//! Solving conformal contact problems: the frictionless normal problem with
//! the conformal operators, and the Hertz-based reference models of the
//! paper (Hertz, and Hertz with the corrected lateral curvature, Eq. 5).

use std::sync::Arc;

use crate::conformal::geometry::ConformalGeometry;
use crate::conformal::operator::{ConformalOperator, InfluenceModel};
use crate::core::cache::KernelCache;
use crate::core::cancel;
use crate::core::error::ContactError;
use crate::core::hertz::{hertz, HertzLoad, HertzSolution};
use crate::core::influence::KernelKind;
use crate::core::material::CombinedMaterial;
use crate::core::normal::{solve_normal_with, NormalLoad, NormalScratch, NormalSettings};

/// Summary of a conformal normal solution. Lengths are curvilinear.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ConformalNormalSummary {
    /// Resultant of the pressures along the approach direction n(0) \[N\].
    pub normal_force_n: f64,
    /// Rigid approach along n(0) \[m\].
    pub approach_m: f64,
    /// Largest pressure \[Pa\].
    pub max_pressure_pa: f64,
    /// Loaded area (curvilinear) \[m²\].
    pub contact_area_m2: f64,
    /// Extent of the loaded elements along x \[m\].
    pub patch_length_m: f64,
    /// Extent of the loaded elements along s \[m\].
    pub patch_width_m: f64,
    /// Total variation of the contact angle over the patch \[deg\].
    pub contact_angle_variation_deg: f64,
    /// CG iterations.
    pub iterations: usize,
    /// FFT products.
    pub matvecs: usize,
    /// Whether the solver met its tolerance.
    pub converged: bool,
}

/// A frictionless conformal solution: the summary and the pressures.
#[derive(Debug, Clone, PartialEq)]
pub struct ConformalNormalSolution {
    /// Totals.
    pub summary: ConformalNormalSummary,
    /// Pressure per element \[Pa\].
    pub pressure_pa: Vec<f64>,
}

/// Solves the frictionless normal problem of `geometry` with the chosen
/// influence coefficients. `load` is the force along, or the approach
/// along, the normal at the rigid contact point.
pub fn solve_frictionless(
    geometry: &ConformalGeometry,
    material: &CombinedMaterial,
    model: InfluenceModel,
    load: NormalLoad,
    settings: &NormalSettings,
    cache: &KernelCache,
) -> Result<ConformalNormalSolution, ContactError> {
    let grid = geometry.grid;
    let kernels: Arc<_> = cache.get(&grid, material, KernelKind::Displacement);
    let mut op = ConformalOperator::new(kernels, model, &geometry.delta_rad);
    let n = grid.len();
    if let NormalLoad::Approach(d) = load {
        let touches = (0..n).any(|i| geometry.gap_m[i] < d * geometry.approach_weight[i]);
        if !touches {
            return Err(ContactError::NoContact {
                detail: format!("the approach {d:e} m closes no gap"),
            });
        }
    }
    let mut pn = vec![0.0; n];
    let mut scratch = NormalScratch::new(n);
    let area = grid.element_area_m2();
    let out = solve_normal_with(
        &mut op,
        &geometry.gap_m,
        Some(&geometry.approach_weight),
        area,
        load,
        &mut pn,
        &mut scratch,
        settings,
    );
    cancel::check()?;
    let (mut force, mut pmax, mut count) = (0.0, 0.0f64, 0usize);
    for iy in 0..grid.ny {
        for ix in 0..grid.nx {
            let i = grid.index(ix, iy);
            if pn[i] > 0.0 {
                if grid.on_border(ix, iy) {
                    return Err(border_error(&grid, ix, iy));
                }
                count += 1;
                force += pn[i] * geometry.approach_weight[i] * area;
                pmax = pmax.max(pn[i]);
            }
        }
    }
    let [length, width] = grid
        .loaded_extent_m(&pn)
        .ok_or_else(|| ContactError::NoContact {
            detail: "no element is loaded".into(),
        })?;
    let summary = ConformalNormalSummary {
        normal_force_n: force,
        approach_m: out.approach_m,
        max_pressure_pa: pmax,
        contact_area_m2: count as f64 * area,
        patch_length_m: length,
        patch_width_m: width,
        contact_angle_variation_deg: geometry.contact_angle_variation_rad(&pn).to_degrees(),
        iterations: out.iterations,
        matvecs: out.matvecs,
        converged: out.converged,
    };
    Ok(ConformalNormalSolution {
        summary,
        pressure_pa: pn,
    })
}

/// The error for a loaded element (ix, iy) on the border of the (x, s) grid.
pub fn border_error(grid: &crate::core::grid::Grid, ix: usize, iy: usize) -> ContactError {
    ContactError::grid_too_small(ix, iy, grid.nx, grid.x_m(ix), grid.y_m(iy))
}

/// Hertz's solution for two circular profiles and a wheel rolling radius
/// (rail straight along x), as the paper uses it (§3.1): curvatures
/// A = 1/(2 R_xw), B = (1/R_yr + 1/R_yw)/2 (convex positive), and, when
/// `corrected`, B_corr = B + d/(2 r²) (Eq. 5) with d the plain Hertz
/// approach and r = (|R_yr| + |R_yw|)/2 the mean lateral radius. The
/// contact angle variation is 2b/r. Returns the solution and the variation
/// \[deg\].
pub fn conformal_hertz(
    rail_lateral_radius_m: f64,
    wheel_lateral_radius_m: f64,
    wheel_rolling_radius_m: f64,
    material: &CombinedMaterial,
    normal_force_n: f64,
    corrected: bool,
) -> Result<(HertzSolution, f64), ContactError> {
    let a = 0.5 / wheel_rolling_radius_m;
    let b = 0.5 * (1.0 / rail_lateral_radius_m + 1.0 / wheel_lateral_radius_m);
    let estar = material.effective_modulus_pa();
    let load = HertzLoad::NormalForce { normal_force_n };
    let reference = |e: crate::core::hertz::HertzError| ContactError::Reference(e.to_string());
    let mut h = hertz(a, b, estar, load).map_err(reference)?;
    let r = 0.5 * (rail_lateral_radius_m.abs() + wheel_lateral_radius_m.abs());
    if corrected {
        let b_corr = b + h.approach_m / (2.0 * r * r);
        h = hertz(a, b_corr, estar, load).map_err(reference)?;
    }
    let variation = (2.0 * h.semi_axis_y_m / r).to_degrees();
    Ok((h, variation))
}
