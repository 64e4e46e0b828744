// f as the rational fraction of section 4.2 of the pw85 documentation:
//   f(lambda) = lambda (1 - lambda) a(lambda) / b(lambda)          eq. (10)
// with a, b the polynomials of eqs. (11a)-(11b), coefficients (12a)-(12g).
// Writing p = lambda (1 - lambda) a, the derivatives are those of p / b:
//   f' = (p' - f b') / b,  f'' = (p'' - 2 f' b' - f b'') / b;
// f' = c / b^2 with the sixth-degree c of eqs. (13)-(15g).
#include <cfloat>
#include <cmath>

#include "legacy.hpp"

namespace pw85 {
namespace legacy {

void rational_coefficients(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                           Rational &rat) noexcept {
  Sym3 q3, q4;  // Q(-1) and Q(1/2)
  for (int i = 0; i < kSym; ++i) {
    q3[i] = 2.0 * q1[i] - q2[i];
    q4[i] = 0.5 * (q1[i] + q2[i]);
  }
  rT_adjQ_r_as_poly(r, q1, q2, q3, rat.a);
  detQ_as_poly(q1, q2, q3, q4, rat.b);
  // Each coefficient combines the sampled values with weights <= 3 (eqs.
  // (12)); each sampled value is off by a few DBL_EPSILON times the sum of
  // the absolute values of its terms. On [0, 1] the error of a(lambda) is
  // therefore a few DBL_EPSILON times the sum of these magnitudes.
  double const sa = xT_adjA_x_abs(r, q1) + xT_adjA_x_abs(r, q2) + xT_adjA_x_abs(r, q3);
  double const sb = det_sym_abs(q1) + det_sym_abs(q2) + det_sym_abs(q3) + det_sym_abs(q4);
  rat.a_err = 8.0 * DBL_EPSILON * sa;
  rat.b_err = 16.0 * DBL_EPSILON * sb;
}

bool f_rational(Rational const &rat, double lambda, FDerivs &out) noexcept {
  double const *a = rat.a;
  double const *b = rat.b;
  double const x = lambda;
  double const av = a[0] + x * (a[1] + x * a[2]);
  double const da = a[1] + 2.0 * x * a[2];
  double const d2a = 2.0 * a[2];
  double const bv = b[0] + x * (b[1] + x * (b[2] + x * b[3]));
  double const db = b[1] + x * (2.0 * b[2] + 3.0 * x * b[3]);
  double const d2b = 2.0 * b[2] + 6.0 * x * b[3];
  double const w = x * (1.0 - x);
  double const dw = 1.0 - 2.0 * x;
  double const p = w * av;
  double const dp = dw * av + w * da;
  double const d2p = -2.0 * av + 2.0 * dw * da + w * d2a;
  if (bv == 0.0) return false;
  out.f = p / bv;
  out.df = (dp - out.f * db) / bv;
  out.d2f = (d2p - 2.0 * out.df * db - out.f * d2b) / bv;
  return std::isfinite(out.f) && std::isfinite(out.df) && std::isfinite(out.d2f);
}

// Eqs. (15a)-(15g).
void numerator_coefficients(Rational const &rat, double c[7]) noexcept {
  double const a0 = rat.a[0], a1 = rat.a[1], a2 = rat.a[2];
  double const b0 = rat.b[0], b1 = rat.b[1], b2 = rat.b[2], b3 = rat.b[3];
  c[0] = a0 * b0;
  c[1] = 2.0 * (a1 - a0) * b0;
  c[2] = -a0 * (b1 + b2) + 3.0 * b0 * (a2 - a1) + a1 * b1;
  c[3] = 2.0 * (b1 * (a2 - a1) - a0 * b3) - 4.0 * a2 * b0;
  c[4] = (a0 - a1) * b3 + (a2 - a1) * b2 - 3.0 * a2 * b1;
  c[5] = -2.0 * a2 * b2;
  c[6] = -a2 * b3;
}

}  // namespace legacy
}  // namespace pw85
