/* pw85_contact_function_method and pw85_contact on inputs where a method's
 * evaluations of f fail or lose their accuracy (extreme magnitudes, aspect
 * ratios, near-singular matrices): the answer is the same bits whatever
 * was computed before, its status is one of the documented list, and a
 * status that writes a value (PW85_OK, PW85_ERR_INACCURATE,
 * PW85_ERR_NO_CONVERGENCE) writes a finite mu2 >= 0, a lambda in [0, 1]
 * and a mu2_error that is not NaN (include/pw85.h, docs/stability.md). */
#include <float.h>
#include <math.h>
#include <string.h>

#include <glib.h>

#include "pw85.h"

typedef struct {
  double r[3], q1[6], q2[6];
} Pair;

/* Pairs found by fuzzing extreme inputs (docs/stability.md): NEWTON's and
 * DEFAULT's double iteration meets a Q(lambda) that is not numerically
 * positive definite after successful evaluations. */
static const Pair failing[] = {
    {{0x1.8543a6eb49d34p-8, 0x1.242ae6631625dp-7, -0x1.3081ab6960afep-7},
     {0x1.3935685aae98p-52, -0x1.95e1d87c96fc8p-52, -0x1.14ecf6e05ae2fp-53,
      0x1.08007d9465d56p-51, 0x1.6599ff8ae5355p-53, 0x1.eb43520f47ec2p-55},
     {0x1.562956075544bp+31, -0x1.12bd33a5cc69ep+33, 0x1.2ff08adc4b9bap+35,
      0x1.b9344d344a511p+34, -0x1.e818f94abcc86p+36, 0x1.0dfcc77ee77edp+39}},
    {{-0x1.d62f3772cf821p+56, 0x1.fe629670d0d8fp+57, -0x1.d8d844b3b9409p+57},
     {0x1.9af07b2515b17p+244, 0x1.eae884e642d91p+243, -0x1.0bf1340b0def7p+244,
      0x1.253835d702514p+243, -0x1.401574e56b39cp+243, 0x1.5d68c8a26a768p+243},
     {0x1.6e9ac00fc9cdfp+114, -0x1.0f3fb45328cdp+114, 0x1.2a9e170dc3842p+113,
      0x1.91642f770883fp+113, -0x1.b9e42a5601d79p+112, 0x1.e67a4332fc593p+111}},
};

/* Pairs computed before the pair under test (with every method), so that
 * the stack holds different values each time: moderate pairs and a pair
 * whose evaluations overflow. */
static const Pair others[] = {
    {{1, 2, 3}, {1, 0, 0, 1, 0, 1}, {4, 0, 0, 9, 0, 1}},
    {{-0.7, 1.1, 0.01}, {3, 0.5, 0, 2, 0, 7}, {0.1, 0, 0, 5, 0.3, 2}},
    {{1e-3, 0, 0}, {1e-6, 0, 0, 1, 0, 1}, {1, 0, 0, 1e-6, 0, 1}},
    {{1, 1, 1}, {DBL_MAX, 0, 0, 4.9e-324, 0, 1}, {1, 0, 0, 1, 0, 1}},
    {{1e8, 0, 0}, {1e16, 0, 0, 1e16, 0, 1e-16}, {1e16, 0, 0, 1e16, 0, 1e-16}},
};

/* Fills the stack below the caller's frame with byte: what a call made next
 * finds in memory it has not written. */
static G_GNUC_NO_INLINE void scribble_stack(unsigned char byte) {
  volatile unsigned char buf[1 << 16];
  for (size_t i = 0; i < sizeof buf; ++i) buf[i] = byte;
}

/* Pairs on which a method ended without an estimate (NaN mu2 or lambda),
 * with NaN mu2_error, or with lambda outside [0, 1]: q1 = q2 =
 * diag(1e16, 1e16, 1e-16) (ZHENG; mu2 = r^T Q^{-1} r / 4 = 0.25 exactly at
 * lambda = 1/2); Q1 = diag(DBL_MAX, 4.9e-324, 1), Q2 = I (every method but
 * RATIONAL); two pairs whose maximiser is within an ulp of 1 (DEFAULT
 * returned lambda = 1 + 2^-52 with PW85_OK). */
