#!/usr/bin/env bash
# Collects the drum results made by drum_sweep.sh (--name sweep), the YADE-
# conventions run, drum_wall_study.sh and drum_scaling.sh from post/ into
# docs/drum/, fills the tables of tools/drum_results.md.in from the generated
# files, and renders the 21 rpm state with ParaView. Run from the repository root.
set -euo pipefail
out=docs/drum
mkdir -p "$out"
cp post/sweep/summary.csv post/sweep/summary.png "$out/"
for f in post/sweep/sweep_*rpm_metrics.txt post/sweep/sweep_14rpm_metrics.png post/sweep/sweep_21rpm_metrics.png; do
  cp "$f" "$out/"
done
yade=$( { echo "| conventions | Hh [m] | Hd [m] | Hc [m] | drum force per bead [N] | angle of repose [deg] |"
          echo "|---|---|---|---|---|---|"
          for c in thesis yade; do
            awk -F, -v c="$c" 'NR == 2 { printf "| %s | %.4f ± %.4f | %.4f ± %.4f | %.5f ± %.5f | %.4f ± %.4f | %.2f ± %.2f |\n",
                c, $5, $6, $7, $8, $9, $10, $11, $12, $13, $14 }' "post/yade/${c}_21rpm_window_average.csv"
          done; } )
python3 - "$out/README.md" "$yade" <<'PY'
import sys
out, yade = sys.argv[1], sys.argv[2]
text = open("tools/drum_results.md.in").read()
text = text.replace("SUMMARY_TABLE", open("post/sweep/summary.md").read().strip())
text = text.replace("YADE_TABLE", yade.strip())
text = text.replace("WALL_TABLE", open("post/wall_study/summary.md").read().split("\n", 2)[2].strip())
text = text.replace("SCALING_TABLE", open("post/scaling/summary.md").read().split("\n", 2)[2].strip())
open(out, "w").write(text)
PY
xvfb-run -a pvbatch tools/render_drum.py post/sweep/sweep_21rpm --out "$out/drum_21rpm.png" --size 900
echo "wrote $out/README.md"
