/* Tests of pw85_overlap: verdicts against the high-precision
 * reference data (mu2 computed in exact rational arithmetic from the stored
 * doubles), exact tangency constructed with exactly representable contact,
 * bad input. */
#include <float.h>
#include <math.h>
#include <pw85.h>

#include "refdata.h"
#include "testutil.h"

/* Zero wrong verdicts on a reference group; *exact_side counts pairs whose
 * stored mu2 is within 1e-6 of 1 (to show the group exercises the hard
 * cases). */
static void check_group(const char *name, double min_gap) {
  RefPairs *g = refdata_pairs_or_skip(name);
  if (g == NULL) return;
  size_t wrong = 0, hard = 0, used = 0;
  for (size_t i = 0; i < g->n; i++) {
    double const mu2 = g->mu2[i];
    /* The stored double is the correctly rounded mu2: its side of 1 is the
     * true side unless it rounds to exactly 1. */
    if (mu2 == 1.0 || fabs(mu2 - 1.0) < min_gap) continue;
    used++;
    if (fabs(mu2 - 1.0) < 1e-6) hard++;
    int const v = pw85_overlap(g->r12 + 3 * i, g->q1 + 6 * i, g->q2 + 6 * i);
    g_assert_cmpint(v, >=, 0);
    if (v != (mu2 < 1.0 ? 1 : 0)) {
      wrong++;
      g_test_message("%s row %zu: mu2 = %.17g, verdict %d", name, i, mu2, v);
    }
  }
  g_test_message("%s: %zu pairs, %zu with |mu2 - 1| < 1e-6, %zu wrong", name, used, hard,
                 wrong);
  g_assert_cmpuint(wrong, ==, 0);
  g_assert_cmpuint(used, >, g->n / 2);
  refdata_pairs_free(g);
}

static void test_reference_near_contact(void) { check_group("/near_contact", 0.0); }
static void test_reference_contact(void) { check_group("/contact", 0.0); }
static void test_reference_special(void) { check_group("/special", 0.0); }

/* Spheres of radii 1.5 and 1, centres at distance exactly 2.5 along
 * (3/5, 4/5, 0): r12 = (1.5, 2, 0). Tangent: 0; one ulp closer: 1. */
static void test_tangent_spheres(void) {
  double q1[6], q2[6];
  sphere_q(1.5, q1);
  sphere_q(1.0, q2);
  double r[3] = {1.5, 2.0, 0.0};
  g_assert_cmpint(pw85_overlap(r, q1, q2), ==, 0);
  double closer[3] = {nextafter(1.5, 0.0), 2.0, 0.0};
  g_assert_cmpint(pw85_overlap(closer, q1, q2), ==, 1);
  double farther[3] = {nextafter(1.5, 2.0), 2.0, 0.0};
  g_assert_cmpint(pw85_overlap(farther, q1, q2), ==, 0);
  /* Swapping the ellipsoids (r12 -> -r12) does not change the verdicts. */
  double mr[3] = {-1.5, -2.0, -0.0};
  g_assert_cmpint(pw85_overlap(mr, q2, q1), ==, 0);
  double mcloser[3] = {-nextafter(1.5, 0.0), -2.0, 0.0};
  g_assert_cmpint(pw85_overlap(mcloser, q2, q1), ==, 1);
}

/* Radii 1 and 2 along x (lambda* = 1/3 is not a double): tangent at 3. */
static void test_tangent_spheres_irrational_lambda(void) {
  double q1[6], q2[6];
  sphere_q(1.0, q1);
  sphere_q(2.0, q2);
  double r[3] = {3.0, 0.0, 0.0};
  g_assert_cmpint(pw85_overlap(r, q1, q2), ==, 0);
  r[0] = nextafter(3.0, 0.0);
  g_assert_cmpint(pw85_overlap(r, q1, q2), ==, 1);
  r[0] = nextafter(3.0, 4.0);
  g_assert_cmpint(pw85_overlap(r, q1, q2), ==, 0);
}

