#!/usr/bin/env python3
"""A student's false claims in the viewer (docs/student.md#in-the-viewer), under Xvfb.

accelviz-kit holds the kit's test structures (tests/student). On one ray of the triangle soup
the planted bug bug_kd_false_exit (its early exit compares t_hit with the far child's t_max,
not its t_split) exits early although t_hit is not below t_split, and then skips the far
child as beyond the closest hit. Asserts:
  * print-claims lists that early exit (kd_false_early_exit) and the skip after it;
  * stepped to the early exit, print-step says FALSE with the truth, and at the skip it does
    not repeat the log's sentence ("skip node N ...: entry beyond the closest hit");
  * the correct solution (sol_kdtree) and the built-in kd-tree claim nothing false on it;
  * a 1280x720 screenshot at the early exit is a real picture (png_check), and differs from
    the correct solution's at the same step (the FALSE marking, the warning colour).
Exit 77 (ctest: skipped) without xvfb-run.

    test_kit_false_claims.py --viewer build/bin/accelviz-kit --png-check build/bin/png_check --work DIR
"""
import argparse
import os
import re
import shutil
import sys

from viewer_harness import FAILURES, check, run, viewer

W, H = 1280, 720
# The scene and ray of a replay state that `accelviz-cli check --worker accelviz-worker-kit
# --structure bug_kd_false_exit --ray-scale 0.2` wrote (wrong1.state): the false early exit
# drops the far child that holds the nearer hit.
SCENE = "scene procedural:soup"
RAY = "ray 0x1.3a7b04p-3 0x1.437ae4p-1 0x1.54cc12p-2 0x1.2ae9b2p-2 -0x1.224adcp-3 0x1.e84472p-2 0x0p+0 inf"


def script(args, name, lines):
    path = os.path.join(args.work, name + ".txt")
    with open(path, "w") as f:
        f.write("\n".join([f"size {W} {H}", SCENE] + lines) + "\n")
    code, out, err = viewer(args, path)
    check(code == 0, f"{name}: viewer exit {code}\n{err}")
    return out.strip().splitlines()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--viewer", required=True)
    ap.add_argument("--png-check", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--xvfb", default=shutil.which("xvfb-run") or "")
    args = ap.parse_args()
    if not args.xvfb:
        print("skipped: xvfb-run not found (Debian package xvfb)")
        return 77
    os.makedirs(args.work, exist_ok=True)

    # Where the claims are: print-claims of the whole walk.
    claims = script(args, "claims", ["structure bug_kd_false_exit", RAY, "print-claims"])
    found = [re.fullmatch(r"claim (\d+): (\w+): (.*) -- (.*)", line) for line in claims]
    check(all(found), f"print-claims: lines not of the form 'claim STEP: CAUSE: CLAIM -- TRUTH': {claims}")
    causes = [(int(m.group(1)), m.group(2), m.group(3), m.group(4)) for m in found if m]
    exits = [c for c in causes if c[1] == "kd_false_early_exit"]
    if not check(exits, f"print-claims names no false early exit: {claims}"):
        return 1
    step, _, claim, truth = exits[0]
    check(re.match(r"t_hit=\S+ < t_split=\S+: return \(node \d+ skipped\)$", claim) is not None,
          f"the early exit's claim: '{claim}'")
    check("triangle" in truth, f"the early exit's truth names no nearer triangle it drops: '{truth}'")
    skips = [c for c in causes if c[1] == "false_cull_beyond" and c[0] == step + 1]
    check(skips, f"no false skip right after the early exit (step {step + 1}): {claims}")

    # Stepped there: the step line says FALSE, with the truth; the skip after it does not
    # repeat the log's sentence. The screenshot shows the early exit's step.
    shot = os.path.join(args.work, "false_exit.png")
    lines = script(args, "step", ["structure bug_kd_false_exit", RAY, f"step {step - 1}", "print-step",
                                  f"screenshot {shot}", "step 1", "print-step"])
    if check(len(lines) == 2, f"print-step at steps {step} and {step + 1}: {lines}"):
        check(re.match(rf"step {step}/\d+: pop node \d+ .* -- FALSE: the log says \"{re.escape(claim)}\"; "
                       rf"true: {re.escape(truth)}$", lines[0]) is not None, f"the early exit's step: '{lines[0]}'")
        check(re.match(rf"step {step + 1}/\d+: FALSE: the log says \"node \d+ skipped: entry beyond the closest hit",
                       lines[1]) is not None and "skip node" not in lines[1], f"the false skip's step: '{lines[1]}'")
    c, o, _ = run([args.png_check, shot, str(W), str(H)])
    check(c == 0, f"{shot} is not a {W}x{H} picture: {o}")

    # The same ray on a right kd-tree, the kit's and the built-in: nothing false.
    right = os.path.join(args.work, "right.png")
    lines = script(args, "right", ["structure sol_kdtree", RAY, "print-claims", f"step {step - 1}",
                                   f"screenshot {right}", "structure kdtree", "print-claims"])
    check(lines == ["claims: none", "claims: none (a built-in structure: not audited)"],
          f"the right kd-trees' claims: {lines}")
    c, o, _ = run([args.png_check, "--differ", shot, right, "30"])
    check(c == 0, f"the false walk's picture looks like the right one's: {o}")

    if FAILURES:
        print(f"{len(FAILURES)} failure(s)")
        return 1
    print("the false claims are marked")
    return 0


if __name__ == "__main__":
    sys.exit(main())
