//! Modified FaStrip on a rectangular potential contact grid: CONTACT's
//! `M = 5`, steady rolling.
//!
//! FaStrip (O. Sichani, R. Enblom, M. Berg, "An alternative to FASTSIM for
//! tangential solution of the wheel-rail contact", Vehicle System Dynamics
//! 54 (2016) 748-764) solves each strip `y = const` of the contact area with
//! Kalker's strip theory (J. J. Kalker, "Rolling with slip and spin in the
//! presence of dry friction", Wear 9 (1966) 20-38), its creepages scaled by
//! Kalker's linear-theory coefficients. E. Vollebregt's "modified FaStrip"
//! (CONTACT's `M = 5`; "Modified Fastsim and FaStrip", the user guide's
//! "Flexibilities of the simplified theory", and Vollebregt 2025, the
//! "indicators" paper) combines it with the modified FASTSIM of
//! [`crate::core::fastsim_grid`]: the slip area's traction direction is
//! FASTSIM's, the adhesion area's tractions are strip theory's. This module
//! is our reading of CONTACT's `src/m_solvpt.f90` (subroutines
//! `modif_fastrip` and `fastsim_params`) and `src/m_hertz.f90`
//! (`equiv_ellipse`); its totals agree with CONTACT's to rounding
//! (`examples/fastsim.inp` cases 4 and 7, the unit tests).
//!
//! [`crate::core::strip`] is a different strip theory (its own spin terms,
//! continuous strips of the Hertz ellipse); this one is CONTACT's, on the
//! elements of a [`Grid`].
//!
//! # Notation
//!
//! | symbol | meaning | unit |
//! |---|---|---|
//! | `a_e`, `b_e` | semi-axes of the contact elements' equivalent ellipse ([`crate::core::fastsim_grid::equivalent_ellipse`]) | m |
//! | `C11`, `C22`, `C23` | Kalker's coefficients at `a_e/b_e` ([`CreepInterpolation`] of the input) | - |
//! | `p_m` | `3 Fn/(2 pi a_e b_e)`, the strip theory's peak pressure | Pa |
//! | `mu` | the static friction coefficient (CONTACT's `fstat`) | - |
//! | `xi'`, `eta'`, `phi'` | the strip theory's creepages (below) | - |
//! | `a_j` | half the length of the contact elements of row `j` | m |
//! | `d_j` | half the length of row `j`'s slip zone (strip theory) | m |
//!
//! # The scheme (CONTACT's)
//!
//! 1. **FASTSIM**: the march of [`crate::core::fastsim_grid`] (same pressure,
//!    flexibilities, blending and slope reduction `k`) with the bound
//!    `mu pn`, `mu` the **static** coefficient for every element (with a
//!    slip-velocity law the slope reduction still uses the coefficient at
//!    the global slip velocity, as CONTACT's `fastsim_params` does).
//! 2. **Strip creepages** of the equivalent ellipse: `xi' = -G 4 (1 - nu)
//!    C11 xi/(2 mu p_m pi^2)`, `eta' = -G 4 (1 - nu) C22 eta/(2 mu p_m
//!    pi^2)`, `phi' = -G 3 sqrt(a_e b_e) C23 phi/(2 mu p_m pi)`.
//! 3. **Per row** `j` at `y_j`: `a_j` from the outer edges of its contact
//!    elements, and the slip zone's half length `d_j = (sqrt(D) + eta' phi')
//!    a_e/((1 - phi'^2)(1 - nu))` with `D = eta'^2 + (1 - phi'^2)(xi' - phi'
//!    y_j/a_e)^2`. The row slides fully (`d_j` unused) when `phi' = 1`
//!    (within `1e-6`), `D < 0`, `d_j < 0` or `d_j` is not finite (CONTACT
//!    stops on a NaN there).
//! 4. **Strip tractions**: with `u = xi' - phi' y_j/a_e`, `v = eta' + phi'
//!    d_j/a_e`, `kappa = u/r`, `lambda = v/r`, `r = sqrt(max(1e-20, u^2 +
//!    v^2))`, `lambda' = lambda - phi'`, the elements of the row at `x >
//!    -a_j + 2 d_j` (the adhesion zone) get `f = (kappa (S_c - S_a), lambda
//!    S_c - lambda' S_a)`, `S_c = sqrt(max(0, a_j^2 - x^2))/a_e`, `S_a =
//!    sqrt(max(0, (a_j - d_j)^2 - (x - d_j)^2))/a_e`. If `|f| <= 1` on every
//!    one of them, they are in adhesion with `p = mu p_m f`, and the row's
//!    other contact elements slip with FASTSIM's traction scaled onto the
//!    bound `mu pn` in its own direction (`|p|` taken at least `1e-4` Pa,
//!    CONTACT's `1e-10` N/mm^2); otherwise the row keeps FASTSIM's solution.
//!
//! The slope reduction `k` acts through FASTSIM only: strip theory's
//! adhesion tractions do not depend on the flexibilities, and the slip
//! zone takes only FASTSIM's direction. With one creepage `xi` or `eta`
//! that direction is the creepage's, so `k0`, `alpha_inf`, `beta` change
//! nothing (CONTACT's library gives the same); with spin, and in rows where
//! strip theory is rejected, they do.
//!
//! As in CONTACT the strip formulas take the row centred at `x = 0` (the
//! Hertzian patch on a grid centred on it) and its adhesion zone towards
//! `+x`, whatever the rolling direction: rolling along `-x`
//! ([`crate::core::fastsim_grid::RollingSense::MinusX`], `CHI = 180`
//! degrees) FASTSIM marches from
//! `-x` but the strip part keeps the adhesion zone at `+x`, the trailing
//! edge, so with spin the results are not the mirror image of `+x`'s
//! (CONTACT's library on `fastsim.inp`'s ellipse, `eta = -0.000625`, `phi =
//! -0.625/m` along `-x`: `FY = -16327 N`, all elements sliding, against
//! `FY = -15829 N` with the spin and direction reversed). Longitudinal
//! creepage alone gives the mirrored totals (CONTACT's library: `FX =
//! 11705.69 N` for `xi = -0.001` along `-x`, `-11705.69 N` for `0.001`
//! along `+x`).
//!
//! The slip `s` is FASTSIM's where both FASTSIM and strip theory put an
//! element in slip, zero elsewhere, as CONTACT reports it: an element that
//! FASTSIM found sticking and strip theory puts in slip keeps FASTSIM's
//! zero slip (CONTACT computes no slip for it). The frictional power `-sum
//! p.s dA` is taken with those (CONTACT's `FRIC.POWER`).
//!
//! # Allocation
//!
//! [`GridFastrip::new`] allocates the buffers of the grid; a solve
//! allocates nothing.

