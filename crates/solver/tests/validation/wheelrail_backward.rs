//! Rolling backwards: a wheelset rolling towards -x is the mirror image in
//! x of one rolling forwards (an isotropic half-space, a body of
//! revolution on a prismatic rail). Mirroring x turns the forward speed,
//! the yaw angle and the yaw and pitch rates over and keeps the lateral
//! shift, the roll and the load; the forces on the rails keep Fy and Fz,
//! and Fx and each patch's x, Fx, Mz and longitudinal creepage and spin
//! change sign. Every model that rolls backwards must give that mirror
//! image: the exact model through its rolling direction pi, the fast
//! models by solving the patch's mirror image.

use railcontact_solver::core::cache::KernelCache;
use railcontact_solver::core::fastsim::SlopeReduction;
use railcontact_solver::core::fastsim_grid::FastsimMaterial;
use railcontact_solver::core::temperature::ThermalBody;
use railcontact_solver::wheelrail::builtin::{mbench_a22_input, mbench_pair};
use railcontact_solver::wheelrail::{
    solve_wheelset, solve_wheelset_warm, ExactTangential, FrictionAxis, FrictionTable,
    SearchScratch, WarmStart, WheelRailInput, WheelRailModel, WheelRailSolution, WheelRailThermal,
};

/// `input` mirrored in x.
fn mirrored(input: &WheelRailInput) -> WheelRailInput {
    let mut m = input.clone();
    m.position.yaw_rad = -input.position.yaw_rad;
    m.velocity.forward_m_per_s = -input.velocity.forward_m_per_s;
    m.velocity.yaw_rad_per_s = -input.velocity.yaw_rad_per_s;
    m.velocity.pitch_rad_per_s = input.velocity.pitch_rad_per_s.map(|w| -w);
    m
}

/// at 6 mm (yaw 14.4 mrad), 2 m/s, the lateral creepage of a
/// wheelset moving sideways, braked by the pitch rate (xi about 2e-3 at
/// the nominal radius) and a yaw rate: every creepage and spin non-zero.
fn moving(model: WheelRailModel) -> WheelRailInput {
    let mut input = mbench_a22_input(6.0, None, None, model);
    let v = input.velocity.forward_m_per_s;
    input.velocity.lateral_m_per_s = 2e-3;
    input.velocity.yaw_rad_per_s = 0.01;
    input.velocity.pitch_rad_per_s = Some(-(1.0 - 2e-3) * v / 0.46);
    input
}

/// Asserts that `b` is `a` mirrored in x, to `tol` of the wheel's load
/// (forces) and of the creepages' size.
fn assert_mirror(model: WheelRailModel, a: &WheelRailSolution, b: &WheelRailSolution, tol: f64) {
    let load = 1e4;
    let mut worst = 0.0f64;
    assert_eq!(a.wheels.len(), b.wheels.len());
    assert!(
        (a.pitch_rad_per_s + b.pitch_rad_per_s).abs() <= 1e-12 * a.pitch_rad_per_s.abs(),
        "{model:?}: pitch rates {} and {}",
        a.pitch_rad_per_s,
        b.pitch_rad_per_s
    );
    for (wa, wb) in a.wheels.iter().zip(&b.wheels) {
        let [fx, fy, fz] = wa.force_track_n;
        let [gx, gy, gz] = wb.force_track_n;
        // The mirror image has to be told apart from the forward solve.
        assert!(fx.abs() > 50.0, "{model:?}: Fx {fx} too small to test");
        for (what, x, y) in [("Fx", fx, -gx), ("Fy", fy, gy), ("Fz", fz, gz)] {
            worst = worst.max((x - y).abs() / load);
            assert!(
                (x - y).abs() <= tol * load,
                "{model:?} {:?} {what}: forwards {x}, backwards mirrored {y}",
                wa.side
            );
        }
        assert_eq!(wa.patches.len(), wb.patches.len(), "{model:?}");
        for (p, q) in wa.patches.iter().zip(&wb.patches) {
            for (what, x, y) in [
                ("x", p.track_x_m, -q.track_x_m),
                ("creepage_long", p.creepage_long, -q.creepage_long),
                ("creepage_lat", p.creepage_lat, q.creepage_lat),
                ("spin", p.spin_per_m * 0.01, -q.spin_per_m * 0.01),
            ] {
                assert!(
                    (x - y).abs() <= 1e-9,
                    "{model:?} {:?} {what}: {x} against {y}",
                    wa.side
                );
            }
            for (what, x, y) in [
                ("Fn", p.normal_force_n, q.normal_force_n),
                ("Fx", p.fx_n, -q.fx_n),
                ("Fs", p.fs_n, q.fs_n),
                ("Mz x 100", 100.0 * p.mz_nm, -100.0 * q.mz_nm),
            ] {
                worst = worst.max((x - y).abs() / load);
                assert!(
                    (x - y).abs() <= tol * load,
                    "{model:?} {:?} patch {what}: forwards {x}, backwards mirrored {y}",
                    wa.side
                );
            }
        }
    }
    println!("{model:?}: mirror image to {worst:.1e} of the load");
}

