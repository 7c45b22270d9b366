"""m1_transient.py PYTHON_INTFC LIBRARY [CASE [STEPS]]

Runs module 1 transient contact (T = 1 shifts, T = 2 transient rolling)
through CONTACT's own Python interface (`python_intfc`, ctypes) on the
library LIBRARY (CONTACT's contact_addon_linux64.so or railcontact's, built
with crates/cntc/build-lib.sh) and prints per time step FN, FX, FS, MZ, the
creepages (shifts with T = 1), the contact, adhesion and slip element
counts and the largest pressure. Run it once per library and compare.

The cases are CONTACT's testbank/examples_trans (eve70a/CONTACT) input
files translated into calls: the bus-like cylinder circ_r100.prr as the
rail, flat_plane.prw as the wheel (nominal radius 100 mm, DROLLW = 5 deg),
G = 200 N/mm2, nu = 0.28, mu = 0.4, DX = DS = 0.2 mm, with the rail and
wheel 200 mm right of the wheelset centre (`Y0`; the files put them at the
centre, which railcontact refuses; on CONTACT's library the forces of the
two placements agree to the digits printed in the reference outputs):

  catt_shift   m1_catt_shift.inp: T = 1, Z_WS = -0.2201 mm, a first shift
               (P = 2) of S 4 mm and PITCH -0.03984 rad, then steps of
               0.2 mm and -0.001992 rad (P = 0)
  totforce     m1_totforce.inp: the same steps of 0.2 mm under FZ = 237 N
               (N = 1) from the first
  trans_roll   m1_trans_roll.inp: T = 2, Z_WS = -0.2201 mm, VS = 100 mm/s,
               VPITCH = -0.996 rad/s, DQREL = 1, a new sequence (P = 2)
               then steps (P = 0)
  trans_dqrel  m1_trans_dqrel.inp's first sequence: T = 2, DQREL = 4,
               Z_WS = 0.160 mm, no DROLLW, yaw 0, VPITCH -0.960 in the
               first step and -0.996 after (CONTACT's leading-edge
               correction, docs/cntc.md)
  trans_dq2    trans_dqrel with DQREL = 2
  trans_dq1    trans_dqrel with DQREL = 1
  steady_roll  trans_roll's wheel in steady rolling (T = 3): the limit

  PYTHON_INTFC  CONTACT's python_intfc folder (a checkout of eve70a/CONTACT)
  LIBRARY       the library to load
  CASE          one of the cases (default all); STEPS: steps to run
                (default 20)

Run it from a scratch directory: CONTACT's library leaves
`contact_addon.out` in the working directory. Needs numpy.
"""
import os
import sys

import numpy as np
from ctypes import c_int

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from placement_cases import PROFILES, load  # noqa: E402

DX = 0.2  # mm, element size (DX = DS)
# RAILY0 [mm]: the rail and the wheel (FBDIST 200, FBPOS -100) 200 mm right
# of the wheelset centre; the files have both at the centre (FBDIST 0,
# RAILY0 0), which railcontact refuses (a wheel profile across the centre).
Y0 = 200.0


# (T, N, Z_WS or FZ, DQREL, DROLLW [rad], YAW [rad], steps): each step
# (P digit, S [mm], PITCH [rad], VS, VPITCH (T = 1: the step's shifts)).
def steps_catt_shift(n):
    first = (2, 0.0, 0.0, 4.0, -0.03984)
    rest = [(0, 0.2 * k, -0.002 if k == 1 else -0.004, 0.2, -0.001992) for k in range(1, n)]
    return [first] + rest


def steps_totforce(n):
    first = (2, 0.0, 0.0, 0.2, -0.001992)
    rest = [(0, 0.2 * k, -0.002 if k == 1 else -0.004, 0.2, -0.001992) for k in range(1, n)]
    return [first] + rest


def steps_trans_roll(n):
    return [(2 if k == 0 else 0, 0.0, 0.0, 100.0, -0.996) for k in range(n)]


def steps_trans_dqrel(n):
    return [(2 if k == 0 else 0, 0.0, 0.0, 100.0, -0.960 if k == 0 else -0.996)
            for k in range(n)]


CASES = {
    'catt_shift': (1, 0, -0.2201, 1.0, np.radians(5.0), 0.004, steps_catt_shift),
    'totforce': (1, 1, 237.0, 1.0, np.radians(5.0), 0.004, steps_totforce),
    'trans_roll': (2, 0, -0.2201, 1.0, np.radians(5.0), 0.004, steps_trans_roll),
    'trans_dqrel': (2, 0, 0.160, 4.0, 0.0, 0.0, steps_trans_dqrel),
    'trans_dq2': (2, 0, 0.160, 2.0, 0.0, 0.0, steps_trans_dqrel),
    'trans_dq1': (2, 0, 0.160, 1.0, 0.0, 0.0, steps_trans_dqrel),
    'steady_roll': (3, 0, -0.2201, 1.0, np.radians(5.0), 0.004, steps_trans_roll),
}


