// extern "C" layer of the scene API: pw85_overlap, pw85_contact and the
// batch calls over index pairs of a scene. Validation and status mapping
// only; the work is in src/core/overlap/ and src/core/geometry/. The batch loops are parallelised with OpenMP when the
// library is built with it; each pair is computed by exactly the code of the
// one-pair function, so results do not depend on the number of threads.
#include <cmath>
#include <cstddef>
#include <cstdint>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "pw85.h"
#include "contact/contact.hpp"
#include "geometry/contact_geometry.hpp"
#include "overlap/overlap.hpp"
#include "common/sym3.hpp"
#include "validate.hpp"

using pw85::capi::fill_nan;

namespace {

void fill_nan_contact(pw85_contact_t *c) noexcept {
  fill_nan(&c->mu2, 1);
  fill_nan(&c->lambda, 1);
  fill_nan(c->x0, 3);
  fill_nan(c->n, 3);
  fill_nan(&c->dca, 1);
  fill_nan(&c->depth, 1);
  fill_nan(&c->depth_n, 1);
}

// r12 = c_j - c_i (rounded to double: the batch functions decide for this
// r12, exactly as the one-pair functions would).
inline bool pair_r12(long long n, double const *centres, long long const *pairs,
                     long long k, double r12[3], long long &i, long long &j) noexcept {
  i = pairs[2 * k];
  j = pairs[2 * k + 1];
  if (i < 0 || j < 0 || i >= n || j >= n) return false;
  for (int d = 0; d < 3; ++d) r12[d] = centres[3 * j + d] - centres[3 * i + d];
  return true;
}

// Software prefetch of the centres and matrices of pair k + kPrefetch
// (docs/batch.md): random index pairs into a scene larger than the caches are
// bound by memory latency (measured: 40-170 ns per far-apart pair without,
// ~30 ns with); the loads of later pairs overlap the work on this one.
// Results are unaffected.
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

inline int threads_of(int nthreads) noexcept {
#ifdef _OPENMP
  return nthreads > 0 ? nthreads : omp_get_max_threads();
#else
  (void)nthreads;
  return 1;
#endif
}

// The loop shared by the three batch functions: pair k of m (OpenMP, dynamic
// chunks of `chunk` pairs; out is the caller's output array, checked
// non-null), one(k, r12, i, j) computes and writes its
// results and returns its status (r12 == nullptr: index out of range). The
// returned status is that of the first failing pair, recomputed after the
// loop (the same deterministic call, so its outputs are rewritten unchanged)
// so that it does not depend on the thread count.
template <class One>
int batch(long long n, double const *centres, double const *q, long long m,
          long long const *pairs, void const *out, int *status, int nthreads, int chunk,
          One one) noexcept {
  if (m == 0) return PW85_OK;
  if (n < 0 || m < 0 || centres == nullptr || q == nullptr || pairs == nullptr ||
      out == nullptr || nthreads < 0)
    return PW85_ERR_INVALID_ARGUMENT;
  long long first_bad = m;
#pragma omp parallel for schedule(dynamic, chunk) num_threads(threads_of(nthreads)) \
    reduction(min : first_bad)
  for (long long k = 0; k < m; ++k) {
    prefetch_pair(n, centres, q, pairs, m, k);
    double r12[3];
    long long i, j;
    bool const ok = pair_r12(n, centres, pairs, k, r12, i, j);
    int const res = one(k, ok ? r12 : nullptr, i, j);
    if (status != nullptr) status[k] = res;
    if (res != PW85_OK && k < first_bad) first_bad = k;
  }
  if (first_bad == m) return PW85_OK;
  double r12[3];
  long long i, j;
  bool const ok = pair_r12(n, centres, pairs, first_bad, r12, i, j);
  return one(first_bad, ok ? r12 : nullptr, i, j);
}

// pw85_overlap off its hot path: full argument check (L D L^T pivots instead
// of a Cholesky factorisation, docs/overlap.md (O9)), then scaling if needed.
// Kept out of line so that the screening pass compiles without spills.
__attribute__((noinline)) int overlap_general(double const *r12, double const *q1,
                                              double const *q2) noexcept {
  int const status = pw85::capi::validate_pair_ldl(r12, q1, q2);
  if (status != PW85_OK) return status;
  int verdict = -1;
  int const s = pw85::overlap(pw85::load_vec3(r12), pw85::load_sym3(q1),
                              pw85::load_sym3(q2), verdict);
  return s == PW85_OK ? verdict : s;
}

}  // namespace

