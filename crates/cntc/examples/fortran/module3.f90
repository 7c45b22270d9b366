! module3.f90 - module 3 (one contact patch) through CONTACT's library
! interface, from Fortran 2003 (ISO_C_BINDING): the same cases as
! examples/c/module3.c, printing the same lines.
!
! Build and run against railcontact's library (crates/cntc/build-lib.sh
! puts it in target/cntc):
!   gfortran crates/cntc/examples/fortran/module3.f90 -L target/cntc \
!      -l:contact_addon_linux64.so -Wl,-rpath,target/cntc -o module3_f
!   ./module3_f
module cntc_interface
   use iso_c_binding, only: c_int, c_double, c_char
   implicit none
   ! The calls used here, each argument by reference (no VALUE), as the
   ! library's C header declares them.
   interface
      subroutine cntc_initializefirst(ifcver, ierror, ioutput, wrkdir, outdir, expnam, &
                                      len_wrkdir, len_outdir, len_expnam) bind(c)
         import :: c_int, c_char
         integer(c_int) :: ifcver, ierror, ioutput, len_wrkdir, len_outdir, len_expnam
         character(kind=c_char) :: wrkdir(*), outdir(*), expnam(*)
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
      subroutine cntc_setsolverflags(ire, icp, gdigit, nints, iparam, nreals, rparam) bind(c)
         import :: c_int, c_double
         integer(c_int) :: ire, icp, gdigit, nints, iparam(*), nreals
         real(c_double) :: rparam(*)
      end subroutine
      subroutine cntc_sethertzcontact(ire, icp, ipotcn, nparam, params) bind(c)
         import :: c_int, c_double
         integer(c_int) :: ire, icp, ipotcn, nparam
         real(c_double) :: params(*)
      end subroutine
      subroutine cntc_setpotcontact(ire, icp, ipotcn, nparam, params) bind(c)
         import :: c_int, c_double
         integer(c_int) :: ire, icp, ipotcn, nparam
         real(c_double) :: params(*)
      end subroutine
      subroutine cntc_setundeformeddistc(ire, icp, ibase, nparam, prmudf) bind(c)
         import :: c_int, c_double
         integer(c_int) :: ire, icp, ibase, nparam
         real(c_double) :: prmudf(*)
      end subroutine
      subroutine cntc_setreferencevelocity(ire, icp, veloc) bind(c)
         import :: c_int, c_double
         integer(c_int) :: ire, icp
         real(c_double) :: veloc
      end subroutine
      subroutine cntc_setnormalforce(ire, icp, fn) bind(c)
         import :: c_int, c_double
         integer(c_int) :: ire, icp
         real(c_double) :: fn
      end subroutine
      subroutine cntc_setcreepages(ire, icp, vx, vy, phi) bind(c)
         import :: c_int, c_double
         integer(c_int) :: ire, icp
         real(c_double) :: vx, vy, phi
      end subroutine
      subroutine cntc_settangentialforces(ire, icp, fx, fy) bind(c)
         import :: c_int, c_double
         integer(c_int) :: ire, icp
         real(c_double) :: fx, fy
      end subroutine
      subroutine cntc_calculate(ire, icp, ierror) bind(c)
         import :: c_int
         integer(c_int) :: ire, icp, ierror
      end subroutine
      subroutine cntc_getcontactforces(ire, icp, fn, fx, fy, mz) bind(c)
         import :: c_int, c_double
         integer(c_int) :: ire, icp
         real(c_double) :: fn, fx, fy, mz
      end subroutine
      subroutine cntc_getpenetration(ire, icp, pen) bind(c)
         import :: c_int, c_double
         integer(c_int) :: ire, icp
         real(c_double) :: pen
      end subroutine
      subroutine cntc_getcreepages(ire, icp, vx, vy, phi) bind(c)
         import :: c_int, c_double
         integer(c_int) :: ire, icp
         real(c_double) :: vx, vy, phi
      end subroutine
      subroutine cntc_finalize(ire) bind(c)
         import :: c_int
         integer(c_int) :: ire
      end subroutine
      subroutine cntc_finalizelast() bind(c)
      end subroutine
   end interface
   ! Flag codes (CONTACT's caddon_flags.inc).
   integer(c_int), parameter :: CNTC_if_units = 1933, CNTC_un_cntc = 1934, CNTC_un_spck = 1935, &
      CNTC_un_si = 1936, CNTC_ic_pvtime = 1970, CNTC_ic_tang = 1972, CNTC_ic_norm = 1973, &
      CNTC_ic_force = 1974
contains
   subroutine report(tag, ire, icp, ierror)
      character(len=*), intent(in) :: tag
      integer(c_int), intent(in) :: ire, icp, ierror
      integer(c_int) :: r, c
      real(c_double) :: fn, fx, fy, mz, pen
      r = ire; c = icp
      fn = 0; fx = 0; fy = 0; mz = 0; pen = 0
      call cntc_getcontactforces(r, c, fn, fx, fy, mz)
      call cntc_getpenetration(r, c, pen)
      write(*, '(a,1x,i0,5(1x,es16.9e2))') tag, ierror, fn, fx, fy, mz, pen
   end subroutine

   subroutine configure(ire, icp, units, tang, norm, gg, mu)
      integer(c_int), intent(in) :: ire, icp, units, tang, norm
      real(c_double), intent(in) :: gg, mu
      integer(c_int) :: r, c, n, m, l, g, ni, nr, flags(4), vals(4), iparam(4)
      real(c_double) :: mat(4), fric(2), eps(1)
      r = ire; c = icp
      flags = [CNTC_if_units, CNTC_ic_tang, CNTC_ic_norm, CNTC_ic_pvtime]
      vals = [units, tang, norm, 2]
      n = 4
      call cntc_setflags(r, c, n, flags, vals)
      m = 0; n = 4; mat = [0.28d0, 0.28d0, gg, gg]
      call cntc_setmaterialparameters(r, c, m, n, mat)
      l = 0; n = 2; fric = [mu, mu]
      call cntc_setfrictionmethod(r, c, l, n, fric)
      g = 0; ni = 4; nr = 1; iparam = [80, 200, 5, 1]; eps = [1d-6]
      call cntc_setsolverflags(r, c, g, ni, iparam, nr, eps)
   end subroutine
end module cntc_interface

program module3
   use cntc_interface
   implicit none
   integer(c_int) :: ifcver, ierror, ioutput, one, five, six, ire, icp, ipotcn, k, ix, iy
   integer(c_int) :: flag, val, ibase, npot
   real(c_double) :: hz(5), veloc, fn, zero, vx, vy, phi, cksi(3), shift(3), fxrel, pot(6)
   real(c_double) :: rksi, reta, rphi, x, y
   real(c_double), allocatable :: h(:)
   character(len=16) :: tag

   ifcver = 0; ierror = 0; ioutput = 0; one = 1; five = 5; six = 6; icp = 1; zero = 0
   call cntc_initializefirst(ifcver, ierror, ioutput, ' ', ' ', ' ', one, one, one)
   write(*, '(a,1x,i0,1x,a,1x,i0)') 'ifcver', ifcver, 'ierror', ierror

   ! 1: CONTACT's tractcurv curve 1.
   ire = 1
   call configure(ire, icp, CNTC_un_cntc, 3, 1, 82000d0, 0.33d0)
   hz = [48d0, 44d0, 0.0008d0, 0.5d0, 1.1d0]; ipotcn = -2
   call cntc_sethertzcontact(ire, icp, ipotcn, five, hz)
   veloc = 10000; fn = 106700
   call cntc_setreferencevelocity(ire, icp, veloc)
   call cntc_setnormalforce(ire, icp, fn)
   cksi = [0.0004d0, 0.0024d0, 0.01d0]
   do k = 1, 3
      call cntc_setcreepages(ire, icp, cksi(k), zero, zero)
      call cntc_calculate(ire, icp, ierror)
      write(tag, '(a,i0)') 'curve', k - 1
      call report(trim(tag), ire, icp, ierror)
   end do

   ! 2: combined creepage with spin.
   ire = 2
   call configure(ire, icp, CNTC_un_cntc, 3, 1, 82000d0, 0.3d0)
   hz = [40d0, 40d0, 0.0005d0, 0.0011d0, 1.2d0]; ipotcn = -1
   call cntc_sethertzcontact(ire, icp, ipotcn, five, hz)
   veloc = 20000; fn = 50000; vx = 0.0008d0; vy = 0.0004d0; phi = -0.0002d0
   call cntc_setreferencevelocity(ire, icp, veloc)
   call cntc_setnormalforce(ire, icp, fn)
   call cntc_setcreepages(ire, icp, vx, vy, phi)
   call cntc_calculate(ire, icp, ierror)
   call report('spin', ire, icp, ierror)

   ! 3: Fx = -0.4 mu Fn prescribed (F = 1).
   ire = 3
   call configure(ire, icp, CNTC_un_cntc, 3, 1, 82000d0, 0.3d0)
   flag = CNTC_ic_force; val = 1
   call cntc_setflags(ire, icp, one, [flag], [val])
   hz = [40d0, 36d0, 0.0008d0, 0.6d0, 1.1d0]; ipotcn = -2
   call cntc_sethertzcontact(ire, icp, ipotcn, five, hz)
   veloc = 10000; fn = 80000; vy = 0.0002d0; fxrel = -0.4d0
   call cntc_setreferencevelocity(ire, icp, veloc)
   call cntc_setnormalforce(ire, icp, fn)
   call cntc_setcreepages(ire, icp, zero, vy, zero)
   call cntc_settangentialforces(ire, icp, fxrel, zero)
   call cntc_calculate(ire, icp, ierror)
   call report('force', ire, icp, ierror)
   call cntc_getcreepages(ire, icp, rksi, reta, rphi)
   write(*, '(a,1x,es16.9e2)') 'force_cksi', rksi

   ! 4: Cattaneo's shifts, continuing (P = 0) after the first.
   ire = 4
   call configure(ire, icp, CNTC_un_cntc, 1, 1, 82000d0, 0.3d0)
   hz = [40d0, 40d0, 0.001d0, 0.001d0, 1.2d0]; ipotcn = -1
   call cntc_sethertzcontact(ire, icp, ipotcn, five, hz)
   fn = 30000
   call cntc_setnormalforce(ire, icp, fn)
   shift = [0.0005d0, 0.0005d0, -0.001d0]
   do k = 1, 3
      if (k == 2) then
         flag = CNTC_ic_pvtime; val = 0
         call cntc_setflags(ire, icp, one, [flag], [val])
      end if
      call cntc_setcreepages(ire, icp, shift(k), zero, zero)
      call cntc_calculate(ire, icp, ierror)
      write(tag, '(a,i0)') 'shift', k - 1
      call report(trim(tag), ire, icp, ierror)
   end do

   ! 5: a given grid and its undeformed distance per element, SI units.
   ire = 5
   call configure(ire, icp, CNTC_un_si, 3, 1, 82.0d9, 0.3d0)
   pot = [30d0, 24d0, -7.25d-3, -5.75d-3, 0.5d-3, 0.5d-3]; ipotcn = 3
   call cntc_setpotcontact(ire, icp, ipotcn, six, pot)
   npot = 30 * 24
   allocate(h(npot))
   do iy = 0, 23
      do ix = 0, 29
         x = pot(3) + ix * pot(5); y = pot(4) + iy * pot(6)
         h(1 + ix + iy * 30) = 90d0 * x * x + 160d0 * y * y + 0.002d0 * x
      end do
   end do
   ibase = 9
   call cntc_setundeformeddistc(ire, icp, ibase, npot, h)
   veloc = 30; fn = 20000; vx = 0.0006d0; vy = 0.0003d0; phi = 0.2d0
   call cntc_setreferencevelocity(ire, icp, veloc)
   call cntc_setnormalforce(ire, icp, fn)
   call cntc_setcreepages(ire, icp, vx, vy, phi)
   call cntc_calculate(ire, icp, ierror)
   call report('grid_si', ire, icp, ierror)

   ! 6: SIMPACK's convention.
   ire = 6
   call configure(ire, icp, CNTC_un_spck, 3, 1, 82.0d9, 0.3d0)
   hz = [40d0, 40d0, 0.5d0, 1.1d0, 1.2d0]; ipotcn = -1
   call cntc_sethertzcontact(ire, icp, ipotcn, five, hz)
   veloc = 20; fn = 50000; vx = 0.001d0; vy = -0.0005d0
   call cntc_setreferencevelocity(ire, icp, veloc)
   call cntc_setnormalforce(ire, icp, fn)
   call cntc_setcreepages(ire, icp, vx, vy, zero)
   call cntc_calculate(ire, icp, ierror)
   call report('simpack', ire, icp, ierror)

   do ire = 1, 6
      call cntc_finalize(ire)
   end do
   call cntc_finalizelast()
end program module3
