/* Cost of the configuration object (docs/scene.md, docs/performance.md,
 * section "Scene"). NOT a test: built by meson, never run by `meson test`.
 *
 *   bench_scene [--n N1,N2,...] [--reps R] [--sweeps S] [--seed X] OUT.csv
 *
 * Configurations (no overlapping pair): spheroids of semi-axes (1, 1,
 * aspect) aligned on a face-centred cubic lattice stretched by the aspect
 * ratio along z, at volume fraction phi in an orthorhombic periodic box,
 * then S Monte Carlo sweeps (pw85_configuration_test_move and _move: random
 * displacement and rotation of each particle in turn, accepted when it
 * overlaps nothing), so that orientations and positions are disordered.
 *
 * Rows (CSV: name, N, aspect, phi, value, min, max, unit):
 *  - query_s1: pw85_configuration_pairs(s = 1, one thread), ns per
 *    particle (median, min, max over R runs, thread CPU time); the
 *    configurations are valid, so no pair is found;
 *  - overlap_pairs: pw85_overlap_pairs (one thread) over the pairs whose
 *    bounding spheres intersect (the broad phase's first test; r12, q1, q2
 *    copied to per-pair arrays beforehand, untimed), ns per particle, and
 *    ratio_query_to_overlap_pairs (per run, median, min, max);
 *  - threads2: ratio of the wall-clock times of s = 1 queries on one and on
 *    two threads (runs alternated);
 *  - candidates: per particle, pairs whose bounding spheres intersect at
 *    s = 1.2, pairs given to the exact predicate, pairs within s = 1.2,
 *    and ratio_examined_to_within;
 *  - test_move: trials per second (thread CPU time) of
 *    pw85_configuration_test_move over one sweep of random trials.
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <pw85.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double thread_seconds(void) {
  struct timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

static double wall_seconds(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

/* xorshift64* */
static unsigned long long rng_state = 88172645463325252ULL;
static double uniform(void) {
  rng_state ^= rng_state >> 12;
  rng_state ^= rng_state << 25;
  rng_state ^= rng_state >> 27;
  return (double)((rng_state * 2685821657736338717ULL) >> 11) * 0x1p-53;
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static void stats(double *v, int n, double out[3]) {
  qsort(v, n, sizeof *v, cmp_double);
  out[0] = v[n / 2];
  out[1] = v[0];
  out[2] = v[n - 1];
}

typedef struct {
  long long n;
  double *c, *q, *quat;
  double radii[3];
  double box[6];
} config;

static void normalise(double *v, int n) {
  double s = 0;
  for (int k = 0; k < n; k++) s += v[k] * v[k];
  s = sqrt(s);
  for (int k = 0; k < n; k++) v[k] /= s;
}

/* The lattice configuration (m^3 cubic cells of 4 particles), then sweeps. */
static void make_config(config *cf, long long nwant, double aspect, double phi, int sweeps) {
  long long m = (long long)llround(cbrt(nwant / 4.0));
  if (m < 2) m = 2;
  long long const n = 4 * m * m * m;
  cf->n = n;
  cf->c = malloc(sizeof(double) * 3 * n);
  cf->q = malloc(sizeof(double) * 6 * n);
  cf->quat = malloc(sizeof(double) * 4 * n);
  cf->radii[0] = cf->radii[1] = 1.0;
  cf->radii[2] = aspect;
  /* d^3 aspect = 4 (4/3 pi aspect) / phi */
  double const d = cbrt(16.0 * 3.14159265358979323846 / (3.0 * phi));
  double const box[6] = {m * d, m * d, m * d * aspect, 0, 0, 0};
  memcpy(cf->box, box, sizeof box);
  double const basis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
  long long k = 0;
  for (long long x = 0; x < m; x++)
    for (long long y = 0; y < m; y++)
      for (long long z = 0; z < m; z++)
        for (int b = 0; b < 4; b++, k++) {
          cf->c[3 * k + 0] = (x + basis[b][0] + 0.25) * d;
          cf->c[3 * k + 1] = (y + basis[b][1] + 0.25) * d;
          cf->c[3 * k + 2] = (z + basis[b][2] + 0.25) * d * aspect;
          double const quat[4] = {1, 0, 0, 0};
          memcpy(cf->quat + 4 * k, quat, sizeof quat);
          pw85_ellipsoid_quat(cf->radii, quat, cf->q + 6 * k);
        }
  if (sweeps == 0) return;
  pw85_configuration *conf;
  if (pw85_configuration_create(n, cf->c, cf->q, cf->box, &conf, NULL) != PW85_OK) {
    fprintf(stderr, "create failed\n");
    exit(1);
  }
  double const step = 0.3 * (d - 2.0 * (aspect < 1 ? aspect : 1)) + 0.05;
  for (int s = 0; s < sweeps; s++)
    for (long long i = 0; i < n; i++) {
      double c[3], quat[4], q[6];
      for (int t = 0; t < 3; t++) c[t] = cf->c[3 * i + t] + step * (uniform() - 0.5);
      for (int t = 0; t < 4; t++) quat[t] = cf->quat[4 * i + t] + 0.3 * (uniform() - 0.5);
      normalise(quat, 4);
      pw85_ellipsoid_quat(cf->radii, quat, q);
      long long j = 0;
      if (pw85_configuration_test_move(conf, i, c, q, &j) == PW85_OK && j < 0 &&
          pw85_configuration_move(conf, i, c, q) == PW85_OK) {
        memcpy(cf->c + 3 * i, c, sizeof c);
        memcpy(cf->q + 6 * i, q, sizeof q);
        memcpy(cf->quat + 4 * i, quat, sizeof quat);
      }
    }
  pw85_configuration_destroy(conf);
}

static void free_config(config *cf) {
  free(cf->c);
  free(cf->q);
  free(cf->quat);
}

/* The pairs whose bounding spheres (radius: the largest semi-axis, known
 * here) intersect, by a plain cell list, as per-pair arrays (r12 the minimum
 * image in the orthorhombic box). Returns their count. */
static double bound_radius(double const q[6]) {
  double radii[3], rot[9];
  pw85_ellipsoid_axes(q, radii, rot, NULL);
  return fmax(radii[0], fmax(radii[1], radii[2]));
}

/* Cell coordinates of particle i in a grid of nc cells per axis. */
static void cell_of(config const *cf, long long i, long long const nc[3], long long x[3]) {
  for (int d = 0; d < 3; d++) {
    double f = cf->c[3 * i + d] / cf->box[d];
    f -= floor(f);
    x[d] = (long long)(f * nc[d]);
    if (x[d] >= nc[d]) x[d] = nc[d] - 1;
  }
}

static long long sphere_pairs(config const *cf, double **r12, double **q1, double **q2) {
  long long const n = cf->n;
  double rmax = 0;
  for (long long i = 0; i < n; i++) rmax = fmax(rmax, bound_radius(cf->q + 6 * i));
  long long nc[3];
  for (int d = 0; d < 3; d++) {
    nc[d] = (long long)floor(cf->box[d] / (2 * rmax));
    if (nc[d] < 3) nc[d] = 1;
  }
  long long const cells = nc[0] * nc[1] * nc[2];
  long long *head = malloc(sizeof(long long) * cells), *next = malloc(sizeof(long long) * n);
  for (long long c = 0; c < cells; c++) head[c] = -1;
  for (long long i = 0; i < n; i++) {
    long long x[3];
    cell_of(cf, i, nc, x);
    long long const c = x[0] + nc[0] * (x[1] + nc[1] * x[2]);
    next[i] = head[c];
    head[c] = i;
  }
  long long cap = 16 * n, m = 0;
  *r12 = malloc(sizeof(double) * 3 * cap);
  *q1 = malloc(sizeof(double) * 6 * cap);
  *q2 = malloc(sizeof(double) * 6 * cap);
  for (long long i = 0; i < n; i++) {
    long long x[3];
    cell_of(cf, i, nc, x);
    double const ri = bound_radius(cf->q + 6 * i);
    for (long long dz = nc[2] == 1 ? 0 : -1; dz <= (nc[2] == 1 ? 0 : 1); dz++)
      for (long long dy = nc[1] == 1 ? 0 : -1; dy <= (nc[1] == 1 ? 0 : 1); dy++)
        for (long long dx = nc[0] == 1 ? 0 : -1; dx <= (nc[0] == 1 ? 0 : 1); dx++) {
          long long const c = (x[0] + dx + nc[0]) % nc[0] +
                              nc[0] * ((x[1] + dy + nc[1]) % nc[1] + nc[1] * ((x[2] + dz + nc[2]) % nc[2]));
          for (long long j = head[c]; j >= 0; j = next[j]) {
            if (j <= i) continue;
            double r[3];
            for (int d = 0; d < 3; d++) {
              r[d] = cf->c[3 * j + d] - cf->c[3 * i + d];
              r[d] -= cf->box[d] * nearbyint(r[d] / cf->box[d]);
            }
            double const rs = ri + bound_radius(cf->q + 6 * j);
            if (r[0] * r[0] + r[1] * r[1] + r[2] * r[2] >= rs * rs) continue;
            if (m == cap) {
              cap *= 2;
              *r12 = realloc(*r12, sizeof(double) * 3 * cap);
              *q1 = realloc(*q1, sizeof(double) * 6 * cap);
              *q2 = realloc(*q2, sizeof(double) * 6 * cap);
            }
            memcpy(*r12 + 3 * m, r, sizeof r);
            memcpy(*q1 + 6 * m, cf->q + 6 * i, 6 * sizeof(double));
            memcpy(*q2 + 6 * m, cf->q + 6 * j, 6 * sizeof(double));
            m++;
          }
        }
  }
  free(head);
  free(next);
  return m;
}

static FILE *csv;

static void row(char const *name, long long n, double aspect, double phi, double const v[3],
                char const *unit) {
  printf("%-30s N=%-8lld aspect=%-4g phi=%-5g %12.4g  [%.4g, %.4g] %s\n", name, n, aspect, phi,
         v[0], v[1], v[2], unit);
  fprintf(csv, "%s,%lld,%g,%g,%.6g,%.6g,%.6g,%s\n", name, n, aspect, phi, v[0], v[1], v[2], unit);
}

static long long count_pairs(pw85_configuration const *conf, double s, int threads,
                             long long ex[2]) {
  long long count = 0;
  int const st = pw85_configuration_pairs(conf, s, threads, 0, NULL, NULL, NULL, &count, ex);
  if (st != PW85_OK && st != PW85_ERR_CAPACITY) {
    fprintf(stderr, "pairs: %s\n", pw85_strerror(st));
    exit(1);
  }
  return count;
}

/* Speed rows for one configuration (aspect 3). */
static void speed(config const *cf, double phi, int reps) {
  pw85_configuration *conf;
  if (pw85_configuration_create(cf->n, cf->c, cf->q, cf->box, &conf, NULL) != PW85_OK) exit(1);
  long long const n = cf->n;
  long long ex[2];
  long long const overlapping = count_pairs(conf, 1.0, 1, ex);
  if (overlapping != 0) fprintf(stderr, "warning: %lld overlapping pairs\n", overlapping);
  double *r12, *q1, *q2;
  long long const m = sphere_pairs(cf, &r12, &q1, &q2);
  if (m != ex[0])
    fprintf(stderr, "warning: %lld sphere pairs, the configuration counts %lld\n", m, ex[0]);
  int *ov = malloc(sizeof(int) * (m + 1));
  double *tq = malloc(sizeof(double) * reps), *to = malloc(sizeof(double) * reps),
         *ratio = malloc(sizeof(double) * reps);
  for (int r = -1; r < reps; r++) {
    double t0 = thread_seconds();
    count_pairs(conf, 1.0, 1, NULL);
    double t1 = thread_seconds();
    pw85_overlap_pairs(m, r12, q1, q2, ov, NULL, 1);
    double t2 = thread_seconds();
    if (r < 0) continue;
    tq[r] = (t1 - t0) / n * 1e9;
    to[r] = (t2 - t1) / n * 1e9;
    ratio[r] = (t1 - t0) / (t2 - t1);
  }
  double v[3];
  stats(tq, reps, v);
  row("query_s1", n, cf->radii[2], phi, v, "ns/particle");
  stats(to, reps, v);
  row("overlap_pairs", n, cf->radii[2], phi, v, "ns/particle");
  stats(ratio, reps, v);
  row("ratio_query_to_overlap_pairs", n, cf->radii[2], phi, v, "ratio");
  double const sp[3] = {(double)m / n, (double)ex[0] / n, (double)ex[1] / n};
  double const a[3] = {sp[0], sp[0], sp[0]}, b[3] = {sp[2], sp[2], sp[2]};
  row("sphere_pairs_s1", n, cf->radii[2], phi, a, "per particle");
  row("examined_s1", n, cf->radii[2], phi, b, "per particle");
  /* Two threads against one, wall clock, alternated. */
  for (int r = -1; r < reps; r++) {
    double t0 = wall_seconds();
    count_pairs(conf, 1.0, 1, NULL);
    double t1 = wall_seconds();
    count_pairs(conf, 1.0, 2, NULL);
    double t2 = wall_seconds();
    if (r >= 0) ratio[r] = (t1 - t0) / (t2 - t1);
  }
  stats(ratio, reps, v);
  row("threads2_speedup", n, cf->radii[2], phi, v, "ratio");
  free(ov);
  free(r12);
  free(q1);
  free(q2);
  free(tq);
  free(to);
  free(ratio);
  pw85_configuration_destroy(conf);
}

/* Candidate rows at s = 1.2. */
static void candidates(config const *cf, double phi) {
  pw85_configuration *conf;
  if (pw85_configuration_create(cf->n, cf->c, cf->q, cf->box, &conf, NULL) != PW85_OK) exit(1);
  long long ex[2];
  long long const within = count_pairs(conf, 1.2, 1, ex);
  double const n = (double)cf->n;
  double const a[3] = {ex[0] / n, ex[0] / n, ex[0] / n}, b[3] = {ex[1] / n, ex[1] / n, ex[1] / n},
               w[3] = {within / n, within / n, within / n},
               r[3] = {(double)ex[1] / within, (double)ex[1] / within, (double)ex[1] / within};
  row("sphere_pairs_s1.2", cf->n, cf->radii[2], phi, a, "per particle");
  row("examined_s1.2", cf->n, cf->radii[2], phi, b, "per particle");
  row("within_s1.2", cf->n, cf->radii[2], phi, w, "per particle");
  row("ratio_examined_to_within", cf->n, cf->radii[2], phi, r, "ratio");
  pw85_configuration_destroy(conf);
}

/* test_move: one sweep of random trials (the make_config moves). */
static void trials(config const *cf, double phi) {
  pw85_configuration *conf;
  if (pw85_configuration_create(cf->n, cf->c, cf->q, cf->box, &conf, NULL) != PW85_OK) exit(1);
  long long const n = cf->n;
  double *tc = malloc(sizeof(double) * 3 * n), *tqm = malloc(sizeof(double) * 6 * n);
  for (long long i = 0; i < n; i++) {
    double quat[4];
    for (int t = 0; t < 3; t++) tc[3 * i + t] = cf->c[3 * i + t] + 0.2 * (uniform() - 0.5);
    for (int t = 0; t < 4; t++) quat[t] = cf->quat[4 * i + t] + 0.2 * (uniform() - 0.5);
    normalise(quat, 4);
    pw85_ellipsoid_quat(cf->radii, quat, tqm + 6 * i);
  }
  double t0 = thread_seconds();
  long long hits = 0;
  for (long long i = 0; i < n; i++) {
    long long j;
    pw85_configuration_test_move(conf, i, tc + 3 * i, tqm + 6 * i, &j);
    hits += j >= 0;
  }
  double const t = thread_seconds() - t0;
  double const v[3] = {n / t, n / t, n / t}, h[3] = {(double)hits / n, (double)hits / n, (double)hits / n};
  row("test_move_rate", n, cf->radii[2], phi, v, "trials/s");
  row("test_move_rejected", n, cf->radii[2], phi, h, "fraction");
  free(tc);
  free(tqm);
  pw85_configuration_destroy(conf);
}

int main(int argc, char **argv) {
  long long sizes[8] = {10000, 1000000};
  int nsizes = 2, reps = 5, sweeps = 3;
  char const *out = NULL;
  for (int k = 1; k < argc; k++) {
    if (!strcmp(argv[k], "--n") && k + 1 < argc) {
      nsizes = 0;
      for (char *p = strtok(argv[++k], ","); p && nsizes < 8; p = strtok(NULL, ","))
        sizes[nsizes++] = atoll(p);
    } else if (!strcmp(argv[k], "--reps") && k + 1 < argc) {
      reps = atoi(argv[++k]);
    } else if (!strcmp(argv[k], "--sweeps") && k + 1 < argc) {
      sweeps = atoi(argv[++k]);
    } else if (!strcmp(argv[k], "--seed") && k + 1 < argc) {
      rng_state = strtoull(argv[++k], NULL, 10) * 2654435761ULL + 1;
    } else if (argv[k][0] == '-') {
      out = NULL;  // an unknown option, or one missing its value
      break;
    } else {
      out = argv[k];
    }
  }
  if (out == NULL || reps < 1) {
    fprintf(stderr, "usage: bench_scene [--n N1,N2] [--reps R] [--sweeps S] [--seed X] OUT.csv\n");
    return 2;
  }
  csv = fopen(out, "w");
  if (!csv) return 2;
  fprintf(csv, "name,n,aspect,phi,median,min,max,unit\n");
  for (int k = 0; k < nsizes; k++) {
    config cf;
    make_config(&cf, sizes[k], 3.0, 0.45, sweeps);
    speed(&cf, 0.45, reps);
    if (k == 0) trials(&cf, 0.45);
    free_config(&cf);
  }
  double const aspects[2] = {10.0, 0.1};
  for (int a = 0; a < 2; a++) {
    config cf;
    make_config(&cf, sizes[0], aspects[a], 0.25, sweeps);
    candidates(&cf, 0.25);
    free_config(&cf);
  }
  fclose(csv);
  return 0;
}
