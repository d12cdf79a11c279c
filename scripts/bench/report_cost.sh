#!/usr/bin/env bash
# What writing report.html costs at the end of a run: runs the ~70 s highway cut-in once,
# then rewrites its report N times and prints the time the program measured for writing it
# (median, min, max) against the run's own wall time.
# Usage: scripts/bench/report_cost.sh [ORCHESTRATOR] [N]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
orch=${1:-$root/build/bin/orchestrator}
n=${2:-10}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
first=$("$orch" run "$root/scenarios/highway_cut_in.json" --out "$out/run" -q | sed -n 's/^report: .* (\(.*\) s)$/\1/p')
times=()
for _ in $(seq "$n"); do
  times+=("$("$orch" report "$out/run" | sed -n 's/^report: .* (\(.*\) s)$/\1/p')")
done
python3 - "$out/run" "$first" "${times[@]}" <<'PY'
import json, os, statistics, sys
run, first, times = sys.argv[1], float(sys.argv[2]), sorted(map(float, sys.argv[3:]))
r = json.load(open(os.path.join(run, "result.json")))
size = os.path.getsize(os.path.join(run, "report.html"))
print(f"run: {r['sim_time']:.2f} s simulated, {r['trace_rows']} trace rows, {r['wall_time_s']:.2f} s wall")
print(f"report.html: {size / 1e6:.2f} MB")
print(f"writing it at the end of the run: {first:.3f} s")
print(f"rewriting it ({len(times)}x): median {statistics.median(times):.3f} s, min {times[0]:.3f} s, max {times[-1]:.3f} s"
      f" = {statistics.median(times) / r['wall_time_s'] * 100:.1f} % of the run's wall time")
PY
