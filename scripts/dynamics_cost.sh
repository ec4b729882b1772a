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
source scripts/timing.sh
echo "config,case,one_passage_s,three_passages_s,passage_s,setup_s,setup_in_passages" > "$out/summary.csv"
printf '%-16s %-10s %10s %10s %10s %12s\n' config case "passage s" "set-up s" "set-up/pass" "1 pass s"
for config in growth_exact growth_discrete; do
  for case in vertical steady transient; do
    case $case in
      vertical) set=(--set dynamics.directions=vertical) ;;
      steady) set=(--set dynamics.directions=all --set dynamics.creep_forces=steady) ;;
      transient) set=(--set dynamics.directions=all --set dynamics.creep_forces=transient) ;;
    esac
    one=$(time_run "configs/$config.toml" 1 "${set[@]}")
    three=$(time_run "configs/$config.toml" 3 "${set[@]}")
    passage=$(echo "($three - $one) / 2" | bc -l)
    setup=$(echo "$one - $passage" | bc -l)
    ratio=$(echo "$setup / $passage" | bc -l)
    printf '%-16s %-10s %10.2f %10.2f %10.2f %12.2f\n' "$config" "$case" "$passage" "$setup" "$ratio" "$one"
    echo "$config,$case,$one,$three,$passage,$setup,$ratio" >> "$out/summary.csv"
  done
done
