// Bounded values (docs/overlap.md, eq. (O3)) and the symmetric 3x3 algebra
// on them, for the overlap filters (overlap/filters.hpp). A bounded value
// holds the computed value fl(E) of an expression E and the computed value
// fl(P) of the same expression on absolute values with every - replaced by
// +; both see the same operations in the same order, so that
// |fl(E) - E| <= kOverlapFilterC fl(P) + kOverlapFilterAbs (err() below). A
// term that is subtracted enters as flip(x) = {value, -bound}: the bound
// then computes P_a - (-P_b) = P_a + P_b, exactly as (O3) requires.
//
// Generic over the lane type Lane of the filters: for W pairs (Lane a
// vector of W doubles of common/lanes.hpp) a bounded value is a pair of
// vectors, value and bound, lane l of each belonging to pair l; for one
// pair (Lane = double) it is one vector of 2 doubles {value, bound}, so
// that one packed operation does the work of the value and of its bound.
// Every function below performs the same operations in the same order for
// both, which is what makes the certificates of one pair and of W pairs
// the same.
#pragma once

#include <cmath>

#include "common/isa.hpp"
#include "common/lanes.hpp"
#include "common/sym3.hpp"
#include "overlap/overlap.hpp"

namespace pw85 {
namespace bounded {

// W pairs: the values and the bounds as two vectors.
template <class Lane>
struct Lanes {
  Lane value, bound;
};
template <class Lane>
PW85_ALWAYS_INLINE Lanes<Lane> operator+(Lanes<Lane> x, Lanes<Lane> y) noexcept {
  return {x.value + y.value, x.bound + y.bound};
}
template <class Lane>
PW85_ALWAYS_INLINE Lanes<Lane> operator-(Lanes<Lane> x, Lanes<Lane> y) noexcept {
  return {x.value - y.value, x.bound - y.bound};
}
template <class Lane>
PW85_ALWAYS_INLINE Lanes<Lane> operator*(Lanes<Lane> x, Lanes<Lane> y) noexcept {
  return {x.value * y.value, x.bound * y.bound};
}
template <class Lane>
PW85_ALWAYS_INLINE Lanes<Lane> operator*(double c, Lanes<Lane> x) noexcept {
  return {c * x.value, c * x.bound};
}
// A weight of each lane times a bounded value (value and bound alike).
template <class Lane>
PW85_ALWAYS_INLINE Lanes<Lane> operator*(Lane w, Lanes<Lane> x) noexcept {
  return {w * x.value, w * x.bound};
}
template <class Lane>
PW85_ALWAYS_INLINE Lane value(Lanes<Lane> x) noexcept { return x.value; }
template <class Lane>
PW85_ALWAYS_INLINE Lane bound(Lanes<Lane> x) noexcept { return x.bound; }
template <class Lane>
PW85_ALWAYS_INLINE Lanes<Lane> flip(Lanes<Lane> x) noexcept { return {x.value, -x.bound}; }

// One pair: value and bound in lanes 0 and 1 of one vector (the
// arithmetic operators and a double times it are the vector's own).
using Pair = lanes::VecD<2>;
PW85_ALWAYS_INLINE double value(Pair x) noexcept { return x[0]; }
PW85_ALWAYS_INLINE double bound(Pair x) noexcept { return x[1]; }
PW85_ALWAYS_INLINE Pair flip(Pair x) noexcept { return x * Pair{1.0, -1.0}; }

template <class Lane>
struct Representation {
  typedef Lanes<Lane> type;
};
template <>
struct Representation<double> {
  typedef Pair type;
};
// The bounded value of the lane type Lane.
template <class Lane>
using Bounded = typename Representation<Lane>::type;

// x as a bounded value: {x, |x|}.
template <class Lane>
PW85_ALWAYS_INLINE Bounded<Lane> pos(Lane x) noexcept {
  return Bounded<Lane>{x, lanes::vabs(x)};
}
// The error bound of x (eq. (O3)).
template <class Value>
PW85_ALWAYS_INLINE auto err(Value x) noexcept {
  return kOverlapFilterC * bound(x) + kOverlapFilterAbs;
}

// A symmetric matrix with its absolute values: p[i] = {q_i, |q_i|}, n[i] =
// flip(p[i]) = {q_i, -|q_i|} (entries in the order of Sym3).
template <class Value>
struct Sym {
  Value p[kSym], n[kSym];
};

// q (entries in the order of Sym3) with its absolute values.
template <class Lane>
PW85_ALWAYS_INLINE Sym<Bounded<Lane>> bound_sym(Lane const q[kSym]) noexcept {
  Sym<Bounded<Lane>> b;
  for (int i = 0; i < kSym; ++i) {
    b.p[i] = pos(q[i]);
    b.n[i] = flip(b.p[i]);
  }
  return b;
}

// Adjugate entries {adj00, adj01, adj02, adj11, adj12, adj22} of q (m[]),
// and det q (returned), with their bounds (eq. (O3), (O10)).
template <class Value>
PW85_ALWAYS_INLINE Value det_adj(Sym<Value> const &q, Value m[kSym]) noexcept {
  Value const *p = q.p, *n = q.n;
  m[0] = p[3] * p[5] - p[4] * n[4];
  m[1] = p[2] * p[4] - p[1] * n[5];
  m[2] = p[1] * p[4] - p[2] * n[3];
  m[3] = p[0] * p[5] - p[2] * n[2];
  m[4] = p[1] * p[2] - p[0] * n[4];
  m[5] = p[0] * p[3] - p[1] * n[1];
  return p[0] * m[0] + p[1] * m[1] + p[2] * m[2];
}

// sum_ij A_ij Y_ij for symmetric A, Y stored as Sym3 (A ordered
// {00, 01, 02, 11, 12, 22}), Y as {00, 11, 22, 01, 02, 12} when yy is the
// product of outer() below. Used for r^T Q r, r^T adj(Q) r, y^T adj(Q) y
// (eq. (O10), (O11), (O6)).
template <class Value>
PW85_ALWAYS_INLINE Value quad(Value const a[kSym], Value const yy[kSym]) noexcept {
  return a[0] * yy[0] + a[3] * yy[1] + a[5] * yy[2] +
         2.0 * (a[1] * yy[3] + a[2] * yy[4] + a[4] * yy[5]);
}

// Products {y0 y0, y1 y1, y2 y2, y0 y1, y0 y2, y1 y2} of bounded y (the
// bound of y_i is a bound of |y_i|).
template <class Value>
PW85_ALWAYS_INLINE void outer(Value const y[kDim], Value yy[kSym]) noexcept {
  yy[0] = y[0] * y[0];
  yy[1] = y[1] * y[1];
  yy[2] = y[2] * y[2];
  yy[3] = y[0] * y[1];
  yy[4] = y[0] * y[2];
  yy[5] = y[1] * y[2];
}

// tr(adj(A) B) = sum_ij adj(A)_ij B_ij (eq. (O10)).
template <class Value>
PW85_ALWAYS_INLINE Value trace_adj(Value const m[kSym], Sym<Value> const &b) noexcept {
  Value const *p = b.p;
  return m[0] * p[0] + m[3] * p[3] + m[5] * p[5] +
         2.0 * (m[1] * p[1] + m[2] * p[2] + m[4] * p[4]);
}

// Mixed adjugate M = adj(A + B) - adj(A) - adj(B), bilinear in (A, B),
// entries in the order of Sym3 (eq. (O10)).
template <class Value>
PW85_ALWAYS_INLINE void mixed_adj(Sym<Value> const &a, Sym<Value> const &b, Value m[kSym]) noexcept {
  Value const *ap = a.p, *an = a.n, *bp = b.p, *bn = b.n;
  m[0] = (ap[3] * bp[5] + bp[3] * ap[5]) - 2.0 * (ap[4] * bn[4]);
  m[1] = (ap[2] * bp[4] + bp[2] * ap[4]) - (ap[1] * bn[5] + bp[1] * an[5]);
  m[2] = (ap[1] * bp[4] + bp[1] * ap[4]) - (ap[2] * bn[3] + bp[2] * an[3]);
  m[3] = (ap[0] * bp[5] + bp[0] * ap[5]) - 2.0 * (ap[2] * bn[2]);
  m[4] = (ap[1] * bp[2] + bp[1] * ap[2]) - (ap[0] * bn[4] + bp[0] * an[4]);
  m[5] = (ap[0] * bp[3] + bp[0] * ap[3]) - 2.0 * (ap[1] * bn[1]);
}

}  // namespace bounded
}  // namespace pw85
