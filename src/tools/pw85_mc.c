/* pw85_mc: a scene of hard spheroids, the demonstration of the scene API of
 * libpw85 (README "A scene").
 *
 *   pw85_mc [--n N] [--sweeps S] [--seed SEED] [--aspect C_OVER_A]
 *           [--phi PACKING_FRACTION] [--threads T]
 *
 * N prolate spheroids (equatorial semi-axis a = 0.5, polar semi-axis
 * c = aspect * a) in a periodic cubic box whose side gives the packing
 * fraction phi. Minimum-image convention; cell lists with cells of side
 * >= 2c (so that only the 27 neighbouring cells can hold an overlapping
 * partner; at least 3 cells per side are required). Start: the spheroids
 * are aligned with z on a lattice whose spacing is >= 2c along z and >= 2a
 * along x and y (non-overlapping, checked). Monte Carlo: S sweeps of N
 * trial moves (random particle; translation uniform in [-dr, dr]^3 and a
 * random rotation of its axis); a move is rejected as soon as pw85_overlap
 * reports an overlap with a neighbour. Prints the number of overlap tests
 * per second of the Monte Carlo loop and the acceptance rate, then checks
 * with pw85_contact_function_batch over every neighbour pair that no pair
 * has mu^2 < 1 (and with pw85_overlap_batch that no pair overlaps).
 * Exit status: 0 when no pair overlaps, 1 when one does, 2 on bad usage or
 * a library error. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <pw85.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "demo_rng.h"

typedef struct {
  int n;
  double L;   /* box side */
  double a, c;
  int nc;     /* cells per side */
  double cell;
  double *x;  /* centres, 3n, in [0, L) */
  double *u;  /* unit axes, 3n */
  double *q;  /* quadratic forms, 6n */
  int *cell_of;
  int **members; /* members[cell][0..count[cell]-1] */
  int *count, *cap;
} scene_t;

static double wrap(double v, double L) {
  v = fmod(v, L);
  if (v < 0) v += L;
  if (v >= L) v -= L;
  return v;
}

static int cell_index(const scene_t *s, const double *p) {
  int idx[3];
  for (int d = 0; d < 3; ++d) {
    idx[d] = (int)(p[d] / s->cell);
    if (idx[d] >= s->nc) idx[d] = s->nc - 1;
    if (idx[d] < 0) idx[d] = 0;
  }
  return (idx[0] * s->nc + idx[1]) * s->nc + idx[2];
}

static void cell_add(scene_t *s, int c, int i) {
  if (s->count[c] == s->cap[c]) {
    s->cap[c] = s->cap[c] ? 2 * s->cap[c] : 8;
    s->members[c] = realloc(s->members[c], (size_t)s->cap[c] * sizeof(int));
    if (!s->members[c]) abort();
  }
  s->members[c][s->count[c]++] = i;
  s->cell_of[i] = c;
}

static void cell_remove(scene_t *s, int c, int i) {
  for (int k = 0; k < s->count[c]; ++k)
    if (s->members[c][k] == i) {
      s->members[c][k] = s->members[c][--s->count[c]];
      return;
    }
}

/* Minimum-image separation r = p_j - p_i. */
static void min_image(const scene_t *s, const double *pi, const double *pj, double r[3]) {
  for (int d = 0; d < 3; ++d) {
    double v = pj[d] - pi[d];
    v -= s->L * nearbyint(v / s->L);
    r[d] = v;
  }
}

/* Calls fn(j) for every particle j != i in the 27 cells around position p. */
#define FOR_NEIGHBOURS(s, p, i, j, BODY)                                      \
  do {                                                                        \
    int ci_[3];                                                               \
    int const c0_ = cell_index((s), (p));                                     \
    ci_[0] = c0_ / ((s)->nc * (s)->nc);                                       \
    ci_[1] = (c0_ / (s)->nc) % (s)->nc;                                       \
    ci_[2] = c0_ % (s)->nc;                                                   \
    for (int dx_ = -1; dx_ <= 1; ++dx_)                                       \
      for (int dy_ = -1; dy_ <= 1; ++dy_)                                     \
        for (int dz_ = -1; dz_ <= 1; ++dz_) {                                 \
          int const cx_ = (ci_[0] + dx_ + (s)->nc) % (s)->nc;                 \
          int const cy_ = (ci_[1] + dy_ + (s)->nc) % (s)->nc;                 \
          int const cz_ = (ci_[2] + dz_ + (s)->nc) % (s)->nc;                 \
          int const cc_ = (cx_ * (s)->nc + cy_) * (s)->nc + cz_;              \
          for (int k_ = 0; k_ < (s)->count[cc_]; ++k_) {                      \
            int const j = (s)->members[cc_][k_];                              \
            if (j == (i)) continue;                                           \
            BODY                                                              \
          }                                                                   \
        }                                                                     \
  } while (0)

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void usage(const char *prog) {
  fprintf(stderr,
          "usage: %s [--n N] [--sweeps S] [--seed SEED] [--aspect C_OVER_A] [--phi PHI] "
          "[--threads T]\n",
          prog);
}

