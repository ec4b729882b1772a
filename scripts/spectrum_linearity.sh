#!/usr/bin/env bash
# Is the linear growth spectrum linear? (issue 43): `corrugation spectrum`
# (central differences, the default; 10-150 mm, the default physics) at
# perturbations of 1 nm, 10 nm (the default) and 0.1 um, on
#   discrete  configs/growth_discrete.toml (one sleeper bay, 100 km/h,
#             force control)
#   curve     the low rail of a curve: configs/curve_low_rail.toml at 30
#             km/h, 55 kN, creepage control at xi_x = -1.5e-3, lateral
#             creepage 8e-3, spin 0.3 1/m, mu 0.45, a 54E1 bay
# then scripts/spectrum_compare.py: the largest difference of the modes'
# and of the harmonics' diagonal rates between 1 and 10 nm and between 10
# nm and 0.1 um, as spectrum_linearity.csv. Existing spectra are kept
# (FORCE=1 computes them again); CASES="discrete" picks cases,
# PERTURBATIONS="1e-9 1e-8" sizes (of the pairs 1e-9 / 1e-8 and 1e-8 /
# 1e-7, those whose two spectra exist are compared);
# OUT=DIR writes elsewhere. About 10 minutes a spectrum on 2 cores: an hour.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/study_env.sh spectrum_linearity
curve=(--set rolling.speed=8.333 --set load.normal_force=55e3 --set rolling.creepage_x=-1.5e-3
  --set rolling.creepage_y=8e-3 --set rolling.spin=0.3 --set material.friction_coefficient=0.45
  --set track.rail=54E1)
for name in ${CASES:-discrete curve}; do
  case $name in
    discrete) config=configs/growth_discrete.toml; extra=() ;;
    curve) config=configs/curve_low_rail.toml; extra=("${curve[@]}") ;;
    *) echo "unknown case $name" >&2; exit 2 ;;
  esac
  for p in ${PERTURBATIONS:-1e-9 1e-8 1e-7}; do
    f="$out/${name}_$p.h5"
    if [ -e "$f" ] && [ "${FORCE:-0}" != 1 ]; then echo "kept $f"; continue; fi
    echo "spectrum $name at $p m"
    "$bin" spectrum --overwrite "$config" -o "$f" --set spectrum.wavelength_max=0.15 \
      --set "spectrum.perturbation=$p" "${extra[@]}" 2> "${f%.h5}.log"
    grep -E "^(wrote|warning)" "${f%.h5}.log" || true
  done
done
{
  echo "a,b,perturbation_a,perturbation_b,modes,mode_rate_max_diff,at_mm,diagonal_rate_max_diff,at_mm,lead_a,lead_b,lead_mm"
  for name in ${CASES:-discrete curve}; do
    for pair in "1e-9 1e-8" "1e-8 1e-7"; do
      read -r a b <<< "$pair"
      [ -e "$out/${name}_$a.h5" ] && [ -e "$out/${name}_$b.h5" ] || continue
      .venv/bin/python scripts/spectrum_compare.py "$out/${name}_$a.h5" "$out/${name}_$b.h5" --csv
    done
  done
} > "$out/spectrum_linearity.csv"
cat "$out/spectrum_linearity.csv"
