//! Module 3: one contact patch as CONTACT's basic contact problem states
//! it: a potential contact area (Hertzian or given), an undeformed distance,
//! an approach or normal force, creepages, shifts or tangential forces, and
//! the exact solver (M = 0) or FASTSIM (M = 2, 3) to solve it.

use std::time::Instant;

use railcontact_solver::core::cache::KernelCache;
use railcontact_solver::core::error::ContactError;
use railcontact_solver::core::fastrip::GridSimplified;
use railcontact_solver::core::fastsim::TractionBound;
use railcontact_solver::core::fastsim_grid::{
    equivalent_ellipse, BoundScaling, CreepInterpolation, FastsimMaterial, GridFastsimInput,
    GridFriction, GridPressure, RollingSense,
};
use railcontact_solver::core::force::{
    solve_prescribed_force, solve_prescribed_force_step, ForceControlSettings, PrescribedForce,
};
use railcontact_solver::core::grid::Grid;
use railcontact_solver::core::hertz::{complete_elliptic, hertz, HertzLoad};
use railcontact_solver::core::layer::InterfacialLayer;
use railcontact_solver::core::material::CombinedMaterial;
use railcontact_solver::core::normal::NormalLoad;
use railcontact_solver::core::problem::{
    ContactProblem, Creepages, ExtraRigidSlip, Friction, Kinematics, ShiftStep, SolverSettings,
};
use railcontact_solver::core::sensitivity::exact_jacobian;
use railcontact_solver::core::solution::{
    ContactSolution, ElementState, IterationLimit, SolveStatus,
};
use railcontact_solver::core::solve::{layer_flexibility, ContactSolver};
use railcontact_solver::core::temperature::{flash_temperatures, ThermalBody, ThermalInput};
use railcontact_solver::core::viscoelastic::Viscoelastic;

use crate::config::{Config, FrictionLaw, MaterialModel, Thermal};
use crate::error::{CntcError, Result};
use crate::outcome::{DisplacementSource, HertzInfo, Outcome};

/// The potential contact area (`cntc_sethertzcontact`,
/// `cntc_setpotcontact`), SI.
#[derive(Debug, Clone, PartialEq)]
pub enum Potcon {
    /// IPOTCN = -1, -2, -3: the grid of mx x my elements over the Hertz
    /// ellipse scaled by `scale`, its undeformed distance A x² + B y².
    Hertz {
        /// Elements in x and y.
        mx: usize,
        /// See `mx`.
        my: usize,
        /// How the ellipse is given.
        spec: HertzSpec,
        /// SCALE [-].
        scale: f64,
    },
    /// IPOTCN = 1-4: a given grid.
    Grid(Grid),
}

/// The Hertzian options of module 3.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum HertzSpec {
    /// IPOTCN = -1: curvatures A1, B1 \[1/m\].
    Curvatures(f64, f64),
    /// IPOTCN = -2: curvature A1 \[1/m\] and the ellipticity AA/BB [-].
    CurvatureAndRatio(f64, f64),
    /// IPOTCN = -3: semi-axes AA, BB \[m\].
    SemiAxes(f64, f64),
}

/// The undeformed distance of a non-Hertzian problem
/// (`cntc_setundeformeddistc`), SI.
#[derive(Debug, Clone, PartialEq)]
pub enum Udist {
    /// IBASE = 1: b1 x² + b2 x y + b3 y² + b4 x + b5 y + b6 (b1-b3 \[1/m\],
    /// b4-b5 [-], b6 \[m\]).
    Quadratic([f64; 6]),
    /// IBASE = 2: a body of revolution about an axle at x = XM with
    /// radius RM, and a profile p(y) sampled from Y1 every DY1 \[m\].
    Revolution {
        /// XM \[m\].
        xm: f64,
        /// RM \[m\].
        rm: f64,
        /// Y1 \[m\].
        y1: f64,
        /// DY1 \[m\].
        dy1: f64,
        /// p(y_k) \[m\].
        heights: Vec<f64>,
    },
    /// IBASE = 3: b1 sin(b2 (x - b3)) - b4 sin(b5 (x - b6)) + x²/b7 +
    /// y²/b8 (SI).
    Sines([f64; 8]),
    /// IBASE = 9: one value per element \[m\].
    Elementwise(Vec<f64>),
}

impl Udist {
    /// The undeformed distance at the element centres of `grid`.
    fn on(&self, grid: &Grid) -> Result<Vec<f64>> {
        let mut h = vec![0.0; grid.len()];
        if let Udist::Elementwise(v) = self {
            if v.len() != grid.len() {
                return Err(CntcError::Discretisation(format!(
                    "the undeformed distance (IBASE = 9) has {} values for a potential contact \
                     area of {} x {} = {} elements: set the grid first",
                    v.len(),
                    grid.nx,
                    grid.ny,
                    grid.len()
                )));
            }
            h.copy_from_slice(v);
            return Ok(h);
        }
        for iy in 0..grid.ny {
            let y = grid.y_m(iy);
            for ix in 0..grid.nx {
                let x = grid.x_m(ix);
                h[grid.index(ix, iy)] = match self {
                    Udist::Quadratic(b) => {
                        b[0] * x * x + b[1] * x * y + b[2] * y * y + b[3] * x + b[4] * y + b[5]
                    }
                    Udist::Revolution {
                        xm,
                        rm,
                        y1,
                        dy1,
                        heights,
                    } => {
                        let t = ((y - y1) / dy1).clamp(0.0, (heights.len() - 1) as f64);
                        let k = (t.floor() as usize).min(heights.len().saturating_sub(2));
                        let f = t - k as f64;
                        let p = if heights.len() == 1 {
                            heights[0]
                        } else {
                            heights[k] * (1.0 - f) + heights[k + 1] * f
                        };
                        p + (x - xm) * (x - xm) / (2.0 * rm)
                    }
                    Udist::Sines(b) => {
                        b[0] * (b[1] * (x - b[2])).sin() - b[3] * (b[4] * (x - b[5])).sin()
                            + x * x / b[6]
                            + y * y / b[7]
                    }
                    Udist::Elementwise(_) => unreachable!("handled above"),
                };
            }
        }
        if let Some(i) = h.iter().position(|v| !v.is_finite()) {
            return Err(CntcError::Input(format!(
                "cntc_setundeformeddistc: the undeformed distance of element {} is not finite",
                i + 1
            )));
        }
        Ok(h)
    }
}

