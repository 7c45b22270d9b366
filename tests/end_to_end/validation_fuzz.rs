//! Fuzzing of the request validation: every numeric field of SolvePatch
//! and SolveWheelRail requests set, one at a time, to extreme values (0,
//! -0, negative, tiny, 5e-324, 1e300, +-inf, NaN, the typical value scaled
//! by 1e+-6) against the real server in-process. Each answer must be OK
//! with every number finite, or INVALID_ARGUMENT naming the mutated field
//! (or one of the documented dependent fields below). The same for the
//! position, velocity and load of wheel/rail session steps, where a refused
//! step must also leave the session as it was. Then the profile
//! readers on mutations of the real profiles in `crates/solver/profiles`: Ok
//! or a ProfileError, never a panic. Then random wheel/rail queries with
//! every input drawn at once, which must also carry their vertical loads.
//! The track's options of a registration (placement by the rail origins,
//! deviations, a roller rig, curvature) and the rollers' rate likewise, on
//! the roller rig's pair; a rail given as slices, its slices file mutated,
//! and the position along it. The text of numerical influence
//! coefficients sent inline, mutated as the profiles are.
//! Seeded and bounded (a few hundred requests on 16 x 16 grids, 400
//! wheel/rail queries); the counts are printed at the end.

use std::collections::BTreeMap;
use std::panic::{catch_unwind, AssertUnwindSafe};

use railcontact::service::config::ServeConfig;
use railcontact::service::convert::check_finite;
use railcontact::service::pb;
use railcontact::service::wheelrail::check_finite as check_wheelrail_finite;
use railcontact::wheelrail::profile::{parse_profile, LoadOptions};
use tonic::Code;

/// The extreme values, relative to a field's typical value `t`.
fn extremes(t: f64) -> Vec<f64> {
    vec![
        0.0,
        -0.0,
        -t,
        1e-300,
        5e-324,
        1e300,
        -1e300,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NAN,
        t * 1e6,
        t * 1e-6,
    ]
}

/// The field a status or item error names: `invalid `FIELD`: ...`.
fn field_of(message: &str) -> Option<&str> {
    message
        .strip_prefix("invalid `")
        .and_then(|r| r.split_once('`'))
        .map(|(f, _)| f)
}

/// Whether an error on `field` is acceptable for a mutation of `mutated`:
/// the field itself, or a documented dependent field. The Hertz patch of
/// the load depends on the geometry and the material (`load.*` names it,
/// see `problem::case::ranges::HERTZ_SEMI_AXIS`); a window's element count
/// on the patch (`grid.window_*`); a wheel/rail placement error names the
/// lateral shift (`position.lateral_m`) whatever pose it comes from; a
/// wheel/rail load whose patch needs too many elements names
/// `element_size_m`; a registration's track that leaves the wheels off
/// their rails names `spec`; a roller rig's forward speed adds to the
/// rollers' surface speed, which names their rate; viscoelastic bodies whose final modulus is far below
/// the initial one (a large relaxation ratio) spread their patch beyond
/// the window (`grid.window_x_m`).
fn acceptable(mutated: &str, field: &str) -> bool {
    if field == mutated {
        return true;
    }
    if mutated.starts_with("case.viscoelastic.") && field == "case.grid.window_x_m" {
        return true;
    }
    let hertz_inputs = [
        "case.geometry.",
        "case.material.",
        "case.load.",
        "case.grid.n",
    ];
    if hertz_inputs.iter().any(|p| mutated.starts_with(p))
        && (field.starts_with("case.load.") || field.starts_with("case.grid.window_"))
    {
        return true;
    }
    // The two lateral radii must leave the profiles touching in one point.
    let radii = [
        "case.geometry.rail_lateral_radius_m",
        "case.geometry.wheel_lateral_radius_m",
    ];
    if radii.contains(&mutated) && radii.contains(&field) {
        return true;
    }
    // A load's patch needs a grid of the query's element size within the
    // grid limits: `element_size_m` names the fix (larger elements).
    if mutated.starts_with("load.") && field == "element_size_m" {
        return true;
    }
    // A track whose placement leaves the wheels off their rails fails the
    // registration's trial solve at the centred position, which names the
    // spec (its message: "check spec.track, ...").
    if mutated.starts_with("spec.track.") && field == "spec" {
        return true;
    }
    // On a roller rig the rolling speed checked is the rollers' surface
    // speed (with the forward speed), named by the rollers' rate.
    if mutated == "velocity.forward_m_per_s" && field == "velocity.roller_rad_per_s" {
        return true;
    }
    mutated.starts_with("position.") && field == "position.lateral_m"
}

#[derive(Default)]
struct Outcomes {
    counts: BTreeMap<&'static str, usize>,
    wrong: Vec<String>,
}

impl Outcomes {
    /// Prints the counts of the answers (`what`: the test) and fails
    /// naming every wrong one.
    fn assert_right(&self, what: &str) {
        let total: usize = self.counts.values().sum();
        eprintln!("{what}: {total} requests, outcomes {:?}", self.counts);
        assert!(
            self.wrong.is_empty(),
            "{} of {total} answers are wrong:\n{}",
            self.wrong.len(),
            self.wrong.join("\n")
        );
    }

    fn record<T>(
        &mut self,
        mutated: &str,
        value: String,
        r: Result<T, tonic::Status>,
        finite: impl Fn(&T) -> Result<(), String>,
    ) {
        match r {
            Ok(v) => {
                *self.counts.entry("OK").or_default() += 1;
                if let Err(e) = finite(&v) {
                    self.wrong
                        .push(format!("{mutated} = {value}: OK with a non-finite {e}"));
                }
            }
            Err(s) if s.code() == Code::InvalidArgument => {
                *self.counts.entry("INVALID_ARGUMENT").or_default() += 1;
                let m = s.message();
                let field = field_of(m).unwrap_or("");
                if !acceptable(mutated, field) || m.len() > 600 {
                    self.wrong.push(format!(
                        "{mutated} = {value}: INVALID_ARGUMENT names `{field}`: {m}"
                    ));
                }
            }
            Err(s) => {
                *self.counts.entry("other").or_default() += 1;
                self.wrong.push(format!(
                    "{mutated} = {value}: {:?} {}",
                    s.code(),
                    s.message()
                ));
            }
        }
    }
}

type Mutator = Box<dyn Fn(&mut pb::PatchCase, f64)>;

fn steel() -> pb::MaterialSection {
    pb::MaterialSection {
        shear_modulus_pa: Some(81.0e9),
        poisson_ratio: Some(0.30),
        ..Default::default()
    }
}

/// Exact steady rolling on an ellipse, 16 x 16.
fn rolling(model: pb::Model) -> pb::PatchCase {
    pb::PatchCase {
        model: model as i32,
        material: Some(steel()),
        friction: Some(pb::FrictionSection {
            coefficient: Some(0.3),
            ..Default::default()
        }),
        geometry: Some(pb::GeometrySection {
            kind: pb::GeometryKind::Quadratic as i32,
            a_per_m: Some(2.6),
            b_per_m: Some(0.92),
            ..Default::default()
        }),
        load: Some(pb::LoadSection {
            load: Some(pb::load_section::Load::NormalForceN(1.0e4)),
        }),
        kinematics: Some(pb::patch_case::Kinematics::Rolling(pb::Creepages {
            creepage_long: 1e-3,
            creepage_lat: 5e-4,
            spin_per_m: 0.1,
            ..Default::default()
        })),
        grid: Some(pb::GridSection {
            nx: Some(16),
            ny: Some(16),
            ..Default::default()
        }),
        solver: None,
        subsurface: None,
        temperature: None,
        rolling_direction_rad: 0.0,
        extra_rigid_slip: None,
        conformal: None,
        interfacial_layer: None,
        viscoelastic: None,
        fastsim: None,
    }
}

