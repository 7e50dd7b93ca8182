#!/usr/bin/env python3
"""Rays aimed at an OBJ's triangle interiors (50%), shared edges (35%) and vertices (15%).

A hard mix for ray/triangle tests that are not watertight: a ray through a shared edge or
vertex may slip between the triangles or hit the one behind. Each ray starts 1.5 scene
diagonals away from its target point, in a uniformly random direction, so some rays hit
another triangle first. Output: the rays file of docs/hits.md.

  edge_rays.py OBJ N SEED > rays.txt
"""
import math
import random
import sys


def main():
    obj, n, seed = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
    vertices, triangles = [], []
    for line in open(obj):
        p = line.split()
        if not p:
            continue
        if p[0] == "v":
            vertices.append(tuple(map(float, p[1:4])))
        elif p[0] == "f":
            idx = [int(t.split("/")[0]) for t in p[1:]]
            idx = [i - 1 if i > 0 else len(vertices) + i for i in idx]
            for k in range(1, len(idx) - 1):  # fan, as docs/hits.md numbers them
                triangles.append((idx[0], idx[k], idx[k + 1]))
    lo = [min(v[i] for v in vertices) for i in range(3)]
    hi = [max(v[i] for v in vertices) for i in range(3)]
    diagonal = math.dist(lo, hi)
    rng = random.Random(seed)
    name = obj.split("/")[-1]
    print(f"# {n} rays at interiors (50%), edges (35%) and vertices (15%) of {name}, seed {seed}")
    for _ in range(n):
        a, b, c = (vertices[i] for i in rng.choice(triangles))
        r = rng.random()
        if r < 0.5:
            u, v = rng.random(), rng.random()
            if u + v > 1:
                u, v = 1 - u, 1 - v
            w = (1 - u - v, u, v)
        elif r < 0.85:
            s = rng.random()
            w = (1 - s, s, 0.0)
        else:
            w = (1.0, 0.0, 0.0)
        target = [w[0] * a[i] + w[1] * b[i] + w[2] * c[i] for i in range(3)]
        z = rng.uniform(-1, 1)
        phi = rng.uniform(0, 2 * math.pi)
        s = math.sqrt(1 - z * z)
        d = (s * math.cos(phi), s * math.sin(phi), z)
        origin = [target[i] - d[i] * 1.5 * diagonal for i in range(3)]
        print(" ".join(f"{x:.9g}" for x in (*origin, *d)))


if __name__ == "__main__":
    main()
