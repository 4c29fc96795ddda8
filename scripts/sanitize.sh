#!/usr/bin/env bash
# The C++ test suite and the bad-input corpus under AddressSanitizer and
# UndefinedBehaviorSanitizer: any report fails the test that caused it (the CLI the tests call is
# instrumented too). --built: build-sanitize/ is already built.
set -euo pipefail
cd "$(dirname "$0")/.."
[ "${1:-}" = --built ] || bash scripts/build-sanitize.sh
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
(cd build-sanitize && ctest --output-on-failure -j"$(nproc)")
