//! What a contact problem is configured with, whichever module: the unit
//! convention, CONTACT's control digits, materials, friction and solver
//! parameters, all stored in SI. The setters here are those of
//! `cntc_setflags`, `cntc_setmaterialparameters`, `cntc_setfrictionmethod`,
//! `cntc_setsolverflags` and `cntc_settemperaturedata`.
//!
//! A value the library does not have (an M digit of FaStrip, a
//! temperature-dependent friction law) is kept as the problem's
//! [`Config::unsupported`]: the setter logs it at once and every
//! `cntc_calculate` refuses with `CNTC_err_notsupported` naming it, until a
//! supported value replaces it.

use railcontact_solver::core::fastsim::SlopeReduction;
use railcontact_solver::core::fastsim_grid::{FastsimMaterial, GridFlexibility};
use railcontact_solver::core::friclaw::{FallingShape, SlipStart, SlipVelocityLaw};
use railcontact_solver::core::layer::InterfacialLayer;
use railcontact_solver::core::material::{CombinedMaterial, Material};
use railcontact_solver::core::problem::Friction;
use railcontact_solver::core::viscoelastic::{Sls, Viscoelastic};

use crate::error::{CntcError, Result};
use crate::flags;
use crate::units::Units;

/// CONTACT's control digits (clamped to their ranges as CONTACT clamps
/// them).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Digits {
    /// C1: 0 left rail, 1 right rail, 4 left roller, 5 right roller (module 1).
    pub config: i32,
    /// P: 0/1 continue from the previous case, 2/3 start afresh.
    pub pvtime: i32,
    /// B: traction bound (0 from the normal problem).
    pub bound: i32,
    /// T: 0 frictionless, 1 shift, 2 transient rolling, 3 steady rolling.
    pub tang: i32,
    /// N: module 1 0 position / 1 vertical force; module 3 0 approach / 1
    /// normal force.
    pub norm: i32,
    /// F: 0 creepages, 1 Fx and eta, 2 Fx and Fy (module 3).
    pub force: i32,
    /// S: sensitivities (0 none, 2 normal, 3 normal and tangential).
    pub sens: i32,
    /// D: module 1 discretisation (2 planar; 4 conformal, refused).
    pub discns: i32,
    /// C3: influence coefficients (2, 3 half-space; 4 conformal).
    pub inflcf: i32,
    /// E: extra rigid slip (0/1 none; 9 given: set by
    /// `cntc_setextrarigidslip`).
    pub exrhs: i32,
    /// I: initial estimate.
    pub iestim: i32,
    /// O: output to the out-file (stored).
    pub output: i32,
    /// W: flow output (stored).
    pub flow: i32,
    /// R: 0/1 solve, 2/3 check only.
    pub ret: i32,
    /// A: mat-file (stored; not written).
    pub matfil: i32,
    /// O_s: subsurface output (stored).
    pub sbsout: i32,
    /// A_s: subs-file (stored; not written).
    pub sbsfil: i32,
    /// M: the material model (set by `cntc_setmaterialparameters`).
    pub mater: i32,
    /// L: the friction law (set by `cntc_setfrictionmethod`).
    pub frclaw: i32,
    /// V: friction variation (module 1; set by `cntc_setfrictionmethod`).
    pub varfrc: i32,
    /// H: temperature (set by `cntc_settemperaturedata`).
    pub heat: i32,
    /// G: the solver (set by `cntc_setsolverflags`).
    pub gausei: i32,
    /// Write an input file (stored; never written).
    pub wrtinp: i32,
}

impl Default for Digits {
    fn default() -> Self {
        Digits {
            config: 0,
            pvtime: 2,
            bound: 0,
            tang: 3,
            norm: 1,
            force: 0,
            sens: 0,
            discns: 2,
            inflcf: 2,
            exrhs: 0,
            iestim: 0,
            output: 1,
            flow: 1,
            ret: 0,
            matfil: 0,
            sbsout: 0,
            sbsfil: 0,
            mater: 0,
            frclaw: 0,
            varfrc: 0,
            heat: 0,
            gausei: 0,
            wrtinp: 0,
        }
    }
}

