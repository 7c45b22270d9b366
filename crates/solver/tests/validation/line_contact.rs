//! Line contact (two dimensions, plane strain) against Carter's closed
//! form and CONTACT's 2-D examples `carter2d` and `bentall`. Each
//! reference number names its source.
//!
//! CONTACT's examples are from its public repository
//! (github.com/eve70a/CONTACT, `examples/carter2d.inp`, `.ref_out` and
//! `examples/bentall.inp`, `.ref_out`, commit 424e4e6, CONTACT revision
//! 2356, 2023-05-10). Their 2-D mode puts one row of elements across the
//! length DY of the cylinders (carter2d 200 mm, bentall 1000 mm), so their
//! forces over DY are forces per metre here. The approach in carter2d's
//! output is that of a displacement datum at the distance DY (ours is at
//! 1 m: the approaches differ by 2 P' ln(1 m / DY) / (pi E*), checked
//! below).

use railcontact_solver::core::cache::KernelCache;
use railcontact_solver::core::force::{
    solve_prescribed_force, ForceControlSettings, PrescribedForce,
};
use railcontact_solver::core::grid::Grid;
use railcontact_solver::core::material::{CombinedMaterial, Material};
use railcontact_solver::core::normal::NormalLoad;
use railcontact_solver::core::problem::{
    ContactProblem, Creepages, Friction, Kinematics, SolverSettings,
};
use railcontact_solver::core::solution::{ContactSolution, ElementState, SolveStatus};
use railcontact_solver::core::solve::{solve, ContactSolver};

use std::f64::consts::PI;

/// A line contact on `grid` with h = A x², load `force_n_per_m` \[N/m\],
/// rolling with `xi`.
fn rolling_line(
    mat: CombinedMaterial,
    grid: Grid,
    a_per_m: f64,
    force_n_per_m: f64,
    mu: f64,
    xi: f64,
) -> ContactProblem {
    ContactProblem {
        material: mat,
        friction: Friction::coulomb(mu),
        gap_m: ContactProblem::quadratic_gap(&grid, a_per_m, 0.0),
        grid,
        load: NormalLoad::NormalForce(force_n_per_m),
        kinematics: Kinematics::SteadyRolling(Creepages {
            creepage_long: xi,
            creepage_lat: 0.0,
            spin_per_m: 0.0,
        }),
        settings: SolverSettings::default(),
        rolling_direction_rad: 0.0,
        extra_rigid_slip: None,
        numerical_influence: None,
    }
}

pub(crate) fn one(p: &ContactProblem) -> ContactSolution {
    let s = solve(p).unwrap().pop().unwrap();
    assert_eq!(s.info.status, SolveStatus::Converged, "{:?}", s.info);
    s
}

/// Elements in contact, in adhesion and in slip.
pub(crate) fn counts(s: &ContactSolution) -> [usize; 3] {
    let n = |st: ElementState| s.fields.state.iter().filter(|&&e| e == st).count();
    let contact = s.fields.pressure_pa.iter().filter(|&&p| p > 0.0).count();
    [contact, n(ElementState::Adhesion), n(ElementState::Slip)]
}

fn within_one(got: [usize; 3], want: [usize; 3], what: &str) {
    for k in 0..3 {
        assert!(
            got[k].abs_diff(want[k]) <= 1,
            "{what}: counts (contact, adhesion, slip) {got:?} vs CONTACT {want:?}"
        );
    }
}

pub(crate) fn rel(got: f64, want: f64) -> f64 {
    (got / want - 1.0).abs()
}

/// The mean deviation over the contact |x| < a (the L1 norm over 2a) of
/// the traction p_x / `scale` from the closed form of Carter and Cattaneo,
/// sqrt(1 - x²/a²) - (c/a) sqrt(1 - (x - d)²/c²), the second term where
/// |x - d| < c.
fn mean_deviation(s: &ContactSolution, grid: &Grid, a: f64, c: f64, d: f64, scale: f64) -> f64 {
    let mut l1 = 0.0;
    for ix in 0..grid.nx {
        let x = grid.x_m(ix);
        if x.abs() >= a {
            continue;
        }
        let mut want = (1.0 - (x / a).powi(2)).sqrt();
        if (x - d).abs() < c {
            want -= (c / a) * (1.0 - ((x - d) / c).powi(2)).sqrt();
        }
        l1 += (s.fields.traction_x_pa[ix] / scale - want).abs() * grid.dx_m;
    }
    l1 / (2.0 * a)
}

