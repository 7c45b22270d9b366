//! Criterion benchmarks of one wheelset time step (both wheels, every patch)
//! at the Manchester benchmark settings (A-2.2: S1002/UIC60, 10 kN per
//! wheel, 0.2 mm elements): tread contact (2 mm), two-point contact (5 mm),
//! flange contact (6.5 mm, 10 mm), with the planar exact model and with
//! Hertz+FASTSIM, direct and with contact tables; and a co-simulation's
//! exact steps along a smooth path, with and without the tangential
//! tractions carried from step to step; and what the flash temperatures
//! of the exact patches add to a step; and what a roller rig and a rail
//! varying along the track (rail slices) cost against a plain track. Kernels
//! are cached (a long-running service's steady state). See benches/README.md; run with `cargo bench --bench wheelrail`.

use std::hint::black_box;

use criterion::measurement::WallTime;
use criterion::{criterion_group, criterion_main, BenchmarkGroup, BenchmarkId, Criterion};

use railcontact::core::cache::KernelCache;
use railcontact::core::temperature::ThermalBody;
use railcontact::wheelrail::builtin::{load_test_input, mbench_a22_input, mbench_pair};
use railcontact::wheelrail::builtin::{profile, MBENCH_TRACK, MBENCH_WHEELSET};
use railcontact::wheelrail::temperature::patch_temperatures;
use railcontact::wheelrail::{
    load_slices, solve_wheelset, solve_wheelset_tabulated, solve_wheelset_tabulated_warm,
    solve_wheelset_warm, ContactTable, LoadOptions, RailMotion, RailPlacement, SearchScratch, Side,
    SplineOptions, TableSettings, TrackData, WarmStart, WheelLoad, WheelRailInput, WheelRailModel,
    WheelRailPair, WheelRailSolution, WheelRailThermal, WheelsetVelocity,
};

fn pair() -> WheelRailPair {
    mbench_pair().unwrap()
}

/// Shift [mm], roll [rad] and wheel rotation [rad/s] of CONTACT's
/// mbench_a22 inputs (docs/data/mbench_a22_contact.csv).
const SHIFTS: [(f64, f64, f64); 4] = [
    (2.0, -0.00011280, -4.34591970),
    (5.0, -0.00035540, -4.33536370),
    (6.5, -0.00437600, -4.27488340),
    (10.0, -0.01126431, -4.24363750),
];

