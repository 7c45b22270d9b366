//! Numerical influence coefficients from a file (`core::numerical_influence`,
//! CONTACT's C3 = 9, issue 42) against the half-space's own coefficients
//! and against CONTACT's program reading the same files.
//!
//! The files are written from the half-space's piecewise-constant
//! coefficients (C3 = 2) of the case's grid and materials: a file of them
//! must reproduce the half-space solution, to the rounding of its printed
//! digits. CONTACT's example file (`inflcf_r10_mx51.txt`) is not
//! available; `tests/data/inflcf/` holds the files given to CONTACT here.

use std::sync::Arc;

use railcontact_solver::core::cache::KernelCache;
use railcontact_solver::core::error::ContactError;
use railcontact_solver::core::grid::Grid;
use railcontact_solver::core::influence::{Component, HalfSpaceInfluence, KernelKind};
use railcontact_solver::core::material::{CombinedMaterial, Material};
use railcontact_solver::core::normal::NormalLoad;
use railcontact_solver::core::numerical_influence::{InfluenceFile, UpperBody};
use railcontact_solver::core::problem::{
    ContactProblem, Creepages, Friction, Kinematics, ShiftStep, SolverSettings,
    NUMERICAL_INFLUENCE_KEY,
};
use railcontact_solver::core::solution::{ContactSolution, ElementState, SolveStatus};
use railcontact_solver::core::solve::solve;
use railcontact_solver::problem::case::Case;
use railcontact_solver::problem::CaseError;

use crate::printed;

/// CONTACT's units: mm, N/mm² (= 1e6 Pa).
const MM: f64 = 1e-3;
const N_PER_MM2: f64 = 1e6;

/// The case of `tests/data/inflcf/inflcf.inp`: 21 x 17 elements of 0.4 x
/// 0.4 mm, POISS 0.28 / 0.20, GG 82000 / 60000 N/mm² (dissimilar: the
/// normal/tangential coupling K != 0), h = 0.0025 x² + 0.0035 y² \[mm\],
/// FN = 12000 N, steady rolling with CKSI, CETA = -0.0012, 0.0008 and CPHI
/// (0 in the .inp, see [`contact_reads_the_same_files`]), FSTAT = FKIN =
/// 0.3.
const NX: usize = 21;
const NY: usize = 17;
const D_MM: f64 = 0.4;
const FN_N: f64 = 12000.0;

fn material() -> CombinedMaterial {
    CombinedMaterial::new(
        Material {
            shear_modulus_pa: 82000.0 * N_PER_MM2,
            poisson_ratio: 0.28,
        },
        Material {
            shear_modulus_pa: 60000.0 * N_PER_MM2,
            poisson_ratio: 0.20,
        },
    )
    .unwrap()
}

fn grid() -> Grid {
    Grid::centered(NX, NY, NX as f64 * D_MM * MM, NY as f64 * D_MM * MM).unwrap()
}

fn problem(table: Option<InfluenceFile>, spin_per_mm: f64) -> ContactProblem {
    problem_on(grid(), 0.0035, FN_N, table, spin_per_mm)
}

/// [`problem`] on `grid` with B = `b_per_mm` \[1/mm\] and FN = `fn_n`.
fn problem_on(
    grid: Grid,
    b_per_mm: f64,
    fn_n: f64,
    table: Option<InfluenceFile>,
    spin_per_mm: f64,
) -> ContactProblem {
    ContactProblem {
        material: material(),
        friction: Friction::coulomb(0.3),
        gap_m: ContactProblem::quadratic_gap(&grid, 0.0025 / MM, b_per_mm / MM),
        grid,
        load: NormalLoad::NormalForce(fn_n),
        kinematics: Kinematics::SteadyRolling(Creepages {
            creepage_long: -0.0012,
            creepage_lat: 0.0008,
            spin_per_m: spin_per_mm / MM,
        }),
        settings: SolverSettings::default(),
        rolling_direction_rad: 0.0,
        extra_rigid_slip: None,
        numerical_influence: table.map(Arc::new),
    }
}

