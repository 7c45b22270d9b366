"""massless_rail.py PYTHON_INTFC LIBRARY [DISCNS]

CONTACT's test bank cases 36 and 37 (testbank/testbank.inp: the massless
rail, F = 3, N = 0, on the set-up of its case 33: site_b_hr.prr rail,
worn_high_mileage.prw wheel, right wheel in flange contact, friction by
contact angle) through CONTACT's own Python interface (`python_intfc`,
ctypes) on the library LIBRARY (CONTACT's contact_addon_linux64.so or
railcontact's, built with crates/cntc/build-lib.sh); then the same at a few
other lateral positions and with N = 1. DISCNS is the D digit: 4
(conformal, the test bank's: case 36 keeps case 35's D = 4) or 2 (planar,
the default; railcontact's module 1 has only the planar approach); then
the Manchester benchmark (python_mbench.py's set-up, planar) with the
massless rail on a tread and a flange contact, N = 1 and N = 0.
Prints per case the deflections DY_DEFL, DZ_DEFL, the total forces on the
rail FX, FY, FZ (track), the wheelset's Z and the contact location of
patch 1 (track y, z, angle; rail y, z). Run it from a scratch directory:
CONTACT's library leaves `contact_addon.out` in the working directory.
The test bank's profiles are read from CONTACT's checkout that holds
PYTHON_INTFC (its testbank/profiles). Needs numpy.
"""
import os
import sys

import numpy as np
from ctypes import c_int

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from placement_cases import load  # noqa: E402

PROFILES = os.path.normpath(os.path.join(HERE, '..', '..', 'solver', 'profiles'))
# The test bank's profiles of cases 33-37 (site_b_hr.prr,
# worn_high_mileage.prw): CONTACT's checkout, beside python_intfc.
TESTBANK = None
DEG = np.pi / 180.0


def setup(cntc, CNTC, ire, discns, norm):
    """testbank.inp case 33's set-up with case 36's digits (F = 3)."""
    cntc.initialize(ire, 1, ' ', 0)
    codes = [CNTC['if_units'], CNTC['ic_config'], CNTC['ic_tang'], CNTC['ic_pvtime'],
             CNTC['ic_norm'], CNTC['ic_force'], CNTC['ic_discns'], CNTC['if_wrtinp'],
             CNTC['ic_matfil'], CNTC['ic_output'], CNTC['ic_flow']]
    values = [CNTC['un_cntc'], 1, 3, 2, norm, 3, discns, 0, 0, 0, 0]
    cntc.setflags(ire, [], np.array(codes, dtype=c_int), np.array(values, dtype=c_int))
    # MAXGS, MAXIN, MAXNR, MAXOUT, EPS of case 33 (G = 0).
    cntc.setsolverflags(ire, [], 0, np.array([999, 100, 30, 1], dtype=c_int),
                        np.array([1e-6]))
    cntc.setmaterialparameters(ire, [], 0, [0.28, 0.28, 82000.0, 82000.0])
    # V = 1: NVF = 2, ALPHA -30 deg mu 0.2, -20 deg mu 0.35.
    cntc.setfrictionmethod(ire, [], 10, np.array(
        [2, -30 * DEG, 0.2, 0.2, -20 * DEG, 0.35, 0.35]))
    # DX, DS, A_SEP, D_SEP, D_COMB, D_TURN of case 35 (kept by case 36).
    cntc.setpotcontact(ire, [], -1, np.array([0.4, 0.4, 90 * DEG, 30.0, 20.0, 40.0]))
    cntc.setrollingstepsize(ire, [], [], 1.0)
    track = [15.875, 0.0, 1435.10, 0.0, 0.0] + [0.0] * 6
    cntc.settrackdimensions(ire, 3, np.array(track))
    rp = [1.0, 0.0]
    cntc.setprofileinputfname(ire, os.path.join(TESTBANK, 'site_b_hr.prr'), [-1, 0, 0], rp)
    cntc.setwheelsetdimensions(ire, 3, np.array([1347.40, 0.0, 444.0]))
    cntc.setprofileinputfname(ire, os.path.join(TESTBANK, 'worn_high_mileage.prw'),
                              [-1, 0, 0], rp)


