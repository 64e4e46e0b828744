! test_fortran_legacy.f90 - the Fortran bindings of libpw85_legacy (module
! pw85_legacy) against closed forms: two spheres of radii 1 and 2 whose
! centres are 3 apart have Q(lambda) = (1 + 3 lambda) I,
! f = 9 lambda (1 - lambda) / (1 + 3 lambda), mu^2 = 1 at lambda = 1/3.
! Prints TAP; error stop on any failure.
program test_fortran_legacy
  use, intrinsic :: iso_c_binding
  use pw85, only: PW85_OK, PW85_ERR_NOT_SPD
  use pw85_legacy
  implicit none

  real(c_double), parameter :: EPS = epsilon(1.0_c_double)
  real(c_double) :: q1(6), q2(6), q3(6), q4(6), r(3), a(3), b(4), out(2), d(3)
  real(c_double) :: f, x
  integer(c_int) :: status
  integer :: ntest = 0, nfail = 0

  write (*, '(a)') 'TAP version 13'
  write (*, '(a)') '1..8'
  q1 = [1.0_c_double, 0.0_c_double, 0.0_c_double, 1.0_c_double, 0.0_c_double, 1.0_c_double]
  q2 = 4 * q1
  r = [3.0_c_double, 0.0_c_double, 0.0_c_double]

  ! det(diag(2, 3, 5)) = 30; adj(diag(2, 3, 5)) = diag(15, 10, 6).
  call check(pw85_legacy__det_sym([2.0_c_double, 0.0_c_double, 0.0_c_double, &
                                   3.0_c_double, 0.0_c_double, 5.0_c_double]) == 30, &
             'pw85_legacy__det_sym')
  call check(pw85_legacy__xT_adjA_x([1.0_c_double, 2.0_c_double, 3.0_c_double], &
                                    [2.0_c_double, 0.0_c_double, 0.0_c_double, &
                                     3.0_c_double, 0.0_c_double, 5.0_c_double]) == 109, &
             'pw85_legacy__xT_adjA_x')
  ! a(lambda) = 9 (1 + 3 lambda)^2, b(lambda) = (1 + 3 lambda)^3.
  q3 = 2 * q1 - q2
  q4 = 0.5_c_double * (q1 + q2)
  call pw85_legacy__rT_adjQ_r_as_poly(r, q1, q2, q3, a)
  call check(maxval(abs(a - [9.0_c_double, 54.0_c_double, 81.0_c_double])) <= 1.0e-12_c_double, &
             'pw85_legacy__rT_adjQ_r_as_poly')
  call pw85_legacy__detQ_as_poly(q1, q2, q3, q4, b)
  call check(maxval(abs(b - [1.0_c_double, 9.0_c_double, 27.0_c_double, 27.0_c_double])) &
               <= 1.0e-12_c_double, 'pw85_legacy__detQ_as_poly')
  ! f1 with and without out, f2 with out.
  x = 0.25_c_double
  f = pw85_legacy_f1(x, r, q1, q2)
  call check(abs(f - 9 * x * (1 - x) / (1 + 3 * x)) <= 8 * EPS * f, 'pw85_legacy_f1 (no out)')
  f = pw85_legacy_f2(x, r, q1, q2, d)
  call check(abs(d(1) - f) == 0 .and. abs(d(2) - 9 * (1 - 2 * x - 3 * x * x) / (1 + 3 * x)**2) &
               <= 1.0e-12_c_double, 'pw85_legacy_f2 (out = f, df)')
  ! Contact functions.
  status = pw85_legacy_contact_function1(r, q1, q2, out)
  call check(status == PW85_OK .and. abs(out(1) - 1) <= 16 * EPS .and. &
             abs(out(2) - 1.0_c_double / 3) <= 1.0e-7_c_double, 'pw85_legacy_contact_function1')
  status = pw85_legacy_contact_function2(r, q1, [1.0_c_double, 0.0_c_double, 0.0_c_double, &
                                                 -1.0_c_double, 0.0_c_double, 1.0_c_double], out)
  call check(status == PW85_ERR_NOT_SPD .and. out(1) /= out(1), &
             'pw85_legacy_contact_function2 (not SPD: status and NaN)')

  if (nfail > 0) error stop 1

contains

  subroutine check(ok, what)
    logical, intent(in) :: ok
    character(len=*), intent(in) :: what
    ntest = ntest + 1
    if (ok) then
      write (*, '(a, i0, a)') 'ok ', ntest, ' - ' // what
    else
      nfail = nfail + 1
      write (*, '(a, i0, a)') 'not ok ', ntest, ' - ' // what
    end if
  end subroutine check

end program test_fortran_legacy
