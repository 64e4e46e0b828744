/* Measures the accuracy of pw85_contact against the reference data
 * (docs/contact_geometry.md). Not part of the build:
 *
 *   cc -O2 -std=c11 docs/contact_geometry_accuracy.c -Iinclude \
 *      $(pkg-config --cflags hdf5) -Lbuild/src -lpw85 -Wl,-rpath,$PWD/build/src \
 *      -lhdf5_serial_hl -lhdf5_serial -lm -o /tmp/cga && /tmp/cga data/pw85_ref_data.h5
 *
 * For each group (/contact per class, /near_contact) and pair it evaluates, in
 * long double (x87, 64-bit mantissa) from the double outputs:
 *   e_point  = max(|x0^T Q1^-1 x0 / mu2_ref - 1|, |(x0-r)^T Q2^-1 (x0-r) / mu2_ref - 1|)
 *              (the contact point on both ellipsoids scaled by mu, eqs. (14a)-(14b));
 *   e_normal = max_i |n_i - (Q1^-1 x0)_i / |Q1^-1 x0||   (n against the exact
 *              normal of ellipsoid 1 at the computed x0);
 *   e_opp    = max_i |m1_i + m2_i| with m_k the unit outward normals at x0;
 *   e_dca    = |dca - |r| / mu_ref| / (|r| / mu_ref);
 * Q^-1 y through the adjugate in long double. Prints max and median. */
#include <hdf5.h>
#include <hdf5_hl.h>
#include <math.h>
#include <pw85.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void adj_times(const double *q, const long double *x, long double *y, long double *det) {
  long double a = q[0], b = q[1], c = q[2], d = q[3], e = q[4], f = q[5];
  long double A00 = d * f - e * e, A01 = c * e - b * f, A02 = b * e - c * d;
  long double A11 = a * f - c * c, A12 = b * c - a * e, A22 = a * d - b * b;
  y[0] = A00 * x[0] + A01 * x[1] + A02 * x[2];
  y[1] = A01 * x[0] + A11 * x[1] + A12 * x[2];
  y[2] = A02 * x[0] + A12 * x[1] + A22 * x[2];
  *det = a * A00 + b * A01 + c * A02;
}

static int cmp(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static void report(const char *name, double *v, int n) {
  if (n == 0) return;
  qsort(v, (size_t)n, sizeof *v, cmp);
  printf(" %s max %.2e med %.2e", name, v[n - 1], v[n / 2]);
}

static void run(hid_t f, const char *group, int cls) {
  char path[128];
  hsize_t dims[2];
  H5T_class_t tc;
  size_t ts;
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
  double *ep = malloc(8 * n), *en = malloc(8 * n), *eo = malloc(8 * n), *ed = malloc(8 * n);
  int k = 0, bad = 0;
  for (int i = 0; i < n; i++) {
    if ((cls >= 0 && c[i] != cls) || mu2[i] == 0.0) continue;
    pw85_contact_t g;
    int s = pw85_contact(r + 3 * i, q1 + 6 * i, q2 + 6 * i, &g);
    if (s != PW85_OK) { bad++; continue; }
    long double x[3], y[3], g1[3], g2[3], d1, d2;
    for (int d = 0; d < 3; d++) { x[d] = g.x0[d]; y[d] = (long double)g.x0[d] - r[3 * i + d]; }
    adj_times(q1 + 6 * i, x, g1, &d1);
    adj_times(q2 + 6 * i, y, g2, &d2);
    long double s1 = (x[0] * g1[0] + x[1] * g1[1] + x[2] * g1[2]) / d1 / mu2[i];
    long double s2 = (y[0] * g2[0] + y[1] * g2[1] + y[2] * g2[2]) / d2 / mu2[i];
    ep[k] = (double)fmaxl(fabsl(s1 - 1), fabsl(s2 - 1));
    long double n1 = sqrtl(g1[0] * g1[0] + g1[1] * g1[1] + g1[2] * g1[2]);
    long double n2 = sqrtl(g2[0] * g2[0] + g2[1] * g2[1] + g2[2] * g2[2]);
    double emn = 0, emo = 0;
    for (int d = 0; d < 3; d++) {
      emn = fmax(emn, (double)fabsl(g.n[d] - g1[d] / n1));
      emo = fmax(emo, (double)fabsl(g1[d] / n1 + g2[d] / n2));
    }
    en[k] = emn;
    eo[k] = emo;
    long double nr = sqrtl((long double)r[3 * i] * r[3 * i] + (long double)r[3 * i + 1] * r[3 * i + 1] +
                           (long double)r[3 * i + 2] * r[3 * i + 2]);
    long double dca = nr / sqrtl((long double)mu2[i]);
    ed[k] = (double)(fabsl(g.dca - dca) / dca);
    k++;
  }
  printf("%-14s class %2d: %5d pairs, %d status != OK;", group, cls, k, bad);
  report("e_point", ep, k);
  report("e_normal", en, k);
  report("e_opp", eo, k);
  report("e_dca", ed, k);
  printf("\n");
  free(r), free(q1), free(q2), free(mu2), free(c), free(ep), free(en), free(eo), free(ed);
}

int main(int argc, char **argv) {
  hid_t f = H5Fopen(argc > 1 ? argv[1] : "data/pw85_ref_data.h5", H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) return 1;
  for (int c = 0; c < 4; c++) run(f, "/contact", c);
  for (int c = 0; c < 4; c++) run(f, "/near_contact", c);
  H5Fclose(f);
  return 0;
}
