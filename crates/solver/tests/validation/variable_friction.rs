//! Friction varying over the rail profile in wheel/rail contact: the
//! Manchester right wheel with CONTACT's `mbench_a22_varfric` table
//! against its reference output, and analytic checks of the table (a
//! constant table is the constant coefficient to the bit; a step between two
//! patches gives each its own coefficient); falling friction per patch.

use railcontact_solver::core::cache::KernelCache;
use railcontact_solver::core::friclaw::{FallingShape, SlipStart, SlipVelocityLaw};
use railcontact_solver::core::problem::Friction;
use railcontact_solver::wheelrail::builtin::mbench_a22_input;
use railcontact_solver::wheelrail::{
    solve_wheelset, FrictionAxis, FrictionTable, SearchScratch, Side, WheelRailInput,
    WheelRailModel, WheelRailSolution,
};

use super::wheelrail::mbench_pair;

/// CONTACT's friction table of `mbench_a22_varfric.inp` (github.com/eve70a/CONTACT,
/// examples/, commit 424e4e6): NVF = 2, ALPHA -20 deg with FSTAT = FKIN = 0.2
/// and -10 deg with 0.3, by contact angle. CONTACT's right-wheel contact
/// angles have the opposite sign of ours (see `wheelrail.rs`): 10 and 20
/// degrees here.
fn varfric_table() -> FrictionTable {
    FrictionTable {
        axis: FrictionAxis::ContactAngle,
        positions: vec![10f64.to_radians(), 20f64.to_radians()],
        track_s_m: Vec::new(),
        coefficients: vec![0.3, 0.2],
    }
}

/// Case 4 of `mbench_a22_varfric.ref_out` (same repository, commit
/// eb670a7, revision 2480, 2023-12-22), right wheel at 5.5 mm, yaw 13.2
/// mrad: the input's roll [rad] and pitch rate [rad/s], then its one
/// patch's FN, FX, FS [N] on the rail and FSTAT (= FKIN) [-]. The flange
/// root patch at 19.3 degrees (CONTACT's DELTCP -0.3363 rad) lies inside the
/// table and slides fully.
///
/// Cases 1 to 3 of the file are left out: there the contact itself differs
/// from CONTACT's whatever the friction. At 0 and 0.5 mm (mu 0.3 at the
/// table's end) our contact points lie at rail y -7.3 and -18.6 mm against
/// CONTACT's -8.7 and -16.0 mm, with other creepages (xi -1.4e-4 against
/// -5.7e-5 at 0 mm: FX 44.6 N against 0.28 N). At 5 mm CONTACT's tread
/// patch has the contact angle 0.248 rad at rail y -23.76 mm, where the
/// rail's surface (and our patch, at -23.71 mm) is at 0.132 rad, so it
/// takes mu 0.258 and we take 0.3 (the table's end); the flange root
/// patch takes 0.2284 here against 0.2323 (our angle 0.2995 rad against
/// 0.2927), FN 8111 N against 8244 N. `wheelrail.rs` compares the same
/// position with plain friction within 10 % (FX) and 3 % (FS).
const CASE4: (f64, f64, [f64; 4]) = (-0.00047770, -4.33188640, [9907.0, -608.6, -1963.0, 0.2076]);

/// Case 3's input (5 mm, two patches), for the analytic checks.
const CASE3: (f64, f64, f64) = (5.0, -0.00035540, -4.33536370);

fn right_wheel(input: &WheelRailInput) -> WheelRailSolution {
    let pair = mbench_pair();
    let cache = KernelCache::default();
    let mut scratch = SearchScratch::default();
    solve_wheelset(&pair, input, &cache, &mut scratch).unwrap()
}

fn case_input((y_mm, roll, pitch): (f64, f64, f64)) -> WheelRailInput {
    let mut input = mbench_a22_input(y_mm, Some(roll), Some(pitch), WheelRailModel::Exact);
    input.sides = vec![Side::Right];
    input.friction_table = Some(varfric_table());
    input
}

