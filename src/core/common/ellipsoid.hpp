// Quadratic forms of spheroids and general ellipsoids,
// Q = sum_i a_i^2 v_i v_i^T (pw85 documentation, section 3.1, eq. (2)).
#pragma once

#include "common/status.hpp"
#include "common/sym3.hpp"

namespace pw85 {

// Spheroid: Q = a^2 I + (c^2 - a^2) n n^T. Evaluated in pw85 1.0's order, so
// the doubles produced are the same as pw85 1.0's.
Sym3 spheroid(double a, double c, Vec3 const &n) noexcept;

// General ellipsoid; axes holds the three unit axes row by row. Checks
// radii > 0 and orthonormality of the axes to within tol, entrywise.
Status ellipsoid(Vec3 const &radii, double const axes[9], double tol, Sym3 &q) noexcept;

}  // namespace pw85
