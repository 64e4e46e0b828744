// Double-double arithmetic: a value hi + lo with |lo| <= ulp(hi)/2, about
// 106 bits of significand. Error-free transformations: two_sum (Knuth, TAOCP
// vol. 2, sec. 4.2.2, theorem B), two_prod via fused multiply-add; the
// compound operations follow the "accurate" double-double algorithms of
// Joldes, Muller and Popescu, ACM TOMS 44(2), 2017 (algorithms 6, 12 and 18
// for sum, product by a double / by a double-double, and algorithm 17 for
// division), relative error below a few units of 2^-106 (the products use
// the cheaper "sloppy" low-order terms, a few more units of 2^-106).
// Everything is inline, allocation-free and noexcept. two_prod uses the FMA
// instruction when the target has it (-mfma), Dekker's product otherwise.
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

#ifdef __FMA__
inline DD two_prod(double a, double b) noexcept {
  double const p = a * b;
  return DD{p, std::fma(a, b, -p)};
}
#else
// Without hardware FMA std::fma is a library call, much slower than
// Dekker's product (Dekker, Numer. Math. 18, 1971, mul12) with Veltkamp's
// splitting, exact barring overflow.
inline void split(double a, double &hi, double &lo) noexcept {
  double const c = 134217729.0 * a;  // 2^27 + 1
  hi = c - (c - a);
  lo = a - hi;
}
inline DD two_prod(double a, double b) noexcept {
  double const p = a * b;
  double ah, al, bh, bl;
  split(a, ah, al);
  split(b, bh, bl);
  return DD{p, ((ah * bh - p) + ah * bl + al * bh) + al * bl};
}
#endif

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

inline DD neg(DD x) noexcept { return DD{-x.hi, -x.lo}; }
inline DD sub(DD x, DD y) noexcept { return add(x, neg(y)); }

inline DD mul(DD x, double y) noexcept {
  DD p = two_prod(x.hi, y);
  p.lo += x.lo * y;
  return fast_two_sum(p.hi, p.lo);
}

inline DD mul(DD x, DD y) noexcept {
  DD p = two_prod(x.hi, y.hi);
  double const t = x.hi * y.lo + x.lo * y.hi;
  p.lo += t;
  return fast_two_sum(p.hi, p.lo);
}

inline DD div(DD x, DD y) noexcept {
  double const q1 = x.hi / y.hi;
  DD const r = sub(x, mul(y, q1));
  double const q2 = r.hi / y.hi;
  DD const r2 = sub(r, mul(y, q2));
  double const q3 = r2.hi / y.hi;
  DD q = fast_two_sum(q1, q2);
  return add(q, q3);
}

inline double to_double(DD x) noexcept { return x.hi + x.lo; }

}  // namespace dd
}  // namespace pw85
