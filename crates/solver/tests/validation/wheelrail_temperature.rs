//! Flash temperatures of wheel/rail patches (`WheelRailInput::temperature`)
//! on the Manchester benchmark: each patch's temperatures against the
//! same patch solved again through the patch path (a `ContactProblem` on
//! the patch's grid, undeformed distance, normal force, creepages and
//! friction, then `flash_temperatures` with the rail as body 1), against
//! the patch's own frictional power, and against the bound of Ertz &
//! Knothe's model; `cect` patches (curved grid) against the exact ones
//! where the patches are barely conformal; the models without fields
//! refused naming the key; and nothing changed when no temperature is
//! asked for.

use railcontact_solver::core::cache::KernelCache;
use railcontact_solver::core::normal::NormalLoad;
use railcontact_solver::core::problem::{ContactProblem, Creepages, Friction, Kinematics};
use railcontact_solver::core::solve::solve;
use railcontact_solver::core::temperature::{flash_temperatures, ThermalBody};
use railcontact_solver::wheelrail::builtin::{mbench_a22_input, mbench_pair};
use railcontact_solver::wheelrail::{
    solve_wheelset, wheelrail_solver_settings, PatchResult, PatchTemperatures, SearchScratch,
    WheelRailError, WheelRailInput, WheelRailModel, WheelRailThermal,
};

/// at 6.5 mm (tread contact on the left wheel, flange contact on the
/// right) with CONTACT's roll and pitch rate (mbench_a22_*.inp of
/// eve70a/CONTACT, as `a22_single_patch_cases_match_contact`).
fn a22(model: WheelRailModel) -> WheelRailInput {
    mbench_a22_input(6.5, Some(-0.004376), Some(-4.2748834), model)
}

/// Rail and wheel of different bulk temperatures and effusivities, so that
/// swapping them would show: the rail steel at 20 °C, the wheel at 60 °C
/// and conducting 40 % less.
fn thermal() -> WheelRailThermal {
    WheelRailThermal {
        rail: ThermalBody::steel(293.15),
        wheel: ThermalBody {
            conductivity_w_per_m_k: 30.0,
            ..ThermalBody::steel(333.15)
        },
    }
}

/// The patch's heat flux sums to its frictional power, to 1e-9.
fn assert_heat_is_the_patch_power(what: &str, p: &PatchResult) {
    let q = p.temperature.as_ref().unwrap().frictional_power_w;
    let w = p.frictional_power_w;
    assert!((q - w).abs() <= 1e-9 * w, "{what}: {q} W against {w} W");
}

fn invalid_key(e: WheelRailError) -> String {
    match e {
        WheelRailError::Invalid { key, .. } => key,
        other => panic!("expected an input error, got {other}"),
    }
}

