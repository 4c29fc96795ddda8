#!/usr/bin/env bash
# Whole test suite: install what is missing, build, run every unit and reference test, then
# the benchmarks (figures with their baseline ratios).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
(cd build && ctest --output-on-failure -j"$(nproc)")
echo
echo "== Benchmark: batch forward kinematics against orocos KDL =="
./build/bench/bench_fk_vs_kdl --benchmark_min_time=0.2 --benchmark_color=false
