#!/usr/bin/env bash
# bench/profile_rays.sh [--out-md FILE] [--out-json FILE] [--label TEXT] [--cases "MESH:RAYS ..."]
#                       [--peers-from JSON] [--no-build] [--keep DIR]
# What one ray costs in the default BVH's fast query and in the peers' on the same rays
# (issue #51's profile): instructions, mispredicted branches, inner nodes, leaves and
# triangle lanes tested per ray, and where the instructions go (ray set-up, node tests,
# child order and stack, leaf tests, the exact double fallback, query entry and exit),
# counted by callgrind in one `accelviz-cli bench` process per case; plus ns per ray with
# one thread, timed natively on the full-size rays in a second bench run. Cycles are ns x
# the CPU's clock: this virtual machine's `perf` has no hardware counters.
#
# It builds its own copy of the CLI with debug line tables in build-prof/ (the Release
# flags plus -g: the same machine code, with each instruction's source line) the first
# time (~8 minutes on 2 cores), then takes ~4 minutes. valgrind hides AVX-512, so accelviz
# runs its AVX2 kernel under callgrind (the same traversal, bit for bit:
# tests/test_wide_isa.cpp). The callgrind rays are a smaller set of the same kind
# (primary rays of the same camera at 256x192; 30,000 random rays); the timed ones are
# those of bench/README.md. docs/performance.md shows the tables.
#
# --no-build profiles the CLI already in build-prof/ (ACCEL_PROFILE_BUILD) as it is: it must
# have been built from these sources, whose lines the categories and counts are matched with.
# --keep DIR keeps the callgrind dumps, logs and timings in DIR.
# --peers-from JSON (an earlier run's --out-json) profiles accelviz alone and takes the
# peers' rows from that file: the peers do not change between two runs, and their builds
# under valgrind (tinybvh's spatial splits above all) are most of a full run's ~25 minutes.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/.." && pwd)"
shared="${ACCEL_SHARED_DIR:-$root/../shared}"
out_md="" out_json="" label="$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)"
cases="crytek_sponza.obj:primary bunny.obj:random"
peers_from="" build=1 keep=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --out-md) out_md="$2"; shift 2 ;;
    --out-json) out_json="$2"; shift 2 ;;
    --label) label="$2"; shift 2 ;;
    --cases) cases="$2"; shift 2 ;;
    --peers-from) peers_from="$2"; shift 2 ;;
    --no-build) build=0; shift ;;
    --keep) keep="$2"; shift 2 ;;
    *) echo "profile_rays.sh: unknown option '$1' (see the comment at the top of the file)" >&2; exit 2 ;;
  esac
done
command -v valgrind >/dev/null || { echo "profile_rays.sh: valgrind is not installed (apt-get install valgrind)" >&2; exit 1; }
[[ -d "$shared/scenes" ]] || { echo "profile_rays.sh: $shared/scenes not found (set ACCEL_SHARED_DIR)" >&2; exit 1; }

prof="${ACCEL_PROFILE_BUILD:-$root/build-prof}"
if [[ ! -f "$prof/CMakeCache.txt" ]]; then
  cmake -S "$root" -B "$prof" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS=-g >/dev/null
fi
if [[ $build == 1 ]]; then
  echo "profile_rays.sh: building accelviz-cli with line tables in $prof" >&2
  cmake --build "$prof" -j"$(nproc)" --target accelviz-cli >/dev/null
fi
cli="$prof/bin/accelviz-cli"

[[ -z "$peers_from" || -e "$peers_from" ]] || { echo "profile_rays.sh: --peers-from $peers_from: no such file" >&2; exit 1; }
no_peers=()
[[ -n "$peers_from" ]] && no_peers=(--no-embree --no-tinybvh)
if [[ -n "$keep" ]]; then  # the dumps and logs stay there, to analyse again (profile_rays.py)
  work="$keep"
  mkdir -p "$work"
else
  work="$(mktemp -d)"
  trap 'rm -rf "$work"' EXIT
fi
args=()
for c in $cases; do
  mesh="${c%%:*}" kind="${c##*:}"
  case "$kind" in
    primary) small="primary:256:192" full="primary:1024:768" ;;
    random) small="random:30000:1" full="random:1000000:1" ;;
    *) echo "profile_rays.sh: case '$c': the rays are primary or random" >&2; exit 2 ;;
  esac
  tag="${mesh%.obj}_$kind"
  echo "profile_rays.sh: $mesh, $kind rays: callgrind ($small)" >&2
  # --dump-before splits the counts at every function named *progress* (the bench's progress
  # line before each row, the builds' progress too): each row's queries land in one dump,
  # which profile_rays.py names by the query function it counted.
  valgrind --tool=callgrind --branch-sim=yes --dump-instr=yes --compress-strings=no --compress-pos=no \
    --callgrind-out-file="$work/$tag.cg" \
    --toggle-collect='accel::wide8_fast_avx2*' --toggle-collect='rtcIntersect1*' \
    --toggle-collect='cli::TinyBvhScene::intersect*' \
    --dump-before='*progress*' \
    "$cli" bench --scene "$shared/scenes/$mesh" --structures bvh --rays "$small" --threads 1 --min-time 0.001 \
    "${no_peers[@]+"${no_peers[@]}"}" >"$work/$tag.log" 2>&1 || { tail -5 "$work/$tag.log" >&2; exit 1; }
  echo "profile_rays.sh: $mesh, $kind rays: timed natively ($full, 1 thread)" >&2
  "$cli" bench --scene "$shared/scenes/$mesh" --structures bvh --rays "$full" --threads 1 --min-time 0.3 \
    "${no_peers[@]+"${no_peers[@]}"}" --out-json "$work/$tag.json" >/dev/null 2>"$work/$tag.timed.log" ||
    { tail -5 "$work/$tag.timed.log" >&2; exit 1; }
  args+=(--case "$tag" "$mesh" "$kind" "$small" "$full" "$work/$tag.json")
done
python3 "$here/profile_rays.py" --label "$label" --root "$root" --tinybvh "$shared/peers/tinybvh/tiny_bvh.h" \
  --mhz "$(awk -F: '/cpu MHz/ {print $2; exit}' /proc/cpuinfo)" --work "$work" \
  ${peers_from:+--peers-from "$peers_from"} ${out_md:+--out-md "$out_md"} ${out_json:+--out-json "$out_json"} "${args[@]}"
