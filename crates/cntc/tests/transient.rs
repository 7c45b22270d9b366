//! Module 1 transient contact (T = 1 shifts, T = 2 transient rolling)
//! called as a C caller calls it, step by step, against CONTACT's
//! reference outputs of eve70a/CONTACT's `testbank/examples_trans`
//! (`m1_catt_shift`, `m1_totforce`, `m1_trans_roll`, `m1_trans_dqrel`;
//! the latter's wheel with DQREL = 1 also against CONTACT's library, see
//! there), each `.inp` translated
//! into the calls below, each value from its `.ref_out`, per case: "TOTAL FORCES" FN, FX, FS, MN, PMAX and "CONTACT
//! STATISTICS" NCON, NADH, NSLIP). The rail is the cylinder
//! `circ_r100.prr`, the wheel `flat_plane.prw` (nominal radius 100 mm),
//! G = 200 N/mm2, nu = 0.28, mu = 0.4, DX = DS = 0.2 mm.
//!
//! One change of the files: they put the rail and the wheel at the
//! wheelset's centre (RAILY0 = 0, FBDIST = FBPOS = 0), which this library
//! refuses (a wheel profile across the centre); here both lie 200 mm to
//! its right (RAILY0 = 200, FBDIST = 200, FBPOS = -100). With the yaw of
//! 4 mrad that puts the patch 0.8 mm further back (x = -200 mm x 0.004),
//! which moves CONTACT's spin moment, taken about the origin of its
//! super-grid, by -0.8 mm x FS (`MZ_OFFSET_MM`), and the rail's curve
//! under the yawed wheel a little: CONTACT's own library
//! (`crates/cntc/bench/m1_transient.py`) gives FN 240.149 N at 200 mm for
//! 239.838 N at the centre in m1_catt_shift's first case, FX and FS within
//! 0.1 %. The tolerances below hold that.

mod common;

use common::{
    close, patch_totals, profile, read_inp, set_flags, set_profile_file, wheelrail_element, InpDir,
};
use contact_addon::ffi::*;
use contact_addon::flags;

/// Element size DX = DS \[mm\].
const DX: f64 = 0.2;
/// How far the placement here moves the patch along x \[mm\]: the wheel
/// 200 mm right of the centre of a wheelset yawed by 4 mrad.
const MZ_OFFSET_MM: f64 = -0.8;

/// One input sequence: T, N (with Z_WS or FZ), DQREL, DROLLW \[rad\],
/// yaw \[rad\].
struct Sequence {
    tang: i32,
    fz: Option<f64>,
    z_ws: f64,
    dqrel: f64,
    drollw: f64,
    yaw: f64,
}

/// One step: the P digit, S \[mm\], PITCH \[rad\], VS \[mm/s\] (T = 1: the
/// shift \[mm\]), VPITCH \[rad/s\] (T = 1: \[rad\]).
type Step = (i32, f64, f64, f64, f64);

/// One case of a `.ref_out`: FN, FX, FS, MN \[N, N mm\], PMAX \[N/mm2\],
/// NCON, NADH, NSLIP.
type Reference = (f64, f64, f64, f64, f64, f64, f64, f64);

/// Sets up element `ire` as the sequence's first case: CONTACT's units,
/// the materials, friction, discretisation, track, profiles, wheelset and
/// its flexibility (E = 5: DROLLW).
unsafe fn setup(ire: i32, seq: &Sequence) {
    let icp = -1;
    wheelrail_element(
        ire,
        &[
            (flags::IC_CONFIG, 1),
            (flags::IC_TANG, seq.tang),
            (flags::IC_PVTIME, 2),
            (flags::IC_NORM, seq.fz.is_some() as i32),
            (flags::IC_DISCNS, 2),
        ],
    );
    // MAXGS, MAXIN, MAXNR, MAXOUT; EPS (G = 0), as the files give them.
    let (iparam, rparam) = ([999, 100, 30, 1], [1e-5]);
    cntc_setsolverflags(&ire, &icp, &0, &4, iparam.as_ptr(), &1, rparam.as_ptr());
    let mat = [0.28, 0.28, 200.0, 200.0];
    cntc_setmaterialparameters(&ire, &icp, &0, &4, mat.as_ptr());
    cntc_setfrictionmethod(&ire, &icp, &0, &2, [0.4, 0.4].as_ptr());
    if let Some(fz) = seq.fz {
        cntc_setverticalforce(&ire, &fz);
    }
    let pot = [DX, DX, std::f64::consts::FRAC_PI_2, 8.0, 4.0];
    cntc_setpotcontact(&ire, &icp, &-1, &5, pot.as_ptr());
    cntc_setrollingstepsize(&ire, &icp, &0.0, &seq.dqrel);
    let mut track = [0.0; 11];
    track[..2].copy_from_slice(&[-1.0, 200.0]);
    cntc_settrackdimensions(&ire, &3, &11, track.as_ptr());
    set_profile_file(ire, &profile("circ_r100.prr"), 0);
    cntc_setwheelsetdimensions(&ire, &3, &3, [200.0, -100.0, 100.0].as_ptr());
    set_profile_file(ire, &profile("flat_plane.prw"), 0);
    let mut flex = [0.0; 12];
    flex[3] = seq.drollw;
    cntc_setwheelsetflexibility(&ire, &5, &12, flex.as_ptr());
}