/// CONTACT's carter2d material: G = 82000 N/mm², nu = 0.28, both bodies.
fn carter_material() -> CombinedMaterial {
    CombinedMaterial::identical(Material {
        shear_modulus_pa: 82.0e9,
        poisson_ratio: 0.28,
    })
    .unwrap()
}

#[test]
fn carter_closed_form_force_adhesion_zone_and_tractions() {
    // Reference: Carter (1926); Johnson 1985 §8.2 (eqs. 8.31-8.34).
    // Identical cylinders, h = x²/(2R), line load P': half-width
    // a = sqrt(4 P' R / (pi E*)), E* = G/(1 - nu), p0 = 2 P'/(pi a).
    // Rolling with creepage xi (0 < |xi| < mu a/R) the adhesion zone is
    // [a - 2c, a] at the leading edge with c/a = 1 - |xi| R/(mu a); the
    // traction is q(x) = -sign(xi) mu p0 (sqrt(1 - x²/a²)
    // - (c/a) sqrt(1 - (x - a + c)²/c²)), the second term in adhesion
    // only, and Fx/(mu P') = -sign(xi) (1 - (c/a)²).
    let mat = carter_material();
    let nu = 0.28;
    let estar = 82.0e9 / (1.0 - nu);
    let (a_curv, mu) = (1.0, 0.3);
    let r = 0.5 / a_curv;
    let half = 1.0e-3;
    let load = PI * half * half * estar / (4.0 * r);
    let p0 = 2.0 * load / (PI * half);
    // 400 strips over 2.2a: 364 across the contact.
    let grid = Grid::line(400, 2.2 * half).unwrap();
    let xi_sat = mu * half / r;
    let mut worst_force: f64 = 0.0;
    for q in [0.25, 0.5, 0.75] {
        let xi = q * xi_sat;
        let s = one(&rolling_line(mat, grid, a_curv, load, mu, xi));
        let c = half * (1.0 - q);
        let want = -(1.0 - (c / half).powi(2));
        let got = s.totals.fx_n / (mu * s.totals.normal_force_n);
        eprintln!("xi/xi_sat {q}: Fx/(mu P') {got:.5} vs Carter {want:.5}");
        worst_force = worst_force.max(rel(got, want));
        // The adhesion zone: its length 2c and its place at the leading
        // edge, within one strip each.
        let adh: Vec<f64> = (0..grid.nx)
            .filter(|&ix| s.fields.state[ix] == ElementState::Adhesion)
            .map(|ix| grid.x_m(ix))
            .collect();
        let length = adh.len() as f64 * grid.dx_m;
        assert!(
            (length - 2.0 * c).abs() <= grid.dx_m,
            "q {q}: adhesion zone {length} m vs Carter {} m",
            2.0 * c
        );
        let (lo, hi) = (adh[0], adh[adh.len() - 1]);
        assert!(
            (lo - (half - 2.0 * c)).abs() <= 1.5 * grid.dx_m
                && (hi - half).abs() <= 1.5 * grid.dx_m,
            "q {q}: adhesion from {lo} to {hi} m vs Carter [{}, {half}] m",
            half - 2.0 * c
        );
        // The traction distribution: the mean deviation over the contact
        // (the L1 norm of q - q_Carter over 2a), relative to mu p0. (At
        // single strips next to the stick/slip boundary, which a strip
        // resolves to dx, the deviation reaches 7e-3 mu p0.)
        let mean = mean_deviation(&s, &grid, half, c, half - c, -mu * p0);
        eprintln!("xi/xi_sat {q}: traction's mean deviation {mean:.2e} mu p0");
        assert!(
            mean < 5e-3,
            "q {q}: traction off by {mean} mu p0 on average"
        );
    }
    assert!(
        worst_force < 5e-3,
        "worst relative deviation of Fx/(mu P') {worst_force}"
    );
}

