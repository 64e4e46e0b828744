// Double-double evaluation of the two sign certificates of the overlap
// filters (docs/overlap.md, eq. (O15)), for the pairs whose double-precision
// bounds (O3) are too wide: ill-conditioned matrices, near contact. Each
// returns the computed value of the expression; the caller certifies its sign
// with kDDRel * P + kAbs, P the (O3) bound expression evaluated in double.
#pragma once

#include "common/sym3.hpp"
#include "dispatch/variant.hpp"

namespace pw85 {

// Relative error bound of the double-double expressions below, in units of
// their absolute-value expression P (eq. (O15)): at most 16 operations on any
// path, each with relative error <= 8 u^2 (u = 2^-53), so <= 2^-98 P; 2^-90
// leaves room for P itself being computed in double.
constexpr double kDDRel = 0x1p-90;

// g = det Q - y^T adj(Q) y, y = x - c (exact double-double differences):
// g > 0 iff y is strictly inside {y : y^T Q^{-1} y < 1} (eq. (O6)).
double witness_g_dd(Sym3 const &q, Vec3 const &x, Vec3 const &c) noexcept;

// p(l) = det Q(l) - l (1 - l) r^T adj Q(l) r with l on the grid 2^-52 Z
// (eq. (O4)): p(l) <= 0 iff f(l) >= 1.
double p_dd(double l, Vec3 const &r, Sym3 const &q1, Sym3 const &q2) noexcept;

// Witness point near contact (eq. (O17)): with s = Q(l)^{-1} r solved in
// double-double (f_dd.hpp), the offset of x = (1 - l) Q1 s from the centre
// of E1 (from_c2 false) or of x - r = -l Q2 s from the centre of E2 (from_c2
// true) as hi + lo, and f'(l) = (1 - l)^2 s^T Q1 s - l^2 s^T Q2 s. Not a
// certificate. Returns false when Q(l) is not positive definite in
// double-double or a value is not finite.
bool witness_point_dd(double l, Vec3 const &r, Sym3 const &q1, Sym3 const &q2, bool from_c2,
                      Vec3 &hi, Vec3 &lo, double &df) noexcept;

// g_k = det Q_k - y_k^T adj(Q_k) y_k (k = 1, 2) at the point P = c + hi + lo,
// c = 0 (from_c2 false) or r (true): the offset from c is exact, the other
// offset is formed in double-double with relative error <= 2^-104, which
// moves g_k by at most 2^-102 P_k, inside the margin kDDRel P_k (eq. (O17)).
void witness_pair_dd(Sym3 const &q1, Sym3 const &q2, Vec3 const &r, Vec3 const &hi,
                     Vec3 const &lo, bool from_c2, double g[2]) noexcept;

// The variants of the four kernels above (overlap_dd.cpp): Dekker's product
// on any CPU, the fused multiply-add from the fma variant up, where built.
struct OverlapDdKernels {
  double (*witness_g)(Sym3 const &q, Vec3 const &x, Vec3 const &c) noexcept;
  double (*p)(double l, Vec3 const &r, Sym3 const &q1, Sym3 const &q2) noexcept;
  bool (*witness_point)(double l, Vec3 const &r, Sym3 const &q1, Sym3 const &q2, bool from_c2,
                        Vec3 &hi, Vec3 &lo, double &df) noexcept;
  void (*witness_pair)(Sym3 const &q1, Sym3 const &q2, Vec3 const &r, Vec3 const &hi,
                       Vec3 const &lo, bool from_c2, double g[2]) noexcept;
};
extern const OverlapDdKernels overlap_dd_kernels[kVariantCount];

}  // namespace pw85
