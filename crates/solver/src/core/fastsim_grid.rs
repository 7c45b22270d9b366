//! FASTSIM on a rectangular potential contact grid: the modified FASTSIM of
//! CONTACT's `M = 3` (Kalker's three flexibilities) and `M = 2` (one given
//! flexibility), steady rolling.
//!
//! [`crate::core::fastsim`] integrates Kalker's simplified theory on strips
//! of the Hertz ellipse and reproduces the linear theory exactly at small
//! creepage. This module solves the same theory the way E. Vollebregt's
//! CONTACT does for `M = 2, 3` (our reading of CONTACT's
//! `src/m_solvpt.f90`, subroutines `modif_fastsim` and `fastsim_params`,
//! `src/m_hertz.f90` `simpflex` and `equiv_ellipse`, `src/m_sdis.f90`
//! `set_tang_rhs` and `init_curr_data`, and its user guide, "Flexibilities
//! of the simplified theory"), on the elements of a [`Grid`], so that its
//! per-element tractions are CONTACT's and its totals agree with CONTACT's
//! to rounding.
//!
//! # Conventions
//!
//! Those of [`crate::core::fastsim`] and [`crate::core::problem`]: SI
//! units; tractions `p = (px, py)` on body 1; creepages `xi`, `eta` [-],
//! spin `phi` \[1/m\]; rigid slip `w = (xi - phi y, eta + phi x)`; slip
//! `s` of body 1 relative to body 2 per unit rolled distance, opposite to
//! the traction in slip. The patch rolls along `+x` ([`RollingSense::PlusX`],
//! CONTACT's `CHI = 0`: material enters at large `x`) or `-x`
//! ([`RollingSense::MinusX`], `CHI = 180` degrees).
//!
//! # The scheme (CONTACT's)
//!
//! * **Pressure** (the traction bound `mu pn`): [`GridPressure::Hertz`]
//!   evaluates at the element centres either Hertz's elliptic pressure
//!   (`B = 2`) `pn = p0 sqrt(1 - x^2/a^2 - y^2/b^2)`, `p0 = 3 Fn/(2 pi a b)`,
//!   or Kalker's parabolic one (`B = 3`) `pn = (2 Fn/(pi a b)) (1 - x^2/a^2 -
//!   y^2/b^2)`, and CONTACT does **not** normalise it on the grid
//!   ([`BoundScaling::Analytic`]): `sum pn dA` differs from `Fn` by the
//!   midpoint rule's error (`+0.008 %` on the 48 x 44 grid of CONTACT's
//!   `python_tractcurv.py`), so full sliding gives `mu sum pn dA`, not
//!   `mu Fn`. [`BoundScaling::NormalForce`] rescales the pressure so that
//!   `sum pn dA = Fn` instead. [`GridPressure::Given`] takes a pressure per
//!   element (`B = 0`: the exact normal problem's). Elements with `pn > 0`
//!   are in contact, the others exterior.
//! * **Flexibilities** ([`GridFlexibility::Kalker`], `M = 3`): Kalker's
//!   `L1 = 8a/(3 C11 G)`, `L2 = 8a/(3 C22 G)`, `L3 = pi a^2/(4 c C23 G)` of
//!   the ellipse `a`, `b` (`c = sqrt(a b)`, `Cij` read from Kalker's table
//!   as [`CreepInterpolation`] says: CONTACT reads it linearly in
//!   `g = min(a/b, b/a)`, [`CreepInterpolation::Contact`]), blended towards
//!   one flexibility at
//!   large creepage (Vollebregt 2022, the "blending approach" CONTACT uses
//!   with prescribed creepages): `L_crss = (xi^2 + eta^2 + r^2)/(xi^2/L1 +
//!   eta^2/L2 + r^2/L3)`, `r = phi (pi a^2/4)/(8a/3)`, and each `Li`
//!   becomes `(1 - w) Li + w L_crss` with `w = min(1, f/3)`, `f = max(1e-10,
//!   sqrt((xi^2 + eta^2)/(x_c^2 + e_c^2)))`, `x_c = mu_s Fn/(c^2 G C11)`,
//!   `e_c = mu_s Fn/(c^2 G C22)` the characteristic creepages (`mu_s` the
//!   static coefficient). A single non-zero creepage `xi` or `eta` leaves
//!   its flexibility unchanged. [`GridFlexibility::Given`] (`M = 2`): one
//!   flexibility `L` for all three.
//! * **Slope reduction** (Spiryagin, Polach and Cole 2013 as CONTACT states
//!   it, [`SlopeReduction`]): every flexibility divided by `k = k0 (alpha +
//!   (1 - alpha)/(1 + beta eps))`, `eps = k0 G A C11' s/(4 mu Fn)` with the
//!   area `A` and the `C11'` of the **equivalent ellipse** of the contact
//!   elements ([`equivalent_ellipse`], Kik and Piotrowski's: the contact
//!   area and the ratio of its extents along `x` and `y`, not the Hertz
//!   ellipse), `s = sqrt(xi^2 + eta_c^2)`, `eta_c = eta + phi a'` where that
//!   has the larger magnitude, else `eta`, `mu` the friction coefficient
//!   below.
//! * **Friction**: Coulomb's coefficient, or a slip-velocity law
//!   ([`SlipVelocityLaw`]) evaluated once at the **global** slip velocity
//!   `V sqrt(xi^2 + eta^2)` and used for every element ([`GridFriction`]):
//!   CONTACT's FASTSIM has no per-element slip velocity and no friction
//!   memory (`fastsim_params` with Spiryagin's total slip). The law's own
//!   rolling speed, memory distance and velocity are not used; the input's
//!   speed `V` is. [`SlopeReduction`]'s own falling factor, if any, is
//!   applied on top at the same slip velocity.
//! * **March** (implicit Euler, element to element): each row of the grid
//!   is integrated from its leading end; the traction carried into an
//!   element is that of its upstream neighbour (zero at the grid's edge and
//!   after an exterior element). In adhesion `p = p_up - dx k W`, with
//!   `W = (xi/L1 - phi y/L3, eta/L2 + phi (x + d)/L3)` at the element
//!   centre, the spin's lateral term taken `d = dx/6` towards the leading
//!   edge (CONTACT's `FACPHI`, [`SPIN_OFFSET_FRACTION`]). The first element
//!   of a row thus carries a full step `-dx k W`, not the half step of
//!   [`crate::core::fastsim`]. Where `|p| > mu pn` the traction is scaled
//!   back onto the bound in its own direction (slip) and the slip is
//!   `s = ((L1/k) (px - px_H), (L2/k) (py - py_H))/dx`, `p_H` the traction
//!   before scaling.
//! * **Totals**: midpoint sums over the elements, `F = sum p dA`,
//!   `Mz = sum (x py - y px) dA` about the grid's origin, `T gamma = -sum
//!   p.s dA`; the areas count elements.
//!
//! # Discretisation error
//!
//! In full adhesion a row of `n` contact elements carries `dx^2 k W n (n +
//! 1)/2` instead of the continuum's `k W (2 a_y)^2/2`: the force exceeds
//! Kalker's linear theory by roughly `1/n`, plus the error of the rows'
//! discrete lengths. Measured at `xi = 1e-6` on the ellipse `a/b = 0.5`
//! with `n x n` elements over 1.1 times it: `+4.0 %` (`n = 40`), `+1.1 %`
//! (100), `+0.32 %` (400), `+0.11 %` (1000); on the 48 x 44 grid of
//! CONTACT's `python_tractcurv.py` `+3.0 %` above the strip solver
//! [`crate::core::fastsim`], which has no such offset.

use crate::core::creep::{
    kalker_creep_coefficients, CreepCoefficients, KALKER_TABLE, MIN_ASPECT_RATIO,
};
use crate::core::error::{require_finite, require_positive, show, ContactError};
use crate::core::fastsim::{SlopeReduction, TractionBound};
use crate::core::friclaw::SlipVelocityLaw;
use crate::core::grid::Grid;
use crate::core::solution::{ElementFields, ElementState};
use serde::{Deserialize, Serialize};

/// The spin's lateral rigid slip is evaluated this fraction of an element
/// towards the leading edge (CONTACT's `FACPHI = 1/6`).
pub const SPIN_OFFSET_FRACTION: f64 = 1.0 / 6.0;

/// The blending weight reaches 1 at this multiple of the characteristic
/// creepage (CONTACT's `simpflex`).
const BLENDING_FULL_AT: f64 = 3.0;

