// The exact image of a centre difference (box.hpp): floating-point
// expansions (Shewchuk, "Adaptive precision floating-point arithmetic and
// fast robust geometric predicates", 1997): a value is held exactly as a
// sum of doubles of increasing magnitude that do not overlap, so its sign is
// the sign of its largest component. Sums by two-sum, products of a count
// and a double by an FMA, both exact barring overflow, which is detected.
// Compiled without floating-point contraction (src/meson.build), so that
// the two-sums stay exact.
#include "batch/box.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace pw85 {
namespace batch {
namespace {

constexpr double kMaxCount = 0x1p50;  // largest count computed (box.hpp)

// Whether a - b is exact in floating point (the error term of Knuth's
// two-sum is zero).
bool difference_exact(double a, double b) noexcept {
  double const s = a - b;
  double const bb = s - a;
  return (a - (s - bb)) + (-b - bb) == 0.0;
}

// Whether the subtraction v - n L of the wrap, n its rounded count, is
// exact with |n| <= 1: Sterbenz's lemma applies when L/2 <= |v| <= 2 L, and
// |v| <= 2 L follows from |n| = 1.
bool unit_step_exact(double v, double n, double len) noexcept {
  return std::fabs(n) <= 1.0 && 2.0 * std::fabs(v) >= len;
}

}  // namespace

bool wrap_exact(Box const &b, double const d[3], double nz, double ny, double nx) noexcept {
  double x = d[0], y = d[1], z = d[2];
  if (nz != 0.0) {
    if (!unit_step_exact(z, nz, b.length[2])) return false;
    if (b.tilted && !(difference_exact(y, b.yz_lz * nz) && difference_exact(x, b.xz_lz * nz)))
      return false;
  }
  y -= b.yz_lz * nz;
  x -= b.xz_lz * nz;
  if (ny != 0.0) {
    if (!unit_step_exact(y, ny, b.length[1])) return false;
    if (b.tilted && !difference_exact(x, b.xy_ly * ny)) return false;
  }
  x -= b.xy_ly * ny;
  return nx == 0.0 || unit_step_exact(x, nx, b.length[0]);
}

namespace {

// An exact sum of at most kCapacity doubles.
struct Expansion {
  static constexpr int kCapacity = 24;
  int size = 0;
  double part[kCapacity];
  bool overflow = false;  // an operation overflowed or the capacity was exceeded
};

// e += b exactly (Shewchuk's GROW-EXPANSION with zero elimination).
void add(Expansion &e, double b) noexcept {
  if (b == 0.0) return;
  double q = b;
  int k = 0;
  for (int i = 0; i < e.size; ++i) {
    double const s = q + e.part[i];
    double const bv = s - q;
    double const err = (q - (s - bv)) + (e.part[i] - bv);
    q = s;
    if (err != 0.0) e.part[k++] = err;
  }
  if (!std::isfinite(q) || k >= Expansion::kCapacity) {
    e.overflow = true;
    return;
  }
  if (q != 0.0) e.part[k++] = q;
  e.size = k;
}

// e += n * v exactly, n an integer of magnitude <= kMaxCount.
void add_product(Expansion &e, double n, double v) noexcept {
  double const p = n * v;
  if (!std::isfinite(p)) {
    e.overflow = true;
    return;
  }
  add(e, std::fma(n, v, -p));
  add(e, p);
}

int sign(Expansion const &e) noexcept {
  if (e.size == 0) return 0;
  double const top = e.part[e.size - 1];
  return top > 0.0 ? 1 : top < 0.0 ? -1 : 0;
}

// An approximation of the value (components summed from the smallest).
double estimate(Expansion const &e) noexcept {
  double s = 0.0;
  for (int i = 0; i < e.size; ++i) s += e.part[i];
  return s;
}

// e * 2 (exact unless it overflows).
Expansion twice(Expansion const &e) noexcept {
  Expansion t = e;
  for (int i = 0; i < t.size; ++i) {
    t.part[i] *= 2.0;
    if (!std::isfinite(t.part[i])) t.overflow = true;
  }
  return t;
}

// The sign of r - side * len / 2 (side = +1 or -1), exactly: with len / 2
// when it is exact, else (len subnormal) as the sign of 2 r - side * len.
int sign_beyond_half(Expansion const &r, double len, int side, bool &overflow) noexcept {
  Expansion t;
  if (len >= 0x1p-1000) {
    t = r;
    add(t, -side * (0.5 * len));
  } else {
    t = twice(r);
    add(t, -side * len);
  }
  overflow = overflow || t.overflow;
  return sign(t);
}

// The nearest integer n to v / len (ties away from zero) and r = v - n len,
// exactly; false when |v / len| exceeds kMaxCount (or on overflow).
bool nearest_count(Expansion const &v, double len, double &n, Expansion &r) noexcept {
  double const q = estimate(v) / len;
  if (!(std::fabs(q) <= kMaxCount)) return false;
  n = std::round(q);
  // The estimate is within a few units of the last place of v, so n is off
  // by at most one: a few exact corrections settle it.
  for (int pass = 0; pass < 4; ++pass) {
    r = v;
    add_product(r, -n, len);
    bool overflow = r.overflow;
    int const above = sign_beyond_half(r, len, 1, overflow);   // r - len/2
    int const below = sign_beyond_half(r, len, -1, overflow);  // r + len/2
    if (overflow) return false;
    if (above > 0 || (above == 0 && n >= 0.0)) {
      n += 1.0;  // v / len above n + 1/2, or exactly n + 1/2 with n + 1/2 > 0
    } else if (below < 0 || (below == 0 && n <= 0.0)) {
      n -= 1.0;
    } else {
      return std::fabs(n) <= kMaxCount;
    }
  }
  return false;
}

// The exact value of e rounded to the nearest double (ties to even).
double round_to_double(Expansion const &e, bool &overflow) noexcept {
  if (e.size <= 1) return e.size == 0 ? 0.0 : e.part[0];
  double a = estimate(e);
  for (int pass = 0; pass < 8; ++pass) {
    Expansion rest = e;
    add(rest, -a);
    int const s = sign(rest);
    if (s == 0) return a;
    // Compare e with the midpoint of a and its neighbour b on the side of e:
    // the sign of 2 e - a - b.
    double const b = std::nextafter(a, s > 0 ? HUGE_VAL : -HUGE_VAL);
    Expansion mid = twice(e);
    add(mid, -a);
    add(mid, -b);
    if (mid.overflow || rest.overflow || !std::isfinite(b)) break;
    int const m = sign(mid) * s;  // > 0: beyond the midpoint
    if (m < 0) return a;
    if (m == 0) {
      std::uint64_t bits;
      std::memcpy(&bits, &a, sizeof bits);
      return (bits & 1u) == 0 ? a : b;  // the even one of two neighbours
    }
    a = b;
  }
  overflow = true;
  return a;
}

// One step of the wrap: v reduced by len; n its count when count_needed.
// False: refused. Without the count, each component of v is first replaced
// by its IEEE remainder (exact for every magnitude): that changes v by a
// multiple of len, so the image is the same, and leaves a count of at most
// the number of components.
bool reduce(Expansion const &v, double len, bool count_needed, double &n,
            Expansion &r) noexcept {
  if (v.overflow) return false;
  if (count_needed) return nearest_count(v, len, n, r);
  Expansion small;
  for (int i = 0; i < v.size; ++i) add(small, std::remainder(v.part[i], len));
  n = 0.0;
  double count;
  return nearest_count(small, len, count, r);
}

}  // namespace

Status minimum_image_exact(Box const &b, double d[3]) noexcept {
  double nz, ny, nx;
  Expansion ez, rz, ey, ry, ex, rx;
  add(ez, d[2]);
  if (!reduce(ez, b.length[2], b.xz_lz != 0.0 || b.yz_lz != 0.0, nz, rz)) return kInvalidArgument;
  add(ey, d[1]);
  if (nz != 0.0) add_product(ey, -nz, b.yz_lz);
  if (!reduce(ey, b.length[1], b.xy_ly != 0.0, ny, ry)) return kInvalidArgument;
  add(ex, d[0]);
  if (nz != 0.0) add_product(ex, -nz, b.xz_lz);
  if (ny != 0.0) add_product(ex, -ny, b.xy_ly);
  if (!reduce(ex, b.length[0], false, nx, rx)) return kInvalidArgument;
  bool overflow = false;
  double const x = round_to_double(rx, overflow), y = round_to_double(ry, overflow),
               z = round_to_double(rz, overflow);
  if (overflow) return kInvalidArgument;
  d[0] = x;
  d[1] = y;
  d[2] = z;
  return kOk;
}

}  // namespace batch
}  // namespace pw85
