#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# The mms physics tier over the contest collection: the flood-fill and the left-wall test clients
# on the robot (`unimouse mms --physical`) in a seeded sample of the solvable classic mazes (a
# maze `unimouse maze solve` finds a path through), or in all of them. Prints, per maze and
# client, the status, the wall contacts, the worst heading error and the worst offset from the
# cell's centre at rest; then the totals and a summary line (docs/performance.md).
#
#   bench/mms_physical_sweep.py [--unimouse BIN] [--floodfill CLIENT] [--sample N] [--seed S]
#                               [--all]
#     (default build/bin/unimouse, build/tests/unimouse_mms_floodfill, 50 mazes drawn with seed 1)
import argparse
import json
import os
import random
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
COLLECTION = os.path.join(os.path.dirname(ROOT), "shared", "mazes", "classic")


def solvable(unimouse, maze):
    out = subprocess.run([unimouse, "maze", "solve", maze], capture_output=True, text=True)
    return out.returncode == 0 and "no path" not in out.stdout


def run(unimouse, maze, client, out):
    # the left-wall follower circles forever in most mazes: a minute of contest time shows how it
    # drives, as the logic tier's test gives it
    limit = ["--time-limit-s", "60"] if client[0] == "python3" else []
    command = [unimouse, "mms", "--physical", "--no-pictures", "--maze", maze, "--out", out]
    subprocess.run(command + limit + ["--"] + client, capture_output=True)
    with open(os.path.join(out, "result.json")) as f:
        result = json.load(f)
    physical = result.get("physical", {})
    return {
        "status": result["status"],
        "contacts": physical.get("wall_contacts", -1),
        "yaw_deg": physical.get("worst_yaw_error_deg", 99),
        "offset_m": physical.get("worst_offset_m", 9),
    }


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--unimouse", default=os.path.join(ROOT, "build", "bin", "unimouse"))
    parser.add_argument(
        "--floodfill", default=os.path.join(ROOT, "build", "tests", "unimouse_mms_floodfill"))
    parser.add_argument("--sample", type=int, default=50)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--all", action="store_true", help="every solvable maze, no sample")
    args = parser.parse_args()
    unimouse = os.path.abspath(args.unimouse)
    clients = {
        "floodfill": [os.path.abspath(args.floodfill)],
        "left_wall": ["python3", os.path.join(ROOT, "tests", "mms", "clients", "left_wall.py")],
    }
    files = sorted(
        os.path.join(COLLECTION, f) for f in os.listdir(COLLECTION) if f.endswith(".txt"))
    mazes = [m for m in files if solvable(unimouse, m)]
    print(f"solvable classic mazes: {len(mazes)} of {len(files)}")
    if not args.all:
        mazes = sorted(random.Random(args.seed).sample(mazes, min(args.sample, len(mazes))))
        print(f"sample: {len(mazes)}, seed {args.seed}")
    start = time.monotonic()
    totals = {name: [] for name in clients}
    with tempfile.TemporaryDirectory() as work:
        print(f"{'maze':32} {'client':10} {'status':14} {'contacts':>8} {'yaw deg':>8} "
              f"{'offset mm':>9}")
        for i, maze in enumerate(mazes):
            for name, client in clients.items():
                r = run(unimouse, maze, client, os.path.join(work, f"{i}-{name}"))
                totals[name].append(r)
                name_of_maze = os.path.basename(maze)[:-4]
                print(f"{name_of_maze:32} {name:10} {r['status']:14} {r['contacts']:8d} "
                      f"{r['yaw_deg']:8.2f} {1000 * r['offset_m']:9.1f}", flush=True)
    took_s = time.monotonic() - start
    clean_all = 0
    for name, rs in totals.items():
        # the flood fill must reach the goal; the left-wall follower drives until its minute is up
        ok_status = {"goal_reached"} if name == "floodfill" else {"goal_reached", "time_out"}
        bad = [r for r in rs if r["status"] not in ok_status]
        touched = [r for r in rs if r["contacts"] != 0]
        over = [r for r in rs if r["yaw_deg"] >= 3]
        clean = sum(1 for r in rs if r["status"] in ok_status and r["contacts"] == 0
                    and r["yaw_deg"] < 3)
        clean_all += clean
        reached = sum(r["status"] == "goal_reached" for r in rs)
        print(f"{name}: {len(rs)} runs, {reached} goal reached, {len(bad)} other ending, "
              f"{sum(r['contacts'] for r in rs)} contacts in {len(touched)} runs, "
              f"{len(over)} runs with a heading error of 3 deg or more; worst yaw "
              f"{max(r['yaw_deg'] for r in rs):.2f} deg, worst offset "
              f"{1000 * max(r['offset_m'] for r in rs):.1f} mm; {clean} clean")
    runs = sum(len(rs) for rs in totals.values())
    print(f"summary: {clean_all} of {runs} runs clean (as expected ending, no contact, heading "
          f"error under 3 deg) over {len(mazes)} mazes, {took_s:.0f} s wall")
    return 0 if clean_all == runs else 1


if __name__ == "__main__":
    sys.exit(main())
