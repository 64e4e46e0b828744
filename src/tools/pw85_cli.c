/* pw85: command-line front end of libpw85.
 *
 *   pw85                                     the pw85 1.0 tutorial ellipsoids
 *   pw85 [--method M] --spheroids X1 Y1 Z1 A1 C1 NX1 NY1 NZ1  X2 ... NZ2
 *   pw85 [--method M] --matrices  RX RY RZ  Q1[6]  Q2[6]
 *   pw85 [--method M] --batch [FILE|-]      one pair per line, CSV out
 *   pw85 --version | --help
 *
 * One pair: prints mu^2, lambda and the overlap verdict; the exit status is
 * the verdict (0 no overlap, 1 overlap), 2 for bad usage, 3 when the library
 * returns an error status. Batch: one CSV row per pair; 0 when every line
 * gave PW85_OK, 3 otherwise. docs/usage.md, "The `pw85` program".
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "pw85.h"

enum { EXIT_APART = 0, EXIT_OVERLAP = 1, EXIT_USAGE = 2, EXIT_FAILED = 3 };

static const char *const method_names[] = {"DEFAULT", "BRENT", "NEWTON", "RATIONAL", "ZHENG"};
static int const method_ids[] = {PW85_METHOD_DEFAULT, PW85_METHOD_BRENT, PW85_METHOD_NEWTON,
                                 PW85_METHOD_RATIONAL, PW85_METHOD_ZHENG};
enum { N_METHODS = sizeof method_ids / sizeof method_ids[0] };

static const char *method_name(int method) {
  for (int k = 0; k < N_METHODS; k++)
    if (method_ids[k] == method) return method_names[k];
  return "?";
}

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
          "       pw85 [--method M] --spheroids X1 Y1 Z1 A1 C1 NX1 NY1 NZ1 "
          "X2 Y2 Z2 A2 C2 NX2 NY2 NZ2\n"
          "       pw85 [--method M] --matrices RX RY RZ Q1_00 Q1_01 Q1_02 Q1_11 Q1_12 Q1_22 "
          "Q2_00 ... Q2_22\n"
          "       pw85 [--method M] --batch [FILE|-]\n"
          "       pw85 --version | --help\n"
          "Prints the contact function mu^2 of two ellipsoids, the maximiser lambda\n"
          "and whether they overlap (mu^2 < 1). Without arguments: the ellipsoids of\n"
          "the pw85 1.0 tutorial, computed by pw85_contact_function.\n"
          "--method M   DEFAULT (default), BRENT, NEWTON, RATIONAL or ZHENG (any case)\n"
          "--batch      reads pairs from FILE (default or '-': standard input), one per\n"
          "             line: 'RX RY RZ Q1[6] Q2[6]' (15 numbers) or 'C1[3] A1[3] W1 X1 Y1 Z1\n"
          "             C2[3] A2[3] W2 X2 Y2 Z2' (20 numbers: centre, semi-axes, quaternion);\n"
          "             '#' starts a comment; writes CSV: line,mu2,lambda,overlap,status\n"
          "Exit status: one pair: 0 no overlap, 1 overlap, 2 usage error, 3 library error;\n"
          "--batch: 0 every line computed with PW85_OK, 2 usage error, 3 otherwise.\n");
}

static void print_matrix(const char *name, const double q[PW85_SYM]) {
  printf("%s = [%g, %g, %g, %g, %g, %g]\n", name, q[0], q[1], q[2], q[3], q[4], q[5]);
}

/* Quadratic form of an ellipsoid with semi-axes radii along the body axes
 * and orientation the quaternion (w, x, y, z) (HOOMD-blue/GSD order) of any
 * non-zero finite length: divided by its length here (first by its largest
 * component when the sum of squares overflows or underflows), then
 * pw85_ellipsoid_quat. For a zero, NaN or infinite quaternion: returns
 * PW85_ERR_INVALID_ARGUMENT and sets *problem to what is wrong with it (for
 * the caller's message); otherwise the status of pw85_ellipsoid_quat. */
static int ellipsoid_from_quaternion(const double radii[3], const double quat[4], double q[6],
                                     const char **problem) {
  double largest = 0.0;
  int nan_component = 0;
  for (int k = 0; k < 4; k++) {
    nan_component |= isnan(quat[k]);
    largest = fmax(largest, fabs(quat[k]));
  }
  *problem = nan_component ? "is not a number (NaN component)"
             : largest == 0.0 ? "is zero (w = x = y = z = 0): no rotation"
             : isinf(largest) ? "has an infinite component"
                              : NULL;
  if (*problem) return PW85_ERR_INVALID_ARGUMENT;
  double scaled[4] = {quat[0], quat[1], quat[2], quat[3]};
  double norm2 = scaled[0] * scaled[0] + scaled[1] * scaled[1] + scaled[2] * scaled[2] +
                 scaled[3] * scaled[3];
  if (!isfinite(norm2) || norm2 < DBL_MIN) {
    for (int k = 0; k < 4; k++) scaled[k] = quat[k] / largest;
    norm2 = scaled[0] * scaled[0] + scaled[1] * scaled[1] + scaled[2] * scaled[2] +
            scaled[3] * scaled[3];
  }
  double const norm = sqrt(norm2);
  double const unit[4] = {scaled[0] / norm, scaled[1] / norm, scaled[2] / norm, scaled[3] / norm};
  return pw85_ellipsoid_quat(radii, unit, q);
}

