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
 * positive definite after successful evaluations. The last entry of each q2
 * is one ulp above the fuzzer's, whose det q2 < 0 exactly (a matrix
 * positive definite only in rounding, now refused): det q2 > 0 exactly,
 * q2 as nearly singular. */
static const Pair failing[] = {
    {{0x1.8543a6eb49d34p-8, 0x1.242ae6631625dp-7, -0x1.3081ab6960afep-7},
     {0x1.3935685aae98p-52, -0x1.95e1d87c96fc8p-52, -0x1.14ecf6e05ae2fp-53,
      0x1.08007d9465d56p-51, 0x1.6599ff8ae5355p-53, 0x1.eb43520f47ec2p-55},
     {0x1.562956075544bp+31, -0x1.12bd33a5cc69ep+33, 0x1.2ff08adc4b9bap+35,
      0x1.b9344d344a511p+34, -0x1.e818f94abcc86p+36, 0x1.0dfcc77ee77eep+39}},
    {{-0x1.d62f3772cf821p+56, 0x1.fe629670d0d8fp+57, -0x1.d8d844b3b9409p+57},
     {0x1.9af07b2515b17p+244, 0x1.eae884e642d91p+243, -0x1.0bf1340b0def7p+244,
      0x1.253835d702514p+243, -0x1.401574e56b39cp+243, 0x1.5d68c8a26a768p+243},
     {0x1.6e9ac00fc9cdfp+114, -0x1.0f3fb45328cdp+114, 0x1.2a9e170dc3842p+113,
      0x1.91642f770883fp+113, -0x1.b9e42a5601d79p+112, 0x1.e67a4332fc594p+111}},
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

/* Pairs of semi-axes log-uniform in [1e-37, 1e37] on which DEFAULT
 * returned PW85_OK with relative errors 1.1e-9, 2.5e-9, 1.3e-8, 5.4e-13
 * and 7.5e-11 (bench/extreme_scale_fuzz.py): the maximiser is within
 * 1e-11 ... 1e-45 of 0 or 1, where f varies on the scale of lambda or of
 * 1 - lambda. The last three: a matrix numerically singular in double
 * (extreme_scale_fuzz.py --small-angles, and a sweep of the derivatives),
 * where the double f'' of step 3 of DEFAULT was rounding noise far above
 * the bound of (M3): PW85_OK with errors 0.5, 0.58 and 0.48. mu2: the
 * exact maximum of f, rounded to double, from
 * `bench/extreme_scale_fuzz.py --reference` (rational arithmetic on the
 * double inputs, bracket of relative width below 1e-130; mpmath at 2000
 * bits agrees to the last bit). */
static const struct {
  Pair p;
  double mu2;
} near_end[] = {
    {{{0x1.18e49a7fb1ea4p-85, 0x1.7508cf8ba221ep-90, -0x1.144393a8bb107p-86},
      {0x1.0f16d4d011de2p+158, 0x1.1ffa3c8ed5d27p+160, -0x1.6bbdf140d8979p+159,
       0x1.31eafb80b1f09p+162, -0x1.826700ed3b969p+161, 0x1.e80fc6763310ep+160},
      {0x1.c35d9fd620b7dp-184, -0x1.836a634b3e9b4p-183, -0x1.d9becc61edbc3p-182,
       0x1.4c86a6d6128e6p-182, 0x1.969fd826944b8p-181, 0x1.f13c0935e8e43p-180}},
     0x1.624f36497b7f0p-286},
    {{{0x1.a325ecbd71374p+75, -0x1.2264daac4dc9bp+79, -0x1.725f1ae7f3364p+79},
      {0x1.0c6c78a6cb8c5p+0, 0x1.d3b149d74cf46p+2, 0x1.60100c8f5492dp+1,
       0x1.9773ab49cc06cp+5, 0x1.32b74bf654570p+4, 0x1.cdc55fbf64240p+2},
      {0x1.ffd6e0d529182p+161, 0x1.5394f2fa8fc4fp+170, -0x1.21c6960491e9fp+170,
       0x1.c29802c791d8dp+178, -0x1.80817445f27ffp+178, 0x1.481c5300890a3p+178}},
     0x1.57c6fea039d77p+40},
    {{{0x1.24918d8debf95p-73, -0x1.c8e687dd6c4e2p-74, -0x1.1bcd519b9aacfp-73},
      {0x1.b18b5d26d70bcp+226, -0x1.6287fae156341p+227, 0x1.38ffcc83338d9p+222,
       0x1.23b305b545edep+228, -0x1.27f5692549a26p+223, 0x1.1917e192b9fc6p+220},
      {0x1.1bf6eb53be10ep+104, -0x1.98a05423c6dd0p+102, -0x1.194b2650397a6p+101,
       0x1.2601efe08536dp+101, 0x1.94c8618beca53p+99, 0x1.16a5cfc69eed7p+98}},
     0x1.42533513052a4p-323},
    {{{0x1.e732a6dac5296p+96, 0x1.96a86df0bf3ccp+95, -0x1.61360941fce97p+95},
      {0x1.ef82117fcec61p+5, -0x1.77bc777d64913p+7, -0x1.84bbcdb012f2dp+5,
       0x1.1cea3e430f133p+9, 0x1.26c54fcecf553p+7, 0x1.30f7a86b62db7p+5},
      {0x1.3db697e333187p+212, 0x1.e6da92aa45353p+206, 0x1.f9f44013bf53ep+209,
       0x1.75050cca09ebep+201, 0x1.83a771a298e18p+204, 0x1.92dcd1171d4ebp+207}},
     0x1.776f5d3870b8bp+47},
    {{{-0x1.c203b9a72c854p+88, 0x1.86a5c4f43087dp+88, -0x1.a497887342c98p+88},
      {0x1.74ba2f94cd1ffp+173, -0x1.89ee729aaea0cp+173, 0x1.419aa7137d686p+173,
       0x1.a147286fda0dcp+173, -0x1.54187b6292cb6p+173, 0x1.1588adc9e4f1cp+173},
      {0x1.bd864b36abab7p-13, 0x1.b0d4597ee28f6p-12, 0x1.38d1ad8440c93p-14,
       0x1.a47f02f888d4fp-11, 0x1.2fe7c60319058p-13, 0x1.b74887f689281p-16}},
     0x1.e2cbcf8b8d2acp+32},
    {{{0x1.437ba4b52d82p-1, -0x1.f9cfaa68d13bp-3, -0x1.3274fe1b84e3p-4},
      {0x1.421a85dffc0c6p-141, -0x1.8da30e537e4dcp-164, 0x1.bc5b6dbcae021p-176,
       0x1.71a88d5a52621p-142, -0x1.15dc98b5e79ap-198, 0x1.1bdcc3e2d4acap-152},
      {0x1.f32f77e0088f5p+110, 0x1.6d3ae55324cd2p+131, 0x1.bdf610f636de7p+52,
       0x1.0b38a9c954faap+152, 0x1.4649d78307dbdp+73, 0x1.8e696f1af08f5p-6}},
     0x1.53bd40b8d14efp+51},
    {{{-0x1.c0e4eb1ee9451p-52, -0x1.14c19ee45328bp-53, 0x1.9cbec7757e721p-50},
      {0x1.f1d0203f80df7p-137, -0x1.d04ccd652798bp-139, -0x1.42bf5c5a36d1bp-122,
       0x1.b10b0e657fe54p-141, 0x1.2d051ef0aeb11p-124, 0x1.a27e8aa9b5204p-108},
      {0x1.583e2f33fcb02p+146, -0x1.0bc41e55e4f1fp+116, -0x1.118b6aa907364p+87,
       0x1.259aa30bb7b34p+176, -0x1.496ee0637c4aep+115, 0x1.71a26c3e31c53p+54}},
     0x1.457839adec292p-96},
    {{{-0x1.3d8f72a459a3cp+120, -0x1.bd8d4b67c7522p+121, 0x1.6a72ff5bde0d0p+118},
      {0x1.147ba17d19eb8p-100, -0x1.8d67c8f10ade8p-62, -0x1.716ad331a5240p-95,
       0x1.1d9b74ae6f032p-23, 0x1.097e24c5ec95dp-56, 0x1.ed9c7528e1335p-90},
      {0x1.fee9392ac6841p+130, -0x1.f2e3d109e8a12p+103, 0x1.0298e640e5d12p+151,
       0x1.2cce3e4937e6cp+102, -0x1.37d7a826a8944p+149, 0x1.4348bc9eabc25p+196}},
     0x1.94ace96acd03ap+194},
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

/* DEFAULT on `near_end`: PW85_OK with mu2 within the documented 1e-14 of
 * the exact value, or PW85_ERR_INACCURATE with mu2_error at least the
 * actual error (docs/methods.md). */
static void test_near_end_honest(void) {
  for (size_t k = 0; k < G_N_ELEMENTS(near_end); ++k) {
    Pair const *p = &near_end[k].p;
    double const ref = near_end[k].mu2;
    pw85_result res;
    int const s = pw85_contact_function_method(p->r, p->q1, p->q2, PW85_METHOD_DEFAULT, &res);
    double const err = fabs(res.mu2 - ref);
    if (g_test_verbose())
      g_test_message("pair %zu: status %d, relative error %.3e, mu2_error / mu2 %.3e", k, s,
                     err / ref, res.mu2_error / res.mu2);
    g_assert_true(s == PW85_OK || s == PW85_ERR_INACCURATE);
    if (s == PW85_OK)
      g_assert_cmpfloat(err, <=, 1e-14 * ref);
    else
      g_assert_cmpfloat(err, <=, res.mu2_error);
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
  g_test_add_func("/pw85_contact_function_method/default/maximiser_near_end/honest",
                  test_near_end_honest);
  return g_test_run();
}
