/* pw85_contact_function (pw85 1.0's algorithm) against published values,
 * closed forms, long-double maximisation, and the geometric meaning of its
 * output (pw85 documentation, section 2.1.1 and chapter 6). */
#include <float.h>
#include <math.h>

#include <pw85.h>

#include "testutil.h"

static void tutorial_pair(double r12[3], double q1[6], double q2[6]) {
  double const x1[3] = {-0.5, 0.4, -0.7}, x2[3] = {0.2, -0.3, 0.4};
  double const n1[3] = {0., 0., 1.}, n2[3] = {1., 0., 0.};
  for (int i = 0; i < 3; i++) r12[i] = x2[i] - x1[i];
  pw85_spheroid(10., 0.1, n1, q1);
  pw85_spheroid(0.5, 5., n2, q2);
}

/* Values published by pw85 1.0 for its tutorial. */
static void test_tutorial(void) {
  double r12[3], q1[6], q2[6], out[2];
  tutorial_pair(r12, q1, q2);
  g_assert_cmpint(pw85_contact_function(r12, q1, q2, out), ==, PW85_OK);
  g_assert_cmpfloat(rel_error(out[0], 3.362706040638343), <=, 1e-12);
  g_assert_cmpfloat(rel_error(out[1], 0.1668589553405904), <=, 1e-12);
}

/* Spheres: mu = |r| / (r1 + r2), lambda* = r1 / (r1 + r2). Radii ratios up
 * to 1e6: when lambda* is within ~1e-6 of 0 or 1, Brent's 25 iterations may
 * not reach it; the answer must then be accurate anyway or come with
 * PW85_ERR_NO_CONVERGENCE, never silently wrong. */
static void test_spheres(void) {
  GRand *rng = g_rand_new_with_seed(41);
  int not_converged = 0;
  for (int n = 0; n < 1000; n++) {
    double const r1 = exp(g_rand_double_range(rng, log(1e-3), log(1e3)));
    double const r2 = exp(g_rand_double_range(rng, log(1e-3), log(1e3)));
    double const q1[6] = {r1 * r1, 0, 0, r1 * r1, 0, r1 * r1};
    double const q2[6] = {r2 * r2, 0, 0, r2 * r2, 0, r2 * r2};
    double r12[3];
    for (int i = 0; i < 3; i++) r12[i] = g_rand_double_range(rng, -1., 1.) * (r1 + r2);
    double out[2];
    int const status = pw85_contact_function(r12, q1, q2, out);
    long double const d = (long double)r12[0] * r12[0] + (long double)r12[1] * r12[1] +
                          (long double)r12[2] * r12[2];
    long double const s = (long double)r1 + r2;
    double const err = rel_error(out[0], (double)(d / (s * s)));
    if (status == PW85_ERR_NO_CONVERGENCE) {
      /* Radii within a factor 100 of each other always converge. */
      g_assert_false(r1 / r2 < 100. && r2 / r1 < 100.);
      not_converged++;
      continue;
    }
    g_assert_cmpint(status, ==, PW85_OK);
    g_assert_cmpfloat(err, <=, 1e-12);
    g_assert_cmpfloat(fabs(out[1] - (double)(r1 / s)), <=, 1e-8);
  }
  g_test_message("spheres: %d of 1000 reported PW85_ERR_NO_CONVERGENCE", not_converged);
  g_rand_free(rng);
}

/* Identical ellipsoids: f = lambda (1 - lambda) r^T Q^{-1} r, maximum at 1/2. */
static void check_identical(double lo, double hi, double rtol) {
  GRand *rng = g_rand_new_with_seed(42);
  double max_err = 0.0;
  for (int n = 0; n < 1000; n++) {
    double radii[3], axes[9], q[6], r12[3], out[2];
    random_radii(rng, lo, hi, radii);
    random_axes(rng, axes);
    make_q(radii, axes, q);
    for (int i = 0; i < 3; i++) r12[i] = g_rand_double_range(rng, -hi, hi);
    g_assert_cmpint(pw85_contact_function(r12, q, q, out), ==, PW85_OK);
    long double const x[3] = {r12[0], r12[1], r12[2]};
    double const expected = (double)(0.25L * xT_inv_x_ld(q, x));
    max_err = fmax(max_err, rel_error(out[0], expected));
    g_assert_cmpfloat(fabs(out[1] - 0.5), <=, 1e-6);
  }
  g_test_message("identical ellipsoids, semi-axes in [%g, %g]: max rel. error %.3g", lo, hi,
                 max_err);
  g_assert_cmpfloat(max_err, <=, rtol);
  g_rand_free(rng);
}

