#!/usr/bin/env bash
# Steady curving and what grows in a curve (book: docs/src/guide/
# curving.md). configs/curve_metro.toml's bogie (S1002 on 60E1 1:40, 2.5 m
# wheelbase, 130 kN axles):
#   1. the steady state (`corrugation curve`) for radii RADII (default 150
#      300 500 1000 m) and speeds SPEEDS (default 30 50 80 km/h), each at
#      the cant that balances the speed (at most 150 mm) and without cant;
#   2. the growth spectrum (`corrugation spectrum`, the config's track and
#      exact contact, the dynamics in every direction) at 50 km/h and 60 mm
#      of cant for the cases SPECTRUM_CASES, each radius:wheelset:rail
#      (default the leading wheelset's low and high rails at 150 and 300 m,
#      the trailing low rail at 300 m, the leading low rail at 1000 m;
#      SPECTRA=0 to skip; about 4 minutes each on 2 cores).
# Writes out/curving_study/ (OUT to change) and prints both tables
# (scripts/curving_summary.py).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/study_env.sh curving_study
config=configs/curve_metro.toml
for radius in ${RADII:-150 300 500 1000}; do
  for kmh in ${SPEEDS:-30 50 80}; do
    speed=$(python3 -c "print($kmh / 3.6)")
    balanced=$(python3 -c "import math; print(min(0.15, 1.5 * math.sin(math.atan(($kmh / 3.6) ** 2 / (9.81 * $radius)))))")
    for cant in "$balanced" 0; do
      name=steady_R${radius}_v${kmh}_cant$(python3 -c "print(round($cant * 1000))")
      "$bin" curve "$config" -o "$out/$name.h5" --overwrite --set "curve.radius=$radius" \
        --set "rolling.speed=$speed" --set "curve.cant=$cant" > "$out/$name.log" 2>&1 ||
        echo "$name: $(tail -1 "$out/$name.log")"
    done
  done
done
if [ "${SPECTRA:-1}" != 0 ]; then
  cases=${SPECTRUM_CASES:-"150:leading:low 150:leading:high 300:leading:low 300:leading:high 300:trailing:low 1000:leading:low"}
  for case in $cases; do
    IFS=: read -r radius wheelset rail <<< "$case"
    name=spectrum_R${radius}_${wheelset}_${rail}
    [ -f "$out/$name.h5" ] && continue
    "$bin" spectrum "$config" -o "$out/$name.h5" --overwrite --set "curve.radius=$radius" \
      --set "curve.wheelset=\"$wheelset\"" --set "curve.rail=\"$rail\"" > "$out/$name.log" 2>&1 ||
      echo "$name: $(tail -1 "$out/$name.log")"
  done
fi
.venv/bin/python scripts/curving_summary.py "$out"
