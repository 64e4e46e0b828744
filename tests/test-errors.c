/* Error handling of the whole pw85 1.0 API and the status codes: bad input
 * gives a negative status or NaN, never a crash, an abort or a print; GSL's
 * process-wide error handler is left alone; concurrent calls agree with
 * sequential ones. */
#include <math.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <pw85.h>

#include "testutil.h"

static void test_version(void) {
  g_assert_cmpstr(pw85_version(), ==, PW85_VERSION);
  char expected[32];
  g_snprintf(expected, sizeof expected, "%d.%d.%d", PW85_VERSION_MAJOR, PW85_VERSION_MINOR,
             PW85_VERSION_PATCH);
  g_assert_cmpstr(PW85_VERSION, ==, expected);
  g_assert_cmpint(PW85_DIM, ==, 3);
  g_assert_cmpint(PW85_SYM, ==, 6);
}

static void test_strerror(void) {
  int const codes[] = {PW85_OK,
                       PW85_ERR_INVALID_ARGUMENT,
                       PW85_ERR_NOT_SPD,
                       PW85_ERR_NO_CONVERGENCE,
                       PW85_ERR_NOT_ORTHONORMAL,
                       PW85_ERR_UNKNOWN_METHOD,
                       PW85_ERR_INACCURATE,
                       PW85_ERR_RANGE,
                       PW85_ERR_CAPACITY,
                       PW85_ERR_NO_MEMORY};
  const char *unknown = pw85_strerror(12345);
  g_assert_nonnull(unknown);
  for (size_t i = 0; i < G_N_ELEMENTS(codes); i++) {
    if (i > 0) g_assert_cmpint(codes[i], <, 0);
    const char *msg = pw85_strerror(codes[i]);
    g_assert_nonnull(msg);
    g_assert_cmpstr(msg, !=, unknown);
    for (size_t j = 0; j < i; j++) g_assert_cmpstr(msg, !=, pw85_strerror(codes[j]));
  }
}

static void assert_nan2(const double out[2]) {
  g_assert_true(isnan(out[0]));
  g_assert_true(isnan(out[1]));
}

/* Every argument of pw85_contact_function in turn: NULL, NaN, +-Inf. */
static void test_contact_function_bad_input(void) {
  double const r[3] = {1., 0.5, -0.25};
  double const q[6] = {1., 0.1, 0., 2., 0., 3.};
  double const specials[3] = {NAN, INFINITY, -INFINITY};
  double out[2];

  g_assert_cmpint(pw85_contact_function(NULL, q, q, out), ==, PW85_ERR_INVALID_ARGUMENT);
  assert_nan2(out);
  g_assert_cmpint(pw85_contact_function(r, NULL, q, out), ==, PW85_ERR_INVALID_ARGUMENT);
  assert_nan2(out);
  g_assert_cmpint(pw85_contact_function(r, q, NULL, out), ==, PW85_ERR_INVALID_ARGUMENT);
  assert_nan2(out);
  g_assert_cmpint(pw85_contact_function(r, q, q, NULL), ==, PW85_ERR_INVALID_ARGUMENT);

  for (int s = 0; s < 3; s++) {
    for (int i = 0; i < 3; i++) {
      double rr[3];
      memcpy(rr, r, sizeof rr);
      rr[i] = specials[s];
      out[0] = out[1] = 0.;
      g_assert_cmpint(pw85_contact_function(rr, q, q, out), ==, PW85_ERR_INVALID_ARGUMENT);
      assert_nan2(out);
    }
    for (int i = 0; i < 6; i++) {
      double qq[6];
      memcpy(qq, q, sizeof qq);
      qq[i] = specials[s];
      out[0] = out[1] = 0.;
      g_assert_cmpint(pw85_contact_function(r, qq, q, out), ==, PW85_ERR_INVALID_ARGUMENT);
      assert_nan2(out);
      out[0] = out[1] = 0.;
      g_assert_cmpint(pw85_contact_function(r, q, qq, out), ==, PW85_ERR_INVALID_ARGUMENT);
      assert_nan2(out);
    }
  }
}

/* Matrices that are not positive definite, including those pw85_spheroid
 * makes of zero, negative or NaN radii. */
static void test_contact_function_not_spd(void) {
  double const r[3] = {1., 0., 0.}, good[6] = {1., 0., 0., 1., 0., 1.};
  double const n[3] = {0., 0., 1.};
  double bad[][6] = {
      {0., 0., 0., 0., 0., 0.},
      {1., 0., 0., 1., 0., -1.},
      {1., 2., 0., 1., 0., 1.},
      {-1., 0., 0., -1., 0., -1.},
      {0}, {0}, {0},
  };
  pw85_spheroid(0., 1., n, bad[4]);
  pw85_spheroid(-1., 1., n, bad[5]);
  pw85_spheroid(NAN, 1., n, bad[6]);
  for (size_t k = 0; k < G_N_ELEMENTS(bad); k++) {
    double out[2] = {0., 0.};
    int const s1 = pw85_contact_function(r, bad[k], good, out);
    g_assert_cmpint(s1, <, 0);
    assert_nan2(out);
    out[0] = out[1] = 0.;
    int const s2 = pw85_contact_function(r, good, bad[k], out);
    g_assert_cmpint(s2, <, 0);
    assert_nan2(out);
    /* Finite matrices that are not positive definite are reported as such. */
    if (k < 4) {
      g_assert_cmpint(s1, ==, PW85_ERR_NOT_SPD);
      g_assert_cmpint(s2, ==, PW85_ERR_NOT_SPD);
    }
  }
}

