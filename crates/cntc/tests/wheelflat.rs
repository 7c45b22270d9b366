//! Module 1 on an out-of-round wheel: a wheel slices file (`.slcw`) given
//! to `cntc_setprofileinputfname`, called as a C caller calls it, the
//! wheel's angle facing the rail the wheelset's pitch from
//! `cntc_setwheelsetposition`. A round wheel given as slices is that wheel
//! bit for bit; a wheel with a flat cut as a chord is flat along x at the
//! flat's centre; and Chalmers' measured wheel flat (CONTACT's
//! `examples/wheelflat.inp`, `crates/solver/profiles/S1002_flat.slcw`) is
//! compared with CONTACT's `examples/wheelflat.ref_out` (revision 2707;
//! more digits of the same numbers from CONTACT's own library through its
//! `python_intfc`: `crates/cntc/bench/wheelflat_cases.py`).

mod common;

use std::path::Path;

use common::{
    close, profile, rolling_right_wheel, scratch, set_profile_file_with, wheelrail_element,
};
use contact_addon::ffi::*;
use contact_addon::flags;

/// CONTACT's wheelflat.inp on element `ire` with the wheel file `wheel`
/// smoothed by `smooth` (lambda, ismooth 0: the example's 5) at the pitch
/// angle `pitch_deg`: FZ = 125 kN, the r300_wide rail at gauge 1435 mm and
/// cant 0.02, S1002's flange back at -70 mm of 1360 mm, nominal radius
/// 490 mm, 2000 mm/s with the pitch rate -4.08190679 rad/s, DX = DS =
/// 0.4 mm, Kalker's exact theory (M = 0) with friction 0.3; the calls of
/// crates/cntc/bench/wheelflat_cases.py. Returns the ierror of
/// `cntc_calculate`.
unsafe fn wheelflat(ire: i32, wheel: &str, smooth: f64, pitch_deg: f64) -> i32 {
    rolling_right_wheel(ire, true);
    let icp = -1;
    cntc_setverticalforce(&ire, &125000.0);
    let pot = [0.4, 0.4, std::f64::consts::FRAC_PI_2, 8.0, 4.0];
    cntc_setpotcontact(&ire, &icp, &-1, &5, pot.as_ptr());
    let track = [14.0, 0.0, 1435.0, 0.020, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    cntc_settrackdimensions(&ire, &3, &11, track.as_ptr());
    set_profile_file_with(ire, &profile("r300_wide.prr"), &[0, 0, 0, -1], &[1.0, 0.0]);
    cntc_setwheelsetdimensions(&ire, &3, &3, [1360.0, -70.0, 490.0].as_ptr());
    set_profile_file_with(ire, wheel, &[1, 0, 0, -1], &[1.0, smooth]);
    let pos = [0.0, 0.0, 0.0, 0.0, 0.0, pitch_deg.to_radians()];
    cntc_setwheelsetposition(&ire, &3, &6, pos.as_ptr());
    let vel = [2000.0, 0.0, 0.0, 0.0, 0.0, -4.08190679];
    cntc_setwheelsetvelocity(&ire, &3, &6, vel.as_ptr());
    let mut ierror = 12345;
    cntc_calculate1(&ire, &mut ierror);
    ierror
}

fn finalize(ids: &[i32]) {
    for ire in ids {
        unsafe { cntc_finalize(ire) };
    }
}

fn npatch(ire: i32) -> i32 {
    let mut n = 0;
    unsafe { cntc_getnumcontactpatches(&ire, &mut n) };
    n
}

/// What the reference reports of patch 1: FN, FX, FS, MN [N, N mm], the
/// approach [mm], PMAX [N/mm2], the elements in contact, XCP(TR) and
/// YCP(TR) [mm].
fn reported(ire: i32) -> [f64; 9] {
    let icp = 1;
    let mut out = [0.0; 9];
    let mut loc = [0.0; 38];
    let mut areas = [0.0; 3];
    unsafe {
        let [fnn, fx, fs, mn, pen, pmax, ..] = &mut out;
        cntc_getcontactforces(&ire, &icp, fnn, fx, fs, mn);
        cntc_getpenetration(&ire, &icp, pen);
        cntc_getmaximumpressure(&ire, &icp, pmax);
        cntc_getcontactpatchareas(&ire, &icp, &mut areas[0], &mut areas[1], &mut areas[2]);
        cntc_getcontactlocation(&ire, &icp, &38, loc.as_mut_ptr());
    }
    // The area over that of one 0.4 x 0.4 mm element.
    out[6] = (areas[0] / 0.16).round();
    out[7] = loc[0];
    out[8] = loc[1];
    out
}

/// Everything a patch reports, as bits: forces, approach, location, grid
/// and the undeformed distance and pressure of every element.
fn results_bits(ire: i32) -> Vec<u64> {
    let icp = 1;
    let mut v = vec![0.0; 4 + 1 + 38 + 8];
    unsafe {
        let [f0, f1, f2, f3, pen, rest @ ..] = &mut v[..] else {
            unreachable!()
        };
        cntc_getcontactforces(&ire, &icp, f0, f1, f2, f3);
        cntc_getpenetration(&ire, &icp, pen);
        cntc_getcontactlocation(&ire, &icp, &38, rest.as_mut_ptr());
        cntc_getpotcontact(&ire, &icp, &8, rest[38..].as_mut_ptr());
    }
    let n = (v[43] * v[44]) as usize;
    v.extend(field(ire, n, flags::field::H));
    v.extend(field(ire, n, flags::field::PN));
    v.iter().map(|x| x.to_bits()).collect()
}

fn field(ire: i32, n: usize, ifld: i32) -> Vec<f64> {
    let mut v = vec![0.0; n];
    unsafe { cntc_getfielddata(&ire, &1, &ifld, &(n as i32), v.as_mut_ptr()) };
    v
}

/// Writes a wheel slices file `name` in `dir`: a slice at each angle [rad]
/// of `slices` naming its profile file (relative to `dir`), TH_INTPOL
/// `intpol`.
fn write_slices(dir: &Path, name: &str, intpol: i32, slices: &[(f64, String)]) -> String {
    let slices: Vec<(f64, &str)> = slices.iter().map(|(t, f)| (*t, f.as_str())).collect();
    common::write_slices_file(dir, name, "TH", intpol, &slices)
}
/// The nominal S1002 wheel of the example (a slice of the flat file away
/// from the flat, byte for byte Wheel_section_1.txt of CONTACT's
/// examples/S1002_flat): (y, z) [mm].
fn nominal_points() -> Vec<[f64; 2]> {
    std::fs::read_to_string(profile("S1002_flat/Wheel_section_6.txt"))
        .unwrap()
        .lines()
        .filter_map(|l| {
            let v: Vec<f64> = l
                .split_whitespace()
                .filter_map(|w| w.parse().ok())
                .collect();
            (v.len() >= 2).then(|| [v[0], v[1]])
        })
        .collect()
}

/// The same profile at every slice is the round wheel: every result of
/// the patch bit for bit, unsmoothed and smoothed (each slice smoothed as
/// the single profile is), at pitch angles on a slice and between them,
/// with both splines along theta.
#[test]
fn a_round_wheel_given_as_slices_is_that_wheel_bit_for_bit() {
    let dir = scratch("wheelflat-round");
    let plain = profile("S1002_flat/Wheel_section_6.txt");
    let same: Vec<(f64, String)> = [-0.3, 0.1, 0.25, 0.6, 1.0]
        .iter()
        .map(|t| (*t, plain.clone()))
        .collect();
    let mut ire = 300;
    for intpol in [1, 2] {
        let slices = write_slices(&dir, &format!("round{intpol}.slcw"), intpol, &same);
        for (smooth, pitch) in [(0.0, -14.32394), (5.0, -37.0), (5.0, 30.0)] {
            let (a, b) = (ire, ire + 1);
            ire += 2;
            unsafe {
                assert_eq!(wheelflat(a, &plain, smooth, pitch), 0);
                assert_eq!(wheelflat(b, &slices, smooth, pitch), 0);
            }
            assert_eq!(npatch(a), 1);
            assert_eq!(npatch(b), 1);
            let (ra, rb) = (results_bits(a), results_bits(b));
            let first = ra.iter().zip(&rb).position(|(u, v)| u != v);
            assert!(
                ra.len() == rb.len() && first.is_none(),
                "TH_INTPOL {intpol}, SMOOTH {smooth}, pitch {pitch}: {} and {} values, \
                 the first different: {first:?}",
                ra.len(),
                rb.len()
            );
            finalize(&[a, b]);
        }
    }
}

/// A flat cut as a chord: radius R - d at its centre theta_c, the wheel
/// r(theta) = (R - d) / cos(theta - theta_c) within acos((R - d) / R) of
/// it (R the radius of the profile at each y, d = 0.1 mm across the whole
/// width), round outside. At pitch -theta_c the flat faces the rail and
/// the wheel's lowest points lie on a straight line along x: the
/// undeformed distance of every row is constant in x where the round
/// wheel's grows as x^2 / (2 R) (50 um at 7 mm on R = 490 mm). Slices
/// every 1 mrad (0.49 mm), interpolating spline: its error on the flat,
/// h^4 f'''' / 384 with f = R / cos, is below 1e-12 mm; the kinks of the
/// chord at the flat's ends lie sqrt(2 R d) = 9.9 mm from the centre,
/// beyond the 7 mm held (the spline's wiggle from a kink decays by 0.27
/// per slice: below 1e-5 mm at 5 slices). Held to 1e-4 mm, the solver's
/// tolerance on the geometry (the wheel's y of a row, the planar patch's
/// tilt across the rows), against the 50 um the round wheel gives; and
/// the patch on the flat is longer than on the round wheel.
#[test]
fn a_chord_flat_is_flat_along_x_at_its_centre() {
    let dir = scratch("wheelflat-chord");
    let nominal = nominal_points();
    let (theta_c, d_mm) = (0.6_f64, 0.1_f64);
    let mut slices = Vec::new();
    for k in -120..=120 {
        let dth = k as f64 * 1e-3;
        let name = format!("chord_{}.txt", k + 120);
        let text: String = nominal
            .iter()
            .map(|p| {
                let r = 490.0 + p[1];
                let half = ((r - d_mm) / r).acos();
                let rr = if dth.abs() < half {
                    (r - d_mm) / dth.cos()
                } else {
                    r
                };
                format!("{:.12} {:.12}\n", p[0], rr - 490.0)
            })
            .collect();
        std::fs::write(dir.join(&name), text).unwrap();
        slices.push((theta_c + dth, name));
    }
    let file = write_slices(&dir, "chord.slcw", 1, &slices);
    let round = profile("S1002_flat/Wheel_section_6.txt");
    let (a, b) = (330, 331);
    unsafe {
        assert_eq!(wheelflat(a, &file, 0.0, -theta_c.to_degrees()), 0);
        assert_eq!(wheelflat(b, &round, 0.0, -theta_c.to_degrees()), 0);
        assert_eq!((npatch(a), npatch(b)), (1, 1));
    }
    let grid = |ire: i32| {
        let mut g = [0.0; 8];
        unsafe { cntc_getpotcontact(&ire, &1, &8, g.as_mut_ptr()) };
        g
    };
    for (ire, flat) in [(a, true), (b, false)] {
        let g = grid(ire);
        let (mx, my, x1, dx) = (g[0] as usize, g[1] as usize, g[2], g[4]);
        let h = field(ire, mx * my, flags::field::H);
        let pn = field(ire, mx * my, flags::field::PN);
        // The row carrying the most pressure.
        let iy = (0..my)
            .max_by(|i, j| {
                let s = |r: usize| pn[r * mx..(r + 1) * mx].iter().sum::<f64>();
                s(*i).total_cmp(&s(*j))
            })
            .unwrap();
        let row = &h[iy * mx..(iy + 1) * mx];
        let ix0 = (0..mx)
            .min_by(|i, j| {
                (x1 + *i as f64 * dx)
                    .abs()
                    .total_cmp(&(x1 + *j as f64 * dx).abs())
            })
            .unwrap();
        let mut held = 0;
        for (ix, hx) in row.iter().enumerate() {
            let x = x1 + ix as f64 * dx;
            if x.abs() > 7.0 {
                continue;
            }
            let rise = hx - row[ix0];
            if flat {
                assert!(
                    rise.abs() < 1e-4,
                    "x {x} mm: the flat's distance rises {rise} mm"
                );
            } else if x.abs() > 4.0 {
                // x^2 / (2 R), the round wheel's (within 10 %).
                let round = x * x / (2.0 * 490.0);
                assert!(
                    rise > 0.9 * round,
                    "x {x} mm: the round wheel's rises {rise} mm"
                );
            }
            held += 1;
        }
        assert!(held >= 30, "{held} elements of the row held");
    }
    // On the flat the patch is longer than on the round wheel under the
    // same load.
    let len = |ire: i32| {
        let g = grid(ire);
        let (mx, my) = (g[0] as usize, g[1] as usize);
        let pn = field(ire, mx * my, flags::field::PN);
        (0..mx)
            .filter(|ix| (0..my).any(|iy| pn[iy * mx + ix] > 0.0))
            .count()
    };
    assert!(
        len(a) > len(b) + 5,
        "columns in contact: flat {}, round {}",
        len(a),
        len(b)
    );
    finalize(&[a, b]);
}

/// One case of CONTACT's wheelflat.inp: its pitch angle [deg] and what
/// wheelflat.ref_out reports (FN, FX, FS [N], MN [N mm], APPROACH [mm],
/// PMAX [N/mm2], NCON, XCP(TR), YCP(TR) [mm]).
struct Reference {
    case: usize,
    pitch_deg: f64,
    values: [f64; 9],
}

/// CONTACT's examples/wheelflat.ref_out, cases at several pitch angles
/// (the digits of CONTACT's own library for the same calls where the
/// output file rounds: crates/cntc/bench/wheelflat_cases.py).
const REFERENCE: &[Reference] = &[
    // Case 1, pitch -25 deg: the flat is 24 mm ahead, the round wheel.
    Reference {
        case: 1,
        pitch_deg: -25.0,
        values: [
            124993.0, 7499.29, -1390.12, -7457.92, 0.108244, 1095.8, 1091.0, 0.0, 759.3304,
        ],
    },
    // Case 4, pitch -28 deg: the flat's start reaches the patch's front.
    Reference {
        case: 4,
        pitch_deg: -28.0,
        values: [
            124997.0, 6582.66, -953.159, -6648.06, 0.116935, 1567.7, 1015.0, -0.2233, 759.4313,
        ],
    },
    // Case 7, pitch -31 deg: the patch on the flat's shallow start.
    Reference {
        case: 7,
        pitch_deg: -31.0,
        values: [
            125006.0, 9134.46, -340.596, -8383.68, 0.111326, 1423.5, 1058.0, -2.1204, 759.5063,
        ],
    },
    // Case 13, pitch -37 deg: the flat's deepest part (1.4 mm) faces the
    // rail; the contact moves 14 mm to the field side.
    Reference {
        case: 13,
        pitch_deg: -37.0,
        values: [
            124930.0, 19784.1, 4243.76, 9710.59, 0.145556, 3001.3, 448.0, -1.2482, 773.4586,
        ],
    },
    // Case 23, pitch -47 deg: the flat has left behind.
    Reference {
        case: 23,
        pitch_deg: -47.0,
        values: [
            124993.0, 7727.98, -1392.48, -7408.43, 0.110913, 1100.6, 1112.0, 0.1955, 759.4735,
        ],
    },
];

const NAMES: [&str; 7] = ["FN", "FX", "FS", "MN", "APPROACH", "PMAX", "NCON"];

/// Chalmers' wheel flat against CONTACT's wheelflat.ref_out, held to
/// what this solver gives on a round wheel and to the geometry's limits.
/// Both place the patch's reference at the weighted centre of the
/// interpenetration over x and y (up to 2.1 mm behind the axle in these
/// cases): XCP within 8 um of CONTACT's, YCP within 3.3 um.
///
/// * FN: both meet FZ = 125 kN; FN differs from FZ by the contact angle,
///   found alike: 5e-4 of FN.
/// * FX 0.2 %, APPROACH 0.2 %, PMAX 0.3 %, NCON 0.5 % (measured 0.089 %,
///   0.1 %, 0.14 %, 2 of 1058 elements): on the round wheel (case 1) FX
///   is 0.02 % apart, the approach 0.01 %, PMAX 0.07 %, NCON equal; on the
///   flat the contact's shape follows the flat's edge within an element
///   (0.4 mm), where the flat's height changes by up to 20 um per element.
/// * FS 4 % or 50 N (measured 41 N, 4.3 %, at the flat's start, case 4;
///   0.033 % of FN), MN 5 % (3.7 % at its deepest, case 13): the spin
///   and the wheel's smoothing, as on the round wheel (FS 31 N, 2.2 %;
///   MN 0.65 %) and in the module's other comparisons.
/// * XCP 0.02 mm, YCP 0.01 mm.
#[test]
fn chalmers_wheel_flat_matches_contacts_reference() {
    let wheel = profile("S1002_flat.slcw");
    for (k, r) in REFERENCE.iter().enumerate() {
        let ire = 340 + k as i32;
        unsafe { assert_eq!(wheelflat(ire, &wheel, 5.0, r.pitch_deg), 0) };
        assert_eq!(npatch(ire), 1, "case {}", r.case);
        let ours = reported(ire);
        let [fnn, fx, fs, mn, pen, pmax, ncon, xcp, ycp] = r.values;
        let tolerances = [
            5e-4 * fnn,
            2e-3 * fx.abs(),
            (0.04 * fs.abs()).max(50.0),
            0.05 * mn.abs(),
            2e-3 * pen,
            3e-3 * pmax,
            0.005 * ncon,
        ];
        for (i, tol) in tolerances.iter().enumerate() {
            let what = format!("case {} (pitch {}): {}", r.case, r.pitch_deg, NAMES[i]);
            close(&what, ours[i], r.values[i], *tol);
        }
        let what = |name| format!("case {} (pitch {}): {name}", r.case, r.pitch_deg);
        close(&what("XCP"), ours[7], xcp, 0.02);
        close(&what("YCP"), ours[8], ycp, 0.01);
        unsafe { cntc_finalize(&ire) };
    }
}

/// An input file naming a wheel slices file (WFNAME, CONTACT's
/// wheelflat.inp's first case) configures the element as the calls do.
#[test]
fn an_input_file_takes_a_wheel_slices_file() {
    let dir = scratch("wheelflat-inp");
    let inp = format!(
        "  1 MODULE
 1203100    C-P-B-T-N-F-S   CONFIG, PVTIME, BOUND,  TANG,   NORM,   FORCE,  STRESS
 0022033    V-L-D-C-M-Z-E   VARFRC, FRCLAW, DISCNS, INFLCF, MATER,  ZTRACK, EWHEEL
 0001321    H-G-I-A-O-W-R     HEAT, GAUSEI, IESTIM, MATFIL, OUTPUT, FLOW,   RETURN
    999     100    30    1     1e-5         MAXGS , MAXIN , MAXNR , MAXOUT, EPS
  0.300   0.300                                 FSTAT, FKIN
  0.280   0.280   82000.  82000.                POISS 1,2,  GG 1,2
  0.400   0.400   1.000   90d   8.0   4.0       DX, DS, DQREL, A_SEP, D_SEP, D_COMB
   14.0     0    1435.0   0.020                 GAUGHT, GAUGSQ, GAUGWD, CANT
  '{}'     0   1.0   0.0   -1        RFNAME, MIRRORY, SCALE, SMOOTH, MIRRORZ
     0.0    0.0   0.000   0.0   0.0   0.000     DY, DZ, ROLL, VY, VZ, VROLL
  1360.0  -70.0   490.0                         FBDIST, FBPOS, NOMRAD
  '{}'   0   1.0   5.0   -1        WFNAME, MIRRORY, SCALE, SMOOTH, MIRRORZ
  0.0  0.0  125000. 0.000  0.000   -37.0d      S, Y, FZ, ROLL, YAW, PITCH
 2000. 0.0  0.0    0.0    0.0    -4.08190679    VS,VY,VZ, VROLL,VYAW,VPITCH

  0 MODULE
",
        profile("r300_wide.prr"),
        profile("S1002_flat.slcw")
    );
    let path = dir.join("wheelflat.inp");
    std::fs::write(&path, inp).unwrap();
    let (a, b) = (360, 361);
    unsafe {
        assert_eq!(wheelflat(a, &profile("S1002_flat.slcw"), 5.0, -37.0), 0);
        wheelrail_element(b, &[]);
    }
    assert_eq!(common::read_inp(b, flags::INP_MODUL1, &path), 0);
    let mut ierror = 12345;
    unsafe { cntc_calculate1(&b, &mut ierror) };
    assert_eq!(ierror, 0);
    assert!(results_bits(a) == results_bits(b));
    finalize(&[a, b]);
}

/// What is not built is refused (the messages, naming the line and the
/// keyword, are the solver's: `each_malformed_wheel_line_is_named` in
/// `wheelrail::slices`): features, perturbations, slices closer than
/// 0.001 rad, a wheel slices file given as the rail.
#[test]
fn what_is_not_built_is_refused() {
    let dir = scratch("wheelflat-refused");
    let plain = profile("S1002_flat/Wheel_section_6.txt");
    let good = write_slices(
        &dir,
        "good.slcw",
        2,
        &[(0.0, plain.clone()), (0.5, plain.clone()), (1.0, plain)],
    );
    let ire = 370;
    unsafe { assert_eq!(wheelflat(ire, &good, 0.0, -30.0), 0) };
    let text = std::fs::read_to_string(&good).unwrap();
    for (name, from, to) in [
        ("feat.slcw", "0 0 0   NFEAT", "3 0 0   NFEAT"),
        ("pert.slcw", "2   TH_INTPOL", "2 1   TH_INTPOL"),
        ("close.slcw", "  0.5  ", "  0.0005  "),
    ] {
        let path = dir.join(name);
        std::fs::write(&path, text.replace(from, to)).unwrap();
        let p = path.display().to_string();
        unsafe { assert_ne!(wheelflat(ire, &p, 0.0, -30.0), 0, "{name}") };
    }
    // The rail given as a wheel slices file (ITYPE = 0).
    set_profile_file_with(ire, &good, &[0, 0, 0, -1], &[1.0, 0.0]);
    let mut ierror = 0;
    unsafe { cntc_calculate1(&ire, &mut ierror) };
    assert_ne!(ierror, 0);
    unsafe { cntc_finalize(&ire) };
}
