#!/usr/bin/env bash
# Installs what corrugation needs on a Debian machine that has a Rust
# toolchain, gcc and python3: HDF5 (libhdf5-dev, pkg-config) from Debian,
# a Python venv (.venv) with the post-processing package (postprocess/,
# its dependencies from PyPI), and, with SETUP_BOOK=1 (the test command), mdbook for the book (docs/): Debian's
# package where the release has one, else from crates.io at a pinned
# version (Debian 12 has none; cargo install takes a few minutes, once).
# Idempotent: does nothing that is already done.
set -euo pipefail
cd "$(dirname "$0")/.."

as_root() { if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi; }
apt_updated=0
apt_install() {
  if [ "$apt_updated" -eq 0 ]; then as_root apt-get update -qq; apt_updated=1; fi
  as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "$@" >/dev/null
}

if ! { command -v pkg-config >/dev/null && pkg-config --exists hdf5; } && [ ! -f /usr/include/hdf5/serial/hdf5.h ]; then
  echo "setup: installing HDF5 (libhdf5-dev) from Debian" >&2
  apt_install libhdf5-dev pkg-config
fi

if [ ! -x .venv/bin/python ]; then
  if ! python3 -m venv .venv 2>/dev/null; then
    echo "setup: installing python3-venv from Debian" >&2
    rm -rf .venv
    apt_install python3-venv
    python3 -m venv .venv
  fi
fi
# The post-processing package, editable (changes to postprocess/ apply at
# once), with its test extra; its command is .venv/bin/corrugation-post.
stamp=.venv/.postprocess.sha256
want=$(sha256sum postprocess/pyproject.toml | cut -d' ' -f1)
if [ "$(cat "$stamp" 2>/dev/null)" != "$want" ]; then
  echo "setup: installing the post-processing package (postprocess/pyproject.toml)" >&2
  .venv/bin/python -m pip install -q --upgrade pip
  PYTHONWARNINGS=ignore .venv/bin/python -m pip install -q -e "postprocess[test]"
  echo "$want" > "$stamp"
fi

# mdbook builds the book (docs/); scripts/test.sh builds it and checks its
# links (and asks for it with SETUP_BOOK=1; the main command does not). Without its serve and watch features (a local web server and a
# file watcher, which the build does not need) it compiles in about half
# the time; unoptimised (--debug) in half that again (31 s against 63 s on
# 2 cores), and it still builds the book in a second.
MDBOOK_VERSION=0.5.4
# Only the test command builds the book: it sets SETUP_BOOK=1.
if [ "${SETUP_BOOK:-0}" = 1 ] && ! command -v mdbook >/dev/null \
  && [ ! -x "${CARGO_HOME:-$HOME/.cargo}/bin/mdbook" ]; then
  if [ "$apt_updated" -eq 0 ]; then as_root apt-get update -qq; apt_updated=1; fi
  if [ -n "$(apt-cache policy mdbook 2>/dev/null | sed -n 's/^ *Candidate: *//p' | grep -v '(none)')" ]; then
    echo "setup: installing mdbook from Debian" >&2
    apt_install mdbook
  else
    echo "setup: installing mdbook $MDBOOK_VERSION from crates.io (cargo install, a few minutes, once)" >&2
    cargo install mdbook --locked --version "$MDBOOK_VERSION" --no-default-features --features search --quiet --debug
  fi
fi
