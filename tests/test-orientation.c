/* Orientations: pw85_ellipsoid_quat, pw85_ellipsoid_rotation and the inverse
 * pw85_ellipsoid_axes. References are independent of the library: the
 * rotation of a quaternion by Hamilton products q p q^* and Q = R diag(a^2)
 * R^T summed in __float128 from the doubles actually passed, exact
 * rationals (quaternions p / m with p0^2 + ... + p3^2 = m^2), and
 * backward-error certificates in __float128 for the eigen-decomposition. */
#include <float.h>
#include <math.h>

#include <pw85.h>

#include "testutil.h"

#define U 0x1p-53

typedef __float128 f128;

static double fabsq_(f128 x) { return (double)(x < 0 ? -x : x); }

/* Hamilton product a b of quaternions (w, x, y, z). */
static void qmul(const f128 a[4], const f128 b[4], f128 out[4]) {
  out[0] = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3];
  out[1] = a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2];
  out[2] = a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1];
  out[3] = a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0];
}

/* Lab-frame image of the body-frame vector p: q p q^* / |q|^2 (the HOOMD-blue
 * and GSD convention: body to lab). */
static void rotate_hamilton(const double q[4], const f128 p[3], f128 out[3]) {
  f128 const a[4] = {q[0], q[1], q[2], q[3]}, c[4] = {q[0], -(f128)q[1], -(f128)q[2],
                                                        -(f128)q[3]};
  f128 const pp[4] = {0, p[0], p[1], p[2]};
  f128 t[4], r[4];
  qmul(a, pp, t);
  qmul(t, c, r);
  f128 const n2 = a[0] * a[0] + a[1] * a[1] + a[2] * a[2] + a[3] * a[3];
  for (int i = 0; i < 3; i++) out[i] = r[i + 1] / n2;
}

/* R of quaternion q (column k = image of e_k) by Hamilton products. */
static void rot_of_quat(const double q[4], f128 r[3][3]) {
  for (int k = 0; k < 3; k++) {
    f128 e[3] = {0, 0, 0}, col[3];
    e[k] = 1;
    rotate_hamilton(q, e, col);
    for (int i = 0; i < 3; i++) r[i][k] = col[i];
  }
}

/* Q = sum_k a_k^2 R_:k R_:k^T in __float128. */
static void q_of_rot(const double radii[3], f128 r[3][3], f128 q[6]) {
  int idx = 0;
  for (int i = 0; i < 3; i++)
    for (int j = i; j < 3; j++, idx++) {
      q[idx] = 0;
      for (int k = 0; k < 3; k++) q[idx] += (f128)radii[k] * radii[k] * r[i][k] * r[j][k];
    }
}

static double max_radius2(const double radii[3]) {
  double m = 0;
  for (int k = 0; k < 3; k++) m = fmax(m, radii[k] * radii[k]);
  return m;
}

/* A random quaternion of |q|^2 - 1 uniform in [-dev, dev]. */
static void random_quat(GRand *rng, double dev, double q[4]) {
  double n2 = 0;
  for (int i = 0; i < 4; i++) {
    q[i] = g_rand_double_range(rng, -1, 1);
    n2 += q[i] * q[i];
  }
  double const s = sqrt((1 + g_rand_double_range(rng, -dev, dev)) / n2);
  for (int i = 0; i < 4; i++) q[i] *= s;
}

/* Each entry within u |Q_ij| + 8 u^2 max a^2 of the exact Q of quat / |quat|
 * (include/pw85.h), at aspect ratios to 1e6, for quaternions up to 1e-5 off
 * unit length. */
static void test_quat_accuracy(void) {
  GRand *rng = g_rand_new_with_seed(43);
  double worst = 0;
  for (int n = 0; n < 20000; n++) {
    double quat[4], radii[3], q[6];
    random_quat(rng, n % 2 ? 1e-5 : 1e-15, quat);
    random_radii(rng, n % 3 ? 0.1 : 1e-3, n % 3 ? 10. : 1e3, radii);
    g_assert_cmpint(pw85_ellipsoid_quat(radii, quat, q), ==, PW85_OK);
    f128 r[3][3], ex[6];
    rot_of_quat(quat, r);
    q_of_rot(radii, r, ex);
    double const m = max_radius2(radii);
    for (int i = 0; i < 6; i++) {
      double const err = fabsq_((f128)q[i] - ex[i]) - U * fabsq_(ex[i]);
      worst = fmax(worst, err / (U * U * m));
      if (!(err <= 8 * U * U * m))
        g_error("Q[%d] = %.17g, exact %.17g (%g u^2 max a^2 beyond u |Q_ij|)", i, q[i],
                (double)ex[i], err / (U * U * m));
    }
  }
  g_test_message("largest error beyond u |Q_ij|: %.3g u^2 max a^2", worst);
  g_rand_free(rng);
}

