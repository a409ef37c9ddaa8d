#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# A left-wall follower for the mms protocol, written as mms programs are: one command a line on
# stdout, flushed, and one reply a line read back from stdin. It stops when it is told it is in
# the centre (it keeps no map, so it asks nothing about where it is: it just walks).
import sys


def command(text):
    sys.stdout.write(text + "\n")
    sys.stdout.flush()


def ask(text):
    command(text)
    return sys.stdin.readline().strip()


def wall(side):
    return ask("wall" + side) == "true"


def log(text):
    sys.stderr.write(text + "\n")
    sys.stderr.flush()


def main():
    log("left-wall follower starting")
    command("setColor 0 0 G")
    command("setText 0 0 start here")
    while True:
        if not wall("Left"):
            ask("turnLeft")
        else:
            while wall("Front"):
                ask("turnRight")
        if ask("moveForward") != "ack":
            log("crashed")


main()
