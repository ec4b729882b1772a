# Sourced by the cost scripts (dynamics_cost.sh, two_rails_cost.sh,
# laws_cost.sh):
# median reads numbers, one per line, and prints their median;
# time_run CONFIG PASSES [--set ...] runs "$bin" on CONFIG (a path) for
# PASSES passages without contact histories, "$runs" times, writing
# "$out/run.h5", and prints the median wall seconds.
median() { sort -n | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }
time_run() {
  local config=$1 passes=$2; shift 2
  for _ in $(seq "$runs"); do
    local t0 t1
    t0=$(date +%s.%N)
    "$bin" run --overwrite "$config" -o "$out/run.h5" --set "growth.passes=$passes" \
      --set 'growth.contact_history=[]' "$@" > /dev/null 2>&1
    t1=$(date +%s.%N)
    echo "$t1 - $t0" | bc -l
  done | median
}
