// Ellipsoids from orientations as simulation codes store them, and back:
// Q from semi-axes and a unit quaternion (w, x, y, z), and the semi-axes,
// rotation matrix and quaternion of a Q (symmetric eigen-decomposition by
// cyclic Jacobi rotations). docs/guide.md, "Orientations".
#pragma once

#include "common/status.hpp"
#include "common/sym3.hpp"
#include "dispatch/variant.hpp"

namespace pw85 {

// Accepted deviation of a quaternion from unit length: | |quat|^2 - 1 |
// (float32 components, or six significant decimal digits).
constexpr double kQuatTol = 1e-5;
// Accepted deviation of the axes given to pw85_ellipsoid and
// pw85_ellipsoid_rotation from orthonormality, entrywise.
constexpr double kAxesTol = 1e-10;

// Q = R diag(radii^2) R^T, R the rotation of the quaternion quat / |quat|
// (eq. (O1) of orientation.cpp). Checks radii > 0 (kNotSpd), the norm of
// quat (kNotOrthonormal) and the range of radii^2 (kRange); kRange too when
// the rounded Q is not positive definite (radii too different for double).
Status ellipsoid_quat(Vec3 const &radii, double const quat[4], Sym3 &q) noexcept;

// Q = R diag(radii^2) R^T with radii ascending and R proper (det +1),
// rot[3 i + j] = R_ij (the columns are the axes), quat (w, x, y, z) with
// w >= 0. q must be finite and positive definite (checked by the caller);
// kInaccurate (nothing written) when an eigenvalue comes out <= 0 or the
// outputs would not give a q back through ellipsoid() and ellipsoid_quat()
// (smallest eigenvalue near the accuracy of the sweeps, ~10 u ||q||);
// kNoConvergence when the sweeps do not converge (never observed; outputs
// written).
Status ellipsoid_axes(Sym3 const &q, Vec3 &radii, double rot[9], double quat[4]) noexcept;

// The variants of ellipsoid_quat (orientation.cpp): Dekker's product on any
// CPU, the fused multiply-add from the fma variant up, where built.
struct OrientationKernels {
  Status (*ellipsoid_quat)(Vec3 const &radii, double const quat[4], Sym3 &q) noexcept;
};
extern const OrientationKernels orientation_kernels[kVariantCount];

}  // namespace pw85