/* Ellipsoids with axes along x, y, z, centres on an axis: the tips touch at
 * |r12| = sum of the semi-axes along it and the plane through the tips
 * separates them, so this is exact external tangency. Extreme aspect ratios
 * included. */
static void test_tangent_aligned(void) {
  static const double semi[][6] = {
      {2.0, 1.0, 0.5, 1.0, 3.0, 2.0},
      {0x1p-10, 1024.0, 1.0, 1024.0, 0x1p-10, 0.5},
      {1024.0, 0x1p-10, 0x1p-10, 0x1p-10, 1024.0, 1024.0},
      {0.75, 0.25, 4.0, 0.125, 8.0, 0.5},
  };
  for (size_t c = 0; c < G_N_ELEMENTS(semi); c++) {
    double q1[6] = {semi[c][0] * semi[c][0], 0, 0, semi[c][1] * semi[c][1], 0,
                    semi[c][2] * semi[c][2]};
    double q2[6] = {semi[c][3] * semi[c][3], 0, 0, semi[c][4] * semi[c][4], 0,
                    semi[c][5] * semi[c][5]};
    for (int axis = 0; axis < 3; axis++) {
      double const a = semi[c][axis], b = semi[c][3 + axis];
      double d = a + b;
      /* The sum and the squares are exact doubles (two-sum, fma). */
      double const bb = d - a;
      g_assert_cmpfloat((a - (d - bb)) + (b - bb), ==, 0.0);
      g_assert_cmpfloat(fma(a, a, -(a * a)), ==, 0.0);
      g_assert_cmpfloat(fma(b, b, -(b * b)), ==, 0.0);
      double r[3] = {0, 0, 0};
      r[axis] = d;
      g_assert_cmpint(pw85_overlap(r, q1, q2), ==, 0);
      r[axis] = nextafter(d, 0.0);
      g_assert_cmpint(pw85_overlap(r, q1, q2), ==, 1);
      r[axis] = nextafter(d, 2 * d);
      g_assert_cmpint(pw85_overlap(r, q1, q2), ==, 0);
      r[axis] = -d;
      g_assert_cmpint(pw85_overlap(r, q1, q2), ==, 0);
    }
  }
}

/* Sweep across exact tangency of axis-aligned ellipsoids whose centres lie
 * on a common axis: the tips touch at |r12| = a + b, so the verdict is 1 iff
 * |r12| < a + b. At this configuration the separating plane normal to r12
 * (eq. (O11)) is exactly tight and the quartic p of eq. (O4) has its minimum
 * 0 at tangency, so a wrong sign, a missing margin or a strict/non-strict
 * mix-up in the plane test or in a certificate on p (eqs. (O13), (O14),
 * (O18)) gives a wrong verdict here. The same pairs
 * are repeated with Q scaled by 4^k and r12 by 2^k (mu^2 unchanged, exact):
 * k = 0, +-25 stay in the range where no scaling is done, k = +-40, +-200
 * go through the exact power-of-two scaling (eq. (O1)). */
