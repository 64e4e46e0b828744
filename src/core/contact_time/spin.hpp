// The rotation R(t) = exp(t [w]x) of one body in double-double
// (docs/contact_time.md (T9)): Rodrigues' formula on the exact input w,
//   R x = cos(th) x + S (w x x) + C w (w . x),  R^T x: the same with -S,
//   th = t |w|, S = sin(th) / |w|, C = (1 - cos(th)) / |w|^2,
// with |w|, th, sin and cos carried in double-double (relative error a few
// 2^-104, after the reduction of th modulo pi by a three-part pi). A vector
// turned to the body frame and back keeps ~32 significant digits, so that
// x^T Q_i(t) x = (R^T x)^T Q_i (R^T x) is formed from the exact input Q_i:
// the thinnest direction of Q_i(t) is not rounded, unlike the entries of
// R Q_i R^T in double (relative error u a_max^2 / a_min^2 there).
#pragma once

#include <cmath>

#include "arith/dd.hpp"
#include "common/isa.hpp"
#include "common/sym3.hpp"

namespace pw85 {

namespace ddx {

using dd::DD;
constexpr bool kF = kStaticFma;

// x / d, d a double (one correction step: a few 2^-104 relative).
inline DD div(DD x, double d) noexcept {
  double const q = x.hi / d;
  DD const p = dd::two_prod<kF>(q, d);
  double const r = ((x.hi - p.hi) - p.lo + x.lo) / d;
  return dd::fast_two_sum(q, r);
}

// sqrt(x), x > 0: one Newton step from the double square root.
inline DD sqrt(DD x) noexcept {
  double const s = std::sqrt(x.hi);
  if (!(s > 0.0)) return DD{s, 0.0};
  DD const e = dd::sub(x, dd::two_prod<kF>(s, s));
  return dd::fast_two_sum(s, to_double(e) / (2.0 * s));
}

inline DD mul(DD x, DD y) noexcept { return dd::mul<kF>(x, y); }
inline DD mul(DD x, double y) noexcept { return dd::mul<kF>(x, y); }

// sin(x), cos(x) for |x| <= ~pi/2: Taylor series of x / 8 (terms to x^21,
// below 2^-110 relative), then three double-angle steps.
inline void sincos(DD x, DD &s, DD &c) noexcept {
  DD const y = DD{x.hi * 0.125, x.lo * 0.125};
  DD const y2 = mul(y, y);
  DD ps{1.0, 0.0}, pc{1.0, 0.0};
  for (int k = 10; k >= 1; --k) {
    ps = dd::add(DD{1.0, 0.0}, dd::neg(div(mul(y2, ps), double(2 * k * (2 * k + 1)))));
    pc = dd::add(DD{1.0, 0.0}, dd::neg(div(mul(y2, pc), double((2 * k - 1) * 2 * k))));
  }
  s = mul(y, ps);
  c = pc;
  for (int k = 0; k < 3; ++k) {
    DD const s2 = mul(s, s);
    s = mul(mul(s, c), 2.0);
    c = dd::add(DD{1.0, 0.0}, dd::neg(mul(s2, 2.0)));
  }
}

}  // namespace ddx

// R(t) of one body at one time: cos(th), S, C of the header, w scaled by a
// power of two (exact) so that |w|^2 cannot overflow.
struct Spin {
  bool moving;  // w != 0 and t != 0 (else R = I)
  Vec3 w;       // 2^-k w_input
  dd::DD cos_th, S, C;
};

// Rodrigues' coefficients at t (t |w| finite): th / 2 = t |w| / 2 reduced
// modulo pi, sin(th) = 2 sin(th/2) cos(th/2), 1 - cos(th) = 2 sin^2(th/2).
inline Spin spin_at(Vec3 const &w, double t) noexcept {
  using dd::DD;
  Spin sp{false, w, {1.0, 0.0}, {0.0, 0.0}, {0.0, 0.0}};
  double const m = std::fmax(std::fabs(w[0]), std::fmax(std::fabs(w[1]), std::fabs(w[2])));
  if (!(m > 0.0) || t == 0.0) return sp;
  sp.moving = true;
  int const k = std::ilogb(m);
  for (int i = 0; i < kDim; ++i) sp.w[i] = std::ldexp(w[i], -k);
  DD ww = dd::two_prod<ddx::kF>(sp.w[0], sp.w[0]);
  ww = dd::add(ww, dd::two_prod<ddx::kF>(sp.w[1], sp.w[1]));
  ww = dd::add(ww, dd::two_prod<ddx::kF>(sp.w[2], sp.w[2]));
  DD const wn = ddx::sqrt(ww);                                   // |2^-k w|
  DD const half = ddx::mul(wn, std::ldexp(t, k - 1));           // th / 2
  // half - n pi, pi = P0 + P1 + P2 (three doubles, 159 bits)
  constexpr double P0 = 3.141592653589793116, P1 = 1.2246467991473532e-16,
                   P2 = -2.9947698097183397e-33;
  double const n = std::nearbyint(half.hi / P0);
  DD x = dd::sub(half, dd::two_prod<ddx::kF>(n, P0));
  x = dd::sub(x, dd::two_prod<ddx::kF>(n, P1));
  x = dd::add(x, -n * P2);
  DD s, c;
  ddx::sincos(x, s, c);  // sin, cos of th/2 up to the sign (-1)^n of both
  DD const sin_th = ddx::mul(ddx::mul(s, c), 2.0);
  DD const one_minus_cos = ddx::mul(ddx::mul(s, s), 2.0);
  sp.cos_th = dd::sub(DD{1.0, 0.0}, one_minus_cos);
  DD const inv = dd::recip<ddx::kF>(wn);
  sp.S = ddx::mul(sin_th, inv);
  sp.C = ddx::mul(one_minus_cos, dd::recip<ddx::kF>(ww));
  return sp;
}

// R x (sign = +1) or R^T x (sign = -1), x and the result in double-double.
inline void turn(Spin const &sp, dd::DD const x[kDim], double sign, dd::DD y[kDim]) noexcept {
  using dd::DD;
  if (!sp.moving) {
    for (int i = 0; i < kDim; ++i) y[i] = x[i];
    return;
  }
  Vec3 const &w = sp.w;
  DD const wx[kDim] = {dd::sub(ddx::mul(x[2], w[1]), ddx::mul(x[1], w[2])),
                       dd::sub(ddx::mul(x[0], w[2]), ddx::mul(x[2], w[0])),
                       dd::sub(ddx::mul(x[1], w[0]), ddx::mul(x[0], w[1]))};
  DD wd = ddx::mul(x[0], w[0]);
  wd = dd::add(wd, ddx::mul(x[1], w[1]));
  wd = dd::add(wd, ddx::mul(x[2], w[2]));
  DD const cw = ddx::mul(sp.C, wd);
  DD const ss = DD{sign * sp.S.hi, sign * sp.S.lo};
  for (int i = 0; i < kDim; ++i)
    y[i] = dd::add(dd::add(ddx::mul(sp.cos_th, x[i]), ddx::mul(ss, wx[i])), ddx::mul(cw, w[i]));
}

// Q y for the input Q (doubles) and y in double-double.
inline void sym_times(Sym3 const &q, dd::DD const y[kDim], dd::DD o[kDim]) noexcept {
  static constexpr int idx[3][3] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};
  for (int i = 0; i < kDim; ++i) {
    dd::DD s = ddx::mul(y[0], q[idx[i][0]]);
    s = dd::add(s, ddx::mul(y[1], q[idx[i][1]]));
    o[i] = dd::add(s, ddx::mul(y[2], q[idx[i][2]]));
  }
}

