#!/usr/bin/env bash
# Unpacks one Mesa version from Debian's archive into a prefix under the project
# (.mesa/VERSION/ by default), side by side with the system's Mesa and without installing
# anything: `apt-get download` with a private package list, then `dpkg -x` into the prefix.
#
#   scripts/mesa-fetch.sh 25.0.7            # bookworm-backports' 25.0.7-2~bpo12+1
#   scripts/mesa-fetch.sh 22.3.6 DIR        # bookworm's own, into DIR
#
# Then: glrefcheck run --mesa .mesa/25.0.7 ...
# The archive's address comes from this machine's own apt sources at run time.
set -euo pipefail

usage() {
  echo "usage: scripts/mesa-fetch.sh VERSION [PREFIX]   (VERSION like 25.0.7)" >&2
  exit 2
}
[ $# -ge 1 ] && [ $# -le 2 ] || usage
version=$1
[[ $version =~ ^[0-9]+\.[0-9]+(\.[0-9]+)?([-~+.a-z0-9]*)$ ]] ||
  { echo "mesa-fetch: expected a Mesa version like 25.0.7, got \"$version\"" >&2; exit 2; }
root=$(cd "$(dirname "$0")/.." && pwd)
prefix=${2:-$root/.mesa/$version}
shown=${prefix#"$root"/}  # messages name a prefix in the project relative to it
work=$root/.mesa/apt
arch=$(dpkg --print-architecture)
triple=$(dpkg-architecture -qDEB_HOST_MULTIARCH 2>/dev/null || echo "$(uname -m)-linux-gnu")

if [ -e "$prefix/usr/lib/$triple/libEGL_mesa.so.0" ] && [ -e "$prefix/.mesa-version" ]; then
  echo "mesa-fetch: $(cat "$prefix/.mesa-version") is already in $shown"
  exit 0
fi

# The Debian archive this machine uses (scripts/debian-archive.sh).
. "$(dirname "$0")/debian-archive.sh"
debian_archive mesa-fetch

# A private package list: the release, its updates and its backports. Nothing under /var/lib/apt
# or /etc/apt is touched.
mkdir -p "$work/lists/partial" "$work/cache/archives/partial" "$work/debs"
cat >"$work/sources.list" <<EOF
deb [signed-by=$keyring] $uri $codename main
deb [signed-by=$keyring] $uri $codename-updates main
deb [signed-by=$keyring] $uri $codename-backports main
EOF
apt_opts=(-o "Dir::State::Lists=$work/lists" -o "Dir::Etc::sourcelist=$work/sources.list"
  -o "Dir::Etc::sourceparts=-" -o "Dir::Cache=$work/cache" -o "Debug::NoLocking=1"
  -o "APT::Sandbox::User=$(id -un)")
echo "mesa-fetch: reading the package lists of $codename, $codename-updates and $codename-backports"
apt-get "${apt_opts[@]}" -qq update >"$work/update.log" 2>&1 || { cat "$work/update.log" >&2; exit 1; }

# The Debian version of each package that carries this Mesa version (25.0.7 -> 25.0.7-2~bpo12+1).
debian_version() {  # package -> version, or nothing
  apt-cache "${apt_opts[@]}" madison "$1" 2>/dev/null |
    awk -F'|' -v v="$version" '{ gsub(/ /, "", $2); if ($2 == v || index($2, v "-") == 1) { print $2; exit } }'
}
newest_version() {  # package -> the newest version in the private lists
  apt-cache "${apt_opts[@]}" madison "$1" 2>/dev/null | awk -F'|' '{ gsub(/ /, "", $2); print $2; exit }'
}
mesa_version=$(debian_version libegl-mesa0)
[ -n "$mesa_version" ] || {
  echo "mesa-fetch: no Mesa $version in $codename, $codename-updates or $codename-backports; available:" \
    "$(apt-cache "${apt_opts[@]}" madison libegl-mesa0 | awk -F'|' '{ gsub(/ /, "", $2); printf "%s ", $2 }')" >&2
  exit 2
}

# Mesa's libraries for OSMesa and EGL with llvmpipe and softpipe (mesa-libgallium exists from
# 24.2 on, libglapi-mesa until 25.0, libosmesa6 until 25.0), at this version; libdrm at the
# newest version of these suites, which Mesa's packages require at least.
packages=()
for p in libosmesa6 libegl-mesa0 mesa-libgallium libgbm1 libglapi-mesa libgl1-mesa-dri; do
  v=$(debian_version "$p")
  [ -n "$v" ] && packages+=("$p=$v")
done
for p in libdrm2 libdrm-amdgpu1 libdrm-intel1; do
  packages+=("$p=$(newest_version "$p")")
done
echo "mesa-fetch: downloading ${packages[*]}"
rm -f "$work/debs"/*.deb
(cd "$work/debs" && apt-get "${apt_opts[@]}" -qq download "${packages[@]}" >"$work/download.log" 2>&1) ||
  { cat "$work/download.log" >&2; exit 1; }

rm -rf "$prefix.partial"
mkdir -p "$prefix.partial"
for deb in "$work/debs"/*.deb; do
  dpkg -x "$deb" "$prefix.partial"
done
echo "$mesa_version" >"$prefix.partial/.mesa-version"
rm -rf "$prefix"
mv "$prefix.partial" "$prefix"
echo "mesa-fetch: Mesa $mesa_version ($arch) is in $shown"
echo "mesa-fetch: run it with: glrefcheck run --mesa $shown --backend egl|osmesa --driver llvmpipe|softpipe"
