#!/usr/bin/env bash
# The programs run on the allocator the build chose (GLRC_MALLOC, CMakeLists.txt): jemalloc,
# which prints its statistics at exit when asked (MALLOC_CONF=stats_print:true), loaded in
# front of the C library. A binary that only listed it after the C library would not use it.
#   malloc.sh PROGRAM...
set -euo pipefail
for program in "$@"; do
  libs=$(ldd "$program")
  je=$(grep -n libjemalloc <<<"$libs" | cut -d: -f1 || true)
  libc=$(grep -n "libc\.so" <<<"$libs" | cut -d: -f1 || true)
  if [ -z "$je" ] || [ -z "$libc" ] || [ "$je" -ge "$libc" ]; then
    echo "$program: libjemalloc is not loaded before the C library:"
    echo "$libs"
    exit 1
  fi
  # --help exits having allocated (CLI11's parser); jemalloc's statistics go to stderr.
  said=$(MALLOC_CONF=stats_print:true "$program" --help 2>&1 >/dev/null || true)
  if ! grep -q "Begin jemalloc statistics" <<<"$said"; then
    echo "$program: jemalloc printed no statistics (MALLOC_CONF=stats_print:true): not its malloc"
    echo "$said" | head -5
    exit 1
  fi
  echo "$program: malloc is jemalloc's"
done