/// Kinematic inputs (SI): set by `cntc_setpenetration`,
/// `cntc_setnormalforce`, `cntc_setcreepages`, ...
#[derive(Debug, Clone, PartialEq)]
pub struct Kin {
    /// VELOC \[m/s\].
    pub veloc: f64,
    /// CHI \[rad\].
    pub chi: f64,
    /// DQ \[m\].
    pub dq: f64,
    /// DT \[s\] (stored).
    pub dt: f64,
    /// PEN \[m\].
    pub pen: f64,
    /// FN \[N\].
    pub fn_n: f64,
    /// CKSI, CETA [-] or \[m\] (shift), CPHI \[1/m\] or \[rad\] (shift).
    pub creep: [f64; 3],
    /// FX, FY relative to FSTAT FN [-] (F = 1, 2).
    pub frel: [f64; 2],
    /// Extra rigid slip (E = 9): wx, wy per element, [-] (rolling) or \[m\]
    /// (shift).
    pub extra: Option<(Vec<f64>, Vec<f64>)>,
}

impl Default for Kin {
    fn default() -> Self {
        Kin {
            veloc: 1.0,
            chi: 0.0,
            dq: 1e-3,
            dt: 1.0,
            pen: 0.0,
            fn_n: 0.0,
            creep: [0.0; 3],
            frel: [0.0; 2],
            extra: None,
        }
    }
}

/// A module 3 contact problem (ire, icp).
#[derive(Default)]
pub struct Patch {
    /// Units, digits, materials, friction, solver parameters.
    pub config: Config,
    /// The potential contact area.
    pub potcon: Option<Potcon>,
    /// The undeformed distance (non-Hertzian).
    pub udist: Option<Udist>,
    /// Kinematic inputs.
    pub kin: Kin,
    /// The last calculation's result.
    pub outcome: Option<Outcome>,
    /// Subsurface stress blocks and their results.
    pub subs: crate::subsurface::Blocks,
    /// Cases calculated.
    pub ncase: usize,
    /// Time spent in calculations since the last reset \[s\]: the
    /// calculations' wall time on the calling thread (reported as both
    /// CPU and wall time).
    pub time_s: f64,
    /// The solver, with the grid, materials and rolling direction it was
    /// built for (its history continues a transient sequence).
    solver: Option<(SolverKey, ContactSolver)>,
}

/// What a solver is built for.
#[derive(Debug, Clone, Copy, PartialEq)]
struct SolverKey {
    grid: Grid,
    material: CombinedMaterial,
    chi: f64,
    /// M = 4's layer (its flexibility is in the solver's kernels, its
    /// yield limit and hardening in its history).
    layer: Option<InterfacialLayer>,
    /// M = 1's viscoelastic bodies (in the solver's kernels).
    viscoelastic: Option<Viscoelastic>,
}

/// The exact normal problem's solution FASTSIM takes its pressure from
/// (B = 0).
struct NormalSolution {
    /// Pressure per element \[Pa\].
    pressure_pa: Vec<f64>,
    /// Normal force \[N\].
    normal_force_n: f64,
    /// Approach \[m\].
    approach_m: f64,
    /// The error of an iteration limit reached.
    status: Option<CntcError>,
}

/// The Hertzian semi-axes and curvatures of `spec` under `load` with
/// `e_star` (= G/(1 - nu)).
fn hertz_geometry(spec: HertzSpec, e_star: f64, load: NormalLoad) -> Result<(f64, f64, f64, f64)> {
    let bad = |what: String| CntcError::Input(format!("cntc_sethertzcontact: {what}"));
    let hload = match load {
        NormalLoad::NormalForce(f) => HertzLoad::NormalForce { normal_force_n: f },
        NormalLoad::Approach(d) => HertzLoad::Approach { approach_m: d },
    };
    let (a1, b1) = match spec {
        HertzSpec::Curvatures(a, b) => (a, b),
        HertzSpec::CurvatureAndRatio(a, aob) => {
            // B_l / A_s = (K - D)/((1 - m) D), m = 1 - (b/a)^2 with a >= b
            // the semi-axis along the smaller curvature.
            let r = aob.min(1.0 / aob);
            let m = 1.0 - r * r;
            let e = complete_elliptic(m).map_err(|e| bad(format!("AOB = {aob}: {e}")))?;
            let ratio = (e.k - e.d) / ((1.0 - m) * e.d);
            if aob <= 1.0 {
                (a, a / ratio) // x semi-axis the shorter: A the larger curvature
            } else {
                (a, a * ratio)
            }
        }
        HertzSpec::SemiAxes(aa, bb) => {
            let (long, short) = if aa >= bb { (aa, bb) } else { (bb, aa) };
            let m = 1.0 - (short / long) * (short / long);
            let e = complete_elliptic(m).map_err(|e| bad(format!("AA, BB = {aa}, {bb} m: {e}")))?;
            let a_small = match load {
                NormalLoad::NormalForce(p) => {
                    3.0 * p * e.d / (2.0 * std::f64::consts::PI * long.powi(3) * e_star)
                }
                NormalLoad::Approach(d) => d * e.d / (long * long * e.k),
            };
            let b_large = a_small * (e.k - e.d) / ((1.0 - m) * e.d);
            if aa >= bb {
                (a_small, b_large)
            } else {
                (b_large, a_small)
            }
        }
    };
    let h = hertz(a1, b1, e_star, hload).map_err(|e| bad(format!("{e}")))?;
    Ok((a1, b1, h.semi_axis_x_m, h.semi_axis_y_m))
}

/// The element count of a grid direction (CONTACT takes max(1, n)).
fn count(n: usize, name: &str) -> Result<usize> {
    use railcontact_solver::core::grid::{MAX_ELEMENTS_PER_DIRECTION, MIN_ELEMENTS};
    if (MIN_ELEMENTS..=MAX_ELEMENTS_PER_DIRECTION).contains(&n) {
        Ok(n)
    } else {
        Err(CntcError::Discretisation(format!(
            "{name} = {n}: this library needs {MIN_ELEMENTS} to {MAX_ELEMENTS_PER_DIRECTION} elements"
        )))
    }
}

impl Patch {
    /// The problem's load (N digit).
    fn load(&self) -> Result<NormalLoad> {
        if self.config.digits.norm == 1 {
            let f = self.kin.fn_n;
            if !(f.is_finite() && f > 0.0) {
                return Err(CntcError::Input(format!(
                    "the normal force FN = {f} N must be > 0 (cntc_setnormalforce)"
                )));
            }
            Ok(NormalLoad::NormalForce(f))
        } else {
            let d = self.kin.pen;
            if !d.is_finite() {
                return Err(CntcError::Input(
                    "the approach PEN is not finite (cntc_setpenetration)".into(),
                ));
            }
            Ok(NormalLoad::Approach(d))
        }
    }

