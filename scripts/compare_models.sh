#!/usr/bin/env bash
# Runs one scene with each contact model (exact-transient, simplified-transient,
# fastsim) and compares them: wear maps and traction snapshots per model, and
# overlays plus a table of differences in creepage and wear depth
# (compare.csv). Usage:
#   scripts/compare_models.sh [CONFIG] [--set section.key=value ...]
# Default: configs/paper_normal_15mm.toml; output in out/compare_<name>/.
# The exact model at 20 x 20 takes a few minutes per passage on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."
config=${1:-configs/paper_normal_15mm.toml}
shift $(( $# > 0 ? 1 : 0 ))
name=$(basename "$config" .toml)
out=out/compare_$name
bash scripts/setup.sh
cargo build --release --quiet
mkdir -p "$out"
files=()
for model in exact-transient simplified-transient fastsim; do
  f="$out/$model.h5"
  ./target/release/corrugation run --overwrite "$config" -o "$f" --set contact.model=$model "$@"
  .venv/bin/corrugation-post figures "$f" --out "$out/$model" >/dev/null
  files+=("$f")
done
.venv/bin/corrugation-post compare "${files[@]}" --out "$out"
