#!/usr/bin/env python3
"""End-to-end tests of accelviz-cli: trace answers (hand-checked), the CSV format of
docs/hits.md, and bad input (exit 2, one line naming file and line, no output file)."""
import argparse
import csv
import json
import math
import os
import re
import shutil
import subprocess
import sys

FAILURES = []


def check(cond, what):
    if not cond:
        FAILURES.append(what)
        print("FAIL:", what)


def run(cli, *args):
    p = subprocess.run([cli, *args], capture_output=True, text=True, timeout=300)
    return p.returncode, p.stdout, p.stderr


# steps.obj: prim 0 = (0,0,0),(2,0,0),(2,2,0); prim 1 = (0,0,0),(2,2,0),(0,2,0); prim 2 at z=1.
RAYS = """# hand-checked rays for scenes/steps.obj
0.25 0.25 5 0 0 -1
1.5 0.5 5 0 0 -1
0.5 1.5 5 0 0 -1
3 3 5 0 0 -1

0.25 0.25 5 0 0 -1 0 3
0.3 0.2 5 0 0 -1 4.5 inf
0x1p-2 0x1p-2 0x1.4p+2 0 0 -1
-1 1 0 1 0 0
0.5 1.5 -1 0 0 1
1 1 5 0 0 -1
0.25 0.25 5 0 0 -2 0 2
"""
# (allowed prims, t, u, v); u, v only checked for a unique prim.
EXPECTED = [
    ({2}, 4.0, 0.25, 0.25),   # triangle above the floor
    ({0}, 5.0, 0.5, 0.25),
    ({1}, 5.0, 0.25, 0.5),
    ({-1}, math.inf, 0, 0),   # outside
    ({-1}, math.inf, 0, 0),   # tmax = 3 stops before the triangle at t = 4
    ({0}, 5.0, 0.05, 0.1),    # tmin = 4.5 skips the triangle
    ({2}, 4.0, 0.25, 0.25),   # hex-float input
    ({-1}, math.inf, 0, 0),   # ray inside the floor's plane: never a hit
    ({1}, 1.0, 0.25, 0.5),    # from below
    ({0, 1}, 5.0, None, None),  # on the shared diagonal: a tie, either triangle
    ({2}, 2.0, 0.25, 0.25),   # unnormalised direction: t in units of d, tmax = 2 inclusive
]


def read_csv(path):
    with open(path) as f:
        lines = f.read().splitlines()
    return lines[0], [l.split(",") for l in lines[1:]]


def test_trace(cli, source, work):
    scene = os.path.join(source, "scenes", "steps.obj")
    rays = os.path.join(work, "steps_rays.txt")
    with open(rays, "w") as f:
        f.write(RAYS)
    for threads in ("1", "2"):
        out = os.path.join(work, f"hits_{threads}.csv")
        code, _, err = run(cli, "trace", "--scene", scene, "--structure", "brute", "--rays", rays, "--out", out,
                           "--threads", threads)
        check(code == 0, f"trace exit {code}: {err}")
        if code != 0:
            return
        header, rows = read_csv(out)
        check(header == "ray,prim,t,u,v", f"header {header!r}")
        check(len(rows) == len(EXPECTED), f"{len(rows)} rows")
        for i, (row, (prims, t, u, v)) in enumerate(zip(rows, EXPECTED)):
            check(int(row[0]) == i, f"row {i} index {row[0]}")
            prim = int(row[1])
            check(prim in prims, f"ray {i}: prim {prim}, expected {prims}")
            if math.isinf(t):
                check(row[2] == "inf", f"ray {i}: t {row[2]} for a miss")
                continue
            check(abs(float(row[2]) - t) <= 1e-6 * max(1, t), f"ray {i}: t {row[2]} expected {t}")
            if u is not None:
                check(abs(float(row[3]) - u) < 1e-6 and abs(float(row[4]) - v) < 1e-6, f"ray {i}: u,v {row[3:]}")
    a = open(os.path.join(work, "hits_1.csv")).read()
    b = open(os.path.join(work, "hits_2.csv")).read()
    check(a == b, "output differs between 1 and 2 threads")


