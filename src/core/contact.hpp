// Common result type and entry points of the contact-function methods. Each
// method lives in its own source file of src/core/ (brent.cpp, ...).
// Preconditions, checked by the C layer: r, q1, q2 finite; q1, q2 positive
// definite.
#pragma once

#include "status.hpp"
#include "sym3.hpp"

namespace pw85 {

struct ContactResult {
  double mu2;       // value of the contact function
  double lambda;    // maximiser of f on [0, 1]
  int iterations;   // iterations of the method (method-specific meaning)
};

// pw85 1.0's algorithm: Brent (GSL) on -f over [0, 1], then Newton on the
// residual g. Returns kOk or kNoConvergence (estimate still written).
Status contact_brent(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                     ContactResult &res) noexcept;

}  // namespace pw85
