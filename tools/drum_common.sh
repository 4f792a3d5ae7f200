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
