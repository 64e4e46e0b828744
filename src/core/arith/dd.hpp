// Double-double arithmetic: a value hi + lo with |lo| <= ulp(hi)/2, about
// 106 bits of significand. Error-free transformations: two_sum (Knuth, TAOCP
// vol. 2, sec. 4.2.2, theorem B), two_prod by fused multiply-add or, without
// one, Dekker's product (Numer. Math. 18, 1971, mul12) with Veltkamp's
// splitting; the compound operations follow the double-double algorithms of
// Joldes, Muller and Popescu, ACM TOMS 44(2), 2017 (sum: algorithm 6, and
// its sloppy form, algorithm 5; products: the "sloppy" low-order terms),
// relative error a few units of 2^-106; the reciprocal is one Newton step
// from the double reciprocal.
//
// Every function takes a template flag F: true uses std::fma (to be
// instantiated only inside a function compiled for a target with an FMA
// instruction: common/isa.hpp), false uses Dekker's product (portable).
// Everything is inline, allocation-free and noexcept.
#pragma once

#include <cmath>

namespace pw85 {
namespace dd {

struct DD {
  double hi, lo;
};

inline DD two_sum(double a, double b) noexcept {
  double const s = a + b;
  double const bb = s - a;
  double const err = (a - (s - bb)) + (b - bb);
  return DD{s, err};
}

inline DD fast_two_sum(double a, double b) noexcept {  // requires |a| >= |b|
  double const s = a + b;
  return DD{s, b - (s - a)};
}

inline void split(double a, double &hi, double &lo) noexcept {
  double const c = 134217729.0 * a;  // 2^27 + 1
  hi = c - (c - a);
  lo = a - hi;
}

template <bool F>
inline DD two_prod(double a, double b) noexcept {
  double const p = a * b;
  if constexpr (F) {
    return DD{p, std::fma(a, b, -p)};
  } else {
    double ah, al, bh, bl;
    split(a, ah, al);
    split(b, bh, bl);
    return DD{p, ((ah * bh - p) + ah * bl + al * bh) + al * bl};
  }
}

inline DD add(DD x, DD y) noexcept {
  DD s = two_sum(x.hi, y.hi);
  DD const t = two_sum(x.lo, y.lo);
  s.lo += t.hi;
  s = fast_two_sum(s.hi, s.lo);
  s.lo += t.lo;
  return fast_two_sum(s.hi, s.lo);
}

inline DD add(DD x, double y) noexcept {
  DD s = two_sum(x.hi, y);
  s.lo += x.lo;
  return fast_two_sum(s.hi, s.lo);
}

// Sloppy sum (Joldes, Muller and Popescu, algorithm 5): 11 operations
// instead of add's 20. Its error is a few u^2 (|x| + |y|), absolute: no
// relative bound when x + y cancels. For sums whose error is counted
// against the magnitudes of their terms anyway (componentwise bounds).
inline DD add_sloppy(DD x, DD y) noexcept {
  DD const s = two_sum(x.hi, y.hi);
  return fast_two_sum(s.hi, s.lo + (x.lo + y.lo));
}

inline DD neg(DD x) noexcept { return DD{-x.hi, -x.lo}; }
inline DD sub(DD x, DD y) noexcept { return add(x, neg(y)); }
inline DD sub_sloppy(DD x, DD y) noexcept { return add_sloppy(x, neg(y)); }

template <bool F>
inline DD mul(DD x, double y) noexcept {
  DD p = two_prod<F>(x.hi, y);
  p.lo += x.lo * y;
  return fast_two_sum(p.hi, p.lo);
}

template <bool F>
inline DD mul(DD x, DD y) noexcept {
  DD p = two_prod<F>(x.hi, y.hi);
  p.lo += x.hi * y.lo + x.lo * y.hi;
  return fast_two_sum(p.hi, p.lo);
}

// 1 / y by one division and one Newton step: with r0 = RN(1 / y.hi), the
// residual e = 1 - y r0 (|e| <= 2u) is formed exactly up to the rounding of
// y.lo r0 (1 - y.hi r0 is a double, Sterbenz), and 1 / y = r0 (1 + e + e^2
// + ...) = r0 + r0 e with relative error below 8 u^2 = 2^-103. One division
// instead of the three in sequence of [JMP]'s division.
template <bool F>
inline DD recip(DD y) noexcept {
  double const r0 = 1.0 / y.hi;
  DD const p = two_prod<F>(y.hi, r0);
  double const e = ((1.0 - p.hi) - p.lo) - y.lo * r0;
  return fast_two_sum(r0, r0 * e);
}

inline double to_double(DD x) noexcept { return x.hi + x.lo; }

}  // namespace dd
}  // namespace pw85
