"""readinp_subs.py PYTHON_INTFC LIBRARY

Reads a module 1 input file with subsurface points (S = 3: the Manchester
benchmark A-2.2 right wheel at y = 3 mm, yaw 7.2 mrad, the file of
crates/cntc/tests/common/mod.rs `MBENCH_RIGHT_INP` with blocks of ISUBS 5
and 9) through CONTACT's own Python interface (`python_intfc`, ctypes) on
the library LIBRARY (CONTACT's contact_addon_linux64.so or railcontact's,
built with crates/cntc/build-lib.sh), calculates, calls subs_calculate and
prints each block's size and columns 1-3 and 7-9 (x, y, z; sighyd, von
Mises, Tresca) of subs_getresults, and the patch's FN. Run it once per
library and compare.

  PYTHON_INTFC  CONTACT's python_intfc folder (a checkout of eve70a/CONTACT)
  LIBRARY       the library to load (copied beside a copy of python_intfc,
                in bin/, where python_intfc looks)

The profiles are the repository's (crates/solver/profiles). Needs numpy.
"""
import os
import shutil
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
PROFILES = os.path.normpath(os.path.join(HERE, '..', '..', 'solver', 'profiles'))

INP = """\
  1 MODULE
 1203103    C-P-B-T-N-F-S   CONFIG, PVTIME, BOUND,  TANG,   NORM,   FORCE,  STRESS
 0022033    V-L-D-C-M-Z-E   VARFRC, FRCLAW, DISCNS, INFLCF, MATER,  ZTRACK, EWHEEL
 0000321    H-G-I-A-O-W-R     HEAT, GAUSEI, IESTIM, MATFIL, OUTPUT, FLOW,   RETURN
    999     100    30    1     1d-5         MAXGS , MAXIN , MAXNR , MAXOUT, EPS
  0.300   0.300                                 FSTAT, FKIN
  0.280,  0.280,  82000., 82000.                POISS 1,2,  GG 1,2
  0.200   0.200   1.000   90d   8.0   4.0       DX, DS, DQREL, A_SEP, D_SEP, D_COMB
   14.0     0    1435.0   0.000                 GAUGHT, GAUGSQ, GAUGWD, CANT
  'MBench_UIC60_v3.prr'   0     1.0   0.0       RFNAME, MIRRORY, SCALE, SMOOTH
     0.0    0.0   0.000   0.0   0.0   0.000     DY, DZ, ROLL, VY, VZ, VROLL
  1360.0  -70.0   460.0                         FBDIST, FBPOS, NOMRAD
  'MBench_S1002_v3.prw'   0     1.0   0.0       WFNAME, MIRRORY, SCALE, SMOOTH
  0.0  3.0  10000. -0.00018030 0.0072  0.0      S, Y, FZ, ROLL, YAW, PITCH
 2000. 0.0    0.0   0.0        0.0  -4.34515030 VS,VY,VZ, VROLL,VYAW,VPITCH
% subsurface points
  2    1              MATFIL, OUTPUT
  7                   ISUBS
  3  4                NX, NY
  12  8  10           IX
  20  14  17  11      IY
  3                   NZ
  1.0  0.0  0.5       Z (sorted when read)
  9                   ISUBS
  3   2   2           NX, NY, NZ
  -1.0  0.0  1.0      X
  0.0  0.5            Y
  2.0  0.25           Z
  0                   ISUBS
"""


def load(intfc, library):
    work = tempfile.mkdtemp(prefix='readinp-subs-')
    shutil.copytree(intfc, os.path.join(work, 'python_intfc'))
    os.makedirs(os.path.join(work, 'bin'))
    shutil.copy(library, os.path.join(work, 'bin', 'contact_addon_linux64.so'))
    for p in ('MBench_UIC60_v3.prr', 'MBench_S1002_v3.prw'):
        shutil.copy(os.path.join(PROFILES, p), work)
    with open(os.path.join(work, 'subs.inp'), 'w') as f:
        f.write(INP)
    os.environ.setdefault('LD_LIBRARY_PATH', '/nonexistent')
    sys.path.insert(0, work)
    os.chdir(work)
    import python_intfc as cntc
    return cntc


def main():
    cntc = load(sys.argv[1], sys.argv[2])
    CNTC, _, ierror = cntc.initlibrary(' ', ' ', ' ', 0)
    assert ierror == 0, ierror
    ire = 1
    cntc.initialize(ire, 1, ' ', 0)
    print('readinpfile', cntc.readinpfile(ire, CNTC['inp_modul1'], 'subs.inp'))
    print('calculate', cntc.calculate(ire))
    fn, fx, fs, mz = cntc.getcontactforces(ire, 1)
    print('FN', repr(fn))
    cntc.subs_calculate(ire, -1)
    for iblk in (1, 2):
        print('block', iblk, cntc.subs_getblocksize(ire, 1, iblk))
        r = cntc.subs_getresults(ire, 1, iblk, [1, 2, 3, 7, 8, 9])
        for row in r:
            print(' '.join('%.7e' % v for v in row))


main()
