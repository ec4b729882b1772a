#!/usr/bin/env bash
# What grows, mechanism by mechanism, as linear growth spectra (issue 43;
# the successor of scripts/mechanism_study.sh's mean rates): `corrugation
# spectrum` (forward differences, 10-150 mm, the default physics: the
# wheelset auto chooses, the dynamics in every direction) of one sleeper
# bay of configs/growth_discrete.toml for each case, then
# scripts/spectrum_table.py: each case's fastest modes (rate, wavelength,
# frequency, drift, purity, the envelope over the sleeper against
# mid-span) and its forced pattern's deepest harmonic, as
# mechanism_spectra.csv, and corrugation-post spectrum's figures per case.
#   single_vV   force control, 20 kN of traction, at 60, 100, 140 km/h
#   braked_vV   -20 kN, at 60, 100, 140 km/h
#   driven_vV   creepage control (-1.26e-3, the driven wheelset of
#               configs/tangent_driven.toml) at 60, 100, 140 km/h
#   bogie       two wheels 2.5 m apart, 100 km/h
#   soft_pad    20 MN/m pads (soft, as on many metros), 100 km/h
#   stiff_pad   1000 MN/m pads (stiff, as on some concrete-sleeper track), 100 km/h
#   low_vV      configs/curve_low_rail.toml (the low rail of a curve, the
#               other wheel free) at 30 and 60 km/h
#   two_rails   configs/curve_two_rails.toml (both rails coupled through
#               the wheelset) at 60 km/h
# Existing spectra are kept (FORCE=1 computes them again); CASES="single
# bogie" picks cases; OUT=DIR writes elsewhere. About 4 minutes a spectrum
# on 2 cores (two_rails about four times that): two hours in all.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/study_env.sh mechanism_spectra
spectrum() {
  local name=$1 config=$2; shift 2
  local f="$out/$name.h5"
  if [ -e "$f" ] && [ "${FORCE:-0}" != 1 ]; then echo "kept $f"; return; fi
  echo "spectrum $name"
  "$bin" spectrum --overwrite "$config" -o "$f" --set spectrum.difference=forward --set spectrum.wavelength_max=0.15 \
    --set "output.title=\"$name\"" "$@" 2> "${f%.h5}.log"
  grep -E "^(wrote|warning)" "${f%.h5}.log" || true
  .venv/bin/corrugation-post spectrum "$f" --out "$out/$name" > /dev/null
}
speeds="60 16.67
100 27.78
140 38.89"
for name in ${CASES:-single braked driven bogie soft_pad stiff_pad low two_rails}; do
  case $name in
    single | braked | driven)
      while read -r kmh v; do
        case $name in
          single) spectrum "single_v$kmh" configs/growth_discrete.toml --set "rolling.speed=$v" ;;
          braked) spectrum "braked_v$kmh" configs/growth_discrete.toml --set "rolling.speed=$v" \
            --set load.longitudinal_force=-2e4 ;;
          driven) spectrum "driven_v$kmh" configs/tangent_driven.toml --set "rolling.speed=$v" ;;
        esac
      done <<< "$speeds" ;;
    bogie) spectrum bogie configs/growth_discrete.toml --set 'vehicle.wheels=[0.0, 2.5]' ;;
    soft_pad) spectrum soft_pad configs/growth_discrete.toml --set track.pad_stiffness=20e6 ;;
    stiff_pad) spectrum stiff_pad configs/growth_discrete.toml --set track.pad_stiffness=1e9 ;;
    low)
      spectrum low_v30 configs/curve_low_rail.toml --set rolling.speed=8.33
      spectrum low_v60 configs/curve_low_rail.toml ;;
    two_rails) spectrum two_rails configs/curve_two_rails.toml ;;
    *) echo "unknown case $name" >&2; exit 2 ;;
  esac
done
.venv/bin/python scripts/spectrum_table.py "$out"/*.h5 > "$out/mechanism_spectra.csv"
cat "$out/mechanism_spectra.csv"
