#!/usr/bin/env python3
"""The blackboard (2D mode, issue #32) driven by a viewer script under a virtual X display.

A 2D scene of 200 random triangles (a .scene2d file) and 1,000 random 2D rays; for every
structure and option below:
  * `print-hit` after each `ray2d` equals the 2D brute force (accelviz-cli trace --structure
    brute on the same scene and rays: the 2D hit rule of docs/hits.md) -- the prim, and t to
    float precision;
  * a screenshot after the first steps and one after more steps differ, and the structures'
    pictures differ from each other;
  * in a grid step, print-vars names tMaxX and tMaxY.
Then `mode 3d` / `mode 2d`, `add2d` and script errors of the 2D commands.
Exit 77 (ctest: skipped) when xvfb-run is missing.
"""
import argparse
import csv
import os
import random
import re
import shutil
import subprocess
import sys

FAILURES = []
W, H = 480, 360
STRUCTURES = [
    ("brute", "brute"),
    ("grid", "grid"),
    ("quadtree_sorted", "octree"),
    ("quadtree_fixed", "octree order=fixed"),
    ("kdtree", "kdtree"),
    ("bvh", "bvh"),
    ("bvh_pqueue", "bvh traversal=pqueue"),
    ("circletree", "spheretree"),
]
RAYS = 1000


def check(cond, what):
    if not cond:
        FAILURES.append(what)
        print("FAIL:", what)
    return cond


def run(cmd, timeout=600, env=None):
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, env=env)
    return p.returncode, p.stdout, p.stderr


def viewer(args, script_path):
    # An X authority file of our own, as test_viewer_scripts.py explains.
    tmp = os.path.join(os.path.dirname(script_path), "xvfb-tmp")
    os.makedirs(tmp, exist_ok=True)
    auth = os.path.join(tmp, os.path.basename(script_path) + ".Xauthority")
    open(auth, "w").close()
    xvfb = [args.xvfb, "-a", "-f", auth, "-s", "-screen 0 1280x1024x24"]
    return run(xvfb + [args.viewer, "--script", script_path], env=dict(os.environ, TMPDIR=tmp))


def planar_t(tri, ray):
    """The 2D hit rule of docs/hits.md (PlanarRayTester) in double: t of the ray on the
    closed triangle, or None."""
    ox, oy, dx, dy = ray
    side = [dx * (y - oy) - dy * (x - ox) for x, y in tri]
    along = [dx * (x - ox) + dy * (y - oy) for x, y in tri]
    ends = [along[k] for k in range(3) if side[k] == 0]
    for a in range(3):
        b = (a + 1) % 3
        if side[a] * side[b] < 0:
            if tri[b] < tri[a]:
                a, b = b, a
            lam = side[a] / (side[a] - side[b])
            ends.append(along[a] + lam * (along[b] - along[a]))
    if not ends:
        return None
    n2 = dx * dx + dy * dy
    enter, leave = min(ends) / n2, max(ends) / n2
    return None if leave < 0 else max(enter, 0.0)


def read_scene(path):
    tris = []
    with open(path) as f:
        for line in f:
            v = line.split()
            if v and v[0] == "tri":
                x = [float(t) for t in v[1:]]
                tris.append([(x[0], x[1]), (x[2], x[3]), (x[4], x[5])])
    return tris


