#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Builds the libFuzzer targets with clang in build-fuzz/ and runs each for SECONDS (default 60),
# seeded from the bundled mazes, robots and scenarios. Exits non-zero at the first finding; the
# input that caused it is left in build-fuzz/findings/.
#
#   fuzz/run.sh [SECONDS]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
build=build-fuzz

cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DUNIMOUSE_FUZZ=ON \
  -DUNIMOUSE_BUILD_TESTS=OFF -DUNIMOUSE_BUILD_BENCH=OFF > /dev/null
targets=(fuzz_maze fuzz_robot fuzz_frames fuzz_scenario)
cmake --build "$build" -j2 --target "${targets[@]}"

# seeds: the bundled files, and a few frames of every kind the firmware sends
seeds=$build/seeds
rm -rf "$seeds"
mkdir -p "$seeds"/{maze,robot,scenario,frames} "$build/findings"
cp mazes/*.txt tests/data/broken_mazes/*.{txt,num,maz} "$seeds/maze/"
cp robots/*.yaml "$seeds/robot/"
cp scenarios/*.lua "$seeds/scenario/"
printf '\x01\x05\x10\x00\x06\xf0\xff' > "$seeds/frames/motors"
printf '\x08\x07\x01hello\x00\x07\x02' > "$seeds/frames/log_and_manager"
printf '\x02\x0a\x01\x02\x03\x0f\x0b\x01\x02\x0c\x02\x00\x00\x00\x01' > "$seeds/frames/debug"
printf '\x03\x0d\x00\x00\x80\x3fspeed\x00' > "$seeds/frames/value"

for target in "${targets[@]}"; do
  corpus=$build/corpus/${target#fuzz_}
  mkdir -p "$corpus"
  echo "== $target: ${seconds} s"
  # -rss_limit_mb: every input's memory is bounded; -timeout: so is its time
  log=$build/findings/$target.log
  if ! "$build/bin/$target" "$corpus" "$seeds/${target#fuzz_}" -max_total_time="$seconds" \
    -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$build/findings/$target-" > "$log" 2>&1; then
    # the finding with its reason and stack, without the progress lines before it
    grep -v '^#[0-9]' "$log" | tail -n 60
    exit 1
  fi
  tail -n 12 "$log"
done
