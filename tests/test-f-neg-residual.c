/* pw85_f_neg and pw85__residual (pw85 1.0) against long-double evaluations
 * through the adjugate (tests/testutil.c), a route independent of the
 * library's Cholesky code, and pw85_f_neg against the dataset /F of the
 * reference data (data/README.md: exact rational arithmetic on the stored
 * doubles, correctly rounded, so the errors measured are the library's
 * alone; skipped when the file is absent). */
#include <float.h>
#include <math.h>
#include <string.h>

#include <pw85.h>

#include "refdata.h"
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

/* ---- /F: pw85_f_neg --------------------------------------------------- */

/* Histogram of correct digits (pw85 documentation, section 4.3): bin
 * floor(-log10(relative error)) clamped to [0, 15]; exact results go to the
 * last bin. */
#define NUM_BINS 16

static int digits_bin(double err) {
  if (err == 0.0) return NUM_BINS - 1;
  double const d = floor(-log10(err));
  if (!(d > 0.0)) return 0; /* also NaN */
  if (d >= NUM_BINS - 1) return NUM_BINS - 1;
  return (int)d;
}

static void test_f_neg_reference(void) {
  hid_t file;
  if (!refdata_open_or_skip(&file)) return;
  hsize_t ds[2], dd[2], dl[1], df[4];
  double *spheroids = refdata_read_double(file, "/spheroids", 2, ds);
  double *directions = refdata_read_double(file, "/directions", 2, dd);
  double *lambdas = refdata_read_double(file, "/lambdas", 1, dl);
  double *F = refdata_read_double(file, "/F", 4, df);
  refdata_close(file);
  g_assert_nonnull(spheroids);
  g_assert_nonnull(directions);
  g_assert_nonnull(lambdas);
  g_assert_nonnull(F);
  g_assert_cmpuint(ds[1], ==, PW85_SYM);
  g_assert_cmpuint(dd[1], ==, PW85_DIM);
  g_assert_cmpuint(df[0], ==, ds[0]);
  g_assert_cmpuint(df[1], ==, ds[0]);
  g_assert_cmpuint(df[2], ==, dd[0]);
  g_assert_cmpuint(df[3], ==, dl[0]);
  g_assert_cmpuint(df[0] * df[1] * df[2] * df[3], ==, 108 * 108 * 12 * 11);

  guint64 hist[NUM_BINS] = {0};
  guint64 n = 0, zeros = 0, above = 0;
  double max_err = 0.0;
  gsize worst = 0;
  double params[PW85_DIM + 2 * PW85_SYM];
  const double *exp = F;
  for (hsize_t i1 = 0; i1 < df[0]; i1++) {
    memcpy(params + PW85_DIM, spheroids + PW85_SYM * i1, sizeof(double) * PW85_SYM);
    for (hsize_t i2 = 0; i2 < df[1]; i2++) {
      memcpy(params + PW85_DIM + PW85_SYM, spheroids + PW85_SYM * i2,
             sizeof(double) * PW85_SYM);
      for (hsize_t k = 0; k < df[2]; k++) {
        memcpy(params, directions + PW85_DIM * k, sizeof(double) * PW85_DIM);
        for (hsize_t j = 0; j < df[3]; j++, exp++, n++) {
          double const act = -pw85_f_neg(lambdas[j], params);
          double err;
          if (*exp == 0.0) {
            /* lambda = 0 or 1: f vanishes identically, exactly. */
            zeros++;
            err = act == 0.0 ? 0.0 : INFINITY;
          } else {
            err = isnan(act) ? INFINITY : rel_error(act, *exp);
          }
          if (err > max_err) max_err = err, worst = (gsize)(exp - F);
          if (err > 1e-10) above++;
          hist[digits_bin(err)]++;
        }
      }
    }
  }
  g_assert_cmpuint(n, ==, 108 * 108 * 12 * 11);

  /* The histogram, as a message and as CSV next to the test program. */
  GString *line = g_string_new("");
  GString *csv = g_string_new("digits,count,percent\n");
  for (int b = 0; b < NUM_BINS; b++) {
    double const pc = 100.0 * (double)hist[b] / (double)n;
    g_string_append_printf(line, " %d:%.2f%%", b, pc);
    g_string_append_printf(csv, "%d,%" G_GUINT64_FORMAT ",%.4f\n", b, hist[b], pc);
  }
  gsize const per_entry = df[3], per_dir = df[2] * per_entry, per_i2 = df[1] * per_dir;
  g_test_message("/F: %" G_GUINT64_FORMAT " entries (%" G_GUINT64_FORMAT
                 " exact zeros), max rel. error %.3g at [%zu,%zu,%zu,%zu], %" G_GUINT64_FORMAT
                 " above 1e-10",
                 n, zeros, max_err, worst / per_i2, (worst % per_i2) / per_dir,
                 (worst % per_dir) / per_entry, worst % per_entry, above);
  g_test_message("/F: correct digits (bin: percent of entries; bin 15 includes exact):%s",
                 line->str);
  char *csv_path = g_test_build_filename(G_TEST_BUILT, "refdata-f-neg-histogram.csv", NULL);
  GError *error = NULL;
  if (g_file_set_contents(csv_path, csv->str, -1, &error))
    g_test_message("/F: histogram written to %s", csv_path);
  else {
    g_test_message("/F: could not write %s: %s", csv_path, error->message);
    g_clear_error(&error);
  }
  g_free(csv_path);
  g_string_free(line, TRUE);
  g_string_free(csv, TRUE);

  g_assert_cmpuint(above, ==, 0);
  g_assert_cmpfloat(max_err, <=, 1e-10);
  g_free(spheroids);
  g_free(directions);
  g_free(lambdas);
  g_free(F);
}

