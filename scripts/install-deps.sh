#!/usr/bin/env bash
# Installs, from Debian 12's own archive, everything glrefcheck needs to build, test and run
# against the system Mesa, and unpacks piglit's shader_runner into .piglit/
# (scripts/piglit-fetch.sh). Idempotent; quiet when nothing is missing.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git
  libosmesa6-dev libgl-dev libegl-dev libegl-mesa0 libgl1-mesa-dri libgles-dev libgbm1
  # lavapipe, Mesa's CPU Vulkan driver: what --driver zink (GL on Vulkan) runs on.
  mesa-vulkan-drivers
  libglm-dev libopenimageio-dev openimageio-tools
  nlohmann-json3-dev libcli11-dev libfmt-dev libgmp-dev libmpfr-dev libssl-dev libre2-dev
  libgtest-dev libgmock-dev libbenchmark-dev fonts-dejavu-core
  # The programs' allocator (CMakeLists.txt, GLRC_MALLOC).
  libjemalloc-dev
  # libFuzzer targets and sanitizer builds (scripts/fuzz.sh, scripts/sanitize.sh).
  clang libclang-rt-14-dev
  # scripts/format.sh: the tree is formatted by .clang-format, checked in CI.
  clang-format
  # scripts/interrupt-test.sh compares results.json files; the schema test validates them.
  jq python3-jsonschema
  # The HTML report test opens the report in headless Chromium to check that it renders.
  chromium
  # piglit's shader_runner (scripts/piglit-fetch.sh, below) runs the shader_tests `glrefcheck
  # export --format shader_test` writes (cli.export_shader_test); the libraries it links.
  libwaffle-1-0 libxkbcommon0 libwayland-client0 libx11-6
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  echo "installing: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# shader_runner alone, out of Debian's piglit package, into .piglit/ (not installed: piglit is
# 2 GB); quiet when it is there.
"$(dirname "$0")/piglit-fetch.sh"
