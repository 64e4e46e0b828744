/* Tests of the batch calls (docs/batch.md): results identical
 * (bitwise) to the one-pair functions, independent of the number of threads
 * (1 and 2, explicit nthreads argument), per-pair status, bad input. */
#include <math.h>
#include <pw85.h>
#include <string.h>

#include "testutil.h"

#define N 120
#define M 3000

typedef struct {
  double c[3 * N], q[6 * N];
  long long pairs[2 * M];
} scene;

static void make_scene(scene *s, guint32 seed) {
  GRand *rng = g_rand_new_with_seed(seed);
  for (int i = 0; i < N; i++) {
    double rad[3], ax[9];
    random_radii(rng, 0.1, 1.0, rad);
    random_axes(rng, ax);
    make_q(rad, ax, s->q + 6 * i);
    for (int d = 0; d < 3; d++) s->c[3 * i + d] = g_rand_double_range(rng, 0.0, 2.0);
  }
  for (int k = 0; k < M; k++) {
    s->pairs[2 * k] = (long long)g_rand_int_range(rng, 0, N);
    s->pairs[2 * k + 1] = (long long)g_rand_int_range(rng, 0, N);
  }
  g_rand_free(rng);
}

static void r12_of(const scene *s, int k, double r[3]) {
  long long i = s->pairs[2 * k], j = s->pairs[2 * k + 1];
  for (int d = 0; d < 3; d++) r[d] = s->c[3 * j + d] - s->c[3 * i + d];
}

static void test_overlap_batch(void) {
  static scene s;
  make_scene(&s, 11);
  static int v1[M], v2[M], st1[M], st2[M];
  g_assert_cmpint(pw85_overlap_batch(N, s.c, s.q, M, s.pairs, v1, st1, 1), ==, PW85_OK);
  g_assert_cmpint(pw85_overlap_batch(N, s.c, s.q, M, s.pairs, v2, st2, 2), ==, PW85_OK);
  int n_overlap = 0;
  for (int k = 0; k < M; k++) {
    double r[3];
    r12_of(&s, k, r);
    long long i = s.pairs[2 * k], j = s.pairs[2 * k + 1];
    int const one = pw85_overlap(r, s.q + 6 * i, s.q + 6 * j);
    g_assert_cmpint(v1[k], ==, one);
    g_assert_cmpint(v2[k], ==, one);
    g_assert_cmpint(st1[k], ==, PW85_OK);
    g_assert_cmpint(st2[k], ==, PW85_OK);
    n_overlap += one;
  }
  /* The scene has both verdicts. */
  g_assert_cmpint(n_overlap, >, M / 20);
  g_assert_cmpint(n_overlap, <, M - M / 20);
}

static void test_contact_function_batch(void) {
  static scene s;
  make_scene(&s, 12);
  /* no self-pairs: r12 = 0 is fine for the contact function, but keep the
   * scene generic */
  static double o1[2 * M], o2[2 * M];
  static int st1[M], st2[M];
  int ret1 = pw85_contact_function_batch(N, s.c, s.q, M, s.pairs, o1, st1, 1);
  int ret2 = pw85_contact_function_batch(N, s.c, s.q, M, s.pairs, o2, st2, 2);
  g_assert_cmpint(ret1, ==, ret2);
  g_assert_true(memcmp(o1, o2, sizeof o1) == 0);
  g_assert_true(memcmp(st1, st2, sizeof st1) == 0);
  for (int k = 0; k < M; k++) {
    double r[3], out[2];
    r12_of(&s, k, r);
    long long i = s.pairs[2 * k], j = s.pairs[2 * k + 1];
    int const one = pw85_contact_function(r, s.q + 6 * i, s.q + 6 * j, out);
    g_assert_cmpint(st1[k], ==, one);
    g_assert_true(memcmp(out, o1 + 2 * k, sizeof out) == 0);
  }
}

