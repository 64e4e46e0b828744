/* Tests of the batch calls (docs/batch.md): results identical
 * (bitwise) to the one-pair functions, independent of the number of threads
 * (1 and 2, explicit nthreads argument), of the order of the pairs and of
 * their neighbours; per-pair status, bad input; nthreads far beyond the
 * CPUs (100000, INT_MAX) gives the results of nthreads = 1; the minimum
 * image of the periodic scenes against a brute-force search over images. */
#include <limits.h>
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

/* ---- Per-pair arrays and periodic scenes -------------------------------- */

/* A periodic test box: lengths in [1.5, 3], tilts uniform in [-tilt, tilt]. */
static void random_box(GRand *rng, double tilt, double box[6]) {
  for (int d = 0; d < 3; d++) box[d] = g_rand_double_range(rng, 1.5, 3.0);
  for (int d = 3; d < 6; d++) box[d] = g_rand_double_range(rng, -tilt, tilt);
}

/* The wrap the header documents (HOOMD's Box::minImage: z, y, x, each by
 * the nearest integer to the coordinate times 1 / L, ties away from zero),
 * written out here independently of the library's code, in floating point:
 * the exact image where its operations are exact (centres and box on a
 * grid: test_new_against_one_pair), within a few ulps of it elsewhere. */
static void wrap(const double box[6], double r[3]) {
  double iz = round(r[2] * (1.0 / box[2]));
  r[2] -= box[2] * iz;
  r[1] -= box[5] * box[2] * iz;
  r[0] -= box[4] * box[2] * iz;
  double iy = round(r[1] * (1.0 / box[1]));
  r[1] -= box[1] * iy;
  r[0] -= box[3] * box[1] * iy;
  r[0] -= box[0] * round(r[0] * (1.0 / box[0]));
}

/* Scene of N ellipsoids, semi-axes in [0.05, 0.35] (bounding spheres small
 * enough for every box of random_box), centres in [-3, 6]^3 (outside the
 * box too), every odd ellipsoid near the even one before it; M pairs (odd k:
 * such neighbours), and the same pairs as per-pair arrays (r12 = c_j - c_i,
 * not wrapped). */
typedef struct {
  double c[3 * N], q[6 * N];
  long long pairs[2 * M];
  double r12[3 * M], q1[6 * M], q2[6 * M];
} pair_arrays;

static void make_pair_arrays(pair_arrays *s, guint32 seed) {
  GRand *rng = g_rand_new_with_seed(seed);
  for (int i = 0; i < N; i++) {
    double rad[3], ax[9];
    random_radii(rng, 0.05, 0.35, rad);
    random_axes(rng, ax);
    make_q(rad, ax, s->q + 6 * i);
    for (int d = 0; d < 3; d++)
      s->c[3 * i + d] = i % 2 ? s->c[3 * (i - 1) + d] + g_rand_double_range(rng, -0.4, 0.4)
                              : g_rand_double_range(rng, -3.0, 6.0);
  }
  for (int k = 0; k < M; k++) {
    long long i = g_rand_int_range(rng, 0, N), j;
    if (k % 2) j = i ^ 1;
    else do j = g_rand_int_range(rng, 0, N); while (j == i);
    s->pairs[2 * k] = i;
    s->pairs[2 * k + 1] = j;
    for (int d = 0; d < 3; d++) s->r12[3 * k + d] = s->c[3 * j + d] - s->c[3 * i + d];
    memcpy(s->q1 + 6 * k, s->q + 6 * i, 6 * sizeof(double));
    memcpy(s->q2 + 6 * k, s->q + 6 * j, 6 * sizeof(double));
  }
  g_rand_free(rng);
}

/* Bad pairs among good ones. Per-pair arrays: a NaN in r12 at k = 7, a
 * q2 not positive definite at k = 3, an infinite q1 at k = 11. Scene: an
 * index out of range at k = 5, a NaN centre (every pair of ellipsoid
 * pairs[18] fails), a matrix not positive definite (ellipsoid pairs[26]). */
static void spoil(pair_arrays *s) {
  s->r12[3 * 7 + 1] = NAN;
  s->q2[6 * 3 + 0] = -1.0;
  s->q1[6 * 11 + 5] = INFINITY;
  s->pairs[2 * 5 + 1] = N;
  s->c[3 * s->pairs[18] + 2] = NAN;
  s->q[6 * s->pairs[26] + 3] = -0.01;
}

/* The arrays with pair k moved to perm[k]. */
static void permute(const pair_arrays *s, const int *perm, pair_arrays *t) {
  memcpy(t->c, s->c, sizeof s->c);
  memcpy(t->q, s->q, sizeof s->q);
  for (int k = 0; k < M; k++) {
    int p = perm[k];
    memcpy(t->pairs + 2 * p, s->pairs + 2 * k, 2 * sizeof(long long));
    memcpy(t->r12 + 3 * p, s->r12 + 3 * k, 3 * sizeof(double));
    memcpy(t->q1 + 6 * p, s->q1 + 6 * k, 6 * sizeof(double));
    memcpy(t->q2 + 6 * p, s->q2 + 6 * k, 6 * sizeof(double));
  }
}

/* The new calls: which = 0 overlap, 1 contact function (method), 2 contact;
 * scene = 0: pw85_*_pairs, 1: pw85_scene_* (box may be NULL). */
static int call_new(int which, int scene, const pair_arrays *s, const double *box, int method,
                    void *out, int *st, int nthreads) {
  if (!scene) {
    if (which == 0) return pw85_overlap_pairs(M, s->r12, s->q1, s->q2, out, st, nthreads);
    if (which == 1)
      return pw85_contact_function_pairs(M, s->r12, s->q1, s->q2, method, out, st, nthreads);
    return pw85_contact_pairs(M, s->r12, s->q1, s->q2, out, st, nthreads);
  }
  if (which == 0) return pw85_scene_overlap(N, s->c, s->q, box, M, s->pairs, out, st, nthreads);
  if (which == 1)
    return pw85_scene_contact_function(N, s->c, s->q, box, M, s->pairs, method, out, st,
                                       nthreads);
  return pw85_scene_contact(N, s->c, s->q, box, M, s->pairs, out, st, nthreads);
}

static size_t out_size(int which) {
  return which == 0 ? sizeof(int) : which == 1 ? sizeof(pw85_result) : sizeof(pw85_contact_t);
}

