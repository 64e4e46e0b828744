// Fixed-capacity signed integers for the exact stage of the overlap predicate
// (docs/overlap.md, section "Exact stage"). No heap allocation: a BigInt lives
// on the stack; an operation whose result would not fit sets the overflow flag
// of the context (the caller then reports kInaccurate instead of a verdict).
// Only ring operations are needed (+, -, *, shifts by powers of two).
#pragma once

#include <cstdint>
#include <cstring>

namespace pw85 {
namespace exact {

constexpr int kLimbs = 320;  // 20480 bits

struct BigInt {
  int n;   // limbs in use (d[n-1] != 0), 0 for zero
  int s;   // sign: -1, 0, +1 (0 iff n == 0)
  std::uint64_t d[kLimbs];
};

struct Ctx {
  bool overflow = false;
};

inline void set_zero(BigInt &a) noexcept {
  a.n = 0;
  a.s = 0;
}

inline void copy(BigInt &dst, BigInt const &src) noexcept {
  if (&dst == &src) return;
  dst.n = src.n;
  dst.s = src.s;
  std::memcpy(dst.d, src.d, sizeof(std::uint64_t) * static_cast<unsigned>(src.n));
}

inline void normalize(BigInt &a) noexcept {
  while (a.n > 0 && a.d[a.n - 1] == 0) --a.n;
  if (a.n == 0) a.s = 0;
}

// a = sign * m * 2^shift, m < 2^64.
inline void set_shifted(Ctx &ctx, BigInt &a, int sign, std::uint64_t m, int shift) noexcept {
  set_zero(a);
  if (m == 0 || sign == 0) return;
  int const w = shift / 64, b = shift % 64;
  if (w + 2 > kLimbs) {
    ctx.overflow = true;
    return;
  }
  for (int i = 0; i < w; ++i) a.d[i] = 0;
  a.d[w] = m << b;
  a.d[w + 1] = b ? (m >> (64 - b)) : 0;
  a.n = w + 2;
  a.s = sign;
  normalize(a);
}

// |a| <=> |b|.
inline int cmp_mag(BigInt const &a, BigInt const &b) noexcept {
  if (a.n != b.n) return a.n < b.n ? -1 : 1;
  for (int i = a.n - 1; i >= 0; --i)
    if (a.d[i] != b.d[i]) return a.d[i] < b.d[i] ? -1 : 1;
  return 0;
}

// r = |a| + |b| (r may alias a or b).
inline void add_mag(Ctx &ctx, BigInt &r, BigInt const &a, BigInt const &b) noexcept {
  BigInt const &x = a.n >= b.n ? a : b;
  BigInt const &y = a.n >= b.n ? b : a;
  int const xn = x.n, yn = y.n;
  unsigned __int128 carry = 0;
  for (int i = 0; i < xn; ++i) {
    unsigned __int128 t = carry + x.d[i];
    if (i < yn) t += y.d[i];
    r.d[i] = static_cast<std::uint64_t>(t);
    carry = t >> 64;
  }
  r.n = xn;
  if (carry) {
    if (xn >= kLimbs) {
      ctx.overflow = true;
      return;
    }
    r.d[xn] = static_cast<std::uint64_t>(carry);
    r.n = xn + 1;
  }
}

// r = |a| - |b|, requires |a| >= |b| (r may alias a or b).
inline void sub_mag(BigInt &r, BigInt const &a, BigInt const &b) noexcept {
  int const an = a.n, bn = b.n;
  std::uint64_t borrow = 0;
  for (int i = 0; i < an; ++i) {
    std::uint64_t const bi = i < bn ? b.d[i] : 0;
    std::uint64_t const t = a.d[i] - bi - borrow;
    borrow = (a.d[i] < bi || (a.d[i] == bi && borrow)) ? 1 : 0;
    r.d[i] = t;
  }
  r.n = an;
}

// r = a + sb * b, sb = +1 or -1 (r may alias a or b).
inline void add_signed(Ctx &ctx, BigInt &r, BigInt const &a, BigInt const &b, int sb) noexcept {
  int const bs = b.s * sb;
  if (bs == 0) {
    copy(r, a);
    return;
  }
  if (a.s == 0) {
    copy(r, b);
    r.s = bs;
    return;
  }
  if (a.s == bs) {
    int const sign = a.s;
    add_mag(ctx, r, a, b);
    r.s = sign;
    normalize(r);
    return;
  }
  int const c = cmp_mag(a, b);
  if (c == 0) {
    set_zero(r);
    return;
  }
  if (c > 0) {
    int const sign = a.s;
    sub_mag(r, a, b);
    r.s = sign;
  } else {
    sub_mag(r, b, a);
    r.s = bs;
  }
  normalize(r);
}

inline void add(Ctx &ctx, BigInt &r, BigInt const &a, BigInt const &b) noexcept {
  add_signed(ctx, r, a, b, +1);
}
inline void sub(Ctx &ctx, BigInt &r, BigInt const &a, BigInt const &b) noexcept {
  add_signed(ctx, r, a, b, -1);
}

// r = a * b; r must not alias a or b.
inline void mul(Ctx &ctx, BigInt &r, BigInt const &a, BigInt const &b) noexcept {
  set_zero(r);
  if (a.s == 0 || b.s == 0) return;
  int const n = a.n + b.n;
  if (n > kLimbs) {
    ctx.overflow = true;
    return;
  }
  for (int i = 0; i < n; ++i) r.d[i] = 0;
  for (int i = 0; i < a.n; ++i) {
    unsigned __int128 carry = 0;
    std::uint64_t const ai = a.d[i];
    for (int j = 0; j < b.n; ++j) {
      unsigned __int128 const t =
          static_cast<unsigned __int128>(ai) * b.d[j] + r.d[i + j] + carry;
      r.d[i + j] = static_cast<std::uint64_t>(t);
      carry = t >> 64;
    }
    r.d[i + b.n] = static_cast<std::uint64_t>(carry);
  }
  r.n = n;
  r.s = a.s * b.s;
  normalize(r);
}

// a *= 2^k (k >= 0), in place.
inline void shl(Ctx &ctx, BigInt &a, int k) noexcept {
  if (a.s == 0 || k == 0) return;
  int const w = k / 64, b = k % 64;
  if (a.n + w + 1 > kLimbs) {
    ctx.overflow = true;
    return;
  }
  a.d[a.n + w] = 0;
  for (int i = a.n - 1; i >= 0; --i) {
    std::uint64_t const x = a.d[i];
    a.d[i + w + 1] |= b ? (x >> (64 - b)) : 0;
    a.d[i + w] = x << b;
  }
  for (int i = 0; i < w; ++i) a.d[i] = 0;
  a.n = a.n + w + 1;
  normalize(a);
}

}  // namespace exact
}  // namespace pw85
