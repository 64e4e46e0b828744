// The pairs of bench_contact's classes drawn one at a time, and the
// near-contact pairs built from them (bench_near_contact, trace_pairs).
// Benchmarks only, not part of the library.
#pragma once

#include <cmath>

#include "bench_common.hpp"
#include "pw85.h"

namespace bench {

// The four classes of bench_contact: three distinct semi-axes log-uniform
// in [lo, hi] of each ellipsoid.
constexpr double kClassBounds[4][2] = {{0.5, 2}, {0.1, 10}, {0.01, 100}, {0.001, 1000}};

// A random pair of class c as bench_contact draws it: two random
// ellipsoids (random_axes) and the offset random_offset(reach, span).
inline void random_pair(Rng &g, int c, double span, double r12[3], double q1[6], double q2[6]) {
  double a[3], rot[3][3];
  random_axes(g, kClassBounds[c][0], kClassBounds[c][1], a, rot);
  q_from_axes(a, rot, q1);
  double reach = std::fmax(a[0], std::fmax(a[1], a[2]));
  random_axes(g, kClassBounds[c][0], kClassBounds[c][1], a, rot);
  q_from_axes(a, rot, q2);
  reach += std::fmax(a[0], std::fmax(a[1], a[2]));
  random_offset(g, reach, span, r12);
}

// A near-contact pair of class c: a random pair (span kContactSpan) whose
// r12 is scaled by sqrt(t / mu2_0) so that mu^2 (proportional to |r12|^2)
// hits the target t = 1 + s delta, s = +1 or -1 with probability 1/2,
// delta log-uniform in [1e-15, 1e-2]; mu2_0 from
// pw85_contact_function_method(PW85_METHOD_DEFAULT) (relative accuracy
// 1e-14, so below delta ~ 1e-14 the realised side is either). Draws again
// until that call succeeds.
inline void near_contact_pair(Rng &g, int c, double r12[3], double q1[6], double q2[6]) {
  for (;;) {
    random_pair(g, c, kContactSpan, r12, q1, q2);
    double const delta = std::pow(10.0, -15.0 + 13.0 * g.uniform());
    double const target = g.uniform() < 0.5 ? 1.0 - delta : 1.0 + delta;
    pw85_result res;
    if (pw85_contact_function_method(r12, q1, q2, PW85_METHOD_DEFAULT, &res) != PW85_OK ||
        !(res.mu2 > 0) || !std::isfinite(res.mu2))
      continue;
    double const scale = std::sqrt(target / res.mu2);
    for (int k = 0; k < 3; ++k) r12[k] *= scale;
    return;
  }
}

}  // namespace bench
