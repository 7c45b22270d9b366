"""fastrip_cases.py PYTHON_INTFC LIBRARY [OUTDIR]
   fastrip_cases.py --compare DIR_A DIR_B

CONTACT's M = 5 (modified FaStrip) through CONTACT's own Python interface
(`python_intfc`, ctypes) on the library LIBRARY (CONTACT's
contact_addon_linux64.so or railcontact's, built with
crates/cntc/build-lib.sh): module 3, the Hertzian ellipse of CONTACT's
examples/fastsim.inp (AA, BB = 8, 4 mm given, IPOTCN = -3, 44 x 44
elements over 1.1 times it, FN = 82 kN, G = 82000 N/mm^2, nu = 0.28,
VELOC 30 m/s, Coulomb 0.3), steady rolling (T = 3) with longitudinal,
lateral and spin creepages and combinations, with B = 2 (elliptical
bound), B = 3 (parabolic), B = 0 (the normal problem's pressure), with
the slope reduction K0_MF, ALFAMF, BETAMF = 1, 1, 1, then 0.54, 0.02,
0.62 and 0.7, 0.3, 0.8, rolling along -x (CHI = 180 degrees), a falling
friction law (L = 4), examples/fastsim.inp case 7's 220 x 220 grid, and
the same in SI units (CNTC_un_spck) for one case. Prints per case FN, FX,
FY, MZ (CONTACT's units, N and N mm), the contact, adhesion and slip areas
[mm^2], the element counts of cntc_getelementdivision, K_EFF and 17
digits; with OUTDIR it also saves each case's PN, PX, PY, SX, SY
(cntc_gettractions, cntc_getmicroslip) as OUTDIR/<case>.npz.

--compare prints, per case saved in both folders, the largest difference
of PX, PY over the largest |PX|, |PY| and of SX, SY over the largest
|SX|, |SY|, and whether the element divisions are equal.

crates/cntc/tests/fastsim.rs quotes CONTACT's numbers. Needs numpy.
"""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)


def compare(dir_a, dir_b):
    import numpy as np
    for name in sorted(os.listdir(dir_a)):
        if not name.endswith('.npz') or not os.path.exists(os.path.join(dir_b, name)):
            continue
        a, b = np.load(os.path.join(dir_a, name)), np.load(os.path.join(dir_b, name))

        def rel(keys):
            scale = max(np.abs(a[k]).max() for k in keys)
            diff = max(np.abs(a[k] - b[k]).max() for k in keys)
            return diff / scale if scale > 0 else diff
        same = bool((a['el'] == b['el']).all())
        print('%-28s p %.3g  s %.3g  eldiv equal %s  (elements differing %d)' %
              (name[:-4], rel(['px', 'py']), rel(['sx', 'sy']), same, int((a['el'] != b['el']).sum())))


if len(sys.argv) >= 2 and sys.argv[1] == '--compare':
    compare(sys.argv[2], sys.argv[3])
    sys.exit(0)

from placement_cases import load  # noqa: E402
import numpy as np  # noqa: E402
from ctypes import c_int  # noqa: E402

cntc = load(sys.argv[1], sys.argv[2])
OUT = sys.argv[3] if len(sys.argv) > 3 else None
CNTC, _, ierror = cntc.initlibrary(' ', ' ', ' ', 0)


def setflags(ire, icp, pairs):
    cntc.setflags(ire, icp, np.array([CNTC[k] for k, _ in pairs], dtype=c_int),
                  np.array([v for _, v in pairs], dtype=c_int))


