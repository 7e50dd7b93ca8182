#!/usr/bin/env bash
# Writes what a lecturer uploads to a course platform to grade accelviz assignments there
# (docs/student.md): the platform's files from scripts/autograder/PLATFORM/, the package list
# and build script they share (scripts/autograder/common/), and a copy of the source the
# CLI-only grader is built from on the platform (the tracked files of CMakeLists.txt, cmake/,
# core/, app/cli/, app/worker/, app/CMakeLists.txt, student/, third_party/, scenes/, as they
# are in the working tree; no tests, no docs, no viewer).
#   scripts/make_autograder.sh gradescope|prairielearn|github [OUT_DIR]
# OUT_DIR (default: autograder-PLATFORM in the current folder) must not exist or be empty.
# Each bundle's README.md says what to upload where.
set -euo pipefail

usage="usage: scripts/make_autograder.sh gradescope|prairielearn|github [OUT_DIR]"
if [ $# -ge 1 ] && { [ "$1" = -h ] || [ "$1" = --help ]; }; then
  echo "$usage"
  exit 0
fi
if [ $# -lt 1 ] || [ $# -gt 2 ]; then
  echo "make_autograder.sh: expected a platform and at most an output folder ($usage)" >&2
  exit 2
fi
platform=$1
case "$platform" in
  gradescope | prairielearn | github) ;;
  *)
    echo "make_autograder.sh: unknown platform '$platform' (gradescope, prairielearn or github)" >&2
    exit 2
    ;;
esac
out=${2-autograder-$platform}
if [ -z "$out" ]; then
  echo "make_autograder.sh: the output folder is an empty name ($usage)" >&2
  exit 2
fi
if [ -e "$out" ] && { [ ! -d "$out" ] || [ -n "$(ls -A "$out")" ]; }; then
  echo "make_autograder.sh: $out exists and is not an empty folder: remove it or name another" >&2
  exit 2
fi

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
templates="$root/scripts/autograder"
if ! git -C "$root" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  echo "make_autograder.sh: $root is not a git checkout: the source copy is its tracked files" >&2
  exit 1
fi

mkdir -p "$out"
cp -R "$templates/$platform/." "$out/"
case "$platform" in
  gradescope) source_dir="$out/source" common_dir="$out" ;;
  prairielearn) source_dir="$out/source" common_dir="$out" ;;
  github) source_dir="$out/accelviz" common_dir="$out/.github/accelviz" ;;
esac
mkdir -p "$source_dir" "$common_dir"
cp "$templates/common/packages.txt" "$templates/common/build_grader.sh" "$common_dir/"

# The source copy: tracked files only (no build folder, no local junk), present ones only
# (a tracked file deleted in the working tree is left out). The viewer is not needed:
# app/CMakeLists.txt adds app/viewer only when ACCEL_BUILD_APP is on and the folder exists.
git -C "$root" ls-files -z -- CMakeLists.txt cmake core app/cli app/worker app/CMakeLists.txt student \
  third_party scenes |
  while IFS= read -r -d '' f; do
    if [ -e "$root/$f" ]; then printf '%s\0' "$f"; fi
  done |
  tar -C "$root" --null -T - -cf - | tar -C "$source_dir" -xf -

chmod +x "$common_dir/build_grader.sh"
case "$platform" in
  gradescope) chmod +x "$out/setup.sh" "$out/run_autograder" ;;
  prairielearn) chmod +x "$out/grade.sh" ;;
  github) chmod +x "$out/.github/accelviz-grade.sh" ;;
esac

# Which source this is, for the lecturer who finds the bundle again in a year.
commit=$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo "no commit")
changes=""
if [ -n "$(git -C "$root" status --porcelain --untracked-files=no -- CMakeLists.txt cmake core app/cli app/worker app/CMakeLists.txt \
  student third_party scenes)" ]; then
  changes=", with uncommitted changes"
fi
printf '\n---\nMade by scripts/make_autograder.sh from accelviz %s%s on %s.\n' "$commit" "$changes" "$(date +%F)" \
  >>"$out/README.md"
files=$(find "$source_dir" -type f | wc -l)
echo "make_autograder.sh: wrote $out ($platform; $files source files); see $out/README.md"
