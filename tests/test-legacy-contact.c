/* Tests of pw85_legacy_contact_function1 (safeguarded Newton on f') and
 * pw85_legacy_contact_function2 (bisection on the numerator of f') against
 * the reference mu^2 of /contact (per class 0..3) and /near_contact; simple
 * cases; bad input. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <glib.h>

#include "refdata.h"
#include "testutil.h"
#include "pw85_legacy.h"

#define NUM_CLASSES 4
/* A result off by more than this (relative) must come with a non-zero
 * status, or be listed below (and in docs/legacy.md). */
#define WRONG_RTOL 1e-6

typedef int (*ContactFn)(const double *, const double *, const double *, double *);

/* Accuracy reached per class (/contact and /near_contact alike) by the
 * results returned with PW85_OK, and the largest share of non-zero statuses
 * on /contact, measured on the committed reference data (docs/legacy.md has
 * the numbers and the command) and asserted. Index: [method - 1][class].
 * Measured max relative errors with PW85_OK, /contact (/near_contact):
 *   method 1: 8.1e-16 (6.7e-16), 1.0e-13 (1.5e-13), 4.4e-10 (3.4e-10), 1.1e-9 (6.9e-10)
 *   method 2: 4.7e-15 (4.4e-15), 2.9e-12 (1.1e-11), 4.4e-11 (2.7e-11), 1.0e-10 (1.3e-10)
 * Measured shares of non-zero statuses on /contact:
 *   method 1: 0, 0, 0.04 %, 13.7 %;  method 2: 0, 0.18 %, 23.9 %, 59.9 %. */
static const double ok_max_rel[2][NUM_CLASSES] = {
    {8 * DBL_EPSILON, 1e-12, 2e-9, 5e-9},
    {40 * DBL_EPSILON, 5e-11, 2e-10, 5e-10},
};
static const double max_flagged_share[2][NUM_CLASSES] = {
    {0.001, 0.001, 0.002, 0.16},
    {0.001, 0.004, 0.26, 0.63},
};

/* Known failures: wrong by more than WRONG_RTOL with PW85_OK. Each entry is
 * documented in docs/legacy.md ("Where accuracy is lost, and why"). */
typedef struct {
  const char *group;
  int method;
  int row;
} KnownFailure;
static const KnownFailure known_failures[] = {
    {NULL, 0, -1},
};

static gboolean is_known_failure(const char *group, int method, int row) {
  for (gsize i = 0; i < G_N_ELEMENTS(known_failures); ++i) {
    const KnownFailure *k = &known_failures[i];
    if (k->group != NULL && k->method == method && k->row == row &&
        strcmp(k->group, group) == 0)
      return TRUE;
  }
  return FALSE;
}

typedef struct {
  const char *group;
  int method;
} Case;

