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

// A vector of W doubles, for any W (4: AVX2, 8: AVX-512; a width the
// target lacks is split by GCC).
template <int W>
struct Width {
  typedef double V __attribute__((vector_size(8 * W)));
};
template <int W>
using VecD = typename Width<W>::V;

// The width of the lane loops that do not choose one per instruction set.
constexpr int kLanes = 4;
typedef VecD<kLanes> V;

constexpr long long kSign = static_cast<long long>(0x8000000000000000ULL);

// Number of lanes of a vector type.
template <class T>
constexpr int width() noexcept {
  return static_cast<int>(sizeof(T) / sizeof(double));
}
// The mask type of a vector type (that of its comparisons): 0 or -1 per
// lane.
template <class T>
using MaskOf = decltype(T{} < T{});
template <int W>
using MaskD = MaskOf<VecD<W>>;
typedef MaskD<kLanes> M;

template <class T>
PW85_ALWAYS_INLINE T vabs(T x) noexcept {
  typedef MaskOf<T> K;
  return reinterpret_cast<T>(reinterpret_cast<K>(x) & (K{} + ~kSign));
}
// m ? a : b, lane by lane.
template <class K, class T>
PW85_ALWAYS_INLINE T select(K m, T a, T b) noexcept {
  return reinterpret_cast<T>((m & reinterpret_cast<K>(a)) | (~m & reinterpret_cast<K>(b)));
}
// a > b ? a : b (a NaN in a gives b), as v2::max of screen.hpp.
template <class T>
PW85_ALWAYS_INLINE T vmax(T a, T b) noexcept { return select(a > b, a, b); }
// std::copysign(x, y), lane by lane.
template <class T>
PW85_ALWAYS_INLINE T copysign(T x, T y) noexcept {
  typedef MaskOf<T> K;
  return reinterpret_cast<T>((reinterpret_cast<K>(x) & (K{} + ~kSign)) |
                             (reinterpret_cast<K>(y) & (K{} + kSign)));
}
template <class T>
PW85_ALWAYS_INLINE T vsqrt(T x) noexcept {
  T y;
  for (int l = 0; l < width<T>(); ++l) y[l] = std::sqrt(x[l]);
  return y;
}
// std::isfinite, lane by lane: x - x is 0 for finite x, NaN otherwise.
template <class T>
PW85_ALWAYS_INLINE MaskOf<T> finite(T x) noexcept { return (x - x) == 0.0; }
template <class K>
PW85_ALWAYS_INLINE bool any(K m) noexcept {
  long long a = 0;
  for (int l = 0; l < width<K>(); ++l) a |= m[l];
  return a != 0;
}

// The same helpers for one pair (T = double), so that code templated on the
// vector type (eval/f_rational_dd.hpp, contact/rational_step.hpp) serves the
// one-pair path too.
PW85_ALWAYS_INLINE double vabs(double x) noexcept { return std::fabs(x); }
PW85_ALWAYS_INLINE double select(bool m, double a, double b) noexcept { return m ? a : b; }
PW85_ALWAYS_INLINE bool finite(double x) noexcept { return std::isfinite(x); }
PW85_ALWAYS_INLINE bool any(bool m) noexcept { return m; }

}  // namespace lanes
}  // namespace pw85
