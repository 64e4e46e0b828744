// The one positive-definiteness decision of the library: a symmetric matrix
// is accepted when the real matrix whose entries are the doubles given is
// positive definite, i.e. when its leading principal minors
//     m1 = a00,   m2 = a00 a11 - a01^2,   m3 = det A
// are all > 0 (Sylvester's criterion), decided exactly (docs/api.md,
// "Positive definiteness"). Every call that validates a matrix uses it, on
// every instruction-set variant, so every call accepts and refuses the same
// matrices on every CPU:
//  - the hot paths screen their arguments with certain_spd (below): the
//    L D L^T pivots of a - c I in floating point, c a multiple of the
//    trace covering their rounding errors; a matrix it does not certify
//    takes the general path;
//  - the general path calls positive_definite (spd.cpp): the same
//    certificate, the minors with rigorous error bounds to certify the
//    opposite, on an exact power-of-two rescaling of the matrix when
//    needed, and where neither decides, the minors in exact integer
//    arithmetic (arith/bigint.hpp).
#pragma once

#include "common/fp.hpp"
#include "common/isa.hpp"
#include "common/lanes.hpp"

namespace pw85 {

// The certificate (Rump, "Verification of positive definiteness", BIT 46
// (2006), theorem 2.3, with the L D L^T form of the factorisation): if the
// pivots of b = fl(a - c I) computed in floating point are all > 0 and
// finite, b + db = L D L^T with |db| <= g |L| D |L^T|, g = gamma_4 ~ 4u,
// so lambda_min(b) >= -g/(1 - g) tr(b) and lambda_min(a) >= c' -
// g/(1 - g) tr(a) > 0, c' = min_i (a_ii - b_ii) >= c - u tr(a). Taking
// c = kSpdShift tr(a) + kSpdAbs leaves a margin of more than 3 in the
// relative term; kSpdAbs covers gradual underflow (Rump's term
// 4 (n + 1)(2 (n + 2) + max a_ii) eta for max a_ii <= kSpdFilterHi). The
// standard model |fl(x op y) - x op y| <= u |x op y| holds for fused
// multiply-adds too, so the certificate is valid whatever the compiler
// contracts. It certifies every matrix with lambda_min > ~17 u tr(a)
// (condition numbers up to ~1e14); nearly singular ones take the exact path.
constexpr double kSpdShift = 16 * kU;
constexpr double kSpdAbs = 0x1p-900;
constexpr double kSpdFilterHi = 0x1p128;

// The pivots d0, d1, d2 of L D L^T of fl(a - c I), a in Sym3 storage (a0
// ... a5 = a00 a01 a02 a11 a12 a22). Generic over the lane type V (a double
// for one matrix, a vector for one matrix per lane), so that every screen
// performs the same operations. No square root; one division per pivot.
template <class V>
PW85_ALWAYS_INLINE void spd_shifted_pivots(V a0, V a1, V a2, V a3, V a4, V a5, V &d0, V &d1,
                                           V &d2) noexcept {
  V const c = kSpdShift * ((a0 + a3) + a5) + kSpdAbs;
  d0 = a0 - c;
  V const i0 = 1.0 / d0;
  V const l1 = a1 * i0, l2 = a2 * i0;
  d1 = (a3 - c) - l1 * a1;
  V const e = a4 - l2 * a1;
  d2 = (a5 - c) - l2 * a2 - (e / d1) * e;  // no overflow of e * e
}

// Error bounds of the minors computed by spd_minors (the certificate of the
// opposite answer, spd.cpp), in the standard model:
//   |fl(m2) - m2| <= 2u (|a00 a11| + a01^2) (1 + O(u)),
//   |fl(m3) - m3| <= 5u P (1 + O(u)),  P = sum_i |a0i| (|x_i y_i| + |z_i w_i|)
// the permanent of the cofactor expansion m3 = sum_i a0i c_i, c_i = x_i y_i
// - z_i w_i; the constants add a margin for the rounding of the bounds
// themselves, kSpdAbs covers gradual underflow.
constexpr double kSpdC2 = 4 * kU;
constexpr double kSpdC3 = 8 * kU;

// The minors m2, m3 of a (Sym3 storage) and their error bounds e2, e3:
// |fl(m) - m| <= e.
template <class V>
PW85_ALWAYS_INLINE void spd_minors(V a0, V a1, V a2, V a3, V a4, V a5, V &m2, V &e2, V &m3,
                                   V &e3) noexcept {
  using lanes::vabs;
  V const p03 = a0 * a3, p11 = a1 * a1;
  m2 = p03 - p11;
  e2 = kSpdC2 * (vabs(p03) + p11) + kSpdAbs;
  // Cofactors of the first row: c0 = a11 a22 - a12^2, c1 = a02 a12 - a01 a22,
  // c2 = a01 a12 - a02 a11.
  V const x0 = a3 * a5, y0 = a4 * a4;
  V const x1 = a2 * a4, y1 = a1 * a5;
  V const x2 = a1 * a4, y2 = a2 * a3;
  V const c0 = x0 - y0, c1 = x1 - y1, c2 = x2 - y2;
  m3 = (a0 * c0 + a1 * c1) + a2 * c2;
  V const perm = (vabs(a0) * (vabs(x0) + y0) + vabs(a1) * (vabs(x1) + vabs(y1))) +
                 vabs(a2) * (vabs(x2) + vabs(y2));
  e3 = kSpdC3 * perm + kSpdAbs;
}

// a (Sym3 storage) is certainly positive definite: the pivots of
// spd_shifted_pivots all > 0 and finite. False for NaN or infinite entries,
// and when the certificate cannot decide; a correct certificate for
// entries of magnitude <= kSpdFilterHi (larger finite entries: see
// positive_definite).
inline bool certain_spd(double const *a) noexcept {
  double d0, d1, d2;
  spd_shifted_pivots(a[0], a[1], a[2], a[3], a[4], a[5], d0, d1, d2);
  return (d0 > 0.0) & (d1 > 0.0) & (d2 > 0.0) & (d2 <= kMaxDouble);
}

// The decision, for a finite matrix of any magnitude (Sym3 storage): true
// iff a is positive definite exactly; false where an entry is not finite.
bool positive_definite(double const *a) noexcept;

// The same decision for a symmetric 2x2 matrix (Sym2 storage a00 a01 a11):
// a00 > 0 and a00 a11 - a01^2 > 0 exactly.
bool positive_definite_2d(double const *a) noexcept;

}  // namespace pw85