def setup(cntc, CNTC, ire, tang, norm, zf, dqrel, drollw):
    """Module 1 element `ire` as the cases' first input block."""
    cntc.initialize(ire, 1, ' ', 0)
    codes = [CNTC['if_units'], CNTC['ic_config'], CNTC['ic_tang'], CNTC['ic_pvtime'],
             CNTC['ic_norm'], CNTC['ic_discns'], CNTC['if_wrtinp'], CNTC['ic_matfil'],
             CNTC['ic_output'], CNTC['ic_flow']]
    values = [CNTC['un_cntc'], 1, tang, 2, norm, 2, 0, 0, 0, 0]
    cntc.setflags(ire, [], np.array(codes, dtype=c_int), np.array(values, dtype=c_int))
    cntc.setsolverflags(ire, -1, 0, np.array([999, 100, 30, 1], dtype=c_int), np.array([1e-5]))
    cntc.setmaterialparameters(ire, [], 0, [0.28, 0.28, 200.0, 200.0])
    cntc.setfrictionmethod(ire, [], 0, np.array([0.4, 0.4]))
    if norm == 1:
        cntc.setverticalforce(ire, zf)
    cntc.setpotcontact(ire, [], -1, np.array([DX, DX, np.pi / 2, 8.0, 4.0]))
    cntc.setrollingstepsize(ire, [], [], dqrel)
    track = [-1.0, Y0, 0.0, 0.0, 0.0] + [0.0] * 6
    cntc.settrackdimensions(ire, 3, np.array(track))
    rp = [1.0, 0.0]
    cntc.setprofileinputfname(ire, os.path.join(PROFILES, 'circ_r100.prr'), [-1, 0, 0], rp)
    cntc.setwheelsetdimensions(ire, 3, np.array([200.0, -100.0, 100.0]))
    cntc.setprofileinputfname(ire, os.path.join(PROFILES, 'flat_plane.prw'), [-1, 0, 0], rp)
    flex = [0.0, 0.0, 0.0, drollw, 0.0, 0.0] + [0.0] * 6
    cntc.setwheelsetflexibility(ire, 5, np.array(flex))


def run_case(cntc, CNTC, ire, name, nsteps):
    tang, norm, zf, dqrel, drollw, yaw, steps = CASES[name]
    setup(cntc, CNTC, ire, tang, norm, zf, dqrel, drollw)
    print(f'case {name}')
    print('step P ierr npatch FN FX FS MZ CKSI CETA CPHI NCON NADH NSLIP PMAX VELOC')
    for k, (p, s, pitch, vs, vpitch) in enumerate(steps(nsteps), 1):
        cntc.setflags(ire, [], np.array([CNTC['ic_pvtime']], dtype=c_int),
                      np.array([p], dtype=c_int))
        z = 0.0 if norm == 1 else zf
        cntc.setwheelsetposition(ire, 5, np.array([s, 0.0, z, 0.0, yaw, pitch]))
        cntc.setwheelsetvelocity(ire, 5, np.array([vs, 0.0, 0.0, 0.0, 0.0, vpitch]))
        ierr = cntc.calculate(ire, -1, 0)
        npatch = cntc.getnumcontactpatches(ire)
        if npatch < 1:
            print(f'{k} {p} {ierr} {npatch}')
            continue
        fn, fx, fs, mz = cntc.getcontactforces(ire, 1)
        cx, cy, cp = cntc.getcreepages(ire, 1)
        carea, harea, sarea, _ = cntc.getcontactpatchareas(ire, 1)
        pmax = cntc.getmaximumpressure(ire, 1)
        veloc = cntc.getparameters(ire, 1, 1)['veloc']
        a = DX * DX
        print(f'{k} {p} {ierr} {npatch} {fn:.6g} {fx:.6g} {fs:.6g} {mz:.6g} {cx:.5g} {cy:.5g} '
              f'{cp:.5g} {carea / a:.0f} {harea / a:.0f} {sarea / a:.0f} {pmax:.5g} {veloc:.6g}')


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    cntc = load(sys.argv[1], sys.argv[2])
    CNTC, _, ierror = cntc.initlibrary(' ', ' ', ' ', 0)
    assert ierror == 0, ierror
    names = [sys.argv[3]] if len(sys.argv) > 3 else list(CASES)
    nsteps = int(sys.argv[4]) if len(sys.argv) > 4 else 20
    for ire, name in enumerate(names, 1):
        run_case(cntc, CNTC, ire, name, nsteps)


if __name__ == '__main__':
    main()
