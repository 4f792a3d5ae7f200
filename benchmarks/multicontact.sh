#!/usr/bin/env bash
# Many simultaneous contacts with exactRestitution: the dense column
# (inputs/column.in, 2009 beads dropped onto a floor, en = 0.56) at tc/10
# with nominal and with exact coefficients, against the finest timestep with
# nominal coefficients (the reference). Compared: the kinetic energy over
# time (the collapse dissipates through many simultaneous contacts), the
# time the column needs to come to rest, and its final height.
#
#   benchmarks/multicontact.sh [--out benchmarks/results] [--reference 100]
set -euo pipefail
out=benchmarks/results; ref=100
while [ $# -gt 0 ]; do
  case "$1" in
    --out) out=$2; shift 2 ;;
    --reference) ref=$2; shift 2 ;;
    *) echo "multicontact: unknown option $1 (see the header of $0)" >&2; exit 2 ;;
  esac
done
source "$(dirname "$0")/../tools/drum_common.sh"
mkdir -p "$out" post/multicontact

runs=("nominal_10:10:off" "exact_10:10:on" "nominal_20:20:off" "exact_20:20:on" "reference_${ref}:${ref}:off")
for r in "${runs[@]}"; do
  IFS=: read -r tag ratio exact <<< "$r"
  dt=$(awk -v r="$ratio" 'BEGIN {printf "%.6g", 1e-4 / r}')
  echo "multicontact: $tag (dt = tc/$ratio, exactRestitution $exact) ..."
  "$liggghts" -in inputs/column.in -var dt "$dt" -var exact "$exact" -var time 0.3 \
    -var name "multicontact/$tag" > "post/multicontact/$tag.log" 2>&1 || { tail -5 "post/multicontact/$tag.log" >&2; exit 1; }
  cp "post/multicontact/${tag}_series.csv" "$out/multicontact_$tag.csv"
done

# summary: peak kinetic energy, time to rest (kinetic energy below 1e-6 J for
# good), final centre-of-mass height; differences against the reference
summary() {  # csv -> "peak t_rest zc"
  awk -F, 'NR > 1 { t[NR] = $1; k[NR] = $2 + $3; z[NR] = $4; n = NR; if (k[NR] > peak) peak = k[NR] }
           END { rest = t[n]; for (i = n; i > 1 && k[i] < 1e-6; --i) rest = t[i]; printf "%.6g %.4f %.6f", peak, rest, z[n] }' "$1"
}
read -r rp rt rz <<< "$(summary "$out/multicontact_reference_${ref}.csv")"
{
  echo "run,peak_kinetic_energy_J,time_to_rest_s,final_centre_height_m,peak_vs_reference,rest_time_vs_reference_s,height_vs_reference_m"
  for r in "${runs[@]}"; do
    tag=${r%%:*}
    read -r p t z <<< "$(summary "$out/multicontact_$tag.csv")"
    awk -v tag="$tag" -v p="$p" -v t="$t" -v z="$z" -v rp="$rp" -v rt="$rt" -v rz="$rz" \
      'BEGIN {printf "%s,%s,%s,%s,%+.4f,%+.4f,%+.6f\n", tag, p, t, z, p / rp - 1, t - rt, z - rz}'
  done
} > "$out/multicontact.csv"
cat "$out/multicontact.csv"

gnuplot <<EOF
set terminal pngcairo size 1000,600 noenhanced
set output '$out/multicontact.png'
set datafile separator ','
set title 'dense column (2009 beads, en = 0.56): kinetic energy (translation + rotation)'
set xlabel 'time [s]'
set ylabel 'kinetic energy [J]'
set logscale y
set grid
plot '$out/multicontact_reference_${ref}.csv' every ::1 using 1:(\$2+\$3) with lines lw 3 lc rgb 'black' title 'tc/$ref nominal (reference)', \
     '$out/multicontact_nominal_10.csv' every ::1 using 1:(\$2+\$3) with lines lw 2 title 'tc/10 nominal', \
     '$out/multicontact_exact_10.csv' every ::1 using 1:(\$2+\$3) with lines lw 2 title 'tc/10 exactRestitution', \
     '$out/multicontact_nominal_20.csv' every ::1 using 1:(\$2+\$3) with lines lw 1 dt 2 title 'tc/20 nominal', \
     '$out/multicontact_exact_20.csv' every ::1 using 1:(\$2+\$3) with lines lw 1 dt 2 title 'tc/20 exactRestitution'
EOF
