//! Criterion benchmarks of the contact core. See benches/README.md for what
//! each measures; run with `cargo bench --bench contact`.

use std::hint::black_box;
use std::sync::Arc;

use criterion::{criterion_group, criterion_main, BatchSize, BenchmarkId, Criterion};

use railcontact::core::cache::KernelCache;
use railcontact::core::fastrip::GridFastrip;
use railcontact::core::fastsim::{Fastsim, FastsimInput, SlopeReduction, TractionBound};
use railcontact::core::fastsim_grid::{
    BoundScaling, CreepInterpolation, GridFastsim, GridFastsimInput, GridFlexibility, GridFriction,
    GridPressure, RollingSense,
};
use railcontact::core::fft::{ConvolutionPlan, KernelSet, Precision};
use railcontact::core::force::{
    solve_prescribed_force, solve_prescribed_force_step, ForceControlSettings, PrescribedForce,
};
use railcontact::core::grid::Grid;
use railcontact::core::hertz::{hertz, HertzLoad};
use railcontact::core::influence::{Component, HalfSpaceInfluence, KernelKind};
use railcontact::core::kikpiotrowski::{KikPiotrowski, KikPiotrowskiSettings, KpSection};
use railcontact::core::layer::InterfacialLayer;
use railcontact::core::material::{CombinedMaterial, Material};
use railcontact::core::normal::NormalLoad;
use railcontact::core::polach::{polach, PolachParameters};
use railcontact::core::problem::{ContactProblem, Creepages, Friction, Kinematics, ShiftStep};
use railcontact::core::sensitivity::exact_jacobian;
use railcontact::core::solve::{ContactSolver, SolverState};
use railcontact::core::strip::strip_theory;
use railcontact::core::subsurface::{subsurface_fields, Body, DepthKernels, SubsurfaceWorkspace};
use railcontact::core::viscoelastic::{Sls, Viscoelastic};

const SIZES: [usize; 4] = [32, 48, 64, 128];
/// Steps per period of the warm-start benches' creepage path.
const PATH_STEPS: usize = 100;

fn steel() -> CombinedMaterial {
    CombinedMaterial::identical(Material::STEEL).unwrap()
}

/// Hertz circle (A = B = 1/m, 10 kN) on an n x n grid 1.2 times the patch.
fn circle(n: usize, kinematics: Kinematics) -> ContactProblem {
    circle_on(n, n, kinematics)
}

/// Hertz circle on an nx x ny grid 1.2 times the patch.
fn circle_on(nx: usize, ny: usize, kinematics: Kinematics) -> ContactProblem {
    let m = steel();
    let hz = hertz(
        1.0,
        1.0,
        m.effective_modulus_pa(),
        HertzLoad::NormalForce {
            normal_force_n: 1e4,
        },
    )
    .unwrap();
    let w = 2.4 * hz.semi_axis_x_m;
    let grid = Grid::centered(nx, ny, w, w).unwrap();
    ContactProblem {
        material: m,
        friction: Friction::coulomb(0.3),
        gap_m: ContactProblem::quadratic_gap(&grid, 1.0, 1.0),
        grid,
        load: NormalLoad::NormalForce(1e4),
        kinematics,
        settings: Default::default(),
        rolling_direction_rad: 0.0,
        extra_rigid_slip: None,
        numerical_influence: None,
    }
}

fn kernels(c: &mut Criterion) {
    let mut g = c.benchmark_group("kernel_build");
    for n in SIZES {
        let plan = Arc::new(ConvolutionPlan::new(n, n));
        let ic = HalfSpaceInfluence::new(1e-4, 1e-4, &steel());
        g.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
            b.iter(|| KernelSet::new(plan.clone(), ic, KernelKind::Displacement))
        });
    }
    g.finish();
}

