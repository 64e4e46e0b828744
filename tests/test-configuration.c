/* Tests of the configuration object (pw85_configuration_*, docs/scene.md)
 * against brute force: every pair i < j of the configuration through
 * pw85_scene_overlap (the minimum image of the scene calls), with the
 * matrices scaled by s^2 for s > 1, and mu^2 through
 * pw85_scene_contact_function (DEFAULT). Open, dense periodic and tilted
 * periodic configurations of spheroids of aspect ratios 0.1 to 50 and of
 * general ellipsoids, centres partly moved by lattice vectors far out of
 * the box; every thread count 1, 2, 3. Test-and-move against brute force,
 * update, and bad input (statuses, the particle named, nothing changed). */
#include <math.h>
#include <pw85.h>
#include <stdlib.h>
#include <string.h>

#include "testutil.h"

typedef struct {
  int n;
  double *c, *q;
  double box[6];
  int periodic;
} config;

static void config_free(config *cf) {
  g_free(cf->c);
  g_free(cf->q);
}

/* n particles of aspect ratio aspect (spheroid semi-axes 1, 1, aspect;
 * aspect 0: general ellipsoids of semi-axes in [0.3, 1.5]) in a box of
 * side lengths scale * rb * (1, 0.9, 1.1), rb the largest bound_radius, with tilts (0, 0, 0) or (0.3, -0.2,
 * 0.4); periodic or open (centres in the same region). Some centres are
 * moved by whole lattice vectors (periodic) so that they lie out of the box. */
/* The bounding radius of the pw85_scene_* calls: the square root of the
 * smaller of the trace and the largest Gershgorin row sum of |Q|. */
static double bound_radius(double const q[6]) {
  double const a[6] = {fabs(q[0]), fabs(q[1]), fabs(q[2]), fabs(q[3]), fabs(q[4]), fabs(q[5])};
  double const r0 = a[0] + a[1] + a[2], r1 = a[1] + a[3] + a[4], r2 = a[2] + a[4] + a[5];
  double g = fmax(r0, fmax(r1, r2));
  return sqrt(fmin(g, a[0] + a[3] + a[5]));
}

static void make_config(config *cf, int n, double aspect, double scale, int periodic, int tilted,
                        guint32 seed) {
  GRand *rng = g_rand_new_with_seed(seed);
  cf->n = n;
  cf->periodic = periodic;
  cf->c = g_new(double, 3 * (n > 0 ? n : 1));
  cf->q = g_new(double, 6 * (n > 0 ? n : 1));
  double rb = 0;
  for (int i = 0; i < n; i++) {
    double rad[3], ax[9];
    if (aspect > 0) {
      rad[0] = rad[1] = 1.0;
      rad[2] = aspect;
    } else {
      random_radii(rng, 0.3, 1.5, rad);
    }
    random_axes(rng, ax);
    make_q(rad, ax, cf->q + 6 * i);
    rb = fmax(rb, bound_radius(cf->q + 6 * i));
  }
  scale *= rb;
  double const box[6] = {scale, 0.9 * scale, 1.1 * scale, tilted ? 0.3 : 0, tilted ? -0.2 : 0,
                         tilted ? 0.4 : 0};
  memcpy(cf->box, box, sizeof box);
  for (int i = 0; i < n; i++) {
    double f[3];
    for (int d = 0; d < 3; d++) f[d] = g_rand_double_range(rng, -0.5, 0.5);
    if (periodic && g_rand_int_range(rng, 0, 4) == 0)
      for (int d = 0; d < 3; d++) f[d] += g_rand_int_range(rng, -3, 4);
    /* x = f0 a1 + f1 a2 + f2 a3 */
    cf->c[3 * i + 0] = f[0] * box[0] + f[1] * box[3] * box[1] + f[2] * box[4] * box[2];
    cf->c[3 * i + 1] = f[1] * box[1] + f[2] * box[5] * box[2];
    cf->c[3 * i + 2] = f[2] * box[2];
  }
  g_rand_free(rng);
}

/* The brute-force pairs with mu^2 < s^2 in the sense of
 * pw85_configuration_pairs: pw85_scene_overlap of every pair i < j with
 * matrices (s s) Q; mu2 by pw85_scene_contact_function (DEFAULT) on the
 * unscaled matrices. Returns the count; *pi, *pj, *pmu2 (g_free). */
static long long brute_pairs(config const *cf, double s, long long **pi, long long **pj,
                             double **pmu2) {
  int const n = cf->n;
  long long const m = (long long)n * (n - 1) / 2;
  long long *pairs = g_new(long long, 2 * (m > 0 ? m : 1));
  long long k = 0;
  for (int i = 0; i < n; i++)
    for (int j = i + 1; j < n; j++) {
      pairs[2 * k] = i;
      pairs[2 * k + 1] = j;
      k++;
    }
  double *qs = g_new(double, 6 * (n > 0 ? n : 1));
  double const s2 = s * s;
  for (int t = 0; t < 6 * n; t++) qs[t] = s2 * cf->q[t];
  int *ov = g_new(int, m > 0 ? m : 1);
  double const *box = cf->periodic ? cf->box : NULL;
  int st = pw85_scene_overlap(n, cf->c, qs, box, m, pairs, ov, NULL, 1);
  g_assert_cmpint(st, ==, PW85_OK);
  long long count = 0;
  for (long long t = 0; t < m; t++) count += ov[t] == 1;
  *pi = g_new(long long, count + 1);
  *pj = g_new(long long, count + 1);
  long long *sel = g_new(long long, 2 * (count + 1));
  long long c = 0;
  for (long long t = 0; t < m; t++)
    if (ov[t] == 1) {
      (*pi)[c] = sel[2 * c] = pairs[2 * t];
      (*pj)[c] = sel[2 * c + 1] = pairs[2 * t + 1];
      c++;
    }
  pw85_result *res = g_new(pw85_result, count + 1);
  if (count > 0) {
    st = pw85_scene_contact_function(n, cf->c, cf->q, box, count, sel, PW85_METHOD_DEFAULT, res,
                                     NULL, 1);
    (void)st; /* per-pair statuses as the configuration reports them: mu2 */
  }
  *pmu2 = g_new(double, count + 1);
  for (long long t = 0; t < count; t++) (*pmu2)[t] = res[t].mu2;
  g_free(res);
  g_free(sel);
  g_free(ov);
  g_free(qs);
  g_free(pairs);
  return count;
}