/// Measured: FN 9905.4, FX -613.65, FS -1966.5 N, mu 0.2075 (0.02 %,
/// 0.83 %, 0.18 %, 0.05 %).
#[test]
fn a22_varfric_matches_contact() {
    let (roll, pitch, r) = CASE4;
    let sol = right_wheel(&case_input((5.5, roll, pitch)));
    let w = &sol.wheels[0];
    assert_eq!(w.patches.len(), 1);
    let p = &w.patches[0];
    let close = |what: &str, got: f64, want: f64| {
        assert!(
            (got - want).abs() <= 0.01 * want.abs(),
            "{what} {got}, CONTACT {want}"
        );
    };
    close("FN", p.normal_force_n, r[0]);
    close("FX", p.fx_n, r[1]);
    close("FS", p.fs_n, r[2]);
    close("mu", p.friction_coefficient, r[3]);
    // The table read at the patch's contact angle.
    let mu = varfric_table().coefficient(p.contact_angle_rad, 0.0);
    assert_eq!(p.friction_coefficient, mu);
}

#[test]
fn constant_table_is_the_constant_coefficient_to_the_bit() {
    let coulomb = right_wheel(&WheelRailInput {
        friction_table: None,
        friction: Friction::coulomb(0.25),
        ..case_input(CASE3)
    });
    for axis in [FrictionAxis::ContactAngle, FrictionAxis::RailLateral] {
        let table = right_wheel(&WheelRailInput {
            friction_table: Some(FrictionTable::constant(axis, 0.25)),
            ..case_input(CASE3)
        });
        for (a, b) in coulomb.wheels[0]
            .patches
            .iter()
            .zip(&table.wheels[0].patches)
        {
            assert_eq!(a.fx_n.to_bits(), b.fx_n.to_bits());
            assert_eq!(a.fs_n.to_bits(), b.fs_n.to_bits());
            assert_eq!(a.normal_force_n.to_bits(), b.normal_force_n.to_bits());
            assert_eq!(b.friction_coefficient, 0.25);
        }
    }
}

/// A step in the table between the two patches of case 3 (tread at 7.6
/// degrees, flange root at 17.2): each patch takes its side's coefficient
/// in every grid row and, sliding fully, carries |t| = mu p_n in every
/// element (summed, to 1e-4: the tangential tolerance is 1e-4 of mu p_max
/// per element; measured -6.7e-9 and -2.4e-8); the same step by rail y
/// gives the same.
#[test]
fn a_step_between_two_patches_gives_each_its_own_coefficient() {
    let by_angle = FrictionTable {
        axis: FrictionAxis::ContactAngle,
        positions: vec![0.21, 0.22],
        track_s_m: Vec::new(),
        coefficients: vec![0.4, 0.15],
    };
    // Rail y decreases towards the gauge face: the step the other way.
    let by_rail_y = FrictionTable {
        axis: FrictionAxis::RailLateral,
        positions: vec![-0.030, -0.029],
        track_s_m: Vec::new(),
        coefficients: vec![0.15, 0.4],
    };
    for table in [by_angle, by_rail_y] {
        let sol = right_wheel(&WheelRailInput {
            friction_table: Some(table),
            ..case_input(CASE3)
        });
        let p = &sol.wheels[0].patches;
        assert_eq!(p.len(), 2);
        for (patch, mu) in p.iter().zip([0.4, 0.15]) {
            assert_eq!(patch.friction_coefficient, mu);
            assert_eq!(patch.adhesion_fraction, 0.0, "{patch:?}");
            // Summed per element: the spin turns the tractions across the
            // patch, |F| is a little less than mu FN.
            let fields = &patch.solution.as_ref().unwrap().fields;
            let carried: f64 = (0..fields.pressure_pa.len())
                .map(|i| fields.traction_x_pa[i].hypot(fields.traction_y_pa[i]))
                .sum();
            let bound = mu * fields.pressure_pa.iter().sum::<f64>();
            eprintln!("sum |t| / (mu sum p_n) - 1: {:.1e}", carried / bound - 1.0);
            assert!(
                (carried - bound).abs() < 1e-4 * bound,
                "sum |t| {carried} Pa against mu sum p_n {bound} Pa"
            );
        }
    }
}

/// Per grid row: a table rising across the flange-root patch of case 3
/// (by 0.1 per 0.1 rad of contact angle) bounds each row of the fully
/// sliding patch by its own coefficient (under one coefficient every row
/// would carry |t| = mu p_n alike).
#[test]
fn an_exact_patch_takes_the_coefficient_of_each_grid_row() {
    let table = FrictionTable {
        axis: FrictionAxis::ContactAngle,
        positions: vec![0.2, 0.4],
        track_s_m: Vec::new(),
        coefficients: vec![0.2, 0.4],
    };
    let sol = right_wheel(&WheelRailInput {
        friction_table: Some(table.clone()),
        ..case_input(CASE3)
    });
    // The rows' coefficients from the traction bound they reached.
    let rows = row_ratios(&sol.wheels[0].patches[1], |_| 1.0);
    // The rows differ (measured: from 0.263 to 0.347 over the 7 loaded rows).
    let (lo, hi) = rows
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), &m| (a.min(m), b.max(m)));
    assert!(hi - lo > 0.01, "row coefficients {rows:?}");
    assert!(lo >= 0.2 - 1e-4 && hi <= 0.4 + 1e-4, "{rows:?}");
}

