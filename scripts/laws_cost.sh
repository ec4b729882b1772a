#!/usr/bin/env bash
# What each friction and wear law costs (issue 36's benchmark): one passage
# of configs/growth_exact.toml (the main job: the exact model on the fixed
# grid, Hertz patch) and of configs/growth_discrete.toml (discrete track,
# every direction, the linear profile contact) with each law against the
# defaults (constant friction, Archard): RUNS (default 3) runs of a
# 4-passage study each, release build, this machine's cores; a passage's
# cost is the median over runs of the median CPU time of passages 2-4
# (passes/cpu_seconds: the first passage carries one-off work). Variants
# as in scripts/laws_study.sh, and falling-gs: the falling law on the
# Gauss-Seidel solver throughout (contact.solver = "gauss-seidel"). Prints
# a table; writes out/laws_cost/summary.csv.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${CORRUGATION_BIN:-./target/release/corrugation}
[ -n "${CORRUGATION_BIN:-}" ] || cargo build --release --quiet
out=out/laws_cost
mkdir -p "$out"
runs=${RUNS:-3}
source scripts/timing.sh
echo "config,variant,passage_cpu_s" > "$out/summary.csv"
printf '%-16s %-12s %10s %10s\n' config variant "CPU s" "vs base"
for config in ${CONFIGS:-growth_exact growth_discrete}; do
  base=""
  for v in ${VARIANTS:-base falling falling-gs modifier work map}; do
    case $v in
      base) set=() ;;
      falling) set=(--set material.friction_characteristic=exponential) ;;
      falling-gs) set=(--set material.friction_characteristic=exponential --set contact.solver=gauss-seidel) ;;
      modifier) set=(--set material.friction_characteristic=modifier --set material.friction_coefficient=0.3
        --set material.kinetic_friction=0.35 --set material.friction_speed=0.1) ;;
      work) set=(--set wear.law=frictional-work) ;;
      map) set=(--set wear.law=map) ;;
      *) echo "unknown variant $v" >&2; exit 2 ;;
    esac
    passage=$(for _ in $(seq "$runs"); do
      "$bin" run --overwrite "configs/$config.toml" -o "$out/run.h5" --set growth.passes=4 \
        --set 'growth.contact_history=[]' "${set[@]}" > /dev/null 2>&1
      .venv/bin/python -c "import h5py, numpy; print(numpy.median(h5py.File('$out/run.h5')['passes/cpu_seconds'][1:]))"
    done | median)
    [ -n "$base" ] || base=$passage
    printf '%-16s %-12s %10.2f %10.2f\n' "$config" "$v" "$passage" "$(echo "$passage / $base" | bc -l)"
    echo "$config,$v,$passage" >> "$out/summary.csv"
  done
done
