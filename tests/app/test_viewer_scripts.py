#!/usr/bin/env python3
"""Scripted runs of the viewer (accelviz --script) under a virtual X display.

For every structure (and the BVH's priority-queue traversal): load a scene, shoot a ray at a
pixel known to hit, step from the first to the last step, take a screenshot of each. Then:
  * the screenshots are real pictures, the first and last step differ, and the last-step
    pictures of different structures differ;
  * the hit the viewer reports (print-hit) equals accelviz-cli trace on the same ray (the
    viewer prints it with print-ray as hex floats, written to a rays file);
  * the last step is the Done event with that hit;
  * `frames` writes one PNG per remaining step, `heatmap prims` overlays the cost image;
  * `construct` + `build-step` + `print-build-step` step through the recorded build, and
    its steps look different;
  * `load-bench` + `show-chart on` draw the speed-against-error chart over the view;
  * print-vars names the lecture's variables; the trap demonstrations' naive answers differ
    from the traversal's, which brute force (accelviz-cli) confirms; a trap's explanation
    goes with a structure or scene it does not apply to (print-trap);
  * one mesh as OBJ, PLY, STL and glTF gives the same hit in the viewer and accelviz-cli;
  * the lecture playlist (scenes/lecture.playlist) runs through every state; `record`
    writes a GIF and an MP4 with one frame per step moved;
  * `tree on` shows the tree diagram (a screenshot differs from `tree off`), `tree-select`
    selects and isolates a node, the grid shows its cell walk, the construction its tree;
  * script errors exit 2 with "accelviz: SCRIPT:LINE: message".
Exit 77 (ctest: skipped) when xvfb-run is missing.
"""
import csv
import os
import re
import sys

from viewer_harness import FAILURES, check, parse_args, run, viewer

W, H = 480, 320
SCENE = "procedural:cornell"
# Name in the files, registry name, parameters (as accelviz-cli --param takes them).
STRUCTURES = [
    ("brute", "brute", []),
    ("grid", "grid", []),
    ("octree", "octree", []),
    ("kdtree", "kdtree", []),
    ("bvh", "bvh", []),
    ("bvh_pqueue", "bvh", ["traversal=pqueue"]),
    ("spheretree", "spheretree", ["traversal=dfs"]),
]
# The centre of the framed Cornell room: the back wall or the blocks, always a hit.
PIXEL = (W // 2, H // 2 + 20)
REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BENCH_JSON = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", "bench_chart.json")


def run_script(args, work, name, lines):
    """Writes `lines` to WORK/NAME.txt and runs the viewer on it: (exit code, stdout, stderr)."""
    script = os.path.join(work, name + ".txt")
    with open(script, "w") as f:
        f.write("\n".join(lines) + "\n")
    return viewer(args, script)


def write_pyramids(work):
    """A pyramid (quad base fan-triangulated, four sides) as OBJ, PLY, binary STL and glTF
    with an embedded buffer; the triangles in the same order in each."""
    import base64
    import json
    import struct
    v = [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0), (0, 0, 1)]
    faces = [(0, 3, 2, 1), (0, 1, 4), (1, 2, 4), (2, 3, 4), (3, 0, 4)]
    tris = [(f[0], f[k - 1], f[k]) for f in faces for k in range(2, len(f))]
    paths = []
    p = os.path.join(work, "pyramid.obj")
    with open(p, "w") as f:
        f.write("".join(f"v {x} {y} {z}\n" for x, y, z in v))
        f.write("".join("f " + " ".join(str(i + 1) for i in face) + "\n" for face in faces))
    paths.append(p)
    p = os.path.join(work, "pyramid.ply")
    with open(p, "w") as f:
        f.write(f"ply\nformat ascii 1.0\nelement vertex {len(v)}\nproperty float x\nproperty float y\n"
                f"property float z\nelement face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n")
        f.write("".join(f"{x} {y} {z}\n" for x, y, z in v))
        f.write("".join(f"{len(face)} " + " ".join(map(str, face)) + "\n" for face in faces))
    paths.append(p)
    p = os.path.join(work, "pyramid.stl")
    with open(p, "wb") as f:
        f.write(b"binary pyramid".ljust(80, b" ") + struct.pack("<I", len(tris)))
        for t in tris:
            f.write(struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *v[i]) for i in t) + b"\0\0")
    paths.append(p)
    pos = b"".join(struct.pack("<3f", *p_) for p_ in v)
    idx = b"".join(struct.pack("<3I", *t) for t in tris)
    doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
           "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": 4}]}],
           "buffers": [{"uri": "data:application/octet-stream;base64," + base64.b64encode(pos + idx).decode(),
                        "byteLength": len(pos) + len(idx)}],
           "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos)},
                           {"buffer": 0, "byteOffset": len(pos), "byteLength": len(idx)}],
           "accessors": [{"bufferView": 0, "componentType": 5126, "count": len(v), "type": "VEC3",
                          "min": [-1, -1, 0], "max": [1, 1, 1]},
                         {"bufferView": 1, "componentType": 5125, "count": 3 * len(tris), "type": "SCALAR"}]}
    p = os.path.join(work, "pyramid.gltf")
    with open(p, "w") as f:
        json.dump(doc, f)
    paths.append(p)
    return paths


