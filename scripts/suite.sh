#!/usr/bin/env bash
# Installs, builds and runs the conformance suite on the system Mesa: llvmpipe and softpipe,
# through OSMesa and through EGL, and zink (GL on Vulkan, on lavapipe) through EGL (OSMesa
# cannot run zink), with the known driver bugs in cases/known-failures.txt (every driver) or
# cases/known-failures-<driver>.txt where there is one (softpipe's and zink's own bugs, and those).
# Results go to out/<backend>-<driver>/. Exit 1 if any run has an unexpected result.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
status=0
for run in osmesa-llvmpipe osmesa-softpipe egl-llvmpipe egl-softpipe egl-zink; do
  backend=${run%%-*} driver=${run#*-}
  echo
  baseline=cases/known-failures.txt
  [ -f "cases/known-failures-$driver.txt" ] && baseline="cases/known-failures-$driver.txt"
  "${GLRC_BUILD_DIR:-build}"/glrefcheck run cases --backend "$backend" --driver "$driver" \
    --baseline "$baseline" --out "out/$run" || status=1
done
exit $status
