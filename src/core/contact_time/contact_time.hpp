// Time of first contact of two moving ellipsoids (docs/contact_time.md):
// r12(t) = r12 + t v12, Q_i(t) = R_i(t) Q_i R_i(t)^T, R_i(t) = exp(t [w_i]x);
// t_c = inf{t in [0, t_max] : mu^2(t) <= 1} by certified conservative
// advancement on lower bounds of mu(t) for the exact motion of the inputs,
// then a refinement of the crossing on a certified bracket (T1)-(T10).
#pragma once

#include "common/status.hpp"
#include "common/sym3.hpp"

namespace pw85 {

// Budget of contact-function evaluations of one call.
constexpr int kContactTimeMaxEval = 100000;

struct ContactTimeResult {
  double t;         // first contact time, +inf when none in [0, t_max]; on
                    // kNoConvergence, the time up to which mu^2 >= kLevel^2
                    // (1 - 2.27e-13, contact_time.cpp) is certified on [0, t]
  int evaluations;  // contact-function evaluations
};

// Preconditions (checked by the C layer): every value finite, q1 and q2
// positive definite, t_max finite and > 0. Returns kOk, kNoConvergence
// (budget exhausted, an evaluation failed or no certified step; res.t as
// above), kInaccurate (decided from the inputs before any evaluation: a
// semi-axis ratio bound above 1e7 in either ellipsoid, or t_max |w_i| >
// 2^50; res.t = 0) or kInvalidArgument (the motion leaves the range of
// double).
Status contact_time(Vec3 const &r12, Vec3 const &v12, Sym3 const &q1, Vec3 const &w1,
                    Sym3 const &q2, Vec3 const &w2, double t_max,
                    ContactTimeResult &res) noexcept;

}  // namespace pw85
