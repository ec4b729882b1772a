# Sourced by the study scripts (not run on its own): `source
# scripts/study_env.sh NAME` from the repository root sets up (scripts/
# setup.sh), sets `out` (OUT, or out/NAME; made) and `bin` (CORRUGATION_BIN,
# or the release binary, built here).
out=${OUT:-out/$1}
bash scripts/setup.sh
mkdir -p "$out"
bin=${CORRUGATION_BIN:-./target/release/corrugation}
[ -n "${CORRUGATION_BIN:-}" ] || cargo build --release --quiet
