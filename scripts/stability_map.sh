#!/usr/bin/env bash
# Stability map of the exact transient model on paper_normal_15mm: where it
# converges and how the answer moves, for
#   - the adapted mesh (10 x 10) with each step solver (Newton-Raphson, the
#     reference, and Gauss-Seidel, the default);
#   - the fixed grid (0.2 x 0.5 mm, the default) with each friction law
#     (regularised, the default, and exact Coulomb), and with the
#     third-order difference;
# against
#   - the regularisation eps (1e-3 ... 1e-7 m/s; not for Coulomb),
#   - the step V dt (adapted: 0.2 ... 3.6 mm, 0.17 ... 3 element lengths;
#     fixed grid: the step is the element, 0.1 ... 0.8 mm with dy = 2.5 dx),
#   - the force ratio F_x / (mu N_min) up to 0.99,
#   - the normal-force amplitude up to contact loss (F_x = 0, lateral creepage 1e-3).
# Each run's outcome (converged, or the program's error), iterations (Newton or sweeps)
# per step, CPU time, and the centre-line wear difference against the
# variant's baseline go to out/stability_map/<variant>/stability.{csv,md}.
# The fixed grid's three variants take about a minute on 2 cores; the adapted
# mesh's two (Newton, Gauss-Seidel) take the rest.
#   VARIANTS="fixed-regularised fixed-third-order" bash scripts/stability_map.sh   # some variants
# A fixed-grid step the CG solver does not converge goes to Gauss-Seidel with a
# warning in the run's log (out/stability_map/<variant>/runs/*.log).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cargo build --release --quiet
for variant in ${VARIANTS:-newton gauss-seidel fixed-regularised fixed-coulomb fixed-third-order}; do
out=out/stability_map/$variant
mkdir -p "$out/runs"
manifest="$out/manifest.csv"
echo "sweep,value,file,exit_code,message" > "$manifest"
case $variant in
  newton|gauss-seidel) base=(--set contact.solver="$variant" --set contact.elements_x=10 --set contact.elements_y=10) ;;
  fixed-third-order) base=(--set contact.grid=fixed --set contact.scheme=third-order --set contact.dx=2e-4
                           --set contact.dy=5e-4) ;;
  fixed-*) base=(--set contact.grid=fixed --set contact.friction_law="${variant#fixed-}" --set contact.dx=2e-4
                 --set contact.dy=5e-4) ;;
esac
run() { # sweep value --set ...
  local sweep=$1 value=$2; shift 2
  local f="$out/runs/${sweep}_${value}.h5" log="$out/runs/${sweep}_${value}.log"
  rm -f "$f"
  local code=0
  ./target/release/corrugation run --overwrite configs/paper_normal_15mm.toml -o "$f" --set contact.model=exact-transient \
    "${base[@]}" --set output.store_fields=false "$@" 2> "$log" || code=$?
  local msg
  msg=$(grep -m1 -A1 "^error" "$log" | tr '\n,|' ' ;/' | cut -c1-200 || true)
  echo "$sweep,$value,$f,$code,$msg" >> "$manifest"
}
run baseline 0
if [ "$variant" != fixed-coulomb ]; then
  for eps in 1e-3 1e-4 1e-6 1e-7; do run eps "$eps" --set contact.regularisation="$eps"; done
fi
case $variant in
  fixed-*) for dx in 1e-4 4e-4 8e-4; do
             run step "$dx" --set contact.dx="$dx" --set passage.step_length="$dx" \
               --set contact.dy="$(python3 -c "print(2.5 * $dx)")"
           done ;;
  *) for step in 6e-4 1.2e-3 2.4e-3 3.6e-3; do run step "$step" --set passage.step_length="$step"; done ;;
esac
# N_min = 55 kN, mu = 0.4: mu N_min = 22 kN.
for ratio in 0.5 0.9 0.95 0.99; do
  run force_ratio "$ratio" --set load.longitudinal_force="$(python3 -c "print($ratio * 22e3)")"
done
for amp in 0.45 0.9 0.99 1.2; do
  run n_amplitude "$amp" --set load.longitudinal_force=0 --set rolling.creepage_y=1e-3 --set rail.half_width=0.016 \
    --set load.harmonics[0].amplitude="$(python3 -c "print($amp * 1e5)")"
done
.venv/bin/corrugation-post stability "$manifest" --out "$out"
done
