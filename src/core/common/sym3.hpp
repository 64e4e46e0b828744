// Symmetric 3x3 algebra on the pw85 storage: a symmetric matrix is six
// doubles, the upper triangle in row-major order {A00, A01, A02, A11, A12, A22}
// (pw85 1.0 documentation, section 3.1, eq. (3)). Everything is inline,
// allocation-free and noexcept: these are the building blocks of every method.
#pragma once

#include <cmath>

namespace pw85 {

constexpr int kDim = 3;
constexpr int kSym = 6;

struct Vec3 {
  double x[kDim];
  constexpr double operator[](int i) const noexcept { return x[i]; }
  constexpr double &operator[](int i) noexcept { return x[i]; }
};

struct Sym3 {
  double a[kSym];
  constexpr double operator[](int i) const noexcept { return a[i]; }
  constexpr double &operator[](int i) noexcept { return a[i]; }
};

inline Vec3 load_vec3(double const *p) noexcept { return Vec3{{p[0], p[1], p[2]}}; }

inline Sym3 load_sym3(double const *p) noexcept {
  return Sym3{{p[0], p[1], p[2], p[3], p[4], p[5]}};
}

// The caller's arrays seen as Vec3 / Sym3, without a copy: the struct is
// exactly its array (checked below) and every access reads a double. For
// the hot path of pw85_contact_function_method (contact_method_entry): a
// copy on the stack is read back by the AVX-512 code of DEFAULT with wide
// loads that span several of the copy's stores, which cannot be forwarded
// and wait for them.
static_assert(sizeof(Vec3) == kDim * sizeof(double) && alignof(Vec3) == alignof(double),
              "Vec3 must be exactly double[3]");
static_assert(sizeof(Sym3) == kSym * sizeof(double) && alignof(Sym3) == alignof(double),
              "Sym3 must be exactly double[6]");
inline Vec3 const &view_vec3(double const *p) noexcept {
  return *reinterpret_cast<Vec3 const *>(p);
}
inline Sym3 const &view_sym3(double const *p) noexcept {
  return *reinterpret_cast<Sym3 const *>(p);
}

inline double dot(Vec3 const &u, Vec3 const &v) noexcept {
  return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
}

// (1 - lambda) q1 + lambda q2, eq. (10) of the pw85 theory chapter; the
// same expression, in the same order, as pw85 1.0 so results match bitwise.
inline Sym3 interpolate(Sym3 const &q1, Sym3 const &q2, double lambda) noexcept {
  Sym3 q;
  double const one_minus = 1.0 - lambda;
  for (int i = 0; i < kSym; ++i) q[i] = one_minus * q1[i] + lambda * q2[i];
  return q;
}

inline Sym3 difference(Sym3 const &q2, Sym3 const &q1) noexcept {
  Sym3 d;
  for (int i = 0; i < kSym; ++i) d[i] = q2[i] - q1[i];
  return d;
}

// y = A x.
inline Vec3 multiply(Sym3 const &a, Vec3 const &x) noexcept {
  return Vec3{{a[0] * x[0] + a[1] * x[1] + a[2] * x[2],
               a[1] * x[0] + a[3] * x[1] + a[4] * x[2],
               a[2] * x[0] + a[4] * x[1] + a[5] * x[2]}};
}

// Cholesky factor A = L L^T, L lower triangular stored as
// {L00, L10, L20, L11, L21, L22}. Returns false, with L undefined, when a
// pivot is not strictly positive (A not positive definite, or NaN).
inline bool cholesky(Sym3 const &a, Sym3 &l) noexcept {
  double const p0 = a[0];
  if (!(p0 > 0.0)) return false;
  l[0] = std::sqrt(p0);
  l[1] = a[1] / l[0];
  l[2] = a[2] / l[0];
  double const p1 = a[3] - l[1] * l[1];
  if (!(p1 > 0.0)) return false;
  l[3] = std::sqrt(p1);
  l[4] = (a[4] - l[1] * l[2]) / l[3];
  double const p2 = a[5] - l[2] * l[2] - l[4] * l[4];
  if (!(p2 > 0.0)) return false;
  l[5] = std::sqrt(p2);
  return std::isfinite(l[1]) && std::isfinite(l[2]) && std::isfinite(l[4]) &&
         std::isfinite(l[5]);
}

// Solves L L^T x = b: forward substitution L y = b, backward L^T x = y.
inline Vec3 cholesky_solve(Sym3 const &l, Vec3 const &b) noexcept {
  double const y0 = b[0] / l[0];
  double const y1 = (b[1] - l[1] * y0) / l[3];
  double const y2 = (b[2] - l[2] * y0 - l[4] * y1) / l[5];
  Vec3 x;
  x[2] = y2 / l[5];
  x[1] = (y1 - l[4] * x[2]) / l[3];
  x[0] = (y0 - l[1] * x[1] - l[2] * x[2]) / l[0];
  return x;
}

// Cholesky factor with the reciprocals of its diagonal, for callers that
// solve several right-hand sides with one factor (multiplications instead
// of divisions).
struct CholInv {
  Sym3 l;
  double i0, i1, i2;
};

inline bool chol_inv(Sym3 const &a, CholInv &c) noexcept {
  if (!cholesky(a, c.l)) return false;
  c.i0 = 1.0 / c.l[0];
  c.i1 = 1.0 / c.l[3];
  c.i2 = 1.0 / c.l[5];
  return true;
}

inline Vec3 chol_solve(CholInv const &c, Vec3 const &b) noexcept {
  Sym3 const &l = c.l;
  double const y0 = b[0] * c.i0;
  double const y1 = (b[1] - l[1] * y0) * c.i1;
  double const y2 = (b[2] - l[2] * y0 - l[4] * y1) * c.i2;
  Vec3 x;
  x[2] = y2 * c.i2;
  x[1] = (y1 - l[4] * x[2]) * c.i1;
  x[0] = (y0 - l[1] * x[1] - l[2] * x[2]) * c.i0;
  return x;
}

// A^{-1} = L^{-T} L^{-1} from the factor of chol_inv: M = L^{-1} by forward
// substitution, then the upper triangle of M^T M.
inline Sym3 chol_inverse(CholInv const &c) noexcept {
  Sym3 const &l = c.l;
  double const m00 = c.i0, m11 = c.i1, m22 = c.i2;
  double const m10 = -l[1] * m00 * m11;
  double const m21 = -l[4] * m11 * m22;
  double const m20 = -(l[2] * m00 + l[4] * m10) * m22;
  return Sym3{{m00 * m00 + m10 * m10 + m20 * m20, m10 * m11 + m20 * m21, m20 * m22,
               m11 * m11 + m21 * m21, m21 * m22, m22 * m22}};
}

// Adjugate (matrix of cofactors) of a symmetric matrix: adj(Q) Q = det(Q) I.
inline Sym3 adjugate3(Sym3 const &q) noexcept {
  return Sym3{{q[3] * q[5] - q[4] * q[4], q[2] * q[4] - q[1] * q[5], q[1] * q[4] - q[2] * q[3],
               q[0] * q[5] - q[2] * q[2], q[1] * q[2] - q[0] * q[4], q[0] * q[3] - q[1] * q[1]}};
}

// det(Q) from Q and c = adj(Q): the first row of Q adj(Q) = det(Q) I.
inline double det_with_adjugate(Sym3 const &q, Sym3 const &c) noexcept {
  return q[0] * c[0] + q[1] * c[1] + q[2] * c[2];
}

inline bool all_finite(double const *p, int n) noexcept {
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(p[i])) return false;
  return true;
}

}  // namespace pw85
