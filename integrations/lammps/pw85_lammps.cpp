#include "pw85_lammps.h"

#include <pw85.h>

#include <algorithm>
#include <climits>
#include <cmath>

#include "atom.h"
#include "atom_vec_ellipsoid.h"
#include "comm.h"
#include "error.h"
#include "fmt/format.h"
#include "lammps.h"

using namespace LAMMPS_NS;

namespace pw85_lammps {

AtomVecEllipsoid *ellipsoid_style(LAMMPS *lmp, const char *style) {
  auto *avec = dynamic_cast<AtomVecEllipsoid *>(lmp->atom->style_match("ellipsoid"));
  if (!avec) lmp->error->all(FLERR, "{} requires atom style ellipsoid", style);
  return avec;
}

/* The checks of atom i (see quadratic_forms): "" or the problem. */
static std::string atom_problem(LAMMPS *lmp, AtomVecEllipsoid *avec, int i, const char *style) {
  Atom *atom = lmp->atom;
  const tagint id = atom->tag[i];
  const double *x = atom->x[i];
  if (!(std::isfinite(x[0]) && std::isfinite(x[1]) && std::isfinite(x[2])))
    return fmt::format("{}: atom {} has a position that is not finite ({} {} {})", style, id,
                       x[0], x[1], x[2]);
  if (atom->ellipsoid[i] < 0)
    return fmt::format("{}: atom {} is not an ellipsoid (a point particle, shape 0 0 0)", style,
                       id);
  const double *r = avec->bonus[atom->ellipsoid[i]].shape;
  if (!(std::isfinite(r[0]) && r[0] > 0.0 && std::isfinite(r[1]) && r[1] > 0.0 &&
        std::isfinite(r[2]) && r[2] > 0.0))
    return fmt::format("{}: atom {} has semi-axes {} {} {}: each must be finite and > 0", style,
                       id, r[0], r[1], r[2]);
  return "";
}

std::string quadratic_forms(LAMMPS *lmp, AtomVecEllipsoid *avec, const char *style,
                            std::vector<double> &q) {
  Atom *atom = lmp->atom;
  q.resize(6 * static_cast<size_t>(atom->nlocal + atom->nghost));
  for (int i = 0; i < atom->nlocal; i++) {
    std::string problem = atom_problem(lmp, avec, i, style);
    if (!problem.empty()) return problem;
    const AtomVecEllipsoid::Bonus &b = avec->bonus[atom->ellipsoid[i]];
    const int status = pw85_ellipsoid_quat(b.shape, b.quat, &q[6 * static_cast<size_t>(i)]);
    if (status != PW85_OK)
      return fmt::format("{}: atom {} (semi-axes {} {} {}, quaternion {} {} {} {}): {}", style,
                         atom->tag[i], b.shape[0], b.shape[1], b.shape[2], b.quat[0],
                         b.quat[1], b.quat[2], b.quat[3], pw85_strerror(status));
  }
  return "";
}

int pack_quadratic_forms(const std::vector<double> &q, int n, const int *list, double *buf) {
  for (int k = 0; k < n; k++)
    std::copy(&q[6 * static_cast<size_t>(list[k])], &q[6 * static_cast<size_t>(list[k]) + 6],
              buf + 6 * k);
  return 6 * n;
}

void unpack_quadratic_forms(std::vector<double> &q, int n, int first, const double *buf) {
  std::copy(buf, buf + 6 * n, &q[6 * static_cast<size_t>(first)]);
}

void stop_on_problem(LAMMPS *lmp, const std::string &problem) {
  const int me = lmp->comm->me;
  int mine = problem.empty() ? INT_MAX : me, first = INT_MAX;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, lmp->world);
  if (first == INT_MAX) return;
  int length = me == first ? static_cast<int>(problem.size()) : 0;
  MPI_Bcast(&length, 1, MPI_INT, first, lmp->world);
  std::string message = me == first ? problem : std::string(length, ' ');
  MPI_Bcast(&message[0], length, MPI_CHAR, first, lmp->world);
  lmp->error->all(FLERR, message);
}

std::vector<double> largest_semi_axis_per_type(LAMMPS *lmp, AtomVecEllipsoid *avec,
                                               const char *style) {
  Atom *atom = lmp->atom;
  std::vector<double> mine(atom->ntypes + 1, 0.0), all(atom->ntypes + 1, 0.0);
  std::string problem;
  for (int i = 0; i < atom->nlocal && problem.empty(); i++) {
    problem = atom_problem(lmp, avec, i, style);
    if (!problem.empty()) break;
    const double *r = avec->bonus[atom->ellipsoid[i]].shape;
    double &m = mine[atom->type[i]];
    m = std::max(m, std::max(r[0], std::max(r[1], r[2])));
  }
  stop_on_problem(lmp, problem);
  MPI_Allreduce(mine.data(), all.data(), atom->ntypes + 1, MPI_DOUBLE, MPI_MAX, lmp->world);
  return all;
}

}  // namespace pw85_lammps