/* Exact cases: the identity quaternion gives diag(a^2), a sphere a^2 I,
 * whatever the quaternion; a quaternion scaled by (1 + 1e-6) the same bits
 * as a rational unit one up to the rounding of the scaled components. */
static void test_quat_exact(void) {
  double const id[4] = {1, 0, 0, 0}, radii[3] = {0.3, 2., 7.}, s[3] = {1.5, 1.5, 1.5};
  double q[6];
  g_assert_cmpint(pw85_ellipsoid_quat(radii, id, q), ==, PW85_OK);
  double const diag[6] = {0.3 * 0.3, 0, 0, 4., 0, 49.};
  for (int i = 0; i < 6; i++) g_assert_cmpfloat(q[i], ==, diag[i]);
  GRand *rng = g_rand_new_with_seed(4);
  for (int n = 0; n < 100; n++) {
    double quat[4];
    random_quat(rng, 1e-6, quat);
    g_assert_cmpint(pw85_ellipsoid_quat(s, quat, q), ==, PW85_OK);
    double const sphere[6] = {2.25, 0, 0, 2.25, 0, 2.25};
    for (int i = 0; i < 6; i++) g_assert_cmpfloat(q[i], ==, sphere[i]);
  }
  g_rand_free(rng);
}

/* Rational unit quaternions p / m (p0^2 + p1^2 + p2^2 + p3^2 = m^2, m a power
 * of two or not): R = M / m^2 with integer M (eq. (O1) of
 * src/core/common/orientation.cpp), Q exact in __float128 for radii^2
 * integers. */
static const int kQuads[][5] = {{1, 1, 1, 1, 2}, {1, 2, 2, 4, 5},  {2, 4, 5, 6, 9},
                                {2, 3, 6, 0, 7}, {1, 2, 8, 10, 13}, {3, 4, 12, 84, 85},
                                {4, 4, 7, 0, 9}, {0, 6, 6, 7, 11},  {-2, 10, 11, 0, 15},
                                {1, 0, 0, 0, 1}, {0, 0, 0, 1, 1},   {5, -1, -3, 1, 6}};

static void exact_rot(const int *p, f128 r[3][3]) {
  f128 const w = p[0], x = p[1], y = p[2], z = p[3], m2 = (f128)p[4] * p[4];
  f128 const mm[3][3] = {{w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y)},
                         {2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x)},
                         {2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z}};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) r[i][j] = mm[i][j] / m2;
}

static void test_quat_rational(void) {
  static const double radii[][3] = {{1, 2, 3}, {1, 1, 5}, {7, 7, 7}, {1e-3, 1, 1e3}, {2, 1, 2}};
  for (size_t iq = 0; iq < G_N_ELEMENTS(kQuads); iq++) {
    int const *p = kQuads[iq];
    double const quat[4] = {(double)p[0] / p[4], (double)p[1] / p[4], (double)p[2] / p[4],
                            (double)p[3] / p[4]};
    f128 r[3][3], rh[3][3];
    exact_rot(p, r);
    /* The Hamilton-product rotation of the rounded components agrees. */
    rot_of_quat(quat, rh);
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) g_assert_cmpfloat(fabsq_(r[i][j] - rh[i][j]), <=, 4 * U);
    for (size_t k = 0; k < G_N_ELEMENTS(radii); k++) {
      double q[6];
      g_assert_cmpint(pw85_ellipsoid_quat(radii[k], quat, q), ==, PW85_OK);
      f128 ex[6];
      q_of_rot(radii[k], rh, ex);
      double const m = max_radius2(radii[k]);
      for (int i = 0; i < 6; i++)
        g_assert_cmpfloat(fabsq_((f128)q[i] - ex[i]), <=, U * fabsq_(ex[i]) + 8 * U * U * m);
      /* Against the rational Q itself: the components are off by u / 2. */
      f128 exr[6];
      q_of_rot(radii[k], r, exr);
      for (int i = 0; i < 6; i++) g_assert_cmpfloat(fabsq_((f128)q[i] - exr[i]), <=, 8 * U * m);
    }
  }
}

/* HOOMD-blue / GSD convention: (cos 45°, 0, 0, sin 45°) turns the body x axis
 * into the lab y axis, so semi-axes (3, 1, 1) give Q = diag(1, 9, 1). */
