"""given_flexibility_cases.py PYTHON_INTFC LIBRARY

CONTACT's M = 2 (modified FASTSIM with one given flexibility FLX) through
CONTACT's own Python interface (`python_intfc`, ctypes) on the library
LIBRARY (CONTACT's contact_addon_linux64.so or railcontact's, built with
crates/cntc/build-lib.sh): module 3 Hertzian patches (python_tractcurv.py's
ellipse with B = 3 and B = 2, FLX 5e-5 and 1.2e-4 mm^3/N, with and without
slope reduction, eight creepages with and without spin; B = 0 on
fastsim.inp's ellipse with falling friction; SI units), module 1 wheel/rail
patches (python_mbench.py's tread case 5 of wheel 1 and flange case 16 of
wheel 2) and a module 1 input file with M = 2 (the benchmark's right wheel
at y = 3 mm); M = 3 on the same ellipse (B = 3, 2, with and without slope
reduction, cntc_getparameters task 2 before the first calculation too)
and on the module 1 patches. Prints FN, FX, FY (FS), MZ, the areas and
FLX(1:3), K0_MF, ALFAMF, BETAMF, K_EFF per case with 17 digits, a module 3 case's
displacement differences at a few elements and the module 1 patches' extremes: run it once per library and
compare (crates/cntc/tests/fastsim.rs, module1.rs, readinp.rs and
displacements.rs quote CONTACT's). The profiles are the repository's (crates/solver/profiles).
Needs numpy.
"""
import os
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from placement_cases import load, PROFILES  # noqa: E402
import numpy as np  # noqa: E402
from ctypes import c_int  # noqa: E402

cntc = load(sys.argv[1], sys.argv[2])
CNTC, _, ierror = cntc.initlibrary(' ', ' ', ' ', 0)
EX = PROFILES + os.sep

def setflags(ire, icp, pairs):
    cntc.setflags(ire, icp, np.array([CNTC[k] for k, _ in pairs], dtype=c_int),
                  np.array([v for _, v in pairs], dtype=c_int))

def m3_patch(ire, units, bound, mat, fric, ipotcn=-2):
    cntc.initialize(ire, 3)
    icp = 1
    setflags(ire, icp, [('if_units', units), ('ic_tang', 3), ('ic_norm', 1), ('ic_pvtime', 2)])
    cntc.setmaterialparameters(ire, icp, mat[0], mat[1])
    setflags(ire, icp, [('ic_bound', bound)])
    if units == CNTC['un_cntc']:
        hz = [48, 44, 0.0008, 0.5, 1.1] if ipotcn == -2 else [44, 44, 8.0, 4.0, 1.1]
        cntc.sethertzcontact(ire, icp, ipotcn, hz)
        cntc.setreferencevelocity(ire, icp, 10000.0)
        cntc.setnormalforce(ire, icp, 106700.0 if ipotcn == -2 else 82000.0)
    else:
        cntc.sethertzcontact(ire, icp, -1, [40, 36, 0.5, 1.2, 1.15])
        cntc.setreferencevelocity(ire, icp, 20.0)
        cntc.setnormalforce(ire, icp, 60000.0)
    cntc.setfrictionmethod(ire, icp, fric[0], fric[1])

def m3_solve(ire, tag, creep):
    icp = 1
    cntc.setcreepages(ire, icp, *creep)
    e = cntc.calculate(ire, icp, 0)
    fn, fx, fy, mz = cntc.getcontactforces(ire, icp)
    ca, ha, sa = cntc.getcontactpatchareas(ire, icp)[:3]
    par = cntc.getparameters(ire, icp, 2)
    print('%s creep %s ierr %d FN %.17g FX %.17g FY %.17g MZ %.17g areas %.17g %.17g %.17g flx %.17g %.17g %.17g k0ab %.6g %.6g %.6g keff %.17g' %
          (tag, creep, e, fn, fx, fy, mz, ca, ha, sa, par['flx1'], par['flx2'], par['flx3'], par['k0_mf'], par['alfamf'], par['betamf'], par['k_eff']))

