# Sourced by scripts/mesa-fetch.sh and scripts/piglit-fetch.sh: `debian_archive NAME` sets
# codename (bookworm), uri and keyring to the Debian archive this machine's own apt sources use,
# or prints "NAME: ..." and exits 2: the URIs and Signed-By of the deb822 stanza whose Suites
# name the release, else a one-line `deb URI bookworm main` entry. Nothing is written.
debian_archive() {
  local who=$1 f
  codename=$(. /etc/os-release && echo "${VERSION_CODENAME:-}")
  [ -n "$codename" ] || { echo "$who: /etc/os-release names no VERSION_CODENAME" >&2; exit 2; }
  uri="" keyring=""
  for f in /etc/apt/sources.list.d/*.sources; do
    [ -r "$f" ] || continue
    read -r uri keyring < <(awk -v suite="$codename" '
      function flush() { if (ok && u != "") { print u, k; found = 1; exit } ok = 0; u = ""; k = "" }
      /^[[:space:]]*$/ { flush(); next }
      /^#/ { next }
      /^URIs:/ { u = $2 }
      /^Signed-By:/ { k = $2 }
      /^Suites:/ { for (i = 2; i <= NF; i++) if ($i == suite) ok = 1 }
      END { if (!found) flush() }' "$f") || true
    [ -n "$uri" ] && break
  done
  if [ -z "$uri" ] && [ -r /etc/apt/sources.list ]; then
    uri=$(awk -v suite="$codename" '$1 == "deb" && $3 == suite { print $2; exit }' /etc/apt/sources.list)
  fi
  [ -n "$uri" ] || { echo "$who: no Debian $codename archive in this machine's apt sources" >&2; exit 2; }
  keyring=${keyring:-/usr/share/keyrings/debian-archive-keyring.gpg}
}
