"""conformal_cases.py PYTHON_INTFC LIBRARY [CONTACT_SRC]

CONTACT's conformal cases of module 1 (D = 4: a curved reference surface
along the rail profile) read with `cntc_readinpfile` through CONTACT's own
Python interface (`python_intfc`, ctypes) on the library LIBRARY (CONTACT's
contact_addon_linux64.so or railcontact's, built with
crates/cntc/build-lib.sh), calculated, and printed per patch: FN, FX, FS,
MN (`cntc_getcontactforces`), the contact location (track y, z, angle;
rail y, z), the approach, PMAX, the contact area and its element count
(area / (DX DS)), the grid's size. Run it once per library and compare,
from a scratch directory (CONTACT's library leaves contact_addon.out in the
working directory).

The cases (from CONTACT_SRC, a checkout of eve70a/CONTACT, default
/tmp/contact-src; its testbank), each with D = 4 and with D = 2 (planar):
  mbench       examples_conformal/mbench_conf.inp case 1: the Manchester
               benchmark's right wheel, cant 0.025, y 6.25 mm, yaw 24 mrad,
               Z_WS 0.172 mm given (N = 0), friction by contact angle
               (V = 1), D_SEP 9, D_COMB 6: CONTACT makes two patches (tread
               and flange at -70 degrees)
  mbench-sep4  the same with D_SEP 4, D_COMB 3 (CONTACT's result is the
               same, and so is this library's: two patches either way)
  tb35         testbank.inp case 35: case 33's worn wheel
               (worn_high_mileage) on site_b_hr, y 14.85 mm, Z_WS 1.17 mm
               given, D_SEP 30, D_COMB 20: one patch over the flange root
               (contact angle -72 to -2 degrees)
  tb35-sep6, tb35-sep3  the same with D_SEP 6, D_COMB 3 and 3, 1.5
  groove       examples_conformal/groove_li.inp case 1: a wheel of lateral
               radius 10 mm in a groove of 10.25 mm, FZ 10 kN, FX_WS = 0
               (F = 1)
Reference outputs: mbench_conf.ref_out, testbank.ref_out (case 35),
groove_li.ref_out; CONTACT's library gives their printed digits.

railcontact's library refuses D = 4 (-40): docs/cntc.md, "Conformal
contact (D = 4)", gives what its conformal model (WheelRailModel::Cect,
Auto) gave on these cases in a build that routed D = 4 to it (in
crates/cntc-core/src/module1.rs, `WheelRailSettings::model` Cect or Auto
with `auto_conformal_angle_rad` 0 when `digits.discns == 4`, and
config.rs's refusal of D >= 4 dropped).
Needs numpy.
"""
import os
import shutil
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from placement_cases import load  # noqa: E402

SRC = sys.argv[3] if len(sys.argv) > 3 else '/tmp/contact-src'
PROF = os.path.join(SRC, 'testbank', 'profiles')

MBENCH = """\
  1 MODULE
 1203000    C-P-B-T-N-F-S  CONFIG, PVTIME, BOUND, TANG, NORM, FORCE, STRESS
 10{d}2033    V-L-D-C-M-Z-E  VARFRC, FRCLAW, DISCNS, INFLCF, MATER, ZTRACK, EWHEEL
 0001321    H-G-I-A-O-W-R  HEAT, GAUSEI, IESTIM, MATFIL, OUTPUT, FLOW, RETURN
    999     100    30    1     1e-5  MAXGS , MAXIN , MAXNR , MAXOUT, EPS
  2                                             NVF
  -20d    0.200   0.200                         ALPHA, FSTAT, FKIN
  -10d    0.300   0.300                         ALPHA, FSTAT, FKIN
  0.280   0.280   82000.  82000.                POISS 1,2,  GG 1,2
  0.200   0.200   1.000   90d   {sep}       DX,DS, DQREL, A_SEP, D_SEP, D_COMB
   14.0     0    1435.0   0.025                 GAUGHT, GAUGSQ, GAUGWD, CANT
  'MBench_UIC60_v3.prr'  0  1. 0.0              RFNAME, MIRRORY, SCALE, SMOOTH
     0.0    0.0   0.000   0.0   0.0   0.000     DY, DZ, ROLL, VY, VZ, VROLL
  1360.0  -70.0   460.0                         FBDIST, FBPOS, NOMRAD
  'MBench_S1002_v3.prw'  0  1. 0.0              WFNAME, MIRRORY, SCALE, SMOOTH
  0.0  6.25 0.1720  0.000      0.024  0.0       S, Y, FZ, ROLL, YAW, PITCH
 2000. 0.0    0.0   0.0        0.0   -4.3481124 VS,VY,VZ, VROLL,VYAW,VPITCH
"""

