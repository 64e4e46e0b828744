// f(lambda) = p(lambda) phi(lambda) with p = lambda (1 - lambda) and
// phi = r^T Q^{-1} r, and its derivatives up to the third by Leibniz's rule.
// With s = Q^{-1} r, u = D s, v = Q^{-1} u, w = D v (D = Q2 - Q1):
//   phi' = -s^T u,  phi'' = 2 u^T v,  phi''' = -6 v^T w
// (pw85 documentation, chapter 4, eqs. (5)-(9), one order further).
// Used by the L D L^T (f_ldl.hpp) and adjugate (f_adj.hpp, which adds the
// fourth derivative, docs/methods.md eq. (M18)) evaluations.
#pragma once

#include "common/isa.hpp"
#include "common/sym3.hpp"

namespace pw85 {

// f = p phi and its first three derivatives from phi, phi', phi'', phi'''.
// For one pair (T = double) or one pair per vector lane (T a vector type,
// contact/default.hpp, coefficient_step_lanes).
template <class T, class Eval>
PW85_ALWAYS_INLINE void set_f_from_phi(T lambda, T phi, T phi1, T phi2, T phi3,
                                       Eval &e) noexcept {
  T const p = lambda * (1.0 - lambda);
  T const p1 = 1.0 - 2.0 * lambda;
  e.phi = phi;
  e.dphi = phi1;
  e.f = p * phi;
  e.df = p1 * phi + p * phi1;
  e.d2f = -2.0 * phi + 2.0 * p1 * phi1 + p * phi2;
  e.d3f = -6.0 * phi1 + 3.0 * p1 * phi2 + p * phi3;
}

template <class Eval>
inline void set_f_derivatives(double lambda, Vec3 const &r, Vec3 const &s, Vec3 const &u,
                              Vec3 const &v, Vec3 const &w, Eval &e) noexcept {
  set_f_from_phi(lambda, dot(r, s), -dot(s, u), 2.0 * dot(u, v), -6.0 * dot(v, w), e);
}

}  // namespace pw85
