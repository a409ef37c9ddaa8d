#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The mms logic tier end to end: the C++ flood-fill client of the tests (its own process, every
# line through a pipe) over every classic maze of the contest collection, first one `unimouse mms`
# after another, then as one `unimouse batch run` with -j 1 and -j 2 (each job in its sandbox).
# Prints the wall time of each, mazes per second and the statuses (docs/performance.md).
#
#   bench/mms_collection.sh [UNIMOUSE] [CLIENT]
#     (default build/bin/unimouse build/tests/unimouse_mms_floodfill)
set -euo pipefail
cd "$(dirname "$0")/.."
unimouse=$(realpath "${1:-build/bin/unimouse}")
client=$(realpath "${2:-build/tests/unimouse_mms_floodfill}")
collection=$(realpath ../shared/mazes/classic)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mazes=("$collection"/*.txt)
now() { date +%s.%N; }
report() {  # label, start time, statuses
  awk -v label="$1" -v a="$2" -v b="$(now)" -v n="${#mazes[@]}" -v s="$3" \
    'BEGIN { printf "%-22s %6.1f s wall, %5.1f mazes/s (%s)\n", label, b - a, n / (b - a), s }'
}

echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
echo "mazes: ${#mazes[@]} classic"
start=$(now)
for i in "${!mazes[@]}"; do
  "$unimouse" mms --no-pictures --maze "${mazes[$i]}" --out "$work/one/$i" -- "$client" \
    > /dev/null 2>&1 || true # an unsolvable maze is a run too
done
statuses=$(python3 -c 'import json, sys
for f in sys.argv[1:]: print(json.load(open(f))["status"])' "$work"/one/*/result.json)
report "one run at a time:" "$start" "$(sort <<<"$statuses" | uniq -c | xargs)"

echo "submissions: [{name: floodfill, mms: '$client'}]" > "$work/manifest.yaml"
echo "mazes: ['$collection/']" >> "$work/manifest.yaml"
for j in 1 2; do
  start=$(now)
  "$unimouse" batch run "$work/manifest.yaml" -j "$j" --out "$work/j$j" > /dev/null 2>&1 || true
  report "batch run -j $j:" "$start" \
    "$(tail -n +2 "$work/j$j/results.csv" | awk -F, '{print $5}' | sort | uniq -c | xargs)"
done
