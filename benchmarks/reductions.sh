#!/usr/bin/env bash
# Scene reduction by axial period: the drum at 21 rpm from the grid with a
# 6, 12 and 24 mm period (16,336 / 32,672 / 65,863 beads), the same protocol
# for each; metrics averaged over the same window, cost per simulated second.
# (Mesh resolution and moving mesh against surface velocity:
# tools/drum_wall_study.sh, docs/drum/README.md.)
#
#   benchmarks/reductions.sh [--periods 0.006,0.012,0.024] [--time 1.0] [--skip 0.5] [--np 2]
#                            [--out benchmarks/results]
# Writes OUT/reductions.csv (one row per period) and keeps the runs in
# post/reduce/ (their restarts feed benchmarks/scaling.sh).
set -euo pipefail
periods=0.006,0.012,0.024; time=1.0; skip=0.5; np=2; out=benchmarks/results
while [ $# -gt 0 ]; do
  case "$1" in
    --periods) periods=$2; shift 2 ;;
    --time) time=$2; shift 2 ;;
    --skip) skip=$2; shift 2 ;;
    --np) np=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    *) echo "reductions: unknown option $1 (see the header of $0)" >&2; exit 2 ;;
  esac
done
source "$(dirname "$0")/../tools/drum_common.sh"
mpirun_for "$np"
mkdir -p "$out" post/reduce

header=""
for p in ${periods//,/ }; do
  mm=$(awk -v p="$p" 'BEGIN {printf "%d", p * 1000 + 0.5}')
  name=reduce/drum_L$mm
  log=post/$name.log
  echo "reductions: ${mm} mm period, ${time} s from the grid ..."
  "${mpirun[@]}" "$liggghts" -in inputs/drum.in -var period "$p" -var rpm 21 -var time "$time" \
    -var name "$name" > "$log" 2>&1 || { tail -5 "$log" >&2; exit 1; }
  loop=$(awk '/^Loop time of/ {print $4}' "$log")
  "$metrics" series --prefix "post/$name" --dt "$drum_dt" --rpm 21 --skip "$skip" > "post/$name.metrics.txt"
  # time averages after --skip (drum_metrics: from the steady-state start, or the last half)
  if [ -z "$header" ]; then
    header="period_m,loop_s,cpu_s_per_simulated_s,$(head -1 "post/${name}_average.csv")"
    echo "$header" > "$out/reductions.csv"
  fi
  echo "$p,$loop,$(awk -v l="$loop" -v np="$np" -v t="$time" 'BEGIN {printf "%.4g", l * np / t}'),$(sed -n 2p "post/${name}_average.csv")" \
    >> "$out/reductions.csv"
done
cat "$out/reductions.csv"
