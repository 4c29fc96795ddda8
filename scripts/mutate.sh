#!/usr/bin/env bash
# The curated mutation run (issue 52): each mutant of tests/mutants.txt (file, exact text,
# replacement, why it is plausible) applied alone to a copy of the tree in build-mutate/, built
# incrementally through the compiler cache and run against ctest; prints a table and the score
# of killed mutants among those that compile to different code (target >= 90 %), and writes it to
# build-mutate/report.md. Not part of CI: about two minutes a mutant on two cores.
# Usage: scripts/mutate.sh [MUTANT_ID ...]   (default: all)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
exec /usr/bin/python3 scripts/mutate.py "$@"
