#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Soak: a board on a pty at 1 kHz against `unimouse run` in real time, for as long as asked.

The board is written as a lab user would write one (os.read/os.write, struct): every millisecond
it sends both motor commands; now and then it sends a burst (the frames of 20 ms at once), splits
a frame across two writes, and puts garbage bytes on the line (about 1 % of the bytes: ids no
frame has, which the protocol skips one by one); every RESTART_S it closes the pty, opens it
again and starts over with begin()'s start-up frames. At the end it checks:

- no frame lost that the protocol could parse: the link's count of frames equals what was sent;
- restarts in result.json equal the restarts made;
- resident memory of the simulator grew by less than 1 MB after the first WARMUP_S;
- with --latency, the real-time pacer's lateness p99 under 200 us (a quiet host only).

usage: soak_pty.py UNIMOUSE OUT_DIR [--seconds 3600] [--restart-every 600] [--warmup 60]
       [--latency]
Prints one line of figures; exit status 0 when every check holds, 1 otherwise.
"""
import argparse
import json
import os
import random
import re
import struct
import subprocess
import sys
import termios
import time
import tty

parser = argparse.ArgumentParser()
parser.add_argument("unimouse")
parser.add_argument("out_dir")
parser.add_argument("--seconds", type=float, default=3600)
parser.add_argument("--restart-every", type=float, default=600)
parser.add_argument("--warmup", type=float, default=60)
parser.add_argument("--latency", action="store_true")
# a sanitized build keeps freed memory in quarantine: its resident memory says nothing of leaks
parser.add_argument("--no-memory-check", action="store_true")
args = parser.parse_args()

START_UP = bytes([7, 0x14, 7, 0x02, 7, 0x12])  # begin(): three frames
link = args.out_dir + ".pty"
rng = random.Random(33)


def motors(step):
    v = (step % 2047) - 1023
    return struct.pack("<BhBh", 5, v, 6, -v)  # two frames


def rss_kb(pid):
    with open("/proc/%d/status" % pid) as f:
        return int(re.search(r"VmRSS:\s+(\d+)", f.read()).group(1))


def open_board():
    fd = os.open(link, os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)
    tty.setraw(fd)
    return fd


def write_all(fd, data):
    """Writes every byte, waiting while the pty is full (a simulator that stalls for a moment)."""
    while data:
        try:
            data = data[os.write(fd, data):]
        except BlockingIOError:
            drain(fd)
            time.sleep(0.001)


def drain(fd):
    try:
        while os.read(fd, 65536):
            pass
    except BlockingIOError:
        pass


if os.path.lexists(link):
    os.remove(link)
run = subprocess.Popen(
    [args.unimouse, "run", "--maze", "none", "--duration", str(args.seconds + 2),
     "--no-pictures", "--out", args.out_dir, "--link", "pty:" + link],
    stderr=subprocess.DEVNULL)
while not os.path.exists(link):
    time.sleep(0.01)

frames = bytes_sent = garbage = restarts = step = 0
board = open_board()
write_all(board, START_UP)
frames += 3
start = time.monotonic()
next_restart = args.restart_every
rss_after_warmup = rss_max = None
next_rss = 1.0
while True:
    now = time.monotonic() - start
    if now >= args.seconds:
        break
    if now >= next_restart:
        # the board goes away and comes back: quiet first, so the simulator has read it all
        termios.tcdrain(board)
        time.sleep(0.2)
        drain(board)
        os.close(board)
        time.sleep(0.05)
        board = open_board()
        write_all(board, START_UP)
        frames += 3
        restarts += 1
        next_restart += args.restart_every
    due = int(now * 1000)
    out = b""
    burst = rng.random() < 0.002
    if burst:
        time.sleep(0.02)  # twenty steps' frames at once
        due = int((time.monotonic() - start) * 1000)
    while step <= due:
        out += motors(step)
        frames += 2
        step += 1
        if rng.random() < 0.06:  # a garbage byte about every 100 bytes
            out += bytes([rng.randrange(0x80, 0xFF)])
            garbage += 1
    try:
        if rng.random() < 0.01 and len(out) > 3:
            write_all(board, out[:3])  # a frame split across two writes
            time.sleep(0.0002)
            write_all(board, out[3:])
        else:
            write_all(board, out)
        bytes_sent += len(out)
        drain(board)
    except OSError as e:
        sys.exit("the simulator went away: %s" % e)
    if now >= next_rss:
        kb = rss_kb(run.pid)
        if now >= args.warmup:
            if rss_after_warmup is None:
                rss_after_warmup = kb
            rss_max = max(rss_max or kb, kb)
        next_rss += 1.0
    time.sleep(0.0005)
termios.tcdrain(board)
time.sleep(0.2)
drain(board)
os.close(board)
run.wait()

with open(os.path.join(args.out_dir, "result.json")) as f:
    result = json.load(f)
log = open(os.path.join(args.out_dir, "log.txt")).read()
counted = int(re.search(r"(\d+) frames from the firmware", log).group(1))
pacing = result.get("real_time_pacing", {})
growth_kb = (rss_max - rss_after_warmup) if rss_after_warmup else 0
print("soak: %.0f s, %d frames sent, %d counted, %d garbage bytes of %d, %d restarts (result %s), "
      "RSS after warm-up %s kB, growth %d kB, lateness p50 %.1f us p99 %.1f us max %.0f us"
      % (args.seconds, frames, counted, garbage, bytes_sent + 6 * (restarts + 1), restarts,
         result.get("restarts"), rss_after_warmup, growth_kb, pacing.get("lateness_p50_us", -1),
         pacing.get("lateness_p99_us", -1), pacing.get("lateness_max_us", -1)))
problems = []
if counted != frames:
    problems.append("frames lost: %d sent, %d counted" % (frames, counted))
if result.get("restarts") != restarts:
    problems.append("restarts: %d made, %r recorded" % (restarts, result.get("restarts")))
if growth_kb >= 1024 and not args.no_memory_check:
    problems.append("resident memory grew by %d kB after the warm-up" % growth_kb)
if args.latency and pacing.get("lateness_p99_us", 1e9) >= 200:
    problems.append("lateness p99 %.1f us" % pacing["lateness_p99_us"])
if result.get("exit_code") != 0:
    problems.append("exit code %r: %s" % (result.get("exit_code"), result.get("error")))
print("\n".join(problems))
sys.exit(1 if problems else 0)