/// Model FASTSIM on CONTACT's grid (16 x 16 over 1.1 times the ellipse),
/// the modified FASTSIM with falling friction (`[fastsim]`).
fn fastsim_grid() -> pb::PatchCase {
    let mut c = rolling(pb::Model::Fastsim);
    c.fastsim = Some(pb::FastsimSection {
        discretisation: pb::FastsimDiscretisation::Grid as i32,
        traction_bound: pb::FastsimTractionBound::Elliptic as i32,
        initial_factor: Some(0.54),
        limit_ratio: Some(0.02),
        transition_rate: Some(0.62),
        friction_limit_ratio: Some(0.38),
        friction_decay_s_per_m: Some(0.7),
        rolling_speed_m_per_s: Some(10.0),
        window_scale: Some(1.1),
        ..Default::default()
    });
    c
}

fn fastsim(c: &mut pb::PatchCase) -> &mut pb::FastsimSection {
    c.fastsim.get_or_insert_with(Default::default)
}

/// Two viscoelastic cylinders in steady rolling (CONTACT's `visc_cylindr`
/// case 3 at the creepage it finds, on 40 strips: a line contact, whose
/// coefficients are integrated in a few milliseconds).
fn viscoelastic() -> pb::PatchCase {
    let mut c = rolling(pb::Model::Exact);
    let m = material(&mut c);
    (m.shear_modulus_pa, m.poisson_ratio) = (Some(1143.0e6), Some(0.4));
    let g = geometry(&mut c);
    (g.kind, g.a_per_m, g.b_per_m) = (pb::GeometryKind::Line as i32, Some(10.0), None);
    load(&mut c, pb::load_section::Load::NormalForceNPerM(6.0e5));
    let r = creepages(&mut c);
    (r.creepage_long, r.creepage_lat, r.spin_per_m) = (1.152e-2, 0.0, 0.0);
    // 40 strips, wide enough for the final modulus' patch (2-D Hertz
    // half-width 6.33 mm at tau_c = 0, see examples/cases/visc_cylindr.toml).
    let n = grid(&mut c);
    (n.nx, n.ny, n.window_x_m) = (Some(40), None, Some(16e-3));
    let sls = pb::ViscoelasticBody {
        relaxation_ratio: 1.0,
        creep_relaxation_time_s: 0.045,
    };
    c.viscoelastic = Some(pb::ViscoelasticSection {
        rolling_speed_m_per_s: 1.0,
        body1: Some(sls),
        body2: Some(sls),
    });
    c
}

fn viscoelastic_body1(c: &mut pb::PatchCase) -> &mut pb::ViscoelasticBody {
    let v = c.viscoelastic.get_or_insert_with(Default::default);
    v.body1.get_or_insert_with(Default::default)
}

/// Conformal case 1 of the paper (cect), frictionless, 16 x 16.
fn conformal() -> pb::PatchCase {
    let mut c = rolling(pb::Model::Cect);
    c.friction = None;
    c.kinematics = None;
    let g = geometry(&mut c);
    *g = pb::GeometrySection {
        kind: pb::GeometryKind::ConformalCircular as i32,
        ..Default::default()
    };
    g.rail_lateral_radius_m = Some(0.010);
    g.wheel_lateral_radius_m = Some(-0.0101);
    g.wheel_rolling_radius_m = Some(0.5);
    load(&mut c, pb::load_section::Load::NormalForceN(8.0e4));
    c
}

/// Exact transient: two shift steps, 16 x 16.
fn transient() -> pb::PatchCase {
    let step = pb::ShiftStep {
        shift_x_m: Some(1e-5),
        ..Default::default()
    };
    pb::PatchCase {
        kinematics: Some(pb::patch_case::Kinematics::Transient(
            pb::TransientSection {
                steps: vec![step, step],
                ..Default::default()
            },
        )),
        ..rolling(pb::Model::Exact)
    }
}

/// [`transient`] started from steady rolling.
fn steady_started() -> pb::PatchCase {
    let mut c = transient();
    if let Some(pb::patch_case::Kinematics::Transient(t)) = &mut c.kinematics {
        t.steady_start = Some(pb::SteadyStart {
            creepage_long: 1e-3,
            creepage_lat: 0.0,
            spin_per_m: 0.0,
        });
    }
    c
}

fn steady_start(c: &mut pb::PatchCase) -> &mut pb::SteadyStart {
    match &mut c.kinematics {
        Some(pb::patch_case::Kinematics::Transient(t)) => {
            t.steady_start.get_or_insert_with(Default::default)
        }
        _ => unreachable!("a transient case"),
    }
}

fn geometry(c: &mut pb::PatchCase) -> &mut pb::GeometrySection {
    c.geometry.get_or_insert_with(Default::default)
}

fn material(c: &mut pb::PatchCase) -> &mut pb::MaterialSection {
    c.material.get_or_insert_with(Default::default)
}

fn creepages(c: &mut pb::PatchCase) -> &mut pb::Creepages {
    match c.kinematics.as_mut() {
        Some(pb::patch_case::Kinematics::Rolling(r)) => r,
        _ => unreachable!("a rolling base case"),
    }
}

fn steps(c: &mut pb::PatchCase) -> &mut Vec<pb::ShiftStep> {
    match c.kinematics.as_mut() {
        Some(pb::patch_case::Kinematics::Transient(t)) => &mut t.steps,
        _ => unreachable!("a transient base case"),
    }
}

fn grid(c: &mut pb::PatchCase) -> &mut pb::GridSection {
    c.grid.get_or_insert_with(Default::default)
}

fn solver(c: &mut pb::PatchCase) -> &mut pb::SolverSection {
    c.solver.get_or_insert_with(Default::default)
}

fn subsurface(c: &mut pb::PatchCase) -> &mut pb::SubsurfaceSection {
    c.subsurface.get_or_insert_with(Default::default)
}

/// The temperature section with steel on both bodies at 300 K and 30 m/s,
/// then body 1 of it.
fn thermal(c: &mut pb::PatchCase) -> &mut pb::TemperatureSection {
    c.temperature.get_or_insert_with(|| {
        let steel = pb::ThermalBody {
            bulk_temperature_k: 300.0,
            conductivity_w_per_m_k: 50.0,
            density_kg_per_m3: 7850.0,
            specific_heat_j_per_kg_k: 450.0,
        };
        pb::TemperatureSection {
            rolling_speed_m_per_s: 30.0,
            body1: Some(steel),
            body2: Some(steel),
        }
    })
}

fn thermal_body1(c: &mut pb::PatchCase) -> &mut pb::ThermalBody {
    thermal(c).body1.get_or_insert_with(Default::default)
}

fn load(c: &mut pb::PatchCase, l: pb::load_section::Load) {
    c.load = Some(pb::LoadSection { load: Some(l) });
}

