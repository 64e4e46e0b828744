#include "testutil.h"

#include <math.h>
#include <stdlib.h>

double rel_error(double act, double exp) {
  if (act == exp) return 0.0;
  if (exp == 0.0) return fabs(act);
  return fabs(act - exp) / fabs(exp);
}

int correct_digits(double act, double exp, int num_bins) {
  if (act == exp) return num_bins - 1;
  if (exp == 0.0) return 0; /* a relative error of act against 0 is not defined */
  double const err = rel_error(act, exp);
  if (!(err < 1.0)) return 0; /* also NaN */
  int d = (int)floor(-log10(err));
  if (d < 0) d = 0;
  if (d > num_bins - 1) d = num_bins - 1;
  return d;
}

void random_axes(GRand *rng, double axes[9]) {
  /* Unit quaternion from four Gaussian deviates (Box-Muller) -> rotation. */
  double g[4];
  for (int i = 0; i < 4; i += 2) {
    double u1 = g_rand_double_range(rng, 1e-300, 1.0);
    double u2 = g_rand_double(rng);
    g[i] = sqrt(-2.0 * log(u1)) * cos(2.0 * G_PI * u2);
    g[i + 1] = sqrt(-2.0 * log(u1)) * sin(2.0 * G_PI * u2);
  }
  double n = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2] + g[3] * g[3]);
  double w = g[0] / n, x = g[1] / n, y = g[2] / n, z = g[3] / n;
  double m[9] = {1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w),
                 2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w),
                 2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)};
  for (int i = 0; i < 9; i++) axes[i] = m[i];
}

void random_radii(GRand *rng, double lo, double hi, double radii[3]) {
  for (int i = 0; i < 3; i++)
    radii[i] = exp(g_rand_double_range(rng, log(lo), log(hi)));
}

void make_q(const double radii[3], const double axes[9], double q[6]) {
  int idx = 0;
  for (int i = 0; i < 3; i++)
    for (int j = i; j < 3; j++, idx++) {
      long double s = 0.0L;
      for (int k = 0; k < 3; k++)
        s += (long double)radii[k] * radii[k] * axes[3 * k + i] * axes[3 * k + j];
      q[idx] = (double)s;
    }
}

void random_spd(GRand *rng, double cond, double a[6]) {
  double radii[3], axes[9];
  double const h = 0.25 * log(cond); /* radii^2 in [cond^-1/2, cond^1/2] */
  for (int i = 0; i < 3; i++) radii[i] = exp(g_rand_double_range(rng, -h, h));
  random_axes(rng, axes);
  make_q(radii, axes, a);
}

void sphere_q(double a, double q[6]) {
  q[0] = q[3] = q[5] = a * a;
  q[1] = q[2] = q[4] = 0.0;
}

/* Determinants and adjugates use __float128 (113-bit significand): the
 * products of three doubles then carry almost no rounding, so the
 * references stay accurate for condition numbers up to ~1e12. */
typedef __float128 hp;

/* Symmetric matrix entries (i, j) from the upper-triangle storage. */
static hp entry(const long double a[6], int i, int j) {
  static const int index[3][3] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};
  return a[index[i][j]];
}

static long double det_ld(const long double a[6]) {
  return (long double)(entry(a, 0, 0) * (entry(a, 1, 1) * entry(a, 2, 2) - entry(a, 1, 2) * entry(a, 2, 1)) -
         entry(a, 0, 1) * (entry(a, 1, 0) * entry(a, 2, 2) - entry(a, 1, 2) * entry(a, 2, 0)) +
         entry(a, 0, 2) * (entry(a, 1, 0) * entry(a, 2, 1) - entry(a, 1, 1) * entry(a, 2, 0)));
}

/* x^T adj(A) x, adj(A)_ij = cofactor C_ji = C_ij for symmetric A. */
static long double xT_adj_x_ld(const long double a[6], const long double x[3]) {
  hp const x0 = x[0], x1 = x[1], x2 = x[2];
  hp c00 = entry(a, 1, 1) * entry(a, 2, 2) - entry(a, 1, 2) * entry(a, 1, 2);
  hp c11 = entry(a, 0, 0) * entry(a, 2, 2) - entry(a, 0, 2) * entry(a, 0, 2);
  hp c22 = entry(a, 0, 0) * entry(a, 1, 1) - entry(a, 0, 1) * entry(a, 0, 1);
  hp c01 = entry(a, 0, 2) * entry(a, 1, 2) - entry(a, 0, 1) * entry(a, 2, 2);
  hp c02 = entry(a, 0, 1) * entry(a, 1, 2) - entry(a, 0, 2) * entry(a, 1, 1);
  hp c12 = entry(a, 0, 1) * entry(a, 0, 2) - entry(a, 0, 0) * entry(a, 1, 2);
  return (long double)(c00 * x0 * x0 + c11 * x1 * x1 + c22 * x2 * x2 +
                       2 * (c01 * x0 * x1 + c02 * x0 * x2 + c12 * x1 * x2));
}

