/* pw85_edmd: event-driven molecular dynamics of hard ellipsoids, the
 * demonstration of pw85_contact_time (docs/edmd.md, labels M1-M6).
 *
 *   pw85_edmd [--shape sphere|spheroid|ellipsoid | --axes A B C] [--n N] [--phi PHI]
 *             [--collisions C] [--equil E] [--blocks B] [--seed SEED]
 *             [--check] [--check-every K] [--cs] [--miss M] [--gsd FILE] [--help]
 *
 * N identical hard ellipsoids (semi-axes 0.5^3, (0.5, 0.5, 1), (0.4, 0.7, 1)
 * or A, B, C in (1e-3, 1e3)), mass 1 and isotropic moment of inertia
 * I = 2 (a^2 + b^2 + c^2) / 15 (M1), in a periodic cubic box at packing
 * fraction PHI, start on a lattice with aligned axes, kT = 1.
 * Free flight: c(t) = c + t v, A(t) = exp(t [w]x) A (exact torque-free
 * motion of a spherical top). Candidate partners: neighbour lists of
 * range 2 R + skin (R: largest semi-axis, skin R / 2) from the
 * configuration object (pw85_configuration_neighbours on the centres at
 * each particle's last list rebuild), kept symmetric; a particle rebuilds
 * its list when its centre has moved skin / 2 (a shell-exit event). Per
 * particle the earliest event (collision with a partner of its list by
 * pw85_contact_time, or shell exit) in an indexed binary heap; collision
 * counters invalidate stale events. Collisions: smooth hard bodies, impulse along the normal of
 * pw85_contact at its contact point (M2-M4). E collisions of equilibration,
 * then C collisions measured: pressure from the collision virial (M5) in B
 * blocks (mean, standard error).
 * Checks (counted and printed always): at each collision pw85_overlap = 0
 * and 1 - 1e-10 <= mu^2 <= 1 + 1e-9 for the pair, the
 * contact points separate after the impulse, the pair's energy, momentum
 * and angular momentum about the origin are conserved to 1e-10 relative;
 * every K events (default 1) no pair of the scene overlaps
 * (pw85_configuration_pairs at s = 1 on a configuration of the current
 * state); at the end total kinetic
 * energy and momentum conserved to 1e-10 relative. --cs: also
 * |Z / Z_CS - 1| <= 1 % (Carnahan-Starling, M6; spheres). --miss M (fault
 * injection, for the test that the checks fail): every M-th
 * pw85_contact_time result is replaced by "no contact".
 * --gsd: the trajectory as a GSD file (HOOMD schema, gsd_write.h), a frame
 * at the start and at the end of each block, step the number of
 * collisions, the time logged as log/pw85/time.
 * Exit status 1 when --check is given and a check fails, 2 on bad usage,
 * a library error or a file that cannot be written, 0 otherwise. */
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

enum { EV_NONE, EV_COLLISION, EV_SHELL, EV_REPREDICT };

typedef struct {
  double t;        /* event time */
  int type, j;     /* partner j of a collision */
  long long cj;    /* partner's collision counter at prediction */
} event_t;

typedef struct {
  int *j, n, cap; /* a neighbour list */
} list_t;

typedef struct {
  int n;
  double L, R, skin, axes2[3], inertia, tnow, tprev; /* tprev: time of the previous event */
  double *t0, *c, *v, *w, *a; /* state at t0: centre, velocity, ang. velocity, A (row major) */
  double *ref;                /* centres at the last list rebuild (3 per particle) */
  long long *count;           /* collisions of each particle */
  event_t *ev;
  int *heap, *pos;            /* indexed binary min-heap of particles by ev.t */
  pw85_configuration *conf;   /* the centres ref: neighbour queries */
  list_t *nb;                 /* neighbour lists, symmetric */
  long long *found;           /* n: a query's result */
  long long calls, skipped_far, events, collisions, rebuilds, repredicts, grazes, backoffs, stuck, miss;
} sim_t;

/* ---- kinematics ---------------------------------------------------------- */

/* R = exp([w]x tau) by Rodrigues' formula. */
static void rotation(const double w[3], double tau, double r[9]) {
  double nw = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]), th = nw * tau;
  for (int k = 0; k < 9; k++) r[k] = (k % 4 == 0) ? 1.0 : 0.0;
  if (!(th != 0.0)) return;
  double k[3] = {w[0] / nw, w[1] / nw, w[2] / nw}, s = sin(th), c1 = 1.0 - cos(th);
  double kx[9] = {0, -k[2], k[1], k[2], 0, -k[0], -k[1], k[0], 0};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double k2 = 0.0;
      for (int m = 0; m < 3; m++) k2 += kx[3 * i + m] * kx[3 * m + j];
      r[3 * i + j] += s * kx[3 * i + j] + c1 * k2;
    }
}

/* Centre, orientation and quadratic form Q = A diag(axes^2) A^T of particle
 * i at time t (any output may be NULL). */
static void state_at(const sim_t *s, int i, double t, double c[3], double a[9], double q[6]) {
  double tau = t - s->t0[i], r[9], at[9];
  if (c)
    for (int d = 0; d < 3; d++) c[d] = s->c[3 * i + d] + tau * s->v[3 * i + d];
  rotation(s->w + 3 * i, tau, r);
  for (int p = 0; p < 3; p++)
    for (int m = 0; m < 3; m++) {
      double x = 0.0;
      for (int k = 0; k < 3; k++) x += r[3 * p + k] * s->a[9 * i + 3 * k + m];
      at[3 * p + m] = x;
    }
  if (a) memcpy(a, at, sizeof at);
  if (q) {
    int k = 0;
    for (int p = 0; p < 3; p++)
      for (int m = p; m < 3; m++) {
        double x = 0.0;
        for (int e = 0; e < 3; e++) x += at[3 * p + e] * s->axes2[e] * at[3 * m + e];
        q[k++] = x;
      }
  }
}