/// The material model (the M digit).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MaterialModel {
    /// M = 0: elastic half-spaces, Kalker's exact theory.
    Elastic,
    /// M = 3: FASTSIM with Kalker's three flexibilities of the ellipse
    /// (blended, [`FastsimMaterial::kalker`]), M = 2: with one given
    /// flexibility FLX; both with Spiryagin-Polach-Cole's slope reduction
    /// (k0, alpha_inf, beta); k0 = alpha = beta = 1 is Kalker's FASTSIM.
    ModifiedFastsim(FastsimMaterial),
    /// M = 5: modified FaStrip ([`railcontact_solver::core::fastrip`]):
    /// strip theory in the adhesion areas of FASTSIM's rows, Kalker's three
    /// flexibilities (blended) and the same slope reduction as M = 3.
    ModifiedFastrip(FastsimMaterial),
    /// M = 4: elastic half-spaces with an interfacial (third-body) layer
    /// between them, elastic or elasto-plastic (GG3, LAYTHK, TAU_C0,
    /// K_TAU; [`railcontact_solver::core::layer`]), Kalker's exact theory.
    InterfacialLayer(InterfacialLayer),
    /// M = 1: viscoelastic bodies, standard linear solids (FG and TC per
    /// body; [`railcontact_solver::core::viscoelastic`]), Kalker's exact
    /// theory in steady rolling; the shear moduli are the glassy ones.
    Viscoelastic([Sls; 2]),
}

impl MaterialModel {
    /// The viscoelastic bodies of M = 1 rolling at `veloc_m_per_s`
    /// (CONTACT's VELOC).
    pub fn viscoelastic(&self, veloc_m_per_s: f64) -> Option<Viscoelastic> {
        match *self {
            MaterialModel::Viscoelastic([body1, body2]) => Some(Viscoelastic {
                rolling_speed_m_per_s: veloc_m_per_s,
                body1,
                body2,
            }),
            _ => None,
        }
    }

    /// The interfacial layer of M = 4.
    pub fn layer(&self) -> Option<InterfacialLayer> {
        match *self {
            MaterialModel::InterfacialLayer(l) => Some(l),
            _ => None,
        }
    }

    /// The simplified material of M = 2, 3 (modified FASTSIM) and M = 5
    /// (modified FaStrip).
    pub fn fastsim(&self) -> Option<FastsimMaterial> {
        match *self {
            MaterialModel::ModifiedFastsim(f) | MaterialModel::ModifiedFastrip(f) => Some(f),
            _ => None,
        }
    }
}

/// CONTACT's smallest layer shear modulus GG3, 1e-6 N/mm² \[Pa\]
/// (`cntc_setmaterialparameters`: `max(1d-6, gg3)` in its internal units).
const MIN_LAYER_MODULUS_PA: f64 = 1.0;

/// CONTACT's smallest layer thickness LAYTHK, 1e-9 mm \[m\] (`max(1d-9,
/// laythk)`): a layer is always there with M = 4, if thin.
const MIN_LAYER_THICKNESS_M: f64 = 1e-12;

/// A yield limit TAU_C0 from 1e10 N/mm² \[Pa\] on is none (CONTACT sets
/// it to 0: an elastic layer).
const NO_YIELD_LIMIT_PA: f64 = 1e16;

/// Materials, in SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MaterialParams {
    /// Poisson ratios of body 1 and 2 [-].
    pub poisson: [f64; 2],
    /// Shear moduli of body 1 and 2 \[Pa\].
    pub shear_modulus_pa: [f64; 2],
    /// The model.
    pub model: MaterialModel,
}

impl Default for MaterialParams {
    /// CONTACT's default: steel (G = 82 GPa, nu = 0.28), elastic.
    fn default() -> Self {
        MaterialParams {
            poisson: [0.28; 2],
            shear_modulus_pa: [82.0e9; 2],
            model: MaterialModel::Elastic,
        }
    }
}

