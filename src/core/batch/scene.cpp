// The scene object (scene.hpp, docs/scene.md).
//
// Broad phase: a cell grid whose cells are at least 2 s R_max wide (R_max
// the largest bounding-sphere radius), pairs of each cell with itself and
// with the neighbour cells of higher index; then two conservative tests,
// each rejecting a pair only when its ellipsoids certainly do not overlap:
// the bounding spheres (|r12| >= s (R_i + R_j)), and a separating plane of
// normal n = adj(Q_i + Q_j) r12 (the normal of the contact plane at
// lambda = 1/2, exact for equal parallel ellipsoids), through the support
// functions h(n) = sqrt(n^T Q n):
//     |n . r12| >= h_i(n) + h_j(n)  =>  mu^2 >= 1,                   (S1)
// evaluated with rounding-error bounds. Narrow phase: the exact overlap
// predicate (the lanes of overlap_lanes, else the one-pair predicate), so
// each verdict is pw85_overlap's.
#include "batch/scene.hpp"

#include "batch/pairs.hpp"
#include "batch/schedule.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <new>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "common/fp.hpp"
#include "common/lanes.hpp"
#include "common/magnitude.hpp"
#include "common/orientation.hpp"
#include "common/screen.hpp"
#include "common/sym3.hpp"
#include "contact/contact.hpp"
#include "overlap/overlap.hpp"

