/*
 * contact_addon.h - the C interface of railcontact's CONTACT-compatible
 * library (libcontact_addon.so, installed as contact_addon_linux64.so).
 *
 * The calls, their arguments and the flag codes are those of CONTACT's
 * library (E.A.H. Vollebregt, Vtech CMCC), so that a program written for
 * CONTACT compiles and links against this library unchanged. Conventions:
 *
 *   - every argument is passed by reference: int is 32-bit, double is
 *     IEEE double, arrays are pointers to their first element;
 *   - 2-D fields are 1-D arrays of mx*my values, element (ix, iy) at
 *     index ix + iy*mx (x fastest, Fortran's column-major order);
 *   - strings are const char* with their length in bytes in an int*
 *     (no terminating NUL needed);
 *   - every function returns void; results come back through pointers;
 *   - errors: calls with an ierror argument set it (0 success; > 0 from
 *     cntc_calculate: contact elements on the border of the potential
 *     contact area; < 0 one of the CNTC_err_* codes below). Every error is
 *     also written as one line to standard error ("railcontact-cntc:
 *     ERROR in <call>(ire=.., icp=..): <what to fix>"); getters leave
 *     their outputs untouched on error. A null pointer or a negative
 *     length is CNTC_err_argument, never a crash.
 *
 * Units follow the unit convention chosen with cntc_setflags(CNTC_if_units)
 * (CONTACT's mm, N, N/mm^2, mm/s by default). See docs/cntc.md of the
 * railcontact repository for which calls, flags and methods are
 * supported.
 */
#ifndef RAILCONTACT_CONTACT_ADDON_H
#define RAILCONTACT_CONTACT_ADDON_H

