// extern "C" layer of the scene API: pw85_overlap, pw85_contact and the
// batch calls over index pairs of a scene. Validation and status mapping
// only; the work is in src/core/overlap/ and src/core/geometry/. The batch
// loops are parallelised with OpenMP when the library is built with it. Each
// pair is computed by the one-pair function, or (overlap; DEFAULT) in a
// vector lane that performs that function's operations on that pair alone
// and gives its result bit for bit, else hands the pair to it; so results
// do not depend on the number of threads, the position or the neighbours.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "pw85.h"
#include "batch/bounds.hpp"
#include "batch/box.hpp"
#include "contact/contact.hpp"
#include "derivatives/derivatives.hpp"
#include "geometry/contact_geometry.hpp"
#include "overlap/overlap.hpp"
#include "common/sym3.hpp"
#include "validate.hpp"

using pw85::capi::fill_nan;
using pw85::batch::Box;
using pw85::batch::make_box;

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

// Software prefetch of the per-pair arrays of the 8 pairs k0 + kAhead ...
// k0 + kAhead + 7 (lines of 8 doubles), once per 8 pairs of
// pw85_overlap_pairs: two threads on 10^6 class-0 pairs gave 1.86-1.90
// times one thread's speed with it, 1.76-1.81 without (and one thread
// 3 % faster); DEFAULT, 4 times slower per pair, gained nothing
// (build/bench/bench_batch, rows "threads", runs alternating the builds).
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
    if (res != PW85_OK && k < first_bad) first_bad = k;
  }
  return first_bad == m ? PW85_OK : one(first_bad);
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
    // (pw85_overlap_pairs, x86-64-v4, class 0: 11.0 ns per pair that way,
    // 9.3 this way; build/bench/bench_batch --reps 9 --threads-n 0).
    for (int l = 0; l < n; ++l)
      if (res[l] != PW85_OK) {
        if (k0 + l < first_bad) first_bad = k0 + l;
        break;
      }
  }
  return first_bad == m ? PW85_OK : one(first_bad);
}

// Overlap of pairs k0 ... k0 + w - 1 through the w lanes of overlap_lanes
// (docs/batch.md, "Throughput"): pair(k, buf, r12, q1, q2) gives pair k's
// arguments (r12 may point to buf, which it may fill; false: the pair fails
// with PW85_ERR_INVALID_ARGUMENT); a lane that overlap_lanes leaves
// undecided is computed by pw85_overlap. Writes overlap[k] and res[k - k0]
// as the one-pair loop would.
template <int w, class Pair>
void overlap_block(long long k0, Pair pair, int *overlap, int res[]) noexcept {
  static constexpr double kZero[6] = {0, 0, 0, 0, 0, 0};  // r = 0: never decided by the lanes
  double buf[w][3];
  double const *rp[w], *q1p[w], *q2p[w];
  bool ok[w];
  for (int l = 0; l < w; ++l) {
    ok[l] = pair(k0 + l, buf[l], rp[l], q1p[l], q2p[l]);
    if (!ok[l]) rp[l] = q1p[l] = q2p[l] = kZero;
  }
  int v[w];
  pw85::overlap_lanes<w>(rp, q1p, q2p, v);
  for (int l = 0; l < w; ++l) {
    int const o = !ok[l] ? PW85_ERR_INVALID_ARGUMENT
                         : v[l] >= 0 ? v[l] : pw85_overlap(rp[l], q1p[l], q2p[l]);
    overlap[k0 + l] = o;
    res[l] = o < 0 ? o : PW85_OK;
  }
}

// Pairs per dynamic OpenMP chunk of the lane loops, each chunk ~20 us of
// work on one thread: smaller chunks (256 and 64) gave 1.60-1.65 and
// 1.76-1.78 times one thread's speed on two threads, these 1.61-1.83 and
// 1.80-1.82 (10^6 class-0 pairs, build/bench/bench_batch, rows "threads").
constexpr int kOverlapChunk = 2048, kDefaultChunk = 512;

