#!/usr/bin/env bash
# YADE against this model on the same head-on collisions of two glass beads
# (Table 3.1: en 0.56, tc 1e-4 s, 1 m/s, 128 contact-start phases each):
# YADE clips the normal force at zero (no attraction), as `limitForce on` does.
#
#   benchmarks/yade_collide.sh [--ratios 5,10,20,40,81] [--phases 128] [--out benchmarks/results]
# Needs yade (Debian package) and collide on PATH (or COLLIDE=...).
set -euo pipefail
ratios=5,10,20,40,81; phases=128; out=benchmarks/results
while [ $# -gt 0 ]; do
  case "$1" in
    --ratios) ratios=$2; shift 2 ;;
    --phases) phases=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    *) echo "yade_collide: unknown option $1 (see the header of $0)" >&2; exit 2 ;;
  esac
done
collide=${COLLIDE:-collide}
for t in yade; do
  command -v "$t" > /dev/null || { echo "yade_collide: needs $t (Debian: apt-get install yade paraview)" >&2; exit 2; }
done
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out" post/yade_collide
yade -n -x "$here/yade/collide_yade.py" post/yade_collide/yade.csv "ratios=$ratios" "phases=$phases" \
  > post/yade_collide/yade.log 2>&1 || { tail -20 post/yade_collide/yade.log >&2; exit 1; }
for lf in on off; do
  "$collide" sweep-dt --geometry pair --en 0.56 --et 0.46 --vn 1 --ratios ${ratios//,/ } --phases "$phases" \
    --limit-force "$lf" --csv "post/yade_collide/ours_$lf.csv" > /dev/null
done
"$collide" sweep-dt --geometry pair --en 0.56 --et 0.46 --vn 1 --ratios ${ratios//,/ } --phases "$phases" \
  --limit-force on --exact-restitution on --csv post/yade_collide/ours_on_exact.csv > /dev/null

# one row per tc/dt: restitution and contact duration (steps) of each
python3 - "$out/yade_collide.csv" <<'PY'
import csv, sys
def rows(p): return {float(r["tc_over_dt"]): r for r in csv.DictReader(open(p))}
y = rows("post/yade_collide/yade.csv")
on, off, ex = (rows("post/yade_collide/ours_%s.csv" % m) for m in ("on", "off", "on_exact"))
with open(sys.argv[1], "w") as f:
    f.write("tc_over_dt,yade_restitution,yade_min,yade_max,ours_limitForce_on,ours_limitForce_off,"
            "ours_limitForce_on_exact,yade_duration_steps,ours_limitForce_on_duration_err_steps\n")
    for r in sorted(y):
        f.write("%g,%s,%s,%s,%s,%s,%s,%s,%s\n" % (r, y[r]["restitution_mean"], y[r]["restitution_min"],
                y[r]["restitution_max"], on[r]["restitution"], off[r]["restitution"], ex[r]["restitution"],
                y[r]["duration_steps_mean"], on[r]["duration_err_steps"]))
PY
gnuplot <<GP
set terminal pngcairo size 900,560 noenhanced
set output '$out/yade_collide.png'
set datafile separator ','
set logscale x
set grid
set key top right
set xlabel 'tc / dt'
set ylabel 'normal restitution, head-on pair (mean of $phases start phases)'
set title 'YADE ViscElMat against viscoelastic (requested en = 0.56)'
plot 0.56 with lines dt 2 lc rgb 'black' title 'requested en', \
     '$out/yade_collide.csv' every ::1 using 1:2:3:4 with yerrorlines pt 7 title 'YADE 2023.02a (bars: min-max over phases)', \
     '' every ::1 using 1:5 with linespoints pt 5 title 'viscoelastic, limitForce on', \
     '' every ::1 using 1:6 with linespoints pt 9 title 'viscoelastic, limitForce off', \
     '' every ::1 using 1:7 with linespoints pt 13 title 'viscoelastic, limitForce on, exactRestitution on'
GP
cat "$out/yade_collide.csv"
