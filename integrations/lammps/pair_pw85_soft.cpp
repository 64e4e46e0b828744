#include "pair_pw85_soft.h"

#include <algorithm>
#include <cmath>

#include "atom.h"
#include "atom_vec_ellipsoid.h"
#include "comm.h"
#include "error.h"
#include "fmt/format.h"
#include "force.h"
#include "memory.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "pw85_lammps.h"

using namespace LAMMPS_NS;

static const char kStyle[] = "pair pw85/soft";

PairPW85Soft::PairPW85Soft(LAMMPS *lmp) : Pair(lmp) {
  single_enable = 0;
  comm_forward = 6;  // Q of the ghost atoms
  restartinfo = 0;
  one_coeff = 0;
}

PairPW85Soft::~PairPW85Soft() {
  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
    memory->destroy(epsilon);
  }
}

void PairPW85Soft::allocate() {
  allocated = 1;
  const int n = atom->ntypes;
  memory->create(setflag, n + 1, n + 1, "pair:setflag");
  memory->create(cutsq, n + 1, n + 1, "pair:cutsq");
  memory->create(epsilon, n + 1, n + 1, "pair:epsilon");
  for (int i = 1; i <= n; i++)
    for (int j = i; j <= n; j++) setflag[i][j] = 0;
}

void PairPW85Soft::settings(int narg, char **) {
  if (narg != 0) error->all(FLERR, "Illegal pair_style pw85/soft command: it takes no argument");
}

/* pair_coeff I J epsilon */
void PairPW85Soft::coeff(int narg, char **arg) {
  if (narg != 3) error->all(FLERR, "Incorrect args for pair coefficients: pair_coeff I J epsilon");
  if (!allocated) allocate();
  int ilo, ihi, jlo, jhi;
  utils::bounds(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, error);
  utils::bounds(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, error);
  const double eps = utils::numeric(FLERR, arg[2], false, lmp);
  if (!(std::isfinite(eps) && eps >= 0.0))
    error->all(FLERR, "pair pw85/soft: epsilon {} is not finite and >= 0", eps);
  int count = 0;
  for (int i = ilo; i <= ihi; i++)
    for (int j = std::max(jlo, i); j <= jhi; j++) {
      epsilon[i][j] = eps;
      setflag[i][j] = 1;
      count++;
    }
  if (count == 0) error->all(FLERR, "Incorrect args for pair coefficients");
}

void PairPW85Soft::init_style() {
  avec = pw85_lammps::ellipsoid_style(lmp, kStyle);
  neighbor->request(this, instance_me);
  semi_axis_max = pw85_lammps::largest_semi_axis_per_type(lmp, avec, kStyle);
}

/* The cutoff of a type pair: two ellipsoids whose centres are farther apart
 * than the sum of their largest semi-axes do not overlap (mu^2 >= 1, U = 0).
 * Unset pairs mix epsilon geometrically. */
double PairPW85Soft::init_one(int i, int j) {
  if (setflag[i][j] == 0) epsilon[i][j] = std::sqrt(epsilon[i][i] * epsilon[j][j]);
  epsilon[j][i] = epsilon[i][j];
  return semi_axis_max[i] + semi_axis_max[j];
}

/* Q of the owned atoms (pw85_lammps::quadratic_forms), and the check that
 * no atom outgrew the cutoff; "" or the first problem. */
std::string PairPW85Soft::owned_quadratic_forms() {
  std::string problem = pw85_lammps::quadratic_forms(lmp, avec, kStyle, q);
  if (!problem.empty()) return problem;
  for (int i = 0; i < atom->nlocal; i++) {
    const double *r = avec->bonus[atom->ellipsoid[i]].shape;
    if (std::max(r[0], std::max(r[1], r[2])) > semi_axis_max[atom->type[i]])
      return fmt::format("{}: atom {} grew beyond the largest semi-axis of its type at the "
                         "start of the run ({}): the cutoff would miss contacts",
                         kStyle, atom->tag[i], semi_axis_max[atom->type[i]]);
  }
  return "";
}

int PairPW85Soft::pack_forward_comm(int n, int *list, double *buf, int, int *) {
  return pw85_lammps::pack_quadratic_forms(q, n, list, buf);
}

void PairPW85Soft::unpack_forward_comm(int n, int first_ghost, double *buf) {
  pw85_lammps::unpack_quadratic_forms(q, n, first_ghost, buf);
}

/* The candidate pairs of the neighbour list: r12 = c_j - c_i (a ghost atom
 * carries its periodic image), centre distance below the cutoff; pairs
 * with coincident centres are tallied here (mu^2 = 0: U = epsilon, no
 * force, no torque). The exact overlap predicate (a few ns per pair) then
 * keeps the pairs with mu^2 < 1, where U > 0, for the derivatives (a few
 * hundred ns); a pair it fails on is kept too. */
