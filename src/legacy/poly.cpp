// Polynomial coefficients of a(lambda) = r^T adj[Q(lambda)] r and
// b(lambda) = det Q(lambda), Q(lambda) = (1 - lambda) Q1 + lambda Q2
// (pw85 documentation, section 4.2, eqs. (11a)-(11b)), from their values at a
// few points: Q(-1) = 2 Q1 - Q2 = q3, Q(1/2) = (Q1 + Q2) / 2 = q4.
// The coefficients are differences of these values: for spheroids of very
// different sizes they lose the leading digits (docs/legacy.md).
#include "legacy.hpp"

namespace pw85 {
namespace legacy {

// Eqs. (12a)-(12c).
void rT_adjQ_r_as_poly(Vec3 const &r, Sym3 const &q1, Sym3 const &q2, Sym3 const &q3,
                       double a[3]) noexcept {
  double const a_0 = xT_adjA_x(r, q1);   // a(0)
  double const a_p1 = xT_adjA_x(r, q2);  // a(1)
  double const a_m1 = xT_adjA_x(r, q3);  // a(-1)
  a[0] = a_0;
  a[1] = 0.5 * (a_p1 - a_m1);
  a[2] = 0.5 * (a_p1 + a_m1) - a_0;
}

// Eqs. (12d)-(12g).
void detQ_as_poly(Sym3 const &q1, Sym3 const &q2, Sym3 const &q3, Sym3 const &q4,
                  double b[4]) noexcept {
  double const b_0 = det_sym(q1);     // b(0)
  double const b_p1 = det_sym(q2);    // b(1)
  double const b_m1 = det_sym(q3);    // b(-1)
  double const b_half = det_sym(q4);  // b(1/2)
  b[0] = b_0;
  b[1] = 8.0 * b_half / 3.0 - 2.0 * b_0 - 0.5 * b_p1 - b_m1 / 6.0;
  b[2] = 0.5 * (b_p1 + b_m1) - b_0;
  b[3] = -8.0 * b_half / 3.0 + 2.0 * b_0 + b_p1 - b_m1 / 3.0;
}

}  // namespace legacy
}  // namespace pw85
