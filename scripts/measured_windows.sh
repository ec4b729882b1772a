#!/usr/bin/env bash
# The numbers of the measured-rail guide (docs/src/guide/measured-rail.md):
# configs/measured_rail.toml as shipped (its first 120 mm window), then once
# per window of its 0.6 m record (roughness.window_start = 0, 0.12, ...,
# 0.48); scripts/measured_windows.py prints the study's rms and wall time
# and the per-harmonic table of the guide. About 6 minutes on 2 cores.
# OUT=DIR writes elsewhere; FORCE=1 re-runs.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/study_env.sh measured_windows
for start in 0 0.12 0.24 0.36 0.48; do
  file="$out/window_$start.h5"
  if [ ! -e "$file" ] || [ "${FORCE:-0}" = 1 ]; then
    /usr/bin/time -f "%e s wall" -o "$out/window_$start.time" \
      "$bin" run --overwrite configs/measured_rail.toml -o "$file" --set roughness.window_start="$start" \
      > "$out/window_$start.log" 2>&1
  fi
done
.venv/bin/python scripts/measured_windows.py "$out"/window_{0,0.12,0.24,0.36,0.48}.h5
