#!/usr/bin/env bash
# glrefcheck export --format shader_test, run as a Mesa developer runs it: with Debian's piglit
# shader_runner (scripts/piglit-fetch.sh puts it in .piglit/), on the system's Mesa through
# Mesa's surfaceless EGL platform.
#   - Mesa 22.3.6's clipper NaN (cases/known-failures.txt; every driver here shares it) fails on
#     llvmpipe and softpipe.
#   - softpipe's own bugs fail on softpipe and pass on llvmpipe, which draws them right, the
#     same file for both: the gap and the double hit on a shared edge (tests/cli/data/, minimal
#     cases from `glrefcheck fuzz --generator mesh --driver softpipe --seed 22`) and the pixels
#     left empty inside a steep edge (cases/steep_edge_interior.json).
#   - Cases llvmpipe passes (one triangle, meshes with shared edges and centres on them, a
#     viewport, the first provoking vertex, GL_LESS, culling) pass on llvmpipe.
#   - A case shader_runner cannot express is refused with one line, exit 2.
# Without .piglit/bin/shader_runner it skips (exit 77), saying how to get it.
#   export_shader_test.sh GLREFCHECK SOURCE_DIR
set -euo pipefail
glrefcheck=$1 source=$2
runner=$source/.piglit/bin/shader_runner
if [ ! -x "$runner" ]; then
  echo "SKIP: no $runner: run scripts/piglit-fetch.sh (scripts/install-deps.sh does)"
  exit 77
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0

# export NAME CASE_FILE DRIVER_MODEL: writes $work/NAME.shader_test.
export_case() {
  local name=$1 file=$2 model=$3 out
  out=$("$glrefcheck" export "$file" --format shader_test --driver "$model" \
    --out "$work/$name.shader_test")
  case $out in
    "wrote $work/$name.shader_test: run with PIGLIT_PLATFORM=surfaceless_egl shader_runner"*) ;;
    *) echo "FAIL: export of $file printed: $out"; failures=$((failures + 1)) ;;
  esac
}

# expect NAME DRIVER pass|fail [TEXT]: shader_runner's verdict on GALLIUM_DRIVER=DRIVER, and
# TEXT in its output (kept in $out for more checks). shader_runner exits 0 on a skip too, so
# the verdict is read from its PIGLIT: line.
out=""
expect() {
  local name=$1 driver=$2 want=$3 text=${4:-} result
  out=$(GALLIUM_DRIVER=$driver "$runner" "$work/$name.shader_test" -auto -fbo 2>&1) || true
  result=$(sed -n 's/^PIGLIT: {"result": "\([a-z]*\)" }$/\1/p' <<<"$out")
  if [ "$result" != "$want" ]; then
    echo "FAIL: $name on $driver: expected $want, got ${result:-no result}:"
    echo "$out" | tail -n 20
    failures=$((failures + 1))
  elif [ -n "$text" ] && ! grep -qF -- "$text" <<<"$out"; then
    echo "FAIL: $name on $driver: no '$text' in:"
    echo "$out" | tail -n 20
    failures=$((failures + 1))
  else
    echo "ok: $name on $driver: $want"
  fi
}

# The clipper NaN: the first NaN pixel the C reproducer names, verdict 1 (NaN or Inf).
export_case clipper "$source/cases/clip_noperspective_x_plane.json" llvmpipe
expect clipper llvmpipe fail "$(printf 'Probe color at (63,17)\n  Expected: 0.000000 0.000000 0.000000 1.000000\n  Observed: 1.000000 0.000000 1.000000 1.000000')"
expect clipper softpipe fail
# Its finite variant: a value outside the stated range (verdict 2).
export_case finite "$source/cases/clip_noperspective_finite_wrong.json" llvmpipe
expect finite llvmpipe fail "$(printf 'Probe color at (0,1)\n  Expected: 0.000000 0.000000 0.000000 1.000000\n  Observed: 1.000000 0.000000 2.000000 1.000000')"

# softpipe's bugs, judged as for softpipe (its model and GL_SUBPIXEL_BITS): fragments, kept
# triangle, verdict, 1 at the pixel glrefcheck run names.
export_case gap "$source/tests/cli/data/softpipe_gap.json" softpipe
expect gap softpipe fail "$(printf 'Probe color at (13,11)\n  Expected: 1.000000')"
expect gap llvmpipe pass
export_case double_hit "$source/tests/cli/data/softpipe_double_hit.json" softpipe
expect double_hit softpipe fail "$(printf 'Probe color at (14,4)\n  Expected: 1.000000')"
expect double_hit llvmpipe pass
export_case steep "$source/cases/steep_edge_interior.json" softpipe
expect steep softpipe fail "$(printf 'Probe color at (56,27)\n  Expected: 1.000000 0.000000 0.000000 1.000000\n  Observed: 0.000000 -1.000000 0.000000 1.000000')"
for hole in "55,38" "54,49" "53,60"; do  # the other three, one every 11 rows
  grep -qF "Probe color at ($hole)" <<<"$out" ||
    { echo "FAIL: steep on softpipe: no probe failure at ($hole)"; failures=$((failures + 1)); }
done
expect steep llvmpipe pass

# Passing cases.
for name in face_on grid_mesh shared_centres_grid viewport_offset flat_provoking_first \
  depth_less_overlap cull_front_cw; do
  export_case "$name" "$source/cases/$name.json" llvmpipe
  expect "$name" llvmpipe pass
done

# Built-ins: gl_FragCoord under both layout qualifiers and gl_FrontFacing pass; the same
# files with the fragment coordinate's y half a pixel off, and the facing inverted, fail.
for name in frag_coord_upper_left_integer front_facing_ccw; do
  export_case "$name" "$source/cases/$name.json" llvmpipe
  expect "$name" llvmpipe pass
done
sed 's/, gl_FragCoord\.y,/, gl_FragCoord.y + 0.5,/' "$work/frag_coord_upper_left_integer.shader_test" \
  >"$work/frag_coord_off.shader_test"
expect frag_coord_off llvmpipe fail
sed 's/(gl_FrontFacing ? 1\.0 : 0\.0)/(gl_FrontFacing ? 0.0 : 1.0)/' \
  "$work/front_facing_ccw.shader_test" >"$work/front_facing_inverted.shader_test"
expect front_facing_inverted llvmpipe fail

# What shader_runner cannot express: one line on stderr, exit 2, no file.
set +e
err=$("$glrefcheck" export "$source/cases/depth_range_partial.json" --format shader_test \
  --out "$work/refused.shader_test" 2>&1 >/dev/null)
status=$?
set -e
if [ $status -ne 2 ] || [ "$(wc -l <<<"$err")" -ne 1 ] || [ -e "$work/refused.shader_test" ] ||
  ! grep -qF 'depth_range (near 0.25, far 0.75) cannot be expressed in a shader_test' <<<"$err"; then
  echo "FAIL: depth_range_partial: exit $status: $err"
  failures=$((failures + 1))
fi

[ $failures -eq 0 ] || { echo "$failures failures"; exit 1; }
echo "all shader_tests as expected"
