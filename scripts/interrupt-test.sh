#!/usr/bin/env bash
# The scripted interruption test of issue 11: a run of N cases (default 300, copies of cases/*.json
# under new names) is stopped with kill -9, SIGINT and SIGTERM at several moments (some runs
# twice, the second time while resuming), then finished with `glrefcheck run --resume`; every
# such run must end with the results.json of an uninterrupted run (timings and the model's
# source, cached or not, aside), an interrupted results.json must say so, and no worker may
# outlive its runner; two runs (and two resumes) into one folder at once, the second refused;
# campaigns stopped with SIGINT and SIGTERM, recorded as interrupted and refused by merge. Prints
# one line per interruption and a one-line summary; exit 1 on any difference.
#
#   scripts/interrupt-test.sh [N]     (GLRC_BIN: the glrefcheck to test, default build/glrefcheck;
#                                      GLRC_JOBS: workers, default 2)
set -euo pipefail
cd "$(dirname "$0")/.."
bin=$(realpath "${GLRC_BIN:-build/glrefcheck}")
n=${1:-300}
jobs=${GLRC_JOBS:-2}
command -v jq >/dev/null || { echo "interrupt-test: needs jq (apt-get install jq)" >&2; exit 2; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir "$work/cases"
made=0 copy=0
while [ "$made" -lt "$n" ]; do
  for f in cases/*.json; do
    [ "$made" -lt "$n" ] || break
    cp "$f" "$work/cases/$(basename "$f" .json)_v$copy.json"
    made=$((made + 1))
  done
  copy=$((copy + 1))
done

# Timings, the model's source and the stamp (of the file's text, timings included) aside.
comparable() { jq -S 'del(.written_by, .run.seconds, .run.model_source) | del(.cases[].seconds)' "$1/results.json"; }
# Workers of this binary still running (a zombie waiting for init is not running).
live_workers() {
  local count=0 pid
  for pid in $(pgrep -f "^$bin worker" || true); do
    [ "$(awk '{print $3}' "/proc/$pid/stat" 2>/dev/null || echo Z)" = Z ] || count=$((count + 1))
  done
  echo "$count"
}

start=$(date +%s.%N)
"$bin" run "$work/cases" --jobs "$jobs" --out "$work/whole" >"$work/whole.log" 2>&1 || true
whole_s=$(awk -v a="$(date +%s.%N)" -v b="$start" 'BEGIN { print a - b }')
comparable "$work/whole" >"$work/whole.json"
total=$(jq '.summary.total' "$work/whole.json")
[ "$total" = "$n" ] || { echo "interrupt-test: the uninterrupted run has $total of $n cases" >&2; exit 1; }

# name: signal@fraction-of-the-uninterrupted-run[,signal@fraction (while resuming)]
scenarios=(KILL@0.02 INT@0.1 TERM@0.3 KILL@0.5 INT@0.7 TERM@0.9 KILL@0.3,INT@0.3 TERM@0.2,KILL@0.4)
failed=0 orphans=0 stops=0
for scenario in "${scenarios[@]}"; do
  out="$work/run-${scenario//[@,]/_}"
  notes=()
  first=1
  IFS=, read -ra stops_here <<<"$scenario"
  for stop in "${stops_here[@]}"; do
    sig=${stop%@*} at=$(awk -v f="${stop#*@}" -v t="$whole_s" 'BEGIN { print f * t }')
    if [ "$first" = 1 ]; then
      "$bin" run "$work/cases" --jobs "$jobs" --out "$out" >"$out.log" 2>&1 &
    else
      "$bin" run --resume "$out" >>"$out.log" 2>&1 &
    fi
    pid=$!
    sleep "$at"
    kill -s "$sig" "$pid" 2>/dev/null || true
    rc=0
    wait "$pid" 2>/dev/null || rc=$?
    stops=$((stops + 1))
    sleep 0.5  # the kernel's PR_SET_PDEATHSIG kill, and init's reaping
    left=$(live_workers)
    orphans=$((orphans + left))
    finished=0
    [ -f "$out/journal.jsonl" ] && finished=$(grep -c '^{"index"' "$out/journal.jsonl" || true)
    state="no results.json"
    if [ -f "$out/results.json" ]; then
      state="results.json interrupted=$(jq '.run.interrupted' "$out/results.json") with $(jq '.summary.total' "$out/results.json") cases"
      if [ "$sig" != KILL ] && [ "$(jq '.run.interrupted' "$out/results.json")" != true ] &&
        [ "$(jq '.summary.total' "$out/results.json")" != "$n" ]; then
        notes+=("results.json not marked interrupted")
        failed=$((failed + 1))
      fi
    fi
    echo "  $scenario: SIG$sig at $(printf %.1f "$at") s: exit $rc, $finished results in the journal, $state, $left workers left"
    # Stopped before the run had begun (no journal yet): nothing to resume, it starts again.
    [ -f "$out/journal.jsonl" ] || continue
    first=0
  done
  rc=0
  if [ -f "$out/journal.jsonl" ]; then
    "$bin" run --resume "$out" >>"$out.log" 2>&1 || rc=$?
  else
    "$bin" run "$work/cases" --jobs "$jobs" --out "$out" >>"$out.log" 2>&1 || rc=$?
  fi
  if [ "$rc" -ge 2 ] || ! diff -q <(comparable "$out") "$work/whole.json" >/dev/null; then
    echo "  $scenario: resumed run DIFFERS from the uninterrupted one (exit $rc; see $out.log)"
    failed=$((failed + 1))
  else
    echo "  $scenario: resumed: same results.json as the uninterrupted run"
  fi
done

# Two runs into one folder at once (two terminals, two CI jobs on the default out/): the second
# is refused with one line naming the first, which ends as if alone; two resumes of one stopped
# run at once: the second is refused, the first checks the rest once.
out="$work/twice"
"$bin" run "$work/cases" --jobs "$jobs" --out "$out" >"$out.log" 2>&1 &
pid=$!
for _ in $(seq 100); do [ -f "$out/journal.jsonl" ] && break; sleep 0.05; done
rc=0
"$bin" run "$work/cases" --jobs "$jobs" --out "$out" >"$out.second.log" 2>&1 || rc=$?
rc_first=0
wait "$pid" || rc_first=$?
if [ "$rc" != 2 ] || ! grep -q "is in use by another glrefcheck (pid $pid" "$out.second.log" ||
  [ "$rc_first" -ge 2 ] || ! diff -q <(comparable "$out") "$work/whole.json" >/dev/null; then
  echo "  two runs into one folder: NOT refused or the first's results changed (exit $rc, $rc_first)"
  failed=$((failed + 1))
else
  echo "  two runs into one folder: the second refused (exit 2, names pid $pid), the first's results whole"
fi
"$bin" run "$work/cases" --jobs "$jobs" --out "$out" >"$out.log" 2>&1 &
pid=$!
sleep "$(awk -v t="$whole_s" 'BEGIN { print 0.3 * t }')"
kill -s INT "$pid" 2>/dev/null || true
wait "$pid" 2>/dev/null || true
"$bin" run --resume "$out" >>"$out.log" 2>&1 &
pid=$!
sleep 0.2
rc=0
"$bin" run --resume "$out" >"$out.second.log" 2>&1 || rc=$?
rc_first=0
wait "$pid" || rc_first=$?
# Cases recorded, and cases recorded twice that no heatmaps explain: a case whose heatmaps were
# still being written when the first resume began is recorded again (heatmaps lost, or checked
# again); any other case twice was checked by both resumes.
read -r lines twice < <(python3 - "$out/journal.jsonl" <<'PY'
import json, sys
first = {}
twice = 0
for line in open(sys.argv[1]):
    j = json.loads(line)
    if "result" not in j:
        continue
    k = j["index"]
    if k in first and first[k].get("heatmaps") != "follow":
        twice += 1
    first.setdefault(k, j)
print(len(first), twice)
PY
)
if [ "$rc" != 2 ] || [ "$rc_first" -ge 2 ] || [ "$lines" != "$n" ] || [ "$twice" != 0 ] ||
  ! diff -q <(comparable "$out") "$work/whole.json" >/dev/null; then
  echo "  two resumes at once: NOT refused, or the rest checked twice ($lines of $n cases recorded, $twice twice; exit $rc, $rc_first)"
  failed=$((failed + 1))
else
  echo "  two resumes at once: the second refused, $lines of $n cases recorded, none twice, results whole"
fi

# A campaign stopped by SIGINT and SIGTERM: exit 130/143, results.json says so, merge refuses it,
# no worker outlives it.
for sig in INT TERM; do
  out="$work/campaign-$sig"
  "$bin" fuzz --seed 7 --count 100000 --generator sizes --jobs "$jobs" --no-shrink --out "$out" \
    >"$out.log" 2>&1 &
  pid=$!
  sleep 3
  kill -s "$sig" "$pid" 2>/dev/null || true
  rc=0
  wait "$pid" 2>/dev/null || rc=$?
  sleep 0.5
  left=$(live_workers)
  orphans=$((orphans + left))
  expected=$((128 + $(kill -l "$sig")))
  merged=0
  "$bin" merge "$out" --out "$work/merged-$sig" >"$out.merge.log" 2>&1 || merged=$?
  if [ "$rc" != "$expected" ] || [ "$(jq '.run.interrupted' "$out/results.json")" != true ] ||
    ! grep -q "interrupted by SIG$sig after" "$out.log" || [ "$merged" != 2 ]; then
    echo "  campaign SIG$sig: exit $rc (expected $expected), interrupted=$(jq '.run.interrupted' "$out/results.json" 2>/dev/null), merge exit $merged: WRONG"
    failed=$((failed + 1))
  else
    echo "  campaign SIG$sig: exit $rc, $(jq '.stats.cases' "$out/results.json") cases recorded as interrupted, merge refused it, $left workers left"
  fi
done

verdict="every resumed run equals the uninterrupted run"
[ "$failed" = 0 ] || verdict="$failed FAILED"
echo "interrupt-test: $n cases ($(printf %.1f "$whole_s") s uninterrupted, $jobs workers), ${#scenarios[@]} runs stopped $stops times (kill -9, SIGINT, SIGTERM at 2-90% of the run, some twice) then --resume, two runs and two resumes into one folder at once, two campaigns stopped: $verdict; $orphans workers outlived their runner"
[ "$failed" = 0 ] && [ "$orphans" = 0 ]
