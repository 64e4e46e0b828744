/* Tests of the algebraic helpers of libpw85_legacy: pw85_legacy__det_sym,
 * pw85_legacy__xT_adjA_x, pw85_legacy__rT_adjQ_r_as_poly and
 * pw85_legacy__detQ_as_poly, against independent __float128 evaluations. */
#include <float.h>
#include <math.h>

#include <glib.h>

#include "refdata.h"
#include "testutil.h"
#include "pw85_legacy.h"

#define NUM_RANDOM 2000

static void to_q(const double *x, int n, __float128 *y) {
  for (int i = 0; i < n; ++i) y[i] = x[i];
}

/* det of well-conditioned SPD matrices (cond <= 100): rtol 1e-12. */
static void test_det_sym_random(void) {
  GRand *rng = g_rand_new_with_seed(20261121);
  double max_err = 0.0;
  for (int t = 0; t < NUM_RANDOM; ++t) {
    double a[6];
    random_spd(rng, 100.0, a);
    double const scale = pow(10.0, g_rand_double_range(rng, -6.0, 6.0));
    for (int i = 0; i < 6; ++i) a[i] *= scale;
    __float128 aq[6];
    to_q(a, 6, aq);
    double const exp = (double)q_det_sym(aq);
    double const err = rel_error(pw85_legacy__det_sym(a), exp);
    if (err > max_err) max_err = err;
    g_assert_cmpfloat(err, <=, 1e-12);
  }
  g_test_message("det_sym: max relative error %.3g over %d SPD matrices (cond <= 100)",
                 max_err, NUM_RANDOM);
  g_rand_free(rng);
}

/* General symmetric matrices (entries uniform in [-1, 1]): the determinant
 * may cancel, so the error is measured against the sum of the magnitudes of
 * the six products of the expansion. */
static void test_det_sym_general(void) {
  GRand *rng = g_rand_new_with_seed(7);
  for (int t = 0; t < NUM_RANDOM; ++t) {
    double a[6];
    for (int i = 0; i < 6; ++i) a[i] = g_rand_double_range(rng, -1.0, 1.0);
    __float128 aq[6];
    to_q(a, 6, aq);
    double const exp = (double)q_det_sym(aq);
    double const mag = fabs(a[0] * a[3] * a[5]) + fabs(a[0] * a[4] * a[4]) +
                       fabs(a[1] * a[1] * a[5]) + 2.0 * fabs(a[1] * a[2] * a[4]) +
                       fabs(a[2] * a[2] * a[3]);
    g_assert_cmpfloat(fabs(pw85_legacy__det_sym(a) - exp), <=, 8.0 * DBL_EPSILON * mag);
  }
  /* Diagonal and a known matrix: exact results. */
  double const d[6] = {2.0, 0.0, 0.0, 3.0, 0.0, 5.0};
  g_assert_cmpfloat(pw85_legacy__det_sym(d), ==, 30.0);
  double const m[6] = {4.0, 1.0, 2.0, 3.0, 0.0, 6.0}; /* det = 4*18 - 1*6 + 2*(-6) = 54 */
  g_assert_cmpfloat(pw85_legacy__det_sym(m), ==, 54.0);
  g_rand_free(rng);
}

static void test_xT_adjA_x_random(void) {
  GRand *rng = g_rand_new_with_seed(42);
  double max_err = 0.0;
  for (int t = 0; t < NUM_RANDOM; ++t) {
    double a[6], x[3];
    random_spd(rng, 100.0, a);
    double const scale = pow(10.0, g_rand_double_range(rng, -6.0, 6.0));
    for (int i = 0; i < 6; ++i) a[i] *= scale;
    for (int i = 0; i < 3; ++i) x[i] = g_rand_double_range(rng, -10.0, 10.0);
    __float128 aq[6], xq[3];
    to_q(a, 6, aq);
    to_q(x, 3, xq);
    double const exp = (double)q_xT_adjA_x(xq, aq);
    double const err = rel_error(pw85_legacy__xT_adjA_x(x, a), exp);
    if (err > max_err) max_err = err;
    /* adj(A) is positive definite with cond <= 100: no cancellation. */
    g_assert_cmpfloat(err, <=, 1e-12);
  }
  g_test_message("xT_adjA_x: max relative error %.3g over %d SPD matrices (cond <= 100)",
                 max_err, NUM_RANDOM);
  /* adj(diag(2, 3, 5)) = diag(15, 10, 6): x = (1, 2, 3) gives 15 + 40 + 54. */
  double const d[6] = {2.0, 0.0, 0.0, 3.0, 0.0, 5.0};
  double const x[3] = {1.0, 2.0, 3.0};
  g_assert_cmpfloat(pw85_legacy__xT_adjA_x(x, d), ==, 109.0);
  g_rand_free(rng);
}