/// A file of `matrices` matrices on an mx x my grid holding the
/// half-space's coefficients of [`material`] (C \[mm\] = A G 1e3), matrix
/// m scaled by `scale(m)`.
fn half_space_file(
    matrices: usize,
    (mx, my): (usize, usize),
    scale: impl Fn(usize) -> f64,
) -> InfluenceFile {
    let m = material();
    let d = D_MM * MM;
    let ic = HalfSpaceInfluence::new(d, d, &m);
    let g = m.shear_modulus_pa;
    InfluenceFile::from_coefficients(
        matrices,
        (mx, my),
        (d, d),
        UpperBody::Rail,
        |k, i, j, ox, oy| scale(k) * ic.coefficient(i, j, ox as f64 * d, oy as f64 * d) * g * 1e3,
    )
    .unwrap()
}

fn one(p: &ContactProblem) -> ContactSolution {
    let s = solve(p).unwrap().pop().unwrap();
    assert_eq!(s.info.status, SolveStatus::Converged, "{:?}", s.info);
    s
}

fn counts(s: &ContactSolution) -> [usize; 2] {
    let st = &s.fields.state;
    [
        st.iter().filter(|&&e| e == ElementState::Adhesion).count(),
        st.iter().filter(|&&e| e == ElementState::Slip).count(),
    ]
}

/// The totals CONTACT prints: FN, FX, FY \[N\], MZ \[N mm\], PMAX \[N/mm²\],
/// PEN \[mm\].
fn printed_totals(s: &ContactSolution) -> [f64; 6] {
    let t = &s.totals;
    [
        t.normal_force_n,
        t.fx_n,
        t.fy_n,
        t.mz_nm * 1e3,
        t.max_pressure_pa / N_PER_MM2,
        t.approach_m / MM,
    ]
}

#[test]
fn half_space_file_reproduces_the_half_space() {
    // The coefficients written with 10 significant digits (5e-10 relative
    // each) and read back: the steady-rolling solution of the half-space
    // (C3 = 2), normal and tangential, to that rounding.
    let file = half_space_file(1, (NX, NY), |_| 1.0);
    assert!(file.coupled(), "dissimilar bodies: coupling coefficients");
    let printed = InfluenceFile::parse(&file.to_text(10)).unwrap();
    let exact = one(&problem(None, 0.0004));
    let table = one(&problem(Some(printed), 0.0004));
    let (a, b) = (printed_totals(&exact), printed_totals(&table));
    eprintln!("half-space {a:?}\nfile       {b:?}");
    for (k, what) in ["FN", "FX", "FY", "MZ", "PMAX", "PEN"].iter().enumerate() {
        assert!(
            (a[k] - b[k]).abs() <= 1e-8 * a[k].abs(),
            "{what}: half-space {} against the file's {}",
            a[k],
            b[k]
        );
    }
    assert_eq!(counts(&exact), counts(&table));
    for (p, q) in exact
        .fields
        .pressure_pa
        .iter()
        .zip(&table.fields.pressure_pa)
    {
        assert!((p - q).abs() <= 1e-8 * exact.totals.max_pressure_pa);
    }
    // The coupling is in the answer: the same file without it moves the
    // solution far beyond that rounding.
    let uncoupled = InfluenceFile::from_coefficients(
        1,
        (NX, NY),
        (D_MM * MM, D_MM * MM),
        UpperBody::Rail,
        |m, i, j, ox, oy| {
            let c = file.coefficient_mm(m, i, j, ox, oy);
            if (i == Component::N) != (j == Component::N) {
                0.0
            } else {
                c
            }
        },
    )
    .unwrap();
    let plain = one(&problem(Some(uncoupled), 0.0004));
    assert!((plain.totals.fx_n - exact.totals.fx_n).abs() > 1e-5 * exact.totals.fx_n.abs());
}

/// Significant digits of the coefficients in the files given to CONTACT
/// (8 in the per-row file, to keep it small).
const FILE_DIGITS: usize = 10;

/// The files of `tests/data/inflcf/`: the half-space's coefficients of the
/// case's grid (`inflcf_hs.txt`), of a smaller grid (13 x 9: CONTACT pads
/// the offsets beyond it with zeros) and of a larger one (23 x 19: the
/// offsets beyond the case's grid are not used), and a file of one
/// matrix per row ([`rows_file`]), with their significant digits.
fn contact_files() -> Vec<(&'static str, InfluenceFile, usize)> {
    vec![
        (
            "inflcf_hs.txt",
            half_space_file(1, (NX, NY), |_| 1.0),
            FILE_DIGITS,
        ),
        (
            "inflcf_hs_small.txt",
            half_space_file(1, (13, 9), |_| 1.0),
            FILE_DIGITS,
        ),
        (
            "inflcf_hs_large.txt",
            half_space_file(1, (23, 19), |_| 1.0),
            FILE_DIGITS,
        ),
        ("inflcf_rows.txt", rows_file(), 8),
    ]
}

