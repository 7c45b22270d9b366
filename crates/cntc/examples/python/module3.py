"""module3.py - module 3 (one contact patch) through CONTACT's library
interface, from Python with ctypes only: the same cases as
examples/c/module3.c, printing the same lines.

Run against railcontact's library (crates/cntc/build-lib.sh puts it in
target/cntc):
    python3 crates/cntc/examples/python/module3.py target/cntc/contact_addon_linux64.so
"""
import ctypes
import sys
from ctypes import byref, c_double, c_int

lib = ctypes.CDLL(sys.argv[1] if len(sys.argv) > 1 else "contact_addon_linux64.so")

# Flag codes (CONTACT's caddon_flags.inc).
IF_UNITS, UN_CNTC, UN_SPCK, UN_SI = 1933, 1934, 1935, 1936
IC_PVTIME, IC_TANG, IC_NORM, IC_FORCE = 1970, 1972, 1973, 1974


def i(v):
    """An int argument, by reference."""
    return byref(c_int(v))


def d(v):
    """A double argument, by reference."""
    return byref(c_double(v))


def ints(v):
    return (c_int * len(v))(*v)


def reals(v):
    return (c_double * len(v))(*v)


def report(tag, ire, icp, ierror):
    fn, fx, fy, mz, pen = (c_double() for _ in range(5))
    lib.cntc_getcontactforces(i(ire), i(icp), byref(fn), byref(fx), byref(fy), byref(mz))
    lib.cntc_getpenetration(i(ire), i(icp), byref(pen))
    print("%s %d %.9e %.9e %.9e %.9e %.9e" % (tag, ierror, fn.value, fx.value, fy.value,
                                               mz.value, pen.value))


def configure(ire, icp, units, tang, norm, gg, mu):
    """Units, T and N digits, P = 2; steel; Coulomb friction mu; EPS 1e-6."""
    lib.cntc_setflags(i(ire), i(icp), i(4), ints([IF_UNITS, IC_TANG, IC_NORM, IC_PVTIME]),
                      ints([units, tang, norm, 2]))
    lib.cntc_setmaterialparameters(i(ire), i(icp), i(0), i(4), reals([0.28, 0.28, gg, gg]))
    lib.cntc_setfrictionmethod(i(ire), i(icp), i(0), i(2), reals([mu, mu]))
    lib.cntc_setsolverflags(i(ire), i(icp), i(0), i(4), ints([80, 200, 5, 1]), i(1),
                            reals([1e-6]))


def calculate(ire, icp):
    ierror = c_int()
    lib.cntc_calculate(i(ire), i(icp), byref(ierror))
    return ierror.value


