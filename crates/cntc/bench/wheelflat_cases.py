"""wheelflat_cases.py PYTHON_INTFC LIBRARY SLCW [SMOOTH] [PITCH_DEG ...]

Runs CONTACT's examples/wheelflat.inp (user guide section 5.8: Chalmers'
measured wheel flat on an S1002 wheel, a wheel slices file .slcw, on the
r300_wide.prr rail; FZ = 125 kN, steady rolling, DX = DS = 0.4 mm) at the
pitch angles PITCH_DEG (default -25 .. -50 degrees, the example's 26 cases)
through CONTACT's own Python interface (`python_intfc`, ctypes) on the
library LIBRARY (CONTACT's contact_addon_linux64.so or railcontact's, built
with crates/cntc/build-lib.sh), and prints per case FN, FX, FS, MN, the
approach, the largest pressure, the elements in contact, the contact
reference point and the median time per calculation. SLCW is the wheel
slices file (CONTACT's examples/S1002_flat.slcw or the repository's
crates/solver/profiles/S1002_flat.slcw), SMOOTH the wheel's smoothing
parameter (the example's 5: lambda of ismooth 0). Needs numpy.
"""
import os
import statistics
import sys
import time

from placement_cases import load, wheelrail_element

HERE = os.path.dirname(os.path.abspath(__file__))
PROFILES = os.path.normpath(os.path.join(HERE, '..', '..', 'solver', 'profiles'))


def run(cntc, slcw, smooth, pitches):
    import numpy as np
    from ctypes import c_int
    CNTC, _, ierror = cntc.initlibrary(' ', ' ', ' ', 0)
    assert ierror == 0, ierror
    ire = 1
    wheelrail_element(cntc, CNTC, ire, 1, 1)
    cntc.setsolverflags(ire, [], 0, np.array([999, 100, 30, 1], dtype=c_int), np.array([1e-5]))
    cntc.setverticalforce(ire, 125000.0)
    cntc.setpotcontact(ire, [], -1, np.array([0.4, 0.4, np.pi / 2, 8.0, 4.0]))
    cntc.setrollingstepsize(ire, [], [], 1.0)
    # Z = 3: GAUGHT, -, GAUGWD, CANT, NOMRAD, CURV, then the deviations
    cntc.settrackdimensions(ire, 3, np.array([14.0, 0.0, 1435.0, 0.020, 0.0, 0.0] + [0.0] * 6))
    cntc.setprofileinputfname(ire, os.path.join(PROFILES, 'r300_wide.prr'), [0, 0, 0, -1],
                              [1.0, 0.0])
    cntc.setwheelsetdimensions(ire, 3, np.array([1360.0, -70.0, 490.0]))
    cntc.setprofileinputfname(ire, slcw, [1, 0, 0, -1], [1.0, smooth])
    cntc.setwheelsetvelocity(ire, 3, np.array([2000.0, 0.0, 0.0, 0.0, 0.0, -4.08190679]))
    times = []
    for deg in pitches:
        cntc.setwheelsetposition(ire, 3, np.array([0.0, 0.0, 0.0, 0.0, 0.0,
                                                    np.radians(deg)]))
        t0 = time.perf_counter()
        ierr = cntc.calculate(ire, -1, 0)
        times.append(time.perf_counter() - t0)
        npatch = cntc.getnumcontactpatches(ire)
        for icp in range(1, npatch + 1):
            fn, fx, fs, mz = cntc.getcontactforces(ire, icp)
            pen = cntc.getpenetration(ire, icp)
            pmax = cntc.getmaximumpressure(ire, icp)
            areas = cntc.getcontactpatchareas(ire, icp)
            loc = cntc.getcontactlocation(ire, icp)
            print(f'pitch {deg:6.1f} ierr {ierr} patch {icp}/{npatch}: FN {fn:.6g} FX {fx:.6g} '
                  f'FS {fs:.6g} MN {mz:.6g} PEN {pen:.6f} PMAX {pmax:.5g} '
                  f'NCON {areas[0] / 0.16:.0f} XCP {loc[0]:.4f} YCP {loc[1]:.4f}')
    print(f'median time per calculation {1e3 * statistics.median(times):.1f} ms '
          f'({len(times)} cases)')


if __name__ == '__main__':
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    smooth = float(sys.argv[4]) if len(sys.argv) > 4 else 5.0
    pitches = [float(a) for a in sys.argv[5:]] or [-25.0 - i for i in range(26)]
    run(load(sys.argv[1], sys.argv[2]), sys.argv[3], smooth, pitches)
