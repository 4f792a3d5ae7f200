#!/usr/bin/env bash
# Regenerates the benchmarks: results in benchmarks/results/, then
# benchmarks/README.md from them (tables, the commands, the machine, the date).
#
#   benchmarks/run.sh [section ...]      sections: core cost stability (default: all)
#     core       Google Benchmark of the physics core's per-contact force (build/bench_core)
#     cost       model_cost.sh: viscoelastic vs stock hooke/stiffness on a settled drum slab
#                (RESTART=file to reuse a settled drum state; otherwise one is settled, ~8 min)
#     stability  stability.sh: dt/tc swept past failure, binary collision and dense column
# Run from the repository root after setup.sh (tools on PATH; BUILD=dir for bench_core).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
results=benchmarks/results
mkdir -p "$results"
sections=("$@")
[ ${#sections[@]} -gt 0 ] || sections=(core cost stability)

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
    stability)
      echo "benchmarks: stability ..."
      benchmarks/stability.sh --out "$results"
      ;;
    *) echo "benchmarks: unknown section $s (core cost stability)" >&2; exit 2 ;;
  esac
done
benchmarks/write_readme.sh