def write_scene_and_rays(work):
    rng = random.Random(32)
    scene = os.path.join(work, "random200.scene2d")
    with open(scene, "w") as f:
        f.write("# 200 random triangles\n")
        for _ in range(200):
            cx, cy, s = rng.uniform(0, 100), rng.uniform(0, 100), rng.uniform(1, 15)
            f.write("tri " + " ".join("%.4f %.4f" % (cx + rng.uniform(-s, s), cy + rng.uniform(-s, s))
                                      for _ in range(3)) + "\n")
    rays = []
    for i in range(RAYS):
        ox, oy = rng.uniform(-20, 120), rng.uniform(-20, 120)
        if i % 10 == 0:  # axis-parallel rays on whole coordinates: on cell and split lines
            ox, oy = float(round(ox)), float(round(oy))
            dx, dy = rng.choice([(1, 0), (-1, 0), (0, 1), (0, -1)])
        else:
            dx, dy = rng.uniform(0, 100) - ox, rng.uniform(0, 100) - oy
        rays.append((ox, oy, dx, dy))
    rays_file = os.path.join(work, "rays2d.txt")
    with open(rays_file, "w") as f:
        for ox, oy, dx, dy in rays:
            f.write(f"{ox!r} {oy!r} 0 {dx!r} {dy!r} 0\n")
    return scene, rays, rays_file


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--viewer", required=True)
    ap.add_argument("--cli", required=True)
    ap.add_argument("--xvfb", default=shutil.which("xvfb-run") or "")
    ap.add_argument("--work", required=True)
    args = ap.parse_args()
    if not args.xvfb:
        print("skipped: xvfb-run not found (Debian package xvfb)")
        return 77
    os.makedirs(args.work, exist_ok=True)
    work = args.work
    scene, rays, rays_file = write_scene_and_rays(work)
    triangles = read_scene(scene)

    # The 2D brute force: accelviz-cli on the same scene and rays.
    ref_csv = os.path.join(work, "brute2d.csv")
    code, _, err = run([args.cli, "trace", "--scene", scene, "--structure", "brute", "--rays", rays_file,
                        "--out", ref_csv])
    if not check(code == 0, f"accelviz-cli trace: {err}"):
        return 1
    with open(ref_csv) as f:
        reference = [(int(r["prim"]), float(r["t"])) for r in csv.DictReader(f)]
    check(sum(p >= 0 for p, _ in reference) > RAYS // 3, "most rays should hit something")

    lines = [f"size {W} {H}", "panel off", f"scene2d {scene}"]
    for name, structure in STRUCTURES:
        lines.append(f"structure {structure}")
        for ox, oy, dx, dy in rays:
            lines += [f"ray2d {ox!r} {oy!r} {dx!r} {dy!r}", "print-hit"]
        # A ray across the board, pictured at its second and at its last step.
        lines += ["ray2d -10 -10 1 0.9", "step start", "step 1", f"screenshot {work}/{name}_a.png",
                  "step end", f"screenshot {work}/{name}_b.png"]
        if name == "grid":
            lines += ["step start", "step 3", "print-vars"]
    lines += ["print-stats", "add2d tri 200 200 201 200 200 201", "print-stats", "mode 3d", "print-stats",
              "mode 2d", "print-stats", "add2d tri 0 0 1 0 0 1", "print-stats"]
    script = os.path.join(work, "blackboard.txt")
    with open(script, "w") as f:
        f.write("# generated by test_viewer_2d.py\n" + "\n".join(lines) + "\n")
    code, out, err = viewer(args, script)
    if not check(code == 0, f"viewer exit {code}\n{err[-2000:]}"):
        return 1
    out_lines = out.strip().splitlines()
    pos = 0
    for name, _ in STRUCTURES:
        wrong = 0
        for i, (prim, t) in enumerate(reference):
            line = out_lines[pos]
            pos += 1
            m = re.fullmatch(r"hit (\d+) (\S+)", line)
            got = (int(m.group(1)), float(m.group(2))) if m else (-1, float("inf")) if line == "miss" else None
            close = got is not None and (prim < 0 or abs(got[1] - t) <= 1e-6 * max(1.0, abs(t)))
            # A tie (docs/hits.md): another triangle whose own t is the reference's.
            tie = close and got[0] >= 0 and prim >= 0 and planar_t(triangles[got[0]], rays[i]) is not None and \
                abs(planar_t(triangles[got[0]], rays[i]) - t) <= 1e-6 * max(1.0, abs(t))
            ok = close and (got[0] == prim or tie)
            if not ok:
                if wrong == 0:
                    print(f"{name}: ray {i} {rays[i]}: viewer '{line}', 2D brute force {prim} {t}")
                wrong += 1
        check(wrong == 0, f"{name}: {wrong} of {RAYS} rays differ from the 2D brute force")
        if name == "grid":
            vars_line = out_lines[pos]
            pos += 1
            check("tMaxX=" in vars_line and "tMaxY=" in vars_line, f"grid print-vars lacks tMaxX/tMaxY: {vars_line}")
    stats = out_lines[pos:]
    nodes = [int(m.group(1)) for m in (re.search(r" nodes (\d+) ", line) for line in stats) if m]
    # The board, with a triangle added far away; the 3D scene; an empty board; one triangle.
    check(len(nodes) == 5 and nodes[1] > nodes[0] and nodes[3] == 0 and nodes[4] >= 1,
          f"print-stats after add2d / mode 3d / mode 2d / add2d: {stats}")

    pictures = {}
    for name, _ in STRUCTURES:
        a, b = (open(os.path.join(work, f"{name}_{k}.png"), "rb").read() for k in "ab")
        check(a != b, f"{name}: the screenshots after 2 and after 12 steps are the same")
        pictures[name] = b
    for i, (n1, s1) in enumerate(STRUCTURES):
        for n2, s2 in STRUCTURES[i + 1:]:
            if s1.split()[0] == s2.split()[0]:
                continue  # the same tree: its traversal orders differ in the steps, not in the last picture
            check(pictures[n1] != pictures[n2], f"{n1} and {n2} look the same")

    # Script errors of the 2D commands: exit 2, one line naming the script and line.
    bad = os.path.join(work, "bad.txt")
    for text, message in [("mode 4d", "usage: mode 2d|3d"), ("add2d tri 0 0 1 0", "usage: add2d tri X1 Y1 X2 Y2 X3 Y3"),
                          ("ray2d 0 0 0 0", "ray2d: the direction is zero"),
                          ("scene procedural:cornell\nadd2d tri 0 0 1 0 0 1", "add2d: not in 2D mode (mode 2d first)"),
                          (f"scene2d {bad}", "tri x1 y1 x2 y2 x3 y3")]:
        with open(bad, "w") as f:
            f.write(text + "\n")
        code, _, err = viewer(args, bad)
        check(code != 0 and message in err and len(err.strip().splitlines()) == 1,
              f"'{text}': exit {code}, stderr {err!r}, expected one line with {message!r}")
    print(f"{'FAILED' if FAILURES else 'OK'}: {len(FAILURES)} failures")
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
