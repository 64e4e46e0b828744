// Symmetric 2x2 algebra for the two-dimensional problems (ellipses): a
// symmetric matrix is three doubles, the upper triangle in row-major order
// {A00, A01, A11}, the 2D analogue of the Sym3 storage of sym3.hpp. Inline,
// allocation-free, noexcept.
#pragma once

#include <cmath>

namespace pw85 {

struct Vec2 {
  double x[2];
  constexpr double operator[](int i) const noexcept { return x[i]; }
  constexpr double &operator[](int i) noexcept { return x[i]; }
};

struct Sym2 {
  double a[3];
  constexpr double operator[](int i) const noexcept { return a[i]; }
  constexpr double &operator[](int i) noexcept { return a[i]; }
};

inline Vec2 load_vec2(double const *p) noexcept { return Vec2{{p[0], p[1]}}; }
inline Sym2 load_sym2(double const *p) noexcept { return Sym2{{p[0], p[1], p[2]}}; }

// a d - b c with one rounding error at most a few ulps of the result
// (Kahan's fma-based algorithm): the determinant of an ill-conditioned 2x2
// matrix is then as accurate as its entries allow.
inline double diff_of_products(double a, double d, double b, double c) noexcept {
  double const w = b * c;
  double const e = std::fma(-b, c, w);  // w - b c, exactly
  double const f = std::fma(a, d, -w);
  return f + e;
}

inline double det(Sym2 const &a) noexcept { return diff_of_products(a[0], a[2], a[1], a[1]); }

// Positive definite: A00 > 0 and det A > 0 (Sylvester), the determinant
// computed as above. NaN entries give false.
inline bool is_positive_definite(Sym2 const &a) noexcept {
  return a[0] > 0.0 && a[2] > 0.0 && det(a) > 0.0;
}

// Eigen-decomposition A = big v v^T + small w w^T, v = (cos t, sin t),
// w = (-sin t, cos t). The larger eigenvalue comes from the trace and the
// discriminant (no cancellation for A positive definite); the smaller one as
// det / big, so that it keeps its relative accuracy when A is ill-conditioned.
// For a multiple of the identity t = atan2(0, 0) = 0: no equality test.
struct Eigen2 {
  double big, small;  // eigenvalues, big >= small
  double c, s;        // cos t, sin t
};

inline Eigen2 eigen(Sym2 const &a) noexcept {
  Eigen2 e;
  double const half_diff = 0.5 * (a[0] - a[2]);
  double const radius = std::hypot(half_diff, a[1]);
  e.big = 0.5 * (a[0] + a[2]) + radius;
  e.small = det(a) / e.big;
  double const t = 0.5 * std::atan2(a[1], half_diff);
  e.c = std::cos(t);
  e.s = std::sin(t);
  return e;
}

// y = A x.
inline Vec2 multiply(Sym2 const &a, Vec2 const &x) noexcept {
  return Vec2{{a[0] * x[0] + a[1] * x[1], a[1] * x[0] + a[2] * x[1]}};
}

inline double dot(Vec2 const &u, Vec2 const &v) noexcept { return u[0] * v[0] + u[1] * v[1]; }

// Solves A x = b through the Cholesky factor of A, whose second pivot
// det(A) / A00 is taken from the accurate determinant. Returns false when A
// is not numerically positive definite.
inline bool solve(Sym2 const &a, Vec2 const &b, Vec2 &x) noexcept {
  double const d = det(a);
  if (!(a[0] > 0.0) || !(d > 0.0)) return false;
  double const l00 = std::sqrt(a[0]);
  double const l10 = a[1] / l00;
  double const l11 = std::sqrt(d / a[0]);
  double const y0 = b[0] / l00;
  double const y1 = (b[1] - l10 * y0) / l11;
  x[1] = y1 / l11;
  x[0] = (y0 - l10 * x[1]) / l00;
  return std::isfinite(x[0]) && std::isfinite(x[1]);
}

}  // namespace pw85
