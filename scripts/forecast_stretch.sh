#!/usr/bin/env bash
# The forecast from a measured rail does not depend on the stretch (issue
# 47): configs/measured_rail.toml with the record of a 3 um, 50 mm wave in
# a 1 um texture (configs/records/wave50_texture.txt, made by
# scripts/make_wave_record.py) through `corrugation spectrum` on stretches
# of 120 mm (4 Bloch classes), 300 mm (2) and 600 mm (1), each a 480-600 mm
# supercell; then scripts/forecast_stretch.py: each band's level against
# the record's own (numpy, rectangular window over its whole periods) and
# the traffic to each limit, stretch by stretch, with the spread.
# About 25 minutes on 2 cores. OUT=DIR writes elsewhere; FORCE=1 re-runs.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/study_env.sh forecast_stretch
python3 scripts/make_wave_record.py "$out/wave50_texture.txt"
cmp "$out/wave50_texture.txt" configs/records/wave50_texture.txt
record=(--set roughness.file=records/wave50_texture.txt)
for case in "120 4" "300 2" "600 1"; do
  set -- $case
  length=$(python3 -c "print($1 / 1000)")
  file="$out/stretch_$1.h5"
  if [ ! -e "$file" ] || [ "${FORCE:-0}" = 1 ]; then
    "$bin" spectrum --overwrite configs/measured_rail.toml -o "$file" "${record[@]}" \
      --set rail.x_max="$length" --set passage.end="$length" --set spectrum.classes="$2" \
      > "$out/stretch_$1.log" 2>&1
    grep -E "^(wrote|warning)" "$out/stretch_$1.log" || true
  fi
done
.venv/bin/python scripts/forecast_stretch.py configs/records/wave50_texture.txt \
  "$out/stretch_120.h5" "$out/stretch_300.h5" "$out/stretch_600.h5"