static void test_quat_hoomd_convention(void) {
  double const c = sqrt(0.5), quat[4] = {c, 0, 0, c}, radii[3] = {3, 1, 1};
  double q[6];
  g_assert_cmpint(pw85_ellipsoid_quat(radii, quat, q), ==, PW85_OK);
  double const ex[6] = {1, 0, 0, 9, 0, 1};
  for (int i = 0; i < 6; i++) g_assert_cmpfloat(fabs(q[i] - ex[i]), <=, 4 * DBL_EPSILON * 9);
  /* LAMMPS: shape = diameters, radii = shape / 2; quaternion (w, i, j, k) */
  double const shape[3] = {6, 2, 2}, half[3] = {shape[0] / 2, shape[1] / 2, shape[2] / 2};
  double ql[6];
  g_assert_cmpint(pw85_ellipsoid_quat(half, quat, ql), ==, PW85_OK);
  for (int i = 0; i < 6; i++) g_assert_cmpfloat(ql[i], ==, q[i]);
}

/* Issue item 5: a body-frame surface point p = (a0 u0, a1 u1, a2 u2), u on
 * the unit sphere, carried to the lab by q p q^* lies on the surface of the
 * Q of pw85_ellipsoid_quat; the columns of the Hamilton R, given to
 * pw85_ellipsoid_rotation, and its rows, given to pw85_ellipsoid, too. */
static void test_convention_surface_points(void) {
  GRand *rng = g_rand_new_with_seed(5);
  double worst = 0;
  for (int n = 0; n < 2000; n++) {
    double quat[4], radii[3], qq[6], qr[6], qe[6], rot[9], axes[9];
    random_quat(rng, 1e-6, quat);
    random_radii(rng, 0.5, 2., radii);
    f128 r[3][3];
    rot_of_quat(quat, r);
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) rot[3 * i + j] = axes[3 * j + i] = (double)r[i][j];
    g_assert_cmpint(pw85_ellipsoid_quat(radii, quat, qq), ==, PW85_OK);
    g_assert_cmpint(pw85_ellipsoid_rotation(radii, rot, qr), ==, PW85_OK);
    g_assert_cmpint(pw85_ellipsoid(radii, axes, qe), ==, PW85_OK);
    for (int t = 0; t < 4; t++) {
      double u[3], nu = 0;
      for (int i = 0; i < 3; i++) {
        u[i] = t < 3 ? (i == t) : g_rand_double_range(rng, -1, 1);
        nu += u[i] * u[i];
      }
      f128 p[3], x[3];
      for (int i = 0; i < 3; i++) p[i] = radii[i] * (u[i] / sqrt(nu));
      rotate_hamilton(quat, p, x);
      long double xl[3] = {(long double)x[0], (long double)x[1], (long double)x[2]};
      /* |p|^2 of the rounded unit u: within 2u of 1. */
      double const *qs[3] = {qq, qr, qe};
      for (int s = 0; s < 3; s++) {
        double const v = fabs((double)xT_inv_x_ld(qs[s], xl) - 1.0);
        worst = fmax(worst, v);
        if (!(v <= 1e-13)) g_error("matrix %d: x^T Q^-1 x - 1 = %g", s, v);
      }
    }
  }
  g_test_message("largest |x^T Q^-1 x - 1|: %.3g", worst);
  g_rand_free(rng);
}

static void test_rotation(void) {
  GRand *rng = g_rand_new_with_seed(6);
  for (int n = 0; n < 1000; n++) {
    double quat[4], radii[3], rot[9], axes[9], q[6], qe[6];
    random_quat(rng, 0, quat);
    random_radii(rng, 0.01, 100., radii);
    f128 r[3][3];
    rot_of_quat(quat, r);
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) rot[3 * i + j] = axes[3 * j + i] = (double)r[i][j];
    g_assert_cmpint(pw85_ellipsoid_rotation(radii, rot, q), ==, PW85_OK);
    g_assert_cmpint(pw85_ellipsoid(radii, axes, qe), ==, PW85_OK);
    for (int i = 0; i < 6; i++) g_assert_cmpfloat(q[i], ==, qe[i]); /* same as rows R^T */
    /* Each entry within a few roundings of its magnitude terms, against the
     * exact Q of the doubles rot. */
    f128 rd[3][3];
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) rd[i][j] = rot[3 * i + j];
    f128 ex[6];
    q_of_rot(radii, rd, ex);
    int idx = 0;
    for (int i = 0; i < 3; i++)
      for (int j = i; j < 3; j++, idx++) {
        double mag = 0;
        for (int k = 0; k < 3; k++)
          mag += radii[k] * radii[k] * fabs(rot[3 * i + k] * rot[3 * j + k]);
        g_assert_cmpfloat(fabsq_((f128)q[idx] - ex[idx]), <=, 6 * U * mag);
      }
    /* A reflection (one column negated) gives the same ellipsoid. */
    for (int i = 0; i < 3; i++) rot[3 * i + 1] = -rot[3 * i + 1];
    double qm[6];
    g_assert_cmpint(pw85_ellipsoid_rotation(radii, rot, qm), ==, PW85_OK);
    for (int i = 0; i < 6; i++) g_assert_cmpfloat(qm[i], ==, q[i]);
  }
  g_rand_free(rng);
}

