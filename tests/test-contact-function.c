/* pw85_contact_function (pw85 1.0's algorithm) against published values,
 * closed forms, long-double maximisation, and the geometric meaning of its
 * output (pw85 documentation, section 2.1.1 and chapter 6); and against the
 * groups /contact, /near_contact and /special of the reference data
 * (data/README.md: exact rational arithmetic on the stored doubles,
 * correctly rounded, so the errors measured are the library's alone; these
 * tests skip when the file is absent). Bad input: test-errors.c. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <pw85.h>

#include "refdata.h"
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

/* Identical ellipsoids: f = lambda (1 - lambda) r^T Q^{-1} r, maximum at 1/2.
 * PW85_ERR_INACCURATE where the error estimate (M10) cannot vouch for 1e-10
 * (it grows with kappa(Q)); the values are accurate anyway. */
static void check_identical(double lo, double hi, double rtol) {
  GRand *rng = g_rand_new_with_seed(42);
  double max_err = 0.0;
  int flagged = 0;
  for (int n = 0; n < 1000; n++) {
    double radii[3], axes[9], q[6], r12[3], out[2];
    random_radii(rng, lo, hi, radii);
    random_axes(rng, axes);
    make_q(radii, axes, q);
    for (int i = 0; i < 3; i++) r12[i] = g_rand_double_range(rng, -hi, hi);
    int const status = pw85_contact_function(r12, q, q, out);
    g_assert_true(status == PW85_OK || status == PW85_ERR_INACCURATE);
    flagged += status == PW85_ERR_INACCURATE;
    long double const x[3] = {r12[0], r12[1], r12[2]};
    double const expected = (double)(0.25L * xT_inv_x_ld(q, x));
    max_err = fmax(max_err, rel_error(out[0], expected));
    g_assert_cmpfloat(fabs(out[1] - 0.5), <=, 1e-6);
  }
  g_test_message("identical ellipsoids, semi-axes in [%g, %g]: max rel. error %.3g, "
                 "%d of 1000 PW85_ERR_INACCURATE", lo, hi, max_err, flagged);
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
  long failures = 0, inaccurate = 0, count = 0;
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
          if (status == PW85_ERR_INACCURATE) inaccurate++;
          if (status != PW85_OK && status != PW85_ERR_INACCURATE) {
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
  g_test_message("%ld calls, %ld neither OK nor INACCURATE, %ld INACCURATE; max rel. "
                 "mismatch mu1^2/mu2^2 vs mu^2: %.3g; max |f'|/|f''|: %.3g",
                 count, failures, inaccurate, worst_mu, worst_df);
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

/* ---- /contact, /near_contact, /special: pw85_contact_function ---------- */

/* Statistics of the relative error of mu^2 over a set of rows. */
typedef struct {
  GArray *err;       /* relative errors of all rows */
  double max_all;    /* max over all rows */
  double max_ok;     /* max over the rows with PW85_OK */
  gsize n, n_ok, n_noconv, n_inaccurate, n_other;
  gsize above;       /* rows with error > 1e-10 */
  gsize above_ok;    /* ... of which returned PW85_OK */
  gsize wrong_side;  /* overlap verdict (mu^2 < 1) differs from the reference */
  gsize tangent;     /* reference mu^2 == 1.0 exactly (no verdict) */
  gsize worst;       /* row of the largest error */
} Stats;

static void stats_init(Stats *s) {
  memset(s, 0, sizeof(*s));
  s->err = g_array_new(FALSE, FALSE, sizeof(double));
}

static int cmp_double(const void *a, const void *b) {
  double const x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double stats_max(const Stats *s) { return s->max_all; }

static double stats_median(const Stats *s) {
  if (s->err->len == 0) return NAN;
  double *v = g_memdup2(s->err->data, sizeof(double) * s->err->len);
  qsort(v, s->err->len, sizeof(double), cmp_double);
  guint const m = s->err->len / 2;
  double const med = s->err->len % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
  g_free(v);
  return med;
}

/* Runs pw85_contact_function on row i of p and accumulates. At most
 * `max_listed` rows beyond 1e-10 with PW85_OK are listed by name. */
static void run_row(const RefPairs *p, gsize i, Stats *s, int max_listed) {
  double out[2] = {NAN, NAN};
  int const status = pw85_contact_function(p->r12 + 3 * i, p->q1 + 6 * i, p->q2 + 6 * i, out);
  double const ref = p->mu2[i];
  double err;
  if (ref == 0.0) {
    /* Coincident centres: mu^2 = 0 exactly. */
    g_assert_cmpint(status, ==, PW85_OK);
    g_assert_cmpfloat(out[0], ==, 0.0);
    err = 0.0;
  } else {
    err = isnan(out[0]) ? INFINITY : rel_error(out[0], ref);
  }
  s->n++;
  if (status == PW85_OK) {
    s->n_ok++;
    s->max_ok = fmax(s->max_ok, err);
  } else if (status == PW85_ERR_NO_CONVERGENCE) {
    s->n_noconv++;
  } else if (status == PW85_ERR_INACCURATE) {
    s->n_inaccurate++;
  } else {
    s->n_other++;
    g_test_message("%s[%zu]: unexpected status %d (%s)", p->group, i, status,
                   pw85_strerror(status));
  }
  if (err > 1e-10) {
    s->above++;
    if (status == PW85_OK) {
      s->above_ok++;
      if ((int)s->above_ok <= max_listed)
        g_test_message("%s[%zu] (class %d): rel. error %.3g with PW85_OK (mu^2 = %.17g, "
                       "lambda* = %.17g; got %.17g, %.17g)",
                       p->group, i, p->cls[i], err, ref, p->lambda[i], out[0], out[1]);
    }
  }
  if (ref == 1.0)
    s->tangent++;
  else if (ref > 0.0 && (out[0] < 1.0) != (ref < 1.0))
    s->wrong_side++;
  if (s->err->len == 0 || err > s->max_all) s->worst = i, s->max_all = err;
  g_array_append_val(s->err, err);
}

static void stats_report(const char *what, const Stats *s) {
  g_test_message("%s: %zu rows, rel. error of mu^2: max %.3g (max with PW85_OK %.3g, row %zu), "
                 "median %.3g; %zu above 1e-10 (%zu of them with PW85_OK); "
                 "PW85_ERR_NO_CONVERGENCE: %zu; PW85_ERR_INACCURATE: %zu; other statuses: %zu",
                 what, s->n, stats_max(s), s->max_ok, s->worst, stats_median(s), s->above,
                 s->above_ok, s->n_noconv, s->n_inaccurate, s->n_other);
}

static void stats_clear(Stats *s) { g_array_free(s->err, TRUE); }

/* Bounds actually met by pw85_contact_function (pw85 1.0's algorithm:
 * Brent to PW85_LAMBDA_ATOL, then Newton on the residual), measured with
 * this file (docs/reference-data-tests.md) and rounded up to the next power
 * of ten; the counts are the measured ones rounded up. Index: size class.
 *   all: max rel. error of mu^2 over every row;
 *   ok: over the rows that returned PW85_OK;
 *   max_noconv: rows returning PW85_ERR_NO_CONVERGENCE;
 *   max_above_ok: rows returning PW85_OK with a rel. error > 1e-10 (each one
 *   is listed by g_test_message for classes 0..2). */
typedef struct {
  const char *name;
  double all, ok;
  gsize max_noconv, max_above_ok;
} Bound;

/* Measured (the final evaluation of mu^2 is the stationary form with
 * compensated sums, src/core/brent.cpp): max 0, 0, 0, 2.6e-11 (all rows;
 * the reference is correctly rounded and the result usually is too);
 * PW85_ERR_NO_CONVERGENCE 0, 0, 0, 87; PW85_OK beyond 1e-10: 0 in every
 * class. */
static const Bound contact_bounds[4] = {
    {"class 0", 1e-15, 1e-15, 0, 0},
    {"class 1", 1e-15, 1e-15, 0, 0},
    {"class 2", 1e-15, 1e-15, 0, 0},
    {"class 3", 1e-10, 1e-10, 100, 0},
};

/* Measured: max 0, 0, 0, 3.1e-13 (1.4e-13 with PW85_OK);
 * PW85_ERR_NO_CONVERGENCE 0, 0, 0, 33; PW85_OK beyond 1e-10: 0. */
static const Bound near_bounds[4] = {
    {"class 0", 1e-15, 1e-15, 0, 0},
    {"class 1", 1e-15, 1e-15, 0, 0},
    {"class 2", 1e-15, 1e-15, 0, 0},
    {"class 3", 1e-12, 1e-12, 40, 0},
};

/* /special, by kind (names from the attribute `kinds` of /special/kind).
 * Measured maxima in the comments (all rows; with PW85_OK). */
static const Bound special_bounds[] = {
    {"coincident_centres", 0.0, 0.0, 0, 0},          /* exactly 0 */
    {"identical_ellipsoids", 1e-13, 1e-13, 0, 0},     /* 2.8e-14 */
    {"equal_spheres", 1e-15, 1e-15, 0, 0},            /* 0 */
    {"very_different_spheres", 1e-5, 0.0, 30, 0},     /* 4.8e-6, all 30 no conv. */
    {"needle_crossing_disc", 1e-5, 1e-12, 16, 0},     /* 3.0e-6; 0 with OK */
    {"parallel_needles", 1e-9, 1e-9, 0, 5},           /* 2.9e-10 */
    {"nearly_parallel_needles", 1e-9, 1e-9, 1, 5},    /* 9.3e-10 */
    {"high_aspect_spheroids", 1e-5, 1e-9, 29, 3},     /* 2.9e-6; 6.1e-10 with OK */
    {"high_aspect_ellipsoids", 1e-15, 1e-15, 0, 0},   /* 0 */
};

static void check_bounds(const Stats *s, const Bound *b) {
  g_test_message("asserted (%s): max rel. error <= %g (with PW85_OK <= %g), "
                 "PW85_ERR_NO_CONVERGENCE <= %zu, PW85_OK beyond 1e-10 <= %zu",
                 b->name, b->all, b->ok, b->max_noconv, b->max_above_ok);
  g_assert_cmpuint(s->n_other, ==, 0);
  g_assert_cmpfloat(stats_max(s), <=, b->all);
  g_assert_cmpfloat(s->max_ok, <=, b->ok);
  g_assert_cmpuint(s->n_noconv, <=, b->max_noconv);
  g_assert_cmpuint(s->above_ok, <=, b->max_above_ok);
}

static void test_contact_class(gconstpointer data) {
  int const cls = GPOINTER_TO_INT(data);
  RefPairs *p = refdata_pairs_or_skip("/contact");
  if (p == NULL) return;
  Stats s;
  stats_init(&s);
  for (gsize i = 0; i < p->n; i++)
    if (p->cls[i] == cls) run_row(p, i, &s, cls < 3 ? G_MAXINT : 10);
  g_assert_cmpuint(s.n, >, 0);
  char *what = g_strdup_printf("/contact class %d", cls);
  stats_report(what, &s);
  g_free(what);
  check_bounds(&s, &contact_bounds[cls]);
  stats_clear(&s);
  refdata_pairs_free(p);
}

static void test_near_contact_class(gconstpointer data) {
  int const cls = GPOINTER_TO_INT(data);
  RefPairs *p = refdata_pairs_or_skip("/near_contact");
  if (p == NULL) return;
  Stats s;
  stats_init(&s);
  for (gsize i = 0; i < p->n; i++)
    if (p->cls[i] == cls) run_row(p, i, &s, cls < 3 ? G_MAXINT : 5);
  g_assert_cmpuint(s.n, >, 0);
  char *what = g_strdup_printf("/near_contact class %d", cls);
  stats_report(what, &s);
  g_test_message("%s: overlap verdict (mu^2 < 1) on the wrong side of 1: %zu of %zu "
                 "(%zu rows with reference mu^2 == 1.0 exactly, not counted)",
                 what, s.wrong_side, s.n, s.tangent);
  g_free(what);
  check_bounds(&s, &near_bounds[cls]);
  stats_clear(&s);
  refdata_pairs_free(p);
}

static void test_special(void) {
  hid_t file;
  if (!refdata_open_or_skip(&file)) return;
  RefPairs *p = refdata_pairs_read(file, "/special");
  char *kinds = refdata_read_string_attribute(file, "/special/kind", "kinds");
  refdata_close(file);
  g_assert_nonnull(p);
  g_assert_nonnull(p->kind);
  g_assert_nonnull(kinds);
  char **names = g_strsplit(kinds, ",", -1);
  guint const num_kinds = g_strv_length(names);
  g_assert_cmpuint(num_kinds, >, 0);
  Stats all;
  stats_init(&all);
  gsize coincident = 0;
  for (guint k = 0; k < num_kinds; k++) {
    Stats s;
    stats_init(&s);
    for (gsize i = 0; i < p->n; i++) {
      if (p->kind[i] != (int)k) continue;
      run_row(p, i, &s, 3);
      run_row(p, i, &all, 0);
      if (p->mu2[i] == 0.0) coincident++;
    }
    char *what = g_strdup_printf("/special %s", names[k]);
    stats_report(what, &s);
    g_test_message("%s: overlap verdict on the wrong side of 1: %zu of %zu", what,
                   s.wrong_side, s.n);
    g_free(what);
    const Bound *b = NULL;
    for (gsize j = 0; j < G_N_ELEMENTS(special_bounds); j++)
      if (strcmp(special_bounds[j].name, names[k]) == 0) b = &special_bounds[j];
    if (b == NULL) g_test_message("/special: kind %s has no bound in this test", names[k]);
    g_assert_nonnull(b);
    g_assert_cmpuint(s.n, >, 0);
    check_bounds(&s, b);
    stats_clear(&s);
  }
  g_assert_cmpuint(all.n, ==, p->n);
  stats_report("/special all kinds", &all);
  g_test_message("/special: %zu rows with coincident centres gave mu^2 = 0 exactly; "
                 "overlap verdict on the wrong side of 1: %zu", coincident, all.wrong_side);
  g_assert_cmpuint(coincident, >, 0);
  g_assert_cmpuint(all.n_other, ==, 0);
  stats_clear(&all);
  g_strfreev(names);
  g_free(kinds);
  refdata_pairs_free(p);
}

/* Exact power-of-two scalings over the whole double range (docs/stability.md,
 * "Accepted input ranges"): r -> 2^kr r, Q -> 2^kq Q give mu2 -> 2^(2 kr - kq)
 * mu2 and the same lambda. Reference: the unscaled call (inputs exact at
 * both scales), scaled exactly in long double. Every method and
 * pw85_contact_function must return that (PW85_OK), or PW85_ERR_RANGE with
 * mu2 rounded to the nearest double when it is out of [DBL_MIN, DBL_MAX]. */
static int method_scaled_ok(const double R[3], const double Q1[6], const double Q2[6], int method,
                            int kr, int kq, double *worst) {
  double r[3], q1[6], q2[6];
  for (int i = 0; i < 3; i++) {
    r[i] = ldexp(R[i], kr);
    if (ldexp(r[i], -kr) != R[i]) return 1;
  }
  for (int i = 0; i < 6; i++) {
    q1[i] = ldexp(Q1[i], kq);
    q2[i] = ldexp(Q2[i], kq);
    if (ldexp(q1[i], -kq) != Q1[i] || ldexp(q2[i], -kq) != Q2[i]) return 1;
  }
  double mu2_ref, lambda_ref, mu2, lambda;
  int s;
  if (method < 0) { /* pw85_contact_function */
    double o0[2], o[2];
    g_assert_cmpint(pw85_contact_function(R, Q1, Q2, o0), ==, PW85_OK);
    s = pw85_contact_function(r, q1, q2, o);
    mu2_ref = o0[0], lambda_ref = o0[1], mu2 = o[0], lambda = o[1];
  } else {
    pw85_result res0, res;
    g_assert_cmpint(pw85_contact_function_method(R, Q1, Q2, method, &res0), ==, PW85_OK);
    s = pw85_contact_function_method(r, q1, q2, method, &res);
    mu2_ref = res0.mu2, lambda_ref = res0.lambda, mu2 = res.mu2, lambda = res.lambda;
  }
  long double const ex = ldexpl(mu2_ref, 2 * kr - kq);
  int const range = !(ex >= DBL_MIN && ex <= DBL_MAX);
  double e = fabs(lambda - lambda_ref);
  if (!(isinf(mu2) && ex > DBL_MAX) && !(fabsl(mu2 - ex) <= 0x1p-1074))
    e = fmax(e, (double)(fabsl(mu2 - ex) / ex));
  *worst = fmax(*worst, e);
  if (s != (range ? PW85_ERR_RANGE : PW85_OK) || !(e <= 8 * DBL_EPSILON)) {
    g_test_message("method %d kr = %d kq = %d: status %d, mu2 %.17g (%.17Lg), lambda %.17g "
                   "(%.17g)", method, kr, kq, s, mu2, ex, lambda, lambda_ref);
    return 0;
  }
  return 1;
}

static void test_method_extreme_scale(void) {
  double const R[3] = {1.25, -0.5, 0.75};
  double const Q1[6] = {1, 0.1, -0.2, 0.5, 0.05, 0.3};
  double const Q2[6] = {0.2, -0.05, 0.01, 0.9, 0.1, 0.4};
  double const S1[6] = {1, 0.125, -0.25, 0.5, 0.0625, 0.375};
  double const S2[6] = {0.25, -0.0625, 0, 1, 0.125, 0.5};
  struct { const double *q1, *q2; } const pairs[] = {{Q1, Q2}, {S1, S2}};
  int const methods[] = {-1, PW85_METHOD_DEFAULT, PW85_METHOD_BRENT, PW85_METHOD_NEWTON,
                         PW85_METHOD_RATIONAL, PW85_METHOD_ZHENG};
  int bad = 0;
  double worst = 0;
  for (size_t p = 0; p < G_N_ELEMENTS(pairs); p++)
    for (size_t m = 0; m < G_N_ELEMENTS(methods); m++)
      for (int k = -1074; k <= 1023; k++) {
        bad += !method_scaled_ok(R, pairs[p].q1, pairs[p].q2, methods[m], k, 0, &worst);
        bad += !method_scaled_ok(R, pairs[p].q1, pairs[p].q2, methods[m], 0, k, &worst);
        bad += !method_scaled_ok(R, pairs[p].q1, pairs[p].q2, methods[m], k, 2 * k, &worst);
      }
  g_test_message("largest deviation from the scaled reference: %.3g eps; %d wrong",
                 worst / DBL_EPSILON, bad);
  g_assert_cmpint(bad, ==, 0);
}

int main(int argc, char **argv) {
  g_test_init(&argc, &argv, NULL);
  g_test_add_func("/pw85_contact_function/tutorial", test_tutorial);
  g_test_add_func("/pw85_contact_function/spheres", test_spheres);
  g_test_add_func("/pw85_contact_function/identical/class1", test_identical_class1);
  g_test_add_func("/pw85_contact_function/identical/class2", test_identical_class2);
  g_test_add_func("/pw85_contact_function/aligned", test_aligned);
  g_test_add_func("/pw85_contact_function/random/class0", test_random_class0);
  g_test_add_func("/pw85_contact_function/random/class1", test_random_class1);
  g_test_add_func("/pw85_contact_function/contact_point", test_contact_point);
  g_test_add_func("/pw85_contact_function/self_consistency_grid", test_self_consistency_grid);
  g_test_add_func("/pw85_contact_function/extreme_sizes", test_extreme_sizes);
  g_test_add_func("/pw85_contact_function/zero_r12", test_zero_r12);
  for (int c = 0; c < 4; c++) {
    char *path = g_strdup_printf("/pw85_contact_function/reference/class%d", c);
    g_test_add_data_func(path, GINT_TO_POINTER(c), test_contact_class);
    g_free(path);
  }
  for (int c = 0; c < 4; c++) {
    char *path = g_strdup_printf("/pw85_contact_function/reference/near_contact/class%d", c);
    g_test_add_data_func(path, GINT_TO_POINTER(c), test_near_contact_class);
    g_free(path);
  }
  g_test_add_func("/pw85_contact_function/reference/special", test_special);
  g_test_add_func("/pw85_contact_function_method/extreme_scale", test_method_extreme_scale);
  return g_test_run();
}
