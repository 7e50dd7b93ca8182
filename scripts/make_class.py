#!/usr/bin/env python3
"""Makes a class of submissions for `accelviz-cli grade-class` from the kit's own code: copies of
the worked example, the five skeletons, the lecturer's test solutions and their planted bugs
(the bug's #define written at the top of the copy), under student names, one folder each.

    scripts/make_class.py OUT [--students 40] [--hostile]

--hostile adds the hostile submissions of tests/student/hostile/ (each under its own name).
Used to measure grade-class on a class of 40 (docs/student.md) and by its tests.
"""
import argparse
import os
import shutil
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SOL = os.path.join(ROOT, "tests", "student", "solutions")

# (what, source file, defines written above it): what a class hands in.
KINDS = [
    ("example", os.path.join(ROOT, "student", "example", "median_bvh.cpp"), []),
    ("sol_grid", os.path.join(SOL, "grid.cpp"), []),
    ("sol_octree", os.path.join(SOL, "octree.cpp"), []),
    ("sol_kdtree", os.path.join(SOL, "kdtree.cpp"), []),
    ("sol_bvh", os.path.join(SOL, "bvh.cpp"), []),
    ("sol_spheretree", os.path.join(SOL, "spheretree.cpp"), []),
    ("bug_grid_tie", os.path.join(SOL, "grid.cpp"), ["PLANT_BUG_GRID_TIE"]),
    ("bug_kd_no_case_c", os.path.join(SOL, "kdtree.cpp"), ["PLANT_BUG_KD_NO_CASE_C"]),
    ("bug_kd_no_tsplit", os.path.join(SOL, "kdtree.cpp"), ["PLANT_BUG_KD_NO_TSPLIT_CHECK"]),
    ("bug_bvh_first_hit", os.path.join(SOL, "bvh.cpp"), ["PLANT_BUG_BVH_FIRST_HIT"]),
    ("bug_octree_boundary", os.path.join(SOL, "octree.cpp"), ["PLANT_BUG_OCTREE_BOUNDARY"]),
    ("bug_sphere_too_small", os.path.join(SOL, "spheretree.cpp"), ["PLANT_BUG_SPHERE_TOO_SMALL"]),
] + [("skeleton_" + k, os.path.join(ROOT, "student", "skeletons", k, k + ".cpp"), [])
     for k in ("grid", "octree", "kdtree", "bvh", "spheretree")]

NAMES = ["ada", "alan", "barbara", "claude", "dennis", "donald", "edsger", "frances", "grace", "guido",
         "hedy", "ivan", "jean", "john", "ken", "leslie", "linus", "margaret", "niklaus", "radia",
         "richard", "robin", "shafi", "sophie", "tim", "tony", "turing", "vint", "whitfield", "yukihiro",
         "anita", "bjarne", "carla", "dana", "edith", "fei", "gwen", "hal", "ida", "jim", "karen", "lynn"]


def write_submission(folder, source, defines, structure):
    os.makedirs(folder, exist_ok=True)
    with open(source) as f:
        text = f.read()
    head = "".join(f"#define {d}\n" for d in defines) + f'#define SOLUTION_NAME "{structure}"\n'
    with open(os.path.join(folder, os.path.basename(source)), "w") as f:
        f.write(head + text)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("--students", type=int, default=40)
    ap.add_argument("--hostile", action="store_true")
    args = ap.parse_args()
    if os.path.exists(args.out):
        shutil.rmtree(args.out)
    os.makedirs(args.out)
    for i in range(args.students):
        what, source, defines = KINDS[i % len(KINDS)]
        name = f"{NAMES[i % len(NAMES)]}{i // len(NAMES) or ''}_{what}"
        # The example and the skeletons name their structure themselves; the solutions take it.
        write_submission(os.path.join(args.out, name), source, defines, "s_" + what)
    if args.hostile:
        hostile = os.path.join(ROOT, "tests", "student", "hostile")
        for h in sorted(os.listdir(hostile)):
            if os.path.isdir(os.path.join(hostile, h)):
                shutil.copytree(os.path.join(hostile, h), os.path.join(args.out, "hostile_" + h))
    print(f"{len(os.listdir(args.out))} submissions in {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
