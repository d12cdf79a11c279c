#!/usr/bin/env bash
# The main job on the embedded default: installs what is missing, builds, and runs the
# sample cut-in scenario on the shipped highway map with libsumo.
# Results land in out/highway_cut_in/ (result.json, trace.csv, run.log, report.html: it
# prints the report's file:// address to open in a browser).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
# Only the program (the tests are scripts/test.sh's business), as a unity build: half the
# compile time from scratch.
ORCH_BUILD_TARGETS=orchestrator "$root/scripts/build.sh" "$root/build" -DORCH_UNITY=ON >/dev/null
exec "$root/build/bin/orchestrator" run "$root/scenarios/highway_cut_in.json" --out "$root/out/highway_cut_in" "$@"