/// Calculates `step` of `seq` on `ire`: ierror.
unsafe fn calculate(ire: i32, seq: &Sequence, step: Step) -> i32 {
    let (p, s, pitch, vs, vpitch) = step;
    set_flags(ire, -1, &[(flags::IC_PVTIME, p)]);
    let z = if seq.fz.is_some() { 0.0 } else { seq.z_ws };
    let pos = [s, 0.0, z, 0.0, seq.yaw, pitch];
    cntc_setwheelsetposition(&ire, &5, &6, pos.as_ptr());
    let vel = [vs, 0.0, 0.0, 0.0, 0.0, vpitch];
    cntc_setwheelsetvelocity(&ire, &5, &6, vel.as_ptr());
    let mut ierror = -1;
    cntc_calculate1(&ire, &mut ierror);
    ierror
}

/// Patch 1 of `ire` in a [`Reference`]'s order.
unsafe fn ours(ire: i32) -> Reference {
    patch_of(ire, 1, DX * DX)
}

/// Patch `icp` of `ire` in a [`Reference`]'s order, the areas in elements
/// of `element_mm2`.
unsafe fn patch_of(ire: i32, icp: i32, element_mm2: f64) -> Reference {
    let t = patch_totals(ire, icp);
    let [fn_, fx, fs, mz] = t.forces;
    let [c, h, s] = t.areas.map(|a| a / element_mm2);
    (fn_, fx, fs, mz, t.pmax, c, h, s)
}

/// Runs `steps` of `seq` on `ire` and compares each with its case of the
/// reference output: FN within 0.5 %, FX and FS within `force_tol` of the
/// larger of their sizes (and of the reference's rounding to 4 digits), MN
/// (moved by the placement, [`MZ_OFFSET_MM`] x FS) within `force_tol` of
/// |MN| + 2 mm x |FS| (the moment arm's rounding and the placement) plus
/// 0.05 N mm (the printed digits), PMAX within
/// 0.5 %, NCON within 3 elements, NADH and NSLIP within 1 % of NCON.
unsafe fn compare(ire: i32, seq: &Sequence, steps: &[Step], refs: &[Reference], force_tol: f64) {
    setup(ire, seq);
    for (k, (&step, r)) in steps.iter().zip(refs).enumerate() {
        assert_eq!(calculate(ire, seq, step), 0, "step {}", k + 1);
        let mut npatch = 0;
        cntc_getnumcontactpatches(&ire, &mut npatch);
        assert_eq!(npatch, 1, "step {}", k + 1);
        let o = ours(ire);
        let what = |name: &str| format!("step {} {name}", k + 1);
        let f = r.1.abs().max(r.2.abs());
        let tf = force_tol * f + 0.005 * f.log10().ceil().exp2();
        close(&what("FN"), o.0, r.0, 5e-3 * r.0);
        close(&what("FX"), o.1, r.1, tf);
        close(&what("FS"), o.2, r.2, tf);
        let mz = r.3 + MZ_OFFSET_MM * r.2;
        let tm = force_tol * (r.3.abs() + 2.0 * r.2.abs()) + 0.05;
        close(&what("MZ"), o.3, mz, tm);
        close(&what("PMAX"), o.4, r.4, 5e-3 * r.4);
        close(&what("NCON"), o.5, r.5, 3.0);
        close(&what("NADH"), o.6, r.6, 0.01 * r.5);
        close(&what("NSLIP"), o.7, r.7, 0.01 * r.5);
    }
}

/// m1_catt_shift.inp's sequence: T = 1, Z_WS = -0.2201 mm, DQREL 1,
/// DROLLW = 5 deg (0.0872665 rad), yaw 4 mrad.
const CATT: Sequence = Sequence {
    tang: 1,
    fz: None,
    z_ws: -0.2201,
    dqrel: 1.0,
    drollw: 0.087_266_462_599_716_48,
    yaw: 0.004,
};

/// m1_catt_shift.inp's steps: a first shift (P = 2) of 4 mm and -0.03984 rad, then steps of 0.2
/// mm and -0.001992 rad, PITCH stepping as the file's.
fn catt_shift_steps(n: usize) -> Vec<Step> {
    let mut steps = vec![(2, 0.0, 0.0, 4.0, -0.03984)];
    for k in 1..n {
        let pitch = if k == 1 { -0.002 } else { -0.004 };
        steps.push((0, 0.2 * k as f64, pitch, 0.2, -0.001992));
    }
    steps
}

/// m1_catt_shift.ref_out, cases 1-10.
const CATT_SHIFT: [Reference; 10] = [
    (239.8, -23.19, -26.15, 286.0, 7.100, 1279.0, 843.0, 436.0),
    (239.8, -23.92, -26.29, 288.6, 7.100, 1279.0, 932.0, 347.0),
    (239.8, -24.62, -26.40, 290.8, 7.100, 1279.0, 926.0, 353.0),
    (239.8, -25.31, -26.48, 292.5, 7.100, 1279.0, 917.0, 362.0),
    (239.8, -25.96, -26.53, 293.8, 7.100, 1279.0, 914.0, 365.0),
    (239.8, -26.60, -26.56, 294.7, 7.100, 1279.0, 906.0, 373.0),
    (239.8, -27.20, -26.55, 295.2, 7.100, 1279.0, 899.0, 380.0),
    (239.8, -27.78, -26.53, 295.4, 7.100, 1279.0, 894.0, 385.0),
    (239.8, -28.34, -26.49, 295.2, 7.100, 1279.0, 889.0, 390.0),
    (239.8, -28.87, -26.43, 294.8, 7.100, 1279.0, 883.0, 396.0),
];