long double xT_inv_x_ld(const double a[6], const long double x[3]) {
  long double al[6];
  for (int i = 0; i < 6; i++) al[i] = a[i];
  return xT_adj_x_ld(al, x) / det_ld(al);
}

long double f_ld(long double lambda, const double r[3], const double q1[6],
                 const double q2[6]) {
  long double q[6], x[3];
  for (int i = 0; i < 6; i++) q[i] = (1.0L - lambda) * q1[i] + lambda * q2[i];
  for (int i = 0; i < 3; i++) x[i] = r[i];
  return lambda * (1.0L - lambda) * xT_adj_x_ld(q, x) / det_ld(q);
}

long double mu2_ld(const double r[3], const double q1[6], const double q2[6],
                   long double *lambda) {
  const long double invphi = 0.618033988749894848204586834365638118L;
  long double a = 0.0L, b = 1.0L;
  long double c = b - invphi * (b - a), d = a + invphi * (b - a);
  long double fc = f_ld(c, r, q1, q2), fd = f_ld(d, r, q1, q2);
  for (int it = 0; it < 200 && b - a > 1e-15L; it++) {
    if (fc > fd) {
      b = d, d = c, fd = fc;
      c = b - invphi * (b - a);
      fc = f_ld(c, r, q1, q2);
    } else {
      a = c, c = d, fc = fd;
      d = a + invphi * (b - a);
      fd = f_ld(d, r, q1, q2);
    }
  }
  long double const l = 0.5L * (a + b);
  if (lambda != NULL) *lambda = l;
  return f_ld(l, r, q1, q2);
}

const char *ref_data_path(void) {
  const char *env = getenv("PW85_REF_DATA");
  if (env != NULL && env[0] != '\0') return env;
  return PW85_REF_DATA_PATH;
}

static void inverse_ld(const long double q[6], long double qi[3][3]) {
  long double const m[3][3] = {{q[0], q[1], q[2]}, {q[1], q[3], q[4]}, {q[2], q[4], q[5]}};
  long double const det = det_ld(q);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      int const i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
      qi[i][j] = (m[i1][j1] * m[i2][j2] - m[i1][j2] * m[i2][j1]) / det;
    }
}

void df_ld(long double lambda, const double r[3], const double q1[6], const double q2[6],
           long double *df, long double *d2f) {
  long double q[6], qi[3][3], d[6];
  for (int i = 0; i < 6; i++) {
    q[i] = (1.0L - lambda) * q1[i] + lambda * q2[i];
    d[i] = (long double)q2[i] - q1[i];
  }
  inverse_ld(q, qi);
  long double const dm[3][3] = {{d[0], d[1], d[2]}, {d[1], d[3], d[4]}, {d[2], d[4], d[5]}};
  long double s[3], u[3], v[3];
  for (int i = 0; i < 3; i++) s[i] = qi[i][0] * r[0] + qi[i][1] * r[1] + qi[i][2] * r[2];
  for (int i = 0; i < 3; i++) u[i] = dm[i][0] * s[0] + dm[i][1] * s[1] + dm[i][2] * s[2];
  for (int i = 0; i < 3; i++) v[i] = qi[i][0] * u[0] + qi[i][1] * u[1] + qi[i][2] * u[2];
  long double rs = 0, su = 0, uv = 0;
  for (int i = 0; i < 3; i++) rs += r[i] * s[i], su += s[i] * u[i], uv += u[i] * v[i];
  long double const l = lambda;
  *df = (1 - 2 * l) * rs - l * (1 - l) * su;
  *d2f = -2 * rs - 2 * (1 - 2 * l) * su + 2 * l * (1 - l) * uv;
}

void grid_direction(int k, double n[3]) {
  /* Icosahedron: cyclic permutations of (0, +-1, +-phi), normalised. */
  double const phi = 0.5 * (1.0 + sqrt(5.0));
  double const norm = sqrt(1.0 + phi * phi);
  int const perm = k / 4, s1 = (k & 1) ? -1 : 1, s2 = (k & 2) ? -1 : 1;
  double v[3] = {0.0, s1 * 1.0 / norm, s2 * phi / norm};
  for (int i = 0; i < 3; i++) n[(i + perm) % 3] = v[i];
}

