#!/usr/bin/env bash
# Where a passage with the dynamics in every direction spends its time
# beyond the vertical passage: samples each build's CPU with Linux perf
# (package linux-perf; release build with debug info) for studies of 1 and
# of 21 passages of CONFIG (default configs/growth_exact.toml) with
# dynamics.directions = "vertical" and "all", and prints, per 20 passages
# (21 less 1: the set-up cancels), the samples of each part of the
# passage (the contact's exact products, its inner products and
# preconditioner, the friction law per element, the CG solver's vectors,
# the creep response, wear and surface, the rest) and their difference.
# Writes out/directions_profile/.
set -euo pipefail
cd "$(dirname "$0")/.."
config=${1:-configs/growth_exact.toml}
bin=${CORRUGATION_BIN:-./target/release/corrugation}
[ -n "${CORRUGATION_BIN:-}" ] || cargo build --release --quiet
command -v perf >/dev/null || { echo "directions_profile: needs perf (Debian: apt-get install linux-perf)" >&2; exit 1; }
out=out/directions_profile
mkdir -p "$out"
for d in vertical all; do
  for n in 1 21; do
    perf record -q -F 499 -o "$out/$d$n.data" "$bin" run --overwrite "$config" -o "$out/run.h5" \
      --set "growth.passes=$n" --set 'growth.contact_history=[]' --set "dynamics.directions=\"$d\"" \
      > /dev/null 2>&1
    perf report -i "$out/$d$n.data" --no-children -n --sort symbol -g none 2>/dev/null \
      | awk '!/^#/ && /%/ {c=$2; $1=""; $2=""; $3=""; print c "\t" $0}' > "$out/$d$n.tsv"
  done
done
python3 - "$out" <<'PY'
import collections, re, sys
out = sys.argv[1]
def load(name):
    d = collections.Counter()
    for line in open(f"{out}/{name}.tsv"):
        c, s = line.split("\t", 1)
        d[s.strip()] += int(c)
    return d
def passages(mode):
    many = load(f"{mode}21")
    many.subtract(load(f"{mode}1"))
    return many
parts = [
    ("exact products (double precision)", r"FftConvolution<T>::tangential|avx64|Symmetric.*product|SymmetricNormal"),
    ("inner products, preconditioner (single)", r"f32|OnSet|avx_mixed|avx_fft_helper|MixedRadix|Butterfly"),
    ("friction law per element", r"local_solve|atan|hypot|tan_fma|frozen_jacobian|regularised|newton_system|friction"),
    ("CG solver's vectors", r"cg::"),
    ("creep response, wear, surface", r"linear::|RailSurface|wear|sqrt_quadratic"),
]
def part(symbol):
    return next((name for name, rx in parts if re.search(rx, symbol)), "the rest")
names = [p[0] for p in parts] + ["the rest"]
total = {}
for mode in ("vertical", "all"):
    t = collections.Counter()
    for s, c in passages(mode).items():
        t[part(s)] += c
    total[mode] = t
v, a = sum(total["vertical"].values()), sum(total["all"].values())
print(f"CPU samples per 20 passages: vertical {v}, every direction {a} ({a / v:.2f} times)")
print(f"{'part':42s} {'vertical':>9s} {'all':>9s} {'extra, % of vertical':>21s}")
for n in names:
    x, y = total["vertical"][n], total["all"][n]
    print(f"{n:42s} {x:9d} {y:9d} {100 * (y - x) / v:+20.1f}%")
PY
