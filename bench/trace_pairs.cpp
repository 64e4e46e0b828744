// The calls of the performance model (docs/performance.md, "Model"), one
// call per pair over a few pairs, for instruction counts (valgrind
// --tool=callgrind --toggle-collect=traced_call) and for the instruction
// traces bench/mca_model.py feeds to llvm-mca (gdb single-steps
// traced_call). NOT a test, not installed.
//
//   trace_pairs CALL SET CLASS COUNT [REPEAT]
//
// CALL: default (pw85_contact_function_method, PW85_METHOD_DEFAULT), overlap
// (pw85_overlap), default_pairs (pw85_contact_function_pairs, DEFAULT, one
// thread), overlap_pairs (pw85_overlap_pairs, one thread). SET: random (the
// pairs of bench_contact's class CLASS, bench::random_pair) or near
// (bench::near_contact_pair). COUNT pairs drawn from seed 20260521 + CLASS
// (+ 1000 for near); traced_call(k) makes the one-pair call on pair k, or
// the pairs call on all COUNT pairs (k = 0); the program calls it for every
// pair (once for the pairs calls), REPEAT times (default 1). Prints the
// number of pairs per traced_call, the number of traced_call calls and a
// checksum of the results.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "bench_common.hpp"
#include "pair_sets.hpp"
#include "pw85.h"

enum class Call { Default, Overlap, DefaultPairs, OverlapPairs };

struct Pairs {
  Call call;
  long long m;
  std::vector<double> r12, q1, q2;
  std::vector<int> verdict;
  std::vector<pw85_result> res;
};

// Not inlined, C linkage: the unit callgrind and gdb look for.
extern "C" __attribute__((noinline)) double traced_call(Pairs *p, long long k) {
  switch (p->call) {
    case Call::Default:
      pw85_contact_function_method(&p->r12[3 * k], &p->q1[6 * k], &p->q2[6 * k],
                                   PW85_METHOD_DEFAULT, &p->res[k]);
      return p->res[k].mu2;
    case Call::Overlap:
      return p->verdict[k] = pw85_overlap(&p->r12[3 * k], &p->q1[6 * k], &p->q2[6 * k]);
    case Call::DefaultPairs:
      pw85_contact_function_pairs(p->m, p->r12.data(), p->q1.data(), p->q2.data(),
                                  PW85_METHOD_DEFAULT, p->res.data(), nullptr, 1);
      return p->res[0].mu2;
    case Call::OverlapPairs:
      pw85_overlap_pairs(p->m, p->r12.data(), p->q1.data(), p->q2.data(), p->verdict.data(),
                         nullptr, 1);
      return p->verdict[0];
  }
  return 0;
}

int main(int argc, char **argv) {
  if (argc < 5 || argc > 6) {
    std::fprintf(stderr,
                 "usage: %s default|overlap|default_pairs|overlap_pairs random|near CLASS COUNT "
                 "[REPEAT]\n",
                 argv[0]);
    return 2;
  }
  Pairs p;
  char const *call = argv[1];
  if (!std::strcmp(call, "default"))
    p.call = Call::Default;
  else if (!std::strcmp(call, "overlap"))
    p.call = Call::Overlap;
  else if (!std::strcmp(call, "default_pairs"))
    p.call = Call::DefaultPairs;
  else if (!std::strcmp(call, "overlap_pairs"))
    p.call = Call::OverlapPairs;
  else
    return 2;
  bool const near = !std::strcmp(argv[2], "near");
  if (!near && std::strcmp(argv[2], "random")) return 2;
  int const cls = std::atoi(argv[3]);
  p.m = std::atoll(argv[4]);
  int const repeat = argc > 5 ? std::atoi(argv[5]) : 1;
  if (cls < 0 || cls > 3 || p.m <= 0 || p.m > 10000000 || repeat <= 0) return 2;
  bench::Rng g{20260521u + (unsigned)cls + (near ? 1000u : 0u)};
  p.r12.resize(3 * p.m), p.q1.resize(6 * p.m), p.q2.resize(6 * p.m);
  p.verdict.resize(p.m), p.res.resize(p.m);
  for (long long k = 0; k < p.m; ++k) {
    if (near)
      bench::near_contact_pair(g, cls, &p.r12[3 * k], &p.q1[6 * k], &p.q2[6 * k]);
    else
      bench::random_pair(g, cls, bench::kContactSpan, &p.r12[3 * k], &p.q1[6 * k], &p.q2[6 * k]);
  }
  bool const batch = p.call == Call::DefaultPairs || p.call == Call::OverlapPairs;
  long long const per_call = batch ? p.m : 1, calls = (batch ? 1 : p.m) * (long long)repeat;
  double sum = 0.0;
  for (int rep = 0; rep < repeat; ++rep)
    for (long long k = 0; k < (batch ? 1 : p.m); ++k) sum += traced_call(&p, k);
  std::printf("pairs_per_call %lld calls %lld checksum %.17g\n", per_call, calls, sum);
  return 0;
}
