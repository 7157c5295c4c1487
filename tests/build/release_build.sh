#!/usr/bin/env bash
# A user's Release build must not fail on warnings: -Werror is off unless asked for (CI asks),
# and the code is clean of the false positives GCC 12 reports only with Release's inlining (a
# -Wrestrict inside std::string in report/ (growth_text, now in comparison_sections.cpp) and
# casefile/ once broke `cmake -DCMAKE_BUILD_TYPE=Release`). Configures SOURCE into BUILD twice: with the defaults
# (GLRC_WERROR must be OFF), then with -Werror, and builds glrefcheck (every library and the CLI).
#   release_build.sh SOURCE BUILD CXX
set -euo pipefail
source=$1 build=$2 cxx=$3
rm -rf "$build"
configure() {
  cmake -S "$source" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER="$cxx" \
    -DGLRC_FLAG_VARIANTS=OFF -DGLRC_BUILD_TESTS=OFF "$@" >"$build.configure.log" 2>&1 ||
    { cat "$build.configure.log"; exit 1; }
}
configure
werror=$(sed -n 's/^GLRC_WERROR:BOOL=//p' "$build/CMakeCache.txt")
[ "$werror" = OFF ] || { echo "GLRC_WERROR defaults to '$werror', expected OFF"; exit 1; }
configure -DGLRC_WERROR=ON
cmake --build "$build" --target glrefcheck -j "$(nproc)" >"$build.build.log" 2>&1 ||
  { grep -E "error|warning" "$build.build.log" | head -20; exit 1; }
echo "Release build of glrefcheck with -Werror: clean"
