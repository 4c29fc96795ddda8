#!/usr/bin/env bash
# Configures and builds mtacc (Release) in build/ through the compiler cache
# (scripts/ccache-env.sh), then installs the Python package with pip (scripts/install-python.sh).
# Usage: scripts/build.sh [--example] [extra cmake args]
#   --example: only what the main job runs: the library, the CLI and the Python module (no
#   tests, no benchmarks), their sources compiled eight to a unit (CMake's unity build: the
#   headers, Eigen's above all, parsed once per eight files, which more than halves a cold
#   build; an edit recompiles its whole unit, so the test suite's build, which developers
#   rebuild, compiles file by file)
# Built for this machine's own instruction sets (-march=native: AVX-512 where it has them). For
# binaries that run on other CPUs: scripts/build.sh -DMTACC_PORTABLE=ON (AVX2 and FMA), adding
# -DMTACC_USE_AVX2=OFF for CPUs without them.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/ccache-env.sh
if [ "${1:-}" = --example ]; then
  shift
  set -- -DMTACC_BUILD_TESTS=OFF -DMTACC_BUILD_BENCH=OFF -DCMAKE_UNITY_BUILD=ON "$@"
else
  set -- -DMTACC_BUILD_TESTS=ON -DMTACC_BUILD_BENCH=ON -DCMAKE_UNITY_BUILD=OFF "$@"
fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${ccache_launcher[@]}" "$@" > /dev/null
cmake --build build -j"$(nproc)"
ccache_summary build/
bash scripts/install-python.sh
