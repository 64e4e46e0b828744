// positive_definite and positive_definite_2d (common/spd.hpp): the
// floating-point certificates of spd.hpp, on an exact power-of-two
// rescaling of the matrix when its entries lie outside their range, and the
// minors in exact integer arithmetic where they cannot decide (nearly
// singular matrices, entries spanning more than the double range).
#include "common/spd.hpp"

#include <cmath>

#include "arith/bigint.hpp"
#include "arith/exact_double.hpp"
#include "common/magnitude.hpp"

namespace pw85 {

namespace {

// The certificates' verdict: +1 positive definite (certain_spd), 0 not
// (a diagonal entry <= 0 or a minor certainly < 0), -1 undecided. n = 6
// (Sym3 storage) or 3 (Sym2 storage a00 a01 a11, as the 3x3 matrix
// diag(A, a00): positive definite iff A is).
int certify(double const *a, int n) noexcept {
  double const b[6] = {a[0], a[1], n == 6 ? a[2] : 0.0, n == 6 ? a[3] : a[2],
                       n == 6 ? a[4] : 0.0, n == 6 ? a[5] : a[0]};
  if (!(b[0] > 0.0) || !(b[3] > 0.0) || !(b[5] > 0.0)) return 0;
  if (certain_spd(b)) return 1;
  double m2, e2, m3, e3;
  spd_minors(b[0], b[1], b[2], b[3], b[4], b[5], m2, e2, m3, e3);
  if (m2 < -e2 || m3 < -e3) return 0;
  return -1;
}

// The minors in exact integer arithmetic: a = 2^e A_int, and the sign of
// each minor of a is that of the same minor of A_int.
bool exact_minors_positive(double const *a, int n) noexcept {
  using namespace exact;
  Ctx ctx;
  BigInt x[6], t1, t2, t3;
  BigInt *out[6] = {&x[0], &x[1], &x[2], &x[3], &x[4], &x[5]};
  to_integers(ctx, a, n, out);
  if (ctx.overflow) return false;  // cannot happen: the spread of doubles fits
  if (n == 6) {
    BigInt &a00 = x[0], &a01 = x[1], &a02 = x[2], &a11 = x[3], &a12 = x[4], &a22 = x[5];
    if (a00.s <= 0) return false;
    mul(ctx, t1, a00, a11);
    mul(ctx, t2, a01, a01);
    sub(ctx, t1, t1, t2);
    if (t1.s <= 0) return false;
    // det = a00 (a11 a22 - a12^2) + a01 (a02 a12 - a01 a22) + a02 (a01 a12 - a02 a11)
    BigInt det;
    set_zero(det);
    BigInt const *const cof[3][5] = {{&a00, &a11, &a22, &a12, &a12},
                                     {&a01, &a02, &a12, &a01, &a22},
                                     {&a02, &a01, &a12, &a02, &a11}};
    for (int i = 0; i < 3; ++i) {
      mul(ctx, t1, *cof[i][1], *cof[i][2]);
      mul(ctx, t2, *cof[i][3], *cof[i][4]);
      sub(ctx, t1, t1, t2);
      mul(ctx, t3, *cof[i][0], t1);
      add(ctx, det, det, t3);
    }
    return !ctx.overflow && det.s > 0;
  }
  BigInt &a00 = x[0], &a01 = x[1], &a11 = x[2];
  if (a00.s <= 0) return false;
  mul(ctx, t1, a00, a11);
  mul(ctx, t2, a01, a01);
  sub(ctx, t1, t1, t2);
  return !ctx.overflow && t1.s > 0;
}

bool decide(double const *a, int n) noexcept {
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(a[i])) return false;  // the exact path takes finite values only
  double const m = max_abs(a, n);
  if (m <= kSpdFilterHi) {
    int const v = certify(a, n);
    if (v >= 0) return v == 1;
  }
  // 2^-e a, max |entry| in [0.5, 1): the certificate decides it unless
  // the matrix is nearly singular, when the scaling is exact (no entry
  // loses bits).
  if (m > 0.0) {
    int const e = max_exponent(a, n);
    double s[6];
    bool scaled_exactly = true;
    for (int i = 0; i < n; ++i) {
      s[i] = std::ldexp(a[i], -e);
      scaled_exactly = scaled_exactly && std::ldexp(s[i], e) == a[i];
    }
    if (scaled_exactly) {
      int const v = certify(s, n);
      if (v >= 0) return v == 1;
    }
  }
  return exact_minors_positive(a, n);
}

}  // namespace

bool positive_definite(double const *a) noexcept { return decide(a, 6); }

bool positive_definite_2d(double const *a) noexcept { return decide(a, 3); }

}  // namespace pw85
