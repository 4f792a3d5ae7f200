#!/usr/bin/env bash
# Scene reduction by axial period: the drum at 21 rpm from the grid with a
# 6, 12 and 24 mm period (16,336 / 32,672 / 65,344 beads), the same protocol
# for each; metrics averaged over the same window. Cost per simulated second:
# --rounds rounds of short runs (--span s) from each period's end state, the
# periods interleaved (6 12 24 6 12 24 ...), median. --cost-only skips the
# long runs and re-times their end states.
# (Mesh resolution and moving mesh against surface velocity:
# tools/drum_wall_study.sh, docs/drum/README.md.)
#
#   benchmarks/reductions.sh [--periods 0.006,0.012,0.024] [--time 1.0] [--skip 0.5] [--np 2]
#                            [--rounds 5] [--span 0.003] [--cost-only] [--out benchmarks/results]
# Writes OUT/reductions.csv (one row per period) and keeps the runs in
# post/reduce/ (their restarts feed benchmarks/scaling.sh).
set -euo pipefail
periods=0.006,0.012,0.024; time=1.0; skip=0.5; np=2; out=benchmarks/results; rounds=5; span=0.003; long=yes
while [ $# -gt 0 ]; do
  case "$1" in
    --periods) periods=$2; shift 2 ;;
    --time) time=$2; shift 2 ;;
    --skip) skip=$2; shift 2 ;;
    --np) np=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --rounds) rounds=$2; shift 2 ;;
    --span) span=$2; shift 2 ;;
    --cost-only) long=no; shift ;;
    *) echo "reductions: unknown option $1 (see the header of $0)" >&2; exit 2 ;;
  esac
done
source "$(dirname "$0")/../tools/drum_common.sh"
mpirun_for "$np"
mkdir -p "$out" post/reduce

mm_of() { awk -v p="$1" 'BEGIN {printf "%d", p * 1000 + 0.5}'; }
if [ "$long" = yes ]; then
  for p in ${periods//,/ }; do
    name=reduce/drum_L$(mm_of "$p")
    echo "reductions: $(mm_of "$p") mm period, ${time} s from the grid ..."
    drum_run "post/$name.log" -var period "$p" -var rpm 21 -var time "$time" -var name "$name"
    # time averages after --skip (drum_metrics: from the steady-state start, or the last half)
    "$metrics" series --prefix "post/$name" --dt "$drum_dt" --rpm 21 --skip "$skip" > "post/$name.metrics.txt"
  done
fi

# cost: short runs from each end state, interleaved
: > post/reduce/timings.txt
for i in $(seq 1 "$rounds"); do
  for p in ${periods//,/ }; do
    mm=$(mm_of "$p")
    echo "reductions: timing round $i, $mm mm ..."
    log=post/reduce/time_L$mm.log
    drum_run "$log" -var period "$p" -var rpm 21 -var time "$span" -var dumpdt 1 \
      -var start restart -var restart "post/reduce/drum_L$mm.restart" -var name "reduce/time_L$mm"
    echo "$p $(loop_time "$log")" >> post/reduce/timings.txt
  done
done

header=""
for p in ${periods//,/ }; do
  name=reduce/drum_L$(mm_of "$p")
  if [ -z "$header" ]; then
    header="period_m,loop_s_median,cpu_s_per_simulated_s,$(head -1 "post/${name}_average.csv")"
    echo "$header" > "$out/reductions.csv"
  fi
  loop=$(awk -v p="$p" '$1 == p {print $2}' post/reduce/timings.txt | median)
  echo "$p,$loop,$(awk -v l="$loop" -v np="$np" -v t="$span" 'BEGIN {printf "%.4g", l * np / t}'),$(sed -n 2p "post/${name}_average.csv")" \
    >> "$out/reductions.csv"
done
cat "$out/reductions.csv"
