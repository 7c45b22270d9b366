"""viscoelastic_cases.py PYTHON_INTFC LIBRARY [CASE ...]

Module 1 with viscoelastic bodies (M = 1): the Manchester benchmark's
right wheel (S1002 on UIC60, gauge-point placement, 10 kN) at several
lateral shifts and yaw angles of its A-2.2 series, rolling at VS = 1 m/s
with the series' pitch rates halved (its creepages), read from module 1
input files (`cntc_readinpfile`) through CONTACT's own Python interface
(`python_intfc`, ctypes) on the library LIBRARY (CONTACT's
contact_addon_linux64.so or railcontact's, built with
crates/cntc/build-lib.sh); prints per case and patch what the getters
report: FN, FX, FS, MZ, the creepages, the area, the maximum pressure and
VELOC. Run it once per library and compare.

Why input files and VS = 1 m/s: CONTACT's `cntc_setmaterialparameters`
does not set the relaxation lengths VT = TC V that its viscoelastic
kernels take (they are left as the memory held, so that its setters give
results that change from run to run); its module 1 input-file reader
sets VT = TC x 1000 mm/s (its default VELOC, whatever the wheelset's
speed). At VS = 1 m/s that is TC times the rolling speed, the
relaxation length railcontact takes (TC x the wheelset's speed), so the
two libraries solve the same problem.

The cases (FG per body, TC per body [s]): both bodies FG 3 (the final
modulus a quarter of G) with TC 5 ms (VT 5 mm, about the patch's
length) on the centred wheelset; at 3 mm, 7.2 mrad with TC 1 ms (VT
1 mm); at 6.5 mm, 15.6 mrad (a flange patch beside the tread's) with
the rail FG 3, TC 2 ms and the wheel FG 1, TC 0.5 ms; two patches (a
flange root's and a tread's, the wheelset's height given: 6.46 mm, 21.6
mrad, crates/cntc/tests/two_point_contact.rs) with FG 3, TC 2 ms; each
beside its elastic case (M = 0), and the centred one with TC 0 (VT 0:
the elastic bodies of G/4).

  PYTHON_INTFC  CONTACT's python_intfc folder (a checkout of eve70a/CONTACT)
  LIBRARY       the library to load (copied beside a copy of python_intfc,
                in bin/, where python_intfc looks)

The profiles are the repository's (crates/solver/profiles). Needs numpy.
"""
import os
import shutil
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from placement_cases import PROFILES, load as load_intfc  # noqa: E402

# The A-2.2 series' (y [mm], roll, yaw [rad], VPITCH at 1 m/s [rad/s],
# FZ [N]) or, with FZ None, the wheelset's height Z_WS [mm] (N = 0): the
# two patches of crates/cntc/tests/two_point_contact.rs at 6.46 mm.
POSITIONS = {
    'y0': (0.0, 0.0, 0.0, -4.34811810 / 2, 10000.0, None),
    'y3': (3.0, -0.00018030, 0.0072, -4.34515030 / 2, 10000.0, None),
    'y6.5': (6.5, -0.00437600, 0.0156, -4.27488340 / 2, 10000.0, None),
    'y6.46': (6.46, 0.0, 0.0216, -2.17, None, -0.698),
}

# (name, position, M digit, FG1, FG2, TC1, TC2): body 1 the rail, 2 the wheel.
CASES = [
    ('y0-elastic', 'y0', 0, 0, 0, 0, 0),
    ('y0-fg3-tc5ms', 'y0', 1, 3.0, 3.0, 5e-3, 5e-3),
    ('y0-fg3-tc0', 'y0', 1, 3.0, 3.0, 0.0, 0.0),
    ('y3-elastic', 'y3', 0, 0, 0, 0, 0),
    ('y3-fg3-tc1ms', 'y3', 1, 3.0, 3.0, 1e-3, 1e-3),
    ('y6.5-elastic', 'y6.5', 0, 0, 0, 0, 0),
    ('y6.5-mixed', 'y6.5', 1, 3.0, 1.0, 2e-3, 5e-4),
    ('y6.46-elastic', 'y6.46', 0, 0, 0, 0, 0),
    ('y6.46-fg3-tc2ms', 'y6.46', 1, 3.0, 3.0, 2e-3, 2e-3),
]