#ifdef __cplusplus
extern "C" {
#endif

/* ---- flag codes (cntc_setflags, cntc_getflags, cntc_setglobalflags) ---- */
enum {
   CNTC_if_units   = 1933,  /* unit convention, value one of CNTC_un_* */
   CNTC_un_cntc    = 1934,  /* CONTACT's: mm, mm/s, N, on body 1 (default) */
   CNTC_un_spck    = 1935,  /* SIMPACK's: m, m/s, N, on body 2 */
   CNTC_un_si      = 1936,  /* SI: m, m/s, N, on body 1 */
   CNTC_un_imper   = 1937,  /* imperial: not supported */

   CNTC_ic_config  = 1967,  /* C1: 0 left rail, 1 right rail */
   CNTC_ic_pvtime  = 1970,  /* P: 0 continue the previous case, 2 start afresh */
   CNTC_ic_bound   = 1971,  /* B: traction bound */
   CNTC_ic_tang    = 1972,  /* T: 0 none, 1 shift, 2 transient rolling, 3 steady rolling */
   CNTC_ic_norm    = 1973,  /* N: module 1 0 position/1 vertical force; module 3 0 approach/1 normal force */
   CNTC_ic_force   = 1974,  /* F: 0 creepages; module 3 1 Fx and eta, 2 Fx and Fy; module 1 1 total force FX_WS (pitch rate found) */
   CNTC_ic_frclaw  = 1976,  /* L (read only) */
   CNTC_ic_discns  = 1977,  /* D: module 1 discretisation */
   CNTC_ic_inflcf  = 1978,  /* C3: influence coefficients */
   CNTC_ic_mater   = 1979,  /* M (read only; set with cntc_setmaterialparameters) */
   CNTC_ic_exrhs   = 1980,  /* E: extra rigid slip */
   CNTC_ic_xflow   = 1981,  /* X: debug output (accepted) */
   CNTC_ic_heat    = 1982,  /* H (read only) */
   CNTC_ic_iestim  = 1983,  /* I: initial estimate */
   CNTC_ic_output  = 1984,  /* O: out-file output (accepted; no out-file is written) */
   CNTC_ic_flow    = 1985,  /* W: flow output (accepted) */
   CNTC_ic_return  = 1986,  /* R: 0-1 solve, 2-3 check only */
   CNTC_ic_matfil  = 1987,  /* A: mat-file (accepted; none is written) */
   CNTC_ic_sens    = 1988,  /* S: 2, 3 compute sensitivities */
   CNTC_ic_ifmeth  = 1989,
   CNTC_ic_ifvari  = 1990,
   CNTC_ic_sbsout  = 1991,
   CNTC_ic_sbsfil  = 1992,
   CNTC_ic_npomax  = 1993,

   CNTC_if_idebug  = 2000,  /* library print level: <0 none, 0 errors, 1 warnings (default), 2 more */
   CNTC_if_licdbg  = 2001,
   CNTC_if_wrtinp  = 2002,
   CNTC_if_openmp  = 2003,
   CNTC_if_timers  = 2004,
   CNTC_if_ncase   = 2005,
   CNTC_if_mode    = 2099   /* railcontact: 0 in process (default), 1 forwarded to a railcontact server (RAILCONTACT_CNTC_SERVER, docs/cntc.md) */
};

/* ---- input file types (cntc_readinpfile) ---- */
enum {
   CNTC_inp_modul1 = 1988,  /* a module 1 input file (its first case) */
   CNTC_inp_spck   = 1990   /* the input file of CONTACT's Simpack user routine */
};

/* ---- field codes (cntc_getfielddata) ---- */
enum {
   CNTC_fld_h = 1, CNTC_fld_mu = 2, CNTC_fld_px = 3, CNTC_fld_py = 4, CNTC_fld_pn = 5,
   CNTC_fld_ux = 7, CNTC_fld_uy = 8, CNTC_fld_un = 9, CNTC_fld_taucrt = 11,
   CNTC_fld_uplsx = 12, CNTC_fld_uplsy = 13, CNTC_fld_sx = 15, CNTC_fld_sy = 16,
   CNTC_fld_temp1 = 20, CNTC_fld_temp2 = 21, CNTC_fld_wx = 22, CNTC_fld_wy = 23
};

/* ---- metadata codes (cntc_setmetadata) ---- */
enum {
   CNTC_mt_tim = 2011, CNTC_mt_xr = 2012, CNTC_mt_yr = 2013, CNTC_mt_xw = 2014,
   CNTC_mt_yw = 2015, CNTC_mt_sw = 2016, CNTC_mt_run = 2021, CNTC_mt_axle = 2022,
   CNTC_mt_side = 2023
};

/* ---- error codes (ierror) ---- */
enum {
   CNTC_err_allow        =  -12,  /* never returned: there is no licence */
   CNTC_err_search       =  -25,  /* contact search failed */
   CNTC_err_ftot         =  -26,  /* total force iteration found no solution */
   CNTC_err_norm         =  -27,  /* normal problem did not converge */
   CNTC_err_tang         =  -28,  /* tangential problem did not converge */
   CNTC_err_tol          =  -29,
   CNTC_err_icp          =  -31,  /* invalid ire/icp, or a call of the other module */
   CNTC_err_profil       =  -32,  /* profile could not be read */
   CNTC_err_frclaw       =  -33,  /* invalid friction parameters */
   CNTC_err_discr        =  -34,  /* invalid discretisation */
   CNTC_err_input        =  -39,  /* an input file (cntc_readinpfile) could not be read or has an error */
   CNTC_err_notsupported =  -40,  /* railcontact: a flag value or method this library does not have */
   CNTC_err_argument     =  -41,  /* railcontact: null pointer or negative length */
   CNTC_err_server       =  -42,  /* railcontact: forwarded, the server could not be reached, refused or went away */
   CNTC_err_other        =  -99,
   CNTC_err_ire          = -101   /* ire outside [1, 999] */
};

/* ---- preparations ---- */
void cntc_initializefirst(int *ifcver, int *ierror, int *ioutput, const char *c_wrkdir,
                          const char *c_outdir, const char *c_expnam, int *len_wrkdir,
                          int *len_outdir, int *len_expnam);
void cntc_initializefirst_new(int *ifcver, int *ierror, int *ioutput, const char *c_wrkdir,
                              const char *c_outdir, const char *c_expnam, int *len_wrkdir,
                              int *len_outdir, int *len_expnam);
void cntc_initialize(int *ire, int *imodul, int *ifcver, int *ierror, const char *c_outdir,
                     int *len_outdir);
void cntc_setfileunits(int *nunits, int *iunits);
void cntc_getmaxnumthreads(int *mxthrd);
void cntc_setglobalflags(int *lenflg, int *params, int *values);
void cntc_readinpfile(int *ire, int *inp_type, const char *c_fname, int *len_fname, int *ierror);

/* ---- configuration (modules 1 and 3) ---- */
void cntc_setflags(int *ire, int *icp, int *lenflg, int *params, int *values);
void cntc_setmetadata(int *ire, int *icp, int *lenmta, int *params, double *values);
void cntc_setsolverflags(int *ire, int *icp, int *gdigit, int *nints, int *iparam, int *nreals,
                         double *rparam);
void cntc_setmaterialparameters(int *ire, int *icp, int *mdigit, int *nparam, double *rparam);
void cntc_settemperaturedata(int *ire, int *icp, int *imeth, int *nparam, double *rparam);
void cntc_settimestep(int *ire, int *icp, double *dt);
void cntc_setreferencevelocity(int *ire, int *icp, double *veloc);
void cntc_setrollingstepsize(int *ire, int *icp, double *chi, double *dq);
void cntc_setfrictionmethod(int *ire, int *icp, int *imeth, int *nparam, double *params);
void cntc_sethertzcontact(int *ire, int *icp, int *ipotcn, int *nparam, double *rparam);
void cntc_setpotcontact(int *ire, int *icp, int *ipotcn, int *nparam, double *rparam);
void cntc_setverticalforce(int *ire, double *fz);
void cntc_setpenetration(int *ire, int *icp, double *pen);
void cntc_setnormalforce(int *ire, int *icp, double *fn);
void cntc_setundeformeddistc(int *ire, int *icp, int *ibase, int *nparam, double *prmudf);
void cntc_setcreepages(int *ire, int *icp, double *vx, double *vy, double *phi);
void cntc_setextrarigidslip(int *ire, int *icp, int *lenarr, double *wx, double *wy);
void cntc_settangentialforces(int *ire, int *icp, double *fx, double *fy);

/* ---- wheel/rail configuration (module 1) ---- */
void cntc_setprofileinputfname(int *ire, const char *c_fname, int *len_fname, int *nints,
                               int *iparam, int *nreals, double *rparam);
void cntc_setprofileinputvalues(int *ire, int *npoint, double *values, int *nints,
                                int *iparam, int *nreals, double *rparam);
void cntc_settrackdimensions(int *ire, int *ztrack, int *nparam, double *rparam);
void cntc_setwheelsetdimensions(int *ire, int *ewheel, int *nparam, double *rparam);
void cntc_setwheelsetposition(int *ire, int *ewheel, int *nparam, double *rparam);
void cntc_setwheelsetvelocity(int *ire, int *ewheel, int *nparam, double *rparam);
void cntc_setwheelsetflexibility(int *ire, int *ewheel, int *nparam, double *rparam);

/* ---- subsurface stresses ---- */
void subs_addblock(int *ire, int *icp, int *iblk, int *isubs, int *nx, int *ny, int *nz,
                   double *xparam, double *yparam, double *zparam);
void subs_calculate(int *ire, int *icp, int *ierror);
void subs_getblocksize(int *ire, int *icp, int *iblk, int *nx, int *ny, int *nz);
void subs_getresults(int *ire, int *icp, int *iblk, int *lenarr, int *ncol, int *icol,
                     double *values);

/* ---- calculation ---- */
void cntc_calculate(int *ire, int *icp, int *ierror);
void cntc_calculate1(int *ire, int *ierror);
void cntc_calculate3(int *ire, int *icp, int *ierror);

/* ---- results ---- */
void cntc_getflags(int *ire, int *icp, int *lenflg, int *params, int *values);
void cntc_getparameters(int *ire, int *icp, int *itask, int *lenarr, double *values);
void cntc_getprofilevalues(int *ire, int *itask, int *nints, int *iparam, int *nreals,
                           double *rparam, int *lenarr, double *values);
void cntc_getprofilevalues_new(int *ire, int *itask, int *nints, int *iparam, int *nreals,
                               double *rparam, int *lenarr, double *values);
void cntc_getwheelsetposition(int *ire, int *lenarr, double *values);
void cntc_getwheelsetvelocity(int *ire, int *lenarr, double *values);
void cntc_getnumcontactpatches(int *ire, int *npatch);
void cntc_getcontactlocation(int *ire, int *icp, int *lenarr, double *values);
void cntc_getreferencevelocity(int *ire, int *icp, double *veloc);
void cntc_gethertzcontact(int *ire, int *icp, int *lenarr, double *values);
void cntc_getnumelements(int *ire, int *icp, int *mx, int *my);
void cntc_getgriddiscretization(int *ire, int *icp, double *dx, double *dy);
void cntc_getpotcontact(int *ire, int *icp, int *lenarr, double *values);
void cntc_getpenetration(int *ire, int *icp, double *pen);
void cntc_getcreepages(int *ire, int *icp, double *vx, double *vy, double *phi);
void cntc_getcontactforces(int *ire, int *icp, double *fn, double *tx, double *ty, double *mz);
void cntc_getglobalforces(int *ire, int *icp, int *lenarr, double *values);
void cntc_getcontactpatchareas(int *ire, int *icp, double *carea, double *harea, double *sarea);
void cntc_getelementdivision(int *ire, int *icp, int *lenarr, int *eldiv);
void cntc_getmaximumpressure(int *ire, int *icp, double *pnmax);
void cntc_getmaximumtraction(int *ire, int *icp, double *ptmax);
void cntc_getmaximumtemperature(int *ire, int *icp, double *t1max, double *t2max);
void cntc_getfielddata(int *ire, int *icp, int *ifld, int *lenarr, double *fld);
void cntc_gettractions(int *ire, int *icp, int *lenarr, double *pn, double *px, double *py);
void cntc_getmicroslip(int *ire, int *icp, int *lenarr, double *sx, double *sy);
void cntc_getdisplacements(int *ire, int *icp, int *lenarr, double *un, double *ux, double *uy);
void cntc_getsensitivities(int *ire, int *icp, int *lenout, int *lenin, double *sens);
void cntc_getcalculationtime(int *ire, int *icp, double *tcpu, double *twall);
void cntc_resetcalculationtime(int *ire, int *icp);

/* ---- finalisation ---- */
void cntc_finalize(int *ire);
void cntc_finalizelast(void);

#ifdef __cplusplus
}
#endif

#endif /* RAILCONTACT_CONTACT_ADDON_H */
