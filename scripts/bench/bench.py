#!/usr/bin/python3
"""The orchestrator's speed against bare SUMO, itself on the other backend, and a plain
Python traci loop, on the same network, traffic, seed, step length and number of steps.
Prints a Markdown table (docs/performance.md). See scripts/bench/README.md.

Usage: scripts/bench/run.sh [--quick] [--hour]   (builds first; or call this with --binary)
"""
import argparse
import json
import os
import platform
import subprocess
import sys
import tempfile
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
SCENARIO = os.path.join(HERE, "bench_scenario.json")
# The ego parks; the traffic flows past it until the ending scene at 3600 s.
HOUR_SCENARIO = os.path.join(HERE, "hour_scenario.json")
PYTHON_LOOP = os.path.join(HERE, "python_loop.py")
MAP = "ALKS_Road"  # 10 km, 3 lanes, 41 edges: room for 3,000 vehicles
WAYPOINTS = os.path.join(ROOT, "sumo_nets", MAP, "ALKS.Road.waypoint.json")
STEP = 0.05

# name, vehicles/hour/lane entering, vehicles per km and lane at the start, steps
SIZES = [("~200", 300, 6.5, 600), ("~1,000", 1800, 33, 400), ("~3,000", 1800, 100, 200)]


def descendants(pid):
    """pid and every process below it (Linux /proc)."""
    children = {}
    for name in os.listdir("/proc"):
        if name.isdigit():
            try:
                with open("/proc/%s/stat" % name) as f:
                    ppid = int(f.read().rsplit(")", 1)[1].split()[1])
                children.setdefault(ppid, []).append(int(name))
            except (OSError, IndexError, ValueError):
                pass
    out, todo = [], [pid]
    while todo:
        p = todo.pop()
        out.append(p)
        todo.extend(children.get(p, []))
    return out


def status_kb(pid, key):
    try:
        with open("/proc/%d/status" % pid) as f:
            for line in f:
                if line.startswith(key + ":"):
                    return int(line.split()[1])
    except OSError:
        pass
    return 0


def measure(cmd, log):
    """Runs cmd; returns (wall s, peak RSS in MB summed over its process tree, samples of
    the tree's RSS over time [(s, MB)])."""
    start = time.monotonic()
    with open(log, "w") as out:
        proc = subprocess.Popen(cmd, stdout=out, stderr=subprocess.STDOUT)
    peaks, samples, done = {}, [], threading.Event()

    def watch():
        while not done.is_set():
            rss = 0
            for p in descendants(proc.pid):
                peaks[p] = max(peaks.get(p, 0), status_kb(p, "VmHWM"))
                rss += status_kb(p, "VmRSS")
            samples.append((time.monotonic() - start, rss / 1024))
            done.wait(0.1)

    watcher = threading.Thread(target=watch)
    watcher.start()
    code = proc.wait()
    wall = time.monotonic() - start
    done.set()
    watcher.join()
    if code not in (0, 1):
        sys.exit("failed (%d): %s\n%s" % (code, " ".join(cmd), open(log).read()[-2000:]))
    return wall, sum(peaks.values()) / 1024, samples


def orchestrator(binary, out, traffic, steps, backend):
    return [binary, "run", SCENARIO, "--out", out, "-q", "--traffic", traffic, "--backend", backend,
            "--max-time", "%g" % (steps * STEP), "--step", "%g" % STEP]


def machine():
    cpu = "unknown CPU"
    with open("/proc/cpuinfo") as f:
        for line in f:
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    load = os.getloadavg()[0]
    with open("/proc/meminfo") as f:
        mem = int(f.readline().split()[1]) / 1024 / 1024
    sumo = subprocess.run(["sumo", "--version"], capture_output=True, text=True).stdout.splitlines()[0]
    return "%s, %d cores, %.0f GB RAM, %s, %s; load average %.1f at the start" % (
        cpu, os.cpu_count(), mem, platform.platform(), sumo, load)


def vehicles(counts_csv):
    with open(counts_csv) as f:
        rows = [line.split(",") for line in f.read().splitlines()[1:]]
    values = [int(r[1]) for r in rows]
    return sum(values) / len(values), values[-1]


