#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# A one-node Slurm runs a three-task job array: slurm_one_node_test.sh HARNESS
# Each task writes a file named after its index; the harness exits 0 when all pass, prints each
# task as COMPLETED, and leaves no daemon running. Skips (77) where the harness does.
set -euo pipefail
harness=$1
scratch=$(mktemp -d "${TMPDIR:-/tmp}/slurm-one-node-test-XXXXXX")
trap 'rm -rf "$scratch"' EXIT
export TMPDIR=$scratch
mkdir "$scratch/work"
cat >"$scratch/array.sh" <<'SCRIPT'
#!/bin/bash
#SBATCH --array=1-3
#SBATCH --output=slurm-%A_%a.out
echo "task $SLURM_ARRAY_TASK_ID of $SLURM_ARRAY_TASK_COUNT" >"task-$SLURM_ARRAY_TASK_ID.txt"
SCRIPT

status=0
output=$("$harness" "$scratch/array.sh" "$scratch/work" 2>&1) || status=$?
echo "$output"
if [ $status -eq 77 ]; then
  exit 77
fi
fail() {
  echo "FAILED: $*"
  exit 1
}
[ $status -eq 0 ] || fail "the harness exited with $status"
for task in 1 2 3; do
  [ "$(cat "$scratch/work/task-$task.txt" 2>/dev/null)" = "task $task of 3" ] ||
    fail "task $task did not write task-$task.txt"
done
[ "$(grep -c 'JobState=COMPLETED ExitCode=0:0' <<<"$output")" -eq 3 ] ||
  fail "the harness did not report three completed tasks"
# nothing the harness started still runs: no process names a file under this test's directory
for cmdline in /proc/[0-9]*/cmdline; do
  if { tr "\0" " " <"$cmdline"; } 2>/dev/null | grep -q "$scratch/slurm-one-node-"; then
    fail "a daemon is still running: $(tr '\0' ' ' <"$cmdline")"
  fi
done
echo "a one-node Slurm ran the three tasks and stopped"
