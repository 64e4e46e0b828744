/* pw85_contact_function_method: every method on the cases where methods
 * fail (the measurements of docs/stability.md), ZHENG against the reference
 * data, and bad input.
 *
 * For every method: aspect ratios 1 to 1e6 (needles and discs), near
 * tangency (|mu^2 - 1| down to 1e-15), coincident centres, identical
 * ellipsoids, a needle crossing a disc at right angles, nearly parallel
 * needles, spheres of radii 1e-6 and 1e6, magnitudes 1e-150 to 1e150. For
 * each pair:
 *  - the status is PW85_OK, PW85_ERR_INACCURATE or PW85_ERR_NO_CONVERGENCE,
 *    mu2 and mu2_error are finite (never NaN), res.method is the method;
 *  - if the status is PW85_OK, the relative error of mu2 is within the
 *    method's documented accuracy (include/pw85.h): a failure is always
 *    reported by the status, never silent;
 *  - the pairs a method flags (PW85_ERR_INACCURATE or
 *    PW85_ERR_NO_CONVERGENCE) are no more, and lie in no other region, than
 *    the failure map of docs/stability.md allows (the allowances of the
 *    table `methods` below); a case the map does not list for a method
 *    allows no flag (PW85_METHOD_DEFAULT: none anywhere). A method id the
 *    library does not know fails the test.
 * References are independent of the library: closed forms where they exist
 * (spheres: mu^2 = |r|^2 / (r1 + r2)^2; identical ellipsoids:
 * mu^2 = r^T Q^{-1} r / 4 at lambda = 1/2; coaxial ellipsoids aligned along
 * a principal axis: mu = |r| / (a1 + a2)), evaluated in __float128 from the
 * double inputs, and otherwise a maximisation of f in __float128 (bisection
 * on the sign of f', then Newton; Q(lambda)^{-1} by LDL^T in __float128).
 * The largest errors per method and case are printed with g_test_message
 * (docs/stability.md quotes them). */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <glib.h>

#include "pw85.h"
#include "refdata.h"
#include "testutil.h"

#ifdef __SIZEOF_FLOAT128__
typedef __float128 real;
#else
typedef long double real;
#endif

/* ---- references ---------------------------------------------------- */


static real rsqrt(real x) {
  if (x <= 0) return 0;
  real y = (real)sqrt((double)x);
  for (int i = 0; i < 3; ++i) y = (y + x / y) / 2;
  return y;
}

/* f, f', f'' at lambda in extended precision; returns 0 if Q(lambda) is not
 * positive definite. */
static int ref_eval(real lam, const double r[3], const double q1[6], const double q2[6],
                    real *f, real *df, real *d2f) {
  real q[6], d[6];
  for (int i = 0; i < 6; ++i) {
    q[i] = (1 - lam) * (real)q1[i] + lam * (real)q2[i];
    d[i] = (real)q2[i] - (real)q1[i];
  }
  real d0 = q[0];
  if (!(d0 > 0)) return 0;
  real l10 = q[1] / d0, l20 = q[2] / d0;
  real d1 = q[3] - l10 * q[1];
  if (!(d1 > 0)) return 0;
  real e = q[4] - l20 * q[1], l21 = e / d1;
  real d2 = q[5] - l20 * q[2] - l21 * e;
  if (!(d2 > 0)) return 0;
  real b[3] = {r[0], r[1], r[2]}, s[3], u[3], v[3];
  for (int pass = 0; pass < 2; ++pass) {
    real *x = pass ? v : s;
    real y0 = b[0], y1 = b[1] - l10 * y0, y2 = b[2] - l20 * y0 - l21 * y1;
    x[2] = y2 / d2;
    x[1] = y1 / d1 - l21 * x[2];
    x[0] = y0 / d0 - l10 * x[1] - l20 * x[2];
    if (!pass) {
      u[0] = d[0] * s[0] + d[1] * s[1] + d[2] * s[2];
      u[1] = d[1] * s[0] + d[3] * s[1] + d[4] * s[2];
      u[2] = d[2] * s[0] + d[4] * s[1] + d[5] * s[2];
      b[0] = u[0], b[1] = u[1], b[2] = u[2];
    }
  }
  real phi = (real)r[0] * s[0] + (real)r[1] * s[1] + (real)r[2] * s[2];
  real phi1 = -(s[0] * u[0] + s[1] * u[1] + s[2] * u[2]);
  real phi2 = 2 * (u[0] * v[0] + u[1] * v[1] + u[2] * v[2]);
  real p = lam * (1 - lam), p1 = 1 - 2 * lam;
  *f = p * phi;
  *df = p1 * phi + p * phi1;
  *d2f = -2 * phi + 2 * p1 * phi1 + p * phi2;
  return 1;
}