static void run_group(gconstpointer data) {
  const Case *c = data;
  hid_t file;
  if (!refdata_open_or_skip(&file)) return;
  gchar *name;
  gsize n, n3, n6, nq, nc;
  name = g_strdup_printf("/%s/r12", c->group);
  double *r12 = refdata_read_double_all(file, name, &n3);
  g_assert_nonnull(r12);
  g_free(name);
  name = g_strdup_printf("/%s/q1", c->group);
  double *q1 = refdata_read_double_all(file, name, &n6);
  g_assert_nonnull(q1);
  g_free(name);
  name = g_strdup_printf("/%s/q2", c->group);
  double *q2 = refdata_read_double_all(file, name, &nq);
  g_assert_nonnull(q2);
  g_free(name);
  name = g_strdup_printf("/%s/mu2", c->group);
  double *mu2 = refdata_read_double_all(file, name, &n);
  g_assert_nonnull(mu2);
  g_free(name);
  name = g_strdup_printf("/%s/class", c->group);
  int *cls = refdata_read_int_all(file, name, &nc);
  g_assert_nonnull(cls);
  g_free(name);
  refdata_close(file);
  g_assert_cmpuint(n3, ==, 3 * n);
  g_assert_cmpuint(n6, ==, 6 * n);
  g_assert_cmpuint(nc, ==, n);

  ContactFn const fn = c->method == 1 ? pw85_legacy_contact_function1
                                      : pw85_legacy_contact_function2;
  gboolean const near = strcmp(c->group, "near_contact") == 0;
  double max_all[NUM_CLASSES] = {0}, max_ok[NUM_CLASSES] = {0};
  gsize count[NUM_CLASSES] = {0}, flagged[NUM_CLASSES] = {0};
  gsize wrong_flagged[NUM_CLASSES] = {0}, wrong_known[NUM_CLASSES] = {0};
  gsize by_status[8] = {0};
  gsize unexplained = 0;
  for (gsize i = 0; i < n; ++i) {
    int const k = cls[i];
    g_assert_cmpint(k, >=, 0);
    g_assert_cmpint(k, <, NUM_CLASSES);
    double out[2];
    int const status = fn(r12 + 3 * i, q1 + 6 * i, q2 + 6 * i, out);
    g_assert_true(status == PW85_OK || status == PW85_ERR_NO_CONVERGENCE ||
                  status == PW85_ERR_INACCURATE);
    ++by_status[-status];
    double const err = rel_error(out[0], mu2[i]);
    ++count[k];
    if (!(err <= max_all[k])) max_all[k] = err;
    if (status == PW85_OK) {
      if (!(err <= max_ok[k])) max_ok[k] = err;
    } else {
      ++flagged[k];
    }
    if (!(err <= WRONG_RTOL)) {
      if (status != PW85_OK) {
        ++wrong_flagged[k];
      } else if (is_known_failure(c->group, c->method, (int)i)) {
        ++wrong_known[k];
      } else {
        ++unexplained;
        g_test_message("UNEXPLAINED %s method %d row %" G_GSIZE_FORMAT
                       " class %d: mu2 = %.17g, expected %.17g (rel. error %.3g), "
                       "lambda = %.17g", c->group, c->method, i, k, out[0], mu2[i], err,
                       out[1]);
      }
    }
  }
  g_test_message("%s, contact_function%d: statuses OK %" G_GSIZE_FORMAT
                 ", NO_CONVERGENCE %" G_GSIZE_FORMAT ", INACCURATE %" G_GSIZE_FORMAT,
                 c->group, c->method, by_status[0], by_status[3], by_status[6]);
  g_test_message("%5s %6s %12s %12s %8s %12s %12s", "class", "rows", "max_err_all",
                 "max_err_OK", "flagged", "wrong+flag", "wrong+known");
  for (int k = 0; k < NUM_CLASSES; ++k) {
    g_test_message("%5d %6" G_GSIZE_FORMAT " %12.3g %12.3g %8" G_GSIZE_FORMAT
                   " %12" G_GSIZE_FORMAT " %12" G_GSIZE_FORMAT,
                   k, count[k], max_all[k], max_ok[k], flagged[k], wrong_flagged[k],
                   wrong_known[k]);
  }
  g_assert_cmpuint(unexplained, ==, 0);
  for (int k = 0; k < NUM_CLASSES; ++k) {
    if (count[k] == 0) continue;
    g_assert_cmpfloat(max_ok[k], <=, ok_max_rel[c->method - 1][k]);
    if (!near)
      g_assert_cmpfloat((double)flagged[k] / (double)count[k], <=,
                        max_flagged_share[c->method - 1][k]);
  }
  g_free(r12);
  g_free(q1);
  g_free(q2);
  g_free(mu2);
  g_free(cls);
}

/* /special (coincident centres, identical ellipsoids, spheres, needles,
 * high aspect ratios; 9 kinds): every result off by more than WRONG_RTOL is
 * flagged, and those returned with PW85_OK are accurate. Measured max
 * relative error with PW85_OK: method 1 2.3e-10, method 2 4.0e-11; flagged:
 * method 1 100 of 660, method 2 286 of 660 (all 30 "very different spheres"
 * and all parallel / nearly parallel needles). */
static const double special_ok_max_rel[2] = {1e-9, 2e-10};

static void run_special(gconstpointer data) {
  int const method = GPOINTER_TO_INT(data);
  hid_t file;
  if (!refdata_open_or_skip(&file)) return;
  gsize n, n3, n6, nq, nk;
  double *r12 = refdata_read_double_all(file, "/special/r12", &n3);
  g_assert_nonnull(r12);
  double *q1 = refdata_read_double_all(file, "/special/q1", &n6);
  g_assert_nonnull(q1);
  double *q2 = refdata_read_double_all(file, "/special/q2", &nq);
  g_assert_nonnull(q2);
  double *mu2 = refdata_read_double_all(file, "/special/mu2", &n);
  g_assert_nonnull(mu2);
  int *kind = refdata_read_int_all(file, "/special/kind", &nk);
  g_assert_nonnull(kind);
  refdata_close(file);
  g_assert_cmpuint(n3, ==, 3 * n);
  g_assert_cmpuint(nk, ==, n);
  ContactFn const fn = method == 1 ? pw85_legacy_contact_function1
                                   : pw85_legacy_contact_function2;
  double max_ok = 0.0;
  gsize flagged = 0, unexplained = 0;
  for (gsize i = 0; i < n; ++i) {
    double out[2];
    int const status = fn(r12 + 3 * i, q1 + 6 * i, q2 + 6 * i, out);
    g_assert_true(status == PW85_OK || status == PW85_ERR_NO_CONVERGENCE ||
                  status == PW85_ERR_INACCURATE);
    double const err = rel_error(out[0], mu2[i]);
    if (status != PW85_OK) {
      ++flagged;
    } else {
      if (!(err <= max_ok)) max_ok = err;
      if (!(err <= WRONG_RTOL) && !is_known_failure("special", method, (int)i)) {
        ++unexplained;
        g_test_message("UNEXPLAINED special method %d row %" G_GSIZE_FORMAT
                       " kind %d: mu2 = %.17g, expected %.17g", method, i, kind[i],
                       out[0], mu2[i]);
      }
    }
  }
  g_test_message("special, contact_function%d: %" G_GSIZE_FORMAT " rows, %" G_GSIZE_FORMAT
                 " flagged, max relative error with PW85_OK %.3g", method, n, flagged,
                 max_ok);
  g_assert_cmpuint(unexplained, ==, 0);
  g_assert_cmpfloat(max_ok, <=, special_ok_max_rel[method - 1]);
  g_free(r12);
  g_free(q1);
  g_free(q2);
  g_free(mu2);
  g_free(kind);
}

