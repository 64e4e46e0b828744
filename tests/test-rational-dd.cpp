/* The coefficient step of PW85_METHOD_DEFAULT on x86-64-v4 (src/core/
 * eval/f_coefficients_dd.hpp; docs/methods.md, "PW85_METHOD_DEFAULT"), tested at
 * the library level: the one test program that includes internal headers,
 * because the public API cannot tell which path a call took. It checks the
 * error bounds the code states, against references computed here in
 * __float128 from the same double inputs (every product of two doubles is
 * exact in binary128, and the few roundings of the references, at 2^-113
 * of their terms, stay far below u for the cancellations these pairs have):
 *  - whenever coefficients_dd accepts, each of the seven
 *    coefficients (M13) is within 2.2 u of the exact value;
 *  - f_eval_coefficients's f is within kCoefficientRel = 16 u of the exact f (from
 *    the exact coefficients), and its f' within the bound edf it returns;
 *  - det_precise (d0, d3 where the double-double sum cancels beyond its
 *    bound) is within 1.13 u of det Q whenever it accepts, against the
 *    exact determinant in big integers (src/core/arith/bigint.hpp: a
 *    __float128 reference loses 2^-113 of the terms, too much for the
 *    cancellations, up to 2^75, of these pairs), and accepts such pairs;
 *  - a pair whose d0 cancels beyond what the double-double sums certify
 *    (det Q1 ~ 1e-15 of its terms) still takes the coefficient step, through
 *    det_precise; a singular Q1 (det = 0) is declined.
 * Skipped where the library has no x86-64-v4 variants (CPU without AVX-512,
 * or built with -Disa_dispatch=false). */
#include <cmath>

#include <glib.h>

#include "arith/bigint.hpp"
#include "eval/f_coefficients_dd.hpp"
#include "../bench/bench_common.hpp"

