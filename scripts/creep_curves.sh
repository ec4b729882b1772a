#!/usr/bin/env bash
# Creep curves with each friction characteristic (the book's friction and
# wear chapter): examples/creep_curves.rs (FASTSIM and the exact model on
# the 0.5 mm fixed grid, the paper's patch at 100 km/h) to
# out/creep_curves.csv, drawn to docs/src/figures/friction_creep_curves.png.
# About 10 s on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
mkdir -p out
cargo run --release --quiet --example creep_curves > out/creep_curves.csv
.venv/bin/python - <<'PY'
import csv
import math
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

curves = defaultdict(list)
with open("out/creep_curves.csv") as f:
    for r in csv.DictReader(f):
        curves[(r["model"], r["law"])].append(
            (float(r["creepage"]), float(r["force_ratio"]), float(r["force_ratio_min"]), float(r["force_ratio_max"]))
        )
fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), sharey=True)
for ax, model in zip(axes, ["fastsim", "exact grid"]):
    for (m, law), pts in curves.items():
        if m != model:
            continue
        pts = [p for p in pts if not math.isnan(p[1])]
        xs = [p[0] * 100 for p in pts]
        (line,) = ax.semilogx(xs, [p[1] for p in pts], marker="." if model != "fastsim" else None, label=law)
        if model != "fastsim":
            ax.fill_between(xs, [p[2] for p in pts], [p[3] for p in pts], color=line.get_color(), alpha=0.2)
    ax.set_title("FASTSIM, 40 x 40" if model == "fastsim" else "exact model, 0.5 mm grid (band: last 20 steps)")
    ax.set_xlabel("longitudinal creepage (%)")
    ax.grid(True, which="both", alpha=0.3)
axes[0].set_ylabel("F_x / N (mu = 0.4 at zero slip)")
axes[0].legend(fontsize=8)
fig.suptitle("Creep curves of the paper's patch at 100 km/h, N = 100 kN, by friction characteristic")
fig.tight_layout()
fig.savefig("docs/src/figures/friction_creep_curves.png", dpi=110)
print("wrote docs/src/figures/friction_creep_curves.png")
PY
