#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# What a test file costs to compile, as a fresh build (no compiler cache) pays it: a sample of
# the suite's files, each compiled with the test target's own command three ways: optimised as
# the libraries are (-O2, how the tests were built before), unoptimised (-O0), and unoptimised
# with the target's precompiled header (how they are built now, tests/CMakeLists.txt). Prints
# each file's seconds and the medians (docs/performance.md, "The quick start and the test
# suite"). Needs a configured and built tree (the precompiled header is the build's).
#
#   bench/test_compile_time.sh [BUILD_DIR]   (default build)
set -euo pipefail
cd "$(dirname "$0")/.."
build=$(realpath "${1:-build}")
source=$PWD
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
files="arduino/examples_avr_test.cc app/cli_test.cc mcap/mcap_writer_test.cc core/maze_test.cc
  plugins/link_native_test.cc scenario/scenario_test.cc run/session_test.cc"
for f in $files; do
  # the target's command for the file, without the cache, the dependency file and the output
  command=$(cd "$build" && ninja -t commands tests/unimouse_tests | grep -F -- "-c $source/tests/$f" |
    head -1 | sed 's|^.*ccache ||; s| -MD -MT [^ ]* -MF [^ ]*||; s| -o [^ ]*| -o '"$work"'/x.o|')
  plain=$(echo "$command" | sed 's| -Winvalid-pch -include [^ ]*||; s| -O0||')
  for way in O2 O0 O0+pch; do
    case $way in
      O2) run="$plain" ;;
      O0) run="$plain -O0" ;;
      O0+pch) run="$command" ;;
    esac
    start=$(date +%s.%N)
    (cd "$build" && eval "$run")
    echo "$f $way $(printf %.1f "$(echo "$(date +%s.%N) - $start" | bc)")"
  done
done | tee "$work/times"
for way in O2 O0 O0+pch; do
  echo "median $way: $(awk -v w="$way" '$2 == w {print $3}' "$work/times" | sort -g |
    awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}') s"
done
