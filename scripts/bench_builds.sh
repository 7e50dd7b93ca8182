#!/usr/bin/env bash
# The build table of bench/README.md: every structure's default build on each mesh of ../shared/scenes
# and on procedural:terrain (1M triangles), against Embree medium's build timed in the same
# run with the same threads (`accelviz-cli bench`: best of 3 builds each), and the SAH cost
# of the bvh's default builder (binned SAH) next to the full sweep's (builder=sah), which it
# replaced as the default. Only builds are of interest here, so each structure traces just
# a few rays (the bench still checks them against the double reference).
#   scripts/bench_builds.sh [--threads N]
# Then the cold builds (issue #31): every structure's default build on crytek_sponza and
# procedural:terrain as a fresh `accelviz-cli stats` process times it (the first build of a
# process, as every CLI run and the viewer's first build pay it), three processes each, the
# median kept; the report sets them against the same build warm (bench's best of 3 in one
# process) and against Embree medium's build of that bench run.
# Writes bench/builds.json (default builds), bench/builds_sweep.json (bvh builder=sah),
# bench/builds_cold.json (cold builds) and bench/builds_report.md (by scripts/bench_report.py
# --builds). Takes about 2.5 minutes on a 2-core machine. The CLI is taken from
# $ACCEL_BUILD_DIR/bin (default build/).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cli="${ACCEL_BUILD_DIR:-$root/build}/bin/accelviz-cli"
shared="${ACCEL_SHARED_DIR:-$root/../shared}"
threads=0
while [[ $# -gt 0 ]]; do
  case "$1" in
    --threads) threads="$2"; shift 2 ;;
    *) echo "bench_builds.sh: unknown option '$1'" >&2; exit 2 ;;
  esac
done
[[ -x "$cli" ]] || { echo "bench_builds.sh: $cli not found: build first (scripts/build.sh)" >&2; exit 1; }
[[ -d "$shared/scenes" ]] || { echo "bench_builds.sh: $shared/scenes not found" >&2; exit 1; }
cd "$root"
scenes=()
for mesh in "$shared"/scenes/*.obj; do scenes+=(--scene "../shared/scenes/$(basename "$mesh")"); done
scenes+=(--scene procedural:terrain)
mkdir -p bench
common=(--kernel watertight --rays random:1000:1 --min-time 0.001 --threads "$threads")
echo "== default builds of every structure, with Embree medium"
"$cli" bench "${scenes[@]}" --structures all "${common[@]}" --out-json bench/builds.json >/dev/null
echo "== bvh builder=sah (the full sweep), for its build time and SAH cost"
"$cli" bench "${scenes[@]}" --structures bvh --param bvh:builder=sah "${common[@]}" \
  --out-json bench/builds_sweep.json >/dev/null
echo "== cold builds: one fresh stats process per build, 3 each"
cold_scenes=(procedural:terrain)
[[ -f "$shared/scenes/crytek_sponza.obj" ]] && cold_scenes=(../shared/scenes/crytek_sponza.obj "${cold_scenes[@]}")
for scene in "${cold_scenes[@]}"; do
  for structure in grid octree kdtree bvh spheretree; do
    for run in 1 2 3; do
      # Each line: the scene, the structure and stats' JSON (its build_ms is the cold build).
      printf '%s\t%s\t' "$scene" "$structure"
      "$cli" stats --scene "$scene" --structure "$structure" --json | tr -d '\n'
      echo
    done
  done
done | python3 -c '
import json, statistics, sys
runs = {}
for line in sys.stdin:
    scene, structure, stats = line.rstrip("\n").split("\t")
    runs.setdefault((scene, structure), []).append(json.loads(stats)["build_ms"])
rows = [{"scene": s, "structure": t, "cold_ms": v, "cold_median_ms": statistics.median(v)} for (s, t), v in runs.items()]
json.dump(rows, sys.stdout, indent=1)
' > bench/builds_cold.json.tmp
mv bench/builds_cold.json.tmp bench/builds_cold.json
python3 scripts/bench_report.py --builds bench/builds.json bench/builds_sweep.json bench/builds_cold.json \
  > bench/builds_report.md
echo "wrote bench/builds_report.md"
