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
       [--steps 400,200] [--backends libsumo,traci] [--long-road-km 40 [--long-fill 83] [--long-steps 100]
       [--only-long]] [--keep DIR]
The orchestrator runs on each backend named (traci: the process's CPU time includes its
`sumo` child's, its memory both processes' peaks). --long-road-km adds a size on ALKS_Road
lengthened to that many km (built into the work folder), for ~10,000 vehicles.
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
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
from bench import descendants, machine, status_kb, vehicles  # noqa: E402

SCENARIO = os.path.join(HERE, "bench_scenario.json")
MAP = "ALKS_Road"
STEP = 0.05
RATE = 1800


def time_v(cmd, log):
    """Runs cmd under /usr/bin/time -v: (wall s, CPU s, peak RSS MB). CPU is the process's
    and its waited-for children's (the traci backend's `sumo`); peak RSS is summed over the
    process tree below `time` (each process's own peak, VmHWM, sampled every 50 ms), since
    `time` reports only the largest single process."""
    start = time.monotonic()
    with open(log, "w") as out:
        proc = subprocess.Popen(["/usr/bin/time", "-v"] + cmd, stdout=out, stderr=subprocess.STDOUT)
    peaks, done = {}, threading.Event()

    def watch():
        while not done.is_set():
            for p in descendants(proc.pid)[1:]:  # not `time` itself
                peaks[p] = max(peaks.get(p, 0), status_kb(p, "VmHWM"))
            done.wait(0.05)

    watcher = threading.Thread(target=watch)
    watcher.start()
    code = proc.wait()
    wall = time.monotonic() - start
    done.set()
    watcher.join()
    text = open(log, errors="replace").read()
    if code not in (0, 1):
        sys.exit("failed (%d): %s\n%s" % (code, " ".join(cmd), text[-2000:]))

    def field(name):
        m = re.search(r"%s: ([0-9.]+)" % re.escape(name), text)
        return float(m.group(1)) if m else 0.0

    cpu = field("User time (seconds)") + field("System time (seconds)")
    return wall, cpu, max(sum(peaks.values()), field("Maximum resident set size (kbytes)")) / 1024


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


def long_road(binary, km, work):
    """ALKS_Road's three straight lanes lengthened to `km` km (the same waypoint spacing, lane
    offsets and build settings), built into work/maps with `orchestrator map build`; returns
    its map id. ~10,000 vehicles do not fit on the 10 km road (a lane holds ~130 cars a km
    bumper to bumper)."""
    map_id = "ALKS_Road_%dkm" % km
    folder = os.path.join(work, "maps", map_id)
    net = os.path.join(folder, map_id + ".net.xml")
    if os.path.exists(net):
        return map_id
    os.makedirs(folder, exist_ok=True)
    source = os.path.join(ROOT, "sumo_nets", MAP)
    meta = json.load(open(os.path.join(source, "map.json")))
    doc = json.load(open(os.path.join(source, meta["waypoint_file"])))
    length = km * 1000
    doc["id"], doc["mapId"] = "WayPoint_" + map_id, map_id
    for route in doc["waypoints"]:
        z = route["points"][0]["z"]
        route["points"] = [{"x": x, "y": 0, "z": z, "v": 80} for x in range(length + 1)]
    for prop in doc.get("properties", []):
        prop["index"] = min(prop["index"], length) if prop["index"] < 10000 else length
    meta.update(id=map_id, aliases=[], waypoint_file=map_id + ".waypoint.json", net_file=map_id + ".net.xml",
                description="ALKS_Road lengthened to %d km for scripts/bench/sumo_compare.py" % km)
    json.dump(doc, open(os.path.join(folder, meta["waypoint_file"]), "w"))
    json.dump(meta, open(os.path.join(folder, "map.json"), "w"), indent=2)
    subprocess.run([binary, "map", "build", folder], check=True, stdout=subprocess.DEVNULL)
    return map_id