/// The numeric fields of the base cases: (base, path, typical value,
/// setter).
fn patch_fields() -> Vec<(pb::PatchCase, &'static str, f64, Mutator)> {
    use pb::load_section::Load;
    let exact = || rolling(pb::Model::Exact);
    let m = |f: fn(&mut pb::PatchCase, f64)| -> Mutator { Box::new(f) };
    vec![
        (
            exact(),
            "case.material.shear_modulus_pa",
            81e9,
            m(|c, v| material(c).shear_modulus_pa = Some(v)),
        ),
        (
            exact(),
            "case.material.poisson_ratio",
            0.3,
            m(|c, v| material(c).poisson_ratio = Some(v)),
        ),
        (
            exact(),
            "case.friction.coefficient",
            0.3,
            m(|c, v| c.friction.as_mut().unwrap().coefficient = Some(v)),
        ),
        (
            exact(),
            "case.friction.kinetic_coefficient",
            0.25,
            m(|c, v| {
                c.friction = Some(pb::FrictionSection {
                    static_coefficient: Some(0.35),
                    kinetic_coefficient: Some(v),
                    ..Default::default()
                })
            }),
        ),
        (
            exact(),
            "case.friction.static_coefficient",
            0.35,
            m(|c, v| {
                c.friction = Some(pb::FrictionSection {
                    static_coefficient: Some(v),
                    kinetic_coefficient: Some(0.0),
                    ..Default::default()
                })
            }),
        ),
        (
            exact(),
            "case.rolling_direction_rad",
            std::f64::consts::PI,
            m(|c, v| c.rolling_direction_rad = v),
        ),
        (
            exact(),
            "case.geometry.gap_m[5]",
            0.0,
            m(|c, v| {
                let mut h = vec![1e-3; 256];
                h[5] = v;
                geometry(c).gap_m = h;
            }),
        ),
        (
            exact(),
            "case.extra_rigid_slip.slip_y[3]",
            1e-4,
            m(|c, v| {
                let mut e = vec![0.0; 256];
                e[3] = v;
                c.extra_rigid_slip = Some(pb::ExtraRigidSlip {
                    slip_x: Vec::new(),
                    slip_y: e,
                    ..Default::default()
                });
            }),
        ),
        (
            exact(),
            "case.geometry.a_per_m",
            2.6,
            m(|c, v| geometry(c).a_per_m = Some(v)),
        ),
        (
            exact(),
            "case.geometry.b_per_m",
            0.92,
            m(|c, v| geometry(c).b_per_m = Some(v)),
        ),
        (
            exact(),
            "case.load.normal_force_n",
            1e4,
            m(|c, v| load(c, Load::NormalForceN(v))),
        ),
        (
            exact(),
            "case.load.approach_m",
            2e-5,
            m(|c, v| load(c, Load::ApproachM(v))),
        ),
        (
            exact(),
            "case.rolling.creepage_long",
            1e-3,
            m(|c, v| creepages(c).creepage_long = v),
        ),
        (
            exact(),
            "case.rolling.creepage_lat",
            5e-4,
            m(|c, v| creepages(c).creepage_lat = v),
        ),
        (
            exact(),
            "case.rolling.spin_per_m",
            0.1,
            m(|c, v| creepages(c).spin_per_m = v),
        ),
        (
            exact(),
            "case.grid.window_x_m",
            6e-3,
            m(|c, v| grid(c).window_x_m = Some(v)),
        ),
        (
            exact(),
            "case.grid.window_y_m",
            1e-2,
            m(|c, v| grid(c).window_y_m = Some(v)),
        ),
        (
            exact(),
            "case.solver.normal_tolerance",
            1e-10,
            m(|c, v| solver(c).normal_tolerance = Some(v)),
        ),
        (
            exact(),
            "case.solver.tangential_tolerance",
            1e-7,
            m(|c, v| solver(c).tangential_tolerance = Some(v)),
        ),
        (
            exact(),
            "case.solver.coupling_tolerance",
            1e-8,
            m(|c, v| solver(c).coupling_tolerance = Some(v)),
        ),
        (
            exact(),
            "case.subsurface.depths_m[0]",
            1e-3,
            m(|c, v| subsurface(c).depths_m = vec![v]),
        ),
        (
            exact(),
            "case.subsurface.shear_yield_stress_pa",
            300e6,
            m(|c, v| {
                let s = subsurface(c);
                s.depths_m = vec![1e-3];
                s.shear_yield_stress_pa = Some(v);
            }),
        ),
        (
            exact(),
            "case.temperature.rolling_speed_m_per_s",
            30.0,
            m(|c, v| thermal(c).rolling_speed_m_per_s = v),
        ),
        (
            exact(),
            "case.temperature.body1.bulk_temperature_k",
            300.0,
            m(|c, v| thermal_body1(c).bulk_temperature_k = v),
        ),
        (
            exact(),
            "case.temperature.body1.conductivity_w_per_m_k",
            50.0,
            m(|c, v| thermal_body1(c).conductivity_w_per_m_k = v),
        ),
        (
            exact(),
            "case.temperature.body1.density_kg_per_m3",
            7850.0,
            m(|c, v| thermal_body1(c).density_kg_per_m3 = v),
        ),
        (
            exact(),
            "case.temperature.body1.specific_heat_j_per_kg_k",
            450.0,
            m(|c, v| thermal_body1(c).specific_heat_j_per_kg_k = v),
        ),
        (
            exact(),
            "case.subsurface.max_depth_m",
            3e-3,
            m(|c, v| {
                let s = subsurface(c);
                s.depth_count = Some(4);
                s.max_depth_m = Some(v);
            }),
        ),
        (
            viscoelastic(),
            "case.viscoelastic.rolling_speed_m_per_s",
            1.0,
            m(|c, v| c.viscoelastic.as_mut().unwrap().rolling_speed_m_per_s = v),
        ),
        (
            viscoelastic(),
            "case.viscoelastic.body1.relaxation_ratio",
            1.0,
            m(|c, v| viscoelastic_body1(c).relaxation_ratio = v),
        ),
        (
            viscoelastic(),
            "case.viscoelastic.body1.creep_relaxation_time_s",
            0.045,
            m(|c, v| viscoelastic_body1(c).creep_relaxation_time_s = v),
        ),
        (
            fastsim_grid(),
            "case.fastsim.initial_factor",
            0.54,
            m(|c, v| fastsim(c).initial_factor = Some(v)),
        ),
        (
            fastsim_grid(),
            "case.fastsim.limit_ratio",
            0.02,
            m(|c, v| fastsim(c).limit_ratio = Some(v)),
        ),
        (
            fastsim_grid(),
            "case.fastsim.transition_rate",
            0.62,
            m(|c, v| fastsim(c).transition_rate = Some(v)),
        ),
        (
            fastsim_grid(),
            "case.fastsim.friction_limit_ratio",
            0.38,
            m(|c, v| fastsim(c).friction_limit_ratio = Some(v)),
        ),
        (
            fastsim_grid(),
            "case.fastsim.friction_decay_s_per_m",
            0.7,
            m(|c, v| fastsim(c).friction_decay_s_per_m = Some(v)),
        ),
        (
            fastsim_grid(),
            "case.fastsim.rolling_speed_m_per_s",
            10.0,
            m(|c, v| fastsim(c).rolling_speed_m_per_s = Some(v)),
        ),
        (
            fastsim_grid(),
            "case.fastsim.flexibility_m_per_pa",
            1e-13,
            m(|c, v| fastsim(c).flexibility_m_per_pa = Some(v)),
        ),
        (
            fastsim_grid(),
            "case.fastsim.window_scale",
            1.1,
            m(|c, v| fastsim(c).window_scale = Some(v)),
        ),
        (
            rolling(pb::Model::Fastsim),
            "case.rolling.creepage_long",
            1e-3,
            m(|c, v| creepages(c).creepage_long = v),
        ),
        (
            rolling(pb::Model::Fastsim),
            "case.friction.coefficient",
            0.3,
            m(|c, v| c.friction.as_mut().unwrap().coefficient = Some(v)),
        ),
        (
            rolling(pb::Model::Fastsim),
            "case.load.normal_force_n",
            1e4,
            m(|c, v| load(c, Load::NormalForceN(v))),
        ),
        (
            rolling(pb::Model::Hertz),
            "case.geometry.b_per_m",
            0.92,
            m(|c, v| geometry(c).b_per_m = Some(v)),
        ),
        (
            rolling(pb::Model::Hertz),
            "case.load.approach_m",
            2e-5,
            m(|c, v| load(c, Load::ApproachM(v))),
        ),
        (
            conformal(),
            "case.geometry.rail_lateral_radius_m",
            0.010,
            m(|c, v| geometry(c).rail_lateral_radius_m = Some(v)),
        ),
        (
            conformal(),
            "case.geometry.wheel_lateral_radius_m",
            -0.0101,
            m(|c, v| geometry(c).wheel_lateral_radius_m = Some(v)),
        ),
        (
            conformal(),
            "case.geometry.wheel_rolling_radius_m",
            0.5,
            m(|c, v| geometry(c).wheel_rolling_radius_m = Some(v)),
        ),
        (
            conformal(),
            "case.load.normal_force_n",
            8e4,
            m(|c, v| load(c, Load::NormalForceN(v))),
        ),
        (
            transient(),
            "case.transient.steps[1].shift_x_m",
            1e-5,
            m(|c, v| steps(c)[1].shift_x_m = Some(v)),
        ),
        (
            transient(),
            "case.transient.steps[1].shift_y_m",
            1e-5,
            m(|c, v| steps(c)[1].shift_y_m = v),
        ),
        (
            transient(),
            "case.transient.steps[1].rotation_rad",
            1e-3,
            m(|c, v| steps(c)[1].rotation_rad = v),
        ),
        (
            transient(),
            "case.transient.steps[0].normal_force_n",
            1e4,
            m(|c, v| steps(c)[0].normal_force_n = Some(v)),
        ),
        (
            transient(),
            "case.transient.steps[1].approach_m",
            2e-5,
            m(|c, v| steps(c)[1].approach_m = Some(v)),
        ),
        (
            steady_started(),
            "case.transient.steady_start.creepage_long",
            1e-3,
            m(|c, v| steady_start(c).creepage_long = v),
        ),
        (
            steady_started(),
            "case.transient.steady_start.creepage_lat",
            1e-3,
            m(|c, v| steady_start(c).creepage_lat = v),
        ),
        (
            steady_started(),
            "case.transient.steady_start.spin_per_m",
            0.1,
            m(|c, v| steady_start(c).spin_per_m = v),
        ),
    ]
}

