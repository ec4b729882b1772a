#!/usr/bin/env bash
# Convergence of the exact-transient model on both discretisations, on the
# four paper scenes: the fixed grid refined with a constant element shape
# (contact.dx = 0.4, 0.28, 0.2, 0.14 mm, dy = 2.5 dx, the step the element)
# and the adapted mesh (20, 28, 40) with its step refined alongside (0.2,
# 0.143, 0.1 mm: at the configs' fixed 0.2 mm the adapted mesh converges to
# the first-order-in-time answer, some 8 % low in wear). For each scene and
# discretisation the three finest runs give
# the observed order and the Richardson limit of the mean wear, its first
# harmonic (amplitude relative to the mean, phase) and the mean creepage;
# every run's error is taken against the fixed grid's limit, and the two
# limits are compared. Writes out/grid_convergence/{grid_convergence,grid_limits}.csv.
#   bash scripts/grid_convergence.sh           # about an hour on 2 cores
#   bash scripts/grid_convergence.sh --quick   # one scene, coarse grids (~1 minute)
set -euo pipefail
cd "$(dirname "$0")/.."
out=out/grid_convergence
scenes=(paper_normal_30mm paper_normal_15mm paper_longitudinal_30mm paper_longitudinal_15mm)
fixed=(4e-4 2.8e-4 2e-4 1.4e-4)
adapted=(20 28 40)
if [ "${1:-}" = "--quick" ]; then
  scenes=(paper_normal_30mm); fixed=(8e-4 5.6e-4 4e-4); adapted=(8 10 14); out=out/grid_convergence_quick
fi
bash scripts/setup.sh
cargo build --release --quiet
mkdir -p "$out/runs"
manifest="$out/manifest.csv"
echo "scene,grid,size,file" > "$manifest"
run() { # scene grid size overrides...
  local scene=$1 grid=$2 size=$3
  shift 3
  local f="$out/runs/${scene}_${grid}_${size}.h5"
  rm -f "$f"
  ./target/release/corrugation run --overwrite "configs/$scene.toml" -o "$f" --set contact.model=exact-transient \
    --set output.store_fields=false "$@" 2> "$f.log"
  echo "$scene,$grid,$size,$f" >> "$manifest"
}
for scene in "${scenes[@]}"; do
  for dx in "${fixed[@]}"; do
    dy=$(python3 -c "print(2.5 * $dx)")
    run "$scene" fixed "$dx" --set contact.grid=fixed --set contact.dx="$dx" --set contact.dy="$dy" \
      --set passage.step_length="$dx"
  done
  for n in "${adapted[@]}"; do
    run "$scene" adapted "$n" --set contact.elements_x="$n" --set contact.elements_y="$n" \
      --set passage.step_length="$(python3 -c "print(4e-3 / $n)")"
  done
  echo "$scene done" >&2
done
.venv/bin/corrugation-post grid-convergence "$manifest" --out "$out"
