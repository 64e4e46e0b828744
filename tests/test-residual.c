/* pw85_f_neg and pw85__residual (pw85 1.0) against long-double evaluations
 * through the adjugate (tests/testutil.c), a route independent of the
 * library's Cholesky code. */
#include <float.h>
#include <math.h>
#include <string.h>

#include <pw85.h>

#include "testutil.h"

#define NUM_PAIRS 500

typedef struct {
  double r[3], q1[6], q2[6];
} pair;

static void random_pair(GRand *rng, double lo, double hi, pair *p) {
  double radii[3], axes[9];
  random_radii(rng, lo, hi, radii);
  random_axes(rng, axes);
  make_q(radii, axes, p->q1);
  random_radii(rng, lo, hi, radii);
  random_axes(rng, axes);
  make_q(radii, axes, p->q2);
  for (int i = 0; i < 3; i++) p->r[i] = g_rand_double_range(rng, -2 * hi, 2 * hi);
}

static void pack(const pair *p, double params[15]) {
  memcpy(params, p->r, sizeof p->r);
  memcpy(params + 3, p->q1, sizeof p->q1);
  memcpy(params + 9, p->q2, sizeof p->q2);
}

/* Semi-axes in [0.5, 2]: Q(lambda) has condition number <= 256, so f is
 * accurate to a small multiple of 256 eps. */
static void test_f_neg_random(void) {
  GRand *rng = g_rand_new_with_seed(31);
  double max_err = 0.0;
  for (int n = 0; n < NUM_PAIRS; n++) {
    pair p;
    random_pair(rng, 0.5, 2.0, &p);
    double params[15];
    pack(&p, params);
    for (int k = 0; k <= 10; k++) {
      double const lambda = k / 10.0;
      double const act = -pw85_f_neg(lambda, params);
      double const exp = (double)f_ld(lambda, p.r, p.q1, p.q2);
      if (k == 0 || k == 10) {
        g_assert_cmpfloat(act, ==, 0.0);
        continue;
      }
      max_err = fmax(max_err, rel_error(act, exp));
    }
  }
  g_test_message("max relative error of f on [0.5, 2]: %.3g", max_err);
  g_assert_cmpfloat(max_err, <=, 256 * 16 * DBL_EPSILON);
  g_rand_free(rng);
}

static void test_f_neg_bad_input(void) {
  double params[15] = {1, 0, 0, 1, 0, 0, 1, 0, 1, 1, 0, 0, 1, 0, 1};
  g_assert_true(isnan(pw85_f_neg(0.5, NULL)));
  g_assert_true(isnan(pw85_f_neg(NAN, params)));
  params[0] = INFINITY;
  g_assert_true(isnan(pw85_f_neg(0.5, params)));
  params[0] = 1.0;
  params[3] = -1.0; /* Q1 indefinite: Q(0) is not positive definite */
  g_assert_true(isnan(pw85_f_neg(0.0, params)));
}