/// Sets one integer field of a case.
type CountSetter = fn(&mut pb::PatchCase, u32);

/// The integer fields: (path, setter) over a list of counts.
fn patch_count_fields() -> Vec<(&'static str, CountSetter)> {
    vec![
        ("case.grid.nx", |c, n| grid(c).nx = Some(n)),
        ("case.grid.ny", |c, n| grid(c).ny = Some(n)),
        ("case.solver.max_iterations", |c, n| {
            solver(c).max_iterations = Some(n)
        }),
        ("case.solver.coupling_max_iterations", |c, n| {
            solver(c).coupling_max_iterations = Some(n)
        }),
        ("case.subsurface.depth_count", |c, n| {
            let s = subsurface(c);
            s.max_depth_m = Some(3e-3);
            s.depth_count = Some(n);
        }),
    ]
}

type WheelMutator = fn(&mut pb::SolveWheelRailRequest, f64);

/// Whether an answered wheel/rail query's numbers are all finite.
fn wheel_finite(r: &tonic::Response<pb::SolveWheelRailResponse>) -> Result<(), String> {
    let r = r.get_ref().result.as_ref().ok_or("no result")?;
    check_wheelrail_finite(r).map_err(|e| e.to_string())
}

fn wheel_query(model: pb::WheelRailModel) -> pb::SolveWheelRailRequest {
    pb::SolveWheelRailRequest {
        pair_id: "mbench_s1002_uic60".into(),
        model: model as i32,
        position: Some(pb::WheelsetPosition {
            lateral_m: 3e-3,
            ..Default::default()
        }),
        velocity: Some(pb::WheelsetVelocity {
            forward_m_per_s: 30.0,
            ..Default::default()
        }),
        load: Some(pb::WheelLoad {
            load: Some(pb::wheel_load::Load::VerticalForceN(1e5)),
            ..Default::default()
        }),
        ..Default::default()
    }
}

fn position(r: &mut pb::SolveWheelRailRequest) -> &mut pb::WheelsetPosition {
    r.position.get_or_insert_with(Default::default)
}

fn velocity(r: &mut pb::SolveWheelRailRequest) -> &mut pb::WheelsetVelocity {
    r.velocity.get_or_insert_with(Default::default)
}

fn wheel_load(r: &mut pb::SolveWheelRailRequest, l: pb::wheel_load::Load) {
    r.load.get_or_insert_with(Default::default).load = Some(l);
}

fn wheel_fields() -> Vec<(&'static str, f64, WheelMutator)> {
    use pb::wheel_load::Load;
    vec![
        ("position.lateral_m", 3e-3, |r, v| position(r).lateral_m = v),
        ("position.yaw_rad", 1e-3, |r, v| position(r).yaw_rad = v),
        ("position.roll_rad", 1e-3, |r, v| {
            position(r).roll_rad = Some(v)
        }),
        ("velocity.forward_m_per_s", 30.0, |r, v| {
            velocity(r).forward_m_per_s = v
        }),
        ("velocity.lateral_m_per_s", 0.1, |r, v| {
            velocity(r).lateral_m_per_s = v
        }),
        ("velocity.vertical_m_per_s", 0.1, |r, v| {
            velocity(r).vertical_m_per_s = v
        }),
        ("velocity.roll_rad_per_s", 0.1, |r, v| {
            velocity(r).roll_rad_per_s = v
        }),
        ("velocity.yaw_rad_per_s", 0.1, |r, v| {
            velocity(r).yaw_rad_per_s = v
        }),
        ("velocity.pitch_rad_per_s", -65.0, |r, v| {
            velocity(r).pitch_rad_per_s = Some(v)
        }),
        ("load.vertical_force_n", 1e5, |r, v| {
            wheel_load(r, Load::VerticalForceN(v))
        }),
        ("load.approach_m", 1e-4, |r, v| {
            wheel_load(r, Load::ApproachM(v))
        }),
        ("load.center_z_m", -0.46, |r, v| {
            wheel_load(r, Load::CenterZM(v))
        }),
        ("load.total_longitudinal_force_n", -1e4, |r, v| {
            r.load
                .get_or_insert_with(Default::default)
                .total_longitudinal_force_n = Some(v)
        }),
        ("polach.k_slip", 0.4, |r, v| {
            r.model = pb::WheelRailModel::HertzPolach as i32;
            r.polach = Some(pb::PolachParameters {
                k_adhesion: 1.0,
                k_slip: v,
                limit_ratio: 0.4,
                decay_s_per_m: 0.6,
            })
        }),
        ("element_size_m", 2e-4, |r, v| r.element_size_m = Some(v)),
        ("friction.coefficient", 0.3, |r, v| {
            r.friction = Some(pb::FrictionSection {
                coefficient: Some(v),
                ..Default::default()
            })
        }),
        // On a track (the built-in pair) every value is refused by name;
        // on a roller rig see `hostile_track_values_*`.
        ("velocity.roller_rad_per_s", 2.5, |r, v| {
            velocity(r).roller_rad_per_s = Some(v)
        }),
    ]
}

/// A profile file of `crates/solver/profiles` as a wire source.
fn profile_source(name: &str) -> pb::ProfileSource {
    let path = crate::common::profile_path(name);
    pb::ProfileSource {
        source: Some(pb::profile_source::Source::File(pb::ProfileFile {
            format: pb::ProfileFormat::Unspecified as i32,
            content: std::fs::read_to_string(path).unwrap(),
            file_name: name.into(),
            ..Default::default()
        })),
        mirror_y: false,
    }
}

/// A pair whose rail profiles' origins are placed at track y =
/// `rail_origin_y_m`, z = 0 (`track.rail_origin_*`), with the wheelset
/// `(flange back distance, nominal radius, flange back y)` [m].
fn placed_by_origin(
    wheel: pb::ProfileSource,
    rail: pb::ProfileSource,
    rail_origin_y_m: f64,
    (flange_back_distance_m, nominal_radius_m, flange_back_y_m): (f64, f64, f64),
) -> pb::ProfilePairSpec {
    pb::ProfilePairSpec {
        wheel: Some(wheel),
        rail: Some(rail),
        track: Some(pb::TrackSpec {
            rail_origin_y_m: Some(rail_origin_y_m),
            rail_origin_z_m: Some(0.0),
            ..Default::default()
        }),
        wheelset: Some(pb::WheelsetSpec {
            flange_back_distance_m,
            nominal_radius_m,
            flange_back_y_m: Some(flange_back_y_m),
        }),
        ..Default::default()
    }
}

/// `examples/cases/roller_rig.toml`'s pair: a flat wheel on a roller of
/// 0.4 m with a 100 mm section, the rails placed by their origins.
fn roller_spec() -> pb::ProfilePairSpec {
    let mut spec = placed_by_origin(
        profile_source("flat_plane.prw"),
        profile_source("circ_r100.prr"),
        0.2,
        (0.3, 0.13333333, -0.05),
    );
    spec.track.as_mut().unwrap().roller_radius_m = Some(0.4);
    spec
}