fn wheelset_step(c: &mut Criterion) {
    let pair = pair();
    let cache = KernelCache::default();
    let mut scratch = SearchScratch::default();
    for (name, model) in [
        ("wheelset_step_exact", WheelRailModel::Exact),
        ("wheelset_step_hertz_fastsim", WheelRailModel::HertzFastsim),
        ("wheelset_step_hertz_polach", WheelRailModel::HertzPolach),
        (
            "wheelset_step_hertz_fastsim_elliptic",
            WheelRailModel::HertzFastsimElliptic,
        ),
        ("wheelset_step_hertz_strip", WheelRailModel::HertzStrip),
        (
            "wheelset_step_hertz_fastsim_modified",
            WheelRailModel::HertzFastsimModified,
        ),
        (
            "wheelset_step_kik_piotrowski",
            WheelRailModel::KikPiotrowski,
        ),
        ("wheelset_step_cect", WheelRailModel::Cect),
    ] {
        let mut g = c.benchmark_group(name);
        g.sample_size(20);
        for &(y, roll, pitch) in &SHIFTS {
            let inp = mbench_a22_input(y, Some(roll), Some(pitch), model);
            // Where the time goes (printed once per case).
            let sol = solve_wheelset(&pair, &inp, &cache, &mut scratch)
                .unwrap_or_else(|e| panic!("{name} y = {y} mm: {e}"));
            let t = sol.timing;
            eprintln!(
                "{name} y = {y} mm: search {:.2} ms, geometry {:.2} ms, solve {:.2} ms, patches {:?}",
                t.search_s * 1e3,
                t.geometry_s * 1e3,
                t.solve_s * 1e3,
                sol.wheels
                    .iter()
                    .map(|w| w.patches.iter().map(|p| p.grid).collect::<Vec<_>>())
                    .collect::<Vec<_>>()
            );
            g.bench_with_input(BenchmarkId::from_parameter(y), &inp, |b, inp| {
                b.iter(|| black_box(solve_wheelset(&pair, inp, &cache, &mut scratch).unwrap()))
            });
        }
        g.finish();
    }
    // What the flash temperatures add to an exact step: every patch's
    // temperatures from its solved fields (rail steel at 20 °C, wheel at
    // 60 °C), the part of a step with `temperature` that one without it
    // does not run.
    let thermal = WheelRailThermal {
        rail: ThermalBody::steel(293.15),
        wheel: ThermalBody::steel(333.15),
    };
    let mut g = c.benchmark_group("wheelset_temperatures_exact");
    g.sample_size(20);
    for &(y, roll, pitch) in &SHIFTS {
        let inp = mbench_a22_input(y, Some(roll), Some(pitch), WheelRailModel::Exact);
        let sol = solve_wheelset(&pair, &inp, &cache, &mut scratch).unwrap();
        let patches: Vec<_> = sol.wheels.iter().flat_map(|w| &w.patches).collect();
        g.bench_with_input(BenchmarkId::from_parameter(y), &patches, |b, patches| {
            b.iter(|| {
                for p in patches.iter() {
                    black_box(patch_temperatures(p, &thermal).unwrap());
                }
            })
        });
    }
    g.finish();
    // A co-simulation's steps with the exact model: the lateral shift along
    // a smooth path (2 mm + 0.05 mm sin(2 pi k / 100), tread contact), each
    // step from the previous one's warm start (roll, load, and the
    // tangential tractions), against the same without the tractions.
    let path: Vec<_> = (0..100)
        .map(|k| {
            let a = 2.0 * std::f64::consts::PI * k as f64 / 100.0;
            let (_, roll, pitch) = SHIFTS[0];
            mbench_a22_input(
                2.0 + 0.05 * a.sin(),
                Some(roll),
                Some(pitch),
                WheelRailModel::Exact,
            )
        })
        .collect();
    let mut g = c.benchmark_group("wheelset_path_exact");
    g.sample_size(20);
    for carry in [true, false] {
        let id = if carry {
            "tractions_carried"
        } else {
            "tractions_dropped"
        };
        let reset = |w: &mut WarmStart| {
            if !carry {
                w.tractions = Default::default();
            }
        };
        bench_path(&mut g, id, &path, reset, |input, warm| {
            solve_wheelset_warm(&pair, input, &cache, &mut scratch, warm).unwrap()
        });
    }
    g.finish();
    // The fast path with contact tables (built once, as the service does at
    // pair registration).
    let table = ContactTable::build(&pair, &TableSettings::default()).unwrap();
    eprintln!("contact table built in {:.2} s", table.build_time_s());
    let mut g = c.benchmark_group("wheelset_step_hertz_fastsim_tabulated");
    g.sample_size(20);
    for &(y, roll, pitch) in &SHIFTS {
        let inp = mbench_a22_input(y, Some(roll), Some(pitch), WheelRailModel::HertzFastsim);
        g.bench_with_input(BenchmarkId::from_parameter(y), &inp, |b, inp| {
            b.iter(|| {
                black_box(solve_wheelset_tabulated(&table, inp, &cache, &mut scratch).unwrap())
            })
        });
    }
    g.finish();
    // A co-simulation on the tables: the load test's wheelset motion
    // (`railcontact loadtest --mix wheelrail:hertz_fastsim_table=1`:
    // lateral 4 mm and yaw 2 mrad at 2 Hz, 20 m/s, 50 kN per wheel
    // varying by 2 kN at 6 Hz, roll found), steps of 1 ms, each from the
    // last one's warm start (as a session does); and the same steps cold.
    let path: Vec<_> = (0..500)
        .map(|k| load_test_input(k, 4e-3, WheelRailModel::HertzFastsim))
        .collect();
    bench_warm_and_cold(
        c,
        "wheelset_path_hertz_fastsim_tabulated",
        50,
        &path,
        |input, warm| {
            solve_wheelset_tabulated_warm(&table, input, &cache, &mut scratch, warm).unwrap()
        },
    );
    // The same motion with the exact model on the direct search, as a
    // `wheelrail:exact` session steps (`railcontact loadtest --mix
    // wheelrail:exact=1`).
    let exact: Vec<_> = (0..300)
        .map(|k| load_test_input(k, 4e-3, WheelRailModel::Exact))
        .collect();
    bench_warm_and_cold(
        c,
        "wheelset_path_exact_load_test",
        20,
        &exact,
        |input, warm| solve_wheelset_warm(&pair, input, &cache, &mut scratch, warm).unwrap(),
    );
    // The same warm steps with the two wheels solved at once, on two
    // threads (`SearchScratch::parallel_wheels`, as the service does when
    // a second worker is free).
    let mut two = SearchScratch::default();
    two.parallel_wheels = true;
    let mut g = c.benchmark_group("wheelset_path_exact_load_test_two_threads");
    g.sample_size(20);
    bench_path(
        &mut g,
        "warm",
        &exact,
        |_| {},
        |input, warm| solve_wheelset_warm(&pair, input, &cache, &mut two, warm).unwrap(),
    );
    g.finish();
    // The same warm steps on one thread, each wheel on the coarsest grid
    // whose forces its checks find within half of 0.5 % of the load of
    // those on 0.2 mm (`force_tolerance_of_wheel_load`).
    let sized: Vec<_> = exact
        .iter()
        .map(|input| {
            let mut input = input.clone();
            input.settings.force_tolerance_of_wheel_load = Some(5e-3);
            input
        })
        .collect();
    let mut own = SearchScratch::default();
    let mut g = c.benchmark_group("wheelset_path_exact_load_test_sized_for_forces");
    g.sample_size(20);
    bench_path(
        &mut g,
        "warm",
        &sized,
        |_| {},
        |input, warm| solve_wheelset_warm(&pair, input, &cache, &mut own, warm).unwrap(),
    );
    g.finish();
}

