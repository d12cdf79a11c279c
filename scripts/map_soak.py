#!/usr/bin/env python3
"""Soak of the map builder's property test (docs/maps.md, "Generated maps"): runs the
property test (tests/integration/test_generated_city_maps.cpp) on any number of seeds of
scripts/city_waypoints.py, one test process per seed, and prints the failing seeds by kind
with the command that reproduces each. A failing seed, once fixed, goes into the test's
fixed seed set as a regression fixture.

Usage: scripts/map_soak.py [--seeds 1-200] [--jobs 2] [--build build] [--scripted]
           --scripted: also drive every route by an orchestrator-scripted actor
           (tests/integration/test_generated_city_scripted.cpp) on every seed
       scripts/map_soak.py --measure [--scales 1,2,4,10] [--build build]
           times `orchestrator map build` on generated maps of growing size (figures for docs/maps.md)
Exit status 1 when any seed fails."""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

KINDS = [  # (kind, pattern in the test's output), first match wins
    ("netconvert failed", r"netconvert failed"),
    ("build refused the map", r"map build refused the map"),
    ("route not one connected path", r"cannot be driven as one connected path"),
    ("waypoint off its lane", r"m from lane"),
    # the scripted test (--scripted): the assertion's own text, not the run log it prints
    ("scripted run did not reach its end", r'log\.find\("ending scene 2"\)'),
    ("scripted actor off its route's lanes", r'log\.find\("SUMO placed actor"\)'),
    ("scripted actor not at its last waypoint", r"the actor of route"),
    ("lanes not connected in drawn order", r" -> "),
    ("degenerate lane", r": lane .* Expected: \(l.length\)"),
    ("vehicle teleported or did not arrive", r"d\.(teleports|running|inserted|loaded)"),
    ("rebuild changed the net", r"rebuilding changed the net"),
    ("generator failed", r"city_waypoints.py failed"),
]


def parse_seeds(text):
    out = []
    for item in text.split(","):
        if "-" in item[1:]:
            a, b = item.split("-", 1)
            out += range(int(a), int(b) + 1)
        else:
            out.append(int(item))
    return out


def run_seed(binary, seed, scripted=False):
    env = dict(os.environ, ORCH_CITY_SEEDS=str(seed))
    t0 = time.monotonic()
    tests = "Seeds/GeneratedCityMaps.*" + (":Scripted/ScriptedCityDrives.*" if scripted else "")
    p = subprocess.run([binary, "--gtest_filter=" + tests], env=env, cwd=ROOT,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    elapsed = time.monotonic() - t0
    if p.returncode == 0:
        return seed, None, elapsed, ""
    kind = "other"
    for k, pattern in KINDS:
        if re.search(pattern, p.stdout):
            kind = k
            break
    return seed, kind, elapsed, p.stdout


def soak(args):
    binary = str(Path(args.build) / "tests" / "integration_tests")
    seeds = parse_seeds(args.seeds)
    failures = {}
    times = []
    with ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for seed, kind, elapsed, out in pool.map(lambda s: run_seed(binary, s, args.scripted), seeds):
            times.append(elapsed)
            status = "ok" if kind is None else "FAIL: " + kind
            print(f"seed {seed}: {status} ({elapsed:.1f} s)", flush=True)
            if kind:
                failures.setdefault(kind, []).append(seed)
                if args.verbose:
                    print(out)
    failed = sum(len(v) for v in failures.values())
    print(f"\n{len(seeds)} seeds tried, {len(seeds) - failed} passed, {failed} failed; "
          f"{sum(times):.0f} s in all, {max(times):.1f} s the slowest")
    for kind, ss in sorted(failures.items()):
        print(f"  {kind}: {len(ss)} ({', '.join(map(str, ss))})")
    for ss in failures.values():
        for s in ss:
            print(f"  reproduce seed {s}: ORCH_CITY_SEEDS={s} {binary} --gtest_filter='Seeds/GeneratedCityMaps.*'\n"
                  f"      or: python3 scripts/city_waypoints.py --seed {s} --out /tmp/city_{s}.waypoint.json && "
                  f"{args.build}/bin/orchestrator map build --waypoints /tmp/city_{s}.waypoint.json --out /tmp/city_{s}")
    return 1 if failed else 0


class _Found:  # the shape of a regex match, for counts read from a net
    def __init__(self, *groups):
        self.groups = groups

    def group(self, i):
        return str(self.groups[i - 1])


def net_counts(net):
    """Junctions (not dead ends or internal), normal edges and their lanes of a SUMO net."""
    import xml.etree.ElementTree as ET
    root = ET.parse(net).getroot()
    junctions = sum(1 for j in root.iter("junction") if j.get("type") not in ("internal", "dead_end"))
    edges = [e for e in root.iter("edge") if e.get("function") != "internal"]
    return _Found(junctions), _Found(len(edges), sum(len(e.findall("lane")) for e in edges))


def measure(args):
    orch = str(Path(args.build) / "bin" / "orchestrator")
    print(f"{'scale':>5} {'routes':>6} {'points':>7} {'junctions':>9} {'edges':>5} {'lanes':>5} {'net KB':>7} "
          f"{'build s':>7}  result")
    for scale in [int(s) for s in args.scales.split(",")]:
        with tempfile.TemporaryDirectory() as tmp:
            wp = Path(tmp) / "city.waypoint.json"
            subprocess.run([sys.executable, str(ROOT / "scripts/city_waypoints.py"), "--seed", str(args.seed),
                            "--scale", str(scale), "--out", str(wp)], check=True)
            doc = json.loads(wp.read_text())
            points = sum(len(r["points"]) for r in doc["waypoints"])
            t0 = time.monotonic()
            p = subprocess.run([orch, "map", "build", "--waypoints", str(wp), "--out", str(Path(tmp) / "map")],
                               stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
            elapsed = time.monotonic() - t0
            m = re.search(r"(\d+) junctions?", p.stdout)
            e = re.search(r"(\d+) edges \(.*?\), (\d+) lanes", p.stdout)
            net = list((Path(tmp) / "map").glob("*.net.xml"))
            size = net[0].stat().st_size / 1024 if net else 0
            if net and not (m and e):  # a net written, then a check failed: count from the net itself
                m, e = net_counts(net[0])
            print(f"{scale:>5} {len(doc['waypoints']):>6} {points:>7} {m.group(1) if m else '-':>9} "
                  f"{e.group(1) if e else '-':>5} {e.group(2) if e else '-':>5} {size:>7.0f} {elapsed:>7.1f}  "
                  f"{'ok' if p.returncode == 0 else 'exit %d' % p.returncode}", flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seeds", default="1-200")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--build", default="build")
    ap.add_argument("--verbose", action="store_true", help="print the test output of failing seeds")
    ap.add_argument("--scripted", action="store_true",
                    help="also drive every route by an orchestrator-scripted actor (orchestrator run on libsumo)")
    ap.add_argument("--measure", action="store_true")
    ap.add_argument("--scales", default="1,2,3,4")
    ap.add_argument("--seed", type=int, default=1, help="--measure: the seed of every size")
    args = ap.parse_args()
    sys.exit(measure(args) if args.measure else soak(args))


if __name__ == "__main__":
    main()
