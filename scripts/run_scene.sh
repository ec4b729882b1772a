#!/usr/bin/env bash
# Sets up (scripts/setup.sh), builds in release, runs one scene and draws its
# figures. Usage: scripts/run_scene.sh [CONFIG] [OUT_DIR] [--set k=v ...]
# (OUT_DIR may be left out before the options).
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
mkdir -p "$out"
./target/release/corrugation run --overwrite "$config" -o "$out/$name.h5" "$@"
.venv/bin/corrugation-post figures "$out/$name.h5" --out "$out" > /dev/null
echo "run file: $out/$name.h5; figures: $(cd "$out" && ls *.png | tr '\n' ' ')(in $out/)"
