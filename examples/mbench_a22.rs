//! The Manchester Contact Benchmark, case, against CONTACT's reference
//! output: `cargo run --release --example mbench_a22 [exact|hertz_fastsim|hertz_polach|hertz_fastsim_elliptic|hertz_strip|hertz_fastsim_modified|kik_piotrowski]`.
//!
//! Reads `docs/data/mbench_a22_contact.csv` (CONTACT's results, with their
//! source), solves every shift 0..10 mm with the same roll and wheel
//! rotation, and prints markdown tables comparing contact position, contact
//! angle, forces and creepages per wheel, the largest differences, and the
//! time per wheelset step. `docs/manchester_a22.md` shows the output.

use std::time::Instant;

use railcontact::core::cache::KernelCache;
use railcontact::wheelrail::builtin::{mbench_a22_input, mbench_pair};
use railcontact::wheelrail::{solve_wheelset, SearchScratch, Side, WheelRailInput, WheelRailModel};

/// One CONTACT row.
struct Row {
    y_mm: f64,
    side: Side,
    roll: f64,
    pitch: f64,
    v: [f64; 10],
}

fn read_reference() -> Vec<Row> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/docs/data/mbench_a22_contact.csv"
    );
    let text = std::fs::read_to_string(path).expect("docs/data/mbench_a22_contact.csv");
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("y_mm"))
        .map(|l| {
            let c: Vec<&str> = l.split(',').collect();
            let num = |i: usize| c[i].parse::<f64>().expect("number");
            Row {
                y_mm: num(0),
                side: if c[1] == "right" {
                    Side::Right
                } else {
                    Side::Left
                },
                roll: num(2),
                pitch: num(3),
                // rail_y, delta, FN, FX, FS, FY, xi, eta, phi, pmax
                v: [
                    num(4),
                    num(5),
                    num(6),
                    num(7),
                    num(8),
                    num(9),
                    num(10),
                    num(11),
                    num(12),
                    num(13),
                ],
            }
        })
        .collect()
}

fn main() {
    let name = std::env::args().nth(1).unwrap_or_else(|| "exact".into());
    let model = match WheelRailModel::from_name(&name) {
        Some(m) if m == WheelRailModel::Exact || m.is_fast() => m,
        _ => {
            eprintln!(
                "unknown model {name}: use exact, hertz_fastsim, hertz_polach, \
                 hertz_fastsim_elliptic, hertz_strip, hertz_fastsim_modified or kik_piotrowski"
            );
            std::process::exit(2);
        }
    };
    let pair = mbench_pair().unwrap();
    let reference = read_reference();
    let cache = KernelCache::default();
    let mut scratch = SearchScratch::default();
    let mut times = Vec::new();
    let mut worst = [0.0f64; 4];
    for side in Side::BOTH {
        // CONTACT reports lateral quantities and the right wheel's contact
        // angle in the track frame; ours are in each side's own frame.
        let (m_lat, m_delta) = match side {
            Side::Right => (1.0, -1.0),
            Side::Left => (-1.0, 1.0),
        };
        println!("\n### {} wheel (`{}`)\n", side.name(), model.name());
        println!(
            "| y mm | n | rail y mm (C) | delta rad (C) | FN N (C) | FX N (C) | FS N (C) | FY track N (C) | xi (C) | eta (C) | phi 1/mm (C) | pmax MPa (C) |"
        );
        println!("|---|---|---|---|---|---|---|---|---|---|---|---|");
        for r in reference.iter().filter(|r| r.side == side) {
            let input = WheelRailInput {
                sides: vec![side],
                ..mbench_a22_input(r.y_mm, Some(r.roll), Some(r.pitch), model)
            };
            let t = Instant::now();
            let sol = solve_wheelset(&pair, &input, &cache, &mut scratch).unwrap();
            times.push(t.elapsed().as_secs_f64());
            let w = &sol.wheels[0];
            let n = w.patches.len();
            // Patch values: the sum of forces; position and creepages of the
            // patch carrying most of the load.
            let main = w
                .patches
                .iter()
                .max_by(|a, b| a.normal_force_n.total_cmp(&b.normal_force_n))
                .unwrap();
            let fsum = |f: &dyn Fn(&railcontact::wheelrail::PatchResult) -> f64| {
                w.patches.iter().map(f).sum::<f64>()
            };
            let fnn = fsum(&|p| p.normal_force_n);
            let fx = fsum(&|p| p.fx_n);
            let fs = m_lat * fsum(&|p| p.fs_n);
            let fy = w.force_track_n[1];
            let v = &r.v;
            println!(
                "| {:.1} | {n} | {:.2} ({:.2}) | {:.4} ({:.4}) | {:.0} ({:.0}) | {:.0} ({:.0}) | {:.0} ({:.0}) | {:.0} ({:.0}) | {:.3e} ({:.3e}) | {:.3e} ({:.3e}) | {:.3e} ({:.3e}) | {:.0} ({:.0}) |",
                r.y_mm,
                m_lat * main.rail_y_m * 1e3,
                v[0],
                m_delta * main.contact_angle_rad,
                v[1],
                fnn,
                v[2],
                fx,
                v[3],
                fs,
                v[4],
                fy,
                v[5],
                main.creepage_long,
                v[6],
                m_lat * main.creepage_lat,
                v[7],
                m_lat * main.spin_per_m * 1e-3,
                v[8],
                main.max_pressure_pa * 1e-6,
                v[9],
            );
            if r.y_mm > 0.0 && !(side == Side::Right && r.y_mm == 5.0) {
                worst[0] = worst[0].max((m_lat * main.rail_y_m * 1e3 - v[0]).abs());
                worst[1] = worst[1].max((fnn - v[2]).abs() / v[2]);
                let t_ours = fx.hypot(fs);
                let t_ref = v[3].hypot(v[4]);
                worst[2] = worst[2].max((t_ours - t_ref).abs() / t_ref);
                worst[3] = worst[3].max((main.max_pressure_pa * 1e-6 - v[9]).abs() / v[9]);
            }
        }
    }
    times.sort_by(f64::total_cmp);
    println!(
        "\nLargest differences for y = 0.5..10 mm (single-patch cases): rail contact position {:.2} mm, \
         normal force {:.2} %, creep force magnitude {:.2} %, max pressure {:.2} %.",
        worst[0],
        100.0 * worst[1],
        100.0 * worst[2],
        100.0 * worst[3]
    );
    println!(
        "Time per wheel (one side, cold kernel cache at first use): median {:.1} ms, max {:.1} ms over {} solves.",
        1e3 * times[times.len() / 2],
        1e3 * times[times.len() - 1],
        times.len()
    );
}
