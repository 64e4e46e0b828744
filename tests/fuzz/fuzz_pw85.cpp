// libFuzzer target over every public function of libpw85 and libpw85_legacy:
// each input is decoded into a pair of ellipsoids (and the scalars the other
// functions take), every function is called, and the promises of
// include/pw85.h and include/pw85_legacy.h are checked; a violated promise
// prints its name and calls __builtin_trap(). This file: the one-pair calls,
// the *_batch calls and the entry points; fuzz_scene.cpp: the pairs, scene,
// configuration, derivative and contact-time calls. Built by meson with
// -Dfuzz=true (Clang only, tests/fuzz/meson.build), run by .ci/fuzz; the
// same checks run as fuzz-replay (fuzz_replay.cpp) over the corpus in every
// build of the suite, on every instruction-set variant.
//
// Input layout (shorter inputs are padded with zeros):
//   byte 0      mode: bit 0 (bit 1): q1 (q2) built from its six doubles as
//               R diag(s) R^T, s the first three, R from three angles,
//               instead of taken raw; bit 2: r12 = 0; bit 3: r12 negated;
//               bit 4: the scene calls with the periodic box below (else
//               without); bit 5: the box keeps its tilts (else they are 0);
//               bit 6: r12 = (r12[0], 0, 0); bit 7: the contact-time calls
//   byte 1      method (signed) for pw85_contact_function_method, pw85_dca
//               and the pairs and scene calls that take one
//   17 doubles  r12[3], q1[6], q2[6], lambda, theta_tol
//   17 doubles  box[6], v12[3], w1[3], w2[3], t_max, s (the scale of
//               pw85_configuration_pairs)
//
// Checks (names for PW85_FUZZ_SKIP, a comma-separated list of checks not to
// make, e.g. PW85_FUZZ_SKIP=lambda,finite): the names of fuzz::check_name
// (fuzz_checks.hpp says what each checks).
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "fuzz_checks.hpp"
#include "pw85.h"
#include "pw85_legacy.h"

