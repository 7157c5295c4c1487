#!/usr/bin/env bash
# Installs, builds and runs the conformance suite on the system Mesa: llvmpipe and softpipe,
# through OSMesa and through EGL, with the known driver bugs in cases/known-failures.txt.
# Results go to out/<backend>-<driver>/. Exit 1 if any run has an unexpected result.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
status=0
for backend in osmesa egl; do
  for driver in llvmpipe softpipe; do
    echo
    "${GLRC_BUILD_DIR:-build}"/glrefcheck run cases --backend "$backend" --driver "$driver" \
      --baseline cases/known-failures.txt --out "out/$backend-$driver" || status=1
  done
done
exit $status
