#!/usr/bin/env bash
# Builds everything with AddressSanitizer and UndefinedBehaviorSanitizer (into build-asan/)
# and runs the whole test suite under them. Mesa's own leaks at exit (its libraries are not
# instrumented) are suppressed by tests/sanitizers/lsan.supp; nothing of ours is.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${GLRC_SANITIZE_BUILD_DIR:-build-asan}
GLRC_BUILD_DIR=$build GLRC_CMAKE_ARGS="-DGLRC_SANITIZE=address,undefined -DGLRC_FLAG_VARIANTS=OFF ${GLRC_CMAKE_ARGS:-}" \
  scripts/build.sh
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:detect_stack_use_after_return=0
export LSAN_OPTIONS=suppressions=$PWD/tests/sanitizers/lsan.supp:print_suppressions=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --test-dir "$build" --output-on-failure -j "$(nproc)" --timeout 1200
