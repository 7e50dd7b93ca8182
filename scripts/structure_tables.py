#!/usr/bin/env python3
"""Markdown tables for the docs, from `accelviz-cli stats --json` (one build per row).

    scripts/structure_tables.py bvh   [--scene ../shared/scenes/bunny.obj] [--rays random:100000:1]
    scripts/structure_tables.py space [--scene ...]

`bvh`: one row per builder (bvh and spheretree): build ms, SAH cost, and nodes visited /
triangles tested per ray for each traversal order. `space`: grid, octree and kd-tree options:
build ms, MB, nodes, references per triangle, per-ray counters."""
import argparse
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CLI = os.path.join(ROOT, "build", "bin", "accelviz-cli")


def stats(scene, structure, params, rays):
    cmd = [CLI, "stats", "--json", "--scene", scene, "--structure", structure, "--rays", rays, "--threads", "1"]
    for p in params:
        cmd += ["--param", p]
    return json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)


def bvh_tables(scene, rays):
    for structure in ("bvh", "spheretree"):
        print(f"\n`{structure}` on `{os.path.basename(scene)}`, rays `{rays}` (nodes visited / triangles tested per ray):\n")
        print("| builder | build ms | SAH cost | nodes | dfs | ordered | pqueue |")
        print("|---|---:|---:|---:|---:|---:|---:|")
        for builder in ("median", "sah", "binned_sah", "pca_sah", "bottom_up", "insertion", "sbvh"):
            cells = []
            first = None
            for traversal in ("dfs", "ordered", "pqueue"):
                # The lecture's binary tree for bvh, so both structures compare like for like.
                width = ["width=2"] if structure == "bvh" else []
                s = stats(scene, structure, [f"builder={builder}", f"traversal={traversal}"] + width, rays)
                first = first or s
                cells.append(f"{s['nodes_visited_per_ray']:.1f} / {s['tris_tested_per_ray']:.1f}")
            print(f"| {builder} | {first['build_ms']:.0f} | {first['sah_cost']:.1f} | {first['nodes']} | " +
                  " | ".join(cells) + " |")
    print(f"\n`bvh` (builder sah, traversal ordered) by node width on `{os.path.basename(scene)}`, rays `{rays}`:\n")
    print("| width | build ms | MB | SAH cost | nodes | nodes visited / ray | nodes culled / ray | tris tested / ray |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|")
    for width in (2, 4):
        s = stats(scene, "bvh", [f"width={width}"], rays)
        print(f"| {width} | {s['build_ms']:.0f} | {s['memory_bytes'] / 2**20:.2f} | {s['sah_cost']:.1f} | {s['nodes']} | "
              f"{s['nodes_visited_per_ray']:.1f} | {s['nodes_culled_per_ray']:.1f} | {s['tris_tested_per_ray']:.1f} |")


def space_tables(scene, rays):
    configs = [("grid", []), ("grid", ["insert=bbox", "mailbox=off", "lambda=1"]), ("grid", ["resolution=avgsize"]),
               ("grid", ["insert=bbox"]), ("grid", ["mailbox=off"]),
               ("octree", []), ("octree", ["order=fixed"]), ("octree", ["insert=bbox"]),
               ("kdtree", ["split=sah"]), ("kdtree", ["split=median", "axis=longest"]),
               ("kdtree", ["split=middle", "axis=longest"]), ("kdtree", ["split=middle", "axis=round_robin"])]
    print(f"\n`{os.path.basename(scene)}`, rays `{rays}`:\n")
    print("| structure | params | build ms | MB | nodes/cells | refs per tri | nodes visited / ray | tris tested / ray |")
    print("|---|---|---:|---:|---:|---:|---:|---:|")
    for structure, params in configs:
        s = stats(scene, structure, params, rays)
        print(f"| {structure} | {' '.join(params) or 'defaults'} | {s['build_ms']:.0f} | {s['memory_bytes'] / 2**20:.2f} | "
              f"{s['nodes']} | {s['refs_per_prim']:.2f} | {s['nodes_visited_per_ray']:.1f} | "
              f"{s['tris_tested_per_ray']:.1f} |")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("which", choices=["bvh", "space"])
    ap.add_argument("--scene", default=os.path.join(os.path.dirname(ROOT), "shared", "scenes", "bunny.obj"))
    ap.add_argument("--rays", default="random:100000:1")
    a = ap.parse_args()
    (bvh_tables if a.which == "bvh" else space_tables)(a.scene, a.rays)
    return 0


if __name__ == "__main__":
    sys.exit(main())
