// Contact geometry of two ellipsoids for discrete-element codes
// (docs/contact_geometry.md): contact point and common normal of the two
// ellipsoids scaled by mu, distance of closest approach along r12 and
// overlap depths.
#pragma once

#include "common/status.hpp"
#include "common/sym3.hpp"

namespace pw85 {

struct ContactGeometry {
  double mu2;        // contact function mu^2 = f(lambda)
  double lambda;     // maximiser of f
  double x0[3];      // contact point of the mu-scaled ellipsoids, relative to centre 1
  double n[3];       // unit common normal at x0, from ellipsoid 1 towards 2
  double dca;        // distance of closest approach along r12: |r12| / mu
  double depth;      // dca - |r12| (> 0: overlapping)
  double depth_n;    // depth (r12/|r12|) . n
};

// Preconditions (checked by the C layer): r != 0, finite, q1 and q2 positive
// definite. Returns kOk or the status of the contact-function solve
// (kNoConvergence / kInaccurate: values still written, NaN where the
// geometry could not be computed).
Status contact_geometry(Vec3 const &r, Sym3 const &q1, Sym3 const &q2,
                        ContactGeometry &g) noexcept;

}  // namespace pw85