fn data_path(name: &str) -> String {
    format!("{}/tests/data/inflcf/{name}", env!("CARGO_MANIFEST_DIR"))
}

/// Writes [`contact_files`] into `tests/data/inflcf/` (run by hand:
/// `cargo test -p railcontact-solver --test validation -- --ignored
/// write_contact_files`).
#[test]
#[ignore = "writes the test data; run by hand"]
fn write_contact_files() {
    for (name, file, digits) in contact_files() {
        std::fs::write(data_path(name), file.to_text(digits)).unwrap();
    }
}

#[test]
fn committed_files_are_the_generated_ones() {
    for (name, file, digits) in contact_files() {
        let committed = InfluenceFile::read(std::path::Path::new(&data_path(name))).unwrap();
        let printed = InfluenceFile::parse(&file.to_text(digits)).unwrap();
        assert!(
            committed == printed,
            "{name} is not what contact_files() writes"
        );
    }
}

/// CONTACT's printed FN, FX, FY \[N\], MZ \[N mm\], PMAX \[N/mm²\],
/// APPROACH \[mm\] and NCON, NADH, NSLIP for one case of `inflcf.inp`.
struct Reference {
    file: Option<&'static str>,
    totals: [&'static str; 6],
    con_adh_slip: [usize; 3],
}

/// CONTACT's numbers for the half-space's coefficients (its cases 1, 2
/// and 4).
const HALF_SPACE_TOTALS: [&str; 6] = [
    "1.200E+04",
    "2217.",
    "-1079.",
    "438.1",
    "889.1",
    "3.869E-02",
];
const HALF_SPACE_COUNTS: [usize; 3] = [133, 63, 70];

/// `tests/data/inflcf/inflcf.inp` run by CONTACT's program
/// (github.com/eve70a/CONTACT revision 2707, 2025-07-23, built by
/// `/work/shared/contact-kit/build.sh` with gfortran 12.2.0 and FFTW
/// 3.3.10) on 2026-12-07: `contact_linux64 2 inflcf` in a folder holding
/// the .inp and the four files; the numbers of its `inflcf.out`, cases
/// 1-4 (cases 5-6: [`CONTACT_ROWS`]).
const CONTACT: [Reference; 4] = [
    // Case 1: the half-space (C3 = 2).
    Reference {
        file: None,
        totals: HALF_SPACE_TOTALS,
        con_adh_slip: HALF_SPACE_COUNTS,
    },
    // Case 2: its coefficients from `inflcf_hs.txt` (C3 = 9): the same
    // numbers, so CONTACT's coefficients are the file's (same directions
    // and signs, the coupling of the dissimilar bodies included).
    Reference {
        file: Some("inflcf_hs.txt"),
        totals: HALF_SPACE_TOTALS,
        con_adh_slip: HALF_SPACE_COUNTS,
    },
    // Case 3: the 13 x 9 file, padded with zeros ("WARNING: file of
    // infl.cf. has smaller grid than CONTACT, padding with zeros").
    Reference {
        file: Some("inflcf_hs_small.txt"),
        totals: [
            "1.200E+04",
            "2122.",
            "-1059.",
            "462.9",
            "876.2",
            "3.826E-02",
        ],
        con_adh_slip: [143, 67, 76],
    },
    // Case 4: the 23 x 19 file, its offsets beyond the grid unused.
    Reference {
        file: Some("inflcf_hs_large.txt"),
        totals: HALF_SPACE_TOTALS,
        con_adh_slip: HALF_SPACE_COUNTS,
    },
];

#[test]
fn contact_reads_the_same_files() {
    // Without spin: CONTACT takes the spin's rigid slip at x + dx/6, the
    // solver at the element centre (`physics::conformal_case_1`).
    for r in &CONTACT {
        let table = r
            .file
            .map(|f| InfluenceFile::read(std::path::Path::new(&data_path(f))).unwrap());
        check_contact(r, &one(&problem(table, 0.0)));
    }
}

/// Our solution `s` against CONTACT's printed numbers `r`: each within
/// half a unit of the last digit printed, the counts equal.
fn check_contact(r: &Reference, s: &ContactSolution) {
    let ours = printed_totals(s);
    let [adh, slip] = counts(s);
    for (k, what) in ["FN", "FX", "FY", "MZ", "PMAX", "PEN"].iter().enumerate() {
        let (value, half) = printed(r.totals[k]);
        assert!(
            (ours[k] - value).abs() <= half * (1.0 + 1e-9),
            "{:?} {what}: {} against CONTACT's {}",
            r.file,
            ours[k],
            r.totals[k]
        );
    }
    assert_eq!([adh + slip, adh, slip], r.con_adh_slip, "{:?}", r.file);
}

/// `examples/cases/numerical_influence.toml`: the case of CONTACT's case 2
/// as a case file, its `material.influence_file` relative to the case
/// file's directory.
fn example_case(text: &str) -> Result<Case, CaseError> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/cases");
    Case::from_toml_in(text, &dir)
}