namespace {

#if PW85_ISA_LEVELS && defined(__SIZEOF_FLOAT128__)
typedef __float128 real;
constexpr double kU = 0x1p-53;

struct Pair {
  pw85::Vec3 r;
  pw85::Sym3 q1, q2;
};

// The kernel and the evaluation compiled for x86-64-v4, as in the library
// (default_variants.cpp inlines them into its v4 variant).
// dd_ok: the double-double coefficients passed (without det_precise).
__attribute__((target("arch=x86-64-v4"), noinline)) bool coefficients_v4(Pair const &p,
                                                                        pw85::CoefficientsDD &k,
                                                                        bool *dd_ok = nullptr) {
  bool const dd = pw85::coefficients_dd(p.r, p.q1, p.q2, k);
  if (dd_ok) *dd_ok = dd;
  return dd || pw85::coefficients_dets_precise(p.q1, p.q2, k);
}

__attribute__((target("arch=x86-64-v4"), noinline)) bool eval_v4(double lambda,
                                                                pw85::CoefficientsDD const &k,
                                                                pw85::CoefficientEval &e) {
  return pw85::f_eval_coefficients(lambda, k, e);
}

__attribute__((target("arch=x86-64-v4"), noinline)) bool det_v4(pw85::Sym3 const &q,
                                                                double &det) {
  return pw85::det_precise(q.a, det);
}

// Exact determinants in big integers: every double is m 2^e, m an integer
// below 2^53.
using pw85::exact::BigInt;
using pw85::exact::Ctx;

int exponent(double x) {  // e of x = m 2^e, x != 0
  int e;
  std::frexp(x, &e);
  return e - 53;
}

void to_big(Ctx &ctx, double x, int e0, BigInt &out) {  // x 2^-e0, exactly
  if (x == 0.0) {
    pw85::exact::set_zero(out);
    return;
  }
  int e;
  double const f = std::frexp(std::fabs(x), &e);
  auto const m = static_cast<std::uint64_t>(std::ldexp(f, 53));
  pw85::exact::set_shifted(ctx, out, x > 0.0 ? 1 : -1, m, e - 53 - e0);
}

void mul3(Ctx &ctx, BigInt &r, BigInt const &a, BigInt const &b, BigInt const &c) {
  BigInt t;
  pw85::exact::mul(ctx, t, a, b);
  pw85::exact::mul(ctx, r, t, c);
}

// The smallest exponent of the entries of q.
int min_exponent(pw85::Sym3 const &q) {
  int emin = 1 << 20;
  for (int i = 0; i < 6; ++i)
    if (q[i] != 0.0 && exponent(q[i]) < emin) emin = exponent(q[i]);
  return emin;
}

// u = det Q 2^(-3 emin), exactly (emin <= min_exponent(q)).
void exact_det(Ctx &ctx, pw85::Sym3 const &q, int emin, BigInt &u) {
  BigInt x[6], t, dq;
  for (int i = 0; i < 6; ++i) to_big(ctx, q[i], emin, x[i]);
  // det Q = q00 q11 q22 - q00 q12^2 - q01^2 q22 + 2 q01 q02 q12 - q02^2 q11.
  mul3(ctx, dq, x[0], x[3], x[5]);
  mul3(ctx, t, x[0], x[4], x[4]);
  pw85::exact::sub(ctx, u, dq, t);
  mul3(ctx, t, x[1], x[1], x[5]);
  pw85::exact::sub(ctx, dq, u, t);
  mul3(ctx, t, x[1], x[2], x[4]);
  pw85::exact::add(ctx, u, dq, t);
  pw85::exact::add(ctx, dq, u, t);
  mul3(ctx, t, x[2], x[2], x[3]);
  pw85::exact::sub(ctx, u, dq, t);
}

// det Q to 113 bits (its three leading limbs).
real det_real(pw85::Sym3 const &q) {
  Ctx ctx;
  int const emin = min_exponent(q);
  BigInt u;
  exact_det(ctx, q, emin, u);
  real v = 0;
  int const lo = u.n > 3 ? u.n - 3 : 0;
  for (int i = u.n - 1; i >= lo; --i) v = v * 0x1p64 + (real)u.d[i];
  for (int i = 0; i < lo; ++i) v = v * 0x1p64;
  v = v * (real)std::ldexp(1.0, emin) * (real)std::ldexp(1.0, emin) * (real)std::ldexp(1.0, emin);
  return u.s < 0 ? -v : v;
}

// |det - det Q| <= (num / den) u det Q, det Q > 0 (exact comparison).
bool det_within(pw85::Sym3 const &q, double det, std::uint64_t num, std::uint64_t den) {
  Ctx ctx;
  int emin = min_exponent(q);
  if (det != 0.0 && exponent(det) < 3 * emin) emin = (exponent(det) - 2) / 3 - 1;
  BigInt u, d, diff, lhs, rhs, k;
  exact_det(ctx, q, emin, u);
  to_big(ctx, det, 3 * emin, d);
  pw85::exact::sub(ctx, diff, d, u);
  if (ctx.overflow) g_error("big integer overflow");
  if (u.s <= 0) return false;
  // |diff| 2^53 den <= num |det Q|.
  diff.s = diff.s != 0 ? 1 : 0;
  pw85::exact::set_shifted(ctx, k, 1, den, 53);
  pw85::exact::mul(ctx, lhs, diff, k);
  pw85::exact::set_shifted(ctx, k, 1, num, 0);
  pw85::exact::mul(ctx, rhs, u, k);
  return pw85::exact::cmp_mag(lhs, rhs) <= 0;
}

// The scenes of bench_contact (src/tools/bench_common.hpp): semi-axes
// log-uniform in [lo, hi], random orientations, centre distances from deep
// overlap to far apart.
Pair random_pair(bench::Rng &g, double lo, double hi) {
  Pair p;
  double a[3], rot[3][3];
  bench::random_axes(g, lo, hi, a, rot);
  double const a1 = std::fmax(a[0], std::fmax(a[1], a[2]));
  bench::q_from_axes(a, rot, p.q1.a);
  bench::random_axes(g, lo, hi, a, rot);
  double const a2 = std::fmax(a[0], std::fmax(a[1], a[2]));
  bench::q_from_axes(a, rot, p.q2.a);
  bench::random_offset(g, a1 + a2, bench::kContactSpan, p.r.x);
  return p;
}

// Full symmetric matrix of Sym3 storage (00 01 02 11 12 22).
void full(pw85::Sym3 const &q, real m[3][3]) {
  int const idx[3][3] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m[i][j] = q[idx[i][j]];
}

void adjugate(real const m[3][3], real c[3][3]) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      int const i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
      c[i][j] = m[i1][j1] * m[i2][j2] - m[i1][j2] * m[i2][j1];
    }
}

