#!/usr/bin/env bash
# The LAMMPS plugin's tests (suite lammps, integrations/lammps/README.md): builds LAMMPS and
# the plugin with build.sh (once; later runs reuse them), registers the suite
# in the meson build directory (options lammps_lmp, lammps_plugin) and runs it.
#
#   integrations/lammps/run_tests.sh [MESON_BUILD_DIR]   (default build/)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
builddir=${1:-build}
paths=$(bash integrations/lammps/build.sh "$builddir")
lmp=$(sed -n 1p <<<"$paths")
plugin=$(sed -n 2p <<<"$paths")
meson setup --reconfigure "$builddir" -Dlammps_lmp="$lmp" -Dlammps_plugin="$plugin" | tail -n 3
meson test -C "$builddir" --suite lammps --print-errorlogs
