#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The racer on the emulated board against the racer in-process: the contest over the twenty
# classic mazes of the racer's test (tests/arduino/examples_test.cc, from the collection beside
# the project, ../shared/mazes), once with the board image (build/avr/racer.elf, the loops every
# 3 ms) and once in-process (every millisecond), graded by `unimouse batch run -j 2`. Prints a
# line per maze and submission (status, best run, contest time, wall contacts) and how many
# contests of each touched no wall (docs/firmware.md, "On the emulated board"). The board's
# twenty take about 15 minutes on two cores. MAZES names others of the collection's classic mazes
# (the tests run it on one).
#
#   bench/racer_board_sweep.sh [UNIMOUSE] [IMAGE] [SEED] [MAZES]   (default build/bin/unimouse
#                                                  build/avr/racer.elf 1, the twenty)
set -euo pipefail
cd "$(dirname "$0")/.."
unimouse=$(realpath "${1:-build/bin/unimouse}")
image=$(realpath "${2:-build/avr/racer.elf}")
seed=${3:-1}
mazes=${4:-"minos19 alljapan-008-1987-pre japan9p map-t1 alljapan-016-1995-exp-fin taiwan2023cef
  AAMC22Maze uknov2010f c00d3f taiwan2015p empty alljapan-014-1993-exp-pre ijcp02 kwu1 minos01w
  uknov2017 japan1999p wmmc-y1 other-world85fin-1985 ukoct2019"}
collection=$(realpath ../shared/mazes/classic)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

{
  echo "robot: unimouse"
  echo "submissions: [{name: board, link: 'avr:$image'}, {name: pc, link: 'inproc:racer'}]"
  echo "scenarios: [{scenario: micromouse, set: {end_on_log: done}}]"
  echo "mazes:"
  for maze in $mazes; do
    echo "  - $collection/$maze.txt"
  done
  echo "seeds: [$seed]"
} > "$work/sweep.yaml"

echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)," \
  "load average $(cut -d' ' -f1 /proc/loadavg); seed $seed; $(date -u +%Y-%m-%dT%H:%MZ)"
"$unimouse" batch run "$work/sweep.yaml" -j 2 --out "$work/out" > "$work/batch.log" 2>&1 ||
  true # a contest that does not pass is still a result

python3 - "$work/out" << 'PY'
import json, pathlib, sys

out = pathlib.Path(sys.argv[1])
jobs = json.loads((out / "results.json").read_text())["jobs"]
clean = {}
print("submission, maze, status, best run s, contest s, wall contacts")
for job in sorted(jobs, key=lambda j: (j["submission"], j["maze"])):
    result = json.loads((out / job["dir"] / "result.json").read_text())
    scores = result.get("scenario", {}).get("scores", {})
    contacts = scores.get("wall_contacts")
    best = scores.get("best_run_s")
    ok = job["status"] == "passed" and contacts == 0
    clean[job["submission"]] = clean.get(job["submission"], 0) + ok
    print(f"  {job['submission']:5} {pathlib.Path(job['maze']).stem:28} {job['status']:7}"
          f" {'-' if best is None else round(best, 3)!s:>8}"
          f" {round(scores.get('time_used_s', 0), 1):>6} {contacts!s:>3}")
for name, n in sorted(clean.items()):
    total = sum(1 for j in jobs if j["submission"] == name)
    print(f"{name}: {n} of {total} contests passed without touching a wall")
PY
