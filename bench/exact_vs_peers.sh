#!/usr/bin/env bash
# bench/exact_vs_peers.sh [--runs 3] [--min-time 0.3] [--meshes "bunny crytek_sponza lost_empire dragon"]
#                         [--out-md FILE] [--out-json FILE]
# Issue #51's ratios, measured beside the peers on the same rays: the exact default BVH
# (watertight kernel) and its `--kernel moller` row against the fastest peer (Embree
# MEDIUM or a tinybvh row, all Möller–Trumbore-style tests) and against Embree's robust mode
# (`--embree-robust`), on each mesh with 1024x768 primary rays and 1M random rays. Each run
# is one `accelviz-cli bench` process per ray set, every row of it timed in that process;
# each ratio is the best of --runs runs (noise on a shared virtual machine only ever slows
# one side down). About 3 minutes a run for the four meshes on 2 cores.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cli="${ACCEL_BUILD_DIR:-$root/build}/bin/accelviz-cli"
shared="${ACCEL_SHARED_DIR:-$root/../shared}"
runs=3 min_time=0.3 meshes="bunny crytek_sponza lost_empire dragon" out_md="" out_json=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --runs) runs="$2"; shift 2 ;;
    --min-time) min_time="$2"; shift 2 ;;
    --meshes) meshes="$2"; shift 2 ;;
    --out-md) out_md="$2"; shift 2 ;;
    --out-json) out_json="$2"; shift 2 ;;
    *) echo "exact_vs_peers.sh: unknown option '$1' (see the comment at the top of the file)" >&2; exit 2 ;;
  esac
done
[[ -x "$cli" ]] || { echo "exact_vs_peers.sh: $cli not built (scripts/build.sh)" >&2; exit 1; }
[[ -d "$shared/scenes" ]] || { echo "exact_vs_peers.sh: $shared/scenes not found (set ACCEL_SHARED_DIR)" >&2; exit 1; }
[[ "$runs" =~ ^[1-9][0-9]*$ ]] || { echo "exact_vs_peers.sh: --runs $runs: a positive whole number" >&2; exit 2; }
scenes=()
for m in $meshes; do
  [[ -f "$shared/scenes/$m.obj" ]] || { echo "exact_vs_peers.sh: --meshes: $shared/scenes/$m.obj not found" >&2; exit 1; }
  scenes+=(--scene "$shared/scenes/$m.obj")
done
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
files=()
for ((r = 1; r <= runs; ++r)); do
  for kind in primary random; do
    rays="primary:1024:768"; [[ $kind == random ]] && rays="random:1000000:1"
    echo "exact_vs_peers.sh: run $r of $runs, $kind rays" >&2
    "$cli" bench "${scenes[@]}" --structures bvh --kernel watertight,moller --rays "$rays" --min-time "$min_time" \
      --embree-robust --out-json "$work/run${r}_$kind.json" >/dev/null 2>"$work/log" ||
      { tail -3 "$work/log" >&2; exit 1; }
    files+=("$kind=$work/run${r}_$kind.json")
  done
done
python3 "$root/bench/exact_vs_peers.py" ${out_md:+--out-md "$out_md"} ${out_json:+--out-json "$out_json"} "${files[@]}"
