#include "compute_pw85_overlap.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "atom.h"
#include "atom_vec_ellipsoid.h"
#include "comm.h"
#include "error.h"
#include "fmt/format.h"
#include "force.h"
#include "neigh_list.h"
#include "neigh_request.h"
#include "neighbor.h"
#include "pair.h"
#include "pw85_lammps.h"
#include "update.h"

using namespace LAMMPS_NS;

static const char kStyle[] = "compute pw85/overlap";

ComputePW85Overlap::ComputePW85Overlap(LAMMPS *lmp, int narg, char **arg)
    : Compute(lmp, narg, arg) {
  if (narg != 3) error->all(FLERR, "Illegal compute pw85/overlap command: it takes no argument");
  vector_flag = 1;
  size_vector = 2;
  extvector = 0;
  vector = new double[2];
  comm_forward = 6;  // Q of the ghost atoms
}

ComputePW85Overlap::~ComputePW85Overlap() { delete[] vector; }

/* An occasional full neighbour list of cutoff 2 R + skin, R the largest
 * semi-axis: every pair that can overlap is in it. */
void ComputePW85Overlap::init() {
  avec = pw85_lammps::ellipsoid_style(lmp, kStyle);
  const std::vector<double> semi_axis = pw85_lammps::largest_semi_axis_per_type(lmp, avec, kStyle);
  cutoff = 2.0 * *std::max_element(semi_axis.begin(), semi_axis.end());
  const double cutneigh = cutoff + neighbor->skin;
  const double cutghost = std::max(force->pair ? force->pair->cutforce + neighbor->skin : 0.0,
                                   comm->cutghostuser);
  if (cutneigh > cutghost)
    error->all(FLERR, "{}: needs ghost atoms to {} (twice the largest semi-axis plus the skin): "
               "use comm_modify cutoff", kStyle, cutneigh);
  const int irequest = neighbor->request(this, instance_me);
  neighbor->requests[irequest]->pair = 0;
  neighbor->requests[irequest]->compute = 1;
  neighbor->requests[irequest]->half = 0;
  neighbor->requests[irequest]->full = 1;
  neighbor->requests[irequest]->occasional = 1;
  neighbor->requests[irequest]->cut = 1;
  neighbor->requests[irequest]->cutoff = cutneigh;
}

void ComputePW85Overlap::init_list(int, NeighList *ptr) { list = ptr; }

int ComputePW85Overlap::pack_forward_comm(int n, int *list, double *buf, int, int *) {
  return pw85_lammps::pack_quadratic_forms(q, n, list, buf);
}

void ComputePW85Overlap::unpack_forward_comm(int n, int first_ghost, double *buf) {
  pw85_lammps::unpack_quadratic_forms(q, n, first_ghost, buf);
}

void ComputePW85Overlap::compute_vector() {
  invoked_vector = update->ntimestep;
  neighbor->build_one(list);
  double **x = atom->x;
  const int *mask = atom->mask;
  const tagint *tag = atom->tag;
  std::string problem = pw85_lammps::quadratic_forms(lmp, avec, kStyle, q);
  comm->forward_comm_compute(this);  // collective: on every rank, problem or not

  // Each pair once over all ranks: the full list holds (i, j) and (j, i)
  // (j a ghost image on this or another rank); the lower ID counts it.
  first.clear(), second.clear(), r12.clear(), q1.clear(), q2.clear();
  for (int ii = 0; ii < list->inum && problem.empty(); ii++) {
    const int i = list->ilist[ii];
    if (!(mask[i] & groupbit)) continue;
    const int *jlist = list->firstneigh[i];
    for (int jj = 0; jj < list->numneigh[i]; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      if (!(mask[j] & groupbit) || !(tag[i] < tag[j])) continue;
      const double d[3] = {x[j][0] - x[i][0], x[j][1] - x[i][1], x[j][2] - x[i][2]};
      if (!(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < cutoff * cutoff)) continue;
      first.push_back(i), second.push_back(j);
      r12.insert(r12.end(), d, d + 3);
      q1.insert(q1.end(), &q[6 * static_cast<size_t>(i)], &q[6 * static_cast<size_t>(i) + 6]);
      q2.insert(q2.end(), &q[6 * static_cast<size_t>(j)], &q[6 * static_cast<size_t>(j) + 6]);
    }
  }
  const long long m = static_cast<long long>(first.size());
  overlap.resize(m), status.resize(m), result.resize(m);
  double mine[2] = {0.0, std::numeric_limits<double>::infinity()};
  if (m > 0) {
    pw85_overlap_pairs(m, r12.data(), q1.data(), q2.data(), overlap.data(), nullptr, 1);
    pw85_contact_function_pairs(m, r12.data(), q1.data(), q2.data(), PW85_METHOD_DEFAULT,
                                result.data(), status.data(), 1);
  }
  for (long long k = 0; k < m && problem.empty(); k++) {
    if (overlap[k] < 0 || (status[k] != PW85_OK && status[k] != PW85_ERR_INACCURATE))
      problem = fmt::format("{}: atoms {} and {}: {}", kStyle, tag[first[k]], tag[second[k]],
                            pw85_strerror(overlap[k] < 0 ? overlap[k] : status[k]));
    mine[0] += overlap[k];
    mine[1] = std::min(mine[1], result[k].mu2);
  }
  pw85_lammps::stop_on_problem(lmp, problem);
  MPI_Allreduce(&mine[0], &vector[0], 1, MPI_DOUBLE, MPI_SUM, world);
  MPI_Allreduce(&mine[1], &vector[1], 1, MPI_DOUBLE, MPI_MIN, world);
}
