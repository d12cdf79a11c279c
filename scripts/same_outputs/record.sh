#!/usr/bin/env bash
# record.sh BIN OUTROOT (BIN an absolute path; see README.md): runs every shipped sample on both backends (plus a few option
# variants that exercise the reference driver, traffic and --ssm) into OUTROOT/<backend>/<case>.
set -uo pipefail
bin=$1; root=$2
src=$(cd "$(dirname "$0")/../.." && pwd)
cd "$src"
cases=()
for f in scenarios/*.json scenarios/openscenario/*.xosc scenarios/evaluation/*.yaml; do cases+=("$f|"); done
cases+=("scenarios/alks_lead_brake.json|--ego-model r157")
cases+=("scenarios/alks_obstacle_stop.json|--ego-model r157 --reference-run")
cases+=("scenarios/openscenario/cut_in_traffic.xosc|--ego-model r157")
cases+=("scenarios/openscenario/overtaking.xosc|--ssm --traffic light")
cases+=("scenarios/highway_cut_in.json|--traffic medium --trace-background --ssm --max-time 12")
cases+=("scenarios/openscenario/every_condition.xosc|--max-time 3")
for backend in ${BACKENDS:-libsumo traci}; do
  for c in "${cases[@]}"; do
    file=${c%%|*}; extra=${c#*|}
    name=$(echo "$file $extra" | sed 's#scenarios/##; s#[/ ]#_#g; s#--##g')
    out=${ORCH_SAME_OUTPUTS_SCRATCH:-/tmp/orch_same_outputs}/$backend/$name
    rm -rf "$out"; mkdir -p "$out"
    start=$(date +%s.%N)
    # shellcheck disable=SC2086
    "$bin" run "$file" --out "$out" -q --no-report --backend "$backend" $extra >"$out.console" 2>&1
    rc=$?
    end=$(date +%s.%N)
    mkdir -p "$root/$backend"
    rm -rf "$root/$backend/$name"; cp -r "$out" "$root/$backend/$name"
    echo "$rc" > "$root/$backend/$name/exit_code"
    printf '%s %s rc=%s %.2fs\n' "$backend" "$name" "$rc" "$(echo "$end - $start" | bc)"
  done
done
