#!/bin/bash
# The memory estimate of `trichart build` (tc/gim/build_memory.h) against the peak resident
# memory that /usr/bin/time -v measures, on the shared meshes: one line per build with the
# estimate, the memory held at the start, the measured peak and estimate / (peak - start).
# Usage: bench/build_memory.sh [build dir, default build] [shared data, default the build's
# TRICHART_SHARED_DATA_DIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
data=${2:-$(grep -m1 '^TRICHART_SHARED_DATA_DIR:' "$build/CMakeCache.txt" | cut -d= -f2)}
python=$(grep -m1 '^Python3_EXECUTABLE:' "$build/CMakeCache.txt" | cut -d= -f2)
destination=$(grep -m1 '^TRICHART_PYTHON_DESTINATION:' "$build/CMakeCache.txt" | cut -d= -f2)
export PYTHONPATH="$build/$destination"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

measure() { # mesh, then build options
  local mesh=$1
  shift
  [ -f "$data/$mesh" ] || { echo "$mesh: absent, skipped"; return; }
  /usr/bin/time -v -o "$work/time" "${python:-python3}" -m trichart build "$data/$mesh" \
    -o "$work/atlas.exr" -q "$@" > "$work/out"
  local peak estimate start
  peak=$(awk '/Maximum resident set size/ {print int($NF / 1024)}' "$work/time")
  read -r estimate start < <(sed -n \
    's/.*estimated \([0-9]*\) MB above the \([0-9]*\) MB.*/\1 \2/p' "$work/out")
  awk -v m="$mesh $*" -v e="$estimate" -v s="$start" -v p="$peak" 'BEGIN {
    printf "%-52s estimate %6d MB  start %4d MB  peak %6d MB  estimate/(peak-start) %.2f\n",
      m, e, s, p, e / (p - s) }'
}

measure static_small/homer.off
measure static_medium/armadillo.off
measure static_medium/bunny00.off
measure static_medium/refined_elephant.off
measure static_medium/bunny_glmark2.obj
measure static_medium/bunny00.off --budget 400000 --max-level 10
measure static_medium/bunny00.off --budget 1600000 --max-level 10
measure static_large/bunny00_loop2.ply.gz
