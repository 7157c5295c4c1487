#!/usr/bin/env bash
# Unpacks piglit's shader_runner from Debian 12's piglit package into .piglit/ in the project,
# without installing piglit (2 GB unpacked): `apt-get download` with a private package list, then
# only the shader_runner binary and the two piglit libraries it links, out of the .deb.
#
#   scripts/piglit-fetch.sh           # quiet when .piglit/ already holds it
#
# Then: .piglit/bin/shader_runner FILE.shader_test -auto -fbo   (glrefcheck export --format
# shader_test writes such files). .piglit/bin/shader_runner is a wrapper that finds the piglit
# libraries and picks Mesa's surfaceless EGL platform (PIGLIT_PLATFORM=surfaceless_egl) unless
# PIGLIT_PLATFORM is set. shader_runner also needs libwaffle-1-0, which scripts/install-deps.sh
# installs. The archive's address comes from this machine's own apt sources at run time.
set -euo pipefail

[ $# -eq 0 ] || { echo "usage: scripts/piglit-fetch.sh" >&2; exit 2; }
# Debian 12's piglit, the one whose shader_runner commands export/shader_test.cpp writes for.
version=0~git20220119-124bca3c9-1
root=$(cd "$(dirname "$0")/.." && pwd)
dest=$root/.piglit
work=$dest/apt

if [ -x "$dest/bin/shader_runner" ] && [ -x "$dest/lib/shader_runner" ] &&
  [ "$(cat "$dest/.piglit-version" 2>/dev/null)" = "$version" ]; then
  exit 0
fi

# The Debian archive this machine uses (scripts/debian-archive.sh).
. "$(dirname "$0")/debian-archive.sh"
debian_archive piglit-fetch

# A private package list of the release. Nothing under /var/lib/apt or /etc/apt is touched.
mkdir -p "$work/lists/partial" "$work/cache/archives/partial" "$work/debs"
cat >"$work/sources.list" <<EOF
deb [signed-by=$keyring] $uri $codename main
EOF
apt_opts=(-o "Dir::State::Lists=$work/lists" -o "Dir::Etc::sourcelist=$work/sources.list"
  -o "Dir::Etc::sourceparts=-" -o "Dir::Cache=$work/cache" -o "Debug::NoLocking=1"
  -o "APT::Sandbox::User=$(id -un)")
echo "piglit-fetch: reading the package list of $codename"
apt-get "${apt_opts[@]}" -qq update >"$work/update.log" 2>&1 || { cat "$work/update.log" >&2; exit 1; }
if ! apt-cache "${apt_opts[@]}" madison piglit 2>/dev/null | grep -q "| *$version *|"; then
  echo "piglit-fetch: no piglit $version in $codename; available:" \
    "$(apt-cache "${apt_opts[@]}" madison piglit | awk -F'|' '{ gsub(/ /, "", $2); printf "%s ", $2 }')" >&2
  exit 2
fi
echo "piglit-fetch: downloading piglit=$version (34 MB)"
rm -f "$work/debs"/*.deb
(cd "$work/debs" && apt-get "${apt_opts[@]}" -qq download "piglit=$version" >"$work/download.log" 2>&1) ||
  { cat "$work/download.log" >&2; exit 1; }

# Only shader_runner and the libraries it links (libpiglitutil_gl, libpiglitutil); its RUNPATH
# is the installed piglit's, so the wrapper names ours.
partial=$dest/unpack.partial
rm -rf "$partial"
mkdir -p "$partial"
dpkg-deb --fsys-tarfile "$work/debs"/piglit_*.deb |
  tar -x -C "$partial" --wildcards './usr/lib/*/piglit/bin/shader_runner' \
    './usr/lib/*/piglit/lib/libpiglitutil.so.0' './usr/lib/*/piglit/lib/libpiglitutil_gl.so.0'
rm -rf "$dest/lib" "$dest/bin"
mkdir -p "$dest/lib" "$dest/bin"
mv "$partial"/usr/lib/*/piglit/bin/shader_runner "$partial"/usr/lib/*/piglit/lib/*.so.0 "$dest/lib/"
rm -rf "$partial"
cat >"$dest/bin/shader_runner" <<'EOF'
#!/bin/sh
# piglit's shader_runner from Debian's piglit package (scripts/piglit-fetch.sh), with its
# libraries, on Mesa's surfaceless EGL platform unless PIGLIT_PLATFORM says otherwise.
lib=$(cd "$(dirname "$0")/../lib" && pwd)
export LD_LIBRARY_PATH="$lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export PIGLIT_PLATFORM="${PIGLIT_PLATFORM:-surfaceless_egl}"
exec "$lib/shader_runner" "$@"
EOF
chmod +x "$dest/bin/shader_runner"

# What the loader cannot find is a missing Debian package, not a missing piglit library.
missing=$(LD_LIBRARY_PATH="$dest/lib" ldd "$dest/lib/shader_runner" | awk '/not found/ { print $1 }')
if [ -n "$missing" ]; then
  echo "piglit-fetch: shader_runner needs $(echo "$missing" | tr '\n' ' ')(libwaffle-1-0 and" \
    "others: run scripts/install-deps.sh)" >&2
  exit 1
fi
echo "$version" >"$dest/.piglit-version"
rm -rf "$work"  # the package lists and the .deb: only this run needed them
echo "piglit-fetch: shader_runner of piglit $version is in .piglit/bin/"
