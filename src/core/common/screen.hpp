// Argument screens of the hot paths, called from the core so that they are
// compiled into each instruction-set variant of those paths: the
// positive-definiteness certificate of spd.hpp for two matrices in two
// lanes, and the one-pass screens of pw85_overlap (overlap/overlap.cpp) and
// pw85_contact_function_method (contact/methods.cpp). A matrix they do not
// certify takes the general path, whose validation (positive_definite)
// makes the same decision exactly.
#pragma once

#include <cmath>
#include <cstring>

#include "common/fp.hpp"
#include "common/lanes.hpp"
#include "common/magnitude.hpp"
#include "common/spd.hpp"

namespace pw85 {

// Two-lane helpers (GCC/Clang vector extension, one SSE2 register).
namespace v2 {
typedef double D2 __attribute__((vector_size(16)));
typedef long long I2 __attribute__((vector_size(16)));
inline D2 load(double const *p) noexcept {
  D2 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline D2 abs(D2 x) noexcept {
  return reinterpret_cast<D2>(reinterpret_cast<I2>(x) & I2{0x7fffffffffffffffLL, 0x7fffffffffffffffLL});
}
inline D2 max(D2 a, D2 b) noexcept { return a > b ? a : b; }  // NaN in a: b
#if defined(__clang__)
inline D2 lo_lanes(D2 a, D2 b) noexcept { return __builtin_shufflevector(a, b, 0, 2); }
inline D2 hi_lanes(D2 a, D2 b) noexcept { return __builtin_shufflevector(a, b, 1, 3); }
#else
inline D2 lo_lanes(D2 a, D2 b) noexcept { return __builtin_shuffle(a, b, I2{0, 2}); }
inline D2 hi_lanes(D2 a, D2 b) noexcept { return __builtin_shuffle(a, b, I2{1, 3}); }
#endif
}  // namespace v2

// certain_spd (spd.hpp) for q1 and q2 at once, given as their three lane
// pairs a01, a23, a45 and b01, b23, b45: each lane performs the operations
// of spd_shifted_pivots, so the decision is certain_spd's for each matrix.
inline bool certain_spd_pair(v2::D2 a01, v2::D2 a23, v2::D2 a45, v2::D2 b01, v2::D2 b23,
                             v2::D2 b45) noexcept {
  using v2::D2;
  D2 const x0 = v2::lo_lanes(a01, b01), x1 = v2::hi_lanes(a01, b01);
  D2 const x2 = v2::lo_lanes(a23, b23), x3 = v2::hi_lanes(a23, b23);
  D2 const x4 = v2::lo_lanes(a45, b45), x5 = v2::hi_lanes(a45, b45);
  D2 d0, d1, d2;
  spd_shifted_pivots(x0, x1, x2, x3, x4, x5, d0, d1, d2);
  D2 const big{kMaxDouble, kMaxDouble};
  v2::I2 const ok = (d0 > 0.0) & (d1 > 0.0) & (d2 > 0.0) & (d2 <= big);
  return (ok[0] & ok[1]) != 0;
}

// One pass over the arguments of pw85_overlap: true when q1 and q2 pass the
// certificate above, |r_i| <= hi, |Q_ij| <= hi and max |Q_ij| >= lo; so
// everything is finite (a NaN entry of a matrix reaches one of its pivots,
// whose test fails; a NaN in r fails |r_i| <= hi). One combined test at the
// end instead of an early exit per test. False does not mean invalid: the
// caller then takes the general path (validation, scaling). Pointers must be
// non-null.
inline bool screen_overlap_pair(double const *r, double const *q1, double const *q2, double lo,
                            double hi) noexcept {
  using v2::D2;
  D2 const a01 = v2::load(q1), a23 = v2::load(q1 + 2), a45 = v2::load(q1 + 4);
  D2 const b01 = v2::load(q2), b23 = v2::load(q2 + 2), b45 = v2::load(q2 + 4);
  // max |Q_ij| over both matrices. A NaN in a matrix may be skipped here;
  // it reaches a pivot below, whose test fails.
  D2 const m = v2::max(v2::max(v2::max(v2::abs(a01), v2::abs(a23)), v2::max(v2::abs(a45), v2::abs(b01))),
                       v2::max(v2::abs(b23), v2::abs(b45)));
  double const qm = m[0] > m[1] ? m[0] : m[1];
  bool const r_ok =
      (std::fabs(r[0]) <= hi) & (std::fabs(r[1]) <= hi) & (std::fabs(r[2]) <= hi);
  return r_ok & (qm >= lo) & (qm <= hi) & certain_spd_pair(a01, a23, a45, b01, b23, b45);
}

// The screen of pw85_contact_function_method, written once for every lane
// type V (a double, or a vector of doubles with one pair or one matrix per
// lane, common/lanes.hpp): true where max |r_i| lies strictly inside
// (lo, hi) (so r != 0 and r is finite), written as "every |r_i| < hi and
// some |r_i| > lo" (the same for finite values; a NaN or an infinite value
// fails both forms; the maximum written as nested conditionals was compiled
// to a branch on r0 > r1, taken at random).
template <class V, class Vc>
PW85_ALWAYS_INLINE auto offset_in_range(Vc const &r, double lo, double hi) noexcept {
  using lanes::gt;
  using lanes::lt;
  using lanes::vabs;
  V const r0 = vabs(r[0]), r1 = vabs(r[1]), r2 = vabs(r[2]);
  return lt(r0, hi) & lt(r1, hi) & lt(r2, hi) & (gt(r0, lo) | gt(r1, lo) | gt(r2, lo));
}

// True where the matrix x0 ... x5 (one per lane) has max |x_i| strictly
// inside (lo, hi) and passes the positive-definiteness certificate of
// spd.hpp (certain_spd, its operations: the decision is certain_spd's). A
// NaN entry may be skipped by the maximum (vmax); it reaches a pivot, whose
// test fails. The comparisons are lanes.hpp's (lt, gt, ...: unsigned masks,
// which GCC does not compile lane by lane in an x86-64-v4 caller).
template <class V>
PW85_ALWAYS_INLINE auto matrix_in_range_spd(V x0, V x1, V x2, V x3, V x4, V x5, double lo,
                                            double hi) noexcept {
  using lanes::gt;
  using lanes::le;
  using lanes::lt;
  using lanes::vabs;
  using lanes::vmax;
  V const m = vmax(vmax(vmax(vabs(x0), vabs(x1)), vabs(x2)),
                   vmax(vmax(vabs(x3), vabs(x4)), vabs(x5)));
  V d0, d1, d2;
  spd_shifted_pivots(x0, x1, x2, x3, x4, x5, d0, d1, d2);
  return gt(m, lo) & lt(m, hi) & gt(d0, 0.0) & gt(d1, 0.0) & gt(d2, 0.0) & le(d2, kMaxDouble);
}

// One pass over the arguments of pw85_contact_function_method: true when
// offset_in_range holds for r and matrix_in_range_spd for q1 and q2 (then
// everything is finite). False: take the general path (validation, then the
// dispatcher's scaling). Pointers must be non-null. The two matrices are
// screened side by side in the two lanes of one vector.
inline bool screen_contact_pair(double const *r, double const *q1, double const *q2,
                                double lo, double hi) noexcept {
  using v2::D2;
  D2 const a01 = v2::load(q1), a23 = v2::load(q1 + 2), a45 = v2::load(q1 + 4);
  D2 const b01 = v2::load(q2), b23 = v2::load(q2 + 2), b45 = v2::load(q2 + 4);
  auto const m = matrix_in_range_spd(v2::lo_lanes(a01, b01), v2::hi_lanes(a01, b01),
                                       v2::lo_lanes(a23, b23), v2::hi_lanes(a23, b23),
                                       v2::lo_lanes(a45, b45), v2::hi_lanes(a45, b45), lo, hi);
  return offset_in_range<double>(r, lo, hi) & ((m[0] & m[1]) != 0);
}

// screen_contact_pair for one pair per lane of the vectors of r, q1, q2
// (Vec3L, SymL of contact/start_lanes.hpp): the same decision in each lane.
template <class V, class Vc, class Sy>
PW85_ALWAYS_INLINE lanes::MaskOf<V> screen_contact_lanes(Vc const &r, Sy const &q1,
                                                         Sy const &q2, double lo,
                                                         double hi) noexcept {
  return reinterpret_cast<lanes::MaskOf<V>>(
      offset_in_range<V>(r, lo, hi) &
      matrix_in_range_spd(q1[0], q1[1], q1[2], q1[3], q1[4], q1[5], lo, hi) &
      matrix_in_range_spd(q2[0], q2[1], q2[2], q2[3], q2[4], q2[5], lo, hi));
}

}  // namespace pw85
