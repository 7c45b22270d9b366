"""m1_fastrip_cases.py PYTHON_INTFC LIBRARY [CASE ...]

Module 1 with CONTACT's modified FaStrip (M = 5) on the wheel/rail
patches: the Manchester benchmark's right wheel (S1002 on UIC60,
gauge-point placement) at several lateral shifts and yaw angles of its
A-2.2 series, read from module 1 input files (`cntc_readinpfile`)
through CONTACT's own Python interface (`python_intfc`, ctypes) on the
library LIBRARY (CONTACT's contact_addon_linux64.so or railcontact's,
built with crates/cntc/build-lib.sh); prints per case and patch what the
getters report: FN, FX, FS, MZ, the creepages, FLX(1:3) and K_EFF
(`cntc_getparameters`), the numbers of elements in adhesion and slip
(`cntc_getelementdivision`) and the grid's size. Run it once per library
and compare.

The cases: the centred wheelset (tread only) with M = 5 and M = 3 beside
it; its pitch rate changed for longitudinal creepages of -0.1, -0.2 and
-0.4 % (towards saturation; the last beside M = 3); at 3 mm with 7.2 mrad
yaw (spin and lateral creepage, saturated) and at 1 mrad, with Kalker's
slope reduction and with
k0, alpha_inf, beta = 0.54, 0.02, 0.62 (beside M = 3) at 1 mrad; at 6.5 mm with 15.6 mrad (a
flange patch beside the tread's); two patches with the wheelset's height
given (6.46 mm, 21.6 mrad, crates/cntc/tests/two_point_contact.rs);
the centred wheelset rolling backwards (VS < 0); a linear falling
friction law (L = 2). Then through the setters
(`cntc_setmaterialparameters` with M = 5): python_mbench.py's tread case
5 of wheel 1 and flange case 16 of wheel 2, with and without slope
reduction (0.54, 0.02, 0.62), and the tread with FX_WS 1500 and -2000 N
given (F = 1; prints the VPITCH found).

  PYTHON_INTFC  CONTACT's python_intfc folder (a checkout of eve70a/CONTACT)
  LIBRARY       the library to load (copied beside a copy of python_intfc,
                in bin/, where python_intfc looks)

The profiles are the repository's (crates/solver/profiles). Needs numpy.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from placement_cases import PROFILES  # noqa: E402
from viscoelastic_cases import GEOMETRY, load, solve_file  # noqa: E402

# Pure rolling on the nominal radius at VS = 1000 mm/s [rad/s].
ROLL = -1000.0 / 460.0

# The A-2.2 series' (y [mm], roll, yaw [rad], VPITCH at 1 m/s [rad/s],
# FZ [N]) or, with FZ None, the wheelset's height Z_WS [mm] (N = 0).
POSITIONS = {
    'y0': (0.0, 0.0, 0.0, -4.34811810 / 2, 10000.0, None),
    'y0-xi1': (0.0, 0.0, 0.0, ROLL * (1.0 - 0.001), 10000.0, None),
    'y0-xi2': (0.0, 0.0, 0.0, ROLL * (1.0 - 0.002), 10000.0, None),
    'y0-xi4': (0.0, 0.0, 0.0, ROLL * (1.0 - 0.004), 10000.0, None),
    'y3': (3.0, -0.00018030, 0.0072, -4.34515030 / 2, 10000.0, None),
    'y3-yaw1': (3.0, -0.00018030, 0.001, -4.34515030 / 2, 10000.0, None),
    'y6.5': (6.5, -0.00437600, 0.0156, -4.27488340 / 2, 10000.0, None),
    'y6.46': (6.46, 0.0, 0.0216, -2.17, None, -0.698),
}

# (name, position, M digit, K0_MF, ALFAMF, BETAMF, VS [mm/s], friction
# law (L, its parameter line)). The linear law: FKIN 0.2, FLIN1 0.15,
# SABSH1 2 m/s (mu_s(0) = 0.35).
COULOMB = (0, '  0.300   0.300                                 FSTAT, FKIN\n')
LINEAR = (2, '  0.200   0.150   2000.0  0.0  1000.0        FKIN, FLIN1, SABSH1, FLIN2, SABSH2\n'
             '  0.001   10.0                                  MEMDST, MEM_S0\n')
KALKER, REDUCED = (1.0, 1.0, 0.0), (0.54, 0.02, 0.62)


def case(pos, m, suffix='', red=KALKER, vs=1000.0, law=COULOMB):
    """The case at `pos` with M = `m`, named '<pos>-m<m><suffix>'."""
    return ('%s-m%d%s' % (pos, m, suffix), pos, m) + red + (vs, law)


CASES = [case(pos, m) for pos, m in [('y0', 5), ('y0', 3), ('y0-xi1', 5), ('y0-xi2', 5),
                                     ('y0-xi4', 5), ('y0-xi4', 3), ('y3', 5), ('y3-yaw1', 5),
                                     ('y6.5', 5), ('y6.46', 5)]]
CASES += [case('y3-yaw1', m, '-red', red=REDUCED) for m in (5, 3)]
CASES += [case('y0-xi2', 5, '-back', vs=-1000.0), case('y0-xi2', 5, '-linear', law=LINEAR)]


def inp_text(case):
    """The module 1 input file of `case`."""
    _, pos, m, k0, alpha, beta, vs, (law, law_line) = case
    y, roll, yaw, vpitch, fz, z_ws = POSITIONS[pos]
    norm, z = (1, fz) if fz is not None else (0, z_ws)
    # Rolling backwards: the pitch rate turns with the speed.
    vpitch = vpitch * vs / 1000.0
    return (
        '  1 MODULE\n'
        ' 1203%d00    C-P-B-T-N-F-S   CONFIG, PVTIME, BOUND,  TANG,   NORM,   FORCE,  STRESS\n'
        ' 0%d22%d33    V-L-D-C-M-Z-E   VARFRC, FRCLAW, DISCNS, INFLCF, MATER,  ZTRACK, EWHEEL\n'
        ' 0000321    H-G-I-A-O-W-R     HEAT, GAUSEI, IESTIM, MATFIL, OUTPUT, FLOW,   RETURN\n'
        '    999     100    30    1     1d-5         MAXGS , MAXIN , MAXNR , MAXOUT, EPS\n'
        '%s'
        '  0.280   0.280   82000.  82000.                POISS 1,2,  GG 1,2\n'
        '  %g  %g  %g                      K0_MF, ALFAMF, BETAMF\n'
        '%s'
        '  0.0  %.4f  %.4f  %.8f  %.4f  0.0      S, Y, FZ, ROLL, YAW, PITCH\n'
        ' %.1f  0.0   0.0   0.0   0.0  %.9f     VS, VY, VZ, VROLL, VYAW, VPITCH\n'
    ) % (norm, law, m, law_line, k0, alpha, beta, GEOMETRY, y, z, roll, yaw, vs, vpitch)


# Through the setters: python_mbench.py's tread case 5 of wheel 1 and
# flange case 16 of wheel 2 (as crates/cntc/tests/module1.rs sets them up)
# with M = 5, (name, wheel, position, VPITCH, K0_MF, ALFAMF, BETAMF).
SETTER_CASES = [
    ('mbench-tread', 1, [0.0, 2.0, 0.0, -0.0001128, 0.0048, 0.0], -4.3459197, 1.0, 1.0, 1.0),
    ('mbench-flange', 2, [0.0, 7.5, 0.0, -0.007642, 0.018, 0.0], -4.2575747, 1.0, 1.0, 1.0),
    ('mbench-tread-red', 1, [0.0, 2.0, 0.0, -0.0001128, 0.0048, 0.0], -4.3459197,
     0.54, 0.02, 0.62),
    ('mbench-flange-red', 2, [0.0, 7.5, 0.0, -0.007642, 0.018, 0.0], -4.2575747,
     0.54, 0.02, 0.62),
]


# The tread with the total force FX_WS [N] given (F = 1) instead of VPITCH.
FORCE_CASES = [('mbench-tread-fxws%d' % fx,) + SETTER_CASES[0][1:] + (fx,)
               for fx in (1500, -2000)]
SETTER_CASES += FORCE_CASES


def set_up_mbench(cntc, CNTC, ire, case):
    """python_mbench.py's wheel of `case` with M = 5 through the setters
    (with FX_WS: F = 1)."""
    _, iwhe, pos, vpitch, k0, alpha, beta = case[:7]
    import numpy as np
    from ctypes import c_int
    cntc.initialize(ire, 1, ' ', 0)
    flags = [('if_units', CNTC['un_cntc']), ('ic_config', iwhe - 1), ('ic_tang', 3),
             ('ic_pvtime', 2), ('ic_norm', 1), ('ic_force', 0), ('ic_discns', 2)]
    cntc.setflags(ire, -1, np.array([CNTC[k] for k, _ in flags], dtype=c_int),
                  np.array([v for _, v in flags], dtype=c_int))
    cntc.setmaterialparameters(ire, -1, 5, [0.28, 0.28, 82000.0, 82000.0, k0, alpha, beta])
    cntc.setfrictionmethod(ire, -1, 0, [0.3, 0.3])
    cntc.setverticalforce(ire, 10000.0)
    cntc.setpotcontact(ire, -1, -1, [0.2, 0.2, np.pi / 2, 8.0, 4.0])
    cntc.settrackdimensions(ire, 3, [14.0, 0.0, 1435.0] + [0.0] * 8)
    rail, mirror = ('MBench_UIC60_v3.prr', 0) if iwhe == 1 else ('MBench_UIC60_v3.ban', 1)
    cntc.setprofileinputfname(ire, os.path.join(PROFILES, rail), [-1, 0, mirror], [1.0, 0.0])
    cntc.setwheelsetdimensions(ire, 3, [1360.0, -70.0, 460.0])
    cntc.setprofileinputfname(ire, os.path.join(PROFILES, 'MBench_S1002_v3.prw'),
                              [-1, 0, 0], [1.0, 0.0])
    cntc.setwheelsetflexibility(ire, 1, [0.0] * 12)
    cntc.setwheelsetposition(ire, 2, pos)
    cntc.setwheelsetvelocity(ire, 2, [2000.0, 0.0, 0.0, 0.0, 0.0, vpitch])
    if len(case) > 7:
        cntc.setflags(ire, -1, np.array([CNTC['ic_force']], dtype=c_int),
                      np.array([1], dtype=c_int))
        cntc.settangentialforces(ire, -1, float(case[7]), 0.0)


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    only = set(sys.argv[3:])
    cntc = load(sys.argv[1], sys.argv[2], CASES, inp_text, 'm1-fastrip-')
    CNTC, _, ierror = cntc.initlibrary(' ', ' ', ' ', 0)
    assert ierror == 0, ierror
    chosen = [(ire, c) for ire, c in enumerate(CASES + SETTER_CASES, 1)
              if not only or c[0] in only]
    for ire, case in chosen:
        if case in SETTER_CASES:
            set_up_mbench(cntc, CNTC, ire, case)
            ierr = cntc.calculate(ire)
            npatch = cntc.getnumcontactpatches(ire)
            print(f'case {case[0]}: setters, ierror {ierr}, {npatch} patch(es)')
            if case in FORCE_CASES:
                print(f'  VPITCH {float(cntc.getwheelsetvelocity(ire)[5])!r}')
        else:
            npatch = solve_file(cntc, CNTC, ire, case[0])
        for icp in range(1, npatch + 1):
            fn, fx, fs, mz = cntc.getcontactforces(ire, icp)
            cx, cy, cp = cntc.getcreepages(ire, icp)
            par = cntc.getparameters(ire, icp, 2)
            eldiv = cntc.getelementdivision(ire, icp)
            mx, my = cntc.getnumelements(ire, icp)
            nadh = int((eldiv == 1).sum())
            nslip = int((eldiv == 2).sum())
            print(f'  patch {icp}: FN {fn!r} FX {fx!r} FS {fs!r} MZ {mz!r}')
            print(f'    CKSI {cx!r} CETA {cy!r} CPHI {cp!r}')
            print(f'    FLX {float(par["flx1"])!r} {float(par["flx2"])!r} '
                  f'{float(par["flx3"])!r} K_EFF {float(par["k_eff"])!r}')
            print(f'    MX {mx} MY {my} NADH {nadh} NSLIP {nslip}')


if __name__ == '__main__':
    main()
