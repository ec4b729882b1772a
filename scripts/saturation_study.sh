#!/usr/bin/env bash
# From initiation to saturation (configs/growth_saturation.toml): the growth
# study run until the corrugation stops growing or the wheel leaves the
# rail, with the consistent chain (contact.normal = "auto": the linear
# profile contact while the corrugation is shallow, the nonlinear one
# beyond), the same study with the nonlinear profile contact throughout
# ("profile"), and with the Hertz contact (capped at 300 passages); then rms
# and the dominant harmonic against traffic (corrugation-post growth). Run
# files and figures in out/saturation/. About 2 minutes on 2 cores.
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
  --out "$out" --wavelength 0.0109