# The lines of the input files from DX to the wheel profile (0.2 mm
# elements, gauge-point placement, the profiles in the working directory).
GEOMETRY = (
    '  0.200   0.200   1.000   90d   8.0   4.0       DX, DS, DQREL, A_SEP, D_SEP, D_COMB\n'
    '   14.0     0    1435.0   0.000         GAUGHT, GAUGSQ, GAUGWD, CANT\n'
    "  'MBench_UIC60_v3.prr'   0     1.0   0.0       RFNAME, MIRRORY, SCALE, SMOOTH\n"
    '     0.0    0.0   0.000   0.0   0.0   0.000     DY, DZ, ROLL, VY, VZ, VROLL\n'
    '  1360.0  -70.0   460.0             FBDIST, FBPOS, NOMRAD\n'
    "  'MBench_S1002_v3.prw'   0     1.0   0.0       WFNAME, MIRRORY, SCALE, SMOOTH\n"
)


def inp_text(case):
    """The module 1 input file of `case`."""
    _, pos, m, fg1, fg2, tc1, tc2 = case
    y, roll, yaw, vpitch, fz, z_ws = POSITIONS[pos]
    norm, z = (1, fz) if fz is not None else (0, z_ws)
    visc = '' if m == 0 else (
        '  %g  %g  %g  %g                FG 1,2,  TC 1,2\n' % (fg1, fg2, tc1, tc2))
    return (
        '  1 MODULE\n'
        ' 1203%d00    C-P-B-T-N-F-S   CONFIG, PVTIME, BOUND,  TANG,   NORM,   FORCE,  STRESS\n'
        ' 0022%d33    V-L-D-C-M-Z-E   VARFRC, FRCLAW, DISCNS, INFLCF, MATER,  ZTRACK, EWHEEL\n'
        ' 0000321    H-G-I-A-O-W-R     HEAT, GAUSEI, IESTIM, MATFIL, OUTPUT, FLOW,   RETURN\n'
        '    999     100    30    1     1d-5         MAXGS , MAXIN , MAXNR , MAXOUT, EPS\n'
        '  0.300   0.300                                 FSTAT, FKIN\n'
        '  0.280   0.280   82000.  82000.                POISS 1,2,  GG 1,2\n'
        '%s'
        '%s'
        '  0.0  %.4f  %.4f  %.8f  %.4f  0.0      S, Y, FZ, ROLL, YAW, PITCH\n'
        ' 1000.  0.0   0.0   0.0   0.0  %.9f     VS, VY, VZ, VROLL, VYAW, VPITCH\n'
    ) % (norm, m, visc, GEOMETRY, y, z, roll, yaw, vpitch)


def load(intfc, library, cases=CASES, text=inp_text, prefix='viscoelastic-'):
    """placement_cases.py's loader, in a folder holding the input files
    `text(case)` of `cases` and their profiles (the working directory)."""
    cntc = load_intfc(intfc, library)
    work = tempfile.mkdtemp(prefix=prefix)
    for p in ('MBench_UIC60_v3.prr', 'MBench_S1002_v3.prw'):
        shutil.copy(os.path.join(PROFILES, p), work)
    for case in cases:
        with open(os.path.join(work, case[0] + '.inp'), 'w') as f:
            f.write(text(case))
    os.chdir(work)
    return cntc


def solve_file(cntc, CNTC, ire, name):
    """Reads `name`.inp on `ire` and calculates it; prints the errors and
    returns the number of patches."""
    cntc.initialize(ire, 1, ' ', 0)
    t0 = time.time()
    ierr_read = cntc.readinpfile(ire, CNTC['inp_modul1'], name + '.inp')
    ierr = cntc.calculate(ire)
    npatch = cntc.getnumcontactpatches(ire)
    print(f'case {name}: readinpfile {ierr_read}, ierror {ierr}, {npatch} patch(es), '
          f'{time.time() - t0:.1f} s')
    return npatch


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    only = set(sys.argv[3:])
    cntc = load(sys.argv[1], sys.argv[2])
    CNTC, _, ierror = cntc.initlibrary(' ', ' ', ' ', 0)
    assert ierror == 0, ierror
    chosen = [(ire, c) for ire, c in enumerate(CASES, 1) if not only or c[0] in only]
    for ire, case in chosen:
        npatch = solve_file(cntc, CNTC, ire, case[0])
        for icp in range(1, npatch + 1):
            fn, fx, fs, mz = cntc.getcontactforces(ire, icp)
            cx, cy, cp = cntc.getcreepages(ire, icp)
            area = cntc.getcontactpatchareas(ire, icp)[0]
            pmax = cntc.getmaximumpressure(ire, icp)
            veloc = cntc.getparameters(ire, icp, 1)['veloc']
            print(f'  patch {icp}: FN {fn!r} FX {fx!r} FS {fs!r} MZ {mz!r}')
            print(f'    CKSI {cx!r} CETA {cy!r} CPHI {cp!r} AREA {area!r} '
                  f'PMAX {pmax!r} VELOC {float(veloc)!r}')


if __name__ == '__main__':
    main()