static void test_tangent_sweep(void) {
  static const double semi[][6] = {
      {2.0, 1.0, 0.5, 1.0, 3.0, 2.0},
      {0x1p-10, 1024.0, 1.0, 1024.0, 0x1p-10, 0.5},
      {0.75, 0.25, 4.0, 0.125, 8.0, 0.5},
      {1.0, 1.0, 1.0, 1.0, 1.0, 1.0},
  };
  static const int scale_k[] = {0, 25, -25, 40, -40, 200, -200};
  static const double rel[] = {0x1p-52, 0x1p-51, 0x1p-50, 0x1p-48, 0x1p-45, 0x1p-40,
                               0x1p-30, 1e-6,    1e-3,    0.1};
  int checked = 0;
  for (size_t c = 0; c < G_N_ELEMENTS(semi); c++)
    for (size_t sk = 0; sk < G_N_ELEMENTS(scale_k); sk++) {
      int const k = scale_k[sk];
      double q1[6] = {ldexp(semi[c][0] * semi[c][0], 2 * k), 0, 0,
                      ldexp(semi[c][1] * semi[c][1], 2 * k), 0,
                      ldexp(semi[c][2] * semi[c][2], 2 * k)};
      double q2[6] = {ldexp(semi[c][3] * semi[c][3], 2 * k), 0, 0,
                      ldexp(semi[c][4] * semi[c][4], 2 * k), 0,
                      ldexp(semi[c][5] * semi[c][5], 2 * k)};
      for (int axis = 0; axis < 3; axis++) {
        double const d = ldexp(semi[c][axis] + semi[c][3 + axis], k); /* exact */
        for (size_t i = 0; i < G_N_ELEMENTS(rel); i++)
          for (int side = -1; side <= 1; side += 2) {
            double r[3] = {0, 0, 0};
            r[axis] = d * (1.0 + side * rel[i]);
            int const expect = r[axis] < d ? 1 : 0;
            g_assert_cmpint(pw85_overlap(r, q1, q2), ==, expect);
            /* Swapped ellipsoids, opposite direction. */
            double mr[3] = {-r[0], -r[1], -r[2]};
            g_assert_cmpint(pw85_overlap(mr, q2, q1), ==, expect);
            checked++;
          }
        double r[3] = {0, 0, 0};
        r[axis] = d;
        g_assert_cmpint(pw85_overlap(r, q1, q2), ==, 0);
      }
    }
  g_assert_cmpint(checked, ==, 4 * 7 * 3 * 10 * 2);
}

/* Elongated ellipsoids (semi-axes in [0.01, 100]) with centre distance
 * between 0.05 and 1.2 times the sum of the largest semi-axes: many pairs
 * near contact with the contact point off the line of centres, so neither
 * the plane normal to r12 nor the coefficient test (O13) decides them; the
 * subdivision of p (eq. (O18)) and, nearer tangency, the minimisation of p
 * and the witnesses (eqs. (O14), (O6)) do.
 * Verdicts against the long-double reference, away from tangency
 * (|mu2 - 1| > 1e-7, the reference's accuracy margin). */
static void test_off_axis(void) {
  GRand *rng = g_rand_new_with_seed(2026);
  int checked = 0;
  for (int k = 0; k < 2000; k++) {
    double rad[3], ax[9], q1[6], q2[6], r[3];
    random_radii(rng, 0.01, 100, rad);
    random_axes(rng, ax);
    make_q(rad, ax, q1);
    random_radii(rng, 0.01, 100, rad);
    random_axes(rng, ax);
    make_q(rad, ax, q2);
    /* Centre distance near the sum of the largest semi-axes: many pairs
     * near contact, with elongated shapes (contact off the line of centres). */
    double amax1 = sqrt(fmax(q1[0], fmax(q1[3], q1[5])));
    double amax2 = sqrt(fmax(q2[0], fmax(q2[3], q2[5])));
    double const scale = (amax1 + amax2) * exp(g_rand_double_range(rng, log(0.05), log(1.2)));
    double nrm = 0.0;
    for (int i = 0; i < 3; i++) {
      r[i] = g_rand_double_range(rng, -1, 1);
      nrm += r[i] * r[i];
    }
    for (int i = 0; i < 3; i++) r[i] *= scale / sqrt(nrm);
    long double lam;
    long double const mu2 = mu2_ld(r, q1, q2, &lam);
    if (fabsl(mu2 - 1.0L) < 1e-7L * (1 + mu2)) continue;
    g_assert_cmpint(pw85_overlap(r, q1, q2), ==, mu2 < 1.0L ? 1 : 0);
    checked++;
  }
  g_assert_cmpint(checked, >, 1900);
  g_rand_free(rng);
}

/* Far apart / deep overlap / coincident centres, against a long-double
 * golden-section reference away from tangency. */