/* max of the concave f on [0, 1]. */
static double ref_mu2(const double r[3], const double q1[6], const double q2[6]) {
  real lo = 0, hi = 1, f, df, d2f;
  for (int k = 0; k < 45; ++k) {
    real m = (lo + hi) / 2;
    g_assert_true(ref_eval(m, r, q1, q2, &f, &df, &d2f));
    if (df > 0)
      lo = m;
    else
      hi = m;
  }
  real lam = (lo + hi) / 2;
  for (int k = 0; k < 6; ++k) {
    g_assert_true(ref_eval(lam, r, q1, q2, &f, &df, &d2f));
    real next = lam - df / d2f;
    if (!(next > lo && next < hi)) break;
    lam = next;
  }
  g_assert_true(ref_eval(lam, r, q1, q2, &f, &df, &d2f));
  return (double)f;
}

/* r^T Q^{-1} r / 4 (identical ellipsoids, lambda = 1/2). */
static double ref_identical(const double r[3], const double q[6]) {
  real f, df, d2f;
  g_assert_true(ref_eval(0.5, r, q, q, &f, &df, &d2f));
  return (double)f; /* f(1/2) = r^T Q^{-1} r / 4 */
}

/* Spheres Q1 = a I, Q2 = b I (a, b the doubles of the squared radii). */
static double ref_spheres(const double r[3], double qa, double qb) {
  real rr = (real)r[0] * r[0] + (real)r[1] * r[1] + (real)r[2] * r[2];
  real s = rsqrt(qa) + rsqrt(qb);
  return (double)(rr / (s * s));
}

/* ---- method table ---------------------------------------------------- */

/* One line of the failure map: the most pairs of case `scase` a method may
 * flag (status PW85_ERR_INACCURATE or PW85_ERR_NO_CONVERGENCE), and the
 * region where it may: parameter >= min_param (with two_sided, max(p, 1/p)
 * >= min_param). Cases a method's map does not list allow no flag at all. */
typedef struct {
  const char *scase;
  int max_flagged;
  double min_param;
  int two_sided;
} Allowance;

#define MAX_ALLOWANCES 8

typedef struct {
  const char *name;
  int id;
  double accuracy; /* documented relative accuracy (include/pw85.h) */
  Allowance map[MAX_ALLOWANCES];
} Method;

/* The failure map, from docs/stability.md, section "Where each method fails
 * and why" (its table: "fails on" gives the regions, "measured" the flagged
 * counts per case) and the paragraph after the table (flagged counts of the
 * case scales). The parameter is the aspect ratio k for aspect, identical,
 * coaxial and needle_disc, the radii ratio for spheres, the angle for
 * parallel_needles and the scale for scales; min_param 0 means the section
 * gives no region for the case. */
static const Method methods[] = {
    /* DEFAULT: "nothing in these sweeps", 0 flagged of 669. */
    {"default", PW85_METHOD_DEFAULT, 1e-14, {{NULL, 0, 0, 0}}},
    /* BRENT: aspect >= 1e3; identical needles/discs >= 1e3; spheres of radii
     * ratio >= 1e6; coaxial and needle_disc at 1e6; parallel needles. */
    {"brent",
     PW85_METHOD_BRENT,
     1e-10,
     {{"aspect", 55, 1e3, 0},
      {"identical", 31, 1e3, 0},
      {"spheres", 18, 1e6, 1},
      {"coaxial", 5, 1e6, 0},
      {"needle_disc", 6, 1e6, 0},
      {"scales", 4, 0, 0},
      {"parallel_needles", 1, 0, 0},
      {NULL, 0, 0, 0}}},
    /* NEWTON: aspect >= 1e2 (random orientations), identical >= 1e2. */
    {"newton",
     PW85_METHOD_NEWTON,
     1e-12,
     {{"aspect", 81, 1e2, 0},
      {"identical", 39, 1e2, 0},
      {"parallel_needles", 2, 0, 0},
      {"scales", 15, 0, 0},
      {NULL, 0, 0, 0}}},
    /* RATIONAL: aspect >= 1e2, identical >= 30, parallel needles. */
    {"rational",
     PW85_METHOD_RATIONAL,
     1e-12,
     {{"aspect", 88, 1e2, 0},
      {"identical", 42, 30, 0},
      {"scales", 23, 0, 0},
      {"parallel_needles", 2, 0, 0},
      {NULL, 0, 0, 0}}},
    /* ZHENG: aspect >= 1e4, identical >= 1e3 (docs/dca.md). */
    {"zheng",
     PW85_METHOD_ZHENG,
     1e-9,
     {{"aspect", 32, 1e4, 0},
      {"identical", 25, 1e3, 0},
      {"needle_disc", 3, 1e4, 0},
      {"parallel_needles", 1, 0, 0},
      {NULL, 0, 0, 0}}},
};
#define N_METHODS (sizeof methods / sizeof methods[0])

typedef struct {
  const Method *m;
  const char *scase;
  const Allowance *allowed; /* NULL: no flag allowed */
  int n, n_flagged, n_flagged_outside; /* outside: where the map allows none */
  double min_flagged_param;
  double max_err_ok, max_err_all;
  double worst_param; /* parameter (aspect ratio, ...) of the largest error */
} Stats;

static void stats_init(Stats *st, const Method *m, const char *scase) {
  memset(st, 0, sizeof *st);
  st->m = m;
  st->scase = scase;
  st->min_flagged_param = INFINITY;
  for (const Allowance *a = m->map; a->scase != NULL; ++a)
    if (strcmp(a->scase, scase) == 0) st->allowed = a;
}

