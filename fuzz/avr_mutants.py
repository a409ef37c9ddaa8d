#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Damaged AVR images against the emulated board.

Makes COUNT mutants of each image given (bit flips, changed bytes, a truncation, a zeroed block,
a duplicated block; half of them aimed at the ELF header and the program and section header
tables, where a damaged number misleads a reader most), all from SEED, and runs each with
`unimouse run --link avr:MUTANT --duration D`. Every run must end with exit code 0, 1, 2 or 3
and leave a result.json; the counts per exit code are printed, and the exit status is 1 if any
run did not (a signal, another code, no result), with the mutant kept in WORK for a look.

    fuzz/avr_mutants.py --unimouse build/bin/unimouse --count 1000 build/avr/*.elf
"""
import argparse
import collections
import os
import random
import shutil
import struct
import subprocess
import sys
import tempfile


def structural_ranges(image):
    """The byte ranges of the ELF header and of the program and section header tables."""
    ranges = [(0, min(52, len(image)))]
    if len(image) >= 52:
        phoff, shoff = struct.unpack_from("<II", image, 28)
        phentsize, phnum, shentsize, shnum = struct.unpack_from("<HHHH", image, 42)
        for offset, size in ((phoff, phentsize * phnum), (shoff, shentsize * shnum)):
            if 0 < size and offset + size <= len(image):
                ranges.append((offset, offset + size))
    return ranges


def mutate(image, rng):
    """Returns a damaged copy of image and a word saying how it was damaged."""
    data = bytearray(image)
    if rng.random() < 0.5:
        start, end = rng.choice(structural_ranges(image))
    else:
        start, end = 0, len(data)
    where = lambda: rng.randrange(start, end)
    kind = rng.choice(["bits", "bytes", "truncate", "zero", "duplicate"])
    if kind == "bits":
        for _ in range(rng.randint(1, 8)):
            data[where()] ^= 1 << rng.randrange(8)
    elif kind == "bytes":
        for _ in range(rng.randint(1, 16)):
            data[where()] = rng.choice([0, 0xFF, 0x7F, 0x80, rng.randrange(256)])
    elif kind == "truncate":
        del data[rng.randrange(len(data)):]
    elif kind == "zero":
        at = where()
        end = min(len(data), at + rng.randint(1, 512))
        data[at:end] = bytes(end - at)
    else:
        at, size = rng.randrange(len(data)), rng.randint(1, 512)
        block = data[at:at + size]
        to = where()
        data[to:to] = block
    return bytes(data), kind


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--unimouse", required=True, help="the program to run")
    parser.add_argument("--count", type=int, default=1000, help="mutants of each image")
    parser.add_argument("--seed", type=int, default=35)
    parser.add_argument("--duration", default="0.5", help="simulated seconds a run")
    parser.add_argument("--work", help="where mutants and runs go (default: a temporary one)")
    parser.add_argument("--records", help="copy every result.json here (the schema check)")
    parser.add_argument("images", nargs="+")
    args = parser.parse_args()

    work = args.work or tempfile.mkdtemp(prefix="avr_mutants_")
    os.makedirs(work, exist_ok=True)
    counts = collections.Counter()
    kinds = collections.Counter()
    bad = []
    for image_path in args.images:
        name = os.path.splitext(os.path.basename(image_path))[0]
        with open(image_path, "rb") as f:
            image = f.read()
        # one stream per image, so that a sample of one image does not depend on the others
        rng = random.Random(f"{args.seed}:{name}")
        for i in range(args.count):
            mutant, kind = mutate(image, rng)
            stem = f"{name}-{i:04d}"
            mutant_path = os.path.join(work, stem + ".elf")
            out = os.path.join(work, stem)
            with open(mutant_path, "wb") as f:
                f.write(mutant)
            shutil.rmtree(out, ignore_errors=True)
            run = subprocess.run(
                [args.unimouse, "run", "--link", "avr:" + mutant_path, "--duration",
                 args.duration, "--out", out],
                stdout=subprocess.PIPE, stderr=subprocess.STDOUT, check=False)
            result = os.path.join(out, "result.json")
            code = run.returncode
            ended = f"signal {-code}" if code < 0 else f"exit {code}"
            counts[ended] += 1
            kinds[(kind, ended)] += 1
            if code not in (0, 1, 2, 3) or not os.path.exists(result):
                last = run.stdout.decode("utf-8", "replace").strip().splitlines()[-1:]
                bad.append(f"{mutant_path} ({kind}): {ended}, "
                           f"{'a' if os.path.exists(result) else 'no'} result.json: {last}")
                continue
            if args.records:
                os.makedirs(args.records, exist_ok=True)
                shutil.copyfile(result, os.path.join(args.records, f"AvrMutant.{stem}__result.json"))
            # what passed needs no look: only a failure keeps its files
            os.remove(mutant_path)
            shutil.rmtree(out)
    total = sum(counts.values())
    print(f"{total} mutants of {len(args.images)} images, seed {args.seed}, "
          f"{args.duration} s each:")
    for ended, n in sorted(counts.items()):
        by_kind = ", ".join(f"{k} {kinds[(k, ended)]}" for k in
                            ("bits", "bytes", "truncate", "zero", "duplicate") if kinds[(k, ended)])
        print(f"  {ended}: {n} ({by_kind})")
    for line in bad:
        print("BAD " + line)
    if not args.work and not bad:
        shutil.rmtree(work)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
