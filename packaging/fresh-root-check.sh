#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Checks the README's promise on a brand-new Debian 12: bootstraps a minimal root, clones this
# repository into it and runs the two quick-start commands exactly as written, timing each
# (issue 32's promise: at most 6 and 10 minutes on a 2-core machine). Needs root, mmdebstrap and
# access to a Debian mirror; takes some 40 minutes. Not part of the test suite.
set -euo pipefail
repo=$(git -C "$(dirname "$0")" rev-parse --show-toplevel)
root=${1:-/tmp/unimouse-fresh-root}

# a run that was killed may have left its mounts: never remove through them
awk -v r="$root" '$2 == r || index($2, r "/") == 1 { print $2 }' /proc/mounts | sort -r |
  while read -r mounted; do umount -l "$mounted"; done
rm -rf "$root"
mmdebstrap --variant=minbase --include=git,ca-certificates bookworm "$root"
git clone -q "$repo" "$root/root/unimouse"
if [ -d "$repo/../shared/mazes" ]; then
  mkdir -p "$root/root/shared" && cp -r "$repo/../shared/mazes" "$root/root/shared/"
fi
cp /etc/resolv.conf "$root/etc/resolv.conf"
# the certificate authorities this machine adds to Debian's (a proxy's on some networks): without
# them npm cannot reach its registry from the root, and the tests that need its packages skip
if compgen -G "/usr/local/share/ca-certificates/*.crt" > /dev/null; then
  cp /usr/local/share/ca-certificates/*.crt "$root/usr/local/share/ca-certificates/"
  chroot "$root" update-ca-certificates > /dev/null
fi
# the root a mount point of its own, as / is on a booted machine (bubblewrap needs that)
mount --bind "$root" "$root"
mount --bind /proc "$root/proc"
mount --bind /dev "$root/dev"
# a booted machine has its pseudo-terminals mounted under /dev (the link's tests open them) and
# its cgroups under /sys (the one-node Slurm test's slurmd needs them)
mount --bind /dev/pts "$root/dev/pts"
mount --rbind /sys "$root/sys"
mount --make-rslave "$root/sys"
trap 'umount -R "$root"' EXIT

# the two commands are the quick start's two shell blocks
quick_start=$(sed -n '/^## Quick start/,/^## /p' "$repo/README.md" |
  awk '/^```sh/ { inside = 1; next } /^```/ { inside = 0 } inside')
[ "$(wc -l <<< "$quick_start")" -eq 2 ] || { echo "expected two quick-start commands" >&2; exit 1; }
echo "on $(nproc) cores, $(git -C "$repo" rev-parse --short HEAD)"
number=0
while IFS= read -r command <&3; do
  number=$((number + 1))
  echo "command $number: $command"
  start=$SECONDS
  status=0
  chroot "$root" /bin/bash -c "cd /root/unimouse && $command" < /dev/null || status=$?
  echo "command $number took $((SECONDS - start)) s of wall time, exit code $status"
  [ "$status" -eq 0 ] || exit "$status"
done 3<<< "$quick_start"
echo "fresh-root check passed"
