//! Criterion benchmarks of the conformal (CECT) solvers against the planar
//! core on the same grids. See benches/README.md; run with
//! `cargo bench --bench conformal`.

use std::hint::black_box;
use std::sync::Arc;
use std::time::Instant;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};

use railcontact::conformal::frictional::{
    solve_frictional, ConformalKinematics, ConformalSettings, FrictionalWorkspace,
};
use railcontact::conformal::geometry::{Circle, ConformalCreepages, ConformalGeometry};
use railcontact::conformal::operator::{ConformalOperator, InfluenceModel};
use railcontact::conformal::solve::{conformal_hertz, solve_frictionless};
use railcontact::core::cache::KernelCache;
use railcontact::core::fft::{ConvolutionPlan, KernelSet};
use railcontact::core::grid::Grid;
use railcontact::core::influence::{Component, HalfSpaceInfluence, KernelKind};
use railcontact::core::material::{CombinedMaterial, Material};
use railcontact::core::normal::{NormalLoad, NormalSettings};
use railcontact::core::problem::{ContactProblem, Creepages, Friction, Kinematics};
use railcontact::core::solve::ContactSolver;
use railcontact::core::steady::TangentialOperator;

fn steel() -> CombinedMaterial {
    CombinedMaterial::identical(Material {
        shear_modulus_pa: 81e9,
        poisson_ratio: 0.3,
    })
    .unwrap()
}

/// Paper Case 1 (R_yr = 10 mm, R_yw = -10.1 mm, R_xw = 500 mm).
const CASE_1: (f64, f64, f64) = (0.010, -0.0101, 0.5);

/// Case 1 at `force` on an nx x ns grid sized from Hertz (3.2 a by 2.6 b,
/// at most +-75°), or with element size `d` when given.
fn case_1(force: f64, n: Option<(usize, usize)>, d: Option<f64>) -> ConformalGeometry {
    let (rr, rw, rx) = CASE_1;
    let (h, _) = conformal_hertz(rr, rw, rx, &steel(), force, false).unwrap();
    let r = 0.5 * (rr + rw.abs());
    let (wx, ws) = (
        3.2 * h.semi_axis_x_m,
        (2.6 * h.semi_axis_y_m).min(2.0 * 75f64.to_radians() * r),
    );
    let grid = match (n, d) {
        (Some((nx, ns)), _) => Grid::centered(nx, ns, wx, ws).unwrap(),
        (None, Some(d)) => {
            let (nx, ns) = ((wx / d).ceil() as usize, (ws / d).ceil() as usize);
            Grid::centered(nx, ns, nx as f64 * d, ns as f64 * d).unwrap()
        }
        _ => unreachable!(),
    };
    ConformalGeometry::new(&Circle::rail(rr), &Circle::wheel(rw), rx, grid).unwrap()
}

fn matvecs(c: &mut Criterion) {
    let mut g = c.benchmark_group("conformal_matvec");
    for n in [32, 64, 128] {
        let plan = Arc::new(ConvolutionPlan::new(n, n));
        let set = Arc::new(KernelSet::new(
            plan,
            HalfSpaceInfluence::new(1e-4, 1e-4, &steel()),
            KernelKind::Displacement,
        ));
        let delta: Vec<f64> = (0..n).map(|l| -0.8 + 1.6 * l as f64 / n as f64).collect();
        let mut op = ConformalOperator::new(set.clone(), InfluenceModel::Blanco, &delta);
        let mut ws = set.workspace();
        let p: Vec<f64> = (0..n * n).map(|i| (i % 7) as f64).collect();
        let (mut ux, mut uy, mut un) = (vec![0.0; n * n], vec![0.0; n * n], vec![0.0; n * n]);
        g.bench_with_input(BenchmarkId::new("planar_full", n), &n, |b, _| {
            b.iter(|| {
                set.apply(
                    &mut ws,
                    &[(Component::X, &p), (Component::Y, &p), (Component::N, &p)],
                    &mut [
                        (Component::X, &mut ux),
                        (Component::Y, &mut uy),
                        (Component::N, &mut un),
                    ],
                )
            })
        });
        g.bench_with_input(BenchmarkId::new("blanco_full", n), &n, |b, _| {
            b.iter(|| op.apply(&p, &p, &p, &mut ux, &mut uy, &mut un))
        });
        g.bench_with_input(BenchmarkId::new("blanco_normal", n), &n, |b, _| {
            b.iter(|| op.apply_normal(&p, &mut un))
        });
        g.bench_with_input(BenchmarkId::new("blanco_tangential", n), &n, |b, _| {
            b.iter(|| op.apply_tangential(&p, &p, &mut ux, &mut uy))
        });
    }
    g.finish();
}

