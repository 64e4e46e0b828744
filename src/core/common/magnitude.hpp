// Magnitudes of arrays, for range checks and exact power-of-two rescaling
// (every method that rescales its arguments: brent.cpp, methods.cpp,
// contact_2d.cpp, dca_2d.cpp, dca_3d.cpp, overlap.cpp, and the C layer's
// screens in src/capi/validate.hpp).
#pragma once

#include <cmath>

namespace pw85 {

// max_i |x_i| by plain comparisons (std::fmax is a call into libm without
// -ffast-math, measurable on the hot paths). A NaN entry is skipped, as
// std::fmax would skip it, but an all-NaN array gives 0, not NaN: for
// arguments already checked finite, or checked again afterwards (the
// screens of src/capi/validate.hpp catch a NaN in a matrix by its pivots).
inline double max_abs(double const *x, int n) noexcept {
  double m = 0.0;
  for (int i = 0; i < n; ++i) {
    double const a = std::fabs(x[i]);
    m = a > m ? a : m;
  }
  return m;
}

// The exponent e with max_i |x_i| 2^-e in [0.5, 1) (std::frexp; 0 when every
// x_i is 0).
inline int max_exponent(double const *x, int n) noexcept {
  int e;
  std::frexp(max_abs(x, n), &e);
  return e;
}

}  // namespace pw85