/* Splits a batch line into at most max numbers (whitespace or commas
 * between them, '#' to the end of the line a comment). Returns the count,
 * -1 for a token that is not a number, -2 for more than max numbers, -3 for
 * a number beyond the range of double. */
static int parse_line(char *line, double *v, int max) {
  char *hash = strchr(line, '#');
  if (hash) *hash = '\0';
  int n = 0;
  char *p = line;
  for (;;) {
    while (*p == ' ' || *p == '\t' || *p == ',' || *p == '\r' || *p == '\n' || *p == '\v' ||
           *p == '\f')
      p++;
    if (*p == '\0') return n;
    if (n == max) return -2;
    char *end;
    errno = 0;
    v[n] = strtod(p, &end);
    if (errno == ERANGE && isinf(v[n])) return -3;
    if (end == p ||
        !(*end == '\0' || *end == ' ' || *end == '\t' || *end == ',' || *end == '\r' ||
          *end == '\n' || *end == '\v' || *end == '\f'))
      return -1;
    n++;
    p = end;
  }
}

static int run_batch(const char *path, int method) {
  FILE *in = stdin;
  if (path && strcmp(path, "-") != 0) {
    in = fopen(path, "r");
    if (!in) {
      fprintf(stderr, "pw85: cannot open '%s': %s\n", path, strerror(errno));
      return EXIT_USAGE;
    }
  }
  printf("line,mu2,lambda,overlap,status\n");
  char *line = NULL;
  size_t cap = 0;
  ssize_t len;
  long lineno = 0, failed = 0, counted = 0; /* counted: non-blank lines */
  while ((len = getline(&line, &cap, in)) != -1) {
    lineno++;
    if ((size_t)len != strlen(line)) {
      fprintf(stderr, "pw85: line %ld: contains a NUL byte\n", lineno);
      counted++, failed++;
      continue;
    }
    double v[20];
    int const n = parse_line(line, v, 20);
    if (n == 0) continue;
    counted++;
    if (n != 15 && n != 20) {
      if (n == -1)
        fprintf(stderr, "pw85: line %ld: not a number\n", lineno);
      else if (n == -3)
        fprintf(stderr, "pw85: line %ld: number beyond the range of double\n", lineno);
      else
        fprintf(stderr, "pw85: line %ld: expected 15 or 20 numbers, got %s\n", lineno,
                n == -2 ? "more than 20" : (n < 15 ? "fewer than 15" : "between 16 and 19"));
      failed++;
      continue;
    }
    double r12[3], q1[6], q2[6];
    int status = PW85_OK, which = 1;
    const char *quaternion_problem = NULL;
    if (n == 15) {
      memcpy(r12, v, sizeof r12);
      memcpy(q1, v + 3, sizeof q1);
      memcpy(q2, v + 9, sizeof q2);
    } else {
      for (int d = 0; d < 3; d++) r12[d] = v[10 + d] - v[d];
      status = ellipsoid_from_quaternion(v + 3, v + 6, q1, &quaternion_problem);
      if (status == PW85_OK) {
        which = 2;
        status = ellipsoid_from_quaternion(v + 13, v + 16, q2, &quaternion_problem);
      }
    }
    pw85_result res = {NAN, NAN, NAN, 0, method};
    int overlap = -1;
    if (status == PW85_OK) {
      status = pw85_contact_function_method(r12, q1, q2, method, &res);
      overlap = pw85_overlap(r12, q1, q2);
      if (status == PW85_OK && overlap < 0) status = overlap;
    }
    if (overlap >= 0)
      printf("%ld,%.17g,%.17g,%d,%d\n", lineno, res.mu2, res.lambda, overlap, status);
    else
      printf("%ld,%.17g,%.17g,,%d\n", lineno, res.mu2, res.lambda, status);
    if (quaternion_problem) {
      fprintf(stderr, "pw85: line %ld: the quaternion of ellipsoid %d %s\n", lineno, which,
              quaternion_problem);
      failed++;
    } else if (status != PW85_OK) {
      fprintf(stderr, "pw85: line %ld: %s\n", lineno, pw85_strerror(status));
      failed++;
    }
  }
  int const read_error = ferror(in);
  free(line);
  if (in != stdin) fclose(in);
  if (read_error) fprintf(stderr, "pw85: read error after line %ld\n", lineno);
  if (fflush(stdout) != 0 || ferror(stdout)) {
    fprintf(stderr, "pw85: write error\n");
    return EXIT_FAILED;
  }
  if (failed) fprintf(stderr, "pw85: %ld of %ld lines failed\n", failed, counted);
  return failed || read_error ? EXIT_FAILED : EXIT_APART;
}

