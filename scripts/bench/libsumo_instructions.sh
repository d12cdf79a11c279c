#!/usr/bin/env bash
# Instructions, simulated cache misses and branches per step of the same simulation in
# libsumo (`orchestrator baseline`) and in the `sumo` executable, under valgrind's callgrind:
# independent of the machine's load (docs/performance.md, "Against the `sumo` executable").
# ALKS_Road with `map traffic --rate 1800 --fill-per-km 33` (~1,000 vehicles), the
# orchestrator's SUMO options; runs of A and B steps, the difference over B - A steps.
# Usage: scripts/bench/libsumo_instructions.sh [BUILD_DIR] [A] [B]   (needs valgrind; slow: ~30 min)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build}
a=${2:-100}
b=${3:-140}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
orch="$build/bin/orchestrator"
net="$root/sumo_nets/ALKS_Road/ALKS_Road.net.xml"
"$orch" map traffic ALKS_Road --rate 1800 --fill-per-km 33 --out "$work/traffic.rou.xml" > /dev/null
cg=(valgrind --tool=callgrind --cache-sim=yes --branch-sim=yes)
for n in "$a" "$b"; do
  "${cg[@]}" --callgrind-out-file="$work/libsumo_$n.cg" "$orch" baseline ALKS_Road \
    --traffic "$work/traffic.rou.xml" --steps "$n" --out "$work/baseline_$n" > /dev/null 2>&1
  "${cg[@]}" --callgrind-out-file="$work/sumo_$n.cg" sumo -n "$net" -r "$work/traffic.rou.xml" --step-length 0.05 \
    --seed 42 --lateral-resolution 0.8 --collision.action warn --collision.check-junctions true \
    --collision.mingap-factor 0 --time-to-teleport -1 --ignore-junction-blocker 20 --no-step-log true \
    --duration-log.disable true --end "$(python3 -c "print($n * 0.05)")" > /dev/null 2>&1
done
python3 - "$work" "$a" "$b" <<'PY'
import re, sys
work, a, b = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
def totals(f):
    text = open(f).read()
    events = re.search(r"^events: (.*)$", text, re.M).group(1).split()
    values = re.search(r"^(?:summary|totals): (.*)$", text, re.M).group(1).split()
    return dict(zip(events, map(int, values)))
per = {}
for k in ("libsumo", "sumo"):
    lo, hi = totals(f"{work}/{k}_{a}.cg"), totals(f"{work}/{k}_{b}.cg")
    per[k] = {e: (hi[e] - lo[e]) / (b - a) for e in lo}
names = {"Ir": "instructions", "Dr": "data reads", "I1mr": "L1 instruction misses", "D1mr": "L1 data read misses",
         "Bi": "indirect branches", "Bim": "indirect branches mispredicted"}
print(f"per step ({b - a} steps): libsumo / sumo executable")
for e, name in names.items():
    print(f"  {name:32s} {per['libsumo'][e] / 1e6:10.3f} M {per['sumo'][e] / 1e6:10.3f} M  {per['libsumo'][e] / per['sumo'][e]:6.3f}")
PY
