#!/usr/bin/env bash
# What a linear growth spectrum costs (issue 43's benchmark): `corrugation
# spectrum` of configs/growth_discrete.toml's sleeper bay at 10-150 mm with
# 1, 2 and 4 Bloch classes (forward differences; CENTRAL=1 for central
# ones), each run REPEAT times (default 1), printing the passages, the
# passage equivalents (passages over one bay) and the wall and CPU seconds
# (median over the repeats), and what 2 mm resolution at 150 mm (19
# classes) costs from them: the passages do not depend on the classes,
# each is M bays long. CLASSES="1 2" picks the class counts; OUT=DIR writes
# elsewhere (default out/spectrum_cost).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${OUT:-out/spectrum_cost}
mkdir -p "$out"
bin=${CORRUGATION_BIN:-./target/release/corrugation}
[ -n "${CORRUGATION_BIN:-}" ] || cargo build --release --quiet
difference=forward
[ "${CENTRAL:-0}" = 1 ] && difference=central
echo "classes,passages,passage_equivalents,wall_s,cpu_s,wall_s_per_passage_equivalent"
for m in ${CLASSES:-1 2 4}; do
  walls=(); cpus=(); line=""
  for r in $(seq 1 "${REPEAT:-1}"); do
    f="$out/bay_m${m}_$r.h5"
    "$bin" spectrum --overwrite configs/growth_discrete.toml -o "$f" --set spectrum.wavelength_max=0.15 \
      --set "spectrum.classes=$m" --set "spectrum.difference=$difference" 2> "${f%.h5}.log"
    line=$(grep '^wrote' "${f%.h5}.log")
    walls+=("$(echo "$line" | sed -E 's/.* ([0-9.]+) s wall.*/\1/')")
    cpus+=("$(echo "$line" | sed -E 's/.* ([0-9.]+) s CPU.*/\1/')")
  done
  median() { printf '%s\n' "$@" | sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2}'; }
  wall=$(median "${walls[@]}"); cpu=$(median "${cpus[@]}")
  equivalents=$(echo "$line" | sed -E 's/.* ([0-9]+) passage equivalents.*/\1/')
  passages=$((equivalents / m))
  echo "$m,$passages,$equivalents,$wall,$cpu,$(awk "BEGIN {print $wall / $equivalents}")"
done
