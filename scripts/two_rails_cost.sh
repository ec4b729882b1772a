#!/usr/bin/env bash
# What a curve's two rails cost (issue 34's benchmark): one passage of
# configs/curve_two_rails.toml (both rails: lateral creepage and spin on
# both, the full products) against today's straight single-contact passage
# on the same grid (the same config with its [second_rail] section removed,
# rolling.creepage_y = 0 and rolling.spin = 0). For each, the median of
# RUNS (default 3) runs of a 1- and a 2-passage study, release build, this
# machine's cores: the difference is one passage; the rest of the
# 1-passage run is the set-up (the receptance tables in three directions,
# the creep response of each rail's contact, the smooth-rail passage on the
# discrete track). Prints a table; writes out/two_rails_cost/summary.csv.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${CORRUGATION_BIN:-./target/release/corrugation}
[ -n "${CORRUGATION_BIN:-}" ] || cargo build --release --quiet
out=out/two_rails_cost
mkdir -p "$out"
runs=${RUNS:-3}
# The straight single contact: the curve config without its second rail.
awk '/^\[second_rail\]/ {skip = 1; next} /^\[/ {skip = 0} !skip' configs/curve_two_rails.toml \
  > "$out/straight.toml"
cp configs/curve_two_rails.toml "$out/curve.toml"
source scripts/timing.sh
echo "case,one_passage_s,two_passages_s,passage_s,setup_s" > "$out/summary.csv"
printf '%-10s %10s %10s %10s\n' case "passage s" "set-up s" "1 pass s"
for case in straight curve; do
  case $case in
    straight) set=(--set rolling.creepage_y=0 --set rolling.spin=0) ;;
    curve) set=() ;;
  esac
  one=$(time_run "$out/$case.toml" 1 "${set[@]}")
  two=$(time_run "$out/$case.toml" 2 "${set[@]}")
  passage=$(echo "$two - $one" | bc -l)
  setup=$(echo "$one - $passage" | bc -l)
  printf '%-10s %10.2f %10.2f %10.2f\n' "$case" "$passage" "$setup" "$one"
  echo "$case,$one,$two,$passage,$setup" >> "$out/summary.csv"
done
awk -F, 'NR == 2 {s = $4} NR == 3 {c = $4} END {printf "curve (two rails) / straight (one contact), one passage: %.2f (issue 34: at most 2.5)\n", c / s}' \
  "$out/summary.csv"
