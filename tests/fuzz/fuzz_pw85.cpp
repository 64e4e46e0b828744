// libFuzzer target over every public function of libpw85 and libpw85_legacy:
// each input is decoded into a pair of ellipsoids (and the scalars the other
// functions take), every function is called, and the promises of
// include/pw85.h and include/pw85_legacy.h are checked; a violated promise
// prints its name and calls __builtin_trap(). Built by meson with
// -Dfuzz=true (Clang only, tests/fuzz/meson.build); .ci/fuzz runs it.
//
// Input layout (shorter inputs are padded with zeros):
//   byte 0      mode: bit 0 (bit 1): q1 (q2) built from its six doubles as
//               R diag(s) R^T, s the first three, R from three angles,
//               instead of taken raw; bit 2: r12 = 0; bit 3: r12 negated
//   byte 1      method (signed) for pw85_contact_function_method, pw85_dca
//   17 doubles  r12[3], q1[6], q2[6], lambda, theta_tol
//
// Checks (names for PW85_FUZZ_SKIP, a comma-separated list of checks not to
// make, e.g. PW85_FUZZ_SKIP=lambda,finite):
//   status       the status is one the function documents
//   finite       the estimates documented as written are finite
//   nan          outputs are NaN on the errors documented so
//   lambda       lambda in [0, 1] whenever a result is written
//   swap         pw85_overlap's verdict unchanged when the ellipsoids swap
//   batch        the batch calls equal the one-pair calls, bit for bit
//   determinism  the same call twice gives the same bits
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <initializer_list>

#include "pw85.h"
#include "pw85_legacy.h"

