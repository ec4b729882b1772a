#!/usr/bin/env bash
# What a track layout of several bays costs (the irregular-track chapter):
# growth_discrete.toml over BAYS_LIST (default "1 2 3 5") bays, each with
# the uniform track and with random spacing (2 cm, seed 1), the dynamics
# in every direction (the default) and vertically: the wall time of a
# study of 1 and of 2 passages (median of RUNS, default 1), their
# difference the passage, the rest the set-up (the tables, the creep
# response, the smooth-rail passage). Prints a table; writes
# out/layout_cost/summary.csv.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${CORRUGATION_BIN:-./target/release/corrugation}
[ -n "${CORRUGATION_BIN:-}" ] || cargo build --release --quiet
out=out/layout_cost
mkdir -p "$out"
runs=${RUNS:-1}
source scripts/timing.sh
echo "bays,layout,directions,one_passage_s,two_passages_s,passage_s,setup_s" > "$out/summary.csv"
printf '%-5s %-8s %-10s %10s %10s %10s\n' bays layout directions "passage s" "set-up s" "per bay"
for bays in ${BAYS_LIST:-1 2 3 5}; do
  length=$(echo "$bays * 0.6" | bc -l)
  for layout in uniform random; do
    [ "$layout" = random ] && [ "$bays" = 1 ] && continue
    for directions in all vertical; do
      set=(--set "rail.x_max=$length" --set "passage.end=$length" --set "dynamics.directions=\"$directions\"")
      [ "$layout" = random ] && set+=(--set track.spacing_std=0.02 --set track.seed=1)
      one=$(time_run configs/growth_discrete.toml 1 "${set[@]}")
      two=$(time_run configs/growth_discrete.toml 2 "${set[@]}")
      passage=$(echo "$two - $one" | bc -l)
      setup=$(echo "$one - $passage" | bc -l)
      per=$(echo "$setup / $bays" | bc -l)
      printf '%-5s %-8s %-10s %10.2f %10.2f %10.2f\n' "$bays" "$layout" "$directions" "$passage" "$setup" "$per"
      echo "$bays,$layout,$directions,$one,$two,$passage,$setup" >> "$out/summary.csv"
    done
  done
done
