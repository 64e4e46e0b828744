// Internals of newton.cpp shared with default.hpp and methods.cpp.
#pragma once

#include "eval/f_ldl.hpp"
#include "contact/start.hpp"
#include "common/sym3.hpp"

namespace pw85 {

struct NewtonState {
  FEval e;        // last successful evaluation (e.f NaN if none)
  double mu2;     // estimate of max f (Taylor-extrapolated from e when step != 0)
  double lambda;  // estimate of the maximiser (e.lambda + step)
  double step;    // extrapolation step (0: mu2 = e.f)
  double trunc;   // size of the last Taylor term used
  double rel;     // estimated relative error of the double phi (< 0: not yet computed)
  double edf;     // estimated absolute error of the double f'
};

// Safeguarded Halley iteration on f' from lambda, bracket [0, 1]; d = Q2 - Q1.
// Returns true when the stopping test (eq. (M9)) was met.
bool newton_iterate(Vec3 const &r, Sym3 const &q1, Sym3 const &q2, Sym3 const &d,
                    double lambda, NewtonState &st, int &iterations) noexcept;

// Fills st.rel and st.edf if not yet computed (eq. (M6)).
void newton_fill_error_terms(NewtonState &st, Vec3 const &r, Sym3 const &q1,
                             Sym3 const &q2) noexcept;

// The part of the error of st.mu2 due to lambda (gap to the maximum or
// error of the extrapolation), given st.rel, st.edf (eq. (M10)).
double newton_lambda_error(NewtonState const &st) noexcept;

// Estimate of |st.mu2 - max f| (eq. (M10)).
double newton_error(NewtonState const &st, Vec3 const &r, Sym3 const &q1,
                    Sym3 const &q2) noexcept;

}  // namespace pw85
