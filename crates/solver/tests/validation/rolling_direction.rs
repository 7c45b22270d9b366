//! The rolling direction chi and the extra rigid slip per element
//! (`core::frame`, `core::problem` conventions) against Kalker's linear
//! theory and against the +x solutions they must reproduce.

use std::f64::consts::{FRAC_PI_2, PI};

use railcontact_solver::core::cache::KernelCache;
use railcontact_solver::core::creep::kalker_creep_coefficients;
use railcontact_solver::core::grid::Grid;
use railcontact_solver::core::hertz::{hertz, HertzLoad};
use railcontact_solver::core::material::{CombinedMaterial, Material};
use railcontact_solver::core::normal::NormalLoad;
use railcontact_solver::core::problem::{
    ContactProblem, Creepages, ExtraRigidSlip, Friction, Kinematics, ShiftStep, SolverSettings,
};
use railcontact_solver::core::solution::{ContactSolution, ElementState, SolveStatus};
use railcontact_solver::core::solve::{solve, ContactSolver};

const FN: f64 = 1.0e4;

fn material() -> CombinedMaterial {
    CombinedMaterial::identical(Material {
        shear_modulus_pa: 80.0e9,
        poisson_ratio: 0.25,
    })
    .unwrap()
}

/// Hertz semi-axes \[m\] of h = A x² + B y² under [`FN`].
fn semi_axes(a: f64, b: f64) -> (f64, f64) {
    let h = hertz(
        a,
        b,
        material().effective_modulus_pa(),
        HertzLoad::NormalForce { normal_force_n: FN },
    )
    .unwrap();
    (h.semi_axis_x_m, h.semi_axis_y_m)
}

/// h = A x² + B y² on an nx x ny grid 2.4 by 2.6 Hertz semi-axes (the
/// elements are not square), rolling in `chi` with `kin`.
fn problem(a: f64, b: f64, n: [usize; 2], mu: f64, kin: Kinematics, chi: f64) -> ContactProblem {
    let (sa, sb) = semi_axes(a, b);
    let grid = Grid::centered(n[0], n[1], 2.4 * sa, 2.6 * sb).unwrap();
    ContactProblem {
        material: material(),
        friction: Friction::coulomb(mu),
        gap_m: ContactProblem::quadratic_gap(&grid, a, b),
        grid,
        load: NormalLoad::NormalForce(FN),
        kinematics: kin,
        settings: SolverSettings::default(),
        rolling_direction_rad: chi,
        extra_rigid_slip: None,
        numerical_influence: None,
    }
}

fn steady(xi: f64, eta: f64, phi: f64) -> Kinematics {
    Kinematics::SteadyRolling(Creepages {
        creepage_long: xi,
        creepage_lat: eta,
        spin_per_m: phi,
    })
}

fn last(p: &ContactProblem) -> ContactSolution {
    let s = solve(p).unwrap().pop().unwrap();
    assert_eq!(s.info.status, SolveStatus::Converged, "{:?}", s.info);
    s
}

/// Mean x of the adhesion elements \[m\].
fn adhesion_centroid_x(p: &ContactProblem, s: &ContactSolution) -> f64 {
    let g = &p.grid;
    let (mut sum, mut n) = (0.0, 0);
    for iy in 0..g.ny {
        for ix in 0..g.nx {
            if s.fields.state[g.index(ix, iy)] == ElementState::Adhesion {
                sum += g.x_m(ix);
                n += 1;
            }
        }
    }
    assert!(n > 0);
    sum / n as f64
}

fn close(a: f64, b: f64, rel: f64, scale: f64) -> bool {
    (a - b).abs() <= rel * scale
}

