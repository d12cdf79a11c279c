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
# -O1 -g1: sanitized code at -O2 takes much longer to compile and gains the tests little;
# line tables (-g1) are all the sanitizers need for their stack traces.
ORCH_BUILD_TARGETS="unit_tests e2e_tests orchestrator scenario_pipeline_fuzz_random binder_fuzz_random traci_fuzz_random" \
  "$root/scripts/build.sh" "$build" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DORCH_SANITIZE=ON -DORCH_WERROR=ON
# A report aborts the process (exit 134 in the CLI tests, never mistaken for a verdict).
export ASAN_OPTIONS=halt_on_error=1:abort_on_error=1:detect_leaks=1
export UBSAN_OPTIONS=halt_on_error=1:abort_on_error=1:print_stacktrace=1
export LSAN_OPTIONS=suppressions=$root/scripts/lsan.supp:print_suppressions=0
cd "$build"
status=0
ctest --output-on-failure -j "$(nproc)" --timeout 900 -L unit "$@" || status=$?
ctest --output-on-failure -j "$(nproc)" --timeout 900 -R '_fuzz_random$' "$@" || status=$?
ctest --output-on-failure -j "$(nproc)" --timeout 900 -L e2e "$@" || status=$?
exit $status