/// A query on the roller pair `pair_id`: the case's approach, the
/// rollers at 2.5 rad/s.
fn roller_query(pair_id: &str) -> pb::SolveWheelRailRequest {
    pb::SolveWheelRailRequest {
        pair_id: pair_id.into(),
        model: pb::WheelRailModel::HertzFastsim as i32,
        sides: pb::WheelSides::Right as i32,
        position: Some(pb::WheelsetPosition {
            roll_rad: Some(0.0),
            ..Default::default()
        }),
        velocity: Some(pb::WheelsetVelocity {
            pitch_rad_per_s: Some(-7.5),
            roller_rad_per_s: Some(2.5),
            ..Default::default()
        }),
        load: Some(pb::WheelLoad {
            load: Some(pb::wheel_load::Load::ApproachM(0.16e-3)),
            ..Default::default()
        }),
        ..Default::default()
    }
}

type TrackMutator = fn(&mut pb::TrackSpec, f64);

/// The track's options of a registration, each with a typical value.
fn track_fields() -> Vec<(&'static str, f64, TrackMutator)> {
    fn deviation(d: &mut Option<pb::RailDeviation>) -> &mut pb::RailDeviation {
        d.get_or_insert_with(Default::default)
    }
    vec![
        ("spec.track.rail_origin_y_m", 0.2, |t, v| {
            t.rail_origin_y_m = Some(v)
        }),
        ("spec.track.rail_origin_z_m", 1e-3, |t, v| {
            t.rail_origin_z_m = Some(v)
        }),
        ("spec.track.rail_deviation_left.dy_m", 1e-3, |t, v| {
            deviation(&mut t.rail_deviation_left).dy_m = v
        }),
        ("spec.track.rail_deviation_left.dz_m", 1e-3, |t, v| {
            deviation(&mut t.rail_deviation_left).dz_m = v
        }),
        ("spec.track.rail_deviation_right.droll_rad", 1e-3, |t, v| {
            deviation(&mut t.rail_deviation_right).droll_rad = v
        }),
        ("spec.track.roller_radius_m", 0.4, |t, v| {
            t.roller_radius_m = Some(v)
        }),
        ("spec.track.curvature_per_m", 2e-3, |t, v| {
            t.curvature_per_m = v
        }),
    ]
}

/// A registration's outcome: the READY pair, or the status that ended it
/// (at the call or in its stream).
async fn registration(
    client: &mut crate::common::Client,
    spec: pb::ProfilePairSpec,
) -> Result<pb::ProfilePairInfo, tonic::Status> {
    let mut stream = client
        .register_profile_pair(pb::RegisterProfilePairRequest {
            pair: Some(pb::register_profile_pair_request::Pair::Spec(spec)),
            label: "fuzz".into(),
        })
        .await?
        .into_inner();
    let mut pair = None;
    while let Some(m) = stream.message().await? {
        pair = m.pair.or(pair);
    }
    pair.ok_or_else(|| tonic::Status::internal("no READY message"))
}

/// The track's options of a registration (placement by the origins, each
/// rail's deviation, the roller's radius, the curvature) and the rollers'
/// rate of a query, each set to the extreme values on the roller rig's
/// pair: registered (and a query on it answered finite, or refused
/// INVALID_ARGUMENT) or refused INVALID_ARGUMENT naming the field.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn hostile_track_values_are_registered_or_refused_by_name() {
    let (server, mut client) = crate::common::server_with(ServeConfig::default()).await;
    let mut out = Outcomes::default();
    let track_finite = |p: &pb::ProfilePairInfo| {
        let t = p.track.as_ref().ok_or("no track")?;
        let d =
            |d: &Option<pb::RailDeviation>| d.map_or([0.0; 3], |d| [d.dy_m, d.dz_m, d.droll_rad]);
        let values = [
            [t.gauge_m, t.gauge_height_m, t.cant_rad],
            [
                t.rail_origin_y_m.unwrap_or(0.0),
                t.rail_origin_z_m.unwrap_or(0.0),
                t.roller_radius_m.unwrap_or(0.0),
            ],
            d(&t.rail_deviation_left),
            d(&t.rail_deviation_right),
            [t.curvature_per_m; 3],
        ];
        match values.as_flattened().iter().all(|v| v.is_finite()) {
            true => Ok(()),
            false => Err(format!("track {t:?}")),
        }
    };
    let mut queries = 0;
    for (path, typical, set) in track_fields() {
        for v in extremes(typical) {
            let mut spec = roller_spec();
            set(spec.track.as_mut().unwrap(), v);
            let r = registration(&mut client, spec).await;
            let id = r.as_ref().ok().map(|p| p.pair_id.clone());
            out.record(path, format!("{v:e}"), r, track_finite);
            // A pair registered is solved on: answered, or refused as
            // invalid input (its placement may leave no contact), never
            // another code.
            if let Some(id) = id {
                queries += 1;
                match client.solve_wheel_rail(roller_query(&id)).await {
                    Ok(r) => {
                        if let Err(e) = wheel_finite(&r) {
                            out.wrong.push(format!("{path} = {v:e}: query OK with {e}"));
                        }
                    }
                    Err(s) if s.code() == Code::InvalidArgument => {}
                    Err(s) => out.wrong.push(format!(
                        "{path} = {v:e}: query {:?} {}",
                        s.code(),
                        s.message()
                    )),
                }
                let _ = client
                    .delete_profile_pair(pb::DeleteProfilePairRequest { pair_id: id })
                    .await;
            }
        }
    }
    // The rollers' rate and the wheelset's forward speed on the roller rig.
    let pair = registration(&mut client, roller_spec())
        .await
        .expect("the roller rig registers");
    type RollerMutator = fn(&mut pb::WheelsetVelocity, f64);
    let rollers: [(&str, f64, RollerMutator); 2] = [
        ("velocity.roller_rad_per_s", 2.5, |w, v| {
            w.roller_rad_per_s = Some(v)
        }),
        ("velocity.forward_m_per_s", 0.5, |w, v| {
            w.forward_m_per_s = v
        }),
    ];
    for (path, typical, set) in rollers {
        for v in extremes(typical) {
            let mut q = roller_query(&pair.pair_id);
            set(q.velocity.as_mut().unwrap(), v);
            let r = client.solve_wheel_rail(q).await;
            out.record(path, format!("{v:e}"), r, wheel_finite);
        }
    }
    server.shutdown().await;
    out.assert_right(&format!(
        "track fuzz ({queries} queries on the pairs registered)"
    ));
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn hostile_values_are_answered_or_refused_by_name() {
    let (server, mut client) = crate::common::server_with(ServeConfig::default()).await;
    let mut out = Outcomes::default();
    let patch_finite = |r: &tonic::Response<pb::SolvePatchResponse>| {
        let r = r.get_ref().result.as_ref().ok_or("no result")?;
        check_finite(r).map_err(|e| e.to_string())
    };
    for (base, path, typical, set) in patch_fields() {
        for v in extremes(typical) {
            let mut case = base.clone();
            set(&mut case, v);
            let r = client
                .solve_patch(pb::SolvePatchRequest {
                    case: Some(case),
                    ..Default::default()
                })
                .await;
            out.record(path, format!("{v:e}"), r, patch_finite);
        }
    }
    for (path, set) in patch_count_fields() {
        for n in [0, 1, 3, 4, 2049, 10_001, u32::MAX] {
            let mut case = rolling(pb::Model::Exact);
            set(&mut case, n);
            let r = client
                .solve_patch(pb::SolvePatchRequest {
                    case: Some(case),
                    ..Default::default()
                })
                .await;
            out.record(path, n.to_string(), r, patch_finite);
        }
    }
    // A batch: the item's path is under `items[1].`.
    let mut bad = rolling(pb::Model::Exact);
    geometry(&mut bad).a_per_m = Some(1e300);
    let items = vec![
        pb::SolvePatchRequest {
            case: Some(rolling(pb::Model::Fastsim)),
            ..Default::default()
        },
        pb::SolvePatchRequest {
            case: Some(bad),
            ..Default::default()
        },
    ];
    let batch = client
        .solve_patch_batch(pb::SolvePatchBatchRequest { items })
        .await
        .expect("batch answered")
        .into_inner();
    match &batch.items[1].outcome {
        Some(pb::batch_item_result::Outcome::Error(e)) => {
            assert_eq!(e.field, "items[1].case.geometry.a_per_m", "{e:?}");
            assert_eq!(e.code, Code::InvalidArgument as i32);
        }
        other => panic!("{other:?}"),
    }

    for (path, typical, set) in wheel_fields() {
        for v in extremes(typical) {
            let mut req = wheel_query(pb::WheelRailModel::HertzFastsim);
            set(&mut req, v);
            let r = client.solve_wheel_rail(req).await;
            out.record(path, format!("{v:e}"), r, wheel_finite);
        }
    }
    // The exact model at the edges of the ranges that set its grids.
    for (path, v) in [
        ("element_size_m", 6e-5),
        ("load.center_z_m", 0.0),
        ("load.center_z_m", -1.5),
        ("load.approach_m", 2e-3),
        ("load.vertical_force_n", 1e6),
        ("position.lateral_m", 0.02),
        ("position.lateral_m", -0.02),
        ("velocity.forward_m_per_s", 150.0),
    ] {
        // The field's setter, by its path.
        let (_, _, set) = wheel_fields()
            .into_iter()
            .find(|f| f.0 == path)
            .expect("a field of wheel_fields");
        let mut req = wheel_query(pb::WheelRailModel::Exact);
        set(&mut req, v);
        let r = client.solve_wheel_rail(req).await;
        out.record(path, format!("{v:e}"), r, wheel_finite);
    }
    // The exact model's narrow patches refined to a number of elements
    // across: any count is answered (refinement is bounded) or refused
    // by name.
    for n in [0, 1, 3, 8, 100, u32::MAX] {
        let mut req = wheel_query(pb::WheelRailModel::Exact);
        req.min_elements_across = Some(n);
        let r = client.solve_wheel_rail(req).await;
        out.record("min_elements_across", n.to_string(), r, wheel_finite);
    }
    server.shutdown().await;
    out.assert_right("validation fuzz");
}