cc = CNTC['un_cntc']
# Module 3, tractcurv's ellipse, parabolic bound B = 3, Coulomb 0.33.
creeps = [(1e-5, 0, 0), (0.0008, 0, 0), (0.0016, 0, 0), (0.0048, 0, 0),
          (0, 0.001, 0), (0.0005, 0.0008, 0.0003), (0, 0, 0.0004), (0.002, -0.001, -0.0006)]
for tag, ire, bound, flx, red in [('b3-kalker', 1, 3, 5e-5, [1.0, 1.0, 1.0]),
                                  ('b3-red', 2, 3, 5e-5, [0.54, 0.02, 0.62]),
                                  ('b2-flx2', 3, 2, 1.2e-4, [1.0, 1.0, 1.0]),
                                  ('b2-red', 4, 2, 1.2e-4, [0.7, 0.3, 0.8])]:
    m3_patch(ire, cc, bound, (2, [0.28, 0.28, 82000.0, 82000.0, flx] + red), (0, [0.33, 0.33]))
    for c in creeps:
        m3_solve(ire, tag, c)
# B = 0 on fastsim.inp's ellipse (-3), falling friction L = 4.
m3_patch(5, cc, 0, (2, [0.28, 0.28, 82000.0, 82000.0, 8e-5, 0.54, 0.02, 0.62]),
         (4, [0.1368, 0.2232, 990.0, 0.0, 0.0, 0.003, 1.0]), ipotcn=-3)
for c in [(0.0, -0.000625, 0.000625), (0.003, 0.0005, -0.0002)]:
    m3_solve(5, 'b0-l4', c)
# SI units: flx 6e-14 m^3/N (6e-5 mm^3/N), B = 2, linear falling friction.
m3_patch(6, CNTC['un_si'], 2, (2, [0.28, 0.28, 82e9, 82e9, 6e-14, 0.7, 0.3, 0.8]),
         (2, [0.2, 0.15, 2.0, 0.0, 0.0, 0.0, 0.0]))
for c in [(0.002, 0.001, 0.4), (0.0003, 0.0, 0.0)]:
    m3_solve(6, 'si', c)

# M = 3 on tractcurv's ellipse (Kalker's three flexibilities, blended), B = 3
# and B = 2, with and without slope reduction; getparameters task 2 before
# the first calculation too.
for tag, ire, bound, red in [('m3-b3', 7, 3, [1.0, 1.0, 1.0]), ('m3-b3-red', 8, 3, [0.54, 0.02, 0.62]),
                             ('m3-b2-red', 9, 2, [0.7, 0.3, 0.8])]:
    m3_patch(ire, cc, bound, (3, [0.28, 0.28, 82000.0, 82000.0] + red), (0, [0.33, 0.33]))
    par = cntc.getparameters(ire, 1, 2)
    print('%s before flx %.17g %.17g %.17g keff %.17g' % (tag, par['flx1'], par['flx2'], par['flx3'], par['k_eff']))
    for c in creeps:
        m3_solve(ire, tag, c)
m3_patch(10, cc, 3, (2, [0.28, 0.28, 82000.0, 82000.0, 5e-5, 0.54, 0.02, 0.62]), (0, [0.33, 0.33]))
par = cntc.getparameters(10, 1, 2)
print('m2 before flx %.17g %.17g %.17g keff %.17g' % (par['flx1'], par['flx2'], par['flx3'], par['k_eff']))

# Module 1: python_mbench.py's wheels (as crates/cntc/tests/common mbench_wheel).
def mbench(ire, iwhe, mat):
    cntc.initialize(ire, 1)
    setflags(ire, -1, [('if_units', cc), ('ic_config', iwhe - 1), ('ic_tang', 3), ('ic_pvtime', 2),
                       ('ic_norm', 1), ('ic_force', 0), ('ic_discns', 2)])
    cntc.setmaterialparameters(ire, -1, mat[0], mat[1])
    cntc.setfrictionmethod(ire, -1, 0, [0.3, 0.3])
    cntc.setverticalforce(ire, 10000.0)
    cntc.setpotcontact(ire, -1, -1, [0.2, 0.2, np.pi / 2, 8.0, 4.0])
    cntc.settrackdimensions(ire, 3, [14.0, 0.0, 1435.0, 0, 0, 0, 0, 0, 0, 0, 0])
    rail, mirror = ('MBench_UIC60_v3.prr', 0) if iwhe == 1 else ('MBench_UIC60_v3.ban', 1)
    cntc.setprofileinputfname(ire, EX + rail, [-1, 0, mirror], [1.0, 0.0])
    cntc.setwheelsetdimensions(ire, 3, [1360.0, -70.0, 460.0])
    cntc.setprofileinputfname(ire, EX + 'MBench_S1002_v3.prw', [-1, 0, 0], [1.0, 0.0])
    cntc.setwheelsetflexibility(ire, 1, [0.0] * 12)

