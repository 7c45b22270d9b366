//! Module 1 with the rail placed absolutely (GAUGHT <= 0: the rail
//! profile's origin at RAILY0, RAILZ0 of the track), on roller rigs
//! (C1 = 4, 5: test-rollers2.inp cases 2 and 3) and in curves (CURV),
//! called as a C caller calls it, against CONTACT's `test-rollers2.inp`
//! (testbank/examples_conformal, its `.ref_out`) and against the values
//! CONTACT's own library (revision 2707) returned for the same calls
//! through its `python_intfc` (`crates/cntc/bench/placement_cases.py`, the
//! case named in each test). The sphere of radius 100 mm (`circ_r100.prw`)
//! rolls on a flat plane (`flat_plane.prr`), the other profiles are named
//! by each case's `Rig`; CONTACT's units (mm, N).

mod common;

use std::ptr::null;

use common::{close, profile, set_profile_file, wheelrail_element};
use contact_addon::ffi::*;
use contact_addon::flags;

/// One case of `placement_cases.py`: the wheel side `c1`, the track
/// (Z = 3: 11 values), the wheelset position (its Z_WS the height with
/// N = 0) and velocity (E = 3, or 5 with the flexibility `flex`), a vertical
/// force `fz` (N = 1) or none (N = 0), and a total longitudinal force
/// FX_WS `fx_ws` (F = 1: the pitch rate found) or none (F = 0).
#[derive(Clone, Copy)]
struct Case {
    c1: i32,
    track: [f64; 11],
    position: [f64; 6],
    velocity: [f64; 6],
    flex: Option<[f64; 12]>,
    fz: Option<f64>,
    fx_ws: Option<f64>,
    rig: Rig,
}

/// The profiles, wheelset dimensions (E = 3: FBDIST, FBPOS, NOMRAD) and
/// track curvature CURV of a case (CURV given after NOMRAD, as the 12th of
/// Z = 3's values).
#[derive(Clone, Copy)]
struct Rig {
    rail: &'static str,
    wheel: &'static str,
    dims: [f64; 3],
    curv: Option<f64>,
}

/// test-rollers2.inp case 1's: the sphere over the plane.
const SPHERE_ON_PLANE: Rig = Rig {
    rail: "flat_plane.prr",
    wheel: "circ_r100.prw",
    dims: [200.0, -100.0, 100.0],
    curv: None,
};

/// Sets up result element `ire` with `case` and calculates it: ierror.
unsafe fn solve(ire: i32, case: &Case) -> i32 {
    let mut npatch = 0;
    let ierror = solve_unchecked(ire, case, &mut npatch);
    assert_eq!(npatch, 1);
    ierror
}

/// [`solve`] without its check of one patch: ierror, the number of
/// patches in `npatch`.
unsafe fn solve_unchecked(ire: i32, case: &Case, npatch: &mut i32) -> i32 {
    let icp = -1;
    wheelrail_element(
        ire,
        &[
            (flags::IC_CONFIG, case.c1),
            (flags::IC_TANG, 3),
            (flags::IC_PVTIME, 2),
            (flags::IC_NORM, case.fz.is_some() as i32),
            (flags::IC_DISCNS, 2),
            (flags::IC_FORCE, case.fx_ws.is_some() as i32),
        ],
    );
    if let Some(fx) = case.fx_ws {
        cntc_settangentialforces(&ire, &icp, &fx, &0.0);
    }
    let mat = [0.28, 0.28, 82000.0, 82000.0];
    cntc_setmaterialparameters(&ire, &icp, &0, &4, mat.as_ptr());
    cntc_setfrictionmethod(&ire, &icp, &0, &2, [0.3, 0.3].as_ptr());
    if let Some(fz) = case.fz {
        cntc_setverticalforce(&ire, &fz);
    }
    let pot = [0.2, 0.2, std::f64::consts::FRAC_PI_2, 8.0, 4.0];
    cntc_setpotcontact(&ire, &icp, &-1, &5, pot.as_ptr());
    let mut track = case.track.to_vec();
    if let Some(curv) = case.rig.curv {
        track.insert(5, curv);
    }
    cntc_settrackdimensions(&ire, &3, &(track.len() as i32), track.as_ptr());
    set_profile_file(ire, &profile(case.rig.rail), 0);
    cntc_setwheelsetdimensions(&ire, &3, &3, case.rig.dims.as_ptr());
    set_profile_file(ire, &profile(case.rig.wheel), 0);
    let e = if case.flex.is_some() { 5 } else { 3 };
    cntc_setwheelsetposition(&ire, &e, &6, case.position.as_ptr());
    cntc_setwheelsetvelocity(&ire, &e, &6, case.velocity.as_ptr());
    if let Some(flex) = case.flex {
        cntc_setwheelsetflexibility(&ire, &e, &12, flex.as_ptr());
    }
    let mut ierror = -1;
    cntc_calculate1(&ire, &mut ierror);
    cntc_getnumcontactpatches(&ire, npatch);
    ierror
}

/// What CONTACT's library returned for one patch: FN, FX, FS, MZ; CKSI,
/// CETA, CPHI; `cntc_getcontactlocation` 1-4 (XCP, YCP, ZCP, DELTCP in the
/// track), 6, 7 (YCP, ZCP on the rail), 11, 12 (YCP, ZCP on the wheel).
type Reference = [f64; 15];

/// Patch 1 of `ire` in a [`Reference`]'s order.
unsafe fn ours(ire: i32) -> Reference {
    let icp = 1;
    let (mut fn_, mut fx, mut fs, mut mz) = (0.0, 0.0, 0.0, 0.0);
    cntc_getcontactforces(&ire, &icp, &mut fn_, &mut fx, &mut fs, &mut mz);
    let (mut cksi, mut ceta, mut cphi) = (0.0, 0.0, 0.0);
    cntc_getcreepages(&ire, &icp, &mut cksi, &mut ceta, &mut cphi);
    let mut loc = [0.0; 38];
    cntc_getcontactlocation(&ire, &icp, &38, loc.as_mut_ptr());
    [
        fn_, fx, fs, mz, cksi, ceta, cphi, loc[0], loc[1], loc[2], loc[3], loc[5], loc[6], loc[10],
        loc[11],
    ]
}

