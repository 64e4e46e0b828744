! pw85_legacy.f90 - Fortran 2003 bindings of libpw85_legacy (see
! include/pw85_legacy.h for what each function computes and how it fails).
!
! module pw85_legacy declares bind(C) interfaces of the C functions of
! pw85_legacy.h, with the same names. Storage conventions are those of module
! pw85: vectors are real(c_double) arrays of dimension 3, symmetric matrices
! real(c_double) arrays of dimension 6 (upper triangle row by row). Status
! codes are the PW85_* constants of module pw85. Link with -lpw85_legacy
! -lpw85; the module has no procedures of its own, so no object code is
! needed.
module pw85_legacy
  use iso_c_binding
  implicit none

  interface
    ! double pw85_legacy__det_sym(double const a[6])
    function pw85_legacy__det_sym(a) bind(C, name="pw85_legacy__det_sym") result(d)
      import :: c_double
      real(c_double), intent(in) :: a(6)
      real(c_double) :: d
    end function pw85_legacy__det_sym

    ! double pw85_legacy__xT_adjA_x(double const x[3], double const a[6])
    function pw85_legacy__xT_adjA_x(x, a) bind(C, name="pw85_legacy__xT_adjA_x") result(y)
      import :: c_double
      real(c_double), intent(in) :: x(3), a(6)
      real(c_double) :: y
    end function pw85_legacy__xT_adjA_x

    ! void pw85_legacy__rT_adjQ_r_as_poly(r, q1, q2, q3, double a[3]),
    ! q3 = 2 q1 - q2
    subroutine pw85_legacy__rT_adjQ_r_as_poly(r, q1, q2, q3, a) &
        bind(C, name="pw85_legacy__rT_adjQ_r_as_poly")
      import :: c_double
      real(c_double), intent(in) :: r(3), q1(6), q2(6), q3(6)
      real(c_double), intent(out) :: a(3)
    end subroutine pw85_legacy__rT_adjQ_r_as_poly

    ! void pw85_legacy__detQ_as_poly(q1, q2, q3, q4, double b[4]),
    ! q3 = 2 q1 - q2, q4 = (q1 + q2) / 2
    subroutine pw85_legacy__detQ_as_poly(q1, q2, q3, q4, b) &
        bind(C, name="pw85_legacy__detQ_as_poly")
      import :: c_double
      real(c_double), intent(in) :: q1(6), q2(6), q3(6), q4(6)
      real(c_double), intent(out) :: b(4)
    end subroutine pw85_legacy__detQ_as_poly

    ! double pw85_legacy_f1(double lambda, r12, q1, q2, double *out)
    ! out (optional; NULL when absent) receives f, f', f''.
    function pw85_legacy_f1(lambda, r12, q1, q2, out) bind(C, name="pw85_legacy_f1") &
        result(f)
      import :: c_double
      real(c_double), value :: lambda
      real(c_double), intent(in) :: r12(3), q1(6), q2(6)
      real(c_double), intent(out), optional :: out(3)
      real(c_double) :: f
    end function pw85_legacy_f1

    ! double pw85_legacy_f2(double lambda, r12, q1, q2, double *out)
    ! out (optional) receives f, f', f'' of the rational fraction.
    function pw85_legacy_f2(lambda, r12, q1, q2, out) bind(C, name="pw85_legacy_f2") &
        result(f)
      import :: c_double
      real(c_double), value :: lambda
      real(c_double), intent(in) :: r12(3), q1(6), q2(6)
      real(c_double), intent(out), optional :: out(3)
      real(c_double) :: f
    end function pw85_legacy_f2

    ! int pw85_legacy_contact_function1(r12, q1, q2, double out[2])
    function pw85_legacy_contact_function1(r12, q1, q2, out) &
        bind(C, name="pw85_legacy_contact_function1") result(status)
      import :: c_double, c_int
      real(c_double), intent(in) :: r12(3), q1(6), q2(6)
      real(c_double), intent(out) :: out(2)
      integer(c_int) :: status
    end function pw85_legacy_contact_function1

    ! int pw85_legacy_contact_function2(r12, q1, q2, double out[2])
    function pw85_legacy_contact_function2(r12, q1, q2, out) &
        bind(C, name="pw85_legacy_contact_function2") result(status)
      import :: c_double, c_int
      real(c_double), intent(in) :: r12(3), q1(6), q2(6)
      real(c_double), intent(out) :: out(2)
      integer(c_int) :: status
    end function pw85_legacy_contact_function2
  end interface
end module pw85_legacy
