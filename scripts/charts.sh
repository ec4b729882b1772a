#!/usr/bin/env bash
# Every speed/accuracy study of the book in one command: the accuracy map
# behind contact.model = "auto" (installed into the source and
# docs/src/figures), the speed-accuracy chart of the four paper scenes, the
# growth-rate accuracy of a growth study, the stability map of both
# exact-model solvers and both fixed-grid friction laws, the convergence of
# both discretisations of the exact model, and the cost of the exact model
# against N (one run per point). Two and a half hours on 2 cores when the
# fixed grid ran Gauss-Seidel; since its CG solver the fixed grid's runs take
# minutes and the adapted mesh's finest runs and the growth study most of
# the rest; the output folders are those of the
# six scripts (out/accuracy_map, out/speed_accuracy, out/growth_accuracy,
# out/stability_map, out/grid_convergence, out/solver_scaling).
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
bash scripts/accuracy_map.sh --install
bash scripts/speed_accuracy.sh
bash scripts/growth_accuracy.sh
bash scripts/stability_map.sh
bash scripts/grid_convergence.sh
REPEATS=1 bash scripts/solver_scaling.sh
echo "all studies: $(( $(date +%s) - start )) s"
