#!/usr/bin/env python3
"""`--model auto` with a damaged cache picks what it picks with a sound one.

An end-to-end check too long for the test suite (the quick error ladder it
runs twice takes 5-7 min each on 2 cores): in a fresh working folder,

  1. `simulate --model auto` with no cache runs the ladder, picks a model
     and caches the ladder (reports/<scene>/model_choice/ladder-<key>.csv);
  2. one digit of a number in the cached table is changed;
  3. `simulate --model auto` again: the cache is refused with a notice, the
     ladder is run again, the same model is picked, and the new cache holds
     the rows of the first (compared to 1e-6; the title line, which names
     the build, is not compared: rebuild nothing while this runs, or give it
     a copy of the executable).

Prints each run's wall time and exits 1 if a check fails. Usage:

  python3 verification/benchmarks/model_auto_damaged_cache.py build/beamslider [--end-time 1]
"""
import argparse
import glob
import os
import re
import subprocess
import sys
import tempfile
import time


def run(program, folder, output, end_time):
    """simulate --model auto into `output`; (exit status, seconds, stdout+stderr)."""
    start = time.monotonic()
    done = subprocess.run([program, "simulate", "--model", "auto", "--end-time", str(end_time), "--output", output],
                          cwd=folder, capture_output=True, text=True)
    return done.returncode, time.monotonic() - start, done.stdout + done.stderr


def picked(summary_path):
    """The model summary.md says was picked ("picked <rung>: ...")."""
    with open(summary_path, encoding="utf-8") as f:
        found = re.search(r"^picked (.+?):", f.read(), re.MULTILINE)
    return found.group(1) if found else None


def damage(path):
    """Changes one digit of a number in the first data row (not the seal line)."""
    with open(path, "rb") as f:
        data = bytearray(f.read())
    row = data.index(b"\n", data.index(b"\n") + 1) + 1
    digit = data.index(b",0.", row) + 3
    data[digit] = ord("9") if data[digit] != ord("9") else ord("1")
    with open(path, "wb") as f:
        f.write(data)


def differences(sound, recomputed, rel=1e-6):
    """Lines of two cache texts that differ beyond `rel` in a number (the
    title line, with its checksum of the rows, is not compared)."""
    found = []
    a, b = sound.splitlines()[1:], recomputed.splitlines()[1:]
    if len(a) != len(b):
        return [f"{len(a)} rows against {len(b)}"]
    for x, y in zip(a, b):
        for u, v in zip(x.split(","), y.split(",")):
            try:
                same = abs(float(u) - float(v)) <= rel * max(abs(float(u)), abs(float(v)), 1e-300)
            except ValueError:
                same = u == v
            if not same:
                found.append(f"{x}\n    against {y}")
                break
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("program", help="the beamslider executable")
    parser.add_argument("--end-time", type=float, default=1.0, help="simulated time of each run [s]")
    args = parser.parse_args()
    program = os.path.abspath(args.program)
    failures = []
    with tempfile.TemporaryDirectory(prefix="beamslider_model_auto_") as folder:
        status, seconds, text = run(program, folder, "sound", args.end_time)
        print(f"no cache: exit {status}, {seconds:.0f} s (the ladder run and cached)")
        if status not in (0, 3):
            sys.exit(f"the first run failed:\n{text}")
        caches = glob.glob(os.path.join(folder, "reports", "*", "model_choice", "ladder-*.csv"))
        if len(caches) != 1:
            sys.exit(f"expected one cached ladder, found {caches}")
        with open(caches[0], encoding="utf-8") as f:
            sound = f.read()
        damage(caches[0])
        status, seconds, text = run(program, folder, "damaged", args.end_time)
        print(f"damaged cache: exit {status}, {seconds:.0f} s")
        if "is not used" not in text:
            failures.append("no notice that the damaged cache was not used")
        first = picked(os.path.join(folder, "sound", "summary.md"))
        second = picked(os.path.join(folder, "damaged", "summary.md"))
        print(f"picked: {first} (sound), {second} (after the damaged cache)")
        if first is None or first != second:
            failures.append(f"the picks differ: {first} against {second}")
        with open(caches[0], encoding="utf-8") as f:
            recomputed = f.read()
        mismatches = differences(sound, recomputed)
        print("recomputed cache: " + ("byte for byte the first" if recomputed == sound else
                                      "the rows of the first to 1e-6" if not mismatches else "different"))
        for line in mismatches:
            failures.append("the recomputed cache differs from the first:\n  " + line)
    for failure in failures:
        print("FAILED:", failure)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
