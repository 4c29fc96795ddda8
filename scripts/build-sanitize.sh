#!/usr/bin/env bash
# Configures and builds build-sanitize/: the library, CLI, C++ tests and fuzz harnesses with
# clang's AddressSanitizer and UndefinedBehaviorSanitizer (-O1, line tables for the reports),
# through the compiler cache (scripts/ccache-env.sh). No Python module, no benchmarks. It is the
# portable build (AVX2 and FMA, -DMTACC_PORTABLE=ON), so that the tests pass in both it and
# build/'s, made for this machine's own instruction sets.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/ccache-env.sh
CC=clang CXX=clang++ cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=Release "${ccache_launcher[@]}" \
  -DCMAKE_CXX_FLAGS_RELEASE="-O1 -gline-tables-only" -DMTACC_BUILD_FUZZERS=ON \
  -DMTACC_BUILD_PYTHON=OFF -DMTACC_BUILD_BENCH=OFF -DMTACC_PORTABLE=ON > /dev/null
cmake --build build-sanitize -j"$(nproc)"
ccache_summary build-sanitize/
