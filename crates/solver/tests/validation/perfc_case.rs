//! The wheel-on-rail case of CONTACT's performance tests
//! (github.com/eve70a/CONTACT, `perfc_test/norm_problm_{1,2,4,8}p.inp` and
//! `tang_problm_*.inp`): the undeformed distance of
//! `tests/data/perfc_wheel_gap_mm.txt` (IBASE = 2), approach 0.02084 mm
//! ("PEN"), G = 82 GPa and nu = 0.28 for both bodies, mu = 0.3, on the
//! inputs' grids from (-3.55, -6.15) mm. Shared by the validation test
//! `perfc` and `benches/perfc.rs` (included there by path).

use railcontact_solver::core::grid::Grid;
use railcontact_solver::core::material::{CombinedMaterial, Material};
use railcontact_solver::core::normal::NormalLoad;
use railcontact_solver::core::problem::{ContactProblem, Friction, Kinematics, ShiftStep};

pub const MM: f64 = 1e-3;
/// The inputs' "PEN" \[m\].
pub const APPROACH_M: f64 = 0.02084 * MM;

/// (nx, ny, element size [mm]) of the inputs' "MX, MY, DX" for
/// `*_1*`, `*_2*`, `*_4*` and `*_8*`.
pub const GRIDS: [(usize, usize, f64); 4] = [
    (71, 81, 0.1),
    (143, 163, 0.05),
    (287, 323, 0.025),
    (575, 647, 0.0125),
];

/// The heights b(y) \[m\] of the data file.
pub fn heights_m() -> Vec<f64> {
    let heights: Vec<f64> = include_str!("../data/perfc_wheel_gap_mm.txt")
        .lines()
        .filter(|l| !l.starts_with('#'))
        .flat_map(|l| l.split_whitespace().map(|v| v.parse::<f64>().unwrap() * MM))
        .collect();
    assert_eq!(heights.len(), 271, "NN of the inputs");
    heights
}

/// The case on grid `level` (0 to 3: `GRIDS`) with `kinematics`.
pub fn case(level: usize, heights: &[f64], kinematics: Kinematics) -> ContactProblem {
    let (nx, ny, d) = GRIDS[level];
    let grid = Grid::new(nx, ny, d * MM, d * MM, -3.55 * MM, -6.15 * MM).unwrap();
    let steel = Material {
        shear_modulus_pa: 82.0e9,
        poisson_ratio: 0.28,
    };
    ContactProblem {
        material: CombinedMaterial::identical(steel).unwrap(),
        friction: Friction::coulomb(0.3),
        gap_m: circular_profile_gap(&grid, heights),
        grid,
        load: NormalLoad::Approach(APPROACH_M),
        kinematics,
        settings: Default::default(),
        rolling_direction_rad: 0.0,
        extra_rigid_slip: None,
        numerical_influence: None,
    }
}

/// `tang_problm_*s.inp`: one shift from the unloaded state, CKSI = 0.0005
/// mm, CETA = -0.001 mm, CPHI = 0.0008, read as a rotation of 0.0008 rad
/// about the origin (the reading under which the slip counts agree).
pub fn shift_step() -> ShiftStep {
    ShiftStep {
        load: NormalLoad::Approach(APPROACH_M),
        shift_x_m: 0.0005 * MM,
        shift_y_m: -0.001 * MM,
        rotation_rad: 0.0008,
        rolling_m: 0.0,
    }
}

/// CONTACT's IBASE = 2, "circular in x, piecewise linear in y": h = b(y) +
/// r - sqrt(r² - (x - x_m)²), with the inputs' XM = 0, RY1 = 483.931 mm and
/// the heights b at y = Y1 + k DY1 (Y1 = -12 mm, DY1 = 0.1 mm), interpolated
/// linearly and held beyond both ends.
fn circular_profile_gap(grid: &Grid, heights: &[f64]) -> Vec<f64> {
    let (r, y_first, dy) = (483.931 * MM, -12.0 * MM, 0.1 * MM);
    let last = heights.len() - 1;
    let root: Vec<f64> = (0..grid.nx)
        .map(|ix| {
            let x = grid.x_m(ix);
            (r * r - x * x).sqrt()
        })
        .collect();
    let mut h = vec![0.0; grid.len()];
    for iy in 0..grid.ny {
        let t = ((grid.y_m(iy) - y_first) / dy).clamp(0.0, last as f64);
        let k = (t.floor() as usize).min(last - 1);
        let f = t - k as f64;
        let b = heights[k] * (1.0 - f) + heights[k + 1] * f;
        for (ix, root) in root.iter().enumerate() {
            h[grid.index(ix, iy)] = b + r - root;
        }
    }
    h
}