/* The flagged pairs against the failure map (docs/stability.md, "Where each
 * method fails and why"). */
static void check_failure_map(const Stats *st) {
  int const allowed = st->allowed != NULL ? st->allowed->max_flagged : 0;
  if (st->n_flagged > allowed || st->n_flagged_outside > 0) {
    g_test_message("%s/%s: %d pairs flagged (%d outside the region of the failure map, "
                   "smallest parameter %.3g); the map of docs/stability.md allows %d%s",
                   st->m->name, st->scase, st->n_flagged, st->n_flagged_outside,
                   st->min_flagged_param, allowed,
                   st->allowed != NULL && st->allowed->min_param > 0 ? " in its region" : "");
  }
  g_assert_cmpint(st->n_flagged, <=, allowed);
  g_assert_cmpint(st->n_flagged_outside, ==, 0);
}

static void stats_report(const Stats *st) {
  g_test_message("%s/%s: %d pairs, %d flagged (status != OK, smallest parameter flagged "
                 "%.3g), max rel. err. of OK results %.2e, of all results %.2e (at parameter "
                 "%.3g)",
                 st->m->name, st->scase, st->n, st->n_flagged, st->min_flagged_param,
                 st->max_err_ok, st->max_err_all, st->worst_param);
  check_failure_map(st);
}

/* Calls the method, checks the contract, updates st. A method the library
 * does not know fails the test. */
static void check(Stats *st, const double r[3], const double q1[6], const double q2[6],
                  double ref, double param) {
  pw85_result res;
  int s = pw85_contact_function_method(r, q1, q2, st->m->id, &res);
  g_assert_cmpint(s, !=, PW85_ERR_UNKNOWN_METHOD);
  if (!(s == PW85_OK || s == PW85_ERR_INACCURATE || s == PW85_ERR_NO_CONVERGENCE))
    g_error("%s/%s: unexpected status %d (%s) at parameter %g", st->m->name, st->scase, s,
            pw85_strerror(s), param);
  g_assert_true(isfinite(res.mu2));
  g_assert_true(isfinite(res.lambda));
  g_assert_true(isfinite(res.mu2_error) && res.mu2_error >= 0.0);
  g_assert_cmpint(res.method, ==, st->m->id);
  double err = ref == 0.0 ? fabs(res.mu2) : fabs(res.mu2 - ref) / ref;
  ++st->n;
  if (err > st->max_err_all) {
    st->max_err_all = err;
    st->worst_param = param;
  }
  if (s == PW85_OK) {
    if (!(err <= st->m->accuracy))
      g_error("%s/%s: silent failure at parameter %g: status OK but rel. err. %.3e > %.0e "
              "(mu2 %.17g, reference %.17g, mu2_error %.3e)",
              st->m->name, st->scase, param, err, st->m->accuracy, res.mu2, ref,
              res.mu2_error);
    if (err > st->max_err_ok) st->max_err_ok = err;
  } else {
    ++st->n_flagged;
    double const where = st->allowed != NULL && st->allowed->two_sided ? fmax(param, 1 / param)
                                                                       : param;
    st->min_flagged_param = fmin(st->min_flagged_param, param);
    if (st->allowed == NULL || where < st->allowed->min_param) ++st->n_flagged_outside;
    if (st->m->id == PW85_METHOD_DEFAULT)
      g_error("default/%s: status %d (%s) at parameter %g, rel. err. %.3e", st->scase, s,
              pw85_strerror(s), param, err);
  }
}

/* Centres on the x axis, x a principal axis of both ellipsoids (q1[0] and
 * q2[0] the squared semi-axes along it): mu^2 = d^2 / (a1 + a2)^2 with
 * a_k = sqrt(qk[0]), the reference formed in extended precision. */
static void check_on_axis(Stats *st, const double q1[6], const double q2[6], double d,
                          double param) {
  double r[3] = {d, 0, 0};
  real s = rsqrt(q1[0]) + rsqrt(q2[0]);
  check(st, r, q1, q2, (double)((real)d * d / (s * s)), param);
}

/* ---- scenes ------------------------------------------------------------ */

static const double aspects[] = {1, 3, 10, 30, 1e2, 1e3, 1e4, 1e5, 1e6};
#define N_ASPECTS (sizeof aspects / sizeof aspects[0])

/* Needle (1, 1/k, 1/k) or disc (1, 1, 1/k), random orientation. */
static void shape(GRand *rng, double k, int disc, double q[6]) {
  double radii[3] = {1.0, disc ? 1.0 : 1.0 / k, 1.0 / k}, axes[9];
  random_axes(rng, axes);
  make_q(radii, axes, q);
}

static void random_dir(GRand *rng, double scale, double r[3]) {
  double n = 0;
  do {
    for (int i = 0; i < 3; ++i) r[i] = g_rand_double_range(rng, -1, 1);
    n = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
  } while (n < 0.1 || n > 1);
  for (int i = 0; i < 3; ++i) r[i] *= scale / n;
}

