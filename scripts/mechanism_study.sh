#!/usr/bin/env bash
# Why corrugation grows (issues 24 and 34): growth-rate spectra with the
# consistent chain (configs/growth_discrete.toml: UIC60 on discrete
# sleepers, one 0.6 m bay, random roughness 10-120 mm, the exact model on
# the 0.4 mm fixed grid with the rail's corrugation in the normal contact)
# at 60, 100 and 140 km/h for each mechanism, with the dynamics in every
# direction (the default: the rail head and the wheel in three directions,
# the creep forces' frequency response; DIRECTIONS=vertical runs the
# vertical models instead, as before issue 34):
#   single  one wheel, the longitudinal force prescribed (20 kN; today's scene)
#   braked  the same wheel braked: -20 kN
#   torsion one wheel, creepage-controlled (-1.26e-3, the exact model's
#           steady creepage at 20 kN) with the wheelset's torsional mode
#           ([wheelset] defaults: 71 Hz): a driven wheelset
#   modal   the driven wheelset as a flexible rotating body ([wheelset]
#           model = "modal": the rigid wheelset on its primary suspension,
#           torsion, bending and wheel modes, gyroscopic coupling)
#   bogie   two wheels 2.5 m apart on the rail, coupled through its
#           transfer receptances (vehicle.wheels = [0.0, 2.5])
#   curve   the leading wheelset in a curve: lateral creepage 5e-3 and spin
#           0.5 1/m, no longitudinal force (the lateral force saturates)
#   rutting the curve with the wheelset's torsional mode and a longitudinal
#           creepage of -2e-3 (the rolling-radius difference), creepage
#           control: the low rail's rutting mechanism of the literature
#   low_rail  configs/curve_two_rails.toml's low rail alone (its
#           [second_rail] section removed): the modal wheelset, its other
#           wheel free
#   two_rails configs/curve_two_rails.toml: the low and the high rail, the
#           two contacts coupled through the modal wheelset (the speeds
#           figure draws both rails; rails_summary.csv has each rail's
#           fastest-growing harmonics)
# then `corrugation-post speeds` per mechanism (growth rate against
# wavelength and frequency with the track's resonances; speeds_summary.csv:
# each study's peak wavelength, frequency and rate) and `corrugation-post
# mechanisms`: all of them side by side (mechanisms.png,
# mechanisms_summary.csv).
# Output in out/mechanism_study/ (out/mechanism_study_vertical/ with
# DIRECTIONS=vertical). About 45 minutes on 2 cores with the config's 40
# passages; PASSES=N runs N passages per study; CASES="single bogie" picks
# mechanisms; SET="dynamics.spin=false" adds --set overrides to every
# study (space-separated) and OUT=DIR writes elsewhere.
set -euo pipefail
cd "$(dirname "$0")/.."
directions=${DIRECTIONS:-all}
out=out/mechanism_study
[ "$directions" = all ] || out=out/mechanism_study_$directions
out=${OUT:-$out}
bash scripts/setup.sh
mkdir -p "$out"
# CORRUGATION_BIN: a binary of its own (a build beside the study then
# leaves it alone).
bin=${CORRUGATION_BIN:-./target/release/corrugation}
[ -n "${CORRUGATION_BIN:-}" ] || cargo build --release --quiet
short=()
if [ -n "${PASSES:-}" ]; then
  short=(--set "growth.passes=$PASSES" --set "growth.store_every=$PASSES" --set "growth.checkpoint_every=$PASSES")
fi
for kv in ${SET:-}; do
  short+=(--set "$kv")
done
"$bin" track --overwrite configs/growth_discrete.toml -o "$out/track.h5" --set "dynamics.directions=$directions"
# The curve's low rail alone: curve_two_rails.toml without its second rail.
awk '/^\[second_rail\]/ {skip = 1; next} /^\[/ {skip = 0} !skip' configs/curve_two_rails.toml > "$out/low_rail.toml"
# Creepage control needs the config without its longitudinal force.
grep -v '^longitudinal_force' configs/growth_discrete.toml > "$out/creepage.toml"
printf '\n[wheelset]\n' >> "$out/creepage.toml"
# mechanism NAME CONFIG [--set ...]: the three speeds, files $out/NAME_v<km/h>.h5.
mechanism() {
  local name=$1 config=$2; shift 2
  local made=()
  for case in "60 16.67" "100 27.78" "140 38.89"; do
    local f="$out/${name}_v${case% *}.h5"
    echo "running $name at ${case% *} km/h"
    "$bin" run --overwrite "$config" -o "$f" --set "rolling.speed=${case#* }" --set "dynamics.directions=$directions" \
      --set 'growth.contact_history=[]' --set "output.title=\"$name, ${case% *} km/h\"" "$@" "${short[@]}" \
      2> "${f%.h5}.log"
    grep -E "^(wrote|warning)" "${f%.h5}.log" || true
    made+=("$f")
  done
  .venv/bin/corrugation-post speeds "${made[@]}" --track "$out/track.h5" --out "$out/$name"
}
cases=${CASES:-single braked torsion modal bogie curve rutting low_rail two_rails}
base=configs/growth_discrete.toml
for name in $cases; do
  case $name in
    single) mechanism single $base ;;
    braked) mechanism braked $base --set load.longitudinal_force=-2e4 ;;
    torsion) mechanism torsion "$out/creepage.toml" --set load.control=creepage --set rolling.creepage_x=-1.26e-3 ;;
    modal) mechanism modal "$out/creepage.toml" --set load.control=creepage --set rolling.creepage_x=-1.26e-3 \
      --set wheelset.model=modal ;;
    bogie) mechanism bogie $base --set 'vehicle.wheels=[0.0, 2.5]' ;;
    curve) mechanism curve $base --set rolling.creepage_y=5e-3 --set rolling.spin=0.5 --set load.longitudinal_force=0 ;;
    rutting) mechanism rutting "$out/creepage.toml" --set load.control=creepage --set rolling.creepage_x=-2e-3 \
      --set rolling.creepage_y=5e-3 --set rolling.spin=0.5 ;;
    low_rail) mechanism low_rail "$out/low_rail.toml" ;;
    two_rails)
      mechanism two_rails configs/curve_two_rails.toml
      # The low rail alone beside, where the study ran it.
      lows=()
      for f in "$out"/low_rail_v*.h5; do [ -e "$f" ] && lows+=("$f"); done
      .venv/bin/python scripts/rails_summary.py "$out"/two_rails_v*.h5 "${lows[@]}" > "$out/rails_summary.csv"
      cat "$out/rails_summary.csv"
      ;;
    *) echo "unknown mechanism $name (single, braked, torsion, modal, bogie, curve, rutting, low_rail, two_rails)" >&2; exit 2 ;;
  esac
done
# The mechanisms side by side: mechanisms.png, mechanisms_summary.csv (per
# mechanism and speed the fastest-growing harmonic and those above 0.1 dB
# per 1e5 passages).
folders=()
for name in $cases; do folders+=("$out/$name"); done
.venv/bin/corrugation-post mechanisms "${folders[@]}" --out "$out"
