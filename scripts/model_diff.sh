#!/usr/bin/env bash
# What a change of the dynamics' arithmetic does to every shipped growth
# study: builds revision REV (default: the one before the vehicle-track
# model became one model) in a worktree beside this checkout, runs each
# shipped growth config for PASSES (default 3) passages with both builds,
# and compares the run files variable by variable (scripts/model_diff.py):
# the recorded normal force's and the profile's largest relative
# difference, the growth rates' largest difference (dB per 1e5 wheel
# passages) at the first and the last passage; and, for scale, the same
# build against itself with growth_exact's speed one ulp higher. Writes
# out/model_diff/summary.txt.
#   bash scripts/model_diff.sh [REV]
set -euo pipefail
cd "$(dirname "$0")/.."
rev=${1:-9ea9b6a}
passes=${PASSES:-3}
out=out/model_diff
old=$out/old-tree
mkdir -p "$out"
cargo build --release --quiet
if [ ! -d "$old" ]; then
  git worktree add --detach "$old" "$rev" >/dev/null
fi
(cd "$old" && CARGO_TARGET_DIR=$PWD/target cargo build --release --quiet --bin corrugation)
py=${PYTHON:-.venv/bin/python}
summary=$out/summary.txt
printf '%-24s %10s %11s %14s %13s\n' config "force rel" "profile rel" "rates first dB" "rates last dB" > "$summary"
for config in configs/*.toml; do
  name=$(basename "$config" .toml)
  grep -q '^\[growth\]' "$config" || continue
  set=(--set "growth.passes=$passes" --set "growth.store_every=1")
  for side in old new; do
    bin=./target/release/corrugation
    [ "$side" = old ] && bin=$old/target/release/corrugation
    rm -f "$out/$name-$side.h5"
    "$bin" run "$config" -o "$out/$name-$side.h5" "${set[@]}" > "$out/$name-$side.log" 2>&1
  done
  "$py" scripts/model_diff.py "$name" "$out/$name-old.h5" "$out/$name-new.h5" | tee -a "$summary"
done
# The noise floor: the same build, growth_exact's speed one ulp higher.
# The exact model's iterations carry a rounding change of 1e-16 into the
# profile at 1e-8 and the rates at 1e-6 dB per 1e5.
speed=$("$py" -c "import math, tomllib; s = tomllib.load(open('configs/growth_exact.toml', 'rb'))['rolling']['speed']; print(repr(math.nextafter(s, math.inf)))")
"$old/target/release/corrugation" run configs/growth_exact.toml -o "$out/control-ulp.h5" --overwrite \
  --set "growth.passes=$passes" --set growth.store_every=1 --set "rolling.speed=$speed" > "$out/control-ulp.log" 2>&1
"$py" scripts/model_diff.py "(old, exact, speed+1ulp)" "$out/growth_exact-old.h5" "$out/control-ulp.h5" | tee -a "$summary"
cat "$summary"