def expect_bad(cli, args, must_contain, out=None, code_expected=2):
    code, stdout, err = run(cli, *args)
    lines = [l for l in err.splitlines() if l.strip()]
    check(code == code_expected, f"{args}: exit {code}, expected {code_expected}; stderr {err!r}")
    check(len(lines) == 1, f"{args}: expected one error line, got {lines!r}")
    check(must_contain in err, f"{args}: message {err!r} lacks {must_contain!r}")
    if out:
        check(not os.path.exists(out), f"{args}: output file {out} was written")
    check("Traceback" not in err and "Aborted" not in err, f"{args}: crashed")


# A 2D scene (docs/hits.md, 2D scenes): prim 0 = (0,0),(4,0),(0,4); prim 1 = (6,0),(8,0),(6,2).
SCENE_2D = """# two triangles
tri 0 0 4 0 0 4
tri 6 0 8 0 6 2
"""
RAYS_2D = """-2 1 0 1 0 0
1 1 0 1 0 0
5 1 0 1 0 0
-1 3 0 1 1 0
5 5 0 1 0 0
9 1 0 -2 0 0
"""
# enters through an edge, starts inside, enters the other, grazes a vertex, misses, d of length 2
EXPECTED_2D = [(0, 2.0), (0, 0.0), (1, 1.0), (0, 1.0), (-1, math.inf), (1, 1.0)]


def test_trace_2d(cli, work):
    scene = os.path.join(work, "two.scene2d")
    rays = os.path.join(work, "rays_2d.txt")
    with open(scene, "w") as f:
        f.write(SCENE_2D)
    with open(rays, "w") as f:
        f.write(RAYS_2D)
    for structure in ("brute", "grid", "octree", "kdtree", "bvh", "spheretree"):
        out = os.path.join(work, f"hits_2d_{structure}.csv")
        code, _, err = run(cli, "trace", "--scene", scene, "--structure", structure, "--rays", rays, "--out", out)
        check(code == 0, f"2D trace {structure} exit {code}: {err}")
        if code != 0:
            continue
        _, rows = read_csv(out)
        got = [(int(r[1]), float(r[2])) for r in rows]
        check(got == EXPECTED_2D, f"2D trace {structure}: {got}, expected {EXPECTED_2D}")
    # bench on a 2D scene judges by the 2D rule too: no wrong answer, the kernel named planar.
    bench_json = os.path.join(work, "bench_2d.json")
    code, _, err = run(cli, "bench", "--scene", scene, "--structures", "grid,kdtree,bvh", "--rays", rays,
                       "--kernel", "watertight", "--no-embree", "--no-tinybvh", "--min-time", "0.001",
                       "--out-json", bench_json)
    check(code == 0, f"2D bench: exit {code}: {err}")
    if code == 0:
        with open(bench_json) as f:
            bench_rows = json.load(f)
        for r in bench_rows:
            check(r["kernel"] == "planar" and r["false_miss"] + r["false_hit"] + r["wrong_prim"] == 0,
                  f"2D bench row {r['structure']}: kernel {r['kernel']}, {r['false_miss']} false misses, "
                  f"{r['false_hit']} false hits, {r['wrong_prim']} wrong triangles")
    three_d = os.path.join(work, "rays_3d.txt")
    with open(three_d, "w") as f:
        f.write("# a 3D ray\n-2 1 0 1 0 0\n0 0 1 0 0 -1\n")
    out = os.path.join(work, "hits_2d_bad.csv")
    expect_bad(cli, ["trace", "--scene", scene, "--rays", three_d, "--out", out],
               f"{three_d}: ray 1 (0-based) is not a 2D ray", out)
    expect_bad(cli, ["trace", "--scene", scene, "--rays", "primary:4:4", "--out", out], "a 2D scene has no camera", out)
    bad_scene = os.path.join(work, "bad.scene2d")
    with open(bad_scene, "w") as f:
        f.write("tri 0 0 1 0 0 1\ntri 0 0 1 0 0\n")
    expect_bad(cli, ["trace", "--scene", bad_scene, "--rays", rays, "--out", out],
               f"{bad_scene}:2: tri needs 6 numbers", out)


