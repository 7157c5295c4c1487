#!/usr/bin/env bash
# Usage: check_digests.sh EXPECTED_FILE PROGRAM [ARGS...]
# Runs PROGRAM (which prints "<sha256>  <case>" lines) and fails on any difference from the
# committed digests, printing the cases whose reference bits changed.
set -euo pipefail
expected=$1; shift
actual=$("$@")
if ! diff <(printf '%s\n' "$actual") "$expected" >/dev/null; then
  echo "reference digests differ from $expected:"
  diff <(printf '%s\n' "$actual") "$expected" || true
  echo "(if the change to the reference is intended, regenerate: glrefcheck digest cases > tests/digests.txt, or build/tests/glrc_digest --expectation 8 cases > tests/expectation_digests.txt)"
  exit 1
fi
echo "$(printf '%s\n' "$actual" | wc -l) digests identical to $expected"
