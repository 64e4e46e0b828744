/* Quadratic forms of ellipsoids: pw85_spheroid (pw85 1.0) and pw85_ellipsoid. */
#include <float.h>
#include <math.h>

#include <pw85.h>

#include "testutil.h"

/* x^T Q^{-1} x == 1 for the tip of every semi-axis. */
static void assert_on_surface(const double q[6], const double x[3], double tol) {
  long double xl[3] = {x[0], x[1], x[2]};
  long double const v = xT_inv_x_ld(q, xl);
  g_assert_cmpfloat(fabs((double)v - 1.0), <=, tol);
}

static void test_spheroid_tutorial(void) {
  /* The matrices printed by pw85 1.0's tutorial. */
  double const n1[3] = {0., 0., 1.}, n2[3] = {1., 0., 0.};
  double q1[6], q2[6];
  pw85_spheroid(10., 0.1, n1, q1);
  pw85_spheroid(0.5, 5., n2, q2);
  double const e1[6] = {100., 0., 0., 100., 0., 0.01};
  double const e2[6] = {25., 0., 0., 0.25, 0., 0.25};
  for (int i = 0; i < 6; i++) {
    g_assert_cmpfloat(fabs(q1[i] - e1[i]), <=, 4 * DBL_EPSILON * 100.);
    g_assert_cmpfloat(fabs(q2[i] - e2[i]), <=, 4 * DBL_EPSILON * 25.);
  }
}

static void test_spheroid_random(void) {
  GRand *rng = g_rand_new_with_seed(7);
  for (int k = 0; k < 1000; k++) {
    double axes[9], radii[3];
    random_axes(rng, axes);
    random_radii(rng, 0.01, 100., radii);
    double const a = radii[0], c = radii[1];
    double const *n = axes; /* first row: axis of revolution */
    double q[6];
    pw85_spheroid(a, c, n, q);
    /* error of x^T Q^{-1} x ~ eps * cond(Q) = eps (a/c)^2 */
    double const tol = 1024 * DBL_EPSILON * fmax(a / c, c / a) * fmax(a / c, c / a);
    double x[3];
    for (int i = 0; i < 3; i++) x[i] = c * axes[i];
    assert_on_surface(q, x, tol);
    for (int row = 1; row < 3; row++) {
      for (int i = 0; i < 3; i++) x[i] = a * axes[3 * row + i];
      assert_on_surface(q, x, tol);
    }
  }
  g_rand_free(rng);
}

static void test_spheroid_bad_input(void) {
  double const n[3] = {0., 0., 1.}, zero[3] = {0., 0., 0.}, nan_n[3] = {NAN, 0., 1.};
  struct {
    double a, c;
    const double *n;
  } const cases[] = {{0., 1., n},  {1., -1., n},      {NAN, 1., n},
                     {1., INFINITY, n}, {1., 1., zero}, {1., 1., nan_n}, {1., 1., NULL}};
  for (size_t k = 0; k < G_N_ELEMENTS(cases); k++) {
    double q[6] = {1, 2, 3, 4, 5, 6};
    pw85_spheroid(cases[k].a, cases[k].c, cases[k].n, q);
    for (int i = 0; i < 6; i++) g_assert_true(isnan(q[i]));
  }
  pw85_spheroid(1., 1., n, NULL); /* must not crash */
}

/* Q = a^2 (I - n n^T) + c^2 n n^T (section 3.1, eq. (2)) for unit axes n of
 * rational components (Pythagorean quadruples p/m, p0^2 + p1^2 + p2^2 = m^2),
 * against the exact Q: a^2 and c^2 of doubles are exact in __float128, the
 * projector entries are the rationals (m^2 delta_ij - p_i p_j) / m^2 and
 * p_i p_j / m^2. Per entry the error is bounded relative to its magnitude
 * terms a^2 |P_ij| + c^2 |N_ij| (the axis given as doubles is off by half an
 * ulp per component); no cancellation between a^2 and c^2 at any aspect. */
