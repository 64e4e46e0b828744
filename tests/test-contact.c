/* Tests of pw85_contact (docs/contact_geometry.md): the contact
 * point lies on both ellipsoids scaled by mu and their outward normals there
 * are opposite; mu2 agrees with the exact-arithmetic reference and with
 * pw85_contact_function; dca = |r12| / mu; depth vanishes at tangency and
 * changes sign across it; x0, n and lambda agree with the exact contact
 * geometry. References are computed in __float128 / long double from the
 * inputs, never by the library. */
#include <float.h>
#include <math.h>
#include <pw85.h>

#include "refdata.h"
#include "testutil.h"

/* Exact contact geometry in __float128 (113-bit significand): Q^{-1} v by
 * the adjugate (products of doubles are exact, cancellation costs at most
 * cond(Q) 2^-113 ~ 1e-22 in class 3), lambda* by Newton on
 * f'(lambda) = (1 - lambda)^2 s.Q1 s - lambda^2 s.Q2 s = 0 with the exact
 * f'' (docs/contact_geometry.md, eqs. (G9), (G11)), started from the
 * library's lambda (Newton converges quadratically: six steps reach 1e-30).
 * Independent of the library's code. */
typedef __float128 quad;

static void q_solve(const quad a[6], const quad v[3], quad s[3]) {
  quad c00 = a[3] * a[5] - a[4] * a[4], c01 = a[2] * a[4] - a[1] * a[5];
  quad c02 = a[1] * a[4] - a[2] * a[3], c11 = a[0] * a[5] - a[2] * a[2];
  quad c12 = a[1] * a[2] - a[0] * a[4], c22 = a[0] * a[3] - a[1] * a[1];
  quad det = a[0] * c00 + a[1] * c01 + a[2] * c02;
  s[0] = (c00 * v[0] + c01 * v[1] + c02 * v[2]) / det;
  s[1] = (c01 * v[0] + c11 * v[1] + c12 * v[2]) / det;
  s[2] = (c02 * v[0] + c12 * v[1] + c22 * v[2]) / det;
}

static void q_mul(const quad a[6], const quad v[3], quad o[3]) {
  o[0] = a[0] * v[0] + a[1] * v[1] + a[2] * v[2];
  o[1] = a[1] * v[0] + a[3] * v[1] + a[4] * v[2];
  o[2] = a[2] * v[0] + a[4] * v[1] + a[5] * v[2];
}

