#!/usr/bin/env bash
# Forking in the search (docs/forking.md, docs/search.md): the same search with --no-fork
# (every point from t = 0) and with forking (the points of an iteration share their common
# prefix); the runs' simulated seconds, the SUMO seconds stepped and the wall time of each.
# The objectives of the two must be the same (forked runs are their runs from t = 0).
#
# Usage: scripts/bench/fork_search.sh [ORCHESTRATOR] [BUDGET] [JOBS] [-- SEARCH ARGS...]
#   default: build/bin/orchestrator 16 2, the late lead brake (brake time 20-30 s, decel 4-12 m/s²)
# Prints figures only; it asserts nothing.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
bin=$(readlink -f "${1:-${ORCHESTRATOR:-$root/build/bin/orchestrator}}")
budget=${2:-16}
jobs=${3:-2}
shift $(( $# < 3 ? $# : 3 ))
[ "${1:-}" = "--" ] && shift
args=("$@")
[ ${#args[@]} -gt 0 ] || args=("$root/scenarios/nightly/logical_8fcbbaab-a3d0-472b-b3d5-1046910ecff3.json"
                              --objective min_ttc --minimize)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "machine: $(nproc) cores, load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
for mode in no-fork fork; do
  extra=(); [ "$mode" = no-fork ] && extra=(--no-fork)
  start=$(date +%s.%N)
  "$bin" search "${args[@]}" --budget "$budget" --jobs "$jobs" --seed 1 --out "$work/$mode" "${extra[@]}" >"$work/$mode.log" 2>&1
  end=$(date +%s.%N)
  python3 -c "print(f'{$end - $start:.3f}')" > "$work/$mode.wall"
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
python3 - "$work" "$budget" "$jobs" <<'PY'
import json, os, sys
work, budget, jobs = sys.argv[1:4]
def figures(mode):
    out = os.path.join(work, mode)
    s = json.load(open(os.path.join(out, "search.json")))
    sim, processes, objectives = 0.0, {}, []
    for it in s["iterations"]:
        for p in it["points"]:
            d = os.path.join(out, p["run_dir"])
            r = json.load(open(os.path.join(d, "result.json")))
            f = json.load(open(os.path.join(d, "fork.json"))) if os.path.exists(os.path.join(d, "fork.json")) else {"process": d, "own_from_s": 0}
            sim += r["sim_time"]
            key = (f["process"], f["own_from_s"])
            processes[key] = max(processes.get(key, 0.0), r["sim_time"] - f["own_from_s"])
            objectives.append(p.get("objective"))
    return sim, sum(processes.values()), objectives, len(s["iterations"])
wall = {m: float(open(os.path.join(work, m + ".wall")).read()) for m in ("no-fork", "fork")}
sb, stepped_b, ob, ib = figures("no-fork")
sf, stepped_f, of, _ = figures("fork")
print(f"\nsearch: budget {budget}, --jobs {jobs}, {ib} iterations")
print(f"simulated s of the runs: {sb:.1f} (no fork) / {sf:.1f} (fork)")
print(f"SUMO s stepped: no fork {stepped_b:.1f}, fork {stepped_f:.1f}, ratio {stepped_b / max(stepped_f, 1e-9):.2f}x")
print(f"the same objectives, run by run: {ob == of}")
print(f"wall time: no fork {wall['no-fork']:.2f} s, fork {wall['fork']:.2f} s, ratio {wall['no-fork'] / wall['fork']:.2f}x")
PY
