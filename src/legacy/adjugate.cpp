// Determinant and adjugate quadratic form of a symmetric 3x3 matrix, the
// building blocks of the rational representation of f (pw85 documentation,
// section 4.2, eqs. (11a)-(11b)). Storage: a = {A00, A01, A02, A11, A12, A22}.
#include <cmath>

#include "legacy.hpp"

namespace pw85 {
namespace legacy {

// Cofactors of a symmetric A (adj(A) is symmetric too):
//   C00 = A11 A22 - A12^2,  C01 = A02 A12 - A01 A22,  C02 = A01 A12 - A02 A11,
//   C11 = A00 A22 - A02^2,  C12 = A01 A02 - A00 A12,  C22 = A00 A11 - A01^2.
double det_sym(Sym3 const &a) noexcept {
  double const c00 = a[3] * a[5] - a[4] * a[4];
  double const c01 = a[2] * a[4] - a[1] * a[5];
  double const c02 = a[1] * a[4] - a[2] * a[3];
  return a[0] * c00 + a[1] * c01 + a[2] * c02;
}

double det_sym_abs(Sym3 const &a) noexcept {
  double const c00 = std::fabs(a[3] * a[5]) + a[4] * a[4];
  double const c01 = std::fabs(a[2] * a[4]) + std::fabs(a[1] * a[5]);
  double const c02 = std::fabs(a[1] * a[4]) + std::fabs(a[2] * a[3]);
  return std::fabs(a[0]) * c00 + std::fabs(a[1]) * c01 + std::fabs(a[2]) * c02;
}

double xT_adjA_x(Vec3 const &x, Sym3 const &a) noexcept {
  double const c00 = a[3] * a[5] - a[4] * a[4];
  double const c01 = a[2] * a[4] - a[1] * a[5];
  double const c02 = a[1] * a[4] - a[2] * a[3];
  double const c11 = a[0] * a[5] - a[2] * a[2];
  double const c12 = a[1] * a[2] - a[0] * a[4];
  double const c22 = a[0] * a[3] - a[1] * a[1];
  return c00 * x[0] * x[0] + c11 * x[1] * x[1] + c22 * x[2] * x[2] +
         2.0 * (c01 * x[0] * x[1] + c02 * x[0] * x[2] + c12 * x[1] * x[2]);
}

double xT_adjA_x_abs(Vec3 const &x, Sym3 const &a) noexcept {
  double const c00 = std::fabs(a[3] * a[5]) + a[4] * a[4];
  double const c01 = std::fabs(a[2] * a[4]) + std::fabs(a[1] * a[5]);
  double const c02 = std::fabs(a[1] * a[4]) + std::fabs(a[2] * a[3]);
  double const c11 = std::fabs(a[0] * a[5]) + a[2] * a[2];
  double const c12 = std::fabs(a[1] * a[2]) + std::fabs(a[0] * a[4]);
  double const c22 = std::fabs(a[0] * a[3]) + a[1] * a[1];
  double const ax0 = std::fabs(x[0]), ax1 = std::fabs(x[1]), ax2 = std::fabs(x[2]);
  return c00 * ax0 * ax0 + c11 * ax1 * ax1 + c22 * ax2 * ax2 +
         2.0 * (c01 * ax0 * ax1 + c02 * ax0 * ax2 + c12 * ax1 * ax2);
}

}  // namespace legacy
}  // namespace pw85
