// Contact geometry (docs/contact_geometry.md, eqs. (G1)-(G7)).
//
// From the maximiser lambda of f (pw85 documentation, chapter 3, eqs. (9a),
// (11), (13)-(14)): with Q = (1 - lambda) Q1 + lambda Q2 and s = Q^{-1} r,
//   x0 = (1 - lambda) Q1 s                     (G1, contact point - c1)
//   n  = s / |s|                               (G2, normal, since the
//        gradient of x^T Q1^{-1} x at x0 is 2 (1 - lambda) s)
//   dca = |r| / mu                             (G4)
//   depth = dca - |r| = |r| (1 - mu^2) / (mu (1 + mu))   (G5)
//   depth_n = depth (r/|r|) . n                (G6)
#include <cmath>

#include "contact.hpp"
#include "contact_geometry.hpp"
#include "f_cholesky.hpp"

namespace pw85 {

Status contact_geometry(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                        ContactGeometry &g) noexcept {
  // PW85_METHOD_DEFAULT (src/core/default.cpp, docs/methods.md).
  MethodResult res;
  Status status = contact_method(kMethodDefault, r, q1, q2, res);
  double lambda = res.lambda;
  if (!(lambda >= 0.0 && lambda <= 1.0)) return kNoConvergence;
  Sym3 l;
  if (!cholesky(interpolate(q1, q2, lambda), l)) return kNoConvergence;
  Vec3 const s = cholesky_solve(l, r);
  double const nu = 1.0 - lambda;
  Vec3 const q1s = multiply(q1, s);
  double const mu2 = res.mu2;  // the method's value (accurate to its documented tolerance)
  double const ns = std::sqrt(dot(s, s));
  double const nr = std::sqrt(dot(r, r));
  g.mu2 = mu2;
  g.lambda = lambda;
  for (int i = 0; i < kDim; ++i) {
    g.x0[i] = nu * q1s[i];
    g.n[i] = s[i] / ns;
  }
  double const mu = std::sqrt(mu2);
  g.dca = nr / mu;
  // dca - |r| without cancellation near tangency: |r| (1 - mu^2) / (mu (1 + mu)).
  g.depth = nr * ((1.0 - mu2) / (mu * (1.0 + mu)));
  g.depth_n = g.depth * (dot(r, s) / (nr * ns));
  return status;
}

}  // namespace pw85
