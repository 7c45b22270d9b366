"""placement_cases.py PYTHON_INTFC LIBRARY [CASE ...]

Runs module 1 cases with absolute rail placement, rail deviations and
wheelset flexibility (CONTACT's test-rollers2.inp cases 1a-1e and variations
of them), roller rigs (C1 = 4, 5: test-rollers2.inp cases 2a, 2e, 3a-3c)
and track curvature (CURV), and some of them with the total force FX_WS
prescribed (F = 1: the cases named `-fx`, VPITCH found and printed)
through CONTACT's own Python interface (`python_intfc`, ctypes) on
the library LIBRARY (CONTACT's contact_addon_linux64.so or railcontact's,
built with crates/cntc/build-lib.sh), and prints per case and patch FN, FX,
FS, MZ, the creepages, the approach and the contact location (track y, z,
contact angle; rail y, z; wheel y, z). Run it once per library and compare.

  PYTHON_INTFC  CONTACT's python_intfc folder (a checkout of eve70a/CONTACT)
  LIBRARY       the library to load (copied beside a copy of python_intfc,
                in bin/, where python_intfc looks)

The profiles are the repository's (crates/solver/profiles: circ_r100.prw,
circ_r100.prr, flat_plane.prr, flat_plane.prw, flat_ang200.prr, from
CONTACT's test bank). Needs numpy.
"""
import os
import shutil
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
PROFILES = os.path.normpath(os.path.join(HERE, '..', '..', 'solver', 'profiles'))


def load(intfc, library):
    work = tempfile.mkdtemp(prefix='placement-')
    shutil.copytree(intfc, os.path.join(work, 'python_intfc'))
    os.makedirs(os.path.join(work, 'bin'))
    shutil.copy(library, os.path.join(work, 'bin', 'contact_addon_linux64.so'))
    os.environ.setdefault('LD_LIBRARY_PATH', '/nonexistent')
    sys.path.insert(0, work)
    import python_intfc as cntc
    return cntc


# Each case: (name, c1, norm, z_or_fz, track params (Z=3, 11 values, or 12
# with CURV after NOMRAD), wheelset position (6), velocity (6; on a roller
# rig VPITCH_ROL first), flexibility (12) or None {, wheelset dimensions}).
def cases():
    return cases_flat() + roller_cases() + curvature_cases() + force_cases()


