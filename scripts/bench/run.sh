#!/usr/bin/env bash
# Builds the orchestrator (Release) into build-bench/ and runs the benchmark: bare SUMO vs
# the orchestrator on libsumo and traci vs a Python traci loop, at ~200, ~1,000 and ~3,000
# vehicles, 5 interleaved rounds (best times). About 20 minutes on 2 cores. Options: --quick (a
# fifth of the steps), --repeat N (rounds), --hour (adds
# the one-hour dense run that checks memory stays flat, ~10 more minutes), --keep DIR.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
"$root/scripts/build.sh" "$root/build-bench" -DCMAKE_BUILD_TYPE=Release -DORCH_BUILD_TESTS=OFF >/dev/null
export SUMO_HOME=${SUMO_HOME:-/usr/share/sumo}
exec /usr/bin/python3 "$root/scripts/bench/bench.py" --binary "$root/build-bench/bin/orchestrator" "$@"