#[test]
fn case_files_name_the_file() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/cases/numerical_influence.toml"
    );
    let text = std::fs::read_to_string(path).unwrap();
    let case = example_case(&text).unwrap();
    assert!(
        case.notes
            .iter()
            .any(|n| n.contains("nmatrix = 1, mxfile x myfile = 21 x 17")),
        "{:?}",
        case.notes
    );
    let s = one(&case.problem().unwrap());
    check_contact(&CONTACT[1], &s);
    // Errors name the key (and the file's field or line).
    let err = |t: &str| match example_case(t) {
        Err(CaseError::BadInput(m)) => m,
        Err(e) => panic!("{e:?}"),
        Ok(_) => panic!("accepted"),
    };
    let m = err(&text.replace("inflcf_hs.txt", "absent.txt"));
    assert!(
        m.contains("material.influence_file") && m.contains("absent.txt"),
        "{m}"
    );
    let m = err(&text.replace("window_x_m = 0.0084", "window_x_m = 0.0088"));
    assert!(m.contains("material.influence_file: dxfile"), "{m}");
    let m = err(&text.replace("model = \"exact\"", "model = \"fastsim\""));
    assert!(
        m.contains("material.influence_file") && m.contains("fastsim"),
        "{m}"
    );
    let m = err(&text.replacen(
        "model = \"exact\"",
        "model = \"exact\"\nrolling_direction_rad = 3.141592653589793",
        1,
    ));
    assert!(
        m.contains("material.influence_file") && m.contains("+x"),
        "{m}"
    );
}

#[test]
fn per_row_files_sum_the_rows() {
    // One matrix per loaded row (nmatrix = my = 17), all the half-space's:
    // the row-by-row products give the one-matrix answer.
    let rows = half_space_file(NY, (NX, NY), |_| 1.0);
    assert_eq!(rows.matrices(), NY);
    let one_matrix = one(&problem(
        Some(half_space_file(1, (NX, NY), |_| 1.0)),
        0.0004,
    ));
    let per_row = one(&problem(Some(rows), 0.0004));
    let (a, b) = (printed_totals(&one_matrix), printed_totals(&per_row));
    eprintln!("one matrix {a:?}\nper row    {b:?}");
    for k in 0..6 {
        assert!((a[k] - b[k]).abs() <= 1e-9 * a[k].abs(), "{k}: {a:?} {b:?}");
    }
    assert_eq!(counts(&one_matrix), counts(&per_row));
    // The memory MAX_PER_ROW_WORK bounds: ny + 1 sets of the grid, under
    // 0.5 kB per element and set.
    let cache = KernelCache::new(usize::MAX);
    let table = Arc::new(half_space_file(NY, (NX, NY), |_| 1.0));
    let set = cache.get_numerical(&grid(), &material(), Some(&table), KernelKind::Displacement);
    let per_element = set.bytes() as f64 / ((NY + 1) * NX * NY) as f64;
    eprintln!(
        "per-row kernels: {} bytes, {per_element:.0} per element and set",
        set.bytes()
    );
    assert!(per_element < 500.0, "{per_element}");
    // A per-row file on a grid whose rows x elements exceed the limit
    // (128 x 128 x 128 = 2^21): refused before any kernel is built.
    let d = D_MM * MM;
    let big = Grid::centered(128, 128, 128.0 * d, 128.0 * d).unwrap();
    let tiny =
        InfluenceFile::from_coefficients(128, (1, 1), (d, d), UpperBody::Rail, |_, _, _, _, _| 0.1)
            .unwrap();
    let (key, reason) = refusal(&problem_on(big, 0.0035, FN_N, Some(tiny), 0.0));
    assert_eq!(key, NUMERICAL_INFLUENCE_KEY);
    assert!(reason.contains("2097152 over 1048576"), "{reason}");
    // nmatrix neither 1 nor my: the field is named.
    let wrong = half_space_file(3, (NX, NY), |_| 1.0);
    let (key, _) = refusal(&problem(Some(wrong), 0.0));
    assert_eq!(key, format!("{NUMERICAL_INFLUENCE_KEY}: nmatrix"));
}

