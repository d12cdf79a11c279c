#!/usr/bin/python3
"""An OSC-ALKS scenario with ~1,000 background vehicles against bare SUMO on the net the
OpenDRIVE road was converted into: the same net, the same route file, seed, step length and
number of steps (docs/openscenario.md, "Speed"). Prints a Markdown row.

Round 0 runs the scenario once to its StopTrigger with `--traffic RATE`: that gives the
number of steps, the converted net and the generated route file, which every later run
uses as they are. Then `--repeat` interleaved pairs: bare SUMO (`orchestrator baseline
NET.net.xml --traffic FILE`: libsumo, stepped, nothing else) and the orchestrator running
the scenario, each a whole process (loading included). The ratio of each pair is taken
(both ran within seconds of each other, so a slow spell of the shared machine hits both);
the row gives the median of the pair ratios with their range, and the best wall time of each.
On a shared machine the CPU time of each process (user + system, from the kernel's
accounting of the finished child) is steadier than its wall time; both are printed.

Usage: scripts/bench/openscenario_bench.py --binary build/bin/orchestrator [--repeat 5] [--rate 2200]
"""
import argparse
import json
import os
import re
import resource
import statistics
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
from bench import machine, measure  # noqa: E402  (the same wall-time and RSS measurement)

SCENARIO = os.path.join(ROOT, "..", "shared", "data", "openscenario",
                        "alks_scenario_4_4_1_cut_in_no_collision_template.xosc")
STEP = 0.05


def timed(cmd, log):
    """measure() plus the CPU seconds (user + system) the finished process tree used."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    wall, rss, _ = measure(cmd, log)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, rss, cpu


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--binary", default=os.path.join(ROOT, "build", "bin", "orchestrator"))
    ap.add_argument("--scenario", default=SCENARIO)
    ap.add_argument("--rate", type=float, default=2200, help="vehicles/hour/lane (steady state at 130 km/h)")
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--keep", help="work folder to keep (default: a temporary one)")
    a = ap.parse_args()
    work = a.keep or tempfile.mkdtemp(prefix="orch_osc_bench_")
    os.makedirs(work, exist_ok=True)
    print(machine(), file=sys.stderr)

    first = os.path.join(work, "round0")
    timed([a.binary, "run", a.scenario, "--out", first, "-q", "--traffic", "%g" % a.rate], first + ".log")
    result = json.load(open(os.path.join(first, "result.json")))
    if result["verdict"] != "success":
        sys.exit("the scenario did not run to its StopTrigger: %s" % result["reason"])
    steps, net = result["steps"], result["inputs"]["net"]["path"]
    traffic = os.path.join(first, "traffic.rou.xml")
    print("%s: %d steps, net %s" % (os.path.basename(a.scenario), steps, net), file=sys.stderr)

    bare_cmd = [a.binary, "baseline", net, "--traffic", traffic, "--steps", str(steps), "--step", "%g" % STEP,
                "--out", os.path.join(work, "bare")]
    orch_cmd = [a.binary, "run", a.scenario, "--out", os.path.join(work, "orch"), "-q", "--traffic", traffic,
                "--step", "%g" % STEP]
    bare, orch, ratios, cpu_ratios, at_end = [], [], [], [], []
    for i in range(a.repeat):
        b = timed(bare_cmd, os.path.join(work, "bare.log"))
        o = timed(orch_cmd, os.path.join(work, "orch.log"))
        bare.append(b)
        orch.append(o)
        ratios.append(o[0] / b[0])
        cpu_ratios.append(o[2] / b[2])
        m = re.search(r"(\d+) vehicles at the end", open(os.path.join(work, "bare.log")).read())
        at_end.append(int(m.group(1)) if m else -1)
        print("  pair %d: bare %.2f s (cpu %.2f s), orchestrator %.2f s (cpu %.2f s), ratio %.3f (cpu %.3f), load %.1f" % (
            i + 1, b[0], b[2], o[0], o[2], ratios[-1], cpu_ratios[-1], os.getloadavg()[0]), file=sys.stderr)
    orch_result = json.load(open(os.path.join(work, "orch", "result.json")))
    log = open(os.path.join(work, "orch", "run.log")).read()
    m = re.search(r"(\d+) background vehicles in SUMO at the end", log)
    print("| scenario, traffic (vehicles at the end) | steps | bare SUMO (libsumo): wall, cpu | orchestrator libsumo: wall, cpu "
          "| orch / bare wall, median of pairs (range) | orch / bare cpu, median (range) |")
    print("|---|---|---|---|---|---|")
    print("| %s, %g veh/h/lane (%s; bare %d) | %d | %.2f s, %.2f s, %.0f MB | %.2f s, %.2f s, %.0f MB | **%.2f** (%.2f-%.2f) "
          "| **%.2f** (%.2f-%.2f) |" % (
              os.path.basename(a.scenario).replace("_template.xosc", ""), a.rate, m.group(1) if m else "?", at_end[-1],
              steps, min(x[0] for x in bare), min(x[2] for x in bare), max(x[1] for x in bare),
              min(x[0] for x in orch), min(x[2] for x in orch), max(x[1] for x in orch),
              statistics.median(ratios), min(ratios), max(ratios),
              statistics.median(cpu_ratios), min(cpu_ratios), max(cpu_ratios)))
    print("verdict %s; load average %.1f at the end" % (orch_result["verdict"], os.getloadavg()[0]), file=sys.stderr)


if __name__ == "__main__":
    main()