def case(tag, ire, creep, bound=2, red=(1.0, 1.0, 1.0), chi=0.0, mx=44, fric=(0, [0.3, 0.3]),
         si=False):
    cntc.initialize(ire, 3)
    icp = 1
    units = CNTC['un_spck'] if si else CNTC['un_cntc']
    setflags(ire, icp, [('if_units', units), ('ic_tang', 3), ('ic_norm', 1), ('ic_pvtime', 2)])
    g = 82e9 if si else 82000.0
    cntc.setmaterialparameters(ire, icp, 5, [0.28, 0.28, g, g] + list(red))
    setflags(ire, icp, [('ic_bound', bound)])
    mm = 1e-3 if si else 1.0
    cntc.sethertzcontact(ire, icp, -3, [mx, mx, 8.0 * mm, 4.0 * mm, 1.1])
    cntc.setreferencevelocity(ire, icp, 30.0 if si else 30000.0)
    cntc.setrollingstepsize(ire, icp, chi, 0.4 * mm)
    cntc.setnormalforce(ire, icp, 82000.0)
    cntc.setfrictionmethod(ire, icp, fric[0], fric[1])
    cntc.setcreepages(ire, icp, creep[0], creep[1], creep[2] / mm)
    e = cntc.calculate(ire, icp, 0)
    fn, fx, fy, mz = cntc.getcontactforces(ire, icp)
    ca, ha, sa = cntc.getcontactpatchareas(ire, icp)[:3]
    par = cntc.getparameters(ire, icp, 2)
    el = np.asarray(cntc.getelementdivision(ire, icp))
    pn, px, py = cntc.gettractions(ire, icp)
    sx, sy = cntc.getmicroslip(ire, icp)[:2]
    if si:  # report in CONTACT's units
        mz, ca, ha, sa = mz * 1e3, ca * 1e6, ha * 1e6, sa * 1e6
    print('%-28s creep %-24s ierr %d FN %.17g FX %.17g FY %.17g MZ %.17g areas %.17g %.17g %.17g '
          'nadh %d nslip %d keff %.17g' %
          (tag, creep, e, fn, fx, fy, mz, ca, ha, sa, int((el == 1).sum()), int((el == 2).sum()),
           par['k_eff']), flush=True)
    if OUT:
        os.makedirs(OUT, exist_ok=True)
        np.savez(os.path.join(OUT, tag + '.npz'), pn=pn, px=px, py=py, sx=sx, sy=sy, el=el)


creeps = [('case4', (0.0, -0.000625, 0.000625)),
          ('xi-tiny', (1e-6, 0.0, 0.0)), ('xi-small', (0.0002, 0.0, 0.0)),
          ('xi', (0.001, 0.0, 0.0)), ('xi-large', (0.005, 0.0, 0.0)), ('xi-full', (0.05, 0.0, 0.0)),
          ('eta-tiny', (0.0, 1e-6, 0.0)), ('eta', (0.0, 0.0005, 0.0)), ('eta-neg', (0.0, -0.002, 0.0)),
          ('phi', (0.0, 0.0, 0.0003)), ('phi-neg', (0.0, 0.0, -0.001)), ('phi-large', (0.0, 0.0, 0.004)),
          ('mixed', (0.0005, 0.0008, 0.0003)), ('mixed2', (0.002, -0.001, -0.0006))]
ire = 0
for red_tag, red in [('', (1.0, 1.0, 1.0)), ('-red1', (0.54, 0.02, 0.62)), ('-red2', (0.7, 0.3, 0.8))]:
    for tag, c in creeps:
        ire += 1
        case(tag + red_tag, ire, c, red=red)
for tag, c in [('case4', (0.0, -0.000625, 0.000625)), ('xi', (0.001, 0.0, 0.0)),
               ('mixed', (0.0005, 0.0008, 0.0003))]:
    ire += 1
    case(tag + '-b3', ire, c, bound=3)
    ire += 1
    case(tag + '-b0', ire, c, bound=0)
for tag, c in [('case3-back', (0.0, -0.000625, -0.000625)), ('xi-back', (-0.001, 0.0, 0.0)),
               ('mixed-back', (-0.0005, 0.0008, -0.0003))]:
    ire += 1
    case(tag, ire, c, chi=np.pi)
ire += 1
case('mixed-l4', ire, (0.0005, 0.0008, 0.0003), red=(0.54, 0.02, 0.62),
     fric=(4, [0.1368, 0.2232, 990.0, 0.0, 0.0, 0.003, 1.0]))
ire += 1
case('case7', ire, (0.0, -0.000625, 0.000625), mx=220)
ire += 1
case('mixed-si', ire, (0.0005, 0.0008, 0.0003), red=(0.7, 0.3, 0.8), si=True)
