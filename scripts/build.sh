#!/usr/bin/env bash
# Configures and builds mtacc (Release) in build/, and makes the Python package importable
# by Debian's /usr/bin/python3 (a .pth file naming python/ of this checkout).
# Usage: scripts/build.sh [extra cmake args]
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "$@" > /dev/null
cmake --build build -j"$(nproc)"
site=$(/usr/bin/python3 -c 'import site; print(site.getsitepackages()[0])')
if mkdir -p "$site" 2>/dev/null && [ -w "$site" ]; then
  echo "$(pwd)/python" > "$site/mtacc.pth"
else
  echo "note: cannot write $site; use PYTHONPATH=$(pwd)/python to import mtacc" >&2
fi
