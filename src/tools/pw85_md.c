/* pw85_md: molecular dynamics of soft rigid ellipsoids, the demonstration of
 * pw85_scene_contact_derivatives (docs/derivatives.md).
 *
 *   pw85_md [--n N] [--steps S] [--dt DT] [--seed SEED] [--check]
 *           [--gsd FILE] [--gsd-every K] [--help]
 *
 * N ellipsoids (semi-axes 1, 0.6, 0.4, mass 1) in a periodic cubic box at
 * packing fraction 0.2, pair potential U = eps (1 - mu^2)^3 for mu < 1, zero
 * beyond (eps = 1): twice continuously differentiable at contact, bounded
 * forces. Forces F_j = -dU/dmu^2 d_r12 = -F_i, torques
 * tau_i = -dU/dmu^2 d_theta1, tau_j = -dU/dmu^2 d_theta2 with
 * dU/dmu^2 = -3 eps (1 - mu^2)^2. Each step, the configuration object
 * (pw85_configuration_update, no allocation) gives the pairs with mu^2 < 1,
 * the support of the potential (pw85_configuration_pairs, s = 1), then one
 * pw85_scene_contact_derivatives call computes them. Integrator: velocity Verlet for the centres; for
 * the orientations the symmetric splitting of the free rigid body into
 * rotations about the body axes x, y, z, y, x (Dullweber, Leimkuhler and
 * McLachlan, J. Chem. Phys. 107, 5840 (1997)), body angular momenta kicked
 * by the torques: symplectic and time-reversible.
 * Prints the total energy every S/10 steps and its relative drift
 * |E(end) - E(0)| / |E(0)| and fluctuation (RMS of E - E(0)) / |E(0)|.
 * --check: runs DT for S steps and DT/2 for 2S steps (same time), exit
 * status 0 when the drift of the first run is <= 1e-5 and the fluctuation
 * ratio is 4 +- 20 %, 1 otherwise; 2 on bad usage or a library error.
 * --gsd: the trajectory of the run with DT as a GSD file (HOOMD schema,
 * gsd_write.h): step 0 and every K steps (default S/10), with the potential
 * and total energy logged as log/pw85/potential_energy and
 * log/pw85/total_energy. */
#include <errno.h>
#include <math.h>
#include <pw85.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "demo_args.h"
#include "demo_rng.h"
#include "gsd_write.h"

static const double kAxes[3] = {1.0, 0.6, 0.4}, kEps = 1.0;

typedef struct {
  int n;
  double L, inertia[3];
  double *c, *p, *a, *pi, *q, *f, *tau; /* a: 3x3 body -> lab (row major); pi: body ang. mom. */
  long long *pairs, *ij, cap; /* ij: the i then the j of the pairs found */
  pw85_derivatives_t *d;
  pw85_configuration *conf;
} md_t;

static void update_q(md_t *s, int i) { /* Q = A diag(axes^2) A^T */
  const double *a = s->a + 9 * i;
  int k = 0;
  for (int r = 0; r < 3; r++)
    for (int c = r; c < 3; c++) {
      double v = 0.0;
      for (int m = 0; m < 3; m++) v += a[3 * r + m] * kAxes[m] * kAxes[m] * a[3 * c + m];
      s->q[6 * i + k++] = v;
    }
}

/* Forces, torques, potential energy; sets *err on an allocation or library
 * error. */