fn solves(c: &mut Criterion) {
    let mut g = c.benchmark_group("conformal_solve");
    g.sample_size(10);
    let cache = KernelCache::default();
    let mat = steel();
    let creep = 0.86e-3;
    // cect steady rolling on 60 x 60 against the planar exact solve of the
    // flattened quadratic gap on the same grid (both cold starts, kernels cached).
    let geo = case_1(80e3, Some((60, 60)), None);
    let roll = ConformalKinematics::SteadyRolling {
        normal_force_n: 80e3,
        creepages: ConformalCreepages {
            creepage_long: creep,
            ..Default::default()
        },
    };
    let settings = ConformalSettings::default();
    // Buffers kept from one solve to the next, as the planar solver below
    // keeps its own.
    let mut workspace = FrictionalWorkspace::default();
    let mut rolling = |geo: &ConformalGeometry| {
        solve_frictional(
            &mut workspace,
            geo,
            &mat,
            0.3,
            InfluenceModel::Blanco,
            &roll,
            &settings,
            &cache,
        )
        .unwrap()
    };

    g.bench_function("cect_steady_rolling_60x60", |b| {
        b.iter(|| black_box(rolling(&geo)))
    });
    let (rr, rw, rx) = CASE_1;
    let planar = ContactProblem {
        material: mat,
        friction: Friction::coulomb(0.3),
        gap_m: ContactProblem::quadratic_gap(&geo.grid, 0.5 / rx, 0.5 * (1.0 / rr + 1.0 / rw)),
        grid: geo.grid,
        load: NormalLoad::NormalForce(80e3),
        kinematics: Kinematics::SteadyRolling(Creepages {
            creepage_long: creep,
            ..Default::default()
        }),
        settings: Default::default(),
        rolling_direction_rad: 0.0,
        extra_rigid_slip: None,
        numerical_influence: None,
    };
    let mut solver = ContactSolver::new(&planar, &cache);
    // The target is a ratio, and this machine's speed changes by up to
    // 1.7x between minutes: the two solves alternated, the ratio of the
    // medians of 21 pairs (after one of each to warm the caches).
    {
        let mut planar_solve = || {
            solver.reset();
            black_box(solver.solve(&planar).unwrap());
        };
        black_box(rolling(&geo));
        planar_solve();
        let (mut tc, mut tp) = (Vec::new(), Vec::new());
        for _ in 0..21 {
            let t = Instant::now();
            black_box(rolling(&geo));
            tc.push(t.elapsed().as_secs_f64());
            let t = Instant::now();
            planar_solve();
            tp.push(t.elapsed().as_secs_f64());
        }
        let median = |v: &mut Vec<f64>| {
            v.sort_by(f64::total_cmp);
            v[v.len() / 2]
        };
        let (mc, mp) = (median(&mut tc), median(&mut tp));
        eprintln!(
            "ratio cect / planar steady rolling 60x60 (21 alternated pairs): {:.2} ({:.2} ms / {:.2} ms, medians)",
            mc / mp,
            mc * 1e3,
            mp * 1e3
        );
    }
    g.bench_function("planar_exact_steady_rolling_60x60", |b| {
        b.iter(|| {
            solver.reset();
            black_box(solver.solve(&planar).unwrap())
        })
    });
    // Case 1 at 80 kN on a 0.2 mm grid.
    let fine = case_1(80e3, None, Some(2e-4));
    let id = format!("{}x{}", fine.grid.nx, fine.grid.ny);
    g.bench_with_input(
        BenchmarkId::new("case1_80kN_frictionless", &id),
        &0,
        |b, _| {
            b.iter(|| {
                black_box(
                    solve_frictionless(
                        &fine,
                        &mat,
                        InfluenceModel::Blanco,
                        NormalLoad::NormalForce(80e3),
                        &NormalSettings::default(),
                        &cache,
                    )
                    .unwrap(),
                )
            })
        },
    );
    g.bench_with_input(
        BenchmarkId::new("case1_80kN_steady_rolling", &id),
        &0,
        |b, _| b.iter(|| black_box(rolling(&fine))),
    );
    g.finish();
}

criterion_group!(benches, matvecs, solves);
criterion_main!(benches);