static void test_helpers_bad_input(void) {
  double const a[6] = {1.0, 0.0, 0.0, 1.0, 0.0, 1.0};
  double const x[3] = {1.0, 0.0, 0.0};
  g_assert_true(isnan(pw85_legacy__det_sym(NULL)));
  g_assert_true(isnan(pw85_legacy__xT_adjA_x(NULL, a)));
  g_assert_true(isnan(pw85_legacy__xT_adjA_x(x, NULL)));
  double const nan_a[6] = {NAN, 0.0, 0.0, 1.0, 0.0, 1.0};
  g_assert_true(isnan(pw85_legacy__det_sym(nan_a)));
  double out[4] = {0.0, 0.0, 0.0, 0.0};
  pw85_legacy__rT_adjQ_r_as_poly(x, a, a, NULL, out);
  for (int i = 0; i < 3; ++i) g_assert_true(isnan(out[i]));
  pw85_legacy__detQ_as_poly(a, NULL, a, a, out);
  for (int i = 0; i < 4; ++i) g_assert_true(isnan(out[i]));
  /* NULL output: nothing to write, no crash. */
  pw85_legacy__rT_adjQ_r_as_poly(x, a, a, a, NULL);
  pw85_legacy__detQ_as_poly(a, a, a, a, NULL);
}

/* Reference spheroids. The coefficients are differences of the values at
 * lambda = -1, 0, 1/2, 1: their error is bounded by a few DBL_EPSILON times
 * the magnitude of the terms of these values (not by the value at lambda),
 * so that is the bound asserted; the relative errors reached are reported. */
/* Sum of the magnitudes of the terms of the cofactor expansions: the
 * rounding error of a double evaluation of det(A) or x^T adj(A) x is a few
 * DBL_EPSILON times these, however much the terms cancel. */
static double det_terms(const __float128 a[6]) {
  __float128 const t = fabs((double)(a[0] * a[3] * a[5])) + fabs((double)(a[0] * a[4] * a[4])) +
                       fabs((double)(a[1] * a[1] * a[5])) +
                       2 * fabs((double)(a[1] * a[2] * a[4])) +
                       fabs((double)(a[2] * a[2] * a[3]));
  return (double)t;
}

static double adj_terms(const __float128 x[3], const __float128 a[6]) {
  __float128 const m[3][3] = {{a[0], a[1], a[2]}, {a[1], a[3], a[4]}, {a[2], a[4], a[5]}};
  double s = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      int const r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
      s += fabs((double)(x[i] * x[j])) * (fabs((double)(m[r0][c0] * m[r1][c1])) +
                                          fabs((double)(m[r0][c1] * m[r1][c0])));
    }
  return s;
}

typedef struct {
  double *spheroids, *directions, *lambdas;
  gsize ns, nd, nl;
} RefGrid;

static gboolean read_grid(RefGrid *g) {
  hid_t file;
  if (!refdata_open_or_skip(&file)) return FALSE;
  g->spheroids = refdata_read_double_all(file, "/spheroids", &g->ns);
  g_assert_nonnull(g->spheroids);
  g->directions = refdata_read_double_all(file, "/directions", &g->nd);
  g_assert_nonnull(g->directions);
  g->lambdas = refdata_read_double_all(file, "/lambdas", &g->nl);
  g_assert_nonnull(g->lambdas);
  g->ns /= 6;
  g->nd /= 3;
  refdata_close(file);
  g_assert_cmpuint(g->nl, ==, 11);
  return TRUE;
}

static void free_grid(RefGrid *g) {
  g_free(g->spheroids);
  g_free(g->directions);
  g_free(g->lambdas);
}

/* Errors of a polynomial evaluated from its computed coefficients against the
 * exact __float128 value: relative, and scaled by DBL_EPSILON times the
 * magnitude of the sampled terms that made the coefficients. */
typedef struct {
  double max_rel, max_scaled;
  gsize n_rel_1e12, n;
} PolyErr;

static void poly_err_add(PolyErr *e, double act, double exp, double mag) {
  double const rel = rel_error(act, exp);
  double const scaled = fabs(act - exp) / (DBL_EPSILON * mag);
  if (rel > e->max_rel) e->max_rel = rel;
  if (scaled > e->max_scaled) e->max_scaled = scaled;
  if (rel > 1e-12) ++e->n_rel_1e12;
  ++e->n;
}

