#!/usr/bin/env bash
# Installs the dependencies, builds from scratch and runs every test: unit, integration
# (real SUMO), end-to-end (the CLI), and -- when ../shared/data exists next to the
# checkout -- the tests on the real user scenario files (label shared_data). Then a second
# build with ASan+UBSan runs the unit tests, fuzz drivers and the quick end-to-end tests
# (scripts/test_sanitized.sh; ORCH_SANITIZE_STAGE=0 skips it for a quicker local round).
# The libFuzzer targets (clang, ASan+UBSan) run in the first stage.
# Usage: scripts/test.sh [ctest arguments...]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
build="$root/build-test"
rm -rf "$build"
"$root/scripts/build.sh" "$build" -DORCH_WERROR=ON
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
