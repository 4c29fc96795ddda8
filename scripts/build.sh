#!/usr/bin/env bash
# Configures and builds mtacc (Release) in build/, and installs the Python package mtacc into
# the site directory of Debian's /usr/bin/python3 (module, sources and a copy of the bundled
# data: it keeps working when this checkout moves or goes).
# Usage: scripts/build.sh [extra cmake args]
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "$@" > /dev/null
cmake --build build -j"$(nproc)"
site=$(/usr/bin/python3 -c 'import sysconfig; print(sysconfig.get_path("purelib"))')
rm -f "$site/mtacc.pth"  # left by earlier versions, which pointed at one checkout
if mkdir -p "$site" 2>/dev/null && [ -w "$site" ]; then
  cmake --install build --component python > /dev/null
else
  echo "note: cannot write $site; use PYTHONPATH=$(pwd)/build/python to import mtacc" >&2
fi