static void test_spheroid_flat_exact(void) {
  static const int quads[][4] = {{0, 0, 1, 1}, {1, 2, 2, 3}, {2, 3, 6, 7}, {1, 4, 8, 9},
                                 {2, 6, 9, 11}, {6, 2, 3, 7}, {-2, 1, 2, 3}, {4, -4, 7, 9}};
  static const double ac[][2] = {{1e4, 1e-4}, {1., 1e-9}, {1e8, 1e-8}, {1e-8, 1e8},
                                 {3., 2.},    {1., 1.},   {1e150, 1e-150}, {0.7, 0.7e-12}};
  double worst = 0.;
  for (size_t iq = 0; iq < G_N_ELEMENTS(quads); iq++) {
    int const *p = quads[iq];
    double const m = p[3];
    double const n[3] = {p[0] / m, p[1] / m, p[2] / m};
    for (size_t k = 0; k < G_N_ELEMENTS(ac); k++) {
      double const a = ac[k][0], c = ac[k][1];
      double q[6];
      pw85_spheroid(a, c, n, q);
      __float128 const a2 = (__float128)a * a, c2 = (__float128)c * c;
      int idx = 0;
      for (int i = 0; i < 3; i++) {
        for (int j = i; j < 3; j++, idx++) {
          __float128 const nn = (__float128)(p[i] * p[j]) / (m * m);
          __float128 const pp = (i == j ? 1 : 0) - nn;
          __float128 const exact = a2 * pp + c2 * nn;
          __float128 const mag = a2 * (pp < 0 ? -pp : pp) + c2 * (nn < 0 ? -nn : nn);
          double const err =
              mag == 0 ? fabs(q[idx]) : (double)(((__float128)q[idx] - exact) / mag);
          worst = fmax(worst, fabs(err));
          if (!(fabs(err) <= 4 * DBL_EPSILON))
            g_error("a=%g c=%g n=(%d,%d,%d)/%d Q[%d]=%.17g exact=%.17g err=%.3g eps", a, c,
                    p[0], p[1], p[2], p[3], idx, q[idx], (double)exact, err / DBL_EPSILON);
        }
      }
    }
  }
  g_test_message("largest error: %.3g eps of the magnitude terms", worst / DBL_EPSILON);
  /* The cases of the issue, axis z: Q22 = c^2 rounded once. */
  double const z[3] = {0., 0., 1.};
  double q[6];
  pw85_spheroid(1e4, 1e-4, z, q);
  g_assert_cmpfloat(q[5], ==, 1e-4 * 1e-4);
  pw85_spheroid(1., 1e-9, z, q);
  g_assert_cmpfloat(q[5], ==, 1e-9 * 1e-9);
  pw85_spheroid(1e8, 1e-8, z, q);
  g_assert_cmpfloat(q[5], ==, 1e-8 * 1e-8);
}

/* n need not be unit: Q is that of the spheroid of axis n / |n|. */
static void test_spheroid_non_unit_axis(void) {
  double const n[3] = {1., 2., 2.}, tiny[3] = {0x1p-700, 0x1p-699, 0x1p-699};
  double const unit[3] = {1. / 3., 2. / 3., 2. / 3.};
  double q[6], qt[6], qu[6];
  pw85_spheroid(2., 0.5, n, q);
  pw85_spheroid(2., 0.5, tiny, qt);
  pw85_spheroid(2., 0.5, unit, qu);
  for (int i = 0; i < 6; i++) {
    g_assert_cmpfloat(q[i], ==, qt[i]);
    g_assert_cmpfloat(fabs(q[i] - qu[i]), <=, 4 * DBL_EPSILON * 4.);
  }
}