#[test]
fn shifts_from_cattaneo_towards_carter_match_contacts_reference() {
    let seq = CATT;
    unsafe { compare(71, &seq, &catt_shift_steps(10), &CATT_SHIFT, 5e-3) };
}

/// m1_totforce.ref_out, cases 1-10.
const TOTFORCE: [Reference; 10] = [
    (238.0, -1.323, -1.493, 17.51, 7.082, 1273.0, 1253.0, 20.0),
    (238.2, -2.614, -2.909, 33.84, 7.083, 1273.0, 1234.0, 39.0),
    (238.3, -3.874, -4.249, 49.06, 7.084, 1273.0, 1217.0, 56.0),
    (238.4, -5.100, -5.519, 63.20, 7.085, 1273.0, 1201.0, 72.0),
    (238.5, -6.299, -6.720, 76.38, 7.086, 1274.0, 1191.0, 83.0),
    (238.6, -7.469, -7.855, 88.62, 7.087, 1274.0, 1172.0, 102.0),
    (238.7, -8.605, -8.922, 99.89, 7.088, 1275.0, 1157.0, 118.0),
    (238.8, -9.711, -9.930, 110.3, 7.089, 1275.0, 1145.0, 130.0),
    (238.9, -10.79, -10.88, 119.9, 7.090, 1275.0, 1131.0, 144.0),
    (238.9, -11.84, -11.77, 128.8, 7.091, 1275.0, 1119.0, 156.0),
];

/// m1_totforce.inp: the shifts of m1_catt_shift's steps from the first
/// (0.2 mm and -0.001992 rad), under FZ = 237 N (N = 1).
#[test]
fn shifts_under_a_vertical_force_match_contacts_reference() {
    let seq = Sequence {
        fz: Some(237.0),
        z_ws: 0.0,
        ..CATT
    };
    let mut steps = catt_shift_steps(10);
    steps[0] = (2, 0.0, 0.0, 0.2, -0.001992);
    unsafe { compare(72, &seq, &steps, &TOTFORCE, 5e-3) };
}

/// m1_trans_dqrel.inp's first sequence with DQREL = 1 instead of its 4
/// ([`transient_rolling_several_elements_a_step_matches_contact`]),
/// as CONTACT's library (revision 2707) solves it through
/// `crates/cntc/bench/m1_transient.py` (case `trans_dq1`): no reference
/// output has it.
const TRANS_DQ1: [Reference; 3] = [
    (237.034, 14.7753, 0.0, 0.0, 7.0753, 1273.0, 1137.0, 136.0),
    (237.034, 15.9892, 0.0, 0.0, 7.0753, 1273.0, 1179.0, 94.0),
    (237.034, 17.175, 0.0, 0.0, 7.0753, 1273.0, 1171.0, 102.0),
];

/// m1_trans_dqrel.inp's wheel (T = 2, Z_WS = 0.160 mm, no deviation or
/// yaw: the placement changes nothing) rolling `dqrel` elements a step.
fn on_the_crown(dqrel: f64) -> Sequence {
    Sequence {
        tang: 2,
        fz: None,
        z_ws: 0.160,
        dqrel,
        drollw: 0.0,
        yaw: 0.0,
    }
}

/// m1_trans_dqrel.inp's steps: VS = 100 mm/s, VPITCH -0.960 rad/s in the
/// first step (P = 2) and -0.996 after.
const ON_THE_CROWN_STEPS: [Step; 3] = [
    (2, 0.0, 0.0, 100.0, -0.960),
    (0, 0.0, 0.0, 100.0, -0.996),
    (0, 0.0, 0.0, 100.0, -0.996),
];

/// [`on_the_crown`] rolling one element a step.
#[test]
fn transient_rolling_on_the_crown_matches_contacts_library() {
    unsafe {
        compare(
            73,
            &on_the_crown(1.0),
            &ON_THE_CROWN_STEPS,
            &TRANS_DQ1,
            5e-3,
        )
    };
}

/// m1_trans_dqrel.inp's first sequence with DQREL = 2 instead of its 4, as
/// CONTACT's library (revision 2707) solves it through
/// `crates/cntc/bench/m1_transient.py` (case `trans_dq2`): no reference
/// output has it.
const TRANS_DQ2: [Reference; 3] = [
    (237.034, 28.3572, 0.0, 0.0, 7.0753, 1273.0, 979.0, 294.0),
    (237.034, 30.2023, 0.0, 0.0, 7.0753, 1273.0, 1097.0, 176.0),
    (237.034, 31.9248, 0.0, 0.0, 7.0753, 1273.0, 1092.0, 181.0),
];

