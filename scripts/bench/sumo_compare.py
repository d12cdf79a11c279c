#!/usr/bin/python3
"""The orchestrator against the `sumo` executable, the program a user would run instead:
whole processes, on ALKS_Road with the traffic of `map traffic --rate 1800 --fill-per-km F`
(F = 33: ~1,000 vehicles; F = 100: ~3,000), step 0.05 s, seed 42.

Per size, a first orchestrator run of scripts/bench/bench_scenario.json gives result.json's
`sumo_args` (net, route files, every SUMO option it used); plain `sumo` then runs with exactly
those arguments (the log moved to the work folder) and `--end` at the same simulated time.
Then `--repeat` rounds, each running the three processes back to back in a rotating order:
`sumo`, `orchestrator run bench_scenario.json`, `orchestrator baseline ALKS_Road` (libsumo,
no scenario). Each process runs under /usr/bin/time -v: wall, CPU (user + system) and peak
resident memory. A round's ratios are taken against that round's `sumo` (run within
seconds of each other, so a slow spell of the shared machine hits both); the table gives the
median of those pair ratios and their range, and the median time and memory of each process.

Usage: scripts/bench/sumo_compare.py [--binary build/bin/orchestrator] [--repeat 5] [--sizes 33,100]
       [--steps 400,200] [--keep DIR]
"""
import argparse
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
from bench import machine, vehicles  # noqa: E402

SCENARIO = os.path.join(HERE, "bench_scenario.json")
MAP = "ALKS_Road"
STEP = 0.05
RATE = 1800


def time_v(cmd, log):
    """Runs cmd under /usr/bin/time -v: (wall s, CPU s, peak RSS MB)."""
    start = time.monotonic()
    with open(log, "w") as out:
        proc = subprocess.run(["/usr/bin/time", "-v"] + cmd, stdout=out, stderr=subprocess.STDOUT)
    wall = time.monotonic() - start
    text = open(log, errors="replace").read()
    if proc.returncode not in (0, 1):
        sys.exit("failed (%d): %s\n%s" % (proc.returncode, " ".join(cmd), text[-2000:]))

    def field(name):
        m = re.search(r"%s: ([0-9.]+)" % re.escape(name), text)
        return float(m.group(1)) if m else 0.0

    cpu = field("User time (seconds)") + field("System time (seconds)")
    return wall, cpu, field("Maximum resident set size (kbytes)") / 1024


def plain_sumo(result, work, steps):
    """`sumo` with the run's own arguments: its route files copied (the run folder is
    written again by every run), its log in the work folder, ending at the same time."""
    args = list(result["sumo_args"])
    for i, a in enumerate(args):
        if a == "-r":
            copies = []
            for f in args[i + 1].split(","):
                dest = os.path.join(work, os.path.basename(f))
                if os.path.abspath(f) != os.path.abspath(dest):
                    shutil.copy(f, dest)
                copies.append(dest)
            args[i + 1] = ",".join(copies)
        if a == "--log":
            args[i + 1] = os.path.join(work, "sumo_plain.log")
    return ["sumo"] + args + ["--end", "%g" % (steps * STEP)]


def size(binary, fill, steps, repeat, work):
    traffic = os.path.join(work, "traffic_%d.rou.xml" % fill)
    subprocess.run([binary, "map", "traffic", MAP, "--rate", str(RATE), "--fill-per-km", str(fill), "--out", traffic],
                   check=True, stdout=subprocess.DEVNULL)
    run_dir = os.path.join(work, "run_%d" % fill)
    run_cmd = [binary, "run", SCENARIO, "--out", run_dir, "-q", "--no-report", "--traffic", traffic,
               "--max-time", "%g" % (steps * STEP), "--step", "%g" % STEP]
    time_v(run_cmd, run_dir + ".log")
    result = json.load(open(os.path.join(run_dir, "result.json")))
    mean, _ = vehicles(os.path.join(run_dir, "counts.csv"))
    commands = {
        "sumo": plain_sumo(result, work, steps),
        "run": run_cmd,
        "baseline": [binary, "baseline", MAP, "--traffic", traffic, "--steps", str(steps), "--step", "%g" % STEP,
                     "--out", os.path.join(work, "baseline_%d" % fill)],
    }
    print("  plain sumo: %s" % " ".join(commands["sumo"]), file=sys.stderr)
    order = list(commands)
    runs = {k: [] for k in commands}
    for r in range(repeat):
        for key in order[r % 3:] + order[:r % 3]:  # rotate who goes first
            runs[key].append(time_v(commands[key], os.path.join(work, "%s_%d.log" % (key, fill))))
        print("  ~%.0f vehicles, round %d: %s" % (mean, r + 1, ", ".join(
            "%s %.2f s wall %.2f s CPU" % (k, v[-1][0], v[-1][1]) for k, v in runs.items())), file=sys.stderr)
    return mean, steps, runs


def pair_ratio(num, den, index):
    each = sorted(a[index] / b[index] for a, b in zip(num, den))
    return "**%.3f** (%.2f-%.2f)" % (statistics.median(each), each[0], each[-1])


def table(rows, repeat):
    lines = ["| vehicles (mean) | steps | `sumo`: wall, CPU, peak RSS | orchestrator run: wall, CPU, peak RSS | "
             "run / sumo, wall | run / sumo, CPU | baseline (libsumo): wall, CPU, peak RSS | baseline / sumo, wall | "
             "baseline / sumo, CPU | memory run / sumo |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for mean, steps, runs in rows:
        def cell(key):
            v = runs[key]
            return "%.2f s, %.2f s, %.0f MB" % (statistics.median(x[0] for x in v), statistics.median(x[1] for x in v),
                                               max(x[2] for x in v))
        mem = max(x[2] for x in runs["run"]) / max(x[2] for x in runs["sumo"])
        lines.append("| %.0f | %d | %s | %s | %s | %s | %s | %s | %s | %.2f |" % (
            mean, steps, cell("sumo"), cell("run"), pair_ratio(runs["run"], runs["sumo"], 0),
            pair_ratio(runs["run"], runs["sumo"], 1), cell("baseline"), pair_ratio(runs["baseline"], runs["sumo"], 0),
            pair_ratio(runs["baseline"], runs["sumo"], 1), mem))
    return "\n".join(lines) + "\n\n%d rounds per size; times are medians over the rounds, ratios the median " \
        "(range) of the rounds' own ratios against that round's `sumo`." % repeat


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--binary", default=os.path.join(ROOT, "build", "bin", "orchestrator"))
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--sizes", default="33,100", help="fill-per-km values (33: ~1,000 vehicles, 100: ~3,000)")
    ap.add_argument("--steps", default="400,200", help="steps per size")
    ap.add_argument("--keep", help="work folder to keep (default: a temporary one)")
    a = ap.parse_args()
    os.environ.setdefault("SUMO_HOME", "/usr/share/sumo")
    work = a.keep or tempfile.mkdtemp(prefix="orch_sumo_compare_")
    os.makedirs(work, exist_ok=True)
    header = machine()
    print(header, file=sys.stderr)
    rows = [size(a.binary, int(f), int(s), a.repeat, work)
            for f, s in zip(a.sizes.split(","), a.steps.split(","))]
    print("Machine: %s; load average %.1f at the end" % (header, os.getloadavg()[0]))
    print(table(rows, a.repeat))


if __name__ == "__main__":
    main()
