//! What a calculation leaves behind for the getters, in SI and the
//! solver's sign conventions (forces on body 1), whichever module: one
//! [`Outcome`] per contact patch. The getters convert to the caller's units
//! ([`crate::units::Units`]) when they read it.

use std::sync::OnceLock;

use railcontact_solver::core::cache::KernelCache;
use railcontact_solver::core::fastsim_grid::AppliedFlexibility;
use railcontact_solver::core::grid::Grid;
use railcontact_solver::core::influence::KernelKind;
use railcontact_solver::core::layer::LayerFields;
use railcontact_solver::core::material::{CombinedMaterial, Material};
use railcontact_solver::core::solution::{ElementFields, ElementState};
use railcontact_solver::core::solve::displacement_differences;
use railcontact_solver::core::viscoelastic::Viscoelastic;
use serde::{Deserialize, Serialize};

use crate::error::{CntcError, Result};

/// A solved contact patch.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Outcome {
    /// The potential contact grid, in the patch's contact frame
    /// (x rolling, y lateral) \[m\].
    pub grid: Grid,
    /// Per-element fields on `grid` (index `iy * nx + ix`), of every
    /// model (FASTSIM's on the same grid).
    pub fields: ElementFields,
    /// An elasto-plastic interfacial layer's state per element on `grid`
    /// (M = 4 with TAU_C0 > 0): the yield limit, the plastic deformation
    /// and where the layer flowed without slip (CONTACT's TAUCRT, UPLSX,
    /// UPLSY and plasticity area; those elements are adhesion in
    /// `fields.state`).
    pub layer: Option<LayerFields>,
    /// Friction coefficient per element [-] (empty: `friction_coefficient`
    /// everywhere).
    pub mu: Vec<f64>,
    /// The static friction coefficient of the patch (FSTAT) [-].
    pub friction_coefficient: f64,
    /// Normal force on body 1 \[N\].
    pub normal_force_n: f64,
    /// Tangential forces on body 1 \[N\].
    pub fx_n: f64,
    /// See `fx_n`.
    pub fy_n: f64,
    /// Spin moment on body 1 about the patch's reference point \[N m\].
    pub mz_nm: f64,
    /// Approach \[m\].
    pub approach_m: f64,
    /// Creepages xi, eta [-] and spin phi \[1/m\] of the solution (those
    /// found when forces were prescribed); a shift (T = 1): shifts \[m\]
    /// and rotation \[rad\].
    pub creepages: [f64; 3],
    /// Whether `creepages` are a shift (T = 1).
    pub is_shift: bool,
    /// Rolling speed \[m/s\].
    pub rolling_speed_m_per_s: f64,
    /// Rolling direction CHI \[rad\] of a wheel/rail patch: 0, or pi
    /// rolling backwards (module 1; 0 elsewhere).
    #[serde(default)]
    pub rolling_direction_rad: f64,
    /// Largest pressure \[Pa\].
    pub max_pressure_pa: f64,
    /// Largest tangential traction \[Pa\].
    pub max_traction_pa: f64,
    /// Contact, adhesion and slip areas \[m²\].
    pub areas_m2: [f64; 3],
    /// Frictional power per unit rolling speed \[N\] (steady rolling).
    pub tgamma_n: f64,
    /// Contact elements on the border of the grid (CONTACT's positive
    /// `ierror`).
    pub border_elements: usize,
    /// The Hertzian problem behind the grid (module 3 Hertzian options).
    pub hertz: Option<HertzInfo>,
    /// Sensitivities dF/d(input), rows Fn, Fx, Fy, Mz, columns pen, xi,
    /// eta, phi, in SI (computed when S >= 2).
    pub sensitivities: Option<[[f64; 4]; 4]>,
    /// Maximum surface temperatures of body 1 and 2 \[K\] (H = 3).
    pub max_temperature_k: Option<[f64; 2]>,
    /// Surface temperatures per element \[K\] (H = 3).
    pub temperature_k: Option<[Vec<f64>; 2]>,
    /// Rigid slip per element (x, y): per rolled distance [-] in rolling,
    /// the shift \[m\] of a shift (T = 1); `None` without friction.
    pub rigid_slip: Option<[Vec<f64>; 2]>,
    /// How [`Outcome::displacements_m`] computes the displacement
    /// differences from `grid` and `fields` when a getter first asks for
    /// them (CONTACT's US, which it computes after the solve in `soutpt`);
    /// `None`: not available (the getters say why). The calculation does
    /// not compute them: most callers never read them.
    pub displacement_source: Option<DisplacementSource>,
    /// The displacement differences once computed (never serialised: a
    /// receiver computes them from the source as the sender would). The
    /// calculation that makes an outcome sets `grid`, `fields` and the
    /// source before any getter reads it; nothing changes them after.
    #[serde(skip)]
    displacements: OnceLock<[Vec<f64>; 3]>,
    /// Where a module 1 patch lies (module 3: `None`).
    pub location: Option<Location>,
    /// The flexibilities and the slope reduction factor of a patch solved
    /// by the modified FASTSIM or FaStrip (M = 2, 3, 5; `None` otherwise): CONTACT's
    /// FLX(1:3) and K_EFF after a calculation (`cntc_getparameters` task
    /// 2).
    pub fastsim: Option<AppliedFlexibility>,
    /// Wall and CPU time of the calculation \[s\].
    pub time_s: f64,
}

