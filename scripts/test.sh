#!/usr/bin/env bash
# Installs the dependencies, builds from scratch and runs every test, in two stages that
# each build only what they run. Main stage (release build): integration (real SUMO), the
# reports in a browser, the libFuzzer targets (clang, ASan+UBSan) and -- when ../shared/data
# exists next to the checkout -- the tests on the real user files (label shared_data).
# Sanitizer stage (ASan+UBSan build, scripts/test_sanitized.sh): unit, end-to-end (the CLI)
# and the random fuzz drivers. Every random test runs a fixed seed set (scripts/soak.sh
# runs random seeds). ORCH_SANITIZE_STAGE=0 runs everything in the release build instead.
# Usage: scripts/test.sh [ctest arguments...]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
build="$root/build-test"
rm -rf "$build"
# The main stage builds and runs what needs the release build: integration tests on real
# SUMO, the real user files, the reports in a browser, the libFuzzer targets and the
# differential test against esmini. The unit
# and end-to-end tests and the random fuzz drivers run in the sanitizer stage (stricter, and
# each test is compiled once): ORCH_SANITIZE_STAGE=0 builds and runs them here instead.
# -g1: line tables are all a failing test's backtrace needs, and full debug information
# costs a fifth of the compile time.
sets="integration;shared_data;browser;libfuzzer;differential"
[ "${ORCH_SANITIZE_STAGE:-1}" = 1 ] || sets="unit;integration;e2e;shared_data;browser;fuzz_random;libfuzzer;differential"
"$root/scripts/build.sh" "$build" -DORCH_WERROR=ON -DORCH_UNITY=ON -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" \
  -DORCH_TEST_SETS="$sets"
cd "$build"
if [ -d "$root/../shared/data/roadeditor" ]; then
  echo "test: ../shared/data found: the shared_data tests run too"
else
  echo "test: no ../shared/data next to the checkout: shared_data tests are not built"
fi
status=0
ctest --output-on-failure -j "$(nproc)" --timeout 900 "$@" || status=$?
if [ "${ORCH_SANITIZE_STAGE:-1}" = 1 ]; then
  rm -rf "$root/build-test-sanitize"
  "$root/scripts/test_sanitized.sh" "$root/build-test-sanitize" || status=$?
fi
exit $status
