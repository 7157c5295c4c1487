#!/usr/bin/env bash
# glrefcheck must start without OpenImageIO (issue 12: its ~260 shared libraries cost every
# process 0.4 s): only the image plugin, opened with dlopen when an image is written, links it.
# ldd lists what the loader maps at start, the libraries' own dependencies included. The plugin
# must list OpenImageIO, so that a grep that can never match does not pass for a clean binary.
#   no_oiio.sh GLREFCHECK PLUGIN
set -euo pipefail
glrefcheck=$1 plugin=$2
# ldd's output is read whole before grep sees it: `ldd | grep -q` fails at random under
# pipefail, since grep -q exits at its first match and ldd then dies of SIGPIPE.
at_start=$(ldd "$glrefcheck")
plugin_libs=$(ldd "$plugin")
if grep -i openimageio <<<"$at_start"; then
  echo "$glrefcheck loads OpenImageIO at start (above); only $plugin may link it"
  exit 1
fi
if ! grep -qi openimageio <<<"$plugin_libs"; then
  echo "$plugin does not link OpenImageIO: the check above proves nothing"
  exit 1
fi
echo "$glrefcheck: $(wc -l <<<"$at_start") shared libraries at start, none of OpenImageIO"