static void advance(sim_t *s, int i, double t) {
  double c[3], a[9];
  state_at(s, i, t, c, a, NULL);
  memcpy(s->c + 3 * i, c, sizeof c);
  memcpy(s->a + 9 * i, a, sizeof a);
  s->t0[i] = t;
}

static void cross3(const double a[3], const double b[3], double c[3]) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* ---- event calendar ------------------------------------------------------ */

static int before(const sim_t *s, int i, int j) {
  return s->ev[i].t < s->ev[j].t || (s->ev[i].t == s->ev[j].t && i < j);
}

static void heap_swap(sim_t *s, int p, int q) {
  int a = s->heap[p], b = s->heap[q];
  s->heap[p] = b, s->heap[q] = a;
  s->pos[b] = p, s->pos[a] = q;
}

static void heap_fix(sim_t *s, int i) {
  int p = s->pos[i];
  while (p > 0 && before(s, s->heap[p], s->heap[(p - 1) / 2])) {
    heap_swap(s, p, (p - 1) / 2);
    p = (p - 1) / 2;
  }
  for (;;) {
    int l = 2 * p + 1, r = l + 1, m = p;
    if (l < s->n && before(s, s->heap[l], s->heap[m])) m = l;
    if (r < s->n && before(s, s->heap[r], s->heap[m])) m = r;
    if (m == p) break;
    heap_swap(s, p, m);
    p = m;
  }
}

/* ---- neighbour lists ------------------------------------------------------ */

static int list_add(list_t *l, int j) {
  if (l->n == l->cap) {
    int cap = l->cap ? 2 * l->cap : 16;
    int *p = realloc(l->j, (size_t)cap * sizeof(int));
    if (!p) return PW85_ERR_NO_MEMORY;
    l->j = p, l->cap = cap;
  }
  l->j[l->n++] = j;
  return PW85_OK;
}

static void list_remove(list_t *l, int j) {
  for (int k = 0; k < l->n; k++)
    if (l->j[k] == j) {
      l->j[k] = l->j[--l->n];
      return;
    }
}

/* Particle i's list from the configuration (centres ref): every j whose
 * reference centre lies within 2 R + skin of i's, added to j's list too.
 * Pairs off the lists are >= 2 R + skin apart at their references; each
 * centre stays within skin / 2 of its reference, so they cannot touch. */
static int rebuild_list(sim_t *s, int i) {
  long long m = 0;
  int st = pw85_configuration_neighbours(s->conf, i, 2.0 * s->R + s->skin, s->n, s->found, &m);
  if (st != PW85_OK) return st;
  for (int k = 0; k < s->nb[i].n; k++) list_remove(&s->nb[s->nb[i].j[k]], i);
  s->nb[i].n = 0;
  for (long long k = 0; k < m && st == PW85_OK; k++) {
    int j = (int)s->found[k];
    st = list_add(&s->nb[i], j);
    if (st == PW85_OK) st = list_add(&s->nb[j], i);
  }
  return st;
}

/* Time after s->tnow at which particle i's centre is skin / 2 from its
 * reference: the larger root of |d + t v| = skin / 2, d = c(tnow) - ref. */
static double shell_exit(const sim_t *s, int i, const double c[3]) {
  double d[3], vv = 0, dv = 0, dd = 0, h = 0.5 * s->skin;
  for (int k = 0; k < 3; k++) d[k] = c[k] - s->ref[3 * i + k];
  for (int k = 0; k < 3; k++) vv += s->v[3 * i + k] * s->v[3 * i + k], dv += d[k] * s->v[3 * i + k], dd += d[k] * d[k];
  if (!(vv > 0.0)) return INFINITY;
  double disc = dv * dv - vv * (dd - h * h);
  double t = (-dv + sqrt(disc > 0.0 ? disc : 0.0)) / vv;
  return t > 0.0 ? t : 0.0;
}

/* Relative state of the pair (i, j) at time t with the image shift of j:
 * r12 = c_j + L shift - c_i, v12, Q_i, Q_j. */
static void pair_at(const sim_t *s, int i, int j, const int shift[3], double t, double r12[3],
                    double v12[3], double qi[6], double qj[6]) {
  double ci[3], cj[3];
  state_at(s, i, t, ci, NULL, qi);
  state_at(s, j, t, cj, NULL, qj);
  for (int d = 0; d < 3; d++) {
    r12[d] = (cj[d] - ci[d]) + s->L * shift[d];
    v12[d] = s->v[3 * j + d] - s->v[3 * i + d];
  }
}

/* Relative normal velocity u.n of the contact points (M2) of a touching
 * pair; *st: status of pw85_contact. */
static double normal_velocity(const sim_t *s, int i, int j, const double r12[3], const double qi[6],
                              const double qj[6], pw85_contact_t *ct, int *st) {
  *st = pw85_contact(r12, qi, qj, ct);
  double ri[3], rj[3], wri[3], wrj[3], u[3];
  for (int d = 0; d < 3; d++) ri[d] = ct->x0[d], rj[d] = ct->x0[d] - r12[d];
  cross3(s->w + 3 * i, ri, wri);
  cross3(s->w + 3 * j, rj, wrj);
  for (int d = 0; d < 3; d++) u[d] = s->v[3 * j + d] + wrj[d] - s->v[3 * i + d] - wri[d];
  return dot3(u, ct->n);
}

