/* The LAMMPS plugin of libpw85: pair_style pw85/soft and compute
 * pw85/overlap, loaded with `plugin load pw85plugin.so` (integrations/lammps/README.md). */
#include "compute_pw85_overlap.h"
#include "lammpsplugin.h"
#include "pair_pw85_soft.h"
#include "version.h"

using namespace LAMMPS_NS;

static Pair *pw85_soft_creator(LAMMPS *lmp) { return new PairPW85Soft(lmp); }

static Compute *pw85_overlap_creator(LAMMPS *lmp, int argc, char **argv) {
  return new ComputePW85Overlap(lmp, argc, argv);
}

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc) {
  auto register_plugin = (lammpsplugin_regfunc)regfunc;
  lammpsplugin_t plugin;
  plugin.version = LAMMPS_VERSION;
  plugin.style = "pair";
  plugin.name = "pw85/soft";
  plugin.info = "pw85/soft: U = eps (1 - mu^2)^3 of the ellipsoid contact function (libpw85)";
  plugin.author = "libpw85";
  plugin.creator.v1 = (lammpsplugin_factory1 *)&pw85_soft_creator;
  plugin.handle = handle;
  (*register_plugin)(&plugin, lmp);

  plugin.style = "compute";
  plugin.name = "pw85/overlap";
  plugin.info = "pw85/overlap: overlapping pairs and smallest mu^2 (libpw85)";
  plugin.creator.v2 = (lammpsplugin_factory2 *)&pw85_overlap_creator;
  (*register_plugin)(&plugin, lmp);
}