TB35 = """\
 1  MODULE
 1203000        C-P-B-T-N-F-S  CONFIG, PVTIME, BOUND, TANG, NORM, FORCE, STRESS
 10{d}2033        V-L-D-C-M-Z-E  VARFRC, FRCLAW, DISCNS, INFLCF, MATER, ZTRACK, EWHEEL
 0001321        H-G-I-A-O-W-R  HEAT, GAUSEI, IESTIM, MATFIL, OUTPUT, FLOW, RETURN
   999   100   30    1    1.0E-06        MAXGS , MAXIN , MAXNR , MAXOUT, EPS
       2                                                  NVF
    -30d      0.2000      0.2000                          ALPHA, FSTAT, FKIN
    -20d      0.3500      0.3500                          ALPHA, FSTAT, FKIN
  0.2800      0.2800      0.8200E+05  0.8200E+05          POISS 1,2,  GG 1,2
  0.400   0.400     1.000    90d   {sep}   40.0     DX, DS, DQREL, A_SEP, D_SEP, D_COMB, D_TURN
  15.8750      0    1435.10   0.000                       GAUGHT, GAUGSQ, GAUGWD, CANT
 'site_b_hr.prr'                   0  1.0   0.0  RFNAME, MIRRORY, SCALE, SMOOTH
   0.00000       0.00000       0.00000                    % DY, DZ, DROLLR
   0.00000       0.00000       0.00000                      VY, VZ, VROLL
   1347.40       0.00000       444.000                    FBDIST, FBPOS, NOMRAD
 'worn_high_mileage.prw'           0  1.0   0.0  WFNAME, MIRRORY, SCALE, SMOOTH
  0.000000      14.850000       1.1700                    % S, Y, Z
 -0.001300       0.005000       0.000000                  % ROLL, YAW, PITCH
  15000.00       0.000000       0.000000                  % VS, VY, VZ
  0.000000       0.000000      -32.10000                  % VROLL, VYAW, FX
"""

GROOVE = """\
  1 MODULE
 1203110    C-P-B-T-N-F-S  CONFIG, PVTIME, BOUND, TANG, NORM, FORCE, STRESS
 00{d}2033    V-L-D-C-M-Z-E  VARFRC, FRCLAW, DISCNS, INFLCF, MATER, ZTRACK, EWHEEL
 0002311    H-G-I-A-O-W-R    HEAT, GAUSEI, IESTIM, MATFIL, OUTPUT, FLOW, RETURN
    999     100    30    1     1e-7  MAXGS , MAXIN , MAXNR , MAXOUT, EPS
  0.300   0.300                                 FSTAT, FKIN
  0.280   0.280   80000.  80000.                POISS 1,2,  GG 1,2
 0.095833 0.250   1.000   90d0  8.0   4.0       DX, DS, DQREL, A_SEP,D_SEP,D_COMB
   -1.0   0.000   0.000   0.000                 GAUGHT, RAILY0, RAILZ0, CANT
  'groove_r1025.prr'  0   1.0  0.0              RFNAME, MIRRORY,SCALE,SMOOTH
     0.0    0.0   0.000   0.0   0.0   0.000     DY,DZ, ROLL, VY,VZ, VROLL
     0.0    0.0   420.0                         FBDIST, FBPOS, NOMRAD
  'circ_r10.prw'     0    1.0  0.0              WFNAME, MIRRORY,SCALE,SMOOTH
   0.0 0.0  10000.  0.000      0.000  0.0       S, Y, FZ, ROLL, YAW, PITCH
 420.0 0.0    0.0   0.0        0.0    0.0       VS,VY,VZ, VROLL,VYAW,FX_WS
"""