/// The Hertzian solution behind a module 3 grid (`cntc_gethertzcontact`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct HertzInfo {
    /// Curvatures A, B \[1/m\].
    pub a1_per_m: f64,
    /// See `a1_per_m`.
    pub b1_per_m: f64,
    /// Semi-axes a, b \[m\].
    pub aa_m: f64,
    /// See `aa_m`.
    pub bb_m: f64,
    /// Scale factor of the potential contact area [-].
    pub scale: f64,
}

/// How an outcome's displacement differences (x, y, n) \[m\] follow from
/// its grid and tractions: body 1's elastic surface displacement minus
/// body 2's under the tractions on body 1, at every element of the grid,
/// the exterior ones too (CONTACT computes those only with A = 2), in the
/// outcome's frame and element order.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum DisplacementSource {
    /// No tractions: zero everywhere.
    Unloaded,
    /// The exact model: u = A p, one product of the half-space influence
    /// operator of the two materials on the outcome's grid (the solver's
    /// operator: the influence functions do not depend on the rolling
    /// direction the solver turns its grid to), an interfacial layer's
    /// shear (M = 4) included, its plastic deformation not (that is
    /// [`Outcome::layer`]). In contact u_n = approach - h; in a transient
    /// step the displacement of the step's tractions.
    Influence {
        /// Body 1's material.
        body1: Material,
        /// Body 2's material.
        body2: Material,
        /// The interfacial layer's tangential flexibility \[m/Pa\] (0
        /// without one).
        layer_flexibility_m_per_pa: f64,
        /// Viscoelastic bodies (M = 1; None: elastic).
        viscoelastic: Option<Viscoelastic>,
    },
    /// FASTSIM (M = 2, 3, module 3 and module 1's patches), as CONTACT's:
    /// u_x, u_y the flexibilities L1/k, L2/k times the tractions (zero
    /// outside contact); u_n the normal row of u = A p with the two
    /// materials when the normal problem was solved (B = 0, as module 1
    /// always does), zero with a Hertzian traction bound (B = 2, 3, as
    /// CONTACT sets it).
    Fastsim {
        /// L1/k, L2/k \[m/Pa\].
        flexibilities_m_per_pa: [f64; 2],
        /// Body 1's and body 2's materials with B = 0.
        normal: Option<[Material; 2]>,
    },
    /// A module 1 patch solved with FaStrip (M = 5): the getters refuse.
    /// CONTACT's are its FASTSIM march's displacements, which the strip
    /// part's tractions do not give where it rewrote a row (L/k times the
    /// final tractions lie 14-21 % from CONTACT's UX there).
    WheelRailFastrip,
}

/// Where a wheel/rail patch lies (`cntc_getcontactlocation`), SI, in
/// CONTACT's reporting frame: a left wheel's y and angles are already those
/// of the actual (left) side; the getter converts units only.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Location {
    /// Contact reference point in track coordinates (x, y, z) \[m\] and the
    /// contact angle \[rad\].
    pub track: [f64; 4],
    /// In rail profile coordinates (x, y, z, s along the profile) \[m\] and
    /// the angle \[rad\].
    pub rail: [f64; 5],
    /// In wheel profile coordinates (x, y, z, s) \[m\] and the angle \[rad\].
    pub wheel: [f64; 5],
    /// Pressure centre in track coordinates (x, y) \[m\].
    pub pressure_centre: [f64; 2],
    /// Wheel profile marker in track coordinates: x, y, z \[m\], roll, yaw
    /// \[rad\].
    pub wheel_marker_track: [f64; 5],
    /// Rail profile marker in track coordinates: y, z \[m\], roll \[rad\].
    pub rail_marker_track: [f64; 3],
    /// Contact reference point in wheelset coordinates (x, y, z) \[m\] and
    /// angle \[rad\].
    pub wheelset: [f64; 4],
    /// Wheel profile marker in wheelset coordinates: x, y, z \[m\], roll,
    /// yaw \[rad\].
    pub wheel_marker_wheelset: [f64; 5],
    /// The contact patch's forces in the track frame on the rail (x, y,
    /// z) \[N\].
    pub force_track_n: [f64; 3],
    /// The massless rail's deflection (F = 3; zero otherwise): along track
    /// y and z \[m\] (CONTACT's DY_DEFL, DZ_DEFL, the same for every
    /// patch).
    pub rail_deflection_m: [f64; 2],
}

