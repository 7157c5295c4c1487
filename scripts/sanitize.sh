#!/usr/bin/env bash
# Builds everything with AddressSanitizer and UndefinedBehaviorSanitizer (into build-asan/)
# and runs the whole test suite under them. Mesa's own leaks at exit (its libraries are not
# instrumented) are suppressed by tests/sanitizers/lsan.supp; nothing of ours is.
# Built with Clang (RelWithDebInfo): the whole tree's Clang build, beside the GCC one of
# scripts/test.sh, and at less than half GCC's time with the sanitizers (cli/fuzz.cpp: 18 s
# against 44 s).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${GLRC_SANITIZE_BUILD_DIR:-build-asan}
CC=${GLRC_SANITIZE_CC:-clang} CXX=${GLRC_SANITIZE_CXX:-clang++} GLRC_BUILD_DIR=$build \
  GLRC_CMAKE_ARGS="-DGLRC_SANITIZE=address,undefined -DGLRC_FLAG_VARIANTS=OFF ${GLRC_CMAKE_ARGS:-}" \
  scripts/build.sh
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:detect_stack_use_after_return=0
export LSAN_OPTIONS=suppressions=$PWD/tests/sanitizers/lsan.supp:print_suppressions=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
log="$build/ctest.log"
if ctest --test-dir "$build" --output-on-failure -j "$(nproc)" --timeout 1200 2>&1 | tee "$log"; then
  exit 0
fi
# LeakSanitizer stops every thread of a process at its exit to scan the memory; its tracer
# sometimes crashes doing so ("Tracer caught signal 11") while threads of Mesa or of the image
# libraries are ending, which says nothing about the code under test. When every failed test
# shows that crash, they are run once more and must pass then; any other failure is final.
failed=$(grep -c . "$build/Testing/Temporary/LastTestsFailed.log" 2>/dev/null || echo 0)
tracer=$(grep -c "Tracer caught signal" "$log" || true)
if [ "$failed" -gt 0 ] && [ "$tracer" -ge "$failed" ]; then
  echo "sanitize.sh: LeakSanitizer's tracer crashed in $failed failed test(s); running them again" >&2
  ctest --test-dir "$build" --rerun-failed --output-on-failure --timeout 1200
  exit $?
fi
exit 1