/* Expected output and status of pair k by the one-pair function (an index
 * out of range: the one-pair function on a NaN r12, which fails with
 * PW85_ERR_INVALID_ARGUMENT and the same NaN outputs). */
static int expect_one(int which, int scene, const pair_arrays *s, const double *box, int method,
                      int k, void *out) {
  double r[3] = {NAN, 0.0, 0.0};
  const double *q1 = s->q1 + 6 * k, *q2 = s->q2 + 6 * k;
  if (!scene) {
    memcpy(r, s->r12 + 3 * k, sizeof r);
  } else {
    long long i = s->pairs[2 * k], j = s->pairs[2 * k + 1];
    q1 = s->q;
    q2 = s->q;
    if (i >= 0 && i < N && j >= 0 && j < N) {
      for (int d = 0; d < 3; d++) r[d] = s->c[3 * j + d] - s->c[3 * i + d];
      if (box && isfinite(r[0]) && isfinite(r[1]) && isfinite(r[2])) wrap(box, r);
      q1 = s->q + 6 * i;
      q2 = s->q + 6 * j;
    }
  }
  if (which == 0) {
    int v = pw85_overlap(r, q1, q2);
    *(int *)out = v;
    return v < 0 ? v : PW85_OK;
  }
  if (which == 1) return pw85_contact_function_method(r, q1, q2, method, out);
  return pw85_contact(r, q1, q2, out);
}

typedef struct {
  int which, scene, periodic;
} new_case;

static const new_case new_cases[9] = {
  {0, 0, 0}, {1, 0, 0}, {2, 0, 0},  /* pw85_*_pairs */
  {0, 1, 0}, {1, 1, 0}, {2, 1, 0},  /* pw85_scene_*, box NULL */
  {0, 1, 1}, {1, 1, 1}, {2, 1, 1},  /* pw85_scene_*, triclinic box */
};

static unsigned char big_out[4][M * sizeof(pw85_contact_t)];
static int big_st[4][M];

/* Every pair of a new call bitwise equal to its one-pair call, with 1 and 2
 * threads, in the original and in a shuffled order (every method for the
 * contact function); the bad pairs of spoil() fail alone; the call returns
 * the status of the lowest failing k. */
static void test_new_against_one_pair(gconstpointer data) {
  const new_case *tc = data;
  static pair_arrays s, t;
  static int perm[M];
  GRand *rng = g_rand_new_with_seed(41 + tc->which);
  make_pair_arrays(&s, 21 + tc->which);
  double box[6];
  random_box(rng, 0.5, box);
  if (tc->periodic) { /* on a grid of 2^-20: every operation of wrap() exact */
    for (int i = 0; i < 3 * N; i++) s.c[i] = ldexp(round(ldexp(s.c[i], 20)), -20);
    for (int d = 0; d < 6; d++) box[d] = ldexp(round(ldexp(box[d], 20)), -20);
  }
  spoil(&s);
  for (int k = 0; k < M; k++) perm[k] = k;
  for (int k = M - 1; k > 0; k--) {
    int j = g_rand_int_range(rng, 0, k + 1), x = perm[k];
    perm[k] = perm[j];
    perm[j] = x;
  }
  permute(&s, perm, &t);
  const double *b = tc->periodic ? box : NULL;
  size_t const sz = out_size(tc->which);
  unsigned char *exp = big_out[0], *out = big_out[1];
  int *exp_st = big_st[0], *st = big_st[1];
  for (int method = 0; method < (tc->which == 1 ? 5 : 1); method++) {
    /* first: lowest failing k in the original order; first_perm: the pair
     * that lands lowest among the failing ones in the shuffled order */
    int first = M, first_perm = M, n_ok = 0, n_overlap = 0;
    for (int k = 0; k < M; k++) {
      exp_st[k] = expect_one(tc->which, tc->scene, &s, b, method, k, exp + k * sz);
      if (exp_st[k] == PW85_OK) n_ok++;
      else if (first == M) first = k;
      if (exp_st[k] != PW85_OK && (first_perm == M || perm[k] < perm[first_perm])) first_perm = k;
      if (tc->which == 0) n_overlap += *(int *)(exp + k * sz) == 1;
    }
    /* the scene has failing and good pairs (and both verdicts) */
    g_assert_cmpint(first, <, 20);
    g_assert_cmpint(n_ok, >, M - M / 10);
    if (tc->which == 0) g_assert_cmpint(n_overlap, >, M / 10);
    for (int order = 0; order < 2; order++)
      for (int threads = 1; threads <= 2; threads++) {
        memset(out, 0xA5, M * sz);
        memset(st, 0xA5, M * sizeof(int));
        int ret = call_new(tc->which, tc->scene, order ? &t : &s, b, method, out, st, threads);
        g_assert_cmpint(ret, ==, exp_st[order ? first_perm : first]);
        for (int k = 0; k < M; k++) {
          int p = order ? perm[k] : k;
          g_assert_cmpint(st[p], ==, exp_st[k]);
          g_assert_true(memcmp(out + p * sz, exp + k * sz, sz) == 0);
        }
      }
  }
  g_rand_free(rng);
}

/* The minimum image against a brute-force search: spheres of radius 0.05
 * (mu2 = |r12|^2 / 0.1^2 gives the length of the image used), centres in
 * [-2 L, 2 L], 20 random triclinic boxes with tilts uniform in [-tilt, tilt].
 * Brute force: every image w - (n1 a1 + n2 a2 + n3 a3) no longer than w (the
 * wrapped vector), n3, then n2, then n1 enumerated over the ranges that this
 * bound allows. Asserted: the image used is the nearest whenever the nearest
 * is shorter than min(Lx, Ly, Lz)/2, never shorter than the nearest; the
 * other pairs where it is not the nearest are counted (g_test_message). */
