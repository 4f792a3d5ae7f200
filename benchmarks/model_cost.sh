#!/usr/bin/env bash
# Cost of the model: the same settled drum slab with `model viscoelastic` and
# with stock `model hooke/stiffness` given identical kn, kt, gamman, gammat
# (absolute damping) for every type pair (tools/stock_equivalent).
#   1. the forces agree: both runs continue from one restart for --check
#      steps, then every bead's position and velocity are compared;
#   2. the time ratio: --runs runs of each, interleaved (A B A B ...), LIGGGHTS'
#      loop time of each; medians and the median of the pairwise ratios.
#
#   benchmarks/model_cost.sh [--restart FILE] [--steps 2000] [--runs 5] [--np 2] [--check 200]
#                            [--out benchmarks/results]
# Without --restart a slab is settled first (drum.in from the grid, 1 s at
# 21 rpm, ~8 min on 2 cores). Run from the repository root; liggghts,
# drum_metrics and stock_equivalent from PATH (or LIGGGHTS=..., DRUM_METRICS=...,
# STOCK_EQUIVALENT=...).
set -euo pipefail
restart=""; steps=2000; runs=5; np=2; check=200; out=benchmarks/results
while [ $# -gt 0 ]; do
  case "$1" in
    --restart) restart=$2; shift 2 ;;
    --steps) steps=$2; shift 2 ;;
    --runs) runs=$2; shift 2 ;;
    --np) np=$2; shift 2 ;;
    --check) check=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    *) echo "model_cost: unknown option $1 (see the header of $0)" >&2; exit 2 ;;
  esac
done
source "$(dirname "$0")/../tools/drum_common.sh"
mpirun_for "$np"
mkdir -p "$out" post/bench
dt=$drum_dt

if [ -z "$restart" ]; then
  echo "model_cost: settling a slab (1 s at 21 rpm from the grid) ..."
  drum_run post/bench/slab.log -var time 1.0 -var dumpdt 1.0 -var name bench/slab
  restart=post/bench/slab.restart
fi

# Table 3.1, thesis conventions (as inputs/drum.in): type 1 beads, type 2 drum.
stock_for table > post/bench/stock.in

run() {  # tag model steps dumps(yes|no) -> loop time [s] on stdout
  local tag=$1 model=$2 n=$3 dumps=$4
  local time dumpdt
  time=$(awk -v n="$n" -v dt="$dt" 'BEGIN {printf "%.10g", n * dt}')
  dumpdt=$time
  [ "$dumps" = yes ] || dumpdt=$(awk -v t="$time" 'BEGIN {printf "%.10g", 10 * t}')
  drum_run "post/bench/$tag.log" -var start restart -var restart "$restart" -var rpm 21 \
    -var time "$time" -var dumpdt "$dumpdt" -var model "$model" -var stock post/bench/stock.in -var name "bench/$tag"
  loop_time "post/bench/$tag.log"
}

echo "model_cost: force check over $check steps ..."
run check_viscoelastic viscoelastic "$check" yes > /dev/null
run check_hooke hooke "$check" yes > /dev/null
agreement=$("$metrics" compare "$(last_snapshot post/bench/check_viscoelastic)" "$(last_snapshot post/bench/check_hooke)")
echo "model_cost: after $check steps: $agreement"
beads=$(echo "$agreement" | awk '{print $2}' | tr -d ,)

echo "model_cost: $runs interleaved runs of $steps steps per model ..."
echo "run,viscoelastic_s,hooke_s,ratio" > "$out/model_cost.csv"
for i in $(seq 1 "$runs"); do
  a=$(run time_viscoelastic viscoelastic "$steps" no)
  b=$(run time_hooke hooke "$steps" no)
  echo "$i,$a,$b,$(awk -v a="$a" -v b="$b" 'BEGIN {printf "%.4f", a / b}')" | tee -a "$out/model_cost.csv"
done
ma=$(tail -n +2 "$out/model_cost.csv" | cut -d, -f2 | median)
mb=$(tail -n +2 "$out/model_cost.csv" | cut -d, -f3 | median)
mr=$(tail -n +2 "$out/model_cost.csv" | cut -d, -f4 | median)
{
  echo "beads=$beads"
  echo "steps=$steps"
  echo "runs=$runs"
  echo "ranks=$np"
  echo "check=\"$agreement\""
  echo "median_viscoelastic_s=$ma"
  echo "median_hooke_s=$mb"
  echo "median_ratio=$mr"
  echo "viscoelastic_psps=$(awk -v n="$beads" -v s="$steps" -v t="$ma" 'BEGIN {printf "%.4g", n * s / t}')"
  echo "hooke_psps=$(awk -v n="$beads" -v s="$steps" -v t="$mb" 'BEGIN {printf "%.4g", n * s / t}')"
  echo "restart=$restart"
  echo "date=$(date -u +%Y-%m-%d)"
} > "$out/model_cost.env"
echo "model_cost: median loop time viscoelastic $ma s, hooke/stiffness $mb s, median ratio $mr"
