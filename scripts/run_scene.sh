#!/usr/bin/env bash
# Sets up (scripts/setup.sh), builds in release, runs one scene and draws its
# figures. Usage: scripts/run_scene.sh [CONFIG] [OUT_DIR] [--set k=v ...]
# Defaults: configs/paper_normal_30mm.toml, out/<config name>/.
set -euo pipefail
cd "$(dirname "$0")/.."
config=${1:-configs/paper_normal_30mm.toml}
name=$(basename "$config" .toml)
out=${2:-out/$name}
shift $(( $# > 2 ? 2 : $# ))
bash scripts/setup.sh
cargo build --release --quiet
mkdir -p "$out"
./target/release/corrugation run --overwrite "$config" -o "$out/$name.h5" "$@"
.venv/bin/corrugation-post figures "$out/$name.h5" --out "$out" > /dev/null
echo "run file: $out/$name.h5; figures: $(cd "$out" && ls *.png | tr '\n' ' ')(in $out/)"