/* Q(lambda) has a condition number up to (max/min semi-axis)^2 = 1e8 here;
 * mu^2 stays accurate because its final evaluation uses the stationary form
 * with compensated sums (docs/theory.md). Measured: 1.5e-16 and 0. */
static void test_identical_class1(void) { check_identical(0.1, 10., 4 * DBL_EPSILON); }
static void test_identical_class2(void) { check_identical(0.01, 100., 4 * DBL_EPSILON); }

/* Coaxial ellipsoids with aligned axes, centres on a common axis:
 * mu = |r| / (a1 + a2), a_i the semi-axes along r. */
static void test_aligned(void) {
  GRand *rng = g_rand_new_with_seed(43);
  for (int n = 0; n < 1000; n++) {
    double a[3], b[3];
    random_radii(rng, 0.1, 10., a);
    random_radii(rng, 0.1, 10., b);
    double const q1[6] = {a[0] * a[0], 0, 0, a[1] * a[1], 0, a[2] * a[2]};
    double const q2[6] = {b[0] * b[0], 0, 0, b[1] * b[1], 0, b[2] * b[2]};
    int const axis = n % 3;
    double r12[3] = {0, 0, 0};
    r12[axis] = g_rand_double_range(rng, 0.1, 20.);
    double out[2];
    g_assert_cmpint(pw85_contact_function(r12, q1, q2, out), ==, PW85_OK);
    long double const mu = (long double)r12[axis] / ((long double)a[axis] + b[axis]);
    g_assert_cmpfloat(rel_error(out[0], (double)(mu * mu)), <=, 1e-12);
  }
  g_rand_free(rng);
}

/* Random general ellipsoids against a long-double golden-section maximum.
 * Semi-axes in [0.5, 2] and [0.1, 10]. */
static void check_random(guint32 seed, double lo, double hi, double rtol) {
  GRand *rng = g_rand_new_with_seed(seed);
  double max_err = 0.0;
  for (int n = 0; n < 2000; n++) {
    double radii[3], axes[9], q1[6], q2[6], r12[3], out[2];
    random_radii(rng, lo, hi, radii);
    random_axes(rng, axes);
    make_q(radii, axes, q1);
    random_radii(rng, lo, hi, radii);
    random_axes(rng, axes);
    make_q(radii, axes, q2);
    double const dist = exp(g_rand_double_range(rng, log(0.01), log(10.))) * 2 * hi;
    double dir[3];
    random_axes(rng, axes);
    for (int i = 0; i < 3; i++) dir[i] = axes[i], r12[i] = dist * dir[i];
    g_assert_cmpint(pw85_contact_function(r12, q1, q2, out), ==, PW85_OK);
    double const expected = (double)mu2_ld(r12, q1, q2, NULL);
    max_err = fmax(max_err, rel_error(out[0], expected));
  }
  g_test_message("semi-axes in [%g, %g]: max relative error of mu^2 %.3g", lo, hi, max_err);
  g_assert_cmpfloat(max_err, <=, rtol);
  g_rand_free(rng);
}

/* Measured: 0 and 2.1e-16 against the __float128/long double reference. */
static void test_random_class0(void) { check_random(44, 0.5, 2.0, 4 * DBL_EPSILON); }
static void test_random_class1(void) { check_random(45, 0.1, 10.0, 4 * DBL_EPSILON); }

static const int IDX[3][3] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};

/* x = A^{-1} b in long double by Cramer's rule. */
static void solve_ld(const double a[6], const long double b[3], long double x[3]) {
  long double m[3][3];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) m[i][j] = a[IDX[i][j]];
  long double const det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                          m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                          m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  for (int k = 0; k < 3; k++) {
    long double c[3][3];
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) c[i][j] = j == k ? b[i] : m[i][j];
    x[k] = (c[0][0] * (c[1][1] * c[2][2] - c[1][2] * c[2][1]) -
            c[0][1] * (c[1][0] * c[2][2] - c[1][2] * c[2][0]) +
            c[0][2] * (c[1][0] * c[2][1] - c[1][1] * c[2][0])) / det;
  }
}

