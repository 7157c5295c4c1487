#!/usr/bin/env bash
# glrefcheck must start without OpenImageIO (issue 12: its ~260 shared libraries cost every
# process 0.4 s): only the image plugin, opened with dlopen when an image is written, links it.
# ldd lists what the loader maps at start, the libraries' own dependencies included. The plugin
# must list OpenImageIO, so that a grep that can never match does not pass for a clean binary.
#   no_oiio.sh GLREFCHECK PLUGIN
set -euo pipefail
glrefcheck=$1 plugin=$2
if ldd "$glrefcheck" | grep -i openimageio; then
  echo "$glrefcheck loads OpenImageIO at start (above); only $plugin may link it"
  exit 1
fi
if ! ldd "$plugin" | grep -qi openimageio; then
  echo "$plugin does not link OpenImageIO: the check above proves nothing"
  exit 1
fi
echo "$glrefcheck: $(ldd "$glrefcheck" | wc -l) shared libraries at start, none of OpenImageIO"
