#!/usr/bin/env bash
# Issue 13's benchmark (bench/README.md): builds, then times llvmpipe, the reference, the
# comparison and whole runs of generated scenes side by side and prints every target with its
# measured ratio. Arguments go to bench/bench.py: --reps N (default 5), --big (the 4096x4096
# scene too), --only SCENE,..., --json FILE.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh >/dev/null
python3 bench/bench.py --build "${GLRC_BUILD_DIR:-build}" "$@"