def test_bad_input(cli, source, shared, work):
    scene = os.path.join(source, "scenes", "steps.obj")
    good_rays = os.path.join(work, "steps_rays.txt")
    out = os.path.join(work, "bad_out.csv")

    def trace(scene_path, rays_path=good_rays, *extra):
        return ["trace", "--scene", scene_path, "--rays", rays_path, "--out", out, *extra]

    expect_bad(cli, trace("/nonexistent/x.obj"), "/nonexistent/x.obj: cannot open", out)
    bad_rays = os.path.join(work, "bad_rays.txt")
    with open(bad_rays, "w") as f:
        f.write("0 0 5 0 0 -1\n# ok so far\n0 0 5 0 0\n")
    expect_bad(cli, trace(scene, bad_rays), f"{bad_rays}:3: expected 6 or 8", out)
    with open(bad_rays, "w") as f:
        f.write("0 0 nan 0 0 -1\n")
    expect_bad(cli, trace(scene, bad_rays), f"{bad_rays}:1: NaN", out)
    expect_bad(cli, trace(scene, "/nonexistent/rays.txt"), "/nonexistent/rays.txt: cannot open", out)
    expect_bad(cli, trace(scene, good_rays, "--structure", "quadtree"), "unknown structure 'quadtree' (valid: brute", out)
    expect_bad(cli, trace(scene, good_rays, "--param", "x=1"), "unknown parameter 'x'", out)
    expect_bad(cli, trace(scene, good_rays, "--kernel", "exact"), "--kernel 'exact' is invalid", out)
    expect_bad(cli, trace(scene, good_rays, "--threads", "-1"), "threads", out)
    expect_bad(cli, ["trace", "--scene", scene, "--rays", good_rays, "--out", "/nonexistent/dir/out.csv"],
               "/nonexistent/dir/out.csv: cannot open for writing")
    expect_bad(cli, ["trace", "--scene", scene], "--rays", out)
    nan_obj = os.path.join(work, "nan.obj")
    with open(nan_obj, "w") as f:
        f.write("v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n")
    expect_bad(cli, trace(nan_obj), f"{nan_obj}:3: vertex coordinate 'nan'", out)

    bad_dir = os.path.join(shared, "scenes", "bad")
    if not os.path.isdir(bad_dir):
        print("SKIP: shared bad files not present")
        return
    rejected = {"empty.obj": "empty file", "malformed.obj": "out of range", "malformed2.obj": "face needs",
                "number_formats.obj": ":11: malformed number", "testline.obj": "no triangles",
                "testpoints.obj": "no triangles", "point_cloud.obj": "no triangles", "box_UTF16BE.obj": "UTF-16"}
    for name in sorted(os.listdir(bad_dir)):
        path = os.path.join(bad_dir, name)
        if name in rejected:
            expect_bad(cli, trace(path), f"{path}:", out)
            expect_bad(cli, trace(path), rejected[name], out)
            expect_bad(cli, ["stats", "--scene", path], rejected[name])
        else:
            code, _, err = run(cli, *trace(path))
            check(code == 0, f"{name}: should load, exit {code} {err}")
            if os.path.exists(out):
                os.remove(out)


BENCH_KEYS = {"scene": str, "structure": str, "params": str, "kernel": str, "rays": str, "n_rays": int,
              "build_ms": (int, float), "memory_bytes": int, "mrays_1t": (int, float), "mrays_mt": (int, float),
              "threads": int, "false_miss": int, "false_hit": int, "wrong_prim": int, "max_rel_t_err": (int, float)}


PEERS = ("embree-", "tinybvh-")
TINYBVH_ROWS = ["tinybvh-bvh8", "tinybvh-bvh4", "tinybvh-bvh8-hq"]


def has_tinybvh(cli):
    """Whether this binary runs the tinybvh rows: built with tinybvh (bench --help says so)
    and the CPU has AVX2 (else bench prints a note and skips them)."""
    _, help_text, _ = run(cli, "bench", "--help")
    if "--no-tinybvh" not in help_text or "has no tinybvh" in help_text:
        return False
    _, _, err = run(cli, "bench", "--scene", "procedural:cornell", "--structures", "grid", "--rays", "random:10:1",
                    "--min-time", "0.001", "--no-embree")
    return "lacks AVX2" not in err