impl MaterialParams {
    /// The combined material (errors name CONTACT's parameters).
    pub fn combined(&self) -> Result<CombinedMaterial> {
        let body = |i: usize| Material {
            shear_modulus_pa: self.shear_modulus_pa[i],
            poisson_ratio: self.poisson[i],
        };
        CombinedMaterial::new(body(0), body(1)).map_err(|e| {
            CntcError::Input(format!(
                "cntc_setmaterialparameters: GG1, GG2 = {:e}, {:e} Pa, POISS1, POISS2 = {}, {}: {e}",
                self.shear_modulus_pa[0], self.shear_modulus_pa[1], self.poisson[0], self.poisson[1]
            ))
        })
    }
}

/// The friction law (the L digit), in SI; a slip-velocity law's rolling
/// speed is the problem's `VELOC`, set at calculation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FrictionLaw {
    /// L = 0: Coulomb's law with one coefficient.
    Coulomb(f64),
    /// L = 2, 3, 4 (and 5, Polach's law as CONTACT maps it to L = 4): a
    /// falling law; `rolling_speed_m_per_s` is filled at calculation.
    Falling(SlipVelocityLaw),
}

impl Default for FrictionLaw {
    fn default() -> Self {
        FrictionLaw::Coulomb(0.3)
    }
}

impl FrictionLaw {
    /// The friction of this law at rolling speed `v` \[m/s\] with the
    /// start of the slip-velocity iteration.
    pub fn friction(&self, v_m_per_s: f64, start: SlipStart) -> Friction {
        match *self {
            FrictionLaw::Coulomb(mu) => Friction::coulomb(mu),
            FrictionLaw::Falling(law) => Friction::falling(SlipVelocityLaw {
                rolling_speed_m_per_s: v_m_per_s,
                start,
                ..law
            }),
        }
    }

    /// The static coefficient (FSTAT).
    pub fn static_coefficient(&self) -> f64 {
        match self {
            FrictionLaw::Coulomb(mu) => *mu,
            FrictionLaw::Falling(law) => law.static_coefficient(),
        }
    }
}

/// Solver parameters (`cntc_setsolverflags`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverParams {
    /// EPS: relative tolerance of the normal and tangential solvers.
    pub eps: f64,
    /// MAXOUT: limit of the normal/tangential alternation.
    pub maxout: usize,
    /// INISLP: the start of the slip-velocity iteration (G = 2, 3, 4).
    pub start: SlipStart,
    /// MXSENS, EPSENS of the sensitivities (G = 6).
    pub sens_iterations: usize,
    /// EPSENS.
    pub sens_eps: f64,
}

impl Default for SolverParams {
    fn default() -> Self {
        SolverParams {
            eps: 1e-6,
            maxout: 30,
            start: SlipStart::Previous,
            sens_iterations: 50,
            sens_eps: 1e-4,
        }
    }
}

/// Bulk temperatures and thermal properties (H = 3), SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Thermal {
    /// Bulk temperature of body 1 and 2 \[K\].
    pub bulk_k: [f64; 2],
    /// Specific heat \[J/(kg K)\].
    pub heat_capacity: [f64; 2],
    /// Conductivity \[W/(m K)\].
    pub conductivity: [f64; 2],
    /// Density \[kg/m³\].
    pub density: [f64; 2],
}

/// The configuration of a contact problem.
#[derive(Debug, Clone, Default)]
pub struct Config {
    /// The unit convention of its inputs and outputs.
    pub units: Units,
    /// Control digits.
    pub digits: Digits,
    /// Materials.
    pub material: MaterialParams,
    /// Friction law (module 3, and module 1 without variation).
    pub friction: FrictionLaw,
    /// Module 1, V = 1: friction per contact angle (angles \[rad\],
    /// static coefficients [-]; same law shape for all).
    pub friction_by_angle: Option<(Vec<f64>, Vec<FrictionLaw>)>,
    /// Solver parameters.
    pub solver: SolverParams,
    /// Temperatures (H = 3), when given.
    pub thermal: Option<Thermal>,
    /// The first configuration this library cannot solve (a flag value or
    /// method it does not have), with the setter that gave it; refused at
    /// every calculation until replaced.
    pub unsupported: Option<(&'static str, String)>,
}

/// Clamps `v` to [lo, hi] (CONTACT's max(lo, min(hi, v)) for digits).
fn clamp(v: i32, lo: i32, hi: i32) -> i32 {
    v.clamp(lo, hi)
}

impl Config {
    /// Refuses to calculate while an unsupported configuration stands.
    pub fn check_supported(&self) -> Result<()> {
        match &self.unsupported {
            Some((call, what)) => Err(CntcError::NotSupported(format!("{what} (set by {call})"))),
            None => Ok(()),
        }
    }

