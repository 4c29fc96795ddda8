#!/usr/bin/env bash
# Installs the Debian packages mtacc needs (and nothing else). Safe to run repeatedly.
# Usage: scripts/install-deps.sh [--example]
#   --example: only what the main job needs: the library, the CLI, the Python module and the
#   report (no test, benchmark, sanitizer or browser packages)
set -euo pipefail
packages=(
  build-essential cmake pkg-config ccache
  libeigen3-dev libboost-dev libceres-dev libyaml-cpp-dev nlohmann-json3-dev libcli11-dev libfmt-dev libpng-dev libssl-dev
  python3 python3-dev pybind11-dev python3-numpy python3-matplotlib python3-pip python3-setuptools python3-wheel
)
if [ "${1:-}" != --example ]; then
  packages+=(
    libgtest-dev libgmock-dev libbenchmark-dev liborocos-kdl-dev
    python3-scipy python3-pytest python3-pytest-xdist
    # The benchmarks' NumPy and SciPy on OpenBLAS (its kernels for the CPU, AVX-512 where it has
    # them) rather than on the ATLAS that libceres-dev brings, or the reference BLAS
    libopenblas0-pthread
    clang libclang-rt-14-dev
    chromium
  )
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "Installing: ${missing[*]}"
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
