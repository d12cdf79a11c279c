#!/usr/bin/env bash
# Forking (docs/forking.md) on the nightly examples: the same batch of every logical scenario
# in scenarios/nightly/ (COUNT sets each, default 20) and of every OpenSCENARIO variation in
# scenarios/openscenario/nightly/ (all its runs) with --no-fork (every run from t = 0) and
# with --fork (one seed per logical scenario, the common prefix run once); the simulated
# seconds SUMO stepped and the wall time of each, and their ratios. The figures per logical
# scenario show where sharing pays (parameters that act late) and where it cannot (parameters
# that act from t = 0).
#
# Usage: [ONLY=UUID] scripts/bench/fork_nightly.sh [ORCHESTRATOR] [COUNT] [JOBS]   (default: build/bin/orchestrator 20 2)
# Prints figures only; it asserts nothing. Run it on an otherwise idle machine (the load
# average before and after is printed).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
bin=$(readlink -f "${1:-${ORCHESTRATOR:-$root/build/bin/orchestrator}}")
count=${2:-20}
jobs=${3:-2}
[ -x "$bin" ] || { echo "no orchestrator binary at $bin (build first: scripts/build.sh)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

for f in "$root"/scenarios/nightly/*.json; do
  case "$f" in *_parameters.json) ;; *) cp "$f" "$work/" ;; esac
done
for logical in "$work"/logical_*.json; do
  "$bin" sample "$logical" --count "$count" --seed 1 >/dev/null
done
logicals=("$work"/logical_*${ONLY:-}*[0-9a-f].json)  # ONLY=UUID: one logical scenario (or variation)
for v in "$root"/scenarios/openscenario/nightly/*${ONLY:-}*_variation.xosc; do
  [ -e "$v" ] && logicals+=("$v")
done
[ -e "${logicals[0]}" ] || logicals=("${logicals[@]:1}")

echo "machine: $(nproc) cores, load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
for mode in no-fork fork; do
  start=$(date +%s.%N)
  "$bin" batch "${logicals[@]}" --out "$work/$mode" --jobs "$jobs" "--$mode" >"$work/$mode.log" 2>&1 || true
  end=$(date +%s.%N)
  python3 -c "print(f'{$end - $start:.3f}')" > "$work/$mode.wall"
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"

python3 - "$work" "$count" "$jobs" <<'PY'
import json, os, sys, collections
work, count, jobs = sys.argv[1], sys.argv[2], sys.argv[3]
def figures(mode):
    out = os.path.join(work, mode)
    logical_of, verdicts = {}, collections.Counter()
    for f in os.listdir(os.path.join(out, "executions")):
        t = json.load(open(os.path.join(out, "executions", f)))
        logical_of[t["outputs"]["run_dir"]] = t["name"]
        verdicts[t["trace"]["implementation"]["final_status"]] += 1
    per = collections.defaultdict(lambda: [0, 0.0, 0.0])  # runs, run sim seconds, SUMO seconds stepped
    processes = {}
    for run_dir, name in logical_of.items():
        r = json.load(open(os.path.join(out, run_dir, "result.json")))
        fork_file = os.path.join(out, run_dir, "fork.json")
        fork = json.load(open(fork_file)) if os.path.exists(fork_file) else {"own_from_s": 0, "process": run_dir}
        per[name][0] += 1
        per[name][1] += r["sim_time"]
        # A process steps SUMO from where it was forked to where its last run ended.
        key = (name, fork["process"], fork["own_from_s"])
        processes[key] = max(processes.get(key, 0.0), r["sim_time"] - fork["own_from_s"])
    for (name, _, _), stepped in processes.items():
        per[name][2] += stepped
    return per, verdicts
wall = {m: float(open(os.path.join(work, m + ".wall")).read()) for m in ("no-fork", "fork")}
base, bv = figures("no-fork")
fork, fv = figures("fork")
print(f"\n{count} sets per logical scenario, --jobs {jobs}")
print(f"{'logical scenario':<52} {'runs':>4} {'simulated s, no fork':>21} {'SUMO s stepped, fork':>21} {'ratio':>6}")
tb = tf = 0.0
for name in sorted(base):
    runs, sim_b, _ = base[name]
    _, _, stepped = fork.get(name, [0, 0.0, 0.0])
    tb += sim_b; tf += stepped
    print(f"{name:<52} {runs:>4} {sim_b:>21.1f} {stepped:>21.1f} {sim_b / max(stepped, 1e-9):>5.2f}x")
print(f"{'all':<52} {sum(v[0] for v in base.values()):>4} {tb:>21.1f} {tf:>21.1f} {tb / max(tf, 1e-9):>5.2f}x")
print(f"verdicts no fork: {dict(bv)}; fork: {dict(fv)} (--fork runs each logical scenario with one seed)")
print(f"wall time: no fork {wall['no-fork']:.2f} s, fork {wall['fork']:.2f} s, ratio {wall['no-fork'] / wall['fork']:.2f}x")
PY
