#!/bin/sh
# CMake package test: stage `meson install` of BUILDDIR into a temporary
# directory, then configure, build and run the CMake project tests/cmake
# against it (find_package(pw85 CONFIG REQUIRED), CMAKE_PREFIX_PATH the
# staged prefix): tutorial.c linked to pw85::pw85 (and to pw85::pw85_static
# when installed), header_legacy.c to pw85::pw85_legacy, example.f90 to
# pw85::pw85_fortran when FC is given. Exit 77 (skip) when cmake is absent.
# Leaves nothing behind.
#
# usage: check_cmake.sh BUILDDIR SRCDIR PREFIX CC [FC]
#   environment: MESON, CMAKE (default: meson, cmake on PATH)
set -eu

builddir=$1 srcdir=$2 prefix=$3 cc=$4
fc=${5:-}
cmake=${CMAKE:-cmake}
if ! command -v "$cmake" >/dev/null 2>&1; then
  echo "# $cmake not found: CMake package test skipped"
  exit 77
fi

tmp=$(mktemp -d "${TMPDIR:-/tmp}/pw85-cmake-test.XXXXXX")
trap 'rm -rf "$tmp"' EXIT INT TERM
stage=$tmp/stage

"${MESON:-meson}" install -C "$builddir" --destdir "$stage" --no-rebuild --quiet >"$tmp/install.log" 2>&1 || {
  cat "$tmp/install.log"
  echo "FAIL: meson install --destdir failed"
  exit 1
}
config=$(find "$stage$prefix" -path '*/cmake/pw85/pw85Config.cmake')
[ -n "$config" ] || { echo "FAIL: no cmake/pw85/pw85Config.cmake installed"; exit 1; }
echo "installed: ${config#"$stage"}"

fortran=OFF
[ -n "$fc" ] && fortran=ON
CC=$cc FC=$fc "$cmake" -S "$srcdir/tests/cmake" -B "$tmp/build" \
  -DCMAKE_PREFIX_PATH="$stage$prefix" -DPW85_FORTRAN=$fortran \
  >"$tmp/configure.log" 2>&1 || {
  cat "$tmp/configure.log"
  echo "FAIL: cmake configure"
  exit 1
}
grep -- '-- pw85 ' "$tmp/configure.log"
"$cmake" --build "$tmp/build" >"$tmp/build.log" 2>&1 || {
  cat "$tmp/build.log"
  echo "FAIL: cmake --build"
  exit 1
}

status=0
expect() {  # expect FILE LINE: FILE must hold LINE as a whole line.
  if grep -qxF -- "$2" "$1"; then
    echo "ok - $(basename "$1"): '$2'"
  else
    echo "FAIL: $(basename "$1") lacks the line '$2'"
    status=1
  fi
}
# run PROGRAM LIB: runs it (exit 0 required) into PROGRAM.out; LIB
# (libpw85, libpw85_legacy) must resolve into the staging directory; LIB
# "none": libpw85.so must not be needed.
run() {
  exe=$tmp/build/$1
  if [ "$2" != none ]; then
    resolved=$(ldd "$exe" | grep "$2\\.so" || true)
    case $resolved in
      *"$stage"*) echo "ok - $1 loads the staged $2" ;;
      *) echo "FAIL: $1 does not load the staged $2: $resolved"; status=1 ;;
    esac
  elif readelf -d "$exe" | grep -q 'NEEDED.*libpw85\.so'; then
    echo "FAIL: $1 needs libpw85.so"
    status=1
  else
    echo "ok - $1 does not need libpw85.so"
  fi
  if "$exe" >"$tmp/$1.out"; then
    echo "ok - $1 exits with status 0"
  else
    echo "FAIL: $1 exits with status $?"
    status=1
  fi
}

run tutorial libpw85
expect "$tmp/tutorial.out" "mu^2 = 3.36271"
expect "$tmp/tutorial.out" "lambda = 0.166859"
if [ -x "$tmp/build/tutorial_static" ]; then
  run tutorial_static none
  expect "$tmp/tutorial_static.out" "mu^2 = 3.36271"
  expect "$tmp/tutorial_static.out" "lambda = 0.166859"
fi
run legacy libpw85_legacy
if [ -n "$fc" ]; then
  run example_f libpw85
  expect "$tmp/example_f.out" "mu^2 = 3.36271"
  expect "$tmp/example_f.out" "lambda = 0.166859"
fi
exit $status