/* Spheres of radii 1 and 2 at distance d: mu^2 = (d / 3)^2, lambda = 1/3. */
static void test_spheres(gconstpointer data) {
  ContactFn const fn = GPOINTER_TO_INT(data) == 1 ? pw85_legacy_contact_function1
                                                   : pw85_legacy_contact_function2;
  double const q1[6] = {1, 0, 0, 1, 0, 1}, q2[6] = {4, 0, 0, 4, 0, 4};
  double const ds[] = {0.01, 0.5, 3.0, 7.0, 1e3};
  for (gsize i = 0; i < G_N_ELEMENTS(ds); ++i) {
    double const r[3] = {0.0, ds[i], 0.0};
    double out[2];
    g_assert_cmpint(fn(r, q1, q2, out), ==, PW85_OK);
    double const exp = ds[i] * ds[i] / 9.0;
    g_assert_cmpfloat(fabs(out[0] - exp), <=, 16 * DBL_EPSILON * exp);
    g_assert_cmpfloat(fabs(out[1] - 1.0 / 3.0), <=, 1e-7);
  }
  /* Coincident centres. */
  double const zero[3] = {0, 0, 0};
  double out[2];
  g_assert_cmpint(fn(zero, q1, q2, out), ==, PW85_OK);
  g_assert_cmpfloat(out[0], ==, 0.0);
  g_assert_cmpfloat(out[1], ==, 0.5);
}

static void check_bad(ContactFn fn, const double *r, const double *q1, const double *q2,
                      int expected) {
  double out[2] = {0.0, 0.0};
  g_assert_cmpint(fn(r, q1, q2, out), ==, expected);
  g_assert_true(isnan(out[0]));
  g_assert_true(isnan(out[1]));
}

static void test_bad_input(gconstpointer data) {
  ContactFn const fn = GPOINTER_TO_INT(data) == 1 ? pw85_legacy_contact_function1
                                                   : pw85_legacy_contact_function2;
  double const q[6] = {1, 0, 0, 1, 0, 1}, r[3] = {1, 0, 0};
  double const not_spd[6] = {1, 0, 0, -1, 0, 1}, with_nan[6] = {1, 0, NAN, 1, 0, 1};
  double const r_nan[3] = {0, NAN, 0};
  check_bad(fn, NULL, q, q, PW85_ERR_INVALID_ARGUMENT);
  check_bad(fn, r, NULL, q, PW85_ERR_INVALID_ARGUMENT);
  check_bad(fn, r, q, NULL, PW85_ERR_INVALID_ARGUMENT);
  check_bad(fn, r_nan, q, q, PW85_ERR_INVALID_ARGUMENT);
  check_bad(fn, r, with_nan, q, PW85_ERR_INVALID_ARGUMENT);
  check_bad(fn, r, not_spd, q, PW85_ERR_NOT_SPD);
  check_bad(fn, r, q, not_spd, PW85_ERR_NOT_SPD);
  g_assert_cmpint(fn(r, q, q, NULL), ==, PW85_ERR_INVALID_ARGUMENT);
}

int main(int argc, char **argv) {
  g_test_init(&argc, &argv, NULL);
  static const Case cases[] = {
      {"contact", 1}, {"contact", 2}, {"near_contact", 1}, {"near_contact", 2}};
  g_test_add_data_func("/pw85_legacy_contact_function1/reference/contact", &cases[0], run_group);
  g_test_add_data_func("/pw85_legacy_contact_function2/reference/contact", &cases[1], run_group);
  g_test_add_data_func("/pw85_legacy_contact_function1/reference/near_contact", &cases[2],
                       run_group);
  g_test_add_data_func("/pw85_legacy_contact_function2/reference/near_contact", &cases[3],
                       run_group);
  g_test_add_data_func("/pw85_legacy_contact_function1/reference/special", GINT_TO_POINTER(1),
                       run_special);
  g_test_add_data_func("/pw85_legacy_contact_function2/reference/special", GINT_TO_POINTER(2),
                       run_special);
  g_test_add_data_func("/pw85_legacy_contact_function1/spheres", GINT_TO_POINTER(1), test_spheres);
  g_test_add_data_func("/pw85_legacy_contact_function2/spheres", GINT_TO_POINTER(2), test_spheres);
  g_test_add_data_func("/pw85_legacy_contact_function1/bad_input", GINT_TO_POINTER(1),
                       test_bad_input);
  g_test_add_data_func("/pw85_legacy_contact_function2/bad_input", GINT_TO_POINTER(2),
                       test_bad_input);
  return g_test_run();
}
