#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The racer example's contest over the maze collection beside the project (../shared/mazes): a
# seeded sample of SAMPLE solvable classic mazes with the bundled robot, and every solvable
# half-size maze with the half-size robot, graded by `unimouse batch run -j 2` with the firmware
# in-process. Prints a line per maze (status, best run, contest time, wall contacts in the best
# run and in all, whether the mouse lost its position) and, per class, the share of contests
# passed and the mean best run (docs/mazes.md).
#
#   bench/racer_sweep.sh [UNIMOUSE] [SAMPLE] [SEED]     (default build/bin/unimouse 50 1)
set -euo pipefail
cd "$(dirname "$0")/.."
unimouse=$(realpath "${1:-build/bin/unimouse}")
sample=${2:-50}
seed=${3:-1}
collection=$(realpath ../shared/mazes)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

solvable() {
  for f in "$@"; do
    "$unimouse" maze solve "$f" | grep -q "no path from the start" || echo "$f"
  done
}
# shuf draws the same sample for the same seed: its random source is the seed's bytes
solvable "$collection"/classic/*.txt |
  shuf -n "$sample" --random-source=<(openssl enc -aes-256-ctr -pass "pass:$seed" -nosalt \
    < /dev/zero 2> /dev/null) | sort > "$work/classic.txt"
solvable "$collection"/halfsize/*.txt | sort > "$work/half.txt"

manifest() { # CLASS ROBOT LIST
  echo "robot: $2"
  echo "submissions: [{name: racer, link: 'inproc:racer'}]"
  echo "scenarios: [{scenario: micromouse, set: {end_on_log: done, maze_class: $1}}]"
  echo "mazes:"
  sed 's/^/  - /' "$3"
  echo "seeds: [1]"
}
manifest classic unimouse "$work/classic.txt" > "$work/classic.yaml"
manifest half unimouse-half "$work/half.txt" > "$work/half.yaml"

echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)," \
  "load average $(cut -d' ' -f1 /proc/loadavg); $(wc -l < "$work/classic.txt") classic mazes" \
  "(seed $seed), $(wc -l < "$work/half.txt") half-size"
for class in classic half; do
  "$unimouse" batch run "$work/$class.yaml" -j 2 --out "$work/$class" \
    > "$work/$class.log" 2>&1 || true # a contest that does not pass is still a result
done

python3 - "$work" << 'EOF'
import json, pathlib, statistics, sys

work = pathlib.Path(sys.argv[1])
for cls in ("classic", "half"):
    rows = json.loads((work / cls / "results.json").read_text())["jobs"]
    passed, best = 0, []
    print(f"{cls}: maze, status, best run s, contest s, contacts in the best run / in all, lost")
    for job in sorted(rows, key=lambda j: j["maze"]):
        result = json.loads((work / cls / job["dir"] / "result.json").read_text())
        scenario = result.get("scenario", {})
        scores = scenario.get("scores", {})
        runs = scenario.get("records", {}).get("runs", [])
        best_s = scores.get("best_run_s")
        best_run = [r for r in runs if r.get("time_s") == best_s]
        in_best = best_run[0]["wall_contacts"] if best_run else "-"
        lost = any("lost its position" in w for w in result.get("warnings", []))
        name = pathlib.Path(job["maze"]).stem
        print(f"  {name:36} {job['status']:8} {best_s if best_s is None else round(best_s, 3)!s:>8}"
              f" {round(scores.get('time_used_s', 0), 1):>6} {in_best!s:>3} /"
              f" {scores.get('wall_contacts', '-')!s:<3} {'lost' if lost else ''}")
        if job["status"] == "passed":
            passed += 1
            best.append(best_s)
    mean = f"{statistics.mean(best):.3f} s" if best else "-"
    print(f"{cls}: {passed} of {len(rows)} contests passed ({100 * passed / len(rows):.0f} %),"
          f" mean best run {mean}")
EOF
