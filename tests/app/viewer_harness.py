"""What the scripted viewer tests share (test_viewer_scripts.py, test_viewer_2d.py, and the kit's
tests/student/test_kit.py): failures
collected rather than raised, subprocess runs, and the viewer run on a script under Xvfb."""
import argparse
import os
import shutil
import subprocess

FAILURES = []


def check(cond, what):
    if not cond:
        FAILURES.append(what)
        print("FAIL:", what)
    return cond


def run(cmd, timeout=300, env=None, cwd=None):
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, env=env, cwd=cwd)
    return p.returncode, p.stdout, p.stderr


def viewer(args, script_path, timeout=300):
    """Runs args.viewer --script SCRIPT under args.xvfb: (exit code, stdout, stderr)."""
    # xvfb-run keeps its X authority file in a temporary directory it removes at the end, and
    # exits 5 whatever the viewer returned when that clean-up fails (it did, on a busy
    # machine, even in a TMPDIR of our own). With an authority file of our own (-f) it makes
    # no directory and has none to remove.
    tmp = os.path.join(os.path.dirname(script_path), "xvfb-tmp")
    os.makedirs(tmp, exist_ok=True)
    auth = os.path.join(tmp, os.path.basename(script_path) + ".Xauthority")
    open(auth, "w").close()
    xvfb = [args.xvfb, "-a", "-f", auth, "-s", "-screen 0 1280x1024x24"]
    return run(xvfb + [args.viewer, "--script", script_path], timeout=timeout, env=dict(os.environ, TMPDIR=tmp))


def parse_args(*extra):
    """--viewer, --cli, --xvfb, --work and the `extra` required options; the work folder made.
    None (after printing why) when xvfb-run is missing: the caller exits 77 (ctest: skipped)."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--viewer", required=True)
    ap.add_argument("--cli", required=True)
    for name in extra:
        ap.add_argument(name, required=True)
    ap.add_argument("--xvfb", default=shutil.which("xvfb-run") or "")
    ap.add_argument("--work", required=True)
    args = ap.parse_args()
    if not args.xvfb:
        print("skipped: xvfb-run not found (Debian package xvfb)")
        return None
    os.makedirs(args.work, exist_ok=True)
    return args
