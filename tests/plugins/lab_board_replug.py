#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""A board on a pseudo-terminal, written as a lab user would: plain os.read/os.write on the pty,
frames packed with struct. It drives the robot, closes the pty (the board emulator quits), opens
it again and starts over; the run must carry on as one run with one restart.

usage: lab_board_replug.py UNIMOUSE OUT_DIR
Exit status 0 when the run said and recorded what it should, 1 (with the reason) when not.
"""
import json
import os
import struct
import subprocess
import sys
import time
import tty

unimouse, out_dir = sys.argv[1], sys.argv[2]
link = os.path.join(out_dir + ".pty")

# begin() of the Arduino library: frame sizes, sensors on, "I repeat my commands"
START_UP = bytes([7, 0x14, 7, 0x02, 7, 0x12])


def motors(left, right):
    return struct.pack("<BhBh", 5, left, 6, right)


def wait_for(path, seconds):
    end = time.monotonic() + seconds
    while not os.path.exists(path):
        if time.monotonic() > end:
            sys.exit("the simulator never made " + path)
        time.sleep(0.01)


def open_board():
    fd = os.open(link, os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)
    tty.setraw(fd)
    return fd


def drive(fd, left, right, seconds):
    """Sends begin() once, then the motor command every 20 ms, as the library does; reads and
    throws away what the simulator sends. Returns False when the simulator went away."""
    os.write(fd, START_UP)
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        try:
            os.write(fd, motors(left, right))
            while os.read(fd, 4096):
                pass
        except BlockingIOError:
            pass
        except OSError:  # EIO: the simulator closed its side, the run is over
            return False
        time.sleep(0.02)
    return True


if os.path.lexists(link):
    os.remove(link)
run = subprocess.Popen(
    [unimouse, "run", "--maze", "none", "--duration", "4", "--no-pictures", "--out", out_dir,
     "--link", "pty:" + link],
    stderr=subprocess.PIPE, text=True)
wait_for(link, 30)
board = open_board()
drive(board, 600, 600, 0.6)
os.close(board)  # the board goes away for a moment
time.sleep(0.3)
board = open_board()
drive(board, 300, 300, 30)  # until the run ends
os.close(board)
console = run.stderr.read()
code = run.wait()

problems = []
if code != 0:
    problems.append("exit code %d" % code)
for line in ["link: firmware disconnected: motors stopped",
             "(its first frame after the link came back): motors stopped until it commands "
             "them; restart 1"]:
    if line not in console:
        problems.append("no line '%s'" % line)
with open(os.path.join(out_dir, "result.json")) as f:
    result = json.load(f)
if result.get("restarts") != 1:
    problems.append("restarts %r, not 1" % result.get("restarts"))
if result.get("status") != "completed":
    problems.append("status %r" % result.get("status"))
if problems:
    print("\n".join(problems) + "\n--- console:\n" + console)
    sys.exit(1)