/* First contact of the pair (i, j) (image shift) in [tnow, tnow + horizon]:
 * returns PW85_OK with *tc = +INFINITY when none, PW85_ERR_NO_CONVERGENCE
 * with *tc the end of the certified contact-free interval, or a library
 * error. Bounding spheres of radius R first: the pair cannot touch outside
 * the times when |r12 + t v12| <= 2R, so pw85_contact_time runs only on
 * that window. A pair touching at its start and separating (u.n >= 0, e.g.
 * just after its collision) is searched from tnow + delta, the smallest
 * delta = 1e-12 2^k after which it no longer touches (none up to 1e-3:
 * counted in s->stuck, a failed check). */
static int pair_time(sim_t *s, int i, int j, const int shift[3], double horizon, double *tc) {
  double r12[3], v12[3], qi[6], qj[6];
  pair_at(s, i, j, shift, s->tnow, r12, v12, qi, qj);
  double sig = 2.0 * s->R * (1.0 + 1e-9), rr = dot3(r12, r12), vv = dot3(v12, v12),
         rv = dot3(r12, v12), disc = rv * rv - vv * (rr - sig * sig);
  *tc = INFINITY;
  if (rr > sig * sig && (vv == 0.0 || disc <= 0.0 || rv >= 0.0)) {
    s->skipped_far++;
    return PW85_OK;
  }
  double t1 = 0.0, t2 = horizon;
  if (vv > 0.0 && disc > 0.0) {
    double sq = sqrt(disc);
    t1 = fmax(0.0, (-rv - sq) / vv * (1.0 - 1e-9));
    t2 = fmin(horizon, (-rv + sq) / vv * (1.0 + 1e-9));
  }
  if (!(t1 < t2)) {
    s->skipped_far++;
    return PW85_OK;
  }
  double start = t1;
  for (int k = 0;; k++) {
    double t, r[3], q1[6], q2[6];
    for (int d = 0; d < 3; d++) r[d] = r12[d] + start * v12[d];
    state_at(s, i, s->tnow + start, NULL, NULL, q1);
    state_at(s, j, s->tnow + start, NULL, NULL, q2);
    s->calls++;
    int st = pw85_contact_time(r, v12, q1, s->w + 3 * i, q2, s->w + 3 * j, t2 - start, &t);
    if (st == PW85_ERR_NO_CONVERGENCE) {
      *tc = start + t;
      return st;
    }
    if (st != PW85_OK) return st;
    if (s->miss > 0 && s->calls % s->miss == 0) t = INFINITY; /* --miss: fault injection */
    if (t > 0.0) {
      *tc = start + t;
      return PW85_OK;
    }
    if (k == 30) { /* still touching after 1e-3: counted as a failed check */
      s->stuck++;
      return PW85_OK;
    }
    pw85_contact_t ct;
    double un = normal_velocity(s, i, j, r, q1, q2, &ct, &st);
    if (st != PW85_OK && st != PW85_ERR_INACCURATE) return st;
    if (un < 0.0) { /* approaching: collision now */
      *tc = start;
      return PW85_OK;
    }
    start = t1 + 1e-12 * ldexp(1.0, k);
    if (!(start < t2)) return PW85_OK;
  }
}

/* Earliest event of particle i from s->tnow: shell exit, collision with a
 * particle of its list (the nearest image now: with L >= 6 R and skin R / 2
 * no other image comes within 2 R while both centres stay within skin / 2 of
 * their references), or a re-prediction where a pw85_contact_time ran out
 * of evaluations. Returns a library status. */
static int predict(sim_t *s, int i) {
  event_t e = {INFINITY, EV_NONE, -1, 0};
  double c[3];
  state_at(s, i, s->tnow, c, NULL, NULL);
  double t_exit = shell_exit(s, i, c);
  if (t_exit < INFINITY) e.t = s->tnow + t_exit, e.type = EV_SHELL;
  for (int k = 0; k < s->nb[i].n; k++) {
    int j = s->nb[i].j[k], shift[3];
    double cj[3], horizon = e.t - s->tnow, tc;
    if (!(horizon > 0.0)) break;
    state_at(s, j, s->tnow, cj, NULL, NULL);
    for (int d = 0; d < 3; d++) shift[d] = -(int)nearbyint((cj[d] - c[d]) / s->L);
    {
      int st = pair_time(s, i, j, shift, horizon, &tc);
      if (st != PW85_OK && st != PW85_ERR_NO_CONVERGENCE) {
        fprintf(stderr, "pw85_edmd: collision prediction: %s\n", pw85_strerror(st));
        return st;
      }
      if (tc < horizon) {
        e.t = s->tnow + tc;
        e.type = st == PW85_OK ? EV_COLLISION : EV_REPREDICT;
        e.j = j, e.cj = s->count[j];
      }
    }
  }
  s->ev[i] = e;
  heap_fix(s, i);
  return PW85_OK;
}

/* ---- collisions and checks ------------------------------------------------ */

typedef struct {
  long long overlap_at_contact, mu2_low, mu2_high, not_separating, energy, momentum, angular, scene_overlaps,
      scene_checks, pairs_checked;
  double mu2_min, mu2_max, energy_max, momentum_max, angular_max;
} checks_t;