namespace pw85 {

namespace {

using batch::Box;

// A growable array of trivially copyable T on malloc (the library links
// no C++ runtime): reserve() and push() return false when memory runs out.
template <class T>
struct Buffer {
  T *data = nullptr;
  long long size = 0, capacity = 0;
  Buffer() = default;
  Buffer(Buffer const &) = delete;
  Buffer &operator=(Buffer const &) = delete;
  ~Buffer() { std::free(data); }
  bool reserve(long long c) noexcept {
    if (c <= capacity) return true;
    long long nc = capacity > 0 ? capacity : 64;
    while (nc < c) nc *= 2;
    void *p = std::realloc(data, static_cast<size_t>(nc) * sizeof(T));
    if (p == nullptr) return false;
    data = static_cast<T *>(p);
    capacity = nc;
    return true;
  }
  bool push(T const &v) noexcept {
    if (size == capacity && !reserve(size + 1)) return false;
    data[size++] = v;
    return true;
  }
};

template <class T>
T *allocate(long long n) noexcept {
  return static_cast<T *>(std::malloc(static_cast<size_t>(n > 0 ? n : 1) * sizeof(T)));
}

// Relative margin of the bounding radii and of the broad-phase comparisons
// (far above the rounding errors, far below any physical scale).
constexpr double kMargin = 0x1p-40;

// Largest |coordinate| of a centre in a scene without a box.
constexpr double kMaxOpenCoordinate = 0x1p500;

// Bounding-sphere radius of the ellipsoid of q (positive definite), rounded
// up: the square root of an upper bound mu of its largest eigenvalue, mu =
// the computed eigenvalue (1 + 2^-20), certified by the pivots of the
// L D L^T factorisation of mu I - Q (each > 2^-30 mu, far above their
// rounding errors); where the certificate fails, the smaller of the trace
// and the largest Gershgorin row sum (the pw85_scene_* calls' bound).
inline double bounding_radius(double const *q) noexcept {
  double const loose = std::sqrt(batch::reach2(q) * (1 + kMargin)) * (1 + kMargin);
  Vec3 radii;
  double rot[9];
  if (ellipsoid_axes(load_sym3(q), radii, rot, nullptr) != kOk) return loose;
  double lam = radii[0] > radii[1] ? radii[0] : radii[1];
  lam = lam > radii[2] ? lam : radii[2];
  double const mu = lam * lam * (1 + 0x1p-20);
  double const tol = 0x1p-30 * mu;
  double const a00 = mu - q[0], a01 = -q[1], a02 = -q[2];
  double const a11 = mu - q[3], a12 = -q[4], a22 = mu - q[5];
  if (!(a00 > tol)) return loose;
  double const l10 = a01 / a00, l20 = a02 / a00;
  double const d1 = a11 - l10 * a01;
  if (!(d1 > tol)) return loose;
  double const b12 = a12 - l20 * a01;
  double const d2 = a22 - l20 * a02 - b12 * b12 / d1;
  if (!(d2 > tol) || !std::isfinite(d2)) return loose;
  double const tight = std::sqrt(mu) * (1 + kMargin);
  return tight < loose ? tight : loose;
}

// Checks one particle: centre finite (and within kMaxFractional box
// lengths, or kMaxOpenCoordinate without a box), q finite and positive
// definite as pw85_overlap checks it.
Status check_particle(Box const &box, double const *c, double const *q) noexcept {
  if (!all_finite(c, 3) || !all_finite(q, 6)) return kInvalidArgument;
  if (!positive_definite(q)) return kNotSpd;
  if (box.periodic) {
    double f[3];
    fractional(box, c, f);
    for (int d = 0; d < 3; ++d)
      if (!(std::fabs(f[d]) <= kMaxFractional)) return kRange;
  } else {
    for (int d = 0; d < 3; ++d)
      if (!(std::fabs(c[d]) <= kMaxOpenCoordinate)) return kRange;
  }
  return kOk;
}

// r12 of the pair (i, j), i < j: c_j - c_i, or its minimum image
// (batch/box.hpp, as the pw85_scene_* calls take it); false where the image
// is refused (not for centres within kMaxFractional box lengths).
inline bool pair_r12(Box const &box, double const *ci, double const *cj, double r[3]) noexcept {
  for (int d = 0; d < 3; ++d) r[d] = cj[d] - ci[d];
  return !box.periodic || batch::minimum_image(box, r) == kOk;
}

// The bounding spheres of radius reach (their sum) do not meet: |r| >=
// reach, with margin.
inline bool spheres_apart(double const r[3], double reach) noexcept {
  double const d2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
  return d2 >= reach * reach * (1 + kMargin);
}

// Upper bound of n^T Q n for a positive definite Q: the computed value plus
// a bound of its rounding error, 32 u sum_a n_a^2 Q_aa (>= gamma_6 sum_ab
// |n_a| |Q_ab| |n_b|, as |Q_ab| <= (Q_aa + Q_bb) / 2), plus a bound of its
// underflow error, 16 (|n|_1 + 1) 2^-1074 (each of the 12 products loses
// at most 2^-1075 when it underflows; those of a_i are multiplied by |n_i|),
// taken as (|n|_1 + 1) 2^-1018 so that no subnormal is computed: x86 takes a
// microcode assist for each subnormal result, on every plane test here
// (build/bench/bench_scene --n 1000000 measures the query).
// The bound is >= 0 unless a product overflows (inf - inf: NaN). It is not
// clamped: the square root is then NaN and the plane test (S1) below
// declines, as it must (a bound clamped to 0 would let it separate
// overlapping ellipsoids). T: double, or a vector of doubles (one pair per
// lane).
template <class T>
PW85_ALWAYS_INLINE T support2_upper(T const q[6], T const n[3], T n_abs) noexcept {
  T const a0 = q[0] * n[0] + q[1] * n[1] + q[2] * n[2];
  T const a1 = q[1] * n[0] + q[3] * n[1] + q[4] * n[2];
  T const a2 = q[2] * n[0] + q[4] * n[1] + q[5] * n[2];
  T const h = n[0] * a0 + n[1] * a1 + n[2] * a2;
  T const diag = q[0] * n[0] * n[0] + q[3] * n[1] * n[1] + q[5] * n[2] * n[2];
  return h + 32 * kU * diag + (16 * kMinNormal) * (n_abs + 1.0);
}

// (S1): true (each lane: a true mask) only when the plane of normal n =
// adj(qa + qb) r separates the ellipsoids (mu^2 >= 1) for every r12 within
// r_error of r (each component), every rounding and underflow error bounded
// (any n gives a valid plane test, so only n^T r and the support values
// need error bounds, not n itself).
template <class T>
PW85_ALWAYS_INLINE auto plane_separates(T const r[3], T const qa[6], T const qb[6],
                                        T r_error) noexcept {
  T const a00 = qa[0] + qb[0], a01 = qa[1] + qb[1], a02 = qa[2] + qb[2];
  T const a11 = qa[3] + qb[3], a12 = qa[4] + qb[4], a22 = qa[5] + qb[5];
  T const c00 = a11 * a22 - a12 * a12, c01 = a02 * a12 - a01 * a22;
  T const c02 = a01 * a12 - a02 * a11, c11 = a00 * a22 - a02 * a02;
  T const c12 = a01 * a02 - a00 * a12, c22 = a00 * a11 - a01 * a01;
  T const n[3] = {c00 * r[0] + c01 * r[1] + c02 * r[2], c01 * r[0] + c11 * r[1] + c12 * r[2],
                  c02 * r[0] + c12 * r[1] + c22 * r[2]};
  T const nr = n[0] * r[0] + n[1] * r[1] + n[2] * r[2];
  T const nr_abs = lanes::vabs(n[0] * r[0]) + lanes::vabs(n[1] * r[1]) + lanes::vabs(n[2] * r[2]);
  T const n_abs = lanes::vabs(n[0]) + lanes::vabs(n[1]) + lanes::vabs(n[2]);
  T const lhs = lanes::vabs(nr) - 8 * kU * nr_abs - n_abs * r_error * (1 + 8 * kU) -
                4 * kMinNormal;  // >= the underflow error 4 2^-1074, normal
  T const rhs = (lanes::vsqrt(support2_upper(qa, n, n_abs)) +
                 lanes::vsqrt(support2_upper(qb, n, n_abs))) *
                (1 + 8 * kU);
  return (lhs > 0.0) & (lhs >= rhs) & (lhs <= kMaxDouble);
}

// pw85_overlap for arguments already checked (finite, pivots of Q positive).
inline Status overlap_one(double const *r, double const *a, double const *b,
                          int &verdict) noexcept {
  Status st = kOk;
  if (overlap_screened(r, a, b, verdict, st)) return st;
  if (!all_finite(r, 3)) return kInvalidArgument;
  if (!positive_definite(a) || !positive_definite(b)) return kNotSpd;
  return overlap(load_vec3(r), load_sym3(a), load_sym3(b), verdict);
}

// mu^2 of pw85_contact_function_method(DEFAULT) (NaN where it writes NaN).
inline double mu2_default(double const *r, double const *a, double const *b) noexcept {
  MethodResult m;
  Status const s = contact_method_entry(r, a, b, kMethodDefault, m);
  if (s == kOk || s == kNoConvergence || s == kInaccurate || s == kRange) return m.mu2;
  return std::nan("");
}

struct Candidate {
  long long i, j;
  double r[3];
};

struct PairOut {
  long long i, j;
  double mu2;
};

// The exact verdicts of candidates [0, m) (matrices qv: the scene's or
// scaled), W pairs at a time through overlap_lanes; overlapping pairs are
// appended to out (mu2 by DEFAULT on the unscaled q when want_mu2).
// cand[k].i, .j index qv; order (may be null: the identity) maps them to
// the scene's indices, which index q.
template <int W>
Status narrow_phase(Candidate const *cand, long long m, double const *qv,
                    long long const *order, double const *q, bool want_mu2,
                    Buffer<PairOut> &out) noexcept {
  for (long long k0 = 0; k0 < m; k0 += W) {
    int const w = m - k0 < W ? static_cast<int>(m - k0) : W;
    int v[W];
    if (w == W) {
      double const *rp[W], *ap[W], *bp[W];
      for (int l = 0; l < W; ++l) {
        rp[l] = cand[k0 + l].r;
        ap[l] = qv + 6 * cand[k0 + l].i;
        bp[l] = qv + 6 * cand[k0 + l].j;
      }
      overlap_lanes<W>(rp, ap, bp, v);
    } else {
      for (int l = 0; l < w; ++l) v[l] = -1;
    }
    for (int l = 0; l < w; ++l) {
      Candidate const &c = cand[k0 + l];
      if (v[l] < 0) {
        Status const s = overlap_one(c.r, qv + 6 * c.i, qv + 6 * c.j, v[l]);
        if (s != kOk) return s;
      }
      if (v[l] == 1) {
        long long const i = order ? order[c.i] : c.i, j = order ? order[c.j] : c.j;
        double const mu2 = want_mu2 ? mu2_default(c.r, q + 6 * i, q + 6 * j) : 0.0;
        if (!out.push(PairOut{i, j, mu2})) return kNoMemory;
      }
    }
  }
  return kOk;
}

Status narrow(Candidate const *cand, long long m, double const *qv, long long const *order,
              double const *q, bool want_mu2, Buffer<PairOut> &out) noexcept {
  if (overlap_lanes_width() == kOverlapLanesV4)
    return narrow_phase<kOverlapLanesV4>(cand, m, qv, order, q, want_mu2, out);
  return narrow_phase<kOverlapLanes>(cand, m, qv, order, q, want_mu2, out);
}

// Bounding box of the centres (open scenes).
void centre_bounds(long long n, double const *c, double lo[3], double hi[3]) noexcept {
  for (int d = 0; d < 3; ++d) lo[d] = hi[d] = n > 0 ? c[d] : 0.0;
  for (long long i = 1; i < n; ++i)
    for (int d = 0; d < 3; ++d) {
      if (c[3 * i + d] < lo[d]) lo[d] = c[3 * i + d];
      if (c[3 * i + d] > hi[d]) hi[d] = c[3 * i + d];
    }
}

inline long long max_cells_for(long long n) noexcept { return 4 * n + 8; }

// Cells per interaction range of the pairs queries: cells rho / kSplit wide,
// a stencil of (2 kSplit + 1)^3 cells, volume (2 kSplit + 1)^3 / kSplit^3
// rho^3 scanned around each particle (27 rho^3 for 1, 15.6 rho^3 for 2).
constexpr int kSplit = 1;

}  // namespace

void cell_grid_init(CellGrid &g, Box const &b, double const lo[3], double const hi[3],
                    double rho, long long max_cells, int split) noexcept {
  g = CellGrid{};
  g.box = b;
  g.periodic = b.periodic;
  if (b.periodic) {
    double tl[3];
    tilts(b, tl);
    double const t = tl[0] * tl[2] - tl[1];
    g.width[2] = b.length[2];
    g.width[1] = b.length[1] / std::sqrt(1 + tl[2] * tl[2]);
    g.width[0] = b.length[0] / std::sqrt(1 + tl[0] * tl[0] + t * t);
    for (int d = 0; d < 3; ++d) g.width[d] *= 1 - kMargin;
  } else {
    for (int d = 0; d < 3; ++d) {
      g.lo[d] = lo[d];
      double const ext = hi[d] - lo[d];
      g.width[d] = ext > 0.0 && std::isfinite(ext) ? ext * (1 - kMargin) : 0.0;
      g.inv_ext[d] = g.width[d] > 0.0 ? 1.0 / ext : 0.0;
    }
  }
  double nd[3];
  for (int d = 0; d < 3; ++d) {
    nd[d] = 1;
    if (g.width[d] > 0.0) {
      double const x = std::floor(split / (rho / g.width[d] + 2 * kSlack));
      if (x > 1) nd[d] = x;
    }
  }
  double const cap = static_cast<double>(max_cells);
  while (nd[0] * nd[1] * nd[2] > cap) {
    int d = nd[0] >= nd[1] ? 0 : 1;
    if (nd[2] > nd[d]) d = 2;
    nd[d] = std::floor(nd[d] / 2);
    if (nd[d] < 1) nd[d] = 1;
  }
  for (int d = 0; d < 3; ++d) g.n[d] = static_cast<long long>(nd[d]);
  g.cells = g.n[0] * g.n[1] * g.n[2];
}

namespace {

// Frees the per-particle arrays of s (not the cell heads).
void free_particle_arrays(Scene &s) noexcept {
  std::free(s.centres);
  std::free(s.q);
  std::free(s.radius);
  std::free(s.wrapped);
  std::free(s.next);
  std::free(s.prev);
  std::free(s.cell_of);
}

}  // namespace

void scene_release(Scene &scene) noexcept {
  free_particle_arrays(scene);
  std::free(scene.head);
  scene = Scene{};
}

namespace {

void unlink(Scene &s, long long i) noexcept {
  long long const p = s.prev[i], x = s.next[i];
  if (p >= 0) s.next[p] = x;
  else s.head[s.cell_of[i]] = x;
  if (x >= 0) s.prev[x] = p;
}

void link(Scene &s, long long i, long long cell) noexcept {
  s.cell_of[i] = cell;
  s.prev[i] = -1;
  s.next[i] = s.head[cell];
  if (s.next[i] >= 0) s.prev[s.next[i]] = i;
  s.head[cell] = i;
}

long long cell_of_point(CellGrid const &g, double const *x) noexcept {
  long long c[3];
  cell_coords(g, x, c);
  return cell_id(g, c);
}

}  // namespace

Status scene_assign(Scene &scene, long long n, double const *centres, double const *q,
                    double const *box_in, long long &bad) noexcept {
  bad = -1;
  Box box;
  if (n < 0 || !batch::make_box(box_in, box)) return kInvalidArgument;
  // Every particle is checked before anything changes.
  double rmax = 0;
  long long imax = -1;
  double g1 = -1;  // the largest reach2
  for (long long i = 0; i < n; ++i) {
    Status const s = check_particle(box, centres + 3 * i, q + 6 * i);
    if (s != kOk) {
      bad = i;
      return s;
    }
    double const r = bounding_radius(q + 6 * i);
    if (r > rmax) rmax = r;
    double const g = batch::reach2(q + 6 * i);
    if (g > g1) {
      g1 = g;
      imax = i;
    }
  }
  // The pw85_scene_* calls' bound on the largest sphere with itself: no
  // particle meets its own images, and any two spheres fit together.
  if (box.periodic && n > 0 && batch::too_large(box, q + 6 * imax, q + 6 * imax)) {
    bad = imax;
    return kInvalidArgument;
  }
  double lo[3], hi[3];
  centre_bounds(n, centres, lo, hi);
  CellGrid grid;
  cell_grid_init(grid, box, lo, hi, 2 * rmax * (1 + kMargin), max_cells_for(n), 1);
  // Storage: kept when large enough, else new arrays (the old ones stay
  // until all the new ones exist).
  Scene next_scene = scene;
  bool const grow = n > scene.capacity;
  bool const grow_grid = grid.cells > scene.grid_capacity;
  if (grow) {
    next_scene.centres = allocate<double>(3 * n);
    next_scene.q = allocate<double>(6 * n);
    next_scene.radius = allocate<double>(n);
    next_scene.wrapped = allocate<double>(3 * n);
    next_scene.next = allocate<long long>(n);
    next_scene.prev = allocate<long long>(n);
    next_scene.cell_of = allocate<long long>(n);
    next_scene.capacity = n;
  }
  if (grow_grid) {
    next_scene.head = allocate<long long>(grid.cells);
    next_scene.grid_capacity = grid.cells;
  }
  bool const ok = (!grow || (next_scene.centres && next_scene.q && next_scene.radius && next_scene.wrapped &&
                             next_scene.next && next_scene.prev && next_scene.cell_of)) &&
                  (!grow_grid || next_scene.head);
  // On failure the new arrays go, else the old ones they replace.
  Scene &dropped = ok ? scene : next_scene;
  if (grow) free_particle_arrays(dropped);
  if (grow_grid) std::free(dropped.head);
  if (!ok) return kNoMemory;
  scene = next_scene;
  scene.n = n;
  scene.box = box;
  scene.grid = grid;
  scene.radius_max = rmax;
  scene.reach_max = n > 0 ? std::sqrt(g1) : 0.0;
  if (n > 0) {
    std::memcpy(scene.centres, centres, static_cast<size_t>(3 * n) * sizeof(double));
    std::memcpy(scene.q, q, static_cast<size_t>(6 * n) * sizeof(double));
  }
  for (long long c = 0; c < grid.cells; ++c) scene.head[c] = -1;
  for (long long i = n - 1; i >= 0; --i) {
    scene.radius[i] = bounding_radius(q + 6 * i);
    wrapped_centre(box, centres + 3 * i, scene.wrapped + 3 * i);
    link(scene, i, cell_of_point(grid, centres + 3 * i));
  }
  return kOk;
}

namespace {

// A query's particles sorted by cell: start[c] .. start[c + 1] - 1 are the
// sorted positions of cell c's particles (ascending index within a cell),
// order[k] the index of sorted particle k, w its centre wrapped into the
// box (periodic: H (f - floor f), f the fractional coordinates; open: the
// centre), rad its bounding radius scaled by s, q its matrix times s^2, in
// the sorted order for locality.
// Entries readable past the end of the sorted arrays (scan_range's lanes).
constexpr int kScanPad = 4;

struct Sorted {
  CellGrid grid;
  Buffer<long long> start, order;
  Buffer<double> wx, wy, wz, rad;
  Buffer<double> q;  // matrices times s^2, sorted
  // Bound of |w_b + shift - w_a - r12| over the pairs (rounding of the
  // wrapped centres and of r12): 0 without a box.
  double wrap_error = 0;
};

// The bound of Sorted::wrap_error for centres whose fractional coordinates
// are at most fmax in magnitude.
inline double wrap_error_bound(Box const &box, double fmax) noexcept {
  double const hsum = box.length[0] + std::fabs(box.xy_ly) + std::fabs(box.xz_lz) + box.length[1] +
                      std::fabs(box.yz_lz) + box.length[2];
  return 64 * kU * (fmax + 2) * hsum;
}

// The per-particle loops run on nt threads (each particle's values depend on
// it alone); the counting sort itself is serial. The grid is sized for the
// largest wrap error any accepted centre can have (kMaxFractional), the
// sphere tests use the one of the centres at hand.
Status sort_by_cell(Scene const &scene, double rho_scaled, double radius_scale, double s2,
                    int nt, Sorted &q) noexcept {
  long long const n = scene.n;
  Box const &box = scene.box;
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  Buffer<double> frac;
  Buffer<long long> cell_of, fill;
  if (!cell_of.reserve(n) || (box.periodic && !frac.reserve(3 * n))) return kNoMemory;
  if (!box.periodic) centre_bounds(n, scene.centres, lo, hi);
  double const grid_error = box.periodic ? wrap_error_bound(box, kMaxFractional) : 0.0;
  cell_grid_init(q.grid, box, lo, hi, rho_scaled + 2 * grid_error, max_cells_for(n), kSplit);
  if (q.grid.periodic && (q.grid.n[0] < 2 * kSplit + 1 || q.grid.n[1] < 2 * kSplit + 1 ||
                          q.grid.n[2] < 2 * kSplit + 1))
    cell_grid_init(q.grid, box, lo, hi, rho_scaled + 2 * grid_error, max_cells_for(n), 1);
  long long const cells = q.grid.cells;
  if (!q.start.reserve(cells + 1) || !q.order.reserve(n) || !fill.reserve(cells) ||
      !q.wx.reserve(n + kScanPad) || !q.wy.reserve(n + kScanPad) ||
      !q.wz.reserve(n + kScanPad) || !q.rad.reserve(n + kScanPad) || !q.q.reserve(6 * n))
    return kNoMemory;
  // Cells, and (periodic) the fractional coordinates wrapped into [0, 1),
  // once; the wrap error grows with the largest unwrapped one.
  double fmax = 0;
  if (box.periodic) {
    // fractional() and cell_coords_fractional() with their constants
    // hoisted: the same operations, the same values.
    double tl[3];
    tilts(box, tl);
    double const t02 = tl[0] * tl[2] - tl[1];
    double const nd[3] = {static_cast<double>(q.grid.n[0]), static_cast<double>(q.grid.n[1]),
                          static_cast<double>(q.grid.n[2])};
    CellGrid const &g = q.grid;
#pragma omp parallel for num_threads(nt) if (nt > 1) schedule(static) reduction(max : fmax)
    for (long long i = 0; i < n; ++i) {
      double const *x = scene.centres + 3 * i;
      double *f = frac.data + 3 * i;
      f[2] = x[2] * box.inv_length[2];
      f[1] = (x[1] - tl[2] * x[2]) * box.inv_length[1];
      f[0] = (x[0] - tl[0] * x[1] + t02 * x[2]) * box.inv_length[0];
      long long k[3];
      for (int d = 0; d < 3; ++d) {
        double const a = std::fabs(f[d]);
        fmax = a > fmax ? a : fmax;
        f[d] -= floor_small(f[d]);
        k[d] = static_cast<long long>(f[d] * nd[d]);
        k[d] = k[d] < 0 ? 0 : (k[d] >= g.n[d] ? g.n[d] - 1 : k[d]);
      }
      cell_of.data[i] = k[0] + g.n[0] * (k[1] + g.n[1] * k[2]);
    }
  } else {
#pragma omp parallel for num_threads(nt) if (nt > 1) schedule(static)
    for (long long i = 0; i < n; ++i) {
      long long cc[3];
      cell_coords(q.grid, scene.centres + 3 * i, cc);
      cell_of.data[i] = cell_id(q.grid, cc);
    }
  }
  q.wrap_error = box.periodic ? wrap_error_bound(box, fmax) : 0.0;
  long long *start = q.start.data;
  for (long long c = 0; c <= cells; ++c) start[c] = 0;
  for (long long i = 0; i < n; ++i) ++start[cell_of.data[i] + 1];
  for (long long c = 0; c < cells; ++c) start[c + 1] += start[c];
  std::memcpy(fill.data, start, static_cast<size_t>(cells) * sizeof(long long));
  for (long long i = 0; i < n; ++i) q.order.data[fill.data[cell_of.data[i]]++] = i;
#pragma omp parallel for num_threads(nt) if (nt > 1) schedule(static)
  for (long long k = 0; k < n; ++k) {
    long long const i = q.order.data[k];
    double const *c = scene.centres + 3 * i;
    double w[3] = {c[0], c[1], c[2]};
    if (box.periodic) {
      double const *f = frac.data + 3 * i;
      w[0] = f[0] * box.length[0] + f[1] * box.xy_ly + f[2] * box.xz_lz;
      w[1] = f[1] * box.length[1] + f[2] * box.yz_lz;
      w[2] = f[2] * box.length[2];
    }
    q.wx.data[k] = w[0];
    q.wy.data[k] = w[1];
    q.wz.data[k] = w[2];
    q.rad.data[k] = scene.radius[i] * radius_scale;
    for (int t = 0; t < 6; ++t) q.q.data[6 * k + t] = s2 * scene.q[6 * i + t];
  }
  for (long long k = n; k < n + kScanPad; ++k) q.wx.data[k] = q.wy.data[k] = q.wz.data[k] = q.rad.data[k] = 0;
  return kOk;
}

// The candidates of one query: for each sorted particle a, every b of the
// same cell after it and of the 13 neighbour cells of the half stencil
// ((dz, dy, dx) > 0 lexicographically), through the rows of 1 or 3
// consecutive cells along x; a pair goes on when its wrapped distance does
// not exclude its bounding spheres, then its exact r12 decides (sphere
// test, (S1)). Needs every periodic axis to have at least 3 cells.
struct CandidateSink {
  Scene const &scene;
  Sorted const &sorted;
  bool want_mu2;
  Buffer<Candidate> &cand;
  Buffer<PairOut> &out;
  long long spheres = 0, examined = 0;
  Status status = kOk;

