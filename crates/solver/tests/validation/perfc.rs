//! CONTACT's performance cases of a wheel on a rail (`perfc_case`) on the
//! two smaller grids, 71 x 81 elements of 0.1 mm and 143 x 163 of 0.05 mm.
//! CONTACT's `perfc_test/get_times.ref_out` (2016) prints the contact
//! element counts of the normal problems ("ncon") and the slip element
//! counts of the shifts ("nslp"); the larger grids (287 x 323, 575 x 647)
//! run in `benches/perfc.rs`.

use railcontact_solver::core::problem::Kinematics;
use railcontact_solver::core::solution::{ContactSolution, ElementState, SolveStatus};
use railcontact_solver::core::solve::solve;

use crate::perfc_case::{case, heights_m, shift_step, MM};

fn count(s: &ContactSolution, f: impl Fn(ElementState, f64) -> bool) -> usize {
    s.fields
        .state
        .iter()
        .zip(&s.fields.pressure_pa)
        .filter(|(&st, &p)| f(st, p))
        .count()
}

#[test]
fn wheel_contact_element_counts_match_contact_perfc() {
    let heights = heights_m();
    // (grid level, "ncon" of norm_problm_1p / _2p, "nslp" of
    // tang_problm_1s / _2s in get_times.ref_out).
    for (level, ncon, nslp) in [(0, 3148, 1730), (1, 12902, 7243)] {
        let normal = solve(&case(level, &heights, Kinematics::Frictionless)).unwrap();
        let n = normal.last().unwrap();
        assert_eq!(n.info.status, SolveStatus::Converged);
        assert_eq!(
            count(n, |_, p| p > 0.0),
            ncon,
            "level {level}: contact elements"
        );
        if level == 0 {
            // norm_problm_1p.inp's own comment: "Fn/G=0.1220" [mm^2].
            let fn_over_g_mm2 = n.totals.normal_force_n / 82.0e9 / (MM * MM);
            assert!(
                (fn_over_g_mm2 - 0.1220).abs() <= 0.00005,
                "Fn/G = {fn_over_g_mm2:.5} mm^2"
            );
        }
        let t = solve(&case(
            level,
            &heights,
            Kinematics::Transient(vec![shift_step()]),
        ))
        .unwrap();
        let t = t.last().unwrap();
        assert_eq!(t.info.status, SolveStatus::Converged);
        assert_eq!(
            count(t, |_, p| p > 0.0),
            ncon,
            "level {level}: contact elements of the shift"
        );
        assert_eq!(
            count(t, |st, _| st == ElementState::Slip),
            nslp,
            "level {level}: slip elements"
        );
    }
}
