#!/usr/bin/env bash
# One sleeper bay's Bloch classes against a stretch of four identical bays
# (issue 43): `corrugation spectrum` of configs/growth_discrete.toml at
# 100-150 mm (forward differences), once on one bay with four classes
# (spectrum.classes = 4: the wavelengths 2.4 m / n) and once on a 2.4 m
# stretch of four bays with one class (its own harmonics 2.4 m / n), then
# scripts/spectrum_compare.py --by-wavelength: the largest difference of
# the modes' and of the diagonal rates (dB per 1e5 wheel passages).
# About 10 minutes on 2 cores. OUT=DIR writes elsewhere.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/study_env.sh spectrum_bays
band=(--set spectrum.wavelength_min=0.0999 --set spectrum.wavelength_max=0.1501 --set spectrum.difference=forward)
if [ ! -e "$out/bay_m4.h5" ] || [ "${FORCE:-0}" = 1 ]; then
  "$bin" spectrum --overwrite configs/growth_discrete.toml -o "$out/bay_m4.h5" "${band[@]}" \
    --set spectrum.classes=4 2> "$out/bay_m4.log"
  grep -E "^(wrote|warning)" "$out/bay_m4.log" || true
fi
if [ ! -e "$out/four_bays.h5" ] || [ "${FORCE:-0}" = 1 ]; then
  "$bin" spectrum --overwrite configs/growth_discrete.toml -o "$out/four_bays.h5" "${band[@]}" \
    --set rail.x_max=2.4 --set passage.end=2.4 2> "$out/four_bays.log"
  grep -E "^(wrote|warning)" "$out/four_bays.log" || true
fi
.venv/bin/python scripts/spectrum_compare.py "$out/bay_m4.h5" "$out/four_bays.h5" --by-wavelength
