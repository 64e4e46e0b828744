// Common result type and entry points of the contact-function methods. Each
// method lives in its own source file of src/core/ (brent.cpp, ...).
// Preconditions, checked by the C layer: r, q1, q2 finite; q1, q2 positive
// definite.
#pragma once

#include "common/isa.hpp"
#include "common/status.hpp"
#include "common/sym3.hpp"

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

// ---- issue 7: methods selected by pw85_contact_function_method ----------
// Method identifiers; equal to the PW85_METHOD_* macros of include/pw85.h.
enum Method : int {
  kMethodDefault = 0,
  kMethodBrent = 1,
  kMethodNewton = 2,
  kMethodRational = 3,
  kMethodZheng = 4,
};

// Documented relative accuracy of mu2 for each method (docs/methods.md): a
// method returns kInaccurate when its error estimate exceeds this times mu2.
constexpr double kDefaultRelAccuracy = 1e-14;
constexpr double kBrentRelAccuracy = 1e-10;
constexpr double kNewtonRelAccuracy = 1e-12;
constexpr double kRationalRelAccuracy = 1e-12;

struct MethodResult {
  double mu2;        // value of the contact function
  double lambda;     // maximiser of f on [0, 1]
  double mu2_error;  // estimate of |mu2 - exact mu2|
  int iterations;    // iterations of the method
  int method;        // method actually used (Method)
};

// Entry point of pw85_contact_function_method (src/core/methods.cpp): handles
// r = 0, rescales r and Q by powers of two when needed, dispatches, checks
// the documented accuracy. Returns kOk, kNoConvergence, kInaccurate or
// kUnknownMethod (res filled with NaN for the last).
Status contact_method(int method, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                      MethodResult &res) noexcept;

// Magnitudes that need no rescaling: every max |r_i|, max |Q1_ij|,
// max |Q2_ij| strictly inside (kSafeLo, kSafeHi).
constexpr double kSafeLo = 0x1p-60, kSafeHi = 0x1p60;

// contact_method without its preliminaries, for callers that have checked
// them (the C layer's one-pass screen): method in [kMethodDefault,
// kMethodZheng], r != 0 and every magnitude in (kSafeLo, kSafeHi).
Status contact_method_in_range(int method, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                               MethodResult &res) noexcept;

// The methods themselves (one source file each). Preconditions: r != 0,
// moderate magnitudes (see contact_method).
Status contact_default(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                       MethodResult &res) noexcept;      // default.cpp
#if PW85_ISA_DISPATCH
// contact_default's x86-64-v4 variant (default.cpp), for callers that have
// checked the CPU (the C layer's v4 entry, src/capi/contact_method.cpp);
// also sets res.method.
Status contact_default_v4(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                          MethodResult &res) noexcept;
#endif
Status contact_newton(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                      MethodResult &res) noexcept;       // newton.cpp
Status contact_rational(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                        MethodResult &res) noexcept;     // rational.cpp

}  // namespace pw85