static double forces(md_t *s, int *err) {
  int const n = s->n;
  double const box[6] = {s->L, s->L, s->L, 0, 0, 0};
  long long m = 0;
  int st = s->conf ? pw85_configuration_update(s->conf, n, s->c, s->q, box, NULL)
                   : pw85_configuration_create(n, s->c, s->q, box, &s->conf, NULL);
  if (st == PW85_OK)
    st = pw85_configuration_pairs(s->conf, 1.0, 1, s->cap, s->ij, s->ij + s->cap, NULL, &m, NULL);
  if (st == PW85_ERR_CAPACITY) {
    long long const cap = 2 * m;
    long long *np = realloc(s->pairs, 2 * cap * sizeof *s->pairs);
    if (np) s->pairs = np;
    long long *nij = np ? realloc(s->ij, 2 * cap * sizeof *s->ij) : NULL;
    if (nij) s->ij = nij;
    pw85_derivatives_t *nd = nij ? realloc(s->d, cap * sizeof *s->d) : NULL;
    if (!nd) {
      *err = 1;
      return 0.0;
    }
    s->d = nd;
    s->cap = cap;
    st = pw85_configuration_pairs(s->conf, 1.0, 1, s->cap, s->ij, s->ij + s->cap, NULL, &m, NULL);
  }
  if (st != PW85_OK) {
    fprintf(stderr, "pw85_md: pw85_configuration: %s\n", pw85_strerror(st));
    *err = 1;
    return 0.0;
  }
  for (long long k = 0; k < m; k++) {
    s->pairs[2 * k] = s->ij[k];
    s->pairs[2 * k + 1] = s->ij[s->cap + k];
  }
  double u = 0.0;
  memset(s->f, 0, 3 * n * sizeof(double));
  memset(s->tau, 0, 3 * n * sizeof(double));
  if (m > 0 && pw85_scene_contact_derivatives(n, s->c, s->q, box, m, s->pairs, s->d, NULL, 0) != PW85_OK) {
    *err = 1;
    return 0.0;
  }
  for (long long k = 0; k < m; k++) {
    const pw85_derivatives_t *d = s->d + k;
    if (d->mu2 >= 1.0) continue;
    long long i = s->pairs[2 * k], j = s->pairs[2 * k + 1];
    double const g = 1.0 - d->mu2;
    double w = -3.0 * kEps * g * g; /* dU/dmu^2 */
    u += kEps * g * g * g;
    for (int e = 0; e < 3; e++) {
      s->f[3 * j + e] -= w * d->d_r12[e];
      s->f[3 * i + e] += w * d->d_r12[e];
      s->tau[3 * i + e] -= w * d->d_theta1[e];
      s->tau[3 * j + e] -= w * d->d_theta2[e];
    }
  }
  return u;
}

static double kinetic(const md_t *s) {
  double k = 0.0;
  for (int i = 0; i < s->n; i++)
    for (int e = 0; e < 3; e++)
      k += 0.5 * s->p[3 * i + e] * s->p[3 * i + e] + 0.5 * s->pi[3 * i + e] * s->pi[3 * i + e] / s->inertia[e];
  return k;
}

/* Free rotation about body axis k for time h: A <- A R_k(phi), pi <- R_k(-phi) pi,
 * phi = h pi_k / I_k. */
static void rotate(md_t *s, int i, int k, double h) {
  double *a = s->a + 9 * i, *pi = s->pi + 3 * i;
  double phi = h * pi[k] / s->inertia[k], cs = cos(phi), sn = sin(phi);
  int u = (k + 1) % 3, v = (k + 2) % 3;
  for (int r = 0; r < 3; r++) { /* columns u, v of A */
    double au = a[3 * r + u], av = a[3 * r + v];
    a[3 * r + u] = cs * au + sn * av;
    a[3 * r + v] = -sn * au + cs * av;
  }
  double pu = pi[u], pv = pi[v];
  pi[u] = cs * pu + sn * pv;
  pi[v] = -sn * pu + cs * pv;
}

static void kick(md_t *s, double h) {
  for (int i = 0; i < s->n; i++) {
    const double *a = s->a + 9 * i;
    for (int e = 0; e < 3; e++) {
      s->p[3 * i + e] += h * s->f[3 * i + e];
      double tb = 0.0; /* body-frame torque A^T tau */
      for (int r = 0; r < 3; r++) tb += a[3 * r + e] * s->tau[3 * i + r];
      s->pi[3 * i + e] += h * tb;
    }
  }
}

