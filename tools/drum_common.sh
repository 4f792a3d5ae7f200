# Sourced by the drum scripts: executables, and an mpirun command line for
# $np ranks (as root Open MPI needs --allow-run-as-root; more ranks than
# cores need --oversubscribe).
liggghts=${LIGGGHTS:-liggghts}
metrics=${DRUM_METRICS:-drum_metrics}
mpirun_for() {  # ranks -> fills the array `mpirun`
  mpirun=(mpirun -np "$1")
  [ "$(id -u)" -eq 0 ] && mpirun+=(--allow-run-as-root)
  [ "$1" -gt "$(nproc)" ] && mpirun+=(--oversubscribe)
  return 0
}

# The timestep drum.in uses by default (to turn dump step numbers into times).
drum_dt=$(grep -E '^variable dt ' "$(dirname "${BASH_SOURCE[0]}")/../inputs/drum.in" | awk '{print $4}')

median() {  # of the numbers on stdin, one per line
  sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'
}

# Mass of a Table 3.1 glass bead (3 mm, 2500 kg/m^3), as LIGGGHTS computes it.
bead_mass=$(awk 'BEGIN {printf "%.17g", 4.0 / 3.0 * atan2(0, -1) * 0.0015^3 * 2500}')

# One drum.in run (mpirun as set by mpirun_for) logging to LOG; a failed run
# stops the calling script with the log's tail.
drum_run() {  # LOG -var NAME VALUE ...
  local log=$1
  shift
  "${mpirun[@]}" "$liggghts" -in inputs/drum.in "$@" > "$log" 2>&1 || { tail -5 "$log" >&2; exit 1; }
}

loop_time() {  # LOG -> LIGGGHTS' loop time [s] of its last run
  awk '/^Loop time of/ {t = $4} END {print t}' "$1"
}

last_snapshot() {  # PREFIX -> PREFIX_<step>.vtp with the highest step
  ls "$1"_*.vtp | sed 's/.*_\([0-9]*\)\.vtp/\1 &/' | sort -n | tail -1 | cut -d' ' -f2
}

# Stock hooke/stiffness constants (tools/stock_equivalent) for the type pairs
# (1,1) (1,2) (2,1) (2,2) of drum.in and column.in, tc 1e-4 s, bead mass for
# type 1 (type 2 is a wall): `table` is Table 3.1 with the thesis conventions
# (en 0.56 between beads, 0.46 with the drum; et 0.46), a number EN sets en =
# et = EN for every pair.
stock_for() {  # table | EN -> the constants file on stdout
  local en et
  if [ "$1" = table ]; then
    en=0.56,0.46,0.46,0.46 et=0.46,0.46,0.46,0.46
  else
    en=$1,$1,$1,$1 et=$1,$1,$1,$1
  fi
  "${STOCK_EQUIVALENT:-stock_equivalent}" --tc 1e-4,1e-4,1e-4,1e-4 --en "$en" --et "$et" --mass "$bead_mass,0"
}