fn matvecs(c: &mut Criterion) {
    let mut g = c.benchmark_group("matvec");
    for n in SIZES {
        let plan = Arc::new(ConvolutionPlan::new(n, n));
        let set = KernelSet::new(
            plan,
            HalfSpaceInfluence::new(1e-4, 1e-4, &steel()),
            KernelKind::Displacement,
        );
        let mut ws = set.workspace();
        let p: Vec<f64> = (0..n * n).map(|i| (i % 7) as f64).collect();
        let (mut ux, mut uy) = (vec![0.0; n * n], vec![0.0; n * n]);
        g.bench_with_input(BenchmarkId::new("normal", n), &n, |b, _| {
            b.iter(|| {
                set.apply(
                    &mut ws,
                    &[(Component::N, &p)],
                    &mut [(Component::N, &mut ux)],
                )
            })
        });
        // Sixteen columns spread over the grid: the pressure changes of the
        // elements a normal iteration clamped (`KernelSet::add_normal_columns`).
        let columns: Vec<(usize, f64)> = (0..16).map(|k| (k * n * n / 16 + n / 2, 1.0)).collect();
        g.bench_with_input(BenchmarkId::new("normal_columns_16", n), &n, |b, _| {
            b.iter(|| set.add_normal_columns(&columns, 0, &mut ux))
        });
        g.bench_with_input(BenchmarkId::new("tangential", n), &n, |b, _| {
            b.iter(|| {
                set.apply(
                    &mut ws,
                    &[(Component::X, &p), (Component::Y, &p)],
                    &mut [(Component::X, &mut ux), (Component::Y, &mut uy)],
                )
            })
        });
        g.bench_with_input(BenchmarkId::new("tangential_single", n), &n, |b, _| {
            b.iter(|| {
                set.apply_with(
                    Precision::Single,
                    &mut ws,
                    &[(Component::X, &p), (Component::Y, &p)],
                    &mut [(Component::X, &mut ux), (Component::Y, &mut uy)],
                )
            })
        });
    }
    g.finish();
}

/// Prints the iteration and product counts of one solve (deterministic,
/// unlike the times), for benches/README.md.
fn print_counts(id: &str, s: &mut ContactSolver, p: &ContactProblem) {
    let i = &s.solve(p).unwrap()[0].info;
    eprintln!(
        "counts {id}: normal iterations {}, tangential (Newton) iterations {}, operator products {}",
        i.normal_iterations, i.tangential_iterations, i.matvecs
    );
}

fn normal_solve(c: &mut Criterion) {
    let mut g = c.benchmark_group("normal_solve");
    for n in SIZES {
        let p = circle(n, Kinematics::Frictionless);
        let cache = KernelCache::default();
        let mut s = ContactSolver::new(&p, &cache);
        print_counts(&format!("normal_solve/{n}"), &mut s, &p);
        g.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
            b.iter(|| {
                s.reset();
                black_box(s.solve(&p).unwrap())
            })
        });
    }
    g.finish();
}

