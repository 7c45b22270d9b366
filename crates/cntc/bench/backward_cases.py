"""backward_cases.py PYTHON_INTFC LIBRARY [CASE ...]

Runs module 1 cases rolling backwards (VS < 0, and VPITCH_ROL < 0 on a
roller rig) beside their forward mirror images, through CONTACT's own
Python interface (`python_intfc`, ctypes) on the library LIBRARY
(CONTACT's contact_addon_linux64.so or railcontact's, built with
crates/cntc/build-lib.sh), and prints per case and patch FN, FX, FS, MZ,
the creepages, the approach and the contact location as
placement_cases.py does (its loader and printer). Run it once per library
and compare.

The cases: the Manchester benchmark's right wheel (S1002 on UIC60,
gauge-point placement, 10 kN, 2 mm off centre) at VS = -20 m/s rolling
freely, braked while reversing (VPITCH 0.3 % below free rolling), yawed
(4 mm, 9.6 mrad), with FX_WS prescribed (F = 1: braking while reversing,
VPITCH found and printed), and the forward mirror images of the first
three (`mb-fwd-*`); test-rollers2.inp's roller case 2a on the left roller
with a load, a lateral rate and a yaw rate, run backwards (VPITCH_ROL < 0,
as its case 2d does), and its forward mirror image.

  PYTHON_INTFC  CONTACT's python_intfc folder (a checkout of eve70a/CONTACT)
  LIBRARY       the library to load (copied beside a copy of python_intfc,
                in bin/, where python_intfc looks)

Run it from a scratch directory: CONTACT's library leaves
`contact_addon.out` in the working directory. Needs numpy.
"""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from placement_cases import calculate, load, print_patches  # noqa: E402

NO_DEV = [0.0] * 6
# Z = 3: GAUGHT, GAUGSQ, GAUGWD, CANT, NOMRAD, CURV, then the deviations.
MBENCH_TRACK = [14.0, 0.0, 1435.0, 0.0, 0.0, 0.0] + NO_DEV
V = -20000.0  # mm/s
FREE = -V / 460.0  # rad/s, > 0 rolling backwards
BUS = [300.0, -50.0, 133.33333]

# placement_cases.py's form: (name, c1, norm, z_or_fz, rail, wheel, track,
# position, velocity, flexibility (None), wheelset dimensions).
CASES = [
    ('mb-back-free', 1, 1, 1.0e4, 'MBench_UIC60_v3.prr', 'MBench_S1002_v3.prw', MBENCH_TRACK,
     [0, 2.0, 0, 0, 0, 0], [V, 0, 0, 0, 0, FREE], None, [1360.0, -70.0, 460.0]),
    ('mb-back-brake', 1, 1, 1.0e4, 'MBench_UIC60_v3.prr', 'MBench_S1002_v3.prw', MBENCH_TRACK,
     [0, 2.0, 0, 0, 0, 0], [V, 0, 0, 0, 0, 0.997 * FREE], None, [1360.0, -70.0, 460.0]),
    ('mb-fwd-free', 1, 1, 1.0e4, 'MBench_UIC60_v3.prr', 'MBench_S1002_v3.prw', MBENCH_TRACK,
     [0, 2.0, 0, 0, 0, 0], [-V, 0, 0, 0, 0, -FREE], None, [1360.0, -70.0, 460.0]),
    ('mb-fwd-brake', 1, 1, 1.0e4, 'MBench_UIC60_v3.prr', 'MBench_S1002_v3.prw', MBENCH_TRACK,
     [0, 2.0, 0, 0, 0, 0], [-V, 0, 0, 0, 0, -0.997 * FREE], None, [1360.0, -70.0, 460.0]),
    ('mb-back-yaw', 1, 1, 1.0e4, 'MBench_UIC60_v3.prr', 'MBench_S1002_v3.prw', MBENCH_TRACK,
     [0, 4.0, 0, 0, 0.0096, 0], [V, 0, 0, 0, 0, FREE], None, [1360.0, -70.0, 460.0]),
    ('mb-fwd-yaw', 1, 1, 1.0e4, 'MBench_UIC60_v3.prr', 'MBench_S1002_v3.prw', MBENCH_TRACK,
     [0, 4.0, 0, 0, -0.0096, 0], [-V, 0, 0, 0, 0, -FREE], None, [1360.0, -70.0, 460.0]),
    ('mb-back-fx', 1, 1, 1.0e4, 'MBench_UIC60_v3.prr', 'MBench_S1002_v3.prw', MBENCH_TRACK,
     [0, 2.0, 0, 0, 0, 0], [V, 0, 0, 0, 0, FREE], None, [1360.0, -70.0, 460.0]),
    ('2a-left-load-back', 4, 1, 3.0e4, 'circ_r100.prr', 'flat_plane.prw',
     [-1.0, -200.0, 0.0, 0.0, 400.0] + NO_DEV, [0, 0.5, 0.0, 0, 0, 0],
     [-0.25, 1.0, 0.0, 0.0, 0.001, 0.751], None, BUS),
    ('2a-left-load-fwd', 4, 1, 3.0e4, 'circ_r100.prr', 'flat_plane.prw',
     [-1.0, -200.0, 0.0, 0.0, 400.0] + NO_DEV, [0, 0.5, 0.0, 0, 0, 0],
     [0.25, 1.0, 0.0, 0.0, -0.001, -0.751], None, BUS),
]


# FX_WS prescribed (F = 1) [N] per case name: the pitch rate is found.
FX_WS = {'mb-back-fx': -1500.0}


def run(cntc, only):
    CNTC, _, ierror = cntc.initlibrary(' ', ' ', ' ', 0)
    assert ierror == 0, ierror
    for ire, case in enumerate(CASES, 1):
        name = case[0]
        if only and name not in only:
            continue
        fx_ws = FX_WS.get(name)
        print_patches(cntc, ire, name, calculate(cntc, CNTC, ire, case, fx_ws))
        params = cntc.getparameters(ire, 1, 1)
        print('    VELOC {:.6g} CHI {:.6f}'.format(params['veloc'], params['chi']))
        if fx_ws is not None:
            print('%s VPITCH %.9g' % (name, cntc.getwheelsetvelocity(ire)[5]))


if __name__ == '__main__':
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    run(load(sys.argv[1], sys.argv[2]), set(sys.argv[3:]))