static void test_min_image(gconstpointer data) {
  double const tilt = *(const double *)data;
  enum { P = 2000 };
  static double c[6 * P], q[12 * P];
  static long long pairs[2 * P];
  static pw85_result res[P];
  GRand *rng = g_rand_new_with_seed(51 + (guint32)(10 * tilt));
  for (int i = 0; i < 2 * P; i++) sphere_q(0.05, q + 6 * i);
  for (int k = 0; k < P; k++) pairs[2 * k] = 2 * k, pairs[2 * k + 1] = 2 * k + 1;
  long long near = 0, far = 0, far_not_nearest = 0;
  double worst_far = 1.0;
  for (int nb = 0; nb < 20; nb++) {
    double box[6];
    random_box(rng, tilt, box);
    double const lmin = fmin(box[0], fmin(box[1], box[2]));
    for (int i = 0; i < 2 * P; i++)
      for (int d = 0; d < 3; d++) c[3 * i + d] = g_rand_double_range(rng, -2.0, 2.0) * box[d];
    g_assert_cmpint(pw85_scene_contact_function(2 * P, c, q, box, P, pairs, PW85_METHOD_DEFAULT,
                                                res, NULL, 2), ==, PW85_OK);
    double const a[3][3] = {{box[0], 0, 0},
                            {box[3] * box[1], box[1], 0},
                            {box[4] * box[2], box[5] * box[2], box[2]}};
    for (int k = 0; k < P; k++) {
      double w[3];
      for (int d = 0; d < 3; d++) w[d] = c[3 * (2 * k + 1) + d] - c[3 * (2 * k) + d];
      wrap(box, w);
      double const lw = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
      double best2 = lw * lw;
      for (long n3 = (long)floor((w[2] - lw) / a[2][2]); n3 <= (long)ceil((w[2] + lw) / a[2][2]);
           n3++) {
        double const y3 = w[1] - n3 * a[2][1];
        for (long n2 = (long)floor((y3 - lw) / a[1][1]); n2 <= (long)ceil((y3 + lw) / a[1][1]);
             n2++) {
          double const x2 = w[0] - n3 * a[2][0] - n2 * a[1][0];
          for (long n1 = (long)floor((x2 - lw) / a[0][0]);
               n1 <= (long)ceil((x2 + lw) / a[0][0]); n1++) {
            double const v[3] = {x2 - n1 * a[0][0], y3 - n2 * a[1][1], w[2] - n3 * a[2][2]};
            double const v2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
            if (v2 < best2) best2 = v2;
          }
        }
      }
      double const used2 = res[k].mu2 * 0.01;
      g_assert_cmpfloat(used2, >=, best2 * (1 - 1e-12));
      if (sqrt(best2) < 0.5 * lmin) {
        near++;
        g_assert_cmpfloat(rel_error(used2, best2), <=, 1e-12);
      } else {
        far++;
        if (rel_error(used2, best2) > 1e-12) {
          far_not_nearest++;
          if (sqrt(used2 / best2) > worst_far) worst_far = sqrt(used2 / best2);
        }
      }
    }
  }
  g_assert_cmpint(near, >, 20 * P / 20);
  g_test_message("tilts in [-%g, %g]: %lld pairs nearer than min(L)/2, all the nearest image; "
                 "%lld farther, of which %lld not the nearest (image used up to %.3f times "
                 "longer)", tilt, tilt, near, far, far_not_nearest, worst_far);
  g_rand_free(rng);
}

/* Bounding spheres against the box: box {2, 2, 2, 0.3, -0.2, 0.4}
 * (min(L)/2 = 1), axis-aligned ellipsoids whose largest semi-axes sum to
 * 1.01 (pair fails with PW85_ERR_INVALID_ARGUMENT, NaN outputs) or 0.99
 * (computed); without a box both are computed. */
