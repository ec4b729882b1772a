#!/usr/bin/env bash
# What the friction and wear laws do to growth (issue 36): the growth-rate
# spectra of the shipped growth configs and of the mechanism study's cases
# (scripts/mechanism_study.sh: single = configs/growth_discrete.toml as
# shipped; modal = the driven modal wheelset on tangent track; two_rails =
# configs/curve_two_rails.toml, the low and the high rail; CASES adds
# others, e.g. rutting) with each law against the defaults:
#   base         constant friction, Archard's wear (the shipped configs)
#   falling      friction falling with the slip speed: Polach's dry-rail
#                law (exponential, mu_k = 0.4 mu, v_c = 1/0.6 m/s), with
#                CONTACT's friction memory (d_c = 1 um, s_0 = 10 mm/s)
#   falling-none the same without memory
#   falling-long the same with a memory of d_c = 0.1 mm (the distance at
#                which the fixed grid's roll-slip settles and converges
#                under refinement; examples/roll_slip_memory.rs)
#   modifier     a top-of-rail friction modifier: mu = 0.3 at zero slip
#                rising to 0.35 (v_c = 0.1 m/s; an illustration: the
#                products' characteristics are not published as numbers)
#   work         the frictional-work (T-gamma/A) wear law with its regimes
#                (Braghin et al. 2006's coefficients)
#   map          Archard's law with Jendel's wear map (the middle of each
#                published range, H = 260 HB)
# Output: out/laws_study/<variant>/ (the mechanism study's files) and
# out/laws_study/laws_summary.csv: per variant, case, rail and speed the
# fastest-growing harmonic, its frequency and rate (dB per 1e5 wheel
# passages). PASSES (default 10) passages per study; VARIANTS and CASES
# pick. About 8 minutes per variant on 2 cores at 10 passages, 30 for
# the falling law (the fixed grid's Gauss-Seidel solver).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${OUT:-out/laws_study}
passes=${PASSES:-10}
variants=${VARIANTS:-base falling modifier work map}
cases=${CASES:-single modal two_rails}
bash scripts/setup.sh
# CORRUGATION_BIN: a binary of its own (a build beside the study then
# leaves it alone).
bin=${CORRUGATION_BIN:-./target/release/corrugation}
[ -n "${CORRUGATION_BIN:-}" ] || cargo build --release --quiet
mkdir -p "$out"
for v in $variants; do
  case $v in
    base) set_kv="" ;;
    falling) set_kv="material.friction_characteristic=exponential" ;;
    falling-none) set_kv="material.friction_characteristic=exponential material.friction_memory=0" ;;
    falling-long) set_kv="material.friction_characteristic=exponential material.friction_memory=1e-4" ;;
    modifier) set_kv="material.friction_characteristic=modifier material.friction_coefficient=0.3 material.kinetic_friction=0.35 material.friction_speed=0.1" ;;
    work) set_kv="wear.law=frictional-work" ;;
    map) set_kv="wear.law=map" ;;
    *) echo "unknown variant $v (base, falling, falling-none, falling-long, modifier, work, map)" >&2; exit 2 ;;
  esac
  echo "== $v: ${set_kv:-defaults}"
  CORRUGATION_BIN=$bin PASSES=$passes CASES="$cases" SET="$set_kv" OUT="$out/$v" bash scripts/mechanism_study.sh
  # The shipped growth configs on the Hertz patch and the fixed grid.
  for config in growth_fastsim growth_exact; do
    overrides=(--set "growth.passes=$passes" --set "growth.store_every=$passes" --set "growth.checkpoint_every=$passes"
      --set 'growth.contact_history=[]')
    for kv in $set_kv; do overrides+=(--set "$kv"); done
    f="$out/$v/$config.h5"
    "$bin" run --overwrite "configs/$config.toml" -o "$f" "${overrides[@]}" 2> "${f%.h5}.log"
    .venv/bin/corrugation-post speeds "$f" --out "$out/$v/$config"
  done
done
.venv/bin/python scripts/laws_summary.py "$out" $variants > "$out/laws_summary.csv"
cat "$out/laws_summary.csv"
