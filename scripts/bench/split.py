#!/usr/bin/python3
"""Where the orchestrator's time over bare SUMO goes (docs/performance.md): at ~1,000
vehicles on ALKS_Road, in interleaved rounds, whole processes:

  bare       `orchestrator baseline`: SUMO with the traffic, no scenario
  actors     actors_baseline: the same SUMO command line as the orchestrator's run, the
             scenario's four vehicles inserted and moved to the run's trace poses every step
             by a minimal libsumo loop (moveToXY, setSpeed): no engine, no subscriptions
  no_ctx     the orchestrator with its context subscriptions off (ORCH_BENCH_NO_CONTEXTS=1,
             measurement only: no nearby vehicles, so no background collisions)
  orch       the orchestrator as it runs

so that actors / bare is SUMO simulating the scenario's vehicles, no_ctx / actors the
orchestrator's own step (engine, reading, trace, metrics), orch / no_ctx the context
subscriptions. Each ratio is the median of the rounds' own ratios (each round runs the four
back to back, in a rotating order), with the range in brackets, of wall times and of CPU
times (user + system of the process and its children): on a shared machine a process
waits for a core for a varying while, so CPU time is the steadier figure.

With --instructions each process runs once under valgrind's callgrind instead, and the
table gives instruction counts: the same on a busy machine as on an idle one, so shares of a
few per cent can be read off where timed rounds scatter by more than that.

Usage: split.py --binary build-bench/bin/orchestrator --actors build-bench/bin/actors_baseline
                [--rounds 7] [--size 1000|200|3000] [--instructions]
"""
import argparse
import json
import os
import statistics
import subprocess
import time
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench  # noqa: E402

SIZES = {s[0].strip("~").replace(",", ""): s for s in bench.SIZES}


def measure(cmd, log, env=None):
    """(wall s, CPU s) of one process."""
    start = time.monotonic()
    with open(log, "w") as out:
        proc = subprocess.Popen(cmd, stdout=out, stderr=subprocess.STDOUT, env=env)
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.monotonic() - start
    code = os.waitstatus_to_exitcode(status)
    if code not in (0, 1):
        sys.exit("failed (%d): %s" % (code, " ".join(cmd)))
    return wall, usage.ru_utime + usage.ru_stime


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--binary", required=True)
    ap.add_argument("--actors", required=True, help="the actors_baseline executable")
    ap.add_argument("--rounds", type=int, default=7)
    ap.add_argument("--size", default="1000", choices=sorted(SIZES))
    ap.add_argument("--keep", help="keep outputs in this folder")
    ap.add_argument("--instructions", action="store_true",
                    help="instead of timing rounds, count each process's instructions once under valgrind's "
                         "callgrind: the same on a busy machine as on an idle one (about 50 times slower)")
    a = ap.parse_args()
    work = a.keep or tempfile.mkdtemp(prefix="orch_split_")
    os.makedirs(work, exist_ok=True)
    header = bench.machine()
    name, rate, fill, steps = SIZES[a.size]
    traffic = os.path.join(work, "traffic.rou.xml")
    bench.subprocess.run([a.binary, "map", "traffic", bench.MAP, "--rate", str(rate), "--fill-per-km", str(fill),
                          "--out", traffic], check=True, stdout=bench.subprocess.DEVNULL)
    d = os.path.join(work, "run")
    # The reference run: its result.json (SUMO's command line, the actors) and trace.csv
    # (their poses) drive the actors baseline.
    ref = d + "_ref"
    bench.measure(bench.orchestrator(a.binary, ref, traffic, steps, "libsumo"), ref + ".log")
    commands = {
        "bare": [a.binary, "baseline", bench.MAP, "--traffic", traffic, "--steps", str(steps), "--step",
                 "%g" % bench.STEP, "--out", d + "_bare"],
        "actors": [a.actors, os.path.join(ref, "result.json"), os.path.join(ref, "trace.csv"), str(steps),
                   d + "_actors.sumo.log"],
        "no_ctx": ["env", "ORCH_BENCH_NO_CONTEXTS=1"] + bench.orchestrator(a.binary, d + "_no_ctx", traffic, steps,
                                                                          "libsumo"),
        "orch": bench.orchestrator(a.binary, d + "_orch", traffic, steps, "libsumo"),
    }
    keys = list(commands)
    if a.instructions:
        return count_instructions(commands, keys, d, header, name, steps)
    walls = {k: [] for k in keys}
    cpus = {k: [] for k in keys}
    own = []
    for r in range(a.rounds):
        order = keys[r % len(keys):] + keys[:r % len(keys)]
        for key in order:
            wall, cpu = measure(commands[key], d + "_%s.log" % key)
            walls[key].append(wall)
            cpus[key].append(cpu)
        timing = json.load(open(os.path.join(d + "_orch", "result.json")))["timing"]
        own.append(timing["orchestrator_s"] / timing["sumo_step_s"])
        print("  round %d: %s" % (r + 1, ", ".join("%s %.2f s (CPU %.2f s)" % (k, walls[k][-1], cpus[k][-1])
                                                    for k in keys)), file=sys.stderr)
    mean, _ = bench.vehicles(os.path.join(d + "_orch", "counts.csv"))

    def ratio(times, num, den):
        each = [x / y for x, y in zip(times[num], times[den])]
        return "**%.3f** (%.2f-%.2f)" % (statistics.median(each), min(each), max(each))

    print("Machine: " + header + "; load average %.1f at the end" % os.getloadavg()[0])
    print("ALKS_Road, bench_scenario.json, %s vehicles (%.0f on average), %d steps of %g s; %d interleaved rounds, "
          "whole processes; medians of the rounds' ratios (range).\n" % (name, mean, steps, bench.STEP, a.rounds))
    print("| median | bare SUMO | same actors (libsumo loop) | orchestrator, contexts off | orchestrator |")
    print("|---|---|---|---|---|")
    print("| wall | %s |" % " | ".join("%.2f s" % statistics.median(walls[k]) for k in keys))
    print("| CPU | %s |" % " | ".join("%.2f s" % statistics.median(cpus[k]) for k in keys))
    print()
    print("| share | wall ratio | CPU ratio |")
    print("|---|---|---|")
    for label, num, den in (("SUMO simulating the scenario's vehicles: same actors / bare", "actors", "bare"),
                            ("the orchestrator's step (engine, reading, trace, metrics): contexts off / same actors",
                             "no_ctx", "actors"),
                            ("the context subscriptions: orchestrator / contexts off", "orch", "no_ctx"),
                            ("**orchestrator / same actors**", "orch", "actors"),
                            ("**orchestrator / bare SUMO**", "orch", "bare")):
        print("| %s | %s | %s |" % (label, ratio(walls, num, den), ratio(cpus, num, den)))
    print("| orchestrator's own time / SUMO's step time (result.json timing, same process) | %.1f %% (%.1f-%.1f) | |"
          % (100 * statistics.median(own), 100 * min(own), 100 * max(own)))
    print("\noutputs in " + work, file=sys.stderr)


