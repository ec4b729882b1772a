#!/usr/bin/env bash
# The sweep commands against a real Slurm (issue 15). Installs Slurm and
# munge from Debian where missing, starts a single-node cluster in a private
# temporary folder (munged, slurmctld and slurmd as plain background
# processes: no systemd; proctrack/pgid and task/none, which work in a
# container), then:
#   1. runs a 4-member sweep locally (`sweep run -j 1`: two threads per
#      member, where the Slurm tasks below have one) and collects it;
#   2. submits the same sweep as a job array (`sweep slurm`), waits, checks
#      `sweep status`, collects, and compares with the local dataset bit for
#      bit (every variable but cpu_seconds, which is measured);
#   3. submits it again into a fresh folder, kills one member mid-run with
#      scancel once it has a checkpoint, checks that `sweep status` reports
#      that member as a checkpoint, re-submits with --only-unfinished (an
#      array of exactly that member), which resumes it, and compares the
#      collected dataset with the local one bit for bit;
#   4. spreads a linear growth spectrum over a job array of two parts and a
#      merge job (`corrugation spectrum --slurm 2`), and compares the merged
#      spectrum with the one measured here in one piece, bit for bit.
# Every daemon it started is stopped by PID, also on failure. About 40 s on
# 2 cores (the cluster starts in about 1 s).
# Needs root (or sudo) to install packages and run the daemons.
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$PWD
bin=${CORRUGATION_BIN:-$repo/target/debug/corrugation}
py=$repo/.venv/bin/python
as_root() { if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi; }
say() { echo "slurm_test: $*" >&2; }
start=$(date +%s)

if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null || ! command -v sbatch >/dev/null; then
  say "installing slurm-wlm and munge from Debian"
  as_root apt-get update -qq
  as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends slurm-wlm munge >/dev/null
fi
[ -x "$bin" ] || { say "building $bin"; cargo build --quiet; }
[ -x "$py" ] || bash scripts/setup.sh

