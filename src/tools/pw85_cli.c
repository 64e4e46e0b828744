/* pw85: command-line front end of libpw85.
 *
 *   pw85                       the pw85 tutorial ellipsoids
 *   pw85 --spheroids X1 Y1 Z1 A1 C1 NX1 NY1 NZ1  X2 Y2 Z2 A2 C2 NX2 NY2 NZ2
 *   pw85 --matrices  RX RY RZ  Q1[6]  Q2[6]
 *
 * prints mu^2, lambda and the overlap verdict of the two ellipsoids.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pw85.h"

static int parse(int n, char **args, double *values) {
  for (int i = 0; i < n; i++) {
    char *end;
    errno = 0;
    values[i] = strtod(args[i], &end);
    if (errno != 0 || end == args[i] || *end != '\0') {
      fprintf(stderr, "pw85: not a number: '%s'\n", args[i]);
      return -1;
    }
  }
  return 0;
}

static void usage(FILE *out) {
  fprintf(out,
          "usage: pw85\n"
          "       pw85 --spheroids X1 Y1 Z1 A1 C1 NX1 NY1 NZ1 X2 Y2 Z2 A2 C2 NX2 NY2 NZ2\n"
          "       pw85 --matrices RX RY RZ Q1_00 Q1_01 Q1_02 Q1_11 Q1_12 Q1_22 "
          "Q2_00 ... Q2_22\n"
          "Prints the contact function mu^2 of two ellipsoids, the maximiser lambda\n"
          "and whether they overlap (mu^2 < 1). Without arguments: the ellipsoids of\n"
          "the pw85 1.0 tutorial.\n");
}

static void print_matrix(const char *name, const double q[PW85_SYM]) {
  printf("%s = [%g, %g, %g, %g, %g, %g]\n", name, q[0], q[1], q[2], q[3], q[4], q[5]);
}

int main(int argc, char **argv) {
  double r12[PW85_DIM], q1[PW85_SYM], q2[PW85_SYM];
  if (argc == 1 || (argc == 18 && strcmp(argv[1], "--spheroids") == 0)) {
    /* Tutorial of pw85 1.0: an oblate and a prolate spheroid. */
    double v[16] = {-0.5, 0.4, -0.7, 10., 0.1, 0., 0., 1.,
                    0.2, -0.3, 0.4, 0.5, 5., 1., 0., 0.};
    if (argc == 18 && parse(16, argv + 2, v) != 0) return 2;
    double n1[PW85_DIM] = {v[5], v[6], v[7]}, n2[PW85_DIM] = {v[13], v[14], v[15]};
    for (int k = 0; k < 2; k++) {
      double *n = k == 0 ? n1 : n2;
      double const norm = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      if (!(norm > 0.0)) {
        fprintf(stderr, "pw85: the axis of spheroid %d is zero\n", k + 1);
        return 2;
      }
      for (int i = 0; i < PW85_DIM; i++) n[i] /= norm;
    }
    for (int i = 0; i < PW85_DIM; i++) r12[i] = v[8 + i] - v[i];
    pw85_spheroid(v[3], v[4], n1, q1);
    pw85_spheroid(v[11], v[12], n2, q2);
    printf("ellipsoid 1: centre (%g, %g, %g), spheroid a = %g, c = %g, axis (%g, %g, %g)\n",
           v[0], v[1], v[2], v[3], v[4], n1[0], n1[1], n1[2]);
    printf("ellipsoid 2: centre (%g, %g, %g), spheroid a = %g, c = %g, axis (%g, %g, %g)\n",
           v[8], v[9], v[10], v[11], v[12], n2[0], n2[1], n2[2]);
  } else if (argc == 17 && strcmp(argv[1], "--matrices") == 0) {
    double v[15];
    if (parse(15, argv + 2, v) != 0) return 2;
    memcpy(r12, v, sizeof r12);
    memcpy(q1, v + 3, sizeof q1);
    memcpy(q2, v + 9, sizeof q2);
  } else if (argc == 2 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0)) {
    usage(stdout);
    return 0;
  } else {
    usage(stderr);
    return 2;
  }
  print_matrix("q1", q1);
  print_matrix("q2", q2);
  printf("r12 = (%g, %g, %g)\n", r12[0], r12[1], r12[2]);

  double out[2];
  int const status = pw85_contact_function(r12, q1, q2, out);
  if (status < 0 && status != PW85_ERR_NO_CONVERGENCE) {
    fprintf(stderr, "pw85: %s\n", pw85_strerror(status));
    return 1;
  }
  printf("mu^2 = %.17g\n", out[0]);
  printf("lambda = %.17g\n", out[1]);
  if (status != PW85_OK) printf("warning: %s\n", pw85_strerror(status));
  printf("verdict: %s\n", out[0] < 1.0 ? "overlap (mu^2 < 1)"
                                       : (out[0] == 1.0 ? "external contact (mu^2 = 1)"
                                                        : "no overlap (mu^2 > 1)"));
  return 0;
}
