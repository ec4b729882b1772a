#!/usr/bin/env bash
# Growth-rate spectra of the normal-contact chains on one set of harmonics:
# one passage at m = 1e3 over nine equal 1 um harmonics (the scene's
# stretch divided into 10, 12, 15, 17.1, 20, 24, 30, 40 and 60 mm on
# growth_exact.toml's scene; 15, 17.1, 20, 24, 30, 33.3, 40, 50 and 60 mm on
# growth_discrete.toml's sleeper bay), 40 mm run-in, for
#   - "hertz" (the paper's chain), "linear" and "auto" (the default) on the
#     0.4 mm fixed grid,
#   - the nonlinear profile contact on the 0.4 and 0.2 mm grids (the
#     reference),
#   - the linear contact on the 0.2 mm grid,
#   - FASTSIM with the linear contact (growth_exact's scene only).
# Writes out/chain_spectra/rates.csv and prints the tables (book, The
# consistent chain). About 15 minutes on 2 cores (DISCRETE=0: 3).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cargo build --release --quiet
out=out/chain_spectra
mkdir -p "$out/runs"
csv="$out/rates.csv"
echo "scene,chain,wavelength,rate_db_per_1e5,cpu_s,profile_contact" > "$csv"
bin=./target/release/corrugation
fine=(--set contact.dx=2e-4 --set contact.dy=5e-4 --set passage.step_length=2e-4)
run() { # scene config harmonics name [--set ...]
  local scene=$1 cfg=$2 harmonics=$3 name=$4
  shift 4
  local f="$out/runs/${scene}_${name}.h5"
  "$bin" run --overwrite "$cfg" -o "$f" --set growth.passes=1 --set growth.adaptive=false \
    --set growth.traffic_scale=1e3 --set growth.store_every=1 --set growth.checkpoint_every=1 \
    --set "growth.contact_history=[]" --set roughness.kind=harmonics --set "roughness.harmonics=$harmonics" \
    --set rail.half_width=0.02 --set passage.start=-0.04 "$@" 2> "$out/runs/${scene}_${name}.log"
  .venv/bin/python - "$f" "$scene" "$name" "$harmonics" >> "$csv" <<'PY'
import re, sys, h5py, numpy as np
f, scene, name, harmonics = sys.argv[1:]
lams = [float(v) for v in re.findall(r"wavelength = ([0-9.e-]+)", harmonics)]
with h5py.File(f) as h:
    wl = h["passes/wavelength"][:]
    for lam in lams:
        i = int(np.argmin(abs(wl - lam)))
        print(f"{scene},{name},{lam},{h['passes/growth_rate'][-1][i]:.4f},{h['passes/cpu_seconds'][-1]:.2f},"
              f"{h['passes/profile_contact'][-1]:.0f}")
PY
}
nine() { # wavelengths...
  local s="["
  for l in "$@"; do s="$s{amplitude = 1e-6, wavelength = $l}, "; done
  echo "${s%, }]"
}
four_contacts() { # scene config harmonics: each normal contact on the 0.4 mm grid
  for c in hertz linear auto profile; do
    if [ "$c" = auto ]; then
      run "$1" "$2" "$3" auto_0.4mm
    else
      run "$1" "$2" "$3" "${c}_0.4mm" --set contact.normal="$c"
    fi
  done
}
exact=configs/growth_exact.toml
h=$(nine 0.010 0.012 0.015 0.0171428571428571 0.020 0.024 0.030 0.040 0.060)
four_contacts exact $exact "$h"
run exact $exact "$h" linear_0.2mm --set contact.normal=linear "${fine[@]}"
run exact $exact "$h" profile_0.2mm --set contact.normal=profile "${fine[@]}"
run exact configs/growth_fastsim.toml "$h" fastsim_linear --set contact.normal=linear
if [ "${DISCRETE:-1}" = 1 ]; then
  d=configs/growth_discrete.toml
  h=$(nine 0.015 0.0171428571428571 0.020 0.024 0.030 0.0333333333333333 0.040 0.050 0.060)
  four_contacts discrete $d "$h"
fi
.venv/bin/python - "$csv" <<'PY'
import csv, sys
from collections import defaultdict
rows = list(csv.DictReader(open(sys.argv[1])))
for scene in ("exact", "discrete"):
    table = defaultdict(dict)
    cpu, lams = {}, []
    for r in rows:
        if r["scene"] != scene:
            continue
        lam = float(r["wavelength"])
        lams.append(lam) if lam not in lams else None
        table[r["chain"]][lam] = float(r["rate_db_per_1e5"])
        cpu[r["chain"]] = (r["cpu_s"], r["profile_contact"])
    if not table:
        continue
    print(f"\n{scene}: growth rate (dB per 1e5 passages), nine 1 um harmonics, one passage at m = 1e3")
    print("| chain | " + " | ".join(f"{1e3 * l:.1f}" for l in lams) + " | CPU s | profile_contact |")
    print("|---|" + "---|" * (len(lams) + 2))
    for chain, rates in table.items():
        print(f"| {chain} | " + " | ".join(f"{rates[l]:+.2f}" for l in lams) + f" | {cpu[chain][0]} | {cpu[chain][1]} |")
PY
