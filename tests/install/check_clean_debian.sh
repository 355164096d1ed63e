#!/usr/bin/env bash
# The newcomer's check on a clean machine (docs/install.md, "Checked on a clean Debian 12"): a minimal
# Debian 12 root made by debootstrap (bookworm, --variant=minbase: apt, dpkg and little else; no compiler,
# no Python), the Debian package copied in and installed with `apt-get install ./tirpol_*.deb`, apt
# resolving every dependency from the Debian mirror. Then, in that root (chroot) as an ordinary user:
#   1. the installed CLI (`tirpol --version`, a library material by name);
#   2. `python3` (Debian's, no PYTHONPATH) imports tirpol and reduces a synthetic analyzer frame set
#      (clean_debian_python_check.py), with nothing on stderr (no glog noise);
#   3. `tirpol live` with the simulated rig (the digital twin's scene camera following the in-process
#      simulated stage) on loopback: page, assets, API, and polarization in the Stokes cycle
#      (clean_debian_live_check.py); then the host's headless Chromium loads the page (the root shares
#      the network) and must draw S0 and DoLP, and a screenshot is kept;
#   4. cmake, g++ and make installed as a developer would, then a downstream CMake project with
#      find_package(tirpol CONFIG REQUIRED) and the same program through pkg-config, built and run;
#   5. `apt-get remove --purge tirpol` after root ran `import tirpol` leaves none of its files.
# Everything is undone on exit (processes, mounts, the root). Any failed step fails with a message
# naming it; a missing tool fails too (nothing is skipped).
#
#   sudo tests/install/check_clean_debian.sh build/packages/tirpol_<version>_<arch>.deb
#   ./run check-clean-install        (builds the package, then runs this)
#
# Needs root (debootstrap, chroot, mount), debootstrap, chromium and network access to the mirrors.
# Environment:
#   TIRPOL_DEBIAN_MIRROR           Debian mirror (http://deb.debian.org/debian)
#   TIRPOL_DEBIAN_SECURITY_MIRROR  security mirror (http://deb.debian.org/debian-security)
#   TIRPOL_CLEAN_CACHE             where the debootstrap tarball and apt's downloaded .deb files are kept
#                                  (<source>/.cache/clean-debian, git-ignored): apt still resolves every
#                                  dependency from the mirror's fresh index and checks each cached file's
#                                  hash against it; delete the folder to download everything again
#   TIRPOL_CLEAN_ARTEFACTS         where the logs and the screenshot are kept
#                                  (<source>/build/test-artefacts/clean-debian)
set -euo pipefail

fail() { echo "check_clean_debian: FAIL: $*" >&2; exit 1; }
start_s=$SECONDS
step_s=$SECONDS
step() {
  echo "== [$((SECONDS - start_s)) s] $*"
  step_s=$SECONDS
}

