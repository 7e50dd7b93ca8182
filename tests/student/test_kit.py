#!/usr/bin/env python3
"""The assignment kit through `accelviz-cli check` (issue #41): the worked example and the
lecturer's solutions pass; every skeleton is reported wrong without a crash; each planted bug
is caught in its category (a named trap, a failed invariant, wrong answers on the hard cases)
with replay files that, opened in the viewer under Xvfb, show the same wrong answer; and
structures that crash, loop, throw or allocate without end get a report within the limits.

    python3 tests/student/test_kit.py --cli build/bin/accelviz-cli --worker build/bin/accelviz-worker-kit \
        [--viewer build/bin/accelviz-kit] --work /tmp/kit --sanitized 0

The kit's structures live in the worker (accelviz-worker-kit); accelviz-cli, the judge, links
none of them and checks them through it, in the sandbox (or with --no-sandbox where
bubblewrap cannot run: ACCEL_TEST_NO_SANDBOX=1).
"""
import argparse
import json
import os
import shutil
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "app"))
from viewer_harness import FAILURES, check, run  # noqa: E402


def check_json(args, name, *extra, scale="0.3", timeout=600):
    """`check --structure NAME --json`: (exit code, the structure's report, seconds)."""
    start = time.monotonic()
    code, out, err = run([args.cli, "check", *args.judge, "--structure", name, "--json", "--ray-scale", scale,
                          "--out-dir", os.path.join(args.work, "check"), *extra], timeout=timeout, cwd=args.work)
    seconds = time.monotonic() - start
    try:
        report = json.loads(out)["structures"][0]
    except (ValueError, KeyError, IndexError):
        check(False, f"{name}: no JSON report (exit {code}): {out[-500:]} {err[-500:]}")
        return code, None, seconds
    return code, report, seconds


def wrong_total(report):
    return sum(sum(c["wrong"].values()) for c in report["categories"])


def invariant(report, text):
    return next((i for i in report["invariants"] if text in i["name"]), None)