fn tangential_solves(c: &mut Criterion) {
    let mut g = c.benchmark_group("tangential_solve");
    g.sample_size(10);
    // Steady rolling, mixed adhesion/slip with creepages and spin, cold
    // start (normal + tangential), and warm: consecutive steps of a smooth
    // path (creepages 1 + 0.3 sin(2 pi k / 100) times the base values, up
    // to 1.9 % a step, as MBS time steps), each from the previous steps'
    // solutions.
    let creep = |f: f64| {
        Kinematics::SteadyRolling(Creepages {
            creepage_long: 5e-4 * f,
            creepage_lat: 3e-4 * f,
            spin_per_m: 0.3 * f,
        })
    };
    for (nx, ny) in [(32, 32), (48, 44), (64, 64), (128, 128)] {
        let p = circle_on(nx, ny, creep(1.0));
        let path: Vec<ContactProblem> = (0..PATH_STEPS)
            .map(|k| {
                let a = 2.0 * std::f64::consts::PI * k as f64 / PATH_STEPS as f64;
                circle_on(nx, ny, creep(1.0 + 0.3 * a.sin()))
            })
            .collect();
        let cache = KernelCache::default();
        let mut s = ContactSolver::new(&p, &cache);
        let id = format!("{nx}x{ny}");
        print_counts(&format!("steady_rolling/{id} (cold)"), &mut s, &p);
        // Two steps of the path first: the third has its full warm start.
        s.solve(&path[0]).unwrap();
        s.solve(&path[1]).unwrap();
        print_counts(&format!("steady_rolling_warm/{id}"), &mut s, &path[2]);
        g.bench_with_input(BenchmarkId::new("steady_rolling", &id), &nx, |b, _| {
            b.iter(|| {
                s.reset();
                black_box(s.solve(&p).unwrap())
            })
        });
        let mut k = 0;
        g.bench_with_input(BenchmarkId::new("steady_rolling_warm", &id), &nx, |b, _| {
            b.iter(|| {
                k += 1;
                black_box(s.solve(&path[k % PATH_STEPS]).unwrap())
            })
        });
    }
    // The Jacobian of the forces (core::sensitivity: 8 perturbed solves
    // warm-started from the converged solution) after a solve.
    for (nx, ny) in [(32, 32), (48, 44)] {
        let p = circle_on(nx, ny, creep(1.0));
        let cache = KernelCache::default();
        let mut s = ContactSolver::new(&p, &cache);
        let base = s.solve(&p).unwrap().pop().unwrap();
        let id = format!("{nx}x{ny}");
        g.bench_with_input(BenchmarkId::new("steady_jacobian", &id), &nx, |b, _| {
            b.iter(|| black_box(exact_jacobian(&s, &p, &base).unwrap()))
        });
    }
    // Transient: one loading step and one tangential shift step (Cattaneo).
    for n in [32, 64] {
        let step = |sx: f64| ShiftStep {
            load: NormalLoad::NormalForce(1e4),
            shift_x_m: sx,
            shift_y_m: 0.0,
            rotation_rad: 0.0,
            rolling_m: 0.0,
        };
        let p = circle(n, Kinematics::Transient(vec![step(0.0), step(0.4e-6)]));
        let cache = KernelCache::default();
        let mut s = ContactSolver::new(&p, &cache);
        g.bench_with_input(BenchmarkId::new("transient_2_steps", n), &n, |b, _| {
            b.iter(|| black_box(s.solve(&p).unwrap()))
        });
    }
    // Transient rolling: one more step of one element (dq = dx) at the
    // creepages of `steady_rolling`, from a patch rolled in for three
    // crossings (each iteration rolls on from the last).
    for n in [32, 64] {
        let Kinematics::SteadyRolling(c) = creep(1.0) else {
            unreachable!()
        };
        let mut p = circle(n, creep(1.0));
        let step = ShiftStep::rolling(p.load, p.grid.dx_m, &c);
        p.kinematics = Kinematics::Transient(vec![step; 3 * n]);
        let cache = KernelCache::default();
        let mut s = ContactSolver::new(&p, &cache);
        s.solve(&p).unwrap();
        let last = s.solve_next_step(&p, &step).unwrap();
        println!(
            "counts transient_rolling_step/{n}: tangential iterations {}, operator products {}",
            last.info.tangential_iterations, last.info.matvecs
        );
        g.bench_with_input(BenchmarkId::new("transient_rolling_step", n), &n, |b, _| {
            b.iter(|| black_box(s.solve_next_step(&p, &step).unwrap()))
        });
        // The same step at its Fx prescribed (the shift starting from 0, as
        // case files and sessions start it), each time from the same state.
        let target = PrescribedForce {
            force_x_n: Some(last.totals.fx_n),
            force_y_n: None,
        };
        let start = ShiftStep {
            shift_x_m: 0.0,
            ..step
        };
        let mut before = SolverState::default();
        s.save_state(&mut before);
        let settings = ForceControlSettings::default();
        let r = solve_prescribed_force_step(&mut s, &p, &start, target, settings).unwrap();
        println!(
            "counts transient_rolling_step_force/{n}: {} secant steps, {} solves",
            r.outer_iterations, r.solves
        );
        g.bench_with_input(
            BenchmarkId::new("transient_rolling_step_force", n),
            &n,
            |b, _| {
                b.iter(|| {
                    s.restore_state(&before).unwrap();
                    black_box(solve_prescribed_force_step(
                        &mut s, &p, &start, target, settings,
                    ))
                })
            },
        );
        // Steady rolling of the same patch at that Fx prescribed, cold
        // (its creepage starting from 0, as case files start it).
        let mut steady = circle(n, creep(1.0));
        let steady_target = PrescribedForce {
            force_x_n: Some(s.solve(&steady).unwrap()[0].totals.fx_n),
            force_y_n: None,
        };
        steady.kinematics = Kinematics::SteadyRolling(Creepages {
            creepage_long: 0.0,
            ..c
        });
        g.bench_with_input(BenchmarkId::new("steady_rolling_force", n), &n, |b, _| {
            b.iter(|| {
                s.reset();
                black_box(solve_prescribed_force(
                    &mut s,
                    &steady,
                    steady_target,
                    settings,
                ))
            })
        });
    }
    g.finish();
}

