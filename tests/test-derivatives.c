/* Tests of pw85_contact_derivatives and its batch forms
 * (docs/derivatives.md). The reference is computed in __float128 from the
 * double inputs, independently of the library: lambda* maximises f by
 * bisection on the sign of f' then Newton steps, Q^{-1} by the adjugate, then
 * the formulas (E1)-(E6) with f'' in its classical form
 * -2 phi + 2 (1 - 2 lambda) phi' + lambda (1 - lambda) phi'' (not the form
 * (E5) the library uses). The formulas themselves are checked against
 * central finite differences of mu^2 computed in __float128. */
#include <float.h>
#include <math.h>
#include <pw85.h>
#include <string.h>

#include "refdata.h"
#include "testutil.h"

typedef __float128 quad;

static void q_adj(const quad a[6], quad c[6], quad *det) {
  c[0] = a[3] * a[5] - a[4] * a[4];
  c[1] = a[2] * a[4] - a[1] * a[5];
  c[2] = a[1] * a[4] - a[2] * a[3];
  c[3] = a[0] * a[5] - a[2] * a[2];
  c[4] = a[1] * a[2] - a[0] * a[4];
  c[5] = a[0] * a[3] - a[1] * a[1];
  *det = a[0] * c[0] + a[1] * c[1] + a[2] * c[2];
}
static void q_mul(const quad a[6], const quad v[3], quad o[3]) {
  o[0] = a[0] * v[0] + a[1] * v[1] + a[2] * v[2];
  o[1] = a[1] * v[0] + a[3] * v[1] + a[4] * v[2];
  o[2] = a[2] * v[0] + a[4] * v[1] + a[5] * v[2];
}
static quad q_dot(const quad a[3], const quad b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
/* 2-norm, scaled so that tiny or huge entries neither underflow nor overflow. */
static double q_norm(const quad *a, int n) {
  quad m = 0, s = 0;
  for (int i = 0; i < n; i++) m = a[i] > m ? a[i] : (-a[i] > m ? -a[i] : m);
  if (m == 0) return 0;
  for (int i = 0; i < n; i++) s += (a[i] / m) * (a[i] / m);
  return (double)m * sqrt((double)s);
}
static void q_cross(const quad a[3], const quad b[3], quad o[3]) {
  o[0] = a[1] * b[2] - a[2] * b[1];
  o[1] = a[2] * b[0] - a[0] * b[2];
  o[2] = a[0] * b[1] - a[1] * b[0];
}

/* Exact derivatives (quad) of one pair given in quad. */
typedef struct {
  quad lambda, mu2, g[3], t1[3], t2[3], dq1[6], dq2[6], h[6], x0[3], xr[3];
} qderiv;

/* f' and f'' at lam; s = Q^{-1} r, inverse qi. */
static void q_at(quad lam, const quad R[3], const quad A[6], const quad B[6], quad s[3],
                 quad qi[6], quad *fp, quad *fpp, quad ds[3], quad v[3]) {
  quad Q[6], D[6], det, t[3], u[3];
  for (int i = 0; i < 6; i++) {
    Q[i] = (1 - lam) * A[i] + lam * B[i];
    D[i] = B[i] - A[i];
  }
  q_adj(Q, qi, &det);
  for (int i = 0; i < 6; i++) qi[i] /= det;
  q_mul(qi, R, s);
  q_mul(A, s, t);
  q_mul(B, s, u);
  *fp = (1 - lam) * (1 - lam) * q_dot(s, t) - lam * lam * q_dot(s, u);
  q_mul(D, s, ds);
  q_mul(qi, ds, v);
  *fpp = -2 * q_dot(R, s) - 2 * (1 - 2 * lam) * q_dot(s, ds) + 2 * lam * (1 - lam) * q_dot(ds, v);
}

static void q_derivs(const quad R[3], const quad A[6], const quad B[6], qderiv *o) {
  quad s[3], qi[6], fp, fpp, ds[3], v[3], lo = 0, hi = 1, lam;
  for (int it = 0; it < 60; it++) { /* f concave: f' decreasing */
    lam = 0.5 * (lo + hi);
    q_at(lam, R, A, B, s, qi, &fp, &fpp, ds, v);
    if (fp > 0) lo = lam; else hi = lam;
  }
  lam = 0.5 * (lo + hi);
  for (int it = 0; it < 4; it++) {
    q_at(lam, R, A, B, s, qi, &fp, &fpp, ds, v);
    lam -= fp / fpp;
  }
  q_at(lam, R, A, B, s, qi, &fp, &fpp, ds, v);
  quad p = lam * (1 - lam), t[3], u[3], hv[3];
  o->lambda = lam;
  o->mu2 = p * q_dot(R, s);
  q_mul(A, s, t);
  q_mul(B, s, u);
  for (int i = 0; i < 3; i++) {
    o->g[i] = 2 * p * s[i];
    o->x0[i] = (1 - lam) * t[i];
    o->xr[i] = o->x0[i] - R[i];
    hv[i] = 2 * (1 - 2 * lam) * s[i] - 2 * p * v[i];
  }
  q_cross(o->x0, o->g, o->t1);
  for (int i = 0; i < 3; i++) o->t1[i] = -o->t1[i];
  q_cross(o->xr, o->g, o->t2);
  static const int I[6] = {0, 0, 0, 1, 1, 2}, J[6] = {0, 1, 2, 1, 2, 2};
  for (int k = 0; k < 6; k++) {
    quad w = I[k] == J[k] ? 1 : 2;
    o->dq1[k] = -w * p * (1 - lam) * s[I[k]] * s[J[k]];
    o->dq2[k] = -w * p * lam * s[I[k]] * s[J[k]];
    o->h[k] = 2 * p * qi[k] - hv[I[k]] * hv[J[k]] / fpp;
  }
}

static void to_quad(const double *x, quad *y, int n) {
  for (int i = 0; i < n; i++) y[i] = x[i];
}

static double rel_q(const double *act, const quad *ref, int n, double scale) {
  quad e[6];
  for (int i = 0; i < n; i++) e[i] = (quad)act[i] - ref[i];
  return q_norm(e, n) / scale;
}
/* Frobenius norm of a stored symmetric matrix (off-diagonal entries twice). */
static double sym_norm(const quad *a) {
  quad b[9] = {a[0], a[3], a[5], a[1], a[1], a[2], a[2], a[4], a[4]};
  return q_norm(b, 9);
}
static double sym_err(const double *act, const quad *ref) {
  quad e[6];
  for (int i = 0; i < 6; i++) e[i] = (quad)act[i] - ref[i];
  return sym_norm(e) / sym_norm(ref);
}

/* Bounds of the issue (docs/derivatives.md, "Accuracy"): gradient 1e-14
 * relative (2-norm); torques 1e-13 relative to |x0| |g| and |x0 - r| |g|;
 * d_q1, d_q2 1e-14 relative (2-norm of the six stored entries); Hessian 1e-12
 * relative (Frobenius norm); lambda 4 ulps of 1, mu2 1e-14 relative. */
static const double kTolG = 1e-14, kTolT = 1e-13, kTolQ = 1e-14, kTolH = 1e-12;

typedef struct {
  double g, t1, t2, dq, h, lambda;
  double cg, ch; /* conditioning: exact g, H after a 1-ulp perturbation */
  size_t n;
} maxima;

/* The problem's own conditioning: relative change of the exact gradient and
 * Hessian when every input double moves by one ulp in a random direction
 * (a reported measurement, docs/derivatives.md; no assertion). */
static void conditioning(const double r[3], const double q1[6], const double q2[6],
                         const qderiv *o, GRand *rng, maxima *mx) {
  double in[15];
  memcpy(in, r, sizeof(double[3]));
  memcpy(in + 3, q1, sizeof(double[6]));
  memcpy(in + 9, q2, sizeof(double[6]));
  for (int i = 0; i < 15; i++) in[i] = nextafter(in[i], g_rand_boolean(rng) ? INFINITY : -INFINITY);
  quad R[3], A[6], B[6], e[3];
  to_quad(in, R, 3);
  to_quad(in + 3, A, 6);
  to_quad(in + 9, B, 6);
  qderiv p;
  q_derivs(R, A, B, &p);
  for (int i = 0; i < 3; i++) e[i] = p.g[i] - o->g[i];
  mx->cg = fmax(mx->cg, q_norm(e, 3) / q_norm(o->g, 3));
  quad eh[6];
  for (int k = 0; k < 6; k++) eh[k] = p.h[k] - o->h[k];
  mx->ch = fmax(mx->ch, sym_norm(eh) / sym_norm(o->h));
}

/* PW85_DERIVATIVES_FORCES against the full call of the pair, whose status
 * is full_status and fields *full (include/pw85.h): where the full call
 * returns PW85_OK or PW85_ERR_INACCURATE, the same status, the same bits in
 * mu2, lambda, d_r12, d_theta1 and d_theta2 (the first 11 doubles), and NaN
 * in d_q1, d_q2 and hess_r12. Returns 1 when the pair was compared. */
static int check_forces_pair(const double r[3], const double q1[6], const double q2[6],
                             int full_status, const pw85_derivatives_t *full) {
  if (full_status != PW85_OK && full_status != PW85_ERR_INACCURATE) return 0;
  pw85_derivatives_t f;
  g_assert_cmpint(pw85_contact_derivatives_ex(r, q1, q2, PW85_DERIVATIVES_FORCES, &f), ==,
                  full_status);
  g_assert_cmpmem(&f, 11 * sizeof(double), full, 11 * sizeof(double));
  for (int k = 0; k < 6; k++) {
    g_assert_true(isnan(f.d_q1[k]));
    g_assert_true(isnan(f.d_q2[k]));
    g_assert_true(isnan(f.hess_r12[k]));
  }
  pw85_derivatives_t a;  /* PW85_DERIVATIVES_ALL: the call without flags, bit for bit */
  g_assert_cmpint(pw85_contact_derivatives_ex(r, q1, q2, PW85_DERIVATIVES_ALL, &a), ==,
                  full_status);
  g_assert_cmpmem(&a, sizeof a, full, sizeof a);
  return 1;
}

static void check_pair(const double r[3], const double q1[6], const double q2[6], maxima *mx,
                       GRand *rng) {
  pw85_derivatives_t d;
  int st = pw85_contact_derivatives(r, q1, q2, &d);
  g_assert_cmpint(st, ==, PW85_OK);
  check_forces_pair(r, q1, q2, st, &d);
  quad R[3], A[6], B[6];
  to_quad(r, R, 3);
  to_quad(q1, A, 6);
  to_quad(q2, B, 6);
  qderiv o;
  q_derivs(R, A, B, &o);
  double ng = q_norm(o.g, 3);
  double eg = rel_q(d.d_r12, o.g, 3, ng);
  double et1 = rel_q(d.d_theta1, o.t1, 3, q_norm(o.x0, 3) * ng);
  double et2 = rel_q(d.d_theta2, o.t2, 3, q_norm(o.xr, 3) * ng);
  double eq = fmax(rel_q(d.d_q1, o.dq1, 6, q_norm(o.dq1, 6)), rel_q(d.d_q2, o.dq2, 6, q_norm(o.dq2, 6)));
  double eh = sym_err(d.hess_r12, o.h);
  double el = fabs((double)((quad)d.lambda - o.lambda));
  double em = fabs((double)(((quad)d.mu2 - o.mu2) / o.mu2));
  mx->g = fmax(mx->g, eg);
  mx->t1 = fmax(mx->t1, et1);
  mx->t2 = fmax(mx->t2, et2);
  mx->dq = fmax(mx->dq, eq);
  mx->h = fmax(mx->h, eh);
  mx->lambda = fmax(mx->lambda, el);
  mx->n++;
  conditioning(r, q1, q2, &o, rng, mx);
  if (!(eg <= kTolG && et1 <= kTolT && et2 <= kTolT && eq <= kTolQ && eh <= kTolH &&
        el <= 4 * DBL_EPSILON && em <= 1e-14))
    g_test_message("pair failing: g %.2e t1 %.2e t2 %.2e q %.2e h %.2e lambda %.2e mu2 %.2e",
                   eg, et1, et2, eq, eh, el, em);
  g_assert_cmpfloat(eg, <=, kTolG);
  g_assert_cmpfloat(et1, <=, kTolT);
  g_assert_cmpfloat(et2, <=, kTolT);
  g_assert_cmpfloat(eq, <=, kTolQ);
  g_assert_cmpfloat(eh, <=, kTolH);
  g_assert_cmpfloat(el, <=, 4 * DBL_EPSILON);
  g_assert_cmpfloat(em, <=, 1e-14);
}

static void check_group(const char *group, size_t stride) {
  RefPairs *p = refdata_pairs_or_skip(group);
  if (p == NULL) return;
  maxima mx[4];
  memset(mx, 0, sizeof mx);
  GRand *rng = g_rand_new_with_seed(11);
  for (size_t i = 0; i < p->n; i += stride) {
    if (p->mu2[i] == 0.0 || p->cls[i] < 0 || p->cls[i] > 3) continue;
    check_pair(p->r12 + 3 * i, p->q1 + 6 * i, p->q2 + 6 * i, &mx[p->cls[i]], rng);
  }
  for (int c = 0; c < 4; c++) {
    g_test_message("%s class %d (%zu pairs): max rel err g %.2e theta1 %.2e theta2 %.2e "
                   "q %.2e hess %.2e lambda %.2e; 1-ulp conditioning g %.2e hess %.2e",
                   group, c, mx[c].n, mx[c].g, mx[c].t1, mx[c].t2, mx[c].dq, mx[c].h,
                   mx[c].lambda, mx[c].cg, mx[c].ch);
    g_assert_cmpuint(mx[c].n, >=, 100);
  }
  g_rand_free(rng);
  refdata_pairs_free(p);
}

static size_t stride(void) { return g_test_slow() ? 1 : 4; }
static void test_contact(void) { check_group("/contact", stride()); }
static void test_near_contact(void) { check_group("/near_contact", stride()); }

/* ---- The formulas against finite differences (all in quad; step 1e-12 relative: truncation ~1e-24, rounding ~1e-22) */

static quad q_mu2(const quad R[3], const quad A[6], const quad B[6]) {
  qderiv o;
  q_derivs(R, A, B, &o);
  return o.mu2;
}

/* Q -> R Q R^T for the rotation by angle h about axis e_ax (Rodrigues, sin
 * and cos by their series: |h| <= 1e-6). */
static void q_rotate(const quad A[6], int ax, quad h, quad out[6]) {
  quad sn = h - h * h * h / 6 + h * h * h * h * h / 120, cs = 1 - h * h / 2 + h * h * h * h / 24;
  quad M[3][3], Rm[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, T[3][3];
  static const int idx[3][3] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) M[i][j] = A[idx[i][j]];
  int a = (ax + 1) % 3, b = (ax + 2) % 3;
  Rm[a][a] = cs;
  Rm[b][b] = cs;
  Rm[a][b] = -sn;
  Rm[b][a] = sn;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      T[i][j] = 0;
      for (int k = 0; k < 3; k++) T[i][j] += Rm[i][k] * M[k][j];
    }
  for (int i = 0; i < 3; i++)
    for (int j = i; j < 3; j++) {
      quad s = 0;
      for (int k = 0; k < 3; k++) s += T[i][k] * Rm[j][k];
      out[idx[i][j]] = s;
    }
}

