#!/usr/bin/env bash
# Builds what the sanitizer stage runs (scripts/test_sanitized.sh) and the soak
# (scripts/soak.sh): the program, the unit and end-to-end tests and the random-input fuzz
# drivers, with AddressSanitizer + UndefinedBehaviorSanitizer, into BUILD_DIR.
# Usage: scripts/build_sanitized.sh BUILD_DIR
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:?usage: scripts/build_sanitized.sh BUILD_DIR}
# -O1 -g1: sanitized code at -O2 takes much longer to compile and gains the tests little;
# line tables (-g1) are all the sanitizers need for their stack traces.
# Only the test sets the stage runs are defined, so "all" is exactly what it needs.
"$root/scripts/build.sh" "$build" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DORCH_SANITIZE=ON -DORCH_WERROR=ON -DORCH_UNITY=ON \
  -DORCH_TEST_SETS="unit;e2e;fuzz_random"