    /// The grid, its undeformed distance and the Hertzian solution behind
    /// them.
    fn geometry(
        &self,
        material: &CombinedMaterial,
        load: NormalLoad,
    ) -> Result<(Grid, Vec<f64>, Option<HertzInfo>)> {
        match &self.potcon {
            None => Err(CntcError::Discretisation(
                "no potential contact area: call cntc_sethertzcontact or cntc_setpotcontact".into(),
            )),
            Some(Potcon::Hertz {
                mx,
                my,
                spec,
                scale,
            }) => {
                if let NormalLoad::Approach(d) = load {
                    if d <= 0.0 {
                        return Err(CntcError::Input(format!(
                            "a Hertzian problem (cntc_sethertzcontact) needs an approach PEN > 0, got {d} m"
                        )));
                    }
                }
                let e_star = material.effective_modulus_pa();
                let (a1, b1, aa, bb) = hertz_geometry(*spec, e_star, load)?;
                let (mx, my) = (count(*mx, "MX")?, count(*my, "MY")?);
                let (wx, wy) = (aa * scale, bb * scale);
                let grid = Grid::new(mx, my, 2.0 * wx / mx as f64, 2.0 * wy / my as f64, -wx, -wy)
                    .map_err(|e| CntcError::Discretisation(e.to_string()))?;
                let gap = ContactProblem::quadratic_gap(&grid, a1, b1);
                let info = HertzInfo {
                    a1_per_m: a1,
                    b1_per_m: b1,
                    aa_m: aa,
                    bb_m: bb,
                    scale: *scale,
                };
                Ok((grid, gap, Some(info)))
            }
            Some(Potcon::Grid(grid)) => {
                let udist = self.udist.as_ref().ok_or_else(|| {
                    CntcError::Input(
                        "no undeformed distance for the potential contact area: call \
                         cntc_setundeformeddistc"
                            .into(),
                    )
                })?;
                Ok((*grid, udist.on(grid)?, None))
            }
        }
    }

    /// `cntc_calculate` of this patch: solves and keeps the outcome.
    /// `Ok(n)`: n >= 0 contact elements on the grid's border; the outcome
    /// of a solve that stopped at an iteration limit is kept and its error
    /// returned.
    pub fn calculate(&mut self, cache: &KernelCache) -> Result<i32> {
        let t0 = Instant::now();
        let r = self.calculate_timed(cache);
        self.time_s += t0.elapsed().as_secs_f64();
        self.ncase += 1;
        r
    }

    fn calculate_timed(&mut self, cache: &KernelCache) -> Result<i32> {
        self.config.check_supported()?;
        if self.config.digits.ret >= 2 {
            return Ok(0); // R = 2, 3: check the input, skip the calculation
        }
        let material = self.config.material.combined()?;
        let load = self.load()?;
        let (grid, gap, hertz) = self.geometry(&material, load)?;
        let t0 = Instant::now();
        let mut outcome = match self.config.material.model {
            MaterialModel::ModifiedFastsim(fastsim) | MaterialModel::ModifiedFastrip(fastsim) => {
                let fastrip = matches!(
                    self.config.material.model,
                    MaterialModel::ModifiedFastrip(_)
                );
                let (mut outcome, status) =
                    self.fastsim(cache, &material, load, hertz, grid, gap, fastsim, fastrip)?;
                if let Some(e) = status {
                    outcome.hertz = hertz;
                    self.outcome = Some(outcome);
                    return Err(e);
                }
                outcome
            }
            MaterialModel::Elastic
            | MaterialModel::InterfacialLayer(_)
            | MaterialModel::Viscoelastic(_) => {
                let (mut outcome, status) = self.exact(cache, material, load, grid, gap)?;
                if let Some(e) = status {
                    outcome.hertz = hertz;
                    self.outcome = Some(outcome);
                    return Err(e);
                }
                outcome
            }
        };
        outcome.hertz = hertz;
        outcome.time_s = t0.elapsed().as_secs_f64();
        let border = outcome.border_elements as i32;
        self.outcome = Some(outcome);
        Ok(border)
    }