/* mu_i^2 and s from long double: s = Q^{-1} r by Cramer's rule. */
static void reference_residual(double lambda, const pair *p, long double *f,
                               long double *g) {
  long double q[6], qi[3][3];
  for (int i = 0; i < 6; i++) q[i] = (1.0L - lambda) * p->q1[i] + (long double)lambda * p->q2[i];
  long double const m[3][3] = {{q[0], q[1], q[2]}, {q[1], q[3], q[4]}, {q[2], q[4], q[5]}};
  long double const det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                          m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                          m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      int const i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
      qi[i][j] = (m[i1][j1] * m[i2][j2] - m[i1][j2] * m[i2][j1]) / det;
    }
  long double s[3];
  for (int i = 0; i < 3; i++) s[i] = qi[i][0] * p->r[0] + qi[i][1] * p->r[1] + qi[i][2] * p->r[2];
  long double const a1[3][3] = {{p->q1[0], p->q1[1], p->q1[2]},
                                {p->q1[1], p->q1[3], p->q1[4]},
                                {p->q1[2], p->q1[4], p->q1[5]}};
  long double const a2[3][3] = {{p->q2[0], p->q2[1], p->q2[2]},
                                {p->q2[1], p->q2[3], p->q2[4]},
                                {p->q2[2], p->q2[4], p->q2[5]}};
  long double s1 = 0, s2 = 0, rs = 0;
  for (int i = 0; i < 3; i++) {
    rs += p->r[i] * s[i];
    for (int j = 0; j < 3; j++) {
      s1 += s[i] * a1[i][j] * s[j];
      s2 += s[i] * a2[i][j] * s[j];
    }
  }
  long double const l = lambda;
  /* chapter 5, eqs. (1a)-(1b): mu1^2 = (1-l)^2 s.Q1.s, mu2^2 = l^2 s.Q2.s */
  *f = l * (1 - l) * rs;
  *g = l * l * s2 - (1 - l) * (1 - l) * s1;
}

static void test_residual_random(void) {
  GRand *rng = g_rand_new_with_seed(32);
  double max_f = 0, max_g = 0, max_dg = 0;
  for (int n = 0; n < NUM_PAIRS; n++) {
    pair p;
    random_pair(rng, 0.5, 2.0, &p);
    for (int k = 1; k < 10; k++) {
      double const lambda = k / 10.0;
      double out[3];
      pw85__residual(lambda, p.r, p.q1, p.q2, out);
      long double f, g, fp, gp, fm, gm;
      reference_residual(lambda, &p, &f, &g);
      double const h = 1e-4;
      reference_residual(lambda + h, &p, &fp, &gp);
      reference_residual(lambda - h, &p, &fm, &gm);
      long double const dg = (gp - gm) / (2 * h);
      /* g is a difference of terms of the size of f: measure its error on
       * that scale; g' likewise on the scale of f. */
      max_f = fmax(max_f, rel_error(out[0], (double)f));
      max_g = fmax(max_g, fabs(out[1] - (double)g) / (double)f);
      max_dg = fmax(max_dg, fabs(out[2] - (double)dg) / (fabs((double)dg) + (double)f));
    }
  }
  g_test_message("max errors: f %.3g, g %.3g, g' %.3g", max_f, max_g, max_dg);
  g_assert_cmpfloat(max_f, <=, 256 * 16 * DBL_EPSILON);
  g_assert_cmpfloat(max_g, <=, 256 * 64 * DBL_EPSILON);
  /* central difference with h = 1e-4: truncation error O(h^2 g''') */
  g_assert_cmpfloat(max_dg, <=, 1e-6);
  g_rand_free(rng);
}

static void test_residual_bad_input(void) {
  double const r[3] = {1, 0, 0}, q[6] = {1, 0, 0, 1, 0, 1}, bad[6] = {1, 0, 0, 1, 0, -1};
  double out[3];
  pw85__residual(0.5, NULL, q, q, out);
  for (int i = 0; i < 3; i++) g_assert_true(isnan(out[i]));
  out[0] = out[1] = out[2] = 0;
  pw85__residual(NAN, r, q, q, out);
  for (int i = 0; i < 3; i++) g_assert_true(isnan(out[i]));
  out[0] = out[1] = out[2] = 0;
  pw85__residual(0.5, r, bad, bad, out);
  for (int i = 0; i < 3; i++) g_assert_true(isnan(out[i]));
  pw85__residual(0.5, r, q, q, NULL);
}

int main(int argc, char **argv) {
  g_test_init(&argc, &argv, NULL);
  g_test_add_func("/f_neg/random", test_f_neg_random);
  g_test_add_func("/f_neg/bad_input", test_f_neg_bad_input);
  g_test_add_func("/residual/random", test_residual_random);
  g_test_add_func("/residual/bad_input", test_residual_bad_input);
  return g_test_run();
}
