#include "common/ellipsoid.hpp"

#include <cmath>

#include "common/fp.hpp"
#include "common/magnitude.hpp"
#include "common/scaling.hpp"

namespace pw85 {

Sym3 spheroid(double a, double c, Vec3 const &n_in) noexcept {
  // Q = a^2 (I - m m^T) + c^2 m m^T with m = n / |n| (section 3.1, eq. (2)
  // for the semi-axes a, a, c), written with w_i = n_i^2 / |n|^2 and the
  // diagonal of I - m m^T as (n_j^2 + n_k^2) / |n|^2: every entry is a sum
  // of terms of one sign except the off-diagonal (c^2 - a^2) m_i m_j, so
  // each entry is within a few roundings of its magnitude terms
  // a^2 |P_ij| + c^2 |N_ij| at any aspect c / a.
  // n scaled by 2^-en (exact) so that its squares neither overflow nor
  // underflow.
  int const en = max_exponent(n_in.x, kDim);
  Vec3 n;
  scale_by_power_of_two(n_in.x, n.x, kDim, -en);
  double const a2 = a * a, c2 = c * c;
  double const s0 = n[0] * n[0], s1 = n[1] * n[1], s2 = n[2] * n[2];
  double const inv = 1.0 / (s0 + s1 + s2);
  double const d = (c - a) * (c + a) * inv;  // (c^2 - a^2) / |n|^2
  Sym3 q;
  q[0] = (a2 * (s1 + s2) + c2 * s0) * inv;
  q[3] = (a2 * (s0 + s2) + c2 * s1) * inv;
  q[5] = (a2 * (s0 + s1) + c2 * s2) * inv;
  q[1] = d * (n[0] * n[1]);
  q[2] = d * (n[0] * n[2]);
  q[4] = d * (n[1] * n[2]);
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
  // Radii so large or small that a_k^2 leaves [DBL_MIN, DBL_MAX]: Q is not
  // representable to the precision of double (kRange, status.hpp).
  for (int k = 0; k < kDim; ++k) {
    double const a2 = radii[k] * radii[k];
    if (!(a2 >= kMinNormal && a2 <= kMaxDouble)) return kRange;
  }
  if (!all_finite(q.a, kSym)) return kRange;
  if (!is_positive_definite(q)) return kNotSpd;
  return kOk;
}

}  // namespace pw85
