#!/usr/bin/env bash
# The growth rate of one corrugation harmonic under each normal-contact
# chain, on growth_exact.toml's scene (100 kN, 20 kN, 100 km/h, receptance
# dynamics or imposed loads): one passage at m = 1e3 over a single harmonic
# of 15, 30 or 60 mm at a few amplitudes, for
#   - the nonlinear profile contact on the fixed grid at 0.4 and 0.2 mm (the
#     reference: the full contact; amplitudes where its patch moves over
#     several elements),
#   - contact.normal = "auto" on the fixed grid (the default),
#   - the linear profile contact on the fixed grid at 0.4 and 0.2 mm,
#   - the Hertz chain (contact.normal = "hertz"),
#   - the linear profile contact on the adapted mesh: the exact model
#     (20 x 20, 0.2 mm steps; 28 x 28, 0.143 mm), the simplified transient
#     model (20 x 20) and FASTSIM (40 x 40).
# Writes out/consistent_chain/rates.csv and prints the table (the book's,
# The consistent chain). About 30 minutes on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cargo build --release --quiet
out=out/consistent_chain
mkdir -p "$out/runs"
csv="$out/rates.csv"
echo "chain,dynamics,wavelength,amplitude,rate_db_per_1e5,cpu_s" > "$csv"
bin=./target/release/corrugation
run() { # name config dynamics wavelength amplitude [--set ...]
  local name=$1 cfg=$2 dyn=$3 lam=$4 amp=$5
  shift 5
  local f="$out/runs/${name}_${dyn}_${lam}_${amp}.h5"
  rm -f "$f"
  "$bin" run --overwrite "$cfg" -o "$f" --set growth.passes=1 --set growth.adaptive=false --set growth.traffic_scale=1e3 \
    --set growth.store_every=1 --set growth.checkpoint_every=1 --set "growth.contact_history=[]" \
    --set roughness.kind=harmonics --set "roughness.harmonics=[{amplitude = $amp, wavelength = $lam}]" \
    --set rail.half_width=0.02 --set dynamics.model="$dyn" "$@" 2> "$out/runs/${name}_${dyn}_${lam}_${amp}.log"
  .venv/bin/python - "$f" "$lam" "$name" "$dyn" "$amp" >> "$csv" <<'EOF'
import sys, h5py, numpy as np
f, lam, name, dyn, amp = sys.argv[1], float(sys.argv[2]), *sys.argv[3:]
with h5py.File(f) as h:
    i = int(np.argmin(abs(h["passes/wavelength"][:] - lam)))
    print(f"{name},{dyn},{lam},{amp},{h['passes/growth_rate'][-1][i]:.4f},{h['passes/cpu_seconds'][-1]:.2f}")
EOF
}
exact=configs/growth_exact.toml
fast=configs/growth_fastsim.toml
fine=(--set contact.dx=2e-4 --set contact.dy=5e-4 --set passage.step_length=2e-4)
adapted=(--set contact.grid=adapted --set passage.step_length=2e-4 --set contact.normal=linear)
for dyn in receptance imposed; do
  for lam in 0.015 0.03 0.06; do
    case $lam in 0.015) amps="1e-6 2e-6 4e-6" ;; 0.03) amps="2e-6 5e-6 1e-5" ;; *) amps="5e-6 1e-5 2e-5" ;; esac
    for amp in $amps; do
      run profile_0.4mm $exact $dyn $lam $amp --set contact.normal=profile
      [ "$dyn" = receptance ] && run profile_0.2mm $exact $dyn $lam $amp --set contact.normal=profile "${fine[@]}"
    done
    mid=$(echo $amps | cut -d' ' -f2)
    run auto_0.4mm $exact $dyn $lam $mid
    run linear_0.4mm $exact $dyn $lam $mid --set contact.normal=linear
    run linear_0.2mm $exact $dyn $lam $mid --set contact.normal=linear "${fine[@]}"
    run hertz_0.4mm $exact $dyn $lam $mid --set contact.normal=hertz
    run linear_exact_20 $exact $dyn $lam $mid "${adapted[@]}"
    run linear_exact_28 $exact $dyn $lam $mid "${adapted[@]}" --set contact.elements_x=28 \
      --set contact.elements_y=28 --set passage.step_length=1.42857142857e-4
    run linear_simplified_20 $fast $dyn $lam $mid --set contact.model=simplified-transient \
      --set contact.elements_x=20 --set contact.elements_y=20 --set contact.normal=linear
    run linear_fastsim_40 $fast $dyn $lam $mid --set contact.normal=linear
    run hertz_fastsim_40 $fast $dyn $lam $mid --set contact.normal=hertz
  done
done
.venv/bin/python - "$csv" <<'EOF'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
for dyn in ("receptance", "imposed"):
    print(f"\n{dyn}: growth rate (dB per 1e5 passages) at wavelength, amplitude")
    for r in rows:
        if r["dynamics"] == dyn:
            print(f"  {r['chain']:22s} {float(r['wavelength'])*1e3:5.1f} mm {float(r['amplitude'])*1e6:5.1f} um "
                  f"{float(r['rate_db_per_1e5']):+7.3f}  ({float(r['cpu_s']):.1f} s CPU)")
EOF