#[test]
fn rolling_in_minus_x_mirrors_the_plus_x_solution_and_moves_adhesion_to_the_new_leading_edge() {
    // Partial slip with spin on an ellipse. Rolling in -x (chi = pi) is
    // rolling in +x turned half a turn about n: with the creepages turned
    // too, (xi, eta) -> (-xi, -eta) and phi unchanged, every field is the
    // +x one at (-x, -y) with its vectors reversed. Physically the
    // adhesion area sits at the leading edge, the side the patch rolls to:
    // large x for chi = 0, small x for chi = pi (problem.rs conventions;
    // Johnson 1985, §8.2: the stick zone at the leading edge).
    let (xi, eta, phi) = (4e-4, -2e-4, 0.6);
    let mu = 0.3;
    let plus = problem(1.0, 0.6, [28, 24], mu, steady(-xi, -eta, phi), 0.0);
    let minus = problem(1.0, 0.6, [28, 24], mu, steady(xi, eta, phi), PI);
    let (sp, sm) = (last(&plus), last(&minus));
    let g = plus.grid;
    let tol = 1e-9 * sp.totals.max_pressure_pa;
    for iy in 0..g.ny {
        for ix in 0..g.nx {
            let i = g.index(ix, iy);
            let j = g.index(g.nx - 1 - ix, g.ny - 1 - iy);
            assert!((sm.fields.pressure_pa[i] - sp.fields.pressure_pa[j]).abs() <= tol);
            assert!((sm.fields.traction_x_pa[i] + sp.fields.traction_x_pa[j]).abs() <= tol);
            assert!((sm.fields.traction_y_pa[i] + sp.fields.traction_y_pa[j]).abs() <= tol);
            assert_eq!(sm.fields.state[i], sp.fields.state[j]);
        }
    }
    let t = (&sm.totals, &sp.totals);
    assert!(
        close(t.0.fx_n, -t.1.fx_n, 1e-9, FN),
        "{} {}",
        t.0.fx_n,
        t.1.fx_n
    );
    assert!(close(t.0.fy_n, -t.1.fy_n, 1e-9, FN));
    assert!(close(t.0.mz_nm, t.1.mz_nm, 1e-9, t.1.mz_nm.abs()));
    // The same creepages rolled both ways: the leading edge swaps sides.
    let same = problem(1.0, 0.6, [28, 24], mu, steady(xi, eta, phi), 0.0);
    let ss = last(&same);
    let (forward, backward) = (
        adhesion_centroid_x(&same, &ss),
        adhesion_centroid_x(&minus, &sm),
    );
    eprintln!("adhesion centroid x: chi 0 {forward:.3e} m, chi pi {backward:.3e} m");
    assert!(forward > 0.0 && backward < 0.0);
}

