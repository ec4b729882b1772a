#!/usr/bin/env bash
# The accuracy map behind contact.model = "auto": the centre-line wear error
# and the CPU cost per step of every model and mesh against lambda / 2a.
#
# Scenes: paper_normal_30mm (N = 100 kN + 45 kN sin, F_x = 20 kN, V = 100
# km/h, eps = 1e-5 m/s, V dt = 0.2 mm) with the load wavelength set to
# 10, 15, 20, 30, 45, 60 mm (lambda / 2a_max = 0.74 ... 4.45); a run-in of one
# wavelength (at least 20 mm), one recorded wavelength.
# Models: exact-transient (Gauss-Seidel) at 6, 8, 10, 14, 20, 28 (adapted
# mesh, 0.2 mm steps) and on the fixed grid ("exact-fixed", mesh = element
# length in um: 400, 280, 200, 140, dy = 2.5 dx, the step the element);
# simplified-transient and FASTSIM at 10, 20, 40. Reference per wavelength:
# Richardson extrapolation of the fixed grid's 0.28, 0.2 and 0.14 mm wear
# profiles with the observed order (corrugation_post accuracy-map). The
# cost column is CPU time per 0.2 mm rolled (a step of the adapted mesh).
#
# Writes out/accuracy_map/accuracy_map.{csv,png} and, with --install, copies
# the CSV to src/model_choice/accuracy_map.csv (the table compiled into the
# binary) and the chart to docs/src/figures/accuracy_map.png.
# About 3 minutes on 2 cores (25 before the fixed grid's symmetric products).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/fixed_grid_args.sh
install=0
[ "${1:-}" = "--install" ] && install=1
out=out/accuracy_map
bash scripts/setup.sh
cargo build --release --quiet
mkdir -p "$out/runs"
manifest="$out/manifest.csv"
echo "wavelength,model,mesh,file" > "$manifest"
for lambda in 0.010 0.015 0.020 0.030 0.045 0.060; do
  start=$(python3 -c "print(-max($lambda, 0.020))")
  end=$(python3 -c "print($lambda + 0.010)")
  run() { # model mesh
    local f="$out/runs/${lambda}_$1_$2.h5"
    local set=(--set contact.model="$1" --set contact.elements_x="$2" --set contact.elements_y="$2")
    if [ "$1" = exact-fixed ]; then
      fixed_grid_args "$2"
      set=("${fixed_args[@]}")
    fi
    rm -f "$f"
    ./target/release/corrugation run --overwrite configs/paper_normal_30mm.toml -o "$f" "${set[@]}" --set output.store_fields=false \
      --set "load.harmonics[0].wavelength=$lambda" --set passage.start="$start" --set passage.end="$end" \
      --set rail.x_max="$lambda" > "$out/runs/${lambda}_$1_$2.log" 2>&1
    echo "$lambda,$1,$2,$f" >> "$manifest"
  }
  for n in 6 8 10 14 20 28; do run exact-transient "$n"; done
  for um in 400 280 200 140; do run exact-fixed "$um"; done
  for n in 10 20 40; do run simplified-transient "$n"; run fastsim "$n"; done
done
.venv/bin/corrugation-post accuracy-map "$manifest" --out "$out"
if [ "$install" = 1 ]; then
  cp "$out/accuracy_map.csv" src/model_choice/accuracy_map.csv
  cp "$out/accuracy_map.png" docs/src/figures/accuracy_map.png
  echo "installed src/model_choice/accuracy_map.csv (rebuild to use it)"
fi