static const Pair extreme[] = {
    {{1e8, 0, 0}, {1e16, 0, 0, 1e16, 0, 1e-16}, {1e16, 0, 0, 1e16, 0, 1e-16}},
    {{1, 1, 1}, {DBL_MAX, 0, 0, 4.9e-324, 0, 1}, {1, 0, 0, 1, 0, 1}},
    {{0x1.0e4157d22a023p+5, -0x1.0079f896a2819p+4, -0x1.185d6796104e7p+5},
     {0x1.8b8485a217c33p-3, -0x1.d00b90ff1a576p-3, -0x1.8abfc52bf215ep-3,
      0x1.65b2612faaf81p-1, 0x1.36dd9281085adp-2, 0x1.a9bbf893c6308p-2},
     {0x1.72ca90bd83cbp-111, 0x1.5e09dc88be3ap-116, -0x1.2c92b4d87eb12p-113,
      0x1.536f2031fe434p-109, -0x1.e70d4b69131e7p-110, 0x1.638ada4a288b2p-110}},
    {{-0x1.208c4ee7eb5fcp-4, 0x1.4188b7d915c8cp-4, 0x1.777954ae21461p-5},
     {0x1.e15e27642af0dp-6, -0x1.ea642823708dcp-5, 0x1.9506c12cd9ab8p-8,
      0x1.4079330acb303p-1, 0x1.9a10c60fc05aap-2, 0x1.22b8edb299417p-1},
     {0x1.0e73a404e28f1p-130, 0x1.f1a0eef4017d2p-132, 0x1.c2552e4b51edbp-130,
      0x1.4735eb1ce9f86p-128, -0x1.843a357b30d19p-130, 0x1.024b212bd2f7dp-128}},
};

/* What a status that writes an estimate promises (include/pw85.h). */
static void check_estimate(int status, const pw85_result *res) {
  g_assert_true(status == PW85_OK || status == PW85_ERR_INACCURATE ||
                status == PW85_ERR_NO_CONVERGENCE);
  g_assert_true(isfinite(res->mu2) && res->mu2 >= 0.0);
  g_assert_true(res->lambda >= 0.0 && res->lambda <= 1.0);
  g_assert_false(isnan(res->mu2_error));
}

/* Every pair of `failing` and `extreme`: the promise above; on the first
 * pair of `extreme`, mu2 within mu2_error of 0.25. */
static void test_estimate(gconstpointer data) {
  int const method = GPOINTER_TO_INT(data);
  for (size_t k = 0; k < G_N_ELEMENTS(failing) + G_N_ELEMENTS(extreme); ++k) {
    Pair const *p = k < G_N_ELEMENTS(failing) ? &failing[k] : &extreme[k - G_N_ELEMENTS(failing)];
    pw85_result res;
    int const s = pw85_contact_function_method(p->r, p->q1, p->q2, method, &res);
    check_estimate(s, &res);
  }
  pw85_result res;
  pw85_contact_function_method(extreme[0].r, extreme[0].q1, extreme[0].q2, method, &res);
  g_assert_cmpfloat(fabs(res.mu2 - 0.25), <=, res.mu2_error);
}

/* The two pairs of `extreme` whose maximiser is within an ulp of 1: lambda
 * in [0, 1], PW85_OK for DEFAULT. */
static void test_lambda_near_1(gconstpointer data) {
  int const method = GPOINTER_TO_INT(data);
  for (size_t k = 2; k < 4; ++k) {
    pw85_result res;
    int const s = pw85_contact_function_method(extreme[k].r, extreme[k].q1, extreme[k].q2,
                                               method, &res);
    g_assert_true(res.lambda >= 0.0 && res.lambda <= 1.0);
    if (method == PW85_METHOD_DEFAULT) g_assert_cmpint(s, ==, PW85_OK);
  }
}

