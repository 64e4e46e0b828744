// Exact power-of-two rescaling, written once for every caller that moves its
// arguments into a safe range (or its results back): the methods, the
// contact geometry, the derivatives, the distance of closest approach, the
// orientation constructors, contact_time and the C layer's screens. The
// exponents are the caller's (max_exponent of magnitude.hpp, made even
// where a square root must scale exactly).
#pragma once

#include <cmath>

#include "common/magnitude.hpp"
#include "common/sym3.hpp"

namespace pw85 {

// out[i] = x[i] 2^e for i < n (std::ldexp: exact unless the result is
// subnormal, where it is rounded, or overflows). out may be x.
inline void scale_by_power_of_two(double const *x, double *out, int n, int e) noexcept {
  for (int i = 0; i < n; ++i) out[i] = std::ldexp(x[i], e);
}

// x[i] *= 2^e for i < n, in place.
inline void scale_by_power_of_two(double *x, int n, int e) noexcept {
  scale_by_power_of_two(x, x, n, e);
}

// A pair (r, q1, q2), 3D (Vec3, Sym3) or 2D (Vec2, Sym2): rs = 2^er r,
// q1s = 2^eq q1, q2s = 2^eq q2 (the outputs may be the inputs).
template <class Vec, class Sym>
inline void scale_pair(Vec const &r, Sym const &q1, Sym const &q2, int er, int eq, Vec &rs,
                       Sym &q1s, Sym &q2s) noexcept {
  constexpr int kVec = sizeof r.x / sizeof r.x[0], kMat = sizeof q1.a / sizeof q1.a[0];
  scale_by_power_of_two(r.x, rs.x, kVec, er);
  scale_by_power_of_two(q1.a, q1s.a, kMat, eq);
  scale_by_power_of_two(q2.a, q2s.a, kMat, eq);
}

// The matrices of a pair only: q1s = 2^eq q1, q2s = 2^eq q2.
template <class Sym>
inline void scale_matrices(Sym const &q1, Sym const &q2, int eq, Sym &q1s, Sym &q2s) noexcept {
  constexpr int kMat = sizeof q1.a / sizeof q1.a[0];
  scale_by_power_of_two(q1.a, q1s.a, kMat, eq);
  scale_by_power_of_two(q2.a, q2s.a, kMat, eq);
}

// A pair scaled into a safe range: when max |r_i| or max |Q_ij| (both
// matrices) lies outside (lo, hi), r' = 2^-er r and Q' = 2^-eq Q, er and eq
// the exponents of those maxima (std::frexp), eq made even so that the
// square roots of a Cholesky factor scale exactly; returns true then. False
// (er = eq = 0, the pair unchanged) inside the range.
inline bool scale_pair_into_range(Vec3 &r, Sym3 &q1, Sym3 &q2, double lo, double hi, int &er,
                                  int &eq) noexcept {
  double const rm = max_abs(r.x, kDim), m1 = max_abs(q1.a, kSym), m2 = max_abs(q2.a, kSym),
               qm = m1 > m2 ? m1 : m2;
  er = eq = 0;
  if (rm > lo && rm < hi && qm > lo && qm < hi) return false;
  std::frexp(rm, &er);
  std::frexp(qm, &eq);
  eq += eq & 1;  // even (also for negative eq: two's complement)
  scale_pair(r, q1, q2, -er, -eq, r, q1, q2);
  return true;
}

}  // namespace pw85
