/* Prints the bits of every output of every public one-pair function of
 * libpw85 and libpw85_legacy over a fixed pseudo-random corpus (calls.c:
 * moderate and extreme inputs, NaN/Inf, r12 = 0), one line per call:
 *     call-number function status output-bits...
 * .ci/run builds the libraries twice, with -ftrivial-auto-var-init=pattern
 * and =zero, runs this program in both and compares the outputs: a read of
 * an uninitialised variable shows as a difference.
 *
 * usage: pw85-determinism [PAIRS [SEED]]   (defaults 10000, 1) */
#include <stdio.h>
#include <stdlib.h>

#include "calls.h"

int main(int argc, char **argv) {
  long const pairs = argc > 1 ? atol(argv[1]) : 10000;
  test_rng g = {argc > 2 ? strtoull(argv[2], NULL, 10) : 1};
  static char buf[1 << 16];
  setvbuf(stdout, buf, _IOFBF, sizeof buf);
  test_sink s = {sink_print, stdout, 0, 0};
  for (long k = 0; k < pairs; ++k) {
    test_input in;
    gen_input(&g, (int)(k % TEST_KINDS), &in);
    call_all(&in, &s);
  }
  fprintf(stderr, "%ld inputs, %lld calls\n", pairs, s.call);
  return 0;
}
