#!/usr/bin/env python3
"""How many runs `orchestrator search` needs against uniform random sampling (docs/search.md).

For each case: (a) a dense grid of real runs is the ground truth (`search --method grid`),
(b) uniform random sampling, (c) the search, and prints how many runs each needs to
 - falsification: find a run within TOL of the grid's minimum of the objective;
 - boundary: classify the space with at most FRACTION of it wrong (against the grid's runs).
Random sampling's figure for the minimum is exact from the grid: with a fraction p of the
space within TOL, a uniform sample needs 1/p runs on average (median ln 2 / p). For the
boundary it is measured: real `search --method random` runs, classified by a Gaussian process
after every --jobs runs. Everything runs in --work (kept; a finished folder is reused).

  scripts/bench/search_vs_random.py --orchestrator build/bin/orchestrator --work /tmp/search-bench
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

CASES = [
    {
        "name": "lead brake (JSON logical): lead.speed x lead.decel",
        "input": "scenarios/nightly/logical_9202dd94-2666-4583-a45c-f8396b848ae9.json",
        "args": ["--set", "lead.brake_time=30", "--max-time", "45"],
        "objective": "min_ttc", "tolerance": 0.02, "boundary": "verdict", "grid": 225,
    },
    {
        "name": "OSC-ALKS 4.4.1 cut-in (variation): dx0 x relative speed",
        "input": "scenarios/openscenario/search/alks_4_4_1_cut_in_variation.xosc",
        "args": [],
        "objective": "min_ttc", "tolerance": 0.05, "boundary": None, "grid": 225,
    },
]


def search(exe, work, name, case, extra):
    out = os.path.join(work, name)
    done = os.path.join(out, "search.json")
    if os.path.exists(done) and json.load(open(done)).get("finished"):
        return json.load(open(done))
    if os.path.exists(out):
        subprocess.run(["rm", "-rf", out], check=True)
    cmd = [exe, "search", os.path.join(ROOT, case["input"]), "--out", out] + case["args"] + extra
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    return json.load(open(done))


def runs_of(s):
    return [p for it in s["iterations"] for p in it["points"]]


def runs_to_minimum(s, target):
    for i, r in enumerate(runs_of(s)):
        if r["objective"] is not None and r["objective"] <= target:
            return i + 1
    return None


def truth_labels(grid):
    return [(r["unit"], r["pass"]) for r in runs_of(grid)]


def misclassified(boundary, truth):
    levels, keys = boundary["levels"], boundary["pass"]
    wrong = 0
    for unit, ok in truth:
        i = [min(levels - 1, max(0, round(u * (levels - 1)))) for u in unit]
        index = 0
        for v in i:
            index = index * levels + v
        wrong += (keys[index] == "1") != ok
    return wrong / len(truth)


def iteration_runs_to_minimum(s, target):
    """Runs until the end of the iteration that found it: what --jobs parallel runs cost."""
    for it in s["iterations"]:
        if any(r["objective"] is not None and r["objective"] <= target for r in it["points"]):
            return it["runs_so_far"]
    return None


def runs_to_boundary(s, truth, fraction):
    for it in s["iterations"]:
        if "boundary" in it and misclassified(it["boundary"], truth) <= fraction:
            return it["runs_so_far"]
    return None


def runs_to_stay_below(s, truth, fraction):
    """Runs after which the estimate stays within `fraction` for the rest of the search: what a
    user, who does not know the truth, can rely on (refinement can make it worse for a while)."""
    errors = [(it["runs_so_far"], misclassified(it["boundary"], truth)) for it in s["iterations"] if "boundary" in it]
    for i, (runs, _) in enumerate(errors):
        if all(m <= fraction for _, m in errors[i:]):
            return runs
    return None


def fmt(v, budget):
    return str(v) if v is not None else f">{budget}"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--orchestrator", default=os.path.join(ROOT, "build/bin/orchestrator"))
    ap.add_argument("--work", default="/tmp/search-bench")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--budget", type=int, default=40, help="search budget (falsification)")
    ap.add_argument("--boundary-budget", type=int, default=150)
    ap.add_argument("--fraction", type=float, default=0.05, help="boundary: misclassified fraction to reach")
    ap.add_argument("--no-random-boundary", action="store_true",
                    help="skip random sampling's boundary runs (the longest part: seeds x budget runs)")
    a = ap.parse_args()
    exe = os.path.abspath(a.orchestrator)
    os.makedirs(a.work, exist_ok=True)
    j = ["--jobs", str(a.jobs)]
    for n, case in enumerate(CASES):
        print(f"\n== {case['name']}")
        modes = ["--objective", case["objective"]] + (["--boundary", case["boundary"]] if case["boundary"] else ["--minimize"])
        grid = search(exe, a.work, f"case{n}_grid", case, modes + ["--method", "grid", "--budget", str(case["grid"])] + j)
        values = [r["objective"] for r in runs_of(grid) if r["objective"] is not None]
        best = min(values)
        target = best + case["tolerance"]
        p = sum(v <= target for v in values) / len(runs_of(grid))
        print(f"ground truth: {len(runs_of(grid))}-run grid, min {case['objective']} = {best:.4g} "
              f"(range {best:.4g}..{max(values):.4g}); tolerance {case['tolerance']}: {100 * p:.1f} % of the space")
        random_mean = 1 / p if p > 0 else math.inf
        found, per_iteration = [], []
        for seed in range(1, a.seeds + 1):
            s = search(exe, a.work, f"case{n}_min_seed{seed}", case,
                       ["--objective", case["objective"], "--minimize", "--budget", str(a.budget), "--seed", str(seed)] + j)
            found.append(runs_to_minimum(s, target))
            per_iteration.append(iteration_runs_to_minimum(s, target))
        ok = [f for f in found if f is not None]
        mean = statistics.mean(ok) if len(ok) == len(found) else None
        print(f"minimum within {case['tolerance']}: random sampling needs {random_mean:.1f} runs on average "
              f"(median {math.log(2) / p:.1f}); the search needed {[fmt(f, a.budget) for f in found]} (seeds 1..{a.seeds})"
              + (f", mean {mean:.1f}: {random_mean / mean:.1f}x fewer" if mean else "")
              + f"; counted to the end of the iteration that found it: {[fmt(f, a.budget) for f in per_iteration]}")
        if not case["boundary"]:
            continue
        truth = truth_labels(grid)
        fail = sum(not ok for _, ok in truth) / len(truth)
        print(f"boundary of {case['boundary']}: the grid fails over {100 * fail:.1f} % of the space")
        s = search(exe, a.work, f"case{n}_boundary", case,
                   ["--objective", case["objective"], "--boundary", case["boundary"], "--budget", str(a.boundary_budget),
                    "--resolution", str(1 / 32)] + j)
        fractions = [a.fraction] + [f for f in (0.03, 0.02, 0.01) if f < a.fraction]
        final = [it for it in s["iterations"] if "boundary" in it][-1]
        print(f"  sparse-grid search: runs to <= {[f'{100 * f:g} %' for f in fractions]} misclassified: "
              f"{[fmt(runs_to_boundary(s, truth, f), a.boundary_budget) for f in fractions]} "
              f"(after all {len(runs_of(s))} runs: {100 * misclassified(final['boundary'], truth):.1f} %); "
              f"and stays there from: {[fmt(runs_to_stay_below(s, truth, f), a.boundary_budget) for f in fractions]}")
        if a.no_random_boundary:
            continue
        rand = []
        for seed in range(1, a.seeds + 1):
            r = search(exe, a.work, f"case{n}_boundary_random_seed{seed}", case,
                       ["--objective", case["objective"], "--boundary", case["boundary"], "--method", "random",
                        "--budget", str(a.boundary_budget), "--seed", str(seed)] + j)
            last = [it for it in r["iterations"] if "boundary" in it][-1]
            rand.append(([runs_to_boundary(r, truth, f) for f in fractions], misclassified(last["boundary"], truth),
                         [runs_to_stay_below(r, truth, f) for f in fractions]))
        for k, f in enumerate(fractions):
            print(f"  uniform random (GP classifier), runs to <= {100 * f:g} %: "
                  f"{[fmt(x[k], a.boundary_budget) for x, _, _ in rand]}, stays there from "
                  f"{[fmt(st[k], a.boundary_budget) for _, _, st in rand]} (seeds 1..{a.seeds})")
        print(f"  uniform random after {a.boundary_budget} runs: {[f'{100 * m:.1f} %' for _, m, _ in rand]}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
