#!/usr/bin/env bash
# The growth study in the speed-accuracy chart: growth_exact.toml's scene
# (120 mm periodic stretch, 1 um random roughness 10-120 mm, receptance
# dynamics) for 3 passages at a fixed traffic scale of 2e3, every model and
# mesh. Accuracy: the growth rates (dB per 1e5 passages) of the filtered
# profile's harmonics of 10-40 mm in the last passage, against the
# Richardson extrapolation of the fixed grid's 0.3, 0.2 and 0.15 mm runs
# (dy = 2.5 dx; model "exact-fixed", mesh = element length in um; elements
# that divide the 120 mm stretch) with the observed order (relative L2 over
# the harmonics). Cost: CPU time per passage.
# Writes out/growth_accuracy/growth_accuracy.csv and prints the table.
# About 20 minutes on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/fixed_grid_args.sh
out=out/growth_accuracy
bash scripts/setup.sh
cargo build --release --quiet
mkdir -p "$out/runs"
manifest="$out/manifest.csv"
echo "model,mesh,file" > "$manifest"
run() { # model mesh [overrides...] (default: the model on an n x n mesh)
  local model=$1 mesh=$2
  shift 2
  local f="$out/runs/${model}_${mesh}.h5"
  local set=(--set contact.model="$model" --set contact.grid=adapted --set passage.step_length=2e-4
             --set contact.elements_x="$mesh" --set contact.elements_y="$mesh")
  [ $# -gt 0 ] && set=("$@")
  rm -f "$f"
  ./target/release/corrugation run --overwrite configs/growth_exact.toml -o "$f" "${set[@]}" --set growth.passes=3 \
    --set growth.adaptive=false --set growth.traffic_scale=2e3 --set growth.contact_history=[0] \
    --set output.store_fields=false > "$out/runs/${model}_${mesh}.log" 2>&1
  echo "$model,$mesh,$f" >> "$manifest"
}
for n in 10 14 20 28; do run exact-transient "$n"; done
for um in 400 300 200 150; do
  fixed_grid_args "$um"
  run exact-fixed "$um" "${fixed_args[@]}"
done
for n in 10 20 40; do run simplified-transient "$n"; run fastsim "$n"; done
.venv/bin/corrugation-post growth-accuracy "$manifest" --out "$out"
