// Periodic box and minimum image of the scene object (scene.cpp): the
// conventions of the pw85_scene_* calls (include/pw85.h), so that a pair of
// the scene gets the r12 those calls give it.
#pragma once

#include <cmath>

namespace pw85 {
namespace scene_box {

// Periodic box in the HOOMD/GSD convention {Lx, Ly, Lz, xy, xz, yz}: lattice
// vectors a1 = (Lx, 0, 0), a2 = (xy Ly, Ly, 0), a3 = (xz Lz, yz Lz, Lz).
struct Box {
  bool periodic = false;
  double l[3] = {0, 0, 0};
  double inv_l[3] = {0, 0, 0};
  double xy = 0, xz = 0, yz = 0;
  double xy_ly = 0, xz_lz = 0, yz_lz = 0;
  // Largest admissible sum of two bounding-sphere radii: min(L)/2, less a
  // relative 1e-9 (the pw85_scene_* calls' bound).
  double max_reach = 0;
  double max_reach2_half = 0;
};

inline bool make_box(double const *box, Box &b) noexcept {
  b = Box{};
  if (box == nullptr) return true;
  for (int d = 0; d < 6; ++d)
    if (!std::isfinite(box[d])) return false;
  if (!(box[0] > 0.0 && box[1] > 0.0 && box[2] > 0.0)) return false;
  b.periodic = true;
  for (int d = 0; d < 3; ++d) {
    b.l[d] = box[d];
    b.inv_l[d] = 1.0 / box[d];
  }
  b.xy = box[3];
  b.xz = box[4];
  b.yz = box[5];
  b.xy_ly = box[3] * box[1];
  b.xz_lz = box[4] * box[2];
  b.yz_lz = box[5] * box[2];
  if (!std::isfinite(b.xy_ly) || !std::isfinite(b.xz_lz) || !std::isfinite(b.yz_lz)) return false;
  double const lmin = std::fmin(box[0], std::fmin(box[1], box[2]));
  b.max_reach = 0.5 * lmin * (1.0 - 1e-9);
  b.max_reach2_half = 0.5 * b.max_reach * b.max_reach;
  return true;
}

inline double round_away(double x) noexcept {
  if (!(std::fabs(x) < 0x1p52)) return x;
  double t = static_cast<double>(static_cast<long long>(x));
  double const rem = x - t;
  if (rem >= 0.5) t += 1.0;
  else if (rem <= -0.5) t -= 1.0;
  return t;
}

inline void min_image(Box const &b, double r[3]) noexcept {
  double const iz = round_away(r[2] * b.inv_l[2]);
  r[2] -= b.l[2] * iz;
  r[1] -= b.yz_lz * iz;
  r[0] -= b.xz_lz * iz;
  double const iy = round_away(r[1] * b.inv_l[1]);
  r[1] -= b.l[1] * iy;
  r[0] -= b.xy_ly * iy;
  double const ix = round_away(r[0] * b.inv_l[0]);
  r[0] -= b.l[0] * ix;
}

inline double reach2(double const *q) noexcept {
  double const a00 = std::fabs(q[0]), a01 = std::fabs(q[1]), a02 = std::fabs(q[2]);
  double const a11 = std::fabs(q[3]), a12 = std::fabs(q[4]), a22 = std::fabs(q[5]);
  double const r0 = a00 + a01 + a02, r1 = a01 + a11 + a12, r2 = a02 + a12 + a22;
  double const trace = a00 + a11 + a22;
  double g = r0 > r1 ? r0 : r1;
  g = g > r2 ? g : r2;
  return trace < g ? trace : g;
}

inline bool too_large(Box const &box, double const *q1, double const *q2) noexcept {
  double const g1 = reach2(q1), g2 = reach2(q2);
  if (g1 + g2 <= box.max_reach2_half) return false;
  return std::sqrt(g1) + std::sqrt(g2) > box.max_reach;
}

}  // namespace scene_box
}  // namespace pw85
