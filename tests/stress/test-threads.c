/* Thread stress test: several threads call every public one-pair function
 * of both libraries (tests/determinism/calls.c) and the three batch calls
 * (nthreads = 1) on the same inputs at once; every result must have the
 * bits of a single-threaded run. Under ThreadSanitizer (.ci/run's
 * build-tsan) a data race is reported and fails the test.
 *
 * usage: test-threads [THREADS [INPUTS [ROUNDS]]]   (defaults 4, 2000, 2) */
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "calls.h"
#include "pw85.h"

static long n_inputs, rounds;
static test_input *inputs;
static uint64_t *reference;

/* Scene for the batch calls: ellipsoid i has centre i * (1, 0.5, 0.25) / 4
 * and the form q1 of input i (kind 0, valid); pairs (i, i + 1), (i + 1, i). */
enum { SCENE = 64, PAIRS = 2 * (SCENE - 1) };
static double centres[3 * SCENE], forms[6 * SCENE];
static long long pairs[2 * PAIRS];
typedef struct {
  int overlap[PAIRS], st_overlap[PAIRS], st_cf[PAIRS], st_c[PAIRS];
  double cf[2 * PAIRS];
  pw85_contact_t c[PAIRS];
} batch_out;
static batch_out batch_reference;

static void run_batch(batch_out *b) {
  memset(b, 0, sizeof *b);
  pw85_overlap_batch(SCENE, centres, forms, PAIRS, pairs, b->overlap, b->st_overlap, 1);
  pw85_contact_function_batch(SCENE, centres, forms, PAIRS, pairs, b->cf, b->st_cf, 1);
  pw85_contact_batch(SCENE, centres, forms, PAIRS, pairs, b->c, b->st_c, 1);
}

static uint64_t hash_of(test_input const *in) {
  test_sink s = {sink_hash, NULL, 0, 0xcbf29ce484222325ULL};
  call_all(in, &s);
  return s.hash;
}

static void *worker(void *arg) {
  long const id = (long)arg;
  long bad = 0;
  for (long r = 0; r < rounds; ++r) {
    for (long k = 0; k < n_inputs; ++k) {
      long const i = (k + id * 997) % n_inputs; /* threads start at different inputs */
      if (hash_of(&inputs[i]) != reference[i]) ++bad;
    }
    batch_out b;
    run_batch(&b);
    if (memcmp(&b, &batch_reference, sizeof b) != 0) ++bad;
  }
  return (void *)bad;
}

int main(int argc, char **argv) {
  int const threads = argc > 1 ? atoi(argv[1]) : 4;
  n_inputs = argc > 2 ? atol(argv[2]) : 2000;
  rounds = argc > 3 ? atol(argv[3]) : 2;
  inputs = calloc((size_t)n_inputs, sizeof *inputs);
  reference = calloc((size_t)n_inputs, sizeof *reference);
  if (!inputs || !reference) return 1;
  test_rng g = {7};
  for (long k = 0; k < n_inputs; ++k) gen_input(&g, (int)(k % TEST_KINDS), &inputs[k]);
  for (int i = 0; i < SCENE; ++i) {
    test_input in;
    gen_input(&g, 0, &in);
    for (int d = 0; d < 3; ++d) centres[3 * i + d] = i * (d == 0 ? 0.25 : d == 1 ? 0.125 : 0.0625);
    memcpy(forms + 6 * i, in.q1, sizeof in.q1);
  }
  for (int i = 0; i + 1 < SCENE; ++i) {
    pairs[4 * i] = i;
    pairs[4 * i + 1] = i + 1;
    pairs[4 * i + 2] = i + 1;
    pairs[4 * i + 3] = i;
  }
  for (long k = 0; k < n_inputs; ++k) reference[k] = hash_of(&inputs[k]);
  run_batch(&batch_reference);

  pthread_t tid[64];
  int const nt = threads < 1 ? 1 : threads > 64 ? 64 : threads;
  for (long t = 0; t < nt; ++t)
    if (pthread_create(&tid[t], NULL, worker, (void *)t) != 0) return 1;
  long bad = 0;
  for (int t = 0; t < nt; ++t) {
    void *r;
    pthread_join(tid[t], &r);
    bad += (long)r;
  }
  printf("%d threads x %ld rounds x (%ld inputs + 3 batch calls): %ld results differ "
         "from the single-threaded run\n", nt, rounds, n_inputs, bad);
  return bad != 0;
}
