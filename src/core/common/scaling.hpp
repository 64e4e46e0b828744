// Exact power-of-two rescaling, written once for every caller that moves its
// arguments into a safe range (or its results back): the methods, the
// contact geometry, the derivatives, the distance of closest approach, the
// orientation constructors, contact_time and the C layer's screens. The
// exponents are the caller's (max_exponent of magnitude.hpp, made even
// where a square root must scale exactly).
#pragma once

#include <cmath>

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

}  // namespace pw85