    /// The exact model: the outcome, and the error of an iteration limit
    /// reached (CONTACT keeps that solution and returns the error).
    fn exact(
        &mut self,
        cache: &KernelCache,
        material: CombinedMaterial,
        load: NormalLoad,
        grid: Grid,
        gap: Vec<f64>,
    ) -> Result<(Outcome, Option<CntcError>)> {
        let d = self.config.digits;
        let k = &self.kin;
        let friction = self
            .config
            .friction
            .friction(k.veloc, self.config.solver.start);
        let fstat = self.config.friction.static_coefficient();
        let creep = Creepages {
            creepage_long: k.creep[0],
            creepage_lat: k.creep[1],
            spin_per_m: k.creep[2],
        };
        let mut settings = SolverSettings::default();
        let eps = self.config.solver.eps.clamp(1e-14, 0.1);
        settings.normal.tolerance = eps;
        settings.tangential.tolerance = eps;
        settings.coupling_max_iterations = self.config.solver.maxout.clamp(1, 1000);
        settings.allow_border_contact = true;
        // M = 4: the interfacial layer between the bodies.
        let layer = self.config.material.model.layer();
        settings.interfacial_layer = layer;
        // M = 1: viscoelastic bodies rolling at VELOC.
        settings.viscoelastic = self.config.material.model.viscoelastic(k.veloc);
        let step = match d.tang {
            1 => Some(ShiftStep {
                load,
                shift_x_m: k.creep[0],
                shift_y_m: k.creep[1],
                rotation_rad: k.creep[2],
                rolling_m: 0.0,
            }),
            2 => Some(ShiftStep::rolling(load, k.dq, &creep)),
            _ => None,
        };
        let kinematics = match (d.tang, &step) {
            (0, _) => Kinematics::Frictionless,
            (3, _) => Kinematics::SteadyRolling(creep),
            (_, Some(s)) => Kinematics::Transient(vec![*s]),
            _ => unreachable!("T is 0-3"),
        };
        // CONTACT takes the spin's rigid slip a sixth of the rolled
        // distance downstream, at (x + cos(chi) dq/6, y + sin(chi) dq/6),
        // dq the grid's element size in steady rolling (its FACPHI = 1/6;
        // the user guide's rigid slip of rolling): the same here, as an
        // extra rigid slip, so that spin cases give CONTACT's numbers.
        let dq_spin = match d.tang {
            3 => grid.dx_m,
            2 => k.dq,
            _ => 0.0,
        };
        let (sn, cs) = k.chi.sin_cos();
        let spin_shift = [
            -k.creep[2] * sn * dq_spin / 6.0,
            k.creep[2] * cs * dq_spin / 6.0,
        ];
        let extra_rigid_slip = match (&k.extra, d.tang) {
            (Some((wx, wy)), 1) => Some(ExtraRigidSlip {
                shift_x_m: wx.clone(),
                shift_y_m: wy.clone(),
                ..Default::default()
            }),
            (extra, 2 | 3) if extra.is_some() || spin_shift != [0.0, 0.0] => {
                let n = grid.len();
                let (mut wx, mut wy) = match extra {
                    Some((wx, wy)) => (wx.clone(), wy.clone()),
                    None => (vec![0.0; n], vec![0.0; n]),
                };
                wx.iter_mut().for_each(|w| *w += spin_shift[0]);
                wy.iter_mut().for_each(|w| *w += spin_shift[1]);
                Some(ExtraRigidSlip {
                    slip_x: wx,
                    slip_y: wy,
                    ..Default::default()
                })
            }
            _ => None,
        };
        let problem = ContactProblem {
            material,
            friction,
            grid,
            gap_m: gap.clone(),
            load,
            kinematics,
            settings,
            rolling_direction_rad: if d.tang == 0 { 0.0 } else { k.chi },
            extra_rigid_slip,
            numerical_influence: None,
        };
        if self.config.thermal.is_some() && d.tang != 3 {
            return Err(CntcError::NotSupported(format!(
                "temperatures (H = 3) with T = {}: flash temperatures are computed in steady \
                 rolling (T = 3)",
                d.tang
            )));
        }
        let prescribed = match d.force {
            0 => PrescribedForce::default(),
            f => {
                let NormalLoad::NormalForce(fnorm) = load else {
                    return Err(CntcError::NotSupported(format!(
                        "F = {f} (tangential forces) with N = 0 (a prescribed approach): give the \
                         normal force (N = 1)"
                    )));
                };
                if d.tang == 0 {
                    return Err(CntcError::Input(format!(
                        "F = {f} needs a tangential problem (T = 1, 2 or 3)"
                    )));
                }
                let scale = fstat * fnorm;
                PrescribedForce {
                    force_x_n: Some(k.frel[0] * scale),
                    force_y_n: (f == 2).then_some(k.frel[1] * scale),
                }
            }
        };
        // A new solver when the grid, the materials or the rolling
        // direction changed, or the case starts afresh (P = 2, 3).
        let key = SolverKey {
            grid,
            material,
            chi: problem.rolling_direction_rad,
            layer,
            viscoelastic: problem.settings.viscoelastic,
        };
        let reuse = matches!(&self.solver, Some((k, _)) if *k == key);
        let continues = d.pvtime <= 1 && reuse;
        if (d.tang == 1 || d.tang == 2) && d.pvtime <= 1 && !reuse && self.outcome.is_some() {
            return Err(CntcError::Discretisation(
                "a transient case continuing the previous one (P = 0, 1) needs the same \
                 potential contact area, materials and rolling direction"
                    .into(),
            ));
        }
        if !reuse {
            self.solver = Some((key, ContactSolver::new(&problem, cache)));
        }
        let solver = &mut self.solver.as_mut().expect("set above").1;
        if !continues {
            solver.reset();
        }
        let solved: std::result::Result<(ContactSolution, [f64; 3]), ContactError> =
            match (&step, prescribed.any()) {
                (None, false) => solver
                    .solve(&problem)
                    .map(|mut v| (v.pop().expect("one solution"), k.creep)),
                (None, true) => solve_prescribed_force(
                    solver,
                    &problem,
                    prescribed,
                    ForceControlSettings::default(),
                )
                .map(|f| {
                    let c = f.creepages;
                    (f.solution, [c.creepage_long, c.creepage_lat, c.spin_per_m])
                }),
                (Some(s), false) => solver
                    .solve_next_step(&problem, s)
                    .map(|sol| (sol, k.creep)),
                (Some(s), true) => solve_prescribed_force_step(
                    solver,
                    &problem,
                    s,
                    prescribed,
                    ForceControlSettings::default(),
                )
                .map(|f| {
                    let st = f.step;
                    let c = if d.tang == 1 {
                        [st.shift_x_m, st.shift_y_m, st.rotation_rad]
                    } else {
                        [st.shift_x_m / k.dq, st.shift_y_m / k.dq, k.creep[2]]
                    };
                    (f.solution, c)
                }),
            };
        let (solution, creepages) = match solved {
            Ok(s) => s,
            Err(ContactError::NoContact { .. }) => {
                let NormalLoad::Approach(pen) = load else {
                    unreachable!("a normal force always makes contact")
                };
                self.solver = None;
                return Ok((Outcome::no_contact(grid, gap, pen), None));
            }
            Err(e) => {
                self.solver = None;
                return Err(CntcError::from_contact(e));
            }
        };
        let mut sensitivities = None;
        if d.sens >= 2 && d.tang == 3 {
            let solver = &self.solver.as_ref().expect("solved above").1;
            let mut at = problem.clone();
            at.kinematics = Kinematics::SteadyRolling(Creepages {
                creepage_long: creepages[0],
                creepage_lat: creepages[1],
                spin_per_m: creepages[2],
            });
            let j = exact_jacobian(solver, &at, &solution).map_err(CntcError::from_contact)?;
            sensitivities = Some(j.columns());
        }
        let status = match (solution.info.status, solution.info.limit) {
            (SolveStatus::Converged, _) => None,
            (_, Some(IterationLimit::Normal)) => Some(CntcError::Normal(format!(
                "no convergence within the iteration limit (residual {:.3e})",
                solution.info.normal_residual
            ))),
            _ => Some(CntcError::Tangential(format!(
                "no convergence within the iteration limit (residual {:.3e})",
                solution.info.tangential_residual
            ))),
        };
        let t = &solution.totals;
        let mut outcome = Outcome::no_contact(grid, gap, t.approach_m);
        outcome.border_elements = grid.loaded_border_elements(&solution.fields.pressure_pa);
        let mut fields = solution.fields;
        // An elasto-plastic layer's state per element (None for an
        // elastic one, or without friction).
        let layer_fields = self
            .solver
            .as_ref()
            .and_then(|(_, s)| s.layer_fields())
            .filter(|_| d.tang != 0);
        if d.tang == 0 {
            // Without friction CONTACT counts the contact area as adhesion.
            for s in fields.state.iter_mut() {
                if *s == ElementState::Slip {
                    *s = ElementState::Adhesion;
                }
            }
        }
        outcome.areas_m2 = Outcome::areas_of(
            &grid,
            &fields.state,
            layer_fields.as_ref().map_or(&[][..], |l| &l.plastic),
        );
        outcome.layer = layer_fields;
        outcome.rigid_slip = problem_rigid_slip(&grid, d.tang, &creepages, &problem);
        if let Some(t) = &self.config.thermal {
            let temperatures = flash_temperatures(&grid, &fields, &thermal_input(t, k.veloc))
                .map_err(CntcError::from_contact)?;
            outcome.max_temperature_k = Some([
                temperatures.summary.max_body1.temperature_k,
                temperatures.summary.max_body2.temperature_k,
            ]);
            outcome.temperature_k = Some([temperatures.body1_k, temperatures.body2_k]);
        }
        // CONTACT's US, computed when a getter asks: u = A p of the
        // tractions with the solver's materials and layer.
        outcome.displacement_source = Some(DisplacementSource::Influence {
            body1: problem.material.body1,
            body2: problem.material.body2,
            layer_flexibility_m_per_pa: layer_flexibility(&problem),
            viscoelastic: problem.settings.viscoelastic,
        });
        outcome.fields = fields;
        outcome.friction_coefficient = fstat;
        outcome.normal_force_n = t.normal_force_n;
        outcome.fx_n = t.fx_n;
        outcome.fy_n = t.fy_n;
        outcome.mz_nm = t.mz_nm;
        outcome.creepages = creepages;
        outcome.is_shift = d.tang == 1;
        outcome.rolling_speed_m_per_s = k.veloc;
        outcome.max_pressure_pa = t.max_pressure_pa;
        outcome.max_traction_pa = t.max_traction_pa;
        outcome.tgamma_n = t.tgamma_n;
        outcome.sensitivities = sensitivities;
        if let FrictionLaw::Falling(_) = self.config.friction {
            outcome.mu = self
                .solver
                .as_ref()
                .and_then(|(_, s)| s.friction_coefficients())
                .unwrap_or_default();
        }
        Ok((outcome, status))
    }