/// m1_trans_dqrel.ref_out, cases 1-3 (its "TOTAL FORCES" and "CONTACT
/// STATISTICS" of each case; FS and MN print as 0).
const TRANS_DQREL: [Reference; 3] = [
    (237.0, 51.71, 0.0, 0.0, 7.075, 1273.0, 696.0, 577.0),
    (237.0, 53.14, 0.0, 0.0, 7.075, 1273.0, 892.0, 381.0),
    (237.0, 54.03, 0.0, 0.0, 7.075, 1273.0, 859.0, 414.0),
];

/// [`on_the_crown`] rolling several elements a step, the elements
/// entering the contact area in a step with CONTACT's leading-edge
/// correction: four (DQREL = 4, m1_trans_dqrel.inp as it is) against its
/// reference output, two against CONTACT's library.
#[test]
fn transient_rolling_several_elements_a_step_matches_contact() {
    for (ire, dqrel, refs) in [(79, 4.0, &TRANS_DQREL), (80, 2.0, &TRANS_DQ2)] {
        unsafe { compare(ire, &on_the_crown(dqrel), &ON_THE_CROWN_STEPS, refs, 5e-3) };
    }
}

/// m1_trans_roll.ref_out, cases 1-10.
const TRANS_ROLL: [Reference; 10] = [
    (239.8, -1.323, -1.483, 17.54, 7.100, 1279.0, 1258.0, 21.0),
    (239.8, -2.615, -2.890, 34.49, 7.100, 1279.0, 1239.0, 40.0),
    (239.8, -3.875, -4.220, 50.84, 7.100, 1279.0, 1222.0, 57.0),
    (239.8, -5.101, -5.480, 66.61, 7.100, 1279.0, 1205.0, 74.0),
    (239.8, -6.299, -6.672, 81.84, 7.100, 1279.0, 1196.0, 83.0),
    (239.8, -7.468, -7.797, 96.57, 7.100, 1279.0, 1176.0, 103.0),
    (239.8, -8.604, -8.854, 110.7, 7.100, 1279.0, 1162.0, 117.0),
    (239.8, -9.709, -9.853, 124.3, 7.100, 1279.0, 1150.0, 129.0),
    (239.8, -10.79, -10.79, 137.4, 7.100, 1279.0, 1135.0, 144.0),
    (239.8, -11.83, -11.67, 150.0, 7.100, 1279.0, 1122.0, 157.0),
];

/// m1_trans_roll.inp: T = 2 from rest (P = 2), VS = 100 mm/s, VPITCH =
/// -0.996 rad/s, DROLLW = 5 deg, DQREL = 1. FX and FS within 1.5 %: this
/// library's creepages of the wheel rolled by DROLLW are relative to its
/// rolling speed about its own axle, CONTACT's about the wheelset's (the
/// module docs of `cntc_core::module1`), 0.38 % larger here (VELOC 99.80
/// against CONTACT's 100.18 mm/s, `crates/cntc/bench/m1_transient.py`);
/// in steady rolling (T = 3) of the same wheel FS is 1.4 % larger than
/// CONTACT's library's for the same reason (-23.87 N against -23.55 N).
#[test]
fn transient_rolling_matches_contacts_reference() {
    let seq = Sequence { tang: 2, ..CATT };
    let steps = [(2, 0.0, 0.0, 100.0, -0.996)]
        .into_iter()
        .chain(std::iter::repeat_n((0, 0.0, 0.0, 100.0, -0.996), 9))
        .collect::<Vec<_>>();
    unsafe { compare(74, &seq, &steps, &TRANS_ROLL, 1.5e-2) };
}

/// The P digit picks the history: P = 3 solves the last step again from
/// what it started from (the same forces, bit for bit, however often), and
/// a new sequence (P = 2) forgets the history: after four shifts, the first
/// shift again gives the first step's forces, bit for bit.
#[test]
fn the_p_digit_picks_the_history() {
    let ire = 75;
    let seq = CATT;
    unsafe {
        setup(ire, &seq);
        let steps = catt_shift_steps(4);
        let mut first = None;
        for &step in &steps {
            assert_eq!(calculate(ire, &seq, step), 0);
            first.get_or_insert(ours(ire));
        }
        let last = ours(ire);
        assert_ne!(first, Some(last), "the shifts changed nothing");
        let (_, s, pitch, vs, vpitch) = steps[3];
        for _ in 0..2 {
            assert_eq!(calculate(ire, &seq, (3, s, pitch, vs, vpitch)), 0);
            assert_eq!(ours(ire), last);
        }
        assert_eq!(calculate(ire, &seq, steps[0]), 0);
        assert_eq!(first, Some(ours(ire)));
    }
}

/// What transient contact does not take is refused with CONTACT's -40
/// (not supported): a rolling step of a fraction of an element (DQREL =
/// 2.5; 4 as in m1_trans_dqrel.inp is taken), a prescribed total force
/// FX_WS (F = 1).
#[test]
fn unsupported_transient_inputs_are_refused() {
    let ire = 76;
    let seq = Sequence {
        tang: 2,
        fz: Some(237.0),
        z_ws: 0.0,
        dqrel: 2.5,
        drollw: 0.0,
        yaw: 0.0,
    };
    unsafe {
        setup(ire, &seq);
        let step = (2, 0.0, 0.0, 100.0, -0.996);
        assert_eq!(calculate(ire, &seq, step), -40);
        cntc_setrollingstepsize(&ire, &-1, &0.0, &4.0);
        assert_eq!(calculate(ire, &seq, step), 0);
        set_flags(ire, -1, &[(flags::IC_FORCE, 1)]);
        cntc_settangentialforces(&ire, &-1, &10.0, &0.0);
        assert_eq!(calculate(ire, &seq, step), -40);
    }
}