/* Aspect-ratio sweep: random needles and discs, random r from overlap to
 * apart; general references. */
static void test_aspect(gconstpointer data) {
  const Method *m = data;
  GRand *rng = g_rand_new_with_seed(7001);
  Stats st;
  stats_init(&st, m, "aspect");
  for (size_t a = 0; a < N_ASPECTS; ++a)
    for (int disc1 = 0; disc1 < 2; ++disc1)
      for (int disc2 = 0; disc2 < 2; ++disc2)
        for (int rep = 0; rep < 6; ++rep) {
          double q1[6], q2[6], r[3];
          shape(rng, aspects[a], disc1, q1);
          shape(rng, aspects[a], disc2, q2);
          random_dir(rng, pow(10.0, g_rand_double_range(rng, -2, 0.5)) * 2.0, r);
          check(&st, r, q1, q2, ref_mu2(r, q1, q2), aspects[a]);
        }
  stats_report(&st);
  g_rand_free(rng);
}

/* Identical ellipsoids: mu^2 = r^T Q^{-1} r / 4. */
static void test_identical(gconstpointer data) {
  const Method *m = data;
  GRand *rng = g_rand_new_with_seed(7002);
  Stats st;
  stats_init(&st, m, "identical");
  for (size_t a = 0; a < N_ASPECTS; ++a)
    for (int disc = 0; disc < 2; ++disc)
      for (int rep = 0; rep < 4; ++rep) {
        double q[6], r[3];
        shape(rng, aspects[a], disc, q);
        random_dir(rng, g_rand_double_range(rng, 0.01, 3), r);
        check(&st, r, q, q, ref_identical(r, q), aspects[a]);
      }
  stats_report(&st);
  g_rand_free(rng);
}

/* Coaxial ellipsoids aligned along a principal axis (x): Q_i diagonal,
 * r = (d, 0, 0): mu = d / (a1 + a2), a_i = sqrt(Q_i[0]). The other
 * semi-axes make needles and discs of aspect ratio up to 1e6. */
static void test_coaxial(gconstpointer data) {
  const Method *m = data;
  Stats st;
  stats_init(&st, m, "coaxial");
  for (size_t a = 0; a < N_ASPECTS; ++a)
    for (int kind = 0; kind < 4; ++kind) {
      double k = aspects[a];
      /* kind 0: needles along x; 1: discs normal to x; 2: needle along x vs
       * disc normal to x; 3: needles across x (long axes y and z). */
      double r1[3], r2[3];
      switch (kind) {
        case 0: r1[0] = 1, r1[1] = 1 / k, r1[2] = 1 / k; r2[0] = 2, r2[1] = 2 / k, r2[2] = 1 / k; break;
        case 1: r1[0] = 1 / k, r1[1] = 1, r1[2] = 1; r2[0] = 1 / k, r2[1] = 2, r2[2] = 3; break;
        case 2: r1[0] = 1, r1[1] = 1 / k, r1[2] = 1 / k; r2[0] = 1 / k, r2[1] = 1, r2[2] = 1; break;
        default: r1[0] = 1 / k, r1[1] = 1, r1[2] = 1 / k; r2[0] = 1 / k, r2[1] = 1 / k, r2[2] = 1; break;
      }
      double q1[6] = {r1[0] * r1[0], 0, 0, r1[1] * r1[1], 0, r1[2] * r1[2]};
      double q2[6] = {r2[0] * r2[0], 0, 0, r2[1] * r2[1], 0, r2[2] * r2[2]};
      for (int j = 0; j < 5; ++j) {
        double d = (rsqrt(q1[0]) + rsqrt(q2[0])) * (double)(0.1 + 0.5 * j);
        check_on_axis(&st, q1, q2, d, k);
      }
    }
  stats_report(&st);
}

/* Near tangency: spheres and coaxial ellipsoids at mu^2 = (1 + eps)^2, eps
 * down to 1e-15 (both signs). */
static void test_tangency(gconstpointer data) {
  const Method *m = data;
  Stats st;
  stats_init(&st, m, "tangency");
  for (int e = 1; e <= 15; ++e)
    for (int sign = -1; sign <= 1; sign += 2)
      for (int kind = 0; kind < 2; ++kind) {
        double eps = sign * pow(10.0, -e);
        double q1[6], q2[6];
        if (kind == 0) {
          double a = 1.5, b = 0.25;
          double qq1[6] = {a * a, 0, 0, a * a, 0, a * a}, qq2[6] = {b * b, 0, 0, b * b, 0, b * b};
          memcpy(q1, qq1, sizeof q1);
          memcpy(q2, qq2, sizeof q2);
        } else {
          double qq1[6] = {1, 0, 0, 1e-4, 0, 1e-6}, qq2[6] = {0.25, 0, 0, 4, 0, 9};
          memcpy(q1, qq1, sizeof q1);
          memcpy(q2, qq2, sizeof q2);
        }
        double d = (sqrt(q1[0]) + sqrt(q2[0])) * (1 + eps);
        check_on_axis(&st, q1, q2, d, eps);
      }
  stats_report(&st);
}

