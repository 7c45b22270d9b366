//! Module 1 on a rail whose profile varies along the track: a rail slices
//! file (`.slcs`) given to `cntc_setprofileinputfname`, called as a C
//! caller calls it. A constant rail given as slices is the constant rail
//! bit for bit; a rail rising linearly along the track adds its slope to
//! each element's undeformed distance; and the S1002 wheel on the UK
//! crossing nose (slices 66-75 of CONTACT's `testbank/profiles/
//! uk_crossing.slcs`, `crates/solver/profiles/uk_crossing_nose.slcs`) is
//! compared with what CONTACT's own library (revision 2707) returned for
//! the same calls through its `python_intfc`
//! (`crates/cntc/bench/slices_cases.py`, the case named in each test).

mod common;

use std::path::Path;

use common::{
    close, mbench_locus as solve, profile, read_inp, scratch, wheel_results, wheelrail_element,
    Load, MBENCH_RIGHT_INP,
};
use contact_addon::ffi::*;
use contact_addon::flags;
use railcontact_solver::wheelrail::load_profile;

fn npatch(ire: i32) -> i32 {
    let mut n = 0;
    unsafe { cntc_getnumcontactpatches(&ire, &mut n) };
    n
}

/// Everything a patch reports: forces, creepages, approach, location,
/// grid and the undeformed distance of every element.
fn results(ire: i32, icp: i32) -> Vec<f64> {
    let mut out = vec![0.0; 4 + 3 + 1 + 38 + 8];
    unsafe {
        let [f0, f1, f2, f3, c0, c1, c2, pen, rest @ ..] = &mut out[..] else {
            unreachable!()
        };
        cntc_getcontactforces(&ire, &icp, f0, f1, f2, f3);
        cntc_getcreepages(&ire, &icp, c0, c1, c2);
        cntc_getpenetration(&ire, &icp, pen);
        cntc_getcontactlocation(&ire, &icp, &38, rest.as_mut_ptr());
        cntc_getpotcontact(&ire, &icp, &8, rest[38..].as_mut_ptr());
    }
    let (mx, my) = (out[46] as usize, out[47] as usize);
    out.extend(field(ire, icp, mx * my, flags::field::H));
    out
}

fn field(ire: i32, icp: i32, n: usize, ifld: i32) -> Vec<f64> {
    let mut v = vec![0.0; n];
    unsafe { cntc_getfielddata(&ire, &icp, &ifld, &(n as i32), v.as_mut_ptr()) };
    v
}

/// Writes a slices file `name` in `dir` with a slice at each u [mm] of
/// `slices` naming its profile file (relative to `dir`).
fn write_slices(dir: &Path, name: &str, slices: &[(f64, &str)]) -> String {
    common::write_slices_file(dir, name, "U", 1, slices)
}

/// Writes the UIC60 rail of the Manchester benchmark as a two-column file
/// (mm, CONTACT's orientation) lowered by `dz_mm`.
fn write_uic60(dir: &Path, name: &str, dz_mm: f64) {
    let p = load_profile(profile("MBench_UIC60_v3.prr")).unwrap();
    let text: String = p
        .points()
        .iter()
        .map(|q| format!("{:.17e} {:.17e}\n", q[0] * 1e3, q[1] * 1e3 + dz_mm))
        .collect();
    std::fs::write(dir.join(name), text).unwrap();
}

