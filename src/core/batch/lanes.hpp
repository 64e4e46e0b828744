// Pairs computed in vector lanes (docs/batch.md, "Throughput"): blocks of
// pairs through overlap_lanes or default_lanes, the lane width chosen for
// this CPU here. A lane gives the one-pair call's result bit for bit, or
// leaves the pair undecided; the caller's one-pair call then computes it.
#pragma once

#include "batch/schedule.hpp"
#include "common/status.hpp"
#include "common/sym3.hpp"
#include "contact/contact.hpp"
#include "derivatives/derivatives.hpp"
#include "overlap/overlap.hpp"

namespace pw85 {
namespace batch {

// Overlap of pairs k0 ... k0 + w - 1 through the w lanes of overlap_lanes:
// pair(k, buf, r12, q1, q2) gives pair k's arguments (pair sources of
// pairs.hpp; false: the pair fails with kInvalidArgument); a lane that
// overlap_lanes leaves undecided is computed by one_pair(r12, q1, q2) (the
// one-pair overlap call: 1, 0 or a negative status). Writes overlap[k] and
// res[k - k0] as the one-pair loop would.
template <int w, class Pair, class OnePair>
void overlap_block(long long k0, Pair const &pair, OnePair const &one_pair, int *overlap,
                   int res[]) noexcept {
  static constexpr double kZero[6] = {0, 0, 0, 0, 0, 0};  // r = 0: never decided by the lanes
  double buf[w][3];
  double const *rp[w], *q1p[w], *q2p[w];
  bool ok[w];
  for (int l = 0; l < w; ++l) {
    ok[l] = pair(k0 + l, buf[l], rp[l], q1p[l], q2p[l]);
    if (!ok[l]) rp[l] = q1p[l] = q2p[l] = kZero;
  }
  int v[w];
  overlap_lanes<w>(rp, q1p, q2p, v);
  for (int l = 0; l < w; ++l) {
    int const o = !ok[l] ? kInvalidArgument : v[l] >= 0 ? v[l] : one_pair(rp[l], q1p[l], q2p[l]);
    overlap[k0 + l] = o;
    res[l] = o < 0 ? o : kOk;
  }
}

// The loop of the overlap calls: run_blocks over blocks of
// overlap_lanes_width() pairs (the widest this CPU runs) through
// overlap_block, one(k) for the rest and the returned status.
template <class Pair, class OnePair, class One>
int run_overlap(long long m, int *status, int nthreads, Pair const &pair,
                OnePair const &one_pair, int *overlap, One one) noexcept {
  if (overlap_lanes_width() == kOverlapLanesV4)
    return run_blocks<kOverlapLanesV4>(
        m, status, nthreads, kOverlapChunk,
        [&](long long k0, int res[]) noexcept {
          overlap_block<kOverlapLanesV4>(k0, pair, one_pair, overlap, res);
        },
        one);
  return run_blocks<kOverlapLanes>(
      m, status, nthreads, kOverlapChunk,
      [&](long long k0, int res[]) noexcept {
        overlap_block<kOverlapLanes>(k0, pair, one_pair, overlap, res);
      },
      one);
}

// DEFAULT for pairs k0 ... k0 + kDefaultLanes - 1 in the lanes of
// default_lanes. ok[l] false: the pair source refused pair k0 + l (it
// fails with kInvalidArgument; its lane got zeros, which default_lanes never
// decides). status[l] == kLaneUndecided: the one-pair call decides.
struct DefaultLanes {
  static constexpr int w = kDefaultLanes;
  double buf[w][3];
  double const *r[w], *q1[w], *q2[w];
  bool ok[w];
  MethodResult res[w];
  int status[w];
};

template <class Pair>
void default_lanes_of(long long k0, Pair const &pair, DefaultLanes &dl) noexcept {
  static constexpr double kZero[6] = {0, 0, 0, 0, 0, 0};
  for (int l = 0; l < DefaultLanes::w; ++l) {
    dl.ok[l] = pair(k0 + l, dl.buf[l], dl.r[l], dl.q1[l], dl.q2[l]);
    if (!dl.ok[l]) dl.r[l] = dl.q1[l] = dl.q2[l] = kZero;
  }
  default_lanes(dl.r, dl.q1, dl.q2, dl.res, dl.status);
}

// The derivatives of lane l continued from DEFAULT's lane solution
// (contact_derivatives_from_default: the one-pair call's bits), when the lane
// decided with a solution (kOk, kInaccurate) of magnitudes that
// contact_derivatives takes without rescaling; false: the one-pair call
// must compute the pair.
inline bool lane_derivatives(DefaultLanes const &dl, int l, DerivativeFields fields,
                             Derivatives &out, int &status) noexcept {
  int const s = dl.status[l];
  if (s != kOk && s != kInaccurate) return false;
  Vec3 const r = load_vec3(dl.r[l]);
  Sym3 const a = load_sym3(dl.q1[l]), b = load_sym3(dl.q2[l]);
  if (!derivatives_from_default_ok(r, a, b)) return false;
  status = contact_derivatives_from_default(r, a, b, Status(s), dl.res[l], out, fields);
  return true;
}

// The loop of the DEFAULT and derivatives calls: run_blocks over blocks of
// kDefaultLanes pairs, block(k0, res) as there, one(k) for the rest.
template <class Block, class One>
int run_default(long long m, int *status, int nthreads, Block block, One one) noexcept {
  return run_blocks<kDefaultLanes>(m, status, nthreads, kDefaultChunk, block, one);
}

}  // namespace batch
}  // namespace pw85
