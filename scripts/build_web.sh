#!/usr/bin/env bash
# Builds accelviz as a web page into build-web/ with Debian's emscripten: accelviz.html,
# page.js, accelviz.js, accelviz.wasm and accelviz.data (shaders, scenes/, fonts and the
# small meshes of ../shared). Any static file server can serve the folder as it is
# (scripts/run_web.sh does). Dear ImGui and giflib are compiled from Debian's source
# packages, fetched once with apt-get source through a private apt configuration
# (scripts/debian_source.sh; the machine's apt sources are left as they are).
#   scripts/build_web.sh                 # ACCEL_WEB_BUILD_DIR=... to build elsewhere
#   scripts/build_web.sh --student DIR   # with a student's structures (docs/student.md)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$root/scripts/student_args.sh"
set -- "${remaining_args[@]}"
build_dir="${ACCEL_WEB_BUILD_DIR:-$root/build-web}"
jobs="$(nproc 2>/dev/null || echo 2)"
"$root/scripts/deps.sh"

# Dear ImGui's and giflib's sources: the versions of the installed libimgui-dev and
# libgif-dev, unpacked into the build folder (kept between builds).
source "$root/scripts/debian_source.sh"
imgui_dir="${ACCEL_IMGUI_SOURCE_DIR:-$build_dir/imgui-src}"
gif_dir="${ACCEL_GIF_SOURCE_DIR:-$build_dir/giflib-src}"
fetch_debian_source libimgui-dev "$imgui_dir"
fetch_debian_source libgif-dev "$gif_dir"

# emcc's JavaScript tools need Debian's acorn; a node from elsewhere on the PATH does not
# look in Debian's module folder.
export NODE_PATH="${NODE_PATH:+$NODE_PATH:}/usr/share/nodejs"
emcmake cmake -S "$root" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DACCEL_IMGUI_SOURCE_DIR="$imgui_dir" \
  -DACCEL_GIF_SOURCE_DIR="$gif_dir" \
  "${student_cmake_args[@]}" "$@" >/dev/null
cmake --build "$build_dir" -j"$jobs" --target accelviz

# site/: exactly the files to put on a web server (next to them a lecturer adds a playlist,
# meshes and scripts; docs/viewer.md). Made anew each build, so nothing stale is uploaded.
site="$build_dir/site"
rm -rf "$site"
mkdir -p "$site"
for file in accelviz.html page.js accelviz.js accelviz.wasm accelviz.data; do
  cp "$build_dir/$file" "$site/$file"
done
bytes="$(du -cb "$site"/* | tail -n1 | cut -f1)"
echo "build_web.sh: site: $site ($(ls "$site" | wc -l) files, $(awk -v b="$bytes" 'BEGIN { printf "%.1f MB", b / 1e6 }'))"