extern "C" {

int pw85_overlap(double const r12[PW85_DIM], double const q1[PW85_SYM],
                 double const q2[PW85_SYM]) {
  if (r12 == nullptr || q1 == nullptr || q2 == nullptr) return PW85_ERR_INVALID_ARGUMENT;
  // Hot path: one screening pass (finite, L D L^T pivots, safe range), then
  // the filters with no scaling. Anything else takes the general path.
  int verdict = -1;
  pw85::Status s = pw85::kOk;
  if (pw85::overlap_screened(r12, q1, q2, verdict, s)) return s == pw85::kOk ? verdict : s;
  return overlap_general(r12, q1, q2);
}

int pw85_contact(double const r12[PW85_DIM], double const q1[PW85_SYM],
                 double const q2[PW85_SYM], pw85_contact_t *c) {
  if (c == nullptr) return PW85_ERR_INVALID_ARGUMENT;
  int const status = pw85::capi::validate_pair(r12, q1, q2);
  if (status != PW85_OK) {
    fill_nan_contact(c);
    return status;
  }
  if (r12[0] == 0.0 && r12[1] == 0.0 && r12[2] == 0.0) {
    fill_nan_contact(c);
    return PW85_ERR_INVALID_ARGUMENT;
  }
  pw85::ContactGeometry g;
  int const s = pw85::contact_geometry(pw85::load_vec3(r12), pw85::load_sym3(q1),
                                       pw85::load_sym3(q2), g);
  if (s != PW85_OK && s != PW85_ERR_NO_CONVERGENCE && s != PW85_ERR_INACCURATE &&
      s != PW85_ERR_RANGE) {
    fill_nan_contact(c);
    return s;
  }
  c->mu2 = g.mu2;
  c->lambda = g.lambda;
  for (int d = 0; d < 3; ++d) {
    c->x0[d] = g.x0[d];
    c->n[d] = g.n[d];
  }
  c->dca = g.dca;
  c->depth = g.depth;
  c->depth_n = g.depth_n;
  return s;
}

int pw85_overlap_batch(long long n, double const *centres, double const *q, long long m,
                       long long const *pairs, int *overlap, int *status, int nthreads) {
  return batch(n, centres, q, m, pairs, overlap, status, nthreads, 256,
               [&](long long k, double const *r12, long long i, long long j) noexcept {
                 int const res = r12 ? pw85_overlap(r12, q + 6 * i, q + 6 * j)
                                     : PW85_ERR_INVALID_ARGUMENT;
                 overlap[k] = res;
                 return res < 0 ? res : PW85_OK;
               });
}

int pw85_contact_function_batch(long long n, double const *centres, double const *q,
                                long long m, long long const *pairs, double *out, int *status,
                                int nthreads) {
  return batch(n, centres, q, m, pairs, out, status, nthreads, 64,
               [&](long long k, double const *r12, long long i, long long j) noexcept {
                 if (r12) return pw85_contact_function(r12, q + 6 * i, q + 6 * j, out + 2 * k);
                 fill_nan(out + 2 * k, 2);
                 return int{PW85_ERR_INVALID_ARGUMENT};
               });
}

int pw85_contact_batch(long long n, double const *centres, double const *q, long long m,
                       long long const *pairs, pw85_contact_t *c, int *status, int nthreads) {
  return batch(n, centres, q, m, pairs, c, status, nthreads, 64,
               [&](long long k, double const *r12, long long i, long long j) noexcept {
                 if (r12) return pw85_contact(r12, q + 6 * i, q + 6 * j, c + k);
                 fill_nan_contact(c + k);
                 return int{PW85_ERR_INVALID_ARGUMENT};
               });
}

}  // extern "C"
