// Bounds on the largest and smallest semi-axes of an ellipsoid from its
// quadratic form Q (a^2 the eigenvalues of Q): the rotation-invariant
// constants of the rate bounds (T3), (T4) of docs/contact_time.md.
#pragma once

#include <cmath>

#include "common/fp.hpp"
#include "common/sym3.hpp"

namespace pw85 {

struct AxisBounds {
  double a_max;  // >= the largest semi-axis
  double a_min;  // <= the smallest semi-axis, > 0
};

// Eigenvalues of Q by cyclic Jacobi rotations; computed eigenvalues differ
// from exact ones by at most a small multiple of u |Q|_F (Weyl), covered by
// the margin 64 u lambda_max. When that margin would swallow lambda_min
// (cond(Q) > ~1e14), lambda_min >= 1 / trace(Q^{-1}) = 1 / |L^{-1}|_F^2
// (L L^T = Q) is used instead, with a relative margin 1e-6.
inline AxisBounds axis_bounds(Sym3 const &q) noexcept {
  double a[3][3] = {{q[0], q[1], q[2]}, {q[1], q[3], q[4]}, {q[2], q[4], q[5]}};
  for (int sweep = 0; sweep < 12; ++sweep) {
    double const off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    double const diag = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
    if (!(off > 1e-40 * diag)) break;
    for (int p = 0; p < 2; ++p)
      for (int r = p + 1; r < 3; ++r) {
        if (a[p][r] == 0.0) continue;
        // Rotation annihilating a[p][r] (Golub & Van Loan, Algorithm 8.5.1).
        double const theta = (a[r][r] - a[p][p]) / (2.0 * a[p][r]);
        double const tn = (theta >= 0 ? 1.0 : -1.0) / (std::fabs(theta) + std::sqrt(theta * theta + 1.0));
        double const c = 1.0 / std::sqrt(tn * tn + 1.0), s = tn * c;
        for (int k = 0; k < 3; ++k) {  // columns p, r
          double const akp = a[k][p], akr = a[k][r];
          a[k][p] = c * akp - s * akr;
          a[k][r] = s * akp + c * akr;
        }
        for (int k = 0; k < 3; ++k) {  // rows p, r
          double const apk = a[p][k], ark = a[r][k];
          a[p][k] = c * apk - s * ark;
          a[r][k] = s * apk + c * ark;
        }
      }
  }
  double const lmax = std::fmax(a[0][0], std::fmax(a[1][1], a[2][2]));
  double const lmin = std::fmin(a[0][0], std::fmin(a[1][1], a[2][2]));
  double const hi = lmax * (1.0 + 256 * kU);
  double lo = lmin - 64 * kU * lmax;
  if (!(lo > 0.5 * lmin)) {
    CholInv c;
    double alt = 0.0;
    if (chol_inv(q, c)) {
      // L^{-1} column by column: trace(Q^{-1}) = sum of squares.
      double tr = 0.0;
      for (int j = 0; j < 3; ++j) {
        Vec3 e{{0.0, 0.0, 0.0}};
        e[j] = 1.0;
        Vec3 const x = chol_solve(c, e);
        tr += x[j];  // (Q^{-1})_jj
      }
      alt = (1.0 - 1e-6) / tr;
    }
    lo = std::fmax(lo, std::fmin(alt, lmin));
  }
  if (!(lo > 0.0)) lo = 0.0;
  return AxisBounds{std::sqrt(hi), std::sqrt(lo)};
}

// Upper bound on ||[W, Q]||_F, W = [w]x: dQ(t)/dt = [W, Q(t)] and
// ||[W, Q(t)]|| = ||[W, Q]|| (R commutes with W), so it bounds the rate of
// change of Q(t) whatever |w|: 0 for a spin about an axis of symmetry
// (T3'). The entries are formed in double; each is a sum of 4 products
// bounded by |w|_inf |Q|_max, whence the margin.
inline double commutator_norm(Sym3 const &q, Vec3 const &w) noexcept {
  double const m[3][3] = {{q[0], q[1], q[2]}, {q[1], q[3], q[4]}, {q[2], q[4], q[5]}};
  double const wm[3][3] = {{0.0, -w[2], w[1]}, {w[2], 0.0, -w[0]}, {-w[1], w[0], 0.0}};
  double sum = 0.0, qmax = 0.0, wmax = 0.0;
  for (int i = 0; i < 3; ++i) {
    wmax = std::fmax(wmax, std::fabs(w[i]));
    for (int j = 0; j < 3; ++j) {
      qmax = std::fmax(qmax, std::fabs(m[i][j]));
      double c = 0.0;
      for (int k = 0; k < 3; ++k) c += wm[i][k] * m[k][j] - m[i][k] * wm[k][j];
      sum += c * c;
    }
  }
  return std::sqrt(sum) * (1.0 + 8 * kU) + 3.0 * 16 * kU * wmax * qmax;
}

}  // namespace pw85
