/*
 * module3.c - module 3 (one contact patch) through CONTACT's library
 * interface, from C: a creep-force curve, combined creepage with spin, a
 * prescribed longitudinal force, Cattaneo's shifts, a given grid with its
 * undeformed distance in SI units, and SIMPACK's unit convention.
 *
 * Build and run against railcontact's library (crates/cntc/build-lib.sh
 * puts it in target/cntc):
 *   cc -I crates/cntc/include crates/cntc/examples/c/module3.c \
 *      -L target/cntc -l:contact_addon_linux64.so -Wl,-rpath,target/cntc -o module3
 *   ./module3
 * Each result is one line: a tag, ierror, FN, FX, FY, MZ, PEN.
 */
#include <stdio.h>
#include <string.h>
#include "contact_addon.h"

static void report(const char *tag, int ire, int icp, int ierror)
{
   double fn = 0, fx = 0, fy = 0, mz = 0, pen = 0;
   cntc_getcontactforces(&ire, &icp, &fn, &fx, &fy, &mz);
   cntc_getpenetration(&ire, &icp, &pen);
   printf("%s %d %.9e %.9e %.9e %.9e %.9e\n", tag, ierror, fn, fx, fy, mz, pen);
}

/* Units, T and N digits, P = 2; steel; Coulomb friction mu; EPS 1e-6. */
static void configure(int ire, int icp, int units, int tang, int norm, double gg, double mu)
{
   int flags[4] = { CNTC_if_units, CNTC_ic_tang, CNTC_ic_norm, CNTC_ic_pvtime };
   int values[4] = { units, tang, norm, 2 };
   int nflag = 4, mdigit = 0, nmat = 4, lmeth = 0, nfric = 2, gdigit = 0, nints = 4, nreals = 1;
   double mat[4] = { 0.28, 0.28, gg, gg };
   double fric[2] = { mu, mu };
   int iparam[4] = { 80, 200, 5, 1 };
   double eps = 1e-6;
   cntc_setflags(&ire, &icp, &nflag, flags, values);
   cntc_setmaterialparameters(&ire, &icp, &mdigit, &nmat, mat);
   cntc_setfrictionmethod(&ire, &icp, &lmeth, &nfric, fric);
   cntc_setsolverflags(&ire, &icp, &gdigit, &nints, iparam, &nreals, &eps);
}