    /// FASTSIM (M = 2, 3) as CONTACT runs it: on the potential contact grid
    /// ([`GridFastsim`]), steady rolling with creepages, the traction bound
    /// Hertz's elliptic (B = 2) or Kalker's parabolic (B = 3) pressure of a
    /// Hertzian problem, or the exact normal problem's pressure (B = 0); the
    /// flexibilities `fastsim`'s (M = 3: those of the Hertz ellipse, a
    /// non-Hertzian grid's of the contact area's equivalent ellipse,
    /// blended as CONTACT blends them; M = 2: the given one); Coulomb
    /// friction or a falling law (L = 2-5) at the global slip velocity.
    /// With `fastrip` (M = 5) modified FaStrip
    /// ([`railcontact_solver::core::fastrip`]) on the same grid, pressure,
    /// flexibilities and slope reduction, the bound the static coefficient.
    /// The outcome has the per-element fields; with an iteration
    /// limit of the normal problem (B = 0) its error too.
    #[allow(clippy::too_many_arguments)]
    fn fastsim(
        &mut self,
        cache: &KernelCache,
        material: &CombinedMaterial,
        load: NormalLoad,
        info: Option<HertzInfo>,
        grid: Grid,
        gap: Vec<f64>,
        fastsim: FastsimMaterial,
        fastrip: bool,
    ) -> Result<(Outcome, Option<CntcError>)> {
        let d = self.config.digits;
        let m = d.mater;
        let method = if fastrip { "FaStrip" } else { "FASTSIM" };
        if d.tang != 3 || d.force != 0 {
            return Err(CntcError::NotSupported(format!(
                "{method} (M = {m}) with T = {}, F = {}: steady rolling (T = 3) with creepages \
                 (F = 0)",
                d.tang, d.force
            )));
        }
        if self.kin.extra.is_some() {
            return Err(CntcError::NotSupported(format!(
                "{method} (M = {m}) with an extra rigid slip (E = 9, cntc_setextrarigidslip)"
            )));
        }
        let friction = match self.config.friction {
            FrictionLaw::Coulomb(mu) => GridFriction::Coulomb(mu),
            FrictionLaw::Falling(law) => GridFriction::SlipVelocity(law),
        };
        // CONTACT's FASTSIM rolls along +x or -x only; another CHI is
        // taken as 0, as CONTACT does (check_roll_stepsize).
        let rolling = if (self.kin.chi - std::f64::consts::PI).abs() < 0.01 {
            RollingSense::MinusX
        } else {
            RollingSense::PlusX
        };
        // The traction bound's pressure, the ellipse of the flexibilities,
        // the normal force and the approach.
        let (pressure, bound, ellipse, fn_n, approach, status) = match (d.bound, info) {
            (b @ (2 | 3), Some(h)) => {
                let e_star = material.effective_modulus_pa();
                let hload = match load {
                    NormalLoad::NormalForce(f) => HertzLoad::NormalForce { normal_force_n: f },
                    NormalLoad::Approach(a) => HertzLoad::Approach { approach_m: a },
                };
                let sol = hertz(h.a1_per_m, h.b1_per_m, e_star, hload)
                    .map_err(|e| CntcError::Input(format!("{method}'s Hertz problem: {e}")))?;
                let bound = if b == 2 {
                    TractionBound::Elliptic
                } else {
                    TractionBound::Parabolic
                };
                let ellipse = [sol.semi_axis_x_m, sol.semi_axis_y_m];
                (
                    None,
                    bound,
                    ellipse,
                    sol.normal_force_n,
                    sol.approach_m,
                    None,
                )
            }
            (b @ (2 | 3), None) => {
                return Err(CntcError::NotSupported(format!(
                    "{method} (M = {m}) with B = {b} on a non-Hertzian potential contact area: the \
                     {} traction bound needs a Hertzian problem (cntc_sethertzcontact); B = 0 \
                     solves the normal problem",
                    if b == 2 { "elliptical" } else { "parabolic" }
                )))
            }
            (0, _) => {
                let Some(NormalSolution {
                    pressure_pa: pn,
                    normal_force_n: fn_n,
                    approach_m: approach,
                    status,
                }) = self.normal_pressure(cache, *material, load, grid, &gap)?
                else {
                    let NormalLoad::Approach(pen) = load else {
                        unreachable!("a normal force always makes contact")
                    };
                    return Ok((Outcome::no_contact(grid, gap, pen), None));
                };
                let ellipse = match info {
                    Some(h) => [h.aa_m, h.bb_m],
                    None => match equivalent_ellipse(&grid, &pn) {
                        Some(e) => e,
                        None => {
                            let mut o = Outcome::no_contact(grid, gap, approach);
                            o.fields.pressure_pa = pn;
                            return Ok((o, status));
                        }
                    },
                };
                (
                    Some(pn),
                    TractionBound::Parabolic,
                    ellipse,
                    fn_n,
                    approach,
                    status,
                )
            }
            (b, _) => {
                return Err(CntcError::NotSupported(format!(
                    "{method} (M = {m}) with B = {b}: B = 0 (the normal problem's pressure), 2 \
                     (elliptical) or 3 (parabolic)"
                )))
            }
        };
        let input = GridFastsimInput {
            semi_axis_x_m: ellipse[0],
            semi_axis_y_m: ellipse[1],
            normal_force_n: fn_n,
            shear_modulus_pa: material.shear_modulus_pa,
            poisson_ratio: material.poisson_ratio,
            creepage_long: self.kin.creep[0],
            creepage_lat: self.kin.creep[1],
            spin_per_m: self.kin.creep[2],
            rolling_speed_m_per_s: self.kin.veloc,
            friction,
            reduction: fastsim.reduction,
            flexibility: fastsim.flexibility,
            rolling,
            creep_table: CreepInterpolation::Contact,
        };
        let p = match &pressure {
            Some(pn) => GridPressure::Given(pn),
            None => GridPressure::Hertz {
                bound,
                scaling: BoundScaling::Analytic,
            },
        };
        let solve_error = |e| CntcError::Input(format!("{method}: {e}"));
        let mut solver = GridSimplified::new(grid, fastrip).map_err(CntcError::from_contact)?;
        let out = solver.solve(&input, p).map_err(solve_error)?;
        let fs = solver.march();
        let mut o = Outcome::no_contact(grid, Vec::new(), approach);
        o.fields = fs.fields(gap);
        o.border_elements = grid.loaded_border_elements(fs.pressure_pa());
        o.areas_m2 = [out.contact_area_m2, out.adhesion_area_m2, out.slip_area_m2];
        o.rigid_slip = Some(fs.rigid_slip());
        let applied = out.applied;
        let [l1, l2, _] = applied
            .flexibilities_m_per_pa
            .map(|l| l / applied.slope_factor);
        o.fastsim = Some(applied);
        o.displacement_source = Some(DisplacementSource::Fastsim {
            flexibilities_m_per_pa: [l1, l2],
            normal: pressure
                .is_some()
                .then_some([material.body1, material.body2]),
        });
        if let GridFriction::SlipVelocity(law) = friction {
            // CONTACT's MU field: the coefficient at the global slip
            // velocity (FaStrip's bound is the static one all the same).
            let mu_eff = if fastrip {
                law.coefficient(self.kin.veloc * self.kin.creep[0].hypot(self.kin.creep[1]))
            } else {
                out.friction_coefficient
            };
            o.mu = vec![mu_eff; grid.len()];
        }
        o.friction_coefficient = self.config.friction.static_coefficient();
        // CONTACT reports a prescribed normal force, else the pressure's sum
        // on the grid (soutpt).
        o.normal_force_n = match load {
            NormalLoad::NormalForce(_) => fn_n,
            NormalLoad::Approach(_) => out.pressure_force_n,
        };
        o.fx_n = out.fx_n;
        o.fy_n = out.fy_n;
        o.mz_nm = out.mz_nm;
        o.creepages = self.kin.creep;
        o.rolling_speed_m_per_s = self.kin.veloc;
        o.max_pressure_pa = out.max_pressure_pa;
        o.max_traction_pa = out.max_traction_pa;
        o.tgamma_n = out.tgamma_n;
        if let Some(t) = &self.config.thermal {
            let temperatures =
                flash_temperatures(&grid, &o.fields, &thermal_input(t, self.kin.veloc))
                    .map_err(CntcError::from_contact)?;
            o.max_temperature_k = Some([
                temperatures.summary.max_body1.temperature_k,
                temperatures.summary.max_body2.temperature_k,
            ]);
            o.temperature_k = Some([temperatures.body1_k, temperatures.body2_k]);
        }
        Ok((o, status))
    }