/// The same profile at every slice is the constant rail: every result of
/// the patch, bit for bit, at a wheelset position between the slices and
/// on one.
#[test]
fn a_constant_rail_given_as_slices_is_that_rail_bit_for_bit() {
    let dir = scratch("slices-constant");
    write_uic60(&dir, "uic60.txt", 0.0);
    let slices = write_slices(
        &dir,
        "constant.slcs",
        &[
            (-200.0, "uic60.txt"),
            (0.0, "uic60.txt"),
            (150.0, "uic60.txt"),
            (300.0, "uic60.txt"),
        ],
    );
    let plain = dir.join("uic60.txt").display().to_string();
    for (k, (s, y)) in [(37.5, 0.0), (0.0, 3.0), (-120.0, -2.0)]
        .into_iter()
        .enumerate()
    {
        let (a, b) = (110 + 2 * k as i32, 111 + 2 * k as i32);
        unsafe {
            assert_eq!(solve(a, &plain, 1.0, (s, y, 0.0), Load::Force(1e4)), 0);
            assert_eq!(solve(b, &slices, 1.0, (s, y, 0.0), Load::Force(1e4)), 0);
        }
        assert!(npatch(a) >= 1);
        assert_eq!(npatch(a), npatch(b));
        for icp in 1..=npatch(a) {
            let (ra, rb) = (results(a, icp), results(b, icp));
            assert_eq!(ra.len(), rb.len());
            for (i, (u, v)) in ra.iter().zip(&rb).enumerate() {
                assert_eq!(
                    u.to_bits(),
                    v.to_bits(),
                    "S {s}, patch {icp}, value {i}: {u} != {v}"
                );
            }
        }
        unsafe {
            cntc_finalize(&a);
            cntc_finalize(&b);
        }
    }
}

