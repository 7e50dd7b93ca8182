#!/usr/bin/env bash
# Sourced by scripts/build_web.sh: fetch_debian_source BINARY_PACKAGE DIR unpacks the Debian
# source package of the installed BINARY_PACKAGE (its very version, from the Debian mirror
# that served it) into DIR, once: DIR/.debian-version remembers the version unpacked. The
# web build compiles Dear ImGui and giflib from these, so the page runs the code the native
# viewer links, and nothing foreign is copied into the repository. apt-get source runs with
# a private apt configuration (a temporary sources.list, lists and cache): the machine's
# apt sources are left as they are.
fetch_debian_source() {
  local package="$1" dir="$2"
  local version source_name
  version="$(dpkg-query -W -f='${source:Version}' "$package")"
  source_name="$(dpkg-query -W -f='${source:Package}' "$package")"
  if [ -d "$dir" ] && [ "$(cat "$dir/.debian-version" 2>/dev/null)" = "$version" ]; then
    return 0
  fi
  echo "fetch_debian_source: fetching $source_name $version's sources (apt-get source, for $package)" >&2
  local apt_dir uri mirror codename keyring signed=""
  apt_dir="$(mktemp -d)"
  uri="$(apt-get download --print-uris "$package" | head -n1 | cut -d"'" -f2)"
  mirror="${uri%%/pool/*}"
  codename="$(. /etc/os-release && echo "${VERSION_CODENAME:-}")"
  if [ -z "$mirror" ] || [ "$mirror" = "$uri" ] || [ -z "$codename" ]; then
    echo "fetch_debian_source: cannot tell which Debian mirror and release $package came from ('$uri', '$codename')" >&2
    rm -rf "$apt_dir"
    return 1
  fi
  keyring=/usr/share/keyrings/debian-archive-keyring.gpg
  [ -f "$keyring" ] && signed="[signed-by=$keyring] "
  echo "deb-src $signed$mirror $codename main" >"$apt_dir/sources.list"
  mkdir -p "$apt_dir/lists/partial" "$apt_dir/cache/archives/partial"
  local apt_options=(-o "Dir::Etc::SourceList=$apt_dir/sources.list" -o Dir::Etc::SourceParts=/dev/null
                     -o "Dir::State::Lists=$apt_dir/lists" -o "Dir::Cache=$apt_dir/cache" -o APT::Sandbox::User=root)
  if ! apt-get "${apt_options[@]}" -qq update ||
     ! (cd "$apt_dir" && apt-get "${apt_options[@]}" -qq source --download-only "$source_name=$version" >/dev/null); then
    echo "fetch_debian_source: apt-get source $source_name=$version failed" >&2
    rm -rf "$apt_dir"
    return 1
  fi
  rm -rf "$dir"
  mkdir -p "$(dirname "$dir")"
  dpkg-source -x "$apt_dir"/"${source_name}"_*.dsc "$dir" >/dev/null
  rm -f "$(dirname "$dir")"/"${source_name}"_*.orig.tar.*  # dpkg-source leaves a link to it there
  rm -rf "$apt_dir"
  echo "$version" >"$dir/.debian-version"
}
