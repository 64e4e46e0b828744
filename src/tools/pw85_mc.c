/* pw85_mc: a scene of hard ellipsoids, the demonstration of the
 * configuration object of libpw85 (README "A scene", docs/usage.md
 * "pw85_mc").
 *
 *   pw85_mc [--n N] [--sweeps S] [--equil E] [--blocks B] [--seed SEED]
 *           [--aspect C_OVER_A | --axes A B C] [--phi PACKING_FRACTION]
 *           [--from FILE.gsd] [--frame K] [--target ACC] [--threads T]
 *           [--xyz FILE] [--gsd FILE] [--progress] [--help]
 *
 * N identical ellipsoids of semi-axes (A, B, C) along their body axes x,
 * y, z (--axes; --aspect: spheroids (0.5, 0.5, 0.5 C_OVER_A), prolate for
 * C_OVER_A > 1, oblate below; default aspect 3) in a periodic cubic box
 * whose side gives the packing fraction phi, held by the configuration
 * object of libpw85 (pw85_configuration_*, docs/scene.md: its cell grid,
 * minimum image and exact overlap verdicts). Start: aligned with the box
 * axes on a lattice of spacing >= 2A, 2B, 2C along x, y, z
 * (non-overlapping), or frame K (default: the last) of a GSD file (HOOMD
 * schema, gsd_read.h): its N, cubic box, positions, orientations and the
 * Ellipsoid type_shapes of its types (all equal), refused when a pair
 * overlaps. Monte Carlo: sweeps of N trial moves (random particle, then
 * with probability 1/2 a translation uniform in [-dr, dr]^3, otherwise a
 * rotation of its unit quaternion p to (p + dtheta/2 g) / |p + dtheta/2 g|,
 * g a standard normal 4-vector; both proposals are symmetric);
 * pw85_configuration_test_move rejects a move that overlaps another
 * particle, pw85_configuration_move commits the others. E equilibration
 * sweeps scale dr and dtheta after each sweep by a power of the ratio of
 * their acceptance to the target (below); the S production sweeps keep
 * them fixed (detailed balance) and are reported in B blocks: acceptance
 * and the nematic order parameter S2 averaged over the sweeps of the
 * block. S2 is the largest eigenvalue of the order tensor
 * Qt = (1/N) sum (3 u u^T - I) / 2 of the body z axes u (the symmetry axis
 * of spheroids: the long axis of prolate, the short axis of oblate ones;
 * 0 <= S2 <= 1 since tr Qt = 0; about 1/sqrt(N) for N isotropic axes).
 * --xyz and --gsd write the configuration at production sweep 0 (after
 * equilibration) and at the end of each block (extended XYZ for OVITO, GSD
 * for HOOMD-blue; S2 of the configuration in both, in the GSD file as
 * log/pw85/S2). Prints the number of trial moves per second of the
 * production loop, then checks that no pair overlaps
 * (pw85_configuration_pairs, s = 1) and the smallest mu^2 of the neighbour
 * pairs within s = 1.2 or 1 (pw85_configuration_pairs, then
 * pw85_scene_contact_function on those pairs).
 * Exit status: 0 when no pair overlaps, 1 when one does, 2 on bad usage, a
 * library error, a file that cannot be read or written. */
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
#include "gsd_read.h"
#include "gsd_write.h"