/* Reports e and asserts the coefficients' error bound (4 DBL_EPSILON times
 * the magnitude of the terms). */
static void poly_err_check(const PolyErr *e, const char *name, const char *terms) {
  g_test_message("%s: %" G_GSIZE_FORMAT " values; max |error| = %.3g "
                 "DBL_EPSILON x (terms of %s); max relative error %.3g; "
                 "%" G_GSIZE_FORMAT " values off by more than 1e-12 relative",
                 name, e->n, e->max_scaled, terms, e->max_rel, e->n_rel_1e12);
  g_assert_cmpfloat(e->max_scaled, <=, 4.0);
}

static void test_detQ_as_poly_reference(void) {
  RefGrid g;
  if (!read_grid(&g)) return;
  PolyErr e = {0};
  for (gsize i1 = 0; i1 < g.ns; ++i1) {
    const double *q1 = g.spheroids + 6 * i1;
    for (gsize i2 = 0; i2 < g.ns; ++i2) {
      const double *q2 = g.spheroids + 6 * i2;
      double q3[6], q4[6], b[4];
      for (int i = 0; i < 6; ++i) {
        q3[i] = 2.0 * q1[i] - q2[i];
        q4[i] = 0.5 * (q1[i] + q2[i]);
      }
      pw85_legacy__detQ_as_poly(q1, q2, q3, q4, b);
      /* Magnitude of the sampled values, from exact __float128 matrices. */
      __float128 qm[6];
      double mag = 0.0;
      double const samples[4] = {-1.0, 0.0, 0.5, 1.0};
      for (int k = 0; k < 4; ++k) {
        q_interpolate(q1, q2, samples[k], qm);
        mag += det_terms(qm);
      }
      for (gsize l = 0; l < g.nl; ++l) {
        double const x = g.lambdas[l];
        q_interpolate(q1, q2, x, qm);
        double const exp = (double)q_det_sym(qm);
        poly_err_add(&e, b[0] + x * (b[1] + x * (b[2] + x * b[3])), exp, mag);
      }
    }
  }
  poly_err_check(&e, "detQ_as_poly", "b(-1, 0, 1/2, 1)");
  free_grid(&g);
}

static void test_rT_adjQ_r_as_poly_reference(void) {
  RefGrid g;
  if (!read_grid(&g)) return;
  PolyErr e = {0};
  for (gsize i1 = 0; i1 < g.ns; ++i1) {
    const double *q1 = g.spheroids + 6 * i1;
    for (gsize i2 = 0; i2 < g.ns; ++i2) {
      const double *q2 = g.spheroids + 6 * i2;
      double q3[6];
      for (int i = 0; i < 6; ++i) q3[i] = 2.0 * q1[i] - q2[i];
      for (gsize k = 0; k < g.nd; ++k) {
        const double *r = g.directions + 3 * k;
        __float128 const rq[3] = {r[0], r[1], r[2]};
        double a[3];
        pw85_legacy__rT_adjQ_r_as_poly(r, q1, q2, q3, a);
        __float128 qm[6];
        double mag = 0.0;
        double const samples[3] = {-1.0, 0.0, 1.0};
        for (int j = 0; j < 3; ++j) {
          q_interpolate(q1, q2, samples[j], qm);
          mag += adj_terms(rq, qm);
        }
        for (gsize l = 0; l < g.nl; ++l) {
          double const x = g.lambdas[l];
          q_interpolate(q1, q2, x, qm);
          double const exp = (double)q_xT_adjA_x(rq, qm);
          poly_err_add(&e, a[0] + x * (a[1] + x * a[2]), exp, mag);
        }
      }
    }
  }
  poly_err_check(&e, "rT_adjQ_r_as_poly", "a(-1, 0, 1)");
  free_grid(&g);
}

int main(int argc, char **argv) {
  g_test_init(&argc, &argv, NULL);
  g_test_add_func("/pw85_legacy__det_sym/random_spd", test_det_sym_random);
  g_test_add_func("/pw85_legacy__det_sym/general", test_det_sym_general);
  g_test_add_func("/pw85_legacy__xT_adjA_x/random_spd", test_xT_adjA_x_random);
  g_test_add_func("/pw85_legacy__helpers/bad_input", test_helpers_bad_input);
  g_test_add_func("/pw85_legacy__detQ_as_poly/reference/spheroids", test_detQ_as_poly_reference);
  g_test_add_func("/pw85_legacy__rT_adjQ_r_as_poly/reference/spheroids",
                  test_rT_adjQ_r_as_poly_reference);
  return g_test_run();
}
