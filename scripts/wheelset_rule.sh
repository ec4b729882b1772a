#!/usr/bin/env bash
# Which wheelset a growth study needs (issue 43, the physics the scene
# needs by default): the linear growth spectrum (corrugation spectrum,
# forward differences, 10-150 mm) of each scene with the rigid wheel, the
# torsional mode alone and the flexible rotating wheelset
# (wheelset.model = rigid | torsion | modal), side by side:
#   force     configs/growth_discrete.toml (one bay, force control, 20 kN)
#             at 60, 100 and 140 km/h
#   braked    the same at 100 km/h braked (-20 kN)
#   driven    configs/tangent_driven.toml (creepage control) at 140 km/h
#             (torsion and modal: the rigid wheel under creepage control
#             leaves out the driven wheelset's own torsion)
#   bogie     growth_discrete.toml with two wheels 2.5 m apart, 100 km/h
#   low_rail  configs/curve_low_rail.toml (60 km/h; torsion and modal)
#   exact     configs/growth_exact.toml (continuous track, 100 km/h)
# then scripts/spectrum_table.py: each run's fastest modes and the rate
# at the leading wavelengths, as wheelset_rule.csv. Output in
# out/wheelset_rule/; about an hour on 2 cores. CASES="force bogie" picks
# cases; OUT=DIR writes elsewhere.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/study_env.sh wheelset_rule
spectrum() {
  local name=$1 config=$2; shift 2
  local f="$out/$name.h5"
  echo "spectrum $name"
  "$bin" spectrum --overwrite "$config" -o "$f" --set spectrum.difference=forward --set spectrum.wavelength_max=0.15 \
    "$@" 2> "${f%.h5}.log"
  grep -E "^(wrote|warning)" "${f%.h5}.log" || true
}
models() {
  local name=$1 config=$2; shift 2
  for model in ${MODELS:-rigid torsion modal}; do
    spectrum "${name}_$model" "$config" --set "wheelset.model=$model" "$@"
  done
}
# Creepage control for the torsional mode under force-control scenes is
# not defined: those take rigid and modal (the modal wheelset turns with
# the force's torque through its own inertia and axle).
for name in ${CASES:-force braked driven bogie low_rail exact}; do
  case $name in
    force)
      for v in "60 16.67" "100 27.78" "140 38.89"; do
        MODELS="rigid modal" models "force_v${v% *}" configs/growth_discrete.toml --set "rolling.speed=${v#* }"
      done ;;
    braked) MODELS="rigid modal" models braked configs/growth_discrete.toml --set load.longitudinal_force=-2e4 ;;
    driven) MODELS=${MODELS:-"torsion modal"} models driven configs/tangent_driven.toml ;;
    bogie) MODELS="rigid modal" models bogie configs/growth_discrete.toml --set 'vehicle.wheels=[0.0, 2.5]' ;;
    low_rail) MODELS=${MODELS:-"torsion modal"} models low_rail configs/curve_low_rail.toml ;;
    exact) MODELS="rigid modal" models exact configs/growth_exact.toml ;;
    *) echo "unknown case $name" >&2; exit 2 ;;
  esac
done
.venv/bin/python scripts/spectrum_table.py "$out"/*.h5 > "$out/wheelset_rule.csv"
cat "$out/wheelset_rule.csv"