void PairPW85Soft::overlapping_pairs(int eflag) {
  double **x = atom->x;
  const int *type = atom->type;
  const int nlocal = atom->nlocal;
  const double *special_lj = force->special_lj;
  first.clear(), second.clear(), r12.clear(), q1.clear(), q2.clear(), weight.clear();

  for (int ii = 0; ii < list->inum; ii++) {
    const int i = list->ilist[ii];
    const int *jlist = list->firstneigh[i];
    for (int jj = 0; jj < list->numneigh[i]; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      const double factor = special_lj[sbmask(jlist[jj])];
      const double d[3] = {x[j][0] - x[i][0], x[j][1] - x[i][1], x[j][2] - x[i][2]};
      const double rsq = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
      if (!(rsq < cutsq[type[i]][type[j]]) || factor == 0.0) continue;
      if (rsq == 0.0) {
        if (eflag)
          ev_tally_xyz(i, j, nlocal, force->newton_pair, factor * epsilon[type[i]][type[j]], 0.0,
                       0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
        continue;
      }
      first.push_back(i), second.push_back(j), weight.push_back(factor);
      r12.insert(r12.end(), d, d + 3);
      q1.insert(q1.end(), &q[6 * static_cast<size_t>(i)], &q[6 * static_cast<size_t>(i) + 6]);
      q2.insert(q2.end(), &q[6 * static_cast<size_t>(j)], &q[6 * static_cast<size_t>(j) + 6]);
    }
  }

  const long long m = static_cast<long long>(first.size());
  overlap.resize(m);
  if (m > 0) pw85_overlap_pairs(m, r12.data(), q1.data(), q2.data(), overlap.data(), nullptr, 1);
  size_t kept = 0;
  for (size_t k = 0; k < first.size(); k++) {
    if (overlap[k] == 0) continue;
    first[kept] = first[k], second[kept] = second[k], weight[kept] = weight[k];
    std::copy(&r12[3 * k], &r12[3 * k + 3], &r12[3 * kept]);
    std::copy(&q1[6 * k], &q1[6 * k + 6], &q1[6 * kept]);
    std::copy(&q2[6 * k], &q2[6 * k + 6], &q2[6 * kept]);
    kept++;
  }
  first.resize(kept), second.resize(kept), weight.resize(kept);
  r12.resize(3 * kept), q1.resize(6 * kept), q2.resize(6 * kept);
}

/* The derivatives of the overlapping pairs; "" or the first pair the
 * library fails on (PW85_ERR_INACCURATE, every field written, is used). */
std::string PairPW85Soft::contact_derivatives() {
  const long long m = static_cast<long long>(first.size());
  derivatives.resize(m);
  status.resize(m);
  if (m > 0)
    pw85_contact_derivatives_pairs(m, r12.data(), q1.data(), q2.data(), derivatives.data(),
                                   status.data(), 1);
  for (long long k = 0; k < m; k++)
    if (status[k] != PW85_OK && status[k] != PW85_ERR_INACCURATE)
      return fmt::format("{}: atoms {} and {} (r12 = {} {} {}): {}", kStyle,
                         atom->tag[first[k]], atom->tag[second[k]], r12[3 * k],
                         r12[3 * k + 1], r12[3 * k + 2], pw85_strerror(status[k]));
  return "";
}

void PairPW85Soft::compute(int eflag, int vflag) {
  ev_init(eflag, vflag);
  std::string problem = owned_quadratic_forms();
  comm->forward_comm_pair(this);  // collective: on every rank, problem or not
  if (problem.empty()) {
    overlapping_pairs(eflag);
    problem = contact_derivatives();
  } else {
    first.clear();
  }
  pw85_lammps::stop_on_problem(lmp, problem);

  // U = eps (1 - mu^2)^3; dU/dmu^2 = -3 eps (1 - mu^2)^2; F_j = -dU/dmu^2
  // d mu^2/d r12 = -F_i; torques -dU/dmu^2 d mu^2/d theta (docs/derivatives.md).
  double **f = atom->f, **torque = atom->torque;
  const int *type = atom->type;
  const int nlocal = atom->nlocal, newton_pair = force->newton_pair;
  for (size_t k = 0; k < first.size(); k++) {
    const pw85_derivatives_t &d = derivatives[k];
    if (!(d.mu2 < 1.0)) continue;
    const int i = first[k], j = second[k];
    const double eps = weight[k] * epsilon[type[i]][type[j]], g = 1.0 - d.mu2;
    const double dudmu2 = -3.0 * eps * g * g;
    const double fi[3] = {dudmu2 * d.d_r12[0], dudmu2 * d.d_r12[1], dudmu2 * d.d_r12[2]};
    for (int e = 0; e < 3; e++) {
      f[i][e] += fi[e];
      torque[i][e] -= dudmu2 * d.d_theta1[e];
    }
    if (newton_pair || j < nlocal)
      for (int e = 0; e < 3; e++) {
        f[j][e] -= fi[e];
        torque[j][e] -= dudmu2 * d.d_theta2[e];
      }
    if (evflag)
      ev_tally_xyz(i, j, nlocal, newton_pair, eflag ? eps * g * g * g : 0.0, 0.0, fi[0], fi[1],
                   fi[2], -r12[3 * k], -r12[3 * k + 1], -r12[3 * k + 2]);
  }
  if (vflag_fdotr) virial_fdotr_compute();
}
