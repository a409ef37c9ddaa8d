#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Throughput of `unimouse batch run`: the micromouse contest with the bundled example firmware
# over 20 mazes of the contest collection, one seed, with -j 1 and then -j 2, side by side in
# one run. Prints the wall time, jobs per minute and the scaling from -j 1 (docs/performance.md).
#
#   bench/batch_throughput.sh [UNIMOUSE] [LINK]     (default build/bin/unimouse native:micromouse)
set -euo pipefail
cd "$(dirname "$0")/.."
unimouse=$(realpath "${1:-build/bin/unimouse}")
link=${2:-native:micromouse}
collection=$(realpath ../shared/mazes/classic)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# every 26th maze of the sorted collection, a spread of years and contests
mazes=(alljapan-006-1985-pre alljapan-017-1996-exp-fin alljapan-044-2023-exp-fin boston
  chubu2017 hk91f japan1991q japan2017ef korea94x map-g4 minos03f northeast-010-1996
  portugal-2019-final-expert sg87 supo2 tyubu200906 uk2009q uk2024-megacon-c-14x14 us01 zigzag)
{
  echo "submissions: [{name: example, link: '$link'}]"
  echo "scenarios: [{scenario: micromouse}]"
  echo "mazes:"
  for m in "${mazes[@]}"; do echo "  - $collection/$m.txt"; done
  echo "seeds: [1]"
} > "$work/manifest.yaml"

echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
echo "link: $link, jobs: ${#mazes[@]}"
declare -A seconds
for j in 1 2; do
  start=$(date +%s.%N)
  "$unimouse" batch run "$work/manifest.yaml" -j "$j" --out "$work/j$j" > "$work/j$j.log" 2>&1 ||
    true # a job that does not pass is still a job done
  seconds[$j]=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { print b - a }')
  statuses=$(tail -n +2 "$work/j$j/results.csv" | awk -F, '{print $5}' | sort | uniq -c | xargs)
  printf -- "-j %s: %6.1f s wall, %5.1f jobs/min (%s)\n" "$j" "${seconds[$j]}" \
    "$(awk -v n="${#mazes[@]}" -v s="${seconds[$j]}" 'BEGIN { print n * 60 / s }')" "$statuses"
done
# which jobs did not pass, and why
for j in 1 2; do
  python3 -c 'import csv, sys
for row in csv.DictReader(open(sys.argv[1])):
    if row["status"] != "passed":
        print("  -j", sys.argv[2], "not passed:", row["maze"], row["status"], row["reason"])' \
    "$work/j$j/results.csv" "$j"
done
# the same jobs must give the same results however many run at once
if ! diff <(cut -d, -f1-8 "$work/j1/results.csv") <(cut -d, -f1-8 "$work/j2/results.csv") > /dev/null; then
  kept=$(mktemp -d)
  cp -r "$work"/. "$kept"
  echo "results differ between -j 1 and -j 2 (both batches are in $kept)" >&2
  exit 1
fi
printf "scaling from -j 1 to -j 2: %.2fx\n" "$(awk -v a="${seconds[1]}" -v b="${seconds[2]}" 'BEGIN { print a / b }')"