#[test]
fn a22_patch_temperatures_equal_the_patch_path_on_the_same_patch() {
    let pair = mbench_pair().unwrap();
    let mut input = a22(WheelRailModel::Exact);
    let t = thermal();
    input.temperature = Some(t);
    let cache = KernelCache::global();
    let sol = solve_wheelset(&pair, &input, cache, &mut SearchScratch::default()).unwrap();
    let mut patches = 0;
    for w in &sol.wheels {
        for p in &w.patches {
            patches += 1;
            let what = format!(
                "{} wheel, patch at rail y {:.2} mm",
                w.side.name(),
                p.rail_y_m * 1e3
            );
            let temp = p
                .temperature
                .as_ref()
                .expect("an exact patch has temperatures");
            let fields = &p.solution.as_ref().unwrap().fields;
            let grid = p.grid_geometry.unwrap();
            // The same patch through the patch path: its grid and
            // undeformed distance at its normal force, creepages and
            // friction, the wheel/rail solver settings.
            let problem = ContactProblem {
                material: input.material,
                friction: Friction::coulomb(p.friction_coefficient),
                grid,
                gap_m: fields.gap_m.clone(),
                load: NormalLoad::NormalForce(p.normal_force_n),
                kinematics: Kinematics::SteadyRolling(Creepages {
                    creepage_long: p.creepage_long,
                    creepage_lat: p.creepage_lat,
                    spin_per_m: p.spin_per_m,
                }),
                settings: wheelrail_solver_settings(),
                rolling_direction_rad: 0.0,
                extra_rigid_slip: None,
                numerical_influence: None,
            };
            let again = solve(&problem).unwrap().pop().unwrap();
            let patch_path =
                flash_temperatures(&grid, &again.fields, &t.input(p.rolling_speed_m_per_s))
                    .unwrap();
            // Temperatures: the rises over the contact temperature agree
            // to within the solver's tolerances (tangential 1e-4 of mu p:
            // the two solves stop at different iterates; measured: 3.9e-6 K
            // of a 20 K rise on the tread, 4.8e-5 K of 215 K on the flange).
            let tc = temp.contact_temperature_k;
            let rise = temp.max_rail.temperature_k - tc;
            assert!(rise > 10.0, "{what}: rise {rise} K");
            let mut worst: f64 = 0.0;
            for (k, (a, b)) in [
                (&temp.surface.body1_k, &patch_path.body1_k),
                (&temp.surface.body2_k, &patch_path.body2_k),
            ]
            .into_iter()
            .enumerate()
            {
                for (i, (x, y)) in a.iter().zip(b).enumerate() {
                    worst = worst.max((x - y).abs());
                    assert!(
                        (x - y).abs() <= 1e-5 * rise,
                        "{what}: body {} element {i}: {x} K against the patch path's {y} K",
                        k + 1
                    );
                }
            }
            let s = patch_path.summary;
            println!(
                "{what}: rail max {:.4} K (patch path {:.4} K), wheel max {:.4} K ({:.4} K), \
                 largest difference {worst:.2e} K, power {:.4} W (patch {:.4} W)",
                temp.max_rail.temperature_k,
                s.max_body1.temperature_k,
                temp.max_wheel.temperature_k,
                s.max_body2.temperature_k,
                temp.frictional_power_w,
                p.frictional_power_w
            );
            // Rail = body 1: its bulk temperature and heat share.
            let (br, bw) = (t.rail.effusivity(), t.wheel.effusivity());
            assert!((temp.heat_share_rail - br / (br + bw)).abs() <= 1e-15);
            assert!(
                (tc - (br * 293.15 + bw * 333.15) / (br + bw)).abs() <= 1e-9,
                "{what}: contact temperature {tc}"
            );
            // The heat flux |p_t| |s| V sums to the patch's frictional
            // power T-gamma V (V the patch's rolling speed, that of its
            // slips): fails if the temperatures took another speed (the
            // forward speed is 1 % below this flange patch's V) or another
            // patch's fields. In slip p_t is opposite to s, so the two
            // sums agree to rounding.
            assert_heat_is_the_patch_power(&what, p);
            // Ertz & Knothe's rise under a flux of at most q_max over a
            // row of at most L (Carslaw & Jaeger's constant flux on a
            // semi-infinite solid, the heat shared by the effusivities):
            // 2 q_max sqrt(L / V) / ((beta_r + beta_w) sqrt(pi)).
            let q_max = temp
                .surface
                .heat_flux_w_per_m2
                .iter()
                .fold(0.0, |a: f64, &b| a.max(b));
            let v = p.rolling_speed_m_per_s;
            let longest_m = (0..grid.ny)
                .map(|iy| {
                    (0..grid.nx)
                        .filter(|&ix| fields.pressure_pa[grid.index(ix, iy)] > 0.0)
                        .count()
                })
                .max()
                .unwrap() as f64
                * grid.dx_m;
            let bound =
                2.0 * q_max * (longest_m / v).sqrt() / ((br + bw) * std::f64::consts::PI.sqrt());
            println!("{what}: rise {rise:.3} K, bound {bound:.3} K");
            assert!(
                rise <= bound && rise >= 0.2 * bound,
                "{what}: rise {rise} K against the bound {bound} K"
            );
        }
    }
    assert_eq!(patches, 2);
}

#[test]
fn temperatures_refuse_models_without_fields_and_name_the_key() {
    let pair = mbench_pair().unwrap();
    let cache = KernelCache::global();
    for model in [
        WheelRailModel::HertzFastsim,
        WheelRailModel::HertzPolach,
        WheelRailModel::HertzStrip,
        WheelRailModel::KikPiotrowski,
    ] {
        let mut input = a22(model);
        input.temperature = Some(thermal());
        let e = solve_wheelset(&pair, &input, cache, &mut SearchScratch::default()).unwrap_err();
        let m = e.to_string();
        assert_eq!(invalid_key(e), "temperature", "{}", model.name());
        assert!(
            m.contains(model.name()) && m.contains("\"exact\", \"cect\" and \"auto\""),
            "{m}"
        );
    }
    let mut input = a22(WheelRailModel::Exact);
    let mut t = thermal();
    t.wheel.conductivity_w_per_m_k = -50.0;
    input.temperature = Some(t);
    let e = solve_wheelset(&pair, &input, cache, &mut SearchScratch::default()).unwrap_err();
    assert_eq!(invalid_key(e), "temperature.wheel.conductivity_w_per_m_k");
    let mut t = thermal();
    t.rail.bulk_temperature_k = 20.0;
    input.temperature = Some(t);
    let e = solve_wheelset(&pair, &input, cache, &mut SearchScratch::default()).unwrap_err();
    let m = e.to_string();
    assert_eq!(invalid_key(e), "temperature.rail.bulk_temperature_k");
    assert!(m.contains("Celsius"), "{m}");
}