static int same_double(double a, double b) {
  return (isnan(a) && isnan(b)) || memcmp(&a, &b, sizeof a) == 0;
}

/* pw85_configuration_pairs at s on every thread count equals brute force,
 * bitwise (indices and mu2). Returns the number of pairs. */
static long long check_pairs(config const *cf, double s) {
  pw85_configuration *conf = NULL;
  long long bad = 7;
  int st = pw85_configuration_create(cf->n, cf->c, cf->q, cf->periodic ? cf->box : NULL, &conf,
                                     &bad);
  g_assert_cmpint(st, ==, PW85_OK);
  g_assert_cmpint(bad, ==, -1);
  long long *bi, *bj;
  double *bmu2;
  long long const m = brute_pairs(cf, s, &bi, &bj, &bmu2);
  for (int threads = 1; threads <= 3; threads++) {
    long long count = -5;
    st = pw85_configuration_pairs(conf, s, threads, 0, NULL, NULL, NULL, &count, NULL);
    g_assert_cmpint(st, ==, m > 0 ? PW85_ERR_CAPACITY : PW85_OK);
    g_assert_cmpint(count, ==, m);
    long long *ci = g_new(long long, m + 1), *cj = g_new(long long, m + 1);
    double *cm = g_new(double, m + 1);
    long long ex[2] = {-1, -1};
    st = pw85_configuration_pairs(conf, s, threads, m, ci, cj, cm, &count, ex);
    g_assert_cmpint(st, ==, PW85_OK);
    g_assert_cmpint(count, ==, m);
    g_assert_cmpint(ex[1], >=, m);
    g_assert_cmpint(ex[0], >=, ex[1]);
    for (long long k = 0; k < m; k++) {
      if (ci[k] != bi[k] || cj[k] != bj[k] || !same_double(cm[k], bmu2[k]))
        g_error("s = %g, %d threads, pair %lld: (%lld, %lld, %.17g), brute force (%lld, %lld, %.17g)",
                s, threads, k, ci[k], cj[k], cm[k], bi[k], bj[k], bmu2[k]);
    }
    g_free(ci);
    g_free(cj);
    g_free(cm);
  }
  g_free(bi);
  g_free(bj);
  g_free(bmu2);
  pw85_configuration_destroy(conf);
  return m;
}

typedef struct {
  double aspect, scale;
  int n, periodic, tilted;
} case_t;

/* scale: box side in units of the largest bounding radius (periodic:
 * >= 4 sqrt(2) / 0.9, so that the box holds the pairs at s = sqrt(2)). */
static void run_cases(case_t const *cases, int ncases) {
  for (int k = 0; k < ncases; k++) {
    config cf;
    make_config(&cf, cases[k].n, cases[k].aspect, cases[k].scale, cases[k].periodic,
                cases[k].tilted, 1000 + k);
    long long const m1 = check_pairs(&cf, 1.0);
    long long const m12 = check_pairs(&cf, 1.2);
    long long const m2 = check_pairs(&cf, sqrt(2.0));
    if (g_test_verbose())
      g_printerr("aspect %g n %d periodic %d tilted %d: %lld, %lld, %lld pairs\n",
                 cases[k].aspect, cases[k].n, cases[k].periodic, cases[k].tilted, m1, m12, m2);
    /* The cases are chosen to have pairs at every s (a test that finds
     * none checks little). */
    g_assert_cmpint(m1, >, 0);
    g_assert_cmpint(m12, >=, m1);
    g_assert_cmpint(m2, >=, m12);
    config_free(&cf);
  }
}

static void test_pairs_open(void) {
  case_t const cases[] = {
      {0.1, 8, 250, 0, 0}, {1, 8, 250, 0, 0},  {3, 5, 250, 0, 0},
      {10, 4, 250, 0, 0},  {50, 3, 200, 0, 0}, {0, 6, 250, 0, 0},
  };
  run_cases(cases, G_N_ELEMENTS(cases));
}

static void test_pairs_periodic(void) {
  case_t const cases[] = {
      {0.1, 6.5, 250, 1, 0}, {1, 6.5, 300, 1, 0},  {3, 6.5, 250, 1, 0},
      {10, 6.5, 250, 1, 0}, {50, 6.5, 200, 1, 0}, {0, 6.5, 300, 1, 0},
  };
  run_cases(cases, G_N_ELEMENTS(cases));
}

static void test_pairs_triclinic(void) {
  case_t const cases[] = {
      {0.1, 6.5, 250, 1, 1}, {1, 6.5, 300, 1, 1},  {3, 6.5, 250, 1, 1},
      {10, 6.5, 250, 1, 1}, {50, 6.5, 200, 1, 1}, {0, 6.5, 300, 1, 1},
  };
  run_cases(cases, G_N_ELEMENTS(cases));
}