def size(binary, fill, steps, repeat, work, map_id=MAP, backends=("libsumo", "traci")):
    scenario = SCENARIO
    if map_id != MAP:  # the same scenario on the lengthened road (its waypoint indices all exist there)
        doc = json.load(open(SCENARIO))
        doc["map_id"] = map_id
        scenario = os.path.join(work, "bench_scenario_%s.json" % map_id)
        json.dump(doc, open(scenario, "w"))
    traffic = os.path.join(work, "traffic_%s_%d.rou.xml" % (map_id, fill))
    subprocess.run([binary, "map", "traffic", map_id, "--rate", str(RATE), "--fill-per-km", str(fill), "--out", traffic],
                   check=True, stdout=subprocess.DEVNULL)
    run_dir = os.path.join(work, "run_%s_%d" % (map_id, fill))

    def run_cmd(backend, out):
        return [binary, "run", scenario, "--out", out, "-q", "--no-report", "--traffic", traffic, "--backend", backend,
                "--max-time", "%g" % (steps * STEP), "--step", "%g" % STEP]

    time_v(run_cmd(backends[0], run_dir), run_dir + ".log")
    result = json.load(open(os.path.join(run_dir, "result.json")))
    mean, _ = vehicles(os.path.join(run_dir, "counts.csv"))
    commands = {"sumo": plain_sumo(result, work, steps)}
    for backend in backends:
        commands[backend] = run_cmd(backend, run_dir + "_" + backend)
    commands["baseline"] = [binary, "baseline", map_id, "--traffic", traffic, "--steps", str(steps), "--step",
                            "%g" % STEP, "--out", os.path.join(work, "baseline_%s_%d" % (map_id, fill))]
    print("  plain sumo: %s" % " ".join(commands["sumo"]), file=sys.stderr)
    order = list(commands)
    runs = {k: [] for k in commands}
    for r in range(repeat):
        k = r % len(order)
        for key in order[k:] + order[:k]:  # rotate who goes first
            runs[key].append(time_v(commands[key], os.path.join(work, "%s_%s_%d.log" % (key, map_id, fill))))
        print("  ~%.0f vehicles, round %d: %s" % (mean, r + 1, ", ".join(
            "%s %.2f s wall %.2f s CPU %.0f MB" % (k, v[-1][0], v[-1][1], v[-1][2]) for k, v in runs.items())),
              file=sys.stderr)
    return mean, steps, map_id, runs


def pair_ratio(num, den, index):
    each = sorted(a[index] / b[index] for a, b in zip(num, den))
    return "**%.3f** (%.2f-%.2f)" % (statistics.median(each), each[0], each[-1])


NAMES = {"libsumo": "orchestrator run, libsumo", "traci": "orchestrator run, traci (its `sumo` child included)",
         "baseline": "orchestrator baseline (libsumo, no scenario)"}


def table(rows, repeat):
    lines = ["| map, vehicles (mean), steps | process | wall | CPU | peak RSS | / sumo, wall | / sumo, CPU | "
             "/ sumo, memory |", "|---|---|---|---|---|---|---|---|"]
    for mean, steps, map_id, runs in rows:
        def cell(key):
            v = runs[key]
            return "%.2f s | %.2f s | %.0f MB" % (statistics.median(x[0] for x in v), statistics.median(x[1] for x in v),
                                                 max(x[2] for x in v))
        lines.append("| %s, %.0f, %d | `sumo` | %s | | | |" % (map_id, mean, steps, cell("sumo")))
        for key in runs:
            if key == "sumo":
                continue
            mem = max(x[2] for x in runs[key]) / max(x[2] for x in runs["sumo"])
            lines.append("| | %s | %s | %s | %s | %.2f |" % (NAMES[key], cell(key), pair_ratio(runs[key], runs["sumo"], 0),
                                                         pair_ratio(runs[key], runs["sumo"], 1), mem))
    return "\n".join(lines) + "\n\n%d rounds per size; times are medians over the rounds, ratios the median " \
        "(range) of the rounds' own ratios against that round's `sumo`; peak RSS summed over the process tree." % repeat


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--binary", default=os.path.join(ROOT, "build", "bin", "orchestrator"))
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--sizes", default="33,100", help="fill-per-km values (33: ~1,000 vehicles, 100: ~3,000)")
    ap.add_argument("--steps", default="400,200", help="steps per size")
    ap.add_argument("--keep", help="work folder to keep (default: a temporary one)")
    ap.add_argument("--long-road-km", type=int, default=0,
                    help="also a size on ALKS_Road lengthened to this many km (with --long-fill, --long-steps)")
    ap.add_argument("--long-fill", type=int, default=83, help="fill-per-km on the long road (83 on 40 km: ~10,000)")
    ap.add_argument("--long-steps", type=int, default=100)
    ap.add_argument("--only-long", action="store_true", help="only the long road's size")
    ap.add_argument("--backends", default="libsumo,traci", help="orchestrator run backends to time")
    a = ap.parse_args()
    os.environ.setdefault("SUMO_HOME", "/usr/share/sumo")
    work = a.keep or tempfile.mkdtemp(prefix="orch_sumo_compare_")
    os.makedirs(work, exist_ok=True)
    header = machine()
    print(header, file=sys.stderr)
    backends = tuple(a.backends.split(","))
    rows = [] if a.only_long else [size(a.binary, int(f), int(s), a.repeat, work, backends=backends)
                                   for f, s in zip(a.sizes.split(","), a.steps.split(","))]
    if a.long_road_km:
        map_id = long_road(a.binary, a.long_road_km, work)
        maps = os.path.join(work, "maps")
        os.environ["ORCH_MAPS"] = maps + os.pathsep + os.environ["ORCH_MAPS"] if os.environ.get("ORCH_MAPS") else maps
        rows.append(size(a.binary, a.long_fill, a.long_steps, a.repeat, work, map_id, backends))
    print("Machine: %s; load average %.1f at the end" % (header, os.getloadavg()[0]))
    print(table(rows, a.repeat))


if __name__ == "__main__":
    main()