/// Wheel/rail session steps: every position, velocity and load field of a
/// step set to each extreme value in one Hertz+FASTSIM session. Each step
/// is answered with a finite result or an in-band INVALID_ARGUMENT naming
/// `step.` + the mutated field (or a documented dependent field). Every
/// mutation is sent right after a rollback to a marked good step; a refused
/// one must change nothing: the good step sent after it gives the bits of
/// the same good step sent right after the rollback.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn hostile_session_steps_are_answered_or_refused_by_name() {
    use pb::wheel_rail_session_request::Kind as In;
    use pb::wheel_rail_session_response::Kind as Out;
    use prost::Message;

    let (server, mut client) = crate::common::server_with(ServeConfig::default()).await;
    let (tx, rx) = tokio::sync::mpsc::channel(4);
    let mut answers = client
        .wheel_rail_session(tokio_stream::wrappers::ReceiverStream::new(rx))
        .await
        .expect("session stream")
        .into_inner();
    let mut call = async |kind: In| {
        tx.send(pb::WheelRailSessionRequest { kind: Some(kind) })
            .await
            .expect("the stream is open");
        answers
            .message()
            .await
            .expect("an answer")
            .and_then(|r| r.kind)
            .expect("a response kind")
    };
    let opened = call(In::Open(pb::WheelRailSessionOpen {
        pair_id: "mbench_s1002_uic60".into(),
        model: pb::WheelRailModel::HertzFastsim as i32,
        client_label: "fuzz".into(),
        ..Default::default()
    }))
    .await;
    assert!(matches!(opened, Out::Opened(_)), "{opened:?}");
    let step = |index: u64, q: &pb::SolveWheelRailRequest, mark: bool| {
        In::Step(pb::WheelRailSessionStep {
            step_index: index,
            time_s: index as f64 * 1e-3,
            position: q.position,
            velocity: q.velocity,
            load: q.load,
            mark,
        })
    };
    let rollback = || In::Rollback(pb::SessionRollback { to_step_index: 0 });
    let good = wheel_query(pb::WheelRailModel::HertzFastsim);
    // The result's bits without its timings (which differ every step).
    let bits = |answer: Out| match answer {
        Out::Step(s) => {
            let mut r = s.result.expect("a result");
            r.timing = None;
            Ok(r.encode_to_vec())
        }
        other => Err(format!("{other:?}")),
    };
    bits(call(step(0, &good, true)).await).expect("the marked good step");
    assert!(matches!(call(rollback()).await, Out::RolledBack(_)));
    let after_mark = bits(call(step(1, &good, false)).await).expect("a good step");
    let mut out = Outcomes::default();
    let fields: Vec<_> = wheel_fields()
        .into_iter()
        .filter(|(path, _, _)| {
            ["position.", "velocity.", "load."]
                .iter()
                .any(|p| path.starts_with(p))
        })
        .collect();
    let mut poisoned = Vec::new();
    for (path, typical, set) in &fields {
        for v in extremes(*typical) {
            let mut q = good.clone();
            set(&mut q, v);
            let back = call(rollback()).await;
            assert!(matches!(back, Out::RolledBack(_)), "{back:?}");
            let r = match call(step(1, &q, false)).await {
                Out::Step(s) => Ok(s),
                Out::Error(e) => {
                    // In-band errors carry their field under `step.`.
                    let field = e.field.strip_prefix("step.").unwrap_or(&e.field);
                    let message = format!("invalid `{field}`: {}", e.message);
                    Err(tonic::Status::new(Code::from_i32(e.code), message))
                }
                other => panic!("{path} = {v:e}: {other:?}"),
            };
            let refused = r.is_err();
            out.record(
                path,
                format!("{v:e}"),
                r,
                |s: &pb::WheelRailSessionStepResult| {
                    let r = s.result.as_ref().ok_or("no result")?;
                    check_wheelrail_finite(r).map_err(|e| e.to_string())
                },
            );
            if refused {
                match bits(call(step(1, &good, false)).await) {
                    Ok(b) if b == after_mark => {}
                    Ok(_) => poisoned.push(format!(
                        "{path} = {v:e}: refused, yet the next good step differs"
                    )),
                    Err(e) => poisoned.push(format!("{path} = {v:e}: the next good step: {e}")),
                }
            }
        }
    }
    let total: usize = out.counts.values().sum();
    eprintln!(
        "session fuzz: {total} mutated steps over {} fields, outcomes {:?}",
        fields.len(),
        out.counts
    );
    drop(tx);
    server.shutdown().await;
    assert!(poisoned.is_empty(), "{}", poisoned.join("\n"));
    assert!(
        out.wrong.is_empty(),
        "{} of {total} answers are wrong:\n{}",
        out.wrong.len(),
        out.wrong.join("\n")
    );
}

/// A seeded xorshift generator (no dependency, the same cases every run).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }

    /// Uniform in [a, b).
    fn uniform(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * ((self.next() >> 11) as f64 / (1u64 << 53) as f64)
    }

    /// Log-uniform in [a, b), a > 0.
    fn log_uniform(&mut self, a: f64, b: f64) -> f64 {
        self.uniform(a.ln(), b.ln()).exp()
    }

    fn chance(&mut self, p: f64) -> bool {
        self.uniform(0.0, 1.0) < p
    }
}

