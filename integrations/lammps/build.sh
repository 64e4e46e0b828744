#!/usr/bin/env bash
# Builds LAMMPS (packages ASPHERE and PLUGIN, OpenMPI) and the pw85 plugin
# against it, then prints two lines: the path of lmp, then the path of the
# plugin (pw85plugin.so).
#
#   integrations/lammps/build.sh [MESON_BUILD_DIR [LAMMPS_SOURCE_TREE]]
#
# MESON_BUILD_DIR (default build/) is the project's meson build directory
# holding libpw85.so. Without LAMMPS_SOURCE_TREE (nor $LAMMPS_SRC), Debian's
# source package of LAMMPS is fetched with apt-get source (a deb-src entry for
# bookworm is added when absent) into build-lammps/ under the repository root
# and built there once; later runs reuse that build. All progress goes to
# stderr, so stdout holds only the two paths.
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
meson_build=${1:-$repo/build}
area=$repo/build-lammps
mkdir -p "$area"
log() { echo "lammps/build.sh: $*" >&2; }

need=()
for pkg in libopenmpi-dev openmpi-bin dpkg-dev cmake; do
  dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q 'ok installed' || need+=("$pkg")
done
lammps_src=${2:-${LAMMPS_SRC:-}}
if [ -z "$lammps_src" ]; then
  lammps_src=$(ls -d "$area"/source/lammps-*/ 2>/dev/null | head -n1 || true)
  lammps_src=${lammps_src%/}
fi
if ((${#need[@]})) || [ -z "$lammps_src" ]; then
  apt-get update -qq >&2
  if ((${#need[@]})); then
    log "installing ${need[*]}"
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${need[@]}" >&2
  fi
fi
if [ -z "$lammps_src" ]; then
  if ! apt-cache showsrc lammps 2>/dev/null | grep -q '^Package: lammps'; then
    log "adding a deb-src entry for bookworm"
    cat > /etc/apt/sources.list.d/pw85-deb-src.sources <<'SRC'
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: bookworm
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
SRC
    apt-get update -qq >&2
  fi
  log "fetching Debian's source package of LAMMPS into $area/source"
  mkdir -p "$area/source"
  (cd "$area/source" && apt-get source -qq lammps >&2)
  lammps_src=$(ls -d "$area"/source/lammps-*/ | head -n1)
  lammps_src=${lammps_src%/}
fi
lammps_src=$(cd "$lammps_src" && pwd)

lammps_build=$area/lammps-build
# Without LAMMPS_EXCEPTIONS (its default): error->one then flushes the
# output before MPI_Abort, so that the message of an error on one rank is
# printed (the exceptions build aborts without flushing it).
options=(-DCMAKE_BUILD_TYPE=Release -DBUILD_MPI=on -DBUILD_SHARED_LIBS=on -DPKG_ASPHERE=on
         -DPKG_PLUGIN=on -DLAMMPS_EXCEPTIONS=off -DBUILD_OMP=off -DWITH_JPEG=off -DWITH_PNG=off
         -DWITH_GZIP=off -DWITH_FFMPEG=off)
stamp="$lammps_src ${options[*]}"
if [ ! -x "$lammps_build/lmp" ] || [ "$(cat "$lammps_build/.pw85-build" 2>/dev/null)" != "$stamp" ]; then
  log "building LAMMPS from $lammps_src in $lammps_build (several minutes)"
  cmake -S "$lammps_src/cmake" -B "$lammps_build" "${options[@]}" >&2
  cmake --build "$lammps_build" -j2 >&2
  echo "$stamp" > "$lammps_build/.pw85-build"
fi

# The plugin: compiled with the LAMMPS library's own definitions (integer
# sizes, exceptions) against its headers, linked to libpw85 of the meson
# build (found at run time through its rpath).
meson_build=$(cd "$meson_build" && pwd)
libdir=$meson_build/src
[ -f "$libdir/libpw85.so" ] || { log "no $libdir/libpw85.so: build the project first (bash .ci/setup)"; exit 1; }
defines=$(sed -n 's/^CXX_DEFINES = //p' "$lammps_build/CMakeFiles/lammps.dir/flags.make")
plugin_dir=$area/plugin
mkdir -p "$plugin_dir"
here=$repo/integrations/lammps
sources=("$here/pw85plugin.cpp" "$here/pair_pw85_soft.cpp" "$here/compute_pw85_overlap.cpp"
         "$here/pw85_lammps.cpp")
plugin=$plugin_dir/pw85plugin.so
newest=$(ls -t "${sources[@]}" "$here"/*.h "$libdir/libpw85.so" "$lammps_build/liblammps.so" "$0" | head -n1)
if [ ! -f "$plugin" ] || [ "$newest" -nt "$plugin" ]; then
  log "building $plugin"
  # shellcheck disable=SC2086  # $defines is a list of -D flags
  mpicxx -std=c++11 -O2 -g -fPIC -shared -Wall -Wextra $defines \
    -I"$lammps_src/src" -I"$repo/include" "${sources[@]}" \
    -L"$libdir" -Wl,-rpath,"$libdir" -lpw85 -o "$plugin.tmp"
  mv "$plugin.tmp" "$plugin"
fi
echo "$lammps_build/lmp"
echo "$plugin"
