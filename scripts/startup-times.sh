#!/usr/bin/env bash
# Start-up times of glrefcheck's light commands, medians of N runs (default 15) in ms:
# --help, list and digest of one case, compare of two tiny runs, and a worker process (the
# same executable, `glrefcheck worker` with no input: it starts and exits). Usage:
#   scripts/startup-times.sh [GLREFCHECK] [N]
# Noisy on a loaded machine: compare builds side by side in one invocation each, not across days.
set -euo pipefail
cd "$(dirname "$0")/.."
exe="${1:-build/glrefcheck}"
n="${2:-15}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$exe" run cases/face_on.json --out "$tmp/a" --jobs 1 >/dev/null 2>&1 || true
"$exe" run cases/face_on.json --out "$tmp/b" --jobs 1 >/dev/null 2>&1 || true

median_ms() {  # the command's median wall time over n runs, in ms
  local times=()
  for _ in $(seq "$n"); do
    local t0 t1
    t0=$(date +%s%N)
    "$@" >/dev/null 2>&1 </dev/null || true
    t1=$(date +%s%N)
    times+=($(((t1 - t0) / 1000)))
  done
  printf '%s\n' "${times[@]}" | sort -n | awk '{a[NR]=$1} END {printf "%.1f", a[int((NR+1)/2)]/1000}'
}

printf '%-32s %8s\n' "command" "ms"
printf '%-32s %8s\n' "--help" "$(median_ms "$exe" --help)"
printf '%-32s %8s\n' "list cases/face_on.json" "$(median_ms "$exe" list cases/face_on.json)"
printf '%-32s %8s\n' "digest cases/face_on.json" "$(median_ms "$exe" digest cases/face_on.json)"
printf '%-32s %8s\n' "compare A B (1 case each)" "$(median_ms "$exe" compare "$tmp/a" "$tmp/b")"
printf '%-32s %8s\n' "worker (start, no input)" "$(median_ms "$exe" worker)"