static void pair_invariants(const sim_t *s, int i, int j, const double ci[3], const double cj[3],
                            double *e, double p[3], double l[3], double mag[3]) {
  double li[3], lj[3];
  cross3(ci, s->v + 3 * i, li);
  cross3(cj, s->v + 3 * j, lj);
  *e = 0.5 * (dot3(s->v + 3 * i, s->v + 3 * i) + dot3(s->v + 3 * j, s->v + 3 * j)) +
       0.5 * s->inertia * (dot3(s->w + 3 * i, s->w + 3 * i) + dot3(s->w + 3 * j, s->w + 3 * j));
  mag[0] = *e, mag[1] = sqrt(dot3(s->v + 3 * i, s->v + 3 * i)) + sqrt(dot3(s->v + 3 * j, s->v + 3 * j));
  mag[2] = sqrt(dot3(li, li)) + sqrt(dot3(lj, lj)) +
           s->inertia * (sqrt(dot3(s->w + 3 * i, s->w + 3 * i)) + sqrt(dot3(s->w + 3 * j, s->w + 3 * j)));
  for (int d = 0; d < 3; d++) {
    p[d] = s->v[3 * i + d] + s->v[3 * j + d];
    l[d] = li[d] + lj[d] + s->inertia * (s->w[3 * i + d] + s->w[3 * j + d]);
  }
}

static double rel_change(const double a[3], const double b[3], double scale) {
  double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
  return sqrt(dot3(d, d)) / scale;
}

/* Collision of the pair of event ev of particle i at s->tnow (M2-M4);
 * *virial += r12 . dp_j (M5). Returns a library status. */
static int collide(sim_t *s, int i, const event_t *ev, checks_t *ck, double *virial) {
  int j = ev->j, shift[3], ov, st;
  double r12[3], v12[3], qi[6], qj[6], ci[3], cj[3];
  /* The contact time rounded to the time grid may lie an ulp after the
   * tangency: step back (within the interval since the previous event)
   * while the pair overlaps. Image: the nearest, |r12| <= 2R < L / 2. */
  for (int k = 0;; k++) {
    state_at(s, i, s->tnow, ci, NULL, NULL);
    state_at(s, j, s->tnow, cj, NULL, NULL);
    for (int d = 0; d < 3; d++) shift[d] = -(int)nearbyint((cj[d] - ci[d]) / s->L);
    pair_at(s, i, j, shift, s->tnow, r12, v12, qi, qj);
    ov = pw85_overlap(r12, qi, qj);
    double t = s->tnow - ldexp(fabs(s->tnow) * 0x1p-52, k);
    if (ov != 1 || k == 60 || !(t >= s->tprev)) break;
    s->tnow = t;
    s->backoffs++;
  }
  if (ov < 0) return ov;
  if (ov) ck->overlap_at_contact++;
  advance(s, i, s->tnow);
  advance(s, j, s->tnow);
  pw85_contact_t ct;
  double un = normal_velocity(s, i, j, r12, qi, qj, &ct, &st);
  if (st != PW85_OK && st != PW85_ERR_INACCURATE) return st;
  if (ct.mu2 < ck->mu2_min) ck->mu2_min = ct.mu2;
  if (ct.mu2 > ck->mu2_max) ck->mu2_max = ct.mu2;
  if (!(ct.mu2 >= 1.0 - 1e-10)) ck->mu2_low++;
  if (!(ct.mu2 <= 1.0 + 1e-9)) ck->mu2_high++; /* not touching */
  if (!(un < 0.0)) { /* grazing: touching without approaching */
    s->grazes++;
    return PW85_OK;
  }
  double ri[3], rj[3], rin[3], rjn[3];
  for (int d = 0; d < 3; d++) {
    ri[d] = ct.x0[d], rj[d] = ct.x0[d] - r12[d];
    cj[d] = ci[d] + r12[d];
  }
  double e0, p0[3], l0[3], mag[3], e1, p1[3], l1[3], mag1[3];
  pair_invariants(s, i, j, ci, cj, &e0, p0, l0, mag);
  cross3(ri, ct.n, rin);
  cross3(rj, ct.n, rjn);
  /* (M3) K = 1/m_i + 1/m_j + |r_i x n|^2 / I + |r_j x n|^2 / I, J = -2 u.n / K */
  double kk = 2.0 + (dot3(rin, rin) + dot3(rjn, rjn)) / s->inertia, jn = -2.0 * un / kk;
  for (int d = 0; d < 3; d++) { /* (M4) */
    s->v[3 * i + d] -= jn * ct.n[d];
    s->v[3 * j + d] += jn * ct.n[d];
    s->w[3 * i + d] -= jn * rin[d] / s->inertia;
    s->w[3 * j + d] += jn * rjn[d] / s->inertia;
  }
  pair_invariants(s, i, j, ci, cj, &e1, p1, l1, mag1);
  double de = fabs(e1 - e0) / mag[0], dp = rel_change(p1, p0, mag[1]), dl = rel_change(l1, l0, mag[2]);
  ck->energy_max = fmax(ck->energy_max, de);
  ck->momentum_max = fmax(ck->momentum_max, dp);
  ck->angular_max = fmax(ck->angular_max, dl);
  ck->energy += !(de <= 1e-10);
  ck->momentum += !(dp <= 1e-10);
  ck->angular += !(dl <= 1e-10);
  double un1 = normal_velocity(s, i, j, r12, qi, qj, &ct, &st);
  if (!(un1 > 0.0)) ck->not_separating++;
  *virial += jn * dot3(r12, ct.n);
  s->count[i]++, s->count[j]++;
  s->collisions++;
  return PW85_OK;
}

