/* Measures the accuracy of pw85_contact against the exact contact geometry
 * (docs/contact_geometry.md, "Measured accuracy"). Built by bench/meson.build:
 *
 *   build/bench/contact_geometry_accuracy data/pw85_ref_data.h5
 *
 * Everything in __float128 from the double inputs: lambda* by six Newton
 * steps on f'(lambda) = (1-lambda)^2 s.Q1 s - lambda^2 s.Q2 s from the
 * library's lambda, Q^{-1} by the adjugate; x0*, n*, mu2* at lambda*.
 * Columns (max/median per group and class):
 *   pt        |x^T Qk^{-1} x / mu2* - 1|, x = x0 and x0 - r (plain residual)
 *   pt_best   the same for x0* rounded to double (the floor of pt)
 *   opp       |m1 + m2|_max, unit outward normals at the double x0
 *   x0        |x0 - x0*|_max / |x0*|_max
 *   n         |n - n*|_max
 *   dlam      |lambda - lambda*|
 *   fp/mu2    |f'(lambda)| / mu2* at the returned lambda
 *   mu2*vsref |mu2* / mu2_ref - 1| (check of the reference computation)
 *   surf      max_k |x^T Qk^{-1} x - mu2*| / (2 |Qk^{-1} x|) / max(|x0|, |x0 - r|)
 *             (distance from the scaled surfaces relative to the size of x0)
 *   surf_best the same for x0* rounded to double */
