// Internals of rational.cpp shared with default.hpp: the coefficients of the
// rational form of f and the maximisation of that form (docs/methods.md,
// eqs. (M12)-(M15)).
#pragma once

#include "common/sym3.hpp"

namespace pw85 {

// f(lambda) = s t a(lambda) / b(lambda), s = 1 - lambda, t = lambda,
//   a = s^2 a0 + s t a1 + t^2 a2,  b = s^3 b0 + s^2 t b1 + s t^2 b2 + t^3 b3,
// with the estimated relative error of each coefficient.
struct RationalCoefs {
  double a[3], b[4];
  double ea[3], eb[4];
};

void rational_coefficients(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                           RationalCoefs &c) noexcept;

struct RationalMax {
  double lambda;     // maximiser
  double f;          // f(lambda) from the coefficients
  double rel_coef;   // relative error of f due to the coefficients and rounding
  double gap;        // relative gap (max f - f(lambda)) / f, estimated
  int iterations;
  bool converged;
};

// Safeguarded Halley iteration on the numerator N of f' (eq. (M14)) from
// lambda0, bracketed in [0, 1].
void rational_maximise(RationalCoefs const &c, double lambda0, RationalMax &m) noexcept;

}  // namespace pw85
