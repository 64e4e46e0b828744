// Cell grid of the scene object (docs/scene.md, "Broad phase"): space, or
// the periodic box, cut into n[0] x n[1] x n[2] cells of equal size in
// fractional coordinates. Every cell is at least `reach` wide across each
// pair of opposite faces, with a fractional slack (kSlack) that covers the
// rounding of the fractional coordinates, so two points closer than reach
// (in some periodic image) lie in cells whose indices differ by at most
// stencil(d, rho) along each axis d (cyclically in a periodic box).
#pragma once

#include <cmath>

#include "batch/box.hpp"

namespace pw85 {

struct CellGrid {
  bool periodic = false;
  long long n[3] = {1, 1, 1};
  long long cells = 1;
  // Fractional coordinates: periodic, f = H^{-1} x (H the box's lattice
  // vectors as columns), taken modulo 1; open, f_d = (x_d - lo_d) inv_ext_d,
  // clamped to [0, 1].
  double lo[3] = {0, 0, 0};
  double inv_ext[3] = {0, 0, 0};
  // Width of the unit fractional slab along each axis: the distance
  // between the planes f_d = 0 and f_d = 1 (rounded down).
  double width[3] = {0, 0, 0};
  batch::Box box;
};

// Slack in fractional coordinates (each |f| <= kMaxFractional is computed
// with an error far below it).
constexpr double kSlack = 0x1p-28;
// Largest |f| accepted (centres at most this many box lengths away from the
// origin): beyond it a centre is refused (PW85_ERR_RANGE).
constexpr double kMaxFractional = 0x1p20;

// The tilts xy, xz, yz of a box, from its tilt offsets (rounded: the
// fractional coordinates and cell widths only need them approximately,
// their errors being covered by kSlack and the wrap error bound).
inline void tilts(batch::Box const &b, double t[3]) noexcept {
  t[0] = b.xy_ly * b.inv_length[1];
  t[1] = b.xz_lz * b.inv_length[2];
  t[2] = b.yz_lz * b.inv_length[2];
}

// Unwrapped fractional coordinates of x in a periodic box (x = f0 a1 +
// f1 a2 + f2 a3, up to roundings).
inline void fractional(batch::Box const &b, double const x[3], double f[3]) noexcept {
  double t[3];
  tilts(b, t);
  f[2] = x[2] * b.inv_length[2];
  f[1] = (x[1] - t[2] * x[2]) * b.inv_length[1];
  f[0] = (x[0] - t[0] * x[1] + (t[0] * t[2] - t[1]) * x[2]) * b.inv_length[0];
}

// floor(x) for |x| < 2^52 without the library call baseline x86-64 makes
// of std::floor (x itself beyond, and for NaN).
inline double floor_small(double x) noexcept {
  if (!(std::fabs(x) < 0x1p52)) return x;
  double const t = static_cast<double>(static_cast<long long>(x));
  return t > x ? t - 1.0 : t;
}

// Cell coordinates of unwrapped fractional coordinates f (periodic grid).
inline void cell_coords_fractional(CellGrid const &g, double const f_in[3], long long c[3]) noexcept {
  for (int d = 0; d < 3; ++d) {
    double const f = f_in[d] - floor_small(f_in[d]);
    long long k = static_cast<long long>(f * static_cast<double>(g.n[d]));
    if (k < 0) k = 0;
    if (k >= g.n[d]) k = g.n[d] - 1;
    c[d] = k;
  }
}

// Cell index of point x along each axis.
inline void cell_coords(CellGrid const &g, double const x[3], long long c[3]) noexcept {
  double f[3];
  if (g.periodic) {
    fractional(g.box, x, f);
    cell_coords_fractional(g, f, c);
    return;
  } else {
    for (int d = 0; d < 3; ++d) {
      f[d] = (x[d] - g.lo[d]) * g.inv_ext[d];
      if (!(f[d] > 0.0)) f[d] = 0.0;
      if (f[d] > 1.0) f[d] = 1.0;
    }
  }
  for (int d = 0; d < 3; ++d) {
    long long k = static_cast<long long>(f[d] * static_cast<double>(g.n[d]));
    if (k < 0) k = 0;
    if (k >= g.n[d]) k = g.n[d] - 1;
    c[d] = k;
  }
}

inline long long cell_id(CellGrid const &g, long long const c[3]) noexcept {
  return c[0] + g.n[0] * (c[1] + g.n[1] * c[2]);
}

// Half-width of the stencil along axis d for points closer than rho.
inline long long stencil(CellGrid const &g, int d, double rho) noexcept {
  if (g.n[d] == 1 || !(g.width[d] > 0.0)) return 0;
  double const k = std::floor((rho / g.width[d] + kSlack) * static_cast<double>(g.n[d]));
  if (!(k < static_cast<double>(g.n[d]))) return g.n[d];
  return static_cast<long long>(k) + 1;
}

// Calls fn(id, wrap) for each distinct cell within k[d] of cell c along
// every axis d (cyclically in a periodic grid, clipped in an open one);
// wrap[d] in {-1, 0, 1}: the cell lies that many periods from c's side
// along d (its particles' images near c are shifted by wrap[d] lattice
// vectors), or wrap null where an axis is enumerated whole (2 k[d] + 1 >=
// n[d]: the image is not the cell's).
template <class Fn>
inline void for_each_neighbour_cell(CellGrid const &g, long long const c[3],
                                    long long const k[3], Fn fn) noexcept {
  long long first[3], count[3];
  bool whole = false;
  for (int d = 0; d < 3; ++d) {
    long long const n = g.n[d];
    if (g.periodic) {
      if (2 * k[d] + 1 >= n) {
        first[d] = 0;
        count[d] = n;
        whole = true;
      } else {
        first[d] = c[d] - k[d];
        count[d] = 2 * k[d] + 1;
      }
    } else {
      long long const a = c[d] - k[d] < 0 ? 0 : c[d] - k[d];
      long long const b = c[d] + k[d] >= n ? n - 1 : c[d] + k[d];
      first[d] = a;
      count[d] = b - a + 1;
    }
  }
  long long x[3];
  int wrap[3];
  for (long long iz = 0; iz < count[2]; ++iz) {
    x[2] = first[2] + iz;
    wrap[2] = x[2] < 0 ? -1 : (x[2] >= g.n[2] ? 1 : 0);
    x[2] -= wrap[2] * g.n[2];
    for (long long iy = 0; iy < count[1]; ++iy) {
      x[1] = first[1] + iy;
      wrap[1] = x[1] < 0 ? -1 : (x[1] >= g.n[1] ? 1 : 0);
      x[1] -= wrap[1] * g.n[1];
      for (long long ix = 0; ix < count[0]; ++ix) {
        x[0] = first[0] + ix;
        wrap[0] = x[0] < 0 ? -1 : (x[0] >= g.n[0] ? 1 : 0);
        x[0] -= wrap[0] * g.n[0];
        fn(cell_id(g, x), whole ? static_cast<int const *>(nullptr) : wrap);
      }
    }
  }
}

// The centre x wrapped into a periodic box, H (f - floor f) with f its
// fractional coordinates (x itself without a box).
inline void wrapped_centre(batch::Box const &b, double const x[3], double w[3]) noexcept {
  if (!b.periodic) {
    w[0] = x[0], w[1] = x[1], w[2] = x[2];
    return;
  }
  double f[3];
  fractional(b, x, f);
  for (int d = 0; d < 3; ++d) f[d] -= floor_small(f[d]);
  w[0] = f[0] * b.length[0] + f[1] * b.xy_ly + f[2] * b.xz_lz;
  w[1] = f[1] * b.length[1] + f[2] * b.yz_lz;
  w[2] = f[2] * b.length[2];
}

// The lattice vector wrap[0] a1 + wrap[1] a2 + wrap[2] a3 of a periodic box.
inline void lattice_shift(batch::Box const &b, int const wrap[3], double s[3]) noexcept {
  s[0] = wrap[0] * b.length[0] + wrap[1] * b.xy_ly + wrap[2] * b.xz_lz;
  s[1] = wrap[1] * b.length[1] + wrap[2] * b.yz_lz;
  s[2] = wrap[2] * b.length[2];
}

// Sets up g for points closer than rho to be found with a stencil of
// half-width split: cells at least rho / split wide (plus kSlack), at most
// max_cells cells (fewer, wider cells then). Periodic: box b; open: the
// bounding box [lo, hi] of the points.
void cell_grid_init(CellGrid &g, batch::Box const &b, double const lo[3],
                    double const hi[3], double rho, long long max_cells, int split) noexcept;

}  // namespace pw85
