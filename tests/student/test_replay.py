#!/usr/bin/env python3
"""A student's failed build replayed in the viewer up to the fault (`construct-until N`, which
`accelviz-cli check` writes into a failed build's state file), on the kit's viewer
(accelviz-kit) under Xvfb:

  * construct-until 50 on sol_kdtree over procedural:soup records exactly the steps of those
    50 build-log calls: the scene box, one step a call (node, candidates, split, leaf), done;
    each the same as the plain construct's step, and nothing after; it opens on the 50th;
  * the replay leaves no structure to query: print-stats says so, a click shoots a ray without
    a crash, switching structure afterwards builds that one;
  * construct-until with a huge N plays the whole build, step for step the plain construct;
  * a check-like state file reopened with --restore: its `structure` line builds only as far
    (the parser hands it the N), the Construction panel shows the failure line (screenshot);
  * construct-until 0 and construct-until on a built-in structure are refused with one line.

    python3 tests/student/test_replay.py --viewer build/bin/accelviz-kit --cli build/bin/accelviz-cli --work /tmp/r
"""
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "app"))
from viewer_harness import FAILURES, check, parse_args, run, viewer  # noqa: E402

CALLS = 50
STEP = re.compile(r"build step (\d+)/(\d+): (.*)")


def run_script(args, name, lines):
    path = os.path.join(args.work, name + ".script")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return viewer(args, path, timeout=240)


def steps(out):
    """The print-build-step lines: [(K, N, TEXT)]."""
    return [(int(m[1]), int(m[2]), m[3]) for m in (STEP.fullmatch(l) for l in out.splitlines()) if m]


def main():
    args = parse_args()
    if args is None:
        return 77
    w = args.work
    head = ["size 1280 800", "scene procedural:soup", "structure sol_kdtree"]

    # The plain construct: every step's text, to compare the replays with.
    lines = head + ["construct", "build-step end", "print-build-step", "build-step start"]
    lines += ["build-step 1", "print-build-step"] * (CALLS + 2)
    code, out, err = run_script(args, "plain", lines)
    plain = steps(out)
    if not check(code == 0 and len(plain) == CALLS + 3, f"plain construct: exit {code}, {len(plain)} steps\n{err}"):
        return 1
    total = plain[0][1]
    by_step = {k: text for k, _, text in plain[1:]}
    check(plain[0][0] == total and plain[0][2].startswith("done"), f"plain construct ends on {plain[0]}")
    check(total > CALLS + 2, f"sol_kdtree over the soup made only {total} steps: too few for the test")

    # construct-until 50: the scene box, the 50 calls, done (the listener's finish()).
    lines = head + [f"construct-until {CALLS}", "print-build-step", "build-step start"]
    lines += ["build-step 1", "print-build-step"] * (CALLS + 2)
    lines += [f"screenshot {w}/replay_{CALLS}.png", "ray-at-pixel 570 400", "print-hit",
              "structure kdtree", "print-stats"]
    code, out, err = run_script(args, "until", lines)
    got = steps(out)
    check(code == 0, f"construct-until {CALLS}: exit {code}\n{err}")
    if check(len(got) == CALLS + 3, f"construct-until {CALLS}: {len(got)} step lines:\n{out}"):
        # It opens on the last call's step (the node it was building current), before "done".
        first = got[0]
        check(first[:2] == (CALLS + 1, CALLS + 2) and first[2] == by_step.get(CALLS + 1),
              f"construct-until {CALLS} opens on {first}: expected step {CALLS + 1}/{CALLS + 2}, "
              f"'{by_step.get(CALLS + 1)}'")
        for k, n, text in got[1:-1]:
            check(n == CALLS + 2 and text == by_step.get(k), f"replay step {k}/{n} '{text}', plain '{by_step.get(k)}'")
        check(got[-1][2].startswith("done"), f"replay step {got[-1][0]} is {got[-1][2]}, expected done")
    check("miss" in out.splitlines(), f"a click into the replay: expected a miss (nothing to query):\n{out}")
    check(re.search(r"^stats kdtree ", out, re.M), f"switching to kdtree after the replay: no stats\n{out}")
    check(os.path.exists(f"{w}/replay_{CALLS}.png"), "the replay's screenshot was not written")

    # The replay has no structure: print-stats says it is the failed build's replay.
    code, out, err = run_script(args, "stats", head + [f"construct-until {CALLS}", "print-stats"])
    check(code == 2 and "the failed build's replay: no structure to query" in err
          and f"stopped after {CALLS} build-log calls" in err, f"print-stats on the replay: exit {code}: {err}")

    # A limit beyond the build: the whole build, the plain construct's steps and structure.
    code, out, err = run_script(args, "huge", head + ["construct-until 1000000000", "print-build-step", "print-stats"])
    got = steps(out)
    check(code == 0 and got and got[0] == plain[0], f"construct-until 1e9: exit {code}, {got[:1]}, plain {plain[0]}\n"
          f"{err}")
    check(re.search(r"^stats sol_kdtree ", out, re.M), f"construct-until 1e9: the whole build is queryable\n{out}")

    # A failed build's state as check writes it, reopened: the structure line builds only as
    # far; the panel shows the check's first comment line in red (looked at by hand).
    state = os.path.join(w, "build_fault1.state")
    with open(state, "w") as f:
        f.write(f"# accelviz-cli check: sol_kdtree, procedural/soup: build threw: std::bad_alloc\n"
                f"# at node 9 (depth 3, 800 triangles); {CALLS} calls in all\n"
                f"scene procedural:soup\nstructure sol_kdtree\nconstruct-until {CALLS}\n")
    script = os.path.join(w, "restored.script")
    with open(script, "w") as f:
        f.write(f"print-build-step\nscreenshot {w}/restored.png\nsave-state {w}/resaved.state\n")
    auth = os.path.join(w, "restore.Xauthority")
    open(auth, "w").close()
    code, out, err = run([args.xvfb, "-a", "-f", auth, "-s", "-screen 0 1280x1024x24", args.viewer, "--msaa", "0",
                          "--restore", state, "--script", script], timeout=240)
    check(code == 0 and f"build step {CALLS + 1}/{CALLS + 2}: " in out, f"--restore: exit {code}\n{out}\n{err}")
    resaved = open(f"{w}/resaved.state").read() if os.path.exists(f"{w}/resaved.state") else ""
    check(f"construct-until {CALLS}" in resaved and "structure sol_kdtree" in resaved,
          f"save-state of the replay wrote:\n{resaved}")

    # One-line refusals.
    code, out, err = run_script(args, "zero", head + ["construct-until 0"])
    check(code == 2 and "construct-until: N must be" in err, f"construct-until 0: exit {code}: {err}")
    code, out, err = run_script(args, "builtin", ["scene procedural:soup", "structure kdtree", "construct-until 5"])
    check(code == 2 and "kdtree is not a student's structure" in err, f"construct-until on kdtree: exit {code}: {err}")

    print(f"{len(FAILURES)} failures" if FAILURES else "ok")
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