fn reference_models(c: &mut Criterion) {
    let e = steel().effective_modulus_pa();
    c.bench_function("hertz", |b| {
        b.iter(|| {
            hertz(
                black_box(1.0),
                black_box(0.37),
                e,
                HertzLoad::NormalForce {
                    normal_force_n: 1e4,
                },
            )
            .unwrap()
        })
    });
    let mut fs = Fastsim::new(40, 40).unwrap();
    let input = FastsimInput {
        semi_axis_x_m: 4e-3,
        semi_axis_y_m: 6e-3,
        normal_force_n: 1e5,
        shear_modulus_pa: 81e9,
        poisson_ratio: 0.3,
        friction_coefficient: 0.3,
        static_friction_coefficient: 0.3,
        creepage_long: 1e-3,
        creepage_lat: 5e-4,
        spin_per_m: 0.2,
    };
    c.bench_function("fastsim_40x40", |b| {
        b.iter(|| black_box(fs.solve(&input).unwrap()))
    });
    let mut totals = Fastsim::totals_only(40, 40).unwrap();
    c.bench_function("fastsim_40x40_totals", |b| {
        b.iter(|| black_box(totals.solve(&input).unwrap()))
    });
    c.bench_function("polach", |b| {
        b.iter(|| black_box(polach(black_box(&input), 30.0, &PolachParameters::DRY).unwrap()))
    });
    // Spiryagin et al.'s reduction with made-up parameters in their ranges:
    // the cost is the solve's, whatever the values.
    let reduction = SlopeReduction {
        initial_factor: 0.7,
        limit_ratio: 0.3,
        transition_rate: 0.5,
        friction_limit_ratio: 0.4,
        friction_decay_s_per_m: 0.6,
    };
    c.bench_function("fastsim_modified_40x40", |b| {
        b.iter(|| black_box(fs.solve_modified(&input, 30.0, &reduction).unwrap()))
    });
    fs.set_traction_bound(TractionBound::Elliptic);
    c.bench_function("fastsim_elliptic_40x40", |b| {
        b.iter(|| black_box(fs.solve(&input).unwrap()))
    });
    c.bench_function("strip_100", |b| {
        b.iter(|| black_box(strip_theory(black_box(&input), 100).unwrap()))
    });
    // Kik-Piotrowski on a non-elliptic gap (a wheel of radius 0.46 m, a
    // lateral gap B y^2 + C y^4 flatter than a parabola), 201 sections, 48
    // strips: the normal solve under force control, then FASTSIM (40
    // elements per strip, totals only) on its area.
    let sections: Vec<KpSection> = (0..201)
        .map(|k| {
            let y = -0.015 + 0.03 * k as f64 / 200.0;
            KpSection {
                y_m: y,
                gap_m: 1.0 * y * y + 4e3 * y.powi(4),
                centre_x_m: 0.0,
                curvature_x_per_m: 1.0 / 0.46,
            }
        })
        .collect();
    let fresh = KikPiotrowski::new(KikPiotrowskiSettings::default()).unwrap();
    let load = NormalLoad::NormalForce(1e5);
    // Cold: a fresh workspace (the force iteration from Hertz's circle);
    // warm: the last solve at 1 % less force (a load iteration's next step).
    c.bench_function("kik_piotrowski_normal_48_cold", |b| {
        b.iter_batched_ref(
            || fresh.clone(),
            |kp| black_box(kp.solve_normal(black_box(&sections), load, e).unwrap()),
            BatchSize::SmallInput,
        )
    });
    let mut kp = fresh.clone();
    c.bench_function("kik_piotrowski_normal_48_warm", |b| {
        b.iter(|| {
            kp.solve_normal(&sections, NormalLoad::NormalForce(0.99e5), e)
                .unwrap();
            black_box(kp.solve_normal(black_box(&sections), load, e).unwrap())
        })
    });
    let normal = kp.solve_normal(&sections, load, e).unwrap();
    c.bench_function("kik_piotrowski_fastsim_48x40_totals", |b| {
        b.iter(|| black_box(kp.solve_tangential(&normal, &input, &mut totals).unwrap()))
    });
}

