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
# use_tls=0: LeakSanitizer (compiler-rt 14, and GCC 12's libasan) takes a stale entry of glibc
# 2.36's dynamic-TLS vector for a range to scan once the vector has been resized, and its tracer
# crashes on it at exit ("Tracer caught signal 11", "DTLS 19 at 0x22de-0x8000033e0" with
# log_threads=1), at random with the memory layout. Not scanning TLS can only report more leaks,
# never fewer: what only TLS points to (glibc's and GLib's per-thread blocks) is suppressed by
# name in lsan.supp.
export LSAN_OPTIONS=suppressions=$PWD/tests/sanitizers/lsan.supp:print_suppressions=0:use_tls=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --test-dir "$build" --output-on-failure -j "$(nproc)" --timeout 1200
