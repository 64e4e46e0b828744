/* ns per pw85_contact call per class of /contact: thread CPU time of a pass
 * over the 5000 pairs of the class, minimum over 7 passes
 * (docs/contact_geometry.md). Built by bench/meson.build:
 *
 *   build/bench/contact_geometry_timing data/pw85_ref_data.h5 */
#define _POSIX_C_SOURCE 199309L
#include <hdf5.h>
#include <hdf5_hl.h>
#include <pw85.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
static double now(void) { struct timespec t; clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t); return t.tv_sec + 1e-9 * t.tv_nsec; }
int main(int argc, char **argv) {
  hid_t f = H5Fopen(argc > 1 ? argv[1] : "data/pw85_ref_data.h5", H5F_ACC_RDONLY, H5P_DEFAULT);
  hsize_t dims[2]; H5T_class_t tc; size_t ts;
  H5LTget_dataset_info(f, "/contact/mu2", dims, &tc, &ts);
  int n = (int)dims[0];
  double *r = malloc(24 * n), *q1 = malloc(48 * n), *q2 = malloc(48 * n);
  int *c = malloc(4 * n);
  H5LTread_dataset_double(f, "/contact/r12", r); H5LTread_dataset_double(f, "/contact/q1", q1);
  H5LTread_dataset_double(f, "/contact/q2", q2); H5LTread_dataset_int(f, "/contact/class", c);
  volatile double sink = 0;
  for (int cls = 0; cls < 4; cls++) {
    double best = 1e30; int k = 0;
    for (int rep = 0; rep < 7; rep++) {
      double t0 = now(); k = 0;
      for (int i = 0; i < n; i++) {
        if (c[i] != cls) continue;
        pw85_contact_t g; pw85_contact(r + 3 * i, q1 + 6 * i, q2 + 6 * i, &g); sink += g.x0[0]; k++;
      }
      double t = (now() - t0) / k * 1e9; if (t < best) best = t;
    }
    printf("class %d: %d pairs, %.0f ns/call\n", cls, k, best);
  }
  return 0;
}