impl Outcome {
    /// An outcome of `grid` with every field zero and no contact (an
    /// approach too small to touch).
    pub fn no_contact(grid: Grid, gap_m: Vec<f64>, approach_m: f64) -> Self {
        let n = grid.len();
        Outcome {
            grid,
            fields: ElementFields {
                pressure_pa: vec![0.0; n],
                traction_x_pa: vec![0.0; n],
                traction_y_pa: vec![0.0; n],
                slip_x: vec![0.0; n],
                slip_y: vec![0.0; n],
                state: vec![ElementState::Exterior; n],
                gap_m,
            },
            layer: None,
            mu: Vec::new(),
            friction_coefficient: 0.0,
            normal_force_n: 0.0,
            fx_n: 0.0,
            fy_n: 0.0,
            mz_nm: 0.0,
            approach_m,
            creepages: [0.0; 3],
            is_shift: false,
            rolling_speed_m_per_s: 0.0,
            rolling_direction_rad: 0.0,
            max_pressure_pa: 0.0,
            max_traction_pa: 0.0,
            areas_m2: [0.0; 3],
            tgamma_n: 0.0,
            border_elements: 0,
            hertz: None,
            sensitivities: None,
            max_temperature_k: None,
            temperature_k: None,
            rigid_slip: None,
            // No tractions, no displacement.
            displacement_source: Some(DisplacementSource::Unloaded),
            displacements: OnceLock::new(),
            location: None,
            fastsim: None,
            time_s: 0.0,
        }
    }

    /// Whether per-element fields are available on [`Outcome::grid`].
    pub fn has_fields(&self) -> bool {
        self.fields.pressure_pa.len() == self.grid.len()
    }

    /// The displacement differences (x, y, n) \[m\] per element on
    /// `grid` ([`DisplacementSource`]): computed on the first call from
    /// `grid`, `fields` and [`Outcome::displacement_source`] (one product
    /// of the influence operator, kernels from [`KernelCache::global`]),
    /// the same afterwards. An error when the source is missing or does
    /// not fit the fields.
    pub fn displacements_m(&self) -> Result<&[Vec<f64>; 3]> {
        if let Some(u) = self.displacements.get() {
            return Ok(u);
        }
        let u = self.compute_displacements()?;
        Ok(self.displacements.get_or_init(|| u))
    }

    fn compute_displacements(&self) -> Result<[Vec<f64>; 3]> {
        let missing =
            |why: &str| CntcError::NotSupported(format!("displacement differences: {why}"));
        let n = self.grid.len();
        let zero = || vec![0.0; n];
        let f = &self.fields;
        let p = [&f.traction_x_pa[..], &f.traction_y_pa, &f.pressure_pa];
        match self.displacement_source {
            None => return Err(missing("the last calculation did not leave them")),
            Some(DisplacementSource::Unloaded) => return Ok([zero(), zero(), zero()]),
            Some(DisplacementSource::WheelRailFastrip) => {
                return Err(missing(
                    "module 1 with M = 5 (FaStrip on the wheel/rail patches) does not give them \
                     (CONTACT's are the FASTSIM march's displacements, which this library does \
                     not keep); M = 0, 2, 3 do",
                ))
            }
            Some(_) => {}
        }
        if !p.iter().all(|c| c.len() == n) {
            return Err(missing("no tractions on every element of the grid"));
        }
        // u = A p with the kernels of `grid` (a hit of the process cache
        // after a calculation in this process).
        let product =
            |body1, body2, layer: f64, visc: Option<&Viscoelastic>| -> Result<[Vec<f64>; 3]> {
                if !(layer.is_finite() && layer >= 0.0) {
                    return Err(CntcError::Input(format!(
                        "displacement differences: the layer flexibility {layer} is not a \
                     finite value >= 0"
                    )));
                }
                let material =
                    CombinedMaterial::new(body1, body2).map_err(CntcError::from_contact)?;
                let kernels = KernelCache::global().get_viscoelastic(
                    &self.grid,
                    &material,
                    layer,
                    visc,
                    KernelKind::Displacement,
                );
                let mut u = [zero(), zero(), zero()];
                displacement_differences(&kernels, &mut kernels.workspace(), p, &mut u);
                Ok(u)
            };
        match self.displacement_source {
            None
            | Some(DisplacementSource::Unloaded)
            | Some(DisplacementSource::WheelRailFastrip) => Ok([zero(), zero(), zero()]),
            Some(DisplacementSource::Influence {
                body1,
                body2,
                layer_flexibility_m_per_pa,
                viscoelastic,
            }) => product(
                body1,
                body2,
                layer_flexibility_m_per_pa,
                viscoelastic.as_ref(),
            ),
            Some(DisplacementSource::Fastsim {
                flexibilities_m_per_pa: [l1, l2],
                normal,
            }) => {
                let ux = f.traction_x_pa.iter().map(|p| l1 * p).collect();
                let uy = f.traction_y_pa.iter().map(|p| l2 * p).collect();
                let un = match normal {
                    Some([body1, body2]) => {
                        let [_, _, un] = product(body1, body2, 0.0, None)?;
                        un
                    }
                    None => zero(),
                };
                Ok([ux, uy, un])
            }
        }
    }

