#!/usr/bin/env bash
# Sets up (scripts/setup.sh), builds in release, puts `corrugation` and
# `corrugation-post` on the PATH (links in cargo's bin folder, where none
# is there yet), runs one
# scene and draws its figures; for a growth study also its linear growth
# spectrum and the forecast of its roughness (what grows, when each band
# reaches its limit). Usage: scripts/run_scene.sh [CONFIG] [OUT_DIR]
# [--set k=v ...] (OUT_DIR may be left out before the options).
# Defaults: configs/paper_normal_30mm.toml, out/<config name>/.
set -euo pipefail
cd "$(dirname "$0")/.."
config=${1:-configs/paper_normal_30mm.toml}
name=$(basename "$config" .toml)
shift $(( $# > 0 ? 1 : 0 ))
out=out/$name
if [[ $# -gt 0 && $1 != --* ]]; then
  out=$1
  shift
fi
bash scripts/setup.sh
echo "building the release binary (a few minutes from a fresh clone; cargo lists the crates as it compiles them)"
cargo build --release
bin_dir=${CARGO_HOME:-$HOME/.cargo}/bin
if ! command -v corrugation > /dev/null && [ -d "$bin_dir" ]; then
  ln -s "$PWD/target/release/corrugation" "$bin_dir/corrugation"
  echo "linked $bin_dir/corrugation to the release binary: \`corrugation\` is on the PATH"
fi
if ! command -v corrugation-post > /dev/null && [ -d "$bin_dir" ]; then
  ln -s "$PWD/.venv/bin/corrugation-post" "$bin_dir/corrugation-post"
  echo "linked $bin_dir/corrugation-post to the post-processing command: \`corrugation-post\` is on the PATH"
fi
mkdir -p "$out"
./target/release/corrugation run --overwrite "$config" -o "$out/$name.h5" "$@"
.venv/bin/corrugation-post figures "$out/$name.h5" --out "$out" > /dev/null
if grep -q '^\[growth\]' "$config"; then
  ./target/release/corrugation spectrum --overwrite "$config" -o "$out/${name}_spectrum.h5" "$@" 2>&1 \
    | grep -v '^spectrum: [0-9]'
  .venv/bin/corrugation-post spectrum "$out/${name}_spectrum.h5" --out "$out" > /dev/null
fi
echo "run file: $out/$name.h5; figures: $(cd "$out" && ls *.png | tr '\n' ' ')(in $out/)"