int main(int argc, char **argv) {
  /* Tutorial of pw85 1.0: an oblate and a prolate spheroid. */
  double v[16] = {-0.5, 0.4, -0.7, 10., 0.1, 0., 0., 1., 0.2, -0.3, 0.4, 0.5, 5., 1., 0., 0.};
  double r12[PW85_DIM], q1[PW85_SYM], q2[PW85_SYM];
  int method = PW85_METHOD_DEFAULT, have_pair = 0, batch = 0;
  const char *batch_path = NULL;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
      usage(stdout);
      return EXIT_APART;
    } else if (!strcmp(a, "--version")) {
      printf("pw85 %s\n", pw85_version());
      return EXIT_APART;
    } else if (!strcmp(a, "--method")) {
      if (i + 1 == argc) {
        fprintf(stderr, "pw85: --method needs a name\n");
        return EXIT_USAGE;
      }
      const char *name = argv[++i];
      method = -1;
      for (int k = 0; k < N_METHODS; k++)
        if (!strcasecmp(name, method_names[k])) method = method_ids[k];
      if (method < 0) {
        fprintf(stderr, "pw85: unknown method '%s' (DEFAULT, BRENT, NEWTON, RATIONAL, ZHENG)\n",
                name);
        return EXIT_USAGE;
      }
    } else if ((!strcmp(a, "--batch") || !strcmp(a, "--spheroids") || !strcmp(a, "--matrices")) &&
               (have_pair || batch)) {
      fprintf(stderr, "pw85: %s: only one of --spheroids, --matrices and --batch may be given\n",
              a);
      return EXIT_USAGE;
    } else if (!strcmp(a, "--batch")) {
      batch = 1;
      if (i + 1 < argc && (strncmp(argv[i + 1], "--", 2) != 0)) batch_path = argv[++i];
    } else if (!strcmp(a, "--spheroids") || !strcmp(a, "--matrices")) {
      int const spheroids = !strcmp(a, "--spheroids"), needed = spheroids ? 16 : 15;
      int given = 0; /* the arguments up to the next option */
      while (given < needed && i + 1 + given < argc && strncmp(argv[i + 1 + given], "--", 2) != 0)
        given++;
      if (given < needed) {
        fprintf(stderr, "pw85: %s needs %d numbers (%s), got %d\n", a, needed,
                spheroids ? "X1 Y1 Z1 A1 C1 NX1 NY1 NZ1 X2 Y2 Z2 A2 C2 NX2 NY2 NZ2"
                          : "RX RY RZ Q1_00 Q1_01 Q1_02 Q1_11 Q1_12 Q1_22 Q2_00 ... Q2_22",
                given);
        return EXIT_USAGE;
      }
      double m[16];
      if (parse(needed, argv + i + 1, m) != 0) return EXIT_USAGE;
      if (spheroids) {
        memcpy(v, m, sizeof v);
      } else {
        memcpy(r12, m, sizeof r12);
        memcpy(q1, m + 3, sizeof q1);
        memcpy(q2, m + 9, sizeof q2);
      }
      have_pair = spheroids ? 1 : 2;
      i += needed;
    } else {
      fprintf(stderr, "pw85: unexpected argument '%s'\n", a);
      usage(stderr);
      return EXIT_USAGE;
    }
  }
  if (batch) return run_batch(batch_path, method);

  if (have_pair != 2) {
    double n1[PW85_DIM] = {v[5], v[6], v[7]}, n2[PW85_DIM] = {v[13], v[14], v[15]};
    for (int k = 0; k < 2; k++) {
      double *n = k == 0 ? n1 : n2;
      double const norm = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      if (!(norm > 0.0)) {
        fprintf(stderr, "pw85: the axis of spheroid %d is zero\n", k + 1);
        return EXIT_USAGE;
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
  }
  print_matrix("q1", q1);
  print_matrix("q2", q2);
  printf("r12 = (%g, %g, %g)\n", r12[0], r12[1], r12[2]);

  double out[2] = {NAN, NAN};
  int status;
  if (argc == 1) {
    /* pw85 1.0's call, as in its tutorial. */
    status = pw85_contact_function(r12, q1, q2, out);
  } else {
    pw85_result res;
    status = pw85_contact_function_method(r12, q1, q2, method, &res);
    out[0] = res.mu2, out[1] = res.lambda;
    printf("method = %s\n", method_name(method));
  }
  if (status < 0 && isnan(out[0])) {
    fprintf(stderr, "pw85: %s\n", pw85_strerror(status));
    return EXIT_FAILED;
  }
  printf("mu^2 = %.17g\n", out[0]);
  printf("lambda = %.17g\n", out[1]);
  if (status != PW85_OK) {
    printf("warning: %s\n", pw85_strerror(status));
    fprintf(stderr, "pw85: %s\n", pw85_strerror(status));
  }
  printf("verdict: %s\n", out[0] < 1.0 ? "overlap (mu^2 < 1)"
                                       : (out[0] == 1.0 ? "external contact (mu^2 = 1)"
                                                        : "no overlap (mu^2 > 1)"));
  if (status != PW85_OK) return EXIT_FAILED;
  return out[0] < 1.0 ? EXIT_OVERLAP : EXIT_APART;
}
