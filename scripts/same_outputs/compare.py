#!/usr/bin/env python3
# compare.py A B [--added-column COLUMN] [--added-summary KEY]: every run folder of A against B.
# CSVs, result.jsonl, ssm.xml and exit codes byte for byte; result.json less its wall-clock fields,
# its keys in order; run.log less the wall time of its last line.
# An intended addition (a new metric): --added-column drops that column from B's metrics.csv and
# --added-summary that key from every actor of B's result.json "metrics", after checking B has
# them, so that the comparison shows the addition and nothing else.
import argparse, collections, json, os, re, sys, filecmp
ap = argparse.ArgumentParser()
ap.add_argument("a"); ap.add_argument("b")
ap.add_argument("--added-column", action="append", default=[])
ap.add_argument("--added-summary", action="append", default=[])
args = ap.parse_args()
a, b = args.a, args.b
WALL = {"wall_time_s", "timing"}
def norm_result(p, added=False):
    j = json.load(open(p), object_pairs_hook=collections.OrderedDict)  # key order counts
    for k in WALL: j.pop(k, None)
    if added:
        for summary in (j.get("metrics") or {}).values():
            for key in args.added_summary:
                if key not in summary: raise SystemExit(f"{p}: no summary {key}")
                summary.pop(key)
    return j
def without_columns(p):
    lines = open(p).read().split("\n")
    header = lines[0].split(",")
    drop = [header.index(c) for c in args.added_column if c in header]
    if len(drop) != len(args.added_column): raise SystemExit(f"{p}: not every added column is there")
    return "\n".join(",".join(c for i, c in enumerate(l.split(",")) if i not in drop) if l else l for l in lines)
def norm_log(p):
    t = open(p).read()
    t = re.sub(r" \((cached|converted now)\)", "", t)  # the OpenDRIVE net cache: filled by the first run
    return re.sub(r", [0-9.]+ s wall\)", ")", t)
def norm_ssm(p):  # SUMO stamps its outputs with the wall-clock date
    t = re.sub(r"generated on [0-9-]+ [0-9:]+", "", open(p).read())
    return re.sub(r"<remote-port value=\"[0-9]+\"/>", "", t)  # traci: a free port
def norm_jsonl(p):
    return re.sub(r'"System":[-0-9.eE+]+,?', "", open(p).read())
files = same = 0
bad = []
for backend in sorted(os.listdir(a)):
    for case in sorted(os.listdir(os.path.join(a, backend))):
        da, db = os.path.join(a, backend, case), os.path.join(b, backend, case)
        for dirpath, _, names in os.walk(da):
            rel = os.path.relpath(dirpath, da)
            for n in sorted(names):
                pa, pb = os.path.join(dirpath, n), os.path.join(db, rel, n)
                if n in ("sumo.log",) or n.endswith(".console"): continue
                files += 1
                if not os.path.exists(pb): bad.append(f"{backend}/{case}/{rel}/{n}: missing in B"); continue
                if n == "result.json": ok = norm_result(pa) == norm_result(pb, True)
                elif n == "metrics.csv" and args.added_column: ok = open(pa).read() == without_columns(pb)
                elif n == "run.log": ok = norm_log(pa) == norm_log(pb)
                elif n == "result.jsonl": ok = norm_jsonl(pa) == norm_jsonl(pb)
                elif n == "ssm.xml": ok = norm_ssm(pa) == norm_ssm(pb)
                else: ok = filecmp.cmp(pa, pb, shallow=False)
                if ok: same += 1
                else: bad.append(f"{backend}/{case}/{rel}/{n}: differs")
        for dirpath, _, names in os.walk(db):
            rel = os.path.relpath(dirpath, db)
            for n in names:
                if n in ("sumo.log",): continue
                if not os.path.exists(os.path.join(da, rel, n)): bad.append(f"{backend}/{case}/{rel}/{n}: only in B")
print(f"{same}/{files} files identical")
for x in bad: print(" ", x)
sys.exit(1 if bad else 0)