static void test_formulas_fd(void) {
  GRand *rng = g_rand_new_with_seed(20261125);
  const double lo[2] = {0.5, 0.1}, hi[2] = {2.0, 10.0};
  for (int t = 0; t < 40; t++) {
    int c = t % 2;
    double rad1[3], rad2[3], ax1[9], ax2[9], q1[6], q2[6], r[3];
    random_radii(rng, lo[c], hi[c], rad1);
    random_radii(rng, lo[c], hi[c], rad2);
    random_axes(rng, ax1);
    random_axes(rng, ax2);
    make_q(rad1, ax1, q1);
    make_q(rad2, ax2, q2);
    for (int i = 0; i < 3; i++) r[i] = g_rand_double_range(rng, -3 * hi[c], 3 * hi[c]);
    quad R[3], A[6], B[6];
    to_quad(r, R, 3);
    to_quad(q1, A, 6);
    to_quad(q2, B, 6);
    qderiv o;
    q_derivs(R, A, B, &o);
    quad nr = q_norm(R, 3), h = 1e-12 * nr, fd[6], e[6];
    /* gradient */
    for (int i = 0; i < 3; i++) {
      quad Rp[3], Rm[3];
      memcpy(Rp, R, sizeof R);
      memcpy(Rm, R, sizeof R);
      Rp[i] += h;
      Rm[i] -= h;
      fd[i] = (q_mu2(Rp, A, B) - q_mu2(Rm, A, B)) / (2 * h);
      e[i] = fd[i] - o.g[i];
    }
    g_assert_cmpfloat(q_norm(e, 3) / q_norm(o.g, 3), <=, 1e-15);
    /* stored entries of Q1, Q2 (off-diagonal q[k] moves Q_ij and Q_ji) */
    for (int m = 0; m < 2; m++) {
      const quad *Q = m ? B : A;
      quad hq = 1e-12 * q_norm(Q, 6);
      for (int k = 0; k < 6; k++) {
        quad Qp[6], Qm[6];
        memcpy(Qp, Q, sizeof Qp);
        memcpy(Qm, Q, sizeof Qm);
        Qp[k] += hq;
        Qm[k] -= hq;
        fd[k] = m ? (q_mu2(R, A, Qp) - q_mu2(R, A, Qm)) / (2 * hq)
                  : (q_mu2(R, Qp, B) - q_mu2(R, Qm, B)) / (2 * hq);
        e[k] = fd[k] - (m ? o.dq2[k] : o.dq1[k]);
      }
      g_assert_cmpfloat(q_norm(e, 6) / q_norm(m ? o.dq2 : o.dq1, 6), <=, 1e-14);
    }
    /* rotations about each centre */
    for (int m = 0; m < 2; m++) {
      quad ha = 1e-12;
      for (int i = 0; i < 3; i++) {
        quad Qp[6], Qm[6];
        q_rotate(m ? B : A, i, ha, Qp);
        q_rotate(m ? B : A, i, -ha, Qm);
        fd[i] = m ? (q_mu2(R, A, Qp) - q_mu2(R, A, Qm)) / (2 * ha)
                  : (q_mu2(R, Qp, B) - q_mu2(R, Qm, B)) / (2 * ha);
        e[i] = fd[i] - (m ? o.t2[i] : o.t1[i]);
      }
      quad const *arm = m ? o.xr : o.x0;
      g_assert_cmpfloat(q_norm(e, 3) / (q_norm(arm, 3) * q_norm(o.g, 3)), <=, 1e-14);
    }
    /* Hessian: central differences of the gradient (E1) */
    quad H[3][3];
    for (int j = 0; j < 3; j++) {
      quad Rp[3], Rm[3];
      qderiv op, om;
      memcpy(Rp, R, sizeof R);
      memcpy(Rm, R, sizeof R);
      Rp[j] += h;
      Rm[j] -= h;
      q_derivs(Rp, A, B, &op);
      q_derivs(Rm, A, B, &om);
      for (int i = 0; i < 3; i++) H[i][j] = (op.g[i] - om.g[i]) / (2 * h);
    }
    quad hs[6] = {H[0][0], H[0][1], H[0][2], H[1][1], H[1][2], H[2][2]};
    for (int k = 0; k < 6; k++) e[k] = hs[k] - o.h[k];
    g_assert_cmpfloat(sym_norm(e) / sym_norm(o.h), <=, 1e-14);
    g_assert_cmpfloat(fabs((double)(H[0][1] - H[1][0])), <=, 1e-14 * sym_norm(o.h));
  }
  g_rand_free(rng);
}