def check_tinybvh_rows(rows, scenes, what):
    """The tinybvh rows: three per scene, a build time, memory and counted errors."""
    tiny = [r for r in rows if r["structure"].startswith("tinybvh-")]
    check(len(tiny) == 3 * scenes, f"{what}: {len(tiny)} tinybvh rows, expected 3 per scene")
    check(sorted(set(r["structure"] for r in tiny)) == sorted(TINYBVH_ROWS), f"{what}: tinybvh rows {tiny}")
    for r in tiny:
        check(r["kernel"] == "tinybvh" and r["build_ms"] > 0 and r["memory_bytes"] > 0,
              f"{what}: {r['structure']} kernel {r['kernel']} build_ms {r['build_ms']} MB {r['memory_bytes']}")
        errors = r["false_miss"] + r["false_hit"] + r["wrong_prim"] + r["wrong_t"]
        check(isinstance(errors, int) and 0 <= errors <= r["n_rays"], f"{what}: {r['structure']} errors {errors}")
        check("peer_ratio_mt" not in r, f"{what}: peer row {r['structure']} has a peer_ratio_mt")


def test_bench(cli, work):
    """bench writes one row per scene x structure x kernel (plus Embree and tinybvh rows when
    built with them) with the keys of issue #6, the same rows as JSON, CSV and Markdown, and the
    watertight kernel makes no error; bad options fail before any output file is written."""
    tinybvh = has_tinybvh(cli)
    out = {ext: os.path.join(work, f"bench.{ext}") for ext in ("json", "csv", "md")}
    args = ["bench", "--scene", "procedural:cornell", "--scene", "procedural:soup", "--structures", "all",
            "--kernel", "watertight,moller", "--rays", "random:2000:1", "--threads", "2", "--min-time", "0.001",
            "--out-json", out["json"], "--out-csv", out["csv"], "--out-md", out["md"]]
    code, stdout, err = run(cli, *args)
    check(code == 0, f"bench: exit {code}, stderr {err!r}")
    if code != 0:
        return
    with open(out["json"]) as f:
        rows = json.load(f)
    ours = [r for r in rows if not r["structure"].startswith(PEERS)]
    embree = [r for r in rows if r["structure"].startswith("embree-")]
    if tinybvh:
        check_tinybvh_rows(rows, 2, "bench")
    else:
        check(not any(r["structure"].startswith("tinybvh-") for r in rows), "bench: tinybvh rows without tinybvh")
    # "all" is every structure but brute: the five built-in ones and any student structure
    # built in (scripts/build.sh --student DIR), as `params` lists them.
    _, params_out, _ = run(cli, "params")
    structures = len([l for l in params_out.splitlines() if l and not l.startswith(" ")]) - 1
    check(len(ours) == 2 * structures * 2,
          f"bench: {len(ours)} project rows, expected 2 scenes x {structures} structures x 2 kernels")
    check(len(embree) in (0, 4), f"bench: {len(embree)} Embree rows, expected none or medium+high per scene")
    for r in rows:
        for key, kind in BENCH_KEYS.items():
            check(key in r and isinstance(r[key], kind), f"bench row {r.get('structure')}: key {key!r} missing or mistyped")
        check(r["n_rays"] == 2000 and r["rays"] == "random:2000:1", f"bench row {r['structure']}: rays {r['rays']}")
        check(r["mrays_1t"] > 0 and r["mrays_mt"] > 0, f"bench row {r['structure']}: no throughput")
    for r in rows:
        # Build ratio on every row (Embree's own too): Embree medium build ms / this row's.
        check("embree_build_ratio" in r, f"bench row {r['structure']}: no embree_build_ratio key")
        ratio = r.get("embree_build_ratio")
        if embree:
            check(isinstance(ratio, (int, float)) and ratio > 0 and math.isfinite(ratio),
                  f"bench row {r['scene']} {r['structure']}: embree_build_ratio {ratio!r} with Embree")
        else:
            check(ratio is None, f"bench row {r['structure']}: embree_build_ratio {ratio!r} without Embree")
        check(r["build_ms"] >= 0, f"bench row {r['structure']}: build_ms {r['build_ms']}")
        # SAH cost: a number for the hierarchies (to compare builders), null for Embree.
        sah = r.get("sah_cost", "missing")
        if r["structure"] in ("bvh", "spheretree"):
            check(isinstance(sah, (int, float)) and sah > 0, f"bench row {r['structure']}: sah_cost {sah!r}")
        elif r["structure"].startswith(PEERS):
            check(sah is None, f"bench row {r['structure']}: sah_cost {sah!r}, expected null")
    for r in embree:
        check(r["build_ms"] > 0, f"bench row {r['scene']} {r['structure']}: Embree build_ms {r['build_ms']}")
        if r["structure"] == "embree-medium":
            check(r["embree_build_ratio"] == 1, f"bench: embree-medium build ratio {r['embree_build_ratio']}, not 1")
    for r in ours:
        check("embree_ratio_mt" in r, f"bench row {r['structure']}: no embree_ratio_mt key")
        check((r["embree_ratio_mt"] is None) == (not embree), f"bench row {r['structure']}: ratio {r['embree_ratio_mt']}")
        for key in ("peer_ratio_mt", "peer_ratio_1t"):
            value = r.get(key, "missing")
            if embree or tinybvh:
                check(isinstance(value, (int, float)) and value > 0, f"bench row {r['structure']}: {key} {value!r}")
            else:
                check(value is None, f"bench row {r['structure']}: {key} {value!r} without peers")
        if r["kernel"] == "watertight":
            errors = r["false_miss"] + r["false_hit"] + r["wrong_prim"]
            check(errors == 0, f"bench: {r['scene']} {r['structure']} watertight has {errors} errors")
    with open(out["csv"]) as f:
        csv_lines = f.read().splitlines()
    check(len(csv_lines) == len(rows) + 1 and csv_lines[0].startswith("scene,structure,params,kernel,rays,n_rays"),
          f"bench CSV: {len(csv_lines)} lines")
    csv_rows = list(csv.DictReader(csv_lines))
    check("build_ms" in csv_rows[0] and "embree_build_ratio" in csv_rows[0], f"bench CSV header {csv_lines[0]!r}")
    check(csv_lines[0].endswith(",embree_build_ratio,peer_ratio_mt,peer_ratio_1t"), f"bench CSV header {csv_lines[0]!r}")
    for r in csv_rows:
        peer = r["structure"].startswith(PEERS)
        check((r["peer_ratio_mt"] != "") == (not peer and bool(embree or tinybvh)),
              f"bench CSV: {r['structure']} peer_ratio_mt {r['peer_ratio_mt']!r}")
    cells = [r.get("embree_build_ratio") for r in csv_rows]
    check(all((c not in ("", None)) == bool(embree) for c in cells), f"bench CSV: embree_build_ratio cells {cells[:4]}")
    with open(out["md"]) as f:
        md = f.read()
    check(md == stdout and md.count("\n") == len(rows) + 2, "bench Markdown: not the printed table")
    md_header = [c.strip() for c in md.splitlines()[0].strip("|").split("|")]
    check("build ms" in md_header and "Embree build ratio" in md_header, f"bench Markdown header {md_header}")
    check(md_header[-2:] == ["vs peer (1t)", "vs peer (mt)"], f"bench Markdown header {md_header}")
    test_bench_without_embree(cli, work)
    test_bench_embree_robust(cli, work, bool(embree))
    test_build_vs_embree(cli, work, bool(embree))
    if tinybvh:
        test_bench_tinybvh_only(cli, work)
    bad_out = os.path.join(work, "bench_bad.json")
    bench = ["bench", "--scene", "procedural:cornell", "--rays", "random:10:1", "--out-json", bad_out]
    expect_bad(cli, bench + ["--structures", "grid,quadtree"], "unknown structure 'quadtree'", bad_out)
    expect_bad(cli, bench + ["--kernel", "fast"], "--kernel 'fast' is invalid", bad_out)
    expect_bad(cli, bench + ["--param", "colour=red"], "--param 'colour=red' matches no parameter", bad_out)
    expect_bad(cli, bench + ["--structures", "bvh", "--param", "leaf_size=0"], "'leaf_size' = '0' is invalid", bad_out)
    expect_bad(cli, ["bench", "--scene", "procedural:cornell", "--rays", "random:0:1", "--out-json", bad_out], "random",
               bad_out)
    expect_bad(cli, bench + ["--min-time", "0"], "--min-time", bad_out)
    expect_bad(cli, ["bench", "--scene", "/nonexistent/x.obj", "--out-json", bad_out], "/nonexistent/x.obj: cannot open",
               bad_out)