(($# == 1)) || fail "usage: $0 PATH/tirpol_<version>_<arch>.deb"
deb=$(realpath -e "$1" 2>/dev/null) || fail "no such package: $1 (./run package builds it)"
[[ $deb == *.deb ]] || fail "$1 is not a .deb"
source_dir=$(cd "$(dirname "$0")/../.." && pwd)
mirror=${TIRPOL_DEBIAN_MIRROR:-http://deb.debian.org/debian}
security_mirror=${TIRPOL_DEBIAN_SECURITY_MIRROR:-http://deb.debian.org/debian-security}
cache=${TIRPOL_CLEAN_CACHE:-$source_dir/.cache/clean-debian}
artefacts=${TIRPOL_CLEAN_ARTEFACTS:-$source_dir/build/test-artefacts/clean-debian}

((EUID == 0)) || fail "needs root (debootstrap, chroot and mount): sudo $0 $1"
for tool in debootstrap chroot mount umount findmnt mkfs.ext4 dpkg-deb chromium /usr/bin/python3; do
  command -v "$tool" >/dev/null || fail "'$tool' not found (apt-get install debootstrap chromium util-linux python3)"
done
arch=$(dpkg-deb -f "$deb" Architecture) || fail "cannot read the control fields of $deb"
version=$(dpkg-deb -f "$deb" Version)

mkdir -p "$cache" "$artefacts"
rm -f "$artefacts"/*.log "$artefacts"/*.png
work=$(mktemp -d "${TMPDIR:-/var/tmp}/tirpol-clean-debian.XXXXXX")
root=$work/root
pids=()
cleanup() {
  local rc=$?
  set +e
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null && wait "$pid" 2>/dev/null; done
  # Innermost mounts first; the root is removed only when nothing is mounted below it any more, so
  # that rm never reaches the host's /proc, /sys or /dev/pts.
  for m in $(findmnt -rn -o TARGET | grep -E "^$root(/|\$)" | sort -r); do umount "$m" || umount -l "$m"; done
  if findmnt -rn -o TARGET | grep -qE "^$root(/|\$)"; then
    echo "check_clean_debian: mounts remain under $root; left $work in place" >&2
  else
    rm -rf --one-file-system "$work"
  fi
  ((rc == 0)) || echo "check_clean_debian: logs in $artefacts" >&2
  exit "$rc"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# Runs a command in the root: as root by default, as the user `newcomer` after `as_user`.
in_root() {
  chroot "$root" /usr/bin/env -i PATH=/usr/local/bin:/usr/bin:/bin:/usr/sbin:/sbin HOME=/root LANG=C.UTF-8 \
    DEBIAN_FRONTEND=noninteractive "$@"
}
# Each program execs the next, so that a background job's $! is the user's program itself.
user_command=(chroot --userspec=newcomer:newcomer "$root" /usr/bin/env -i PATH=/usr/local/bin:/usr/bin:/bin
              HOME=/home/newcomer USER=newcomer LANG=C.UTF-8 /bin/sh -c 'cd "$HOME" && exec "$@"' sh)
as_user() { "${user_command[@]}" "$@"; }
# Runs "$@" with its output in $artefacts/$1.log; on failure prints the log's end and fails.
logged() {
  local name=$1; shift
  "$@" >"$artefacts/$name.log" 2>&1 || { tail -n 60 "$artefacts/$name.log" >&2; fail "$name (log: $artefacts/$name.log)"; }
}

tarball=$cache/bookworm-minbase-$arch.tgz
if [[ ! -s $tarball ]]; then
  step "debootstrap --make-tarball: a minimal Debian 12 base ($mirror) into $tarball"
  logged debootstrap-download debootstrap --arch="$arch" --variant=minbase --make-tarball="$tarball.part" \
    bookworm "$work/download" "$mirror"
  mv "$tarball.part" "$tarball"
  rm -rf "$work/download"
fi
# The root lives on an ext4 image of its own, loop-mounted: creating and deleting its ~60 000 files on
# the host's file system (mounted with online discard here) took 2.5 minutes of the check; unmounting and
# deleting one image file takes seconds. Where no loop device can be had, a plain folder is used.
mkdir -p "$root"
truncate -s 12G "$work/root.ext4"
if mkfs.ext4 -q -F -E nodiscard "$work/root.ext4" && mount -o loop,noatime "$work/root.ext4" "$root"; then
  echo "the root is on a loop-mounted ext4 image ($work/root.ext4)"
else
  rm -f "$work/root.ext4"
  echo "no loop device: the root is a plain folder (its removal at the end is slower)"
fi
step "debootstrap --variant=minbase bookworm into $root (from $tarball)"
logged debootstrap debootstrap --arch="$arch" --variant=minbase --unpack-tarball="$tarball" bookworm "$root" "$mirror"
[[ -x $root/usr/bin/apt-get && ! -e $root/usr/bin/python3 && ! -e $root/usr/bin/g++ && ! -e $root/usr/bin/cmake ]] \
  || fail "$root is not a minimal base system (python3, g++ or cmake already there)"

mount -t proc proc "$root/proc"
mount -t sysfs sysfs "$root/sys"
mount --bind /dev/pts "$root/dev/pts"
mkdir -p "$cache/apt-archives/partial"
mount --bind "$cache/apt-archives" "$root/var/cache/apt/archives"
cp /etc/resolv.conf "$root/etc/resolv.conf"
# A Debian 12 installation's sources: the release, its updates and security updates.
cat >"$root/etc/apt/sources.list" <<EOF
deb $mirror bookworm main
deb $mirror bookworm-updates main
deb $security_mirror bookworm-security main
EOF
in_root useradd --create-home --shell /bin/sh newcomer
# No fsync per unpacked file: the root is thrown away, and dpkg's syncs dominate the install's time.
echo force-unsafe-io >"$root/etc/dpkg/dpkg.cfg.d/tirpol-check-unsafe-io"

step "apt-get update; apt-get install ./$(basename "$deb") (apt resolves the dependencies from $mirror)"
cp "$deb" "$root/tmp/"
logged apt-update in_root apt-get update
before=$(in_root dpkg-query -W -f='.\n' | wc -l)
logged apt-install in_root apt-get install -y --no-install-recommends "/tmp/$(basename "$deb")"
after=$(in_root dpkg-query -W -f='.\n' | wc -l)
echo "installed tirpol $version and $((after - before - 1)) packages it depends on in $((SECONDS - step_s)) s"
in_root dpkg-query -W -f='${Status}' tirpol | grep -q "install ok installed" || fail "dpkg does not list tirpol as installed"
[[ $(in_root sh -c 'command -v tirpol') == /usr/bin/tirpol ]] || fail "tirpol is not /usr/bin/tirpol on the PATH"
init=$(in_root dpkg -L tirpol | grep -m 1 '/dist-packages/tirpol/__init__.py$') || fail "the package has no Python package"
site=$(dirname "$(dirname "$init")")
compiled=$(find "$root$site/tirpol/__pycache__" -name '*.pyc' 2>/dev/null | wc -l)
((compiled > 0)) || fail "the package's postinst did not byte-compile $site/tirpol (no __pycache__/*.pyc)"

step "as user newcomer: the installed CLI"
out=$(as_user tirpol --version 2>&1) || fail "tirpol --version: $out"
[[ $out == *"$version"* ]] || fail "tirpol --version printed '$out', expected version $version"
echo "$out"
logged cli-brdf as_user tirpol brdf snow --wavelength-um 10 --incident-deg 30 0 --exitant-deg 30 180 --json
grep -q '"material": "snow"' "$artefacts/cli-brdf.log" || fail "tirpol brdf snow --json printed no material (cli-brdf.log)"

step "as user newcomer: python3 -c 'import tirpol' and a Stokes reduction of synthetic frames"
install -m 0644 "$source_dir/tests/install/clean_debian_python_check.py" "$root/home/newcomer/python_check.py"
as_user python3 python_check.py >"$artefacts/python.log" 2>"$artefacts/python-stderr.log" \
  || { cat "$artefacts/python.log" "$artefacts/python-stderr.log" >&2; fail "the installed Python package"; }
cat "$artefacts/python.log"
[[ ! -s $artefacts/python-stderr.log ]] || { cat "$artefacts/python-stderr.log" >&2; fail "import tirpol wrote to stderr (glog or other noise)"; }

step "as user newcomer: tirpol live with the simulated rig (scene camera behind the simulated stage) on loopback"
width=80 height=64
camera="sim://config/scenes/panels_before_trees.yaml?width=$width&height=$height&spp=2&fps=10"
"${user_command[@]}" tirpol live --camera "$camera" --stage sim:// --frames-per-angle 2 --settle-s 0 --port 0 \
  >"$artefacts/live.log" 2>&1 &
live_pid=$!
pids+=("$live_pid")
port=
for _ in $(seq 240); do
  port=$(sed -n 's|.*open http://127\.0\.0\.1:\([0-9]*\)/.*|\1|p' "$artefacts/live.log" | head -n 1)
  [[ -n $port ]] && break
  kill -0 "$live_pid" 2>/dev/null || { cat "$artefacts/live.log" >&2; fail "tirpol live exited before serving"; }
  sleep 0.5
done
[[ -n $port ]] || { cat "$artefacts/live.log" >&2; fail "tirpol live printed no 'open http://127.0.0.1:PORT/' within 120 s"; }
echo "tirpol live serves http://127.0.0.1:$port/ ($(head -n 1 "$artefacts/live.log"))"
install -m 0644 "$source_dir/tests/install/clean_debian_live_check.py" "$root/home/newcomer/live_check.py"
if ! as_user python3 live_check.py "$port" "$width" "$height" 300 2>&1 | tee "$artefacts/live-check.log"; then
  cat "$artefacts/live.log" >&2
  fail "tirpol live with the simulated rig"
fi

step "the host's headless Chromium loads the page served from the root"
observer=clean
chromium --headless --no-sandbox --disable-gpu --no-first-run --user-data-dir="$work/chromium-observe" \
  --window-size=1400,1300 "http://127.0.0.1:$port/?observe=$observer&dolp_min=0" >"$artefacts/chromium.log" 2>&1 &
chromium_pid=$!
pids+=("$chromium_pid")
if ! /usr/bin/python3 - "$port" "$observer" <<'PY' 2>&1 | tee "$artefacts/chromium-check.log"; then
# The page's test mode (?observe=ID, docs/live.md) posts what it drew twice a second.
import json, sys, time, urllib.request
port, name = sys.argv[1], sys.argv[2]
deadline, seen = time.monotonic() + 240, {}
while time.monotonic() < deadline:
    with urllib.request.urlopen(f"http://127.0.0.1:{port}/api/observations", timeout=30) as r:
        seen = json.loads(r.read()).get(name, {})
    if seen.get("frames_shown", 0) >= 3 and seen.get("stokes_shown", 0) >= 2 and seen.get("dolp_painted", 0) > 0.5:
        print(f"ok   the page drew {seen['frames_shown']} frames and {seen['stokes_shown']} Stokes cycles; "
              f"DoLP canvas {100 * seen['dolp_painted']:.0f} % painted, DoLP range {seen.get('dolp_range')}")
        sys.exit(0)
    time.sleep(1)
sys.exit(f"the page did not draw S0 and DoLP within 240 s; last observation: {json.dumps(seen)}")
PY
  tail -n 20 "$artefacts/chromium.log" >&2
  fail "headless Chromium did not show the live page"
fi
kill "$chromium_pid" 2>/dev/null
wait "$chromium_pid" 2>/dev/null || true
shot=$artefacts/live_clean_debian.png
timeout 180 chromium --headless --no-sandbox --disable-gpu --no-first-run --user-data-dir="$work/chromium-shot" \
  --hide-scrollbars --window-size=1100,950 --virtual-time-budget=20000 --screenshot="$shot" \
  "http://127.0.0.1:$port/" >"$artefacts/chromium-shot.log" 2>&1 || true
[[ -s $shot && $(stat -c %s "$shot") -gt 20000 ]] || { tail -n 20 "$artefacts/chromium-shot.log" >&2; fail "no screenshot, or a blank one ($shot)"; }
echo "screenshot $shot ($(stat -c %s "$shot") bytes)"

kill -TERM "$live_pid"
live_rc=0
wait "$live_pid" || live_rc=$?
((live_rc == 0)) || { cat "$artefacts/live.log" >&2; fail "tirpol live exited with $live_rc on SIGTERM"; }
grep -q "Logging before InitGoogleLogging\|^WARNING" "$artefacts/live.log" && { cat "$artefacts/live.log" >&2; fail "tirpol live printed glog noise"; }

step "developer tools as a developer installs them: apt-get install cmake g++ make"
logged apt-install-developer in_root apt-get install -y --no-install-recommends cmake g++ make
echo "installed in $((SECONDS - step_s)) s"

step "as user newcomer: a downstream CMake project with find_package(tirpol CONFIG REQUIRED)"
cp -r "$source_dir/tests/install/downstream" "$root/home/newcomer/downstream"
in_root chown -R newcomer:newcomer /home/newcomer/downstream
logged downstream-configure as_user cmake -S downstream -B downstream-build -DCMAKE_BUILD_TYPE=Release
logged downstream-build as_user cmake --build downstream-build
as_user downstream-build/tirpol_downstream 2>&1 | tee "$artefacts/downstream-run.log" \
  || fail "the downstream program (CMake package)"

step "as user newcomer: the same program through pkg-config"
logged downstream-pkg-config as_user sh -c 'g++ -std=c++20 -O1 -o downstream_pc downstream/main.cpp \
  -DTIRPOL_INSTALLED_CONFIG_DIR="\"$(pkg-config --variable=datadir tirpol)/config\"" \
  $(pkg-config --cflags tirpol) $(pkg-config --libs tirpol)'
as_user ./downstream_pc >/dev/null || fail "the downstream program (pkg-config)"

step "as root: python3 -c 'import tirpol', then apt-get remove --purge tirpol leaves none of its files"
in_root python3 -c 'import tirpol' || fail "import tirpol as root"
logged apt-remove in_root apt-get remove --purge -y tirpol
! grep -q "not empty so not removed" "$artefacts/apt-remove.log" || { cat "$artefacts/apt-remove.log" >&2; fail "apt-get remove left files of tirpol behind"; }
for left in /usr/bin/tirpol /usr/include/tirpol /usr/lib/cmake/tirpol /usr/lib/pkgconfig/tirpol.pc /usr/share/tirpol "$site/tirpol"; do
  [[ ! -e $root$left ]] || fail "after apt-get remove --purge tirpol, $left is still there"
done

echo "check_clean_debian: all checks passed on a clean Debian 12 root ($(basename "$deb"), $((SECONDS - start_s)) s)"
