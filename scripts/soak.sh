#!/usr/bin/env bash
# Soak: the property and fuzz tests with random seeds, under AddressSanitizer +
# UndefinedBehaviorSanitizer, for a given time. The README's test command runs the same
# tests on a fixed seed set; this looks further. Every failing seed is printed with the
# command that replays it, and its log is kept; at the end a table per kind: batches,
# mutants (or fuzz inputs) tried, failures, the slowest mutant.
# Usage: scripts/soak.sh [--minutes M] [--build DIR] [--kinds json,xosc,xodr,yaml,fuzz] [--runs N] [--out DIR]
#   --runs N: mutants per seed (default 16); kinds are taken in turn until the time is up.
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
minutes=60
build=$root/build-sanitize
kinds=json,xosc,xodr,yaml,fuzz
runs=16
out=$root/soak_out
while [ $# -gt 0 ]; do
  case "$1" in
    --minutes) minutes=$2; shift 2 ;;
    --build) build=$2; shift 2 ;;
    --kinds) kinds=$2; shift 2 ;;
    --runs) runs=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    *) echo "soak: unknown option $1" >&2; exit 2 ;;
  esac
done
if [ ! -x "$build/tests/e2e_tests" ] || [ ! -x "$build/bin/orchestrator" ]; then
  "$root/scripts/build_sanitized.sh" "$build" || exit 2
fi
source "$root/scripts/sanitizer_env.sh"
mkdir -p "$out"
summary=$out/mutants.tsv   # kind seed index file exit seconds what
: > "$summary"
failures=$out/failures.txt
: > "$failures"

filter_of() {
  case "$1" in
    json) echo 'MutatedScenariosCli.EveryMutationEndsInAWrittenResult' ;;
    xosc) echo 'MutatedOpenScenarioCli.EveryMutatedXoscEndsInAWrittenResult' ;;
    xodr) echo 'MutatedOpenScenarioCli.EveryMutatedRoadEndsInAWrittenResult' ;;
    yaml) echo 'MutatedOpenScenarioCli.EveryMutatedEvaluationFileEndsInAWrittenResult' ;;
  esac
}

random_seed() { od -An -N4 -tu4 /dev/urandom | tr -d ' '; }


# The table so far (also written to $out/summary.md after every seed, so that a soak cut
# short still leaves its figures).
print_table() {
  echo "| kind | seeds | mutants / inputs | failing seeds | slowest mutant |"
  echo "|---|---|---|---|---|"
  for kind in "${kind_list[@]}"; do
    if [ "$kind" = fuzz ]; then
      total=0
      for d in "${!fuzz_inputs[@]}"; do total=$((total + fuzz_inputs[$d])); done
      echo "| fuzz (3 drivers) | ${batches[$kind]:-0} | $total inputs | ${fails[$kind]:-0} | - |"
    else
      n=$(awk -F'\t' -v k="$kind" '$1 == k' "$summary" | wc -l)
      slow=$(awk -F'\t' -v k="$kind" '$1 == k' "$summary" | sort -t$'\t' -k6 -g | tail -1 |
             awk -F'\t' '{printf "%.1f s, %s: %s", $6, $4, $7}')
      echo "| $kind | ${batches[$kind]:-0} | $n | ${fails[$kind]:-0} | ${slow:--} |"
    fi
  done
}

IFS=, read -r -a kind_list <<< "$kinds"
end=$(( $(date +%s) + minutes * 60 ))
declare -A batches fails fuzz_inputs
round=0
echo "soak: ${minutes} min over ${kinds}, ${runs} mutants per seed, build $build, logs in $out"
while [ "$(date +%s)" -lt "$end" ]; do
  kind=${kind_list[$(( round % ${#kind_list[@]} ))]}
  round=$((round + 1))
  seed=$(random_seed)
  log=$out/${kind}_${seed}.log
  if [ "$kind" = fuzz ]; then
    status=0
    for driver in scenario_pipeline binder traci; do
      corpus=()
      case $driver in
        scenario_pipeline) corpus=("$root/scenarios" "$root/tests/fuzz/regressions/scenario")
                           [ -d "$root/../shared/data/roadeditor/scenarios" ] && corpus+=("$root/../shared/data/roadeditor/scenarios") ;;
        binder) corpus=("$root/tests/fuzz/binder_corpus" "$root/tests/fuzz/regressions/binder") ;;
        traci) corpus=("$root/tests/fuzz/corpus") ;;
      esac
      "$build/tests/fuzz/${driver}_fuzz_random" --seed "$seed" --seconds 60 "${corpus[@]}" >> "$log" 2>&1 || status=$?
      n=$(grep -o '[0-9]* inputs, no crash' "$log" | tail -1 | cut -d' ' -f1)
      fuzz_inputs[$driver]=$(( ${fuzz_inputs[$driver]:-0} + ${n:-0} ))
      if [ $status -ne 0 ]; then
        echo "FAIL fuzz $driver seed $seed: replay: $build/tests/fuzz/${driver}_fuzz_random --seed $seed --seconds 60 ${corpus[*]}" | tee -a "$failures"
        break
      fi
    done
  else
    status=0
    ORCH_PROPERTY_SEED=$seed ORCH_PROPERTY_RUNS=$runs "$build/tests/e2e_tests" --gtest_filter="$(filter_of "$kind")" \
      > "$log" 2>&1 || status=$?
    grep '^mutant ' "$log" | sed -E 's/^mutant ([a-z]+) seed=([0-9]+) index=([0-9]+) file=([^ ]+) exit=(-?[0-9]+) seconds=([0-9.e+-]+) what=(.*)$/\1\t\2\t\3\t\4\t\5\t\6\t\7/' >> "$summary"
    if [ $status -ne 0 ]; then
      echo "FAIL $kind seed $seed: replay: ORCH_PROPERTY_SEED=$seed ORCH_PROPERTY_RUNS=$runs $build/tests/e2e_tests --gtest_filter=$(filter_of "$kind") (log $log)" | tee -a "$failures"
    fi
  fi
  batches[$kind]=$(( ${batches[$kind]:-0} + 1 ))
  [ $status -ne 0 ] && fails[$kind]=$(( ${fails[$kind]:-0} + 1 ))
  [ $status -eq 0 ] && rm -f "$log"
  { echo "soak since $(date -d @$((end - minutes * 60)) -u +%H:%M) UTC, now $(date -u +%H:%M) UTC"; print_table; } > "$out/summary.md"
done

echo
print_table
if [ -s "$failures" ]; then
  echo
  echo "failing seeds (replay commands):"
  cat "$failures"
  exit 1
fi
echo "soak: no failure"