work=$(mktemp -d /tmp/corrugation-slurm.XXXXXX)
chmod 755 "$work"
munge_pid="" ctld_pid="" slurmd_pid=""
export SLURM_CONF=$work/slurm.conf
cleanup() {
  status=$?
  if [ -n "$ctld_pid" ] && kill -0 "$ctld_pid" 2>/dev/null; then
    # Jobs left running would make slurmd ignore SIGTERM.
    scancel --user="$(id -un)" 2>/dev/null || true
    for _ in $(seq 50); do [ -z "$(squeue -h 2>/dev/null)" ] && break; sleep 0.2; done
  fi
  for pid in "$slurmd_pid" "$ctld_pid"; do
    [ -n "$pid" ] && kill "$pid" 2>/dev/null && wait "$pid" 2>/dev/null || true
  done
  if [ -n "$munge_pid" ]; then as_root kill "$munge_pid" 2>/dev/null || true; fi
  if [ "$status" -ne 0 ]; then
    say "FAILED; daemon logs:"
    tail -n 20 "$work"/*.log >&2 2>/dev/null || true
  fi
  [ -n "${KEEP:-}" ] && say "kept $work" || as_root rm -rf "$work"
  exit "$status"
}
trap cleanup EXIT

# munge, as user munge, on its own socket and key.
mkdir -p "$work/munge"
dd if=/dev/urandom of="$work/munge/munge.key" bs=1024 count=1 status=none
as_root chown -R munge:munge "$work/munge"
as_root chmod 711 "$work/munge"
as_root chmod 400 "$work/munge/munge.key"
as_root runuser -u munge -- munged --socket="$work/munge/munge.socket" --key-file="$work/munge/munge.key" \
  --pid-file="$work/munge/munged.pid" --log-file="$work/munge/munged.log" --seed-file="$work/munge/munged.seed"
for _ in $(seq 50); do [ -S "$work/munge/munge.socket" ] && break; sleep 0.1; done
munge_pid=$(as_root cat "$work/munge/munged.pid")

# A single-node cluster; ports chosen per run so that parallel runs do not clash.
port=$((20000 + RANDOM % 20000))
memory=$(( $(awk '/MemTotal/ {print int($2 / 1024)}' /proc/meminfo) / 2 ))
mkdir -p "$work/state" "$work/spool"
cat > "$SLURM_CONF" <<EOF
ClusterName=corrugationtest
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$work/munge/munge.socket
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
ProctrackType=proctrack/pgid
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
MailProg=/bin/true
ReturnToService=2
NodeName=localhost CPUs=$(nproc) RealMemory=$memory State=UNKNOWN
PartitionName=test Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
slurmctld -D -i -f "$SLURM_CONF" >"$work/slurmctld.out" 2>&1 &
ctld_pid=$!
slurmd -D -N localhost -f "$SLURM_CONF" >"$work/slurmd.out" 2>&1 &
slurmd_pid=$!
for _ in $(seq 100); do [ "$(sinfo -h -o %T 2>/dev/null)" = "idle" ] && break; sleep 0.2; done
[ "$(sinfo -h -o %T)" = "idle" ] || { say "the node did not come up"; exit 1; }
say "cluster up ($(( $(date +%s) - start )) s)"

# The sweep: growth_fastsim.toml, coarse, 100 passages (about 5 s a member on
# one core), 2 speeds x 2 pad stiffnesses, checkpoints every 5 passages.
spec() {
  cat > "$work/$1.toml" <<EOF
base = "$repo/configs/growth_fastsim.toml"
output = "$1"
set = ["contact.elements_x=6", "contact.elements_y=6", "rail.dx=5e-4", "rail.dy=1e-3", "passage.step_length=5e-4",
       "growth.passes=100", "growth.checkpoint_every=5", "growth.store_every=50", "growth.contact_history=[0]"]

[[axis]]
key = "rolling.speed"
values = [22.22, 27.78]

[[axis]]
key = "track.pad_stiffness"
values = [100e6, 500e6]
EOF
}
wait_job() { # job id
  for _ in $(seq 600); do [ -z "$(squeue -h -j "$1" 2>/dev/null)" ] && return 0; sleep 0.2; done
  say "job $1 did not end in 120 s"; return 1
}
# Every variable but cpu_seconds equal bit for bit.
same() {
  "$py" - "$1" "$2" <<'EOF'
import sys, h5py, numpy as np
a, b = (h5py.File(p, "r") for p in sys.argv[1:])
names = sorted(k for k in a if k != "cpu_seconds")
assert names == sorted(k for k in b if k != "cpu_seconds"), "different variables"
for k in names:
    x, y = a[k][()], b[k][()]
    if x.dtype.kind == "f":
        assert x.tobytes() == y.tobytes(), f"{k} differs"
    else:
        assert np.array_equal(x, y), f"{k} differs"
print(f"{len(names)} variables equal bit for bit")
EOF
}

cd "$work"
spec local
"$bin" sweep run local.toml -j 1
"$bin" sweep collect local.toml -o local.h5

spec slurm
job=$("$bin" sweep slurm slurm.toml --cpus-per-task 1 --max-concurrent 2 --sbatch-arg=--partition=test)
say "submitted job array $job"
wait_job "$job"
"$bin" sweep status slurm.toml | tee status.txt
grep -q "4 members: 4 complete" status.txt
"$bin" sweep collect slurm.toml -o slurm.h5
same local.h5 slurm.h5
say "slurm job array = local run, bit for bit ($(( $(date +%s) - start )) s)"

spec killed
job=$("$bin" sweep slurm killed.toml --cpus-per-task 1 --max-concurrent 2)
victim=killed/member_0001.h5
for _ in $(seq 300); do
  if [ -f "$victim" ] && "$py" -c "import h5py,sys; f=h5py.File('$victim','r'); sys.exit(0 if f.attrs['status']=='checkpoint' and f.attrs['passes_done']>=10 else 1)" 2>/dev/null; then
    break
  fi
  sleep 0.1
done
scancel "${job}_1"
say "cancelled member 1 (task ${job}_1) after its checkpoint"
wait_job "$job"
"$bin" sweep status killed.toml | tee status.txt
grep -E "^member_0001 .*checkpoint \([0-9]+ of 100 passages\)" status.txt
grep -q "3 complete" status.txt
if "$bin" sweep collect killed.toml -o killed.h5 2>collect.err; then
  say "collect must refuse an unfinished member"; exit 1
fi
grep -q "member 1: checkpoint" collect.err
rerun=$("$bin" sweep slurm killed.toml --only-unfinished --cpus-per-task 1 2>submit.err)
grep -q "1 array tasks (1, member = task + 0)" submit.err
wait_job "$rerun"
grep -q "resumed from its checkpoint" killed/logs/member_0001.log
"$bin" sweep status killed.toml | tee status.txt
grep -q "4 members: 4 complete" status.txt
"$bin" sweep collect killed.toml -o killed.h5
same local.h5 killed.h5
say "killed member resumed by --only-unfinished = local run, bit for bit"

# A spectrum over two array tasks and the merge job.
short=(--set rail.x_max=0.06 --set passage.end=0.06 --set roughness.wavelength_max=0.06
       --set spectrum.wavelength_min=0.029 --set spectrum.wavelength_max=0.061
       --set spectrum.difference=forward)
"$bin" spectrum "$repo/configs/growth_exact.toml" "${short[@]}" -o here.h5
merge=$("$bin" spectrum "$repo/configs/growth_exact.toml" "${short[@]}" -o spread.h5 --slurm 2 --cpus-per-task 1)
say "submitted the spectrum's parts and its merge job $merge"
for _ in $(seq 900); do [ -z "$(squeue -h 2>/dev/null)" ] && break; sleep 0.2; done
[ -f spread.h5 ] || { say "the merge job wrote no spectrum"; cat spread.h5.parts/*.out >&2 || true; exit 1; }
"$py" - here.h5 spread.h5 <<'EOF'
import sys, h5py
a, b = (h5py.File(p, "r")["spectrum"] for p in sys.argv[1:])
names = sorted(a)
assert names == sorted(b), "different variables"
for k in names:
    x, y = a[k][()], b[k][()]
    # Strings (variable-length: object arrays) by value, numbers by their bytes.
    same = x.tolist() == y.tolist() if x.dtype.kind == "O" else x.tobytes() == y.tobytes()
    assert same, f"{k} differs: {x!r} against {y!r}" if x.size < 20 else f"{k} differs"
print(f"spectrum: {len(names)} variables equal bit for bit")
EOF
say "spectrum spread over a job array and merged = measured in one piece, bit for bit"
say "passed in $(( $(date +%s) - start )) s"
