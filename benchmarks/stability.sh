#!/usr/bin/env bash
# Stability map: dt/tc swept past failure, for several en.
#   binary collision  the integrator's recurrence (collide recurrence; LIGGGHTS
#                     follows it to round-off, test Integrator.*): mean and
#                     largest restitution over the contact-start phase
#   dense column      inputs/column.in (2009 beads) settled at tc/10, then
#                     0.05 s at each dt: with stock hooke/stiffness fed our
#                     constants (no guard: where does it fail?) and with
#                     `model viscoelastic` (what does the guard say?)
# Failure: beads leave the box, or the settled column's kinetic energy ends
# above 1e-3 J (about m g d per bead: a settled bed cannot have it).
#
#   benchmarks/stability.sh [--out benchmarks/results] [--en 0.3,0.56,0.9]
#                           [--fractions 0.1,0.2,...]
set -euo pipefail
out=benchmarks/results; ens=0.3,0.56,0.9
fractions=0.1,0.2,0.25,0.3,0.35,0.4,0.45,0.5,0.55,0.6
while [ $# -gt 0 ]; do
  case "$1" in
    --out) out=$2; shift 2 ;;
    --en) ens=$2; shift 2 ;;
    --fractions) fractions=$2; shift 2 ;;
    *) echo "stability: unknown option $1 (see the header of $0)" >&2; exit 2 ;;
  esac
done
source "$(dirname "$0")/../tools/drum_common.sh"
collide=${COLLIDE:-collide}
mkdir -p "$out" post/stability

echo "en,dt_over_tc,restitution_mean,restitution_max,duration_steps,stability_limit_dt_over_tc" > "$out/stability_binary.csv"
echo "en,dt_over_tc,model,status,beads_kept,beads,ke_final_J,guard" > "$out/stability_column.csv"
for en in ${ens//,/ }; do
  "$collide" recurrence --en "$en" --dt-over-tc "$fractions" | tail -n +2 | sed "s/^/$en,/" >> "$out/stability_binary.csv"

  tag=column_en$en
  echo "stability: settling the column, en $en ..."
  "$liggghts" -in inputs/column.in -var en "$en" -var time 0.25 -var name "stability/$tag" \
    > "post/stability/$tag.log" 2>&1 || { tail -5 "post/stability/$tag.log" >&2; exit 1; }
  stock_for "$en" > "post/stability/stock_$en.in"
  for f in ${fractions//,/ }; do
    dt=$(awk -v f="$f" 'BEGIN {printf "%.6g", f * 1e-4}')
    for model in hooke viscoelastic; do
      log=post/stability/${tag}_${f}_${model}.log
      status=ok
      "$liggghts" -in inputs/column.in -var start restart -var restart "post/stability/$tag.restart" \
        -var en "$en" -var time 0.05 -var dt "$dt" -var model "$model" -var stock "post/stability/stock_$en.in" \
        -var name "stability/${tag}_${f}_${model}" > "$log" 2>&1 || status=stopped
      kept=$(sed -n 's/^column: done, \([0-9]*\) beads kept.*/\1/p' "$log")
      total=$(sed -n 's/^column: \([0-9]*\) beads, dt.*/\1/p' "$log" | head -1)
      ke=$(sed -n 's/^column: done, .* ke \([^ ]*\) J/\1/p' "$log")
      guard=none
      grep -q "exceeds the stable timestep" "$log" && guard=error
      if [ "$status" = ok ]; then
        awk -v k="$kept" -v t="$total" -v e="$ke" 'BEGIN {exit !(k < t || e > 1e-3)}' && status=failed
      fi
      echo "$en,$f,$model,$status,${kept:-0},${total:-0},${ke:-nan},$guard" | tee -a "$out/stability_column.csv"
    done
  done
done
