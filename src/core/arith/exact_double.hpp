// Doubles as exact big integers (arith/bigint.hpp): every finite double is
// an odd integer times a power of two, so a set of doubles times a common
// power of two is a set of integers. For the exact stage of the overlap
// predicate (overlap/overlap_exact.cpp) and the exact positive-definiteness
// decision (common/spd.cpp).
#pragma once

#include <cmath>
#include <cstdint>

#include "arith/bigint.hpp"

namespace pw85 {
namespace exact {

// x = sign * m * 2^e with m odd (x != 0); sign 0 for x = 0.
struct Decomposed {
  int sign;
  std::uint64_t m;
  int e;
};

inline Decomposed decompose(double x) noexcept {
  Decomposed d{0, 0, 0};
  if (x == 0.0) return d;
  int ex;
  double const f = std::frexp(std::fabs(x), &ex);  // |x| = f 2^ex, f in [0.5, 1)
  std::uint64_t m = static_cast<std::uint64_t>(std::ldexp(f, 53));
  int e = ex - 53;
  while ((m & 1u) == 0) {
    m >>= 1;
    ++e;
  }
  d.sign = x > 0 ? 1 : -1;
  d.m = m;
  d.e = e;
  return d;
}

// Sets *out[i] = x[i] * 2^-emin as exact integers (n <= 12); returns emin
// (0 if every entry vanishes). Sets ctx.overflow when the spread of the
// exponents exceeds the capacity of BigInt.
inline int to_integers(Ctx &ctx, double const *x, int n, BigInt *const *out) noexcept {
  Decomposed d[12];
  int emin = 0;
  bool any = false;
  for (int i = 0; i < n; ++i) {
    d[i] = decompose(x[i]);
    if (d[i].sign != 0 && (!any || d[i].e < emin)) {
      emin = d[i].e;
      any = true;
    }
  }
  for (int i = 0; i < n; ++i) {
    long const shift = static_cast<long>(d[i].e) - emin;
    if (d[i].sign != 0 && shift > 64L * kLimbs) {
      ctx.overflow = true;
      set_zero(*out[i]);
      continue;
    }
    set_shifted(ctx, *out[i], d[i].sign, d[i].m, static_cast<int>(shift));
  }
  return emin;
}

}  // namespace exact
}  // namespace pw85
