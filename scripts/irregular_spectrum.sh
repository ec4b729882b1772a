#!/usr/bin/env bash
# The growth spectrum on irregular track (book: docs/src/guide/
# irregular-track.md): pinned_pinned.toml's scene (140 km/h, where the
# pinned-pinned resonance falls near 33 mm and grows) over BAYS (default
# 4) bays, the dynamics vertical, the spectrum's band WMIN-WMAX (default
# 28-42 mm: the pinned-pinned mode's harmonics; on one bay its rate moves
# by 0.003 dB per 1e5 from 28-42 to 22-60 mm) in forward differences:
#   the uniform track; random sleeper spacing of standard deviation 1, 2
#   and 5 cm, SEEDS (default 1 2) each; one failed support (its pad at 20
#   MN/m).
# Writes out/irregular_spectrum/ (OUT to change) and prints the summary
# table (scripts/irregular_spectrum_summary.py): each case's fastest mode,
# its rate, wavelength, support ratio and where in its span it is deepest.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/study_env.sh irregular_spectrum
config=configs/pinned_pinned.toml
bays=${BAYS:-4}
seeds=${SEEDS:-"1 2"}
length=$(echo "$bays * 0.6" | bc -l)
common=(--set "rail.x_max=$length" --set "passage.end=$length" --set 'dynamics.directions="vertical"'
  --set "spectrum.wavelength_min=${WMIN:-0.028}" --set "spectrum.wavelength_max=${WMAX:-0.042}")
failed=$(python3 -c "print(str([2e8] * ($bays - 1) + [2e7]).replace(' ', ''))")
declare -A cases=([uniform]="" [failed_support]="track.pad_stiffness_pattern=$failed")
for std in 0.01 0.02 0.05; do
  for seed in $seeds; do
    cases[spacing_${std}_seed${seed}]="track.spacing_std=$std track.seed=$seed"
  done
done
for name in "${!cases[@]}"; do
  sets=()
  for s in ${cases[$name]}; do sets+=(--set "$s"); done
  "$bin" spectrum "$config" -o "$out/spectrum_$name.h5" --overwrite "${common[@]}" "${sets[@]}" \
    > "$out/spectrum_$name.txt" 2>&1
done
.venv/bin/python scripts/irregular_spectrum_summary.py "$out"
