#!/usr/bin/env bash
# The thesis' speed sweep (section 3.4.2): the slowest speed starts from the
# grid, each faster one from the settled end state of the one before; then
# the metrics of every run and a table against speed. Optionally the speed
# ramp of Fig. 3.5-3.6.
#
#   tools/drum_sweep.sh [options] [-- extra -var arguments for inputs/drum.in]
#     --speeds 7,14,21,28,35,42,49,56,63   rpm, ascending
#     --time 2.0         simulated seconds per speed (the first: plus --settle)
#     --settle 1.0       extra seconds for the first speed, to settle from the grid
#     --period 0.006     axial period [m] (0.024: the thesis scene)
#     --np 2             MPI ranks
#     --name sweep       everything goes to post/NAME/ (runs, logs, metrics, summary.*)
#     --ramp 21:28:20    after the sweep, ramp FROM:TO rpm over SECONDS, starting
#                        from the FROM run's end state (FROM must be in --speeds)
# Run from the repository root; liggghts and drum_metrics from PATH (or
# LIGGGHTS=..., DRUM_METRICS=...).
set -euo pipefail
speeds=7,14,21,28,35,42,49,56,63; time=2.0; settle=1.0; period=0.006; np=2; sweep=sweep; ramp=""
while [ $# -gt 0 ]; do
  case "$1" in
    --speeds) speeds=$2; shift 2 ;;
    --time) time=$2; shift 2 ;;
    --settle) settle=$2; shift 2 ;;
    --period) period=$2; shift 2 ;;
    --np) np=$2; shift 2 ;;
    --name) sweep=$2; shift 2 ;;
    --ramp) ramp=$2; shift 2 ;;
    --) shift; break ;;
    *) echo "drum_sweep: unknown option $1 (see the header of $0)" >&2; exit 2 ;;
  esac
done
source "$(dirname "$0")/drum_common.sh"
mpirun_for "$np"
dir=post/$sweep
mkdir -p "$dir"
dt=$drum_dt
for arg in "$@"; do [ "${prev:-}" = dt ] && dt=$arg; prev=$arg; done

run() {  # name, extra -var arguments...
  local name=$1; shift
  local start=$SECONDS
  echo "drum_sweep: $name ..."
  "${mpirun[@]}" "$liggghts" -in inputs/drum.in -var period "$period" -var name "$sweep/$name" "$@" \
    > "$dir/$name.log" 2>&1 || { echo "drum_sweep: $name failed, see $dir/$name.log" >&2; tail -5 "$dir/$name.log" >&2; exit 1; }
  echo "drum_sweep: $name done in $((SECONDS - start)) s"
}

previous=""
averages=()
for rpm in ${speeds//,/ }; do
  name=${sweep}_${rpm}rpm
  if [ -z "$previous" ]; then
    run "$name" -var rpm "$rpm" -var time "$(awk "BEGIN {print $time + $settle}")" -var start grid "$@"
  else
    run "$name" -var rpm "$rpm" -var time "$time" -var start restart -var restart "$dir/${previous}.restart" "$@"
  fi
  "$metrics" series --prefix "$dir/$name" --dt "$dt" --rpm "$rpm" | tee "$dir/${name}_metrics.txt"
  averages+=("$dir/${name}_average.csv")
  previous=$name
done
"$metrics" table --out "$dir/summary" "${averages[@]}"

if [ -n "$ramp" ]; then
  IFS=: read -r from to seconds <<< "$ramp"
  [ -f "$dir/${sweep}_${from}rpm.restart" ] || { echo "drum_sweep: no run at $from rpm to ramp from" >&2; exit 1; }
  run "${sweep}_ramp_${from}_${to}" -var wall ramp -var rpm "$from" -var rpm_end "$to" -var time "$seconds" \
    -var start restart -var restart "$dir/${sweep}_${from}rpm.restart" "$@"
fi
