#!/usr/bin/env bash
# The LIGGGHTS side of one peers.sh round, run by drum_yade.py before each of
# its timed rounds. Appends LIGGGHTS' particle-steps per second to
# post/peers/liggghts_np<cores>.txt.
#   benchmarks/yade/liggghts_round.sh STATE TIME BEADS CORES ROUND
set -euo pipefail
state=$1 time=$2 beads=$3 cores=$4 round=$5
source "$(dirname "$0")/../../tools/drum_common.sh"
mpirun_for "$cores"
tag=liggghts_np${cores}_r$round
drum_run "post/peers/$tag.log" -var start restart -var restart "$state.restart" \
  -var period 0.012 -var rpm 21 -var wall moving -var conventions yade -var time "$time" \
  -var dumpdt 1 -var name "peers/$tag"
awk -v n="$beads" '/^Loop time of/ {printf "%.6g\n", n * $9 / $4}' "post/peers/$tag.log" >> "post/peers/liggghts_np$cores.txt"
