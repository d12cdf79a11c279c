#!/usr/bin/env python3
"""How many runs `orchestrator search` needs against uniform random sampling (docs/search.md).

For each case: (a) a dense grid of real runs is the ground truth (`search --method grid`),
(b) uniform random sampling, (c) the search, and prints how many runs each needs to
 - falsification: find a run within TOL of the grid's minimum of the objective;
 - boundary: classify the space with at most FRACTION of it wrong (against the grid's runs).
Random sampling is measured with real `search --method random` runs (uniform in the box):
for the minimum, with a fraction p of its runs within TOL (seeds pooled), it needs 1/p runs
on average; for the boundary, its runs are classified by a Gaussian process after every
--jobs runs. Everything runs in --work (kept; a finished folder is reused).

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
        "objective": "min_ttc", "tolerances": [0.002, 0.005, 0.01, 0.02, 0.05], "boundary": "verdict", "grid": 225,
    },
    {
        "name": "OSC-ALKS 4.4.1 cut-in (variation): dx0 x relative speed",
        "input": "scenarios/openscenario/search/alks_4_4_1_cut_in_variation.xosc",
        "args": [],
        "objective": "min_ttc", "tolerances": [0.002, 0.05], "boundary": None, "grid": 225,
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


def random_folders(exe, a, n, case, j):
    """Uniform random sampling's real runs for a case: the boundary's random runs where the case
    has a boundary (they record the objective too), otherwise --method random --minimize runs."""
    if case["boundary"] and not a.no_random_boundary:
        return [search(exe, a.work, f"case{n}_boundary_random_seed{seed}", case,
                       ["--objective", case["objective"], "--boundary", case["boundary"], "--method", "random",
                        "--budget", str(a.boundary_budget), "--seed", str(seed)] + j)
                for seed in range(1, a.seeds + 1)]
    return [search(exe, a.work, f"case{n}_min_random_seed{seed}", case,
                   ["--objective", case["objective"], "--minimize", "--method", "random",
                    "--budget", str(a.random_budget), "--seed", str(seed)] + j)
            for seed in range(1, a.seeds + 1)]


def ratio(random_mean, search_mean, sampled):
    """Random sampling's runs over the search's; a lower bound when no random run got there."""
    if math.isinf(random_mean):
        return f"more than {sampled / search_mean:.0f}x"
    return f"{random_mean / search_mean:.1f}x"


def print_minimum(case, grid, searches, randoms, a):
    values = [r["objective"] for r in runs_of(grid) if r["objective"] is not None]
    best = min(values)
    print(f"ground truth: {len(runs_of(grid))}-run grid, min {case['objective']} = {best:.4g} "
          f"(range {best:.4g}..{max(values):.4g})")
    sampled = [r["objective"] for s in randoms for r in runs_of(s)]
    # Random sampling's runs to the goal: 1/p for the fraction p of the box within the
    # tolerance, measured on its own uniform runs (all seeds pooled). The grid's fraction is
    # printed beside it: it overstates p when the minimum lies on a face of the box, where a
    # grid puts a whole row of points and a uniform sample almost none.
    for tolerance in case["tolerances"]:
        target = best + tolerance
        hits = sum(v is not None and v <= target for v in sampled)
        p_grid = sum(v <= target for v in values) / len(runs_of(grid))
        random_mean = len(sampled) / hits if hits else math.inf
        average = f"{random_mean:.1f} runs on average" if hits else f"more than {len(sampled)} runs on average"
        first = [runs_to_minimum(s, target) for s in randoms]
        found = [runs_to_minimum(s, target) for s in searches]
        per_iteration = [iteration_runs_to_minimum(s, target) for s in searches]
        mean = statistics.mean(found) if None not in found else None
        print(f"minimum within {tolerance}: uniform random sampling {hits} of {len(sampled)} runs "
              f"({100 * hits / len(sampled):.2f} %; the grid {100 * p_grid:.1f} %): {average}, "
              f"its own seeds first at {[fmt(f, len(runs_of(s))) for f, s in zip(first, randoms)]}; "
              f"the search needed {[fmt(f, a.budget) for f in found]} (seeds 1..{a.seeds})"
              + (f", mean {mean:.1f}: {ratio(random_mean, mean, len(sampled))} fewer" if mean else "")
              + f"; to the end of the iteration that found it: {[fmt(f, a.budget) for f in per_iteration]}")


def print_boundary(exe, case, n, grid, randoms, a, j):
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
        return
    for f in fractions:
        print(f"  uniform random (GP classifier), runs to <= {100 * f:g} %: "
              f"{[fmt(runs_to_boundary(r, truth, f), len(runs_of(r))) for r in randoms]}, stays there from "
              f"{[fmt(runs_to_stay_below(r, truth, f), len(runs_of(r))) for r in randoms]} (seeds 1..{a.seeds})")
    lasts = [[it for it in r["iterations"] if "boundary" in it][-1] for r in randoms]
    after = [f"{100 * misclassified(last['boundary'], truth):.1f} %" for last in lasts]
    print(f"  uniform random after {[len(runs_of(r)) for r in randoms]} runs: {after}")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--orchestrator", default=os.path.join(ROOT, "build/bin/orchestrator"))
    ap.add_argument("--work", default="/tmp/search-bench")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--budget", type=int, default=40, help="search budget (falsification)")
    ap.add_argument("--boundary-budget", type=int, default=150,
                    help="the boundary search's budget, and random sampling's runs per seed where a case has a boundary")
    ap.add_argument("--random-budget", type=int, default=100,
                    help="random sampling's runs per seed for the minimum of a case without a boundary")
    ap.add_argument("--fraction", type=float, default=0.05, help="boundary: misclassified fraction to reach")
    ap.add_argument("--no-random-boundary", action="store_true",
                    help="skip random sampling's boundary runs (the longest part: seeds x budget runs); "
                         "the minimum's random runs are then --random-budget runs of --method random --minimize")
    a = ap.parse_args()
    exe = os.path.abspath(a.orchestrator)
    os.makedirs(a.work, exist_ok=True)
    j = ["--jobs", str(a.jobs)]
    for n, case in enumerate(CASES):
        print(f"\n== {case['name']}")
        modes = ["--objective", case["objective"]] + (["--boundary", case["boundary"]] if case["boundary"] else ["--minimize"])
        grid = search(exe, a.work, f"case{n}_grid", case, modes + ["--method", "grid", "--budget", str(case["grid"])] + j)
        searches = [search(exe, a.work, f"case{n}_min_seed{seed}", case,
                           ["--objective", case["objective"], "--minimize", "--budget", str(a.budget), "--seed", str(seed)] + j)
                    for seed in range(1, a.seeds + 1)]
        randoms = random_folders(exe, a, n, case, j)
        print_minimum(case, grid, searches, randoms, a)
        if case["boundary"]:
            print_boundary(exe, case, n, grid, randoms, a, j)
    return 0


if __name__ == "__main__":
    sys.exit(main())