    /// The exact normal problem on `grid` (FASTSIM's B = 0): the pressure,
    /// the normal force, the approach and the error of an iteration limit;
    /// None when a prescribed approach makes no contact.
    fn normal_pressure(
        &mut self,
        cache: &KernelCache,
        material: CombinedMaterial,
        load: NormalLoad,
        grid: Grid,
        gap: &[f64],
    ) -> Result<Option<NormalSolution>> {
        let mut settings = SolverSettings::default();
        let eps = self.config.solver.eps.clamp(1e-14, 0.1);
        settings.normal.tolerance = eps;
        settings.allow_border_contact = true;
        let problem = ContactProblem {
            material,
            friction: Friction::coulomb(self.config.friction.static_coefficient()),
            grid,
            gap_m: gap.to_vec(),
            load,
            kinematics: Kinematics::Frictionless,
            settings,
            rolling_direction_rad: 0.0,
            extra_rigid_slip: None,
            numerical_influence: None,
        };
        let key = SolverKey {
            grid,
            material,
            chi: 0.0,
            layer: None,
            viscoelastic: None,
        };
        if !matches!(&self.solver, Some((k, _)) if *k == key) {
            self.solver = Some((key, ContactSolver::new(&problem, cache)));
        }
        let solver = &mut self.solver.as_mut().expect("set above").1;
        solver.reset();
        let solution = match solver.solve(&problem) {
            Ok(mut v) => v.pop().expect("one solution"),
            Err(ContactError::NoContact { .. }) => {
                self.solver = None;
                return Ok(None);
            }
            Err(e) => {
                self.solver = None;
                return Err(CntcError::from_contact(e));
            }
        };
        let status = (solution.info.status != SolveStatus::Converged).then(|| {
            CntcError::Normal(format!(
                "no convergence within the iteration limit (residual {:.3e})",
                solution.info.normal_residual
            ))
        });
        Ok(Some(NormalSolution {
            pressure_pa: solution.fields.pressure_pa,
            normal_force_n: solution.totals.normal_force_n,
            approach_m: solution.totals.approach_m,
            status,
        }))
    }

    /// The number of elements of the potential contact grid set (`None`:
    /// none set yet).
    pub fn grid_elements(&self) -> Option<usize> {
        match &self.potcon {
            None => None,
            Some(Potcon::Hertz { mx, my, .. }) => Some(mx.saturating_mul(*my)),
            Some(Potcon::Grid(g)) => Some(g.len()),
        }
    }

    /// Takes the outcome a server's calculation left, as
    /// [`Patch::calculate`] leaves it, counting the calculation and its
    /// `seconds`.
    pub fn accept_calculation(&mut self, outcome: Option<Outcome>, seconds: f64) {
        self.ncase += 1;
        self.time_s += seconds;
        self.outcome = outcome;
    }

    /// Forgets the solver's history (`cntc_finalize`, a new grid).
    pub fn reset_solver(&mut self) {
        self.solver = None;
    }
}