static void test_ellipsoid_random(void) {
  GRand *rng = g_rand_new_with_seed(8);
  for (int k = 0; k < 1000; k++) {
    double axes[9], radii[3], q[6];
    random_axes(rng, axes);
    random_radii(rng, 0.1, 10., radii);
    g_assert_cmpint(pw85_ellipsoid(radii, axes, q), ==, PW85_OK);
    for (int row = 0; row < 3; row++) {
      double x[3];
      for (int i = 0; i < 3; i++) x[i] = radii[row] * axes[3 * row + i];
      assert_on_surface(q, x, 1e-12);
    }
  }
  g_rand_free(rng);
}

/* A spheroid is an ellipsoid with two equal radii. */
static void test_ellipsoid_matches_spheroid(void) {
  double const s = 1.0 / sqrt(2.0);
  double const axes[9] = {s, s, 0., -s, s, 0., 0., 0., 1.};
  double const radii[3] = {3., 0.5, 0.5};
  double q[6], qs[6];
  g_assert_cmpint(pw85_ellipsoid(radii, axes, q), ==, PW85_OK);
  pw85_spheroid(0.5, 3., axes, qs);
  for (int i = 0; i < 6; i++) g_assert_cmpfloat(fabs(q[i] - qs[i]), <=, 16 * DBL_EPSILON * 9.);
}