/// m1_catt_shift.inp's first case (with this file's placement, the
/// profiles named by their paths) read by `cntc_readinpfile` is the same
/// element as the calls of [`setup`] make: its first shift gives the same
/// forces, bit for bit.
#[test]
fn a_transient_input_file_reads_as_its_calls() {
    let dir = InpDir::new("transient");
    let text = format!(
        "% From Cattaneo to Carter using shift (T=1)\n\
         \n  1 MODULE\n\
         \x20 1201000    C-P-B-T-N-F-S\n\
         \x20 0022035    V-L-D-C-M-Z-E\n\
         \x20 0001321    H-G-I-A-O-W-R\n\
         \x20   999     100    30    1     1e-5             MAXGS , MAXIN , MAXNR , MAXOUT, EPS\n\
         \x20 0.400   0.400                                 FSTAT, FKIN\n\
         \x20 0.280   0.280   200.0   200.0                 POISS 1,2,  GG 1,2\n\
         \x20 0.200   0.200   1.000   90d   8.0   4.0       DX, DS, DQREL, A_SEP, D_SEP, D_COMB\n\
         \x20  -1.0 200.000   0.000   0.000                 GAUGHT, RAILY0, RAILZ0, CANT\n\
         \x20 '{}'   0     1.0   0.0             RFNAME, MIRRORY, SCALE, SMOOTH\n\
         \x20    0.0    0.0   0.000   0.0   0.0   0.000     DY, DZ, ROLL, VY, VZ, VROLL\n\
         \x20  200.0 -100.0   100.0                         FBDIST, FBPOS, NOMRAD\n\
         \x20 '{}'        0     1.0   0.0       WFNAME, MIRRORY, SCALE, SMOOTH\n\
         \x20  0.0   0.0  -0.2201   0.0   0.004  0.0        S, Y, FZ, ROLL, YAW, PITCH\n\
         \x20 4.000  0.0     0.0    0.0   0.0   -0.03984   DS,DY,DZ, DROLL,DYAW,DPITCH\n\
         \x20  0.0   0.0     0.0    5.0d  0.0    0.0        DXWHL--DPITCHW\n\
         \x20  0.0   0.0     0.0    0.0   0.0    0.0        VXWHL--VPITCHW\n\
         \n  0 MODULE\n",
        profile("circ_r100.prr"),
        profile("flat_plane.prw")
    );
    let path = dir.write("catt_shift_1.inp", &text);
    unsafe {
        let ire = 77;
        wheelrail_element(ire, &[]);
        assert_eq!(read_inp(ire, flags::INP_MODUL1, &path), 0);
        let mut ierror = -1;
        cntc_calculate1(&ire, &mut ierror);
        assert_eq!(ierror, 0);
        let from_file = ours(ire);
        let ire = 78;
        setup(ire, &CATT);
        assert_eq!(calculate(ire, &CATT, catt_shift_steps(1)[0]), 0);
        assert_eq!(from_file, ours(ire));
    }
}

// ---------------------------------------------------------------------
// Several patches per wheel: CONTACT's t1_merge_cp and t1_split_cp.

/// The first case of `testbank/examples_trans/t1_merge_cp.inp` (and of
/// t1_split_cp.inp, which differs in Z_WS and in the I digit, 0 or 1, which
/// start the first solve from nothing either way) on elements
/// of `dx_mm` with one change: V = 0 with FSTAT = FKIN = 0.35 for its V = 1
/// table (friction by contact angle: 0.2 at -30 deg and below, 0.35 at -20
/// deg and above; the tread patches lie above it, DELTCP -0.196, -0.213,
/// -0.259 rad, the flange patch below, -1.270 rad). The places and
/// angles of the patches do not depend on the friction; their forces are
/// compared with CONTACT's library run on this same input.
fn t1_case(z_ws: f64, dx_mm: f64) -> String {
    t1_case_as(z_ws, dx_mm, 0)
}