/// A rail rising along the track by 1 mm per 100 mm (each slice the UIC60
/// rail raised by u / 100), and one falling as much: the slice at the
/// wheelset's S is the plain rail, so at the same wheelset height (that of
/// the plain rail under 10 kN) the contact search is the plain rail's.
/// Each element's undeformed distance adds the rail's rise at its own x
/// along the contact normal, -0.01 x cos(delta) (x from the wheelset,
/// delta the contact angle; z down, so a rail rising ahead closes the gap
/// ahead), which moves the interpenetration's vertex ahead by that slope
/// over the wheel's curvature along x, cos(delta) / r: by 0.01 r, r the
/// wheel's radius at the contact (460 mm + ZCP_W). The contact reference
/// lies at the interpenetration's weighted centre, as CONTACT places it:
/// 0.01 r ahead (to 0.5 %: the wheel's curvature along x varies across
/// the patch; measured 0.1 %), at the plain rail's lateral place (within
/// 0.01 mm) and contact angle. Without yaw the falling rail is the rising
/// one's mirror image in x: its reference as far behind, and its
/// undeformed distance the rising rail's at -x in every row (the grid has
/// an element's centre on the reference point; held to the rounding of
/// the millimetre values, 1e-12 mm). The rising patch then carries more
/// ahead than behind: the centre of its pressure lies forward of the
/// plain rail's.
#[test]
fn a_rail_rising_along_the_track_adds_its_slope_to_the_gap() {
    let dir = scratch("slices-rising");
    let mut slices = [Vec::new(), Vec::new()];
    for (k, u) in [-200.0, -100.0, 0.0, 100.0, 200.0].into_iter().enumerate() {
        for (sign, list) in [1.0, -1.0].into_iter().zip(&mut slices) {
            let name = format!("slope{sign}_{k}.txt");
            write_uic60(&dir, &name, -0.01 * sign * u);
            list.push((u, name));
        }
    }
    let [rising, falling] = [0, 1].map(|k| {
        let list: Vec<(f64, &str)> = slices[k].iter().map(|(u, f)| (*u, f.as_str())).collect();
        write_slices(&dir, &format!("slope{k}.slcs"), &list)
    });
    let plain = dir.join("slope1_2.txt").display().to_string();
    let (a, b, c) = (120, 121, 122);
    let mut pos = [0.0; 6];
    unsafe {
        assert_eq!(solve(a, &plain, 1.0, (0.0, 0.0, 0.0), Load::Force(1e4)), 0);
        cntc_getwheelsetposition(&a, &6, pos.as_mut_ptr());
        cntc_finalize(&a);
        let height = Load::Height(pos[2]);
        assert_eq!(solve(a, &plain, 1.0, (0.0, 0.0, 0.0), height), 0);
        assert_eq!(solve(b, &rising, 1.0, (0.0, 0.0, 0.0), height), 0);
        assert_eq!(solve(c, &falling, 1.0, (0.0, 0.0, 0.0), height), 0);
    }
    assert_eq!([npatch(a), npatch(b), npatch(c)], [1, 1, 1]);
    let [ra, rb, rc] = [a, b, c].map(|ire| results(ire, 1));
    // The contact reference (XCP, YCP, ZCP, DELTCP in the track; ZCP_W).
    let r_wheel = 460.0 + ra[8 + 11];
    close("XCP plain", ra[8], 0.0, 1e-12);
    close("XCP rising", rb[8], 0.01 * r_wheel, 0.005 * 0.01 * r_wheel);
    close("XCP falling", rc[8], -rb[8], 1e-9);
    for r in [&rb, &rc] {
        close("YCP", r[8 + 1], ra[8 + 1], 0.01);
        close("ZCP", r[8 + 2], ra[8 + 2], 0.01);
        close("DELTCP", r[8 + 3], ra[8 + 3], 1e-12);
    }
    let grid = |r: &[f64]| (r[46] as usize, r[47] as usize, r[48], r[50]);
    let (mx, my, xc1, dx) = grid(&rb);
    assert_eq!((my, dx), (grid(&rc).1, grid(&rc).3));
    let (hb, hc) = (&rb[54..], &rc[54..]);
    assert_eq!(hb.len(), mx * my);
    // The falling rail's elements at -x (its grid reaches further the
    // other way when it has an even number of elements).
    let (mxc, xc1c) = (grid(&rc).0, grid(&rc).2);
    let mut pairs = 0;
    for iy in 0..my {
        for ix in 0..mx {
            let x = xc1 + ix as f64 * dx;
            let mirror = ((-x - xc1c) / dx).round();
            if mirror < 0.0 || mirror as usize >= mxc {
                continue;
            }
            let (rise, fall) = (hb[iy * mx + ix], hc[iy * mxc + mirror as usize]);
            assert!(
                (rise - fall).abs() < 1e-12,
                "row {iy}, x = {x} mm: {rise} against {fall}"
            );
            pairs += 1;
        }
    }
    assert!(pairs >= my * (mx - 1), "{pairs} pairs");
    // The patch then carries more ahead than behind: the centre of its
    // pressure lies forward of the plain rail's.
    let centre = |ire: i32, r: &[f64]| {
        let (mx, n, xc1, dx) = (r[46] as usize, (r[46] * r[47]) as usize, r[48], r[50]);
        let p = field(ire, 1, n, flags::field::PN);
        let (w, wx) = p.iter().enumerate().fold((0.0, 0.0), |(w, wx), (i, pn)| {
            (w + pn, wx + pn * (r[8] + xc1 + (i % mx) as f64 * dx))
        });
        wx / w
    };
    assert!(centre(b, &rb) > centre(a, &ra) + 0.1);
    for ire in [a, b, c] {
        unsafe { cntc_finalize(&ire) };
    }
}

/// What CONTACT's library returned for a case of `slices_cases.py`: FN,
/// FX, FS [N]; YCP, ZCP in the track [mm] (`cntc_getcontactlocation` 2, 3).
struct Reference {
    case: (f64, f64, f64),
    forces: [f64; 3],
    location: [f64; 2],
}