/// The setters of a module 3 problem, taking the caller's values in its
/// units (the one conversion into SI).
impl Patch {
    /// `cntc_sethertzcontact`: IPOTCN -1..-6 with MX, MY and the ellipse.
    pub fn set_hertz(&mut self, ipotcn: i32, p: &[f64]) -> Result<()> {
        let want = match ipotcn {
            -6 => 6,
            -5..=-1 => 5,
            _ => {
                return Err(CntcError::Input(format!(
                    "IPOTCN = {ipotcn} (cntc_sethertzcontact): the Hertzian options are -6 to -1"
                )))
            }
        };
        if p.len() != want {
            return Err(CntcError::Input(format!(
                "IPOTCN = {ipotcn} (cntc_sethertzcontact) needs {want} parameters, got {}",
                p.len()
            )));
        }
        if ipotcn <= -4 {
            return Err(CntcError::NotSupported(format!(
                "IPOTCN = {ipotcn} (cntc_sethertzcontact): {} is not supported; -1, -2 and -3 are",
                if ipotcn == -6 {
                    "the SDEC double half-ellipse"
                } else {
                    "a rectangular (2D Hertzian) contact"
                }
            )));
        }
        let u = self.config.units;
        let (mx, my) = (grid_count(p[0], "MX")?, grid_count(p[1], "MY")?);
        let spec = match ipotcn {
            -1 => HertzSpec::Curvatures(u.per_len(p[2].max(1e-12)), u.per_len(p[3].max(1e-12))),
            -2 => HertzSpec::CurvatureAndRatio(u.per_len(p[2].max(1e-12)), p[3].max(1e-6)),
            _ => HertzSpec::SemiAxes(u.len(p[2].max(1e-6)), u.len(p[3].max(1e-6))),
        };
        self.potcon = Some(Potcon::Hertz {
            mx,
            my,
            spec,
            scale: p[4].max(1e-6),
        });
        Ok(())
    }

    /// `cntc_setpotcontact` (module 3): IPOTCN 1-4.
    pub fn set_potcon(&mut self, ipotcn: i32, p: &[f64]) -> Result<()> {
        if !(1..=4).contains(&ipotcn) {
            return Err(CntcError::Input(format!(
                "IPOTCN = {ipotcn} (cntc_setpotcontact, module 3): the options are 1 to 4"
            )));
        }
        if p.len() != 6 {
            return Err(CntcError::Input(format!(
                "IPOTCN = {ipotcn} (cntc_setpotcontact) needs 6 parameters, got {}",
                p.len()
            )));
        }
        let u = self.config.units;
        let (mx, my) = (grid_count(p[0], "MX")?, grid_count(p[1], "MY")?);
        let (a, b, c, d) = (u.len(p[2]), u.len(p[3]), u.len(p[4]), u.len(p[5]));
        let (nx, ny) = (mx as f64, my as f64);
        // (x0, y0) the lower-left corner, (dx, dy) the element size.
        let (x0, y0, dx, dy) = match ipotcn {
            1 => (a, b, c.max(1e-15), d.max(1e-15)),
            2 => (a, b, (c - a) / nx, (d - b) / ny),
            3 => (
                a - 0.5 * c.max(1e-15),
                b - 0.5 * d.max(1e-15),
                c.max(1e-15),
                d.max(1e-15),
            ),
            _ => {
                let (dx, dy) = ((c - a) / (nx - 1.0), (d - b) / (ny - 1.0));
                (a - 0.5 * dx, b - 0.5 * dy, dx, dy)
            }
        };
        let grid = Grid::new(mx, my, dx, dy, x0, y0).map_err(|e| {
            CntcError::Discretisation(format!(
                "IPOTCN = {ipotcn} (cntc_setpotcontact): element size {dx:e} x {dy:e} m from the \
                 parameters {p:?}: {e}"
            ))
        })?;
        if self.potcon.as_ref() != Some(&Potcon::Grid(grid)) {
            if let Some(Udist::Elementwise(_)) = self.udist {
                self.udist = None; // IBASE = 9 values belong to the old grid
            }
        }
        self.potcon = Some(Potcon::Grid(grid));
        Ok(())
    }

    /// `cntc_setundeformeddistc`: IBASE 1, 2, 3 or 9.
    pub fn set_udist(&mut self, ibase: i32, p: &[f64]) -> Result<()> {
        let u = self.config.units;
        let want = match ibase {
            1 => 6,
            2 => {
                let nn = p.first().copied().unwrap_or(0.0).round();
                if !(1.0..=1e6).contains(&nn) {
                    return Err(CntcError::Input(format!(
                        "IBASE = 2 (cntc_setundeformeddistc): NN = {nn} profile points"
                    )));
                }
                5 + nn as usize
            }
            3 => 8,
            9 => match &self.potcon {
                Some(Potcon::Grid(g)) => g.len(),
                _ => {
                    return Err(CntcError::Discretisation(
                        "IBASE = 9 (cntc_setundeformeddistc) needs the potential contact area \
                         first (cntc_setpotcontact, IPOTCN 1-4)"
                            .into(),
                    ))
                }
            },
            _ => {
                return Err(CntcError::Input(format!(
                    "IBASE = {ibase} (cntc_setundeformeddistc): the options are 1, 2, 3 and 9"
                )))
            }
        };
        if p.len() != want {
            return Err(CntcError::Input(format!(
                "IBASE = {ibase} (cntc_setundeformeddistc) needs {want} parameters, got {}",
                p.len()
            )));
        }
        if let Some(i) = p.iter().position(|v| !v.is_finite()) {
            return Err(CntcError::Input(format!(
                "IBASE = {ibase} (cntc_setundeformeddistc): parameter {} is not finite",
                i + 1
            )));
        }
        self.udist = Some(match ibase {
            1 => Udist::Quadratic([
                u.per_len(p[0]),
                u.per_len(p[1]),
                u.per_len(p[2]),
                p[3],
                p[4],
                u.len(p[5]),
            ]),
            2 => Udist::Revolution {
                xm: u.len(p[1]),
                rm: u.len(p[2]),
                y1: u.len(p[3]),
                dy1: u.len(p[4]),
                heights: p[5..].iter().map(|h| u.len(*h)).collect(),
            },
            3 => Udist::Sines([
                u.len(p[0]),
                u.per_len(p[1]),
                u.len(p[2]),
                u.len(p[3]),
                u.per_len(p[4]),
                u.len(p[5]),
                u.len(p[6]),
                u.len(p[7]),
            ]),
            _ => Udist::Elementwise(p.iter().map(|h| u.len(*h)).collect()),
        });
        Ok(())
    }

