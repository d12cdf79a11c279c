#!/usr/bin/env python3
"""The cost of metrics and criteria (docs/evaluation.md "Cost").

Runs bench_scenario.json (ego plus three scripted cars) on ALKS_Road with ~1,000 background
vehicles, 400 steps of 0.05 s, libsumo, and prints from result.json's `timing` the
orchestrator's own time in its stepping loop (reading, engine, commands, trace, metrics,
criteria) over the time inside SUMO's steps, measured in the same process. With --against
OLD_BINARY (a build without metrics) the same runs interleaved with it, for the difference.
result.json's timing.observers_s splits the stepping loop's time by observer (trace,
metrics, criteria, result.jsonl), measured in the same process, so the metrics' own share
does not depend on how busy the machine is. Figures, not a test: nothing is asserted.
"""
import argparse
import csv
import json
import os
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
SCENARIO = os.path.join(HERE, "bench_scenario.json")
EVALUATION = os.path.join(HERE, "bench_evaluation.yaml")
STEP, STEPS = 0.05, 400


def run(binary, target, traffic, out):
    subprocess.run([binary, "run", target, "--out", out, "-q", "--traffic", traffic, "--max-time", "%g" % (STEP * STEPS),
                    "--step", "%g" % STEP, "--backend", "libsumo"], check=False, stdout=subprocess.DEVNULL)
    with open(os.path.join(out, "result.json")) as f:
        timing = json.load(f)["timing"]
    with open(os.path.join(out, "counts.csv")) as f:
        vehicles = statistics.mean(int(r["background_vehicles"]) for r in csv.DictReader(f))
    shares = {"all": timing["orchestrator_s"] / timing["sumo_step_s"]}
    for name, s in timing.get("observers_s", {}).items():
        shares[name] = s / timing["sumo_step_s"]
    return shares, vehicles


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("binary")
    ap.add_argument("--against", help="an orchestrator binary without metrics")
    ap.add_argument("--rounds", type=int, default=5)
    a = ap.parse_args()
    print("load average at start: %.2f" % os.getloadavg()[0])
    with tempfile.TemporaryDirectory() as work:
        traffic = os.path.join(work, "traffic.rou.xml")
        subprocess.run([a.binary, "map", "traffic", "ALKS_Road", "--rate", "1800", "--fill-per-km", "33", "--out",
                        traffic], check=True, stdout=subprocess.DEVNULL)
        configs = [("metrics", a.binary, SCENARIO), ("metrics + criteria", a.binary, EVALUATION)]
        if a.against:
            configs.insert(0, ("without metrics", a.against, SCENARIO))
        shares = {name: {} for name, _, _ in configs}
        vehicles = []
        for r in range(a.rounds):
            for name, binary, target in configs:
                got, v = run(binary, target, traffic, os.path.join(work, "%s_%d" % (name.replace(" ", "_"), r)))
                for part, share in got.items():
                    shares[name].setdefault(part, []).append(share)
                vehicles.append(v)
        print("%.0f background vehicles on average, %d steps, %d rounds; per cent of SUMO's step time, "
              "median (range):" % (statistics.mean(vehicles), STEPS, a.rounds))
        for name, _, _ in configs:
            parts = ", ".join("%s %.2f (%.2f-%.2f)" % ("orchestrator's own time" if part == "all" else part,
                                                       100 * statistics.median(s), 100 * min(s), 100 * max(s))
                              for part, s in shares[name].items())
            print("%-20s %s" % (name, parts))


if __name__ == "__main__":
    sys.exit(main())
