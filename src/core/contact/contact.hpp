// Common result type and entry points of the contact-function methods. Each
// method lives in its own source file of this folder (brent.cpp, ...); the
// table of methods is in methods.cpp. A new method: a value before
// kMethodCount below, a PW85_METHOD_* macro in include/pw85.h, its source
// file and its row in methods.cpp's table.
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
  // The rescaled problem contact_brent solves: r' = 2^-er r, Q' = 2^-eq Q,
  // mu2 = 2^(2 er - eq) mu2_rescaled.
  double mu2_rescaled;
  int er, eq;
};

// pw85 1.0's algorithm: Brent (GSL) on -f over [0, 1], then Newton on the
// residual g. Returns kOk or kNoConvergence (estimate still written).
Status contact_brent(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                     ContactResult &res) noexcept;

// Status of pw85_contact_function for a result cr of contact_brent with
// status s: kInaccurate where s is kOk but the error estimate (M10) at
// cr.lambda (that of PW85_METHOD_BRENT, contact/methods.cpp) exceeds
// kBrentRelAccuracy mu2; s otherwise.
Status contact_brent_status(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                            ContactResult const &cr, Status s) noexcept;

// Method identifiers of pw85_contact_function_method; equal to the
// PW85_METHOD_* macros of include/pw85.h (checked in src/capi).
enum Method : int {
  kMethodDefault = 0,
  kMethodBrent = 1,
  kMethodNewton = 2,
  kMethodRational = 3,
  kMethodZheng = 4,
  kMethodCount  // number of methods: the valid identifiers are 0 .. kMethodCount - 1
};

constexpr bool is_method(int method) noexcept { return method >= 0 && method < kMethodCount; }

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

// The contact function by method, for arguments the caller has checked
// (contact/methods.cpp): handles
// r = 0, rescales r and Q by powers of two when needed, dispatches, checks
// the documented accuracy. Returns kOk, kNoConvergence, kInaccurate or
// kUnknownMethod (res filled with NaN for the last).
Status contact_method(int method, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                      MethodResult &res) noexcept;

// Magnitudes that need no rescaling: every max |r_i|, max |Q1_ij|,
// max |Q2_ij| strictly inside (kSafeLo, kSafeHi).
constexpr double kSafeLo = 0x1p-60, kSafeHi = 0x1p60;

// contact_method without its preliminaries, for callers that have checked
// them (contact_method_entry's one-pass screen): is_method(method), r != 0
// and every magnitude in (kSafeLo, kSafeHi).
Status contact_method_in_range(int method, Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                               MethodResult &res) noexcept;

// Entry of pw85_contact_function_method (contact/methods.cpp) for non-null
// pointers whose values are not yet checked: one screening pass recognises
// valid arguments of moderate magnitude (nearly all calls) and sends them to
// contact_method_in_range (DEFAULT: to the table of kernels, default_variants.hpp);
// the others are validated, then go to contact_method. Returns as
// contact_method, plus kInvalidArgument (NaN or infinite value) and kNotSpd
// (res not written for these two).
Status contact_method_entry(double const *r12, double const *q1, double const *q2, int method,
                            MethodResult &res) noexcept;

// The methods themselves (one source file each). Preconditions: r != 0,
// moderate magnitudes (see contact_method).
Status contact_default(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                       MethodResult &res) noexcept;      // default.hpp
// DEFAULT for kDefaultLanes pairs at once, pair l = (r[l], q1[l], q2[l])
// (docs/batch.md, "Throughput"): on x86-64-v4 the coefficient step in eight
// lanes (default.hpp, coefficient_step_lanes), elsewhere the common path of contact_default
// in two times four lanes (default.hpp, first_step_lanes). status[l] != kLaneUndecided:
// res[l] and status[l] are what pw85_contact_function_method(..., DEFAULT,
// ...) gives, bit for bit; kLaneUndecided: res[l] is meaningless and the
// caller makes the one-pair call. Any values are accepted (read unchecked:
// 3 and 6 doubles at each pointer).
constexpr int kDefaultLanes = 8;
constexpr int kLaneUndecided = 1;  // not a Status (status.hpp)
void default_lanes(double const *const r[kDefaultLanes], double const *const q1[kDefaultLanes],
                   double const *const q2[kDefaultLanes], MethodResult res[kDefaultLanes],
                   int status[kDefaultLanes]) noexcept;

Status contact_newton(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                      MethodResult &res) noexcept;       // newton.cpp
Status contact_rational(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                        MethodResult &res) noexcept;     // rational.cpp

}  // namespace pw85