/* Side of the cubic box of n ellipsoids at packing fraction 0.2. */
static double box_side(int n) {
  double const vol = 4.0 / 3.0 * 3.141592653589793 * kAxes[0] * kAxes[1] * kAxes[2];
  return cbrt(n * vol / 0.2);
}

static const char *const gsd_logged[] = {"log/pw85/potential_energy", "log/pw85/total_energy"};

/* A GSD frame of the trajectory (gsd_write_frame): centres, the
 * quaternions of the orientations, potential and total energy. quat: 4n
 * doubles, buf: 4n floats of scratch. */
static int write_frame(gsd_writer *w, const md_t *s, uint64_t step, double u, double e,
                       double *quat, float *buf) {
  for (int i = 0; i < s->n; i++) gsd_quaternion_of_rotation(s->a + 9 * i, quat + 4 * i);
  double const logged[2] = {u, e};
  gsd_frame const frame = {step,   (uint32_t)s->n, s->L, {kAxes[0], kAxes[1], kAxes[2]}, s->c,
                           quat,   2,             gsd_logged, logged};
  return gsd_write_frame(w, &frame, buf);
}

/* Runs `steps` steps of dt; drift and RMS fluctuation of E relative to |E(0)|,
 * sampled every `every` steps; with traj, a frame at step 0 and every
 * traj_every steps. Returns 1 on an allocation or library error, 2 when
 * the trajectory cannot be written. */