/* Certificate of an eigen-decomposition (radii, rot) of q in __float128:
 * returns max |rot diag(radii^2) rot^T - q| / ||q|| (||q|| = radii[2]^2, the
 * largest eigenvalue) and, in *orth,
 * max |rot^T rot - I|; checks ascending radii and det rot > 0. */
static double decomposition_error(const double q[6], const double radii[3], const double rot[9],
                                  double *orth) {
  g_assert_true(radii[0] <= radii[1] && radii[1] <= radii[2]);
  f128 r[3][3], rq[6];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) r[i][j] = rot[3 * i + j];
  q_of_rot(radii, r, rq);
  double const m = radii[2] * radii[2];
  double e = 0, o = 0;
  for (int i = 0; i < 6; i++) e = fmax(e, fabsq_(rq[i] - q[i]));
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      f128 s = 0;
      for (int k = 0; k < 3; k++) s += r[k][i] * r[k][j];
      o = fmax(o, fabsq_(s - (i == j)));
    }
  f128 const det = r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1]) -
                   r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0]) +
                   r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0]);
  g_assert_cmpfloat(fabsq_(det - 1), <=, 16 * U);
  *orth = o;
  return e / m;
}

/* The quaternion written agrees with rot (Hamilton products), w >= 0. */
static void check_quat_of_rot(const double quat[4], const double rot[9]) {
  g_assert_cmpfloat(quat[0], >=, 0.);
  double n2 = 0;
  for (int i = 0; i < 4; i++) n2 += quat[i] * quat[i];
  g_assert_cmpfloat(fabs(n2 - 1), <=, 8 * U);
  f128 r[3][3];
  rot_of_quat(quat, r);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double const d = fabsq_(r[i][j] - rot[3 * i + j]);
      if (!(d <= 16 * U)) g_error("R[%d][%d] of quat off by %g u", i, j, d / U);
    }
}

/* Random Q (random rotations, semi-axes of aspect to 1e4, and random SPD
 * matrices of condition number to 1e12): backward error within 10 u ||q||
 * and orthonormality within 8 u in __float128 (include/pw85.h), and the
 * quaternion consistent with rot. */
static void test_axes_random(void) {
  GRand *rng = g_rand_new_with_seed(9);
  double we = 0, wo = 0;
  for (int n = 0; n < 20000; n++) {
    double q[6], radii[3], rot[9], quat[4];
    if (n % 2) {
      random_spd(rng, n % 4 == 1 ? 1e4 : 1e12, q);
    } else {
      double axes[9], r0[3];
      random_axes(rng, axes);
      random_radii(rng, 0.01, 100., r0);
      make_q(r0, axes, q);
    }
    g_assert_cmpint(pw85_ellipsoid_axes(q, radii, rot, quat), ==, PW85_OK);
    double orth;
    double const e = decomposition_error(q, radii, rot, &orth);
    we = fmax(we, e / U);
    wo = fmax(wo, orth / U);
    if (!(e <= 10 * U && orth <= 8 * U))
      g_error("backward error %g u, orthonormality %g u", e / U, orth / U);
    check_quat_of_rot(quat, rot);
    /* Sign convention of columns 0 and 1. */
    for (int k = 0; k < 2; k++) {
      int big = 0;
      for (int i = 1; i < 3; i++)
        if (fabs(rot[3 * i + k]) > fabs(rot[3 * big + k])) big = i;
      g_assert_cmpfloat(rot[3 * big + k], >, 0.);
    }
  }
  g_test_message("largest backward error %.3g u ||q||, orthonormality %.3g u", we, wo);
  g_rand_free(rng);
}

/* Exact rationals: Q = R diag(a^2) R^T with the rational R of kQuads and
 * integer a^2, rounded once to doubles: the semi-axes squared within
 * 4 u ||Q|| of the exact a^2 (Weyl: u/2 for the rounding of Q, u for that of
 * the semi-axes), the axes within 4 u ||Q|| / gap of the exact ones. */
