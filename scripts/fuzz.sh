#!/usr/bin/env bash
# Runs every libFuzzer harness of fuzz/ for SECONDS each (default 60), after replaying once the
# inputs kept in fuzz/regressions/<reader>/ (earlier findings, which must stay fixed) and the seeds.
# The test suite runs it for a few seconds a harness; long runs: scripts/fuzz.sh 600.
# Seeds: the bundled files of the reader's kind and fuzz/seeds/<reader>/. A new crash, leak,
# sanitizer report or hang (10 s per input) is saved in fuzz/regressions/<reader>/ and fails
# the run. Prints executions and coverage per harness.
# Usage: scripts/fuzz.sh [SECONDS] [--built]   (--built: build-sanitize/ is already built)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
[ "${2:-}" = --built ] || bash scripts/build-sanitize.sh
export ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
declare -A bundled=([machine_yaml]="data/machines tests/data" [errors_yaml]="data/machines data/stiffness"
                    [plan_yaml]="data/plans" [structure_yaml]="data/structures" [limits_yaml]="data/limits"
                    [cubic_test_yaml]="data/test-pieces" [positioning_files]="data/positioning" [component_runs_csv]="data/direct-measurements" [plate_csv]="data/plates" [artefact_csv]="data/artefacts" [cone_points_csv]="data/test-pieces" [drift_test_csv]="data/thermal" [thermal_state_yaml]="data/thermal" [spindle_drift_yaml]="data/thermal" [seed002_eccentricities_yaml]="data/ballbar" [measurement_conditions_yaml]="data/positioning" [tolerances_yaml]="data/positioning data/acceptance" [acceptance_yaml]="data/acceptance")
status=0
for harness in build-sanitize/fuzz/*_fuzzer; do
  reader=$(basename "$harness" _fuzzer)
  regressions=fuzz/regressions/$reader
  mkdir -p "$regressions"
  seeds=()
  for d in ${bundled[$reader]:-} fuzz/seeds/$reader; do [ -d "$d" ] && seeds+=("$d"); done
  # First every kept input once: earlier findings (files), which must stay fixed, then the seeds
  # (folders; libFuzzer takes either files or folders in one call).
  replay() {
    "$harness" -runs=0 -timeout=10 -rss_limit_mb=2048 "$@" 2>> "build-sanitize/$reader-replay.log" ||
      { echo "$reader: a kept input fails (build-sanitize/$reader-replay.log)"; status=1; }
  }
  rm -f "build-sanitize/$reader-replay.log"
  if compgen -G "$regressions/*" > /dev/null; then replay "$regressions"/*; fi
  if [ ${#seeds[@]} -gt 0 ]; then replay "${seeds[@]}"; fi
  corpus=build-sanitize/fuzz-corpus/$reader
  mkdir -p "$corpus"
  log=build-sanitize/$reader-fuzz.log
  if "$harness" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
       -artifact_prefix="$regressions/" "$corpus" "${seeds[@]}" 2> "$log"; then
    result=ok
  else
    result="FAILED (see $log; the input is in $regressions/)"
    status=1
  fi
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo 0)
  coverage=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*' || echo 0)
  printf '%-16s %10s executions  %6s coverage points  %s\n' "$reader" "$execs" "$coverage" "$result"
done
exit $status
