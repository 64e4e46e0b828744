// Where the pairs of a batch call come from: per-pair arrays, or index
// pairs into a scene (centres, matrices, an optional periodic box). A pair
// source gives pair k's r12, q1 and q2 to the loops of schedule.hpp and to
// the lanes (lanes.hpp).
#pragma once

#include <cmath>

#include "batch/box.hpp"
#include "batch/prefetch.hpp"
#include "batch/schedule.hpp"
#include "common/status.hpp"

namespace pw85 {
namespace batch {

// r12 = c_j - c_i of scene pair k (rounded to double: the batch functions
// decide for this r12, exactly as the one-pair functions would); false for
// an index outside [0, n).
inline bool pair_r12(long long n, double const *centres, long long const *pairs,
                     long long k, double r12[3], long long &i, long long &j) noexcept {
  i = pairs[2 * k];
  j = pairs[2 * k + 1];
  if (i < 0 || j < 0 || i >= n || j >= n) return false;
  for (int d = 0; d < 3; ++d) r12[d] = centres[3 * j + d] - centres[3 * i + d];
  return true;
}

// Upper bound of the largest eigenvalue of Q, the square of the largest
// semi-axis of its ellipsoid: the smaller of the trace and the largest
// Gershgorin row sum (both of |entries|). (Plain comparisons, not
// std::fmax, which is a library call here; a NaN entry may give any value:
// such a pair fails either way.)
inline double reach2(double const *q) noexcept {
  double const a00 = std::fabs(q[0]), a01 = std::fabs(q[1]), a02 = std::fabs(q[2]);
  double const a11 = std::fabs(q[3]), a12 = std::fabs(q[4]), a22 = std::fabs(q[5]);
  double const r0 = a00 + a01 + a02, r1 = a01 + a11 + a12, r2 = a02 + a12 + a22;
  double const trace = a00 + a11 + a22;
  double g = r0 > r1 ? r0 : r1;
  g = g > r2 ? g : r2;
  return trace < g ? trace : g;
}

// Whether the bounding spheres of q1 and q2 (radii sqrt(reach2)) have radii
// summing to more than box.max_reach. Cheap test first: (a + b)^2 <=
// 2 (a^2 + b^2).
inline bool too_large(Box const &box, double const *q1, double const *q2) noexcept {
  double const g1 = reach2(q1), g2 = reach2(q2);
  if (g1 + g2 <= box.max_reach2_half) return false;
  return std::sqrt(g1) + std::sqrt(g2) > box.max_reach;
}

// A scene: n ellipsoids (centres[3i..3i+2], q[6i..6i+5]), an optional
// periodic box, m index pairs.
struct Scene {
  long long n;
  double const *centres, *q;
  Box const &box;
  long long const *pairs;
  long long m;
};

// r12 of pair k of a scene: c_j - c_i, or its minimum image in the box.
// Returns kOk, or kInvalidArgument for an index out of range or (periodic
// box) a pair whose bounding spheres reach past max_reach or whose image
// minimum_image refuses. A non-finite centre or matrix is passed on to the
// one-pair function, which reports it.
[[gnu::always_inline]] inline Status scene_r12(Scene const &s, long long k, double r12[3], long long &i,
                        long long &j) noexcept {
  if (!pair_r12(s.n, s.centres, s.pairs, k, r12, i, j)) return kInvalidArgument;
  if (!s.box.periodic) return kOk;
  if (too_large(s.box, s.q + 6 * i, s.q + 6 * j)) return kInvalidArgument;
  if (std::isfinite(r12[0]) && std::isfinite(r12[1]) && std::isfinite(r12[2]))
    return minimum_image(s.box, r12);
  return kOk;
}

// Pair k of per-pair arrays (r12[3k..], q1[6k..], q2[6k..]), for the lane
// blocks: pair(k, buf, r, a, b) points r, a, b to pair k's arguments (r may
// point to buf, which the source may fill) and returns false when the pair
// fails before its one-pair call (with kInvalidArgument).
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

// ArrayPair with the array prefetch of pw85_overlap_pairs (once per 8 pairs).
struct PrefetchedArrayPair {
  long long m;
  double const *r12, *q1, *q2;
  bool operator()(long long k, double *, double const *&r, double const *&a,
                  double const *&b) const noexcept {
    if (k % 8 == 0) prefetch_arrays(m, r12, q1, q2, k);
    r = r12 + 3 * k;
    a = q1 + 6 * k;
    b = q2 + 6 * k;
    return true;
  }
};

// Pair k of a scene (scene_r12, with the scene prefetch), for the lane
// blocks; false: the pair failed scene_r12.
struct ScenePair {
  Scene s;  // a copy: its fields stay in registers in the lanes' loops
  [[gnu::always_inline]] bool operator()(long long k, double *buf, double const *&r, double const *&a,
                  double const *&b) const noexcept {
    prefetch_pair(s.n, s.centres, s.q, s.pairs, s.m, k);
    long long i, j;
    r = buf;
    if (scene_r12(s, k, buf, i, j) != kOk) return false;
    a = s.q + 6 * i;
    b = s.q + 6 * j;
    return true;
  }
};

// Pair k of a scene through one(k, r12, i, j), which computes it (r12 ==
// nullptr: the pair failed scene_r12) and returns its status.
template <class One>
int scene_one(Scene const &s, long long k, One &one) noexcept {
  double r12[3];
  long long i, j;
  int const st = scene_r12(s, k, r12, i, j);
  return one(k, st == kOk ? r12 : nullptr, i, j);
}

// Every pair of a scene, pair by pair through scene_one (run_pairs, chunk
// pairs per chunk).
template <class One>
int run_scene(Scene const &s, int *status, int nthreads, int chunk, One one) noexcept {
  return run_pairs(s.m, status, nthreads, chunk, [&](long long k) noexcept {
    prefetch_pair(s.n, s.centres, s.q, s.pairs, s.m, k);
    return scene_one(s, k, one);
  });
}

}  // namespace batch
}  // namespace pw85
