/* pw85_mc: a scene of hard spheroids, the demonstration of the scene API of
 * libpw85 (README "A scene", docs/usage.md "pw85_mc").
 *
 *   pw85_mc [--n N] [--sweeps S] [--equil E] [--blocks B] [--seed SEED]
 *           [--aspect C_OVER_A] [--phi PACKING_FRACTION] [--target ACC]
 *           [--threads T] [--xyz FILE] [--gsd FILE] [--progress] [--help]
 *
 * N spheroids (equatorial semi-axis a = 0.5, polar semi-axis c = aspect * a:
 * prolate for aspect > 1, oblate for aspect < 1) in a periodic cubic box
 * whose side gives the packing fraction phi, held by the configuration object
 * of libpw85 (pw85_configuration_*, docs/scene.md: its cell grid, minimum
 * image and exact overlap verdicts). Start: the spheroids are aligned with z on a lattice whose
 * spacing is >= 2c along z and >= 2a along x and y (non-overlapping). Monte
 * Carlo: sweeps of N trial moves (random particle, then with probability
 * 1/2 a translation uniform in [-dr, dr]^3, otherwise a rotation of its
 * axis u to (u + dtheta g) / |u + dtheta g|, g a standard normal vector;
 * both proposals are symmetric); pw85_configuration_test_move rejects a move
 * that overlaps another particle, pw85_configuration_move commits the
 * others. E equilibration sweeps scale dr and
 * dtheta after each sweep by a power of the ratio of their acceptance to
 * the target (below); the S production sweeps keep them fixed
 * (detailed balance) and are reported in B blocks: acceptance and the
 * nematic order parameter S2 averaged over the sweeps of the block. S2 is
 * the largest eigenvalue of the order tensor Qt = (1/N) sum (3 u u^T - I) / 2
 * of the symmetry axes u (the long axis of prolate, the short axis of oblate
 * spheroids; 0 <= S2 <= 1 since tr Qt = 0; about 1/sqrt(N) for N isotropic
 * axes). --xyz and --gsd write the configuration at production sweep 0
 * (after equilibration) and at the end of each block (extended XYZ for
 * OVITO, GSD for HOOMD-blue; S2 of the configuration in both, in the GSD
 * file as log/pw85/S2). Prints the number of trial moves per second of the
 * production loop, then checks that no pair overlaps
 * (pw85_configuration_pairs, s = 1) and the smallest mu^2 of the neighbour
 * pairs within s = 1.2 or 1 (pw85_configuration_pairs, then
 * pw85_scene_contact_function on those pairs).
 * Exit status: 0 when no pair overlaps, 1 when one does, 2 on bad usage, a
 * library error or a file that cannot be written. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <pw85.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "demo_args.h"
#include "demo_rng.h"
#include "gsd_write.h"

typedef struct {
  int n;
  double L;   /* box side */
  double a, c;
  double *x;  /* centres, 3n, in [0, L) */
  double *u;  /* unit axes, 3n */
  double *q;  /* quadratic forms, 6n */
  pw85_configuration *conf; /* the same particles in the periodic box */
} scene_t;

static double wrap(double v, double L) {
  v = fmod(v, L);
  if (v < 0) v += L;
  if (v >= L) v -= L;
  return v;
}

