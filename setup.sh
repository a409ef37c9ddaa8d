#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Installs every Debian 12 package unimouse needs to build, test and run. Idempotent and
# non-interactive; run as root or through sudo.
set -euo pipefail

packages=(
  # toolchain (help2man: the man pages, written from --help)
  build-essential cmake ninja-build ccache pkg-config clang-format git help2man
  # simulator libraries (libqhull-dev: the MuJoCo CMake config names its include dir)
  libmujoco-dev libqhull-dev libeigen3-dev liblua5.4-dev libyaml-cpp-dev libboost-dev libboost-context-dev libcli11-dev
  nlohmann-json3-dev libpng-dev
  # recordings (run.mcap): their chunks' compressions
  libzstd-dev liblz4-dev zlib1g-dev
  # rendering: offscreen EGL (Mesa) and the live viewer
  libegl-dev libgl-dev libopengl-dev libegl-mesa0 libgl1-mesa-dri libglfw3-dev libx11-dev xvfb xauth
  # video export of a run (optional at run time: without it, --video says so)
  ffmpeg
  # tests and benchmarks; clang and its libFuzzer runtime for fuzz/run.sh; the result.json schema
  # check (docs/result.schema.json); a headless browser for the batch report, and Slurm (the
  # tests start its daemons on one node, from their own config)
  libgtest-dev libgmock-dev libbenchmark-dev clang libclang-rt-14-dev python3-jsonschema
  # the tests' own MCAP reader (tests/support/mcap_reader.py): the chunks' decompressions and
  # each JSON message's check against its schema
  python3-zstandard python3-lz4 python3-fastjsonschema
  chromium slurmctld slurmd slurm-client
  # counting a run's system calls (tests/run/step_system_calls_test.cc)
  strace
  # batch runs: a submission's sandbox, and GNU parallel for running a batch's plan
  bubblewrap parallel
  # firmware: AVR builds and emulation
  gcc-avr avr-libc binutils-avr arduino-core-avr simavr libsimavr-dev libelf-dev
)

# the official MCAP reader runs in the tests on node, installed from npm into the build tree
# (tests/mcap/package-lock.json): Debian's node and npm, unless the machine has a node with
# its own npm already (whose package conflicts with Debian's npm)
if ! command -v npm >/dev/null 2>&1; then
  packages+=(nodejs npm)
fi

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  sudo_cmd=(sudo)
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages already installed"
  exit 0
fi

echo "setup: installing ${missing[*]}"
"${sudo_cmd[@]}" apt-get update -q
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends \
  "${missing[@]}"