  // The pair of sorted particles a, b that the plane (S1) does not
  // separate, reach their radii sum: its exact r12, the sphere test on it,
  // then the exact predicate.
  void candidate(long long a, long long b, double reach) noexcept {
    long long const ia = sorted.order.data[a], ib = sorted.order.data[b];
    // r12 of the pair (i, j), i < j.
    bool const forward = ia < ib;
    long long const lo = forward ? a : b, hi = forward ? b : a;
    long long const i = forward ? ia : ib, j = forward ? ib : ia;
    double r[3];
    if (!pair_r12(scene.box, scene.centres + 3 * i, scene.centres + 3 * j, r)) {
      status = kInvalidArgument;
      return;
    }
    if (spheres_apart(r, reach)) return;
    ++examined;
    Candidate &k = cand.data[cand.size++];
    k.i = lo;
    k.j = hi;
    k.r[0] = r[0];
    k.r[1] = r[1];
    k.r[2] = r[2];
    if (cand.size == cand.capacity) flush();
  }
  void flush() noexcept {
    if (status == kOk && cand.size > 0)
      status = narrow(cand.data, cand.size, sorted.q.data, sorted.order.data, scene.q, want_mu2,
                      out);
    cand.size = 0;
  }
};

// Lane l of compress[bits][l]: the position of the l-th set bit of bits
// (4 bits), 0 past the last: the passing lanes of a sphere test, packed.
constexpr signed char kCompress[16][4] = {
    {0, 0, 0, 0}, {0, 0, 0, 0}, {1, 0, 0, 0}, {0, 1, 0, 0}, {2, 0, 0, 0}, {0, 2, 0, 0},
    {1, 2, 0, 0}, {0, 1, 2, 0}, {3, 0, 0, 0}, {0, 3, 0, 0}, {1, 3, 0, 0}, {0, 1, 3, 0},
    {2, 3, 0, 0}, {0, 2, 3, 0}, {1, 2, 3, 0}, {0, 1, 2, 3}};

// A run of consecutive sorted positions [b0, b1) (cells adjacent along x)
// and the image shift of its particles.
struct ScanRange {
  long long b0, b1;
  double shift[3];
};
// Ranges of one cell: (1 + k + k (2k + 1)) rows of the half stencil of
// half-width k <= 2, two runs each at most.
constexpr int kMaxRanges = 32;

// Hits of a scan: sorted position b times kHitRanges plus the index of the
// range it was found in.
constexpr long long kHitRanges = 64;
static_assert(kMaxRanges + 1 <= kHitRanges, "a range index fits in a hit");

// GCC 12 reports the vectors of separate_hits, each assigned whole before
// its use, as maybe uninitialised once inlined into a target variant.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
// (S1) on the hits of particle a (as[r]: the centre of a less the shift of
// range index r), four at a time (the last group padded with its first
// pair); the survivors go to the sink. The lanes are built from scalars in
// registers (no store of scalars reloaded as a vector).
PW85_ALWAYS_INLINE void separate_hits(Sorted const &q, long long a, double const (*as)[3],
                                      long long const *hits, int m, CandidateSink &sink) noexcept {
  using Lane = lanes::VecD<kScanPad>;
  static_assert(kScanPad == 4, "four lanes");
  double const *wx = q.wx.data, *wy = q.wy.data, *wz = q.wz.data, *rad = q.rad.data;
  double const *qa = q.q.data + 6 * a;
  Lane const qav[6] = {Lane{} + qa[0], Lane{} + qa[1], Lane{} + qa[2],
                       Lane{} + qa[3], Lane{} + qa[4], Lane{} + qa[5]};
  Lane const vrerr = Lane{} + (q.grid.periodic ? q.wrap_error : 0.0);
  sink.spheres += m;
  for (int t = 0; t < m; t += kScanPad) {
    long long b[kScanPad];
    double const *ab[kScanPad], *qb[kScanPad];
    for (int l = 0; l < kScanPad; ++l) {
      long long const h = hits[t + l < m ? t + l : t];
      b[l] = h / kHitRanges;
      ab[l] = as[h % kHitRanges];
      qb[l] = q.q.data + 6 * b[l];
    }
    Lane d[3], qbv[6];
    d[0] = Lane{wx[b[0]], wx[b[1]], wx[b[2]], wx[b[3]]} -
           Lane{ab[0][0], ab[1][0], ab[2][0], ab[3][0]};
    d[1] = Lane{wy[b[0]], wy[b[1]], wy[b[2]], wy[b[3]]} -
           Lane{ab[0][1], ab[1][1], ab[2][1], ab[3][1]};
    d[2] = Lane{wz[b[0]], wz[b[1]], wz[b[2]], wz[b[3]]} -
           Lane{ab[0][2], ab[1][2], ab[2][2], ab[3][2]};
    for (int k = 0; k < 6; ++k) qbv[k] = Lane{qb[0][k], qb[1][k], qb[2][k], qb[3][k]};
    auto const separated = plane_separates(d, qav, qbv, vrerr);
    int const w = m - t < kScanPad ? m - t : kScanPad;
    for (int l = 0; l < w; ++l)
      if (!separated[l]) sink.candidate(a, b[l], rad[b[l]] + rad[a]);
  }
}

// Particle a against the ranges (range r < 0: its own cell after it, [a + 1,
// own_end), no shift). Branch-free first pass (most pairs fail the sphere
// test, at unpredictable places): the passing b are packed into hits with
// their range, then separate_hits. Inlined into each instruction-set
// variant of scan_cell.
PW85_ALWAYS_INLINE void scan_particle(Sorted const &q, long long a, ScanRange const *ranges,
                                      int nranges, long long own_end,
                                      CandidateSink &sink) noexcept {
  using Lane = lanes::VecD<kScanPad>;
  double const *wx = q.wx.data, *wy = q.wy.data, *wz = q.wz.data, *rad = q.rad.data;
  Lane const vra = Lane{} + (rad[a] + q.wrap_error);
  // a's centre less each range's shift (index r + 1; 0: its own cell).
  double as[kMaxRanges + 1][3];
  as[0][0] = wx[a], as[0][1] = wy[a], as[0][2] = wz[a];
  for (int r = 0; r < nranges; ++r)
    for (int d = 0; d < 3; ++d) as[r + 1][d] = as[0][d] - ranges[r].shift[d];
  constexpr int kHits = 128;
  long long hits[kHits + kScanPad];
  int m = 0;
  for (int r = -1; r < nranges; ++r) {
    long long const b0 = r < 0 ? a + 1 : ranges[r].b0, b1 = r < 0 ? own_end : ranges[r].b1;
    double const *ab = as[r + 1];
    Lane const vax = Lane{} + ab[0], vay = Lane{} + ab[1], vaz = Lane{} + ab[2];
    // Four lanes at a time (the arrays carry kScanPad readable entries past
    // their end, lanes past b1 dropped).
    for (long long b = b0; b < b1; b += kScanPad) {
      Lane x, y, z, rb;
      std::memcpy(&x, wx + b, sizeof x);
      std::memcpy(&y, wy + b, sizeof y);
      std::memcpy(&z, wz + b, sizeof z);
      std::memcpy(&rb, rad + b, sizeof rb);
      Lane const dx = x - vax, dy = y - vay, dz = z - vaz, reach = vra + rb;
      auto const near = dx * dx + dy * dy + dz * dz < reach * reach * (1 + kMargin);
      int bits = static_cast<int>((near[0] & 1) | (near[1] & 2) | (near[2] & 4) | (near[3] & 8));
      if (b1 - b < kScanPad) bits &= (1 << (b1 - b)) - 1;
      for (int l = 0; l < kScanPad; ++l) hits[m + l] = (b + kCompress[bits][l]) * kHitRanges + (r + 1);
      m += __builtin_popcount(static_cast<unsigned>(bits));
      if (m > kHits - kScanPad) {
        separate_hits(q, a, as, hits, m, sink);
        m = 0;
      }
    }
  }
  separate_hits(q, a, as, hits, m, sink);
}

// Cell c's pairs, fast path (grid of cells at least rho / split wide,
// split = 1 or 2; every periodic axis with at least 2 split + 1 cells).
PW85_ALWAYS_INLINE void scan_cell_body(Sorted const &q, long long c, int split,
                                       CandidateSink &sink) noexcept {
  CellGrid const &g = q.grid;
  Box const &box = g.box;
  long long const nx = g.n[0], ny = g.n[1], nz = g.n[2];
  long long const x = c % nx, y = (c / nx) % ny, z = c / (nx * ny);
  long long const *start = q.start.data;
  int const k = split;
  // Rows (dy, dz) of the half stencil ((dz, dy, dx) > 0): (0, 0) holds the
  // cell itself and x + 1 .. x + k; (dy > 0, 0) and (-k..k, dz > 0) hold
  // x - k .. x + k. A periodic row wraps once at most (nx >= 2k + 1).
  ScanRange ranges[kMaxRanges];
  int nranges = 0;
  for (int dz = 0; dz <= k; ++dz)
    for (int dy = dz == 0 ? 0 : -k; dy <= k; ++dy) {
      long long yy = y + dy, zz = z + dz;
      int wy = 0, wz = 0;
      if (g.periodic) {
        if (yy < 0) { yy += ny; wy = -1; }
        if (yy >= ny) { yy -= ny; wy = 1; }
        if (zz >= nz) { zz -= nz; wz = 1; }
      } else if (yy < 0 || yy >= ny || zz >= nz) {
        continue;
      }
      long long const base = nx * (yy + ny * zz);
      bool const own = dy == 0 && dz == 0;
      long long const lo = own ? x + 1 : x - k, hi = x + k;
      // Up to two runs of consecutive cells [x0, x1] with their x wrap.
      long long runs[2][2];
      int wrap[2];
      int nrun = 0;
      if (g.periodic) {
        if (lo < 0) { runs[nrun][0] = lo + nx; runs[nrun][1] = nx - 1; wrap[nrun++] = -1; }
        long long const m0 = lo < 0 ? 0 : lo, m1 = hi >= nx ? nx - 1 : hi;
        if (m0 <= m1) { runs[nrun][0] = m0; runs[nrun][1] = m1; wrap[nrun++] = 0; }
        if (hi >= nx) { runs[nrun][0] = 0; runs[nrun][1] = hi - nx; wrap[nrun++] = 1; }
      } else {
        long long const a0 = lo < 0 ? 0 : lo, a1 = hi >= nx ? nx - 1 : hi;
        if (a0 <= a1) { runs[nrun][0] = a0; runs[nrun][1] = a1; wrap[nrun++] = 0; }
      }
      for (int r = 0; r < nrun; ++r) {
        ScanRange &s = ranges[nranges];
        s.b0 = start[base + runs[r][0]];
        s.b1 = start[base + runs[r][1] + 1];
        if (s.b0 == s.b1) continue;
        s.shift[0] = s.shift[1] = s.shift[2] = 0;
        if (g.periodic) {
          s.shift[0] = wrap[r] * box.length[0] + wy * box.xy_ly + wz * box.xz_lz;
          s.shift[1] = wy * box.length[1] + wz * box.yz_lz;
          s.shift[2] = wz * box.length[2];
        }
        ++nranges;
      }
    }
  for (long long a = start[c]; a < start[c + 1] && sink.status == kOk; ++a)
    scan_particle(q, a, ranges, nranges, start[c + 1], sink);
}

// scan_cell_body for the CPU at hand: the x86-64-v3 variant (four lanes in
// one AVX register) where the CPU has it, else the portable one; the same
// operations, no contraction (-ffp-contract=off), so the same verdicts.
#if PW85_ISA_LEVELS
PW85_TARGET_V3 void scan_cell_v3(Sorted const &q, long long c, int split,
                                 CandidateSink &sink) noexcept {
  scan_cell_body(q, c, split, sink);
}
#endif
void scan_cell_portable(Sorted const &q, long long c, int split, CandidateSink &sink) noexcept {
  scan_cell_body(q, c, split, sink);
}
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
using ScanCell = void (*)(Sorted const &, long long, int, CandidateSink &) noexcept;
ScanCell scan_cell_for_cpu() noexcept {
#if PW85_ISA_LEVELS
  if (variant_runs(Variant::v3)) return scan_cell_v3;
#endif
  return scan_cell_portable;
}

// Cell c's pairs, general path (any grid): the neighbour cells of higher
// index, each pair through its exact r12.
void scan_cell_general(Sorted const &q, long long c, double rho, CandidateSink &sink) noexcept {
  CellGrid const &g = q.grid;
  long long k[3];
  for (int d = 0; d < 3; ++d) k[d] = stencil(g, d, rho);
  long long const cc[3] = {c % g.n[0], (c / g.n[0]) % g.n[1], c / (g.n[0] * g.n[1])};
  long long const *start = q.start.data;
  for (long long a = start[c]; a < start[c + 1] && sink.status == kOk; ++a) {
    double const ra = q.rad.data[a];
    for_each_neighbour_cell(g, cc, k, [&](long long c2, int const *) noexcept {
      if (c2 < c) return;
      for (long long b = c2 == c ? a + 1 : start[c2]; b < start[c2 + 1]; ++b) {
        double d[3];
        double const *centres = sink.scene.centres;
        if (!pair_r12(g.box, centres + 3 * q.order.data[a], centres + 3 * q.order.data[b], d)) {
          sink.status = kInvalidArgument;
          return;
        }
        if (spheres_apart(d, ra + q.rad.data[b])) continue;
        ++sink.spheres;
        if (plane_separates(d, q.q.data + 6 * a, q.q.data + 6 * b, 0.0)) continue;
        sink.candidate(a, b, ra + q.rad.data[b]);
      }
    });
  }
}

}  // namespace

Status scene_pairs(Scene const &scene, double s, int nthreads, long long capacity,
                   long long *i_out, long long *j_out, double *mu2_out, long long &count,
                   long long *examined) noexcept {
  if (!(s >= 1.0) || !std::isfinite(s) || nthreads < 0 || capacity < 0) return kInvalidArgument;
  long long const n = scene.n;
  Box const &box = scene.box;
  double const s2 = s * s;
  bool const scaled = s2 != 1.0;
  // The scaled matrices s^2 q must be finite, and a box must hold the pairs
  // of the two largest scaled spheres.
  if (scaled && n > 0) {
    double r1 = 0, r2 = 0, qmax = 0;
    for (long long i = 0; i < n; ++i) {
      double const *qi = scene.q + 6 * i;
      double const g = std::sqrt(batch::reach2(qi));
      if (g > r1) {
        r2 = r1;
        r1 = g;
      } else if (g > r2) {
        r2 = g;
      }
      qmax = std::max(qmax, max_abs(qi, kSym));
    }
    if (!(s2 * qmax <= kMaxDouble)) return kInvalidArgument;
    if (n == 1) r2 = r1;
    if (box.periodic && s * (r1 + r2) > box.max_reach) return kInvalidArgument;
  }
  if (n < 2) {
    count = 0;
    if (examined) examined[0] = examined[1] = 0;
    return kOk;
  }
  double const radius_scale = s * (1 + 4 * kMargin);
  double const rho = 2 * scene.radius_max * radius_scale * (1 + kMargin);
  Sorted sorted;
  Status const sort_status =
      sort_by_cell(scene, rho, radius_scale, s2, batch::threads_for(nthreads, n), sorted);
  if (sort_status != kOk) return sort_status;
  CellGrid const &grid = sorted.grid;
  long long const cells = grid.cells;
  bool const fast = !grid.periodic || (grid.n[0] >= 2 * kSplit + 1 &&
                                       grid.n[1] >= 2 * kSplit + 1 &&
                                       grid.n[2] >= 2 * kSplit + 1);

  int const nt = batch::threads_for(nthreads, cells);
  Buffer<PairOut> *results = allocate<Buffer<PairOut>>(nt);
  if (results == nullptr) return kNoMemory;
  for (int t = 0; t < nt; ++t) new (&results[t]) Buffer<PairOut>();
  Status status = kOk;
  long long spheres_total = 0, examined_total = 0;
  bool const want_mu2 = mu2_out != nullptr;
  ScanCell const scan_cell = scan_cell_for_cpu();
  constexpr long long kBlock = 256;
#pragma omp parallel num_threads(nt) if (nt > 1) reduction(+ : spheres_total, examined_total)
  {
#ifdef _OPENMP
    int const tid = omp_get_thread_num();
#else
    int const tid = 0;
#endif
    Buffer<Candidate> cand;
    CandidateSink sink{scene, sorted, want_mu2, cand, results[tid]};
    if (!cand.reserve(kBlock)) sink.status = kNoMemory;
#pragma omp for schedule(dynamic, 16)
    for (long long c = 0; c < cells; ++c) {
      if (sink.status != kOk) continue;
      if (fast) scan_cell(sorted, c, kSplit, sink);
      else scan_cell_general(sorted, c, rho, sink);
    }
    sink.flush();
    spheres_total += sink.spheres;
    examined_total += sink.examined;
    if (sink.status != kOk) {
#pragma omp critical(pw85_scene_status)
      {
        // The error of lowest code wins, so the status is the same for
        // every thread count when one kind of error occurs.
        if (status == kOk || sink.status < status) status = sink.status;
      }
    }
  }
  long long total = 0;
  for (int t = 0; t < nt; ++t) total += results[t].size;
  Buffer<PairOut> merged;
  Buffer<long long> first;
  if (status == kOk && total > 0 && total <= capacity &&
      (!merged.reserve(total) || !first.reserve(n + 1)))
    status = kNoMemory;
  if (status == kOk && total > 0 && total <= capacity) {
    // Counting sort by i, then each i's pairs by j: one order for every
    // thread count.
    for (long long i = 0; i <= n; ++i) first.data[i] = 0;
    for (int t = 0; t < nt; ++t)
      for (long long k = 0; k < results[t].size; ++k) ++first.data[results[t].data[k].i + 1];
    for (long long i = 0; i < n; ++i) first.data[i + 1] += first.data[i];
    for (int t = 0; t < nt; ++t)
      for (long long k = 0; k < results[t].size; ++k) {
        PairOut const &p = results[t].data[k];
        merged.data[first.data[p.i]++] = p;
      }
    long long a = 0;
    for (long long i = 0; i < n; ++i) {
      long long const b = first.data[i];
      if (b - a > 1)
        std::sort(merged.data + a, merged.data + b,
                  [](PairOut const &x, PairOut const &y) { return x.j < y.j; });
      a = b;
    }
  }
  for (int t = 0; t < nt; ++t) results[t].~Buffer<PairOut>();
  std::free(results);
  if (status != kOk) return status;
  count = total;
  if (examined) {
    examined[0] = spheres_total;
    examined[1] = examined_total;
  }
  if (total > capacity) return kCapacity;
  for (long long k = 0; k < total; ++k) {
    i_out[k] = merged.data[k].i;
    j_out[k] = merged.data[k].j;
    if (mu2_out) mu2_out[k] = merged.data[k].mu2;
  }
  return kOk;
}

namespace {

// Checks a trial (i, centre, q) of scene: index, values, and (periodic)
// that its bounding sphere fits the box with itself and with the largest
// one (scene.reach_max), the bound scene_create checks. radius gets the
// trial's bounding radius, reach its sqrt(reach2).
Status check_trial(Scene const &scene, long long i, double const *centre, double const *q,
                   double &radius, double &reach) noexcept {
  if (i < 0 || i >= scene.n) return kInvalidArgument;
  Status const s = check_particle(scene.box, centre, q);
  if (s != kOk) return s;
  radius = bounding_radius(q);
  reach = std::sqrt(batch::reach2(q));
  if (scene.box.periodic) {
    double const other = scene.reach_max > reach ? scene.reach_max : reach;
    if (reach + other > scene.box.max_reach) return kInvalidArgument;
  }
  return kOk;
}

}  // namespace

namespace {

// Screen of the object's grid queries: the image of particle b near the
// point of wrapped centre w (shifted by the lattice vector of its cell's
// wrap) lies at least reach + err from w, err the bound of the roundings of
// the wrapped centres and of r12 (sort_by_cell's, for any accepted centre),
// so the pair's exact r12 is at least reach long. wrap null (an axis
// enumerated whole): no screen.
inline bool image_apart(Scene const &scene, double const w[3], long long b, int const *wrap,
                        double reach, double err) noexcept {
  if (wrap == nullptr) return false;
  double shift[3];
  lattice_shift(scene.box, wrap, shift);
  double const *wb = scene.wrapped + 3 * b;
  double const d[3] = {wb[0] + shift[0] - w[0], wb[1] + shift[1] - w[1], wb[2] + shift[2] - w[2]};
  double const limit = reach + err;
  return d[0] * d[0] + d[1] * d[1] + d[2] * d[2] >= limit * limit * (1 + 2 * kMargin);
}

inline double screen_error(Box const &box) noexcept {
  return box.periodic ? wrap_error_bound(box, kMaxFractional) : 0.0;
}

// The grid walk of test_move and neighbours: fn(b, r, reach(b)) for each
// particle b != i in the cells within rho (the largest reach) of point x
// whose image passes the screen, r the r12 of the pair (min(i, b),
// max(i, b)) with x in i's place (pair_r12). Returns false where a minimum
// image was refused.
template <class Reach, class Fn>
bool for_each_near(Scene const &scene, long long i, double const x[3], double rho, Reach reach,
                   Fn fn) noexcept {
  CellGrid const &g = scene.grid;
  long long k[3], c[3];
  for (int d = 0; d < 3; ++d) k[d] = stencil(g, d, rho);
  cell_coords(g, x, c);
  double w[3];
  wrapped_centre(scene.box, x, w);
  double const err = screen_error(scene.box);
  bool refused = false;
  for_each_neighbour_cell(g, c, k, [&](long long cell, int const *wrap) noexcept {
    for (long long b = scene.head[cell]; b >= 0; b = scene.next[b]) {
      if (b == i) continue;
      double const rb = reach(b);
      if (image_apart(scene, w, b, wrap, rb, err)) continue;
      double r[3];
      double const *cb = scene.centres + 3 * b;
      if (!(i < b ? pair_r12(scene.box, x, cb, r) : pair_r12(scene.box, cb, x, r))) {
        refused = true;
        continue;
      }
      fn(b, r, rb);
    }
  });
  return !refused;
}

}  // namespace

Status scene_test_move(Scene const &scene, long long i, double const centre[3],
                       double const q[6], long long &j_found) noexcept {
  double rt, reach;
  Status const s = check_trial(scene, i, centre, q, rt, reach);
  if (s != kOk) return s;
  // Candidates in ascending j, then the exact predicate in that order.
  constexpr int kLocal = 64;
  Candidate local[kLocal];
  Buffer<Candidate> heap;
  Candidate *cand = local;
  long long m = 0, cap = kLocal;
  bool oom = false;
  bool const walked = for_each_near(
      scene, i, centre, (rt + scene.radius_max) * (1 + 4 * kMargin),
      [&](long long b) noexcept { return rt + scene.radius[b]; },
      [&](long long b, double const r[3], double reach) noexcept {
        if (oom || spheres_apart(r, reach)) return;
        double const *qa = i < b ? q : scene.q + 6 * b;
        double const *qb = i < b ? scene.q + 6 * b : q;
        if (plane_separates(r, qa, qb, 0.0)) return;
        if (m == cap) {
          if (!heap.reserve(2 * cap)) {
            oom = true;
            return;
          }
          if (cand == local) std::memcpy(heap.data, local, sizeof local);
          cand = heap.data;
          cap = heap.capacity;
        }
        cand[m].i = b;  // the other particle
        cand[m].j = b;
        std::memcpy(cand[m].r, r, 3 * sizeof(double));
        ++m;
      });
  if (oom) return kNoMemory;
  if (!walked) return kInvalidArgument;
  std::sort(cand, cand + m, [](Candidate const &x, Candidate const &y) { return x.j < y.j; });
  for (long long t = 0; t < m; ++t) {
    long long const b = cand[t].j;
    double const *qa = i < b ? q : scene.q + 6 * b;
    double const *qb = i < b ? scene.q + 6 * b : q;
    int v = 0;
    Status const st = overlap_one(cand[t].r, qa, qb, v);
    if (st != kOk) return st;
    if (v == 1) {
      j_found = b;
      return kOk;
    }
  }
  j_found = -1;
  return kOk;
}

Status scene_neighbours(Scene const &scene, long long i, double distance, long long capacity,
                        long long *j_out, long long &count) noexcept {
  if (i < 0 || i >= scene.n || !(distance >= 0.0) || !std::isfinite(distance) || capacity < 0)
    return kInvalidArgument;
  if (scene.box.periodic && distance > scene.box.max_reach) return kInvalidArgument;
  double const d2 = distance * distance;
  Buffer<long long> found;
  bool oom = false;
  bool const walked = for_each_near(
      scene, i, scene.centres + 3 * i, distance * (1 + 4 * kMargin),
      [distance](long long) noexcept { return distance; },
      [&](long long b, double const r[3], double) noexcept {
        if (r[0] * r[0] + r[1] * r[1] + r[2] * r[2] < d2 && !found.push(b)) oom = true;
      });
  if (oom) return kNoMemory;
  if (!walked) return kInvalidArgument;
  std::sort(found.data, found.data + found.size);
  count = found.size;
  if (found.size > capacity) return kCapacity;
  if (found.size > 0)
    std::memcpy(j_out, found.data, static_cast<size_t>(found.size) * sizeof(long long));
  return kOk;
}

Status scene_move(Scene &scene, long long i, double const centre[3], double const q[6]) noexcept {
  double rt, reach;
  Status const s = check_trial(scene, i, centre, q, rt, reach);
  if (s != kOk) return s;
  std::memcpy(scene.centres + 3 * i, centre, 3 * sizeof(double));
  std::memcpy(scene.q + 6 * i, q, 6 * sizeof(double));
  scene.radius[i] = rt;
  wrapped_centre(scene.box, centre, scene.wrapped + 3 * i);
  if (rt > scene.radius_max) scene.radius_max = rt;
  if (reach > scene.reach_max) scene.reach_max = reach;
  long long const cell = cell_of_point(scene.grid, centre);
  if (cell != scene.cell_of[i]) {
    unlink(scene, i);
    link(scene, i, cell);
  }
  return kOk;
}

}  // namespace pw85