use crate::core::creep::MIN_ASPECT_RATIO;
use crate::core::error::{show, ContactError};
use crate::core::fastsim::SlopeReduction;
use crate::core::fastsim_grid::{
    CreepInterpolation, GridFastsim, GridFastsimInput, GridFastsimOutput, GridPressure,
    MarchBuffers, MarchFriction,
};
use crate::core::grid::Grid;
use crate::core::solution::{ElementFields, ElementState};
use std::f64::consts::PI;

/// `phi'` this close to 1 slides every row (CONTACT's `1e-6`).
const FULL_SPIN_TOLERANCE: f64 = 1e-6;

/// The smallest traction magnitude a sliding row's FASTSIM traction is
/// divided by \[Pa\] (CONTACT's `1e-10` N/mm^2).
const MIN_TRACTION_PA: f64 = 1e-4;

/// The strip theory's quantities of one solve (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StripParameters {
    /// Semi-axes `a_e`, `b_e` of the equivalent ellipse \[m\].
    pub equivalent_semi_axes_m: [f64; 2],
    /// The strip theory's peak pressure `p_m = 3 Fn/(2 pi a_e b_e)` \[Pa\].
    pub peak_pressure_pa: f64,
    /// `xi'`, `eta'`, `phi'` [-].
    pub creepages: [f64; 3],
    /// Rows whose adhesion zone strip theory set [-].
    pub strip_rows: usize,
    /// Rows that kept FASTSIM's solution because a strip traction exceeded
    /// the bound [-].
    pub fastsim_rows: usize,
}