namespace fuzz {

char const *const check_name[kChecks] = {"status",      "finite", "nan",   "lambda",
                                         "swap",        "batch",  "determinism",
                                         "untouched",   "spd",    "image", "time",
                                         "axes",        "answers"};
bool skip_check[kChecks];
int current_method = -1;
std::FILE *trace;
int spd_expected = -1;

namespace {
std::uint64_t digest_state = 0xcbf29ce484222325ULL;
void fnv(void const *p, std::size_t n) {
  unsigned char const *c = static_cast<unsigned char const *>(p);
  for (std::size_t i = 0; i < n; ++i) digest_state = (digest_state ^ c[i]) * 0x100000001B3ULL;
}
}  // namespace

[[noreturn]] void violated(Check c, char const *fn, int status) {
  std::fprintf(stderr, "promise violated: %s of %s (status %d, method %d)\n", check_name[c], fn,
               status, current_method);
  __builtin_trap();
}

void record(char const *fn, long long value) {
  fnv(fn, std::strlen(fn));
  fnv(&current_method, sizeof current_method);
  fnv(&value, sizeof value);
  if (trace) std::fprintf(trace, "%s %d %lld\n", fn, current_method, value);
}

std::uint64_t digest() { return digest_state; }

void spd_decision(char const *fn, int status) {
  if (spd_expected >= 0)
    CHECK(kSpd, (status == PW85_ERR_NOT_SPD) == (spd_expected == 1), fn, status);
}

namespace {

// The positive-definiteness decision of the pair, as the calls on (r, q1,
// q2) must all take it (pw85.h, "Positive definiteness"): 1 when q1 or q2
// is refused, 0 when both are accepted, -1 when a call may fail first for
// another reason (a value not finite, r = 0). Probed once per matrix by
// pw85_contact_function_method on (e_x, q, q).
int spd_expectation(double const *r, double const *q1, double const *q2) {
  if (!all_finite(r, 3) || !all_finite(q1, 6) || !all_finite(q2, 6) ||
      (r[0] == 0.0 && r[1] == 0.0 && r[2] == 0.0))
    return -1;
  double const ex[3] = {1.0, 0.0, 0.0};
  pw85_result res;
  bool const refused = pw85_contact_function_method(ex, q1, q1, PW85_METHOD_DEFAULT, &res) ==
                           PW85_ERR_NOT_SPD ||
                       pw85_contact_function_method(ex, q2, q2, PW85_METHOD_DEFAULT, &res) ==
                           PW85_ERR_NOT_SPD;
  return refused ? 1 : 0;
}

// q = R diag(s) R^T from six doubles: s_i = |p[i]| (1 when that is 0 or not
// finite), R from the angles p[3..5] (reduced mod 2 pi).
void build_form(double const *p, double *q) {
  double s[3], a[3];
  for (int i = 0; i < 3; ++i) {
    s[i] = std::fabs(p[i]);
    if (!(s[i] > 0.0) || !(s[i] <= 1.79e308)) s[i] = 1.0;
    a[i] = std::isfinite(p[3 + i]) ? std::fmod(p[3 + i], 6.283185307179586) : 0.0;
  }
  double const c0 = std::cos(a[0]), s0 = std::sin(a[0]), c1 = std::cos(a[1]),
               s1 = std::sin(a[1]), c2 = std::cos(a[2]), s2 = std::sin(a[2]);
  // R = Rz(a0) Ry(a1) Rz(a2), rows are the axes
  double const r[9] = {c0 * c1 * c2 - s0 * s2, -c0 * c1 * s2 - s0 * c2, c0 * s1,
                       s0 * c1 * c2 + c0 * s2, -s0 * c1 * s2 + c0 * c2, s0 * s1,
                       -s1 * c2,              s1 * s2,                c1};
  int k = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) {
      double v = 0.0;
      for (int l = 0; l < 3; ++l) v += s[l] * r[3 * l + i] * r[3 * l + j];
      q[k++] = v;
    }
}

void check_contact_function_method(double const *r, double const *q1, double const *q2,
                                   int method) {
  char const *fn = "pw85_contact_function_method";
  current_method = method;
  pw85_result a, b;
  int const s = pw85_contact_function_method(r, q1, q2, method, &a);
  record(fn, s);
  if (method >= PW85_METHOD_DEFAULT && method <= PW85_METHOD_ZHENG) spd_decision(fn, s);
  int const s2 = pw85_contact_function_method(r, q1, q2, method, &b);
  CHECK(kDeterminism, s == s2 && same_bits(&a, &b, sizeof a), fn, s);
  CHECK(kStatus,
        in_list(s, {PW85_OK, PW85_ERR_INACCURATE, PW85_ERR_NO_CONVERGENCE, PW85_ERR_RANGE,
                    PW85_ERR_INVALID_ARGUMENT, PW85_ERR_NOT_SPD, PW85_ERR_UNKNOWN_METHOD}),
        fn, s);
  if (s == PW85_OK || s == PW85_ERR_INACCURATE || s == PW85_ERR_NO_CONVERGENCE ||
      s == PW85_ERR_RANGE) {
    // mu2 >= 0, +inf only beyond the range of double (PW85_ERR_RANGE, or a
    // status that flags the estimate); mu2_error never NaN.
    CHECK(kFinite, a.mu2 >= 0.0 && !std::isnan(a.mu2_error) &&
                       (std::isfinite(a.mu2) || s != PW85_OK), fn, s);
    CHECK(kLambda, lambda_ok(a.lambda), fn, s);
  } else {
    CHECK(kNan, std::isnan(a.mu2) && std::isnan(a.lambda) && std::isnan(a.mu2_error) &&
                    a.iterations == 0, fn, s);
  }
}

void check_dca(double const *u, double const *q1, double const *q2, int method) {
  char const *fn = "pw85_dca";
  current_method = method;
  double d, d2;
  int const s = pw85_dca(u, q1, q2, method, &d);
  record(fn, s);
  if (method >= PW85_METHOD_DEFAULT && method <= PW85_METHOD_ZHENG) spd_decision(fn, s);
  int const s2 = pw85_dca(u, q1, q2, method, &d2);
  CHECK(kDeterminism, s == s2 && same_bits(&d, &d2, sizeof d), fn, s);
  bool const zheng = method == PW85_METHOD_ZHENG;
  CHECK(kStatus,
        in_list(s, {PW85_OK, PW85_ERR_INVALID_ARGUMENT, PW85_ERR_NOT_SPD,
                    PW85_ERR_UNKNOWN_METHOD, PW85_ERR_NO_CONVERGENCE}) ||
            (!zheng && s == PW85_ERR_INACCURATE),
        fn, s);
  if (s == PW85_OK) CHECK(kFinite, std::isfinite(d), fn, s);
  if (in_list(s, {PW85_ERR_INVALID_ARGUMENT, PW85_ERR_NOT_SPD, PW85_ERR_UNKNOWN_METHOD}))
    CHECK(kNan, std::isnan(d), fn, s);
}

}  // namespace