/// The friction coefficient of a grid FASTSIM solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GridFriction {
    /// Coulomb's law with one coefficient [-], >= 0 (CONTACT's `L = 0`).
    Coulomb(f64),
    /// A slip-velocity law (`L = 2-5`) evaluated at the global slip
    /// velocity `V sqrt(xi^2 + eta^2)` and used for every element (see the
    /// module docs); its static coefficient `mu_s(0)` sets the
    /// characteristic creepages of the blending. The law's rolling speed
    /// and memory are not used.
    SlipVelocity(SlipVelocityLaw),
}

impl GridFriction {
    /// The coefficient at slip velocity `s_a` \[m/s\].
    fn at(&self, s_a: f64) -> f64 {
        match self {
            GridFriction::Coulomb(mu) => *mu,
            GridFriction::SlipVelocity(law) => law.coefficient(s_a),
        }
    }

    /// The static coefficient [-].
    pub fn static_coefficient(&self) -> f64 {
        match self {
            GridFriction::Coulomb(mu) => *mu,
            GridFriction::SlipVelocity(law) => law.static_coefficient(),
        }
    }

    fn validate(&self) -> Result<(), ContactError> {
        match self {
            GridFriction::Coulomb(mu) => {
                require_finite("fastsim.friction", *mu)?;
                if *mu < 0.0 {
                    return Err(ContactError::invalid(
                        "fastsim.friction",
                        format!("must be >= 0, got {}", show(*mu)),
                    ));
                }
                Ok(())
            }
            // The law's speed is not used (the input's is): check the rest.
            GridFriction::SlipVelocity(law) => SlipVelocityLaw {
                rolling_speed_m_per_s: 1.0,
                ..*law
            }
            .validate()
            .map_err(|e| e.with_key_prefix("friction", "fastsim.friction")),
        }
    }
}

/// The flexibilities of the simplified theory.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GridFlexibility {
    /// Kalker's `L1`, `L2`, `L3` of the ellipse (CONTACT's `M = 3`), with or
    /// without CONTACT's blending towards one flexibility at large creepage
    /// (module docs; CONTACT blends when creepages are prescribed).
    Kalker {
        /// Whether to blend.
        blending: bool,
    },
    /// One flexibility `L` for all three (CONTACT's `M = 2`, `FLX`)
    /// \[m/Pa\] (= m^3/N), > 0.
    Given {
        /// `L` \[m/Pa\].
        flexibility_m_per_pa: f64,
    },
}

/// The simplified material of a patch: its flexibilities and slope
/// reduction (CONTACT's `M = 3` with `K0_MF, ALFAMF, BETAMF`, or `M = 2`
/// with `FLX` as well).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FastsimMaterial {
    /// The flexibilities.
    pub flexibility: GridFlexibility,
    /// The slope reduction ([`SlopeReduction::NONE`]: Kalker's FASTSIM).
    pub reduction: SlopeReduction,
}

impl FastsimMaterial {
    /// CONTACT's `M = 3`: Kalker's three flexibilities of the ellipse,
    /// blended as CONTACT blends them, with `reduction`.
    pub fn kalker(reduction: SlopeReduction) -> Self {
        FastsimMaterial {
            flexibility: GridFlexibility::Kalker { blending: true },
            reduction,
        }
    }

    /// Checks the ranges in the field docs; errors name `key.reduction...`
    /// and `key.flexibility_m_per_pa`.
    pub fn validate_as(&self, key: &str) -> Result<(), ContactError> {
        self.reduction.validate_as(&format!("{key}.reduction"))?;
        if let GridFlexibility::Given {
            flexibility_m_per_pa,
        } = self.flexibility
        {
            require_positive(&format!("{key}.flexibility_m_per_pa"), flexibility_m_per_pa)?;
        }
        Ok(())
    }
}

/// Whether the Hertzian pressure is rescaled on the grid.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum BoundScaling {
    /// The analytic pressure at the element centres, `sum pn dA` close to
    /// but not equal to `Fn` (CONTACT's; the default).
    #[default]
    Analytic,
    /// Rescaled so that `sum pn dA = Fn` exactly: full sliding gives
    /// `mu Fn`.
    NormalForce,
}

/// The pressure of the traction bound.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GridPressure<'a> {
    /// Hertz's elliptic (`B = 2`) or Kalker's parabolic (`B = 3`) pressure
    /// of the input's ellipse and normal force at the element centres.
    Hertz {
        /// Elliptic or parabolic.
        bound: TractionBound,
        /// Rescaled or not.
        scaling: BoundScaling,
    },
    /// A pressure per element of the grid \[Pa\] (index `iy * nx + ix`),
    /// finite; elements with `pn <= 0` are exterior (`B = 0`: the exact
    /// normal problem's pressure).
    Given(&'a [f64]),
}

/// How Kalker's creep coefficients are read from his table between its
/// rows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum CreepInterpolation {
    /// [`kalker_creep_coefficients`]: shape-preserving cubic in `ln(a/b)`,
    /// the asymptotes beyond `g = 0.1` scaled to meet the table (the
    /// default).
    #[default]
    Smooth,
    /// CONTACT's `linrol`: linear in `g = min(a/b, b/a)` between the rows
    /// `g = 0.1, 0.2, .., 1`, Kalker's asymptotes unscaled below `g =
    /// 0.101`; `1/C` quadratic in `nu` as in [`CreepInterpolation::Smooth`].
    /// The two agree at the rows; between them, at `nu = 0.28`, `C11`,
    /// `C22`, `C23` differ by up to 0.9, 1.0 and 2.3 % for `0.3 <= a/b
    /// <= 3.3` and up to 6.6, 7.3 and 16 % at `a/b` near 6.7 (linear
    /// interpolation of a coefficient growing like `1/g`).
    Contact,
}

impl CreepInterpolation {
    /// `C11`, `C22`, `C23` at `a_over_b` and `nu` (`C33` is not used);
    /// None outside `[MIN_ASPECT_RATIO, 1/MIN_ASPECT_RATIO]`.
    pub(crate) fn coefficients(self, a_over_b: f64, nu: f64) -> Option<[f64; 3]> {
        if !(MIN_ASPECT_RATIO..=1.0 / MIN_ASPECT_RATIO).contains(&a_over_b) {
            return None;
        }
        match self {
            CreepInterpolation::Smooth => kalker_creep_coefficients(a_over_b, nu)
                .ok()
                .map(|c: CreepCoefficients| [c.c11, c.c22, c.c23]),
            CreepInterpolation::Contact => Some(linear_in_g(a_over_b, nu)),
        }
    }
}

/// Kalker's `C11`, `C22`, `C23` at `a/b`, `nu` as CONTACT's `linrol` reads
/// his table ([`CreepInterpolation::Contact`]).
fn linear_in_g(a_over_b: f64, nu: f64) -> [f64; 3] {
    use std::f64::consts::PI;
    let narrow = a_over_b <= 1.0; // a <= b
    let g = if narrow { a_over_b } else { 1.0 / a_over_b };
    if g < 0.101 {
        // Kalker's asymptotes for g -> 0.
        return if narrow {
            let c11 = PI * PI / (4.0 * (1.0 - nu));
            let c23 = PI * g.sqrt() / (3.0 * (1.0 - nu)) * (1.0 + nu * ((16.0 / g).ln() - 5.0));
            [c11, PI * PI / 4.0, c23]
        } else {
            let l = (16.0 / (g * g)).ln();
            let r = 3.0 - 4.0_f64.ln();
            let c11 = 2.0 * PI / ((l - 2.0 * nu) * g) * (1.0 + r / (l - 2.0 * nu));
            let q = (1.0 - nu) * l + 2.0 * nu;
            let c22 = 2.0 * PI / g * (1.0 + (1.0 - nu) * r / q) / q;
            let c23 = 2.0 * PI / (3.0 * g.powf(1.5) * ((1.0 - nu) * l - 2.0 + 4.0 * nu));
            [c11, c22, c23]
        };
    }
    // The table's rows of this side by g = 0.1 .. 1.0 (the row g = 1 is
    // shared).
    let row_at = |tenths: usize| {
        let g_row = tenths as f64 / 10.0;
        KALKER_TABLE
            .iter()
            .find(|r| (r.g - g_row).abs() < 1e-9 && (r.a_le_b == narrow || tenths == 10))
            .expect("Kalker's table has the rows g = 0.1 .. 1 on both sides")
    };
    // CONTACT's row index: floor(10 g - 0.005), weight 10 g - index.
    let lo = ((10.0 * g - 0.005).floor() as usize).clamp(1, 9);
    let w = 10.0 * g - lo as f64;
    let (r0, r1) = (row_at(lo), row_at(lo + 1));
    let weights = [
        8.0 * (nu - 0.25) * (nu - 0.5),
        -16.0 * nu * (nu - 0.5),
        8.0 * nu * (nu - 0.25),
    ];
    let mut out = [0.0; 3];
    for (which, o) in out.iter_mut().enumerate() {
        let pick = |r: &crate::core::creep::KalkerTableRow, i: usize| match which {
            0 => r.c11[i],
            1 => r.c22[i],
            _ => r.c23[i],
        };
        let inv: f64 = (0..3)
            .map(|i| weights[i] / (w * pick(r1, i) + (1.0 - w) * pick(r0, i)))
            .sum();
        *o = 1.0 / inv;
    }
    out
}

