#!/usr/bin/env bash
# Every benchmark at full size with its baseline, side by side in one run, printing its ratio
# (bench/README.md). Installs and builds what is missing first (scripts/build.sh).
# Usage: scripts/bench.sh [NAME ...]   (e.g. bench_identify_vs_scipy; default: all twelve)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
# name | what it measures (in the order they run)
benchmarks=(
  "bench_fk_vs_kdl|batch forward kinematics against orocos KDL (full frames, 1 thread each)"
  "bench_cone_monte_carlo|cone-frustum Monte Carlo, 1000 samples, exact evaluation"
  "bench_cubic_zmap|seed 001 cubic machining test, surface on a 10 um grid; the removal against a NumPy z-buffer"
  "bench_identify_vs_scipy|identification of 13 parameters from 10,000 R-test points, against SciPy (analytic Jacobian, LM)"
  "bench_plate_identification|component errors from a 24-plate campaign (seed 003), against NumPy + SciPy"
  "bench_program_compensation|compensating a 1,000,000-line 5-axis program, against a vectorised NumPy Newton"
  "bench_program_streaming|a 20,000,000-line program streamed from file to file: peak memory and rate, against the whole program in memory"
  "bench_dynamics_vs_numpy|3x3 FRF at 500 frequencies at 10,000 positions of a 10-body model, against vectorised NumPy"
  "bench_decomposition_vs_numpy|seed 004's decomposition of six feeds of 150,000 samples, against NumPy + SciPy"
  "bench_sensor_selection_vs_numpy|stepwise choice among 64 temperature sensors on 24 h at 1 Hz, against NumPy"
  "bench_experiment_design_vs_numpy|D-optimal choice of 60 among 10,000 R-test poses for 13 parameters, against NumPy"
  "bench_python_batch_fk|the Python batch API against the C++ call it wraps"
)
declare -A title=()
for entry in "${benchmarks[@]}"; do title[${entry%%|*}]=${entry#*|}; done
order=("${benchmarks[@]%%|*}")
[ $# -gt 0 ] && order=("$@")
status=0
for name in "${order[@]}"; do
  [ -n "${title[$name]:-}" ] || { echo "bench.sh: no benchmark '$name' (the benchmarks: ${benchmarks[*]%%|*})" >&2; exit 2; }
  echo
  echo "== Benchmark: ${title[$name]} =="
  args=()
  [ "$name" = bench_fk_vs_kdl ] && args=(--benchmark_min_time=0.2)
  [[ "$name" = bench_fk_vs_kdl || "$name" = bench_cone_monte_carlo ]] && args+=(--benchmark_color=false)
  "./build/bench/$name" "${args[@]}" || { echo "$name: FAILED"; status=1; }
done
exit $status
