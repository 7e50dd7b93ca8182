#!/usr/bin/env bash
# Regenerates the viewer figures of the README and docs/viewer.md (bench/figures/viewer_*.png) from the viewer
# scripts in scripts/figures/viewer_*.txt (accelviz --script), under a virtual X display.
#   scripts/make_figures.sh             all figures
#   scripts/make_figures.sh bvh grid    only scripts/figures/viewer_bvh.txt, viewer_grid.txt
#   scripts/make_figures.sh --recordings [NAME ...]
#                                       the GIF / MP4 recordings instead, from
#                                       scripts/recordings/NAME.txt (scripts/make_recordings.sh)
#   scripts/make_figures.sh --kit [NAME ...]
#                                       the assignment kit's figures, from scripts/figures/kit_NAME.txt,
#                                       with the kit tests' viewer (bin/accelviz-kit: the worked
#                                       example, the solutions and the planted bugs built in)
# The viewer is taken from $ACCEL_BUILD_DIR/bin (default build/, as scripts/build.sh makes it).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${ACCEL_BUILD_DIR:-$root/build}"
viewer="$build_dir/bin/accelviz"
if [[ ! -x "$viewer" ]]; then
  echo "make_figures.sh: $viewer not found: build first (scripts/build.sh) or set ACCEL_BUILD_DIR" >&2
  exit 1
fi
if ! command -v xvfb-run >/dev/null; then
  echo "make_figures.sh: xvfb-run not found (Debian package xvfb)" >&2
  exit 1
fi
cd "$root"  # the scripts write to bench/figures/, relative to the repository root
mkdir -p bench/figures
dir=scripts/figures prefix=viewer_ what=figures
if [[ "${1:-}" == "--recordings" ]]; then
  shift
  dir=scripts/recordings prefix= what=recordings
elif [[ "${1:-}" == "--kit" ]]; then
  shift
  prefix=kit_ what="kit figures"
  viewer="$build_dir/bin/accelviz-kit"
  [[ -x "$viewer" ]] || { echo "make_figures.sh: $viewer not found: build the tests (scripts/build.sh)" >&2; exit 1; }
fi
if [[ $# -gt 0 ]]; then
  scripts=()
  for name in "$@"; do scripts+=("$dir/$prefix$name.txt"); done
else
  scripts=("$dir/$prefix"*.txt)
fi
for script in "${scripts[@]}"; do
  echo "== $script"
  # 24-bit screen: the default depth may offer no RGB visual for an OpenGL context.
  xvfb-run -a -s "-screen 0 1920x1080x24" "$viewer" --script "$script"
done
echo "$what written to bench/figures/"