/// The exponential law mu_kin + mu_1 exp(-s_a ln 2 / 0.05 m/s), starting
/// from sticking (the rolling speed is each patch's own).
fn exponential(mu_kin: f64, mu1: f64) -> SlipVelocityLaw {
    SlipVelocityLaw {
        shape: FallingShape::Exponential,
        kinetic_coefficient: mu_kin,
        falling_coefficients: [mu1, 0.0],
        half_velocities_m_per_s: [0.05, 0.0],
        rolling_speed_m_per_s: 1.0,
        memory_distance_m: 0.0,
        memory_velocity_m_per_s: 0.0,
        start: SlipStart::Sticking,
        max_iterations: 0,
    }
}

/// An exponential falling law (the exact model's, per patch at its own
/// rolling speed) whose falling coefficient is 0 is Coulomb's law with its
/// kinetic coefficient, to the bit. With mu_1 = 0.3 falling to mu_kin =
/// 0.1 (halved at 0.05 m/s) the fully sliding flange-root patch of case 4
/// carries in each element the law's mu(s_a) p_n at its own slip velocity
/// s_a = V |s| (V the patch's rolling speed): summed over the patch within
/// 0.1 %, the law's iteration tolerance being 1e-4 of the bounds (measured:
/// 1.9e-6); and less than under Coulomb's law at the static coefficient 0.4
/// (measured: |F| 2885.5 N against 3736.5 N, FN 9630 N).
#[test]
fn falling_friction_per_patch() {
    let law = |mu1: f64| exponential(0.1, mu1);
    let with = |f: Friction| {
        right_wheel(&WheelRailInput {
            friction_table: None,
            friction: f,
            ..case_input((5.5, CASE4.0, CASE4.1))
        })
    };
    let coulomb = with(Friction::coulomb(0.1));
    let flat = with(Friction::falling(law(0.0)));
    for (a, b) in coulomb.wheels[0]
        .patches
        .iter()
        .zip(&flat.wheels[0].patches)
    {
        assert_eq!(a.fx_n.to_bits(), b.fx_n.to_bits());
        assert_eq!(a.fs_n.to_bits(), b.fs_n.to_bits());
        assert_eq!(a.normal_force_n.to_bits(), b.normal_force_n.to_bits());
    }
    let falling = law(0.3);
    let sol = with(Friction::falling(falling));
    let p = &sol.wheels[0].patches[0];
    let fields = &p.solution.as_ref().unwrap().fields;
    let (mut carried, mut predicted) = (0.0, 0.0);
    for i in 0..fields.pressure_pa.len() {
        let pn = fields.pressure_pa[i];
        if pn > 0.0 {
            let s_a = p.rolling_speed_m_per_s * fields.slip_x[i].hypot(fields.slip_y[i]);
            carried += fields.traction_x_pa[i].hypot(fields.traction_y_pa[i]);
            predicted += falling.coefficient(s_a) * pn;
        }
    }
    assert_eq!(p.adhesion_fraction, 0.0);
    assert!(
        (carried - predicted).abs() < 1e-3 * predicted,
        "sum |t| {carried} Pa, sum mu(s_a) p_n {predicted} Pa"
    );
    let f = p.fx_n.hypot(p.fs_n);
    let high = with(Friction::coulomb(0.4));
    let q = &high.wheels[0].patches[0];
    assert!(f < 0.95 * q.fx_n.hypot(q.fs_n), "{f} N against {:?}", q);
}