static quad q_dot(const quad a[3], const quad b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static long double q_norm(const quad a[3]) { return sqrtl((long double)q_dot(a, a)); }
static long double q_abs(quad x) { return fabsl((long double)x); }

typedef struct {
  quad lambda, mu2, x0[3], n[3];
} exact_geom;

static void exact_geometry(const double r[3], const double q1[6], const double q2[6],
                           double lambda0, exact_geom *g) {
  quad R[3], A[6], B[6], D[6], Q[6], s[3], t[3], u[3], w[3], lam = lambda0;
  for (int i = 0; i < 3; i++) R[i] = r[i];
  for (int i = 0; i < 6; i++) {
    A[i] = q1[i];
    B[i] = q2[i];
    D[i] = B[i] - A[i];
  }
  for (int it = 0; it < 6; it++) {
    for (int i = 0; i < 6; i++) Q[i] = (1 - lam) * A[i] + lam * B[i];
    q_solve(Q, R, s);
    q_mul(A, s, t);
    q_mul(B, s, u);
    quad fp = (1 - lam) * (1 - lam) * q_dot(s, t) - lam * lam * q_dot(s, u);
    q_mul(D, s, t);  /* D s */
    q_solve(Q, t, w);
    /* f'' = -2 phi + 2 (1 - 2 lambda) phi' + lambda (1 - lambda) phi'' with
     * phi = r.s, phi' = -s.D s, phi'' = 2 (D s).Q^{-1} (D s). */
    quad fpp = -2 * q_dot(R, s) - 2 * (1 - 2 * lam) * q_dot(s, t) + 2 * lam * (1 - lam) * q_dot(t, w);
    lam -= fp / fpp;
  }
  for (int i = 0; i < 6; i++) Q[i] = (1 - lam) * A[i] + lam * B[i];
  q_solve(Q, R, s);
  q_mul(A, s, t);
  long double ns = q_norm(s);
  for (int i = 0; i < 3; i++) {
    g->x0[i] = (1 - lam) * t[i];
    g->n[i] = s[i] / ns;
  }
  g->mu2 = lam * (1 - lam) * q_dot(R, s);
  g->lambda = lam;
}

/* Per-class bounds (semi-axes log-uniform in [0.5, 2], [0.1, 10],
 * [0.01, 100], [0.001, 1000]), set just above the maxima measured over all
 * pairs of /contact and /near_contact (docs/contact_geometry.md, "Measured
 * accuracy"):
 *   x0:     |x0 - x0*|_max / |x0*|_max (x0* exact contact point);
 *   n:      |n - n*|_max;
 *   lambda: |lambda - lambda*|;
 *   surf:   distance of x0 from each mu*-scaled surface, to first order
 *           |x^T Qk^{-1} x - mu*^2| / (2 |Qk^{-1} x|) with x = x0, x0 - r,
 *           divided by max(|x0|, |x0 - r|);
 *   point:  |x^T Qk^{-1} x / mu*^2 - 1| (the plain residual of the scaled
 *           quadratic forms; amplified by up to sqrt(cond Qk) over surf:
 *           rounding x0* to double alone gives 1.7e-11 in class 3);
 *   opp:    |m1 + m2|_max, m1, m2 the unit outward normals of the two
 *           surfaces through the double x0 (the rounding of x0 tilts the
 *           normal of a needle-like ellipsoid: ~2e-6 in class 3; n itself
 *           is within the n bound of the exact normal).
 * x0, n, lambda and surf are within ~1 ulp: the target 1e-12 holds in
 * every class; pt and opp are limited by the rounding of x0 to double.
 * x0, n and lambda get 2 ulps (4.5e-16 for x0 and n, DBL_EPSILON for lambda
 * in [0, 1]): the double-double kernels without FMA (Dekker products, no
 * contraction; the build with isa_dispatch=false) differ from the FMA ones
 * by up to 1 ulp (lambda: 1.02e-16 measured without FMA). pt gets about
 * twice its measured maximum, which is about twice the floor set by x0*
 * rounded to double (4.8e-15 in class 1, 2.7e-13 in class 2). */
static const double kTolX0[4] = {4.5e-16, 4.5e-16, 4.5e-16, 1.5e-15};
static const double kTolN[4] = {4.5e-16, 4.5e-16, 4.5e-16, 4.5e-16};
static const double kTolLambda[4] = {DBL_EPSILON, DBL_EPSILON, DBL_EPSILON, DBL_EPSILON};
static const double kTolSurf[4] = {2.5e-16, 2.5e-16, 2.5e-16, 2.5e-16};
static const double kTolPoint[4] = {1e-15, 2e-14, 8e-13, 2e-11};
static const double kTolOpp[4] = {1e-15, 3e-13, 3e-9, 3e-6};

/* Checks one pair of class cls against the reference mu2_ref
 * (exact-arithmetic value). full: also compare with the other entry
 * points (slower). */
static void check_pair(const double r[3], const double q1[6], const double q2[6],
                       double mu2_ref, int cls, int full) {
  pw85_contact_t c;
  g_assert_cmpint(pw85_contact(r, q1, q2, &c), ==, PW85_OK);
  g_assert_cmpfloat(rel_error(c.mu2, mu2_ref), <=, 1e-14);
  if (full) {
    double out[2];
    int s = pw85_contact_function(r, q1, q2, out);
    g_assert_true(s == PW85_OK || s == PW85_ERR_INACCURATE || s == PW85_ERR_NO_CONVERGENCE);
    /* pw85 1.0's Brent algorithm is less accurate on ill-conditioned pairs. */
    g_assert_cmpfloat(rel_error(c.mu2, out[0]), <=, 1e-6);
    pw85_result res;
    s = pw85_contact_function_method(r, q1, q2, PW85_METHOD_DEFAULT, &res);
    g_assert_true(s == PW85_OK || s == PW85_ERR_INACCURATE);
    g_assert_cmpfloat(c.mu2, ==, res.mu2);
    /* lambda is refined beyond the method's (docs/contact_geometry.md). */
    g_assert_cmpfloat(fabs(c.lambda - res.lambda), <=, 1e-6);
  }
  exact_geom e;
  exact_geometry(r, q1, q2, c.lambda, &e);
  g_assert_cmpfloat(fabsl((long double)(e.mu2 / mu2_ref) - 1.0L), <=, 1e-15);
  g_assert_cmpfloat(q_abs(c.lambda - e.lambda), <=, kTolLambda[cls]);
  long double xmax = 0, ex = 0, en = 0;
  for (int i = 0; i < 3; i++) xmax = fmaxl(xmax, q_abs(e.x0[i]));
  for (int i = 0; i < 3; i++) {
    ex = fmaxl(ex, q_abs(c.x0[i] - e.x0[i]) / xmax);
    en = fmaxl(en, q_abs(c.n[i] - e.n[i]));
  }
  g_assert_cmpfloat(ex, <=, kTolX0[cls]);
  g_assert_cmpfloat(en, <=, kTolN[cls]);
  /* x0 on both scaled ellipsoids; outward normals Q1^{-1} x0 and
   * Q2^{-1} (x0 - r) at the double x0. */
  quad A[6], B[6], x[3], y[3], g1[3], g2[3];
  for (int i = 0; i < 6; i++) {
    A[i] = q1[i];
    B[i] = q2[i];
  }
  for (int i = 0; i < 3; i++) {
    x[i] = c.x0[i];
    y[i] = x[i] - r[i];
  }
  q_solve(A, x, g1);
  q_solve(B, y, g2);
  long double n1 = q_norm(g1), n2 = q_norm(g2);
  long double scale = fmaxl(q_norm(x), q_norm(y));
  g_assert_cmpfloat(q_abs(q_dot(x, g1) - e.mu2) / (2 * n1) / scale, <=, kTolSurf[cls]);
  g_assert_cmpfloat(q_abs(q_dot(y, g2) - e.mu2) / (2 * n2) / scale, <=, kTolSurf[cls]);
  g_assert_cmpfloat(q_abs(q_dot(x, g1) / e.mu2 - 1), <=, kTolPoint[cls]);
  g_assert_cmpfloat(q_abs(q_dot(y, g2) / e.mu2 - 1), <=, kTolPoint[cls]);
  for (int i = 0; i < 3; i++) {
    g_assert_cmpfloat(fabsl((long double)g1[i] / n1 + (long double)g2[i] / n2), <=, kTolOpp[cls]);
  }
  g_assert_cmpfloat(fabs(c.n[0] * c.n[0] + c.n[1] * c.n[1] + c.n[2] * c.n[2] - 1.0), <=,
                    8 * DBL_EPSILON);
  /* n points from 1 towards 2. */
  g_assert_cmpfloat(c.n[0] * r[0] + c.n[1] * r[1] + c.n[2] * r[2], >, 0.0);
  /* dca = |r| / mu, depth = dca - |r|, depth_n = depth (r/|r|).n. */
  long double nr = sqrtl((long double)r[0] * r[0] + (long double)r[1] * r[1] +
                         (long double)r[2] * r[2]);
  long double dca = nr / sqrtl(mu2_ref);
  g_assert_cmpfloat(fabsl(c.dca - dca) / dca, <=, 8 * DBL_EPSILON);
  g_assert_cmpfloat(fabsl(c.depth - (dca - nr)), <=, 16 * DBL_EPSILON * (dca + nr));
  long double cosine = (r[0] * (long double)c.n[0] + r[1] * (long double)c.n[1] +
                        r[2] * (long double)c.n[2]) / nr;
  g_assert_cmpfloat(fabsl(c.depth_n - c.depth * cosine), <=, 16 * DBL_EPSILON * (dca + nr));
}

static void test_reference(void) {
  RefPairs *g = refdata_pairs_or_skip("/contact");
  if (g == NULL) return;
  size_t checked[4] = {0, 0, 0, 0};
  for (size_t i = 0; i < g->n; i++) {
    if (g->mu2[i] == 0.0) continue;
    check_pair(g->r12 + 3 * i, g->q1 + 6 * i, g->q2 + 6 * i, g->mu2[i], g->cls[i], i % 10 == 0);
    checked[g->cls[i]]++;
  }
  for (int k = 0; k < 4; k++) g_assert_cmpuint(checked[k], >=, 1000);
  refdata_pairs_free(g);
}

static void test_near_contact(void) {
  RefPairs *g = refdata_pairs_or_skip("/near_contact");
  if (g == NULL) return;
  for (size_t i = 0; i < g->n; i++) {
    check_pair(g->r12 + 3 * i, g->q1 + 6 * i, g->q2 + 6 * i, g->mu2[i], g->cls[i], i % 10 == 0);
    /* Near tangency the depth is small and its sign is the overlap verdict
     * whenever |mu2 - 1| exceeds the accuracy of mu2. */
    pw85_contact_t c;
    g_assert_cmpint(pw85_contact(g->r12 + 3 * i, g->q1 + 6 * i, g->q2 + 6 * i, &c), ==,
                    PW85_OK);
    if (fabs(g->mu2[i] - 1.0) > 1e-9) {
      g_assert_true((c.depth > 0) == (g->mu2[i] < 1.0));
    }
    g_assert_cmpfloat(fabs(c.depth), <=, 2 * fabs(g->mu2[i] - 1.0) * c.dca + 1e-9 * c.dca);
  }
  refdata_pairs_free(g);
}

/* Spheres 1.5 and 1 tangent at distance 2.5 along (3/5, 4/5, 0): depth 0,
 * then positive when moved closer, negative when moved apart; x0 is the
 * tangency point 1.5 u, n = u, depth_n = depth. */
static void test_tangency_sign(void) {
  double q1[6] = {2.25, 0, 0, 2.25, 0, 2.25}, q2[6] = {1, 0, 0, 1, 0, 1};
  double r[3] = {1.5, 2.0, 0.0};
  pw85_contact_t c;
  g_assert_cmpint(pw85_contact(r, q1, q2, &c), ==, PW85_OK);
  g_assert_cmpfloat(fabs(c.depth), <=, 8 * DBL_EPSILON * 2.5);
  g_assert_cmpfloat(fabs(c.dca - 2.5), <=, 8 * DBL_EPSILON * 2.5);
  g_assert_cmpfloat(fabs(c.x0[0] - 0.9), <=, 8 * DBL_EPSILON);
  g_assert_cmpfloat(fabs(c.x0[1] - 1.2), <=, 8 * DBL_EPSILON);
  g_assert_cmpfloat(fabs(c.n[0] - 0.6), <=, 8 * DBL_EPSILON);
  g_assert_cmpfloat(fabs(c.n[1] - 0.8), <=, 8 * DBL_EPSILON);
  g_assert_cmpfloat(fabs(c.lambda - 0.6), <=, 1e-12);
  for (int k = -3; k <= 3; k++) {
    if (k == 0) continue;
    double s = 1.0 + k * 1e-7;
    double rs[3] = {1.5 * s, 2.0 * s, 0.0};
    g_assert_cmpint(pw85_contact(rs, q1, q2, &c), ==, PW85_OK);
    /* exact depth: dca - |r12| = 2.5 - |rs| */
    long double const expect =
        2.5L - sqrtl((long double)rs[0] * rs[0] + (long double)rs[1] * rs[1]);
    g_assert_cmpfloat(fabsl(c.depth - expect), <=, 1e-9 * fabsl(expect) + 4 * DBL_EPSILON * 2.5);
    g_assert_cmpfloat(fabs(c.depth_n - c.depth), <=, 1e-15);
    g_assert_true(k < 0 ? c.depth > 0 : c.depth < 0);
  }
}

/* Exact power-of-two scalings r -> 2^kr r, Q -> 2^kq Q over the whole double
 * range: lambda and n are unchanged, mu2 scales by 2^(2 kr - kq), x0 by
 * 2^kr, dca by 2^(kq/2) (docs/contact_geometry.md, (G12)); depth = dca - |r|.
 * The reference is pw85_contact on the unscaled inputs (r rounded at the
 * scale 2^kr, then scaled back exactly), scaled exactly in long double. A
 * result out of the range of double must come with PW85_ERR_RANGE and the
 * value rounded to the nearest double. */
static int out_of_range(long double v) { return !(fabsl(v) >= DBL_MIN && fabsl(v) <= DBL_MAX); }

static int check_scaled(const double R[3], const double Q1[6], const double Q2[6], int kr,
                        int kq, double *worst) {
  double r[3], rt[3], q1[6], q2[6];
  for (int i = 0; i < 3; i++) {
    r[i] = ldexp(R[i], kr);
    rt[i] = ldexp(r[i], -kr);
  }
  if (rt[0] == 0. && rt[1] == 0. && rt[2] == 0.) return 1;
  for (int i = 0; i < 6; i++) {
    q1[i] = ldexp(Q1[i], kq);
    q2[i] = ldexp(Q2[i], kq);
    if (ldexp(q1[i], -kq) != Q1[i] || ldexp(q2[i], -kq) != Q2[i]) return 1; /* not exact */
  }
  pw85_contact_t ref, c;
  g_assert_cmpint(pw85_contact(rt, Q1, Q2, &ref), ==, PW85_OK);
  int const s = pw85_contact(r, q1, q2, &c);
  long double const scale_dca = sqrtl(ldexpl(1.0L, kq));
  long double const mu2 = ldexpl(ref.mu2, 2 * kr - kq);
  long double const dca = ref.dca * scale_dca;
  long double const nr = ldexpl(sqrtl((long double)rt[0] * rt[0] + (long double)rt[1] * rt[1] +
                                      (long double)rt[2] * rt[2]), kr);
  long double const depth = dca - nr;
  long double x0[3], xmax = 0;
  for (int i = 0; i < 3; i++) {
    x0[i] = ldexpl(ref.x0[i], kr);
    xmax = fmaxl(xmax, fabsl(x0[i]));
  }
  int const range = out_of_range(mu2) || out_of_range(dca) || out_of_range(xmax) ||
                    !(fabsl(depth) <= DBL_MAX);
  double const tol = 4 * DBL_EPSILON, tiny = 0x1p-1074;
  int ok = s == (range ? PW85_ERR_RANGE : PW85_OK);
  double e_mu2 = (double)(fabsl(c.mu2 - mu2) / mu2);
  if ((isinf(c.mu2) && mu2 > DBL_MAX) || fabsl(c.mu2 - mu2) <= tiny) e_mu2 = 0;
  double e = fmax(e_mu2, fabs(c.lambda - ref.lambda));
  for (int i = 0; i < 3; i++) {
    e = fmax(e, fabs(c.n[i] - ref.n[i]));
    double const ex = (double)(fabsl(c.x0[i] - x0[i]) / xmax);
    e = fmax(e, fabsl(c.x0[i] - x0[i]) <= tiny ? 0. : ex); /* subnormal: one rounding */
  }
  e = fmax(e, (double)(fabsl(c.dca - dca) / dca));
  if (fabsl(depth) <= DBL_MAX)
    e = fmax(e, (double)(fabsl(c.depth - depth) / (dca + nr)));
  *worst = fmax(*worst, e);
  ok = ok && e <= tol;
  if (!ok)
    g_test_message("kr = %d kq = %d: status %d, mu2 %.17g (%.17Lg), dca %.17g (%.17Lg), n (%g, %g, "
                   "%g), error %.3g eps", kr, kq, s, c.mu2, mu2, c.dca, dca, c.n[0], c.n[1], c.n[2],
                   e / DBL_EPSILON);
  return ok;
}

static void test_extreme_scale(void) {
  double const R[3] = {1.3, -0.4, 0.7};
  double const Q1[6] = {1, 0.1, -0.2, 0.5, 0.05, 0.3};
  double const Q2[6] = {0.2, -0.05, 0.01, 0.9, 0.1, 0.4};
  /* An elongated pair: semi-axes 1e-2..1e2 (make_q of fixed axes). */
  double const radii1[3] = {100., 1., 0.01}, radii2[3] = {0.05, 3., 20.};
  double const axes[9] = {0.6, 0.8, 0., -0.8, 0.6, 0., 0., 0., 1.};
  double const axes2[9] = {1., 0., 0., 0., 0.6, 0.8, 0., -0.8, 0.6};
  double E1[6], E2[6];
  make_q(radii1, axes, E1);
  make_q(radii2, axes2, E2);
  struct { const double *q1, *q2; } const pairs[] = {{Q1, Q2}, {E1, E2}};
  int bad = 0;
  double worst = 0.;
  for (size_t p = 0; p < G_N_ELEMENTS(pairs); p++) {
    for (int k = -1074; k <= 1023; k++) {
      bad += !check_scaled(R, pairs[p].q1, pairs[p].q2, k, 0, &worst);    /* r alone */
      bad += !check_scaled(R, pairs[p].q1, pairs[p].q2, 0, k, &worst);    /* Q alone */
      bad += !check_scaled(R, pairs[p].q1, pairs[p].q2, k, 2 * k, &worst); /* both: mu2 fixed */
    }
  }
  g_test_message("largest error: %.3g eps; %d scalings wrong", worst / DBL_EPSILON, bad);
  g_assert_cmpint(bad, ==, 0);
  /* Magnitude ratio: Q2 -> 2^k Q2 (short significands: exact), statuses
   * only; the PW85_OK range around k = 0 is reported (docs/stability.md). */
  double const S1[6] = {1, 0.125, -0.25, 0.5, 0.0625, 0.375};
  double const S2[6] = {0.25, -0.0625, 0, 1, 0.125, 0.5};
  int lo = 0, hi = 0, n_other = 0;
  for (int k = -1070; k <= 1023; k++) {
    double q2[6];
    for (int i = 0; i < 6; i++) q2[i] = ldexp(S2[i], k);
    pw85_contact_t c;
    int const s = pw85_contact(R, S1, q2, &c);
    g_assert_true(s == PW85_OK || s == PW85_ERR_NO_CONVERGENCE || s == PW85_ERR_INACCURATE ||
                  s == PW85_ERR_RANGE);
    if (s != PW85_OK) n_other++;
  }
  for (int k = 0; k >= -1070; k--) {
    double q2[6];
    for (int i = 0; i < 6; i++) q2[i] = ldexp(S2[i], k);
    pw85_contact_t c;
    if (pw85_contact(R, S1, q2, &c) != PW85_OK) break;
    lo = k;
  }
  for (int k = 0; k <= 1023; k++) {
    double q2[6];
    for (int i = 0; i < 6; i++) q2[i] = ldexp(S2[i], k);
    pw85_contact_t c;
    if (pw85_contact(R, S1, q2, &c) != PW85_OK) break;
    hi = k;
  }
  g_test_message("ratio Q2 = 2^k Q2: PW85_OK for every k in [%d, %d]; %d of k = -1070..1023 "
                 "with another status", lo, hi, n_other);
}

/* depth = dca - |r12| against the reference mu^2 of /contact, /near_contact
 * and /special (correctly rounded; depth_ref = |r| (1 - mu^2) / (mu (1 + mu))
 * in long double): the error relative to max(dca, |r12|) -- the accuracy
 * docs/contact_geometry.md states -- is at most 1e-15 (measured 5.9e-16
 * with AVX-512, 5.0e-16 portable);
 * relative to dca alone it is not bounded by a constant (far pairs). */
static void test_depth_accuracy(void) {
  const char *groups[3] = {"/contact", "/near_contact", "/special"};
  double worst = 0.0;
  for (int gi = 0; gi < 3; gi++) {
    RefPairs *g = refdata_pairs_or_skip(groups[gi]);
    if (g == NULL) return;
    for (gsize i = 0; i < g->n; i++) {
      double const *r = g->r12 + 3 * i;
      long double const rn = sqrtl((long double)r[0] * r[0] + (long double)r[1] * r[1] +
                                   (long double)r[2] * r[2]);
      if (rn == 0.0L) continue;
      pw85_contact_t c;
      int const s = pw85_contact(r, g->q1 + 6 * i, g->q2 + 6 * i, &c);
      if (s != PW85_OK) continue;
      long double const mu2 = g->mu2[i], mu = sqrtl(mu2);
      long double const depth = rn * (1.0L - mu2) / (mu * (1.0L + mu));
      long double const scale = fmaxl(rn / mu, rn);
      double const e = (double)(fabsl((long double)c.depth - depth) / scale);
      if (e > worst) worst = e;
    }
    refdata_pairs_free(g);
  }
  g_test_message("depth: largest error / max(dca, |r12|) = %.3g", worst);
  g_assert_cmpfloat(worst, <=, 1e-15);
}

/* The contact point at extreme size ratios: pair (r12, q1, 2^k q2),
 * k = -1070 ... 156 (docs/stability.md), two r12. With PW85_OK, x0 lies on
 * both ellipsoids scaled by mu to within 8 u max(|x0|, |x0 - r12|) (the
 * distance |y^T Q^-1 y - mu^2| / (2 |Q^-1 y|) of y = x0, x0 - r12 from the
 * surface, in __float128; where y = 0, the size of that scaled ellipsoid,
 * mu sqrt(3 max |Q_ij|)); and on each relative to its own size,
 * |y^T (mu^2 Q)^-1 y - 1| <= 1e-9, for k in [-44, 103]
 * (docs/contact_geometry.md, "Measured accuracy"). */
static void test_size_ratio(void) {
  double const rr[2][3] = {{-0x1.603d97098ec97p-3, 0x1.087c848e777b7p-1, -0x1.0cdcb891621c6p+1},
                           {1.3, -0.4, 0.9}};
  double const qa[6] = {2, 0.3, -0.1, 1, 0.2, 0.5}, qb[6] = {1, 0.1, -0.2, 2, 0.3, 0.5};
  int n_ok = 0;
  for (int p = 0; p < 2; p++)
    for (int k = -1070; k <= 156; k++) {
      double const *r = rr[p];
      double q2[6];
      for (int i = 0; i < 6; i++) q2[i] = ldexp(qb[i], k);
      pw85_contact_t c;
      if (pw85_contact(r, qa, q2, &c) != PW85_OK) continue;
      n_ok++;
      quad y[2][3];
      for (int i = 0; i < 3; i++) {
        y[0][i] = c.x0[i];
        y[1][i] = (quad)c.x0[i] - r[i];
      }
      double const *qs[2] = {qa, q2};
      long double const ny = fmaxl(q_norm(y[0]), q_norm(y[1]));
      for (int e = 0; e < 2; e++) {
        quad qq[6], g[3];
        for (int i = 0; i < 6; i++) qq[i] = qs[e][i];
        q_solve(qq, y[e], g);
        quad const f = q_dot(y[e], g);
        double dist;
        if (q_norm(y[e]) == 0.0L) {
          double m = 0;
          for (int i = 0; i < 6; i++) m = fmax(m, fabs(qs[e][i]));
          dist = sqrt(c.mu2 * 3.0 * m);
        } else {
          dist = (double)(q_abs(f - c.mu2) / (2.0L * q_norm(g)));
        }
        double const tol = 4.0 * DBL_EPSILON * (double)ny;
        if (!(dist <= tol))
          g_test_message("k = %d, pair %d, ellipsoid %d: distance %.3g, max(|x0|, |x0 - r|) %.3g",
                         k, p, e + 1, dist, (double)ny);
        g_assert_cmpfloat(dist, <=, tol);
        if (k >= -44 && k <= 103) g_assert_cmpfloat((double)q_abs(f / c.mu2 - 1), <=, 1e-9);
      }
    }
  g_assert_cmpint(n_ok, >, 1500);
}

static void test_bad_input(void) {
  double q[6] = {1, 0, 0, 1, 0, 1}, r[3] = {1, 0, 0}, zero[3] = {0, 0, 0};
  double notspd[6] = {1, 2, 0, 1, 0, 1};
  pw85_contact_t c;
  g_assert_cmpint(pw85_contact(r, q, q, NULL), ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_contact(NULL, q, q, &c), ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_true(isnan(c.mu2) && isnan(c.x0[2]) && isnan(c.n[0]) && isnan(c.depth_n));
  g_assert_cmpint(pw85_contact(zero, q, q, &c), ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_true(isnan(c.dca) && isnan(c.lambda));
  g_assert_cmpint(pw85_contact(r, notspd, q, &c), ==, PW85_ERR_NOT_SPD);
  g_assert_true(isnan(c.depth));
}

int main(int argc, char **argv) {
  g_test_init(&argc, &argv, NULL);
  g_test_add_func("/pw85_contact/reference/contact", test_reference);
  g_test_add_func("/pw85_contact/reference/near_contact", test_near_contact);
  g_test_add_func("/pw85_contact/tangency/depth-sign", test_tangency_sign);
  g_test_add_func("/pw85_contact/bad-input", test_bad_input);
  g_test_add_func("/pw85_contact/extreme_scale", test_extreme_scale);
  g_test_add_func("/pw85_contact/reference/depth_accuracy", test_depth_accuracy);
  g_test_add_func("/pw85_contact/size_ratio", test_size_ratio);
  return g_test_run();
}
