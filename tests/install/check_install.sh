#!/usr/bin/env bash
# Installs the built tree into a fresh prefix and uses it from outside the source tree, as a user would
# (ctest -L install; docs/install.md): a downstream CMake project (find_package(tirpol CONFIG)) and the
# same program through pkg-config, the installed CLI finding the installed material library, and the
# installed Python package. Any missing tool or failed step fails the test with a message.
#
# check_install.sh BUILD_DIR SOURCE_DIR GENERATOR CXX_COMPILER CXX_LAUNCHER PYTHON PYTHON_SITE_RELATIVE VERSION LIBDIR DATADIR
# With TIRPOL_CHECK_PREFIX set, the checks run against that already-populated prefix instead of a fresh
# `cmake --install` (check_deb.sh: the Debian package extracted with dpkg-deb -x).
set -euo pipefail
build_dir=$1 source_dir=$2 generator=$3 cxx=$4 launcher=$5 python=$6 python_site=$7 version=$8 libdir=$9 datadir=${10}

fail() { echo "check_install: FAIL: $*" >&2; exit 1; }
step() { echo "== $*"; }
for tool in cmake pkg-config "$cxx"; do command -v "$tool" >/dev/null || fail "'$tool' not found (needed to check the install)"; done

work=$(mktemp -d "${TMPDIR:-/tmp}/tirpol-install-check.XXXXXX")
trap 'rm -rf "$work"' EXIT
if [[ -n ${TIRPOL_CHECK_PREFIX:-} ]]; then
  prefix=$TIRPOL_CHECK_PREFIX
  step "checking the populated prefix $prefix"
else
  prefix=$work/prefix
  step "cmake --install $build_dir --prefix $prefix"
  cmake --install "$build_dir" --prefix "$prefix" >"$work/install.log" || { cat "$work/install.log"; fail "cmake --install"; }
fi

step "installed files: libraries, headers, package files, programs, data; no test fixtures"
for f in $libdir/libtirpol_core.a $libdir/libtirpol_sweep.a include/tirpol/core/radiometry.h include/tirpol/twin \
         $libdir/cmake/tirpol/tirpolConfig.cmake $libdir/cmake/tirpol/tirpolTargets.cmake $libdir/pkgconfig/tirpol.pc \
         bin/tirpol bin/tirpol-stage-sim $datadir/tirpol/config/materials/snow.yaml $datadir/tirpol/config/scenes; do
  [[ -e $prefix/$f ]] || fail "not installed: $prefix/$f"
done
leaked=$(cd "$prefix" && find . \( -name '*testing*' -o -name 'internal' -o -name 'test_support*' -o -name '*_tests' \) -print)
[[ -z $leaked ]] || fail "test-only files installed: $leaked"

cd "$work"  # outside the source tree from here on: nothing may come from it

step "downstream CMake project: find_package(tirpol CONFIG REQUIRED)"
cmake -S "$source_dir/tests/install/downstream" -B "$work/downstream" -G "$generator" -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_CXX_COMPILER="$cxx" ${launcher:+-DCMAKE_CXX_COMPILER_LAUNCHER="$launcher"} \
      -DCMAKE_PREFIX_PATH="$prefix" >"$work/configure.log" 2>&1 || { cat "$work/configure.log"; fail "downstream configure"; }
cmake --build "$work/downstream" >"$work/build.log" 2>&1 || { cat "$work/build.log"; fail "downstream build"; }
"$work/downstream/tirpol_downstream" || fail "downstream program (CMake package)"

step "the same program through pkg-config"
export PKG_CONFIG_PATH=$prefix/$libdir/pkgconfig
pc_config_dir=$(pkg-config --variable=datadir tirpol)/config
# shellcheck disable=SC2046
$launcher "$cxx" -std=c++20 -O1 -o "$work/downstream_pc" "$source_dir/tests/install/downstream/main.cpp" \
  -DTIRPOL_INSTALLED_CONFIG_DIR="\"$pc_config_dir\"" $(pkg-config --cflags tirpol) \
  $(pkg-config --libs tirpol) || fail "downstream build with pkg-config"
"$work/downstream_pc" || fail "downstream program (pkg-config)"

step "installed CLI"
out=$("$prefix/bin/tirpol" --version) || fail "tirpol --version"
echo "$out"
[[ $out == *"$version"* ]] || fail "tirpol --version printed '$out', expected version $version"
# A library material by name: found in <prefix>/$datadir/tirpol/config above the installed program.
"$prefix/bin/tirpol" brdf snow --wavelength-um 10 --incident-deg 30 0 --exitant-deg 30 180 --json >"$work/brdf.json" \
  || fail "installed tirpol brdf snow (material library not found from $prefix/bin?)"
grep -q '"material": "snow"' "$work/brdf.json" || { cat "$work/brdf.json"; fail "tirpol brdf --json printed no material"; }

if [[ -z $python ]]; then
  echo "== Python package not built (TIRPOL_BUILD_PYTHON=OFF): not installed, not checked"
  exit 0
fi
step "installed Python package"
PYTHONPATH=$prefix/$python_site PYTHONDONTWRITEBYTECODE=1 "$python" - "$prefix" "$datadir" <<'PY' || fail "installed Python package"
import math, os, sys
import numpy as np
import tirpol
from tirpol import core, simulation

prefix = os.path.realpath(sys.argv[1])
assert os.path.realpath(tirpol.__file__).startswith(prefix + os.sep), f"tirpol imported from {tirpol.__file__}"
# Planck's law from the exact SI constants (h, c, k; SI 2019): L(10 µm, 300 K) in W/(m² sr µm).
h, c, k = 6.62607015e-34, 299792458.0, 1.380649e-23
lam = 10e-6
expected = 2 * h * c**2 / lam**5 / math.expm1(h * c / (lam * k * 300.0)) * 1e-6
got = core.planck_radiance(10.0, 300.0)
assert abs(got / expected - 1) < 1e-12, (got, expected)
assert abs(float(core.dolp(core.linearly_polarized(1.0, 0.3, 20.0))) - 0.3) < 1e-12
scene = simulation.load_scene(os.path.join(prefix, sys.argv[2], "tirpol/config/scenes/panels_night.yaml"))
print(f"ok   tirpol {tirpol.__file__}: L(10 um, 300 K) = {got:.6f} W/(m2 sr um), scene {scene!r:.60}")
PY
echo "check_install: all checks passed"
