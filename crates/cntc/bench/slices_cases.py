"""slices_cases.py PYTHON_INTFC LIBRARY [CASE ...]

Runs module 1 cases on a variable rail (a rail slices file, .slcs) through
CONTACT's own Python interface (`python_intfc`, ctypes) on the library
LIBRARY (CONTACT's contact_addon_linux64.so or railcontact's, built with
crates/cntc/build-lib.sh), and prints per case and patch FN, FX, FS, MZ, the
creepages, the approach and the contact location. Run it once per library
and compare (crates/cntc/tests/slices.rs holds CONTACT's numbers).

The cases are CONTACT's testbank/examples_s+c/mbench_locus.inp (its calls
made one by one: the S1002 wheel of the Manchester benchmark on the UK
crossing nose, S = 239 mm, FZ = 10 kN, a pitch rate giving large
longitudinal creepage) at several wheelset positions, on the slices of
crates/solver/profiles/uk_crossing_nose.slcs (slices 66-75 of CONTACT's
uk_crossing.slcs). Needs numpy.
"""
import os
import sys

from placement_cases import load, print_patches, wheelrail_element

HERE = os.path.dirname(os.path.abspath(__file__))
PROFILES = os.path.normpath(os.path.join(HERE, '..', '..', 'solver', 'profiles'))


# (name, S [mm], Y [mm], YAW [rad], rail file)
CASES = [
    ('s239', 239.0, 0.81, 0.0, 'uk_crossing_nose.slcs'),
    ('s239-y5', 239.0, 5.0, 0.0, 'uk_crossing_nose.slcs'),
    ('s239-ym5', 239.0, -5.0, 0.0, 'uk_crossing_nose.slcs'),
    ('s280', 280.0, 0.81, 0.0, 'uk_crossing_nose.slcs'),
    ('s260-yaw', 260.0, 2.0, 0.003, 'uk_crossing_nose.slcs'),
    # two patches: the wing rail and the nose
    ('s300-ym6.8', 300.0, -6.8, 0.0, 'uk_crossing_nose.slcs'),
    ('s300-ym7', 300.0, -7.0, 0.0, 'uk_crossing_nose.slcs'),
]


def run(cntc, only):
    import numpy as np
    from ctypes import c_int
    CNTC, _, ierror = cntc.initlibrary(' ', ' ', ' ', 0)
    assert ierror == 0, ierror
    for ire, (name, s, y, yaw, rail) in enumerate(CASES, 1):
        if only and name not in only:
            continue
        wheelrail_element(cntc, CNTC, ire, 1, 1)
        cntc.setsolverflags(ire, [], 0, np.array([999, 100, 30, 1], dtype=c_int), np.array([1e-5]))
        cntc.setverticalforce(ire, 10000.0)
        cntc.setpotcontact(ire, [], -1, np.array([0.2, 0.2, np.pi / 2, 8.0, 4.0]))
        cntc.setrollingstepsize(ire, [], [], 1.0)
        cntc.settrackdimensions(ire, 3, np.array([-1.0, 750.0, 0.0, 0.0, 0.0] + [0.0] * 6))
        cntc.setprofileinputfname(ire, os.path.join(PROFILES, rail), [0, 0, 0, -1],
                                  [1000.0, 0.0])
        cntc.setwheelsetdimensions(ire, 3, np.array([1360.0, -70.0, 460.0]))
        cntc.setprofileinputfname(ire, os.path.join(PROFILES, 'MBench_S1002_v3.prw'),
                                  [1, 0, 0, -1], [1.0, 0.0])
        cntc.setwheelsetposition(ire, 3, np.array([s, y, 0.0, 0.0, yaw, 0.0]))
        cntc.setwheelsetvelocity(ire, 3, np.array([2000.0, 0.0, 0.0, 0.0, 0.0, -4.34811810]))
        print_patches(cntc, ire, name, cntc.calculate(ire, -1, 0))

if __name__ == '__main__':
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    run(load(sys.argv[1], sys.argv[2]), set(sys.argv[3:]))
