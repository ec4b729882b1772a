#!/usr/bin/env bash
# Validity map of a normal contact on a corrugated rail against the
# nonlinear profile contact: for a harmonic corrugation of wavelength
# 10-100 mm and amplitude 1-50 um, one growth passage
# (configs/growth_exact.toml: 100 kN, 20 kN, 100 km/h, receptance dynamics,
# fixed grid 0.4 x 1 mm, or 0.2 x 0.5 mm with FINE=1) with contact.normal =
# CANDIDATE ("hertz", the default, or "linear") and with "profile"; the
# difference in the wear of the passage (mean) and
# in the first harmonic (complex: amplitude and phase) of the wear the
# corrugation drives (less the same model's wear on a smooth rail), charted,
# with the 5 % line. The map (out/validity_map/validity.csv) is what
# src/model_choice/hertz_validity.csv holds for the growth loop's check.
#
# The stretch is a whole number of wavelengths, at least 60 mm, after a run-in
# of 40 mm (six semi-axes: the contact transient of the virgin start has
# died out, so the wear's harmonic is the corrugation's alone); the rail
# grid is 40 mm wide so that a widened patch stays on it. Runs that fail
# (full sliding when the dynamic force takes N below F_x / mu) are recorded
# with the program's error. About 10 minutes on 2 cores (the 0.2 mm grid:
# about 40). Writes out/validity_map (hertz) or out/validity_map_linear.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cargo build --release --quiet
candidate=${CANDIDATE:-hertz}
case $candidate in hertz | linear) ;; *) echo "CANDIDATE must be hertz or linear, got $candidate" >&2; exit 2 ;; esac
out=out/validity_map
[ "$candidate" = hertz ] || out="${out}_$candidate"
grid=()
if [ "${FINE:-0}" = 1 ]; then
  out="${out}_fine"
  grid=(--set contact.dx=2e-4 --set contact.dy=5e-4 --set passage.step_length=2e-4)
fi
mkdir -p "$out/runs"
manifest="$out/manifest.csv"
echo "wavelength,amplitude,normal,file,exit_code,message,contact_loss" > "$manifest"
for lambda in 0.010 0.015 0.020 0.030 0.040 0.060 0.100; do
  length=$(python3 -c "import math; l=$lambda; print(round(l*math.ceil(0.06/l - 1e-9), 6))")
  # Amplitude 0 (a smooth rail) is each model's baseline: the corrugation's
  # wear is the difference to it (what the two grids discretise alike).
  for amp in 0 1e-6 2e-6 5e-6 1e-5 2e-5 5e-5; do
    for normal in "$candidate" profile; do
      f="$out/runs/${lambda}_${amp}_${normal}.h5"
      log="${f%.h5}.log"
      rm -f "$f"
      code=0
      ./target/release/corrugation run --overwrite configs/growth_exact.toml -o "$f" \
        --set growth.passes=1 --set growth.adaptive=false --set growth.traffic_scale=1 \
        --set growth.store_every=1 --set growth.checkpoint_every=1 --set "growth.contact_history=[0]" \
        --set roughness.kind=harmonics \
        --set "roughness.harmonics=[{amplitude = $amp, wavelength = $lambda}]" \
        --set rail.x_max="$length" --set passage.end="$length" --set rail.half_width=0.02 --set passage.start=-0.04 \
        --set contact.normal="$normal" --set contact.profile_grid_scale=2.5 "${grid[@]}" 2> "$log" || code=$?
      msg=$(grep -m1 -A1 "^error" "$log" | tr '\n,|' ' ;/' | cut -c1-200 || true)
      loss=$(grep -c "left the rail" "$log" || true)
      echo "$lambda,$amp,$normal,$f,$code,$msg,$loss" >> "$manifest"
    done
  done
  echo "wavelength $lambda done"
done
.venv/bin/corrugation-post validity-map "$manifest" --out "$out"