static int run(int n, int steps, double dt, uint64_t seed, int every, int verbose,
               gsd_writer *traj, int traj_every, double *drift, double *fluct) {
  md_t s = {0};
  s.n = n;
  s.L = box_side(n);
  for (int e = 0; e < 3; e++)
    s.inertia[e] = 0.2 * (kAxes[(e + 1) % 3] * kAxes[(e + 1) % 3] + kAxes[(e + 2) % 3] * kAxes[(e + 2) % 3]);
  s.c = calloc(3 * n, sizeof(double));
  s.p = calloc(3 * n, sizeof(double));
  s.a = calloc(9 * n, sizeof(double));
  s.pi = calloc(3 * n, sizeof(double));
  s.q = calloc(6 * n, sizeof(double));
  s.f = calloc(3 * n, sizeof(double));
  s.tau = calloc(3 * n, sizeof(double));
  s.cap = 16 * n;
  s.pairs = malloc(2 * s.cap * sizeof *s.pairs);
  s.ij = malloc(2 * s.cap * sizeof *s.ij);
  s.d = malloc(s.cap * sizeof *s.d);
  s.conf = NULL;
  double *quat = traj ? malloc(4 * (size_t)n * sizeof(double)) : NULL;
  float *fbuf = traj ? malloc(4 * (size_t)n * sizeof(float)) : NULL;
  int err = !s.c || !s.p || !s.a || !s.pi || !s.q || !s.f || !s.tau || !s.pairs || !s.ij || !s.d ||
            (traj && (!quat || !fbuf));
  int traj_error = 0;
  rng_t g = {seed};
  int side = (int)ceil(cbrt((double)n));
  for (int i = 0; i < n && !err; i++) {
    int x = i % side, y = (i / side) % side, z = i / (side * side);
    s.c[3 * i] = (x + 0.5) * s.L / side;
    s.c[3 * i + 1] = (y + 0.5) * s.L / side;
    s.c[3 * i + 2] = (z + 0.5) * s.L / side;
    double w = rng_normal(&g), qx = rng_normal(&g), qy = rng_normal(&g), qz = rng_normal(&g);
    double nq = sqrt(w * w + qx * qx + qy * qy + qz * qz);
    w /= nq, qx /= nq, qy /= nq, qz /= nq;
    double m[9] = {1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - w * qz), 2 * (qx * qz + w * qy),
                   2 * (qx * qy + w * qz), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - w * qx),
                   2 * (qx * qz - w * qy), 2 * (qy * qz + w * qx), 1 - 2 * (qx * qx + qy * qy)};
    memcpy(s.a + 9 * i, m, sizeof m);
    for (int e = 0; e < 3; e++) {
      s.p[3 * i + e] = sqrt(0.5) * rng_normal(&g);
      s.pi[3 * i + e] = sqrt(0.5 * s.inertia[e]) * rng_normal(&g);
    }
    update_q(&s, i);
  }
  double u = err ? 0.0 : forces(&s, &err), e0 = u + kinetic(&s), sum2 = 0.0, e = e0;
  int samples = 0;
  if (traj && !err) traj_error = write_frame(traj, &s, 0, u, e0, quat, fbuf) != 0;
  for (int t = 1; t <= steps && !err; t++) {
    kick(&s, 0.5 * dt);
    for (int i = 0; i < n; i++) {
      for (int k = 0; k < 3; k++) s.c[3 * i + k] += dt * s.p[3 * i + k];
      rotate(&s, i, 0, 0.5 * dt);
      rotate(&s, i, 1, 0.5 * dt);
      rotate(&s, i, 2, dt);
      rotate(&s, i, 1, 0.5 * dt);
      rotate(&s, i, 0, 0.5 * dt);
      update_q(&s, i);
    }
    u = forces(&s, &err);
    kick(&s, 0.5 * dt);
    if (t % every == 0) {
      e = u + kinetic(&s);
      sum2 += (e - e0) * (e - e0);
      samples++;
      if (verbose && t % (steps / 10 > 0 ? steps / 10 : 1) == 0)
        printf("step %d  t %.4f  E %.12f  U %.6f\n", t, t * dt, e, u);
    }
    if (traj && !err && t % traj_every == 0)
      traj_error |= write_frame(traj, &s, (uint64_t)t, u, u + kinetic(&s), quat, fbuf) != 0;
  }
  *drift = fabs(e - e0) / fabs(e0);
  *fluct = sqrt(sum2 / (samples > 0 ? samples : 1)) / fabs(e0);
  free(s.c), free(s.p), free(s.a), free(s.pi), free(s.q), free(s.f), free(s.tau);
  free(s.pairs), free(s.ij), free(s.d), free(quat), free(fbuf);
  pw85_configuration_destroy(s.conf);
  return err ? 1 : traj_error ? 2 : 0;
}

static void usage(FILE *out) {
  fprintf(out,
          "usage: pw85_md [--n N] [--steps S] [--dt DT] [--seed SEED] [--check]\n"
          "               [--gsd FILE] [--gsd-every K] [--help]\n"
          "Molecular dynamics of N soft ellipsoids (semi-axes 1, 0.6, 0.4) at packing\n"
          "fraction 0.2, pair potential (1 - mu^2)^3 for mu^2 < 1, forces and torques\n"
          "from pw85_scene_contact_derivatives; prints the total energy every S/10 steps,\n"
          "its relative drift and fluctuation.\n"
          "  --n N          number of ellipsoids, >= 43 (default 256)\n"
          "  --steps S      time steps, >= 10 (default 10000)\n"
          "  --dt DT        time step, > 0 (default 0.002)\n"
          "  --seed SEED    seed of the initial orientations and velocities (default 1)\n"
          "  --check        also runs DT/2 for 2S steps; exit 1 unless the drift of the\n"
          "                 first run is <= 1e-5 and the fluctuation ratio 4 +- 20 %%\n"
          "  --gsd FILE     writes the trajectory of the first run (GSD, HOOMD schema:\n"
          "                 positions, orientations, type_shapes ellipsoid; potential\n"
          "                 and total energy as log/pw85/potential_energy and\n"
          "                 log/pw85/total_energy)\n"
          "  --gsd-every K  a frame at step 0 and every K steps (default S/10)\n"
          "  --help         this text\n"
          "Exit status: 0 success, 1 a --check failed, 2 bad usage, a library error or a\n"
          "file that cannot be written.\n");
}