/// [`t1_case`] with the N digit `n`: N = 1 takes `z_or_fz` as the
/// vertical force FZ \[N\] (t1_force_cp.inp's first case, with V = 0 and
/// 0.35 as [`t1_case`]).
fn t1_case_as(z_or_fz: f64, dx_mm: f64, n: u8) -> String {
    format!(
        "% t1_merge_cp.inp / t1_split_cp.inp with V = 0\n\
         \n  1  MODULE\n\
         \x20 1201{n}00        C-P-B-T-N-F-S\n\
         \x20 0022033        V-L-D-C-M-Z-E\n\
         \x20 0001321        H-G-I-A-O-W-R\n\
         \x20  999   100   30    1    1.0E-06              MAXGS , MAXIN , MAXNR , MAXOUT, EPS\n\
         \x20 0.35  0.35                                      FSTAT, FKIN\n\
         \x20 0.2800      0.2800      0.8200E+05  0.8200E+05  POISS 1,2,  GG 1,2\n\
         \x20 {dx_mm}  {dx_mm}  1.000   90d   6.0   3.0  DX, DS, DQREL, A_SEP, D_SEP, D_COMB\n\
         \x20 15.8750      0    1435.10   0.000               GAUGHT, GAUGSQ, GAUGWD, CANT\n\
         \x20'{}'   0  1.0   0.0  RFNAME, MIRRORY, SCALE, SMOOTH\n\
         \x20  0.00000       0.00000       0.00000          % DY, DZ, DROLLR\n\
         \x20  0.00000       0.00000       0.00000            VY, VZ, VROLL\n\
         \x20  1347.40       0.00000       444.000            FBDIST, FBPOS, NOMRAD\n\
         \x20'{}'    0  1.0   0.0  WFNAME, MIRRORY, SCALE, SMOOTH\n\
         \x20 0.0     14.74   {z_or_fz}   -0.0013   0.0050      0.0       S, Y, Z, ROLL, YAW, PITCH\n\
         \x20 0.400     0.0   0.0      0.0      0.0    -0.00086667    VS, VY, VZ VROLL, VYAW, VPITCH\n\
         \n  0  MODULE\n",
        profile("site_b_hr.prr"),
        profile("worn_high_mileage.prw")
    )
}

/// One patch of ours: XCP(TR), YCP(TR) \[mm\], DELTCP(TR) \[rad\], FN, FX,
/// FS \[N\], PMAX \[N/mm2\].
type T1Patch = (f64, f64, f64, f64, f64, f64, f64);

/// Runs the two steps of a t1 case on elements of `dx_mm` (the first from
/// [`t1_case`], the second P = 0 at S = 0.4 mm, Z_WS `z_second`, shifts VS
/// = 0.004 mm and VPITCH = -8.6667e-6 rad, as the files' second case): per
/// step, the patches in the library's order. Prints them.
unsafe fn t1_steps(
    ire: i32,
    name: &str,
    [z_first, z_second]: [f64; 2],
    dx_mm: f64,
) -> [Vec<T1Patch>; 2] {
    let dir = InpDir::new(&format!("{name}-{ire}"));
    let path = dir.write(&format!("{name}.inp"), &t1_case(z_first, dx_mm));
    wheelrail_element(ire, &[]);
    assert_eq!(read_inp(ire, flags::INP_MODUL1, &path), 0);
    [0, 1].map(|step| {
        if step == 1 {
            set_flags(ire, -1, &[(flags::IC_PVTIME, 0)]);
            let pos = [0.4, 14.74, z_second, -0.0013, 0.005, 0.0];
            cntc_setwheelsetposition(&ire, &1, &6, pos.as_ptr());
            let vel = [0.004, 0.0, 0.0, 0.0, 0.0, -8.6667e-6];
            cntc_setwheelsetvelocity(&ire, &1, &6, vel.as_ptr());
        }
        let mut ierror = -1;
        cntc_calculate1(&ire, &mut ierror);
        assert_eq!(ierror, 0, "{name} DX {dx_mm} step {}", step + 1);
        let patches = t1_patches(ire);
        println!("{name} DX {dx_mm} step {}: {patches:?}", step + 1);
        patches
    })
}

/// The patches of `ire` in the library's order.
unsafe fn t1_patches(ire: i32) -> Vec<T1Patch> {
    let mut n = 0;
    cntc_getnumcontactpatches(&ire, &mut n);
    (1..=n)
        .map(|icp| {
            let (fn_, fx, fs, _, pmax, ..) = patch_of(ire, icp, 1.0);
            let mut loc = [0.0; 4];
            cntc_getcontactlocation(&ire, &icp, &4, loc.as_mut_ptr());
            (loc[0], loc[1], loc[3], fn_, fx, fs, pmax)
        })
        .collect()
}

/// Per step, per patch of a t1 `.ref_out` (CONTACT's 0.4 mm elements):
/// its "CONTACT REFERENCE LOCATION" XCP(TR), YCP(TR) \[mm\] and DELTCP(TR)
/// \[rad\].
type T1Places<'a> = [&'a [(f64, f64, f64)]; 2];

/// Compares the patches of `ours` (0.4 mm) with a `.ref_out`'s: as many
/// per step, each where CONTACT puts it (XCP, YCP within 0.01 mm; CONTACT
/// prints 0.1 um) at its contact angle (within 1 mrad; it prints 0.1
/// mrad). The angles are CONTACT's turned ones: the two tread patches of
/// t1_merge_cp's first step, their facing ends 6.4 mm apart, between D_SEP
/// (6 mm) and D_TURN (9 mm), have weighted mean angles of -0.066 and
/// -0.579 rad and are turned to -0.196 and -0.259 rad.
fn compare_places(name: &str, ours: &[Vec<T1Patch>; 2], want: T1Places) {
    per_patch(name, ours, &want, |what, p, r| {
        close(&what("XCP"), p.0, r.0, 0.01);
        close(&what("YCP"), p.1, r.1, 0.01);
        close(&what("DELTCP"), p.2, r.2, 1e-3);
    });
}

