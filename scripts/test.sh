#!/usr/bin/env bash
# Installs, builds and runs the test suite (ctest: unit tests, GL tests on llvmpipe and softpipe
# through OSMesa and EGL, reference digests under three flag sets).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
ctest --test-dir "${GLRC_BUILD_DIR:-build}" --output-on-failure -j "$(nproc)"