/* Coincident centres: mu^2 = 0 exactly. */
static void test_coincident(gconstpointer data) {
  const Method *m = data;
  GRand *rng = g_rand_new_with_seed(7003);
  Stats st;
  stats_init(&st, m, "coincident");
  for (size_t a = 0; a < N_ASPECTS; ++a) {
    double q1[6], q2[6], r[3] = {0, 0, 0};
    shape(rng, aspects[a], 0, q1);
    shape(rng, aspects[a], 1, q2);
    pw85_result res;
    int s = pw85_contact_function_method(r, q1, q2, m->id, &res);
    g_assert_cmpint(s, ==, PW85_OK);
    g_assert_cmpfloat(res.mu2, ==, 0.0);
    g_assert_cmpfloat(res.mu2_error, ==, 0.0);
    g_assert_true(res.lambda >= 0.0 && res.lambda <= 1.0);
    ++st.n;
  }
  stats_report(&st);
  g_rand_free(rng);
}

/* Needle along z crossing a disc normal to z (in the plane z = 0): centres
 * offset along random directions. */
static void test_needle_disc(gconstpointer data) {
  const Method *m = data;
  GRand *rng = g_rand_new_with_seed(7004);
  Stats st;
  stats_init(&st, m, "needle_disc");
  for (size_t a = 0; a < N_ASPECTS; ++a) {
    double k = aspects[a];
    double q1[6] = {1 / (k * k), 0, 0, 1 / (k * k), 0, 1}; /* needle along z */
    double q2[6] = {1, 0, 0, 1, 0, 1 / (k * k)};           /* disc normal to z */
    for (int rep = 0; rep < 6; ++rep) {
      double r[3];
      random_dir(rng, g_rand_double_range(rng, 0.05, 4), r);
      check(&st, r, q1, q2, ref_mu2(r, q1, q2), k);
    }
  }
  stats_report(&st);
  g_rand_free(rng);
}

/* Nearly parallel needles of aspect ratio 1e3 and 1e5 at angles 1e-1 to
 * 1e-8 rad, side by side and end to end. */
static void test_parallel_needles(gconstpointer data) {
  const Method *m = data;
  Stats st;
  stats_init(&st, m, "parallel_needles");
  const double ks[] = {1e3, 1e5};
  for (int ik = 0; ik < 2; ++ik)
    for (int e = 1; e <= 8; ++e) {
      double k = ks[ik], th = pow(10.0, -e);
      double radii[3] = {1.0, 1.0 / k, 1.0 / k};
      double ax1[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
      double c = cos(th), s = sin(th);
      double ax2[9] = {c, s, 0, -s, c, 0, 0, 0, 1};
      double q1[6], q2[6];
      make_q(radii, ax1, q1);
      make_q(radii, ax2, q2);
      double rs[3][3] = {{0, 3.0 / k, 0}, {2.5, 0, 0}, {0.3, 1.0 / k, 1.5 / k}};
      for (int j = 0; j < 3; ++j)
        check(&st, rs[j], q1, q2, ref_mu2(rs[j], q1, q2), th);
    }
  stats_report(&st);
}

/* Spheres of radii 1e-6 and 1e6 (and both equal), several distances. */
static void test_spheres(gconstpointer data) {
  const Method *m = data;
  GRand *rng = g_rand_new_with_seed(7005);
  Stats st;
  stats_init(&st, m, "spheres");
  const double radii[][2] = {{1e-6, 1e6}, {1e6, 1e-6}, {1e-6, 1e-6}, {1e6, 1e6}, {1, 1e-6}};
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 6; ++j) {
      double a = radii[i][0] * radii[i][0], b = radii[i][1] * radii[i][1];
      double q1[6] = {a, 0, 0, a, 0, a}, q2[6] = {b, 0, 0, b, 0, b}, r[3];
      random_dir(rng, (radii[i][0] + radii[i][1]) * pow(10.0, -2.0 + 0.8 * j), r);
      check(&st, r, q1, q2, ref_spheres(r, a, b), radii[i][0] / radii[i][1]);
    }
  stats_report(&st);
  g_rand_free(rng);
}

/* Extreme magnitudes: the same shapes scaled by 1e-150 ... 1e150 (Q by the
 * square), so that products of entries of Q overflow or underflow in double
 * unless the method rescales. */
static void test_scales(gconstpointer data) {
  const Method *m = data;
  GRand *rng = g_rand_new_with_seed(7007);
  Stats st;
  stats_init(&st, m, "scales");
  const double scales[] = {1e-150, 1e-60, 1e-20, 1e20, 1e60, 1e150};
  for (int i = 0; i < 6; ++i)
    for (int a = 0; a < 4; ++a)
      for (int rep = 0; rep < 3; ++rep) {
        double q1[6], q2[6], r[3], sc = scales[i], k = pow(10.0, a);
        shape(rng, k, rep & 1, q1);
        shape(rng, k, (rep >> 1) & 1, q2);
        for (int j = 0; j < 6; ++j) {
          q1[j] *= sc * sc;
          q2[j] *= sc * sc;
        }
        random_dir(rng, sc * pow(10.0, g_rand_double_range(rng, -2, 0.5)) * 2.0, r);
        check(&st, r, q1, q2, ref_mu2(r, q1, q2), sc);
      }
  stats_report(&st);
  g_rand_free(rng);
}

