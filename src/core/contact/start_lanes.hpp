// The Sym3 / Vec3 algebra of sym3.hpp for W pairs at once, pair l in lane l
// of each vector (contact/default.hpp, first_step_lanes: W = 4;
// contact/default.hpp, coefficient_step_lanes: W = 8), with which start.hpp's
// start_quartics computes the quartics of DEFAULT's start (M22) for those
// pairs. Every lane performs the scalar operations of the one-pair code in
// the same order (the including files are compiled without contraction,
// src/meson.build), so its values are the same bits.
#pragma once

#include "common/isa.hpp"
#include "common/lanes.hpp"
#include "common/sym3.hpp"
#include "contact/start.hpp"

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

}  // namespace lanes
}  // namespace pw85
