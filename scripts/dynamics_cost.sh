#!/usr/bin/env bash
# What the dynamics in every direction costs (issue 34's benchmark): for
# growth_exact.toml (continuous track) and growth_discrete.toml (discrete
# track), the wall time of a study of 1 and of 3 passages with
#   vertical   dynamics.directions = "vertical" (the vertical models)
#   steady     dynamics.directions = "all", dynamics.creep_forces = "steady"
#   transient  dynamics.directions = "all" (the default: the creep response)
# median of RUNS (default 3) runs each, release build, this machine's cores.
# The difference 3 passages - 1 passage is two passages; the rest of the
# 1-passage run is the set-up (tables, creep response, the smooth-rail
# passage on the discrete track). Prints a table; writes
# out/dynamics_cost/summary.csv.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${CORRUGATION_BIN:-./target/release/corrugation}
[ -n "${CORRUGATION_BIN:-}" ] || cargo build --release --quiet
out=out/dynamics_cost
mkdir -p "$out"
runs=${RUNS:-3}
median() { sort -n | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }
time_run() { # config passes settings... -> median wall seconds
  local config=$1 passes=$2; shift 2
  for _ in $(seq "$runs"); do
    local t0 t1
    t0=$(date +%s.%N)
    "$bin" run --overwrite "configs/$config.toml" -o "$out/run.h5" --set "growth.passes=$passes" \
      --set 'growth.contact_history=[]' "$@" > /dev/null 2>&1
    t1=$(date +%s.%N)
    echo "$t1 - $t0" | bc -l
  done | median
}
echo "config,case,one_passage_s,three_passages_s,passage_s,setup_s,setup_in_passages" > "$out/summary.csv"
printf '%-16s %-10s %10s %10s %10s %12s\n' config case "passage s" "set-up s" "set-up/pass" "1 pass s"
for config in growth_exact growth_discrete; do
  for case in vertical steady transient; do
    case $case in
      vertical) set=(--set dynamics.directions=vertical) ;;
      steady) set=(--set dynamics.directions=all --set dynamics.creep_forces=steady) ;;
      transient) set=(--set dynamics.directions=all --set dynamics.creep_forces=transient) ;;
    esac
    one=$(time_run "$config" 1 "${set[@]}")
    three=$(time_run "$config" 3 "${set[@]}")
    passage=$(echo "($three - $one) / 2" | bc -l)
    setup=$(echo "$one - $passage" | bc -l)
    ratio=$(echo "$setup / $passage" | bc -l)
    printf '%-16s %-10s %10.2f %10.2f %10.2f %12.2f\n' "$config" "$case" "$passage" "$setup" "$ratio" "$one"
    echo "$config,$case,$one,$three,$passage,$setup,$ratio" >> "$out/summary.csv"
  done
done