def test_bench_embree_robust(cli, work, with_embree):
    """--embree-robust adds one embree-robust row per scene (Embree's robust mode, issue #51's
    ratio) after medium and high, an Embree row like them; without Embree, none."""
    out = os.path.join(work, "bench_robust.json")
    code, _, err = run(cli, "bench", "--scene", "procedural:cornell", "--structures", "bvh", "--rays", "random:2000:1",
                       "--threads", "2", "--min-time", "0.001", "--no-tinybvh", "--embree-robust", "--out-json", out)
    check(code == 0, f"bench --embree-robust: exit {code}, stderr {err!r}")
    if code != 0:
        return
    with open(out) as f:
        names = [r["structure"] for r in json.load(f)]
    expected = ["embree-medium", "embree-high", "embree-robust", "bvh"] if with_embree else ["bvh"]
    check(names == expected, f"bench --embree-robust: rows {names}, expected {expected}")


def test_build_vs_embree(cli, work, with_embree):
    """build-vs-embree (issue #51): per scene, --runs fresh processes per side, their medians and
    Embree / accelviz as the ratio, in the printed line and the JSON; a scene that cannot be
    loaded is a one-line error naming it, nothing printed, no file; without Embree, an error."""
    out = {ext: os.path.join(work, f"build_vs_embree.{ext}") for ext in ("json", "md")}
    scenes = ["procedural:cornell", "procedural:soup"]
    args = ["build-vs-embree", "--scene", scenes[0], "--scene", scenes[1], "--runs", "3", "--threads", "2",
            "--out-json", out["json"], "--out-md", out["md"]]
    code, stdout, err = run(cli, *args)
    if not with_embree:
        check(code == 2 and "without Embree" in err and stdout == "", f"build-vs-embree without Embree: {code} {err!r}")
        return
    check(code == 0, f"build-vs-embree: exit {code}, stderr {err!r}")
    if code != 0:
        return
    with open(out["json"]) as f:
        rows = json.load(f)
    check([r["scene"] for r in rows] == scenes, f"build-vs-embree: rows {[r['scene'] for r in rows]}")
    for r in rows:
        for side in ("accelviz", "embree"):
            cold = r[f"{side}_cold_ms"]
            check(len(cold) == 3 and all(ms > 0 for ms in cold), f"build-vs-embree {r['scene']}: {side} runs {cold}")
            check(r[f"{side}_cold_median_ms"] == sorted(cold)[1], f"build-vs-embree {r['scene']}: {side} median")
        ratio = r["embree_cold_median_ms"] / r["accelviz_cold_median_ms"]
        check(abs(r["embree_over_accelviz_cold"] - ratio) <= 1e-9 * ratio,
              f"build-vs-embree {r['scene']}: ratio {r['embree_over_accelviz_cold']} vs {ratio}")
        check(r["triangles"] > 0 and r["threads"] == 2,
              f"build-vs-embree {r['scene']}: {r['triangles']} triangles, {r['threads']} threads")
        line = [l for l in stdout.splitlines() if l.startswith(r["scene"] + " ")]
        check(len(line) == 1 and f"{r['embree_over_accelviz_cold']:.2f}" in line[0].split(),
              f"build-vs-embree: printed line of {r['scene']}: {line}")
    with open(out["md"]) as f:
        check(len(f.read().splitlines()) == 2 + len(scenes), f"build-vs-embree: Markdown rows")
    bad_out = os.path.join(work, "build_vs_embree_bad.json")
    code, stdout, err = run(cli, "build-vs-embree", "--scene", "/nonexistent/x.obj", "--runs", "1",
                            "--out-json", bad_out)
    check(code == 2 and stdout == "" and len(err.splitlines()) == 1 and "/nonexistent/x.obj" in err,
          f"build-vs-embree, missing scene: exit {code}, stdout {stdout!r}, stderr {err!r}")
    check(not os.path.exists(bad_out), "build-vs-embree, missing scene: the JSON was written")