/* ---- Known values, bad input, batch forms ------------------------------- */

/* Spheres of radii a1, a2: mu2 = |r|^2 / (a1 + a2)^2, lambda = a1 / (a1 + a2),
 * g = 2 r / (a1 + a2)^2, H = 2 I / (a1 + a2)^2, torques 0. */
static void test_spheres(void) {
  double q1[6] = {2.25, 0, 0, 2.25, 0, 2.25}, q2[6] = {1, 0, 0, 1, 0, 1}, r[3] = {1.5, 2.0, 0.0};
  pw85_derivatives_t d;
  g_assert_cmpint(pw85_contact_derivatives(r, q1, q2, &d), ==, PW85_OK);
  g_assert_cmpfloat(fabs(d.lambda - 0.6), <=, 2 * DBL_EPSILON);
  g_assert_cmpfloat(fabs(d.d_r12[0] - 2 * 1.5 / 6.25), <=, 4 * DBL_EPSILON);
  g_assert_cmpfloat(fabs(d.d_r12[1] - 2 * 2.0 / 6.25), <=, 4 * DBL_EPSILON);
  g_assert_cmpfloat(fabs(d.d_r12[2]), <=, 4 * DBL_EPSILON);
  for (int i = 0; i < 3; i++) {
    g_assert_cmpfloat(fabs(d.d_theta1[i]), <=, 4 * DBL_EPSILON);
    g_assert_cmpfloat(fabs(d.d_theta2[i]), <=, 4 * DBL_EPSILON);
  }
  const double hexp[6] = {2 / 6.25, 0, 0, 2 / 6.25, 0, 2 / 6.25};
  for (int k = 0; k < 6; k++) g_assert_cmpfloat(fabs(d.hess_r12[k] - hexp[k]), <=, 8 * DBL_EPSILON);
}