static void test_axes_rational(void) {
  static const double a2[][3] = {{1, 4, 9}, {1, 2, 3}, {1, 100, 10000}, {5, 6, 1e6}};
  double worst_l = 0, worst_v = 0;
  for (size_t iq = 0; iq < G_N_ELEMENTS(kQuads); iq++) {
    f128 r[3][3];
    exact_rot(kQuads[iq], r);
    for (size_t k = 0; k < G_N_ELEMENTS(a2); k++) {
      f128 ex[6];
      int idx = 0;
      for (int i = 0; i < 3; i++)
        for (int j = i; j < 3; j++, idx++) {
          ex[idx] = 0;
          for (int l = 0; l < 3; l++) ex[idx] += (f128)a2[k][l] * r[i][l] * r[j][l];
        }
      double q[6], radii[3], rot[9], m = 0;
      for (int i = 0; i < 6; i++) {
        q[i] = (double)ex[i];
        m = fmax(m, fabs(q[i]));
      }
      g_assert_cmpint(pw85_ellipsoid_axes(q, radii, rot, NULL), ==, PW85_OK);
      for (int l = 0; l < 3; l++) {
        double const d = fabsq_((f128)radii[l] * radii[l] - a2[k][l]);
        worst_l = fmax(worst_l, d / (U * a2[k][2]));
        g_assert_cmpfloat(d, <=, 4 * U * a2[k][2]);
        double gap = INFINITY;
        for (int o = 0; o < 3; o++)
          if (o != l) gap = fmin(gap, fabs(a2[k][o] - a2[k][l]));
        /* sin of the angle between rot column l and the exact axis l: the
         * norm of their cross product */
        f128 c[3];
        for (int i = 0; i < 3; i++) {
          int const i1 = (i + 1) % 3, i2 = (i + 2) % 3;
          c[i] = rot[3 * i1 + l] * r[i2][l] - rot[3 * i2 + l] * r[i1][l];
        }
        double const ang = sqrt((double)(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]));
        worst_v = fmax(worst_v, ang * gap / (U * a2[k][2]));
        if (!(ang <= 4 * U * a2[k][2] / gap))
          g_error("quad %d, a^2 set %d: axis %d off by %g", (int)iq, (int)k, l, ang);
      }
    }
  }
  g_test_message("eigenvalues: %.3g u ||Q||; axes: %.3g u ||Q|| / gap", worst_l, worst_v);
}

/* Repeated semi-axes: a sphere gives rot = I and quat = (1, 0, 0, 0)
 * exactly; a diagonal Q the coordinate axes (signs by the convention);
 * spheroids a valid decomposition with the distinct axis along n. */
static void test_axes_repeated(void) {
  double const sphere[6] = {2.25, 0, 0, 2.25, 0, 2.25};
  double radii[3], rot[9], quat[4];
  g_assert_cmpint(pw85_ellipsoid_axes(sphere, radii, rot, quat), ==, PW85_OK);
  for (int i = 0; i < 3; i++) g_assert_cmpfloat(radii[i], ==, 1.5);
  for (int i = 0; i < 9; i++) g_assert_cmpfloat(rot[i], ==, (i % 4 == 0));
  double const qid[4] = {1, 0, 0, 0};
  for (int i = 0; i < 4; i++) g_assert_cmpfloat(quat[i], ==, qid[i]);
  /* diag(9, 4, 1): ascending 1, 4, 9 along e2, e1 and (det +1) -e0. */
  double const diag[6] = {9, 0, 0, 4, 0, 1};
  g_assert_cmpint(pw85_ellipsoid_axes(diag, radii, rot, quat), ==, PW85_OK);
  double const er[3] = {1, 2, 3}, erot[9] = {0, 0, -1, 0, 1, 0, 1, 0, 0};
  for (int i = 0; i < 3; i++) g_assert_cmpfloat(radii[i], ==, er[i]);
  for (int i = 0; i < 9; i++) g_assert_cmpfloat(rot[i], ==, erot[i]);
  check_quat_of_rot(quat, rot);
  GRand *rng = g_rand_new_with_seed(10);
  double we = 0;
  for (int n = 0; n < 5000; n++) {
    double axes[9], r0[3], q[6], orth;
    random_axes(rng, axes);
    random_radii(rng, 0.01, 100., r0);
    double const a = r0[0], c = r0[1];
    pw85_spheroid(a, c, axes, q);
    g_assert_cmpint(pw85_ellipsoid_axes(q, radii, rot, quat), ==, PW85_OK);
    double const e = decomposition_error(q, radii, rot, &orth);
    we = fmax(we, e / U);
    g_assert_cmpfloat(e, <=, 10 * U);
    g_assert_cmpfloat(orth, <=, 8 * U);
    check_quat_of_rot(quat, rot);
    int const l = c < a ? 0 : 2; /* the column of c */
    g_assert_cmpfloat(fabs(radii[l] - c), <=, 8 * U * fmax(a, c) * fmax(a / c, c / a));
    double dot = 0;
    for (int i = 0; i < 3; i++) dot += rot[3 * i + l] * axes[i];
    g_assert_cmpfloat(fabs(fabs(dot) - 1), <=, 1e-10);
  }
  g_test_message("spheroids: largest backward error %.3g u ||q||", we);
  g_rand_free(rng);
}

