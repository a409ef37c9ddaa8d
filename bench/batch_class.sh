#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# A class graded at once: SUBMISSIONS (30) x 5 mazes = 150 micromouse contests in one
# `unimouse batch run -j 2`, each submission the bundled example or the racer (alternately),
# loaded into the simulator (inproc, the default) or run as a program of its own (native).
# Prints the wall time, the CPU time of all its processes, the cost of a contest and how the
# jobs ended (docs/performance.md). On a shared machine the CPU time is the steady figure.
#
#   bench/batch_class.sh [UNIMOUSE] [inproc|native] [SUBMISSIONS]
#   (default build/bin/unimouse inproc 30)
set -euo pipefail
cd "$(dirname "$0")/.."
unimouse=$(realpath "${1:-build/bin/unimouse}")
kind=${2:-inproc}
submissions=${3:-30}
collection=$(realpath ../shared/mazes/classic)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

mazes=(alljapan-044-2023-exp-fin japan2017ef portugal-2019-final-expert uk2009q us01)
{
  echo "submissions:"
  for i in $(seq -w 1 "$submissions"); do
    if ((10#$i % 2)); then firmware=micromouse; else firmware=racer; fi
    echo "  - {name: s$i, link: '$kind:$firmware'}"
  done
  # as docs/batch.md grades: the contest ends when the firmware says it is done
  echo "scenarios: [{scenario: micromouse, set: {end_on_log: done}}]"
  echo "mazes:"
  for m in "${mazes[@]}"; do echo "  - $collection/$m.txt"; done
  echo "seeds: [1]"
} > "$work/manifest.yaml"

echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)," \
  "load average $(cut -d' ' -f1 /proc/loadavg) before"
# the batch's own rusage counts every process it waited for: the jobs and their firmware
/usr/bin/time -f "%e %U %S" -o "$work/time.txt" \
  "$unimouse" batch run "$work/manifest.yaml" -j 2 --out "$work/out" > "$work/batch.log" 2>&1 ||
  true # a job that does not pass is still a job done
read -r seconds user system < <(tail -1 "$work/time.txt")
jobs=$(($(wc -l < "$work/out/results.csv") - 1))
statuses=$(tail -n +2 "$work/out/results.csv" | awk -F, '{print $5}' | sort | uniq -c | xargs)
cpu=$(awk -v u="$user" -v s="$system" -v n="$jobs" 'BEGIN { print (u + s) / n }')
printf "%d contests (%s), link %s, -j 2: %.1f s wall (%.1f contests a minute)\n" "$jobs" \
  "$statuses" "$kind" "$seconds" "$(awk -v s="$seconds" -v n="$jobs" 'BEGIN { print n * 60 / s }')"
printf "CPU: %.1f s user, %.1f s system: %.2f s a contest, so 150 contests on 2 cores: %.1f min\n" \
  "$user" "$system" "$cpu" "$(awk -v c="$cpu" 'BEGIN { print 150 * c / 2 / 60 }')"
# where a job's time goes: the simulated contest and the rest (start, pictures, replay page)
python3 - "$work/out" <<'EOF'
import glob, json, statistics, sys
sim, wall = [], []
for f in glob.glob(sys.argv[1] + "/**/result.json", recursive=True):
    r = json.load(open(f))
    if "sim_time_s" in r and "wall_time_s" in r:
        sim.append(r["sim_time_s"])
        wall.append(r["wall_time_s"])
if wall:
    print("per contest: median %.1f s simulated in %.2f s of the run's own wall time" %
          (statistics.median(sim), statistics.median(wall)))
EOF