static void free_scene(scene_t *s) {
  pw85_configuration_destroy(s->conf);
  free(s->x), free(s->u), free(s->q);
}

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void usage(FILE *out) {
  fprintf(out,
          "usage: pw85_mc [--n N] [--sweeps S] [--equil E] [--blocks B] [--seed SEED]\n"
          "               [--aspect C_OVER_A] [--phi PHI] [--target ACC] [--threads T]\n"
          "               [--xyz FILE] [--gsd FILE] [--progress] [--help]\n"
          "Monte Carlo of N hard spheroids (semi-axes 0.5, 0.5, 0.5 * C_OVER_A) at packing\n"
          "fraction PHI: E sweeps tuning the steps to acceptance ACC (default 0.3), then\n"
          "S sweeps with fixed steps reported in B blocks (acceptance, nematic order S2);\n"
          "--xyz/--gsd write the configuration at sweep 0 (after equilibration) and after\n"
          "each block (extended XYZ, GSD; S2 in both, in GSD as log/pw85/S2);\n"
          "--progress reports on stderr (default when stderr is a terminal).\n"
          "Defaults: --n 1000 --sweeps 20 --equil 10 --blocks 4 --seed 1 --aspect 3\n"
          "--phi 0.2 --threads 0 (all). Exit status: 0 no overlapping pair at the end,\n"
          "1 an overlapping pair, 2 bad usage, library or file error.\n");
}

/* Largest eigenvalue of the symmetric matrix m = (xx, xy, xz, yy, yz, zz)
 * by the trigonometric solution of its characteristic cubic (O. K. Smith,
 * Commun. ACM 4(4), 168, 1961): t = tr m / 3, p = sqrt(tr (m - t I)^2 / 6),
 * B = (m - t I) / p, lambda_max = t + 2 p cos(acos(det B / 2) / 3). */
static double largest_eigenvalue(const double m[6]) {
  double const t = (m[0] + m[3] + m[5]) / 3.0;
  double const d0 = m[0] - t, d1 = m[3] - t, d2 = m[5] - t;
  double const p2 = d0 * d0 + d1 * d1 + d2 * d2 + 2.0 * (m[1] * m[1] + m[2] * m[2] + m[4] * m[4]);
  if (!(p2 > 0.0)) return t;
  double const p = sqrt(p2 / 6.0);
  double const b0 = d0 / p, b1 = m[1] / p, b2 = m[2] / p, b3 = d1 / p, b4 = m[4] / p,
               b5 = d2 / p;
  double r = 0.5 * (b0 * (b3 * b5 - b4 * b4) - b1 * (b1 * b5 - b4 * b2) + b2 * (b1 * b4 - b3 * b2));
  r = r < -1.0 ? -1.0 : (r > 1.0 ? 1.0 : r);
  return t + 2.0 * p * cos(acos(r) / 3.0);
}

/* Nematic order parameter S2: largest eigenvalue of
 * Qt = (1/N) sum_i (3 u_i u_i^T - I) / 2 over the symmetry axes u_i. */
static double order_parameter(const scene_t *s) {
  double m[6] = {0, 0, 0, 0, 0, 0};
  for (int i = 0; i < s->n; ++i) {
    const double *u = s->u + 3 * i;
    m[0] += u[0] * u[0], m[1] += u[0] * u[1], m[2] += u[0] * u[2];
    m[3] += u[1] * u[1], m[4] += u[1] * u[2], m[5] += u[2] * u[2];
  }
  for (int k = 0; k < 6; ++k) m[k] *= 1.5 / s->n;
  m[0] -= 0.5, m[3] -= 0.5, m[5] -= 0.5;
  return largest_eigenvalue(m);
}

/* Unit quaternion (w, x, y, z) of the rotation taking z onto the axis u,
 * the orientation of a spheroid whose body frame has semi-axes (a, a, c)
 * along x, y, z: shortest arc q = (1 + z.u, z x u) / |(1 + z.u, z x u)|,
 * with u replaced by -u (the same spheroid) when u_z < 0, so 1 + z.u >= 1. */
static void axis_quaternion(const double *u, double q[4]) {
  double const sgn = u[2] < 0.0 ? -1.0 : 1.0;
  double const w = 1.0 + sgn * u[2], x = -sgn * u[1], y = sgn * u[0];
  double const norm = sqrt(w * w + x * x + y * y);
  q[0] = w / norm, q[1] = x / norm, q[2] = y / norm, q[3] = 0.0;
}

/* Extended XYZ frame: positions in [0, L)^3, OVITO's orientation order
 * (x, y, z, w) and aspherical_shape (semi-axes along body x, y, z). */
