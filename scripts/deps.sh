#!/usr/bin/env bash
# Installs the Debian packages accelviz needs, and only those that are missing.
# Quiet when everything is present; uses sudo when not run as root.
set -euo pipefail

packages=(
  build-essential cmake pkg-config           # toolchain
  libglfw3-dev libglm-dev libimgui-dev       # viewer: window, math, UI (libimgui.a has the GLFW/GL3 backends)
  python3-glad                               # GL 3.3 core loader, generated at configure time
  libgl-dev                                  # OpenGL headers/libs for the viewer
  libtinyobjloader-dev                       # OBJ loading
  libassimp-dev                              # PLY, STL, glTF 2.0 / GLB loading
  libgtest-dev libcli11-dev libstb-dev       # tests, CLI parsing, PNG writing
  libtbb-dev                                 # parallel tracing
  nlohmann-json3-dev                         # the viewer reads the bench's JSON
  libgif-dev                                 # viewer: animated GIF recordings
  libavcodec-dev libavformat-dev libswscale-dev libavutil-dev  # viewer: MP4 (H.264) recordings
  libembree-dev                              # industry baseline in the benchmark
  bubblewrap libseccomp-dev libssl-dev       # the kit's judge: its sandbox, the worker's seccomp filter, SHA-256
  xvfb xauth libgl1-mesa-dri                 # headless viewer tests (Xvfb + Mesa llvmpipe)
  xdotool                                    # the playlist's keyboard test presses keys in Xvfb
  clang libclang-rt-dev                      # the sanitizer build and its libFuzzer targets (tests/fuzz)
  time                                       # /usr/bin/time -v: peak memory in scripts/bench_huge.sh
  emscripten dpkg-dev fonts-dejavu-core      # the web page (scripts/build_web.sh; dpkg-source unpacks ImGui's sources)
  chromium                                   # the web page's browser test (tests/web)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "deps.sh: installing ${missing[*]}" >&2
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