/// The simplified theory on a grid with its buffers, FASTSIM or FaStrip
/// (CONTACT's M = 2, 3 or 5), as one solver: the C library's module 3
/// patches and the wheel/rail exact patches' tangential part
/// (`ExactTangential::Fastsim`, `Fastrip`) drive it alike.
#[derive(Debug, Clone)]
pub enum GridSimplified {
    /// [`GridFastsim`].
    Fastsim(GridFastsim),
    /// [`GridFastrip`].
    Fastrip(GridFastrip),
}

impl GridSimplified {
    /// FaStrip's buffers on `grid` with `fastrip`, else FASTSIM's.
    pub fn new(grid: Grid, fastrip: bool) -> Result<Self, ContactError> {
        Ok(if fastrip {
            Self::Fastrip(GridFastrip::new(grid)?)
        } else {
            Self::Fastsim(GridFastsim::new(grid)?)
        })
    }

    /// Whether these are the buffers of FaStrip (`fastrip`) or FASTSIM
    /// on `grid`.
    pub fn fits(&self, grid: &Grid, fastrip: bool) -> bool {
        match self {
            Self::Fastsim(fs) => !fastrip && fs.grid() == grid,
            Self::Fastrip(fs) => fastrip && fs.grid() == grid,
        }
    }

    /// One solve's totals ([`GridFastsim::solve`], [`GridFastrip::solve`]).
    /// No allocation.
    pub fn solve(
        &mut self,
        input: &GridFastsimInput,
        pressure: GridPressure<'_>,
    ) -> Result<GridFastsimOutput, ContactError> {
        match self {
            Self::Fastsim(fs) => fs.solve(input, pressure),
            Self::Fastrip(fs) => fs.solve(input, pressure).map(|o| o.totals),
        }
    }

    /// The march whose buffers hold the last solve's fields (FaStrip's
    /// after its strip part).
    pub fn march(&self) -> &GridFastsim {
        match self {
            Self::Fastsim(fs) => fs,
            Self::Fastrip(fs) => fs.march(),
        }
    }
}

/// FaStrip bounds the tractions by the static coefficient: an error
/// naming `key` when `reduction` has falling friction of its own
/// ([`SlopeReduction::has_falling_friction`]).
pub fn require_static_bound(reduction: &SlopeReduction, key: &str) -> Result<(), ContactError> {
    if !reduction.has_falling_friction() {
        return Ok(());
    }
    Err(ContactError::invalid(
        key,
        format!(
            "FaStrip bounds the tractions by the static coefficient: the slope reduction's \
             falling friction (A = {}, B = {} s/m) must be off (A = 1 or B = 0)",
            show(reduction.friction_limit_ratio),
            show(reduction.friction_decay_s_per_m)
        ),
    ))
}

/// The totals of one FaStrip solve.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GridFastripOutput {
    /// The totals after the strip theory (the fields of
    /// [`GridFastsimOutput`]; `friction_coefficient` the static one).
    pub totals: GridFastsimOutput,
    /// The strip theory's quantities.
    pub strip: StripParameters,
}

/// Modified FaStrip on a potential contact grid with its per-element
/// buffers.
///
/// Element `(ix, iy)` is at index `iy * nx + ix` of every slice, as on the
/// [`Grid`]. Before the first solve every field is zero.
#[derive(Debug, Clone)]
pub struct GridFastrip {
    march: GridFastsim,
}

impl GridFastrip {
    /// A solver for `grid` (not a line contact's single row).
    pub fn new(grid: Grid) -> Result<Self, ContactError> {
        GridFastsim::new(grid)
            .map(|march| Self { march })
            .map_err(|e| e.with_key_prefix("grid", "fastrip.grid"))
    }

    /// The grid.
    pub fn grid(&self) -> &Grid {
        self.march.grid()
    }

    /// The pressure of the traction bound \[Pa\].
    pub fn pressure_pa(&self) -> &[f64] {
        self.march.pressure_pa()
    }

    /// The FASTSIM march whose buffers hold the last solve's fields (after
    /// the strip theory: its tractions, slips and states are this
    /// solver's).
    pub fn march(&self) -> &GridFastsim {
        &self.march
    }