/// A falling law is the exact model's: the others refuse it naming the
/// key (with a table too); unequal static and kinetic coefficients are
/// refused by the conformal method.
#[test]
fn falling_friction_is_refused_where_it_cannot_be_solved() {
    let law = SlipVelocityLaw {
        shape: FallingShape::Linear,
        kinetic_coefficient: 0.2,
        falling_coefficients: [0.1, 0.0],
        half_velocities_m_per_s: [0.1, 0.0],
        rolling_speed_m_per_s: 1.0,
        memory_distance_m: 0.0,
        memory_velocity_m_per_s: 0.0,
        start: SlipStart::Previous,
        max_iterations: 0,
    };
    let pair = mbench_pair();
    let cache = KernelCache::default();
    let mut scratch = SearchScratch::default();
    let mut input = case_input(CASE3);
    input.friction = Friction::falling(law);
    input.settings.model = WheelRailModel::HertzFastsim;
    let err = solve_wheelset(&pair, &input, &cache, &mut scratch).unwrap_err();
    assert!(
        err.to_string()
            .starts_with("friction.law: a falling friction law needs model = \"exact\""),
        "{err}"
    ); // The conformal method takes one coefficient (as in patch cases).
    input.friction = Friction::static_kinetic(0.3, 0.2);
    input.settings.model = WheelRailModel::Cect;
    let err = solve_wheelset(&pair, &input, &cache, &mut scratch).unwrap_err();
    assert!(
        err.to_string().starts_with("friction.static_coefficient"),
        "{err}"
    );
}

/// Row coefficients |t| / p_n summed over each loaded grid row of `p`'s
/// fields, and the same with each element's bound `mu(i)` p_n in place of
/// |t|: their ratio per row.
fn row_ratios(
    p: &railcontact_solver::wheelrail::PatchResult,
    mu: impl Fn(usize) -> f64,
) -> Vec<f64> {
    let fields = &p.solution.as_ref().unwrap().fields;
    let g = p.grid_geometry.unwrap();
    let mut rows = Vec::new();
    for iy in 0..g.ny {
        let (mut t, mut bound) = (0.0, 0.0);
        for ix in 0..g.nx {
            let i = g.index(ix, iy);
            t += fields.traction_x_pa[i].hypot(fields.traction_y_pa[i]);
            bound += mu(i) * fields.pressure_pa[i];
        }
        if bound > 0.0 {
            rows.push(t / bound);
        }
    }
    rows
}

/// A table scales the friction's law to its static coefficients
/// (`Friction::scaled_to`, wheelrail::friction docs). With a falling law
/// of static coefficient 0.4 (mu_kin 0.1 + mu_1 0.3) and the table rising
/// across the fully sliding flange-root patch of case 3 (0.2 to 0.4 by
/// contact angle), every element carries the law's mu(s_a) p_n times its
/// row's table coefficient over 0.4; under Coulomb's law with the same
/// table each row carries its table coefficient: per row, the first ratio
/// is the second over 0.4 (within 1e-3: the law's iteration tolerance is
/// 1e-4 of the bounds). A constant table of the law's static coefficient
/// is the law without a table, to the bit; a constant table at half of it
/// is the law with both coefficients halved, to the bit.
#[test]
fn a_table_scales_a_falling_law_row_by_row() {
    let law = exponential;
    let rising = FrictionTable {
        axis: FrictionAxis::ContactAngle,
        positions: vec![0.2, 0.4],
        track_s_m: Vec::new(),
        coefficients: vec![0.2, 0.4],
    };
    let with = |f: Friction, t: Option<FrictionTable>| {
        right_wheel(&WheelRailInput {
            friction_table: t,
            friction: f,
            ..case_input(CASE3)
        })
    };
    let falling = law(0.1, 0.3);
    let scaled = with(Friction::falling(falling), Some(rising.clone()));
    let coulomb = with(Friction::coulomb(0.3), Some(rising));
    let (p, q) = (&scaled.wheels[0].patches[1], &coulomb.wheels[0].patches[1]);
    assert_eq!(p.adhesion_fraction, 0.0);
    assert_eq!(q.adhesion_fraction, 0.0);
    let fields = &p.solution.as_ref().unwrap().fields;
    let speed = p.rolling_speed_m_per_s;
    let mu = |i: usize| falling.coefficient(speed * fields.slip_x[i].hypot(fields.slip_y[i]));
    let law_rows = row_ratios(p, mu);
    let table_rows = row_ratios(q, |_| 1.0);
    eprintln!("rows: law-scaled {law_rows:?}, Coulomb table {table_rows:?}");
    assert_eq!(law_rows.len(), table_rows.len());
    // The rows differ (measured: 0.347 to 0.263 under Coulomb's law).
    assert!((table_rows[table_rows.len() - 1] - table_rows[0]).abs() > 0.01);
    for (a, b) in law_rows.iter().zip(&table_rows) {
        assert!((a - b / 0.4).abs() < 1e-3, "{law_rows:?} {table_rows:?}");
    }
    // Constant tables.
    let bits = |s: &WheelRailSolution| {
        s.wheels[0]
            .patches
            .iter()
            .map(|p| {
                [
                    p.fx_n.to_bits(),
                    p.fs_n.to_bits(),
                    p.normal_force_n.to_bits(),
                ]
            })
            .collect::<Vec<_>>()
    };
    let constant = |mu: f64| Some(FrictionTable::constant(FrictionAxis::ContactAngle, mu));
    let plain = with(Friction::falling(falling), None);
    assert_eq!(
        bits(&with(Friction::falling(falling), constant(0.4))),
        bits(&plain)
    );
    let halved = with(Friction::falling(law(0.05, 0.15)), None);
    assert_eq!(
        bits(&with(Friction::falling(falling), constant(0.2))),
        bits(&halved)
    );
}