real quad(real const c[3][3], pw85::Vec3 const &r) {
  real s = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) s += c[i][j] * (real)r[i] * (real)r[j];
  return s;
}

real trace_product(real const a[3][3], real const b[3][3]) {
  real s = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) s += a[i][j] * b[j][i];
  return s;
}

// The seven coefficients (M13): a0 = r^T adj(Q1) r, a1 = r^T M r,
// a2 = r^T adj(Q2) r (M = adj(Q1 + Q2) - adj(Q1) - adj(Q2), the mixed
// adjugate), d0 = det Q1, d1 = tr(adj(Q1) Q2), d2 = tr(Q1 adj(Q2)),
// d3 = det Q2.
void exact_coefficients(Pair const &p, real c[7]) {
  real m1[3][3], m2[3][3], m12[3][3], c1[3][3], c2[3][3], c12[3][3], cm[3][3];
  full(p.q1, m1);
  full(p.q2, m2);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m12[i][j] = m1[i][j] + m2[i][j];  // exact: 54 bits
  adjugate(m1, c1);
  adjugate(m2, c2);
  adjugate(m12, c12);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) cm[i][j] = c12[i][j] - c1[i][j] - c2[i][j];
  c[0] = quad(c1, p.r);
  c[1] = quad(cm, p.r);
  c[2] = quad(c2, p.r);
  // det Q1, det Q2 from exact big integers: their terms cancel by up to
  // 2^75 in class 3, beyond the 113 bits of __float128.
  c[3] = det_real(p.q1);
  c[4] = trace_product(c1, m2);
  c[5] = trace_product(m1, c2);
  c[6] = det_real(p.q2);
}

// f = s t A / B and f' from exact coefficients.
void exact_f(real const c[7], double lambda, real &f, real &df) {
  real const t = lambda, s = 1 - t;
  real const A = c[0] * s * s + c[1] * s * t + c[2] * t * t;
  real const B = c[3] * s * s * s + c[4] * s * s * t + c[5] * s * t * t + c[6] * t * t * t;
  real const A1 = 2 * (c[2] * t - c[0] * s) + c[1] * (s - t);
  real const B1 = 3 * (c[6] * t * t - c[3] * s * s) + c[4] * (s * s - 2 * s * t) +
                  c[5] * (2 * s * t - t * t);
  real const phi = A / B, phi1 = (A1 - phi * B1) / B;
  f = s * t * phi;
  df = (s - t) * phi + s * t * phi1;
}

double rel(real x, real ref) { return (double)((x - ref) / ref); }

// Classes of bench_contact (semi-axes in [lo, hi]) and needles / discs.
struct Class {
  double lo, hi;
};
Class const kClasses[] = {{0.5, 2.0}, {0.1, 10.0}, {0.01, 100.0}, {0.001, 1000.0}, {1e-5, 10.0}};
constexpr int kPairsPerClass = 4000;

