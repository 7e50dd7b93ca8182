#!/usr/bin/env bash
# The speed-against-error table of bench/README.md: `accelviz-cli bench` on every mesh of
# ../shared/scenes with 1M random rays and 1000x1000 primary rays. Every structure runs with
# the watertight kernel (the accuracy target: zero errors); the BVH, the fastest structure,
# also runs with moller and double, so the cost of each kernel is measured on the same
# rays (their Embree ratios against Embree rows timed in the same run). procedural:terrain
# (1M triangles, for its build row against Embree's) runs every structure once with 100k
# random rays: its rays only need to check the build, not to time tracing at length. Writes
# bench/shared_{random,primary,terrain}.{json,csv,md} (the raw rows), bench/shared.json
# (all rows, for the viewer's chart: accelviz --bench-json bench/shared.json) and
# bench/shared_report.md (the summary tables of bench/README.md, by scripts/bench_report.py).
#   scripts/bench_shared.sh [--rays-random random:1000000:1] [--rays-primary primary:1000:1000]
#                           [--rays-terrain random:100000:1] [--min-time 0.5]
# Takes about 40 minutes on a 2-core machine (the terrain run about 3.5 of them, 300 MB of
# memory). The CLI is taken from $ACCEL_BUILD_DIR/bin
# (default build/, as scripts/build.sh makes it).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cli="${ACCEL_BUILD_DIR:-$root/build}/bin/accelviz-cli"
shared="${ACCEL_SHARED_DIR:-$root/../shared}"
random_rays="random:1000000:1"
primary_rays="primary:1000:1000"
terrain_rays="random:100000:1"
min_time="0.5"
while [[ $# -gt 0 ]]; do
  case "$1" in
    --rays-random) random_rays="$2"; shift 2 ;;
    --rays-primary) primary_rays="$2"; shift 2 ;;
    --rays-terrain) terrain_rays="$2"; shift 2 ;;
    --min-time) min_time="$2"; shift 2 ;;
    *) echo "bench_shared.sh: unknown option '$1'" >&2; exit 2 ;;
  esac
done
[[ -x "$cli" ]] || { echo "bench_shared.sh: $cli not found: build first (scripts/build.sh)" >&2; exit 1; }
[[ -d "$shared/scenes" ]] || { echo "bench_shared.sh: $shared/scenes not found" >&2; exit 1; }
cd "$root"
scenes=()
for mesh in "$shared"/scenes/*.obj; do scenes+=(--scene "../shared/scenes/$(basename "$mesh")"); done
mkdir -p bench
for kind in random primary; do
  rays="$random_rays"; [[ $kind == primary ]] && rays="$primary_rays"
  echo "== $kind rays ($rays): every structure, watertight"
  "$cli" bench "${scenes[@]}" --structures all --kernel watertight --rays "$rays" --min-time "$min_time" \
    --out-json "bench/shared_${kind}.json" --out-csv "bench/shared_${kind}.csv" --out-md "bench/shared_${kind}.md" >/dev/null
  echo "== $kind rays ($rays): bvh with moller and double"
  "$cli" bench "${scenes[@]}" --structures bvh --kernel moller,double --rays "$rays" --min-time "$min_time" \
    --out-json "bench/shared_${kind}_kernels.json" --out-csv "bench/shared_${kind}_kernels.csv" \
    --out-md "bench/shared_${kind}_kernels.md" >/dev/null
done
echo "== procedural:terrain ($terrain_rays): every structure, watertight (the 1M-triangle build row)"
"$cli" bench --scene procedural:terrain --structures all --kernel watertight --rays "$terrain_rays" \
  --min-time "$min_time" --out-json bench/shared_terrain.json --out-csv bench/shared_terrain.csv \
  --out-md bench/shared_terrain.md >/dev/null
python3 scripts/bench_report.py bench/shared_random.json bench/shared_random_kernels.json \
  bench/shared_primary.json bench/shared_primary_kernels.json bench/shared_terrain.json \
  --out-json bench/shared.json > bench/shared_report.md
echo "wrote bench/shared.json and bench/shared_report.md"