static void test_random_clear(void) {
  GRand *rng = g_rand_new_with_seed(6006);
  static const double range[4][2] = {{0.5, 2}, {0.1, 10}, {0.01, 100}, {0.001, 1000}};
  int checked = 0;
  for (int c = 0; c < 4; c++)
    for (int k = 0; k < 300; k++) {
      double rad[3], ax[9], q1[6], q2[6], r[3];
      random_radii(rng, range[c][0], range[c][1], rad);
      random_axes(rng, ax);
      make_q(rad, ax, q1);
      random_radii(rng, range[c][0], range[c][1], rad);
      random_axes(rng, ax);
      make_q(rad, ax, q2);
      double scale = exp(g_rand_double_range(rng, log(1e-3), log(1e3)));
      for (int i = 0; i < 3; i++) r[i] = scale * g_rand_double_range(rng, -1, 1);
      long double lam;
      long double mu2 = mu2_ld(r, q1, q2, &lam);
      if (fabsl(mu2 - 1.0L) < 1e-6L * (1 + mu2)) continue;
      g_assert_cmpint(pw85_overlap(r, q1, q2), ==, mu2 < 1.0L ? 1 : 0);
      checked++;
    }
  g_assert_cmpint(checked, >, 1000);
  double q[6] = {1, 0, 0, 1, 0, 1}, zero[3] = {0, 0, 0};
  g_assert_cmpint(pw85_overlap(zero, q, q), ==, 1);
  g_rand_free(rng);
}

/* A far pair whose r12 is out of scale with its matrices: 2^515 (1, 1/2, 1/4)
 * with entries <= 1 is separated (mu^2 ~ 2^1030), by (O19). */
static void test_far_pair(void) {
  double const q1[6] = {1, 0.1, -0.2, 0.5, 0.05, 0.3};
  double const q2[6] = {0.2, -0.05, 0.01, 0.9, 0.1, 0.4};
  for (int k = 30; k <= 1023; k++) {
    double const r[3] = {ldexp(1., k), ldexp(0.5, k), ldexp(0.25, k)};
    int const v = pw85_overlap(r, q1, q2);
    if (v != 0) g_error("k = %d: pw85_overlap returns %d, expected 0", k, v);
  }
}

/* Exact power-of-two scalings over the whole double range (docs/stability.md,
 * "Accepted input ranges"): r -> 2^kr r, Q -> 2^kq Q scales mu^2 by
 * 2^(2 kr - kq); the verdict must be mu^2 < 1 for mu^2 from the long double
 * reference of the unscaled pair (scalings putting mu^2 within 1e-9 of 1
 * skipped), for every scaling whose inputs are exact doubles. */
static int overlap_scaled_ok(const double R[3], const double Q1[6], const double Q2[6],
                             long double mu0, int kr, int kq) {
  double r[3], q1[6], q2[6];
  for (int i = 0; i < 3; i++) {
    r[i] = ldexp(R[i], kr);
    if (ldexp(r[i], -kr) != R[i]) return 1;
  }
  for (int i = 0; i < 6; i++) {
    q1[i] = ldexp(Q1[i], kq);
    q2[i] = ldexp(Q2[i], kq);
    if (ldexp(q1[i], -kq) != Q1[i] || ldexp(q2[i], -kq) != Q2[i]) return 1;
  }
  long double const mu2 = ldexpl(mu0, 2 * kr - kq);
  if (fabsl(mu2 - 1) <= 1e-9L) return 1;
  int const v = pw85_overlap(r, q1, q2);
  if (v != (mu2 < 1)) {
    g_test_message("kr = %d kq = %d: pw85_overlap = %d, mu2 = %Lg", kr, kq, v, mu2);
    return 0;
  }
  return 1;
}

