#!/usr/bin/env bash
# Regenerates the benchmarks: results in benchmarks/results/, then
# benchmarks/README.md from them (tables, the commands, the machine, the date).
#
#   benchmarks/run.sh [section ...]   sections (default: all, in this order; ~4 h on 2 cores):
#     core          Google Benchmark of the physics core's per-contact force (build/bench_core)
#     cost          model_cost.sh: viscoelastic vs stock hooke/stiffness on a settled drum slab
#                   (RESTART=file to reuse a settled 6 mm drum; otherwise one is settled, ~8 min)
#     accuracy      accuracy_cost.sh: dt = tc/5 ... tc/81, cost against two-body and drum errors
#                   (same RESTART, or the slab cost settled), ~40 min
#     multicontact  multicontact.sh: the dense column with exactRestitution, ~10 min
#     stability     stability.sh and stability_drum.sh: dt/tc swept past failure, binary
#                   collision, dense column and the drum (same RESTART), ~40 min
#     reductions    reductions.sh: 6 / 12 / 24 mm periods from the grid, ~1 h
#     peers         yade_collide.sh and peers.sh: YADE on the same collisions and drum state
#                   (the 12 mm state of reductions), ~15 min
#     scaling       the full drum (24 mm state of reductions) on 1 and 2 ranks, ~5 min
# Run from the repository root after setup.sh (tools on PATH; BUILD=dir for bench_core).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
results=benchmarks/results
mkdir -p "$results"
sections=("$@")
[ ${#sections[@]} -gt 0 ] || sections=(core cost accuracy multicontact stability reductions peers scaling)

for s in "${sections[@]}"; do
  case "$s" in
    core)
      echo "benchmarks: core (Google Benchmark, 5 repetitions) ..."
      "$build/bench_core" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
        --benchmark_format=csv > "$results/core.csv" 2> "$results/core.context"
      ;;
    cost)
      echo "benchmarks: cost ..."
      benchmarks/model_cost.sh ${RESTART:+--restart "$RESTART"} --steps 2000 --runs 5 --out "$results"
      ;;
    accuracy)
      echo "benchmarks: accuracy ..."
      benchmarks/accuracy_cost.sh --restart "${RESTART:-post/bench/slab.restart}" --out "$results"
      ;;
    multicontact)
      echo "benchmarks: multicontact ..."
      benchmarks/multicontact.sh --out "$results"
      ;;
    stability)
      echo "benchmarks: stability ..."
      benchmarks/stability.sh --out "$results"
      benchmarks/stability_drum.sh --restart "${RESTART:-post/bench/slab.restart}" --out "$results"
      benchmarks/stability_drum.sh --restart "${RESTART:-post/bench/slab.restart}" --out "$results" --append \
        --runs 0.3:hooke --fractions 0.1,0.21,0.22,0.23,0.24
      ;;
    reductions)
      echo "benchmarks: reductions ..."
      benchmarks/reductions.sh --out "$results"
      ;;
    peers)
      echo "benchmarks: peers ..."
      benchmarks/yade_collide.sh --out "$results"
      benchmarks/peers.sh --steps 300 --runs 5 --out "$results"
      ;;
    scaling)
      echo "benchmarks: scaling ..."
      tools/drum_scaling.sh --restart post/reduce/drum_L24.restart --period 0.024 --ranks 1,2 --rounds 5 \
        --time 0.003 --name bench_scaling
      cp post/bench_scaling/timings.csv "$results/scaling.csv"
      cp post/bench_scaling/summary.md "$results/scaling.md"
      ;;
    *) echo "benchmarks: unknown section $s (core cost accuracy multicontact stability reductions peers scaling)" >&2
       exit 2 ;;
  esac
done
benchmarks/write_readme.sh
