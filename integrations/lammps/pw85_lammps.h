/* Shared by pair_style pw85/soft and compute pw85/overlap: the quadratic
 * forms of LAMMPS's ellipsoids, the largest semi-axis of each atom type,
 * and the collective stop on bad input. integrations/lammps/README.md. */
#ifndef PW85_LAMMPS_H
#define PW85_LAMMPS_H

#include <string>
#include <vector>

namespace LAMMPS_NS {
class LAMMPS;
class AtomVecEllipsoid;
}  // namespace LAMMPS_NS

namespace pw85_lammps {

/* The atom style's ellipsoid part (atom_style ellipsoid, or a hybrid style
 * holding it); error->all naming `style` when there is none. */
LAMMPS_NS::AtomVecEllipsoid *ellipsoid_style(LAMMPS_NS::LAMMPS *lmp, const char *style);

/* Resizes q to 6 (nlocal + nghost) and writes the quadratic form
 * Q = R diag(r^2) R^T of each owned atom from its semi-axes r (LAMMPS
 * stores the radii, half the diameters of the data file and of `set
 * shape`) and its quaternion (w, x, y, z) (pw85_ellipsoid_quat); the ghost
 * atoms' entries are left to the caller's forward communication
 * (pack_quadratic_forms, unpack_quadratic_forms): a ghost is an image of an
 * owned atom, with its shape and orientation. Returns "" or, for the first
 * owned atom that is not an ellipsoid (a point particle: shape 0), has a
 * semi-axis that is not finite and > 0, a quaternion that is not unit or a
 * position that is not finite, a message naming `style` and the atom's ID
 * (q is then incomplete). */
std::string quadratic_forms(LAMMPS_NS::LAMMPS *lmp, LAMMPS_NS::AtomVecEllipsoid *avec,
                            const char *style, std::vector<double> &q);

/* The forward communication of Q (6 doubles per atom) for the
 * pack_forward_comm and unpack_forward_comm of the pair style and the
 * compute. */
int pack_quadratic_forms(const std::vector<double> &q, int n, const int *list, double *buf);
void unpack_quadratic_forms(std::vector<double> &q, int n, int first, const double *buf);

/* Collective over the ranks of the simulation: when any rank's `problem` is
 * not empty, every rank stops with error->all and the message of the lowest
 * such rank (printed once, the output flushed); else returns. One
 * MPI_Allreduce of an int when there is no problem. */
void stop_on_problem(LAMMPS_NS::LAMMPS *lmp, const std::string &problem);

/* The largest semi-axis of the atoms of each type over all ranks (index
 * 1..ntypes; 0 for a type without atoms). Collective; stops (as
 * stop_on_problem) on an owned atom that fails the checks of
 * quadratic_forms. */
std::vector<double> largest_semi_axis_per_type(LAMMPS_NS::LAMMPS *lmp,
                                               LAMMPS_NS::AtomVecEllipsoid *avec,
                                               const char *style);

}  // namespace pw85_lammps

#endif