/// The names of a [`Reference`]'s values.
const NAMES: [&str; 15] = [
    "FN",
    "FX",
    "FS",
    "MZ",
    "CKSI",
    "CETA",
    "CPHI",
    "XCP_TR",
    "YCP_TR",
    "ZCP_TR",
    "DELTCP_TR",
    "YCP_R",
    "ZCP_R",
    "YCP_W",
    "ZCP_W",
];

/// Compares patch 1 of `ire` with `r`: the location to 0.01 mm and 0.1
/// mrad, creepages to 1e-6 (1e-7 /mm for the spin), FN to 0.05 % (our
/// grid has no element centred on the reference point, CONTACT's has:
/// h(0.1 mm) = 0.1^2 / (2 R) = 5e-5 mm of the sphere's approach of 0.16 mm
/// is not loaded), FX and FS to 0.5 % of mu FN (on `abs-load`, FS differs
/// by 41 N = 0.27 % of mu FN, a difference that stays when both grids are
/// refined to 0.1 mm: CONTACT -2006.9 N, ours -1975.2 N), MZ to 0.01 FN mm.
unsafe fn compare(ire: i32, r: &Reference) {
    let ours = ours(ire);
    let mu_fn = 0.3 * r[0];
    for k in 0..15 {
        let tol = match k {
            0 => 5e-4 * r[0],
            1 | 2 => 5e-3 * mu_fn,
            3 => 0.01 * r[0],
            4 | 5 => 1e-6,
            6 => 1e-7,
            10 => 1e-4,
            _ => 0.01,
        };
        close(NAMES[k], ours[k], r[k], tol);
    }
}

/// Solves `case` on element `ire`, compares it with `r` and frees the
/// element.
unsafe fn check(ire: i32, case: &Case, r: &Reference) {
    assert_eq!(solve(ire, case), 0);
    compare(ire, r);
    cntc_finalize(&ire);
}

const NO_DEVIATION: [f64; 6] = [0.0; 6];

/// Solves `case` on element `ire`, checks its creepages against `r`'s to
/// `tol` and the rest as [`compare`] does.
unsafe fn check_creepages_apart(ire: i32, case: &Case, r: &Reference, tol: [f64; 3]) {
    check_apart(ire, case, r, &[(4, tol[0]), (5, tol[1]), (6, tol[2])]);
}

/// Solves `case` on element `ire`, checks the values of `r` at the
/// indices of `apart` to their tolerances and the rest as [`compare`]
/// does.
unsafe fn check_apart(ire: i32, case: &Case, r: &Reference, apart: &[(usize, f64)]) {
    assert_eq!(solve(ire, case), 0);
    let got = ours(ire);
    let mut r = *r;
    for &(k, tol) in apart {
        close(NAMES[k], got[k], r[k], tol);
        r[k] = got[k];
    }
    compare(ire, &r);
}

/// Solves `a` on element `ia` and `b` on `ib` and asserts the same FN,
/// FX, FS, MZ to rounding (1e-9 FN).
unsafe fn same_forces(ia: i32, a: &Case, ib: i32, b: &Case) {
    assert_eq!(solve(ia, a), 0);
    assert_eq!(solve(ib, b), 0);
    let (mut fa, mut fb) = ([0.0; 4], [0.0; 4]);
    cntc_getcontactforces(&ia, &1, &mut fa[0], &mut fa[1], &mut fa[2], &mut fa[3]);
    cntc_getcontactforces(&ib, &1, &mut fb[0], &mut fb[1], &mut fb[2], &mut fb[3]);
    for k in 0..4 {
        close("force", fb[k], fa[k], 1e-9 * fa[0]);
    }
}

/// `case` on the left rail (C1 = 0), its RAILY0 mirrored.
fn on_the_left(case: Case) -> Case {
    let mut left = case;
    left.c1 = 0;
    left.track[1] = -case.track[1];
    left
}