/// A wheel/rail session carries a falling law's slip velocities from one
/// time step to the next (`PatchTractions::slip_velocity_m_per_s`): with
/// `start = "previous"` the next step's iteration on the slip velocities
/// starts from them instead of from sticking. A-2.2's right wheel on its
/// tread at 20 m/s, partly adhering (creepage 8e-4, the law falling from
/// 0.4 to 0.1 at 0.05 m/s): a step at the same motion as the one before,
/// from its tractions, gives the same forces with the carried velocities
/// as with the carried tractions alone (within 1e-5 of mu Fn: the law's
/// and the Newton solver's tolerances; measured 2e-3 N) in fewer
/// tangential iterations (measured 9 against 22, 77 against 137 operator
/// products). (The step before lies on a grid half an element apart
/// laterally, its forces 2.5 N = 6e-4 mu Fn away (Fn 10 kN): the grid's
/// placement, not the start.)
#[test]
fn a_session_carries_the_slip_velocities_of_a_falling_law() {
    use railcontact_solver::wheelrail::{solve_wheelset_warm, WarmStart};
    let mut input = mbench_a22_input(0.0, None, None, WheelRailModel::Exact);
    input.sides = vec![Side::Right];
    input.position.yaw_rad = 0.0;
    // 20 m/s, the pitch rate of a 0.46 m radius 0.1 % above rolling.
    input.velocity.forward_m_per_s = 20.0;
    input.velocity.pitch_rad_per_s = Some(-20.0 / 0.46 * 1.001);
    input.friction = Friction::falling(SlipVelocityLaw {
        start: SlipStart::Previous,
        ..exponential(0.1, 0.3)
    });
    let pair = mbench_pair();
    let cache = KernelCache::default();
    let mut scratch = SearchScratch::default();
    // Two steps: the second one's grid is sized from the first's contact
    // and keeps its shape from then on, so that the third step starts
    // from the second's tractions.
    let mut warm = WarmStart::default();
    solve_wheelset_warm(&pair, &input, &cache, &mut scratch, &mut warm).unwrap();
    let first = solve_wheelset_warm(&pair, &input, &cache, &mut scratch, &mut warm).unwrap();
    let carried = warm.clone();
    let mut without = warm.clone();
    for t in without.tractions.iter_mut().flatten() {
        assert!(!t.slip_velocity_m_per_s.is_empty());
        t.slip_velocity_m_per_s.clear();
    }
    let mut step = |mut w: WarmStart| {
        let s = solve_wheelset_warm(&pair, &input, &cache, &mut scratch, &mut w).unwrap();
        let p = &s.wheels[0].patches[0];
        let info = &p.solution.as_ref().unwrap().info;
        (p.fx_n, p.fs_n, info.tangential_iterations, info.matvecs)
    };
    let (a, b) = (step(carried), step(without));
    let p = &first.wheels[0].patches[0];
    eprintln!(
        "step: fx {:.3} fs {:.3} adhesion {:.3}; next step with the slip velocities: fx {:.3} \
         fs {:.3}, {} tangential iterations, {} products; without: fx {:.3} fs {:.3}, {} and {}",
        p.fx_n, p.fs_n, p.adhesion_fraction, a.0, a.1, a.2, a.3, b.0, b.1, b.2, b.3
    );
    assert!(p.adhesion_fraction > 0.1 && p.adhesion_fraction < 0.9);
    let scale = 0.4 * p.normal_force_n;
    for (got, want) in [(a.0, b.0), (a.1, b.1)] {
        assert!((got - want).abs() < 1e-5 * scale, "{got} against {want}");
    }
    assert!(a.2 < b.2 && a.3 < b.3, "{a:?} against {b:?}");
}