/// Every model that rolls backwards gives the mirror image of rolling
/// forwards. The fast models solve the mirror image itself (the same bits
/// here); the exact model turns its grid by pi, which mirrors the forward
/// one's (1.5e-10 of the load here: rounding and the iterations'
/// different paths). Rolling backwards as if forwards (the direction
/// left out) is off by 1.8e-4 of the load with Hertz+FASTSIM.
#[test]
fn rolling_backwards_is_the_mirror_image_of_rolling_forwards() {
    let pair = mbench_pair().unwrap();
    let cache = KernelCache::default();
    for (model, tol) in [
        (WheelRailModel::HertzFastsim, 1e-12),
        (WheelRailModel::HertzFastsimElliptic, 1e-12),
        (WheelRailModel::HertzFastsimModified, 1e-12),
        (WheelRailModel::HertzPolach, 1e-12),
        (WheelRailModel::HertzStrip, 1e-12),
        (WheelRailModel::KikPiotrowski, 1e-12),
        (WheelRailModel::Exact, 1e-8),
    ] {
        let forwards = moving(model);
        let backwards = mirrored(&forwards);
        let solve = |input: &WheelRailInput| {
            solve_wheelset(&pair, input, &cache, &mut SearchScratch::default()).unwrap()
        };
        let (a, b) = (solve(&forwards), solve(&backwards));
        assert_mirror(model, &a, &b, tol);
        // Rolling backwards with the forward kinematics is another
        // problem: the longitudinal force does not just turn over.
        let reversed = WheelRailInput {
            velocity: railcontact_solver::wheelrail::WheelsetVelocity {
                forward_m_per_s: -forwards.velocity.forward_m_per_s,
                pitch_rad_per_s: forwards.velocity.pitch_rad_per_s.map(|w| -w),
                ..forwards.velocity
            },
            ..forwards.clone()
        };
        let c = solve(&reversed);
        let d = (a.wheels[0].force_track_n[1] - c.wheels[0].force_track_n[1]).abs();
        assert!(
            d > 10.0,
            "{model:?}: Fy changes with the yaw's sign ({d} N)"
        );
    }
    // FASTSIM on the exact patches' grids integrates from the leading
    // edge at -x.
    let mut forwards = moving(WheelRailModel::Exact);
    forwards.settings.exact_tangential =
        ExactTangential::Fastsim(FastsimMaterial::kalker(SlopeReduction::NONE));
    let solve = |input: &WheelRailInput| {
        solve_wheelset(&pair, input, &cache, &mut SearchScratch::default()).unwrap()
    };
    let (a, b) = (solve(&forwards), solve(&mirrored(&forwards)));
    assert_mirror(WheelRailModel::Exact, &a, &b, 1e-8);
}

/// A prescribed total longitudinal force rolling backwards: the pitch rate
/// found is the mirror image's (braking while reversing pushes the rails
/// towards -x), and free rolling turns the wheel the other way.
#[test]
fn a_prescribed_force_rolling_backwards_finds_the_mirrored_pitch_rate() {
    let pair = mbench_pair().unwrap();
    let cache = KernelCache::default();
    let mut forwards = mbench_a22_input(6.0, None, None, WheelRailModel::HertzFastsim);
    forwards.total_longitudinal_force_n = Some(2e3);
    let mut backwards = mirrored(&forwards);
    backwards.total_longitudinal_force_n = Some(-2e3);
    let solve = |input: &WheelRailInput| {
        solve_wheelset(&pair, input, &cache, &mut SearchScratch::default()).unwrap()
    };
    let (a, b) = (solve(&forwards), solve(&backwards));
    let (ca, cb) = (a.pitch_control.unwrap(), b.pitch_control.unwrap());
    assert!(ca.converged && cb.converged);
    assert!(b.pitch_rad_per_s > 0.0, "{}", b.pitch_rad_per_s);
    assert!(
        (ca.nominal_creepage + cb.nominal_creepage).abs() < 1e-6 * ca.nominal_creepage.abs(),
        "nominal creepages {} and {}",
        ca.nominal_creepage,
        cb.nominal_creepage
    );
    assert!((a.pitch_rad_per_s + b.pitch_rad_per_s).abs() < 1e-9 * a.pitch_rad_per_s.abs());
}