/// Subsurface stresses below the 64 x 64 steady-rolling circle (xi = 1e-3,
/// mu = 0.3) at 32 depths from 0 to 1.5 a: the kernels of body 1 at all
/// depths (built once), one evaluation of body 1 from built kernels
/// (transform of the tractions, 32 x 9 products), and the one-shot
/// `subsurface_fields` of both bodies (kernels built and dropped depth by
/// depth).
fn subsurface(c: &mut Criterion) {
    let mut g = c.benchmark_group("subsurface");
    g.sample_size(10);
    let n = 64;
    let p = circle(
        n,
        Kinematics::SteadyRolling(Creepages {
            creepage_long: 1e-3,
            ..Default::default()
        }),
    );
    let cache = KernelCache::default();
    let mut s = ContactSolver::new(&p, &cache);
    let sol = s.solve(&p).unwrap().pop().unwrap();
    let a = 0.5 * sol.totals.patch_length_m;
    let depths: Vec<f64> = (0..32).map(|k| 1.5 * a * k as f64 / 31.0).collect();
    let plan = ConvolutionPlan::new(n, n);
    let body1 = p.material.body1;
    g.bench_function("kernels_32_depths/64", |b| {
        b.iter(|| {
            black_box(
                depths
                    .iter()
                    .map(|&z| DepthKernels::new(&plan, &p.grid, &body1, z))
                    .collect::<Vec<_>>(),
            )
        })
    });
    let kernels: Vec<DepthKernels> = depths
        .iter()
        .map(|&z| DepthKernels::new(&plan, &p.grid, &body1, z))
        .collect();
    eprintln!(
        "subsurface kernels, 32 depths at 64x64: {:.1} MB",
        kernels.iter().map(DepthKernels::bytes).sum::<usize>() as f64 / 1e6
    );
    let f = &sol.fields;
    let mut ws = SubsurfaceWorkspace::new(&plan);
    let mut out: Vec<Vec<f64>> = (0..9).map(|_| vec![0.0; n * n * depths.len()]).collect();
    g.bench_function("evaluate_32_depths/64", |b| {
        b.iter(|| {
            ws.load(
                &plan,
                Body::One,
                [&f.traction_x_pa, &f.traction_y_pa, &f.pressure_pa],
            );
            for (k, kz) in kernels.iter().enumerate() {
                let r = k * n * n..(k + 1) * n * n;
                let [o0, o1, o2, o3, o4, o5, o6, o7, o8] = &mut out[..] else {
                    unreachable!()
                };
                kz.apply(
                    &plan,
                    &mut ws,
                    [
                        &mut o0[r.clone()],
                        &mut o1[r.clone()],
                        &mut o2[r.clone()],
                        &mut o3[r.clone()],
                        &mut o4[r.clone()],
                        &mut o5[r.clone()],
                        &mut o6[r.clone()],
                        &mut o7[r.clone()],
                        &mut o8[r],
                    ],
                );
            }
        })
    });
    g.bench_function("fields_both_bodies_32_depths/64", |b| {
        b.iter(|| black_box(subsurface_fields(&p.grid, &p.material, f, &depths).unwrap()))
    });
    g.finish();
}