/// The S1002 wheel on the UK crossing nose (`slices_cases.py` cases s239,
/// the position of CONTACT's `mbench_locus.inp`, and s280), one patch
/// each, on the nose's top. CONTACT's library (revision 2707) on the same
/// slices: s239 FN 10076.7, FX 2754.59, FS 277.245 N, YCP_TR 788.60833,
/// ZCP_TR -1.42404 mm; s280 FN 10055.8, FX -2741.46, FS -1173.38 N,
/// YCP_TR 722.69759, ZCP_TR 2.65280 mm (its `.ref_out` of mbench_locus
/// on all 148 slices: FN 1.007E+04, FX 2758, FS 269.5 N, YCP 788.6406).
///
/// Where the two differ, and why: the nose's surface turns along the
/// track within a patch. Both place the patch's reference at the weighted
/// centre of the interpenetration over x and y (XCP 3.31 mm behind the
/// axle at s239, CONTACT's 3.2; 4.47 mm ahead at s280, CONTACT's 4.4), but
/// CONTACT takes the tangent plane there, with the weighted mean contact
/// angle over x and y, and the solver on the slice at the wheelset's S
/// (the contact locus at x = 0), the rail's change along x only in each
/// element's undeformed distance. The contact angles are then 0.032 rad
/// (s239) and 0.015 rad (s280) apart, and with them the spin creepage
/// (CPHI 1.45e-4 against CONTACT's 2.15e-4 /mm at s239), FS (200 against
/// 277 N) and MZ, which are not compared here. The vertical load is the
/// same; FN, which carries it along the normal, follows the angle's
/// cosine and the vertical parts of FX and FS: 0.41 % apart at s239 (cos
/// 0.0666 / cos 0.0990 = 1.0027 of it), 0.12 % at s280. FX, at 91 % of the
/// friction bound, to 0.8 % (0.36 % at s239, 0.70 % at s280). The contact
/// point: YCP within 0.1 mm (0.057 mm measured), ZCP within 0.06 mm
/// (0.047 mm).
#[test]
fn the_uk_crossing_nose_matches_contacts_library() {
    let rail = profile("uk_crossing_nose.slcs");
    let cases = [
        Reference {
            case: (239.0, 0.81, 0.0),
            forces: [10076.7, 2754.59, 277.245],
            location: [788.60833, -1.42404],
        },
        Reference {
            case: (280.0, 0.81, 0.0),
            forces: [10055.8, -2741.46, -1173.38],
            location: [722.69759, 2.65280],
        },
    ];
    for (k, r) in cases.iter().enumerate() {
        let ire = 130 + k as i32;
        unsafe { assert_eq!(solve(ire, &rail, 1000.0, r.case, Load::Force(1e4)), 0) };
        assert_eq!(npatch(ire), 1, "S {}", r.case.0);
        let v = results(ire, 1);
        let what = |name: &str| format!("S {}: {name}", r.case.0);
        close(&what("FN"), v[0], r.forces[0], 5e-3 * r.forces[0]);
        close(&what("FX"), v[1], r.forces[1], 8e-3 * r.forces[1].abs());
        close(&what("YCP_TR"), v[8 + 1], r.location[0], 0.1);
        close(&what("ZCP_TR"), v[8 + 2], r.location[1], 0.06);
        unsafe { cntc_finalize(&ire) };
    }
}

/// What is not built is refused naming it: a slices file with features
/// (NFEAT >= 2), a wheel slices file (.slcw), and a wheelset beyond the
/// slices.
#[test]
fn what_is_not_built_is_refused_naming_it() {
    let dir = scratch("slices-refused");
    write_uic60(&dir, "uic60.txt", 0.0);
    let with_features = dir.join("features.slcs");
    std::fs::write(
        &with_features,
        "0 1  U_OFFSET, U_SCALE\n2  NSLC\n3 0 0  NFEAT\n1  U_INTPOL\n0 'uic60.txt'\n10 'uic60.txt'\n",
    )
    .unwrap();
    let short = write_slices(
        &dir,
        "short.slcs",
        &[(0.0, "uic60.txt"), (100.0, "uic60.txt")],
    );
    let ire = 140;
    unsafe {
        let e = solve(
            ire,
            &with_features.display().to_string(),
            1.0,
            (50.0, 0.0, 0.0),
            Load::Force(1e4),
        );
        assert_ne!(e, 0);
        cntc_finalize(&ire);
        // Beyond the slices: the wheelset's S, or the patch's length.
        assert_ne!(
            solve(ire, &short, 1.0, (150.0, 0.0, 0.0), Load::Force(1e4)),
            0
        );
        cntc_finalize(&ire);
        assert_ne!(
            solve(ire, &short, 1.0, (1.0, 0.0, 0.0), Load::Force(1e4)),
            0
        );
        cntc_finalize(&ire);
        assert_eq!(
            solve(ire, &short, 1.0, (50.0, 0.0, 0.0), Load::Force(1e4)),
            0
        );
        cntc_finalize(&ire);
    }
}

