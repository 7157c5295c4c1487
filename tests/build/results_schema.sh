#!/usr/bin/env bash
# results.json against its committed schema (report/schema/results.schema.json): a real run
# with passing, failing (NaN values included), expected-fail and skipped cases, and the merge
# of two shards, must validate; a results.json missing a required field must not (so the check
# can fail).
set -euo pipefail
glrefcheck="${1:?usage: results_schema.sh GLREFCHECK SOURCE_DIR}"
src="${2:?usage: results_schema.sh GLREFCHECK SOURCE_DIR}"
schema="$src/report/schema/results.schema.json"
validate="$src/tests/tools/validate_json.py"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$src"

cases="^(face_on|fan|clip_noperspective_x_plane|attr_huge|viewport_tiny)$"
printf '^viewport_tiny$\n' >"$tmp/skips.txt"
printf 'clip_noperspective_x_plane,Fail\n' >"$tmp/fails.txt"
for shard in 1 2; do
  "$glrefcheck" run --filter "$cases" --jobs 1 --out "$tmp/shard$shard" --fraction 2 \
    --fraction-start "$shard" --skips "$tmp/skips.txt" --baseline "$tmp/fails.txt" \
    >"$tmp/shard$shard.log" 2>&1 || true
done
"$glrefcheck" merge "$tmp/shard1" "$tmp/shard2" --out "$tmp/merged" >"$tmp/merge.log" 2>&1 || true
"$glrefcheck" run --filter "$cases" --jobs 1 --out "$tmp/whole" --skips "$tmp/skips.txt" \
  >"$tmp/whole.log" 2>&1 || true
for f in whole shard1 shard2 merged; do
  [ -s "$tmp/$f/results.json" ] || { echo "no results.json from $f:"; cat "$tmp/$f.log"; exit 1; }
done
# The run must hold what the schema has to describe: each status kind and a non-finite number.
for want in '"status": "Pass"' '"status": "Fail"' '"status": "Skip"' '"nan"'; do
  grep -q "$want" "$tmp/whole/results.json" || { echo "the run has no $want"; exit 1; }
done
grep -q '"status": "ExpectedFail"' "$tmp/merged/results.json" || { echo "no ExpectedFail"; exit 1; }
python3 "$validate" "$schema" "$tmp"/{whole,shard1,shard2,merged}/results.json

python3 - "$tmp/whole/results.json" "$tmp/broken.json" <<'PY'
import json, sys
doc = json.load(open(sys.argv[1]))
del doc["cases"][0]["outcome"]
doc["run"]["backend"] = "vulkan"
json.dump(doc, open(sys.argv[2], "w"))
PY
if python3 "$validate" "$schema" "$tmp/broken.json" >"$tmp/broken.log"; then
  echo "a results.json without cases[0].outcome and with backend \"vulkan\" validated"
  exit 1
fi
grep -q "outcome" "$tmp/broken.log" && grep -q "vulkan" "$tmp/broken.log" ||
  { echo "the broken file's errors do not name both faults:"; cat "$tmp/broken.log"; exit 1; }
echo "results.json validates against report/schema/results.schema.json"
