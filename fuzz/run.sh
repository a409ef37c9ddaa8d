#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Builds the libFuzzer targets with clang in build-fuzz/ and runs each for SECONDS (default 60),
# seeded from the bundled mazes, robots, scenarios, AVR images and a recording and from hand-made hostile
# cases. Exits non-zero at the first finding; the input that caused it is left in
# build-fuzz/findings/.
#
#   fuzz/run.sh [SECONDS]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
build=build-fuzz

cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DUNIMOUSE_FUZZ=ON \
  -DUNIMOUSE_BUILD_TESTS=OFF -DUNIMOUSE_BUILD_BENCH=OFF > /dev/null
targets=(fuzz_maze fuzz_robot fuzz_frames fuzz_scenario fuzz_manifest fuzz_mms fuzz_link_set
  fuzz_recording)
# the AVR image loader where the emulated board is built (simavr, libelf), seeded from the
# bundled examples where the AVR toolchain builds them
known=$(ninja -C "$build" -t targets all)
have() { grep -q "^$1:" <<< "$known"; }
if have fuzz_avr_image; then
  targets+=(fuzz_avr_image)
  if have unimouse_avr_examples; then
    cmake --build "$build" -j2 --target unimouse_avr_examples
  fi
fi
cmake --build "$build" -j2 --target "${targets[@]}"

# seeds: the bundled files, and a few frames of every kind the firmware sends
seeds=$build/seeds
rm -rf "$seeds"
mkdir -p "$seeds"/{maze,robot,scenario,frames,manifest,mms,link_set,avr_image,recording} \
  "$build/findings"
cp mazes/*.txt tests/data/broken_mazes/*.{txt,num,maz} "$seeds/maze/"
cp robots/*.yaml "$seeds/robot/"
# a list that holds an alias of itself, and values nested deeper than the bound
printf 'a: &b [*b]\n' > "$seeds/robot/cycle.yaml"
printf 'a: %s7%s\n' "$(printf '[%.0s' {1..70})" "$(printf ']%.0s' {1..70})" > "$seeds/robot/deep.yaml"
cp scenarios/*.lua "$seeds/scenario/"
printf '\x01\x05\x10\x00\x06\xf0\xff' > "$seeds/frames/motors"
printf '\x08\x07\x01hello\x00\x07\x02' > "$seeds/frames/log_and_manager"
printf '\x02\x0a\x01\x02\x03\x0f\x0b\x01\x02\x0c\x02\x00\x00\x00\x01' > "$seeds/frames/debug"
printf '\x03\x0d\x00\x00\x80\x3fspeed\x00' > "$seeds/frames/value"
# manifests: docs/batch.md's examples, and the cycles that overflowed the stack
awk '/^```yaml/ { n++; keep = 1; next } /^```/ { keep = 0 } keep { print > (dir "/batch_doc" n ".yaml") }' \
  dir="$seeds/manifest" docs/batch.md
head='submissions: [{name: amy, controller: amy.lua}]\nscenarios: [micromouse]\n'
printf "${head}seeds: {a: &b [*b]}\n" > "$seeds/manifest/seeds_cycle.yaml"
printf "${head}jobs: {a: &b [*b]}\n" > "$seeds/manifest/jobs_cycle.yaml"
# mms: a short exploration with every kind of command, and damaged lines
printf 'mazeWidth\nmazeHeight\nwallFront\nwallLeft 2\nmoveForward 3\nturnRight\nturnLeft45\nsetWall 0 0 n\nclearWall 0 0 n\nsetColor 1 1 G\nclearColor 1 1\nclearAllColor\nsetText 0 0 hi\nclearText 0 0\nclearAllText\nwasReset\nackReset\ngetStat total-distance\n' \
  > "$seeds/mms/commands"
printf 'moveForward -1\nmoveForward 99999999999999999999\nsetWall 255 -3 q\nsetText 0 0 \xff\xfe\x00x\nturnRight \r\n\x00\n' \
  > "$seeds/mms/mangled"
# --link-set values (the first byte chooses the transport), good and bad
printf '\x00failsafe_s=0.2\nextensions=false\nprofile=unimousesim-0.1' > "$seeds/link_set/good"
printf '\x03mcu=atmega328p\nf_cpu_hz=1e99\n=x\nnoequals\nsend=[[[' > "$seeds/link_set/bad"
# recordings: a short run's, whole and cut short (tests/data/short_run.mcap)
cp tests/data/short_run.mcap "$seeds/recording/"
head -c 3000 tests/data/short_run.mcap > "$seeds/recording/cut.mcap"
# AVR images: the bundled examples, and the test image whose .mmcu section names its part
cp "$build"/avr/*.elf "$seeds/avr_image/" 2> /dev/null || true
if command -v avr-gcc > /dev/null; then
  avr-gcc -mmcu=atmega328p -Os -I/usr/include/simavr -Wl,--undefined=_mmcu \
    tests/avr/names_its_mcu.c -o "$seeds/avr_image/names_its_mcu.elf"
fi

for target in "${targets[@]}"; do
  corpus=$build/corpus/${target#fuzz_}
  mkdir -p "$corpus"
  echo "== $target: ${seconds} s"
  # -rss_limit_mb: every input's memory is bounded; -timeout: so is its time
  log=$build/findings/$target.log
  # the emulated board runs a fuzzed image's code for 1000 cycles: simavr's own peripheral code
  # (its EEPROM and flash writing) keeps 32 bytes it never frees for some instruction streams.
  # Crashes there are still findings; that leak is simavr's, and is not counted there
  leaks=1
  [ "$target" = fuzz_avr_image ] && leaks=0
  if ! ASAN_OPTIONS=detect_leaks=$leaks "$build/bin/$target" "$corpus" \
    "$seeds/${target#fuzz_}" -max_total_time="$seconds" \
    -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 -detect_leaks=$leaks \
    -artifact_prefix="$build/findings/$target-" > "$log" 2>&1; then
    # the finding with its reason and stack, without the progress lines before it
    grep -v '^#[0-9]' "$log" | tail -n 60
    exit 1
  fi
  tail -n 12 "$log"
done
