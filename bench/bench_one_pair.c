/* ns per call of the one-pair calls pw85_overlap and
 * pw85_contact_function_method (PW85_METHOD_DEFAULT) over the pairs of a
 * file, the C side of bench/bench_python.py (which writes the file and runs
 * this program in the same run as its Python timings). Thread CPU time of a
 * pass over the n pairs, `reps` passes after an untimed one; prints one
 * line per call: name, then the ns per call of each pass.
 *
 *   build/bench/bench_one_pair PAIRS_FILE REPS
 *
 * PAIRS_FILE: n (int64), then r12 (n x 3), q1 (n x 6), q2 (n x 6) as
 * native doubles. */
#define _POSIX_C_SOURCE 199309L
#include <pw85.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

int main(int argc, char **argv) {
  if (argc != 3) {
    fprintf(stderr, "usage: %s PAIRS_FILE REPS\n", argv[0]);
    return 2;
  }
  int reps = atoi(argv[2]);
  FILE *f = fopen(argv[1], "rb");
  int64_t n = 0;
  if (f == NULL || fread(&n, sizeof n, 1, f) != 1 || n <= 0 || n > 100000000 || reps <= 0) {
    fprintf(stderr, "%s: cannot read %s (or REPS <= 0)\n", argv[0], argv[1]);
    return 2;
  }
  double *r12 = malloc(sizeof(double) * 15 * (size_t)n);
  if (r12 == NULL || fread(r12, sizeof(double), 15 * (size_t)n, f) != 15 * (size_t)n) {
    fprintf(stderr, "%s: %s is short\n", argv[0], argv[1]);
    return 2;
  }
  fclose(f);
  double const *q1 = r12 + 3 * n, *q2 = q1 + 6 * n;
  volatile int sink = 0;
  printf("pw85_overlap");
  for (int rep = 0; rep <= reps; ++rep) {
    double t0 = now();
    for (int64_t k = 0; k < n; ++k) sink += pw85_overlap(r12 + 3 * k, q1 + 6 * k, q2 + 6 * k);
    if (rep) printf(" %.2f", (now() - t0) / n * 1e9);
  }
  printf("\npw85_contact_function_method");
  pw85_result res;
  for (int rep = 0; rep <= reps; ++rep) {
    double t0 = now();
    for (int64_t k = 0; k < n; ++k)
      sink += pw85_contact_function_method(r12 + 3 * k, q1 + 6 * k, q2 + 6 * k,
                                           PW85_METHOD_DEFAULT, &res);
    if (rep) printf(" %.2f", (now() - t0) / n * 1e9);
  }
  printf("\n");
  free(r12);
  return 0;
}