static void test_contact_batch(void) {
  static scene s;
  make_scene(&s, 13);
  for (int k = 0; k < M; k++)
    if (s.pairs[2 * k] == s.pairs[2 * k + 1]) s.pairs[2 * k + 1] = (s.pairs[2 * k] + 1) % N;
  static pw85_contact_t c1[M], c2[M];
  static int st1[M], st2[M];
  int ret1 = pw85_contact_batch(N, s.c, s.q, M, s.pairs, c1, st1, 1);
  int ret2 = pw85_contact_batch(N, s.c, s.q, M, s.pairs, c2, st2, 2);
  g_assert_cmpint(ret1, ==, ret2);
  g_assert_true(memcmp(c1, c2, sizeof c1) == 0);
  g_assert_true(memcmp(st1, st2, sizeof st1) == 0);
  for (int k = 0; k < M; k++) {
    double r[3];
    r12_of(&s, k, r);
    long long i = s.pairs[2 * k], j = s.pairs[2 * k + 1];
    pw85_contact_t one;
    g_assert_cmpint(pw85_contact(r, s.q + 6 * i, s.q + 6 * j, &one), ==, st1[k]);
    g_assert_true(memcmp(&one, c1 + k, sizeof one) == 0);
  }
}

/* Out-of-range pair indices: the per-pair status says which pairs failed
 * and the call returns the first failure. */
static const long long bad_pairs[8] = {0, 1, 2, N, 3, 4, -1, 0};

static void test_overlap_batch_bad_input(void) {
  static scene s;
  make_scene(&s, 14);
  int v[4], st[4];
  long long pairs[8];
  memcpy(pairs, bad_pairs, sizeof pairs);
  g_assert_cmpint(pw85_overlap_batch(N, s.c, s.q, 4, pairs, v, st, 0), ==,
                  PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(st[0], ==, PW85_OK);
  g_assert_cmpint(st[1], ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(v[1], ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(st[2], ==, PW85_OK);
  g_assert_cmpint(st[3], ==, PW85_ERR_INVALID_ARGUMENT);
  /* a non-positive-definite matrix in the scene */
  s.q[6 * 4 + 0] = -1.0;
  g_assert_cmpint(pw85_overlap_batch(N, s.c, s.q, 1, pairs + 4, v, st, 1), ==,
                  PW85_ERR_NOT_SPD);
  g_assert_cmpint(st[0], ==, PW85_ERR_NOT_SPD);
  /* NULL arrays, negative nthreads; m = 0 is a no-op */
  g_assert_cmpint(pw85_overlap_batch(N, NULL, s.q, 1, pairs, v, st, 1), ==,
                  PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_overlap_batch(N, s.c, s.q, 1, pairs, NULL, st, 1), ==,
                  PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_overlap_batch(N, s.c, s.q, 1, pairs, v, st, -1), ==,
                  PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_overlap_batch(N, NULL, NULL, 0, NULL, NULL, NULL, 1), ==, PW85_OK);
}

static void test_contact_function_batch_bad_input(void) {
  static scene s;
  make_scene(&s, 14);
  int st[4];
  long long pairs[8];
  memcpy(pairs, bad_pairs, sizeof pairs);
  double out[8];
  g_assert_cmpint(pw85_contact_function_batch(N, s.c, s.q, 4, pairs, out, st, 0), ==,
                  PW85_ERR_INVALID_ARGUMENT);
  g_assert_true(isnan(out[2]) && isnan(out[3]) && !isnan(out[0]));
  g_assert_cmpint(pw85_contact_function_batch(N, s.c, NULL, 1, pairs, out, st, 1), ==,
                  PW85_ERR_INVALID_ARGUMENT);
}

static void test_contact_batch_bad_input(void) {
  static scene s;
  make_scene(&s, 14);
  int st[4];
  long long pairs[8];
  memcpy(pairs, bad_pairs, sizeof pairs);
  pw85_contact_t c[4];
  g_assert_cmpint(pw85_contact_batch(N, s.c, s.q, 4, pairs, c, st, 0), ==,
                  PW85_ERR_INVALID_ARGUMENT);
  g_assert_true(isnan(c[3].depth) && !isnan(c[2].depth));
  g_assert_cmpint(pw85_contact_batch(N, s.c, s.q, 1, NULL, c, st, 1), ==,
                  PW85_ERR_INVALID_ARGUMENT);
}

int main(int argc, char **argv) {
  g_test_init(&argc, &argv, NULL);
  g_test_add_func("/pw85_overlap_batch/threads-1-2", test_overlap_batch);
  g_test_add_func("/pw85_contact_function_batch/threads-1-2", test_contact_function_batch);
  g_test_add_func("/pw85_contact_batch/threads-1-2", test_contact_batch);
  g_test_add_func("/pw85_overlap_batch/bad-input", test_overlap_batch_bad_input);
  g_test_add_func("/pw85_contact_function_batch/bad-input",
                  test_contact_function_batch_bad_input);
  g_test_add_func("/pw85_contact_batch/bad-input", test_contact_batch_bad_input);
  return g_test_run();
}
