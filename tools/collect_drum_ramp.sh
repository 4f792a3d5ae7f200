#!/usr/bin/env bash
# Collects the faster speeds and the speed ramp (Fig. 3.5-3.6) into
# docs/drum/speeds_and_ramp.md with its tables and charts:
#   post/high/   tools/drum_sweep.sh --speeds 42,49,56,63 --time 1.2 --settle 0.8 --name high
#   post/ramp/   tools/drum_sweep.sh --speeds 21 --time 1.2 --settle 0.8 --ramp 21:28:3 --name ramp
# plus docs/drum/summary.csv (the 7-42 rpm sweep) for the combined table.
# Run from the repository root; drum_metrics from PATH (or DRUM_METRICS=...).
set -euo pipefail
source "$(dirname "$0")/drum_common.sh"
out=docs/drum
ramp=post/ramp/ramp_ramp_21_28
mkdir -p "$out" post/combined

# metrics of the ramp run over time (speed from the run's own log of it)
"$metrics" series --prefix "$ramp" --dt "$drum_dt" --rpm 21 > "$ramp.metrics.txt"
# speed of each snapshot: the ramp is linear from its first snapshot (test DrumInput.RampRaisesTheSpeedLinearly)
awk -F, 'NR == 1 { print $0 ",rpm"; next } NR == 2 { t0 = $1 } { print $0 "," 21 + 7 * ($1 - t0) / 3 }' \
  "${ramp}_metrics.csv" > post/combined/ramp_metrics_rpm.csv
cp "${ramp}_run.csv" "$out/ramp_21_28_run.csv"
cp post/combined/ramp_metrics_rpm.csv "$out/ramp_21_28_metrics.csv"

gnuplot <<EOF
set terminal pngcairo size 1400,520 noenhanced
set output '$out/ramp_21_28.png'
set datafile separator ','
set multiplot layout 1,2 title 'speed ramp 21 -> 28 rpm over 3 s (6 mm period, 16,336 beads, dt = tc/10)'
set grid
set xlabel 'drum speed [rpm]'
set ylabel 'centre of mass Hc above the axis [m]'
set title 'Fig. 3.5: centre of mass'
plot '$out/ramp_21_28_run.csv' every ::1 using 2:5 with lines lw 2 notitle
set ylabel 'mean drum force along its motion per touching bead [N]'
set title 'Fig. 3.6: drum tangential force (grey: snapshots; line: moving average of 9)'
n = 9
array buf[n]
do for [i=1:n] { buf[i] = NaN }
k = 0
avg(x) = (k = k + 1, buf[(k - 1) % n + 1] = x, (k < n) ? NaN : (sum [i=1:n] buf[i]) / n)
plot '$out/ramp_21_28_metrics.csv' every ::2 using 9:7 with points pt 7 ps 0.6 lc rgb 'grey' notitle, \
     '' every ::2 using 9:(avg(\$7)) with lines lw 2 lc rgb 'dark-red' notitle
unset multiplot
EOF

# the faster speeds alone, and all speeds: the 7-42 rpm chain (docs/drum/summary.csv)
# with 49-63 rpm of the chain started at 42 rpm
"$metrics" table --out post/combined/high post/high/high_*rpm_average.csv > /dev/null
awk -F, 'NR == 1 || $1 != 42' post/combined/high.csv > post/combined/high_only.csv
"$metrics" table --out post/combined/all "$out/summary.csv" post/combined/high_only.csv > /dev/null
cp post/combined/all.png "$out/summary_all.png"
cp post/combined/all.csv "$out/summary_all.csv"
cp post/combined/high.csv "$out/summary_high.csv"
for f in post/high/high_*rpm_metrics.txt; do cp "$f" "$out/"; done
cp "$ramp.metrics.txt" "$out/ramp_21_28_metrics.txt"

python3 - "$out/speeds_and_ramp.md" <<'PY'
import sys
text = open("tools/drum_ramp.md.in").read()
text = text.replace("HIGH_TABLE", open("post/combined/high.md").read().strip())
text = text.replace("ALL_TABLE", open("post/combined/all.md").read().strip())
open(sys.argv[1], "w").write(text)
PY
echo "wrote $out/speeds_and_ramp.md"
