//! Large grids: CONTACT's performance cases of a wheel on a rail
//! (github.com/eve70a/CONTACT, `perfc_test/norm_problm_{1,2,4,8}p.inp`,
//! `tang_problm_{1,2,4,8}s.inp`, `tang_problm_{1,2,4}c.inp`) from 71 x 81
//! to 575 x 647 elements, solved cold, with the operator products, the time
//! of one product and the growth against N log N. See benches/README.md.
//!
//! `cargo bench --bench perfc -- [normal] [shift] [steady] [steady_nested]
//! [--levels 0,1,2,3] [--runs N]`: the problems (default all four;
//! `steady_nested` is steady rolling started as the command line and the
//! service start it, [`ContactSolver::start_nested`], the coarse solves in
//! its time and their kernels built beforehand too), the grids (0: 71 x 81 of
//! 0.1 mm, 1: 143 x 163 of 0.05 mm, 2: 287 x 323 of 0.025 mm, 3: 575 x 647
//! of 0.0125 mm; default all) and the runs per case whose median is printed
//! (default 3). The kernels are built once per grid, outside the timing;
//! the runs of one grid alternate between its problems.

use std::sync::Arc;
use std::time::Instant;

use railcontact::core::cache::KernelCache;
use railcontact::core::fft::{ConvolutionPlan, KernelSet, Precision};
use railcontact::core::influence::{Component, HalfSpaceInfluence, KernelKind};
use railcontact::core::problem::{ContactProblem, Creepages, Kinematics};
use railcontact::core::solution::{ContactSolution, ElementState};
use railcontact::core::solve::ContactSolver;

#[path = "../crates/solver/tests/validation/perfc_case.rs"]
mod perfc_case;

use perfc_case::{case, heights_m, shift_step, GRIDS};

/// `perfc_test/get_times.ref_out` (CONTACT version 1274, 2016, one thread),
/// per grid: the normal problem's "ncon", "ItCG", "tot.wall" [s]; the
/// shift's "nslp", "ItGS", "wall.tang" [s]; steady rolling's "nslp",
/// "ItGS", "wall.tang" [s] (not run at 575 x 647).
const CONTACT: [[(usize, usize, f64); 3]; 4] = [
    [(3148, 19, 0.1), (1730, 51, 0.3), (1872, 56, 4.8)],
    [(12902, 22, 0.5), (7243, 71, 2.1), (7735, 90, 97.0)],
    [(50796, 27, 2.7), (28260, 154, 22.6), (30181, 151, 2210.0)],
    [(200980, 31, 17.6), (111191, 190, 167.0), (0, 0, f64::NAN)],
];

#[derive(Clone, Copy, PartialEq)]
enum Kind {
    Normal,
    Shift,
    Steady,
    SteadyNested,
}

impl Kind {
    fn name(self) -> &'static str {
        match self {
            Kind::Normal => "normal",
            Kind::Shift => "shift",
            Kind::Steady => "steady",
            Kind::SteadyNested => "steady_nested",
        }
    }

    /// Its column in [`CONTACT`].
    fn column(self) -> usize {
        (self as usize).min(2)
    }

    /// The shift of `tang_problm_*s.inp` and the steady rolling of
    /// `tang_problm_*c.inp`.
    fn kinematics(self) -> Kinematics {
        match self {
            Kind::Normal => Kinematics::Frictionless,
            Kind::Shift => Kinematics::Transient(vec![shift_step()]),
            // CKSI = 0.0005, CETA = 0, CPHI = 0.0003 /mm.
            Kind::Steady | Kind::SteadyNested => Kinematics::SteadyRolling(Creepages {
                creepage_long: 0.0005,
                creepage_lat: 0.0,
                spin_per_m: 0.3,
            }),
        }
    }
}

fn problem(level: usize, heights: &[f64], kind: Kind) -> ContactProblem {
    case(level, heights, kind.kinematics())
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Medians \[s\] of one normal product, one tangential product in `f64`
/// and one in `f32` on the grid of `p`.
fn product_times(p: &ContactProblem, runs: usize) -> [f64; 3] {
    let (nx, ny) = (p.grid.nx, p.grid.ny);
    let plan = Arc::new(ConvolutionPlan::new(nx, ny));
    let influence = HalfSpaceInfluence::new(p.grid.dx_m, p.grid.dy_m, &p.material);
    let set = KernelSet::new(plan, influence, KernelKind::Displacement);
    let mut ws = set.workspace();
    let q: Vec<f64> = (0..nx * ny).map(|i| (i % 7) as f64).collect();
    let (mut ux, mut uy) = (vec![0.0; nx * ny], vec![0.0; nx * ny]);
    let mut t = [vec![], vec![], vec![]];
    for _ in 0..runs.max(5) {
        let a = Instant::now();
        set.apply(
            &mut ws,
            &[(Component::N, &q)],
            &mut [(Component::N, &mut ux)],
        );
        let b = Instant::now();
        let tangential = [(Component::X, &q[..]), (Component::Y, &q[..])];
        set.apply(
            &mut ws,
            &tangential,
            &mut [(Component::X, &mut ux), (Component::Y, &mut uy)],
        );
        let c = Instant::now();
        set.apply_with(
            Precision::Single,
            &mut ws,
            &tangential,
            &mut [(Component::X, &mut ux), (Component::Y, &mut uy)],
        );
        let d = Instant::now();
        t[0].push((b - a).as_secs_f64());
        t[1].push((c - b).as_secs_f64());
        t[2].push((d - c).as_secs_f64());
    }
    t.map(|mut v| median(&mut v))
}

/// The runs of one case.
struct Runs {
    time_s: Vec<f64>,
    normal_time_s: Vec<f64>,
    last: ContactSolution,
}

struct Options {
    kinds: Vec<Kind>,
    levels: Vec<usize>,
    runs: usize,
}

fn options() -> Options {
    let mut o = Options {
        kinds: vec![],
        levels: (0..GRIDS.len()).collect(),
        runs: 3,
    };
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "normal" => o.kinds.push(Kind::Normal),
            "shift" => o.kinds.push(Kind::Shift),
            "steady" => o.kinds.push(Kind::Steady),
            "steady_nested" => o.kinds.push(Kind::SteadyNested),
            "--levels" => {
                o.levels = args
                    .next()
                    .expect("--levels 0,1,2,3")
                    .split(',')
                    .map(|v| v.parse().expect("a grid level, 0 to 3"))
                    .filter(|&l: &usize| l < GRIDS.len())
                    .collect()
            }
            "--runs" => o.runs = args.next().and_then(|v| v.parse().ok()).expect("--runs N"),
            // `cargo bench` passes --bench.
            _ => {}
        }
    }
    if o.kinds.is_empty() {
        o.kinds = vec![Kind::Normal, Kind::Shift, Kind::Steady, Kind::SteadyNested];
    }
    o
}