void test_coefficients(void) {
  if (!__builtin_cpu_supports("x86-64-v4")) {
    g_test_skip("CPU without x86-64-v4 (AVX-512): the coefficient step is not used");
    return;
  }
  bench::Rng g{20261122};
  double worst = 0.0;
  int accepted = 0, total = 0;
  for (Class const &cl : kClasses) {
    int dd_failed = 0, rescued = 0;
    for (int n = 0; n < kPairsPerClass; ++n) {
      Pair const p = random_pair(g, cl.lo, cl.hi);
      pw85::CoefficientsDD k;
      ++total;
      bool dd_ok;
      bool const ok = coefficients_v4(p, k, &dd_ok);
      dd_failed += !dd_ok;
      rescued += !dd_ok && ok;
      if (!ok) continue;
      ++accepted;
      real c[7];
      exact_coefficients(p, c);
      // d0 and d3 (possibly from det_precise): exact references.
      if (!det_within(p.q1, k.c[3] / k.scale, 11, 5) || !det_within(p.q2, k.c[6] / k.scale, 11, 5))
        g_error("d0 or d3 beyond 2.2 u of the exact determinant, semi-axes [%g, %g]", cl.lo,
                cl.hi);
      for (int i = 0; i < 7; ++i) {
        if (i == 3 || i == 6) continue;
        double const e = std::fabs(rel(k.c[i] / k.scale, c[i]));  // (exact: a power of two)
        if (e > worst) worst = e;
        if (!(e <= 2.2 * kU))
          g_error("coefficient %d: relative error %.3g u (> 2.2 u), semi-axes [%g, %g]", i,
                  e / kU, cl.lo, cl.hi);
      }
    }
    g_test_message("semi-axes [%g, %g]: double-double test failed for %d of %d pairs, %d of "
                   "them accepted with det_precise", cl.lo, cl.hi, dd_failed, kPairsPerClass,
                   rescued);
  }
  g_test_message("coefficients: %d of %d pairs accepted; max relative error of a0, a1, a2, d1, d2 %.3f u", accepted,
                 total, worst / kU);
  // Most pairs must take the coefficient step (otherwise it is not tested).
  g_assert_cmpint(accepted, >=, total * 9 / 10);
}

// det_precise on the matrices of bench_contact's classes and wider: within
// 1.13 u of the exact determinant whenever accepted; accepted for every
// matrix of classes 0-3 (cancellation up to ~2^75, far below its 2^87).
void test_det_precise(void) {
  if (!__builtin_cpu_supports("x86-64-v4")) {
    g_test_skip("CPU without x86-64-v4 (AVX-512): the coefficient step is not used");
    return;
  }
  bench::Rng g{4127};
  Class const classes[] = {{0.5, 2.0}, {0.1, 10.0}, {0.01, 100.0}, {0.001, 1000.0},
                           {1e-4, 1e4}, {1e-5, 10.0}};
  for (int c = 0; c < 6; ++c) {
    int accepted = 0;
    for (int n = 0; n < kPairsPerClass; ++n) {
      Pair const p = random_pair(g, classes[c].lo, classes[c].hi);
      double det;
      for (pw85::Sym3 const *q : {&p.q1, &p.q2}) {
        if (!det_v4(*q, det)) continue;
        ++accepted;
        // 1.13 u < 17 / 15 u.
        if (!det_within(*q, det, 17, 15))
          g_error("det_precise beyond 1.13 u of the exact determinant, semi-axes [%g, %g]",
                  classes[c].lo, classes[c].hi);
      }
    }
    g_test_message("det_precise: %d of %d matrices accepted, semi-axes [%g, %g]", accepted,
                   2 * kPairsPerClass, classes[c].lo, classes[c].hi);
    if (c <= 3) g_assert_cmpint(accepted, ==, 2 * kPairsPerClass);
  }
  // Exact cases: det = (2^52 + 1)^2 - 2^104 = 2^53 + 1 (terms ~2^104), and
  // a singular matrix (det = 0: declined).
  double const a = 0x1p52 + 1.0, b = 0x1p52;
  double det;
  pw85::Sym3 q{{a, b, 0.0, a, 0.0, 1.0}};
  g_assert_true(det_v4(q, det));
  g_assert_true(det_within(q, det, 17, 15));
  g_assert_false(det_within(q, det + 4.0, 17, 15));  // 3 u off: the check fails
  q = pw85::Sym3{{1.0, 1.0, 0.0, 1.0, 0.0, 1.0}};
  g_assert_false(det_v4(q, det));
}