#[test]
fn contact_carter2d() {
    // carter2d.inp: FN = 35780 N over DY = 200 mm (178 900 N/m), B1 =
    // 0.001/mm (A = 1/m), 55 elements of DX = 0.04 mm, the first centred at
    // XC1 = -1.05 mm, mu 0.3, CKSI = -0.00024. carter2d.ref_out: FX = 6955
    // N (34 775 N/m), FX/FSTAT/FN 0.6480, PMAX 113.9 N/mm², APPROACH
    // 6.492e-3 mm, NCON 50, NADH 30, NSLIP 20.
    let mat = carter_material();
    let grid = Grid::line_from(55, 0.04e-3, -1.07e-3).unwrap();
    let s = one(&rolling_line(mat, grid, 1.0, 178_900.0, 0.3, -2.4e-4));
    let t = s.totals;
    eprintln!("carter2d: {t:?}");
    assert!(rel(t.fx_n, 34_775.0) < 0.01, "Fx {} N/m", t.fx_n);
    assert!(
        rel(t.fx_n / (0.3 * t.normal_force_n), 0.6480) < 0.01,
        "Fx/(mu Fn)"
    );
    assert!(
        rel(t.max_pressure_pa, 113.9e6) < 0.01,
        "pmax {}",
        t.max_pressure_pa
    );
    within_one(counts(&s), [50, 30, 20], "carter2d");
    // The approach with CONTACT's reference distance DY = 0.2 m:
    // ours - 2 P' ln(1 m / 0.2 m) / (pi E*).
    let estar = 82.0e9 / (1.0 - 0.28);
    let theirs = t.approach_m - 2.0 * 178_900.0 * (1.0f64 / 0.2).ln() / (PI * estar);
    assert!(rel(theirs, 6.492e-6) < 0.01, "approach {theirs} m");
}

/// Bentall's rollers (bentall.inp): aluminium, body 1 (G 23000 N/mm², nu
/// 0.31), on steel (82000 N/mm², 0.28), R1 = R2 = 50 mm (B1 = 0.020/mm:
/// A = 20/m), FN = 16201.9 N over DY = 1000 mm, 216 elements of 1 µm
/// from -0.108 mm.
fn bentall(mu: f64) -> ContactProblem {
    let mat = CombinedMaterial::new(
        Material {
            shear_modulus_pa: 23.0e9,
            poisson_ratio: 0.31,
        },
        Material {
            shear_modulus_pa: 82.0e9,
            poisson_ratio: 0.28,
        },
    )
    .unwrap();
    let grid = Grid::line(216, 0.216e-3).unwrap();
    rolling_line(mat, grid, 20.0, 16_201.9, mu, 0.0)
}

/// Solves `p` for the longitudinal force per metre `fx`.
pub(crate) fn with_force(p: &ContactProblem, fx: f64) -> (ContactSolution, f64) {
    let mut solver = ContactSolver::new(p, KernelCache::global());
    let f = solve_prescribed_force(
        &mut solver,
        p,
        PrescribedForce {
            force_x_n: Some(fx),
            force_y_n: None,
        },
        ForceControlSettings::default(),
    )
    .unwrap();
    assert!(f.converged);
    assert_eq!(
        f.solution.info.status,
        SolveStatus::Converged,
        "{:?}",
        f.solution.info
    );
    (f.solution, f.creepages.creepage_long)
}

/// bentall.ref_out, cases 2-6, prescribed FX with CONTACT's rolling
/// direction CHI = 180 deg (mu, Fx/(mu Fn) in CONTACT, CREEP X, PMAX
/// [N/mm²], NCON, NADH, NSLIP):
///   case 2: 1e-4, 0, 5.260e-4, 103.1, 200, 1, 199 (full slip:
///           Bentall & Johnson 1967, Int. J. Mech. Sci. 9)
///   case 3: 10, 0, 3.591e-4, 103.8, 200, 200, 0 (full adhesion: Bufler)
///   case 4: 0.05, 0, 4.294e-4, 103.6, 200, 125, 75
///   case 5: 0.05, 0.75, 2.108e-4, 103.2, 200, 36, 164
///   case 6: 0.05, -0.75, 5.392e-4, 103.3, 201, 106, 95
const BENTALL_CASES: [(f64, f64, f64, f64, [usize; 3]); 5] = [
    (1e-4, 0.0, 5.260e-4, 103.1e6, [200, 1, 199]),
    (10.0, 0.0, 3.591e-4, 103.8e6, [200, 200, 0]),
    (0.05, 0.0, 4.294e-4, 103.6e6, [200, 125, 75]),
    (0.05, 0.75, 2.108e-4, 103.2e6, [200, 36, 164]),
    (0.05, -0.75, 5.392e-4, 103.3e6, [201, 106, 95]),
];

/// bentall.ref_out, case 4, "FORM OF THE CONTACT, ADHESION AND SLIP-AREA`S"
/// (Chi = 180 degrees): grid columns 8 to 209 (our elements 7 to 208), `o`
/// exterior, `S` slip, `*` adhesion; the adhesion area at the leading edge,
/// small x.
const BENTALL_CASE_4_AREAS: &str = "oSSSSSSSSSSSSSSSSSSSSSSSSSSSSSSSS*********************************************************************************************************************SSSSSSSSSSSSSSSSSSSSSSSSSSSSSSSSSSS********SSSSSSSSo";

