// Distance of closest approach (DCA) of two ellipses (2D) and of two
// ellipsoids (3D) whose centres lie on a line of given unit direction u: the
// distance d between the centres at which the two are externally tangent.
// Since the contact function F(r12, Q1, Q2) is homogeneous of degree 2 in r12
// and equals 1 at tangency, d(u) = 1 / sqrt(F(u, Q1, Q2)).
//
//  - dca_2d.cpp: closed-form 2D DCA (quartic, after Zheng & Palffy-Muhoray,
//    Phys. Rev. E 75, 061709 (2007); derivation in docs/dca.md);
//  - contact_2d.cpp: the 2D Perram-Wertheim contact function, for comparison;
//  - dca_3d.cpp: the plane-rotation method of X. Zheng, W. Iglesias and
//    P. Palffy-Muhoray, "Distance of closest approach of two arbitrary hard
//    ellipsoids" (preprint, October 14, 2008); contact_zheng() (the method
//    PW85_METHOD_ZHENG) is in contact/zheng.cpp.
//
// Preconditions, checked by the C layer: every value finite, the matrices
// positive definite, u of unit length (dca_2d, dca_zheng).
#pragma once

#include "contact/contact.hpp"
#include "common/status.hpp"
#include "common/sym2.hpp"
#include "common/sym3.hpp"

namespace pw85 {

// Mirrors of PW85_DCA_THETA_TOL and PW85_DCA_MAX_EVAL (include/pw85.h,
// checked by static_assert in src/capi/dca_capi.cpp).
constexpr double kDcaThetaTol = 1e-8;
constexpr int kDcaMaxEval = 100;

struct Dca2dResult {
  double d;           // distance of closest approach along u
  double lambda;      // maximiser of the 2D contact function f (docs/dca.md, eq. (D7))
  int newton_steps;   // safeguarded Newton steps polishing the closed-form root
  bool closed_form;   // false: no root of the quartic was usable, the
                      // polishing started from the bracket (never seen so far)
};

// 2D DCA of the ellipses {m : m^T Q^{-1} m <= 1}; u is a unit vector.
// Returns kOk, kNoConvergence if the polishing did not converge (the
// estimate is still written), or kInaccurate (nothing written) when q1 or
// q2, positive definite, is singular in rounding after the exact common
// rescaling: condition number above about 1/u, or magnitudes of q1 and q2
// more than about 2^1000 apart.
Status dca_2d(Vec2 const &u, Sym2 const &q1, Sym2 const &q2, Dca2dResult &res) noexcept;

// 2D contact function, out mu2 = max over [0, 1] of
// f(lambda) = lambda (1 - lambda) r^T ((1 - lambda) Q1 + lambda Q2)^{-1} r,
// by safeguarded Newton iterations on f' (f is concave). r = 0 gives mu2 = 0,
// lambda = 1/2. Returns kOk, kNoConvergence (estimate still written) or
// kInaccurate (mu2, lambda NaN) as dca_2d.
Status contact_function_2d(Vec2 const &r, Sym2 const &q1, Sym2 const &q2, double &mu2,
                           double &lambda, int &iterations) noexcept;

struct DcaResult {
  double d;          // distance of closest approach along u
  double lambda;     // maximiser of f (3D contact function) at r12 = u
  double theta;      // angle of the optimal plane (docs/dca.md, eq. (D9))
  int evaluations;   // number of 2D DCA evaluations (planes) used
};

// Plane-rotation method: d = max over theta of the 2D DCA of the sections of
// both ellipsoids by the plane through the line of centres at angle theta.
// theta_tol > 0 is the absolute tolerance on theta (radians), max_eval the
// budget of 2D evaluations. Returns kOk, or kNoConvergence when the budget is
// exhausted (the best estimate is still written).
Status dca_zheng(Vec3 const &u, Sym3 const &q1, Sym3 const &q2, double theta_tol,
                 int max_eval, DcaResult &res) noexcept;

// Contact function through the plane-rotation DCA:
// mu^2 = |r|^2 / d(r / |r|)^2, lambda = the maximiser of f recovered from the
// contact geometry of the optimal plane (docs/dca.md, eq. (D7)); iterations
// = number of 2D evaluations. r = 0 gives mu2 = 0, lambda = 1/2 (as Brent).
Status contact_zheng(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                     ContactResult &res) noexcept;

// Documented relative accuracy of mu2 by the plane-rotation method for pair
// aspect ratios up to 100 (docs/dca.md); PW85_METHOD_ZHENG of
// pw85_contact_function_method returns kInaccurate beyond it.
constexpr double kZhengRelAccuracy = 1e-9;

// PW85_METHOD_ZHENG of pw85_contact_function_method (called by
// contact_method, methods.cpp): contact_zheng, plus the error estimate
// mu2_error = |mu2 - f(lambda)|, f evaluated at the recovered lambda through
// a Cholesky factorisation of Q(lambda) (docs/dca.md, eq. (D13)). Returns
// kOk, kNoConvergence, or kInaccurate when mu2_error > kZhengRelAccuracy mu2.
Status contact_zheng_method(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                            MethodResult &res) noexcept;

// Distance of closest approach through a contact-function method (any
// method of pw85_contact_function_method): since F is homogeneous of degree
// 2 in r12, d(u) = |u| / sqrt(F(u)) for any u != 0 (docs/dca.md).
// u is scaled by a power of two (exact) to max |u_i| in [0.5, 1), then |u|
// and F are computed from the scaled u itself: normalising u first would
// round its components, an error that F amplifies by the conditioning of
// the pair. Preconditions as contact_method, u != 0. Returns as
// contact_method; d is written unless the status is kUnknownMethod.
Status dca_by_contact_function(Vec3 const &u, Sym3 const &q1, Sym3 const &q2, int method,
                               double &d) noexcept;

}  // namespace pw85
