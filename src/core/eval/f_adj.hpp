// f and its first four derivatives in double through the adjugate of
// Q(lambda): Q^{-1} = adj(Q) / det(Q) (docs/methods.md, eq. (M16)). Shorter
// dependency chains than LDL^T (one division instead of three in sequence),
// hence faster; not backward stable, so it is used only where the error of
// s = Q^{-1} r enters the result to second order (the stationary form of
// f_dd.hpp) and with the componentwise error bound of adj_error().
#pragma once

#include <cmath>
#include <type_traits>

#include "common/fp.hpp"
#include "eval/f_derivatives.hpp"
#include "common/isa.hpp"
#include "common/lanes.hpp"
#include "common/sym3.hpp"

namespace pw85 {

// One pair (AdjEval), or one pair per vector lane (V a lanes::VecD, S and T
// start_lanes.hpp's SymL and Vec3L: contact/default.hpp), with the
// same operations in the same order in f_eval_adj and adj_error below.
template <class V, class S, class T>
struct AdjEvalOf {
  V lambda;
  V phi, dphi;
  V f, df, d2f, d3f, d4f;
  V det, inv_det;  // inv_det = fl(1 / det)
  S q, adj;
  T s;
};
using AdjEval = AdjEvalOf<double, Sym3, Vec3>;

// f and its first four derivatives at lambda. The dependency chain of (M16)
// is kept short: the products with C = adj Q are formed unnormalised
// (C r = det s, D C r = det u, C D C r = det^2 v, ...) and the powers of
// 1/det, computed off the critical path, are applied to the dot products:
//   phi = r.Cr / det,  phi' = -(Cr).(DCr) / det^2,  phi'' = 2 (DCr).(CDCr) / det^3,
//   phi''' = -6 (CDCr).(DCDCr) / det^4,  phi'''' = 24 (DCDCr).(CDCDCr) / det^5
// (pw85 documentation ch. 4, eqs. (5)-(9), carried two orders further with
// d/dlambda Q^{-1} = -Q^{-1} D Q^{-1}); f = p phi with p = lambda (1 - lambda)
// by Leibniz's rule (p' = 1 - 2 lambda, p'' = -2), eq. (M18):
//   f'''' = p phi'''' + 4 p' phi''' - 12 phi''.
// Returns whether the evaluation succeeded (one pair: a bool; lanes: a mask).
template <class V, class S, class T>
PW85_ALWAYS_INLINE auto f_eval_adj(V lambda, T const &r, S const &q1, S const &q2, S const &d,
                                   AdjEvalOf<V, S, T> &e) noexcept {
  e.lambda = lambda;
  e.q = interpolate(q1, q2, lambda);
  S const &q = e.q;
  e.adj = adjugate3(q);
  S const &c = e.adj;
  V const det = det_with_adjugate(q, c);
  e.det = det;
  T const s0 = multiply(c, r);   // det s
  T const u0 = multiply(d, s0);  // det u
  T const v0 = multiply(c, u0);  // det^2 v
  T const w0 = multiply(d, v0);  // det^2 w
  T const x0 = multiply(c, w0);  // det^3 Q^{-1} w
  V const id = 1.0 / det, id2 = id * id;
  e.inv_det = id;
  V const id3 = id2 * id, id4 = id2 * id2;
  e.s = T{{s0[0] * id, s0[1] * id, s0[2] * id}};
  V const phi = dot(r, s0) * id;
  V const phi1 = -dot(s0, u0) * id2;
  V const phi2 = 2.0 * dot(u0, v0) * id3;
  V const phi3 = -6.0 * dot(v0, w0) * id4;
  V const phi4 = 24.0 * dot(w0, x0) * (id4 * id);
  set_f_from_phi(lambda, phi, phi1, phi2, phi3, e);
  e.d4f = -12.0 * phi2 + 4.0 * (1.0 - 2.0 * lambda) * phi3 + lambda * (1.0 - lambda) * phi4;
  if constexpr (std::is_same_v<V, double>)
    return det > 0.0 && phi > 0.0 && std::isfinite(e.f) && std::isfinite(e.df) &&
           std::isfinite(e.d2f) && std::isfinite(e.d3f) && std::isfinite(e.d4f);
  else
    return (det > 0.0) & (phi > 0.0) & lanes::finite(e.f) & lanes::finite(e.df) &
           lanes::finite(e.d2f) & lanes::finite(e.d3f) & lanes::finite(e.d4f);
}

// Componentwise bound (first order in u) on the error of the computed s
// (eq. (M17)): rounding of Q(lambda) (u |Q|), of the adjugate (2u per
// entry, relative to the sum of the absolute values of its two products), of
// det and of the products adj r / det.
template <class V, class S, class T>
PW85_ALWAYS_INLINE T adj_error(AdjEvalOf<V, S, T> const &e, T const &r, S const &q1,
                               S const &q2) noexcept {
  using lanes::vabs;
  S qa;
  V const lm = 1.0 - e.lambda;
  for (int i = 0; i < kSym; ++i) qa[i] = lm * vabs(q1[i]) + e.lambda * vabs(q2[i]);
  // Sums of absolute values of the products of each adjugate entry.
  S const aa{{qa[3] * qa[5] + qa[4] * qa[4], qa[2] * qa[4] + qa[1] * qa[5],
              qa[1] * qa[4] + qa[2] * qa[3], qa[0] * qa[5] + qa[2] * qa[2],
              qa[1] * qa[2] + qa[0] * qa[4], qa[0] * qa[3] + qa[1] * qa[1]}};
  V const det_abs = qa[0] * aa[0] + qa[1] * aa[1] + qa[2] * aa[2];
  // 1/det from the evaluation (its rounding, 1u, is inside the factor 4).
  V const k = 4.0 * kU * e.inv_det;
  V const rel_det = k * det_abs;
  T const ar{{vabs(r[0]), vabs(r[1]), vabs(r[2])}};
  T const t = multiply(aa, ar);
  T err;
  for (int i = 0; i < kDim; ++i) err[i] = k * t[i] + rel_det * vabs(e.s[i]);
  return err;
}

}  // namespace pw85
