#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The live viewer's frame rate: the main job in its 1200x900 window under a virtual X server
# (Xvfb, drawn by Mesa's software renderer as on a lab PC without a GPU), FRAMES frames, REPEAT
# times. Prints each run's frames a second (result.json's view.frames_per_second) and their
# median (docs/performance.md).
#
#   bench/viewer_frame_rate.sh [UNIMOUSE] [FRAMES] [REPEAT]   (default build/bin/unimouse 300 3)
set -euo pipefail
cd "$(dirname "$0")/.."
unimouse=$(realpath "${1:-build/bin/unimouse}")
frames=${2:-300}
repeat=${3:-3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)," \
  "load average $(cut -d' ' -f1 /proc/loadavg)"
rates=()
for i in $(seq "$repeat"); do
  # the run ends when the window has drawn its frames: exit status 1, the contest undecided
  xvfb-run -a -s "-screen 0 1280x1024x24" "$unimouse" run --view --view-frames "$frames" \
    --no-pictures --out "$work/run$i" > "$work/run$i.txt" 2>&1 || true
  rate=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['view']['frames_per_second'])" \
    "$work/run$i/result.json")
  echo "run $i: $frames frames, $rate a second"
  rates+=("$rate")
done
printf '%s\n' "${rates[@]}" | sort -g | awk '{a[NR]=$1} END {printf "median: %.1f frames a second\n", a[int((NR+1)/2)]}'