def test_bench_tinybvh_only(cli, work):
    """--no-embree with tinybvh: the tinybvh rows are the peers, so peer_ratio_* are numbers
    while the embree_* ratios are null."""
    out = os.path.join(work, "bench_tinybvh.json")
    code, _, err = run(cli, "bench", "--scene", "procedural:cornell", "--structures", "bvh", "--rays", "random:500:1",
                       "--threads", "2", "--min-time", "0.001", "--no-embree", "--out-json", out)
    check(code == 0, f"bench --no-embree (tinybvh): exit {code}, stderr {err!r}")
    if code != 0:
        return
    with open(out) as f:
        rows = json.load(f)
    check_tinybvh_rows(rows, 1, "bench --no-embree")
    ours = [r for r in rows if not r["structure"].startswith(PEERS)]
    fastest = max(r["mrays_mt"] for r in rows if r["structure"].startswith("tinybvh-"))
    for r in ours:
        check(r["embree_ratio_mt"] is None, f"bench --no-embree {r['structure']}: embree_ratio_mt {r['embree_ratio_mt']}")
        check(isinstance(r.get("peer_ratio_mt"), (int, float)) and isinstance(r.get("peer_ratio_1t"), (int, float)),
              f"bench --no-embree {r['structure']}: peer ratios {r.get('peer_ratio_mt')!r} {r.get('peer_ratio_1t')!r}")
        if isinstance(r.get("peer_ratio_mt"), (int, float)):
            check(abs(r["peer_ratio_mt"] - r["mrays_mt"] / fastest) <= 1e-3 * max(1.0, r["peer_ratio_mt"]) + 1e-3,
                  f"bench --no-embree {r['structure']}: peer_ratio_mt {r['peer_ratio_mt']} vs {r['mrays_mt']}/{fastest}")


