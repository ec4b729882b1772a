#!/usr/bin/env bash
# Cost of the exact-transient model against the element count N, for both
# step solvers on the adapted mesh (contact.solver = gauss-seidel | newton)
# and for the fixed grid (0.4, 0.28, 0.2, 0.14 mm elements, dy = 2.5 dx, the
# step the element; N = the elements in contact at the mean load) with both
# of its solvers (contact.solver = cg | gauss-seidel), on a
# whole paper_normal_30mm passage (varying load): wall time per passage
# and per step (median of REPEATS runs, release build), iterations per step
# (Gauss-Seidel sweeps, Newton iterations, or the CG solver's FFT products),
# and the fitted exponent of the
# time per step in N between successive meshes.
# Writes out/solver_scaling/scaling.csv and prints the table. About 12
# minutes on 2 cores (Newton at 20 x 20 is about a minute a run, the fixed
# grid at 0.14 mm about two).
#   REPEATS=1 bash scripts/solver_scaling.sh    # one run per point
#   ADAPTED=0 bash scripts/solver_scaling.sh    # the fixed grid only
set -euo pipefail
cd "$(dirname "$0")/.."
repeats=${REPEATS:-3}
out=out/solver_scaling
bash scripts/setup.sh
cargo build --release --quiet
mkdir -p "$out"
csv="$out/scaling.csv"
echo "solver,n,elements,run,wall_s,steps,iterations_mean" > "$csv"
adapted_solvers="gauss-seidel newton"
[ "${ADAPTED:-1}" = 0 ] && adapted_solvers=""
for solver in $adapted_solvers; do
  if [ "$solver" = newton ]; then meshes="8 10 14 20"; else meshes="8 10 14 20 28"; fi
  for n in $meshes; do
    for r in $(seq 1 "$repeats"); do
      f="$out/${solver}_${n}.h5"
      rm -f "$f"
      start=$(date +%s.%N)
      ./target/release/corrugation run --overwrite configs/paper_normal_30mm.toml -o "$f" --set contact.model=exact-transient \
        --set contact.solver="$solver" --set contact.elements_x="$n" --set contact.elements_y="$n" \
        --set output.store_fields=false > /dev/null 2>&1
      end=$(date +%s.%N)
      stats=$(.venv/bin/python -c "
import h5py, numpy as np
with h5py.File('$f') as h:
    it = h['contact/pass_00000/newton_iterations'][:]
    print(f'{len(it)},{it.mean():.2f}')")
      echo "$solver,$n,$((n * n)),$r,$(python3 -c "print(round($end - $start, 3))"),$stats" >> "$csv"
    done
  done
done
# The fixed grid: N = pi a b / (dx dy) at the mean load (a = 5.957, b = 10.216 mm).
for fixed_solver in cg gauss-seidel; do
for um in 400 280 200 140; do
  dx=$(python3 -c "print($um * 1e-6)")
  for r in $(seq 1 "$repeats"); do
    f="$out/fixed_${fixed_solver}_${um}.h5"
    rm -f "$f"
    start=$(date +%s.%N)
    ./target/release/corrugation run --overwrite configs/paper_normal_30mm.toml -o "$f" --set contact.model=exact-transient \
      --set contact.grid=fixed --set contact.dx="$dx" --set contact.dy="$(python3 -c "print(2.5 * $dx)")" \
      --set passage.step_length="$dx" --set contact.solver="$fixed_solver" --set output.store_fields=false \
      > /dev/null 2>&1
    end=$(date +%s.%N)
    stats=$(.venv/bin/python -c "
import h5py, numpy as np
with h5py.File('$f') as h:
    it = h['contact/pass_00000/newton_iterations'][:]
    print(f'{len(it)},{it.mean():.2f}')")
    elements=$(python3 -c "import math; print(round(math.pi * 5.957e-3 * 10.216e-3 / (2.5 * $dx * $dx)))")
    echo "fixed-$fixed_solver,$um,$elements,$r,$(python3 -c "print(round($end - $start, 3))"),$stats" >> "$csv"
  done
done
done
.venv/bin/python - "$csv" <<'EOF'
import csv, sys, statistics, math
rows = list(csv.DictReader(open(sys.argv[1])))
keys = sorted({(r["solver"], int(r["elements"]), int(r["n"])) for r in rows})
print(f"{'solver':18} {'mesh':>7} {'N':>5} {'wall/passage s':>15} {'ms/step':>9} {'iter/step':>9} {'exponent':>9}")
prev = {}
for solver, elements, n in keys:
    sel = [r for r in rows if r["solver"] == solver and int(r["n"]) == n]
    wall = statistics.median(float(r["wall_s"]) for r in sel)
    step = 1e3 * wall / int(sel[0]["steps"])
    exp = ""
    if solver in prev:
        e0, s0 = prev[solver]
        exp = f"{math.log(step / s0) / math.log(elements / e0):.2f}"
    prev[solver] = (elements, step)
    mesh = f"{n / 1000:.2f} mm" if solver.startswith("fixed") else f"{n:>3}x{n:<3}"
    print(f"{solver:18} {mesh:>7} {elements:>5} {wall:>15.2f} {step:>9.2f} {float(sel[0]['iterations_mean']):>9.1f} {exp:>9}")
EOF