static void test_scene_reach(void) {
  double const box[6] = {2.0, 2.0, 2.0, 0.3, -0.2, 0.4};
  double c[12] = {0, 0, 0, 0.3, 0.02, 0.03, 1.0, 1.0, 1.0, 1.3, 1.02, 1.03};
  double q[24] = {0.96 * 0.96, 0, 0, 0.01, 0, 0.01,  0.05 * 0.05, 0, 0, 0.0025, 0, 0.0025,
                  0.94 * 0.94, 0, 0, 0.01, 0, 0.01,  0.05 * 0.05, 0, 0, 0.0025, 0, 0.0025};
  long long pairs[4] = {0, 1, 2, 3};
  int v[2], st[2];
  pw85_result r[2];
  pw85_contact_t ct[2];
  g_assert_cmpint(pw85_scene_overlap(4, c, q, box, 2, pairs, v, st, 1), ==,
                  PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(st[0], ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(v[0], ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(st[1], ==, PW85_OK);
  g_assert_cmpint(v[1], ==, 1);
  g_assert_cmpint(pw85_scene_contact_function(4, c, q, box, 2, pairs, 0, r, st, 1), ==,
                  PW85_ERR_INVALID_ARGUMENT);
  g_assert_true(isnan(r[0].mu2) && r[1].mu2 < 1.0);
  g_assert_cmpint(pw85_scene_contact(4, c, q, box, 2, pairs, ct, st, 1), ==,
                  PW85_ERR_INVALID_ARGUMENT);
  g_assert_true(isnan(ct[0].depth) && ct[1].depth > 0.0);
  g_assert_cmpint(pw85_scene_overlap(4, c, q, NULL, 2, pairs, v, st, 1), ==, PW85_OK);
  g_assert_cmpint(v[0], ==, 1);
}

/* Boxes where a floating-point wrap goes wrong: box {1, 1, 1, t, 0, 0},
 * t = 2^60, 2^52, 2^20, spheres q = 0x1.d7dbf487fcb92p-9 I (radius 0.06),
 * centres 0 and (0x1.3333333333333p-2, 0x1.ccccccccccccdp-1, 0): the image
 * is (0x1.3333333333333p-2, 0x1.ccccccccccccdp-1 - 1, 0) exactly
 * (|r12|^2 = 0.1, mu^2 = 0.1 / 0.12^2 = 6.94); box {3, 3, 3, 0, 0, 0},
 * spheres of radius 0.4, centres 0 and (2^53, 0, 0): 2^53 = 3 (2^53 + 1) / 3
 * - 1, the image is (-1, 0, 0) exactly, mu^2 = 1 / 0.8^2 = 1.5625. Each
 * scene call must give the one-pair call's bits on that image, and mu^2 the
 * value of the formula. */
static void test_scene_extreme_boxes(void) {
  struct {
    double box[6], cj[3], r12[3], q, mu2;
  } const cases[] = {
      {{1, 1, 1, 0x1p60, 0, 0}, {0x1.3333333333333p-2, 0x1.ccccccccccccdp-1, 0},
       {0x1.3333333333333p-2, 0x1.ccccccccccccdp-1 - 1.0, 0}, 0x1.d7dbf487fcb92p-9, 0},
      {{1, 1, 1, 0x1p52, 0, 0}, {0x1.3333333333333p-2, 0x1.ccccccccccccdp-1, 0},
       {0x1.3333333333333p-2, 0x1.ccccccccccccdp-1 - 1.0, 0}, 0x1.d7dbf487fcb92p-9, 0},
      {{1, 1, 1, 0x1p20, 0, 0}, {0x1.3333333333333p-2, 0x1.ccccccccccccdp-1, 0},
       {0x1.3333333333333p-2, 0x1.ccccccccccccdp-1 - 1.0, 0}, 0x1.d7dbf487fcb92p-9, 0},
      {{3, 3, 3, 0, 0, 0}, {0x1p53, 0, 0}, {-1, 0, 0}, 0.16, 1.5625},
  };
  for (size_t t = 0; t < sizeof cases / sizeof cases[0]; t++) {
    double c[6] = {0, 0, 0, cases[t].cj[0], cases[t].cj[1], cases[t].cj[2]};
    double q[12];
    sphere_q(1.0, q);
    for (int i = 0; i < 6; i++) q[i] *= cases[t].q;
    for (int i = 0; i < 6; i++) q[6 + i] = q[i];
    long long const pair[2] = {0, 1};
    double const *r = cases[t].r12;
    int v = -9, st = -9;
    g_assert_cmpint(pw85_scene_overlap(2, c, q, cases[t].box, 1, pair, &v, &st, 1), ==, PW85_OK);
    g_assert_cmpint(v, ==, pw85_overlap(r, q, q + 6));
    g_assert_cmpint(v, ==, 0);
    pw85_result res, one;
    g_assert_cmpint(pw85_scene_contact_function(2, c, q, cases[t].box, 1, pair,
                                                PW85_METHOD_DEFAULT, &res, &st, 1), ==,
                    pw85_contact_function_method(r, q, q + 6, PW85_METHOD_DEFAULT, &one));
    g_assert_true(memcmp(&res, &one, sizeof res) == 0);
    double const mu2 = cases[t].mu2 > 0 ? cases[t].mu2
                                        : (r[0] * r[0] + r[1] * r[1]) / (4.0 * cases[t].q);
    g_assert_cmpfloat(rel_error(res.mu2, mu2), <=, 1e-14);
    pw85_contact_t ct, ct1;
    g_assert_cmpint(pw85_scene_contact(2, c, q, cases[t].box, 1, pair, &ct, &st, 1), ==,
                    pw85_contact(r, q, q + 6, &ct1));
    g_assert_true(memcmp(&ct, &ct1, sizeof ct) == 0);
    pw85_derivatives_t d, d1;
    g_assert_cmpint(pw85_scene_contact_derivatives(2, c, q, cases[t].box, 1, pair, &d, &st, 1),
                    ==, pw85_contact_derivatives(r, q, q + 6, &d1));
    g_assert_true(memcmp(&d, &d1, sizeof d) == 0);
  }
}

/* A tilted box where a needed count exceeds 2^50 (box.hpp): the pair fails
 * with PW85_ERR_INVALID_ARGUMENT and NaN outputs; the same centres in the
 * box without tilt are reduced exactly. */
static void test_scene_count_limit(void) {
  double c[6] = {0, 0, 0, 0.25, 0.5, 0x1p60};
  double q[12];
  sphere_q(0.1, q);
  sphere_q(0.1, q + 6);
  long long const pair[2] = {0, 1};
  double const tilted[6] = {2, 2, 2, 0, 0.5, 0}, straight[6] = {2, 2, 2, 0, 0, 0};
  pw85_result res;
  int st = 0;
  g_assert_cmpint(pw85_scene_contact_function(2, c, q, tilted, 1, pair, PW85_METHOD_DEFAULT,
                                              &res, &st, 1), ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(st, ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_true(isnan(res.mu2));
  double const r[3] = {0.25, 0.5, 0};
  pw85_result one;
  g_assert_cmpint(pw85_scene_contact_function(2, c, q, straight, 1, pair, PW85_METHOD_DEFAULT,
                                              &res, &st, 1), ==,
                  pw85_contact_function_method(r, q, q + 6, PW85_METHOD_DEFAULT, &one));
  g_assert_true(memcmp(&res, &one, sizeof res) == 0);
}

/* Call-level errors of the new functions: nothing written (outputs and
 * status keep a sentinel); m = 0 is a no-op. */
static void test_new_bad_input(void) {
  static pair_arrays s;
  make_pair_arrays(&s, 61);
  double const good[6] = {3, 3, 3, 0.2, 0.1, -0.3};
  double bad_boxes[][6] = {{0, 3, 3, 0, 0, 0},       {3, -1, 3, 0, 0, 0},
                           {3, 3, NAN, 0, 0, 0},     {INFINITY, 3, 3, 0, 0, 0},
                           {3, 3, 3, NAN, 0, 0},     {3, 3, 3, 0, INFINITY, 0},
                           {3, 3, 3, 0, 0, -INFINITY}, {3, 3, 1e300, 0, 0, 1e300}};
  int v[4], st[4];
  pw85_result r[4];
  pw85_contact_t ct[4];
  double *r12 = s.r12, *q1 = s.q1, *q2 = s.q2, *c = s.c, *q = s.q;
  long long *pr = s.pairs;
#define NOTHING_WRITTEN(call, expect)                         \
  do {                                                        \
    memset(v, 0x5A, sizeof v);                                \
    memset(st, 0x5A, sizeof st);                              \
    memset(r, 0x5A, sizeof r);                                \
    memset(ct, 0x5A, sizeof ct);                              \
    g_assert_cmpint((call), ==, (expect));                    \
    unsigned char ref[sizeof ct];                             \
    memset(ref, 0x5A, sizeof ref);                            \
    g_assert_true(memcmp(v, ref, sizeof v) == 0);             \
    g_assert_true(memcmp(st, ref, sizeof st) == 0);           \
    g_assert_true(memcmp(r, ref, sizeof r) == 0);             \
    g_assert_true(memcmp(ct, ref, sizeof ct) == 0);           \
  } while (0)
  int const E = PW85_ERR_INVALID_ARGUMENT;
  /* NULL required pointers, m < 0, nthreads < 0 */
  NOTHING_WRITTEN(pw85_overlap_pairs(4, NULL, q1, q2, v, st, 1), E);
  NOTHING_WRITTEN(pw85_overlap_pairs(4, r12, NULL, q2, v, st, 1), E);
  NOTHING_WRITTEN(pw85_overlap_pairs(4, r12, q1, NULL, v, st, 1), E);
  NOTHING_WRITTEN(pw85_overlap_pairs(4, r12, q1, q2, NULL, st, 1), E);
  NOTHING_WRITTEN(pw85_overlap_pairs(-1, r12, q1, q2, v, st, 1), E);
  NOTHING_WRITTEN(pw85_overlap_pairs(4, r12, q1, q2, v, st, -1), E);
  NOTHING_WRITTEN(pw85_contact_function_pairs(4, NULL, q1, q2, 0, r, st, 1), E);
  NOTHING_WRITTEN(pw85_contact_function_pairs(4, r12, NULL, q2, 0, r, st, 1), E);
  NOTHING_WRITTEN(pw85_contact_function_pairs(4, r12, q1, NULL, 0, r, st, 1), E);
  NOTHING_WRITTEN(pw85_contact_function_pairs(4, r12, q1, q2, 0, NULL, st, 1), E);
  NOTHING_WRITTEN(pw85_contact_function_pairs(-5, r12, q1, q2, 0, r, st, 1), E);
  NOTHING_WRITTEN(pw85_contact_function_pairs(4, r12, q1, q2, 0, r, st, INT_MIN), E);
  NOTHING_WRITTEN(pw85_contact_function_pairs(4, r12, q1, q2, -1, r, st, 1),
                  PW85_ERR_UNKNOWN_METHOD);
  NOTHING_WRITTEN(pw85_contact_function_pairs(4, r12, q1, q2, 5, r, st, 1),
                  PW85_ERR_UNKNOWN_METHOD);
  NOTHING_WRITTEN(pw85_contact_pairs(4, NULL, q1, q2, ct, st, 1), E);
  NOTHING_WRITTEN(pw85_contact_pairs(4, r12, NULL, q2, ct, st, 1), E);
  NOTHING_WRITTEN(pw85_contact_pairs(4, r12, q1, NULL, ct, st, 1), E);
  NOTHING_WRITTEN(pw85_contact_pairs(4, r12, q1, q2, NULL, st, 1), E);
  NOTHING_WRITTEN(pw85_contact_pairs(LLONG_MIN, r12, q1, q2, ct, st, 1), E);
  NOTHING_WRITTEN(pw85_contact_pairs(4, r12, q1, q2, ct, st, -3), E);
  for (int nb = -1; nb < (int)(sizeof bad_boxes / sizeof bad_boxes[0]); nb++) {
    const double *b = nb < 0 ? good : bad_boxes[nb];
    if (nb >= 0) {
      NOTHING_WRITTEN(pw85_scene_overlap(N, c, q, b, 4, pr, v, st, 1), E);
      NOTHING_WRITTEN(pw85_scene_contact_function(N, c, q, b, 4, pr, 0, r, st, 1), E);
      NOTHING_WRITTEN(pw85_scene_contact(N, c, q, b, 4, pr, ct, st, 1), E);
      continue;
    }
    NOTHING_WRITTEN(pw85_scene_overlap(-1, c, q, b, 4, pr, v, st, 1), E);
    NOTHING_WRITTEN(pw85_scene_overlap(N, NULL, q, b, 4, pr, v, st, 1), E);
    NOTHING_WRITTEN(pw85_scene_overlap(N, c, NULL, b, 4, pr, v, st, 1), E);
    NOTHING_WRITTEN(pw85_scene_overlap(N, c, q, b, 4, NULL, v, st, 1), E);
    NOTHING_WRITTEN(pw85_scene_overlap(N, c, q, b, 4, pr, NULL, st, 1), E);
    NOTHING_WRITTEN(pw85_scene_overlap(N, c, q, b, -4, pr, v, st, 1), E);
    NOTHING_WRITTEN(pw85_scene_overlap(N, c, q, b, 4, pr, v, st, -1), E);
    NOTHING_WRITTEN(pw85_scene_contact_function(-1, c, q, b, 4, pr, 0, r, st, 1), E);
    NOTHING_WRITTEN(pw85_scene_contact_function(N, NULL, q, b, 4, pr, 0, r, st, 1), E);
    NOTHING_WRITTEN(pw85_scene_contact_function(N, c, NULL, b, 4, pr, 0, r, st, 1), E);
    NOTHING_WRITTEN(pw85_scene_contact_function(N, c, q, b, 4, NULL, 0, r, st, 1), E);
    NOTHING_WRITTEN(pw85_scene_contact_function(N, c, q, b, 4, pr, 0, NULL, st, 1), E);
    NOTHING_WRITTEN(pw85_scene_contact_function(N, c, q, b, -4, pr, 0, r, st, 1), E);
    NOTHING_WRITTEN(pw85_scene_contact_function(N, c, q, b, 4, pr, 0, r, st, -1), E);
    NOTHING_WRITTEN(pw85_scene_contact_function(N, c, q, b, 4, pr, 7, r, st, 1),
                    PW85_ERR_UNKNOWN_METHOD);
    NOTHING_WRITTEN(pw85_scene_contact(-1, c, q, b, 4, pr, ct, st, 1), E);
    NOTHING_WRITTEN(pw85_scene_contact(N, NULL, q, b, 4, pr, ct, st, 1), E);
    NOTHING_WRITTEN(pw85_scene_contact(N, c, NULL, b, 4, pr, ct, st, 1), E);
    NOTHING_WRITTEN(pw85_scene_contact(N, c, q, b, 4, NULL, ct, st, 1), E);
    NOTHING_WRITTEN(pw85_scene_contact(N, c, q, b, 4, pr, NULL, st, 1), E);
    NOTHING_WRITTEN(pw85_scene_contact(N, c, q, b, -4, pr, ct, st, 1), E);
    NOTHING_WRITTEN(pw85_scene_contact(N, c, q, b, 4, pr, ct, st, -1), E);
  }
  /* m = 0: a no-op, whatever the pointers */
  NOTHING_WRITTEN(pw85_overlap_pairs(0, NULL, NULL, NULL, NULL, NULL, 1), PW85_OK);
  NOTHING_WRITTEN(pw85_contact_function_pairs(0, NULL, NULL, NULL, 0, NULL, NULL, 1), PW85_OK);
  NOTHING_WRITTEN(pw85_contact_pairs(0, NULL, NULL, NULL, NULL, NULL, 1), PW85_OK);
  NOTHING_WRITTEN(pw85_scene_overlap(0, NULL, NULL, NULL, 0, NULL, NULL, NULL, 1), PW85_OK);
  NOTHING_WRITTEN(pw85_scene_contact_function(0, NULL, NULL, NULL, 0, NULL, 0, NULL, NULL, 1),
                  PW85_OK);
  NOTHING_WRITTEN(pw85_scene_contact(0, NULL, NULL, NULL, 0, NULL, NULL, NULL, 1), PW85_OK);
#undef NOTHING_WRITTEN
  /* status may be NULL */
  g_assert_cmpint(pw85_contact_pairs(4, r12, q1, q2, ct, NULL, 2), ==, PW85_OK);
  g_assert_cmpint(pw85_scene_overlap(N, c, q, good, 4, pr, v, NULL, 2), ==, PW85_OK);
}

/* nthreads far beyond the CPUs: every batch call (ids below) returns the
 * results of nthreads = 1. Without the clamp of the thread count, the
 * OpenMP runtime fails to create the threads and ends the process. */
enum { F_OVERLAP_BATCH, F_CF_BATCH, F_CONTACT_BATCH, F_OVERLAP_PAIRS, F_CF_PAIRS, F_CONTACT_PAIRS,
       F_SCENE_OVERLAP, F_SCENE_CF, F_SCENE_CONTACT, F_COUNT };
static const int f_ids[F_COUNT] = {0, 1, 2, 3, 4, 5, 6, 7, 8};

static int call_batch(int f, const pair_arrays *s, void *out, int *st, int nthreads) {
  double const box[6] = {4.0, 3.5, 5.0, 0.4, -0.3, 0.2};
  switch (f) {
    case F_OVERLAP_BATCH: return pw85_overlap_batch(N, s->c, s->q, M, s->pairs, out, st, nthreads);
    case F_CF_BATCH:
      return pw85_contact_function_batch(N, s->c, s->q, M, s->pairs, out, st, nthreads);
    case F_CONTACT_BATCH: return pw85_contact_batch(N, s->c, s->q, M, s->pairs, out, st, nthreads);
    case F_OVERLAP_PAIRS: return call_new(0, 0, s, NULL, 0, out, st, nthreads);
    case F_CF_PAIRS: return call_new(1, 0, s, NULL, PW85_METHOD_DEFAULT, out, st, nthreads);
    case F_CONTACT_PAIRS: return call_new(2, 0, s, NULL, 0, out, st, nthreads);
    case F_SCENE_OVERLAP: return call_new(0, 1, s, box, 0, out, st, nthreads);
    case F_SCENE_CF: return call_new(1, 1, s, box, PW85_METHOD_DEFAULT, out, st, nthreads);
    default: return call_new(2, 1, s, box, 0, out, st, nthreads);
  }
}

/* Reference mu2, independent of the library: the maximiser from the golden
 * section search of mu2_ld, then Newton steps on f' with f, f', f'' in
 * __float128 (q_f_derivs); the largest f met. About 1e-16 relative in the
 * classes below, also under valgrind, whose long double is a double. */
static double mu2_ref(const double r[3], const double q1[6], const double q2[6]) {
  long double lam_ld;
  mu2_ld(r, q1, q2, &lam_ld);
  double lam = (double)lam_ld, best = 0.0;
  for (int it = 0; it < 3; it++) {  /* lam from mu2_ld: ~1e-8, then 1e-16 */
    double d[3];
    q_f_derivs(lam, r, q1, q2, d);
    if (d[0] > best) best = d[0];
    if (!(d[2] < 0.0)) break;
    double const next = lam - d[1] / d[2];
    if (!(next > 0.0 && next < 1.0)) break;
    lam = next;
  }
  return best;
}

/* Pairs of the four classes of the benchmarks (semi-axes log-uniform in
 * [0.5, 2], [0.1, 10], [0.01, 100], [0.001, 1000]), centre distance
 * (a1max + a2max) 10^U(-2, 0.5); every odd pair rescaled to near contact,
 * mu2 = t = 1 -+ 10^U(-13, -2) by mu2_ref (side[k]: the verdict, when
 * |1 - t| exceeds 1e-9, far above the error of mu2_ref, else -1). A few
 * degenerate pairs: r12 = 0, a matrix of condition number 1e15. */
#define LP 2048
typedef struct {
  double r12[3 * LP], q1[6 * LP], q2[6 * LP];
  int side[LP];
} lane_pairs;

static void make_lane_pairs(lane_pairs *s, int cls, guint32 seed) {
  static const double lo[4] = {0.5, 0.1, 0.01, 0.001}, hi[4] = {2.0, 10.0, 100.0, 1000.0};
  double const tol = 1e-9;
  GRand *rng = g_rand_new_with_seed(seed);
  for (int k = 0; k < LP; k++) {
    double rad1[3], rad2[3], ax[9], dir[9];
    double *r = s->r12 + 3 * k, *q1 = s->q1 + 6 * k, *q2 = s->q2 + 6 * k;
    random_radii(rng, lo[cls], hi[cls], rad1);
    random_axes(rng, ax);
    make_q(rad1, ax, q1);
    random_radii(rng, lo[cls], hi[cls], rad2);
    random_axes(rng, ax);
    make_q(rad2, ax, q2);
    if (k % 61 == 9) random_spd(rng, 1e15, q1);
    random_axes(rng, dir);
    double const reach = fmax(rad1[0], fmax(rad1[1], rad1[2])) + fmax(rad2[0], fmax(rad2[1], rad2[2]));
    double const dist = reach * pow(10.0, g_rand_double_range(rng, -2.0, 0.5));
    for (int d = 0; d < 3; d++) r[d] = k % 97 == 3 ? 0.0 : dist * dir[d];
    s->side[k] = -1;
    if (k % 2 && k % 61 != 9 && k % 97 != 3) {
      double const mu2 = mu2_ref(r, q1, q2);
      double const e = pow(10.0, g_rand_double_range(rng, -13.0, -2.0));
      double const t = k % 4 == 1 ? 1.0 - e : 1.0 + e;
      double const sc = sqrt(t / mu2);
      for (int d = 0; d < 3; d++) r[d] *= sc;
      if (e >= tol) s->side[k] = t < 1.0;
    }
  }
  g_rand_free(rng);
}

/* The overlap calls through the lanes of overlap_lanes (docs/batch.md,
 * "Throughput") against pw85_overlap on the pairs above with bad ones among
 * them (NaN r12, a matrix not positive definite, an infinite entry, a zero
 * matrix): every verdict and status bitwise equal, for the whole array on 1
 * and 2 threads, for arrays of m = 1 ... 17 pairs starting at every offset
 * 0 ... 47 (each pair in every lane position of blocks of 4 or 8 lanes and
 * in the tail, next to bad pairs), and through pw85_scene_overlap and
 * pw85_overlap_batch on the scene of the same pairs; the verdicts known from
 * mu2_ref all right. */
static void test_overlap_lanes(gconstpointer data) {
  int const cls = *(const int *)data;
  static lane_pairs s;
  static int exp[LP], exp_st[LP], out[LP], st[LP];
  static double c[6 * LP], q[12 * LP];
  static long long pairs[2 * LP];
  make_lane_pairs(&s, cls, 81 + cls);
  s.r12[3 * 10 + 2] = NAN;
  s.q2[6 * 21 + 0] = -1.0;
  s.q1[6 * 33 + 3] = INFINITY;
  memset(s.q2 + 6 * 45, 0, 6 * sizeof(double));
  s.side[10] = s.side[21] = s.side[33] = s.side[45] = -1;
  int known = 0, wrong = 0, first = LP, n_overlap = 0;
  for (int k = 0; k < LP; k++) {
    exp[k] = pw85_overlap(s.r12 + 3 * k, s.q1 + 6 * k, s.q2 + 6 * k);
    exp_st[k] = exp[k] < 0 ? exp[k] : PW85_OK;
    if (exp[k] < 0 && first == LP) first = k;
    n_overlap += exp[k] == 1;
    if (s.side[k] >= 0) {
      known++;
      wrong += exp[k] != s.side[k];
    }
  }
  g_assert_cmpint(wrong, ==, 0);
  g_assert_cmpint(known, >, LP / 4);
  g_assert_cmpint(first, ==, 10);
  g_assert_cmpint(n_overlap, >, LP / 4);
  g_assert_cmpint(n_overlap, <, 3 * LP / 4);
  for (int threads = 1; threads <= 2; threads++) {
    memset(out, 0xA5, sizeof out);
    memset(st, 0xA5, sizeof st);
    g_assert_cmpint(pw85_overlap_pairs(LP, s.r12, s.q1, s.q2, out, st, threads), ==,
                    exp_st[first]);
    g_assert_true(memcmp(out, exp, sizeof out) == 0);
    g_assert_true(memcmp(st, exp_st, sizeof st) == 0);
  }
  for (int m = 1; m <= 17; m++)
    for (int k0 = 0; k0 < 48; k0++) {
      int lowest = PW85_OK;
      for (int k = k0 + m - 1; k >= k0; k--)
        if (exp_st[k] != PW85_OK) lowest = exp_st[k];
      memset(out, 0xA5, m * sizeof(int));
      memset(st, 0xA5, m * sizeof(int));
      g_assert_cmpint(pw85_overlap_pairs(m, s.r12 + 3 * k0, s.q1 + 6 * k0, s.q2 + 6 * k0, out, st, 1),
                      ==, lowest);
      g_assert_true(memcmp(out, exp + k0, m * sizeof(int)) == 0);
      g_assert_true(memcmp(st, exp_st + k0, m * sizeof(int)) == 0);
    }
  /* scene: ellipsoid 2k at the origin, 2k+1 at r12 (c_j - c_i = r12 exactly) */
  for (int k = 0; k < LP; k++) {
    for (int d = 0; d < 3; d++) {
      c[6 * k + d] = 0.0;
      c[6 * k + 3 + d] = s.r12[3 * k + d];
    }
    memcpy(q + 12 * k, s.q1 + 6 * k, 6 * sizeof(double));
    memcpy(q + 12 * k + 6, s.q2 + 6 * k, 6 * sizeof(double));
    pairs[2 * k] = 2 * k;
    pairs[2 * k + 1] = 2 * k + 1;
  }
  for (int f = 0; f < 2; f++) {
    memset(out, 0xA5, sizeof out);
    memset(st, 0xA5, sizeof st);
    int const ret = f ? pw85_overlap_batch(2 * LP, c, q, LP, pairs, out, st, 2)
                      : pw85_scene_overlap(2 * LP, c, q, NULL, LP, pairs, out, st, 2);
    g_assert_cmpint(ret, ==, exp_st[first]);
    g_assert_true(memcmp(out, exp, sizeof out) == 0);
    g_assert_true(memcmp(st, exp_st, sizeof st) == 0);
  }
}

/* pw85_contact_function_pairs with DEFAULT through the lanes of
 * default_lanes (docs/batch.md, "Throughput") against
 * pw85_contact_function_method on the pairs of make_lane_pairs (r12 = 0, a
 * matrix of condition 1e15, near-contact pairs) with bad ones among them
 * (NaN r12, a matrix not positive definite, an infinite entry, a zero
 * matrix): every result and status bitwise equal, for the whole array on 1
 * and 2 threads and for arrays of m = 1 ... 9 pairs at every offset
 * 0 ... 47. Relative error against mu2_ref <= 1e-14 on every third pair
 * whose status is PW85_OK (r12 = 0, the condition-1e15 and the small-Q1
 * pairs left out). */
static void test_default_lanes(gconstpointer data) {
  int const cls = *(const int *)data;
  static lane_pairs s;
  static pw85_result exp[LP], out[LP];
  static int exp_st[LP], st[LP];
  make_lane_pairs(&s, cls, 91 + cls);
  /* Q1 times 1e-10 in every 53rd pair: the maximiser lambda near 0, off
   * the grid of the start (M24) on x86-64-v4 (its lanes then take (M22)). */
  for (int k = 7; k < LP; k += 53)
    for (int i = 0; i < 6; i++) s.q1[6 * k + i] *= 1e-10;
  s.r12[3 * 12 + 0] = NAN;
  s.q1[6 * 23 + 3] = -1.0;
  s.q2[6 * 35 + 4] = -INFINITY;
  memset(s.q1 + 6 * 47, 0, 6 * sizeof(double));
  int first = LP, n_ok = 0;
  double max_err = 0.0;
  for (int k = 0; k < LP; k++) {
    exp_st[k] = pw85_contact_function_method(s.r12 + 3 * k, s.q1 + 6 * k, s.q2 + 6 * k,
                                             PW85_METHOD_DEFAULT, exp + k);
    if (exp_st[k] != PW85_OK && first == LP) first = k;
    if (exp_st[k] != PW85_OK) continue;
    n_ok++;
    if (k % 3 == 0 && k % 61 != 9 && k % 97 != 3 && k % 53 != 7) {
      double const ref = mu2_ref(s.r12 + 3 * k, s.q1 + 6 * k, s.q2 + 6 * k);
      max_err = fmax(max_err, rel_error(exp[k].mu2, ref));
    }
  }
  g_test_message("class %d: %d of %d pairs PW85_OK, max relative error %.3g", cls, n_ok, LP,
                 max_err);
  g_assert_cmpint(first, ==, 12);
  g_assert_cmpint(n_ok, >, LP - LP / 10);
  g_assert_cmpfloat(max_err, <=, 1e-14);
  for (int threads = 1; threads <= 2; threads++) {
    memset(out, 0xA5, sizeof out);
    memset(st, 0xA5, sizeof st);
    g_assert_cmpint(pw85_contact_function_pairs(LP, s.r12, s.q1, s.q2, PW85_METHOD_DEFAULT, out,
                                                st, threads),
                    ==, exp_st[first]);
    g_assert_true(memcmp(out, exp, sizeof out) == 0);
    g_assert_true(memcmp(st, exp_st, sizeof st) == 0);
  }
  for (int m = 1; m <= 9; m++)
    for (int k0 = 0; k0 < 48; k0++) {
      int lowest = PW85_OK;
      for (int k = k0 + m - 1; k >= k0; k--)
        if (exp_st[k] != PW85_OK) lowest = exp_st[k];
      memset(out, 0xA5, m * sizeof(pw85_result));
      memset(st, 0xA5, m * sizeof(int));
      g_assert_cmpint(pw85_contact_function_pairs(m, s.r12 + 3 * k0, s.q1 + 6 * k0, s.q2 + 6 * k0,
                                                  PW85_METHOD_DEFAULT, out, st, 1),
                      ==, lowest);
      g_assert_true(memcmp(out, exp + k0, m * sizeof(pw85_result)) == 0);
      g_assert_true(memcmp(st, exp_st + k0, m * sizeof(int)) == 0);
    }
}

static void test_huge_nthreads(gconstpointer data) {
  int const f = *(const int *)data;
  static pair_arrays s;
  make_pair_arrays(&s, 71);
  spoil(&s);
  memset(big_out[0], 0xA5, sizeof big_out[0]);
  int const ret1 = call_batch(f, &s, big_out[0], big_st[0], 1);
  g_assert_cmpint(ret1, !=, PW85_OK);  /* the spoiled pairs fail */
  int const huge[3] = {100000, INT_MAX, 0};
  for (int h = 0; h < 3; h++) {
    memset(big_out[1], 0xA5, sizeof big_out[1]);
    g_assert_cmpint(call_batch(f, &s, big_out[1], big_st[1], huge[h]), ==, ret1);
    g_assert_true(memcmp(big_out[0], big_out[1], sizeof big_out[0]) == 0);
    g_assert_true(memcmp(big_st[0], big_st[1], sizeof big_st[0]) == 0);
  }
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
  static const char *const new_names[9] = {
    "/pw85_overlap_pairs/one-pair-bitwise", "/pw85_contact_function_pairs/one-pair-bitwise",
    "/pw85_contact_pairs/one-pair-bitwise", "/pw85_scene_overlap/one-pair-bitwise",
    "/pw85_scene_contact_function/one-pair-bitwise", "/pw85_scene_contact/one-pair-bitwise",
    "/pw85_scene_overlap/periodic-one-pair-bitwise",
    "/pw85_scene_contact_function/periodic-one-pair-bitwise",
    "/pw85_scene_contact/periodic-one-pair-bitwise"};
  for (int c = 0; c < 9; c++)
    g_test_add_data_func(new_names[c], &new_cases[c], test_new_against_one_pair);
  static const double tilts[3] = {0.5, 1.0, 3.0};
  g_test_add_data_func("/pw85_scene_contact_function/min-image-tilt-0.5", &tilts[0],
                       test_min_image);
  g_test_add_data_func("/pw85_scene_contact_function/min-image-tilt-1", &tilts[1],
                       test_min_image);
  g_test_add_data_func("/pw85_scene_contact_function/min-image-tilt-3", &tilts[2],
                       test_min_image);
  static const int classes[4] = {0, 1, 2, 3};
  for (int c = 0; c < 4; c++) {
    char path[64];
    g_snprintf(path, sizeof path, "/pw85_overlap_pairs/lanes-class-%d", c);
    g_test_add_data_func(path, &classes[c], test_overlap_lanes);
    g_snprintf(path, sizeof path, "/pw85_contact_function_pairs/default-lanes-class-%d", c);
    g_test_add_data_func(path, &classes[c], test_default_lanes);
  }
  g_test_add_func("/pw85_scene_overlap/bounding-spheres", test_scene_reach);
  g_test_add_func("/pw85_scene_overlap/bad-input", test_new_bad_input);
  g_test_add_func("/pw85_scene_contact/extreme-boxes", test_scene_extreme_boxes);
  g_test_add_func("/pw85_scene_contact_function/count-limit", test_scene_count_limit);
  static const char *const f_names[F_COUNT] = {
    "pw85_overlap_batch", "pw85_contact_function_batch", "pw85_contact_batch",
    "pw85_overlap_pairs", "pw85_contact_function_pairs", "pw85_contact_pairs",
    "pw85_scene_overlap", "pw85_scene_contact_function", "pw85_scene_contact"};
  for (int f = 0; f < F_COUNT; f++) {
    char path[96];
    g_snprintf(path, sizeof path, "/%s/nthreads-huge", f_names[f]);
    g_test_add_data_func(path, &f_ids[f], test_huge_nthreads);
  }
  return g_test_run();
}
