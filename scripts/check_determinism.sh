#!/usr/bin/env bash
# Runs every seeded random test of the test command twice on one build and compares what
# they print: the seeds, each mutant (file, mutation, exit status) and each fuzz driver's
# input count and verdict. Two runs of the same tree must print the same; a difference is
# printed and the exit status is 1. (Wall-clock seconds are left out of the comparison.)
# Usage: scripts/check_determinism.sh [BUILD_DIR]   (default build/; needs e2e_tests and the
#        random fuzz drivers built, e.g. the sanitizer stage's build-test-sanitize/)
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$root/build}" && pwd) || exit 2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$build" || exit 2
[ -f "$root/scripts/sanitizer_env.sh" ] && source "$root/scripts/sanitizer_env.sh"
for round in 1 2; do
  "$build/tests/e2e_tests" --gtest_filter='Mutated*' 2>&1 |
    sed -E 's/ seconds=[0-9.e+-]+//; s/ \([0-9]+ ms( total)?\)//' |
    grep -E '^mutant |mutants: ORCH_PROPERTY_SEED=|^\[ +(OK|FAILED|PASSED) +\]' > "$work/mutants_$round.txt"
  ctest -L fuzz -R '_fuzz_random$' -V 2>&1 |
    grep -E 'inputs, no crash|seed|Passed|Failed' | sed -E 's/ +[0-9.]+ sec//; s/^[0-9]+: //' > "$work/fuzz_$round.txt"
done
status=0
for kind in mutants fuzz; do
  lines=$(wc -l < "$work/${kind}_1.txt")
  if diff "$work/${kind}_1.txt" "$work/${kind}_2.txt" > "$work/${kind}.diff"; then
    echo "$kind: both runs printed the same $lines lines"
  else
    echo "$kind: the two runs differ:"; cat "$work/${kind}.diff"; status=1
  fi
done
grep -c '^mutant ' "$work/mutants_1.txt" | xargs echo "mutants per run:"
grep -o 'ORCH_PROPERTY_SEED=[0-9]*' "$work/mutants_1.txt" | sort -u | tr '\n' ' ' | xargs echo "seeds:"
exit $status