/* mu^2(2^k r, 2^2k Q1, 2^2k Q2) = mu^2(r, Q1, Q2): g scales by 2^-k, d_q and
 * the Hessian by 2^-2k, the torques not, also where 2^2k Q is far out of the
 * range of a direct solve. */
static void test_scaling(void) {
  double r[3] = {1.2, 0.3, -0.4}, q1[6] = {1, 0.1, 0.2, 2, 0.3, 0.5}, q2[6] = {0.3, 0, 0.05, 0.4, 0, 0.9};
  pw85_derivatives_t d0, d;
  g_assert_cmpint(pw85_contact_derivatives(r, q1, q2, &d0), ==, PW85_OK);
  const int ks[6] = {-500, -200, -40, 40, 200, 500};
  for (int m = 0; m < 6; m++) {
    int k = ks[m];
    double rs[3], a[6], b[6];
    for (int i = 0; i < 3; i++) rs[i] = ldexp(r[i], k);
    for (int i = 0; i < 6; i++) {
      a[i] = ldexp(q1[i], 2 * k);
      b[i] = ldexp(q2[i], 2 * k);
    }
    g_assert_cmpint(pw85_contact_derivatives(rs, a, b, &d), ==, PW85_OK);
    g_assert_cmpfloat(fabs(d.mu2 - d0.mu2), <=, 4 * DBL_EPSILON * d0.mu2);
    for (int i = 0; i < 3; i++) {
      g_assert_cmpfloat(fabs(ldexp(d.d_r12[i], k) - d0.d_r12[i]), <=, 1e-15 * fabs(d0.d_r12[0]) * 4);
      g_assert_cmpfloat(fabs(d.d_theta1[i] - d0.d_theta1[i]), <=, 1e-15 * fabs(d0.d_theta1[0]) * 4);
    }
    for (int i = 0; i < 6; i++) {
      g_assert_cmpfloat(fabs(ldexp(d.hess_r12[i], 2 * k) - d0.hess_r12[i]), <=, 1e-14 * fabs(d0.hess_r12[0]));
      g_assert_cmpfloat(fabs(ldexp(d.d_q2[i], 2 * k) - d0.d_q2[i]), <=, 1e-14 * fabs(d0.d_q2[0]));
    }
  }
}

static int all_nan(const pw85_derivatives_t *d) {
  const double *p = &d->mu2;
  for (size_t i = 0; i < sizeof *d / sizeof(double); i++)
    if (!isnan(p[i])) return 0;
  return 1;
}

