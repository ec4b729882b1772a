#!/usr/bin/env bash
# From initiation to saturation (configs/growth_saturation.toml): the growth
# study run until the corrugation stops growing or the wheel leaves the
# rail, with its normal contact chosen per passage (contact.normal = "auto":
# Hertz while the corrugation is below the profile contact's floor, the
# profile from then on), and the same study with the profile in the contact
# from the start and with the Hertz contact throughout (capped at 300
# passages); then rms and the dominant harmonic against traffic
# (corrugation_post growth). Run files and figures in out/saturation/.
# About 15 minutes on 2 cores (2.4 s per passage with the profile contact,
# 1.2 s with Hertz).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cargo build --release --quiet
out=out/saturation
mkdir -p "$out"
run() { # name --set ...
  local name=$1; shift
  ./target/release/corrugation run --overwrite configs/growth_saturation.toml -o "$out/$name.h5" "$@" 2>&1 | tee "$out/$name.log"
}
run auto
run profile --set contact.normal=profile
run hertz --set contact.normal=hertz --set growth.passes=300
.venv/bin/corrugation-post growth "$out/auto.h5" "$out/profile.h5" "$out/hertz.h5" \
  --out "$out"