def bench(binary, quick, repeat, work):
    """Each size: `repeat` rounds of bare SUMO, the orchestrator on both backends and the
    subscribing Python loop, interleaved so that a slow spell of the machine hits all of
    them, and the best time of each is kept: on a shared VM the same run's CPU time varies
    by 15 % and more from one run to the next. The polling loop (several times slower) runs
    once."""
    rows = []
    for name, rate, fill, steps in SIZES:
        if quick:
            steps = max(40, steps // 5)
        traffic = os.path.join(work, "traffic_%d.rou.xml" % fill)
        subprocess.run([binary, "map", "traffic", MAP, "--rate", str(rate), "--fill-per-km", str(fill),
                        "--out", traffic], check=True, stdout=subprocess.DEVNULL)
        d = os.path.join(work, "n%d" % fill)

        def python_loop(mode):
            return ["/usr/bin/python3", PYTHON_LOOP, "--result", os.path.join(d + "_libsumo", "result.json"),
                    "--waypoints", WAYPOINTS, "--steps", str(steps), "--out", d + "_py_" + mode, "--neighbours", mode]

        commands = {
            "bare": [binary, "baseline", MAP, "--traffic", traffic, "--steps", str(steps), "--step", "%g" % STEP,
                     "--out", d + "_bare"],
            "libsumo": orchestrator(binary, d + "_libsumo", traffic, steps, "libsumo"),
            "traci": orchestrator(binary, d + "_traci", traffic, steps, "traci"),
            "py_subscribe": python_loop("subscribe"),
        }
        runs = {key: [] for key in list(commands) + ["py_poll"]}
        own = []  # the orchestrator's own time per step over SUMO's step time, in one process
        for _ in range(repeat):
            for key, cmd in commands.items():
                runs[key].append(measure(cmd, d + "_%s.log" % key))
                if key == "libsumo":
                    timing = json.load(open(os.path.join(d + "_libsumo", "result.json")))["timing"]
                    own.append(timing["orchestrator_s"] / timing["sumo_step_s"])
            print("  %s round: %s" % (name, ", ".join("%s %.2f s" % (k, v[-1][0]) for k, v in runs.items() if v)),
                  file=sys.stderr)
        runs["py_poll"].append(measure(python_loop("poll"), d + "_py_poll.log"))
        mean, last = vehicles(os.path.join(d + "_libsumo", "counts.csv"))
        rows.append((name, mean, steps, runs, own))
        print("measured %s: %.0f vehicles on average over %d steps" % (name, mean, steps), file=sys.stderr)
    return rows


def table(rows):
    lines = [
        "| vehicles (mean) | steps | bare SUMO (libsumo) | orchestrator libsumo | orch / bare | orchestrator traci "
        "| traci / libsumo | Python traci loop, polling | loop / orch | Python traci loop, subscriptions "
        "| loop / orch | orchestrator's own time / SUMO's step time (libsumo, same process) |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for name, mean, steps, r, own in rows:
        wall = {k: min(m[0] for m in v) for k, v in r.items()}
        rss = {k: max(m[1] for m in v) for k, v in r.items()}

        def cell(key):
            return "%.2f s, %.0f MB" % (wall[key], rss[key])

        def ratio(num, den):
            """Ratio of the best times, and the range of the rounds' own ratios."""
            text = "**%.2f**" % (wall[num] / wall[den])
            if len(r[num]) > 1 and len(r[num]) == len(r[den]):
                each = [a[0] / b[0] for a, b in zip(r[num], r[den])]
                text += " (%.2f-%.2f)" % (min(each), max(each))
            return text

        lines.append("| %s (%.0f) | %d | %s | %s | %s | %s | %s | %s | %s | %s | %s | %.1f %% (%.1f-%.1f) |" % (
            name, mean, steps, cell("bare"), cell("libsumo"), ratio("libsumo", "bare"), cell("traci"),
            ratio("traci", "libsumo"), cell("py_poll"), "**%.2f**" % (wall["py_poll"] / wall["libsumo"]),
            cell("py_subscribe"), ratio("py_subscribe", "libsumo"), 100 * sorted(own)[len(own) // 2], 100 * min(own),
            100 * max(own)))
    return "\n".join(lines)


def hour(binary, work):
    """One hour simulated, dense traffic: the orchestrator's memory at the start and end."""
    d = os.path.join(work, "hour")
    wall, peak, samples = measure([binary, "run", HOUR_SCENARIO, "--out", d, "-q", "--traffic", "dense",
                                   "--step", "0.1"], d + ".log")
    result = json.load(open(os.path.join(d, "result.json")))
    early = [mb for t, mb in samples if t > 0.05 * wall][:10]
    late = [mb for t, mb in samples if t > 0.95 * wall][-10:]
    mean, last = vehicles(os.path.join(d, "counts.csv"))
    return ("hour_scenario.json, %.0f s simulated (%s, step 0.1 s, %d steps, dense traffic: %.0f vehicles on average, "
            "%d at the end) in %.0f s wall: resident memory %.1f MB at 5%% of the run, %.1f MB at the end (peak %.1f MB)." % (
                result["sim_time"], result["verdict"], result["steps"], mean, last, wall, early[0] if early else 0,
                late[-1] if late else 0, peak))


URBAN_SCENARIO = os.path.join(ROOT, "scenarios", "urban_loop_follow.json")


def urban(binary, work, repeat, steps=2000):
    """The junction map with dense traffic: urban_loop_follow.json (the ego and a follower
    round the block through three junctions) against bare SUMO on the same net and traffic,
    interleaved rounds, best times."""
    runs = {"bare": [], "orch": []}
    for _ in range(repeat):
        runs["bare"].append(measure([binary, "baseline", "urban", "--traffic", "dense", "--steps", str(steps),
                                     "--step", "%g" % STEP, "--out", os.path.join(work, "urban_bare")],
                                    os.path.join(work, "urban_bare.log")))
        runs["orch"].append(measure([binary, "run", URBAN_SCENARIO, "--out", os.path.join(work, "urban_orch"), "-q",
                                     "--traffic", "dense", "--max-time", "%g" % (steps * STEP)],
                                    os.path.join(work, "urban_orch.log")))
    mean, _ = vehicles(os.path.join(work, "urban_orch", "counts.csv"))
    best = {k: min(m[0] for m in v) for k, v in runs.items()}
    each = [a[0] / b[0] for a, b in zip(runs["orch"], runs["bare"])]
    return ("| urban (junctions), dense (%.0f) | %d | %.2f s | %.2f s | **%.2f** (%.2f-%.2f) |" % (
        mean, steps, best["bare"], best["orch"], best["orch"] / best["bare"], min(each), max(each)))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--binary", default=os.path.join(ROOT, "build-bench", "bin", "orchestrator"))
    ap.add_argument("--quick", action="store_true", help="a fifth of the steps (a smoke test)")
    ap.add_argument("--repeat", type=int, default=5, help="rounds per size; the table shows the best (default 5)")
    ap.add_argument("--hour", action="store_true", help="also the one-hour dense run (memory; ~10 min)")
    ap.add_argument("--hour-only", action="store_true", help="only the one-hour run")
    ap.add_argument("--keep", help="keep outputs in this folder")
    ap.add_argument("--urban-only", action="store_true", help="only the junction map row")
    a = ap.parse_args()
    work = a.keep or tempfile.mkdtemp(prefix="orch_bench_")
    os.makedirs(work, exist_ok=True)
    header = machine()
    if a.hour_only:
        print("Machine: " + header)
        print(hour(a.binary, work))
        return
    urban_header = ("| map, traffic (vehicles, mean) | steps | bare SUMO (libsumo) | orchestrator libsumo | orch / bare |\n"
                    "|---|---|---|---|---|")
    if a.urban_only:
        print("Machine: " + header)
        print(urban_header)
        print(urban(a.binary, work, max(1, a.repeat)))
        return
    rows = bench(a.binary, a.quick, max(1, a.repeat), work)
    print("Machine: " + header)
    print("Map %s, bench_scenario.json (ego + 3 scripted cars; scene conditions, a collision stop condition and "
          "speed, relative-speed, blinker and lane-change actions active), step %g s, seed 42. Wall time of each "
          "process from start to exit (loading included), the best of %d interleaved rounds (the polling loop: "
          "one round); ratios of the best times, with the range of the rounds' own ratios in brackets; peak RSS "
          "summed over its processes (orchestrator + sumo on traci; Python + sumo for the loops), the largest "
          "of the rounds. Last column: result.json's timing of the libsumo runs, the orchestrator's own time "
          "in the stepping loop (reading, engine, commands, trace) over the time inside SUMO's steps, median "
          "and range of the rounds: both measured in one process at the same moments, so the machine's "
          "changing speed cancels out.\n" % (MAP, STEP, max(1, a.repeat)))
    print(table(rows))
    print()
    print(urban_header)
    print(urban(a.binary, work, max(1, a.repeat)))
    if a.hour:
        print()
        print(hour(a.binary, work))
    print("\noutputs in " + work, file=sys.stderr)


if __name__ == "__main__":
    main()