/// Asserts that `ours` has as many patches per step as `want` and calls
/// `check` on each with its entry of `want` and the name of a field of it.
fn per_patch<W>(
    name: &str,
    ours: &[Vec<T1Patch>],
    want: &[&[W]],
    check: impl Fn(&dyn Fn(&str) -> String, &T1Patch, &W),
) {
    for (step, (o, w)) in ours.iter().zip(want).enumerate() {
        let n = step + 1;
        assert_eq!(o.len(), w.len(), "{name} step {n}: number of patches");
        for (k, (p, r)) in o.iter().zip(w.iter()).enumerate() {
            check(
                &|field| format!("{name} step {n} patch {} {field}", k + 1),
                p,
                r,
            );
        }
    }
}

/// Per step, per patch, CONTACT's library on 0.1 mm elements: YCP(TR)
/// \[mm\] (which patch), FN, FX, FS (None: not compared, see the tests)
/// \[N\], PMAX \[N/mm2\].
type T1Library<'a> = [&'a [T1LibraryPatch]; 2];

/// Compares `ours` with CONTACT's library patch by patch: YCP within
/// 0.01 mm, FN, FX, FS each within 1 % of itself (FX and FS carry the
/// step's history: a second step started afresh moves t1_merge_cp's merged
/// patch's FX by 1.5 %), PMAX within 1 %.
fn compare_library(name: &str, ours: &[Vec<T1Patch>], want: &[&[T1LibraryPatch]]) {
    per_patch(name, ours, want, |what, p, &(y, fn_, fxs, pmax)| {
        close(&what("YCP"), p.1, y, 0.01);
        close(&what("FN"), p.3, fn_, 0.01 * fn_);
        if let Some([fx, fs]) = fxs {
            close(&what("FX"), p.4, fx, 0.01 * fx.abs());
            close(&what("FS"), p.5, fs, 0.01 * fs.abs());
        }
        close(&what("PMAX"), p.6, pmax, 0.01 * pmax);
    });
}

/// t1_merge_cp.ref_out: Z_WS 1.2110 mm gives three patches (two on the
/// tread at YCP(TR) 754.66 and 723.39 mm, one on the flange at 714.26
/// mm); 1 micrometre lower (1.2120) the two tread patches are one (CONTACT's
/// "PATCH 1 (PREV 1, 2)"), which takes both their tractions as its
/// history; the flange patch keeps its own ("PATCH 2 (PREV 3)").
///
/// The forces on CONTACT's 0.4 mm elements are its discretisation's: its
/// library on this input moves by up to 2.2 % from 0.4 to 0.1 mm (FN of
/// the tread patch at 723.39 mm 47969, 47410.6, 47280.1 N on 0.4, 0.2, 0.1
/// mm; of the flange patch 4394.2, 4473.8, 4493.7 N; its PMAX 633.6,
/// 620.4, 627.2 N/mm2) where ours moves by 0.4 % (47263.4, 47252.3,
/// 47244.9 N; 4484.6, 4502.0, 4499.8 N; PMAX 670.2, 627.4, 626.2 on the
/// flange's few elements): the forces are compared on 0.1 mm with
/// CONTACT's library there (`cntc_readinpfile` of [`t1_case`] with DX =
/// DS = 0.1, these steps, then `cntc_getcontactforces`,
/// `cntc_getmaximumpressure`, `cntc_getcontactlocation` per patch; the
/// contact-kit build of CONTACT revision 2707, eve70a/CONTACT), its values
/// printed to the digits below (ours within 0.15 %).
#[test]
fn merging_patches_match_contacts_reference() {
    let ire = 81;
    let z = [1.211, 1.212];
    let places: T1Places = [
        &[
            (-3.5536, 754.6563, -0.1957),
            (-2.0554, 723.3895, -0.2589),
            (4.0759, 714.2580, -1.2698),
        ],
        &[(-3.1226, 745.6461, -0.2133), (4.0763, 714.2591, -1.2698)],
    ];
    let library: T1Library = [
        &[
            (754.6563, 79130.7, Some([19320.4, -2311.48]), 807.14),
            (723.3895, 47280.1, Some([6507.98, -1718.33]), 1646.2),
            (714.2571, 4493.67, Some([-1237.76, -938.591]), 627.15),
        ],
        &[
            (745.6461, 126698.0, Some([25386.2, -4008.34]), 1684.7),
            (714.2582, 4658.54, Some([-1216.52, -941.516]), 635.02),
        ],
    ];
    unsafe {
        compare_places("t1_merge_cp", &t1_steps(ire, "t1_merge_cp", z, 0.4), places);
        let fine = t1_steps(ire + 1, "t1_merge_cp", z, 0.1);
        compare_library("t1_merge_cp 0.1 mm", &fine, &library);
    }
}

/// One patch of CONTACT's library in a [`T1Library`].
type T1LibraryPatch = (f64, f64, Option<[f64; 2]>, f64);

/// t1_split_cp's first step, CONTACT's library on 0.1 mm
/// ([`merging_patches_match_contacts_reference`] says how).
const SPLIT_FIRST: [T1LibraryPatch; 2] = [
    (745.6461, 126698.0, Some([25776.3, -3520.78]), 1684.6),
    (714.2582, 4658.51, Some([-1282.45, -972.924]), 634.93),
];

