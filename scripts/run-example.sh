#!/usr/bin/env bash
# Main job: install what is missing, build, and show the bundled tilting-table example: its
# kinematic chain and its error budget.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
./build/mtacc check tilting-table
echo
./build/mtacc budget tilting-table