inline dd::DD dot_dd(dd::DD const a[kDim], dd::DD const b[kDim]) noexcept {
  dd::DD s = ddx::mul(a[0], b[0]);
  s = dd::add(s, ddx::mul(a[1], b[1]));
  return dd::add(s, ddx::mul(a[2], b[2]));
}

// Q(t) x = R Q R^T x in double-double.
inline void rotated_times(Spin const &sp, Sym3 const &q, dd::DD const x[kDim],
                          dd::DD o[kDim]) noexcept {
  dd::DD y[kDim], qy[kDim];
  turn(sp, x, -1.0, y);
  sym_times(q, y, qy);
  turn(sp, qy, 1.0, o);
}

// x^T Q(t) x = y^T Q y, y = R^T x (body frame), in double-double; y is
// also written (rounded) for the callers' rate terms.
inline dd::DD rotated_form(Spin const &sp, Sym3 const &q, dd::DD const x[kDim],
                           Vec3 *body = nullptr) noexcept {
  dd::DD y[kDim], qy[kDim];
  turn(sp, x, -1.0, y);
  sym_times(q, y, qy);
  if (body != nullptr)
    for (int i = 0; i < kDim; ++i) (*body)[i] = to_double(y[i]);
  return dot_dd(y, qy);
}

}  // namespace pw85