/// t1_split_cp's second step, as [`SPLIT_FIRST`].
const SPLIT_SECOND: [T1LibraryPatch; 3] = [
    (754.6563, 79130.8, Some([20161.4, -2314.6]), 807.14),
    (723.3895, 47280.0, Some([5916.98, -1471.63]), 1646.4),
    (714.2571, 4493.71, Some([-1208.36, -940.75]), 627.25),
];

/// t1_split_cp.ref_out's patches: the other way round, Z_WS 1.2120 then
/// 1.2110 mm: the tread patch splits in two ("PATCH 1 (PREV 1)", "PATCH
/// 2 (PREV 1)"). Forces as in [`merging_patches_match_contacts_reference`],
/// on 0.1 mm against CONTACT's library, but for the outer part's FX and
/// FS after the split: that part (YCP 754.66 mm) takes another history
/// than CONTACT's. CONTACT keeps the split patch's grid for it (its
/// super-grid's y from -32 to +17 mm, 123 rows on 0.4 mm, as the split
/// patch's; the inner part gets 29 rows, its own region), so the inner
/// part's last tractions (47 kN, FX 6 kN, 31 mm away) enter the outer
/// part's last displacements but not its current ones; this library
/// gives each part the history on its own lateral range. Ours are FX
/// 19479.1, FS -2071.32 N against 20161.4, -2314.6 (3.4 % and 10.5 %
/// apart). A scratch build whose outer grid spans the split patch, with
/// its elements outside the outer part's range out of contact, gives
/// 20161.1, -2314.9 N on 0.1 mm (and 20162.0, -2315.1 on 0.2 mm against
/// CONTACT's 20166.6, -2315.9): that history is the whole difference.
#[test]
fn splitting_patches_match_contacts_reference() {
    let ire = 83;
    let z = [1.212, 1.211];
    let places: T1Places = [
        &[(-3.1226, 745.6461, -0.2133), (4.0763, 714.2591, -1.2698)],
        &[
            (-3.5536, 754.6563, -0.1957),
            (-2.0554, 723.3895, -0.2589),
            (4.0759, 714.2580, -1.2698),
        ],
    ];
    let mut second = SPLIT_SECOND;
    second[0].2 = None;
    let library: T1Library = [&SPLIT_FIRST, &second];
    unsafe {
        compare_places("t1_split_cp", &t1_steps(ire, "t1_split_cp", z, 0.4), places);
        let fine = t1_steps(ire + 1, "t1_split_cp", z, 0.1);
        compare_library("t1_split_cp 0.1 mm", &fine, &library);
    }
}

/// t1_force_cp.inp's first case (FZ = 127 kN given, N = 1; V = 0 with
/// 0.35 as [`t1_case`]) on 0.2 mm elements: two patches, the merged tread
/// patch and the flange patch, where CONTACT's library puts the wheelset
/// on them on 0.1 mm elements, its converged answer (Z_WS 1.21364,
/// 1.21388 mm on 0.2, 0.1 mm, the flange's FN 4915.22, 4974.31 N; on 0.4
/// mm it lands on the case's other solution, three patches at Z_WS
/// 1.21097 mm, which the file's comment names; called as
/// [`merging_patches_match_contacts_reference`] says, with
/// `cntc_getwheelsetposition`). Ours moves by 0.02 um and 0.1 % from 0.2 to
/// 0.1 mm and takes a minute there in a debug build: compared on 0.2 mm,
/// Z_WS within 0.1 um (ours 0.02 um away), FN, FX, FS within 1 % (ours
/// within 0.05 %); PMAX not (it is the grid's). The wheel's reference
/// points move fast with the approach here (the tread patch's centre by 18
/// um per um): placed by plain repetition, four passes left the answer 1.1
/// um lower with the flange's FN 3.8 % above.
#[test]
fn a_vertical_force_finds_contacts_two_patches() {
    let ire = 86;
    let dir = InpDir::new("t1_force_cp");
    let path = dir.write("t1_force_cp.inp", &t1_case_as(127000.0, 0.2, 1));
    let want = [
        (745.6853, 126632.0, [25761.1, -3515.25]),
        (714.2604, 4974.31, [-1367.95, -1038.66]),
    ];
    unsafe {
        wheelrail_element(ire, &[]);
        assert_eq!(read_inp(ire, flags::INP_MODUL1, &path), 0);
        let mut ierror = -1;
        cntc_calculate1(&ire, &mut ierror);
        assert_eq!(ierror, 0);
        let mut ws = [0.0; 6];
        cntc_getwheelsetposition(&ire, &6, ws.as_mut_ptr());
        let ours = t1_patches(ire);
        println!("t1_force_cp 0.2 mm: Z_WS {} {ours:?}", ws[2]);
        close("t1_force_cp Z_WS", ws[2], 1.21387792, 1e-4);
        per_patch(
            "t1_force_cp",
            &[ours],
            &[&want],
            |what, p, &(y, fn_, [fx, fs])| {
                close(&what("YCP"), p.1, y, 0.01);
                close(&what("FN"), p.3, fn_, 0.01 * fn_);
                close(&what("FX"), p.4, fx, 0.01 * fx.abs());
                close(&what("FS"), p.5, fs, 0.01 * fs.abs());
            },
        );
    }
}