typedef struct {
  int n;
  double L;        /* box side */
  double axes[3];  /* semi-axes along the body x, y, z */
  double *x;       /* centres, 3n, in [0, L) */
  double *quat;    /* orientations, 4n: unit quaternions (w, x, y, z), w >= 0, body to lab */
  double *q;       /* quadratic forms, 6n */
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
  free(s->x), free(s->quat), free(s->q);
}

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void usage(FILE *out) {
  fprintf(out,
          "usage: pw85_mc [--n N] [--sweeps S] [--equil E] [--blocks B] [--seed SEED]\n"
          "               [--aspect C_OVER_A | --axes A B C] [--phi PHI] [--from FILE.gsd]\n"
          "               [--frame K] [--target ACC] [--threads T] [--xyz FILE] [--gsd FILE]\n"
          "               [--progress] [--help]\n"
          "Monte Carlo of N hard ellipsoids (semi-axes A, B, C; --aspect: spheroids 0.5,\n"
          "0.5, 0.5 * C_OVER_A) at packing fraction PHI: E sweeps tuning the steps to\n"
          "acceptance ACC (default 0.3), then S sweeps with fixed steps reported in B\n"
          "blocks (acceptance, nematic order S2 of the body z axes);\n"
          "--from starts from frame K (default -1: the last) of a GSD file (HOOMD schema:\n"
          "N, cubic box, positions, orientations, Ellipsoid type_shapes, all equal)\n"
          "instead of a lattice, without --n, --aspect, --axes, --phi;\n"
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

/* The body z axis of the unit quaternion p = (w, x, y, z): the third
 * column of its rotation matrix. */
static void body_z(const double p[4], double u[3]) {
  u[0] = 2.0 * (p[1] * p[3] + p[0] * p[2]);
  u[1] = 2.0 * (p[2] * p[3] - p[0] * p[1]);
  u[2] = 1.0 - 2.0 * (p[1] * p[1] + p[2] * p[2]);
}

/* Nematic order parameter S2: largest eigenvalue of
 * Qt = (1/N) sum_i (3 u_i u_i^T - I) / 2 over the body z axes u_i. */
static double order_parameter(const scene_t *s) {
  double m[6] = {0, 0, 0, 0, 0, 0};
  for (int i = 0; i < s->n; ++i) {
    double u[3];
    body_z(s->quat + 4 * i, u);
    m[0] += u[0] * u[0], m[1] += u[0] * u[1], m[2] += u[0] * u[2];
    m[3] += u[1] * u[1], m[4] += u[1] * u[2], m[5] += u[2] * u[2];
  }
  for (int k = 0; k < 6; ++k) m[k] *= 1.5 / s->n;
  m[0] -= 0.5, m[3] -= 0.5, m[5] -= 0.5;
  return largest_eigenvalue(m);
}

/* p / |p|, with the sign making w >= 0 (the same rotation). Returns 0, or
 * -1 for p = 0 or not finite. */
static int normalise_quaternion(double p[4]) {
  double norm = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3]);
  if (!(norm > 0.0) || !isfinite(norm)) return -1;
  if (p[0] < 0.0) norm = -norm;
  for (int k = 0; k < 4; ++k) p[k] /= norm;
  return 0;
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
    const double *q = s->quat + 4 * i, *x = s->x + 3 * i;
    fprintf(f, "E %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", x[0], x[1],
            x[2], q[1], q[2], q[3], q[0], s->axes[0], s->axes[1], s->axes[2]);
  }
  return (fflush(f) != 0 || ferror(f)) ? -1 : 0;
}

static const char *const gsd_logged[] = {"log/pw85/S2"};

/* GSD frame (HOOMD schema, gsd_write_frame): positions, the quaternions
 * (w, x, y, z), the semi-axes and S2 logged as log/pw85/S2. buf: 4n
 * floats of scratch. */
static int write_gsd(gsd_writer *w, const scene_t *s, uint64_t sweep, double s2, float *buf) {
  gsd_frame const frame = {sweep, (uint32_t)s->n, s->L, {s->axes[0], s->axes[1], s->axes[2]},
                           s->x, s->quat, 1, gsd_logged, &s2};
  return gsd_write_frame(w, &frame, buf);
}

/* One trial move of particle i: a rotation (rotate = 1) or a translation.
 * Returns 1 when accepted, 0 when rejected, -1 on a library error. tests
 * counts the trials. */