def solve(cntc, ire, rail, pos, vpitch, fz=None):
    cntc.settrackdimensions(ire, 32, np.array(rail))
    if fz is not None:
        cntc.setverticalforce(ire, fz)
    cntc.setwheelsetposition(ire, 2, np.array(pos))
    cntc.setwheelsetvelocity(ire, 2, np.array([15000.0, 0, 0, 0, 0, vpitch]))
    return cntc.calculate(ire, -1, 0)


def show(cntc, ire, name, ierr):
    npatch = cntc.getnumcontactpatches(ire)
    print(f'case {name}: ierror {ierr}, {npatch} patch(es)')
    if npatch < 1:
        return
    loc = cntc.getcontactlocation(ire, 1)
    f = cntc.getglobalforces(ire, -1)
    ws = cntc.getwheelsetposition(ire)
    print('  DY_DEFL {:.6f} DZ_DEFL {:.6f} Z_WS {:.6f}'.format(loc[17], loc[18], ws[2]))
    print('  FX_TR {:.6g} FY_TR {:.6g} FZ_TR {:.6g}'.format(f[0], f[1], f[2]))
    print('  YCP_TR {:.5f} ZCP_TR {:.5f} DELT_TR {:.6f} YCP_R {:.5f} ZCP_R {:.5f}'.format(
        loc[1], loc[2], loc[3], loc[5], loc[6]))


def mbench(cntc, CNTC, ire, iwhe, norm):
    """python_mbench.py's set-up of wheel `iwhe` (1 left on the Simpack
    rail, 2 right on the MiniProf rail), FZ = 10 kN, with F = 3."""
    cntc.initialize(ire, 1, ' ', 0)
    codes = [CNTC['if_units'], CNTC['ic_config'], CNTC['ic_tang'], CNTC['ic_pvtime'],
             CNTC['ic_norm'], CNTC['ic_force'], CNTC['ic_discns'], CNTC['if_wrtinp'],
             CNTC['ic_matfil'], CNTC['ic_output'], CNTC['ic_flow']]
    values = [CNTC['un_cntc'], iwhe - 1, 3, 2, norm, 3, 2, 0, 0, 0, 0]
    cntc.setflags(ire, [], np.array(codes, dtype=c_int), np.array(values, dtype=c_int))
    cntc.setmaterialparameters(ire, [], 0, [0.28, 0.28, 82000.0, 82000.0])
    cntc.setfrictionmethod(ire, [], 0, np.array([0.3, 0.3]))
    if norm == 1:
        # (cntc_setverticalforce sets N = 1.)
        cntc.setverticalforce(ire, 10000.0)
    cntc.setpotcontact(ire, [], -1, np.array([0.2, 0.2, np.pi / 2, 8.0, 4.0]))
    cntc.settrackdimensions(ire, 3, np.array([14.0, 0.0, 1435.0, 0.0, 0.0] + [0.0] * 6))
    rail, mirror = ('MBench_UIC60_v3.prr', 0) if iwhe == 1 else ('MBench_UIC60_v3.ban', 1)
    rp = [1.0, 0.0]
    cntc.setprofileinputfname(ire, os.path.join(PROFILES, rail), [-1, 0, mirror], rp)
    cntc.setwheelsetdimensions(ire, 3, np.array([1360.0, -70.0, 460.0]))
    cntc.setprofileinputfname(ire, os.path.join(PROFILES, 'MBench_S1002_v3.prw'),
                              [-1, 0, 0], rp)


def mbench_solve(cntc, ire, rail, pos, vpitch):
    cntc.settrackdimensions(ire, 32, np.array(rail))
    cntc.setwheelsetposition(ire, 2, np.array(pos))
    cntc.setwheelsetvelocity(ire, 2, np.array([2000.0, 0, 0, 0, 0, vpitch]))
    return cntc.calculate(ire, -1, 0)


