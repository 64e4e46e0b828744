! test_fortran.f90 - the Fortran bindings (module pw85) against the C library.
!
! Reference values: mu^2 and lambda of the two spheroids of the pw85 1.0
! tutorial, as published by pw85 1.0 (independent of this implementation):
!   mu^2 = 3.362706040638343, lambda = 0.1668589553405904.
! Prints TAP; error stop (non-zero exit) on any failure.
program test_fortran
  use, intrinsic :: iso_c_binding
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_nan
  use pw85
  implicit none

  real(c_double), parameter :: MU2_REF = 3.362706040638343_c_double
  real(c_double), parameter :: LAMBDA_REF = 0.1668589553405904_c_double
  real(c_double), parameter :: RTOL = 1.0e-12_c_double

  real(c_double) :: x1(3), x2(3), n1(3), n2(3), r12(3)
  real(c_double) :: q1(6), q2(6), q(6), out(2)
  real(c_double) :: radii(3), axes(3, 3)
  integer(c_int) :: status
  integer :: ntest = 0, nfail = 0
  type(pw85_contact_t) :: contact
  type(pw85_result) :: mres
  real(c_double) :: centres(3, 2), qs(6, 2)
  integer(c_long_long) :: pairs(2, 2)
  integer(c_int) :: verdicts(2), statuses(2)
  real(c_double) :: r12s(3, 2), q1s(6, 2), q2s(6, 2), box(6)
  type(pw85_result) :: mresv(2)
  type(pw85_contact_t) :: contacts(2)
  type(pw85_derivatives_t) :: deriv, derivs(2)
  real(c_double) :: hr(3)
  real(c_double) :: quat(4), rot(3, 3), rmat(3, 3), qr(6), ra(3)
  character(len=:), allocatable :: version, message_ok, message_spd
  type(c_ptr) :: conf
  real(c_double) :: cc(3, 3), qc(6, 3), mu2s(3), far(3)
  integer(c_long_long) :: ci(3), cj(3), count, jfound, bad

  write (*, '(a)') 'TAP version 13'
  write (*, '(a)') '1..45'

  ! Version: the loaded library and the module constant agree.
  version = pw85_version_string()
  call check(version == PW85_VERSION_HEADER, &
             'pw85_version_string() = "' // version // '" = PW85_VERSION_HEADER')
  message_ok = pw85_strerror_string(PW85_OK)
  message_spd = pw85_strerror_string(PW85_ERR_NOT_SPD)
  call check(len(message_ok) > 0 .and. message_spd /= message_ok, &
             'pw85_strerror_string() distinguishes codes: "' // message_spd // '"')

  ! The tutorial spheroids.
  x1 = [-0.5_c_double, 0.4_c_double, -0.7_c_double]
  n1 = [0.0_c_double, 0.0_c_double, 1.0_c_double]
  x2 = [0.2_c_double, -0.3_c_double, 0.4_c_double]
  n2 = [1.0_c_double, 0.0_c_double, 0.0_c_double]
  r12 = x2 - x1
  call pw85_spheroid(10.0_c_double, 0.1_c_double, n1, q1)
  call pw85_spheroid(0.5_c_double, 5.0_c_double, n2, q2)
  ! Q = a^2 I + (c^2 - a^2) n n^T, upper triangle row by row; the entries
  ! are sums of terms up to max(a, c)^2, so allow a few ulps of that.
  call check(maxval(abs(q1 - [100.0_c_double, 0.0_c_double, 0.0_c_double, &
                              100.0_c_double, 0.0_c_double, 0.01_c_double])) &
               <= 4 * epsilon(1.0_c_double) * 100.0_c_double .and. &
             maxval(abs(q2 - [25.0_c_double, 0.0_c_double, 0.0_c_double, &
                              0.25_c_double, 0.0_c_double, 0.25_c_double])) &
               <= 4 * epsilon(1.0_c_double) * 25.0_c_double, &
             'pw85_spheroid: tutorial quadratic forms')

  out = -1.0_c_double
  status = pw85_contact_function(r12, q1, q2, out)
  call check(status == PW85_OK, 'pw85_contact_function: status PW85_OK')
  call check(abs(out(1) - MU2_REF) <= RTOL * MU2_REF, &
             'pw85_contact_function: mu^2 of the tutorial to 1e-12 relative')
  call check(abs(out(2) - LAMBDA_REF) <= RTOL * LAMBDA_REF, &
             'pw85_contact_function: lambda of the tutorial to 1e-12 relative')

  ! pw85_ellipsoid with the axes of the second spheroid (axis of revolution
  ! along x, semi-axes 5, 0.5, 0.5) gives the same quadratic form.
  radii = [5.0_c_double, 0.5_c_double, 0.5_c_double]
  axes = 0.0_c_double
  axes(1, 1) = 1.0_c_double
  axes(2, 2) = 1.0_c_double
  axes(3, 3) = 1.0_c_double
  status = pw85_ellipsoid(radii, axes, q)
  call check(status == PW85_OK .and. &
             maxval(abs(q - q2)) <= 4 * epsilon(1.0_c_double) * 25.0_c_double, &
             'pw85_ellipsoid: axis-aligned spheroid equals pw85_spheroid')
  ! Non-orthonormal axes are refused and q is NaN-filled.
  axes(1, 2) = 0.5_c_double
  status = pw85_ellipsoid(radii, axes, q)
  call check(status == PW85_ERR_NOT_ORTHONORMAL .and. all(ieee_is_nan(q)), &
             'pw85_ellipsoid: non-orthonormal axes give PW85_ERR_NOT_ORTHONORMAL')

  ! Orientations: the HOOMD-blue quaternion (cos 45, 0, 0, sin 45) turns the
  ! body x axis into the lab y axis: semi-axes (3, 1, 1) give diag(1, 9, 1).
  ! rmat has the body axes as columns (Fortran order).
  radii = [3.0_c_double, 1.0_c_double, 1.0_c_double]
  quat = [sqrt(0.5_c_double), 0.0_c_double, 0.0_c_double, sqrt(0.5_c_double)]
  status = pw85_ellipsoid_quat(radii, quat, q)
  call check(status == PW85_OK .and. maxval(abs(q - [1.0_c_double, 0.0_c_double, &
             0.0_c_double, 9.0_c_double, 0.0_c_double, 1.0_c_double])) &
             <= 36 * epsilon(1.0_c_double), &
             'pw85_ellipsoid_quat: body x axis to lab y axis')
  rmat = reshape([0.0_c_double, 1.0_c_double, 0.0_c_double, -1.0_c_double, 0.0_c_double, &
                  0.0_c_double, 0.0_c_double, 0.0_c_double, 1.0_c_double], [3, 3])
  status = pw85_ellipsoid_rotation(radii, transpose(rmat), qr)
  call check(status == PW85_OK .and. maxval(abs(qr - q)) <= 36 * epsilon(1.0_c_double), &
             'pw85_ellipsoid_rotation: transpose of the Fortran R of axis columns')
  status = pw85_ellipsoid(radii, rmat, qr)
  call check(status == PW85_OK .and. maxval(abs(qr - q)) <= 36 * epsilon(1.0_c_double), &
             'pw85_ellipsoid: the Fortran R of axis columns as axes')
  status = pw85_ellipsoid_axes(q, ra, rot, quat)
  call check(status == PW85_OK .and. &
             maxval(abs(ra - [1.0_c_double, 1.0_c_double, 3.0_c_double])) &
             <= 8 * epsilon(1.0_c_double) &
             .and. abs(abs(rot(3, 2)) - 1.0_c_double) <= 8 * epsilon(1.0_c_double) &
             .and. quat(1) >= 0.0_c_double, &
             'pw85_ellipsoid_axes: semi-axes ascending, long axis rot(3, :) along y')
  status = pw85_ellipsoid_axes(q, ra)
  call check(status == PW85_OK .and. abs(ra(3) - 3.0_c_double) <= 8 * epsilon(1.0_c_double), &
             'pw85_ellipsoid_axes: rot and quat omitted')
  quat = 0.0_c_double
  status = pw85_ellipsoid_quat(radii, quat, q)
  call check(status == PW85_ERR_NOT_ORTHONORMAL .and. all(ieee_is_nan(q)), &
             'pw85_ellipsoid_quat: zero quaternion gives PW85_ERR_NOT_ORTHONORMAL')

  ! NaN in r12: PW85_ERR_INVALID_ARGUMENT, out NaN-filled.
  r12(2) = ieee_value(r12(2), ieee_quiet_nan)
  out = 0.0_c_double
  status = pw85_contact_function(r12, q1, q2, out)
  call check(status == PW85_ERR_INVALID_ARGUMENT .and. all(ieee_is_nan(out)), &
             'pw85_contact_function: NaN in r12 gives PW85_ERR_INVALID_ARGUMENT')

  ! Overlap predicate, contact geometry and a batch call on the
  ! tutorial pair (mu^2 = 3.36 > 1: apart; with r12 / 2, mu^2 = 3.36 / 4 < 1:
  ! overlapping, since mu^2 is homogeneous of degree 2 in r12).
  r12 = x2 - x1
  call check(pw85_overlap(r12, q1, q2) == 0, 'pw85_overlap: tutorial pair (mu^2 = 3.36) gives 0')
  call check(pw85_overlap(0.5_c_double * r12, q1, q2) == 1, &
             'pw85_overlap: tutorial pair with r12 / 2 (mu^2 = 0.84) gives 1')
  status = pw85_contact(r12, q1, q2, contact)
  call check(status == PW85_OK .and. abs(contact%mu2 - MU2_REF) <= RTOL * MU2_REF .and. &
             abs(contact%lambda - LAMBDA_REF) <= RTOL * LAMBDA_REF .and. &
             abs(contact%dca - norm2(r12) / sqrt(MU2_REF)) <= RTOL * contact%dca .and. &
             contact%depth < 0.0_c_double .and. &
             abs(norm2(contact%n) - 1.0_c_double) <= 8 * epsilon(1.0_c_double) .and. &
             dot_product(contact%n, r12) > 0.0_c_double, &
             'pw85_contact: tutorial mu^2, lambda, dca = |r12| / mu, depth < 0, unit normal towards 2')
  ! Derivatives: mu^2 is homogeneous of degree 2 in r12, so
  ! d_r12 . r12 = 2 mu^2 and hess_r12 r12 = d_r12 (Euler's theorem).
  status = pw85_contact_derivatives(r12, q1, q2, deriv)
  hr = [deriv%hess_r12(1) * r12(1) + deriv%hess_r12(2) * r12(2) + deriv%hess_r12(3) * r12(3), &
        deriv%hess_r12(2) * r12(1) + deriv%hess_r12(4) * r12(2) + deriv%hess_r12(5) * r12(3), &
        deriv%hess_r12(3) * r12(1) + deriv%hess_r12(5) * r12(2) + deriv%hess_r12(6) * r12(3)]
  call check(status == PW85_OK .and. abs(deriv%mu2 - MU2_REF) <= RTOL * MU2_REF .and. &
             abs(dot_product(deriv%d_r12, r12) - 2 * MU2_REF) <= RTOL * MU2_REF .and. &
             norm2(hr - deriv%d_r12) <= RTOL * norm2(deriv%d_r12), &
             'pw85_contact_derivatives: tutorial pair, g . r12 = 2 mu^2, H r12 = g')
  r12s(:, 1) = r12
  r12s(:, 2) = 0.0_c_double
  q1s(:, 1) = q1
  q1s(:, 2) = q1
  q2s(:, 1) = q2
  q2s(:, 2) = q2
  status = pw85_contact_derivatives_pairs(2_c_long_long, r12s, q1s, q2s, derivs, statuses, 1_c_int)
  call check(status == PW85_ERR_INVALID_ARGUMENT .and. statuses(1) == PW85_OK .and. &
             statuses(2) == PW85_ERR_INVALID_ARGUMENT .and. &
             all(derivs(1)%d_r12 == deriv%d_r12) .and. derivs(2)%mu2 /= derivs(2)%mu2, &
             'pw85_contact_derivatives_pairs: pair 1 as the one-pair call, r12 = 0 fails with NaN')
  ! PW85_DERIVATIVES_FORCES: mu2, lambda, gradient and torques bitwise the
  ! full call's, d_q1, d_q2 and the Hessian NaN; other flags are invalid.
  block
    type(pw85_derivatives_t) :: light, lights(2), scene_light(1)
    integer(c_long_long) :: one_pair(2, 1)
    real(c_double) :: centres2(3, 2), qs2(6, 2)
    status = pw85_contact_derivatives_ex(r12, q1, q2, PW85_DERIVATIVES_FORCES, light)
    call check(status == PW85_OK .and. light%mu2 == deriv%mu2 .and. &
               light%lambda == deriv%lambda .and. all(light%d_r12 == deriv%d_r12) .and. &
               all(light%d_theta1 == deriv%d_theta1) .and. &
               all(light%d_theta2 == deriv%d_theta2) .and. &
               all(light%d_q1 /= light%d_q1) .and. all(light%d_q2 /= light%d_q2) .and. &
               all(light%hess_r12 /= light%hess_r12), &
               'pw85_contact_derivatives_ex FORCES: the full call''s forces and torques, the rest NaN')
    status = pw85_contact_derivatives_ex(r12, q1, q2, 2_c_int, light)
    call check(status == PW85_ERR_INVALID_ARGUMENT .and. light%mu2 /= light%mu2, &
               'pw85_contact_derivatives_ex: flags 2 is invalid, NaN')
    status = pw85_contact_derivatives_pairs_ex(2_c_long_long, r12s, q1s, q2s, &
                                               PW85_DERIVATIVES_FORCES, lights, statuses, 1_c_int)
    call check(status == PW85_ERR_INVALID_ARGUMENT .and. statuses(1) == PW85_OK .and. &
               all(lights(1)%d_r12 == deriv%d_r12) .and. &
               all(lights(1)%d_theta2 == deriv%d_theta2) .and. &
               lights(1)%hess_r12(1) /= lights(1)%hess_r12(1), &
               'pw85_contact_derivatives_pairs_ex FORCES: pair 1 as the full call')
    centres2(:, 1) = 0.0_c_double
    centres2(:, 2) = r12
    qs2(:, 1) = q1
    qs2(:, 2) = q2
    one_pair(:, 1) = [0_c_long_long, 1_c_long_long]
    status = pw85_scene_contact_derivatives_ex(2_c_long_long, centres2, qs2, m=1_c_long_long, &
                                               pairs=one_pair, flags=PW85_DERIVATIVES_FORCES, &
                                               d=scene_light, nthreads=1_c_int)
    call check(status == PW85_OK .and. all(scene_light(1)%d_r12 == deriv%d_r12) .and. &
               all(scene_light(1)%d_theta1 == deriv%d_theta1) .and. &
               scene_light(1)%mu2 == deriv%mu2 .and. &
               scene_light(1)%d_q2(1) /= scene_light(1)%d_q2(1), &
               'pw85_scene_contact_derivatives_ex FORCES: the full call''s fields, d_q NaN')
  end block
  ! First contact time: unit spheres 3 apart closing at unit speed touch at
  ! t = 1; spinning spheres change nothing.
  block
    real(c_double) :: tc, tcs(2), rr(3, 2), vv(3, 2), ww(3, 2), qq(6, 2)
    integer(c_int) :: nev, sts(2)
    real(c_double), parameter :: unit(6) = [1, 0, 0, 1, 0, 1]
    status = pw85_contact_time_ex([3.0_c_double, 0.0_c_double, 0.0_c_double], &
                                  [-1.0_c_double, 0.0_c_double, 0.0_c_double], unit, &
                                  [0.0_c_double, 0.0_c_double, 5.0_c_double], unit, &
                                  [1.0_c_double, 0.0_c_double, 0.0_c_double], 2.0_c_double, &
                                  tc, nev)
    call check(status == PW85_OK .and. abs(tc - 1.0_c_double) <= 1e-14_c_double .and. nev >= 1, &
               'pw85_contact_time_ex: unit spheres 3 apart at unit speed touch at t = 1')
    rr(:, 1) = [3.0_c_double, 0.0_c_double, 0.0_c_double]
    rr(:, 2) = [3.0_c_double, 0.0_c_double, 0.0_c_double]
    vv(:, 1) = [-1.0_c_double, 0.0_c_double, 0.0_c_double]
    vv(:, 2) = [1.0_c_double, 0.0_c_double, 0.0_c_double]
    ww = 0.0_c_double
    qq(:, 1) = unit
    qq(:, 2) = unit
    status = pw85_contact_time_pairs(2_c_long_long, rr, vv, qq, ww, qq, ww, 2.0_c_double, tcs, &
                                     sts, 1_c_int)
    call check(status == PW85_OK .and. all(sts == PW85_OK) .and. tcs(1) == tc .and. &
               tcs(2) > huge(1.0_c_double), &
               'pw85_contact_time_pairs: approaching pair as the one-pair call, receding pair +Inf')
    status = pw85_contact_time(rr(:, 1), vv(:, 1), unit, ww(:, 1), unit, ww(:, 1), &
                               -1.0_c_double, tc)
    call check(status == PW85_ERR_INVALID_ARGUMENT .and. tc /= tc, &
               'pw85_contact_time: t_max < 0 fails with NaN')
  end block
  centres(:, 1) = x1
  centres(:, 2) = x2
  qs(:, 1) = q1
  qs(:, 2) = q2
  pairs(:, 1) = [0_c_long_long, 1_c_long_long]
  pairs(:, 2) = [1_c_long_long, 0_c_long_long]
  status = pw85_overlap_batch(2_c_long_long, centres, qs, 2_c_long_long, pairs, verdicts, &
                              nthreads=1_c_int)
  call check(status == PW85_OK .and. all(verdicts == 0), &
             'pw85_overlap_batch: both orders of the tutorial pair give 0 (status omitted)')

  ! Method-selecting contact function: the tutorial pair by the
  ! default method; an unknown method id.
  status = pw85_contact_function_method(r12, q1, q2, PW85_METHOD_DEFAULT, mres)
  call check(status == PW85_OK .and. mres%method == PW85_METHOD_DEFAULT .and. &
             abs(mres%mu2 - MU2_REF) <= RTOL * MU2_REF .and. &
             abs(mres%lambda - LAMBDA_REF) <= 1.0e-8_c_double .and. &
             mres%mu2_error >= 0.0_c_double .and. mres%mu2_error <= 1.0e-14_c_double * mres%mu2, &
             'pw85_contact_function_method: DEFAULT on the tutorial pair (mu^2, lambda, error)')
  status = pw85_contact_function_method(r12, q1, q2, 99_c_int, mres)
  call check(status == PW85_ERR_UNKNOWN_METHOD .and. ieee_is_nan(mres%mu2), &
             'pw85_contact_function_method: unknown method gives PW85_ERR_UNKNOWN_METHOD, NaN')

  ! Per-pair arrays: the tutorial pair and the same with r12 / 2
  ! (mu^2 / 4), two threads.
  r12s(:, 1) = r12
  r12s(:, 2) = 0.5_c_double * r12
  q1s(:, 1) = q1
  q1s(:, 2) = q1
  q2s(:, 1) = q2
  q2s(:, 2) = q2
  status = pw85_contact_function_pairs(2_c_long_long, r12s, q1s, q2s, PW85_METHOD_DEFAULT, &
                                       mresv, statuses, 2_c_int)
  call check(status == PW85_OK .and. all(statuses == PW85_OK) .and. &
             abs(mresv(1)%mu2 - MU2_REF) <= RTOL * MU2_REF .and. &
             abs(mresv(2)%mu2 - 0.25_c_double * MU2_REF) <= RTOL * MU2_REF, &
             'pw85_contact_function_pairs: tutorial pair, and with r12 / 2 (mu^2 / 4)')
  status = pw85_contact_pairs(2_c_long_long, r12s, q1s, q2s, contacts, nthreads=1_c_int)
  call check(status == PW85_OK .and. contacts(1)%depth < 0.0_c_double .and. &
             contacts(2)%depth > 0.0_c_double, &
             'pw85_contact_pairs: apart, then overlapping (status omitted)')

  ! Periodic scene: centre 2 moved by the lattice vector a2 = (xy Ly, Ly, 0)
  ! of a tilted box; the minimum image is the tutorial pair again.
  box = [40.0_c_double, 40.0_c_double, 40.0_c_double, 0.25_c_double, 0.0_c_double, &
         0.0_c_double]
  centres(:, 2) = x2 + [10.0_c_double, 40.0_c_double, 0.0_c_double]
  status = pw85_scene_contact_function(2_c_long_long, centres, qs, box, 2_c_long_long, pairs, &
                                       PW85_METHOD_DEFAULT, mresv, statuses, 1_c_int)
  call check(status == PW85_OK .and. abs(mresv(1)%mu2 - MU2_REF) <= RTOL * MU2_REF .and. &
             abs(mresv(2)%mu2 - MU2_REF) <= RTOL * MU2_REF, &
             'pw85_scene_contact_function: minimum image in a tilted box is the tutorial pair')
  status = pw85_scene_overlap(2_c_long_long, centres, qs, box, 2_c_long_long, pairs, &
                              verdicts, nthreads=2_c_int)
  call check(status == PW85_OK .and. all(verdicts == 0), &
             'pw85_scene_overlap: periodic tutorial pair gives 0 (status omitted)')
  status = pw85_scene_contact_function(2_c_long_long, centres, qs, m=2_c_long_long, &
                                       pairs=pairs, method=PW85_METHOD_DEFAULT, res=mresv, &
                                       nthreads=1_c_int)
  call check(status == PW85_OK .and. mresv(1)%mu2 > 2.0_c_double * MU2_REF, &
             'pw85_scene_contact_function: box omitted, no periodicity (farther apart)')

  ! Configuration of three particles: the tutorial pair (0, 1) (mu^2 3.36)
  ! and particle 2 (matrix q2) at x1 + r12/2, which overlaps both.
  cc(:, 1) = x1
  cc(:, 2) = x2
  cc(:, 3) = x1 + 0.5_c_double * r12
  qc(:, 1) = q1
  qc(:, 2) = q2
  qc(:, 3) = q2
  conf = c_null_ptr
  status = pw85_configuration_create(3_c_long_long, cc, qc, configuration=conf, bad=bad)
  call check(status == PW85_OK .and. c_associated(conf) .and. bad == -1 .and. &
             pw85_configuration_size(conf) == 3, 'pw85_configuration_create: three particles')
  status = pw85_configuration_pairs(conf, 1.0_c_double, 1_c_int, 3_c_long_long, ci, cj, &
                                    count=count)
  call check(status == PW85_OK .and. count == 2 .and. all(ci(1:2) == [0, 1]) .and. &
             all(cj(1:2) == [2, 2]), 'pw85_configuration_pairs: s = 1, pairs (0, 2), (1, 2)')
  status = pw85_configuration_pairs(conf, 2.0_c_double, 1_c_int, 3_c_long_long, ci, cj, mu2s, &
                                    count)
  call check(status == PW85_OK .and. count == 3 .and. ci(1) == 0 .and. cj(1) == 1 .and. &
             abs(mu2s(1) - MU2_REF) <= RTOL * MU2_REF, &
             'pw85_configuration_pairs: s = 2 adds the tutorial pair, its mu^2')
  status = pw85_configuration_pairs(conf, 2.0_c_double, 1_c_int, 0_c_long_long, count=count)
  call check(status == PW85_ERR_CAPACITY .and. count == 3, &
             'pw85_configuration_pairs: capacity 0 gives the count')
  jfound = -7
  status = pw85_configuration_test_move(conf, 1_c_long_long, cc(:, 3), q2, jfound)
  call check(status == PW85_OK .and. jfound == 0, &
             'pw85_configuration_test_move: onto particle 2, first overlap is particle 0')
  far = x1 + 100.0_c_double
  status = pw85_configuration_move(conf, 2_c_long_long, far, q2)
  call check(status == PW85_OK, 'pw85_configuration_move: particle 2 far away')
  status = pw85_configuration_pairs(conf, 1.0_c_double, 0_c_int, 3_c_long_long, ci, cj, &
                                    count=count)
  call check(status == PW85_OK .and. count == 0, &
             'pw85_configuration_pairs: no overlap after the move')
  ! Neighbours by centre distance: particle 1 at |r12| from particle 0,
  ! particle 2 at |(100, 100, 100)|.
  status = pw85_configuration_neighbours(conf, 0_c_long_long, 1.01_c_double * norm2(r12), &
                                         3_c_long_long, cj, count)
  call check(status == PW85_OK .and. count == 1 .and. cj(1) == 1, &
             'pw85_configuration_neighbours: particle 1 within 1.01 |r12| of particle 0')
  status = pw85_configuration_neighbours(conf, 0_c_long_long, 0.99_c_double * norm2(r12), &
                                         3_c_long_long, cj, count)
  call check(status == PW85_OK .and. count == 0, &
             'pw85_configuration_neighbours: none within 0.99 |r12|')
  status = pw85_configuration_neighbours(conf, 0_c_long_long, 200.0_c_double, 0_c_long_long, &
                                         count=count)
  call check(status == PW85_ERR_CAPACITY .and. count == 2, &
             'pw85_configuration_neighbours: capacity 0 gives the count')
  call pw85_configuration_destroy(conf)

  ! Main-program allocatables are not freed automatically at the end; free
  ! them so that LeakSanitizer (sanitizer builds) sees no leak.
  deallocate(version, message_ok, message_spd)

  if (nfail > 0) then
    write (*, '(a,i0,a,i0,a)') '# ', nfail, ' of ', ntest, ' tests failed'
    error stop 1
  end if

contains

  subroutine check(ok, description)
    logical, intent(in) :: ok
    character(len=*), intent(in) :: description
    ntest = ntest + 1
    if (ok) then
      write (*, '(a,i0,a,a)') 'ok ', ntest, ' - ', description
    else
      nfail = nfail + 1
      write (*, '(a,i0,a,a)') 'not ok ', ntest, ' - ', description
    end if
  end subroutine check

end program test_fortran
