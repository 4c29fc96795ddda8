#!/usr/bin/env bash
# Installs the Python package mtacc built in build/ with pip, for Debian's /usr/bin/python3.
#
# Where: as root, into /usr/local/lib/python3.11/dist-packages (pip's default there), beside
# Debian's numpy, scipy and matplotlib, so that `python3 -c "import mtacc"` and `mtacc report`
# (which runs /usr/bin/python3) work with no environment to activate. Debian 12 marks its Python
# as externally managed to keep pip away from the packages apt installed in /usr/lib/python3;
# --break-system-packages lifts that, and --no-deps keeps pip from touching any of them: it
# writes mtacc alone, under /usr/local, and `pip uninstall mtacc` removes it whole. As another
# user, pip installs into ~/.local. (A virtual environment made with --system-site-packages
# works too: MTACC_PIP="venv/bin/python -m pip" bash scripts/install-python.sh.)
set -euo pipefail
cd "$(dirname "$0")/.."
pip=(${MTACC_PIP:-/usr/bin/python3 -m pip})
stage=build/python-package
rm -rf "$stage"
cmake --install build --component python --prefix "$stage" > /dev/null
# Earlier versions of this script copied the package into the site folder without pip's record.
site=$(/usr/bin/python3 -c 'import sysconfig; print(sysconfig.get_path("purelib"))')
if [ -d "$site/mtacc" ] && ! compgen -G "$site/mtacc-*.dist-info" > /dev/null && [ -w "$site" ]; then
  rm -rf "$site/mtacc" "$site/mtacc.pth"
fi
"${pip[@]}" install --quiet --no-build-isolation --no-deps --no-index --break-system-packages \
  --disable-pip-version-check --root-user-action=ignore "$stage"
"${pip[@]}" show mtacc 2>/dev/null | grep -E '^(Name|Version|Location):' | paste -sd' '