    /// Contact, adhesion and slip areas \[m²\] of a contact area `area_m2`
    /// with the share `adhesion_fraction` in adhesion (a model without
    /// element states).
    pub fn areas_by_fraction(area_m2: f64, adhesion_fraction: f64) -> [f64; 3] {
        [
            area_m2,
            area_m2 * adhesion_fraction,
            area_m2 * (1.0 - adhesion_fraction),
        ]
    }

    /// Contact, adhesion and slip areas from the element states \[m²\];
    /// with an elasto-plastic layer's flags (`plastic`, empty without),
    /// the elements that flowed are in contact but neither adhesion nor
    /// slip (CONTACT's plasticity area, contact minus adhesion minus
    /// slip).
    pub fn areas_of(grid: &Grid, state: &[ElementState], plastic: &[bool]) -> [f64; 3] {
        let da = grid.dx_m * grid.dy_m;
        let (mut adh, mut slip, mut plast) = (0usize, 0usize, 0usize);
        for (i, s) in state.iter().enumerate() {
            match s {
                ElementState::Adhesion if plastic.get(i) == Some(&true) => plast += 1,
                ElementState::Adhesion => adh += 1,
                ElementState::Slip => slip += 1,
                ElementState::Exterior => {}
            }
        }
        [
            (adh + slip + plast) as f64 * da,
            adh as f64 * da,
            slip as f64 * da,
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn displacements_are_computed_once_or_refused_with_a_typed_error() {
        fn shared<T: Send + Sync + Clone>() {}
        shared::<Outcome>();
        let grid = Grid::new(6, 5, 1e-3, 1e-3, -3e-3, -2.5e-3).unwrap();
        let o = Outcome::no_contact(grid, vec![0.0; 30], 0.0);
        assert!(o
            .displacements_m()
            .unwrap()
            .iter()
            .flatten()
            .all(|u| *u == 0.0));
        let mut o = Outcome::no_contact(grid, vec![0.0; 30], 0.0);
        o.displacement_source = None;
        assert!(matches!(
            o.displacements_m(),
            Err(CntcError::NotSupported(m)) if m.contains("did not leave them")
        ));
        let mut o = Outcome::no_contact(grid, vec![0.0; 30], 0.0);
        o.fields.pressure_pa[14] = 1e8;
        o.fields.traction_y_pa.pop();
        o.displacement_source = Some(DisplacementSource::Influence {
            body1: Material::STEEL,
            body2: Material::STEEL,
            layer_flexibility_m_per_pa: 0.0,
            viscoelastic: None,
        });
        assert!(matches!(
            o.displacements_m(),
            Err(CntcError::NotSupported(_))
        ));
        o.fields.traction_y_pa.push(0.0);
        let first = o.displacements_m().unwrap() as *const _;
        assert!(o.displacements_m().unwrap()[2][14] > 0.0);
        assert_eq!(o.displacements_m().unwrap() as *const _, first);
        // A clone carries the values computed.
        let c = o.clone();
        assert_eq!(c.displacements_m().unwrap(), o.displacements_m().unwrap());
    }
}
