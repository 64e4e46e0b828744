// The variants of the overlap predicate's hot path (overlap_variants.cpp),
// each compiled from the one body of overlap/filters.hpp: the one-pair path
// of pw85_overlap and the lanes of 4 and 8 pairs of the batch calls.
#pragma once

#include "common/status.hpp"
#include "dispatch/variant.hpp"

namespace pw85 {

struct OverlapKernels {
  // overlap_screened (overlap.hpp).
  bool (*screened)(double const *r, double const *q1, double const *q2, int &verdict,
                   Status &status) noexcept;
  // overlap_lanes<4> and overlap_lanes<8> (overlap.hpp).
  void (*lanes4)(double const *const r[4], double const *const q1[4], double const *const q2[4],
                 int verdict[4]) noexcept;
  void (*lanes8)(double const *const r[8], double const *const q1[8], double const *const q2[8],
                 int verdict[8]) noexcept;
  // overlap_lanes_width(): 8 where one vector holds 8 doubles, else 4.
  int lanes_width;
};

// The kernels of variant v: x86-64-v4, x86-64-v3 where built, else the
// portable code (the fma variant has no kernels of its own here).
extern const OverlapKernels overlap_kernels[kVariantCount];

}  // namespace pw85