    /// Records (or, with `None`, clears) the unsupported configuration of
    /// setter `call` that `key` identifies, replacing an earlier one of
    /// the same setter.
    fn mark(&mut self, call: &'static str, what: Option<String>) {
        match what {
            Some(w) => self.unsupported = Some((call, w)),
            None => {
                if matches!(self.unsupported, Some((c, _)) if c == call) {
                    self.unsupported = None;
                }
            }
        }
    }

    /// `cntc_setflags`: one (code, value). Returns a warning for the log
    /// (an unknown code, a value clamped or stored without effect); an
    /// unsupported value is also kept in [`Config::unsupported`].
    pub fn set_flag(&mut self, module: u8, code: i32, value: i32) -> Option<String> {
        let d = &mut self.digits;
        match code {
            0 => {}
            flags::IF_UNITS => match Units::from_code(value) {
                Some(u) => self.units = u,
                None => {
                    let what = format!(
                        "CNTC_if_units = {value}: the unit conventions are CNTC_un_cntc (1934), \
                         CNTC_un_spck (1935) and CNTC_un_si (1936)"
                    );
                    self.mark("cntc_setflags", Some(what.clone()));
                    return Some(what);
                }
            },
            flags::IC_CONFIG => {
                d.config = clamp(value, 0, 5);
                if d.config == 2 || d.config == 3 {
                    let what = format!(
                        "C1 = {} (CNTC_ic_config): 0 left rail, 1 right rail, 4 left roller, 5 \
                         right roller",
                        d.config
                    );
                    self.mark("cntc_setflags C1", Some(what.clone()));
                    return Some(what);
                }
                self.mark("cntc_setflags C1", None);
            }
            flags::IC_PVTIME => d.pvtime = clamp(value, 0, 3),
            flags::IC_BOUND => {
                d.bound = clamp(value, 0, 6);
                self.check_bound();
            }
            flags::IC_TANG => d.tang = clamp(value, 0, 3),
            flags::IC_NORM => d.norm = clamp(value, 0, 1),
            flags::IC_FORCE => {
                d.force = if module == 3 {
                    clamp(value, 0, 2)
                } else {
                    clamp(value, 0, 3)
                };
                if module == 1 && d.force == 2 {
                    let what = format!(
                        "F = {} (CNTC_ic_force) in module 1 is not supported: give the pitch rate \
                         VPITCH (F = 0), the total force FX_WS (F = 1) or use the massless rail \
                         (F = 3)",
                        d.force
                    );
                    self.mark("cntc_setflags F", Some(what.clone()));
                    return Some(what);
                }
                self.mark("cntc_setflags F", None);
            }
            flags::IC_SENS => d.sens = clamp(value, 0, 3),
            flags::IC_DISCNS => {
                if (0..=9).contains(&value) {
                    d.discns = value;
                }
                if d.discns >= 4 {
                    let what = format!(
                        "D = {} (CNTC_ic_discns): conformal contact in module 1 is not supported; D = 2 planar",
                        d.discns
                    );
                    self.mark("cntc_setflags D", Some(what.clone()));
                    return Some(what);
                }
                self.mark("cntc_setflags D", None);
            }
            flags::IC_INFLCF => {
                if (0..=4).contains(&value) {
                    d.inflcf = value;
                }
                if d.inflcf == 4 {
                    let what = "C3 = 4 (CNTC_ic_inflcf): conformal influence coefficients are not \
                                supported through this interface; C3 = 2 or 3 (half-space)"
                        .to_string();
                    self.mark("cntc_setflags C3", Some(what.clone()));
                    return Some(what);
                }
                self.mark("cntc_setflags C3", None);
            }
            flags::IC_IFMETH | flags::IC_IFVARI => {}
            flags::IC_MATER => {
                return Some(
                    "the M digit cannot be set by cntc_setflags: use cntc_setmaterialparameters"
                        .to_string(),
                )
            }
            flags::IC_EXRHS => d.exrhs = clamp(value, 0, 3),
            flags::IC_IESTIM => d.iestim = clamp(value, 0, 3),
            flags::IC_MATFIL => d.matfil = if (0..=2).contains(&value) { value } else { 0 },
            flags::IC_OUTPUT => d.output = clamp(value, 0, 5),
            flags::IC_SBSFIL => d.sbsfil = if (0..=2).contains(&value) { value } else { 0 },
            flags::IC_SBSOUT => d.sbsout = clamp(value, 0, 4),
            flags::IC_FLOW => d.flow = clamp(value, 0, 9),
            flags::IC_XFLOW => {}
            // CONTACT coarsens a patch of NPOMAX elements or more; every
            // patch here is solved on the DX asked (docs/cntc.md).
            flags::IC_NPOMAX => {
                return Some(format!(
                    "CNTC_ic_npomax = {value} is not applied: every patch is solved on the DX \
                     asked (CONTACT doubles DX and DS of a patch of NPOMAX elements or more)"
                ))
            }
            flags::IC_RETURN => d.ret = clamp(value, 0, 3),
            flags::IF_WRTINP => d.wrtinp = value,
            flags::IF_NCASE | flags::IF_TIMERS => {}
            flags::IF_IDEBUG | flags::IF_LICDBG | flags::IF_OPENMP | flags::IF_MODE => {
                // Global flags: the caller passes these on to
                // cntc_setglobalflags (as CONTACT does).
            }
            other => return Some(format!("unknown flag code {other} is ignored")),
        }
        None
    }