def cases_flat():
    r = 'flat_plane.prr'
    w = 'circ_r100.prw'
    no_dev = [0.0] * 6
    flat = [-1.0, 200.0, 0.0, 0.0, 0.0] + no_dev
    vel = [100.0, 0.0, 0.0, 0.0, 0.0, -1.0]
    return [
        # test-rollers2.inp case 1a
        ('1a', 1, 0, 0.16, r, w, flat, [0, 0, 0.16, 0, 0, 0], vel, None),
        # 1a on the left rail at RAILY0 = -200
        ('1a-left', 0, 0, 0.16, r, w, [-1.0, -200.0, 0.0, 0.0, 0.0] + no_dev,
         [0, 0, 0.16, 0, 0, 0], vel, None),
        # a load, a lateral shift, a cant, RAILZ0 and some creepage
        ('abs-load', 1, 1, 5.0e4, r, w, [-1.0, 200.0, 0.5, 0.05, 0.0] + no_dev,
         [0, 3.0, 0.0, 0, 0, 0], [100.0, 0.0, 0.0, 0.0, 0.0, -1.002], None),
        ('abs-load-left', 0, 1, 5.0e4, r, w, [-1.0, -200.0, 0.5, 0.05, 0.0] + no_dev,
         [0, 3.0, 0.0, 0.001, 0.002, 0], [100.0, 0.0, 0.0, 0.0, 0.0, -1.002], None),
        # test-rollers2.inp case 1b: DYAWW = -0.3 rad
        ('1b', 1, 0, 0.16, r, w, flat, [0, 0, 0.16, 0, 0, 0], vel,
         [0, 0, 0, 0, -0.3, 0] + [0] * 6),
        # test-rollers2.inp case 1e: DROLLW = 0.1 rad, DZWHL = -0.4996
        ('1e', 1, 0, 0.16, r, w, flat, [0, 0, 0.16, 0, 0, 0], vel,
         [0, 0, -0.4996, 0.1, 0, 0] + [0] * 6),
        # flexibility with deviations and velocities on both sides
        ('flex', 1, 1, 5.0e4, r, w, flat, [0, 1.0, 0.0, 0.002, 0.003, 0],
         [100.0, 0.02, 0.01, 0.0002, 0.0003, -1.0],
         [0.5, 0.3, -0.2, 0.02, 0.03, 0.1, 0.04, 0.03, 0.02, 0.0001, 0.0002, 0.0003]),
        ('flex-left', 0, 1, 5.0e4, r, w, [-1.0, -200.0, 0.0, 0.0, 0.0] + no_dev,
         [0, 1.0, 0.0, 0.002, 0.003, 0], [100.0, 0.02, 0.01, 0.0002, 0.0003, -1.0],
         [0.5, 0.3, -0.2, 0.02, 0.03, 0.1, 0.04, 0.03, 0.02, 0.0001, 0.0002, 0.0003]),
        # rail deviations DY, DZ, DROLL and their velocities
        ('dev', 1, 1, 5.0e4, r, w, [-1.0, 200.0, 0.0, 0.0, 0.0, 2.0, 0.3, 0.02, 1.0, 0.5, 0.01],
         [0, 1.0, 0.0, 0.0, 0.0, 0], [100.0, 0.0, 0.0, 0.0, 0.0, -1.0], None),
        ('dev-left', 0, 1, 5.0e4, r, w,
         [-1.0, -200.0, 0.0, 0.0, 0.0, 2.0, 0.3, 0.02, 1.0, 0.5, 0.01],
         [0, 1.0, 0.0, 0.0, 0.0, 0], [100.0, 0.0, 0.0, 0.0, 0.0, -1.0], None),
        # deviations of a gauge-placed rail (the Manchester benchmark)
        ('dev-mbench', 1, 1, 1.0e4, 'MBench_UIC60_v3.prr', 'MBench_S1002_v3.prw',
         [14.0, 0.0, 1435.0, 0.0, 0.0, 0.0, 1.0, 0.2, 0.003, 1.0, 0.5, 0.01],
         [0, 2.0, 0.0, 0.0, 0.0, 0], [2000.0, 0.0, 0.0, 0.0, 0.0, -4.34], None),
    ]


def roller_cases():
    """test-rollers2.inp's roller rig cases (C1 = 5, NOMRAD_R = 400 mm)."""
    bus = [300.0, -50.0, 133.33333]
    ellipsoid = [200.0, -100.0, 133.33333]

    def rig(dev=(0.0,) * 6, curv=None):
        head = [-1.0, 200.0, 0.0, 0.0, 400.0]
        return head + ([] if curv is None else [curv]) + list(dev)
    vel = [0.25, 0.0, 0.0, 0.0, 0.0, -0.75]
    return [
        # 2a: the bus (a cylinder R 133 mm) on an ellipsoidal roller
        ('2a', 5, 0, 0.16, 'circ_r100.prr', 'flat_plane.prw', rig(),
         [0, 0, 0.16, 0, 0, 0], vel, None, bus),
        # 2e: the roller tilted by the rail deviation DROLL = 0.1 rad
        ('2e', 5, 0, 0.16, 'circ_r100.prr', 'flat_plane.prw',
         rig((0.0, 0.4996, 0.1, 0.0, 0.0, 0.0)), [0, 0, 0.16, 0, 0, 0], vel, None, bus),
        # 3a: an ellipsoid (R 133 mm, lateral 100 mm) on a conical roller
        ('3a', 5, 0, -1.870, 'flat_ang200.prr', 'circ_r100.prw', rig(),
         [0, 0, -1.870, 0, 0, 0], [0.24381, 0.0, 0.0, 0.0, 0.0, -0.75], None, ellipsoid),
        # 3b: on a cylindrical roller tilted by DROLL = 0.2 rad
        ('3b', 5, 0, -1.870, 'flat_plane.prr', 'circ_r100.prw',
         rig((0.0, 0.0, 0.2, 0.0, 0.0, 0.0)), [0, 0, -1.870, 0, 0, 0],
         [0.24381, 0.0, 0.0, 0.0, 0.0, -0.75], None, ellipsoid),
        # 3c: on the conical roller with a wheelset roll of 0.266667 rad
        ('3c', 5, 0, -56.60956, 'flat_ang200.prr', 'circ_r100.prw', rig(),
         [0, 0, -56.60956, 0.266667, 0, 0], [0.2451499, 0.0, 0.0, 0.0, 0.0, -0.75], None,
         ellipsoid),
        # 3a on a track: the cone's contact on a prismatic rail
        ('3a-track', 1, 0, -1.870, 'flat_ang200.prr', 'circ_r100.prw',
         [-1.0, 200.0, 0.0, 0.0, 0.0] + [0.0] * 6, [0, 0, -1.870, 0, 0, 0],
         [100.0, 0.0, 0.0, 0.0, 0.0, -0.7623], None, ellipsoid),
        # 2a on the left roller, with a load, a lateral rate and creepage
        ('2a-left-load', 4, 1, 3.0e4, 'circ_r100.prr', 'flat_plane.prw',
         [-1.0, -200.0, 0.0, 0.0, 400.0] + [0.0] * 6, [0, 0.5, 0.0, 0, 0, 0],
         [0.25, 1.0, 0.0, 0.0, 0.001, -0.751], None, bus),
        # 3a yawed by 0.02 rad (the contact ahead of the axle on the cone)
        ('3a-yaw', 5, 1, 5.0e4, 'flat_ang200.prr', 'circ_r100.prw', rig(),
         [0, 0, 0.0, 0, 0.02, 0], [0.24381, 0.0, 0.0, 0.0, 0.0, -0.75], None, ellipsoid),
        # 2a with a track curvature of 1/(20 m)
        ('2a-curv', 5, 1, 3.0e4, 'circ_r100.prr', 'flat_plane.prw', rig(curv=5.0e-5),
         [0, 0, 0.0, 0, 0, 0], vel, None, bus),
    ]