void check_one_pair(Input const &in) {
  double const *r = in.r, *q1 = in.q1, *q2 = in.q2;
  int const method = in.method;
  double const lambda = in.lambda, theta = in.theta;
  spd_expected = spd_expectation(r, q1, q2);
  for (int m = PW85_METHOD_DEFAULT; m <= PW85_METHOD_ZHENG; ++m) {
    check_contact_function_method(r, q1, q2, m);
    check_dca(r, q1, q2, m);
  }
  check_contact_function_method(r, q1, q2, method);
  check_dca(r, q1, q2, method);
  current_method = -1;

  {
    char const *fn = "pw85_contact_function";
    double o[2], o2[2];
    int const s = pw85_contact_function(r, q1, q2, o);
    record(fn, s);
    spd_decision(fn, s);
    int const s2 = pw85_contact_function(r, q1, q2, o2);
    CHECK(kDeterminism, s == s2 && same_bits(o, o2, sizeof o), fn, s);
    CHECK(kStatus, in_list(s, {PW85_OK, PW85_ERR_INVALID_ARGUMENT, PW85_ERR_NOT_SPD,
                               PW85_ERR_NO_CONVERGENCE, PW85_ERR_INACCURATE,
                               PW85_ERR_RANGE}), fn, s);
    if (s == PW85_OK || s == PW85_ERR_INACCURATE) {
      CHECK(kFinite, std::isfinite(o[0]), fn, s);
      CHECK(kLambda, lambda_ok(o[1]), fn, s);
    }
    if (s == PW85_ERR_NO_CONVERGENCE || s == PW85_ERR_RANGE) CHECK(kLambda, lambda_ok(o[1]), fn, s);
    if (s == PW85_ERR_INVALID_ARGUMENT || s == PW85_ERR_NOT_SPD) CHECK(kNan, all_nan(o, 2), fn, s);
  }
  {
    char const *fn = "pw85_overlap";
    double const mr[3] = {-r[0], -r[1], -r[2]};
    int const v = pw85_overlap(r, q1, q2);
    record(fn, v);
    spd_decision(fn, v);
    CHECK(kDeterminism, v == pw85_overlap(r, q1, q2), fn, v);
    CHECK(kStatus, in_list(v, {0, 1, PW85_ERR_INVALID_ARGUMENT, PW85_ERR_NOT_SPD,
                               PW85_ERR_INACCURATE}), fn, v);
    int const w = pw85_overlap(mr, q2, q1);
    record(fn, w);
    spd_decision(fn, w);
    // Both decided: the same verdict. (One may decide while the other runs
    // out of capacity, PW85_ERR_INACCURATE: documented for entries spanning
    // more than about 2^300.) Invalid arguments are invalid either way.
    if (v >= 0 && w >= 0) CHECK(kSwap, v == w, fn, v);
    if (v == PW85_ERR_INVALID_ARGUMENT) CHECK(kSwap, v == w, fn, v);
    // One positive-definiteness decision (pw85.h): refused in one order,
    // refused in the other.
    if (v == PW85_ERR_NOT_SPD || w == PW85_ERR_NOT_SPD) CHECK(kSpd, v == w, fn, v);
  }
  {
    char const *fn = "pw85_contact";
    pw85_contact_t c, c2;
    int const s = pw85_contact(r, q1, q2, &c);
    record(fn, s);
    spd_decision(fn, s);
    int const s2 = pw85_contact(r, q1, q2, &c2);
    CHECK(kDeterminism, s == s2 && same_bits(&c, &c2, sizeof c), fn, s);
    CHECK(kStatus, in_list(s, {PW85_OK, PW85_ERR_INVALID_ARGUMENT, PW85_ERR_NOT_SPD,
                               PW85_ERR_NO_CONVERGENCE, PW85_ERR_INACCURATE,
                               PW85_ERR_RANGE}), fn, s);
    if (s == PW85_OK) {
      CHECK(kFinite, std::isfinite(c.mu2), fn, s);
      CHECK(kLambda, lambda_ok(c.lambda), fn, s);
    }
    if (s == PW85_ERR_INVALID_ARGUMENT || s == PW85_ERR_NOT_SPD)
      CHECK(kNan, all_nan(&c.mu2, sizeof c / sizeof(double)), fn, s);
  }
  {
    char const *fn = "pw85_dca_ex";
    double d, d2;
    int ev, ev2;
    int const s = pw85_dca_ex(r, q1, q2, theta, &d, &ev);
    record(fn, s);
    spd_decision(fn, s);
    int const s2 = pw85_dca_ex(r, q1, q2, theta, &d2, &ev2);
    CHECK(kDeterminism, s == s2 && ev == ev2 && same_bits(&d, &d2, sizeof d), fn, s);
    CHECK(kStatus, in_list(s, {PW85_OK, PW85_ERR_INVALID_ARGUMENT, PW85_ERR_NOT_SPD,
                               PW85_ERR_NO_CONVERGENCE}), fn, s);
    if (s == PW85_OK) CHECK(kFinite, std::isfinite(d), fn, s);
    if (s == PW85_ERR_INVALID_ARGUMENT || s == PW85_ERR_NOT_SPD) CHECK(kNan, std::isnan(d), fn, s);
  }
  {
    double const u[2] = {r[0], r[1]}, p1[3] = {q1[0], q1[1], q1[3]},
                 p2[3] = {q2[0], q2[1], q2[3]};
    char const *fn = "pw85_dca_2d";
    double d, d2;
    int s = pw85_dca_2d(u, p1, p2, &d);
    record(fn, s);
    int s2 = pw85_dca_2d(u, p1, p2, &d2);
    CHECK(kDeterminism, s == s2 && same_bits(&d, &d2, sizeof d), fn, s);
    CHECK(kStatus, in_list(s, {PW85_OK, PW85_ERR_INVALID_ARGUMENT, PW85_ERR_NOT_SPD,
                               PW85_ERR_NO_CONVERGENCE, PW85_ERR_INACCURATE}), fn, s);
    if (s == PW85_OK) CHECK(kFinite, std::isfinite(d), fn, s);
    if (s == PW85_ERR_INVALID_ARGUMENT || s == PW85_ERR_NOT_SPD || s == PW85_ERR_INACCURATE)
      CHECK(kNan, std::isnan(d), fn, s);

    fn = "pw85_contact_function_2d";
    double o[2], o2[2];
    s = pw85_contact_function_2d(u, p1, p2, o);
    record(fn, s);
    s2 = pw85_contact_function_2d(u, p1, p2, o2);
    CHECK(kDeterminism, s == s2 && same_bits(o, o2, sizeof o), fn, s);
    CHECK(kStatus, in_list(s, {PW85_OK, PW85_ERR_INVALID_ARGUMENT, PW85_ERR_NOT_SPD,
                               PW85_ERR_NO_CONVERGENCE, PW85_ERR_RANGE, PW85_ERR_INACCURATE}),
          fn, s);
    if (s == PW85_OK) {
      CHECK(kFinite, std::isfinite(o[0]), fn, s);
      CHECK(kLambda, lambda_ok(o[1]), fn, s);
    }
    if (s == PW85_ERR_INVALID_ARGUMENT || s == PW85_ERR_NOT_SPD || s == PW85_ERR_INACCURATE)
      CHECK(kNan, all_nan(o, 2), fn, s);
  }

  // Helpers and constructors of pw85.h.
  {
    double l[6], l2[6], x[3], x2[3];
    pw85__cholesky_decomp(q1, l);
    pw85__cholesky_decomp(q1, l2);
    CHECK(kDeterminism, same_bits(l, l2, sizeof l), "pw85__cholesky_decomp", 0);
    bool q1_nan = false;  // NaN in q1: all NaN; Inf: not documented
    for (int i = 0; i < 6; ++i) q1_nan = q1_nan || std::isnan(q1[i]);
    if (q1_nan) CHECK(kNan, all_nan(l, 6), "pw85__cholesky_decomp", 0);
    else if (all_finite(q1, 6))
      CHECK(kNan, all_nan(l, 6) || all_finite(l, 6), "pw85__cholesky_decomp", 0);
    pw85__cholesky_solve(l, r, x);
    pw85__cholesky_solve(l, r, x2);
    CHECK(kDeterminism, same_bits(x, x2, sizeof x), "pw85__cholesky_solve", 0);

    double params[15];
    std::memcpy(params, r, 24);
    std::memcpy(params + 3, q1, 48);
    std::memcpy(params + 9, q2, 48);
    double const f = pw85_f_neg(lambda, params), f2 = pw85_f_neg(lambda, params);
    CHECK(kDeterminism, same_bits(&f, &f2, 8), "pw85_f_neg", 0);
    bool const finite_in = std::isfinite(lambda) && all_finite(params, 15);
    if (!finite_in) CHECK(kNan, std::isnan(f), "pw85_f_neg", 0);
    double o[3], o2[3];
    pw85__residual(lambda, r, q1, q2, o);
    pw85__residual(lambda, r, q1, q2, o2);
    CHECK(kDeterminism, same_bits(o, o2, sizeof o), "pw85__residual", 0);
    if (!finite_in) CHECK(kNan, all_nan(o, 3), "pw85__residual", 0);

    double q[6], qq[6];
    double const a = r[0], c = r[1];
    pw85_spheroid(a, c, q2, q);
    pw85_spheroid(a, c, q2, qq);
    CHECK(kDeterminism, same_bits(q, qq, sizeof q), "pw85_spheroid", 0);
    bool const bad = !(a > 0.0) || !(c > 0.0) || !std::isfinite(a) || !std::isfinite(c) ||
                     !all_finite(q2, 3) || (q2[0] == 0.0 && q2[1] == 0.0 && q2[2] == 0.0);
    if (bad) CHECK(kNan, all_nan(q, 6), "pw85_spheroid", 0);

    double axes[9];
    std::memcpy(axes, q1, 48);
    std::memcpy(axes + 6, q2, 24);
    int const s = pw85_ellipsoid(r, axes, q);
    record("pw85_ellipsoid", s);
    int const s2 = pw85_ellipsoid(r, axes, qq);
    CHECK(kDeterminism, s == s2 && same_bits(q, qq, sizeof q), "pw85_ellipsoid", s);
    CHECK(kStatus, in_list(s, {PW85_OK, PW85_ERR_INVALID_ARGUMENT, PW85_ERR_NOT_SPD,
                               PW85_ERR_NOT_ORTHONORMAL, PW85_ERR_RANGE}), "pw85_ellipsoid", s);
    if (s != PW85_OK) CHECK(kNan, all_nan(q, 6), "pw85_ellipsoid", s);
    // PW85_ERR_NOT_SPD only for a radius <= 0 (pw85.h); positive radii
    // whose Q is not representable give PW85_ERR_RANGE.
    bool const radius_not_positive = !(r[0] > 0.0) || !(r[1] > 0.0) || !(r[2] > 0.0);
    if (s == PW85_ERR_NOT_SPD) CHECK(kStatus, radius_not_positive, "pw85_ellipsoid", s);
    int const sr = pw85_ellipsoid_rotation(r, axes, q);
    record("pw85_ellipsoid_rotation", sr);
    int const sr2 = pw85_ellipsoid_rotation(r, axes, qq);
    CHECK(kDeterminism, sr == sr2 && same_bits(q, qq, sizeof q), "pw85_ellipsoid_rotation", sr);
    CHECK(kStatus, in_list(sr, {PW85_OK, PW85_ERR_INVALID_ARGUMENT, PW85_ERR_NOT_SPD,
                                PW85_ERR_NOT_ORTHONORMAL, PW85_ERR_RANGE}),
          "pw85_ellipsoid_rotation", sr);
    if (sr != PW85_OK) CHECK(kNan, all_nan(q, 6), "pw85_ellipsoid_rotation", sr);
    if (sr == PW85_ERR_NOT_SPD) CHECK(kStatus, radius_not_positive, "pw85_ellipsoid_rotation", sr);
    int const sq = pw85_ellipsoid_quat(r, q2, q);
    record("pw85_ellipsoid_quat", sq);
    int const sq2 = pw85_ellipsoid_quat(r, q2, qq);
    CHECK(kDeterminism, sq == sq2 && same_bits(q, qq, sizeof q), "pw85_ellipsoid_quat", sq);
    CHECK(kStatus, in_list(sq, {PW85_OK, PW85_ERR_INVALID_ARGUMENT, PW85_ERR_NOT_SPD,
                                PW85_ERR_NOT_ORTHONORMAL, PW85_ERR_RANGE}),
          "pw85_ellipsoid_quat", sq);
    if (sq != PW85_OK) CHECK(kNan, all_nan(q, 6), "pw85_ellipsoid_quat", sq);
    if (sq == PW85_ERR_NOT_SPD) CHECK(kStatus, radius_not_positive, "pw85_ellipsoid_quat", sq);
    double ra[3], ra2[3], ro[9], ro2[9], qu[4], qu2[4];
    int const sa = pw85_ellipsoid_axes(q1, ra, ro, qu);
    record("pw85_ellipsoid_axes", sa);
    int const sa2 = pw85_ellipsoid_axes(q1, ra2, ro2, qu2);
    CHECK(kDeterminism, sa == sa2 && same_bits(ra, ra2, sizeof ra) &&
          same_bits(ro, ro2, sizeof ro) && same_bits(qu, qu2, sizeof qu), "pw85_ellipsoid_axes", sa);
    CHECK(kStatus, in_list(sa, {PW85_OK, PW85_ERR_INVALID_ARGUMENT, PW85_ERR_NOT_SPD,
                                PW85_ERR_NO_CONVERGENCE, PW85_ERR_INACCURATE}),
          "pw85_ellipsoid_axes", sa);
    if (sa != PW85_OK && sa != PW85_ERR_NO_CONVERGENCE)
      CHECK(kNan, all_nan(ra, 3) && all_nan(ro, 9) && all_nan(qu, 4), "pw85_ellipsoid_axes", sa);
    if (all_finite(q1, 6)) {
      // One decision: pw85_ellipsoid_axes refuses q1 as every call does.
      double const ex[3] = {1.0, 0.0, 0.0};
      pw85_result res;
      bool const refused = pw85_contact_function_method(ex, q1, q1, PW85_METHOD_DEFAULT, &res) ==
                           PW85_ERR_NOT_SPD;
      CHECK(kSpd, (sa == PW85_ERR_NOT_SPD) == refused, "pw85_ellipsoid_axes", sa);
    }
    if (sa == PW85_OK) {
      CHECK(kStatus, ra[0] <= ra[1] && ra[1] <= ra[2] && qu[0] >= 0.0, "pw85_ellipsoid_axes", sa);
      // The outputs give a q back through both constructors (pw85.h), the
      // same matrix within the accuracy of the sweeps, 10 u ||q|| entrywise,
      // and a few roundings of each constructor (u ||q|| each, allowed 6 u
      // in all; entries near the subnormal range: DBL_MIN absolute).
      double qr[6], qt[6];
      int const back_r = pw85_ellipsoid_rotation(ra, ro, qr);
      int const back_q = pw85_ellipsoid_quat(ra, qu, qt);
      CHECK(kStatus, back_r == PW85_OK && back_q == PW85_OK, "pw85_ellipsoid_axes", sa);
      double const norm = ra[2] * ra[2];
      if (std::isfinite(norm)) {
        double const tol = 16.0 * 0x1p-53 * norm + 0x1p-1022;
        bool close = true;
        for (int i = 0; i < 6; ++i)
          close = close && std::fabs(qr[i] - q1[i]) <= tol && std::fabs(qt[i] - q1[i]) <= tol;
        CHECK(kAxes, close, "pw85_ellipsoid_axes", sa);
      }
    }
    CHECK(kStatus, pw85_strerror(method) != nullptr, "pw85_strerror", method);
  }

  // libpw85_legacy.
  {
    double const d = pw85_legacy__det_sym(q1), d2 = pw85_legacy__det_sym(q1);
    CHECK(kDeterminism, same_bits(&d, &d2, 8), "pw85_legacy__det_sym", 0);
    double const x = pw85_legacy__xT_adjA_x(r, q1), x2 = pw85_legacy__xT_adjA_x(r, q1);
    CHECK(kDeterminism, same_bits(&x, &x2, 8), "pw85_legacy__xT_adjA_x", 0);
    double q3[6], q4[6], pa[3], pa2[3], pb[4], pb2[4];
    for (int i = 0; i < 6; ++i) {
      q3[i] = 2.0 * q1[i] - q2[i];
      q4[i] = 0.5 * (q1[i] + q2[i]);
    }
    pw85_legacy__rT_adjQ_r_as_poly(r, q1, q2, q3, pa);
    pw85_legacy__rT_adjQ_r_as_poly(r, q1, q2, q3, pa2);
    CHECK(kDeterminism, same_bits(pa, pa2, sizeof pa), "pw85_legacy__rT_adjQ_r_as_poly", 0);
    pw85_legacy__detQ_as_poly(q1, q2, q3, q4, pb);
    pw85_legacy__detQ_as_poly(q1, q2, q3, q4, pb2);
    CHECK(kDeterminism, same_bits(pb, pb2, sizeof pb), "pw85_legacy__detQ_as_poly", 0);

    for (int k = 0; k < 2; ++k) {
      char const *fn = k ? "pw85_legacy_f2" : "pw85_legacy_f1";
      auto f = k ? pw85_legacy_f2 : pw85_legacy_f1;
      double o[3], o2[3];
      double const v = f(lambda, r, q1, q2, o), v2 = f(lambda, r, q1, q2, o2);
      CHECK(kDeterminism, same_bits(&v, &v2, 8) && same_bits(o, o2, sizeof o), fn, 0);
      if (!std::isfinite(lambda) || !all_finite(r, 3) || !all_finite(q1, 6) || !all_finite(q2, 6))
        CHECK(kNan, std::isnan(v) && all_nan(o, 3), fn, 0);
    }
    for (int k = 0; k < 2; ++k) {
      char const *fn = k ? "pw85_legacy_contact_function2" : "pw85_legacy_contact_function1";
      auto cf = k ? pw85_legacy_contact_function2 : pw85_legacy_contact_function1;
      double o[2], o2[2];
      int const s = cf(r, q1, q2, o), s2 = cf(r, q1, q2, o2);
      record(fn, s);
      CHECK(kDeterminism, s == s2 && same_bits(o, o2, sizeof o), fn, s);
      CHECK(kStatus, in_list(s, {PW85_OK, PW85_ERR_INVALID_ARGUMENT, PW85_ERR_NOT_SPD,
                                 PW85_ERR_NO_CONVERGENCE, PW85_ERR_INACCURATE}), fn, s);
      if (s == PW85_OK) {
        CHECK(kFinite, std::isfinite(o[0]), fn, s);
        CHECK(kLambda, lambda_ok(o[1]), fn, s);
      }
      if (s == PW85_ERR_INVALID_ARGUMENT || s == PW85_ERR_NOT_SPD) CHECK(kNan, all_nan(o, 2), fn, s);
    }
  }
}


