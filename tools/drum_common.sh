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