/* Invalid method ids and bad input: status and NaN-filled result. */
static void test_errors(void) {
  double r[3] = {1, 0, 0}, q[6] = {1, 0, 0, 1, 0, 1}, bad[6] = {1, 0, 0, -1, 0, 1};
  pw85_result res;
  g_assert_cmpint(pw85_contact_function_method(r, q, q, -1, &res), ==, PW85_ERR_UNKNOWN_METHOD);
  g_assert_true(isnan(res.mu2) && isnan(res.lambda) && isnan(res.mu2_error));
  g_assert_cmpint(pw85_contact_function_method(r, q, q, 99, &res), ==, PW85_ERR_UNKNOWN_METHOD);
  g_assert_true(isnan(res.mu2));
  g_assert_cmpint(pw85_contact_function_method(r, q, bad, PW85_METHOD_DEFAULT, &res), ==,
                  PW85_ERR_NOT_SPD);
  g_assert_true(isnan(res.mu2) && isnan(res.mu2_error));
  g_assert_cmpint(res.iterations, ==, 0);
  g_assert_cmpint(pw85_contact_function_method(NULL, q, q, PW85_METHOD_DEFAULT, &res), ==,
                  PW85_ERR_INVALID_ARGUMENT);
  g_assert_true(isnan(res.mu2));
  r[1] = NAN;
  g_assert_cmpint(pw85_contact_function_method(r, q, q, PW85_METHOD_DEFAULT, &res), ==,
                  PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_contact_function_method(r, q, q, PW85_METHOD_DEFAULT, NULL), ==,
                  PW85_ERR_INVALID_ARGUMENT);
  /* The one-pass screen of the C layer (src/capi/validate.hpp) must send
     every one of these to the general checks. */
  r[1] = INFINITY;
  g_assert_cmpint(pw85_contact_function_method(r, q, q, PW85_METHOD_DEFAULT, &res), ==,
                  PW85_ERR_INVALID_ARGUMENT);
  g_assert_true(isnan(res.mu2));
  r[1] = 0.0;
  double qnan[6] = {1, 0, 0, 1, NAN, 1};
  g_assert_cmpint(pw85_contact_function_method(r, q, qnan, PW85_METHOD_DEFAULT, &res), ==,
                  PW85_ERR_INVALID_ARGUMENT);
  g_assert_true(isnan(res.mu2));
  double zero[3] = {0, 0, 0};
  g_assert_cmpint(pw85_contact_function_method(zero, q, q, PW85_METHOD_DEFAULT, &res), ==,
                  PW85_OK);
  g_assert_cmpfloat(res.mu2, ==, 0.0);
  g_assert_cmpfloat(res.lambda, ==, 0.5);
}

/* Magnitudes on both sides of the screen's range (2^-60, 2^60): the same
   pair scaled by 2^k (r) and 4^k (Q) has the same mu2 / 4^0 = mu2 and the
   same lambda, whichever path (screened or rescaled) computes it. */
static void test_magnitudes(gconstpointer data) {
  Method const *m = data;
  double const r0[3] = {0.7, -0.4, 1.3};
  double const q10[6] = {1.5, 0.2, -0.1, 0.8, 0.3, 2.0};
  double const q20[6] = {0.6, -0.05, 0.1, 1.1, 0.0, 0.4};
  pw85_result ref;
  int const s0 = pw85_contact_function_method(r0, q10, q20, m->id, &ref);
  g_assert_cmpint(s0, ==, PW85_OK);
  static const int ks[] = {-40, -31, -30, -29, 29, 30, 31, 40, 200, -200};
  for (size_t i = 0; i < sizeof ks / sizeof ks[0]; ++i) {
    double r[3], q1[6], q2[6];
    for (int j = 0; j < 3; ++j) r[j] = ldexp(r0[j], ks[i]);
    for (int j = 0; j < 6; ++j) {
      q1[j] = ldexp(q10[j], 2 * ks[i]);
      q2[j] = ldexp(q20[j], 2 * ks[i]);
    }
    pw85_result res;
    g_assert_cmpint(pw85_contact_function_method(r, q1, q2, m->id, &res), ==, s0);
    g_assert_cmpfloat(fabs(res.mu2 - ref.mu2), <=, 4e-15 * ref.mu2);
    g_assert_cmpfloat(fabs(res.lambda - ref.lambda), <=, 1e-12);
  }
}

/* Magnitude ratio of the two matrices (docs/stability.md, "Accepted input
 * ranges"): Q2 -> 2^k Q2 with r and Q1 fixed, k = -1070..1023 (exact
 * scalings). Every status is one of PW85_OK, PW85_ERR_INACCURATE,
 * PW85_ERR_NO_CONVERGENCE, PW85_ERR_RANGE, mu2 is not NaN, and for |k| <= 60
 * (where the reference resolves lambda*) PW85_OK comes with mu2 within the
 * documented accuracy of the __float128 reference. Reports the range of k
 * around 0 in which the status is PW85_OK throughout. */
