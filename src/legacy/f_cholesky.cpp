// f, f' and f'' through a Cholesky factorisation Q = L L^T of
// Q(lambda) = (1 - lambda) Q1 + lambda Q2 (pw85 documentation, section 4.1):
//   s = Q^{-1} r, u = (Q2 - Q1) s, v = Q^{-1} u,
//   f   = lambda (1 - lambda) r^T s                                   eq. (4)
//   f'  = (1 - 2 lambda) r^T s - lambda (1 - lambda) s^T u            eq. (6)
//   f'' = -2 r^T s - 2 (1 - 2 lambda) s^T u + 2 lambda (1 - lambda) u^T v  eq. (9)
#include <cfloat>
#include <cmath>

#include "legacy.hpp"

namespace pw85 {
namespace legacy {

bool f_cholesky(double lambda, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                FDerivs &out, double *rel_err) noexcept {
  Sym3 const q = interpolate(q1, q2, lambda);
  Sym3 l;
  if (!cholesky(q, l)) return false;
  Vec3 const s = cholesky_solve(l, r);
  Vec3 const u = multiply(difference(q2, q1), s);
  Vec3 const v = cholesky_solve(l, u);
  double const rs = dot(r, s);
  double const su = dot(s, u);
  double const uv = dot(u, v);
  double const w = lambda * (1.0 - lambda);
  out.f = w * rs;
  out.df = (1.0 - 2.0 * lambda) * rs - w * su;
  out.d2f = -2.0 * rs - 2.0 * (1.0 - 2.0 * lambda) * su + 2.0 * w * uv;
  if (rel_err != nullptr) {
    // The computed s solves (Q + E) s = r with |E| <~ c DBL_EPSILON |Q|, so
    // r^T s is off by about s^T E s <= c DBL_EPSILON |Q|_F |s|^2.
    double const norm_q = std::sqrt(q[0] * q[0] + q[3] * q[3] + q[5] * q[5] +
                                    2.0 * (q[1] * q[1] + q[2] * q[2] + q[4] * q[4]));
    *rel_err = 4.0 * DBL_EPSILON * norm_q * dot(s, s) / rs;
  }
  return std::isfinite(out.f) && std::isfinite(out.df) && std::isfinite(out.d2f);
}

}  // namespace legacy
}  // namespace pw85