def count_instructions(commands, keys, d, header, name, steps):
    """Instructions each process executes (valgrind's callgrind): independent of what else
    runs on the machine, so shares below the noise of timed rounds can be read off."""
    counts = {}
    for key in keys:
        log = d + "_%s.callgrind.log" % key
        command, env = commands[key], dict(os.environ)
        if command[0] == "env":  # the variable goes to the process itself, not to a traced `env`
            name_value = command[1].split("=", 1)
            env[name_value[0]] = name_value[1]
            command = command[2:]
        cmd = ["valgrind", "--tool=callgrind", "--callgrind-out-file=" + d + "_%s.callgrind" % key] + command
        measure(cmd, log, env)
        with open(log) as f:
            counts[key] = int(next(line.split(":")[1] for line in f if "Collected :" in line).replace(",", ""))
        print("  %s: %d instructions" % (key, counts[key]), file=sys.stderr)
    print("Machine: " + header)
    print("ALKS_Road, bench_scenario.json, %s vehicles, %d steps of %g s; instructions of each whole process "
          "(valgrind --tool=callgrind, one run each).\n" % (name, steps, bench.STEP))
    print("| | bare SUMO | same actors (libsumo loop) | orchestrator, contexts off | orchestrator |")
    print("|---|---|---|---|---|")
    print("| instructions | %s |" % " | ".join("%.3f G" % (counts[k] / 1e9) for k in keys))
    print()
    print("| share | instruction ratio |")
    print("|---|---|")
    for label, num, den in (("SUMO simulating the scenario's vehicles: same actors / bare", "actors", "bare"),
                            ("the orchestrator's step and start: contexts off / same actors", "no_ctx", "actors"),
                            ("the context subscriptions: orchestrator / contexts off", "orch", "no_ctx"),
                            ("**orchestrator / same actors**", "orch", "actors"),
                            ("**orchestrator / bare SUMO**", "orch", "bare")):
        print("| %s | **%.4f** |" % (label, counts[num] / counts[den]))


if __name__ == "__main__":
    main()