    /// Longitudinal traction on body 1 \[Pa\].
    pub fn traction_x_pa(&self) -> &[f64] {
        self.march.traction_x_pa()
    }

    /// Lateral traction on body 1 \[Pa\].
    pub fn traction_y_pa(&self) -> &[f64] {
        self.march.traction_y_pa()
    }

    /// Longitudinal slip per unit rolled distance [-] (FASTSIM's where
    /// both methods slide, zero elsewhere; module docs).
    pub fn slip_x(&self) -> &[f64] {
        self.march.slip_x()
    }

    /// Lateral slip per unit rolled distance [-] (as
    /// [`GridFastrip::slip_x`]).
    pub fn slip_y(&self) -> &[f64] {
        self.march.slip_y()
    }

    /// The element states.
    pub fn state(&self) -> &[ElementState] {
        self.march.state()
    }

    /// The last solve's per-element fields, with the undeformed distance
    /// `gap_m` (empty: zeros).
    pub fn fields(&self, gap_m: Vec<f64>) -> ElementFields {
        self.march.fields(gap_m)
    }

    /// The rigid slip per element [-] the FASTSIM march used
    /// ([`GridFastsim::rigid_slip`]).
    pub fn rigid_slip(&self) -> [Vec<f64>; 2] {
        self.march.rigid_slip()
    }