/* The contact point x0 of theory eqs. (9a), computed in long double from the
 * returned lambda, lies on both ellipsoids scaled by mu (eqs. (14a)-(14b)),
 * and the outward normals Q1^{-1}(x0 - c1) and Q2^{-1}(x0 - c2) are opposite
 * (pw85 documentation, section 2.1.1). */
static void test_contact_point(void) {
  GRand *rng = g_rand_new_with_seed(46);
  double max_surface = 0, max_normal = 0;
  for (int n = 0; n < 1000; n++) {
    double radii[3], axes[9], q1[6], q2[6], r12[3], out[2];
    random_radii(rng, 0.2, 5., radii);
    random_axes(rng, axes);
    make_q(radii, axes, q1);
    random_radii(rng, 0.2, 5., radii);
    random_axes(rng, axes);
    make_q(radii, axes, q2);
    for (int i = 0; i < 3; i++) r12[i] = g_rand_double_range(rng, -5., 5.);
    g_assert_cmpint(pw85_contact_function(r12, q1, q2, out), ==, PW85_OK);
    long double const mu2 = out[0], l = out[1];
    double q[6];
    for (int i = 0; i < 6; i++) q[i] = (double)((1 - l) * q1[i] + l * q2[i]);
    long double const r[3] = {r12[0], r12[1], r12[2]};
    long double x[3], p1[3], p2[3];
    solve_ld(q, r, x);
    for (int i = 0; i < 3; i++) {
      long double s = 0;
      for (int j = 0; j < 3; j++) s += q1[IDX[i][j]] * x[j];
      p1[i] = (1 - l) * s;       /* x0 - c1, eq. (9a) */
      p2[i] = p1[i] - r[i];      /* x0 - c2 */
    }
    double const s1 = (double)(xT_inv_x_ld(q1, p1) / mu2);
    double const s2 = (double)(xT_inv_x_ld(q2, p2) / mu2);
    max_surface = fmax(max_surface, fmax(fabs(s1 - 1), fabs(s2 - 1)));
    long double n1[3], n2[3], nn1 = 0, nn2 = 0;
    solve_ld(q1, p1, n1);
    solve_ld(q2, p2, n2);
    for (int i = 0; i < 3; i++) nn1 += n1[i] * n1[i], nn2 += n2[i] * n2[i];
    for (int i = 0; i < 3; i++)
      max_normal = fmax(max_normal, fabs((double)(n1[i] / sqrtl(nn1) + n2[i] / sqrtl(nn2))));
  }
  g_test_message("contact point: surface error %.3g, normal mismatch %.3g", max_surface,
                 max_normal);
  g_assert_cmpfloat(max_surface, <=, 1e-10);
  g_assert_cmpfloat(max_normal, <=, 1e-8);
  g_rand_free(rng);
}

/* pw85's own self-consistency checks (chapter 6) on the grid of spheroids x
 * directions x distances {0.15, 1.1, 11}: mu1^2 and mu2^2 (chapter 5, eqs.
 * (3a)-(3b)) agree with mu^2 to 1e-10, |f'(lambda)| <= PW85_LAMBDA_ATOL
 * |f''(lambda)|. */