fn main() {
    let o = options();
    let heights = heights_m();
    println!(
        "| problem | grid | contact / slip elements (CONTACT) | normal iterations (CONTACT) | Newton steps (CONTACT GS) | products | one product: normal / tangential f64 / f32 [ms] | solve [s] (normal part) | CONTACT 2016 [s] | solve / (products x product) | growth / N log N growth |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    let mut first: Vec<Option<(f64, f64)>> = vec![None; o.kinds.len()];
    for &level in &o.levels {
        let cache = KernelCache::default();
        let problems: Vec<ContactProblem> = o
            .kinds
            .iter()
            .map(|&k| problem(level, &heights, k))
            .collect();
        for (p, &kind) in problems.iter().zip(&o.kinds) {
            let mut s = ContactSolver::new(p, &cache);
            if kind == Kind::SteadyNested {
                s.start_nested(p, &cache).unwrap();
            }
        }
        let [t_normal, t_tang, t_single] = product_times(&problems[0], o.runs);
        let mut runs: Vec<Option<Runs>> = o.kinds.iter().map(|_| None).collect();
        for _ in 0..o.runs.max(1) {
            for (k, p) in problems.iter().enumerate() {
                let t0 = Instant::now();
                let mut solver = ContactSolver::new(p, &cache);
                if o.kinds[k] == Kind::SteadyNested {
                    solver.start_nested(p, &cache).unwrap();
                }
                let last = solver.solve(p).unwrap().pop().unwrap();
                let dt = t0.elapsed().as_secs_f64();
                let r = runs[k].get_or_insert_with(|| Runs {
                    time_s: vec![],
                    normal_time_s: vec![],
                    last: last.clone(),
                });
                r.time_s.push(dt);
                r.normal_time_s.push(last.info.normal_time_s);
                r.last = last;
            }
        }
        let (nx, ny, _) = GRIDS[level];
        let n = (nx * ny) as f64;
        // The products of the normal solve alone (the same in every problem
        // of these identical bodies).
        let normal_products = o
            .kinds
            .iter()
            .position(|&k| k == Kind::Normal)
            .and_then(|k| runs[k].as_ref())
            .map(|r| r.last.info.matvecs);
        for (k, &kind) in o.kinds.iter().enumerate() {
            let r = runs[k].as_mut().unwrap();
            let info = r.last.info;
            let fields = &r.last.fields;
            let contact = fields.pressure_pa.iter().filter(|&&p| p > 0.0).count();
            let slip = fields
                .state
                .iter()
                .filter(|&&s| s == ElementState::Slip)
                .count();
            let time = median(&mut r.time_s);
            let normal_time = median(&mut r.normal_time_s);
            // The products at their time: the normal solve's at the normal
            // product's, the rest at the tangential f32 product's (GMRES's
            // products are single precision, the residuals' f64: the f32
            // time gives the larger ratio).
            let expected = match (kind, normal_products) {
                (Kind::Normal, _) => info.matvecs as f64 * t_normal,
                (_, Some(np)) => np as f64 * t_normal + (info.matvecs - np) as f64 * t_single,
                (_, None) => f64::NAN,
            };
            let (c_count, c_its, c_time) = CONTACT[level][kind.column()];
            let counts = match kind {
                Kind::Normal => format!("{contact} ({c_count})"),
                _ => format!("{contact} / {slip} ({c_count})"),
            };
            let newton = match kind {
                Kind::Normal => "0".to_string(),
                _ => format!("{} ({c_its})", info.tangential_iterations),
            };
            let nlogn = n * n.ln();
            let growth = match first[k] {
                None => {
                    first[k] = Some((time, nlogn));
                    "1".to_string()
                }
                Some((t0, g0)) => format!("{:.2}", (time / t0) / (nlogn / g0)),
            };
            println!(
                "| {} | {nx} x {ny} | {counts} | {} ({}) | {newton} | {} | {:.3} / {:.3} / {:.3} | {:.3} ({:.3}) | {c_time} | {:.2} | {growth} |",
                kind.name(),
                info.normal_iterations,
                CONTACT[level][0].1,
                info.matvecs,
                t_normal * 1e3,
                t_tang * 1e3,
                t_single * 1e3,
                time,
                normal_time,
                time / expected,
            );
        }
    }
}
