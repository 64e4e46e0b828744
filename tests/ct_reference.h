/* Independent reference for the first contact time of two moving ellipsoids
 * (docs/contact_time.md), shared by tests/test-contact-time.c and
 * bench/bench_contact_time.c; it never calls the library. mu^2(t) is
 * evaluated in long double from the double inputs, and in __float128 where
 * it is within 1e-6 of 1: Q_i(t) = R Q_i R^T with R by Rodrigues' formula
 * (sin, cos in long double), lambda* by a safeguarded Newton
 * iteration on f'(lambda) = (1 - lambda)^2 s^T Q1 s - lambda^2 s^T Q2 s = 0
 * (f concave; f'' = -2 (Q1 s)^T Q^{-1} (Q2 s)), s = Q(lambda)^{-1} r by a
 * Cholesky solve in long double, mu^2 = lambda (1 - lambda) r^T s. The
 * trajectory is sampled on a uniform grid (ct_grid_points), every local
 * minimum of the samples is refined by golden-section search, and each
 * level crossing is located by bisection. Also the generators of the
 * trajectories (random, grazing, spinning, rotating grazes) of the test
 * and the benchmark. */
#ifndef PW85_CT_REFERENCE_H
#define PW85_CT_REFERENCE_H

#include <math.h>
#include <stdint.h>
#include <stdlib.h>

typedef long double ctr_real;

#define CT_PI 3.14159265358979323846

typedef struct {
  double r0[3], v[3], q1[6], w1[3], q2[6], w2[3], t_max;
} ct_traj;

/* ---- mu^2(t) in long double ---------------------------------------------- */

/* R(t) Q R(t)^T in type T (long double or __float128); sin and cos of the
 * angle in long double (relative error ~1e-19). */
#define CTR_ROTATE(NAME, T)                                                                   \
  static inline void NAME(const double q[6], const double w[3], long double t, T o[6]) {     \
    long double wn = sqrtl((long double)w[0] * w[0] + (long double)w[1] * w[1] +             \
                           (long double)w[2] * w[2]);                                        \
    T Q[3][3] = {{q[0], q[1], q[2]}, {q[1], q[3], q[4]}, {q[2], q[4], q[5]}};                \
    T R[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};                                           \
    if (wn > 0 && t != 0) {                                                                  \
      T k[3] = {(T)w[0] / (T)wn, (T)w[1] / (T)wn, (T)w[2] / (T)wn};                          \
      long double th = t * wn;                                                               \
      T s = (T)sinl(th), c1 = (T)(2 * sinl(0.5L * th) * sinl(0.5L * th));                    \
      T K[3][3] = {{0, -k[2], k[1]}, {k[2], 0, -k[0]}, {-k[1], k[0], 0}};                    \
      for (int i = 0; i < 3; i++)                                                            \
        for (int j = 0; j < 3; j++) {                                                        \
          T k2 = 0;                                                                          \
          for (int l = 0; l < 3; l++) k2 += K[i][l] * K[l][j];                               \
          R[i][j] += s * K[i][j] + c1 * k2;                                                  \
        }                                                                                    \
    }                                                                                        \
    T M[3][3];                                                                               \
    for (int i = 0; i < 3; i++)                                                              \
      for (int j = 0; j < 3; j++)                                                            \
        M[i][j] = R[i][0] * Q[0][j] + R[i][1] * Q[1][j] + R[i][2] * Q[2][j];                 \
    int idx = 0;                                                                             \
    for (int i = 0; i < 3; i++)                                                              \
      for (int j = i; j < 3; j++)                                                            \
        o[idx++] = M[i][0] * R[j][0] + M[i][1] * R[j][1] + M[i][2] * R[j][2];                \
  }
CTR_ROTATE(ctr_rotate, long double)
CTR_ROTATE(ctq_rotate, __float128)

