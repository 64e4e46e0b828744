// f and its first three derivatives in double through the adjugate of
// Q(lambda): Q^{-1} = adj(Q) / det(Q) (docs/methods.md, eq. (M16)). Shorter
// dependency chains than LDL^T (one division instead of three in sequence),
// hence faster; not backward stable, so it is used only where the error of
// s = Q^{-1} r enters the result to second order (the stationary form of
// f_dd.hpp) and with the componentwise error bound of adj_error().
#pragma once

#include <cmath>

#include "f_derivatives.hpp"
#include "sym3.hpp"

namespace pw85 {

struct AdjEval {
  double lambda;
  double phi, dphi;
  double f, df, d2f, d3f;
  double det;
  Sym3 q, adj;
  Vec3 s;
};

inline Sym3 adjugate3(Sym3 const &q) noexcept {
  return Sym3{{q[3] * q[5] - q[4] * q[4], q[2] * q[4] - q[1] * q[5], q[1] * q[4] - q[2] * q[3],
               q[0] * q[5] - q[2] * q[2], q[1] * q[2] - q[0] * q[4], q[0] * q[3] - q[1] * q[1]}};
}

inline bool f_eval_adj(double lambda, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                       Sym3 const &d, AdjEval &e) noexcept {
  e.lambda = lambda;
  e.q = interpolate(q1, q2, lambda);
  Sym3 const &q = e.q;
  e.adj = adjugate3(q);
  Sym3 const &c = e.adj;
  e.det = q[0] * c[0] + q[1] * c[1] + q[2] * c[2];
  if (!(e.det > 0.0)) return false;
  double const id = 1.0 / e.det;
  Vec3 const cr = multiply(c, r);
  Vec3 const s{{cr[0] * id, cr[1] * id, cr[2] * id}};
  e.s = s;
  Vec3 const u = multiply(d, s);
  Vec3 const cu = multiply(c, u);
  Vec3 const v{{cu[0] * id, cu[1] * id, cu[2] * id}};
  Vec3 const w = multiply(d, v);
  set_f_derivatives(lambda, r, s, u, v, w, e);
  return e.phi > 0.0 && std::isfinite(e.f) && std::isfinite(e.df) && std::isfinite(e.d2f) &&
         std::isfinite(e.d3f);
}

// Componentwise bound (first order in u) on the error of the computed s
// (eq. (M17)): rounding of Q(lambda) (u |Q|), of the adjugate (2u per
// entry, relative to the sum of the absolute values of its two products), of
// det and of the products adj r / det.
inline Vec3 adj_error(AdjEval const &e, Vec3 const &r, Sym3 const &q1,
                      Sym3 const &q2) noexcept {
  constexpr double u = 0x1p-53;
  Sym3 const &q = e.q;
  Sym3 qa;
  double const lm = 1.0 - e.lambda;
  for (int i = 0; i < kSym; ++i) qa[i] = lm * std::fabs(q1[i]) + e.lambda * std::fabs(q2[i]);
  // Sums of absolute values of the products of each adjugate entry.
  Sym3 const aa{{qa[3] * qa[5] + qa[4] * qa[4], qa[2] * qa[4] + qa[1] * qa[5],
                 qa[1] * qa[4] + qa[2] * qa[3], qa[0] * qa[5] + qa[2] * qa[2],
                 qa[1] * qa[2] + qa[0] * qa[4], qa[0] * qa[3] + qa[1] * qa[1]}};
  double const det_abs = qa[0] * aa[0] + qa[1] * aa[1] + qa[2] * aa[2];
  double const rel_det = 4.0 * u * det_abs / e.det;
  Vec3 const ar{{std::fabs(r[0]), std::fabs(r[1]), std::fabs(r[2])}};
  Vec3 const t = multiply(aa, ar);
  double const k = 4.0 * u / e.det;
  Vec3 err;
  for (int i = 0; i < kDim; ++i) err[i] = k * t[i] + rel_det * std::fabs(e.s[i]);
  (void)q;
  return err;
}

}  // namespace pw85
