/* ns per call of the functions the benchmarks do not time: the constructors
 * pw85_spheroid, pw85_ellipsoid, pw85_ellipsoid_quat, pw85_ellipsoid_rotation
 * and the inverse pw85_ellipsoid_axes, and the legacy contact functions of
 * libpw85_legacy next to pw85_contact_function, per class of /contact
 * (docs/guide.md, docs/legacy.md). Thread CPU time of a pass over the 5000
 * pairs of a class, minimum over 7 passes.
 *
 *   build/bench/timing_misc data/pw85_ref_data.h5 */
#define _POSIX_C_SOURCE 199309L
#include <hdf5.h>
#include <hdf5_hl.h>
#include <math.h>
#include <pw85.h>
#include <pw85_legacy.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

typedef int (*contact_fn)(double const *, double const *, double const *, double *);

static int legacy1(double const *r, double const *q1, double const *q2, double *out) {
  return pw85_legacy_contact_function1(r, q1, q2, out);
}
static int legacy2(double const *r, double const *q1, double const *q2, double *out) {
  return pw85_legacy_contact_function2(r, q1, q2, out);
}
static int pw85_10(double const *r, double const *q1, double const *q2, double *out) {
  return pw85_contact_function(r, q1, q2, out);
}

int main(int argc, char **argv) {
  hid_t f = H5Fopen(argc > 1 ? argv[1] : "data/pw85_ref_data.h5", H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) return 1;
  hsize_t dims[2];
  H5T_class_t tc;
  size_t ts;
  H5LTget_dataset_info(f, "/contact/mu2", dims, &tc, &ts);
  int n = (int)dims[0];
  double *r = malloc(24 * (size_t)n), *q1 = malloc(48 * (size_t)n), *q2 = malloc(48 * (size_t)n);
  double *mu2 = malloc(8 * (size_t)n);
  int *c = malloc(4 * (size_t)n);
  H5LTread_dataset_double(f, "/contact/r12", r);
  H5LTread_dataset_double(f, "/contact/q1", q1);
  H5LTread_dataset_double(f, "/contact/q2", q2);
  H5LTread_dataset_double(f, "/contact/mu2", mu2);
  H5LTread_dataset_int(f, "/contact/class", c);
  H5Fclose(f);
  volatile double sink = 0;

  /* Constructors: random unit axes, semi-axes in [0.5, 2]. */
  enum { M = 100000 };
  double *in = malloc(sizeof(double) * 16 * M), *qs = malloc(sizeof(double) * 6 * M);
  srand(1);
  for (int i = 0; i < M; i++) {
    double *p = in + 16 * i;
    for (int k = 0; k < 3; k++) p[k] = 0.5 + 1.5 * rand() / (double)RAND_MAX;
    double w = rand() / (double)RAND_MAX - .5, x = rand() / (double)RAND_MAX - .5,
           y = rand() / (double)RAND_MAX - .5, z = rand() / (double)RAND_MAX - .5;
    double nn = sqrt(w * w + x * x + y * y + z * z);
    w /= nn; x /= nn; y /= nn; z /= nn;
    double R[9] = {1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),
                   2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
                   2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)};
    for (int k = 0; k < 9; k++) p[3 + k] = R[k];
    p[12] = w, p[13] = x, p[14] = y, p[15] = z;
    pw85_ellipsoid(p, p + 3, qs + 6 * i);
  }
  double best_s = 1e30, best_e = 1e30, best_q = 1e30, best_r = 1e30, best_a = 1e30;
  for (int rep = 0; rep < 7; rep++) {
    double q[6], t0 = now();
    for (int i = 0; i < M; i++) {
      double const *p = in + 16 * i;
      pw85_spheroid(p[0], p[1], p + 3, q);
      sink += q[0];
    }
    double t = (now() - t0) / M * 1e9;
    if (t < best_s) best_s = t;
    t0 = now();
    for (int i = 0; i < M; i++) {
      double const *p = in + 16 * i;
      sink += pw85_ellipsoid(p, p + 3, q);
      sink += q[0];
    }
    t = (now() - t0) / M * 1e9;
    if (t < best_e) best_e = t;
    t0 = now();
    for (int i = 0; i < M; i++) {
      double const *p = in + 16 * i;
      sink += pw85_ellipsoid_quat(p, p + 12, q);
      sink += q[0];
    }
    t = (now() - t0) / M * 1e9;
    if (t < best_q) best_q = t;
    t0 = now();
    for (int i = 0; i < M; i++) {
      double const *p = in + 16 * i;
      sink += pw85_ellipsoid_rotation(p, p + 3, q);
      sink += q[0];
    }
    t = (now() - t0) / M * 1e9;
    if (t < best_r) best_r = t;
    t0 = now();
    for (int i = 0; i < M; i++) {
      double radii[3], rot[9], quat[4];
      sink += pw85_ellipsoid_axes(qs + 6 * i, radii, rot, quat);
      sink += radii[0] + rot[0] + quat[0];
    }
    t = (now() - t0) / M * 1e9;
    if (t < best_a) best_a = t;
  }
  printf("pw85_spheroid: %.1f ns/call\npw85_ellipsoid: %.1f ns/call\n", best_s, best_e);
  printf("pw85_ellipsoid_quat: %.1f ns/call\npw85_ellipsoid_rotation: %.1f ns/call\n"
         "pw85_ellipsoid_axes: %.1f ns/call\n", best_q, best_r, best_a);

  struct { char const *name; contact_fn fn; } fns[] = {
      {"pw85_contact_function", pw85_10},
      {"pw85_legacy_contact_function1", legacy1},
      {"pw85_legacy_contact_function2", legacy2}};
  for (int m = 0; m < 3; m++) {
    for (int cls = 0; cls < 4; cls++) {
      double best = 1e30, maxerr = 0;
      int k = 0, notok = 0;
      for (int rep = 0; rep < 7; rep++) {
        double t0 = now();
        k = 0;
        for (int i = 0; i < n; i++) {
          if (c[i] != cls) continue;
          double out[2];
          int st = fns[m].fn(r + 3 * i, q1 + 6 * i, q2 + 6 * i, out);
          sink += out[0];
          k++;
          if (rep == 0) {
            if (st != PW85_OK) notok++;
            else {
              double e = fabs(out[0] - mu2[i]) / mu2[i];
              if (e > maxerr) maxerr = e;
            }
          }
        }
        double t = (now() - t0) / k * 1e9;
        if (t < best) best = t;
      }
      printf("%-30s class %d: %d pairs, %.0f ns/call, max rel. error (PW85_OK) %.2g, not PW85_OK %d\n",
             fns[m].name, cls, k, best, maxerr, notok);
    }
  }
  (void)sink;
  return 0;
}