static void assert_same_result(const pw85_result *a, int sa, const pw85_result *b, int sb) {
  g_assert_cmpint(sa, ==, sb);
  g_assert_true(memcmp(&a->mu2, &b->mu2, sizeof a->mu2) == 0);
  g_assert_true(memcmp(&a->lambda, &b->lambda, sizeof a->lambda) == 0);
  g_assert_true(memcmp(&a->mu2_error, &b->mu2_error, sizeof a->mu2_error) == 0);
  g_assert_cmpint(a->iterations, ==, b->iterations);
}

/* The pair alone, then with the stack filled with each of four bytes, then
 * after each other pair by every method: same bits. */
static void test_repeatable(gconstpointer data) {
  int const method = GPOINTER_TO_INT(data);
  for (size_t k = 0; k < G_N_ELEMENTS(failing); ++k) {
    Pair const *p = &failing[k];
    pw85_result fresh;
    int const s0 = pw85_contact_function_method(p->r, p->q1, p->q2, method, &fresh);
    g_assert_true(s0 == PW85_OK || s0 == PW85_ERR_INACCURATE || s0 == PW85_ERR_NO_CONVERGENCE);
    for (unsigned byte = 0; byte < 256; byte += 0x55) {
      pw85_result again;
      scribble_stack((unsigned char)byte);
      int const s = pw85_contact_function_method(p->r, p->q1, p->q2, method, &again);
      assert_same_result(&fresh, s0, &again, s);
    }
    for (size_t j = 0; j < G_N_ELEMENTS(others); ++j)
      for (int m = 0; m <= PW85_METHOD_ZHENG; ++m) {
        pw85_result other, again;
        pw85_contact_function_method(others[j].r, others[j].q1, others[j].q2, m, &other);
        int const s = pw85_contact_function_method(p->r, p->q1, p->q2, method, &again);
        assert_same_result(&fresh, s0, &again, s);
      }
  }
}

/* As test_repeatable, for pw85_contact (DEFAULT, then the contact point). */
static void test_contact_repeatable(void) {
  for (size_t k = 0; k < G_N_ELEMENTS(failing); ++k) {
    Pair const *p = &failing[k];
    pw85_contact_t fresh;
    int const s0 = pw85_contact(p->r, p->q1, p->q2, &fresh);
    for (unsigned byte = 0; byte < 256; byte += 0x55) {
      pw85_contact_t again;
      scribble_stack((unsigned char)byte);
      int const s = pw85_contact(p->r, p->q1, p->q2, &again);
      g_assert_cmpint(s, ==, s0);
      g_assert_true(memcmp(&fresh, &again, sizeof fresh) == 0);
    }
    for (size_t j = 0; j < G_N_ELEMENTS(others); ++j) {
      pw85_contact_t other, again;
      pw85_contact(others[j].r, others[j].q1, others[j].q2, &other);
      int const s = pw85_contact(p->r, p->q1, p->q2, &again);
      g_assert_cmpint(s, ==, s0);
      g_assert_true(memcmp(&fresh, &again, sizeof fresh) == 0);
    }
  }
}

int main(int argc, char **argv) {
  g_test_init(&argc, &argv, NULL);
  static const char *const names[] = {"default", "brent", "newton", "rational", "zheng"};
  for (int m = 0; m <= PW85_METHOD_ZHENG; ++m) {
    char path[128];
    g_snprintf(path, sizeof path, "/pw85_contact_function_method/%s/failing_evaluation/repeatable",
               names[m]);
    g_test_add_data_func(path, GINT_TO_POINTER(m), test_repeatable);
  }
  for (int m = 0; m <= PW85_METHOD_ZHENG; ++m) {
    char path[128];
    g_snprintf(path, sizeof path, "/pw85_contact_function_method/%s/failing_evaluation/estimate",
               names[m]);
    g_test_add_data_func(path, GINT_TO_POINTER(m), test_estimate);
    g_snprintf(path, sizeof path, "/pw85_contact_function_method/%s/maximiser_near_1/lambda",
               names[m]);
    g_test_add_data_func(path, GINT_TO_POINTER(m), test_lambda_near_1);
  }
  g_test_add_func("/pw85_contact/failing_evaluation/repeatable", test_contact_repeatable);
  return g_test_run();
}