/* radii + quat -> Q -> radii' (ascending) + quat', rot' -> the same Q. */
static void test_round_trip(void) {
  GRand *rng = g_rand_new_with_seed(11);
  double worst = 0;
  for (int n = 0; n < 5000; n++) {
    double quat[4], r0[3], q[6], radii[3], rot[9], quat2[4], q2[6], q3[6];
    random_quat(rng, 1e-7, quat);
    random_radii(rng, 0.1, 10., r0);
    g_assert_cmpint(pw85_ellipsoid_quat(r0, quat, q), ==, PW85_OK);
    g_assert_cmpint(pw85_ellipsoid_axes(q, radii, rot, quat2), ==, PW85_OK);
    double s[3] = {r0[0], r0[1], r0[2]};
    for (int i = 0; i < 3; i++)
      for (int j = i + 1; j < 3; j++)
        if (s[j] < s[i]) {
          double const t = s[i];
          s[i] = s[j];
          s[j] = t;
        }
    for (int i = 0; i < 3; i++) g_assert_cmpfloat(fabs(radii[i] - s[i]), <=, 1e-12 * s[2]);
    g_assert_cmpint(pw85_ellipsoid_quat(radii, quat2, q2), ==, PW85_OK);
    g_assert_cmpint(pw85_ellipsoid_rotation(radii, rot, q3), ==, PW85_OK);
    double m = 0;
    for (int i = 0; i < 6; i++) m = fmax(m, fabs(q[i]));
    for (int i = 0; i < 6; i++) {
      double const e = fmax(fabs(q2[i] - q[i]), fabs(q3[i] - q[i])) / (U * m);
      worst = fmax(worst, e);
      if (!(e <= 16)) g_error("round trip: Q[%d] off by %g u max|Q|", i, e);
    }
  }
  g_test_message("round trip: largest error %.3g u max|Q|", worst);
  g_rand_free(rng);
}

static void assert_all_nan(const double *x, int n);

/* Nearly singular matrices (eigenvalue ratios 1 ... 1e-20, random axes,
 * entries rounded): whenever pw85_ellipsoid_axes returns PW85_OK, its radii,
 * rot and quat are accepted back by pw85_ellipsoid_rotation and
 * pw85_ellipsoid_quat (include/pw85.h); otherwise the status is
 * PW85_ERR_INACCURATE (q positive definite, eigenvalue below the sweeps'
 * accuracy) or PW85_ERR_NOT_SPD. Both OK and INACCURATE must occur. */
static void test_axes_accepted_back(void) {
  GRand *rng = g_rand_new_with_seed(55);
  int ok = 0, inaccurate = 0, refused = 0;
  for (int n = 0; n < 20000; n++) {
    double axes[9], q[6], radii[3], rot[9], quat[4], q2[6], q3[6];
    random_axes(rng, axes);
    double const r[3] = {1.0, g_rand_double_range(rng, 0.1, 1.0),
                         pow(10.0, g_rand_double_range(rng, -10.0, 0.0))};
    if (pw85_ellipsoid(r, axes, q) != PW85_OK) continue;
    int const s = pw85_ellipsoid_axes(q, radii, rot, quat);
    if (s == PW85_OK) {
      ok++;
      g_assert_cmpint(pw85_ellipsoid_rotation(radii, rot, q2), ==, PW85_OK);
      g_assert_cmpint(pw85_ellipsoid_quat(radii, quat, q3), ==, PW85_OK);
    } else if (s == PW85_ERR_INACCURATE) {
      inaccurate++;
      assert_all_nan(radii, 3);
    } else {
      g_assert_cmpint(s, ==, PW85_ERR_NOT_SPD);
      refused++;
    }
  }
  g_test_message("%d PW85_OK, %d PW85_ERR_INACCURATE, %d PW85_ERR_NOT_SPD", ok, inaccurate,
                 refused);
  g_assert_cmpint(ok, >, 10000);
  g_assert_cmpint(inaccurate, >, 0);
  g_rand_free(rng);
}

