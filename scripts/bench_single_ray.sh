#!/usr/bin/env bash
# Single-ray speed against the peers (issue #13's table): the BVH layouts and builders
# against Embree (medium, high) and tinybvh (bvh8, bvh4, bvh8-hq) on the same rays, with
# 1M random rays and 1024x768 primary rays, on bunny, crytek_sponza and lost_empire (or
# every shared mesh with --all). Every accelviz row has peer_ratio_mt / peer_ratio_1t: its
# throughput over the fastest peer row of the same rays. Writes
# bench/single_ray_{random,primary}.{json,md}.
#   scripts/bench_single_ray.sh [--all] [--min-time 0.5] [--configs "width=8;width=4"]
# About 6 minutes for the three meshes on a 2-core machine. The CLI is taken from
# $ACCEL_BUILD_DIR/bin (default build/).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cli="${ACCEL_BUILD_DIR:-$root/build}/bin/accelviz-cli"
shared="${ACCEL_SHARED_DIR:-$root/../shared}"
min_time="0.5"
all=0
configs="width=8;width=4"
while [[ $# -gt 0 ]]; do
  case "$1" in
    --all) all=1; shift ;;
    --min-time) min_time="$2"; shift 2 ;;
    --configs) configs="$2"; shift 2 ;;
    *) echo "bench_single_ray.sh: unknown option '$1'" >&2; exit 2 ;;
  esac
done
[[ -x "$cli" ]] || { echo "bench_single_ray.sh: $cli not found: build first (scripts/build.sh)" >&2; exit 1; }
[[ -d "$shared/scenes" ]] || { echo "bench_single_ray.sh: $shared/scenes not found" >&2; exit 1; }
cd "$root"
scenes=()
if [[ $all == 1 ]]; then
  for mesh in "$shared"/scenes/*.obj; do scenes+=(--scene "../shared/scenes/$(basename "$mesh")"); done
else
  for mesh in bunny crytek_sponza lost_empire; do scenes+=(--scene "../shared/scenes/$mesh.obj"); done
fi
mkdir -p bench
for kind in random primary; do
  rays="random:1000000:1"; [[ $kind == primary ]] && rays="primary:1024:768"
  out="bench/single_ray_${kind}"
  files=()
  IFS=';' read -ra list <<<"$configs"
  for i in "${!list[@]}"; do
    params=()
    for kv in ${list[$i]}; do params+=(--param "bvh:$kv"); done
    echo "== $kind rays ($rays): bvh ${list[$i]}"
    # The peers are timed in every run, so each row's ratio is against peers measured beside it.
    "$cli" bench "${scenes[@]}" --structures bvh "${params[@]}" --rays "$rays" --min-time "$min_time" \
      --out-json "$out.$i.json" >/dev/null
    files+=("$out.$i.json")
  done
  python3 - "$out.json" "${files[@]}" <<'PY'
import json, sys
rows = []
for f in sys.argv[2:]:
    rows += json.load(open(f))
json.dump(rows, open(sys.argv[1], "w"), indent=1)
PY
  rm -f "${files[@]}"
  python3 scripts/bench_report.py --made-by scripts/bench_single_ray.sh "$out.json" > "$out.md"
  echo "wrote $out.json and $out.md"
done