/// Two patches, the wing rail's and the nose's, from the contact search
/// on the slice at S (`slices_cases.py` cases s300-ym6.8, s300-ym7: S =
/// 300 mm, Y = -6.8 and -7 mm). CONTACT's library: patch 1 on the wing
/// rail at YCP_TR 795.29663 and 795.31538 mm, ZCP_TR -1.42651 and
/// -1.42782; patch 2 on the nose at YCP_TR 724.11102 and 724.12321, ZCP_TR
/// 2.12274 and 2.12081 mm. Their FN: 5015.8 + 4968.21 N and 7594.99 +
/// 2431.82 N.
///
/// The patches lie where CONTACT's do, within 0.3 mm laterally and 0.09
/// mm vertically (the tangent planes taken on the slice at S, see
/// `the_uk_crossing_nose_matches_contacts_library`). How the load is
/// shared is not held to CONTACT's here: the solver puts 6509 and 3474 N
/// (8851 and 1167 N) on them, the wing rail carrying 30 % (17 %) more. A
/// patch's share goes with pen^1.5, so a 9 micrometre difference in the
/// patches' relative height moves it this much; the surfaces between the
/// slices (20 mm apart here) are natural cubic splines in u here and
/// CONTACT's tensor B-spline there, and the nose patch lies 5.5 mm ahead
/// of the axle on a nose rising along the track.
#[test]
fn the_wing_rail_and_the_nose_are_two_patches_where_contacts_are() {
    let rail = profile("uk_crossing_nose.slcs");
    // (Y; per patch YCP_TR, ZCP_TR) of CONTACT's library.
    let cases = [
        (-6.8, [[795.29663, -1.42651], [724.11102, 2.12274]]),
        (-7.0, [[795.31538, -1.42782], [724.12321, 2.12081]]),
    ];
    for (k, (y, patches)) in cases.iter().enumerate() {
        let ire = 150 + k as i32;
        unsafe {
            assert_eq!(
                solve(ire, &rail, 1000.0, (300.0, *y, 0.0), Load::Force(1e4)),
                0
            );
        }
        assert_eq!(npatch(ire), 2, "Y {y}");
        for (icp, r) in (1..).zip(patches) {
            let v = results(ire, icp);
            let what = |name: &str| format!("Y {y}, patch {icp}: {name}");
            close(&what("YCP_TR"), v[8 + 1], r[0], 0.3);
            close(&what("ZCP_TR"), v[8 + 2], r[1], 0.09);
        }
        unsafe { cntc_finalize(&ire) };
    }
}

