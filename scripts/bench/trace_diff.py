#!/usr/bin/python3
"""Compares the run folders of two trees of runs (the same scenarios run by two builds, e.g.
before and after a speed change): per run, whether trace.csv, metrics.csv and run.log are
byte-identical, and where they are not, the largest absolute difference of each numeric
column of trace.csv (rows matched in order; a differing row count or text cell is named).

Usage: scripts/bench/trace_diff.py BEFORE_ROOT AFTER_ROOT
       (each holds one folder per run, as written by `orchestrator run --out ROOT/NAME`)
"""
import csv
import os
import sys

FILES = ["trace.csv", "metrics.csv", "run.log"]


def numeric_diff(a_path, b_path):
    """(largest |difference| per numeric column, other differences as text)."""
    with open(a_path, newline="") as fa, open(b_path, newline="") as fb:
        a_rows, b_rows = list(csv.reader(fa)), list(csv.reader(fb))
    notes, largest = [], {}
    if len(a_rows) != len(b_rows):
        notes.append("%d rows against %d" % (len(a_rows), len(b_rows)))
    header = a_rows[0] if a_rows else []
    for ra, rb in zip(a_rows[1:], b_rows[1:]):
        for i, (x, y) in enumerate(zip(ra, rb)):
            if x == y:
                continue
            name = header[i] if i < len(header) else str(i)
            try:
                largest[name] = max(largest.get(name, 0.0), abs(float(x) - float(y)))
            except ValueError:
                if len(notes) < 5:
                    notes.append("%s: %r against %r" % (name, x, y))
    return largest, notes


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    before, after = sys.argv[1:]
    names = sorted(n for n in os.listdir(before) if os.path.isdir(os.path.join(before, n)))
    identical = 0
    worst = 0.0
    for name in names:
        a, b = os.path.join(before, name), os.path.join(after, name)
        if not os.path.isdir(b):
            print("%s: missing in %s" % (name, after))
            continue
        differing = []
        for f in FILES:
            fa, fb = os.path.join(a, f), os.path.join(b, f)
            if not os.path.exists(fa) and not os.path.exists(fb):
                continue
            if not (os.path.exists(fa) and os.path.exists(fb)) or open(fa, "rb").read() != open(fb, "rb").read():
                differing.append(f)
        if not differing:
            identical += 1
            print("%s: identical (%s)" % (name, ", ".join(f for f in FILES if os.path.exists(os.path.join(a, f)))))
            continue
        line = "%s: differs in %s" % (name, ", ".join(differing))
        if "trace.csv" in differing and os.path.exists(os.path.join(a, "trace.csv")) and os.path.exists(
                os.path.join(b, "trace.csv")):
            largest, notes = numeric_diff(os.path.join(a, "trace.csv"), os.path.join(b, "trace.csv"))
            if largest:
                worst = max(worst, max(largest.values()))
                line += "; trace.csv largest differences: " + ", ".join(
                    "%s %.3g" % (k, v) for k, v in sorted(largest.items(), key=lambda kv: -kv[1])[:6])
            if notes:
                line += "; " + "; ".join(notes)
        print(line)
    print("%d of %d runs identical; largest numeric difference in a trace.csv: %.3g" % (identical, len(names), worst))


if __name__ == "__main__":
    main()