/// A group `name` of two benches along `path`: `warm`, each step from the
/// last one's warm start (as a session does), and `cold`, each step from a
/// fresh one.
fn bench_warm_and_cold(
    c: &mut Criterion,
    name: &str,
    samples: usize,
    path: &[WheelRailInput],
    mut solve: impl FnMut(&WheelRailInput, &mut WarmStart) -> WheelRailSolution,
) {
    let mut g = c.benchmark_group(name);
    g.sample_size(samples);
    for warm_start in [true, false] {
        let id = if warm_start { "warm" } else { "cold" };
        let reset = |w: &mut WarmStart| {
            if !warm_start {
                *w = WarmStart::default();
            }
        };
        bench_path(&mut g, id, path, reset, &mut solve);
    }
    g.finish();
}

/// Benchmarks `solve` stepping along `path` (one step an iteration, round
/// and round), each step from the warm start the last one left, after
/// `reset` has cleared what the case leaves out. First prints where the
/// time of a step goes (the solution's timing, mean over one pass).
fn bench_path(
    g: &mut BenchmarkGroup<'_, WallTime>,
    id: &str,
    path: &[WheelRailInput],
    reset: impl Fn(&mut WarmStart),
    mut solve: impl FnMut(&WheelRailInput, &mut WarmStart) -> WheelRailSolution,
) {
    let mut warm = WarmStart::default();
    let mut split = [0.0; 5];
    let mut total = 0.0;
    for input in path {
        reset(&mut warm);
        let t0 = std::time::Instant::now();
        let t = solve(input, &mut warm).timing;
        total += t0.elapsed().as_secs_f64() * 1e6 / path.len() as f64;
        let parts = [
            t.search_s,
            t.geometry_s,
            t.solve_s,
            t.normal_s,
            t.tangential_s,
        ];
        for (s, v) in split.iter_mut().zip(parts) {
            *s += v * 1e6 / path.len() as f64;
        }
    }
    eprintln!(
        "{id}: per step {total:.1} us: search {:.1} us, geometry {:.1} us, solve {:.1} us \
         (exact patches: normal {:.1} us, tangential and the rest {:.1} us)",
        split[0], split[1], split[2], split[3], split[4]
    );
    let mut warm = WarmStart::default();
    let mut k = 0;
    g.bench_function(id, |b| {
        b.iter(|| {
            k += 1;
            reset(&mut warm);
            black_box(solve(&path[k % path.len()], &mut warm))
        })
    });
}

