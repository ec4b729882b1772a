#!/usr/bin/env bash
# Where traffic scaling makes growth spurious: the growth_fastsim study with
# a fixed m = 2e3, 1e4, 4e4, 1e5, 2e5 real passages per simulated passage,
# all to the same traffic of 4e5 wheel passages, compared with
# `corrugation_post growth` (rms and the fastest-growing harmonic against
# traffic, growth rate relative to m = 2e3, largest update ratio q).
# Output in out/traffic_scaling/. About 2 minutes on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."
out=out/traffic_scaling
bash scripts/setup.sh
cargo build --release --quiet
mkdir -p "$out"
files=()
for m in 2e3 1e4 4e4 1e5 2e5; do
  passes=$(python3 -c "print(round(4e5 / $m))")
  f="$out/m_$m.h5"
  rm -f "$f"
  if ./target/release/corrugation run --overwrite configs/growth_fastsim.toml -o "$f" --set growth.adaptive=false \
    --set growth.traffic_scale="$m" --set growth.passes="$passes" --set growth.store_every="$passes" \
    --set 'growth.contact_history=[]' 2> "$out/m_$m.log"; then
    grep -E "^(wrote|warning)" "$out/m_$m.log" || true
    files+=("$f")
  else
    echo "m = $m failed (left out):"; grep -E "^error" "$out/m_$m.log" || tail -3 "$out/m_$m.log"
  fi
done
.venv/bin/corrugation-post growth "${files[@]}" --out "$out"
