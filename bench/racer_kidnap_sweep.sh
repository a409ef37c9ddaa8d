#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The racer kidnapped (tests/scenarios/kidnapped.lua): over classic mazes of the collection beside
# the project (../shared/mazes), at each of six moments of the contest, it is put down one cell
# and two cells from where it was, graded by `unimouse batch run -j 2`. Prints a line per contest
# and a tally: found its place and went on to the goal; found a wrong place; ended saying it was
# lost (and why); or never noticed (the contest ended first). The default six mazes (72 contests)
# take about a minute on two cores (the tests run them); MAZES and MOMENTS name others.
#
#   bench/racer_kidnap_sweep.sh [UNIMOUSE] [MAZES] [MOMENTS]   (default build/bin/unimouse, six
#                                                     mazes, 20 40 60 80 100 120 s)
set -euo pipefail
cd "$(dirname "$0")/.."
unimouse=$(realpath "${1:-build/bin/unimouse}")
mazes=${2:-"japan2018 apec2013 japan2016-ef map-t1 alljapan-016-1995-exp-fin uknov2017"}
moments=${3:-"20 40 60 80 100 120"}
collection=$(realpath ../shared/mazes/classic)
scenario=$(realpath tests/scenarios/kidnapped.lua)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

{
  echo "robot: unimouse"
  echo "submissions: [{name: racer, link: 'inproc:racer'}]"
  echo "scenarios:"
  for at in $moments; do
    for away in 1 2; do
      echo "  - {name: kidnapped-$at-$away, scenario: $scenario, set: {at_s: $at, away: $away}}"
    done
  done
  echo "mazes:"
  for maze in $mazes; do
    echo "  - $collection/$maze.txt"
  done
} > "$work/sweep.yaml"

echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)," \
  "load average $(cut -d' ' -f1 /proc/loadavg); $(date -u +%Y-%m-%dT%H:%MZ)"
"$unimouse" batch run "$work/sweep.yaml" -j 2 --out "$work/out" > "$work/batch.log" 2>&1 ||
  true # a contest that does not pass is still a result

python3 - "$work/out" << 'PY'
import collections, json, pathlib, sys

out = pathlib.Path(sys.argv[1])
jobs = json.loads((out / "results.json").read_text())["jobs"]
tally = collections.Counter()
print("maze, put down at s, cells away, status, reason")
for job in jobs:
    result = json.loads((out / job["dir"] / "result.json").read_text())
    reason = result.get("scenario", {}).get("reason", "")
    params = result.get("scenario", {}).get("params", {})
    if job["status"] == "passed":
        kind = "found its place and reached the goal"
    elif "found itself" in reason:
        kind = "found a wrong place"
    elif "said 'lost:" in reason:
        kind = "said it was lost: " + reason.split("said 'lost: ", 1)[1].rstrip("'")
    else:
        kind = "did not notice"
    tally[kind] += 1
    print(f"  {pathlib.Path(job['maze']).stem:28} {params.get('at_s', '?')!s:>4}"
          f" {params.get('away', '?')!s:>2} {job['status']:7} {reason}")
for kind, n in tally.most_common():
    print(f"{n} of {len(jobs)}: {kind}")
PY