/* Boxes of at least 3 cells along each axis at every s (the grid's fast
 * path, with images across the faces, edges and corners of the box). */
static void test_pairs_large(void) {
  case_t const cases[] = {
      {1, 14, 1200, 1, 1},  {3, 14, 1200, 1, 0}, {10, 14, 1500, 1, 1},
      {0.1, 14, 1200, 1, 0}, {0, 14, 1500, 1, 1}, {50, 14, 1500, 1, 1},
  };
  run_cases(cases, G_N_ELEMENTS(cases));
}

/* A dense configuration: many particles per cell, many overlaps. */
static void test_pairs_dense(void) {
  case_t const cases[] = {
      {1, 6.5, 600, 1, 1}, {3, 6.5, 500, 1, 0}, {0.1, 6.5, 600, 1, 1}, {1, 3, 400, 0, 0},
  };
  run_cases(cases, G_N_ELEMENTS(cases));
}

/* Smallest j != i overlapping particle i at (c, q), brute force with
 * pw85_scene_overlap on the pair (min, max) of the configuration with the
 * trial in place of i. */
static long long brute_test_move(config const *cf, long long i, double const c[3],
                                 double const q[6]) {
  double *cc = g_memdup2(cf->c, sizeof(double) * 3 * cf->n);
  double *qq = g_memdup2(cf->q, sizeof(double) * 6 * cf->n);
  memcpy(cc + 3 * i, c, 3 * sizeof(double));
  memcpy(qq + 6 * i, q, 6 * sizeof(double));
  long long found = -1;
  for (long long j = 0; j < cf->n && found < 0; j++) {
    if (j == i) continue;
    long long const pair[2] = {i < j ? i : j, i < j ? j : i};
    int ov = -9;
    int st = pw85_scene_overlap(cf->n, cc, qq, cf->periodic ? cf->box : NULL, 1, pair, &ov, NULL,
                                1);
    g_assert_cmpint(st, ==, PW85_OK);
    if (ov == 1) found = j;
  }
  g_free(cc);
  g_free(qq);
  return found;
}

static void test_move_brute_force(void) {
  double const aspects[] = {0.1, 1, 10, 0};
  for (int a = 0; a < 4; a++)
    for (int periodic = 0; periodic <= 1; periodic++) {
      config cf;
      double const rmax = aspects[a] > 1 ? aspects[a] : (aspects[a] > 0 ? 1.0 : 1.5);
      make_config(&cf, 200, aspects[a], aspects[a] == 1 ? 15 : 9, periodic, periodic, 77 + a);
      pw85_configuration *conf = NULL;
      g_assert_cmpint(pw85_configuration_create(cf.n, cf.c, cf.q, periodic ? cf.box : NULL, &conf,
                                                NULL),
                      ==, PW85_OK);
      GRand *rng = g_rand_new_with_seed(5 + a);
      int hits = 0; /* trials that overlap something */
      for (int t = 0; t < 300; t++) {
        long long const i = g_rand_int_range(rng, 0, cf.n);
        double c[3], q[6], rad[3], ax[9];
        for (int d = 0; d < 3; d++)
          c[d] = cf.c[3 * i + d] + g_rand_double_range(rng, -0.6, 0.6) * rmax;
        if (t % 3 == 0)
          for (int d = 0; d < 3; d++) c[d] += 2 * cf.box[d] * periodic; /* out of the box */
        random_radii(rng, 0.3, 1.0, rad);
        if (aspects[a] > 0) {
          rad[0] = rad[1] = 1.0;
          rad[2] = aspects[a];
        }
        random_axes(rng, ax);
        make_q(rad, ax, q);
        long long j = -7;
        g_assert_cmpint(pw85_configuration_test_move(conf, i, c, q, &j), ==, PW85_OK);
        long long const expect = brute_test_move(&cf, i, c, q);
        if (j != expect) g_error("trial %d of particle %lld: %lld, brute force %lld", t, i, j, expect);
        hits += j >= 0;
        /* Accept every other trial that overlaps nothing (and some that
         * do): the configuration follows, checked below against brute
         * force. */
        if (t % 2 == 0) {
          g_assert_cmpint(pw85_configuration_move(conf, i, c, q), ==, PW85_OK);
          memcpy(cf.c + 3 * i, c, sizeof c);
          memcpy(cf.q + 6 * i, q, sizeof q);
        }
      }
      if (g_test_verbose()) g_printerr("aspect %g periodic %d: %d of 300 trials overlap\n", aspects[a], periodic, hits);
      g_assert_cmpint(hits, >, 10);
      g_assert_cmpint(hits, <, 290);
      /* After the moves: the pairs of the moved configuration. */
      long long *bi, *bj;
      double *bm;
      long long const m = brute_pairs(&cf, 1.0, &bi, &bj, &bm);
      long long *ci = g_new(long long, m + 1), *cj = g_new(long long, m + 1), count = -1;
      g_assert_cmpint(pw85_configuration_pairs(conf, 1.0, 2, m, ci, cj, NULL, &count, NULL), ==,
                      PW85_OK);
      g_assert_cmpint(count, ==, m);
      for (long long k = 0; k < m; k++) {
        g_assert_cmpint(ci[k], ==, bi[k]);
        g_assert_cmpint(cj[k], ==, bj[k]);
      }
      g_free(ci);
      g_free(cj);
      g_free(bi);
      g_free(bj);
      g_free(bm);
      g_rand_free(rng);
      pw85_configuration_destroy(conf);
      config_free(&cf);
    }
}

