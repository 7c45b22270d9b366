! module1.f90 - module 1 (a wheel on its rail) through CONTACT's library
! interface, from Fortran 2003 (ISO_C_BINDING): the cases of
! examples/c/module1.c, printing the same lines.
!
! Build and run against railcontact's library (crates/cntc/build-lib.sh):
!   gfortran crates/cntc/examples/fortran/module1.f90 -L target/cntc \
!      -l:contact_addon_linux64.so -Wl,-rpath,target/cntc -o module1_f
!   ./module1_f crates/solver/profiles
module cntc_module1
   use iso_c_binding, only: c_int, c_double, c_char
   implicit none
   ! The calls used here, each argument by reference (no VALUE).
   interface
      subroutine cntc_initialize(ire, imodul, ifcver, ierror, outdir, len_outdir) bind(c)
         import :: c_int, c_char
         integer(c_int) :: ire, imodul, ifcver, ierror, len_outdir
         character(kind=c_char) :: outdir(*)
      end subroutine
      subroutine cntc_setflags(ire, icp, lenflg, params, values) bind(c)
         import :: c_int
         integer(c_int) :: ire, icp, lenflg, params(*), values(*)
      end subroutine
      subroutine cntc_setmaterialparameters(ire, icp, mdigit, nparam, rparam) bind(c)
         import :: c_int, c_double
         integer(c_int) :: ire, icp, mdigit, nparam
         real(c_double) :: rparam(*)
      end subroutine
      subroutine cntc_setfrictionmethod(ire, icp, imeth, nparam, params) bind(c)
         import :: c_int, c_double
         integer(c_int) :: ire, icp, imeth, nparam
         real(c_double) :: params(*)
      end subroutine
      subroutine cntc_setverticalforce(ire, fz) bind(c)
         import :: c_int, c_double
         integer(c_int) :: ire
         real(c_double) :: fz
      end subroutine
      subroutine cntc_setpotcontact(ire, icp, ipotcn, nparam, params) bind(c)
         import :: c_int, c_double
         integer(c_int) :: ire, icp, ipotcn, nparam
         real(c_double) :: params(*)
      end subroutine
      subroutine cntc_settrackdimensions(ire, ztrack, nparam, params) bind(c)
         import :: c_int, c_double
         integer(c_int) :: ire, ztrack, nparam
         real(c_double) :: params(*)
      end subroutine
      subroutine cntc_setprofileinputfname(ire, fname, len_fname, nints, iparam, nreals, rparam) bind(c)
         import :: c_int, c_double, c_char
         integer(c_int) :: ire, len_fname, nints, iparam(*), nreals
         character(kind=c_char) :: fname(*)
         real(c_double) :: rparam(*)
      end subroutine
      subroutine cntc_setwheelsetdimensions(ire, ewheel, nparam, params) bind(c)
         import :: c_int, c_double
         integer(c_int) :: ire, ewheel, nparam
         real(c_double) :: params(*)
      end subroutine
      subroutine cntc_setwheelsetflexibility(ire, ewheel, nparam, params) bind(c)
         import :: c_int, c_double
         integer(c_int) :: ire, ewheel, nparam
         real(c_double) :: params(*)
      end subroutine
      subroutine cntc_setwheelsetposition(ire, ewheel, nparam, params) bind(c)
         import :: c_int, c_double
         integer(c_int) :: ire, ewheel, nparam
         real(c_double) :: params(*)
      end subroutine
      subroutine cntc_setwheelsetvelocity(ire, ewheel, nparam, params) bind(c)
         import :: c_int, c_double
         integer(c_int) :: ire, ewheel, nparam
         real(c_double) :: params(*)
      end subroutine
      subroutine cntc_calculate1(ire, ierror) bind(c)
         import :: c_int
         integer(c_int) :: ire, ierror
      end subroutine
      subroutine cntc_getnumcontactpatches(ire, npatch) bind(c)
         import :: c_int
         integer(c_int) :: ire, npatch
      end subroutine
      subroutine cntc_getglobalforces(ire, icp, lenarr, values) bind(c)
         import :: c_int, c_double
         integer(c_int) :: ire, icp, lenarr
         real(c_double) :: values(*)
      end subroutine
      subroutine cntc_getcontactforces(ire, icp, fn, fx, fs, mz) bind(c)
         import :: c_int, c_double
         integer(c_int) :: ire, icp
         real(c_double) :: fn, fx, fs, mz
      end subroutine
      subroutine cntc_getcontactlocation(ire, icp, lenarr, values) bind(c)
         import :: c_int, c_double
         integer(c_int) :: ire, icp, lenarr
         real(c_double) :: values(*)
      end subroutine
      subroutine cntc_finalize(ire) bind(c)
         import :: c_int
         integer(c_int) :: ire
      end subroutine
   end interface
   integer(c_int), parameter :: CNTC_if_units = 1933, CNTC_un_cntc = 1934, CNTC_ic_config = 1967, &
      CNTC_ic_pvtime = 1970, CNTC_ic_tang = 1972, CNTC_ic_norm = 1973, CNTC_ic_discns = 1977
