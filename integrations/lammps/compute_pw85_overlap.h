/* compute ID group pw85/overlap: global vector of 2, the number of
 * overlapping pairs (exact verdicts of pw85_overlap) and the smallest mu^2
 * over the pairs of the group closer than twice the largest semi-axis.
 * integrations/lammps/README.md. */
#ifndef COMPUTE_PW85_OVERLAP_H
#define COMPUTE_PW85_OVERLAP_H

#include <pw85.h>

#include <vector>

#include "compute.h"

namespace LAMMPS_NS {

class ComputePW85Overlap : public Compute {
 public:
  ComputePW85Overlap(class LAMMPS *, int, char **);
  ~ComputePW85Overlap() override;
  void init() override;
  void init_list(int, class NeighList *) override;
  void compute_vector() override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;

 private:
  class AtomVecEllipsoid *avec = nullptr;
  class NeighList *list = nullptr;
  double cutoff = 0.0;  // twice the largest semi-axis of all atoms
  std::vector<double> q, r12, q1, q2;
  std::vector<int> first, second, overlap, status;
  std::vector<pw85_result> result;
};

}  // namespace LAMMPS_NS

#endif