#[test]
fn rolling_in_plus_y_on_a_circle_turns_kalkers_coefficients_with_the_direction() {
    // Reference: Kalker 1990, Table E3 (core::creep::KALKER_TABLE), a/b =
    // 1, nu = 0.25: C11 = 4.12 along the rolling direction, C22 = 3.67
    // across it. Rolling in +y (chi = pi/2) the creepage along the rolling
    // direction is eta: Fy = -G ab C11 eta, Fx = -G ab C22 xi (full
    // adhesion, mu large, vanishing creepage).
    let (xi, eta) = (1e-6, -2e-6);
    let up = problem(1.0, 1.0, [32, 35], 100.0, steady(xi, eta, 0.0), FRAC_PI_2);
    let s = last(&up);
    let (a, b) = semi_axes(1.0, 1.0);
    let k = kalker_creep_coefficients(a / b, 0.25).unwrap();
    let g = material().shear_modulus_pa;
    let along = -s.totals.fy_n / (g * a * b * eta);
    let across = -s.totals.fx_n / (g * a * b * xi);
    eprintln!(
        "chi pi/2: C along {along:.4} vs C11 {:.4}, across {across:.4} vs C22 {:.4}",
        k.c11, k.c22
    );
    assert!((along / k.c11 - 1.0).abs() < 0.03, "{along} vs {}", k.c11);
    assert!((across / k.c22 - 1.0).abs() < 0.03, "{across} vs {}", k.c22);

    // Against the +x solution on the grid turned with it, (x', y') = (y,
    // -x), with the creepages turned, (xi', eta') = (eta, -xi): the forces
    // turn back, Fx = -Fy', Fy = Fx'. Partial slip with spin.
    let (xi, eta, phi) = (3e-4, 5e-4, 0.8);
    let up = problem(1.0, 1.0, [24, 20], 0.3, steady(xi, eta, phi), FRAC_PI_2);
    let su = last(&up);
    let g = up.grid;
    let turned = Grid::new(
        g.ny,
        g.nx,
        g.dy_m,
        g.dx_m,
        g.y0_m,
        -(g.x0_m + g.nx as f64 * g.dx_m),
    )
    .unwrap();
    let plus = ContactProblem {
        gap_m: ContactProblem::quadratic_gap(&turned, 1.0, 1.0),
        grid: turned,
        kinematics: steady(eta, -xi, phi),
        rolling_direction_rad: 0.0,
        ..up.clone()
    };
    let sp = last(&plus);
    let (tu, tp) = (&su.totals, &sp.totals);
    eprintln!(
        "chi pi/2: Fx {:.6} Fy {:.6}; +x turned back: Fx {:.6} Fy {:.6}",
        tu.fx_n, tu.fy_n, -tp.fy_n, tp.fx_n
    );
    assert!(close(tu.fx_n, -tp.fy_n, 1e-8, FN));
    assert!(close(tu.fy_n, tp.fx_n, 1e-8, FN));
    assert!(close(tu.mz_nm, tp.mz_nm, 1e-8, tp.mz_nm.abs()));
    assert_eq!(tu.contact_area_m2, tp.contact_area_m2);
    assert_eq!(tu.patch_length_m, tp.patch_width_m);
}

#[test]
fn transient_rolling_in_minus_x_tends_to_steady_rolling_in_minus_x() {
    // Moving coordinates (problem.rs conventions): rolling steps of one
    // element from rest carry the tractions against the rolling direction
    // and approach the steady state rolled the same way (Kalker 1990,
    // §5.4); here in -x.
    let (xi, eta, phi) = (-3e-4, 1e-4, 0.4);
    let st = problem(1.0, 0.7, [24, 20], 0.3, steady(xi, eta, phi), PI);
    let dq = st.grid.dx_m;
    let c = Creepages {
        creepage_long: xi,
        creepage_lat: eta,
        spin_per_m: phi,
    };
    let steps = vec![ShiftStep::rolling(NormalLoad::NormalForce(FN), dq, &c); 120];
    let tr = ContactProblem {
        kinematics: Kinematics::Transient(steps),
        ..st.clone()
    };
    let s = last(&st);
    let t = solve(&tr).unwrap();
    // Distance to the steady forces relative to mu Fn: with one element
    // per step the limit is the steady solution itself (as in +x,
    // core::solve::tests::transient_rolling_tends_to_steady_rolling), the
    // distance shrinking by some 7 % per step.
    let gap = |x: &ContactSolution| {
        (x.totals.fx_n - s.totals.fx_n)
            .abs()
            .max((x.totals.fy_n - s.totals.fy_n).abs())
            / (0.3 * FN)
    };
    let end = t.last().unwrap();
    eprintln!(
        "chi pi: steady Fx {:.3} Fy {:.3}; rolling step 1 gap {:.3e}, step 120 gap {:.3e}",
        s.totals.fx_n,
        s.totals.fy_n,
        gap(&t[0]),
        gap(end)
    );
    assert!(gap(&t[0]) > 0.1);
    assert!(gap(end) < 1e-3);
    assert_eq!(end.fields.state, s.fields.state);
}

