#!/usr/bin/env bash
# Stability map of the exact transient model (10 x 10) on paper_normal_15mm,
# for each step solver (Newton-Raphson, the reference, and Gauss-Seidel, the
# default): where it converges and how the answer moves, against
#   - the regularisation eps (1e-3 ... 1e-7 m/s),
#   - the step V dt (0.2 ... 3.6 mm, 0.17 ... 3 element lengths),
#   - the force ratio F_x / (mu N_min) up to 0.99,
#   - the normal-force amplitude up to contact loss (F_x = 0, lateral creepage 1e-3).
# Each run's outcome (converged, or the program's error), iterations (Newton or sweeps)
# per step, CPU time, and the centre-line wear difference against the
# baseline (eps 1e-5, 0.2 mm) go to out/stability_map/{newton,gauss-seidel}/stability.{csv,md}.
# About 1 minute on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cargo build --release --quiet
for solver in newton gauss-seidel; do
out=out/stability_map/$solver
mkdir -p "$out/runs"
manifest="$out/manifest.csv"
echo "sweep,value,file,exit_code,message" > "$manifest"
run() { # sweep value --set ...
  local sweep=$1 value=$2; shift 2
  local f="$out/runs/${sweep}_${value}.h5" log="$out/runs/${sweep}_${value}.log"
  rm -f "$f"
  local code=0
  ./target/release/corrugation run configs/paper_normal_15mm.toml -o "$f" --set contact.model=exact-transient \
    --set contact.solver="$solver" \
    --set contact.elements_x=10 --set contact.elements_y=10 --set output.store_fields=false "$@" 2> "$log" || code=$?
  local msg
  msg=$(grep -m1 -A1 "^error" "$log" | tr '\n,|' ' ;/' | cut -c1-200 || true)
  echo "$sweep,$value,$f,$code,$msg" >> "$manifest"
}
run baseline 0
for eps in 1e-3 1e-4 1e-6 1e-7; do run eps "$eps" --set contact.regularisation="$eps"; done
for step in 6e-4 1.2e-3 2.4e-3 3.6e-3; do run step "$step" --set passage.step_length="$step"; done
# N_min = 55 kN, mu = 0.4: mu N_min = 22 kN.
for ratio in 0.5 0.9 0.95 0.99; do
  run force_ratio "$ratio" --set load.longitudinal_force="$(python3 -c "print($ratio * 22e3)")"
done
for amp in 0.45 0.9 0.99 1.2; do
  run n_amplitude "$amp" --set load.longitudinal_force=0 --set rolling.creepage_y=1e-3 --set rail.half_width=0.016 \
    --set load.harmonics[0].amplitude="$(python3 -c "print($amp * 1e5)")"
done
PYTHONPATH=postprocess .venv/bin/python -m corrugation_post stability "$manifest" --out "$out"
done