static inline void ctr_mul(const ctr_real a[6], const ctr_real x[3], ctr_real y[3]) {
  y[0] = a[0] * x[0] + a[1] * x[1] + a[2] * x[2];
  y[1] = a[1] * x[0] + a[3] * x[1] + a[4] * x[2];
  y[2] = a[2] * x[0] + a[4] * x[1] + a[5] * x[2];
}
static inline ctr_real ctr_dot(const ctr_real a[3], const ctr_real b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* x = A^{-1} b, A symmetric positive definite (Cholesky); 0 if not. */
static inline int ctr_solve(const ctr_real a[6], const ctr_real b[3], ctr_real x[3]) {
  x[0] = x[1] = x[2] = 0;
  ctr_real l00 = a[0];
  if (!(l00 > 0)) return 0;
  l00 = sqrtl(l00);
  ctr_real l10 = a[1] / l00, l20 = a[2] / l00;
  ctr_real d1 = a[3] - l10 * l10;
  if (!(d1 > 0)) return 0;
  ctr_real l11 = sqrtl(d1), l21 = (a[4] - l20 * l10) / l11;
  ctr_real d2 = a[5] - l20 * l20 - l21 * l21;
  if (!(d2 > 0)) return 0;
  ctr_real l22 = sqrtl(d2);
  ctr_real y0 = b[0] / l00, y1 = (b[1] - l10 * y0) / l11, y2 = (b[2] - l20 * y0 - l21 * y1) / l22;
  x[2] = y2 / l22;
  x[1] = (y1 - l21 * x[2]) / l11;
  x[0] = (y0 - l10 * x[1] - l20 * x[2]) / l00;
  return 1;
}

/* mu^2 of (r, A, B); *lam: starting guess in (0, 1) on entry, maximiser on
 * exit. */
static inline ctr_real ctr_mu2(const ctr_real r[3], const ctr_real A[6], const ctr_real B[6],
                               ctr_real *lam) {
  ctr_real lo = 0, hi = 1, l = (*lam > 0 && *lam < 1) ? *lam : 0.5L;
  ctr_real s[3];
  for (int it = 0; it < 200; it++) {
    ctr_real Q[6], As[3], Bs[3], x[3];
    for (int i = 0; i < 6; i++) Q[i] = (1 - l) * A[i] + l * B[i];
    if (!ctr_solve(Q, r, s)) return NAN;
    ctr_mul(A, s, As);
    ctr_mul(B, s, Bs);
    ctr_real fp = (1 - l) * (1 - l) * ctr_dot(s, As) - l * l * ctr_dot(s, Bs);
    ctr_solve(Q, Bs, x);
    ctr_real fpp = -2 * ctr_dot(As, x);
    if (fp > 0) lo = l; else hi = l;
    ctr_real ln = l - fp / fpp;
    if (!(ln > lo && ln < hi)) ln = 0.5L * (lo + hi);
    ctr_real step = fabsl(ln - l), m = fminl(l, 1 - l);
    l = ln;
    if (step <= 1e-12L * m || hi - lo <= 1e-18L * m) break;
  }
  ctr_real Q[6];
  for (int i = 0; i < 6; i++) Q[i] = (1 - l) * A[i] + l * B[i];
  if (!ctr_solve(Q, r, s)) return NAN;
  *lam = l;
  return l * (1 - l) * ctr_dot(r, s);
}

/* The same in __float128 (L D L^T, no square root), from lambda0: two Newton
 * steps on f' = 0 (mu^2 is stationary in lambda, its error is of the order
 * of the square of that of lambda). */
typedef __float128 ctq_real;
static inline void ctq_mul(const ctq_real a[6], const ctq_real x[3], ctq_real y[3]) {
  y[0] = a[0] * x[0] + a[1] * x[1] + a[2] * x[2];
  y[1] = a[1] * x[0] + a[3] * x[1] + a[4] * x[2];
  y[2] = a[2] * x[0] + a[4] * x[1] + a[5] * x[2];
}
static inline ctq_real ctq_dot(const ctq_real a[3], const ctq_real b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
static inline int ctq_solve(const ctq_real a[6], const ctq_real b[3], ctq_real x[3]) {
  ctq_real d0 = a[0];
  if (!(d0 > 0)) return 0;
  ctq_real l10 = a[1] / d0, l20 = a[2] / d0;
  ctq_real d1 = a[3] - l10 * l10 * d0;
  if (!(d1 > 0)) return 0;
  ctq_real l21 = (a[4] - l20 * l10 * d0) / d1;
  ctq_real d2 = a[5] - l20 * l20 * d0 - l21 * l21 * d1;
  if (!(d2 > 0)) return 0;
  ctq_real y0 = b[0], y1 = b[1] - l10 * y0, y2 = b[2] - l20 * y0 - l21 * y1;
  x[2] = y2 / d2;
  x[1] = y1 / d1 - l21 * x[2];
  x[0] = y0 / d0 - l10 * x[1] - l20 * x[2];
  return 1;
}
static inline ctq_real ctq_mu2(const ctq_real r[3], const ctq_real A[6], const ctq_real B[6],
                               ctq_real l) {
  ctq_real Q[6], s[3];
  for (int it = 0; it < 2; it++) {
    ctq_real As[3], Bs[3], x[3];
    for (int i = 0; i < 6; i++) Q[i] = (1 - l) * A[i] + l * B[i];
    if (!ctq_solve(Q, r, s)) return NAN;
    ctq_mul(A, s, As);
    ctq_mul(B, s, Bs);
    ctq_real fp = (1 - l) * (1 - l) * ctq_dot(s, As) - l * l * ctq_dot(s, Bs);
    ctq_solve(Q, Bs, x);
    ctq_real ln = l + fp / (2 * ctq_dot(As, x));
    if (ln > 0 && ln < 1) l = ln;
  }
  for (int i = 0; i < 6; i++) Q[i] = (1 - l) * A[i] + l * B[i];
  if (!ctq_solve(Q, r, s)) return NAN;
  return l * (1 - l) * ctq_dot(r, s);
}

/* mu^2(t): long double; within 1e-6 of 1, recomputed in __float128. */
static inline ctr_real ctr_mu2_at(const ct_traj *tr, ctr_real t, ctr_real *lam) {
  ctr_real r[3], A[6], B[6];
  for (int i = 0; i < 3; i++) r[i] = (ctr_real)tr->r0[i] + t * (ctr_real)tr->v[i];
  ctr_rotate(tr->q1, tr->w1, t, A);
  ctr_rotate(tr->q2, tr->w2, t, B);
  ctr_real m = ctr_mu2(r, A, B, lam);
  if (!(fabsl(m - 1) < 1e-6L)) return m;
  ctq_real rq[3], Aq[6], Bq[6];
  for (int i = 0; i < 3; i++) rq[i] = (ctq_real)tr->r0[i] + (ctq_real)t * (ctq_real)tr->v[i];
  ctq_rotate(tr->q1, tr->w1, t, Aq);
  ctq_rotate(tr->q2, tr->w2, t, Bq);
  ctq_real mq = ctq_mu2(rq, Aq, Bq, *lam);
  /* the double nearest mu^2 - 1, then back: keeps the 1e-12 digits */
  return 1 + (ctr_real)(double)(mq - 1);
}

/* ---- First crossings ------------------------------------------------------ */

#define CT_LEVELS 2
/* Levels of mu^2: 1 - 1e-12 (below: must be detected), 1 (contact: not to
 * be reported earlier, nor on a trajectory whose mu^2 stays above it). */
static const double ct_levels[CT_LEVELS] = {1.0 - 1e-12, 1.0};

typedef struct {
  double t[CT_LEVELS]; /* first time mu^2 <= level, INFINITY when none */
  double min_mu2;      /* smallest mu^2 found on [0, t_max] */
  long evaluations;
} ct_ref;

/* Grid: 512 intervals plus 64 per turn of the faster rotation. */
static inline int ct_grid_points(const ct_traj *tr) {
  double w = fmax(sqrt(tr->w1[0] * tr->w1[0] + tr->w1[1] * tr->w1[1] + tr->w1[2] * tr->w1[2]),
                  sqrt(tr->w2[0] * tr->w2[0] + tr->w2[1] * tr->w2[1] + tr->w2[2] * tr->w2[2]));
  return 512 + (int)(64.0 * w * tr->t_max / (2 * CT_PI));
}

/* A crossing of level L in [a, b] with mu^2(a) > L >= mu^2(b), by bisection. */
static inline double ctr_bisect(const ct_traj *tr, ctr_real a, ctr_real b, double L,
                                ctr_real lam, long *ev) {
  for (int it = 0; it < 80 && b - a > 1e-18L * fabsl(b); it++) {
    ctr_real m = 0.5L * (a + b);
    ++*ev;
    if (ctr_mu2_at(tr, m, &lam) <= L) b = m; else a = m;
  }
  return (double)b;
}

static inline void ct_reference(const ct_traj *tr, ct_ref *out) {
  int n = ct_grid_points(tr);
  ctr_real *mu = (ctr_real *)calloc(n + 1, sizeof(ctr_real));
  ctr_real *lm = (ctr_real *)calloc(n + 1, sizeof(ctr_real));
  for (int k = 0; k < CT_LEVELS; k++) out->t[k] = NAN;
  out->min_mu2 = NAN;
  out->evaluations = 0;
  if (mu == NULL || lm == NULL) {
    free(mu);
    free(lm);
    return;
  }
  ctr_real h = (ctr_real)tr->t_max / n, lam = 0.5L, best = INFINITY;
  long ev = 0;
  for (int j = 0; j <= n; j++) {
    mu[j] = ctr_mu2_at(tr, j * h, &lam);
    lm[j] = lam;
    ev++;
  }
  for (int k = 0; k < CT_LEVELS; k++) out->t[k] = INFINITY;
  for (int j = 0; j <= n; j++) {
    if (mu[j] < best) best = mu[j];
    /* A sample at or below a level: the crossing lies in (t_{j-1}, t_j]. */
    for (int k = 0; k < CT_LEVELS; k++) {
      if (out->t[k] != INFINITY || mu[j] > ct_levels[k]) continue;
      out->t[k] = j == 0 ? 0.0 : ctr_bisect(tr, (j - 1) * h, j * h, ct_levels[k], lm[j], &ev);
    }
    /* A local minimum of the samples: golden section on [t_{j-1}, t_{j+1}]. */
    int lo = j > 0 ? j - 1 : 0, hi = j < n ? j + 1 : n;
    if (!(mu[j] <= mu[lo] && mu[j] <= mu[hi])) continue;
    const ctr_real g = 0.6180339887498948482L;
    ctr_real a = lo * h, b = hi * h, lam1 = lm[j], lam2 = lm[j];
    ctr_real x1 = b - g * (b - a), x2 = a + g * (b - a);
    ctr_real f1 = ctr_mu2_at(tr, x1, &lam1), f2 = ctr_mu2_at(tr, x2, &lam2);
    ev += 2;
    for (int it = 0; it < 90 && b - a > 1e-17L * (fabsl(a) + fabsl(b)); it++) {
      if (f1 <= f2) {
        b = x2; x2 = x1; f2 = f1; x1 = b - g * (b - a);
        f1 = ctr_mu2_at(tr, x1, &lam1);
      } else {
        a = x1; x1 = x2; f1 = f2; x2 = a + g * (b - a);
        f2 = ctr_mu2_at(tr, x2, &lam2);
      }
      ev++;
    }
    ctr_real tm = f1 <= f2 ? x1 : x2, fm = f1 <= f2 ? f1 : f2;
    if (fm < best) best = fm;
    for (int k = 0; k < CT_LEVELS; k++) {
      if (fm > ct_levels[k] || mu[lo] <= ct_levels[k]) continue;
      double tc = ctr_bisect(tr, lo * h, tm, ct_levels[k], lm[j], &ev);
      if (tc < out->t[k]) out->t[k] = tc;
    }
  }
  out->min_mu2 = (double)best;
  out->evaluations = ev;
  free(mu);
  free(lm);
}

/* ---- Verdict on a reported time -------------------------------------------- */

/* Verdict on the time t reported with PW85_OK for the trajectory tr, against
 * its reference, tol = 1e-9 t_max (docs/contact_time.md):
 *   CT_MISSED: the reference finds mu^2 < 1 - 1e-12, first at t_a, and t is
 *              later than t_a + tol (or +INFINITY);
 *   CT_EARLY:  t < t_c - tol, t_c the reference's first crossing of mu^2 = 1;
 *   CT_FALSE:  a contact (t finite) on a trajectory whose reference minimum of
 *              mu^2 is above 1.
 * The last two are waived when the reference finds mu^2 <= 1 at t or t + tol
 * (a dip narrower than its samples: then t_c <= t + tol). */
enum { CT_MISSED = 1, CT_EARLY = 2, CT_FALSE = 4 };
static inline int ct_verdict(const ct_traj *tr, const ct_ref *ref, double t) {
  double const tol = 1e-9 * tr->t_max;
  int v = 0;
  if (ref->t[0] != INFINITY && !(t <= ref->t[0] + tol)) v |= CT_MISSED;
  if (t != INFINITY && ref->t[1] != INFINITY && !(t >= ref->t[1] - tol)) v |= CT_EARLY;
  if (t != INFINITY && ref->t[1] == INFINITY) v |= CT_FALSE;
  if (v & (CT_EARLY | CT_FALSE)) {
    ctr_real lam = 0.5L;
    if (ctr_mu2_at(tr, t, &lam) <= 1 || ctr_mu2_at(tr, t + tol, &lam) <= 1)
      v &= ~(CT_EARLY | CT_FALSE);
  }
  return v;
}

/* ---- Trajectories ---------------------------------------------------------- */

typedef struct { uint64_t s; } ct_rng;

static inline double ct_uniform(ct_rng *g) { /* splitmix64, [0, 1) */
  uint64_t z = (g->s += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  z ^= z >> 31;
  return (double)(z >> 11) * 0x1p-53;
}
static inline double ct_normal(ct_rng *g) {
  double u1 = ct_uniform(g), u2 = ct_uniform(g);
  return sqrt(-2.0 * log(1.0 - u1)) * cos(2 * CT_PI * u2);
}
static inline void ct_unit(ct_rng *g, double u[3]) {
  double n;
  do {
    for (int i = 0; i < 3; i++) u[i] = ct_normal(g);
    n = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  } while (!(n > 1e-3));
  for (int i = 0; i < 3; i++) u[i] /= n;
}

/* Semi-axes log-uniform in [lo, hi], random orientation (unit quaternion);
 * Q = R diag(a^2) R^T in long double, rounded. *amax: largest semi-axis. */
static inline void ct_ellipsoid(ct_rng *g, double lo, double hi, double q[6], double *amax) {
  double a[3], p[4], n = 0;
  for (int i = 0; i < 3; i++) a[i] = lo * exp(ct_uniform(g) * log(hi / lo));
  for (int i = 0; i < 4; i++) { p[i] = ct_normal(g); n += p[i] * p[i]; }
  n = sqrt(n);
  ctr_real w = p[0] / n, x = p[1] / n, y = p[2] / n, z = p[3] / n;
  ctr_real R[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                      {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                      {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
  int idx = 0;
  for (int i = 0; i < 3; i++)
    for (int j = i; j < 3; j++) {
      ctr_real s = 0;
      for (int k = 0; k < 3; k++) s += R[i][k] * R[j][k] * (ctr_real)a[k] * a[k];
      q[idx++] = (double)s;
    }
  *amax = fmax(a[0], fmax(a[1], a[2]));
}

/* Kinds of trajectories. */
enum { CT_RANDOM, CT_GRAZING, CT_SPINNING, CT_ROTGRAZE, CT_KINDS };

/* A trajectory of class [lo, hi], t_max = 1:
 *  - CT_RANDOM: centres 1.1-3 bounding radii apart, heading towards each
 *    other with an offset up to the bounding radii, rotations of up to half
 *    a turn over the horizon;
 *  - CT_GRAZING (translation): the line r* + t v tangent to the level set
 *    mu^2 = 1 + delta at r*, touching it at t = 0.5, delta = +-1e-6,
 *    +-1e-9, +-1e-12 (k selects);
 *  - CT_SPINNING: as CT_RANDOM with 2-5 turns of each ellipsoid;
 *  - CT_ROTGRAZE: a stationary minimum of mu^2 at 1 + delta (as
 *    CT_GRAZING) while each body turns 0.5-3 times (ct_rotgraze). */
/* The translation of CT_GRAZING for the ellipsoids q1, q2 (largest
 * semi-axes a1, a2), d a random unit vector: tangent to mu^2 = 1 + delta. */
static inline void ct_graze(ct_rng *g, double a1, double a2, const double d[3], double delta,
                            ct_traj *tr) {
  double e[3];
  ctr_real R[3] = {d[0], d[1], d[2]}, A[6], B[6], lam = 0.5L, s[3], Q[6];
  for (int i = 0; i < 6; i++) { A[i] = tr->q1[i]; B[i] = tr->q2[i]; }
  ctr_real m2 = ctr_mu2(R, A, B, &lam);
  ctr_real sc = sqrtl((1.0L + delta) / m2);
  for (int i = 0; i < 3; i++) R[i] *= sc; /* mu^2(R) = 1 + delta */
  for (int i = 0; i < 6; i++) Q[i] = (1 - lam) * A[i] + lam * B[i];
  ctr_solve(Q, R, s); /* normal of the level set at R */
  ctr_real sn = sqrtl(ctr_dot(s, s));
  ct_unit(g, e);
  ctr_real en = 0, t[3];
  ctr_real es = (e[0] * s[0] + e[1] * s[1] + e[2] * s[2]) / (sn * sn);
  for (int i = 0; i < 3; i++) { t[i] = e[i] - es * s[i]; en += t[i] * t[i]; }
  en = sqrtl(en);
  double speed = (a1 + a2) * (0.5 + 2 * ct_uniform(g));
  for (int i = 0; i < 3; i++) {
    tr->v[i] = (double)(speed * t[i] / en);
    tr->r0[i] = (double)(R[i] - 0.5L * tr->v[i]);
  }
}

/* CT_ROTGRAZE: each body turning 0.5-3 times over t_max = 1, the centre
 * offset passing at t = 0.5 through r* with mu^2(r*) = 1 + delta at a
 * stationary point of mu^2(t): v = (a random part perpendicular to
 * s = Q(lambda)^{-1} r*, speed 2-6 (a1 + a2)) + alpha s / |s|^2,
 * alpha = (1 - lambda) s.(w1 x Q1 s) + lambda s.(w2 x Q2 s), so that
 * dmu^2/dt = lambda (1 - lambda) (2 s.v - 2 alpha) = 0 there (Q_i at t = 0.5,
 * long double). The inputs are rounded to double: the exact minimum moves
 * (the reference finds it). */
static inline void ct_rotgraze(ct_rng *g, double a1, double a2, const double d[3], double delta,
                               ct_traj *tr) {
  double u[3], e[3];
  for (int b = 0; b < 2; b++) {
    double const turns = 0.5 + 2.5 * ct_uniform(g);
    ct_unit(g, u);
    for (int i = 0; i < 3; i++) (b ? tr->w2 : tr->w1)[i] = 2 * CT_PI * turns * u[i];
  }
  ctr_real A[6], B[6], R[3] = {d[0], d[1], d[2]}, lam = 0.5L, s[3], Q[6], As[3], Bs[3], c[3];
  ctr_rotate(tr->q1, tr->w1, 0.5L, A);
  ctr_rotate(tr->q2, tr->w2, 0.5L, B);
  ctr_real const m2 = ctr_mu2(R, A, B, &lam);
  ctr_real const sc = sqrtl((1.0L + delta) / m2);
  for (int i = 0; i < 3; i++) R[i] *= sc;
  ctr_mu2(R, A, B, &lam);
  for (int i = 0; i < 6; i++) Q[i] = (1 - lam) * A[i] + lam * B[i];
  ctr_solve(Q, R, s);
  ctr_mul(A, s, As);
  ctr_mul(B, s, Bs);
  ctr_real alpha = 0;
  ctr_real const w1[3] = {tr->w1[0], tr->w1[1], tr->w1[2]}, w2[3] = {tr->w2[0], tr->w2[1], tr->w2[2]};
  c[0] = w1[1] * As[2] - w1[2] * As[1]; c[1] = w1[2] * As[0] - w1[0] * As[2]; c[2] = w1[0] * As[1] - w1[1] * As[0];
  alpha += (1 - lam) * ctr_dot(s, c);
  c[0] = w2[1] * Bs[2] - w2[2] * Bs[1]; c[1] = w2[2] * Bs[0] - w2[0] * Bs[2]; c[2] = w2[0] * Bs[1] - w2[1] * Bs[0];
  alpha += lam * ctr_dot(s, c);
  ctr_real const ss = ctr_dot(s, s);
  ct_unit(g, e);
  ctr_real es = (e[0] * s[0] + e[1] * s[1] + e[2] * s[2]) / ss, p[3], pn = 0;
  for (int i = 0; i < 3; i++) { p[i] = e[i] - es * s[i]; pn += p[i] * p[i]; }
  pn = sqrtl(pn);
  double const speed = (a1 + a2) * (2.0 + 4.0 * ct_uniform(g));
  for (int i = 0; i < 3; i++) {
    tr->v[i] = (double)(speed * p[i] / pn + alpha * s[i] / ss);
    tr->r0[i] = (double)(R[i] - 0.5L * tr->v[i]);
  }
}

static inline void ct_make(ct_rng *g, double lo, double hi, int kind, int k, ct_traj *tr) {
  double a1, a2, d[3], e[3];
  ct_ellipsoid(g, lo, hi, tr->q1, &a1);
  ct_ellipsoid(g, lo, hi, tr->q2, &a2);
  tr->t_max = 1.0;
  for (int i = 0; i < 3; i++) tr->w1[i] = tr->w2[i] = 0.0;
  ct_unit(g, d);
  static const double deltas[6] = {1e-6, -1e-6, 1e-9, -1e-9, 1e-12, -1e-12};
  if (kind == CT_GRAZING) {
    ct_graze(g, a1, a2, d, deltas[k % 6], tr);
    return;
  }
  if (kind == CT_ROTGRAZE) {
    ct_rotgraze(g, a1, a2, d, deltas[k % 6], tr);
    return;
  }
  double dist = (a1 + a2) * (1.1 + 1.9 * ct_uniform(g));
  ct_unit(g, e);
  double off = (a1 + a2) * ct_uniform(g);
  for (int i = 0; i < 3; i++) tr->r0[i] = dist * d[i];
  /* v: towards -r0, plus an offset perpendicular-ish, reaching in ~t_max/2 */
  double speed = dist * (1.0 + 2.0 * ct_uniform(g));
  for (int i = 0; i < 3; i++) tr->v[i] = -speed * d[i] + 2.0 * off * e[i];
  double turns = kind == CT_SPINNING ? 2.0 + 3.0 * ct_uniform(g) : 0.5 * ct_uniform(g);
  double u[3];
  ct_unit(g, u);
  for (int i = 0; i < 3; i++) tr->w1[i] = 2 * CT_PI * turns * u[i];
  turns = kind == CT_SPINNING ? 2.0 + 3.0 * ct_uniform(g) : 0.5 * ct_uniform(g);
  ct_unit(g, u);
  for (int i = 0; i < 3; i++) tr->w2[i] = 2 * CT_PI * turns * u[i];
}

#endif /* PW85_CT_REFERENCE_H */