    /// Whether the B digit suits the material model (B = 2, 3 prescribe a
    /// Hertzian pressure for FASTSIM; 4-6 are SDEC/KPEC/ANALYN bounds).
    fn check_bound(&mut self) {
        let what = match (self.digits.bound, self.material.model) {
            (0, _) => None,
            (2 | 3, MaterialModel::ModifiedFastsim(_) | MaterialModel::ModifiedFastrip(_)) => {
                None
            }
            (b @ (2 | 3), _) => {
                Some(format!(
                    "B = {b} (CNTC_ic_bound) with M = {}: a prescribed {} pressure under Kalker's \
                     exact theory is not supported (B = 2, 3 are for FASTSIM and FaStrip, M = 2, 3, \
                     5)",
                    self.digits.mater,
                    if b == 2 { "elliptical" } else { "parabolic" }
                ))
            }
            (b, _) => Some(format!(
                "B = {b} (CNTC_ic_bound): the SDEC, KPEC and ANALYN traction bounds are not supported"
            )),
        };
        self.mark("cntc_setflags B", what);
    }

    /// `cntc_setmaterialparameters` (M digit `m`, parameters in this
    /// problem's units).
    pub fn set_material(&mut self, m: i32, p: &[f64]) -> Result<()> {
        const COUNTS: [usize; 13] = [4, 8, 8, 7, 8, 7, 4, 4, 0, 0, 0, 0, 4];
        let known = (0..=7).contains(&m) || (10..=12).contains(&m);
        if !known {
            return Err(CntcError::Input(format!(
                "M = {m} (cntc_setmaterialparameters): the M digit is 0-7, or 10-12 for its second digit"
            )));
        }
        let want = COUNTS[m as usize];
        if (want == 0 && p.len() >= 2) || (want != 0 && p.len() != want) {
            return Err(CntcError::Input(format!(
                "M = {m} (cntc_setmaterialparameters) needs {want} parameters, got {}",
                p.len()
            )));
        }
        if m >= 10 {
            let what = (m == 12).then(|| {
                "M2 = 2 (cntc_setmaterialparameters): damping is not supported".to_string()
            });
            self.mark("cntc_setmaterialparameters M2", what);
            return Ok(());
        }
        let u = self.units;
        // M = 2: FLX [volume/force], refused unless it is > 0 and finite in
        // SI too (not under- or overflowing).
        let flx_m_per_pa = if m == 2 { u.flexibility(p[4]) } else { 0.0 };
        if m == 2 && !(p[4] > 0.0 && flx_m_per_pa > 0.0 && flx_m_per_pa.is_finite()) {
            return Err(CntcError::Input(format!(
                "FLX = {} (cntc_setmaterialparameters, M = 2): the flexibility \
                 [volume/force] must be finite and > 0",
                p[4]
            )));
        }
        self.material.poisson = [p[0], p[1]];
        self.material.shear_modulus_pa = [u.stress(p[2]), u.stress(p[3])];
        self.digits.mater = m;
        let what = match m {
            0 => {
                self.material.model = MaterialModel::Elastic;
                None
            }
            2 | 3 | 5 => {
                let k = if m == 2 { 5 } else { 4 };
                let reduction = SlopeReduction {
                    initial_factor: p[k].max(1e-6),
                    limit_ratio: p[k + 1].max(1e-6),
                    transition_rate: p[k + 2].max(1e-6),
                    ..SlopeReduction::NONE
                };
                self.material.model = match m {
                    2 => MaterialModel::ModifiedFastsim(FastsimMaterial {
                        flexibility: GridFlexibility::Given {
                            flexibility_m_per_pa: flx_m_per_pa,
                        },
                        reduction,
                    }),
                    3 => MaterialModel::ModifiedFastsim(FastsimMaterial::kalker(reduction)),
                    _ => MaterialModel::ModifiedFastrip(FastsimMaterial::kalker(reduction)),
                };
                None
            }
            1 => {
                // FG and TC per body (TC in seconds, whatever the units);
                // checked at calculation (naming viscoelastic.body1...).
                let sls = |fg: f64, tc: f64| Sls {
                    relaxation_ratio: fg,
                    creep_relaxation_time_s: tc,
                };
                self.material.model =
                    MaterialModel::Viscoelastic([sls(p[4], p[6]), sls(p[5], p[7])]);
                None
            }
            4 => {
                // GG3, LAYTHK, TAU_C0 and K_TAU, clamped as CONTACT clamps
                // them; a negative TAU_C0 is refused at calculation
                // (naming interfacial_layer.yield_limit_pa).
                let tau_c0 = u.stress(p[6]);
                self.material.model = MaterialModel::InterfacialLayer(InterfacialLayer {
                    thickness_m: u.len(p[5]).max(MIN_LAYER_THICKNESS_M),
                    shear_modulus_pa: u.stress(p[4]).max(MIN_LAYER_MODULUS_PA),
                    yield_limit_pa: if tau_c0 >= NO_YIELD_LIMIT_PA {
                        0.0
                    } else {
                        tau_c0
                    },
                    hardening_pa_per_m: u.stress(p[7]) / u.length_m(),
                });
                None
            }
            _ => Some(format!(
                "M = {m} (CONTACT's original FaStrip, for testing) is not supported; M = 5 \
                 (modified FaStrip) is"
            )),
        };
        self.mark("cntc_setmaterialparameters", what);
        self.check_bound();
        Ok(())
    }

