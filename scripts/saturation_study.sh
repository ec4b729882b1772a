#!/usr/bin/env bash
# From initiation to saturation (configs/growth_saturation.toml): the growth
# study with the rail's corrugation in the normal contact, run until the
# corrugation stops growing or the wheel leaves the rail, and the same study
# with the Hertz normal contact for comparison; then rms and the dominant
# harmonic against traffic (corrugation_post growth). Run files and figures
# in out/saturation/. Each study takes up to 600 passages (about 2.5 s per
# passage with the profile contact, 1.2 s with Hertz, 2 cores).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cargo build --release --quiet
out=out/saturation
mkdir -p "$out"
./target/release/corrugation run configs/growth_saturation.toml -o "$out/profile.h5" 2>&1 | tee "$out/profile.log"
./target/release/corrugation run configs/growth_saturation.toml -o "$out/hertz.h5" \
  --set contact.normal=hertz 2>&1 | tee "$out/hertz.log"
PYTHONPATH=postprocess .venv/bin/python -m corrugation_post growth "$out/profile.h5" "$out/hertz.h5" --out "$out"
