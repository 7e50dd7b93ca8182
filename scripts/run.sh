#!/usr/bin/env bash
# One command for a new user: install missing packages, build, start the viewer.
#   scripts/run.sh                       # default scene
#   scripts/run.sh path/to/mesh.obj      # any viewer arguments (see accelviz --help)
#   scripts/run.sh --student DIR [...]   # with a student's structures built in (docs/student.md)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$root/scripts/student_args.sh"  # --student / --no-student for the build, the rest for the viewer
"$root/scripts/deps.sh"
# Only what the viewer needs (the tests are scripts/test.sh's), with progress: a student's
# first picture is about 5 minutes from a fresh clone on 2 cores (README).
"$root/scripts/build.sh" --viewer-only --progress "${student_cmake_args[@]+"${student_cmake_args[@]}"}"
exec "$root/build/bin/accelviz" "${remaining_args[@]}"