void grid_spheroid(int i, double q[6]) {
  static const double radii[3] = {0.01999, 1.999, 9.999};
  int const ia = i / 36, ic = (i / 12) % 3, in = i % 12;
  double n[3];
  grid_direction(in, n);
  double const a = radii[ia], c = radii[ic];
  /* Q = a^2 I + (c^2 - a^2) n n^T, in long double (independent of the library). */
  long double const a2 = (long double)a * a, d = (long double)c * c - a2;
  q[0] = (double)(a2 + d * n[0] * n[0]);
  q[1] = (double)(d * n[0] * n[1]);
  q[2] = (double)(d * n[0] * n[2]);
  q[3] = (double)(a2 + d * n[1] * n[1]);
  q[4] = (double)(d * n[1] * n[2]);
  q[5] = (double)(a2 + d * n[2] * n[2]);
}

/* Cofactor expansion of the full symmetric matrix, written out independently
 * of the library (by minors of the first column). */
__float128 q_det_sym(const __float128 a[6]) {
  __float128 const m00 = a[0], m01 = a[1], m02 = a[2];
  __float128 const m11 = a[3], m12 = a[4], m22 = a[5];
  return m00 * (m11 * m22 - m12 * m12) - m01 * (m01 * m22 - m02 * m12) +
         m02 * (m01 * m12 - m02 * m11);
}

__float128 q_xT_adjA_x(const __float128 x[3], const __float128 a[6]) {
  /* Full matrix and its 9 cofactors C_ij = (-1)^(i+j) M_ij; adj = C^T. */
  __float128 m[3][3] = {{a[0], a[1], a[2]}, {a[1], a[3], a[4]}, {a[2], a[4], a[5]}};
  __float128 s = 0;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      int const r0 = (j + 1) % 3, r1 = (j + 2) % 3; /* rows of the minor of adj_ij = C_ji */
      int const c0 = (i + 1) % 3, c1 = (i + 2) % 3;
      /* cyclic indices give the sign (-1)^(i+j) for free */
      __float128 const cof = m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0];
      s += x[i] * cof * x[j];
    }
  }
  return s;
}

void q_interpolate(const double q1[6], const double q2[6], double lambda, __float128 q[6]) {
  __float128 const l = lambda, one_minus = 1 - l;
  for (int i = 0; i < 6; ++i) q[i] = one_minus * q1[i] + l * q2[i];
}

static void q_solve(const __float128 q[6], __float128 det, const __float128 b[3],
                    __float128 x[3]) {
  __float128 const c00 = q[3] * q[5] - q[4] * q[4];
  __float128 const c01 = q[2] * q[4] - q[1] * q[5];
  __float128 const c02 = q[1] * q[4] - q[2] * q[3];
  __float128 const c11 = q[0] * q[5] - q[2] * q[2];
  __float128 const c12 = q[1] * q[2] - q[0] * q[4];
  __float128 const c22 = q[0] * q[3] - q[1] * q[1];
  x[0] = (c00 * b[0] + c01 * b[1] + c02 * b[2]) / det;
  x[1] = (c01 * b[0] + c11 * b[1] + c12 * b[2]) / det;
  x[2] = (c02 * b[0] + c12 * b[1] + c22 * b[2]) / det;
}

void q_f_derivs(double lambda, const double r[3], const double q1[6], const double q2[6],
                double out[3]) {
  __float128 q[6], d[6];
  q_interpolate(q1, q2, lambda, q);
  for (int i = 0; i < 6; ++i) d[i] = (__float128)q2[i] - q1[i];
  __float128 const det = q_det_sym(q);
  __float128 const rr[3] = {r[0], r[1], r[2]};
  __float128 s[3], u[3], v[3];
  q_solve(q, det, rr, s);
  u[0] = d[0] * s[0] + d[1] * s[1] + d[2] * s[2];
  u[1] = d[1] * s[0] + d[3] * s[1] + d[4] * s[2];
  u[2] = d[2] * s[0] + d[4] * s[1] + d[5] * s[2];
  q_solve(q, det, u, v);
  __float128 const rs = rr[0] * s[0] + rr[1] * s[1] + rr[2] * s[2];
  __float128 const su = s[0] * u[0] + s[1] * u[1] + s[2] * u[2];
  __float128 const uv = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
  __float128 const l = lambda, w = l * (1 - l);
  out[0] = (double)(w * rs);
  out[1] = (double)((1 - 2 * l) * rs - w * su);
  out[2] = (double)(-2 * rs - 2 * (1 - 2 * l) * su + 2 * w * uv);
}
