#!/bin/sh
# Install test: stage `meson install` into a temporary directory, then build
# the documented examples against the staged files only, the way a user
# would (pkg-config for C and Fortran (pw85.pc, pw85-fortran.pc), the installed
# Python packages with no environment variable), run them and check what
# they print. Leaves nothing behind.
#
# usage: check_install.sh BUILDDIR SRCDIR PREFIX LIBDIR INCLUDEDIR SANITIZE CC PYTHON PURELIB [FC]
#   LIBDIR, INCLUDEDIR: as get_option() gives them (relative to PREFIX or
#   absolute); SANITIZE: get_option('b_sanitize') (the staged library of a
#   sanitizer build needs the examples linked with the same runtime);
#   PYTHON: the `python` option's interpreter; PURELIB: the absolute directory
#   the Python packages are installed into; FC: Fortran compiler, empty or
#   absent to skip the Fortran example.
set -eu

builddir=$1 srcdir=$2 prefix=$3 libdir=$4 includedir=$5 sanitize=$6 cc=$7
python=$8 purelib=$9
fc=${10:-}

case $libdir in /*) ;; *) libdir=$prefix/$libdir ;; esac
case $includedir in /*) ;; *) includedir=$prefix/$includedir ;; esac

tmp=$(mktemp -d "${TMPDIR:-/tmp}/pw85-install-test.XXXXXX")
trap 'rm -rf "$tmp"' EXIT INT TERM
stage=$tmp/stage

"${MESON:-meson}" install -C "$builddir" --destdir "$stage" --no-rebuild --quiet >"$tmp/install.log" 2>&1 || {
  cat "$tmp/install.log"
  echo "FAIL: meson install --destdir failed"
  exit 1
}

san_flags=
if [ "$sanitize" != none ]; then
  san_flags="-fsanitize=$sanitize"
fi

status=0
expect() {  # expect FILE LINE: FILE must hold LINE as a whole line.
  if grep -qxF -- "$2" "$1"; then
    echo "ok - $(basename "$1"): '$2'"
  else
    echo "FAIL: $(basename "$1") lacks the line '$2'"
    status=1
  fi
}

for f in "$stage$includedir/pw85.h" "$stage$libdir/pkgconfig/pw85.pc"; do
  [ -f "$f" ] || { echo "FAIL: $f was not installed"; exit 1; }
done

# C: the tutorial, compiled with the flags of the staged pw85.pc, its prefix
# redirected to the staging directory.
flags=$(PKG_CONFIG_PATH="$stage$libdir/pkgconfig" \
  pkg-config --define-variable=prefix="$stage$prefix" --cflags --libs pw85)
echo "pkg-config --cflags --libs pw85: $flags"
case $flags in
  *"$stage"*) ;;
  *) echo "FAIL: the pkg-config flags do not point into the staging directory"
     exit 1 ;;
esac
# shellcheck disable=SC2086
"$cc" $san_flags "$srcdir/docs/examples/tutorial.c" $flags -o "$tmp/tutorial"
if command -v ldd >/dev/null 2>&1; then
  resolved=$(LD_LIBRARY_PATH="$stage$libdir" ldd "$tmp/tutorial" | grep 'libpw85\.so' || true)
  echo "resolved: $resolved"
  case $resolved in
    *"$stage"*) ;;
    *) echo "FAIL: the tutorial does not load the staged libpw85"; exit 1 ;;
  esac
fi
LD_LIBRARY_PATH="$stage$libdir" "$tmp/tutorial" >"$tmp/tutorial.out"
cat "$tmp/tutorial.out"
expect "$tmp/tutorial.out" "mu^2 = 3.36271"
expect "$tmp/tutorial.out" "lambda = 0.166859"

# The same program linked with the rpath of docs/usage.md ("A prefix
# outside the loader's search path"): it runs without LD_LIBRARY_PATH and
# loads the staged library.
rpath=$(PKG_CONFIG_PATH="$stage$libdir/pkgconfig" \
  pkg-config --define-variable=prefix="$stage$prefix" --variable=libdir pw85)
# shellcheck disable=SC2086
"$cc" $san_flags "$srcdir/docs/examples/tutorial.c" $flags -Wl,-rpath,"$rpath" \
  -o "$tmp/tutorial_rpath"
if command -v ldd >/dev/null 2>&1; then
  resolved=$(env -u LD_LIBRARY_PATH ldd "$tmp/tutorial_rpath" | grep 'libpw85\.so' || true)
  echo "resolved with -Wl,-rpath,$rpath: $resolved"
  case $resolved in
    *"$stage"*) ;;
    *) echo "FAIL: the tutorial linked with the rpath does not load the staged libpw85"; status=1 ;;
  esac
fi
env -u LD_LIBRARY_PATH "$tmp/tutorial_rpath" >"$tmp/tutorial_rpath.out"
expect "$tmp/tutorial_rpath.out" "mu^2 = 3.36271"

# Fortran: the example against the installed pw85.mod and libpw85_fortran.a,
# with the flags of the staged pw85-fortran.pc.
if [ -n "$fc" ]; then
  for f in "$stage$includedir/pw85.mod" "$stage$libdir/libpw85_fortran.a"; do
    [ -f "$f" ] || { echo "FAIL: $f was not installed"; exit 1; }
  done
  fflags=$(PKG_CONFIG_PATH="$stage$libdir/pkgconfig" \
    pkg-config --define-variable=prefix="$stage$prefix" --cflags --libs pw85-fortran)
  echo "pkg-config --cflags --libs pw85-fortran: $fflags"
  # shellcheck disable=SC2086
  (cd "$tmp" && "$fc" $san_flags "$srcdir/docs/examples/example.f90" $fflags \
     -o "$tmp/example_f")
  LD_LIBRARY_PATH="$stage$libdir" "$tmp/example_f" >"$tmp/example_f.out"
  cat "$tmp/example_f.out"
  expect "$tmp/example_f.out" "mu^2 = 3.36271"
  expect "$tmp/example_f.out" "lambda = 0.166859"
else
  echo "# no Fortran compiler: Fortran example skipped"
fi

# Python: the tutorial of pypw85 and a call of pw85 from the staged
# site-packages, the libraries found through the installed pw85/_config.py
# (which records $libdir) without PW85_LIBRARY or PW85_LEGACY_LIBRARY.
pydir=$stage$purelib
for f in pw85/__init__.py pw85/_config.py pypw85/__init__.py pypw85/legacy.py; do
  [ -f "$pydir/$f" ] || { echo "FAIL: $pydir/$f was not installed"; exit 1; }
done
grep -F "LIBPW85 = \"$libdir/libpw85." "$pydir/pw85/_config.py" \
  || { echo "FAIL: pw85/_config.py does not record $libdir"; exit 1; }
preload=
case $sanitize in *address*) preload=$("$cc" -print-file-name=libasan.so) ;; esac
env -u PW85_LIBRARY -u PW85_LEGACY_LIBRARY PYTHONPATH="$pydir" \
  ${preload:+LD_PRELOAD="$preload" ASAN_OPTIONS=detect_leaks=0} \
  "$python" -c '
import numpy as np, pypw85, pypw85.legacy, pw85
from pw85 import _lib
q1 = pypw85.spheroid(10, 0.1, np.array([0., 0., 1.]))
q2 = pypw85.spheroid(0.5, 5., np.array([1., 0., 0.]))
mu2, lambda_ = pypw85.contact_function(np.array([0.7, -0.7, 1.1]), q1, q2)
print("mu^2 = %.6g" % mu2)
print("lambda = %.6g" % lambda_)
print("legacy mu^2 = %.6g" % pypw85.legacy.contact_function1(np.array([0.7, -0.7, 1.1]), q1, q2)[0])
print("pw85 overlap = %s" % pw85.overlap([0.7, -0.7, 1.1], q1, q2))
_lib.legacy()
print("libpw85:", _lib.library_path)
print("libpw85_legacy:", _lib.legacy_library_path)
' >"$tmp/python.out"
cat "$tmp/python.out"
expect "$tmp/python.out" "mu^2 = 3.36271"
expect "$tmp/python.out" "lambda = 0.166859"
expect "$tmp/python.out" "legacy mu^2 = 3.36271"
expect "$tmp/python.out" "pw85 overlap = False"
if [ "$(grep -c "^libpw85.*: $stage" "$tmp/python.out")" != 2 ]; then
  echo "FAIL: the Python packages do not load the staged libraries"
  status=1
fi

exit $status