int main(int argc, char **argv) {
  int n = 1000, sweeps = 20, threads = 0;
  unsigned long long seed = 1;
  double aspect = 3.0, phi = 0.2;
  for (int i = 1; i < argc; ++i) {
    if (i + 1 < argc && !strcmp(argv[i], "--n"))
      n = atoi(argv[++i]);
    else if (i + 1 < argc && !strcmp(argv[i], "--sweeps"))
      sweeps = atoi(argv[++i]);
    else if (i + 1 < argc && !strcmp(argv[i], "--seed"))
      seed = strtoull(argv[++i], NULL, 10);
    else if (i + 1 < argc && !strcmp(argv[i], "--aspect"))
      aspect = atof(argv[++i]);
    else if (i + 1 < argc && !strcmp(argv[i], "--phi"))
      phi = atof(argv[++i]);
    else if (i + 1 < argc && !strcmp(argv[i], "--threads"))
      threads = atoi(argv[++i]);
    else {
      usage(argv[0]);
      return 2;
    }
  }
  if (n < 2 || sweeps < 0 || threads < 0 || !(aspect >= 1.0) || !(phi > 0.0 && phi < 0.5)) {
    usage(argv[0]);
    return 2;
  }
  scene_t s;
  memset(&s, 0, sizeof s);
  s.n = n;
  s.a = 0.5;
  s.c = aspect * s.a;
  double const volume = 4.0 / 3.0 * 3.141592653589793 * s.a * s.a * s.c;
  s.L = cbrt(n * volume / phi);
  s.nc = (int)floor(s.L / (2.0 * s.c));
  if (s.nc < 3) {
    fprintf(stderr, "pw85_mc: box too small for cell lists (L = %g < 6c); increase --n\n", s.L);
    return 2;
  }
  s.cell = s.L / s.nc;
  /* Lattice: nz layers of spacing >= 2c along z, nxy x nxy sites per layer
   * of spacing >= 2a. */
  int const nz = (int)floor(s.L / (2.0 * s.c));
  int const nxy = (int)ceil(sqrt((double)n / nz));
  if (s.L / nxy < 2.0 * s.a) {
    fprintf(stderr, "pw85_mc: packing fraction too high for the initial lattice\n");
    return 2;
  }
  s.x = malloc(3 * (size_t)n * sizeof(double));
  s.u = malloc(3 * (size_t)n * sizeof(double));
  s.q = malloc(6 * (size_t)n * sizeof(double));
  s.cell_of = malloc((size_t)n * sizeof(int));
  int const ncells = s.nc * s.nc * s.nc;
  s.members = calloc((size_t)ncells, sizeof(int *));
  s.count = calloc((size_t)ncells, sizeof(int));
  s.cap = calloc((size_t)ncells, sizeof(int));
  if (!s.x || !s.u || !s.q || !s.cell_of || !s.members || !s.count || !s.cap) return 2;
  for (int i = 0; i < n; ++i) {
    int const iz = i / (nxy * nxy), iy = (i / nxy) % nxy, ix = i % nxy;
    s.x[3 * i] = (ix + 0.5) * s.L / nxy;
    s.x[3 * i + 1] = (iy + 0.5) * s.L / nxy;
    s.x[3 * i + 2] = (iz + 0.5) * s.L / nz;
    s.u[3 * i] = 0.0, s.u[3 * i + 1] = 0.0, s.u[3 * i + 2] = 1.0;
    pw85_spheroid(s.a, s.c, s.u + 3 * i, s.q + 6 * i);
    cell_add(&s, cell_index(&s, s.x + 3 * i), i);
  }
  printf("pw85_mc: %d prolate spheroids (a = %g, c = %g), packing fraction %g, box %.4g, "
         "%d^3 cells, seed %llu\n",
         n, s.a, s.c, phi, s.L, s.nc, seed);

  rng_t g = {seed};
  double const dr = 0.4 * s.a, dtheta = 0.4;
  long long tests = 0, accepted = 0, moves = (long long)sweeps * n;
  int lib_error = 0;
  double const t0 = now();
  for (long long mv = 0; mv < moves && !lib_error; ++mv) {
    int const i = (int)(rng_next(&g) % (uint64_t)n);
    double xn[3], un[3], qn[6];
    for (int d = 0; d < 3; ++d) xn[d] = wrap(s.x[3 * i + d] + dr * (2.0 * rng_uniform(&g) - 1.0), s.L);
    double norm = 0.0;
    for (int d = 0; d < 3; ++d) {
      un[d] = s.u[3 * i + d] + dtheta * rng_normal(&g);
      norm += un[d] * un[d];
    }
    norm = sqrt(norm);
    for (int d = 0; d < 3; ++d) un[d] /= norm;
    pw85_spheroid(s.a, s.c, un, qn);
    int overlap = 0;
    FOR_NEIGHBOURS(&s, xn, i, j, {
      if (!overlap && !lib_error) {
        double r[3];
        min_image(&s, xn, s.x + 3 * j, r);
        int const v = pw85_overlap(r, qn, s.q + 6 * j);
        ++tests;
        if (v < 0) {
          fprintf(stderr, "pw85_mc: pw85_overlap: %s\n", pw85_strerror(v));
          lib_error = 1;
        } else if (v == 1) {
          overlap = 1;
        }
      }
    });
    if (overlap || lib_error) continue;
    ++accepted;
    int const c_old = s.cell_of[i], c_new = cell_index(&s, xn);
    memcpy(s.x + 3 * i, xn, sizeof xn);
    memcpy(s.u + 3 * i, un, sizeof un);
    memcpy(s.q + 6 * i, qn, sizeof qn);
    if (c_new != c_old) {
      cell_remove(&s, c_old, i);
      cell_add(&s, c_new, i);
    }
  }
  double const t1 = now();
  if (lib_error) return 2;
  double const elapsed = t1 - t0;
  printf("Monte Carlo: %d sweeps, %lld moves, acceptance rate %.3f, %lld overlap tests in %.3f s "
         "(%.3g tests/s)\n",
         sweeps, moves, moves ? (double)accepted / (double)moves : 0.0, tests, elapsed,
         elapsed > 0 ? (double)tests / elapsed : 0.0);

  /* Final check over every neighbour pair (i < j). The batch functions take
   * r12 = centres[j] - centres[i]: the periodic image of j nearest to i is
   * stored as an extra "ellipsoid" n + k with the matrix of j. */
  long long m = 0, cap_pairs = 16 * (long long)n;
  long long *pairs = malloc(2 * (size_t)cap_pairs * sizeof(long long));
  double *img = malloc(3 * (size_t)cap_pairs * sizeof(double));
  if (!pairs || !img) return 2;
  for (int i = 0; i < n; ++i) {
    FOR_NEIGHBOURS(&s, s.x + 3 * i, i, j, {
      if (j > i) {
        if (m == cap_pairs) {
          cap_pairs *= 2;
          pairs = realloc(pairs, 2 * (size_t)cap_pairs * sizeof(long long));
          img = realloc(img, 3 * (size_t)cap_pairs * sizeof(double));
          if (!pairs || !img) abort();
        }
        double r[3];
        min_image(&s, s.x + 3 * i, s.x + 3 * j, r);
        for (int d = 0; d < 3; ++d) img[3 * m + d] = s.x[3 * i + d] + r[d];
        pairs[2 * m] = i;
        pairs[2 * m + 1] = j; /* replaced by n + m below */
        ++m;
      }
    });
  }
  long long const ntot = n + m;
  double *centres = malloc(3 * (size_t)ntot * sizeof(double));
  double *qall = malloc(6 * (size_t)ntot * sizeof(double));
  double *out = malloc(2 * (size_t)(m ? m : 1) * sizeof(double));
  int *ov = malloc((size_t)(m ? m : 1) * sizeof(int));
  int *status = malloc((size_t)(m ? m : 1) * sizeof(int));
  if (!centres || !qall || !out || !ov || !status) return 2;
  memcpy(centres, s.x, 3 * (size_t)n * sizeof(double));
  memcpy(qall, s.q, 6 * (size_t)n * sizeof(double));
  for (long long k = 0; k < m; ++k) {
    long long const j = pairs[2 * k + 1];
    memcpy(centres + 3 * (n + k), img + 3 * k, 3 * sizeof(double));
    memcpy(qall + 6 * (n + k), s.q + 6 * j, 6 * sizeof(double));
    pairs[2 * k + 1] = n + k;
  }
  int const st = pw85_contact_function_batch(ntot, centres, qall, m, pairs, out, status, threads);
  int const st2 = pw85_overlap_batch(ntot, centres, qall, m, pairs, ov, NULL, threads);
  long long bad = 0, nov = 0;
  double mu2_min = INFINITY;
  for (long long k = 0; k < m; ++k) {
    if (out[2 * k] < mu2_min) mu2_min = out[2 * k];
    if (!(out[2 * k] >= 1.0)) ++bad;
    if (ov[k] != 0) ++nov;
  }
  printf("check: %lld neighbour pairs, min mu^2 = %.6f (pw85_contact_function_batch: %s), "
         "%lld pairs with mu^2 < 1, %lld overlapping (pw85_overlap_batch: %s)\n",
         m, mu2_min, pw85_strerror(st), bad, nov, pw85_strerror(st2));
  int const rc = (st != PW85_OK || st2 != PW85_OK) ? 2 : (bad || nov) ? 1 : 0;
  printf("%s\n", rc == 0 ? "OK: no overlapping pair" : "FAILED");

  for (int c = 0; c < ncells; ++c) free(s.members[c]);
  free(s.members), free(s.count), free(s.cap), free(s.cell_of);
  free(s.x), free(s.u), free(s.q);
  free(pairs), free(img), free(centres), free(qall), free(out), free(ov), free(status);
  return rc;
}
