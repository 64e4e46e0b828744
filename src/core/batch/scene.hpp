// The scene object (docs/scene.md): n ellipsoids, optionally in a periodic
// box, with the pairs within a scale factor s found by a cell grid over
// bounding spheres, a conservative separating-plane filter and the exact
// overlap predicate. The C layer (src/capi/configuration_capi.cpp) checks
// pointers and copies out; everything else is here.
#pragma once

#include "batch/cell_grid.hpp"
#include "common/status.hpp"

namespace pw85 {

struct Scene {
  long long n = 0;
  long long capacity = 0;  // particles the arrays hold
  batch::Box box;
  double *centres = nullptr;  // 3n, as given
  double *q = nullptr;        // 6n
  double *radius = nullptr;   // n, bounding-sphere radius rounded up
  double *wrapped = nullptr;  // 3n, centres wrapped into the box (wrapped_centre)
  double radius_max = 0;      // >= every radius
  // >= every sqrt(batch::reach2(q_i)), and (with a box) at most half of
  // box.max_reach: no bounding sphere meets its own images.
  double reach_max = 0;
  // Cell grid for test_move/move: doubly linked lists of the particles of
  // each cell.
  CellGrid grid;
  long long grid_capacity = 0;
  long long *head = nullptr;     // cells: first particle or -1
  long long *next = nullptr;     // n
  long long *prev = nullptr;     // n
  long long *cell_of = nullptr;  // n
};

// Sets up scene (zero-initialised, or destroyed) for n particles.
// Returns kOk, kInvalidArgument (bad box, n < 0, a non-finite value: bad
// gets the particle, -1 for the box), kNotSpd (bad: the particle), kRange
// (a centre more than 2^20 box lengths out of the box), kInvalidArgument
// (bounding spheres too large for the box, bad: the particle with the largest)
// or kNoMemory (allocation failed). On error scene is left as it was.
Status scene_assign(Scene &scene, long long n, double const *centres, double const *q,
                    double const *box, long long &bad) noexcept;

void scene_release(Scene &scene) noexcept;

// Pairs i < j with verdict overlap(r12, s^2 Q_i, s^2 Q_j) = 1 (exact; s = 1:
// the matrices as given), r12 = c_j - c_i or its minimum image, sorted by
// (i, j). count receives their number; when count <= capacity, i_out, j_out
// (and mu2_out, when not null: mu^2 by DEFAULT of the unscaled pair) receive
// them, else nothing is written and kCapacity is returned.
Status scene_pairs(Scene const &scene, double s, int nthreads, long long capacity,
                   long long *i_out, long long *j_out, double *mu2_out, long long &count,
                   long long *examined) noexcept;

// Smallest j != i whose ellipsoid overlaps particle i moved to (centre, q),
// or -1.
Status scene_test_move(Scene const &scene, long long i, double const centre[3],
                       double const q[6], long long &j) noexcept;

// The particles j != i whose centre lies closer than distance to particle
// i's: r . r < distance^2, r = c_j - c_i taken for the pair (min(i, j),
// max(i, j)) with its image as scene_pairs takes it; ascending j. count
// receives their number; when count <= capacity, j_out receives them, else
// nothing is written and kCapacity is returned. distance finite, >= 0 and,
// in a box, at most box.max_reach.
Status scene_neighbours(Scene const &scene, long long i, double distance, long long capacity,
                        long long *j_out, long long &count) noexcept;

// Moves particle i to (centre, q) (no overlap test); on error nothing changes.
Status scene_move(Scene &scene, long long i, double const centre[3], double const q[6]) noexcept;

}  // namespace pw85