/// Runs [`BENTALL_CASES`] rolling in `chi_rad`: 0 is CONTACT's case
/// mirrored in x to our +x rolling, which reverses the creepage and the
/// force (the materials keep their sign of K under the mirror); pi is
/// CONTACT's case as it states it. Returns case 4's solution.
fn bentall_cases(chi_rad: f64) -> ContactSolution {
    let sign = if chi_rad == 0.0 { -1.0 } else { 1.0 };
    let mut case_4 = None;
    for (mu, f_rel, creep, pmax, want) in BENTALL_CASES {
        let p = ContactProblem {
            rolling_direction_rad: chi_rad,
            ..bentall(mu)
        };
        let (s, xi) = with_force(&p, sign * f_rel * mu * 16_201.9);
        eprintln!(
            "bentall chi {chi_rad}, mu {mu}, Fx/(mu Fn) {f_rel}: xi {xi:.4e} (CONTACT {:.4e}), counts {:?}, pmax {:.4e} Pa",
            sign * creep,
            counts(&s),
            s.totals.max_pressure_pa
        );
        assert!(
            rel(sign * xi, creep) < 0.01,
            "mu {mu}, F {f_rel}: creepage {xi} vs CONTACT {}",
            sign * creep
        );
        assert!(
            rel(s.totals.max_pressure_pa, pmax) < 0.01,
            "mu {mu}, F {f_rel}: pmax {} Pa vs CONTACT {pmax}",
            s.totals.max_pressure_pa
        );
        within_one(counts(&s), want, &format!("bentall mu {mu}, F {f_rel}"));
        if mu == 0.05 && f_rel == 0.0 {
            case_4 = Some(s);
        }
    }
    case_4.unwrap()
}

#[test]
fn contact_bentall_aluminium_on_steel() {
    bentall_cases(0.0);
}

#[test]
fn contact_bentall_rolling_in_minus_x_as_contact_states_it() {
    // CHI = 180 deg given as it is (core::frame): the creepages and forces
    // of bentall.ref_out without a mirror, and the adhesion and slip areas
    // element by element where CONTACT drew them: each of the four
    // boundaries between them within one element.
    let s = bentall_cases(PI);
    let drawn: Vec<char> = BENTALL_CASE_4_AREAS.chars().collect();
    let ours: Vec<char> = (0..drawn.len())
        .map(|k| {
            let i = 7 + k;
            match s.fields.state[i] {
                _ if s.fields.pressure_pa[i] <= 0.0 => 'o',
                ElementState::Adhesion => '*',
                _ => 'S',
            }
        })
        .collect();
    let differ = drawn.iter().zip(&ours).filter(|(a, b)| a != b).count();
    eprintln!(
        "bentall case 4, chi pi: {differ} elements differ from CONTACT's picture\n{}",
        ours.iter().collect::<String>()
    );
    assert!(differ <= 4, "{differ} elements differ");
}

#[test]
fn a_stalled_newton_solve_restarts_after_a_short_march() {
    // Bentall's rollers at mu 0.05 rolling freely (xi = 0) from rest: in
    // the first normal/tangential alternation Newton stalls in a cycle of
    // active sets. Time marching from its iterate then took its whole
    // limit of 2000 iterations (2057 tangential iterations in all, 12 s),
    // and the solve still said converged, the later alternations having
    // converged. Newton again after 50 marching iterations converges in a
    // few steps: the same answer in about 110 iterations.
    let p = bentall(0.05);
    let s = one(&p);
    assert!(
        s.info.tangential_iterations < 300,
        "{} tangential iterations",
        s.info.tangential_iterations
    );
    // The answer of a solve warm-started from it (one more alternation).
    let mut solver = ContactSolver::new(&p, KernelCache::global());
    let first = solver.solve(&p).unwrap().pop().unwrap();
    let again = solver.solve(&p).unwrap().pop().unwrap();
    let fmax = 0.05 * first.totals.normal_force_n;
    assert!(
        (first.totals.fx_n - again.totals.fx_n).abs() < 1e-6 * fmax,
        "{} vs {} N/m",
        first.totals.fx_n,
        again.totals.fx_n
    );
    assert_eq!(first.totals.fx_n, s.totals.fx_n);
}