/// One mutation of a profile's text.
fn mutate(text: &str, rng: &mut Rng) -> String {
    let mut s = text.to_string();
    let bytes = s.len();
    match rng.below(7) {
        // A digit changed.
        0 => {
            let digits: Vec<usize> = s
                .char_indices()
                .filter(|(_, c)| c.is_ascii_digit())
                .map(|(i, _)| i)
                .collect();
            if !digits.is_empty() {
                let i = digits[rng.below(digits.len())];
                let d = (b'0' + rng.below(10) as u8) as char;
                s.replace_range(i..i + 1, &d.to_string());
            }
        }
        // A number replaced by a huge, tiny or non-finite one.
        1 | 2 => {
            let huge = [
                "1e300", "-1e300", "5e-324", "nan", "inf", "-inf", "1e308", "0",
            ];
            let word = huge[rng.below(huge.len())];
            let starts: Vec<usize> = s
                .char_indices()
                .filter(|(i, c)| {
                    c.is_ascii_digit() && (*i == 0 || !s.as_bytes()[i - 1].is_ascii_alphanumeric())
                })
                .map(|(i, _)| i)
                .collect();
            if !starts.is_empty() {
                let i = starts[rng.below(starts.len())];
                let end = s[i..]
                    .find(|c: char| !(c.is_ascii_digit() || c == '.' || c == 'e' || c == '-'))
                    .map_or(s.len(), |k| i + k);
                s.replace_range(i..end, word);
            }
        }
        // Truncated at a character boundary.
        3 => {
            let mut cut = rng.below(bytes);
            while !s.is_char_boundary(cut) {
                cut -= 1;
            }
            s.truncate(cut);
        }
        // A very long line inserted.
        4 => {
            let mut at = rng.below(bytes);
            while !s.is_char_boundary(at) {
                at -= 1;
            }
            s.insert_str(at, &format!("\n{}\n", "9".repeat(100_000)));
        }
        // A line deleted.
        5 => {
            let lines: Vec<&str> = s.lines().collect();
            let k = rng.below(lines.len());
            s = lines
                .iter()
                .enumerate()
                .filter(|(i, _)| *i != k)
                .map(|(_, l)| *l)
                .collect::<Vec<_>>()
                .join("\n");
        }
        // Lines swapped (non-monotonic points).
        _ => {
            let mut lines: Vec<&str> = s.lines().collect();
            let (a, b) = (rng.below(lines.len()), rng.below(lines.len()));
            lines.swap(a, b);
            s = lines.join("\n");
        }
    }
    s
}

/// `crates/solver/profiles/uk_crossing_nose.slcs` with its slices file's
/// text `text`, placed by its origin under the S1002 wheel.
fn slices_spec(text: String) -> pb::ProfilePairSpec {
    let mut rail = crate::common::crossing_slices();
    if let Some(pb::profile_source::Source::Slices(s)) = rail.source.as_mut() {
        s.content = text;
    }
    let wheel = pb::ProfileSource {
        source: Some(pb::profile_source::Source::BuiltinName(
            "MBench_S1002_v3.prw".into(),
        )),
        mirror_y: false,
    };
    pb::ProfilePairSpec {
        smoothing_wavelength_m: Some(0.0),
        ..placed_by_origin(wheel, rail, 0.75, (1.36, 0.46, -0.07))
    }
}

/// A rail given as slices: its slices file mutated (as the profiles are
/// below) is registered or refused INVALID_ARGUMENT naming the rail
/// (`spec.rail.slices...`, or `spec` when the rail it makes does not
/// carry the trial solve), never a panic or another code; on the
/// registered pair, `position.track_s_m` at its extremes is answered or
/// refused naming it.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn mutated_rail_slices_register_or_are_refused_by_name() {
    let (server, mut client) = crate::common::server_with(ServeConfig::default()).await;
    let text = std::fs::read_to_string(crate::common::profiles_dir().join("uk_crossing_nose.slcs"))
        .unwrap();
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    let (mut ok, mut refused, mut wrong) = (0usize, 0usize, Vec::new());
    for k in 0..30 {
        let mutated = mutate(&text, &mut rng);
        match registration(&mut client, slices_spec(mutated)).await {
            Ok(_) => ok += 1,
            Err(s) if s.code() == Code::InvalidArgument => {
                refused += 1;
                let field = field_of(s.message()).unwrap_or("");
                if !(field.starts_with("spec.rail.slices") || field == "spec") {
                    wrong.push(format!("mutation {k}: names `{field}`: {}", s.message()));
                }
            }
            Err(s) => wrong.push(format!("mutation {k}: {:?} {}", s.code(), s.message())),
        }
    }
    let pair = registration(&mut client, slices_spec(text))
        .await
        .expect("the crossing nose registers");
    let mut out = Outcomes::default();
    for v in extremes(0.25).into_iter().chain([0.20875, 0.239, 0.32696]) {
        let mut q = wheel_query(pb::WheelRailModel::Exact);
        q.pair_id = pair.pair_id.clone();
        q.sides = pb::WheelSides::Right as i32;
        q.position = Some(pb::WheelsetPosition {
            lateral_m: 0.00081,
            roll_rad: Some(0.0),
            track_s_m: v,
            ..Default::default()
        });
        q.velocity = Some(pb::WheelsetVelocity {
            forward_m_per_s: 2.0,
            ..Default::default()
        });
        q.load = Some(pb::WheelLoad {
            load: Some(pb::wheel_load::Load::VerticalForceN(1e4)),
            ..Default::default()
        });
        let r = client.solve_wheel_rail(q).await;
        out.record("position.track_s_m", format!("{v:e}"), r, wheel_finite);
    }
    eprintln!(
        "slices fuzz: 30 mutated slices files, {ok} registered, {refused} refused; \
         track_s_m outcomes {:?}",
        out.counts
    );
    server.shutdown().await;
    wrong.extend(out.wrong);
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

/// Numerical influence coefficients sent inline
/// (`case.material.influence_file_content`): the text of a real file
/// (`crates/solver/tests/data/inflcf/inflcf_hs_small.txt`) mutated as the
/// profiles are (digits, huge/tiny/non-finite numbers, truncation, a
/// 100 kB line, lines deleted or swapped), and headers declaring huge
/// grids: solved with every number finite, or INVALID_ARGUMENT naming the
/// field (at most 600 characters of message), never another code.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn mutated_influence_coefficients_are_solved_or_refused_by_name() {
    use crate::service_influence::{inflcf, numerical_influence_case};
    let (server, mut client) = crate::common::server_with(ServeConfig::default()).await;
    let text = inflcf("inflcf_hs_small.txt");
    let mut rng = Rng(0xd1b5_4a32_d192_ed03);
    let mut texts: Vec<String> = (0..40).map(|_| mutate(&text, &mut rng)).collect();
    for (matrices, mx, my) in [
        ("1", "1048576", "1048576"),
        ("1048576", "1", "1"),
        ("1", "1048576", "1"),
        ("-1", "13", "9"),
        ("1", "0", "9"),
        ("1", "9223372036854775807", "9"),
    ] {
        texts.push(format!("{matrices} 1\n0 312\n1 0\n{mx} {my} 0.4 0.4\n"));
    }
    let mut out = Outcomes::default();
    for (k, t) in texts.into_iter().enumerate() {
        let r = client
            .solve_patch(pb::SolvePatchRequest {
                case: Some(numerical_influence_case(t)),
                ..Default::default()
            })
            .await;
        out.record(
            "case.material.influence_file_content",
            format!("text {k}"),
            r,
            |r: &tonic::Response<pb::SolvePatchResponse>| {
                let r = r.get_ref().result.as_ref().ok_or("no result")?;
                check_finite(r).map_err(|e| e.to_string())
            },
        );
    }
    server.shutdown().await;
    out.assert_right("influence-coefficient fuzz");
}

