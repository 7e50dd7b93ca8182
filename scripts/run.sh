#!/usr/bin/env bash
# One command for a new user: install missing packages, build, start the viewer.
#   scripts/run.sh                       # default scene
#   scripts/run.sh path/to/mesh.obj      # any viewer arguments (see accelviz --help)
#   scripts/run.sh --student DIR [...]   # with a student's structures built in (docs/student.md)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_args=()
viewer_args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --student) build_args+=("$1" "${2:-}"); shift; [ $# -gt 0 ] && shift ;;
    --student=*|--no-student) build_args+=("$1"); shift ;;
    *) viewer_args+=("$1"); shift ;;
  esac
done
"$root/scripts/deps.sh"
"$root/scripts/build.sh" "${build_args[@]}" >/dev/null
exec "$root/build/bin/accelviz" "${viewer_args[@]}"