static void test_extreme_scale(void) {
  double const R[3] = {1.25, -0.5, 0.75};
  double const Q1[6] = {1, 0.1, -0.2, 0.5, 0.05, 0.3};
  double const Q2[6] = {0.2, -0.05, 0.01, 0.9, 0.1, 0.4};
  /* few significant bits: exact down to the subnormal range */
  double const S1[6] = {1, 0.125, -0.25, 0.5, 0.0625, 0.375};
  double const S2[6] = {0.25, -0.0625, 0, 1, 0.125, 0.5};
  struct { const double *q1, *q2; } const pairs[] = {{Q1, Q2}, {S1, S2}};
  int bad = 0;
  for (size_t p = 0; p < G_N_ELEMENTS(pairs); p++) {
    long double lambda;
    long double const mu0 = mu2_ld(R, pairs[p].q1, pairs[p].q2, &lambda);
    for (int k = -1074; k <= 1023; k++) {
      bad += !overlap_scaled_ok(R, pairs[p].q1, pairs[p].q2, mu0, k, 0);
      bad += !overlap_scaled_ok(R, pairs[p].q1, pairs[p].q2, mu0, 0, k);
      bad += !overlap_scaled_ok(R, pairs[p].q1, pairs[p].q2, mu0, k, 2 * k);
    }
  }
  g_assert_cmpint(bad, ==, 0);
  /* Magnitude ratio: Q2 -> 2^k Q2, a verdict or PW85_ERR_INACCURATE; the
   * verdict range around k = 0 is reported (docs/stability.md). */
  int lo = 0, hi = 0, n_inaccurate = 0;
  for (int k = -1070; k <= 1023; k++) {
    double q2[6];
    for (int i = 0; i < 6; i++) q2[i] = ldexp(S2[i], k);
    int const v = pw85_overlap(R, S1, q2);
    g_assert_true(v == 0 || v == 1 || v == PW85_ERR_INACCURATE);
    n_inaccurate += v == PW85_ERR_INACCURATE;
  }
  for (int k = 0; k >= -1070; k--) {
    double q2[6];
    for (int i = 0; i < 6; i++) q2[i] = ldexp(S2[i], k);
    if (pw85_overlap(R, S1, q2) < 0) break;
    lo = k;
  }
  for (int k = 0; k <= 1023; k++) {
    double q2[6];
    for (int i = 0; i < 6; i++) q2[i] = ldexp(S2[i], k);
    if (pw85_overlap(R, S1, q2) < 0) break;
    hi = k;
  }
  g_test_message("ratio Q2 = 2^k Q2: a verdict for every k in [%d, %d]; %d of k = -1070..1023 "
                 "PW85_ERR_INACCURATE", lo, hi, n_inaccurate);
}

static void test_bad_input(void) {
  double q[6] = {1, 0, 0, 1, 0, 1}, r[3] = {1, 0, 0};
  double notspd[6] = {1, 2, 0, 1, 0, 1};
  double nanq[6] = {1, 0, 0, NAN, 0, 1};
  double infr[3] = {INFINITY, 0, 0};
  g_assert_cmpint(pw85_overlap(NULL, q, q), ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_overlap(r, NULL, q), ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_overlap(r, q, NULL), ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_overlap(r, nanq, q), ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_overlap(infr, q, q), ==, PW85_ERR_INVALID_ARGUMENT);
  g_assert_cmpint(pw85_overlap(r, q, notspd), ==, PW85_ERR_NOT_SPD);
  double neg[6] = {-1, 0, 0, 1, 0, 1};
  g_assert_cmpint(pw85_overlap(r, neg, q), ==, PW85_ERR_NOT_SPD);
}

int main(int argc, char **argv) {
  g_test_init(&argc, &argv, NULL);
  g_test_add_func("/pw85_overlap/reference/near_contact", test_reference_near_contact);
  g_test_add_func("/pw85_overlap/reference/contact", test_reference_contact);
  g_test_add_func("/pw85_overlap/reference/special", test_reference_special);
  g_test_add_func("/pw85_overlap/tangent/spheres", test_tangent_spheres);
  g_test_add_func("/pw85_overlap/tangent/spheres-irrational-lambda",
                  test_tangent_spheres_irrational_lambda);
  g_test_add_func("/pw85_overlap/tangent/aligned-axes", test_tangent_aligned);
  g_test_add_func("/pw85_overlap/random/clear-cases", test_random_clear);
  g_test_add_func("/pw85_overlap/tangent/sweep-scaled", test_tangent_sweep);
  g_test_add_func("/pw85_overlap/random/off-axis-near-contact", test_off_axis);
  g_test_add_func("/pw85_overlap/bad-input", test_bad_input);
  g_test_add_func("/pw85_overlap/far_pair", test_far_pair);
  g_test_add_func("/pw85_overlap/extreme_scale", test_extreme_scale);
  return g_test_run();
}
