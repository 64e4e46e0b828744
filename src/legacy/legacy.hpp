// Core of libpw85_legacy: the methods of pw85 1.0's legacy library, in
// namespace pw85::legacy. One method per source file of src/legacy/:
//   adjugate.cpp           det(A) and x^T adj(A) x (section 4.2)
//   poly.cpp               coefficients of a(lambda), b(lambda) (eqs. (11)-(12))
//   f_cholesky.cpp         f, f', f'' by Cholesky (section 4.1, eqs. (4)-(9))
//   f_rational.cpp         f, f', f'' as a rational fraction (eqs. (10)-(15))
//   contact_newton.cpp     safeguarded Newton iterations on f'
//   contact_bisection.cpp  bisection on the numerator c(lambda) of f'
// Equation numbers refer to the pw85 1.0 documentation, chapter
// "Implementation of the function f". Preconditions (checked by capi.cpp):
// finite input, q1 and q2 positive definite.
#pragma once

#include "contact/contact.hpp"
#include "common/status.hpp"
#include "common/sym3.hpp"

namespace pw85 {
namespace legacy {

// det(A), cofactor expansion along the first row.
double det_sym(Sym3 const &a) noexcept;
// Sum of the absolute values of the terms of that expansion: the rounding
// error of det_sym() is a small multiple of DBL_EPSILON times this.
double det_sym_abs(Sym3 const &a) noexcept;
// x^T adj(A) x.
double xT_adjA_x(Vec3 const &x, Sym3 const &a) noexcept;
// Same, with every cofactor term and product taken in absolute value.
double xT_adjA_x_abs(Vec3 const &x, Sym3 const &a) noexcept;

// Coefficients (lowest degree first) of a(lambda) = r^T adj[Q(lambda)] r,
// eqs. (12a)-(12c); q3 = 2 q1 - q2.
void rT_adjQ_r_as_poly(Vec3 const &r, Sym3 const &q1, Sym3 const &q2, Sym3 const &q3,
                       double a[3]) noexcept;
// Coefficients of b(lambda) = det Q(lambda), eqs. (12d)-(12g);
// q3 = 2 q1 - q2, q4 = (q1 + q2) / 2.
void detQ_as_poly(Sym3 const &q1, Sym3 const &q2, Sym3 const &q3, Sym3 const &q4,
                  double b[4]) noexcept;

// f and its first two derivatives.
struct FDerivs {
  double f, df, d2f;
};

// Section 4.1, eqs. (4)-(9). rel_err (may be null) receives an estimate of
// the relative rounding error of f: DBL_EPSILON |Q| |s|^2 / (r^T s), s =
// Q^{-1} r. Returns false when Q(lambda) is not numerically positive
// definite or a result is not finite.
bool f_cholesky(double lambda, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                FDerivs &out, double *rel_err) noexcept;

// The rational representation f = lambda (1 - lambda) a / b of eq. (10).
struct Rational {
  double a[3];      // a(lambda), eqs. (12a)-(12c)
  double b[4];      // b(lambda), eqs. (12d)-(12g)
  double a_err;     // estimate of the absolute error of a(lambda), 0 <= lambda <= 1
  double b_err;     // same for b(lambda)
};

void rational_coefficients(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                           Rational &rat) noexcept;
// f, f', f'' of the rational fraction at lambda. Returns false if b(lambda)
// = 0 or a result is not finite.
bool f_rational(Rational const &rat, double lambda, FDerivs &out) noexcept;
// Coefficients of the numerator c of f' = c / b^2, eqs. (15a)-(15g).
void numerator_coefficients(Rational const &rat, double c[7]) noexcept;

// Relative accuracy on mu^2 that the contact functions claim; above it their
// own error estimate makes them return kInaccurate.
constexpr double kContactRtol = 1e-8;

// Safeguarded Newton iterations on f' (f_cholesky). kOk, kNoConvergence or
// kInaccurate; the estimate is always written.
Status contact_newton(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                      ContactResult &res) noexcept;
// Bisection on c(lambda). kOk, kNoConvergence or kInaccurate; the estimate is
// always written.
Status contact_bisection(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                         ContactResult &res) noexcept;

}  // namespace legacy
}  // namespace pw85