/// The rolling direction along the grid's `x` axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum RollingSense {
    /// Rolling along `+x`: the leading edge at large `x` (CONTACT's
    /// `CHI = 0`).
    #[default]
    PlusX,
    /// Rolling along `-x` (`CHI = 180` degrees).
    MinusX,
}

/// The input of one grid FASTSIM solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GridFastsimInput {
    /// Semi-axis `a` along `x` of the ellipse of the flexibilities and of a
    /// Hertzian pressure \[m\], > 0 (a non-Hertzian patch: its equivalent
    /// ellipse, [`equivalent_ellipse`]).
    pub semi_axis_x_m: f64,
    /// Semi-axis `b` along `y` \[m\], > 0.
    pub semi_axis_y_m: f64,
    /// Normal force `Fn` \[N\], > 0: of the Hertzian pressure, the slope
    /// reduction and the characteristic creepages.
    pub normal_force_n: f64,
    /// Combined shear modulus `G` \[Pa\], > 0.
    pub shear_modulus_pa: f64,
    /// Combined Poisson ratio `nu` [-], in `[0, 0.5]`.
    pub poisson_ratio: f64,
    /// Longitudinal creepage `xi` [-].
    pub creepage_long: f64,
    /// Lateral creepage `eta` [-].
    pub creepage_lat: f64,
    /// Spin creepage `phi` \[1/m\].
    pub spin_per_m: f64,
    /// Rolling speed `V` \[m/s\], >= 0: the global slip velocity of the
    /// friction law.
    pub rolling_speed_m_per_s: f64,
    /// The friction coefficient.
    pub friction: GridFriction,
    /// The slope reduction (`k0`, `alpha_inf`, `beta`; [`SlopeReduction::NONE`]:
    /// Kalker's FASTSIM).
    pub reduction: SlopeReduction,
    /// The flexibilities.
    pub flexibility: GridFlexibility,
    /// The rolling direction.
    pub rolling: RollingSense,
    /// How the creep coefficients of the flexibilities and of the slope
    /// reduction are read from Kalker's table.
    pub creep_table: CreepInterpolation,
}

/// The flexibilities and the slope reduction factor one grid FASTSIM solve
/// used (CONTACT's FLX(1:3) and K_EFF after a calculation).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct AppliedFlexibility {
    /// `L1`, `L2`, `L3` after blending, before the division by `k`
    /// \[m/Pa\] (= m^3/N); [`GridFlexibility::Given`]: the given one
    /// three times.
    pub flexibilities_m_per_pa: [f64; 3],
    /// The slope reduction factor `k` [-] (1 without slope reduction).
    pub slope_factor: f64,
}

/// The totals of one grid FASTSIM solve.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GridFastsimOutput {
    /// Longitudinal force on body 1 \[N\].
    pub fx_n: f64,
    /// Lateral force on body 1 \[N\].
    pub fy_n: f64,
    /// Spin moment on body 1 about the grid's origin [N m].
    pub mz_nm: f64,
    /// `sum pn dA` of the traction bound's pressure \[N\].
    pub pressure_force_n: f64,
    /// Contact area (elements with `pn > 0`) \[m^2\].
    pub contact_area_m2: f64,
    /// Area in adhesion \[m^2\].
    pub adhesion_area_m2: f64,
    /// Area in slip \[m^2\].
    pub slip_area_m2: f64,
    /// Frictional power per unit rolling speed `-sum p.s dA` \[N\].
    pub tgamma_n: f64,
    /// Largest pressure \[Pa\].
    pub max_pressure_pa: f64,
    /// Largest traction `|p|` \[Pa\].
    pub max_traction_pa: f64,
    /// The friction coefficient used for every element [-].
    pub friction_coefficient: f64,
    /// The flexibilities and the slope reduction factor the solve used.
    pub applied: AppliedFlexibility,
    /// Semi-axes of the contact elements' equivalent ellipse \[m\] (zero
    /// without contact).
    pub equivalent_semi_axes_m: [f64; 2],
}

/// The semi-axes `[a, b]` \[m\] of the equivalent ellipse of the elements
/// of `grid` where `pressure_pa > 0` (Kik and Piotrowski's, as CONTACT's
/// `equiv_ellipse`): the same area `A = n dx dy` and the ratio `a/b` of the
/// elements' extents `L = dx (ix_max - ix_min + 1)`, `W = dy (iy_max -
/// iy_min + 1)`: `a = sqrt(A/pi) sqrt(L/W)`, `b = sqrt(A/pi) sqrt(W/L)`.
/// None without contact elements or when `pressure_pa` is not one value an
/// element.
pub fn equivalent_ellipse(grid: &Grid, pressure_pa: &[f64]) -> Option<[f64; 2]> {
    if pressure_pa.len() != grid.len() {
        return None;
    }
    let [len, wid] = grid.loaded_extent_m(pressure_pa)?;
    let n = pressure_pa.iter().filter(|p| **p > 0.0).count();
    let r = (n as f64 * grid.element_area_m2() / std::f64::consts::PI).sqrt();
    Some([r * (len / wid).sqrt(), r * (wid / len).sqrt()])
}

/// The friction coefficient of the march's traction bound.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum MarchFriction {
    /// The coefficient at the global slip velocity (CONTACT's FASTSIM).
    GlobalSlipVelocity,
    /// The static coefficient (CONTACT's FaStrip, `fstat`).
    Static,
}

/// The buffers of a [`GridFastsim`] that a method built on its march
/// rewrites ([`crate::core::fastrip`]).
pub(crate) struct MarchBuffers<'a> {
    pub(crate) grid: Grid,
    pub(crate) pn: &'a [f64],
    pub(crate) px: &'a mut [f64],
    pub(crate) py: &'a mut [f64],
    pub(crate) sx: &'a mut [f64],
    pub(crate) sy: &'a mut [f64],
    pub(crate) state: &'a mut [ElementState],
}

/// What the march of one solve uses, kept for [`GridFastsim::rigid_slip`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct March {
    xi: f64,
    eta: f64,
    phi: f64,
    /// Flexibilities over `k` \[m/Pa\].
    l1: f64,
    l2: f64,
    l3: f64,
    /// Offset of the spin's lateral term \[m\].
    x_offset: f64,
    rolling: RollingSense,
}

/// FASTSIM on a potential contact grid with its per-element buffers.
///
/// Element `(ix, iy)` is at index `iy * nx + ix` of every slice, as on the
/// [`Grid`]. Before the first solve every field is zero.
#[derive(Debug, Clone)]
pub struct GridFastsim {
    grid: Grid,
    pn: Vec<f64>,
    px: Vec<f64>,
    py: Vec<f64>,
    sx: Vec<f64>,
    sy: Vec<f64>,
    state: Vec<ElementState>,
    march: March,
}

impl GridFastsim {
    /// A solver for `grid` (not a line contact's single row).
    pub fn new(grid: Grid) -> Result<Self, ContactError> {
        if grid.is_line() {
            return Err(ContactError::invalid(
                "grid.ny",
                "FASTSIM on a grid needs a patch of several rows, not a line contact's one",
            ));
        }
        let n = grid.len();
        Ok(Self {
            grid,
            pn: vec![0.0; n],
            px: vec![0.0; n],
            py: vec![0.0; n],
            sx: vec![0.0; n],
            sy: vec![0.0; n],
            state: vec![ElementState::Exterior; n],
            march: March::default(),
        })
    }

