// The loops of the batch calls: OpenMP threads, dynamic chunks of pairs,
// the returned status independent of the thread count (docs/batch.md,
// "Threads and determinism").
#pragma once

#ifdef _OPENMP
#include <omp.h>
#endif

#include "common/status.hpp"

namespace pw85 {
namespace batch {

// Pairs per dynamic OpenMP chunk of the lane loops (each chunk ~20 us of
// work on one thread; build/bench/bench_batch, rows "threads"), and of the
// pair-by-pair loops (a pair's cost: overlap and DEFAULT, the other methods
// and pw85_contact, pw85_contact_time).
constexpr int kOverlapChunk = 2048, kDefaultChunk = 512;
constexpr int kPairChunk = 64, kContactTimeChunk = 16;

// Number of OpenMP threads of a batch call of m > 0 pairs: nthreads (0: the
// OpenMP default), at most omp_get_num_procs() and at most m. An unbounded
// request would make the OpenMP runtime create that many threads, which
// fails (the runtime then prints and exits, or the process crashes) long
// before nthreads = INT_MAX.
inline int threads_for(int nthreads, long long m) noexcept {
#ifdef _OPENMP
  long long t = nthreads > 0 ? nthreads : omp_get_max_threads();
  long long const procs = omp_get_num_procs();
  if (t > procs) t = procs;
  if (t > m) t = m;
  return t < 1 ? 1 : static_cast<int>(t);
#else
  (void)nthreads;
  (void)m;
  return 1;
#endif
}

// The loop of every batch call: one(k) computes pair k of m > 0, writes its
// outputs and returns its status; status (may be null) receives it. OpenMP,
// dynamic chunks of `chunk` pairs on threads_for(nthreads, m) threads. The
// returned status is that of the lowest failing k, recomputed after the loop
// (the same deterministic call, so its outputs are rewritten unchanged) so
// that it does not depend on the thread count.
template <class One>
int run_pairs(long long m, int *status, int nthreads, int chunk, One one) noexcept {
  long long first_bad = m;
#pragma omp parallel for schedule(dynamic, chunk) num_threads(threads_for(nthreads, m)) \
    reduction(min : first_bad)
  for (long long k = 0; k < m; ++k) {
    int const res = one(k);
    if (status != nullptr) status[k] = res;
    if (res != kOk && k < first_bad) first_bad = k;
  }
  return first_bad == m ? kOk : one(first_bad);
}

// The loop of the calls whose pairs are computed w at a time (the lanes of
// overlap_lanes or default_lanes): block(k0, res) computes pairs k0 ...
// k0 + w - 1 (all < m), writes their outputs and their statuses res[0..w-1]; one(k)
// computes pair k alone (the last m mod w pairs, and the
// returned status) and must give the same outputs and status as block.
// Otherwise as run_pairs: chunk pairs per dynamic chunk, the status of the
// lowest failing k.
template <int w, class Block, class One>
int run_blocks(long long m, int *status, int nthreads, int chunk, Block block,
               One one) noexcept {
  long long const nb = m / w;
  long long first_bad = m;
#pragma omp parallel for schedule(dynamic, chunk / w) num_threads(threads_for(nthreads, m)) \
    reduction(min : first_bad)
  for (long long b = 0; b < nb + (m % w); ++b) {
    int res[w];
    long long k0;
    int n;
    if (b < nb) {
      k0 = w * b;
      n = w;
      block(k0, res);
    } else {
      k0 = w * nb + (b - nb);
      n = 1;
      res[0] = one(k0);
    }
    if (status != nullptr)
      for (int l = 0; l < n; ++l) status[k0 + l] = res[l];
    // The block's first failure only: GCC compiles a minimum over every lane
    // to a chain of dependent conditional moves, carried from block to block
    // (slower on pw85_overlap_pairs: build/bench/bench_batch --reps 9
    // --threads-n 0).
    for (int l = 0; l < n; ++l)
      if (res[l] != kOk) {
        if (k0 + l < first_bad) first_bad = k0 + l;
        break;
      }
  }
  return first_bad == m ? kOk : one(first_bad);
}

}  // namespace batch
}  // namespace pw85
