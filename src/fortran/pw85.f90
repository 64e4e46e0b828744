! pw85.f90 - Fortran 2003 bindings of libpw85 (see include/pw85.h).
!
! module pw85 declares, through iso_c_binding, the constants and the
! bind(C) interfaces of the public C functions of pw85.h, with the same names.
! Storage conventions are those of the C API:
!  - a vector is a real(c_double) array of dimension 3 (PW85_DIM);
!  - a symmetric 3x3 matrix is a real(c_double) array of dimension 6
!    (PW85_SYM) holding its upper triangle row by row:
!    (A11, A12, A13, A22, A23, A33);
!  - the axes of pw85_ellipsoid() are a real(c_double) array axes(3, 3)
!    whose column j is the j-th unit axis (the C row-major rows, read in
!    Fortran column-major order).
! Status codes are integer(c_int): PW85_OK or a negative PW85_ERR_* value.
!
! The two functions returning const char* in C (pw85_version, pw85_strerror)
! return type(c_ptr) here; the module procedures pw85_version_string() and
! pw85_strerror_string(status) return them as Fortran strings.
!
! Using the convenience wrappers requires linking their object code
! (libpw85_fortran.a is installed next to libpw85); programs calling only the
! bind(C) interfaces need just libpw85.
module pw85
  use iso_c_binding
  implicit none

  private :: c_strlen, fortran_string

  ! Mirrors of the macros of pw85.h.
  character(len=*), parameter :: PW85_VERSION_HEADER = "2.0.0"
  integer(c_int), parameter :: PW85_DIM = 3
  integer(c_int), parameter :: PW85_SYM = 6
  real(c_double), parameter :: PW85_LAMBDA_ATOL = 1.0e-6_c_double
  integer(c_int), parameter :: PW85_MAX_ITER = 25
  integer(c_int), parameter :: PW85_NR_ITER = 3

  integer(c_int), parameter :: PW85_OK = 0
  integer(c_int), parameter :: PW85_ERR_INVALID_ARGUMENT = -1
  integer(c_int), parameter :: PW85_ERR_NOT_SPD = -2
  integer(c_int), parameter :: PW85_ERR_NO_CONVERGENCE = -3
  integer(c_int), parameter :: PW85_ERR_NOT_ORTHONORMAL = -4
  integer(c_int), parameter :: PW85_ERR_UNKNOWN_METHOD = -5
  integer(c_int), parameter :: PW85_ERR_INACCURATE = -6
  integer(c_int), parameter :: PW85_ERR_RANGE = -7
  integer(c_int), parameter :: PW85_ERR_CAPACITY = -8
  integer(c_int), parameter :: PW85_ERR_NO_MEMORY = -9
  ! Distance of closest approach : PW85_DCA_THETA_TOL, PW85_DCA_MAX_EVAL.
  real(c_double), parameter :: PW85_DCA_THETA_TOL = 1.0e-8_c_double
  integer(c_int), parameter :: PW85_DCA_MAX_EVAL = 100
  ! First contact time: PW85_CONTACT_TIME_MAX_EVAL.
  integer(c_int), parameter :: PW85_CONTACT_TIME_MAX_EVAL = 100000
  ! Flags of the _ex derivatives calls (unsigned in C): every field, or mu2,
  ! lambda, d_r12, d_theta1, d_theta2 only (the others NaN).
  integer(c_int), parameter :: PW85_DERIVATIVES_ALL = 0
  integer(c_int), parameter :: PW85_DERIVATIVES_FORCES = 1

  ! Contact geometry : mirror of struct pw85_contact_t of pw85.h
  ! (docs/contact_geometry.md). Fortran index k of x0 and n is C index k - 1.
  type, bind(c) :: pw85_contact_t
    real(c_double) :: mu2      ! contact function mu^2
    real(c_double) :: lambda   ! maximiser of f on [0, 1]
    real(c_double) :: x0(3)    ! contact point (scaled by mu), relative to centre 1
    real(c_double) :: n(3)     ! unit common normal at x0, from 1 towards 2
    real(c_double) :: dca      ! distance of closest approach along r12
    real(c_double) :: depth    ! overlap depth along r12 (> 0: overlap)
    real(c_double) :: depth_n  ! depth projected on the normal
  end type pw85_contact_t

  ! Mirror of struct pw85_derivatives_t (docs/derivatives.md): derivatives of
  ! mu^2; symmetric 3x3 quantities stored as q (11, 12, 13, 22, 23, 33).
  type, bind(c) :: pw85_derivatives_t
    real(c_double) :: mu2          ! contact function mu^2
    real(c_double) :: lambda       ! maximiser of f on [0, 1]
    real(c_double) :: d_r12(3)     ! d mu^2 / d r12
    real(c_double) :: d_theta1(3)  ! d mu^2 / d theta1 (rotation of ellipsoid 1)
    real(c_double) :: d_theta2(3)  ! d mu^2 / d theta2 (rotation of ellipsoid 2)
    real(c_double) :: d_q1(6)      ! d mu^2 / d q1(k), off-diagonal: 2 x matrix derivative
    real(c_double) :: d_q2(6)      ! d mu^2 / d q2(k), same convention
    real(c_double) :: hess_r12(6)  ! d^2 mu^2 / d r12^2 (matrix entries)
  end type pw85_derivatives_t

  ! Method-selecting contact function (docs/methods.md): the
  ! PW85_METHOD_* values and the mirror of struct pw85_result of pw85.h.
  integer(c_int), parameter :: PW85_METHOD_DEFAULT = 0
  integer(c_int), parameter :: PW85_METHOD_BRENT = 1
  integer(c_int), parameter :: PW85_METHOD_NEWTON = 2
  integer(c_int), parameter :: PW85_METHOD_RATIONAL = 3
  integer(c_int), parameter :: PW85_METHOD_ZHENG = 4
  type, bind(c) :: pw85_result
    real(c_double) :: mu2         ! contact function mu^2
    real(c_double) :: lambda      ! maximiser of f on [0, 1]
    real(c_double) :: mu2_error   ! estimate of the absolute error on mu2
    integer(c_int) :: iterations  ! iterations of the method
    integer(c_int) :: method      ! method actually used (PW85_METHOD_*)
  end type pw85_result

  interface
    ! size_t strlen(const char *s) of the C library.
    function c_strlen(s) bind(C, name="strlen") result(n)
      import :: c_ptr, c_size_t
      type(c_ptr), value :: s
      integer(c_size_t) :: n
    end function c_strlen

    ! const char *pw85_version(void)
    function pw85_version() bind(C, name="pw85_version") result(p)
      import :: c_ptr
      type(c_ptr) :: p
    end function pw85_version

    ! const char *pw85_strerror(int status)
    function pw85_strerror(status) bind(C, name="pw85_strerror") result(p)
      import :: c_ptr, c_int
      integer(c_int), value :: status
      type(c_ptr) :: p
    end function pw85_strerror

    ! void pw85__cholesky_decomp(double const a[6], double l[6])
    subroutine pw85__cholesky_decomp(a, l) bind(C, name="pw85__cholesky_decomp")
      import :: c_double
      real(c_double), intent(in) :: a(6)
      real(c_double), intent(out) :: l(6)
    end subroutine pw85__cholesky_decomp

    ! void pw85__cholesky_solve(double const l[6], double const b[3], double x[3])
    subroutine pw85__cholesky_solve(l, b, x) bind(C, name="pw85__cholesky_solve")
      import :: c_double
      real(c_double), intent(in) :: l(6), b(3)
      real(c_double), intent(out) :: x(3)
    end subroutine pw85__cholesky_solve

    ! void pw85_spheroid(double a, double c, double const n[3], double q[6])
    subroutine pw85_spheroid(a, c, n, q) bind(C, name="pw85_spheroid")
      import :: c_double
      real(c_double), value :: a, c
      real(c_double), intent(in) :: n(3)
      real(c_double), intent(out) :: q(6)
    end subroutine pw85_spheroid

    ! int pw85_ellipsoid(double const radii[3], double const axes[9], double q[6])
    ! axes(:, j) is the j-th unit axis.
    function pw85_ellipsoid(radii, axes, q) bind(C, name="pw85_ellipsoid") result(status)
      import :: c_double, c_int
      real(c_double), intent(in) :: radii(3), axes(3, 3)
      real(c_double), intent(out) :: q(6)
      integer(c_int) :: status
    end function pw85_ellipsoid

    ! int pw85_ellipsoid_quat(double const radii[3], double const quat[4], double q[6])
    ! quat = (w, x, y, z), rotating body frame to lab frame (HOOMD-blue,
    ! GSD, LAMMPS order), |quat|^2 within 1e-5 of 1.
    function pw85_ellipsoid_quat(radii, quat, q) bind(C, name="pw85_ellipsoid_quat") &
        result(status)
      import :: c_double, c_int
      real(c_double), intent(in) :: radii(3), quat(4)
      real(c_double), intent(out) :: q(6)
      integer(c_int) :: status
    end function pw85_ellipsoid_quat

    ! int pw85_ellipsoid_rotation(double const radii[3], double const rot[9], double q[6])
    ! The C row-major R read column-major: rot(k, :) is body axis k, so rot
    ! is the transpose of the R whose columns are the axes. For such an R in
    ! Fortran: pw85_ellipsoid(radii, R, q), or this call with transpose(R).
    function pw85_ellipsoid_rotation(radii, rot, q) bind(C, name="pw85_ellipsoid_rotation") &
        result(status)
      import :: c_double, c_int
      real(c_double), intent(in) :: radii(3), rot(3, 3)
      real(c_double), intent(out) :: q(6)
      integer(c_int) :: status
    end function pw85_ellipsoid_rotation

    ! int pw85_ellipsoid_axes(double const q[6], double radii[3], double rot[9], double quat[4])
    ! radii ascending; rot(k, :) is the unit axis of radii(k) (the C R read
    ! column-major, as in pw85_ellipsoid_rotation); rot and quat optional.
    function pw85_ellipsoid_axes(q, radii, rot, quat) bind(C, name="pw85_ellipsoid_axes") &
        result(status)
      import :: c_double, c_int
      real(c_double), intent(in) :: q(6)
      real(c_double), intent(out) :: radii(3)
      real(c_double), intent(out), optional :: rot(3, 3), quat(4)
      integer(c_int) :: status
    end function pw85_ellipsoid_axes

    ! double pw85_f_neg(double lambda, double const *params), params = r12, q1, q2
    function pw85_f_neg(lambda, params) bind(C, name="pw85_f_neg") result(f)
      import :: c_double
      real(c_double), value :: lambda
      real(c_double), intent(in) :: params(15)
      real(c_double) :: f
    end function pw85_f_neg

    ! void pw85__residual(double lambda, double const r12[3], double const q1[6],
    !                     double const q2[6], double out[3])
    subroutine pw85__residual(lambda, r12, q1, q2, out) bind(C, name="pw85__residual")
      import :: c_double
      real(c_double), value :: lambda
      real(c_double), intent(in) :: r12(3), q1(6), q2(6)
      real(c_double), intent(out) :: out(3)
    end subroutine pw85__residual

    ! int pw85_contact_function(double const r12[3], double const q1[6],
    !                           double const q2[6], double out[2])
    ! out(1) = mu^2, out(2) = lambda.
    function pw85_contact_function(r12, q1, q2, out) &
        bind(C, name="pw85_contact_function") result(status)
      import :: c_double, c_int
      real(c_double), intent(in) :: r12(3), q1(6), q2(6)
      real(c_double), intent(out) :: out(2)
      integer(c_int) :: status
    end function pw85_contact_function

    ! -- interfaces added by later features go below --

    ! ---- Method-selecting contact function (docs/methods.md) ----
    ! int pw85_contact_function_method(double const r12[3], double const q1[6],
    !     double const q2[6], int method, pw85_result *res)
    function pw85_contact_function_method(r12, q1, q2, method, res) &
        bind(C, name="pw85_contact_function_method") result(status)
      import :: c_double, c_int, pw85_result
      real(c_double), intent(in) :: r12(3), q1(6), q2(6)
      integer(c_int), value :: method
      type(pw85_result), intent(out) :: res
      integer(c_int) :: status
    end function pw85_contact_function_method

    ! ---- Overlap, contact geometry and batch calls (docs/overlap.md,
    ! docs/contact_geometry.md, docs/batch.md) ----
    ! int pw85_overlap(double const r12[3], double const q1[6], double const q2[6])
    ! Returns 1 (overlap), 0 (no overlap) or a negative status.
    function pw85_overlap(r12, q1, q2) bind(C, name="pw85_overlap") result(verdict)
      import :: c_double, c_int
      real(c_double), intent(in) :: r12(3), q1(6), q2(6)
      integer(c_int) :: verdict
    end function pw85_overlap

    ! int pw85_contact(double const r12[3], double const q1[6],
    !                  double const q2[6], pw85_contact_t *c)
    function pw85_contact(r12, q1, q2, c) bind(C, name="pw85_contact") result(status)
      import :: c_double, c_int, pw85_contact_t
      real(c_double), intent(in) :: r12(3), q1(6), q2(6)
      type(pw85_contact_t), intent(out) :: c
      integer(c_int) :: status
    end function pw85_contact

    ! int pw85_contact_derivatives(double const r12[3], double const q1[6],
    !                              double const q2[6], pw85_derivatives_t *d)
    function pw85_contact_derivatives(r12, q1, q2, d) &
        bind(C, name="pw85_contact_derivatives") result(status)
      import :: c_double, c_int, pw85_derivatives_t
      real(c_double), intent(in) :: r12(3), q1(6), q2(6)
      type(pw85_derivatives_t), intent(out) :: d
      integer(c_int) :: status
    end function pw85_contact_derivatives

    ! int pw85_contact_derivatives_ex(double const r12[3], double const q1[6],
    !     double const q2[6], unsigned flags, pw85_derivatives_t *d)
    function pw85_contact_derivatives_ex(r12, q1, q2, flags, d) &
        bind(C, name="pw85_contact_derivatives_ex") result(status)
      import :: c_double, c_int, pw85_derivatives_t
      real(c_double), intent(in) :: r12(3), q1(6), q2(6)
      integer(c_int), value :: flags
      type(pw85_derivatives_t), intent(out) :: d
      integer(c_int) :: status
    end function pw85_contact_derivatives_ex

    ! Batch calls: centres(3, n), q(6, n), pairs(2, m) holding 0-based (C)
    ! indices; status(m) may be omitted (NULL).
    ! int pw85_overlap_batch(long long n, double const *centres,
    !     double const *q, long long m, long long const *pairs, int *overlap,
    !     int *status, int nthreads)
    function pw85_overlap_batch(n, centres, q, m, pairs, overlap, status, nthreads) &
        bind(C, name="pw85_overlap_batch") result(res)
      import :: c_double, c_int, c_long_long
      integer(c_long_long), value :: n, m
      real(c_double), intent(in) :: centres(3, *), q(6, *)
      integer(c_long_long), intent(in) :: pairs(2, *)
      integer(c_int), intent(out) :: overlap(*)
      integer(c_int), intent(out), optional :: status(*)
      integer(c_int), value :: nthreads
      integer(c_int) :: res
    end function pw85_overlap_batch

    ! int pw85_contact_function_batch(long long n, double const *centres,
    !     double const *q, long long m, long long const *pairs, double *out,
    !     int *status, int nthreads); out(1, k) = mu^2, out(2, k) = lambda.
    function pw85_contact_function_batch(n, centres, q, m, pairs, out, status, nthreads) &
        bind(C, name="pw85_contact_function_batch") result(res)
      import :: c_double, c_int, c_long_long
      integer(c_long_long), value :: n, m
      real(c_double), intent(in) :: centres(3, *), q(6, *)
      integer(c_long_long), intent(in) :: pairs(2, *)
      real(c_double), intent(out) :: out(2, *)
      integer(c_int), intent(out), optional :: status(*)
      integer(c_int), value :: nthreads
      integer(c_int) :: res
    end function pw85_contact_function_batch

    ! int pw85_contact_batch(long long n, double const *centres,
    !     double const *q, long long m, long long const *pairs,
    !     pw85_contact_t *c, int *status, int nthreads)
    function pw85_contact_batch(n, centres, q, m, pairs, c, status, nthreads) &
        bind(C, name="pw85_contact_batch") result(res)
      import :: c_double, c_int, c_long_long, pw85_contact_t
      integer(c_long_long), value :: n, m
      real(c_double), intent(in) :: centres(3, *), q(6, *)
      integer(c_long_long), intent(in) :: pairs(2, *)
      type(pw85_contact_t), intent(out) :: c(*)
      integer(c_int), intent(out), optional :: status(*)
      integer(c_int), value :: nthreads
      integer(c_int) :: res
    end function pw85_contact_batch

    ! Per-pair arrays: r12(3, m), q1(6, m), q2(6, m); status(m) may be
    ! omitted (NULL). nthreads is clamped to the CPUs and to m (docs/batch.md).
    ! int pw85_overlap_pairs(long long m, double const *r12, double const *q1,
    !     double const *q2, int *overlap, int *status, int nthreads)
    function pw85_overlap_pairs(m, r12, q1, q2, overlap, status, nthreads) &
        bind(C, name="pw85_overlap_pairs") result(res)
      import :: c_double, c_int, c_long_long
      integer(c_long_long), value :: m
      real(c_double), intent(in) :: r12(3, *), q1(6, *), q2(6, *)
      integer(c_int), intent(out) :: overlap(*)
      integer(c_int), intent(out), optional :: status(*)
      integer(c_int), value :: nthreads
      integer(c_int) :: res
    end function pw85_overlap_pairs

    ! int pw85_contact_function_pairs(long long m, double const *r12,
    !     double const *q1, double const *q2, int method, pw85_result *res,
    !     int *status, int nthreads)
    function pw85_contact_function_pairs(m, r12, q1, q2, method, res, status, nthreads) &
        bind(C, name="pw85_contact_function_pairs") result(ret)
      import :: c_double, c_int, c_long_long, pw85_result
      integer(c_long_long), value :: m
      real(c_double), intent(in) :: r12(3, *), q1(6, *), q2(6, *)
      integer(c_int), value :: method
      type(pw85_result), intent(out) :: res(*)
      integer(c_int), intent(out), optional :: status(*)
      integer(c_int), value :: nthreads
      integer(c_int) :: ret
    end function pw85_contact_function_pairs

    ! int pw85_contact_pairs(long long m, double const *r12, double const *q1,
    !     double const *q2, pw85_contact_t *c, int *status, int nthreads)
    function pw85_contact_pairs(m, r12, q1, q2, c, status, nthreads) &
        bind(C, name="pw85_contact_pairs") result(res)
      import :: c_double, c_int, c_long_long, pw85_contact_t
      integer(c_long_long), value :: m
      real(c_double), intent(in) :: r12(3, *), q1(6, *), q2(6, *)
      type(pw85_contact_t), intent(out) :: c(*)
      integer(c_int), intent(out), optional :: status(*)
      integer(c_int), value :: nthreads
      integer(c_int) :: res
    end function pw85_contact_pairs

    ! int pw85_contact_derivatives_pairs(long long m, double const *r12,
    !     double const *q1, double const *q2, pw85_derivatives_t *d,
    !     int *status, int nthreads)
    function pw85_contact_derivatives_pairs(m, r12, q1, q2, d, status, nthreads) &
        bind(C, name="pw85_contact_derivatives_pairs") result(res)
      import :: c_double, c_int, c_long_long, pw85_derivatives_t
      integer(c_long_long), value :: m
      real(c_double), intent(in) :: r12(3, *), q1(6, *), q2(6, *)
      type(pw85_derivatives_t), intent(out) :: d(*)
      integer(c_int), intent(out), optional :: status(*)
      integer(c_int), value :: nthreads
      integer(c_int) :: res
    end function pw85_contact_derivatives_pairs

    ! int pw85_contact_derivatives_pairs_ex(long long m, double const *r12,
    !     double const *q1, double const *q2, unsigned flags,
    !     pw85_derivatives_t *d, int *status, int nthreads)
    function pw85_contact_derivatives_pairs_ex(m, r12, q1, q2, flags, d, status, nthreads) &
        bind(C, name="pw85_contact_derivatives_pairs_ex") result(res)
      import :: c_double, c_int, c_long_long, pw85_derivatives_t
      integer(c_long_long), value :: m
      real(c_double), intent(in) :: r12(3, *), q1(6, *), q2(6, *)
      integer(c_int), value :: flags
      type(pw85_derivatives_t), intent(out) :: d(*)
      integer(c_int), intent(out), optional :: status(*)
      integer(c_int), value :: nthreads
      integer(c_int) :: res
    end function pw85_contact_derivatives_pairs_ex

    ! Scenes: centres(3, n), q(6, n), pairs(2, m) holding 0-based (C)
    ! indices; box(6) = [Lx, Ly, Lz, xy, xz, yz] (HOOMD/GSD convention) or
    ! omitted (NULL: no periodicity); status(m) may be omitted.
    ! int pw85_scene_overlap(long long n, double const *centres,
    !     double const *q, double const box[6], long long m,
    !     long long const *pairs, int *overlap, int *status, int nthreads)
    function pw85_scene_overlap(n, centres, q, box, m, pairs, overlap, status, nthreads) &
        bind(C, name="pw85_scene_overlap") result(res)
      import :: c_double, c_int, c_long_long
      integer(c_long_long), value :: n, m
      real(c_double), intent(in) :: centres(3, *), q(6, *)
      real(c_double), intent(in), optional :: box(6)
      integer(c_long_long), intent(in) :: pairs(2, *)
      integer(c_int), intent(out) :: overlap(*)
      integer(c_int), intent(out), optional :: status(*)
      integer(c_int), value :: nthreads
      integer(c_int) :: res
    end function pw85_scene_overlap

    ! int pw85_scene_contact_function(long long n, double const *centres,
    !     double const *q, double const box[6], long long m,
    !     long long const *pairs, int method, pw85_result *res, int *status,
    !     int nthreads)
    function pw85_scene_contact_function(n, centres, q, box, m, pairs, method, res, status, &
                                         nthreads) &
        bind(C, name="pw85_scene_contact_function") result(ret)
      import :: c_double, c_int, c_long_long, pw85_result
      integer(c_long_long), value :: n, m
      real(c_double), intent(in) :: centres(3, *), q(6, *)
      real(c_double), intent(in), optional :: box(6)
      integer(c_long_long), intent(in) :: pairs(2, *)
      integer(c_int), value :: method
      type(pw85_result), intent(out) :: res(*)
      integer(c_int), intent(out), optional :: status(*)
      integer(c_int), value :: nthreads
      integer(c_int) :: ret
    end function pw85_scene_contact_function

    ! int pw85_scene_contact(long long n, double const *centres,
    !     double const *q, double const box[6], long long m,
    !     long long const *pairs, pw85_contact_t *c, int *status, int nthreads)
    function pw85_scene_contact(n, centres, q, box, m, pairs, c, status, nthreads) &
        bind(C, name="pw85_scene_contact") result(res)
      import :: c_double, c_int, c_long_long, pw85_contact_t
      integer(c_long_long), value :: n, m
      real(c_double), intent(in) :: centres(3, *), q(6, *)
      real(c_double), intent(in), optional :: box(6)
      integer(c_long_long), intent(in) :: pairs(2, *)
      type(pw85_contact_t), intent(out) :: c(*)
      integer(c_int), intent(out), optional :: status(*)
      integer(c_int), value :: nthreads
      integer(c_int) :: res
    end function pw85_scene_contact

    ! int pw85_scene_contact_derivatives(long long n, double const *centres,
    !     double const *q, double const box[6], long long m,
    !     long long const *pairs, pw85_derivatives_t *d, int *status,
    !     int nthreads)
    function pw85_scene_contact_derivatives(n, centres, q, box, m, pairs, d, status, &
        nthreads) bind(C, name="pw85_scene_contact_derivatives") result(res)
      import :: c_double, c_int, c_long_long, pw85_derivatives_t
      integer(c_long_long), value :: n, m
      real(c_double), intent(in) :: centres(3, *), q(6, *)
      real(c_double), intent(in), optional :: box(6)
      integer(c_long_long), intent(in) :: pairs(2, *)
      type(pw85_derivatives_t), intent(out) :: d(*)
      integer(c_int), intent(out), optional :: status(*)
      integer(c_int), value :: nthreads
      integer(c_int) :: res
    end function pw85_scene_contact_derivatives

    ! int pw85_scene_contact_derivatives_ex(long long n, double const *centres,
    !     double const *q, double const box[6], long long m,
    !     long long const *pairs, unsigned flags, pw85_derivatives_t *d,
    !     int *status, int nthreads)
    function pw85_scene_contact_derivatives_ex(n, centres, q, box, m, pairs, flags, d, &
        status, nthreads) bind(C, name="pw85_scene_contact_derivatives_ex") result(res)
      import :: c_double, c_int, c_long_long, pw85_derivatives_t
      integer(c_long_long), value :: n, m
      real(c_double), intent(in) :: centres(3, *), q(6, *)
      real(c_double), intent(in), optional :: box(6)
      integer(c_long_long), intent(in) :: pairs(2, *)
      integer(c_int), value :: flags
      type(pw85_derivatives_t), intent(out) :: d(*)
      integer(c_int), intent(out), optional :: status(*)
      integer(c_int), value :: nthreads
      integer(c_int) :: res
    end function pw85_scene_contact_derivatives_ex

    ! ---- Configurations: N ellipsoids in a box (docs/scene.md) ----
    ! The handle is a type(c_ptr); indices (i, j, bad) are 0-based, as in C.
    ! int pw85_configuration_create(long long n, double const *centres,
    !     double const *q, double const box[6],
    !     pw85_configuration **configuration, long long *bad)
    function pw85_configuration_create(n, centres, q, box, configuration, bad) &
        bind(C, name="pw85_configuration_create") result(status)
      import :: c_double, c_int, c_long_long, c_ptr
      integer(c_long_long), value :: n
      real(c_double), intent(in) :: centres(3, *), q(6, *)
      real(c_double), intent(in), optional :: box(6)
      type(c_ptr), intent(inout) :: configuration
      integer(c_long_long), intent(out), optional :: bad
      integer(c_int) :: status
    end function pw85_configuration_create

    ! void pw85_configuration_destroy(pw85_configuration *configuration)
    subroutine pw85_configuration_destroy(configuration) &
        bind(C, name="pw85_configuration_destroy")
      import :: c_ptr
      type(c_ptr), value :: configuration
    end subroutine pw85_configuration_destroy

    ! int pw85_configuration_update(pw85_configuration *configuration,
    !     long long n, double const *centres, double const *q,
    !     double const box[6], long long *bad)
    function pw85_configuration_update(configuration, n, centres, q, box, bad) &
        bind(C, name="pw85_configuration_update") result(status)
      import :: c_double, c_int, c_long_long, c_ptr
      type(c_ptr), value :: configuration
      integer(c_long_long), value :: n
      real(c_double), intent(in) :: centres(3, *), q(6, *)
      real(c_double), intent(in), optional :: box(6)
      integer(c_long_long), intent(out), optional :: bad
      integer(c_int) :: status
    end function pw85_configuration_update

    ! long long pw85_configuration_size(pw85_configuration const *configuration)
    function pw85_configuration_size(configuration) &
        bind(C, name="pw85_configuration_size") result(n)
      import :: c_long_long, c_ptr
      type(c_ptr), value :: configuration
      integer(c_long_long) :: n
    end function pw85_configuration_size

    ! int pw85_configuration_pairs(pw85_configuration const *configuration,
    !     double s, int nthreads, long long capacity, long long *i,
    !     long long *j, double *mu2, long long *count, long long examined[2])
    function pw85_configuration_pairs(configuration, s, nthreads, capacity, i, j, mu2, count, &
        examined) bind(C, name="pw85_configuration_pairs") result(status)
      import :: c_double, c_int, c_long_long, c_ptr
      type(c_ptr), value :: configuration
      real(c_double), value :: s
      integer(c_int), value :: nthreads
      integer(c_long_long), value :: capacity
      integer(c_long_long), intent(out), optional :: i(*), j(*)
      real(c_double), intent(out), optional :: mu2(*)
      integer(c_long_long), intent(out) :: count
      integer(c_long_long), intent(out), optional :: examined(2)
      integer(c_int) :: status
    end function pw85_configuration_pairs

    ! int pw85_configuration_test_move(pw85_configuration const *configuration,
    !     long long i, double const centre[3], double const q[6], long long *j)
    function pw85_configuration_test_move(configuration, i, centre, q, j) &
        bind(C, name="pw85_configuration_test_move") result(status)
      import :: c_double, c_int, c_long_long, c_ptr
      type(c_ptr), value :: configuration
      integer(c_long_long), value :: i
      real(c_double), intent(in) :: centre(3), q(6)
      integer(c_long_long), intent(inout) :: j
      integer(c_int) :: status
    end function pw85_configuration_test_move

    ! int pw85_configuration_neighbours(pw85_configuration const *configuration,
    !     long long i, double distance, long long capacity, long long *j,
    !     long long *count)
    function pw85_configuration_neighbours(configuration, i, distance, capacity, j, count) &
        bind(C, name="pw85_configuration_neighbours") result(status)
      import :: c_double, c_int, c_long_long, c_ptr
      type(c_ptr), value :: configuration
      integer(c_long_long), value :: i
      real(c_double), value :: distance
      integer(c_long_long), value :: capacity
      integer(c_long_long), intent(out), optional :: j(*)
      integer(c_long_long), intent(out) :: count
      integer(c_int) :: status
    end function pw85_configuration_neighbours

    ! int pw85_configuration_move(pw85_configuration *configuration,
    !     long long i, double const centre[3], double const q[6])
    function pw85_configuration_move(configuration, i, centre, q) &
        bind(C, name="pw85_configuration_move") result(status)
      import :: c_double, c_int, c_long_long, c_ptr
      type(c_ptr), value :: configuration
      integer(c_long_long), value :: i
      real(c_double), intent(in) :: centre(3), q(6)
      integer(c_int) :: status
    end function pw85_configuration_move

    ! ---- First contact time (docs/contact_time.md) ----
    ! int pw85_contact_time(double const r12[3], double const v12[3],
    !     double const q1[6], double const w1[3], double const q2[6],
    !     double const w2[3], double t_max, double *t)
    function pw85_contact_time(r12, v12, q1, w1, q2, w2, t_max, t) &
        bind(C, name="pw85_contact_time") result(status)
      import :: c_double, c_int
      real(c_double), intent(in) :: r12(3), v12(3), q1(6), w1(3), q2(6), w2(3)
      real(c_double), value :: t_max
      real(c_double), intent(out) :: t
      integer(c_int) :: status
    end function pw85_contact_time

    ! int pw85_contact_time_ex(..., double t_max, double *t, int *evaluations)
    function pw85_contact_time_ex(r12, v12, q1, w1, q2, w2, t_max, t, evaluations) &
        bind(C, name="pw85_contact_time_ex") result(status)
      import :: c_double, c_int
      real(c_double), intent(in) :: r12(3), v12(3), q1(6), w1(3), q2(6), w2(3)
      real(c_double), value :: t_max
      real(c_double), intent(out) :: t
      integer(c_int), intent(out), optional :: evaluations
      integer(c_int) :: status
    end function pw85_contact_time_ex

    ! int pw85_contact_time_pairs(long long m, double const *r12,
    !     double const *v12, double const *q1, double const *w1,
    !     double const *q2, double const *w2, double t_max, double *t,
    !     int *status, int nthreads)
    function pw85_contact_time_pairs(m, r12, v12, q1, w1, q2, w2, t_max, t, status, &
        nthreads) bind(C, name="pw85_contact_time_pairs") result(res)
      import :: c_double, c_int, c_long_long
      integer(c_long_long), value :: m
      real(c_double), intent(in) :: r12(3, *), v12(3, *), q1(6, *), w1(3, *), q2(6, *), w2(3, *)
      real(c_double), value :: t_max
      real(c_double), intent(out) :: t(*)
      integer(c_int), intent(out), optional :: status(*)
      integer(c_int), value :: nthreads
      integer(c_int) :: res
    end function pw85_contact_time_pairs

    ! ---- Distance of closest approach (docs/dca.md) ----
    ! int pw85_dca_2d(double const u[2], double const q1[3],
    !                 double const q2[3], double *d)
    ! 2D ellipses: q = (Q11, Q12, Q22); u need not be a unit vector.
    function pw85_dca_2d(u, q1, q2, d) bind(C, name="pw85_dca_2d") result(status)
      import :: c_double, c_int
      real(c_double), intent(in) :: u(2), q1(3), q2(3)
      real(c_double), intent(out) :: d
      integer(c_int) :: status
    end function pw85_dca_2d

    ! int pw85_contact_function_2d(double const r12[2], double const q1[3],
    !                              double const q2[3], double out[2])
    function pw85_contact_function_2d(r12, q1, q2, out) &
        bind(C, name="pw85_contact_function_2d") result(status)
      import :: c_double, c_int
      real(c_double), intent(in) :: r12(2), q1(3), q2(3)
      real(c_double), intent(out) :: out(2)
      integer(c_int) :: status
    end function pw85_contact_function_2d

    ! int pw85_dca(double const u[3], double const q1[6], double const q2[6],
    !              int method, double *d)
    function pw85_dca(u, q1, q2, method, d) bind(C, name="pw85_dca") result(status)
      import :: c_double, c_int
      real(c_double), intent(in) :: u(3), q1(6), q2(6)
      integer(c_int), value :: method
      real(c_double), intent(out) :: d
      integer(c_int) :: status
    end function pw85_dca

    ! int pw85_dca_ex(double const u[3], double const q1[6], double const q2[6],
    !                 double theta_tol, double *d, int *evaluations)
    function pw85_dca_ex(u, q1, q2, theta_tol, d, evaluations) &
        bind(C, name="pw85_dca_ex") result(status)
      import :: c_double, c_int
      real(c_double), intent(in) :: u(3), q1(6), q2(6)
      real(c_double), value :: theta_tol
      real(c_double), intent(out) :: d
      integer(c_int), intent(out) :: evaluations
      integer(c_int) :: status
    end function pw85_dca_ex
  end interface

contains

  ! Copies the NUL-terminated C string p into an allocatable Fortran string
  ! (empty for a NULL pointer).
  function fortran_string(p) result(s)
    type(c_ptr), intent(in) :: p
    character(len=:), allocatable :: s
    character(kind=c_char), pointer :: chars(:)
    integer :: i, n

    if (.not. c_associated(p)) then
      s = ""
      return
    end if
    n = int(c_strlen(p))
    call c_f_pointer(p, chars, [n])
    allocate(character(len=n) :: s)
    do i = 1, n
      s(i:i) = chars(i)
    end do
  end function fortran_string

  ! Version string of the library actually loaded (pw85_version()).
  function pw85_version_string() result(s)
    character(len=:), allocatable :: s
    s = fortran_string(pw85_version())
  end function pw85_version_string

  ! Description of a status code (pw85_strerror()).
  function pw85_strerror_string(status) result(s)
    integer(c_int), intent(in) :: status
    character(len=:), allocatable :: s
    s = fortran_string(pw85_strerror(status))
  end function pw85_strerror_string

end module pw85
