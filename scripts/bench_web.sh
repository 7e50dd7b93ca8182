#!/usr/bin/env bash
# The web page against the native viewer on one thread (scripts/bench_web.py): builds both,
# then writes bench/web.md and bench/web.json. Needs ../shared (the bunny, crytek_sponza).
#   scripts/bench_web.sh [--runs N]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh" >/dev/null
"$root/scripts/build_web.sh" >/dev/null
exec python3 "$root/scripts/bench_web.py" --web-dir "$root/build-web" --viewer "$root/build/bin/accelviz" \
  --shared "$root/../shared" --out-md "$root/bench/web.md" --out-json "$root/bench/web.json" "$@"
