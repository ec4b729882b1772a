#!/usr/bin/env bash
# The growth study in the speed-accuracy chart: growth_exact.toml's scene
# (120 mm periodic stretch, 1 um random roughness 10-120 mm, receptance
# dynamics) for 3 passages at a fixed traffic scale of 2e3, every model and
# mesh. Accuracy: the growth rates (dB per 1e5 passages) of the filtered
# profile's harmonics of 10-40 mm in the last passage, against the
# Richardson extrapolation of exact 14, 20 and 28 with the observed order
# (relative L2 over the harmonics). Cost: CPU time per passage.
# Writes out/growth_accuracy/growth_accuracy.csv and prints the table.
# About 6 minutes on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."
out=out/growth_accuracy
bash scripts/setup.sh
cargo build --release --quiet
mkdir -p "$out/runs"
manifest="$out/manifest.csv"
echo "model,mesh,file" > "$manifest"
run() { # model mesh
  local f="$out/runs/$1_$2.h5"
  rm -f "$f"
  ./target/release/corrugation run configs/growth_exact.toml -o "$f" --set contact.model="$1" \
    --set contact.elements_x="$2" --set contact.elements_y="$2" --set growth.passes=3 \
    --set growth.adaptive=false --set growth.traffic_scale=2e3 --set growth.contact_history=[0] \
    --set output.store_fields=false > "$out/runs/$1_$2.log" 2>&1
  echo "$1,$2,$f" >> "$manifest"
}
for n in 10 14 20 28; do run exact-transient "$n"; done
for n in 10 20 40; do run simplified-transient "$n"; run fastsim "$n"; done
PYTHONPATH=postprocess .venv/bin/python -m corrugation_post growth-accuracy "$manifest" --out "$out"