static int write_xyz(FILE *f, const scene_t *s, long long sweep, double s2) {
  fprintf(f,
          "%d\nLattice=\"%.17g 0 0 0 %.17g 0 0 0 %.17g\" pbc=\"T T T\" "
          "Properties=species:S:1:pos:R:3:orientation:R:4:aspherical_shape:R:3 "
          "sweep=%lld S2=%.17g\n",
          s->n, s->L, s->L, s->L, sweep, s2);
  for (int i = 0; i < s->n; ++i) {
    double q[4];
    axis_quaternion(s->u + 3 * i, q);
    const double *x = s->x + 3 * i;
    fprintf(f, "E %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", x[0], x[1],
            x[2], q[1], q[2], q[3], q[0], s->a, s->a, s->c);
  }
  return (fflush(f) != 0 || ferror(f)) ? -1 : 0;
}

static const char *const gsd_logged[] = {"log/pw85/S2"};

/* GSD frame (HOOMD schema, gsd_write_frame): positions, the quaternions
 * (w, x, y, z) of axis_quaternion, the semi-axes (a, a, c) and S2 logged
 * as log/pw85/S2. quat: 4n doubles, buf: 4n floats of scratch. */
static int write_gsd(gsd_writer *w, const scene_t *s, uint64_t sweep, double s2, double *quat,
                     float *buf) {
  for (int i = 0; i < s->n; ++i) axis_quaternion(s->u + 3 * i, quat + 4 * i);
  gsd_frame const frame = {sweep, (uint32_t)s->n, s->L, {s->a, s->a, s->c}, s->x, quat, 1,
                           gsd_logged, &s2};
  return gsd_write_frame(w, &frame, buf);
}

/* One trial move of particle i: a rotation (rotate = 1) or a translation.
 * Returns 1 when accepted, 0 when rejected, -1 on a library error. tests
 * counts the trials. */
static int trial_move(scene_t *s, rng_t *g, int i, int rotate, double dr, double dtheta,
                      long long *tests) {
  double xn[3], un[3], qn[6];
  memcpy(xn, s->x + 3 * i, sizeof xn);
  memcpy(un, s->u + 3 * i, sizeof un);
  memcpy(qn, s->q + 6 * i, sizeof qn);
  if (rotate) {
    double norm = 0.0;
    for (int d = 0; d < 3; ++d) {
      un[d] += dtheta * rng_normal(g);
      norm += un[d] * un[d];
    }
    norm = sqrt(norm);
    if (!(norm > 0.0)) return 0;
    for (int d = 0; d < 3; ++d) un[d] /= norm;
    pw85_spheroid(s->a, s->c, un, qn);
  } else {
    for (int d = 0; d < 3; ++d) xn[d] = wrap(xn[d] + dr * (2.0 * rng_uniform(g) - 1.0), s->L);
  }
  long long j = -1;
  int st = pw85_configuration_test_move(s->conf, i, xn, qn, &j);
  ++*tests;
  if (st == PW85_OK && j >= 0) return 0;
  if (st == PW85_OK) st = pw85_configuration_move(s->conf, i, xn, qn);
  if (st != PW85_OK) {
    fprintf(stderr, "pw85_mc: particle %d: %s\n", i, pw85_strerror(st));
    return -1;
  }
  memcpy(s->x + 3 * i, xn, sizeof xn);
  memcpy(s->u + 3 * i, un, sizeof un);
  memcpy(s->q + 6 * i, qn, sizeof qn);
  return 1;
}

/* Progress on stderr, at most once per second: sweeps done, acceptance of
 * the last sweep, sweeps per second, time left at that rate. */
typedef struct {
  int on, tty, shown;
  double t0, last;
} progress_t;

