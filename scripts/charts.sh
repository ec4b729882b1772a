#!/usr/bin/env bash
# Every speed/accuracy study of the README in one command: the accuracy map
# behind contact.model = "auto" (installed into the source and
# docs/figures), the speed-accuracy chart of the four paper scenes, the
# growth-rate accuracy of a growth study, the stability map of both
# exact-model solvers, and the cost of the exact model against N (one run per
# point). About 6 minutes on 2 cores (20 on an older machine); the output
# folders are those of the five scripts (out/accuracy_map, out/speed_accuracy,
# out/growth_accuracy, out/stability_map, out/solver_scaling).
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
bash scripts/accuracy_map.sh --install
bash scripts/speed_accuracy.sh
bash scripts/growth_accuracy.sh
bash scripts/stability_map.sh
REPEATS=1 bash scripts/solver_scaling.sh
echo "all studies: $(( $(date +%s) - start )) s"
