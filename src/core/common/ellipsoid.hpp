// Quadratic forms of spheroids and general ellipsoids,
// Q = sum_i a_i^2 v_i v_i^T (pw85 documentation, section 3.1, eq. (2)).
#pragma once

#include "common/status.hpp"
#include "common/sym3.hpp"

namespace pw85 {

// Spheroid of semi-axes a, a, c and axis n / |n| (n != 0):
// Q = a^2 (I - m m^T) + c^2 m m^T, m = n / |n|, without cancellation between
// a^2 and c^2. Entries beyond the double range come out as +-Inf or 0.
Sym3 spheroid(double a, double c, Vec3 const &n) noexcept;

// General ellipsoid; axes holds the three unit axes row by row. Checks
// radii > 0 and orthonormality of the axes to within tol, entrywise.
Status ellipsoid(Vec3 const &radii, double const axes[9], double tol, Sym3 &q) noexcept;

}  // namespace pw85