# The Manchester benchmark's cases with the massless rail: (name, wheel,
# N, Z_WS (N = 0), KYRAIL, FYRAIL, KZRAIL, FZRAIL, position, VPITCH). The
# positions are python_mbench.py's (tests/module1.rs); `*-n0` prescribe
# the Z_WS that CONTACT's library found for the case before with N = 1.
MBENCH = [
    ('mb-left-tread', 1, 1, None, 5000.0, 0.0, 20000.0, 0.0,
     [0.0, 2.0, 0.0, -0.0001128, 0.0048, 0.0], -4.3459197),
    ('mb-left-tread-n0', 1, 0, 'mb-left-tread', 5000.0, 0.0, 20000.0, 0.0,
     [0.0, 2.0, 0.0, -0.0001128, 0.0048, 0.0], -4.3459197),
    ('mb-right-flange', 2, 1, None, 20000.0, -2000.0, 20000.0, -5000.0,
     [0.0, 7.5, 0.0, -0.007642, 0.018, 0.0], -4.2575747),
    ('mb-right-flange-n0', 2, 0, 'mb-right-flange', 20000.0, -2000.0, 20000.0, -5000.0,
     [0.0, 7.5, 0.0, -0.007642, 0.018, 0.0], -4.2575747),
]


def run_mbench(cntc, CNTC, first_ire):
    z_ws = {}
    for k, (name, iwhe, norm, zfrom, ky, fy, kz, fz, pos, vp) in enumerate(MBENCH):
        ire = first_ire + k
        mbench(cntc, CNTC, ire, iwhe, norm)
        p = list(pos)
        if zfrom is not None:
            p[2] = z_ws[zfrom]
        ierr = mbench_solve(cntc, ire, [ky, fy, kz, fz, 0.5], p, vp)
        show(cntc, ire, name, ierr)
        z_ws[name] = cntc.getwheelsetposition(ire)[2]
        print('  Z_WS {:.9f}'.format(z_ws[name]))


def run(cntc, discns):
    CNTC, _, ierror = cntc.initlibrary(' ', ' ', ' ', 0)
    assert ierror == 0, ierror
    # Cases 36 and 37 on one element (37 with I = 1 starts from 36).
    setup(cntc, CNTC, 1, discns, 0)
    show(cntc, 1, 'tb36', solve(cntc, 1, [10000.0, -68230.0, 10000.0, -30000.0, 0.75],
                                [0.0, 15.55, 2.0884, -0.0013, 0.0050, 0.0], -32.1))
    cntc.setflags(1, [], np.array([CNTC['ic_iestim']], dtype=c_int),
                  np.array([1], dtype=c_int))
    show(cntc, 1, 'tb37', solve(cntc, 1, [10000.0, -68130.0, 10000.0, -30000.0],
                                [0.0, 15.551, 2.0884, -0.0013, 0.0050, 0.0], -32.1))
    # Other lateral positions, each on a fresh element (I = 0).
    for ire, y in ((2, 15.0), (3, 16.0)):
        setup(cntc, CNTC, ire, discns, 0)
        show(cntc, ire, f'y{y}', solve(cntc, ire, [10000.0, -68230.0, 10000.0, -30000.0, 0.75],
                                       [0.0, y, 2.0884, -0.0013, 0.0050, 0.0], -32.1))
    # N = 1: FZ = 40 kN, dz = (FZ + FZRAIL) / KZRAIL.
    setup(cntc, CNTC, 4, discns, 1)
    show(cntc, 4, 'n1', solve(cntc, 4, [10000.0, -68230.0, 10000.0, -30000.0, 0.75],
                              [0.0, 15.55, 0.0, -0.0013, 0.0050, 0.0], -32.1, fz=40000.0))
    run_mbench(cntc, CNTC, 5)


if __name__ == '__main__':
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    TESTBANK = os.path.join(os.path.dirname(os.path.abspath(sys.argv[1])), 'testbank',
                            'profiles')
    run(load(sys.argv[1], sys.argv[2]), int(sys.argv[3]) if len(sys.argv) > 3 else 2)
