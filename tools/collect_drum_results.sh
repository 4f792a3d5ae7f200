#!/usr/bin/env bash
# Copies the drum results made by drum_sweep.sh (--name sweep), drum_wall_study.sh,
# drum_scaling.sh and the YADE-conventions run from post/ into docs/drum/, and
# renders the last sweep snapshot at 21 rpm with ParaView.
set -euo pipefail
out=docs/drum
mkdir -p "$out"
cp post/sweep/summary.md post/sweep/summary.csv post/sweep/summary.png "$out/"
for f in post/sweep/sweep_*rpm_metrics.txt; do cp "$f" "$out/"; done
cp post/sweep/sweep_21rpm_metrics.png post/sweep/sweep_7rpm_metrics.png "$out/"
[ -f post/wall_study/summary.md ] && cp post/wall_study/summary.md "$out/wall_study.md"
[ -f post/scaling/summary.md ] && cp post/scaling/summary.md "$out/scaling.md"
[ -f post/yade/yade_21rpm_metrics.txt ] && cp post/yade/yade_21rpm_metrics.txt "$out/"
xvfb-run -a pvbatch tools/render_drum.py post/sweep/sweep_21rpm --out "$out/drum_21rpm.png" --size 900