static void test_self_consistency_grid(void) {
  static const double distances[3] = {0.15, 1.1, 11.};
  double worst_mu = 0, worst_df = 0;
  long failures = 0, count = 0;
  for (int i1 = 0; i1 < 108; i1++) {
    double q1[6];
    grid_spheroid(i1, q1);
    for (int i2 = 0; i2 < 108; i2++) {
      double q2[6];
      grid_spheroid(i2, q2);
      for (int k = 0; k < 12; k++) {
        double n[3];
        grid_direction(k, n);
        for (int j = 0; j < 3; j++) {
          double r12[3] = {distances[j] * n[0], distances[j] * n[1], distances[j] * n[2]};
          double out[2], res[3];
          int const status = pw85_contact_function(r12, q1, q2, out);
          count++;
          if (status != PW85_OK) {
            failures++;
            continue;
          }
          pw85__residual(out[1], r12, q1, q2, res);
          /* Eqs. (3a)-(3b) of chapter 5 give f = l mu1^2 + (1 - l) mu2^2 and
           * g = mu2^2 - mu1^2, hence mu1^2 = f - (1 - l) g, mu2^2 = f + l g. */
          double const l = out[1];
          double const mu1_2 = res[0] - (1 - l) * res[1];
          double const mu2_2 = res[0] + l * res[1];
          double const e = fmax(rel_error(mu1_2, out[0]), rel_error(mu2_2, out[0]));
          worst_mu = fmax(worst_mu, e);
          long double df, d2f;
          df_ld(l, r12, q1, q2, &df, &d2f);
          double const ratio = (double)(fabsl(df) / fabsl(d2f));
          worst_df = fmax(worst_df, ratio);
        }
      }
    }
  }
  g_test_message("%ld calls, %ld non-OK; max rel. mismatch mu1^2/mu2^2 vs mu^2: %.3g; "
                 "max |f'|/|f''|: %.3g",
                 count, failures, worst_mu, worst_df);
  g_assert_cmpint(failures, ==, 0);
  g_assert_cmpfloat(worst_mu, <=, 1e-10);
  g_assert_cmpfloat(worst_df, <=, PW85_LAMBDA_ATOL);
}

/* Extreme but valid sizes: radii 1e-8 and 1e8. Equal sizes are solved
 * accurately; for 1e-8 against 1e8, lambda* ~ 1e-16 is out of reach of
 * Brent's absolute tolerance: an accurate answer or PW85_ERR_NO_CONVERGENCE,
 * never a silent wrong one. */
static void test_extreme_sizes(void) {
  double const sizes[2] = {1e-8, 1e8};
  for (int a = 0; a < 2; a++)
    for (int b = 0; b < 2; b++) {
      double const r1 = sizes[a], r2 = sizes[b];
      double const q1[6] = {r1 * r1, 0, 0, r1 * r1, 0, 4 * r1 * r1};
      double const q2[6] = {r2 * r2, 0, 0, 4 * r2 * r2, 0, r2 * r2};
      double const r12[3] = {0.0, 0.0, 1.5 * (2 * r1 + r2)};
      double out[2];
      int const status = pw85_contact_function(r12, q1, q2, out);
      if (a == b) g_assert_cmpint(status, ==, PW85_OK);
      if (status == PW85_ERR_NO_CONVERGENCE) {
        g_test_message("sizes %g and %g: PW85_ERR_NO_CONVERGENCE (mu^2 = %g)", r1, r2, out[0]);
        continue;
      }
      g_assert_cmpint(status, ==, PW85_OK);
      /* aligned along z: mu = |r| / (2 r1 + r2) */
      g_assert_cmpfloat(rel_error(out[0], 2.25), <=, 1e-10);
    }
}

static void test_zero_r12(void) {
  double const r12[3] = {0., 0., 0.}, q1[6] = {1, 0, 0, 2, 0, 3}, q2[6] = {3, 0, 0, 2, 0, 1};
  double out[2];
  g_assert_cmpint(pw85_contact_function(r12, q1, q2, out), ==, PW85_OK);
  g_assert_cmpfloat(out[0], ==, 0.0);
  g_assert_true(out[1] >= 0.0 && out[1] <= 1.0);
}

int main(int argc, char **argv) {
  g_test_init(&argc, &argv, NULL);
  g_test_add_func("/contact_function/tutorial", test_tutorial);
  g_test_add_func("/contact_function/spheres", test_spheres);
  g_test_add_func("/contact_function/identical/class1", test_identical_class1);
  g_test_add_func("/contact_function/identical/class2", test_identical_class2);
  g_test_add_func("/contact_function/aligned", test_aligned);
  g_test_add_func("/contact_function/random/class0", test_random_class0);
  g_test_add_func("/contact_function/random/class1", test_random_class1);
  g_test_add_func("/contact_function/contact_point", test_contact_point);
  g_test_add_func("/contact_function/self_consistency_grid", test_self_consistency_grid);
  g_test_add_func("/contact_function/extreme_sizes", test_extreme_sizes);
  g_test_add_func("/contact_function/zero_r12", test_zero_r12);
  return g_test_run();
}
