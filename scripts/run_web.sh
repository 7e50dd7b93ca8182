#!/usr/bin/env bash
# Builds the web page (scripts/build_web.sh) and serves build-web/site/ on this machine:
# open the printed URL in a browser. Ctrl+C stops the server.
#   ACCEL_WEB_PORT=8080 scripts/run_web.sh
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${ACCEL_WEB_BUILD_DIR:-$root/build-web}"
port="${ACCEL_WEB_PORT:-8000}"
"$root/scripts/build_web.sh"
echo "accelviz: http://localhost:$port/accelviz.html"
exec python3 -m http.server "$port" --bind 127.0.0.1 --directory "$build_dir/site"