def curvature_cases():
    """Track curvature CURV on a track (C1 = 0, 1)."""
    no_dev = [0.0] * 6
    vel = [100.0, 0.0, 0.0, 0.0, 0.0, -1.0]
    return [
        # 1a with a load and CURV = 1/(100 m), right and left
        ('curv', 1, 1, 5.0e4, 'flat_plane.prr', 'circ_r100.prw',
         [-1.0, 200.0, 0.0, 0.0, 0.0, 1.0e-5] + no_dev, [0, 0, 0.0, 0, 0, 0], vel, None),
        ('curv-left', 0, 1, 5.0e4, 'flat_plane.prr', 'circ_r100.prw',
         [-1.0, -200.0, 0.0, 0.0, 0.0, 1.0e-5] + no_dev, [0, 0, 0.0, 0, 0, 0], vel, None),
        # the Manchester benchmark in a left-hand curve of 300 m
        ('curv-mbench', 1, 1, 1.0e4, 'MBench_UIC60_v3.prr', 'MBench_S1002_v3.prw',
         [14.0, 0.0, 1435.0, 0.0, 0.0, -1.0 / 300e3] + no_dev, [0, 2.0, 0.0, 0.0, 0.001, 0],
         [2000.0, 0.0, 0.0, 0.0, 0.0, -4.34], None),
    ]


# FX_WS prescribed (F = 1) [N] per case name: the pitch rate is found.
FX_WS = {'2a-left-load-fx': -2000.0, '3a-yaw-fx': 4000.0, 'flex-fx': 3000.0,
         'dev-fx': -3000.0}


def force_cases():
    """Cases of the lists above with FX_WS prescribed (F = 1): on a roller
    rig, with wheelset flexibility and with rail deviation rates."""
    base = {c[0]: c for c in roller_cases() + cases_without_force()}
    return [(name,) + base[name[:-3]][1:] for name in FX_WS]


def cases_without_force():
    return [c for c in cases_flat() if c[0] in ('flex', 'dev')]


def wheelrail_element(cntc, CNTC, ire, c1, norm):
    """Initializes module 1 element `ire` (wheel side c1, N digit norm):
    CONTACT's units, steady rolling, the materials and friction of the
    cases."""
    import numpy as np
    from ctypes import c_int
    cntc.initialize(ire, 1, ' ', 0)
    codes = [CNTC['if_units'], CNTC['ic_config'], CNTC['ic_tang'], CNTC['ic_pvtime'],
             CNTC['ic_norm'], CNTC['ic_discns'], CNTC['if_wrtinp'], CNTC['ic_matfil'],
             CNTC['ic_output'], CNTC['ic_flow']]
    values = [CNTC['un_cntc'], c1, 3, 2, norm, 2, 0, 0, 0, 0]
    cntc.setflags(ire, [], np.array(codes, dtype=c_int), np.array(values, dtype=c_int))
    cntc.setmaterialparameters(ire, [], 0, [0.28, 0.28, 82000.0, 82000.0])
    cntc.setfrictionmethod(ire, [], 0, np.array([0.3, 0.3]))


