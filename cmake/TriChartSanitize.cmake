# TRICHART_SANITIZE: a build folder whose every target runs under AddressSanitizer (with its
# leak checker) and UndefinedBehaviorSanitizer, for the core, its tests and the fuzz targets
# (scripts/test-sanitize.sh, run by scripts/test.sh, configures one core-only in
# build-sanitize). Any report aborts the program, so a test that triggers one fails.
#
# The code is compiled as Release is (NDEBUG: the checks are those of the shipped code) but at
# -O1 with line tables: -O1 keeps the sanitizers' reports exact and the build short; -g1 names
# the source line of every frame in a report.
#
# With clang and libFuzzer (Debian's clang and libclang-rt-14-dev), TRICHART_LIBFUZZER is set:
# the core is also compiled with libFuzzer's coverage instrumentation and the fuzz targets
# (tests/fuzz/) link libFuzzer's main; otherwise they link a main that only replays inputs.
option(TRICHART_SANITIZE "Compile everything with -fsanitize=address,undefined (a separate build folder)" OFF)
set(TRICHART_LIBFUZZER OFF)
# Whether this build's fuzz targets are libFuzzer's, for bench/fuzz.sh to read.
set(TRICHART_LIBFUZZER_ACTIVE OFF CACHE INTERNAL "")
if (NOT TRICHART_SANITIZE)
  return ()
endif ()

add_compile_options(-fsanitize=address,undefined -fno-sanitize-recover=undefined
  -fno-omit-frame-pointer -O1 -g1)
add_link_options(-fsanitize=address,undefined)

# Every test of this build runs with these settings, however ctest is started: the file is read
# by ctest before it runs any test (TEST_INCLUDE_FILES), and what it sets in the environment the
# tests inherit (bench/fuzz.sh reads it too). A report stops the program with a failing status.
# LeakSanitizer skips only the third-party leaks of tests/sanitize/lsan.supp, which it can name
# only from whole stacks: the fast unwinder stops at the first library built without frame
# pointers (zlib, under Assimp's leak), and the slow one costs the core tests about 8%.
set(_tc_sanitize_env "${CMAKE_BINARY_DIR}/TriChartSanitizeEnv.cmake")
file(WRITE "${_tc_sanitize_env}"
  "set(ENV{ASAN_OPTIONS} \"detect_leaks=1:fast_unwind_on_malloc=0:halt_on_error=1:exitcode=23\")\n"
  "set(ENV{UBSAN_OPTIONS} \"print_stacktrace=1:halt_on_error=1\")\n"
  "set(ENV{LSAN_OPTIONS} \"suppressions=${CMAKE_SOURCE_DIR}/tests/sanitize/lsan.supp:print_suppressions=0\")\n")
set_property(DIRECTORY "${CMAKE_SOURCE_DIR}" APPEND PROPERTY TEST_INCLUDE_FILES "${_tc_sanitize_env}")

if (CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  include(CheckCXXSourceCompiles)
  set(CMAKE_REQUIRED_LINK_OPTIONS -fsanitize=fuzzer)
  check_cxx_source_compiles([[
    #include <cstddef>
    #include <cstdint>
    extern "C" int LLVMFuzzerTestOneInput(const uint8_t*, size_t) { return 0; }
  ]] TRICHART_HAVE_LIBFUZZER)
  unset(CMAKE_REQUIRED_LINK_OPTIONS)
  if (TRICHART_HAVE_LIBFUZZER)
    set(TRICHART_LIBFUZZER ON)
    set(TRICHART_LIBFUZZER_ACTIVE ON CACHE INTERNAL "")
  else ()
    message(STATUS "TriChart: clang without libFuzzer (Debian: libclang-rt-14-dev); the fuzz "
      "targets only replay their corpora")
  endif ()
endif ()