def main():
    ifcver, ierror = c_int(), c_int()
    lib.cntc_initializefirst(byref(ifcver), byref(ierror), i(0), b" ", b" ", b" ", i(1), i(1),
                             i(1))
    print("ifcver %d ierror %d" % (ifcver.value, ierror.value))
    icp = 1

    # 1: CONTACT's tractcurv curve 1.
    configure(1, icp, UN_CNTC, 3, 1, 82000.0, 0.33)
    lib.cntc_sethertzcontact(i(1), i(icp), i(-2), i(5), reals([48, 44, 0.0008, 0.5, 1.1]))
    lib.cntc_setreferencevelocity(i(1), i(icp), d(10000.0))
    lib.cntc_setnormalforce(i(1), i(icp), d(106700.0))
    for k, cksi in enumerate([0.0004, 0.0024, 0.01]):
        lib.cntc_setcreepages(i(1), i(icp), d(cksi), d(0.0), d(0.0))
        report("curve%d" % k, 1, icp, calculate(1, icp))

    # 2: combined creepage with spin.
    configure(2, icp, UN_CNTC, 3, 1, 82000.0, 0.3)
    lib.cntc_sethertzcontact(i(2), i(icp), i(-1), i(5), reals([40, 40, 0.0005, 0.0011, 1.2]))
    lib.cntc_setreferencevelocity(i(2), i(icp), d(20000.0))
    lib.cntc_setnormalforce(i(2), i(icp), d(50000.0))
    lib.cntc_setcreepages(i(2), i(icp), d(0.0008), d(0.0004), d(-0.0002))
    report("spin", 2, icp, calculate(2, icp))

    # 3: Fx = -0.4 mu Fn prescribed (F = 1).
    configure(3, icp, UN_CNTC, 3, 1, 82000.0, 0.3)
    lib.cntc_setflags(i(3), i(icp), i(1), ints([IC_FORCE]), ints([1]))
    lib.cntc_sethertzcontact(i(3), i(icp), i(-2), i(5), reals([40, 36, 0.0008, 0.6, 1.1]))
    lib.cntc_setreferencevelocity(i(3), i(icp), d(10000.0))
    lib.cntc_setnormalforce(i(3), i(icp), d(80000.0))
    lib.cntc_setcreepages(i(3), i(icp), d(0.0), d(0.0002), d(0.0))
    lib.cntc_settangentialforces(i(3), i(icp), d(-0.4), d(0.0))
    report("force", 3, icp, calculate(3, icp))
    cksi, ceta, cphi = c_double(), c_double(), c_double()
    lib.cntc_getcreepages(i(3), i(icp), byref(cksi), byref(ceta), byref(cphi))
    print("force_cksi %.9e" % cksi.value)

    # 4: Cattaneo's shifts, continuing (P = 0) after the first.
    configure(4, icp, UN_CNTC, 1, 1, 82000.0, 0.3)
    lib.cntc_sethertzcontact(i(4), i(icp), i(-1), i(5), reals([40, 40, 0.001, 0.001, 1.2]))
    lib.cntc_setnormalforce(i(4), i(icp), d(30000.0))
    for k, shift in enumerate([0.0005, 0.0005, -0.001]):
        if k == 1:
            lib.cntc_setflags(i(4), i(icp), i(1), ints([IC_PVTIME]), ints([0]))
        lib.cntc_setcreepages(i(4), i(icp), d(shift), d(0.0), d(0.0))
        report("shift%d" % k, 4, icp, calculate(4, icp))

    # 5: a given grid and its undeformed distance per element, SI units.
    configure(5, icp, UN_SI, 3, 1, 82.0e9, 0.3)
    mx, my = 30, 24
    pot = [mx, my, -7.25e-3, -5.75e-3, 0.5e-3, 0.5e-3]
    lib.cntc_setpotcontact(i(5), i(icp), i(3), i(6), reals(pot))
    h = []
    for iy in range(my):
        for ix in range(mx):
            x, y = pot[2] + ix * pot[4], pot[3] + iy * pot[5]
            h.append(90.0 * x * x + 160.0 * y * y + 0.002 * x)
    lib.cntc_setundeformeddistc(i(5), i(icp), i(9), i(len(h)), reals(h))
    lib.cntc_setreferencevelocity(i(5), i(icp), d(30.0))
    lib.cntc_setnormalforce(i(5), i(icp), d(20000.0))
    lib.cntc_setcreepages(i(5), i(icp), d(0.0006), d(0.0003), d(0.2))
    report("grid_si", 5, icp, calculate(5, icp))

    # 6: SIMPACK's convention.
    configure(6, icp, UN_SPCK, 3, 1, 82.0e9, 0.3)
    lib.cntc_sethertzcontact(i(6), i(icp), i(-1), i(5), reals([40, 40, 0.5, 1.1, 1.2]))
    lib.cntc_setreferencevelocity(i(6), i(icp), d(20.0))
    lib.cntc_setnormalforce(i(6), i(icp), d(50000.0))
    lib.cntc_setcreepages(i(6), i(icp), d(0.001), d(-0.0005), d(0.0))
    report("simpack", 6, icp, calculate(6, icp))

    for ire in range(1, 7):
        lib.cntc_finalize(i(ire))
    lib.cntc_finalizelast()


main()
