#!/usr/bin/env bash
# What each friction and wear law costs (issue 36's benchmark): one passage
# of configs/growth_exact.toml (the main job: the exact model on the fixed
# grid, Hertz patch) and of configs/growth_discrete.toml (discrete track,
# every direction, the linear profile contact) with each law against the
# defaults (constant friction, Archard). For each, the median of RUNS
# (default 3) runs of a 1- and a 2-passage study, release build, this
# machine's cores: the difference is one passage. Variants as in
# scripts/laws_study.sh, and falling-cg: the falling law with the CG solver
# forced (contact.solver = "cg": its steps that stall go to Gauss-Seidel).
# Prints a table; writes out/laws_cost/summary.csv.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${CORRUGATION_BIN:-./target/release/corrugation}
[ -n "${CORRUGATION_BIN:-}" ] || cargo build --release --quiet
out=out/laws_cost
mkdir -p "$out"
runs=${RUNS:-3}
source scripts/timing.sh
echo "config,variant,one_passage_s,two_passages_s,passage_s" > "$out/summary.csv"
printf '%-16s %-12s %10s %10s\n' config variant "passage s" "vs base"
for config in ${CONFIGS:-growth_exact growth_discrete}; do
  base=""
  for v in ${VARIANTS:-base falling falling-cg modifier work map}; do
    case $v in
      base) set=() ;;
      falling) set=(--set material.friction_characteristic=exponential) ;;
      falling-cg) set=(--set material.friction_characteristic=exponential --set contact.solver=cg) ;;
      modifier) set=(--set material.friction_characteristic=modifier --set material.friction_coefficient=0.3
        --set material.kinetic_friction=0.35 --set material.friction_speed=0.1) ;;
      work) set=(--set wear.law=frictional-work) ;;
      map) set=(--set wear.law=map) ;;
      *) echo "unknown variant $v" >&2; exit 2 ;;
    esac
    one=$(time_run "configs/$config.toml" 1 "${set[@]}")
    two=$(time_run "configs/$config.toml" 2 "${set[@]}")
    passage=$(echo "$two - $one" | bc -l)
    [ -n "$base" ] || base=$passage
    printf '%-16s %-12s %10.2f %10.2f\n' "$config" "$v" "$passage" "$(echo "$passage / $base" | bc -l)"
    echo "$config,$v,$one,$two,$passage" >> "$out/summary.csv"
  done
done
