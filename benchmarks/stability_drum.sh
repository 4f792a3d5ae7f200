#!/usr/bin/env bash
# Stability map, third scene: the drum (the settled 6 mm slab at 21 rpm)
# continued for --time at each dt/tc. Stock hooke/stiffness fed our constants
# (no guard) for en = et = 0.3, 0.9 (every pair) and Table 3.1 (en: beads
# 0.56, drum 0.46; et 0.46); `model viscoelastic` with Table 3.1 (what does the guard say?).
# Failure: the run stops (beads leave the box through the drum wall:
# thermo_modify lost error), beads are missing at the end, or the kinetic
# energy ends above twice that of the same en at dt = tc/10 (energy growth:
# a drum turning at constant speed keeps its kinetic energy).
#
#   benchmarks/stability_drum.sh --restart FILE [--time 0.03] [--fractions 0.1,0.2,...]
#                                [--runs 0.3:hooke,...] [--np 2] [--out benchmarks/results]
# --runs: en:model pairs (en `table` = Table 3.1); --fractions must hold 0.1
# (the energy reference). Writes OUT/stability_drum.csv, or appends with --append.
set -euo pipefail
restart=""; time=0.03; np=2; out=benchmarks/results; append=no
runs=0.3:hooke,0.9:hooke,table:hooke,table:viscoelastic
fractions=0.1,0.2,0.25,0.3,0.35,0.4,0.45,0.5
while [ $# -gt 0 ]; do
  case "$1" in
    --restart) restart=$2; shift 2 ;;
    --time) time=$2; shift 2 ;;
    --fractions) fractions=$2; shift 2 ;;
    --np) np=$2; shift 2 ;;
    --runs) runs=$2; shift 2 ;;
    --append) append=yes; shift ;;
    --out) out=$2; shift 2 ;;
    *) echo "stability_drum: unknown option $1 (see the header of $0)" >&2; exit 2 ;;
  esac
done
[ -f "$restart" ] || { echo "stability_drum: --restart FILE (a settled 6 mm drum) is needed" >&2; exit 2; }
source "$(dirname "$0")/../tools/drum_common.sh"
mpirun_for "$np"
mkdir -p "$out" post/stability_drum

[ "$append" = yes ] || echo "en,dt_over_tc,model,status,beads_kept,beads,ke_final_J,guard" > "$out/stability_drum.csv"
for spec in ${runs//,/ }; do
  en=${spec%%:*}; model=${spec##*:}
  stock_for "$en" > "post/stability_drum/stock_$en.in"
  ref=""
  for f in ${fractions//,/ }; do
    dt=$(awk -v f="$f" 'BEGIN {printf "%.6g", f * 1e-4}')
    tag=en${en}_${f}_$model
    log=post/stability_drum/$tag.log
    echo "stability_drum: en $en, dt/tc $f, $model ..."
    status=ok
    "${mpirun[@]}" "$liggghts" -in inputs/drum.in -var start restart -var restart "$restart" -var rpm 21 \
      -var dt "$dt" -var time "$time" -var dumpdt 1 -var model "$model" -var stock "post/stability_drum/stock_$en.in" \
      -var name "stability_drum/$tag" > "$log" 2>&1 || status=stopped
    kept=$(sed -n 's/^drum: done, \([0-9]*\) beads kept.*/\1/p' "$log")
    total=$(sed -n 's/^drum: \([0-9]*\) beads (target.*/\1/p' "$log" | head -1)
    # last thermo line: step time atoms ke rke cpu
    ke=$(awk '/^ *Step +Time +Atoms +KinEng/ {on = 1; next} /^Loop time/ {on = 0} on && NF == 6 {k = $4} END {print k}' "$log")
    guard=none
    grep -q "exceeds the stable timestep" "$log" && guard=error
    [ "$status" = ok ] && [ "$f" = 0.1 ] && ref=$ke
    if [ "$status" = ok ]; then
      awk -v k="$kept" -v t="$total" -v e="$ke" -v r="${ref:-1e300}" 'BEGIN {exit !(k < t || e > 2 * r)}' && status=failed
    fi
    echo "$en,$f,$model,$status,${kept:-0},${total:-0},${ke:-nan},$guard" | tee -a "$out/stability_drum.csv"
  done
done