# (name, text, DX * DS [mm2])
CASES = [('mbench', MBENCH, '9.0   6.0', 0.2 * 0.2), ('mbench-sep4', MBENCH, '4.0   3.0', 0.2 * 0.2),
         ('tb35', TB35, '30.0   20.0', 0.4 * 0.4), ('tb35-sep6', TB35, '6.0   3.0', 0.4 * 0.4),
         ('tb35-sep3', TB35, '3.0   1.5', 0.4 * 0.4),
         ('groove', GROOVE, '', 0.095833 * 0.25)]
PROFILES = ['MBench_UIC60_v3.prr', 'MBench_S1002_v3.prw', 'site_b_hr.prr',
            'worn_high_mileage.prw', 'groove_r1025.prr', 'circ_r10.prw']


def scratch():
    """A scratch directory holding the profiles, made the working one."""
    work = tempfile.mkdtemp(prefix='conformal-cases-')
    for p in PROFILES:
        shutil.copy(os.path.join(PROF, p), work)
    os.chdir(work)


def main():
    cntc = load(sys.argv[1], sys.argv[2])
    scratch()
    CNTC, _, ierror = cntc.initlibrary(' ', ' ', ' ', 0)
    assert ierror == 0, ierror
    ire = 0
    for name, text, sep, elem in CASES:
        for d in (4, 2):
            ire += 1
            fname = f'{name}_d{d}.inp'
            with open(fname, 'w') as f:
                f.write(text.format(d=d, sep=sep))
            cntc.initialize(ire, 1, ' ', 0)
            r = cntc.readinpfile(ire, CNTC['inp_modul1'], fname)
            ierr = cntc.calculate(ire, -1, 0) if r >= 0 else r
            npatch = cntc.getnumcontactpatches(ire) if ierr >= 0 else 0
            print(f'{name} D={d}: ierror {ierr}, {npatch} patch(es)')
            if npatch < 1:
                continue
            g = cntc.getglobalforces(ire, -1)
            ws = cntc.getwheelsetposition(ire)
            print('  total on rail (track) FX {:.6g} FY {:.6g} FZ {:.6g}; Z_WS {:.6f}'.format(
                g[0], g[1], g[2], ws[2]))
            for icp in range(1, npatch + 1):
                fn, fx, fs, mn = cntc.getcontactforces(ire, icp)
                loc = cntc.getcontactlocation(ire, icp)
                pen = cntc.getpenetration(ire, icp)
                pmax = cntc.getmaximumpressure(ire, icp)
                carea = cntc.getcontactpatchareas(ire, icp)[0]
                mx, my = cntc.getnumelements(ire, icp)
                print(f'  patch {icp}: FN {fn:.6g} FX {fx:.6g} FS {fs:.6g} MN {mn:.6g}')
                print('    YCP_TR {:.4f} ZCP_TR {:.4f} DELTCP_TR {:.4f} YCP_R {:.4f} '
                      'ZCP_R {:.4f} XCP_TR {:.4f}'.format(loc[1], loc[2], loc[3], loc[5],
                                                        loc[6], loc[0]))
                print(f'    approach {pen:.6g} PMAX {pmax:.6g} area {carea:.6g} '
                      f'(~{carea / elem:.0f} elements) grid {mx} x {my}')


main()