    /// The grid.
    pub fn grid(&self) -> &Grid {
        &self.grid
    }

    /// The pressure of the traction bound \[Pa\].
    pub fn pressure_pa(&self) -> &[f64] {
        &self.pn
    }

    /// Longitudinal traction on body 1 \[Pa\].
    pub fn traction_x_pa(&self) -> &[f64] {
        &self.px
    }

    /// Lateral traction on body 1 \[Pa\].
    pub fn traction_y_pa(&self) -> &[f64] {
        &self.py
    }

    /// Longitudinal slip per unit rolled distance [-] (zero outside slip).
    pub fn slip_x(&self) -> &[f64] {
        &self.sx
    }

    /// Lateral slip per unit rolled distance [-] (zero outside slip).
    pub fn slip_y(&self) -> &[f64] {
        &self.sy
    }

    /// The element states.
    pub fn state(&self) -> &[ElementState] {
        &self.state
    }

    /// The last solve's per-element fields, with the undeformed distance
    /// `gap_m` (empty: zeros).
    pub fn fields(&self, gap_m: Vec<f64>) -> ElementFields {
        let gap_m = if gap_m.is_empty() {
            vec![0.0; self.grid.len()]
        } else {
            gap_m
        };
        ElementFields {
            pressure_pa: self.pn.clone(),
            traction_x_pa: self.px.clone(),
            traction_y_pa: self.py.clone(),
            slip_x: self.sx.clone(),
            slip_y: self.sy.clone(),
            state: self.state.clone(),
            gap_m,
        }
    }

    /// The buffers the last solve filled, the tractions and states to be
    /// rewritten.
    pub(crate) fn buffers_mut(&mut self) -> MarchBuffers<'_> {
        MarchBuffers {
            grid: self.grid,
            pn: &self.pn,
            px: &mut self.px,
            py: &mut self.py,
            sx: &mut self.sx,
            sy: &mut self.sy,
            state: &mut self.state,
        }
    }

    /// The rigid slip per element [-] the last solve marched with, as
    /// CONTACT's `M = 3` states it: `(xi - (L1/L3) phi y, eta + (L2/L3) phi
    /// (x + d))` (the spin's terms scaled so that each component over its
    /// own flexibility is `W`; `d` the spin offset), `(xi - phi y, eta +
    /// phi (x + d))` with one flexibility.
    pub fn rigid_slip(&self) -> [Vec<f64>; 2] {
        let m = &self.march;
        let g = &self.grid;
        let (mut wx, mut wy) = (vec![0.0; g.len()], vec![0.0; g.len()]);
        if m.l3 <= 0.0 {
            return [wx, wy]; // no solve yet
        }
        for iy in 0..g.ny {
            for ix in 0..g.nx {
                let i = g.index(ix, iy);
                wx[i] = m.xi - m.l1 / m.l3 * m.phi * g.y_m(iy);
                wy[i] = m.eta + m.l2 / m.l3 * m.phi * (g.x_m(ix) + m.x_offset);
            }
        }
        [wx, wy]
    }

    /// Solves one steady rolling problem on the grid with the traction
    /// bound of `pressure`. No allocation.
    pub fn solve(
        &mut self,
        input: &GridFastsimInput,
        pressure: GridPressure<'_>,
    ) -> Result<GridFastsimOutput, ContactError> {
        self.solve_with(input, pressure, MarchFriction::GlobalSlipVelocity)
    }

    /// [`GridFastsim::solve`] with the march's friction coefficient chosen
    /// by `march` (the slope reduction always uses the coefficient at the
    /// global slip velocity). No allocation.
    pub(crate) fn solve_with(
        &mut self,
        input: &GridFastsimInput,
        pressure: GridPressure<'_>,
        march: MarchFriction,
    ) -> Result<GridFastsimOutput, ContactError> {
        validate(input)?;
        let (a, b) = (input.semi_axis_x_m, input.semi_axis_y_m);
        let g = self.grid;
        // The pressure of the bound.
        match pressure {
            GridPressure::Hertz { bound, scaling } => {
                let fn_ = input.normal_force_n;
                for iy in 0..g.ny {
                    let ry = g.y_m(iy) / b;
                    for ix in 0..g.nx {
                        let rx = g.x_m(ix) / a;
                        let f = 1.0 - rx * rx - ry * ry;
                        self.pn[g.index(ix, iy)] = match bound {
                            TractionBound::Elliptic => {
                                3.0 * fn_ / (2.0 * std::f64::consts::PI * a * b) * f.max(0.0).sqrt()
                            }
                            TractionBound::Parabolic => {
                                2.0 * fn_ / (std::f64::consts::PI * a * b) * f.max(0.0)
                            }
                        };
                    }
                }
                if scaling == BoundScaling::NormalForce {
                    let sum: f64 = self.pn.iter().sum::<f64>() * g.element_area_m2();
                    if sum > 0.0 {
                        let s = fn_ / sum;
                        self.pn.iter_mut().for_each(|p| *p *= s);
                    }
                }
            }
            GridPressure::Given(p) => {
                if p.len() != g.len() {
                    return Err(ContactError::invalid(
                        "fastsim.pressure",
                        format!(
                            "needs one value per element of the {} x {} grid ({}), got {}",
                            g.nx,
                            g.ny,
                            g.len(),
                            p.len()
                        ),
                    ));
                }
                if let Some(i) = p.iter().position(|v| !v.is_finite()) {
                    return Err(ContactError::invalid(
                        "fastsim.pressure",
                        format!("element {i} is {}, not finite", show(p[i])),
                    ));
                }
                for (d, s) in self.pn.iter_mut().zip(p) {
                    *d = s.max(0.0);
                }
            }
        }

        let (xi, eta, phi) = (input.creepage_long, input.creepage_lat, input.spin_per_m);
        let g_mod = input.shear_modulus_pa;
        // Friction at the global slip velocity (CONTACT's `fastsim_params`).
        let slip_velocity = (input.rolling_speed_m_per_s * xi.hypot(eta)).min(f64::MAX);
        let mu = input.friction.at(slip_velocity) * input.reduction.friction_factor(slip_velocity);
        let mu_static = input.friction.static_coefficient();

        // Flexibilities of the ellipse, blended.
        let mut l = match input.flexibility {
            GridFlexibility::Given {
                flexibility_m_per_pa,
            } => [flexibility_m_per_pa; 3],
            GridFlexibility::Kalker { blending } => {
                let [c11, c22, c23] = input
                    .creep_table
                    .coefficients(a / b, input.poisson_ratio)
                    .ok_or_else(|| {
                        ContactError::invalid(
                            "fastsim.semi_axis_x_m",
                            format!(
                                "a/b = {} is outside the creep coefficients' range [1e-4, 1e4]",
                                show(a / b)
                            ),
                        )
                    })?;
                let c2 = a * b;
                let mut l = [
                    8.0 * a / (3.0 * c11 * g_mod),
                    8.0 * a / (3.0 * c22 * g_mod),
                    std::f64::consts::PI * a * a / (4.0 * c2.sqrt() * c23 * g_mod),
                ];
                if blending {
                    let r = phi * (std::f64::consts::PI * a * a / 4.0) / (8.0 * a / 3.0);
                    let num = xi * xi + eta * eta + r * r;
                    let den = xi * xi / l[0] + eta * eta / l[1] + r * r / l[2];
                    let l_crss = if den > 0.0 { num / den } else { 0.0 };
                    let ch = mu_static * input.normal_force_n / (c2 * g_mod);
                    let (ch_xi, ch_eta) = (ch / c11, ch / c22);
                    let (cr2, ch2) = (xi * xi + eta * eta, ch_xi * ch_xi + ch_eta * ch_eta);
                    let ratio = if ch2 > 0.0 {
                        (cr2 / ch2).sqrt()
                    } else if cr2 > 0.0 {
                        f64::INFINITY
                    } else {
                        0.0
                    };
                    let w = (ratio.max(1e-10) / BLENDING_FULL_AT).min(1.0);
                    for li in &mut l {
                        *li = (1.0 - w) * *li + w * l_crss;
                    }
                }
                l
            }
        };

        // Slope reduction with the equivalent ellipse of the contact area.
        let equivalent = equivalent_ellipse(&g, &self.pn).unwrap_or([0.0; 2]);
        let k = if equivalent[0] > 0.0 {
            let [ae, be] = equivalent;
            let ratio = (ae / be).clamp(MIN_ASPECT_RATIO, 1.0 / MIN_ASPECT_RATIO);
            let c11 = input
                .creep_table
                .coefficients(ratio, input.poisson_ratio)
                .map_or(f64::NAN, |c| c[0]);
            let eta_c = if (eta + phi * ae).abs() < eta.abs() {
                eta
            } else {
                eta + phi * ae
            };
            input.reduction.factor(
                g_mod * std::f64::consts::PI * ae * be * c11 * xi.hypot(eta_c),
                mu * input.normal_force_n,
            )
        } else {
            input.reduction.initial_factor
        };
        let flexibilities = l;
        for li in &mut l {
            *li /= k;
        }

        let dx = g.dx_m;
        let x_offset = match input.rolling {
            RollingSense::PlusX => SPIN_OFFSET_FRACTION * dx,
            RollingSense::MinusX => -SPIN_OFFSET_FRACTION * dx,
        };
        self.march = March {
            xi,
            eta,
            phi,
            l1: l[0],
            l2: l[1],
            l3: l[2],
            x_offset,
            rolling: input.rolling,
        };
        let march_mu = match march {
            MarchFriction::GlobalSlipVelocity => mu,
            MarchFriction::Static => mu_static,
        };
        let mut out = self.march_rows(march_mu);
        let totals = [out.fx_n, out.fy_n, out.mz_nm, out.tgamma_n];
        if !(k > 0.0 && totals.iter().all(|v| v.is_finite())) {
            return Err(ContactError::invalid(
                "fastsim.creepage_long",
                format!(
                    "creepages ({}, {}, {} 1/m) too large: the tractions overflow",
                    show(xi),
                    show(eta),
                    show(phi)
                ),
            ));
        }
        out.friction_coefficient = march_mu;
        out.applied = AppliedFlexibility {
            flexibilities_m_per_pa: flexibilities,
            slope_factor: k,
        };
        out.equivalent_semi_axes_m = equivalent;
        Ok(out)
    }

    /// Marches every row from its leading end with the bound `mu pn`
    /// (module docs); the totals.
    fn march_rows(&mut self, mu: f64) -> GridFastsimOutput {
        let g = self.grid;
        let m = self.march;
        let (dx, da) = (g.dx_m, g.element_area_m2());
        let (eta_l2, phi_l3) = (m.eta / m.l2, m.phi / m.l3);
        let mut o = GridFastsimOutput::default();
        let (mut n_adh, mut n_slip) = (0usize, 0usize);
        let mut pmax2 = 0.0_f64;
        for iy in 0..g.ny {
            let y = g.y_m(iy);
            let wx = m.xi / m.l1 - phi_l3 * y;
            let (mut cx, mut cy) = (0.0, 0.0);
            for step in 0..g.nx {
                let ix = match m.rolling {
                    RollingSense::PlusX => g.nx - 1 - step,
                    RollingSense::MinusX => step,
                };
                let i = g.index(ix, iy);
                let pn = self.pn[i];
                if pn <= 0.0 {
                    (self.px[i], self.py[i], self.sx[i], self.sy[i]) = (0.0, 0.0, 0.0, 0.0);
                    self.state[i] = ElementState::Exterior;
                    (cx, cy) = (0.0, 0.0);
                    continue;
                }
                let x = g.x_m(ix);
                let wy = eta_l2 + phi_l3 * (x + m.x_offset);
                let (hx, hy) = (cx - dx * wx, cy - dx * wy);
                let bound = mu * pn;
                let mag = (hx * hx + hy * hy).sqrt();
                let (px, py) = if mag > bound {
                    let f = bound / mag;
                    let (px, py) = (hx * f, hy * f);
                    self.sx[i] = m.l1 * (px - hx) / dx;
                    self.sy[i] = m.l2 * (py - hy) / dx;
                    self.state[i] = ElementState::Slip;
                    n_slip += 1;
                    o.tgamma_n -= (px * self.sx[i] + py * self.sy[i]) * da;
                    (px, py)
                } else {
                    (self.sx[i], self.sy[i]) = (0.0, 0.0);
                    self.state[i] = ElementState::Adhesion;
                    n_adh += 1;
                    (hx, hy)
                };
                (self.px[i], self.py[i]) = (px, py);
                (cx, cy) = (px, py);
                o.fx_n += px * da;
                o.fy_n += py * da;
                o.mz_nm += (x * py - y * px) * da;
                o.pressure_force_n += pn * da;
                o.max_pressure_pa = o.max_pressure_pa.max(pn);
                pmax2 = pmax2.max(px * px + py * py);
            }
        }
        o.max_traction_pa = pmax2.sqrt();
        o.adhesion_area_m2 = n_adh as f64 * da;
        o.slip_area_m2 = n_slip as f64 * da;
        o.contact_area_m2 = (n_adh + n_slip) as f64 * da;
        o
    }
}