def run(cntc, only):
    CNTC, _, ierror = cntc.initlibrary(' ', ' ', ' ', 0)
    assert ierror == 0, ierror
    for ire, case in enumerate(cases(), 1):
        name = case[0]
        if only and name not in only:
            continue
        print_patches(cntc, ire, name, calculate(cntc, CNTC, ire, case, FX_WS.get(name)))
        if name in FX_WS:
            print('%s VPITCH %.9g' % (name, cntc.getwheelsetvelocity(ire)[5]))


def calculate(cntc, CNTC, ire, case, fx_ws):
    """Sets up element `ire` with `case` (a tuple of cases()' form) and, with
    `fx_ws` not None, F = 1 and that FX_WS; calculates it: ierror."""
    import numpy as np
    from ctypes import c_int
    name, c1, norm, zf, rail, wheel, track, pos, vel, flex = case[:10]
    wheelrail_element(cntc, CNTC, ire, c1, norm)
    if norm == 1:
        cntc.setverticalforce(ire, zf)
    cntc.setpotcontact(ire, [], -1, np.array([0.2, 0.2, np.pi / 2, 8.0, 4.0]))
    cntc.setrollingstepsize(ire, [], [], 1.0)
    cntc.settrackdimensions(ire, 3, np.array(track, dtype=float))
    rp = [1.0, 0.0]
    cntc.setprofileinputfname(ire, os.path.join(PROFILES, rail), [-1, 0, 0], rp)
    if len(case) > 10:
        dims = case[10]
    elif rail.startswith('MBench'):
        dims = [1360.0, -70.0, 460.0]
    else:
        dims = [200.0, -100.0, 100.0]
    cntc.setwheelsetdimensions(ire, 3, np.array(dims))
    cntc.setprofileinputfname(ire, os.path.join(PROFILES, wheel), [-1, 0, 0], rp)
    e = 5 if flex else 3
    p = list(pos)
    if norm == 0:
        p[2] = zf
    cntc.setwheelsetposition(ire, e, np.array(p, dtype=float))
    cntc.setwheelsetvelocity(ire, e, np.array(vel, dtype=float))
    if flex:
        cntc.setwheelsetflexibility(ire, e, np.array(flex, dtype=float))
    if fx_ws is not None:
        cntc.setflags(ire, [], np.array([CNTC['ic_force']], dtype=c_int),
                      np.array([1], dtype=c_int))
        cntc.settangentialforces(ire, -1, fx_ws, 0.0)
    return cntc.calculate(ire, -1, 0)


def print_patches(cntc, ire, name, ierr):
    """Prints the case's ierror and per patch what the library reports."""
    npatch = cntc.getnumcontactpatches(ire)
    print(f'case {name}: ierror {ierr}, {npatch} patch(es)')
    for icp in range(1, npatch + 1):
        fn, fx, fs, mz = cntc.getcontactforces(ire, icp)
        cx, cy, cp = cntc.getcreepages(ire, icp)
        pen = cntc.getpenetration(ire, icp)
        loc = cntc.getcontactlocation(ire, icp)
        print(f'  patch {icp}: FN {fn:.6g} FX {fx:.6g} FS {fs:.6g} MZ {mz:.6g}')
        grid = cntc.getpotcontact(ire, icp)
        print('    grid mx {:.0f} my {:.0f} xc1 {:.5f} yc1 {:.5f}'.format(*grid[:4]))
        print(f'    CKSI {cx:.6g} CETA {cy:.6g} CPHI {cp:.6g} PEN {pen:.6g}')
        print('    XCP_TR {:.5f} YCP_TR {:.5f} ZCP_TR {:.5f} DELT_TR {:.6f} YCP_R {:.5f} '
              'ZCP_R {:.5f} YCP_W {:.5f} ZCP_W {:.5f}'.format(
                  loc[0], loc[1], loc[2], loc[3], loc[5], loc[6], loc[10], loc[11]))
        print('    W_TR {:.5f} {:.5f} {:.5f} {:.6f} {:.6f} R_TR {:.5f} {:.5f} {:.6f}'.format(
            *loc[20:28]))


if __name__ == '__main__':
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    run(load(sys.argv[1], sys.argv[2]), set(sys.argv[3:]))