#[test]
fn steps_solved_one_at_a_time_in_minus_y_are_the_whole_sequence_bit_for_bit() {
    // A co-simulation session advances with solve_next_step: rolling in
    // -y (chi = 3 pi/2, a step of dy) it must give the bits of the whole
    // transient problem solved at once.
    let st = problem(1.0, 0.7, [20, 22], 0.3, steady(1e-4, -3e-4, 0.3), 1.5 * PI);
    let c = Creepages {
        creepage_long: 1e-4,
        creepage_lat: -3e-4,
        spin_per_m: 0.3,
    };
    let step = ShiftStep::rolling(NormalLoad::NormalForce(FN), st.grid.dy_m, &c);
    let p = ContactProblem {
        kinematics: Kinematics::Transient(vec![step; 6]),
        ..st
    };
    let whole = solve(&p).unwrap();
    let mut solver = ContactSolver::new(&p, KernelCache::global());
    for (k, w) in whole.iter().enumerate() {
        let one = solver.solve_next_step(&p, &step).unwrap();
        assert_eq!(one.fields, w.fields, "step {k}");
        assert_eq!(
            format!("{:?}", one.totals),
            format!("{:?}", w.totals),
            "step {k}"
        );
    }
    // A step of dx is no whole number of elements along y here.
    let dx = ShiftStep::rolling(NormalLoad::NormalForce(FN), p.grid.dx_m, &c);
    let e = solver.solve_next_step(&p, &dx).unwrap_err();
    assert_eq!(e.key(), Some("step.rolling_m"));
}

#[test]
fn a_uniform_extra_rigid_slip_is_a_changed_creepage() {
    // w + e = (xi + e_x - phi y, eta + e_y + phi x): steady rolling and
    // transient rolling steps (dq e added to the shift) alike.
    let (xi, eta, phi) = (2e-4, -1e-4, 0.5);
    let (ex, ey) = (-3e-4, 2.5e-4);
    for chi in [0.0, PI] {
        let base = problem(1.0, 0.6, [24, 20], 0.3, steady(xi, eta, phi), chi);
        let mut extra = base.clone();
        extra.extra_rigid_slip = Some(ExtraRigidSlip::uniform(&base.grid, ex, ey));
        let changed = ContactProblem {
            kinematics: steady(xi + ex, eta + ey, phi),
            ..base.clone()
        };
        let (a, b) = (last(&extra), last(&changed));
        eprintln!(
            "chi {chi}: extra slip Fx {:.6} Fy {:.6}; creepage Fx {:.6} Fy {:.6}",
            a.totals.fx_n, a.totals.fy_n, b.totals.fx_n, b.totals.fy_n
        );
        assert!(close(a.totals.fx_n, b.totals.fx_n, 1e-8, FN));
        assert!(close(a.totals.fy_n, b.totals.fy_n, 1e-8, FN));
        assert!(close(
            a.totals.mz_nm,
            b.totals.mz_nm,
            1e-8,
            b.totals.mz_nm.abs()
        ));

        let dq = base.grid.dx_m;
        let roll = |c: Creepages| {
            Kinematics::Transient(vec![
                ShiftStep::rolling(NormalLoad::NormalForce(FN), dq, &c);
                5
            ])
        };
        let c = Creepages {
            creepage_long: xi,
            creepage_lat: eta,
            spin_per_m: phi,
        };
        let mut extra = ContactProblem {
            kinematics: roll(c),
            ..base.clone()
        };
        extra.extra_rigid_slip = Some(ExtraRigidSlip::uniform(&base.grid, ex, ey));
        let changed = ContactProblem {
            kinematics: roll(Creepages {
                creepage_long: xi + ex,
                creepage_lat: eta + ey,
                spin_per_m: phi,
            }),
            ..base.clone()
        };
        let (a, b) = (solve(&extra).unwrap(), solve(&changed).unwrap());
        for (a, b) in a.iter().zip(&b) {
            assert!(close(a.totals.fx_n, b.totals.fx_n, 1e-8, FN));
            assert!(close(a.totals.fy_n, b.totals.fy_n, 1e-8, FN));
        }
    }
}

