#!/usr/bin/env bash
# Regression-checks the system's Mesa against another Mesa version: unpacks VERSION into
# .mesa/VERSION (scripts/mesa-fetch.sh), runs the suite on both with llvmpipe and softpipe through
# OSMesa and EGL, and compares each pair. Results in out/mesa-system-<backend>-<driver>/ and
# out/mesa-VERSION-<backend>-<driver>/, comparisons in out/compare-VERSION-<backend>-<driver>.{md,json,html}.
# Exit 1 if any comparison finds a regression.
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -eq 1 ] || { echo "usage: scripts/compare-mesa.sh VERSION   (like 25.0.7)" >&2; exit 2; }
version=$1
scripts/build.sh
scripts/mesa-fetch.sh "$version"
bin=${GLRC_BUILD_DIR:-build}/glrefcheck
mkdir -p out
status=0
for backend in osmesa egl; do
  for driver in llvmpipe softpipe; do
    base=out/mesa-system-$backend-$driver current=out/mesa-$version-$backend-$driver
    report=out/compare-$version-$backend-$driver
    baseline=cases/known-failures.txt
    [ -f "cases/known-failures-$driver.txt" ] && baseline="cases/known-failures-$driver.txt"
    common=(--backend "$backend" --driver "$driver" --baseline "$baseline" --html)
    "$bin" run "${common[@]}" --out "$base" >"$base.log" 2>&1 || true
    "$bin" run "${common[@]}" --mesa ".mesa/$version" --out "$current" >"$current.log" 2>&1 || true
    for log in "$base.log" "$current.log"; do
      grep -q "^wrote " "$log" || { cat "$log" >&2; exit 2; }
    done
    echo
    echo "== $backend, $driver"
    "$bin" compare "$base" "$current" --markdown "$report.md" --json "$report.json" \
      --html "$report.html" || status=1
  done
done
exit $status
