#!/usr/bin/env bash
# The sanitizer stage of scripts/test.sh: builds with -DORCH_SANITIZE=ON (AddressSanitizer +
# UndefinedBehaviorSanitizer, halting on the first report) into build-sanitize/ and runs
# what fits CI's budget: the unit tests, the random-input fuzz drivers (the libFuzzer
# targets already run with ASan+UBSan in the main build) and every end-to-end test (the real
# CLI on real SUMO, bad and mutated input included: each needs seconds, not minutes;
# docs/hardening.md has the stage's time).
# Usage: scripts/test_sanitized.sh [BUILD_DIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build-sanitize}
"$root/scripts/build_sanitized.sh" "$build"
source "$root/scripts/sanitizer_env.sh"
cd "$build"
status=0
ctest --output-on-failure -j "$(nproc)" --timeout 900 -L unit "$@" || status=$?
ctest --output-on-failure -j "$(nproc)" --timeout 900 -R '_fuzz_random$' "$@" || status=$?
ctest --output-on-failure -j "$(nproc)" --timeout 900 -L e2e "$@" || status=$?
exit $status