#[test]
fn a_uniform_extra_shift_is_a_changed_step_shift() {
    // CONTACT's EXRHS in a shift case: an extra rigid shift (ex, ey) [m]
    // in every element of every shift step is the step's shift changed by
    // it; mixed with rolling steps, those take the extra slip. Both ways,
    // rolling in +x and -x.
    let (ex, ey) = (2e-7, -1.5e-7);
    for chi in [0.0, PI] {
        let base = problem(1.0, 0.6, [24, 20], 0.3, Kinematics::Frictionless, chi);
        let load = NormalLoad::NormalForce(FN);
        let shift = |x: f64, y: f64| ShiftStep {
            load,
            shift_x_m: x,
            shift_y_m: y,
            rotation_rad: 1e-4,
            rolling_m: 0.0,
        };
        let c = Creepages {
            creepage_long: 2e-4,
            creepage_lat: 0.0,
            spin_per_m: 0.3,
        };
        let rolled = ShiftStep::rolling(load, base.grid.dx_m, &c);
        let steps = |d: [f64; 2]| {
            Kinematics::Transient(vec![
                shift(1e-7 + d[0], d[1]),
                shift(-2e-7 + d[0], 3e-7 + d[1]),
                rolled,
            ])
        };
        let mut extra = ExtraRigidSlip::uniform_shift(&base.grid, ex, ey);
        extra.slip_x = vec![0.0; base.grid.len()];
        extra.slip_y = vec![0.0; base.grid.len()];
        let with = ContactProblem {
            kinematics: steps([0.0, 0.0]),
            extra_rigid_slip: Some(extra),
            ..base.clone()
        };
        let changed = ContactProblem {
            kinematics: steps([ex, ey]),
            ..base.clone()
        };
        let (a, b) = (solve(&with).unwrap(), solve(&changed).unwrap());
        for (k, (a, b)) in a.iter().zip(&b).enumerate() {
            eprintln!(
                "chi {chi} step {k}: extra shift Fx {:.6} Fy {:.6}; shift Fx {:.6} Fy {:.6}",
                a.totals.fx_n, a.totals.fy_n, b.totals.fx_n, b.totals.fy_n
            );
            assert!(close(a.totals.fx_n, b.totals.fx_n, 1e-8, FN));
            assert!(close(a.totals.fy_n, b.totals.fy_n, 1e-8, FN));
        }
        // A shift step needs the shift, steady rolling refuses it.
        let slip_only = ContactProblem {
            extra_rigid_slip: Some(ExtraRigidSlip::uniform(&base.grid, ex, ey)),
            ..with.clone()
        };
        let key = |p: &ContactProblem| solve(p).unwrap_err().key().map(str::to_string);
        assert_eq!(
            key(&slip_only).as_deref(),
            Some("extra_rigid_slip.shift_x_m")
        );
        let steady_shift = ContactProblem {
            kinematics: steady(2e-4, 0.0, 0.3),
            extra_rigid_slip: Some(ExtraRigidSlip::uniform_shift(&base.grid, ex, ey)),
            ..base.clone()
        };
        assert_eq!(
            key(&steady_shift).as_deref(),
            Some("extra_rigid_slip.shift_x_m")
        );
    }
}

#[test]
fn a_full_turn_is_no_turn_bit_for_bit() {
    let p = problem(1.0, 0.6, [20, 20], 0.3, steady(3e-4, 1e-4, 0.5), 0.0);
    let turned = ContactProblem {
        rolling_direction_rad: 2.0 * PI,
        ..p.clone()
    };
    assert_eq!(
        format!("{:?}", last(&p).totals),
        format!("{:?}", last(&turned).totals)
    );
}

