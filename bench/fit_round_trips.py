#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# `unimouse fit` over many draws, as a lab would try it: for each robot and seed, a copy of the
# robot file with each motor's Kt and Ra drawn within +-30 % and the encoders' jitter on, its
# sysid log from the bundled scenario, and the fit of that log against the unchanged file. Prints
# per draw each fitted constant over the drawn one, whether its 95 % interval holds the drawn
# value, the replays, and the time; then the worst error and how many intervals held
# (docs/calibrate.md, limits).
#
#   bench/fit_round_trips.py [--unimouse BIN] [--robots unimouse unimouse-half] [--seeds 1 2 ...]
#     (default $UNIMOUSE_BINARY, else build/bin/unimouse; both robots; seeds 1 to 5)
import argparse
import os
import random
import re
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
KT, RA = 0.079025, 16.66667  # the pololu_30_1_lp model's, as both robot files take them
ROW = re.compile(r"^(left|right)_motor\.(kt_nm_per_a|resistance_ohm)\s+(\S+)\s+(\S+)\s+"
                 r"\[(\S+), (\S+)\]\s+(yes|no)")


def changed_robot(text, truth):
    for side in ("left", "right"):
        anchor = "params: { actuator: %s_motor, model: pololu_30_1_lp," % side
        kt, ra = truth[side + "_motor.kt_nm_per_a"], truth[side + "_motor.resistance_ohm"]
        assert anchor in text, anchor
        text = text.replace(anchor, anchor + " kt_nm_per_a: %.6f, resistance_ohm: %.6f," % (kt, ra))
        counts = "cpr: 12, counts_out: %s" % side
        assert counts in text, counts
        text = text.replace(counts, "cpr: 12, jitter_counts_sd: 0.1, counts_out: %s" % side)
    return text


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--unimouse", default=os.environ.get(
        "UNIMOUSE_BINARY", os.path.join(ROOT, "build", "bin", "unimouse")))
    parser.add_argument("--robots", nargs="+", default=["unimouse", "unimouse-half"])
    parser.add_argument("--seeds", nargs="+", type=int, default=[1, 2, 3, 4, 5])
    args = parser.parse_args()
    worst, held, intervals = 0.0, 0, 0
    for robot in args.robots:
        with open(os.path.join(ROOT, "robots", robot + ".yaml")) as f:
            original = f.read()
        for seed in args.seeds:
            draw = random.Random(seed)
            truth = {}
            for side in ("left", "right"):
                truth[side + "_motor.kt_nm_per_a"] = KT * (1 + draw.uniform(-0.3, 0.3))
                truth[side + "_motor.resistance_ohm"] = RA * (1 + draw.uniform(-0.3, 0.3))
            with tempfile.TemporaryDirectory() as work:
                changed = os.path.join(work, robot + "-changed.yaml")
                with open(changed, "w") as f:
                    f.write(changed_robot(original, truth))
                run = subprocess.run([args.unimouse, "run", "--robot", changed, "--scenario",
                                      "sysid", "--link", "native:sysid", "--no-pictures",
                                      "--record", "off", "--out", os.path.join(work, "sysid")],
                                     capture_output=True, text=True)
                if run.returncode != 0:
                    sys.exit("%s seed %d: the sysid run failed: %s" % (robot, seed, run.stdout))
                began = time.monotonic()
                fit = subprocess.run([args.unimouse, "fit", robot,
                                      os.path.join(work, "sysid", "sysid.csv"), "--out",
                                      os.path.join(work, "fit")], capture_output=True, text=True)
                seconds = time.monotonic() - began
            if fit.returncode != 0:
                sys.exit("%s seed %d: fit failed: %s" % (robot, seed, fit.stderr))
            replays = re.search(r"(\d+) replays", fit.stdout).group(1)
            cells = []
            for line in fit.stdout.splitlines():
                m = ROW.match(line)
                if not m:
                    continue
                name = m.group(1) + "_motor." + m.group(2)
                fitted, low, high = float(m.group(4)), float(m.group(5)), float(m.group(6))
                ratio = fitted / truth[name]
                holds = low <= truth[name] <= high
                worst = max(worst, abs(ratio - 1))
                held += holds
                intervals += 1
                short = ("Kt" if "kt" in name else "Ra") + " " + m.group(1)
                cells.append("%s %.4f%s%s" % (short, ratio, "" if holds else " (outside)",
                                              "" if m.group(7) == "yes" else " not identified"))
            print("%-14s seed %2d  %s  %s replays  %.1f s" % (robot, seed, "  ".join(cells),
                                                              replays, seconds), flush=True)
    print("worst error %.1f %%; the interval held the drawn value in %d of %d" %
          (100 * worst, held, intervals))


if __name__ == "__main__":
    main()