/// A roller rig and a rail varying along the track, each beside the plain
/// track it extends (exact model, kernels cached):
/// - `track_a22_2mm` and `rollers_a22_2mm`: at 2 mm (both wheels,
///   10 kN each, 2 m/s) on its track, and the same wheelset standing on
///   rollers of 0.6 m radius whose surfaces move at 2 m/s;
/// - `crossing_slices_s239` and `crossing_constant_s239`: the S1002 wheel
///   (right wheel, 10 kN) on the UK crossing nose at S = 239 mm, given as
///   rail slices (`uk_crossing_nose.slcs`: each element's rail height
///   taken at its own position along the track), and on the slice at S
///   alone as a prismatic rail (CONTACT's `mbench_locus.inp` case, as
///   `crates/cntc/bench/slices_cases.py` runs it).
fn variable_rail_and_roller(c: &mut Criterion) {
    let cache = KernelCache::default();
    let mut scratch = SearchScratch::default();
    let (_, roll, pitch) = SHIFTS[0];
    let track = mbench_a22_input(2.0, Some(roll), Some(pitch), WheelRailModel::Exact);
    let track_pair = pair();
    let rail = profile("MBench_UIC60_v3.prr", &LoadOptions::default())
        .expect("built in")
        .unwrap();
    let wheel = profile("MBench_S1002_v3.prw", &LoadOptions::default())
        .expect("built in")
        .unwrap();
    let roller_pair = WheelRailPair::new(
        [&rail, &rail],
        [&wheel, &wheel],
        TrackData {
            roller_radius_m: Some(0.6),
            ..MBENCH_TRACK
        },
        MBENCH_WHEELSET,
        &SplineOptions::default(),
    )
    .unwrap();
    let mut rollers = track.clone();
    rollers.velocity.forward_m_per_s = 0.0;
    rollers.rail_motion = [RailMotion {
        roller_rad_per_s: 2.0 / 0.6,
        ..RailMotion::default()
    }; 2];
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/crates/solver/profiles/uk_crossing_nose.slcs"
    );
    let slices = load_slices(path, &LoadOptions::default()).unwrap();
    let nose = slices.profile_at(0.239).unwrap();
    let crossing_pair = WheelRailPair::new(
        [&nose, &nose],
        [&wheel, &wheel],
        TrackData {
            placement: RailPlacement::Origin {
                q_m: 0.75,
                z_m: 0.0,
            },
            ..MBENCH_TRACK
        },
        MBENCH_WHEELSET,
        &SplineOptions::smoothing(0.0),
    )
    .unwrap();
    let mut constant = mbench_a22_input(0.81, Some(0.0), None, WheelRailModel::Exact);
    constant.position.yaw_rad = 0.0;
    constant.position.track_s_m = 0.239;
    constant.sides = vec![Side::Right];
    constant.load = WheelLoad::VerticalForce(1e4);
    constant.velocity = WheelsetVelocity {
        pitch_rad_per_s: Some(-4.34811810),
        ..WheelsetVelocity::rolling(2.0)
    };
    let mut varying = constant.clone();
    varying.rail_slices[Side::Right.index()] = Some(slices);
    let mut g = c.benchmark_group("wheelset_step_roller_and_slices");
    g.sample_size(20);
    for (id, pair, input) in [
        ("track_a22_2mm", &track_pair, &track),
        ("rollers_a22_2mm", &roller_pair, &rollers),
        ("crossing_constant_s239", &crossing_pair, &constant),
        ("crossing_slices_s239", &crossing_pair, &varying),
    ] {
        let sol = solve_wheelset(pair, input, &cache, &mut scratch)
            .unwrap_or_else(|e| panic!("{id}: {e}"));
        let t = sol.timing;
        eprintln!(
            "{id}: patches {:?}, normal forces {:?} N, load iterations {:?}; search {:.2} ms, \
             geometry {:.2} ms, normal {:.2} ms, tangential and the rest {:.2} ms",
            sol.wheels
                .iter()
                .map(|w| w.patches.iter().map(|p| p.grid).collect::<Vec<_>>())
                .collect::<Vec<_>>(),
            sol.wheels
                .iter()
                .map(|w| w
                    .patches
                    .iter()
                    .map(|p| p.normal_force_n.round())
                    .collect::<Vec<_>>())
                .collect::<Vec<_>>(),
            sol.wheels
                .iter()
                .map(|w| w.load_iterations)
                .collect::<Vec<_>>(),
            t.search_s * 1e3,
            t.geometry_s * 1e3,
            t.normal_s * 1e3,
            t.tangential_s * 1e3,
        );
        g.bench_function(id, |b| {
            b.iter(|| black_box(solve_wheelset(pair, input, &cache, &mut scratch).unwrap()))
        });
    }
    g.finish();
}

criterion_group!(benches, wheelset_step, variable_rail_and_roller);
criterion_main!(benches);
