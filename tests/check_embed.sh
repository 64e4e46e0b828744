#!/bin/sh
# Embedding test (docs/usage.md, "Embedding in other builds"): the parent
# project tests/subproject, a debug build with the source tree as its
# subproject subprojects/pw85 (a symlink, and a wrap file whose [provide]
# names the dependencies) and -Dpw85:default_library=both. Checks that
#  - dependency('pw85'), dependency('pw85', static: true),
#    dependency('pw85_legacy'), dependency('pw85-fortran') resolve with no
#    variable name, and the programs built with them print the tutorial's
#    values (the static one without libpw85.so);
#  - the libraries are compiled with -O3 while the parent's code has -O0;
#  - libpw85.so of the both-kinds build exports exactly tests/libpw85.symbols;
#  - `meson install` stages only libraries, headers, modules, pkg-config and
#    CMake files (no program, data or Python package);
#  - a C program links libpw85.a with the C compiler and the flags of
#    `pkg-config --static --libs pw85` alone.
# Then tests/check_cmake.sh over the parent's install (pw85::pw85_static).
# Leaves nothing behind.
#
# usage: check_embed.sh SRCDIR PYTHON NM CC CXX [FC]
#   environment: MESON, CMAKE (default: meson, cmake on PATH)
set -eu

srcdir=$1 python=$2 nm=$3 cc=$4 cxx=$5
fc=${6:-}
meson=${MESON:-meson}

tmp=$(mktemp -d "${TMPDIR:-/tmp}/pw85-embed-test.XXXXXX")
trap 'rm -rf "$tmp"' EXIT INT TERM
parent=$tmp/parent build=$tmp/build stage=$tmp/stage
prefix=/opt/parent

mkdir -p "$parent/subprojects"
cp "$srcdir/tests/subproject/meson.build" "$srcdir/docs/examples/tutorial.c" \
   "$srcdir/tests/header_legacy.c" "$parent/"
[ -n "$fc" ] && cp "$srcdir/docs/examples/example.f90" "$parent/"
ln -s "$srcdir" "$parent/subprojects/pw85"
cat >"$parent/subprojects/pw85.wrap" <<WRAP
[wrap-git]
url = $srcdir
revision = HEAD

[provide]
dependency_names = pw85, pw85_legacy, pw85-fortran
WRAP

fail() { echo "FAIL: $*"; exit 1; }
logged() {  # logged LOG COMMAND...: runs COMMAND, shows LOG if it fails
  log=$1
  shift
  "$@" >"$log" 2>&1 || { cat "$log"; fail "$*"; }
}

# The parent's compilers are the ones of this build. FC unset and no
# Fortran compiler: the parent and the subproject build no Fortran.
logged "$tmp/setup.log" env CC="$cc" CXX="$cxx" ${fc:+FC="$fc"} \
  "$meson" setup "$build" "$parent" --force-fallback-for=pw85 \
  -Dpw85:default_library=both --prefix=$prefix --libdir=lib
grep -E '^Dependency pw85.*found' "$tmp/setup.log"
[ "$(grep -c '^Dependency pw85.* (overridden)$' "$tmp/setup.log")" -ge 3 ] \
  || fail "the dependencies were not found through meson.override_dependency"
logged "$tmp/compile.log" "$meson" compile -C "$build"

status=0
ok() { echo "ok - $*"; }
bad() { echo "FAIL: $*"; status=1; }
expect() {  # expect FILE LINE: FILE must hold LINE as a whole line.
  if grep -qxF -- "$2" "$1"; then ok "$(basename "$1"): '$2'"; else
    bad "$(basename "$1") lacks the line '$2'"; fi
}

# Optimisation levels: every C++ source of the subproject at -O3 (the last
# -O wins), the parent's sources at -O0.
"$python" - "$build/compile_commands.json" <<'PY' || status=1
import json, re, sys
bad = 0
for c in json.load(open(sys.argv[1])):
    src = c["file"]
    level = (re.findall(r"(?:^|\s)(-O\S*)", c["command"]) or ["none"])[-1]
    want = "-O3" if "/subprojects/pw85/src/" in src and src.endswith(".cpp") else None
    if want is None and "/subprojects/" not in src:
        want = "-O0"
    if want is not None and level != want:
        print("FAIL: %s compiled with %s, not %s" % (src, level, want))
        bad = 1