    /// Solves one steady rolling problem with the traction bound of
    /// `pressure` (module docs). `input` is FASTSIM's; its
    /// `reduction` must have no falling friction of its own
    /// (`friction_limit_ratio` 1, `friction_decay_s_per_m` 0): the bound
    /// is the static coefficient. Errors name `fastrip.<field>`. No
    /// allocation.
    pub fn solve(
        &mut self,
        input: &GridFastsimInput,
        pressure: GridPressure<'_>,
    ) -> Result<GridFastripOutput, ContactError> {
        require_static_bound(&input.reduction, "fastrip.reduction.friction_limit_ratio")?;
        let fastsim = self
            .march
            .solve_with(input, pressure, MarchFriction::Static)
            .map_err(|e| e.with_key_prefix("fastsim", "fastrip"))?;
        let mu = fastsim.friction_coefficient;
        let fn_ = input.normal_force_n;
        let nu = input.poisson_ratio;
        let g_mod = input.shear_modulus_pa;
        let b = self.march.buffers_mut();
        let grid = b.grid;
        let [ae, be] = fastsim.equivalent_semi_axes_m;
        if ae <= 0.0 {
            // No contact element: FASTSIM's empty solution.
            return Ok(GridFastripOutput {
                totals: fastsim,
                strip: StripParameters::default(),
            });
        }
        let pm = 1.5 * fn_ / (PI * ae * be);
        let [c11, c22, c23] = strip_coefficients(input.creep_table, ae / be, nu);
        let scale = 2.0 * mu * pm;
        let xi_s = -g_mod * 4.0 * (1.0 - nu) * c11 * input.creepage_long / (scale * PI * PI);
        let eta_s = -g_mod * 4.0 * (1.0 - nu) * c22 * input.creepage_lat / (scale * PI * PI);
        let phi_s = -g_mod * 3.0 * (ae * be).sqrt() * c23 * input.spin_per_m / (scale * PI);
        let mut strip = StripParameters {
            equivalent_semi_axes_m: [ae, be],
            peak_pressure_pa: pm,
            creepages: [xi_s, eta_s, phi_s],
            strip_rows: 0,
            fastsim_rows: 0,
        };
        let dx = grid.dx_m;
        let bound = mu * pm;
        for iy in 0..grid.ny {
            let row = iy * grid.nx..(iy + 1) * grid.nx;
            // The row's contact length.
            let (mut xsta, mut xend) = (f64::INFINITY, f64::NEG_INFINITY);
            for ix in 0..grid.nx {
                if b.state[row.start + ix] != ElementState::Exterior {
                    let x = grid.x_m(ix);
                    xsta = xsta.min(x - 0.5 * dx);
                    xend = xend.max(x + 0.5 * dx);
                }
            }
            if xsta > xend {
                continue; // no contact element in this row
            }
            let aj = 0.5 * (xend - xsta);
            let y = grid.y_m(iy);
            let u = xi_s - phi_s * y / ae;
            // The slip zone's half length; None: the row slides.
            let dj = if (phi_s - 1.0).abs() <= FULL_SPIN_TOLERANCE {
                None
            } else {
                let disc = eta_s * eta_s + (1.0 - phi_s * phi_s) * u * u;
                let d = (disc.sqrt() + eta_s * phi_s) / (1.0 - phi_s * phi_s) * ae / (1.0 - nu);
                (disc >= 0.0 && d >= 0.0 && d.is_finite()).then_some(d)
            };
            let x_adh = dj.map_or(f64::INFINITY, |d| -aj + 2.0 * d);
            let d = dj.unwrap_or(0.0);
            let v = eta_s + phi_s * d / ae;
            let r = (u * u + v * v).max(1e-20).sqrt();
            let (kappa, lambda) = (u / r, v / r);
            let lambda_p = lambda - phi_s;
            let strip_traction = |x: f64| {
                let sc = (aj * aj - x * x).max(0.0).sqrt() / ae;
                let sa = ((aj - d) * (aj - d) - (x - d) * (x - d)).max(0.0).sqrt() / ae;
                (kappa * (sc - sa), lambda * sc - lambda_p * sa)
            };
            let within = (0..grid.nx)
                .filter(|&ix| {
                    b.state[row.start + ix] != ElementState::Exterior && grid.x_m(ix) > x_adh
                })
                .all(|ix| {
                    let (fx, fy) = strip_traction(grid.x_m(ix));
                    fx * fx + fy * fy <= 1.0
                });
            if !within {
                strip.fastsim_rows += 1;
                continue;
            }
            strip.strip_rows += 1;
            for ix in 0..grid.nx {
                let i = row.start + ix;
                if b.state[i] == ElementState::Exterior {
                    continue;
                }
                let x = grid.x_m(ix);
                if x > x_adh {
                    let (fx, fy) = strip_traction(x);
                    b.state[i] = ElementState::Adhesion;
                    (b.px[i], b.py[i]) = (bound * fx, bound * fy);
                    (b.sx[i], b.sy[i]) = (0.0, 0.0);
                } else {
                    b.state[i] = ElementState::Slip;
                    let mag = b.px[i].hypot(b.py[i]).max(MIN_TRACTION_PA);
                    let f = mu * b.pn[i] / mag;
                    (b.px[i], b.py[i]) = (b.px[i] * f, b.py[i] * f);
                }
            }
        }
        let totals = totals(&b, fastsim);
        if ![totals.fx_n, totals.fy_n, totals.mz_nm, totals.tgamma_n]
            .iter()
            .all(|v| v.is_finite())
        {
            return Err(ContactError::invalid(
                "fastrip.creepage_long",
                format!(
                    "creepages ({}, {}, {} 1/m) too large: the tractions overflow",
                    show(input.creepage_long),
                    show(input.creepage_lat),
                    show(input.spin_per_m)
                ),
            ));
        }
        Ok(GridFastripOutput { totals, strip })
    }
}

/// Kalker's `C11`, `C22`, `C23` of the equivalent ellipse, its `a/b` held
/// within the table's range.
fn strip_coefficients(table: CreepInterpolation, a_over_b: f64, nu: f64) -> [f64; 3] {
    let ratio = a_over_b.clamp(MIN_ASPECT_RATIO, 1.0 / MIN_ASPECT_RATIO);
    table
        .coefficients(ratio, nu)
        .expect("a/b is held within the table's range")
}

