#!/usr/bin/python3
"""OpenSCENARIO files in the orchestrator against esmini, the peer player: every OSC-ALKS
template (../shared/data/openscenario/*.xosc) and every esmini example
(../shared/data/esmini_examples/xosc/*.xosc), no background traffic, fixed step 0.05 s,
whole processes (loading included). Prints a Markdown table (docs/performance.md).

Each file first runs once in the orchestrator (a probe: it converts the road to a SUMO net,
which later runs find cached, and tells whether the file runs at all: a run whose verdict is
`error` is listed as not running and not timed). Then `--repeat` interleaved pairs: esmini
(`--headless --fixed_timestep 0.05 --disable_stdout`, nothing recorded) and the orchestrator
(`run FILE -q --no-report --traffic none --step 0.05`). The row gives the best wall time
and the best CPU time (user + system of the finished process, less disturbed than the wall
time on a loaded machine) of each, and the median of the pairs' own ratios (orchestrator /
esmini) with their range, of wall and of CPU time. A process still running after
`--timeout` seconds is stopped and the row says so.

Usage: scripts/bench/openscenario_esmini.py [--binary build/bin/orchestrator]
       [--esmini ../shared/tools/esmini/bin/esmini] [--repeat 3] [--timeout 300] [--only SUBSTRING]...
"""
import argparse
import glob
import json
import os
import re
import resource
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
SHARED = os.path.join(os.path.dirname(ROOT), "shared")
sys.path.insert(0, HERE)
from bench import machine  # noqa: E402

STEP = 0.05


def corpus():
    alks = sorted(glob.glob(os.path.join(SHARED, "data", "openscenario", "*.xosc")))
    examples = sorted(glob.glob(os.path.join(SHARED, "data", "esmini_examples", "xosc", "*.xosc")))
    return [("OSC-ALKS", f) for f in alks] + [("esmini example", f) for f in examples]


def road_of(xosc):
    """The LogicFile's name (with a $parameter resolved from its declaration)."""
    text = open(xosc, encoding="utf-8-sig", errors="replace").read()
    m = re.search(r'<LogicFile\s+filepath="([^"]*)"', text)
    if not m:
        return "-"
    path = m.group(1)
    if path.startswith("$"):
        d = re.search(r'<ParameterDeclaration\s+name="%s"[^>]*value="([^"]*)"' % re.escape(path[1:]), text)
        path = d.group(1) if d else path
    return os.path.splitext(os.path.basename(path))[0]


