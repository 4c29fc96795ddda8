#!/usr/bin/env bash
# Whole test suite: install what is missing, build, run every test through ctest (C++ unit and
# reference tests, the layer check, and the Python tests including the report in headless
# Chromium; screenshots kept in build/test-artifacts/), the C++ tests under the sanitizers, a
# short fuzz run of every reader, then the benchmarks.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
(cd build && ctest --output-on-failure -j"$(nproc)")
echo
echo "== The C++ tests under AddressSanitizer and UndefinedBehaviorSanitizer =="
bash scripts/sanitize.sh
echo
echo "== Fuzzing: every reader's harness for 8 s =="
bash scripts/fuzz.sh 8
echo
echo "== Benchmark: batch forward kinematics against orocos KDL (full frames, 1 thread each) =="
./build/bench/bench_fk_vs_kdl --benchmark_min_time=0.2 --benchmark_color=false
echo
echo "== Benchmark: cone-frustum Monte Carlo, 1000 samples, exact evaluation =="
./build/bench/bench_cone_monte_carlo --benchmark_color=false
echo
echo "== Benchmark: seed 001 cubic machining test, surface on a 10 um grid, against a per-cell loop over all moves =="
./build/bench/bench_cubic_zmap
echo
echo "== Benchmark: identification of 13 parameters from 10,000 R-test points, against SciPy (analytic Jacobian, LM) =="
./build/bench/bench_identify_vs_scipy
echo
echo "== Benchmark: component errors from a 24-plate campaign (seed 003), against NumPy + SciPy =="
./build/bench/bench_plate_identification
echo
echo "== Benchmark: compensating a 1,000,000-line 5-axis program, against a vectorised NumPy Newton =="
./build/bench/bench_program_compensation
echo
echo "== Benchmark: 3x3 FRF at 500 frequencies at 10,000 positions of a 10-body model, against vectorised NumPy =="
./build/bench/bench_dynamics_vs_numpy
echo
echo "== Benchmark: seed 004's decomposition of six feeds of 150,000 samples, against NumPy + SciPy =="
./build/bench/bench_decomposition_vs_numpy
echo
echo "== Benchmark: stepwise choice among 64 temperature sensors on 24 h at 1 Hz, against NumPy =="
./build/bench/bench_sensor_selection_vs_numpy
echo
echo "== Benchmark: the Python batch API against the C++ call it wraps =="
./build/bench/bench_python_batch_fk
