#!/usr/bin/env bash
# Growth on the real track at three speeds and under mixed traffic (issues
# 14 and 21): configs/growth_discrete.toml (UIC60 on discrete sleepers, one
# 0.6 m bay, random roughness 10-120 mm, the exact model on the 0.4 mm fixed
# grid with the rail's corrugation in the normal contact, adaptive m) at 80,
# 100 and 140 km/h, and configs/growth_discrete_mix.toml (the three speeds, a
# third of the traffic each); then `corrugation_post speeds`: growth rate
# against wavelength and against frequency (V / wavelength) with the track's
# resonances from `corrugation track`, and the mix against the share-weighted
# mean of the single-speed rates (what the linear regime predicts).
# HERTZ=1 adds the three speeds on the Hertz chain with FASTSIM 40 x 40 (the
# chain the program shipped before issue 21), for comparison.
# Output in out/discrete_speeds/. About 30 minutes on 2 cores (HERTZ=1: 5
# more); PASSES=N shortens every study to N passages (the mix to 1.6 N).
set -euo pipefail
cd "$(dirname "$0")/.."
out=out/discrete_speeds
bash scripts/setup.sh
cargo build --release --quiet
mkdir -p "$out"
bin=./target/release/corrugation
"$bin" track --overwrite configs/growth_discrete.toml -o "$out/track.h5"
short=()
mix_short=()
if [ -n "${PASSES:-}" ]; then
  short=(--set "growth.passes=$PASSES")
  mix_short=(--set "growth.passes=$(( PASSES * 8 / 5 ))")
fi
# speeds PREFIX LABEL [--set ...]: growth_discrete.toml at the three
# speeds, files $out/PREFIXv<km/h>.h5; their names in the array `made`.
speeds() {
  local prefix=$1 label=$2; shift 2
  made=()
  for case in "80 22.22" "100 27.78" "140 38.89"; do
    local kmh=${case% *} ms=${case#* } f="$out/${prefix}v${case% *}.h5"
    echo "running $kmh km/h$label ($ms m/s)"
    "$bin" run --overwrite configs/growth_discrete.toml -o "$f" --set "rolling.speed=$ms" \
      --set 'growth.contact_history=[]' "$@" "${short[@]}" 2> "${f%.h5}.log"
    grep -E "^(wrote|warning)" "${f%.h5}.log" || true
    made+=("$f")
  done
}
speeds "" ""
runs=("${made[@]}")
if [ -n "${HERTZ:-}" ]; then
  speeds hertz_ " on the Hertz chain (FASTSIM 40 x 40)" --set contact.model=fastsim --set contact.grid=adapted \
    --set contact.elements_x=40 --set contact.elements_y=40 --set passage.step_length=2e-4 --set contact.normal=hertz
  .venv/bin/corrugation-post speeds "${made[@]}" --track "$out/track.h5" --out "$out/hertz"
fi
echo "running the mix"
"$bin" run --overwrite configs/growth_discrete_mix.toml -o "$out/mix.h5" "${mix_short[@]}" 2> "$out/mix.log"
grep -E "^(wrote|warning)" "$out/mix.log" || true
.venv/bin/corrugation-post speeds "${runs[@]}" "$out/mix.h5" \
  --track "$out/track.h5" --out "$out"
