// Rigid motion of the pair (docs/contact_time.md (T1)): centre offset
// r12(t) = r12 + t v12 and quadratic forms Q(t) = R(t) Q R(t)^T with
// R(t) = exp(t [w]x) = I + sin(th) K + (1 - cos(th)) K^2 (Rodrigues),
// th = t |w|, K = [w / |w|]x.
#pragma once

#include <cmath>

#include "arith/dd.hpp"
#include "common/sym3.hpp"

namespace pw85 {

inline Vec3 cross(Vec3 const &a, Vec3 const &b) noexcept {
  return Vec3{{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}};
}

// |a|, without overflow or underflow of the squares for any finite a.
inline double norm(Vec3 const &a) noexcept {
  double const m = std::fmax(std::fabs(a[0]), std::fmax(std::fabs(a[1]), std::fabs(a[2])));
  if (m > 0x1p-500 && m < 0x1p500) return std::sqrt(dot(a, a));
  if (!(m > 0.0) || !std::isfinite(m)) return m;
  Vec3 const b{{a[0] / m, a[1] / m, a[2] / m}};
  return m * std::sqrt(dot(b, b));
}

// r12 + t v12 in double-double, rounded once: relative error u per
// component, however much r12 and t v12 cancel.
inline Vec3 position(Vec3 const &r, Vec3 const &v, double t) noexcept {
  Vec3 p;
  for (int i = 0; i < kDim; ++i) p[i] = dd::to_double(dd::add(dd::two_prod<false>(t, v[i]), r[i]));
  return p;
}

// R(t) Q R(t)^T; Q itself when w = 0 or t = 0.
inline Sym3 rotated(Sym3 const &q, Vec3 const &w, double t) noexcept {
  double const wn = norm(w);
  if (wn == 0.0 || t == 0.0) return q;
  double const k[3] = {w[0] / wn, w[1] / wn, w[2] / wn};
  double const th = t * wn;
  double const s = std::sin(th), c1 = 1.0 - std::cos(th);
  // R = I + s K + c1 K^2, K^2 = k k^T - I.
  double rm[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) rm[i][j] = (i == j ? 1.0 - c1 : 0.0) + c1 * k[i] * k[j];
  rm[0][1] -= s * k[2]; rm[1][0] += s * k[2];
  rm[0][2] += s * k[1]; rm[2][0] -= s * k[1];
  rm[1][2] -= s * k[0]; rm[2][1] += s * k[0];
  double const qf[3][3] = {{q[0], q[1], q[2]}, {q[1], q[3], q[4]}, {q[2], q[4], q[5]}};
  double m[3][3];  // R Q
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m[i][j] = rm[i][0] * qf[0][j] + rm[i][1] * qf[1][j] + rm[i][2] * qf[2][j];
  auto e = [&](int i, int j) { return m[i][0] * rm[j][0] + m[i][1] * rm[j][1] + m[i][2] * rm[j][2]; };
  return Sym3{{e(0, 0), e(0, 1), e(0, 2), e(1, 1), e(1, 2), e(2, 2)}};
}

}  // namespace pw85
