#!/usr/bin/env bash
# Builds the libFuzzer targets (Clang, ASan + UBSan, into build-fuzz/) and runs each for SECONDS
# (default 60): fuzz_casefile on the case loader, seeded from tests/fuzz/corpus/, and
# fuzz_reference on the reference and comparator. Prints one line per target (inputs executed,
# seconds, findings); a finding is kept in build-fuzz/findings/ and the script exits 1.
#   scripts/fuzz.sh [SECONDS] [TARGET...]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(fuzz_casefile fuzz_reference)
case $seconds in '' | *[!0-9]*) echo "fuzz.sh: SECONDS: expected a whole number, got \"$seconds\"" >&2; exit 2 ;; esac
scripts/install-deps.sh
build=${GLRC_FUZZ_BUILD_DIR:-build-fuzz}
CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGLRC_FUZZ=ON \
  -DGLRC_BUILD_TESTS=OFF -DGLRC_FLAG_VARIANTS=OFF -DGLRC_IMAGES=OFF >"$build.configure.log" 2>&1 ||
  { cat "$build.configure.log"; exit 1; }
cmake --build "$build" --target "${targets[@]}" -j "$(nproc)" >"$build.build.log" 2>&1 ||
  { tail -50 "$build.build.log"; exit 1; }
mkdir -p "$build/findings"
status=0
for target in "${targets[@]}"; do
  corpus="$build/corpus/$target"
  mkdir -p "$corpus"
  seeds=()
  [ "$target" = fuzz_casefile ] && seeds=(tests/fuzz/corpus)
  log="$build/$target.log"
  touch "$build/findings/.start-$target"  # findings newer than this are this run's
  # -timeout: an input taking 10 s is a hang, a finding; -rss_limit_mb: so is 2 GB of memory.
  if ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
    "$build/tests/fuzz/$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=4096 \
    -print_final_stats=1 -artifact_prefix="$build/findings/$target-" "$corpus" "${seeds[@]}" \
    >"$log" 2>&1; then
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
    echo "$target: ${runs:-?} inputs in ${seconds} s, no finding"
  else
    status=1
    echo "$target: FINDING (log: $log)"
    grep -E "ERROR|SUMMARY|fuzz_reference:|runtime error|Test unit written" "$log" | head -10
    # The input itself, so that a finding on a machine whose files are gone can be replayed:
    # xxd -r -p turns these lines back into the file the target reads.
    find "$build/findings" -name "$target-*" -newer "$build/findings/.start-$target" |
      while read -r finding; do
        echo "$(basename "$finding") as hex:"
        od -An -v -tx1 "$finding" | tr -d ' \n' | fold -w 128
        echo
      done
  fi
done
exit $status