static void test_bad_input(void) {
  double q[6] = {1, 0, 0, 1, 0, 1}, r[3] = {1, 0, 0}, zero[3] = {0, 0, 0};
  double notspd[6] = {1, 2, 0, 1, 0, 1}, nanr[3] = {NAN, 0, 0}, infq[6] = {INFINITY, 0, 0, 1, 0, 1};
  pw85_derivatives_t d;
  g_assert_cmpint(sizeof d, ==, 29 * sizeof(double));
  g_assert_cmpint(pw85_contact_derivatives(r, q, q, NULL), ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_contact_derivatives(NULL, q, q, &d), ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_true(all_nan(&d));
  g_assert_cmpint(pw85_contact_derivatives(r, NULL, q, &d), ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_contact_derivatives(r, q, NULL, &d), ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_true(all_nan(&d));
  g_assert_cmpint(pw85_contact_derivatives(r, q, q, &d), ==, PW85_OK);
  g_assert_false(all_nan(&d));
  g_assert_cmpint(pw85_contact_derivatives(zero, q, q, &d), ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_true(all_nan(&d));
  g_assert_cmpint(pw85_contact_derivatives(r, q, q, &d), ==, PW85_OK);
  g_assert_cmpint(pw85_contact_derivatives(nanr, q, q, &d), ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_true(all_nan(&d));
  g_assert_cmpint(pw85_contact_derivatives(r, infq, q, &d), ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_true(all_nan(&d));
  g_assert_cmpint(pw85_contact_derivatives(r, q, notspd, &d), ==, PW85_ERR_NOT_SPD);
  g_assert_true(all_nan(&d));
  /* flags other than PW85_DERIVATIVES_ALL and PW85_DERIVATIVES_FORCES */
  unsigned const bad_flags[] = {2u, 3u, 0x80000000u, ~0u};
  for (size_t i = 0; i < sizeof bad_flags / sizeof bad_flags[0]; i++) {
    g_assert_cmpint(pw85_contact_derivatives(r, q, q, &d), ==, PW85_OK);
    g_assert_cmpint(pw85_contact_derivatives_ex(r, q, q, bad_flags[i], &d), ==,
                    PW85_ERR_INVALID_ARGUMENT);
    g_assert_true(all_nan(&d));
  }
  g_assert_cmpint(pw85_contact_derivatives_ex(r, q, q, PW85_DERIVATIVES_FORCES, NULL), ==,
                  PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_contact_derivatives_ex(zero, q, q, PW85_DERIVATIVES_FORCES, &d), ==,
                  PW85_ERR_INVALID_ARGUMENT);
  g_assert_true(all_nan(&d));
  g_assert_cmpint(pw85_contact_derivatives_ex(r, q, notspd, PW85_DERIVATIVES_FORCES, &d), ==,
                  PW85_ERR_NOT_SPD);
  g_assert_true(all_nan(&d));
}

/* n ellipsoids of semi-axes in [amin, 1], random orientations, centres in
 * [0, side)^3, and m random pairs (i, j), i != j, with their per-pair arrays
 * r12 = c_j - c_i, q1 = q_i, q2 = q_j. */
static void random_scene(GRand *rng, int n, int m, double amin, double side, double *centres,
                         double *q, long long *pairs, double *r12, double *q1, double *q2) {
  for (int i = 0; i < n; i++) {
    double rad[3], ax[9];
    random_radii(rng, amin, 1.0, rad);
    random_axes(rng, ax);
    make_q(rad, ax, q + 6 * i);
    for (int c = 0; c < 3; c++) centres[3 * i + c] = g_rand_double_range(rng, 0.0, side);
  }
  for (int k = 0; k < m; k++) {
    int i = g_rand_int_range(rng, 0, n), j = (i + 1 + g_rand_int_range(rng, 0, n - 1)) % n;
    pairs[2 * k] = i;
    pairs[2 * k + 1] = j;
    for (int c = 0; c < 3; c++) r12[3 * k + c] = centres[3 * j + c] - centres[3 * i + c];
    memcpy(q1 + 6 * k, q + 6 * i, sizeof(double[6]));
    memcpy(q2 + 6 * k, q + 6 * j, sizeof(double[6]));
  }
}

/* The batch forms with PW85_DERIVATIVES_FORCES: bitwise the one-pair
 * PW85_DERIVATIVES_FORCES call (and so the full call's fields, above), for
 * 1000 random pairs of semi-axes in [0.001, 1] (lanes and their fallbacks);
 * bad flags write nothing. */
static void test_batch_forces(void) {
  GRand *rng = g_rand_new_with_seed(23);
  enum { N = 200, M = 1000 };
  static double centres[3 * N], q[6 * N], r12[3 * M], q1[6 * M], q2[6 * M];
  static long long pairs[2 * M];
  static pw85_derivatives_t d[M], ds[M];
  static int status[M], status_s[M];
  random_scene(rng, N, M, 0.001, 3.0, centres, q, pairs, r12, q1, q2);
  int compared = 0;
  for (int nt = 0; nt <= 2; nt += 2) {
    g_assert_cmpint(pw85_contact_derivatives_pairs_ex(M, r12, q1, q2, PW85_DERIVATIVES_FORCES, d,
                                                      status, nt), ==, PW85_OK);
    g_assert_cmpint(pw85_scene_contact_derivatives_ex(N, centres, q, NULL, M, pairs,
                                                      PW85_DERIVATIVES_FORCES, ds, status_s, nt),
                    ==, PW85_OK);
    for (int k = 0; k < M; k++) {
      pw85_derivatives_t one, full;
      int const s = pw85_contact_derivatives_ex(r12 + 3 * k, q1 + 6 * k, q2 + 6 * k,
                                                PW85_DERIVATIVES_FORCES, &one);
      g_assert_cmpint(status[k], ==, s);
      g_assert_cmpint(status_s[k], ==, s);
      g_assert_cmpmem(&one, sizeof one, d + k, sizeof one);
      g_assert_cmpmem(&one, sizeof one, ds + k, sizeof one);
      compared += check_forces_pair(r12 + 3 * k, q1 + 6 * k, q2 + 6 * k,
                                    pw85_contact_derivatives(r12 + 3 * k, q1 + 6 * k, q2 + 6 * k,
                                                             &full), &full);
    }
  }
  g_assert_cmpint(compared, ==, 2 * M);
  /* bad flags: PW85_ERR_INVALID_ARGUMENT, nothing written */
  memset(status, 0x7f, sizeof status);
  memset(d, 0x7f, sizeof d);
  g_assert_cmpint(pw85_contact_derivatives_pairs_ex(M, r12, q1, q2, 2u, d, status, 0), ==,
                  PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_scene_contact_derivatives_ex(N, centres, q, NULL, M, pairs, ~0u, d,
                                                    status, 0), ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(status[0], ==, 0x7f7f7f7f);
  g_assert_cmpint(status[M - 1], ==, 0x7f7f7f7f);
  unsigned char const *bytes = (unsigned char const *)d;
  for (size_t i = 0; i < sizeof d; i++) g_assert_cmpint(bytes[i], ==, 0x7f);
  g_rand_free(rng);
}

/* Batch forms: bitwise the one-pair call, per-pair statuses, lowest failing
 * pair's status returned, call errors write nothing. */
static void test_batch(void) {
  GRand *rng = g_rand_new_with_seed(7);
  enum { N = 40, M = 100 };
  double centres[3 * N], q[6 * N], r12[3 * M], q1[6 * M], q2[6 * M];
  long long pairs[2 * M];
  random_scene(rng, N, M, 0.1, 10.0, centres, q, pairs, r12, q1, q2);
  q1[6 * 37] = NAN;    /* pair 37 fails in the per-pair form */
  pairs[2 * 53] = N;   /* pair 53 out of range in the scene form */
  pw85_derivatives_t d[M], one;
  int status[M];
  for (int nt = 0; nt <= 2; nt++) {
    g_assert_cmpint(pw85_contact_derivatives_pairs(M, r12, q1, q2, d, status, nt), ==,
                    PW85_ERR_INVALID_ARGUMENT);
    for (int k = 0; k < M; k++) {
      int s = pw85_contact_derivatives(r12 + 3 * k, q1 + 6 * k, q2 + 6 * k, &one);
      g_assert_cmpint(status[k], ==, s);
      g_assert_cmpmem(&one, sizeof one, d + k, sizeof one);
    }
    g_assert_cmpint(status[37], ==, PW85_ERR_INVALID_ARGUMENT);
    g_assert_cmpint(pw85_scene_contact_derivatives(N, centres, q, NULL, M, pairs, d, status, nt),
                    ==, PW85_ERR_INVALID_ARGUMENT);
    for (int k = 0; k < M; k++) {
      if (k == 53) {
        g_assert_cmpint(status[k], ==, PW85_ERR_INVALID_ARGUMENT);
        g_assert_true(all_nan(d + k));
        continue;
      }
      int s = pw85_contact_derivatives(r12 + 3 * k, q + 6 * pairs[2 * k], q + 6 * pairs[2 * k + 1], &one);
      g_assert_cmpint(status[k], ==, s);
      g_assert_cmpmem(&one, sizeof one, d + k, sizeof one);
    }
  }
  /* periodic box: r12 is the minimum image */
  double box[6] = {10, 10, 10, 0, 0, 0};
  pairs[2 * 53] = 0;
  g_assert_cmpint(pw85_scene_contact_derivatives(N, centres, q, box, M, pairs, d, status, 2), ==,
                  PW85_OK);
  for (int k = 0; k < M; k++) {
    double r[3];
    for (int c = 0; c < 3; c++) {
      r[c] = centres[3 * pairs[2 * k + 1] + c] - centres[3 * pairs[2 * k] + c];
      r[c] -= 10.0 * nearbyint(r[c] / 10.0);
    }
    int s = pw85_contact_derivatives(r, q + 6 * pairs[2 * k], q + 6 * pairs[2 * k + 1], &one);
    g_assert_cmpint(s, ==, PW85_OK);
    for (int c = 0; c < 3; c++) g_assert_cmpfloat(fabs(one.d_r12[c] - d[k].d_r12[c]), <=, 1e-12 * fabs(one.d_r12[c]) + 1e-300);
  }
  /* call errors: nothing written */
  memset(status, 0x7f, sizeof status);
  g_assert_cmpint(pw85_contact_derivatives_pairs(0, NULL, NULL, NULL, NULL, NULL, 0), ==, PW85_OK);
  g_assert_cmpint(pw85_contact_derivatives_pairs(-1, r12, q1, q2, d, status, 0), ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_contact_derivatives_pairs(M, r12, q1, q2, NULL, status, 0), ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_contact_derivatives_pairs(M, r12, q1, q2, d, status, -1), ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_scene_contact_derivatives(-1, centres, q, NULL, M, pairs, d, status, 0), ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_scene_contact_derivatives(N, centres, NULL, NULL, M, pairs, d, status, 0), ==, PW85_ERR_INVALID_ARGUMENT);
  double badbox[6] = {-1, 10, 10, 0, 0, 0};
  g_assert_cmpint(pw85_scene_contact_derivatives(N, centres, q, badbox, M, pairs, d, status, 0), ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(status[0], ==, 0x7f7f7f7f);
  g_rand_free(rng);
}

/* The batch forms take DEFAULT from its lanes (docs/batch.md) and continue
 * from that solution: their results must be the one-pair call's, bit for
 * bit, in every class, for pairs the one-pair call rescales (magnitudes far
 * from 1) and for pairs it rejects, in every lane position. */
static void test_batch_lanes(void) {
  GRand *rng = g_rand_new_with_seed(11);
  enum { M = 4 * 256 + 5, N = 2 * M };
  static double r12[3 * M], q1[6 * M], q2[6 * M], centres[3 * N], q[6 * N];
  static long long pairs[2 * M];
  static pw85_derivatives_t d[M];
  static int status[M];
  const double lo[4] = {0.5, 0.1, 0.01, 0.001}, hi[4] = {2.0, 10.0, 100.0, 1000.0};
  for (int k = 0; k < M; k++) {
    int c = k % 4;
    double rad1[3], rad2[3], ax[9], dir[3], n2 = 0.0;
    random_radii(rng, lo[c], hi[c], rad1);
    random_axes(rng, ax);
    make_q(rad1, ax, q1 + 6 * k);
    random_radii(rng, lo[c], hi[c], rad2);
    random_axes(rng, ax);
    make_q(rad2, ax, q2 + 6 * k);
    for (int i = 0; i < 3; i++) {
      dir[i] = g_rand_double_range(rng, -1.0, 1.0);
      n2 += dir[i] * dir[i];
    }
    double reach = fmax(rad1[0], fmax(rad1[1], rad1[2])) + fmax(rad2[0], fmax(rad2[1], rad2[2]));
    double t = g_rand_double_range(rng, 0.2, 1.5) * reach / sqrt(n2);
    for (int i = 0; i < 3; i++) r12[3 * k + i] = t * dir[i];
    if (k % 7 == 3) { /* far from 1: r times 2^e, Q times 2^-2e (mu^2 unchanged) */
      int e = k % 2 ? 40 : -40;
      for (int i = 0; i < 3; i++) r12[3 * k + i] = ldexp(r12[3 * k + i], e);
      for (int i = 0; i < 6; i++) {
        q1[6 * k + i] = ldexp(q1[6 * k + i], -2 * e);
        q2[6 * k + i] = ldexp(q2[6 * k + i], -2 * e);
      }
    }
  }
  for (int i = 0; i < 3; i++) r12[3 * 100 + i] = 0.0; /* r12 = 0 */
  q1[6 * 201] = -1.0;                                  /* not positive definite */
  q2[6 * 302 + 4] = NAN;
  for (int k = 0; k < M; k++) { /* the same pairs as a scene: ellipsoids 2k, 2k + 1 */
    for (int i = 0; i < 3; i++) {
      centres[3 * (2 * k) + i] = g_rand_double_range(rng, -5.0, 5.0);
      centres[3 * (2 * k + 1) + i] = centres[3 * (2 * k) + i] + r12[3 * k + i];
    }
    memcpy(q + 6 * (2 * k), q1 + 6 * k, sizeof(double[6]));
    memcpy(q + 6 * (2 * k + 1), q2 + 6 * k, sizeof(double[6]));
    pairs[2 * k] = 2 * k;
    pairs[2 * k + 1] = 2 * k + 1;
  }
  int counts[3] = {0, 0, 0}; /* statuses OK, INACCURATE, other */
  for (int nt = 0; nt <= 2; nt += 2) {
    memset(d, 0x55, sizeof d);
    pw85_contact_derivatives_pairs(M, r12, q1, q2, d, status, nt);
    for (int k = 0; k < M; k++) {
      pw85_derivatives_t one;
      int s = pw85_contact_derivatives(r12 + 3 * k, q1 + 6 * k, q2 + 6 * k, &one);
      g_assert_cmpint(status[k], ==, s);
      g_assert_cmpmem(&one, sizeof one, d + k, sizeof one);
      if (nt == 0) counts[s == PW85_OK ? 0 : s == PW85_ERR_INACCURATE ? 1 : 2]++;
    }
    memset(d, 0x55, sizeof d);
    pw85_scene_contact_derivatives(N, centres, q, NULL, M, pairs, d, status, nt);
    for (int k = 0; k < M; k++) {
      double r[3];
      for (int i = 0; i < 3; i++) r[i] = centres[3 * (2 * k + 1) + i] - centres[3 * (2 * k) + i];
      pw85_derivatives_t one;
      int s = pw85_contact_derivatives(r, q + 6 * (2 * k), q + 6 * (2 * k + 1), &one);
      g_assert_cmpint(status[k], ==, s);
      g_assert_cmpmem(&one, sizeof one, d + k, sizeof one);
    }
  }
  g_assert_cmpint(counts[0], >=, M - 8); /* the three bad pairs and a few others at most */
  g_assert_cmpint(counts[2], >=, 3);
  g_rand_free(rng);
}

/* Far and close pairs: unit spheres at r12 = (2^k, 0, 0), k = -500 ... 512
 * (mu^2 = 2^(2k - 2) up to 2^1022): PW85_OK with the closed forms of equal
 * spheres, lambda = 1/2, s = r12: mu^2 = |r12|^2 / 4, d_r12 = r12 / 2,
 * d_q1 = d_q2 = -(1/8) r12 r12^T, Hessian I / 2, torques 0. */
static void test_far_pairs(void) {
  double const q[6] = {1, 0, 0, 1, 0, 1};
  for (int k = -500; k <= 512; k++) {
    double const x = ldexp(1.0, k);
    double const r[3] = {x, 0, 0};
    pw85_derivatives_t d;
    int const s = pw85_contact_derivatives(r, q, q, &d);
    if (s != PW85_OK) g_test_message("k = %d: status %d", k, s);
    g_assert_cmpint(s, ==, PW85_OK);
    g_assert_true(check_forces_pair(r, q, q, s, &d));
    double const mu2 = ldexp(1.0, 2 * k - 2);
    g_assert_cmpfloat(rel_error(d.mu2, mu2), <=, 4 * DBL_EPSILON);
    g_assert_cmpfloat(fabs(d.lambda - 0.5), <=, 4 * DBL_EPSILON);
    g_assert_cmpfloat(rel_error(d.d_r12[0], 0.5 * x), <=, 4 * DBL_EPSILON);
    g_assert_cmpfloat(rel_error(d.d_q1[0], -mu2 / 2), <=, 4 * DBL_EPSILON);
    g_assert_cmpfloat(rel_error(d.d_q2[0], -mu2 / 2), <=, 4 * DBL_EPSILON);
    for (int i = 0; i < 6; i++)
      g_assert_cmpfloat(fabs(d.hess_r12[i] - (i == 0 || i == 3 || i == 5 ? 0.5 : 0.0)), <=,
                        4 * DBL_EPSILON);
    for (int i = 1; i < 3; i++) g_assert_cmpfloat(fabs(d.d_r12[i]), <=, 4 * DBL_EPSILON * x);
    for (int i = 0; i < 3; i++) {
      g_assert_cmpfloat(fabs(d.d_theta1[i]), <=, 4 * DBL_EPSILON * mu2);
      g_assert_cmpfloat(fabs(d.d_theta2[i]), <=, 4 * DBL_EPSILON * mu2);
    }
  }
}

/* Matrices of very different magnitudes: the pair of docs/stability.md's
 * ratio range (r12 of the issue that found the failures, q2 = 2^k q for
 * k = -300 ... 300, q = I and a general matrix). Wherever DEFAULT returns
 * PW85_OK and its maximiser has min(lambda, 1 - lambda) >= 1e-15 (the
 * documented limit, docs/derivatives.md), the derivatives are PW85_OK and
 * satisfy Euler's identities of the homogeneity of mu^2 (degree 2 in r12,
 * -1 in (Q1, Q2) together): r12 . d_r12 = 2 mu^2 and
 * sum_k (q1[k] d_q1[k] + q2[k] d_q2[k]) = -mu^2, within 1e-12; and the
 * torques as below. */
static void test_matrix_ratio(void) {
  double const r[3] = {-0x1.603d97098ec97p-3, 0x1.087c848e777b7p-1, -0x1.0cdcb891621c6p+1};
  double const qa[2][6] = {{1, 0, 0, 1, 0, 1}, {2, 0.3, -0.1, 1, 0.2, 0.5}};
  int checked = 0, beyond = 0;
  for (int w = 0; w < 2; w++)
    for (int k = -300; k <= 300; k++) {
      double q2[6];
      for (int i = 0; i < 6; i++) q2[i] = ldexp(qa[w][i], k);
      double const *q1 = qa[0];
      pw85_result res;
      {
        pw85_derivatives_t full;
        check_forces_pair(r, q1, q2, pw85_contact_derivatives(r, q1, q2, &full), &full);
      }
      if (pw85_contact_function_method(r, q1, q2, PW85_METHOD_DEFAULT, &res) != PW85_OK) continue;
      if (fmin(res.lambda, 1.0 - res.lambda) < 1e-15) {
        beyond++;
        continue;
      }
      pw85_derivatives_t d;
      int const s = pw85_contact_derivatives(r, q1, q2, &d);
      if (s != PW85_OK) g_test_message("w = %d, k = %d: status %d, lambda %.17g", w, k, s, res.lambda);
      g_assert_cmpint(s, ==, PW85_OK);
      double const euler_r = r[0] * d.d_r12[0] + r[1] * d.d_r12[1] + r[2] * d.d_r12[2];
      double euler_q = 0.0;
      for (int i = 0; i < 6; i++) euler_q += q1[i] * d.d_q1[i] + q2[i] * d.d_q2[i];
      g_assert_cmpfloat(rel_error(euler_r, 2.0 * d.mu2), <=, 1e-12);
      g_assert_cmpfloat(rel_error(-euler_q, d.mu2), <=, 1e-12);
      /* (E4) with pw85_contact's x0: d_theta1 = -x0 x g, and the rigid
       * rotation of the whole pair, d_theta1 + d_theta2 + r12 x g = 0, both
       * within 1e-12 |r12| |g| (x0 is accurate to u max(|x0|, |x0 - r12|)). */
      pw85_contact_t c;
      g_assert_cmpint(pw85_contact(r, q1, q2, &c), ==, PW85_OK);
      double const *g = d.d_r12;
      double const gn = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
      double const rn = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
      for (int i = 0; i < 3; i++) {
        int const j = (i + 1) % 3, l = (i + 2) % 3;
        double const x0g = c.x0[j] * g[l] - c.x0[l] * g[j], rg = r[j] * g[l] - r[l] * g[j];
        g_assert_cmpfloat(fabs(d.d_theta1[i] + x0g), <=, 1e-12 * rn * gn);
        g_assert_cmpfloat(fabs(d.d_theta1[i] + d.d_theta2[i] + rg), <=, 1e-12 * rn * gn);
      }
      checked++;
    }
  g_test_message("%d pairs checked, %d beyond the documented limit", checked, beyond);
  g_assert_cmpint(checked, >, 350);
}

/* An ellipsoid far longer than r12: q1 = diag(2^k, 1, 1) (a needle along x
 * of half-length 2^(k/2)), q2 = I. For 2^k beyond 2^(2 * 53), mu2 =
 * (y^2 + z^2) / 4 and lambda = 1/2 in double, d_r12 = (~0, y/2, z/2):
 * PW85_OK wherever DEFAULT answers (k up to 560), every field finite. Then
 * the pair libFuzzer found (tests/fuzz/corpus/derivatives-long-needle)
 * against mpmath at 400 digits (maximiser of f by bisection on f'). */
static void test_long_needle(void) {
  double const r[3] = {0x1.6666666666666p-1, -0x1.6666666666666p-1, 0x1.199999999999ap+0};
  double const q2[6] = {1, 0, 0, 1, 0, 1};
  double const mu2 = (r[1] * r[1] + r[2] * r[2]) / 4;
  int checked = 0;
  for (int k = 120; k <= 600; k++) {
    double const q1[6] = {ldexp(1.0, k), 0, 0, 1, 0, 1};
    pw85_result res;
    if (pw85_contact_function_method(r, q1, q2, PW85_METHOD_DEFAULT, &res) != PW85_OK) continue;
    pw85_derivatives_t d;
    int const s = pw85_contact_derivatives(r, q1, q2, &d);
    if (s != PW85_OK) g_test_message("k = %d: status %d", k, s);
    g_assert_cmpint(s, ==, PW85_OK);
    g_assert_true(check_forces_pair(r, q1, q2, s, &d));
    g_assert_cmpfloat(rel_error(d.mu2, mu2), <=, 4 * DBL_EPSILON);
    g_assert_cmpfloat(fabs(d.lambda - 0.5), <=, 4 * DBL_EPSILON);
    g_assert_cmpfloat(fabs(d.d_r12[0]), <=, 4 * DBL_EPSILON);
    for (int i = 1; i < 3; i++) g_assert_cmpfloat(rel_error(d.d_r12[i], r[i] / 2), <=, 4 * DBL_EPSILON);
    checked++;
  }
  g_assert_cmpint(checked, >=, 400);
  double const fr[3] = {0x1.6666666666666p-1, -0x1.6666666666666p-1, 0x1.199999999999ap+0};
  double const f1[6] = {0x1.9p+518, 0, -0x1p-863, 0x1.9p+6, 0, 0x1.47ae147ae147bp-7};
  double const f2[6] = {0x1.9p+4, 0, 0, 0x1p-2, 0, 0x1.00000002fp-2};
  pw85_derivatives_t d;
  g_assert_cmpint(pw85_contact_derivatives(fr, f1, f2, &d), ==, PW85_OK);
  g_assert_cmpfloat(rel_error(d.mu2, 3.3619276153448344061), <=, 4 * DBL_EPSILON);
  g_assert_cmpfloat(rel_error(d.lambda, 0.16676786861612571565), <=, 1e-14);
  g_assert_cmpfloat(rel_error(d.d_r12[1], -0.0023335825190758001585), <=, 1e-14);
  g_assert_cmpfloat(rel_error(d.d_r12[2], 6.1111106572057410995), <=, 1e-14);
  g_assert_cmpfloat(fabs(d.d_r12[0]), <=, 1e-150);
}

/* Matrix entries over 2^400 apart and r12 far longer than both
 * ellipsoids' short axes (the pair libFuzzer found,
 * tests/fuzz/corpus/derivatives-wide-scales): PW85_OK where DEFAULT
 * answers, against mpmath at 400 digits (the matrices are diagonal: f' by
 * its sum over the axes, the maximiser by bisection; (E1), (E2)). */
static void test_wide_scales(void) {
  double const r[3] = {-0x1.bfa4dff172bb4p-2, -0x1.5eedb89747b64p-2, 0x1.0a40039385f78p+288};
  double const q1[6] = {9.000000000000112, 0, 0, 1.2067027136948337e+155, 0, 9.000495910644531};
  double const q2[6] = {1, 0, 0, 5.192296858534828e+33, 0, 1};
  pw85_derivatives_t d;
  int const s = pw85_contact_derivatives(r, q1, q2, &d);
  g_assert_cmpint(s, ==, PW85_OK);
  g_assert_true(check_forces_pair(r, q1, q2, s, &d));
  g_assert_cmpfloat(rel_error(d.mu2, 1.6720107021031418809e+172), <=, 4 * DBL_EPSILON);
  g_assert_cmpfloat(rel_error(d.lambda, 0.7500051655579887924), <=, 1e-14);
  g_assert_cmpfloat(rel_error(d.d_r12[0], -0.054644048100303268155), <=, 1e-14);
  g_assert_cmpfloat(rel_error(d.d_r12[1], -4.2600310580612198835e-156), <=, 1e-14);
  g_assert_cmpfloat(rel_error(d.d_r12[2], 6.4651790537290090943e+85), <=, 1e-14);
  g_assert_cmpfloat(rel_error(d.d_q1[0], -0.00099531714243819706488), <=, 1e-14);
  g_assert_cmpfloat(rel_error(d.d_q1[2], 2.3552074799791896414e+84), <=, 1e-14);
  g_assert_cmpfloat(rel_error(d.d_q1[5], -1.3932750771682702462e+171), <=, 1e-14);
  g_assert_cmpfloat(rel_error(d.d_q2[0], -0.0029860336909090047223), <=, 1e-14);
  g_assert_cmpfloat(rel_error(d.d_q2[5], -4.1799403865754587495e+171), <=, 1e-14);
}

/* Q1 nearly singular (smallest eigenvalue ~4e-18), r12 along its thin
 * direction, lambda ~3.5e-9: f' computed from a solve refined to ~2^-60 |s|
 * is too noisy for the Newton steps to settle (docs/derivatives.md, (E7)),
 * which then go on in double-double. PW85_OK on every variant, DEFAULT's
 * mu2, and the accuracy of the reference pairs against __float128. */
static void test_thin_direction(void) {
  double const r[3] = {0x1.033e80df146afp+0, -0x1.fe6e01f6990f8p+0, 0x1.ca756a21fbd73p-1};
  double const q1[6] = {0x1.ec661d778fec2p-2, 0x1.fac907446d3fp-2,  0x1.18d013d6036b4p-4,
                        0x1.0e6fa2590c9b3p-1, -0x1.0bb43f203545cp-4, 0x1.fb5d4eeb2b6edp-1};
  double const q2[6] = {0x1.1ea0a1466ebdep-1, 0x1.49c45c27aae9ap-2, 0x1.42bbad45f6196p-5,
                        0x1.875ed9f5adf74p-1, -0x1.d839d1c34d47p-6, 0x1.fe31d8c186428p-1};
  pw85_result res;
  g_assert_cmpint(pw85_contact_function_method(r, q1, q2, PW85_METHOD_DEFAULT, &res), ==, PW85_OK);
  pw85_derivatives_t d;
  g_assert_cmpint(pw85_contact_derivatives(r, q1, q2, &d), ==, PW85_OK);
  double const *all = &d.mu2;
  for (size_t i = 0; i < sizeof d / sizeof(double); i++) g_assert_true(isfinite(all[i]));
  g_assert_cmpfloat(rel_error(d.mu2, res.mu2), <=, 2e-14);
  maxima mx = {0};
  GRand *rng = g_rand_new_with_seed(7);
  check_pair(r, q1, q2, &mx, rng);
  g_rand_free(rng);
}

int main(int argc, char **argv) {
  g_test_init(&argc, &argv, NULL);
  g_test_add_func("/pw85_contact_derivatives/formulas-finite-differences", test_formulas_fd);
  g_test_add_func("/pw85_contact_derivatives/reference/contact", test_contact);
  g_test_add_func("/pw85_contact_derivatives/reference/near_contact", test_near_contact);
  g_test_add_func("/pw85_contact_derivatives/spheres", test_spheres);
  g_test_add_func("/pw85_contact_derivatives/scaling", test_scaling);
  g_test_add_func("/pw85_contact_derivatives/far_pairs", test_far_pairs);
  g_test_add_func("/pw85_contact_derivatives/matrix_ratio", test_matrix_ratio);
  g_test_add_func("/pw85_contact_derivatives/thin-direction", test_thin_direction);
  g_test_add_func("/pw85_contact_derivatives/long-needle", test_long_needle);
  g_test_add_func("/pw85_contact_derivatives/wide-scales", test_wide_scales);
  g_test_add_func("/pw85_contact_derivatives/bad-input", test_bad_input);
  g_test_add_func("/pw85_contact_derivatives/batch/forms", test_batch);
  g_test_add_func("/pw85_contact_derivatives/batch/lanes", test_batch_lanes);
  g_test_add_func("/pw85_contact_derivatives/batch/forces", test_batch_forces);
  return g_test_run();
}
