#!/usr/bin/env bash
# The sanitizer run of scripts/test.sh: a second, small build (the core, its tests and the fuzz
# targets; no VTK) compiled with -fsanitize=address,undefined in build-sanitize, and its tests:
# the core tests and every bad-input case (the readers' damaged copies, the fuzz targets' seed
# corpora and regression inputs, tests/fuzz/). Any sanitizer report fails its test.
# With Debian's clang and libclang-rt-14-dev the fuzz targets are libFuzzer's (bench/fuzz.sh
# runs them); with GCC alone they only replay their inputs.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${TRICHART_SANITIZE_BUILD_DIR:-$here/build-sanitize}"
main="${TRICHART_BUILD_DIR:-$here/build}"
# The larger test meshes: those of the main build (scripts/setup.sh's choice), if it has some.
shared="$(sed -n 's/^TRICHART_SHARED_DATA_DIR:PATH=//p' "$main/CMakeCache.txt" 2>/dev/null || true)"
shared="${shared:-$(cd "$here/.." && pwd)/shared/data}"
# Of those, this build's tests see only the files the readers' damaged-copy tests break (the
# scenes and a scan): the algorithm tests' pipelines on the larger meshes take over 20 minutes
# under the sanitizers on 2 cores, and the main build runs them; here they run on testing-data.
mkdir -p "$build"
inputs="$build/shared-data"
rm -rf "$inputs"
mkdir -p "$inputs/static_small"
for f in skinned static_small/dragon_vrip_res4.ply.gz; do
  if [ -e "$shared/$f" ]; then ln -s "$shared/$f" "$inputs/$f"; fi
done
jobs="${TRICHART_JOBS:-$(nproc)}"

compilers=()
if command -v clang++ >/dev/null; then
  compilers=(-DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++)
fi
launcher=()
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
echo "test: the sanitizer build in $build"
cmake -S "$here" -B "$build" -G Ninja "${compilers[@]}" "${launcher[@]}" \
  -DCMAKE_BUILD_TYPE=Release -DTRICHART_SANITIZE=ON -DTRICHART_BUILD_VTK=OFF \
  -DTRICHART_SHARED_DATA_DIR="$inputs" >/dev/null
# Only what the tests run: not the benchmarks.
targets=(tc_core_tests $(sed -n 's/^build \(tc_fuzz_[a-z_]*\): phony.*/\1/p' "$build/build.ninja"))
cmake --build "$build" -j "$jobs" --target "${targets[@]}"
echo "test: ctest under AddressSanitizer and UndefinedBehaviorSanitizer"
cd "$build"
ctest --output-on-failure -j "$jobs" -L 'core|fuzz' "$@"