#[test]
fn the_note_of_a_limit_names_the_key_that_raises_it() {
    // Bentall's rollers with full adhesion (mu 5): two alternations are
    // not enough for the coupled solution; the note named
    // `[solver] max_iterations`, which changes nothing here.
    use railcontact_solver::problem::case::Case;
    use railcontact_solver::problem::ExactRun;
    let text = |solver: &str| {
        format!(
            r#"
[material.body1]
shear_modulus_pa = 23.0e9
poisson_ratio = 0.31
[material.body2]
shear_modulus_pa = 82.0e9
poisson_ratio = 0.28
[friction]
coefficient = 5.0
[geometry]
kind = "line"
a_per_m = 20.0
[load]
normal_force_n_per_m = 16201.9
[rolling]
creepage_long = -3.591e-4
[grid]
nx = 216
window_x_m = 0.216e-3
[solver]
{solver}
"#
        )
    };
    for (solver, key, other) in [
        (
            "coupling_max_iterations = 2",
            "`solver.coupling_max_iterations`",
            "`solver.max_iterations`",
        ),
        // One tangential iteration is too few when the pressures are
        // solved to 1e-10 (at the default 1e-6 the first suffices here).
        (
            "max_iterations = 1\nnormal_tolerance = 1e-10",
            "`solver.max_iterations`",
            "`solver.coupling_max_iterations`",
        ),
    ] {
        let case = Case::from_toml(&text(solver)).unwrap();
        let run = ExactRun::solve(&case).unwrap();
        let report = run.report(&case, false);
        assert_eq!(report.totals.status, SolveStatus::MaxIterations, "{solver}");
        let notes = report.notes.join("\n");
        assert!(notes.contains(key), "{solver}: {notes}");
        assert!(!notes.contains(other), "{solver}: {notes}");
    }
}

#[test]
fn cattaneo_shift_of_cylinders() {
    // Reference: Cattaneo (1938), Mindlin (1949) in two dimensions;
    // Johnson 1985 §7.2: cylinders pressed together by P' and then shifted
    // with a tangential force Q' < mu P' stick in the centre, |x| < c with
    // c/a = sqrt(1 - |Q'|/(mu P')), and slip outside; the traction is
    // q(x) = mu p0 (sqrt(1 - x²/a²) - (c/a) sqrt(1 - x²/c²)) (second term
    // in the stick zone only), opposing the shift. The shift that gives Q'
    // depends on the datum of the displacements; c/a and q do not.
    use railcontact_solver::core::problem::ShiftStep;
    let mat = carter_material();
    let estar = 82.0e9 / (1.0 - 0.28);
    let (a_curv, mu, half) = (1.0, 0.3, 1.0e-3);
    let load = PI * half * half * estar / (4.0 * 0.5 / a_curv);
    let p0 = 2.0 * load / (PI * half);
    let grid = Grid::line(400, 2.2 * half).unwrap();
    let step = |shift_x_m: f64| ShiftStep {
        load: NormalLoad::NormalForce(load),
        shift_x_m,
        shift_y_m: 0.0,
        rotation_rad: 0.0,
        rolling_m: 0.0,
    };
    let p = ContactProblem {
        kinematics: Kinematics::Transient(vec![step(0.0), step(1.0e-6)]),
        ..rolling_line(mat, grid, a_curv, load, mu, 0.0)
    };
    let s = solve(&p).unwrap().pop().unwrap();
    assert_eq!(s.info.status, SolveStatus::Converged, "{:?}", s.info);
    let ratio = -s.totals.fx_n / (mu * s.totals.normal_force_n);
    assert!(
        ratio > 0.2 && ratio < 0.9,
        "partial slip wanted: Q'/(mu P') {ratio}"
    );
    let c = half * (1.0 - ratio).sqrt();
    let stick = s
        .fields
        .state
        .iter()
        .filter(|&&e| e == ElementState::Adhesion)
        .count() as f64
        * grid.dx_m;
    eprintln!(
        "Q'/(mu P') {ratio:.4}: stick zone {stick:e} m vs Cattaneo {:e} m",
        2.0 * c
    );
    assert!(
        (stick - 2.0 * c).abs() <= 2.0 * grid.dx_m,
        "stick zone {stick} m vs Cattaneo {} m",
        2.0 * c
    );
    let mean = mean_deviation(&s, &grid, half, c, 0.0, -mu * p0);
    eprintln!("traction's mean deviation {mean:.2e} mu p0");
    assert!(mean < 5e-3, "traction off by {mean} mu p0 on average");
}
