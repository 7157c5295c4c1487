#!/usr/bin/env bash
# Installs what glrefcheck needs (Debian 12 packages) and builds it into build/.
# Quiet unless something fails; set GLRC_BUILD_DIR to build elsewhere.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
build=${GLRC_BUILD_DIR:-build}
# GLRC_CMAKE_ARGS: more -D options (CI: -DGLRC_WERROR=ON; scripts/sanitize.sh: sanitizers).
# shellcheck disable=SC2086
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo ${GLRC_CMAKE_ARGS:-} >"$build.configure.log" 2>&1 ||
  { cat "$build.configure.log"; exit 1; }
cmake --build "$build" -j "$(nproc)" >"$build.build.log" 2>&1 || { tail -50 "$build.build.log"; exit 1; }
echo "built $build/glrefcheck"