def timed(cmd, log, timeout, cwd=None):
    """(wall s, CPU s, exit code or None when stopped at the time-out)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.monotonic()
    with open(log, "w") as out:
        proc = subprocess.Popen(cmd, stdout=out, stderr=subprocess.STDOUT, cwd=cwd)
        try:
            code = proc.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()
            code = None
    wall = time.monotonic() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime), code


def esmini_end(log):
    """The last simulation time esmini logged ("[12.350] ..."), or None."""
    times = re.findall(r"^\[(\d+\.\d+)\]", open(log, errors="replace").read(), re.M)
    return float(times[-1]) if times else None


def run_file(a, kind, xosc, work):
    name = os.path.splitext(os.path.basename(xosc))[0]
    out = os.path.join(work, name)
    orch_cmd = [a.binary, "run", xosc, "--out", out, "-q", "--no-report", "--traffic", "none", "--step", "%g" % STEP]
    esmini_log = os.path.join(work, name + ".esmini.txt")
    esmini_cmd = [a.esmini, "--headless", "--fixed_timestep", "%g" % STEP, "--osc", xosc, "--disable_stdout",
                  "--logfile_path", esmini_log]
    row = {"kind": kind, "file": os.path.basename(xosc), "road": road_of(xosc)}
    probe = timed(orch_cmd, out + ".log", a.timeout)
    if probe[2] is None:
        row["note"] = "orchestrator still running after %d s" % a.timeout
        return row
    try:
        result = json.load(open(os.path.join(out, "result.json")))
    except (OSError, ValueError):
        row["note"] = "orchestrator: no result.json (exit %s)" % probe[2]
        return row
    if result.get("verdict") == "error":
        row["note"] = "does not run in the orchestrator: " + result.get("reason", "")[:120]
        return row
    row["sim_time"] = result.get("sim_time")
    args = result.get("sumo_args") or []
    if "-n" in args:
        net = args[args.index("-n") + 1]
        row["floor"] = min(timed(["sumo", "-n", net, "--end", "0", "--no-step-log"], out + ".floor.log", a.timeout)[1]
                           for _ in range(a.repeat))
    orch, esm = [], []
    for i in range(a.repeat):
        pair = [("esmini", esmini_cmd, esmini_log + ".out"), ("orch", orch_cmd, out + ".log")]
        if i % 2:
            pair.reverse()  # alternate which goes first
        for who, cmd, log in pair:
            (esm if who == "esmini" else orch).append(timed(cmd, log, a.timeout))
    if any(e[2] is None for e in esm):
        row["note"] = "esmini still running after %d s" % a.timeout
    elif any(e[2] != 0 for e in esm):
        row["note"] = "esmini exit code %s" % ",".join(str(e[2]) for e in esm)
    row["esmini_time"] = esmini_end(esmini_log)
    row["orch"], row["esmini"] = orch, esm
    print("  %s: orchestrator %s s, esmini %s s" % (row["file"], " ".join("%.2f" % o[0] for o in orch),
                                                     " ".join("%.2f" % e[0] for e in esm)), file=sys.stderr)
    return row


def ratio_text(num, den, index):
    each = sorted(n[index] / d[index] for n, d in zip(num, den) if d[index] > 0)
    if not each:
        return "-", None
    med = statistics.median(each)
    return ("**%.2f** (%.2f-%.2f)" % (med, each[0], each[-1]) if len(each) > 1 else "**%.2f**" % med), med


def table(rows):
    lines = ["| file | road | simulated (orchestrator / esmini) | orchestrator wall | esmini wall | "
             "orch / esmini, wall | orchestrator CPU | esmini CPU | orch / esmini, CPU | floor: `sumo` loading the net, CPU |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    medians, cpu_medians = [], []
    for r in rows:
        if "orch" not in r:
            note = " ".join(r["note"].split())  # one table row: netconvert's errors span lines
            lines.append("| %s | %s | %s | | | | | | | |" % (r["file"], r["road"], note))
            continue
        wall, med = ratio_text(r["orch"], r["esmini"], 0)
        cpu, cpu_med = ratio_text(r["orch"], r["esmini"], 1)
        if med is not None and "note" not in r:
            medians.append((med, r["file"]))
        if cpu_med is not None and "note" not in r:
            cpu_medians.append((cpu_med, r["file"]))
        et = r.get("esmini_time")
        floor = r.get("floor")
        esmini_cpu = min(e[1] for e in r["esmini"])
        lines.append("| %s | %s | %.2f s / %s%s | %.2f s | %.2f s | %s | %.2f s | %.2f s | %s | %s |" % (
            r["file"], r["road"], r["sim_time"] or 0, "%.2f s" % et if et is not None else "?",
            " (%s)" % r["note"] if "note" in r else "", min(o[0] for o in r["orch"]), min(e[0] for e in r["esmini"]),
            wall, min(o[1] for o in r["orch"]), esmini_cpu, cpu,
            "-" if floor is None else "%.3f s%s" % (floor, " (above esmini's)" if floor > esmini_cpu else "")))
    summary = ""
    if medians:
        medians.sort()
        over = [f for m, f in medians if m > 1.0]
        cpu_medians.sort()
        cpu_over = [f for m, f in cpu_medians if m > 1.0]
        summary = ("\n%d files timed; median of the per-file wall ratios %.2f, largest %.2f (%s); %d above 1.00%s" % (
            len(medians), statistics.median(m for m, _ in medians), medians[-1][0], medians[-1][1], len(over),
            ": " + ", ".join(over) if over else ""))
        if cpu_medians:  # CPU time: the steadier figure on a loaded machine
            summary += ("\nCPU: median of the per-file ratios %.2f, largest %.2f (%s); %d above 1.00; at most 1.00: %s" % (
                statistics.median(m for m, _ in cpu_medians), cpu_medians[-1][0], cpu_medians[-1][1], len(cpu_over),
                ", ".join(f for m, f in cpu_medians if m <= 1.0) or "none"))
        timed_rows = [r for r in rows if "orch" in r and "note" not in r and r.get("floor") is not None]
        bound = [r for r in timed_rows if r["floor"] > min(e[1] for e in r["esmini"])]
        free = [r for r in timed_rows if r not in bound]
        met = [r for r in free if min(o[1] for o in r["orch"]) <= min(e[1] for e in r["esmini"])]
        summary += ("\nFloor: in %d of %d timed files `sumo` loading the net takes more CPU than esmini's whole run "
                    "(no SUMO-based run can match esmini there); of the other %d, %d take at most esmini's CPU time"
                    % (len(bound), len(timed_rows), len(free), len(met)))
    return "\n".join(lines) + summary


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--binary", default=os.path.join(ROOT, "build", "bin", "orchestrator"))
    ap.add_argument("--esmini", default=os.path.join(SHARED, "tools", "esmini", "bin", "esmini"))
    ap.add_argument("--repeat", type=int, default=3, help="interleaved pairs per file (default 3)")
    ap.add_argument("--timeout", type=float, default=300, help="seconds before a process is stopped")
    ap.add_argument("--only", action="append", help="only files whose name contains this (repeatable)")
    ap.add_argument("--keep", help="work folder to keep (default: a temporary one)")
    a = ap.parse_args()
    work = a.keep or tempfile.mkdtemp(prefix="orch_osc_esmini_")
    os.makedirs(work, exist_ok=True)
    os.environ.setdefault("SUMO_HOME", "/usr/share/sumo")
    header = machine() + ", " + time.strftime("%Y-%m-%d %H:%M", time.gmtime()) + " UTC"
    print(header, file=sys.stderr)
    rows = []
    for kind, xosc in corpus():
        if a.only and not any(s in os.path.basename(xosc) for s in a.only):
            continue
        rows.append(run_file(a, kind, xosc, work))
    print("Machine: " + header + "; finished with load average %.1f, %s UTC" % (
        os.getloadavg()[0], time.strftime("%Y-%m-%d %H:%M", time.gmtime())))
    print(table(rows))


if __name__ == "__main__":
    main()