    /// `cntc_setcreepages`: creepages (T = 2, 3) or shifts (T = 1).
    pub fn set_creepages(&mut self, vx: f64, vy: f64, phi: f64) -> Result<()> {
        // Inputs are body 1's under every convention (CONTACT's rule: only
        // the outputs follow the output body).
        let u = self.config.units;
        finite("cntc_setcreepages", &[vx, vy, phi])?;
        self.kin.creep = if self.config.digits.tang == 1 {
            [u.len(vx), u.len(vy), phi]
        } else {
            [vx, vy, u.per_len(phi)]
        };
        Ok(())
    }

    /// `cntc_setextrarigidslip`: wx, wy per element (E = 9).
    pub fn set_extra_rigid_slip(&mut self, wx: &[f64], wy: &[f64]) -> Result<()> {
        finite("cntc_setextrarigidslip", wx)?;
        finite("cntc_setextrarigidslip", wy)?;
        let u = self.config.units;
        let conv = |v: &[f64]| -> Vec<f64> {
            if self.config.digits.tang == 1 {
                v.iter().map(|w| u.len(*w)).collect()
            } else {
                v.to_vec()
            }
        };
        self.kin.extra = if wx.is_empty() {
            None
        } else {
            Some((conv(wx), conv(wy)))
        };
        self.config.digits.exrhs = if wx.is_empty() { 0 } else { 9 };
        Ok(())
    }

    /// `cntc_settangentialforces`: FX, FY relative to FSTAT FN.
    pub fn set_tangential_forces(&mut self, fx: f64, fy: f64) -> Result<()> {
        finite("cntc_settangentialforces", &[fx, fy])?;
        self.kin.frel = [fx, fy];
        Ok(())
    }

    /// `cntc_setpenetration` (also N = 0).
    pub fn set_penetration(&mut self, pen: f64) -> Result<()> {
        finite("cntc_setpenetration", &[pen])?;
        self.kin.pen = self.config.units.len(pen);
        self.config.digits.norm = 0;
        Ok(())
    }

    /// `cntc_setnormalforce` (also N = 1).
    pub fn set_normal_force(&mut self, fn_n: f64) -> Result<()> {
        finite("cntc_setnormalforce", &[fn_n])?;
        self.kin.fn_n = fn_n;
        self.config.digits.norm = 1;
        Ok(())
    }

    /// `cntc_setreferencevelocity`: VELOC (CONTACT keeps max(1e-9, |v|)).
    pub fn set_reference_velocity(&mut self, v: f64) -> Result<()> {
        finite("cntc_setreferencevelocity", &[v])?;
        self.kin.veloc = self.config.units.velocity(v.abs()).max(1e-12);
        Ok(())
    }

    /// `cntc_setrollingstepsize`: CHI and DQ.
    pub fn set_rolling_step(&mut self, chi: f64, dq: f64) -> Result<()> {
        finite("cntc_setrollingstepsize", &[chi, dq])?;
        self.kin.chi = chi;
        self.kin.dq = self.config.units.len(dq);
        Ok(())
    }

    /// `cntc_settimestep`: DT (stored).
    pub fn set_timestep(&mut self, dt: f64) -> Result<()> {
        finite("cntc_settimestep", &[dt])?;
        self.kin.dt = dt;
        Ok(())
    }

    /// `cntc_gethertzcontact`: A1, B1, AA, BB, RHO, CP, SCALE, BNEG, BPOS,
    /// AOB in the caller's units.
    pub fn hertz_values(&self) -> Result<[f64; 10]> {
        let h = self.outcome.as_ref().and_then(|o| o.hertz).ok_or_else(|| {
            CntcError::Input(
                "no Hertzian solution: set a Hertzian potential contact area \
                     (cntc_sethertzcontact) and call cntc_calculate"
                    .into(),
            )
        })?;
        let u = self.config.units;
        Ok([
            u.per_len_out(h.a1_per_m),
            u.per_len_out(h.b1_per_m),
            u.len_out(h.aa_m),
            u.len_out(h.bb_m),
            u.len_out(2.0 / (h.a1_per_m + h.b1_per_m)),
            u.len_out((h.aa_m * h.bb_m).sqrt()),
            h.scale,
            u.len_out(h.bb_m),
            u.len_out(h.bb_m),
            h.aa_m / h.bb_m,
        ])
    }
}

/// A grid dimension given as a real (CONTACT rounds: nint).
fn grid_count(v: f64, name: &str) -> Result<usize> {
    if !(0.5..=1e7).contains(&v) {
        return Err(CntcError::Discretisation(format!(
            "{name} = {v}: a number of elements"
        )));
    }
    count(v.round() as usize, name)
}

/// Refuses non-finite inputs, naming the call.
fn finite(call: &str, v: &[f64]) -> Result<()> {
    match v.iter().position(|x| !x.is_finite()) {
        Some(i) => Err(CntcError::Input(format!(
            "{call}: value {} is not finite ({})",
            i + 1,
            v[i]
        ))),
        None => Ok(()),
    }
}

/// The rigid slip (T = 2, 3: per rolled distance [-]; T = 1: shift \[m\])
/// of each element: the creepages' (xi - phi y, eta + phi x) plus the
/// problem's extra rigid slip (CONTACT's field WX, WY).
fn problem_rigid_slip(
    grid: &Grid,
    tang: i32,
    creepages: &[f64; 3],
    problem: &ContactProblem,
) -> Option<[Vec<f64>; 2]> {
    if tang == 0 {
        return None;
    }
    let n = grid.len();
    let (mut wx, mut wy) = (vec![0.0; n], vec![0.0; n]);
    let [xi, eta, phi] = *creepages;
    for iy in 0..grid.ny {
        for ix in 0..grid.nx {
            let i = grid.index(ix, iy);
            wx[i] = xi - phi * grid.y_m(iy);
            wy[i] = eta + phi * grid.x_m(ix);
        }
    }
    if let Some(e) = &problem.extra_rigid_slip {
        let (ex, ey) = if tang == 1 {
            (&e.shift_x_m, &e.shift_y_m)
        } else {
            (&e.slip_x, &e.slip_y)
        };
        for (w, v) in wx.iter_mut().zip(ex).chain(wy.iter_mut().zip(ey)) {
            *w += v;
        }
    }
    Some([wx, wy])
}

/// The solver's thermal input of H = 3's data at rolling speed `v`.
fn thermal_input(t: &Thermal, v_m_per_s: f64) -> ThermalInput {
    let body = |i: usize| ThermalBody {
        bulk_temperature_k: t.bulk_k[i],
        conductivity_w_per_m_k: t.conductivity[i],
        density_kg_per_m3: t.density[i],
        specific_heat_j_per_kg_k: t.heat_capacity[i],
    };
    ThermalInput {
        body1: body(0),
        body2: body(1),
        rolling_speed_m_per_s: v_m_per_s,
    }
}
