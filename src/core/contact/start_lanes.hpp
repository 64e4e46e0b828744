// The Sym3 / Vec3 algebra of sym3.hpp and the quartics of DEFAULT's start
// (M22) (start.hpp) for W pairs at once, pair l in lane l of each vector
// (contact/default_lanes.cpp: W = 4; contact/rational_lanes.cpp: W = 8).
// Every lane performs the scalar operations of the one-pair code in the
// same order (the including files are compiled without contraction,
// src/meson.build), so its values are the same bits.
#pragma once

#include "common/isa.hpp"
#include "common/lanes.hpp"
#include "common/sym3.hpp"

namespace pw85 {
namespace lanes {

template <int W>
struct SymL {
  VecD<W> a[kSym];
  PW85_ALWAYS_INLINE VecD<W> &operator[](int i) noexcept { return a[i]; }
  PW85_ALWAYS_INLINE VecD<W> const &operator[](int i) const noexcept { return a[i]; }
};
template <int W>
struct Vec3L {
  VecD<W> x[kDim];
  PW85_ALWAYS_INLINE VecD<W> &operator[](int i) noexcept { return x[i]; }
  PW85_ALWAYS_INLINE VecD<W> const &operator[](int i) const noexcept { return x[i]; }
};

// sym3.hpp: dot, multiply, adjugate3, det_with_adjugate, interpolate.
template <int W>
PW85_ALWAYS_INLINE VecD<W> dot(Vec3L<W> const &u, Vec3L<W> const &v) noexcept {
  return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
}
template <int W>
PW85_ALWAYS_INLINE Vec3L<W> multiply(SymL<W> const &a, Vec3L<W> const &x) noexcept {
  return Vec3L<W>{{a[0] * x[0] + a[1] * x[1] + a[2] * x[2],
                   a[1] * x[0] + a[3] * x[1] + a[4] * x[2],
                   a[2] * x[0] + a[4] * x[1] + a[5] * x[2]}};
}
template <int W>
PW85_ALWAYS_INLINE SymL<W> adjugate3(SymL<W> const &q) noexcept {
  return SymL<W>{{q[3] * q[5] - q[4] * q[4], q[2] * q[4] - q[1] * q[5], q[1] * q[4] - q[2] * q[3],
                  q[0] * q[5] - q[2] * q[2], q[1] * q[2] - q[0] * q[4], q[0] * q[3] - q[1] * q[1]}};
}
template <int W>
PW85_ALWAYS_INLINE VecD<W> det_with_adjugate(SymL<W> const &q, SymL<W> const &c) noexcept {
  return q[0] * c[0] + q[1] * c[1] + q[2] * c[2];
}
template <int W>
PW85_ALWAYS_INLINE SymL<W> interpolate(SymL<W> const &q1, SymL<W> const &q2,
                                       VecD<W> lambda) noexcept {
  SymL<W> q;
  VecD<W> const one_minus = 1.0 - lambda;
  for (int i = 0; i < kSym; ++i) q[i] = one_minus * q1[i] + lambda * q2[i];
  return q;
}

// start.hpp: detail::support_squares, detail::tree_times, newton_start.
template <int W>
PW85_ALWAYS_INLINE void support_squares(Vec3L<W> const &n, SymL<W> const &q1,
                                        SymL<W> const &q2, VecD<W> &a1, VecD<W> &a2) noexcept {
  VecD<W> const n00 = n[0] * n[0], n11 = n[1] * n[1], n22 = n[2] * n[2];
  VecD<W> const n01 = 2.0 * n[0] * n[1], n02 = 2.0 * n[0] * n[2], n12 = 2.0 * n[1] * n[2];
  a1 = (q1[0] * n00 + q1[3] * n11) + (q1[5] * n22 + q1[1] * n01) + (q1[2] * n02 + q1[4] * n12);
  a2 = (q2[0] * n00 + q2[3] * n11) + (q2[5] * n22 + q2[1] * n01) + (q2[2] * n02 + q2[4] * n12);
}

template <int W>
PW85_ALWAYS_INLINE Vec3L<W> tree_times(SymL<W> const &c, Vec3L<W> const &r) noexcept {
  return Vec3L<W>{{c[0] * r[0] + (c[1] * r[1] + c[2] * r[2]),
                   c[1] * r[0] + (c[3] * r[1] + c[4] * r[2]),
                   c[2] * r[0] + (c[4] * r[1] + c[5] * r[2])}};
}

template <int W>
PW85_ALWAYS_INLINE VecD<W> newton_start(Vec3L<W> const &r, SymL<W> const &q1,
                                        SymL<W> const &q2) noexcept {
  VecD<W> const h1 = vsqrt(dot(r, multiply(q1, r)));
  VecD<W> const h2 = vsqrt(dot(r, multiply(q2, r)));
  VecD<W> const l0 = h1 / (h1 + h2);
  return select((l0 > 0.0) & (l0 < 1.0), l0, VecD<W>{} + 0.5);
}

// start.hpp: StartQuartics and start_quartics<kScaled>.
template <int W>
struct StartQuarticsL {
  VecD<W> a1[5], a2[5];
  VecD<W> x0;
};

template <bool kScaled, int W>
PW85_ALWAYS_INLINE void start_quartics(Vec3L<W> const &r, SymL<W> const &q1, SymL<W> const &q2,
                                       StartQuarticsL<W> &sq) noexcept {
  typedef VecD<W> V;
  SymL<W> q12;
  for (int i = 0; i < kSym; ++i) q12[i] = q1[i] + q2[i];
  SymL<W> const c1 = adjugate3(q1), c2 = adjugate3(q2);
  Vec3L<W> const n12 = tree_times(adjugate3(q12), r);
  Vec3L<W> const n1 = tree_times(c1, r), n2 = tree_times(c2, r);
  Vec3L<W> m;
  for (int i = 0; i < kDim; ++i) m[i] = n12[i] - (n1[i] + n2[i]);
  V sc = V{} + 1.0;
  sq.x0 = V{};
  if constexpr (kScaled) {
    V s1, s2;
    support_squares(n12, q1, q2, s1, s2);
    sq.x0 = vsqrt(s1 / s2);
    sc = 1.0 / (s1 + s2);
  }
  V const det1 = det_with_adjugate(q1, c1) * sc;
  V const det2 = det_with_adjugate(q2, c2) * sc;
  V const t1 = ((c1[0] * q2[0] + c1[3] * q2[3]) + c1[5] * q2[5] +
                2.0 * ((c1[1] * q2[1] + c1[2] * q2[2]) + c1[4] * q2[4])) * sc;
  V const t2 = ((q1[0] * c2[0] + q1[3] * c2[3]) + q1[5] * c2[5] +
                2.0 * ((q1[1] * c2[1] + q1[2] * c2[2]) + q1[4] * c2[4])) * sc;
  V const rn1 = dot(r, n1), rm = dot(r, m), rn2 = dot(r, n2);
  Vec3L<W> const p = multiply(q2, n1), q = multiply(q1, n2);
  V const mp = dot(m, p) * sc, mq = dot(m, q) * sc;
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

}  // namespace lanes
}  // namespace pw85