void test_f_bounds(void) {
  if (!__builtin_cpu_supports("x86-64-v4")) {
    g_test_skip("CPU without x86-64-v4 (AVX-512): the coefficient step is not used");
    return;
  }
  bench::Rng g{20261123};
  double worst_f = 0.0, worst_df = 0.0;  // relative to f, and to edf
  for (Class const &cl : kClasses)
    for (int n = 0; n < kPairsPerClass; ++n) {
      Pair const p = random_pair(g, cl.lo, cl.hi);
      pw85::CoefficientsDD k;
      if (!coefficients_v4(p, k)) continue;
      real c[7];
      exact_coefficients(p, c);
      double const lambdas[3] = {g.uniform(), 1e-6 + 1e-3 * g.uniform(), 1.0 - 1e-3 * g.uniform()};
      for (double const lambda : lambdas) {
        if (!(lambda > 0.0 && lambda < 1.0)) continue;
        pw85::CoefficientEval e;
        if (!eval_v4(lambda, k, e)) g_error("f_eval_coefficients failed at %g", lambda);
        real f, df;
        exact_f(c, lambda, f, df);
        double const ef = std::fabs(rel(e.f, f));
        double const edf = std::fabs((double)((e.df - df))) / e.edf;
        worst_f = ef > worst_f ? ef : worst_f;
        worst_df = edf > worst_df ? edf : worst_df;
        if (!(ef <= 16.0 * kU))
          g_error("f: relative error %.3g u (> 16 u) at lambda = %g", ef / kU, lambda);
        if (!(edf <= 1.0)) g_error("f': error %.3g times its bound at lambda = %g", edf, lambda);
      }
    }
  g_test_message("f: max relative error %.3f u (bound 16 u); f': max error / edf %.3g", worst_f / kU,
                 worst_df);
}

void test_cancellation(void) {
  if (!__builtin_cpu_supports("x86-64-v4")) {
    g_test_skip("CPU without x86-64-v4 (AVX-512): the coefficient step is not used");
    return;
  }
  // Q1 = diag(1, 1, 1e-15) rotated: det Q1 = 1e-15 while the terms of its
  // double-double sum are ~1, a cancellation of 1e15 > 2^45 (the bound's
  // limit, f_coefficients_dd.hpp): d0 comes from det_precise.
  double const c = std::cos(0.3), s = std::sin(0.3), e = 1e-15;
  Pair p;
  p.q1 = pw85::Sym3{{c * c + s * s * e, c * s * (1 - e), 0.0, s * s + c * c * e, 0.0, 1.0}};
  p.q2 = pw85::Sym3{{2.0, 0.1, 0.2, 3.0, 0.3, 4.0}};
  p.r = pw85::Vec3{{1.0, 2.0, 3.0}};
  pw85::CoefficientsDD k;
  g_assert_true(coefficients_v4(p, k));
  g_assert_true(det_within(p.q1, k.c[3] / k.scale, 11, 5));
  // The same matrices with the small eigenvalue 1e-6: certified.
  double const e2 = 1e-6;
  p.q1 = pw85::Sym3{{c * c + s * s * e2, c * s * (1 - e2), 0.0, s * s + c * c * e2, 0.0, 1.0}};
  g_assert_true(coefficients_v4(p, k));
  // A singular Q1 (det Q1 = 0): declined.
  p.q1 = pw85::Sym3{{1.0, 1.0, 0.0, 1.0, 0.0, 1.0}};
  g_assert_false(coefficients_v4(p, k));
}
#endif

}  // namespace

int main(int argc, char **argv) {
  g_test_init(&argc, &argv, NULL);
#if PW85_ISA_LEVELS && defined(__SIZEOF_FLOAT128__)
  g_test_add_func("/rational-dd/coefficients", test_coefficients);
  g_test_add_func("/rational-dd/f-bounds", test_f_bounds);
  g_test_add_func("/rational-dd/det-precise", test_det_precise);
  g_test_add_func("/rational-dd/cancellation", test_cancellation);
#else
  g_test_add_func("/rational-dd/skipped", [] {
    g_test_skip("built without the x86-64-v4 variants (isa_dispatch=false or not GCC 12+ on x86-64)");
  });
#endif
  return g_test_run();
}