def m1_solve(ire, tag, pos, vpitch):
    cntc.setwheelsetposition(ire, 2, pos)
    cntc.setwheelsetvelocity(ire, 2, [2000.0, 0, 0, 0, 0, vpitch])
    e = cntc.calculate(ire, -1, 0)
    g = cntc.getglobalforces(ire, -1)
    np_ = cntc.getnumcontactpatches(ire)
    print('%s ierr %d npatch %d FX_TR %.17g FY_TR %.17g FZ_TR %.17g' % (tag, e, np_, g[0], g[1], g[2]))
    for icp in range(1, np_ + 1):
        fn, fx, fs, mz = cntc.getcontactforces(ire, icp)
        ca, ha, sa = cntc.getcontactpatchareas(ire, icp)[:3]
        pm = cntc.getmaximumpressure(ire, icp)
        cr = cntc.getcreepages(ire, icp)
        par = cntc.getparameters(ire, icp, 2)
        print('   %d FN %.17g FX %.17g FS %.17g MZ %.17g areas %.9g %.9g %.9g pmax %.9g creep %s' %
              (icp, fn, fx, fs, mz, ca, ha, sa, pm, ' '.join('%.9g' % c for c in cr)))
        print('   %d flx %.17g %.17g %.17g keff %.17g' %
              (icp, par['flx1'], par['flx2'], par['flx3'], par['k_eff']))

tread = ([0.0, 2.0, 0.0, -0.0001128, 0.0048, 0.0], -4.3459197)
flange = ([0.0, 7.5, 0.0, -0.007642, 0.018, 0.0], -4.2575747)
for k, (flx, red) in enumerate([(5e-5, [1.0, 1.0, 1.0]), (1.5e-4, [0.54, 0.02, 0.62])]):
    mat = (2, [0.28, 0.28, 82000.0, 82000.0, flx] + red)
    mbench(11 + 2 * k, 1, mat)
    m1_solve(11 + 2 * k, 'm1-tread-%d' % k, *tread)
    mbench(12 + 2 * k, 2, mat)
    m1_solve(12 + 2 * k, 'm1-flange-%d' % k, *flange)
# The same with M = 3 (Kalker's flexibilities of each patch's equivalent ellipse).
for k, red in enumerate([[1.0, 1.0, 1.0], [0.54, 0.02, 0.62]]):
    mat = (3, [0.28, 0.28, 82000.0, 82000.0] + red)
    mbench(41 + 2 * k, 1, mat)
    m1_solve(41 + 2 * k, 'm1-m3-tread-%d' % k, *tread)
    mbench(42 + 2 * k, 2, mat)
    m1_solve(42 + 2 * k, 'm1-m3-flange-%d' % k, *flange)

# Module 1 displacement differences (cntc_getdisplacements) of the M = 3 tread
# patch without reduction, the M = 3 flange patch with it and the M = 2 tread
# patch of FLX 1.5e-4 with it: the largest UN and the extremes of UX, UY
# (crates/cntc/tests/displacements.rs).
for tag, ire in [('m1-m3-tread-0', 41), ('m1-m3-flange-1', 44), ('m1-tread-1', 13)]:
    un, ux, uy = (np.ravel(u) for u in cntc.getdisplacements(ire, 1))
    print('m1 disp %s: UN max %.10g UX min %.10g max %.10g UY min %.10g max %.10g' %
          (tag, un.max(), ux.min(), ux.max(), uy.min(), uy.max()))

