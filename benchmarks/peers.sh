#!/usr/bin/env bash
# LIGGGHTS with this model against YADE (Debian's yade: ViscElMat +
# Law2_ScGeom_ViscElPhys_Basic, the thesis' own law) on the same drum state:
# the settled 12 mm slab of benchmarks/reductions.sh (32,672 beads; YADE's
# periodic collider needs a period above two bead diameters), same dt, same
# steps, rotating drum mesh and YADE's mixing rules on both sides
# (`-var wall moving -var conventions yade`). 1 core (1 MPI rank, yade -j1)
# and 2 cores (2 ranks, yade -j2), interleaved L Y L Y ... over --runs
# rounds; each side times its own stepping loop only (LIGGGHTS' loop time,
# YADE's O.run after 20 warm-up steps).
#
#   benchmarks/peers.sh [--state post/reduce/drum_L12] [--steps 200] [--runs 5] [--out benchmarks/results]
# Needs yade and pvpython (Debian's yade and paraview) besides liggghts.
set -euo pipefail
state=post/reduce/drum_L12; steps=200; runs=5; out=benchmarks/results
while [ $# -gt 0 ]; do
  case "$1" in
    --state) state=$2; shift 2 ;;
    --steps) steps=$2; shift 2 ;;
    --runs) runs=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    *) echo "peers: unknown option $1 (see the header of $0)" >&2; exit 2 ;;
  esac
done
for t in yade pvpython; do
  command -v "$t" > /dev/null || { echo "peers: needs $t (Debian: apt-get install yade paraview)" >&2; exit 2; }
done
here=$(cd "$(dirname "$0")" && pwd)
source "$here/../tools/drum_common.sh"
[ -f "$state.restart" ] || { echo "peers: $state.restart missing (run benchmarks/reductions.sh first)" >&2; exit 2; }
mkdir -p "$out" post/peers
# the restart and the last snapshot hold the same state (drum.in dumps at its end)
pvpython "$here/yade/vtp_to_csv.py" "$(last_snapshot "$state")" post/peers/beads.csv > /dev/null
beads=$(($(wc -l < post/peers/beads.csv) - 1))
dt=$drum_dt
time=$(awk -v n="$steps" -v dt="$dt" 'BEGIN {printf "%.10g", n * dt}')

# One YADE process per core count serves all rounds (its first step costs
# minutes, see drum_yade.py); before each timed round it runs the LIGGGHTS
# side (yade/liggghts_round.sh): L Y L Y ... with 1 core, then with 2.
echo "cores,round,liggghts_psps,yade_psps,ratio" > "$out/peers.csv"
for c in 1 2; do
  echo "peers: $c core(s), $runs interleaved rounds (YADE's first step takes minutes) ..."
  rm -f "post/peers/liggghts_np$c.txt"
  log=post/peers/yade_j$c.log
  yade -n -x -j"$c" "$here/yade/drum_yade.py" post/peers/beads.csv period=0.012 "steps=$steps" rpm=21 "dt=$dt" \
    "rounds=$runs" "before=$here/yade/liggghts_round.sh $state $time $beads $c" > "$log" 2>&1 \
    || { tail -5 "$log" >&2; exit 1; }
  [ "$(grep -c '^yade: round' "$log")" -eq "$runs" ] || { tail -5 "$log" >&2; exit 1; }
  if grep '^yade: round' "$log" | grep -vq ' 0 outside the drum'; then echo "peers: YADE lost beads ($log)" >&2; exit 1; fi
  sed -n 's/^yade: round \([0-9]*\),.* s, \([0-9.e+]*\) particle-steps\/s.*/\1 \2/p' "$log" \
    | paste -d' ' - "post/peers/liggghts_np$c.txt" \
    | awk -v c="$c" '{printf "%s,%s,%s,%s,%.4g\n", c, $1, $3, $2, $3 / $2}' | tee -a "$out/peers.csv"
done
{
  echo "beads=$beads"
  echo "steps=$steps"
  echo "dt=$dt"
  echo "runs=$runs"
  echo "state=$state"
  echo "yade_version=\"$(dpkg-query -W -f='${Version}' yade 2>/dev/null || echo '?')\""
  for c in 1 2; do
    for k in 3 4 5; do
      v=$(awk -F, -v c="$c" -v k="$k" 'NR > 1 && $1 == c {print $k}' "$out/peers.csv" | median)
      echo "median_${c}_$(head -1 "$out/peers.csv" | cut -d, -f"$k")=$v"
    done
  done
  echo "date=$(date -u +%Y-%m-%d)"
} > "$out/peers.env"
cat "$out/peers.env"
