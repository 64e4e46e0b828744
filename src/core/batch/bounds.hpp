// Bounding spheres of the scene calls and of the configuration object
// (docs/batch.md, "Periodic boxes"): the bound a periodic box puts on the
// two bounding spheres of a pair.
#pragma once

#include <cmath>

#include "batch/box.hpp"

namespace pw85 {
namespace batch {

// Upper bound of the largest eigenvalue of Q, the square of the largest
// semi-axis of its ellipsoid: the smaller of the trace and the largest
// Gershgorin row sum (both of |entries|). (Plain comparisons, not
// std::fmax, which is a library call here; a NaN entry may give any value:
// such a pair fails with PW85_ERR_INVALID_ARGUMENT either way.)
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

}  // namespace batch
}  // namespace pw85
