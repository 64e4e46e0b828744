/*
 * pw85_legacy.h - public C API of libpw85_legacy.
 *
 * The "legacy" implementations of pw85 1.0, kept to compare methods: the
 * function f evaluated through Cholesky factorisations (pw85_legacy_f1) or as
 * a rational fraction (pw85_legacy_f2), and two contact-function solvers,
 * Newton iterations on f' (pw85_legacy_contact_function1) and bisection on the
 * numerator of f' (pw85_legacy_contact_function2). Names and signatures are
 * those of pw85 1.0 (inputs are const-qualified, which stays source
 * compatible); link with -lpw85_legacy. Prefer pw85_contact_function() of
 * pw85.h: docs/legacy.md measures where each legacy method loses accuracy.
 *
 * Unlike pw85 1.0, every function validates its input and the contact
 * functions return a status code of pw85.h instead of always 0. Functions
 * returning a double return NaN on bad input. No function prints, aborts or
 * allocates; all are reentrant and thread-safe. Every function reads all its
 * inputs before it writes an output, so an output may be one of its input
 * arrays (as in pw85.h).
 *
 * Storage conventions are those of pw85.h: vectors are double[3], symmetric
 * matrices double[6] = {A00, A01, A02, A11, A12, A22}.
 */
#ifndef PW85_LEGACY_H
#define PW85_LEGACY_H

#include "pw85.h"

#if defined(_WIN32) && !defined(__GNUC__)
#  ifdef PW85_LEGACY_BUILDING
#    define PW85_LEGACY_API __declspec(dllexport)
#  else
#    define PW85_LEGACY_API __declspec(dllimport)
#  endif
#elif defined(__GNUC__)
#  define PW85_LEGACY_API __attribute__((visibility("default")))
#else
#  define PW85_LEGACY_API
#endif

PW85_BEGIN_DECLS

/* Determinant of the symmetric matrix a, by cofactor expansion along the
 * first row. Returns NaN when a is NULL. (NaN or infinite entries propagate
 * to the result.) */
PW85_LEGACY_API double pw85_legacy__det_sym(double const a[PW85_SYM]);

/* x^T adj(A) x, where adj(A) is the adjugate (transposed cofactor matrix) of
 * the symmetric matrix a. Returns NaN when x or a is NULL. */
PW85_LEGACY_API double pw85_legacy__xT_adjA_x(double const x[PW85_DIM],
                                              double const a[PW85_SYM]);

/* Coefficients of the quadratic lambda -> r^T adj[(1 - lambda) Q1 + lambda Q2] r
 * = a[0] + a[1] lambda + a[2] lambda^2 (pw85 documentation, section 4.2,
 * eqs. (11a), (12a)-(12c)), from its values at lambda = 0, 1 and -1. The
 * caller passes q3 = 2 Q1 - Q2 (entrywise). The coefficients come from
 * differences of these values, so their absolute error is of order
 * DBL_EPSILON times the largest of |a(-1)|, |a(0)|, |a(1)|. Returns nothing;
 * fails on a NULL pointer: a is then filled with NaN (when a is not NULL). */
PW85_LEGACY_API void pw85_legacy__rT_adjQ_r_as_poly(double const r[PW85_DIM],
                                                    double const q1[PW85_SYM],
                                                    double const q2[PW85_SYM],
                                                    double const q3[PW85_SYM],
                                                    double a[PW85_DIM]);

/* Coefficients of the cubic lambda -> det[(1 - lambda) Q1 + lambda Q2]
 * = b[0] + b[1] lambda + b[2] lambda^2 + b[3] lambda^3 (section 4.2,
 * eqs. (11b), (12d)-(12g)), from its values at lambda = 0, 1, -1 and 1/2.
 * The caller passes q3 = 2 Q1 - Q2 and q4 = (Q1 + Q2) / 2 (entrywise).
 * Absolute error of order DBL_EPSILON times the largest of |b(-1)|, |b(0)|,
 * |b(1/2)|, |b(1)|. Returns nothing; fails on a NULL pointer: b is then
 * filled with NaN (when b is not NULL). */
PW85_LEGACY_API void pw85_legacy__detQ_as_poly(double const q1[PW85_SYM],
                                               double const q2[PW85_SYM],
                                               double const q3[PW85_SYM],
                                               double const q4[PW85_SYM],
                                               double b[PW85_DIM + 1]);