/// A session that reverses: the step after the reversal starts its
/// patches cold (the carried tractions roll the other way) and answers
/// the cold solve of that step to the solver's tolerance.
#[test]
fn a_session_that_reverses_starts_cold() {
    let pair = mbench_pair().unwrap();
    let cache = KernelCache::default();
    let forwards = mbench_a22_input(2.0, None, None, WheelRailModel::Exact);
    let backwards = mirrored(&forwards);
    let mut scratch = SearchScratch::default();
    let mut warm = WarmStart::default();
    solve_wheelset_warm(&pair, &forwards, &cache, &mut scratch, &mut warm).unwrap();
    assert!(warm
        .tractions
        .iter()
        .all(|t| t.as_ref().is_some_and(|t| !t.rolling_backward)));
    let after = solve_wheelset_warm(&pair, &backwards, &cache, &mut scratch, &mut warm).unwrap();
    assert!(warm
        .tractions
        .iter()
        .all(|t| t.as_ref().is_some_and(|t| t.rolling_backward)));
    let cold = solve_wheelset(&pair, &backwards, &cache, &mut SearchScratch::default()).unwrap();
    for (w, c) in after.wheels.iter().zip(&cold.wheels) {
        for k in 0..3 {
            let (x, y) = (w.force_track_n[k], c.force_track_n[k]);
            assert!(
                (x - y).abs() < 1e-3 * 1e4,
                "{:?} {k}: {x} against {y}",
                w.side
            );
        }
    }
}

/// The models that roll forwards only are refused by name rolling
/// backwards, as are the flash temperatures.
#[test]
fn conformal_models_and_temperatures_refuse_rolling_backwards() {
    let pair = mbench_pair().unwrap();
    let cache = KernelCache::default();
    for model in [WheelRailModel::Cect, WheelRailModel::Auto] {
        let input = mirrored(&mbench_a22_input(2.0, None, None, model));
        let e = solve_wheelset(&pair, &input, &cache, &mut SearchScratch::default())
            .unwrap_err()
            .to_string();
        assert!(e.contains("model") && e.contains("backwards"), "{e}");
    }
    let mut input = mirrored(&mbench_a22_input(2.0, None, None, WheelRailModel::Exact));
    input.temperature = Some(WheelRailThermal {
        rail: ThermalBody::steel(293.15),
        wheel: ThermalBody::steel(293.15),
    });
    let e = solve_wheelset(&pair, &input, &cache, &mut SearchScratch::default())
        .unwrap_err()
        .to_string();
    assert!(e.contains("temperature"), "{e}");
    input.temperature = None;
    input.velocity.forward_m_per_s = 0.0;
    let e = solve_wheelset(&pair, &input, &cache, &mut SearchScratch::default())
        .unwrap_err()
        .to_string();
    assert!(e.contains("velocity.forward_m_per_s"), "{e}");
}

/// Friction varying across an exact patch (a friction table, one
/// coefficient per grid row) rolls backwards on the grid turned by pi,
/// whose rows run the other way: the mirror image still holds. A
/// coefficient rising steeply with the contact angle over the patch and a
/// braking creepage near saturation make the rows' coefficients count.
#[test]
fn friction_per_grid_row_rolling_backwards_is_the_mirror_image() {
    let pair = mbench_pair().unwrap();
    let cache = KernelCache::default();
    let mut forwards = moving(WheelRailModel::Exact);
    forwards.velocity.pitch_rad_per_s = Some(-(1.0 - 5e-3) * 2.0 / 0.46);
    forwards.friction_table = Some(FrictionTable {
        axis: FrictionAxis::ContactAngle,
        positions: vec![-0.02, 0.06],
        track_s_m: Vec::new(),
        coefficients: vec![0.1, 0.5],
    });
    let solve = |input: &WheelRailInput| {
        solve_wheelset(&pair, input, &cache, &mut SearchScratch::default()).unwrap()
    };
    let (a, b) = (solve(&forwards), solve(&mirrored(&forwards)));
    assert_mirror(WheelRailModel::Exact, &a, &b, 1e-8);
}