static int trial_move(scene_t *s, rng_t *g, int i, int rotate, double dr, double dtheta,
                      long long *tests) {
  double xn[3], pn[4], qn[6];
  memcpy(xn, s->x + 3 * i, sizeof xn);
  memcpy(pn, s->quat + 4 * i, sizeof pn);
  memcpy(qn, s->q + 6 * i, sizeof qn);
  if (rotate) {
    for (int k = 0; k < 4; ++k) pn[k] += 0.5 * dtheta * rng_normal(g);
    if (normalise_quaternion(pn) != 0) return 0;
    int const st = pw85_ellipsoid_quat(s->axes, pn, qn);
    if (st != PW85_OK) {
      fprintf(stderr, "pw85_mc: particle %d: %s\n", i, pw85_strerror(st));
      return -1;
    }
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
  memcpy(s->quat + 4 * i, pn, sizeof pn);
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

/* Particle positions, orientations and box of s from a GSD frame (gsd_read.h):
 * a cubic box, one ellipsoid shape for all the types of its particles.
 * Returns 0, or -1 with a message on stderr. */
static int scene_from_gsd(scene_t *s, const char *path, long long frame) {
  gsd_hoomd_frame f;
  char message[256];
  if (gsd_read_hoomd_frame(path, frame, &f, message, sizeof message) != 0) {
    fprintf(stderr, "pw85_mc: --from '%s': %s\n", path, message);
    return -1;
  }
  const char *problem = NULL;
  if (f.n < 2) problem = "fewer than 2 particles";
  else if (!(f.box[0] > 0.0) || f.box[1] != f.box[0] || f.box[2] != f.box[0] || f.box[3] != 0.0 ||
           f.box[4] != 0.0 || f.box[5] != 0.0)
    problem = "the box is not cubic (Lx = Ly = Lz, no tilt)";
  for (uint32_t i = 0; i < f.n && !problem; ++i) {
    const double *abc = f.semi_axes + 3 * f.typeid[i];
    for (int d = 0; d < 3 && !problem; ++d) {
      if (!(abc[d] > 1e-3 && abc[d] < 1e3)) problem = "a particle's type has no Ellipsoid type_shape with a, b, c in (1e-3, 1e3)";
      else if (abc[d] != f.semi_axes[3 * f.typeid[0] + d]) problem = "the particles' shapes differ (one shape for all)";
    }
  }
  s->n = (int)f.n;
  s->L = f.box[0];
  s->x = malloc(3 * (size_t)s->n * sizeof(double));
  s->quat = malloc(4 * (size_t)s->n * sizeof(double));
  s->q = malloc(6 * (size_t)s->n * sizeof(double));
  if (!problem && (!s->x || !s->quat || !s->q)) problem = "out of memory";
  if (!problem) memcpy(s->axes, f.semi_axes + 3 * f.typeid[0], sizeof s->axes);
  for (int i = 0; i < s->n && !problem; ++i) {
    for (int d = 0; d < 3; ++d) s->x[3 * i + d] = wrap(f.position[3 * i + d] + 0.5 * s->L, s->L);
    memcpy(s->quat + 4 * i, f.orientation + 4 * i, 4 * sizeof(double));
    if (!isfinite(s->x[3 * i] + s->x[3 * i + 1] + s->x[3 * i + 2]) ||
        normalise_quaternion(s->quat + 4 * i) != 0 || pw85_ellipsoid_quat(s->axes, s->quat + 4 * i, s->q + 6 * i) != PW85_OK)
      problem = "a position or orientation is not finite or zero";
  }
  if (problem) fprintf(stderr, "pw85_mc: --from '%s', frame %lld: %s\n", path, frame, problem);
  gsd_hoomd_frame_free(&f);
  return problem ? -1 : 0;
}

/* The aligned lattice: nl[d] = floor(L / (2 axes[d])) sites of spacing
 * >= 2 axes[d] along axis d, particle i on site i * sites / n. Returns 0,
 * or -1 when the sites are fewer than n or memory runs out. */
static int scene_lattice(scene_t *s) {
  long long nl[3];
  for (int d = 0; d < 3; d++) nl[d] = (long long)floor(s->L / (2.0 * s->axes[d]));
  if (nl[0] < 1 || nl[1] < 1 || nl[2] < 1 || nl[0] * nl[1] * nl[2] < s->n) {
    fprintf(stderr, "pw85_mc: packing fraction too high for the initial lattice\n");
    return -1;
  }
  long long const sites = nl[0] * nl[1] * nl[2];
  s->x = malloc(3 * (size_t)s->n * sizeof(double));
  s->quat = malloc(4 * (size_t)s->n * sizeof(double));
  s->q = malloc(6 * (size_t)s->n * sizeof(double));
  if (!s->x || !s->quat || !s->q) {
    fprintf(stderr, "pw85_mc: out of memory\n");
    return -1;
  }
  for (int i = 0; i < s->n; ++i) {
    long long const site = (long long)i * sites / s->n;
    long long const idx[3] = {site % nl[0], site / nl[0] % nl[1], site / nl[0] / nl[1]};
    for (int d = 0; d < 3; d++) s->x[3 * i + d] = ((double)idx[d] + 0.5) * s->L / (double)nl[d];
    double *p = s->quat + 4 * i;
    p[0] = 1.0, p[1] = p[2] = p[3] = 0.0;
    if (pw85_ellipsoid_quat(s->axes, p, s->q + 6 * i) != PW85_OK) return -1;
  }
  return 0;
}

int main(int argc, char **argv) {
  long n = 1000, sweeps = 20, equil = 10, blocks = 4, threads = 0;
  uint64_t seed = 1;
  double aspect = 3.0, phi = 0.2, target = 0.3, axes[3] = {0, 0, 0};
  long long frame = -1; /* of --from: the last */
  int have_axes = 0, shape_or_size_given = 0;
  const char *xyz_path = NULL, *gsd_path = NULL, *from_path = NULL;
  progress_t prog = {0, isatty(STDERR_FILENO), 0, 0.0, 0.0};
  prog.on = prog.tty;
  for (int i = 1; i < argc; ++i) {
    const char *o = argv[i], *arg = i + 1 < argc ? argv[i + 1] : NULL;
    int bad = 0, takes = 1;
    long value = 0;
    if (!strcmp(o, "--help") || !strcmp(o, "-h")) {
      usage(stdout);
      return 0;
    } else if (!strcmp(o, "--progress")) {
      prog.on = 1, takes = 0;
    } else if (!arg) {
      bad = 1;
    } else if (!strcmp(o, "--n")) {
      bad = parse_long(arg, 2, 100000000, &n);
      shape_or_size_given = 1;
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
      bad = have_axes || parse_double(arg, 1e-3, 1e3, &aspect);
      shape_or_size_given = 1;
    } else if (!strcmp(o, "--axes")) {
      for (int d = 0; d < 3 && !bad; d++)
        bad = i + 1 + d >= argc || parse_double(argv[i + 1 + d], 1e-3, 1e3, &axes[d]) ||
              !(axes[d] > 1e-3 && axes[d] < 1e3);
      have_axes = 1, shape_or_size_given = 1, takes = 3;
    } else if (!strcmp(o, "--phi")) {
      bad = parse_double(arg, 1e-6, 0.5, &phi) || phi == 0.5;
      shape_or_size_given = 1;
    } else if (!strcmp(o, "--from")) {
      from_path = arg;
    } else if (!strcmp(o, "--frame")) {
      bad = parse_long(arg, -1000000000L, 1000000000L, &value);
      frame = value;
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
  if (from_path && shape_or_size_given) {
    fprintf(stderr, "pw85_mc: --from takes N, the box and the shape from the file: no --n, "
            "--aspect, --axes or --phi\n");
    return 2;
  }
  if (frame != -1 && !from_path) {
    fprintf(stderr, "pw85_mc: --frame needs --from\n");
    return 2;
  }
  if (blocks > sweeps) blocks = sweeps;
  scene_t s;
  memset(&s, 0, sizeof s);
  if (from_path) {
    if (scene_from_gsd(&s, from_path, frame) != 0) {
      free_scene(&s);
      return 2;
    }
    n = s.n;
    phi = n * 4.0 / 3.0 * 3.141592653589793 * s.axes[0] * s.axes[1] * s.axes[2] / (s.L * s.L * s.L);
  } else {
    s.n = (int)n;
    if (have_axes) memcpy(s.axes, axes, sizeof axes);
    else s.axes[0] = s.axes[1] = 0.5, s.axes[2] = 0.5 * aspect;
    s.L = cbrt(n * 4.0 / 3.0 * 3.141592653589793 * s.axes[0] * s.axes[1] * s.axes[2] / phi);
    if (scene_lattice(&s) != 0) {
      free_scene(&s);
      return 2;
    }
  }
  double const box[6] = {s.L, s.L, s.L, 0.0, 0.0, 0.0};
  /* The box must hold every orientation: the library's bound on two
   * bounding spheres (radius at most sqrt(trace Q) = sqrt(A^2 + B^2 + C^2),
   * whatever the rotation) against half the side. */
  double const reach = sqrt(s.axes[0] * s.axes[0] + s.axes[1] * s.axes[1] + s.axes[2] * s.axes[2]);
  if (2.0 * reach > 0.5 * s.L * (1.0 - 1e-9)) {
    fprintf(stderr, "pw85_mc: box %g too small for the ellipsoids (side < 4 sqrt(A^2 + B^2 + C^2) = %g); "
            "increase --n\n", s.L, 4.0 * reach);
    free_scene(&s);
    return 2;
  }
  long long bad_particle = -1;
  int const created = pw85_configuration_create(n, s.x, s.q, box, &s.conf, &bad_particle);
  if (created != PW85_OK) {
    fprintf(stderr, "pw85_mc: the box (side %g) cannot hold the particles: %s (particle %lld); "
            "increase --n\n", s.L, pw85_strerror(created), bad_particle);
    free_scene(&s);
    return 2;
  }
  if (from_path) { /* hard particles: a start with overlaps is no state of the model */
    long long overlapping = 0;
    int const st = pw85_configuration_pairs(s.conf, 1.0, (int)threads, 0, NULL, NULL, NULL, &overlapping, NULL);
    if ((st != PW85_OK && st != PW85_ERR_CAPACITY) || overlapping > 0) {
      fprintf(stderr, "pw85_mc: --from '%s': %lld overlapping pairs in the frame (%s)\n", from_path,
              overlapping, pw85_strerror(st == PW85_ERR_CAPACITY ? PW85_OK : st));
      free_scene(&s);
      return 2;
    }
  }
  /* Output files: nothing else to undo when they cannot be created. */
  FILE *xyz = NULL;
  gsd_writer gsd;
  int have_gsd = 0, file_error = 0;
  if (xyz_path && !(xyz = fopen(xyz_path, "w"))) {
    fprintf(stderr, "pw85_mc: cannot write '%s': %s\n", xyz_path, strerror(errno));
    free_scene(&s);
    return 2;
  }
  if (gsd_path) {
    char app[64];
    snprintf(app, sizeof app, "pw85_mc %s", pw85_version());
    if (gsd_open(&gsd, gsd_path, app, gsd_logged, 1) != 0) {
      fprintf(stderr, "pw85_mc: cannot write '%s': %s\n", gsd_path, strerror(errno));
      if (xyz) fclose(xyz);
      free_scene(&s);
      return 2;
    }
    have_gsd = 1;
  }
  float *fbuf = malloc(4 * (size_t)n * sizeof(float));
  if (!fbuf) {
    fprintf(stderr, "pw85_mc: out of memory\n");
    return 2;
  }
  double const *ax = s.axes;
  int const spheroid = ax[0] == ax[1];
  printf("pw85_mc: %ld %s (semi-axes %g %g %g), packing fraction %g, box %.4g, %s, seed %llu\n", n,
         !spheroid ? "ellipsoids"
                   : ax[2] > ax[0] ? "prolate spheroids" : (ax[2] < ax[0] ? "oblate spheroids" : "spheres"),
         ax[0], ax[1], ax[2], phi, s.L, from_path ? "start from a GSD frame" : "lattice start",
         (unsigned long long)seed);

  rng_t g = {seed};
  double dr = 0.4 * fmin(s.axes[0], fmin(s.axes[1], s.axes[2])), dtheta = 0.4;
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
      if (have_gsd && write_gsd(&gsd, &s, 0, s2, fbuf) != 0) file_error = 1;
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
        if (have_gsd && write_gsd(&gsd, &s, (uint64_t)done, s2, fbuf) != 0) file_error = 1;
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
    free(fbuf);
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
  free(fbuf);
  free(ij), free(pairs), free(res);
  return rc;
}
