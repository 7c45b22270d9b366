/*
 * module1.c - module 1 (a wheel on its rail) through CONTACT's library
 * interface, from C: the Manchester benchmark as CONTACT's
 * python_mbench.py sets it up (S1002 wheel, UIC60 rail 1:40, 10 kN,
 * 2 m/s), the left wheel on the Simpack rail at y = 2 mm and the right
 * wheel on the MiniProf rail at y = 7.5 mm (flange contact).
 *
 * Build and run against railcontact's library (crates/cntc/build-lib.sh):
 *   cc -I crates/cntc/include crates/cntc/examples/c/module1.c \
 *      -L target/cntc -l:contact_addon_linux64.so -Wl,-rpath,target/cntc -o module1
 *   ./module1 crates/solver/profiles
 * Each result is one line: the side, ierror, the number of patches, the
 * total forces on the rail in track coordinates FX, FY, FZ [N], and the
 * first patch's FN, FX, FS [N] and contact angle [rad].
 */
#include <stdio.h>
#include <string.h>
#include "contact_addon.h"

/* Sets profile file dir/name (itype from the extension, mirrored in y
 * when mirror_y is 1, values in mm). */
static void profile(int ire, const char *dir, const char *name, int mirror_y)
{
   char path[1024];
   int len, nints = 3, nreals = 2;
   int iparam[3] = { -1, 0, mirror_y };
   double rparam[2] = { 1.0, 0.0 };
   snprintf(path, sizeof path, "%s/%s", dir, name);
   len = (int) strlen(path);
   cntc_setprofileinputfname(&ire, path, &len, &nints, iparam, &nreals, rparam);
}

static void wheel(int ire, const char *dir, const char *rail, int side, double pos[6],
                  double vel[6], const char *tag)
{
   int icp = -1, nflag = 6, ierror = 0, npatch = 0, one = 1, len24 = 24, len38 = 38;
   int flags[6] = { CNTC_if_units, CNTC_ic_config, CNTC_ic_tang, CNTC_ic_pvtime, CNTC_ic_norm,
                    CNTC_ic_discns };
   int values[6] = { CNTC_un_cntc, side, 3, 2, 1, 2 };
   int mdigit = 0, nmat = 4, lmeth = 0, nfric = 2, ipotcn = -1, npot = 5, ztrack = 3, ntrack = 11;
   int ewheel = 3, ndim = 3, eflex = 1, nflex = 12, epos = 2, npos = 6;
   double mat[4] = { 0.28, 0.28, 82000.0, 82000.0 };
   double fric[2] = { 0.3, 0.3 };
   double fz = 10000.0;
   double pot[5] = { 0.2, 0.2, 1.5707963267948966, 8.0, 4.0 };
   double track[11] = { 14, 0, 1435, 0, 0, 0, 0, 0, 0, 0, 0 };
   double dims[3] = { 1360, -70, 460 };
   double flex[12] = { 0 };
   double g[24] = { 0 }, loc[38] = { 0 };
   double fn = 0, fx = 0, fs = 0, mz = 0;

   cntc_setflags(&ire, &icp, &nflag, flags, values);
   cntc_setmaterialparameters(&ire, &icp, &mdigit, &nmat, mat);
   cntc_setfrictionmethod(&ire, &icp, &lmeth, &nfric, fric);
   cntc_setverticalforce(&ire, &fz);
   cntc_setpotcontact(&ire, &icp, &ipotcn, &npot, pot);
   cntc_settrackdimensions(&ire, &ztrack, &ntrack, track);
   profile(ire, dir, rail, side == 1);
   cntc_setwheelsetdimensions(&ire, &ewheel, &ndim, dims);
   profile(ire, dir, "MBench_S1002_v3.prw", 0);
   cntc_setwheelsetflexibility(&ire, &eflex, &nflex, flex);
   cntc_setwheelsetposition(&ire, &epos, &npos, pos);
   cntc_setwheelsetvelocity(&ire, &epos, &npos, vel);
   cntc_calculate1(&ire, &ierror);
   cntc_getnumcontactpatches(&ire, &npatch);
   cntc_getglobalforces(&ire, &icp, &len24, g);
   cntc_getcontactforces(&ire, &one, &fn, &fx, &fs, &mz);
   cntc_getcontactlocation(&ire, &one, &len38, loc);
   printf("%s %d %d %.9e %.9e %.9e %.9e %.9e %.9e %.9e\n", tag, ierror, npatch, g[0], g[1], g[2],
          fn, fx, fs, loc[3]);
}

int main(int argc, char **argv)
{
   const char *dir = argc > 1 ? argv[1] : ".";
   int ire, ifcver = 0, ierror = 0, imodul = 1, zero = 0;
   double left_pos[6] = { 0, 2.0, 0, -0.0001128, 0.0048, 0 };
   double left_vel[6] = { 2000, 0, 0, 0, 0, -4.3459197 };
   double right_pos[6] = { 0, 7.5, 0, -0.007642, 0.018, 0 };
   double right_vel[6] = { 2000, 0, 0, 0, 0, -4.2575747 };

   for (ire = 1; ire <= 2; ire++) cntc_initialize(&ire, &imodul, &ifcver, &ierror, " ", &zero);
   wheel(1, dir, "MBench_UIC60_v3.prr", 0, left_pos, left_vel, "left");
   wheel(2, dir, "MBench_UIC60_v3.ban", 1, right_pos, right_vel, "right");
   for (ire = 1; ire <= 2; ire++) cntc_finalize(&ire);
   return 0;
}
