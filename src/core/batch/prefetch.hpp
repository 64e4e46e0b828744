// Software prefetch for the batch loops (docs/batch.md, "Throughput"):
// random index pairs into a scene larger than the caches are bound by
// memory latency; loading the arguments of later pairs overlaps the work on
// this one. Results are unaffected. Measured by build/bench/bench_batch.
#pragma once

namespace pw85 {
namespace batch {

// Distance, in pairs, of the scene prefetch.
constexpr long long kPrefetch = 16;

// GCC 12 at -O2 drops __builtin_prefetch here as dead code (checked with
// objdump): on x86 the instruction is issued by a volatile asm.
inline void prefetch(double const *p) noexcept {
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
  __asm__ volatile("prefetcht0 %0" : : "m"(*p));
#elif defined(__GNUC__)
  __builtin_prefetch(p);
#else
  (void)p;
#endif
}

// The centres and matrices of scene pair k + kPrefetch (of m), when its
// indices are in [0, n).
inline void prefetch_pair(long long n, double const *centres, double const *q,
                          long long const *pairs, long long m, long long k) noexcept {
  long long const kk = k + kPrefetch;
  if (kk >= m) return;
  long long const i = pairs[2 * kk], j = pairs[2 * kk + 1];
  if (i < 0 || j < 0 || i >= n || j >= n) return;
  prefetch(centres + 3 * i);
  prefetch(centres + 3 * j);
  prefetch(q + 6 * i);
  prefetch(q + 6 * i + 5);
  prefetch(q + 6 * j);
  prefetch(q + 6 * j + 5);
}

// The per-pair arrays of the 8 pairs k0 + kAhead ... k0 + kAhead + 7
// (lines of 8 doubles), issued once per 8 pairs by pw85_overlap_pairs: it
// helps two threads share the memory bandwidth (DEFAULT, slower per pair,
// gains nothing from it; build/bench/bench_batch, rows "threads").
inline void prefetch_arrays(long long m, double const *r12, double const *q1,
                            double const *q2, long long k0) noexcept {
  constexpr long long kAhead = 64;
  long long const k = k0 + kAhead;
  if (k + 8 > m) return;
  for (int i = 0; i < 24; i += 8) prefetch(r12 + 3 * k + i);
  for (int i = 0; i < 48; i += 8) {
    prefetch(q1 + 6 * k + i);
    prefetch(q2 + 6 * k + i);
  }
}

}  // namespace batch
}  // namespace pw85
