// Distance of closest approach through a contact-function method
// (dca.hpp): d(u) = |u| / sqrt(F(u)).
#include <algorithm>
#include <cmath>

#include "common/magnitude.hpp"
#include "contact/contact.hpp"
#include "dca/dca.hpp"
#include "common/scaling.hpp"

namespace pw85 {

Status dca_by_contact_function(Vec3 const &u, Sym3 const &q1, Sym3 const &q2, int method,
                               double &d) noexcept {
  // max |u_i| in [0.5, 1): |u| in [0.5, sqrt(3)), no overflow or underflow
  // of u^T u, and F(u) = |u|^2 / d^2 as representable as 1 / d^2.
  // Q' = 2^-2m Q with max |Q'_ij| in [1/4, 1) (exact) keeps F(v) = |v|^2 / d'^2
  // near 1 / max |Q_ij| in range; d = 2^m d' (d scales as the square root
  // of Q).
  int const e = max_exponent(u.x, kDim);
  Vec3 v;
  scale_by_power_of_two(u.x, v.x, kDim, -e);
  int eq = std::max(max_exponent(q1.a, kSym), max_exponent(q2.a, kSym));
  eq += eq & 1;
  Sym3 p1, p2;
  scale_matrices(q1, q2, -eq, p1, p2);
  MethodResult res;
  Status const s = contact_method(method, v, p1, p2, res);
  if (s == kUnknownMethod) return s;
  double const norm = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  d = std::ldexp(norm / std::sqrt(res.mu2), eq / 2);
  return s;
}

}  // namespace pw85