/* |r|^2 of the nearest image of r = c_j - c_i (periodic: the lattice
 * vectors a1 = (Lx, 0, 0), a2 = (xy Ly, Ly, 0), a3 = (xz Lz, yz Lz, Lz);
 * the fractional coordinates rounded, then the 5^3 images around them),
 * in long double. */
static long double nearest_distance2(config const *cf, double const ci[3], double const cj[3]) {
  long double r[3] = {(long double)cj[0] - ci[0], (long double)cj[1] - ci[1],
                      (long double)cj[2] - ci[2]};
  if (!cf->periodic) return r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
  double const *b = cf->box;
  long double const a[3][3] = {{b[0], 0, 0},
                               {(long double)b[3] * b[1], b[1], 0},
                               {(long double)b[4] * b[2], (long double)b[5] * b[2], b[2]}};
  long double f[3];
  f[2] = r[2] / a[2][2];
  f[1] = (r[1] - f[2] * a[2][1]) / a[1][1];
  f[0] = (r[0] - f[1] * a[1][0] - f[2] * a[2][0]) / a[0][0];
  long double best = INFINITY;
  for (int u = -2; u <= 2; u++)
    for (int v = -2; v <= 2; v++)
      for (int w = -2; w <= 2; w++) {
        long double const n[3] = {roundl(f[0]) + u, roundl(f[1]) + v, roundl(f[2]) + w};
        long double x2 = 0;
        for (int d = 0; d < 3; d++) {
          long double const x = r[d] - n[0] * a[0][d] - n[1] * a[1][d] - n[2] * a[2][d];
          x2 += x * x;
        }
        if (x2 < best) best = x2;
      }
  return best;
}

/* pw85_configuration_neighbours against the nearest image in long double:
 * every j closer than distance (1 - 1e-9) listed, none farther than
 * distance (1 + 1e-9), ascending; open, periodic and tilted, before and
 * after moves (particles leaving their cells), the count query. */
static void test_neighbours_brute_force(void) {
  for (int variant = 0; variant < 3; variant++) {
    config cf;
    int const periodic = variant > 0, tilted = variant == 2;
    make_config(&cf, 300, variant == 1 ? 3 : 0, 8, periodic, tilted, 91 + variant);
    pw85_configuration *conf = NULL;
    g_assert_cmpint(pw85_configuration_create(cf.n, cf.c, cf.q, periodic ? cf.box : NULL, &conf,
                                              NULL),
                    ==, PW85_OK);
    double const lmin = fmin(cf.box[0], fmin(cf.box[1], cf.box[2]));
    double const distances[] = {0.0, 0.05 * lmin, 0.2 * lmin, 0.37 * lmin, 0.5 * lmin * (1 - 2e-9)};
    GRand *rng = g_rand_new_with_seed(400 + variant);
    long long *j = g_new(long long, cf.n);
    long long listed = 0;
    for (int t = 0; t < 200; t++) {
      long long const i = g_rand_int_range(rng, 0, cf.n);
      if (t % 2 == 1) { /* move particle i (out of the box one time in four) */
        double c[3];
        for (int d = 0; d < 3; d++)
          c[d] = cf.c[3 * i + d] + g_rand_double_range(rng, -0.3, 0.3) * lmin +
                 (t % 4 == 1 ? 3 * cf.box[d] * periodic : 0);
        g_assert_cmpint(pw85_configuration_move(conf, i, c, cf.q + 6 * i), ==, PW85_OK);
        memcpy(cf.c + 3 * i, c, sizeof c);
      }
      double const distance = distances[t % G_N_ELEMENTS(distances)];
      long long count = -1;
      g_assert_cmpint(pw85_configuration_neighbours(conf, i, distance, 0, NULL, &count), ==,
                      count == 0 ? PW85_OK : PW85_ERR_CAPACITY);
      long long const first_count = count;
      g_assert_cmpint(pw85_configuration_neighbours(conf, i, distance, cf.n, j, &count), ==,
                      PW85_OK);
      g_assert_cmpint(count, ==, first_count);
      long long k = 0;
      for (long long b = 0; b < cf.n; b++) {
        if (b == i) continue;
        long double const r2 = nearest_distance2(&cf, cf.c + 3 * i, cf.c + 3 * b);
        long double const lo = (long double)distance * (1 - 1e-9L), hi = (long double)distance * (1 + 1e-9L);
        int const listed_b = k < count && j[k] == b;
        if (r2 < lo * lo && !listed_b)
          g_error("variant %d: particle %lld missing from the neighbours of %lld (%Lg < %g)", variant, b,
                  i, sqrtl(r2), distance);
        if (r2 >= hi * hi && listed_b)
          g_error("variant %d: particle %lld listed as a neighbour of %lld (%Lg >= %g)", variant, b, i,
                  sqrtl(r2), distance);
        k += listed_b;
      }
      g_assert_cmpint(k, ==, count); /* ascending, no duplicates, no i */
      listed += count;
    }
    g_assert_cmpint(listed, >, 1000);
    /* Bad input: nothing written. */
    long long count = -5;
    j[0] = -5;
    g_assert_cmpint(pw85_configuration_neighbours(conf, -1, 1.0, cf.n, j, &count), ==, PW85_ERR_INVALID_ARGUMENT);
    g_assert_cmpint(pw85_configuration_neighbours(conf, cf.n, 1.0, cf.n, j, &count), ==, PW85_ERR_INVALID_ARGUMENT);
    g_assert_cmpint(pw85_configuration_neighbours(conf, 0, -1.0, cf.n, j, &count), ==, PW85_ERR_INVALID_ARGUMENT);
    g_assert_cmpint(pw85_configuration_neighbours(conf, 0, NAN, cf.n, j, &count), ==, PW85_ERR_INVALID_ARGUMENT);
    g_assert_cmpint(pw85_configuration_neighbours(conf, 0, INFINITY, cf.n, j, &count), ==, PW85_ERR_INVALID_ARGUMENT);
    g_assert_cmpint(pw85_configuration_neighbours(conf, 0, 1.0, -1, j, &count), ==, PW85_ERR_INVALID_ARGUMENT);
    g_assert_cmpint(pw85_configuration_neighbours(conf, 0, 1.0, 1, NULL, &count), ==, PW85_ERR_INVALID_ARGUMENT);
    g_assert_cmpint(pw85_configuration_neighbours(conf, 0, 1.0, cf.n, j, NULL), ==, PW85_ERR_INVALID_ARGUMENT);
    g_assert_cmpint(pw85_configuration_neighbours(NULL, 0, 1.0, cf.n, j, &count), ==, PW85_ERR_INVALID_ARGUMENT);
    g_assert_cmpint(pw85_configuration_neighbours(conf, 0, 0.5 * lmin, cf.n, j, &count), ==,
                    periodic ? PW85_ERR_INVALID_ARGUMENT : PW85_OK);
    if (periodic) g_assert_cmpint(count, ==, -5);
    g_assert_cmpint(j[0], ==, periodic ? -5 : j[0]);
    g_free(j);
    g_rand_free(rng);
    pw85_configuration_destroy(conf);
    config_free(&cf);
  }
}