static void test_matrix_ratio(gconstpointer data) {
  Method const *m = data;
  double const r[3] = {1.25, -0.5, 0.75};
  double const q1[6] = {1, 0.125, -0.25, 0.5, 0.0625, 0.375};
  double const q20[6] = {0.25, -0.0625, 0, 1, 0.125, 0.5};
  int lo = 0, hi = 0, n_ok = 0, n_flagged = 0, n_nan = 0;
  int lo_open = 1, hi_open = 1;
  int status_at[2100];
  for (int k = -1070; k <= 1023; ++k) {
    double q2[6];
    for (int j = 0; j < 6; ++j) q2[j] = ldexp(q20[j], k);
    pw85_result res;
    int const s = pw85_contact_function_method(r, q1, q2, m->id, &res);
    status_at[k + 1070] = s;
    g_assert_true(s == PW85_OK || s == PW85_ERR_INACCURATE || s == PW85_ERR_NO_CONVERGENCE ||
                  s == PW85_ERR_RANGE);
    /* NaN estimates with a failure status: counted (NEWTON, ZHENG; see
     * docs/stability.md, "Accepted input ranges"). */
    if (isnan(res.mu2)) {
      g_assert_cmpint(s, !=, PW85_OK);
      n_nan++;
    }
    if (s == PW85_OK) {
      n_ok++;
      if (abs(k) <= 60) {
        double const ref = ref_mu2(r, q1, q2);
        g_assert_cmpfloat(fabs(res.mu2 - ref), <=, m->accuracy * ref);
      }
    } else {
      n_flagged++;
    }
  }
  for (int k = 0; k >= -1070 && lo_open; --k)
    if (status_at[k + 1070] == PW85_OK) lo = k; else lo_open = 0;
  for (int k = 0; k <= 1023 && hi_open; ++k)
    if (status_at[k + 1070] == PW85_OK) hi = k; else hi_open = 0;
  g_test_message("%s: PW85_OK for every k in [%d, %d]; %d PW85_OK, %d other statuses (%d with "
                 "mu2 NaN) over k = -1070..1023", m->name, lo, hi, n_ok, n_flagged, n_nan);
}

/* BRENT is pw85_contact_function(): same mu2 and lambda bit for bit. */
static void test_brent_is_legacy(void) {
  GRand *rng = g_rand_new_with_seed(7006);
  for (int i = 0; i < 50; ++i) {
    double q1[6], q2[6], r[3], out[2];
    shape(rng, 10, i & 1, q1);
    shape(rng, 10, (i >> 1) & 1, q2);
    random_dir(rng, 1.0, r);
    pw85_result res;
    int s1 = pw85_contact_function(r, q1, q2, out);
    int s2 = pw85_contact_function_method(r, q1, q2, PW85_METHOD_BRENT, &res);
    g_assert_true(s2 == PW85_OK || s2 == PW85_ERR_INACCURATE);
    g_assert_cmpint(s1, ==, s2);
    g_assert_cmpfloat(res.mu2, ==, out[0]);
    g_assert_cmpfloat(res.lambda, ==, out[1]);
  }
  g_rand_free(rng);
}

/* pw85_contact_function (pw85 1.0's Brent) on random ellipsoids with
 * semi-axes log-uniform in [1e-4, 1e4] (kappa(Q) up to 1e16, within the
 * reach of the __float128 reference): PW85_OK only within the 1e-10 of
 * PW85_METHOD_BRENT; the others PW85_ERR_INACCURATE or
 * PW85_ERR_NO_CONVERGENCE, with the same values as method BRENT. */
static void test_legacy_ill_conditioned(void) {
  GRand *rng = g_rand_new_with_seed(7007);
  int flagged = 0, n = 0, mismatched = 0;
  double worst_ok = 0.0, worst = 0.0;
  for (int i = 0; i < 2000; ++i) {
    double radii[3], axes[9], q1[6], q2[6], r[3], out[2];
    random_radii(rng, 1e-4, 1e4, radii);
    random_axes(rng, axes);
    make_q(radii, axes, q1);
    random_radii(rng, 1e-4, 1e4, radii);
    random_axes(rng, axes);
    make_q(radii, axes, q2);
    random_dir(rng, exp(g_rand_double_range(rng, log(1e-4), log(1e4))), r);
    int const s = pw85_contact_function(r, q1, q2, out);
    pw85_result res;
    int const sm = pw85_contact_function_method(r, q1, q2, PW85_METHOD_BRENT, &res);
    if (s == PW85_ERR_NOT_SPD || sm == PW85_ERR_NOT_SPD) continue; /* kappa(Q) ~ 1 / u */
    double const e = rel_error(out[0], ref_mu2(r, q1, q2));
    n++;
    worst = fmax(worst, e);
    if (s == PW85_OK) {
      worst_ok = fmax(worst_ok, e);
      g_assert_cmpfloat(e, <=, 1e-10);
    } else {
      flagged++;
      g_assert_true(s == PW85_ERR_INACCURATE || s == PW85_ERR_NO_CONVERGENCE);
    }
    mismatched += s != sm;
    g_assert_cmpfloat(res.mu2, ==, out[0]);
  }
  g_assert_cmpint(mismatched, ==, 0);
  g_test_message("pw85_contact_function, semi-axes in [1e-4, 1e4]: %d of %d flagged; max "
                 "rel. error %.3g, with PW85_OK %.3g", flagged, n, worst, worst_ok);
  g_rand_free(rng);
}