namespace {

bool skip_check[8];
enum Check { kStatus, kFinite, kNan, kLambda, kSwap, kBatch, kDeterminism, kChecks };
char const *const check_name[kChecks] = {"status", "finite", "nan", "lambda",
                                         "swap", "batch", "determinism"};

int current_method;  // method of the pw85_contact_function_method/pw85_dca call checked

[[noreturn]] void violated(Check c, char const *fn, int status) {
  std::fprintf(stderr, "promise violated: %s of %s (status %d, method %d)\n", check_name[c], fn,
               status, current_method);
  __builtin_trap();
}

#define CHECK(check, cond, fn, status)                                        \
  do {                                                                        \
    if (!skip_check[check] && !(cond)) violated(check, fn, status);           \
  } while (0)

bool in_list(int s, std::initializer_list<int> l) {
  for (int x : l)
    if (s == x) return true;
  return false;
}
bool all_nan(double const *v, int n) {
  for (int i = 0; i < n; ++i)
    if (!std::isnan(v[i])) return false;
  return true;
}
bool all_finite(double const *v, int n) {
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}
bool same_bits(void const *a, void const *b, std::size_t n) { return std::memcmp(a, b, n) == 0; }
bool lambda_ok(double l) { return l >= 0.0 && l <= 1.0; }

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

void check_one_pair(double const *r, double const *q1, double const *q2, int method,
                    double lambda, double theta) {
  for (int m = PW85_METHOD_DEFAULT; m <= PW85_METHOD_ZHENG; ++m) {
    check_contact_function_method(r, q1, q2, m);
    check_dca(r, q1, q2, m);
  }
  check_contact_function_method(r, q1, q2, method);
  check_dca(r, q1, q2, method);

  {
    char const *fn = "pw85_contact_function";
    double o[2], o2[2];
    int const s = pw85_contact_function(r, q1, q2, o);
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
    CHECK(kDeterminism, v == pw85_overlap(r, q1, q2), fn, v);
    CHECK(kStatus, in_list(v, {0, 1, PW85_ERR_INVALID_ARGUMENT, PW85_ERR_NOT_SPD,
                               PW85_ERR_INACCURATE}), fn, v);
    int const w = pw85_overlap(mr, q2, q1);
    // Both decided: the same verdict. (One may decide while the other runs
    // out of capacity, PW85_ERR_INACCURATE: documented for entries spanning
    // more than about 2^300.) Invalid arguments are invalid either way.
    if (v >= 0 && w >= 0) CHECK(kSwap, v == w, fn, v);
    if (v == PW85_ERR_INVALID_ARGUMENT) CHECK(kSwap, v == w, fn, v);
    // PW85_ERR_NOT_SPD is "not positive definite in floating point or, for
    // the pairs reaching the exact stage, exactly" (pw85.h): a matrix
    // positive definite in floating point but not exactly may be refused in
    // one order, at the exact stage, and decided by a filter in the other.
    // A verdict against NOT_SPD is allowed only then: when the floating-point
    // test (the one of pw85_contact_function_method) accepts both matrices.
    if (v == PW85_ERR_NOT_SPD && w != v) {
      pw85_result res;
      CHECK(kSwap,
            w >= 0 && pw85_contact_function_method(r, q1, q2, PW85_METHOD_DEFAULT, &res) !=
                          PW85_ERR_NOT_SPD,
            fn, v);
    }
  }
  {
    char const *fn = "pw85_contact";
    pw85_contact_t c, c2;
    int const s = pw85_contact(r, q1, q2, &c);
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
    int const s2 = pw85_ellipsoid(r, axes, qq);
    CHECK(kDeterminism, s == s2 && same_bits(q, qq, sizeof q), "pw85_ellipsoid", s);
    CHECK(kStatus, in_list(s, {PW85_OK, PW85_ERR_INVALID_ARGUMENT, PW85_ERR_NOT_SPD,
                               PW85_ERR_NOT_ORTHONORMAL, PW85_ERR_RANGE}), "pw85_ellipsoid", s);
    if (s != PW85_OK) CHECK(kNan, all_nan(q, 6), "pw85_ellipsoid", s);
    int const sr = pw85_ellipsoid_rotation(r, axes, q);
    int const sr2 = pw85_ellipsoid_rotation(r, axes, qq);
    CHECK(kDeterminism, sr == sr2 && same_bits(q, qq, sizeof q), "pw85_ellipsoid_rotation", sr);
    CHECK(kStatus, in_list(sr, {PW85_OK, PW85_ERR_INVALID_ARGUMENT, PW85_ERR_NOT_SPD,
                                PW85_ERR_NOT_ORTHONORMAL, PW85_ERR_RANGE}),
          "pw85_ellipsoid_rotation", sr);
    if (sr != PW85_OK) CHECK(kNan, all_nan(q, 6), "pw85_ellipsoid_rotation", sr);
    int const sq = pw85_ellipsoid_quat(r, q2, q);
    int const sq2 = pw85_ellipsoid_quat(r, q2, qq);
    CHECK(kDeterminism, sq == sq2 && same_bits(q, qq, sizeof q), "pw85_ellipsoid_quat", sq);
    CHECK(kStatus, in_list(sq, {PW85_OK, PW85_ERR_INVALID_ARGUMENT, PW85_ERR_NOT_SPD,
                                PW85_ERR_NOT_ORTHONORMAL, PW85_ERR_RANGE}),
          "pw85_ellipsoid_quat", sq);
    if (sq != PW85_OK) CHECK(kNan, all_nan(q, 6), "pw85_ellipsoid_quat", sq);
    double ra[3], ra2[3], ro[9], ro2[9], qu[4], qu2[4];
    int const sa = pw85_ellipsoid_axes(q1, ra, ro, qu);
    int const sa2 = pw85_ellipsoid_axes(q1, ra2, ro2, qu2);
    CHECK(kDeterminism, sa == sa2 && same_bits(ra, ra2, sizeof ra) &&
          same_bits(ro, ro2, sizeof ro) && same_bits(qu, qu2, sizeof qu), "pw85_ellipsoid_axes", sa);
    CHECK(kStatus, in_list(sa, {PW85_OK, PW85_ERR_INVALID_ARGUMENT, PW85_ERR_NOT_SPD,
                                PW85_ERR_NO_CONVERGENCE, PW85_ERR_INACCURATE}),
          "pw85_ellipsoid_axes", sa);
    if (sa != PW85_OK && sa != PW85_ERR_NO_CONVERGENCE)
      CHECK(kNan, all_nan(ra, 3) && all_nan(ro, 9) && all_nan(qu, 4), "pw85_ellipsoid_axes", sa);
    if (sa == PW85_OK) {
      CHECK(kStatus, ra[0] <= ra[1] && ra[1] <= ra[2] && qu[0] >= 0.0, "pw85_ellipsoid_axes", sa);
      // The outputs give a q back through both constructors (pw85.h).
      CHECK(kStatus, pw85_ellipsoid_rotation(ra, ro, qq) == PW85_OK &&
                         pw85_ellipsoid_quat(ra, qu, qq) == PW85_OK,
            "pw85_ellipsoid_axes", sa);
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
void check_batch(double const *r, double const *q1, double const *q2) {
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

}  // namespace

extern "C" int LLVMFuzzerInitialize(int *, char ***) {
  if (char const *skip = std::getenv("PW85_FUZZ_SKIP")) {
    for (int c = 0; c < kChecks; ++c) {
      std::size_t const n = std::strlen(check_name[c]);
      for (char const *p = skip; (p = std::strstr(p, check_name[c])) != nullptr; p += n)
        if ((p == skip || p[-1] == ',') && (p[n] == '\0' || p[n] == ',')) skip_check[c] = true;
    }
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(std::uint8_t const *data, std::size_t size) {
  unsigned char buf[2 + 17 * 8] = {};
  std::memcpy(buf, data, size < sizeof buf ? size : sizeof buf);
  unsigned const mode = buf[0];
  int const method = static_cast<signed char>(buf[1]);
  double v[17];
  std::memcpy(v, buf + 2, sizeof v);
  double r[3] = {v[0], v[1], v[2]}, q1[6], q2[6];
  if (mode & 1) build_form(v + 3, q1);
  else std::memcpy(q1, v + 3, sizeof q1);
  if (mode & 2) build_form(v + 9, q2);
  else std::memcpy(q2, v + 9, sizeof q2);
  if (mode & 4) r[0] = r[1] = r[2] = 0.0;
  if (mode & 8)
    for (double &x : r) x = -x;
  check_one_pair(r, q1, q2, method, v[15], v[16]);
  check_batch(r, q1, q2);
  return 0;
}
