#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# A one-node Slurm cluster for tests: slurm_one_node.sh BATCH_SCRIPT WORK_DIR [SBATCH_OPTION...]
#
# Writes a slurm.conf for this host into a temporary directory, starts slurmctld and slurmd from
# Debian's packages under it (auth/none: no munge key, no cgroups, proctrack/linuxproc,
# task/none, every file in the temporary directory), submits BATCH_SCRIPT with `sbatch --wait`
# from WORK_DIR, prints every job's (and array task's) state and exit code, and stops the
# daemons it started, however it ends. Exits with sbatch's status (the highest of the array's
# tasks), 77 when it cannot run here (not root, or the packages are missing), 3 when the cluster
# does not come up, and 124 when the jobs have not ended after SLURM_ONE_NODE_WAIT_S seconds
# (default 600).
set -euo pipefail

if [ $# -lt 2 ]; then
  echo "usage: $0 BATCH_SCRIPT WORK_DIR [SBATCH_OPTION...]" >&2
  exit 2
fi
script=$(realpath "$1")
work_dir=$(realpath "$2")
shift 2

for program in slurmctld slurmd sbatch scontrol sinfo; do
  if ! command -v "$program" >/dev/null; then
    echo "skipped: $program is not installed (Debian: apt-get install slurmctld slurmd slurm-client)"
    exit 77
  fi
done
# the daemons run as the user that starts them, and slurmd must be root to start jobs as the
# submitting user
if [ "$(id -u)" -ne 0 ]; then
  echo "skipped: a one-node Slurm needs root (slurmd starts each job as its submitting user)"
  exit 77
fi

cluster=$(mktemp -d "${TMPDIR:-/tmp}/slurm-one-node-XXXXXX")
daemons=()
stop_daemons() {
  local pid
  # a job still running would outlive slurmd: cancel every job and give them 10 s to end
  if [ ${#daemons[@]} -gt 0 ]; then
    scancel --partition=test 2>/dev/null || true
    for _ in $(seq 50); do
      [ -z "$(squeue -h 2>/dev/null)" ] && break
      sleep 0.2
    done
  fi
  for pid in "${daemons[@]}"; do
    kill "$pid" 2>/dev/null || true
  done
  for pid in "${daemons[@]}"; do
    # a daemon that ignores SIGTERM for 10 s is killed
    for _ in $(seq 100); do
      kill -0 "$pid" 2>/dev/null || break
      sleep 0.1
    done
    kill -KILL "$pid" 2>/dev/null || true
    wait "$pid" 2>/dev/null || true
  done
  rm -rf "$cluster"
}
trap stop_daemons EXIT
trap 'exit 130' INT TERM

# a port nobody listens on, from a range that changes with this process's id, so that two
# clusters started at once do not collide
free_port() {
  local port=$1
  while (exec 3<>"/dev/tcp/127.0.0.1/$port") 2>/dev/null; do
    port=$((port + 1))
  done
  echo "$port"
}
ctld_port=$(free_port $((20000 + ($$ % 20000) * 2)))
slurmd_port=$(free_port $((ctld_port + 1)))

node=$(hostname -s)
cpus=$(nproc)
# the machine's memory, so that a job asking for some (--mem) fits
memory_mb=$(awk '/^MemTotal:/ { print int($2 / 1024) }' /proc/meminfo)
mkdir -p "$cluster/state" "$cluster/spool"
cat >"$cluster/slurm.conf" <<EOF
ClusterName=unimouse-test
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/none
CredType=cred/none
StateSaveLocation=$cluster/state
SlurmdSpoolDir=$cluster/spool
SlurmctldPidFile=$cluster/slurmctld.pid
SlurmdPidFile=$cluster/slurmd.pid
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SlurmdParameters=config_overrides
ReturnToService=2
MinJobAge=600
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$memory_mb State=UNKNOWN
PartitionName=test Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$cluster/slurm.conf

# in the foreground (-D), each logs to its standard error, kept in the temporary directory
slurmctld -D -i -f "$SLURM_CONF" >>"$cluster/slurmctld.log" 2>&1 &
daemons+=($!)
slurmd -D -f "$SLURM_CONF" -N "$node" >>"$cluster/slurmd.log" 2>&1 &
daemons+=($!)

# the node is ready when the controller reports it idle
ready=no
for _ in $(seq 150); do
  if [ "$(sinfo -h -n "$node" -o %t 2>/dev/null)" = idle ]; then
    ready=yes
    break
  fi
  sleep 0.2
done
if [ $ready != yes ]; then
  echo "slurm_one_node: the node did not come up within 30 s; the daemons' logs:" >&2
  tail -n 20 "$cluster/slurmctld.log" "$cluster/slurmd.log" >&2
  exit 3
fi

status=0
job=$(cd "$work_dir" && timeout "${SLURM_ONE_NODE_WAIT_S:-600}" sbatch --parsable --wait "$@" \
  "$script") || status=$?
job=${job%%;*}
if [ -n "$job" ]; then
  # one line per job, or per task of an array: its id, state and exit code
  scontrol -o show job "$job" | awk '{
    line = ""
    for (i = 1; i <= NF; i++) if ($i ~ /^(JobId|ArrayTaskId|JobState|ExitCode)=/) line = line " " $i
    print substr(line, 2)
  }'
fi
if [ $status -eq 124 ]; then
  echo "slurm_one_node: the jobs did not end within ${SLURM_ONE_NODE_WAIT_S:-600} s; the node's log:" >&2
  tail -n 20 "$cluster/slurmd.log" >&2
elif [ $status -ne 0 ]; then
  echo "slurm_one_node: sbatch exited with $status; the node's log:" >&2
  tail -n 20 "$cluster/slurmd.log" >&2
fi
exit $status