#[test]
fn bad_rolling_directions_and_extra_slips_are_refused_naming_the_key() {
    let p = problem(1.0, 0.6, [16, 16], 0.3, steady(3e-4, 0.0, 0.0), 0.0);
    let key = |p: &ContactProblem| solve(p).unwrap_err().key().map(str::to_string);
    // 0.3: steady rolling rolls along a grid axis.
    for chi in [f64::NAN, f64::INFINITY, 0.3] {
        let bad = ContactProblem {
            rolling_direction_rad: chi,
            ..p.clone()
        };
        assert_eq!(key(&bad).as_deref(), Some("rolling_direction_rad"), "{chi}");
    }
    let mut short = p.clone();
    short.extra_rigid_slip = Some(ExtraRigidSlip {
        slip_x: vec![0.0; 7],
        slip_y: vec![0.0; p.grid.len()],
        ..ExtraRigidSlip::default()
    });
    assert_eq!(key(&short).as_deref(), Some("extra_rigid_slip.slip_x"));
    let mut half = p.clone();
    half.extra_rigid_slip = Some(ExtraRigidSlip {
        slip_x: vec![0.0; p.grid.len()],
        slip_y: vec![0.0; p.grid.len()],
        shift_y_m: vec![0.0; p.grid.len()],
        ..ExtraRigidSlip::default()
    });
    assert_eq!(key(&half).as_deref(), Some("extra_rigid_slip.shift_y_m"));
    let mut nan = p.clone();
    let mut e = ExtraRigidSlip::uniform(&p.grid, 0.0, 0.0);
    e.slip_y[5] = f64::NAN;
    nan.extra_rigid_slip = Some(e);
    assert_eq!(key(&nan).as_deref(), Some("extra_rigid_slip.slip_y[5]"));
    let mut frictionless = p.clone();
    frictionless.kinematics = Kinematics::Frictionless;
    frictionless.extra_rigid_slip = Some(ExtraRigidSlip::uniform(&p.grid, 0.0, 0.0));
    assert_eq!(key(&frictionless).as_deref(), Some("extra_rigid_slip"));
}

/// Forces (Fx, Fy) and moment Mz of the last of `steps` transient rolling
/// steps of dq = `dq_elements` x the smaller element side at `chi`, from
/// rest, on a circle (A = B = 1 /m) with `n` x `n` elements.
fn rolled(n: usize, mu: f64, chi: f64, c: Creepages, dq_elements: f64, steps: usize) -> [f64; 3] {
    let base = problem(1.0, 1.0, [n, n], mu, Kinematics::Frictionless, chi);
    let dq = dq_elements * base.grid.dx_m.min(base.grid.dy_m);
    let p = ContactProblem {
        kinematics: Kinematics::Transient(vec![
            ShiftStep::rolling(
                NormalLoad::NormalForce(FN),
                dq,
                &c
            );
            steps
        ]),
        ..base
    };
    let s = solve(&p).unwrap().pop().unwrap();
    assert_eq!(s.info.status, SolveStatus::Converged, "{:?}", s.info);
    [s.totals.fx_n, s.totals.fy_n, s.totals.mz_nm]
}

/// `v` turned by `chi` about n.
fn turned([x, y]: [f64; 2], chi: f64) -> [f64; 2] {
    let (s, c) = chi.sin_cos();
    [c * x - s * y, s * x + c * y]
}

#[test]
fn oblique_transient_rolling_on_a_circle_is_the_plus_x_solution_turned() {
    // A circular contact of identical bodies is isotropic: turning the
    // rolling direction and the creepages together by chi turns the whole
    // problem, so the continuum's forces are the chi = 0 ones turned by chi
    // and Mz is unchanged. Off the grid's axes the rolling steps carry the
    // tractions between element centres (bilinear, core::frame); the
    // difference to the axis solution on the same grid is that
    // discretisation's, and it must fall as the grid is refined. Reference
    // for the limit: the +x rolling steps of one element, whose limit is
    // steady rolling (rolling_direction tests above).
    let chi = 0.5;
    let (along, across, phi) = (-3e-4, 2e-4, 0.4);
    let mu = 0.3;
    let mut errors = Vec::new();
    for (n, steps) in [(20, 100), (40, 200)] {
        let c0 = Creepages {
            creepage_long: along,
            creepage_lat: across,
            spin_per_m: phi,
        };
        let [xi, eta] = turned([along, across], chi);
        let c = Creepages {
            creepage_long: xi,
            creepage_lat: eta,
            spin_per_m: phi,
        };
        let axis = rolled(n, mu, 0.0, c0, 1.0, steps);
        let oblique = rolled(n, mu, chi, c, 1.0, steps);
        let [fx, fy] = turned([axis[0], axis[1]], chi);
        let error = (oblique[0] - fx).hypot(oblique[1] - fy) / (mu * FN);
        let moment = (oblique[2] - axis[2]).abs() / axis[2].abs();
        eprintln!(
            "{n} x {n}: chi 0 turned Fx {fx:.3} Fy {fy:.3} Mz {:.5}; chi {chi} Fx {:.3} Fy {:.3} \
             Mz {:.5}; |dF|/(mu Fn) {error:.3e}, dMz {moment:.3e}",
            axis[2], oblique[0], oblique[1], oblique[2]
        );
        errors.push([error, moment]);
    }
    // Measured: |dF|/(mu Fn) 2.77e-3 on 20 x 20 and 1.66e-3 on 40 x 40, Mz
    // 1.9 % and 1.2 %. Bounds: twice the coarse grid's, and refining must
    // reduce both by a fifth at least.
    assert!(errors[0][0] < 6e-3 && errors[0][1] < 0.04, "{errors:?}");
    for k in 0..2 {
        assert!(errors[1][k] < 0.8 * errors[0][k], "{errors:?}");
    }
}