/// FASTSIM and FaStrip on CONTACT's rectangular grid (CONTACT's M = 3 and
/// M = 5 with B = 2, `core::fastsim_grid`, `core::fastrip`): the patch of
/// CONTACT's `examples/fastsim.inp` cases 4 and 7 (a, b = 8, 4 mm, FN = 82
/// kN, G = 82 GPa, nu = 0.28, mu = 0.3, eta = -0.000625, phi = 0.625 /m),
/// 44 x 44 and 220 x 220 elements over 1.1 times the ellipse.
fn grid_fastsim(c: &mut Criterion) {
    let mut g = c.benchmark_group("fastsim_grid");
    let input = GridFastsimInput {
        semi_axis_x_m: 8e-3,
        semi_axis_y_m: 4e-3,
        normal_force_n: 82e3,
        shear_modulus_pa: 82e9,
        poisson_ratio: 0.28,
        creepage_long: 0.0,
        creepage_lat: -0.000625,
        spin_per_m: 0.625,
        rolling_speed_m_per_s: 30.0,
        friction: GridFriction::Coulomb(0.3),
        reduction: SlopeReduction::NONE,
        flexibility: GridFlexibility::Kalker { blending: true },
        rolling: RollingSense::PlusX,
        creep_table: CreepInterpolation::Contact,
    };
    let elliptic = GridPressure::Hertz {
        bound: TractionBound::Elliptic,
        scaling: BoundScaling::Analytic,
    };
    for n in [44, 220] {
        let grid = Grid::centered(n, n, 2.2 * 8e-3, 2.2 * 4e-3).unwrap();
        let mut fastsim = GridFastsim::new(grid).unwrap();
        g.bench_with_input(BenchmarkId::new("fastsim", n), &n, |b, _| {
            b.iter(|| black_box(fastsim.solve(&input, elliptic).unwrap()))
        });
        let mut fastrip = GridFastrip::new(grid).unwrap();
        g.bench_with_input(BenchmarkId::new("fastrip", n), &n, |b, _| {
            b.iter(|| black_box(fastrip.solve(&input, elliptic).unwrap()))
        });
    }
    g.finish();
}

/// Exact steady rolling of `steady_rolling`'s circle (cold, 32 x 32) with
/// an elasto-plastic third-body layer (CONTACT's M = 4: h = 0.1 mm, G3 = 10
/// GPa, a flexibility h/G3 near the bodies' own, yield limit 50 MPa, below
/// mu p0, perfectly plastic) and with viscoelastic bodies (M = 1: body 1
/// f_g = 1, tau_c = 5 ms at 1 m/s; the solve on cached kernels, and the
/// kernels built afresh and a solve).
fn capabilities(c: &mut Criterion) {
    let mut g = c.benchmark_group("capabilities");
    g.sample_size(10);
    let n = 32;
    let rolling = Kinematics::SteadyRolling(Creepages {
        creepage_long: 5e-4,
        creepage_lat: 3e-4,
        spin_per_m: 0.3,
    });
    let mut p = circle(n, rolling.clone());
    p.settings.interfacial_layer = Some(InterfacialLayer {
        yield_limit_pa: 50e6,
        ..InterfacialLayer::elastic(1e-4, 10e9)
    });
    let cache = KernelCache::default();
    let mut s = ContactSolver::new(&p, &cache);
    print_counts(
        &format!("capabilities/layer_plastic_steady/{n}"),
        &mut s,
        &p,
    );
    g.bench_with_input(BenchmarkId::new("layer_plastic_steady", n), &n, |b, _| {
        b.iter(|| {
            s.reset();
            black_box(s.solve(&p).unwrap())
        })
    });
    let mut p = circle(n, rolling);
    p.settings.viscoelastic = Some(Viscoelastic {
        rolling_speed_m_per_s: 1.0,
        body1: Sls {
            relaxation_ratio: 1.0,
            creep_relaxation_time_s: 5e-3,
        },
        body2: Sls::default(),
    });
    let cache = KernelCache::default();
    let mut s = ContactSolver::new(&p, &cache);
    print_counts(&format!("capabilities/viscoelastic_steady/{n}"), &mut s, &p);
    g.bench_with_input(BenchmarkId::new("viscoelastic_steady", n), &n, |b, _| {
        b.iter(|| {
            s.reset();
            black_box(s.solve(&p).unwrap())
        })
    });
    g.bench_with_input(BenchmarkId::new("viscoelastic_cold", n), &n, |b, _| {
        b.iter(|| {
            let cache = KernelCache::default();
            let mut s = ContactSolver::new(&p, &cache);
            black_box(s.solve(&p).unwrap())
        })
    });
    g.finish();
}

criterion_group!(
    benches,
    kernels,
    matvecs,
    normal_solve,
    tangential_solves,
    reference_models,
    grid_fastsim,
    capabilities,
    subsurface
);
criterion_main!(benches);
