/* Linear-algebra helpers of pw85 1.0: pw85__cholesky_decomp and
 * pw85__cholesky_solve. */
#include <float.h>
#include <math.h>

#include <pw85.h>

#include "testutil.h"

#define NUM_CASES 2000

/* L L^T reproduces A entrywise to a few ulps of the largest diagonal term
 * of the row and column (the natural scale of a Cholesky backward error). */
static void test_cholesky_decomp_random(void) {
  GRand *rng = g_rand_new_with_seed(20191);
  for (int n = 0; n < NUM_CASES; n++) {
    double a[6], l[6];
    random_spd(rng, 1e4, a); /* semi-axes in [0.1, 10] */
    pw85__cholesky_decomp(a, l);
    /* L = [l0 0 0; l1 l3 0; l2 l4 l5] */
    double L[3][3] = {{l[0], 0, 0}, {l[1], l[3], 0}, {l[2], l[4], l[5]}};
    int idx = 0;
    for (int i = 0; i < 3; i++)
      for (int j = i; j < 3; j++, idx++) {
        double s = 0.0;
        for (int k = 0; k < 3; k++) s += L[i][k] * L[j][k];
        double const diag_i = a[i == 0 ? 0 : (i == 1 ? 3 : 5)];
        double const diag_j = a[j == 0 ? 0 : (j == 1 ? 3 : 5)];
        g_assert_cmpfloat(fabs(s - a[idx]), <=, 8 * DBL_EPSILON * sqrt(diag_i * diag_j));
      }
    g_assert_cmpfloat(l[0], >, 0.0);
    g_assert_cmpfloat(l[3], >, 0.0);
    g_assert_cmpfloat(l[5], >, 0.0);
  }
  g_rand_free(rng);
}

/* The exact factor of a matrix built from an exactly representable L. */
static void test_cholesky_decomp_exact(void) {
  /* L = [2 0 0; 1 3 0; -1 0.5 4] -> A = L L^T */
  double const a[6] = {4.0, 2.0, -2.0, 10.0, 0.5, 17.25};
  double l[6];
  pw85__cholesky_decomp(a, l);
  double const expected[6] = {2.0, 1.0, -1.0, 3.0, 0.5, 4.0};
  for (int i = 0; i < 6; i++) g_assert_cmpfloat(l[i], ==, expected[i]);
}

static void test_cholesky_decomp_not_spd(void) {
  double const bad[][6] = {
      {1.0, 0.0, 0.0, -1.0, 0.0, 1.0},  /* indefinite */
      {0.0, 0.0, 0.0, 0.0, 0.0, 0.0},   /* zero */
      {1.0, 2.0, 0.0, 1.0, 0.0, 1.0},   /* indefinite off-diagonal */
      {1.0, 0.0, 0.0, 1.0, 0.0, NAN},   /* NaN */
  };
  for (size_t k = 0; k < G_N_ELEMENTS(bad); k++) {
    double l[6] = {1, 1, 1, 1, 1, 1};
    pw85__cholesky_decomp(bad[k], l);
    for (int i = 0; i < 6; i++) g_assert_true(isnan(l[i]));
  }
  /* NULL: nothing written, no crash. */
  double l[6] = {7, 7, 7, 7, 7, 7};
  pw85__cholesky_decomp(NULL, l);
  for (int i = 0; i < 6; i++) g_assert_cmpfloat(l[i], ==, 7.0);
  pw85__cholesky_decomp(bad[0], NULL);
}

/* A x = b solved to a small backward error. */
static void test_cholesky_solve_random(void) {
  GRand *rng = g_rand_new_with_seed(20192);
  for (int n = 0; n < NUM_CASES; n++) {
    double a[6], l[6], b[3], x[3];
    random_spd(rng, 1e4, a); /* semi-axes in [0.1, 10] */
    for (int i = 0; i < 3; i++) b[i] = g_rand_double_range(rng, -1.0, 1.0);
    pw85__cholesky_decomp(a, l);
    pw85__cholesky_solve(l, b, x);
    double const ax[3] = {a[0] * x[0] + a[1] * x[1] + a[2] * x[2],
                          a[1] * x[0] + a[3] * x[1] + a[4] * x[2],
                          a[2] * x[0] + a[4] * x[1] + a[5] * x[2]};
    double norm_a = fabs(a[0]) + fabs(a[3]) + fabs(a[5]) + 2 * (fabs(a[1]) + fabs(a[2]) + fabs(a[4]));
    double norm_x = fabs(x[0]) + fabs(x[1]) + fabs(x[2]);
    for (int i = 0; i < 3; i++)
      g_assert_cmpfloat(fabs(ax[i] - b[i]), <=, 16 * DBL_EPSILON * norm_a * norm_x);
  }
  g_rand_free(rng);
}

static void test_cholesky_solve_exact(void) {
  double const l[6] = {2.0, 1.0, -1.0, 3.0, 0.5, 4.0};
  /* A = L L^T = [4 2 -2; 2 10 0.5; -2 0.5 17.25]; x = (1, -2, 0.5). */
  double const b[3] = {4.0 - 4.0 - 1.0, 2.0 - 20.0 + 0.25, -2.0 - 1.0 + 8.625};
  double x[3];
  pw85__cholesky_solve(l, b, x);
  g_assert_cmpfloat(fabs(x[0] - 1.0), <=, 4 * DBL_EPSILON);
  g_assert_cmpfloat(fabs(x[1] + 2.0), <=, 4 * DBL_EPSILON);
  g_assert_cmpfloat(fabs(x[2] - 0.5), <=, 4 * DBL_EPSILON);
  double y[3] = {9, 9, 9};
  pw85__cholesky_solve(NULL, b, y);
  pw85__cholesky_solve(l, NULL, y);
  for (int i = 0; i < 3; i++) g_assert_cmpfloat(y[i], ==, 9.0);
  pw85__cholesky_solve(l, b, NULL);
}

int main(int argc, char **argv) {
  g_test_init(&argc, &argv, NULL);
  g_test_add_func("/pw85__cholesky_decomp/exact", test_cholesky_decomp_exact);
  g_test_add_func("/pw85__cholesky_decomp/random", test_cholesky_decomp_random);
  g_test_add_func("/pw85__cholesky_decomp/not_spd", test_cholesky_decomp_not_spd);
  g_test_add_func("/pw85__cholesky_solve/exact", test_cholesky_solve_exact);
  g_test_add_func("/pw85__cholesky_solve/random", test_cholesky_solve_random);
  return g_test_run();
}