static void progress(progress_t *p, long long done, long long total, double acceptance) {
  if (!p->on) return;
  double const t = now();
  if (t - p->last < 1.0 && done < total) return;
  p->last = t;
  double const rate = done / (t - p->t0 > 0.0 ? t - p->t0 : 1e-9);
  fprintf(stderr, "%spw85_mc: sweep %lld/%lld, acceptance %.3f, %.3g sweeps/s, %.0f s left%s",
          p->tty ? "\r" : "", done, total, acceptance, rate,
          rate > 0.0 ? (double)(total - done) / rate : 0.0, p->tty ? "   " : "\n");
  p->shown = 1;
}

int main(int argc, char **argv) {
  long n = 1000, sweeps = 20, equil = 10, blocks = 4, threads = 0;
  uint64_t seed = 1;
  double aspect = 3.0, phi = 0.2, target = 0.3;
  const char *xyz_path = NULL, *gsd_path = NULL;
  progress_t prog = {0, isatty(STDERR_FILENO), 0, 0.0, 0.0};
  prog.on = prog.tty;
  for (int i = 1; i < argc; ++i) {
    const char *o = argv[i], *arg = i + 1 < argc ? argv[i + 1] : NULL;
    int bad = 0, takes = 1;
    if (!strcmp(o, "--help") || !strcmp(o, "-h")) {
      usage(stdout);
      return 0;
    } else if (!strcmp(o, "--progress")) {
      prog.on = 1, takes = 0;
    } else if (!arg) {
      bad = 1;
    } else if (!strcmp(o, "--n")) {
      bad = parse_long(arg, 2, 100000000, &n);
    } else if (!strcmp(o, "--sweeps")) {
      bad = parse_long(arg, 0, 1000000000, &sweeps);
    } else if (!strcmp(o, "--equil")) {
      bad = parse_long(arg, 0, 1000000000, &equil);
    } else if (!strcmp(o, "--blocks")) {
      bad = parse_long(arg, 1, 1000000, &blocks);
    } else if (!strcmp(o, "--threads")) {
      bad = parse_long(arg, 0, 4096, &threads);
    } else if (!strcmp(o, "--seed")) {
      bad = parse_seed(arg, &seed);
    } else if (!strcmp(o, "--aspect")) {
      bad = parse_double(arg, 1e-3, 1e3, &aspect);
    } else if (!strcmp(o, "--phi")) {
      bad = parse_double(arg, 1e-6, 0.5, &phi) || phi == 0.5;
    } else if (!strcmp(o, "--target")) {
      bad = parse_double(arg, 0.01, 0.99, &target);
    } else if (!strcmp(o, "--xyz")) {
      xyz_path = arg;
    } else if (!strcmp(o, "--gsd")) {
      gsd_path = arg;
    } else {
      fprintf(stderr, "pw85_mc: unknown option '%s'\n", o);
      usage(stderr);
      return 2;
    }
    if (bad) {
      fprintf(stderr, "pw85_mc: bad or missing value for %s\n", o);
      usage(stderr);
      return 2;
    }
    i += takes;
  }
  if (blocks > sweeps) blocks = sweeps;
  scene_t s;
  memset(&s, 0, sizeof s);
  s.n = (int)n;
  s.a = 0.5;
  s.c = aspect * s.a;
  double const volume = 4.0 / 3.0 * 3.141592653589793 * s.a * s.a * s.c;
  s.L = cbrt(n * volume / phi);
  /* Lattice: nz layers of spacing >= 2c along z, nxy x nxy sites per layer
   * of spacing >= 2a. */
  double const nzd = floor(s.L / (2.0 * s.c));
  int const nz = nzd > n ? (int)n : (int)nzd;
  int const nxy = (int)ceil(sqrt((double)n / nz));
  if (s.L / nxy < 2.0 * s.a) {
    fprintf(stderr, "pw85_mc: packing fraction too high for the initial lattice\n");
    return 2;
  }
  /* Output files first: nothing to free when they cannot be created. */
  FILE *xyz = NULL;
  gsd_writer gsd;
  int have_gsd = 0, file_error = 0;
  if (xyz_path && !(xyz = fopen(xyz_path, "w"))) {
    fprintf(stderr, "pw85_mc: cannot write '%s': %s\n", xyz_path, strerror(errno));
    return 2;
  }
  if (gsd_path) {
    char app[64];
    snprintf(app, sizeof app, "pw85_mc %s", pw85_version());
    if (gsd_open(&gsd, gsd_path, app, gsd_logged, 1) != 0) {
      fprintf(stderr, "pw85_mc: cannot write '%s': %s\n", gsd_path, strerror(errno));
      if (xyz) fclose(xyz);
      return 2;
    }
    have_gsd = 1;
  }

  s.x = malloc(3 * (size_t)n * sizeof(double));
  s.u = malloc(3 * (size_t)n * sizeof(double));
  s.q = malloc(6 * (size_t)n * sizeof(double));
  float *fbuf = malloc(4 * (size_t)n * sizeof(float));
  double *qbuf = malloc(4 * (size_t)n * sizeof(double));
  if (!s.x || !s.u || !s.q || !fbuf || !qbuf) return 2;
  for (int i = 0; i < n; ++i) {
    int const iz = i / (nxy * nxy), iy = (i / nxy) % nxy, ix = i % nxy;
    s.x[3 * i] = (ix + 0.5) * s.L / nxy;
    s.x[3 * i + 1] = (iy + 0.5) * s.L / nxy;
    s.x[3 * i + 2] = (iz + 0.5) * s.L / nz;
    s.u[3 * i] = 0.0, s.u[3 * i + 1] = 0.0, s.u[3 * i + 2] = 1.0;
    pw85_spheroid(s.a, s.c, s.u + 3 * i, s.q + 6 * i);
  }
  double const box[6] = {s.L, s.L, s.L, 0.0, 0.0, 0.0};
  /* The box must hold every orientation: the library's bound on two
   * bounding spheres (radius at most sqrt(trace Q) = sqrt(2 a^2 + c^2),
   * whatever the rotation) against half the side. */
  if (2.0 * sqrt(2.0 * s.a * s.a + s.c * s.c) > 0.5 * s.L * (1.0 - 1e-9)) {
    fprintf(stderr, "pw85_mc: box %g too small for the spheroids (side < 4 sqrt(2 a^2 + c^2)); "
            "increase --n\n", s.L);
    free_scene(&s);
    free(fbuf), free(qbuf);
    if (xyz) fclose(xyz);
    if (have_gsd) gsd_close(&gsd);
    return 2;
  }
  long long bad_particle = -1;
  int const created = pw85_configuration_create(n, s.x, s.q, box, &s.conf, &bad_particle);
  if (created != PW85_OK) {
    fprintf(stderr, "pw85_mc: the box (side %g) cannot hold the particles: %s (particle %lld); "
            "increase --n\n", s.L, pw85_strerror(created), bad_particle);
    free_scene(&s);
    free(fbuf), free(qbuf);
    if (xyz) fclose(xyz);
    if (have_gsd) gsd_close(&gsd);
    return 2;
  }
  printf("pw85_mc: %ld %s spheroids (a = %g, c = %g), packing fraction %g, box %.4g, "
         "seed %llu\n",
         n, s.c > s.a ? "prolate" : (s.c < s.a ? "oblate" : "spherical"), s.a, s.c, phi, s.L,
         (unsigned long long)seed);

  rng_t g = {seed};
  double dr = 0.4 * s.a, dtheta = 0.4;
  double const dr_max = 0.5 * s.L, dtheta_max = 10.0;
  long long tests = 0, accepted = 0, moves = 0;
  long long const total = equil + sweeps;
  double acc_last[2] = {0.0, 0.0}, t_prod = 0.0;
  long long blk_att[2] = {0, 0}, blk_acc[2] = {0, 0}, blk_first = 1;
  double blk_s2 = 0.0;
  int blk = 0, lib_error = 0;
  if (equil == 0)
    printf("equilibration: none; translation dr = %.4g, rotation dtheta = %.4g\n", dr, dtheta);
  prog.t0 = prog.last = now();
  for (long long sw = 0; sw <= total && !lib_error; ++sw) {
    if (sw == equil) { /* the frame of sweep 0: the start of production */
      double const s2 = order_parameter(&s);
      if (xyz && write_xyz(xyz, &s, 0, s2) != 0) file_error = 1;
      if (have_gsd && write_gsd(&gsd, &s, 0, s2, qbuf, fbuf) != 0) file_error = 1;
    }
    if (sw == total) break;
    int const production = sw >= equil;
    long long att[2] = {0, 0}, acc[2] = {0, 0}, sweep_tests = 0;
    double const t0 = now();
    for (long k = 0; k < n; ++k) {
      int const i = (int)(rng_next(&g) % (uint64_t)n);
      int const rotate = rng_uniform(&g) < 0.5;
      int const r = trial_move(&s, &g, i, rotate, dr, dtheta, &sweep_tests);
      if (r < 0) {
        lib_error = 1;
        break;
      }
      att[rotate]++, acc[rotate] += r;
    }
    for (int k = 0; k < 2; ++k) acc_last[k] = att[k] ? (double)acc[k] / (double)att[k] : 0.0;
    if (!production) {
      /* Step tuning: step *= (acceptance / target)^gain, factor clamped to
       * [0.5, 2], gain 1 for the first 4 sweeps then 4 / (sweep + 1) (a
       * Robbins-Monro gain, which averages out the noise of the
       * acceptance of one sweep). */
      double f[2];
      double const gain = sw < 4 ? 1.0 : 4.0 / (double)(sw + 1);
      for (int k = 0; k < 2; ++k) {
        f[k] = pow(acc_last[k] > 0.0 ? acc_last[k] / target : 0.0, gain);
        f[k] = f[k] < 0.5 ? 0.5 : (f[k] > 2.0 ? 2.0 : f[k]);
      }
      dr = fmin(dr * f[0], dr_max);
      dtheta = fmin(dtheta * f[1], dtheta_max);
      if (sw + 1 == equil)
        printf("equilibration: %ld sweeps, steps tuned to acceptance %g: translation dr = %.4g "
               "(last sweep %.3f), rotation dtheta = %.4g (last sweep %.3f)\n",
               equil, target, dr, acc_last[0], dtheta, acc_last[1]);
    } else {
      t_prod += now() - t0;
      tests += sweep_tests;
      moves += n;
      accepted += acc[0] + acc[1];
      for (int k = 0; k < 2; ++k) blk_att[k] += att[k], blk_acc[k] += acc[k];
      blk_s2 += order_parameter(&s);
      long long const done = sw - equil + 1;
      if (done * blocks >= (long long)(blk + 1) * sweeps) {
        long long const nsw = done - blk_first + 1;
        double const s2 = order_parameter(&s);
        printf("block %d: sweeps %lld-%lld, acceptance translation %.3f rotation %.3f, "
               "S2 = %.4f (mean over the block; last sweep %.4f)\n",
               blk + 1, blk_first, done,
               blk_att[0] ? (double)blk_acc[0] / (double)blk_att[0] : 0.0,
               blk_att[1] ? (double)blk_acc[1] / (double)blk_att[1] : 0.0, blk_s2 / (double)nsw,
               s2);
        if (xyz && write_xyz(xyz, &s, done, s2) != 0) file_error = 1;
        if (have_gsd && write_gsd(&gsd, &s, (uint64_t)done, s2, qbuf, fbuf) != 0) file_error = 1;
        blk++, blk_first = done + 1, blk_s2 = 0.0;
        blk_att[0] = blk_att[1] = blk_acc[0] = blk_acc[1] = 0;
      }
    }
    progress(&prog, sw + 1, total, 0.5 * (acc_last[0] + acc_last[1]));
  }
  if (prog.shown && prog.tty) fputc('\n', stderr);
  if (lib_error) {
    if (xyz) fclose(xyz);
    if (have_gsd) gsd_close(&gsd);
    free_scene(&s);
    free(fbuf), free(qbuf);
    return 2;
  }
  if (xyz && fclose(xyz) != 0) file_error = 1;
  if (have_gsd && gsd_close(&gsd) != 0) file_error = 1;
  if (file_error) fprintf(stderr, "pw85_mc: writing the configuration failed\n");
  printf("Monte Carlo: %ld sweeps, %lld moves, acceptance rate %.3f, %lld trial moves tested in "
         "%.3f s (%.3g trials/s)\n",
         sweeps, moves, moves ? (double)accepted / (double)moves : 0.0, tests, t_prod,
         t_prod > 0 ? (double)tests / t_prod : 0.0);

  /* Final check: the overlapping pairs (s = 1), then the neighbour pairs
   * within s = 1.2 (1 where the box cannot hold 1.2) and their mu^2
   * through pw85_scene_contact_function. */
  long long nov = 0, m = 0;
  int const st2 = pw85_configuration_pairs(s.conf, 1.0, (int)threads, 0, NULL, NULL, NULL, &nov,
                                           NULL);
  /* The shell s = 1.2, or s = 1 where the box cannot hold it. */
  double shell = 1.2;
  int st = pw85_configuration_pairs(s.conf, shell, (int)threads, 0, NULL, NULL, NULL, &m, NULL);
  if (st == PW85_ERR_INVALID_ARGUMENT) {
    shell = 1.0;
    st = pw85_configuration_pairs(s.conf, shell, (int)threads, 0, NULL, NULL, NULL, &m, NULL);
  }
  long long *ij = malloc(3 * (size_t)(m ? m : 1) * sizeof(long long));
  long long *pairs = malloc(2 * (size_t)(m ? m : 1) * sizeof(long long));
  pw85_result *res = malloc((size_t)(m ? m : 1) * sizeof(pw85_result));
  if (!ij || !pairs || !res) return 2;
  if (st == PW85_ERR_CAPACITY)
    st = pw85_configuration_pairs(s.conf, shell, (int)threads, m, ij, ij + m, NULL, &m, NULL);
  for (long long k = 0; k < m; ++k) pairs[2 * k] = ij[k], pairs[2 * k + 1] = ij[m + k];
  if (st == PW85_OK && m > 0)
    st = pw85_scene_contact_function(n, s.x, s.q, box, m, pairs, PW85_METHOD_DEFAULT, res, NULL,
                                     (int)threads);
  long long bad = 0;
  double mu2_min = INFINITY;
  for (long long k = 0; st == PW85_OK && k < m; ++k) {
    if (res[k].mu2 < mu2_min) mu2_min = res[k].mu2;
    if (!(res[k].mu2 >= 1.0)) ++bad;
  }
  printf("check: %lld neighbour pairs (mu^2 < %.4g), min mu^2 = %.6f "
         "(pw85_scene_contact_function: %s), %lld pairs with mu^2 < 1, %lld overlapping "
         "(pw85_configuration_pairs: %s)\n",
         m, shell * shell, mu2_min, pw85_strerror(st), bad, nov,
         pw85_strerror(st2 == PW85_ERR_CAPACITY ? PW85_OK : st2));
  int const rc = (st != PW85_OK || (st2 != PW85_OK && st2 != PW85_ERR_CAPACITY) || file_error)
                     ? 2
                     : (bad || nov) ? 1 : 0;
  printf("%s\n", rc == 0 ? "OK: no overlapping pair" : "FAILED");

  free_scene(&s);
  free(fbuf), free(qbuf);
  free(ij), free(pairs), free(res);
  return rc;
}