/// The totals of the rewritten fields; the pressure's, the friction
/// coefficient, the flexibilities and the equivalent ellipse from
/// FASTSIM's.
fn totals(b: &MarchBuffers<'_>, fastsim: GridFastsimOutput) -> GridFastsimOutput {
    let g = b.grid;
    let da = g.element_area_m2();
    let mut o = GridFastsimOutput {
        pressure_force_n: fastsim.pressure_force_n,
        max_pressure_pa: fastsim.max_pressure_pa,
        friction_coefficient: fastsim.friction_coefficient,
        applied: fastsim.applied,
        equivalent_semi_axes_m: fastsim.equivalent_semi_axes_m,
        ..GridFastsimOutput::default()
    };
    let (mut n_adh, mut n_slip) = (0usize, 0usize);
    let mut pmax2 = 0.0_f64;
    for iy in 0..g.ny {
        let y = g.y_m(iy);
        for ix in 0..g.nx {
            let i = g.index(ix, iy);
            match b.state[i] {
                ElementState::Exterior => continue,
                ElementState::Slip => n_slip += 1,
                _ => n_adh += 1,
            }
            let (px, py) = (b.px[i], b.py[i]);
            o.fx_n += px * da;
            o.fy_n += py * da;
            o.mz_nm += (g.x_m(ix) * py - y * px) * da;
            o.tgamma_n -= (px * b.sx[i] + py * b.sy[i]) * da;
            pmax2 = pmax2.max(px * px + py * py);
        }
    }
    o.max_traction_pa = pmax2.sqrt();
    o.adhesion_area_m2 = n_adh as f64 * da;
    o.slip_area_m2 = n_slip as f64 * da;
    o.contact_area_m2 = (n_adh + n_slip) as f64 * da;
    o
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::creep::kalker_linear_forces;
    use crate::core::fastsim::TractionBound;
    use crate::core::fastsim_grid::{BoundScaling, RollingSense};

    const ELLIPTIC: GridPressure<'static> = GridPressure::Hertz {
        bound: TractionBound::Elliptic,
        scaling: BoundScaling::Analytic,
    };

    /// CONTACT's `examples/fastsim.inp` cases 4 and 7: AA, BB = 8, 4 mm,
    /// n x n elements over 1.1 times the ellipse, FN = 82 kN, G = 82 GPa,
    /// nu = 0.28, FSTAT = 0.3, VELOC 30 m/s, B = 2, M = 5.
    fn fastsim_inp(n: usize, xi: f64, eta: f64, phi: f64) -> (GridFastrip, GridFastsimInput) {
        let grid = Grid::centered(n, n, 17.6e-3, 8.8e-3).unwrap();
        let input = crate::core::fastsim_grid::tests::input(8e-3, 4e-3, xi, eta, phi);
        (GridFastrip::new(grid).unwrap(), input)
    }

    fn count(fs: &GridFastrip, st: ElementState) -> usize {
        fs.state().iter().filter(|s| **s == st).count()
    }

    fn rel(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs()
    }

    /// CONTACT's numbers for `fastsim.inp` case 4 (44 x 44) and case 7
    /// (220 x 220), ETA = -0.000625, PHI = 0.000625 rad/mm: its library
    /// (`contact_addon_linux64.so`, CONTACT revision 2707) driven through
    /// `cntc_*` (`cntc_getcontactforces`, N and N mm;
    /// `cntc_getcontactpatchareas`). `fastsim.ref_out` prints them rounded:
    /// case 4 FY -1.583E+04, MZ -4.816E+04, FRIC.POWER -614.0 (W at 30
    /// m/s), NADH 626, NSLIP 638; case 7 FY -1.585E+04, MZ -4.757E+04,
    /// FRIC.POWER -668.1, NADH 15866, NSLIP 15562.
    #[test]
    fn contacts_fastsim_example_cases_4_and_7() {
        for (n, fy, mz_nmm, power_w, adh, slip) in [
            (
                44,
                -15829.428007966377,
                -48164.809410048954,
                -614.0,
                626,
                638,
            ),
            (
                220,
                -15846.662973532173,
                -47568.0724264622,
                -668.1,
                15866,
                15562,
            ),
        ] {
            let (mut fs, inp) = fastsim_inp(n, 0.0, -0.000625, 0.625);
            let o = fs.solve(&inp, ELLIPTIC).unwrap().totals;
            assert!(rel(o.fy_n, fy) < 1e-7, "{n}: FY {} vs {fy}", o.fy_n);
            assert!(rel(o.mz_nm * 1e3, mz_nmm) < 1e-7, "{n}: MZ {}", o.mz_nm);
            assert!(o.fx_n.abs() < 1e-9 * fy.abs());
            assert_eq!(
                (
                    count(&fs, ElementState::Adhesion),
                    count(&fs, ElementState::Slip)
                ),
                (adh, slip)
            );
            let p = -o.tgamma_n * 30.0;
            assert!((p - power_w).abs() < 0.05, "{n}: power {p} vs {power_w}");
        }
    }

    /// Rolling along -x with the spin reversed: CONTACT's strip part keeps
    /// its adhesion zone at +x (module docs), every element slides. Its
    /// library: FY = -16327.337767153876 N, MZ = 51138.971932769666 N mm,
    /// adhesion area 0, slip area 101.12 mm^2 (1264 elements).
    #[test]
    fn rolling_backwards_keeps_contacts_strip_orientation() {
        let (mut fs, inp) = fastsim_inp(44, 0.0, -0.000625, -0.625);
        let inp = GridFastsimInput {
            rolling: RollingSense::MinusX,
            ..inp
        };
        let o = fs.solve(&inp, ELLIPTIC).unwrap().totals;
        assert!(rel(o.fy_n, -16327.337767153876) < 1e-7, "{}", o.fy_n);
        assert!(rel(o.mz_nm * 1e3, 51138.971932769666) < 1e-7, "{}", o.mz_nm);
        assert_eq!(count(&fs, ElementState::Adhesion), 0);
        assert_eq!(count(&fs, ElementState::Slip), 1264);
    }

    /// Small creepage: Kalker's linear theory `Fx = -G c^2 C11 xi`, `Fy =
    /// -G c^2 C22 eta` (a/b = 2 is a row of Kalker's table: CONTACT's and
    /// the smooth coefficients agree there), approached as the grid is
    /// refined. The strip tractions vanish like a square root at the
    /// leading edge and the rows' lengths are whole elements: measured
    /// `Fx/Fx_lin - 1` = -6.09 % (44 x 44), -4.67 % (88), -2.72 % (220),
    /// -1.72 % (440), the same for `Fy` to 0.05 %; spin alone `phi = 1e-4/m`
    /// (`Fy = -G c^3 C23 phi`): +1.11, -0.03, +0.08, +0.02 %.
    #[test]
    fn small_creepage_approaches_the_linear_theory() {
        let lin =
            |xi, eta, phi| kalker_linear_forces(8e-3, 4e-3, 82e9, 0.28, xi, eta, phi).unwrap();
        let mut prev = f64::INFINITY;
        for (n, err, err_spin) in [
            (44, -0.0609, 0.0111),
            (88, -0.0467, -0.0003),
            (220, -0.0272, 0.0008),
            (440, -0.0172, 0.0002),
        ] {
            let (mut fs, inp) = fastsim_inp(n, 1e-6, 0.0, 0.0);
            let fx = fs.solve(&inp, ELLIPTIC).unwrap().totals.fx_n;
            let e = fx / lin(1e-6, 0.0, 0.0).fx_n - 1.0;
            assert!((e - err).abs() < 0.001, "{n}: {e}");
            assert!(e.abs() < prev);
            prev = e.abs();
            let (mut fs, inp) = fastsim_inp(n, 0.0, 1e-6, 0.0);
            let fy = fs.solve(&inp, ELLIPTIC).unwrap().totals.fy_n;
            let e_eta = fy / lin(0.0, 1e-6, 0.0).fy_n - 1.0;
            assert!((e_eta - e).abs() < 0.0005, "{n}: {e_eta} vs {e}");
            let (mut fs, inp) = fastsim_inp(n, 0.0, 0.0, 1e-4);
            let o = fs.solve(&inp, ELLIPTIC).unwrap().totals;
            let e_spin = o.fy_n / lin(0.0, 0.0, 1e-4).fy_n - 1.0;
            assert!((e_spin - err_spin).abs() < 0.0002, "{n}: {e_spin}");
            assert_eq!(count(&fs, ElementState::Slip), 0, "{n}");
        }
    }

    /// Large creepage: every row slides, `F = mu sum pn dA` in the
    /// direction of the creepage (CONTACT's pressure is not normalised, so
    /// not exactly `mu Fn`), whatever the slope reduction; along `-x` too.
    #[test]
    fn full_sliding_is_mu_times_the_grid_pressure() {
        let reduced = SlopeReduction {
            initial_factor: 0.54,
            limit_ratio: 0.02,
            transition_rate: 0.62,
            ..SlopeReduction::NONE
        };
        for (xi, eta, reduction, rolling) in [
            (0.05, 0.0, SlopeReduction::NONE, RollingSense::PlusX),
            (0.0, -0.05, reduced, RollingSense::PlusX),
            (0.03, 0.04, reduced, RollingSense::MinusX),
        ] {
            let (mut fs, inp) = fastsim_inp(44, xi, eta, 0.0);
            let inp = GridFastsimInput {
                reduction,
                rolling,
                ..inp
            };
            let o = fs.solve(&inp, ELLIPTIC).unwrap().totals;
            let sum: f64 = fs.pressure_pa().iter().sum::<f64>() * fs.grid().element_area_m2();
            let s = xi.hypot(eta);
            assert!(rel(o.fx_n, -0.3 * sum * xi / s) < 1e-12 || xi == 0.0);
            assert!(rel(o.fy_n, -0.3 * sum * eta / s) < 1e-12 || eta == 0.0);
            assert!(rel(sum, 82e3) < 1e-2);
            assert_eq!(count(&fs, ElementState::Adhesion), 0);
        }
    }

    /// The slope reduction scales FASTSIM's flexibilities only: with one
    /// creepage xi or eta strip theory sets every traction (its adhesion
    /// zone's by itself, the slip zone's direction is the creepage's), so
    /// k0, alpha, beta change nothing; with spin they turn the slip zone's
    /// tractions. CONTACT's library: `xi = 0.001` gives `FX = -11705.69 N`
    /// with and without (0.54, 0.02, 0.62); `fastsim.inp` case 4 with it
    /// `FY = -16711.962661680493 N`, `MZ = -44330.5667472003 N mm`,
    /// K_EFF = 0.3326120387336499 (without: -15829.43 N).
    #[test]
    fn slope_reduction_acts_through_fastsims_directions() {
        let reduced = SlopeReduction {
            initial_factor: 0.54,
            limit_ratio: 0.02,
            transition_rate: 0.62,
            ..SlopeReduction::NONE
        };
        let solve = |xi, eta, phi, reduction| {
            let (mut fs, inp) = fastsim_inp(44, xi, eta, phi);
            let inp = GridFastsimInput { reduction, ..inp };
            fs.solve(&inp, ELLIPTIC).unwrap().totals
        };
        let plain = solve(0.001, 0.0, 0.0, SlopeReduction::NONE);
        let red = solve(0.001, 0.0, 0.0, reduced);
        assert!(rel(red.fx_n, plain.fx_n) < 1e-14 && red.applied.slope_factor < 0.5);
        assert!(
            rel(plain.fx_n, -11705.693492681163) < 1e-7,
            "{}",
            plain.fx_n
        );
        let o = solve(0.0, -0.000625, 0.625, reduced);
        assert!(rel(o.fy_n, -16711.962661680493) < 1e-7, "{}", o.fy_n);
        assert!(rel(o.mz_nm * 1e3, -44330.5667472003) < 1e-7, "{}", o.mz_nm);
        assert!(rel(o.applied.slope_factor, 0.3326120387336499) < 1e-7);
    }

    /// Bad input names its field under `fastrip.`; the reduction's own
    /// falling friction is refused.
    #[test]
    fn bad_input_names_the_field() {
        let (mut fs, inp) = fastsim_inp(20, 0.001, 0.0, 0.0);
        let mut bad = inp;
        bad.poisson_ratio = 0.7;
        let e = fs.solve(&bad, ELLIPTIC).unwrap_err();
        assert!(e.to_string().contains("fastrip.poisson_ratio"), "{e}");
        let mut falling = inp;
        falling.reduction.friction_limit_ratio = 0.5;
        falling.reduction.friction_decay_s_per_m = 0.1;
        let e = fs.solve(&falling, ELLIPTIC).unwrap_err();
        assert!(
            e.to_string()
                .contains("fastrip.reduction.friction_limit_ratio"),
            "{e}"
        );
    }
}