/* update: a new configuration replaces the old one (same n, then larger),
 * the pairs follow. */
static void test_update(void) {
  config a, b;
  make_config(&a, 150, 3, 5, 1, 1, 11);
  make_config(&b, 300, 0, 6, 1, 0, 12);
  pw85_configuration *conf = NULL;
  g_assert_cmpint(pw85_configuration_create(a.n, a.c, a.q, a.box, &conf, NULL), ==, PW85_OK);
  g_assert_cmpint(pw85_configuration_size(conf), ==, 150);
  config *both[2] = {&b, &a};
  for (int k = 0; k < 2; k++) {
    config const *cf = both[k];
    g_assert_cmpint(pw85_configuration_update(conf, cf->n, cf->c, cf->q, cf->box, NULL), ==,
                    PW85_OK);
    g_assert_cmpint(pw85_configuration_size(conf), ==, cf->n);
    long long *bi, *bj;
    double *bm;
    long long const m = brute_pairs(cf, 1.0, &bi, &bj, &bm);
    long long *ci = g_new(long long, m + 1), *cj = g_new(long long, m + 1), count = -1;
    g_assert_cmpint(pw85_configuration_pairs(conf, 1.0, 1, m, ci, cj, NULL, &count, NULL), ==,
                    PW85_OK);
    g_assert_cmpint(count, ==, m);
    g_assert_true(memcmp(ci, bi, sizeof(long long) * m) == 0);
    g_assert_true(memcmp(cj, bj, sizeof(long long) * m) == 0);
    g_free(ci);
    g_free(cj);
    g_free(bi);
    g_free(bj);
    g_free(bm);
  }
  pw85_configuration_destroy(conf);
  config_free(&a);
  config_free(&b);
}

/* The pairs of conf at s = 1 (count, then the arrays), as a checksum of
 * its state. */
static unsigned long long pairs_sum(pw85_configuration const *conf) {
  long long count = 0;
  pw85_configuration_pairs(conf, 1.0, 1, 0, NULL, NULL, NULL, &count, NULL);
  long long *i = g_new(long long, count + 1), *j = g_new(long long, count + 1);
  g_assert_cmpint(pw85_configuration_pairs(conf, 1.0, 1, count, i, j, NULL, &count, NULL), ==,
                  PW85_OK);
  unsigned long long sum = (unsigned long long)count;  /* wraps modulo 2^64 */
  for (long long k = 0; k < count; k++)
    sum = sum * 31u + (unsigned long long)i[k] * 1000003u + (unsigned long long)j[k];
  g_free(i);
  g_free(j);
  return sum;
}