#[test]
fn temperatures_leave_the_contact_solution_unchanged() {
    let pair = mbench_pair().unwrap();
    let cache = KernelCache::global();
    let plain = a22(WheelRailModel::Exact);
    let with = WheelRailInput {
        temperature: Some(thermal()),
        ..plain.clone()
    };
    let a = solve_wheelset(&pair, &plain, cache, &mut SearchScratch::default()).unwrap();
    let b = solve_wheelset(&pair, &with, cache, &mut SearchScratch::default()).unwrap();
    assert_eq!(a.wheels.len(), b.wheels.len());
    for (wa, wb) in a.wheels.iter().zip(&b.wheels) {
        assert_eq!(wa.force_track_n, wb.force_track_n);
        for (pa, pb) in wa.patches.iter().zip(&wb.patches) {
            assert!(pa.temperature.is_none() && pb.temperature.is_some());
            let fields = |p: &PatchResult| p.solution.as_ref().map(|s| s.fields.clone());
            assert_eq!(fields(pa), fields(pb));
            assert_eq!(
                [pa.normal_force_n, pa.fx_n, pa.fs_n, pa.frictional_power_w],
                [pb.normal_force_n, pb.fx_n, pb.fs_n, pb.frictional_power_w]
            );
        }
    }
}

/// On at 6.5 mm both patches are barely conformal (the contact angle
/// varies by 14 and 46 mrad over the exact patches' loaded extent, below
/// `auto`'s 175 mrad, so `auto` keeps them exact), where `cect` and `exact`
/// agree: the flash temperatures of the cect patches, from the tractions
/// and slips on their curved grids, against the exact patches'. Their
/// frictional powers differ by 0.008 % (tread) and 0.34 % (flange), and so
/// may the rises; measured: the rail's peak rises within 0.003 % and
/// 0.67 %, at the same element.
#[test]
fn a22_cect_temperatures_agree_with_the_exact_ones_on_barely_conformal_patches() {
    let pair = mbench_pair().unwrap();
    let cache = KernelCache::global();
    let solve_with = |model| {
        let mut input = a22(model);
        input.temperature = Some(thermal());
        solve_wheelset(&pair, &input, cache, &mut SearchScratch::default()).unwrap()
    };
    let exact = solve_with(WheelRailModel::Exact);
    let cect = solve_with(WheelRailModel::Cect);
    for (we, wc) in exact.wheels.iter().zip(&cect.wheels) {
        assert_eq!(we.patches.len(), wc.patches.len());
        for (pe, pc) in we.patches.iter().zip(&wc.patches) {
            assert_eq!((pe.method, pc.method), ("exact", "cect"));
            let what = format!("{} wheel", we.side.name());
            let (te, tc) = (
                pe.temperature.as_ref().unwrap(),
                pc.temperature.as_ref().unwrap(),
            );
            // Each cect patch's heat sums to its own frictional power.
            assert_heat_is_the_patch_power(&what, pc);
            let rise = |t: &PatchTemperatures| t.max_rail.temperature_k - t.contact_temperature_k;
            let (re, rc) = (rise(te), rise(tc));
            println!(
                "{what}: rail's peak rise exact {re:.4} K, cect {rc:.4} K ({:+.3} %), power \
                 {:.3} / {:.3} W",
                100.0 * (rc / re - 1.0),
                pe.frictional_power_w,
                pc.frictional_power_w
            );
            assert!(
                (rc - re).abs() <= 0.01 * re,
                "{what}: {rc} K against {re} K"
            );
            assert_eq!(
                [te.max_rail.x_m, te.max_rail.y_m],
                [tc.max_rail.x_m, tc.max_rail.y_m],
                "{what}: the peak's element"
            );
        }
    }
    // `auto` solves these patches exact: the same temperatures.
    let auto = solve_with(WheelRailModel::Auto);
    for (wa, we) in auto.wheels.iter().zip(&exact.wheels) {
        for (pa, pe) in wa.patches.iter().zip(&we.patches) {
            assert_eq!(pa.method, "exact");
            assert_eq!(pa.temperature, pe.temperature);
        }
    }
}