int main(int argc, char **argv) {
  long n = 256, steps = 10000, gsd_every = 0;
  int check = 0;
  double dt = 0.002;
  uint64_t seed = 1;
  const char *gsd_path = NULL;
  for (int i = 1; i < argc; i++) {
    const char *o = argv[i], *arg = i + 1 < argc ? argv[i + 1] : NULL;
    int bad = 0;
    if (!strcmp(o, "--help") || !strcmp(o, "-h")) {
      usage(stdout);
      return 0;
    } else if (!strcmp(o, "--check")) {
      check = 1;
      continue;
    } else if (!strcmp(o, "--n")) {
      bad = !arg || parse_long(arg, 8, 10000000, &n);
    } else if (!strcmp(o, "--steps")) {
      bad = !arg || parse_long(arg, 10, 1000000000, &steps);
    } else if (!strcmp(o, "--dt")) {
      bad = !arg || parse_double(arg, 1e-12, 1e3, &dt);
    } else if (!strcmp(o, "--seed")) {
      bad = !arg || parse_seed(arg, &seed);
    } else if (!strcmp(o, "--gsd")) {
      bad = !arg;
      gsd_path = arg;
    } else if (!strcmp(o, "--gsd-every")) {
      bad = !arg || parse_long(arg, 1, 1000000000, &gsd_every);
    } else {
      fprintf(stderr, "pw85_md: unknown option '%s'\n", o);
      usage(stderr);
      return 2;
    }
    if (bad) {
      fprintf(stderr, "pw85_md: bad or missing value for %s\n", o);
      usage(stderr);
      return 2;
    }
    i++;
  }
  if (n < 43) {
    fprintf(stderr, "pw85_md: --n %ld: at least 43 ellipsoids (a box of side %g holds fewer "
            "neighbour shells than the potential's range needs)\n", n, box_side((int)n));
    return 2;
  }
  if (gsd_every == 0) gsd_every = steps / 10;
  gsd_writer traj;
  if (gsd_path) {
    char app[64];
    snprintf(app, sizeof app, "pw85_md %s", pw85_version());
    if (gsd_open(&traj, gsd_path, app, gsd_logged, 2) != 0) {
      fprintf(stderr, "pw85_md: cannot write '%s': %s\n", gsd_path, strerror(errno));
      return 2;
    }
  }
  double drift, fluct, drift2, fluct2;
  int const status = run((int)n, (int)steps, dt, seed, 10, 1, gsd_path ? &traj : NULL,
                         (int)gsd_every, &drift, &fluct);
  if (gsd_path && gsd_close(&traj) != 0 && status == 0) {
    fprintf(stderr, "pw85_md: writing '%s' failed\n", gsd_path);
    return 2;
  }
  if (status != 0) {
    fprintf(stderr, "pw85_md: %s\n",
            status == 2 ? "writing the trajectory failed" : "out of memory or library error");
    return 2;
  }
  printf("dt %g: relative drift %.3e, relative fluctuation %.3e\n", dt, drift, fluct);
  if (!check) return 0;
  if (run((int)n, 2 * (int)steps, 0.5 * dt, seed, 20, 0, NULL, 0, &drift2, &fluct2)) {
    fprintf(stderr, "pw85_md: out of memory or library error\n");
    return 2;
  }
  printf("dt %g: relative drift %.3e, relative fluctuation %.3e\n", 0.5 * dt, drift2, fluct2);
  double ratio = fluct / fluct2;
  printf("fluctuation ratio %.3f (expected 4 +- 20 %%)\n", ratio);
  return drift <= 1e-5 && ratio >= 3.2 && ratio <= 4.8 ? 0 : 1;
}