#[test]
fn mutated_profiles_read_or_fail_without_panicking() {
    let dir = crate::common::profiles_dir();
    let files = [
        "MBench_S1002_v3.prw",
        "MBench_UIC60_v3.prr",
        "avg_HR.BAN",
        "avg_wheel.whl",
    ];
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let (mut ok, mut refused, mut panicked) = (0usize, 0usize, Vec::new());
    let quiet = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    for name in files {
        let Ok(text) = std::fs::read_to_string(dir.join(name)) else {
            continue;
        };
        for k in 0..120 {
            let mutated = mutate(&text, &mut rng);
            let r = catch_unwind(AssertUnwindSafe(|| {
                parse_profile(&mutated, name, &LoadOptions::default()).is_ok()
            }));
            match r {
                Ok(true) => ok += 1,
                Ok(false) => refused += 1,
                Err(_) => panicked.push(format!("{name} mutation {k}")),
            }
        }
    }
    std::panic::set_hook(quiet);
    eprintln!(
        "profile reader fuzz: {} cases, {ok} read, {refused} ProfileError, {} panics",
        ok + refused + panicked.len(),
        panicked.len()
    );
    assert!(ok + refused > 0, "no profile found in {}", dir.display());
    assert!(panicked.is_empty(), "the readers panicked on: {panicked:?}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn wheel_rail_patch_grids_obey_the_grid_limit() {
    let (server, mut client) = crate::common::server_with(ServeConfig {
        max_grid_elements: 160 * 160,
        ..ServeConfig::default()
    })
    .await;
    let mut req = wheel_query(pb::WheelRailModel::Exact);
    req.element_size_m = Some(6e-5);
    let e = client.solve_wheel_rail(req.clone()).await.unwrap_err();
    assert_eq!(e.code(), Code::InvalidArgument, "{e:?}");
    assert_eq!(field_of(e.message()), Some("element_size_m"), "{e:?}");
    assert!(
        e.message().contains("more than the limit of 25600"),
        "{e:?}"
    );
    // The pair's own 0.2 mm elements fit.
    req.element_size_m = None;
    let r = client.solve_wheel_rail(req).await.expect("solves");
    check_wheelrail_finite(r.get_ref().result.as_ref().unwrap()).unwrap();
    server.shutdown().await;
}

/// A wheel/rail query of the built-in pair with every input drawn at once
/// over the range of a wheelset on its track and somewhat beyond: lateral
/// shift within 12 mm (a sixth of them 20 mm), yaw 20 mrad, roll given in
/// a fifth, speeds 0.5 to 100 m/s (a quarter of them backwards) with
/// lateral, vertical, roll and yaw rates, the pitch rate given in a fifth
/// (2 % about rolling) or a total
/// longitudinal force in some others, a vertical load of 1 to 250 kN
/// (or an approach, or a centre height), friction 0.05 to 0.7; the fast
/// models mostly, exact, cect and auto in one query of `heavy` on
/// average, with the element size drawn in some.
fn random_wheel_query(rng: &mut Rng, heavy: f64) -> pb::SolveWheelRailRequest {
    use pb::wheel_load::Load;
    use pb::WheelRailModel as M;
    let heavy = rng.chance(heavy);
    let model = if heavy {
        [M::Exact, M::Cect, M::Auto][rng.below(3)]
    } else {
        [
            M::HertzFastsim,
            M::HertzFastsimTable,
            M::HertzPolach,
            M::HertzFastsimElliptic,
            M::HertzStrip,
            M::KikPiotrowski,
            M::HertzFastsimModified,
        ][rng.below(7)]
    };
    let reach = if rng.chance(0.15) { 20e-3 } else { 12e-3 };
    let lateral_m = rng.uniform(-reach, reach);
    let yaw_rad = rng.uniform(-20e-3, 20e-3);
    let roll_rad = rng.chance(0.2).then(|| rng.uniform(-5e-3, 5e-3));
    // A quarter roll backwards (cect and auto refuse them naming `model`).
    let sense = if rng.chance(0.25) { -1.0 } else { 1.0 };
    let forward_m_per_s = sense * rng.log_uniform(0.5, 100.0);
    let pitch_rad_per_s = rng
        .chance(0.2)
        .then(|| -forward_m_per_s / 0.46 * (1.0 + rng.uniform(-0.02, 0.02)));
    let load = match rng.below(7) {
        0 => Load::ApproachM(rng.log_uniform(1e-6, 5e-4)),
        1 => Load::CenterZM(rng.uniform(-0.462, -0.455)),
        _ => Load::VerticalForceN(rng.log_uniform(1e3, 2.5e5)),
    };
    let total_longitudinal_force_n =
        (pitch_rad_per_s.is_none() && rng.chance(0.15)).then(|| rng.uniform(-3e4, 3e4));
    let coefficient = Some(rng.uniform(0.05, 0.7));
    let element_size_m = (heavy && rng.chance(0.3)).then(|| rng.uniform(1.2e-4, 5e-4));
    pb::SolveWheelRailRequest {
        pair_id: "mbench_s1002_uic60".into(),
        model: model as i32,
        position: Some(pb::WheelsetPosition {
            lateral_m,
            yaw_rad,
            roll_rad,
            ..Default::default()
        }),
        velocity: Some(pb::WheelsetVelocity {
            forward_m_per_s,
            lateral_m_per_s: rng.uniform(-1.0, 1.0),
            vertical_m_per_s: rng.uniform(-0.1, 0.1),
            roll_rad_per_s: rng.uniform(-0.3, 0.3),
            yaw_rad_per_s: rng.uniform(-0.3, 0.3),
            pitch_rad_per_s,
            roller_rad_per_s: None,
        }),
        load: Some(pb::WheelLoad {
            load: Some(load),
            total_longitudinal_force_n,
        }),
        friction: Some(pb::FrictionSection {
            coefficient,
            ..Default::default()
        }),
        element_size_m,
        ..Default::default()
    }
}

/// Random wheel/rail queries, every input drawn at once
/// ([`random_wheel_query`], seeded: the same 400 every run), against the
/// real server in-process. Each is answered with finite figures and, when
/// the load is a vertical force, each wheel's vertical force within the
/// load tolerance (1e-6) of it (within `LOAD_LIMIT_MISS` where the load
/// iteration spent its solves), or refused with INVALID_ARGUMENT naming a
/// field of the request. (Such queries found load iterations that answered
/// 17 % short of a flange's load and with a negative vertical force on a
/// steep flange, conformal surfaces refused naming `geometry` and
/// Kik-Piotrowski's normal problem naming `kik_piotrowski`, fields of no
/// wheel/rail request; this seed's 400 meet the first two.)
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn random_wheel_queries_carry_their_loads_or_are_refused_by_name() {
    let (server, mut client) = crate::common::server_with(ServeConfig::default()).await;
    use railcontact::wheelrail::contact::{WheelRailSettings, LOAD_LIMIT_MISS};
    let limit = WheelRailSettings::default().max_load_iterations;
    let mut rng = Rng(3);
    let fields = [
        "position.",
        "velocity.",
        "load.",
        "element_size_m",
        "friction.",
        "model",
    ];
    let (mut counts, mut wrong) = (BTreeMap::<String, usize>::new(), Vec::new());
    for i in 0..400 {
        let req = random_wheel_query(&mut rng, 0.08);
        let vertical = match req.load.as_ref().and_then(|l| l.load.as_ref()) {
            Some(pb::wheel_load::Load::VerticalForceN(f)) => Some(*f),
            _ => None,
        };
        let what = format!("query {i}: {req:?}");
        match client.solve_wheel_rail(req).await {
            Ok(r) => {
                *counts.entry("OK".into()).or_default() += 1;
                let r = r.into_inner().result.expect("a result");
                if let Err(e) = check_wheelrail_finite(&r) {
                    wrong.push(format!("non-finite {e}: {what}"));
                }
                for (w, f) in r.wheels.iter().filter_map(|w| Some((w, vertical?))) {
                    let fz = w.force_track_n.unwrap().z_n;
                    // The load tolerance, or the nearest solve of a load
                    // iteration that spent its solves (a force that jumps
                    // with the normal force) within LOAD_LIMIT_MISS.
                    let spent = w.load_iterations as usize >= limit;
                    if spent {
                        *counts.entry("at the iteration limit".into()).or_default() += 1;
                    }
                    let allowed = if spent { LOAD_LIMIT_MISS } else { 1.01e-6 };
                    if (fz - f).abs() > allowed * f {
                        wrong.push(format!(
                            "vertical force {fz} N against {f} N after {} load iterations: {what}",
                            w.load_iterations
                        ));
                    }
                }
            }
            Err(s) if s.code() == Code::InvalidArgument => {
                let field = field_of(s.message()).unwrap_or("").to_string();
                if !fields.iter().any(|f| field.starts_with(f)) {
                    wrong.push(format!(
                        "INVALID_ARGUMENT names `{field}`: {}: {what}",
                        s.message()
                    ));
                }
                *counts.entry(field).or_default() += 1;
            }
            Err(s) => wrong.push(format!("{:?} {}: {what}", s.code(), s.message())),
        }
    }
    eprintln!("random wheel/rail queries: {counts:?}");
    server.shutdown().await;
    assert!(
        wrong.is_empty(),
        "{} wrong:\n{}",
        wrong.len(),
        wrong.join("\n")
    );
    // Most are answered.
    assert!(counts["OK"] > 250, "{counts:?}");
}
