#!/usr/bin/env bash
# The programs run on the allocator the build chose (GLRC_MALLOC, CMakeLists.txt): mimalloc,
# which says so at its start when asked (MIMALLOC_VERBOSE), in front of the C library's malloc.
# A binary that only lists it among its libraries, after the C library, would not use it.
#   malloc.sh PROGRAM...
set -euo pipefail
for program in "$@"; do
  libs=$(ldd "$program")
  mi=$(grep -n libmimalloc <<<"$libs" | cut -d: -f1 || true)
  libc=$(grep -n "libc\.so" <<<"$libs" | cut -d: -f1 || true)
  if [ -z "$mi" ] || [ -z "$libc" ] || [ "$mi" -ge "$libc" ]; then
    echo "$program: libmimalloc is not loaded before the C library:"
    echo "$libs"
    exit 1
  fi
  # --help exits 0 having allocated (CLI11's parser); mimalloc's banner comes first on stderr.
  said=$(MIMALLOC_VERBOSE=1 "$program" --help 2>&1 >/dev/null || true)
  if ! grep -q "mimalloc: process init" <<<"$said"; then
    echo "$program: mimalloc did not start (MIMALLOC_VERBOSE=1 printed no banner):"
    echo "$said" | head -5
    exit 1
  fi
  echo "$program: malloc is mimalloc's"
done
