#!/usr/bin/env bash
# Builds the Debian package (cpack -G DEB, cmake/TirpolPackage.cmake), checks its control fields (every
# declared dependency is in ./run's PACKAGES list or was found by dpkg-shlibdeps, and apt resolves them all
# on this Debian 12), extracts it with dpkg-deb -x into a fresh folder and runs check_install.sh's checks
# against <folder>/usr: the downstream CMake and pkg-config programs, the installed CLI and
# `import tirpol`. Any missing tool or failed step fails the test with a message.
#
# check_deb.sh BUILD_DIR SOURCE_DIR <the rest of check_install.sh's arguments>
set -euo pipefail
build_dir=$1 source_dir=$2 version=$8

fail() { echo "check_deb: FAIL: $*" >&2; exit 1; }
step() { echo "== $*"; }
for tool in cpack dpkg-deb dpkg-shlibdeps apt-get; do
  command -v "$tool" >/dev/null || fail "'$tool' not found (needed to build and check the Debian package)"
done

work=$(mktemp -d "${TMPDIR:-/tmp}/tirpol-deb-check.XXXXXX")
trap 'rm -rf "$work"' EXIT

step "cpack -G DEB (build folder $build_dir)"
(cd "$build_dir" && cpack -G DEB -B "$work/packages") >"$work/cpack.log" 2>&1 || { cat "$work/cpack.log"; fail "cpack -G DEB"; }
shopt -s nullglob
debs=("$work"/packages/tirpol_"$version"_*.deb)
((${#debs[@]} == 1)) || { ls -l "$work/packages"; fail "expected one tirpol_${version}_<arch>.deb, found ${#debs[@]}"; }
deb=${debs[0]}
echo "$(basename "$deb"): $(du -h "$deb" | cut -f1)"

step "control fields"
[[ $(dpkg-deb -f "$deb" Package) == tirpol ]] || fail "Package is '$(dpkg-deb -f "$deb" Package)', expected tirpol"
[[ $(dpkg-deb -f "$deb" Version) == "$version" ]] || fail "Version is '$(dpkg-deb -f "$deb" Version)', expected $version"
depends=$(dpkg-deb -f "$deb" Depends)
echo "Depends: $depends"
# ./run's PACKAGES=( ... ) list: the packages a source build installs.
run_packages=" $(sed -n '/^PACKAGES=(/,/^)/p' "$source_dir/run" | sed 's/^PACKAGES=(//; s/)$//' | tr -s ' \n' ' ') "
[[ $run_packages == *" libopencv-dev "* ]] || fail "could not read the PACKAGES list from $source_dir/run"
# A dependency of the shared libraries the programs load (dpkg-shlibdeps) must be there: opencv's core.
[[ $depends == *libopencv-core* ]] || fail "Depends lacks the shared libraries found by dpkg-shlibdeps (no libopencv-core*)"
for required in libopencv-dev libeigen3-dev python3-numpy; do
  [[ $depends == *"$required"* ]] || fail "Depends lacks $required"
done
# One name per alternative: "a (>= 1) | b, c" gives a, b, c.
for name in $(tr ',|' '\n\n' <<<"$depends" | sed 's/(.*//; s/[[:space:]]//g'); do
  # Shared-library packages (lib..., not -dev) come from dpkg-shlibdeps; every other name must be one
  # that ./run installs, so that the package asks for nothing a source build does not use.
  [[ $run_packages == *" $name "* || $name == python3 ]] && continue
  # zlib1g is Debian's one shared-library package whose name does not start with lib.
  [[ ($name == lib* || $name == zlib1g) && $name != *-dev ]] && continue
  fail "Depends names '$name', which is not in ./run's PACKAGES list"
done

if [[ $depends == *python3-numpy* ]]; then  # the Python package: byte-compiled on install, cleaned on removal
  for script in postinst prerm; do
    dpkg-deb -I "$deb" "$script" | grep -q "py3" || fail "the package's $script does not call py3compile/py3clean"
  done
fi

step "apt resolves the dependencies (apt-get install --simulate ./$(basename "$deb"))"
apt-get install --simulate --no-install-recommends "$deb" >"$work/apt.log" 2>&1 || { cat "$work/apt.log"; fail "apt cannot resolve the package's dependencies"; }
grep -q "^Inst tirpol\|^Conf tirpol\|tirpol is already" "$work/apt.log" || { cat "$work/apt.log"; fail "apt's simulation does not install tirpol"; }

step "dpkg-deb -x into a fresh folder"
root=$work/root
dpkg-deb -x "$deb" "$root"
[[ -x $root/usr/bin/tirpol ]] || fail "the package has no /usr/bin/tirpol"
[[ -f $root/usr/lib/cmake/tirpol/tirpolConfig.cmake ]] || fail "the package has no /usr/lib/cmake/tirpol/tirpolConfig.cmake"

TIRPOL_CHECK_PREFIX=$root/usr "$source_dir/tests/install/check_install.sh" "$@" || fail "the extracted package failed the install checks"
echo "check_deb: all checks passed ($(basename "$deb"))"