/// The key and reason of the invalid input `p` is refused for.
fn refusal(p: &ContactProblem) -> (String, String) {
    match solve(p) {
        Err(ContactError::InvalidInput { key, reason }) => (key, reason),
        other => panic!("{:?}", other.map(|s| s.len())),
    }
}

/// The grid of `inflcf.inp` case 5: 13 x 9 elements of 0.4 mm.
fn small_grid() -> Grid {
    Grid::centered(13, 9, 13.0 * D_MM * MM, 9.0 * D_MM * MM).unwrap()
}

/// `inflcf_rows.txt`: one matrix per row of the 13 x 9 grid, row jy's
/// the half-space's times 0.8 + 0.05 jy (0.8 .. 1.2).
fn rows_file() -> InfluenceFile {
    half_space_file(9, (13, 9), |m| 0.8 + 0.05 * m as f64)
}

/// `inflcf.inp` cases 5 and 6 (as [`CONTACT`]): on the 13 x 9 grid, h =
/// 0.0025 x² + 0.006 y² \[mm\], FN = 3000 N, the per-row file (C3 = 9;
/// CONTACT skips the four lines that start each matrix, the last of them
/// the matrix line) and the half-space (C3 = 2): the rows' scaling moves
/// MZ from 57.77 to 82.72 N mm.
const CONTACT_ROWS: [Reference; 2] = [
    Reference {
        file: Some("inflcf_rows.txt"),
        totals: ["3000.", "654.6", "-346.1", "82.72", "679.8", "1.658E-02"],
        con_adh_slip: [42, 14, 28],
    },
    Reference {
        file: None,
        totals: ["3000.", "653.0", "-351.0", "57.77", "680.8", "1.663E-02"],
        con_adh_slip: [42, 14, 28],
    },
];

#[test]
fn per_row_file_against_contact() {
    for r in &CONTACT_ROWS {
        let table = r
            .file
            .map(|f| InfluenceFile::read(std::path::Path::new(&data_path(f))).unwrap());
        check_contact(
            r,
            &one(&problem_on(small_grid(), 0.006, 3000.0, table, 0.0)),
        );
    }
}

#[test]
fn transient_steps_take_the_file() {
    // Two shift steps and one rolling step of one element: the half-space,
    // its one-matrix file and its per-row file (equal rows) give the same
    // tractions, to the file's rounding.
    let step = |shift_mm: f64, rolling_m: f64| ShiftStep {
        load: NormalLoad::NormalForce(FN_N),
        shift_x_m: shift_mm * MM,
        shift_y_m: 0.5 * shift_mm * MM,
        rotation_rad: 0.0,
        rolling_m,
    };
    let steps = vec![
        step(-0.004, 0.0),
        step(-0.004, 0.0),
        step(-0.002, D_MM * MM),
    ];
    let run = |table: Option<InfluenceFile>| {
        let mut p = problem(table, 0.0);
        p.kinematics = Kinematics::Transient(steps.clone());
        let all = solve(&p).unwrap();
        assert!(all.iter().all(|s| s.info.status == SolveStatus::Converged));
        all.iter().map(printed_totals).collect::<Vec<_>>()
    };
    let exact = run(None);
    let file = InfluenceFile::parse(&half_space_file(1, (NX, NY), |_| 1.0).to_text(FILE_DIGITS));
    for totals in [
        run(Some(file.unwrap())),
        run(Some(half_space_file(NY, (NX, NY), |_| 1.0))),
    ] {
        for (a, b) in exact.iter().zip(&totals) {
            for k in 0..6 {
                assert!((a[k] - b[k]).abs() <= 1e-8 * a[k].abs(), "{k}: {a:?} {b:?}");
            }
        }
    }
    eprintln!("{exact:?}");
}
