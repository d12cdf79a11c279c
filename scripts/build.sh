#!/usr/bin/env bash
# Configures and builds the orchestrator and its tests (Release with debug info, Ninja).
# Usage: scripts/build.sh [BUILD_DIR] [extra cmake -D options...]
# ORCH_BUILD_TARGETS="a b" builds only those targets (default: all).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
shift || true
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
launcher=()
# ccache (when installed) makes rebuilds and further checkouts of the same sources cheap.
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$(dirname "$root")}
fi
cmake -S "$root" -B "$build" "${generator[@]}" "${launcher[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo "$@"
targets=()
for t in ${ORCH_BUILD_TARGETS:-}; do targets+=(--target "$t"); done
cmake --build "$build" -j "$(nproc)" "${targets[@]}"
