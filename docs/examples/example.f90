! example.f90 - libpw85 from Fortran: the tutorial spheroids.
!
! Build (installed library):
!   gfortran -I<includedir> example.f90 -L<libdir> -lpw85_fortran -lpw85
! (-lpw85_fortran is needed for pw85_version_string/pw85_strerror_string).
program example
  use, intrinsic :: iso_c_binding, only: c_double, c_int
  use pw85
  implicit none

  real(c_double) :: x1(3), x2(3), n1(3), n2(3), q1(6), q2(6), out(2)
  integer(c_int) :: status

  x1 = [-0.5_c_double, 0.4_c_double, -0.7_c_double]
  n1 = [0.0_c_double, 0.0_c_double, 1.0_c_double]
  x2 = [0.2_c_double, -0.3_c_double, 0.4_c_double]
  n2 = [1.0_c_double, 0.0_c_double, 0.0_c_double]

  call pw85_spheroid(10.0_c_double, 0.1_c_double, n1, q1)
  call pw85_spheroid(0.5_c_double, 5.0_c_double, n2, q2)

  status = pw85_contact_function(x2 - x1, q1, q2, out)
  if (status /= PW85_OK) then
    write (*, '(2a)') 'pw85_contact_function: ', pw85_strerror_string(status)
    error stop 1
  end if
  write (*, '(2a)') 'libpw85 ', pw85_version_string()
  write (*, '(a,g0.6)') 'mu^2 = ', out(1)
  write (*, '(a,g0.6)') 'lambda = ', out(2)
end program example
