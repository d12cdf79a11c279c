#!/usr/bin/env bash
# Scaling of `orchestrator batch`: the same 40 runs of the nightly example (20 sets of each
# logical scenario) with --jobs 1 and --jobs 2, their wall times and speed-up, and where a
# run's time goes besides simulating (process start-up, loading net and map, writing).
#
# Usage: scripts/bench/batch_scaling.sh [ORCHESTRATOR]   (default: build/bin/orchestrator)
# Prints figures only; it asserts nothing. Run it on an otherwise idle machine: the load
# average before and after is printed because other work on the cores skews the speed-up.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
bin=$(readlink -f "${1:-${ORCHESTRATOR:-$root/build/bin/orchestrator}}")
[ -x "$bin" ] || { echo "no orchestrator binary at $bin (build first: scripts/build.sh)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

for f in "$root"/scenarios/nightly/*.json; do
  case "$f" in *_parameters.json) ;; *) cp "$f" "$work/" ;; esac
done
for logical in "$work"/logical_*.json; do
  "$bin" sample "$logical" --count 20 --seed 1 >/dev/null
done
logicals=("$work"/logical_*[0-9a-f].json)

echo "machine: $(nproc) cores, load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
declare -A wall
for jobs in 1 2; do
  start=$(date +%s.%N)
  "$bin" batch "${logicals[@]}" --out "$work/jobs$jobs" --jobs "$jobs" >"$work/jobs$jobs.log" 2>&1 || true
  end=$(date +%s.%N)
  wall[$jobs]=$(python3 -c "print(f'{$end - $start:.2f}')")
  grep -E '^[0-9]+ runs:' "$work/jobs$jobs.log" | sed "s/^/jobs $jobs: /"
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"

# A one-step run of each scenario: everything a run costs besides simulating.
one_step=()
for logical in "${logicals[@]}"; do
  scenario=$(find "$work/jobs1/runs" -name scenario.json | grep "$(basename "$logical" .json | sed 's/logical_//')" | head -1)
  s=$(date +%s.%N)
  "$bin" run "$scenario" --out "$work/one_step" --max-time 0.05 -q >/dev/null || true
  e=$(date +%s.%N)
  one_step+=("$(python3 -c "import json;print($e - $s, json.load(open('$work/one_step/result.json'))['wall_time_s'])")")
done

python3 - "$work" "${wall[1]}" "${wall[2]}" "${one_step[@]}" <<'PY'
import glob, json, sys
work, wall1, wall2 = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
steps = [tuple(map(float, s.split())) for s in sys.argv[4:]]
def attempts(folder):
    out = []
    for f in glob.glob(f"{work}/{folder}/executions/*.json"):
        for a in json.load(open(f))["trace"]["implementation"]["attempts"]:
            out.append(a)
    return out
a1 = attempts("jobs1")
n = len(a1)
child = sum(a["wall_time_s"] for a in a1) / n                      # fork to exit, as the batch saw it
inside = sum(a["run_wall_time_s"] or 0 for a in a1) / n            # run_scenario: load, simulate, write
sim = sum(a["sim_time"] or 0 for a in a1) / n
process = child - inside                                           # exec, libsumo/dynamic loading, exit
fixed_process = sum(s[0] for s in steps) / len(steps)              # whole one-step run
fixed_inside = sum(s[1] for s in steps) / len(steps)               # its run_scenario part
bookkeeping = (wall1 - n * child) / n                              # the batch between children (jobs 1)
print()
print(f"| runs | --jobs 1 | --jobs 2 | speed-up |")
print(f"|---|---|---|---|")
print(f"| {n} | {wall1:.1f} s | {wall2:.1f} s | {wall1 / wall2:.2f}x |")
print()
print(f"per run (means, --jobs 1): {child:.3f} s wall in the child for {sim:.1f} s simulated")
print(f"  outside the simulation:")
print(f"    process start-up and exit (outside run_scenario): {process:.3f} s")
print(f"    loading net, map, scenario and starting SUMO, writing results (a one-step run): {fixed_inside:.3f} s"
      f" ({fixed_process:.3f} s with its process)")
print(f"    batch bookkeeping (binding, starting, judging, writing the trace): {bookkeeping:.3f} s")
print(f"  simulating: {inside - fixed_inside:.3f} s")
overhead = process + fixed_inside + max(bookkeeping, 0)
print(f"  overhead share: {100 * overhead / (child + max(bookkeeping, 0)):.0f} % of a run")
PY
