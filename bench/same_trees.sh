#!/usr/bin/env bash
# Prints `accelviz-cli stats` for every BVH builder (from `accelviz-cli params`), both
# hierarchies, binary and collapsed, on dragon, crytek_sponza and stadium, timings left out
# and every tree's digest in (stats --digest: equal digests, the same tree): run before and
# after a change to the builders and diff the two files.
#   bench/same_trees.sh CLI > FILE
set -euo pipefail
cli=${1:?usage: same_trees.sh ACCELVIZ_CLI}
shared="${ACCEL_SHARED:-$(cd "$(dirname "$0")/../.." && pwd)/shared}/scenes"
builders=$("$cli" params | sed -n 's/^  builder .*one of: \([a-z_, ]*\);.*/\1/p' | head -1 | tr -d ',')
for scene in "$shared/dragon.obj" "$shared/crytek_sponza.obj" procedural:stadium; do
  for structure in bvh spheretree; do
    for builder in $builders; do
      for width in 2 auto; do
        [ "$structure" = spheretree ] && [ "$width" = auto ] && continue
        params=(--param builder=$builder)
        [ "$structure" = bvh ] && params+=(--param width=$width)
        echo "== $(basename "$scene") $structure builder=$builder width=$width"
        "$cli" stats --scene "$scene" --structure $structure "${params[@]}" --digest |
          grep -v -E '^(load_ms|build_ms|refit_ms|scene):'
      done
    done
  done
done
