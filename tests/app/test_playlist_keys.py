#!/usr/bin/env python3
"""The lecture playlist driven by the keyboard alone, as a presenter's clicker does it: the
viewer runs interactively under Xvfb with scenes/lecture.playlist, xdotool presses Page Down
through every state (the window title names the state and says "(loading)" until it is
shown, "(error)" if a command failed), Page Up and the up arrow go back, F12 writes a
numbered screenshot into $XDG_PICTURES_DIR/accelviz and R ... R records a GIF while space
plays the traversal.
Exit 77 (ctest: skipped) without xvfb-run or xdotool."""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--viewer", required=True)
    ap.add_argument("--playlist", required=True)
    ap.add_argument("--inner", action="store_true", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if not args.inner:
        if not shutil.which("xvfb-run") or not shutil.which("xdotool"):
            print("skipped: xvfb-run or xdotool not found (Debian packages xvfb, xdotool)")
            return 77
        # One X server for the whole run; this script again inside it.
        # An X authority file of our own: xvfb-run then has no temporary directory whose
        # clean-up could fail (see test_viewer_scripts.py).
        tmp = tempfile.mkdtemp(prefix="accel_keys_xvfb_")
        auth = os.path.join(tmp, "Xauthority")
        open(auth, "w").close()
        code = subprocess.run(["xvfb-run", "-a", "-f", auth, "-s", "-screen 0 1280x1024x24", sys.executable, __file__,
                               "--viewer", args.viewer, "--playlist", args.playlist, "--inner"],
                              env=dict(os.environ, TMPDIR=tmp)).returncode
        shutil.rmtree(tmp, ignore_errors=True)
        return code
    failures = []
    work = tempfile.mkdtemp(prefix="accel_keys_")
    # F12 writes into the pictures folder: $XDG_PICTURES_DIR/accelviz, never the working folder.
    pictures = os.path.join(work, "pictures")
    viewer = subprocess.Popen([args.viewer, "--playlist", os.path.abspath(args.playlist), "--msaa", "0",
                               "--size", "1024x640"], cwd=work, stderr=subprocess.PIPE, text=True,
                              env=dict(os.environ, XDG_PICTURES_DIR=pictures))
    started = time.time()
    seen = []  # (seconds, title) each time the title changed: printed when a check fails
    try:
        # The window, within the 60 s settled() gives each state below: 200 polls (about 27 s)
        # were too few in CI, where the kit's compiles share the two cores with the viewer.
        window = ""
        deadline = time.time() + 60.0
        while time.time() < deadline and viewer.poll() is None:
            r = subprocess.run(["xdotool", "search", "--name", "^accelviz"], capture_output=True, text=True)
            if r.stdout.strip():
                window = r.stdout.split()[0]
                break
            time.sleep(0.1)
        if not window:
            exited = viewer.poll()
            print(f"FAIL: no viewer window after {time.time() - started:.0f} s"
                  + (f" (the viewer exited with {exited})" if exited is not None else ""))
            return 1

        def title():
            t = subprocess.run(["xdotool", "getwindowname", window], capture_output=True, text=True).stdout.strip()
            if not seen or seen[-1][1] != t:
                seen.append((time.time() - started, t))
            return t

        def settled(pattern=r" state \d+/", timeout=60.0):
            # The window first has GLFW's title ("accelviz"); the viewer names the state once
            # it is up (and once it has taken the key: frames are slow on a busy machine), and
            # says "(loading)" until the state's commands have run.
            end = time.time() + timeout
            while time.time() < end:
                t = title()
                if re.search(pattern, t) and "(loading)" not in t:
                    return t
                time.sleep(0.1)
            return title()

        def key(name):
            subprocess.run(["xdotool", "key", "--window", window, name])
            time.sleep(0.3)

        t = settled()
        m = re.search(r"state 1/(\d+): ", t)
        if not m:
            print(f"FAIL: title '{t}' names no first state")
            return 1
        n = int(m.group(1))
        for k in range(1, n + 1):
            t = settled(rf"state {k}/{n}: ")
            if not re.search(rf"state {k}/{n}: ", t) or "(error)" in t:
                failures.append(f"after {k - 1} x Page Down: '{t}'")
            if k < n:
                key("Next")
        key("Next")  # past the end: stays on the last state
        time.sleep(1.0)
        if not re.search(rf"state {n}/{n}: ", settled()):
            failures.append(f"Page Down past the end: '{title()}'")
        key("Prior")
        settled(rf"state {n - 1}/{n}: ")
        key("Up")
        t = settled(rf"state {n - 2}/{n}: ")
        if not re.search(rf"state {n - 2}/{n}: ", t) or "(error)" in t:
            failures.append(f"Page Up then up arrow from {n}: '{t}'")
        def appears(path, timeout=15.0):
            end = time.time() + timeout
            while time.time() < end and not os.path.exists(path):
                time.sleep(0.1)
            return os.path.exists(path)

        key("F12")
        if not appears(os.path.join(pictures, "accelviz", "accelviz_0001.png")):
            failures.append(f"F12 wrote no accelviz_0001.png into $XDG_PICTURES_DIR/accelviz ({pictures}/accelviz)")
        if os.path.exists(os.path.join(work, "accelviz_0001.png")):
            failures.append("F12 wrote accelviz_0001.png into the working folder too")
        # Record the traversal of the first state while it plays.
        key("Home")
        for k in range(n - 3, 0, -1):  # up to the first state (its traversal plays)
            key("Up")
            settled(rf"state {k}/{n}: ")
        # The title says "recording" from R until R again. Waiting for it, and not only for
        # the clock, matters when frames are slow: two R presses taken in one frame record
        # nothing (the viewer then says so on stderr).
        key("r")
        if "recording" not in settled(r" - recording"):
            failures.append(f"R started no recording: '{title()}'")
        key("space")
        time.sleep(3.0)
        key("r")
        t = settled(r"^(?!.* - recording)")
        if "recording" in t:
            failures.append(f"the second R did not stop the recording: '{t}'")
        gif = os.path.join(work, "accelviz.gif")
        if not appears(gif) or os.path.getsize(gif) < 100:
            failures.append("R, space, R recorded no accelviz.gif")
        else:
            with open(gif, "rb") as f:
                if f.read(6) != b"GIF89a":
                    failures.append("accelviz.gif is not a GIF89a file")
    finally:
        viewer.terminate()
        try:
            _, err = viewer.communicate(timeout=10)
        except subprocess.TimeoutExpired:
            viewer.kill()
            _, err = viewer.communicate()
    if err.strip():
        failures.append(f"the viewer printed: {err.strip()}")
    for f in failures:
        print("FAIL:", f)
    if failures:
        print("the window's titles, seconds after the viewer started:")
        for at, t in seen:
            print(f"  {at:7.1f}  {t}")
        return 1
    print(f"the playlist ran through its {n} states from the keyboard")
    shutil.rmtree(work, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