    /// `cntc_setfrictionmethod` (method `imeth` = 10 V + L, parameters in
    /// this problem's units); `module` 1 or 3.
    pub fn set_friction(&mut self, module: u8, imeth: i32, p: &[f64]) -> Result<()> {
        const COUNTS: [usize; 7] = [2, 0, 7, 7, 7, 3, 6];
        let (v, l) = (imeth.div_euclid(10), imeth.rem_euclid(10));
        if !(0..=2).contains(&v) || !(0..=6).contains(&l) {
            return Err(CntcError::Friction(format!(
                "method {imeth} (cntc_setfrictionmethod): V digit 0-2, L digit 0-6"
            )));
        }
        if l == 1 {
            return Ok(()); // L = 1: keep the previous law
        }
        if v >= 1 && module != 1 {
            return Err(CntcError::Friction(format!(
                "V = {v} (cntc_setfrictionmethod): friction variation needs module 1"
            )));
        }
        let per = COUNTS[l as usize];
        let (nvf, expect) = if v >= 1 && !p.is_empty() {
            let nvf = p[0].round();
            if !(1.0..=1000.0).contains(&nvf) {
                return Err(CntcError::Friction(format!(
                    "NVF = {} (cntc_setfrictionmethod, V = {v}): 1 to 1000 rows",
                    p[0]
                )));
            }
            (nvf as usize, 1 + nvf as usize * (1 + per))
        } else {
            (1, per)
        };
        if p.len() != expect {
            return Err(CntcError::Friction(format!(
                "method {imeth} (cntc_setfrictionmethod) with {nvf} row(s) needs {expect} parameters, got {}",
                p.len()
            )));
        }
        if v == 2 {
            self.mark(
                "cntc_setfrictionmethod",
                Some("V = 2 (friction varying along the rail) is not supported; V = 1 (by contact angle) is".to_string()),
            );
            return Ok(());
        }
        if l == 6 {
            self.mark(
                "cntc_setfrictionmethod",
                Some("L = 6 (temperature-dependent friction) is not supported".to_string()),
            );
            return Ok(());
        }
        let u = self.units;
        let law = |q: &[f64]| -> FrictionLaw {
            match l {
                0 => FrictionLaw::Coulomb(q[0].min(q[1]).max(1e-6)),
                2..=4 => FrictionLaw::Falling(SlipVelocityLaw {
                    shape: match l {
                        2 => FallingShape::Linear,
                        3 => FallingShape::Rational,
                        _ => FallingShape::Exponential,
                    },
                    kinetic_coefficient: q[0].max(1e-6),
                    falling_coefficients: [q[1].max(0.0), q[3].max(0.0)],
                    half_velocities_m_per_s: [
                        u.velocity(q[2]).max(1e-7),
                        u.velocity(q[4]).max(1e-7),
                    ],
                    rolling_speed_m_per_s: 1.0,
                    memory_distance_m: u.len(q[5]).max(0.0),
                    memory_velocity_m_per_s: u.velocity(q[6]).max(0.0),
                    start: SlipStart::Previous,
                    max_iterations: 0,
                }),
                _ => {
                    // L = 5, Polach's law as CONTACT states it: exponential
                    // with mu_kin = A mu_s, mu_1 = mu_s - mu_kin, s_h =
                    // ln 2 / B, and CONTACT's fixed memory (1 um, 10 mm/s).
                    let fstat = q[0].max(1e-6);
                    let a = q[1].clamp(0.0, 1.0);
                    let b_s_per_m = q[2] / u.length_m();
                    FrictionLaw::Falling(SlipVelocityLaw {
                        shape: FallingShape::Exponential,
                        kinetic_coefficient: (a * fstat).max(1e-6),
                        falling_coefficients: [fstat - a * fstat, 0.0],
                        half_velocities_m_per_s: [std::f64::consts::LN_2 / b_s_per_m, 10.0],
                        rolling_speed_m_per_s: 1.0,
                        memory_distance_m: 1e-6,
                        memory_velocity_m_per_s: 0.01,
                        start: SlipStart::Previous,
                        max_iterations: 0,
                    })
                }
            }
        };
        if v == 0 {
            self.friction = law(p);
            self.friction_by_angle = None;
        } else {
            let mut angles = Vec::with_capacity(nvf);
            let mut laws = Vec::with_capacity(nvf);
            for row in p[1..].chunks(1 + per) {
                angles.push(row[0]);
                laws.push(law(&row[1..]));
            }
            if angles.windows(2).any(|w| w[1] <= w[0]) {
                return Err(CntcError::Friction(format!(
                    "V = 1 (cntc_setfrictionmethod): the contact angles must increase, got {angles:?}"
                )));
            }
            self.friction = laws[0];
            self.friction_by_angle = Some((angles, laws));
        }
        self.digits.frclaw = if l == 5 { 4 } else { l };
        self.digits.varfrc = v;
        self.mark("cntc_setfrictionmethod", None);
        Ok(())
    }