// The loop of the overlap calls: run_blocks over blocks of
// overlap_lanes_width() pairs through overlap_block (pair as there), one(k)
// for the rest and the returned status.
template <class Pair, class One>
int run_overlap(long long m, int *status, int nthreads, Pair pair, int *overlap,
                One one) noexcept {
  if (pw85::overlap_lanes_width() == pw85::kOverlapLanesV4)
    return run_blocks<pw85::kOverlapLanesV4>(
        m, status, nthreads, kOverlapChunk,
        [&](long long k0, int res[]) noexcept {
          overlap_block<pw85::kOverlapLanesV4>(k0, pair, overlap, res);
        },
        one);
  return run_blocks<pw85::kOverlapLanes>(
      m, status, nthreads, kOverlapChunk,
      [&](long long k0, int res[]) noexcept {
        overlap_block<pw85::kOverlapLanes>(k0, pair, overlap, res);
      },
      one);
}

// The index-pair loop of the *_batch functions: checks the call's arguments,
// then one(k, r12, i, j) computes pair k with r12 = c_j - c_i (r12 ==
// nullptr: index out of range) and returns its status.
template <class One>
int batch(long long n, double const *centres, double const *q, long long m,
          long long const *pairs, void const *out, int *status, int nthreads, int chunk,
          One one) noexcept {
  if (m == 0) return PW85_OK;
  if (n < 0 || m < 0 || centres == nullptr || q == nullptr || pairs == nullptr ||
      out == nullptr || nthreads < 0)
    return PW85_ERR_INVALID_ARGUMENT;
  return run_pairs(m, status, nthreads, chunk, [&](long long k) noexcept {
    prefetch_pair(n, centres, q, pairs, m, k);
    double r12[3];
    long long i, j;
    bool const ok = pair_r12(n, centres, pairs, k, r12, i, j);
    return one(k, ok ? r12 : nullptr, i, j);
  });
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

// ---- Per-pair arrays and periodic scenes ------------------------------------
// pw85_*_pairs: pair k is (r12[3k..3k+2], q1[6k..6k+5], q2[6k..6k+5]).
// pw85_scene_*: pair k is (i, j) = (pairs[2k], pairs[2k+1]) of the scene,
// r12 = c_j - c_i, or its minimum image in the box. Each pair's result is
// the one-pair function's on that r12 (computed by it, or in a lane of
// overlap_lanes / default_lanes with the same bits), so it does not depend
// on the other pairs, on its position k or on the thread count
// (docs/batch.md).

namespace {

void fill_nan_result(pw85_result *res, int method) noexcept {
  fill_nan(&res->mu2, 1);
  fill_nan(&res->lambda, 1);
  fill_nan(&res->mu2_error, 1);
  res->iterations = 0;
  res->method = method;
}

// Pairs k0 ... k0 + kDefaultLanes - 1 and DEFAULT for them in the lanes of
// default_lanes (docs/batch.md, "Throughput"): pair(k, buf, r12, q1, q2)
// gives pair k's arguments (as for overlap_block; false: the pair fails with
// PW85_ERR_INVALID_ARGUMENT, and its lane gets zeros, which default_lanes
// never decides).
struct DefaultLanes {
  static constexpr int w = pw85::kDefaultLanes;
  double buf[w][3];
  double const *r[w], *q1[w], *q2[w];
  bool ok[w];
  pw85::MethodResult res[w];
  int status[w];  // pw85::kLaneUndecided: the one-pair call decides
};

template <class Pair>
void default_lanes_of(long long k0, Pair pair, DefaultLanes &dl) noexcept {
  static constexpr double kZero[6] = {0, 0, 0, 0, 0, 0};
  for (int l = 0; l < DefaultLanes::w; ++l) {
    dl.ok[l] = pair(k0 + l, dl.buf[l], dl.r[l], dl.q1[l], dl.q2[l]);
    if (!dl.ok[l]) dl.r[l] = dl.q1[l] = dl.q2[l] = kZero;
  }
  pw85::default_lanes(dl.r, dl.q1, dl.q2, dl.res, dl.status);
}

// DEFAULT for pairs k0 ... k0 + kDefaultLanes - 1 (default_lanes_of); a
// lane that default_lanes leaves undecided is computed by
// pw85_contact_function_method. Writes res[k] and st[k - k0] as the
// one-pair loop would.
template <class Pair>
void default_block(long long k0, Pair pair, pw85_result *res, int st[]) noexcept {
  DefaultLanes dl;
  default_lanes_of(k0, pair, dl);
  for (int l = 0; l < DefaultLanes::w; ++l) {
    pw85_result &o = res[k0 + l];
    if (!dl.ok[l]) {
      fill_nan_result(&o, PW85_METHOD_DEFAULT);
      st[l] = PW85_ERR_INVALID_ARGUMENT;
    } else if (dl.status[l] != pw85::kLaneUndecided) {
      o.mu2 = dl.res[l].mu2;
      o.lambda = dl.res[l].lambda;
      o.mu2_error = dl.res[l].mu2_error;
      o.iterations = dl.res[l].iterations;
      o.method = dl.res[l].method;
      st[l] = dl.status[l];
    } else {
      st[l] = pw85_contact_function_method(dl.r[l], dl.q1[l], dl.q2[l], PW85_METHOD_DEFAULT, &o);
    }
  }
}

// pw85_contact_derivatives for pairs k0 ... k0 + kDefaultLanes - 1, with
// DEFAULT from default_lanes_of: a lane that default_lanes decides with a
// solution (PW85_OK, PW85_ERR_INACCURATE), of magnitudes that
// pw85_contact_derivatives takes without rescaling, continues from that
// solution (contact_derivatives_from_default: the one-pair call's bits);
// the other lanes make the one-pair call.
template <class Pair>
void derivatives_block(long long k0, Pair pair, pw85_derivatives_t *d, int st[]) noexcept {
  DefaultLanes dl;
  default_lanes_of(k0, pair, dl);
  for (int l = 0; l < DefaultLanes::w; ++l) {
    pw85_derivatives_t &o = d[k0 + l];
    if (!dl.ok[l]) {
      fill_nan(&o.mu2, 29);
      st[l] = PW85_ERR_INVALID_ARGUMENT;
      continue;
    }
    pw85::Vec3 const r = pw85::load_vec3(dl.r[l]);
    pw85::Sym3 const a = pw85::load_sym3(dl.q1[l]), b = pw85::load_sym3(dl.q2[l]);
    int const s = dl.status[l];
    if ((s == PW85_OK || s == PW85_ERR_INACCURATE) && pw85::derivatives_from_default_ok(r, a, b)) {
      pw85::Derivatives out;
      st[l] = pw85::contact_derivatives_from_default(r, a, b, pw85::Status(s), dl.res[l], out);
      std::memcpy(&o, &out, sizeof out);
    } else {
      st[l] = pw85_contact_derivatives(dl.r[l], dl.q1[l], dl.q2[l], &o);
    }
  }
}

// The checks shared by the calls of m > 0 pairs (pointers checked by the
// caller).
inline bool valid_count(long long m, int nthreads) noexcept { return m > 0 && nthreads >= 0; }

using pw85::batch::too_large;

// r12 of pair k of a scene: c_j - c_i, or its minimum image in the box.
// Returns PW85_OK, or PW85_ERR_INVALID_ARGUMENT for an index out of range or
// (periodic box) a pair whose bounding spheres reach past max_reach or whose
// image minimum_image refuses (batch/box.hpp). A
// non-finite centre or matrix is passed on to the one-pair function, which
// reports it.
inline int scene_r12(long long n, double const *centres, double const *q, Box const &box,
                     long long const *pairs, long long k, double r12[3], long long &i,
                     long long &j) noexcept {
  if (!pair_r12(n, centres, pairs, k, r12, i, j)) return PW85_ERR_INVALID_ARGUMENT;
  if (!box.periodic) return PW85_OK;
  if (too_large(box, q + 6 * i, q + 6 * j)) return PW85_ERR_INVALID_ARGUMENT;
  if (std::isfinite(r12[0]) && std::isfinite(r12[1]) && std::isfinite(r12[2]))
    return pw85::batch::minimum_image(box, r12);
  return PW85_OK;
}

// Pair k of a scene for the lane blocks (overlap_block, default_block):
// r12 into buf (r points to it), a and b to its matrices; false: the pair
// failed scene_r12.
inline bool scene_pair(long long n, double const *centres, double const *q, Box const &box,
                       long long const *pairs, long long m, long long k, double *buf,
                       double const *&r, double const *&a, double const *&b) noexcept {
  prefetch_pair(n, centres, q, pairs, m, k);
  long long i, j;
  r = buf;
  if (scene_r12(n, centres, q, box, pairs, k, buf, i, j) != PW85_OK) return false;
  a = q + 6 * i;
  b = q + 6 * j;
  return true;
}

// Pair k of per-pair arrays, for the lane blocks (default_block,
// derivatives_block).
struct ArrayPair {
  double const *r12, *q1, *q2;
  bool operator()(long long k, double *, double const *&r, double const *&a,
                  double const *&b) const noexcept {
    r = r12 + 3 * k;
    a = q1 + 6 * k;
    b = q2 + 6 * k;
    return true;
  }
};

// Pair k of a scene (scene_pair), for the lane blocks.
struct ScenePair {
  long long n;
  double const *centres, *q;
  Box const &box;
  long long const *pairs;
  long long m;
  bool operator()(long long k, double *buf, double const *&r, double const *&a,
                  double const *&b) const noexcept {
    return scene_pair(n, centres, q, box, pairs, m, k, buf, r, a, b);
  }
};

// Pair k of a scene through one(k, r12, i, j), which computes it (r12 ==
// nullptr: the pair failed scene_r12) and returns its status.
template <class One>
int scene_one(long long n, double const *centres, double const *q, Box const &box,
              long long const *pairs, long long k, One &one) noexcept {
  double r12[3];
  long long i, j;
  int const s = scene_r12(n, centres, q, box, pairs, k, r12, i, j);
  return one(k, s == PW85_OK ? r12 : nullptr, i, j);
}

// The loop of the pw85_scene_* functions after their argument checks, pair
// by pair through scene_one.
template <class One>
int scene(long long n, double const *centres, double const *q, Box const &box, long long m,
          long long const *pairs, int *status, int nthreads, int chunk, One one) noexcept {
  return run_pairs(m, status, nthreads, chunk, [&](long long k) noexcept {
    prefetch_pair(n, centres, q, pairs, m, k);
    return scene_one(n, centres, q, box, pairs, k, one);
  });
}

// The loop of pw85_scene_overlap and pw85_overlap_batch after their
// argument checks: blocks of pairs through run_overlap, the rest (and the
// returned status) by pw85_overlap pair by pair.
int scene_overlap(long long n, double const *centres, double const *q, Box const &box,
                  long long m, long long const *pairs, int *overlap, int *status,
                  int nthreads) noexcept {
  auto one = [&](long long k) noexcept {
    double r12[3];
    long long i, j;
    int const s = scene_r12(n, centres, q, box, pairs, k, r12, i, j);
    int const res = s == PW85_OK ? pw85_overlap(r12, q + 6 * i, q + 6 * j) : s;
    overlap[k] = res;
    return res < 0 ? res : PW85_OK;
  };
  return run_overlap(m, status, nthreads, ScenePair{n, centres, q, box, pairs, m}, overlap, one);
}

inline bool scene_args(long long n, double const *centres, double const *q, double const *box,
                       long long m, long long const *pairs, void const *out, int nthreads,
                       Box &b) noexcept {
  return n >= 0 && valid_count(m, nthreads) && centres != nullptr && q != nullptr &&
         pairs != nullptr && out != nullptr && make_box(box, b);
}

}  // namespace

extern "C" {

int pw85_overlap_pairs(long long m, double const *r12, double const *q1, double const *q2,
                       int *overlap, int *status, int nthreads) {
  if (m == 0) return PW85_OK;
  if (!valid_count(m, nthreads) || r12 == nullptr || q1 == nullptr || q2 == nullptr ||
      overlap == nullptr)
    return PW85_ERR_INVALID_ARGUMENT;
  auto one = [&](long long k) noexcept {
    int const res = pw85_overlap(r12 + 3 * k, q1 + 6 * k, q2 + 6 * k);
    overlap[k] = res;
    return res < 0 ? res : PW85_OK;
  };
  auto pair = [&](long long k, double *, double const *&r, double const *&a,
                  double const *&b) noexcept {
    if (k % 8 == 0) prefetch_arrays(m, r12, q1, q2, k);
    r = r12 + 3 * k;
    a = q1 + 6 * k;
    b = q2 + 6 * k;
    return true;
  };
  return run_overlap(m, status, nthreads, pair, overlap, one);
}

int pw85_contact_function_pairs(long long m, double const *r12, double const *q1,
                                double const *q2, int method, pw85_result *res, int *status,
                                int nthreads) {
  if (m == 0) return PW85_OK;
  if (!valid_count(m, nthreads) || r12 == nullptr || q1 == nullptr || q2 == nullptr ||
      res == nullptr)
    return PW85_ERR_INVALID_ARGUMENT;
  if (!pw85::is_method(method)) return PW85_ERR_UNKNOWN_METHOD;
  auto one = [&](long long k) noexcept {
    return pw85_contact_function_method(r12 + 3 * k, q1 + 6 * k, q2 + 6 * k, method, res + k);
  };
  if (method != PW85_METHOD_DEFAULT)
    return run_pairs(m, status, nthreads, 64, one);
  auto block = [&](long long k0, int st[]) noexcept {
    default_block(k0, ArrayPair{r12, q1, q2}, res, st);
  };
  return run_blocks<pw85::kDefaultLanes>(m, status, nthreads, kDefaultChunk, block, one);
}

int pw85_contact_pairs(long long m, double const *r12, double const *q1, double const *q2,
                       pw85_contact_t *c, int *status, int nthreads) {
  if (m == 0) return PW85_OK;
  if (!valid_count(m, nthreads) || r12 == nullptr || q1 == nullptr || q2 == nullptr ||
      c == nullptr)
    return PW85_ERR_INVALID_ARGUMENT;
  return run_pairs(m, status, nthreads, 64, [&](long long k) noexcept {
    return pw85_contact(r12 + 3 * k, q1 + 6 * k, q2 + 6 * k, c + k);
  });
}

int pw85_scene_overlap(long long n, double const *centres, double const *q,
                       double const box[6], long long m, long long const *pairs, int *overlap,
                       int *status, int nthreads) {
  if (m == 0) return PW85_OK;
  Box b;
  if (!scene_args(n, centres, q, box, m, pairs, overlap, nthreads, b))
    return PW85_ERR_INVALID_ARGUMENT;
  return scene_overlap(n, centres, q, b, m, pairs, overlap, status, nthreads);
}

int pw85_overlap_batch(long long n, double const *centres, double const *q, long long m,
                       long long const *pairs, int *overlap, int *status, int nthreads) {
  if (m == 0) return PW85_OK;
  if (n < 0 || m < 0 || centres == nullptr || q == nullptr || pairs == nullptr ||
      overlap == nullptr || nthreads < 0)
    return PW85_ERR_INVALID_ARGUMENT;
  return scene_overlap(n, centres, q, Box{}, m, pairs, overlap, status, nthreads);
}

int pw85_scene_contact_function(long long n, double const *centres, double const *q,
                                double const box[6], long long m, long long const *pairs,
                                int method, pw85_result *res, int *status, int nthreads) {
  if (m == 0) return PW85_OK;
  Box b;
  if (!scene_args(n, centres, q, box, m, pairs, res, nthreads, b))
    return PW85_ERR_INVALID_ARGUMENT;
  if (!pw85::is_method(method)) return PW85_ERR_UNKNOWN_METHOD;
  auto one_r12 = [&](long long k, double const *r12, long long i, long long j) noexcept {
    if (r12) return pw85_contact_function_method(r12, q + 6 * i, q + 6 * j, method, res + k);
    fill_nan_result(res + k, method);
    return int{PW85_ERR_INVALID_ARGUMENT};
  };
  if (method != PW85_METHOD_DEFAULT)
    return scene(n, centres, q, b, m, pairs, status, nthreads, 64, one_r12);
  auto one = [&](long long k) noexcept { return scene_one(n, centres, q, b, pairs, k, one_r12); };
  auto block = [&](long long k0, int st[]) noexcept {
    default_block(k0, ScenePair{n, centres, q, b, pairs, m}, res, st);
  };
  return run_blocks<pw85::kDefaultLanes>(m, status, nthreads, kDefaultChunk, block, one);
}

int pw85_contact_derivatives_pairs(long long m, double const *r12, double const *q1,
                                   double const *q2, pw85_derivatives_t *d, int *status,
                                   int nthreads) {
  if (m == 0) return PW85_OK;
  if (!valid_count(m, nthreads) || r12 == nullptr || q1 == nullptr || q2 == nullptr ||
      d == nullptr)
    return PW85_ERR_INVALID_ARGUMENT;
  auto one = [&](long long k) noexcept {
    return pw85_contact_derivatives(r12 + 3 * k, q1 + 6 * k, q2 + 6 * k, d + k);
  };
  auto block = [&](long long k0, int st[]) noexcept {
    derivatives_block(k0, ArrayPair{r12, q1, q2}, d, st);
  };
  return run_blocks<pw85::kDefaultLanes>(m, status, nthreads, kDefaultChunk, block, one);
}

int pw85_contact_time_pairs(long long m, double const *r12, double const *v12, double const *q1,
                            double const *w1, double const *q2, double const *w2, double t_max,
                            double *t, int *status, int nthreads) {
  if (m == 0) return PW85_OK;
  if (!valid_count(m, nthreads) || r12 == nullptr || v12 == nullptr || q1 == nullptr ||
      w1 == nullptr || q2 == nullptr || w2 == nullptr || t == nullptr ||
      !std::isfinite(t_max) || !(t_max > 0.0))
    return PW85_ERR_INVALID_ARGUMENT;
  return run_pairs(m, status, nthreads, 16, [&](long long k) noexcept {
    return pw85_contact_time(r12 + 3 * k, v12 + 3 * k, q1 + 6 * k, w1 + 3 * k, q2 + 6 * k,
                             w2 + 3 * k, t_max, t + k);
  });
}

int pw85_scene_contact_derivatives(long long n, double const *centres, double const *q,
                                   double const box[6], long long m, long long const *pairs,
                                   pw85_derivatives_t *d, int *status, int nthreads) {
  if (m == 0) return PW85_OK;
  Box b;
  if (!scene_args(n, centres, q, box, m, pairs, d, nthreads, b))
    return PW85_ERR_INVALID_ARGUMENT;
  auto one_r12 = [&](long long k, double const *r12, long long i, long long j) noexcept {
    if (r12) return pw85_contact_derivatives(r12, q + 6 * i, q + 6 * j, d + k);
    fill_nan(&d[k].mu2, 29);
    return int{PW85_ERR_INVALID_ARGUMENT};
  };
  auto one = [&](long long k) noexcept { return scene_one(n, centres, q, b, pairs, k, one_r12); };
  auto block = [&](long long k0, int st[]) noexcept {
    derivatives_block(k0, ScenePair{n, centres, q, b, pairs, m}, d, st);
  };
  return run_blocks<pw85::kDefaultLanes>(m, status, nthreads, kDefaultChunk, block, one);
}

int pw85_scene_contact(long long n, double const *centres, double const *q, double const box[6],
                       long long m, long long const *pairs, pw85_contact_t *c, int *status,
                       int nthreads) {
  if (m == 0) return PW85_OK;
  Box b;
  if (!scene_args(n, centres, q, box, m, pairs, c, nthreads, b))
    return PW85_ERR_INVALID_ARGUMENT;
  return scene(n, centres, q, b, m, pairs, status, nthreads, 64,
               [&](long long k, double const *r12, long long i, long long j) noexcept {
                 if (r12) return pw85_contact(r12, q + 6 * i, q + 6 * j, c + k);
                 fill_nan_contact(c + k);
                 return int{PW85_ERR_INVALID_ARGUMENT};
               });
}

}  // extern "C"
