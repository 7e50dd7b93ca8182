#!/usr/bin/env python3
"""Checks that `accelviz-cli trace` answers every shared mesh identically to `brute` for every
structure and option (docs/hits.md rule: same prim, or a tie within the t tolerance).

    scripts/verify_shared_meshes.py [--rays random:100000:1] [--meshes a.obj,b.obj] [--structures grid,bvh]

The brute-force answers are computed once per mesh and ray set (cached in build/verify/).
Prints one line per (mesh, configuration) and a summary; exits 1 on any mismatch."""
import argparse
import math
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CLI = os.path.join(ROOT, "build", "bin", "accelviz-cli")
SHARED = os.path.join(os.path.dirname(ROOT), "shared", "scenes")

CONFIGS = [
    ("grid", []), ("grid", ["resolution=avgsize"]), ("grid", ["insert=exact"]), ("grid", ["mailbox=off"]),
    ("grid", ["mailbox=on"]), ("grid", ["lambda=8"]),
    ("octree", []), ("octree", ["order=fixed"]), ("octree", ["insert=bbox"]), ("octree", ["insert=exact"]),
    ("kdtree", []), ("kdtree", ["split=middle", "axis=round_robin"]), ("kdtree", ["split=median", "axis=longest"]),
    ("kdtree", ["split=middle", "axis=longest"]),
] + [("bvh", [f"builder={b}", f"traversal={t}"]) for b in
     ("median", "sah", "binned_sah", "pca_sah", "bottom_up", "insertion", "sbvh") for t in ("dfs", "ordered", "pqueue")] + [
    ("bvh", ["width=2", f"traversal={t}"]) for t in ("dfs", "ordered", "pqueue")] + [
    ("spheretree", [f"builder={b}", f"traversal={t}"]) for b in
    ("median", "sah", "binned_sah", "pca_sah", "bottom_up", "insertion", "sbvh") for t in ("ordered", "pqueue")]


def read_hits(path):
    with open(path) as f:
        next(f)
        return [(int(r[1]), float(r[2])) for r in (line.rstrip("\n").split(",") for line in f)]


def trace(scene, structure, params, rays, out):
    cmd = [CLI, "trace", "--scene", scene, "--structure", structure, "--rays", rays, "--out", out]
    for p in params:
        cmd += ["--param", p]
    t0 = time.time()
    subprocess.run(cmd, check=True)
    return time.time() - t0


def compare(ref, got):
    bad = 0
    for (p0, t0), (p1, t1) in zip(ref, got):
        if (p0 < 0) != (p1 < 0):
            bad += 1
        elif p0 >= 0 and abs(t1 - t0) > 1e-4 * max(1.0, abs(t0)):
            bad += 1
    return bad + abs(len(ref) - len(got))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rays", default="random:100000:1")
    ap.add_argument("--meshes", default="")
    ap.add_argument("--structures", default="")
    a = ap.parse_args()
    meshes = a.meshes.split(",") if a.meshes else sorted(f for f in os.listdir(SHARED) if f.endswith(".obj"))
    wanted = set(a.structures.split(",")) if a.structures else None
    work = os.path.join(ROOT, "build", "verify")
    os.makedirs(work, exist_ok=True)
    failures = checked = 0
    for mesh in meshes:
        scene = os.path.join(SHARED, mesh)
        tag = mesh.replace(".obj", "") + "_" + a.rays.replace(":", "_").replace("/", "_")
        ref_csv = os.path.join(work, tag + "_brute.csv")
        if not os.path.exists(ref_csv):
            secs = trace(scene, "brute", [], a.rays, ref_csv)
            print(f"{mesh}: brute force in {secs:.1f} s", flush=True)
        ref = read_hits(ref_csv)
        for structure, params in CONFIGS:
            if wanted and structure not in wanted:
                continue
            out = os.path.join(work, tag + "_test.csv")
            secs = trace(scene, structure, params, a.rays, out)
            bad = compare(ref, read_hits(out))
            checked += 1
            failures += bad > 0
            print(f"{'OK  ' if bad == 0 else 'FAIL'} {mesh} {structure} {' '.join(params)}: "
                  f"{bad} of {len(ref)} rays differ ({secs:.1f} s)", flush=True)
    print(f"{checked - failures} passed, {failures} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