def test_bench_without_embree(cli, work):
    """--no-embree --no-tinybvh: no peer rows, and the build and peer ratios are null / empty /
    "-" everywhere."""
    out = {ext: os.path.join(work, f"bench_noembree.{ext}") for ext in ("json", "csv", "md")}
    code, _, err = run(cli, "bench", "--scene", "procedural:cornell", "--structures", "bvh,grid", "--rays", "random:500:1",
                       "--threads", "2", "--min-time", "0.001", "--no-embree", "--no-tinybvh", "--out-json", out["json"],
                       "--out-csv", out["csv"], "--out-md", out["md"])
    check(code == 0, f"bench --no-embree: exit {code}, stderr {err!r}")
    if code != 0:
        return
    with open(out["json"]) as f:
        rows = json.load(f)
    check(len(rows) == 2 and not any(r["structure"].startswith(PEERS) for r in rows),
          f"bench --no-embree: rows {[r['structure'] for r in rows]}")
    for r in rows:
        check("embree_build_ratio" in r and r["embree_build_ratio"] is None,
              f"bench --no-embree {r['structure']}: embree_build_ratio {r.get('embree_build_ratio')!r}")
        check(isinstance(r.get("build_ms"), (int, float)), f"bench --no-embree {r['structure']}: build_ms")
        check(r.get("peer_ratio_mt", "missing") is None and r.get("peer_ratio_1t", "missing") is None,
              f"bench --no-embree {r['structure']}: peer ratios {r.get('peer_ratio_mt')!r} without peers")
    with open(out["csv"]) as f:
        lines = f.read().splitlines()
    cells = [r.get("embree_build_ratio") for r in csv.DictReader(lines)]
    check(len(cells) == 2 and all(c == "" for c in cells), f"bench --no-embree CSV: ratio cells {cells}")
    with open(out["md"]) as f:
        md_lines = f.read().splitlines()
    md_header = [c.strip() for c in md_lines[0].strip("|").split("|")]
    if "Embree build ratio" in md_header:
        col = md_header.index("Embree build ratio")
        cells = [[c.strip() for c in l.strip("|").split("|")][col] for l in md_lines[2:]]
        check(cells and all(c == "-" for c in cells), f"bench --no-embree Markdown: ratio cells {cells}")


