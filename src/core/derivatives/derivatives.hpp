// Derivatives of the contact function mu^2 (docs/derivatives.md, eqs.
// (E1)-(E7)): gradient with respect to r12, torques of infinitesimal
// rotations of each ellipsoid about its own centre, derivatives with respect
// to the stored entries of Q1 and Q2, Hessian with respect to r12.
#pragma once

#include "common/status.hpp"
#include "common/sym3.hpp"
#include "contact/contact.hpp"

namespace pw85 {

struct Derivatives {
  double mu2;          // contact function mu^2 (PW85_METHOD_DEFAULT)
  double lambda;       // maximiser of f, refined by Newton steps on f' = 0
  double d_r12[3];     // d mu^2 / d r12                          (E1)
  double d_theta1[3];  // d mu^2 / d theta_1 (rotation of 1)      (E4)
  double d_theta2[3];  // d mu^2 / d theta_2 (rotation of 2)      (E4)
  double d_q1[6];      // d mu^2 / d q1[k], k over stored entries (E2)
  double d_q2[6];      // d mu^2 / d q2[k]                        (E2)
  double hess_r12[6];  // d^2 mu^2 / d r12^2, stored as Q         (E6)
};

// What contact_derivatives computes: every field, or the fields forces and
// torques need (mu2, lambda, d_r12, d_theta1, d_theta2; d_q1, d_q2 and
// hess_r12 are then NaN). Where the kAll call returns kOk or kInaccurate,
// the kForces call returns the same status and the same bits in its fields.
enum class DerivativeFields { kAll, kForces };

// Preconditions (checked by the C layer): r != 0, finite, q1 and q2 finite
// and positive definite. Returns kOk or kInaccurate (every field written),
// or kNoConvergence (every field NaN).
Status contact_derivatives(Vec3 const &r, Sym3 const &q1, Sym3 const &q2, Derivatives &d,
                           DerivativeFields fields = DerivativeFields::kAll) noexcept;

// contact_derivatives for a caller that already has DEFAULT's solution of
// the pair (status and res as pw85_contact_function_method gives them: the
// batch calls, from default_lanes). Its result is contact_derivatives',
// bit for bit, where derivatives_from_default_ok holds: magnitudes that
// contact_derivatives takes without rescaling (r != 0 among them).
bool derivatives_from_default_ok(Vec3 const &r, Sym3 const &q1, Sym3 const &q2) noexcept;
Status contact_derivatives_from_default(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                                        Status status, MethodResult const &res,
                                        Derivatives &d,
                                        DerivativeFields fields = DerivativeFields::kAll) noexcept;

}  // namespace pw85