#[test]
fn oblique_rolling_in_full_adhesion_gives_kalkers_coefficients_along_and_across() {
    // Reference: Kalker 1990, Table E3 (core::creep::KALKER_TABLE), a/b =
    // 1, nu = 0.25: C11 = 4.12 along the rolling direction, C22 = 3.67
    // across it, whatever the direction on a circle. Rolling at chi = 0.6
    // rad in steps of one element, full adhesion (mu large, vanishing
    // creepage), the force turned into (along, across) gives them.
    let chi = 0.6;
    let (along, across) = (1e-6, -2e-6);
    let [xi, eta] = turned([along, across], chi);
    let c = Creepages {
        creepage_long: xi,
        creepage_lat: eta,
        spin_per_m: 0.0,
    };
    let f = rolled(32, 100.0, chi, c, 1.0, 150);
    let [f_along, f_across] = turned([f[0], f[1]], -chi);
    let (a, b) = semi_axes(1.0, 1.0);
    let k = kalker_creep_coefficients(a / b, 0.25).unwrap();
    let g = material().shear_modulus_pa;
    let c_along = -f_along / (g * a * b * along);
    let c_across = -f_across / (g * a * b * across);
    eprintln!(
        "chi {chi}: C along {c_along:.4} vs C11 {:.4}, across {c_across:.4} vs C22 {:.4}",
        k.c11, k.c22
    );
    assert!(
        (c_along / k.c11 - 1.0).abs() < 0.03,
        "{c_along} vs {}",
        k.c11
    );
    assert!(
        (c_across / k.c22 - 1.0).abs() < 0.03,
        "{c_across} vs {}",
        k.c22
    );
}

#[test]
fn oblique_directions_roll_transient_steps_only() {
    // Steady rolling is refused off the axes, naming the key; a transient
    // step off the axes may be any distance within the grid.
    let p = problem(1.0, 0.6, [16, 16], 0.3, steady(3e-4, 0.0, 0.0), 0.3);
    assert_eq!(solve(&p).unwrap_err().key(), Some("rolling_direction_rad"));
    let c = Creepages {
        creepage_long: 3e-4,
        creepage_lat: 0.0,
        spin_per_m: 0.0,
    };
    let step = |dq: f64| ShiftStep::rolling(NormalLoad::NormalForce(FN), dq, &c);
    let half = ContactProblem {
        kinematics: Kinematics::Transient(vec![step(0.37 * p.grid.dx_m); 3]),
        ..p.clone()
    };
    assert_eq!(solve(&half).unwrap().len(), 3);
    let far = ContactProblem {
        kinematics: Kinematics::Transient(vec![step(20.0 * p.grid.dx_m)]),
        ..p
    };
    assert_eq!(
        solve(&far).unwrap_err().key(),
        Some("transient.steps[0].rolling_m")
    );
}
