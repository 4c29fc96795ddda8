#!/usr/bin/env bash
# Whole test suite: install what is missing, build (through the compiler cache), run every test
# through ctest (C++ unit and reference tests, the layer check, every benchmark's agreement check
# at a small size, and the Python tests including the report in headless Chromium; screenshots
# kept in build/test-artifacts/), the C++ tests and the bad-input corpus under the sanitizers, then
# a replay of every fuzz harness's kept inputs and a short fuzz run. Ends with each phase's
# seconds. The benchmarks at full size: scripts/bench.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
fuzz_seconds=${MTACC_FUZZ_SECONDS:-3}

names=()
times=()
print_phases() {
  local status=$?
  echo
  echo "== Phases (seconds) =="
  for i in "${!names[@]}"; do printf '%-20s %6d\n' "${names[$i]}" "${times[$i]}"; done
  printf '%-20s %6d\n' total "$SECONDS"
  exit $status
}
trap print_phases EXIT
phase() {
  local name=$1 start=$SECONDS status=0
  shift
  echo
  echo "== $name =="
  "$@" || status=$?
  names+=("$name$([ $status -eq 0 ] || echo ' (FAILED)')")
  times+=($((SECONDS - start)))
  return $status
}

phase install bash scripts/install-deps.sh
phase build bash scripts/build.sh
phase ctest bash -c 'cd build && ctest --output-on-failure -j"$(nproc)"'
phase "sanitizer build" bash scripts/build-sanitize.sh
phase "sanitizer ctest" bash scripts/sanitize.sh --built
phase fuzz bash scripts/fuzz.sh "$fuzz_seconds" --built
