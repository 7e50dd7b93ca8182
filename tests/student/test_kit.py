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
        code, out, err = run(["xvfb-run", "-a", "-f", auth, "-s", "-screen 0 1280x1024x24", args.viewer, "--msaa", "0",
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

    # 3. Skeletons: wrong answers, reported, no crash.
    for kind in ["grid", "octree", "kdtree", "bvh", "spheretree"]:
        code, r, _ = check_json(args, "my_" + kind, "--no-time", scale=scale("0.05"))
        if r is None:
            continue
        check(code == 1 and not r["passed"] and not r.get("failure") and wrong_total(r) > 0,
              f"my_{kind}: expected wrong answers and no crash: exit {code}, {r.get('failure')}, {wrong_total(r)}")

    # 4. Planted bugs, each in its category, with replays that show the wrong answer.
    def any_trap(r, text):
        return any(text in w.get("trap", "") for w in r["wrong_rays"])

    bugs = {
        "bug_grid_tie": lambda r: any(c["name"] == "hard" and sum(c["wrong"].values()) for c in r["categories"]),
        "bug_kd_no_case_c": lambda r: wrong_total(r) > 0,
        "bug_kd_no_tsplit": lambda r: any_trap(r, "beyond t_split"),
        "bug_bvh_first_hit": lambda r: any_trap(r, "first leaf"),
        "bug_octree_boundary": lambda r: any_trap(r, "straddles a split") or invariant(r, "referenced")["failed"] > 0,
        "bug_sphere_too_small": lambda r: invariant(r, "contains its triangles")["failed"] > 0,
    }
    if sanitized:
        bugs = {k: v for k, v in bugs.items() if k in ("bug_bvh_first_hit", "bug_sphere_too_small")}
    for name, caught in bugs.items():
        code, r, s = check_json(args, name, "--no-time", scale=scale("0.3"))
        if r is None:
            continue
        traps = sorted({w["trap"] for w in r["wrong_rays"] if w["trap"]})
        print(f"{name}: exit {code}, {wrong_total(r)} wrong, traps {traps}, {s:.1f} s")
        check(code == 1 and not r["passed"] and not r.get("failure"), f"{name}: expected a clean FAILED report: exit {code}")
        check(caught(r), f"{name}: not caught in its category: {json.dumps(r)[:1500]}")
        if r["wrong_rays"]:
            replay_in_viewer(args, r, name)

    # The table names the trap and prints the replay command.
    code, out, err = run([args.cli, "check", *args.judge, "--structure", "bug_bvh_first_hit", "--no-time", "--ray-scale", "0.2",
                          "--out-dir", os.path.join(args.work, "table")], cwd=args.work)
    check(code == 1 and "the lecture's trap: stopped at the first leaf" in out and " --restore " in out
          and "accelviz-kit --restore" in out and "FAILED" in out, f"table output: {out[-1500:]}")

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

    print(f"{len(FAILURES)} failed")
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
