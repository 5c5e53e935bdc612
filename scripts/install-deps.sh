#!/usr/bin/env bash
# Installs the Debian 12 packages TriChart builds and tests with. Idempotent: packages that
# are already installed are skipped, and nothing is downloaded when none is missing.
set -euo pipefail

packages=(
  g++ cmake ninja-build pkg-config git
  paraview-dev python3-paraview
  qtbase5-dev qttools5-dev libqt5opengl5-dev libqt5svg5-dev qtxmlpatterns5-dev-tools
  libutfcpp-dev libxml2-dev libhdf5-mpi-dev libogg-dev libtheora-dev libavformat-dev
  libswscale-dev libgl2ps-dev libpng-dev libnetcdf-dev libgdal-dev libglew-dev
  libdouble-conversion-dev libfreetype-dev
  libeigen3-dev libspectra-dev libcgal-dev libopenexr-dev libboost-graph-dev libassimp-dev
  libgtest-dev libtbb-dev zlib1g-dev libmeshoptimizer-dev nlohmann-json3-dev libtinygltf-dev
  # gltfpack: the peer of the glTF export (bench/gltf_export.py).
  gltfpack
  xvfb xauth mesa-utils libgl1-mesa-dri
  universal-ctags
  # The sanitizer build and its libFuzzer targets (scripts/test-sanitize.sh, bench/fuzz.sh);
  # llvm's llvm-symbolizer names the source line of each frame of a sanitizer's report.
  clang libclang-rt-14-dev llvm
  python3-numpy python3-pytest python3-matplotlib
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages already installed"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install-deps: installing ${#missing[@]} missing packages: ${missing[*]}"
$SUDO apt-get update -q
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