def replay_in_viewer(args, report, name):
    """Each kept wrong ray's state file, opened in the viewer: print-hit gives the wrong answer."""
    if not args.viewer or not shutil.which("xvfb-run"):
        return
    replays = [w for w in report["wrong_rays"] if "state_file" in w]
    check(replays, f"{name}: no replay state files among {len(report['wrong_rays'])} wrong rays")
    for k, w in enumerate(replays[:2]):
        script = os.path.join(args.work, f"{name}_{k}.script")
        shot = os.path.join(args.work, f"{name}_{k}.png")
        saved = os.path.join(args.work, f"{name}_{k}.state")
        with open(script, "w") as f:
            f.write(f"print-hit\nstep hit\nscreenshot {shot}\nsave-state {saved}\n")
        auth = os.path.join(args.work, f"{name}_{k}.Xauthority")
        open(auth, "w").close()
        # Display numbers from 150: this test runs beside the viewer's tests (which take
        # turns from 99, RESOURCE_LOCK xvfb), and two `xvfb-run -a` picking the same free
        # number at once leave one viewer without its X server (CI: app_playlist_keys found
        # no window).
        code, out, err = run(["xvfb-run", "-a", "-n", "150", "-f", auth, "-s", "-screen 0 1280x1024x24", args.viewer,
                              "--msaa", "0",
                              "--restore", w["state_file"], "--script", script], timeout=300)
        got = w["got"]
        line = next((l for l in out.splitlines() if l.startswith("hit ") or l == "miss"), "")
        parts = line.split()
        if got["prim"] < 0:
            same = line == "miss"
        else:
            same = (len(parts) == 3 and parts[0] == "hit" and int(parts[1]) == got["prim"]
                    and abs(float(parts[2]) - got["t"]) <= 1e-6 * max(1.0, abs(got["t"])))
        check(code == 0 and same, f"{name}: replay {w['state_file']} printed '{line}', the check saw {got} "
              f"(exit {code}: {err[-300:]})")
        check(os.path.exists(shot), f"{name}: the replay's screenshot {shot} was not written")
        # save-state writes what --restore read: the same scene, structure and ray.
        wanted = [l for l in open(w["state_file"]).read().splitlines() if l.split(" ", 1)[0] in ("structure", "ray")]
        got_lines = open(saved).read().splitlines() if os.path.exists(saved) else []
        check(all(l in got_lines for l in wanted), f"{name}: save-state wrote {got_lines}, expected {wanted} in it")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cli", required=True)
    ap.add_argument("--worker", required=True)
    ap.add_argument("--viewer", default="")
    ap.add_argument("--work", required=True)
    ap.add_argument("--sanitized", default="0")
    args = ap.parse_args()
    args.judge = ["--worker", args.worker] + (["--no-sandbox"] if os.environ.get("ACCEL_TEST_NO_SANDBOX") else [])
    sanitized = args.sanitized.lower() in ("1", "on", "true", "yes")
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)

    # The sanitizer build (several times slower) runs a subset at a tenth of the rays: the
    # Release pass runs them all.
    scale = (lambda x: str(float(x) / 10)) if sanitized else str
    solutions = ["median_bvh", "sol_grid", "sol_octree", "sol_kdtree", "sol_bvh", "sol_spheretree"]

    # 1. The worked example and the solutions: every answer right, every invariant kept.
    for name in (["median_bvh", "sol_kdtree"] if sanitized else solutions):
        code, r, s = check_json(args, name, "--no-time", scale=scale("0.3"))
        if r is None:
            continue
        print(f"{name}: exit {code}, {r['rays']} rays, {wrong_total(r)} wrong, {s:.1f} s")
        check(code == 0 and r["passed"], f"{name}: expected to pass: exit {code}, wrong {wrong_total(r)}, "
              f"invariants {[i for i in r['invariants'] if i['failed']]}, faults {r['faults']}, {r.get('failure')}")
        check(r["rays"] > 10000 and {c["name"] for c in r["categories"]} >= {"procedural", "edge", "hard"},
              f"{name}: too few rays or categories: {r['rays']} {[c['name'] for c in r['categories']]}")
        lis = invariant(r, "with and without a log listening")
        check(lis and lis["checked"] == r["rays"] and lis["failed"] == 0,
              f"{name}: recording changed an answer or was not checked on every ray: {lis}")

    # 2. Speed against the built-in, and the refusal to time unoptimised code.
    code, r, _ = check_json(args, "median_bvh", scale=scale("0.1"))
    if r is not None:
        sp = r["speed"]
        if sanitized:
            check(not sp["timed"] and "optimisation" in sp["why_not"], f"sanitized build timed: {sp}")
        else:
            check(sp["timed"] and sp["mrays_per_s"] > 0 and sp["builtin_mrays_per_s"] > 0 and sp["nodes_per_ray"] > 0,
                  f"median_bvh: no speed figures: {sp}")
    code, r, _ = check_json(args, "sol_bvh_unoptimised", scale=scale("0.1"))
    if r is not None:
        check(code == 0 and not r["speed"]["timed"] and "without optimisation" in r["speed"]["why_not"],
              f"sol_bvh_unoptimised: expected a refusal to time: {r['speed']}")

    # 3. Skeletons: wrong answers, reported, no crash, never timed, no trap a skeleton cannot have.
    for kind in ["grid", "octree", "kdtree", "bvh", "spheretree"]:
        code, r, _ = check_json(args, "my_" + kind, scale=scale("0.05"))
        if r is None:
            continue
        check(code == 1 and not r["passed"] and not r.get("failure") and wrong_total(r) > 0,
              f"my_{kind}: expected wrong answers and no crash: exit {code}, {r.get('failure')}, {wrong_total(r)}")
        check(not r["speed"]["timed"] and "not right" in r["speed"]["why_not"],
              f"my_{kind}: a wrong structure must not be timed: {r['speed']}")
        check([c["cause"] for c in r["causes"]] == ["unreferenced"],
              f"my_{kind}: expected only 'unreferenced' (an empty tree): {[c['cause'] for c in r['causes']]}")

    # 4. Planted bugs: every wrong ray has a cause; the expected cause comes first (or is
    # there: a bug hidden behind another shows as its own cause), with replays that show
    # the wrong answer.
    def causes(r):
        return [c["cause"] for c in r["causes"]]

    def top(*ids):
        return lambda r: bool(r["causes"]) and r["causes"][0]["cause"] in ids

    def has(*ids):
        return lambda r: all(i in causes(r) for i in ids)

    bugs = {
        "bug_grid_tie": lambda r: top("grid_dda_tie", "grid_cell_skipped")(r)
        and r["causes"][0]["cases"][0]["case"] == "hard/cube_diagonals",
        "bug_kd_no_case_c": top("kd_wrong_case"),
        "bug_kd_no_tsplit": top("kd_false_early_exit", "kd_hit_beyond_t_split"),
        "bug_kd_slide_near": lambda r: top("kd_plane_behind_origin")(r) and has("kd_parallel_ray")(r),
        "bug_kd_minus_zero": top("kd_parallel_ray"),
        "bug_kd_false_exit": top("kd_false_early_exit"),
        "bug_kd_two_bugs": has("kd_plane_behind_origin", "kd_false_early_exit"),
        "bug_bvh_false_cull": top("false_cull_beyond"),
        "bug_bvh_slab_nan": top("slab_nan"),
        "bug_bvh_first_hit": top("stopped_first_leaf"),
        "bug_octree_boundary": lambda r: top("straddle_lost")(r) or invariant(r, "referenced")["failed"] > 0,
        "bug_sphere_too_small": lambda r: invariant(r, "contains its triangles")["failed"] > 0,
    }
    if sanitized:
        bugs = {k: v for k, v in bugs.items() if k in ("bug_bvh_first_hit", "bug_sphere_too_small", "bug_kd_slide_near")}
    for name, caught in bugs.items():
        code, r, s = check_json(args, name, "--no-time", scale=scale("0.3"))
        if r is None:
            continue
        print(f"{name}: exit {code}, {wrong_total(r)} wrong, causes "
              f"{[(c['cause'], c['rays']) for c in r['causes']]}, {s:.1f} s")
        check(code == 1 and not r["passed"] and not r.get("failure"), f"{name}: expected a clean FAILED report: exit {code}")
        check(caught(r), f"{name}: not caught in its category: {json.dumps(r)[:1500]}")
        # Every wrong ray is counted under one cause, and per case.
        check(sum(c["rays"] for c in r["causes"]) == wrong_total(r),
              f"{name}: the causes count {sum(c['rays'] for c in r['causes'])} rays, the categories {wrong_total(r)}")
        check(sum(c["wrong"] for c in r["cases"]) == wrong_total(r), f"{name}: the per-case counts disagree")
        unexplained = sum(c["rays"] for c in r["causes"] if c["cause"] == "unexplained")
        check(unexplained * 20 <= max(1, wrong_total(r)), f"{name}: {unexplained} of {wrong_total(r)} rays unexplained")
        check(all(c["examples"] for c in r["causes"]), f"{name}: a cause without an example ray")
        misses = [w for w in r["wrong_rays"] if w["got"]["prim"] < 0]
        check(all(w["got"]["t"] is None for w in misses), f"{name}: a miss must be t null in --json: {misses[:1]}")
        if r["wrong_rays"]:
            replay_in_viewer(args, r, name)

    # Waste: case (c) falling through to (a) answers right, so it passes, with the waste
    # named; --strict fails it.
    if not sanitized:
        code, r, _ = check_json(args, "bug_kd_c_as_a", "--no-time", scale="0.1")
        if r is not None:
            said = " ".join(f["sentence"] for f in r["waste"]["findings"])
            check(code == 0 and r["passed"] and "case (c) was never taken" in said,
                  f"bug_kd_c_as_a: expected a pass with the waste named: exit {code}, {r['waste']}")
        code, r, _ = check_json(args, "bug_kd_c_as_a", "--no-time", "--strict", scale="0.1")
        if r is not None:
            check(code == 1 and not r["passed"] and r["waste"]["over_limit"],
                  f"bug_kd_c_as_a --strict: expected to fail: exit {code}, {r['waste']}")
        code, r, _ = check_json(args, "sol_kdtree", "--no-time", "--strict", scale="0.1")
        if r is not None:
            check(code == 0 and r["passed"], f"sol_kdtree --strict: expected to pass: exit {code}, {r['waste']}")
        code, out, err = run([args.cli, "check", *args.judge, "--structure", "sol_kdtree", "--limit", "nosuch=1"],
                             cwd=args.work)
        check(code == 2 and "--limit nosuch=1" in err and len(err.strip().splitlines()) == 1, f"--limit: {code} {err}")

    # A runaway build: a fault naming the node being built, with a replay of the construction.
    if not sanitized:
        code, r, s = check_json(args, "bug_kd_no_progress", "--no-time", "--memory-limit", "1G", scale="0.05",
                                timeout=300)
        if r is not None:
            bf = r.get("build_faults", [])
            print(f"bug_kd_no_progress: exit {code}, {len(bf)} build faults, {s:.1f} s: {bf[:1]}")
            check(code == 1 and bf and "depth" in bf[0]["node"] and "state_file" in bf[0],
                  f"bug_kd_no_progress: expected a build fault with its node and replay: {json.dumps(r)[:1200]}")
            if bf and "state_file" in bf[0]:
                text = open(bf[0]["state_file"]).read()
                check("construct-until " in text and "scene " in text, f"build replay state: {text}")

    # The text names each cause with its rays and prints the replay command.
    code, out, err = run([args.cli, "check", *args.judge, "--structure", "bug_bvh_first_hit", "--no-time", "--ray-scale", "0.2",
                          "--out-dir", os.path.join(args.work, "table")], cwd=args.work)
    check(code == 1 and "stopped at the first leaf" in out and "cause 1: " in out and "wrong answers per case:" in out
          and " --restore " in out and "accelviz-kit --restore" in out and "FAILED" in out, f"table output: {out[-1500:]}")

    # 5. Faults: a report within the limits, naming the case and the ray.
    faults = {
        "fault_crash": (lambda r: "crashed" in r.get("failure", "") and "ray" in r["failure"], []),
        "fault_loop": (lambda r: "no answer within the time limit" in r.get("failure", ""),
                       ["--timeout", "5"]),
        "fault_logged_loop": (lambda r: any("endless loop" in f for f in r["faults"]), ["--timeout", "60"]),
        "fault_throw": (lambda r: any("threw" in f and "planted student bug" in f for f in r["faults"]), []),
        "fault_build_throw": (lambda r: any("build threw" in f for f in r["faults"]), []),
    }
    if not sanitized:  # ASan reserves terabytes: no address-space limit there
        faults["fault_alloc"] = (lambda r: any("ran out of memory" in f for f in r["faults"]) or
                                 "crashed" in r.get("failure", ""), ["--memory-limit", "1G"])
    for name, (reported, extra) in faults.items():
        code, r, s = check_json(args, name, "--no-time", *extra, scale="0.05", timeout=120)
        if r is None:
            continue
        print(f"{name}: exit {code} in {s:.1f} s: {r.get('failure') or r['faults'][:1]}")
        check(code == 1 and not r["passed"] and reported(r), f"{name}: not reported as expected: {json.dumps(r)[:800]}")
        check(s < 60, f"{name}: took {s:.0f} s")

    # 6. Bad use: no worker, a built-in, an unknown name.
    code, out, err = run([args.cli, "check", "--worker", os.path.join(args.work, "no-such-worker")], cwd=args.work)
    no_students = "no student structure" in err
    check(code == 2 and len(err.strip().splitlines()) == 1, f"check without a worker: exit {code}: {err}")
    code, out, err = run([args.cli, "check", *args.judge, "--structure", "bvh"], cwd=args.work)
    check(code == 2 and "built-in" in err and len(err.strip().splitlines()) == 1, f"check --structure bvh: {code} {err}")
    code, out, err = run([args.cli, "check", *args.judge, "--structure", "nosuch"], cwd=args.work)
    check(code == 2 and "unknown structure" in err, f"check --structure nosuch: {code} {err}")
    print(f"plain CLI without students: {'one-line error' if no_students else 'has students'}")
    # No shared meshes: the category is skipped with a one-line notice saying where to put them.
    code, r, _ = check_json(args, "sol_bvh", "--no-time", "--shared", os.path.join(args.work, "no-shared"), scale="0.02")
    if r is not None:
        check(any(n.startswith("meshes: skipped") and "--shared" in n for n in r["notices"])
              and "meshes" not in [c["name"] for c in r["categories"]], f"no meshes notice: {r['notices']}")

    print(f"{len(FAILURES)} failed")
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
