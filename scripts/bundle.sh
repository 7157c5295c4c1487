#!/usr/bin/env bash
# Builds a lean glrefcheck (no OpenImageIO: diff writes no images) into build-lean/ and copies it
# with the shared libraries it needs beyond the C library into DIR (default bundle/), so that it
# runs on another x86-64 Linux machine without Debian's packages, such as a GPU machine:
#   LD_LIBRARY_PATH=DIR/lib DIR/glrefcheck run cases --backend egl-device --driver ""
set -euo pipefail
cd "$(dirname "$0")/.."
dir=${1:-bundle}
scripts/install-deps.sh
cmake -S . -B build-lean -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGLRC_IMAGES=OFF \
  -DGLRC_BUILD_TESTS=OFF -DGLRC_FLAG_VARIANTS=OFF -DGLRC_WERROR=OFF >build-lean.configure.log 2>&1 ||
  { cat build-lean.configure.log; exit 1; }
cmake --build build-lean -j "$(nproc)" --target glrefcheck >build-lean.build.log 2>&1 ||
  { tail -50 build-lean.build.log; exit 1; }
rm -rf "$dir" && mkdir -p "$dir/lib"
cp build-lean/glrefcheck "$dir/"
strip "$dir/glrefcheck"
# Everything ldd resolves except the C and C++ runtimes, which a newer machine has newer.
ldd build-lean/glrefcheck | awk '$3 ~ /^\// {print $3}' |
  grep -vE '/(libc|libm|libdl|libpthread|librt|ld-linux-x86-64|libstdc\+\+|libgcc_s)\.so' |
  while read -r lib; do cp -L "$lib" "$dir/lib/"; done
echo "bundled $dir/glrefcheck with $(ls "$dir/lib" | wc -l) libraries ($(du -sh "$dir" | cut -f1))"