/// Checks the input's ranges; errors name `fastsim.<field>`.
fn validate(input: &GridFastsimInput) -> Result<(), ContactError> {
    require_positive("fastsim.semi_axis_x_m", input.semi_axis_x_m)?;
    require_positive("fastsim.semi_axis_y_m", input.semi_axis_y_m)?;
    require_positive("fastsim.normal_force_n", input.normal_force_n)?;
    require_positive("fastsim.shear_modulus_pa", input.shear_modulus_pa)?;
    let nu = input.poisson_ratio;
    if !(0.0..=0.5).contains(&nu) {
        return Err(ContactError::invalid(
            "fastsim.poisson_ratio",
            format!("must be in [0, 0.5], got {}", show(nu)),
        ));
    }
    require_finite("fastsim.creepage_long", input.creepage_long)?;
    require_finite("fastsim.creepage_lat", input.creepage_lat)?;
    require_finite("fastsim.spin_per_m", input.spin_per_m)?;
    let v = input.rolling_speed_m_per_s;
    require_finite("fastsim.rolling_speed_m_per_s", v)?;
    if v < 0.0 {
        return Err(ContactError::invalid(
            "fastsim.rolling_speed_m_per_s",
            format!("must be >= 0, got {}", show(v)),
        ));
    }
    input.friction.validate()?;
    input.reduction.validate_as("fastsim.reduction")?;
    if let GridFlexibility::Given {
        flexibility_m_per_pa,
    } = input.flexibility
    {
        require_positive("fastsim.flexibility_m_per_pa", flexibility_m_per_pa)?;
    }
    Ok(())
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::core::creep::kalker_linear_forces;

    /// The input the tests of this module and of
    /// [`crate::core::fastrip`] start from: ellipse `a`, `b`, FN = 82 kN,
    /// G = 82 GPa, nu = 0.28, V = 30 m/s, Coulomb 0.3, Kalker's blended
    /// flexibilities, no slope reduction, rolling along +x, CONTACT's
    /// creep table.
    pub(crate) fn input(a: f64, b: f64, xi: f64, eta: f64, phi: f64) -> GridFastsimInput {
        GridFastsimInput {
            semi_axis_x_m: a,
            semi_axis_y_m: b,
            normal_force_n: 82e3,
            shear_modulus_pa: 82e9,
            poisson_ratio: 0.28,
            creepage_long: xi,
            creepage_lat: eta,
            spin_per_m: phi,
            rolling_speed_m_per_s: 30.0,
            friction: GridFriction::Coulomb(0.3),
            reduction: SlopeReduction::NONE,
            flexibility: GridFlexibility::Kalker { blending: true },
            rolling: RollingSense::PlusX,
            creep_table: CreepInterpolation::Contact,
        }
    }

    fn grid(a: f64, b: f64, nx: usize, ny: usize) -> Grid {
        Grid::centered(nx, ny, 2.2 * a, 2.2 * b).unwrap()
    }

    const PARABOLIC: GridPressure<'static> = GridPressure::Hertz {
        bound: TractionBound::Parabolic,
        scaling: BoundScaling::Analytic,
    };

    fn rel(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs()
    }

    /// CONTACT's `examples/fastsim.inp`: AA, BB = 8, 4 mm, 44 x 44
    /// elements over 1.1 times the ellipse, FN = 82 kN, G = 82 GPa,
    /// nu = 0.28, FSTAT = 0.3, CETA = -0.000625, CPHI = 0.000625 rad/mm.
    fn fastsim_inp(phi: f64, rolling: RollingSense) -> (GridFastsim, GridFastsimInput) {
        let fs = GridFastsim::new(grid(8e-3, 4e-3, 44, 44)).unwrap();
        let inp = GridFastsimInput {
            rolling,
            ..input(8e-3, 4e-3, 0.0, -0.000625, phi)
        };
        (fs, inp)
    }

    /// CONTACT's numbers: its library (`contact_addon_linux64.so` of
    /// CONTACT revision 2707, 2025-07-23) driven through `cntc_*` with the
    /// cases of its `examples/fastsim.inp` (M = 3, steady rolling,
    /// `cntc_getcontactforces` in CONTACT's units, N and N mm); the
    /// example's `fastsim.ref_out` prints them rounded (case 2: FY
    /// -1.505E+04, MZ -3.900E+04, PMAX 1629). Case 2: B = 3; case 3: B =
    /// 2; case 8: B = 3 rolling along -x with the spin reversed (there on a
    /// 220 x 220 grid, here on case 2's). Ours agree to 1e-7.
    #[test]
    fn contacts_fastsim_example() {
        let cases = [
            (
                PARABOLIC,
                0.625,
                RollingSense::PlusX,
                -15050.925566873188,
                -39001.60370457417,
            ),
            (
                GridPressure::Hertz {
                    bound: TractionBound::Elliptic,
                    scaling: BoundScaling::Analytic,
                },
                0.625,
                RollingSense::PlusX,
                -14799.295140316011,
                -48286.123775974665,
            ),
            (
                PARABOLIC,
                -0.625,
                RollingSense::MinusX,
                -15050.925566873188,
                39001.60370457417,
            ),
        ];
        for (pressure, phi, rolling, fy, mz_nmm) in cases {
            let (mut fs, inp) = fastsim_inp(phi, rolling);
            let o = fs.solve(&inp, pressure).unwrap();
            assert!(rel(o.fy_n, fy) < 1e-7, "{rolling:?}: {} vs {fy}", o.fy_n);
            assert!(
                rel(o.mz_nm, mz_nmm * 1e-3) < 1e-7,
                "{} vs {mz_nmm}",
                o.mz_nm
            );
            assert!(o.fx_n.abs() < 1e-9 * fy.abs(), "{}", o.fx_n);
        }
        // Case 2's element division (the ref_out's "A, S = 738, 526"), its
        // peak pressure 1629 N/mm^2 and its frictional power -509.3 W.
        let (mut fs, inp) = fastsim_inp(0.625, RollingSense::PlusX);
        let o = fs.solve(&inp, PARABOLIC).unwrap();
        let count = |st| fs.state().iter().filter(|s| **s == st).count();
        assert_eq!(
            (count(ElementState::Adhesion), count(ElementState::Slip)),
            (738, 526)
        );
        assert!((o.max_pressure_pa / 1e6 - 1629.0).abs() < 0.5);
        assert!(
            (o.tgamma_n * 30.0 - 509.3).abs() < 0.05,
            "{}",
            o.tgamma_n * 30.0
        );
    }

    /// Small creepage: Kalker's linear theory, plus the grid's
    /// discretisation error (module docs). Measured at xi = 1e-6 on the
    /// ellipse a/b = 0.5 with n x n elements over 1.1 times it: +4.0 %
    /// (n = 40), +1.1 % (100), +0.32 % (400), +0.11 % (1000).
    #[test]
    fn small_creepage_approaches_the_linear_theory() {
        let (a, b) = (4e-3, 8e-3);
        let lin = kalker_linear_forces(a, b, 82e9, 0.28, 1e-6, 0.0, 0.0).unwrap();
        let mut prev = f64::INFINITY;
        for (n, err) in [(40, 0.040), (100, 0.0112), (400, 0.0032)] {
            let mut fs = GridFastsim::new(grid(a, b, n, n)).unwrap();
            let o = fs.solve(&input(a, b, 1e-6, 0.0, 0.0), PARABOLIC).unwrap();
            let e = o.fx_n / lin.fx_n - 1.0;
            assert!(e > 0.0 && (e - err).abs() < 0.1 * err, "{n}: {e}");
            assert!(e < prev);
            prev = e;
            assert!(o.slip_area_m2 / o.contact_area_m2 < 0.02);
        }
    }

    /// Full sliding: `|F| = mu sum pn dA` to rounding, against the
    /// creepage; with [`BoundScaling::NormalForce`] that is `mu Fn`.
    #[test]
    fn full_sliding_is_mu_times_the_grid_pressure() {
        let (a, b) = (6e-3, 4e-3);
        for bound in [TractionBound::Parabolic, TractionBound::Elliptic] {
            for scaling in [BoundScaling::Analytic, BoundScaling::NormalForce] {
                let mut fs = GridFastsim::new(grid(a, b, 40, 30)).unwrap();
                let p = GridPressure::Hertz { bound, scaling };
                let o = fs.solve(&input(a, b, 0.5, 0.0, 0.0), p).unwrap();
                let sum: f64 = fs.pressure_pa().iter().sum::<f64>() * fs.grid().element_area_m2();
                assert!(rel(sum, o.pressure_force_n) < 1e-13);
                assert!(rel(o.fx_n, -0.3 * sum) < 1e-12, "{bound:?} {scaling:?}");
                assert!(o.fy_n.abs() < 1e-9 && o.adhesion_area_m2 == 0.0);
                if scaling == BoundScaling::NormalForce {
                    assert!(rel(o.fx_n, -0.3 * 82e3) < 1e-12);
                } else {
                    // CONTACT's pressure is not normalised: the midpoint
                    // rule's error.
                    assert!(rel(sum, 82e3) > 1e-6 && rel(sum, 82e3) < 1e-2, "{sum}");
                }
            }
        }
    }

    /// Blending: a single creepage xi or eta keeps its flexibility; large
    /// combined creepage blends all three into one.
    #[test]
    fn blending_towards_one_flexibility() {
        let (a, b) = (6e-3, 4e-3);
        let mut fs = GridFastsim::new(grid(a, b, 20, 20)).unwrap();
        let plain = |fs: &mut GridFastsim, xi, eta, phi| {
            let inp = GridFastsimInput {
                flexibility: GridFlexibility::Kalker { blending: false },
                ..input(a, b, xi, eta, phi)
            };
            fs.solve(&inp, PARABOLIC)
                .unwrap()
                .applied
                .flexibilities_m_per_pa
        };
        let l = plain(&mut fs, 1e-3, 0.0, 0.0);
        let o = fs.solve(&input(a, b, 0.5, 0.0, 0.0), PARABOLIC).unwrap();
        assert!(rel(o.applied.flexibilities_m_per_pa[0], l[0]) < 1e-15);
        let o = fs.solve(&input(a, b, 0.0, 0.5, 0.0), PARABOLIC).unwrap();
        assert!(rel(o.applied.flexibilities_m_per_pa[1], l[1]) < 1e-15);
        // Far beyond 3 characteristic creepages: one flexibility.
        let o = fs.solve(&input(a, b, 0.3, 0.4, 0.0), PARABOLIC).unwrap();
        let crss = 0.25 / (0.09 / l[0] + 0.16 / l[1]);
        for li in o.applied.flexibilities_m_per_pa {
            assert!(rel(li, crss) < 1e-14);
        }
        // Tiny creepage: Kalker's three, to 1e-6.
        let o = fs.solve(&input(a, b, 1e-8, 1e-8, 1e-6), PARABOLIC).unwrap();
        for (li, k) in o.applied.flexibilities_m_per_pa.iter().zip(l) {
            assert!(rel(*li, k) < 1e-6);
        }
    }

    /// M = 2's one given flexibility equal to L1 is M = 3's FASTSIM for
    /// xi alone; the pressure given per element is the Hertzian one's.
    #[test]
    fn given_flexibility_and_given_pressure() {
        let (a, b) = (6e-3, 4e-3);
        let mut fs = GridFastsim::new(grid(a, b, 30, 30)).unwrap();
        let inp = input(a, b, 2e-3, 0.0, 0.0);
        let kalker = fs.solve(&inp, PARABOLIC).unwrap();
        let pn = fs.pressure_pa().to_vec();
        let px = fs.traction_x_pa().to_vec();
        let given = GridFastsimInput {
            flexibility: GridFlexibility::Given {
                flexibility_m_per_pa: kalker.applied.flexibilities_m_per_pa[0],
            },
            ..inp
        };
        assert_eq!(fs.solve(&given, PARABOLIC).unwrap().fx_n, kalker.fx_n);
        let o = fs.solve(&inp, GridPressure::Given(&pn)).unwrap();
        assert_eq!(o, kalker);
        assert_eq!(fs.traction_x_pa(), &px[..]);
        // With one flexibility the slip is exactly opposite the traction.
        let o = fs
            .solve(
                &GridFastsimInput {
                    creepage_lat: 1e-3,
                    spin_per_m: 0.5,
                    ..given
                },
                PARABOLIC,
            )
            .unwrap();
        let mut slipping = 0;
        for i in 0..fs.grid().len() {
            let (p, s) = (
                [fs.traction_x_pa()[i], fs.traction_y_pa()[i]],
                [fs.slip_x()[i], fs.slip_y()[i]],
            );
            let bound = 0.3 * fs.pressure_pa()[i];
            match fs.state()[i] {
                ElementState::Slip => {
                    slipping += 1;
                    assert!(rel(p[0].hypot(p[1]), bound) < 1e-12);
                    let cross = p[0] * s[1] - p[1] * s[0];
                    let dot = p[0] * s[0] + p[1] * s[1];
                    assert!(dot < 0.0 && cross.abs() < 1e-9 * dot.abs());
                }
                ElementState::Adhesion => {
                    assert!(p[0].hypot(p[1]) <= bound && s == [0.0, 0.0]);
                }
                ElementState::Exterior => assert!(p == [0.0, 0.0] && bound == 0.0),
            }
        }
        assert!(slipping > 0 && o.tgamma_n > 0.0);
        let area = o.adhesion_area_m2 + o.slip_area_m2;
        assert!(rel(area, o.contact_area_m2) < 1e-15);
    }

    /// Rolling along -x is rolling along +x turned half a turn: x, y and
    /// the creepages xi, eta change sign, the spin not; so do the
    /// tractions, element (ix, iy) becoming (nx-1-ix, ny-1-iy).
    #[test]
    fn rolling_backwards_is_the_problem_turned() {
        let (a, b) = (6e-3, 4e-3);
        let g = grid(a, b, 24, 20);
        let (mut fwd, mut back) = (GridFastsim::new(g).unwrap(), GridFastsim::new(g).unwrap());
        let inp = input(a, b, 1e-3, -6e-4, 0.4);
        let o1 = fwd.solve(&inp, PARABOLIC).unwrap();
        let turned = GridFastsimInput {
            creepage_long: -1e-3,
            creepage_lat: 6e-4,
            rolling: RollingSense::MinusX,
            ..inp
        };
        let o2 = back.solve(&turned, PARABOLIC).unwrap();
        assert!(rel(o2.fx_n, -o1.fx_n) < 1e-12 && rel(o2.fy_n, -o1.fy_n) < 1e-12);
        assert!(rel(o2.mz_nm, o1.mz_nm) < 1e-12);
        for iy in 0..g.ny {
            for ix in 0..g.nx {
                let (i, j) = (g.index(ix, iy), g.index(g.nx - 1 - ix, g.ny - 1 - iy));
                assert_eq!(fwd.state()[i], back.state()[j]);
                let d = (fwd.traction_x_pa()[i] + back.traction_x_pa()[j]).abs();
                assert!(d <= 1e-9 * o1.max_traction_pa, "({ix}, {iy})");
            }
        }
    }

    /// A falling law at the global slip velocity V sqrt(xi^2 + eta^2):
    /// full sliding gives mu(V |creepage|) sum pn dA; its memory does not
    /// enter; the static coefficient sets the blending.
    #[test]
    fn falling_friction_at_the_global_slip_velocity() {
        let (a, b) = (6e-3, 4e-3);
        let law = SlipVelocityLaw {
            shape: crate::core::friclaw::FallingShape::Exponential,
            kinetic_coefficient: 0.1368,
            falling_coefficients: [0.2232, 0.0],
            half_velocities_m_per_s: [0.99, 0.0],
            rolling_speed_m_per_s: 123.0,
            memory_distance_m: 3e-6,
            memory_velocity_m_per_s: 1e-3,
            start: crate::core::friclaw::SlipStart::Previous,
            max_iterations: 0,
        };
        let mut fs = GridFastsim::new(grid(a, b, 30, 30)).unwrap();
        let inp = GridFastsimInput {
            friction: GridFriction::SlipVelocity(law),
            rolling_speed_m_per_s: 10.0,
            ..input(a, b, 0.3, 0.4, 0.0)
        };
        let o = fs.solve(&inp, PARABOLIC).unwrap();
        let mu = law.coefficient(10.0 * 0.5);
        assert!(rel(o.friction_coefficient, mu) < 1e-15);
        assert!(rel(o.fx_n.hypot(o.fy_n), mu * o.pressure_force_n) < 1e-12);
        let no_memory = SlipVelocityLaw {
            memory_distance_m: 0.0,
            ..law
        };
        let o2 = fs
            .solve(
                &GridFastsimInput {
                    friction: GridFriction::SlipVelocity(no_memory),
                    ..inp
                },
                PARABOLIC,
            )
            .unwrap();
        assert_eq!(o, o2);
        // A slope reduction's own falling factor multiplies it.
        let r = SlopeReduction {
            friction_limit_ratio: 0.5,
            friction_decay_s_per_m: 0.2,
            ..SlopeReduction::NONE
        };
        let o3 = fs
            .solve(
                &GridFastsimInput {
                    reduction: r,
                    ..inp
                },
                PARABOLIC,
            )
            .unwrap();
        assert!(rel(o3.friction_coefficient, mu * r.friction_factor(5.0)) < 1e-15);
    }

    /// The slope reduction: the factor k of the contact elements'
    /// equivalent ellipse; in adhesion every traction is k times the
    /// unreduced one.
    #[test]
    fn slope_reduction_with_the_equivalent_ellipse() {
        let (a, b) = (4e-3, 8e-3);
        let g = grid(a, b, 48, 44);
        let mut fs = GridFastsim::new(g).unwrap();
        let r = SlopeReduction {
            initial_factor: 0.54,
            limit_ratio: 0.02,
            transition_rate: 0.62,
            ..SlopeReduction::NONE
        };
        let xi = 1e-7;
        let plain = fs.solve(&input(a, b, xi, 0.0, 0.0), PARABOLIC).unwrap();
        let inp = GridFastsimInput {
            reduction: r,
            ..input(a, b, xi, 0.0, 0.0)
        };
        let o = fs.solve(&inp, PARABOLIC).unwrap();
        let [ae, be] = equivalent_ellipse(&g, fs.pressure_pa()).unwrap();
        assert_eq!(o.equivalent_semi_axes_m, [ae, be]);
        // The area is the contact elements'; the ratio of their extents
        // (44 of 48 columns, 40 of 44 rows), close to a/b.
        assert!(rel(std::f64::consts::PI * ae * be, o.contact_area_m2) < 1e-14);
        assert!(rel(ae / be, 0.5) < 0.02, "{}", ae / be);
        let c11 = CreepInterpolation::Contact
            .coefficients(ae / be, 0.28)
            .unwrap()[0];
        let k = r.factor(82e9 * std::f64::consts::PI * ae * be * c11 * xi, 0.3 * 82e3);
        assert_eq!(o.applied.slope_factor, k);
        assert!(rel(o.fx_n, k * plain.fx_n) < 1e-12 && rel(k, 0.54) < 1e-3);
    }

    /// CONTACT's table reading: the rows themselves, linear in g between
    /// them (at nu = 0 and 0.25 the table's columns), close to the smooth
    /// interpolation.
    #[test]
    fn creep_interpolation_of_contact() {
        let c = |aob, nu| CreepInterpolation::Contact.coefficients(aob, nu).unwrap();
        let s = |aob, nu| CreepInterpolation::Smooth.coefficients(aob, nu).unwrap();
        for aob in [0.2, 0.5, 1.0, 2.0, 1.0 / 0.3] {
            for nu in [0.0, 0.28, 0.5] {
                let (x, y) = (c(aob, nu), s(aob, nu));
                for k in 0..3 {
                    assert!(rel(x[k], y[k]) < 1e-12, "{aob} {nu} {k}");
                }
            }
        }
        assert!(rel(c(0.55, 0.0)[0], 0.5 * (2.88 + 2.98)) < 1e-14);
        assert!(rel(c(1.0 / 0.55, 0.25)[2], 0.5 * (2.62 + 2.23)) < 1e-14);
        // Between the rows: 2.3 % at most for 0.3 <= a/b <= 3.3, 16 %
        // for C23 near a/b = 6.7 (see [`CreepInterpolation::Contact`]).
        for (aob, tol) in [(0.62, 0.01), (1.7, 0.025), (2.86, 0.025), (6.65, 0.17)] {
            let (x, y) = (c(aob, 0.28), s(aob, 0.28));
            for k in 0..3 {
                assert!(rel(x[k], y[k]) < tol, "{aob} {k}: {} {}", x[k], y[k]);
            }
        }
        // Beyond the table: Kalker's asymptotes, finite and positive.
        for aob in [1e-4, 0.05, 20.0, 1e4] {
            assert!(c(aob, 0.3).iter().all(|v| v.is_finite() && *v > 0.0));
        }
        assert!(CreepInterpolation::Contact.coefficients(2e4, 0.3).is_none());
    }

    /// Typed errors, never a panic; zero creepage, zero friction and a
    /// grid that misses the ellipse solve to zero.
    #[test]
    fn bad_input_is_an_error_and_edge_cases_solve() {
        let (a, b) = (6e-3, 4e-3);
        let mut fs = GridFastsim::new(grid(a, b, 10, 10)).unwrap();
        let base = input(a, b, 1e-3, 0.0, 0.0);
        let bad = [
            (
                "fastsim.semi_axis_x_m",
                GridFastsimInput {
                    semi_axis_x_m: -1.0,
                    ..base
                },
            ),
            (
                "fastsim.normal_force_n",
                GridFastsimInput {
                    normal_force_n: f64::NAN,
                    ..base
                },
            ),
            (
                "fastsim.poisson_ratio",
                GridFastsimInput {
                    poisson_ratio: 0.6,
                    ..base
                },
            ),
            (
                "fastsim.creepage_lat",
                GridFastsimInput {
                    creepage_lat: f64::INFINITY,
                    ..base
                },
            ),
            (
                "fastsim.rolling_speed_m_per_s",
                GridFastsimInput {
                    rolling_speed_m_per_s: -1.0,
                    ..base
                },
            ),
            (
                "fastsim.friction",
                GridFastsimInput {
                    friction: GridFriction::Coulomb(-0.1),
                    ..base
                },
            ),
            (
                "fastsim.flexibility_m_per_pa",
                GridFastsimInput {
                    flexibility: GridFlexibility::Given {
                        flexibility_m_per_pa: 0.0,
                    },
                    ..base
                },
            ),
            (
                "fastsim.reduction.initial_factor",
                GridFastsimInput {
                    reduction: SlopeReduction {
                        initial_factor: 0.0,
                        ..SlopeReduction::NONE
                    },
                    ..base
                },
            ),
            (
                "fastsim.semi_axis_x_m",
                GridFastsimInput {
                    semi_axis_x_m: 1e3,
                    ..base
                },
            ),
            (
                "fastsim.creepage_long",
                GridFastsimInput {
                    creepage_long: 1e300,
                    spin_per_m: 1e300,
                    ..base
                },
            ),
        ];
        for (key, inp) in bad {
            let e = fs.solve(&inp, PARABOLIC).unwrap_err();
            assert_eq!(e.key(), Some(key), "{e}");
        }
        let law = SlipVelocityLaw {
            shape: crate::core::friclaw::FallingShape::Linear,
            kinetic_coefficient: 0.0,
            falling_coefficients: [0.1, 0.0],
            half_velocities_m_per_s: [1.0, 0.0],
            rolling_speed_m_per_s: 0.0,
            memory_distance_m: 0.0,
            memory_velocity_m_per_s: 0.0,
            start: crate::core::friclaw::SlipStart::Previous,
            max_iterations: 0,
        };
        let falling = GridFastsimInput {
            friction: GridFriction::SlipVelocity(law),
            ..base
        };
        let e = fs.solve(&falling, PARABOLIC).unwrap_err();
        assert_eq!(e.key(), Some("fastsim.friction.kinetic_coefficient"), "{e}");
        let e = fs.solve(&base, GridPressure::Given(&[1.0; 3])).unwrap_err();
        assert_eq!(e.key(), Some("fastsim.pressure"));
        let mut nan = vec![0.0; 100];
        nan[7] = f64::NAN;
        assert!(fs.solve(&base, GridPressure::Given(&nan)).is_err());
        assert!(GridFastsim::new(Grid::line(10, 0.01).unwrap()).is_err());
        // Zero creepage, zero friction: zero forces, no NaN.
        let o = fs.solve(&input(a, b, 0.0, 0.0, 0.0), PARABOLIC).unwrap();
        assert_eq!((o.fx_n, o.fy_n, o.mz_nm, o.tgamma_n), (0.0, 0.0, 0.0, 0.0));
        assert_eq!(o.adhesion_area_m2, o.contact_area_m2);
        let o = fs
            .solve(
                &GridFastsimInput {
                    friction: GridFriction::Coulomb(0.0),
                    ..base
                },
                PARABOLIC,
            )
            .unwrap();
        assert_eq!((o.fx_n, o.max_traction_pa), (0.0, 0.0));
        assert_eq!(o.slip_area_m2, o.contact_area_m2);
        // A grid beside the ellipse: no contact element.
        let mut away = GridFastsim::new(Grid::new(10, 10, 1e-3, 1e-3, 0.1, 0.1).unwrap()).unwrap();
        let o = away.solve(&base, PARABOLIC).unwrap();
        assert_eq!(
            (o.fx_n, o.contact_area_m2, o.equivalent_semi_axes_m),
            (0.0, 0.0, [0.0; 2])
        );
        assert!(away.state().iter().all(|s| *s == ElementState::Exterior));
        // The rigid slip the march used, CONTACT's scaled spin terms (zero
        // before a solve).
        let fresh = GridFastsim::new(grid(a, b, 10, 10)).unwrap();
        assert!(fresh.rigid_slip()[1].iter().all(|w| *w == 0.0));
        let o = fs.solve(&input(a, b, 1e-3, 2e-4, 0.3), PARABOLIC).unwrap();
        let [l1, l2, l3] = o.applied.flexibilities_m_per_pa;
        let [wx, wy] = fs.rigid_slip();
        let g = *fs.grid();
        let (ix, iy) = (2, 7);
        let i = g.index(ix, iy);
        assert!(rel(wx[i], 1e-3 - l1 / l3 * 0.3 * g.y_m(iy)) < 1e-14);
        let x = g.x_m(ix) + g.dx_m / 6.0;
        assert!(rel(wy[i], 2e-4 + l2 / l3 * 0.3 * x) < 1e-14);
    }

    /// On fine grids with the pressure normalised, the grid's forces
    /// converge to the strip solver's ([`crate::core::fastsim`], which
    /// has no first-element offset), in partial slip too.
    #[test]
    fn converges_to_the_strip_solver() {
        use crate::core::fastsim::{Fastsim, FastsimInput};
        let (a, b) = (6e-3, 4e-3);
        for (xi, eta) in [(1e-3, 0.0), (0.0, 1.5e-3), (2e-3, 1e-3)] {
            let mut strips = Fastsim::new(400, 400).unwrap();
            let s = strips
                .solve(&FastsimInput {
                    semi_axis_x_m: a,
                    semi_axis_y_m: b,
                    normal_force_n: 82e3,
                    shear_modulus_pa: 82e9,
                    poisson_ratio: 0.28,
                    friction_coefficient: 0.3,
                    static_friction_coefficient: 0.3,
                    creepage_long: xi,
                    creepage_lat: eta,
                    spin_per_m: 0.0,
                })
                .unwrap();
            let mut fs = GridFastsim::new(grid(a, b, 440, 440)).unwrap();
            let inp = GridFastsimInput {
                flexibility: GridFlexibility::Kalker { blending: false },
                creep_table: CreepInterpolation::Smooth,
                ..input(a, b, xi, eta, 0.0)
            };
            let p = GridPressure::Hertz {
                bound: TractionBound::Parabolic,
                scaling: BoundScaling::NormalForce,
            };
            let o = fs.solve(&inp, p).unwrap();
            let (f, fs_) = (o.fx_n.hypot(o.fy_n), s.fx_n.hypot(s.fy_n));
            assert!(rel(f, fs_) < 4e-3, "({xi}, {eta}): {f} vs {fs_}");
        }
    }
}
