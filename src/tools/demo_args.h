/* Option values of the demonstration programs (pw85_mc, pw85_md,
 * pw85_edmd): the whole argument must be a number within [lo, hi]. Each
 * returns 0 and writes *out, or -1 (nothing written). */
#ifndef PW85_DEMO_ARGS_H
#define PW85_DEMO_ARGS_H

#include <errno.h>
#include <stdint.h>
#include <stdlib.h>

static inline int parse_long(const char *arg, long lo, long hi, long *out) {
  char *end;
  errno = 0;
  long const v = strtol(arg, &end, 10);
  if (errno != 0 || end == arg || *end != '\0' || v < lo || v > hi) return -1;
  *out = v;
  return 0;
}

static inline int parse_double(const char *arg, double lo, double hi, double *out) {
  char *end;
  errno = 0;
  double const v = strtod(arg, &end);
  if (errno != 0 || end == arg || *end != '\0' || !(v >= lo && v <= hi)) return -1;
  *out = v;
  return 0;
}

/* A seed: any unsigned 64-bit decimal number (no sign). */
static inline int parse_seed(const char *arg, uint64_t *out) {
  char *end;
  errno = 0;
  unsigned long long const v = strtoull(arg, &end, 10);
  if (errno != 0 || end == arg || *end != '\0' || arg[0] == '-' || arg[0] == '+') return -1;
  *out = (uint64_t)v;
  return 0;
}

#endif