/* Overlap check of every pair of the scene at s->tnow: the overlapping
 * pairs of a configuration of the current state (check, updated in place:
 * pw85_configuration_pairs at s = 1, the count only). */
static int check_scene(sim_t *s, pw85_configuration *check, checks_t *ck, double *cbuf, double *qbuf) {
  for (int i = 0; i < s->n; i++) state_at(s, i, s->tnow, cbuf + 3 * i, NULL, qbuf + 6 * i);
  double box[6] = {s->L, s->L, s->L, 0, 0, 0};
  long long count = 0, examined[2] = {0, 0};
  int st = pw85_configuration_update(check, s->n, cbuf, qbuf, box, NULL);
  if (st == PW85_OK) st = pw85_configuration_pairs(check, 1.0, 1, 0, NULL, NULL, NULL, &count, examined);
  if (st != PW85_OK && st != PW85_ERR_CAPACITY) return st;
  ck->pairs_checked += examined[0];
  ck->scene_checks++;
  ck->scene_overlaps += count;
  return PW85_OK;
}

static void totals(const sim_t *s, double *ktrans, double *krot, double p[3], double *pmag) {
  *ktrans = *krot = *pmag = 0.0;
  p[0] = p[1] = p[2] = 0.0;
  for (int i = 0; i < s->n; i++) {
    *ktrans += 0.5 * dot3(s->v + 3 * i, s->v + 3 * i);
    *krot += 0.5 * s->inertia * dot3(s->w + 3 * i, s->w + 3 * i);
    *pmag += sqrt(dot3(s->v + 3 * i, s->v + 3 * i));
    for (int d = 0; d < 3; d++) p[d] += s->v[3 * i + d];
  }
}

/* ---- set-up and main loop --------------------------------------------------- */

static void free_sim(sim_t *s) {
  free(s->t0), free(s->c), free(s->v), free(s->w), free(s->a), free(s->ref), free(s->count);
  free(s->ev), free(s->heap), free(s->pos), free(s->found);
  if (s->nb)
    for (int i = 0; i < s->n; i++) free(s->nb[i].j);
  free(s->nb);
  pw85_configuration_destroy(s->conf);
}

static const char *const gsd_logged[] = {"log/pw85/time"};

/* A GSD frame of the scene at s->tnow (gsd_write_frame): centres, the
 * quaternions of the orientations, the time. c: 3n doubles, quat: 4n
 * doubles, buf: 4n floats of scratch. */
static int write_frame(gsd_writer *w, const sim_t *s, const double axes[3], double *c,
                       double *quat, float *buf) {
  for (int i = 0; i < s->n; i++) {
    double a[9];
    state_at(s, i, s->tnow, c + 3 * i, a, NULL);
    gsd_quaternion_of_rotation(a, quat + 4 * i);
  }
  gsd_frame const frame = {(uint64_t)s->collisions, (uint32_t)s->n, s->L, {axes[0], axes[1], axes[2]},
                           c, quat, 1, gsd_logged, &s->tnow};
  return gsd_write_frame(w, &frame, buf);
}

static void usage(FILE *out) {
  fprintf(out,
          "usage: pw85_edmd [--shape sphere|spheroid|ellipsoid | --axes A B C] [--n N]\n"
          "                 [--phi PHI] [--collisions C] [--equil E] [--blocks B]\n"
          "                 [--seed SEED] [--check] [--check-every K] [--cs] [--miss M]\n"
          "                 [--gsd FILE] [--help]\n"
          "Event-driven molecular dynamics of N hard ellipsoids (pw85_contact_time):\n"
          "collisions predicted and resolved exactly, pressure from the collision virial.\n"
          "  --shape S        sphere (semi-axes 0.5 0.5 0.5), spheroid (0.5 0.5 1, the\n"
          "                   default) or ellipsoid (0.4 0.7 1)\n"
          "  --axes A B C     any semi-axes, each in (1e-3, 1e3)\n"
          "  --n N            number of ellipsoids, >= 8 (default 256)\n"
          "  --phi PHI        packing fraction, in (0, 0.5) (default 0.3)\n"
          "  --collisions C   collisions measured, >= B (default 10000)\n"
          "  --equil E        collisions of equilibration before them (default 0)\n"
          "  --blocks B       blocks of the pressure average, >= 2 (default 10)\n"
          "  --seed SEED      seed of the initial velocities (default 1)\n"
          "  --check          exit 1 when a check fails (overlap after an event, mu^2 at\n"
          "                   contact, conservation per collision and in total)\n"
          "  --check-every K  checks every pair of the scene every K events (default 1)\n"
          "  --cs             also checks the pressure of spheres against\n"
          "                   Carnahan-Starling to 1 %%\n"
          "  --miss M         fault injection: drops every M-th predicted contact (for\n"
          "                   the test that the checks fail)\n"
          "  --gsd FILE       writes the trajectory (GSD, HOOMD schema: positions,\n"
          "                   orientations, type_shapes ellipsoid; a frame at the start\n"
          "                   and at the end of each block, step = collisions, the time\n"
          "                   as log/pw85/time)\n"
          "  --help           this text\n"
          "Exit status: 0 success, 1 a --check failed, 2 bad usage, a library error or a\n"
          "file that cannot be written.\n");
}

