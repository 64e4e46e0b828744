/* pair_style pw85/soft: U = epsilon (1 - mu^2)^3 for mu^2 < 1, zero beyond,
 * mu^2 the Perram-Wertheim contact function of two ellipsoids; forces and
 * torques from pw85_contact_derivatives_pairs. integrations/lammps/README.md. */
#ifndef PAIR_PW85_SOFT_H
#define PAIR_PW85_SOFT_H

#include <pw85.h>

#include <string>
#include <vector>

#include "pair.h"

namespace LAMMPS_NS {

class PairPW85Soft : public Pair {
 public:
  explicit PairPW85Soft(class LAMMPS *);
  ~PairPW85Soft() override;
  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  double init_one(int, int) override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;

 private:
  void allocate();
  std::string owned_quadratic_forms();
  void overlapping_pairs(int eflag);
  std::string contact_derivatives();
  class AtomVecEllipsoid *avec = nullptr;
  double **epsilon = nullptr;
  std::vector<double> semi_axis_max;  // largest semi-axis of each type
  // per-step scratch: the matrices of the owned and ghost atoms; the pairs
  // (i, j), their r12, Q_i, Q_j and special-bond factor: the candidates
  // (centre distance below the cutoff), then those that overlap
  std::vector<double> q, r12, q1, q2, weight;
  std::vector<int> first, second;
  std::vector<pw85_derivatives_t> derivatives;
  std::vector<int> overlap, status;
};

}  // namespace LAMMPS_NS

#endif
