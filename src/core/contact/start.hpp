// Starting points of the iterations (docs/methods.md, eqs. (M7), (M19), (M20),
// (M22)), inline so that the instruction-set variants of DEFAULT
// (default.hpp) compile them for their level. (M22) is DEFAULT's start;
// (M19)-(M20) are NEWTON's and RATIONAL's.
#pragma once

#include <cmath>

#include "common/isa.hpp"
#include "common/lanes.hpp"
#include "common/sym3.hpp"

namespace pw85 {

// Eq. (M7): lambda0 = h1 / (h1 + h2), h_i = (r^T Q_i r)^(1/2); the fallback
// of fixed_point_start and of the iteration of (M22). One pair (Vec3, Sym3)
// or one pair per lane (start_lanes.hpp: Vec3L, SymL).
template <class Vc, class Sy>
PW85_ALWAYS_INLINE auto newton_start(Vc const &r, Sy const &q1, Sy const &q2) noexcept {
  using lanes::vsqrt;
  typedef decltype(dot(r, r)) Lane;
  Lane const h1 = vsqrt(dot(r, multiply(q1, r)));
  Lane const h2 = vsqrt(dot(r, multiply(q2, r)));
  Lane const l0 = h1 / (h1 + h2);
  lanes::MaskOf<Lane> const in = (l0 > 0.0) & (l0 < 1.0);
  return lanes::select(in, l0, Lane{} + 0.5);
}

namespace detail {

// The algebra below is written once for one pair (Sym3, Vec3, double) and
// for one pair per vector lane (contact/start_lanes.hpp: SymL, Vec3L,
// lanes::VecD): the same operations in the same order, so a lane's values
// are the one-pair code's bits (the including files are compiled without
// contraction, src/meson.build).

// a_i = n^T Q_i n, i = 1, 2, and adj(q) r below: what dot(n, multiply(q, n))
// and multiply(adjugate3(q), r) of sym3.hpp compute, summed as short trees
// (the dependency chain is the cost of the start). The two orders give
// starts that differ in the last bits, which moves some results by an ulp
// (tests/test-contact.c's point bounds, set at the measured maxima, notice).
template <class Vc, class Sy, class V>
PW85_ALWAYS_INLINE void support_squares(Vc const &n, Sy const &q1, Sy const &q2, V &a1,
                                        V &a2) noexcept {
  V const n00 = n[0] * n[0], n11 = n[1] * n[1], n22 = n[2] * n[2];
  V const n01 = 2.0 * n[0] * n[1], n02 = 2.0 * n[0] * n[2], n12 = 2.0 * n[1] * n[2];
  a1 = (q1[0] * n00 + q1[3] * n11) + (q1[5] * n22 + q1[1] * n01) + (q1[2] * n02 + q1[4] * n12);
  a2 = (q2[0] * n00 + q2[3] * n11) + (q2[5] * n22 + q2[1] * n01) + (q2[2] * n02 + q2[4] * n12);
}

// c r summed as short trees (multiply() of sym3.hpp sums left to right).
template <class Sy, class Vc>
PW85_ALWAYS_INLINE Vc tree_times(Sy const &c, Vc const &r) noexcept {
  return Vc{{c[0] * r[0] + (c[1] * r[1] + c[2] * r[2]),
             c[1] * r[0] + (c[3] * r[1] + c[4] * r[2]),
             c[2] * r[0] + (c[4] * r[1] + c[5] * r[2])}};
}

template <class Sy, class Vc>
PW85_ALWAYS_INLINE Vc adj_times(Sy const &q, Vc const &r) noexcept {
  return tree_times(adjugate3(q), r);
}

}  // namespace detail

// Eq. (M19). At the maximiser, n = Q(lambda*)^{-1} r is the common normal and
// lambda* = h1(n) / (h1(n) + h2(n)), h_i(n) = (n^T Q_i n)^(1/2); iterating
// that map from lambda = 1/2 approaches lambda* fast while far from it (it is
// exact for spheres). n is needed only up to a factor: with x = h1 / h2 =
// lambda / (1 - lambda),
//   adj(Q(lambda)) r ~ adj(Q1) r + x M r + x^2 adj(Q2) r,
// M the mixed adjugate (eq. (M13)), M r = adj(Q1 + Q2) r - adj(Q1) r -
// adj(Q2) r. The three vectors do not depend on lambda and are formed in
// parallel at the start. Multiplied by h2^2 / (a1 + a2), a_i = h_i^2, the
// next n is (a2 n1 + sqrt(a1 a2) M r + a1 n2) / (a1 + a2): one square root
// on the dependency chain of a step and no division there (the reciprocal
// of a1 + a2 is formed while the square root runs; the factor keeps n from
// over- or underflowing over the steps). The result is the Aitken
// extrapolation of the three iterates (eq. (M20)).
PW85_ALWAYS_INLINE double fixed_point_start(Vec3 const &r, Sym3 const &q1, Sym3 const &q2) noexcept {
  constexpr int kSteps = 3;
  Sym3 q12;
  for (int i = 0; i < kSym; ++i) q12[i] = q1[i] + q2[i];
  Vec3 const n12 = detail::adj_times(q12, r), n1 = detail::adj_times(q1, r),
             n2 = detail::adj_times(q2, r);
  Vec3 mr;
  for (int i = 0; i < kDim; ++i) mr[i] = n12[i] - (n1[i] + n2[i]);
  double a1, a2;
  detail::support_squares(n12, q1, q2, a1, a2);  // step 1: lambda = 1/2, n = adj(Q1 + Q2) r
  static_assert(kSteps >= 3, "Aitken's extrapolation needs three iterates");
  double lam[kSteps - 1];  // lambda after steps 1 .. kSteps - 1
  for (int k = 1; k < kSteps; ++k) {
    // Range: with every magnitude in (2^-60, 2^60) (methods.cpp rescales
    // the others), a_i <= ~2^420, and a_i >= ~2^-460 for eigenvalue ratios
    // up to 2^40, so a1 a2 stays a normal double. Beyond, an overflow makes
    // lambda NaN ((M7) below) and an underflow gives a worse start, never a
    // wrong result. sqrt(a1) sqrt(a2) would avoid both, at one more square
    // root per step on the chain (slower: build/bench/bench_contact).
    double const g = std::sqrt(a1 * a2), scale = 1.0 / (a1 + a2);
    lam[k - 1] = a1 / (a1 + g);  // h1 / (h1 + h2), off the chain
    double const c1 = a2 * scale, cm = g * scale, c2 = a1 * scale;
    Vec3 n;
    for (int i = 0; i < kDim; ++i) n[i] = c1 * n1[i] + (cm * mr[i] + c2 * n2[i]);
    detail::support_squares(n, q1, q2, a1, a2);
  }
  double const h1 = std::sqrt(a1), h2 = std::sqrt(a2);
  double const l3 = h1 / (h1 + h2);
  // Eq. (M20): Aitken's extrapolation of the last three iterates (the map
  // converges linearly), kept when the correction is at most 10 times the
  // last step (contraction ratio below ~0.9, or oscillation) and lands in
  // (0, 1); a zero or NaN denominator fails the test.
  double const e1 = l3 - lam[kSteps - 2], e0 = lam[kSteps - 2] - lam[kSteps - 3];
  double const corr = e1 * e1 / (e1 - e0);
  double const l = std::fabs(corr) <= 10.0 * std::fabs(e1) ? l3 - corr : l3;
  return l > 0.0 && l < 1.0 ? l : (l3 > 0.0 && l3 < 1.0 ? l3 : newton_start(r, q1, q2));
}

// Eq. (M22): Newton's method on the fixed-point equation of (M19) in
// logarithmic coordinates (DEFAULT's start). With x = lambda / (1 - lambda)
// and n(x) = adj(Q1) r + x M r + x^2 adj(Q2) r (as in (M19)),
//   a_i(x) = n(x)^T Q_i n(x) = sum_k c_ik x^k,  k = 0..4,
// are quartics whose coefficients are formed once, and lambda* is the root
// of F(t) = G(t) - t, t = log x, G = (log a1 - log a2) / 2, since
//   f'(lambda) = (1 - lambda)^6 / det(Q(lambda))^2 (a1(x) - x^2 a2(x))
// (with s = Q^{-1} r: f' = (1 - lambda)^2 s^T Q1 s - lambda^2 s^T Q2 s).
// (M19) is the fixed-point iteration t <- G(t) (linear convergence); a
// Newton step on F is
//   delta = (G - t) / (1 - G'),  G - t = log(rho) / 2,  rho = a1 / (x^2 a2),
//   1 - G' = 1 - x (a1' / a1 - a2' / a2) / 2,
// taken with two changes that keep its quadratic convergence (they differ
// from the exact step by third-order terms) and make it safe far from the
// root: log(rho) / 2 is replaced by tanh(log(rho) / 2) = (a1 - x^2 a2) /
// (a1 + x^2 a2), bounded by 1, and exp(delta) by its Pade form
// (2 + delta) / (2 - delta), with |delta| clamped to kClamp < 2 so that x
// stays positive. Where 1 - G' <= 0 (far from the root) the step is the
// fixed-point direction delta = tanh(log(rho) / 2). The step is one
// division: x <- x (2 D + N) / (2 D - N), delta = N / D. It starts from the
// first (M19) iterate x = (a1(1) / a2(1))^(1/2) and stops after kMin steps
// once |delta| <= tol (then the error of x is ~delta^2), or after kMax;
// the last step returns lambda = x / (1 + x) directly.
// Coefficients: the identity (Q1 + x Q2) adj(Q1 + x Q2) = det(Q1 + x Q2) I
// leaves two products Q_i v to form (below). They are scaled by
// 1 / (a1(1) + a2(1)) (F and G' do not change when a1 and a2 are scaled
// together), which keeps the products of three a's in the step from
// overflowing. A lambda outside (0, 1) (NaN from an overflow, or a
// rounding-dominated quartic) falls back to (M7).
// The quartics of (M22) (scaled coefficients c_ik, k = 0..4) and the first
// (M19) iterate x0.
template <class V>
struct StartQuarticsOf {
  V a1[5], a2[5];
  V x0;
};
using StartQuartics = StartQuarticsOf<double>;

// kScaled = false (start_scan.hpp): the coefficients unscaled and no x0.
// One pair, or one pair per lane (start_lanes.hpp).
template <bool kScaled = true, class Vc, class Sy, class V>
PW85_ALWAYS_INLINE void start_quartics(Vc const &r, Sy const &q1, Sy const &q2,
                                       StartQuarticsOf<V> &sq) noexcept {
  Sy q12;
  for (int i = 0; i < kSym; ++i) q12[i] = q1[i] + q2[i];
  Sy const c1 = adjugate3(q1), c2 = adjugate3(q2);
  Vc const n12 = detail::adj_times(q12, r);
  Vc const n1 = detail::tree_times(c1, r), n2 = detail::tree_times(c2, r);
  Vc m;
  for (int i = 0; i < kDim; ++i) m[i] = n12[i] - (n1[i] + n2[i]);
  // a_i(1) (x = 1, lambda = 1/2: n = adj(Q1 + Q2) r), the first (M19) iterate.
  V s1, s2;
  detail::support_squares(n12, q1, q2, s1, s2);
  V sc = V{} + 1.0;
  sq.x0 = V{};
  if constexpr (kScaled) {
    sq.x0 = lanes::vsqrt(s1 / s2);
    sc = 1.0 / (s1 + s2);
  }
  V const det1 = det_with_adjugate(q1, c1) * sc;
  V const det2 = det_with_adjugate(q2, c2) * sc;
  // t1 = tr(adj(Q1) Q2), t2 = tr(Q1 adj(Q2)) (scaled), the middle terms of
  // det(Q1 + x Q2) = det1 + t1 x + t2 x^2 + det2 x^3.
  V const t1 = ((c1[0] * q2[0] + c1[3] * q2[3]) + c1[5] * q2[5] +
                2.0 * ((c1[1] * q2[1] + c1[2] * q2[2]) + c1[4] * q2[4])) * sc;
  V const t2 = ((q1[0] * c2[0] + q1[3] * c2[3]) + q1[5] * c2[5] +
                2.0 * ((q1[1] * c2[1] + q1[2] * c2[2]) + q1[4] * c2[4])) * sc;
  V const rn1 = dot(r, n1), rm = dot(r, m), rn2 = dot(r, n2);
  // The x^0 and x^1 terms of (Q1 + x Q2) adj(Q1 + x Q2) = det(Q1 + x Q2) I
  // give Q1 n1 = det1 r and Q1 m = t1 r - Q2 n1; likewise Q2 n2 = det2 r
  // and Q2 m = t2 r - Q1 n2: two products Q_i v remain.
  Vc const p = multiply(q2, n1), q = multiply(q1, n2);
  V const mp = dot(m, p) * sc, mq = dot(m, q) * sc;
  // c_ik (scaled): a1 = n1.Q1n1 + 2x m.Q1n1 + x^2 (m.Q1m + 2 n2.Q1n1) + 2x^3 n2.Q1m + x^4 n2.Q1n2.
  sq.a1[0] = det1 * rn1;
  sq.a1[1] = 2.0 * det1 * rm;
  sq.a1[2] = (t1 * rm - mp) + 2.0 * det1 * rn2;
  sq.a1[3] = 2.0 * mq;
  sq.a1[4] = dot(n2, q) * sc;
  sq.a2[4] = det2 * rn2;
  sq.a2[3] = 2.0 * det2 * rm;
  sq.a2[2] = (t2 * rm - mq) + 2.0 * det2 * rn1;
  sq.a2[1] = 2.0 * mp;
  sq.a2[0] = dot(n1, p) * sc;
}

// Clamp of |delta| in the iteration of (M22) (above).
constexpr double kLogNewtonClamp = 1.6;

// The Newton iteration of (M22) from sq.x0 (start_quartics), for one pair
// (V = double) or one pair per lane: a lane stops at its own step; the loop
// runs until every lane has stopped.
template <int kMin, int kMax, class V, class Vc, class Sy>
PW85_ALWAYS_INLINE V log_newton_iterate(StartQuarticsOf<V> const &sq, double tol, Vc const &r,
                                        Sy const &q1, Sy const &q2) noexcept {
  static_assert(1 <= kMin && kMin <= kMax, "step counts");
  using lanes::select;
  using lanes::vabs;
  typedef lanes::MaskOf<V> Mask;
  constexpr double kClamp = kLogNewtonClamp;
  V const a10 = sq.a1[0], a11 = sq.a1[1], a12 = sq.a1[2], a13 = sq.a1[3], a14 = sq.a1[4];
  V const a20 = sq.a2[0], a21 = sq.a2[1], a22 = sq.a2[2], a23 = sq.a2[3], a24 = sq.a2[4];
  V x = sq.x0;
  // Coefficients of the derivatives a_i'.
  V const b12 = 2.0 * a12, b13 = 3.0 * a13, b14 = 4.0 * a14;
  V const b22 = 2.0 * a22, b23 = 3.0 * a23, b24 = 4.0 * a24;
  V out{};
  Mask done{};
  for (int k = 1;; ++k) {
    // Estrin's scheme (short dependency chains).
    V const x2 = x * x;
    V const a1 = (a10 + a11 * x) + x2 * ((a12 + a13 * x) + x2 * a14);
    V const a2 = (a20 + a21 * x) + x2 * ((a22 + a23 * x) + x2 * a24);
    V const d1 = (a11 + b12 * x) + x2 * (b13 + b14 * x);
    V const d2 = (a21 + b22 * x) + x2 * (b23 + b24 * x);
    V const b = x2 * a2;
    V n = a1 - b, dd = a1 + b;  // tanh(log(rho) / 2) = n / dd
    V const w = 2.0 * (a1 * a2);
    V const g = w - x * (d1 * a2 - d2 * a1);  // (1 - G') w
    Mask const gp = g > 0.0;
    n = select(gp, n * w, n);  // delta = n / dd
    dd = select(gp, dd * g, dd);
    V const lim = kClamp * dd;
    V const nc = select(vabs(n) > lim, lanes::copysign(lim, n), n);
    V const num = x * (2.0 * dd + nc), den = 2.0 * dd - nc;
    Mask stop = k >= kMin ? Mask(vabs(n) <= tol * dd) : Mask{};
    if (k >= kMax) stop = lanes::all_set<Mask>();
    stop &= lanes::mask_not(done);
    if (lanes::any(stop)) {
      V const l = num / (den + num);
      out = select(stop, l, out);
      done |= stop;
      if (k >= kMax || !lanes::any(lanes::mask_not(done))) break;
    }
    x = num / den;
  }
  Mask const in = (out > 0.0) & (out < 1.0);
  if (lanes::any(lanes::mask_not(in))) out = select(in, out, newton_start(r, q1, q2));
  return out;
}

// DEFAULT's start (M22) for one pair or one pair per lane.
template <int kMin, int kMax, class Vc, class Sy>
PW85_ALWAYS_INLINE auto log_newton_start(Vc const &r, Sy const &q1, Sy const &q2,
                                         double tol) noexcept {
  StartQuarticsOf<decltype(dot(r, r))> sq;
  start_quartics(r, q1, q2, sq);
  return log_newton_iterate<kMin, kMax>(sq, tol, r, q1, q2);
}

}  // namespace pw85