def main():
    args = parse_args("--png-check")
    if args is None:
        return 77
    work = args.work

    # ---- One viewer run for all structures (one X server start).
    lines = [f"size {W} {H}", f"scene {SCENE}"]
    for name, structure, params in STRUCTURES:
        lines += [
            f"structure {structure} {' '.join(params)}".strip(),
            f"ray-at-pixel {PIXEL[0]} {PIXEL[1]}",
            "print-ray", "print-hit",
            "step start", "print-step", f"screenshot {work}/{name}_first.png",
            "step end", "print-step", f"screenshot {work}/{name}_last.png",
        ]
    # frames: the last three steps of the sphere tree's trace; then its cost heat map.
    lines += ["step back 2", f"frames {work}/frames_", "heatmap prims", f"screenshot {work}/heatmap.png", "heatmap off"]
    # The bench chart, with every setting the script can change.
    lines += [f"load-bench {BENCH_JSON}", "show-chart on group=2 x=t-error speed=1t y=log labels=off",
              f"screenshot {work}/chart.png", "show-chart off"]
    script = os.path.join(work, "all_structures.txt")
    with open(script, "w") as f:
        f.write("# generated by test_viewer_scripts.py\n" + "\n".join(lines) + "\n")
    for old in os.listdir(work):
        if old.endswith(".png"):
            os.remove(os.path.join(work, old))
    code, out, err = viewer(args, script)
    if not check(code == 0, f"viewer exit {code}\n{err}"):
        return 1
    out_lines = out.strip().splitlines()
    # Per structure: ray, hit, first step, last step.
    if not check(len(out_lines) == 4 * len(STRUCTURES), f"expected {4 * len(STRUCTURES)} output lines:\n{out}"):
        return 1

    for i, (name, structure, params) in enumerate(STRUCTURES):
        ray_line, hit_line, first_line, last_line = out_lines[4 * i: 4 * i + 4]
        m = re.fullmatch(r"hit (\d+) (\S+)", hit_line)
        if not check(m is not None, f"{name}: print-hit gave '{hit_line}', expected a hit"):
            continue
        prim, t = int(m.group(1)), float(m.group(2))
        m1 = re.fullmatch(r"step 1/(\d+): .*", first_line)
        m2 = re.fullmatch(r"step (\d+)/(\d+): done: hit triangle (\d+) at t=.*", last_line)
        check(m1 is not None, f"{name}: first step line '{first_line}'")
        check(m2 is not None and m2.group(1) == m2.group(2) and int(m2.group(3)) == prim,
              f"{name}: last step line '{last_line}' is not Done with triangle {prim}")
        # The same ray through accelviz-cli: the same triangle and t.
        rays = os.path.join(work, f"{name}_ray.txt")
        with open(rays, "w") as f:
            f.write(ray_line + "\n")
        hits = os.path.join(work, f"{name}_hits.csv")
        cmd = [args.cli, "trace", "--scene", SCENE, "--structure", structure, "--rays", rays, "--out", hits]
        for p in params:
            cmd += ["--param", p]
        c, _, e = run(cmd)
        if check(c == 0, f"{name}: accelviz-cli trace failed: {e}"):
            with open(hits) as f:
                row = list(csv.DictReader(f))[0]
            check(int(row["prim"]) == prim, f"{name}: viewer hit triangle {prim}, accelviz-cli {row['prim']}")
            check(abs(float(row["t"]) - t) <= 1e-6 * max(1.0, abs(t)),
                  f"{name}: viewer t={t}, accelviz-cli t={row['t']}")
        # Pictures.
        for which in ("first", "last"):
            png = os.path.join(work, f"{name}_{which}.png")
            c, o, _ = run([args.png_check, png, str(W), str(H)])
            check(c == 0, f"{name}: {png} is not a real picture: {o}")
        c, o, _ = run([args.png_check, "--differ", f"{work}/{name}_first.png", f"{work}/{name}_last.png", "30"])
        check(c == 0, f"{name}: the first and the last step look the same: {o}")

    names = [s[0] for s in STRUCTURES]
    for a in range(len(names)):
        for b in range(a + 1, len(names)):
            c, o, _ = run([args.png_check, "--differ", f"{work}/{names[a]}_last.png", f"{work}/{names[b]}_last.png", "30"])
            check(c == 0, f"{names[a]} and {names[b]} look the same: {o}")

    frames = sorted(f for f in os.listdir(work) if f.startswith("frames_") and f.endswith(".png"))
    check(len(frames) == 3, f"frames: expected 3 PNGs, got {frames}")
    c, o, _ = run([args.png_check, "--differ", f"{work}/spheretree_last.png", f"{work}/heatmap.png", "2000"])
    check(c == 0, f"the heat map overlay changed nothing: {o}")
    c, o, _ = run([args.png_check, "--differ", f"{work}/heatmap.png", f"{work}/chart.png", "2000"])
    check(c == 0, f"show-chart on changed nothing: {o}")

    # ---- The construction mode: brute force records 4 steps; the pictures of its steps differ.
    lines = [f"size {W} {H}", f"scene {SCENE}", "structure brute", "construct", "print-build-step",
             "build-step 1", "print-build-step", f"screenshot {work}/build_1.png",
             "build-step 1", "print-build-step", f"screenshot {work}/build_2.png",
             "build-step end", "print-build-step", f"screenshot {work}/build_end.png",
             "build-step back 10", "print-build-step", "sah-plot off",
             "structure bvh", "construct", "build-step end", "print-build-step", f"screenshot {work}/build_bvh.png"]
    script = os.path.join(work, "construct.txt")
    with open(script, "w") as f:
        f.write("\n".join(lines) + "\n")
    code, out, err = viewer(args, script)
    if check(code == 0, f"construct: viewer exit {code}\n{err}"):
        got = out.strip().splitlines()
        expected = [
            r"build step 0/4: nothing built yet",
            r"build step 1/4: scene box computed",
            r"build step 2/4: node 0 \(depth 0\) with \d+ triangles",
            r"build step 4/4: done: 1 nodes",
            r"build step 0/4: nothing built yet",
            r"build step (\d+)/\1: .*",
        ]
        if check(len(got) == len(expected), f"construct: expected {len(expected)} lines:\n{out}"):
            for line, pattern in zip(got, expected):
                check(re.fullmatch(pattern, line) is not None, f"construct: '{line}' does not match {pattern}")
        for a, b in (("build_1", "build_2"), ("build_2", "build_end")):
            c, o, _ = run([args.png_check, "--differ", f"{work}/{a}.png", f"{work}/{b}.png", "30"])
            check(c == 0, f"construct: {a} and {b} look the same: {o}")

    # ---- Every structure: pictures early, midway and at the end of its construction differ.
    lines = [f"size {W} {H}", f"scene {SCENE}"]
    structures = ["grid", "octree", "kdtree", "bvh", "bvh builder=bottom_up", "bvh builder=insertion", "spheretree"]
    for k, s in enumerate(structures):
        lines += [f"structure {s}", "construct", "build-step 3", f"screenshot {work}/bs{k}_early.png",
                  "build-step 40", f"screenshot {work}/bs{k}_mid.png",
                  "build-step end", f"screenshot {work}/bs{k}_end.png"]
    script = os.path.join(work, "construct_all.txt")
    with open(script, "w") as f:
        f.write("\n".join(lines) + "\n")
    code, out, err = viewer(args, script)
    if check(code == 0, f"construct every structure: viewer exit {code}\n{err}"):
        for k, s in enumerate(structures):
            for a, b in (("early", "mid"), ("mid", "end")):
                c, o, _ = run([args.png_check, "--differ", f"{work}/bs{k}_{a}.png", f"{work}/bs{k}_{b}.png", "30"])
                check(c == 0, f"construct {s}: build steps {a} and {b} look the same: {o}")

    # ---- The traversal's variables (print-vars names the lecture's variables: tMaxX on a
    # grid step, the case on a kd-tree node) and the lecture's traps: the naive answer
    # differs from the traversal's, which equals brute force (accelviz-cli).
    lines = [f"size {W} {H}", f"scene {SCENE}", "structure grid", f"ray-at-pixel {PIXEL[0]} {PIXEL[1]}",
             "step start", "print-vars", "structure kdtree", "step start", "print-vars", "step end", "print-vars",
             f"screenshot {work}/vars_on.png", "panel vars off", "panel strip off", f"screenshot {work}/vars_off.png",
             "panel vars on", "panel strip on"]
    for trap in ("pq", "kd", "grid"):
        lines += [f"trap {trap}", "print-hit", "print-naive", "print-ray"]
    code, out, err = run_script(args, work, "vars_traps", lines)
    if check(code == 0, f"vars and traps: viewer exit {code}\n{err}"):
        got = out.strip().splitlines()
        if check(len(got) == 3 + 3 * 3, f"vars and traps: expected 12 lines:\n{out}"):
            check(re.match(r"vars: X=\d+ Y=\d+ Z=\d+ .*\btMaxX=\S+ .*\bnext=[xyz] closest_hit=\S+$", got[0]) is not None,
                  f"grid print-vars: '{got[0]}'")
            check(re.match(r"vars: t_min=\S+ t_split=\S+ t_max=\S+ .*\bcase=[abc]\(\w+\) closest_hit=\S+ stack=\S+$", got[1])
                  is not None, f"kd-tree print-vars: '{got[1]}'")
            check(re.match(r"vars: .*closest_hit=[0-9.]+ stack=\S+$", got[2]) is not None, f"kd-tree at the end: '{got[2]}'")
            for k, trap in enumerate(("pq", "kd", "grid")):
                hit, naive, ray = got[3 + 3 * k: 6 + 3 * k]
                m, n = re.fullmatch(r"hit (\d+) (\S+)", hit), re.fullmatch(r"naive hit (\d+) (\S+)", naive)
                if not check(m is not None and n is not None, f"trap {trap}: '{hit}' / '{naive}'"):
                    continue
                check(m.group(1) != n.group(1), f"trap {trap}: the naive answer '{naive}' equals the traversal's '{hit}'")
                check(float(n.group(2)) > float(m.group(2)), f"trap {trap}: the naive hit is not the farther one")
                rays, hits = os.path.join(work, f"trap_{trap}_ray.txt"), os.path.join(work, f"trap_{trap}_hits.csv")
                with open(rays, "w") as f:
                    f.write(ray + "\n")
                c, _, e = run([args.cli, "trace", "--scene", f"procedural:trap_{trap}", "--structure", "brute",
                               "--rays", rays, "--out", hits])
                if check(c == 0, f"trap {trap}: accelviz-cli trace failed: {e}"):
                    with open(hits) as f:
                        row = list(csv.DictReader(f))[0]
                    check(row["prim"] == m.group(1), f"trap {trap}: brute force hits {row['prim']}, the viewer {hit}")
        c, o, _ = run([args.png_check, "--differ", f"{work}/vars_on.png", f"{work}/vars_off.png", "30"])
        check(c == 0, f"panel vars/strip off changed nothing: {o}")

    # ---- A trap's explanation applies to its scene and its structure with its parameters
    # only: another structure, the same one with other parameters or another scene hides it
    # (print-trap), and the demo's structure brings it back. A built-in structure's walk is
    # never audited (print-claims).
    kd = "structure kdtree split=middle axis=longest max_depth=1 clip=on"
    lines = [f"size {W} {H}", "trap kd", "print-trap", "print-claims", "structure kdtree", "print-trap", kd,
             "print-trap", "structure bvh", "print-trap", "trap grid", "print-trap", f"scene {SCENE}", "print-trap"]
    code, out, err = run_script(args, work, "trap_switch", lines)
    if check(code == 0, f"trap switch: viewer exit {code}\n{err}"):
        got = out.strip().splitlines()
        expected = ["trap kd: kd-tree: a hit beyond t_split in the near child",
                    "claims: none (a built-in structure: not audited)", "trap: none",
                    "trap kd: kd-tree: a hit beyond t_split in the near child", "trap: none",
                    "trap grid: uniform grid: a hit found in a cell but lying beyond it", "trap: none"]
        check(got == expected, f"trap switch: expected {expected}, got {got}")

    # ---- Mesh formats: one pyramid (a quad base, four sides) written as OBJ, PLY, STL and
    # glTF loads in the viewer and in accelviz-cli with the same numbering: the same hit.
    mesh_files = write_pyramids(work)
    lines = [f"size {W} {H}"]
    for path in mesh_files:
        lines += [f"scene {path}", "structure bvh", "ray 0.3 0.2 5 0 0 -1", "print-hit"]
    code, out, err = run_script(args, work, "mesh_formats", lines)
    if check(code == 0, f"mesh formats: viewer exit {code}\n{err}"):
        got = out.strip().splitlines()
        check(len(got) == len(mesh_files) and len(set(got)) == 1 and got[0].startswith("hit "),
              f"mesh formats: the viewer's hits differ or miss: {got}")
        rays = os.path.join(work, "pyramid_ray.txt")
        with open(rays, "w") as f:
            f.write("0.3 0.2 5 0 0 -1\n")
        for path in mesh_files:
            hits = path + ".csv"
            c, _, e = run([args.cli, "trace", "--scene", path, "--structure", "kdtree", "--rays", rays, "--out", hits])
            if check(c == 0, f"{path}: accelviz-cli trace failed: {e}") and got:
                with open(hits) as f:
                    row = list(csv.DictReader(f))[0]
                check(f"hit {row['prim']} {row['t']}" == got[0], f"{path}: accelviz-cli {row}, the viewer {got[0]}")
    # ---- The tree diagram: on and off differ; selection, isolation, the grid's cell walk, the
    # construction's tree and lecture mode all run.
    lines = ["size 1280 720", f"scene {SCENE}", "structure bvh traversal=pqueue width=2", "ray-at-pixel 640 300",
             "step hit", "tree off", f"screenshot {work}/tree_off.png", "tree on", f"screenshot {work}/tree_on.png",
             "tree-select 1", f"screenshot {work}/tree_select.png", "tree-select 1 isolate",
             f"screenshot {work}/tree_isolate.png", "large on", f"screenshot {work}/tree_large.png", "large off",
             "structure kdtree", "step 5", f"screenshot {work}/tree_kd.png",
             "structure grid", "step 5", f"screenshot {work}/tree_grid.png",
             "structure octree", "construct", "build-step 20", f"screenshot {work}/tree_build.png"]
    code, out, err = run_script(args, work, "tree", lines)
    if check(code == 0, f"tree: viewer exit {code}\n{err}"):
        for a, b in (("tree_off", "tree_on"), ("tree_on", "tree_select"), ("tree_select", "tree_isolate"),
                     ("tree_on", "tree_large"), ("tree_kd", "tree_grid"), ("tree_grid", "tree_build")):
            c, o, _ = run([args.png_check, "--differ", f"{work}/{a}.png", f"{work}/{b}.png", "30"])
            check(c == 0, f"tree: {a} and {b} look the same: {o}")

    # ---- The lecture playlist, headless: every state in order, back one; then recordings:
    # one frame per step moved, a GIF with the panels, an MP4 of the construction without.
    playlist = os.path.join(REPO, "scenes", "lecture.playlist")
    with open(playlist) as f:
        n_states = sum(1 for line in f if line.startswith("state "))
    lines = [f"size {W} {H}", f"playlist {playlist}", "print-state"] + ["next", "print-state"] * (n_states - 1)
    lines += ["next", "print-state", "prev", "print-state", "panel compare off", "show-chart off"]
    gif, mp4 = os.path.join(work, "steps.gif"), os.path.join(work, "build.mp4")
    lines += ["preset cornell", "structure kdtree", "step start",  # the preset's ray: the camera moved
              f"record {gif} fps=5", "step 5", "record stop",
              "construct", f"record {mp4} fps=10 ui=off size=320x200", "build-step 12", "record stop"]
    code, out, err = run_script(args, work, "playlist_record", lines)
    if check(code == 0, f"playlist and record: viewer exit {code}\n{err}"):
        states = [l for l in out.splitlines() if l.startswith("state ")]
        expected = [f"state {k}/{n_states}: " for k in range(1, n_states + 1)] + [f"state {n_states}/{n_states}: ",
                                                                                  f"state {n_states - 1}/{n_states}: "]
        check(len(states) == len(expected) and all(a.startswith(b) for a, b in zip(states, expected)),
              f"playlist: print-state lines {states}")
        wrote = [l for l in out.splitlines() if l.startswith("wrote ")]
        check(wrote == [f"wrote {gif} (6 frames)", f"wrote {mp4} (13 frames)"], f"record: {wrote}")
        for path, magic, offset in ((gif, b"GIF89a", 0), (mp4, b"ftyp", 4)):
            ok = os.path.exists(path)
            if ok:
                with open(path, "rb") as f:
                    ok = f.read(offset + len(magic))[offset:] == magic
            check(ok, f"record: {path} is not a {magic.decode()} file")
            check(not os.path.exists(path + ".part"), f"record: {path}.part left behind")

    # ---- The heat map's scale: automatic per image, fixed and shared by two structures; the
    # colour schemes switch.
    lines = [f"size {W} {H}", "preset stadium", "structure grid", "heatmap prims", "print-heatmap",
             "structure bvh", "heatmap prims", "print-heatmap", "heatmap-scale 0 30", "print-heatmap",
             "structure grid", "heatmap prims", "print-heatmap", "heatmap-diff bvh", "print-heatmap",
             "heatmap-diff off", "colors cividis hits=green-red",
             f"screenshot {work}/cividis.png", "colors viridis", f"screenshot {work}/viridis.png"]
    code, out, err = run_script(args, work, "heatmap_scale", lines)
    if check(code == 0, f"heatmap-scale: viewer exit {code}\n{err}"):
        got = out.strip().splitlines()
        if check(len(got) == 5 and all(l.startswith("heat map: prims ") for l in got), f"print-heatmap: {got}"):
            check("(auto)" in got[0] and "(auto)" in got[1] and got[0].split(",")[1] != got[1].split(",")[1],
                  f"auto scales follow each image: {got[:2]}")
            check(all("scale 0..30 (fixed)" in l for l in got[2:4]), f"a fixed scale stays across structures: {got[2:4]}")
            # grid minus bvh on a symmetric fixed scale; its mean is the two means' difference.
            m = re.search(r"heat map: prims minus bvh \d+x\d+, scale -30\.\.30 \(fixed\), mean (\S+),", got[4])
            means = [float(re.search(r"mean ([^,]+),", l).group(1)) for l in got[1:4]]
            check(m is not None and abs(float(m.group(1)) - (means[2] - means[0])) < 1e-2,
                  f"difference view: '{got[4]}' against the means {means}")
        c, o, _ = run([args.png_check, "--differ", f"{work}/cividis.png", f"{work}/viridis.png", "30"])
        check(c == 0, f"colors cividis and viridis look the same: {o}")

    # ---- Errors: parse errors (before any window) and execution errors, with SCRIPT:LINE.
    cases = [
        ("bad_parse.txt", "size 320 240\n# comment\nfly to the moon\n", r"^accelviz: .*bad_parse\.txt:3: unknown command 'fly'\n$"),
        ("bad_param.txt", "structure bvh leaf_size=999\n",
         r"^accelviz: .*bad_param\.txt:1: bvh parameter 'leaf_size' = '999' is invalid: expected an integer in \[1, 64\]\n$"),
        ("bad_step.txt", f"size {W} {H}\nscene {SCENE}\nstep 3\n", r"^accelviz: .*bad_step\.txt:3: no debug ray yet"),
        ("bad_pixel.txt", f"size {W} {H}\nscene {SCENE}\n\nray-at-pixel 5000 10\n",
         r"^accelviz: .*bad_pixel\.txt:4: ray-at-pixel: \(5000, 10\) is outside the 480x320 window"),
        # 1280x720 with the panels: the 3D view lies between them (the scene is framed there),
        # so x = 100 is under the controls.
        ("under_panel.txt", f"size 1280 720\nscene {SCENE}\nray-at-pixel 100 360\n",
         r"^accelviz: .*under_panel\.txt:3: ray-at-pixel: x = 100 is under a panel; the 3D view spans x = 3\d\d\.\.7\d\d "),
        ("bad_scene.txt", f"size {W} {H}\nscene /no/such/file.obj\n", r"^accelviz: .*bad_scene\.txt:2: .*/no/such/file\.obj"),
        ("bad_chart.txt", f"size {W} {H}\nshow-chart on\nload-bench {BENCH_JSON}\nshow-chart on group=3\n",
         r"^accelviz: .*bad_chart\.txt:2: show-chart: no bench JSON loaded"),
        ("bad_group.txt", f"size {W} {H}\nload-bench {BENCH_JSON}\nshow-chart on group=3\n",
         r"^accelviz: .*bad_group\.txt:3: show-chart: group=3, but .*bench_chart\.json has 2 group\(s\)"),
        ("bad_build_step.txt", f"size {W} {H}\nscene {SCENE}\nbuild-step 3\n",
         r"^accelviz: .*bad_build_step\.txt:3: build-step: no construction recorded yet \(use construct first\)\n$"),
        ("bad_build_args.txt", "build-step back\n",
         r"^accelviz: .*bad_build_args\.txt:1: usage: build-step N \| build-step end \| build-step back N"),
        ("bad_trap.txt", "trap nope\n", r"^accelviz: .*bad_trap\.txt:1: trap: unknown trap 'nope' \(valid: pq, kd, grid\)\n$"),
        ("bad_vars.txt", f"size {W} {H}\nscene {SCENE}\nprint-vars\n",
         r"^accelviz: .*bad_vars\.txt:3: print-vars: no debug ray yet"),
        ("bad_naive.txt", "print-naive now\n", r"^accelviz: .*bad_naive\.txt:1: 'print-naive' takes no arguments\n$"),
        ("bad_heatmap_diff.txt", "heatmap-diff nope\n", r"^accelviz: .*bad_heatmap_diff\.txt:1: heatmap-diff: .*nope"),
        ("bad_heatmap_scale.txt", "heatmap-scale 5 2\n",
         r"^accelviz: .*bad_heatmap_scale\.txt:1: heatmap-scale: expected 0 <= LO < HI, got 5 2\n$"),
        ("bad_colors.txt", "colors jet\n", r"^accelviz: .*bad_colors\.txt:1: usage: colors viridis\|cividis\|turbo"),
        ("bad_record_stop.txt", "record stop\n", r"^accelviz: .*bad_record_stop\.txt:1: record stop: not recording\n$"),
        ("bad_next.txt", "next\n", r"^accelviz: .*bad_next\.txt:1: no playlist loaded \(use playlist FILE first\)\n$"),
        ("bad_playlist_ref.txt", f"size {W} {H}\nplaylist {work}/bad.playlist\n",
         r"^accelviz: .*bad_playlist_ref\.txt:2: .*bad\.playlist:3: unknown command 'fly'\n$"),
        ("bad_record_dir.txt", f"size {W} {H}\nrecord /no/such/dir/a.gif\n",
         r"^accelviz: .*bad_record_dir\.txt:2: record: /no/such/dir/a\.gif: the directory /no/such/dir does not exist\n$"),
        ("bad_tree_select.txt", f"size {W} {H}\nscene {SCENE}\nstructure bvh\ntree-select 99999999\n",
         r"^accelviz: .*bad_tree_select\.txt:4: tree-select: node 99999999 does not exist \(the .+ has \d+ nodes, 0\.\.\d+\)\n$"),
        ("bad_tree_grid.txt", f"size {W} {H}\nscene {SCENE}\nstructure grid\ntree-select 0\n",
         r"^accelviz: .*bad_tree_grid\.txt:4: tree-select: the .+ has no tree"),
        # The memory budget reaches the viewer's builds: over it, the builder's one line.
        ("over_budget.txt", f"size {W} {H}\nscene {SCENE}\nmemory-limit 8M\nstructure grid res=256,256,256\n",
         r"^accelviz: .*over_budget\.txt:4: .*'res'.*memory limit 8 MiB"),
        ("bad_memory_limit.txt", "memory-limit 12Q\n",
         r"^accelviz: .*bad_memory_limit\.txt:1: memory-limit '12Q': expected a size"),
        ("bad_bench.txt", f"size {W} {H}\nload-bench /no/such/bench.json\n",
         r"^accelviz: .*bad_bench\.txt:2: /no/such/bench\.json: cannot read the file\n$"),
    ]
    with open(os.path.join(work, "bad.playlist"), "w") as f:
        f.write("state One\nscene procedural:cornell\nfly to the moon\n")
    for file, text, pattern in cases:
        path = os.path.join(work, file)
        with open(path, "w") as f:
            f.write(text)
        c, _, e = viewer(args, path)
        check(c == 2, f"{file}: expected exit 2, got {c}: {e}")
        check(re.search(pattern, e) is not None, f"{file}: stderr '{e.strip()}' does not match {pattern}")

    if FAILURES:
        print(f"{len(FAILURES)} failure(s)")
        return 1
    print("all viewer script checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
