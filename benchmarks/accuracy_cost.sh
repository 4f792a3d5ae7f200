#!/usr/bin/env bash
# Accuracy against cost, dt = tc/5 ... tc/81 (the thesis' 1.23 us):
#   cost   CPU seconds per simulated second of the drum: the settled slab of
#          model_cost.sh continued for --span simulated seconds at each dt,
#          LIGGGHTS loop time x ranks / span; --runs runs per dt, median
#   error  two-body head-on collision (collide, 128 start phases): restitution
#          and contact-duration error against the requested en and tc,
#          nominal coefficients (= stock hooke/stiffness given them: identical
#          forces, see model_cost) and `exactRestitution on`
#
#   benchmarks/accuracy_cost.sh --restart FILE [--ratios 5,10,20,40,81] [--span 0.01] [--runs 3] [--np 2]
#                               [--out benchmarks/results]
set -euo pipefail
restart=""; ratios=5,10,20,40,81; span=0.01; runs=3; np=2; out=benchmarks/results
while [ $# -gt 0 ]; do
  case "$1" in
    --restart) restart=$2; shift 2 ;;
    --ratios) ratios=$2; shift 2 ;;
    --span) span=$2; shift 2 ;;
    --runs) runs=$2; shift 2 ;;
    --np) np=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    *) echo "accuracy_cost: unknown option $1 (see the header of $0)" >&2; exit 2 ;;
  esac
done
[ -n "$restart" ] || { echo "accuracy_cost: --restart FILE (a settled drum, e.g. from model_cost.sh) is needed" >&2; exit 2; }
source "$(dirname "$0")/../tools/drum_common.sh"
collide=${COLLIDE:-collide}
mpirun_for "$np"
mkdir -p "$out" post/accuracy

# two-body errors: one LIGGGHTS run per dt holds all 128 phases
for mode in off on; do
  "$collide" sweep-dt --geometry pair --en 0.56 --et 0.46 --ratios "$ratios" --phases 128 \
    --exact-restitution "$mode" --csv "post/accuracy/twobody_exact_$mode.csv" > /dev/null
done

echo "tc_over_dt,dt,cpu_s_per_simulated_s,particle_steps_per_s,restitution_err_nominal,duration_err_steps_nominal,restitution_err_exact,duration_err_steps_exact" \
  > "$out/accuracy_cost.csv"
for r in ${ratios//,/ }; do
  dt=$(awk -v r="$r" 'BEGIN {printf "%.6g", 1e-4 / r}')
  times=()
  for i in $(seq 1 "$runs"); do
    log=post/accuracy/drum_$r.log
    "${mpirun[@]}" "$liggghts" -in inputs/drum.in -var start restart -var restart "$restart" -var dt "$dt" \
      -var time "$span" -var dumpdt 1 -var name "accuracy/drum_$r" > "$log" 2>&1 || { tail -5 "$log" >&2; exit 1; }
    times+=("$(awk '/^Loop time of/ {t = $4} END {print t}' "$log")")
  done
  loop=$(printf '%s\n' "${times[@]}" | median)
  beads=$(sed -n 's/^drum: done, \([0-9]*\) beads kept.*/\1/p' post/accuracy/drum_$r.log)
  row=$(awk -F, -v r="$r" 'NR > 1 && $1 + 0 == r + 0 {print $4 "," $6}' post/accuracy/twobody_exact_off.csv)
  rowx=$(awk -F, -v r="$r" 'NR > 1 && $1 + 0 == r + 0 {print $4 "," $6}' post/accuracy/twobody_exact_on.csv)
  awk -v r="$r" -v dt="$dt" -v loop="$loop" -v np="$np" -v span="$span" -v n="$beads" -v a="$row" -v b="$rowx" \
    'BEGIN {steps = span / dt; printf "%s,%s,%.6g,%.6g,%s,%s\n", r, dt, loop * np / span, n * steps / loop, a, b}' \
    | tee -a "$out/accuracy_cost.csv"
done

gnuplot <<EOF
set terminal pngcairo size 1100,650 noenhanced
set output '$out/accuracy_cost.png'
set datafile separator ','
set title 'accuracy against cost: head-on collision (en = 0.56, 128 start phases) vs drum cost (16,336 beads)'
set xlabel 'cost: CPU seconds per simulated second of the drum'
set ylabel '|restitution error| [%]'
set logscale xy
set grid
set key bottom left
plot '$out/accuracy_cost.csv' every ::1 using 3:(100*abs(\$5)):(sprintf('tc/%d', \$1)) with labels offset 0,1 notitle, \
     '' every ::1 using 3:(100*abs(\$5)) with linespoints lw 2 pt 7 title 'nominal coefficients (ours = stock hooke/stiffness fed them)', \
     '' every ::1 using 3:(abs(\$7) > 0 ? 100*abs(\$7) : 1e-6) with linespoints lw 2 pt 5 title 'exactRestitution on'
EOF
echo "wrote $out/accuracy_cost.csv, $out/accuracy_cost.png"