# Module 1 input file: crates/cntc/tests/common's MBENCH_RIGHT_INP with M = 2.
INP = """\
  1 MODULE
 1203100    C-P-B-T-N-F-S   CONFIG, PVTIME, BOUND,  TANG,   NORM,   FORCE,  STRESS
 0022233    V-L-D-C-M-Z-E   VARFRC, FRCLAW, DISCNS, INFLCF, MATER,  ZTRACK, EWHEEL
 0000321    H-G-I-A-O-W-R     HEAT, GAUSEI, IESTIM, MATFIL, OUTPUT, FLOW,   RETURN
    999     100    30    1     1d-5         MAXGS , MAXIN , MAXNR , MAXOUT, EPS
  0.300   0.300                                 FSTAT, FKIN
  0.280,  0.280,  82000., 82000.                POISS 1,2,  GG 1,2
  1.0e-4  0.54    0.02    0.62                  FLX, K0_MF, ALFAMF, BETAMF
  0.200   0.200   1.000   90d   8.0   4.0       DX, DS, DQREL, A_SEP, D_SEP, D_COMB
   14.0     0    1435.0   0.000                 GAUGHT, GAUGSQ, GAUGWD, CANT
  '%(p)s/MBench_UIC60_v3.prr'   0     1.0   0.0       RFNAME, MIRRORY, SCALE, SMOOTH
     0.0    0.0   0.000   0.0   0.0   0.000     DY, DZ, ROLL, VY, VZ, VROLL
  1360.0  -70.0   460.0                         FBDIST, FBPOS, NOMRAD
  '%(p)s/MBench_S1002_v3.prw'   0     1.0   0.0       WFNAME, MIRRORY, SCALE, SMOOTH
  0.0  3.0  10000. -0.00018030 0.0072  0.0      S, Y, FZ, ROLL, YAW, PITCH
 2000. 0.0    0.0   0.0        0.0  -4.34515030 VS,VY,VZ, VROLL,VYAW,VPITCH
""" % {'p': PROFILES}
path = os.path.join(tempfile.mkdtemp(prefix='m2-inp-'), 'mbench_m2.inp')
with open(path, 'w') as f:
    f.write(INP)
ire = 21
cntc.initialize(ire, 1)
print('inp readinp', cntc.readinpfile(ire, CNTC['inp_modul1'], path))
e = cntc.calculate(ire, -1, 0)
g = cntc.getglobalforces(ire, -1)
print('inp ierr %d npatch %d FX_TR %.17g FY_TR %.17g FZ_TR %.17g' %
      (e, cntc.getnumcontactpatches(ire), g[0], g[1], g[2]))
fn, fx, fs, mz = cntc.getcontactforces(ire, 1)
cr = cntc.getcreepages(ire, 1)
print('   1 FN %.17g FX %.17g FS %.17g MZ %.17g creep %.17g %.17g %.17g' % ((fn, fx, fs, mz) + tuple(cr)))

# Module 3 displacement differences (cntc_getdisplacements) with M = 2:
# crates/cntc/tests/common's tractcurv set-up, A = 2 (CONTACT computes the
# exterior elements too), FLX 5e-5 mm^3/N, k0 0.54, alpha 0.02, beta 0.62,
# B = 3; UN, UX, UY at elements 0, 1058, 1080, 510, 1500, their max, min.
ire = 31
m3_patch(ire, cc, 3, (2, [0.28, 0.28, 82000.0, 82000.0, 5e-5, 0.54, 0.02, 0.62]), (0, [0.33, 0.33]))
setflags(ire, 1, [('ic_matfil', 2)])
cntc.setcreepages(ire, 1, 0.0007, -0.0004, 0.00003)
print('disp ierr', cntc.calculate(ire, 1, 0))
un, ux, uy = (np.ravel(u) for u in cntc.getdisplacements(ire, 1))
for i in [0, 1058, 1080, 510, 1500]:
    print('disp element %d: %r, %r, %r' % (i, float(un[i]), float(ux[i]), float(uy[i])))
print('disp max: %r, %r, %r' % (float(un.max()), float(ux.max()), float(uy.max())))
print('disp min: %r, %r, %r' % (float(un.min()), float(ux.min()), float(uy.min())))