contains
   subroutine profile(ire, dir, name, mirror_y)
      integer(c_int), intent(in) :: ire, mirror_y
      character(len=*), intent(in) :: dir, name
      integer(c_int) :: r, n, ni, nr, iparam(3)
      real(c_double) :: rparam(2)
      character(len=1024) :: path
      r = ire
      path = trim(dir) // '/' // name
      n = len_trim(path); ni = 3; nr = 2
      iparam = [-1, 0, mirror_y]; rparam = [1d0, 0d0]
      call cntc_setprofileinputfname(r, path, n, ni, iparam, nr, rparam)
   end subroutine

   subroutine wheel(ire, dir, rail, side, pos, vel, tag)
      integer(c_int), intent(in) :: ire, side
      character(len=*), intent(in) :: dir, rail, tag
      real(c_double), intent(in) :: pos(6), vel(6)
      integer(c_int) :: r, icp, one, n, ierror, npatch, flags(6), vals(6), m, l, ip, z, e
      real(c_double) :: mat(4), fric(2), fz, pot(5), track(11), dims(3), flex(12), p(6), v(6)
      real(c_double) :: g(24), loc(38), fn, fx, fs, mz
      r = ire; icp = -1; one = 1
      flags = [CNTC_if_units, CNTC_ic_config, CNTC_ic_tang, CNTC_ic_pvtime, CNTC_ic_norm, CNTC_ic_discns]
      vals = [CNTC_un_cntc, side, 3, 2, 1, 2]
      n = 6
      call cntc_setflags(r, icp, n, flags, vals)
      m = 0; n = 4; mat = [0.28d0, 0.28d0, 82000d0, 82000d0]
      call cntc_setmaterialparameters(r, icp, m, n, mat)
      l = 0; n = 2; fric = [0.3d0, 0.3d0]
      call cntc_setfrictionmethod(r, icp, l, n, fric)
      fz = 10000
      call cntc_setverticalforce(r, fz)
      ip = -1; n = 5; pot = [0.2d0, 0.2d0, 1.5707963267948966d0, 8d0, 4d0]
      call cntc_setpotcontact(r, icp, ip, n, pot)
      z = 3; n = 11; track = 0; track(1) = 14; track(3) = 1435
      call cntc_settrackdimensions(r, z, n, track)
      if (side == 1) then
         call profile(r, dir, rail, 1)
      else
         call profile(r, dir, rail, 0)
      end if
      e = 3; n = 3; dims = [1360d0, -70d0, 460d0]
      call cntc_setwheelsetdimensions(r, e, n, dims)
      call profile(r, dir, 'MBench_S1002_v3.prw', 0)
      e = 1; n = 12; flex = 0
      call cntc_setwheelsetflexibility(r, e, n, flex)
      e = 2; n = 6; p = pos; v = vel
      call cntc_setwheelsetposition(r, e, n, p)
      call cntc_setwheelsetvelocity(r, e, n, v)
      call cntc_calculate1(r, ierror)
      call cntc_getnumcontactpatches(r, npatch)
      n = 24
      call cntc_getglobalforces(r, icp, n, g)
      call cntc_getcontactforces(r, one, fn, fx, fs, mz)
      n = 38
      call cntc_getcontactlocation(r, one, n, loc)
      write(*, '(a,2(1x,i0),7(1x,es16.9e2))') tag, ierror, npatch, g(1), g(2), g(3), fn, fx, fs, loc(4)
   end subroutine
end module cntc_module1

program module1
   use cntc_module1
   implicit none
   integer(c_int) :: ire, imodul, ifcver, ierror, zero
   character(len=1024) :: dir
   if (command_argument_count() >= 1) then
      call get_command_argument(1, dir)
   else
      dir = '.'
   end if
   imodul = 1; zero = 0
   do ire = 1, 2
      call cntc_initialize(ire, imodul, ifcver, ierror, ' ', zero)
   end do
   call wheel(1, trim(dir), 'MBench_UIC60_v3.prr', 0, [0d0, 2d0, 0d0, -0.0001128d0, 0.0048d0, 0d0], &
              [2000d0, 0d0, 0d0, 0d0, 0d0, -4.3459197d0], 'left')
   call wheel(2, trim(dir), 'MBench_UIC60_v3.ban', 1, [0d0, 7.5d0, 0d0, -0.007642d0, 0.018d0, 0d0], &
              [2000d0, 0d0, 0d0, 0d0, 0d0, -4.2575747d0], 'right')
   do ire = 1, 2
      call cntc_finalize(ire)
   end do
end program module1
