#!/usr/bin/env bash
# Runs every fuzz target (tests/fuzz/) for a set time and prints, per target, the executions,
# the executions per second and the crashes and hangs found:
#
#   bash bench/fuzz.sh [SECONDS_PER_TARGET (default 60)] [TARGET...]
#
# The core's readers (off ply ply_gz obj scene atlas height) are libFuzzer targets of the sanitizer
# build (build-sanitize, built here if needed by scripts/test-sanitize.sh's configuration:
# Debian's clang with libclang-rt-14-dev); stl (VTK's reader behind tcMeshReader) and cli (the
# `trichart` command line) are in-process loops of the main build (build/, scripts/setup.sh).
# Each starts from its seed corpus and regression inputs; what libFuzzer adds to the corpus is
# kept in a scratch folder, not in the repository. A crash or hang leaves its input in
# $TRICHART_FUZZ_DIR/<target>/ (crash-*, timeout-*, leak-*, oom-*): once the bug is fixed,
# commit it as tests/fuzz/regressions/<target>/<name> and the tests replay it.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds="${1:-60}"
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(off ply ply_gz obj scene atlas height stl cli)
sanitize="${TRICHART_SANITIZE_BUILD_DIR:-$here/build-sanitize}"
main="${TRICHART_BUILD_DIR:-$here/build}"
work="${TRICHART_FUZZ_DIR:-${TMPDIR:-/tmp}/trichart-fuzz}"
fuzz="$here/tests/fuzz"
libfuzzer_targets=" off ply ply_gz obj scene atlas height "

inputs_of() { # the seed corpus and the regression inputs of target $1 that exist
  for d in "$fuzz/corpus/$1" "$fuzz/regressions/$1"; do [ -d "$d" ] && echo "$d"; done
}

# Builds what the chosen targets need.
need_sanitize=0 need_main=()
for t in "${targets[@]}"; do
  case "$libfuzzer_targets" in *" $t "*) need_sanitize=1 ;; esac
  [ "$t" = stl ] && need_main+=(tc_fuzz_stl)
done
if [ $need_sanitize = 1 ]; then
  if [ ! -f "$sanitize/build.ninja" ]; then
    bash "$here/scripts/test-sanitize.sh" -N >/dev/null # configures and builds; lists the tests
  fi
  cmake --build "$sanitize" -j "${TRICHART_JOBS:-$(nproc)}" --target $(printf 'tc_fuzz_%s ' \
    $(for t in "${targets[@]}"; do case "$libfuzzer_targets" in *" $t "*) echo "$t" ;; esac; done))
  if ! grep -q '^TRICHART_LIBFUZZER_ACTIVE:INTERNAL=ON' "$sanitize/CMakeCache.txt"; then
    echo "fuzz: $sanitize has no libFuzzer (needs clang and libclang-rt-14-dev)" >&2
    exit 1
  fi
  # The sanitizers' settings the tests run with (one place: cmake/TriChartSanitize.cmake).
  eval "$(sed -n 's/^set(ENV{\([A-Z_]*\)} "\(.*\)")$/export \1="\2"/p' \
    "$sanitize/TriChartSanitizeEnv.cmake")"
fi
if [ ${#need_main[@]} -gt 0 ]; then
  cmake --build "$main" -j "${TRICHART_JOBS:-$(nproc)}" --target "${need_main[@]}"
fi
python_path="$main/$(sed -n 's/^TRICHART_PYTHON_DESTINATION:STRING=//p' "$main/CMakeCache.txt" \
  2>/dev/null || true)"

rm -rf "$work"
mkdir -p "$work"
printf '%-8s %8s %12s %10s %8s %8s\n' target seconds executions "per s" crashes hangs
failed=0
for t in "${targets[@]}"; do
  out="$work/$t"
  mkdir -p "$out/corpus"
  log="$out/log.txt"
  start=$(date +%s.%N)
  status=0
  case "$t" in
    stl)
      "$main/bin/tc_fuzz_stl" --seconds "$seconds" --artifacts "$out" \
        $(inputs_of stl) >"$log" 2>&1 || status=$?
      executions=$(sed -n 's/^tc_fuzz_stl: \([0-9]*\) executions.*/\1/p' "$log")
      ;;
    cli)
      PYTHONPATH="$python_path" /usr/bin/python3 "$fuzz/fuzz_cli.py" --seconds "$seconds" \
        --artifacts "$out" $(inputs_of cli) >"$log" 2>&1 || status=$?
      executions=$(sed -n 's/^tc_fuzz_cli: \([0-9]*\) executions.*/\1/p' "$log")
      ;;
    *)
      # -timeout: an input running 10 s is a hang; -rss_limit_mb: a reader that allocates
      # what a damaged header declares is a failure, as the readers promise not to. The slow
      # unwinder is kept for scene only, whose libassimp leak suppression needs whole stacks;
      # it costs the others executions.
      unwind=1
      [ "$t" = scene ] && unwind=0
      ASAN_OPTIONS="$ASAN_OPTIONS:fast_unwind_on_malloc=$unwind" "$sanitize/bin/tc_fuzz_$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
        -print_final_stats=1 -artifact_prefix="$out/" "$out/corpus" $(inputs_of "$t") \
        >"$log" 2>&1 || status=$?
      executions=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
      ;;
  esac
  elapsed=$(echo "$(date +%s.%N) - $start" | bc)
  crashes=$(find "$out" -maxdepth 1 \( -name 'crash-*' -o -name 'leak-*' -o -name 'oom-*' \) | wc -l)
  hangs=$(find "$out" -maxdepth 1 -name 'timeout-*' | wc -l)
  if [ "$status" -ne 0 ] && [ "$crashes" -eq 0 ] && [ "$hangs" -eq 0 ]; then
    crashes=1 # stopped without saving its input: the log says why
  fi
  printf '%-8s %8.0f %12s %10.0f %8d %8d\n' "$t" "$elapsed" "${executions:-?}" \
    "$(echo "${executions:-0} / $elapsed" | bc -l)" "$crashes" "$hangs"
  if [ "$crashes" -ne 0 ] || [ "$hangs" -ne 0 ]; then
    failed=1
    echo "  see $log and the inputs in $out/" >&2
  fi
done
exit $failed