// The batch calls over the scene {0, r}, pairs (0, 1) and (1, 0): each pair
// gives the bits of the one-pair call (r12 = r and -r, exactly).
void check_batch(Input const &in) {
  double const *r = in.r, *q1 = in.q1, *q2 = in.q2;
  double const centres[6] = {0.0, 0.0, 0.0, r[0], r[1], r[2]};
  double q[12];
  std::memcpy(q, q1, 48);
  std::memcpy(q + 6, q2, 48);
  long long const pairs[4] = {0, 1, 1, 0};
  double const mr[3] = {0.0 - r[0], 0.0 - r[1], 0.0 - r[2]};
  int st[2];

  int ov[2];
  pw85_overlap_batch(2, centres, q, 2, pairs, ov, st, 1);
  CHECK(kBatch, ov[0] == pw85_overlap(r, q1, q2) && ov[1] == pw85_overlap(mr, q2, q1),
        "pw85_overlap_batch", ov[0]);

  double out[4], one[2];
  pw85_contact_function_batch(2, centres, q, 2, pairs, out, st, 1);
  int s = pw85_contact_function(r, q1, q2, one);
  CHECK(kBatch, st[0] == s && same_bits(out, one, sizeof one), "pw85_contact_function_batch", s);
  s = pw85_contact_function(mr, q2, q1, one);
  CHECK(kBatch, st[1] == s && same_bits(out + 2, one, sizeof one), "pw85_contact_function_batch", s);

  pw85_contact_t c[2], c1;
  pw85_contact_batch(2, centres, q, 2, pairs, c, st, 1);
  s = pw85_contact(r, q1, q2, &c1);
  if (!skip_check[kBatch] && !(st[0] == s && same_bits(&c[0], &c1, sizeof c1))) {
    double const *a = &c[0].mu2, *b = &c1.mu2;
    for (std::size_t i = 0; i < sizeof c1 / sizeof(double); ++i)
      std::fprintf(stderr, "field %zu: batch %a, one pair %a\n", i, a[i], b[i]);
  }
  CHECK(kBatch, st[0] == s && same_bits(&c[0], &c1, sizeof c1), "pw85_contact_batch", s);
  s = pw85_contact(mr, q2, q1, &c1);
  CHECK(kBatch, st[1] == s && same_bits(&c[1], &c1, sizeof c1), "pw85_contact_batch", s);
}

}  // namespace fuzz

