#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# A benchmark cut small, run from the source tree: bench_expect.sh PATTERN... -- COMMAND...
# Passes when COMMAND succeeds and its output holds a line matching each PATTERN (grep's basic
# patterns); skips (77) without the maze collection beside the project (../shared/mazes).
set -uo pipefail
test -d ../shared/mazes || exit 77
patterns=()
while [ "$1" != -- ]; do
  patterns+=("$1")
  shift
done
shift
out=$("$@")
status=$?
echo "$out"
[ "$status" -eq 0 ] || exit "$status"
for pattern in "${patterns[@]}"; do
  grep -q -- "$pattern" <<< "$out" || { echo "no line matches: $pattern"; exit 1; }
done
