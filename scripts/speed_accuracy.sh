#!/usr/bin/env bash
# Speed against accuracy of the contact models on the paper scenes: every
# model over a range of meshes, and the exact model on the fixed grid
# ("exact-fixed", mesh = element length in um, dy = 2.5 dx), CPU time per
# passage (median of 3 repeats for FASTSIM and simplified-transient, one run
# of the exact model), errors against each scene's reference run (centre-line
# wear profile, its first harmonic's amplitude and phase, creepage history):
# the fixed grid at 0.14 mm, within 0.1-1 % of the grid limit
# (scripts/grid_convergence.sh).
# Writes out/speed_accuracy/{speed_accuracy.csv,speed_accuracy.png}.
#   bash scripts/speed_accuracy.sh           # 4 scenes (~3 min)
#   bash scripts/speed_accuracy.sh --quick   # one scene, coarse meshes, reference fixed 0.2 mm (~1 min)
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/fixed_grid_args.sh
out=out/speed_accuracy
if [ "${1:-}" = "--quick" ]; then
  scenes=(paper_normal_30mm); cheap=(6 10); exact=(6); fixed=(800 400); ref=200; out=out/speed_accuracy_quick
else
  scenes=(paper_normal_30mm paper_normal_15mm paper_longitudinal_30mm paper_longitudinal_15mm)
  cheap=(6 10 14 20 30 40); exact=(6 10 14 20); fixed=(400 280 200); ref=140
fi
bash scripts/setup.sh
cargo build --release --quiet
mkdir -p "$out/runs"
manifest="$out/manifest.csv"
failures=0
echo "scene,model,mesh,file,reference" > "$manifest"
run() { # scene model mesh repeat reference
  local f="$out/runs/$1_$2_$3_r$4.h5"
  local set=(--set contact.model="$2" --set contact.elements_x="$3" --set contact.elements_y="$3")
  if [ "$2" = exact-fixed ]; then
    fixed_grid_args "$3"
    set=("${fixed_args[@]}")
  fi
  rm -f "$f"
  if ./target/release/corrugation run --overwrite "configs/$1.toml" -o "$f" "${set[@]}" --set output.store_fields=false \
    2> "$f.log"; then
    echo "$1,$2,$3,$f,$5" >> "$manifest"
  else
    echo "$1 $2 $3: failed, left out:" >&2
    grep -m1 -A1 "^error" "$f.log" >&2 || true
    failures=$((failures + 1))
  fi
}
for scene in "${scenes[@]}"; do
  run "$scene" exact-fixed "$ref" 1 1
  for um in "${fixed[@]}"; do run "$scene" exact-fixed "$um" 1 0; done
  for n in "${exact[@]}"; do run "$scene" exact-transient "$n" 1 0; done
  for model in fastsim simplified-transient; do
    for n in "${cheap[@]}"; do for r in 1 2 3; do run "$scene" "$model" "$n" "$r" 0; done; done
  done
  echo "$scene done" >&2
done
.venv/bin/corrugation-post speed-accuracy "$manifest" --out "$out"
if [ "$failures" -gt 0 ]; then
  echo "$failures run(s) failed and are missing from the table" >&2
  exit 1
fi