def test_build_trace(cli, source, work):
    """stats --build-trace FILE: JSON lines, a header then one object per step, from the scene
    box to done; the same structure's statistics on stdout; bad paths are one-line errors."""
    obj = os.path.join(source, "scenes", "steps.obj")
    for structure in ["brute", "grid", "octree", "kdtree", "bvh", "spheretree"]:
        out = os.path.join(work, f"build_{structure}.jsonl")
        code, stdout, err = run(cli, "stats", "--scene", obj, "--structure", structure, "--build-trace", out)
        check(code == 0, f"stats --build-trace {structure}: exit {code}, {err!r}")
        if code != 0:
            continue
        check("build trace:" in err and out in err, f"{structure}: no 'build trace:' line in {err!r}")
        with open(out) as f:
            lines = [json.loads(l) for l in f]
        header, steps = lines[0], lines[1:]
        check(header["steps"] == len(steps), f"{structure}: header says {header['steps']} steps, file has {len(steps)}")
        check(header["coverage"] == "complete", f"{structure}: coverage {header['coverage']}")
        check(len(steps) > 0, f"{structure}: no steps recorded")
        if not steps:
            continue
        check(steps[0]["kind"] == "scene_box" and steps[-1]["kind"] == "done",
              f"{structure}: first/last steps {steps[0]['kind']}/{steps[-1]['kind']}")
        check([s["step"] for s in steps] == list(range(len(steps))), f"{structure}: steps not numbered 0..N-1")
    expect_bad(cli, ["stats", "--scene", obj, "--structure", "bvh", "--build-trace",
                     os.path.join(work, "no_such_dir", "t.jsonl")], "no_such_dir",
               out=os.path.join(work, "no_such_dir", "t.jsonl"))
    expect_bad(cli, ["stats", "--scene", obj, "--structure", "bvh", "--build-trace",
                     os.path.join(work, "t.jsonl"), "--build-trace-budget", "0"], "--build-trace-budget",
               out=os.path.join(work, "t.jsonl"))


def test_digest(cli, source):
    """stats --digest: one 16-hex-digit line, the same for the same build (text and JSON alike),
    another for another tree (the kd-tree's middle split against its SAH)."""
    obj = os.path.join(source, "scenes", "steps.obj")

    def digest(structure, *extra):
        code, stdout, err = run(cli, "stats", "--scene", obj, "--structure", structure, "--digest", *extra)
        check(code == 0, f"stats --digest {structure} {extra}: exit {code}, {err!r}")
        if "--json" in extra:
            return json.loads(stdout)["extra"].get("digest") if code == 0 else None
        lines = [l for l in stdout.splitlines() if l.startswith("digest: ")]
        check(len(lines) == 1, f"stats --digest {structure}: {len(lines)} digest lines")
        return lines[0].split(": ", 1)[1] if lines else None

    for structure in ["brute", "grid", "octree", "kdtree", "bvh", "spheretree"]:
        first = digest(structure)
        check(first is not None and re.fullmatch(r"[0-9a-f]{16}", first) is not None,
              f"{structure}: digest {first!r}")
        check(digest(structure) == first, f"{structure}: two builds, two digests")
        check(digest(structure, "--json") == first, f"{structure}: the JSON digest differs from the text one")
    check(digest("kdtree", "--param", "split=middle") != digest("kdtree"), "kdtree: middle and sah, one digest")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cli", required=True)
    ap.add_argument("--source", required=True)
    ap.add_argument("--shared", required=True)
    ap.add_argument("--work", required=True)
    a = ap.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    test_trace(a.cli, a.source, a.work)
    test_bad_input(a.cli, a.source, a.shared, a.work)
    test_trace_2d(a.cli, a.work)
    test_bench(a.cli, a.work)
    test_build_trace(a.cli, a.source, a.work)
    test_digest(a.cli, a.source)
    print(f"{'FAILED' if FAILURES else 'OK'}: {len(FAILURES)} failures")
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