static void test_bad_input(void) {
  config cf;
  make_config(&cf, 100, 3, 6, 1, 1, 21);
  pw85_configuration *conf = NULL, *none = NULL;
  long long bad = 0;
  /* n = 0: valid, no pairs. */
  g_assert_cmpint(pw85_configuration_create(0, NULL, NULL, cf.box, &conf, &bad), ==, PW85_OK);
  long long count = -1;
  g_assert_cmpint(pw85_configuration_pairs(conf, 1.0, 1, 0, NULL, NULL, NULL, &count, NULL), ==,
                  PW85_OK);
  g_assert_cmpint(count, ==, 0);
  pw85_configuration_destroy(conf);
  pw85_configuration_destroy(NULL);
  /* Each bad particle is named; *configuration unchanged. */
  double const nan = NAN;
  struct {
    int field, index;
    double value;
    int status;
  } const bads[] = {
      {0, 17, NAN, PW85_ERR_INVALID_ARGUMENT},      {0, 3, INFINITY, PW85_ERR_INVALID_ARGUMENT},
      {1, 42, NAN, PW85_ERR_INVALID_ARGUMENT},      {1, 9, -1.0, PW85_ERR_NOT_SPD},
      {0, 55, 1e30, PW85_ERR_RANGE},                {1, 61, 1e4, PW85_ERR_INVALID_ARGUMENT},
  };
  (void)nan;
  for (size_t k = 0; k < G_N_ELEMENTS(bads); k++) {
    double *c = g_memdup2(cf.c, sizeof(double) * 3 * cf.n);
    double *q = g_memdup2(cf.q, sizeof(double) * 6 * cf.n);
    int const i = bads[k].index;
    if (bads[k].field == 0) c[3 * i + 1] = bads[k].value;
    else if (bads[k].value == 1e4) {
      for (int t = 0; t < 6; t++) q[6 * i + t] = t == 0 || t == 3 || t == 5 ? 1e4 : 0.0;
    } else {
      q[6 * i + (bads[k].value < 0 ? 0 : 4)] = bads[k].value;
    }
    bad = -3;
    none = (pw85_configuration *)&bad; /* must stay as is */
    pw85_configuration *before = none;
    g_assert_cmpint(pw85_configuration_create(cf.n, c, q, cf.box, &none, &bad), ==,
                    bads[k].status);
    g_assert_true(none == before);
    g_assert_cmpint(bad, ==, i);
    g_free(c);
    g_free(q);
  }
  /* Invalid boxes. */
  double const boxes[][6] = {{0, 1, 1, 0, 0, 0}, {1, NAN, 1, 0, 0, 0}, {1, 1, 1, INFINITY, 0, 0}};
  for (int k = 0; k < 3; k++)
    g_assert_cmpint(pw85_configuration_create(cf.n, cf.c, cf.q, boxes[k], &conf, &bad), ==,
                    PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_configuration_create(-1, cf.c, cf.q, NULL, &conf, &bad), ==,
                  PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_configuration_create(cf.n, NULL, cf.q, NULL, &conf, &bad), ==,
                  PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_configuration_create(cf.n, cf.c, cf.q, NULL, NULL, &bad), ==,
                  PW85_ERR_INVALID_ARGUMENT);

  g_assert_cmpint(pw85_configuration_create(cf.n, cf.c, cf.q, cf.box, &conf, &bad), ==, PW85_OK);
  unsigned long long const sum0 = pairs_sum(conf);
  /* Capacity: nothing written but the count. */
  long long total = 0;
  g_assert_cmpint(pw85_configuration_pairs(conf, 1.2, 1, 0, NULL, NULL, NULL, &total, NULL), ==,
                  PW85_ERR_CAPACITY);
  g_assert_cmpint(total, >, 1);
  long long si[4] = {-9, -9, -9, -9}, sj[4] = {-9, -9, -9, -9};
  double sm[4] = {-9, -9, -9, -9};
  count = -1;
  g_assert_cmpint(pw85_configuration_pairs(conf, 1.2, 1, total - 1 < 4 ? total - 1 : 4, si, sj,
                                           sm, &count, NULL),
                  ==, PW85_ERR_CAPACITY);
  g_assert_cmpint(count, ==, total);
  for (int k = 0; k < 4; k++) g_assert_true(si[k] == -9 && sj[k] == -9 && sm[k] == -9);
  /* Bad s, nthreads, capacity; a box too small for s. */
  double const bad_s[] = {0.99, NAN, INFINITY, -1};
  for (int k = 0; k < 4; k++)
    g_assert_cmpint(pw85_configuration_pairs(conf, bad_s[k], 1, 0, NULL, NULL, NULL, &count, NULL),
                    ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_configuration_pairs(conf, 1.0, -1, 0, NULL, NULL, NULL, &count, NULL), ==,
                  PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_configuration_pairs(conf, 1.0, 1, -1, NULL, NULL, NULL, &count, NULL), ==,
                  PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_configuration_pairs(conf, 1.0, 1, 0, NULL, NULL, NULL, NULL, NULL), ==,
                  PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_configuration_pairs(NULL, 1.0, 1, 0, NULL, NULL, NULL, &count, NULL), ==,
                  PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_configuration_pairs(conf, 2.0, 1, 0, NULL, NULL, NULL, &count, NULL), ==,
                  PW85_ERR_INVALID_ARGUMENT); /* 2 x 2 rb > 6 rb x 0.9 / 2 */
  /* Moves: index out of range, bad trials; nothing changes. */
  double c[3] = {0.5, 0.5, 0.5}, q[6] = {1, 0, 0, 1, 0, 1};
  long long j = -5;
  long long const bad_i[] = {-1, cf.n, (long long)1 << 62};
  for (int k = 0; k < 3; k++) {
    g_assert_cmpint(pw85_configuration_test_move(conf, bad_i[k], c, q, &j), ==,
                    PW85_ERR_INVALID_ARGUMENT);
    g_assert_cmpint(pw85_configuration_move(conf, bad_i[k], c, q), ==, PW85_ERR_INVALID_ARGUMENT);
  }
  g_assert_cmpint(j, ==, -5);
  double const qbad[][6] = {{1, 0, 0, 1, 0, -1}, {1, 2, 0, 1, 0, 1}, {1, 0, 0, NAN, 0, 1},
                            {100, 0, 0, 1, 0, 1}};
  int const qstatus[] = {PW85_ERR_NOT_SPD, PW85_ERR_NOT_SPD, PW85_ERR_INVALID_ARGUMENT,
                         PW85_ERR_INVALID_ARGUMENT};
  for (int k = 0; k < 4; k++) {
    g_assert_cmpint(pw85_configuration_test_move(conf, 4, c, qbad[k], &j), ==, qstatus[k]);
    g_assert_cmpint(pw85_configuration_move(conf, 4, c, qbad[k]), ==, qstatus[k]);
  }
  double const cbad[][3] = {{NAN, 0, 0}, {0, INFINITY, 0}, {0, 0, 1e30}};
  int const cstatus[] = {PW85_ERR_INVALID_ARGUMENT, PW85_ERR_INVALID_ARGUMENT, PW85_ERR_RANGE};
  for (int k = 0; k < 3; k++) {
    g_assert_cmpint(pw85_configuration_test_move(conf, 4, cbad[k], q, &j), ==, cstatus[k]);
    g_assert_cmpint(pw85_configuration_move(conf, 4, cbad[k], q), ==, cstatus[k]);
  }
  g_assert_cmpint(j, ==, -5);
  g_assert_cmpint(pw85_configuration_test_move(NULL, 4, c, q, &j), ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_configuration_test_move(conf, 4, NULL, q, &j), ==,
                  PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_configuration_test_move(conf, 4, c, q, NULL), ==,
                  PW85_ERR_INVALID_ARGUMENT);
  /* A failed update leaves the configuration as it was. */
  double *c2 = g_memdup2(cf.c, sizeof(double) * 3 * cf.n);
  c2[3 * 70] = NAN;
  g_assert_cmpint(pw85_configuration_update(conf, cf.n, c2, cf.q, cf.box, &bad), ==,
                  PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(bad, ==, 70);
  g_free(c2);
  g_assert_cmpint(pw85_configuration_size(conf), ==, cf.n);
  g_assert_cmpuint(pairs_sum(conf), ==, sum0);
  /* Centres far out of the box (2^19 box lengths) are wrapped: the same
   * pairs as the brute force of pw85_scene_overlap. */
  double *c3 = g_memdup2(cf.c, sizeof(double) * 3 * cf.n);
  for (int i = 0; i < cf.n; i += 3) c3[3 * i + 2] += 524288.0 * cf.box[2];
  config far = cf;
  far.c = c3;
  check_pairs(&far, 1.0);
  g_free(c3);
  pw85_configuration_destroy(conf);
  config_free(&cf);
  g_assert_cmpstr(pw85_strerror(PW85_ERR_CAPACITY), ==, "output array too small");
  g_assert_cmpstr(pw85_strerror(PW85_ERR_NO_MEMORY), ==, "memory allocation failed");
}

/* Whether the overlapping pair (ellipsoids 0 and 1 of centres, q) is found
 * by pw85_configuration_pairs and by a trial move of ellipsoid 1 onto
 * itself; messages what was returned where it is not (case k). */
static int overlap_found(double const centres[6], double const q[12], int k) {
  pw85_configuration *cf = NULL;
  g_assert_cmpint(pw85_configuration_create(2, centres, q, NULL, &cf, NULL), ==, PW85_OK);
  long long i[1], j[1], count = -1, moved = -7;
  int const s = pw85_configuration_pairs(cf, 1.0, 1, 1, i, j, NULL, &count, NULL);
  int const sm = pw85_configuration_test_move(cf, 1, centres + 3, q + 6, &moved);
  pw85_configuration_destroy(cf);
  if (s == PW85_OK && count == 1 && sm == PW85_OK && moved == 0) return 1;
  g_test_message("k = %d: pairs status %d count %lld, test_move status %d j %lld", k, s, count,
                 sm, moved);
  return 0;
}

/* Two ellipsoids whose matrices are scaled by 2^k, k = 0 ... 1000, centres
 * at distance sqrt(5): each centre lies inside the other ellipsoid (the
 * smallest eigenvalue of each base matrix is above 0.3 by Gershgorin, so
 * r^T Q^-1 r <= 5 / (0.3 2^k) < 1 from k = 5), so the pair overlaps at
 * every scale from k = 5 on. The broad phase's plane test meets overflowing
 * support values (inf - inf) from k = 341: it must decline there, not
 * separate the pair. Checked: the pair is found by pw85_configuration_pairs
 * and by a trial move, as pw85_overlap finds it. */
static void test_pairs_huge_matrices(void) {
  double const base1[6] = {2.0, -1.0, 0.5, 2.0, -0.7, 2.0};
  double const base2[6] = {1.5, 0.6, -0.4, 2.5, 0.3, 1.0};
  int missed = 0;
  for (int k = 5; k <= 1000; k++) {
    double q[12], centres[6] = {0.0, 0.0, 0.0, 1.0, 2.0, 0.0};
    for (int t = 0; t < 6; t++) {
      q[t] = ldexp(base1[t], k);
      q[6 + t] = ldexp(base2[t], k);
    }
    g_assert_cmpint(pw85_overlap(centres + 3, q, q + 6), ==, 1);
    missed += !overlap_found(centres, q, k);
  }
  g_assert_cmpint(missed, ==, 0);
}

/* Discs of unit radius in the x-z plane, thickness sqrt(t) in y (q =
 * {1, -t, 0, t, 0, 1}), centres 1 apart along x: they overlap for every t.
 * For t subnormal, the plane normal of (S1) is subnormal and each support
 * value n^T Q n underflows to 0: the bound must count the underflow, not
 * separate the pair. The first case is the input the fuzz target found
 * (tests/fuzz/corpus/configuration-subnormal-discs). Checked: the pair is
 * found by pw85_configuration_pairs and by a trial move, as pw85_overlap
 * finds it. */
static void test_pairs_subnormal_entries(void) {
  int missed = 0;
  for (int k = 0; k <= 1074; k++) {
    double const t1 = k == 0 ? 0x0.0000000004022p-1022 : ldexp(1.0, -k);
    double const t2 = k == 0 ? 0x0.0000000003ffp-1022 : t1 * 0.75;
    double const q[12] = {1.0, -t1, 0.0, t1, 0.0, 1.0, 1.0, -t2, 0.0, t2, 0.0, 1.0};
    double const centres[6] = {0.0, 0.0, 0.0, 1.0, 0.0, 0.0};
    g_assert_cmpint(pw85_overlap(centres + 3, q, q + 6), ==, 1);
    missed += !overlap_found(centres, q, k);
  }
  g_assert_cmpint(missed, ==, 0);
}

/* The box bound: in a 10-cube (half width 5), spheres of radii 2.6 and 1
 * fit together (3.6) but the first meets its own images (5.2): refused,
 * bad = 0. Radii 2.4 and 1 are accepted, and moving either particle where
 * it is, or growing the second to the first's size, passes the same bound;
 * growing it beyond 2.5 does not. Then the input the fuzz target found
 * (tests/fuzz/corpus/configuration-move-in-place-tilted-box): a box of huge
 * tilts, where the sum of the two spheres fits but the first meets its
 * own images: refused at creation, as by the bound of a move. Then the
 * scale s of pw85_configuration_pairs at the range of double (the input
 * tests/fuzz/corpus/configuration-pairs-scale-overflow). */
static void test_box_bound(void) {
  double const box[6] = {10, 10, 10, 0, 0, 0};
  double const c[6] = {0, 0, 0, 5, 5, 5};
  double q[12] = {2.6 * 2.6, 0, 0, 2.6 * 2.6, 0, 2.6 * 2.6, 1, 0, 0, 1, 0, 1};
  pw85_configuration *cf = NULL;
  long long bad = -7, j = -7;
  g_assert_cmpint(pw85_configuration_create(2, c, q, box, &cf, &bad), ==,
                  PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(bad, ==, 0);
  g_assert_null(cf);
  q[0] = q[3] = q[5] = 2.4 * 2.4;
  g_assert_cmpint(pw85_configuration_create(2, c, q, box, &cf, &bad), ==, PW85_OK);
  for (int i = 0; i < 2; i++) {
    g_assert_cmpint(pw85_configuration_test_move(cf, i, c + 3 * i, q + 6 * i, &j), ==, PW85_OK);
    g_assert_cmpint(pw85_configuration_move(cf, i, c + 3 * i, q + 6 * i), ==, PW85_OK);
  }
  g_assert_cmpint(pw85_configuration_move(cf, 1, c + 3, q), ==, PW85_OK);
  double const big[6] = {2.51 * 2.51, 0, 0, 2.51 * 2.51, 0, 2.51 * 2.51};
  g_assert_cmpint(pw85_configuration_move(cf, 1, c + 3, big), ==, PW85_ERR_INVALID_ARGUMENT);
  pw85_configuration_destroy(cf);

  double const tbox[6] = {8, 9, 10, 0x1.05247p+54, 0x1.c55414645445fp+325, 0x1.f525f4c53535fp+245};
  double const tc[6] = {0, 0, 0, 0x1.79016c803a351p+4, 0, 0};
  double const tq[12] = {0x1.331ffc328ad2bp-1008, 0x1.02p-1019, 0, 0x1.80000000215p+1, 1,
                         0x1.14f5ep+0, 0x1.0d2163ad6fc9dp-1, -0x1.ffee7b92c3abep-2,
                         0x1.ab97a49b1e1dap-259, 0x1.667a40640f828p+0, -0x1.f313e61191986p-2,
                         0x1.fdbd1fd1348bp+0};
  cf = NULL;
  g_assert_cmpint(pw85_configuration_create(2, tc, tq, tbox, &cf, &bad), ==,
                  PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(bad, ==, 0);
  g_assert_null(cf);

  /* Pairs within s: s^2 q must stay finite (2^600 with unit spheres, open
   * scene): a call error, nothing written; 2^500 is taken. */
  double const uq[12] = {1, 0, 0, 1, 0, 1, 1, 0, 0, 1, 0, 1};
  double const uc[6] = {0, 0, 0, 3, 0, 0};
  g_assert_cmpint(pw85_configuration_create(2, uc, uq, NULL, &cf, &bad), ==, PW85_OK);
  long long i[1] = {-7}, jj[1] = {-7}, count = -7;
  g_assert_cmpint(pw85_configuration_pairs(cf, 0x1p600, 1, 1, i, jj, NULL, &count, NULL), ==,
                  PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(count, ==, -7);
  g_assert_cmpint(i[0], ==, -7);
  g_assert_cmpint(pw85_configuration_pairs(cf, 0x1p500, 1, 1, i, jj, NULL, &count, NULL), ==,
                  PW85_OK);
  g_assert_cmpint(count, ==, 1);
  pw85_configuration_destroy(cf);
}

int main(int argc, char **argv) {
  g_test_init(&argc, &argv, NULL);
  g_test_add_func("/pw85_configuration_pairs/open", test_pairs_open);
  g_test_add_func("/pw85_configuration_pairs/periodic", test_pairs_periodic);
  g_test_add_func("/pw85_configuration_pairs/triclinic", test_pairs_triclinic);
  g_test_add_func("/pw85_configuration_pairs/dense", test_pairs_dense);
  g_test_add_func("/pw85_configuration_pairs/large_box", test_pairs_large);
  g_test_add_func("/pw85_configuration_pairs/huge_matrices", test_pairs_huge_matrices);
  g_test_add_func("/pw85_configuration_pairs/subnormal_entries", test_pairs_subnormal_entries);
  g_test_add_func("/pw85_configuration_test_move/brute_force", test_move_brute_force);
  g_test_add_func("/pw85_configuration_update/brute_force", test_update);
  g_test_add_func("/pw85_configuration_neighbours/brute_force", test_neighbours_brute_force);
  g_test_add_func("/pw85_configuration/bad_input", test_bad_input);
  g_test_add_func("/pw85_configuration/box_bound", test_box_bound);
  return g_test_run();
}