/// `cntc_getprofilevalues` of a variable rail is its profile at the
/// wheelset's position S: the rail rising 1 mm per 100 mm, at S = 50 mm,
/// is the UIC60 rail 0.5 mm higher (z down), point for point (the splines
/// along u reproduce the linear rise; to the rounding of mm values).
#[test]
fn the_profile_values_of_a_variable_rail_are_those_at_the_wheelset() {
    let dir = scratch("slices-values");
    write_uic60(&dir, "plain.txt", 0.0);
    write_uic60(&dir, "low.txt", 1.0);
    write_uic60(&dir, "high.txt", -1.0);
    let rising = write_slices(
        &dir,
        "rising.slcs",
        &[(-100.0, "low.txt"), (100.0, "high.txt")],
    );
    let plain = dir.join("plain.txt").display().to_string();
    let values = |ire: i32| {
        let (ip, rp) = ([0, -1], [0.0]);
        let mut n = 0.0;
        unsafe {
            cntc_getprofilevalues(&ire, &0, &2, ip.as_ptr(), &1, rp.as_ptr(), &1, &mut n);
            let mut v = vec![0.0; 2 * n as usize];
            let len = v.len() as i32;
            cntc_getprofilevalues(
                &ire,
                &1,
                &2,
                ip.as_ptr(),
                &1,
                rp.as_ptr(),
                &len,
                v.as_mut_ptr(),
            );
            v
        }
    };
    let (a, b) = (160, 161);
    unsafe {
        assert_eq!(solve(a, &plain, 1.0, (50.0, 0.0, 0.0), Load::Force(1e4)), 0);
        assert_eq!(
            solve(b, &rising, 1.0, (50.0, 0.0, 0.0), Load::Force(1e4)),
            0
        );
    }
    let (va, vb) = (values(a), values(b));
    assert_eq!(va.len(), vb.len());
    let n = va.len() / 2;
    for i in 0..n {
        assert!((va[i] - vb[i]).abs() < 1e-12, "y of point {i}");
        let dz = vb[n + i] - va[n + i];
        assert!((dz + 0.5).abs() < 1e-12, "z of point {i}: {dz}");
    }
    unsafe {
        cntc_finalize(&a);
        cntc_finalize(&b);
    }
}

/// A module 1 input file naming a rail slices file (RFNAME, CONTACT's
/// `mbench_locus.inp` on the nose's slices) configures the element as the
/// calls do: the same results bit for bit.
#[test]
fn an_input_file_takes_a_rail_slices_file() {
    let dir = scratch("slices-inp");
    let inp = MBENCH_RIGHT_INP
        .replace(
            "   14.0     0    1435.0   0.000                 GAUGHT, GAUGSQ, GAUGWD, CANT",
            "   -1.0   750.0   0.000   0.000                 GAUGHT, RAILY0, RAILZ0, CANT",
        )
        .replace(
            "  'MBench_UIC60_v3.prr'   0     1.0   0.0       RFNAME, MIRRORY, SCALE, SMOOTH",
            &format!(
                "  '{}'  0  1000.  0.0  -1   RFNAME",
                profile("uk_crossing_nose.slcs")
            ),
        )
        .replace(
            "  'MBench_S1002_v3.prw'   0     1.0   0.0       WFNAME, MIRRORY, SCALE, SMOOTH",
            &format!(
                "  '{}'  0  1.0  0.0  -1   WFNAME",
                profile("MBench_S1002_v3.prw")
            ),
        )
        .replace(
            "  0.0  3.0  10000. -0.00018030 0.0072  0.0      S, Y, FZ, ROLL, YAW, PITCH",
            "  239.0  0.81  10000.  0.0  0.0  0.0      S, Y, FZ, ROLL, YAW, PITCH",
        )
        .replace(
            " 2000. 0.0    0.0   0.0        0.0  -4.34515030 VS,VY,VZ, VROLL,VYAW,VPITCH",
            " 2000. 0.0    0.0   0.0        0.0  -4.34811810 VS,VY,VZ, VROLL,VYAW,VPITCH",
        );
    assert!(inp.contains("uk_crossing_nose.slcs") && inp.contains("239.0"));
    let path = dir.join("nose.inp");
    std::fs::write(&path, inp).unwrap();
    let (a, b) = (170, 171);
    unsafe {
        assert_eq!(
            solve(
                a,
                &profile("uk_crossing_nose.slcs"),
                1000.0,
                (239.0, 0.81, 0.0),
                Load::Force(1e4)
            ),
            0
        );
        wheelrail_element(b, &[]);
    }
    assert_eq!(read_inp(b, flags::INP_MODUL1, &path), 0);
    let (ra, rb) = (wheel_results(a), wheel_results(b));
    assert_eq!(ra.0, 0);
    assert_eq!(ra, rb);
    unsafe {
        cntc_finalize(&a);
        cntc_finalize(&b);
    }
}