/// test-rollers2.inp case 1a: the sphere at Z_WS = 0.16 mm on the plane at
/// RAILY0 = 200 mm, rolling at 100 mm/s with VPITCH = -1 rad/s.
const CASE_1A: Case = Case {
    c1: 1,
    track: [-1.0, 200.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    position: [0.0, 0.0, 0.16, 0.0, 0.0, 0.0],
    velocity: [100.0, 0.0, 0.0, 0.0, 0.0, -1.0],
    flex: None,
    fz: None,
    fx_ws: None,
    rig: SPHERE_ON_PLANE,
};

/// The track of test-rollers2.inp case 1a: GAUGHT = -1, the plane's origin
/// at RAILY0 = `y0`, RAILZ0 = `z0`, cant `cant`.
fn absolute_track(y0: f64, z0: f64, cant: f64, deviation: [f64; 6]) -> [f64; 11] {
    let mut t = [-1.0, y0, z0, cant, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    t[5..].copy_from_slice(&deviation);
    t
}

/// test-rollers2.inp case 1a ([`CASE_1A`]). Its `.ref_out` (Case 1): FN
/// 9.722E+04 N, no creep forces, the contact at (0, 200, 0) of the track
/// and (0, 0, -0.16) of the wheel profile, APPROACH 0.160000.
#[test]
fn case_1a_sphere_on_a_plane_placed_absolutely() {
    let ire = 41;
    unsafe {
        assert_eq!(solve(ire, &CASE_1A), 0);
        let mut r = [0.0; 15];
        r[0] = 9.722e4;
        r[8] = 200.0;
        r[14] = -0.16;
        compare(ire, &r);
        // The rail profile marker (cntc_getcontactlocation 26-28) at
        // (RAILY0, RAILZ0), not rolled.
        let mut loc = [0.0; 38];
        cntc_getcontactlocation(&ire, &1, &38, loc.as_mut_ptr());
        assert_eq!(&loc[25..28], &[200.0, 0.0, 0.0]);
        cntc_finalize(&ire);
    }
}

/// `placement_cases.py` cases `abs-load` (right) and `abs-load-left`: the
/// plane at RAILZ0 = 0.5 mm with a cant of 0.05 rad at RAILY0 = 200 mm,
/// -200 mm on the left, the wheelset at Y_WS = 3 mm (rolled and yawed on
/// the left), FZ = 50 kN, VPITCH = -1.002 rad/s: the contact where the
/// sphere's normal is the canted plane's, with longitudinal and spin
/// creepage.
#[test]
fn absolute_placement_with_cant_and_load_matches_contacts_library() {
    let right = Case {
        track: absolute_track(200.0, 0.5, 0.05, NO_DEVIATION),
        position: [0.0, 3.0, 0.0, 0.0, 0.0, 0.0],
        velocity: [100.0, 0.0, 0.0, 0.0, 0.0, -1.002],
        fz: Some(5.0e4),
        ..CASE_1A
    };
    let left = Case {
        c1: 0,
        track: absolute_track(-200.0, 0.5, 0.05, NO_DEVIATION),
        position: [0.0, 3.0, 0.0, 0.001, 0.002, 0.0],
        ..right
    };
    unsafe {
        #[rustfmt::skip]
        check(42, &right, &[
            49962.0, -2375.92, -2008.94, -4477.25, 0.000746317, 0.0, 0.000500604,
            0.0, 207.99599, 0.09987, -0.05, 8.006, 0.0, 4.99599, -0.22764,
        ]);
        #[rustfmt::skip]
        check(43, &left, &[
            50241.6, -2389.84, -3576.99, 9174.21, 0.000793883, 0.0020032, -0.000490588,
            0.4, -201.99549, 0.40014, 0.05, -1.99798, 0.0, -4.8962, -0.22308,
        ]);
    }
}

/// test-rollers2.inp case 1e: the sphere deflected by DROLLW = 0.1 rad and
/// DZWHL = -0.4996 mm (E = 4), so that its lowest point moves 100 sin(0.1)
/// = 9.98 mm outwards at the same height. Its `.ref_out` (Case 5): FN
/// 9.720E+04 N, the contact at track y 209.9833, wheel profile (9.9674,
/// -0.6588), APPROACH 0.160018; CKSI 1.767E-07 and FX -0.9974 N, no spin
/// (DROLLW turns the wheel but gives no spin: only VROLLW would), which
/// ours meets within 1e-6 and 0.5 % of mu FN.
#[test]
fn case_1e_a_rolled_wheel_moves_its_contact_without_spin() {
    let case = Case {
        flex: Some([
            0.0, 0.0, -0.4996, 0.1, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
        ]),
        ..CASE_1A
    };
    unsafe {
        #[rustfmt::skip]
        check(44, &case, &[
            9.720e4, -0.9974, 0.0, 0.0, 1.767e-7, 0.0, 0.0,
            0.0, 209.9833, 0.0, 0.0, 9.9833, 0.0, 9.9674, -0.6588,
        ]);
    }
}

/// `placement_cases.py` cases `flex` and `flex-left`: every deviation and
/// rate of the wheel at once (DXWHL 0.5, DYWHL 0.3, DZWHL -0.2 mm, DROLLW
/// 0.02, DYAWW 0.03, DPITCHW 0.1 rad; 0.04, 0.03, 0.02 mm/s, 0.1, 0.2,
/// 0.3 mrad/s) on a rolled and yawed wheelset moving laterally and
/// vertically, FZ = 50 kN. The contact location matches CONTACT's library
/// to its printed digits; the creepages lie 0.15-0.19 % below CONTACT's
/// (all three by about the same factor): CONTACT divides the slip by the
/// rolling speed of the wheelset's pitch about the wheelset's axle, the
/// solver by that of the deflected wheel about its own axle, whose lever
/// arm to the contact differs by the axle's shift (DROLLW 0.02 rad over
/// 100 mm: 0.15 %). Creepages are therefore compared to 0.25 % here.
#[test]
fn flexible_wheelset_deviations_match_contacts_library() {
    let flex = [
        0.5, 0.3, -0.2, 0.02, 0.03, 0.1, 0.04, 0.03, 0.02, 0.0001, 0.0002, 0.0003,
    ];
    let right = Case {
        position: [0.0, 1.0, 0.0, 0.002, 0.003, 0.0],
        velocity: [100.0, 0.02, 0.01, 0.0002, 0.0003, -1.0],
        flex: Some(flex),
        fz: Some(5.0e4),
        ..CASE_1A
    };
    let left = on_the_left(right);
    #[rustfmt::skip]
    let contact: [Reference; 2] = [
        [50000.0, 4606.77, -6970.68, 4908.32, -0.0015955, 0.00270734, 1.5009e-05,
         -0.1069, 203.30045, 0.0, 0.0, 3.30045, 0.0, 2.19659, -0.12693],
        [50000.0, 7564.18, -6531.69, 3706.86, -0.00279503, 0.00270051, 1.5e-05,
         1.09309, -196.69695, 0.0, 0.0, 3.30305, 0.0, 2.19659, -0.12693],
    ];
    for (k, (case, r)) in [(right, contact[0]), (left, contact[1])].iter().enumerate() {
        let ire = 45 + k as i32;
        let tol = [r[4], r[5], r[6]].map(|c: f64| 2.5e-3 * c.abs());
        unsafe {
            check_creepages_apart(ire, case, r, tol);
            cntc_finalize(&ire);
        }
    }
}

/// Zero deviations given (E = 5) are no deviations (E = 3), bit for bit;
/// DYWHL = d on the right wheel of an unrolled, unyawed wheelset is the
/// wheelset moved by d (Y_WS), to rounding.
#[test]
fn flexibility_conventions() {
    let with_zeros = Case {
        flex: Some([0.0; 12]),
        ..CASE_1A
    };
    unsafe {
        assert_eq!(solve(47, &CASE_1A), 0);
        assert_eq!(solve(48, &with_zeros), 0);
        assert_eq!(common::wheel_results(47), common::wheel_results(48));
        let mut shifted = CASE_1A;
        shifted.position[1] = 0.7;
        let mut deflected = CASE_1A;
        deflected.flex = Some([0.0, 0.7, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
        same_forces(49, &shifted, 50, &deflected);
        for ire in 47..=50 {
            cntc_finalize(&ire);
        }
    }
}

/// `placement_cases.py` cases `dev` and `dev-left`: the plane at RAILY0 =
/// +-200 mm deviated by DYRAIL 2 mm, DZRAIL 0.3 mm, DROLLR 0.02 rad and
/// moving at VYRAIL 1 mm/s, VZRAIL 0.5 mm/s, VROLLR 0.01 rad/s (Z = 3),
/// the wheelset at Y_WS = 1 mm, FZ = 50 kN. DYRAIL is a track y: the left
/// rail moves towards the track centre, the right one outwards, and both
/// give the same forces. The rail's marker and the contact match CONTACT's
/// library to its printed digits, and so do the creepages (CETA
/// 0.0100990 against CONTACT's 0.010099, the rail's velocity taken at the
/// rail's point of the patch as CONTACT does); compared to 1.1e-5.
#[test]
fn rail_deviations_match_contacts_library() {
    let deviation = [2.0, 0.3, 0.02, 1.0, 0.5, 0.01];
    let right = Case {
        track: absolute_track(200.0, 0.0, 0.0, deviation),
        position: [0.0, 1.0, 0.0, 0.0, 0.0, 0.0],
        fz: Some(5.0e4),
        ..CASE_1A
    };
    let left = on_the_left(right);
    #[rustfmt::skip]
    let contact: [Reference; 2] = [
        [50305.2, 325.48, -14759.5, 2355.76, -0.000199809, 0.010099, -0.000200007,
         0.0, 199.00087, 0.24001, 0.02, -2.99973, 0.0, -1.99913, -0.12311],
        [50305.2, 325.477, -14759.5, 2355.75, -0.000199809, 0.010099, -0.000200007,
         0.0, -200.99913, 0.24001, 0.02, -2.99973, 0.0, -1.99913, -0.12311],
    ];
    let markers = [[202.0, 0.3, 0.02], [-198.0, 0.3, 0.02]];
    for (k, (case, r)) in [(right, contact[0]), (left, contact[1])].iter().enumerate() {
        let ire = 51 + k as i32;
        unsafe {
            check_creepages_apart(ire, case, r, [1e-6, 1.1e-5, 1e-7]);
            let mut loc = [0.0; 38];
            cntc_getcontactlocation(&ire, &1, &38, loc.as_mut_ptr());
            for (j, name) in ["YR_TR", "ZR_TR", "ROLLR_TR"].iter().enumerate() {
                close(name, loc[25 + j], markers[k][j], 1e-9);
            }
            cntc_finalize(&ire);
        }
    }
}

/// A rail shifted by DYRAIL = d is the wheelset shifted by -d: the same
/// forces and creepages (to rounding), the contact d further.
#[test]
fn a_rail_deviation_is_the_wheelset_moved_the_other_way() {
    let rail_moved = Case {
        track: absolute_track(200.0, 0.0, 0.0, [0.8, 0.0, 0.0, 0.0, 0.0, 0.0]),
        fz: Some(5.0e4),
        ..CASE_1A
    };
    let mut wheelset_moved = rail_moved;
    wheelset_moved.track = CASE_1A.track;
    wheelset_moved.position[1] = -0.8;
    unsafe {
        same_forces(53, &rail_moved, 54, &wheelset_moved);
        let (mut la, mut lb) = ([0.0; 38], [0.0; 38]);
        cntc_getcontactlocation(&53, &1, &38, la.as_mut_ptr());
        cntc_getcontactlocation(&54, &1, &38, lb.as_mut_ptr());
        close("YCP_TR", la[1] - lb[1], 0.8, 1e-9);
        cntc_finalize(&53);
        cntc_finalize(&54);
    }
}

/// test-rollers2.inp's case 1a, its profiles' paths those of this
/// repository.
fn case_1a_inp() -> String {
    format!(
        "  1 MODULE
 1203000    C-P-B-T-N-F-S  CONFIG, PVTIME, BOUND, TANG, NORM, FORCE, STRESS
 0022033    V-L-D-C-M-Z-E    FRCLAW, DISCNS, INFLCF, MATER , ZTRACK, EWHEEL
 0000321    H-G-I-A-O-W-R    GAUSEI, IESTIM, MATFIL, OUTPUT, FLOW  , RETURN
    999     100    10    1     1e-7  MAXGS , MAXIN , MAXNR , MAXOUT, EPS
  0.300   0.300                                 FSTAT, FKIN
  0.280   0.280   82000.  82000.                POISS 1,2,  GG 1,2
  0.200   0.200   1.000   90d   8.0   4.0       DX,DS, DQREL, A_SEP, D_SEP, D_COMB
   -1.0   200.0   0.000   0.000                 GAUGHT, RAILY0, RAILZ0, CANT
  '{}'   0  1.0   0.0   RFNAME, MIRRORY, SCALE, SMOOTH
     0.0    0.0   0.000   0.0    0.0   0.000    DY, DZ, ROLL, VY, VZ, VROLL
   200.0 -100.0   100.0                         FBDIST, FBPOS, NOMRAD_W
  '{}'    0  1.0   0.0   WFNAME, MIRRORY, SCALE, SMOOTH
     0.0    0.0     0.160                       % X_WS, Y_WS, Z_WS
     0.0    0.0     0.0                         % ROLL_WS, YAW_WS, PITCH_WS
   100.0    0.0     0.0                         % VS_WS, VY_WS, VZ_WS
     0.0    0.0    -1.000                       % VROLL, VYAW, VPITCH_WS
  0 MODULE
",
        profile("flat_plane.prr"),
        profile("circ_r100.prw")
    )
}

/// test-rollers2.inp's first case as CONTACT's input file reader takes it
/// (`cntc_readinpfile`, CNTC_inp_modul1): the file's lines of case 1a
/// (eve70a/CONTACT, testbank/examples_conformal, Apache-2.0) with the
/// profiles' paths those of this repository. It sets GAUGHT = -1 with
/// RAILY0 = 200 (Z = 3) and is solved as `case_1a` is: the `.ref_out`'s
/// FN 9.722E+04 N within 0.05 % and the contact at track y 200 mm.
#[test]
fn case_1a_read_from_contacts_input_file() {
    let inp = case_1a_inp();
    let mut r = [0.0; 15];
    r[0] = 9.722e4;
    r[8] = 200.0;
    r[14] = -0.16;
    unsafe { check_inp(55, "test-rollers2-1a.inp", &inp, &r) };
}

/// Reads `inp` (written to the scratch file `name`) into element `ire`
/// with `cntc_readinpfile` (CNTC_inp_modul1), calculates it, compares it
/// with `r` as [`compare`] does and frees the element.
unsafe fn check_inp(ire: i32, name: &str, inp: &str, r: &Reference) {
    let path = common::scratch("placement").join(name);
    std::fs::write(&path, inp).unwrap();
    let (mut ifcver, mut ierror) = (0, 0);
    cntc_initialize(&ire, &1, &mut ifcver, &mut ierror, null(), null());
    assert_eq!(common::read_inp(ire, flags::INP_MODUL1, &path), 0);
    let mut ierror = -1;
    cntc_calculate1(&ire, &mut ierror);
    assert_eq!(ierror, 0);
    compare(ire, r);
    cntc_finalize(&ire);
}

/// test-rollers2.inp case 2a as CONTACT's input file reader takes it: case
/// 1a's lines ([`case_1a_inp`]) changed to 2a's (C1 = 5, Z = 3 with
/// NOMRAD_R = 400 mm, the bus's profiles and dimensions, E = 5 with its
/// zero deviations, VPITCH_ROL = 0.25 rad/s in the place of VS_WS,
/// VPITCH_WS = -0.75 rad/s), its third control word and solver line
/// those of case 1a (this file holds 2a alone). Solved as
/// [`roller_rig_cases_2a_2e_match_contacts_library`]'s 2a (the `.ref_out`'s
/// Case 6: FN 9.719E+04 N, CKSI -2.500E-08, at track y 200 mm).
#[test]
fn case_2a_read_from_contacts_input_file() {
    let mut inp = case_1a_inp();
    for (from, to) in [
        ("flat_plane.prr", "circ_r100.prr"),
        ("circ_r100.prw", "flat_plane.prw"),
        (" 1203000 ", " 5203000 "),
        (" 0022033 ", " 0022035 "),
        (
            "0.000   0.000                 GAUGHT, RAILY0, RAILZ0, CANT",
            "0.000   400.0                 GAUGHT, RAILY0, RAILZ0, NOMRAD_R",
        ),
        ("   200.0 -100.0   100.0  ", "   300.0  -50.0   133.33333"),
        (
            "   100.0    0.0     0.0                         % VS_WS",
            "   0.250    0.0     0.0                         % VPITCH_ROL",
        ),
        (
            "-1.000                       % VROLL, VYAW, VPITCH_WS\n",
            "-0.750                       % VROLL, VYAW, VPITCH_WS\n\
              0.0 0.0 0.0 0.0 0.0 0.0  DX,DY,DZ, DROLL,DYAW,DPITCH\n\
              0.0 0.0 0.0 0.0 0.0 0.0  VX,VY,VZ, VROLL,VYAW,VPITCH\n",
        ),
    ] {
        assert!(inp.contains(from), "{from}");
        inp = inp.replace(from, to);
    }
    unsafe { check_inp(73, "test-rollers2-2a.inp", &inp, &CASE_2A_REFERENCE) };
}

/// test-rollers2.inp's roller rig: the rail profile's origin at RAILY0 =
/// `y0` on a roller of NOMRAD_R = 400 mm, with `deviation`.
fn roller_track(y0: f64, deviation: [f64; 6]) -> [f64; 11] {
    let mut t = absolute_track(y0, 0.0, 0.0, deviation);
    t[4] = 400.0;
    t
}

/// test-rollers2.inp cases 2: the "bus", a flat wheel at a nominal radius
/// of 133.3 mm (a cylinder), on the ellipsoidal roller `circ_r100.prr`.
const BUS: Rig = Rig {
    rail: "circ_r100.prr",
    wheel: "flat_plane.prw",
    dims: [300.0, -50.0, 133.33333],
    curv: None,
};

/// test-rollers2.inp cases 3: an ellipsoid (the sphere's profile at a
/// nominal radius of 133.3 mm) on the conical roller `flat_ang200.prr`.
const ELLIPSOID: Rig = Rig {
    rail: "flat_ang200.prr",
    wheel: "circ_r100.prw",
    dims: [200.0, -100.0, 133.33333],
    curv: None,
};

/// test-rollers2.inp case 2a (C1 = 5): the bus at Z_WS = 0.16 mm on the
/// roller turning at VPITCH_ROL = 0.25 rad/s, the wheel at -0.75 rad/s
/// (both surfaces at 100 mm/s).
const CASE_2A: Case = Case {
    c1: 5,
    track: [-1.0, 200.0, 0.0, 0.0, 400.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    velocity: [0.25, 0.0, 0.0, 0.0, 0.0, -0.75],
    rig: BUS,
    ..CASE_1A
};

/// `case` in a curve of CURV = `curv`, centred (Y_WS = 0) and loaded by
/// FZ = `fz`.
fn in_a_curve(case: Case, curv: f64, fz: f64) -> Case {
    let mut c = case;
    c.position = [0.0; 6];
    c.fz = Some(fz);
    c.rig.curv = Some(curv);
    c
}

/// CONTACT's library on [`CASE_2A`] (`placement_cases.py` case `2a`).
#[rustfmt::skip]
const CASE_2A_REFERENCE: Reference = [
    97186.9, 0.141092, 1.43397e-07, 0.0, -2.5e-08, 0.0, -7.30257e-15,
    0.0, 200.0, 0.0, 0.0, 0.0, 0.0, 0.0, -0.16,
];

/// test-rollers2.inp cases 2a and 2e (the roller tilted by DROLL = 0.1 rad
/// with DZ = 0.4996 mm), against CONTACT's library (`placement_cases.py`,
/// cases `2a`, `2e`) and the `.ref_out` (Cases 6 and 9: FN 9.719E+04 N,
/// CKSI -2.500E-08 and -3.684E-08, YCP(TR) 200.0 and 190.0167 mm, YCP(R)
/// -9.9833 and ZCP(R) 0.4996 mm in 2e). The roller's curvature along x
/// (1/400 mm) and the wheel's (1/133.3 mm) make A = B = 5 /m: FN is Hertz's
/// 97 185 N within 0.02 % (ours 97 198 and 97 204 N). FX and FS are below
/// 0.3 N (rounding) in both.
#[test]
fn roller_rig_cases_2a_2e_match_contacts_library() {
    unsafe {
        check(61, &CASE_2A, &CASE_2A_REFERENCE);
        let tilted = Case {
            track: roller_track(200.0, [0.0, 0.4996, 0.1, 0.0, 0.0, 0.0]),
            ..CASE_2A
        };
        #[rustfmt::skip]
        check(62, &tilted, &[
            97187.8, 0.207919, 0.00387635, 0.0, -3.6841e-08, 0.0, -4.84811e-10,
            0.0, 190.01666, 0.00002, 0.0, -9.98334, 0.49958, -9.98334, -0.15998,
        ]);
    }
}

/// test-rollers2.inp cases 3: the ellipsoid on the conical roller at
/// Z_WS = `z_ws`, rolled by `roll`, the roller turning at VPITCH_ROL =
/// `rate`, the wheel at -0.75 rad/s.
fn on_the_cone(z_ws: f64, roll: f64, rate: f64) -> Case {
    Case {
        track: roller_track(200.0, NO_DEVIATION),
        position: [0.0, 0.0, z_ws, roll, 0.0, 0.0],
        velocity: [rate, 0.0, 0.0, 0.0, 0.0, -0.75],
        rig: ELLIPSOID,
        ..CASE_2A
    }
}

/// test-rollers2.inp cases 3a (the ellipsoid on the conical roller, taper
/// 0.2 rad) and 3b (on a cylindrical roller tilted by DROLL = 0.2 rad),
/// Z_WS = -1.870 mm, VPITCH_ROL = 0.24381 rad/s: against CONTACT's library
/// (`placement_cases.py`, cases `3a`, `3b`) and the `.ref_out` (Cases 10
/// and 11: FN 9.805E+04 and 9.786E+04 N, CKSI -3.364E-05, CPHI -2.004E-03,
/// YCP(TR) 180.1450 mm, contact angle 0.2 rad). FN within 0.03 % (ours
/// 98 074 and 97 892 N), the creepages and location as in [`compare`]. FX
/// and FS differ by up to 0.8 % of mu FN (3a: FX 214 N against -18 N, FS
/// 13 956 N against 14 173 N): a difference of this spin-dominated patch
/// (spin 0.002 /mm), not of the roller, for the same wheel on the same
/// profile as a prismatic rail differs as much (`placement_cases.py` case
/// `3a-track`: FX -5147 N against -5339 N, FS 15 403 N against 15 597 N,
/// 0.65 % of mu FN): 1 % of mu FN here.
#[test]
fn roller_rig_cases_3a_3b_match_contacts_library() {
    let cone = on_the_cone(-1.870, 0.0, 0.24381);
    let tilted = Case {
        track: roller_track(200.0, [0.0, 0.0, 0.2, 0.0, 0.0, 0.0]),
        rig: Rig {
            rail: "flat_plane.prr",
            ..ELLIPSOID
        },
        ..cone
    };
    let mu_fn = 0.3 * 9.8e4;
    let apart = [(1, 0.01 * mu_fn), (2, 0.01 * mu_fn)];
    unsafe {
        #[rustfmt::skip]
        check_apart(63, &cone, &[
            98048.7, -18.0522, 14173.3, 33237.4, -3.36359e-05, 0.0, -0.00200439,
            0.0, 180.14504, -4.02480, 0.2, -19.85496, -4.02480, -19.85496, -2.15480,
        ], &apart);
        #[rustfmt::skip]
        check_apart(64, &tilted, &[
            97863.7, -21.475, 14024.2, 33087.6, -3.36417e-05, 0.0, -0.00200439,
            0.0, 180.14504, -4.02480, 0.2, -20.25879, 0.0, -19.85496, -2.15480,
        ], &apart);
    }
}

/// The ellipsoid of test-rollers2.inp case 3a on the conical roller,
/// yawed by 0.02 rad and loaded by FZ = 50 kN (`placement_cases.py` case
/// `3a-yaw`): the wheel's closest point to a prismatic cone would lie 4.13
/// mm behind the axle; with the roller's curvature along x the gap's
/// minimum, and CONTACT's contact point, lie at kw / (kw + kr) of that,
/// -3.12 mm, on the roller's surface there (12 um below its profile).
/// CKSI within 1e-5: the reference point lies 4 um (lateral) and 0.8 um
/// (height) from CONTACT's on the 0.2 rad slope, which changes the wheel's
/// and the roller's surface speeds there by 0.75 x 0.8e-3 and 0.244 x
/// 0.8e-3 mm/s of 98.4 mm/s: 8e-6, as found. The rest as [`compare`].
#[test]
fn a_yawed_wheel_on_a_roller_touches_it_where_contact_does() {
    let mut yawed = on_the_cone(0.0, 0.0, 0.24381);
    yawed.position[4] = 0.02;
    yawed.fz = Some(5.0e4);
    unsafe {
        #[rustfmt::skip]
        check_apart(74, &yawed, &[
            54258.7, 183.764, -15992.2, 4482.29, -0.000238482, 0.020408, -0.00200431,
            -3.12064, 180.10358, -4.02115, 0.2, -19.89642, -4.02115, -19.87003, -2.10532,
        ], &[(4, 1e-5)]);
    }
}

/// The bus on the left roller (C1 = 4, RAILY0 = -200 mm) loaded by FZ =
/// 30 kN, shifted by Y_WS = 0.5 mm, with VY = 1 mm/s, VYAW = 0.001 rad/s
/// and VPITCH = -0.751 rad/s; and on the right roller in a curve of CURV
/// = 5e-5 /mm (20 m), where the rollers turn about z at -r W CURV (CONTACT's
/// `wr_creep_cref`, r the roller's radius at the contact, W its rate):
/// CKSI = 0.0100502 = r k y / (r (1 - k y / 2)), y = 200 mm, and CPHI =
/// -k / (1 - k y / 2). Against CONTACT's library (`placement_cases.py`,
/// cases `2a-left-load`, `2a-curv`).
#[test]
fn a_loaded_left_roller_and_a_curved_roller_match_contacts_library() {
    let left = Case {
        c1: 4,
        track: roller_track(-200.0, NO_DEVIATION),
        position: [0.0, 0.5, 0.0, 0.0, 0.0, 0.0],
        velocity: [0.25, 1.0, 0.0, 0.0, 0.001, -0.751],
        fz: Some(3.0e4),
        ..CASE_2A
    };
    let curved = in_a_curve(CASE_2A, 5.0e-5, 3.0e4);
    unsafe {
        #[rustfmt::skip]
        check(65, &left, &[
            29999.9, 641.059, 8971.12, -393.484, -0.000671917, -0.0100034, -1.00034e-05,
            0.0, -200.0, 0.0, 0.0, 0.0, 0.0, -0.5, -0.07306,
        ]);
        #[rustfmt::skip]
        check(66, &curved, &[
            29999.9, -8993.95, 41.3389, 55.392, 0.0100502, 0.0, -5.02513e-05,
            0.0, 200.0, 0.0, 0.0, 0.0, 0.0, 0.0, -0.07306,
        ]);
    }
}

/// Track curvature CURV on a track: the sphere loaded by 50 kN on the
/// plane at RAILY0 = +-200 mm in a right-hand curve of CURV = 1e-5 /mm
/// (100 m), free rolling: CKSI = k y / (1 - k y / 2) = +-0.002002 and
/// CPHI -1.001e-5 and -0.999e-5 /mm (the rails turning at -V k under the
/// wheelset, CONTACT's `wr_creep_cref`); and the Manchester benchmark's
/// right wheel at 2 mm with VYAW = 0.001 rad/s in a left-hand curve of
/// 300 m (CURV = -1/300 000 /mm). Against CONTACT's library
/// (`placement_cases.py`, cases `curv`, `curv-left`, `curv-mbench`).
#[test]
fn track_curvature_matches_contacts_library() {
    let right = in_a_curve(CASE_1A, 1.0e-5, 5.0e4);
    let mbench = Case {
        track: [14.0, 0.0, 1435.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        position: [0.0, 2.0, 0.0, 0.0, 0.001, 0.0],
        velocity: [2000.0, 0.0, 0.0, 0.0, 0.0, -4.34],
        fz: Some(1.0e4),
        rig: Rig {
            rail: "MBench_UIC60_v3.prr",
            wheel: "MBench_S1002_v3.prw",
            dims: [1360.0, -70.0, 460.0],
            curv: Some(-1.0 / 300e3),
        },
        ..CASE_1A
    };
    unsafe {
        check(
            67,
            &right,
            &[
                50000.0, -6238.78, 39.6134, 69.6167, 0.002002, 0.0, -1.001e-05, 0.0, 200.0, 0.0,
                0.0, 0.0, 0.0, 0.0, -0.10268,
            ],
        );
        #[rustfmt::skip]
        check(68, &on_the_left(right), &[
            50000.0, 6228.33, 39.5383, 69.4736, -0.001998, 0.0, -9.99001e-06,
            0.0, -200.0, 0.0, 0.0, 0.0, 0.0, 0.0, -0.10268,
        ]);
        #[rustfmt::skip]
        check(69, &mbench, &[
            9943.17, 2759.74, -1108.51, -299.73, -0.00296135, 0.000999389, 0.000176413,
            -0.70207, 740.97180, 0.65025, -0.079930, -19.56076, 0.65025, -11.02787, 0.57692,
        ]);
    }
}

/// FX_WS prescribed (F = 1, the pitch rate VPITCH found) on a roller rig,
/// with flexible wheelset deviations and with rail deviation rates
/// (VROLLR among them): the cases of
/// [`a_loaded_left_roller_and_a_curved_roller_match_contacts_library`],
/// [`a_yawed_wheel_on_a_roller_touches_it_where_contact_does`],
/// [`flexible_wheelset_deviations_match_contacts_library`] and
/// [`rail_deviations_match_contacts_library`] with FX_WS = -2000, 4000,
/// 3000 and -3000 N, against CONTACT's library (`placement_cases.py`, cases
/// `2a-left-load-fx`, `3a-yaw-fx`, `flex-fx`, `dev-fx`). On a roller the
/// creepages are relative to the roller's surface speed: the pitch rate is
/// found from it. FN, FX, FS and MZ as [`compare`]; VPITCH within 1e-5 of
/// CONTACT's, and 5e-5 on the cone (3a-yaw), where the same case at F = 0
/// has FX 40 N (0.25 % of mu FN) apart: 4.8e-5 of creepage at this
/// patch's slope of 8.4e5 N.
#[test]
fn a_prescribed_fx_ws_on_rollers_and_moving_rails_matches_contacts_library() {
    let flex = [
        0.5, 0.3, -0.2, 0.02, 0.03, 0.1, 0.04, 0.03, 0.02, 0.0001, 0.0002, 0.0003,
    ];
    let mut cone = on_the_cone(0.0, 0.0, 0.24381);
    cone.position[4] = 0.02;
    let cases = [
        Case {
            c1: 4,
            track: roller_track(-200.0, NO_DEVIATION),
            position: [0.0, 0.5, 0.0, 0.0, 0.0, 0.0],
            velocity: [0.25, 1.0, 0.0, 0.0, 0.001, -0.751],
            fz: Some(3.0e4),
            fx_ws: Some(-2000.0),
            ..CASE_2A
        },
        Case {
            fz: Some(5.0e4),
            fx_ws: Some(4000.0),
            ..cone
        },
        Case {
            position: [0.0, 1.0, 0.0, 0.002, 0.003, 0.0],
            velocity: [100.0, 0.02, 0.01, 0.0002, 0.0003, -1.0],
            flex: Some(flex),
            fz: Some(5.0e4),
            fx_ws: Some(3000.0),
            ..CASE_1A
        },
        Case {
            track: absolute_track(200.0, 0.0, 0.0, [2.0, 0.3, 0.02, 1.0, 0.5, 0.01]),
            position: [0.0, 1.0, 0.0, 0.0, 0.0, 0.0],
            fz: Some(5.0e4),
            fx_ws: Some(-3000.0),
            ..CASE_1A
        },
    ];
    // FN, FX, FS, MZ and VPITCH of CONTACT's library.
    let contact: [([f64; 4], f64, f64); 4] = [
        ([29999.9, -2000.0, 8769.37, -368.009], -0.753115541, 1e-5),
        ([54125.6, 4516.55, -15335.6, 4133.73], -0.746146095, 5e-5),
        ([49999.9, 3021.07, -7119.05, 5367.42], -1.00057141, 1e-5),
        ([50300.7, -2999.99, -14514.2, 2155.2], -1.00207343, 1e-5),
    ];
    for (k, (case, (forces, vpitch, tol))) in cases.iter().zip(contact).enumerate() {
        let ire = 75 + k as i32;
        unsafe {
            assert_eq!(solve(ire, case), 0, "case {k}");
            let got = ours(ire);
            let mu_fn = 0.3 * forces[0];
            for (j, tol) in [
                5e-4 * forces[0],
                5e-3 * mu_fn,
                5e-3 * mu_fn,
                0.01 * forces[0],
            ]
            .into_iter()
            .enumerate()
            {
                close(NAMES[j], got[j], forces[j], tol);
            }
            let mut velocity = [0.0; 6];
            cntc_getwheelsetvelocity(&ire, &6, velocity.as_mut_ptr());
            close("VPITCH", velocity[5], vpitch, tol * vpitch.abs());
            cntc_finalize(&ire);
        }
    }
}

/// What a roller rig refuses: VPITCH_ROL = 0 (rollers standing: the
/// creepages are divided by their surface speed) and X_WS != 0 with -40
/// (not supported); a roll of 0.267 rad (test-rollers2.inp case 3c) with
/// the solver's limit of 0.2 rad (-25); none of them leaves a patch.
#[test]
fn a_roller_rig_refuses_what_it_cannot_solve() {
    let standing = Case {
        velocity: [0.0, 0.0, 0.0, 0.0, 0.0, 0.75],
        ..CASE_2A
    };
    let ahead = Case {
        position: [1.0, 0.0, 0.16, 0.0, 0.0, 0.0],
        ..CASE_2A
    };
    let rolled = on_the_cone(-56.60956, 0.266667, 0.2451499);
    unsafe {
        for (ire, case, code) in [(70, standing, -40), (71, ahead, -40), (72, rolled, -25)] {
            let mut npatch = -1;
            assert_eq!(solve_unchecked(ire, &case, &mut npatch), code);
            assert_eq!(npatch, 0);
        }
    }
}

/// The Manchester benchmark's right wheel (S1002 on UIC60, gauge point
/// placement, FZ = 10 kN) at Y_WS = 2 mm rolling backwards at VS = -20 m/s
/// at VPITCH = `vpitch_over_free` times free rolling (-VS / 460 mm).
fn mbench_backwards(vpitch_over_free: f64) -> Case {
    let vs = -20000.0;
    Case {
        track: [14.0, 0.0, 1435.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        position: [0.0, 2.0, 0.0, 0.0, 0.0, 0.0],
        velocity: [vs, 0.0, 0.0, 0.0, 0.0, -vpitch_over_free * vs / 460.0],
        fz: Some(1.0e4),
        rig: Rig {
            rail: "MBench_UIC60_v3.prr",
            wheel: "MBench_S1002_v3.prw",
            dims: [1360.0, -70.0, 460.0],
            curv: None,
        },
        ..CASE_1A
    }
}

/// CHI of patch 1 of `ire` (`cntc_getparameters`, task 1) \[rad\].
unsafe fn chi(ire: i32) -> f64 {
    let mut values = [0.0; 6];
    cntc_getparameters(&ire, &1, &1, &6, values.as_mut_ptr());
    values[1]
}

/// Rolling backwards (VS < 0, and VPITCH_ROL < 0 on a roller rig), as
/// CONTACT accepts it: the creepages the rail's velocity relative to the
/// wheel's over the positive reference speed, the patch rolling towards
/// -x (CHI = pi). Against the values CONTACT's library (built from
/// eve70a/CONTACT at d431cdb, revision 2707) returned through its
/// `python_intfc` for `crates/cntc/bench/backward_cases.py`, cases
/// `mb-back-free`, `mb-back-brake` (VPITCH 0.3 % below free rolling:
/// braking while reversing, FX < 0 on the rail), `mb-back-yaw` (4 mm, yaw
/// 9.6 mrad), `mb-back-fx` (F = 1, FX_WS = -1500 N) and
/// `2a-left-load-back` (test-rollers2.inp's bus on the left roller, FZ =
/// 30 kN, VY = 1 mm/s, VYAW = 0.001 rad/s, run backwards as its case 2d).
/// All as [`compare`] (creepages within 3e-8, FX within 0.33 % of mu FN,
/// the location within 0.2 um), but FS of the untilted benchmark wheel,
/// 16.9 N and 16.4 N (0.56 % and 0.55 % of mu FN) apart in `mb-back-free`
/// and `mb-back-fx`: the difference of the forward cases, whose mirror
/// images they are (`mb-fwd-free`: CONTACT FS -534.177 N, ours -517.281
/// N, the same as backwards in both libraries). VPITCH found within 2.5e-6
/// relative of CONTACT's.
#[test]
fn rolling_backwards_matches_contacts_library() {
    let free = mbench_backwards(1.0);
    let braked = mbench_backwards(0.997);
    let yawed = Case {
        position: [0.0, 4.0, 0.0, 0.0, 0.0096, 0.0],
        ..free
    };
    let roller = Case {
        c1: 4,
        track: roller_track(-200.0, NO_DEVIATION),
        position: [0.0, 0.5, 0.0, 0.0, 0.0, 0.0],
        velocity: [-0.25, 1.0, 0.0, 0.0, 0.001, 0.751],
        fz: Some(3.0e4),
        ..CASE_2A
    };
    let fs_apart = 6e-3 * 0.3 * 1e4;
    unsafe {
        #[rustfmt::skip]
        check_apart(85, &free, &[
            9989.3, 2429.15, -534.177, 487.752, -0.0013077, 0.0, -0.000173469,
            0.0, 740.97174, 0.65026, -0.079933, -19.56082, 0.65026, -11.02826, 0.57688,
        ], &[(2, fs_apart)]);
        #[rustfmt::skip]
        check(86, &braked, &[
            9995.11, -2736.09, -461.305, 443.29, 0.00169681, 0.0, -0.000173209,
            0.0, 740.97177, 0.65025, -0.079933, -19.56079, 0.65025, -11.02823, 0.57687,
        ]);
        #[rustfmt::skip]
        check(87, &yawed, &[
            10376.6, 656.843, 3041.51, 68.9834, -0.00205875, -0.0096636, -0.000227967,
            -6.58847, 738.94854, 0.83786, -0.105172, -21.58402, 0.83786, -15.02208, 0.94455,
        ]);
        #[rustfmt::skip]
        check_apart(88, &roller, &[
            29999.9, 2999.9, 8479.47, 361.294, -0.00333275, -0.00998334, -9.98334e-06,
            0.0, -200.0, 0.0, 0.0, 0.0, 0.0, -0.5, -0.07306,
        ], &[]);
        for ire in [85, 88] {
            close("CHI", chi(ire), std::f64::consts::PI, 1e-12);
        }
        let fx = Case {
            fx_ws: Some(-1500.0),
            ..free
        };
        let ire = 89;
        assert_eq!(solve(ire, &fx), 0);
        let got = ours(ire);
        let forces = [9981.59, -1500.01, -629.713, 359.678];
        let mu_fn = 0.3 * forces[0];
        for (j, tol) in [5e-4 * forces[0], 5e-3 * mu_fn, fs_apart, 0.01 * forces[0]]
            .into_iter()
            .enumerate()
        {
            close(NAMES[j], got[j], forces[j], tol);
        }
        let mut velocity = [0.0; 6];
        cntc_getwheelsetvelocity(&ire, &6, velocity.as_mut_ptr());
        close("VPITCH", velocity[5], 43.3930181, 1e-5 * 43.3930181);
        for ire in [85, 88, 89] {
            cntc_finalize(&ire);
        }
    }
}
