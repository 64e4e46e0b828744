// Symmetric 3x3 algebra on bounded values (docs/overlap.md, eq. (O3)), shared
// by the one-pair filters (overlap.cpp, T = one SSE2 register {fl(E), fl(P)})
// and the filters across pairs (overlap_lanes.cpp, T = a pair of vectors, one
// pair per lane). T needs +, -, * on T and double * T, each acting on the
// value and on its bound alike, and flip(T) = {value, -bound}, so that a
// subtracted term adds its bound; every function performs the same
// operations in the same order for both, which is what makes the two
// callers' certificates the same.
#pragma once

#include "common/isa.hpp"
#include "common/sym3.hpp"

namespace pw85 {
namespace bounded {

// A symmetric matrix with its absolute values: p[i] = {q_i, |q_i|}, n[i] =
// flip(p[i]) = {q_i, -|q_i|} (entries in the order of Sym3).
template <class T>
struct Sym {
  T p[kSym], n[kSym];
};

// Adjugate entries {adj00, adj01, adj02, adj11, adj12, adj22} of q (m[]),
// and det q (returned), with their bounds (eq. (O3), (O10)).
template <class T>
PW85_ALWAYS_INLINE T det_adj(Sym<T> const &q, T m[kSym]) noexcept {
  T const *p = q.p, *n = q.n;
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
template <class T>
PW85_ALWAYS_INLINE T quad(T const a[kSym], T const yy[kSym]) noexcept {
  return a[0] * yy[0] + a[3] * yy[1] + a[5] * yy[2] +
         2.0 * (a[1] * yy[3] + a[2] * yy[4] + a[4] * yy[5]);
}

// Products {y0 y0, y1 y1, y2 y2, y0 y1, y0 y2, y1 y2} of bounded y (the
// bound of y_i is a bound of |y_i|).
template <class T>
PW85_ALWAYS_INLINE void outer(T const y[kDim], T yy[kSym]) noexcept {
  yy[0] = y[0] * y[0];
  yy[1] = y[1] * y[1];
  yy[2] = y[2] * y[2];
  yy[3] = y[0] * y[1];
  yy[4] = y[0] * y[2];
  yy[5] = y[1] * y[2];
}

// tr(adj(A) B) = sum_ij adj(A)_ij B_ij (eq. (O10)).
template <class T>
PW85_ALWAYS_INLINE T trace_adj(T const m[kSym], Sym<T> const &b) noexcept {
  T const *p = b.p;
  return m[0] * p[0] + m[3] * p[3] + m[5] * p[5] +
         2.0 * (m[1] * p[1] + m[2] * p[2] + m[4] * p[4]);
}

// Mixed adjugate M = adj(A + B) - adj(A) - adj(B), bilinear in (A, B),
// entries in the order of Sym3 (eq. (O10)).
template <class T>
PW85_ALWAYS_INLINE void mixed_adj(Sym<T> const &a, Sym<T> const &b, T m[kSym]) noexcept {
  T const *ap = a.p, *an = a.n, *bp = b.p, *bn = b.n;
  m[0] = (ap[3] * bp[5] + bp[3] * ap[5]) - 2.0 * (ap[4] * bn[4]);
  m[1] = (ap[2] * bp[4] + bp[2] * ap[4]) - (ap[1] * bn[5] + bp[1] * an[5]);
  m[2] = (ap[1] * bp[4] + bp[1] * ap[4]) - (ap[2] * bn[3] + bp[2] * an[3]);
  m[3] = (ap[0] * bp[5] + bp[0] * ap[5]) - 2.0 * (ap[2] * bn[2]);
  m[4] = (ap[1] * bp[2] + bp[1] * ap[2]) - (ap[0] * bn[4] + bp[0] * an[4]);
  m[5] = (ap[0] * bp[3] + bp[0] * ap[3]) - 2.0 * (ap[1] * bn[1]);
}

}  // namespace bounded
}  // namespace pw85