    /// `cntc_setsolverflags` (G digit, integer and real parameters).
    pub fn set_solver(&mut self, g: i32, ip: &[i32], rp: &[f64]) -> Result<()> {
        const NINTS: [usize; 7] = [4, 0, 5, 5, 5, 5, 1];
        const NREALS: [usize; 7] = [1, 0, 4, 4, 2, 8, 1];
        if !(0..=6).contains(&g) {
            return Err(CntcError::Input(format!(
                "G = {g} (cntc_setsolverflags): the G digit is 0-6"
            )));
        }
        let gi = g as usize;
        if ip.len() != NINTS[gi] || rp.len() != NREALS[gi] {
            return Err(CntcError::Input(format!(
                "G = {g} (cntc_setsolverflags) needs {} integer and {} real parameters, got {} and {}",
                NINTS[gi],
                NREALS[gi],
                ip.len(),
                rp.len()
            )));
        }
        match g {
            1 => {}
            6 => {
                self.solver.sens_iterations = ip[0].max(1) as usize;
                self.solver.sens_eps = rp[0].max(1e-20);
            }
            _ => {
                self.digits.gausei = g;
                self.solver.eps = rp[0].max(1e-20);
                self.solver.maxout = ip[3].max(1) as usize;
                if (2..=4).contains(&g) {
                    self.solver.start = match ip[4] {
                        i if i > 0 => SlipStart::Sticking,
                        i if i < 0 => SlipStart::Sliding,
                        _ => SlipStart::Previous,
                    };
                }
            }
        }
        Ok(())
    }

