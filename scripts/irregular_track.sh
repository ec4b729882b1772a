#!/usr/bin/env bash
# Irregular track (book: docs/src/guide/irregular-track.md): what a track
# layout of unequal bays does to the receptance and to what grows, on
# growth_discrete.toml's track over BAYS (default 10) bays, the dynamics
# vertical (dynamics.directions = "vertical": the layout's tables in every
# direction cost minutes at 10 bays).
#   receptances (corrugation track, POINTS frequencies over 20-5000 Hz,
#     default 1921: a ratio of 1.0029, the peaks converged to about 0.2 %):
#     the uniform track; random sleeper
#     spacing of standard deviation 1, 2 and 5 cm, SEEDS (default 1 2 3 4
#     5) each; pads of mixed stiffness (100 and 300 MN/m alternating);
#     one failed support in ten (its pad at 20 MN/m);
#   growth (corrugation run, PASSES passages, default 3): the uniform
#     track, spacing 2 and 5 cm with the first seed, the mixed pads, the
#     failed support.
# Writes out/irregular_track/ (OUT to change) and prints the summary
# tables (scripts/irregular_summary.py).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/study_env.sh irregular_track
config=configs/growth_discrete.toml
bays=${BAYS:-10}
seeds=${SEEDS:-"1 2 3 4 5"}
passes=${PASSES:-3}
points=${POINTS:-1921}
length=$(echo "$bays * 0.6" | bc -l)
common=(--set "rail.x_max=$length" --set "passage.end=$length" --set 'dynamics.directions="vertical"')
# Lists without spaces: each case's overrides split on spaces.
failed=$(python3 -c "print(str([2e8] * ($bays - 1) + [2e7]).replace(' ', ''))")
declare -A cases=(
  [uniform]=""
  [mixed_pads]="track.pad_stiffness_pattern=[1e8,3e8]"
  [failed_support]="track.pad_stiffness_pattern=$failed"
)
for std in 0.01 0.02 0.05; do
  for seed in $seeds; do
    cases[spacing_${std}_seed${seed}]="track.spacing_std=$std track.seed=$seed"
  done
done
first=${seeds%% *}
grow=(uniform mixed_pads failed_support "spacing_0.02_seed$first" "spacing_0.05_seed$first")
for name in "${!cases[@]}"; do
  sets=()
  for s in ${cases[$name]}; do sets+=(--set "$s"); done
  "$bin" track "$config" -o "$out/track_$name.h5" --overwrite --points "$points" "${common[@]}" "${sets[@]}" \
    > "$out/track_$name.txt"
  if [[ " ${grow[*]} " == *" $name "* ]]; then
    "$bin" run "$config" -o "$out/run_$name.h5" --overwrite "${common[@]}" "${sets[@]}" \
      --set "growth.passes=$passes" --set 'growth.contact_history=[]' > "$out/run_$name.txt" 2>&1
  fi
done
.venv/bin/python scripts/irregular_summary.py "$out"
