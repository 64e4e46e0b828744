// Vectors of kLanes doubles (GCC vector extensions) and their lane-by-lane
// helpers, for the loops that process several pairs at once
// (overlap/overlap_lanes.cpp, contact/default_lanes.cpp; docs/batch.md,
// "Throughput"). No operation mixes lanes.
#pragma once

#include <cmath>

#include "common/isa.hpp"

// Every function taking or returning a vector is always inline into the
// instruction-set variants of its callers (no vector crosses a call), so
// GCC's note that the ABI of a 32-byte vector argument depends on AVX does
// not apply.
#if defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace pw85 {
namespace lanes {

constexpr int kLanes = 4;
typedef double V __attribute__((vector_size(8 * kLanes)));
typedef long long M __attribute__((vector_size(8 * kLanes)));  // lane masks: 0 or -1

constexpr long long kSign = static_cast<long long>(0x8000000000000000ULL);

PW85_ALWAYS_INLINE V vabs(V x) noexcept {
  return reinterpret_cast<V>(reinterpret_cast<M>(x) & (M{} + ~kSign));
}
// m ? a : b, lane by lane.
PW85_ALWAYS_INLINE V select(M m, V a, V b) noexcept {
  return reinterpret_cast<V>((m & reinterpret_cast<M>(a)) | (~m & reinterpret_cast<M>(b)));
}
// a > b ? a : b (a NaN in a gives b), as v2::max of screen.hpp.
PW85_ALWAYS_INLINE V vmax(V a, V b) noexcept { return select(a > b, a, b); }
// std::copysign(x, y), lane by lane.
PW85_ALWAYS_INLINE V copysign(V x, V y) noexcept {
  return reinterpret_cast<V>((reinterpret_cast<M>(x) & (M{} + ~kSign)) |
                             (reinterpret_cast<M>(y) & (M{} + kSign)));
}
PW85_ALWAYS_INLINE V vsqrt(V x) noexcept {
  V y;
  for (int l = 0; l < kLanes; ++l) y[l] = std::sqrt(x[l]);
  return y;
}
// std::isfinite, lane by lane: x - x is 0 for finite x, NaN otherwise.
PW85_ALWAYS_INLINE M finite(V x) noexcept { return (x - x) == 0.0; }
PW85_ALWAYS_INLINE bool any(M m) noexcept {
  long long a = 0;
  for (int l = 0; l < kLanes; ++l) a |= m[l];
  return a != 0;
}

}  // namespace lanes
}  // namespace pw85
