#!/usr/bin/env bash
# Sets up (scripts/setup.sh) and runs every test: formatting, the Rust tests
# (unit, integration, doc; with cargo-nextest where installed), a compile
# check of benchmarks and examples, then the Python post-processing tests
# on a run file produced by the binary, and
# the sweep commands against a real single-node Slurm cluster
# (scripts/slurm_test.sh, about 20 s; it installs slurm-wlm and munge from
# Debian as root), and builds the book (docs/) and checks its links.
set -euo pipefail
cd "$(dirname "$0")/.."
SETUP_BOOK=1 bash scripts/setup.sh
# A one-off build needs no incremental cache (it doubles the disk it takes).
export CARGO_INCREMENTAL=0
cargo fmt --check
# cargo-nextest, where the machine has it, runs the tests of every binary
# side by side (`cargo test` runs the binaries one after another, and a
# binary's longest test leaves the other core idle); the same tests.
if cargo nextest --version >/dev/null 2>&1; then
  cargo nextest run --lib --bins --tests
else
  cargo test --lib --bins --tests
fi
cargo test --doc
# Benchmarks and examples must compile; they run with `cargo bench` /
# `cargo run --release --example ...`, not here.
cargo build --benches --examples
run_dir=target/test-run
mkdir -p "$run_dir"
# The binary the integration tests built (`cargo run` would resolve features
# without the dev-dependencies and rebuild faer).
./target/debug/corrugation run --overwrite configs/paper_normal_15mm.toml -o "$run_dir/paper_normal_15mm.h5" \
  --set contact.elements_x=12 --set contact.elements_y=12
# Two workers (pytest-xdist), each test file on one of them (its
# module-scoped runs made once).
CORRUGATION_RUN_FILE="$PWD/$run_dir/paper_normal_15mm.h5" CORRUGATION_BIN="$PWD/target/debug/corrugation" \
  .venv/bin/python -m pytest -q -n 2 --dist loadfile postprocess/tests
# Sweeps on a real Slurm (installs slurm-wlm and munge where missing).
CORRUGATION_BIN="$PWD/target/debug/corrugation" bash scripts/slurm_test.sh
# The book: built with mdbook (scripts/setup.sh installs it), its internal
# links and anchors checked (external links are not followed).
mdbook=$(command -v mdbook || echo "${CARGO_HOME:-$HOME/.cargo}/bin/mdbook")
"$mdbook" build docs
python3 scripts/check_links.py docs/book
