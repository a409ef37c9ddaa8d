#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Checks the Debian packages on a brand-new Debian 12, as a lab PC would get them.
#
#   packaging/deb-install-check.sh [WORK_DIR [PACKAGE.deb...]]
#
# Without .debs it builds them (dpkg-buildpackage -us -uc -b, from a clean clone of this
# repository's HEAD: commit first) and runs lintian on them, failing on any error or warning.
# Then it bootstraps a minimal root with mmdebstrap, installs the packages there with apt (their
# dependencies come from the mirror) and, with no source tree and from an empty directory, runs
# the main job, solves a maze, runs firmware on the emulated board, reads the man pages, builds
# the Arduino library's micromouse example for the Mega 2560 with the installed library through
# arduino-mk and through arduino-builder (what the IDE runs), and builds the example out-of-tree
# plugin against unimouse-dev and loads it. Last it purges them, reinstalls and purges again, and
# fails if any file is left behind.
#
# Needs root, mmdebstrap, a Debian mirror (DEBIAN_MIRROR) and, to build, the build dependencies
# of debian/control. The log is printed and kept as WORK_DIR/deb-install-check.log.
set -euo pipefail
repo=$(git -C "$(dirname "$0")" rev-parse --show-toplevel)
work=$(realpath -m "${1:-/tmp/unimouse-deb-check}")
shift || true
mirror=${DEBIAN_MIRROR:-http://deb.debian.org/debian}
debs=("$@")

if [ ${#debs[@]} -eq 0 ]; then
  rm -rf "$work"
  mkdir -p "$work"
else
  mkdir -p "$work"
fi
exec > >(tee "$work/deb-install-check.log") 2>&1
start_s=$SECONDS

if [ ${#debs[@]} -eq 0 ]; then
  echo "== building the packages from a clean clone of $(git -C "$repo" rev-parse --short HEAD)"
  git clone -q "$repo" "$work/unimouse"
  # a package build runs with a HOME of its own: keep the compiler cache where it is
  export CCACHE_DIR=${CCACHE_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/ccache}
  (cd "$work/unimouse" && dpkg-buildpackage -us -uc -b)
  echo "== lintian (no error or warning allowed)"
  lintian --fail-on error,warning --info --display-info "$work"/unimouse_*.changes
  debs=()
  for deb in "$work"/*.deb; do
    [[ $deb == *-dbgsym_* ]] || debs+=("$deb")
  done
  echo "== built in $((SECONDS - start_s)) s: ${debs[*]##*/}"
fi

# what runs inside the fresh root
cat > "$work/inside.sh" <<'INSIDE'
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive LC_ALL=C.UTF-8 MANWIDTH=100
packages=(unimouse unimouse-dev arduino-unimousesim)
step() { echo "== $*"; }
# every file of the root but the package managers' own records, caches and logs
snapshot() {
  find / -xdev \( -path /proc -o -path /sys -o -path /dev -o -path /run -o -path /tmp \
    -o -path /root -o -path /var/cache -o -path /var/log -o -path /var/lib/apt \
    -o -path /var/lib/dpkg \) -prune -o -print | sort > "$1"
}
install_packages() { apt-get install -y -q --no-install-recommends /root/debs/*.deb; }
purge_and_compare() {
  apt-get purge -y -q "${packages[@]}"
  apt-get autoremove --purge -y -q
  snapshot /root/after.txt
  if ! diff /root/before.txt /root/after.txt; then
    echo "FAIL: purging left the files above behind (> left, < removed)"
    exit 1
  fi
  echo "purged: no file left behind"
}

snapshot /root/before.txt
step "apt install ${packages[*]} (dependencies from the mirror)"
install_packages
dpkg -s "${packages[@]}" | grep -E '^(Package|Version|Depends):'
mkdir /root/job && cd /root/job

step "unimouse run (the main job, from an empty directory)"
unimouse run
test -s out/result.json && test -s out/final.png && test -s out/maze.png

step "unimouse maze solve japan2018"
unimouse maze solve japan2018

step "the emulated board: the wall_distance example's AVR image"
firmware=$(dirname "$(dpkg -L unimouse | grep '/firmware/wall_distance.elf$')")
unimouse run --link "avr:$firmware/wall_distance.elf" --duration 1 --out avr-out

step "man unimouse, man unimouse-run"
man -P cat unimouse | head -n 20
man -P cat unimouse-run | grep -e '--robot'

step "the library's micromouse example for the Mega 2560, arduino-mk and the installed library"
cp -r /usr/share/arduino/libraries/UnimouseSim/examples/micromouse sketch
cat > sketch/Makefile <<'MAKEFILE'
BOARD_TAG = mega
BOARD_SUB = atmega2560
# gcc-avr 5.4 defines DECIMAL_DIG for C only, which the Arduino core's WString.cpp needs in C++;
# the larger receive buffer is the one the bundled AVR images use (arduino-lib/avr)
CXXFLAGS_STD = -std=gnu++11 -DDECIMAL_DIG=__DECIMAL_DIG__
CPPFLAGS += -DSERIAL_RX_BUFFER_SIZE=256
include /usr/share/arduino/Arduino.mk
MAKEFILE
make -C sketch > sketch.log 2>&1 || { cat sketch.log; exit 1; }
grep -E '^(Program|Data):' sketch.log
ls -l sketch/build-mega-atmega2560/*.hex

step "the same with arduino-builder, as Debian's Arduino IDE builds it"
mkdir ide && cp -r /usr/share/arduino/libraries/UnimouseSim/examples/micromouse ide/
mkdir ide/build
arduino-builder -verbose -hardware /usr/share/arduino/hardware \
  -tools /usr/share/arduino/hardware/tools -built-in-libraries /usr/share/arduino/libraries \
  -fqbn arduino:avr:mega:cpu=atmega2560 -build-path "$PWD/ide/build" \
  -prefs=compiler.cpp.extra_flags=-DDECIMAL_DIG=__DECIMAL_DIG__ ide/micromouse/micromouse.ino \
  > ide.log 2>&1 || { cat ide.log; exit 1; }
grep -E '^(Using library|Sketch uses)' ide.log

step "unimouse firmware build: a sketch outside the tree, for the PC and for the emulated board"
mkdir mine && cp /usr/share/arduino/libraries/UnimouseSim/examples/wall_distance/wall_distance.ino \
  mine/mine.ino
unimouse firmware build mine --out mine-bin
unimouse run --scenario wall_distance --link native:mine-bin/mine --no-pictures --out mine-run
unimouse firmware build mine --board mega2560 --out mine-bin > mine-avr.log
unimouse run --link avr:mine-bin/mine.elf --duration 1 --no-pictures --out mine-avr
unimouse run --scenario wall_distance --link native:wall_distance --no-pictures --out bundled

step "the example out-of-tree plugin, built against unimouse-dev"
cp -r /usr/share/doc/unimouse-dev/examples/out-of-tree-plugin plugin
cmake -S plugin -B plugin/build > /dev/null
cmake --build plugin/build
unimouse --plugin-path plugin/build plugins | grep -A3 'lab.voltage_divider'

step "purge, then reinstall and purge again"
cd /
purge_and_compare
install_packages > /dev/null
unimouse --version
purge_and_compare
INSIDE

echo "== a fresh Debian 12 root, the packages installed there with apt"
mmdebstrap --variant=apt --include=ca-certificates,man-db,cmake,g++,make,arduino-mk \
  --customize-hook='mkdir -p "$1/root/debs"' \
  --customize-hook="copy-in ${debs[*]} /root/debs" \
  --customize-hook="copy-in $work/inside.sh /root" \
  --customize-hook='chroot "$1" bash /root/inside.sh' \
  bookworm /dev/null "$mirror"
echo "deb-install-check passed in $((SECONDS - start_s)) s"
