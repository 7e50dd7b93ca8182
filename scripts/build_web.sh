#!/usr/bin/env bash
# Builds accelviz as a web page into build-web/ with Debian's emscripten: accelviz.html,
# page.js, accelviz.js, accelviz.wasm and accelviz.data (shaders, scenes/, fonts and the
# small meshes of ../shared). Any static file server can serve the folder as it is
# (scripts/run_web.sh does). Dear ImGui is compiled from Debian's source package, fetched
# once with apt-get source through a private apt configuration (the machine's apt sources
# are left as they are).
#   scripts/build_web.sh                 # ACCEL_WEB_BUILD_DIR=... to build elsewhere
#   scripts/build_web.sh --student DIR   # with a student's structures (docs/student.md)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$root/scripts/student_args.sh"
set -- "${remaining_args[@]}"
build_dir="${ACCEL_WEB_BUILD_DIR:-$root/build-web}"
jobs="$(nproc 2>/dev/null || echo 2)"
"$root/scripts/deps.sh"

# ImGui's sources: the version of the installed libimgui-dev, from the Debian mirror that
# served it, unpacked into $imgui_dir (kept between builds).
imgui_dir="${ACCEL_IMGUI_SOURCE_DIR:-$build_dir/imgui-src}"
version="$(dpkg-query -W -f='${source:Version}' libimgui-dev)"
if [ ! -f "$imgui_dir/imgui.cpp" ] || [ "$(cat "$imgui_dir/.debian-version" 2>/dev/null)" != "$version" ]; then
  echo "build_web.sh: fetching Dear ImGui $version's sources (apt-get source imgui)" >&2
  apt_dir="$(mktemp -d)"
  trap 'rm -rf "$apt_dir"' EXIT
  uri="$(apt-get download --print-uris libimgui-dev | head -n1 | cut -d"'" -f2)"
  mirror="${uri%%/pool/*}"
  codename="$(. /etc/os-release && echo "${VERSION_CODENAME:-}")"
  if [ -z "$mirror" ] || [ "$mirror" = "$uri" ] || [ -z "$codename" ]; then
    echo "build_web.sh: cannot tell which Debian mirror and release libimgui-dev came from ('$uri', '$codename')" >&2
    exit 1
  fi
  keyring=/usr/share/keyrings/debian-archive-keyring.gpg
  signed=""
  [ -f "$keyring" ] && signed="[signed-by=$keyring] "
  echo "deb-src $signed$mirror $codename main" >"$apt_dir/sources.list"
  mkdir -p "$apt_dir/lists/partial" "$apt_dir/cache/archives/partial"
  apt_options=(-o "Dir::Etc::SourceList=$apt_dir/sources.list" -o Dir::Etc::SourceParts=/dev/null
               -o "Dir::State::Lists=$apt_dir/lists" -o "Dir::Cache=$apt_dir/cache" -o APT::Sandbox::User=root)
  apt-get "${apt_options[@]}" -qq update
  (cd "$apt_dir" && apt-get "${apt_options[@]}" -qq source --download-only "imgui=$version" >/dev/null)
  rm -rf "$imgui_dir"
  mkdir -p "$(dirname "$imgui_dir")"
  dpkg-source -x "$apt_dir"/imgui_*.dsc "$imgui_dir" >/dev/null
  rm -f "$(dirname "$imgui_dir")"/imgui_*.orig.tar.*  # dpkg-source leaves a link to it there
  echo "$version" >"$imgui_dir/.debian-version"
fi

# emcc's JavaScript tools need Debian's acorn; a node from elsewhere on the PATH does not
# look in Debian's module folder.
export NODE_PATH="${NODE_PATH:+$NODE_PATH:}/usr/share/nodejs"
emcmake cmake -S "$root" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DACCEL_IMGUI_SOURCE_DIR="$imgui_dir" \
  "${student_cmake_args[@]}" "$@" >/dev/null
cmake --build "$build_dir" -j"$jobs" --target accelviz
