#!/usr/bin/env python3
"""Finds text that README.md and doc/*.md say twice: every run of 20 or more
consecutive words (case, punctuation and Markdown marks ignored) that stands
in two places, within one file or across files. Code blocks and tables are
included (a table row copied is a duplicate too). Prints one line per run and
exits 1 if there is any, 0 if none.

    python3 scripts/doc_duplicates.py [--words N]
"""
import argparse
import glob
import os
import re
import sys

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--words", type=int, default=20, help="shortest run of shared words reported")
args = parser.parse_args()

root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
files = [os.path.join(root, "README.md")] + sorted(glob.glob(os.path.join(root, "doc", "*.md")))
words = []  # (word, file, line)
for path in files:
    for number, line in enumerate(open(path, encoding="utf-8"), 1):
        for w in re.findall(r"[\w.'’/=-]+", line.lower()):
            w = w.strip(".'’")
            if w:
                words.append((w, os.path.relpath(path, root), number))

n = args.words
first = {}
reported = set()
found = 0
for i in range(len(words) - n + 1):
    key = tuple(w for w, _, _ in words[i:i + n])
    if key not in first:
        first[key] = i
        continue
    j = first[key]
    if j + n > i:  # overlapping with itself (a repeated phrase inside one run)
        continue
    # Report each shared run once: skip a window that continues the last one.
    if (i - 1, j - 1) in reported:
        reported.add((i, j))
        continue
    reported.add((i, j))
    found += 1
    _, file_a, line_a = words[j]
    _, file_b, line_b = words[i]
    print(f"{file_a}:{line_a} ~ {file_b}:{line_b}: {' '.join(key)}")
print(f"{found} shared run(s) of {n}+ words in {len(files)} files", file=sys.stderr)
sys.exit(1 if found else 0)