print("ok - libraries at -O3, the parent at -O0" if not bad else "")
sys.exit(bad)
PY

run() {  # run PROGRAM [ARGS...] > PROGRAM.out, exit status 0 required
  p=$1
  shift
  if "$build/$p" "$@" >"$tmp/$p.out"; then ok "$p exits with status 0"; else
    bad "$p exits with status $?"; fi
}
for p in tutorial tutorial-static; do
  run $p
  expect "$tmp/$p.out" "mu^2 = 3.36271"
  expect "$tmp/$p.out" "lambda = 0.166859"
done
if readelf -d "$build/tutorial-static" | grep -q 'NEEDED.*libpw85\.so'; then
  bad "tutorial-static needs libpw85.so"
else
  ok "tutorial-static does not need libpw85.so"
fi
run legacy
if [ -n "$fc" ]; then
  run example-fortran
  expect "$tmp/example-fortran.out" "mu^2 = 3.36271"
fi

"$python" "$srcdir/tests/check_symbols.py" "$nm" \
  "$build/subprojects/pw85/src/libpw85.so" "$srcdir/tests/libpw85.symbols" \
  pw85_ >"$tmp/symbols.log" 2>&1 && ok "libpw85.so exports tests/libpw85.symbols" \
  || { cat "$tmp/symbols.log"; bad "exported symbols of libpw85.so"; }

# What the parent's installation stages.
logged "$tmp/install.log" "$meson" install -C "$build" --destdir "$stage" --no-rebuild
(cd "$stage$prefix" && find . ! -type d | sort) >"$tmp/installed"
while read -r f; do
  case $f in
    ./include/*.h|./include/*.mod|./lib/lib*.a|./lib/lib*.so*) ;;
    ./lib/pkgconfig/*.pc|./lib/cmake/pw85/*.cmake) ;;
    *) bad "installed by the subproject: $f" ;;
  esac
done <"$tmp/installed"
for f in include/pw85.h include/pw85_legacy.h lib/libpw85.a lib/libpw85.so \
         lib/libpw85_legacy.so lib/pkgconfig/pw85.pc lib/cmake/pw85/pw85Config.cmake; do
  if [ -e "$stage$prefix/$f" ]; then ok "installed: $f"; else bad "not installed: $f"; fi
done
[ "$(find "$stage" ! -type d | wc -l)" = "$(wc -l <"$tmp/installed")" ] \
  || bad "files installed outside $prefix"

# libpw85.a with the C compiler and pkg-config --static: every object of the
# archive (--whole-archive, so that the batch calls' OpenMP is needed too),
# taken over libpw85.so (-l:libpw85.a).
flags=$(PKG_CONFIG_PATH="$stage$prefix/lib/pkgconfig" \
  pkg-config --define-variable=prefix="$stage$prefix" --static --cflags --libs pw85)
echo "pkg-config --static --cflags --libs pw85: $flags"
whole='-Wl,--whole-archive -l:libpw85.a -Wl,--no-whole-archive'
# shellcheck disable=SC2086
"$cc" "$parent/tutorial.c" $(echo " $flags " | sed "s/ -lpw85 / $whole /") \
  -o "$build/tutorial-pkg-static" || fail "linking libpw85.a with $cc"
if readelf -d "$build/tutorial-pkg-static" | grep -q 'NEEDED.*libpw85\.so'; then
  bad "tutorial-pkg-static needs libpw85.so"
fi
run tutorial-pkg-static
expect "$tmp/tutorial-pkg-static.out" "mu^2 = 3.36271"

echo "# tests/check_cmake.sh over the parent's installation"
sh "$srcdir/tests/check_cmake.sh" "$build" "$srcdir" "$prefix" "$cc" "$fc" || {
  rc=$?
  [ $rc = 77 ] || status=1
}
exit $status
