#!/usr/bin/env bash
# One command for a new user: install missing packages, build, start the viewer.
#   scripts/run.sh                       # default scene
#   scripts/run.sh path/to/mesh.obj      # any viewer arguments (see accelviz --help)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/deps.sh"
"$root/scripts/build.sh" >/dev/null
exec "$root/build/bin/accelviz" "$@"
