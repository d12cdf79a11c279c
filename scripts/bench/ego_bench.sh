#!/usr/bin/env bash
# Lockstep steps per second of an ego plug-in (SUMO's Python traci, one subscription and one
# command per step) through the orchestrator, next to the same loop on a plain SUMO.
# Usage: scripts/bench/ego_bench.sh [BUILD_DIR] [--steps N] [--repeat N]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build}
shift || true
[ -x "$build/bin/orchestrator" ] || "$root/scripts/build.sh" "$build"
export SUMO_HOME=${SUMO_HOME:-/usr/share/sumo}
PYTHONPATH="$SUMO_HOME/tools${PYTHONPATH:+:$PYTHONPATH}" exec /usr/bin/python3 "$root/scripts/bench/ego_lockstep.py" \
  --orchestrator "$build/bin/orchestrator" "$@"