/* The library must never install or change GSL's error handler. */
static void test_gsl_error_handler_untouched(void) {
  gsl_error_handler_t *before = gsl_set_error_handler(NULL);
  gsl_set_error_handler(before);
  double const r[3] = {1e-300, 0., 0.}, q[6] = {1., 0., 0., 1e-10, 0., 1e10};
  double out[2];
  pw85_contact_function(r, q, q, out);
  double const r2[3] = {1e300, 1e300, 0.};
  pw85_contact_function(r2, q, q, out);
  gsl_error_handler_t *after = gsl_set_error_handler(NULL);
  gsl_set_error_handler(after);
  g_assert_true(before == after);
}

/* Tiny and huge r12 (f underflows or overflows without rescaling). */
static void test_contact_function_extreme_r12(void) {
  double const q1[6] = {1., 0., 0., 4., 0., 9.}, q2[6] = {4., 0., 0., 1., 0., 1.};
  double const scales[] = {1e-300, 1e-160, 1e160, 1e300};
  for (size_t k = 0; k < G_N_ELEMENTS(scales); k++) {
    double const r[3] = {3. * scales[k], 0., 0.};
    double out[2];
    int const s = pw85_contact_function(r, q1, q2, out);
    /* aligned along x: mu = |r| / (1 + 2) */
    double const expected = scales[k] * scales[k];
    if (isfinite(expected) && expected >= DBL_MIN) {
      g_assert_cmpint(s, ==, PW85_OK);
      g_assert_cmpfloat(rel_error(out[0], expected), <=, 1e-12);
    } else {
      /* out of the range of double: rounded (+Inf or 0) */
      g_assert_cmpint(s, ==, PW85_ERR_RANGE);
      g_assert_true(out[0] == expected);
    }
  }
}

typedef struct {
  double r12[3], q1[6], q2[6], out[2];
  int status;
} job;

#define NUM_JOBS 512

static gpointer worker(gpointer data) {
  job *jobs = data;
  for (int rep = 0; rep < 4; rep++)
    for (int i = 0; i < NUM_JOBS; i++) {
      double out[2];
      int const status = pw85_contact_function(jobs[i].r12, jobs[i].q1, jobs[i].q2, out);
      if (status != jobs[i].status || memcmp(out, jobs[i].out, sizeof out) != 0)
        return GINT_TO_POINTER(1);
    }
  return GINT_TO_POINTER(0);
}

/* Concurrent calls give bitwise the results of sequential calls. */
static void test_contact_function_threads(void) {
  GRand *rng = g_rand_new_with_seed(99);
  job *jobs = g_new(job, NUM_JOBS);
  for (int i = 0; i < NUM_JOBS; i++) {
    double radii[3], axes[9];
    random_radii(rng, 0.01, 100., radii);
    random_axes(rng, axes);
    make_q(radii, axes, jobs[i].q1);
    random_radii(rng, 0.01, 100., radii);
    random_axes(rng, axes);
    make_q(radii, axes, jobs[i].q2);
    for (int k = 0; k < 3; k++) jobs[i].r12[k] = g_rand_double_range(rng, -100., 100.);
    jobs[i].status = pw85_contact_function(jobs[i].r12, jobs[i].q1, jobs[i].q2, jobs[i].out);
  }
  GThread *threads[4];
  for (int t = 0; t < 4; t++) threads[t] = g_thread_new("pw85", worker, jobs);
  for (int t = 0; t < 4; t++) g_assert_cmpint(GPOINTER_TO_INT(g_thread_join(threads[t])), ==, 0);
  g_free(jobs);
  g_rand_free(rng);
}

int main(int argc, char **argv) {
  g_test_init(&argc, &argv, NULL);
  g_test_add_func("/pw85_version", test_version);
  g_test_add_func("/pw85_strerror", test_strerror);
  g_test_add_func("/pw85_contact_function/bad_input", test_contact_function_bad_input);
  g_test_add_func("/pw85_contact_function/not_spd", test_contact_function_not_spd);
  g_test_add_func("/pw85_contact_function/extreme_r12", test_contact_function_extreme_r12);
  g_test_add_func("/pw85_contact_function/gsl_error_handler", test_gsl_error_handler_untouched);
  g_test_add_func("/pw85_contact_function/threads", test_contact_function_threads);
  return g_test_run();
}
