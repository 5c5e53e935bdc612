#!/usr/bin/env bash
# Sets TriChart up on Debian 12: installs the missing Debian packages, configures, builds and
# installs (default prefix /usr/local), so that `import trichart` works in /usr/bin/python3 and
# pvpython, the ParaView plugin loads, and `trichart` / `trichart-viewer` are on PATH.
# Safe to run again: it only installs what is missing and rebuilds what changed.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${TRICHART_BUILD_DIR:-$here/build}"
prefix="${TRICHART_PREFIX:-/usr/local}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi

bash "$here/scripts/install-deps.sh"

echo "setup: configuring in $build"
cmake -S "$here" -B "$build" -G Ninja \
  -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_INSTALL_PREFIX="$prefix" \
  -DVTK_DIR=/usr/lib/x86_64-linux-gnu/cmake/paraview-5.11/vtk \
  -DPython3_EXECUTABLE=/usr/bin/python3 \
  -DTRICHART_SHARED_DATA_DIR="$(cd "$here/.." && pwd)/shared/data" >/dev/null
echo "setup: building with $(nproc) jobs"
cmake --build "$build" -j "$(nproc)"
echo "setup: installing into $prefix"
$SUDO cmake --install "$build" >/dev/null
$SUDO ldconfig
echo "setup: done ($(command -v trichart))"