/* The constructors' statuses as include/pw85.h states them: PW85_ERR_NOT_SPD
 * only for a radius <= 0. Radii 2^500, 2^-500, 1 with quat = 1: the exact
 * diagonal, as pw85_ellipsoid_rotation with R = I gives it. The positive
 * radii {0x1.9c77c2b8fa4bcp-106, 0x1.367e751f48531p+0, 0x1.5b45212ad5b4cp+4}
 * with random axes: PW85_OK (q then accepted by every call) or
 * PW85_ERR_RANGE (q rounded to double not positive definite), never
 * PW85_ERR_NOT_SPD. */
static void test_constructor_statuses(void) {
  double const wide[3] = {0x1p500, 0x1p-500, 1.0}, one[4] = {1, 0, 0, 0};
  double const ident[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  double q[6], q2[6];
  g_assert_cmpint(pw85_ellipsoid_quat(wide, one, q), ==, PW85_OK);
  g_assert_cmpint(pw85_ellipsoid_rotation(wide, ident, q2), ==, PW85_OK);
  double const diag[6] = {0x1p1000, 0, 0, 0x1p-1000, 0, 1};
  for (int i = 0; i < 6; i++) {
    g_assert_cmpfloat(q[i], ==, diag[i]);
    g_assert_cmpfloat(q2[i], ==, diag[i]);
  }
  double const tiny[3] = {0x1.9c77c2b8fa4bcp-106, 0x1.367e751f48531p+0, 0x1.5b45212ad5b4cp+4};
  GRand *rng = g_rand_new_with_seed(7);
  int ok = 0, range = 0;
  double const r12[3] = {30.0, 0.0, 0.0};
  for (int n = 0; n < 2000; n++) {
    double axes[9], quat[4];
    random_axes(rng, axes);
    random_quat(rng, 0.0, quat);
    int const s1 = pw85_ellipsoid(tiny, axes, q);
    int const s2 = pw85_ellipsoid_quat(tiny, quat, q2);
    g_assert_true(s1 == PW85_OK || s1 == PW85_ERR_RANGE);
    g_assert_true(s2 == PW85_OK || s2 == PW85_ERR_RANGE);
    if (s1 == PW85_OK) g_assert_cmpint(pw85_overlap(r12, q, q), >=, 0);
    if (s2 == PW85_OK) g_assert_cmpint(pw85_overlap(r12, q2, q2), >=, 0);
    ok += (s1 == PW85_OK) + (s2 == PW85_OK);
    range += (s1 == PW85_ERR_RANGE) + (s2 == PW85_ERR_RANGE);
  }
  g_test_message("radii of ratio 2^-110: %d PW85_OK, %d PW85_ERR_RANGE", ok, range);
  g_assert_cmpint(range, >, 0);
  g_assert_cmpint(pw85_ellipsoid(tiny, ident, q), ==, PW85_OK);
  g_rand_free(rng);
}

static void assert_all_nan(const double *x, int n) {
  for (int i = 0; i < n; i++) g_assert_true(isnan(x[i]));
}

static void test_bad_input(void) {
  double const radii[3] = {1, 2, 3}, neg_r[3] = {1, -2, 3}, nan_r[3] = {1, NAN, 3},
               huge_r[3] = {1e200, 1, 1};
  double const unit[4] = {0.5, 0.5, 0.5, 0.5}, zero[4] = {0, 0, 0, 0},
               off[4] = {0.5, 0.5, 0.5, 0.5 * (1 + 3e-5)}, inf_q[4] = {INFINITY, 0, 0, 0},
               ok_f32[4] = {0.5, 0.5, 0.5, 0.5 * (1 + 4e-6)};
  struct {
    const double *r, *qt;
    int status;
  } const qc[] = {
      {NULL, unit, PW85_ERR_INVALID_ARGUMENT},  {radii, NULL, PW85_ERR_INVALID_ARGUMENT},
      {nan_r, unit, PW85_ERR_INVALID_ARGUMENT}, {radii, inf_q, PW85_ERR_INVALID_ARGUMENT},
      {neg_r, unit, PW85_ERR_NOT_SPD},          {radii, zero, PW85_ERR_NOT_ORTHONORMAL},
      {radii, off, PW85_ERR_NOT_ORTHONORMAL},   {huge_r, unit, PW85_ERR_RANGE}};
  for (size_t k = 0; k < G_N_ELEMENTS(qc); k++) {
    double q[6] = {1, 2, 3, 4, 5, 6};
    g_assert_cmpint(pw85_ellipsoid_quat(qc[k].r, qc[k].qt, q), ==, qc[k].status);
    assert_all_nan(q, 6);
  }
  double q[6];
  g_assert_cmpint(pw85_ellipsoid_quat(radii, unit, NULL), ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_ellipsoid_quat(radii, ok_f32, q), ==, PW85_OK);

  double const id[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, skew[9] = {1, 0, 0, 1e-9, 1, 0, 0, 0, 1},
               almost[9] = {1, 0, 0, 1e-11, 1, 0, 0, 0, 1},
               nan_rot[9] = {1, 0, 0, 0, NAN, 0, 0, 0, 1};
  struct {
    const double *r, *rot;
    int status;
  } const rc[] = {{NULL, id, PW85_ERR_INVALID_ARGUMENT},  {radii, NULL, PW85_ERR_INVALID_ARGUMENT},
                  {radii, nan_rot, PW85_ERR_INVALID_ARGUMENT}, {neg_r, id, PW85_ERR_NOT_SPD},
                  {radii, skew, PW85_ERR_NOT_ORTHONORMAL},  {huge_r, id, PW85_ERR_RANGE}};
  for (size_t k = 0; k < G_N_ELEMENTS(rc); k++) {
    double qq[6] = {1, 2, 3, 4, 5, 6};
    g_assert_cmpint(pw85_ellipsoid_rotation(rc[k].r, rc[k].rot, qq), ==, rc[k].status);
    assert_all_nan(qq, 6);
  }
  g_assert_cmpint(pw85_ellipsoid_rotation(radii, id, NULL), ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_ellipsoid_rotation(radii, almost, q), ==, PW85_OK);

  double const good[6] = {4, 1, 0, 3, 0, 1}, indef[6] = {1, 2, 0, 1, 0, 1},
               zero_q[6] = {0, 0, 0, 0, 0, 0}, nan_q[6] = {1, 0, 0, NAN, 0, 1};
  struct {
    const double *q;
    int status;
  } const ac[] = {{NULL, PW85_ERR_INVALID_ARGUMENT}, {nan_q, PW85_ERR_INVALID_ARGUMENT},
                  {indef, PW85_ERR_NOT_SPD}, {zero_q, PW85_ERR_NOT_SPD}};
  for (size_t k = 0; k < G_N_ELEMENTS(ac); k++) {
    double r[3] = {1, 2, 3}, rot[9] = {0}, qt[4] = {1, 2, 3, 4};
    g_assert_cmpint(pw85_ellipsoid_axes(ac[k].q, r, rot, qt), ==, ac[k].status);
    assert_all_nan(r, 3);
    assert_all_nan(rot, 9);
    assert_all_nan(qt, 4);
  }
  double rot[9] = {0}, qt[4] = {0};
  g_assert_cmpint(pw85_ellipsoid_axes(good, NULL, rot, qt), ==, PW85_ERR_INVALID_ARGUMENT);
  assert_all_nan(rot, 9);
  assert_all_nan(qt, 4);
  /* rot and quat may be NULL: radii as with them. */
  double r1[3], r2[3];
  g_assert_cmpint(pw85_ellipsoid_axes(good, r1, NULL, NULL), ==, PW85_OK);
  g_assert_cmpint(pw85_ellipsoid_axes(good, r2, rot, qt), ==, PW85_OK);
  for (int i = 0; i < 3; i++) g_assert_cmpfloat(r1[i], ==, r2[i]);
}

int main(int argc, char **argv) {
  g_test_init(&argc, &argv, NULL);
  g_test_add_func("/pw85_ellipsoid_quat/accuracy", test_quat_accuracy);
  g_test_add_func("/pw85_ellipsoid_quat/exact", test_quat_exact);
  g_test_add_func("/pw85_ellipsoid_quat/rational", test_quat_rational);
  g_test_add_func("/pw85_ellipsoid_quat/hoomd_convention", test_quat_hoomd_convention);
  g_test_add_func("/pw85_ellipsoid_quat/surface_points", test_convention_surface_points);
  g_test_add_func("/pw85_ellipsoid_rotation/random", test_rotation);
  g_test_add_func("/pw85_ellipsoid_axes/random", test_axes_random);
  g_test_add_func("/pw85_ellipsoid_axes/rational", test_axes_rational);
  g_test_add_func("/pw85_ellipsoid_axes/repeated", test_axes_repeated);
  g_test_add_func("/pw85_ellipsoid_axes/round_trip", test_round_trip);
  g_test_add_func("/pw85_ellipsoid_axes/accepted_back", test_axes_accepted_back);
  g_test_add_func("/pw85_ellipsoid/statuses", test_constructor_statuses);
  g_test_add_func("/pw85_ellipsoid_axes/bad_input", test_bad_input);
  return g_test_run();
}
