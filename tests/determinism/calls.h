/* Every public one-pair function of libpw85 and libpw85_legacy called on one
 * generated input, each output's bits handed to a sink: shared by the
 * determinism program (which prints them) and the thread stress test (which
 * hashes them). */
#ifndef PW85_TEST_CALLS_H
#define PW85_TEST_CALLS_H

#include <stdint.h>
#include <stdio.h>

/* One input: a pair of ellipsoids and the scalars the other functions take. */
typedef struct {
  double r12[3], q1[6], q2[6];
  double lambda;         /* for pw85_f_neg, pw85__residual, pw85_legacy_f1/f2 */
  double a, c, n[3];     /* for pw85_spheroid */
  double radii[3], axes[9]; /* for pw85_ellipsoid */
  double theta_tol;      /* for pw85_dca_ex */
  int kind;              /* which generator made it (gen_input) */
} test_input;

/* Deterministic generator (splitmix64). */
typedef struct { uint64_t s; } test_rng;
uint64_t rng_next(test_rng *g);
double rng_uniform(test_rng *g); /* in [0, 1) */

/* Number of input kinds; gen_input(g, k % TEST_KINDS, in) makes one:
 * moderate pairs, magnitudes 1e-300..1e300, aspect ratios up to 1e16,
 * near-singular matrices, r12 = 0, NaN/Inf entries, random bit patterns,
 * non-SPD matrices, matrices of very different scales, near tangency. */
#define TEST_KINDS 10
void gen_input(test_rng *g, int kind, test_input *in);

/* Receives the outputs of one call: name of the function (and method),
 * its int result, n doubles. */
typedef struct test_sink test_sink;
struct test_sink {
  void (*put)(test_sink *s, char const *fn, long long status, double const *v, int n);
  FILE *out;      /* printing sink */
  long long call; /* number of calls so far */
  uint64_t hash;  /* hashing sink */
};
void sink_print(test_sink *s, char const *fn, long long status, double const *v, int n);
void sink_hash(test_sink *s, char const *fn, long long status, double const *v, int n);

/* Calls every public one-pair function (both libraries) on in, twice each
 * for pw85_overlap (the pair and its swap). */
void call_all(test_input const *in, test_sink *s);

#endif
