#!/usr/bin/env bash
# Main job: install what is missing (the library's, the CLI's, the Python module's and the
# report's packages only), build only those (no tests, no benchmarks), and write the accuracy
# report of the bundled tilting-table machine (with its documented, realistic errors) to report/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --example
bash scripts/build.sh --example
./build/mtacc check tilting-table
echo
./build/mtacc budget tilting-table --rows 10
echo
report=$(./build/mtacc report tilting-table --plan tilting-table-rtest --structure tzyx-arm-x --compare tzyx-arm-y -o report)
echo "Report written: $(pwd)/$report — open it in a browser."