static void test_ellipsoid_bad_input(void) {
  double const axes[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  double const skew[9] = {1, 1e-9, 0, 0, 1, 0, 0, 0, 1};
  double const nonunit[9] = {1.001, 0, 0, 0, 1, 0, 0, 0, 1};
  double const nan_axes[9] = {1, 0, 0, 0, NAN, 0, 0, 0, 1};
  double const radii[3] = {1, 2, 3}, zero_r[3] = {1, 0, 3}, neg_r[3] = {1, 2, -3},
               nan_r[3] = {1, NAN, 3}, inf_r[3] = {INFINITY, 1, 1};
  struct {
    const double *radii, *axes;
    int status;
  } const cases[] = {
      {NULL, axes, PW85_ERR_INVALID_ARGUMENT},   {radii, NULL, PW85_ERR_INVALID_ARGUMENT},
      {nan_r, axes, PW85_ERR_INVALID_ARGUMENT},  {inf_r, axes, PW85_ERR_INVALID_ARGUMENT},
      {radii, nan_axes, PW85_ERR_INVALID_ARGUMENT}, {zero_r, axes, PW85_ERR_NOT_SPD},
      {neg_r, axes, PW85_ERR_NOT_SPD},           {radii, skew, PW85_ERR_NOT_ORTHONORMAL},
      {radii, nonunit, PW85_ERR_NOT_ORTHONORMAL},
  };
  for (size_t k = 0; k < G_N_ELEMENTS(cases); k++) {
    double q[6] = {1, 2, 3, 4, 5, 6};
    g_assert_cmpint(pw85_ellipsoid(cases[k].radii, cases[k].axes, q), ==, cases[k].status);
    for (int i = 0; i < 6; i++) g_assert_true(isnan(q[i]));
  }
  g_assert_cmpint(pw85_ellipsoid(radii, axes, NULL), ==, PW85_ERR_INVALID_ARGUMENT);
  /* Axes orthonormal to within 1e-11 are accepted. */
  double const almost[9] = {1, 1e-11, 0, 0, 1, 0, 0, 0, 1};
  double q[6];
  g_assert_cmpint(pw85_ellipsoid(radii, almost, q), ==, PW85_OK);
  /* Extreme but valid sizes. */
  double const tiny[3] = {1e-8, 1e-8, 1e-8}, huge[3] = {1e8, 1e8, 1e8};
  g_assert_cmpint(pw85_ellipsoid(tiny, axes, q), ==, PW85_OK);
  g_assert_cmpfloat(rel_error(q[0], 1e-16), <=, 2 * DBL_EPSILON);
  g_assert_cmpint(pw85_ellipsoid(huge, axes, q), ==, PW85_OK);
  g_assert_cmpfloat(rel_error(q[5], 1e16), <=, 2 * DBL_EPSILON);
}

/* Scale sweep (docs/stability.md, "Accepted input ranges"): radii 2^k times
 * fixed ones, k = -1074..1023. pw85_ellipsoid: PW85_OK with Q = 2^2k Q0
 * within 2 eps per entry of its magnitude while every radius^2 lies in
 * [DBL_MIN, DBL_MAX], PW85_ERR_RANGE (q NaN) otherwise. pw85_spheroid:
 * 2^2k Q0 (rounded once where subnormal) or NaN exactly when an entry
 * overflows or a diagonal entry rounds to 0. */
static void test_ellipsoid_extreme_scale(void) {
  double const axes[9] = {0.6, 0.8, 0, -0.8, 0.6, 0, 0, 0, 1};
  double const r0[3] = {1.5, 0.75, 1.}, n[3] = {0.6, 0., 0.8};
  double q0[6], s0[6];
  g_assert_cmpint(pw85_ellipsoid(r0, axes, q0), ==, PW85_OK);
  pw85_spheroid(1.5, 0.75, n, s0);
  for (int k = -1074; k <= 1023; k++) {
    double radii[3], q[6];
    int in = 1;
    for (int i = 0; i < 3; i++) {
      radii[i] = ldexp(r0[i], k);
      long double const a2 = (long double)radii[i] * radii[i];
      in = in && a2 >= DBL_MIN && a2 <= DBL_MAX;
    }
    int const s = pw85_ellipsoid(radii, axes, q);
    if (s != (in ? PW85_OK : PW85_ERR_RANGE)) g_error("pw85_ellipsoid, k = %d: status %d", k, s);
    for (int i = 0; i < 6; i++) {
      if (!in) {
        g_assert_true(isnan(q[i]));
        continue;
      }
      long double const ex = ldexpl(q0[i], 2 * k);
      if (!(fabsl(q[i] - ex) <= 2 * DBL_EPSILON * ldexpl(2.25L, 2 * k) + 0x1p-1074))
        g_error("pw85_ellipsoid, k = %d: Q[%d] = %g, expected %Lg", k, i, q[i], ex);
    }
    double sq[6];
    pw85_spheroid(radii[0], radii[1], n, sq);
    int overflow = 0, zero = 0;
    for (int i = 0; i < 6; i++) overflow = overflow || fabsl(ldexpl(s0[i], 2 * k)) > DBL_MAX;
    for (int i = 0; i < 6; i += (i == 0 ? 3 : 2))
      zero = zero || ldexpl(s0[i], 2 * k) < 0x1p-1075L;
    for (int i = 0; i < 6; i++) {
      if (overflow || zero) {
        g_assert_true(isnan(sq[i]));
        continue;
      }
      long double const ex = ldexpl(s0[i], 2 * k);
      if (!(fabsl(sq[i] - ex) <= 4 * DBL_EPSILON * ldexpl(2.25L, 2 * k) + 0x1p-1073))
        g_error("pw85_spheroid, k = %d: Q[%d] = %g, expected %Lg", k, i, sq[i], ex);
    }
  }
}

int main(int argc, char **argv) {
  g_test_init(&argc, &argv, NULL);
  g_test_add_func("/pw85_spheroid/tutorial", test_spheroid_tutorial);
  g_test_add_func("/pw85_spheroid/random", test_spheroid_random);
  g_test_add_func("/pw85_spheroid/bad_input", test_spheroid_bad_input);
  g_test_add_func("/pw85_spheroid/flat_exact", test_spheroid_flat_exact);
  g_test_add_func("/pw85_spheroid/non_unit_axis", test_spheroid_non_unit_axis);
  g_test_add_func("/pw85_ellipsoid/random", test_ellipsoid_random);
  g_test_add_func("/pw85_ellipsoid/matches_spheroid", test_ellipsoid_matches_spheroid);
  g_test_add_func("/pw85_ellipsoid/bad_input", test_ellipsoid_bad_input);
  g_test_add_func("/pw85_ellipsoid/extreme_scale", test_ellipsoid_extreme_scale);
  return g_test_run();
}