int main(int argc, char **argv) {
  int n = 256, check = 0, check_every = 1, cs = 0, blocks = 10;
  long long ncoll = 10000, nequil = 0, miss = 0;
  double phi = 0.3;
  const char *shape = "spheroid";
  double axes[3] = {0.0, 0.0, 0.0};
  uint64_t seed = 1;
  const char *gsd_path = NULL;
  for (int i = 1; i < argc; i++) {
    const char *o = argv[i], *arg = i + 1 < argc ? argv[i + 1] : NULL;
    long value = 0;
    int bad = 0, takes = 1;
    if (!strcmp(o, "--help") || !strcmp(o, "-h")) {
      usage(stdout);
      return 0;
    } else if (!strcmp(o, "--check")) {
      check = 1, takes = 0;
    } else if (!strcmp(o, "--cs")) {
      cs = 1, takes = 0;
    } else if (!strcmp(o, "--shape")) {
      bad = !arg;
      shape = arg;
    } else if (!strcmp(o, "--axes")) {
      shape = "custom";
      for (int d = 0; d < 3 && !bad; d++)
        bad = i + 1 + d >= argc || parse_double(argv[i + 1 + d], 1e-3, 1e3, &axes[d]);
      takes = 3;
    } else if (!strcmp(o, "--n")) {
      bad = !arg || parse_long(arg, 8, 10000000, &value);
      n = (int)value;
    } else if (!strcmp(o, "--phi")) {
      bad = !arg || parse_double(arg, 1e-9, 0.5, &phi) || phi == 0.5;
    } else if (!strcmp(o, "--collisions")) {
      bad = !arg || parse_long(arg, 1, 1000000000000L, &value);
      ncoll = value;
    } else if (!strcmp(o, "--equil")) {
      bad = !arg || parse_long(arg, 0, 1000000000000L, &value);
      nequil = value;
    } else if (!strcmp(o, "--miss")) {
      bad = !arg || parse_long(arg, 0, 1000000000000L, &value);
      miss = value;
    } else if (!strcmp(o, "--blocks")) {
      bad = !arg || parse_long(arg, 2, 1000000000, &value);
      blocks = (int)value;
    } else if (!strcmp(o, "--check-every")) {
      bad = !arg || parse_long(arg, 1, 1000000000, &value);
      check_every = (int)value;
    } else if (!strcmp(o, "--seed")) {
      bad = !arg || parse_seed(arg, &seed);
    } else if (!strcmp(o, "--gsd")) {
      bad = !arg;
      gsd_path = arg;
    } else {
      fprintf(stderr, "pw85_edmd: unknown option '%s'\n", o);
      usage(stderr);
      return 2;
    }
    if (bad) {
      fprintf(stderr, "pw85_edmd: bad or missing value for %s\n", o);
      usage(stderr);
      return 2;
    }
    i += takes;
  }
  if (!strcmp(shape, "custom")) {
    for (int d = 0; d < 3; d++)
      if (!(axes[d] > 1e-3 && axes[d] < 1e3)) shape = "";
  } else if (!strcmp(shape, "sphere")) axes[0] = axes[1] = axes[2] = 0.5;
  else if (!strcmp(shape, "spheroid")) axes[0] = axes[1] = 0.5, axes[2] = 1.0;
  else if (!strcmp(shape, "ellipsoid")) axes[0] = 0.4, axes[1] = 0.7, axes[2] = 1.0;
  else
    shape = "";
  if (!*shape) {
    fprintf(stderr, "pw85_edmd: unknown shape (sphere, spheroid or ellipsoid) or semi-axis of "
            "--axes not in (1e-3, 1e3)\n");
    return 2;
  }
  if (ncoll < blocks) {
    fprintf(stderr, "pw85_edmd: --collisions %lld fewer than --blocks %d\n", ncoll, blocks);
    return 2;
  }
  sim_t s = {0};
  s.n = n;
  s.miss = miss;
  s.R = fmax(axes[0], fmax(axes[1], axes[2]));
  for (int d = 0; d < 3; d++) s.axes2[d] = axes[d] * axes[d];
  s.inertia = 2.0 * (s.axes2[0] + s.axes2[1] + s.axes2[2]) / 15.0; /* (M1) */
  s.L = cbrt(n * 4.0 / 3.0 * 3.141592653589793 * axes[0] * axes[1] * axes[2] / phi);
  s.skin = 0.5 * s.R;
  /* L > 4 R + 2 skin: one image of a pair within 2 R + skin at a time
   * (predict). */
  if (!(s.L >= 6.0 * s.R * (1.0 + 1e-9))) {
    fprintf(stderr, "pw85_edmd: box %g smaller than 6R = %g; increase --n\n", s.L, 6 * s.R);
    return 2;
  }
  /* Lattice of aligned particles, nl[d] = floor(L / (2 axes[d])) sites of
   * spacing >= 2 axes[d] along axis d; particle i on site i * sites / n. */
  int nl[3];
  for (int d = 0; d < 3; d++) nl[d] = (int)floor(s.L / (2.0 * axes[d]));
  long long sites = (long long)nl[0] * nl[1] * nl[2];
  if (sites < n) {
    fprintf(stderr, "pw85_edmd: packing fraction too high for the initial lattice\n");
    return 2;
  }
  size_t nn = (size_t)n;
  s.t0 = calloc(nn, sizeof(double));
  s.c = calloc(3 * nn, sizeof(double));
  s.v = calloc(3 * nn, sizeof(double));
  s.w = calloc(3 * nn, sizeof(double));
  s.a = calloc(9 * nn, sizeof(double));
  s.ref = calloc(3 * nn, sizeof(double));
  s.count = calloc(nn, sizeof(long long));
  s.ev = calloc(nn, sizeof(event_t));
  s.heap = calloc(nn, sizeof(int));
  s.pos = calloc(nn, sizeof(int));
  s.nb = calloc(nn, sizeof(list_t));
  s.found = calloc(nn, sizeof(long long));
  double *cbuf = calloc(3 * nn, sizeof(double)), *qbuf = calloc(6 * nn, sizeof(double));
  double *zblock = calloc((size_t)blocks, sizeof(double));
  if (!s.t0 || !s.c || !s.v || !s.w || !s.a || !s.ref || !s.count || !s.ev || !s.heap || !s.pos ||
      !s.nb || !s.found || !cbuf || !qbuf || !zblock) {
    fprintf(stderr, "pw85_edmd: out of memory\n");
    return 2;
  }
  rng_t g = {seed};
  double vm[3] = {0, 0, 0};
  for (int i = 0; i < n; i++) {
    long long site = (long long)i * sites / n;
    int idx[3] = {(int)(site % nl[0]), (int)(site / nl[0] % nl[1]), (int)(site / nl[0] / nl[1])};
    for (int d = 0; d < 3; d++) s.c[3 * i + d] = (idx[d] + 0.5) * s.L / nl[d];
    s.a[9 * i] = s.a[9 * i + 4] = s.a[9 * i + 8] = 1.0;
    for (int d = 0; d < 3; d++) {
      s.v[3 * i + d] = rng_normal(&g);
      s.w[3 * i + d] = rng_normal(&g) / sqrt(s.inertia);
      vm[d] += s.v[3 * i + d] / n;
    }
  }
  for (int i = 0; i < n; i++)
    for (int d = 0; d < 3; d++) s.v[3 * i + d] -= vm[d];
  memcpy(s.ref, s.c, 3 * nn * sizeof(double));
  for (int i = 0; i < n; i++) state_at(&s, i, 0.0, NULL, NULL, qbuf + 6 * i);
  double const box[6] = {s.L, s.L, s.L, 0, 0, 0};
  pw85_configuration *checker = NULL;
  int st = pw85_configuration_create(n, s.ref, qbuf, box, &s.conf, NULL);
  if (st == PW85_OK) st = pw85_configuration_create(n, s.ref, qbuf, box, &checker, NULL);
  for (int i = 0; i < n && st == PW85_OK; i++) st = rebuild_list(&s, i);
  checks_t ck = {0};
  ck.mu2_min = INFINITY;
  if (st == PW85_OK) st = check_scene(&s, checker, &ck, cbuf, qbuf);
  if (st != PW85_OK || ck.scene_overlaps) {
    fprintf(stderr, "pw85_edmd: initial lattice overlaps or library error (%s)\n", pw85_strerror(st));
    return 2;
  }
  long long listed = 0;
  for (int i = 0; i < n; i++) listed += s.nb[i].n;
  printf("pw85_edmd: %d ellipsoids (%s, semi-axes %g %g %g, I = %.6g), packing fraction %g, box %.6g, "
         "neighbour lists of range 2R + %g (%.1f per particle at the start), seed %llu\n",
         n, shape, axes[0], axes[1], axes[2], s.inertia, phi, s.L, s.skin, (double)listed / n,
         (unsigned long long)seed);
  gsd_writer traj;
  double *gsd_quat = NULL;
  float *gsd_buf = NULL;
  int file_error = 0;
  if (gsd_path) {
    char app[64];
    snprintf(app, sizeof app, "pw85_edmd %s", pw85_version());
    gsd_quat = malloc(4 * nn * sizeof(double));
    gsd_buf = malloc(4 * nn * sizeof(float));
    if (!gsd_quat || !gsd_buf || gsd_open(&traj, gsd_path, app, gsd_logged, 1) != 0) {
      fprintf(stderr, "pw85_edmd: cannot write '%s': %s\n", gsd_path, strerror(errno));
      free_sim(&s);
      pw85_configuration_destroy(checker);
      free(cbuf), free(qbuf), free(zblock), free(gsd_quat), free(gsd_buf);
      return 2;
    }
    file_error = write_frame(&traj, &s, axes, cbuf, gsd_quat, gsd_buf) != 0;
  }
  for (int i = 0; i < n; i++) s.heap[i] = i, s.pos[i] = i, s.ev[i].t = INFINITY;
  for (int i = 0; i < n && st == PW85_OK; i++) st = predict(&s, i);
  double kt0, kr0, p0[3], pm0;
  totals(&s, &kt0, &kr0, p0, &pm0);
  /* Production: collision virial W = sum r12 . dp_j per block of time (M5). */
  long long per_block = ncoll / blocks, total = nequil + per_block * blocks;
  double virial = 0.0, tblock = 0.0;
  int b = 0;
  while (st == PW85_OK && s.collisions < total) {
    int i = s.heap[0];
    event_t e = s.ev[i];
    if (!(e.t < INFINITY)) {
      fprintf(stderr, "pw85_edmd: no event left\n");
      st = PW85_ERR_NO_CONVERGENCE;
      break;
    }
    s.tprev = s.tnow;
    s.tnow = e.t;
    s.events++;
    long long before_c = s.collisions;
    if (e.type == EV_SHELL) { /* new reference (in the box), new list */
      double q[6];
      advance(&s, i, s.tnow);
      for (int d = 0; d < 3; d++) {
        if (s.c[3 * i + d] < 0.0) s.c[3 * i + d] += s.L;
        if (s.c[3 * i + d] >= s.L) s.c[3 * i + d] -= s.L;
      }
      memcpy(s.ref + 3 * i, s.c + 3 * i, 3 * sizeof(double));
      state_at(&s, i, s.tnow, NULL, NULL, q);
      st = pw85_configuration_move(s.conf, i, s.ref + 3 * i, q);
      if (st == PW85_OK) st = rebuild_list(&s, i);
      s.rebuilds++;
      if (st == PW85_OK) st = predict(&s, i);
    } else if (e.type == EV_COLLISION && s.count[e.j] == e.cj) {
      st = collide(&s, i, &e, &ck, &virial);
      if (s.collisions == nequil && s.collisions != before_c) tblock = s.tnow, virial = 0.0;
      if (st == PW85_OK) st = predict(&s, i);
      if (st == PW85_OK) st = predict(&s, e.j);
    } else {
      s.repredicts += e.type == EV_REPREDICT;
      st = predict(&s, i);
    }
    if (st == PW85_OK && s.events % check_every == 0) st = check_scene(&s, checker, &ck, cbuf, qbuf);
    if (st != PW85_OK || s.collisions == before_c || s.collisions <= nequil) continue;
    if ((s.collisions - nequil) % per_block == 0) {
      double kt, kr, p[3], pm;
      totals(&s, &kt, &kr, p, &pm);
      double kT = 2.0 * kt / (3.0 * (n - 1)); /* momentum is zero */
      zblock[b++] = (2.0 / 3.0 * kt + virial / (3.0 * (s.tnow - tblock))) / (n * kT);
      tblock = s.tnow, virial = 0.0;
      if (gsd_path && write_frame(&traj, &s, axes, cbuf, gsd_quat, gsd_buf) != 0) file_error = 1;
    }
  }
  if (gsd_path && gsd_close(&traj) != 0) file_error = 1;
  free(gsd_quat), free(gsd_buf);
  if (st != PW85_OK) {
    fprintf(stderr, "pw85_edmd: library error: %s\n", pw85_strerror(st));
    return 2;
  }
  if (file_error) {
    fprintf(stderr, "pw85_edmd: writing '%s' failed\n", gsd_path);
    return 2;
  }
  double kt1, kr1, p1[3], pm1;
  totals(&s, &kt1, &kr1, p1, &pm1);
  double de = fabs(kt1 + kr1 - kt0 - kr0) / (kt0 + kr0);
  double dp = sqrt((p1[0] - p0[0]) * (p1[0] - p0[0]) + (p1[1] - p0[1]) * (p1[1] - p0[1]) +
                   (p1[2] - p0[2]) * (p1[2] - p0[2])) / pm0;
  printf("events %lld: collisions %lld (grazing, no impulse: %lld), list rebuilds %lld, "
         "re-predictions %lld, time %.6g\n",
         s.events, s.collisions, s.grazes, s.rebuilds, s.repredicts, s.tnow);
  printf("pw85_contact_time calls %lld (%.1f per collision), pairs skipped by bounding spheres %lld\n",
         s.calls, (double)s.calls / (double)(s.collisions ? s.collisions : 1), s.skipped_far);
  printf("at contact: mu^2 - 1 in [%.3e, %.3e], mu^2 < 1 - 1e-10: %lld, mu^2 > 1 + 1e-9: %lld, "
         "pw85_overlap = 1: %lld (after %lld steps back of an ulp or more), not separating after "
         "impulse: %lld\n",
         ck.mu2_min - 1.0, ck.mu2_max - 1.0, ck.mu2_low, ck.mu2_high, ck.overlap_at_contact,
         s.backoffs, ck.not_separating);
  printf("per collision, largest relative change: energy %.3e, momentum %.3e, angular momentum "
         "%.3e; above 1e-10: %lld %lld %lld\n",
         ck.energy_max, ck.momentum_max, ck.angular_max, ck.energy, ck.momentum, ck.angular);
  printf("pairs still touching 1e-3 after a contact: %lld\n", s.stuck);
  printf("scene checks %lld (every %d events), %lld close pairs tested, overlapping %lld\n",
         ck.scene_checks, check_every, ck.pairs_checked, ck.scene_overlaps);
  printf("total kinetic energy: relative change %.3e; total momentum: |dP| / sum |p| = %.3e\n", de, dp);
  double zm = 0.0, zv = 0.0;
  for (int k = 0; k < blocks; k++) zm += zblock[k] / blocks;
  for (int k = 0; k < blocks; k++) zv += (zblock[k] - zm) * (zblock[k] - zm) / (blocks - 1);
  double zerr = sqrt(zv / blocks), zcs = (1 + phi + phi * phi - phi * phi * phi) / pow(1 - phi, 3);
  printf("pressure: Z = PV/(N kT) = %.5f +- %.5f (%d blocks of %lld collisions after %lld)", zm, zerr,
         blocks, per_block, nequil);
  int spheres = axes[0] == axes[1] && axes[1] == axes[2];
  if (spheres)
    printf("; Carnahan-Starling %.5f, Z/Z_CS - 1 = %+.3f %%", zcs, 100.0 * (zm / zcs - 1.0));
  printf("\n");
  int fail = s.stuck || ck.mu2_low || ck.mu2_high || ck.overlap_at_contact || ck.not_separating || ck.energy || ck.momentum ||
             ck.angular || ck.scene_overlaps || !(de <= 1e-10) || !(dp <= 1e-10) ||
             (cs && !(spheres && fabs(zm / zcs - 1.0) <= 0.01));
  printf("%s\n", fail ? "FAILED" : "OK");
  free_sim(&s);
  pw85_configuration_destroy(checker);
  free(cbuf), free(qbuf), free(zblock);
  return check && fail ? 1 : 0;
}
