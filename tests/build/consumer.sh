#!/usr/bin/env bash
# find_package(glrefcheck) as an outside project uses it (issue 12): installs BUILD into a fresh
# prefix under WORK with `cmake --install`, configures tests/consumer/ against that prefix alone
# (CMAKE_PREFIX_PATH), builds it and runs it on cases/face_on.json, which must pass against
# itself and fail with one value changed.
#   consumer.sh SOURCE BUILD WORK CXX GENERATOR
set -euo pipefail
source=$1 build=$2 work=$3 cxx=$4 generator=$5
rm -rf "$work"
mkdir -p "$work"
log() { echo "$work/$1.log"; }
step() {  # step NAME COMMAND...: the command's output goes to WORK/NAME.log, shown on failure
  local name=$1
  shift
  "$@" >"$(log "$name")" 2>&1 || { echo "$name failed: $*"; tail -40 "$(log "$name")"; exit 1; }
}
step install cmake --install "$build" --prefix "$work/prefix"
# The installed package must not point back into the source or build tree.
if grep -rlF -e "$source" -e "$build" "$work/prefix/lib"*/ --include='*.cmake' 2>/dev/null |
  grep .; then
  echo "the installed CMake files above name the source or build tree"
  exit 1
fi
step configure cmake -S "$source/tests/consumer" -B "$work/build" -G "$generator" \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_PREFIX_PATH="$work/prefix"
step build cmake --build "$work/build" -j "$(nproc)"
"$work/build/consumer" "$source/cases/face_on.json"