extern "C" int LLVMFuzzerInitialize(int *, char ***) {
  using fuzz::check_name;
  if (char const *skip = std::getenv("PW85_FUZZ_SKIP")) {
    for (int c = 0; c < fuzz::kChecks; ++c) {
      std::size_t const n = std::strlen(check_name[c]);
      for (char const *p = skip; (p = std::strstr(p, check_name[c])) != nullptr; p += n)
        if ((p == skip || p[-1] == ',') && (p[n] == '\0' || p[n] == ','))
          fuzz::skip_check[c] = true;
    }
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(std::uint8_t const *data, std::size_t size) {
  unsigned char buf[2 + 34 * 8] = {};
  if (size > 0) std::memcpy(buf, data, size < sizeof buf ? size : sizeof buf);
  unsigned const mode = buf[0];
  double v[34];
  std::memcpy(v, buf + 2, sizeof v);
  fuzz::Input in;
  in.method = static_cast<signed char>(buf[1]);
  std::memcpy(in.r, v, sizeof in.r);
  if (mode & 1) fuzz::build_form(v + 3, in.q1);
  else std::memcpy(in.q1, v + 3, sizeof in.q1);
  if (mode & 2) fuzz::build_form(v + 9, in.q2);
  else std::memcpy(in.q2, v + 9, sizeof in.q2);
  if (mode & 4) in.r[0] = in.r[1] = in.r[2] = 0.0;
  if (mode & 8)
    for (double &x : in.r) x = -x;
  if (mode & 64) in.r[1] = in.r[2] = 0.0;
  in.lambda = v[15];
  in.theta = v[16];
  in.has_box = (mode & 16) != 0;
  std::memcpy(in.box, v + 17, sizeof in.box);
  if (!(mode & 32)) in.box[3] = in.box[4] = in.box[5] = 0.0;
  in.with_time = (mode & 128) != 0;
  std::memcpy(in.v12, v + 23, sizeof in.v12);
  std::memcpy(in.w1, v + 26, sizeof in.w1);
  std::memcpy(in.w2, v + 29, sizeof in.w2);
  in.t_max = v[32];
  in.scale = v[33];

  fuzz::check_one_pair(in);
  fuzz::check_batch(in);
  fuzz::check_pairs(in);
  fuzz::check_scene(in);
  fuzz::check_configuration(in);
  fuzz::check_derivatives(in);
  if (in.with_time) fuzz::check_contact_time(in);
  return 0;
}
