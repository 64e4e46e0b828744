// The periodic box of the scene calls and the minimum image of a centre
// difference (docs/batch.md, "Periodic box and minimum image").
//
// Box {Lx, Ly, Lz, xy, xz, yz} (HOOMD/GSD convention): lattice vectors
// a1 = (Lx, 0, 0), a2 = (xy Ly, Ly, 0), a3 = (xz Lz, yz Lz, Lz), the tilt
// offsets xy Ly, xz Lz, yz Lz rounded to double once (as HOOMD stores them).
//
// The image of a difference d is the triclinic wrap of HOOMD's
// Box::minImage in exact arithmetic: nz = nearest integer to d_z / Lz (ties
// away from zero), d -= nz a3; then ny from d_y / Ly, d -= ny a2; then nx
// from d_x / Lx, d -= nx a1; each component of the exact result is rounded
// to double once. The result lies in the brick |x| <= Lx/2, |y| <= Ly/2,
// |z| <= Lz/2, a fundamental domain of the lattice, so it is the nearest
// image whenever the nearest image is shorter than min(Lx, Ly, Lz)/2. The
// counts come from rounded quotients where the wrap is done in floating
// point: where a quotient lies within a relative 2^-48 of a half-integer,
// the image of either neighbouring count may be returned (both exact).
//
// Where the counts are needed (a count along a3 with xz or yz not zero, a
// count along a2 with xy not zero) they must be at most 2^50 in magnitude,
// and every intermediate sum must stay finite; beyond that the image is
// refused (kInvalidArgument). Along a direction whose count is not needed,
// any magnitude is reduced exactly (an IEEE remainder).
#pragma once

#include <cmath>

#include "common/status.hpp"

namespace pw85 {
namespace batch {

struct Box {
  bool periodic = false;
  bool tilted = false;  // some tilt offset is not zero
  double length[3] = {0, 0, 0};
  double inv_length[3] = {0, 0, 0};  // 1 / length, rounded
  double xy_ly = 0, xz_lz = 0, yz_lz = 0;  // tilt offsets, rounded
  // Largest admissible sum of the two bounding-sphere radii of a pair:
  // min(Lx, Ly, Lz) / 2, less a relative 1e-9 for the rounding of the radius
  // bounds (docs/batch.md).
  double max_reach = 0;
  double max_reach2_half = 0;  // max_reach^2 / 2
};

// A null box: no periodicity (b left non-periodic), true. Else true when the
// lengths are finite and > 0, the tilts finite and the tilt offsets finite;
// false (an invalid box) otherwise.
inline bool make_box(double const *box, Box &b) noexcept {
  if (box == nullptr) return true;
  for (int d = 0; d < 6; ++d)
    if (!std::isfinite(box[d])) return false;
  if (!(box[0] > 0.0 && box[1] > 0.0 && box[2] > 0.0)) return false;
  b.periodic = true;
  for (int d = 0; d < 3; ++d) {
    b.length[d] = box[d];
    b.inv_length[d] = 1.0 / box[d];
  }
  b.xy_ly = box[3] * box[1];
  b.xz_lz = box[4] * box[2];
  b.yz_lz = box[5] * box[2];
  if (!std::isfinite(b.xy_ly) || !std::isfinite(b.xz_lz) || !std::isfinite(b.yz_lz)) return false;
  b.tilted = b.xy_ly != 0.0 || b.xz_lz != 0.0 || b.yz_lz != 0.0;
  double const lmin = std::fmin(box[0], std::fmin(box[1], box[2]));
  b.max_reach = 0.5 * lmin * (1.0 - 1e-9);
  b.max_reach2_half = 0.5 * b.max_reach * b.max_reach;
  return true;
}

// std::round (nearest integer, ties away from zero) without the library
// call that baseline x86-64 (no SSE4.1 roundsd) makes of it: truncation by
// conversion, then the exact remainder x - t decides. |x| >= 2^52, NaN:
// x is returned, as std::round does.
inline double round_away(double x) noexcept {
  if (!(std::fabs(x) < 0x1p52)) return x;
  double t = static_cast<double>(static_cast<long long>(x));
  double const rem = x - t;
  if (rem >= 0.5) t += 1.0;
  else if (rem <= -0.5) t -= 1.0;
  return t;
}

// The image of d in exact arithmetic (the definition at the top of this
// file), for any d; kInvalidArgument beyond the limits stated there (d
// unchanged). Out of line: the path of minimum_image for what its floating-
// point wrap cannot certify.
Status minimum_image_exact(Box const &b, double d[3]) noexcept;

// The image of d when every count of the wrap is 0 or +-1 and each
// subtraction of a length is exact (Sterbenz's lemma, checked): HOOMD's
// operations, plus the rounding errors of the subtractions of the tilt
// offsets kept by two-sums, each component of the exact image rounded once;
// d written, true. False (d unchanged) otherwise. Out of line: taken only
// by pairs that may wrap.
bool wrap_small_counts(Box const &b, double d[3]) noexcept;

// d (periodic box b, every component finite) replaced by its image
// (definition at the top of this file); kOk, or kInvalidArgument with d
// unchanged. A pair that does not wrap takes HOOMD's wrap in floating
// point (all its counts are 0, so it leaves d as it is); a pair that may
// wrap goes to wrap_small_counts, and what that cannot do to
// minimum_image_exact.
[[gnu::always_inline]] inline Status minimum_image(Box const &b, double d[3]) noexcept {
  double x = d[0], y = d[1], z = d[2];
  double const qz = z * b.inv_length[2], nz = round_away(qz);
  z -= b.length[2] * nz;
  y -= b.yz_lz * nz;
  x -= b.xz_lz * nz;
  double const qy = y * b.inv_length[1], ny = round_away(qy);
  y -= b.length[1] * ny;
  x -= b.xy_ly * ny;
  double const qx = x * b.inv_length[0], nx = round_away(qx);
  x -= b.length[0] * nx;
  // A count is 0 exactly when its quotient is below 1/2 in magnitude, so a
  // sum of the |q| (those of round_away, shared) below 1/2 means no wrap; a
  // larger sum, an infinity or a NaN (a subnormal length: 1 / L = inf) goes
  // to wrap_small_counts. Without tilt, the wrap just computed is exact
  // when each count is 0, or +-1 with |d_k| >= L_k / 2 (Sterbenz's lemma).
  if (!(std::fabs(qz) + std::fabs(qy) + std::fabs(qx) < 0.5)) {
    auto const unit_step_exact = [](double v, double n, double len) noexcept {
      return n == 0.0 || (std::fabs(n) <= 1.0 && 2.0 * std::fabs(v) >= len);
    };
    if (b.tilted || !(unit_step_exact(d[2], nz, b.length[2]) &&
                      unit_step_exact(d[1], ny, b.length[1]) &&
                      unit_step_exact(d[0], nx, b.length[0])))
      return wrap_small_counts(b, d) ? kOk : minimum_image_exact(b, d);
  }
  d[0] = x;
  d[1] = y;
  d[2] = z;
  return kOk;
}

// A position p wrapped into the brick |x| <= Lx/2, |y| <= Ly/2,
// |z| <= Lz/2 centred on the origin: its image, as minimum_image.
inline Status wrap_position(Box const &b, double p[3]) noexcept { return minimum_image(b, p); }

}  // namespace batch
}  // namespace pw85
