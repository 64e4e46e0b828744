#include "common/ellipsoid.hpp"

#include <cmath>

namespace pw85 {

Sym3 spheroid(double a, double c, Vec3 const &n) noexcept {
  double const a2 = a * a;
  double const c2_minus_a2 = c * c - a2;
  Sym3 q;
  q[0] = n[0] * n[0] * c2_minus_a2 + a2;
  q[3] = n[1] * n[1] * c2_minus_a2 + a2;
  q[5] = n[2] * n[2] * c2_minus_a2 + a2;
  q[1] = n[0] * n[1] * c2_minus_a2;
  q[2] = n[0] * n[2] * c2_minus_a2;
  q[4] = n[1] * n[2] * c2_minus_a2;
  return q;
}

Status ellipsoid(Vec3 const &radii, double const axes[9], double tol, Sym3 &q) noexcept {
  for (int k = 0; k < kDim; ++k)
    if (!(radii[k] > 0.0)) return kNotSpd;
  // Orthonormality: V V^T = I, V the matrix whose rows are the axes.
  for (int i = 0; i < kDim; ++i) {
    for (int j = i; j < kDim; ++j) {
      double const vij = axes[3 * i] * axes[3 * j] + axes[3 * i + 1] * axes[3 * j + 1] +
                         axes[3 * i + 2] * axes[3 * j + 2];
      if (!(std::fabs(vij - (i == j ? 1.0 : 0.0)) <= tol)) return kNotOrthonormal;
    }
  }
  // Q_ij = sum_k a_k^2 v_k,i v_k,j, upper triangle in row-major order.
  int idx = 0;
  for (int i = 0; i < kDim; ++i) {
    for (int j = i; j < kDim; ++j, ++idx) {
      double qij = 0.0;
      for (int k = 0; k < kDim; ++k)
        qij += radii[k] * radii[k] * axes[3 * k + i] * axes[3 * k + j];
      q[idx] = qij;
    }
  }
  // Radii so large or small that a_k^2 overflows or underflows.
  if (!all_finite(q.a, kSym)) return kInvalidArgument;
  if (!is_positive_definite(q)) return kNotSpd;
  return kOk;
}

}  // namespace pw85