/* Exact power-of-two scalings over the whole double range (docs/stability.md,
 * "Accepted input ranges"): r -> 2^kr r, Q -> 2^kq Q multiply f, g and g'
 * by 2^(2 kr - kq). Reference: the unscaled call, scaled exactly in long
 * double and rounded once, within 2 eps (the unscaled evaluation of Q scaled
 * by an odd power of two differs in the roundings of its square roots);
 * inputs exact at both scales. Values beyond the double range come out as
 * +-Inf, subnormal or 0 (the rounded value). */
static int f_scaled_ok(const double R[3], const double Q1[6], const double Q2[6], int kr, int kq,
                       double *worst) {
  double p0[15], p[15];
  for (int i = 0; i < 3; i++) {
    p0[i] = R[i];
    p[i] = ldexp(R[i], kr);
    if (ldexp(p[i], -kr) != R[i]) return 1;
  }
  for (int i = 0; i < 6; i++) {
    p0[3 + i] = Q1[i], p0[9 + i] = Q2[i];
    p[3 + i] = ldexp(Q1[i], kq), p[9 + i] = ldexp(Q2[i], kq);
    if (ldexp(p[3 + i], -kq) != Q1[i] || ldexp(p[9 + i], -kq) != Q2[i]) return 1;
  }
  int const e = 2 * kr - kq;
  double const lambda = 0.3;
  double out0[3], out[3], got[4], ref[4];
  pw85__residual(lambda, p0, p0 + 3, p0 + 9, out0);
  pw85__residual(lambda, p, p + 3, p + 9, out);
  got[0] = pw85_f_neg(lambda, p);
  ref[0] = -pw85_f_neg(lambda, p0);
  for (int i = 0; i < 3; i++) got[1 + i] = out[i], ref[1 + i] = out0[i];
  got[0] = -got[0];
  int ok = 1;
  for (int i = 0; i < 4; i++) {
    double const ex = (double)ldexpl(ref[i], e); /* rounded once */
    double const err = ex == got[i] ? 0. : fabs(got[i] - ex) / fabs(ex);
    *worst = fmax(*worst, isfinite(ex) && fabs(ex) >= DBL_MIN ? err : 0.);
    /* below DBL_MIN: the same relative error plus one subnormal rounding */
    int const good = !isfinite(ex) ? got[i] == ex
                                   : fabs(got[i] - ex) <= 2 * DBL_EPSILON * fabs(ex) + 0x1p-1074;
    if (!good) {
      g_test_message("kr = %d kq = %d: output %d = %.17g, expected %.17g", kr, kq, i, got[i], ex);
      ok = 0;
    }
  }
  return ok;
}

static void test_f_neg_extreme_scale(void) {
  double const R[3] = {1.25, -0.5, 0.75};
  double const Q1[6] = {1, 0.125, -0.25, 0.5, 0.0625, 0.375};
  double const Q2[6] = {0.25, -0.0625, 0, 1, 0.125, 0.5};
  int bad = 0;
  double worst = 0.;
  for (int k = -1074; k <= 1023; k++) {
    bad += !f_scaled_ok(R, Q1, Q2, k, 0, &worst);
    bad += !f_scaled_ok(R, Q1, Q2, 0, k, &worst);
    bad += !f_scaled_ok(R, Q1, Q2, k, 2 * k, &worst);
  }
  g_test_message("largest deviation %.3g eps; %d scalings wrong", worst / DBL_EPSILON, bad);
  g_assert_cmpint(bad, ==, 0);
}

int main(int argc, char **argv) {
  g_test_init(&argc, &argv, NULL);
  g_test_add_func("/pw85_f_neg/random", test_f_neg_random);
  g_test_add_func("/pw85_f_neg/bad_input", test_f_neg_bad_input);
  g_test_add_func("/pw85_f_neg/reference/F", test_f_neg_reference);
  g_test_add_func("/pw85__residual/random", test_residual_random);
  g_test_add_func("/pw85__residual/bad_input", test_residual_bad_input);
  g_test_add_func("/pw85_f_neg/extreme_scale", test_f_neg_extreme_scale);
  return g_test_run();
}