/* ---- ZHENG against the reference data ------------------------------------ */

/* pw85_contact_function_method with PW85_METHOD_ZHENG: mu2 = |r12|^2 / d^2,
 * lambda recovered from the optimal plane and polished (docs/dca.md). Up to
 * pair aspect 100: PW85_OK, mu2 to 1e-9 (documented), lambda to 1e-12;
 * beyond: PW85_OK only when the error estimate is within 1e-9 mu2, checked
 * to hold up to aspect 1e3 (measured beyond: printed). */
static void check_method_zheng(const char *group) {
  RefPairs *g = refdata_pairs_or_skip(group);
  if (g == NULL) return;
  g_assert_nonnull(g->radii1);
  g_assert_nonnull(g->radii2);
  double worst_mu2 = 0.0, worst_lambda = 0.0;
  int n_inaccurate = 0, n_ok_wrong = 0, n_high = 0;
  for (gsize i = 0; i < g->n; i++) {
    const double *r = g->r12 + 3 * i;
    pw85_result res;
    int status = pw85_contact_function_method(r, g->q1 + 6 * i, g->q2 + 6 * i,
                                              PW85_METHOD_ZHENG, &res);
    if (r[0] == 0.0 && r[1] == 0.0 && r[2] == 0.0) {
      g_assert_cmpint(status, ==, PW85_OK);
      g_assert_cmpfloat(res.mu2, ==, 0.0);
      continue;
    }
    double aspect = refdata_pair_aspect(g, i), e = rel_error(res.mu2, g->mu2[i]);
    double el = fabs(res.lambda - g->lambda[i]);
    g_assert_true(status == PW85_OK || status == PW85_ERR_INACCURATE);
    g_assert_cmpint(res.method, ==, PW85_METHOD_ZHENG);
    g_assert_cmpint(res.iterations, >, 0);
    g_assert_cmpint(res.iterations, <=, PW85_DCA_MAX_EVAL);
    if (aspect <= 100.0) {
      g_assert_cmpint(status, ==, PW85_OK);
      g_assert_cmpfloat(e, <=, 1e-9);
      g_assert_cmpfloat(el, <=, 1e-12);
      worst_mu2 = fmax(worst_mu2, e);
      worst_lambda = fmax(worst_lambda, el);
    } else {
      n_high++;
      if (status == PW85_ERR_INACCURATE) n_inaccurate++;
      if (status == PW85_OK && e > 1e-9) {
        n_ok_wrong++;
        g_assert_cmpfloat(aspect, >, 1e3);
      }
    }
  }
  g_test_message("%s, contact_function_method(ZHENG), pair aspect <= 100: max rel. error "
                 "of mu2 %.3g, max |lambda error| %.3g; aspect > 100: %d pairs, %d "
                 "PW85_ERR_INACCURATE, %d PW85_OK with error > 1e-9",
                 group, worst_mu2, worst_lambda, n_high, n_inaccurate, n_ok_wrong);
  refdata_pairs_free(g);
}

static void test_method_zheng_contact(void) { check_method_zheng("/contact"); }
static void test_method_zheng_special(void) { check_method_zheng("/special"); }


int main(int argc, char **argv) {
  g_test_init(&argc, &argv, NULL);
  static const struct {
    const char *name;
    GTestDataFunc fn;
  } cases[] = {
      {"aspect", test_aspect},           {"identical", test_identical},
      {"coaxial", test_coaxial},         {"tangency", test_tangency},
      {"coincident", test_coincident},   {"needle_disc", test_needle_disc},
      {"parallel_needles", test_parallel_needles}, {"spheres", test_spheres},
      {"scales", test_scales},           {"magnitudes", test_magnitudes},
      {"matrix_ratio", test_matrix_ratio},
  };
  for (size_t i = 0; i < N_METHODS; ++i)
    for (size_t j = 0; j < sizeof cases / sizeof cases[0]; ++j) {
      char *path = g_strdup_printf("/pw85_contact_function_method/%s/%s", methods[i].name,
                                   cases[j].name);
      g_test_add_data_func(path, &methods[i], cases[j].fn);
      g_free(path);
    }
  g_test_add_func("/pw85_contact_function_method/zheng/reference/contact",
                  test_method_zheng_contact);
  g_test_add_func("/pw85_contact_function_method/zheng/reference/special",
                  test_method_zheng_special);
  g_test_add_func("/pw85_contact_function_method/bad_input", test_errors);
  g_test_add_func("/pw85_contact_function_method/brent/same_as_pw85_contact_function",
                  test_brent_is_legacy);
  g_test_add_func("/pw85_contact_function/ill_conditioned/ok_within_1e-10",
                  test_legacy_ill_conditioned);
  return g_test_run();
}