/* f(lambda) = lambda (1 - lambda) r12^T Q^{-1} r12, Q = (1 - lambda) Q1 +
 * lambda Q2, through a Cholesky factorisation of Q (section 4.1, eqs.
 * (4)-(9)). Returns f(lambda). If out is not NULL it is a double[3] that
 * receives out[0] = f, out[1] = f', out[2] = f''.
 * Bad input (NULL r12, q1 or q2; NaN or infinite values; q1 or q2 not
 * positive definite; Q(lambda) not numerically positive definite): returns
 * NaN and fills out with NaN. */
PW85_LEGACY_API double pw85_legacy_f1(double lambda, double const r12[PW85_DIM],
                                      double const q1[PW85_SYM],
                                      double const q2[PW85_SYM], double *out);

/* Same f(lambda) as pw85_legacy_f1(), as the rational fraction
 * lambda (1 - lambda) a(lambda) / b(lambda) of section 4.2, eq. (10), with the
 * coefficients of pw85_legacy__rT_adjQ_r_as_poly() and
 * pw85_legacy__detQ_as_poly(). Returns f(lambda). If out is not NULL it is a
 * double[3] that receives out[0] = f, out[1] = f', out[2] = f'', the
 * derivatives of the same rational fraction. (pw85 1.0 wrote only out[0]: a
 * pw85 1.0 program that passes a double[1] must pass a double[3].) Less
 * accurate than pw85_legacy_f1(): the coefficients suffer
 * from cancellation (docs/legacy.md). Bad input: as pw85_legacy_f1(), and
 * NaN when b(lambda) = 0. */
PW85_LEGACY_API double pw85_legacy_f2(double lambda, double const r12[PW85_DIM],
                                      double const q1[PW85_SYM],
                                      double const q2[PW85_SYM], double *out);

/* Contact function by safeguarded Newton iterations on f' (f, f', f'' of
 * pw85_legacy_f1()): a Newton step that leaves the bracket [lo, hi] of the
 * root of f' (or meets f'' >= 0) is replaced by a bisection step, so the
 * iterates stay in [0, 1].
 *     out[0] = mu^2 = f(lambda),  out[1] = lambda (the maximiser of f).
 * r12 = 0 gives mu^2 = 0, lambda = 0.5 and PW85_OK.
 * Returns PW85_OK, PW85_ERR_INVALID_ARGUMENT (NULL pointer, NaN or infinite
 * value), PW85_ERR_NOT_SPD (q1 or q2 not positive definite),
 * PW85_ERR_NO_CONVERGENCE (the bracket did not shrink to a few ulps of lambda
 * within the iteration limit; or rounding made Q(lambda) lose positive
 * definiteness, out[0] is then NaN) or PW85_ERR_INACCURATE (converged, but the
 * rounding-error estimate of f(lambda), which grows with the condition number
 * of Q(lambda), exceeds 1e-8 relative). On the last two, out holds the best
 * estimate; on the first two it is NaN-filled (when out is not NULL). */
PW85_LEGACY_API int pw85_legacy_contact_function1(double const r12[PW85_DIM],
                                                  double const q1[PW85_SYM],
                                                  double const q2[PW85_SYM],
                                                  double out[2]);

/* Contact function through the rational fraction of section 4.2: lambda is
 * the root in [0, 1] of the sixth-degree numerator c(lambda) of f' (eqs.
 * (13)-(15g)), found by bisection; mu^2 = f(lambda) by eq. (10).
 *     out[0] = mu^2,  out[1] = lambda.
 * r12 = 0 gives mu^2 = 0, lambda = 0.5 and PW85_OK.
 * Returns PW85_OK, PW85_ERR_INVALID_ARGUMENT, PW85_ERR_NOT_SPD (as
 * pw85_legacy_contact_function1(), out NaN-filled), PW85_ERR_NO_CONVERGENCE
 * (the computed c does not change sign on [0, 1], so no root is bracketed,
 * and out holds the endpoint the computed sign points to, mu^2 = f = 0 there;
 * or the rational fraction cannot be evaluated at the root found, b = 0 or
 * overflow, and out[0] is NaN) or PW85_ERR_INACCURATE (the error estimate of
 * mu^2 that follows from the cancellation in the coefficients of a and b
 * exceeds 1e-8 relative; out holds the estimate). */
PW85_LEGACY_API int pw85_legacy_contact_function2(double const r12[PW85_DIM],
                                                  double const q1[PW85_SYM],
                                                  double const q2[PW85_SYM],
                                                  double out[2]);

PW85_END_DECLS

#endif /* PW85_LEGACY_H */
