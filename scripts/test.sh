#!/usr/bin/env bash
# Installs what is missing, builds softsub and its tests with warnings as errors, and runs
# the whole suite with CTest.
#   scripts/test.sh             Release build in build-test/
#   scripts/test.sh --sanitize  AddressSanitizer + UBSan build (-O1 -g1) in build-asan/
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

#   scripts/test.sh --fuzz      the libFuzzer targets (clang, ASan + UBSan) in build-fuzz/: every
#                               regression input, then each target for FUZZ_SECONDS (default 60)
mode=${1:-}
case "$mode" in
  "") dir=build-test; config=(-DCMAKE_BUILD_TYPE=Release) ;;
  # -O1 -g1 (line tables: stack traces keep file and line): with UBSan's checks GCC spends
  # 2.5 times as long compiling at -O2 -g, which made this build 22 of CI's 40 minutes;
  # the suite runs about 5% slower at -O1.
  --sanitize) dir=build-asan
    config=(-DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" -DSOFTSUB_SANITIZE=ON) ;;
  --fuzz) exec ./scripts/fuzz.sh ;;
  *) echo "usage: $0 [--sanitize | --fuzz]" >&2; exit 2 ;;
esac
# The benchmarks are built too (not run) so that they cannot rot unnoticed.
if [[ -f bench/CMakeLists.txt && -z "$mode" ]]; then config+=(-DSOFTSUB_BUILD_BENCH=ON); fi

./scripts/install-deps.sh
# SOFTSUB_TEST_MODULES empty: every test folder (a build folder may remember a narrower list).
cmake -S . -B "$dir" -G Ninja -DSOFTSUB_BUILD_TESTS=ON -DSOFTSUB_WERROR=ON -DSOFTSUB_TEST_MODULES= "${config[@]}"
cmake --build "$dir" -j2
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
# assimp's own leaks (fuzz/lsan-suppressions.txt says which), not ours
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/fuzz/lsan-suppressions.txt}
ctest --test-dir "$dir" --output-on-failure -j2