#include <hdf5.h>
#include <hdf5_hl.h>
#include <math.h>
#include <pw85.h>
#include <stdio.h>
#include <stdlib.h>
typedef __float128 F;
static F fab(F x) { return x < 0 ? -x : x; }
static void solve(const F a[6], const F v[3], F s[3]) {
  F c00 = a[3] * a[5] - a[4] * a[4], c01 = a[2] * a[4] - a[1] * a[5];
  F c02 = a[1] * a[4] - a[2] * a[3], c11 = a[0] * a[5] - a[2] * a[2];
  F c12 = a[1] * a[2] - a[0] * a[4], c22 = a[0] * a[3] - a[1] * a[1];
  F det = a[0] * c00 + a[1] * c01 + a[2] * c02;
  s[0] = (c00 * v[0] + c01 * v[1] + c02 * v[2]) / det;
  s[1] = (c01 * v[0] + c11 * v[1] + c12 * v[2]) / det;
  s[2] = (c02 * v[0] + c12 * v[1] + c22 * v[2]) / det;
}
static void mulv(const F a[6], const F v[3], F o[3]) {
  o[0] = a[0] * v[0] + a[1] * v[1] + a[2] * v[2];
  o[1] = a[1] * v[0] + a[3] * v[1] + a[4] * v[2];
  o[2] = a[2] * v[0] + a[4] * v[1] + a[5] * v[2];
}
static F dot(const F a[3], const F b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void exact(const double *r, const double *q1, const double *q2, F lam, F *lo, F x0[3], F n[3], F *mu2, F *fp0) {
  F R[3], A[6], B[6], Qm[6], D[6], s[3], t[3], u[3], w[3];
  for (int i = 0; i < 3; i++) R[i] = r[i];
  for (int i = 0; i < 6; i++) { A[i] = q1[i]; B[i] = q2[i]; D[i] = B[i] - A[i]; }
  for (int it = 0; it < 6; it++) {
    for (int i = 0; i < 6; i++) Qm[i] = (1 - lam) * A[i] + lam * B[i];
    solve(Qm, R, s);
    mulv(A, s, t); mulv(B, s, u);
    F fp = (1 - lam) * (1 - lam) * dot(s, t) - lam * lam * dot(s, u);
    if (it == 0) *fp0 = fp;
    F phi = dot(R, s);
    mulv(D, s, t); F php = -dot(s, t);
    solve(Qm, t, w); F phpp = 2 * dot(t, w);
    F fpp = -2 * phi + 2 * (1 - 2 * lam) * php + lam * (1 - lam) * phpp;
    if (it < 5) lam -= fp / fpp;
  }
  for (int i = 0; i < 6; i++) Qm[i] = (1 - lam) * A[i] + lam * B[i];
  solve(Qm, R, s); mulv(A, s, t);
  F ns = sqrtl((long double)dot(s, s));
  for (int i = 0; i < 3; i++) { x0[i] = (1 - lam) * t[i]; n[i] = s[i] / ns; }
  *mu2 = lam * (1 - lam) * dot(R, s);
  *lo = lam;
}
static int cmp(const void *a, const void *b) { double x = *(const double *)a, y = *(const double *)b; return (x > y) - (x < y); }
static void report(const char *name, double *v, int n) {
  qsort(v, (size_t)n, sizeof *v, cmp);
  printf(" %s %.1e/%.1e", name, v[n - 1], v[n / 2]);
}
static void run(hid_t f, const char *group, int cls) {
  char path[128]; hsize_t dims[2]; H5T_class_t tc; size_t ts;
  snprintf(path, sizeof path, "%s/mu2", group);
  if (H5LTget_dataset_info(f, path, dims, &tc, &ts) < 0) return;
  int n = (int)dims[0];
  double *r = malloc(24 * n), *q1 = malloc(48 * n), *q2 = malloc(48 * n), *mu2 = malloc(8 * n);
  int *c = malloc(4 * n);
  snprintf(path, sizeof path, "%s/r12", group); H5LTread_dataset_double(f, path, r);
  snprintf(path, sizeof path, "%s/q1", group); H5LTread_dataset_double(f, path, q1);
  snprintf(path, sizeof path, "%s/q2", group); H5LTread_dataset_double(f, path, q2);
  snprintf(path, sizeof path, "%s/mu2", group); H5LTread_dataset_double(f, path, mu2);
  snprintf(path, sizeof path, "%s/class", group); H5LTread_dataset_int(f, path, c);
  double *e[10]; for (int j = 0; j < 10; j++) e[j] = malloc(8 * n);
  int k = 0, bad = 0;
  for (int i = 0; i < n; i++) {
    if (c[i] != cls || mu2[i] == 0.0) continue;
    pw85_contact_t g;
    int st = pw85_contact(r + 3 * i, q1 + 6 * i, q2 + 6 * i, &g);
    if (st != PW85_OK) { bad++; continue; }
    F lam, x0[3], nn[3], m2, fp0;
    exact(r + 3 * i, q1 + 6 * i, q2 + 6 * i, g.lambda, &lam, x0, nn, &m2, &fp0);
    F A[6], B[6], x[3], y[3], g1[3], g2[3], xb[3], yb[3], h1[3], h2[3];
    for (int j = 0; j < 6; j++) { A[j] = q1[6 * i + j]; B[j] = q2[6 * i + j]; }
    for (int d = 0; d < 3; d++) { x[d] = g.x0[d]; y[d] = x[d] - r[3 * i + d];
      xb[d] = (double)x0[d]; yb[d] = xb[d] - r[3 * i + d]; }
    solve(A, x, g1); solve(B, y, g2); solve(A, xb, h1); solve(B, yb, h2);
    F p1 = dot(x, g1) / m2 - 1, p2 = dot(y, g2) / m2 - 1;
    F b1 = dot(xb, h1) / m2 - 1, b2 = dot(yb, h2) / m2 - 1;
    e[0][k] = (double)fmaxl((long double)fab(p1), (long double)fab(p2));
    e[1][k] = (double)fmaxl((long double)fab(b1), (long double)fab(b2));
    long double n1 = sqrtl((long double)dot(g1, g1)), n2 = sqrtl((long double)dot(g2, g2));
    long double nx = fmaxl(fmaxl(fabsl((long double)x0[0]), fabsl((long double)x0[1])), fabsl((long double)x0[2]));
    double eo = 0, ex = 0, en = 0;
    for (int d = 0; d < 3; d++) {
      eo = fmax(eo, fabsl((long double)g1[d] / n1 + (long double)g2[d] / n2));
      ex = fmax(ex, (double)(fab(x[d] - x0[d]) / nx));
      en = fmax(en, (double)fab(g.n[d] - nn[d]));
    }
    e[2][k] = eo; e[3][k] = ex; e[4][k] = en;
    e[5][k] = (double)fab(g.lambda - lam);
    e[6][k] = (double)fab(fp0 / m2);
    e[7][k] = (double)fab(m2 / mu2[i] - 1);
    {
      long double nx1 = sqrtl((long double)dot(x, x)), ny1 = sqrtl((long double)dot(y, y));
      long double d1 = (long double)fab(dot(x, g1) - m2) / (2 * n1), d2 = (long double)fab(dot(y, g2) - m2) / (2 * n2);
      e[8][k] = (double)(fmaxl(d1, d2) / fmaxl(nx1, ny1));
      long double xb1 = sqrtl((long double)dot(xb, xb)), yb1 = sqrtl((long double)dot(yb, yb));
      long double hn1 = sqrtl((long double)dot(h1, h1)), hn2 = sqrtl((long double)dot(h2, h2));
      long double c1 = (long double)fab(dot(xb, h1) - m2) / (2 * hn1), c2 = (long double)fab(dot(yb, h2) - m2) / (2 * hn2);
      e[9][k] = (double)(fmaxl(c1, c2) / fmaxl(xb1, yb1));
    }
    k++;
  }
  printf("%-13s %d: %4d (%d bad)", group, cls, k, bad);
  const char *nm[10] = {"pt", "pt_best", "opp", "x0", "n", "dlam", "fp/mu2", "mu2*vsref", "surf", "surf_best"};
  for (int j = 0; j < 10; j++) report(nm[j], e[j], k);
  printf("\n");
}
int main(int argc, char **argv) {
  hid_t f = H5Fopen(argc > 1 ? argv[1] : "data/pw85_ref_data.h5", H5F_ACC_RDONLY, H5P_DEFAULT);
  for (int c = 0; c < 4; c++) run(f, "/contact", c);
  for (int c = 0; c < 4; c++) run(f, "/near_contact", c);
  return 0;
}