    /// `cntc_settemperaturedata` (H digit, parameters in this problem's
    /// units).
    pub fn set_temperature(&mut self, h: i32, p: &[f64]) -> Result<()> {
        if !(h == 0 || h == 1 || h == 3) {
            return Err(CntcError::Input(format!(
                "H = {h} (cntc_settemperaturedata): the H digit is 0, 1 or 3"
            )));
        }
        let want = if h == 3 { 9 } else { 0 };
        if (want == 0 && p.len() >= 2) || (want != 0 && p.len() != want) {
            return Err(CntcError::Input(format!(
                "H = {h} (cntc_settemperaturedata) needs {want} parameters, got {}",
                p.len()
            )));
        }
        self.digits.heat = h;
        // The flash temperatures are computed (module3), but differ from
        // CONTACT's library by up to 14 % of the temperature rise in
        // partial slip (equal slips and forces; the models' discretisation
        // of the heat flux differs): refused until they agree.
        self.mark(
            "cntc_settemperaturedata",
            (h == 3).then(|| {
                "H = 3 (surface temperatures): not yet offered through this interface (the \
                 flash temperatures differ from CONTACT's by up to 14 % of the rise)"
                    .to_string()
            }),
        );
        if h == 3 {
            let u = self.units;
            // Conductivity W/(length K), density kg/length³ in CONTACT's
            // units.
            let l = u.length_m();
            self.thermal = Some(Thermal {
                bulk_k: [u.temperature_k(p[0]), u.temperature_k(p[4])],
                heat_capacity: [p[1], p[5]],
                conductivity: [p[2] / l, p[6] / l],
                density: [p[3] / (l * l * l), p[7] / (l * l * l)],
            });
        } else if h == 0 {
            self.thermal = None;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn npomax_is_named_as_not_applied_and_other_codes_as_unknown() {
        let mut c = Config::default();
        let warning = c.set_flag(1, flags::IC_NPOMAX, 50_000).expect("a warning");
        assert!(
            warning.contains("CNTC_ic_npomax = 50000 is not applied"),
            "{warning}"
        );
        let unknown = c.set_flag(1, 424_242, 1).expect("a warning");
        assert!(unknown.contains("unknown flag code 424242"), "{unknown}");
    }
}