int main(void)
{
   int ifcver = 0, ierror = 0, ioutput = 0, one = 1, five = 5, six = 6;
   const char *blank = " ";
   int ire, icp = 1, ipotcn, k;
   char tag[16];

   cntc_initializefirst(&ifcver, &ierror, &ioutput, blank, blank, blank, &one, &one, &one);
   printf("ifcver %d ierror %d\n", ifcver, ierror);

   /* 1: CONTACT's tractcurv curve 1: an ellipse a/b = 0.5, 106.7 kN, mu 0.33. */
   {
      double hz[5] = { 48, 44, 0.0008, 0.5, 1.1 };
      double veloc = 10000.0, fn = 106700.0, zero = 0.0;
      double cksi[3] = { 0.0004, 0.0024, 0.01 };
      ire = 1;
      configure(ire, icp, CNTC_un_cntc, 3, 1, 82000.0, 0.33);
      ipotcn = -2;
      cntc_sethertzcontact(&ire, &icp, &ipotcn, &five, hz);
      cntc_setreferencevelocity(&ire, &icp, &veloc);
      cntc_setnormalforce(&ire, &icp, &fn);
      for (k = 0; k < 3; k++) {
         cntc_setcreepages(&ire, &icp, &cksi[k], &zero, &zero);
         cntc_calculate(&ire, &icp, &ierror);
         snprintf(tag, sizeof tag, "curve%d", k);
         report(tag, ire, icp, ierror);
      }
   }

   /* 2: combined creepage with spin on the ellipse A = 0.0005, B = 0.0011 1/mm. */
   {
      double hz[5] = { 40, 40, 0.0005, 0.0011, 1.2 };
      double veloc = 20000.0, fn = 50000.0, vx = 0.0008, vy = 0.0004, phi = -0.0002;
      ire = 2;
      configure(ire, icp, CNTC_un_cntc, 3, 1, 82000.0, 0.3);
      ipotcn = -1;
      cntc_sethertzcontact(&ire, &icp, &ipotcn, &five, hz);
      cntc_setreferencevelocity(&ire, &icp, &veloc);
      cntc_setnormalforce(&ire, &icp, &fn);
      cntc_setcreepages(&ire, &icp, &vx, &vy, &phi);
      cntc_calculate(&ire, &icp, &ierror);
      report("spin", ire, icp, ierror);
   }

   /* 3: Fx = -0.4 mu Fn prescribed (F = 1) with a lateral creepage. */
   {
      double hz[5] = { 40, 36, 0.0008, 0.6, 1.1 };
      double veloc = 10000.0, fn = 80000.0, zero = 0.0, vy = 0.0002, fxrel = -0.4;
      int flag = CNTC_ic_force, value = 1;
      double cksi = 0, ceta = 0, cphi = 0;
      ire = 3;
      configure(ire, icp, CNTC_un_cntc, 3, 1, 82000.0, 0.3);
      cntc_setflags(&ire, &icp, &one, &flag, &value);
      ipotcn = -2;
      cntc_sethertzcontact(&ire, &icp, &ipotcn, &five, hz);
      cntc_setreferencevelocity(&ire, &icp, &veloc);
      cntc_setnormalforce(&ire, &icp, &fn);
      cntc_setcreepages(&ire, &icp, &zero, &vy, &zero);
      cntc_settangentialforces(&ire, &icp, &fxrel, &zero);
      cntc_calculate(&ire, &icp, &ierror);
      report("force", ire, icp, ierror);
      cntc_getcreepages(&ire, &icp, &cksi, &ceta, &cphi);
      printf("force_cksi %.9e\n", cksi);
   }

   /* 4: Cattaneo: three shifts of a circle at 30 kN, continuing (P = 0). */
   {
      double hz[5] = { 40, 40, 0.001, 0.001, 1.2 };
      double fn = 30000.0, zero = 0.0;
      double shift[3] = { 0.0005, 0.0005, -0.001 };
      int flag = CNTC_ic_pvtime, value = 0;
      ire = 4;
      configure(ire, icp, CNTC_un_cntc, 1, 1, 82000.0, 0.3);
      ipotcn = -1;
      cntc_sethertzcontact(&ire, &icp, &ipotcn, &five, hz);
      cntc_setnormalforce(&ire, &icp, &fn);
      for (k = 0; k < 3; k++) {
         if (k == 1) cntc_setflags(&ire, &icp, &one, &flag, &value);
         cntc_setcreepages(&ire, &icp, &shift[k], &zero, &zero);
         cntc_calculate(&ire, &icp, &ierror);
         snprintf(tag, sizeof tag, "shift%d", k);
         report(tag, ire, icp, ierror);
      }
   }

   /* 5: a given grid (IPOTCN = 3) and its undeformed distance per element
    *    (IBASE = 9), SI units, steady rolling with spin. */
   {
      enum { MX = 30, MY = 24 };
      double pot[6] = { MX, MY, -7.25e-3, -5.75e-3, 0.5e-3, 0.5e-3 };
      double h[MX * MY];
      double veloc = 30.0, fn = 20000.0, vx = 0.0006, vy = 0.0003, phi = 0.2;
      int ix, iy, ibase = 9, npot = MX * MY;
      for (iy = 0; iy < MY; iy++)
         for (ix = 0; ix < MX; ix++) {
            double x = pot[2] + ix * pot[4], y = pot[3] + iy * pot[5];
            h[ix + iy * MX] = 90.0 * x * x + 160.0 * y * y + 0.002 * x;
         }
      ire = 5;
      configure(ire, icp, CNTC_un_si, 3, 1, 82.0e9, 0.3);
      ipotcn = 3;
      cntc_setpotcontact(&ire, &icp, &ipotcn, &six, pot);
      cntc_setundeformeddistc(&ire, &icp, &ibase, &npot, h);
      cntc_setreferencevelocity(&ire, &icp, &veloc);
      cntc_setnormalforce(&ire, &icp, &fn);
      cntc_setcreepages(&ire, &icp, &vx, &vy, &phi);
      cntc_calculate(&ire, &icp, &ierror);
      report("grid_si", ire, icp, ierror);
   }

   /* 6: SIMPACK's convention (SI, forces on body 2). */
   {
      double hz[5] = { 40, 40, 0.5, 1.1, 1.2 };
      double veloc = 20.0, fn = 50000.0, vx = 0.001, vy = -0.0005, zero = 0.0;
      ire = 6;
      configure(ire, icp, CNTC_un_spck, 3, 1, 82.0e9, 0.3);
      ipotcn = -1;
      cntc_sethertzcontact(&ire, &icp, &ipotcn, &five, hz);
      cntc_setreferencevelocity(&ire, &icp, &veloc);
      cntc_setnormalforce(&ire, &icp, &fn);
      cntc_setcreepages(&ire, &icp, &vx, &vy, &zero);
      cntc_calculate(&ire, &icp, &ierror);
      report("simpack", ire, icp, ierror);
   }

   for (ire = 1; ire <= 6; ire++) cntc_finalize(&ire);
   cntc_finalizelast();
   return 0;
}
